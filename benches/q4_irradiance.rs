//! Q4 accuracy versus time.
//!
//! `cargo bench -p hw3-benches --bench q4_irradiance` first sweeps every method and parameter on the soft and sun
//! maps (error from the closed-form oracle over 64 normals, time per normal with `Instant`: the
//! median of 101 short samples, each method in its own monomorphised loop, so no per-call dispatch
//! is timed),
//! writing `docs/data/q4_accuracy_time.{csv,md}`, then runs the divan benchmarks.
//! `cargo bench -p hw3-benches --bench q4_irradiance -- sh9` runs only the matching divan benchmarks (no sweep).
//! `cargo test --benches` runs each divan benchmark once and skips the sweep.

use divan::{Bencher, black_box};
use glam::DVec3;
use hw3::envmap::{Probe, ProbeFormat, horizontal_camera};
use hw3::q4_light_probe::fibonacci_normals;
use hw3::q4_light_probe::irradiance::{Estimator, Irradiance, Sh9};
use hw3::q4_light_probe::maps::AnalyticMap;
use hw3::q4_light_probe::study::{self, Config};
use hw3::stats::median;
use std::fmt::Write as _;
use std::time::Instant;

fn sun_probe(size: usize) -> Probe {
    AnalyticMap::sun().rasterise(ProbeFormat::MirrorBall, size, horizontal_camera()).expect("valid analytic map")
}

fn normal() -> DVec3 {
    DVec3::new(0.3, 0.4, 0.8).normalize()
}

#[divan::bench(args = [16, 64, 256])]
fn weighted_sum(bencher: Bencher, size: usize) {
    let probe = sun_probe(size);
    let prepared = Irradiance::new(&probe);
    bencher.bench_local(|| prepared.weighted(black_box(normal())));
}

#[divan::bench(args = [16, 64, 256])]
fn unweighted_sum(bencher: Bencher, size: usize) {
    let probe = sun_probe(size);
    let prepared = Irradiance::new(&probe);
    bencher.bench_local(|| prepared.unweighted(black_box(normal())));
}

#[divan::bench(args = [16, 64, 256])]
fn sh9_projection(bencher: Bencher, size: usize) {
    let probe = sun_probe(size);
    bencher.bench_local(|| Sh9::project(black_box(&probe)));
}

#[divan::bench]
fn sh9_evaluation(bencher: Bencher) {
    let probe = sun_probe(64);
    let sh9 = Sh9::project(&probe);
    bencher.bench_local(|| sh9.irradiance(black_box(normal())));
}

fn monte_carlo(bencher: Bencher, method: Estimator, samples: usize) {
    let probe = sun_probe(256);
    let prepared = Irradiance::new(&probe);
    let mut rng = hw3::rng::seeded(1, 0);
    bencher.bench_local(|| prepared.estimate(black_box(normal()), method, samples, &mut rng).expect("valid normal"));
}

#[divan::bench(args = [16, 256, 4096])]
fn uniform_mc(bencher: Bencher, samples: usize) {
    monte_carlo(bencher, Estimator::Uniform, samples);
}

#[divan::bench(args = [16, 256, 4096])]
fn cosine_mc(bencher: Bencher, samples: usize) {
    monte_carlo(bencher, Estimator::Cosine, samples);
}

#[divan::bench(args = [16, 256, 4096])]
fn map_mc(bencher: Bencher, samples: usize) {
    monte_carlo(bencher, Estimator::Map, samples);
}

#[divan::bench(args = [16, 256, 4096])]
fn mis_mc(bencher: Bencher, samples: usize) {
    monte_carlo(bencher, Estimator::Mis, samples);
}

/// Samples per configuration: the reported time is their median, as divan reports.
const SAMPLES: usize = 101;

/// Shortest sample: a sample holds as many calls as fill this, so that the clock's ~25 ns per read
/// is under 0.1 % of it, yet stays far below a scheduler time slice (milliseconds), so that on a
/// shared machine a preemption lands in few samples and the median skips it.
const MIN_SAMPLE_NS: f64 = 50_000.0;

