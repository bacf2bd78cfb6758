//! The numerically stable ray/sphere intersection, the surface frame at a hit, mirror reflection,
//! and a self-intersection-free origin for secondary rays.
//!
//! # The stable solver (Ray Tracing Gems ch. 7, Haines et al. 2019)
//! With `f = e − o`, `A = d·d`, `b' = −f·d` and `C = f·f − r²`, the roots of `A t² − 2b' t + C = 0`
//! are `t = (b' ± √(b'² − A C))/A`. Two rewrites keep every bit that matters:
//!
//! 1. **Discriminant from the closest-approach vector** (Hearn & Baker). `t_ca = b'/A` is the
//!    parameter of the point of the ray nearest the centre (the homework's Q2c), and
//!    `l = f + t_ca d` is the vector from the centre to that point. Then
//!    `b'² − A C = A (r² − l·l)`: the subtraction of two large squares `f·f − r²` (which loses
//!    `r²` entirely once `|f| > 4096 r` in `f32`) becomes a subtraction of two quantities of the
//!    size of `r²`. The code evaluates `A (l·l)` as `|f × d|²`, the same length by Lagrange's
//!    identity (`l = d × (f × d)/A`): it needs no `t_ca`, so the square root does not wait for
//!    the division, and its rounding error (`ε|f|` in the perpendicular vector, like that of `l`)
//!    gives the same accuracy (`grazing_roots_match_the_f64_reference_statistically`).
//! 2. **No cancellation in the roots** (Press et al., *Numerical Recipes* §5.6). The roots are
//!    `t_ca ∓ h` with the half-chord `h = √((r² − l·l)/A)`. The one whose terms have opposite
//!    signs can cancel (an eye close to a big sphere: a root near 0); it is recomputed from the
//!    other with `t_near t_far = C/A`, a quotient of like-signed terms. This is Press's
//!    `q = b' + sign(b') √(A disc)`, roots `C/q` and `q/A`, applied only when cancellation is
//!    possible, so that a primary ray pays one division and one square root.
//!
//! What neither rewrite can fix: `C = f·f − r²` itself, when the eye sits within a few units of a
//! sphere of radius 10⁶ in `f32` (`C` is then rounding noise). That needs `f64`; see the Q2 notes.
//!
//! # Policies (stated once, used everywhere)
//! - A hit is a root in the open interval `(t_min, t_max)`; the default `t_min` is 0, so a root at
//!   exactly `t = 0` (the eye on the surface) is **not** a hit. Secondary rays must therefore be
//!   spawned from [`spawn_origin`], never from the raw hit point.
//! - A tangent ray (double root) is a hit.
//! - An eye inside the sphere hits the far root (the near one is behind it).
//! - Comparisons are written so that NaN fails them: NaN anywhere is a miss, never a NaN `t`.
//!   Validated constructors ([`Ray::new`], [`Sphere::new`]) reject such input earlier.
//! - Valid input can still be out of a precision's reach: a square that overflows (for `|d| ≈ 1`,
//!   `r ≥ 2⁵⁰⁹` in `f64`, `r ≥ 2⁶¹` in `f32`). [`check_solvable`] refuses such cases with the
//!   reason; inside its domain every hit of [`first_hit_stable`] has a finite `t`, a point on the
//!   sphere to within the rounding of its coordinates, and a unit normal.
//! - How far that answer can be from the exact one is what [`bounded_first_hit`] states: the same
//!   `t`, point, normal and reflection, each with a bound on its error computed from the actual
//!   inputs (see [its derivation](bounded_first_hit#numerics)). It refuses only where no answer
//!   within the bound exists: hit and miss, or the two sides of the eye, or the two sides of the
//!   sphere, cannot be told apart.

mod tracked;

use super::{InputError, Ray, Sphere};
use crate::real::Real;

/// The two roots of the ray/sphere quadratic, sorted (`near ≤ far`), possibly negative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Roots<T: Real> {
    /// The smaller parameter.
    pub near: T,
    /// The larger parameter.
    pub far: T,
}

impl<T: Real> Roots<T> {
    /// The smallest root strictly inside `(t_min, t_max)`, or `None`.
    ///
    /// # Examples
    /// ```
    /// use hw3_core::geometry::sphere::Roots;
    /// let roots = Roots { near: -1.0, far: 3.0 };
    /// assert_eq!(roots.first_in(0.0, f64::INFINITY), Some(3.0));
    /// assert_eq!(roots.first_in(3.0, f64::INFINITY), None);
    /// ```
    #[must_use]
    pub fn first_in(&self, t_min: T, t_max: T) -> Option<T> {
        [self.near, self.far].into_iter().find(|&t| t > t_min && t < t_max)
    }
}

/// The closest-approach parameter `t_ca = −(e − o)·d / (d·d)`: the `t` at which the ray passes
/// nearest to `center` (Q2c). Valid for any non-zero `d`; it may be negative (closest point behind
/// the eye).
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::{Ray, sphere::closest_approach_t};
/// let ray = Ray::<f64>::new(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0)).unwrap();
/// assert_eq!(closest_approach_t(&ray, DVec3::new(4.0, 1.0, 0.0)), 2.0);
/// ```
#[must_use]
pub fn closest_approach_t<T: Real>(ray: &Ray<T>, center: T::Vec3) -> T {
    let f = ray.origin - center;
    -T::dot(f, ray.dir) / T::dot(ray.dir, ray.dir)
}

/// Checks that the ray/sphere problem is within reach of precision `T`: every square and product
/// the solvers here and the Q2 ones form stays a finite normal number, so that they give a finite
/// `t`, and a finite point and unit normal for every hit.
///
/// With `s = ‖e − o‖∞`, it requires every square and product the solvers form (`r²|d|²`,
/// `|f × d|²`, `f·f`, the homework's `4AC`, `t = |f|/|d|`) to be a finite normal number, with a
/// factor 64 to spare. It does not judge how accurate the answer is: that depends on the ray, not
/// only on sizes, and [`bounded_first_hit`] states it (a unit sphere `10⁵` away is answered in
/// `f32` to a few hundredths, its two sides being 256 `f32` spacings apart).
///
/// # Errors
/// [`InputError::Unresolvable`] naming the quantity out of reach.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::{Ray, Sphere, sphere::check_solvable};
/// let sphere = Sphere::<f64>::new(DVec3::ZERO, 1.0).unwrap();
/// let near = Ray::<f64>::new(DVec3::new(-5.0, 0.0, 0.0), DVec3::X).unwrap();
/// assert!(check_solvable(&near, &sphere).is_ok());
/// let huge = Sphere::<f64>::new(DVec3::ZERO, 1e200).unwrap();
/// assert!(check_solvable(&near, &huge).is_err()); // r² overflows
/// ```
pub fn check_solvable<T: Real>(ray: &Ray<T>, sphere: &Sphere<T>) -> Result<(), InputError> {
    let refuse = |reason: String| Err(InputError::Unresolvable { precision: T::NAME, reason });
    let size = |v: T::Vec3| T::components(v).iter().map(|c| c.to_f64().abs()).fold(0.0, f64::max);
    let offset = ray.origin - sphere.center;
    let (f, d, r) = (size(offset), size(ray.dir), sphere.radius.to_f64());
    if !f.is_finite() {
        return refuse("e − o overflows".into());
    }
    // Exponents, so that the test itself cannot overflow; log2(0) = −∞ passes every upper bound.
    let (max_exp, min_exp) = (T::MAX.to_f64().log2(), T::MIN_POSITIVE.to_f64().log2());
    let (lf, ld, lr) = (f.log2(), d.log2(), r.log2());
    // A factor 64 to spare: the homework's `4AC` is 4 times a product of sums of three squares,
    // and |·| is up to √3 times ‖·‖∞.
    let spare = 6.0;
    let (fs, ds, rs) = (short(f), short(d), short(r));
    if 2.0 * lr.max(lr + ld) + spare >= max_exp {
        return refuse(format!("r² |d|² overflows for r = {rs}, |d| = {ds}"));
    }
    if 2.0 * lf.max(lf + ld) + spare >= max_exp {
        return refuse(format!("|e − o|² |d|² overflows for |e − o| = {fs}, |d| = {ds}"));
    }
    if lf.max(lr) - ld + spare >= max_exp {
        return refuse(format!("t ≈ |e − o|/|d| overflows for |e − o| = {fs}, r = {rs}, |d| = {ds}"));
    }
    if 2.0 * lr.min(lr + ld) - spare <= min_exp {
        return refuse(format!("r² |d|² underflows for r = {rs}, |d| = {ds}"));
    }
    Ok(())
}

