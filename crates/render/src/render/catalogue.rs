//! The catalogue of built-in scenes: Q1's four hard scenes (and their easy twins), plus a small box for the path
//! tracer, and the Cornell box ([`cornell_box`]) the renderer and Q5 share. `hw3 scenes` lists them; `hw3 render NAME` and `hw3 paths NAME` take their names.

use super::environment::Environment;
use super::error::RenderError;
use super::{
    camera::Camera,
    scene::{Fog, Material, Object, PointLight, Scene, Shape},
};
use glam::DVec3;
use hw3_core::geometry::{InputError, Sphere};
use hw3_core::rng;

/// Every built-in scene: CLI name and a one-line description.
pub const CATALOGUE: [(&str, &str); 11] = [
    ("clutter", "1500 spheres in a 41×41×10 slab, seen from the front"),
    ("fog", "a street with two lamps in fog (σ_s = 0.08, no absorption)"),
    ("clear-street", "the fog street in clear air"),
    ("mirrors", "four mirror spheres over a checker floor"),
    ("diffuse-spheres", "the mirrors scene with the spheres made diffuse"),
    ("motion", "a ball moving 2 units while the shutter is open"),
    ("still", "the motion scene with the ball at rest"),
    ("cornell", "the Cornell box with a mirror, a glossy and a glass sphere (indirect light, caustics)"),
    ("probe-lit", "diffuse, glossy and mirror spheres on a floor, lit only by the courtyard light probe"),
    ("fog-panel", "a ceiling panel light over a ball in fog (area-light single scattering)"),
    ("caustic", "a glass ball over a white floor under a small area light (a refraction caustic)"),
];

/// The built-in scene called `name` (see [`CATALOGUE`]).
///
/// # Errors
/// [`RenderError::UnknownScene`] listing the known names.
///
/// # Examples
/// ```
/// assert!(hw3_render::render::catalogue::by_name("mirrors").is_ok());
/// assert!(hw3_render::render::catalogue::by_name("nope").is_err());
/// ```
pub fn by_name(name: &str) -> Result<Scene, RenderError> {
    let scene = match name {
        "clutter" => clutter_forest(CLUTTER_COUNT, 1),
        "fog" => fog_street(0.08),
        "clear-street" => fog_street(0.0),
        "mirrors" => mirror_spheres(true),
        "diffuse-spheres" => mirror_spheres(false),
        "motion" => moving_ball(2.0),
        "still" => moving_ball(0.0),
        "cornell" => cornell_mirror(),
        "probe-lit" => return probe_lit(),
        "fog-panel" => fog_panel(0.15),
        "caustic" => glass_ball_caustic(),
        _ => {
            return Err(RenderError::UnknownScene { name: name.into(), known: CATALOGUE.map(|(n, _)| n).join(", ") });
        }
    };
    Ok(scene?)
}

/// Number of spheres of the built-in `clutter` scene.
pub const CLUTTER_COUNT: usize = 1500;
/// Half-width `W/2` of the clutter slab's square front face.
pub const CLUTTER_HALF_WIDTH: f64 = 20.0;
/// Depth `Z` of the clutter slab (it spans `z ∈ [−Z, 0]`).
pub const CLUTTER_DEPTH: f64 = 10.0;
/// Radius `a` of every clutter sphere.
pub const CLUTTER_RADIUS: f64 = 0.5;

/// `count` diffuse spheres of radius [`CLUTTER_RADIUS`] with centres uniform in
/// `[−W/2 − a, W/2 + a]² × [−Z, 0]` (a Boolean model), seeded by `seed`; camera 12 units in
/// front of the slab looking in, a point light above it, sky-blue background.
///
/// # Errors
/// Never for the built-in numbers; the `Result` carries [`Scene::new`]'s validation.
pub fn clutter_forest(count: usize, seed: u64) -> Result<Scene, InputError> {
    let mut random = rng::pcg32(seed, 0xC1);
    let mut uniform = move || rng::uniform(&mut random);
    let half = CLUTTER_HALF_WIDTH + CLUTTER_RADIUS;
    let objects = (0..count)
        .map(|_| {
            let center =
                DVec3::new(-half + 2.0 * half * uniform(), -half + 2.0 * half * uniform(), -CLUTTER_DEPTH * uniform());
            let shade = 0.35 + 0.4 * uniform();
            Ok(Object {
                shape: Shape::Sphere { sphere: Sphere::new(center, CLUTTER_RADIUS)?, velocity: DVec3::ZERO },
                material: Material::Diffuse { albedo: DVec3::new(0.3 * shade, shade, 0.35 * shade) },
            })
        })
        .collect::<Result<Vec<_>, InputError>>()?;
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 12.0), DVec3::new(0.0, 0.0, -CLUTTER_DEPTH), 40.0);
    let sun = PointLight { position: DVec3::new(10.0, 40.0, 25.0), intensity: DVec3::splat(2500.0) };
    Scene::new(camera, objects, vec![sun], None, DVec3::new(0.55, 0.7, 0.9))
}

