//! The student's pages: every graded part taught where the answer key links it, no answer given
//! away by the template, every term defined at its first use, and no lab diary on the student's
//! path. Each check is a function of the text it reads, so each also has a test that plants the
//! fault it looks for.

use hw3::checker::{Expected, QUESTIONS, variant};
use std::path::Path;

const DOCS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs");

/// The pages a student reads: the index, the chapters, the glossary and how to hand in.
const STUDENT_PAGES: [&str; 9] = [
    "index.md",
    "q1_hard_scenes.md",
    "q2_ray_sphere.md",
    "q3_kd_traversal.md",
    "q4_light_probe.md",
    "q5_effect_tables.md",
    "render.md",
    "glossary.md",
    "hand_in.md",
];

fn page(name: &str) -> String {
    std::fs::read_to_string(Path::new(DOCS).join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A heading's anchor as rustdoc writes it: lower case, white space to `-`, other punctuation
/// dropped.
fn anchor(heading: &str) -> String {
    heading
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            c if c.is_whitespace() => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The level and text of a markdown heading line outside code.
fn heading(line: &str) -> Option<(usize, &str)> {
    let level = line.chars().take_while(|&c| c == '#').count();
    (level > 0 && line[level..].starts_with(' ')).then(|| (level, line[level..].trim()))
}

// ---------------------------------------------------------------------------------------------
// Every graded part has its lesson.

/// The lead-ins every graded part's section has, in this order.
const LEAD_INS: [&str; 4] =
    ["**Asked.**", "**Method.**", "**Worked example.**", "**Mistakes the checker recognises.**"];

/// What is missing for the template's table `table` (`q2a`) in `chapter`: the section whose
/// heading names the part ("Part q2a: …", or "Parts q3d and q3e: …"), its four lead-ins, and the
/// anchor every part of the table must link. Returns the anchor and the gaps found.
fn graded_section(chapter: &str, table: &str) -> (Option<String>, Vec<String>) {
    let lines: Vec<&str> = chapter.lines().collect();
    let mut in_fence = false;
    let mut found = None;
    for (i, line) in lines.iter().enumerate() {
        if line.trim_start().starts_with("```") {
            in_fence = !in_fence;
        }
        let Some((level, text)) = heading(line).filter(|_| !in_fence) else { continue };
        let names_part = (text.starts_with("Part ") || text.starts_with("Parts "))
            && text.split(|c: char| !c.is_alphanumeric()).any(|word| word == table);
        if names_part {
            found = Some((i, level, text));
            break;
        }
    }
    let Some((start, level, text)) = found else {
        return (None, vec![format!("no heading \"Part {table}: ...\"")]);
    };
    let body: Vec<&str> =
        lines[start + 1..].iter().take_while(|l| heading(l).is_none_or(|(other, _)| other > level)).copied().collect();
    let body = body.join("\n");
    let mut gaps = Vec::new();
    let mut at = 0;
    for lead_in in LEAD_INS {
        match body[at..].find(lead_in) {
            Some(i) => at += i + lead_in.len(),
            None => gaps.push(format!("section \"{text}\" lacks {lead_in} (after the ones before it)")),
        }
    }
    (Some(anchor(text)), gaps)
}

/// The template's tables with their parts' links, for seed `seed`.
fn tables(seed: u64) -> Vec<(String, Vec<(&'static str, &'static str)>)> {
    let mut tables: Vec<(String, Vec<(&'static str, &'static str)>)> = Vec::new();
    for question in QUESTIONS {
        for part in variant(question, seed).unwrap().parts {
            let table = part.key.split_once('.').unwrap().0.to_string();
            match tables.iter_mut().find(|(t, _)| *t == table) {
                Some((_, parts)) => parts.push((part.key, part.explained_in)),
                None => tables.push((table, vec![(part.key, part.explained_in)])),
            }
        }
    }
    tables
}

#[test]
fn every_graded_part_is_taught_where_its_link_lands() {
    let mut gaps = Vec::new();
    for seed in [0, 1, 2, 3] {
        for (table, parts) in tables(seed) {
            let (page_path, _) = parts[0].1.split_once('#').unwrap_or((parts[0].1, ""));
            let module = page_path.trim_start_matches("hw3/").trim_end_matches("/index.html");
            let (anchor, missing) = graded_section(&page(&format!("{module}.md")), &table);
            gaps.extend(missing.into_iter().map(|m| format!("{module}.md, {table}: {m}")));
            let Some(anchor) = anchor else { continue };
            for (key, link) in parts {
                let wanted = format!("hw3/{module}/index.html#{anchor}");
                if link != wanted {
                    gaps.push(format!("{key} links {link}, not its section {wanted}"));
                }
            }
        }
    }
    gaps.dedup();
    assert!(gaps.is_empty(), "graded parts without their lesson:\n{}", gaps.join("\n"));
}

#[test]
fn a_missing_lead_in_or_section_is_found() {
    let whole = "# C\n### Part q9x: a thing\n**Asked.** a\n**Method.** b\n**Worked example.** c\n\
                 **Mistakes the checker recognises.** d\n## Next\n";
    assert_eq!(graded_section(whole, "q9x"), (Some("part-q9x-a-thing".into()), vec![]));
    let no_example = whole.replace("**Worked example.**", "");
    assert_eq!(graded_section(&no_example, "q9x").1.len(), 1);
    // A lead-in below the next heading of the same level belongs to another section.
    let moved = whole
        .replace("**Mistakes the checker recognises.** d\n## Next", "## Next\n**Mistakes the checker recognises.**");
    assert_eq!(graded_section(&moved, "q9x").1.len(), 1);
    assert_eq!(graded_section(whole, "q9y").0, None);
    let joint = "### Parts q3d and q3e: traces\n**Asked.** **Method.** **Worked example.** **Mistakes the checker recognises.**";
    assert_eq!(graded_section(joint, "q3e").0.as_deref(), Some("parts-q3d-and-q3e-traces"));
}

// ---------------------------------------------------------------------------------------------
// The template says what is asked and in which form, never the answer.

/// Key formulas and the forms they take in words: none may appear in a template. Compared with
/// the template lower-cased and without white space.
const KEY_FORMULAS: [&str; 34] = [
    // Q1
    "(1-p)^n",
    "e^(-np)",
    "pia^2",
    "e^(-sigma_t",
    "exp(-sigma",
    "ln(50)",
    "ln50",
    "2delta/r",
    "2step/r",
    "2*step/r",
    "tan(fov/2)",
    "(h/2)/tan",
    "v/fps",
    // Q2
    "-(e-o).d",
    "-(e-o)*d",
    "/|d|^2",
    "(p-o)/r",
    "d^-2(n.d^)n",
    "dhat-2",
    "2(n.d",
    "b^2-4ac",
    "-b/2a",
    "(-b-sqrt",
    // Q3
    "(3-e_x)/d_x",
    "(1-e_y)/d_y",
    "(s-e_a)/d_a",
    // Q4
    "arcsin(r/d)",
    "asin(r/d)",
    "sumoflmax(0,n.w)dw",
    "lmax(0,n.w)dw",
    "4piminus",
    "(4pi/n)",
    "4pi/n",
    "sin^2",
];

/// Every key formula (from the list above, and each formula part's own key) and every
/// non-integer key number (to three and four significant digits) that `template` shows.
fn leaks(template: &str, seed: u64) -> Vec<String> {
    let squeezed: String = template.to_lowercase().chars().filter(|c| !c.is_whitespace()).collect();
    let mut found: Vec<String> = KEY_FORMULAS.iter().filter(|f| squeezed.contains(*f)).map(|f| f.to_string()).collect();
    for question in QUESTIONS {
        for part in variant(question, seed).unwrap().parts {
            let key = match &part.expected {
                Expected::OrNone { value, none: false } => value.as_ref(),
                other => other,
            };
            match key {
                Expected::Formula { source, .. } => {
                    let source: String = source.to_lowercase().chars().filter(|c| !c.is_whitespace()).collect();
                    if squeezed.contains(&source) {
                        found.push(format!("{}: {source}", part.key));
                    }
                }
                Expected::Number { value, .. } if value.fract() != 0.0 && value.is_finite() => {
                    for digits in [3, 4] {
                        let shown = format!("{:.*}", digits_after_point(*value, digits), value);
                        if contains_number(template, &shown) {
                            found.push(format!("{}: {shown}", part.key));
                        }
                    }
                }
                _ => {}
            }
        }
    }
    found
}

/// Digits after the decimal point that show `value` to `significant` figures.
fn digits_after_point(value: f64, significant: i32) -> usize {
    let magnitude = value.abs().log10().floor() as i32;
    (significant - 1 - magnitude).max(0) as usize
}

/// `number` as a whole number in `text` (not the start of a longer one).
fn contains_number(text: &str, number: &str) -> bool {
    text.match_indices(number).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + number.len()..].chars().next();
        let digit = |c: Option<char>| c.is_some_and(|c| c.is_ascii_digit() || c == '.');
        !digit(before) && !digit(after)
    })
}

