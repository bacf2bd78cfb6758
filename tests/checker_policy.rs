//! The partial-credit policy: each rule earns the same credit in every question where it occurs,
//! the chapter's table is the code's, an error carried forward is charged once, and every part's
//! link goes to a section that exists.

use hw3::checker::{Expected, PartResult, QUESTIONS, Rule, check, policy_table, variant};
use std::path::Path;

/// Seeds enough to reach every Q2 case twice, every Q3 second-ray kind and several Q1/Q4 grids.
const SEEDS: std::ops::Range<u64> = 0..13;

/// A wrong value as the TOML a student would write.
fn toml_value(expected: &Expected) -> String {
    let vector = |v: &[f64; 3]| format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2]);
    match expected {
        Expected::Number { value, .. } => format!("{value:?}"),
        Expected::Vector { value, .. } | Expected::Direction { value, .. } | Expected::Parallel { value, .. } => {
            vector(value)
        }
        Expected::Choice { value, .. } => format!("{value:?}"),
        Expected::Flag { value } => value.to_string(),
        Expected::Formula { source, .. } => format!("{source:?}"),
        Expected::Paths { value } => format!("{value:?}"),
        other => panic!("no mal-rule has a value like {other:?}"),
    }
}

fn graded(question: &str, seed: u64, key: &str, value: &str) -> PartResult {
    let (table, name) = key.split_once('.').unwrap();
    let text = format!("[meta]\nseed = {seed}\n[{table}]\n{name} = {value}\n");
    let report = check(&text, None).unwrap_or_else(|e| panic!("{question} {seed} {key} = {value}: {e}"));
    report.parts.into_iter().find(|p| p.key == key).unwrap()
}

/// Every part where `rule` occurs, in every question and seed: answering its wrong value earns
/// the policy's credit, names the rule, and is not the key.
fn applied_alike(rule: Rule) {
    let mut questions = Vec::new();
    for question in QUESTIONS {
        for seed in SEEDS {
            let v = variant(question, seed).unwrap();
            for part in &v.parts {
                for mal_rule in part.mal_rules.iter().filter(|m| m.rule == rule) {
                    let value = toml_value(&mal_rule.value);
                    let result = graded(question, seed, part.key, &value);
                    let what = format!("{question} seed {seed} {} = {value}: {result:?}", part.key);
                    assert_eq!(result.mistake, Some(rule.id()), "{what}");
                    assert_eq!(result.score, (part.points * rule.credit() * 100.0).round() / 100.0, "{what}");
                    assert!(result.feedback.contains(mal_rule.message), "{what}");
                    if rule.credit() < 1.0 {
                        assert_ne!(result.status, "correct", "{what}");
                    }
                    if !questions.contains(&question) {
                        questions.push(question);
                    }
                }
            }
        }
    }
    assert!(!questions.is_empty(), "rule {} occurs in no part", rule.id());
}

macro_rules! one_test_per_rule {
    ($($name:ident => $rule:expr,)*) => {
        $(
            #[test]
            fn $name() {
                applied_alike($rule);
            }
        )*

        /// Every rule but the carried-forward one (tested on whole files below) has its test.
        #[test]
        fn every_rule_has_its_test() {
            let tested = [$($rule),*];
            for rule in Rule::ALL {
                assert!(tested.contains(&rule) || rule == Rule::CarriedForward, "no test for {}", rule.id());
            }
        }
    };
}

one_test_per_rule! {
    sign_earns_nothing_everywhere => Rule::Sign,
    factor_earns_half_everywhere => Rule::Factor,
    power_earns_nothing_everywhere => Rule::Power,
    wrong_term_earns_nothing_everywhere => Rule::WrongTerm,
    wrong_root_earns_nothing_everywhere => Rule::WrongRoot,
    distance_for_parameter_earns_half_everywhere => Rule::DistanceForParameter,
    not_normalised_earns_half_everywhere => Rule::NotNormalised,
    unit_earns_half_everywhere => Rule::Unit,
    full_for_half_angle_earns_half => Rule::FullForHalfAngle,
    convention_earns_half_everywhere => Rule::Convention,
    other_quantity_earns_nothing_everywhere => Rule::OtherQuantity,
    wrong_case_earns_nothing_everywhere => Rule::WrongCase,
    wrong_verdict_earns_nothing_everywhere => Rule::WrongVerdict,
}

/// The issue's inconsistencies, each resolved by one rule: the distance for t earns the same in
/// q2a as in q2c; radians and the full cone angle both earn half.
#[test]
fn the_same_slip_earns_the_same_in_every_part() {
    // Seed 1: an outside ray with |d| ≠ 1, so the distance and the parameter differ.
    let v = variant("q2", 1).unwrap();
    let rule_of = |key: &str, rule: Rule| {
        let part = v.parts.iter().find(|p| p.key == key).unwrap();
        part.mal_rules.iter().find(|m| m.rule == rule).map(|m| (part.points, toml_value(&m.value)))
    };
    for key in ["q2a.t", "q2c.t_closest", "q2c.t_formula"] {
        let (points, value) = rule_of(key, Rule::DistanceForParameter).unwrap_or_else(|| panic!("{key}"));
        assert_eq!(graded("q2", 1, key, &value).score, points / 2.0, "{key}");
    }
    let q4 = variant("q4", 0).unwrap();
    let blind = q4.parts.iter().find(|p| p.key == "q4b.blind_half_angle_deg").unwrap();
    let credits: Vec<f64> = blind.mal_rules.iter().map(|m| m.credit()).collect();
    assert_eq!(credits, [0.5, 0.5], "radians and the full cone angle");
}

