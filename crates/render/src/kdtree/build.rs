//! The binned SAH builder: node layout, cost model and the recursive split search.
//!
//! # Cost model (surface area heuristic, Havran 2000; Wald & Havran 2006)
//! A split of a cell of surface area `A` into cells of areas `A_L`, `A_R` holding `N_L`, `N_R`
//! spheres costs `K_T + K_I (1 − b) (A_L/A · N_L + A_R/A · N_R)`, where `b` is the empty-space
//! bonus (only when `N_L` or `N_R` is 0); a leaf costs `K_I · N`. The node becomes a leaf when no
//! split beats that, when it holds at most one sphere, or at depth `8 + 1.3 log₂ N` (pbrt-v3's
//! bound; it also bounds the traversal stack). Default constants: see [`SahCosts::default`].
//!
//! # Candidates and complexity
//! Each node bins its spheres' bounding-box starts and ends (clamped to the cell) into
//! [`SahCosts::bins`] equal bins per axis and evaluates the planes between bins — the min-max
//! binning that Mitsuba uses near the top of its trees — instead of Wald & Havran's exact event
//! sweep. A node costs `O(n + bins)` per axis, so with depth `O(log N)` the whole build is
//! `O(N log N)`; the price is that the chosen plane is only the best of `bins − 1` candidates.
//! A node of at most [`EXACT_MAX`] spheres instead tries every box face (Wald & Havran's candidate
//! set; each face's two side counts taken over padded fixed-width arrays on the stack, no sort),
//! fewer planes than the bins and the exact best among them. Nodes of at least [`PARALLEL_MIN`]
//! spheres build their two children on two threads (`rayon::join`).
//!
//! # Vector code
//! On x86-64 the bins of a box are computed two lanes at a time (SSE2 intrinsics, the baseline).
//! The small nodes' side counts are plain loops written so that the compiler vectorises them
//! (box by box, each box compared with every face at once), and both searches are compiled a
//! second time for AVX2, used when the CPU has it (checked at run time): four lanes instead of
//! two. Every lane does the scalar code's IEEE operations in the same order, so the tree is the
//! same bit for bit on any CPU; the tests compare each vector path with the scalar one.
//!
//! # Branches
//! Which child a box goes to is as good as random, so the split passes ([`partition`] and the
//! parallel levels' pass) write every box to both places and advance each end by its test, with
//! no branch per box.
//! Spheres whose box touches or crosses the plane go to both children (closed test on both
//! sides), so every cell whose closure contains a sphere's point lists that sphere.

use super::node::{Aabb, MAX_PACKED, Node};
use hw3_core::geometry::{InputError, Sphere};
use std::sync::atomic::{AtomicBool, Ordering};

/// Constants of the SAH cost model and the binning.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SahCosts {
    /// `K_T`: cost of one interior-node step.
    pub traversal: f64,
    /// `K_I`: cost of one ray/sphere test, in the same unit.
    pub intersection: f64,
    /// `b`: fraction of the cost forgiven when a split cuts off empty space (0 ≤ b < 1).
    pub empty_bonus: f64,
    /// Candidate planes per axis + 1 (≥ 2).
    pub bins: usize,
}

impl Default for SahCosts {
    /// `K_T = 1`, `K_I = 0.075`, `b = 0.2`, 32 bins.
    ///
    /// The costs are this tree's, measured, not a textbook's: a node step is a dependent load from
    /// a tree that outgrows the cache, while a sphere test is mostly an 8-byte conservative reject
    /// made several at a time on data beside its leaf's other spheres, so a step costs about
    /// thirteen tests, and a ray should rather test a few more spheres than walk many small cells.
    /// With these costs any node of up to 13 spheres is a leaf (`13 × 0.075 < 1`). The Q3
    /// benchmark's `ab` mode times trees of two `K_I` in turns in one process; the Q3 engineering
    /// notes give the current comparison. The textbooks' (traversal, intersection) costs:
    /// pbrt-v4's `KdTreeAggregate` (1, 5), pbrt-v3's `KdTreeAccel` (1, 80), Mitsuba 0.5 (15, 20),
    /// each with an empty-space bonus.
    fn default() -> Self {
        Self { traversal: 1.0, intersection: 0.075, empty_bonus: 0.2, bins: 32 }
    }
}

/// Why a kd-tree could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BuildError {
    /// A sphere's centre or radius is not finite, its radius is negative, or its bounding box
    /// overflows.
    #[error("sphere {index}: {source}")]
    InvalidSphere {
        /// The sphere's index in the input slice.
        index: usize,
        /// What is wrong with it.
        source: InputError,
    },
    /// More spheres than a `u32` index can address.
    #[error("{count} spheres exceed the kd-tree's limit of 2^30 − 1 (30-bit counts in 8-byte nodes)")]
    TooManySpheres {
        /// The number given.
        count: usize,
    },
    /// The cost constants are out of range.
    #[error("invalid SAH constants: {0}")]
    InvalidCosts(&'static str),
    /// [`super::KdTree::build_moving`] got a different number of velocities than spheres.
    #[error("{velocities} velocities for {spheres} spheres")]
    VelocityCount {
        /// Spheres given.
        spheres: usize,
        /// Velocities given.
        velocities: usize,
    },
}

/// The input spheres as the builder reads them: each one's index and validated bounding box, in
/// input order (made here in one pass, not as a list of boxes copied into a list of `Prim`s: one
/// pass and one array of fresh pages fewer). From [`PARALLEL_MIN`] spheres on, on the rayon pool
/// (each box depends on its sphere alone, so the list is the same); the error is always the one
/// of the lowest invalid index, as in a serial pass.
pub(super) fn sphere_prims(spheres: &[Sphere<f64>]) -> Result<Vec<Prim>, BuildError> {
    use rayon::prelude::*;
    if spheres.len() >= MAX_PACKED as usize {
        return Err(BuildError::TooManySpheres { count: spheres.len() });
    }
    let serial = || spheres.iter().enumerate().map(sphere_box).collect();
    if spheres.len() < PARALLEL_MIN {
        return serial();
    }
    // An indexed collect writes each box in place (collecting `Result`s would gather pieces and
    // copy them); an invalid sphere leaves a placeholder and a flag, and the serial pass then names
    // the lowest invalid index.
    let invalid = AtomicBool::new(false);
    let boxes = spheres
        .par_iter()
        .enumerate()
        .with_min_len(PARALLEL_CHUNK)
        .map(|item| {
            sphere_box(item).unwrap_or_else(|_| {
                invalid.store(true, Ordering::Relaxed);
                Prim { index: 0, bounds: Aabb { min: glam::DVec3::ZERO, max: glam::DVec3::ZERO } }
            })
        })
        .collect();
    if invalid.into_inner() { serial() } else { Ok(boxes) }
}

