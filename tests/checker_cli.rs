//! `hw3 check`, `hw3 template` and `hw3 variant` as a student or grader uses them.

use crate::common;

use std::process::{Command, Output};

fn hw3(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hw3")).args(args).output().expect("the hw3 binary runs")
}

fn answers(name: &str) -> String {
    format!("{}/tests/answers/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn wrong_answers_get_per_part_feedback_and_exit_1() {
    let out = hw3(&["check", &answers("q2_wrong.toml")]);
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("that is the larger root"), "{text}");
    assert!(text.contains("sign error"), "{text}");
    // The misspelt `t_closet` is close to one unanswered part only: graded there, with a warning.
    assert!(text.contains("! graded `q2c.t_closest` for `q2c.t_closet`"), "{text}");
    assert!(text.contains("the factor 2 is missing: B = 2 (e - o) . d"), "{text}");
    assert!(text.contains("|d| for |d|^2"), "{text}");
    assert!(text.contains("the key says outside"), "{text}");
    common::insta_settings().bind(|| insta::assert_snapshot!("checker_feedback_wrong", text));
}

#[test]
fn template_then_key_round_trip() {
    let dir = std::env::temp_dir().join(format!("hw3-checker-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let blank = dir.join("blank.toml");
    let out = hw3(&["template", "--seed", "9"]);
    assert!(out.status.success());
    std::fs::write(&blank, &out.stdout).unwrap();
    let graded = hw3(&["check", blank.to_str().unwrap(), "--format", "json"]);
    assert_eq!(graded.status.code(), Some(1), "a blank file is not all correct");
    let report: serde_json::Value = serde_json::from_slice(&graded.stdout).unwrap();
    assert_eq!(report["seed"], 9);
    assert_eq!(report["score"], 0.0);
    let key = dir.join("key.toml");
    std::fs::write(&key, hw3::checker::answer_key(9).unwrap()).unwrap();
    let perfect = hw3(&["check", key.to_str().unwrap(), "--format", "gradescope"]);
    assert_eq!(perfect.status.code(), Some(0));
    let results: serde_json::Value = serde_json::from_slice(&perfect.stdout).unwrap();
    let available: f64 = results["tests"].as_array().unwrap().iter().map(|t| t["max_score"].as_f64().unwrap()).sum();
    assert_eq!(results["score"], available);
    assert!(results["tests"].as_array().unwrap().iter().all(|t| t["status"] == "passed"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn unreadable_files_exit_2_with_one_line() {
    let dir = std::env::temp_dir().join(format!("hw3-checker-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in
        [("syntax.toml", "[q2a\nt = 1"), ("type.toml", "[q2a]\nt = \"x\""), ("nan.toml", "[q2a]\nt = nan")]
    {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let out = hw3(&["check", path.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{name}");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(stderr.trim_end().lines().count(), 1, "{name}: {stderr}");
        assert!(out.stdout.is_empty());
    }
    assert_eq!(hw3(&["check", "/no/such/file.toml"]).status.code(), Some(2));
    assert_eq!(hw3(&["variant", "--question", "q9"]).status.code(), Some(2));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn variant_prints_statement_and_solution() {
    let out = hw3(&["variant", "--question", "q2", "--seed", "1"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("e = (-5, -5, 2)") && text.contains("t_closest = 0.5555"), "{text}");
}

#[test]
fn the_students_own_answers_graded() {
    let out = hw3(&["check", &answers("seed_hw3.toml")]);
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8(out.stdout).unwrap();
    // Q3 (d): the second leaf's tmin is the y = 3 crossing (t = 3), not the x = 3 crossing (t = 2).
    assert!(text.contains("t = 3 is where the ray crosses y = 3, not where it enters this cell"), "{text}");
    let line =
        |key: &str| text.lines().find(|l| l.contains(key)).unwrap_or_default().split_whitespace().collect::<Vec<_>>();
    // Its leaves follow from its own descents: the erratum is charged once, in q3d.descents.
    assert_eq!(line("q3d.leaves")[2..], ["3.00/3", "correct"], "{text}");
    assert_eq!(line("q3d.descents")[2..], ["1.13/1.5", "partial"], "{text}");
    assert_eq!(line("q3e.leaves")[2..], ["2.00/2", "correct"], "{text}");
    // The chapter quotes this score; it must be the one the checker prints.
    let score = text.lines().last().unwrap().trim_start_matches("score ").split(" over").next().unwrap();
    let chapter = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/checker.md")).unwrap();
    assert!(chapter.contains(&format!("**{score}**")), "docs/checker.md should quote the student's score {score}");
    common::insta_settings().bind(|| insta::assert_snapshot!("checker_seed_graded", text));
}

/// One variant per case of each question, worked outside the crate
/// (`tests/answers/fixtures/keys.py`, output committed as `keys.json`): the checker's key agrees.
#[test]
fn keys_agree_with_the_independent_script() {
    use hw3::checker::Expected;
    let text = std::fs::read_to_string(answers("fixtures/keys.json")).unwrap();
    let cases: Vec<serde_json::Value> = serde_json::from_str(&text).unwrap();
    let close = |a: f64, b: f64, rel: f64| (a - b).abs() <= rel * b.abs().max(1.0);
    let mut checked = 0;
    for case in &cases {
        let question = case["question"].as_str().unwrap();
        let seed = case["seed"].as_u64().unwrap();
        let variant = hw3::checker::variant(question, seed).unwrap();
        let what = format!("{question} seed {seed} ({})", case["case"]);
        assert!(variant.statement.contains(case["statement"].as_str().unwrap()), "{what}: {}", variant.statement);
        // The quadrature of Q4 is good to about 1e-6; everything else is the same arithmetic.
        let rel = if question == "q4" { 1e-5 } else { 1e-9 };
        let rel = if question == "q1" { 1e-12 } else { rel };
        for (key, want) in case["key"].as_object().unwrap() {
            let part = variant.parts.iter().find(|p| p.key == key).unwrap_or_else(|| panic!("{what}: no part {key}"));
            let expected = match &part.expected {
                Expected::OrNone { value, none: false } => value.as_ref(),
                other => other,
            };
            match expected {
                Expected::Number { value, .. } => {
                    assert!(close(*value, want.as_f64().unwrap(), rel), "{what} {key}: {value} vs {want}")
                }
                Expected::Vector { value, .. } | Expected::Direction { value, .. } => {
                    for (v, w) in value.iter().zip(want.as_array().unwrap()) {
                        assert!(close(*v, w.as_f64().unwrap(), rel), "{what} {key}: {value:?} vs {want}");
                    }
                }
                Expected::Choice { value, .. } => assert_eq!(*value, want.as_str().unwrap(), "{what} {key}"),
                Expected::Flag { value } => assert_eq!(*value, want.as_bool().unwrap(), "{what} {key}"),
                Expected::Trace { leaves, .. } => {
                    let want = want.as_array().unwrap();
                    assert_eq!(leaves.len(), want.len(), "{what} {key}: {leaves:?} vs {want:?}");
                    for (leaf, w) in leaves.iter().zip(want) {
                        let path: Vec<&str> =
                            w["path"].as_array().unwrap().iter().map(|p| p.as_str().unwrap()).collect();
                        assert_eq!(leaf.path, path, "{what} {key}");
                        let bound = |v: &serde_json::Value| v.as_f64().unwrap_or(f64::INFINITY);
                        assert!(close(leaf.t_min, bound(&w["tmin"]), rel), "{what} {key}: {leaf:?} vs {w}");
                        assert!(
                            leaf.t_max == bound(&w["tmax"]) || close(leaf.t_max, bound(&w["tmax"]), rel),
                            "{what} {key}: {leaf:?} vs {w}"
                        );
                    }
                }
                other => panic!("{what} {key}: the script has no value for {other:?}"),
            }
            checked += 1;
        }
        if question == "q2" {
            // A ray that misses has no t to give ("none"): the script and the checker agree on which.
            let t = variant.parts.iter().find(|p| p.key == "q2a.t").unwrap();
            let asked = matches!(t.expected, Expected::OrNone { none: false, .. });
            assert_eq!(asked, case["key"].get("q2a.t").is_some(), "{what}");
        }
    }
    // Two Q1 variants, seven Q2 cases (the worked example and one seed per case), five Q3 rays,
    // three Q4 skies and two Q4 probe images (5 × 5 and 4 × 4).
    assert_eq!(cases.len(), 19);
    assert_eq!(checked, 87, "values compared");
}

/// A file answering "none" everywhere earns exactly the parts whose key is "none" (a ray that
/// misses has no t; a table cell that captures an effect misses no paths), and every other part
/// is graded wrong with a reason, not refused as unreadable.
#[test]
fn answering_none_everywhere_scores_only_the_parts_with_no_value() {
    use hw3::checker::{Expected, QUESTIONS, check, variant};
    for seed in 0..12 {
        let variants: Vec<_> = QUESTIONS.iter().map(|q| variant(q, seed).unwrap()).collect();
        let mut file = format!("[meta]\nseed = {seed}\n");
        let mut table = "";
        let mut none_points = 0.0;
        for part in variants.iter().flat_map(|v| &v.parts) {
            let (section, name) = part.key.split_once('.').unwrap();
            if section != table {
                file.push_str(&format!("[{section}]\n"));
                table = section;
            }
            file.push_str(&format!("{name} = \"none\"\n"));
            if matches!(&part.expected, Expected::OrNone { none: true, .. })
                || matches!(&part.expected, Expected::Paths { value } if value == "none")
            {
                none_points += part.points;
            }
        }
        let report = check(&file, None).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        assert!((report.score - none_points).abs() < 1e-9, "seed {seed}: {} vs {none_points}", report.score);
        for part in &report.parts {
            assert_ne!(part.status, "missing", "seed {seed} {}", part.key);
            if part.status != "correct" {
                assert!(!part.feedback.is_empty() && part.feedback != "answer has the wrong shape", "{}", part.key);
            }
        }
        let numbers = report.parts.iter().find(|p| p.key == "q4c.weighted_sum").unwrap();
        assert!(numbers.feedback.contains("accepted only where the template offers it"), "{}", numbers.feedback);
    }
}

/// The demo class of `tests/answers/class/`: 54 submissions made from the checker's own key, so
/// that each is known to be right or to carry one named error.
mod class_demo {
    use hw3::checker::{Expected, MalRule, answer_key, variant};

    /// One submission: its file name and its bytes (an unreadable one need not be UTF-8).
    pub struct Submission {
        pub name: String,
        pub bytes: Vec<u8>,
    }

    /// Files written so, and graded as: right, one recognised mistake, an early error carried
    /// forward, a question left out, or not gradable at all.
    pub const CLASS: usize = 54;
    pub const CARRIED: usize = 4;
    pub const INCOMPLETE: usize = 2;
    pub const UNREADABLE: usize = 5;

    /// The right files: the rest of the class.
    pub fn right() -> usize {
        CLASS - CARRIED - INCOMPLETE - UNREADABLE - mistake_files().len()
    }

    /// The id the class report gives a recognised mistake.
    pub fn rule_id(rule: &MalRule) -> &'static str {
        rule.rule.id()
    }

    /// A wrong answer as the file writes it; `None` for kinds no mal-rule uses.
    fn toml_of(expected: &Expected) -> Option<toml::Value> {
        let floats = |v: &[f64]| toml::Value::Array(v.iter().map(|&x| toml::Value::Float(x)).collect());
        Some(match expected {
            Expected::Number { value, .. } => toml::Value::Float(*value),
            Expected::Vector { value, .. } | Expected::Direction { value, .. } => floats(value),
            // Any length along the direction: twice the unit vector, so it is not the key's.
            Expected::Parallel { value, .. } => floats(&value.map(|x| 2.0 * x)),
            Expected::Formula { source, .. } => toml::Value::String((*source).into()),
            Expected::Choice { value, .. } => toml::Value::String((*value).into()),
            Expected::Paths { value } => toml::Value::String(value.clone()),
            Expected::Flag { value } => toml::Value::Boolean(*value),
            Expected::OrNone { none: true, .. } => toml::Value::String("none".into()),
            Expected::OrNone { value, none: false } => return toml_of(value),
            Expected::Trace { .. } | Expected::Planes { .. } => return None,
        })
    }

    fn key_table(seed: u64) -> toml::Table {
        toml::from_str(&answer_key(seed).unwrap()).unwrap()
    }

    fn set(file: &mut toml::Table, key: &str, value: toml::Value) {
        let (section, name) = key.split_once('.').unwrap();
        file.get_mut(section).and_then(toml::Value::as_table_mut).unwrap().insert(name.into(), value);
    }

    fn vector(v: [f64; 3]) -> toml::Value {
        toml::Value::Array(v.iter().map(|&x| toml::Value::Float(x)).collect())
    }

    fn written(about: &str, file: &toml::Table) -> Vec<u8> {
        format!("# {about}\n{}", toml::to_string(file).unwrap()).into_bytes()
    }

    /// The variants whose mistakes the class makes: seed 0 and one of each Q2 case (seeds 1 to 6:
    /// outside, inside, behind, tangent, miss, on the surface), which have mistakes of their own.
    const MISTAKE_SEEDS: std::ops::RangeInclusive<u64> = 0..=6;

    /// Mistakes packed into one file: at most this many, each in a different part.
    const MISTAKES_PER_FILE: usize = 3;

    /// One recognised mistake: the variant, the part's key and the rule.
    #[derive(Debug, Clone)]
    pub struct Mistake {
        pub seed: u64,
        pub key: &'static str,
        pub rule: MalRule,
    }

    /// Every recognised mistake of the variants [`MISTAKE_SEEDS`], once per part and message, in
    /// variant and question order: each rule whose wrong value, written alone into the variant's
    /// key, is graded as that rule (a value the key also accepts, or that an earlier rule of the
    /// part already names, is not a mistake of its own).
    pub fn mistakes() -> Vec<Mistake> {
        let mut out: Vec<Mistake> = Vec::new();
        for seed in MISTAKE_SEEDS {
            for question in hw3::checker::QUESTIONS {
                for part in variant(question, seed).unwrap().parts {
                    for rule in &part.mal_rules {
                        let seen = out.iter().any(|m| m.key == part.key && m.rule.message == rule.message);
                        let Some(value) = toml_of(&rule.value).filter(|_| !seen) else { continue };
                        let mut file = key_table(seed);
                        set(&mut file, part.key, value);
                        let report = hw3::checker::check(&toml::to_string(&file).unwrap(), None).unwrap();
                        let graded = report.parts.iter().find(|p| p.key == part.key).unwrap();
                        if graded.status != "correct" && graded.mistake == Some(rule_id(rule)) {
                            out.push(Mistake { seed, key: part.key, rule: rule.clone() });
                        }
                    }
                }
            }
        }
        out
    }

    /// The mistakes packed [`MISTAKES_PER_FILE`] to a file, each file one variant's and its
    /// mistakes in different parts, to leave room for right files in a class of 54.
    pub fn mistake_files() -> Vec<Vec<Mistake>> {
        let mut files: Vec<Vec<Mistake>> = Vec::new();
        for mistake in mistakes() {
            let room = files.iter_mut().find(|f| {
                f.len() < MISTAKES_PER_FILE && f[0].seed == mistake.seed && f.iter().all(|m| m.key != mistake.key)
            });
            match room {
                Some(file) => file.push(mistake),
                None => files.push(vec![mistake]),
            }
        }
        files
    }

    /// Q2's worked example (seed 0: e = (-5, 1, 0), d = (1, 0, 0), o = 0, r = 2) answered from a
    /// wrong t: the point, normal and reflection that follow from it.
    fn q2_from_t(file: &mut toml::Table, t: f64, r: f64) {
        let point = [-5.0 + t, 1.0, 0.0];
        let normal = point.map(|x| x / r);
        let length = normal.iter().map(|x| x * x).sum::<f64>().sqrt();
        let n = normal.map(|x| x / length);
        // d = (1, 0, 0) is unit: r = d - 2 (n·d) n.
        let reflected = [1.0 - 2.0 * n[0] * n[0], -2.0 * n[0] * n[1], -2.0 * n[0] * n[2]];
        set(file, "q2a.t", toml::Value::Float(t));
        set(file, "q2a.point", vector(point));
        set(file, "q2b.normal", vector(n));
        set(file, "q2b.reflected_dir", vector(reflected));
    }

    /// The 54 submissions, in file-name order.
    pub fn submissions() -> Vec<Submission> {
        let mut out = Vec::new();
        let mut push = |about: String, bytes: Vec<u8>, kind: &str| {
            let name = format!("{:02}_{kind}.toml", out.len() + 1);
            let mut bytes = bytes;
            if bytes.is_empty() {
                bytes = about.into_bytes();
            }
            out.push(Submission { name, bytes });
        };
        for seed in 0..right() as u64 {
            let about = format!("right: the key of variant {seed}");
            push(about.clone(), written(&about, &key_table(seed)), &format!("right_seed{seed}"));
        }
        for group in mistake_files() {
            let seed = group[0].seed;
            let mut file = key_table(seed);
            let mut about = Vec::new();
            for m in &group {
                set(&mut file, m.key, toml_of(&m.rule.value).unwrap());
                about.push(format!("{}: {}", m.key, m.rule.message));
            }
            let about = format!("recognised mistakes (variant {seed}) in {}", about.join("; "));
            push(about.clone(), written(&about, &file), &format!("mistakes_seed{seed}"));
        }
        // Early errors carried forward: each later answer follows correctly from the wrong one.
        let mut file = key_table(0);
        q2_from_t(&mut file, 5.0 + 3f64.sqrt(), 2.0);
        let about = "carried: the larger root t = 5 + sqrt 3, then its point, normal and reflection";
        push(about.into(), written(about, &file), "carried_q2_larger_root");
        let mut file = key_table(0);
        set(&mut file, "q2a.C", toml::Value::String("dot(e - o, e - o) - r".into()));
        // C = |f|² - r = 24 instead of 22: t = (10 - sqrt(100 - 96))/2 = 4.
        q2_from_t(&mut file, 4.0, 2.0);
        let about = "carried: r for r^2 in C, then t = 4 from it, its point, normal and reflection";
        push(about.into(), written(about, &file), "carried_q2_c_with_r");
        let mut file = key_table(0);
        // The student's erratum: the x<3 cell entered at t = 3 (the y = 3 crossing), in its descent
        // and again in its leaf.
        for part in ["descents", "leaves"] {
            let entries = file["q3d"][part].as_array().unwrap().clone();
            let moved: Vec<toml::Value> = entries
                .into_iter()
                .map(|mut entry| {
                    let cell = entry.as_table_mut().unwrap();
                    if cell["path"].as_array().unwrap()[0].as_str() == Some("x<3") {
                        cell.insert("tmin".into(), toml::Value::Float(3.0));
                    }
                    entry
                })
                .collect();
            set(&mut file, &format!("q3d.{part}"), toml::Value::Array(moved));
        }
        let about = "carried: the x<3 cell entered at t = 3 instead of 2, in every descent and leaf after it";
        push(about.into(), written(about, &file), "carried_q3d_entry");
        let mut file = key_table(0);
        // D = 3R: the half angle in radians, asin(1/3), and the lost fraction from it as if it were
        // degrees, sin²(0.3398°).
        let gamma = (1.0f64 / 3.0).asin();
        set(&mut file, "q4b.blind_half_angle_deg", toml::Value::Float(gamma));
        set(&mut file, "q4b.lost_fraction", toml::Value::Float(gamma.to_radians().sin().powi(2)));
        let about = "carried: the blind half angle in radians, then the lost fraction from it read as degrees";
        push(about.into(), written(about, &file), "carried_q4b_radians");
        // Incomplete: whole questions left out.
        let mut file = key_table(1);
        file.retain(|section, _| section == "meta" || section.starts_with("q2"));
        let about = "incomplete: only Q2 answered (variant 1)";
        push(about.into(), written(about, &file), "incomplete_q2_only");
        let mut file = key_table(2);
        file.retain(|section, _| !section.starts_with("q5"));
        let about = "incomplete: Q5 left out (variant 2)";
        push(about.into(), written(about, &file), "incomplete_no_q5");
        // Not gradable: each is a row of the class report with its reason.
        let key = answer_key(0).unwrap();
        let broken = [
            ("unreadable_syntax", format!("# a table left open\n{}", key.replacen("[q2a]", "[q2a", 1)).into_bytes()),
            (
                "unreadable_nan",
                format!("# a NaN\n{}", key.replacen("t_closest = 5.0", "t_closest = nan", 1)).into_bytes(),
            ),
            ("unreadable_binary", b"# not UTF-8 text\n\xff\xfe\x00\x01".to_vec()),
            ("unreadable_seed", key.replacen("seed = 0", "seed = -1", 1).into_bytes()),
            ("unreadable_shape", b"# a question that is not a table\nq2 = [1, 2]\n".to_vec()),
        ];
        for (kind, bytes) in broken {
            push(String::new(), bytes, kind);
        }
        out
    }
}

fn class_dir() -> std::path::PathBuf {
    std::path::PathBuf::from(answers("class"))
}

/// The committed demo class is what [`class_demo::submissions`] writes (`HW3_WRITE_CLASS=1
/// cargo test --test integration class_demo_files` rewrites it after a change of the key).
#[test]
fn class_demo_files_are_the_generators() {
    let dir = class_dir();
    let submissions = class_demo::submissions();
    assert_eq!(submissions.len(), class_demo::CLASS, "the demo class has 54 submissions");
    if std::env::var_os("HW3_WRITE_CLASS").is_some() {
        std::fs::create_dir_all(&dir).unwrap();
        for old in std::fs::read_dir(&dir).unwrap() {
            std::fs::remove_file(old.unwrap().path()).unwrap();
        }
        for s in &submissions {
            std::fs::write(dir.join(&s.name), &s.bytes).unwrap();
        }
    }
    let mut committed: Vec<String> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    committed.sort();
    let names: Vec<&str> = submissions.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(committed, names, "rewrite with HW3_WRITE_CLASS=1");
    for s in &submissions {
        assert_eq!(std::fs::read(dir.join(&s.name)).unwrap(), s.bytes, "{}: rewrite with HW3_WRITE_CLASS=1", s.name);
    }
    // The chapter describes the class by its counts: they are the generator's.
    let chapter =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/checker.md")).unwrap().replace('\n', " ");
    let (right, mistakes) = (class_demo::right(), class_demo::mistake_files().len());
    let described =
        format!("{right} right (variants 0 to {}), {mistakes} with up to three recognised mistakes", right - 1);
    assert!(chapter.contains(&described), "docs/checker.md should say: {described}");
}

#[test]
fn a_class_of_54_graded_in_one_command() {
    use hw3::checker::variant;
    let out = hw3(&["check", class_dir().to_str().unwrap(), "--format", "json"]);
    assert_eq!(out.status.code(), Some(1), "some parts wrong, some files not graded");
    let class: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let submissions = class["submissions"].as_array().unwrap();
    assert_eq!(submissions.len(), class_demo::CLASS);
    assert_eq!(class["graded"], class_demo::CLASS - class_demo::UNREADABLE);
    assert_eq!(class["ungraded"], class_demo::UNREADABLE);
    let named = |kind: &str| -> Vec<&serde_json::Value> {
        submissions.iter().filter(|s| s["file"].as_str().unwrap().contains(kind)).collect()
    };
    let parts = |s: &serde_json::Value| s["report"]["parts"].as_array().unwrap().clone();
    // Right files: every part correct, whatever the variant.
    assert_eq!(named("_right_").len(), class_demo::right());
    for s in named("_right_") {
        assert!(parts(s).iter().all(|p| p["status"] == "correct"), "{}", s["file"]);
    }
    // Recognised mistakes: those parts only, each recognised by its rule.
    let files = class_demo::mistake_files();
    assert_eq!(named("_mistakes_").len(), files.len());
    for (s, group) in named("_mistakes_").into_iter().zip(&files) {
        let off: Vec<_> = parts(s)
            .into_iter()
            .filter(|p| p["status"] != "correct")
            .map(|p| (p["key"].as_str().unwrap().to_owned(), p["mistake"].as_str().map(str::to_owned)))
            .collect();
        let mut injected: Vec<_> =
            group.iter().map(|m| (m.key.to_owned(), Some(class_demo::rule_id(&m.rule).to_owned()))).collect();
        // The report lists parts in question order.
        let order = |key: &str| parts(s).iter().position(|p| p["key"] == key).unwrap();
        injected.sort_by_key(|(key, _)| order(key));
        assert_eq!(off, injected, "{}", s["file"]);
    }
    // Not gradable: a row each, with its one-line reason.
    for (kind, reason) in [
        ("syntax", "not valid TOML"),
        ("nan", "finite"),
        ("binary", "not UTF-8"),
        ("seed", "meta.seed"),
        ("shape", "must be a table"),
    ] {
        let s = named(&format!("unreadable_{kind}"))[0];
        let error = s["error"].as_str().unwrap();
        assert!(error.contains(reason) && !error.contains('\n'), "{kind}: {error}");
        assert!(s["report"].is_null());
    }
    // Statistics: each part's counts cover the graded files, its mean is the files' mean, and the
    // larger root's rule (at least one mistake file and one carried) is q2a.t's most common mistake.
    let graded: Vec<_> = submissions.iter().filter(|s| !s["report"].is_null()).collect();
    let t_rule = variant("q2", 0).unwrap().parts.into_iter().find(|p| p.key == "q2a.t").unwrap().mal_rules;
    let larger = t_rule.iter().find(|r| r.message.contains("larger root")).unwrap();
    for stat in class["parts"].as_array().unwrap() {
        let key = stat["key"].as_str().unwrap();
        let counts: u64 = ["correct", "partial", "wrong", "missing"].iter().map(|c| stat[c].as_u64().unwrap()).sum();
        assert_eq!(counts as usize, graded.len(), "{key}");
        let scores: Vec<f64> = graded
            .iter()
            .map(|s| parts(s).iter().find(|p| p["key"] == key).unwrap()["score"].as_f64().unwrap())
            .collect();
        let mean = scores.iter().sum::<f64>() / scores.len() as f64;
        assert!((stat["mean_score"].as_f64().unwrap() - mean).abs() <= 0.005 + 1e-12, "{key}");
        let right =
            graded.iter().filter(|s| parts(s).iter().any(|p| p["key"] == key && p["status"] == "correct")).count();
        assert_eq!(stat["correct"].as_u64().unwrap() as usize, right, "{key}");
        if key == "q2a.t" {
            assert_eq!(stat["most_common_mistake"].as_str(), Some(class_demo::rule_id(larger)));
            // Every q2a.t answer the policy files under the larger root's rule (the rule id groups
            // the larger root with the other wrong-root slips of that part).
            let larger_count = graded
                .iter()
                .filter(|s| {
                    parts(s)
                        .iter()
                        .any(|p| p["key"] == key && p["mistake"].as_str() == Some(class_demo::rule_id(larger)))
                })
                .count();
            assert!(larger_count >= 2, "{larger_count}");
            assert_eq!(stat["most_common_mistake_count"].as_u64().unwrap() as usize, larger_count);
        }
    }
    let mean = graded.iter().map(|s| s["report"]["score"].as_f64().unwrap()).sum::<f64>() / graded.len() as f64;
    assert!((class["mean_score"].as_f64().unwrap() - mean).abs() <= 0.005 + 1e-12);
}

#[test]
fn a_class_report_as_text_csv_and_gradescope() {
    let dir = class_dir();
    let text = hw3(&["check", dir.to_str().unwrap()]);
    assert_eq!(text.status.code(), Some(1));
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(text.starts_with("class of 54 files: 49 graded, 5 not graded"), "{text}");
    assert!(text.contains("not graded: not valid TOML"), "{text}");
    assert!(text.contains("most common recognised mistake per part"), "{text}");
    let csv = String::from_utf8(hw3(&["check", dir.to_str().unwrap(), "--format", "csv"]).stdout).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 1 + class_demo::CLASS + 2, "header, a row per file, mean and right");
    assert!(rows[0].starts_with("file,seed,score,max_score,error,q1a.gap_fraction"));
    let n = class_demo::CLASS;
    assert!(rows[n + 1].starts_with("(mean),,") && rows[n + 2].starts_with("(right),,"));

    let out = std::env::temp_dir().join(format!("hw3-class-gradescope-{}", std::process::id()));
    let graded = hw3(&["check", dir.to_str().unwrap(), "--format", "gradescope", "--out", out.to_str().unwrap()]);
    assert_eq!(graded.status.code(), Some(1));
    assert!(graded.stdout.is_empty());
    let written: Vec<_> = std::fs::read_dir(&out).unwrap().collect();
    assert_eq!(written.len(), class_demo::CLASS, "one results file per student");
    let first: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("01_right_seed0.json")).unwrap()).unwrap();
    let full = hw3::checker::check(&std::fs::read_to_string(dir.join("01_right_seed0.toml")).unwrap(), None).unwrap();
    assert!(full.all_correct());
    assert_eq!(first["score"].as_f64(), Some(full.max_score));
    let broken: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("54_unreadable_shape.json")).unwrap()).unwrap();
    assert_eq!(broken["score"], 0.0);
    assert!(broken["output"].as_str().unwrap().starts_with("not graded: "), "{broken}");
    std::fs::remove_dir_all(&out).ok();

    // The report to a file, atomically: no temporary left beside it.
    let report = std::env::temp_dir().join(format!("hw3-class-{}.csv", std::process::id()));
    let to_file = hw3(&["check", dir.to_str().unwrap(), "--format", "csv", "--out", report.to_str().unwrap()]);
    assert_eq!(to_file.status.code(), Some(1));
    assert_eq!(std::fs::read_to_string(&report).unwrap(), format!("{csv}"));
    std::fs::remove_file(&report).ok();
}

#[test]
fn a_class_of_unreadable_files_or_over_the_bounds_exits_2() {
    let dir = class_dir();
    let bad: Vec<String> = ["52_unreadable_binary.toml", "54_unreadable_shape.toml"]
        .iter()
        .map(|f| dir.join(f).display().to_string())
        .collect();
    let out = hw3(&["check", &bad[0], &bad[1]]);
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("no file could be graded"), "{stderr}");
    // More files than the bound: refused before any is read (these do not exist).
    let many: Vec<String> = (0..=hw3::checker::MAX_CLASS_FILES).map(|i| format!("/no/such/{i}.toml")).collect();
    let mut args = vec!["check"];
    args.extend(many.iter().map(String::as_str));
    let out = hw3(&args);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8(out.stderr).unwrap().contains(&format!("more than {}", hw3::checker::MAX_CLASS_FILES)));
    // A missing file among readable ones is a row of the report, not the end of the run.
    let key = dir.join("01_right_seed0.toml");
    let out = hw3(&["check", key.to_str().unwrap(), "/no/such/file.toml", "--format", "json"]);
    assert_eq!(out.status.code(), Some(1));
    let class: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!((class["graded"].as_u64(), class["ungraded"].as_u64()), (Some(1), Some(1)));
}
