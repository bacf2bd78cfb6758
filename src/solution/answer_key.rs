//! The printable answer key of the notes: every part's final answer for seed 0, the student's
//! own answer beside it with the grade the checker gives it, and where the chapter explains it.

use super::text::value;
use super::{QUESTIONS, SolutionError, solution};
use crate::checker::{self, PartResult};
use crate::plot::{Figure, PlotError, markdown_table};
use std::fmt::Write as _;

/// The student's answers, transcribed as an answers file for seed 0 (the file the checker's
/// tests grade).
const STUDENT_ANSWERS: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/answers/seed_hw3.toml"));

/// The chapter section that teaches each graded part, by the part's table (the text before the
/// `.` of its key): the heading's text, as written in the chapter.
const SECTIONS: [(&str, &str); 18] = [
    ("q1a", "Part q1a: the gap fraction of a slab of spheres"),
    ("q1b", "Part q1b: transmittance and visual range"),
    ("q1c", "Part q1c: how far a mirror ball's reflection turns"),
    ("q1d", "Part q1d: image shift per frame"),
    ("q1match", "Part q1match: which scene shows which difficulty"),
    ("q2a", "Part q2a: the case, the first hit and its point"),
    ("q2b", "Part q2b: the normal and the reflected direction"),
    ("q2c", "Part q2c: the closest approach"),
    ("q3b", "Part q3b: the root plane's parameter"),
    ("q3c", "Part q3c: the plane parameter in the left child"),
    ("q3d", "Parts q3d and q3e: tracing a ray through the tree"),
    ("q3e", "Parts q3d and q3e: tracing a ray through the tree"),
    ("q4a", "Part q4a: the irradiance of a linear sky"),
    ("q4b", "Part q4b: the blind cone and the light it loses"),
    ("q4c", "Part q4c: a small mirror-ball image, texel by texel"),
    ("q5a", "Parts q5a and q5b: deciding a cell, and the paths a method misses"),
    ("q5b", "Parts q5a and q5b: deciding a cell, and the paths a method misses"),
    ("q5paths", "Part q5paths: an effect's class of light paths"),
];

/// A heading's anchor as rustdoc writes it: lower case, spaces to `-`, other punctuation dropped.
fn anchor(heading: &str) -> String {
    heading
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The chapter's module (`q2_ray_sphere`) from a checker `explained_in` path
/// (`hw3/q2_ray_sphere/index.html`), and the anchor it names, if any.
fn chapter_of(explained_in: &str) -> (String, Option<String>) {
    let (path, anchor) = explained_in.split_once('#').map_or((explained_in, None), |(p, a)| (p, Some(a.to_owned())));
    let module = path.trim_start_matches("hw3/").trim_end_matches("/index.html").replace('/', "::");
    (module, anchor)
}

/// A markdown link to the section explaining `part`: the checker's anchor when it names one,
/// else the section of [`SECTIONS`].
fn section_link(key: &str, explained_in: &str) -> String {
    let (module, given) = chapter_of(explained_in);
    let table = key.split_once('.').map_or(key, |(table, _)| table);
    let heading = SECTIONS.iter().find(|(prefix, _)| *prefix == table).map(|(_, h)| *h);
    match (given, heading) {
        (Some(given), _) => match SECTIONS.iter().find(|(_, h)| anchor(h) == given) {
            Some((_, heading)) => format!("[§ {heading}](crate::{module}#{given})"),
            None => format!("[{module} §](crate::{module}#{given})"),
        },
        (None, Some(heading)) => format!("[§ {heading}](crate::{module}#{})", anchor(heading)),
        (None, None) => format!("[{module}](crate::{module})"),
    }
}

/// What a part asks, in a few words: the checker's prompt, or for a Q1 match its scene and for a Q5
/// cell its method and effect (the prompt is the same for every scene and every cell).
fn asked(key: &str, prompt: &str) -> String {
    if let Some(scene) = key.strip_prefix("q1match.") {
        return format!("which difficulty `{scene}` shows");
    }
    match super::q5::cell_of(key) {
        Some((method, effect)) => format!("{}: {}", method.name, effect.name),
        None => prompt.to_owned(),
    }
}

/// Text for a table cell: pipes and brackets escaped (a leaf `[x<3, y<1]` is not a link).
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('[', "\\[").replace(']', "\\]").replace('\n', " ")
}

/// The grade as the key prints it: points, status, and for full points earned by following an
/// earlier wrong answer, the part where the error was made.
fn grade(result: &PartResult, follows: &[checker::Follows]) -> String {
    let points = |x: f64| format!("{x}");
    // A trace's own later pieces also carry a bound forward within the part; only credit earned
    // from an earlier part's answer names that part.
    let carried = (result.mistake == Some(checker::Rule::CarriedForward.id()))
        .then(|| {
            follows.iter().find(|f| {
                f.key == result.key && result.feedback.starts_with(&format!("follows from your `{}`", f.from))
            })
        })
        .flatten()
        .map_or(String::new(), |f| format!(", error carried forward from `{}`", f.from));
    format!("{}/{} {}{carried}", points(result.score), points(result.max_score), result.status)
}

