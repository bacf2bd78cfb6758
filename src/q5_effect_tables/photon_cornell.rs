//! The photon map's error in a scene with gradients: the global (`all`) map's radiance estimate
//! at fixed floor points of the Cornell box with the block ([`cornell_box`]) against the path tracer, for
//! several photon counts and k. `cargo bench -p hw3-benches --bench q5_photon` measures it and writes
//! `docs/data/q5_photon_cornell.md` and `.csv`; [`figure`] plots the committed CSV, so the
//! figures stay deterministic (timings come only from the benchmark).
//!
//! The error splits into the two parts the estimate trades against each other, measured over
//! several independent photon traces (seeds) per count: **noise** (the spread between seeds, about
//! `1/√(k − 2)` of the value, set by k) and **bias** (the seed-mean's error: the kNN disc blurs the
//! radiance over a radius `r ∝ √(k/N)`, so it grows with k and shrinks as photons are added).

use super::photon_accuracy::LogLogChart;
use crate::data::DataError;
use crate::geometry::{InputError, Ray};
use crate::plot::{Figure, PlotError};
use crate::render::catalogue::{CornellContents, cornell_box};
use crate::render::photon::{PhotonError, PhotonMap};
use crate::render::scene::Scene;
use crate::render::{analysis::analyze, passes::Pass};
use crate::render::{
    integrator::{Integrator, Tracer},
    sampling::Sampler,
};
use glam::DVec3;
use plotters::prelude::SeriesLabelPosition;
use rayon::prelude::*;

/// File name of the committed measurement (under `docs/data/`).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::photon_cornell::{CSV_NAME, parse};
/// // The committed file, compiled in, parses: one row per photon count and k.
/// assert!(CSV_NAME.ends_with(".csv") && parse(hw3::data::Q5_PHOTON_CORNELL).unwrap().len() > 4);
/// ```
pub const CSV_NAME: &str = "q5_photon_cornell.csv";

/// The box ([`cornell_box`] with the red wall) and the probe rays: straight down onto a 6 × 6 grid
/// of floor points 0.36 apart (`x, z ∈ [−0.9, 0.9]`), less the four inside the block: 32 points
/// from the corners by the walls to the block's edges, where the radiance has its gradients.
///
/// # Errors
/// Never for the built-in scene.
///
/// # Examples
/// ```
/// let (_, probes) = hw3::q5_effect_tables::photon_cornell::scene_and_probes().unwrap();
/// assert_eq!(probes.len(), 32);
/// ```
pub fn scene_and_probes() -> Result<(Scene, Vec<Ray<f64>>), InputError> {
    let scene = cornell_box(true, CornellContents::Block)?;
    let coordinates = (0..6).map(|i| -0.9 + 0.36 * f64::from(i));
    let probes = coordinates
        .clone()
        .flat_map(|z| coordinates.clone().map(move |x| DVec3::new(x, -1.0, z)))
        .filter(|p| !((0.1..0.7).contains(&p.x) && (-0.3..0.3).contains(&p.z)))
        .map(|p| Ray { origin: p + DVec3::Y * 0.05, dir: DVec3::NEG_Y })
        .collect();
    Ok((scene, probes))
}

/// The path-traced reference at each probe: channel-mean radiance and its standard error.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::photon_cornell::{reference, scene_and_probes};
/// let (scene, probes) = scene_and_probes().unwrap();
/// let truth = reference(&scene, &probes[..3], 16);
/// assert_eq!((truth.radiance.len(), truth.standard_error.len()), (3, 3));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    /// Mean radiance per probe.
    pub radiance: Vec<f64>,
    /// Standard error of each mean (sample standard deviation over `√spp`).
    pub standard_error: Vec<f64>,
}

impl Reference {
    /// The largest relative standard error over the probes.
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::photon_cornell::Reference;
    /// let reference = Reference { radiance: vec![2.0, 4.0], standard_error: vec![0.1, 0.4] };
    /// assert_eq!(reference.max_relative_error(), 0.1);
    /// ```
    #[must_use]
    pub fn max_relative_error(&self) -> f64 {
        self.radiance.iter().zip(&self.standard_error).map(|(l, s)| s / l).fold(0.0, f64::max)
    }
}

