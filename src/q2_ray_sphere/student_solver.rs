//! Q2a as the homework writes it: `A`, `B`, `C`, the discriminant's three cases, and the
//! "smallest positive `t`" selection, transcribed literally so that its behaviour (and its two
//! errata) can be tested and measured against the stable solver of [`crate::geometry::sphere`].

use crate::geometry::{Ray, Sphere};
use crate::real::Real;
use std::fmt;

/// Which branch of the homework's case analysis a ray took.
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::{student_solver::{StudentBranch, student_trace}, worked_example};
/// let (ray, sphere) = worked_example();
/// assert_eq!(student_trace(&ray, &sphere).branch, StudentBranch::TwoRootsT2Smaller);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StudentBranch {
    /// `4AC > B²`: no real roots, no intersection.
    NoRealRoots,
    /// `4AC = B²`: one double root `−B/2A`, accepted when `≥ 0` (note: `≥`, unlike the `>` below).
    Tangent,
    /// `4AC < B²` and `t1 < t2`: the student's first sub-branch. It is dead code for any `A > 0`,
    /// because `t1` takes `+√` and `t2` takes `−√` (see the erratum in the chapter).
    TwoRootsT1Smaller,
    /// `4AC < B²` and `t1 ≥ t2`: the branch every real ray takes (`t2` first, then `t1`).
    TwoRootsT2Smaller,
}

/// Every intermediate value of the homework's algorithm for one ray, for traces and snapshots.
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::{student_solver::student_trace, worked_example};
/// let (ray, sphere) = worked_example();
/// let trace = student_trace(&ray, &sphere);
/// assert_eq!((trace.a, trace.b, trace.c, trace.discriminant), (1.0, -10.0, 22.0, 12.0));
/// assert_eq!(trace.chosen, Some(trace.t2));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StudentTrace<T: Real> {
    /// `A = d·d`.
    pub a: T,
    /// `B = 2 (e − o)·d`.
    pub b: T,
    /// `C = (e − o)·(e − o) − r²`.
    pub c: T,
    /// `B² − 4AC`.
    pub discriminant: T,
    /// The branch taken.
    pub branch: StudentBranch,
    /// `t1 = (−B + √disc)/2A` (NaN when there are no real roots).
    pub t1: T,
    /// `t2 = (−B − √disc)/2A` (NaN when there are no real roots).
    pub t2: T,
    /// The first intersection the homework's rules select.
    pub chosen: Option<T>,
}

/// Runs the homework's algorithm on `ray` and `sphere`, recording every step.
///
/// The comparison `4AC > B²` is evaluated as written; it agrees with `B² − 4AC < 0` in floating
/// point, because a correctly rounded difference has the sign of the exact difference.
///
/// # Examples
/// The homework's setting with round numbers: eye at the origin looking down +z at a unit sphere
/// centred 5 away.
/// ```
/// use glam::DVec3;
/// use hw3::geometry::{Ray, Sphere};
/// use hw3::q2_ray_sphere::student_solver::{student_trace, StudentBranch};
/// let ray = Ray::<f64>::new(DVec3::ZERO, DVec3::Z).unwrap();
/// let sphere = Sphere::<f64>::new(DVec3::new(0.0, 0.0, 5.0), 1.0).unwrap();
/// let trace = student_trace(&ray, &sphere);
/// assert_eq!((trace.a, trace.b, trace.c), (1.0, -10.0, 24.0));
/// assert_eq!(trace.branch, StudentBranch::TwoRootsT2Smaller);
/// assert_eq!((trace.t1, trace.t2, trace.chosen), (6.0, 4.0, Some(4.0)));
/// ```
#[must_use]
pub fn student_trace<T: Real>(ray: &Ray<T>, sphere: &Sphere<T>) -> StudentTrace<T> {
    let f = ray.origin - sphere.center;
    let a = T::dot(ray.dir, ray.dir);
    let b = T::dot(f, ray.dir) * T::TWO;
    let c = T::dot(f, f) - sphere.radius * sphere.radius;
    let discriminant = b * b - T::FOUR * a * c;
    let four_ac = T::FOUR * a * c;
    let b_squared = b * b;
    let nan = T::NAN;
    let no_roots = |branch| StudentTrace { a, b, c, discriminant, branch, t1: nan, t2: nan, chosen: None };
    // "If 4AC > B² there is no intersection"; written as a negated `≤` so that NaN also lands here.
    if !(four_ac <= b_squared) {
        return no_roots(StudentBranch::NoRealRoots);
    }
    if four_ac == b_squared {
        let t = -b / (T::TWO * a);
        let chosen = (t >= T::ZERO).then_some(t);
        return StudentTrace { a, b, c, discriminant, branch: StudentBranch::Tangent, t1: t, t2: t, chosen };
    }
    let root = discriminant.sqrt();
    let t1 = (-b + root) / (T::TWO * a);
    let t2 = (-b - root) / (T::TWO * a);
    let (branch, first, second) =
        if t1 < t2 { (StudentBranch::TwoRootsT1Smaller, t1, t2) } else { (StudentBranch::TwoRootsT2Smaller, t2, t1) };
    let chosen = if first > T::ZERO {
        Some(first)
    } else if second > T::ZERO {
        Some(second)
    } else {
        None
    };
    StudentTrace { a, b, c, discriminant, branch, t1, t2, chosen }
}