/// Sphere `index` with its validated bounding box.
fn sphere_box((index, s): (usize, &Sphere<f64>)) -> Result<Prim, BuildError> {
    let invalid = |source| BuildError::InvalidSphere { index, source };
    let valid = Sphere::new(s.center, s.radius).map_err(invalid)?;
    let r = glam::DVec3::splat(valid.radius);
    let bounds = Aabb { min: valid.center - r, max: valid.center + r };
    if bounds.min.is_finite() && bounds.max.is_finite() {
        // Below 2³⁰ (checked by the caller).
        Ok(Prim { index: index as u32, bounds })
    } else {
        Err(invalid(InputError::OutOfRange {
            name: "sphere bounds",
            value: format!("{bounds:?}"),
            expected: "finite (centre ± radius must not overflow)",
        }))
    }
}

pub(super) fn check_costs(costs: &SahCosts) -> Result<(), BuildError> {
    let positive = |x: f64| x.is_finite() && x > 0.0;
    if !positive(costs.traversal) || !positive(costs.intersection) {
        return Err(BuildError::InvalidCosts("K_T and K_I must be finite and > 0"));
    }
    if !(0.0..1.0).contains(&costs.empty_bonus) {
        return Err(BuildError::InvalidCosts("the empty bonus must lie in [0, 1)"));
    }
    if !(2..=MAX_BINS).contains(&costs.bins) {
        return Err(BuildError::InvalidCosts("bins must lie in 2..=1024"));
    }
    Ok(())
}

/// The largest tree depth the builder makes, whatever the scene; the traversal stack is sized by it.
pub(super) const MAX_DEPTH: usize = 60;

/// The maximum depth for `n` spheres: `round(8 + 1.3 log₂ n)`, at most [`MAX_DEPTH`].
pub(super) fn max_depth(n: usize) -> usize {
    let n = n.max(1) as f64;
    ((8.0 + 1.3 * n.log2()).round() as usize).min(MAX_DEPTH)
}

/// The recursive builder's inputs.
pub(super) struct Builder {
    pub costs: SahCosts,
    pub max_depth: usize,
    /// Nodes of at most this many spheres try every box face ([`EXACT_MAX`] in the crate's trees).
    pub exact_max: usize,
}

/// A sphere as the builder reads it: its index in the input slice and its bounding box, carried
/// along with the index so that a node reads its spheres' boxes in order (from the input slice by
/// index, each read at every level was a cache miss on large scenes).
#[derive(Debug, Clone, Copy)]
pub(super) struct Prim {
    pub index: u32,
    pub bounds: Aabb,
}

/// A built subtree: its nodes in pre-order (an interior node's lower child directly follows it) and
/// its leaves' concatenated sphere lists, with node and list positions relative to these arrays.
#[derive(Debug, Default)]
pub(super) struct Subtree {
    pub nodes: Vec<Node>,
    pub indices: Vec<u32>,
}

impl Subtree {
    /// Reserves room for the subtree of a node of `count` spheres beyond what is there: about a
    /// node per sphere and two references (more than the benchmark's trees need: 0.4–0.6 nodes
    /// and 1.1–2.0 references per sphere). Only capacity: pages never written are never touched.
    fn reserve(&mut self, count: usize) {
        self.nodes.reserve(count);
        self.indices.reserve(2 * count);
    }

    /// Appends `other`, shifting its upper-child and first-index fields by where it lands.
    fn append(&mut self, other: Self) {
        let node_offset = u32::try_from(self.nodes.len()).expect("node count fits u32");
        let index_offset = u32::try_from(self.indices.len()).expect("index count fits u32");
        self.nodes.extend(other.nodes.into_iter().map(|node| node.shifted(node_offset, index_offset)));
        self.indices.extend(other.indices);
    }
}

/// Spheres up to which a node tries every box face as its plane instead of binned planes: `2n`
/// faces are then fewer than the binned planes, sorting them is cheap, and the face lists fit on
/// the stack. With the default `K_I = 0.075` nodes of up to 13 spheres are leaves without a
/// search, so only nodes of 14 to 16 spheres take the exact set. A test pins that the exact set is
/// never worse than the binned one at the default, and strictly better at `K_I = 0.3`.
pub(super) const EXACT_MAX: usize = 16;

/// The largest `exact_max` a [`Builder`] accepts (its face arrays live on the stack).
const EXACT_MAX_LIMIT: usize = 16;

/// The largest `f32` strictly below `x` (as `f64`).
fn f32_below(x: f64) -> f64 {
    let y = x as f32;
    f64::from(if f64::from(y) < x { y } else { y.next_down() })
}

/// The smallest `f32` strictly above `x` (as `f64`).
fn f32_above(x: f64) -> f64 {
    let y = x as f32;
    f64::from(if f64::from(y) > x { y } else { y.next_up() })
}

/// Spheres from which a node builds its two subtrees on two threads (`rayon::join`): below it the
/// per-subtree bookkeeping costs more than the second thread saves. The per-sphere passes around
/// the build (boxes, quantised copies, leaf arrays) run on the pool from this many items on too.
pub(super) const PARALLEL_MIN: usize = 8_192;

/// The fewest items a rayon task of the per-sphere passes takes: fewer tasks than items by far, so
/// that splitting and stealing cost nothing next to the work.
pub(super) const PARALLEL_CHUNK: usize = 4_096;

/// Bin counts up to which [`Builder::best_split`] keeps its counts on the stack.
const INLINE_BINS: usize = 32;

