//! The effect tables as languages: each effect is a set of light paths (Heckbert's notation),
//! each method two languages (paths it can produce, paths it samples efficiently), and a cell's
//! verdict is decided by language inclusion.

use crate::plot::markdown_table;
use crate::render::analysis::grammar::{GrammarError, Lang, shortest_word, word_text};
use serde::Serialize;

/// A lighting effect of Q5, reconstructed from the student's reasons (the effect list itself is
/// missing from the transcription).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::EFFECTS;
/// let highlight = &EFFECTS[0];
/// assert_eq!((highlight.id, highlight.student_letter, highlight.paths), ("a", 'a', "LGE"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Effect {
    /// Row id: `a` … `e`; the student's (d) "a specular effect" is split into `d_mirror` and `d_caustic`.
    pub id: &'static str,
    /// The student's letter this row is compared with.
    // Serialized as `seed_letter`, as `Algorithm::student_part` is as `seed_part`: the names
    // serialized tables already carry.
    #[serde(rename = "seed_letter")]
    pub student_letter: char,
    /// What the effect looks like.
    pub name: &'static str,
    /// Its paths in Heckbert's notation (light first).
    pub paths: &'static str,
    /// The student's reason that the reconstruction rests on.
    pub evidence: &'static str,
}

/// The reconstructed effects, in table order.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::EFFECTS;
/// use hw3::render::analysis::grammar::Lang;
/// // The student's (d) is two rows; every row's paths parse.
/// assert_eq!(EFFECTS.iter().filter(|e| e.student_letter == 'd').count(), 2);
/// assert!(EFFECTS.iter().all(|e| Lang::parse(e.paths).is_ok()));
/// ```
pub const EFFECTS: [Effect; 6] = [
    Effect {
        id: "a",
        student_letter: 'a',
        name: "specular highlight on a glossy surface",
        paths: "LGE",
        evidence: "radiosity: \"No - only diffuse effects\"; two-pass: \"Yes - through direct lighting calculation\"",
    },
    Effect {
        id: "b",
        student_letter: 'b',
        name: "colour bleeding",
        paths: "LDD+E",
        evidence: "\"effect of light transfer from one diffuse surface to another\"",
    },
    Effect {
        id: "c",
        student_letter: 'c',
        name: "diffuse shading that varies with the surface normal",
        paths: "LDE",
        evidence: "\"diffuse reflection varies w/ surface normal\"",
    },
    Effect {
        id: "d_mirror",
        student_letter: 'd',
        name: "a specular effect: a diffuse object seen in a mirror",
        paths: "LDS+E",
        evidence: "\"this is a specular effect\"; \"rays are only cast from eye, not traced further\"",
    },
    Effect {
        id: "d_caustic",
        student_letter: 'd',
        name: "a specular effect: a caustic (light focused by a mirror or glass onto a diffuse surface)",
        paths: "LS+DE",
        evidence: "\"photon tracing does not capture this specular effect well\"",
    },
    Effect {
        id: "e",
        student_letter: 'e',
        name: "ambient glow (light in regions no light sees directly)",
        paths: "LDD+E",
        evidence: "\"most ambient glow is due to diffuse surface interreflections\"",
    },
];

/// The kind of light the table assumes; it changes which paths exist and which a method samples.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{EFFECTS, LightKind, ALGORITHMS, Verdict, decide};
/// // The path tracer's caustic: impractical with an area light, impossible with a point light.
/// let verdict = |light| decide(&EFFECTS[4], &ALGORITHMS[3], light).unwrap().verdict;
/// assert_eq!((verdict(LightKind::Area), verdict(LightKind::Point)), (Verdict::Impractical, Verdict::No));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LightKind {
    /// An area light (a quad emitter): every path class has positive measure.
    Area,
    /// A point light: paths `LS*E` (the light seen directly or in mirrors) have measure zero, and
    /// a path tracer can reach the light only by a shadow ray from a non-delta vertex.
    Point,
}

impl LightKind {
    /// Both kinds, area first (the student names no light; an area light is the general case).
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::LightKind;
    /// assert_eq!(LightKind::ALL, [LightKind::Area, LightKind::Point]);
    /// ```
    pub const ALL: [LightKind; 2] = [LightKind::Area, LightKind::Point];

    /// Paths that carry energy from this kind of light: all of `L…E` for area lights, those with
    /// a non-delta vertex for point lights.
    fn paths(self) -> &'static str {
        match self {
            LightKind::Area => "L…E",
            LightKind::Point => "L…[DGV]…E",
        }
    }
}

