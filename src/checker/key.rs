//! The key: what each part of a question expects, how it is compared, and the wrong answers it
//! recognises.

use super::formula::{Formula, Kind, Point};
use super::policy::Rule;
use crate::geometry::{Ray, Sphere};
use crate::q3_kd_traversal::Ray2;

/// The answer a part expects, with how it is compared.
///
/// # Examples
/// ```
/// use hw3::checker::Expected;
/// let q2 = hw3::checker::variant("q2", 0).unwrap();
/// // Seed 0's first hit is t = 5 − √3 (a value, not "none"), compared within 10⁻³ relative.
/// let t = q2.parts.iter().find(|p| p.key == "q2a.t").unwrap();
/// let Expected::OrNone { value, none: false } = &t.expected else { panic!() };
/// let Expected::Number { value, rtol, .. } = **value else { panic!() };
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
        /// The key's leaves (or, when `descents`, every child descended, with its interval).
        leaves: Vec<ExpectedLeaf>,
        /// The entries are every descent into a child, not only the leaves.
        descents: bool,
        /// The plane crossings of the key's trace (`"y = 3"`, t), used to explain a wrong bound.
        planes: Vec<(String, f64)>,
    },
    /// One word out of a few (`"yes"`, `"no"`, `"impractical"`; Q2's cases), compared
    /// case-insensitively. The file may give it as `a = "no"` or
    /// `a = { answer = "no", why = "..." }`; the `why` is echoed in the feedback, never graded.
    Choice {
        /// The key's word.
        value: &'static str,
        /// Every word the part accepts as an answer (the template lists them).
        options: &'static [&'static str],
    },
    /// `true` or `false` (does the ray hit?).
    Flag {
        /// The key's value.
        value: bool,
    },
    /// A formula in the part's symbols, graded by evaluating it and the key at the same random
    /// points (agreement to 10⁻⁶ relative at every point).
    Formula {
        /// The key's formula as text (shown after an answer).
        source: &'static str,
        /// The key, parsed.
        key: Formula,
        /// The symbols a formula may use, each a number or a vector.
        symbols: &'static [(&'static str, Kind)],
        /// The points both are evaluated at (drawn so that every symbol is consistent: `A = d·d`
        /// and so on).
        points: Vec<Point>,
    },
    /// A value that may not exist (Q2's t, point, normal and reflection when the ray does not
    /// hit): the file gives the value, or `"none"`. Every variant lists the same parts, so which
    /// parts the template shows never gives away whether the ray hits.
    OrNone {
        /// The key when there is a value; when `none`, a stand-in of the same kind, for the
        /// template's format line only.
        value: Box<Expected>,
        /// The key is "none".
        none: bool,
    },
    /// A class of light paths in Heckbert's notation (`LD+E`), graded by language equivalence:
    /// `LDD*E` and `LD+E` are the same answer. `none` is the empty class.
    Paths {
        /// The key's expression.
        value: String,
    },
    /// The planes met in a kd-tree traversal, in order: at each node, the plane parameter (or
    /// parallel) and the child descended first. Graded node by node (`checker::traces`).
    Planes {
        /// The key's steps.
        steps: Vec<ExpectedPlane>,
        /// Why each step's first child comes first, by the question's rule, one per step (the
        /// feedback on a wrong `first`).
        why_first: Vec<String>,
        /// The ray's origin `e` and direction `d`, to follow a wrong plane parameter to the
        /// nodes and first children it changes below it.
        ray: ([f64; 2], [f64; 2]),
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

impl Expected {
    /// A number accepted within `rtol·|value|`: purely relative, so a tiny key (Q1's gap fraction
    /// at a dense forest, about 10⁻¹⁰) is not matched by 0. A key of exactly zero, which no
    /// relative tolerance can meet, is accepted within 10⁻⁹. Parts that need another absolute
    /// floor write [`Expected::Number`] out.
    ///
    /// # Examples
    /// ```
    /// use hw3::checker::Expected;
    /// assert_eq!(Expected::number(2.0, 1e-3), Expected::Number { value: 2.0, rtol: 1e-3, atol: 0.0 });
    /// assert_eq!(Expected::number(0.0, 1e-3), Expected::Number { value: 0.0, rtol: 1e-3, atol: 1e-9 });
    /// ```
    #[must_use]
    pub const fn number(value: f64, rtol: f64) -> Self {
        Self::Number { value, rtol, atol: if value == 0.0 { 1e-9 } else { 0.0 } }
    }
}

/// One leaf of a traversal: its path from the root (`["x>=3", "y<3"]`) and its t-interval.
///
/// # Examples
/// ```
/// use hw3::checker::Expected;
/// let q3 = hw3::checker::variant("q3", 0).unwrap();
/// let part = q3.parts.iter().find(|p| p.key == "q3d.leaves").unwrap();
/// let Expected::Trace { leaves, .. } = &part.expected else { panic!() };
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

/// A wrong answer we expect students to give, with its own message; its credit is its
/// [`Rule`]'s, the same in every question.
///
/// # Examples
/// ```
/// use hw3::checker::Rule;
/// let q2 = hw3::checker::variant("q2", 0).unwrap();
/// let t = q2.parts.iter().find(|p| p.key == "q2a.t").unwrap();
/// let mal_rule = &t.mal_rules[0];
/// assert!(mal_rule.message.contains("larger root"));
/// assert_eq!((mal_rule.rule, mal_rule.credit()), (Rule::WrongRoot, 0.0));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct MalRule {
    /// The wrong value it recognises (compared with the part's own tolerance).
    pub value: Expected,
    /// What went wrong, in one line.
    pub message: &'static str,
    /// The policy's rule it is an instance of (its credit and reason).
    pub rule: Rule,
}