/// The chapter's policy table is the code's.
#[test]
fn the_chapters_policy_table_is_the_codes() {
    let chapter = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/checker.md")).unwrap();
    assert!(
        chapter.contains(&policy_table()),
        "paste hw3::checker::policy_table() into docs/checker.md:\n{}",
        policy_table()
    );
}

fn part<'a>(report: &'a hw3::checker::Report, key: &str) -> &'a PartResult {
    report.parts.iter().find(|p| p.key == key).unwrap()
}

/// Q2 seed 0 (e = (-5, 1, 0), d = (1, 0, 0), o = 0, r = 2) with one early slip, t = 3 instead of
/// 5 − √3, and every later step computed correctly from it: the point e + 3 d = (-2, 1, 0), its
/// normal (-2, 1, 0)/√5, and the reflection of d about that normal. Only t loses its points.
#[test]
fn q2_an_early_slip_is_charged_once() {
    let s5 = 5f64.sqrt();
    let n = [-2.0 / s5, 1.0 / s5, 0.0];
    // r = d − 2 (n · d) n with d = x̂: n · d = −2/√5.
    let r = [1.0 - 2.0 * (-2.0 / s5) * n[0], -2.0 * (-2.0 / s5) * n[1], 0.0];
    let text = format!(
        "[q2a]\nt = 3.0\npoint = [-2.0, 1.0, 0.0]\n[q2b]\nnormal = [{:?}, {:?}, 0.0]\nreflected_dir = [{:?}, {:?}, 0.0]\n",
        n[0], n[1], r[0], r[1]
    );
    let report = check(&text, None).unwrap();
    assert_eq!(part(&report, "q2a.t").status, "wrong");
    for key in ["q2a.point", "q2b.normal", "q2b.reflected_dir"] {
        let p = part(&report, key);
        assert_eq!((p.score, p.max_score, p.mistake), (p.max_score, p.max_score, Some("carried_forward")), "{p:?}");
        assert!(p.feedback.contains("first wrong step: `q2a.t`"), "{key}: {}", p.feedback);
    }
    // A point that follows from nothing the student wrote is wrong; the feedback says the earlier
    // part is wrong too without calling it the first wrong step (fixing it would not fix this).
    let broken = check("[q2a]\nt = 3.0\npoint = [-2.0, 1.5, 0.0]\n", None).unwrap();
    let p = part(&broken, "q2a.point");
    assert_eq!((p.status, p.mistake), ("wrong", None));
    assert!(
        p.feedback.contains("`q2a.t` is wrong too, but this answer does not follow from it either"),
        "{}",
        p.feedback
    );
    assert!(!p.feedback.contains("first wrong step"), "{}", p.feedback);
}

/// Q3 (d) with a wrong root crossing, t = 2.5 instead of 2 for x = 3, and every descent and leaf
/// after it consistent with 2.5: the descents lose only the first wrong entry, the leaves nothing
/// (they are the student's own descents into leaf cells).
#[test]
fn q3_a_wrong_plane_parameter_is_carried_through_the_trace() {
    let text = r#"
[q3d]
descents = [
  { path = ["x>=3"], tmin = 0, tmax = 2.5 },
  { path = ["x>=3", "y<3"], tmin = 0, tmax = 2.5 },
  { path = ["x<3"], tmin = 2.5, tmax = "inf" },
  { path = ["x<3", "y>=1"], tmin = 2.5, tmax = "inf" },
]
leaves = [
  { path = ["x>=3", "y<3"], tmin = 0, tmax = 2.5 },
  { path = ["x<3", "y>=1"], tmin = 2.5, tmax = "inf" },
]
"#;
    let report = check(text, None).unwrap();
    let descents = part(&report, "q3d.descents");
    // Four descents: the first wrong, three follow from its 2.5.
    assert_eq!((descents.score, descents.mistake), (1.13, Some("carried_forward")), "{descents:?}");
    assert!(descents.feedback.contains("3 later descents follow from that bound"), "{}", descents.feedback);
    let leaves = part(&report, "q3d.leaves");
    assert_eq!((leaves.score, leaves.status, leaves.mistake), (3.0, "correct", Some("carried_forward")), "{leaves:?}");
    assert!(leaves.feedback.contains("follows from your `q3d.descents`"), "{}", leaves.feedback);
}

/// Q4 seed 0 (D = 3R) with the half-angle taken as arctan(R/D) = 18.43° instead of arcsin: the
/// lost fraction sin²(18.43°) = 0.1 follows from it and earns its points.
#[test]
fn q4_the_lost_fraction_follows_from_the_students_half_angle() {
    let gamma = (1.0f64 / 3.0).atan().to_degrees();
    let lost = gamma.to_radians().sin().powi(2);
    let report = check(&format!("[q4b]\nblind_half_angle_deg = {gamma:?}\nlost_fraction = {lost:?}"), None).unwrap();
    assert_eq!(part(&report, "q4b.blind_half_angle_deg").score, 0.0);
    let p = part(&report, "q4b.lost_fraction");
    assert_eq!((p.score, p.mistake), (2.0, Some("carried_forward")), "{p:?}");
}

