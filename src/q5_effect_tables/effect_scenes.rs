//! The scenes of the highlight, direct-shading, mirror-image and caustic experiments, with the
//! probe rays each measurement averages over.
//!
//! All of them are *open* scenes (black background, no enclosing walls), so that the only light
//! transport present is the one the effect needs and the methods differ only in the effect:
//! - [`lit_floor`]: a 4 × 4 floor under a small area light 4 units up, optionally with a glass
//!   ball over the floor's centre (the caustic) and with a glossy or diffuse floor (the
//!   highlight). A floor alone has no `LDD` path at all, so every radiance measured on it is
//!   direct light or a caustic.
//! - [`mirror_room`]: a red diffuse panel lit from the side, seen in a mirror that no light
//!   reaches directly (the light is one-sided and the mirror is behind it), so the mirror shows
//!   `LDS+E` and no `LS…` path.

use crate::geometry::{InputError, Ray, Sphere};
use crate::render::catalogue::{CORNELL_RED, CORNELL_WHITE};
use crate::render::{
    camera::Camera,
    scene::{Material, Object, Scene},
};
use glam::DVec3;

/// Radiance of the small lights of the open scenes (brighter than the box's: one light, no walls).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::OPEN_LIGHT_RADIANCE;
/// use hw3::render::catalogue::CORNELL_LIGHT_RADIANCE;
/// assert!(OPEN_LIGHT_RADIANCE > CORNELL_LIGHT_RADIANCE);
/// ```
pub const OPEN_LIGHT_RADIANCE: f64 = 50.0;
/// Side of the square light over the floor.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::{FLOOR_LIGHT_SIZE, WHITE_FLOOR, lit_floor};
/// let scene = lit_floor(WHITE_FLOOR, false).unwrap();
/// let light = scene.area_lights().next().unwrap();
/// assert_eq!((light.edge_u.length(), light.edge_v.length()), (FLOOR_LIGHT_SIZE, FLOOR_LIGHT_SIZE));
/// ```
pub const FLOOR_LIGHT_SIZE: f64 = 0.5;
/// Height of that light above the floor.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::{FLOOR_LIGHT_HEIGHT, WHITE_FLOOR, lit_floor};
/// let light = lit_floor(WHITE_FLOOR, false).unwrap().area_lights().next().unwrap();
/// assert_eq!(light.corner.y, FLOOR_LIGHT_HEIGHT);
/// ```
pub const FLOOR_LIGHT_HEIGHT: f64 = 4.0;
/// Radius of the glass ball of the caustic scene (refractive index [`GLASS_INDEX`]).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::{BALL_HEIGHT, BALL_RADIUS};
/// // The ball floats: its lowest point is above the floor.
/// assert!(BALL_HEIGHT - BALL_RADIUS > 0.2);
/// ```
pub const BALL_RADIUS: f64 = 0.5;
/// Refractive index of the ball.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::{GLASS_INDEX, WHITE_FLOOR, lit_floor};
/// use hw3::render::scene::Material;
/// let scene = lit_floor(WHITE_FLOOR, true).unwrap();
/// assert_eq!(scene.objects()[2].material, Material::Glass { index: GLASS_INDEX });
/// ```
pub const GLASS_INDEX: f64 = 1.5;
/// Height of the ball's centre: the paraxial focal length of a ball lens, `nR/(2(n − 1))` from
/// its centre, puts the focus of parallel light on the floor (the light, 3.25 above the centre, is
/// imaged 0.975 below it, 0.225 below the floor).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::{BALL_HEIGHT, FLOOR_LIGHT_HEIGHT};
/// // The paraxial focus, 0.75 above the floor, and the light's image 0.225 below it.
/// assert!((BALL_HEIGHT - 0.75).abs() < 1e-12);
/// let f = BALL_HEIGHT;
/// let s = FLOOR_LIGHT_HEIGHT - BALL_HEIGHT;
/// assert!((1.0 / (1.0 / f - 1.0 / s) - BALL_HEIGHT - 0.225).abs() < 1e-12);
/// ```
pub const BALL_HEIGHT: f64 = GLASS_INDEX * BALL_RADIUS / (2.0 * (GLASS_INDEX - 1.0));
/// The glossy floor of the highlight experiment: modified Phong with this diffuse and specular
/// reflectance and exponent.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::{GLOSSY_FLOOR, lit_floor};
/// // A valid material (kd + ks ≤ 1): the scene builds.
/// assert!(lit_floor(GLOSSY_FLOOR, false).is_ok());
/// ```
pub const GLOSSY_FLOOR: Material =
    Material::Glossy { diffuse: DVec3::splat(0.3), specular: DVec3::splat(0.5), exponent: 30.0 };
