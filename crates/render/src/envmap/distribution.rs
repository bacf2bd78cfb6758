//! Importance sampling of an environment map's directions: texels in proportion to luminance ×
//! solid angle, then a point uniformly in the chosen texel's image area, with the exact
//! solid-angle pdf of the result. Irradiance estimators (light-probe question) and the
//! renderer's environment light share it.

use super::probe::Probe;
use glam::{DVec2, DVec3};

/// Rec. 709 / sRGB primaries' luminance weights `(0.2126, 0.7152, 0.0722)` (ITU-R BT.709-6,
/// item 3.2): the relative luminance `Y` of a linear RGB colour.
pub const LUMINANCE_WEIGHTS: DVec3 = DVec3::new(0.2126, 0.7152, 0.0722);

/// The relative luminance `Y` of linear RGB `c` (the dot product with [`LUMINANCE_WEIGHTS`]): the
/// scalar [`MapDistribution`] follows (equal to the value itself for grey radiance), and the one
/// the renderer compares images by and weighs lights' powers by. Linear: no transfer curve.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_render::envmap::luminance;
/// assert!((luminance(DVec3::splat(2.0)) - 2.0).abs() < 1e-15);
/// assert!((luminance(DVec3::ONE) - 1.0).abs() < 1e-15); // the weights sum to 1
/// assert_eq!(luminance(DVec3::Y), 0.7152);
/// ```
#[must_use]
pub fn luminance(c: DVec3) -> f64 {
    c.dot(LUMINANCE_WEIGHTS)
}

/// What one map sample returns: the direction, its solid-angle pdf, and the texel.
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3_render::envmap::{MapDistribution, Probe, ProbeFormat};
/// let probe = Probe::from_fn(ProbeFormat::LatLong, 16, 8, DMat3::IDENTITY, |w| DVec3::splat(1.0 + w.z)).unwrap();
/// let distribution = MapDistribution::new(&probe);
/// let mut numbers = [0.9, 0.5, 0.5].into_iter().cycle();
/// let sample = distribution.sample(&probe, &mut || numbers.next().unwrap()).unwrap();
/// assert_eq!(probe.texel_index_toward(sample.omega), Some(sample.texel));
/// assert!(sample.pdf > 0.0 && (sample.omega.length() - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapSample {
    /// The sampled world direction (unit).
    pub omega: DVec3,
    /// Its solid-angle pdf (per steradian).
    pub pdf: f64,
    /// The texel it lies in (its radiance is the probe's radiance toward `omega`).
    pub texel: usize,
}

/// Importance sampling of a probe's directions in proportion to texel luminance × solid angle:
/// the "map" strategy of the light-probe question's irradiance estimators and the renderer's
/// environment-light sampler. It owns only the cumulative table; the probe is passed to each call, so
/// the table can be stored next to the probe it was built from.
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3_render::envmap::{MapDistribution, Probe, ProbeFormat};
/// let probe = Probe::from_fn(ProbeFormat::LatLong, 16, 8, DMat3::IDENTITY, |w| DVec3::splat(1.0 + w.z)).unwrap();
/// let distribution = MapDistribution::new(&probe);
/// let mut numbers = [0.3, 0.6, 0.2].into_iter().cycle();
/// let sample = distribution.sample(&probe, &mut || numbers.next().unwrap()).unwrap();
/// assert!((distribution.pdf(&probe, sample.omega) - sample.pdf).abs() < 1e-12 * sample.pdf);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct MapDistribution {
    /// Cumulative `luminance × Δω` over all texels (unnormalised).
    cdf: Vec<f64>,
}

impl MapDistribution {
    /// The table of `probe`.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{MapDistribution, Probe, ProbeFormat};
    /// let probe = Probe::from_fn(ProbeFormat::LatLong, 16, 8, DMat3::IDENTITY, |w| DVec3::splat(1.0 + w.z)).unwrap();
    /// let distribution = MapDistribution::new(&probe);
    /// // ∫ luminance dω of L = 1 + ω_z over the sphere is 4π; texel sums get it to rounding.
    /// assert!((distribution.total_power() - 4.0 * std::f64::consts::PI).abs() < 1e-9);
    /// ```
    #[must_use]
    pub fn new(probe: &Probe) -> Self {
        let mut running = 0.0;
        let cdf = probe
            .texels()
            .iter()
            .map(|t| {
                running += luminance(t.radiance) * t.solid_angle;
                running
            })
            .collect();
        Self { cdf }
    }