/// The largest bin count [`check_costs`] accepts (a power of two: the width of the heap rows).
const MAX_BINS: usize = 1024;

/// One axis of a small node for [`Builder::exact_axis`]: its boxes' starts and ends on the axis,
/// the first `m` real and the rest padding.
#[derive(Clone, Copy)]
struct ExactAxis<'a> {
    cell: &'a Aabb,
    area: f64,
    axis: usize,
    starts: &'a [f64; EXACT_MAX_LIMIT],
    ends: &'a [f64; EXACT_MAX_LIMIT],
    m: usize,
}

/// `(#(start ≤ split), #(end ≥ split))` for each of the first `2W` faces in `splits`, over the
/// first `m` boxes (`m ≤ W`): the builder's closed tests for the two children, as `f64` counts
/// for the cost. Box by box, each box's start and end compared with every face at once: the
/// inner loop has a constant length and no dependence between faces, so it compiles to vector
/// compares and adds (four faces per instruction where the caller is compiled for AVX2), with no
/// per-face sum across lanes. The counts are exact either way (integers below 2⁵³).
#[inline(always)]
fn face_counts<const W: usize>(
    splits: &[f64; 2 * EXACT_MAX_LIMIT],
    starts: &[f64; EXACT_MAX_LIMIT],
    ends: &[f64; EXACT_MAX_LIMIT],
    m: usize,
) -> ([f64; 2 * EXACT_MAX_LIMIT], [f64; 2 * EXACT_MAX_LIMIT]) {
    const { assert!(W <= EXACT_MAX_LIMIT) };
    let (mut lowers, mut uppers) = ([0.0; 2 * EXACT_MAX_LIMIT], [0.0; 2 * EXACT_MAX_LIMIT]);
    for (&start, &end) in starts[..m.min(W)].iter().zip(&ends[..m.min(W)]) {
        let faces = splits[..2 * W].iter().zip(&mut lowers[..2 * W]).zip(&mut uppers[..2 * W]);
        for ((&split, lower), upper) in faces {
            *lower += if start <= split { 1.0 } else { 0.0 };
            *upper += if end >= split { 1.0 } else { 0.0 };
        }
    }
    (lowers, uppers)
}

/// The best split found for one node.
struct Candidate {
    axis: usize,
    split: f64,
    cost: f64,
}

/// Appends a leaf listing `prims` to `out`.
fn push_leaf(prims: &[Prim], out: &mut Subtree) {
    let first = u32::try_from(out.indices.len()).expect("index count fits u32");
    let count = u32::try_from(prims.len()).expect("sphere count fits u32");
    out.indices.extend(prims.iter().map(|p| p.index));
    out.nodes.push(Node::leaf(first, count));
}

/// Splits the boxes `list[start..end]` at `split` on `axis` in one pass, each box read once, in
/// order: the boxes reaching below the plane (`min ≤ split`) are compacted in place to the front
/// of the range, and those reaching above it (`max ≥ split`; a box on the plane goes to both) are
/// appended to `list`. Returns the end of the compacted lower part; `list[end..]` is left as it
/// was, then the upper part. Every box is written to both places and each place's end advanced
/// by its test, without a branch: which side a box falls on is as good as random, and the
/// mispredicted branches were the pass's largest cost. (`kept ≤ i`, so the compaction never
/// overwrites a box not yet read.)
fn partition(list: &mut Vec<Prim>, start: usize, end: usize, axis: usize, split: f64) -> usize {
    let top = list.len();
    // Room for every box going up, filled with copies that are then overwritten.
    list.extend_from_within(start..end);
    let (mut kept, mut upper) = (start, top);
    for i in start..end {
        let p = list[i];
        let (goes_down, goes_up) = sides(&p, axis, split);
        list[upper] = p;
        upper += usize::from(goes_up);
        list[kept] = p;
        kept += usize::from(goes_down);
    }
    list.truncate(upper);
    kept
}

/// Whether the box of `p` reaches the lower child of a split at `split` on `axis`
/// (`min ≤ split`) and the upper one (`max ≥ split`): closed tests, so a box on the plane goes to
/// both, and a NaN to neither (the builder never makes one).
#[inline(always)]
fn sides(p: &Prim, axis: usize, split: f64) -> (bool, bool) {
    // As arrays: indexing a glam vector by a run-time axis is a three-way branch.
    (p.bounds.min.to_array()[axis] <= split, p.bounds.max.to_array()[axis] >= split)
}

/// The two cells of `cell` split on `axis` at `split` (lower, upper).
fn children(cell: Aabb, axis: usize, split: f64) -> (Aabb, Aabb) {
    let (mut lower, mut upper) = (cell, cell);
    lower.max[axis] = split;
    upper.min[axis] = split;
    (lower, upper)
}

