//! kd-trees: the interval rule every traversal in the crate shares, and a 3-D SAH kd-tree over
//! spheres (closest hit with early exit) for the renderers.
//!
//! # The interval rule ([`split_interval`])
//! A traversal keeps the part `[t_min, t_max]` of the ray `e + d t` that lies inside the current
//! node. At a node split by the plane `p_a = s` (axis `a`), the ray meets the plane at
//! `t = (s − e_a) / d_a`, and the interval divides into at most two pieces: the **near** child
//! (the side the ray moves from, by the sign of `d_a`) over `[t_min, t]` and the **far** child over
//! `[t, t_max]`. The child visited first, the one the ray is in just after `t_min`, is the near
//! child when the crossing lies ahead of `t_min`, and the far child when it lies behind.
//! The rule is written once, against [`AxisLine`]; how `t` is evaluated is the axis's business:
//! [`QuotientAxis`] divides, exactly as the homework writes it (the Q3 traces), and
//! [`ReciprocalAxis`] multiplies by `1/d_a` taken once per ray (the 3-D tree, where a division at
//! every node was the largest single cost).
//! Cells are half-open: the lower child holds `p_a < s`, the upper child `p_a ≥ s` (the homework
//! writes them `x < 3` and `x ≥ 3`). The rule, with every tie stated:
//!
//! | situation | decision | why |
//! |---|---|---|
//! | `d_a = ±0` (parallel) | one child, by the origin: lower if `e_a < s`, else upper; **no division** | the ray's coordinate never changes; `e_a = s` lies in the upper cell by the half-open convention, so the `0/0` of the naive formula never arises ([`ReciprocalAxis`] also counts a subnormal `d_a`, whose reciprocal overflows, as parallel) |
//! | `d_a > 0` | near = lower, far = upper | the coordinate grows with `t` |
//! | `d_a < 0` | near = upper, far = lower | it shrinks |
//! | `t ≤ t_min` | far child only, whole interval | the near piece `[t_min, t]` is empty or a point |
//! | `t ≥ t_max` | near child only, whole interval | the far piece is empty or a point |
//! | otherwise | near over `[t_min, t]`, then far over `[t, t_max]` | a genuine crossing |
//!
//! So no zero-length interval is ever produced, each child interval is a sub-interval of its
//! parent's, and the near/far choice is by the *sign* of `d_a`, read only after the parallel
//! case is out of the way (`−0.0` counts as zero, and `1/−0.0 = −∞` is never read as "moving
//! down": the trap that makes obvhs 0.4's CWBVH miss a hit). Overflow is harmless: `t = ±∞` compares
//! correctly with any finite bound. The rule never reads `t_min ≥ 0`; it is correct for any
//! `t_min < t_max`.
//!
//! The homework's Q3 (in `hw3`) traces this rule on its 2-D tree; the 3-D [`KdTree`] uses the
//! same function at every interior node.
//!
//! `benches/q3_kdtree.rs` measures the tree on random sphere scenes, camera and random rays, beside
//! peer BVHs and Embree; the Q3 engineering notes of the course notes (`hw3::notes`) say how,
//! and describe the node and leaf layout, the build and the walk.

mod build;
mod coarse;
mod exact;
mod node;
mod prefetch;
mod stack;
mod tree;
mod tree_f32;

pub use build::{BuildError, SahCosts};
pub(crate) use tree::moved;
pub use tree::{HitStats, KdTree, Walk, brute_force_closest_hit};
pub use tree_f32::KdTreeF32;

/// Which child of a split a piece of the ray lies in: `Lower` holds `p_a < s`, `Upper` holds
/// `p_a ≥ s`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
pub enum Side {
    /// The half-space `p_a < s`.
    Lower,
    /// The half-space `p_a ≥ s` (it contains the plane itself).
    Upper,
}

impl Side {
    /// The other side.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::kdtree::Side;
    /// assert_eq!(Side::Lower.opposite(), Side::Upper);
    /// ```
    #[must_use]
    pub fn opposite(self) -> Self {
        match self {
            Self::Lower => Self::Upper,
            Self::Upper => Self::Lower,
        }
    }

