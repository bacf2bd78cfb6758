#![doc = include_str!(concat!(env!("OUT_DIR"), "/q4_light_probe.md"))]

pub mod blind_spot;
mod figures;
pub mod irradiance;
pub mod maps;
mod normals;
pub mod study;
#[cfg(test)]
mod tests;

pub use figures::{figure_jobs, figures};
pub use irradiance::{Estimator, Irradiance, Sh9};
pub use normals::fibonacci_normals;

use crate::answers::Answers;
use crate::envmap::{Probe, ProbeError, ProbeFormat, horizontal_camera};
use crate::plot::significant;
use glam::{DVec2, DVec3};
use maps::AnalyticMap;
use std::fmt::Write as _;

/// The `hw3 irradiance` request, as parsed by the CLI.
///
/// # Examples
/// ```
/// use hw3::q4_light_probe::{irradiance_command, IrradianceRequest};
/// // What `hw3 irradiance --env sky --normal 0,0,1 --method weighted --size 32` asks for.
/// let request = IrradianceRequest {
///     env: "sky".into(), normal: glam::DVec3::Z, method: "weighted".into(),
///     samples: 256, seed: 0, size: 32, json: false,
/// };
/// assert!(irradiance_command(&request).unwrap().starts_with("E(n) = 3.1"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct IrradianceRequest {
    /// `constant:L`, `sky`, `linear:A,B` or a path to a lat-long `.hdr` file.
    pub env: String,
    /// The surface normal (any non-zero length).
    pub normal: DVec3,
    /// The method's CLI name.
    pub method: String,
    /// Monte Carlo samples.
    pub samples: usize,
    /// Monte Carlo seed.
    pub seed: u64,
    /// Texels across the mirror-ball probe an analytic map is rasterised into.
    pub size: usize,
    /// Print `{"irradiance":[r,g,b]}` instead of a sentence.
    pub json: bool,
}

/// Builds the probe an `--env` spec names: analytic maps are rasterised into an orthographic
/// mirror-ball probe of `size`² texels (camera on the horizon, see [`horizontal_camera`]); a file
/// is read as a latitude-longitude map at its own resolution.
///
/// # Errors
/// [`ProbeError::Spec`] for a malformed spec or a negative/non-finite radiance,
/// [`ProbeError::Read`] for an unreadable file, [`ProbeError::Empty`] for size 0.
///
/// # Examples
/// ```
/// let probe = hw3::q4_light_probe::probe_from_spec("linear:1,0.5", 8).unwrap();
/// assert_eq!(probe.width(), 8);
/// assert!(hw3::q4_light_probe::probe_from_spec("linear:1,2", 8).is_err()); // negative radiance
/// ```
pub fn probe_from_spec(spec: &str, size: usize) -> Result<Probe, ProbeError> {
    let numbers = |text: &str, count: usize| -> Result<Vec<f64>, ProbeError> {
        let values: Result<Vec<f64>, _> = text.split(',').map(|p| p.trim().parse()).collect();
        match values {
            Ok(v) if v.len() == count && v.iter().all(|x| x.is_finite()) => Ok(v),
            _ => Err(ProbeError::Spec(format!("expected {count} finite number(s) after the colon in `{spec}`"))),
        }
    };
    let map = if spec == "sky" {
        AnalyticMap::sky()
    } else if let Some(rest) = spec.strip_prefix("constant:") {
        let l = numbers(rest, 1)?[0];
        if l < 0.0 {
            return Err(ProbeError::Spec(format!("radiance must be ≥ 0 in `{spec}`")));
        }
        texel_range(spec, l)?;
        AnalyticMap::constant(l)
    } else if let Some(rest) = spec.strip_prefix("linear:") {
        let v = numbers(rest, 2)?;
        if v[0] < v[1].abs() {
            return Err(ProbeError::Spec(format!(
                "linear:A,B needs A ≥ |B| so that radiance is never negative, got `{spec}`"
            )));
        }
        texel_range(spec, v[0] + v[1].abs())?;
        AnalyticMap::linear_z(v[0], v[1])
    } else {
        return Probe::read_lat_long(spec);
    };
    map.rasterise(ProbeFormat::MirrorBall, size, horizontal_camera())
}