#[test]
fn the_template_never_shows_a_key_formula_or_value() {
    for seed in 0..16 {
        let template = hw3::checker::template(seed).unwrap();
        let found = leaks(&template, seed);
        assert!(found.is_empty(), "seed {seed}: the template gives away:\n{}", found.join("\n"));
    }
}

#[test]
fn a_planted_formula_or_value_is_found() {
    let template = hw3::checker::template(0).unwrap();
    let planted = template.replace("# visual_range = ", "# visual range ln(50)/sigma_t\n# visual_range = ");
    assert_eq!(leaks(&planted, 0), ["ln(50)"]);
    let planted = template.replace("[q2c]", "[q2c]\n# t = 3.268");
    assert_eq!(leaks(&planted, 0), ["q2a.t: 3.268"]);
    let planted = template.replace("[q2a]", "[q2a]\n# A = dot(d, d)");
    assert_eq!(leaks(&planted, 0), ["q2a.A: dot(d,d)"]);
}

// ---------------------------------------------------------------------------------------------
// Every term defined at its first use.

/// The chapters' technical terms, each with the glossary entry (its anchor) that defines it and
/// the spellings it goes by. The first use of a spelling on a student page is a link to the entry.
const TERMS: [(&str, &[&str]); 61] = [
    ("airlight", &["airlight"]),
    ("albedo", &["albedo"]),
    ("antialiasing", &["antialiasing", "antialiased"]),
    ("beerlambert-law", &["Beer–Lambert", "Beer-Lambert"]),
    ("bias-and-variance", &["unbiased", "biased"]),
    ("bilinear-interpolation", &["bilinear", "bilinearly"]),
    ("boolean-model", &["Boolean model"]),
    ("brdf", &["BRDF"]),
    ("bsdf", &["BSDF"]),
    ("bvh", &["BVH", "BVHs"]),
    ("cache", &["cache", "caches", "cache line"]),
    ("cancellation", &["cancellation", "cancels"]),
    ("caustic", &["caustic", "caustics"]),
    ("caustic-map", &["caustic map"]),
    ("chaotic-scattering", &["chaotic scattering"]),
    ("colour-bleeding", &["colour bleeding"]),
    ("depth-complexity", &["depth complexity"]),
    ("diffuse-glossy-and-specular", &["Lambertian", "glossy", "specular"]),
    ("display-level", &["display level", "display levels"]),
    ("double-double-arithmetic", &["double-double"]),
    ("environment-map", &["environment map", "latitude-longitude"]),
    ("equiangular-sampling", &["equiangular"]),
    ("extinction-coefficient", &["extinction coefficient"]),
    ("field-of-view", &["field of view", "focal length"]),
    ("final-gather", &["final gather"]),
    ("fireflies", &["firefly", "fireflies"]),
    ("floating-point-f32-and-f64", &["f32", "f64", "significand", "floating point"]),
    ("form-factor", &["form factor", "form factors"]),
    ("fresnel-reflectance", &["Fresnel"]),
    ("furnace-test", &["furnace"]),
    ("gausslegendre-quadrature", &["Gauss–Legendre"]),
    ("heckberts-path-notation", &["Heckbert's"]),
    ("importance-sampling", &["importance sampling", "cosine-weighted", "cosine-distributed"]),
    ("irradiance", &["irradiance"]),
    ("jacobian", &["Jacobian"]),
    ("kd-tree", &["kd-tree", "kd-trees"]),
    ("k-nearest-neighbours", &["kNN", "nearest neighbours", "nearest photons"]),
    ("koschmieders-visual-range", &["Koschmieder", "Koschmieder's"]),
    ("lambert-equal-area-projection", &["equal-area"]),
    ("light-probe", &["light probe"]),
    ("luminance", &["luminance"]),
    ("mean-free-path", &["mean free path"]),
    ("mis", &["MIS"]),
    ("monte-carlo-integration", &["Monte Carlo"]),
    ("motion-blur", &["motion blur"]),
    ("next-event-estimation", &["next-event"]),
    ("oracle", &["oracle", "oracles"]),
    ("path-tracing", &["path tracing", "path tracer"]),
    ("pdf", &["pdf", "pdfs"]),
    ("phase-function", &["phase function"]),
    ("photon-mapping", &["photon mapping", "photon map"]),
    ("radiance", &["radiance"]),
    ("radiosity", &["radiosity"]),
    ("regular-language", &["regular language", "regular languages", "grammar"]),
    ("russian-roulette", &["Russian roulette"]),
    ("samples-per-pixel-spp", &["spp", "samples per pixel"]),
    ("snells-law", &["Snell", "Snell's"]),
    ("solid-angle", &["solid angle", "solid angles"]),
    ("spherical-harmonics", &["spherical harmonics", "spherical-harmonic"]),
    ("terminator", &["terminator"]),
    ("tone-mapping", &["tone-mapped", "tone mapping", "tone-map"]),
];

