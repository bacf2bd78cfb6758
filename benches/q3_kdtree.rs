//! Q3 cost versus scene size: builds the crate's SAH kd-tree for the benchmark workload
//! (`kdtree-perf.md` §5: N = 10² … 10⁵ random spheres, both density scalings, 512×512 camera rays
//! and 10⁶ random rays, t_min = 10⁻⁴), measures build time and closest-hit rays per second on one
//! thread, counts nodes and sphere tests per ray, checks the benchmark's checksums, times brute force
//! as a peer where it is affordable (and checks the tree against it ray by ray there), and writes
//! `docs/data/q3_kdtree_perf.csv` and `.md`, from which the notes' plot is drawn.
//!
//! Peers in the same run, on the same rays (`q3_kdtree/peers.rs`): the `bvh` crate and `obvhs`
//! BVH2 and CWBVH, each on the `f32` scene, and with `--features embree` the system's Embree 3
//! (`q3_kdtree/embree.rs`); every peer answer is checked against the kd-tree ray by
//! ray (a mismatch is a different sphere, or hit versus miss), and the benchmark's ray #839 669 with
//! direction (−0, −0, −1) is a named probe in every configuration.
//!
//! Batch rounds of their own (`batch_rounds`) time the tree's batch query [`KdTree::closest_hits`]
//! (asserted equal to the single-ray answers, bit for bit) beside the tree ray by ray and Embree's
//! single-ray, stream (`rtcIntersect1M`) and 8-wide packet (`rtcIntersect8`) calls.
//!
//! Beside the crate's `f64` tree runs its `f32` copy ([`KdTreeF32`], on the `f32` rays); its
//! accuracy cost is counted twice per scene: rays where it names another sphere than the `f64`
//! tree, and, on those rays, which of the two answers a double-double evaluation of both
//! candidates confirms.
//!
//! `cargo bench -p hw3-benches --bench q3_kdtree` measures and writes (`HW3_Q3_MAX_N=1000000` adds N = 10⁶;
//! `HW3_Q3_KI`, `HW3_Q3_EMPTY_BONUS`, `HW3_Q3_BINS`, `HW3_Q3_MIN_N` make a tuning run that only prints);
//! under `cargo test --benches` it runs one small smoke round and writes nothing.

#[cfg(feature = "embree")]
#[path = "q3_kdtree/embree.rs"]
mod embree;
#[path = "q3_kdtree/peers.rs"]
mod peers;
#[path = "q3_kdtree/workload.rs"]
mod workload;

use hw3::geometry::{Ray, Sphere};
use hw3::kdtree::{HitStats, KdTree, KdTreeF32, SahCosts, brute_force_closest_hit};
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;
use workload::{Density, T_MIN, camera_rays, checksum, random_rays, scene};

type Hit = Option<(usize, f64)>;

/// The contender index of obvhs's CWBVH in the interleaved timings (the kd-tree is 0).
const CWBVH: usize = 3;

/// The benchmark's ray with direction exactly (−0, −0, −1), on which obvhs 0.4's CWBVH can miss.
const PROBE: usize = 839_669;

/// Seconds of the fastest of `repeats` runs of `work`, and its last result.
fn best_of<R>(repeats: usize, mut work: impl FnMut() -> R) -> (f64, R) {
    let mut best = f64::INFINITY;
    let mut result = None;
    for _ in 0..repeats {
        let start = Instant::now();
        let r = black_box(work());
        best = best.min(start.elapsed().as_secs_f64());
        result = Some(r);
    }
    (best, result.expect("at least one repeat"))
}

fn trace_all(tree: &KdTree, rays: &[Ray<f64>]) -> Vec<Hit> {
    rays.iter().map(|r| tree.closest_hit(black_box(r), T_MIN, f64::INFINITY)).collect()
}

/// The batch query over the same rays (the rays passed through `black_box` as one slice).
fn trace_batch(tree: &KdTree, rays: &[Ray<f64>]) -> Vec<Hit> {
    let mut out = vec![None; rays.len()];
    tree.closest_hits(black_box(rays), T_MIN, f64::INFINITY, &mut out);
    out
}

fn brute_all(spheres: &[Sphere<f64>], rays: &[Ray<f64>]) -> Vec<Hit> {
    rays.iter().map(|r| brute_force_closest_hit(spheres, black_box(r), T_MIN, f64::INFINITY)).collect()
}

/// Nodes and sphere tests per ray over the first 65 536 rays (as in the note).
fn work_per_ray(tree: &KdTree, rays: &[Ray<f64>]) -> (f64, f64) {
    let sample = &rays[..rays.len().min(65_536)];
    let mut stats = HitStats::default();
    for r in sample {
        let _ = tree.closest_hit_with_stats(r, T_MIN, f64::INFINITY, &mut stats);
    }
    let n = sample.len() as f64;
    (stats.nodes_visited as f64 / n, stats.sphere_tests as f64 / n)
}

/// The benchmark's checksums (f32, fixed k): (N, camera hits, camera Σt, random hits, random Σt).
const NOTE: [(usize, usize, f64, usize, f64); 5] = [
    (100, 184_983, 223_855.88, 727_694, 96_248.64),
    (1_000, 172_545, 215_827.48, 676_168, 104_288.96),
    (10_000, 172_385, 216_190.76, 652_278, 112_220.02),
    (100_000, 175_400, 221_348.85, 649_661, 117_884.38),
    (1_000_000, 175_441, 221_645.86, 647_497, 119_375.47),
];

