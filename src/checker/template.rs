//! Answers files written by the checker: the blank template and the key itself.

use super::error::CheckError;
use super::formula::Kind;
use super::key::Expected;
use super::variants::{QUESTIONS, variant};
use std::fmt::Write as _;

/// A blank answers file for `seed`: every question's statement as comments, every key present
/// but commented out, with its tolerance.
///
/// # Examples
/// ```
/// let blank = hw3::checker::template(0).unwrap();
/// assert!(blank.contains("# t = "));
/// let report = hw3::checker::check(&blank, None).unwrap();
/// assert_eq!(report.score, 0.0);
/// ```
///
/// # Errors
/// Never for the built-in questions; the `Result` covers future question ids.
pub fn template(seed: u64) -> Result<String, CheckError> {
    let mut out = format!("# hw3 answers file. Grade it with: hw3 check FILE\n[meta]\nseed = {seed}\n");
    for question in QUESTIONS {
        let variant = variant(question, seed)?;
        out.push('\n');
        for line in variant.statement.lines() {
            let _ = writeln!(out, "# {line}");
        }
        let mut section = "";
        for part in &variant.parts {
            let name = open_table(&mut out, &mut section, part.key);
            let shape = shape(&part.expected);
            let _ = writeln!(out, "# {} ({shape}, {} points)\n# {name} = ", part.prompt, part.points);
        }
    }
    Ok(out)
}

/// The key itself as an answers file (what a perfect student would submit).
///
/// # Errors
/// Never for the built-in questions.
///
/// # Examples
/// ```
/// assert!(hw3::checker::answer_key(3).unwrap().contains("seed = 3"));
/// ```
pub fn answer_key(seed: u64) -> Result<String, CheckError> {
    let mut out = format!("[meta]\nseed = {seed}\n");
    for question in QUESTIONS {
        out.push_str(&answer_key_for(question, seed)?);
    }
    Ok(out)
}

/// The key's tables for one question (no `[meta]`).
///
/// # Errors
/// [`CheckError::UnknownQuestion`] for an unknown question id.
///
/// # Examples
/// ```
/// assert!(hw3::checker::answer_key_for("q3", 0).unwrap().contains("[q3d]"));
/// ```
pub fn answer_key_for(question: &str, seed: u64) -> Result<String, CheckError> {
    let mut out = String::new();
    let mut section = "";
    for part in variant(question, seed)?.parts {
        let name = open_table(&mut out, &mut section, part.key);
        let value = key_value(&part.expected);
        let _ = writeln!(out, "{name} = {value}");
    }
    Ok(out)
}

/// Writes the `[table]` header of the dotted `key` (`q2a.t`) when it starts a new table, and returns
/// the key's name within it (`t`): the parts of a variant come grouped by table.
fn open_table<'k>(out: &mut String, section: &mut &'k str, key: &'k str) -> &'k str {
    let (table, name) = key.split_once('.').unwrap_or((key, ""));
    if table != *section {
        let _ = writeln!(out, "\n[{table}]");
        *section = table;
    }
    name
}

/// The format line of a part in the template.
fn shape(expected: &Expected) -> String {
    match expected {
        Expected::OrNone { value, .. } => format!("{}; or \"none\" if there is none", shape(value)),
        Expected::Number { rtol, .. } => format!("a number; relative tolerance {rtol:.0e}"),
        Expected::Vector { .. } => "[x, y, z]".to_string(),
        Expected::Direction { angle_tol, .. } | Expected::Parallel { angle_tol, .. } => {
            format!("[x, y, z], unit length, within {angle_tol:.0e} rad")
        }
        Expected::Trace { .. } => "[{ path = [...], tmin = N, tmax = N or \"inf\" }, ...]".to_string(),
        Expected::Planes { .. } => {
            "[{ node = [...], t = N or \"parallel\", first = \"x>=3\" }, ...]; node = [] is the root".to_string()
        }
        Expected::Choice { options, .. } => {
            let words: Vec<String> = options.iter().map(|o| format!("\"{o}\"")).collect();
            format!("one of {}; or {{ answer = ..., why = \"...\" }}", words.join(", "))
        }
        Expected::Flag { .. } => "true or false".to_string(),
        Expected::Formula { symbols, .. } => {
            let names: Vec<String> = symbols
                .iter()
                .map(|(name, kind)| match kind {
                    Kind::Vector => format!("{name} (vector; {name}_x ...)"),
                    Kind::Scalar => (*name).to_string(),
                })
                .collect();
            format!(
                "a formula in quotes in {}; + - * / ^, dot, cross, norm, sqrt, abs, max; write * for products",
                names.join(", ")
            )
        }
        Expected::Paths { .. } => {
            "light paths in Heckbert's notation in quotes: L D G S V E, | * + ? ( ), or \"none\"".to_string()
        }
    }
}

/// A part's key as a TOML value.
fn key_value(expected: &Expected) -> String {
    match expected {
        Expected::Number { value, .. } => format!("{value:?}"),
        Expected::Vector { value, .. } | Expected::Direction { value, .. } | Expected::Parallel { value, .. } => {
            format!("[{:?}, {:?}, {:?}]", value[0], value[1], value[2])
        }
        Expected::OrNone { none: true, .. } => "\"none\"".to_string(),
        Expected::OrNone { value, .. } => key_value(value),
        Expected::Choice { value, .. } => format!("{value:?}"),
        Expected::Flag { value } => value.to_string(),
        Expected::Formula { source, .. } => format!("{source:?}"),
        Expected::Paths { value } => format!("{value:?}"),
        Expected::Planes { steps, .. } => {
            let rows: Vec<String> = steps
                .iter()
                .map(|p| {
                    let node: Vec<String> = p.node.iter().map(|b| format!("{b:?}")).collect();
                    let t = p.t.map_or_else(|| "\"parallel\"".to_string(), |t| format!("{t:?}"));
                    format!("  {{ node = [{}], t = {t}, first = {:?} }},", node.join(", "), p.first)
                })
                .collect();
            format!("[\n{}\n]", rows.join("\n"))
        }
        Expected::Trace { leaves, .. } => {
            let bound = |t: f64| if t.is_infinite() { "\"inf\"".to_string() } else { format!("{t:?}") };
            let rows: Vec<String> = leaves
                .iter()
                .map(|l| {
                    let path: Vec<String> = l.path.iter().map(|p| format!("{p:?}")).collect();
                    format!(
                        "  {{ path = [{}], tmin = {}, tmax = {} }},",
                        path.join(", "),
                        bound(l.t_min),
                        bound(l.t_max)
                    )
                })
                .collect();
            format!("[\n{}\n]", rows.join("\n"))
        }
    }
}
