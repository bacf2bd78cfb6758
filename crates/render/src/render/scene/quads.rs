//! The quads of a scene, prepared for ray queries: each quad's plane normal, the tolerance of its
//! parallel-ray test and the dual basis of its edges are computed once when the scene is built,
//! and a ray meets the plane first, so a quad whose plane lies beyond the closest hit found so far
//! is rejected before its edge coordinates are computed (plane-first rejection).
//!
//! Runs of consecutive quads that sit close together (a block's five faces) share a bounding box,
//! and a ray that misses the box, or meets it only beyond the closest hit so far, skips all of
//! them. Which runs get a box is decided once by the surface-area heuristic (Goldsmith and Salmon
//! 1987; Pharr, Jakob and Humphreys, *Physically Based Rendering*, 4th ed., §7.3.2): a random ray
//! meets a convex box with probability about proportional to its surface area, so a run of `k`
//! quads in a box of area `A` costs about `1 + k·A/A_scene` tests instead of `k`. The box is
//! padded far beyond rounding (see [`Bounds::may_hit`]), so it never skips a quad the test would
//! have hit.
//!
//! Every number of the quad test is the one [`super::intersect`] computes for the same quad, in
//! the same order of operations, and the quads are tried in object order, so a query through the
//! set returns the brute-force `t` bit for bit.

use super::{Object, Shape};
use glam::DVec3;
use hw3_core::geometry::Ray;
use std::ops::Range;

/// One quad `corner + a·edge_u + b·edge_v` with the per-quad constants of its hit test.
#[derive(Debug, Clone, Copy)]
struct PreparedQuad {
    /// Index of the object in the scene's objects.
    object: usize,
    corner: DVec3,
    edge_u: DVec3,
    edge_v: DVec3,
    /// `edge_u × edge_v` (not normalised).
    normal: DVec3,
    /// `1e-12 · |normal|`: the parallel-ray tolerance before the factor `|ray.dir|`.
    parallel_tolerance: f64,
    /// `normal / (normal · normal)`, the dual basis's common factor.
    dual: DVec3,
}

impl PreparedQuad {
    /// The plane's `t` for `ray` when the ray is not parallel to it and `t > 0` (the first half
    /// of [`super::intersect`]); `dir_length` is `|ray.dir|`.
    #[inline]
    fn plane_t(&self, ray: &Ray<f64>, dir_length: f64) -> Option<f64> {
        let denominator = ray.dir.dot(self.normal);
        if denominator.is_nan() || denominator.abs() <= self.parallel_tolerance * dir_length {
            return None;
        }
        let numerator = (self.corner - ray.origin).dot(self.normal);
        // `numerator / denominator > 0` needs both of one sign (a zero, a NaN or opposite signs
        // give 0, NaN or a negative quotient): the plane behind the ray costs no division.
        if !((numerator > 0.0 && denominator > 0.0) || (numerator < 0.0 && denominator < 0.0)) {
            return None;
        }
        let t = numerator / denominator;
        (!t.is_nan() && t > 0.0).then_some(t)
    }

    /// Whether the plane point at `t` lies inside the parallelogram (the second half).
    #[inline]
    fn contains(&self, ray: &Ray<f64>, t: f64) -> bool {
        let offset = ray.at(t) - self.corner;
        let a = offset.cross(self.edge_v).dot(self.dual);
        let b = self.edge_u.cross(offset).dot(self.dual);
        (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)
    }

    /// The hit `t ∈ (0, limit]`, or `None`; a plane beyond `limit` costs no edge test.
    #[inline]
    fn hit_within(&self, ray: &Ray<f64>, dir_length: f64, limit: f64) -> Option<f64> {
        self.plane_t(ray, dir_length).filter(|&t| t <= limit && self.contains(ray, t))
    }

    /// The quad's four vertices.
    fn vertices(&self) -> [DVec3; 4] {
        let (c, u, v) = (self.corner, self.edge_u, self.edge_v);
        [c, c + u, c + v, c + u + v]
    }

