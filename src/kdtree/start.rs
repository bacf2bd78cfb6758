//! Where a walk begins: a coarse uniform grid over the tree's box whose every cell names the
//! deepest node that holds the whole cell, with that node's cell.
//!
//! # Why
//! Every walk used to begin at the root and descend to the cell where the ray enters the tree:
//! at N = 10⁵ (fixed k) about 15 of a random ray's 52 node steps, each a dependent load and, for a
//! camera ray, a branch. One look-up in a small grid (a few hundred cells, so it stays in the
//! nearest cache) replaces the top of that descent: the walk begins at the node `S` of the grid
//! cell where the ray's interval begins.
//!
//! # Why the answers do not change
//! The walk from the root over `[t, t_end]` reaches `S` with the interval `[t, min(t_end, t_exit)]`
//! when, in the walk's own arithmetic (`(s − e_a) · (1/d_a)` per plane), every face of `S`'s cell
//! that the ray moves away from has its plane parameter at most `t` (the walk finds the near piece
//! of that ancestor's split empty and goes to `S`'s side) and every face it moves towards has it
//! above `t` (the near piece, `S`'s side, is live, and the far piece, if live, ends the interval at
//! that plane). The parameters of an ancestor's plane and of the face it bounds grow together (a
//! correctly rounded `(s − e_a) · (1/d_a)` is monotonic in `s`), so the faces' smallest exit
//! parameter `t_exit` is where the walk's interval at `S` ends. An axis the ray is parallel to goes,
//! in the walk, to the side of the origin (`e_a ≥ s` upwards): there the origin must lie in `S`'s
//! half-open cell. [`StartGrid::find`] checks exactly these conditions, so a start it gives is the
//! root walk's own state at `S`, whatever rounding did to the grid cell's choice.
//!
//! Below `S` the walk is the root walk. What the root walk would pop after `S` (the far children
//! of `S`'s ancestors, the first beginning at `t_exit`) is one stack entry here: the root over
//! `[t_exit, t_end]`, whose walk makes the same decisions at every plane and so visits the same
//! cells after `S`, at the cost of a second descent from the root to the first of them, which is a
//! child of an ancestor of `S`. So the walk tests the same spheres in the same leaves in the same
//! order, and never takes more node steps than from the root (tested: same answers, same sphere
//! tests, no more steps, on random scenes and rays with origins on planes and grid lines).
//!
//! See also: Reshetov, Soupikov and Hurley, "Multi-level ray tracing algorithm", ACM TOG 24(3),
//! 2005, which finds a deeper entry node for a whole beam of rays at once.

use super::node::{Aabb, Node, NodeKind};
use super::{AxisLine, ReciprocalAxis};
use crate::geometry::Ray;
use glam::DVec3;

/// A grid cell's entry: the deepest node whose cell holds the grid cell, and that node's cell as
/// `f32` bounds (every split is an `f32`; a face on the tree's box is `∓∞`, where the root
/// interval, clipped to the box, already ends).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
struct Start {
    lo: [f32; 3],
    hi: [f32; 3],
    node: u32,
}

/// The grid of [`Start`]s over one tree's box.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct StartGrid {
    /// `x` fastest, then `y`, then `z`.
    cells: Vec<Start>,
    /// Cells per axis.
    resolution: usize,
    corner: DVec3,
    /// Cells per unit length on each axis (0 on an axis without extent).
    scale: DVec3,
}

impl StartGrid {
    /// The grid of the tree `nodes` (root first) over its box `bounds`, with about one cell per
    /// `nodes_per_cell` nodes: at least one cell, at most 64 per axis.
    pub fn new(nodes: &[Node], bounds: &Aabb, nodes_per_cell: usize) -> Self {
        let target = (nodes.len() / nodes_per_cell.max(1)).max(1) as f64;
        let resolution = (target.cbrt().round() as usize).clamp(1, 64);
        let extent = bounds.max - bounds.min;
        let cell = extent / resolution as f64;
        let scale = DVec3::select(extent.cmpgt(DVec3::ZERO), DVec3::splat(resolution as f64) / extent, DVec3::ZERO);
        let mut cells = Vec::with_capacity(resolution.pow(3));
        for k in 0..resolution {
            for j in 0..resolution {
                for i in 0..resolution {
                    let at = DVec3::new(i as f64, j as f64, k as f64);
                    cells.push(deepest_holding(nodes, bounds.min + cell * at, bounds.min + cell * (at + 1.0)));
                }
            }
        }
        Self { cells, resolution, corner: bounds.min, scale }
    }

    /// Where the walk of `ray` (axes `axes`) over an interval that begins at `t` may begin: the
    /// node of the grid cell of the point at `t`, and the parameter `t_exit > t` where the ray
    /// leaves that node's cell; `None` when the walk from the root would not reach that node with
    /// its interval beginning at `t` (the module docs give the conditions, checked exactly here).
    /// A one-cell grid names the root, whose cell has no face inside the box: it answers the root
    /// with `t_exit = ∞` for every `t` that is not NaN, the walk as it was without a grid.
    #[inline]
    pub fn find(&self, ray: &Ray<f64>, axes: &[ReciprocalAxis; 3], t: f64) -> Option<(u32, f64)> {
        let n = self.resolution;
        let point = ray.at(t);
        let index = |a: usize| {
            // `as` saturates: a NaN offset is cell 0; the clamp keeps a point on or beyond the
            // box's far face in the last cell.
            ((point[a] - self.corner[a]) * self.scale[a]).max(0.0).min((n - 1) as f64) as usize
        };
        let start = &self.cells[(index(2) * n + index(1)) * n + index(0)];
        let (mut t_entry, mut t_exit) = (f64::NEG_INFINITY, f64::INFINITY);
        for a in 0..3 {
            let (lo, hi) = (f64::from(start.lo[a]), f64::from(start.hi[a]));
            if axes[a].is_parallel() {
                let e = axes[a].origin();
                if !(lo <= e && e < hi) {
                    return None;
                }
                continue;
            }
            let (entry, exit) = if axes[a].increasing() { (lo, hi) } else { (hi, lo) };
            t_entry = t_entry.max(axes[a].plane_t(entry));
            t_exit = t_exit.min(axes[a].plane_t(exit));
        }
        (t_entry <= t && t < t_exit).then_some((start.node, t_exit))
    }
}

/// The deepest node of `nodes` whose cell holds the box `[lo, hi]`, with its cell.
fn deepest_holding(nodes: &[Node], lo: DVec3, hi: DVec3) -> Start {
    let mut start = Start { lo: [f32::NEG_INFINITY; 3], hi: [f32::INFINITY; 3], node: 0 };
    while let NodeKind::Interior { split, upper, axis } = nodes[start.node as usize].kind() {
        // Splits are `f32`s, so narrowing is exact.
        if hi[axis] <= split {
            start.hi[axis] = split as f32;
            start.node += 1;
        } else if lo[axis] >= split {
            start.lo[axis] = split as f32;
            start.node = upper;
        } else {
            break;
        }
    }
    start
}
