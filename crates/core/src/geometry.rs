//! Shared geometry core: rays, spheres, input validation, and the numerically stable ray/sphere
//! solver that every renderer in the crate uses.
//!
//! The homework's own formulas live in the question modules (Q2 keeps the student's literal solver
//! for comparison); this core holds what the rest of the crate builds on. All public entry points
//! validate their input and return an [`InputError`] instead of panicking or producing a silent NaN.

pub mod sphere;

use crate::real::Real;
use glam::DVec3;

/// Invalid input to a geometric routine. Every variant names the offending argument.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InputError {
    /// A coordinate or scalar is NaN or infinite.
    #[error("{name} must be finite, got {value}")]
    NonFinite {
        /// The argument's name as the user knows it (`"origin"`, `"radius"`).
        name: &'static str,
        /// The value as printed.
        value: String,
    },
    /// A direction is the zero vector, or so short that its squared length is not a normal float.
    #[error("{name} must be a non-zero vector whose squared length is a normal float, got {value}")]
    DegenerateDirection {
        /// The argument's name.
        name: &'static str,
        /// The value as printed.
        value: String,
    },
    /// A scalar is outside its allowed range.
    #[error("{name} must be {expected}, got {value}")]
    OutOfRange {
        /// The argument's name.
        name: &'static str,
        /// The value as printed.
        value: String,
        /// The allowed range in words.
        expected: &'static str,
    },
    /// Valid input whose answer this precision cannot compute: a square that overflows or
    /// underflows ([`sphere::check_solvable`]), or an answer rounding leaves undecided, such as hit
    /// or miss for a ray within rounding of a sphere's outline ([`sphere::Unresolved`]).
    #[error("{precision} cannot solve this case: {reason}")]
    Unresolvable {
        /// `"f32"` or `"f64"`.
        precision: &'static str,
        /// Which quantity is out of reach, with the values that put it there.
        reason: String,
    },
}

/// Checks that every component of `v` is finite.
///
/// # Errors
/// [`InputError::NonFinite`] naming `name`.
pub fn require_finite<T: Real>(name: &'static str, v: T::Vec3) -> Result<T::Vec3, InputError> {
    if T::components(v).iter().all(|c| c.is_finite()) {
        Ok(v)
    } else {
        Err(InputError::NonFinite { name, value: format!("{v:?}") })
    }
}

/// Checks that `v` is a usable ray direction: finite, and with `v·v` a normal float (neither zero,
/// subnormal nor overflowed), so that dividing by `v·v` is safe.
///
/// # Errors
/// [`InputError::NonFinite`] or [`InputError::DegenerateDirection`] naming `name`.
pub fn require_direction<T: Real>(name: &'static str, v: T::Vec3) -> Result<T::Vec3, InputError> {
    require_finite::<T>(name, v)?;
    let a = T::dot(v, v);
    if a.is_finite() && a >= T::MIN_POSITIVE {
        Ok(v)
    } else {
        Err(InputError::DegenerateDirection { name, value: format!("{v:?}") })
    }
}

/// A ray `origin + t·dir`, in the homework's notation `e + d t`. `dir` need not be unit length:
/// `t` is then measured in multiples of `|dir|`, exactly as in the homework.
///
/// Plain data, like glam's vectors: the fields are public, and the renderer writes the rays it
/// spawns straight into them. Values from outside the program (the command line, a scene, an
/// answers file) are checked where they come in, by [`Ray::new`]: a finite origin and a usable
/// direction. The solvers assume a valid ray; given a non-finite one they report no hit, never a
/// NaN parameter ([`sphere`] says how).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray<T: Real> {
    /// The eye point `e`.
    pub origin: T::Vec3,
    /// The direction `d` (any non-zero length).
    pub dir: T::Vec3,
}

impl<T: Real> Ray<T> {
    /// A validated ray.
    ///
    /// # Errors
    /// [`InputError`] if `origin` is not finite or `dir` is not a usable direction
    /// (see [`require_direction`]).
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::Ray;
    /// let ray = Ray::<f64>::new(DVec3::ZERO, DVec3::Z).unwrap();
    /// assert_eq!(ray.at(2.0), DVec3::new(0.0, 0.0, 2.0));
    /// assert!(Ray::<f64>::new(DVec3::ZERO, DVec3::ZERO).is_err());
    /// ```
    pub fn new(origin: T::Vec3, dir: T::Vec3) -> Result<Self, InputError> {
        Ok(Self { origin: require_finite::<T>("origin", origin)?, dir: require_direction::<T>("direction", dir)? })
    }

