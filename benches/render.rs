//! Renderer benchmarks.
//!
//! - divan: camera samples per second of Whitted tracing on the mirror scene, with 1 and 2 rayon
//!   threads (the scaling the issue asks for).
//! - `cargo bench --bench render` also measures accuracy against time for each Q1 scene and writes
//!   `docs/data/q1_accuracy.csv` and `docs/data/q1_accuracy.md` (the chapter's table; the CSV is
//!   plotted by `hw3::q1_hard_scenes::figures`). `cargo test --benches` runs each divan bench once
//!   and skips that measurement.

use hw3::render::analysis::{Passes, analyze};
use hw3::render::integrator::Integrator;
use hw3::render::scene::Scene;
use hw3::render::{Image, Settings, render, scenes};
use std::fmt::Write as _;
use std::time::Instant;

fn main() {
    if std::env::args().any(|a| a == "--bench") {
        write_accuracy_tables();
    }
    divan::main();
}

const SIZE: (u32, u32) = (64, 48);
const SPP: u32 = 4;

#[divan::bench(args = [1, 2])]
fn whitted_mirrors_camera_samples(bencher: divan::Bencher, threads: usize) {
    let scene = scenes::mirror_spheres(true).expect("built-in scene");
    let settings = Settings::whitted(SIZE.0, SIZE.1, SPP, analyze(&scene).plan);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a rayon pool");
    let samples = (SIZE.0 * SIZE.1 * SPP) as usize;
    bencher
        .counter(divan::counter::ItemsCount::new(samples))
        .bench(|| pool.install(|| render(&scene, &settings, &|_| {}).expect("valid settings")));
}

/// Image size, samples per pixel and seed of the converged path-traced references.
const ACCURACY_SIZE: (u32, u32) = (48, 36);
const REFERENCE_SPP: u32 = 256;
const REFERENCE_SEED: u64 = 1_000_003;
const LEVELS: [u32; 7] = [1, 2, 4, 8, 16, 32, 64];
const PATH_DEPTH: u32 = 4;

fn timed_render(scene: &Scene, integrator: Integrator, spp: u32, seed: u64) -> (Image, f64) {
    let plan: Passes = analyze(scene).plan.for_integrator(integrator);
    let settings = Settings { integrator, seed, ..Settings::whitted(ACCURACY_SIZE.0, ACCURACY_SIZE.1, spp, plan) };
    let start = Instant::now();
    let image = render(scene, &settings, &|_| {}).expect("valid settings");
    (image, start.elapsed().as_secs_f64())
}

/// RMS luminance error against a 256-spp path-traced reference, for path tracing and Whitted
/// tracing at 1…64 spp, with wall times; writes the CSV and a Markdown table.
fn write_accuracy_tables() {
    let cases = [
        ("clutter", scenes::clutter_forest(300, 1)),
        ("fog", scenes::fog_street(0.08)),
        ("mirrors", scenes::mirror_spheres(true)),
        ("motion", scenes::moving_ball(2.0)),
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
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/data");
    std::fs::create_dir_all(data).expect("docs/data is writable");
    std::fs::write(format!("{data}/q1_accuracy.csv"), csv).expect("write the CSV");
    std::fs::write(format!("{data}/q1_accuracy.md"), table).expect("write the table");
}