/// A rendering method as two languages: the paths it can produce at all, and the ones it samples
/// efficiently (the rest are "possible but impractical": noise, not missing paths).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::ALGORITHMS;
/// let radiosity = &ALGORITHMS[0];
/// assert_eq!((radiosity.id, radiosity.student_part, radiosity.paths[0]), ("radiosity", Some('a'), "LD*E"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Algorithm {
    /// Column id.
    pub id: &'static str,
    /// Display name.
    pub name: &'static str,
    /// The student's column letter (`Some('a')` = Q5(a) radiosity, `Some('b')` = Q5(b) two-pass).
    #[serde(rename = "seed_part")]
    pub student_part: Option<char>,
    /// Paths the method can produce with an area light / a point light.
    pub paths: [&'static str; 2],
    /// Paths it samples efficiently with an area light / a point light.
    pub efficient: [&'static str; 2],
}

/// The methods (columns): the student's two, then three more.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::ALGORITHMS;
/// // The student's two columns come first.
/// assert_eq!(ALGORITHMS.map(|m| m.student_part)[..3], [Some('a'), Some('b'), None]);
/// ```
pub const ALGORITHMS: [Algorithm; 5] = [
    Algorithm {
        id: "radiosity",
        name: "radiosity",
        student_part: Some('a'),
        paths: ["LD*E", "LD*E"],
        efficient: ["LD*E", "LD*E"],
    },
    Algorithm {
        // Eye rays stop at the first hit (direct light by shadow rays, L(D|G)E). Photons bounce
        // off diffuse surfaces and through mirrors and glass, and the map read at the eye ray's
        // diffuse hit holds only photons that had already bounced off a diffuse surface: the
        // diffuse transport, which the direct light of the eye pass does not already count.
        id: "two_pass",
        name: "two-pass (eye rays + photon tracing)",
        student_part: Some('b'),
        paths: ["L(D|G)E|L(D|S)*D(D|S)*DE", "L(D|G)E|L(D|S)*D(D|S)*DE"],
        efficient: ["L(D|G)E|L(D|S)*D(D|S)*DE", "L(D|G)E|L(D|S)*D(D|S)*DE"],
    },
    Algorithm {
        id: "whitted",
        name: "Whitted ray tracing",
        student_part: None,
        paths: ["L(D|G)?S*E", "L(D|G)?S*E"],
        efficient: ["L(D|G)?S*E", "L(D|G)?S*E"],
    },
    Algorithm {
        // With an area light a caustic path is found only when a bounce after S happens to hit
        // the light; with a point light never.
        id: "path_tracing",
        name: "path tracing",
        student_part: None,
        paths: ["L(D|G|S)*E", "L(D|G)(D|G|S)*E"],
        efficient: ["LS*E|L(D|G)(D|G|S)*E", "L(D|G)(D|G|S)*E"],
    },
    Algorithm {
        id: "photon_mapping",
        name: "photon mapping (global + caustic map)",
        student_part: None,
        paths: ["L(D|G|S)*E", "L(D|G|S)*E"],
        efficient: ["L(D|G|S)*E", "L(D|G|S)*E"],
    },
];

/// A cell's verdict.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{EFFECTS, LightKind, ALGORITHMS, Verdict, decide};
/// // Radiosity misses the highlight.
/// assert_eq!(decide(&EFFECTS[0], &ALGORITHMS[0], LightKind::Area).unwrap().verdict, Verdict::No);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Every path of the effect is in the method's efficient language.
    Yes,
    /// In the method's language, but some paths only by chance: possible but impractical (noise).
    Impractical,
    /// Some path of the effect is not in the method's language.
    No,
}

impl Verdict {
    /// The word the table prints.
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::Verdict;
    /// assert_eq!([Verdict::Yes, Verdict::Impractical, Verdict::No].map(Verdict::text), ["Yes", "Impractical", "No"]);
    /// ```
    #[must_use]
    pub fn text(self) -> &'static str {
        match self {
            Verdict::Yes => "Yes",
            Verdict::Impractical => "Impractical",
            Verdict::No => "No",
        }
    }
}

/// The student's answer for a cell.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{EFFECTS, ALGORITHMS, StudentAnswer, student_answer};
/// // Q5(b)(d): the student says the two-pass method misses the mirror image.
/// assert_eq!(student_answer(&ALGORITHMS[1], &EFFECTS[3]), StudentAnswer::No);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StudentAnswer {
    /// The student wrote Yes.
    Yes,
    /// The student wrote No.
    No,
    /// The student's answers have no such column.
    NotAsked,
}

