//! The node layout both the builder and the traversal read: the bounding box, the packed 8-byte
//! node and its decoded view, and the cells a built tree's splits make ([`visit_cells`]).

use glam::DVec3;
use hw3_core::geometry::Ray;

/// An axis-aligned box `min ≤ p ≤ max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Aabb {
    pub fn union(self, other: Self) -> Self {
        Self { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    pub fn surface_area(&self) -> f64 {
        let e = self.max - self.min;
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// The part of `[t_min, t_max]` where the ray is inside the closed box, or `None`.
    /// A parallel ray is inside iff its origin is; comparisons are written so that no division by
    /// zero occurs.
    pub fn clip(&self, ray: &Ray<f64>, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        let (mut t0, mut t1) = (t_min, t_max);
        for a in 0..3 {
            let (o, d) = (ray.origin[a], ray.dir[a]);
            if d == 0.0 {
                if !(self.min[a] <= o && o <= self.max[a]) {
                    return None;
                }
                continue;
            }
            let (t_lo, t_hi) = ((self.min[a] - o) / d, (self.max[a] - o) / d);
            t0 = t0.max(t_lo.min(t_hi));
            t1 = t1.min(t_lo.max(t_hi));
        }
        (t0 <= t1).then_some((t0, t1))
    }
}

/// A node of the flat array, packed into 8 bytes (pbrt-v3's layout): `payload` holds the split
/// value's `f32` bits (interior) or the first index (leaf); `tag`'s low two bits hold the split axis,
/// or 3 for a leaf, and its upper 30 bits the upper child's index (interior) or the sphere count
/// (leaf). An interior node's lower child is the next node. Split values are `f32` by construction
/// (the builder only picks `f32`-representable planes), so widening them back to `f64` is exact and
/// the traversal still works in `f64` throughout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Node {
    payload: u32,
    tag: u32,
}

/// The decoded view of a [`Node`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum NodeKind {
    Interior { split: f64, upper: u32, axis: usize },
    Leaf { first: u32, count: u32 },
}

/// The tag value marking a leaf; also the largest index or count the upper 30 bits can hold + 1.
const LEAF_TAG: u32 = 3;
pub(crate) const MAX_PACKED: u32 = 1 << 30;

impl Node {
    /// # Panics
    /// If `upper ≥ 2³⁰` or `axis > 2` (the builder's invariants).
    pub fn interior(split: f32, axis: usize, upper: u32) -> Self {
        assert!(upper < MAX_PACKED && axis < 3, "kd-tree node index {upper} or axis {axis} out of range");
        Self { payload: split.to_bits(), tag: (upper << 2) | axis as u32 }
    }

    /// # Panics
    /// If `count ≥ 2³⁰` (the builder rejects such scenes first).
    pub fn leaf(first: u32, count: u32) -> Self {
        assert!(count < MAX_PACKED, "kd-tree leaf of {count} spheres out of range");
        Self { payload: first, tag: (count << 2) | LEAF_TAG }
    }

    /// The node with its upper-child index raised by `nodes` (interior) or its first index by
    /// `indices` (leaf): a subtree's node moved to where another array places it.
    ///
    /// # Panics
    /// If the shifted index leaves the 30 bits (interior) or 32 bits (leaf) it is stored in.
    pub fn shifted(self, nodes: u32, indices: u32) -> Self {
        match self.kind() {
            NodeKind::Interior { upper, .. } => {
                let upper = upper.checked_add(nodes).filter(|&u| u < MAX_PACKED).expect("kd-tree node index in range");
                Self { payload: self.payload, tag: (upper << 2) | (self.tag & 3) }
            }
            NodeKind::Leaf { first, .. } => {
                Self { payload: first.checked_add(indices).expect("kd-tree index in range"), tag: self.tag }
            }
        }
    }

    #[inline]
    pub fn kind(self) -> NodeKind {
        let axis = self.tag & 3;
        if axis == LEAF_TAG {
            NodeKind::Leaf { first: self.payload, count: self.tag >> 2 }
        } else {
            NodeKind::Interior {
                split: f64::from(f32::from_bits(self.payload)),
                upper: self.tag >> 2,
                axis: axis as usize,
            }
        }
    }
}

/// Calls `visit` with every node of the tree `nodes` and its cell, depth first from the root (each
/// upper subtree before its lower one): the root's is `bounds`; an interior node's lower child
/// (the next node) takes the part below its split plane, its upper child the part above. The one
/// place the cells are derived from the splits, for the measures of a built tree.
pub(crate) fn visit_cells(nodes: &[Node], bounds: Aabb, mut visit: impl FnMut(NodeKind, &Aabb)) {
    let mut cells = vec![(0u32, bounds)];
    while let Some((node, cell)) = cells.pop() {
        let kind = nodes[node as usize].kind();
        visit(kind, &cell);
        if let NodeKind::Interior { split, upper, axis } = kind {
            let (mut lower_cell, mut upper_cell) = (cell, cell);
            lower_cell.max[axis] = split;
            upper_cell.min[axis] = split;
            cells.push((node + 1, lower_cell));
            cells.push((upper, upper_cell));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The chapter's memory figures assume 8-byte nodes.
    #[test]
    fn nodes_are_8_bytes_and_round_trip() {
        assert_eq!(std::mem::size_of::<Node>(), 8);
        let interior = Node::interior(0.375, 2, MAX_PACKED - 1);
        assert_eq!(interior.kind(), NodeKind::Interior { split: 0.375, upper: MAX_PACKED - 1, axis: 2 });
        assert_eq!(Node::leaf(u32::MAX, 7).kind(), NodeKind::Leaf { first: u32::MAX, count: 7 });
        assert_eq!(interior.shifted(0, 9), interior);
        assert_eq!(
            Node::interior(0.375, 1, 5).shifted(10, 9).kind(),
            NodeKind::Interior { split: 0.375, upper: 15, axis: 1 }
        );
        assert_eq!(Node::leaf(3, 7).shifted(10, 9).kind(), NodeKind::Leaf { first: 12, count: 7 });
    }
}
