//! Analytic environment maps whose irradiance is known in closed form: the test oracles.
//!
//! Every map is a sum of [`Term`]s, each with radiance `L(ω)` and exact irradiance
//! `E(n) = ∫ L(ω) max(0, n·ω) dω` (closed forms, checked against an independent quadrature in the
//! tests). Oracles add linearly, so a sky plus a
//! sun is exact too. Radiance is grey (one number); probes store it in all three channels.

use crate::envmap::{Probe, ProbeError, ProbeFormat};
use glam::{DMat3, DVec3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// One analytic radiance term.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::q4_light_probe::maps::Term;
/// let lobe = Term::ClampedLobe { axis: DVec3::Z };
/// assert_eq!(lobe.radiance(DVec3::X), 0.0);
/// assert!((lobe.irradiance(DVec3::Z) - 2.0 * std::f64::consts::PI / 3.0).abs() < 1e-12);
/// let sun = Term::Cap { radiance: 1.0, centre: DVec3::Z, half_angle: 0.1 };
/// assert!((sun.cap_solid_angle().unwrap() - 2.0 * std::f64::consts::PI * (1.0 - 0.1f64.cos())).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Term {
    /// `L(ω) = radiance` everywhere. `E = π L`.
    Constant {
        /// The radiance.
        radiance: f64,
    },
    /// `L(ω) = a + b (ω·g)`, non-negative when `a ≥ |b|`. `E = π a + (2π/3) b (n·g)`.
    Linear {
        /// Constant part.
        a: f64,
        /// Gradient strength.
        b: f64,
        /// Unit gradient axis `g`.
        axis: DVec3,
    },
    /// `L(ω) = (ω·q)²`. `E = (π/4)(1 + (n·q)²)`.
    Quadratic {
        /// Unit axis `q`.
        axis: DVec3,
    },
    /// Hemisphere step: `L = radiance` where `ω·u > 0`. `E = (π/2) L (1 + cos α)`.
    Hemisphere {
        /// The radiance of the bright half.
        radiance: f64,
        /// Unit axis `u` (the sky's zenith).
        axis: DVec3,
    },
    /// Clamped lobe `L = max(0, ω·u)`. `E = (2/3)[(π−α) cos α + sin α]`.
    ClampedLobe {
        /// Unit axis `u`.
        axis: DVec3,
    },
    /// CIE overcast sky `L = L_z (1 + 2 ω·u)/3` above the horizon, 0 below.
    Overcast {
        /// Zenith radiance `L_z`.
        zenith: f64,
        /// Unit zenith `u`.
        axis: DVec3,
    },
    /// A uniform spherical cap (a "sun") of radiance `radiance` and half-angle `half_angle`.
    Cap {
        /// The cap's radiance `L_s`.
        radiance: f64,
        /// Unit centre direction `s`.
        centre: DVec3,
        /// Half-angle `δ` in radians, in `(0, π/2]`.
        half_angle: f64,
    },
}

impl Term {
    /// Radiance arriving from unit direction `omega`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::maps::Term;
    /// let gradient = Term::Linear { a: 1.0, b: 0.5, axis: DVec3::Z };
    /// assert_eq!(gradient.radiance(DVec3::Z), 1.5);
    /// assert_eq!(gradient.radiance(-DVec3::Z), 0.5);
    /// ```
    #[must_use]
    pub fn radiance(&self, omega: DVec3) -> f64 {
        match *self {
            Self::Constant { radiance } => radiance,
            Self::Linear { a, b, axis } => a + b * omega.dot(axis),
            Self::Quadratic { axis } => omega.dot(axis).powi(2),
            Self::Hemisphere { radiance, axis } => {
                if omega.dot(axis) > 0.0 {
                    radiance
                } else {
                    0.0
                }
            }
            Self::ClampedLobe { axis } => omega.dot(axis).max(0.0),
            Self::Overcast { zenith, axis } => {
                let c = omega.dot(axis);
                if c > 0.0 { zenith * (1.0 + 2.0 * c) / 3.0 } else { 0.0 }
            }
            Self::Cap { radiance, centre, half_angle } => {
                if omega.dot(centre) >= half_angle.cos() {
                    radiance
                } else {
                    0.0
                }
            }
        }
    }

