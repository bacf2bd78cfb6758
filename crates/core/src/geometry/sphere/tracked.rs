//! Running error analysis: a number computed in precision `T`, carried with a bound on its
//! distance from the exact value it stands for.
//!
//! A [`Tracked`] is the pair `(v, e)` of a computed value `v` and a bound `e ≥ 0` with
//! `|v − x| ≤ e`, where `x` is the value the same formula takes in exact arithmetic on the exact
//! inputs. This is midpoint–radius interval arithmetic (Rump, "Fast and parallel interval
//! arithmetic", *BIT* 39(3), 1999) with the midpoint being the very value the plain solver
//! computes, so that the bound belongs to that value: the same information as pbrt-v4's
//! `Interval` (Pharr, Jakob & Humphreys, *Physically Based Rendering*, 4th ed., §6.8), kept as
//! "value and error" as in Higham's running error analysis (*Accuracy and Stability of Numerical
//! Algorithms*, 2nd ed., §3.3).
//!
//! Each operation `z = x ∘ y` has two sources of error:
//! - **propagated**: the operands' errors, through the exact operation (for `x·y`,
//!   `|x̃|e_y + |ỹ|e_x + e_x e_y`; for `x/y`, `(e_x + |x̃/ỹ| e_y)/(|ỹ| − e_y)`; for `√x`,
//!   `e_x/(√x̃ + √max(x̃ − e_x, 0))`, and never more than `√e_x`);
//! - **local**: the rounding of `z̃` itself. Where an error-free transformation gives it
//!   exactly (Knuth's TwoSum for `±`, *TAOCP* vol. 2 §4.2.2; Dekker's TwoProduct with Veltkamp's
//!   split for `×`, Dekker, "A floating-point technique for extending the available precision",
//!   *Numer. Math.* 18, 1971), that exact amount is used, so an operation that happens to be exact
//!   adds nothing; otherwise (a quotient, a square root, or a product near underflow) pbrt's
//!   `γ₁|z̃| = u/(1 − u)·|z̃|` with the unit roundoff `u = ε/2`, plus the absolute error of a
//!   subnormal result, `ε·MIN_POSITIVE`, so that the bound also holds in gradual underflow.
//!
//! The bounds are summed in `f64`, and every sum or product of bounds is rounded up by a relative
//! `2⁻⁴⁵` (far more than the few `f64` roundings it covers), so the bound holds for `T = f64` too.
//! A non-finite value or bound stays non-finite: the caller refuses it.

use crate::real::Real;

/// A computed value and a bound on its distance from the exact value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tracked<T: Real> {
    /// The value computed in precision `T`.
    pub v: T,
    /// `|v − exact| ≤ e`.
    pub e: f64,
}

/// Rounds a bound up: `x (1 + 2⁻⁴⁵)`, more than the relative error of the handful of `f64`
/// operations that computed it.
pub(crate) fn up(x: f64) -> f64 {
    x * (1.0 + f64::EPSILON * 128.0)
}

/// Rounds a positive denominator of a bound down, by the same relative amount.
pub(crate) fn down(x: f64) -> f64 {
    x * (1.0 - f64::EPSILON * 128.0)
}

/// The unit roundoff `u = ε/2` of `T`.
fn unit_roundoff<T: Real>() -> f64 {
    T::EPSILON.to_f64() / 2.0
}

/// pbrt's `γₙ = n u/(1 − n u)`: the relative error of `n` correctly rounded operations.
pub(crate) fn gamma<T: Real>(n: u32) -> f64 {
    let nu = f64::from(n) * unit_roundoff::<T>();
    up(nu / down(1.0 - nu))
}

/// The error of a rounded result `z̃` whose exact rounding error is unknown: `γ₁|z̃|`, plus
/// `ε·MIN_POSITIVE` for a result in (or rounded to) the subnormal range.
fn rounding_bound<T: Real>(z: T) -> f64 {
    up(gamma::<T>(1) * z.to_f64().abs() + (T::EPSILON * T::MIN_POSITIVE).to_f64())
}

/// Knuth's TwoSum: `s = fl(a + b)` and the exact error `a + b − s` (NaN if `s` overflows).
fn two_sum<T: Real>(a: T, b: T) -> (T, T) {
    let s = a + b;
    let b_virtual = s - a;
    let a_virtual = s - b_virtual;
    (s, (a - a_virtual) + (b - b_virtual))
}

/// Veltkamp's split constant `2^⌈p/2⌉ + 1` for a `p`-bit significand.
fn split_constant<T: Real>() -> T {
    let bits = 1.0 - T::EPSILON.to_f64().log2();
    T::from_f64(2f64.powf((bits / 2.0).ceil()) + 1.0)
}

/// Veltkamp's split of `a` into two halves of at most `⌈p/2⌉` bits, `a = hi + lo`; `None` if the
/// scaling overflows.
fn split<T: Real>(a: T) -> Option<(T, T)> {
    let c = split_constant::<T>() * a;
    if !c.is_finite() {
        return None;
    }
    let hi = c - (c - a);
    Some((hi, a - hi))
}

