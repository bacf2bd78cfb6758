//! Tests of `render::integrator`.

use crate::render::camera::Camera;
use crate::render::integrator::*;
use crate::render::medium::airlight_closed_form;
use crate::render::passes::{Pass, Passes};
use crate::render::photon::Photon;
use crate::render::photon::{Gather, PhotonMap};
use crate::render::sampling::Sampler;
use crate::render::scene::{Fog, Object, PointLight};
use crate::render::scene::{Material, Scene};
use glam::DVec3;
use hw3_core::geometry::Ray;
use hw3_core::geometry::Sphere;
use std::f64::consts::PI;

fn camera() -> Camera {
    Camera::looking_at(DVec3::ZERO, DVec3::NEG_Z, 40.0)
}

/// The airlight the tracer measures (its own copy of the set-up, so the test does not lean
/// on a catalogue scene): a camera ray along `−z` ends on a black wall at `length`, a
/// unit-intensity point light sits at distance `light_distance` and angle `gamma` from the
/// ray, the fog has `σ_s = beta`, and single scattering uses `steps` quadrature steps.
fn traced_airlight(beta: f64, light_distance: f64, gamma: f64, length: f64, steps: usize) -> f64 {
    let lamp = PointLight {
        position: DVec3::new(light_distance * gamma.sin(), 0.0, -light_distance * gamma.cos()),
        intensity: DVec3::ONE,
    };
    let black = Material::Diffuse { albedo: DVec3::ZERO };
    let wall =
        Object::quad(DVec3::new(-1e3, -1e3, -length), DVec3::new(2e3, 0.0, 0.0), DVec3::new(0.0, 2e3, 0.0), black);
    let fog = Fog { sigma_a: 0.0, sigma_s: beta };
    let scene = Scene::new(camera(), vec![wall], vec![lamp], Some(fog), DVec3::ZERO).unwrap();
    let tracer = Tracer::new(&scene, Passes::all()).with_in_scatter_steps(steps);
    let ray = Ray { origin: DVec3::ZERO, dir: DVec3::NEG_Z };
    tracer.radiance(Integrator::Whitted { max_depth: 0 }, &ray, 0.0, &mut Sampler::new(0, 0, 0)).x
}

#[test]
fn single_scattering_matches_the_closed_form_and_the_note_anchor() {
    // Anchors of an independent implementation (β, D, γ, d) → airlight.
    let anchors = [
        (0.05, 1.0, 5.0, 20.0, 1.304350e-01),
        (0.3, 1.0, 5.0, 20.0, 5.770888e-01),
        (0.3, 5.0, 90.0, 20.0, 4.383999e-04),
        (1.0, 5.0, 5.0, 20.0, 2.164528e-03),
    ];
    for (beta, d, gamma_degrees, length, anchor) in anchors {
        let gamma = f64::to_radians(gamma_degrees);
        let closed = airlight_closed_form(beta, 1.0, d, gamma, length).unwrap();
        assert!(((closed - anchor) / anchor).abs() < 2e-6, "{closed} vs {anchor}");
        // The midpoint rule is second order: 1.2e-4 at 256 steps, 7e-6 at 1024, 4e-7 at 4096
        // (β = 0.05, D = 1, γ = 5°).
        let traced = traced_airlight(beta, d, gamma, length, 4096);
        assert!(
            ((traced - closed) / closed).abs() < 2e-6,
            "β={beta} D={d} γ={gamma_degrees}: traced {traced:e}, closed {closed:e}"
        );
        let default_steps = traced_airlight(beta, d, gamma, length, IN_SCATTER_STEPS);
        assert!(((default_steps - closed) / closed).abs() < 1e-2);
    }
}

/// pbrt-v4's furnace: inside a diffuse sphere of albedo 0.5 with a point light of intensity π
/// at its centre, and a ray from near the centre.
fn furnace() -> (Scene, Ray<f64>) {
    let shell = Object::sphere(Sphere::new(DVec3::ZERO, 1.0).unwrap(), Material::Diffuse { albedo: DVec3::splat(0.5) });
    let light = PointLight { position: DVec3::ZERO, intensity: DVec3::splat(PI) };
    let scene = Scene::new(camera(), vec![shell], vec![light], None, DVec3::ZERO).unwrap();
    (scene, Ray { origin: DVec3::new(0.1, 0.0, 0.0), dir: DVec3::new(0.3, 0.4, -0.5).normalize() })
}

