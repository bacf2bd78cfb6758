//! Single scattering from quad area lights in homogeneous fog (the area-light "airlight").
//!
//! Along a view ray `p(x) = o + x d`, `0 ≤ x ≤ ℓ`, a quad light of radiance `L_e`, area `A` and
//! unit normal `n_l` adds
//!
//! `L_air = ∫₀^ℓ ∫_A σ_s/(4π) · L_e cos θ_l / r² · V · e^(−σ_t (x + r)) dA dx`,
//!
//! with `r = |y − p(x)|` and `cos θ_l = n_l · (p(x) − y)/r` (zero behind the light). It is
//! estimated by [`AREA_IN_SCATTER_SAMPLES`] samples: a point `y` uniform on the quad
//! (pdf `1/A`), then a distance `x` by *equiangular sampling* toward `y` — `x = Δ + h tan θ`, `θ`
//! uniform between the angles of the segment's ends, pdf `h / ((θ_b − θ_a) r²)` — which cancels
//! the `1/r²` exactly, so each sample is
//!
//! `σ_s/(4π) · L_e A cos θ_l · (θ_b − θ_a)/h · V · e^(−σ_t (x + r))`,
//!
//! bounded even when the ray passes close to the light. Both pdfs are positive wherever the
//! integrand is, so the estimate is unbiased. As the quad shrinks to a point this is the
//! point-light integrand with the intensity `I(ω) = L_e A cos θ_l` of a small flat emitter.

use super::sampling::Sampler;
use super::scene::Scene;
use glam::DVec3;
use hw3_core::geometry::{InputError, Ray};
use std::f64::consts::PI;

/// Samples (light point, distance) per area light per ray segment.
pub const AREA_IN_SCATTER_SAMPLES: usize = 8;

/// The equiangular parametrisation of a ray segment `[0, end]` seen from a target point:
/// `x = along + h tan θ` for `θ ∈ [theta_start, theta_end]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Equiangular {
    /// Ray parameter of the foot of the perpendicular from the target.
    pub along: f64,
    /// Distance from the target to the ray's line (kept ≥ a tiny positive floor).
    pub h: f64,
    /// Angle of the segment's start.
    pub theta_start: f64,
    /// Angle of the segment's end.
    pub theta_end: f64,
}

impl Equiangular {
    /// The parametrisation of `ray`'s segment `[0, end]` (unit direction) toward `target`.
    pub(crate) fn new(ray: &Ray<f64>, target: DVec3, end: f64) -> Self {
        let to_target = target - ray.origin;
        let along = to_target.dot(ray.dir);
        // A target on the ray's line makes the integral diverge like 1/h; keep it finite.
        let h = (to_target - ray.dir * along).length().max(1e-9 * (1.0 + to_target.length()));
        Self { along, h, theta_start: (-along / h).atan(), theta_end: ((end - along) / h).atan() }
    }

    /// The ray parameter at angle `theta`.
    pub(crate) fn distance(&self, theta: f64) -> f64 {
        self.along + self.h * theta.tan()
    }
}

