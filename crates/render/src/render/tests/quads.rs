//! Tests of `render::scene::quads`.

use crate::render::catalogue;
use crate::render::scene::quads::QuadSet;
use crate::render::scene::{Material, Object, Scene};
use glam::DVec3;
use hw3_core::geometry::Ray;

/// Plane-first rejection changes no answer: on the Cornell box (quads and spheres) with a
/// quad duplicated bit for bit and one sharing an edge (exact ties, decided by object index),
/// every query equals the brute-force loop's over rays from inside and outside the box.
#[test]
fn prepared_quads_answer_every_query_as_the_brute_force_loop() {
    let cornell = catalogue::cornell_mirror().unwrap();
    let mut objects = cornell.objects().to_vec();
    let grey = Material::Diffuse { albedo: DVec3::splat(0.5) };
    let panel = Object::quad(DVec3::new(-0.5, -0.5, -0.5), DVec3::X, DVec3::Y, grey);
    let neighbour = Object::quad(DVec3::new(0.5, -0.5, -0.5), DVec3::X, DVec3::Y, grey);
    objects.extend([panel, neighbour, panel]);
    let scene = Scene::new(*cornell.camera(), objects, vec![], None, DVec3::ZERO).unwrap();
    let brute = scene.without_kd_tree();
    let mut rng = hw3_core::rng::seeded(5, 0);
    let mut coordinate = |half: f64| hw3_core::rng::uniform_in(&mut rng, -half, half);
    let (mut hits, mut ties) = (0, 0);
    for case in 0..4000 {
        let half = if case % 2 == 0 { 1.0 } else { 4.0 };
        let origin = DVec3::new(coordinate(half), coordinate(half), coordinate(half) + 2.0);
        let target = if case % 4 == 1 {
            DVec3::new(0.5, coordinate(0.5), -0.5) // the shared edge and the duplicate
        } else {
            DVec3::new(coordinate(1.5), coordinate(1.5), coordinate(1.5))
        };
        let Ok(ray) = Ray::<f64>::new(origin, (target - origin).normalize()) else { continue };
        let t_max = if case % 3 == 0 { 2.0 } else { f64::INFINITY };
        let hit = scene.closest_hit(&ray, 0.0, t_max);
        assert_eq!(hit, brute.closest_hit(&ray, 0.0, t_max), "ray {case}");
        assert_eq!(scene.occluded(&ray, 0.0, t_max), brute.occluded(&ray, 0.0, t_max), "ray {case}");
        assert_eq!(scene.objects_pierced(&ray, 0.0, t_max), brute.objects_pierced(&ray, 0.0, t_max), "ray {case}");
        hits += usize::from(hit.is_some());
        ties += usize::from(hit.is_some_and(|h| h.object == cornell.objects().len()));
    }
    assert!(hits > 2000 && ties > 10, "the rays hit the box and the tied panels: {hits} hits, {ties} ties");
}

/// The boxes skip nothing the quad test would hit: on the Cornell box with its block (a boxed
/// run of five faces) and on the checker floor of 64 tiles (boxed rows), every query equals the
/// brute-force loop's over rays from inside and outside the scene, from far away (where the
/// origin's share of the padding matters), along the axes (a direction component of exactly
/// zero) and grazing the boxes' faces.
#[test]
fn boxed_runs_answer_every_query_as_the_brute_force_loop() {
    let block = catalogue::cornell_box(true, catalogue::CornellContents::Block).unwrap();
    let floor = catalogue::mirror_spheres(true).unwrap();
    for (scene, boxed_run) in [(&block, 6..11), (&floor, 0..8)] {
        let (runs, boxed) = QuadSet::new(scene.objects()).runs_and_boxed_objects();
        assert!(runs.contains(&(boxed_run, true)), "{runs:?}");
        let brute = scene.without_kd_tree();
        let mut rng = hw3_core::rng::seeded(9, 0);
        let mut coordinate = |half: f64| hw3_core::rng::uniform_in(&mut rng, -half, half);
        let mut hits = 0;
        for case in 0..6000 {
            let scale = [1.0, 5.0, 1e6][case % 3];
            let origin = DVec3::new(coordinate(scale), coordinate(scale), coordinate(scale));
            let target = DVec3::new(coordinate(1.0), coordinate(1.0) - 0.5, coordinate(1.0) - 2.0);
            let dir = match case % 5 {
                0 => DVec3::new(0.0, -1.0, 0.0), // straight down: x and z components exactly 0
                1 => DVec3::new(1.0, 0.0, 0.0),
                _ => (target - origin).normalize(),
            };
            // Grazing: along the block's top face (y = −0.4) and the floor (y = 0, y = −1).
            let origin =
                if case % 7 == 0 { DVec3::new(origin.x, [-0.4, 0.0, -1.0][case % 3], origin.z) } else { origin };
            let Ok(ray) = Ray::<f64>::new(origin, dir) else { continue };
            let t_max = if case % 4 == 0 { 1.5 } else { f64::INFINITY };
            let hit = scene.closest_hit(&ray, 0.0, t_max);
            assert_eq!(hit, brute.closest_hit(&ray, 0.0, t_max), "ray {case}");
            assert_eq!(scene.occluded(&ray, 0.0, t_max), brute.occluded(&ray, 0.0, t_max), "ray {case}");
            assert_eq!(scene.objects_pierced(&ray, 0.0, t_max), brute.objects_pierced(&ray, 0.0, t_max), "ray {case}");
            hits += usize::from(hit.is_some_and(|h| boxed.contains(&h.object)));
        }
        assert!(hits > 100, "the rays hit the boxed quads: {hits}");
    }
}
