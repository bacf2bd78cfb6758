//! Photon-map benchmarks.
//!
//! - divan: 1000 k-nearest queries (k = 50) in a map of 10⁵ photons with the photon map's own
//!   kd-tree ([`hw3::render::photon::PointTree`], what [`hw3::render::photon::PhotonMap`] uses),
//!   with a brute-force scan (`select_nth_unstable` over all squared distances), and, with
//!   `--features kiddo`, with `kiddo`'s `ImmutableKdTree` (6.3, the crate the photon map used
//!   before), each answer checked against the tree's; and the trees' builds over the same photons.
//! - `cargo bench -p hw3-benches --bench q5_photon` also measures the photon map's accuracy against time in the
//!   white furnace (closed unit sphere, ρ = 0.5, point light I = 1 at the centre, exact irradiance
//!   E = I/(1 − ρ) = 2 everywhere, which the path tracer reproduces to 1e-9 in
//!   `render::integrator`'s furnace test): the relative RMS error of the irradiance at 1000 wall
//!   points for photon counts 10⁴…10⁶ and k = 8…512, with the seconds of tracing and of the
//!   queries; writes `docs/data/q5_photon_accuracy.md` and `.csv`.
//! - and the same in a scene with gradients, the Cornell-like box: the global map's radiance at 32
//!   floor probes against a path-traced reference (2¹⁷ samples per probe, its standard error
//!   stated), for photon counts 10⁴…10⁶ and k = 8…2048, four independent traces each, the error
//!   split into bias and noise; writes `docs/data/q5_photon_cornell.md` and `.csv`
//!   ([`hw3::q5_effect_tables::photon_cornell`]).
//!
//! `cargo test --benches` runs each divan bench once and skips both measurements.

use glam::DVec3;
use hw3::q5_effect_tables::photon_cornell::{self, ErrorSplit};
use hw3::render::{
    catalogue::furnace_sphere,
    photon::{PhotonMap, PointTree, trace_photons},
    sampling::fibonacci_sphere,
};
use std::fmt::Write as _;
use std::time::Instant;

fn main() {
    if std::env::args().any(|a| a == "--bench") {
        write_accuracy_table();
        write_cornell_table();
    }
    divan::main();
}

fn furnace_map(photons: usize) -> PhotonMap {
    trace_photons(&furnace_sphere(0.5, 1.0).expect("valid scene"), photons, 1).expect("photons").into_all()
}

fn brute_force_nearest(points: &[DVec3], query: DVec3, k: usize) -> f64 {
    let mut distances: Vec<f64> = points.iter().map(|p| p.distance_squared(query)).collect();
    let (_, kth, _) = distances.select_nth_unstable_by(k - 1, f64::total_cmp);
    *kth
}

fn furnace_positions() -> Vec<DVec3> {
    furnace_map(50_000).photons().iter().map(|p| p.position).collect()
}

#[divan::bench]
fn knn_point_tree(bencher: divan::Bencher) {
    let tree = PointTree::new(&furnace_positions());
    let queries = fibonacci_sphere(1000);
    bencher.bench_local(|| {
        queries
            .iter()
            .map(|&q| tree.nearest(q, 50, f64::INFINITY).last().expect("50 found").distance_squared)
            .sum::<f64>()
    });
}

#[divan::bench]
fn build_point_tree(bencher: divan::Bencher) {
    let positions = furnace_positions();
    bencher.bench_local(|| PointTree::new(&positions));
}

/// `kiddo`'s tree as a peer: the same photons and queries; its 50 nearest must be the point
/// tree's (the same squared distances, nearest first; indices may differ only between photons
/// at equal distance).
#[cfg(feature = "kiddo")]
mod kiddo_peer {
    use super::*;
    use kiddo::{ImmutableKdTree, SquaredEuclidean};
    use std::num::NonZero;