/// Path-traces `spp` samples along every probe (every bounce on, 12 at most; probe `i` draws from
/// stream `(7, i)`, so the result does not depend on the thread count). The same as
/// [`reference_seeded`] with seed 7.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::photon_cornell::{reference, scene_and_probes};
/// let (scene, probes) = scene_and_probes().unwrap();
/// let truth = reference(&scene, &probes[..2], 64);
/// assert!(truth.radiance.iter().all(|&l| l > 0.0) && truth.max_relative_error() > 0.0);
/// ```
#[must_use]
pub fn reference(scene: &Scene, probes: &[Ray<f64>], spp: u32) -> Reference {
    reference_seeded(scene, probes, u64::from(spp), 7)
}

/// Samples of one random stream in [`reference_seeded`]: a long reference is cut into chunks of
/// this many samples, each its own stream, so that both cores share the work of a single probe.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{cornell_published::REFERENCE_SPP, photon_cornell::REFERENCE_CHUNK};
/// // The committed published-box reference is 64 chunks per probe.
/// assert_eq!(REFERENCE_SPP / REFERENCE_CHUNK, 64);
/// ```
pub const REFERENCE_CHUNK: u64 = 1 << 17;

/// Path-traces `spp` samples along every probe with random seed `seed` (every bounce on, 12 at
/// most). Sample chunk `c` ([`REFERENCE_CHUNK`] samples) of probe `i` draws from stream
/// `(seed, i, c)` and the chunks are summed in order, so the result depends on neither the thread
/// count nor the scheduling; two seeds give independent references.
///
/// The standard error is the sample standard deviation over `√spp`; the sums are `f64`, whose
/// rounding (about `spp · 2⁻⁵³` relative) stays far below it for any count that finishes.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::photon_cornell::{reference, reference_seeded, scene_and_probes};
/// let (scene, probes) = scene_and_probes().unwrap();
/// assert_eq!(reference_seeded(&scene, &probes[..1], 32, 7), reference(&scene, &probes[..1], 32));
/// assert_ne!(reference_seeded(&scene, &probes[..1], 32, 8), reference(&scene, &probes[..1], 32));
/// ```
#[must_use]
pub fn reference_seeded(scene: &Scene, probes: &[Ray<f64>], spp: u64, seed: u64) -> Reference {
    let integrator = Integrator::PathTracer { max_depth: 12 };
    let passes = analyze(scene).plan.with(Pass::IndirectBounces, true);
    let tracer = Tracer::new(scene, passes);
    let chunks = spp.div_ceil(REFERENCE_CHUNK).max(1);
    let sums: Vec<(f64, f64)> = (0..probes.len() as u64 * chunks)
        .into_par_iter()
        .map(|job| {
            let (i, chunk) = (job / chunks, job % chunks);
            let count = REFERENCE_CHUNK.min(spp - (chunk * REFERENCE_CHUNK).min(spp));
            let mut sampler = Sampler::new(seed, i, chunk);
            let (mut sum, mut squares) = (0.0, 0.0);
            for _ in 0..count {
                let l = tracer.radiance(integrator, &probes[i as usize], 0.0, &mut sampler).element_sum() / 3.0;
                sum += l;
                squares += l * l;
            }
            (sum, squares)
        })
        .collect();
    let (radiance, standard_error) = sums
        .chunks(chunks as usize)
        .map(|probe| {
            let (sum, squares) = probe.iter().fold((0.0, 0.0), |(s, q), &(a, b)| (s + a, q + b));
            let n = spp as f64;
            let mean = sum / n;
            let variance = ((squares - n * mean * mean) / (n - 1.0).max(1.0)).max(0.0);
            (mean, (variance / n).sqrt())
        })
        .unzip();
    Reference { radiance, standard_error }
}