    /// `|edge_u| |edge_v| / |edge_u × edge_v|` (1 for a rectangle, the inverse sine of the edges'
    /// angle): how much rounding in the edge coordinates can move an accepted point.
    fn skew(&self) -> f64 {
        self.edge_u.length() * self.edge_v.length() / self.normal.length()
    }
}

/// Relative padding of a run's box: a million times the few units in the last place by which the
/// quad test's accepted point and the slab test's `t` can be off.
const PADDING: f64 = 1e-9;

/// Cost of one box test in units of one quad test (both a few dot products and a division or so).
const BOX_COST: f64 = 1.0;

/// Most quads the runs are searched over (the search costs about the square of the count);
/// beyond it every quad is tested on its own.
const MAX_GROUPED_QUADS: usize = 1024;

/// The axis-aligned box around a run of quads, and the run's share of the padding.
#[derive(Debug, Clone, Copy)]
struct Bounds {
    min: DVec3,
    max: DVec3,
    /// `PADDING · skew · (|box|∞ + extent)`: the padding before the ray origin's share.
    padding: f64,
    /// `PADDING · skew`: the padding per unit of the ray origin's largest coordinate.
    padding_per_origin: f64,
}

/// What every box test of one query needs from its ray: the inverse direction and the origin's
/// largest coordinate, computed once per query.
#[derive(Debug, Clone, Copy)]
struct SlabRay {
    origin: DVec3,
    /// `1 / dir` per axis (`±∞` on an axis the ray does not move along).
    inverse_dir: DVec3,
    /// `|origin|∞`, the origin's share of the padding.
    origin_scale: f64,
    /// Whether the boxes may reject: a finite origin, and a finite inverse wherever the direction
    /// is not zero (a subnormal or non-finite direction tests every quad).
    usable: bool,
}

impl SlabRay {
    /// The ray's slab data, or an unusable one (no work) when `wanted` is false.
    #[inline]
    fn new(ray: &Ray<f64>, wanted: bool) -> Self {
        if !wanted {
            return Self { origin: ray.origin, inverse_dir: DVec3::ZERO, origin_scale: 0.0, usable: false };
        }
        let inverse_dir = ray.dir.recip();
        let finite_inverse = (0..3).all(|axis| ray.dir[axis] == 0.0 || inverse_dir[axis].is_finite());
        Self {
            origin: ray.origin,
            inverse_dir,
            origin_scale: ray.origin.abs().max_element(),
            usable: ray.origin.is_finite() && finite_inverse,
        }
    }
}

impl Bounds {
    /// Whether the ray may meet a quad of the box with `t ∈ (0, limit]`.
    ///
    /// Why skipping on `false` is exact: an accepted quad hit `t` has edge coordinates in `[0, 1]`
    /// as computed, so the exact point `origin + t·dir` lies within a few units in the last place
    /// of `skew · (|origin| + |box|)` of the parallelogram, far inside the padding; the slab `t`s
    /// of the padded box (through the rounded inverse direction), off by a unit or two in the last
    /// place of the same size, then bracket `t`, so `near ≤ t ≤ limit` and `far ≥ t > 0`. On an
    /// axis the ray does not move along, the slab is `(−∞, ∞)` for an origin inside it and empty
    /// (`+∞` or `−∞` twice) outside; an origin exactly on the padded face makes `0 · ∞` a NaN and
    /// either answer right, since such a ray stays a whole padding away from every quad.
    #[inline]
    fn may_hit(&self, ray: &SlabRay, limit: f64) -> bool {
        if !ray.usable {
            return true;
        }
        let padding = DVec3::splat(self.padding + self.padding_per_origin * ray.origin_scale);
        let t0 = (self.min - padding - ray.origin) * ray.inverse_dir;
        let t1 = (self.max + padding - ray.origin) * ray.inverse_dir;
        let (near, far) = (t0.min(t1).max_element(), t0.max(t1).min_element());
        near <= far && far >= 0.0 && near <= limit
    }