impl Builder {
    /// Builds the subtree of `cell` holding `prims`, appending it to `out` (pre-order: the lower
    /// child directly follows its parent). Nodes of at least [`PARALLEL_MIN`] spheres build their
    /// children in parallel, each child from a list of its own, the lower child into `out`, the
    /// upper into a [`Subtree`] of its own appended after it; smaller ones build serially in one
    /// scratch list ([`Builder::build_serial`]). The result is the same tree as a serial build.
    pub fn build(&self, cell: Aabb, mut prims: Vec<Prim>, depth: usize, out: &mut Subtree) {
        if prims.len() < PARALLEL_MIN {
            let count = prims.len();
            let mut scratch = prims;
            // Room for the upper lists the serial build appends (they add up to about the node's
            // own count, more where spheres straddle planes), reserved once: growing on demand
            // copied the list several times (at 10⁶, fixed volume, 83 reallocations of scratch
            // lists and 459 of the parallel levels' arrays copied 93 M instructions' worth).
            scratch.reserve(2 * count);
            out.reserve(count);
            self.build_serial(cell, &mut scratch, 0, count, depth, out);
            return;
        }
        let Some(Candidate { axis, split, .. }) = self.choose(&cell, &prims, depth) else {
            push_leaf(&prims, out);
            return;
        };
        // One pass, each box read once, in order, written to both children and each end advanced
        // by its test, as in [`partition`]. The lower child keeps the parent's list, compacted in
        // place (a fresh list for it was written into fresh pages, and at N = 10⁶ the kernel's
        // page faults and page clearing were a tenth of the build); the upper child's boxes go to
        // a fresh list's spare capacity (appending them to the parent's list, as `partition`
        // does, doubled that list here: a copy and fresh pages at every parallel level).
        let count = prims.len();
        let mut upper = Vec::with_capacity(count);
        let spare = upper.spare_capacity_mut();
        let (mut kept, mut above) = (0, 0);
        for i in 0..count {
            let p = prims[i];
            let (goes_down, goes_up) = sides(&p, axis, split);
            // `above ≤ i < count`: inside the spare capacity.
            spare[above].write(p);
            above += usize::from(goes_up);
            prims[kept] = p;
            kept += usize::from(goes_down);
        }
        // SAFETY: the first `above` elements of the spare capacity were written in the loop.
        unsafe { upper.set_len(above) };
        prims.truncate(kept);
        let lower = prims;
        let here = out.nodes.len();
        out.nodes.push(Node::leaf(0, 0));
        let (lower_cell, upper_cell) = children(cell, axis, split);
        // The lower child builds straight into `out`, where it belongs (pre-order), and only the
        // upper child's arrays are copied, once: appending both had copied every node and index
        // twice per parallel level (the second append's growth copying the first's) into fresh
        // pages.
        let ((), upper_part) = rayon::join(
            || self.build(lower_cell, lower, depth + 1, out),
            || {
                let mut part = Subtree::default();
                part.reserve(upper.len());
                self.build(upper_cell, upper, depth + 1, &mut part);
                part
            },
        );
        let upper_index = u32::try_from(out.nodes.len()).expect("node count fits u32");
        out.append(upper_part);
        out.nodes[here] = Node::interior(split as f32, axis, upper_index);
    }

    /// Builds the subtree of `cell` holding `scratch[start..end]` into `out`, on one thread, with
    /// no allocation of its own: a split keeps the lower child's spheres in place (a compaction of
    /// `start..end`, in order) and appends the upper child's to `scratch`, whose end is the free
    /// space of every node below. `scratch[start..end]` is consumed; `scratch`'s length is left as
    /// it was found.
    fn build_serial(
        &self,
        cell: Aabb,
        scratch: &mut Vec<Prim>,
        start: usize,
        end: usize,
        depth: usize,
        out: &mut Subtree,
    ) {
        let Some(Candidate { axis, split, .. }) = self.choose(&cell, &scratch[start..end], depth) else {
            push_leaf(&scratch[start..end], out);
            return;
        };
        let top = scratch.len();
        let kept = partition(scratch, start, end, axis, split);
        let upper_end = scratch.len();
        let here = out.nodes.len();
        out.nodes.push(Node::leaf(0, 0));
        let (lower_cell, upper_cell) = children(cell, axis, split);
        self.build_serial(lower_cell, scratch, start, kept, depth + 1, out);
        let upper_index = u32::try_from(out.nodes.len()).expect("node count fits u32");
        self.build_serial(upper_cell, scratch, top, upper_end, depth + 1, out);
        scratch.truncate(top);
        out.nodes[here] = Node::interior(split as f32, axis, upper_index);
    }

    /// The split of the node of `cell` holding `prims` at `depth`, or `None` for a leaf: one sphere
    /// or none, the depth bound, or no candidate cheaper than the leaf.
    fn choose(&self, cell: &Aabb, prims: &[Prim], depth: usize) -> Option<Candidate> {
        let leaf_cost = self.costs.intersection * prims.len() as f64;
        // A split costs at least K_T (its other terms are products of non-negative factors), so a
        // leaf that costs no more (13 spheres, with the default constants) needs no search.
        if prims.len() <= 1 || depth >= self.max_depth || leaf_cost <= self.costs.traversal {
            return None;
        }
        let best = if prims.len() <= self.exact_max {
            self.best_exact_split(cell, prims)
        } else {
            self.best_split(cell, prims)
        };
        best.filter(|c| c.cost < leaf_cost)
    }

