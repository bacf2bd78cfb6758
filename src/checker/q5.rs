//! Q5 tables: which effects each method captures, graded cell by cell against the grammar's
//! verdicts (area light, the homework's setting). Q5 has one variant: the seed is ignored.

use super::key::{Derivation, Expected, Follows, MalRule, Part, Setting, Variant};
use super::policy::Rule;
use crate::q5_effect_tables::{ALGORITHMS, Cell, EFFECTS, Effect, LightKind, Verdict, grammar_table};
use std::sync::OnceLock;

/// The chapter's sections on deciding a cell (and the paths a method misses), and on an effect's paths.
const CELL_NOTES: &str =
    "hw3/q5_effect_tables/index.html#parts-q5a-and-q5b-deciding-a-cell-and-the-paths-a-method-misses";
const PATHS_NOTES: &str = "hw3/q5_effect_tables/index.html#part-q5paths-an-effects-class-of-light-paths";

const CELL_METHOD: &str = "Write the effect as light paths and compare them with the paths the method produces: all of them on purpose is yes; some not at all is no; all, but some only by chance (noise), is impractical.";

/// The part keys: one per table and effect row of the Q5 chapter.
const KEYS: [&str; 12] = [
    "q5a.a",
    "q5a.b",
    "q5a.c",
    "q5a.d_mirror",
    "q5a.d_caustic",
    "q5a.e",
    "q5b.a",
    "q5b.b",
    "q5b.c",
    "q5b.d_mirror",
    "q5b.d_caustic",
    "q5b.e",
];

/// The reason parts: per cell, the effect's paths the method misses (or samples only by chance).
const MISSED: [&str; 12] = [
    "q5a.a_missed",
    "q5a.b_missed",
    "q5a.c_missed",
    "q5a.d_mirror_missed",
    "q5a.d_caustic_missed",
    "q5a.e_missed",
    "q5b.a_missed",
    "q5b.b_missed",
    "q5b.c_missed",
    "q5b.d_mirror_missed",
    "q5b.d_caustic_missed",
    "q5b.e_missed",
];

/// The row parts: each effect's class of light paths.
const ROWS: [&str; 6] = ["q5paths.a", "q5paths.b", "q5paths.c", "q5paths.d_mirror", "q5paths.d_caustic", "q5paths.e"];

/// The words a Q5 cell accepts.
const VERDICTS: [&str; 3] = ["yes", "no", "impractical"];

/// The tables graded, with their method.
const TABLES: [(&str, &str); 2] = [("q5a", "radiosity"), ("q5b", "two_pass")];

fn word(verdict: Verdict) -> &'static str {
    match verdict {
        Verdict::Yes => "yes",
        Verdict::No => "no",
        Verdict::Impractical => "impractical",
    }
}

/// The missed class a cell's key gives: `none` for a yes, the effect's whole class otherwise (the
/// effects are narrow classes: a method misses all of one or none of it; tested below).
fn missed_class(cell: &Cell, effect: &Effect) -> &'static str {
    if cell.verdict == Verdict::Yes { "none" } else { effect.paths }
}

/// What is wrong with answering `given` on `cell`, in one line, from the grammar's decision: the
/// effect's paths, the method's paths (all of them, and those it produces on purpose), the cell's
/// missed class and its shortest missed path. Built from the cell, never written per cell.
fn verdict_message(cell: &Cell, effect: &Effect, given: Verdict) -> String {
    let method = ALGORITHMS.iter().find(|m| m.id == cell.algorithm).expect("every cell has a method");
    let column = usize::from(cell.light == LightKind::Point);
    let (paths, efficient) = (method.paths[column], method.efficient[column]);
    let missed = missed_class(cell, effect);
    let witness = cell.witness.as_deref().unwrap_or("");
    match (cell.verdict, given) {
        (Verdict::Yes, _) => format!(
            "every path of the effect, {}, is among the paths the method produces on purpose, {efficient}: it misses nothing",
            effect.paths
        ),
        (Verdict::No, Verdict::Yes) => {
            format!("the method misses {missed}: its paths, {paths}, do not include {witness}, for one")
        }
        (Verdict::No, _) => format!(
            "impractical needs every path of the effect among the method's paths; {witness} is not among {paths} at all, so the method misses {missed}"
        ),
        (Verdict::Impractical, Verdict::Yes) => format!(
            "the method produces {missed} only by chance: {witness} is among its paths, {paths}, but not among those it produces on purpose, {efficient}"
        ),
        (Verdict::Impractical, _) => format!(
            "every path of the effect, {}, is among the method's paths, {paths}; it produces {missed} only by chance ({witness}, for one): impractical, not no",
            effect.paths
        ),
    }
}

