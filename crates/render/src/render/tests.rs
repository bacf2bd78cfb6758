//! The renderer's tests: they render scenes of the catalogue with every integrator and pass, so
//! they sit above every module of `render/`, one file a module under test.

mod analysis;
mod environment;
mod integrator;
mod medium;
mod noise;
mod photon;
mod quads;
mod scene;

use crate::render::*;
use crate::render::{analysis::analyze, passes::Pass};

fn small(scene: &Scene, passes: Passes, spp: u32) -> Image {
    render(scene, &Settings::whitted(48, 36, spp, passes), &|_| {}).unwrap()
}

fn in_pool(threads: usize, f: impl FnOnce() -> Image + Send) -> Image {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(f)
}

#[test]
fn image_bytes_are_identical_for_one_and_two_threads() {
    for scene in [
        catalogue::moving_ball(2.0).unwrap(),
        catalogue::fog_street(0.1).unwrap(),
        catalogue::glass_ball_caustic().unwrap(),
    ] {
        let plan = analyze(&scene).plan;
        let one = in_pool(1, || small(&scene, plan, 3));
        let two = in_pool(2, || small(&scene, plan, 3));
        assert_eq!(one.to_rgb8().into_raw(), two.to_rgb8().into_raw());
        assert_eq!(one, two, "linear radiances identical too");
    }
}

#[test]
fn path_tracer_is_deterministic_across_thread_counts() {
    let scene = catalogue::cornell_mirror().unwrap();
    let settings = Settings {
        integrator: Integrator::PathTracer { max_depth: 4 },
        ..Settings::whitted(24, 18, 2, analyze(&scene).plan)
    };
    let run = |threads| in_pool(threads, || render(&scene, &settings, &|_| {}).unwrap());
    assert_eq!(run(1), run(2));
}

/// For every scene and every pass the plan skips, forcing it on gives the same image bit for
/// bit (Whitted, and the path tracer); for every pass the plan runs, forcing it off changes
/// the mean luminance by more than 1 % of the image's mean.
#[test]
fn the_plan_skips_only_passes_that_change_nothing_and_keeps_those_that_matter() {
    let scenes = [
        catalogue::mirror_spheres(true).unwrap(),
        catalogue::mirror_spheres(false).unwrap(),
        catalogue::fog_street(0.15).unwrap(),
        catalogue::fog_street(0.0).unwrap(),
        catalogue::moving_ball(2.0).unwrap(),
        catalogue::moving_ball(0.0).unwrap(),
        catalogue::cornell_mirror().unwrap(),
        catalogue::probe_lit().unwrap(),
        catalogue::fog_panel(0.15).unwrap(),
        catalogue::fog_panel(0.0).unwrap(),
        catalogue::glass_ball_caustic().unwrap(),
    ];
    let mut skipped_checked = 0;
    let mut needed_checked = 0;
    for scene in &scenes {
        for integrator in [Integrator::Whitted { max_depth: 8 }, Integrator::PathTracer { max_depth: 3 }] {
            let plan = integrator.restrict(analyze(scene).plan);
            let run = |passes| {
                let settings = Settings { integrator, ..Settings::whitted(32, 24, 2, passes) };
                render(scene, &settings, &|_| {}).unwrap()
            };
            let planned = run(plan);
            let mean = planned.luminance().iter().sum::<f64>() / planned.pixels.len() as f64;
            for pass in Pass::ALL {
                if plan.get(pass) {
                    let without = run(plan.with(pass, false));
                    let change = planned.mean_abs_difference(&without);
                    assert!(
                        change > 0.01 * mean,
                        "{pass:?} is planned but removing it changes only {change:e} (mean {mean:e})"
                    );
                    needed_checked += 1;
                } else {
                    assert_eq!(run(plan.with(pass, true)), planned, "{pass:?} forced on");
                    skipped_checked += 1;
                }
            }
        }
    }
    assert!(skipped_checked >= 30 && needed_checked >= 8);
}

/// Mean floor radiance of the `caustic` scene over `points` (rays straight down from 0.01
/// above the floor), `samples` per point, by `tracer` with `integrator`; and its standard
/// error over the points × samples estimates.
fn footprint_radiance(tracer: &Tracer, integrator: Integrator, points: &[DVec3], samples: u64) -> (f64, f64) {
    let values: Vec<f64> = points
        .iter()
        .enumerate()
        .flat_map(|(i, &p)| {
            let mut sampler = Sampler::new(7, i as u64, 0);
            let ray = hw3_core::geometry::Ray { origin: p + DVec3::Y * 0.01, dir: DVec3::NEG_Y };
            (0..samples).map(move |_| tracer.radiance(integrator, &ray, 0.0, &mut sampler).x).collect::<Vec<_>>()
        })
        .collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (variance / n).sqrt())
}

