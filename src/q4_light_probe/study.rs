//! Shared tools of the accuracy study: test normals, peak-normalised errors, and the table of
//! methods and parameters the benchmark sweeps.

use super::irradiance::{Irradiance, Method};
use super::maps::AnalyticMap;
use glam::DVec3;
use rand_core::SeedableRng;
use rand_pcg::Pcg64;

/// `n` unit normals spread evenly over the sphere (a Fibonacci spiral), deterministic.
///
/// # Examples
/// ```
/// let normals = hw3::q4_light_probe::fibonacci_normals(64);
/// assert_eq!(normals.len(), 64);
/// assert!(normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-12));
/// ```
#[must_use]
pub fn fibonacci_normals(n: usize) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * i as f64;
            DVec3::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

/// Error of a method over a set of normals, as percentages of the peak exact irradiance
/// (peak-normalised, so that grazing normals where `E → 0` do not blow up a relative error).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorSummary {
    /// Mean over normals (for Monte Carlo: of each normal's RMS error over seeds).
    pub mean_percent: f64,
    /// Worst normal.
    pub max_percent: f64,
}

/// The error of `method` (first channel) against `map`'s exact irradiance over `normals`; Monte
/// Carlo methods are run once per seed and summarised by their RMS error per normal.
///
/// # Panics
/// If `normals` is empty, `seeds` is empty, or a normal is not a unit vector (internal tool).
///
/// # Examples
/// ```
/// use hw3::q4_light_probe::{horizontal_camera, maps::AnalyticMap, study, irradiance::{Irradiance, Method}, Probe, ProbeFormat};
/// let map = AnalyticMap::constant(1.0);
/// let probe = Probe::from_map(&map, ProbeFormat::MirrorBall, 16, horizontal_camera()).unwrap();
/// let e = study::method_error(&map, &Irradiance::new(&probe), Method::Cosine, 8, &[1, 2], &study::fibonacci_normals(8));
/// assert!(e.max_percent < 1e-10);
/// ```
#[must_use]
pub fn method_error(
    map: &AnalyticMap,
    prepared: &Irradiance<'_>,
    method: Method,
    samples: usize,
    seeds: &[u64],
    normals: &[DVec3],
) -> ErrorSummary {
    assert!(!normals.is_empty() && !seeds.is_empty());
    let exact: Vec<f64> = normals.iter().map(|n| map.irradiance(*n)).collect();
    let peak = exact.iter().copied().fold(0.0, f64::max);
    let seeds = if method.is_monte_carlo() {
        seeds
    } else {
        &seeds[..1]
    };
    let errors: Vec<f64> = normals
        .iter()
        .zip(&exact)
        .map(|(n, e)| {
            let squared: f64 = seeds
                .iter()
                .map(|seed| {
                    let mut rng = Pcg64::seed_from_u64(*seed);
                    let got = prepared
                        .estimate(*n, method, samples, &mut rng)
                        .expect("unit normals and samples ≥ 1");
                    (got.x - e).powi(2)
                })
                .sum();
            (squared / seeds.len() as f64).sqrt() / peak * 100.0
        })
        .collect();
    ErrorSummary {
        mean_percent: errors.iter().sum::<f64>() / errors.len() as f64,
        max_percent: errors.iter().copied().fold(0.0, f64::max),
    }
}

/// One configuration of the accuracy-versus-time study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Config {
    /// The method.
    pub method: Method,
    /// Probe size (texels across).
    pub size: usize,
    /// Samples per normal (Monte Carlo only; 0 otherwise).
    pub samples: usize,
}

impl Config {
    /// A label such as `weighted 64²` or `cosine N=256`.
    #[must_use]
    pub fn label(&self) -> String {
        if self.method.is_monte_carlo() {
            format!("{} N={}", self.method.name(), self.samples)
        } else {
            format!("{} {}²", self.method.name(), self.size)
        }
    }
}

/// The study's maps: `(name, map)` for the soft sky and the sun.
#[must_use]
pub fn study_maps() -> [(&'static str, AnalyticMap); 2] {
    [("soft", AnalyticMap::soft()), ("sun", AnalyticMap::sun())]
}

/// The direction of the sun in [`AnalyticMap::sun`] (elevation 30° toward `+x`).
///
/// # Examples
/// ```
/// let s = hw3::q4_light_probe::study::sun_direction();
/// assert!((s.z - 0.5).abs() < 1e-12);
/// ```
#[must_use]
pub fn sun_direction() -> DVec3 {
    let elevation = 30f64.to_radians();
    DVec3::new(elevation.cos(), 0.0, elevation.sin())
}

/// Every configuration the benchmark measures: texel sums and SH9 at each probe size, Monte Carlo
/// at each sample count on a 256² probe.
#[must_use]
pub fn configurations() -> Vec<Config> {
    let mut configs = Vec::new();
    for size in [16, 32, 64, 128, 256] {
        for method in [Method::Unweighted, Method::Weighted, Method::Sh9] {
            configs.push(Config {
                method,
                size,
                samples: 0,
            });
        }
    }
    for samples in [16, 64, 256, 1024, 4096] {
        for method in [Method::Uniform, Method::Cosine, Method::Map, Method::Mis] {
            configs.push(Config {
                method,
                size: 256,
                samples,
            });
        }
    }
    configs
}