/// Q5: a missed class that follows from the student's own wrong verdict is charged once, at the
/// verdict. Radiosity captures colour bleeding (`q5a.b` is yes, its missed class `none`); a student
/// who says no and names the whole effect as missed is consistent with that no, since a method
/// misses all of each of Q5's effects or none of it. So is a yes with `none` for the highlight,
/// which radiosity misses.
#[test]
fn q5_a_missed_class_follows_from_the_students_verdict() {
    let report = check("[q5a]\nb = \"no\"\nb_missed = \"LDD*DE\"\na = \"yes\"\na_missed = \"none\"\n", None).unwrap();
    for (cell, missed) in [("q5a.b", "q5a.b_missed"), ("q5a.a", "q5a.a_missed")] {
        let verdict = part(&report, cell);
        assert_eq!((verdict.score, verdict.mistake), (0.0, Some("wrong_verdict")), "{verdict:?}");
        let p = part(&report, missed);
        assert_eq!((p.score, p.status, p.mistake), (0.5, "correct", Some("carried_forward")), "{p:?}");
        assert!(p.feedback.contains(&format!("first wrong step: `{cell}`")), "{}", p.feedback);
    }
    // A class that does not follow from the verdict is wrong, and not blamed on the verdict.
    let report = check("[q5a]\nb = \"no\"\nb_missed = \"LDE\"\n", None).unwrap();
    let p = part(&report, "q5a.b_missed");
    assert_eq!((p.score, p.mistake), (0.0, None), "{p:?}");
    assert!(
        p.feedback.contains("`q5a.b` is wrong too, but this answer does not follow from it either"),
        "{}",
        p.feedback
    );
    // An impractical for a no implies the same missed class as the no: a wrong class there is its
    // own mistake, not one carried from the verdict.
    let report = check("[q5b]\nd_caustic = \"impractical\"\nd_caustic_missed = \"LSDE\"\n", None).unwrap();
    let p = part(&report, "q5b.d_caustic_missed");
    assert_eq!(p.score, 0.0);
    assert!(!p.feedback.contains("first wrong step"), "{}", p.feedback);
}

/// The section a part links to, as rustdoc numbers a chapter's headings (lower case,
/// alphanumerics and hyphens kept, spaces to hyphens).
fn heading_ids(chapter: &str) -> Vec<String> {
    let id = |title: &str| -> String {
        title
            .to_lowercase()
            .replace(' ', "-")
            .chars()
            .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_'))
            .collect()
    };
    chapter.lines().filter_map(|l| l.strip_prefix('#')).map(|l| id(l.trim_start_matches('#').trim())).collect()
}

/// Every part of every question links to a section (`#anchor`) that its chapter has, and every
/// wrong answer's feedback ends with a sentence on the method.
#[test]
fn every_part_links_an_existing_section_and_teaches_its_method() {
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs");
    for question in QUESTIONS {
        for seed in 0..7 {
            for part in variant(question, seed).unwrap().parts {
                let (page, anchor) =
                    part.explained_in.split_once('#').unwrap_or_else(|| panic!("{}: no anchor", part.key));
                let module = page.strip_prefix("hw3/").and_then(|p| p.strip_suffix("/index.html")).unwrap();
                let chapter = std::fs::read_to_string(docs.join(format!("{module}.md"))).unwrap();
                assert!(
                    heading_ids(&chapter).iter().any(|id| id == anchor),
                    "{}: no section #{anchor} in {module}",
                    part.key
                );
                assert!(part.method.ends_with('.') && part.method.len() > 20, "{}: {}", part.key, part.method);
            }
        }
    }
    let report = check("[q2a]\nt = 1.0", None).unwrap();
    let t = part(&report, "q2a.t");
    assert!(t.feedback.ends_with(variant("q2", 0).unwrap().parts.iter().find(|p| p.key == "q2a.t").unwrap().method));
}

/// Leaves follow from the student's own descents only when those descents follow the traversal's
/// method: a bound kept at 0 where the ray crosses a plane is a mistake of method, and the leaves
/// that repeat it are graded against the key (seed 0, case (d)).
#[test]
fn leaves_carry_a_slip_of_the_descents_not_a_mistake_of_method() {
    let file =
        |descents: &str, leaves: &str| format!("[meta]\nseed = 0\n[q3d]\ndescents = {descents}\nleaves = {leaves}\n");
    let kept_at_zero = file(
        r#"[{ path = ["x>=3"], tmin = 0, tmax = 2 }, { path = ["x>=3", "y<3"], tmin = 0, tmax = 2 }, { path = ["x<3"], tmin = 0, tmax = "inf" }, { path = ["x<3", "y>=1"], tmin = 0, tmax = "inf" }]"#,
        r#"[{ path = ["x>=3", "y<3"], tmin = 0, tmax = 2 }, { path = ["x<3", "y>=1"], tmin = 0, tmax = "inf" }]"#,
    );
    let report = check(&kept_at_zero, None).unwrap();
    let leaves = part(&report, "q3d.leaves");
    assert_eq!((leaves.score, leaves.mistake), (1.5, None), "{leaves:?}");
    assert!(
        leaves.feedback.contains("do not follow the traversal from the plane parameters they show"),
        "{}",
        leaves.feedback
    );
    // A slip of arithmetic (the root crossed at t = 2.5) is carried into the leaves.
    let slip = file(
        r#"[{ path = ["x>=3"], tmin = 0, tmax = 2.5 }, { path = ["x>=3", "y<3"], tmin = 0, tmax = 2.5 }, { path = ["x<3"], tmin = 2.5, tmax = "inf" }, { path = ["x<3", "y>=1"], tmin = 2.5, tmax = "inf" }]"#,
        r#"[{ path = ["x>=3", "y<3"], tmin = 0, tmax = 2.5 }, { path = ["x<3", "y>=1"], tmin = 2.5, tmax = "inf" }]"#,
    );
    let report = check(&slip, None).unwrap();
    let leaves = part(&report, "q3d.leaves");
    assert_eq!((leaves.score, leaves.mistake), (3.0, Some("carried_forward")), "{leaves:?}");
}