    /// `Σ luminance × Δω` (the map's luminous "power"); 0 for a black map, which has no samples.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{MapDistribution, Probe, ProbeFormat};
    /// let black = Probe::from_fn(ProbeFormat::MirrorBall, 4, 4, DMat3::IDENTITY, |_| DVec3::ZERO).unwrap();
    /// assert_eq!(MapDistribution::new(&black).total_power(), 0.0);
    /// ```
    #[must_use]
    pub fn total_power(&self) -> f64 {
        self.cdf.last().copied().unwrap_or(0.0)
    }

    /// Draws a texel in proportion to luminance × Δω, then a point uniformly in the texel's image
    /// area inside the domain; the solid-angle pdf is `p_t / (A_t · dω/dA)`. `uniform` supplies
    /// numbers in `[0, 1)`: one for the texel, two per rejection try. `probe` must be the probe
    /// the table was built from.
    ///
    /// Returns `None` for a black map, and when a rim texel of a disk format rejects all 64 tries
    /// (a texel with a fraction `f` of its square inside the disk fails with probability
    /// `(1 − f)^64`; the sample then counts as zero, a bias below 1e-3 of that texel's share —
    /// already tiny, since `Δω ∝ f` — unless `f < 0.1`). Lat-long texels lie wholly inside
    /// their domain and never fail: sampling a lat-long map is exactly unbiased.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{MapDistribution, Probe, ProbeFormat};
    /// let probe = Probe::from_fn(ProbeFormat::LatLong, 16, 8, DMat3::IDENTITY, |w| DVec3::splat(1.0 + w.z)).unwrap();
    /// let distribution = MapDistribution::new(&probe);
    /// let mut rng = hw3_core::rng::seeded(1, 0);
    /// // Bright directions (up) are drawn more often than dark ones (down).
    /// let up = (0..1000)
    ///     .filter_map(|_| distribution.sample(&probe, &mut || hw3_core::rng::uniform(&mut rng)))
    ///     .filter(|s| s.omega.z > 0.0)
    ///     .count();
    /// assert!(up > 600, "{up}");
    /// ```
    pub fn sample(&self, probe: &Probe, uniform: &mut dyn FnMut() -> f64) -> Option<MapSample> {
        let total = self.total_power();
        if total <= 0.0 {
            return None;
        }
        let target = uniform() * total;
        let texel = self.cdf.partition_point(|c| *c <= target).min(self.cdf.len() - 1);
        let rect = probe.texel_rect(texel);
        for _ in 0..64 {
            let u = DVec2::new(uniform(), uniform());
            let p = rect.min + (rect.max - rect.min) * u;
            if let Some((omega, jacobian)) = probe.image_to_world(p)
                && probe.texel_index_at(p) == texel
                && jacobian > 0.0
            {
                return Some(MapSample {
                    omega,
                    pdf: self.texel_probability(probe, texel) / (probe.texels()[texel].area * jacobian),
                    texel,
                });
            }
        }
        None
    }

    fn texel_probability(&self, probe: &Probe, texel: usize) -> f64 {
        let t = &probe.texels()[texel];
        luminance(t.radiance) * t.solid_angle / self.total_power()
    }

    /// The solid-angle pdf with which [`Self::sample`] draws direction `omega` (unit); 0 for a
    /// black map or a blind direction.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{MapDistribution, Probe, ProbeFormat};
    /// let probe = Probe::from_fn(ProbeFormat::LatLong, 16, 8, DMat3::IDENTITY, |w| DVec3::splat(1.0 + w.z)).unwrap();
    /// let distribution = MapDistribution::new(&probe);
    /// // Brighter directions are likelier: luminance 1 + ω_z.
    /// let up = distribution.pdf(&probe, DVec3::new(0.6, 0.0, 0.8));
    /// let side = distribution.pdf(&probe, DVec3::X);
    /// assert!(up > side && side > 0.0);
    /// let black = Probe::from_fn(ProbeFormat::LatLong, 4, 2, DMat3::IDENTITY, |_| DVec3::ZERO).unwrap();
    /// assert_eq!(MapDistribution::new(&black).pdf(&black, DVec3::X), 0.0);
    /// ```
    #[must_use]
    pub fn pdf(&self, probe: &Probe, omega: DVec3) -> f64 {
        if self.total_power() <= 0.0 {
            return 0.0;
        }
        let Some(p) = probe.world_to_image(omega) else {
            return 0.0;
        };
        let texel = probe.texel_index_at(p);
        let t = &probe.texels()[texel];
        let jacobian = probe.format().jacobian(p);
        if t.area <= 0.0 || jacobian <= 0.0 {
            return 0.0;
        }
        self.texel_probability(probe, texel) / (t.area * jacobian)
    }
}