/// Text a reader reads of a page, line by line: fenced code, headings and include lines are
/// left out (a heading cannot carry a link; included tables are generated); figure captions stay
/// in (they are plain text, so a term must be defined before its caption).
fn prose_lines(page: &str) -> Vec<(usize, &str)> {
    let mut in_fence = false;
    let mut lines = Vec::new();
    for (number, line) in page.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            in_fence = !in_fence;
            continue;
        }
        if in_fence || heading(line).is_some() || line.trim_start().starts_with("{{include:") {
            continue;
        }
        lines.push((number + 1, line));
    }
    lines
}

/// Byte ranges of `[text](crate::notes::glossary#anchor)` link texts in `line`, with their anchors.
fn glossary_links(line: &str) -> Vec<(std::ops::Range<usize>, &str)> {
    let marker = "](crate::notes::glossary#";
    let mut links = Vec::new();
    for (close, _) in line.match_indices(marker) {
        let Some(open) = line[..close].rfind('[') else { continue };
        let rest = &line[close + marker.len()..];
        let anchor = rest.split(')').next().unwrap_or("");
        links.push((open..close, anchor));
    }
    links
}

/// `line` with the destinations of links (`](…)`) and code paths (`` `a::b` ``) blanked out,
/// byte for byte: a path such as `crate::envmap::radiance` is not a use of a term.
fn masked(line: &str) -> String {
    let mut bytes = line.as_bytes().to_vec();
    let mut blank = |from: usize, to: usize| {
        for b in &mut bytes[from..to] {
            if b.is_ascii() {
                *b = b' ';
            }
        }
    };
    for (start, _) in line.match_indices("](") {
        let end = line[start..].find(')').map_or(line.len(), |e| start + e);
        blank(start, end);
    }
    let ticks: Vec<usize> = line.match_indices('`').map(|(i, _)| i).collect();
    for pair in ticks.chunks(2) {
        if let [open, close] = *pair
            && line[open..close].contains("::")
        {
            blank(open, close);
        }
    }
    String::from_utf8(bytes).expect("only ASCII bytes were replaced")
}

