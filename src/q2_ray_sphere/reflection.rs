//! Q2b: the hit point, its normal, the reflected direction, and where the reflected ray may start.
//!
//! The homework's reflected ray is `e + d t_i + r̂ t`: it starts exactly at the computed hit point.
//! That is the classic *shadow-acne* bug (Shirley, Black and Hollasch, *Ray Tracing in One
//! Weekend*, version 4, §9.3 "Fixing Shadow Acne"): the computed point is
//! off the true surface by the rounding error of `t_i`, on the inside about half of the time, and a
//! ray that starts inside re-hits the sphere at `t ≈ 0`. [`SpawnPolicy`] names the three fixes the
//! notes compare, and [`self_hit_rate`] measures each over many random hits.

use crate::geometry::sphere::{
    first_hit_stable, offset_along, reflect, reflect_with_cosine, roots_stable, surface_hit,
};
use crate::geometry::{Ray, Sphere};
use crate::real::Real;
use crate::rng::{self, Generator};
use glam::DVec3;

/// Where a secondary ray starts and which `t` it accepts.
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::reflection::SpawnPolicy;
/// assert_eq!(SpawnPolicy::ALL[0], SpawnPolicy::AtComputedPoint);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SpawnPolicy {
    /// The homework's ray: origin `e + d t_i`, accept `t > 0`.
    AtComputedPoint,
    /// Origin `e + d t_i`, accept `t >` [`FIXED_T_MIN`] (Ray Tracing in One Weekend's fix;
    /// scale-dependent).
    FixedEpsilon,
    /// Reproject the point onto the sphere, then push it off along the normal by a scaled number
    /// of ulps ([`crate::geometry::sphere::offset_along`]); accept `t > 0`.
    ReprojectAndOffset,
}

/// The smallest `t` a secondary ray accepts under [`SpawnPolicy::FixedEpsilon`]: `0.001`, the value
/// of Shirley, Black and Hollasch's *Ray Tracing in One Weekend* (version 4, §9.3 "Fixing Shadow
/// Acne", `interval(0.001, infinity)`).
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::reflection::FIXED_T_MIN;
/// assert_eq!(FIXED_T_MIN, 0.001);
/// ```
pub const FIXED_T_MIN: f64 = 1e-3;

impl SpawnPolicy {
    /// All policies, in the order the notes present them.
    ///
    /// # Examples
    /// ```
    /// use hw3::q2_ray_sphere::reflection::SpawnPolicy;
    /// assert_eq!(SpawnPolicy::ALL.len(), 3);
    /// assert_eq!(SpawnPolicy::ALL[2], SpawnPolicy::ReprojectAndOffset);
    /// ```
    pub const ALL: [SpawnPolicy; 3] =
        [SpawnPolicy::AtComputedPoint, SpawnPolicy::FixedEpsilon, SpawnPolicy::ReprojectAndOffset];
}

/// A reflection at a hit: the surface frame and the reflected ray with its minimum accepted `t`.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::geometry::{Ray, Sphere};
/// use hw3::q2_ray_sphere::reflection::{SpawnPolicy, reflect_at_hit};
/// let ray = Ray::<f64>::new(DVec3::new(0.0, 0.0, -5.0), DVec3::Z).unwrap();
/// let sphere = Sphere::<f64>::new(DVec3::ZERO, 1.0).unwrap();
/// let bounce = reflect_at_hit(&ray, &sphere, 4.0, SpawnPolicy::FixedEpsilon);
/// assert_eq!(bounce.point, DVec3::new(0.0, 0.0, -1.0));
/// assert_eq!(bounce.t_min, hw3::q2_ray_sphere::reflection::FIXED_T_MIN);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reflection<T: Real> {
    /// The hit point as the policy computes it (reprojected for [`SpawnPolicy::ReprojectAndOffset`]).
    pub point: T::Vec3,
    /// Outward unit normal `(p − o)/r`.
    pub normal: T::Vec3,
    /// The reflected ray `r̂ = d̂ − 2(n̂·d̂)n̂` (unit direction) from its spawn origin.
    pub ray: Ray<T>,
    /// Hits of the reflected ray count only for `t > t_min`.
    pub t_min: T,
}