    /// The exact irradiance `E(n) = ∫ L(ω) max(0, n·ω) dω` at unit normal `normal`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::maps::Term;
    /// // E = (π/4)(1 + (n·q)²) for L = (ω·q)².
    /// let quadratic = Term::Quadratic { axis: DVec3::Z };
    /// assert!((quadratic.irradiance(DVec3::Z) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    /// assert!((quadratic.irradiance(DVec3::X) - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn irradiance(&self, normal: DVec3) -> f64 {
        let angle_to = |axis: DVec3| normal.dot(axis).clamp(-1.0, 1.0).acos();
        match *self {
            Self::Constant { radiance } => PI * radiance,
            Self::Linear { a, b, axis } => PI * a + TAU / 3.0 * b * normal.dot(axis),
            Self::Quadratic { axis } => PI / 4.0 * (1.0 + normal.dot(axis).powi(2)),
            Self::Hemisphere { radiance, axis } => FRAC_PI_2 * radiance * (1.0 + normal.dot(axis)),
            Self::ClampedLobe { axis } => clamped_lobe(angle_to(axis)),
            Self::Overcast { zenith, axis } => {
                let alpha = angle_to(axis);
                zenith / 3.0 * (FRAC_PI_2 * (1.0 + alpha.cos()) + 2.0 * clamped_lobe(alpha))
            }
            Self::Cap { radiance, centre, half_angle } => {
                radiance * cap_irradiance_per_radiance(angle_to(centre), half_angle)
            }
        }
    }

    /// The solid angle of a cap term (`2π(1 − cos δ)`), `None` for the other terms.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::maps::Term;
    /// let hemisphere = Term::Cap { radiance: 1.0, centre: DVec3::Z, half_angle: std::f64::consts::FRAC_PI_2 };
    /// assert!((hemisphere.cap_solid_angle().unwrap() - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    /// assert_eq!(Term::Constant { radiance: 1.0 }.cap_solid_angle(), None);
    /// ```
    #[must_use]
    pub fn cap_solid_angle(&self) -> Option<f64> {
        match *self {
            Self::Cap { half_angle, .. } => Some(TAU * 2.0 * (0.5 * half_angle).sin().powi(2)),
            _ => None,
        }
    }
}

/// `E/L` of the clamped lobe `max(0, ω·u)` at angle `α` between `n` and `u`.
fn clamped_lobe(alpha: f64) -> f64 {
    2.0 / 3.0 * ((PI - alpha) * alpha.cos() + alpha.sin())
}

/// `E / L_s` for a uniform cap of half-angle `δ` whose centre is at angle `α` from the normal,
/// clipped by the normal's horizon (Lagarde & de Rousiers 2014, "Moving Frostbite to physically based rendering").
///
/// # Examples
/// ```
/// use hw3::q4_light_probe::maps::cap_irradiance_per_radiance;
/// // A hemisphere (δ = 90°) seen head-on gives π; a tiny cap gives π sin²δ cos α.
/// assert!((cap_irradiance_per_radiance(0.0, std::f64::consts::FRAC_PI_2) - std::f64::consts::PI).abs() < 1e-12);
/// ```
#[must_use]
pub fn cap_irradiance_per_radiance(alpha: f64, half_angle: f64) -> f64 {
    let sin2 = half_angle.sin().powi(2);
    if alpha <= FRAC_PI_2 - half_angle {
        return PI * sin2 * alpha.cos();
    }
    if alpha >= FRAC_PI_2 + half_angle {
        return 0.0;
    }
    let x = 1.0 / half_angle.tan();
    let y = (-x / alpha.tan()).clamp(-1.0, 1.0);
    let t = alpha.sin() * (1.0 - y * y).max(0.0).sqrt();
    sin2 * (alpha.cos() * y.acos() - x * t) + (t / x).atan()
}

/// A sum of analytic terms.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::q4_light_probe::maps::AnalyticMap;
/// let pi = std::f64::consts::PI;
/// assert_eq!(AnalyticMap::constant(2.0).irradiance(DVec3::X), 2.0 * pi);
/// assert!((AnalyticMap::linear_z(1.0, 0.5).irradiance(DVec3::Z) - pi * (1.0 + 1.0 / 3.0)).abs() < 1e-12);
/// // The sun map: the sky plus a sun of direct normal irradiance 10π; caps are not "smooth".
/// let sun = AnalyticMap::sun();
/// assert_eq!(sun.terms.len(), 2);
/// assert_eq!(sun.smooth_radiance(DVec3::Z), 1.0);
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AnalyticMap {
    /// The terms; radiance and irradiance add.
    pub terms: Vec<Term>,
}