/// The homework's first intersection, without the trace (the "naive" method of the notes).
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::geometry::{Ray, Sphere};
/// use hw3::q2_ray_sphere::student_solver::first_hit_naive;
/// let ray = Ray::<f64>::new(DVec3::ZERO, DVec3::Z).unwrap();
/// let sphere = Sphere::<f64>::new(DVec3::new(0.0, 0.0, 5.0), 1.0).unwrap();
/// assert_eq!(first_hit_naive(&ray, &sphere), Some(4.0));
/// ```
#[must_use]
pub fn first_hit_naive<T: Real>(ray: &Ray<T>, sphere: &Sphere<T>) -> Option<T> {
    student_trace(ray, sphere).chosen
}

impl<T: Real> fmt::Display for StudentTrace<T> {
    /// Seven significant digits: enough to show every `f32` digit and to keep snapshots stable.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let g = |x: T| format!("{:.6e}", x.to_f64());
        writeln!(f, "A = {}", g(self.a))?;
        writeln!(f, "B = {}", g(self.b))?;
        writeln!(f, "C = {}", g(self.c))?;
        writeln!(f, "B^2 - 4AC = {}", g(self.discriminant))?;
        writeln!(f, "branch = {:?}", self.branch)?;
        if self.branch != StudentBranch::NoRealRoots {
            writeln!(f, "t1 = {}, t2 = {}", g(self.t1), g(self.t2))?;
        }
        match self.chosen {
            Some(t) => write!(f, "first intersection t = {}", g(t)),
            None => write!(f, "no intersection"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use proptest::prelude::*;

    fn ray(e: [f64; 3], d: [f64; 3]) -> Ray<f64> {
        Ray::new(DVec3::from(e), DVec3::from(d)).unwrap()
    }

    fn unit_sphere() -> Sphere<f64> {
        Sphere::new(DVec3::ZERO, 1.0).unwrap()
    }

    #[test]
    fn erratum_tangent_branch_accepts_t_equal_zero_but_two_root_branch_does_not() {
        // Eye on the sphere, ray tangent to it: B = 0 and C = 0, so 4AC = B² exactly and the student's
        // "−B/2A ≥ 0" accepts t = 0 — the eye's own position. The two-root branch uses "> 0".
        let trace = student_trace(&ray([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]), &unit_sphere());
        assert_eq!(trace.branch, StudentBranch::Tangent);
        assert_eq!(trace.chosen, Some(0.0));
        // Eye on the sphere, ray leaving it: roots 0 and −2; "> 0" rejects t = 0.
        let leaving = student_trace(&ray([0.0, 1.0, 0.0], [0.0, 1.0, 0.0]), &unit_sphere());
        assert_eq!(leaving.branch, StudentBranch::TwoRootsT2Smaller);
        assert_eq!(leaving.chosen, None);
    }

    #[test]
    fn student_cases_eye_inside_and_sphere_behind() {
        let inside = student_trace(&ray([0.0; 3], [0.0, 0.0, 2.0]), &unit_sphere());
        assert_eq!((inside.t1, inside.t2, inside.chosen), (0.5, -0.5, Some(0.5)));
        let behind = student_trace(&ray([0.0, 0.0, 5.0], [0.0, 0.0, 1.0]), &unit_sphere());
        assert_eq!(behind.chosen, None);
        let miss = student_trace(&ray([0.0, 2.0, -5.0], [0.0, 0.0, 1.0]), &unit_sphere());
        assert_eq!(miss.branch, StudentBranch::NoRealRoots);
    }

    #[test]
    fn tangent_with_negative_root_is_no_intersection() {
        let trace = student_trace(&ray([3.0, 1.0, 0.0], [1.0, 0.0, 0.0]), &unit_sphere());
        assert_eq!(trace.branch, StudentBranch::Tangent);
        assert_eq!(trace.chosen, None);
    }

    proptest! {
        /// Erratum: the student's `t1 < t2` sub-branch can never run, because `A > 0` and `√disc ≥ 0`
        /// make `t1 = (−B + √disc)/2A ≥ t2 = (−B − √disc)/2A` in exact *and* rounded arithmetic
        /// (division by a positive number and rounding are both monotone).
        #[test]
        fn erratum_t1_is_never_smaller_than_t2(
            e in prop::array::uniform3(-1e3f64..1e3),
            d in prop::array::uniform3(-1e2f64..1e2),
            o in prop::array::uniform3(-1e3f64..1e3),
            r in 1e-3f64..1e3,
        ) {
            prop_assume!(DVec3::from(d).length_squared() > 1e-6);
            let trace = student_trace(&ray(e, d), &Sphere::new(DVec3::from(o), r).unwrap());
            prop_assert_ne!(trace.branch, StudentBranch::TwoRootsT1Smaller);
            let f32_trace = student_trace(
                &Ray::<f32>::new(f32::vec_from_f64(DVec3::from(e)), f32::vec_from_f64(DVec3::from(d))).unwrap(),
                &Sphere::new(f32::vec_from_f64(DVec3::from(o)), r as f32).unwrap(),
            );
            prop_assert_ne!(f32_trace.branch, StudentBranch::TwoRootsT1Smaller);
        }
    }
}