    /// The point at parameter `t`: `e + d t`.
    #[must_use]
    pub fn at(&self, t: T) -> T::Vec3 {
        self.origin + self.dir * t
    }
}

/// A sphere `|p − o|² = r²` with centre `o = (a, b, c)` and radius `r`.
///
/// Plain data, as [`Ray`]: values from outside the program are checked where they come in, by
/// [`Sphere::new`] (a finite centre, a finite radius > 0); the kd-tree's build and the renderer's
/// scenes check every sphere they are given. The solvers assume a valid sphere: non-finite values
/// give no hit, and a radius ≤ 0 gives answers without meaning.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere<T: Real> {
    /// The centre `o`.
    pub center: T::Vec3,
    /// The radius `r` (finite, > 0).
    pub radius: T,
}

impl<T: Real> Sphere<T> {
    /// A validated sphere.
    ///
    /// # Errors
    /// [`InputError::NonFinite`] for a non-finite centre or radius, [`InputError::OutOfRange`]
    /// for a radius ≤ 0 (a sphere of radius 0 has no normal, so Q2b would be undefined).
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::Sphere;
    /// assert!(Sphere::<f64>::new(DVec3::ZERO, 1.0).is_ok());
    /// assert!(Sphere::<f64>::new(DVec3::ZERO, -1.0).is_err());
    /// assert!(Sphere::<f64>::new(DVec3::ZERO, 0.0).is_err());
    /// assert!(Sphere::<f64>::new(DVec3::ZERO, f64::INFINITY).is_err());
    /// ```
    pub fn new(center: T::Vec3, radius: T) -> Result<Self, InputError> {
        require_finite::<T>("center", center)?;
        if !radius.is_finite() {
            return Err(InputError::NonFinite { name: "radius", value: format!("{radius}") });
        }
        if radius <= T::ZERO {
            return Err(InputError::OutOfRange { name: "radius", value: format!("{radius}"), expected: "> 0" });
        }
        Ok(Self { center, radius })
    }
}

/// Converts a validated `f64` ray to `f32` (rounding each coordinate), for precision comparisons.
///
/// # Errors
/// [`InputError`] if the rounded ray is no longer valid (a direction whose squared length
/// underflows or overflows in `f32`).
pub fn ray_to_f32(ray: &Ray<f64>) -> Result<Ray<f32>, InputError> {
    Ray::new(f32::vec_from_f64(ray.origin), f32::vec_from_f64(ray.dir))
}

/// A command-line vector that is not three comma-separated numbers ([`parse_vec3`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{name}: expected three comma-separated numbers like 1,0,-2.5, got `{text}`")]
pub struct ParseVec3Error {
    /// The option the text was given to (`"--normal"`).
    pub name: String,
    /// The text as given.
    pub text: String,
}

/// Parses `"x,y,z"` into a `DVec3` (used by the CLI; spaces allowed).
///
/// # Errors
/// [`ParseVec3Error`] naming `name` and the text when there are not exactly three numbers.
///
/// # Examples
/// ```
/// use hw3_core::geometry::{ParseVec3Error, parse_vec3};
/// assert_eq!(parse_vec3("d", "1, -2,3e0").unwrap(), glam::DVec3::new(1.0, -2.0, 3.0));
/// let error = parse_vec3("d", "1,2").unwrap_err();
/// assert_eq!(error, ParseVec3Error { name: "d".into(), text: "1,2".into() });
/// assert_eq!(error.to_string(), "d: expected three comma-separated numbers like 1,0,-2.5, got `1,2`");
/// ```
pub fn parse_vec3(name: &str, text: &str) -> Result<DVec3, ParseVec3Error> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let numbers: Result<Vec<f64>, _> = parts.iter().map(|p| p.parse::<f64>()).collect();
    match numbers {
        Ok(n) if n.len() == 3 => Ok(DVec3::new(n[0], n[1], n[2])),
        _ => Err(ParseVec3Error { name: name.to_owned(), text: text.to_owned() }),
    }
}