/// Nanoseconds per call of `estimate`: the median of [`SAMPLES`] samples, each of as many
/// consecutive calls over `normals` (cycling) as fill [`MIN_SAMPLE_NS`], divan's method (many short
/// samples, their median). `estimate` is a concrete closure, so each method's loop is
/// monomorphised: no per-call dispatch (no `match` on the method, no validation of the normal) is
/// timed, the way divan times one method's call.
fn time_per_call(normals: &[DVec3], mut estimate: impl FnMut(DVec3) -> DVec3) -> f64 {
    // Warm-up pass (caches, branch predictors), which also sizes the samples.
    let start = Instant::now();
    for n in normals {
        black_box(estimate(black_box(*n)));
    }
    let per_call = start.elapsed().as_secs_f64() * 1e9 / normals.len() as f64;
    let calls = ((MIN_SAMPLE_NS / per_call.max(1.0)).ceil() as usize).max(1);
    let mut next = normals.iter().cycle();
    let mut samples: Vec<f64> = (0..SAMPLES)
        .map(|_| {
            let start = Instant::now();
            for n in next.by_ref().take(calls) {
                black_box(estimate(black_box(*n)));
            }
            start.elapsed().as_secs_f64() * 1e9 / calls as f64
        })
        .collect();
    median(&mut samples)
}

/// Nanoseconds per normal of one configuration: the method is chosen once, outside the timed loop
/// (the normals are unit vectors already, so nothing `estimate` checks is skipped that matters).
fn time_per_normal(prepared: &Irradiance<'_>, config: Config, normals: &[DVec3]) -> f64 {
    let mut rng = hw3::rng::seeded(99, 0);
    let samples = config.samples.max(1);
    match config.method {
        Estimator::Unweighted => time_per_call(normals, |n| prepared.unweighted(n)),
        Estimator::Weighted => time_per_call(normals, |n| prepared.weighted(n)),
        Estimator::Uniform => time_per_call(normals, |n| prepared.uniform(n, samples, &mut rng)),
        Estimator::Cosine => time_per_call(normals, |n| prepared.cosine(n, samples, &mut rng)),
        Estimator::Map => time_per_call(normals, |n| prepared.map(n, samples, &mut rng)),
        Estimator::Mis => time_per_call(normals, |n| prepared.mis(n, samples, &mut rng)),
        Estimator::Sh9 => time_per_call(normals, |n| prepared.sh9().irradiance(n)),
    }
}