impl AnalyticMap {
    /// A map of the given terms.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::maps::{AnalyticMap, Term};
    /// let map = AnalyticMap::new(vec![Term::Constant { radiance: 1.0 }, Term::ClampedLobe { axis: DVec3::Z }]);
    /// // Oracles add: π + 2π/3 facing the lobe.
    /// assert!((map.irradiance(DVec3::Z) - 5.0 * std::f64::consts::PI / 3.0).abs() < 1e-12);
    /// ```
    #[must_use]
    pub fn new(terms: Vec<Term>) -> Self {
        Self { terms }
    }

    /// Total radiance from unit direction `omega`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::maps::AnalyticMap;
    /// let sun = AnalyticMap::sun();
    /// let towards = hw3::q4_light_probe::maps::sun_direction();
    /// assert!(sun.radiance(towards) > 1e4); // sky 1 plus the sun's disk
    /// assert_eq!(sun.radiance(DVec3::Z), 1.0);
    /// ```
    #[must_use]
    pub fn radiance(&self, omega: DVec3) -> f64 {
        self.terms.iter().map(|t| t.radiance(omega)).sum()
    }

    /// Radiance of the terms that are not caps (caps are splatted, not point-sampled).
    ///
    /// # Examples
    /// ```
    /// use hw3::q4_light_probe::maps::{sun_direction, AnalyticMap};
    /// let sun = AnalyticMap::sun();
    /// assert_eq!(sun.smooth_radiance(sun_direction()), 1.0); // the sky only: the sun is a cap
    /// ```
    #[must_use]
    pub fn smooth_radiance(&self, omega: DVec3) -> f64 {
        self.terms.iter().filter(|t| t.cap_solid_angle().is_none()).map(|t| t.radiance(omega)).sum()
    }