/// An extra entry costs its own share, not the credit of the entries after it: a zero-length
/// piece listed first (the tie the question rules out) and then the key's four descents earn 4
/// of 5 shares.
#[test]
fn an_extra_descent_costs_its_own_share() {
    let text = "[meta]\nseed = 0\n[q3d]\ndescents = [{ path = [\"x<3\"], tmin = 0, tmax = 0 }, { path = [\"x>=3\"], tmin = 0, tmax = 2 }, { path = [\"x>=3\", \"y<3\"], tmin = 0, tmax = 2 }, { path = [\"x<3\"], tmin = 2, tmax = \"inf\" }, { path = [\"x<3\", \"y>=1\"], tmin = 2, tmax = \"inf\" }]\n";
    let report = check(text, None).unwrap();
    let descents = part(&report, "q3d.descents");
    assert_eq!(descents.score, 1.2, "{descents:?}");
    assert!(descents.feedback.contains("descent 1 is extra: [x<3] t in [0, 0] has no length"), "{}", descents.feedback);
}

/// `inf` is a bound like any other: a finite tmax where the ray never leaves the cell is wrong,
/// however large (seed 0, case (d): the last leaf is [x<3, y>=1] on [2, inf]).
#[test]
fn a_finite_bound_is_not_inf() {
    let leaves = |last: &str| {
        format!(
            "[meta]\nseed = 0\n[q3d]\nleaves = [{{ path = [\"x>=3\", \"y<3\"], tmin = 0, tmax = 2 }}, {{ path = [\"x<3\", \"y>=1\"], tmin = 2, tmax = {last} }}]\n"
        )
    };
    let right = check(&leaves("\"inf\""), None).unwrap();
    assert_eq!(part(&right, "q3d.leaves").score, 3.0);
    for finite in ["7", "1e300"] {
        let report = check(&leaves(finite), None).unwrap();
        let p = part(&report, "q3d.leaves");
        assert_eq!(p.score, 1.5, "tmax = {finite}: {p:?}");
        assert!(
            p.feedback.contains("tmax should be inf: the ray does not leave this cell by any plane"),
            "{}",
            p.feedback
        );
    }
}

/// A zero-length piece listed before the right entry of the same cell is the extra one: the right
/// entry keeps its credit and the feedback names the piece, not the right entry.
#[test]
fn a_zero_length_piece_before_the_right_entry_is_the_extra_one() {
    let text = "[meta]\nseed = 0\n[q3d]\nleaves = [{ path = [\"x>=3\", \"y<3\"], tmin = 0, tmax = 2 }, { path = [\"x<3\", \"y>=1\"], tmin = 2, tmax = 2 }, { path = [\"x<3\", \"y>=1\"], tmin = 2, tmax = \"inf\" }]\n";
    let report = check(text, None).unwrap();
    let p = part(&report, "q3d.leaves");
    assert_eq!(p.score, 2.0, "two of three entries right: {p:?}");
    assert!(p.feedback.contains("leaf 2 is extra: [x<3, y>=1] t in [2, 2] has no length"), "{}", p.feedback);
}

/// A formula that divides by zero is infinite at every point and agrees with no finite key.
#[test]
fn a_formula_that_divides_by_zero_is_wrong() {
    let p = graded("q2", 0, "q2c.t_formula", "\"1/0\"");
    assert_eq!((p.score, p.status), (0.0, "wrong"), "{p:?}");
}

/// A number is compared relatively: 0 is not accepted for a tiny key (Q1's gap fraction of a dense
/// forest).
#[test]
fn zero_is_not_a_tiny_number() {
    let tiny = (0..1000)
        .find(|&seed| {
            let v = variant("q1", seed).unwrap();
            let part = v.parts.iter().find(|p| p.key == "q1a.gap_fraction").unwrap();
            matches!(part.expected, Expected::Number { value, .. } if value > 0.0 && value < 1e-9)
        })
        .expect("a seed whose gap fraction is below 1e-9");
    let p = graded("q1", tiny, "q1a.gap_fraction", "0");
    assert_eq!(p.score, 0.0, "seed {tiny}: {p:?}");
}