/// The eye of the highlight probes: it sees the light's mirror image at [`HIGHLIGHT_POINT`].
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::{FLOOR_LIGHT_HEIGHT, HIGHLIGHT_EYE, HIGHLIGHT_POINT};
/// // Mirrored in the floor, the direction to the eye is the direction to the light's centre.
/// let to_eye = HIGHLIGHT_EYE - HIGHLIGHT_POINT;
/// let to_light = glam::DVec3::Y * FLOOR_LIGHT_HEIGHT - HIGHLIGHT_POINT;
/// assert_eq!(glam::DVec3::new(-to_eye.x, to_eye.y, to_eye.z), to_light);
/// ```
pub const HIGHLIGHT_EYE: DVec3 = DVec3::new(-3.0, 4.0, 0.0);
/// The floor point whose mirror direction towards [`HIGHLIGHT_EYE`] points at the light's centre.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::HIGHLIGHT_POINT;
/// // On the floor, inside its 4 × 4 square.
/// assert!(HIGHLIGHT_POINT.y == 0.0 && HIGHLIGHT_POINT.x.abs() < 2.0);
/// ```
pub const HIGHLIGHT_POINT: DVec3 = DVec3::new(-1.5, 0.0, 0.0);

/// The camera of the highlight's pictures: at [`HIGHLIGHT_EYE`], looking past
/// [`HIGHLIGHT_POINT`] towards the floor's centre, so that the highlight sits left of the middle.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::{HIGHLIGHT_EYE, highlight_camera};
/// assert_eq!(highlight_camera().eye, HIGHLIGHT_EYE);
/// ```
#[must_use]
pub fn highlight_camera() -> Camera {
    Camera::looking_at(HIGHLIGHT_EYE, HIGHLIGHT_POINT + DVec3::X * 0.6, 45.0)
}

/// A 4 × 4 floor (`y = 0`, `x, z ∈ [−2, 2]`) of material `floor` under a
/// [`FLOOR_LIGHT_SIZE`]² light facing down at height [`FLOOR_LIGHT_HEIGHT`] over the origin,
/// with a glass ball ([`BALL_RADIUS`], [`GLASS_INDEX`]) centred [`BALL_HEIGHT`] above the origin
/// when `glass_ball` is set.
///
/// # Errors
/// [`InputError`] for an invalid `floor` material (reflectances outside `[0, 1]`, `kd + ks > 1`).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::lit_floor;
/// use hw3::render::scene::Material;
/// let white = Material::Diffuse { albedo: glam::DVec3::splat(0.5) };
/// assert_eq!(lit_floor(white, true).unwrap().objects().len(), 3);
/// assert!(lit_floor(Material::Diffuse { albedo: glam::DVec3::splat(2.0) }, false).is_err());
/// ```
pub fn lit_floor(floor: Material, glass_ball: bool) -> Result<Scene, InputError> {
    let half = FLOOR_LIGHT_SIZE / 2.0;
    let mut objects = vec![
        Object::quad(DVec3::new(-2.0, 0.0, -2.0), DVec3::Z * 4.0, DVec3::X * 4.0, floor),
        Object::quad(
            DVec3::new(-half, FLOOR_LIGHT_HEIGHT, -half),
            DVec3::X * FLOOR_LIGHT_SIZE,
            DVec3::Z * FLOOR_LIGHT_SIZE,
            Material::Emitter { radiance: DVec3::splat(OPEN_LIGHT_RADIANCE) },
        ),
    ];
    if glass_ball {
        let ball = Sphere::new(DVec3::Y * BALL_HEIGHT, BALL_RADIUS)?;
        objects.push(Object::sphere(ball, Material::Glass { index: GLASS_INDEX }));
    }
    let camera = Camera::looking_at(DVec3::new(0.0, 2.0, 4.5), DVec3::new(0.0, 0.4, 0.0), 40.0);
    Scene::new(camera, objects, vec![], None, DVec3::ZERO)
}

/// The white diffuse floor of the direct-shading and caustic experiments.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::WHITE_FLOOR;
/// use hw3::render::catalogue::CORNELL_WHITE;
/// use hw3::render::scene::Material;
/// assert_eq!(WHITE_FLOOR, Material::Diffuse { albedo: CORNELL_WHITE });
/// ```
pub const WHITE_FLOOR: Material = Material::Diffuse { albedo: CORNELL_WHITE };

