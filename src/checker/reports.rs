//! A graded file as text for the student and as Gradescope's `results.json`.

use super::grading::Report;
use std::fmt::Write as _;

/// Where `cargo doc` writes the notes, from the crate's folder: the text report's links to the
/// chapters' sections start here, so that they open as printed (a [`super::Part`]'s
/// `explained_in` is the path below it, which a course serving the notes elsewhere appends to its
/// own address).
pub const NOTES_ROOT: &str = "target/doc/";

/// The report as plain text: one line per part, then the total; each part that loses points
/// links its chapter's section under [`NOTES_ROOT`].
///
/// # Examples
/// ```
/// let report = hw3::checker::check("", None).unwrap();
/// assert!(hw3::checker::report_text(&report).contains("missing"));
/// ```
#[must_use]
pub fn report_text(report: &Report) -> String {
    let mut out = format!("variant seed {}\n", report.seed);
    for part in &report.parts {
        let mark = match part.status {
            "correct" => "✓",
            "partial" => "~",
            _ => "✗",
        };
        let _ = writeln!(out, "{mark} {:<26} {:>5.2}/{:<4} {}", part.key, part.score, part.max_score, part.status);
        if part.status != "correct" || part.mistake.is_some() {
            let given = part.given.as_deref().unwrap_or("—");
            let _ = writeln!(out, "    given {given}, expected {}\n    {}", part.expected, part.feedback);
            let _ = writeln!(out, "    explained in {NOTES_ROOT}{}", part.explained_in);
        }
    }
    for warning in &report.warnings {
        let _ = writeln!(out, "! {warning}");
    }
    for key in &report.unknown_keys {
        let _ = writeln!(out, "? unknown key {key}: not graded");
    }
    let _ = write!(out, "score {:.2} / {:.2} over {} parts", report.score, report.max_score, report.parts.len());
    out
}

/// The report in Gradescope's autograder `results.json` shape (one test per part).
///
/// # Examples
/// ```
/// let report = hw3::checker::check("", None).unwrap();
/// let json = hw3::checker::report_gradescope(&report);
/// assert!(json["tests"].as_array().unwrap().iter().any(|t| t["name"] == "q2a.t"));
/// ```
#[must_use]
pub fn report_gradescope(report: &Report) -> serde_json::Value {
    let tests: Vec<serde_json::Value> = report
        .parts
        .iter()
        .map(|p| {
            serde_json::json!({
                "name": p.key,
                "score": p.score,
                "max_score": p.max_score,
                "status": if p.status == "correct" { "passed" } else { "failed" },
                "output": format!("{}: given {}, expected {}. {}", p.status, p.given.as_deref().unwrap_or("—"), p.expected, p.feedback),
                "visibility": "visible",
            })
        })
        .collect();
    serde_json::json!({ "score": report.score, "output": format!("variant seed {}", report.seed), "tests": tests })
}
