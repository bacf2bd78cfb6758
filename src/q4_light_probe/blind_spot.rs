//! What a mirrored ball cannot see: the cone behind it, and the camera in front of it.
//!
//! A pinhole camera at distance `D` from the centre of a ball of radius `R` sees reflections up to
//! `θ = π − γ` from the direction back to the camera, with `γ = arcsin(R/D)`: the cone of
//! half-angle `γ` straight behind the ball is light that would have to pass *through* the ball to
//! reach the eye. The camera (and photographer) hide a second cone around the direction toward the
//! camera: [`camera_half_angle`] traces it (about `(r_c/D)(1 + R/(2(D − R)))` for a camera of
//! radius `r_c`, wider than the far-camera `arctan(r_c/D)` because the reflecting points sit in
//! front of the ball's centre).

use super::maps::cap_irradiance_per_radiance;
use crate::envmap::ProbeFormat;
use crate::geometry::InputError;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

fn require_outside(distance_over_radius: f64) -> Result<f64, InputError> {
    ProbeFormat::perspective_ball(distance_over_radius).map(|_| distance_over_radius)
}

/// The blind cone's half-angle `γ = arcsin(R/D)` in radians.
///
/// # Errors
/// [`InputError`] unless `D/R > 1` and finite.
///
/// # Examples
/// ```
/// let gamma = hw3::q4_light_probe::blind_spot::half_angle(3.0).unwrap();
/// assert!((gamma.to_degrees() - 19.47).abs() < 0.01);
/// ```
pub fn half_angle(distance_over_radius: f64) -> Result<f64, InputError> {
    Ok((1.0 / require_outside(distance_over_radius)?).asin())
}

/// The blind cone's solid angle `2π(1 − √(1 − (R/D)²)) ≈ π (R/D)²`, written without cancellation.
///
/// # Errors
/// As [`half_angle`].
///
/// # Examples
/// ```
/// let omega = hw3::q4_light_probe::blind_spot::solid_angle(10.0).unwrap();
/// assert!((omega - 0.0315).abs() < 1e-4);
/// ```
pub fn solid_angle(distance_over_radius: f64) -> Result<f64, InputError> {
    let s2 = (1.0 / require_outside(distance_over_radius)?).powi(2);
    Ok(TAU * s2 / (1.0 + (1.0 - s2).sqrt()))
}

/// The fraction of a uniform map's irradiance `πL` that the blind cone removes, for a normal at
/// angle `alpha` from the direction straight behind the ball. At `alpha = 0` it is `(R/D)²`.
///
/// # Errors
/// As [`half_angle`].
///
/// # Examples
/// ```
/// let lost = hw3::q4_light_probe::blind_spot::lost_fraction(5.0, 0.0).unwrap();
/// assert!((lost - 0.04).abs() < 1e-12);
/// ```
pub fn lost_fraction(distance_over_radius: f64, alpha: f64) -> Result<f64, InputError> {
    let gamma = half_angle(distance_over_radius)?;
    Ok(cap_irradiance_per_radiance(alpha, gamma) / PI)
}