/// `x` in scientific notation with at most 4 significant digits (`1e16`, `2.22e0`).
fn short(x: f64) -> String {
    let text = format!("{x:.3e}");
    let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
    let mantissa = if mantissa.contains('.') { mantissa.trim_end_matches('0').trim_end_matches('.') } else { mantissa };
    format!("{mantissa}e{exponent}")
}

/// Both roots by the stable method (module docs), or `None` when the ray's line misses the sphere.
///
/// # Numerics
/// The roots are computed as `t_ca ∓ h`, with the half-chord `h = √((r² − l·l)/A)` in parameter
/// units, evaluated as `√(r² A − |f × d|²)/A` (one division, shared, and one square root, which
/// run side by side because neither needs the other's result). Subtracting `h` from `t_ca` is accurate to a
/// few ulps whenever `h ≤ |t_ca|/2`; otherwise the root of smaller magnitude may cancel, and it is
/// recomputed from the other by Vieta's product `t_near t_far = C/A` — Press's cure, paid only where
/// it is needed (an eye inside or close to the sphere), so primary rays cost one division. Relative
/// error of each root is then a few ulps of `t` whenever `C = f·f − r²` is itself accurate (every
/// case of the Q2 catalogue except an `f32` eye within ~100 units of an `r = 10⁶` sphere).
/// Non-finite input can give NaN roots; [`Roots::first_in`] never returns NaN.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::{Ray, Sphere, sphere::roots_stable};
/// let ray = Ray::<f64>::new(DVec3::ZERO, DVec3::Z).unwrap();
/// let sphere = Sphere::<f64>::new(DVec3::new(0.0, 0.0, 5.0), 1.0).unwrap();
/// let roots = roots_stable(&ray, &sphere).unwrap();
/// assert_eq!((roots.near, roots.far), (4.0, 6.0));
/// ```
#[inline]
#[must_use]
pub fn roots_stable<T: Real>(ray: &Ray<T>, sphere: &Sphere<T>) -> Option<Roots<T>> {
    let f = ray.origin - sphere.center;
    let a = T::dot(ray.dir, ray.dir);
    let r2 = sphere.radius * sphere.radius;
    let perpendicular = T::cross(f, ray.dir);
    let disc_times_a = r2 * a - T::dot(perpendicular, perpendicular);
    if !(disc_times_a >= T::ZERO) {
        return None;
    }
    let inv_a = T::ONE / a;
    let t_ca = -T::dot(f, ray.dir) * inv_a;
    let h = disc_times_a.sqrt() * inv_a;
    let (mut near, mut far) = (t_ca - h, t_ca + h);
    if h > t_ca.abs() * T::from_f64(0.5) {
        let c_over_a = (T::dot(f, f) - r2) * inv_a;
        if t_ca >= T::ZERO {
            near = c_over_a / far;
        } else {
            far = c_over_a / near;
        }
        if near > far {
            // Only for a tangent eye on the surface (0/0 avoided below) or rounding at h ≈ |t_ca|.
            std::mem::swap(&mut near, &mut far);
        }
    }
    if h == T::ZERO {
        // Double root (tangent ray): both equal t_ca; also avoids 0/0 when the eye is on the sphere.
        return Some(Roots { near: t_ca, far: t_ca });
    }
    Some(Roots { near, far })
}

/// The first hit `t > 0` by the stable method, or `None` (miss, or sphere entirely behind).
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::{Ray, Sphere, sphere::first_hit_stable};
/// let sphere = Sphere::<f64>::new(DVec3::ZERO, 1.0).unwrap();
/// let inside = Ray::<f64>::new(DVec3::ZERO, DVec3::X).unwrap();
/// assert_eq!(first_hit_stable(&inside, &sphere), Some(1.0)); // eye inside: the far root
/// ```
#[inline]
#[must_use]
pub fn first_hit_stable<T: Real>(ray: &Ray<T>, sphere: &Sphere<T>) -> Option<T> {
    roots_stable(ray, sphere)?.first_in(T::ZERO, T::INFINITY)
}

/// The surface frame at a hit: point, outward unit normal, and the parameter it came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceHit<T: Real> {
    /// The ray parameter `t_i` of the hit.
    pub t: T,
    /// The hit point, moved back onto the sphere (see [`surface_hit`]).
    pub point: T::Vec3,
    /// Outward unit normal `(p − o)/r`.
    pub normal: T::Vec3,
}

/// The hit point and outward normal at parameter `t`.
///
/// The computed `e + d t` is off the surface by the error in `t` times `|d|` (far from the eye that
/// is many ulps), so the point is **reprojected**: `p = o + r (p' − o)/|p' − o|`, which puts it
/// within a few ulps of the true surface whatever the error in `t` (pbrt-v4 §6.8.5). The normal is
/// `(p − o)/r`, as in the homework. For the small `t` errors of the stable solver, `r/|p' − o|` is
/// taken from one Newton step starting at `1` (that is, `1/|p' − o|` from the guess `1/r`) (error `O(δ²)` for `|p' − o|² = r²(1 + δ)`), which
/// avoids a square root; larger errors fall back to the exact square root.
///
/// # Preconditions
/// `t` is a hit of `ray` on `sphere` from a solver, and `r > 0` (guaranteed by [`Sphere::new`]).
/// A `t` far from the true hit still gives a unit normal and a point on the sphere (through the
/// square-root branch), just not the right one.
///
/// # Panics
/// Never.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::{Ray, Sphere, sphere::surface_hit};
/// let ray = Ray::<f64>::new(DVec3::ZERO, DVec3::Z).unwrap();
/// let sphere = Sphere::<f64>::new(DVec3::new(0.0, 0.0, 5.0), 1.0).unwrap();
/// let hit = surface_hit(&ray, &sphere, 4.0);
/// assert_eq!(hit.normal, DVec3::new(0.0, 0.0, -1.0));
/// ```
#[must_use]
pub fn surface_hit<T: Real>(ray: &Ray<T>, sphere: &Sphere<T>, t: T) -> SurfaceHit<T> {
    let radial = ray.at(t) - sphere.center;
    let inv_r = T::ONE / sphere.radius;
    // |radial|²/r² = 1 + δ with |δ| of a few ulps times t|d|/r for a t from the stable solver.
    // One Newton step for 1/√ from the guess 1/r gives 1/|radial| to O(δ²) (here scaled by r),
    // with no square root;
    // a larger δ (a t from a less accurate solver) takes the exact route.
    let ratio = T::dot(radial, radial) * inv_r * inv_r;
    let delta = ratio - T::ONE;
    // Below √ε the Newton step's error (3/8)δ² is under half an ulp.
    let r_over_length = if delta.abs() < T::EPSILON.sqrt() {
        T::from_f64(1.5) - T::from_f64(0.5) * ratio
    } else {
        sphere.radius / T::dot(radial, radial).sqrt()
    };
    // The point and the normal are both scalings of `radial`, computed side by side rather than
    // one from the other: the reflected ray's origin then waits for one multiply less.
    let normal = radial * (inv_r * r_over_length);
    SurfaceHit { t, point: sphere.center + radial * r_over_length, normal }
}

