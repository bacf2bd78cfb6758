//! Solutions as text and markdown, and their final answers as an answers file.

use super::{Format, Solution, Value};
use crate::checker::ExpectedLeaf;
use std::fmt::Write as _;

/// A number as a student writes it: six decimals with trailing zeros dropped (`5`, `3.267949`),
/// `inf` for an unbounded interval, and never `-0`.
pub(super) fn num(x: f64) -> String {
    if x.is_infinite() {
        return if x > 0.0 { "inf".into() } else { "-inf".into() };
    }
    let text = format!("{x:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" { "0".into() } else { text.into() }
}

/// [`num`], in parentheses when negative, for a number inside a formula (`(3 - 5)/(-1)`).
pub(super) fn operand(x: f64) -> String {
    let text = num(x);
    if text.starts_with('-') { format!("({text})") } else { text }
}

/// `(x, y, z)` with [`num`] coordinates.
pub(super) fn vector(v: [f64; 3]) -> String {
    format!("({}, {}, {})", num(v[0]), num(v[1]), num(v[2]))
}

/// A leaf as the answers file writes it: `[x>=3, y<3] t in [0, 2]`.
pub(super) fn leaf(l: &ExpectedLeaf) -> String {
    format!("[{}] t in [{}, {}]", l.path.join(", "), num(l.t_min), num(l.t_max))
}

/// The value as the solution prints it.
pub(super) fn value(value: &Value) -> String {
    match value {
        Value::Number(x) => num(*x),
        Value::Vector(v) => vector(*v),
        Value::Leaves(leaves) => leaves.iter().map(leaf).collect::<Vec<_>>().join("; "),
        Value::Word(w) => w.clone(),
    }
}

pub(super) fn solution(s: &Solution, format: Format) -> String {
    let mut out = String::new();
    match format {
        Format::Text => {
            let _ = writeln!(out, "{}\n", s.statement);
            for section in &s.sections {
                let _ = writeln!(out, "{}", section.title);
                for step in &section.steps {
                    let indent = "  ".repeat(step.depth + 1);
                    let mark = step.answer.as_ref().map_or(String::new(), |a| format!("    [{}]", a.key));
                    let _ = writeln!(out, "{indent}{}{mark}", step.text);
                }
            }
            if s.answers().next().is_some() {
                let _ = writeln!(out, "\nanswers:");
            }
            for answer in s.answers() {
                let _ = writeln!(out, "  {} = {}", answer.key, value(&answer.value));
            }
        }
        Format::Markdown => {
            let (title, rest) = s.statement.split_once(". ").unwrap_or((&s.statement, ""));
            let _ = writeln!(out, "## {title}\n\n{}\n", rest.replace('\n', "  \n"));
            for section in &s.sections {
                let _ = writeln!(out, "### {}\n", section.title);
                for step in &section.steps {
                    let indent = "  ".repeat(step.depth);
                    match &step.answer {
                        Some(a) => {
                            let _ = writeln!(out, "{indent}- **{}** (`{}`)", step.text, a.key);
                        }
                        None => {
                            let _ = writeln!(out, "{indent}- {}", step.text);
                        }
                    }
                }
                out.push('\n');
            }
            if s.answers().next().is_some() {
                let _ = writeln!(out, "| part | answer |\n|---|---|");
            }
            for answer in s.answers() {
                let _ = writeln!(out, "| `{}` | {} |", answer.key, value(&answer.value));
            }
        }
    }
    out
}

/// TOML for one value, with the digits [`num`] prints.
fn toml_value(value: &Value) -> String {
    let bound = |t: f64| if t.is_infinite() { "\"inf\"".to_string() } else { num(t) };
    match value {
        Value::Number(x) => num(*x),
        Value::Vector(v) => format!("[{}, {}, {}]", num(v[0]), num(v[1]), num(v[2])),
        Value::Word(w) => format!("{w:?}"),
        Value::Leaves(leaves) => {
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

pub(super) fn answers_toml(s: &Solution) -> String {
    let mut out = String::new();
    let mut table = "";
    for answer in s.answers() {
        let (section, name) = answer.key.split_once('.').unwrap_or((answer.key, ""));
        if section != table {
            let _ = writeln!(out, "\n[{section}]");
            table = section;
        }
        let _ = writeln!(out, "{name} = {}", toml_value(&answer.value));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_a_student_writes_them() {
        assert_eq!(num(5.0), "5");
        assert_eq!(num(5.0 - 3f64.sqrt()), "3.267949");
        assert_eq!(num(-1e-17), "0");
        assert_eq!(num(f64::INFINITY), "inf");
        assert_eq!(num(0.5), "0.5");
        assert_eq!((operand(-1.0), operand(2.0)), ("(-1)".to_string(), "2".to_string()));
    }
}