/// The half-angle of the cone of directions hidden by a camera of radius `r_c` at distance `D`
/// (both in ball radii), centred on the direction back to the camera.
///
/// The camera is a disc of radius `r_c` facing the ball, centred on the axis at distance `D` from
/// the ball's centre, with the pinhole at its centre. The camera ray that meets the ball where the
/// normal makes the angle `α` with the axis leaves the pinhole at `β` off the axis,
/// `tan β = R sin α / (D − R cos α)`, meets the surface at incidence `i = α + β` and is reflected
/// to `ψ = 2α + β` from the direction back to the camera. It leaves from `P = R (sin α, cos α)`, not
/// from the centre, so it reaches the camera's plane at the distance
/// `x(α) = R sin α + (D − R cos α) tan ψ` from the axis. `x` grows with `α` (it is infinite once
/// `ψ ≥ 90°`: the ray no longer heads toward the camera's plane), so the hidden cone is `ψ(α*)` with
/// `x(α*) = r_c`, found by bisection. For small angles `x ≈ 2Dα`, so
/// `ψ ≈ (r_c/D)(1 + R/(2(D − R)))`: wider than the far-camera `arctan(r_c/D)`.
///
/// # Errors
/// As [`half_angle`], and [`InputError::OutOfRange`] for a negative or non-finite camera radius.
///
/// # Examples
/// ```
/// use hw3::q4_light_probe::blind_spot::camera_half_angle;
/// // A camera as wide as the ball, 10 radii away: 6.03°, not arctan(1/10) = 5.71°.
/// let cone = camera_half_angle(1.0, 10.0).unwrap();
/// assert!((cone.to_degrees() - 6.026).abs() < 1e-3);
/// assert_eq!(camera_half_angle(0.0, 10.0).unwrap(), 0.0);
/// ```
pub fn camera_half_angle(camera_radius: f64, distance_over_radius: f64) -> Result<f64, InputError> {
    let d = require_outside(distance_over_radius)?;
    if !(camera_radius >= 0.0 && camera_radius.is_finite()) {
        return Err(InputError::OutOfRange {
            name: "camera radius",
            value: format!("{camera_radius}"),
            expected: "finite and ≥ 0",
        });
    }
    // The reflected direction ψ(α) and where its ray meets the camera's plane, x(α).
    let reflected = |alpha: f64| {
        let beta = alpha.sin().atan2(d - alpha.cos());
        let psi = 2.0 * alpha + beta;
        let x = if psi < FRAC_PI_2 { alpha.sin() + (d - alpha.cos()) * psi.tan() } else { f64::INFINITY };
        (psi, x)
    };
    // From the axis (x = 0) to the silhouette, where cos α = R/D and ψ = 180° − γ (x infinite).
    let (mut lo, mut hi) = (0.0, (1.0 / d).acos());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if reflected(mid).1 <= camera_radius {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= f64::EPSILON * hi {
            break;
        }
    }
    Ok(reflected(lo).0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sphere::{first_hit_stable, reflect, surface_hit};
    use crate::geometry::{Ray, Sphere};
    use glam::{DVec2, DVec3};

    /// Traces camera rays at angle β off the axis into a unit ball with the crate's sphere solver,
    /// and returns the reflected direction.
    fn traced_reflection(d: f64, beta: f64) -> Option<DVec3> {
        let ray = Ray::<f64>::new(DVec3::new(0.0, 0.0, d), DVec3::new(beta.sin(), 0.0, -beta.cos())).ok()?;
        let ball = Sphere::<f64>::new(DVec3::ZERO, 1.0).ok()?;
        let t = first_hit_stable(&ray, &ball)?;
        let hit = surface_hit(&ray, &ball, t);
        Some(reflect::<f64>(ray.dir, hit.normal))
    }

    #[test]
    fn the_perspective_mapping_matches_traced_reflections() {
        for d in [1.5, 3.0, 10.0] {
            let format = ProbeFormat::perspective_ball(d).unwrap();
            let beta_max = (1.0 / d).asin();
            for k in 0..=200 {
                let beta = beta_max * k as f64 / 200.0 * (1.0 - 1e-9);
                let traced = traced_reflection(d, beta).unwrap();
                let rho = beta.tan() / beta_max.tan();
                let mapped = format.image_to_direction(DVec2::new(rho, 0.0)).unwrap();
                assert!((traced - mapped).length() < 1e-6, "D/R {d}, β {beta}: {traced} vs {mapped}");
            }
        }
    }

    #[test]
    fn no_traced_ray_reaches_into_the_blind_cone() {
        // The student's claim: what is missing is the light that would pass through the ball.
        for d in [3.0, 5.0, 10.0, 20.0] {
            let gamma = half_angle(d).unwrap();
            let beta_max = (1.0 / d).asin();
            // ψ(β) is steep at the silhouette (like √): sample β ever closer to β_max there.
            let betas = (0..=2_000)
                .map(|k| beta_max * k as f64 / 2_000.0)
                .chain((1..=15).map(|j| beta_max * (1.0 - 10f64.powi(-j))));
            let closest = betas
                .filter_map(|beta| traced_reflection(d, beta))
                .map(|r| r.dot(-DVec3::Z).clamp(-1.0, 1.0).acos())
                .fold(f64::INFINITY, f64::min);
            assert!(closest >= gamma - 1e-9, "D/R {d}: reached {closest} < γ {gamma}");
            assert!(closest < gamma + 1e-4, "D/R {d}: the cone is tight ({closest} vs {gamma})");
        }
    }

    #[test]
    fn the_reference_table_is_reproduced() {
        // The chapter's table: D/R, half-angle (deg), solid angle (sr), loss at n = away.
        for (d, degrees, sr, loss) in [
            (3.0, 19.47, 0.359, 0.111),
            (5.0, 11.54, 0.127, 0.040),
            (10.0, 5.74, 0.0315, 0.010),
            (20.0, 2.87, 0.00786, 0.0025),
        ] {
            assert!((half_angle(d).unwrap().to_degrees() - degrees).abs() < 0.01);
            assert!((solid_angle(d).unwrap() - sr).abs() < 0.0015 * sr.max(1.0));
            assert!((lost_fraction(d, 0.0).unwrap() - loss).abs() < 5e-4);
        }
    }

    #[test]
    fn the_blind_cone_is_the_gap_in_the_texel_solid_angles() {
        use crate::envmap::Probe;
        for d in [3.0, 10.0] {
            let format = ProbeFormat::perspective_ball(d).unwrap();
            let probe = Probe::from_fn(format, 24, 24, glam::DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
            let covered: f64 = probe.texels().iter().map(|t| t.solid_angle).sum();
            assert!((4.0 * PI - covered - solid_angle(d).unwrap()).abs() < 1e-9);
        }
    }

    /// Where the traced reflection of the camera ray at angle β off the axis meets the camera's
    /// plane (`z = D`): its distance from the axis (infinite if it heads away), and its angle from
    /// the direction back to the camera.
    fn traced_at_camera_plane(d: f64, beta: f64) -> (f64, f64) {
        let ray = Ray::<f64>::new(DVec3::new(0.0, 0.0, d), DVec3::new(beta.sin(), 0.0, -beta.cos())).unwrap();
        let ball = Sphere::<f64>::new(DVec3::ZERO, 1.0).unwrap();
        let hit = surface_hit(&ray, &ball, first_hit_stable(&ray, &ball).unwrap());
        let out = reflect::<f64>(ray.dir, hit.normal);
        let psi = out.z.clamp(-1.0, 1.0).acos();
        if out.z <= 0.0 {
            return (f64::INFINITY, psi);
        }
        let at = hit.point + out * ((d - hit.point.z) / out.z);
        (at.truncate().length(), psi)
    }

    #[test]
    fn the_camera_cone_is_where_traced_reflections_reach_the_camera() {
        for (r_c, d) in [(1.0_f64, 10.0_f64), (0.2, 3.0), (0.5, 5.0), (1.0, 3.0), (0.2, 20.0)] {
            // Bisection on the camera ray's angle: the last ray whose reflection hits the camera.
            let (mut lo, mut hi) = (0.0, (1.0 / d).asin() * (1.0 - 1e-12));
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if traced_at_camera_plane(d, mid).0 <= r_c {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let traced = traced_at_camera_plane(d, lo).1;
            let cone = camera_half_angle(r_c, d).unwrap();
            assert!((cone - traced).abs() < 1e-9, "r_c {r_c}, D {d}: {cone} against traced {traced}");
            // Wider than the far-camera estimate, and close to the small-angle form.
            assert!(cone > (r_c / d).atan());
            let small_angle = r_c / d * (1.0 + 1.0 / (2.0 * (d - 1.0)));
            assert!((cone / small_angle - 1.0).abs() < 0.06, "r_c {r_c}, D {d}");
        }
    }

    #[test]
    fn invalid_distances_are_typed_errors() {
        for d in [1.0, 0.5, -3.0, f64::NAN, f64::INFINITY] {
            assert!(half_angle(d).is_err(), "{d}");
        }
        assert!(camera_half_angle(-1.0, 5.0).is_err());
    }
}
