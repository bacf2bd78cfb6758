#![doc = include_str!(concat!(env!("OUT_DIR"), "/checker.md"))]

mod carried;
mod class;
mod error;
mod formula;
mod grading;
mod key;
mod paths;
mod policy;
mod q1;
mod q2;
mod q3;
mod q4;
mod q5;
mod reading;
mod reports;
mod suggest;
mod template;
#[cfg(test)]
mod tests;
mod traces;
mod variants;

pub use class::{
    ClassError, ClassReport, GradescopeError, MAX_CLASS_BYTES, MAX_CLASS_FILES, PartStatistics, Submission,
    check_class, class_csv, class_files, class_gradescope, class_text, gradescope_files, read_class,
};
pub use error::CheckError;
pub use formula::{Formula, FormulaError, Kind, Point, Value};
pub use grading::{PartResult, Report, check};
pub use key::{
    Derivation, Expected, ExpectedLeaf, ExpectedPlane, Follows, MalRule, Part, Q1Setting, Q4Image, Q4Setting, Setting,
    Variant,
};
pub use policy::{Rule, policy_table};
pub use reports::{NOTES_ROOT, report_gradescope, report_text};
pub use template::{answer_key, answer_key_for, template};
pub use variants::{QUESTIONS, variant};

/// Q1's key numbers, for the worked solution (which computes each step from them).
pub(crate) use q1::{SCENES as Q1_SCENES, difficulty_of, key as q1_key};
