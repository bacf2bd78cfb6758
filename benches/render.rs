//! Renderer benchmarks.
//!
//! - divan: camera samples per second of Whitted tracing on the mirror scene and on the
//!   1500-sphere clutter forest, with 1 and 2 rayon threads, and
//!   on the clutter forest with and without the kd-tree on one thread (the speed-up of
//!   acceleration; both renders are bit-identical, see `render::tests`).
//! - `cargo bench -p hw3-benches --bench render` also measures accuracy against time for each Q1 scene and writes
//!   `docs/data/q1_accuracy.csv` and `docs/data/q1_accuracy.md` (the chapter's table; the CSV is
//!   plotted by `hw3::q1_hard_scenes::figures`). `cargo test --benches` runs each divan bench once
//!   and skips that measurement.
//! - `cargo bench -p hw3-benches --bench render` also writes `docs/data/render_speed.md`: the kd-tree's speed-up
//!   and the 1→2 thread scaling on the clutter scene, with the CPU time the process actually got,
//!   so that a shared machine's contention shows as cores used below the threads asked for.
//! - divan: the cost of the caustic pass on the `caustic` scene (Whitted with the pass planned
//!   and forced off, and tracing the caustic map alone).
//! - The tables are written only by a run without a name filter: `cargo bench -p hw3-benches --bench render --
//!   caustic` runs the matching divan benchmarks and nothing else.

use hw3::render::integrator::Integrator;
use hw3::render::photon;
use hw3::render::scene::Scene;
use hw3::render::{Image, Settings, catalogue, render};
use hw3::render::{
    analysis::analyze,
    passes::{Pass, Passes},
};
use hw3::stats::median;
use std::fmt::Write as _;
use std::time::Instant;

fn main() {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    let filtered = arguments.iter().any(|a| !a.starts_with('-'));
    if arguments.iter().any(|a| a == "--bench") && !filtered {
        write_speed_tables();
        write_accuracy_tables();
    }
    divan::main();
}

const SIZE: (u32, u32) = (64, 48);
const SPP: u32 = 4;

#[divan::bench(args = [1, 2])]
fn whitted_mirrors_camera_samples(bencher: divan::Bencher, threads: usize) {
    bench_whitted(bencher, &catalogue::mirror_spheres(true).expect("built-in scene"), threads);
}

/// Whitted tracing of one scene at [`SIZE`] and [`SPP`] on a pool of `threads` rayon threads.
fn bench_whitted(bencher: divan::Bencher, scene: &Scene, threads: usize) {
    let settings = Settings::whitted(SIZE.0, SIZE.1, SPP, analyze(scene).plan);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a rayon pool");
    let samples = (SIZE.0 * SIZE.1 * SPP) as usize;
    bencher
        .counter(divan::counter::ItemsCount::new(samples))
        .bench(|| pool.install(|| render(scene, &settings, &|_| {}).expect("valid settings")));
}

#[divan::bench(args = [1, 2])]
fn whitted_clutter_camera_samples(bencher: divan::Bencher, threads: usize) {
    bench_whitted(bencher, &catalogue::by_name("clutter").expect("built-in scene"), threads);
}

/// Whitted tracing of the `caustic` scene on one thread with its plan (caustic map traced and
/// read) and with the caustic pass forced off: the difference is the pass's cost.
#[divan::bench(args = ["planned", "caustics off"])]
fn whitted_caustic_scene(bencher: divan::Bencher, plan: &str) {
    let scene = catalogue::by_name("caustic").expect("built-in scene");
    let planned = analyze(&scene).plan;
    let passes = if plan == "planned" { planned } else { planned.with(Pass::Caustics, false) };
    let settings = Settings::whitted(SIZE.0, SIZE.1, SPP, passes);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("a rayon pool");
    bencher.bench(|| pool.install(|| render(&scene, &settings, &|_| {}).expect("valid settings")));
}

/// Tracing the `caustic` scene's caustic map alone ([`photon::CAUSTIC_PHOTONS`] photons, one
/// thread).
#[divan::bench]
fn caustic_map_trace(bencher: divan::Bencher) {
    let scene = catalogue::by_name("caustic").expect("built-in scene");
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("a rayon pool");
    bencher.bench(|| {
        pool.install(|| photon::trace_caustic_photons(&scene, photon::CAUSTIC_PHOTONS, 1).expect("valid count"))
    });
}

/// The 1500-sphere forest on one thread, its static spheres through the kd-tree or tested one
/// by one.
#[divan::bench(args = ["kd-tree", "brute force"])]
fn whitted_clutter_acceleration(bencher: divan::Bencher, queries: &str) {
    let scene = catalogue::by_name("clutter").expect("built-in scene");
    let scene = if queries == "kd-tree" { scene } else { scene.without_kd_tree() };
    bench_whitted(bencher, &scene, 1);
}

/// Rounds of the speed table; each round times every configuration once, interleaved, so that a
/// change in the machine's load hits all configurations alike.
const SPEED_ROUNDS: usize = 9;
/// Image of the speed table (160×120 at 4 spp, 76 800 camera samples).
const SPEED_SIZE: (u32, u32, u32) = (160, 120, 4);

/// CPU time (user + system) this process has used so far, from `/proc/self/stat` (Linux), in
/// seconds; `None` where that file is absent.
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the parenthesised command name; utime and stime are fields 14 and 15.
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0) // USER_HZ is 100 on Linux
}