/// A night street: ground, two rows of pale posts (spheres) every 5 units, two lamps, and a
/// non-absorbing fog with `σ_s = σ_t = sigma_t` (no medium at all when `sigma_t = 0`).
///
/// # Errors
/// [`InputError`] for a negative or non-finite `sigma_t`.
pub fn fog_street(sigma_t: f64) -> Result<Scene, InputError> {
    let ground = Object::quad(
        DVec3::new(-6.0, 0.0, 5.0),
        DVec3::new(12.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -70.0),
        Material::Diffuse { albedo: DVec3::splat(0.4) },
    );
    let mut objects = vec![ground];
    for k in 1..=8 {
        for side in [-2.5, 2.5] {
            objects.push(Object {
                shape: Shape::Sphere {
                    sphere: Sphere::new(DVec3::new(side, 0.6, -5.0 * f64::from(k)), 0.6)?,
                    velocity: DVec3::ZERO,
                },
                material: Material::Diffuse { albedo: DVec3::new(0.9, 0.85, 0.7) },
            });
        }
    }
    let lamps = [-6.0, -22.0]
        .map(|z| PointLight { position: DVec3::new(0.0, 3.5, z), intensity: DVec3::new(40.0, 34.0, 24.0) });
    let camera = Camera::looking_at(DVec3::new(0.0, 1.6, 4.0), DVec3::new(0.0, 1.2, -20.0), 45.0);
    let fog = (sigma_t != 0.0).then_some(Fog { sigma_a: 0.0, sigma_s: sigma_t });
    Scene::new(camera, objects, lamps.to_vec(), fog, DVec3::ZERO)
}

/// An `n × n` checker of unit-square diffuse tiles on `y = 0`, centred on `(0, 0, center_z)`.
fn checker_floor(n: u32, center_z: f64) -> Vec<Object> {
    let half = f64::from(n) / 2.0;
    (0..n * n)
        .map(|k| {
            let (i, j) = (k % n, k / n);
            let albedo = if (i + j) % 2 == 0 { 0.8 } else { 0.15 };
            Object {
                shape: Shape::Quad {
                    corner: DVec3::new(f64::from(i) - half, 0.0, center_z - half + f64::from(j)),
                    edge_u: DVec3::X,
                    edge_v: DVec3::Z,
                },
                material: Material::Diffuse { albedo: DVec3::splat(albedo) },
            }
        })
        .collect()
}

/// The camera of [`mirror_spheres`], moved by `offset` (Q1c displaces it).
#[must_use]
pub fn mirror_camera(offset: DVec3) -> Camera {
    Camera::looking_at(DVec3::new(0.0, 2.2, 3.0) + offset, DVec3::new(0.0, 0.6, -3.0) + offset, 40.0)
}

/// Four spheres of radius 0.7 in a 2×2 block over an 8×8 checker floor, mirrors (reflectance
/// 0.9) or, for `mirror = false`, diffuse grey (albedo 0.8): Q1c's scene and its easy twin.
///
/// # Errors
/// Never for the built-in numbers.
pub fn mirror_spheres(mirror: bool) -> Result<Scene, InputError> {
    let mut objects = checker_floor(8, -3.0);
    for (x, z) in [(-0.75, -2.25), (0.75, -2.25), (-0.75, -3.75), (0.75, -3.75)] {
        objects.push(Object {
            shape: Shape::Sphere { sphere: Sphere::new(DVec3::new(x, 0.7, z), 0.7)?, velocity: DVec3::ZERO },
            material: if mirror {
                Material::Mirror { reflectance: DVec3::splat(0.9) }
            } else {
                Material::Diffuse { albedo: DVec3::splat(0.8) }
            },
        });
    }
    seen_by_mirror_camera(objects, DVec3::new(3.0, 6.0, 1.0), DVec3::new(0.25, 0.35, 0.55))
}

