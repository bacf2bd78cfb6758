//! Q2c: the parameter `t` of the ray's closest approach to the sphere's centre, derived two ways.
//!
//! - **Algebraically**, as the vertex of the parabola `A t² + B t + C`: `t = −B/2A`, which with the
//!   homework's `A = |d|²` and `B = 2 (e − o)·d` is `t = −(e − o)·d / |d|²`.
//! - **Geometrically**, by projecting `o − e` onto the ray's unit direction: the foot of the
//!   perpendicular lies at distance `(o − e)·d̂` from `e`, and a distance `s` along the ray is
//!   `t = s/|d|` in the ray's own parameter.
//!
//! Both give the same number in exact arithmetic; in floating point they differ by a few ulps
//! (the geometric route rounds `|d|` through a square root), which the property tests bound.
//! The same `t` is the first line of the stable solver ([`crate::geometry::sphere::roots_stable`]):
//! the discriminant is computed from the vector at the closest point, `l = (e − o) + t_ca d`.

use crate::geometry::Ray;
use crate::real::Real;

/// `t = −B/2A` with the homework's `A` and `B` (the vertex of the quadratic).
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::geometry::Ray;
/// use hw3::q2_ray_sphere::closest_approach::closest_approach_algebraic;
/// let ray = Ray::<f64>::new(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0)).unwrap();
/// assert_eq!(closest_approach_algebraic(&ray, DVec3::new(4.0, 3.0, 0.0)), 2.0);
/// ```
#[must_use]
pub fn closest_approach_algebraic<T: Real>(ray: &Ray<T>, center: T::Vec3) -> T {
    let a = T::dot(ray.dir, ray.dir);
    let b = T::TWO * T::dot(ray.origin - center, ray.dir);
    -b / (T::TWO * a)
}

/// `t = ((o − e)·d̂) / |d|`: project the centre onto the ray, then convert distance to parameter.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::geometry::Ray;
/// use hw3::q2_ray_sphere::closest_approach::closest_approach_geometric;
/// let ray = Ray::<f64>::new(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0)).unwrap();
/// assert_eq!(closest_approach_geometric(&ray, DVec3::new(4.0, 3.0, 0.0)), 2.0);
/// ```
#[must_use]
pub fn closest_approach_geometric<T: Real>(ray: &Ray<T>, center: T::Vec3) -> T {
    let length = T::dot(ray.dir, ray.dir).sqrt();
    let unit = ray.dir * (T::ONE / length);
    let distance_along_ray = T::dot(center - ray.origin, unit);
    distance_along_ray / length
}

/// Squared distance from `center` to the ray's point at parameter `t` (what `t_ca` minimises).
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::geometry::Ray;
/// use hw3::q2_ray_sphere::closest_approach::distance_squared_at;
/// let ray = Ray::<f64>::new(DVec3::ZERO, DVec3::X).unwrap();
/// assert_eq!(distance_squared_at(&ray, DVec3::new(4.0, 3.0, 0.0), 4.0), 9.0);
/// ```
#[must_use]
pub fn distance_squared_at<T: Real>(ray: &Ray<T>, center: T::Vec3, t: T) -> T {
    let v = ray.at(t) - center;
    T::dot(v, v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sphere::closest_approach_t;
    use glam::DVec3;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn both_derivations_agree_and_match_the_stable_solvers_first_line(
            e in prop::array::uniform3(-1e3f64..1e3),
            d in prop::array::uniform3(-10f64..10.0),
            o in prop::array::uniform3(-1e3f64..1e3),
        ) {
            prop_assume!(DVec3::from(d).length() > 1e-3);
            let ray = Ray::<f64>::new(DVec3::from(e), DVec3::from(d)).unwrap();
            let center = DVec3::from(o);
            let algebraic = closest_approach_algebraic(&ray, center);
            let geometric = closest_approach_geometric(&ray, center);
            // Both are sums of |e−o||d| / |d|² terms; 8 ulps of that scale bounds their rounding.
            let scale = (ray.origin - center).length() / ray.dir.length();
            prop_assert!((algebraic - geometric).abs() <= 8.0 * f64::EPSILON * scale,
                "algebraic {algebraic:e} geometric {geometric:e}");
            prop_assert!((algebraic - closest_approach_t(&ray, center)).abs() <= 4.0 * f64::EPSILON * scale);
        }

        #[test]
        fn closest_approach_minimises_distance(
            e in prop::array::uniform3(-100f64..100.0),
            d in prop::array::uniform3(-10f64..10.0),
            o in prop::array::uniform3(-100f64..100.0),
            step in 1e-3f64..10.0,
        ) {
            prop_assume!(DVec3::from(d).length() > 1e-2);
            let ray = Ray::<f64>::new(DVec3::from(e), DVec3::from(d)).unwrap();
            let center = DVec3::from(o);
            let t = closest_approach_algebraic(&ray, center);
            let best = distance_squared_at(&ray, center, t);
            // Exactly: dist²(t ± s) = best + s²|d|²; check the increase, allowing rounding of best.
            let slack = 1e-12 * (best + (ray.origin - center).length_squared());
            for t_other in [t - step, t + step] {
                let other = distance_squared_at(&ray, center, t_other);
                prop_assert!(other + slack >= best);
                let expected = best + step * step * ray.dir.length_squared();
                prop_assert!((other - expected).abs() <= 1e-9 * expected.max(1.0));
            }
        }
    }

    #[test]
    fn closest_approach_behind_the_eye_is_negative() {
        let ray = Ray::<f64>::new(DVec3::ZERO, DVec3::X).unwrap();
        assert_eq!(closest_approach_algebraic(&ray, DVec3::new(-3.0, 1.0, 0.0)), -3.0);
        assert_eq!(closest_approach_geometric(&ray, DVec3::new(-3.0, 1.0, 0.0)), -3.0);
    }
}