fn sweep() {
    let normals = fibonacci_normals(64);
    let seeds: Vec<u64> = (1..=8).collect();
    let mut csv =
        String::from("map,method,label,size,samples,mean_percent,max_percent,ns_per_normal,mean_relative_percent\n");
    let mut table = String::from(
        "| map | configuration | mean error (% of peak) | max error (% of peak) | mean relative error (%) | time per normal |\n|---|---|---|---|---|---|\n",
    );
    let mut summary = String::new();
    for (map_name, map) in study::study_maps().expect("the vendored maps are readable") {
        let reference = map.reference(&normals);
        let mut probes: Vec<(usize, Probe)> = Vec::new();
        let mut results: Vec<(Config, study::ErrorSummary, f64)> = Vec::new();
        for config in study::configurations() {
            if !probes.iter().any(|(s, _)| *s == config.size) {
                let probe = map.ball(config.size).expect("a valid size");
                probes.push((config.size, probe));
            }
            let probe = &probes.iter().find(|(s, _)| *s == config.size).expect("just built").1;
            let prepared = Irradiance::new(probe);
            let error = study::method_error(&prepared, config.method, config.samples, &seeds, &normals, &reference);
            let ns = time_per_normal(&prepared, config, &normals);
            eprintln!(
                "{map_name:>9} {:<18} {:>9.4} % {:>9.4} % {:>12.1} ns",
                config.label(),
                error.mean_percent,
                error.max_percent,
                ns
            );
            let _ = writeln!(
                csv,
                "{map_name},{},{},{},{},{:.6},{:.6},{:.1},{:.6}",
                config.method.name(),
                config.label(),
                config.size,
                config.samples,
                error.mean_percent,
                error.max_percent,
                ns,
                error.mean_relative_percent
            );
            let _ = writeln!(
                table,
                "| {map_name} | {} | {:.4} | {:.4} | {:.3} | {} |",
                config.label(),
                error.mean_percent,
                error.max_percent,
                error.mean_relative_percent,
                human_time(ns)
            );
            results.push((config, error, ns));
        }
        let find = |label: &str| results.iter().find(|(c, _, _)| c.label() == label).expect("swept");
        let (_, sh9_error, sh9_ns) = find("sh9 256²");
        let (_, weighted_error, weighted_ns) = find("weighted 256²");
        let projection = {
            let probe = &probes.iter().find(|(s, _)| *s == 256).expect("built").1;
            let mut runs: Vec<f64> = (0..11)
                .map(|_| {
                    let start = Instant::now();
                    black_box(Sh9::project(black_box(probe)));
                    start.elapsed().as_secs_f64() * 1e9
                })
                .collect();
            median(&mut runs)
        };
        let _ = writeln!(
            summary,
            "- **{map_name}**: SH9 (256² projection) {:.3} % mean / {:.3} % max error ({:.2} % mean relative) in {} per normal; \
             the 256² weighted sum {:.4} % / {:.4} % in {}: SH9 is {:.0}× faster \
             (plus a one-off projection of {}).",
            sh9_error.mean_percent,
            sh9_error.max_percent,
            sh9_error.mean_relative_percent,
            human_time(*sh9_ns),
            weighted_error.mean_percent,
            weighted_error.max_percent,
            human_time(*weighted_ns),
            weighted_ns / sh9_ns,
            human_time(projection)
        );
    }
    let markdown = format!(
        "Measured by `cargo bench -p hw3-benches --bench q4_irradiance` (release, one thread). Error: % of the peak exact irradiance over 64 Fibonacci normals; \
         Relative error: per normal, against that normal's own reference, normals below 1 % of the peak left out. \
         Time per normal: the median of 101 samples of at least 50 µs of consecutive calls over the 64 \
         normals, each method in its own monomorphised loop (no per-call dispatch or input check is \
         timed; divan's method). \
         Monte Carlo: per-normal RMS over 8 seeds, on a 256² probe. Orthographic mirror-ball probes \
         rasterised from the analytic soft and sun maps (exact reference: the closed forms), or \
         resampled from the vendored 256×128 CC0 lat-long maps courtyard and sunrise (reference: the \
         file's own solid-angle-weighted texel sum); no photograph of a real ball.\n\n{summary}\n{table}"
    );
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/data");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q4_accuracy_time.csv")), csv.as_bytes())
        .expect("docs/data is writable");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q4_accuracy_time.md")), markdown.as_bytes())
        .expect("docs/data is writable");
}

fn human_time(ns: f64) -> String {
    if ns < 1e3 {
        format!("{ns:.1} ns")
    } else if ns < 1e6 {
        format!("{:.2} µs", ns / 1e3)
    } else {
        format!("{:.2} ms", ns / 1e6)
    }
}

/// `cargo bench -p hw3-benches --bench q4_irradiance` sweeps, then runs every divan benchmark; with a divan filter
/// (`cargo bench -p hw3-benches --bench q4_irradiance -- sh9`) only the matching divan benchmarks run, so that a
/// quick check leaves the committed table alone.
fn main() {
    let mut args = std::env::args().skip(1);
    let measuring = args.any(|a| a == "--bench");
    let filtered = std::env::args().skip(1).any(|a| !a.starts_with('-'));
    if measuring && !filtered {
        sweep();
    }
    divan::main();
}