/// Mirror reflection of `d` about the unit normal `n`: `r̂ = d̂ − 2 (n̂·d̂) n̂`, returned unit length.
///
/// Works for either orientation of `n` (the formula is even in `n`).
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::sphere::reflect;
/// let r = reflect::<f64>(DVec3::new(1.0, -1.0, 0.0), DVec3::Y);
/// assert!((r - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-15);
/// ```
#[must_use]
pub fn reflect<T: Real>(d: T::Vec3, n: T::Vec3) -> T::Vec3 {
    reflect_with_cosine::<T>(d, n).0
}

/// [`reflect`], also returning `n̂·d̂`, whose sign tells which side of the surface the reflected
/// ray leaves by (the side `n` points to when `n̂·d̂ < 0`), so a caller can spawn it with
/// [`offset_along`] without another dot product.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::sphere::reflect_with_cosine;
/// let (r, cos) = reflect_with_cosine::<f64>(DVec3::new(0.0, -2.0, 0.0), DVec3::Y);
/// assert_eq!((r, cos), (DVec3::Y, -1.0));
/// ```
#[must_use]
pub fn reflect_with_cosine<T: Real>(d: T::Vec3, n: T::Vec3) -> (T::Vec3, T) {
    let d_hat = d * (T::ONE / T::dot(d, d).sqrt());
    let cos = T::dot(n, d_hat);
    (d_hat - n * (T::TWO * cos), cos)
}

/// A secondary-ray origin that cannot re-hit the surface it leaves: the (reprojected) hit point
/// pushed off the surface along the normal, to the side `new_dir` leaves by.
///
/// The push is `256 ε · max(‖p‖∞, 1/2)` along the unit normal. The rounding error of a computed
/// point grows with its coordinates, so the push is a fixed number of ulps (at least 256) of the
/// largest coordinate; near the world origin, where ulps become too fine to cover the error of the
/// arithmetic that produced the point, it stays at `128 ε` (`2⁻¹⁶` in `f32`). These are the
/// constants of Wächter & Binder (Ray Tracing Gems ch. 6), who push each coordinate by 256 of its
/// own ulps through its bit pattern; pushing every coordinate by the largest one's amount is never
/// less, and costs one multiply-add per coordinate. Combined with reprojection ([`surface_hit`])
/// it gives 0 self-hits in 10⁶ reflected rays in each test scenario (near, far, huge and tiny
/// spheres, translated scenes); either alone does not.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::sphere::spawn_origin;
/// let p = DVec3::new(0.0, 0.0, 1.0);
/// let out = spawn_origin::<f64>(p, DVec3::Z, DVec3::Z);
/// assert!(out.z > 1.0); // moved outward, the side the new ray leaves by
/// let inward = spawn_origin::<f64>(p, DVec3::Z, -DVec3::Z);
/// assert!(inward.z < 1.0);
/// ```
#[must_use]
pub fn spawn_origin<T: Real>(point: T::Vec3, normal: T::Vec3, new_dir: T::Vec3) -> T::Vec3 {
    offset_along::<T>(point, normal, T::dot(normal, new_dir) >= T::ZERO)
}

/// The push of [`spawn_origin`] along the unit `normal`: to the side it points to when
/// `with_normal`, else to the other side.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::sphere::offset_along;
/// assert!(offset_along::<f64>(DVec3::new(0.0, 0.0, 1.0), DVec3::Z, true).z > 1.0);
/// assert!(offset_along::<f64>(DVec3::new(0.0, 0.0, 1.0), DVec3::Z, false).z < 1.0);
/// ```
#[must_use]
pub fn offset_along<T: Real>(point: T::Vec3, normal: T::Vec3, with_normal: bool) -> T::Vec3 {
    let [x, y, z] = T::components(point);
    let push = T::from_f64(256.0) * T::EPSILON * x.abs().max(y.abs()).max(z.abs()).max(T::from_f64(0.5));
    point + normal * if with_normal { push } else { -push }
}

/// A first hit with error bounds: what [`first_hit_stable`], [`surface_hit`] and
/// [`reflect_with_cosine`] compute, each number with a bound on its distance from the exact
/// answer of the problem (pbrt's way of carrying a computed intersection with its error: Pharr,
/// Jakob & Humphreys, *Physically Based Rendering*, 4th ed., §6.8).
///
/// The values are bit for bit those of the plain solver; the bounds are in `f64` and hold for the
/// exact inputs the solver was given ([`bounded_first_hit`]) or, from `f64` inputs rounded to a
/// narrower `T`, for those `f64` inputs ([`bounded_first_hit_from_f64`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundedHit<T: Real> {
    /// The ray parameter of the first hit, as [`first_hit_stable`] computes it.
    pub t: T,
    /// `|t − t_exact| ≤ t_error`.
    pub t_error: f64,
    /// The hit point, reprojected onto the sphere as [`surface_hit`] computes it.
    pub point: T::Vec3,
    /// Per component, `|point − p_exact| ≤ point_error`, with `p_exact = e + d t_exact`.
    pub point_error: [f64; 3],
    /// The outward unit normal, as [`surface_hit`] computes it.
    pub normal: T::Vec3,
    /// Per component, `|normal − (p_exact − o)/r| ≤ normal_error`.
    pub normal_error: [f64; 3],
    /// The unit reflected direction `d̂ − 2(n̂·d̂)n̂`, as [`reflect_with_cosine`] computes it.
    pub reflected: T::Vec3,
    /// Per component, the bound on its distance from the exact reflection.
    pub reflected_error: [f64; 3],
}

/// What rounding leaves undecided, with the numbers that decide it ([`bounded_first_hit`]).
///
/// # Examples
/// ```
/// use hw3_core::geometry::sphere::Unresolved;
/// let edge = Unresolved::HitOrMiss { discriminant: 1e-9, error: 3e-9 };
/// assert!(edge.to_string().contains("1e-9 ± 3e-9"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Unresolved {
    /// The ray passes within rounding of the sphere's outline: the scaled discriminant
    /// `r²|d|² − |(e − o) × d|²` is `discriminant ± error` with `error ≥ |discriminant|`, so it may
    /// be negative (a miss) or not (a hit).
    HitOrMiss {
        /// The computed `r²|d|² − |(e − o) × d|²`.
        discriminant: f64,
        /// Its error bound.
        error: f64,
    },
    /// The eye is within rounding of the sphere: the root that decides the first hit is
    /// `root ± error` with `error ≥ |root|`, on either side of the eye (`t = 0`).
    EyeOnSurface {
        /// The computed root.
        root: f64,
        /// Its error bound.
        error: f64,
    },
    /// The hit point is known only to within `point_error` (the length of its error bound), at
    /// least the sphere's diameter: every point of the sphere fits the bound, the other side
    /// included.
    OtherSide {
        /// The length of the hit point's error bound.
        point_error: f64,
        /// The sphere's diameter `2r`.
        diameter: f64,
    },
    /// An error bound is not finite: a quotient whose divisor may be 0 (the computed vector from
    /// the centre to the hit rounds to 0), or a coordinate near the largest float.
    Unbounded,
}