    /// The box around `quads` (at least one).
    fn around(quads: &[PreparedQuad]) -> Self {
        let (mut min, mut max, mut skew) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY), 1.0f64);
        for quad in quads {
            for vertex in quad.vertices() {
                (min, max) = (min.min(vertex), max.max(vertex));
            }
            skew = skew.max(quad.skew());
        }
        let scale = min.abs().max(max.abs()).max_element() + (max - min).max_element();
        Self { min, max, padding: PADDING * skew * scale, padding_per_origin: PADDING * skew }
    }

    /// The surface area of the box.
    fn area(&self) -> f64 {
        let e = self.max - self.min;
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }
}

/// A run of consecutive quads (in object order), with a box when the box pays.
#[derive(Debug, Clone)]
struct Run {
    quads: Range<usize>,
    bounds: Option<Bounds>,
}

/// The quads of a scene in object order, prepared for closest-hit and any-hit queries.
#[derive(Debug, Clone, Default)]
pub(crate) struct QuadSet {
    quads: Vec<PreparedQuad>,
    /// Consecutive runs covering `quads` in order.
    runs: Vec<Run>,
    /// Whether some run has a box (else a query computes no [`SlabRay`]).
    boxed: bool,
}

impl QuadSet {
    /// The quads among `objects`, in increasing object index.
    pub(crate) fn new(objects: &[Object]) -> Self {
        let quads: Vec<PreparedQuad> = objects
            .iter()
            .enumerate()
            .filter_map(|(object, o)| match o.shape {
                Shape::Quad { corner, edge_u, edge_v } => {
                    let normal = edge_u.cross(edge_v);
                    Some(PreparedQuad {
                        object,
                        corner,
                        edge_u,
                        edge_v,
                        normal,
                        parallel_tolerance: 1e-12 * normal.length(),
                        dual: normal / normal.dot(normal),
                    })
                }
                Shape::Sphere { .. } => None,
            })
            .collect();
        let runs = runs(&quads);
        let boxed = runs.iter().any(|run| run.bounds.is_some());
        Self { quads, runs, boxed }
    }

    /// Lowers `best` (the closest `(t, object)` so far, `t < t_max`) to every quad hit that
    /// beats it by [`offer`]'s rule; a quad whose plane lies beyond `best` costs no edge test, a
    /// run whose box lies beyond it no test at all.
    pub(super) fn closest(&self, ray: &Ray<f64>, t_max: f64, best: &mut Option<(f64, usize)>) {
        let (dir_length, slab) = (ray.dir.length(), SlabRay::new(ray, self.boxed));
        for run in &self.runs {
            if let Some(bounds) = run.bounds
                && !bounds.may_hit(&slab, best.map_or(t_max, |(limit, _)| limit))
            {
                continue;
            }
            for quad in &self.quads[run.quads.clone()] {
                let hit = match *best {
                    Some((limit, _)) => quad.hit_within(ray, dir_length, limit),
                    None => quad.hit_within(ray, dir_length, t_max).filter(|&t| t < t_max),
                };
                if let Some(t) = hit {
                    offer(best, quad.object, t);
                }
            }
        }
    }

    /// Whether some quad is hit with `t ∈ (0, t_max)`; stops at the first one found.
    pub(super) fn any_before(&self, ray: &Ray<f64>, t_max: f64) -> bool {
        let (dir_length, slab) = (ray.dir.length(), SlabRay::new(ray, self.boxed));
        self.quads_near(&slab, t_max).any(|quad| quad.hit_within(ray, dir_length, t_max).is_some_and(|t| t < t_max))
    }