    /// The side of the split value `split` that the coordinate `p` lies on (half-open cells).
    ///
    /// # Examples
    /// ```
    /// use hw3_render::kdtree::Side;
    /// assert_eq!(Side::of(2.9, 3.0), Side::Lower);
    /// assert_eq!(Side::of(3.0, 3.0), Side::Upper);
    /// ```
    #[must_use]
    pub fn of(p: f64, split: f64) -> Self {
        if p < split { Self::Lower } else { Self::Upper }
    }
}

/// Which children a ray's interval visits at one split (see the module docs for the rule).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Visit {
    /// One child over the whole interval `[t_min, t_max]`.
    Only(Side),
    /// `near` over `[t_min, t_plane]`, then its opposite over `[t_plane, t_max]`, with
    /// `t_min < t_plane < t_max`.
    NearThenFar {
        /// The child visited first.
        near: Side,
        /// Where the ray crosses the plane.
        t_plane: f64,
    },
}

/// The outcome of [`split_interval`]: the plane parameter, if one was computed, and the visit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplitDecision {
    /// `t = (s − e_a)/d_a`, or `None` when `d_a = ±0` (the ray is parallel and nothing is divided).
    /// It may be `±∞` when the quotient overflows; it is never NaN for finite input.
    pub t_plane: Option<f64>,
    /// The children visited, near first.
    pub visit: Visit,
}

impl SplitDecision {
    /// The visited children with their intervals, in visiting order (one or two entries).
    ///
    /// # Examples
    /// ```
    /// use hw3_render::kdtree::{split_interval, QuotientAxis, Side};
    /// // e_x = 5, d_x = −1, plane x = 3: the ray crosses at t = 2, upper side first.
    /// let decision = split_interval(QuotientAxis::new(5.0, -1.0), 3.0, 0.0, f64::INFINITY);
    /// assert_eq!(decision.t_plane, Some(2.0));
    /// let pieces: Vec<_> = decision.pieces(0.0, f64::INFINITY).collect();
    /// assert_eq!(pieces, [(Side::Upper, 0.0, 2.0), (Side::Lower, 2.0, f64::INFINITY)]);
    /// ```
    pub fn pieces(self, t_min: f64, t_max: f64) -> impl Iterator<Item = (Side, f64, f64)> {
        let pair = match self.visit {
            Visit::Only(side) => [Some((side, t_min, t_max)), None],
            Visit::NearThenFar { near, t_plane } => {
                [Some((near, t_min, t_plane)), Some((near.opposite(), t_plane, t_max))]
            }
        };
        pair.into_iter().flatten()
    }
}

/// A ray's coordinate along one axis, `origin + dir·t`, as the interval rule needs it: where it
/// starts, whether it moves, which way, and the parameter `t` at which it reaches a plane. The
/// rule ([`split_interval`]) is written once against this trait; the two implementations differ
/// only in how `t` is evaluated.
pub trait AxisLine: Copy {
    /// The coordinate at `t = 0`.
    fn origin(self) -> f64;
    /// True when the coordinate does not change along the ray; the rule then decides by the origin
    /// alone and never calls [`AxisLine::plane_t`].
    fn is_parallel(self) -> bool;
    /// True when the coordinate grows with `t` (meaningful only when not parallel).
    fn increasing(self) -> bool;
    /// The `t` at which the coordinate equals `split` (only called when not parallel; never NaN
    /// for finite input, possibly `±∞` on overflow).
    fn plane_t(self, split: f64) -> f64;
}

/// The homework's arithmetic: `t = (s − e_a)/d_a`, one subtraction and one correctly rounded
/// division. The 2-D traversal of Q3 uses it, so that its traces equal the homework's hand
/// computation and a brute-force clip bit for bit.
///
/// # Examples
/// ```
/// use hw3_render::kdtree::{AxisLine, QuotientAxis};
/// let axis = QuotientAxis::new(5.0, -1.0);
/// assert_eq!(axis.plane_t(3.0), 2.0);
/// assert!(QuotientAxis::new(1.0, -0.0).is_parallel());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuotientAxis {
    origin: f64,
    dir: f64,
}

impl QuotientAxis {
    /// The axis of a ray with coordinate `origin` and direction component `dir` (finite; `±0`
    /// means parallel).
    ///
    /// # Panics
    /// Never.
    #[must_use]
    pub fn new(origin: f64, dir: f64) -> Self {
        Self { origin, dir }
    }
}