impl std::fmt::Display for Unresolved {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Unresolved::HitOrMiss { discriminant, error } => write!(
                f,
                "the ray passes within rounding of the sphere's edge: r²|d|² − |(e − o) × d|² = {} ± {}, so hit \
                 and miss cannot be told apart",
                short(discriminant),
                short(error)
            ),
            Unresolved::EyeOnSurface { root, error } => write!(
                f,
                "the eye is within rounding of the sphere: the root t = {} ± {} may be on either side of the eye \
                 (t = 0), so the first hit cannot be told",
                short(root),
                short(error)
            ),
            Unresolved::OtherSide { point_error, diameter } => write!(
                f,
                "the hit point is known only to within {}, at least the sphere's diameter {}: every point of the \
                 sphere fits that bound, the other side included",
                short(point_error),
                short(diameter)
            ),
            Unresolved::Unbounded => write!(
                f,
                "an error bound is not finite (the vector from the centre to the hit is lost to rounding, or a \
                 number nears the largest float)"
            ),
        }
    }
}

/// The answer of [`bounded_first_hit`]: a hit with its bounds, a miss, or what rounding leaves
/// undecided.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BoundedOutcome<T: Real> {
    /// The first hit `t > 0`, with error bounds.
    Hit(BoundedHit<T>),
    /// Certainly no hit `t > 0`: the line misses the sphere, or both roots are `≤ 0`.
    Miss,
    /// No answer within the error bound exists.
    Unresolved(Unresolved),
}

impl<T: Real> BoundedOutcome<T> {
    /// The hit, if any; [`Unresolved`] becomes [`InputError::Unresolvable`] with its reason.
    ///
    /// # Errors
    /// [`InputError::Unresolvable`] for [`BoundedOutcome::Unresolved`].
    pub fn into_result(self) -> Result<Option<BoundedHit<T>>, InputError> {
        match self {
            BoundedOutcome::Hit(hit) => Ok(Some(hit)),
            BoundedOutcome::Miss => Ok(None),
            BoundedOutcome::Unresolved(why) => {
                Err(InputError::Unresolvable { precision: T::NAME, reason: why.to_string() })
            }
        }
    }
}

/// The first hit by the stable method, with error bounds on `t`, the hit point, the normal and
/// the reflected direction, computed from the actual inputs; or a miss; or, where no answer
/// within the bound exists, what is undecided.
///
/// The inputs (`ray`, `sphere`) are taken as exact: the bounds are on the distance from the exact
/// answer for them. [`bounded_first_hit_from_f64`] also covers the rounding of `f64` inputs to `T`.
///
/// # Numerics
/// Every quantity of [`roots_stable`], [`surface_hit`] and [`reflect_with_cosine`] is evaluated in
/// the same order in precision `T`, carried with a bound on its distance from its exact value
/// (running error analysis, Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed.,
/// §3.3; the same information as pbrt-v4's `Interval`, §6.8, whose `Sphere::BasicIntersect` runs
/// this quadratic in intervals). One operation `z = x ∘ y` adds the operands' bounds carried
/// through the exact operation, and its own rounding: the exact amount where an error-free
/// transformation gives it (TwoSum, TwoProduct), so that an exact operation adds nothing, and
/// otherwise pbrt's `γ₁|z̃|`, with `γₙ = n u/(1 − n u)` and `u = ε/2` (pbrt-v4 §6.8.1).
///
/// To first order, with `u` the unit roundoff, `f = e − o`, `|d|` the direction's length and
/// `ℓ = h|d|` the half-chord's length, the error comes from:
/// - `f = e − o`, off by at most `u|fᵢ|` per component, and `f × d`, off by a few `u|f||d|`;
/// - the scaled discriminant `Q = r²|d|² − |f × d|²` (which is `|d|² ℓ²`), off by about
///   `2|f × d|·|Δ(f × d)|` plus a few `u r²|d|²`: a few `u r|d|²(|f| + r)`, as `|f × d| ≤ r|d|`
///   on a hit;
/// - the half-chord `h = √Q/|d|²`, off by `|ΔQ|/(2|d|³ℓ)`, a few `u r(|f| + r)/(|d|ℓ)`: the
///   grazing amplification `r/ℓ`, without bound at the sphere's outline;
/// - the closest approach `t_ca = −(f·d)/|d|²`, off by a few `u|f|/|d|`;
/// - so a root `t_ca ∓ h` is off by a few `u|f|(1 + r/ℓ)/|d|`, plus `u|t|` for its own rounding.
///   For a sphere far away (`|f| = s ≫ r`) that is of order `10 u s/|d|` when hit half a radius
///   off its centre: the error grows with the distance, not with the distance over the radius,
///   which is why a unit sphere `10⁵` away is within reach of `f32` (`u s ≈ 6·10⁻³`). The bound
///   computed at run time is usually below this estimate, as it takes each operation's actual
///   rounding: `2.6·10⁻²` for `t` there, about `4 u s`, the rounding of the inputs to `f32`
///   included. Where Press's product `C/(A t_far)` replaces a root (an eye near the sphere), its
///   relative error is that of `C = f·f − r²`, a few `u|f|²/|C|`: with the eye within a few units
///   of an `r = 10⁶` sphere in `f32`, `C` is rounding noise.
///
/// The hit point `e + d t` is off by `|d||Δt|` plus the rounding of coordinates the size of `e`
/// and `d t`. Reprojecting it onto the sphere, `p = o + r R̃/|R̃|` with `R̃ = e + d t − o`, moves
/// it from the exact hit `o + r R/|R|` by at most `r` times the distance between the directions of
/// `R̃` and `R`, which is bounded by the smaller of Dunkl & Williams' `2|R̃ − R|/(|R̃| + |R|)`
/// ("A simple norm inequality", *Amer. Math. Monthly* 71, 1964) and the chord `2 sin(θ/2)` of the
/// angle between them, whose sine is the part of `R̃ − R` across `R̃` over `|R|`: an error along
/// `R̃` (a ray aimed at the centre, its `t` off) does not move the reprojected point. Per
/// component the point keeps the smaller of that and the bound carried through the formulas. This
/// is the distance from the *exact hit*, not only from the surface: pbrt's `γ₅|p|` (§6.8.5)
/// bounds the latter, which is what a spawned ray needs; an answer needs the former.
///
/// # Refusals
/// The bound decides, as pbrt-v4's sphere does with its intervals (§6.8.7): the line hits the
/// sphere when the discriminant's lower bound is `≥ 0` and misses when its upper bound is `< 0`; a
/// root is a hit when its lower bound is `> 0` and is not when its upper bound is `≤ 0` (a root at
/// exactly 0 is the eye, as in [`first_hit_stable`]). Where pbrt then takes the safe side (a miss,
/// or the other root), this solver reports [`Unresolved`], because either answer may be wrong by
/// more than its bound:
/// - [`Unresolved::HitOrMiss`]: the discriminant's bound straddles 0;
/// - [`Unresolved::EyeOnSurface`]: the deciding root's bound straddles 0;
/// - [`Unresolved::OtherSide`]: the hit point's bound is at least the sphere's diameter;
/// - [`Unresolved::Unbounded`]: a bound overflows.
///
/// # Errors
/// [`InputError::Unresolvable`] where [`check_solvable`] refuses the case (a square overflows or
/// underflows).
///
/// # Examples
/// A unit sphere `10⁵` away in `f32`: the two sides are 256 spacings of `f32` apart there, and
/// the answer comes with its bound.
/// ```
/// use glam::Vec3;
/// use hw3_core::geometry::{Ray, Sphere, sphere::{BoundedOutcome, bounded_first_hit}};
/// let ray = Ray::<f32>::new(Vec3::new(-1e5, 0.5, 0.0), Vec3::X).unwrap();
/// let sphere = Sphere::<f32>::new(Vec3::ZERO, 1.0).unwrap();
/// let BoundedOutcome::Hit(hit) = bounded_first_hit(&ray, &sphere).unwrap() else { panic!() };
/// let exact = 1e5 - 0.75f64.sqrt();
/// assert!((f64::from(hit.t) - exact).abs() <= hit.t_error);
/// assert!(hit.t_error < 0.01);
/// ```
pub fn bounded_first_hit<T: Real>(ray: &Ray<T>, sphere: &Sphere<T>) -> Result<BoundedOutcome<T>, InputError> {
    check_solvable(ray, sphere)?;
    let exact = |v: T::Vec3| T::components(v).map(tracked::Tracked::exact);
    Ok(bounded(exact(ray.origin), exact(ray.dir), exact(sphere.center), tracked::Tracked::exact(sphere.radius)))
}

