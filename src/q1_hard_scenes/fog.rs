//! Q1(b) fog: contrast falls by Beer–Lambert along the path, and a lamp beside the path adds
//! airlight that the renderer's single-scattering quadrature reproduces (Sun et al. 2005).

use crate::geometry::{InputError, Ray};
use crate::plot::markdown_table;
use crate::render::integrator::{IN_SCATTER_STEPS, Integrator, Tracer};
use crate::render::medium::airlight_closed_form;
use crate::render::sampling::Sampler;
use crate::render::{
    analysis::analyze,
    passes::{Pass, Passes},
};
use crate::render::{
    camera::Camera,
    scene::{Fog, Material, Object, PointLight, Scene},
};
use glam::DVec3;

/// Beer–Lambert transmittance `e^(−σ_t ℓ)`: the share of a target's light that crosses `length`
/// units of a medium of extinction coefficient `sigma_t` (the contrast of a target against the
/// fog falls by the same factor).
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::transmittance;
/// // The fog street (σ_t = 0.08) over 10 units: 45 % gets through.
/// assert!((transmittance(0.08, 10.0) - (-0.8f64).exp()).abs() < 1e-15);
/// assert_eq!(transmittance(0.08, 0.0), 1.0);
/// ```
#[must_use]
pub fn transmittance(sigma_t: f64, length: f64) -> f64 {
    (-sigma_t * length).exp()
}

/// Koschmieder's visual range `ln(50)/σ_t`: the distance at which a target's contrast falls to
/// 2 % (`e^(−σ_t d) = 1/50`), the eye's threshold.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{transmittance, visual_range};
/// let d = visual_range(0.08);
/// assert!((d - 48.9).abs() < 0.01);
/// assert!((transmittance(0.08, d) - 0.02).abs() < 1e-15);
/// ```
#[must_use]
pub fn visual_range(sigma_t: f64) -> f64 {
    50f64.ln() / sigma_t
}

/// Extinction coefficients of the fog experiment.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{FOG_SIGMAS, visual_range};
/// // Visual ranges of 78, 39 and 20 units.
/// let ranges = FOG_SIGMAS.map(visual_range);
/// assert!((ranges[0] - 78.24).abs() < 0.01 && (ranges[2] - 19.56).abs() < 0.01);
/// ```
pub const FOG_SIGMAS: [f64; 3] = [0.05, 0.1, 0.2];
/// Target distances (along the optical axis) of the fog experiment.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{FOG_DISTANCES, FOG_SIGMAS, transmittance};
/// // The farthest target in the densest fog keeps well under 1 % of its light.
/// assert!(transmittance(FOG_SIGMAS[2], FOG_DISTANCES[5]) < 1e-3);
/// ```
pub const FOG_DISTANCES: [f64; 6] = [1.0, 2.0, 5.0, 10.0, 20.0, 40.0];
/// Relative differences below this are rounding (they vary in the last bit between platforms'
/// `exp`): the table prints `< 1e-13`.
pub(super) const ROUNDING_LEVEL: f64 = 1e-13;
/// Relative error of the traced airlight at the renderer's [`IN_SCATTER_STEPS`] steps, and at
/// 4096 steps, against the closed form: the bounds [`airlight_rows`] meets (tested).
#[cfg(test)]
const AIRLIGHT_TOLERANCES: (f64, f64) = (1e-2, 1e-6);
/// Direction of the probe ray: off axis, so the path length is `d / cos θ`, not `d`.
pub(super) fn fog_probe_direction() -> DVec3 {
    DVec3::new(0.1, 0.05, -1.0).normalize()
}

/// The fog measurement's path length per unit of target distance, `ℓ/d = 1/cos θ`: the probe ray
/// runs slightly off the axis (`(0.1, 0.05, −1)`), so its path to a target at distance `d` is
/// `ℓ = 1.0062 d` and the measured dimming is `e^(−σ_t ℓ)`, not `e^(−σ_t d)`.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::fog_path_factor;
/// assert!((fog_path_factor() - 1.0125f64.sqrt()).abs() < 1e-15);
/// ```
#[must_use]
pub fn fog_path_factor() -> f64 {
    1.0 / -fog_probe_direction().z
}

