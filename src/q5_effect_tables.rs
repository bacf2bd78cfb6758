#![doc = include_str!(concat!(env!("OUT_DIR"), "/q5_effect_tables.md"))]

mod budget;
pub use budget::Budget;
pub mod cornell_published;
pub mod effect_grid;
pub mod effect_scenes;
pub mod error;
pub mod experiments;
mod figures;
pub use figures::{CAUSTIC_SPP, NOISY_SPP, PATH_SPP, PUBLISHED_SPP, renders};
mod grammar;
pub mod photon_accuracy;
pub mod photon_cornell;
pub mod radiosity;
mod regions;

pub use grammar::{
    ALGORITHMS, Algorithm, Cell, EFFECTS, Effect, LightKind, STUDENT_ANSWERS, StudentAnswer, Verdict, decide,
    grammar_table, grammar_table_markdown, student_answer,
};

use crate::answers::Answers;
use crate::plot::{Figure, PlotError, markdown_table};
use error::TablesError;
use grammar::agreement;

/// The cell-by-cell comparison with the student's answers (area light, the student's two
/// columns): the student's answer, the grammar's verdict with the shortest missed path, and the measured verdict with
/// the fraction of the path-traced effect captured, read from `measured` (the cells of
/// [`experiments::measured_table`]; "–" for a cell it lacks).
///
/// # Errors
/// [`TablesError::Grammar`] when the grammar ([`decide`]) fails (never for the built-in tables).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{StudentAnswer, Verdict, student_comparison_markdown};
/// use hw3::q5_effect_tables::experiments::{MeasuredCell, Measurement};
/// let cell = MeasuredCell {
///     effect: "a",
///     algorithm: "radiosity",
///     value: 0.0,
///     reference: 1.4,
///     fraction: 0.0,
///     verdict: Measurement::No,
///     grammar: Verdict::No,
///     student: StudentAnswer::No,
/// };
/// let markdown = student_comparison_markdown(&[cell]).unwrap();
/// // 5(a)(a) carries the measured cell; the other eleven cells of the student's have none here.
/// assert!(markdown.lines().any(|l| l.starts_with("| 5(a)(a) |") && l.ends_with("| No (0.00) |")));
/// assert_eq!(markdown.lines().filter(|l| l.starts_with("| 5(") && l.ends_with("| – |")).count(), 11);
/// ```
pub fn student_comparison_markdown(measured: &[experiments::MeasuredCell]) -> Result<String, TablesError> {
    let mut rows = Vec::new();
    for cell in grammar_table()?.iter().filter(|c| c.student != StudentAnswer::NotAsked) {
        let Some(method) = ALGORITHMS.iter().find(|m| m.id == cell.algorithm) else { continue };
        let Some(effect) = EFFECTS.iter().find(|e| e.id == cell.effect) else { continue };
        let experiment = measured
            .iter()
            .find(|m| m.effect == cell.effect && m.algorithm == cell.algorithm)
            .map_or_else(|| "–".to_string(), |m| format!("{} ({:.2})", m.verdict.text(), m.fraction));
        rows.push([
            format!("5({})({})", method.student_part.unwrap_or('?'), effect.id.replace('_', " ")),
            format!("`{}`", effect.paths),
            cell.student.text().to_string(),
            cell.verdict.text().to_string(),
            cell.witness.as_deref().unwrap_or("–").to_string(),
            agreement(cell).to_string(),
            experiment,
        ]);
    }
    let header = ["cell", "effect", "student", "grammar", "shortest path missed", "comparison", "measured"];
    Ok(markdown_table(&header, rows))
}

