//! Light-path analysis: which of Heckbert's path classes can carry energy to the eye in a scene,
//! derived from its materials, lights, medium and motion, and the render passes that follow.
//!
//! Which letters a class needs is a question about regular languages, answered by [`grammar`]
//! (shared with the Q5 effect tables): a class is kept only when its language meets the scene's.
//!
//! The analysis is *conservative where it is coarse*: a class is dropped only when a letter it
//! needs is absent from the scene (no mirror, no medium, nothing moving, no two diffuse surfaces),
//! or, for caustics, when no light sees any specular surface (checked by shadow rays to sample
//! points on each mirror). A coarse "present" can keep a pass that turns out to add nothing; a
//! "skipped" is always safe, which is what the plan tests check.

pub mod grammar;

use super::passes::{Pass, Passes};
use super::sampling::fibonacci_sphere;
use super::scene::{Material, Scene, Shape};
use glam::DVec3;
use grammar::{Lang, Letter, common_word};
use hw3_core::geometry::Ray;
use hw3_core::geometry::sphere::spawn_origin;
use serde::Serialize;

/// One light-path class in Heckbert's notation and whether it can carry energy in the scene.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct PathClass {
    /// The regular expression, light first: `LDE`, `L(D|G)?S+E`, …
    pub notation: &'static str,
    /// What the class looks like in an image.
    pub effect: &'static str,
    /// Whether the scene has everything the class needs.
    pub carries_energy: bool,
    /// Why (or what is missing), derived from the scene.
    pub reason: String,
    /// The pass that renders the class, if it needs one beyond plain eye rays with direct light.
    pub pass: Option<Pass>,
}

/// The analysis of a scene: letters present, path classes, and the pass plan.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Analysis {
    /// Path classes in a fixed order.
    pub classes: Vec<PathClass>,
    /// Whether every segment is attenuated by a medium with `σ_t > 0` (not a letter of its own:
    /// it multiplies every class).
    pub extinction: bool,
    /// Whether some object moves during an open shutter (every class then varies over time).
    pub moving: bool,
    /// The passes the renderer runs.
    pub plan: Passes,
    /// Classes that carry energy but that no pass of this renderer renders (for example caustics
    /// from point lights), as notation strings.
    pub not_rendered: Vec<&'static str>,
}

/// Letters and facts of a scene that the path classes depend on.
#[derive(Debug, Clone, Copy, Default)]
struct Letters {
    point_light: bool,
    area_light: bool,
    /// A non-black environment map: a light at infinity, non-delta like an area light.
    environment: bool,
    diffuse: bool,
    glossy: bool,
    specular: bool,
    diffuse_like_objects: usize,
    /// A light (point, area or environment) sees a mirror or glass.
    lit_specular: bool,
    /// A point or area light sees a mirror or glass: the caustic map has photons to shoot.
    lamp_lit_specular: bool,
    scattering: bool,
    extinction: bool,
    moving: bool,
}