/// `objects` lit by one point light of intensity 50 at `light`, seen by [`mirror_camera`].
fn seen_by_mirror_camera(objects: Vec<Object>, light: DVec3, background: DVec3) -> Result<Scene, InputError> {
    let light = PointLight { position: light, intensity: DVec3::splat(50.0) };
    Scene::new(mirror_camera(DVec3::ZERO), objects, vec![light], None, background)
}

/// A mirror sphere under an opaque roof that hides it from the only light (for the caustic test).
///
/// # Errors
/// Never for the built-in numbers.
pub fn mirror_behind_wall() -> Result<Scene, InputError> {
    let mirror = Object {
        shape: Shape::Sphere { sphere: Sphere::new(DVec3::new(0.0, 1.0, -3.0), 0.7)?, velocity: DVec3::ZERO },
        material: Material::Mirror { reflectance: DVec3::ONE },
    };
    let roof = Object::quad(
        DVec3::new(-10.0, 2.5, 7.0),
        DVec3::new(20.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -20.0),
        Material::Diffuse { albedo: DVec3::splat(0.5) },
    );
    let mut objects = checker_floor(4, -3.0);
    objects.extend([mirror, roof]);
    seen_by_mirror_camera(objects, DVec3::new(0.0, 6.0, -3.0), DVec3::ZERO)
}

/// Shutter of [`moving_ball`]: open at 0, close at 1.
pub const MOTION_SHUTTER: (f64, f64) = (0.0, 1.0);

/// A red ball of radius 0.5 moving along `+x` at `speed` units per unit time across a 6×6
/// checker floor, shutter [`MOTION_SHUTTER`]: Q1d's scene (at rest for `speed = 0`).
///
/// # Errors
/// [`InputError`] for a non-finite `speed`.
pub fn moving_ball(speed: f64) -> Result<Scene, InputError> {
    moving_ball_with_shutter(speed, MOTION_SHUTTER)
}

/// [`moving_ball`] with another shutter interval (Q1d renders instantaneous frames).
///
/// # Errors
/// [`InputError`] for a non-finite `speed` or an invalid shutter.
pub fn moving_ball_with_shutter(speed: f64, shutter: (f64, f64)) -> Result<Scene, InputError> {
    let mut objects = checker_floor(6, -3.0);
    objects.push(Object {
        shape: Shape::Sphere {
            sphere: Sphere::new(DVec3::new(-1.0, 0.5, -3.0), 0.5)?,
            velocity: DVec3::new(speed, 0.0, 0.0),
        },
        material: Material::Diffuse { albedo: DVec3::new(0.8, 0.15, 0.1) },
    });
    let camera = Camera {
        eye: DVec3::new(0.0, 2.0, 1.5),
        look_at: DVec3::new(0.0, 0.4, -3.0),
        up: DVec3::Y,
        vfov_degrees: 45.0,
        shutter,
    };
    let light = PointLight { position: DVec3::new(1.5, 5.0, 0.0), intensity: DVec3::splat(40.0) };
    Scene::new(camera, objects, vec![light], None, DVec3::splat(0.2))
}

