//! Solutions as text and markdown, and their final answers as an answers file.

use super::{Format, Solution, Value};
use crate::checker::{ExpectedLeaf, ExpectedPlane};
use crate::plot::markdown_table;
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

/// A final number, as the solution prints it and writes it to an answers file: [`num`], except
/// that a non-zero number below 10⁻³ keeps six significant digits, which six decimals would not
/// (the gap fraction of a dense slab can be a few millionths, or 10⁻¹²): the checker compares
/// numbers relatively.
pub(super) fn final_number(x: f64) -> String {
    if x != 0.0 && x.abs() < 1e-3 { format!("{x:.5e}") } else { num(x) }
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

/// A plane as the answers file writes it: `root: t = 2, first x>=3`.
fn plane(p: &ExpectedPlane) -> String {
    let node = if p.node.is_empty() { "root".to_owned() } else { p.node.join(", ") };
    let t = p.t.map_or_else(|| "parallel".to_owned(), |t| format!("t = {}", num(t)));
    format!("[{node}] {t}, first {}", p.first)
}

/// The value as the solution prints it.
pub(super) fn value(value: &Value) -> String {
    match value {
        Value::Number(x) => final_number(*x),
        Value::Vector(v) => vector(*v),
        Value::Leaves(leaves) => leaves.iter().map(leaf).collect::<Vec<_>>().join("; "),
        Value::Word(w) | Value::Formula(w) | Value::Paths(w) => w.clone(),
        Value::Flag(flag) => flag.to_string(),
        Value::None => "none".into(),
        Value::Planes(planes) => planes.iter().map(plane).collect::<Vec<_>>().join("; "),
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
                let rows = s.answers().map(|answer| [format!("`{}`", answer.key), value(&answer.value)]);
                out.push_str(&markdown_table(&["part", "answer"], rows));
            }
        }
    }
    out
}

/// One value as TOML, with the digits [`num`] prints (so a file built from it is what a student
/// copying the solution hands in).
fn toml_value(value: &Value) -> toml::Value {
    let printed = |x: f64| match num(x).parse::<f64>() {
        Ok(y) if y.is_finite() => toml::Value::Float(y),
        _ => toml::Value::String(num(x)),
    };
    let words = |words: &[String]| toml::Value::Array(words.iter().cloned().map(toml::Value::String).collect());
    let row = |cells: [(&str, toml::Value); 3]| {
        toml::Value::Table(cells.into_iter().map(|(key, value)| (key.to_owned(), value)).collect())
    };
    match value {
        Value::Number(x) => final_number(*x).parse().map_or_else(|_| printed(*x), toml::Value::Float),
        Value::Vector(v) => toml::Value::Array(v.iter().map(|&x| printed(x)).collect()),
        Value::Word(w) | Value::Formula(w) | Value::Paths(w) => toml::Value::String(w.clone()),
        Value::Flag(flag) => toml::Value::Boolean(*flag),
        Value::None => toml::Value::String("none".into()),
        Value::Planes(planes) => toml::Value::Array(
            planes
                .iter()
                .map(|p| {
                    let t = p.t.map_or_else(|| toml::Value::String("parallel".into()), printed);
                    row([("node", words(&p.node)), ("t", t), ("first", toml::Value::String(p.first.clone()))])
                })
                .collect(),
        ),
        Value::Leaves(leaves) => toml::Value::Array(
            leaves
                .iter()
                .map(|l| row([("path", words(&l.path)), ("tmin", printed(l.t_min)), ("tmax", printed(l.t_max))]))
                .collect(),
        ),
    }
}

pub(super) fn answers_toml(s: &Solution) -> String {
    let mut file = toml::Table::new();
    for answer in s.answers() {
        let (section, name) = answer.key.split_once('.').unwrap_or((answer.key, ""));
        let table = file.entry(section).or_insert_with(|| toml::Value::Table(toml::Table::new()));
        if let toml::Value::Table(table) = table {
            table.insert(name.into(), toml_value(&answer.value));
        }
    }
    toml::to_string(&file).expect("a table of numbers, strings and arrays serialises")
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
        assert_eq!(
            (final_number(4.6e-6), final_number(1e-17), final_number(-0.0), final_number(0.5)),
            ("4.60000e-6".into(), "1.00000e-17".into(), "0".into(), "0.5".into())
        );
    }
}