/// Refuses a radiance above what a probe's texels (`f32`) hold: the map would be rasterised into
/// infinities. Irradiance itself is summed in `f64`, so `πL` is representable for any `L` that
/// passes.
fn texel_range(spec: &str, largest: f64) -> Result<(), ProbeError> {
    if largest > f64::from(f32::MAX) {
        return Err(ProbeError::Spec(format!(
            "radiance up to {largest:e} in `{spec}` is above {:e}, the largest a probe's texel (f32) holds",
            f32::MAX
        )));
    }
    Ok(())
}

/// Runs `hw3 irradiance`: the text (or JSON) it prints.
///
/// # Errors
/// [`ProbeError`] for any invalid input (the CLI exits with status 2).
///
/// # Examples
/// ```
/// use hw3::q4_light_probe::{irradiance_command, IrradianceRequest};
/// let request = IrradianceRequest {
///     env: "constant:2".into(), normal: glam::DVec3::Z, method: "sh9".into(),
///     samples: 16, seed: 0, size: 16, json: true,
/// };
/// let out = irradiance_command(&request).unwrap();
/// assert!(out.starts_with("{\"irradiance\":[6.28"));
/// ```
pub fn irradiance_command(request: &IrradianceRequest) -> Result<String, ProbeError> {
    let method: Estimator = request.method.parse().map_err(ProbeError::Spec)?;
    let probe = probe_from_spec(&request.env, request.size)?;
    let prepared = Irradiance::new(&probe);
    let mut rng = crate::rng::seeded(request.seed, 0);
    let e = prepared.estimate(request.normal, method, request.samples, &mut rng)?;
    if request.json {
        Ok(serde_json::json!({ "irradiance": [e.x, e.y, e.z] }).to_string())
    } else {
        Ok(format!(
            "E(n) = {} {} {} (RGB; env {}, method {}, normal {})",
            significant(e.x),
            significant(e.y),
            significant(e.z),
            request.env,
            method.name(),
            request.normal
        ))
    }
}

/// Texels across the probes of the unweighted-sum bias table.
const BIAS_SIZE: usize = 128;
/// Normals the bias table averages over.
const BIAS_NORMALS: usize = 64;
/// The camera of the answers' camera-cone line: its radius and distance in ball radii (the text
/// calls the radius `R`, so it must stay 1: pinned in the tests).
const CAMERA_RADIUS: f64 = 1.0;
const CAMERA_DISTANCE: f64 = 10.0;
/// Pixels across the ball whose outermost pixel ring the answers measure.
const RIM_BALL_SIZE: usize = 256;
/// Texels across the ball of the SH9-near-a-sun line.
const SUN_BALL_SIZE: usize = 64;

/// The unweighted sum's error on a constant map, in percent of `πL`, mean and max over
/// [`BIAS_NORMALS`] normals, for a format at [`BIAS_SIZE`] texels across.
fn unweighted_bias(format: ProbeFormat) -> study::ErrorSummary {
    let map = AnalyticMap::constant(1.0);
    let probe = map.rasterise(format, BIAS_SIZE, horizontal_camera()).expect("valid analytic map");
    let normals = fibonacci_normals(BIAS_NORMALS);
    study::analytic_error(&map, &Irradiance::new(&probe), Estimator::Unweighted, 1, &[0], &normals)
}

/// The angle, in degrees, that the outermost pixel ring of an orthographic mirror ball `pixels`
/// across spans on the sphere: from `θ(1 − 2/pixels)` to the rim's `θ = 180°`.
fn rim_ring_degrees(pixels: usize) -> f64 {
    let inner = DVec2::new(1.0 - 2.0 / pixels as f64, 0.0);
    let direction = ProbeFormat::MirrorBall.image_to_direction(inner).expect("inside the disk");
    180.0 - direction.z.acos().to_degrees()
}