/// The answer key as markdown: one table per question (part, what is asked, the answer, the
/// student's answer, its grade, the section explaining it), the student's total, and the
/// checker's feedback on every part the student lost points on.
///
/// # Errors
/// [`SolutionError`] if a solution cannot be written (a bug: seed 0 of every question is tested).
///
/// # Panics
/// If the student's transcribed answers no longer grade (the checker's tests pin that they do).
///
/// # Examples
/// ```
/// let key = hw3::solution::answer_key_table().unwrap();
/// assert!(key.contains("| `q2a.t` |") && key.contains("partial"));
/// ```
pub fn answer_key_table() -> Result<String, SolutionError> {
    let report = checker::check(STUDENT_ANSWERS, Some(0)).expect("the student's transcribed answers grade");
    let mut out = String::new();
    for question in QUESTIONS {
        let heading = question.to_uppercase();
        let variant = checker::variant(question, 0).expect("every question has a variant 0");
        let solved = solution(question, 0)?;
        // One block per question, so that printing never parts a heading from its table.
        let _ = writeln!(out, "<div class=\"answer-key-question\">\n\n### {heading}\n");
        let mut lost = Vec::new();
        let mut rows = Vec::new();
        for part in &variant.parts {
            let answer = solved.answers().find(|a| a.key == part.key).map_or("—".into(), |a| value(&a.value));
            let result = report.parts.iter().find(|r| r.key == part.key).expect("the report grades every part");
            let given = result.given.as_deref().unwrap_or("—");
            rows.push([
                format!("`{}`", part.key),
                cell(&asked(part.key, part.prompt)),
                // A trace's leaves, one a line.
                cell(&answer).replace("; ", "<br>"),
                cell(given).replace("; ", "<br>"),
                grade(result, &variant.follows),
                section_link(part.key, part.explained_in),
            ]);
            if result.status != "correct" && result.status != "missing" {
                // Escaped as a cell is: a path such as `[x<3]` would read as a link.
                lost.push(format!("- `{}`: {}", part.key, cell(&result.feedback)));
            }
        }
        let header = ["part", "asked", "answer", "the student's answer", "its grade", "explained in"];
        out.push_str(&markdown_table(&header, rows));
        out.push('\n');
        if !lost.is_empty() {
            let _ = writeln!(out, "Where the student lost points:\n\n{}\n", lost.join("\n"));
        }
        let _ = writeln!(out, "</div>\n");
    }
    let _ = writeln!(
        out,
        "The student's total: **{} / {}** over {} parts.",
        report.score,
        report.max_score,
        report.parts.len()
    );
    Ok(out)
}

/// The answer key's generated table, `answer_key_table.md`, for the figures pipeline.
///
/// # Errors
/// [`PlotError::Data`] with the [`SolutionError`] of [`answer_key_table`] if the table cannot be
/// written.
pub fn figures() -> Result<Vec<Figure>, PlotError> {
    let file_name = "answer_key_table.md".to_string();
    let table = answer_key_table().map_err(|e| PlotError::data(&file_name, e))?;
    Ok(vec![Figure { file_name, bytes: table.into_bytes() }])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_linked_section_is_a_heading_of_its_chapter() {
        for question in QUESTIONS {
            for part in checker::variant(question, 0).unwrap().parts {
                let (module, _) = chapter_of(part.explained_in);
                let path = format!("{}/docs/{module}.md", env!("CARGO_MANIFEST_DIR"));
                let chapter = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
                let table = part.key.split_once('.').unwrap().0;
                let (_, heading) = SECTIONS.iter().find(|(p, _)| *p == table).expect("a section per part");
                let (_, given) = chapter_of(part.explained_in);
                assert_eq!(given.as_deref(), Some(anchor(heading).as_str()), "{}", part.key);
                let found = chapter.lines().any(|l| l.trim_start_matches('#').trim() == *heading && l.starts_with('#'));
                assert!(found, "{module}.md has no heading `{heading}` for {}", part.key);
            }
        }
    }

    #[test]
    fn anchors_are_rustdocs() {
        assert_eq!(anchor("(c) The closest approach, two ways"), "c-the-closest-approach-two-ways");
        assert_eq!(anchor("The student's answer, checked"), "the-students-answer-checked");
    }

    #[test]
    fn the_key_carries_the_students_grade_for_every_part() {
        let table = answer_key_table().unwrap();
        let report = checker::check(STUDENT_ANSWERS, Some(0)).unwrap();
        for part in &report.parts {
            let row = table.lines().find(|l| l.starts_with(&format!("| `{}` |", part.key))).expect("a row per part");
            let follows = checker::variant(&part.key[..2], 0).unwrap().follows;
            assert!(row.contains(&grade(part, &follows)), "{row}");
        }
        assert!(table.contains(&format!("**{} / {}**", report.score, report.max_score)));
        // The student's q3d leaves earn full points only by following its own wrong descent:
        // the key says so where it prints the grade.
        let leaves = table.lines().find(|l| l.starts_with("| `q3d.leaves` |")).unwrap();
        assert!(leaves.contains("3/3 correct, error carried forward from `q3d.descents`"), "{leaves}");
        // Its descents lose points for their own slip, carried within the trace, not for its
        // planes, which are right.
        let descents = table.lines().find(|l| l.starts_with("| `q3d.descents` |")).unwrap();
        assert!(descents.contains("1.13/1.5 partial |"), "{descents}");
    }
}
