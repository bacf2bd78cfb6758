//! Reading an answers file: the TOML values of each part, shaped like the part's key.

use super::error::CheckError;
use super::formula::Formula;
use super::key::{Expected, ExpectedLeaf, ExpectedPlane};
use super::paths::paths;

pub(super) fn read_seed(table: &toml::Table) -> Result<u64, CheckError> {
    match table.get("meta").and_then(|m| m.get("seed")) {
        None => Ok(0),
        Some(toml::Value::Integer(i)) if *i >= 0 => Ok(*i as u64),
        Some(other) => Err(CheckError::BadSeed(other.to_string())),
    }
}

/// The sections an answers file may have: `[meta]` and one per question. Each must be a table:
/// `meta = 3` or `q2 = [1, 2]` is a wrong shape, refused rather than graded as if it were absent.
const SECTIONS: [&str; 6] = ["meta", "q1", "q2", "q3", "q4", "q5"];

/// Refuses a known section that is not a table (before any grading).
pub(super) fn require_tables(table: &toml::Table) -> Result<(), CheckError> {
    for section in SECTIONS {
        if let Some(value) = table.get(section)
            && !value.is_table()
        {
            return Err(CheckError::BadValue {
                key: section.into(),
                problem: format!("must be a table (`[{section}]`), got {}", value.type_str()),
            });
        }
    }
    Ok(())
}

pub(super) fn lookup<'a>(table: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let (section, name) = key.split_once('.')?;
    table.get(section)?.get(name)
}

/// An answer read from the file, shaped like the part's expected value.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Given {
    Number(f64),
    Vector([f64; 3]),
    Trace(Vec<ExpectedLeaf>),
    Choice {
        answer: String,
        why: Option<String>,
    },
    Flag(bool),
    Formula {
        formula: Formula,
        source: String,
    },
    Paths(String),
    Planes(Vec<ExpectedPlane>),
    /// `"none"`: right for a part that may have no value, wrong (with a reason) elsewhere.
    None,
    /// Some value for a part whose key is "none" (its shape is not checked: any value is wrong).
    Something(String),
}

fn read_choice(key: &str, value: &toml::Value, options: &[&str]) -> Result<Given, CheckError> {
    let bad = |problem: String| CheckError::BadValue { key: key.to_string(), problem };
    let text = |v: &toml::Value| v.as_str().map(|s| s.trim().to_lowercase());
    match value {
        toml::Value::String(_) => Ok(Given::Choice { answer: text(value).unwrap_or_default(), why: None }),
        toml::Value::Table(table) => {
            let answer = table
                .get("answer")
                .and_then(text)
                .ok_or_else(|| bad(format!("needs answer = one of {}", quoted(options))))?;
            let why = match table.get("why") {
                None => None,
                Some(toml::Value::String(why)) => Some(why.clone()),
                Some(other) => return Err(bad(format!("`why` must be a string, got {}", other.type_str()))),
            };
            Ok(Given::Choice { answer, why })
        }
        other => Err(bad(format!("expected one of {}, got {} `{other}`", quoted(options), other.type_str()))),
    }
}

/// A t bound: a number, or infinity written `"inf"` (any case) or as TOML's bare `inf`.
fn bound(key: &str, value: Option<&toml::Value>) -> Result<f64, CheckError> {
    match value {
        Some(toml::Value::String(s)) if s.trim().eq_ignore_ascii_case("inf") => Ok(f64::INFINITY),
        Some(toml::Value::Float(x)) if *x == f64::INFINITY => Ok(f64::INFINITY),
        Some(other) => number(key, other),
        None => Err(CheckError::BadValue { key: key.to_string(), problem: "each leaf needs tmin and tmax".into() }),
    }
}

fn read_trace(key: &str, value: &toml::Value) -> Result<Vec<ExpectedLeaf>, CheckError> {
    let bad = |problem: String| CheckError::BadValue { key: key.to_string(), problem };
    let toml::Value::Array(items) = value else {
        return Err(bad(format!("expected an array of leaves, got {} `{value}`", value.type_str())));
    };
    items
        .iter()
        .map(|item| {
            let leaf = item.as_table().ok_or_else(|| bad("each leaf is a table { path, tmin, tmax }".into()))?;
            let path = leaf
                .get("path")
                .and_then(toml::Value::as_array)
                .ok_or_else(|| bad("each leaf needs path = [\"x>=3\", ...]".into()))?
                .iter()
                .map(|b| {
                    b.as_str().map(str::to_owned).ok_or_else(|| bad("path entries are strings like \"y<1\"".into()))
                })
                .collect::<Result<Vec<_>, _>>()?;
            Ok(ExpectedLeaf { path, t_min: bound(key, leaf.get("tmin"))?, t_max: bound(key, leaf.get("tmax"))? })
        })
        .collect()
}

