//! Shared tools of the accuracy study: peak-normalised errors, the study's maps, and the table
//! of methods and parameters the benchmark sweeps.

use super::irradiance::{Estimator, Irradiance};
use super::maps::AnalyticMap;
use crate::envmap::{BuiltinMap, Probe, ProbeError, ProbeFormat, horizontal_camera, luminance};
use glam::DVec3;

/// Error of a method over a set of normals, as percentages of the peak exact irradiance
/// (peak-normalised, so that grazing normals where `E → 0` do not blow up a relative error).
///
/// # Examples
/// ```
/// use hw3::envmap::{horizontal_camera, ProbeFormat};
/// use hw3::q4_light_probe::{fibonacci_normals, maps::AnalyticMap, study, Irradiance, Estimator};
/// let map = AnalyticMap::sky();
/// let probe = map.rasterise(ProbeFormat::AngularMap, 32, horizontal_camera()).unwrap();
/// let e = study::analytic_error(&map, &Irradiance::new(&probe), Estimator::Weighted, 1, &[0], &fibonacci_normals(16));
/// assert!(e.max_percent >= e.mean_percent && e.mean_percent > 0.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorSummary {
    /// Mean over normals (for Monte Carlo: of each normal's RMS error over seeds).
    pub mean_percent: f64,
    /// Worst normal.
    pub max_percent: f64,
    /// Mean over normals of the error relative to that normal's own reference, where the
    /// reference exceeds 1 % of the peak (grazing normals are left out): the metric papers quote.
    pub mean_relative_percent: f64,
}

/// The error of `method` (luminance) against the exact `reference` irradiance at each of
/// `normals`; Monte Carlo methods are run once per seed and summarised by their RMS error per
/// normal.
///
/// # Panics
/// If `normals` or `seeds` is empty, `reference` has another length, or a normal is not a unit
/// vector (an internal tool with fixed inputs).
///
/// # Examples
/// ```
/// use hw3::envmap::{horizontal_camera, Probe, ProbeFormat};
/// use hw3::q4_light_probe::{maps::AnalyticMap, study, irradiance::{Irradiance, Estimator}};
/// let map = AnalyticMap::constant(1.0);
/// let probe = map.rasterise(ProbeFormat::MirrorBall, 16, horizontal_camera()).unwrap();
/// let normals = hw3::q4_light_probe::fibonacci_normals(8);
/// let exact: Vec<f64> = normals.iter().map(|n| map.irradiance(*n)).collect();
/// let e = study::method_error(&Irradiance::new(&probe), Estimator::Cosine, 8, &[1, 2], &normals, &exact);
/// assert!(e.max_percent < 1e-10);
/// ```
#[must_use]
pub fn method_error(
    prepared: &Irradiance<'_>,
    method: Estimator,
    samples: usize,
    seeds: &[u64],
    normals: &[DVec3],
    reference: &[f64],
) -> ErrorSummary {
    assert!(!normals.is_empty() && !seeds.is_empty() && reference.len() == normals.len());
    let peak = reference.iter().copied().fold(0.0, f64::max);
    let seeds = if method.is_monte_carlo() { seeds } else { &seeds[..1] };
    let errors: Vec<(f64, f64)> = normals
        .iter()
        .zip(reference)
        .map(|(n, e)| {
            let squared: f64 = seeds
                .iter()
                .map(|seed| {
                    let mut rng = crate::rng::seeded(*seed, 0);
                    let got = prepared.estimate(*n, method, samples, &mut rng).expect("unit normals and samples ≥ 1");
                    (luminance(got) - e).powi(2)
                })
                .sum();
            let rms = (squared / seeds.len() as f64).sqrt();
            (rms / peak * 100.0, rms / e.abs() * 100.0)
        })
        .collect();
    let relative: Vec<f64> =
        errors.iter().zip(reference).filter(|(_, e)| e.abs() > 0.01 * peak).map(|((_, r), _)| *r).collect();
    ErrorSummary {
        mean_percent: errors.iter().map(|e| e.0).sum::<f64>() / errors.len() as f64,
        max_percent: errors.iter().map(|e| e.0).fold(0.0, f64::max),
        mean_relative_percent: relative.iter().sum::<f64>() / relative.len().max(1) as f64,
    }
}

/// [`method_error`] against an analytic map's exact irradiance.
///
/// # Examples
/// ```
/// use hw3::envmap::{horizontal_camera, Probe, ProbeFormat};
/// use hw3::q4_light_probe::{maps::AnalyticMap, study, Irradiance, Estimator};
/// let map = AnalyticMap::sky();
/// let probe = map.rasterise(ProbeFormat::MirrorBall, 32, horizontal_camera()).unwrap();
/// let e = study::analytic_error(&map, &Irradiance::new(&probe), Estimator::Sh9, 1, &[0], &hw3::q4_light_probe::fibonacci_normals(16));
/// assert!(e.mean_percent < 0.5 && e.max_percent >= e.mean_percent);
/// ```
#[must_use]
pub fn analytic_error(
    map: &AnalyticMap,
    prepared: &Irradiance<'_>,
    method: Estimator,
    samples: usize,
    seeds: &[u64],
    normals: &[DVec3],
) -> ErrorSummary {
    let exact: Vec<f64> = normals.iter().map(|n| map.irradiance(*n)).collect();
    method_error(prepared, method, samples, seeds, normals, &exact)
}