/// The global map's channel-mean radiance estimate at every probe's hit, with `k` neighbours.
///
/// # Errors
/// As [`PhotonMap::radiance`] (fewer than `k` photons, `k < 2`); a probe that misses the scene
/// estimates 0.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::photon_cornell::{estimates, scene_and_probes};
/// use hw3::render::photon::trace_photons;
/// let (scene, probes) = scene_and_probes().unwrap();
/// let map = trace_photons(&scene, 5000, 1).unwrap().into_all();
/// assert!(estimates(&scene, &map, &probes, 16).unwrap().iter().all(|&l| l > 0.0));
/// assert!(estimates(&scene, &map, &probes, 1).is_err()); // k < 2
/// ```
pub fn estimates(scene: &Scene, map: &PhotonMap, probes: &[Ray<f64>], k: usize) -> Result<Vec<f64>, PhotonError> {
    probes
        .iter()
        .map(|ray| {
            let Some(hit) = scene.closest_hit(ray, 0.0, f64::INFINITY) else { return Ok(0.0) };
            let material = scene.objects()[hit.object].material;
            let normal = if ray.dir.dot(hit.normal) < 0.0 { hit.normal } else { -hit.normal };
            Ok(map.radiance(&material, hit.point, -ray.dir, normal, k)?.element_sum() / 3.0)
        })
        .collect()
}

/// Relative error of estimates against a reference, over probes and independent traces.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::photon_cornell::error_split;
/// // Two traces exactly 10 % high: all bias, no noise.
/// let split = error_split(&[vec![1.1, 2.2], vec![1.1, 2.2]], &[1.0, 2.0]);
/// assert!(split.noise == 0.0 && (split.bias - 0.1).abs() < 1e-12 && (split.rms - split.bias).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorSplit {
    /// Root mean square of `estimate/reference − 1` over every probe and trace.
    pub rms: f64,
    /// Root mean square over probes of the trace-mean error, less the part the noise leaves in
    /// a mean of `S` traces (`noise²/S`): the systematic error, blur and the disc's leaks.
    pub bias: f64,
    /// Root mean square over probes of the spread between traces (sample standard deviation).
    pub noise: f64,
}

/// Splits the error of `traces` (one vector of estimates per independent trace, at least two)
/// against `reference`: `rms² = bias² + noise²` exactly, unless the bias estimate (unbiased for
/// the squared bias, so it can dip below 0 when the bias is small against the noise) is clamped
/// at 0.
///
/// # Panics
/// If fewer than two traces are given or a trace's length differs from the reference's.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::photon_cornell::error_split;
/// // Errors +10 % and +30 % at both probes: mean +20 %, spread √0.02 between the two traces.
/// let split = error_split(&[vec![1.1, 1.3], vec![1.3, 1.1]], &[1.0, 1.0]);
/// assert!((split.noise - 0.02f64.sqrt()).abs() < 1e-12);
/// assert!((split.bias - 0.03f64.sqrt()).abs() < 1e-12); // 0.2² − 0.02/2
/// assert!((split.rms - 0.05f64.sqrt()).abs() < 1e-12);
/// ```
#[must_use]
pub fn error_split(traces: &[Vec<f64>], reference: &[f64]) -> ErrorSplit {
    assert!(traces.len() >= 2, "the noise needs at least two traces");
    assert!(traces.iter().all(|t| t.len() == reference.len()), "one estimate per probe");
    let s = traces.len() as f64;
    let (mut squares, mut mean_squares, mut variances) = (0.0, 0.0, 0.0);
    for (p, &truth) in reference.iter().enumerate() {
        let errors: Vec<f64> = traces.iter().map(|t| t[p] / truth - 1.0).collect();
        let mean = errors.iter().sum::<f64>() / s;
        squares += errors.iter().map(|e| e * e).sum::<f64>();
        mean_squares += mean * mean;
        variances += errors.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (s - 1.0);
    }
    let probes = reference.len() as f64;
    let noise_squared = variances / probes;
    ErrorSplit {
        rms: (squares / (s * probes)).sqrt(),
        bias: (mean_squares / probes - noise_squared / s).max(0.0).sqrt(),
        noise: noise_squared.sqrt(),
    }
}