/// The caustic pass on the `caustic` scene, measured on the floor under the glass ball (mean
/// radiance over [`catalogue::caustic_footprint`], rays straight down):
/// - without the pass Whitted tracing leaves the footprint exactly black (its shadow rays to
///   the light are blocked by the glass), with it the footprint is more than 10× as bright
///   as the open floor beside the ball (12.8× with seed 1);
/// - the path tracer (256 paths per point, depth 8; it finds the caustic by bouncing off the
///   floor through the ball into the light) agrees with Whitted + caustic map within 4 of its
///   standard errors;
/// - the k-nearest estimate blurs the spot but keeps its flux: averaged over the disc it is
///   within 2 % of the photons' own histogram, the stored power inside the disc over its
///   area (no blur at all; the 2 % is light moved across the disc's rim by the 0.1 gather).
#[test]
fn the_caustic_pass_lights_the_shadow_under_the_glass_ball_as_the_path_tracer_does() {
    let scene = catalogue::glass_ball_caustic().unwrap();
    let plan = analyze(&scene).plan;
    assert!(plan.caustics);
    let map = crate::render::photon::trace_caustic_photons(&scene, crate::render::photon::CAUSTIC_PHOTONS, 1).unwrap();
    let with = Tracer::new(&scene, plan).with_caustics(&map, crate::render::photon::CAUSTIC_GATHER);
    let without = Tracer::new(&scene, plan.with(passes::Pass::Caustics, false));
    let reference = Tracer::new(&scene, plan.with(passes::Pass::IndirectBounces, true));
    let whitted = Integrator::Whitted { max_depth: 8 };
    let (center, radius, points) = catalogue::caustic_footprint(400);
    let (lit, _) = footprint_radiance(&with, whitted, &points, 1);
    let (dark, _) = footprint_radiance(&without, whitted, &points, 1);
    let (path, standard_error) = footprint_radiance(&reference, Integrator::PathTracer { max_depth: 8 }, &points, 256);
    let open_points: Vec<DVec3> = points.iter().map(|p| *p + DVec3::new(0.0, 0.0, 3.0)).collect();
    let (open_floor, _) = footprint_radiance(&without, whitted, &open_points, 4);
    let inside: f64 = map.photons().iter().filter(|p| (p.position - center).length() < radius).map(|p| p.power.x).sum();
    let histogram = 0.7 / std::f64::consts::PI * inside / (std::f64::consts::PI * radius * radius);
    assert_eq!(dark, 0.0, "Whitted without the pass: the glass casts a black shadow");
    assert!(lit > 10.0 * open_floor, "caustic {lit} vs open floor {open_floor}");
    assert!(
        (lit - path).abs() < 4.0 * standard_error,
        "Whitted + caustics {lit}, path tracer {path} ± {standard_error}"
    );
    assert!((lit / histogram - 1.0).abs() < 0.02, "kNN {lit} vs histogram {histogram}");
}

/// Every built-in scene renders to the same linear radiances with the kd-tree and with the
/// brute-force loop, for both integrators (so every closest-hit and shadow query agreed).
#[test]
fn kd_tree_renders_are_identical_to_brute_force_on_every_built_in_scene() {
    for (name, _) in catalogue::CATALOGUE {
        let scene = catalogue::by_name(name).unwrap();
        let brute = scene.without_kd_tree();
        assert_eq!(brute.kd_tree_spheres(), 0);
        for integrator in [Integrator::Whitted { max_depth: 8 }, Integrator::PathTracer { max_depth: 3 }] {
            let plan = integrator.restrict(analyze(&scene).plan);
            let settings = Settings { integrator, ..Settings::whitted(24, 18, 2, plan) };
            let fast = render(&scene, &settings, &|_| {}).unwrap();
            let slow = render(&brute, &settings, &|_| {}).unwrap();
            assert_eq!(fast, slow, "{name} with {integrator:?}");
        }
    }
}

#[test]
fn bad_sizes_and_sample_counts_are_refused() {
    let scene = catalogue::moving_ball(0.0).unwrap();
    let plan = analyze(&scene).plan;
    for (w, h) in [(0, 10), (10, 0), (MAX_SIDE + 1, 1), (5000, 5000)] {
        assert_eq!(
            render(&scene, &Settings::whitted(w, h, 1, plan), &|_| {}),
            Err(RenderError::ImageSize { width: w, height: h })
        );
    }
    for spp in [0, MAX_SPP + 1] {
        assert_eq!(
            render(&scene, &Settings::whitted(4, 4, spp, plan), &|_| {}),
            Err(RenderError::SamplesPerPixel(spp))
        );
    }
}

/// A point light inside a closed sphere lights nothing outside it, and a camera inside a
/// mirror sphere sees a finite, black image (light cannot get in; recursion stops at depth 8).
#[test]
fn enclosed_lights_and_cameras_stay_dark_and_finite() {
    use crate::render::camera::Camera;
    use crate::render::scene::{Material, Object, PointLight};
    use hw3_core::geometry::Sphere;
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 40.0);
    let shell = |material| Object::sphere(Sphere::new(DVec3::ZERO, 1.0).unwrap(), material);
    let lamp = PointLight { position: DVec3::ZERO, intensity: DVec3::splat(100.0) };
    let diffuse = Material::Diffuse { albedo: DVec3::splat(0.8) };
    let enclosed = Scene::new(camera, vec![shell(diffuse)], vec![lamp], None, DVec3::ZERO).unwrap();
    let outside = small(&enclosed, analyze(&enclosed).plan, 1);
    assert!(outside.pixels.iter().all(|p| *p == DVec3::ZERO));
    let mirror = Material::Mirror { reflectance: DVec3::splat(0.9) };
    let inside_camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.5), DVec3::ZERO, 40.0);
    let outside_lamp = PointLight { position: DVec3::new(0.0, 5.0, 0.0), ..lamp };
    let trapped = Scene::new(inside_camera, vec![shell(mirror)], vec![outside_lamp], None, DVec3::ONE).unwrap();
    let image = small(&trapped, analyze(&trapped).plan, 1);
    assert!(image.pixels.iter().all(|p| *p == DVec3::ZERO));
}

#[test]
fn thumbnail_averages_blocks() {
    let image = Image {
        width: 4,
        height: 2,
        pixels: vec![
            DVec3::ONE,
            DVec3::ONE,
            DVec3::ZERO,
            DVec3::ZERO,
            DVec3::ONE,
            DVec3::ONE,
            DVec3::ZERO,
            DVec3::ZERO,
        ],
    };
    assert_eq!(image.thumbnail_text(2, 1), "1.00 0.00\n");
}
