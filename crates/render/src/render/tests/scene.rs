//! Tests of [`super`] that exercise it through the layers above it (scenes of the catalogue, the
//! integrators): kept in their own file so that the import graph of the renderer stays a DAG.

use crate::render::camera::Camera;
use crate::render::scene::*;
use glam::DVec3;
use hw3_core::geometry::{InputError, Ray, Sphere};

fn unit_quad() -> Shape {
    Shape::Quad {
        corner: DVec3::new(-1.0, -1.0, 0.0),
        edge_u: DVec3::new(2.0, 0.0, 0.0),
        edge_v: DVec3::new(0.0, 2.0, 0.0),
    }
}

fn ray(origin: [f64; 3], dir: [f64; 3]) -> Ray<f64> {
    Ray::new(DVec3::from(origin), DVec3::from(dir)).unwrap()
}

#[test]
fn quad_is_hit_inside_and_missed_outside_and_behind() {
    let quad = unit_quad();
    assert_eq!(intersect(&quad, &ray([0.5, 0.5, 3.0], [0.0, 0.0, -1.0]), 0.0), Some(3.0));
    assert_eq!(intersect(&quad, &ray([1.5, 0.0, 3.0], [0.0, 0.0, -1.0]), 0.0), None);
    assert_eq!(intersect(&quad, &ray([0.0, 0.0, 3.0], [0.0, 0.0, 1.0]), 0.0), None);
}

#[test]
fn grazing_ray_in_the_plane_of_a_quad_is_a_miss_not_a_nan() {
    let quad = unit_quad();
    assert_eq!(intersect(&quad, &ray([-5.0, 0.0, 0.0], [1.0, 0.0, 0.0]), 0.0), None);
    let nearly = ray([-5.0, 0.0, 1e-300], [1.0, 0.0, -1e-300]);
    assert_eq!(intersect(&quad, &nearly, 0.0), None);
}

#[test]
fn moving_sphere_is_where_its_velocity_puts_it() {
    let shape = Shape::Sphere { sphere: Sphere::new(DVec3::ZERO, 1.0).unwrap(), velocity: DVec3::new(2.0, 0.0, 0.0) };
    let probe = ray([2.0, 0.0, 5.0], [0.0, 0.0, -1.0]);
    assert_eq!(intersect(&shape, &probe, 0.0), None);
    assert_eq!(intersect(&shape, &probe, 1.0), Some(4.0));
}

/// Random rays from inside and outside a 400-sphere forest with a moving sphere and a quad
/// added: closest hits, shadow tests and pierce counts agree with the brute-force loop.
#[test]
fn kd_tree_queries_equal_brute_force_on_a_mixed_scene() {
    let forest = crate::render::catalogue::clutter_forest(400, 3).unwrap();
    let mut objects = forest.objects().to_vec();
    let material = Material::Diffuse { albedo: DVec3::splat(0.5) };
    let mover = Sphere::new(DVec3::new(0.0, 0.0, -5.0), 2.0).unwrap();
    objects.insert(7, Object { shape: Shape::Sphere { sphere: mover, velocity: DVec3::X }, material });
    objects.push(Object::quad(DVec3::new(-30.0, -3.0, -12.0), DVec3::X * 60.0, DVec3::Y * 6.0, material));
    // Times 0…1.5 fall in the shutter (the mover's swept box), 2.0 outside it.
    let camera = Camera { shutter: (0.0, 1.5), ..*forest.camera() };
    let scene = Scene::new(camera, objects, vec![], None, DVec3::ZERO).unwrap();
    assert_eq!(scene.kd_tree_spheres(), 401, "the moving sphere is in the tree, the quad outside");
    let brute = scene.without_kd_tree();
    let mut rng = hw3_core::rng::seeded(11, 0);
    let mut point = |half: f64| {
        let mut coordinate = || hw3_core::rng::uniform_in(&mut rng, -half, half);
        DVec3::new(coordinate(), coordinate(), coordinate() - 5.0)
    };
    let mut hits = 0;
    for case in 0..2000 {
        let origin = if case % 2 == 0 { point(8.0) } else { point(30.0) };
        let ray = Ray::<f64>::new(origin, (point(25.0) - origin).normalize()).unwrap();
        let (time, t_max) = (f64::from(case % 5) * 0.5, if case % 3 == 0 { 6.0 } else { f64::INFINITY });
        let hit = scene.closest_hit(&ray, time, t_max);
        assert_eq!(hit, brute.closest_hit(&ray, time, t_max), "ray {case}");
        assert_eq!(scene.occluded(&ray, time, t_max), brute.occluded(&ray, time, t_max), "ray {case}");
        assert_eq!(scene.objects_pierced(&ray, time, t_max), brute.objects_pierced(&ray, time, t_max), "ray {case}");
        hits += usize::from(hit.is_some());
    }
    assert!((300..1700).contains(&hits), "the rays both hit and miss: {hits} hits of 2000");
}