/// Step counts of the airlight convergence table ([`airlight_convergence`]): each step is one
/// shadow ray to the lamp per view ray.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::AIRLIGHT_STEPS;
/// // Doubling counts, through the renderer's 32.
/// assert!(AIRLIGHT_STEPS.windows(2).all(|w| w[1] == 2 * w[0]));
/// assert!(AIRLIGHT_STEPS.contains(&hw3::render::integrator::IN_SCATTER_STEPS));
/// ```
pub const AIRLIGHT_STEPS: [usize; 9] = [1, 2, 4, 8, 16, 32, 64, 128, 256];

/// The lamps of the convergence table, `(β, D, γ in degrees)` as in [`airlight_rows`]: a lamp far
/// from the ray in dense fog, a lamp 2 units off at 30° in the fog street's density, and a lamp
/// close beside the ray in thin fog.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::AIRLIGHT_CONVERGENCE_LAMPS;
/// assert_eq!(AIRLIGHT_CONVERGENCE_LAMPS.len(), 3);
/// ```
pub const AIRLIGHT_CONVERGENCE_LAMPS: [(f64, f64, f64); 3] = [(1.0, 5.0, 90.0), (0.08, 2.0, 30.0), (0.05, 1.0, 5.0)];

/// The airlight's relative error against Sun et al.'s closed form for each step count of
/// [`AIRLIGHT_STEPS`] and each lamp of [`AIRLIGHT_CONVERGENCE_LAMPS`]: what computing the glow
/// costs (one shadow ray per step) against what it gets right. A view ray of length 20, as in
/// [`airlight_rows`].
///
/// # Errors
/// [`InputError`] never for the built-in cases.
///
/// # Examples
/// ```
/// let rows = hw3::q1_hard_scenes::airlight_convergence().unwrap();
/// // Far from the lamp the midpoint rule's error falls about fourfold per doubling of the steps.
/// let (at_16, at_32) = (rows[4].1[0], rows[5].1[0]);
/// assert!(at_16 / at_32 > 3.5 && at_16 / at_32 < 4.5);
/// ```
pub fn airlight_convergence() -> Result<Vec<(usize, [f64; 3])>, InputError> {
    let exact = AIRLIGHT_CONVERGENCE_LAMPS
        .iter()
        .map(|&(beta, d, gamma)| airlight_closed_form(beta, 1.0, d, gamma.to_radians(), 20.0))
        .collect::<Result<Vec<_>, _>>()?;
    AIRLIGHT_STEPS
        .iter()
        .map(|&steps| {
            let mut errors = [0.0; 3];
            for (k, &(beta, d, gamma)) in AIRLIGHT_CONVERGENCE_LAMPS.iter().enumerate() {
                let traced = airlight_traced(beta, d, gamma.to_radians(), 20.0, steps)?;
                errors[k] = (traced / exact[k] - 1.0).abs();
            }
            Ok((steps, errors))
        })
        .collect()
}

pub(super) fn airlight_convergence_table(rows: &[(usize, [f64; 3])]) -> String {
    let lamp = |(beta, d, gamma): (f64, f64, f64)| format!("rel. err, β = {beta}, D = {d}, γ = {gamma}°");
    let [a, b, c] = AIRLIGHT_CONVERGENCE_LAMPS.map(lamp);
    let header = ["steps (shadow rays per lamp per view ray)", a.as_str(), b.as_str(), c.as_str()];
    markdown_table(
        &header,
        rows.iter().map(|(steps, errors)| {
            [
                steps.to_string(),
                format!("{:.1e}", errors[0]),
                format!("{:.1e}", errors[1]),
                format!("{:.1e}", errors[2]),
            ]
        }),
    )
}

