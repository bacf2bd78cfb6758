//! The partial-credit policy: every recognised mistake is one [`Rule`], with one credit and one
//! reason, applied the same way in every question where it occurs.

use crate::plot::markdown_table;

/// A recognised kind of mistake, with the share of a part's points it still earns.
///
/// Every [`MalRule`](super::MalRule) names one, so a part never sets its own credit: the same
/// slip earns the same share in Q1 as in Q4. The policy's table in the checker chapter is
/// [`policy_table`], checked against this enum by a test.
///
/// # Examples
/// ```
/// use hw3::checker::Rule;
/// assert_eq!(Rule::Unit.id(), "unit");
/// assert_eq!(Rule::Unit.credit(), 0.5);
/// assert_eq!(Rule::Sign.credit(), 0.0);
/// assert!(Rule::ALL.iter().all(|r| (0.0..=1.0).contains(&r.credit())));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Rule {
    /// A sign that changes the geometry.
    Sign,
    /// A constant factor lost in an otherwise right formula.
    Factor,
    /// A length for a squared length.
    Power,
    /// A term left out or swapped.
    WrongTerm,
    /// Another root of the quadratic.
    WrongRoot,
    /// The distance along the ray for its parameter.
    DistanceForParameter,
    /// The right direction, not of unit length.
    NotNormalised,
    /// Radians for degrees.
    Unit,
    /// The full cone angle for the half-angle.
    FullForHalfAngle,
    /// The right quantity in another convention: a vector in the camera's frame, a ratio turned over.
    Convention,
    /// A different quantity with its own name.
    OtherQuantity,
    /// The wrong case of the analysis.
    WrongCase,
    /// A verdict on whether a method captures an effect that the light paths contradict.
    WrongVerdict,
    /// A step that follows correctly from the student's own earlier wrong answer.
    CarriedForward,
}

impl Rule {
    /// Every rule, in the order of the policy table.
    pub const ALL: [Self; 14] = [
        Self::Sign,
        Self::Factor,
        Self::Power,
        Self::WrongTerm,
        Self::WrongRoot,
        Self::DistanceForParameter,
        Self::NotNormalised,
        Self::Unit,
        Self::FullForHalfAngle,
        Self::Convention,
        Self::OtherQuantity,
        Self::WrongCase,
        Self::WrongVerdict,
        Self::CarriedForward,
    ];

    /// The stable id reports use (`PartResult::mistake`): lower case, underscores.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(hw3::checker::Rule::CarriedForward.id(), "carried_forward");
    /// ```
    #[must_use]
    pub const fn id(self) -> &'static str {
        match self {
            Self::Sign => "sign",
            Self::Factor => "factor",
            Self::Power => "power",
            Self::WrongTerm => "wrong_term",
            Self::WrongRoot => "wrong_root",
            Self::DistanceForParameter => "distance_for_parameter",
            Self::NotNormalised => "not_normalised",
            Self::Unit => "unit",
            Self::FullForHalfAngle => "full_for_half_angle",
            Self::Convention => "convention",
            Self::OtherQuantity => "other_quantity",
            Self::WrongCase => "wrong_case",
            Self::WrongVerdict => "wrong_verdict",
            Self::CarriedForward => "carried_forward",
        }
    }

    /// The share of the part's points the mistake still earns, 0 to 1.
    ///
    /// Half credit is for a right method with one mechanical slip in expressing it (a unit, a
    /// constant, a normalisation, a convention); none for a different method, quantity or
    /// geometry; full credit for a step that follows from the student's own earlier mistake
    /// (charged once, where it was made).
    ///
    /// # Examples
    /// ```
    /// use hw3::checker::Rule;
    /// assert_eq!(Rule::DistanceForParameter.credit(), 0.5);
    /// assert_eq!(Rule::CarriedForward.credit(), 1.0);
    /// ```
    #[must_use]
    pub const fn credit(self) -> f64 {
        match self {
            Self::Sign
            | Self::Power
            | Self::WrongTerm
            | Self::WrongRoot
            | Self::OtherQuantity
            | Self::WrongCase
            | Self::WrongVerdict => 0.0,
            Self::Factor
            | Self::DistanceForParameter
            | Self::NotNormalised
            | Self::Unit
            | Self::FullForHalfAngle
            | Self::Convention => 0.5,
            Self::CarriedForward => 1.0,
        }
    }

    /// Why the rule earns its credit, in one sentence.
    ///
    /// # Examples
    /// ```
    /// assert!(hw3::checker::Rule::Unit.why().contains("radians"));
    /// ```
    #[must_use]
    pub const fn why(self) -> &'static str {
        match self {
            Self::Sign => {
                "A flipped sign changes the geometry (an inward normal, a ray that passes through the surface instead of reflecting, the root of another quadratic): the method is wrong, not the arithmetic."
            }
            Self::Factor => {
                "A constant factor lost in an otherwise right formula (the 2 of B or of 2A, the 4 of 4AC, the π of E/π): the method is right, one constant is not."
            }
            Self::Power => {
                "A length where a squared length is asked (|d| for |d|², r for r²): the answer has the wrong dimension."
            }
            Self::WrongTerm => {
                "A term left out, swapped or misplaced (e for e − o, 3 for 3 − e_x, the x-axis for the y-axis, the whole image over the tangent of the whole angle): the formula describes another geometry."
            }
            Self::WrongRoot => {
                "Another root of the quadratic (the larger, the negative one, t = 0 at the eye): another intersection, so the hit is wrong."
            }
            Self::DistanceForParameter => {
                "The distance along the ray where its parameter t is asked (they differ by the factor |d|): the geometry is right, the unit of t is not."
            }
            Self::NotNormalised => {
                "The right direction, not of unit length: the construction is right, its last normalisation is missing."
            }
            Self::Unit => "An angle in radians where degrees are asked: the value is right, its unit is not.",
            Self::FullForHalfAngle => {
                "The full cone angle where the half-angle is asked: the construction is right, the convention is not (a lost factor 2)."
            }
            Self::Convention => {
                "The right quantity in another convention than the one asked (a direction in the camera's frame for the world's, a ratio turned over): the construction is right, its last step of expression is not."
            }
            Self::OtherQuantity => {
                "A different quantity with a name of its own (a first-order term, the mean free path, the normal's turn, a projection for a reflection, an integral without its cosine, a share of the sphere): the method answers another question."
            }
            Self::WrongCase => {
                "The wrong case of the analysis, or a hit for a miss: every later part rests on it, and the feedback says which sign decides."
            }
            Self::WrongVerdict => {
                "A yes, no or impractical that the light paths contradict (yes where the method misses some of the effect's paths, no where it produces them all on purpose, impractical where some cannot be produced at all): the cell is that comparison and nothing else, so nothing of it is right."
            }
            Self::CarriedForward => {
                "A step that follows correctly from the student's own earlier wrong answer: the error is charged once, at the step where it was made."
            }
        }
    }
}

/// The policy as a Markdown table (rule id, credit, why), as the checker chapter prints it.
///
/// # Examples
/// ```
/// let table = hw3::checker::policy_table();
/// assert!(table.starts_with("| rule | credit | why |"));
/// assert!(table.contains("| `unit` | 0.5 |"));
/// ```
#[must_use]
pub fn policy_table() -> String {
    let rows = Rule::ALL.into_iter().map(|rule| {
        // A `|` inside a cell would end it.
        [format!("`{}`", rule.id()), rule.credit().to_string(), rule.why().replace('|', "\\|")]
    });
    markdown_table(&["rule", "credit", "why"], rows)
}
