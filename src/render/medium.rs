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
use crate::geometry::{InputError, Ray};
use glam::DVec3;
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
/// the renderer's marching, computed by a different route (reference note §4).
///
/// # Errors
/// [`InputError::OutOfRange`] unless `beta`, `light_distance` and `length` are finite and > 0
/// and `gamma` is in `(0, π)` (on the ray's line the integral diverges).
///
/// # Examples
/// ```
/// use hw3::render::medium::airlight_closed_form;
/// // Anchor from the reference note (results_airlight.txt): β = 0.3, D = 1, γ = 5°, 20 units.
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::integrator::{Integrator, Tracer};
    use crate::render::passes::Passes;
    use crate::render::{
        camera::Camera,
        scene::{Fog, Material, Object},
    };

    const SIGMA_S: f64 = 0.2;
    const LENGTH: f64 = 10.0;
    const LIGHT_RADIANCE: f64 = 5.0;

    /// A camera ray along `−z` from the origin ending on a black wall at `LENGTH`, in a
    /// non-absorbing fog, and a square light of side `side` centred at `centre`, facing `−x`
    /// (toward the ray's line, which is at `x = 0`).
    fn scene(side: f64, centre: DVec3) -> Scene {
        let wall = Object::quad(
            DVec3::new(-1e3, -1e3, -LENGTH),
            DVec3::new(2e3, 0.0, 0.0),
            DVec3::new(0.0, 2e3, 0.0),
            Material::Diffuse { albedo: DVec3::ZERO },
        );
        let light = Object::quad(
            centre - DVec3::new(0.0, side, side) / 2.0,
            DVec3::new(0.0, 0.0, side),
            DVec3::new(0.0, side, 0.0),
            Material::Emitter { radiance: DVec3::splat(LIGHT_RADIANCE) },
        );
        let camera = Camera::looking_at(DVec3::ZERO, DVec3::NEG_Z, 40.0);
        let fog = Fog { sigma_a: 0.0, sigma_s: SIGMA_S };
        Scene::new(camera, vec![wall, light], vec![], Some(fog), DVec3::ZERO).unwrap()
    }

    /// The integrand of the module docs at ray distance `x` and light point `y` (no occluders).
    fn integrand(x: f64, y: DVec3, light_normal: DVec3) -> f64 {
        let offset = y - DVec3::new(0.0, 0.0, -x);
        let r = offset.length();
        let cos_light = (-light_normal.dot(offset) / r).max(0.0);
        SIGMA_S / (4.0 * PI) * LIGHT_RADIANCE * cos_light / (r * r) * (-SIGMA_S * (x + r)).exp()
    }

    /// The double integral by the plain midpoint rule in `x` and on an `m × m` grid on the light:
    /// a route independent of the renderer's (no equiangular change of variable, no sampling).
    fn midpoint_reference(side: f64, centre: DVec3, steps: usize, m: usize) -> f64 {
        let corner = centre - DVec3::new(0.0, side, side) / 2.0;
        let cell = side / m as f64;
        let dx = LENGTH / steps as f64;
        let mut total = 0.0;
        for i in 0..steps {
            let x = (i as f64 + 0.5) * dx;
            for a in 0..m {
                for b in 0..m {
                    let y = corner + DVec3::new(0.0, (b as f64 + 0.5) * cell, (a as f64 + 0.5) * cell);
                    total += integrand(x, y, DVec3::NEG_X);
                }
            }
        }
        total * dx * cell * cell
    }

    /// Mean and standard error of `count` renderer estimates along the camera ray.
    fn rendered(scene: &Scene, count: u64) -> (f64, f64) {
        let tracer = Tracer::new(scene, Passes::all());
        let ray = Ray { origin: DVec3::ZERO, dir: DVec3::NEG_Z };
        let values: Vec<f64> = (0..count)
            .map(|i| tracer.radiance(Integrator::Whitted { max_depth: 0 }, &ray, 0.0, &mut Sampler::new(4, i, 0)).x)
            .collect();
        let n = count as f64;
        let mean = values.iter().sum::<f64>() / n;
        let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, (variance / n).sqrt())
    }

    /// A 1.5 × 1.5 light 1.2 units from the ray: the renderer's estimate agrees with the
    /// midpoint double integral within 5 standard errors plus the reference's own error, which
    /// is bounded by the change from (400 steps, 24² light cells) to (800, 48²).
    #[test]
    fn area_light_airlight_matches_a_midpoint_double_integral() {
        let (side, centre) = (1.5, DVec3::new(1.2, 0.3, -4.0));
        let coarse = midpoint_reference(side, centre, 400, 24);
        let fine = midpoint_reference(side, centre, 800, 48);
        let quadrature_error = (fine - coarse).abs();
        assert!(quadrature_error < 1e-3 * fine, "the reference has converged: {coarse} → {fine}");
        let (mean, error) = rendered(&scene(side, centre), 4000);
        assert!(error < 0.02 * fine, "the test can tell: standard error {error:e} of {fine:e}");
        assert!((mean - fine).abs() < 5.0 * error + quadrature_error, "{mean:e} vs {fine:e} ± {error:e}");
    }

    /// As the light shrinks (side 0.4 → 0.1 → 0.025 at fixed power-per-area scaling `L_e A`
    /// divided out), the airlight per unit area tends to the point-light integral with the small
    /// flat emitter's intensity `L_e A cos θ_l`: the relative gap falls at least 8-fold per
    /// 4-fold shrink (it is second order in the side) and ends below 0.1 %.
    #[test]
    fn a_shrinking_area_light_converges_to_the_point_light_limit() {
        let centre = DVec3::new(1.0, 0.0, -3.0);
        // The limit uses the same x grid as the references, so their x errors cancel.
        let steps = 4000;
        let dx = LENGTH / steps as f64;
        let point_limit: f64 =
            (0..steps).map(|i| integrand((i as f64 + 0.5) * dx, centre, DVec3::NEG_X)).sum::<f64>() * dx;
        let gaps: Vec<f64> = [0.4, 0.1, 0.025]
            .iter()
            .map(|&side| {
                let per_area = midpoint_reference(side, centre, steps, 8) / (side * side);
                (per_area / point_limit - 1.0).abs()
            })
            .collect();
        assert!(gaps[1] < gaps[0] / 8.0 && gaps[2] < gaps[1] / 8.0 && gaps[2] < 1e-3, "{gaps:?}");
        // The renderer on the smallest light, scaled by its area, agrees with the limit.
        let side = 0.025;
        let (mean, error) = rendered(&scene(side, centre), 2000);
        let (mean, error) = (mean / (side * side), error / (side * side));
        assert!(
            (mean - point_limit).abs() < 5.0 * error + gaps[2] * point_limit,
            "{mean:e} vs {point_limit:e} ± {error:e}"
        );
    }

    #[test]
    fn a_light_behind_an_occluder_adds_no_glow_and_no_fog_draws_no_numbers() {
        let (side, centre) = (1.0, DVec3::new(1.2, 0.0, -4.0));
        let base = scene(side, centre);
        let mut objects = base.objects().to_vec();
        // A wall between the light and the ray, parallel to the light.
        objects.push(Object::quad(
            DVec3::new(0.6, -50.0, 50.0),
            DVec3::new(0.0, 0.0, -100.0),
            DVec3::new(0.0, 100.0, 0.0),
            Material::Diffuse { albedo: DVec3::ZERO },
        ));
        let blocked = Scene::new(*base.camera(), objects, vec![], base.fog(), DVec3::ZERO).unwrap();
        let ray = Ray { origin: DVec3::ZERO, dir: DVec3::NEG_Z };
        assert_eq!(area_in_scattering(&blocked, &ray, LENGTH, 0.0, &mut Sampler::new(0, 0, 0)), DVec3::ZERO);
        let clear = Scene::new(*base.camera(), base.objects().to_vec(), vec![], None, DVec3::ZERO).unwrap();
        let mut sampler = Sampler::new(0, 0, 0);
        assert_eq!(area_in_scattering(&clear, &ray, LENGTH, 0.0, &mut sampler), DVec3::ZERO);
        assert_eq!(sampler.uniform(), Sampler::new(0, 0, 0).uniform(), "no random number was drawn");
    }
}