/// A red diffuse panel (`x = −1`, facing `+x`, `y ∈ [0, 2]`, `z ∈ [−1, 1]`), a 0.6 × 0.4 light
/// at `x = 0` above the eye line facing `−x` (towards the panel), and a mirror (`x = 1`, facing
/// `−x`, reflectance 0.9) behind the light's back: the mirror receives no direct light, so what
/// it shows is the lit panel, `LDS+E`.
///
/// # Errors
/// Never for the built-in numbers.
///
/// # Examples
/// ```
/// let room = hw3::q5_effect_tables::effect_scenes::mirror_room().unwrap();
/// assert_eq!(room.objects().len(), 3);
/// ```
pub fn mirror_room() -> Result<Scene, InputError> {
    let objects = vec![
        Object::quad(
            DVec3::new(-1.0, 0.0, -1.0),
            DVec3::Y * 2.0,
            DVec3::Z * 2.0,
            Material::Diffuse { albedo: CORNELL_RED },
        ),
        Object::quad(
            DVec3::new(0.0, 1.6, -0.3),
            DVec3::Z * 0.6,
            DVec3::Y * 0.4,
            Material::Emitter { radiance: DVec3::splat(OPEN_LIGHT_RADIANCE) },
        ),
        Object::quad(
            DVec3::new(1.0, 0.5, -0.5),
            DVec3::Z,
            DVec3::Y,
            Material::Mirror { reflectance: DVec3::splat(0.9) },
        ),
    ];
    // Near the probes' eye, so that the mirror fills the view and shows the panel.
    let camera = Camera::looking_at(DVec3::new(0.3, 1.1, 0.25), DVec3::new(1.0, 1.0, 0.0), 60.0);
    Scene::new(camera, objects, vec![], None, DVec3::ZERO)
}

/// Radiance of the thin frame [`mirror_room_framed`] draws around the mirror: a light grey on the
/// display, dim beside the panel's light (its power is under 1 % of the light's).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::{MIRROR_FRAME_RADIANCE, OPEN_LIGHT_RADIANCE};
/// assert!(MIRROR_FRAME_RADIANCE < OPEN_LIGHT_RADIANCE / 50.0);
/// ```
pub const MIRROR_FRAME_RADIANCE: f64 = 0.6;

/// The mirror room as the pictures show it ([`mirror_room`] is the one measured): the same panel,
/// light and mirror, plus a thin frame that glows dimly around the mirror (four emitting strips
/// 0.04 wide in the mirror's plane, facing the panel, radiance [`MIRROR_FRAME_RADIANCE`]), seen
/// from behind the light's plane so that the whole mirror is in view. Without the frame the mirror
/// is black wherever it reflects nothing (the background is black), so a picture shows a red
/// shape on black and no mirror; the frame marks where the mirror is, in every method's picture,
/// including those that see the mirror black. Its light on the panel is under 1 % of the lamp's.
///
/// # Errors
/// Never for the built-in numbers.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::{mirror_room, mirror_room_framed};
/// let (measured, pictured) = (mirror_room().unwrap(), mirror_room_framed().unwrap());
/// // The measured scene's three objects come first, then the frame's four strips.
/// assert_eq!(pictured.objects().len(), measured.objects().len() + 4);
/// assert_eq!(pictured.objects()[..3], measured.objects()[..]);
/// ```
pub fn mirror_room_framed() -> Result<Scene, InputError> {
    let room = mirror_room()?;
    let (width, glow) = (0.04, Material::Emitter { radiance: DVec3::splat(MIRROR_FRAME_RADIANCE) });
    // The mirror spans y ∈ [0.5, 1.5], z ∈ [−0.5, 0.5] at x = 1; each strip's edges (z, then y)
    // make it face −x, toward the panel, as the mirror does.
    let strip =
        |corner: DVec3, along_z: f64, along_y: f64| Object::quad(corner, DVec3::Z * along_z, DVec3::Y * along_y, glow);
    let mut objects = room.objects().to_vec();
    objects.extend([
        strip(DVec3::new(1.0, 1.5, -0.5 - width), 1.0 + 2.0 * width, width),
        strip(DVec3::new(1.0, 0.5 - width, -0.5 - width), 1.0 + 2.0 * width, width),
        strip(DVec3::new(1.0, 0.5, -0.5 - width), width, 1.0),
        strip(DVec3::new(1.0, 0.5, 0.5), width, 1.0),
    ]);
    let camera = Camera::looking_at(DVec3::new(-0.3, 1.15, 0.35), DVec3::new(1.0, 1.0, 0.0), 60.0);
    Scene::new(camera, objects, vec![], None, DVec3::ZERO)
}