/// Offsets where `spelling` occurs in `line` as a whole word (case-insensitive, except for
/// spellings with two capitals or more, so that `MIS` is not the start of "mis-").
fn occurrences(line: &str, spelling: &str) -> Vec<usize> {
    let exact = spelling.chars().filter(|c| c.is_uppercase()).count() > 1;
    let line = masked(line);
    let (hay, needle) =
        if exact { (line, spelling.to_string()) } else { (line.to_lowercase(), spelling.to_lowercase()) };
    let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '-');
    hay.match_indices(&needle)
        .filter(|(i, _)| {
            let before = hay[..*i].chars().next_back();
            let after = hay[i + needle.len()..].chars().next();
            !word(before) && !word(after)
        })
        .map(|(i, _)| i)
        .collect()
}

/// Every term whose first use on `page` is not a link to its glossary entry.
fn unlinked_first_uses(name: &str, page: &str) -> Vec<String> {
    let mut found = Vec::new();
    let lines = prose_lines(page);
    for (entry, spellings) in TERMS {
        let first = lines.iter().find_map(|(number, line)| {
            let at = spellings.iter().flat_map(|s| occurrences(line, s)).min()?;
            Some((*number, *line, at))
        });
        let Some((number, line, at)) = first else { continue };
        let linked = glossary_links(line).iter().any(|(range, anchor)| range.contains(&at) && *anchor == entry);
        if !linked {
            let shown: String = line.chars().take(110).collect();
            found
                .push(format!("{name}:{number}: first use of \"{}\" is not linked to #{entry}: {shown}", spellings[0]));
        }
    }
    found
}