impl StudentAnswer {
    /// The word the tables print (`–` for a column the student's answers do not have).
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::StudentAnswer;
    /// assert_eq!((StudentAnswer::Yes.text(), StudentAnswer::NotAsked.text()), ("Yes", "–"));
    /// ```
    #[must_use]
    pub fn text(self) -> &'static str {
        match self {
            StudentAnswer::Yes => "Yes",
            StudentAnswer::No => "No",
            StudentAnswer::NotAsked => "–",
        }
    }
}

/// The student's answers, as transcribed: Q5(a) radiosity a–e, Q5(b) two-pass a–e (the last line of
/// the homework is (b)(e), "Yes - as in (b)").
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{STUDENT_ANSWERS, StudentAnswer};
/// assert_eq!(STUDENT_ANSWERS.len(), 10);
/// assert!(STUDENT_ANSWERS.contains(&('b', 'e', StudentAnswer::Yes)));
/// ```
pub const STUDENT_ANSWERS: [(char, char, StudentAnswer); 10] = [
    ('a', 'a', StudentAnswer::No),
    ('a', 'b', StudentAnswer::Yes),
    ('a', 'c', StudentAnswer::Yes),
    ('a', 'd', StudentAnswer::No),
    ('a', 'e', StudentAnswer::Yes),
    ('b', 'a', StudentAnswer::Yes),
    ('b', 'b', StudentAnswer::Yes),
    ('b', 'c', StudentAnswer::Yes),
    ('b', 'd', StudentAnswer::No),
    ('b', 'e', StudentAnswer::Yes),
];

/// The student's answer for `effect` under `method`.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{EFFECTS, ALGORITHMS, StudentAnswer, student_answer};
/// // Q5(a)(a): the student says radiosity misses the highlight; Whitted is not a column of the student's.
/// assert_eq!(student_answer(&ALGORITHMS[0], &EFFECTS[0]), StudentAnswer::No);
/// assert_eq!(student_answer(&ALGORITHMS[2], &EFFECTS[0]), StudentAnswer::NotAsked);
/// ```
#[must_use]
pub fn student_answer(method: &Algorithm, effect: &Effect) -> StudentAnswer {
    method
        .student_part
        .and_then(|part| {
            STUDENT_ANSWERS.iter().find(|(p, letter, _)| *p == part && *letter == effect.student_letter).map(|c| c.2)
        })
        .unwrap_or(StudentAnswer::NotAsked)
}

/// One cell of the derived table.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{LightKind, Verdict, grammar_table};
/// let cells = grammar_table().unwrap();
/// let first = &cells[0];
/// assert_eq!((first.effect, first.algorithm, first.light), ("a", "radiosity", LightKind::Area));
/// assert_eq!((first.verdict, first.witness.as_deref()), (Verdict::No, Some("LGE")));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Cell {
    /// Effect id (row).
    pub effect: &'static str,
    /// Algorithm id (column).
    // The JSON keeps its published field names (`method`, `seed`), so scripts reading it keep working.
    #[serde(rename = "method")]
    pub algorithm: &'static str,
    /// Light kind.
    pub light: LightKind,
    /// The grammar's verdict.
    pub verdict: Verdict,
    /// For No: the shortest effect path outside the method's language; for Impractical: the
    /// shortest one outside its efficient language.
    pub witness: Option<String>,
    /// The student's answer (area-light table only; `NotAsked` for the point-light table).
    #[serde(rename = "seed")]
    pub student: StudentAnswer,
}