/// Analyses `scene`: which path classes carry energy, and which passes to run.
///
/// # Examples
/// ```
/// use hw3_render::render::{analysis::analyze, catalogue, passes::Pass};
/// let fog = analyze(&catalogue::fog_street(0.1).unwrap());
/// assert!(fog.plan.get(Pass::InScattering));
/// assert!(!fog.plan.get(Pass::SpecularRecursion)); // no mirror in the street
/// ```
#[must_use]
pub fn analyze(scene: &Scene) -> Analysis {
    let letters = letters(scene);
    let light = letters.point_light || letters.area_light || letters.environment;
    let diffuse_like = letters.diffuse || letters.glossy;
    let yes_no = |ok: bool, yes: &str, no: &str| {
        if ok { yes.to_string() } else { no.to_string() }
    };
    let mut classes = vec![
        PathClass {
            notation: "LE",
            effect: "an area light or environment seen directly",
            carries_energy: true,
            reason: yes_no(
                letters.area_light || letters.environment,
                "an emitter quad or an environment map",
                "no area light or environment",
            ),
            pass: None,
        },
        PathClass {
            notation: "LDE",
            effect: "diffuse shading and shadows",
            carries_energy: true,
            reason: yes_no(
                light && letters.diffuse,
                "a light and a diffuse surface",
                "needs a light and a diffuse surface",
            ),
            pass: None,
        },
        PathClass {
            notation: "LGE",
            effect: "glossy highlights",
            carries_energy: true,
            reason: yes_no(light && letters.glossy, "a light and a glossy surface", "no glossy surface"),
            pass: None,
        },
        PathClass {
            notation: "L(D|G)?S+E",
            effect: "reflections and refractions (mirrors, glass)",
            carries_energy: true,
            reason: yes_no(letters.specular, "a mirror or glass", "no mirror or glass"),
            pass: Some(Pass::SpecularRecursion),
        },
        PathClass {
            notation: "L(D|G)(D|G)+S*E",
            effect: "indirect light, colour bleeding",
            carries_energy: letters.diffuse_like_objects >= 2,
            reason: format!(
                "{} diffuse or glossy objects; two or more can exchange light",
                letters.diffuse_like_objects
            ),
            pass: Some(Pass::IndirectBounces),
        },
        PathClass {
            notation: "LS+(D|G)…E",
            effect: "caustics",
            carries_energy: letters.lit_specular,
            reason: yes_no(letters.lit_specular, "a light sees a mirror or glass", "no light sees a mirror or glass"),
            pass: Some(Pass::Caustics),
        },
        PathClass {
            notation: "LV(D|G|S)*E",
            effect: "glow of lights in fog (single scattering)",
            carries_energy: letters.point_light || letters.area_light,
            reason: yes_no(
                letters.scattering && (letters.point_light || letters.area_light),
                "a scattering medium and a point or area light",
                "needs a scattering medium (σ_s > 0) and a point or area light",
            ),
            pass: Some(Pass::InScattering),
        },
    ];
    // The letter test is one language intersection per class: the class must share a path with
    // the scene's language. The flags left above are what letters cannot say (two objects to
    // exchange light, a light that sees the mirror, in-scattering only from point and area lights).
    let scene_language = scene_language(&letters);
    for class in &mut classes {
        let class_language = Lang::parse(class.notation).expect("built-in notation parses");
        class.carries_energy &= common_word(&class_language, &scene_language).expect("small languages").is_some();
    }
    let mut plan = Passes { transmittance: letters.extinction, time_sampling: letters.moving, ..Passes::default() };
    for class in &classes {
        if let (true, Some(pass)) = (class.carries_energy, class.pass) {
            plan = plan.with(pass, true);
        }
    }
    // A mirror that only reflects the background or fog still needs recursion.
    plan.specular_recursion |= letters.specular;
    // The caustic map is shot from point and area lights: caustics of the environment alone are
    // left to the path tracer (whose escaping bounces see the map), so the pass would trace nothing.
    plan.caustics &= letters.lamp_lit_specular && diffuse_like;
    // The path tracer reaches a caustic by bouncing off the diffuse surface through the glass
    // into an area light or the environment: that bounce is the indirect pass, needed even with
    // a single diffuse object (a point light is never hit, so it adds nothing there).
    let caustic_carried = classes.iter().any(|c| c.pass == Some(Pass::Caustics) && c.carries_energy);
    plan.indirect_bounces |= caustic_carried && (letters.area_light || letters.environment);
    let mut not_rendered = vec![];
    // Single scattering gathers point lights only: the environment's glow in fog is not rendered
    // (and in a medium nothing arrives from infinitely far, so the environment lights nothing else).
    if letters.environment && letters.scattering {
        not_rendered.push("LV(D|G|S)*E (environment)");
    }
    Analysis { classes, extinction: letters.extinction, moving: letters.moving, plan, not_rendered }
}

/// The paths a scene can carry, as a language over the letters its materials provide:
/// `L M* E` for area lights and the environment (M = the letters present) and `L M* [DGV] M* E` for point lights,
/// whose paths need one non-delta vertex (a point light seen directly or through mirrors only,
/// `LS*E`, has measure zero). ∅ without a light.
#[must_use]
fn scene_language(letters: &Letters) -> Lang {
    let present: Vec<Letter> = [
        (Letter::D, letters.diffuse),
        (Letter::G, letters.glossy),
        (Letter::S, letters.specular),
        (Letter::V, letters.scattering),
    ]
    .into_iter()
    .filter_map(|(l, on)| on.then_some(l))
    .collect();
    let any = || Lang::star(Lang::any_of(&present));
    let light_to = |middle: Lang| Lang::concat(Lang::letter(Letter::L), Lang::concat(middle, Lang::letter(Letter::E)));
    let area = if letters.area_light || letters.environment { light_to(any()) } else { Lang::Empty };
    let non_delta: Vec<Letter> = present.iter().copied().filter(|&l| l != Letter::S).collect();
    let point = if letters.point_light {
        light_to(Lang::concat(any(), Lang::concat(Lang::any_of(&non_delta), any())))
    } else {
        Lang::Empty
    };
    Lang::union(area, point)
}

