//! `hw3 check`, `hw3 template` and `hw3 variant` as a student or grader uses them.

mod common;

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
    assert!(text.contains("did you mean `q2c.t_closest`"), "{text}");
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
    std::fs::write(&key, hw3::checker::answers_key(9).unwrap()).unwrap();
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
fn the_seeds_own_answers_graded() {
    let out = hw3(&["check", &answers("seed_hw3.toml")]);
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8(out.stdout).unwrap();
    // Q3 (d): the second leaf's tmin is the y = 3 crossing (t = 3), not the x = 3 crossing (t = 2).
    assert!(text.contains("t = 3 is where the ray crosses y = 3, not where it enters this cell"), "{text}");
    let line =
        |key: &str| text.lines().find(|l| l.contains(key)).unwrap_or_default().split_whitespace().collect::<Vec<_>>();
    assert_eq!(line("q3d.leaves")[2..], ["1.50/3", "partial"], "{text}");
    assert_eq!(line("q3e.leaves")[2..], ["2.00/2", "correct"], "{text}");
    // The chapter quotes this score; it must be the one the checker prints.
    let score = text.lines().last().unwrap().trim_start_matches("score ").split(" over").next().unwrap();
    let chapter = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/checker.md")).unwrap();
    assert!(chapter.contains(&format!("**{score}**")), "docs/checker.md should quote the seed's score {score}");
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
