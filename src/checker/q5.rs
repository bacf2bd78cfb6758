//! Q5 tables: which effects each method captures, graded cell by cell against the grammar's
//! verdicts (area light, the homework's setting). Q5 has one variant: the seed is ignored.

use super::key::{Expected, Part, Variant};
use crate::q5_effect_tables::{Cell, EFFECTS, LightKind, Verdict, grammar_table};
use std::sync::OnceLock;

/// The chapter's sections on deciding a cell (and the paths a method misses), and on an effect's paths.
const CELL_NOTES: &str =
    "hw3/q5_effect_tables/index.html#parts-q5a-and-q5b-deciding-a-cell-and-the-paths-a-method-misses";
const PATHS_NOTES: &str = "hw3/q5_effect_tables/index.html#part-q5paths-an-effects-class-of-light-paths";

const CELL_METHOD: &str = "Write the effect as light paths and compare with the paths the method produces: all of them is yes, none is no, only by chance (noise) is impractical.";

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

fn word(verdict: Verdict) -> &'static str {
    match verdict {
        Verdict::Yes => "yes",
        Verdict::No => "no",
        Verdict::Impractical => "impractical",
    }
}

pub(super) fn variant(seed: u64) -> Variant {
    // Decided once per process: the grammar's search is most of a variant's cost, and no seed changes it.
    static CELLS: OnceLock<Vec<Cell>> = OnceLock::new();
    let cells =
        CELLS.get_or_init(|| grammar_table().expect("the built-in grammar tables parse (tested in q5_effect_tables)"));
    let mut parts = Vec::new();
    for (table, method) in [("q5a", "radiosity"), ("q5b", "two_pass")] {
        let mut cell_parts = Vec::new();
        let mut missed_parts = Vec::new();
        for cell in cells.iter().filter(|c| c.algorithm == method && c.light == LightKind::Area) {
            let name = format!("{table}.{}", cell.effect);
            let key = *KEYS.iter().find(|k| **k == name).expect("every Q5 effect row has a key");
            cell_parts.push(Part {
                key,
                prompt: "does the method capture the effect: yes, no or impractical (a `why` is shown, not graded)",
                points: 1.0,
                expected: Expected::Choice { value: word(cell.verdict), options: &VERDICTS },
                mal_rules: vec![],
                explained_in: CELL_NOTES,
                method: CELL_METHOD,
            });
            let name = format!("{table}.{}_missed", cell.effect);
            let effect = EFFECTS.iter().find(|e| e.id == cell.effect).expect("every cell has an effect");
            // The effects are narrow classes: a method misses all of one or none of it (tested below).
            let missed = if cell.verdict == Verdict::Yes { "none" } else { effect.paths };
            missed_parts.push(Part {
                key: MISSED.iter().find(|k| **k == name).expect("every Q5 cell has a reason key"),
                prompt: "the whole class of the effect's light paths that the method misses or gets only by chance (Heckbert's notation), or none",
                points: 0.5,
                expected: Expected::Paths { value: missed.to_string() },
                mal_rules: vec![],
                explained_in: CELL_NOTES,
                method: "The effect's paths that are outside the method's language (or outside its efficient part), in Heckbert's notation.",
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
            method: "Follow the light from L to E and name each surface it meets: D diffuse, G glossy, S specular, V a volume.",
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
    Variant { question: "q5", seed, statement, parts, follows: vec![] }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::q5_effect_tables::ALGORITHMS;
    use crate::render::analysis::grammar::{Lang, shortest_word};

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