fn number(key: &str, value: &toml::Value) -> Result<f64, CheckError> {
    let x = match value {
        toml::Value::Float(x) => *x,
        toml::Value::Integer(i) => *i as f64,
        other => {
            let problem = format!("expected a number, got {} `{other}`", other.type_str());
            return Err(CheckError::BadValue { key: key.to_string(), problem });
        }
    };
    if x.is_finite() {
        Ok(x)
    } else {
        Err(CheckError::BadValue { key: key.to_string(), problem: format!("must be finite, got {x}") })
    }
}

pub(super) fn read_value(key: &str, value: &toml::Value, expected: &Expected) -> Result<Given, CheckError> {
    // "none" is an answer only where the part allows it (an `OrNone` value, a class of light
    // paths); anywhere else it is read as an answer, so that it is graded wrong with a reason
    // rather than refusing the whole file.
    let none = matches!(value, toml::Value::String(s) if s.trim().eq_ignore_ascii_case("none"));
    if none && !matches!(expected, Expected::OrNone { .. } | Expected::Paths { .. }) {
        return Ok(Given::None);
    }
    match expected {
        Expected::Number { .. } => number(key, value).map(Given::Number),
        Expected::Trace { .. } => read_trace(key, value).map(Given::Trace),
        Expected::Choice { options, .. } => read_choice(key, value, options),
        Expected::Flag { .. } => match value {
            toml::Value::Boolean(b) => Ok(Given::Flag(*b)),
            other => Err(CheckError::BadValue {
                key: key.to_string(),
                problem: format!("expected true or false, got {} `{other}`", other.type_str()),
            }),
        },
        Expected::Formula { symbols, .. } => {
            let source = text(key, value, "a formula in quotes, e.g. \"dot(d, d)\"")?;
            let formula = Formula::parse(&source, symbols).map_err(|e| CheckError::BadValue {
                key: key.to_string(),
                problem: format!("formula `{source}`: {e}"),
            })?;
            Ok(Given::Formula { formula, source })
        }
        Expected::Paths { .. } => {
            let source = text(key, value, "a light-path class in quotes, e.g. \"LD+E\", or \"none\"")?;
            paths(&source).map_err(|e| CheckError::BadValue {
                key: key.to_string(),
                problem: format!("light paths `{source}`: {e}"),
            })?;
            Ok(Given::Paths(source))
        }
        Expected::Planes { .. } => read_planes(key, value).map(Given::Planes),
        Expected::OrNone { value: inner, none } => match value {
            toml::Value::String(s) if s.trim().eq_ignore_ascii_case("none") => Ok(Given::None),
            other if *none => Ok(Given::Something(other.to_string())),
            other => read_value(key, other, inner),
        },
        Expected::Vector { .. } | Expected::Direction { .. } | Expected::Parallel { .. } => {
            let bad = |problem: String| CheckError::BadValue { key: key.to_string(), problem };
            let toml::Value::Array(items) = value else {
                return Err(bad(format!("expected an array of 3 numbers, got {} `{value}`", value.type_str())));
            };
            if items.len() != 3 {
                return Err(bad(format!("expected 3 numbers, got {}", items.len())));
            }
            let mut out = [0.0; 3];
            for (slot, item) in out.iter_mut().zip(items) {
                *slot = number(key, item)?;
            }
            Ok(Given::Vector(out))
        }
    }
}

fn quoted(options: &[&str]) -> String {
    options.iter().map(|o| format!("\"{o}\"")).collect::<Vec<_>>().join(", ")
}

fn text(key: &str, value: &toml::Value, wanted: &str) -> Result<String, CheckError> {
    match value {
        toml::Value::String(s) => Ok(s.clone()),
        other => Err(CheckError::BadValue {
            key: key.to_string(),
            problem: format!("expected {wanted}, got {} `{other}`", other.type_str()),
        }),
    }
}

fn read_planes(key: &str, value: &toml::Value) -> Result<Vec<ExpectedPlane>, CheckError> {
    let bad = |problem: String| CheckError::BadValue { key: key.to_string(), problem };
    let shape = "each plane is a table { node = [...], t = N or \"parallel\", first = \"x>=3\" }";
    let toml::Value::Array(items) = value else {
        return Err(bad(format!("expected an array of planes, got {} `{value}`", value.type_str())));
    };
    items
        .iter()
        .map(|item| {
            let step = item.as_table().ok_or_else(|| bad(shape.into()))?;
            let node = step
                .get("node")
                .and_then(toml::Value::as_array)
                .ok_or_else(|| bad(shape.into()))?
                .iter()
                .map(|b| {
                    b.as_str().map(str::to_owned).ok_or_else(|| bad("node entries are strings like \"x>=3\"".into()))
                })
                .collect::<Result<Vec<_>, _>>()?;
            let t = match step.get("t") {
                Some(toml::Value::String(s)) if s == "parallel" => None,
                Some(other) => Some(number(key, other)?),
                None => return Err(bad(shape.into())),
            };
            let first = step.get("first").and_then(toml::Value::as_str).ok_or_else(|| bad(shape.into()))?.to_string();
            Ok(ExpectedPlane { node, t, first })
        })
        .collect()
}