/// Reflects `ray` at its hit `t` on `sphere` under `policy`.
///
/// # Preconditions
/// `t` is a hit of `ray` on `sphere` (from a solver), and the sphere has `r > 0`.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::geometry::{Ray, Sphere};
/// use hw3::q2_ray_sphere::reflection::{reflect_at_hit, SpawnPolicy};
/// let ray = Ray::<f64>::new(DVec3::new(0.0, 0.0, -5.0), DVec3::new(0.0, 0.0, 2.0)).unwrap();
/// let sphere = Sphere::<f64>::new(DVec3::ZERO, 1.0).unwrap();
/// let bounce = reflect_at_hit(&ray, &sphere, 2.0, SpawnPolicy::ReprojectAndOffset);
/// assert_eq!(bounce.normal, DVec3::new(0.0, 0.0, -1.0));
/// assert_eq!(bounce.ray.dir, DVec3::new(0.0, 0.0, -1.0)); // straight back
/// assert!(bounce.ray.origin.z < -1.0); // just outside the surface
/// ```
#[must_use]
pub fn reflect_at_hit<T: Real>(ray: &Ray<T>, sphere: &Sphere<T>, t: T, policy: SpawnPolicy) -> Reflection<T> {
    match policy {
        SpawnPolicy::AtComputedPoint | SpawnPolicy::FixedEpsilon => {
            let point = ray.at(t);
            let normal = (point - sphere.center) * (T::ONE / sphere.radius);
            let dir = reflect::<T>(ray.dir, normal);
            let t_min = if policy == SpawnPolicy::FixedEpsilon { T::from_f64(FIXED_T_MIN) } else { T::ZERO };
            Reflection { point, normal, ray: Ray { origin: point, dir }, t_min }
        }
        SpawnPolicy::ReprojectAndOffset => {
            let hit = surface_hit(ray, sphere, t);
            let (dir, cos) = reflect_with_cosine::<T>(ray.dir, hit.normal);
            // The reflection leaves on the side the ray came from: along n when n·d < 0.
            let origin = offset_along::<T>(hit.point, hit.normal, cos < T::ZERO);
            Reflection { point: hit.point, normal: hit.normal, ray: Ray { origin, dir }, t_min: T::ZERO }
        }
    }
}

/// A family of random primary rays for the self-intersection experiment.
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::reflection::{Scenario, SpawnPolicy, self_hit_rate};
/// let far = self_hit_rate::<f64>(Scenario::Far, SpawnPolicy::ReprojectAndOffset, 200, 3);
/// assert_eq!(far.self_hits, 0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Scenario {
    /// Radius log-uniform in [0.1, 10], centre in [−10, 10]³, eye 1.5–20 radii away.
    Near,
    /// As `Near`, eye 10³–10⁴ radii away.
    Far,
    /// Radius 10⁶, eye 1–100 units above the surface.
    HugeSphere,
    /// Radius 10⁻³, centre in [−1, 1]³, eye 1.5–20 radii away.
    TinySphere,
    /// As `Near`, translated 10⁴ units from the world origin.
    Translated,
}

impl Scenario {
    /// All scenarios.
    ///
    /// # Examples
    /// ```
    /// use hw3::q2_ray_sphere::reflection::Scenario;
    /// assert_eq!(Scenario::ALL.len(), 5);
    /// assert_eq!(Scenario::ALL[0], Scenario::Near);
    /// ```
    pub const ALL: [Scenario; 5] =
        [Scenario::Near, Scenario::Far, Scenario::HugeSphere, Scenario::TinySphere, Scenario::Translated];

    /// Draws a sphere and a ray aimed at a uniform point of a disk of radius 0.999 r facing the eye
    /// (so the ray hits in exact arithmetic).
    fn draw(self, g: &mut Generator) -> (Ray<f64>, Sphere<f64>) {
        let unit = |g: &mut Generator| {
            let z = rng::uniform_in(g, -1.0, 1.0);
            let phi = rng::uniform_in(g, 0.0, std::f64::consts::TAU);
            let s = (1.0 - z * z).sqrt();
            DVec3::new(s * phi.cos(), s * phi.sin(), z)
        };
        let cube = |g: &mut Generator, half: f64| {
            DVec3::new(
                rng::uniform_in(g, -half, half),
                rng::uniform_in(g, -half, half),
                rng::uniform_in(g, -half, half),
            )
        };
        let (radius, center, eye_distance) = match self {
            Scenario::Near | Scenario::Translated => {
                let r = 10f64.powf(rng::uniform_in(g, -1.0, 1.0));
                (r, cube(g, 10.0), r * rng::uniform_in(g, 1.5, 20.0))
            }
            Scenario::Far => {
                let r = 10f64.powf(rng::uniform_in(g, -1.0, 1.0));
                (r, cube(g, 10.0), r * 10f64.powf(rng::uniform_in(g, 3.0, 4.0)))
            }
            Scenario::HugeSphere => (1e6, cube(g, 10.0), 1e6 + rng::uniform_in(g, 1.0, 100.0)),
            Scenario::TinySphere => {
                let r = 1e-3;
                (r, cube(g, 1.0), r * rng::uniform_in(g, 1.5, 20.0))
            }
        };
        let offset = if self == Scenario::Translated { DVec3::splat(1e4) } else { DVec3::ZERO };
        let center = center + offset;
        let towards_eye = unit(g);
        let eye = center + towards_eye * eye_distance;
        // A point on the disk through the centre perpendicular to the eye direction.
        let helper = if towards_eye.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
        let u = towards_eye.cross(helper).normalize();
        let v = towards_eye.cross(u);
        let (rho, phi) = (0.999 * radius * rng::uniform(g).sqrt(), rng::uniform_in(g, 0.0, std::f64::consts::TAU));
        let target = center + u * (rho * phi.cos()) + v * (rho * phi.sin());
        let scale = 10f64.powf(rng::uniform_in(g, -1.0, 1.0));
        (Ray { origin: eye, dir: (target - eye) * (scale / eye_distance) }, Sphere { center, radius })
    }
}

