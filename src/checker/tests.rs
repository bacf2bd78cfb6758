//! Tests of the checker as a whole: answers files graded end to end, against the variants, the
//! templates and the keys. They sit above every other file of `checker/`, which they use.

use super::key::Expected;
use super::variants::{CACHE, CACHED_VARIANTS, uncached};
use super::*;

// The variants: pinned, and cached without changing a report.
/// Value stability: seeds 1–5 of every question, statement and key, pinned (a change here
/// changes every student's variant).
#[test]
fn variants_are_pinned_for_seeds_1_to_5() {
    for question in QUESTIONS {
        let text: String = (1..=5)
            .map(|s| {
                format!(
                    "{}\n-- key --\n{}\n",
                    variant(question, s).unwrap().statement,
                    answer_key_for(question, s).unwrap()
                )
            })
            .collect();
        let name = format!("checker_{question}_variants");
        crate::testing::insta_settings().bind(|| insta::assert_snapshot!(name, text));
    }
}

/// The cache changes no report: files of several seeds (blank templates, the full keys, the
/// homework's own answers) graded through the cache, twice, and with it bypassed, give equal
/// reports; and more seeds than the cache holds leave it at its bound.
#[test]
fn cached_and_uncached_reports_are_equal() {
    let homework = include_str!("../../tests/answers/seed_hw3.toml");
    for seed in [0, 1, 7, 1 << 40, i64::MAX as u64] {
        let files = [crate::checker::template(seed).unwrap(), crate::checker::answer_key(seed).unwrap()];
        for text in files.iter().map(String::as_str).chain([homework]) {
            let fresh = uncached(|| crate::checker::check(text, Some(seed)));
            let first = crate::checker::check(text, Some(seed));
            let second = crate::checker::check(text, Some(seed));
            assert_eq!(first, fresh, "seed {seed}");
            assert_eq!(second, fresh, "seed {seed}");
        }
    }
    for seed in 0..40 {
        for question in QUESTIONS {
            assert_eq!(variant(question, seed).unwrap(), uncached(|| variant(question, seed).unwrap()));
        }
    }
    assert!(CACHE.lock().unwrap().len() <= CACHED_VARIANTS);
    assert!(matches!(variant("q6", 0), Err(CheckError::UnknownQuestion(_))));
}

// Keys that are misspelt or unknown.
#[test]
fn misspelt_key_gets_a_suggestion() {
    let report = check("[q2a]\npiont = [1, 2, 3]\n[q2c]\nt_closet = 5.0\nwhatever = 1", Some(0)).unwrap();
    // Both misspellings are close to one unanswered part each: graded there, with a warning.
    assert_eq!(report.warnings, ["graded `q2a.point` for `q2a.piont`", "graded `q2c.t_closest` for `q2c.t_closet`"]);
    assert_eq!(report.unknown_keys, vec!["`q2c.whatever`".to_string()]);
    let part = |key: &str| report.parts.iter().find(|p| p.key == key).unwrap();
    assert_eq!((part("q2c.t_closest").status, part("q2c.t_closest").score), ("correct", 2.0));
    assert_eq!(part("q2a.point").status, "wrong");
    assert!(part("q2a.point").feedback.starts_with("graded `q2a.point` for `q2a.piont`"));
}

#[test]
fn ambiguous_far_or_answered_keys_stay_unknown() {
    // `q2a.D` is one edit from t, A, B and C; `q2a.pointt` is one from a part already
    // answered; `q1a.share_of_gaps` is far from every part; two spellings of one part are both
    // a guess.
    let text = "[q2a]\nD = \"1\"\npoint = [1, 2, 3]\npointt = [1, 2, 3]\n[q1a]\nshare_of_gaps = 0.5\n[q2c]\nt_closet = 5.0\nt_closeste = 5.0";
    let report = check(text, Some(0)).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    assert_eq!(
        report.unknown_keys,
        [
            "`q1a.share_of_gaps`",
            "`q2a.D` (did you mean `q2a.t`?)",
            "`q2a.pointt` (did you mean `q2a.point`?)",
            "`q2c.t_closeste` (did you mean `q2c.t_closest`?)",
            "`q2c.t_closet` (did you mean `q2c.t_closest`?)",
        ]
    );
    assert_eq!(report.parts.iter().find(|p| p.key == "q2c.t_closest").unwrap().status, "missing");
}

