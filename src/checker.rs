#![doc = include_str!(concat!(env!("OUT_DIR"), "/checker.md"))]

mod carried;
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
mod traces;
mod variants;

pub use error::CheckError;
pub use formula::{Formula, FormulaError, Kind, Point, Value};
pub use grading::{PartResult, Report, check};
pub use key::{Derivation, Expected, ExpectedLeaf, ExpectedPlane, Follows, MalRule, Part, Variant};
pub use policy::{Rule, policy_table};
pub use reports::{report_gradescope, report_text};
pub use template::{answers_key, answers_key_for, template};
pub use variants::{QUESTIONS, variant};