/// The exact error `a·b − p` of the rounded product `p = fl(a·b)` (Dekker's TwoProduct), or
/// `None` where the transformation is not error-free: an overflow, or a product small enough that
/// a partial product could fall into the subnormal range (below `MIN_POSITIVE/ε³`).
fn product_error<T: Real>(a: T, b: T, p: T) -> Option<T> {
    if a == T::ZERO || b == T::ZERO {
        return Some(T::ZERO);
    }
    let tiny = T::MIN_POSITIVE.to_f64() / T::EPSILON.to_f64().powi(3);
    if !p.is_finite() || !(p.to_f64().abs() >= tiny) {
        return None;
    }
    let ((a_hi, a_lo), (b_hi, b_lo)) = (split(a)?, split(b)?);
    let error = (((a_hi * b_hi - p) + a_hi * b_lo) + a_lo * b_hi) + a_lo * b_lo;
    error.is_finite().then_some(error)
}

impl<T: Real> Tracked<T> {
    /// An exact value (an input taken as given).
    pub fn exact(v: T) -> Self {
        Self { v, e: 0.0 }
    }

    /// `x` rounded to `T`, with its rounding as the error.
    pub fn rounded(x: f64) -> Self {
        let v = T::from_f64(x);
        Self { v, e: up((v.to_f64() - x).abs()) }
    }

    /// The bound as an interval test: the exact value is certainly `> 0`.
    pub fn certainly_positive(self) -> bool {
        self.v.to_f64() > self.e
    }

    /// The exact value is certainly `≤ 0`.
    pub fn certainly_not_positive(self) -> bool {
        self.v.to_f64() <= -self.e
    }

    /// Both the value and its bound are finite.
    pub fn is_finite(self) -> bool {
        self.v.is_finite() && self.e.is_finite()
    }

    /// `−x`: exact.
    pub fn neg(self) -> Self {
        Self { v: -self.v, e: self.e }
    }

    /// `x + y`, with TwoSum's exact rounding error.
    pub fn add(self, other: Self) -> Self {
        let (v, local) = two_sum(self.v, other.v);
        let local = if v.is_finite() { local.to_f64().abs() } else { f64::INFINITY };
        Self { v, e: up(self.e + other.e + local) }
    }

    /// `x − y`.
    pub fn sub(self, other: Self) -> Self {
        self.add(other.neg())
    }

    /// `x · y`, with TwoProduct's exact rounding error where it is error-free.
    pub fn mul(self, other: Self) -> Self {
        let v = self.v * other.v;
        let local = product_error(self.v, other.v, v).map_or_else(|| rounding_bound(v), |x| x.to_f64().abs());
        let (x, y) = (self.v.to_f64().abs(), other.v.to_f64().abs());
        Self { v, e: up(x * other.e + y * self.e + self.e * other.e + local) }
    }

    /// `x / y`; an unbounded error if `y`'s bound reaches 0.
    pub fn div(self, other: Self) -> Self {
        let v = self.v / other.v;
        let y = other.v.to_f64().abs();
        if !(y > other.e) {
            return Self { v, e: f64::INFINITY };
        }
        // Exact when q·y = x exactly.
        let exact = product_error(v, other.v, v * other.v).is_some_and(|r| r == T::ZERO && v * other.v == self.v);
        let local = if exact { 0.0 } else { rounding_bound(v) };
        let quotient = up(self.v.to_f64().abs() / down(y));
        Self { v, e: up(up(self.e + quotient * other.e) / down(y - other.e) + local) }
    }

    /// `√x`, for an `x` whose exact value is known to be `≥ 0` (the caller checks it).
    pub fn sqrt(self) -> Self {
        let v = self.v.sqrt();
        let x = self.v.to_f64();
        let root_of_bound = up(self.e.sqrt());
        let propagated = if x > 0.0 {
            let lower = (x - self.e).max(0.0);
            root_of_bound.min(up(self.e / down(x.sqrt() + down(lower).sqrt())))
        } else {
            root_of_bound
        };
        let exact = product_error(v, v, v * v).is_some_and(|r| r == T::ZERO && v * v == self.v);
        let local = if exact { 0.0 } else { rounding_bound(v) };
        Self { v, e: up(propagated + local) }
    }
}

/// A 3-vector of tracked components, with the operations the sphere solver uses, in the order
/// [`Real::dot`] and [`Real::cross`] evaluate them.
pub(crate) type Vec3<T> = [Tracked<T>; 3];

/// `a + b` componentwise.
pub(crate) fn add<T: Real>(a: Vec3<T>, b: Vec3<T>) -> Vec3<T> {
    [a[0].add(b[0]), a[1].add(b[1]), a[2].add(b[2])]
}

