//! Tests of [`super`] that exercise it through the layers above it (scenes of the catalogue, the
//! integrators): kept in their own file so that the import graph of the renderer stays a DAG.

use crate::render::integrator::{Integrator, Tracer};
use crate::render::medium::*;
use crate::render::passes::Passes;
use crate::render::sampling::Sampler;
use crate::render::scene::Scene;
use crate::render::{
    camera::Camera,
    scene::{Fog, Material, Object},
};
use glam::DVec3;
use hw3_core::geometry::Ray;
use std::f64::consts::PI;

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
    let point_limit: f64 = (0..steps).map(|i| integrand((i as f64 + 0.5) * dx, centre, DVec3::NEG_X)).sum::<f64>() * dx;
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