/// The single-scattered radiance from every emitter quad along `ray`'s segment `[0, length]`
/// (see the module docs). Zero, with no random number drawn, without a scattering medium or
/// without an area light.
pub(crate) fn area_in_scattering(
    scene: &Scene,
    ray: &Ray<f64>,
    length: f64,
    time: f64,
    sampler: &mut Sampler,
) -> DVec3 {
    let Some(fog) = scene.fog().filter(|f| f.sigma_s > 0.0) else {
        return DVec3::ZERO;
    };
    let sigma_t = fog.sigma_t();
    // Beyond σ_t·x = 40 the integrand is below e^(−40) ≈ 4e-18 of its peak.
    let end = length.min(40.0 / sigma_t);
    let mut total = DVec3::ZERO;
    for light in scene.area_lights() {
        let cross = light.edge_u.cross(light.edge_v);
        let area = cross.length();
        let light_normal = cross / area;
        let mut sum = 0.0;
        for _ in 0..AREA_IN_SCATTER_SAMPLES {
            let target = light.point(sampler.uniform(), sampler.uniform());
            let span = Equiangular::new(ray, target, end);
            let theta = span.theta_start + (span.theta_end - span.theta_start) * sampler.uniform();
            let x = span.distance(theta);
            let point = ray.at(x);
            let offset = target - point;
            let r = offset.length();
            let cos_light = -light_normal.dot(offset) / r;
            // NaN (a point on the light itself) fails the test too.
            if !(cos_light > 0.0) {
                continue;
            }
            let shadow = Ray { origin: point, dir: offset / r };
            // Stop just short of the target so the light does not shadow itself.
            if scene.occluded(&shadow, time, r * (1.0 - 1e-9)) {
                continue;
            }
            sum += cos_light * (span.theta_end - span.theta_start) / span.h * (-sigma_t * (x + r)).exp();
        }
        total += light.radiance * (fog.sigma_s / (4.0 * PI) * area * sum / AREA_IN_SCATTER_SAMPLES as f64);
    }
    total
}

/// The single-scattered radiance ("airlight") along a view ray of length `length` in a
/// non-absorbing homogeneous medium (`σ_s = σ_t = beta`) from an isotropic point light of
/// intensity `intensity` at distance `light_distance` and angle `gamma` (radians) from the ray:
/// Sun et al.'s (2005) closed form `A₀ [F(A₁, ξ₁) − F(A₁, γ/2)]` with
/// `F(u, v) = ∫₀^v e^(−u tan ξ) dξ` evaluated by composite Simpson (20 000 panels). An oracle for
/// the renderer's marching, computed by a different route (the anchors below come from an independent implementation).
///
/// # Errors
/// [`InputError::OutOfRange`] unless `beta`, `light_distance` and `length` are finite and > 0
/// and `gamma` is in `(0, π)` (on the ray's line the integral diverges).
///
/// # Examples
/// ```
/// use hw3_render::render::medium::airlight_closed_form;
/// // An anchor from an independent implementation: β = 0.3, D = 1, γ = 5°, 20 units.
/// let l = airlight_closed_form(0.3, 1.0, 1.0, 5f64.to_radians(), 20.0).unwrap();
/// assert!((l / 5.770888e-01 - 1.0).abs() < 2e-6);
/// ```
pub fn airlight_closed_form(
    beta: f64,
    intensity: f64,
    light_distance: f64,
    gamma: f64,
    length: f64,
) -> Result<f64, InputError> {
    for (name, value) in [("beta", beta), ("light distance", light_distance), ("length", length)] {
        if !(value > 0.0 && value.is_finite()) {
            return Err(InputError::OutOfRange { name, value: format!("{value}"), expected: "finite and > 0" });
        }
    }
    if !(gamma > 0.0 && gamma < PI) {
        return Err(InputError::OutOfRange { name: "gamma", value: format!("{gamma}"), expected: "in (0, π)" });
    }
    let f = |u: f64, v: f64| {
        let n = 20_000;
        let h = v / f64::from(n);
        let g = |xi: f64| (-u * xi.tan()).exp();
        let inner: f64 = (1..n).map(|i| g(f64::from(i) * h) * if i % 2 == 1 { 4.0 } else { 2.0 }).sum();
        (g(0.0) + inner + g(v)) * h / 3.0
    };
    let (t_sv, t_vp) = (beta * light_distance, beta * length);
    let a0 = beta * beta * intensity * (-t_sv * gamma.cos()).exp() / (2.0 * PI * t_sv * gamma.sin());
    let a1 = t_sv * gamma.sin();
    let v_end = PI / 4.0 + 0.5 * ((t_vp - t_sv * gamma.cos()) / (t_sv * gamma.sin())).atan();
    Ok(a0 * (f(a1, v_end) - f(a1, gamma / 2.0)))
}