fn letters(scene: &Scene) -> Letters {
    let mut letters = Letters {
        point_light: scene.point_lights().iter().any(|l| l.intensity.max_element() > 0.0),
        environment: scene.environment().is_some_and(|e| !e.is_black()),
        ..Letters::default()
    };
    let (open, close) = scene.camera().shutter;
    for object in scene.objects() {
        match object.material {
            Material::Diffuse { albedo } => letters.diffuse |= albedo.max_element() > 0.0,
            Material::Glossy { diffuse, specular, .. } => {
                letters.diffuse |= diffuse.max_element() > 0.0;
                letters.glossy |= specular.max_element() > 0.0;
            }
            Material::Mirror { reflectance } => letters.specular |= reflectance.max_element() > 0.0,
            Material::Glass { .. } => letters.specular = true,
            Material::Emitter { radiance } => letters.area_light |= radiance.max_element() > 0.0,
        }
        letters.diffuse_like_objects += usize::from(reflects_diffusely(&object.material));
        if let Shape::Sphere { velocity, .. } = object.shape {
            letters.moving |= velocity != DVec3::ZERO && close > open;
        }
    }
    if let Some(fog) = scene.fog() {
        letters.scattering = fog.sigma_s > 0.0;
        letters.extinction = fog.sigma_t() > 0.0;
    }
    // An environment surrounds everything: coarsely, it sees every mirror.
    letters.lamp_lit_specular = letters.specular && light_sees_a_mirror(scene);
    letters.lit_specular = letters.lamp_lit_specular || (letters.specular && letters.environment);
    letters
}

fn reflects_diffusely(material: &Material) -> bool {
    match *material {
        Material::Diffuse { albedo } => albedo.max_element() > 0.0,
        Material::Glossy { diffuse, specular, .. } => (diffuse + specular).max_element() > 0.0,
        Material::Mirror { .. } | Material::Glass { .. } | Material::Emitter { .. } => false,
    }
}

/// Whether any light position (point lights, area-light corners and centres) has an unoccluded
/// line of sight to a front-facing sample point of any mirror, at shutter open.
fn light_sees_a_mirror(scene: &Scene) -> bool {
    let mut light_points: Vec<DVec3> = scene.point_lights().iter().map(|l| l.position).collect();
    for light in scene.area_lights() {
        light_points.extend(quad_samples(light.corner, light.edge_u, light.edge_v).map(|(p, _)| p));
    }
    let time = scene.camera().shutter.0;
    scene
        .objects()
        .iter()
        .filter(|o| matches!(o.material, Material::Mirror { .. } | Material::Glass { .. }))
        .flat_map(|o| surface_samples(&o.shape, time))
        .any(|(point, normal)| {
            light_points.iter().any(|&light| {
                let to_light = light - point;
                let distance = to_light.length();
                if normal.dot(to_light) <= 0.0 {
                    return false;
                }
                let dir = to_light / distance;
                let ray = Ray { origin: spawn_origin::<f64>(point, normal, dir), dir };
                !scene.occluded(&ray, time, distance * (1.0 - 1e-9))
            })
        })
}

/// Sample points with normals on a shape: 3×3 grid on quads (corners, edge midpoints and centre),
/// 200 Fibonacci-lattice points on spheres.
fn surface_samples(shape: &Shape, time: f64) -> Vec<(DVec3, DVec3)> {
    match *shape {
        Shape::Quad { corner, edge_u, edge_v } => quad_samples(corner, edge_u, edge_v).collect(),
        Shape::Sphere { sphere, velocity } => {
            let center = sphere.center + velocity * time;
            fibonacci_sphere(200).into_iter().map(|normal| (center + normal * sphere.radius, normal)).collect()
        }
    }
}

fn quad_samples(corner: DVec3, edge_u: DVec3, edge_v: DVec3) -> impl Iterator<Item = (DVec3, DVec3)> {
    let normal = edge_u.cross(edge_v).normalize();
    (0..9).map(move |k| {
        let (a, b) = ((k % 3) as f64 / 2.0, (k / 3) as f64 / 2.0);
        (corner + edge_u * a + edge_v * b, normal)
    })
}