    /// The cheapest plane among every sphere's box faces (Wald & Havran's candidates, for a node
    /// small enough that counting its spheres on each side of each face costs less than binning):
    /// each face is moved to the nearest `f32` just outside its box, so that a plane at a box's
    /// start leaves that box wholly above it (the cut-off side really is empty and earns the bonus)
    /// and one at its end wholly below. Each plane's two counts are taken over all the node's boxes
    /// (at most [`EXACT_MAX_LIMIT`], in fixed-size arrays the compiler turns into vector compares):
    /// no sort, and no branch that depends on the data but the choice of the best. Among equally
    /// cheap planes of an axis the lowest wins, as in a sweep in plane order.
    #[inline(never)] // one call per node: a profile names it, and its callers stay small
    fn best_exact_split(&self, cell: &Aabb, prims: &[Prim]) -> Option<Candidate> {
        #[cfg(x86_simd)]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2 (checked just above).
            return unsafe { self.best_exact_split_avx2(cell, prims) };
        }
        self.exact_split(cell, prims)
    }

    /// [`Builder::best_exact_split`] compiled for AVX2 (checked at run time: the crate is compiled
    /// for x86-64's SSE2 baseline), so that the side counts take four faces per instruction instead
    /// of two. The same planes: a compare gives the same answer in any width, and nothing else
    /// changes width.
    #[cfg(x86_simd)]
    #[target_feature(enable = "avx2")]
    fn best_exact_split_avx2(&self, cell: &Aabb, prims: &[Prim]) -> Option<Candidate> {
        self.exact_split(cell, prims)
    }

    /// [`Builder::best_exact_split`]'s body.
    #[inline(always)]
    fn exact_split(&self, cell: &Aabb, prims: &[Prim]) -> Option<Candidate> {
        let area = cell.surface_area();
        let m = prims.len();
        assert!(m <= EXACT_MAX_LIMIT, "exact candidates for {m} spheres (at most {EXACT_MAX_LIMIT})");
        let mut best: Option<Candidate> = None;
        // The padding never counts: no plane lies above a start of +∞ or below an end of −∞.
        let (mut starts, mut ends) = ([f64::INFINITY; EXACT_MAX_LIMIT], [f64::NEG_INFINITY; EXACT_MAX_LIMIT]);
        for axis in 0..3 {
            let (lo, hi) = (cell.min[axis], cell.max[axis]);
            if !(hi - lo > 0.0) {
                continue;
            }
            for (k, p) in prims.iter().enumerate() {
                (starts[k], ends[k]) = (p.bounds.min[axis], p.bounds.max[axis]);
            }
            // The counts over the smallest padded width that holds the node's boxes: a node has
            // about six on average, and sixteen compares per count would triple the work.
            let faces = ExactAxis { cell, area, axis, starts: &starts, ends: &ends, m };
            match m {
                0..=4 => self.exact_axis::<4>(&faces, &mut best),
                5..=8 => self.exact_axis::<8>(&faces, &mut best),
                _ => self.exact_axis::<EXACT_MAX_LIMIT>(&faces, &mut best),
            }
        }
        best
    }

    /// Tries every face of one axis of [`Builder::best_exact_split`], counting over the first `W`
    /// entries of the padded arrays (`W ≥ m`, a constant so that the counts become vector code).
    #[inline(always)]
    fn exact_axis<const W: usize>(&self, faces: &ExactAxis<'_>, best: &mut Option<Candidate>) {
        let ExactAxis { cell, area, axis, starts, ends, m } = *faces;
        let (lo, hi) = (cell.min[axis], cell.max[axis]);
        // The cost model (module docs) with the cell's constants taken once per axis; the binned
        // search computes it the same way.
        let e = cell.max - cell.min;
        let (eb, ec) = (e[(axis + 1) % 3], e[(axis + 2) % 3]);
        let (cap, side) = (2.0 * eb * ec, 2.0 * (eb + ec));
        let (k_t, k_i, kept) = (self.costs.traversal, self.costs.intersection, 1.0 - self.costs.empty_bonus);
        // Face `2k` just below box `k`'s start, `2k + 1` just above its end: the order of a sweep
        // over the boxes, which the choice below keeps. The counts, the costs and the choice in
        // loops of their own, so that the costs (no dependence between faces) compile to vector
        // code, as in the binned search.
        let n = 2 * m;
        // The faces past `n` are NaN, on neither side of any box: their counts stay 0 and are never read.
        let mut splits = [f64::NAN; 2 * EXACT_MAX_LIMIT];
        for k in 0..m {
            (splits[2 * k], splits[2 * k + 1]) = (f32_below(starts[k]), f32_above(ends[k]));
        }
        let (lowers, uppers) = face_counts::<W>(&splits, starts, ends, m);
        let cost = |p_lower: f64, p_upper: f64, n_lower: f64, n_upper: f64| {
            let bonus = if n_lower == 0.0 || n_upper == 0.0 { kept } else { 1.0 };
            k_t + k_i * bonus * (p_lower * n_lower + p_upper * n_upper)
        };
        let mut costs = [0.0; 2 * EXACT_MAX_LIMIT];
        let faces = splits[..n].iter().zip(&lowers[..n]).zip(&uppers[..n]).zip(&mut costs[..n]);
        if area > 0.0 {
            for (((&split, &n_lower), &n_upper), c) in faces {
                let (p_lower, p_upper) = ((cap + side * (split - lo)) / area, (cap + side * (hi - split)) / area);
                *c = cost(p_lower, p_upper, n_lower, n_upper);
            }
        } else {
            for (((&split, &n_lower), &n_upper), c) in faces {
                let f = (split - lo) / (hi - lo);
                *c = cost(f, 1.0 - f, n_lower, n_upper);
            }
        }
        for (&split, &cost) in splits[..n].iter().zip(&costs[..n]) {
            if !(lo < split && split < hi) {
                continue;
            }
            let better = best.as_ref().is_none_or(|b| {
                cost < b.cost || (cost == b.cost && b.axis == axis && split.total_cmp(&b.split).is_lt())
            });
            if better {
                *best = Some(Candidate { axis, split, cost });
            }
        }
    }

    /// The cheapest binned plane over the three axes, if any axis has extent. One pass over the
    /// spheres bins all three axes; a candidate's child areas are linear in its plane, so each
    /// costs a few flops.
    #[inline(never)] // one call per node: a profile names it, and its callers stay small
    fn best_split(&self, cell: &Aabb, prims: &[Prim]) -> Option<Candidate> {
        #[cfg(x86_simd)]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2 (checked just above).
            return unsafe { self.best_split_avx2(cell, prims) };
        }
        self.binned_search(cell, prims)
    }

    /// [`Builder::best_split`] compiled for AVX2 (checked at run time), so that the candidates'
    /// costs take four planes per instruction instead of two. The same planes and costs: each
    /// lane does the same operations in the same order.
    #[cfg(x86_simd)]
    #[target_feature(enable = "avx2")]
    fn best_split_avx2(&self, cell: &Aabb, prims: &[Prim]) -> Option<Candidate> {
        self.binned_search(cell, prims)
    }

    /// [`Builder::best_split`]'s body.
    #[inline(always)]
    fn binned_search(&self, cell: &Aabb, prims: &[Prim]) -> Option<Candidate> {
        // On the stack for the default bin count, so that a node allocates nothing; rows of a
        // power-of-two width, so that a masked bin index needs no bounds check.
        if self.costs.bins <= INLINE_BINS {
            self.binned_split(cell, prims, &mut [[0u32; INLINE_BINS]; 6])
        } else {
            let mut heap = vec![[0u32; MAX_BINS]; 6];
            let rows: &mut [[u32; MAX_BINS]; 6] = heap.as_mut_slice().try_into().expect("six rows");
            self.binned_split(cell, prims, rows)
        }
    }

    /// [`Builder::best_split`] with `counts` (zeroed, `W ≥ bins`): row `a` the starts on axis `a`,
    /// row `3 + a` the ends.
    #[inline(always)]
    fn binned_split<const W: usize>(
        &self,
        cell: &Aabb,
        prims: &[Prim],
        counts: &mut [[u32; W]; 6],
    ) -> Option<Candidate> {
        let bins = self.costs.bins;
        const { assert!(W.is_power_of_two()) };
        assert!(bins <= W);
        let area = cell.surface_area();
        let (lo, hi) = (cell.min.to_array(), cell.max.to_array());
        let extent = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
        let scale = extent.map(|e| bins as f64 / e);
        let binner = Binner::new(lo, scale, (bins - 1) as f64);
        for p in prims {
            let bin = binner.bins(&p.bounds);
            // `bin[r] ≤ bins − 1 < W`: the mask changes nothing but spares the bounds check.
            for (row, &k) in counts.iter_mut().zip(&bin) {
                row[k & (W - 1)] += 1;
            }
        }
        let n = prims.len() as f64;
        // Dividing by a power of two is exact, so multiplying by its reciprocal gives the same
        // planes, one division per candidate fewer.
        let inv_bins = bins.is_power_of_two().then(|| 1.0 / bins as f64);
        let (k_t, k_i, kept) = (self.costs.traversal, self.costs.intersection, 1.0 - self.costs.empty_bonus);
        // Plane `k` (1 ≤ k < bins) at index `k`: its counts, `f32` plane and cost, in three loops so
        // that the middle one, the costs, has no dependence between planes and compiles to vector
        // code; only the choice of the best stays a scalar loop in plane order.
        let (mut lowers, mut uppers, mut splits, mut costs) = ([0.0; W], [0.0; W], [0.0; W], [0.0; W]);
        let mut best: Option<Candidate> = None;
        for axis in 0..3 {
            if !(extent[axis] > 0.0) {
                continue;
            }
            let (starts, ends) = (&counts[axis][..bins], &counts[3 + axis][..bins]);
            // A child's area is 2 (e_b e_c + e_axis (e_b + e_c)) with e_axis its extent on the axis.
            let (eb, ec) = (extent[(axis + 1) % 3], extent[(axis + 2) % 3]);
            let (cap, side) = (2.0 * eb * ec, 2.0 * (eb + ec));
            let (lo, hi, e) = (lo[axis], hi[axis], extent[axis]);
            let (mut n_lower, mut n_ended) = (0.0, 0.0);
            for k in 1..bins {
                n_lower += f64::from(starts[k - 1]);
                n_ended += f64::from(ends[k - 1]);
                (lowers[k], uppers[k]) = (n_lower, n - n_ended);
            }
            // Through `u32` (bins ≤ 1024), whose conversion to `f64` vectorises.
            let plane = |k: usize| {
                let offset = e * f64::from(k as u32);
                let offset = match inv_bins {
                    Some(inv) => offset * inv,
                    None => offset / bins as f64,
                };
                // Only planes representable in `f32` (the node stores the split as `f32`).
                f64::from((lo + offset) as f32)
            };
            let cost = |p_lower: f64, p_upper: f64, n_lower: f64, n_upper: f64| {
                let bonus = if n_lower == 0.0 || n_upper == 0.0 { kept } else { 1.0 };
                k_t + k_i * bonus * (p_lower * n_lower + p_upper * n_upper)
            };
            if area > 0.0 {
                for k in 1..bins {
                    let split = plane(k);
                    let (p_lower, p_upper) = ((cap + side * (split - lo)) / area, (cap + side * (hi - split)) / area);
                    (splits[k], costs[k]) = (split, cost(p_lower, p_upper, lowers[k], uppers[k]));
                }
            } else {
                for k in 1..bins {
                    let f = f64::from(k as u32) / bins as f64;
                    (splits[k], costs[k]) = (plane(k), cost(f, 1.0 - f, lowers[k], uppers[k]));
                }
            }
            for k in 1..bins {
                // Strictly inside the cell: rounding may push a plane of a tiny or far-away cell out.
                let (split, cost) = (splits[k], costs[k]);
                if lo < split && split < hi && best.as_ref().is_none_or(|b| cost < b.cost) {
                    best = Some(Candidate { axis, split, cost });
                }
            }
        }
        best
    }
}

