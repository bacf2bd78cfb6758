//! The two floating-point precisions the notes compare, behind one small trait.
//!
//! Every numerical method that is taught in both precisions (Q2's naive and stable sphere solvers,
//! the ray-spawn offset) is written once, generic over [`Real`], and instantiated for `f32` (the
//! GPU's precision, where the textbook formula visibly fails) and `f64` (the default everywhere
//! else). The trait is deliberately narrow: exactly the operations those methods use, with the
//! vector type being glam's `Vec3` or `DVec3`.

use glam::{DVec3, Vec3};
use std::fmt::{Debug, Display, LowerExp};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A floating-point scalar (`f32` or `f64`) with its matching glam vector type.
pub trait Real:
    Copy
    + PartialOrd
    + Debug
    + Display
    + LowerExp
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Send
    + Sync
    + 'static
{
    /// glam's 3-vector in this precision.
    type Vec3: Copy
        + Debug
        + PartialEq
        + Add<Output = Self::Vec3>
        + Sub<Output = Self::Vec3>
        + Mul<Self, Output = Self::Vec3>
        + Neg<Output = Self::Vec3>
        + Send
        + Sync;
    /// Name used in tables and CLI output (`"f32"`, `"f64"`).
    const NAME: &'static str;
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 4.
    const FOUR: Self;
    /// Machine epsilon (the gap between 1 and the next float): 2⁻²³ or 2⁻⁵².
    const EPSILON: Self;
    /// Largest finite value.
    const MAX: Self;
    /// Smallest positive normal value: 2⁻¹²⁶ or 2⁻¹⁰²².
    const MIN_POSITIVE: Self;
    /// +∞.
    const INFINITY: Self;
    /// A quiet NaN (marks "no value" in traces).
    const NAN: Self;

    /// Rounds an `f64` to this precision (exact for `f64`).
    fn from_f64(x: f64) -> Self;
    /// Widens to `f64` (always exact).
    fn to_f64(self) -> f64;
    /// Correctly rounded square root (IEEE 754); NaN for negative input.
    fn sqrt(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// `self` with the sign of `sign` (sign of −0.0 counts as negative).
    fn copysign(self, sign: Self) -> Self;
    /// True when neither NaN nor ±∞.
    fn is_finite(self) -> bool;
    /// The larger of two numbers, as one `maxss`/`maxsd` instruction: `if self > other { self }
    /// else { other }`, so a NaN `self` yields `other` and a NaN `other` yields NaN (unlike
    /// `f32::max`, whose NaN rule costs extra instructions on x86).
    fn max(self, other: Self) -> Self;

    /// Builds a vector from three scalars.
    fn vec3(x: Self, y: Self, z: Self) -> Self::Vec3;
    /// The components of a vector.
    fn components(v: Self::Vec3) -> [Self; 3];
    /// Dot product, evaluated as `x*x' + y*y' + z*z'` (no fused multiply-add, as in the homework).
    fn dot(a: Self::Vec3, b: Self::Vec3) -> Self;
    /// Cross product `a × b`, evaluated componentwise as `a_y b_z − a_z b_y`, … (no fused
    /// multiply-add).
    fn cross(a: Self::Vec3, b: Self::Vec3) -> Self::Vec3;
    /// Rounds a `DVec3` to this precision.
    fn vec_from_f64(v: DVec3) -> Self::Vec3 {
        Self::vec3(Self::from_f64(v.x), Self::from_f64(v.y), Self::from_f64(v.z))
    }
    /// Widens a vector to `DVec3` (exact).
    fn vec_to_f64(v: Self::Vec3) -> DVec3 {
        let [x, y, z] = Self::components(v);
        DVec3::new(x.to_f64(), y.to_f64(), z.to_f64())
    }
}

impl Real for f32 {
    type Vec3 = Vec3;
    const NAME: &'static str = "f32";
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const TWO: Self = 2.0;
    const FOUR: Self = 4.0;
    const EPSILON: Self = f32::EPSILON;
    const MAX: Self = f32::MAX;
    const MIN_POSITIVE: Self = f32::MIN_POSITIVE;
    const INFINITY: Self = f32::INFINITY;
    const NAN: Self = f32::NAN;

    fn from_f64(x: f64) -> Self {
        x as f32
    }
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    fn abs(self) -> Self {
        f32::abs(self)
    }
    fn copysign(self, sign: Self) -> Self {
        f32::copysign(self, sign)
    }
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    fn max(self, other: Self) -> Self {
        if self > other { self } else { other }
    }
    fn vec3(x: Self, y: Self, z: Self) -> Vec3 {
        Vec3::new(x, y, z)
    }
    fn components(v: Vec3) -> [Self; 3] {
        v.to_array()
    }
    fn dot(a: Vec3, b: Vec3) -> Self {
        a.x * b.x + a.y * b.y + a.z * b.z
    }
    fn cross(a: Vec3, b: Vec3) -> Vec3 {
        Vec3::new(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x)
    }
}

impl Real for f64 {
    type Vec3 = DVec3;
    const NAME: &'static str = "f64";
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const TWO: Self = 2.0;
    const FOUR: Self = 4.0;
    const EPSILON: Self = f64::EPSILON;
    const MAX: Self = f64::MAX;
    const MIN_POSITIVE: Self = f64::MIN_POSITIVE;
    const INFINITY: Self = f64::INFINITY;
    const NAN: Self = f64::NAN;

    fn from_f64(x: f64) -> Self {
        x
    }
    fn to_f64(self) -> f64 {
        self
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn abs(self) -> Self {
        f64::abs(self)
    }
    fn copysign(self, sign: Self) -> Self {
        f64::copysign(self, sign)
    }
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
    fn max(self, other: Self) -> Self {
        if self > other { self } else { other }
    }
    fn vec3(x: Self, y: Self, z: Self) -> DVec3 {
        DVec3::new(x, y, z)
    }
    fn components(v: DVec3) -> [Self; 3] {
        v.to_array()
    }
    fn dot(a: DVec3, b: DVec3) -> Self {
        a.x * b.x + a.y * b.y + a.z * b.z
    }
    fn cross(a: DVec3, b: DVec3) -> DVec3 {
        DVec3::new(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn max_documents_its_nan_rule() {
        assert_eq!(Real::max(2.0f32, 1.0), 2.0);
        assert_eq!(Real::max(f32::NAN, 1.0), 1.0);
        assert!(Real::max(1.0f64, f64::NAN).is_nan());
    }

    #[test]
    fn dot_matches_glam_without_fma() {
        let a = Vec3::new(1.5, -2.0, 0.25);
        let b = Vec3::new(4.0, 0.5, -8.0);
        assert_eq!(<f32 as Real>::dot(a, b), 6.0 - 1.0 - 2.0);
    }
}