    /// How many quads are hit with `t ∈ (0, t_max)`.
    pub(super) fn count_before(&self, ray: &Ray<f64>, t_max: f64) -> usize {
        let (dir_length, slab) = (ray.dir.length(), SlabRay::new(ray, self.boxed));
        self.quads_near(&slab, t_max)
            .filter(|quad| quad.hit_within(ray, dir_length, t_max).is_some_and(|t| t < t_max))
            .count()
    }

    /// The quads of every run whose box the ray may meet within `(0, limit]` (all of an unboxed
    /// run's), in object order: the candidates of a query with a fixed limit.
    fn quads_near<'a>(&'a self, slab: &'a SlabRay, limit: f64) -> impl Iterator<Item = &'a PreparedQuad> + 'a {
        self.runs
            .iter()
            .filter(move |run| run.bounds.is_none_or(|bounds| bounds.may_hit(slab, limit)))
            .flat_map(|run| &self.quads[run.quads.clone()])
    }
}

/// The runs of `quads`: starting from one run per quad, the two neighbouring runs whose merge
/// lowers the estimated cost most are merged until no merge lowers it. A run of `k` quads costs
/// `k` tests without a box and `BOX_COST + k · A/A_all` with one (`A` the area of its box, `A_all`
/// that of the box around every quad), whichever is less.
fn runs(quads: &[PreparedQuad]) -> Vec<Run> {
    let single = |k: usize| Run { quads: k..k + 1, bounds: None };
    if quads.len() < 2 || quads.len() > MAX_GROUPED_QUADS {
        return (0..quads.len()).map(single).collect();
    }
    let all = Bounds::around(quads).area();
    if !(all.is_finite() && all > 0.0) {
        return (0..quads.len()).map(single).collect();
    }
    let cost = |range: Range<usize>| -> (f64, Option<Bounds>) {
        let count = range.len() as f64;
        let bounds = Bounds::around(&quads[range]);
        let boxed = BOX_COST + count * bounds.area() / all;
        if boxed < count { (boxed, Some(bounds)) } else { (count, None) }
    };
    let mut runs: Vec<(Run, f64)> = (0..quads.len()).map(|k| (single(k), 1.0)).collect();
    loop {
        let best_merge = (0..runs.len() - 1)
            .map(|k| {
                let merged = runs[k].0.quads.start..runs[k + 1].0.quads.end;
                let (merged_cost, bounds) = cost(merged.clone());
                (runs[k].1 + runs[k + 1].1 - merged_cost, k, Run { quads: merged, bounds }, merged_cost)
            })
            .filter(|(saving, ..)| *saving > 0.0)
            .max_by(|a, b| a.0.total_cmp(&b.0));
        let Some((_, k, run, merged_cost)) = best_merge else { break };
        runs[k] = (run, merged_cost);
        runs.remove(k + 1);
        if runs.len() < 2 {
            break;
        }
    }
    runs.into_iter().map(|(run, _)| run).collect()
}

/// Makes `(t, object)` the closest hit when it is nearer than `best`, or as near with a lower
/// object index (the tie rule of every closest-hit query).
pub(super) fn offer(best: &mut Option<(f64, usize)>, object: usize, t: f64) {
    if best.is_none_or(|(u, j)| t < u || (t == u && object < j)) {
        *best = Some((t, object));
    }
}

/// What the tests read of a [`QuadSet`]: its runs with whether each has a box, and the object
/// index of every quad in a boxed run.
#[cfg(test)]
impl QuadSet {
    pub(crate) fn runs_and_boxed_objects(&self) -> (Vec<(Range<usize>, bool)>, Vec<usize>) {
        let runs = self.runs.iter().map(|run| (run.quads.clone(), run.bounds.is_some())).collect();
        let boxed = self
            .runs
            .iter()
            .filter(|run| run.bounds.is_some())
            .flat_map(|run| self.quads[run.quads.clone()].iter().map(|quad| quad.object))
            .collect();
        (runs, boxed)
    }
}