/// Least-squares slope of `ln y` against `ln x`.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::photon_cornell::log_log_slope;
/// let points: Vec<(f64, f64)> = [1e4, 1e5, 1e6].iter().map(|&n: &f64| (n, 3.0 * n.powf(-1.0 / 3.0))).collect();
/// assert!((log_log_slope(&points) + 1.0 / 3.0).abs() < 1e-12);
/// ```
#[must_use]
pub fn log_log_slope(points: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x.ln(), y.ln())).collect();
    let n = logs.len() as f64;
    let (mx, my) = (logs.iter().map(|p| p.0).sum::<f64>() / n, logs.iter().map(|p| p.1).sum::<f64>() / n);
    let covariance: f64 = logs.iter().map(|&(x, y)| (x - mx) * (y - my)).sum();
    let spread: f64 = logs.iter().map(|&(x, _)| (x - mx).powi(2)).sum();
    covariance / spread
}

/// One row of the committed CSV.
///
/// # Examples
/// ```
/// let rows = hw3::q5_effect_tables::photon_cornell::parse(hw3::data::Q5_PHOTON_CORNELL).unwrap();
/// // More neighbours: less noise, at every photon count of the committed measurement.
/// let first = rows.iter().filter(|r| r.photons == rows[0].photons).collect::<Vec<_>>();
/// assert!(first.windows(2).all(|w| w[0].k < w[1].k && w[0].error.noise > w[1].error.noise));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// Photons emitted per trace.
    pub photons: f64,
    /// Neighbours of the estimate.
    pub k: f64,
    /// Seconds to trace one photon map (mean over the traces).
    pub trace_seconds: f64,
    /// Seconds for the probes' queries in one map.
    pub query_seconds: f64,
    /// The error split over probes and traces.
    pub error: ErrorSplit,
    /// The reference's largest relative standard error over the probes.
    pub reference_error: f64,
}

/// Parses the CSV (header `photons,k,trace_seconds,query_seconds,rms,bias,noise,reference_error`).
///
/// # Errors
/// [`DataError::NotANumber`] for the first record with a non-numeric field,
/// [`DataError::FieldCount`] for the first with other than 8 fields.
///
/// # Examples
/// ```
/// use hw3::data::DataError;
/// use hw3::q5_effect_tables::photon_cornell::parse;
/// let rows = parse("header\n10000,32,0.01,0.001,0.2,0.1,0.17,0.004\n").unwrap();
/// assert_eq!((rows[0].k, rows[0].error.bias), (32.0, 0.1));
/// assert!(matches!(parse("header\n1,2\n"), Err(DataError::FieldCount { expected: 8, got: 2, .. })));
/// ```
pub fn parse(csv: &str) -> Result<Vec<Row>, DataError> {
    super::photon_accuracy::numeric_rows(csv, CSV_NAME)?
        .into_iter()
        .map(|fields| match fields[..] {
            [photons, k, trace_seconds, query_seconds, rms, bias, noise, reference_error] => Ok(Row {
                photons,
                k,
                trace_seconds,
                query_seconds,
                error: ErrorSplit { rms, bias, noise },
                reference_error,
            }),
            _ => Err(DataError::FieldCount { file: CSV_NAME, expected: 8, got: fields.len() }),
        })
        .collect()
}

/// For each photon count, the row of smallest RMS error (the best k for that count).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::photon_cornell::{best_k, parse};
/// let rows = parse("h\n1e4,8,0,0,0.4,0,0.4,0\n1e4,32,0,0,0.2,0,0.2,0\n1e5,8,0,0,0.4,0,0.4,0\n").unwrap();
/// let best: Vec<(f64, f64)> = best_k(&rows).iter().map(|r| (r.photons, r.k)).collect();
/// assert_eq!(best, [(1e4, 32.0), (1e5, 8.0)]);
/// ```
#[must_use]
pub fn best_k(rows: &[Row]) -> Vec<Row> {
    let mut best: Vec<Row> = Vec::new();
    for row in rows {
        match best.iter_mut().find(|b| b.photons == row.photons) {
            Some(b) if row.error.rms < b.error.rms => *b = *row,
            Some(_) => {}
            None => best.push(*row),
        }
    }
    best
}

