//! The key: what each part of a question expects, how it is compared, and the wrong answers it
//! recognises.

/// The answer a part expects, with how it is compared.
///
/// # Examples
/// ```
/// use hw3::checker::Expected;
/// let q2 = hw3::checker::variant("q2", 0).unwrap();
/// // Seed 0's first hit is t = 5 − √3, compared as a number within 10⁻³ relative.
/// let Expected::Number { value, rtol, .. } = q2.parts[0].expected else { panic!() };
/// assert!((value - (5.0 - 3f64.sqrt())).abs() < 1e-12 && rtol == 1e-3);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum Expected {
    /// A number, accepted within `rtol·|value| + atol`.
    Number {
        /// The key's value.
        value: f64,
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance.
        atol: f64,
    },
    /// A point or vector, accepted when `|given − value| ≤ rtol·|value| + atol`.
    Vector {
        /// The key's value.
        value: [f64; 3],
        /// Relative tolerance on the norm of the difference.
        rtol: f64,
        /// Absolute tolerance on the norm of the difference.
        atol: f64,
    },
    /// A unit direction, accepted within `angle_tol` radians *and* within 10⁻³ of unit length.
    Direction {
        /// The key's unit vector.
        value: [f64; 3],
        /// Angular tolerance in radians.
        angle_tol: f64,
    },
    /// A kd-tree traversal: the leaves reached, in order, graded leaf by leaf up to the first
    /// divergence (numbers within 10⁻⁶, `inf` exactly).
    Trace {
        /// The key's leaves.
        leaves: Vec<ExpectedLeaf>,
        /// The plane crossings of the key's trace (`"y = 3"`, t), used to explain a wrong bound.
        planes: Vec<(String, f64)>,
    },
    /// One word out of a few (`"yes"`, `"no"`, `"impractical"`), compared case-insensitively.
    /// The file may give it as `a = "no"` or `a = { answer = "no", why = "..." }`; the `why` is
    /// echoed in the feedback, never graded.
    Choice {
        /// The key's word.
        value: &'static str,
    },
    /// Any vector pointing within `angle_tol` radians of `value`, whatever its length (for
    /// recognising wrong answers whose length is also off).
    Parallel {
        /// A unit vector along the direction.
        value: [f64; 3],
        /// Angular tolerance in radians.
        angle_tol: f64,
    },
}

/// One leaf of a traversal: its path from the root (`["x>=3", "y<3"]`) and its t-interval.
///
/// # Examples
/// ```
/// use hw3::checker::Expected;
/// let q3 = hw3::checker::variant("q3", 0).unwrap();
/// let Expected::Trace { leaves, .. } = &q3.parts[0].expected else { panic!() };
/// assert_eq!(leaves[0].path, ["x>=3", "y<3"]);
/// assert_eq!((leaves[0].t_min, leaves[0].t_max), (0.0, 2.0));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExpectedLeaf {
    /// Branch conditions from the root.
    pub path: Vec<String>,
    /// Where the ray enters the leaf.
    pub t_min: f64,
    /// Where it leaves (`+∞` for an unbounded cell).
    pub t_max: f64,
}

/// A wrong answer we expect students to give, with its own message and partial credit.
///
/// # Examples
/// ```
/// let q2 = hw3::checker::variant("q2", 0).unwrap();
/// let rule = &q2.parts[0].mal_rules[0];
/// assert!(rule.message.contains("larger root") && rule.credit == 0.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct MalRule {
    /// The wrong value it recognises (compared with the part's own tolerance).
    pub value: Expected,
    /// What went wrong, in one line.
    pub message: &'static str,
    /// Fraction of the part's points it still earns (0 to 1).
    pub credit: f64,
}

/// One gradable part of a question: `key` is the TOML path (`q2a.t`).
///
/// # Examples
/// ```
/// let q2 = hw3::checker::variant("q2", 0).unwrap();
/// let part = &q2.parts[0];
/// assert_eq!((part.key, part.points), ("q2a.t", 2.0));
/// assert!(part.explained_in.starts_with("hw3/q2_ray_sphere"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// TOML path of the answer: table and key (`"q2a.t"`).
    pub key: &'static str,
    /// What the student is asked, in one line.
    pub prompt: &'static str,
    /// Points for a correct answer.
    pub points: f64,
    /// The key's answer and comparison.
    pub expected: Expected,
    /// Recognised wrong answers.
    pub mal_rules: Vec<MalRule>,
    /// Where the notes explain it (a path inside the rustdoc, e.g. `hw3/q2_ray_sphere/index.html`).
    pub explained_in: &'static str,
}

/// A question variant: its parameters in words and its parts.
///
/// # Examples
/// ```
/// let q3 = hw3::checker::variant("q3", 0).unwrap();
/// assert_eq!((q3.question, q3.seed), ("q3", 0));
/// assert!(q3.statement.contains("(d) e = (5, 0), d = (-1, 1)"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Variant {
    /// Question id (`"q2"`).
    pub question: &'static str,
    /// The seed it came from (0 = the homework's own numbers, or the notes' worked example).
    pub seed: u64,
    /// The question with its numbers, as markdown.
    pub statement: String,
    /// Its parts, in order.
    pub parts: Vec<Part>,
}