/// The bin of each of a box's six coordinates (min x, y, z, max x, y, z):
/// `⌊clamp((x − lo) · scale, 0, bins − 1)⌋`, NaN (an axis without extent) in bin 0.
struct Binner {
    #[cfg(x86_simd)]
    pairs: [(std::arch::x86_64::__m128d, std::arch::x86_64::__m128d); 3],
    #[cfg(x86_simd)]
    last: std::arch::x86_64::__m128d,
    #[cfg(not(x86_simd))]
    lo: [f64; 6],
    #[cfg(not(x86_simd))]
    scale: [f64; 6],
    #[cfg(not(x86_simd))]
    last: f64,
}

impl Binner {
    fn new(lo: [f64; 3], scale: [f64; 3], last: f64) -> Self {
        let lo = [lo[0], lo[1], lo[2], lo[0], lo[1], lo[2]];
        let scale = [scale[0], scale[1], scale[2], scale[0], scale[1], scale[2]];
        #[cfg(x86_simd)]
        {
            use std::arch::x86_64::_mm_set_pd;
            // SAFETY: SSE2 is part of every x86-64 CPU (the baseline the crate is compiled for), and
            // `_mm_set_pd` touches no memory.
            let pair = |v: &[f64; 6], j: usize| unsafe { _mm_set_pd(v[2 * j + 1], v[2 * j]) };
            Self { pairs: [0, 1, 2].map(|j| (pair(&lo, j), pair(&scale, j))), last: unsafe { _mm_set_pd(last, last) } }
        }
        #[cfg(not(x86_simd))]
        Self { lo, scale, last }
    }