/// One measurement of the fog experiment.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{FogRow, fog_row};
/// let row: FogRow = fog_row(0.05, 2.0).unwrap();
/// // Thin fog over a short path: the target keeps most of its light and outshines the airlight.
/// assert!(row.transmittance > 0.9 && row.apparent_contrast > 1.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FogRow {
    /// `σ_t` (all scattering).
    pub sigma_t: f64,
    /// Target distance along the axis.
    pub distance: f64,
    /// Measured transmittance: (radiance with the target lit − radiance with it dark) / emitted.
    pub transmittance: f64,
    /// Beer–Lambert `e^(−σ_t ℓ)`, `ℓ` = path length along the probe ray.
    pub law: f64,
    /// The airlight added by a lamp beside the path (radiance with the target dark).
    pub airlight: f64,
    /// Apparent (Weber) contrast of the lit target against the airlight, `(L_lit − L_dark)/L_dark`.
    pub apparent_contrast: f64,
}

/// The fog measurement's scene: an emitter wall of radiance `target_radiance` at `distance`, a
/// lamp beside the path, and fog `σ_s = sigma_t`.
fn fog_target_scene(sigma_t: f64, distance: f64, target_radiance: f64) -> Result<Scene, InputError> {
    let lamp = PointLight { position: DVec3::new(2.0, 1.5, -distance / 2.0), intensity: DVec3::splat(5.0) };
    let target = Material::Emitter { radiance: DVec3::splat(target_radiance) };
    wall_in_fog(distance, target, lamp, sigma_t)
}

/// Measures one fog row by tracing the probe ray through the lit and the dark target.
///
/// # Errors
/// [`InputError`] for an invalid `sigma_t` or `distance`.
///
/// # Examples
/// ```
/// let row = hw3::q1_hard_scenes::fog_row(0.1, 5.0).unwrap();
/// assert!((row.transmittance / row.law - 1.0).abs() < 1e-12);
/// assert!(row.airlight > 0.0 && row.apparent_contrast > 1.0);
/// ```
pub fn fog_row(sigma_t: f64, distance: f64) -> Result<FogRow, InputError> {
    let probe = Ray { origin: DVec3::ZERO, dir: fog_probe_direction() };
    let radiance = |target: f64, in_scattering: bool| -> Result<f64, InputError> {
        let scene = fog_target_scene(sigma_t, distance, target)?;
        let plan = analyze(&scene).plan.with(Pass::InScattering, in_scattering);
        let tracer = Tracer::new(&scene, plan);
        let whitted = Integrator::Whitted { max_depth: 0 };
        Ok(tracer.radiance(whitted, &probe, 0.0, &mut Sampler::new(0, 0, 0)).x)
    };
    // The lamp's airlight is common to the lit and the dark target and cancels in the difference;
    // the lit target's own glow (an area light in fog) is left out: the contrast law is about
    // what the medium does to a target's light on its way to the eye, not about the target
    // lighting the fog.
    let transmittance = radiance(1.0, false)? - radiance(0.0, false)?;
    let dark = radiance(0.0, true)?;
    let path_length = distance / -probe.dir.z;
    Ok(FogRow {
        sigma_t,
        distance,
        transmittance,
        law: self::transmittance(sigma_t, path_length),
        airlight: dark,
        apparent_contrast: transmittance / dark,
    })
}

/// The airlight comparison of the fog chapter: `(β, D, γ°, closed form, 32 steps, 4096 steps)`.
///
/// # Errors
/// [`InputError`] never for the built-in cases.
///
/// # Examples
/// ```
/// let rows = hw3::q1_hard_scenes::airlight_rows().unwrap();
/// assert_eq!(rows.len(), 12);
/// for [_, _, _, closed, coarse, fine] in rows {
///     assert!((coarse / closed - 1.0).abs() < 1e-2 && (fine / closed - 1.0).abs() < 1e-6);
/// }
/// ```
pub fn airlight_rows() -> Result<Vec<[f64; 6]>, InputError> {
    let mut rows = Vec::new();
    for beta in [0.05, 0.3, 1.0] {
        for (d, gamma_degrees) in [(1.0, 5.0), (1.0, 90.0), (5.0, 5.0), (5.0, 90.0)] {
            let gamma = f64::to_radians(gamma_degrees);
            rows.push([
                beta,
                d,
                gamma_degrees,
                airlight_closed_form(beta, 1.0, d, gamma, 20.0)?,
                airlight_traced(beta, d, gamma, 20.0, IN_SCATTER_STEPS)?,
                airlight_traced(beta, d, gamma, 20.0, 4096)?,
            ]);
        }
    }
    Ok(rows)
}