/// The eye of the mirror probes, between the light's plane and the mirror.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_scenes::MIRROR_EYE;
/// // Between the light's plane (x = 0) and the mirror (x = 1).
/// assert!(MIRROR_EYE.x > 0.0 && MIRROR_EYE.x < 1.0);
/// ```
pub const MIRROR_EYE: DVec3 = DVec3::new(0.4, 1.0, 0.0);

/// A 4 × 4 grid of offsets `spacing` apart, centred on 0, in the plane spanned by `u` and `v`.
fn grid(u: DVec3, v: DVec3, spacing: f64) -> impl Iterator<Item = DVec3> {
    (0..16).map(move |k| (u * ((k % 4) as f64 - 1.5) + v * ((k / 4) as f64 - 1.5)) * spacing)
}

/// Rays from `eye` through 16 points around `target` (offsets in the plane of `u`, `v`).
fn rays_from(eye: DVec3, target: DVec3, u: DVec3, v: DVec3, spacing: f64) -> Vec<Ray<f64>> {
    grid(u, v, spacing).map(|offset| Ray { origin: eye, dir: (target + offset - eye).normalize() }).collect()
}

/// Rays straight down onto 16 floor points around `centre`, `spacing` apart.
pub(super) fn floor_probes(centre: DVec3, spacing: f64) -> Vec<Ray<f64>> {
    grid(DVec3::X, DVec3::Z, spacing).map(|p| Ray { origin: centre + p + DVec3::Y * 0.05, dir: DVec3::NEG_Y }).collect()
}

/// The highlight probes: rays from [`HIGHLIGHT_EYE`] to 16 floor points within ±0.075 of
/// [`HIGHLIGHT_POINT`], all inside the specular peak.
pub(super) fn highlight_probes() -> Vec<Ray<f64>> {
    rays_from(HIGHLIGHT_EYE, HIGHLIGHT_POINT, DVec3::X, DVec3::Z, 0.05)
}

/// The mirror probes: rays from [`MIRROR_EYE`] to 16 points within ±0.15 of the mirror's centre.
pub(super) fn mirror_probes() -> Vec<Ray<f64>> {
    rays_from(MIRROR_EYE, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::Z, 0.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The probes hit what the experiments claim: the highlight probes the glossy floor near the
    /// mirror point of the light's centre, the mirror probes the mirror and then the red panel,
    /// the caustic probes the floor inside the ball's shadow (no direct light).
    #[test]
    fn probes_hit_the_surfaces_the_measurements_need() {
        let floor = lit_floor(GLOSSY_FLOOR, false).unwrap();
        for ray in highlight_probes() {
            let hit = floor.closest_hit(&ray, 0.0, f64::INFINITY).unwrap();
            assert_eq!(hit.object, 0);
            let mirrored = crate::geometry::sphere::reflect::<f64>(ray.dir, DVec3::Y);
            let to_light = (DVec3::Y * FLOOR_LIGHT_HEIGHT - hit.point).normalize();
            assert!(mirrored.dot(to_light) > 0.995, "{}", mirrored.dot(to_light));
        }
        let room = mirror_room().unwrap();
        for ray in mirror_probes() {
            let hit = room.closest_hit(&ray, 0.0, f64::INFINITY).unwrap();
            assert_eq!(hit.object, 2, "the mirror");
            let next = crate::render::bsdf::reflected_ray(&ray, &hit);
            assert_eq!(room.closest_hit(&next, 0.0, f64::INFINITY).unwrap().object, 0, "then the panel");
        }
        let ball = lit_floor(WHITE_FLOOR, true).unwrap();
        for ray in floor_probes(DVec3::ZERO, 0.01) {
            let hit = ball.closest_hit(&ray, 0.0, f64::INFINITY).unwrap();
            let up = Ray { origin: hit.point + DVec3::Y * 1e-9, dir: DVec3::Y };
            assert!(hit.object == 0 && ball.occluded(&up, 0.0, FLOOR_LIGHT_HEIGHT), "in the ball's shadow");
        }
    }
}