/// The output of `hw3 effect-tables` for the measured cells `measured` (the CLI passes
/// [`experiments::measured_table`]): the grammar tables, the comparison with the student's answers
/// and the measured table as text, or everything as one JSON value.
///
/// # Errors
/// [`TablesError::Grammar`] when a table cannot be built (a grammar overflow),
/// [`TablesError::Json`] when the JSON value cannot be serialised.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{ALGORITHMS, EFFECTS, StudentAnswer, Verdict, effect_tables_command};
/// use hw3::q5_effect_tables::experiments::{MeasuredCell, Measurement};
/// let cell = MeasuredCell {
///     effect: "e",
///     algorithm: "whitted",
///     value: 0.0,
///     reference: 0.3,
///     fraction: 0.0,
///     verdict: Measurement::No,
///     grammar: Verdict::No,
///     student: StudentAnswer::NotAsked,
/// };
/// let json: serde_json::Value = serde_json::from_str(&effect_tables_command(true, &[cell]).unwrap()).unwrap();
/// assert_eq!(json["measured"][0]["method"], "whitted");
/// assert_eq!(json["grammar"].as_array().unwrap().len(), 2 * EFFECTS.len() * ALGORITHMS.len()); // two lights
/// assert!(effect_tables_command(false, &[]).unwrap().contains("measured verdict"));
/// ```
pub fn effect_tables_command(json: bool, measured: &[experiments::MeasuredCell]) -> Result<String, TablesError> {
    let cells = grammar_table()?;
    if json {
        let value = serde_json::json!({ "grammar": cells, "measured": measured });
        Ok(serde_json::to_string_pretty(&value)?)
    } else {
        let mut out = grammar_table_markdown()?;
        out.push_str(&measured_tables_markdown(measured)?);
        Ok(out)
    }
}

/// The second half of `hw3 effect-tables` as text, the part that needs the measured cells: the
/// comparison with the student's answers and the measured table. The first half,
/// [`grammar_table_markdown`], needs no measurement, so the CLI prints it before measuring (and
/// ends there if its standard output cannot take it).
///
/// # Errors
/// [`TablesError::Grammar`] when the grammar table cannot be built (a grammar overflow).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{effect_tables_command, grammar_table_markdown, measured_tables_markdown};
/// let both = grammar_table_markdown().unwrap() + &measured_tables_markdown(&[]).unwrap();
/// assert_eq!(both, effect_tables_command(false, &[]).unwrap());
/// ```
pub fn measured_tables_markdown(measured: &[experiments::MeasuredCell]) -> Result<String, TablesError> {
    let mut out = student_comparison_markdown(measured)?;
    out.push('\n');
    out.push_str(&experiments::measured_table_markdown(measured));
    Ok(out)
}

/// Percentage of the path-traced caustic that the student's two-pass method captures (two
/// decimals) and that photon mapping captures (no decimals), as [`answers`] prints them. Measured
/// by [`experiments::measured_table`], too slow for `answers`; pinned by
/// `tests::printed_caustic_fractions_are_the_measured_ones`.
const CAUSTIC_PERCENT: (&str, &str) = ("0.03", "100");

/// Q5's answers.
///
/// # Examples
/// ```
/// assert!(hw3::q5_effect_tables::answers().text.contains("LGE"));
/// ```
#[must_use]
pub fn answers() -> Answers {
    let (two_pass, photon_mapping) = CAUSTIC_PERCENT;
    let text = format!(
        "(a) radiosity, LD*E: (a) highlight No (misses LGE), (b) colour bleeding Yes, (c) diffuse shading Yes, (d) specular effects No (misses LDSE, LSDE), (e) ambient glow Yes — all five as the student says, and all five measured so against the path tracer (table q5_measured).\n\
         (b) two-pass (direct light from eye rays + photon tracing): (a) Yes, (b) Yes, (c) Yes, (d) mirror images No (misses LDSE: eye rays are not traced further), caustics No (misses LSDE: its map keeps photons only after a diffuse bounce, so it never holds the LS+D photons of a caustic; measured {two_pass} % of the path-traced caustic, against {photon_mapping} % for photon mapping, whose caustic map keeps them), (e) Yes (the student: Yes, as in (b)).\n\
         With a point light the path tracer loses caustics altogether (No: LSDE), photon mapping keeps them."
    );
    Answers {
        question: "q5",
        title: "Which effects radiosity and a two-pass method capture (grammar + experiment)",
        text,
    }
}