/// Reflectance of the Cornell box's white walls: an RGB stand-in for the measured spectrum of
/// the Cornell University Program of Computer Graphics' "Cornell Box Data", the one of the
/// Tungsten renderer's scene (book.vertexwahn.de/docs/tools/cornell_box).
///
/// # Examples
/// ```
/// use hw3_render::render::catalogue::{CORNELL_GREEN, CORNELL_RED, CORNELL_WHITE};
/// // White reflects every channel alike (within 5 %); red and green reflect mostly their own.
/// assert!(CORNELL_WHITE.max_element() - CORNELL_WHITE.min_element() < 0.05);
/// assert!(CORNELL_RED.x > 5.0 * CORNELL_RED.y && CORNELL_GREEN.y > 3.0 * CORNELL_GREEN.x);
/// ```
pub const CORNELL_WHITE: DVec3 = DVec3::new(0.725, 0.71, 0.68);
/// Reflectance of the Cornell box's red wall (the source of [`CORNELL_WHITE`]).
///
/// # Examples
/// ```
/// let red = hw3_render::render::catalogue::CORNELL_RED;
/// assert!(red.x > red.y && red.x > red.z);
/// ```
pub const CORNELL_RED: DVec3 = DVec3::new(0.63, 0.065, 0.05);
/// Reflectance of the Cornell box's green wall (the source of [`CORNELL_WHITE`]).
///
/// # Examples
/// ```
/// let green = hw3_render::render::catalogue::CORNELL_GREEN;
/// assert!(green.y > green.x && green.y > green.z);
/// ```
pub const CORNELL_GREEN: DVec3 = DVec3::new(0.14, 0.45, 0.091);
/// Radiance of the [`cornell_box`]'s ceiling light (grey).
///
/// # Examples
/// ```
/// use hw3_render::render::catalogue::{CORNELL_LIGHT_RADIANCE, CornellContents, cornell_box};
/// let light = cornell_box(true, CornellContents::Block).unwrap().area_lights().next().unwrap();
/// assert_eq!(light.radiance, glam::DVec3::splat(CORNELL_LIGHT_RADIANCE));
/// ```
pub const CORNELL_LIGHT_RADIANCE: f64 = 12.0;

/// The six inward-facing walls of the box `[−1, 1]³` (each quad's `edge_u × edge_v` points
/// inside), in the order floor, ceiling, back, left, right, front.
fn box_walls(albedos: [DVec3; 6]) -> Vec<Object> {
    let (x, y, z) = (DVec3::X * 2.0, DVec3::Y * 2.0, DVec3::Z * 2.0);
    let low = DVec3::splat(-1.0);
    let geometry = [
        (low, z, x),
        (DVec3::new(-1.0, 1.0, -1.0), x, z),
        (low, x, y),
        (low, y, z),
        (DVec3::new(1.0, -1.0, -1.0), z, y),
        (DVec3::new(-1.0, -1.0, 1.0), y, x),
    ];
    geometry
        .iter()
        .zip(albedos)
        .map(|(&(corner, u, v), albedo)| Object::quad(corner, u, v, Material::Diffuse { albedo }))
        .collect()
}

/// A closed box `[−1, 1]³` with every wall of reflectance `albedo` and the camera inside: a white
/// furnace of quads, where every wall's radiance is the same (the radiosity tests' analytic case).
///
/// # Errors
/// [`InputError`] for an albedo outside `[0, 1]`.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_render::render::catalogue::furnace_box;
/// assert_eq!(furnace_box(DVec3::splat(0.5)).unwrap().objects().len(), 6);
/// assert!(furnace_box(DVec3::splat(1.5)).is_err());
/// ```
pub fn furnace_box(albedo: DVec3) -> Result<Scene, InputError> {
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.9), DVec3::ZERO, 60.0);
    Scene::new(camera, box_walls([albedo; 6]), vec![], None, DVec3::ZERO)
}

/// What stands on the floor of the [`cornell_box`].
///
/// # Examples
/// ```
/// use hw3_render::render::catalogue::{CornellContents, cornell_box};
/// // Five walls and the light, then the block's five faces or the three spheres.
/// assert_eq!(cornell_box(true, CornellContents::Block).unwrap().objects().len(), 11);
/// assert_eq!(cornell_box(true, CornellContents::Spheres).unwrap().objects().len(), 9);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CornellContents {
    /// A white block `[0.1, 0.7] × [−1, −0.4] × [−0.3, 0.3]` (five faces, no bottom): a box of
    /// diffuse surfaces only, Q5's radiosity and measurement scene.
    Block,
    /// A mirror sphere (reflectance 0.95), a glossy one and a glass one (index 1.5): the
    /// `cornell` scene, with reflections and caustics.
    Spheres,
}