impl MalRule {
    /// Fraction of the part's points it still earns (0 to 1): its rule's credit.
    ///
    /// # Examples
    /// ```
    /// use hw3::checker::{Expected, MalRule, Rule};
    /// let radians = MalRule { value: Expected::Flag { value: true }, message: "radians", rule: Rule::Unit };
    /// assert_eq!(radians.credit(), 0.5);
    /// ```
    #[must_use]
    pub const fn credit(&self) -> f64 {
        self.rule.credit()
    }
}

/// One gradable part of a question: `key` is the TOML path (`q2a.t`).
///
/// # Examples
/// ```
/// let q2 = hw3::checker::variant("q2", 0).unwrap();
/// let part = q2.parts.iter().find(|p| p.key == "q2a.t").unwrap();
/// assert_eq!(part.points, 2.0);
/// assert_eq!(part.explained_in, "hw3/q2_ray_sphere/index.html#part-q2a-the-case-the-first-hit-and-its-point");
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
    /// Where the notes explain it: a path inside the rustdoc and the section's anchor
    /// (`hw3/q2_ray_sphere/index.html#a-derivation`).
    pub explained_in: &'static str,
    /// How the key is computed, in one sentence (the feedback on a wrong answer ends with it).
    pub method: &'static str,
}

/// The numbers a variant is drawn as. Its statement, its key, its template and its worked
/// solution are all made from them; nothing is read back from the statement's words.
#[derive(Debug, Clone, PartialEq)]
pub enum Setting {
    /// Q1: the numbers of each difficulty.
    Q1(Q1Setting),
    /// Q2: the ray and the sphere.
    Q2 {
        /// The ray `e + d t`.
        ray: Ray<f64>,
        /// The sphere.
        sphere: Sphere<f64>,
    },
    /// Q3: the rays of parts (d) and (e), in the homework's tree.
    Q3 {
        /// The ray of part (d).
        d: Ray2,
        /// The ray of part (e).
        e: Ray2,
    },
    /// Q4: the sky, the tilt, the ball's distance and the probe image of part (c).
    Q4(Q4Setting),
    /// Q5: no numbers (one variant).
    Q5,
}