/// `a − b` componentwise.
pub(crate) fn sub<T: Real>(a: Vec3<T>, b: Vec3<T>) -> Vec3<T> {
    [a[0].sub(b[0]), a[1].sub(b[1]), a[2].sub(b[2])]
}

/// `a · s` componentwise.
pub(crate) fn scale<T: Real>(a: Vec3<T>, s: Tracked<T>) -> Vec3<T> {
    [a[0].mul(s), a[1].mul(s), a[2].mul(s)]
}

/// `a·b` as `x x' + y y' + z z'`, left to right.
pub(crate) fn dot<T: Real>(a: Vec3<T>, b: Vec3<T>) -> Tracked<T> {
    a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
}

/// `a × b` as `(a_y b_z − a_z b_y, a_z b_x − a_x b_z, a_x b_y − a_y b_x)`.
pub(crate) fn cross<T: Real>(a: Vec3<T>, b: Vec3<T>) -> Vec3<T> {
    [a[1].mul(b[2]).sub(a[2].mul(b[1])), a[2].mul(b[0]).sub(a[0].mul(b[2])), a[0].mul(b[1]).sub(a[1].mul(b[0]))]
}

/// The computed vector.
pub(crate) fn value<T: Real>(a: Vec3<T>) -> T::Vec3 {
    T::vec3(a[0].v, a[1].v, a[2].v)
}

/// The Euclidean length of a vector of bounds, rounded up.
pub(crate) fn norm(a: [f64; 3]) -> f64 {
    up(a.iter().map(|x| x * x).sum::<f64>().sqrt())
}

/// The per-component bounds.
pub(crate) fn errors<T: Real>(a: Vec3<T>) -> [f64; 3] {
    [a[0].e, a[1].e, a[2].e]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_operations_add_no_error_and_inexact_ones_add_their_rounding() {
        let (a, b) = (Tracked::<f32>::exact(3.0), Tracked::exact(0.5));
        assert_eq!(a.add(b), Tracked { v: 3.5, e: 0.0 });
        assert_eq!(a.mul(b), Tracked { v: 1.5, e: 0.0 });
        assert_eq!(a.div(b), Tracked { v: 6.0, e: 0.0 });
        assert_eq!(Tracked::<f32>::exact(2.25).sqrt(), Tracked { v: 1.5, e: 0.0 });
        // 1e8 + 1 rounds to 1e8 in f32: TwoSum finds the lost 1 exactly.
        let sum = Tracked::<f32>::exact(1e8).add(Tracked::exact(1.0));
        assert_eq!(sum.v, 1e8);
        assert!((1.0..1.0 + 1e-9).contains(&sum.e), "{sum:?}");
        // (1 + 2⁻¹²)² = 1 + 2⁻¹¹ + 2⁻²⁴ loses its last term in f32: TwoProduct finds 2⁻²⁴.
        let x = Tracked::<f32>::exact(1.0 + 2f32.powi(-12));
        let square = x.mul(x);
        assert!((2f64.powi(-24)..2f64.powi(-24) * (1.0 + 1e-9)).contains(&square.e), "{square:?}");
        // A quotient that is not exact carries γ₁|q|.
        let third = Tracked::<f64>::exact(1.0).div(Tracked::exact(3.0));
        assert!(third.e >= (third.v - 1.0 / 3.0).abs() && third.e < 1e-16, "{third:?}");
    }

    #[test]
    fn propagated_bounds_contain_the_exact_result() {
        // x = 2 ± 0.1, y = 0.5 ± 0.01: the exact x·y, x/y and √x over the corners.
        let x = Tracked::<f64> { v: 2.0, e: 0.1 };
        let y = Tracked::<f64> { v: 0.5, e: 0.01 };
        for (xe, ye) in [(1.9, 0.49), (1.9, 0.51), (2.1, 0.49), (2.1, 0.51)] {
            let (p, q) = (x.mul(y), x.div(y));
            assert!((p.v - xe * ye).abs() <= p.e, "{p:?}");
            assert!((q.v - xe / ye).abs() <= q.e, "{q:?}");
            let s = x.sqrt();
            assert!((s.v - f64::sqrt(xe)).abs() <= s.e, "{s:?}");
        }
        // A square root near 0: √(0 ± 1e-10) is within 1e-5 of 0.
        let near_zero = Tracked::<f64> { v: 0.0, e: 1e-10 }.sqrt();
        assert!(near_zero.e >= 1e-5 && near_zero.e < 1.1e-5, "{near_zero:?}");
        // A divisor whose bound reaches 0 gives no bound.
        assert!(!x.div(Tracked { v: 0.5, e: 0.5 }).is_finite());
    }

    #[test]
    fn gamma_is_pbrts() {
        let u = f64::from(f32::EPSILON) / 2.0;
        assert!((gamma::<f32>(5) / (5.0 * u / (1.0 - 5.0 * u)) - 1.0).abs() < 1e-12);
    }
}