/// Q4's answers, computed.
///
/// # Panics
/// Never for the fixed inputs used here (they are validated constants).
///
/// # Examples
/// ```
/// let a = hw3::q4_light_probe::answers();
/// assert_eq!(a.question, "q4");
/// assert!(a.text.contains("blind cone"));
/// ```
#[must_use]
pub fn answers() -> Answers {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "Diffuse light from a mirrored-ball probe: E(n) = Σ_t L_t max(0, n·ω_t) Δω_t, and L_o = (K_d/π) E \
         with K_d the albedo. The student's Σ K_d L (n·l) omits Δω_t: right only if every texel subtends the same solid angle."
    );
    let _ = writeln!(
        text,
        "Unweighted sum on a constant map (error % of πL, mean / max over {BIAS_NORMALS} normals, {BIAS_SIZE} px):"
    );
    for format in [
        ProbeFormat::MirrorBall,
        ProbeFormat::AngularMap,
        ProbeFormat::LatLong,
        ProbeFormat::PerspectiveBall { distance_over_radius: 10.0 },
    ] {
        let e = unweighted_bias(format);
        let _ = writeln!(text, "  {:<28} {:>7.3} / {:>7.3}", format.name(), e.mean_percent, e.max_percent);
    }
    let _ = writeln!(
        text,
        "The orthographic ball is equal-area (dω = {} dA), so the student's sum is right there and only there.",
        ProbeFormat::MirrorBall.jacobian(DVec2::ZERO)
    );
    let _ = writeln!(
        text,
        "The student's claim \"only light that would pass through the ball to reach the eye & light occluded by the camera is missing\": \
         right for an ideal ball, and quantifiable: the blind cone behind the ball has half-angle arcsin(R/D):"
    );
    for d in [3.0, 5.0, 10.0, 20.0] {
        let _ = writeln!(
            text,
            "  D/R = {d:>4}: half-angle {:>6.2}°, {:.4} sr, a uniform map loses {:.2} % of E at n = away",
            blind_spot::half_angle(d).map_or(f64::NAN, f64::to_degrees),
            blind_spot::solid_angle(d).unwrap_or(f64::NAN),
            100.0 * blind_spot::lost_fraction(d, 0.0).unwrap_or(f64::NAN)
        );
    }
    let camera_cone = blind_spot::camera_half_angle(CAMERA_RADIUS, CAMERA_DISTANCE).unwrap_or(f64::NAN);
    let _ = writeln!(
        text,
        "  The camera: one as wide as the ball (r_c = R) at D = {CAMERA_DISTANCE}R hides a {:.2}° cone around the direction back to it, \
         {:.2} % of a uniform map's E at n = toward the camera; its reflection replaces that light.",
        camera_cone.to_degrees(),
        100.0 * maps::cap_irradiance_per_radiance(0.0, camera_cone) / std::f64::consts::PI
    );
    let _ = writeln!(
        text,
        "  It omits: the camera's reflection is not missing light but wrong light (it replaces the scene behind the camera); \
         the rim is smeared (the last pixel ring of a {RIM_BALL_SIZE} px ball spans ~{:.0}° of the sphere); the ball's reflectance < 1.",
        rim_ring_degrees(RIM_BALL_SIZE)
    );
    let map = AnalyticMap::sun();
    let probe = map.rasterise(ProbeFormat::MirrorBall, SUN_BALL_SIZE, horizontal_camera()).expect("valid map");
    let prepared = Irradiance::new(&probe);
    // The normal 90° from the sun, in the plane of the sun and the zenith.
    let sun = maps::sun_direction();
    let terminator = DVec3::new(-sun.z, 0.0, sun.x);
    let sun_half_angle = map.terms.iter().find_map(|t| match *t {
        maps::Term::Cap { half_angle, .. } => Some(half_angle),
        _ => None,
    });
    let _ = writeln!(
        text,
        "SH9 near a sun (sky + {:.2}° sun, {SUN_BALL_SIZE} px ball): at the sun's terminator exact {:.3}, SH9 {:.3}, weighted sum {:.3}.",
        sun_half_angle.map_or(f64::NAN, f64::to_degrees),
        map.irradiance(terminator),
        prepared.sh9().irradiance(terminator).x,
        prepared.weighted(terminator).x
    );
    Answers { question: "q4", title: "Environment lighting from a mirrored-ball light probe", text }
}