/// "ok" when within the benchmark's tolerance for an independent implementation (3 hits, 2·10⁻⁵
/// relative on Σt), else the differences; "-" when the note has no checksum.
fn versus_note(n: usize, density: Density, camera: (usize, f64), random: (usize, f64)) -> String {
    let Some(&(_, ch, ct, rh, rt)) = NOTE.iter().find(|row| row.0 == n) else {
        return "-".into();
    };
    if density != Density::FixedMeanFreePath {
        return "-".into();
    }
    let close = |(h, t): (usize, f64), (eh, et): (usize, f64)| h.abs_diff(eh) <= 3 && ((t - et) / et).abs() < 2e-5;
    if close(camera, (ch, ct)) && close(random, (rh, rt)) {
        "ok".into()
    } else {
        format!(
            "differs: camera {} hits / {:+.1e} rel; random {} hits / {:+.1e} rel",
            camera.0 as i64 - ch as i64,
            (camera.1 - ct) / ct,
            random.0 as i64 - rh as i64,
            (random.1 - rt) / rt
        )
    }
}

fn mrays(count: usize, secs: f64) -> f64 {
    count as f64 / secs / 1e6
}

/// Rays on which a peer names a different sphere than the tree (or hits where it misses).
fn mismatches(peer: &[Hit], tree: &[Hit]) -> usize {
    peer.iter().zip(tree).filter(|(p, t)| p.map(|h| h.0) != t.map(|h| h.0)).count()
}

/// Best seconds per contender, the median per-round time ratio of each contender to the first,
/// and each contender's answers.
struct Timed {
    best_secs: Vec<f64>,
    median_ratio: Vec<f64>,
    /// Seconds of every round, per contender.
    secs: Vec<Vec<f64>>,
    answers: Vec<Vec<Hit>>,
}