/// The log-log chart of RMS error against photon count, one line per k, with the best-k envelope
/// and its fitted slope in the legend.
///
/// # Errors
/// [`PlotError`] when the CSV is missing or malformed, or drawing fails.
///
/// # Examples
/// ```
/// let figure = hw3::q5_effect_tables::photon_cornell::figure().unwrap();
/// assert_eq!(figure.file_name, "q5_photon_cornell.svg");
/// ```
pub fn figure() -> Result<Figure, PlotError> {
    let name = "q5_photon_cornell.svg";
    let rows = super::photon_accuracy::read_committed(crate::data::Q5_PHOTON_CORNELL, name, parse)?;
    let mut ks: Vec<f64> = rows.iter().map(|r| r.k).collect();
    ks.sort_by(f64::total_cmp);
    ks.dedup();
    let envelope: Vec<(f64, f64)> = best_k(&rows).iter().map(|r| (r.photons, r.error.rms)).collect();
    let slope = log_log_slope(&envelope);
    let lines = ks
        .iter()
        .map(|&k| {
            let points = rows.iter().filter(|r| r.k == k).map(|r| (r.photons, r.error.rms)).collect();
            (format!("k = {k:.0}"), points)
        })
        .collect();
    LogLogChart {
        name,
        caption: "Photon map in the Cornell box: error vs photons",
        x_range: (5e3, 2e6),
        y_range: (0.03, 1.0),
        x_desc: "photons emitted",
        y_desc: "relative RMS error of L",
        lines,
        dashed: (format!("best k: slope {slope:.2}"), envelope),
        tick_formats: Some((|x| format!("{x:.0e}"), |y| format!("{y:.2}"))),
        legend: Some(SeriesLabelPosition::LowerLeft),
    }
    .draw()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::photon::trace_photons;

    /// The committed measurement: the reference's own noise stays below a third of every error it
    /// judges; the noise stays above half the floor 1/√(k − 2) that k sets, whatever the photon
    /// count; and with the best k per count the error falls as photons are added (slope between −0.7 and −0.15, around the
    /// −1/3 that the bias–variance balance of a 2-D density estimate predicts).
    #[test]
    fn committed_cornell_accuracy_is_judged_by_a_converged_reference_and_falls_with_photons() {
        let rows =
            super::super::photon_accuracy::read_committed(crate::data::Q5_PHOTON_CORNELL, "test", parse).unwrap();
        assert!(rows.len() >= 12);
        for r in &rows {
            assert!(r.reference_error < r.error.rms / 3.0, "{r:?}");
            assert!(r.error.noise > 0.5 / (r.k - 2.0).sqrt(), "noise floor {r:?}");
        }
        let slope = log_log_slope(&best_k(&rows).iter().map(|r| (r.photons, r.error.rms)).collect::<Vec<_>>());
        assert!((-0.7..-0.15).contains(&slope), "{slope}");
    }

    /// The pipeline end to end at a small size: two 2·10⁴-photon maps at k = 32 land within 40 %
    /// RMS of a 256-sample reference (whose own error is up to about 15 % per probe), and the
    /// split adds up (rms² = bias² + noise² when the bias is not clamped).
    #[test]
    fn small_run_is_consistent() {
        let (scene, probes) = scene_and_probes().unwrap();
        let truth = reference(&scene, &probes, 256);
        assert!(truth.radiance.iter().all(|&l| l > 0.0));
        let traces: Vec<Vec<f64>> = (1..=2)
            .map(|seed| {
                estimates(&scene, &trace_photons(&scene, 20_000, seed).unwrap().into_all(), &probes, 32).unwrap()
            })
            .collect();
        let split = error_split(&traces, &truth.radiance);
        assert!(split.rms < 0.4, "{split:?}");
        assert!(split.bias > 0.0, "{split:?}");
        let rebuilt = (split.bias.powi(2) + split.noise.powi(2)).sqrt();
        assert!((rebuilt / split.rms - 1.0).abs() < 1e-12, "{split:?}");
    }
}