/// [`bounded_first_hit`] for a problem given in `f64` and solved in `T`: the inputs are rounded to
/// `T`, and the bounds are on the distance from the exact answer of the `f64` problem, the rounding
/// of the inputs included.
///
/// # Errors
/// [`InputError::Unresolvable`] for an input beyond `T`'s largest finite value (it would round to
/// ∞); [`InputError`] if the rounded ray or sphere is not valid in `T` (a direction whose squared
/// length underflows), or where [`check_solvable`] refuses the rounded case.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::{Ray, Sphere, sphere::{BoundedOutcome, bounded_first_hit_from_f64}};
/// // 0.1 is not an f32 number: the bound covers its rounding too.
/// let ray = Ray::<f64>::new(DVec3::new(-5.0, 0.1, 0.0), DVec3::X).unwrap();
/// let sphere = Sphere::<f64>::new(DVec3::ZERO, 1.0).unwrap();
/// let BoundedOutcome::Hit(hit) = bounded_first_hit_from_f64::<f32>(&ray, &sphere).unwrap() else { panic!() };
/// let exact = 5.0 - (1.0f64 - 0.01).sqrt();
/// assert!((f64::from(hit.t) - exact).abs() <= hit.t_error);
/// ```
pub fn bounded_first_hit_from_f64<T: Real>(
    ray: &Ray<f64>,
    sphere: &Sphere<f64>,
) -> Result<BoundedOutcome<T>, InputError> {
    let inputs = [("origin", ray.origin), ("direction", ray.dir), ("centre", sphere.center)]
        .into_iter()
        .flat_map(|(name, v)| v.to_array().map(|x| (name, x)))
        .chain([("radius", sphere.radius)]);
    for (name, x) in inputs {
        if x.abs() > T::MAX.to_f64() {
            let reason =
                format!("the {name} has {x:e}, beyond the largest {} number, {:.7e}", T::NAME, T::MAX.to_f64());
            return Err(InputError::Unresolvable { precision: T::NAME, reason });
        }
    }
    let narrow = Ray::<T>::new(T::vec_from_f64(ray.origin), T::vec_from_f64(ray.dir))?;
    let narrow_sphere = Sphere::<T>::new(T::vec_from_f64(sphere.center), T::from_f64(sphere.radius))?;
    check_solvable(&narrow, &narrow_sphere)?;
    let rounded = |v: glam::DVec3| v.to_array().map(tracked::Tracked::rounded);
    Ok(bounded(rounded(ray.origin), rounded(ray.dir), rounded(sphere.center), tracked::Tracked::rounded(sphere.radius)))
}

/// The bounded solver on tracked inputs: [`roots_stable`], [`surface_hit`] and
/// [`reflect_with_cosine`] step by step, in their order of operations.
fn bounded<T: Real>(
    e: tracked::Vec3<T>,
    d: tracked::Vec3<T>,
    o: tracked::Vec3<T>,
    r: tracked::Tracked<T>,
) -> BoundedOutcome<T> {
    use tracked::{Tracked, add, cross, dot, errors, norm, scale, sub, up, value};
    let constant = |x: f64| Tracked::exact(T::from_f64(x));
    let o_input_error = errors(o);
    let input_error = norm(o_input_error);
    // roots_stable
    let f = sub(e, o);
    let a = dot(d, d);
    let r2 = r.mul(r);
    let perpendicular = cross(f, d);
    let disc_times_a = r2.mul(a).sub(dot(perpendicular, perpendicular));
    if disc_times_a.v.to_f64() < -disc_times_a.e {
        return BoundedOutcome::Miss;
    }
    if !disc_times_a.is_finite() {
        return BoundedOutcome::Unresolved(Unresolved::Unbounded);
    }
    if !(disc_times_a.v.to_f64() >= disc_times_a.e) {
        return BoundedOutcome::Unresolved(Unresolved::HitOrMiss {
            discriminant: disc_times_a.v.to_f64(),
            error: disc_times_a.e,
        });
    }
    let inv_a = constant(1.0).div(a);
    let t_ca = dot(f, d).neg().mul(inv_a);
    let h = disc_times_a.sqrt().mul(inv_a);
    let (mut near, mut far) = (t_ca.sub(h), t_ca.add(h));
    if h.v != T::ZERO && h.v > t_ca.v.abs() * T::from_f64(0.5) {
        let c_over_a = dot(f, f).sub(r2).mul(inv_a);
        if t_ca.v >= T::ZERO {
            near = c_over_a.div(far);
        } else {
            far = c_over_a.div(near);
        }
    }
    // The exact roots satisfy near ≤ far, whatever the computed values.
    let t = if far.certainly_not_positive() {
        return BoundedOutcome::Miss;
    } else if near.certainly_positive() {
        near
    } else if near.certainly_not_positive() && far.certainly_positive() {
        far
    } else {
        let open = if near.certainly_not_positive() { far } else { near };
        if !open.is_finite() {
            return BoundedOutcome::Unresolved(Unresolved::Unbounded);
        }
        return BoundedOutcome::Unresolved(Unresolved::EyeOnSurface { root: open.v.to_f64(), error: open.e });
    };
    // surface_hit, bounded two ways, each valid, and the smaller bound kept per component:
    // - carried through: `radial` is tracked against the exact R = e + d t − o of the exact hit,
    //   and at the exact values the formulas are exact (|R| = r, so the Newton step's ratio is 1
    //   and 1.5 − 0.5 = 1 = r/|R|);
    // - reprojected: the rounding of o + r R̃/|R̃| from the computed R̃ (R̃, o, r taken as exact,
    //   the Newton step's truncation added), plus the distance from that exact reprojection of R̃
    //   to the exact hit point, |r̃ R̂̃ − r R̂| ≤ |r̃ − r| + r |R̂̃ − R̂|, with the distance between
    //   the directions bounded by [`direction_bound`].
    let radial = sub(add(e, scale(d, t)), o);
    let (carried_point, carried_normal) = surface::<T>(radial, o, r, false);
    let (r_value, r_error) = (r.v.to_f64(), r.e);
    let direction_error = direction_bound::<T>(radial, r_value - r_error);
    let projection_error = up(r_error + up(up(r_value + r_error) * direction_error));
    let exact = |v: tracked::Vec3<T>| v.map(|c| Tracked::exact(c.v));
    let (point, normal) = surface::<T>(exact(radial), exact(o), Tracked::exact(r.v), true);
    let diameter = 2.0 * r_value;
    let reprojected = up(projection_error + norm(errors(point)) + input_error);
    let point_error = reprojected.min(norm(errors(carried_point)));
    if point_error.is_nan() {
        // Both bounds failed: the computed vector from the centre to the hit is 0 or not finite.
        return BoundedOutcome::Unresolved(Unresolved::Unbounded);
    }
    if !(point_error < diameter) {
        return BoundedOutcome::Unresolved(Unresolved::OtherSide { point_error, diameter });
    }
    let point_errors =
        std::array::from_fn(|i| up(point[i].e + o_input_error[i] + projection_error).min(carried_point[i].e));
    let normal: tracked::Vec3<T> =
        std::array::from_fn(|i| Tracked { e: up(normal[i].e + direction_error).min(carried_normal[i].e), ..normal[i] });
    // reflect_with_cosine, on the normal with its whole bound and the direction with its own.
    let d_hat = scale(d, constant(1.0).div(dot(d, d).sqrt()));
    let cos = dot(normal, d_hat);
    let reflected = sub(d_hat, scale(normal, constant(2.0).mul(cos)));
    let hit = BoundedHit {
        t: t.v,
        t_error: t.e,
        point: value(point),
        point_error: point_errors,
        normal: value(normal),
        normal_error: errors(normal),
        reflected: value(reflected),
        reflected_error: errors(reflected),
    };
    let all = [hit.t_error].into_iter().chain(hit.point_error).chain(hit.normal_error).chain(hit.reflected_error);
    if !all.into_iter().all(f64::is_finite) || !t.v.is_finite() {
        return BoundedOutcome::Unresolved(Unresolved::Unbounded);
    }
    BoundedOutcome::Hit(hit)
}