    /// Two coordinates per SSE2 instruction (x86-64's baseline): the scalar code spent about 100
    /// instructions per box, most of them on the six saturating conversions' NaN and range fixes,
    /// which the clamp already makes unnecessary. The same bins: `maxpd(v, 0)` sends NaN to 0 as
    /// the scalar path does, and the truncation of a value in `[0, bins − 1]` is the same.
    #[cfg(x86_simd)]
    #[inline(always)]
    fn bins(&self, b: &Aabb) -> [usize; 6] {
        use std::arch::x86_64::{
            _mm_cvtsi128_si64, _mm_cvttpd_epi32, _mm_max_pd, _mm_min_pd, _mm_mul_pd, _mm_set_pd, _mm_setzero_pd,
            _mm_sub_pd,
        };
        let c = [b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z];
        let mut out = [0; 6];
        for (j, &(lo, scale)) in self.pairs.iter().enumerate() {
            // SAFETY: SSE2 is part of every x86-64 CPU (the baseline the crate is compiled for), and
            // these intrinsics touch no memory.
            let two = unsafe {
                let v = _mm_mul_pd(_mm_sub_pd(_mm_set_pd(c[2 * j + 1], c[2 * j]), lo), scale);
                let v = _mm_min_pd(_mm_max_pd(v, _mm_setzero_pd()), self.last);
                // Two `i32` lanes, each in [0, bins − 1].
                _mm_cvtsi128_si64(_mm_cvttpd_epi32(v)) as u64
            };
            (out[2 * j], out[2 * j + 1]) = ((two & 0xFFFF_FFFF) as usize, (two >> 32) as usize);
        }
        out
    }