impl AxisLine for QuotientAxis {
    fn origin(self) -> f64 {
        self.origin
    }
    fn is_parallel(self) -> bool {
        self.dir == 0.0
    }
    fn increasing(self) -> bool {
        self.dir > 0.0
    }
    fn plane_t(self, split: f64) -> f64 {
        (split - self.origin) / self.dir
    }
}

/// The fast arithmetic: `t = (s − e_a)·(1/d_a)` with the reciprocal taken once per ray (pbrt's
/// `invDir`), within one rounding of the quotient (identical when `d_a` is a power of two). A
/// division at every node was the largest single cost in the profile of the 3-D traversal (a fifth
/// of its samples waited on it), so [`KdTree`] uses this one.
///
/// A subnormal `d_a`, whose reciprocal overflows to `±∞`, counts as parallel: `(s − e_a)·∞` would
/// be `0·∞ = NaN` for an origin on the plane, and such a ray moves less than `2⁻¹⁰²²` per unit `t`.
///
/// # Examples
/// ```
/// use hw3_render::kdtree::{AxisLine, ReciprocalAxis};
/// let axis = ReciprocalAxis::new(5.0, -0.5);
/// assert_eq!(axis.plane_t(3.0), 4.0);
/// assert!(ReciprocalAxis::new(1.0, -0.0).is_parallel());
/// assert!(ReciprocalAxis::new(1.0, 5e-324).is_parallel());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReciprocalAxis {
    origin: f64,
    inv_dir: f64,
}

impl ReciprocalAxis {
    /// The axis of a ray with coordinate `origin` and direction component `dir` (finite).
    ///
    /// # Panics
    /// Never.
    #[must_use]
    #[inline]
    pub fn new(origin: f64, dir: f64) -> Self {
        Self { origin, inv_dir: 1.0 / dir }
    }
}

impl AxisLine for ReciprocalAxis {
    #[inline]
    fn origin(self) -> f64 {
        self.origin
    }
    #[inline]
    fn is_parallel(self) -> bool {
        self.inv_dir.is_infinite()
    }
    #[inline]
    fn increasing(self) -> bool {
        self.inv_dir > 0.0
    }
    #[inline]
    fn plane_t(self, split: f64) -> f64 {
        (split - self.origin) * self.inv_dir
    }
}

/// Divides the ray interval `[t_min, t_max]` at the plane `p_a = split`, for a ray whose
/// coordinate on that axis is `axis`. The one implementation of the interval rule.
///
/// Preconditions: finite `split`; `t_min < t_max` (either may be infinite).
/// Numerics: `t` is the axis's [`AxisLine::plane_t`] (a correctly rounded quotient for
/// [`QuotientAxis`], within one more rounding for [`ReciprocalAxis`]); a parallel axis is decided
/// by the origin alone, so no `0/0` or `0·∞` is ever evaluated.
///
/// # Examples
/// ```
/// use hw3_render::kdtree::{split_interval, QuotientAxis, Side, Visit};
/// // Parallel ray lying exactly in the plane: the upper (≥) cell, no 0/0.
/// let d = split_interval(QuotientAxis::new(3.0, -0.0), 3.0, 0.0, f64::INFINITY);
/// assert_eq!((d.t_plane, d.visit), (None, Visit::Only(Side::Upper)));
/// ```
///
/// # Panics
/// Never.
#[must_use]
#[inline]
pub fn split_interval(axis: impl AxisLine, split: f64, t_min: f64, t_max: f64) -> SplitDecision {
    let pieces = split_pieces(axis, split, t_min, t_max);
    let visit = match (pieces.near_live, pieces.far_live) {
        (true, true) => Visit::NearThenFar { near: pieces.near, t_plane: pieces.t_plane },
        (true, false) => Visit::Only(pieces.near),
        _ => Visit::Only(pieces.near.opposite()),
    };
    SplitDecision { t_plane: (!axis.is_parallel()).then_some(pieces.t_plane), visit }
}