/// A bound on `|R̂̃ − R̂|`, the distance between the directions of the computed `radial` vector
/// `R̃` and of the exact `R` it stands for, of length at least `r_low`: the smaller of
/// - Dunkl & Williams' `2|R̃ − R|/(|R̃| + |R|)` ("A simple norm inequality", *Amer. Math.
///   Monthly* 71, 1964), which holds for any two vectors;
/// - the chord `2 sin(θ/2)` of the angle `θ` between them, where it is below 90° (certain when
///   `Σ|R̃ᵢ| eᵢ < |R̃|²`): `sin θ` is the part of `R − R̃` across `R̃` over `|R|`, at most
///   `Σ eᵢ √(1 − R̂̃ᵢ²)/r_low`. An error along `R̃` (the ray aimed at the centre, its `t` off)
///   does not move the direction at all.
fn direction_bound<T: Real>(radial: tracked::Vec3<T>, r_low: f64) -> f64 {
    use tracked::{down, errors, norm, up, value};
    let error = errors(radial);
    let c = T::components(value(radial)).map(Real::to_f64);
    let squares = c.map(|x| x * x);
    let length_squared: f64 = squares.iter().sum();
    if !length_squared.is_finite() {
        return f64::INFINITY;
    }
    let r_low = r_low.max(0.0);
    let dunkl_williams = up(2.0 * norm(error)) / down(down(length_squared.sqrt()) + r_low);
    let along: f64 = (0..3).map(|i| c[i].abs() * error[i]).sum();
    if !(up(along) < down(length_squared)) || !(r_low > 0.0) {
        return dunkl_williams;
    }
    let across: f64 = (0..3)
        .map(|i| {
            let others = up(squares[(i + 1) % 3] + squares[(i + 2) % 3]);
            error[i] * up(up(others / down(length_squared)).sqrt())
        })
        .sum();
    let sine = (up(across) / down(r_low)).min(1.0);
    let cosine = down(down((1.0 - up(sine * sine)).max(0.0)).sqrt());
    let chord = up(sine * up(up(2.0 / down(1.0 + cosine)).sqrt()));
    dunkl_williams.min(chord)
}

