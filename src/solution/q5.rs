//! Q5 worked: each cell's verdict with the light path that decides it.
//!
//! A cell is decided by comparing the effect's paths with the paths the method can produce and
//! those it samples efficiently ([`decide`], the function the checker's key is built from): the
//! shortest path the method misses makes a No, the shortest it finds only by chance an
//! Impractical.

use super::{Section, Step, Value};
use crate::checker::Variant;
use crate::q5_effect_tables::{ALGORITHMS, Algorithm, EFFECTS, Effect, LightKind, Verdict, decide};

/// The method and effect of a part key: in `q5a.d_mirror`, table `q5a` is the homework's part (a)
/// (its method), row `d_mirror` the effect.
pub(super) fn cell_of(key: &str) -> Option<(&'static Algorithm, &'static Effect)> {
    let (table, row) = key.split_once('.')?;
    let letter = table.strip_prefix("q5")?.chars().next()?;
    let method = ALGORITHMS.iter().find(|m| m.student_part == Some(letter))?;
    let effect = EFFECTS.iter().find(|e| e.id == row)?;
    Some((method, effect))
}

/// The parts' keys are the checker's own, each naming an effect row and a method's table, and
/// every built-in cell is decidable (both tested), so nothing here can fail on a variant.
pub(super) fn sections(variant: &Variant) -> Vec<Section> {
    let mut sections: Vec<Section> = Vec::new();
    let mut push = |title: String, step: Step| {
        if sections.last().is_none_or(|s| s.title != title) {
            sections.push(Section { title, steps: Vec::new() });
        }
        sections.last_mut().expect("pushed above").steps.push(step);
    };
    for part in &variant.parts {
        if let Some(row) = part.key.strip_prefix("q5paths.") {
            let effect = EFFECTS.iter().find(|e| e.id == row).expect("every q5paths row is an effect");
            let text = format!("{row}. {}: light first, eye last: `{}`", effect.name, effect.paths);
            push(
                "(q5paths) each effect's light paths".into(),
                Step::answer(text, part.key, Value::Paths(effect.paths.into())),
            );
            continue;
        }
        let (cell_key, missed) = match part.key.strip_suffix("_missed") {
            Some(cell) => (cell, true),
            None => (part.key, false),
        };
        let (method, effect) = cell_of(cell_key).expect("every Q5 cell key names a method and an effect");
        let (table, row) = cell_key.split_once('.').unwrap_or((cell_key, ""));
        let cell = decide(effect, method, LightKind::Area).expect("the built-in cells are decidable");
        let title = format!(
            "({table}) {}, area light: can produce `{}`, efficiently `{}`",
            method.name, method.paths[0], method.efficient[0]
        );
        let witness = cell.witness.as_deref().unwrap_or("");
        if missed {
            // An effect is a narrow class of paths: a method gets all of it or misses all of it.
            let (paths, text) = match cell.verdict {
                Verdict::Yes => ("none", format!("{row}, reason: the method misses none of `{}`: none", effect.paths)),
                Verdict::Impractical | Verdict::No => (
                    effect.paths,
                    format!("{row}, reason: `{witness}` is one of them, so the whole class `{}`", effect.paths),
                ),
            };
            push(title, Step::answer(text, part.key, Value::Paths(paths.into())));
            continue;
        }
        let why = match cell.verdict {
            Verdict::Yes => format!("every path of `{}` is sampled efficiently", effect.paths),
            Verdict::Impractical => format!(
                "every path can be produced, but `{witness}` is not among those sampled efficiently: found only by \
                 chance (noise)"
            ),
            Verdict::No => format!("`{witness}` is a path of the effect the method cannot produce"),
        };
        let word = cell.verdict.text().to_lowercase();
        let text = format!("{row}. {}: paths `{}`; {why}: {word}", effect.name, effect.paths);
        push(title, Step::answer(text, part.key, Value::Word(word)));
    }
    sections
}