/// Q5's drawn figures and tables, with the measurements at `budget` (the renders are
/// [`renders`]): the solvers' convergence chart, the published Cornell box's validation table,
/// the measured table, the grammar tables, the comparison with the student's answers, and the two
/// photon-map charts (drawn from committed data). [`Budget::PUBLISHED`] gives the committed
/// files, which `cargo run --release` rewrites byte for byte.
///
/// # Errors
/// [`PlotError`] if a figure cannot be drawn or a scene fails.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{Budget, figures};
/// let figures = figures(&Budget::TINY).unwrap();
/// let text = |name: &str| String::from_utf8(figures.iter().find(|f| f.file_name == name).unwrap().bytes.clone()).unwrap();
/// // Every one of the 24 measured cells is a row of the measured table...
/// assert_eq!(text("q5_measured_table.md").lines().filter(|l| l.starts_with("| (")).count(), 24);
/// // ...and the student's ten answers (twelve cells, Q5's (d) split in two) are compared.
/// assert_eq!(text("q5_seed_comparison.md").lines().filter(|l| l.starts_with("| 5(")).count(), 12);
/// ```
pub fn figures(budget: &Budget) -> Result<Vec<Figure>, PlotError> {
    let mut figures = figures::figures(budget)?;
    figures.push(photon_accuracy::figure()?);
    figures.push(photon_cornell::figure()?);
    Ok(figures)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::analysis::grammar::{Lang, shortest_word};

    #[test]
    fn every_built_in_expression_parses() {
        for effect in &EFFECTS {
            assert!(Lang::parse(effect.paths).is_ok(), "{}", effect.paths);
        }
        for method in &ALGORITHMS {
            for text in method.paths.iter().chain(&method.efficient) {
                assert!(Lang::parse(text).is_ok(), "{text}");
            }
        }
        // The efficient language is inside the full one, for every method and light.
        for method in &ALGORITHMS {
            for k in 0..2 {
                let langs = [Lang::parse(method.efficient[k]).unwrap(), Lang::parse(method.paths[k]).unwrap()];
                assert_eq!(shortest_word(&langs, |a| a[0] && !a[1]).unwrap(), None, "{}", method.id);
            }
        }
    }

    #[test]
    fn grammar_agrees_with_every_transcribed_student_cell() {
        let cells = grammar_table().unwrap();
        let disagreements: Vec<String> = cells
            .iter()
            .filter(|c| agreement(c) == "DISAGREES")
            .map(|c| format!("{} {} {:?}", c.algorithm, c.effect, c.verdict))
            .collect();
        assert!(disagreements.is_empty(), "{disagreements:?}");
        // Ten transcribed answers map onto 12 cells (d is split), every one of them answered:
        // the homework's last line is Q5(b)(e), "Yes - as in (b)".
        assert_eq!(cells.iter().filter(|c| c.student != StudentAnswer::NotAsked).count(), 12);
        assert!(STUDENT_ANSWERS.contains(&('b', 'e', StudentAnswer::Yes)));
    }

    #[test]
    fn light_type_changes_the_path_tracer_caustic_cell() {
        let caustic = EFFECTS.iter().find(|e| e.id == "d_caustic").unwrap();
        let pt = ALGORITHMS.iter().find(|m| m.id == "path_tracing").unwrap();
        let area = decide(caustic, pt, LightKind::Area).unwrap();
        let point = decide(caustic, pt, LightKind::Point).unwrap();
        assert_eq!((area.verdict, area.witness.as_deref()), (Verdict::Impractical, Some("LSDE")));
        assert_eq!((point.verdict, point.witness.as_deref()), (Verdict::No, Some("LSDE")));
    }

    #[test]
    fn effect_tables_json_has_every_cell_with_its_student_answer() {
        let measured = experiments::measured_table(&Budget::PUBLISHED).unwrap();
        let value: serde_json::Value = serde_json::from_str(&effect_tables_command(true, &measured).unwrap()).unwrap();
        let grammar = value["grammar"].as_array().unwrap();
        assert_eq!(grammar.len(), 2 * EFFECTS.len() * ALGORITHMS.len());
        let first = &grammar[0];
        assert_eq!((first["effect"].as_str(), first["method"].as_str()), (Some("a"), Some("radiosity")));
        assert_eq!((first["verdict"].as_str(), first["seed"].as_str()), (Some("no"), Some("no")));
        assert_eq!(value["measured"].as_array().unwrap().len(), 24);
        let text = effect_tables_command(false, &measured).unwrap();
        assert!(text.contains("No `LGE` (student: No)") && text.contains("measured verdict"));
    }

    #[test]
    fn grammar_tables_snapshot() {
        crate::testing::insta_settings().bind(|| {
            insta::assert_snapshot!("q5_grammar_tables", grammar_table_markdown().unwrap());
            let measured = experiments::measured_table(&Budget::PUBLISHED).unwrap();
            insta::assert_snapshot!("q5_seed_comparison", student_comparison_markdown(&measured).unwrap());
        });
    }

    /// The caustic percentages [`answers`] prints are the measured table's, and every radiosity
    /// cell is measured as the student answers it ("all five measured so").
    #[test]
    fn printed_caustic_fractions_are_the_measured_ones() {
        let cells = experiments::measured_table(&Budget::PUBLISHED).unwrap();
        let fraction = |method: &str| {
            cells.iter().find(|c| c.effect == "d_caustic" && c.algorithm == method).map(|c| 100.0 * c.fraction).unwrap()
        };
        let printed = (format!("{:.2}", fraction("two_pass")), format!("{:.0}", fraction("photon_mapping")));
        assert_eq!((printed.0.as_str(), printed.1.as_str()), CAUSTIC_PERCENT);
        for c in cells.iter().filter(|c| c.algorithm == "radiosity") {
            assert_eq!(c.verdict.text(), c.student.text(), "{c:?}");
        }
    }

    /// The verdict words and missed paths that [`answers`] prints for radiosity are the grammar's
    /// (area light), and the two-pass ones for (a)–(c) and the mirror image too.
    #[test]
    fn printed_verdicts_are_the_grammar_ones() {
        let cells = grammar_table().unwrap();
        let cell = |method: &str, effect: &str| {
            cells.iter().find(|c| c.light == LightKind::Area && c.algorithm == method && c.effect == effect).unwrap()
        };
        let text = answers().text;
        let radiosity = |effect| cell("radiosity", effect);
        let expected = [
            format!(
                "(a) highlight {} (misses {})",
                radiosity("a").verdict.text(),
                radiosity("a").witness.as_deref().unwrap()
            ),
            format!("(b) colour bleeding {}", radiosity("b").verdict.text()),
            format!("(c) diffuse shading {}", radiosity("c").verdict.text()),
            format!(
                "(d) specular effects {} (misses {}, {})",
                radiosity("d_mirror").verdict.text(),
                radiosity("d_mirror").witness.as_deref().unwrap(),
                radiosity("d_caustic").witness.as_deref().unwrap()
            ),
            format!("(e) ambient glow {}", radiosity("e").verdict.text()),
        ];
        for fragment in &expected {
            assert!(text.contains(fragment.as_str()), "{fragment}");
        }
        assert_eq!(radiosity("d_caustic").verdict, Verdict::No);
        let two_pass = |effect| cell("two_pass", effect).verdict.text();
        let line = text.lines().find(|l| l.starts_with("(b) two-pass")).unwrap();
        let expected = format!(
            "(a) {}, (b) {}, (c) {}, (d) mirror images {} (misses {}",
            two_pass("a"),
            two_pass("b"),
            two_pass("c"),
            two_pass("d_mirror"),
            cell("two_pass", "d_mirror").witness.as_deref().unwrap()
        );
        assert!(line.contains(&expected), "{expected}");
        assert_eq!(cell("two_pass", "d_caustic").verdict, Verdict::No, "printed as No");
        assert!(
            line.contains(&format!(
                "caustics No (misses {}",
                cell("two_pass", "d_caustic").witness.as_deref().unwrap()
            ))
        );
        // "all five as the student says" (printed): one answer of the student's per letter of Q5(a).
        assert_eq!(STUDENT_ANSWERS.iter().filter(|(part, _, _)| *part == 'a').count(), 5);
    }
}