/// [`surface_hit`]'s point and normal from `radial = e + d t − o`, on tracked values, in its order
/// of operations. With `newton_truncation`, the Newton step's truncation error is added: needed
/// where `radial` is taken as exact, so that `|radial| ≠ r`.
fn surface<T: Real>(
    radial: tracked::Vec3<T>,
    o: tracked::Vec3<T>,
    r: tracked::Tracked<T>,
    newton_truncation: bool,
) -> (tracked::Vec3<T>, tracked::Vec3<T>) {
    use tracked::{Tracked, add, dot, scale, up};
    let constant = |x: f64| Tracked::exact(T::from_f64(x));
    let inv_r = constant(1.0).div(r);
    let length_squared = dot(radial, radial);
    let ratio = length_squared.mul(inv_r).mul(inv_r);
    let delta = ratio.sub(constant(1.0));
    let r_over_length = if delta.v.abs() < T::EPSILON.sqrt() {
        // One Newton step for 1/√(1 + δ) from 1: its truncation error is at most
        // (3/8) ξ^(−5/2) δ² ≤ 3 δ² for |δ| ≤ 1/2 (Taylor's remainder).
        let newton = constant(1.5).sub(constant(0.5).mul(ratio));
        let delta_bound = delta.v.to_f64().abs() + delta.e;
        let truncation = match (newton_truncation, delta_bound <= 0.5) {
            (false, _) => 0.0,
            (true, true) => 3.0 * delta_bound * delta_bound,
            (true, false) => f64::INFINITY,
        };
        Tracked { e: up(newton.e + truncation), ..newton }
    } else {
        r.div(length_squared.sqrt())
    };
    (add(o, scale(radial, r_over_length)), scale(radial, inv_r.mul(r_over_length)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec3, Vec3};

    fn ray64(e: [f64; 3], d: [f64; 3]) -> Ray<f64> {
        Ray::new(DVec3::from(e), DVec3::from(d)).unwrap()
    }

    /// `Ray` and `Sphere` are plain data: a non-finite value written into one is a miss for the
    /// first-hit solver, never a NaN or infinite parameter.
    #[test]
    fn non_finite_rays_and_spheres_are_misses() {
        let ray = Ray { origin: DVec3::new(-5.0, 0.5, 0.0), dir: DVec3::X };
        let sphere = Sphere { center: DVec3::ZERO, radius: 1.0 };
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let cases = [
                (Ray { origin: DVec3::new(bad, 0.5, 0.0), ..ray }, sphere),
                (Ray { dir: DVec3::new(1.0, bad, 0.0), ..ray }, sphere),
                (ray, Sphere { center: DVec3::new(0.0, bad, 0.0), ..sphere }),
                (ray, Sphere { radius: bad, ..sphere }),
            ];
            for (ray, sphere) in cases {
                assert_eq!(first_hit_stable(&ray, &sphere), None, "{ray:?} {sphere:?}");
            }
        }
    }

    /// The discriminant's error model: the perpendicular vector `f × d` carries `ε|f||d|` of
    /// rounding, which the square root amplifies by `r/h` near a silhouette. Over random grazing
    /// rays the `f32` near root stays within that bound of the exact root of the rounded input, and
    /// its mean error is a few ulps (measured 1.1e-7 at distance 5, 7e-8 at 1000).
    #[test]
    fn grazing_roots_match_the_f64_reference_statistically() {
        let mut generator = crate::rng::seeded(7, 0);
        let mut uniform = |low, high| crate::rng::uniform_in(&mut generator, low, high);
        for distance in [5.0, 1e3] {
            let (mut sum, mut count) = (0.0, 0);
            for _ in 0..20_000 {
                let d = DVec3::new(uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0)) * uniform(0.5, 1.5);
                let e = DVec3::new(uniform(0.0, 3.0), uniform(0.0, 3.0), uniform(0.0, 3.0));
                let o = e + d.normalize() * distance + d.any_orthonormal_vector() * uniform(0.99, 1.0);
                let ray32 = Ray::<f32>::new(e.as_vec3(), d.as_vec3()).unwrap();
                let sphere32 = Sphere::<f32>::new(o.as_vec3(), 1.0).unwrap();
                let widened = Ray::<f64>::new(ray32.origin.as_dvec3(), ray32.dir.as_dvec3()).unwrap();
                let reference = roots_stable(&widened, &Sphere::new(sphere32.center.as_dvec3(), 1.0).unwrap());
                let (Some(exact), Some(rounded)) = (reference, roots_stable(&ray32, &sphere32)) else { continue };
                let f = (widened.origin - o).length();
                let a = widened.dir.length_squared();
                let h = (exact.far - exact.near) / 2.0;
                let bound = 2.0 * f64::from(f32::EPSILON) * (f / (h * a) + exact.near.abs());
                let error = (f64::from(rounded.near) - exact.near).abs();
                assert!(error <= bound, "distance {distance}: error {error:e} > bound {bound:e}");
                sum += error / exact.near.abs();
                count += 1;
            }
            assert!(count > 5_000, "{count} hits");
            let mean = sum / f64::from(count);
            assert!(mean < 2e-7, "distance {distance}: mean relative error {mean:e}");
        }
    }

    #[test]
    fn documents_policy_root_at_zero_is_not_a_hit() {
        let sphere = Sphere::<f64>::new(DVec3::ZERO, 1.0).unwrap();
        let outward = ray64([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]);
        assert_eq!(first_hit_stable(&outward, &sphere), None);
        let inward = ray64([0.0, 0.0, 1.0], [0.0, 0.0, -1.0]);
        assert_eq!(first_hit_stable(&inward, &sphere), Some(2.0));
    }

    #[test]
    fn documents_policy_tangent_is_a_hit_and_tangent_on_surface_is_not() {
        let sphere = Sphere::<f64>::new(DVec3::ZERO, 1.0).unwrap();
        let tangent = ray64([-3.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
        assert_eq!(first_hit_stable(&tangent, &sphere), Some(3.0));
        let on_surface = ray64([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
        assert_eq!(roots_stable(&on_surface, &sphere), Some(Roots { near: 0.0, far: 0.0 }));
        assert_eq!(first_hit_stable(&on_surface, &sphere), None);
    }

    #[test]
    fn documents_policy_sphere_behind_is_a_miss() {
        let sphere = Sphere::<f64>::new(DVec3::new(0.0, 0.0, -5.0), 1.0).unwrap();
        let ray = ray64([0.0; 3], [0.0, 0.0, 1.0]);
        let roots = roots_stable(&ray, &sphere).unwrap();
        assert_eq!((roots.near, roots.far), (-6.0, -4.0));
        assert_eq!(first_hit_stable(&ray, &sphere), None);
    }

    #[test]
    fn surface_hit_puts_the_point_on_the_sphere_for_accurate_and_inaccurate_t() {
        let sphere = Sphere::<f64>::new(DVec3::new(1.0, -2.0, 3.0), 2.5).unwrap();
        let ray = ray64([-10.0, -1.0, 2.0], [1.0, 0.05, 0.1]);
        let t = first_hit_stable(&ray, &sphere).unwrap();
        // Exact t (Newton branch), t off by 1e-6 (Newton branch), t off by 0.3 (square-root branch).
        for t in [t, t + 1e-6, t - 0.3] {
            let hit = surface_hit(&ray, &sphere, t);
            let off = ((hit.point - sphere.center).length() - sphere.radius).abs();
            assert!(off <= 4.0 * f64::EPSILON * sphere.radius, "t = {t}: off by {off:e}");
            assert!((hit.normal.length() - 1.0).abs() <= 4.0 * f64::EPSILON);
        }
    }

    #[test]
    fn reflect_is_unit_and_preserves_angle() {
        let n = DVec3::new(0.0, 1.0, 0.0);
        let d = DVec3::new(3.0, -4.0, 0.0);
        let r = reflect::<f64>(d, n);
        assert!((r.length() - 1.0).abs() < 1e-15);
        assert!((r.dot(n) + d.normalize().dot(n)).abs() < 1e-15);
    }

    #[test]
    fn spawn_origin_pushes_at_least_256_ulps_of_the_largest_coordinate() {
        let p = Vec3::new(-3.0e3, 20.0, 0.5);
        let n = Vec3::new(0.0, 0.6, 0.8);
        let moved = spawn_origin::<f32>(p, n, n);
        let push = (moved - p).dot(n);
        let ulp_of_largest = f32::EPSILON * 2048.0; // spacing of floats in [2048, 4096)
        assert!(push >= 256.0 * ulp_of_largest * 0.99, "push {push:e}");
        assert!(push <= 2.0 * 256.0 * ulp_of_largest, "push {push:e}");
        let near_origin = spawn_origin::<f32>(Vec3::new(0.01, 0.0, 0.0), Vec3::X, -Vec3::X);
        assert_eq!(near_origin.x, 0.01 - 128.0 * f32::EPSILON);
    }

    #[test]
    fn spawn_origin_leaves_the_surface_in_f32_far_from_world_origin() {
        let p = Vec3::new(1.0e4, 2.0e4, -3.0e4);
        let n = Vec3::new(0.6, 0.0, 0.8);
        let out = spawn_origin::<f32>(p, n, n);
        assert!((out - p).dot(n) > 0.0);
    }

    fn hit<T: Real>(outcome: BoundedOutcome<T>) -> BoundedHit<T> {
        match outcome {
            BoundedOutcome::Hit(hit) => hit,
            other => panic!("expected a hit, got {other:?}"),
        }
    }

    /// The bounded solver reports the plain solvers' own numbers, bit for bit: the bound belongs
    /// to the value every other caller computes.
    fn values_are_the_plain_solvers<T: Real>(widen: impl Fn(DVec3) -> T::Vec3) {
        let mut generator = crate::rng::seeded(3, 1);
        let mut uniform = |low, high| crate::rng::uniform_in(&mut generator, low, high);
        let (mut hits, mut misses) = (0, 0);
        for _ in 0..20_000 {
            let scale = 10f64.powf(uniform(-3.0, 6.0));
            let e = DVec3::new(uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0)) * scale;
            let o = DVec3::new(uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0)) * scale;
            let r = uniform(0.05, 1.0) * scale * 10f64.powf(uniform(-4.0, 0.0));
            let aim = o + DVec3::new(uniform(-1.5, 1.5), uniform(-1.5, 1.5), uniform(-1.5, 1.5)) * r - e;
            let (Ok(ray), Ok(sphere)) =
                (Ray::<T>::new(widen(e), widen(aim)), Sphere::<T>::new(widen(o), T::from_f64(r)))
            else {
                continue;
            };
            match bounded_first_hit(&ray, &sphere).unwrap() {
                BoundedOutcome::Hit(bounded) => {
                    hits += 1;
                    assert_eq!(Some(bounded.t), first_hit_stable(&ray, &sphere), "{ray:?} {sphere:?}");
                    let frame = surface_hit(&ray, &sphere, bounded.t);
                    assert_eq!((bounded.point, bounded.normal), (frame.point, frame.normal));
                    assert_eq!(bounded.reflected, reflect_with_cosine::<T>(ray.dir, frame.normal).0);
                }
                BoundedOutcome::Miss => {
                    misses += 1;
                    assert_eq!(first_hit_stable(&ray, &sphere), None, "{ray:?} {sphere:?}");
                }
                BoundedOutcome::Unresolved(_) => {}
            }
        }
        assert!(hits > 5_000 && misses > 2_000, "{hits} hits, {misses} misses");
    }

    #[test]
    fn bounded_values_are_the_plain_solvers_bit_for_bit() {
        values_are_the_plain_solvers::<f64>(|v| v);
        values_are_the_plain_solvers::<f32>(|v| v.as_vec3());
    }

    /// Where every operation is exact, the bound is 0: an exact tangent is a hit, an eye exactly on
    /// the surface is not one (t = 0), and the answers of the worked policy cases are exact.
    #[test]
    fn exact_cases_have_zero_bounds_and_keep_the_policies() {
        let unit = Sphere::<f64>::new(DVec3::ZERO, 1.0).unwrap();
        let tangent = hit(bounded_first_hit(&ray64([-3.0, 1.0, 0.0], [1.0, 0.0, 0.0]), &unit).unwrap());
        assert_eq!((tangent.t, tangent.t_error), (3.0, 0.0));
        assert_eq!((tangent.point, tangent.point_error), (DVec3::Y, [0.0; 3]));
        let inside = hit(bounded_first_hit(&ray64([0.0; 3], [0.0, 0.0, 2.0]), &unit).unwrap());
        assert_eq!((inside.t, inside.t_error), (0.5, 0.0));
        let behind = bounded_first_hit(&ray64([0.0, 0.0, 5.0], [0.0, 0.0, 1.0]), &unit).unwrap();
        assert_eq!(behind, BoundedOutcome::Miss);
        let outside = bounded_first_hit(&ray64([0.0, 2.0, -5.0], [0.0, 0.0, 1.0]), &unit).unwrap();
        assert_eq!(outside, BoundedOutcome::Miss);
        // The eye on a sphere of radius 5 (e − o = (3, 4, 0)): C = 0 exactly, and the root t = 0
        // is the eye.
        let sphere = Sphere::<f64>::new(DVec3::new(1.0, 2.0, 3.0), 5.0).unwrap();
        let inward = hit(bounded_first_hit(&ray64([4.0, 6.0, 3.0], [-1.0, 0.0, 0.0]), &sphere).unwrap());
        assert_eq!((inward.t, inward.t_error), (6.0, 0.0));
        let outward = bounded_first_hit(&ray64([4.0, 6.0, 3.0], [1.0, 0.0, 0.0]), &sphere).unwrap();
        assert_eq!(outward, BoundedOutcome::Miss);
    }

    /// The defect this solver answers: a unit sphere 10⁵ away in f32 was refused ("cannot be told
    /// apart from the other side"); its sides are 256 f32 spacings apart, and the answer holds to
    /// its bound, as at 10⁶ and 10⁷.
    #[test]
    fn a_far_small_sphere_in_f32_is_answered_within_its_bound() {
        let sphere = Sphere::<f32>::new(Vec3::ZERO, 1.0).unwrap();
        for distance in [1e5f32, 1e6, 1e7] {
            let ray = Ray::<f32>::new(Vec3::new(-distance, 0.5, 0.0), Vec3::X).unwrap();
            let answer = hit(bounded_first_hit(&ray, &sphere).unwrap());
            let exact_t = f64::from(distance) - 0.75f64.sqrt();
            let error = (f64::from(answer.t) - exact_t).abs();
            assert!(error <= answer.t_error && answer.t_error < 2.0 * error.max(1e-9), "{distance}: {answer:?}");
            let exact_point = DVec3::new(-(0.75f64.sqrt()), 0.5, 0.0);
            for i in 0..3 {
                let off = (f64::from(answer.point[i]) - exact_point[i]).abs();
                assert!(off <= answer.point_error[i], "{distance}: {answer:?}");
            }
        }
    }

    #[test]
    fn refusals_name_what_rounding_leaves_undecided() {
        // The eye as parsed is 2e-17 outside the unit sphere, but f·f − r² rounds to 0.
        let on_surface =
            bounded_first_hit(&ray64([0.6, 0.8, 0.0], [-1.0, 0.0, 0.0]), &Sphere::new(DVec3::ZERO, 1.0).unwrap());
        assert!(
            matches!(on_surface, Ok(BoundedOutcome::Unresolved(Unresolved::EyeOnSurface { .. }))),
            "{on_surface:?}"
        );
        // 10¹⁷ away along an oblique ray, where f64's spacing is 16: e − o, and with it the
        // ray's distance from the centre, is rounded by more than the radius.
        let eye = DVec3::new(-7.1e16, 3.3e16, 2.9e16);
        let far = Ray::<f64>::new(eye, DVec3::new(0.3, 0.1, 0.7) - eye).unwrap();
        let refused = bounded_first_hit(&far, &Sphere::new(DVec3::new(0.3, 0.1, 0.7), 1.0).unwrap()).unwrap();
        assert!(
            matches!(refused, BoundedOutcome::Unresolved(Unresolved::HitOrMiss { discriminant, error }) if discriminant.abs() <= error),
            "{refused:?}"
        );
        // Rays through 2000 consecutive f32 directions around the outline (distance r from the
        // centre at y = (3.6 + √(3.6² + 4·8.51·4.05))/17.02): a few leave hit or miss undecided.
        let sphere = Sphere::<f32>::new(Vec3::new(0.1, 0.2, 3.0), 0.7).unwrap();
        let outline = (3.6 + (3.6f64 * 3.6 + 4.0 * 8.51 * 4.05).sqrt()) / 17.02;
        let mut undecided = 0;
        for k in 0..2000u32 {
            let y = f32::from_bits((outline as f32).to_bits() + k - 1000);
            let ray = Ray::<f32>::new(Vec3::new(0.1, 0.0, 0.0), Vec3::new(0.0, y, 3.0)).unwrap();
            if let BoundedOutcome::Unresolved(why) = bounded_first_hit(&ray, &sphere).unwrap() {
                assert!(matches!(why, Unresolved::HitOrMiss { discriminant, error } if discriminant.abs() <= error));
                undecided += 1;
            }
        }
        assert!((1..100).contains(&undecided), "{undecided} of 2000 undecided");
        let why = Unresolved::OtherSide { point_error: 3.0, diameter: 2.0 };
        assert!(why.to_string().contains("known only to within 3e0, at least the sphere's diameter 2e0"));
    }
}