    /// Exact irradiance at unit normal `normal`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::maps::AnalyticMap;
    /// assert!((AnalyticMap::sky().irradiance(DVec3::Z) - std::f64::consts::PI).abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn irradiance(&self, normal: DVec3) -> f64 {
        self.terms.iter().map(|t| t.irradiance(normal)).sum()
    }

    /// `constant:L`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::maps::AnalyticMap;
    /// let map = AnalyticMap::constant(0.5);
    /// assert_eq!(map.radiance(-DVec3::Y), 0.5);
    /// assert_eq!(map.irradiance(DVec3::Y), 0.5 * std::f64::consts::PI);
    /// ```
    #[must_use]
    pub fn constant(radiance: f64) -> Self {
        Self::new(vec![Term::Constant { radiance }])
    }

    /// `sky`: radiance 1 above the horizon (`+z` up), 0 below.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::maps::AnalyticMap;
    /// let sky = AnalyticMap::sky();
    /// assert_eq!((sky.radiance(DVec3::Z), sky.radiance(-DVec3::Z)), (1.0, 0.0));
    /// assert!((sky.irradiance(DVec3::X) - std::f64::consts::FRAC_PI_2).abs() < 1e-15); // half the sky
    /// ```
    #[must_use]
    pub fn sky() -> Self {
        Self::new(vec![Term::Hemisphere { radiance: 1.0, axis: DVec3::Z }])
    }

    /// `linear:A,B`: `L = A + B ω_z`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::maps::AnalyticMap;
    /// let map = AnalyticMap::linear_z(1.0, 0.5);
    /// assert_eq!(map.radiance(DVec3::Z), 1.5);
    /// assert!((map.irradiance(-DVec3::Z) - std::f64::consts::PI * (1.0 - 1.0 / 3.0)).abs() < 1e-12);
    /// ```
    #[must_use]
    pub fn linear_z(a: f64, b: f64) -> Self {
        Self::new(vec![Term::Linear { a, b, axis: DVec3::Z }])
    }

    /// The accuracy study's soft map: an overcast sky over a dim ground, with a broad warm glow
    /// (a 40° cap) low in the east. Smooth apart from the horizon step.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q4_light_probe::maps::AnalyticMap;
    /// let soft = AnalyticMap::soft();
    /// assert_eq!(soft.terms.len(), 3);
    /// assert!(soft.irradiance(DVec3::Z) > soft.irradiance(-DVec3::Z)); // sky above, dim ground below
    /// ```
    #[must_use]
    pub fn soft() -> Self {
        Self::new(vec![
            Term::Overcast { zenith: 1.0, axis: DVec3::Z },
            Term::Constant { radiance: 0.15 },
            Term::Cap { radiance: 0.5, centre: DVec3::new(1.0, 0.0, 0.35).normalize(), half_angle: 40f64.to_radians() },
        ])
    }

    /// The accuracy study's sun map: the [`Self::sky`] step plus a real-size sun (half-angle
    /// 0.2665°) 30° above the horizon whose direct irradiance at normal incidence is `10π`
    /// (ten times the sky's zenith irradiance), the accuracy study's hardest case.
    ///
    /// # Examples
    /// ```
    /// use hw3::q4_light_probe::maps::{sun_direction, AnalyticMap};
    /// let sun = AnalyticMap::sun();
    /// // Facing the sun: its 10π plus the sky seen from a normal 30° above the horizon.
    /// let sky = AnalyticMap::sky().irradiance(sun_direction());
    /// assert!((sun.irradiance(sun_direction()) - 10.0 * std::f64::consts::PI - sky).abs() < 1e-9);
    /// ```
    #[must_use]
    pub fn sun() -> Self {
        Self::sky_with_sun(0.2665f64.to_radians())
    }

    /// [`Self::sky`] plus a sun of half-angle `half_angle` at elevation 30°, with direct normal
    /// irradiance `10π` whatever its size.
    ///
    /// # Examples
    /// ```
    /// use hw3::q4_light_probe::maps::{sun_direction, AnalyticMap};
    /// // The sun's direct irradiance is 10π whatever its size.
    /// for degrees in [0.5_f64, 5.0] {
    ///     let map = AnalyticMap::sky_with_sun(degrees.to_radians());
    ///     assert!((map.terms[1].irradiance(sun_direction()) - 10.0 * std::f64::consts::PI).abs() < 1e-9);
    /// }
    /// ```
    #[must_use]
    pub fn sky_with_sun(half_angle: f64) -> Self {
        let mut map = Self::sky();
        map.terms.push(Term::Cap { radiance: 10.0 / half_angle.sin().powi(2), centre: sun_direction(), half_angle });
        map
    }

    /// Rasterises the map into a probe of `size` texels across (`2·size × size` for lat-long):
    /// smooth terms by subsampling each texel ([`Probe::from_fn`]), caps by splatting `m²`
    /// stratified points per cap ([`Probe::splat_cap`], `m = 256`), so a sub-texel sun keeps its
    /// exact energy. Cap points in a blind cone are lost, as they are in a real photo.
    ///
    /// `world_from_probe` must be a rotation (see [`crate::envmap::horizontal_camera`]).
    ///
    /// # Errors
    /// As [`Probe::from_fn`] (size 0, or a negative or non-finite radiance anywhere).
    ///
    /// # Examples
    /// ```
    /// use hw3::envmap::{horizontal_camera, ProbeFormat};
    /// use hw3::q4_light_probe::maps::AnalyticMap;
    /// let probe = AnalyticMap::sun().rasterise(ProbeFormat::MirrorBall, 32, horizontal_camera()).unwrap();
    /// assert_eq!(probe.texels().len(), 32 * 32);
    /// let lat_long = AnalyticMap::sky().rasterise(ProbeFormat::LatLong, 8, horizontal_camera()).unwrap();
    /// assert_eq!((lat_long.width(), lat_long.height()), (16, 8));
    /// ```
    pub fn rasterise(&self, format: ProbeFormat, size: usize, world_from_probe: DMat3) -> Result<Probe, ProbeError> {
        let (width, height) = if format == ProbeFormat::LatLong { (2 * size, size) } else { (size, size) };
        let mut probe =
            Probe::from_fn(format, width, height, world_from_probe, |omega| DVec3::splat(self.smooth_radiance(omega)))?;
        for term in &self.terms {
            if let Term::Cap { radiance, centre, half_angle } = *term {
                probe.splat_cap(radiance, centre, half_angle, 256)?;
            }
        }
        Ok(probe)
    }
}