#[test]
fn every_term_is_linked_to_the_glossary_at_its_first_use() {
    let glossary = page("glossary.md");
    let entries: Vec<String> = glossary.lines().filter_map(|l| l.strip_prefix("## ")).map(anchor).collect();
    let undefined: Vec<&str> = TERMS.iter().map(|(e, _)| *e).filter(|e| !entries.iter().any(|a| a == e)).collect();
    assert!(undefined.is_empty(), "the glossary has no entry for: {undefined:?}");
    let found: Vec<String> = STUDENT_PAGES
        .iter()
        .filter(|name| **name != "glossary.md")
        .flat_map(|name| unlinked_first_uses(name, &page(name)))
        .collect();
    assert!(found.is_empty(), "{} terms used before they are defined:\n{}", found.len(), found.join("\n"));
}

#[test]
fn an_unlinked_first_use_is_found() {
    let linked = "A [solid angle](crate::notes::glossary#solid-angle) is an area; every solid angle adds up.";
    assert!(unlinked_first_uses("x", linked).is_empty());
    let unlinked = "Every solid angle adds up; a [solid angle](crate::notes::glossary#solid-angle) is an area.";
    assert_eq!(unlinked_first_uses("x", unlinked).len(), 1);
    let wrong_entry = "A [solid angle](crate::notes::glossary#radiance) is an area.";
    assert_eq!(unlinked_first_uses("x", wrong_entry).len(), 1);
    assert!(unlinked_first_uses("x", "## A solid angle\nno term here").is_empty(), "headings are skipped");
    assert!(unlinked_first_uses("x", "misses the MIS- prefix").is_empty(), "a capitalised term matches exactly");
    assert!(
        unlinked_first_uses("x", "see [`radiance`](crate::envmap::radiance) and `crate::envmap::radiance`").len() == 1
    );
    assert!(
        unlinked_first_uses("x", "the module `crate::envmap::radiance` and [the sky](crate::envmap::radiance)")
            .is_empty()
    );
}

// ---------------------------------------------------------------------------------------------
// The student's pages say what is true now, not how it was measured.

/// Words that mark a line of a lab diary: machines, loads, runs, tries and clock time.
const DIARY_WORDS: [&str; 41] = [
    "machine",
    "machines",
    "load",
    "loads",
    "cores",
    "2-core",
    "two-core",
    "processor",
    "processors",
    "cpu",
    "avx",
    "avx2",
    "avx-512",
    "sse2",
    "zen",
    "embree",
    "tried",
    "not kept",
    "did not help",
    "seconds",
    "millisecond",
    "milliseconds",
    "microsecond",
    "microseconds",
    "mrays",
    "run-to-run",
    "run to run",
    "this run",
    "that run",
    "one run",
    "two runs",
    "three runs",
    "each run",
    "other runs",
    "earlier runs",
    "later runs",
    "the run",
    "wall time",
    "wall-clock",
    "timings",
    "timed",
];

/// Whether `line` reads like a lab diary: a diary word (whole word, case-insensitive), a clock
/// time in seconds (`5 s`, `3.2 ms`, `80 µs`, `13 ns`), a memory size (`1.9 MB`), a date or a
/// numbered step.
fn diary_like(line: &str) -> bool {
    let lower = line.to_lowercase();
    let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '-' || c == '_');
    let has = |needle: &str| {
        lower
            .match_indices(needle)
            .any(|(i, _)| !word(lower[..i].chars().next_back()) && !word(lower[i + needle.len()..].chars().next()))
    };
    if DIARY_WORDS.iter().any(|w| has(w)) {
        return true;
    }
    let chars: Vec<char> = lower.chars().collect();
    for (i, c) in chars.iter().enumerate() {
        if !c.is_ascii_digit() || chars.get(i + 1).is_some_and(|n| n.is_ascii_digit() || *n == '.') {
            continue;
        }
        // A number ends at i: is it followed by a unit of time?
        let rest: String = chars[i + 1..].iter().collect();
        let rest = rest.strip_prefix(' ').unwrap_or(&rest);
        for unit in ["s", "ms", "µs", "μs", "ns", "kb", "mb", "mib", "gb"] {
            if rest.starts_with(unit) && !rest[unit.len()..].chars().next().is_some_and(char::is_alphanumeric) {
                return true;
            }
        }
    }
    let bytes = lower.as_bytes();
    let date = bytes.windows(10).any(|w| {
        w[0..2] == *b"20" && w[4] == b'-' && w[7] == b'-' && [2, 3, 5, 6, 8, 9].iter().all(|&k| w[k].is_ascii_digit())
    });
    date || lower.split("step ").skip(1).any(|r| r.starts_with(|c: char| c.is_ascii_digit()))
}