/// The same airlight as [`airlight_closed_form`], measured by the renderer: a camera ray along
/// `−z` ends on a black wall at distance `length`, a unit-intensity point light sits at
/// distance `light_distance` and angle `gamma` from the ray, the fog has `σ_s = beta`, and the
/// in-scattering integral uses `steps` quadrature steps.
///
/// # Errors
/// [`InputError`] for a non-finite or negative `beta`, or geometry that makes an invalid scene.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::airlight_traced;
/// use hw3::render::medium::airlight_closed_form;
/// let traced = airlight_traced(0.3, 1.0, 0.5, 20.0, 64).unwrap();
/// let exact = airlight_closed_form(0.3, 1.0, 1.0, 0.5, 20.0).unwrap();
/// assert!((traced / exact - 1.0).abs() < 1e-3);
/// ```
pub fn airlight_traced(
    beta: f64,
    light_distance: f64,
    gamma: f64,
    length: f64,
    steps: usize,
) -> Result<f64, InputError> {
    let light = PointLight {
        position: DVec3::new(light_distance * gamma.sin(), 0.0, -light_distance * gamma.cos()),
        intensity: DVec3::ONE,
    };
    let black = Material::Diffuse { albedo: DVec3::ZERO };
    let scene = wall_in_fog(length, black, light, beta)?;
    let tracer = Tracer::new(&scene, Passes::all()).with_in_scatter_steps(steps);
    let ray = Ray { origin: DVec3::ZERO, dir: DVec3::NEG_Z };
    let radiance = tracer.radiance(Integrator::Whitted { max_depth: 0 }, &ray, 0.0, &mut Sampler::new(0, 0, 0));
    Ok(radiance.x)
}

/// A camera at the origin looking along `−z` at a 2000×2000 wall of `wall` material facing it at
/// distance `distance`, one `lamp`, and a non-absorbing fog of scattering coefficient `sigma_s`:
/// the set-up of the fog measurements (transmittance and airlight).
///
/// # Errors
/// [`InputError`] for an invalid distance, lamp, material or density.
fn wall_in_fog(distance: f64, wall: Material, lamp: PointLight, sigma_s: f64) -> Result<Scene, InputError> {
    let wall =
        Object::quad(DVec3::new(-1e3, -1e3, -distance), DVec3::new(2e3, 0.0, 0.0), DVec3::new(0.0, 2e3, 0.0), wall);
    let camera = Camera::looking_at(DVec3::ZERO, DVec3::NEG_Z, 40.0);
    let fog = Fog { sigma_a: 0.0, sigma_s };
    Scene::new(camera, vec![wall], vec![lamp], Some(fog), DVec3::ZERO)
}

pub(super) fn fog_table(rows: &[FogRow]) -> String {
    let header = ["σ_t", "d", "T measured", "e^(−σ_t ℓ)", "rel. diff", "airlight", "apparent contrast"];
    markdown_table(
        &header,
        rows.iter().map(|r| {
            [
                r.sigma_t.to_string(),
                r.distance.to_string(),
                format!("{:.6e}", r.transmittance),
                format!("{:.6e}", r.law),
                // Rounding-level differences vary in the last bit between platforms' `exp`.
                if (r.transmittance / r.law - 1.0).abs() < ROUNDING_LEVEL {
                    format!("< {ROUNDING_LEVEL:e}")
                } else {
                    format!("{:.1e}", (r.transmittance / r.law - 1.0).abs())
                },
                format!("{:.4e}", r.airlight),
                format!("{:.4e}", r.apparent_contrast),
            ]
        }),
    )
}

pub(super) fn airlight_table(rows: &[[f64; 6]]) -> String {
    let header =
        ["β", "D", "γ (°)", "closed form", "renderer, 32 steps", "rel. err", "renderer, 4096 steps", "rel. err"];
    markdown_table(
        &header,
        rows.iter().map(|[beta, d, gamma, closed, coarse, fine]| {
            [
                beta.to_string(),
                d.to_string(),
                gamma.to_string(),
                format!("{closed:.6e}"),
                format!("{coarse:.6e}"),
                format!("{:.1e}", (coarse / closed - 1.0).abs()),
                format!("{fine:.6e}"),
                format!("{:.1e}", (fine / closed - 1.0).abs()),
            ]
        }),
    )
}