/// Q1's numbers: a slab of spheres, a fog, a mirror ball and a camera step, a moving object.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Q1Setting {
    /// Spheres in the slab, `N`.
    pub count: f64,
    /// The side `W` of the slab's front face.
    pub side: f64,
    /// The spheres' radius `a`.
    pub radius: f64,
    /// The fog's extinction coefficient `σ_t`.
    pub sigma_t: f64,
    /// The path length `l` through the fog.
    pub path: f64,
    /// The mirror sphere's radius `R`.
    pub mirror_radius: f64,
    /// The camera's sideways step.
    pub step: f64,
    /// The object's speed, units per second.
    pub speed: f64,
    /// Frames per second.
    pub fps: f64,
    /// The object's distance (depth) from the camera.
    pub depth: f64,
    /// The vertical field of view, degrees.
    pub fov_deg: f64,
    /// The image height, pixels.
    pub height: f64,
}

/// Q4's numbers: the sky `L(ω) = a + b ω_z`, the normal's tilt from up towards `+x`, the ball's
/// distance in radii, and part (c)'s probe image.
#[derive(Debug, Clone, PartialEq)]
pub struct Q4Setting {
    /// The sky's constant term `a`.
    pub a: f64,
    /// The sky's gradient `b` along `ω_z`.
    pub b: f64,
    /// The normal's tilt from up towards `+x`, degrees.
    pub tilt_deg: f64,
    /// The ball's distance `D/R`.
    pub distance_over_radius: f64,
    /// Part (c)'s image.
    pub image: Q4Image,
}

/// Part (c) of Q4: a small orthographic mirror-ball image, texel by texel.
#[derive(Debug, Clone, PartialEq)]
pub struct Q4Image {
    /// Texels across and down.
    pub size: usize,
    /// Each texel's radiance, row by row from the top; `None` where the texel's centre is
    /// outside the disc (masked).
    pub radiance: Vec<Option<f64>>,
    /// The three listed texels, `(row, column)`.
    pub listed: [(usize, usize); 3],
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
    /// The seed it came from (0 = the homework's own numbers where it has them, fixed numbers elsewhere).
    pub seed: u64,
    /// The numbers it is drawn as.
    pub setting: Setting,
    /// The question with its numbers, as markdown.
    pub statement: String,
    /// Its parts, in order.
    pub parts: Vec<Part>,
    /// The parts whose key follows from the answer to an earlier part (error carried forward).
    pub follows: Vec<Follows>,
}

/// A part whose key can be recomputed from the student's own answer to an earlier part: when
/// the later answer follows correctly from a wrong earlier one, it earns
/// [`Rule::CarriedForward`]'s credit.
///
/// # Examples
/// ```
/// let q2 = hw3::checker::variant("q2", 0).unwrap();
/// let point = q2.follows.iter().find(|f| f.key == "q2a.point").unwrap();
/// assert_eq!(point.from, "q2a.t");
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Follows {
    /// The later part.
    pub key: &'static str,
    /// The earlier part it is computed from.
    pub from: &'static str,
    /// How.
    pub derivation: Derivation,
}