/// The interval rule as flags rather than an enum: [`split_interval`] is this function with the
/// flags turned into a [`Visit`] (for the traces), and the 3-D traversal branches on the flags
/// directly. It branches rather than selecting with conditional moves: a predicted branch lets the
/// CPU start loading the next node early; the branch-free walk is slower on camera rays (the Q3
/// engineering notes measure both).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SplitPieces {
    /// The side the ray moves from (by the sign of `d_a`; for a parallel ray, its origin's side):
    /// the child the ray is in just after `t_min` when `near_live`, the other one when not.
    pub near: Side,
    /// Where the ray crosses the plane; NaN for a parallel axis (then `far_live` is false).
    pub t_plane: f64,
    /// The near piece `[t_min, t_plane]` has positive length.
    pub near_live: bool,
    /// The far piece `[t_plane, t_max]` has positive length.
    pub far_live: bool,
}

#[inline]
pub(crate) fn split_pieces(axis: impl AxisLine, split: f64, t_min: f64, t_max: f64) -> SplitPieces {
    if axis.is_parallel() {
        let near = Side::of(axis.origin(), split);
        return SplitPieces { near, t_plane: f64::NAN, near_live: true, far_live: false };
    }
    let t_plane = axis.plane_t(split);
    let near = if axis.increasing() { Side::Lower } else { Side::Upper };
    // For t_min < t_max at least one piece is live; a crossing at either end leaves a point, not a piece.
    SplitPieces { near, t_plane, near_live: t_plane > t_min, far_live: t_plane < t_max }
}

#[cfg(test)]
mod tests {
    use super::*;

    const INF: f64 = f64::INFINITY;

    #[test]
    fn crossing_gives_near_then_far() {
        let d = split_interval(QuotientAxis::new(0.0, 1.0), 1.0, 0.0, INF);
        assert_eq!(d.visit, Visit::NearThenFar { near: Side::Lower, t_plane: 1.0 });
    }

    #[test]
    fn parallel_ray_goes_by_origin_for_both_signs_of_zero() {
        for dir in [0.0, -0.0] {
            assert_eq!(split_interval(QuotientAxis::new(2.0, dir), 3.0, 0.0, INF).visit, Visit::Only(Side::Lower));
            assert_eq!(split_interval(QuotientAxis::new(3.0, dir), 3.0, 0.0, INF).visit, Visit::Only(Side::Upper));
            assert_eq!(split_interval(QuotientAxis::new(3.0, dir), 3.0, 0.0, INF).t_plane, None);
        }
    }

    #[test]
    fn origin_on_plane_goes_where_the_ray_goes() {
        assert_eq!(split_interval(QuotientAxis::new(3.0, -1.0), 3.0, 0.0, INF).visit, Visit::Only(Side::Lower));
        assert_eq!(split_interval(QuotientAxis::new(3.0, 1.0), 3.0, 0.0, INF).visit, Visit::Only(Side::Upper));
    }

    #[test]
    fn crossing_exactly_at_an_end_of_the_interval_visits_one_child() {
        // t = 2 = t_max: the far piece [2, 2] is a point, skipped.
        assert_eq!(split_interval(QuotientAxis::new(0.0, 1.0), 2.0, 0.0, 2.0).visit, Visit::Only(Side::Lower));
        // t = 2 = t_min: the near piece is a point, skipped.
        assert_eq!(split_interval(QuotientAxis::new(0.0, 1.0), 2.0, 2.0, 5.0).visit, Visit::Only(Side::Upper));
    }

    #[test]
    fn overflowing_plane_parameter_is_infinite_not_nan() {
        let d = split_interval(QuotientAxis::new(-1e308, 1e-300), 1e308, 0.0, INF);
        assert_eq!(d.t_plane, Some(INF));
        assert_eq!(d.visit, Visit::Only(Side::Lower));
    }

    #[test]
    fn subnormal_direction_on_the_plane_is_parallel_not_nan() {
        // 1/5e-324 overflows to ∞, and (s − e)·∞ would be 0·∞ = NaN for an origin on the plane.
        for dir in [5e-324, -5e-324] {
            let d = split_interval(ReciprocalAxis::new(3.0, dir), 3.0, 0.0, INF);
            assert_eq!((d.t_plane, d.visit), (None, Visit::Only(Side::Upper)));
        }
    }
}
