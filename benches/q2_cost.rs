//! Q2 accuracy versus time: times every intersection variant and spawn policy on one batch of
//! camera rays, interleaved round by round so that the ratios compare like with like, and writes
//! `docs/data/q2_cost.csv`, which the notes' table and chart are drawn from.
//!
//! `cargo bench -p hw3-benches --bench q2_cost` measures and writes; under `cargo test --benches` it runs one
//! quick round as a smoke test and writes nothing.

use hw3::geometry::sphere::first_hit_stable;
use hw3::geometry::{Ray, Sphere};
use hw3::q2_ray_sphere::catalogue::camera_batch;
use hw3::q2_ray_sphere::reflection::{SpawnPolicy, reflect_at_hit};
use hw3::q2_ray_sphere::student_solver::first_hit_naive;
use hw3::real::Real;
use hw3::stats::median;
use std::hint::black_box;
use std::time::Instant;

const BATCH: usize = 4096;

fn convert<T: Real>(pairs: &[(Ray<f64>, Sphere<f64>)]) -> Vec<(Ray<T>, Sphere<T>)> {
    pairs
        .iter()
        .map(|(r, s)| {
            (
                Ray { origin: T::vec_from_f64(r.origin), dir: T::vec_from_f64(r.dir) },
                Sphere { center: T::vec_from_f64(s.center), radius: T::from_f64(s.radius) },
            )
        })
        .collect()
}

/// Nanoseconds per call of `work` over the batch, best of `repeats` passes (one round's sample).
fn time_per_call(repeats: u32, mut work: impl FnMut() -> f64) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..repeats {
        let start = Instant::now();
        black_box(work());
        best = best.min(start.elapsed().as_nanos() as f64 / BATCH as f64);
    }
    best
}

fn intersect<T: Real>(pairs: &[(Ray<T>, Sphere<T>)], solver: fn(&Ray<T>, &Sphere<T>) -> Option<T>) -> f64 {
    pairs
        .iter()
        .fold(0.0, |acc, (ray, sphere)| acc + solver(black_box(ray), black_box(sphere)).map_or(0.0, Real::to_f64))
}

/// Intersects and builds the whole reflected ray. Every component of origin and direction feeds
/// the sum: a policy whose origin does not depend on the direction (the naive one) would otherwise
/// have its reflection removed as dead code and look cheaper than it is.
fn spawn(pairs: &[(Ray<f32>, Sphere<f32>)], policy: SpawnPolicy) -> f64 {
    pairs.iter().fold(0.0, |acc, (ray, sphere)| match first_hit_stable(black_box(ray), sphere) {
        Some(t) => {
            let reflected = reflect_at_hit(ray, sphere, t, black_box(policy)).ray;
            acc + f64::from((reflected.origin + reflected.dir).element_sum())
        }
        None => acc,
    })
}

fn main() {
    let measuring = std::env::args().any(|a| a == "--bench");
    let (rounds, repeats) = if measuring { (41, 20) } else { (1, 1) };
    let batch = camera_batch(BATCH, 1);
    let (b32, b64) = (convert::<f32>(&batch), convert::<f64>(&batch));
    // (kind, label, baseline label, measurement)
    type Job<'a> = (&'static str, &'static str, &'static str, Box<dyn Fn() -> f64 + 'a>);
    let jobs: Vec<Job<'_>> = vec![
        ("intersect", "naive f32", "naive f32", Box::new(|| intersect(&b32, first_hit_naive::<f32>))),
        ("intersect", "stable f32", "naive f32", Box::new(|| intersect(&b32, first_hit_stable::<f32>))),
        ("intersect", "naive f64", "naive f32", Box::new(|| intersect(&b64, first_hit_naive::<f64>))),
        ("intersect", "stable f64", "naive f32", Box::new(|| intersect(&b64, first_hit_stable::<f64>))),
        ("spawn", "AtComputedPoint", "AtComputedPoint", Box::new(|| spawn(&b32, SpawnPolicy::AtComputedPoint))),
        ("spawn", "ReprojectAndOffset", "AtComputedPoint", Box::new(|| spawn(&b32, SpawnPolicy::ReprojectAndOffset))),
    ];
    let mut samples: Vec<Vec<f64>> = vec![Vec::new(); jobs.len()];
    let mut ratios: Vec<Vec<f64>> = vec![Vec::new(); jobs.len()];
    for _ in 0..rounds {
        let round: Vec<f64> = jobs.iter().map(|(_, _, _, work)| time_per_call(repeats, work)).collect();
        for (i, (_, _, baseline, _)) in jobs.iter().enumerate() {
            let base = jobs.iter().position(|(_, label, _, _)| label == baseline).expect("baseline is a job");
            samples[i].push(round[i]);
            ratios[i].push(round[i] / round[base]);
        }
    }
    let mut csv = format!(
        "# {BATCH} camera rays (about 55 % hits), median over {rounds} interleaved rounds of the best of {repeats} passes; \
         ratio = median of per-round ratios to the baseline (naive f32 / AtComputedPoint); release build, 1 thread.\n"
    );
    csv.push_str("kind,variant,median_ns,ratio\n");
    for (i, (kind, label, _, _)) in jobs.iter().enumerate() {
        let line =
            format!("{kind},{label},{:.3},{:.3}\n", median(&mut samples[i].clone()), median(&mut ratios[i].clone()));
        print!("{line}");
        csv.push_str(&line);
    }
    if measuring {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/data/q2_cost.csv");
        hw3::fsio::write_atomic(std::path::Path::new(&path), csv.as_bytes()).expect("docs/data is writable");
        eprintln!("wrote {path}");
    }
}