#[test]
fn a_file_without_its_seed_is_graded_as_variant_0_with_a_warning() {
    let report = check("[q2c]\nt_closest = 5.0", None).unwrap();
    assert_eq!((report.seed, report.warnings.len()), (0, 1), "{:?}", report.warnings);
    assert!(report.warnings[0].contains("no `[meta] seed`"));
    assert!(check("[meta]\nseed = 0\n[q2c]\nt_closest = 5.0", None).unwrap().warnings.is_empty());
    assert!(check("[q2c]\nt_closest = 5.0", Some(0)).unwrap().warnings.is_empty());
    // The class's list shows it too, on the file's row.
    let class = super::class::check_class(&[("a.toml".into(), Ok("[q2c]\nt_closest = 5.0".into()))], None);
    let row = super::class::class_text(&class).lines().find(|l| l.starts_with("a.toml")).unwrap().to_owned();
    assert!(row.contains("no `[meta] seed`"), "{row}");
}

#[test]
fn a_misspelt_key_of_the_wrong_shape_stays_unknown() {
    // `t_closet` is close to `t_closest`, but a string is no number: not graded, not an error.
    let report = check("[q2c]\nt_closet = \"five\"", Some(0)).unwrap();
    assert!(report.warnings.is_empty());
    assert_eq!(report.unknown_keys, ["`q2c.t_closet` (did you mean `q2c.t_closest`?)"]);
}

// Q2: every variant asks the same parts, and "none" is an answer.
#[test]
fn every_variant_asks_the_same_parts_and_none_is_an_answer() {
    let keys = |seed| q2::variant(seed).parts.iter().map(|p| p.key).collect::<Vec<_>>();
    for seed in 2..=6 {
        assert_eq!(keys(seed), keys(1), "seed {seed}: the parts must not give the case away");
    }
    // Seed 5 misses: "none" is right, a number is wrong; seed 1 hits: "none" is wrong.
    let miss = crate::checker::check("[meta]\nseed = 5\n[q2a]\nt = \"none\"\npoint = [1, 2, 3]", None).unwrap();
    let part = |report: &crate::checker::Report, key: &str| report.parts.iter().find(|p| p.key == key).unwrap().clone();
    assert_eq!(part(&miss, "q2a.t").status, "correct");
    assert_eq!(part(&miss, "q2a.point").status, "wrong");
    assert!(part(&miss, "q2a.point").feedback.contains("write \"none\""));
    let hit = crate::checker::check("[meta]\nseed = 1\n[q2a]\nt = \"none\"", None).unwrap();
    assert_eq!(part(&hit, "q2a.t").status, "wrong");
}

// Q4's probe image: the slips are recognised by name.
/// Every slip the probe parts name is reachable: answering its value is graded wrong (or
/// partial) with a recognised message, never correct, unless the slip coincides with the key
/// (4 × a whole texel's area *is* the solid angle of a texel wholly inside the disc).
#[test]
fn every_probe_slip_is_recognised() {
    for seed in 0..12 {
        let v = q4::variant(seed);
        for part in v.parts.iter().filter(|p| p.key.starts_with("q4c.") && p.key != "q4c.term_formula") {
            let toml_value = |e: &Expected| match e {
                Expected::Number { value, .. } => format!("{value:?}"),
                Expected::Direction { value, .. } => format!("[{:?}, {:?}, {:?}]", value[0], value[1], value[2]),
                other => unreachable!("{other:?}"),
            };
            let name = part.key.trim_start_matches("q4c.");
            for rule in &part.mal_rules {
                let file = format!("[meta]\nseed = {seed}\n[q4c]\n{name} = {}\n", toml_value(&rule.value));
                let report = check(&file, None).unwrap();
                let result = report.parts.iter().find(|p| p.key == part.key).unwrap();
                if result.status == "correct" {
                    continue;
                }
                let named = part.mal_rules.iter().any(|r| result.feedback.starts_with(r.message));
                assert!(named, "seed {seed} {}: `{}` not recognised: {}", part.key, rule.message, result.feedback);
            }
        }
    }
}