impl Timed {
    /// The median over rounds of `secs[slower] / secs[faster]`: how many times faster contender
    /// `faster` ran than `slower` in the same round.
    fn speedup(&self, faster: usize, slower: usize) -> f64 {
        median(self.secs[slower].iter().zip(&self.secs[faster]).map(|(s, f)| s / f).collect())
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Times every contender on the same rays in interleaved rounds (round r runs the kd-tree, then
/// each peer), so that a change of load on the shared machine hits all of them alike and the
/// per-round ratios compare like with like.
fn interleaved(rounds: usize, contenders: &mut [&mut dyn FnMut() -> Vec<Hit>]) -> Timed {
    let count = contenders.len();
    let mut secs = vec![Vec::with_capacity(rounds); count];
    let mut answers = vec![Vec::new(); count];
    for _ in 0..rounds {
        for (c, work) in contenders.iter_mut().enumerate() {
            let (elapsed, hits) = best_of(1, &mut **work);
            secs[c].push(elapsed);
            answers[c] = hits;
        }
    }
    let best_secs = secs.iter().map(|s| s.iter().copied().fold(f64::INFINITY, f64::min)).collect();
    let median_ratio = secs.iter().map(|s| median(s.iter().zip(&secs[0]).map(|(t, kd)| t / kd).collect())).collect();
    Timed { best_secs, median_ratio, secs, answers }
}

/// The camera and random timings of the kd-tree and every peer, with the peers' CSV fields (build
/// ms, camera and random Mrays/s, mismatches against the tree) and the probe's verdict per peer.
struct Run {
    camera: Timed,
    random: Timed,
    peer_fields: String,
    /// Embree's CSV fields (build ms, camera and random Mrays/s, mismatches, kd ÷ Embree speed
    /// camera and random), appended after the older columns; `-` without the `embree` feature.
    embree_fields: String,
    /// The `f32` tree's CSV fields: camera and random Mrays/s; rays where it names another sphere
    /// than the `f64` tree, camera and random; rays where the `f64` tree and where the `f32` tree
    /// differ from the double-double verdict; its speed ÷ Embree's, camera and random; camera and
    /// random rays compared; its speed ÷ the `f64` tree's, camera and random.
    f32_fields: String,
    /// The batch rounds' CSV fields ([`batch_rounds`]).
    batch_fields: String,
    probe: Vec<String>,
}

/// The high-precision verdict on the rays where the two trees disagree: each tree's candidate
/// sphere is intersected in double-double arithmetic (`twofloat`), and the closer true hit in
/// `(t_min, ∞)` is the right answer. Returns how many of those rays each tree (`f64`, `f32`)
/// got wrong. Rays where the trees agree are not re-checked (the `f64` tree equals `f64` brute
/// force, which the benchmark checks where it is affordable).
fn reference_verdicts(spheres: &[Sphere<f64>], rays: &[Ray<f64>], exact: &[Hit], narrow: &[Hit]) -> (usize, usize) {
    let mut wrong = (0, 0);
    for ((ray, a), b) in rays.iter().zip(exact).zip(narrow) {
        let (a, b) = (a.map(|h| h.0), b.map(|h| h.0));
        if a == b {
            continue;
        }
        let t_of = |i: Option<usize>| i.and_then(|i| double_double_hit(ray, &spheres[i], T_MIN));
        let (ta, tb) = (t_of(a), t_of(b));
        let verdict = match (ta, tb) {
            (Some(x), Some(y)) => Some(if x <= y { a } else { b }),
            (Some(_), None) => Some(a),
            (None, Some(_)) => Some(b),
            (None, None) => None,
        }
        .flatten();
        wrong.0 += usize::from(a != verdict);
        wrong.1 += usize::from(b != verdict);
    }
    wrong
}

/// The first root in `(t_min, ∞)` of the ray/sphere quadratic in double-double arithmetic (inputs
/// exact, `f − o` and every product carried to about 106 bits), rounded to `f64`; `None` on a miss.
fn double_double_hit(ray: &Ray<f64>, sphere: &Sphere<f64>, t_min: f64) -> Option<f64> {
    use twofloat::TwoFloat;
    let zero = TwoFloat::from(0.0);
    let (e, d, o) = (ray.origin.to_array(), ray.dir.to_array(), sphere.center.to_array());
    let f: Vec<TwoFloat> = (0..3).map(|k| TwoFloat::new_add(e[k], -o[k])).collect();
    let a = d.iter().fold(zero, |acc, &x| acc + TwoFloat::new_mul(x, x));
    let b_half = -f.iter().zip(d).fold(zero, |acc, (&fk, dk)| acc + fk * dk);
    let c = f.iter().fold(zero, |acc, &fk| acc + fk * fk) - TwoFloat::new_mul(sphere.radius, sphere.radius);
    let disc = b_half * b_half - a * c;
    if disc < zero {
        return None;
    }
    let root = disc.sqrt();
    let (near, far) = ((b_half - root) / a, (b_half + root) / a);
    [near, far].into_iter().map(|t| t.hi() + t.lo()).find(|&t| t > t_min)
}

/// The rays every contender traces: `f64` for the kd-tree, the same rays narrowed (exactly) to
/// `f32` for the peers, and the probe ray.
struct Rays<'a> {
    camera: &'a [Ray<f64>],
    random: &'a [Ray<f64>],
    camera32: &'a [peers::RayF32],
    random32: &'a [peers::RayF32],
    probe32: &'a peers::RayF32,
}

/// The trees of this crate under test: the `f64` tree (contender 0) and its `f32` copy (the last).
struct Trees<'a> {
    f64: &'a KdTree,
    f32: &'a KdTreeF32,
}

fn run_all(
    trees: &Trees<'_>,
    spheres: &[Sphere<f64>],
    rays: &Rays<'_>,
    tree_probe: Hit,
    repeats: (usize, usize),
) -> Run {
    let Rays { camera, random, camera32, random32, probe32 } = *rays;
    let tree = trees.f64;
    let t_min = T_MIN as f32;
    let built: Vec<(Vec<peers::SphereF32>, peers::Peer, f64)> = (0..peers::NAMES.len())
        .map(|index| {
            let mut shapes = peers::spheres_f32(spheres);
            let (build_secs, peer) = best_of(repeats.0, || peers::Peer::build(index, &mut shapes));
            (shapes, peer, build_secs)
        })
        .collect();
    let time_on = |rounds: usize, kd_rays: &[Ray<f64>], peer_rays: &[peers::RayF32], coherent: bool| {
        let mut kd = || trace_all(tree, kd_rays);
        let mut peer_work: Vec<_> = built
            .iter()
            .map(|(shapes, peer, _)| {
                move || -> Vec<Hit> {
                    peer_rays
                        .iter()
                        .map(|r| {
                            peer.closest_hit(shapes, black_box(r), t_min, coherent).map(|(i, t)| (i, f64::from(t)))
                        })
                        .collect()
                }
            })
            .collect();
        let mut kd32 = || -> Vec<Hit> {
            peer_rays
                .iter()
                .map(|r| {
                    let r = black_box(r);
                    trees
                        .f32
                        .closest_hit(r.origin.to_array().into(), r.dir.to_array().into(), t_min, f32::INFINITY)
                        .map(|(i, t)| (i, f64::from(t)))
                })
                .collect()
        };
        let mut contenders: Vec<&mut dyn FnMut() -> Vec<Hit>> = vec![&mut kd];
        contenders.extend(peer_work.iter_mut().map(|w| w as &mut dyn FnMut() -> Vec<Hit>));
        contenders.push(&mut kd32);
        interleaved(rounds, &mut contenders)
    };
    let camera_timed = time_on(repeats.1, camera, camera32, true);
    let random_timed = time_on(repeats.1.min(3), random, random32, false);
    let mut run = Run {
        camera: camera_timed,
        random: random_timed,
        peer_fields: String::new(),
        embree_fields: ",-,-,-,-,-,-".into(),
        f32_fields: String::new(),
        batch_fields: batch_rounds(tree, &built, rays, repeats.1),
        probe: Vec::new(),
    };
    let kd32 = 1 + peers::NAMES.len();
    let embree = peers::NAMES.iter().position(|&name| name == peers::EMBREE).map(|p| p + 1);
    let (camera_wrong, random_wrong) = (
        reference_verdicts(spheres, camera, &run.camera.answers[0], &run.camera.answers[kd32]),
        reference_verdicts(spheres, random, &run.random.answers[0], &run.random.answers[kd32]),
    );
    let versus_embree = |timed: &Timed| embree.map_or("-".into(), |e| format!("{:.3}", timed.speedup(kd32, e)));
    run.f32_fields = format!(
        ",{:.3},{:.3},{},{},{},{},{},{},{},{},{:.3},{:.3}",
        mrays(camera.len(), run.camera.best_secs[kd32]),
        mrays(random.len(), run.random.best_secs[kd32]),
        mismatches(&run.camera.answers[kd32], &run.camera.answers[0]),
        mismatches(&run.random.answers[kd32], &run.random.answers[0]),
        camera_wrong.0 + random_wrong.0,
        camera_wrong.1 + random_wrong.1,
        versus_embree(&run.camera),
        versus_embree(&run.random),
        camera.len(),
        random.len(),
        run.camera.speedup(kd32, 0),
        run.random.speedup(kd32, 0),
    );
    for (p, (&name, (shapes, peer, build_secs))) in peers::NAMES.iter().zip(&built).enumerate() {
        let c = p + 1;
        let wrong = mismatches(&run.camera.answers[c], &run.camera.answers[0])
            + mismatches(&run.random.answers[c], &run.random.answers[0]);
        let fields = format!(
            ",{:.3},{:.3},{:.3},{wrong}",
            build_secs * 1e3,
            mrays(camera32.len(), run.camera.best_secs[c]),
            mrays(random32.len(), run.random.best_secs[c])
        );
        if name == peers::EMBREE {
            run.embree_fields = format!("{fields},{:.3},{:.3}", run.camera.median_ratio[c], run.random.median_ratio[c]);
        } else {
            run.peer_fields.push_str(&fields);
        }
        let answer = peer.closest_hit(shapes, probe32, t_min, false);
        let verdict = match (answer, tree_probe) {
            (a, b) if a.map(|h| h.0) == b.map(|h| h.0) => "ok".to_string(),
            (None, Some((i, _))) => format!("MISSES sphere {i}"),
            (Some((i, _)), _) => format!("differs (sphere {i})"),
            (None, None) => unreachable!("equal answers are matched first"),
        };
        run.probe.push(format!("{name} {verdict}"));
    }
    run
}

/// The batch rounds: the kd-tree ray by ray and through its batch query
/// [`KdTree::closest_hits`], and (with the `embree` feature) Embree ray by ray (`rtcIntersect1`),
/// by its stream call (`rtcIntersect1M`) and by 8-wide packets (`rtcIntersect8`), interleaved in
/// the same rounds on the same rays, camera (with Embree's coherent hint) and random. Asserts that
/// the batch query answers every ray exactly as the single-ray query does, and counts Embree's
/// batch answers that name another sphere than its single-ray answers. Returns the CSV fields:
/// kd batch camera and random Mrays/s, kd batch ÷ kd speed (camera, random), Embree stream and
/// packet Mrays/s (camera, random each), Embree batch mismatches, kd ÷ Embree single-ray speed in
/// these rounds (camera, random), and kd batch ÷ Embree's faster batch form per round (camera,
/// random); medians of per-round ratios, `-` without Embree.
fn batch_rounds(
    tree: &KdTree,
    built: &[(Vec<peers::SphereF32>, peers::Peer, f64)],
    rays: &Rays<'_>,
    rounds: usize,
) -> String {
    let embree = built.iter().find_map(|(_, peer, _)| peer.embree());
    let absent = || "-".to_string();
    // Per ray set (camera, random): kd batch Mrays/s, kd batch ÷ kd, Embree stream and packet
    // Mrays/s, kd ÷ Embree single-ray, kd batch ÷ Embree's faster batch form.
    let mut sets: Vec<[String; 6]> = Vec::new();
    let mut mismatched = 0;
    for (kd_rays, peer_rays, coherent, rounds) in
        [(rays.camera, rays.camera32, true, rounds), (rays.random, rays.random32, false, rounds.min(3))]
    {
        let plain: Vec<([f32; 3], [f32; 3])> = peer_rays.iter().map(|r| (r.origin.into(), r.dir.into())).collect();
        let (plain, t_min) = (&plain, T_MIN as f32);
        let mut kd = || trace_all(tree, kd_rays);
        let mut batch = || trace_batch(tree, kd_rays);
        let mut contenders: Vec<&mut dyn FnMut() -> Vec<Hit>> = vec![&mut kd, &mut batch];
        let widen = |hits: Vec<Option<(usize, f32)>>| -> Vec<Hit> {
            hits.into_iter().map(|h| h.map(|(i, t)| (i, f64::from(t)))).collect()
        };
        let mut single = embree.map(|e| {
            move || -> Vec<Hit> {
                widen(plain.iter().map(|&(o, d)| e.closest_hit(black_box(o), d, t_min, coherent)).collect())
            }
        });
        let mut stream = embree.map(|e| move || widen(e.closest_hits_stream(black_box(plain), t_min, coherent)));
        let mut packet = embree.map(|e| move || widen(e.closest_hits_packet8(black_box(plain), t_min, coherent)));
        if let (Some(single), Some(stream), Some(packet)) = (single.as_mut(), stream.as_mut(), packet.as_mut()) {
            contenders.push(single);
            contenders.push(stream);
            contenders.push(packet);
        }
        let timed = interleaved(rounds, &mut contenders);
        assert_eq!(
            timed.answers[1].iter().map(|h| h.map(|(i, t)| (i, t.to_bits()))).collect::<Vec<_>>(),
            timed.answers[0].iter().map(|h| h.map(|(i, t)| (i, t.to_bits()))).collect::<Vec<_>>(),
            "the batch query answers as the single-ray query, bit for bit"
        );
        let count = kd_rays.len();
        let mut set = [(); 6].map(|()| absent());
        set[0] = format!("{:.3}", mrays(count, timed.best_secs[1]));
        set[1] = format!("{:.3}", timed.speedup(1, 0));
        if timed.secs.len() == 5 {
            mismatched +=
                mismatches(&timed.answers[3], &timed.answers[2]) + mismatches(&timed.answers[4], &timed.answers[2]);
            let best_batch: Vec<f64> = timed.secs[3].iter().zip(&timed.secs[4]).map(|(a, b)| a.min(*b)).collect();
            set[2] = format!("{:.3}", mrays(count, timed.best_secs[3]));
            set[3] = format!("{:.3}", mrays(count, timed.best_secs[4]));
            set[4] = format!("{:.3}", timed.speedup(0, 2));
            set[5] = format!("{:.3}", median(best_batch.iter().zip(&timed.secs[1]).map(|(e, k)| e / k).collect()));
        }
        sets.push(set);
    }
    let mismatched = if embree.is_some() { mismatched.to_string() } else { absent() };
    // The header's order: each quantity for camera, then random; the mismatches after the packets.
    let pair = |k: usize| format!(",{},{}", sets[0][k], sets[1][k]);
    format!("{}{}{}{},{mismatched}{}{}", pair(0), pair(1), pair(2), pair(3), pair(4), pair(5))
}

/// A setting read from the environment variable `name`, if set and parseable.
fn env_override<T: std::str::FromStr>(name: &str) -> Option<T> {
    std::env::var(name).ok().and_then(|v| v.parse().ok())
}

/// `HW3_Q3_PROFILE=kd|kdbatch|kd32|build|ab` (`kdbatch`: the batch query [`KdTree::closest_hits`];
/// `ab`: two values of `K_I` timed in turns, [`compare_costs`]) (with `HW3_Q3_PROFILE_N`, default 10⁵, fixed k unless
/// `HW3_Q3_PROFILE_DENSITY=volume`, and
/// `HW3_Q3_PROFILE_RAYS`, default 10⁵ random rays, `HW3_Q3_KI` for the tree's `K_I`, and
/// `HW3_Q3_PROFILE_BUILDS` builds, default 1, of which the median time is printed): one contender alone, for a profiler
/// (`valgrind --tool=callgrind`, whose counts do not depend on the machine's load). Prints the
/// checksum so the work cannot be optimised away, with the tree's size, SAH cost and build time.
fn profile(what: &str) {
    let n = env_override("HW3_Q3_PROFILE_N").unwrap_or(100_000);
    let count = env_override("HW3_Q3_PROFILE_RAYS").unwrap_or(100_000);
    // `HW3_Q3_PROFILE_CAMERA=1`: the benchmark's 512 × 512 camera rays, repeated up to `count`.
    let rays: Vec<Ray<f64>> = if std::env::var("HW3_Q3_PROFILE_CAMERA").is_ok() {
        camera_rays(512, 512).into_iter().cycle().take(count).collect()
    } else {
        random_rays(count, 0xBEEF)
    };
    let density = match std::env::var("HW3_Q3_PROFILE_DENSITY").as_deref() {
        Ok("volume") => Density::FixedVolumeFraction,
        _ => Density::FixedMeanFreePath,
    };
    let spheres = scene(n, density);
    let defaults = SahCosts::default();
    let costs = SahCosts { intersection: env_override("HW3_Q3_KI").unwrap_or(defaults.intersection), ..defaults };
    if what == "ab" {
        compare_costs(&spheres, &rays, costs);
        return;
    }
    // `HW3_Q3_PROFILE_BUILDS=K`: K builds, the median time printed (a build alone, for a
    // profiler that needs more than one).
    let builds: usize = env_override("HW3_Q3_PROFILE_BUILDS").unwrap_or(1).max(1);
    let mut times = Vec::with_capacity(builds);
    let mut built = None;
    for _ in 0..builds {
        let start = Instant::now();
        built = Some(KdTree::build_with(&spheres, costs).unwrap());
        times.push(start.elapsed().as_secs_f64());
    }
    let tree = built.expect("at least one build");
    times.sort_by(f64::total_cmp);
    let build_secs = times[times.len() / 2];
    let answers: Vec<Hit> = match what {
        "kd" => trace_all(&tree, &rays),
        "kdbatch" => trace_batch(&tree, &rays),
        "kd32" => {
            let tree32 = KdTreeF32::from_tree(&tree);
            rays.iter()
                .map(|r| {
                    let (o, d) = (r.origin.as_vec3(), r.dir.as_vec3());
                    tree32.closest_hit(o, d, T_MIN as f32, f32::INFINITY).map(|(i, t)| (i, f64::from(t)))
                })
                .collect()
        }
        _ => Vec::new(),
    };
    let (nodes_per_ray, tests_per_ray) = work_per_ray(&tree, &rays);
    eprintln!(
        "{what} N = {n}: nodes {}, references {}, SAH cost {:?}, build {:.1} ms (wall), \
         per ray {nodes_per_ray:.2} nodes and {tests_per_ray:.2} sphere tests, checksum {:?}",
        tree.node_count(),
        tree.reference_count(),
        tree.sah_cost(&SahCosts::default()),
        build_secs * 1e3,
        checksum(&answers)
    );
}

/// `HW3_Q3_PROFILE=ab`: two trees over the same spheres, A with `HW3_Q3_KI` (or the default
/// `K_I`) and B with `HW3_Q3_KI_B`, timed over the same rays in 15 alternating rounds in one
/// process (B first in every other round), so that a change of load or clock hits both alike;
/// prints each round's B ÷ A time ratio and their median, and asserts that both answer the same.
fn compare_costs(spheres: &[Sphere<f64>], rays: &[Ray<f64>], costs: SahCosts) {
    let costs_b = SahCosts { intersection: env_override("HW3_Q3_KI_B").unwrap_or(costs.intersection), ..costs };
    let (a, b) = (KdTree::build_with(spheres, costs).unwrap(), KdTree::build_with(spheres, costs_b).unwrap());
    let time = |tree: &KdTree| best_of(1, || trace_all(tree, rays));
    let mut ratios = Vec::new();
    for round in 0..15 {
        let ((time_a, answers_a), (time_b, answers_b)) = if round % 2 == 0 {
            let first = time(&a);
            (first, time(&b))
        } else {
            let first = time(&b);
            (time(&a), first)
        };
        assert!(answers_a == answers_b, "the two trees answer alike");
        ratios.push(time_b / time_a);
        eprint!("{:.3} ", time_b / time_a);
    }
    eprintln!(
        "\nK_I {} ({} nodes) against {} ({} nodes): median time ratio B / A {:.3}",
        costs_b.intersection,
        b.node_count(),
        costs.intersection,
        a.node_count(),
        hw3::stats::median(&mut ratios)
    );
}

fn main() {
    if let Ok(what) = std::env::var("HW3_Q3_PROFILE") {
        profile(&what);
        return;
    }
    let measuring = std::env::args().any(|a| a == "--bench");
    assert_eq!(peers::NAMES[CWBVH - 1], "obvhs_cwbvh", "CWBVH's contender index");
    workload::self_checks();
    let max_n: usize = env_override("HW3_Q3_MAX_N").unwrap_or(100_000);
    // Tuning knobs: override K_I, the empty bonus, the bin count, or skip small N. A tuning run
    // prints its rows but writes nothing (the committed data are the crate's defaults).
    let defaults = SahCosts::default();
    let (ki, bonus, bins, min_n) = (
        env_override("HW3_Q3_KI"),
        env_override("HW3_Q3_EMPTY_BONUS"),
        env_override("HW3_Q3_BINS"),
        env_override::<usize>("HW3_Q3_MIN_N"),
    );
    let tuning = ki.is_some() || bonus.is_some() || bins.is_some() || min_n.is_some();
    let costs = SahCosts {
        intersection: ki.unwrap_or(defaults.intersection),
        empty_bonus: bonus.unwrap_or(defaults.empty_bonus),
        bins: bins.unwrap_or(defaults.bins),
        ..defaults
    };
    let min_n = min_n.unwrap_or(0);
    let (sizes, camera, random, repeats): (Vec<usize>, _, _, usize) = if measuring {
        let sizes =
            [100, 1_000, 10_000, 100_000, 1_000_000].into_iter().filter(|&n| (min_n..=max_n).contains(&n)).collect();
        (sizes, camera_rays(512, 512), random_rays(1_000_000, 0xBEEF), 7)
    } else {
        (vec![100], camera_rays(64, 64), random_rays(4_096, 0xBEEF), 1)
    };
    let (camera32, random32) = (peers::rays_f32(&camera), peers::rays_f32(&random));
    let probe_ray = random_rays(PROBE + 1, 0xBEEF)[PROBE];
    let probe32 = peers::rays_f32(&[probe_ray])[0];
    let mut peer_header = String::new();
    for name in peers::NAMES.iter().filter(|&&name| name != peers::EMBREE) {
        let _ = write!(peer_header, ",{name}_build_ms,{name}_camera_mrays,{name}_random_mrays,{name}_mismatches");
    }
    let mut csv = String::from(
        "density,n,build_ms,nodes,references,camera_mrays,camera_nodes_per_ray,camera_tests_per_ray,\
         camera_hits,camera_sum_t,random_mrays,random_nodes_per_ray,random_tests_per_ray,random_hits,\
         random_sum_t,brute_camera_mrays,brute_random_mrays,brute_mismatches,versus_note",
    );
    csv.push_str(&peer_header);
    let e = peers::EMBREE;
    let _ = writeln!(
        csv,
        ",probe_839669,kd_over_cwbvh_camera,kd_over_cwbvh_random,\
         {e}_build_ms,{e}_camera_mrays,{e}_random_mrays,{e}_mismatches,kd_over_{e}_camera,kd_over_{e}_random,\
         kd32_build_ms,sah_cost,kd32_camera_mrays,kd32_random_mrays,kd32_camera_mismatches,kd32_random_mismatches,\
         kd_wrong_vs_double_double,kd32_wrong_vs_double_double,kd32_over_{e}_camera,kd32_over_{e}_random,\
         camera_rays,random_rays,kd32_over_kd_camera,kd32_over_kd_random,\
         kdbatch_camera_mrays,kdbatch_random_mrays,kdbatch_over_kd_camera,kdbatch_over_kd_random,\
         {e}_stream_camera_mrays,{e}_stream_random_mrays,{e}_packet8_camera_mrays,{e}_packet8_random_mrays,\
         {e}_batch_mismatches,kd_over_{e}_batch_rounds_camera,kd_over_{e}_batch_rounds_random,\
         kdbatch_over_{e}_batch_camera,kdbatch_over_{e}_batch_random"
    );
    for density in [Density::FixedMeanFreePath, Density::FixedVolumeFraction] {
        let label = match density {
            Density::FixedMeanFreePath => "fixed_k",
            Density::FixedVolumeFraction => "fixed_volume",
        };
        for &n in &sizes {
            let spheres = scene(n, density);
            let build_repeats = match n {
                1_000_000.. => 3,
                100_000.. => 5,
                _ => repeats,
            };
            let (build_secs, tree) = best_of(build_repeats, || KdTree::build_with(&spheres, costs).unwrap());
            let (narrow_secs, tree32) = best_of(build_repeats, || KdTreeF32::from_tree(&tree));
            let tree_probe = tree.closest_hit(&probe_ray, T_MIN, f64::INFINITY);
            let run = run_all(
                &Trees { f64: &tree, f32: &tree32 },
                &spheres,
                &Rays { camera: &camera, random: &random, camera32: &camera32, random32: &random32, probe32: &probe32 },
                tree_probe,
                (build_repeats, repeats),
            );
            let (camera_hits, random_hits) = (&run.camera.answers[0], &run.random.answers[0]);
            let (camera_secs, random_secs) = (run.camera.best_secs[0], run.random.best_secs[0]);
            let camera_work = work_per_ray(&tree, &camera);
            let random_work = work_per_ray(&tree, &random);
            // Brute force only where it is affordable, on a prefix as in the note.
            let prefix = match n {
                0..=100 => Some(usize::MAX),
                101..=1_000 => Some(200_000),
                1_001..=10_000 => Some(20_000),
                _ => None,
            };
            let (brute_camera, brute_random, mismatches) = match prefix {
                Some(p) => {
                    let (cam, ran) = (&camera[..p.min(camera.len())], &random[..p.min(random.len())]);
                    let (cs, cb) = best_of(1, || brute_all(&spheres, cam));
                    let (rs, rb) = best_of(1, || brute_all(&spheres, ran));
                    let wrong = cb.iter().zip(camera_hits).filter(|(a, b)| a != b).count()
                        + rb.iter().zip(random_hits).filter(|(a, b)| a != b).count();
                    (format!("{:.3}", mrays(cam.len(), cs)), format!("{:.3}", mrays(ran.len(), rs)), wrong.to_string())
                }
                None => ("-".into(), "-".into(), "-".into()),
            };
            let (ch, ct) = checksum(camera_hits);
            let (rh, rt) = checksum(random_hits);
            let probe = match tree_probe {
                Some((i, t)) => format!("kd hits sphere {i} at t={t:.6}; {}", run.probe.join("; ")),
                None => format!("kd misses; {}", run.probe.join("; ")),
            };
            let note = if measuring { versus_note(n, density, (ch, ct), (rh, rt)) } else { "-".into() };
            let line = format!(
                "{label},{n},{:.3},{},{},{:.3},{:.2},{:.2},{ch},{ct:.2},{:.3},{:.2},{:.2},{rh},{rt:.2},\
                 {brute_camera},{brute_random},{mismatches},{note}{},{probe},{:.3},{:.3}{},{:.3},{:.3}{}{}\n",
                build_secs * 1e3,
                tree.node_count(),
                tree.reference_count(),
                mrays(camera.len(), camera_secs),
                camera_work.0,
                camera_work.1,
                mrays(random.len(), random_secs),
                random_work.0,
                random_work.1,
                run.peer_fields,
                run.camera.median_ratio[CWBVH],
                run.random.median_ratio[CWBVH],
                run.embree_fields,
                (build_secs + narrow_secs) * 1e3,
                tree.sah_cost(&costs),
                run.f32_fields,
                run.batch_fields,
            );
            eprint!("{line}");
            csv.push_str(&line);
            assert!(
                mismatches == "0" || mismatches == "-",
                "the kd-tree disagrees with brute force on {mismatches} rays"
            );
        }
    }
    if measuring && !tuning {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/data");
        hw3::fsio::write_atomic(std::path::Path::new(&format!("{dir}/q3_kdtree_perf.csv")), csv.as_bytes())
            .expect("docs/data is writable");
        hw3::fsio::write_atomic(std::path::Path::new(&format!("{dir}/q3_kdtree_perf.md")), markdown(&csv).as_bytes())
            .expect("docs/data is writable");
        eprintln!("wrote {dir}/q3_kdtree_perf.csv and .md");
    }
}

/// One table row's cells: each cell joins the CSV fields of its columns with " / " (underscores of
/// the density labels read as spaces).
fn cells(fields: &[&str], columns: &[&[usize]]) -> Vec<String> {
    columns
        .iter()
        .map(|cell| cell.iter().map(|&c| fields[c].replace('_', " ")).collect::<Vec<_>>().join(" / "))
        .collect()
}

/// The CSV as the chapter's tables.
fn markdown(csv: &str) -> String {
    let mut md = String::from(
        "| density | N | build ms | nodes | camera Mrays/s | nodes/ray | tests/ray | random Mrays/s | nodes/ray | tests/ray | brute camera / random Mrays/s | vs note checksums |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let columns: [&[usize]; 12] = [&[0], &[1], &[2], &[3], &[5], &[6], &[7], &[10], &[11], &[12], &[15, 16], &[18]];
        let _ = writeln!(md, "| {} |", cells(&f, &columns).join(" | "));
    }
    md.push_str(
        "\nPeers in the same run, on the same rays (f32 scene; kd = the crate's f64 tree; Mrays/s, 1 thread; \
         mismatches = rays, camera + random, where the peer names another sphere than the kd-tree):\n\n\
         | density | N | kd build ms | kd camera | kd random | bvh build ms | bvh camera | bvh random | \
         BVH2 build ms | BVH2 camera | BVH2 random | CWBVH build ms | CWBVH camera | CWBVH random | \
         kd ÷ CWBVH speed, camera / random (median of per-round ratios) | mismatches bvh / BVH2 / CWBVH |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let ratio = match (f.get(32), f.get(33)) {
            (Some(camera), Some(random)) => format!("{camera} / {random}"),
            _ => "-".into(),
        };
        let columns: [&[usize]; 15] = [
            &[0],
            &[1],
            &[2],
            &[5],
            &[10],
            &[19],
            &[20],
            &[21],
            &[23],
            &[24],
            &[25],
            &[27],
            &[28],
            &[29],
            &[22, 26, 30],
        ];
        let mut row = cells(&f, &columns);
        row.insert(row.len() - 1, ratio);
        let _ = writeln!(md, "| {} |", row.join(" | "));
    }
    md.push_str(
        "\nEmbree 3 (system library 3.13.5, native sphere points, `rtcIntersect1`, 1 thread; `-` where the \
         run was made without the `embree` feature), same run, same rays; kd ÷ Embree is the median of the \
         per-round speed ratios:\n\n\
         | density | N | kd build ms | Embree build ms | kd camera | Embree camera | kd ÷ Embree camera | \
         kd random | Embree random | kd ÷ Embree random | mismatches Embree |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let columns: [&[usize]; 11] = [&[0], &[1], &[2], &[34], &[5], &[35], &[38], &[10], &[36], &[39], &[37]];
        let _ = writeln!(md, "| {} |", cells(&f, &columns).join(" | "));
    }
    md.push_str(
        "\nBatch queries, same run, same rays, in rounds of their own: the kd-tree's `closest_hits` (8 rays in \
         flight, interleaved, branch-free step; the same answers as ray by ray, asserted) and Embree's stream \
         (`rtcIntersect1M`) and 8-wide packet (`rtcIntersect8`) calls (coherent hint on camera rays); ratios are \
         medians of per-round speed ratios, Embree's batch is the faster of its two forms in each round:\n\n\
         | density | N | kd batch camera | kd batch random | kd batch ÷ kd camera / random | Embree stream camera / random | \
         Embree packet8 camera / random | kd ÷ Embree ray by ray, camera / random | kd batch ÷ Embree batch, camera / random | \
         mismatches Embree batch |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        if f.len() < 67 {
            continue;
        }
        let columns: [&[usize]; 10] =
            [&[0], &[1], &[54], &[55], &[56, 57], &[58, 59], &[60, 61], &[63, 64], &[65, 66], &[62]];
        let _ = writeln!(md, "| {} |", cells(&f, &columns).join(" | "));
    }
    md.push_str(
        "\nThe `f32` tree (the `f64` tree's nodes, leaf spheres rounded to `f32`, four to a cache line, \
         traversed in `f32`) beside the `f64` tree and Embree, same run, same rays; build = the `f64` build + \
         narrowing; speed ratios are medians of per-round ratios; accuracy per 10⁶ rays: rays where the `f32` \
         tree names another sphere than the `f64` tree (camera / random), and, on those rays, answers that \
         differ from the double-double verdict (`f64` tree / `f32` tree):\n\n\
         | density | N | SAH cost | f32 build ms | f32 camera | f32 random | f32 ÷ f64 camera / random | \
         f32 ÷ Embree camera / random | differ from f64, per 10⁶ camera / random | wrong vs double-double per 10⁶, f64 / f32 |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        if f.len() < 54 {
            continue;
        }
        let count = |c: usize| f[c].parse::<f64>().unwrap_or(f64::NAN);
        let per_million = |c: usize, rays: f64| format!("{:.1}", count(c) / rays * 1e6);
        let (camera_rays, random_rays) = (count(50), count(51));
        let mut row = cells(&f, &[&[0], &[1], &[41], &[40], &[42], &[43], &[52, 53], &[48, 49]]);
        row.push(format!("{} / {}", per_million(44, camera_rays), per_million(45, random_rays)));
        let all = camera_rays + random_rays;
        row.push(format!("{} / {}", per_million(46, all), per_million(47, all)));
        let _ = writeln!(md, "| {} |", row.join(" | "));
    }
    md.push_str("\nProbe, the benchmark's random ray #839 669 with direction (−0, −0, −1), per scene:\n\n");
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let _ = writeln!(md, "- {} N = {}: {}", f[0].replace('_', " "), f[1], f[31]);
    }
    md
}