/// A slip of a plane parameter is charged once, in `planes`: the descents follow from the
/// student's planes and the leaves from those descents (seed 0, case (d), the root crossed at
/// t = 2.5 instead of 2 throughout).
#[test]
fn a_plane_slip_is_charged_once_in_the_planes() {
    let text = r#"[meta]
seed = 0
[q3d]
planes = [{ node = [], t = 2.5, first = "x>=3" }, { node = ["x>=3"], t = 3, first = "y<3" }, { node = ["x<3"], t = 1, first = "y>=1" }]
descents = [{ path = ["x>=3"], tmin = 0, tmax = 2.5 }, { path = ["x>=3", "y<3"], tmin = 0, tmax = 2.5 }, { path = ["x<3"], tmin = 2.5, tmax = "inf" }, { path = ["x<3", "y>=1"], tmin = 2.5, tmax = "inf" }]
leaves = [{ path = ["x>=3", "y<3"], tmin = 0, tmax = 2.5 }, { path = ["x<3", "y>=1"], tmin = 2.5, tmax = "inf" }]
"#;
    let report = check(text, None).unwrap();
    let planes = part(&report, "q3d.planes");
    assert_eq!(planes.score, 1.0, "one of three nodes wrong: {planes:?}");
    for (key, points) in [("q3d.descents", 1.5), ("q3d.leaves", 3.0)] {
        let p = part(&report, key);
        assert_eq!((p.score, p.mistake), (points, Some("carried_forward")), "{p:?}");
        assert!(p.feedback.contains("first wrong step: `q3d.planes`"), "{}", p.feedback);
    }
    // A wrong first child is a mistake of method: the descents are graded against the key.
    let method = text.replace(r#"t = 2.5, first = "x>=3""#, r#"t = 2.5, first = "x<3""#);
    let report = check(&method, None).unwrap();
    let descents = part(&report, "q3d.descents");
    assert!(descents.score < 1.5, "{descents:?}");
    assert!(descents.feedback.contains("are not the traversal's with one slip of arithmetic"), "{}", descents.feedback);
}

/// A trailing zero-length piece is named for what it is, and two entries in swapped order are
/// out of order, not missing (seed 0, case (d)).
#[test]
fn trailing_pieces_and_swapped_entries_are_named() {
    let leaves = |list: &str| format!("[meta]\nseed = 0\n[q3d]\nleaves = [{list}]\n");
    let (first, second) =
        (r#"{ path = ["x>=3", "y<3"], tmin = 0, tmax = 2 }"#, r#"{ path = ["x<3", "y>=1"], tmin = 2, tmax = "inf" }"#);
    let trailing = leaves(&format!(r#"{first}, {second}, {{ path = ["x<3", "y>=1"], tmin = 0, tmax = 0 }}"#));
    let report = check(&trailing, None).unwrap();
    let p = part(&report, "q3d.leaves");
    assert!(p.feedback.contains("leaf 3 is extra: [x<3, y>=1] t in [0, 0] has no length"), "{}", p.feedback);
    let swapped = leaves(&format!("{second}, {first}"));
    let report = check(&swapped, None).unwrap();
    let p = part(&report, "q3d.leaves");
    assert!(p.feedback.contains("leaf 1 out of order: the ray enters [x>=3, y<3]"), "{}", p.feedback);
}

/// TOML's bare `inf` is read as infinity in a trace, like `"inf"`.
#[test]
fn bare_inf_is_infinity() {
    let text = "[meta]\nseed = 0\n[q3d]\nleaves = [{ path = [\"x>=3\", \"y<3\"], tmin = 0, tmax = 2 }, { path = [\"x<3\", \"y>=1\"], tmin = 2, tmax = inf }]\n";
    assert_eq!(part(&check(text, None).unwrap(), "q3d.leaves").score, 3.0);
}

/// A slip of a plane parameter that changes which children the ray visits is still charged
/// once: seed 3, case (d), the root crossed at t = 1.5 instead of 0.5, so the ray reaches x < 3
/// after it has crossed y = 1 and visits one child there, not two. The planes lose the root's
/// share only (the first child below it follows from 1.5); the descents and leaves follow.
#[test]
fn a_slip_that_changes_the_branching_is_charged_once() {
    let planes = r#"planes = [{ node = [], t = 1.5, first = "x>=3" }, { node = ["x>=3"], t = 3, first = "y<3" }, { node = ["x<3"], t = 1, first = "y>=1" }]"#;
    let rest = r#"descents = [{ path = ["x>=3"], tmin = 0, tmax = 1.5 }, { path = ["x>=3", "y<3"], tmin = 0, tmax = 1.5 }, { path = ["x<3"], tmin = 1.5, tmax = "inf" }, { path = ["x<3", "y>=1"], tmin = 1.5, tmax = "inf" }]
leaves = [{ path = ["x>=3", "y<3"], tmin = 0, tmax = 1.5 }, { path = ["x<3", "y>=1"], tmin = 1.5, tmax = "inf" }]"#;
    let key = variant("q3", 3).unwrap();
    let Expected::Planes { steps, .. } = &key.parts.iter().find(|p| p.key == "q3d.planes").unwrap().expected else {
        unreachable!()
    };
    assert_eq!((steps[0].t, steps[2].first.as_str()), (Some(0.5), "y<1"), "the case this test is about");
    let report = check(&format!("[meta]\nseed = 3\n[q3d]\n{planes}\n{rest}\n"), None).unwrap();
    let p = part(&report, "q3d.planes");
    assert_eq!((p.score, p.mistake), (1.0, Some("carried_forward")), "{p:?}");
    assert!(p.feedback.contains("2 more planes right as they follow from your t"), "{}", p.feedback);
    for (key, points) in [("q3d.descents", 1.5), ("q3d.leaves", 3.0)] {
        let p = part(&report, key);
        assert_eq!((p.score, p.mistake), (points, Some("carried_forward")), "{p:?}");
    }
    // Without planes the slip is charged in the descents, and the leaves follow from them.
    let report = check(&format!("[meta]\nseed = 3\n[q3d]\n{rest}\n"), None).unwrap();
    assert!(part(&report, "q3d.descents").score < 1.5);
    let leaves = part(&report, "q3d.leaves");
    assert_eq!((leaves.score, leaves.mistake), (3.0, Some("carried_forward")), "{leaves:?}");
    // A wrong first child below the slip is a mistake of method even so: the leaves that repeat
    // it are graded against the key.
    let swapped = rest.replace(
        r#"{ path = ["x<3", "y>=1"], tmin = 1.5, tmax = "inf" }]"#,
        r#"{ path = ["x<3", "y<1"], tmin = 1.5, tmax = "inf" }]"#,
    );
    let report = check(&format!("[meta]\nseed = 3\n[q3d]\n{swapped}\n"), None).unwrap();
    let leaves = part(&report, "q3d.leaves");
    assert!(
        leaves.feedback.contains("do not follow the traversal from the plane parameters they show"),
        "{}",
        leaves.feedback
    );
}

/// When only part of a list follows from the student's earlier answer, the feedback names what is
/// still wrong against the student's own values (seed 3, case (d): the plane y = 1 taken at 1.25,
/// and the descent into y < 1 left unclipped).
#[test]
fn what_is_wrong_against_your_own_values_is_named() {
    let text = r#"[meta]
seed = 3
[q3d]
planes = [{ node = [], t = 0.5, first = "x>=3" }, { node = ["x>=3"], t = 3, first = "y<3" }, { node = ["x<3"], t = 1.25, first = "y<1" }]
descents = [{ path = ["x>=3"], tmin = 0, tmax = 0.5 }, { path = ["x>=3", "y<3"], tmin = 0, tmax = 0.5 }, { path = ["x<3"], tmin = 0.5, tmax = "inf" }, { path = ["x<3", "y<1"], tmin = 0.5, tmax = "inf" }, { path = ["x<3", "y>=1"], tmin = 1.25, tmax = "inf" }]
"#;
    let report = check(text, None).unwrap();
    let p = part(&report, "q3d.descents");
    assert_eq!(p.score, 1.2, "{p:?}");
    assert!(p.feedback.starts_with("80 % of it follows from your `q3d.planes`"), "{}", p.feedback);
    assert!(
        p.feedback
            .contains("against the values you had: first 3 descents right; descent 4 [x<3, y<1]: tmax should be 1.25"),
        "{}",
        p.feedback
    );
}

/// The accepted range printed for a number never contradicts the verdict for an answer written
/// with six significant digits: rounded just outside the range it is wrong and printed outside;
/// the key so rounded is right and printed inside (Q1's gap fraction, seeds 0..200, where it
/// spans 10⁻¹² to 0.9).
#[test]
fn an_accepted_range_is_never_rounded_onto_a_wrong_answer() {
    let six_digits = |x: f64| -> f64 { format!("{x:.5e}").parse().unwrap() };
    for seed in 0..200 {
        let key = variant("q1", seed).unwrap();
        let Expected::Number { value, rtol, atol } =
            key.parts.iter().find(|p| p.key == "q1a.gap_fraction").unwrap().expected
        else {
            unreachable!()
        };
        let allowed = rtol * value.abs() + atol;
        let mut outside = [six_digits(value + allowed), six_digits(value - allowed)];
        let unit = |x: f64| 10f64.powi(x.abs().log10().floor() as i32 - 5);
        if outside[0] <= value + allowed {
            outside[0] += unit(outside[0]);
        }
        if outside[1] >= value - allowed {
            outside[1] -= unit(outside[1]);
        }
        for (given, right) in [(outside[0], false), (outside[1], false), (six_digits(value), true)] {
            let result = graded("q1", seed, "q1a.gap_fraction", &format!("{given:e}"));
            assert_eq!(result.status == "correct", right, "seed {seed}: {given:e}: {}", result.feedback);
            if right {
                continue;
            }
            let range = result.feedback.split("accepted: ").nth(1).unwrap();
            let (low, high) = range.split_once(" to ").unwrap();
            let high = high.split(|c: char| !(c.is_ascii_digit() || "-+.e".contains(c))).next().unwrap();
            let (low, high): (f64, f64) = (low.parse().unwrap(), high.parse().unwrap());
            assert!(!(low..=high).contains(&given), "seed {seed}: {given:e} printed inside [{low}, {high}]");
        }
    }
}

/// A t so large that the point's squared length overflows does not make any point "follow" from
/// it (seed 1: with t = 10¹⁵⁵ the recomputed point's tolerance was infinite).
#[test]
fn a_huge_t_does_not_make_any_point_right() {
    for t in ["1e155", "1e200", "1e300"] {
        let report = check(&format!("[meta]\nseed = 1\n[q2a]\nt = {t}\npoint = [7, 7, 7]\n"), None).unwrap();
        let point = part(&report, "q2a.point");
        assert_eq!((point.score, point.status), (0.0, "wrong"), "t = {t}: {point:?}");
    }
}

/// A decimal answer at either printed end of the accepted range is accepted: the key ± its
/// tolerance computed in binary lands a rounding error away from the decimal (seed 116's q1d key
/// is 2 with 1 %; seed 3's q2c key is −2 with 0.1 %).
#[test]
fn a_decimal_answer_at_the_end_of_the_range_is_accepted() {
    for (seed, key, value, outside) in [
        (116, "q1d.pixels_per_frame", "1.98", "1.9799"),
        (116, "q1d.pixels_per_frame", "2.02", "2.0201"),
        (3, "q2c.t_closest", "-1.998", "-1.9979"),
        (3, "q2c.t_closest", "-2.002", "-2.0021"),
    ] {
        let question = &key[..2];
        let result = graded(question, seed, key, value);
        assert_eq!(result.status, "correct", "seed {seed} {key} = {value}: {}", result.feedback);
        assert_eq!(graded(question, seed, key, outside).status, "wrong", "seed {seed} {key} = {outside}");
    }
}

/// A plane parameter with its sign flipped is a wrong formula, not a slip: what follows from it is
/// not carried (seed 3, case (e): t = +1 at the root instead of −1, then the near child first, as
/// the sign of d would suggest; the ray never enters x ≥ 3).
#[test]
fn a_flipped_sign_is_not_followed() {
    let text = r#"[meta]
seed = 3
[q3e]
planes = [{ node = [], t = 1, first = "x>=3" }, { node = ["x>=3"], t = 1, first = "y>=3" }, { node = ["x<3"], t = 3, first = "y>=1" }]
descents = [{ path = ["x>=3"], tmin = 0, tmax = 1 }, { path = ["x>=3", "y>=3"], tmin = 0, tmax = 1 }, { path = ["x<3"], tmin = 1, tmax = "inf" }, { path = ["x<3", "y>=1"], tmin = 1, tmax = 3 }, { path = ["x<3", "y<1"], tmin = 3, tmax = "inf" }]
leaves = [{ path = ["x>=3", "y>=3"], tmin = 0, tmax = 1 }, { path = ["x<3", "y>=1"], tmin = 1, tmax = 3 }, { path = ["x<3", "y<1"], tmin = 3, tmax = "inf" }]
"#;
    let report = check(text, None).unwrap();
    let planes = part(&report, "q3e.planes");
    assert!(planes.feedback.contains("sign error"), "{}", planes.feedback);
    for key in ["q3e.planes", "q3e.descents", "q3e.leaves"] {
        let p = part(&report, key);
        assert_ne!(p.mistake, Some("carried_forward"), "{p:?}");
        assert!(p.score < 0.75 * p.max_score, "{p:?}");
    }
}

/// The leaves follow from the student's planes when the descents are missing (seed 3, case (d),
/// the root crossed at 1.5 instead of 0.5), and when the descents repeat a mistake of method the
/// leaves do not (tmin kept at 0 in the descents only).
#[test]
fn leaves_follow_from_the_planes_when_the_descents_cannot_lead() {
    let planes = r#"planes = [{ node = [], t = 1.5, first = "x>=3" }, { node = ["x>=3"], t = 3, first = "y<3" }, { node = ["x<3"], t = 1, first = "y>=1" }]"#;
    let leaves = r#"leaves = [{ path = ["x>=3", "y<3"], tmin = 0, tmax = 1.5 }, { path = ["x<3", "y>=1"], tmin = 1.5, tmax = "inf" }]"#;
    let report = check(&format!("[meta]\nseed = 3\n[q3d]\n{planes}\n{leaves}\n"), None).unwrap();
    let p = part(&report, "q3d.leaves");
    assert_eq!((p.score, p.mistake), (3.0, Some("carried_forward")), "{p:?}");
    assert!(p.feedback.starts_with("follows from your `q3d.planes`"), "{}", p.feedback);
    let descents = r#"descents = [{ path = ["x>=3"], tmin = 0, tmax = 1.5 }, { path = ["x>=3", "y<3"], tmin = 0, tmax = 1.5 }, { path = ["x<3"], tmin = 0, tmax = "inf" }, { path = ["x<3", "y>=1"], tmin = 0, tmax = "inf" }]"#;
    let report = check(&format!("[meta]\nseed = 3\n[q3d]\n{planes}\n{descents}\n{leaves}\n"), None).unwrap();
    let p = part(&report, "q3d.leaves");
    assert_eq!((p.score, p.mistake), (3.0, Some("carried_forward")), "{p:?}");
}

/// Only a slip is followed: one wrong plane parameter of the right sign that is not another
/// plane's. Invented values that make the trace trivial, a t of the other sign, and another
/// plane's t earn nothing downstream (seed 2 and seed 3, case (d)).
#[test]
fn only_a_slip_is_followed() {
    let invented = r#"[meta]
seed = 2
[q3d]
planes = [{ node = [], t = -7, first = "x<3" }, { node = ["x<3"], t = -7, first = "y<1" }]
descents = [{ path = ["x<3"], tmin = 0, tmax = "inf" }, { path = ["x<3", "y<1"], tmin = 0, tmax = "inf" }]
leaves = [{ path = ["x<3", "y<1"], tmin = 0, tmax = "inf" }]
"#;
    let report = check(invented, None).unwrap();
    for key in ["q3d.descents", "q3d.leaves"] {
        let p = part(&report, key);
        assert!(p.mistake != Some("carried_forward") && p.score < p.max_score, "{p:?}");
    }
    // Seed 3, case (d): the root plane x = 3 is met at t = 0.5, the plane y = 3 at t = 3.
    let root = |t: &str, tmax: &str| {
        format!(
            "[meta]\nseed = 3\n[q3d]\nplanes = [{{ node = [], t = {t}, first = \"x>=3\" }}, {{ node = [\"x>=3\"], t = 3, first = \"y<3\" }}]\ndescents = [{{ path = [\"x>=3\"], tmin = 0, tmax = {tmax} }}, {{ path = [\"x>=3\", \"y<3\"], tmin = 0, tmax = {tmax} }}]\n"
        )
    };
    for (t, why) in [("3", "another plane's t"), ("-0.50001", "the other sign")] {
        let report = check(&root(t, t), None).unwrap();
        let p = part(&report, "q3d.descents");
        assert!(p.feedback.contains("are not the traversal's with one slip of arithmetic"), "{why}: {p:?}");
        assert!(p.score < 1.0, "{why}: {p:?}");
    }
}

/// A formula right only for an eye outside the sphere is wrong: the comparison points include eyes
/// inside, where C < 0 and n · d > 0 (the forms a student might reach for with abs or max).
#[test]
fn a_formula_right_only_from_outside_is_wrong() {
    for (key, formula) in [
        ("q2a.C", "abs(dot(e - o, e - o) - r^2)"),
        ("q2a.C", "max(0, dot(e - o, e - o) - r^2)"),
        ("q2a.C", "abs(r^2 - dot(e - o, e - o))"),
        ("q2b.reflected_formula", "dhat + 2*abs(dot(n, dhat))*n"),
        ("q2b.reflected_formula", "dhat + 2*max(0, -dot(n, dhat))*n"),
    ] {
        let result = graded("q2", 0, key, &format!("\"{formula}\""));
        assert_eq!(result.status, "wrong", "{key} = {formula}: {}", result.feedback);
    }
    for (key, formula) in [("q2a.C", "dot(e - o, e - o) - r^2"), ("q2b.reflected_formula", "dhat - 2*dot(n, dhat)*n")] {
        assert_eq!(graded("q2", 0, key, &format!("\"{formula}\"")).status, "correct", "{key} = {formula}");
    }
}

/// Descents with bounds made up to fit (two wrong crossings, no planes) do not carry into the
/// leaves: one wrong value is a slip, two are not (seed 3, case (d), crossings 0.5 and 1 written
/// as 1 and 2).
#[test]
fn made_up_bounds_do_not_carry_into_the_leaves() {
    let text = r#"[meta]
seed = 3
[q3d]
descents = [{ path = ["x>=3"], tmin = 0, tmax = 1 }, { path = ["x>=3", "y<3"], tmin = 0, tmax = 1 }, { path = ["x<3"], tmin = 1, tmax = "inf" }, { path = ["x<3", "y<1"], tmin = 1, tmax = 2 }, { path = ["x<3", "y>=1"], tmin = 2, tmax = "inf" }]
leaves = [{ path = ["x>=3", "y<3"], tmin = 0, tmax = 1 }, { path = ["x<3", "y<1"], tmin = 1, tmax = 2 }, { path = ["x<3", "y>=1"], tmin = 2, tmax = "inf" }]
"#;
    let report = check(text, None).unwrap();
    let leaves = part(&report, "q3d.leaves");
    assert!(leaves.score < 3.0, "{leaves:?}");
    assert!(leaves.feedback.contains("your descents do not follow the traversal"), "{}", leaves.feedback);
    // One wrong crossing (0.5 written as 0.75) is a slip, and the leaves follow.
    let one = r#"[meta]
seed = 3
[q3d]
descents = [{ path = ["x>=3"], tmin = 0, tmax = 0.75 }, { path = ["x>=3", "y<3"], tmin = 0, tmax = 0.75 }, { path = ["x<3"], tmin = 0.75, tmax = "inf" }, { path = ["x<3", "y<1"], tmin = 0.75, tmax = 1 }, { path = ["x<3", "y>=1"], tmin = 1, tmax = "inf" }]
leaves = [{ path = ["x>=3", "y<3"], tmin = 0, tmax = 0.75 }, { path = ["x<3", "y<1"], tmin = 0.75, tmax = 1 }, { path = ["x<3", "y>=1"], tmin = 1, tmax = "inf" }]
"#;
    let report = check(one, None).unwrap();
    let leaves = part(&report, "q3d.leaves");
    assert_eq!((leaves.score, leaves.mistake), (3.0, Some("carried_forward")), "{leaves:?}");
}