/// The direction of the sun in [`AnalyticMap::sun`] (elevation 30° toward `+x`).
///
/// # Examples
/// ```
/// let s = hw3::q4_light_probe::maps::sun_direction();
/// assert!((s.z - 0.5).abs() < 1e-12);
/// ```
#[must_use]
pub fn sun_direction() -> DVec3 {
    let elevation = 30f64.to_radians();
    DVec3::new(elevation.cos(), 0.0, elevation.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::envmap::horizontal_camera;
    use crate::q4_light_probe::normals::fibonacci_normals;

    /// Brute-force `∫ L max(0, n·ω) dω` on a θφ grid in a frame around `axis` (so a cap is
    /// resolved by its own grid), midpoint rule in cos θ and φ.
    fn quadrature(term: &Term, normal: DVec3, axis: DVec3, theta_max: f64) -> f64 {
        let (t1, t2) = axis.any_orthonormal_pair();
        let (rings, sectors) = (1500, 1500);
        let z_min = theta_max.cos();
        let dz = (1.0 - z_min) / rings as f64;
        let dphi = TAU / sectors as f64;
        let mut sum = 0.0;
        for r in 0..rings {
            let z = 1.0 - (r as f64 + 0.5) * dz;
            let s = (1.0 - z * z).sqrt();
            for k in 0..sectors {
                let phi = (k as f64 + 0.5) * dphi;
                let omega = axis * z + t1 * (s * phi.cos()) + t2 * (s * phi.sin());
                sum += term.radiance(omega) * normal.dot(omega).max(0.0);
            }
        }
        sum * dz * dphi
    }

    #[test]
    fn oracles_match_brute_force_quadrature() {
        let axis = DVec3::new(0.3, -0.5, 0.8).normalize();
        let terms = [
            Term::Linear { a: 1.0, b: 0.9, axis },
            Term::Quadratic { axis },
            Term::Hemisphere { radiance: 2.0, axis },
            Term::ClampedLobe { axis },
            Term::Overcast { zenith: 1.5, axis },
        ];
        for normal in [DVec3::Z, DVec3::new(1.0, 1.0, -0.2).normalize(), -axis] {
            for term in &terms {
                let exact = term.irradiance(normal);
                let brute = quadrature(term, normal, axis, PI);
                // The step terms converge at first order in the grid; 1e-3 of π is the grid's bound.
                assert!((exact - brute).abs() < 3e-3, "{term:?} at {normal}: {exact} vs {brute}");
            }
        }
    }

    #[test]
    fn cap_oracle_matches_quadrature_across_the_horizon() {
        let half_angle = 10f64.to_radians();
        for alpha_deg in [0.0, 45.0, 80.0, 85.0, 90.0, 95.0, 99.0, 100.5] {
            let alpha = f64::to_radians(alpha_deg);
            let centre = DVec3::new(alpha.sin(), 0.0, alpha.cos());
            let term = Term::Cap { radiance: 1.0, centre, half_angle };
            let exact = term.irradiance(DVec3::Z);
            // Integrate over the cap only, in the cap's own frame; the horizon cuts it smoothly
            // enough for the midpoint rule at this resolution.
            let brute = quadrature(&term, DVec3::Z, centre, half_angle);
            let peak = PI * half_angle.sin().powi(2);
            assert!((exact - brute).abs() < 1e-5 * peak, "α = {alpha_deg}°: {exact} vs {brute}");
        }
    }

    #[test]
    fn cap_oracle_reduces_to_the_hemisphere_at_ninety_degrees() {
        for normal in fibonacci_normals(16) {
            let cap = Term::Cap { radiance: 1.0, centre: DVec3::Z, half_angle: FRAC_PI_2 };
            let sky = AnalyticMap::sky().irradiance(normal);
            assert!((cap.irradiance(normal) - sky).abs() < 1e-12, "{normal}");
        }
    }

    #[test]
    fn splatted_caps_keep_their_energy() {
        let map = AnalyticMap::sun();
        let probe = map.rasterise(ProbeFormat::MirrorBall, 32, horizontal_camera()).unwrap();
        let sky_power = 2.0 * PI; // the hemisphere step, radiance 1
        let total: f64 = probe.texels().iter().map(|t| t.radiance.x * t.solid_angle).sum();
        let sun_power = map.terms[1].cap_solid_angle().unwrap() * 10.0 / (0.2665f64.to_radians().sin().powi(2));
        assert!((total - sky_power - sun_power).abs() < 2e-3 * (sky_power + sun_power), "{total}");
    }
}