/// Method of the count: the lines of the student pages' markdown sources (included tables are
/// generated data, not prose) that [`diary_like`] flags.
fn diary_lines() -> Vec<String> {
    STUDENT_PAGES
        .iter()
        .flat_map(|name| {
            page(name)
                .lines()
                .enumerate()
                .filter(|(_, line)| diary_like(line))
                .map(|(i, line)| format!("{name}:{}: {}", i + 1, line.chars().take(100).collect::<String>()))
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn the_student_pages_keep_no_lab_diary() {
    let lines = diary_lines();
    assert!(lines.len() <= 20, "{} diary-like lines (at most 20):\n{}", lines.len(), lines.join("\n"));
}

#[test]
fn diary_lines_are_recognised() {
    for line in [
        "on a shared 2-core machine",
        "took 5 s to render",
        "the same in two runs",
        "12.9 ns per normal",
        "measured on 2026-12-05",
        "what was tried and not kept",
        "step 24 made it faster",
        "1 MB of second-level cache",
    ] {
        assert!(diary_like(line), "{line}");
    }
    for line in ["the ray's parameter s", "the samples per pixel", "a path runs from the light", "2 spp"] {
        assert!(!diary_like(line), "{line}");
    }
}

// ---------------------------------------------------------------------------------------------
// The student's pages hold lessons, not keys.

/// What belongs to the grader's pages only: the worked solutions and keys of variants, and how
/// variants are drawn.
const GRADERS_ONLY: [&str; 8] =
    ["hw3 solution", "hw3 variant", "notes::answer_key", "answer_key", "mod 6", "mod 3", "seed −", "seed -"];

#[test]
fn the_student_pages_show_no_key_and_no_variant_design() {
    let mut found = Vec::new();
    for name in STUDENT_PAGES {
        for (number, line) in page(name).lines().enumerate() {
            for marker in GRADERS_ONLY {
                if line.contains(marker) {
                    found.push(format!("{name}:{}: \"{marker}\"", number + 1));
                }
            }
        }
    }
    assert!(found.is_empty(), "the grader's pages hold these:\n{}", found.join("\n"));
}

// ---------------------------------------------------------------------------------------------
// The student pages' links to a chapter's section land on a heading of that chapter.

/// The `(qN_…/index.html#anchor)` and `(crate::qN_…#anchor)` links of `text` whose chapter has
/// no heading with that anchor.
fn dangling_section_links(text: &str) -> Vec<String> {
    let mut dangling = Vec::new();
    for (marker, end) in [("/index.html#", ')'), ("#", ')')] {
        for (at, _) in text.match_indices(marker) {
            let before = &text[..at];
            let start = before.rfind('(').map_or(0, |i| i + 1);
            let target = &before[start..];
            let module = target.trim_start_matches("crate::");
            let is_chapter = module.starts_with('q') && module.as_bytes().get(2) == Some(&b'_') || module == "render";
            if !is_chapter || (marker == "#" && target.contains('/')) {
                continue;
            }
            let wanted = text[at + marker.len()..].split(end).next().unwrap_or("");
            let Ok(chapter) = std::fs::read_to_string(Path::new(DOCS).join(format!("{module}.md"))) else {
                dangling.push(format!("{module}: no such chapter"));
                continue;
            };
            let headings: Vec<String> = chapter.lines().filter_map(heading).map(|(_, t)| anchor(t)).collect();
            if !headings.iter().any(|h| h == wanted) {
                dangling.push(format!("{module}#{wanted}"));
            }
        }
    }
    dangling
}

#[test]
fn links_to_a_chapters_section_land_on_a_heading() {
    let dangling: Vec<String> = STUDENT_PAGES
        .iter()
        .flat_map(|name| dangling_section_links(&page(name)).into_iter().map(move |d| format!("{name}: {d}")))
        .collect();
    assert!(dangling.is_empty(), "links to no heading:\n{}", dangling.join("\n"));
}

#[test]
fn a_dangling_section_link_is_found() {
    let text = "[x](q2_ray_sphere/index.html#no-such-section) and [y](crate::q3_kd_traversal#the-answer)";
    assert_eq!(dangling_section_links(text), ["q2_ray_sphere#no-such-section"]);
}