#[test]
fn camera_inside_a_diffuse_sphere_with_a_light_at_its_centre_sees_the_furnace_value() {
    // pbrt-v4's integrator test: albedo 0.5, point light I = π at the centre, all bounces
    // → radiance 0.5/(1 − 0.5) = 1; direct light alone gives 0.5.
    let (scene, ray) = furnace();
    let whitted = Tracer::new(&scene, Passes::default()).radiance(
        Integrator::Whitted { max_depth: 0 },
        &ray,
        0.0,
        &mut Sampler::new(0, 0, 0),
    );
    assert!((whitted.x - 0.5).abs() < 1e-12);
    let tracer = Tracer::new(&scene, Passes::default().with(Pass::IndirectBounces, true));
    let samples = 4000;
    let mean: f64 = (0..samples)
        .map(|i| {
            let mut sampler = Sampler::new(1, i, 0);
            tracer.radiance(Integrator::PathTracer { max_depth: 40 }, &ray, 0.0, &mut sampler).x
        })
        .sum::<f64>()
        / samples as f64;
    // Exact up to 0.5^41 truncation; the estimate's spread is 0 here (every bounce sees the
    // light with the same weight), so the tolerance is rounding only.
    assert!((mean - 1.0).abs() < 1e-9, "{mean}");
}

/// Russian roulette keeps the furnace's mean: from [`ROULETTE_FROM`] on a path survives with
/// probability equal to its throughput (0.5⁴ at the first draw, 0.5 at the later ones), so
/// the samples now spread, and their mean is 1 within four standard errors.
#[test]
fn russian_roulette_keeps_the_furnace_value() {
    let (scene, ray) = furnace();
    let tracer = Tracer::new(&scene, Passes::default().with(Pass::IndirectBounces, true));
    let samples: Vec<f64> = (0..20_000)
        .map(|i| {
            let mut sampler = Sampler::new(1, i, 0);
            tracer.radiance(Integrator::PathTracerWithRoulette { max_depth: 40 }, &ray, 0.0, &mut sampler).x
        })
        .collect();
    let (mean, spread) = (hw3_core::stats::mean(&samples), hw3_core::stats::sample_sd(&samples));
    assert!(spread > 0.1, "roulette spreads the samples: sd {spread}");
    let standard_error = hw3_core::stats::standard_error(&samples);
    assert!((mean - 1.0).abs() < 4.0 * standard_error, "mean {mean}, standard error {standard_error}");
}

/// A glass sphere in front of a uniform background: every path ends in the background, so
/// Whitted's reflect-and-refract tree must return the background (energy conservation), up to
/// the weight still inside the sphere at depth 8.
#[test]
fn glass_sphere_against_a_uniform_background_conserves_energy() {
    let glass = Object::sphere(Sphere::new(DVec3::new(0.0, 0.0, -3.0), 1.0).unwrap(), Material::Glass { index: 1.5 });
    let scene = Scene::new(camera(), vec![glass], vec![], None, DVec3::splat(0.7)).unwrap();
    let tracer = Tracer::new(&scene, Passes::all());
    for x in [0.0, 0.1, 0.25, 0.32] {
        let ray = Ray { origin: DVec3::ZERO, dir: DVec3::new(x, 0.05, -1.0).normalize() };
        let whitted = tracer.radiance(Integrator::Whitted { max_depth: 8 }, &ray, 0.0, &mut Sampler::new(0, 0, 0));
        assert!((whitted.x - 0.7).abs() < 1e-4, "x = {x}: {}", whitted.x);
        let path = tracer.radiance(Integrator::PathTracer { max_depth: 40 }, &ray, 0.0, &mut Sampler::new(0, 1, 0));
        assert!((path.x - 0.7).abs() < 1e-12, "every sampled path ends in the background");
    }
}