    #[cfg(not(x86_simd))]
    #[inline(always)]
    fn bins(&self, b: &Aabb) -> [usize; 6] {
        let c = [b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z];
        // Clamping in floating point first (NaN included: it goes to bin 0) leaves the conversion
        // nothing to saturate; through `i32` (exact after the clamp), whose saturating conversion is
        // a few instructions shorter than `usize`'s.
        std::array::from_fn(|r| ((c[r] - self.lo[r]) * self.scale[r]).clamp(0.0, self.last) as i32 as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// Boxes from a fixed linear congruential sequence, some sticking out of `[0, 1]³`, some of
    /// them flat on an axis.
    fn boxes(count: usize, seed: u64) -> Vec<Prim> {
        let mut state = seed;
        let mut next = move || {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..count as u32)
            .map(|index| {
                let c = DVec3::new(next(), next(), next()) * 1.2 - 0.1;
                let r = DVec3::new(next(), next(), next()) * 0.2 * f64::from(u8::from(index % 7 != 0));
                Prim { index, bounds: Aabb { min: c - r, max: c + r } }
            })
            .collect()
    }

    fn same(a: Option<Candidate>, b: Option<Candidate>) -> bool {
        match (a, b) {
            (None, None) => true,
            (Some(a), Some(b)) => a.axis == b.axis && a.split.to_bits() == b.split.to_bits() && a.cost == b.cost,
            _ => false,
        }
    }

    #[test]
    fn vector_bins_equal_the_scalar_formula() {
        let (lo, bins) = ([0.0, -1.0, 2.5], 32);
        // The last axis has no extent: its scale is +∞ and a coordinate at its start gives NaN.
        let scale = [bins as f64 / 1.0, bins as f64 / 3.0, f64::INFINITY];
        let last = (bins - 1) as f64;
        let binner = Binner::new(lo, scale, last);
        for p in boxes(500, 7) {
            let mut b = p.bounds;
            b.min.z = if p.index % 2 == 0 { 2.5 } else { b.min.z };
            let c = [b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z];
            let scalar: [usize; 6] =
                std::array::from_fn(|r| ((c[r] - lo[r % 3]) * scale[r % 3]).clamp(0.0, last) as i32 as usize);
            assert_eq!(binner.bins(&b), scalar, "{b:?}");
        }
    }

    /// The face counts are the closed tests counted one by one, NaN, ±∞, ±0 and faces on a box's
    /// start or end included (the closed tests count a face on the plane on both sides; NaN on
    /// neither), for every width and box count, in the baseline build and compiled for AVX2.
    #[test]
    fn face_counts_equal_the_closed_tests_counted_one_by_one() {
        let values = [f64::NEG_INFINITY, -1.0, 0.0, 0.25, 0.5, 0.75, 1.0, f64::INFINITY, f64::NAN, -0.0];
        let mut state = 3u64;
        let mut pick = || {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            values[(state >> 33) as usize % values.len()]
        };
        #[cfg(x86_simd)]
        #[target_feature(enable = "avx2")]
        fn counts_avx2<const W: usize>(
            splits: &[f64; 2 * EXACT_MAX_LIMIT],
            starts: &[f64; EXACT_MAX_LIMIT],
            ends: &[f64; EXACT_MAX_LIMIT],
            m: usize,
        ) -> ([f64; 2 * EXACT_MAX_LIMIT], [f64; 2 * EXACT_MAX_LIMIT]) {
            face_counts::<W>(splits, starts, ends, m)
        }
        fn check<const W: usize>(pick: &mut impl FnMut() -> f64) {
            for m in 0..=W {
                let starts: [f64; EXACT_MAX_LIMIT] = std::array::from_fn(|_| pick());
                let ends: [f64; EXACT_MAX_LIMIT] = std::array::from_fn(|_| pick());
                let splits: [f64; 2 * EXACT_MAX_LIMIT] = std::array::from_fn(|_| pick());
                let (lowers, uppers) = face_counts::<W>(&splits, &starts, &ends, m);
                for f in 0..2 * W {
                    let lower = starts[..m].iter().filter(|&&x| x <= splits[f]).count();
                    let upper = ends[..m].iter().filter(|&&x| x >= splits[f]).count();
                    assert_eq!((lowers[f], uppers[f]), (lower as f64, upper as f64), "W = {W}, m = {m}, face {f}");
                }
                #[cfg(x86_simd)]
                if std::arch::is_x86_feature_detected!("avx2") {
                    // SAFETY: the CPU has AVX2 (checked just above).
                    let wide = unsafe { counts_avx2::<W>(&splits, &starts, &ends, m) };
                    assert_eq!(wide, (lowers, uppers), "AVX2, W = {W}, m = {m}");
                }
            }
        }
        for _ in 0..200 {
            check::<4>(&mut pick);
            check::<8>(&mut pick);
            check::<EXACT_MAX_LIMIT>(&mut pick);
        }
    }

    /// The branch-free pass gives each child the boxes the closed tests send it, in order, and
    /// leaves the rest of the list as it was: boxes on the plane go to both sides, NaN to neither.
    #[test]
    fn partition_sends_each_box_where_the_closed_tests_say_in_order() {
        for (seed, split) in (0..30).zip([0.5, 0.0, 1.0, 0.25].into_iter().cycle()) {
            let mut list = boxes(300, seed);
            for (k, p) in list.iter_mut().enumerate() {
                match k % 11 {
                    0 => p.bounds.min.x = split,
                    1 => p.bounds.max.y = split,
                    2 => p.bounds.max.z = f64::NAN,
                    _ => {}
                }
            }
            let before = list.clone();
            let (start, end) = (40, 260);
            for axis in 0..3 {
                let mut list = before.clone();
                let kept = partition(&mut list, start, end, axis, split);
                let range = &before[start..end];
                let lower: Vec<u32> =
                    range.iter().filter(|p| p.bounds.min.to_array()[axis] <= split).map(|p| p.index).collect();
                let upper: Vec<u32> =
                    range.iter().filter(|p| p.bounds.max.to_array()[axis] >= split).map(|p| p.index).collect();
                let indices = |prims: &[Prim]| prims.iter().map(|p| p.index).collect::<Vec<_>>();
                assert_eq!(indices(&list[start..kept]), lower, "seed {seed}, axis {axis}");
                assert_eq!(indices(&list[before.len()..]), upper, "seed {seed}, axis {axis}");
                assert_eq!(indices(&list[..start]), indices(&before[..start]));
                assert_eq!(indices(&list[end..before.len()]), indices(&before[end..]));
            }
        }
    }

    /// The parallel levels' pass (fresh upper lists) and the serial one (one scratch list) build
    /// the same subtree.
    #[test]
    fn parallel_and_serial_levels_build_the_same_subtree() {
        let builder = Builder { costs: SahCosts::default(), max_depth: max_depth(40_000), exact_max: EXACT_MAX };
        for seed in 0..2 {
            let prims = boxes(4 * PARALLEL_MIN, seed);
            let cell = prims.iter().fold(prims[0].bounds, |b, p| b.union(p.bounds));
            let mut parallel = Subtree::default();
            builder.build(cell, prims.clone(), 0, &mut parallel);
            let (mut scratch, mut serial) = (prims.clone(), Subtree::default());
            builder.build_serial(cell, &mut scratch, 0, prims.len(), 0, &mut serial);
            assert!(parallel.nodes.len() > 1000, "a deep tree");
            assert_eq!(parallel.nodes, serial.nodes, "seed {seed}");
            assert_eq!(parallel.indices, serial.indices, "seed {seed}");
        }
    }

    /// From the parallel threshold on, the boxes are made on the pool; an invalid sphere is still
    /// reported by the lowest invalid index, and valid input gives the serial pass's list.
    #[test]
    fn parallel_sphere_pass_names_the_lowest_invalid_index() {
        let n = PARALLEL_MIN + 3 * PARALLEL_CHUNK;
        let mut spheres: Vec<Sphere<f64>> =
            (0..n).map(|i| Sphere { center: DVec3::new(i as f64 * 1e-3, 0.5, -0.25), radius: 1e-4 }).collect();
        let serial: Vec<Prim> = spheres.iter().enumerate().map(|item| sphere_box(item).unwrap()).collect();
        let parallel = sphere_prims(&spheres).unwrap();
        assert_eq!(parallel.len(), n);
        assert!(parallel.iter().zip(&serial).all(|(a, b)| a.index == b.index && a.bounds == b.bounds));
        spheres[n - 5].radius = f64::NAN;
        spheres[PARALLEL_MIN + 7].center.x = f64::INFINITY;
        spheres[n - 1].radius = -1.0;
        assert!(matches!(
            sphere_prims(&spheres),
            Err(BuildError::InvalidSphere { index, .. }) if index == PARALLEL_MIN + 7
        ));
    }

    #[test]
    fn every_search_path_picks_the_same_plane() {
        let cell = Aabb { min: DVec3::ZERO, max: DVec3::ONE };
        let flat = Aabb { min: DVec3::ZERO, max: DVec3::new(1.0, 1.0, 0.0) };
        for bins in [7, 32, 64] {
            let builder =
                Builder { costs: SahCosts { bins, ..SahCosts::default() }, max_depth: 30, exact_max: EXACT_MAX };
            for (seed, n) in (0..40).zip([3, 5, 8, 11, 16, 17, 40, 300].into_iter().cycle()) {
                let prims = boxes(n, seed);
                for cell in [cell, flat] {
                    if n <= EXACT_MAX {
                        let plain = builder.exact_split(&cell, &prims);
                        assert!(same(plain, builder.best_exact_split(&cell, &prims)), "exact, n = {n}, seed {seed}");
                    }
                    let plain = builder.binned_search(&cell, &prims);
                    assert!(same(plain, builder.best_split(&cell, &prims)), "binned, n = {n}, seed {seed}");
                }
            }
        }
    }

    #[test]
    fn max_depth_follows_pbrt() {
        assert_eq!(max_depth(1), 8);
        assert_eq!(max_depth(1 << 10), 21);
        assert_eq!(max_depth(usize::MAX), MAX_DEPTH);
    }

    #[test]
    fn invalid_spheres_are_typed_errors_naming_the_index() {
        let ok = Sphere { center: DVec3::ZERO, radius: 1.0 };
        let nan = Sphere { center: DVec3::new(f64::NAN, 0.0, 0.0), radius: 1.0 };
        let overflow = Sphere { center: DVec3::splat(f64::MAX), radius: f64::MAX };
        assert!(matches!(sphere_prims(&[ok, nan]), Err(BuildError::InvalidSphere { index: 1, .. })));
        assert!(matches!(sphere_prims(&[overflow]), Err(BuildError::InvalidSphere { index: 0, .. })));
    }

    #[test]
    fn out_of_range_costs_are_rejected() {
        let bad = SahCosts { empty_bonus: 1.0, ..SahCosts::default() };
        assert!(check_costs(&bad).is_err());
        assert!(check_costs(&SahCosts::default()).is_ok());
    }
}
