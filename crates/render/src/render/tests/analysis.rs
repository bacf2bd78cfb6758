//! Tests of [`super`] that exercise it through the layers above it (scenes of the catalogue, the
//! integrators): kept in their own file so that the import graph of the renderer stays a DAG.

use crate::render::analysis::*;
use crate::render::catalogue;
use crate::render::integrator::Integrator;
use crate::render::passes::{Pass, Passes};
use crate::render::scene::Scene;
use glam::DVec3;

fn carried(analysis: &Analysis) -> Vec<&'static str> {
    analysis.classes.iter().filter(|c| c.carries_energy).map(|c| c.notation).collect()
}

#[test]
fn each_built_in_scene_gets_the_classes_its_contents_imply() {
    let mirrors = analyze(&catalogue::mirror_spheres(true).unwrap());
    assert!(carried(&mirrors).contains(&"L(D|G)?S+E"));
    assert!(carried(&mirrors).contains(&"LS+(D|G)…E"));
    assert!(mirrors.plan.caustics && mirrors.not_rendered.is_empty(), "a point light's caustics get the photon pass");
    assert!(!Integrator::PathTracer { max_depth: 3 }.restrict(mirrors.plan).caustics);
    let caustic = analyze(&catalogue::by_name("caustic").unwrap());
    assert!(caustic.plan.caustics && caustic.plan.specular_recursion);
    assert!(!analyze(&catalogue::fog_street(0.1).unwrap()).plan.caustics);
    let diffuse = analyze(&catalogue::mirror_spheres(false).unwrap());
    assert!(!carried(&diffuse).contains(&"L(D|G)?S+E"));
    assert!(!diffuse.plan.specular_recursion);
    let fog = analyze(&catalogue::fog_street(0.1).unwrap());
    assert!(fog.extinction && fog.plan.in_scattering && fog.plan.transmittance);
    let clear = analyze(&catalogue::fog_street(0.0).unwrap());
    assert!(!clear.extinction && !clear.plan.in_scattering && !clear.plan.transmittance);
    let moving = analyze(&catalogue::moving_ball(2.0).unwrap());
    assert!(moving.moving && moving.plan.time_sampling);
    let still = analyze(&catalogue::moving_ball(0.0).unwrap());
    assert!(!still.moving && !still.plan.time_sampling);
}

#[test]
fn a_mirror_hidden_from_every_light_carries_no_caustic() {
    let scene = catalogue::mirror_behind_wall().unwrap();
    let analysis = analyze(&scene);
    assert!(analysis.plan.specular_recursion, "the eye still sees it");
    assert!(!carried(&analysis).contains(&"LS+(D|G)…E"));
    assert!(!analysis.plan.caustics);
}

/// The environment is a light derived from the scene: a non-black map lights the probe-lit
/// scene (LE, LDE, reflections, caustics through the mirror), a black one lights nothing, and
/// its glow in fog is reported as not rendered while an area light's glow is planned.
#[test]
fn the_environment_is_a_light_and_area_lights_glow_in_fog() {
    use crate::render::environment::Environment;
    let lit = analyze(&catalogue::probe_lit().unwrap());
    for class in ["LE", "LDE", "LGE", "L(D|G)?S+E", "LS+(D|G)…E"] {
        assert!(carried(&lit).contains(&class), "{class}");
    }
    assert!(!lit.plan.caustics, "environment caustics are the path tracer's: no photons to shoot");
    let no_light = catalogue::mirror_spheres(false).unwrap();
    let (camera, objects) = (*no_light.camera(), no_light.objects().to_vec());
    let dark = Scene::new(camera, objects, vec![], None, DVec3::ONE).unwrap();
    let black = analyze(&dark.with_environment(Environment::constant(DVec3::ZERO).unwrap()));
    assert!(!carried(&black).contains(&"LDE"), "a black environment is no light");
    let foggy = catalogue::fog_panel(0.15).unwrap();
    let analysis = analyze(&foggy);
    assert!(analysis.plan.in_scattering && analysis.not_rendered.is_empty());
    let with_sky = analyze(&foggy.with_environment(Environment::constant(DVec3::ONE).unwrap()));
    assert_eq!(with_sky.not_rendered, vec!["LV(D|G|S)*E (environment)"]);
}

#[test]
fn passes_all_sets_every_flag_and_with_clears_one() {
    let all = Passes::all();
    assert!(Pass::ALL.iter().all(|&p| all.get(p)));
    for pass in Pass::ALL {
        let off = all.with(pass, false);
        assert!(!off.get(pass));
        assert_eq!(Pass::ALL.iter().filter(|&&p| off.get(p)).count(), Pass::ALL.len() - 1);
    }
}
