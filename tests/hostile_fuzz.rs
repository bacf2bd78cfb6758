//! Generated hostile input for five entry points, with the invariants each must keep: the
//! answers-file reader and grader, the `.hdr` map reader behind `hw3 irradiance`, the command
//! line's number and vector parsers, the sphere solver, and the kd-tree query.
//!
//! Each target is a seeded proptest run (the same inputs every time), short by default so that
//! `cargo test` stays fast; `HW3_FUZZ_CASES=1000000 cargo test --release --test integration hostile_fuzz::`
//! runs 10⁶ inputs per target (the counts and times are in the README's "Exit statuses and
//! limits").

use glam::DVec3;
use hw3::geometry::{Ray, Sphere};
use hw3::q2_ray_sphere::catalogue::quotient;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use twofloat::TwoFloat;

/// Inputs per target: `HW3_FUZZ_CASES`, or `default` (sized for a few seconds in all).
fn cases(default: u32) -> u32 {
    std::env::var("HW3_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// A deterministic runner: the same inputs on every machine, no persisted failures.
fn runner(cases: u32) -> TestRunner {
    let config = Config { cases, failure_persistence: None, max_shrink_iters: 256, ..Config::default() };
    TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha))
}

/// Runs `test` on `cases` values of `strategy`, panicking with the smallest failing input.
fn fuzz<S: Strategy>(name: &str, cases: u32, strategy: S, test: impl Fn(S::Value) -> Result<(), TestCaseError>)
where
    S::Value: std::fmt::Debug,
{
    let start = std::time::Instant::now();
    if let Err(e) = runner(cases).run(&strategy, test) {
        panic!("{name}: {e}");
    }
    eprintln!("fuzz {name}: {cases} inputs, 0 failures, {:.1} s", start.elapsed().as_secs_f64());
}

/// A float from every region that breaks arithmetic: zeros, subnormals, huge, ordinary, and
/// the non-finite values.
fn hostile_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -10.0..10.0f64,
        2 => any::<f64>(),
        1 => prop::sample::select(vec![
            0.0, -0.0, 1e-310, -1e-310, f64::MIN_POSITIVE, 1e-160, 1e154, 1.4e154, 1e300, f64::MAX, -f64::MAX,
            f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 1e16, -1e16, 1e20, 3.4e38, 1e-45,
        ]),
        1 => (-60i32..60, -1.0..1.0f64).prop_map(|(e, m)| m * 10f64.powi(e)),
    ]
}

