//! Q5 tables: which effects each method captures, graded cell by cell against the grammar's
//! verdicts (area light, the homework's setting). Q5 has one variant: the seed is ignored.

use super::key::{Expected, MalRule, Part, Variant};
use crate::q5_effect_tables::{LightKind, Verdict, grammar_table};

const NOTES: &str = "hw3/q5_effect_tables/index.html";

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

fn word(verdict: Verdict) -> &'static str {
    match verdict {
        Verdict::Yes => "yes",
        Verdict::No => "no",
        Verdict::Impractical => "impractical",
    }
}

pub(super) fn variant(seed: u64) -> Variant {
    let cells = grammar_table().expect("the built-in grammar tables parse (tested in q5_effect_tables)");
    let mut parts = Vec::new();
    for (table, method) in [("q5a", "radiosity"), ("q5b", "two_pass")] {
        for cell in cells.iter().filter(|c| c.method == method && c.light == LightKind::Area) {
            let name = format!("{table}.{}", cell.effect);
            let key = *KEYS.iter().find(|k| **k == name).expect("every Q5 effect row has a key");
            let mal_rules = if cell.verdict == Verdict::Impractical {
                vec![
                    MalRule {
                        value: Expected::Choice { value: "yes" },
                        message: "possible in principle, but only by chance (noise): impractical, not a practical yes",
                        credit: 0.5,
                    },
                    MalRule {
                        value: Expected::Choice { value: "no" },
                        message: "the method can produce these paths, only by chance (noise): impractical, not impossible",
                        credit: 0.5,
                    },
                ]
            } else {
                vec![]
            };
            parts.push(Part {
                key,
                prompt: "yes, no or impractical (a `why` is shown, not graded)",
                points: 1.0,
                expected: Expected::Choice { value: word(cell.verdict) },
                mal_rules,
                explained_in: NOTES,
            });
        }
    }
    let statement = format!(
        "Q5 (one variant; seed {seed} ignored). Effects: (a) a specular highlight on a glossy surface; (b) colour \
         bleeding; (c) diffuse shading that varies with the normal; (d) a specular effect, split into d_mirror (a \
         diffuse object seen in a mirror) and d_caustic (light focused by a mirror or glass); (e) ambient glow.\n\
         For an area light, does (q5a) radiosity, and (q5b) the two-pass method (eye rays not traced further, \
         plus photon tracing of diffuse transport), capture each? Answer yes, no or impractical."
    );
    Variant { question: "q5", seed, statement, parts }
}