    fn tree(positions: &[DVec3]) -> ImmutableKdTree<f64, 3> {
        let points: Vec<[f64; 3]> = positions.iter().map(|p| p.to_array()).collect();
        ImmutableKdTree::new_from_slice(&points).expect("fewer than 2³² photons")
    }

    #[divan::bench]
    fn knn_kiddo(bencher: divan::Bencher) {
        let positions = furnace_positions();
        let (kiddo, ours) = (tree(&positions), PointTree::new(&positions));
        let queries = fibonacci_sphere(1000);
        let fifty = NonZero::new(50).expect("50 > 0");
        // kiddo's 50 nearest, nearest first (`distance` is the squared distance).
        let nearest = |q: DVec3| kiddo.query(&q.to_array()).nearest_n::<SquaredEuclidean<f64>>(fifty).execute();
        for &q in &queries {
            let theirs: Vec<f64> = nearest(q).iter().map(|n| n.distance).collect();
            let mine: Vec<f64> = ours.nearest(q, 50, f64::INFINITY).iter().map(|n| n.distance_squared).collect();
            assert_eq!(theirs, mine, "kiddo and the point tree disagree at {q}");
        }
        bencher.bench_local(|| queries.iter().map(|&q| nearest(q).last().expect("50 found").distance).sum::<f64>());
    }

    #[divan::bench]
    fn build_kiddo(bencher: divan::Bencher) {
        let positions = furnace_positions();
        bencher.bench_local(|| tree(&positions));
    }
}

#[divan::bench(sample_count = 3)]
fn knn_brute_force(bencher: divan::Bencher) {
    let points = furnace_positions();
    let queries = fibonacci_sphere(1000);
    bencher.bench_local(|| queries.iter().map(|&q| brute_force_nearest(&points, q, 50)).sum::<f64>());
}

const PHOTONS: [usize; 4] = [10_000, 30_000, 100_000, 1_000_000];
const NEIGHBOURS: [usize; 5] = [8, 32, 128, 512, 2048];

fn write_accuracy_table() {
    let exact = 2.0;
    let queries = fibonacci_sphere(1000);
    let mut csv = String::from("photons,stored,k,trace_seconds,query_seconds,rms_error,mean_error\n");
    let mut table = String::from(
        "White furnace (closed unit sphere, ρ = 0.5, I = 1 at the centre, exact E = 2); irradiance from the `all` map at 1000 wall points, (k − 1)/(πr²) estimate. Seconds: tracing (2 threads) and the 1000 queries.\n\n| photons | stored | k | trace s | query s | RMS error | mean error |\n|---|---|---|---|---|---|---|\n",
    );
    for photons in PHOTONS {
        let start = Instant::now();
        let map = furnace_map(photons);
        let trace_seconds = start.elapsed().as_secs_f64();
        for k in NEIGHBOURS.into_iter().filter(|&k| k * 20 <= map.len()) {
            let start = Instant::now();
            let errors: Vec<f64> =
                queries.iter().map(|&q| map.irradiance(q, k).expect("enough photons").x / exact - 1.0).collect();
            let query_seconds = start.elapsed().as_secs_f64();
            let n = errors.len() as f64;
            let rms = (errors.iter().map(|e| e * e).sum::<f64>() / n).sqrt();
            let mean = errors.iter().sum::<f64>() / n;
            let stored = map.len();
            let _ =
                writeln!(csv, "{photons},{stored},{k},{trace_seconds:.4e},{query_seconds:.4e},{rms:.4e},{mean:.4e}");
            let _ = writeln!(
                table,
                "| {photons} | {stored} | {k} | {trace_seconds:.3} | {query_seconds:.4} | {:.2} % | {:+.2} % |",
                rms * 100.0,
                mean * 100.0
            );
        }
    }
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/data");
    std::fs::create_dir_all(data).expect("docs/data is writable");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q5_photon_accuracy.csv")), csv.as_bytes())
        .expect("write the CSV");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q5_photon_accuracy.md")), table.as_bytes())
        .expect("write the table");
}

