//! `hw3 kd-trace`: the homework tree's traversal for one ray, as text or as the JSON contract.

use super::{Branch, Interval, Node2, Ray2, Step, traverse};
use crate::geometry::InputError;
use serde_json::{Value, json};

/// Why `hw3 kd-trace` rejected its input (the CLI exits with status 2).
///
/// # Examples
/// ```
/// use hw3::q3_kd_traversal::{TraceInputError, parse_vec2};
/// let error = parse_vec2("origin", "5;0").unwrap_err();
/// assert!(matches!(error, TraceInputError::Parse { name: "origin", .. }));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TraceInputError {
    /// An argument is not two comma-separated numbers.
    #[error("--{name}: expected two comma-separated numbers like 5,-1.5, got `{text}`")]
    Parse {
        /// The option's name.
        name: &'static str,
        /// What the user typed.
        text: String,
    },
    /// The numbers do not make a valid ray (NaN, infinite, or a zero direction).
    #[error(transparent)]
    Input(#[from] InputError),
}

/// Parses `"x,y"` (spaces allowed) into two numbers; `nan`/`inf` parse here and are rejected
/// later by [`Ray2::new`].
///
/// # Errors
/// [`TraceInputError::Parse`] unless there are exactly two numbers.
///
/// # Examples
/// ```
/// use hw3::q3_kd_traversal::parse_vec2;
/// assert_eq!(parse_vec2("origin", "5, -1e0").unwrap(), [5.0, -1.0]);
/// assert!(parse_vec2("origin", "5").is_err());
/// ```
pub fn parse_vec2(name: &'static str, text: &str) -> Result<[f64; 2], TraceInputError> {
    let numbers: Result<Vec<f64>, _> = text.split(',').map(|p| p.trim().parse::<f64>()).collect();
    match numbers.as_deref() {
        Ok(&[x, y]) => Ok([x, y]),
        _ => Err(TraceInputError::Parse { name, text: text.to_owned() }),
    }
}

/// Runs `hw3 kd-trace --origin X,Y --dir X,Y [--json]`: traverses the homework's tree
/// ([`Node2::homework`]) and returns the trace as text, or as JSON: an object with `leaves` (each
/// `{"path": ["x>=3", "y<3"], "tmin": N, "tmax": N}`, infinite bounds as the string `"inf"`) and
/// `steps` (every step, tagged by `kind`: `plane` with `t` — `null` when the ray is parallel —,
/// `descend` and `leaf` with `tmin`/`tmax`).
///
/// # Errors
/// [`TraceInputError`] for unparsable, non-finite or zero-direction input.
///
/// # Examples
/// ```
/// let out = hw3::q3_kd_traversal::kd_trace_command("2,0", "-1,-1", true).unwrap();
/// let v: serde_json::Value = serde_json::from_str(&out).unwrap();
/// assert_eq!(v["leaves"][0]["path"], serde_json::json!(["x<3", "y<1"]));
/// assert_eq!(v["leaves"][0]["tmax"], "inf");
/// ```
pub fn kd_trace_command(origin: &str, dir: &str, json: bool) -> Result<String, TraceInputError> {
    let ray = Ray2::new(parse_vec2("origin", origin)?, parse_vec2("dir", dir)?)?;
    let trace = traverse(&Node2::homework(), &ray);
    if !json {
        return Ok(trace.to_string().trim_end().to_owned());
    }
    let leaves: Vec<Value> =
        trace.leaves().iter().map(|leaf| interval_object(None, &leaf.path, leaf.interval)).collect();
    let steps: Vec<Value> = trace.steps.iter().map(step_value).collect();
    let value = json!({
        "origin": ray.origin,
        "dir": ray.dir,
        "leaves": leaves,
        "steps": steps,
    });
    Ok(serde_json::to_string_pretty(&value).expect("a JSON value always serialises"))
}

/// A number, or `"inf"` / `"-inf"` (JSON has no infinities).
fn number(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { json!(super::Number(x).to_string()) }
}

fn path_value(path: &[Branch]) -> Value {
    path.iter().map(ToString::to_string).collect()
}

fn interval_object(kind: Option<&str>, path: &[Branch], interval: Interval) -> Value {
    let mut object = json!({
        "path": path_value(path),
        "tmin": number(interval.t_min),
        "tmax": number(interval.t_max),
    });
    if let Some(kind) = kind {
        object["kind"] = json!(kind);
    }
    object
}

fn step_value(step: &Step) -> Value {
    match step {
        Step::Plane { path, axis, split, t } => json!({
            "kind": "plane",
            "path": path_value(path),
            "axis": axis.to_string(),
            "split": split,
            "t": t.map_or(Value::Null, number),
        }),
        Step::Descend { path, interval } => interval_object(Some("descend"), path, *interval),
        Step::Leaf { path, interval } => interval_object(Some("leaf"), path, *interval),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_contract_for_case_d() {
        let out = kd_trace_command("5,0", "-1,1", true).unwrap();
        let v: Value = serde_json::from_str(&out).unwrap();
        assert_eq!(
            v["leaves"],
            json!([
                {"path": ["x>=3", "y<3"], "tmin": 0.0, "tmax": 2.0},
                {"path": ["x<3", "y>=1"], "tmin": 2.0, "tmax": "inf"},
            ])
        );
        let kinds: Vec<&str> = v["steps"].as_array().unwrap().iter().map(|s| s["kind"].as_str().unwrap()).collect();
        assert_eq!(kinds, ["plane", "descend", "plane", "descend", "leaf", "descend", "plane", "descend", "leaf"]);
        assert_eq!(v["steps"][0]["t"], json!(2.0));
    }

    #[test]
    fn parallel_plane_step_has_null_t() {
        let out = kd_trace_command("3,0", "0,1", true).unwrap();
        let v: Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["steps"][0]["t"], Value::Null);
    }

    #[test]
    fn bad_input_is_rejected_with_a_typed_error() {
        assert!(matches!(kd_trace_command("5", "-1,1", false), Err(TraceInputError::Parse { name: "origin", .. })));
        assert!(matches!(
            kd_trace_command("nan,0", "-1,1", false),
            Err(TraceInputError::Input(InputError::NonFinite { .. }))
        ));
        assert!(matches!(
            kd_trace_command("0,0", "0,-0", true),
            Err(TraceInputError::Input(InputError::DegenerateDirection { .. }))
        ));
    }
}