/// A map of the accuracy study: analytic (exact irradiance known in closed form) or a real
/// lat-long HDR file (reference: its own solid-angle-weighted texel sum at full resolution).
///
/// # Examples
/// ```
/// use hw3::q4_light_probe::study::{self, StudyMap};
/// let normals = hw3::q4_light_probe::fibonacci_normals(4);
/// for (name, map) in study::study_maps().unwrap() {
///     let ball = map.ball(8).unwrap();
///     assert_eq!(ball.width(), 8);
///     assert!(map.reference(&normals).iter().all(|e| e.is_finite() && *e >= 0.0), "{name}");
/// }
/// ```
#[derive(Debug, Clone)]
pub enum StudyMap {
    /// A closed-form map.
    Analytic(AnalyticMap),
    /// A lat-long probe read from a file.
    LatLong(Probe),
}

impl StudyMap {
    /// The orthographic mirror-ball probe of `size`² texels synthesised from the map (camera on
    /// the +x horizon): analytic maps are rasterised, files are resampled by splatting
    /// ([`Probe::resample_lat_long`]).
    ///
    /// # Errors
    /// [`ProbeError`] for a zero size.
    ///
    /// # Examples
    /// ```
    /// use hw3::envmap::{BuiltinMap, ProbeFormat};
    /// use hw3::q4_light_probe::study::StudyMap;
    /// let map = StudyMap::LatLong(BuiltinMap::Courtyard.probe().unwrap());
    /// let ball = map.ball(16).unwrap();
    /// assert_eq!((ball.format(), ball.width()), (ProbeFormat::MirrorBall, 16));
    /// assert!(map.ball(0).is_err());
    /// ```
    pub fn ball(&self, size: usize) -> Result<Probe, ProbeError> {
        match self {
            Self::Analytic(map) => map.rasterise(ProbeFormat::MirrorBall, size, horizontal_camera()),
            Self::LatLong(source) => {
                Probe::resample_lat_long(source, ProbeFormat::MirrorBall, size, horizontal_camera())
            }
        }
    }

    /// The reference irradiance (luminance) at each normal.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::{maps::AnalyticMap, study::StudyMap};
    /// let sky = StudyMap::Analytic(AnalyticMap::sky());
    /// assert_eq!(sky.reference(&[DVec3::Z, -DVec3::Z]), [std::f64::consts::PI, 0.0]);
    /// ```
    #[must_use]
    pub fn reference(&self, normals: &[DVec3]) -> Vec<f64> {
        match self {
            Self::Analytic(map) => normals.iter().map(|n| map.irradiance(*n)).collect(),
            Self::LatLong(source) => {
                let prepared = Irradiance::new(source);
                normals.iter().map(|n| luminance(prepared.weighted(*n))).collect()
            }
        }
    }
}

/// One configuration of the accuracy-versus-time study.
///
/// # Examples
/// ```
/// use hw3::q4_light_probe::{study::Config, Estimator};
/// let config = Config { method: Estimator::Weighted, size: 64, samples: 0 };
/// assert_eq!(config.label(), "weighted 64²");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Config {
    /// The method.
    pub method: Estimator,
    /// Probe size (texels across).
    pub size: usize,
    /// Samples per normal (Monte Carlo only; 0 otherwise).
    pub samples: usize,
}

impl Config {
    /// A label such as `weighted 64²` or `cosine N=256`.
    ///
    /// # Examples
    /// ```
    /// use hw3::q4_light_probe::{study::Config, Estimator};
    /// assert_eq!(Config { method: Estimator::Cosine, size: 256, samples: 256 }.label(), "cosine N=256");
    /// ```
    #[must_use]
    pub fn label(&self) -> String {
        if self.method.is_monte_carlo() {
            format!("{} N={}", self.method.name(), self.samples)
        } else {
            format!("{} {}²", self.method.name(), self.size)
        }
    }
}

/// The study's maps: the analytic soft sky and sun, and the vendored real CC0 maps (soft
/// `courtyard`, hard `sunrise`).
///
/// # Errors
/// [`ProbeError`] if a vendored file cannot be read.
///
/// # Examples
/// ```
/// let names: Vec<_> = hw3::q4_light_probe::study::study_maps().unwrap().into_iter().map(|(name, _)| name).collect();
/// assert_eq!(names, ["soft", "sun", "courtyard", "sunrise"]);
/// ```
pub fn study_maps() -> Result<Vec<(&'static str, StudyMap)>, ProbeError> {
    Ok(vec![
        ("soft", StudyMap::Analytic(AnalyticMap::soft())),
        ("sun", StudyMap::Analytic(AnalyticMap::sun())),
        ("courtyard", StudyMap::LatLong(BuiltinMap::Courtyard.probe()?)),
        ("sunrise", StudyMap::LatLong(BuiltinMap::Sunrise.probe()?)),
    ])
}

/// Every configuration the benchmark measures: texel sums and SH9 at each probe size, Monte Carlo
/// at each sample count on a 256² probe.
///
/// # Examples
/// ```
/// let configs = hw3::q4_light_probe::study::configurations();
/// assert!(configs.iter().any(|c| c.label() == "sh9 256²"));
/// assert!(configs.iter().any(|c| c.label() == "mis N=4096"));
/// ```
#[must_use]
pub fn configurations() -> Vec<Config> {
    let mut configs = Vec::new();
    for size in [16, 32, 64, 128, 256] {
        for method in [Estimator::Unweighted, Estimator::Weighted, Estimator::Sh9] {
            configs.push(Config { method, size, samples: 0 });
        }
    }
    for samples in [16, 64, 256, 1024, 4096] {
        for method in [Estimator::Uniform, Estimator::Cosine, Estimator::Map, Estimator::Mis] {
            configs.push(Config { method, size: 256, samples });
        }
    }
    configs
}