/// The Cornell box `[−1, 1]³`, open at the front (`z = 1`) where the camera looks in from
/// `(0, 0, 3.4)`: [`CORNELL_WHITE`] floor, ceiling and back, a [`CORNELL_GREEN`] right wall, a
/// left wall that is [`CORNELL_RED`] (`red_left`) or white (the twin without the red wall's
/// bleeding), a 0.5 × 0.5 light of radiance [`CORNELL_LIGHT_RADIANCE`] just under the ceiling
/// facing down, and `contents` on the floor. Every wall faces inwards; the ceiling is lit only
/// indirectly (the light faces away from it).
///
/// # Errors
/// Never for the built-in numbers.
///
/// # Examples
/// ```
/// use hw3_render::render::{catalogue::{CORNELL_RED, CornellContents, cornell_box}, scene::Material};
/// let scene = cornell_box(true, CornellContents::Block).unwrap();
/// assert_eq!(scene.objects()[3].material, Material::Diffuse { albedo: CORNELL_RED });
/// assert_eq!(scene.area_lights().count(), 1);
/// ```
pub fn cornell_box(red_left: bool, contents: CornellContents) -> Result<Scene, InputError> {
    let left = if red_left { CORNELL_RED } else { CORNELL_WHITE };
    let mut objects = box_walls([CORNELL_WHITE, CORNELL_WHITE, CORNELL_WHITE, left, CORNELL_GREEN, CORNELL_WHITE]);
    objects.pop(); // open front: the camera looks in
    objects.push(Object::quad(
        DVec3::new(-0.25, 0.99, -0.25),
        DVec3::X * 0.5,
        DVec3::Z * 0.5,
        Material::Emitter { radiance: DVec3::splat(CORNELL_LIGHT_RADIANCE) },
    ));
    match contents {
        CornellContents::Block => {
            let (x0, x1, y0, y1, z0, z1) = (0.1, 0.7, -1.0, -0.4, -0.3, 0.3);
            let (w, h) = (DVec3::X * (x1 - x0), DVec3::Y * (y1 - y0));
            let d = DVec3::Z * (z1 - z0);
            let white = Material::Diffuse { albedo: CORNELL_WHITE };
            for (corner, u, v) in [
                (DVec3::new(x0, y1, z0), d, w),
                (DVec3::new(x0, y0, z1), w, h),
                (DVec3::new(x0, y0, z0), h, w),
                (DVec3::new(x0, y0, z0), d, h),
                (DVec3::new(x1, y0, z0), h, d),
            ] {
                objects.push(Object::quad(corner, u, v, white));
            }
        }
        CornellContents::Spheres => objects.extend([
            Object::sphere(
                Sphere::new(DVec3::new(-0.4, -0.6, -0.3), 0.4)?,
                Material::Mirror { reflectance: DVec3::splat(0.95) },
            ),
            Object::sphere(
                Sphere::new(DVec3::new(0.45, -0.65, 0.2), 0.35)?,
                Material::Glossy { diffuse: DVec3::splat(0.5), specular: DVec3::splat(0.3), exponent: 40.0 },
            ),
            Object::sphere(Sphere::new(DVec3::new(0.1, -0.75, 0.6), 0.25)?, Material::Glass { index: 1.5 }),
        ]),
    }
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 3.4), DVec3::ZERO, 40.0);
    Scene::new(camera, objects, vec![], None, DVec3::ZERO)
}

/// The `cornell` scene: the [`cornell_box`] with its red left wall and the three spheres
/// ([`CornellContents::Spheres`]).
///
/// # Errors
/// Never for the built-in numbers.
///
/// # Examples
/// ```
/// let scene = hw3_render::render::catalogue::cornell_mirror().unwrap();
/// assert_eq!(scene.area_lights().count(), 1);
/// ```
pub fn cornell_mirror() -> Result<Scene, InputError> {
    cornell_box(true, CornellContents::Spheres)
}

/// A 1×1 panel light facing down 3 units above a grey floor, a ball under it, and a
/// non-absorbing fog of scattering coefficient `sigma_s` (no medium for 0): the area light's
/// glow in the fog is single scattering from an area light ([`super::medium`]).
///
/// # Errors
/// [`InputError`] for a negative or non-finite `sigma_s`.
pub fn fog_panel(sigma_s: f64) -> Result<Scene, InputError> {
    let floor = Object::quad(
        DVec3::new(-5.0, 0.0, 3.0),
        DVec3::new(10.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -12.0),
        Material::Diffuse { albedo: DVec3::splat(0.5) },
    );
    let panel = Object::quad(
        DVec3::new(-0.5, 3.0, -3.5),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
        Material::Emitter { radiance: DVec3::new(12.0, 11.0, 9.0) },
    );
    let ball =
        Object::sphere(Sphere::new(DVec3::new(0.0, 0.7, -3.0), 0.7)?, Material::Diffuse { albedo: DVec3::splat(0.7) });
    let camera = Camera::looking_at(DVec3::new(0.0, 1.8, 4.0), DVec3::new(0.0, 1.5, -3.0), 45.0);
    let fog = (sigma_s != 0.0).then_some(Fog { sigma_a: 0.0, sigma_s });
    Scene::new(camera, vec![floor, panel, ball], vec![], fog, DVec3::ZERO)
}