/// Times Whitted renders of the 1500-sphere clutter scene: with the kd-tree on 1 and 2 threads
/// and by brute force on 1 thread, interleaved over [`SPEED_ROUNDS`] rounds; writes the medians
/// of wall time and of the cores the process got (CPU time / wall time) to
/// `docs/data/render_speed.md`.
fn write_speed_tables() {
    let scene = catalogue::by_name("clutter").expect("built-in scene");
    let brute = scene.without_kd_tree();
    let (width, height, spp) = SPEED_SIZE;
    let settings = Settings::whitted(width, height, spp, analyze(&scene).plan);
    let configurations = [("kd-tree", &scene, 1), ("kd-tree", &scene, 2), ("brute force", &brute, 1)];
    let pools: Vec<rayon::ThreadPool> = configurations
        .iter()
        .map(|&(_, _, threads)| rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a pool"))
        .collect();
    let mut walls = vec![Vec::new(); configurations.len()];
    let mut cores = vec![Vec::new(); configurations.len()];
    for _ in 0..SPEED_ROUNDS {
        for (k, &(_, scene, _)) in configurations.iter().enumerate() {
            let (cpu_start, start) = (process_cpu_seconds(), Instant::now());
            pools[k].install(|| render(scene, &settings, &|_| {}).expect("valid settings"));
            let wall = start.elapsed().as_secs_f64();
            walls[k].push(wall);
            if let (Some(a), Some(b)) = (cpu_start, process_cpu_seconds()) {
                cores[k].push((b - a) / wall);
            }
        }
    }
    let samples = f64::from(width * height * spp);
    let mut table = format!(
        "Whitted tracing of the clutter scene (1500 spheres), {width}×{height} pixels at {spp} spp, median of {SPEED_ROUNDS} interleaved runs, on a machine with {} logical CPUs.\n\n| queries | threads | wall time (s) | camera samples/s | cores used (CPU time / wall) |\n|---|---|---|---|---|\n",
        std::thread::available_parallelism().map_or(0, std::num::NonZero::get)
    );
    for (k, &(queries, _, threads)) in configurations.iter().enumerate() {
        let wall = median(&mut walls[k]);
        let used = if cores[k].is_empty() { "n/a".to_string() } else { format!("{:.2}", median(&mut cores[k])) };
        let _ = writeln!(table, "| {queries} | {threads} | {wall:.3e} | {:.3e} | {used} |", samples / wall);
    }
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/data");
    std::fs::create_dir_all(data).expect("docs/data is writable");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/render_speed.md")), table.as_bytes())
        .expect("write the table");
}

/// Image size, samples per pixel and seed of the converged path-traced references.
const ACCURACY_SIZE: (u32, u32) = (48, 36);
const REFERENCE_SPP: u32 = 256;
const REFERENCE_SEED: u64 = 1_000_003;
const LEVELS: [u32; 7] = [1, 2, 4, 8, 16, 32, 64];
const PATH_DEPTH: u32 = 4;

fn timed_render(scene: &Scene, integrator: Integrator, spp: u32, seed: u64) -> (Image, f64) {
    let plan: Passes = integrator.restrict(analyze(scene).plan);
    let settings = Settings { integrator, seed, ..Settings::whitted(ACCURACY_SIZE.0, ACCURACY_SIZE.1, spp, plan) };
    let start = Instant::now();
    let image = render(scene, &settings, &|_| {}).expect("valid settings");
    (image, start.elapsed().as_secs_f64())
}

/// RMS luminance error against a 256-spp path-traced reference, for path tracing and Whitted
/// tracing at 1…64 spp, with wall times; writes the CSV and a Markdown table.
fn write_accuracy_tables() {
    let cases = [
        ("clutter", catalogue::clutter_forest(catalogue::CLUTTER_COUNT, 1)),
        ("fog", catalogue::fog_street(0.08)),
        ("mirrors", catalogue::mirror_spheres(true)),
        ("motion", catalogue::moving_ball(2.0)),
    ];
    let path = Integrator::PathTracer { max_depth: PATH_DEPTH };
    let whitted = Integrator::Whitted { max_depth: 8 };
    let mut csv = String::from("scene,integrator,spp,seconds,rmse\n");
    let mut table = format!(
        "Reference: path tracing, {REFERENCE_SPP} spp, {}×{} pixels, depth {PATH_DEPTH}; RMS luminance error.\n\n| scene | spp | path tracing RMSE | seconds | Whitted RMSE | seconds |\n|---|---|---|---|---|---|\n",
        ACCURACY_SIZE.0, ACCURACY_SIZE.1
    );
    for (name, scene) in cases {
        let scene = scene.expect("built-in scene");
        let (reference, _) = timed_render(&scene, path, REFERENCE_SPP, REFERENCE_SEED);
        for spp in LEVELS {
            let (traced, t_path) = timed_render(&scene, path, spp, 1);
            let (whitted_image, t_whitted) = timed_render(&scene, whitted, spp, 1);
            let (e_path, e_whitted) = (traced.rms_difference(&reference), whitted_image.rms_difference(&reference));
            let _ = writeln!(csv, "{name},path,{spp},{t_path:.4e},{e_path:.4e}");
            let _ = writeln!(csv, "{name},whitted,{spp},{t_whitted:.4e},{e_whitted:.4e}");
            let _ =
                writeln!(table, "| {name} | {spp} | {e_path:.3e} | {t_path:.3e} | {e_whitted:.3e} | {t_whitted:.3e} |");
        }
    }
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/data");
    std::fs::create_dir_all(data).expect("docs/data is writable");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q1_accuracy.csv")), csv.as_bytes())
        .expect("write the CSV");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q1_accuracy.md")), table.as_bytes())
        .expect("write the table");
}