/// The classic slips of seed 0, by name: the solid angle forgotten, the clamp forgotten, the
/// light's travel direction for the direction it comes from, a corner for the centre.
#[test]
fn seed_zero_names_the_classic_slips() {
    let v = q4::variant(0);
    let feedback = |key: &str, value: String| {
        let (table, name) = key.split_once('.').unwrap();
        let report = check(&format!("[{table}]\n{name} = {value}\n"), None).unwrap();
        report.parts.into_iter().find(|p| p.key == key).unwrap().feedback
    };
    let rule_value = |key: &str, start: &str| {
        let part = v.parts.iter().find(|p| p.key == key).unwrap();
        let rule = part.mal_rules.iter().find(|r| r.message.starts_with(start)).unwrap();
        match rule.value {
            Expected::Number { value, .. } => format!("{value:?}"),
            Expected::Direction { value, .. } => format!("{value:?}"),
            _ => unreachable!(),
        }
    };
    for (key, slip) in [
        ("q4c.weighted_sum", "the solid angle dw is missing"),
        ("q4c.weighted_sum", "the clamp max(0, .) is missing"),
        ("q4c.weighted_sum", "that uses -w"),
        ("q4c.texel1_direction", "that is -w"),
        ("q4c.texel1_direction", "that is the direction of a corner"),
        ("q4c.texel3_solid_angle", "that is 4 x the whole texel's area"),
        ("q4c.unweighted_sum", "that is the literal sum"),
    ] {
        let text = feedback(key, rule_value(key, slip));
        assert!(text.starts_with(slip), "{key}: {text}");
    }
    // The student's own sum as a formula, and the key's, written with the clamp as (x + |x|)/2.
    let text = feedback("q4c.term_formula", "\"L*dot(n, w)\"".into());
    assert!(text.contains("the student's K_d L (n . l)"), "{text}");
    let text = feedback("q4c.term_formula", "\"L*(dot(n, w) + abs(dot(n, w)))/2*dw\"".into());
    assert!(!text.contains("missing"), "{text}");
}

// The statement states the setting the key, the template and the worked solution are made from.
#[test]
fn every_statement_states_its_setting() {
    let v3 = |v: glam::DVec3| format!("({}, {}, {})", v.x, v.y, v.z);
    for seed in 0..=20 {
        for question in QUESTIONS {
            let v = variant(question, seed).unwrap();
            let says: Vec<String> = match &v.setting {
                Setting::Q1(n) => vec![
                    format!("{} spheres of radius a = {}", n.count, n.radius),
                    format!("front face is a {} x {} square", n.side, n.side),
                    format!("sigma_t = {}: the transmittance along a path of length {}", n.sigma_t, n.path),
                    format!("radius R = {} steps sideways by {}", n.mirror_radius, n.step),
                    format!("moving at {} units/s across the view, {} units away", n.speed, n.depth),
                    format!("filmed at {} frames/s with a vertical field of view of {} degrees", n.fps, n.fov_deg),
                    format!("an image {} pixels high", n.height),
                ],
                Setting::Q2 { ray, sphere } => vec![
                    format!("e = {}, d = {}", v3(ray.origin), v3(ray.dir)),
                    format!("centre o = {}, radius r = {}", v3(sphere.center), sphere.radius),
                ],
                Setting::Q3 { d, e } => [('d', d), ('e', e)]
                    .map(|(label, r)| {
                        format!("({label}) e = ({}, {}), d = ({}, {})", r.origin[0], r.origin[1], r.dir[0], r.dir[1])
                    })
                    .to_vec(),
                Setting::Q4(s) => {
                    let sign = if s.b < 0.0 { '-' } else { '+' };
                    let mut says = vec![
                        format!("L(w) = {} {sign} {} w_z", s.a, s.b.abs()),
                        format!("tilted {} degrees", s.tilt_deg),
                        format!("distance D = {} R", s.distance_over_radius),
                        format!("as a {} x {} image", s.image.size, s.image.size),
                    ];
                    let listed: Vec<String> = s.image.listed.iter().map(|p| format!("{p:?}")).collect();
                    says.push(format!("For texels {} (row, column)", listed.join(", ")));
                    for (row, texels) in s.image.radiance.chunks(s.image.size).enumerate() {
                        let cells: Vec<String> =
                            texels.iter().map(|l| l.map_or_else(|| "-".to_string(), |l| format!("{l}"))).collect();
                        says.push(format!("| {row} | {} |", cells.join(" | ")));
                    }
                    says
                }
                Setting::Q5 => vec![],
            };
            for said in says {
                assert!(v.statement.contains(&said), "{question} seed {seed}: `{said}` not in\n{}", v.statement);
            }
        }
    }
}