/// How a later part's key follows from an earlier answer.
///
/// # Examples
/// ```
/// use hw3::checker::Derivation;
/// let q4 = hw3::checker::variant("q4", 0).unwrap();
/// assert!(q4.follows.iter().any(|f| f.derivation == Derivation::LostFromHalfAngle));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum Derivation {
    /// Q2: the point `e + d t` from the student's t.
    PointFromT {
        /// The ray's origin `e`.
        origin: [f64; 3],
        /// The ray's direction `d`.
        dir: [f64; 3],
    },
    /// Q2: the unit normal `(p − o)/|p − o|` from the student's point.
    NormalFromPoint {
        /// The sphere's centre `o`.
        center: [f64; 3],
    },
    /// Q2: the reflection `d̂ − 2 (n̂ · d̂) n̂` from the student's normal (normalised).
    ReflectionFromNormal {
        /// The ray's direction `d`.
        dir: [f64; 3],
    },
    /// Q3: the descents as the traversal makes them with the student's own plane parameters, when
    /// the student's planes are that traversal's (a wrong `t` is a slip of arithmetic, charged
    /// once, in the planes; whatever it changes below follows); a wrong node, first child or
    /// parallel is a mistake of method, and the descents are graded against the key.
    DescentsFromPlanes {
        /// The ray's origin `e`.
        origin: [f64; 2],
        /// The ray's direction `d`.
        dir: [f64; 2],
    },
    /// Q3: the leaves as the traversal makes them with the student's own plane parameters, when
    /// the student's planes are that traversal's (as for [`Derivation::DescentsFromPlanes`]): the
    /// way to the leaves when the descents are missing or repeat a mistake the planes do not.
    LeavesFromPlanes {
        /// The ray's origin `e`.
        origin: [f64; 2],
        /// The ray's direction `d`.
        dir: [f64; 2],
    },
    /// Q3: the leaves are the student's descents into cells that are not split further, when
    /// those descents follow the traversal's method (the key's cells with each bound right,
    /// carried from a wrong plane parameter, or that slip itself; or the traversal's descents
    /// for some plane parameters): a wrong cell or first child, or a bound kept at 0 or left
    /// unclipped, is a mistake of method, charged again in the leaves.
    LeavesFromDescents {
        /// The key's descents, to tell a slip from a mistake of method.
        descents: Vec<ExpectedLeaf>,
        /// The ray's origin `e`.
        origin: [f64; 2],
        /// The ray's direction `d`.
        dir: [f64; 2],
    },
    /// Q4: the irradiance lost for a normal into the blind cone, `sin² γ`, from the student's
    /// half-angle `γ` in degrees.
    LostFromHalfAngle,
    /// Q5: the paths a method misses, from the student's verdict on the cell: `none` for a yes,
    /// the effect's whole class for a no or an impractical (a method misses all of each of Q5's
    /// effects or none of it, so that is what the student's own verdict implies).
    MissedFromVerdict {
        /// The effect's class of light paths (Heckbert's notation).
        effect: &'static str,
    },
}

/// One plane of a traversal: the node, where the ray crosses its plane, and which child comes first.
///
/// # Examples
/// ```
/// use hw3::checker::Expected;
/// let q3 = hw3::checker::variant("q3", 0).unwrap();
/// let planes = q3.parts.iter().find(|p| p.key == "q3d.planes").unwrap();
/// let Expected::Planes { steps, .. } = &planes.expected else { panic!() };
/// assert_eq!((steps[0].node.len(), steps[0].t, steps[0].first.as_str()), (0, Some(2.0), "x>=3"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExpectedPlane {
    /// The node's path from the root (empty for the root).
    pub node: Vec<String>,
    /// The plane parameter, `None` for a ray parallel to the plane.
    pub t: Option<f64>,
    /// The child descended first (`"x>=3"`).
    pub first: String,
}

/// A formula part: the key `source` in `symbols`, compared at `points`; each slip is a formula
/// with its message and the policy's rule.
///
/// # Panics
/// If the key or a slip does not parse (a bug in the question, caught by every test).
#[allow(clippy::too_many_arguments)]
pub(super) fn formula_part(
    key: &'static str,
    prompt: &'static str,
    points_worth: f64,
    source: &'static str,
    symbols: &'static [(&'static str, Kind)],
    points: &[Point],
    slips: &[(&'static str, &'static str, Rule)],
    explained_in: &'static str,
    method: &'static str,
) -> Part {
    let formula = |text: &str| Formula::parse(text, symbols).unwrap_or_else(|e| panic!("{key}: `{text}`: {e}"));
    let expected =
        |source: &'static str| Expected::Formula { source, key: formula(source), symbols, points: points.to_vec() };
    Part {
        key,
        prompt,
        points: points_worth,
        expected: expected(source),
        mal_rules: slips
            .iter()
            .map(|&(slip, message, rule)| MalRule { value: expected(slip), message, rule })
            .collect(),
        explained_in,
        method,
    }
}