/// Centre of the `caustic` scene's glass ball (radius 1, refractive index 1.5).
pub const CAUSTIC_BALL_CENTER: DVec3 = DVec3::new(0.0, 1.5, 0.0);
/// Centre of the `caustic` scene's 0.8 × 0.8 area light, facing down.
pub const CAUSTIC_LIGHT_CENTER: DVec3 = DVec3::new(-3.0, 9.5, 0.0);

/// A glass ball (radius 1, index 1.5, centre [`CAUSTIC_BALL_CENTER`]) over a white diffuse floor,
/// lit by one small area light ([`CAUSTIC_LIGHT_CENTER`], 0.8 × 0.8, radiance 250) up and to
/// the side, so that the ball focuses the light into a bright spot inside its own shadow. A ball
/// lens of index n and radius R focuses parallel light at `f = nR/(2(n − 1)) = 1.5` from its
/// centre; the light's centre, `s = √73 ≈ 8.54` from the ball's, is imaged by the lens law
/// `1/s + 1/s′ = 1/f` (both distances from the centre, where a ball's principal planes lie) at
/// `s′ ≈ 1.82` beyond it. The floor point on the line from the light through the centre,
/// (0.56, 0, 0), lies 1.60 from the centre, so the floor catches the converging light 0.22 before
/// its focus: a small bright disc. Eye rays with shadow rays cannot find it (the shadow ray from
/// the floor to the light is blocked by the glass): the scene of the caustic pass.
///
/// # Errors
/// Never for the built-in numbers.
///
/// # Examples
/// ```
/// use hw3_render::render::catalogue::{CAUSTIC_BALL_CENTER, CAUSTIC_LIGHT_CENTER, caustic_footprint};
/// let scene = hw3_render::render::catalogue::glass_ball_caustic().unwrap();
/// assert_eq!(scene.objects().len(), 3);
/// // The lens law puts the light's image 1.82 beyond the centre; the floor's spot is at 1.60.
/// let (f, s) = (1.5 * 1.0 / (2.0 * 0.5), (CAUSTIC_LIGHT_CENTER - CAUSTIC_BALL_CENTER).length());
/// let image = 1.0 / (1.0 / f - 1.0 / s);
/// let floor = (caustic_footprint(1).0 - CAUSTIC_BALL_CENTER).length();
/// assert_eq!((format!("{s:.2}"), format!("{image:.2}"), format!("{floor:.2}")), ("8.54".into(), "1.82".into(), "1.60".into()));
/// ```
pub fn glass_ball_caustic() -> Result<Scene, InputError> {
    let floor = Object::quad(
        DVec3::new(-6.0, 0.0, 6.0),
        DVec3::new(12.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -12.0),
        Material::Diffuse { albedo: DVec3::splat(0.7) },
    );
    let half = 0.4;
    let light = Object::quad(
        CAUSTIC_LIGHT_CENTER - DVec3::new(half, 0.0, half),
        DVec3::new(2.0 * half, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 2.0 * half),
        Material::Emitter { radiance: DVec3::splat(250.0) },
    );
    let ball = Object::sphere(Sphere::new(CAUSTIC_BALL_CENTER, 1.0)?, Material::Glass { index: 1.5 });
    let camera = Camera::looking_at(DVec3::new(1.0, 3.0, 6.5), DVec3::new(0.3, 0.6, 0.0), 35.0);
    Scene::new(camera, vec![floor, light, ball], vec![], None, DVec3::ZERO)
}

/// The `caustic` scene's footprint: the disc of radius 0.3 about the spot's centre (0.5625, 0, 0), the
/// floor point on the line from the light's centre through the ball's centre, all of it in the
/// ball's umbra; with `n` floor points spread evenly over its area (a sunflower pattern). The
/// caustic pass's tests and accuracy table measure there.
///
/// # Examples
/// ```
/// let (center, radius, points) = hw3_render::render::catalogue::caustic_footprint(100);
/// assert!(points.iter().all(|p| (*p - center).length() <= radius && p.y == 0.0));
/// ```
#[must_use]
pub fn caustic_footprint(n: usize) -> (DVec3, f64, Vec<DVec3>) {
    let (center, radius) = (DVec3::new(0.5625, 0.0, 0.0), 0.3);
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let points = (0..n)
        .map(|i| {
            let r = radius * ((i as f64 + 0.5) / n as f64).sqrt();
            let angle = golden * i as f64;
            center + DVec3::new(r * angle.cos(), 0.0, r * angle.sin())
        })
        .collect();
    (center, radius, points)
}