/// Decides one cell: effect ∩ light paths ⊆ efficient → Yes, ⊆ paths → Impractical, else No.
///
/// # Errors
/// [`GrammarError`] if a built-in expression fails to parse or the search overflows (never for
/// the built-in tables; tested).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{EFFECTS, LightKind, ALGORITHMS, Verdict, decide};
/// let caustic = EFFECTS.iter().find(|e| e.id == "d_caustic").unwrap();
/// let path_tracing = ALGORITHMS.iter().find(|m| m.id == "path_tracing").unwrap();
/// let cell = decide(caustic, path_tracing, LightKind::Point).unwrap();
/// assert_eq!((cell.verdict, cell.witness.as_deref()), (Verdict::No, Some("LSDE")));
/// ```
pub fn decide(effect: &Effect, method: &Algorithm, light: LightKind) -> Result<Cell, GrammarError> {
    let column = usize::from(light == LightKind::Point);
    let languages = [
        Lang::parse(effect.paths)?,
        Lang::parse(light.paths())?,
        Lang::parse(method.paths[column])?,
        Lang::parse(method.efficient[column])?,
    ];
    let missing = shortest_word(&languages, |a| a[0] && a[1] && !a[2])?;
    let slow = shortest_word(&languages, |a| a[0] && a[1] && !a[3])?;
    let (verdict, witness) = match (missing, slow) {
        (Some(path), _) => (Verdict::No, Some(path)),
        (None, Some(path)) => (Verdict::Impractical, Some(path)),
        (None, None) => (Verdict::Yes, None),
    };
    let seed = if light == LightKind::Area { student_answer(method, effect) } else { StudentAnswer::NotAsked };
    Ok(Cell {
        effect: effect.id,
        algorithm: method.id,
        light,
        verdict,
        witness: witness.map(|w| word_text(&w)),
        student: seed,
    })
}

/// Every cell: both light kinds × [`EFFECTS`] × [`ALGORITHMS`], in that order.
///
/// # Errors
/// As [`decide`].
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{grammar_table, LightKind, Verdict};
/// let cells = grammar_table().unwrap();
/// let cell = cells.iter().find(|c| c.effect == "a" && c.algorithm == "radiosity" && c.light == LightKind::Area).unwrap();
/// assert_eq!((cell.verdict, cell.witness.as_deref()), (Verdict::No, Some("LGE")));
/// ```
pub fn grammar_table() -> Result<Vec<Cell>, GrammarError> {
    let mut cells = Vec::new();
    for light in LightKind::ALL {
        for effect in &EFFECTS {
            for method in &ALGORITHMS {
                cells.push(decide(effect, method, light)?);
            }
        }
    }
    Ok(cells)
}

/// Whether the grammar's verdict agrees with the student's: Impractical counts as the student's
/// No when the student's reason says "not … well".
pub(super) fn agreement(cell: &Cell) -> &'static str {
    match (cell.student, cell.verdict) {
        (StudentAnswer::Yes, Verdict::Yes) | (StudentAnswer::No, Verdict::No) => "agrees",
        (StudentAnswer::No, Verdict::Impractical) => "agrees (possible but impractical)",
        (StudentAnswer::NotAsked, _) => "",
        _ => "DISAGREES",
    }
}

fn cell_text(cell: &Cell) -> String {
    let seed = match cell.student {
        StudentAnswer::NotAsked => String::new(),
        answer => format!(" (student: {})", answer.text()),
    };
    match &cell.witness {
        Some(w) => format!("{} `{w}`{seed}", cell.verdict.text()),
        None => format!("{}{seed}", cell.verdict.text()),
    }
}

/// The grammar table as markdown, one table per light kind; a No or Impractical cell prints the
/// shortest path the method misses (or samples only by chance) as code, and the student's answer
/// beside it (printed as `(student: …)`).
///
/// # Errors
/// As [`decide`].
///
/// # Examples
/// ```
/// let markdown = hw3::q5_effect_tables::grammar_table_markdown().unwrap();
/// assert!(markdown.starts_with("**Area light**"));
/// assert!(markdown.contains("No `LGE` (student: No)"));
/// ```
pub fn grammar_table_markdown() -> Result<String, GrammarError> {
    let cells = grammar_table()?;
    let mut out = String::new();
    for light in LightKind::ALL {
        let title = match light {
            LightKind::Area => "Area light",
            LightKind::Point => "Point light",
        };
        let header: Vec<&str> = ["effect", "paths"].into_iter().chain(ALGORITHMS.iter().map(|m| m.name)).collect();
        let rows = EFFECTS.iter().map(|effect| {
            let verdicts = ALGORITHMS.iter().map(|method| {
                cells
                    .iter()
                    .find(|c| c.light == light && c.effect == effect.id && c.algorithm == method.id)
                    .map(cell_text)
                    .unwrap_or_default()
            });
            [format!("({}) {}", effect.id.replace('_', " "), effect.name), format!("`{}`", effect.paths)]
                .into_iter()
                .chain(verdicts)
                .collect::<Vec<_>>()
        });
        out.push_str(&format!("**{title}**\n\n{}", markdown_table(&header, rows)));
        out.push('\n');
    }
    Ok(out)
}