/// Outcome of [`self_hit_rate`].
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::reflection::{Scenario, SpawnPolicy, self_hit_rate};
/// let count = self_hit_rate::<f64>(Scenario::Near, SpawnPolicy::ReprojectAndOffset, 100, 2);
/// assert!(count.reflected > 0 && count.self_hits <= count.reflected);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SelfHitCount {
    /// Primary rays whose stable first hit was found (the others are skipped).
    pub reflected: u64,
    /// Reflected rays that hit the same (convex) sphere again — each one a rendering bug.
    pub self_hits: u64,
}

/// Reflects `rays` random primary hits of `scenario` (in precision `T`, seed `seed`) under `policy`
/// and counts reflected rays that hit their own sphere again. A ray leaving a convex surface cannot
/// meet it again, so every such hit is an artefact.
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::reflection::{self_hit_rate, Scenario, SpawnPolicy};
/// let robust = self_hit_rate::<f32>(Scenario::Near, SpawnPolicy::ReprojectAndOffset, 1_000, 1);
/// assert_eq!(robust.self_hits, 0);
/// let naive = self_hit_rate::<f32>(Scenario::Near, SpawnPolicy::AtComputedPoint, 1_000, 1);
/// assert!(naive.self_hits > 100); // the acne the homework's formula produces
/// ```
#[must_use]
pub fn self_hit_rate<T: Real>(scenario: Scenario, policy: SpawnPolicy, rays: u64, seed: u64) -> SelfHitCount {
    let mut g = rng::seeded(seed, scenario as u64);
    let mut count = SelfHitCount { reflected: 0, self_hits: 0 };
    for _ in 0..rays {
        let (ray64, sphere64) = scenario.draw(&mut g);
        let ray = Ray::<T> { origin: T::vec_from_f64(ray64.origin), dir: T::vec_from_f64(ray64.dir) };
        let sphere = Sphere::<T> { center: T::vec_from_f64(sphere64.center), radius: T::from_f64(sphere64.radius) };
        let Some(t) = first_hit_stable(&ray, &sphere) else {
            continue;
        };
        let bounce = reflect_at_hit(&ray, &sphere, t, policy);
        count.reflected += 1;
        let again = roots_stable(&bounce.ray, &sphere).and_then(|roots| roots.first_in(bounce.t_min, T::INFINITY));
        count.self_hits += u64::from(again.is_some());
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The robustness bar: 0 self-intersections over 10⁶ random hits per scenario, in both precisions.
    #[test]
    fn robust_spawn_never_self_intersects_in_a_million_hits_per_scenario() {
        for scenario in Scenario::ALL {
            let f32_count = self_hit_rate::<f32>(scenario, SpawnPolicy::ReprojectAndOffset, 1_000_000, 7);
            let f64_count = self_hit_rate::<f64>(scenario, SpawnPolicy::ReprojectAndOffset, 1_000_000, 7);
            assert!(f32_count.reflected > 900_000 && f64_count.reflected > 900_000, "{scenario:?}: {f32_count:?}");
            assert_eq!(f32_count.self_hits, 0, "{scenario:?} f32");
            assert_eq!(f64_count.self_hits, 0, "{scenario:?} f64");
        }
    }

    #[test]
    fn homework_spawn_self_intersects_about_half_the_time_in_every_precision() {
        for scenario in [Scenario::Near, Scenario::Far] {
            for count in [
                self_hit_rate::<f32>(scenario, SpawnPolicy::AtComputedPoint, 20_000, 3),
                self_hit_rate::<f64>(scenario, SpawnPolicy::AtComputedPoint, 20_000, 3),
            ] {
                let rate = count.self_hits as f64 / count.reflected as f64;
                assert!((0.3..0.7).contains(&rate), "{scenario:?}: rate {rate}");
            }
        }
    }

    /// Shirley's fixed `t_min = 0.001` removes the self-hits near the world origin, in both
    /// precisions; in `f32` it is too small once coordinates are large: a huge sphere, a scene
    /// translated by 10⁴.
    #[test]
    fn fixed_epsilon_fails_once_the_scene_is_translated() {
        let rate = |c: SelfHitCount| c.self_hits as f64 / c.reflected as f64;
        for near in [
            rate(self_hit_rate::<f32>(Scenario::Near, SpawnPolicy::FixedEpsilon, 20_000, 5)),
            rate(self_hit_rate::<f64>(Scenario::Near, SpawnPolicy::FixedEpsilon, 20_000, 5)),
        ] {
            assert!(near < 1e-3, "near {near}");
        }
        let moved = rate(self_hit_rate::<f32>(Scenario::Translated, SpawnPolicy::FixedEpsilon, 20_000, 5));
        let huge = rate(self_hit_rate::<f32>(Scenario::HugeSphere, SpawnPolicy::FixedEpsilon, 20_000, 5));
        assert!(moved > 0.01, "translated {moved}");
        assert!(huge > 0.1, "huge sphere {huge}");
    }
}