/// The indirect-map option reads the map exactly as a photon-map gather at the diffuse hit
/// would, and with a radius of [`f64::MAX`] that is the plain `k`-nearest estimate; without
/// lights the direct part is exactly zero, so the radiances are compared bit for bit.
#[test]
fn the_indirect_map_option_equals_a_photon_map_gather_at_a_diffuse_hit() {
    let grey = Material::Diffuse { albedo: DVec3::splat(0.5) };
    let floor = Object::quad(DVec3::new(-1.0, -1.0, -2.0), DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 2.0, 0.0), grey);
    let scene = Scene::new(camera(), vec![floor], vec![], None, DVec3::ZERO).unwrap();
    let photons = (0..400)
        .map(|i| Photon {
            position: DVec3::new(f64::from(i % 20) * 0.05 - 0.5, f64::from(i / 20) * 0.05 - 0.5, -2.0),
            direction: DVec3::new(0.0, 0.6, -0.8),
            normal: DVec3::Z,
            power: DVec3::splat(0.01),
        })
        .collect();
    let map = PhotonMap::new(photons);
    let whitted = Integrator::Whitted { max_depth: 0 };
    let ray = Ray { origin: DVec3::ZERO, dir: DVec3::new(0.05, -0.02, -1.0).normalize() };
    let hit = scene.closest_hit(&ray, 0.0, f64::INFINITY).unwrap();
    for gather in [Gather::new(30, 0.1).unwrap(), Gather::new(30, f64::MAX).unwrap()] {
        let tracer = Tracer::new(&scene, Passes::default()).with_indirect(&map, gather);
        let traced = tracer.radiance(whitted, &ray, 0.0, &mut Sampler::new(0, 0, 0));
        let expected = map.radiance_gathered(&grey, hit.point, -ray.dir, DVec3::Z, gather);
        assert_eq!(traced, expected);
        assert!(traced.x > 0.0);
    }
    let knn = map.radiance(&grey, hit.point, -ray.dir, DVec3::Z, 30).unwrap();
    let unbounded = Tracer::new(&scene, Passes::default()).with_indirect(&map, Gather::new(30, f64::MAX).unwrap());
    assert_eq!(unbounded.radiance(whitted, &ray, 0.0, &mut Sampler::new(0, 0, 0)), knn);
    // Off, or an empty map: the tracer without the option, bit for bit.
    let empty = PhotonMap::new(vec![]);
    let off = Tracer::new(&scene, Passes::default());
    let with_empty = off.with_indirect(&empty, Gather::new(30, 0.1).unwrap());
    let plain = off.radiance(whitted, &ray, 0.0, &mut Sampler::new(0, 0, 0));
    assert_eq!(with_empty.radiance(whitted, &ray, 0.0, &mut Sampler::new(0, 0, 0)), plain);
    assert_eq!(plain, DVec3::ZERO);
}

/// The light-samples option is the mean of that many direct-light-only radiances drawn one
/// after the other from one sampler (an eye pass that averaged Whitted depth-0 calls, bit for
/// bit, in a scene without fog), and it reduces the area light's noise.
#[test]
fn light_samples_average_direct_light_estimates_from_one_stream() {
    let scene = crate::render::catalogue::cornell_mirror().unwrap();
    let tracer = Tracer::new(&scene, Passes::default());
    let whitted = Integrator::Whitted { max_depth: 0 };
    let ray = Ray { origin: DVec3::new(0.0, 0.0, 3.4), dir: DVec3::new(-0.1, 0.05, -1.0).normalize() };
    let estimate = |samples: u32, stream: u64| {
        tracer.with_light_samples(samples).radiance(whitted, &ray, 0.0, &mut Sampler::new(9, stream, 0))
    };
    let mut sampler = Sampler::new(9, 0, 0);
    let by_hand = (0..16).map(|_| tracer.radiance(whitted, &ray, 0.0, &mut sampler)).sum::<DVec3>() / 16.0;
    assert_eq!(estimate(16, 0), by_hand);
    let spread = |samples| {
        let values: Vec<f64> = (0..64).map(|stream| estimate(samples, stream).x).collect();
        let mean = values.iter().sum::<f64>() / 64.0;
        values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 63.0
    };
    assert!(spread(16) < spread(1) / 4.0, "16 samples cut the variance about 16-fold");
}