/// Every row of the fog experiment: [`FOG_SIGMAS`] × [`FOG_DISTANCES`], σ_t outer.
pub(super) fn fog_rows() -> Result<Vec<FogRow>, InputError> {
    FOG_SIGMAS.iter().flat_map(|&s| FOG_DISTANCES.iter().map(move |&d| fog_row(s, d))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::q1_hard_scenes::metric::snapshot;
    use crate::render::catalogue;
    use crate::render::{Settings, render};

    /// The laws against the numbers they have always given (the checker's seeds 0 and 1, as
    /// worked by `tests/answers/fixtures/keys.py`), and against the traced fog.
    #[test]
    fn transmittance_and_visual_range_are_the_numbers_they_were() {
        assert!((transmittance(0.08, 10.0) - 0.449_328_964_117_221_56).abs() < 1e-15);
        assert!((transmittance(0.2, 2.0) - 0.670_320_046_035_639_3).abs() < 1e-15);
        assert!((visual_range(0.08) - 48.900_287_567_851_83).abs() < 1e-12);
        assert!((visual_range(0.2) - 19.560_115_027_140_73).abs() < 1e-12);
        let row = fog_row(0.1, 5.0).unwrap();
        let path = 5.0 / -fog_probe_direction().z;
        assert!((row.transmittance / transmittance(0.1, path) - 1.0).abs() < 1e-12, "{row:?}");
    }

    #[test]
    fn fog_transmittance_is_beer_lambert_and_the_airlight_is_sun_et_al() {
        let rows = fog_rows().unwrap();
        for r in &rows {
            assert!((r.transmittance / r.law - 1.0).abs() < 1e-12, "{r:?}");
            assert!(r.airlight > 0.0);
        }
        let airlight = airlight_rows().unwrap();
        for [.., closed, coarse, fine] in &airlight {
            assert!((coarse / closed - 1.0).abs() < AIRLIGHT_TOLERANCES.0);
            assert!((fine / closed - 1.0).abs() < AIRLIGHT_TOLERANCES.1);
        }
        snapshot("q1_fog_metrics", &fog_table(&rows));
        snapshot("q1_airlight_metrics", &airlight_table(&airlight));
        // The glow's quadrature: error falls with the steps, fourfold per doubling far from the lamp.
        let steps = airlight_convergence().unwrap();
        for pair in steps.windows(2).skip(3) {
            let ratio = pair[0].1[0] / pair[1].1[0];
            assert!((3.5..4.5).contains(&ratio), "{ratio} at {} steps", pair[1].0);
        }
        snapshot("q1_airlight_steps", &airlight_convergence_table(&steps));
    }

    #[test]
    fn zero_density_fog_renders_exactly_like_no_fog() {
        let clear = catalogue::fog_street(0.0).unwrap();
        let zero = Scene::new(
            *clear.camera(),
            clear.objects().to_vec(),
            clear.point_lights().to_vec(),
            Some(Fog { sigma_a: 0.0, sigma_s: 0.0 }),
            clear.background(),
        )
        .unwrap();
        let settings = Settings::whitted(24, 18, 1, crate::render::passes::Passes::all());
        assert_eq!(render(&zero, &settings, &|_| {}).unwrap(), render(&clear, &settings, &|_| {}).unwrap());
    }

    #[test]
    fn extreme_fog_hides_everything_but_stays_finite() {
        let scene = catalogue::fog_street(1e6).unwrap();
        let image = render(&scene, &Settings::whitted(16, 12, 1, analyze(&scene).plan), &|_| {}).unwrap();
        assert!(image.pixels.iter().all(|p| p.is_finite() && p.min_element() >= 0.0));
        let far = fog_row(1e3, 10.0).unwrap();
        assert_eq!(far.transmittance, 0.0);
    }
}
