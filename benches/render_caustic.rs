//! The caustic pass's accuracy against time.
//!
//! - divan: 1000 caustic radiance gathers (k = 50 within 0.1) on the `caustic` scene's floor.
//! - `cargo bench -p hw3-benches --bench render_caustic` also measures the bias/noise trade-off of the caustic
//!   gather on the `caustic` scene: the floor radiance at 200 points of the caustic's footprint
//!   ([`hw3::render::catalogue::caustic_footprint`]) from maps of 12 500, 50 000 (the render
//!   default) and 200 000 aimed photons, each with eight seeds, for k = 8…800 within the
//!   default maximum radius 0.1, against a reference map of 4·10⁶ photons at k = 400 (its blur
//!   radius is that of k = 5 at 5·10⁴ photons; its noise, 1/√398 = 5 % per point, is known and
//!   subtracted). Errors are relative to each point's reference value, RMS over the points:
//!   noise is the spread between seeds, bias the deviation of the seeds' mean from the reference
//!   with the two known variances (the mean's, noise²/8, and the reference's) subtracted. With
//!   the seconds of tracing and of the gathers; writes `docs/data/render_caustic_k.md` and `.csv`.
//!   `cargo test --benches` runs the divan bench once and skips that measurement.

use glam::DVec3;
use hw3::render::catalogue;
use hw3::render::photon::{CAUSTIC_GATHER, Gather, PhotonMap, trace_caustic_photons};
use hw3::render::scene::{Material, Scene};
use std::fmt::Write as _;
use std::time::Instant;

fn main() {
    if std::env::args().any(|a| a == "--bench") {
        write_accuracy_table();
    }
    divan::main();
}

/// The floor's material (white, albedo 0.7).
const FLOOR: Material = Material::Diffuse { albedo: DVec3::splat(0.7) };

fn caustic_scene() -> Scene {
    catalogue::glass_ball_caustic().expect("built-in scene")
}

/// Radiance toward +y at each floor point (red channel; the scene is grey).
fn gather(map: &PhotonMap, points: &[DVec3], gather: Gather) -> Vec<f64> {
    points.iter().map(|&p| map.radiance_gathered(&FLOOR, p, DVec3::Y, DVec3::Y, gather).x).collect()
}

#[divan::bench]
fn caustic_gathers(bencher: divan::Bencher) {
    let map = trace_caustic_photons(&caustic_scene(), 50_000, 1).expect("valid count");
    let (_, _, points) = catalogue::caustic_footprint(1000);
    bencher.bench_local(|| gather(&map, &points, CAUSTIC_GATHER).iter().sum::<f64>());
}

const PHOTONS: [usize; 3] = [12_500, 50_000, 200_000];
const NEIGHBOURS: [usize; 5] = [8, 16, 50, 200, 800];
const SEEDS: u64 = 8;
const REFERENCE_PHOTONS: usize = 4_000_000;
const REFERENCE_NEIGHBOURS: usize = 400;

fn write_accuracy_table() {
    let scene = caustic_scene();
    let (_, _, points) = catalogue::caustic_footprint(200);
    let reference_map = trace_caustic_photons(&scene, REFERENCE_PHOTONS, 1_000_003).expect("valid count");
    let reference_gather = Gather::new(REFERENCE_NEIGHBOURS, CAUSTIC_GATHER.max_radius()).expect("k ≥ 2");
    let reference = gather(&reference_map, &points, reference_gather);
    let mean = reference.iter().sum::<f64>() / reference.len() as f64;
    let reference_variance = 1.0 / (REFERENCE_NEIGHBOURS - 2) as f64;
    let mut csv = String::from("photons,k,bias,noise,rms_error,trace_seconds,gather_microseconds\n");
    let mut table = format!(
        "Floor radiance at 200 points of the caustic's footprint (mean {mean:.3}); reference: {REFERENCE_PHOTONS} photons, k = {REFERENCE_NEIGHBOURS}. Relative errors per point, RMS over the points, {SEEDS} seeds per row; bias with the known variances subtracted.\n\n| photons | k | bias | noise | RMS error | trace (s) | gather (µs) |\n|---|---|---|---|---|---|---|\n"
    );
    for photons in PHOTONS {
        let mut maps = Vec::new();
        let start = Instant::now();
        for seed in 0..SEEDS {
            maps.push(trace_caustic_photons(&scene, photons, seed + 1).expect("valid count"));
        }
        let trace_seconds = start.elapsed().as_secs_f64() / SEEDS as f64;
        for k in NEIGHBOURS {
            let settings = Gather::new(k, CAUSTIC_GATHER.max_radius()).expect("k ≥ 2");
            let start = Instant::now();
            let estimates: Vec<Vec<f64>> = maps.iter().map(|map| gather(map, &points, settings)).collect();
            let gather_microseconds = start.elapsed().as_secs_f64() * 1e6 / (SEEDS as f64 * points.len() as f64);
            let (mut bias_squared, mut noise_squared) = (0.0, 0.0);
            for (i, &truth) in reference.iter().enumerate() {
                let values: Vec<f64> = estimates.iter().map(|e| e[i] / truth).collect();
                let seed_mean = values.iter().sum::<f64>() / SEEDS as f64;
                bias_squared += (seed_mean - 1.0).powi(2);
                noise_squared += values.iter().map(|v| (v - seed_mean).powi(2)).sum::<f64>() / (SEEDS - 1) as f64;
            }
            let n = reference.len() as f64;
            let noise = (noise_squared / n).sqrt();
            let bias = (bias_squared / n - noise * noise / SEEDS as f64 - reference_variance).max(0.0).sqrt();
            let rms = (bias * bias + noise * noise).sqrt();
            let _ = writeln!(
                csv,
                "{photons},{k},{bias:.4e},{noise:.4e},{rms:.4e},{trace_seconds:.4e},{gather_microseconds:.4e}"
            );
            let _ = writeln!(
                table,
                "| {photons} | {k} | {bias:.3e} | {noise:.3e} | {rms:.3e} | {trace_seconds:.3e} | {gather_microseconds:.3} |"
            );
        }
    }
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/data");
    std::fs::create_dir_all(data).expect("docs/data is writable");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/render_caustic_k.csv")), csv.as_bytes())
        .expect("write the CSV");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/render_caustic_k.md")), table.as_bytes())
        .expect("write the table");
}