/// The documented exception of the hit-by-hit walk: a sphere duplicated bit for bit is crossed
/// at the same `t` as its twin, and the tree reports one sphere per `t`.
#[test]
fn duplicated_sphere_is_pierced_once_through_the_tree_and_twice_by_brute_force() {
    let ball = Object::sphere(Sphere::new(DVec3::ZERO, 1.0).unwrap(), Material::Diffuse { albedo: DVec3::ONE });
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 40.0);
    let scene = Scene::new(camera, vec![ball, ball], vec![], None, DVec3::ZERO).unwrap();
    let probe = ray([0.0, 0.0, 5.0], [0.0, 0.0, -1.0]);
    assert_eq!(scene.objects_pierced(&probe, 0.0, f64::INFINITY), 1);
    assert_eq!(scene.without_kd_tree().objects_pierced(&probe, 0.0, f64::INFINITY), 2);
    assert_eq!(scene.closest_hit(&probe, 0.0, 9.0).map(|h| h.object), Some(0), "ties go to the lower index");
}

#[test]
fn invalid_scenes_are_typed_errors_naming_the_value() {
    let camera = Camera { shutter: (0.0, 1.0), ..Camera::looking_at(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 40.0) };
    let name = |r: Result<Scene, InputError>| match r.unwrap_err() {
        InputError::NonFinite { name, .. }
        | InputError::DegenerateDirection { name, .. }
        | InputError::OutOfRange { name, .. } => name,
        InputError::Unresolvable { precision, .. } => precision,
    };
    let scene = |camera, objects, fog| Scene::new(camera, objects, vec![], fog, DVec3::ZERO);
    let parallel_up = Camera { up: DVec3::Z, ..camera };
    assert_eq!(name(scene(parallel_up, vec![], None)), "camera view direction");
    let inverted = Camera { shutter: (1.0, 0.0), ..camera };
    assert_eq!(name(scene(inverted, vec![], None)), "shutter close");
    let flat = Object {
        shape: Shape::Quad { corner: DVec3::ZERO, edge_u: DVec3::X, edge_v: DVec3::X * 2.0 },
        material: Material::Diffuse { albedo: DVec3::ONE },
    };
    assert_eq!(name(scene(camera, vec![flat], None)), "quad edges");
    let bright = Object { shape: unit_quad(), material: Material::Diffuse { albedo: DVec3::splat(1.5) } };
    assert_eq!(name(scene(camera, vec![bright], None)), "diffuse albedo");
    let fog = Fog { sigma_a: 0.0, sigma_s: f64::NAN };
    assert_eq!(name(scene(camera, vec![], Some(fog))), "fog sigma_s");
}

/// Every built-in scene's spheres are found by the cheapest walk that is right for it: the
/// coarse-filtered tree whenever no sphere moves (the moving tree only for the motion scene's
/// moving ball, which, alone, is tested directly).
#[test]
fn every_built_in_scene_takes_the_walk_its_spheres_allow() {
    use crate::kdtree::Walk;
    use crate::render::catalogue::{CATALOGUE, by_name};
    use crate::render::scene::SphereQueries;
    let walks: Vec<(&str, Option<SphereQueries>)> =
        CATALOGUE.iter().map(|(name, _)| (*name, by_name(name).unwrap().sphere_queries())).collect();
    crate::testing::insta_settings().bind(|| insta::assert_debug_snapshot!("builtin_scene_walks", walks));
    for (name, walk) in walks {
        assert_ne!(walk, Some(SphereQueries::Tree(Walk::Moving)), "{name}: no built-in scene needs the moving tree");
        assert_ne!(walk, Some(SphereQueries::Tree(Walk::Exact)), "{name}: every built-in sphere fits the coarse grid");
    }
    let moving = crate::render::catalogue::moving_ball(2.0).unwrap();
    assert_eq!(moving.sphere_queries(), Some(SphereQueries::OneByOne));
}