fn hostile_vec3() -> impl Strategy<Value = DVec3> {
    (hostile_f64(), hostile_f64(), hostile_f64()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

// ---------------------------------------------------------------------------------------------
// 1. The answers-file reader and grader (`hw3::checker`).

const SEED_FILE: &str = include_str!("answers/seed_hw3.toml");

/// Text near the checker's format: the seed's own file with bytes edited, keys of the template
/// with values of every TOML type, or any string.
fn answers_text() -> impl Strategy<Value = String> {
    let keys: Vec<String> = hw3::checker::template(0)
        .unwrap()
        .lines()
        .filter_map(|line| line.strip_prefix("# ").and_then(|l| l.split_once(" = ")).map(|(k, _)| k.to_owned()))
        .filter(|k| !k.contains(' '))
        .chain(["seed".into(), "meta".into(), "q2a".into(), "leaves".into(), "unknown".into()])
        .collect();
    let value = prop_oneof![
        hostile_f64().prop_map(|x| format!("{x:?}").replace("NaN", "nan")),
        any::<i64>().prop_map(|i| i.to_string()),
        "[a-z<>=0-9,\\[\\]{} \"-]{0,40}".prop_map(|s| format!("\"{s}\"")),
        Just("[1, 2, 3]".to_owned()),
        Just("{ path = [\"x>=3\", \"y<3\"], tmin = 0, tmax = \"inf\" }".to_owned()),
        Just("[{ path = [\"x<3\"], tmin = -1, tmax = 1e400 }]".to_owned()),
        Just("true".to_owned()),
        Just("\"\\u001b[2J\"".to_owned()),
        Just("1979-05-27T07:32:00Z".to_owned()),
    ];
    let line = (prop::sample::select(keys), value).prop_map(|(k, v)| format!("{k} = {v}\n"));
    let section = prop::sample::select(vec!["[meta]\n", "[q2a]\n", "[q3d]\n", "[q4b]\n", "[q5]\n", "[[q3d]]\n", ""]);
    let structured = prop::collection::vec((section, line), 0..12)
        .prop_map(|parts| parts.into_iter().map(|(s, l)| format!("{s}{l}")).collect::<String>());
    let edits = prop::collection::vec((any::<prop::sample::Index>(), 0u8..4, any::<char>()), 1..8).prop_map(|edits| {
        let mut text: Vec<char> = SEED_FILE.chars().collect();
        for (at, op, c) in edits {
            let i = at.index(text.len().max(1)).min(text.len());
            match op {
                0 if i < text.len() => {
                    text.remove(i);
                }
                1 => text.insert(i, c),
                2 if i < text.len() => text[i] = c,
                _ => {
                    let digit = char::from(b'0' + (u32::from(c) % 10) as u8);
                    text.insert(i, digit);
                }
            }
        }
        text.into_iter().collect::<String>()
    });
    prop_oneof![3 => structured, 3 => edits, 1 => any::<String>()]
}

/// Seeds to grade against: the file's own (`None`: its `[meta] seed`, whatever the edits made of
/// it), one of 64 small seeds (so that the checker's variant cache is exercised as a grader
/// uses it, many files of few seeds), or rarely any `u64` (each a new variant, and the values a
/// file cannot store).
fn check_seeds() -> impl Strategy<Value = Option<u64>> {
    prop_oneof![8 => Just(None), 8 => (0u64..64).prop_map(Some), 1 => any::<u64>().prop_map(Some)]
}

#[test]
fn fuzz_answers_reader_and_grader() {
    use std::collections::HashSet;
    use std::sync::Mutex;
    use std::sync::atomic::{AtomicU64, Ordering};
    let (graded, refused) = (AtomicU64::new(0), AtomicU64::new(0));
    let seeds = Mutex::new(HashSet::new());
    fuzz("checker", cases(400), (answers_text(), check_seeds()), |(text, seed)| {
        match hw3::checker::check(&text, seed) {
            Ok(report) => {
                graded.fetch_add(1, Ordering::Relaxed);
                seeds.lock().unwrap().insert(report.seed);
                let shown = hw3::checker::report_text(&report);
                prop_assert!(shown.contains("score"), "{shown}");
                prop_assert!(report.score <= report.max_score, "{shown}");
                let _ = hw3::checker::report_gradescope(&report);
                prop_assert!(serde_json::to_string(&report).is_ok());
            }
            Err(error) => {
                refused.fetch_add(1, Ordering::Relaxed);
                prop_assert!(!error.to_string().is_empty());
            }
        }
        Ok(())
    });
    eprintln!(
        "fuzz checker: {} graded ({} distinct seeds), {} refused as bad input",
        graded.into_inner(),
        seeds.into_inner().unwrap().len(),
        refused.into_inner()
    );
}

/// Every template a user can ask for reads back, all blank (nothing correct); variants and keys of
/// any seed and any question id never panic. A template and its check build the seed's five
/// variants once (the second use is the checker's cache), so each input costs one seed's
/// variants.
#[test]
fn fuzz_templates_and_variants_of_any_seed() {
    let question = prop::sample::select(vec!["q1", "q2", "q3", "q4", "q5", "", "Q2", "q2 "]);
    let seed = prop_oneof![any::<u64>(), 0u64..1024, (0u32..64).prop_map(|k| (1u64 << k).wrapping_sub(1))];
    fuzz("checker seeds", cases(8), (question, seed), |(question, seed)| {
        let template = hw3::checker::template(seed);
        if seed <= hw3::cli::MAX_SEED {
            let report = hw3::checker::check(&template.unwrap(), None);
            prop_assert!(report.is_ok(), "seed {seed}: {report:?}");
            let report = report.unwrap();
            prop_assert!(report.seed == seed && report.score == 0.0, "seed {seed}: {report:?}");
        }
        let _ = hw3::checker::variant(question, seed);
        let _ = hw3::checker::answer_key_for(question, seed);
        Ok(())
    });
}

// ---------------------------------------------------------------------------------------------
// 2. The `.hdr` reader, as `hw3 irradiance --env FILE` runs it: the header check, then the decoder.

/// A Radiance file: a real header (or a broken one) and random or run-length-looking pixel bytes.
fn hdr_bytes() -> impl Strategy<Value = Vec<u8>> {
    let magic = prop::sample::select(vec!["#?RADIANCE\n", "#?RGBE\n", "#?RADIANCE", "\u{89}PNG\r\n", ""]);
    let format =
        prop::sample::select(vec!["FORMAT=32-bit_rle_rgbe\n", "FORMAT=32-bit_rle_xyze\n", "", "EXPOSURE=1e400\n"]);
    let dims = prop_oneof![
        (1u64..40, 1u64..80).prop_map(|(h, w)| format!("-Y {h} +X {w}\n")),
        (0u64..u64::MAX, 0u64..u64::MAX).prop_map(|(h, w)| format!("-Y {h} +X {w}\n")),
        "[-+XY0-9 ]{0,20}\n",
    ];
    let body = prop_oneof![
        prop::collection::vec(any::<u8>(), 0..4096),
        (prop::collection::vec(any::<u8>(), 0..64), 1usize..64).prop_map(|(chunk, n)| chunk.repeat(n)),
        (1u8..255, prop::collection::vec(any::<u8>(), 0..512)).prop_map(|(w, rest)| [vec![2, 2, 0, w], rest].concat()),
    ];
    (magic, format, dims, body).prop_map(|(m, f, d, b)| [m.as_bytes(), f.as_bytes(), b"\n", d.as_bytes(), &b].concat())
}

#[test]
fn fuzz_hdr_reader() {
    let dir = std::env::temp_dir().join(format!("hw3-fuzz-hdr-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("map.hdr");
    fuzz("hdr reader", cases(300), hdr_bytes(), |bytes| {
        std::fs::write(&path, &bytes).unwrap();
        if hw3::cli::check_hdr_file(&path, false).is_ok()
            && let Ok(probe) = hw3::envmap::Probe::read_lat_long(&path)
        {
            let texels = probe.width() as u64 * probe.height() as u64;
            prop_assert!(texels <= hw3::cli::MAP_TEXELS.max);
            prop_assert!(probe.texels().iter().all(|t| t.radiance.is_finite() && t.radiance.min_element() >= 0.0));
        }
        Ok(())
    });
    std::fs::remove_dir_all(&dir).unwrap();
}

// ---------------------------------------------------------------------------------------------
// 3. The command line's number and vector parsers, and the message cleaner.

fn number_text() -> impl Strategy<Value = String> {
    prop_oneof![
        "[-+0-9.eExX, ]{0,30}",
        hostile_f64().prop_map(|x| x.to_string()),
        any::<u64>().prop_map(|x| x.to_string()),
        any::<i64>().prop_map(|x| x.to_string()),
        (hostile_f64(), hostile_f64(), hostile_f64()).prop_map(|(x, y, z)| format!("{x},{y},{z}")),
        any::<String>(),
    ]
}

#[test]
fn fuzz_cli_number_and_vector_parsing() {
    fuzz("cli parsers", cases(3000), number_text(), |text| {
        if let Ok(v) = hw3::geometry::parse_vec3("--origin", &text) {
            prop_assert_eq!(text.split(',').count(), 3);
            let _ = v;
        }
        if let Ok(n) = hw3::cli::parse_unsigned(&text, 1000) {
            prop_assert!(n <= 1000);
            prop_assert!(text.bytes().all(|b| b.is_ascii_digit()));
            prop_assert_eq!(Ok(n), text.parse::<u64>());
        }
        if let Ok(seed) = hw3::cli::parse_seed(&text) {
            prop_assert!(seed <= hw3::cli::MAX_SEED);
        }
        if let Ok((w, h)) = hw3::cli::parse_size(&text, 8192) {
            prop_assert!((1..=8192).contains(&w) && (1..=8192).contains(&h));
        }
        let _ = hw3::q3_kd_traversal::kd_trace_command(&text, "1,0", false);
        let _ = hw3::q3_kd_traversal::kd_trace_command("5,0", &text, true);
        let line = hw3::cli::one_line(&text);
        prop_assert!(!line.chars().any(char::is_control));
        prop_assert!(line.chars().count() <= hw3::cli::MESSAGE_CHARS + 32);
        prop_assert!(hw3::cli::quote(&text).chars().count() <= hw3::cli::QUOTE_CHARS * 10 + 32);
        Ok(())
    });
}

// ---------------------------------------------------------------------------------------------
// 4. The sphere solver, as `hw3 sphere` runs it, against a double-double reference.

/// The roots `t` (near, far) with the hit's normal at each, in double-double arithmetic from the
/// exact inputs, through the Lagrange form of the discriminant.
fn reference_roots(e: DVec3, d: DVec3, o: DVec3, r: f64) -> Option<[(f64, DVec3); 2]> {
    let two = TwoFloat::from;
    let f = [TwoFloat::new_add(e.x, -o.x), TwoFloat::new_add(e.y, -o.y), TwoFloat::new_add(e.z, -o.z)];
    let d = [two(d.x), two(d.y), two(d.z)];
    let dot = |a: [TwoFloat; 3], b: [TwoFloat; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = [f[1] * d[2] - f[2] * d[1], f[2] * d[0] - f[0] * d[2], f[0] * d[1] - f[1] * d[0]];
    let a = dot(d, d);
    let disc_a = TwoFloat::new_mul(r, r) * a - dot(cross, cross);
    if disc_a < two(0.0) {
        return None;
    }
    let t_ca = quotient(-dot(f, d), a);
    let h = quotient(disc_a.sqrt(), a);
    let at = |t: TwoFloat| {
        let radial = [f[0] + t * d[0], f[1] + t * d[1], f[2] + t * d[2]];
        let unit = |x: TwoFloat| f64::from(quotient(x, two(r)));
        (f64::from(t), DVec3::new(unit(radial[0]), unit(radial[1]), unit(radial[2])))
    };
    Some([at(t_ca - h), at(t_ca + h)])
}

fn sphere_case() -> impl Strategy<Value = (DVec3, DVec3, DVec3, f64)> {
    let ordinary = (
        prop::collection::vec(-10.0..10.0f64, 9),
        prop_oneof![0.01..10.0f64, (-40i32..40).prop_map(|e| 10f64.powi(e))],
        -30i32..30,
    )
        .prop_map(|(v, r, scale)| {
            let s = 10f64.powi(scale);
            (DVec3::new(v[0], v[1], v[2]) * s, DVec3::new(v[3], v[4], v[5]), DVec3::new(v[6], v[7], v[8]) * s, r * s)
        });
    prop_oneof![3 => ordinary, 1 => (hostile_vec3(), hostile_vec3(), hostile_vec3(), hostile_f64())]
}

#[test]
fn fuzz_sphere_solver() {
    use hw3::q2_ray_sphere::catalogue::{Precision, Solver};
    let variant = prop::sample::select(hw3::q2_ray_sphere::catalogue::VARIANTS.to_vec());
    fuzz("sphere solver", cases(3000), (sphere_case(), variant), |((e, d, o, r), (method, precision))| {
        let (Ok(ray), Ok(sphere)) = (Ray::new(e, d), Sphere::new(o, r)) else { return Ok(()) };
        let Ok(answer) = hw3::q2_ray_sphere::solve(&ray, &sphere, method, precision) else { return Ok(()) };
        prop_assert!(answer.closest_approach_t.is_finite());
        let Some(t) = answer.t else {
            prop_assert!(!answer.hit && answer.point.is_none() && answer.normal.is_none());
            return Ok(());
        };
        // A hit: every number finite, t > 0, a unit normal, the reflection a unit vector.
        prop_assert!(answer.hit && t.is_finite() && t > 0.0, "t = {t}");
        let numbers = [answer.point.unwrap(), answer.normal.unwrap(), answer.reflected_dir.unwrap()];
        prop_assert!(numbers.iter().flatten().all(|x| x.is_finite()), "{answer:?}");
        let normal = DVec3::from(answer.normal.unwrap());
        let unit_tolerance = if precision == Precision::F32 { 1e-5 } else { 1e-12 };
        if method == Solver::Stable {
            prop_assert!((normal.length() - 1.0).abs() < unit_tolerance, "|n| = {}", normal.length());
            // On the sphere to within the point's stated error bound (the exact hit is on it).
            let point = DVec3::from(answer.point.unwrap());
            let bound = DVec3::from(answer.point_error.unwrap()).length();
            prop_assert!(((point - o).length() - r).abs() <= r / 64.0 + bound, "point off the sphere: {answer:?}");
        }
        // Against the reference, for f64 and the stable method, where the chord is not grazing.
        if method == Solver::Stable
            && precision == Precision::F64
            && let Some(roots) = reference_roots(e, d, o, r)
        {
            let s = [e.abs().max_element(), o.abs().max_element(), (e - o).abs().max_element()]
                .into_iter()
                .fold(r, f64::max);
            let chord = (r * r - ((e - o).cross(d).length() / d.length()).powi(2)).max(0.0).sqrt();
            let tolerance = 32.0 * f64::EPSILON * s / d.length();
            // A root within rounding of 0 (the eye on the sphere) may fall on either side of the
            // policy "t = 0 is not a hit": the solver may then report the other root.
            let candidates: Vec<(f64, DVec3)> = if roots[0].0.abs() <= tolerance {
                roots.into_iter().filter(|&(t, _)| t > -tolerance).collect()
            } else {
                roots.into_iter().filter(|&(t, _)| t > 0.0).take(1).collect()
            };
            let nearest = candidates.into_iter().min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()));
            if chord > r / 4.0
                && let Some((t_ref, n_ref)) = nearest
            {
                prop_assert!((t - t_ref).abs() <= tolerance, "t {t} vs {t_ref} (tolerance {tolerance:e})");
                prop_assert!((normal - n_ref).length() <= 32.0 * f64::EPSILON * s / r, "n {normal} vs {n_ref}");
            }
        }
        Ok(())
    });
}

// ---------------------------------------------------------------------------------------------
// 5. The kd-tree query: the same answer as testing every sphere.

#[test]
fn fuzz_kdtree_query() {
    let spheres = prop::collection::vec(
        (prop::collection::vec(-20.0..20.0f64, 3), prop_oneof![0.01..5.0f64, Just(1e-6), Just(50.0)]),
        1..24,
    );
    let ray = (hostile_vec3(), hostile_vec3(), hostile_f64(), hostile_f64());
    let rays = prop::collection::vec(ray, 16);
    // Counted per query: each tree answers 16 rays.
    let count = cases(3000).div_ceil(16);
    fuzz("kd-tree query (x16 rays)", count, (spheres, rays), |(spheres, rays)| {
        let spheres: Vec<Sphere<f64>> =
            spheres.into_iter().filter_map(|(c, r)| Sphere::new(DVec3::new(c[0], c[1], c[2]), r).ok()).collect();
        let tree = hw3::kdtree::KdTree::build(&spheres).unwrap();
        for (origin, dir, t_min, t_max) in rays {
            let Ok(ray) = Ray::new(origin, dir) else { continue };
            let (t_min, t_max) = if t_min.is_nan() || t_max.is_nan() { (0.0, f64::INFINITY) } else { (t_min, t_max) };
            let tree_hit = tree.closest_hit(&ray, t_min, t_max);
            // The answers must agree where the problem is within f64's reach for every sphere (the
            // bounded solver answers it); beyond it (an eye 10²⁰ away from spheres of radius 4), the
            // query must only not panic: there the cells' entry parameters round to one value.
            let resolvable = spheres.iter().all(|s| {
                use hw3::geometry::sphere::{BoundedOutcome, bounded_first_hit};
                matches!(bounded_first_hit(&ray, s), Ok(BoundedOutcome::Hit(_) | BoundedOutcome::Miss))
            });
            if resolvable {
                let brute = hw3::kdtree::brute_force_closest_hit(&spheres, &ray, t_min, t_max);
                prop_assert_eq!(tree_hit, brute, "ray {:?} in ({}, {})", ray, t_min, t_max);
            }
        }
        Ok(())
    });
}