/// Three spheres (diffuse, glossy, mirror) on a grey floor quad, lit only by the vendored Q4
/// `courtyard` map (`docs/data/q4`), which the camera also sees around them.
///
/// # Errors
/// [`RenderError::Environment`] if the map file cannot be read.
///
/// # Examples
/// ```
/// let scene = hw3_render::render::catalogue::probe_lit().unwrap();
/// assert!(scene.environment().is_some() && scene.point_lights().is_empty());
/// ```
pub fn probe_lit() -> Result<Scene, RenderError> {
    let probe = crate::envmap::BuiltinMap::Courtyard.probe().map_err(|e| RenderError::Environment(e.to_string()))?;
    let environment = Environment::from_probe(probe);
    let floor = Object::quad(
        DVec3::new(-4.0, 0.0, 2.0),
        DVec3::new(8.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -8.0),
        Material::Diffuse { albedo: DVec3::splat(0.5) },
    );
    let ball = |x: f64, material| -> Result<Object, InputError> {
        Ok(Object::sphere(Sphere::new(DVec3::new(x, 0.6, -2.0), 0.6)?, material))
    };
    let objects = vec![
        floor,
        ball(-1.4, Material::Diffuse { albedo: DVec3::new(0.8, 0.8, 0.8) })?,
        ball(
            0.0,
            Material::Glossy { diffuse: DVec3::new(0.6, 0.25, 0.1), specular: DVec3::splat(0.3), exponent: 60.0 },
        )?,
        ball(1.4, Material::Mirror { reflectance: DVec3::splat(0.9) })?,
    ];
    let camera = Camera::looking_at(DVec3::new(0.0, 1.5, 2.5), DVec3::new(0.0, 0.5, -2.0), 45.0);
    Ok(Scene::new(camera, objects, vec![], None, DVec3::ZERO)?.with_environment(environment))
}

/// The white-furnace scene: a closed unit sphere of grey albedo `albedo` with an isotropic point
/// light of intensity `intensity` at its centre. Every point of the wall receives the irradiance
/// `E = Φ/(A(1 − ρ)) = I/(1 − ρ)` (direct `I` at distance 1, plus the geometric series of uniform
/// interreflection), the exact reference of the photon-map tests and accuracy bench.
///
/// # Errors
/// [`InputError`] for an albedo outside `[0, 1]` or a negative or non-finite intensity.
///
/// # Examples
/// ```
/// let scene = hw3_render::render::catalogue::furnace_sphere(0.5, 1.0).unwrap();
/// assert_eq!(scene.objects().len(), 1);
/// assert!(hw3_render::render::catalogue::furnace_sphere(1.5, 1.0).is_err());
/// ```
pub fn furnace_sphere(albedo: f64, intensity: f64) -> Result<Scene, InputError> {
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.5), DVec3::ZERO, 40.0);
    let shell = Object::sphere(Sphere::new(DVec3::ZERO, 1.0)?, Material::Diffuse { albedo: DVec3::splat(albedo) });
    let lamp = PointLight { position: DVec3::ZERO, intensity: DVec3::splat(intensity) };
    Scene::new(camera, vec![shell], vec![lamp], None, DVec3::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_catalogued_name_builds_and_unknown_names_list_them() {
        for (name, _) in CATALOGUE {
            assert!(by_name(name).is_ok(), "{name}");
        }
        let Err(RenderError::UnknownScene { known, .. }) = by_name("fgo") else {
            panic!("an unknown name is an error")
        };
        assert!(known.starts_with("clutter, fog"));
    }

    #[test]
    fn bad_parameters_are_typed_errors() {
        assert!(fog_street(-0.1).is_err());
        assert!(fog_street(f64::NAN).is_err());
        assert!(moving_ball(f64::INFINITY).is_err());
        assert!(moving_ball_with_shutter(1.0, (1.0, 0.0)).is_err());
    }
}