/// A graded cell: the grammar's decision and, for each wrong verdict, what the checker says.
struct Graded {
    cell: Cell,
    wrong: Vec<(&'static str, String)>,
}

/// The graded cells (area light, the two methods of the homework), decided once per process: the
/// grammar's search is most of a variant's cost, and no seed changes it.
fn graded() -> &'static [Graded] {
    static GRADED: OnceLock<Vec<Graded>> = OnceLock::new();
    GRADED.get_or_init(|| {
        let cells = grammar_table().expect("the built-in grammar tables parse (tested in q5_effect_tables)");
        cells
            .into_iter()
            .filter(|c| c.light == LightKind::Area && TABLES.iter().any(|(_, method)| *method == c.algorithm))
            .map(|cell| {
                let effect = EFFECTS.iter().find(|e| e.id == cell.effect).expect("every cell has an effect");
                let wrong = [Verdict::Yes, Verdict::No, Verdict::Impractical]
                    .into_iter()
                    .filter(|v| *v != cell.verdict)
                    .map(|v| (word(v), verdict_message(&cell, effect, v)))
                    .collect();
                Graded { cell, wrong }
            })
            .collect()
    })
}

pub(super) fn variant(seed: u64) -> Variant {
    let mut parts = Vec::new();
    let mut follows = Vec::new();
    for (table, method) in TABLES {
        let mut cell_parts = Vec::new();
        let mut missed_parts = Vec::new();
        for graded in graded().iter().filter(|g| g.cell.algorithm == method) {
            let cell = &graded.cell;
            let name = format!("{table}.{}", cell.effect);
            let key = *KEYS.iter().find(|k| **k == name).expect("every Q5 effect row has a key");
            cell_parts.push(Part {
                key,
                prompt: "does the method capture the effect: yes, no or impractical (a `why` is shown, not graded)",
                points: 1.0,
                expected: Expected::Choice { value: word(cell.verdict), options: &VERDICTS },
                mal_rules: graded
                    .wrong
                    .iter()
                    .map(|(given, message)| MalRule {
                        value: Expected::Choice { value: given, options: &VERDICTS },
                        message: message.as_str(),
                        rule: Rule::WrongVerdict,
                    })
                    .collect(),
                explained_in: CELL_NOTES,
                method: CELL_METHOD,
            });
            let name = format!("{table}.{}_missed", cell.effect);
            let effect = EFFECTS.iter().find(|e| e.id == cell.effect).expect("every cell has an effect");
            let missed_key = *MISSED.iter().find(|k| **k == name).expect("every Q5 cell has a reason key");
            missed_parts.push(Part {
                key: missed_key,
                prompt: "the whole class of the effect's light paths that the method misses or gets only by chance (Heckbert's notation), or none",
                points: 0.5,
                expected: Expected::Paths { value: missed_class(cell, effect).to_string() },
                mal_rules: vec![],
                explained_in: CELL_NOTES,
                method: "The effect's paths that the method does not produce on purpose (none for a yes; for each of Q5's effects, all of it or none), in Heckbert's notation.",
            });
            // A missed class that follows from the student's own verdict on the cell (none for a
            // yes, the whole effect for a no) is charged once, at the verdict.
            follows.push(Follows {
                key: missed_key,
                from: key,
                derivation: Derivation::MissedFromVerdict { effect: effect.paths },
            });
        }
        parts.extend(cell_parts);
        parts.extend(missed_parts);
    }
    for (effect, key) in EFFECTS.iter().zip(ROWS) {
        parts.push(Part {
            key,
            prompt: "the effect's class of light paths, in Heckbert's notation (light first)",
            points: 0.5,
            expected: Expected::Paths { value: effect.paths.to_string() },
            mal_rules: vec![],
            explained_in: PATHS_NOTES,
            method: "Name the surfaces that make the effect, light first: D diffuse, G glossy, S specular; the lamp lights the first of them directly, the eye sees the last directly, and a surface the effect may meet again and stay the same effect gets a +.",
        });
    }
    let statement = format!(
        "Q5 (one variant; seed {seed} ignored). Effects: (a) a specular highlight on a glossy surface; (b) colour \
         bleeding; (c) diffuse shading that varies with the normal; (d) a specular effect, split into d_mirror (a \
         diffuse object seen in a mirror) and d_caustic (light focused by a mirror or glass); (e) ambient glow.\n\
         The scene is lit by an area light. (q5a) Radiosity. (q5b) The two-pass method: a first pass traces photons \
         from the light, off diffuse surfaces and through mirrors and glass, and keeps in its map only the photons \
         that land on a diffuse surface after at least one diffuse bounce; a second pass traces one ray from the eye \
         to the first surface it meets, adds the direct light there with shadow rays to the light, and adds the \
         map's estimate there. Eye rays are not traced further.\n\
         For each method and effect: does the method capture the effect? Answer yes, no or impractical (possible, \
         but only by chance: noise). For a no or an impractical, give the whole class of the effect's light paths \
         that the method misses or gets only by chance (\"none\" where it misses nothing), in Heckbert's notation \
         (L D G S V E, with | * + ? and parentheses), e.g. \"LS+E\" for every path from the light through one or \
         more mirrors to the eye. Equivalent expressions are the same answer (LDD*E = LD+E).\n\
         q5paths: each effect's own class of light paths, light first and eye last."
    );
    Variant { question: "q5", seed, setting: Setting::Q5, statement, parts, follows }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::analysis::grammar::{Lang, common_word, shortest_word};

    /// Every cell recognises both wrong verdicts under one rule, and what it says is the grammar's
    /// decision: for a no, the missed class and a path of the effect that the method's paths lack
    /// (checked here with the grammar, not read from the cell); for a yes, that every path of the
    /// effect is among those the method produces on purpose.
    #[test]
    fn a_wrong_verdict_is_told_what_the_paths_say() {
        let v = variant(0);
        for (table, method) in TABLES {
            let method = ALGORITHMS.iter().find(|m| m.id == method).unwrap();
            for effect in &EFFECTS {
                let part = v.parts.iter().find(|p| p.key == format!("{table}.{}", effect.id)).unwrap();
                let Expected::Choice { value: key, .. } = part.expected else { unreachable!() };
                let mut words: Vec<&str> = part
                    .mal_rules
                    .iter()
                    .map(|m| match m.value {
                        Expected::Choice { value, .. } => value,
                        _ => unreachable!(),
                    })
                    .collect();
                words.push(key);
                words.sort_unstable();
                assert_eq!(words, ["impractical", "no", "yes"], "{}", part.key);
                for mal_rule in &part.mal_rules {
                    assert_eq!(mal_rule.rule, Rule::WrongVerdict);
                    let message = mal_rule.message;
                    match key {
                        "yes" => {
                            assert!(
                                message.contains(effect.paths) && message.contains(method.efficient[0]),
                                "{message}"
                            );
                            assert!(message.contains("misses nothing"), "{message}");
                        }
                        "no" => {
                            assert!(message.contains(&format!("misses {}", effect.paths)), "{message}");
                            // The path the message names is the effect's and not the method's.
                            let named =
                                message.split(" include ").nth(1).or_else(|| message.split("; ").nth(1)).unwrap();
                            let witness = named.split([' ', ',']).find(|w| w.starts_with('L')).unwrap();
                            let word = Lang::parse(witness).unwrap();
                            assert!(common_word(&word, &Lang::parse(effect.paths).unwrap()).unwrap().is_some());
                            assert!(common_word(&word, &Lang::parse(method.paths[0]).unwrap()).unwrap().is_none());
                        }
                        other => panic!("no Q5 key cell is {other}"),
                    }
                }
            }
        }
    }

    /// The missed class follows from the cell's verdict as the key's does: the derivation applied
    /// to the key's verdict gives the key's missed class, for every cell.
    #[test]
    fn every_missed_class_follows_from_its_cell() {
        let v = variant(0);
        assert_eq!(v.follows.len(), MISSED.len());
        for follows in &v.follows {
            assert!(MISSED.contains(&follows.key) && KEYS.contains(&follows.from), "{follows:?}");
            assert_eq!(follows.from, follows.key.trim_end_matches("_missed"));
        }
    }

    /// The reason key is the effect's paths outside the method's language (Impractical: outside
    /// its efficient language), decided by the grammar: for the built-in effects that is all of
    /// the effect or none of it.
    #[test]
    fn reason_keys_are_the_grammars_difference() {
        let v = variant(0);
        for (table, method) in [("q5a", "radiosity"), ("q5b", "two_pass")] {
            let method = ALGORITHMS.iter().find(|m| m.id == method).unwrap();
            for effect in &EFFECTS {
                let key = format!("{table}.{}_missed", effect.id);
                let part = v.parts.iter().find(|p| p.key == key).unwrap();
                let Expected::Paths { value } = &part.expected else { unreachable!() };
                let cell = v.parts.iter().find(|p| p.key == format!("{table}.{}", effect.id)).unwrap();
                let Expected::Choice { value: verdict, .. } = cell.expected else { unreachable!() };
                let language = if verdict == "impractical" { method.efficient[0] } else { method.paths[0] };
                let langs = [
                    Lang::parse(effect.paths).unwrap(),
                    Lang::parse(language).unwrap(),
                    super::super::paths::paths(value).unwrap(),
                ];
                // A path is in the key iff it is an effect path the method's language lacks.
                let differs = shortest_word(&langs, |x| x[2] != (x[0] && !x[1])).unwrap();
                assert_eq!(differs, None, "{key}: {value}");
            }
        }
    }
}