const CORNELL_PHOTONS: [usize; 5] = [10_000, 30_000, 100_000, 300_000, 1_000_000];
const CORNELL_NEIGHBOURS: [usize; 5] = [8, 32, 128, 512, 2048];
const CORNELL_TRACES: u64 = 4;
const CORNELL_REFERENCE_SPP: u32 = 1 << 17;

fn write_cornell_table() {
    let (scene, probes) = photon_cornell::scene_and_probes().expect("built-in scene");
    let start = Instant::now();
    let reference = photon_cornell::reference(&scene, &probes, CORNELL_REFERENCE_SPP);
    let reference_seconds = start.elapsed().as_secs_f64();
    let reference_error = reference.max_relative_error();
    let mut csv = String::from("photons,k,trace_seconds,query_seconds,rms,bias,noise,reference_error\n");
    let mut rows = Vec::new();
    for photons in CORNELL_PHOTONS {
        let start = Instant::now();
        let maps: Vec<PhotonMap> = (1..=CORNELL_TRACES)
            .map(|seed| trace_photons(&scene, photons, seed).expect("photons").into_all())
            .collect();
        let trace_seconds = start.elapsed().as_secs_f64() / CORNELL_TRACES as f64;
        for k in CORNELL_NEIGHBOURS {
            let start = Instant::now();
            let traces: Vec<Vec<f64>> = maps
                .iter()
                .map(|map| photon_cornell::estimates(&scene, map, &probes, k).expect("enough photons"))
                .collect();
            let query_seconds = start.elapsed().as_secs_f64() / CORNELL_TRACES as f64;
            let ErrorSplit { rms, bias, noise } = photon_cornell::error_split(&traces, &reference.radiance);
            let _ = writeln!(
                csv,
                "{photons},{k},{trace_seconds:.4e},{query_seconds:.4e},{rms:.4e},{bias:.4e},{noise:.4e},{reference_error:.4e}"
            );
            rows.push(format!(
                "| {photons} | {k} | {trace_seconds:.3} | {query_seconds:.5} | {:.2} % | {:.2} % | {:.2} % |",
                rms * 100.0,
                bias * 100.0,
                noise * 100.0
            ));
        }
    }
    let parsed = photon_cornell::parse(&csv).expect("the CSV just written");
    let envelope: Vec<(f64, f64)> = photon_cornell::best_k(&parsed).iter().map(|r| (r.photons, r.error.rms)).collect();
    let slope = photon_cornell::log_log_slope(&envelope);
    let median_error = {
        let mut relative: Vec<f64> =
            reference.radiance.iter().zip(&reference.standard_error).map(|(l, s)| s / l).collect();
        relative.sort_by(f64::total_cmp);
        relative[relative.len() / 2]
    };
    let mut table = format!(
        "Cornell-like box, global photon map (`all`), (k − 1)/(πr²) radiance estimate at 32 floor probes against the path tracer ({CORNELL_REFERENCE_SPP} samples per probe, {reference_seconds:.1} s; relative standard error median {:.2} %, largest {:.2} %). {CORNELL_TRACES} independent traces per photon count; error relative, RMS over probes and traces, split into bias (error of the trace mean) and noise (spread between traces). Seconds per trace (2 threads) and per 32 queries. Best k per count: log-log slope {slope:.2}.\n\n| photons | k | trace s | query s | RMS error | bias | noise |\n|---|---|---|---|---|---|---|\n",
        median_error * 100.0,
        reference_error * 100.0
    );
    for row in rows {
        table.push_str(&row);
        table.push('\n');
    }
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/data");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q5_photon_cornell.csv")), csv.as_bytes())
        .expect("write the CSV");
    hw3::fsio::write_atomic(std::path::Path::new(&format!("{data}/q5_photon_cornell.md")), table.as_bytes())
        .expect("write the table");
}
