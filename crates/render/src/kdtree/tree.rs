//! The 3-D kd-tree over spheres: flat node array, closest-hit traversal with early exit, one ray
//! at a time ([`KdTree::closest_hit`]) or several in flight ([`KdTree::closest_hits`]); both walks
//! share the leaf step (`KdTree::test_leaf`: four quantised copies per test, eight or sixteen in
//! the single-ray walk on a CPU with AVX2 or AVX-512, then the exact test).

use super::build::{
    Builder, EXACT_MAX, PARALLEL_CHUNK, PARALLEL_MIN, Prim, SahCosts, Subtree, check_costs, max_depth, sphere_prims,
};
#[cfg(x86_simd)]
use super::coarse::WIDE_LANES;
use super::coarse::{CoarseRay, CoarseSphere, Grid, LANES, WIDEST_LANES};
use super::exact::ExactLists;
use super::node::{Aabb, Node, NodeKind, visit_cells};
use super::prefetch::prefetch;
use super::stack::FarStack;
use super::{BuildError, ReciprocalAxis, Side, split_pieces};
use glam::DVec3;
use hw3_core::geometry::sphere::roots_stable;
use hw3_core::geometry::{Ray, Sphere};
use std::sync::atomic::{AtomicBool, Ordering};

/// Work counters of one or more closest-hit queries.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct HitStats {
    /// Nodes (interior and leaf) entered.
    pub nodes_visited: u64,
    /// Ray/sphere tests made (a sphere listed in several leaves may be tested more than once).
    pub sphere_tests: u64,
}

/// What the traversal counts; `()` counts nothing and compiles away.
trait Counter {
    fn node(&mut self);
    fn sphere_tests(&mut self, count: u32);
}

impl Counter for () {
    #[inline]
    fn node(&mut self) {}
    #[inline]
    fn sphere_tests(&mut self, _count: u32) {}
}

impl Counter for HitStats {
    #[inline]
    fn node(&mut self) {
        self.nodes_visited += 1;
    }
    #[inline]
    fn sphere_tests(&mut self, count: u32) {
        self.sphere_tests += u64::from(count);
    }
}

/// How [`KdTree::closest_hit_at`] walks a tree ([`KdTree::walk`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Walk {
    /// Static spheres on the coarse grid: each leaf's spheres are first rejected in `f32` from
    /// 8-byte copies, and only those kept are tested exactly.
    Filtered,
    /// Static spheres, one of which does not fit the coarse grid: every listed sphere is tested
    /// exactly.
    Exact,
    /// Moving spheres: each listed sphere is moved to the ray's time and tested exactly.
    Moving,
}

/// A kd-tree over spheres, built by the surface area heuristic (see [`SahCosts`]), answering
/// closest-hit queries front to back with the crate's one interval rule,
/// [`split_interval`](super::split_interval).
#[derive(Debug, Clone)]
pub struct KdTree {
    /// The spheres' motion ([`KdTree::build_moving`]); `None` for a tree of static spheres, whose
    /// traversal then never reads it.
    motion: Option<Motion>,
    /// A leaf's `first` indexes [`KdTree::coarse`], [`KdTree::exact`] and [`KdTree::indices`], its
    /// `count` is its number of spheres.
    pub(super) nodes: Vec<Node>,
    /// The leaves' sphere lists, concatenated in node order, as the coarse `f32` test reads them
    /// (8 bytes a sphere, on [`KdTree::grid`]): a copy of each sphere sits beside its leaf's others
    /// instead of behind an index into the input slice (that indirection was a cache miss per
    /// sphere test on large scenes), in the fewest bytes that still reject safely.
    coarse: Vec<CoarseSphere>,
    /// The grid [`KdTree::coarse`] is counted on.
    grid: Grid,
    /// False when a sphere does not fit the grid: then [`KdTree::coarse`] is a placeholder and
    /// the traversal tests every sphere exactly.
    fits: bool,
    /// The same lists exact (32 bytes a sphere in `f64`, or 16 in `f32` when the scene's spheres
    /// are all `f32` values): read only for the spheres the coarse test keeps, one line each.
    exact: ExactLists,
    /// Each listed sphere's index in the input slice, beside [`KdTree::exact`] rather than in it
    /// (40 bytes a sphere would put half of them across two lines): read only for a hit (and, in a
    /// moving tree, for every exact test, to find the sphere's velocity).
    indices: Vec<u32>,
    /// Whether a walk from inside the tree's box asks for every line of a leaf's exact spheres as
    /// it reaches the leaf, before the coarse test: see [`prefetches_exact`].
    prefetch_exact: bool,
    pub(super) bounds: Aabb,
}

/// Spheres moving with constant velocities, and the time interval their swept boxes bound.
#[derive(Debug, Clone)]
struct Motion {
    /// The spheres at time 0, in input order (for queries outside the interval).
    spheres: Vec<Sphere<f64>>,
    /// One per sphere, in input order.
    velocities: Vec<DVec3>,
    /// `(open, close)`.
    interval: (f64, f64),
}

/// [`prefetches_exact`]'s threshold on the coarse test's expected survivors per leaf visit.
const PREFETCH_SURVIVORS: f64 = 0.5;

/// [`prefetches_exact`]'s threshold on the size of a tree's exact lists: two to four times a
/// core's second-level cache on the processors the Q3 engineering notes measure (1 MB and
/// 512 KB), below which the lists are found in the near caches anyway and the requests are only
/// work.
const PREFETCH_MIN_BYTES: usize = 2 << 20;

/// Whether a tree with these leaves asks for a leaf's exact spheres ahead (the single-ray walk of
/// [`KdTree::traverse_with`], for rays that start inside the box): when its exact lists take more
/// than [`PREFETCH_MIN_BYTES`] and a leaf visit is expected to find at least
/// [`PREFETCH_SURVIVORS`] coarse survivors ([`KdTree::survivors_per_leaf_visit`]). Large spheres (many
/// survivors) then have their exact lines on the way while the coarse test runs; small ones would
/// have nearly every line read for nothing. The threshold is checked on the benchmark's two
/// densities only, whose estimates (0.16–0.35 with fixed k and 0.89–0.98 with fixed volume at N
/// = 10⁴ and 10⁵, with `K_I = 0.075`) any value between them separates.
fn prefetches_exact(nodes: &[Node], bounds: Aabb, exact: &ExactLists) -> bool {
    exact.bytes() > PREFETCH_MIN_BYTES && survivors_per_leaf_visit(nodes, bounds, exact) >= PREFETCH_SURVIVORS
}

/// [`KdTree::survivors_per_leaf_visit`] of the tree with these nodes, box and exact lists.
fn survivors_per_leaf_visit(nodes: &[Node], bounds: Aabb, exact: &ExactLists) -> f64 {
    let (mut met, mut visits) = (0.0, 0.0);
    visit_cells(nodes, bounds, |kind, cell| {
        if let NodeKind::Leaf { first, count } = kind {
            let area = cell.surface_area();
            visits += area;
            for k in first as usize..(first + count) as usize {
                let radius = exact.sphere(k).radius;
                met += (4.0 * std::f64::consts::PI * radius * radius).min(area);
            }
        }
    });
    if visits > 0.0 { met / visits } else { 0.0 }
}

impl KdTree {
    /// Builds the tree with the default [`SahCosts`].
    ///
    /// # Errors
    /// [`BuildError::InvalidSphere`] for a sphere with a NaN/infinite centre or radius, a negative
    /// radius, or an overflowing bounding box; [`BuildError::TooManySpheres`] from 2³⁰ spheres on
    /// (30-bit counts in the 8-byte nodes).
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::{Ray, Sphere};
    /// use hw3_render::kdtree::KdTree;
    /// let spheres = [
    ///     Sphere::new(DVec3::new(0.0, 0.0, 5.0), 1.0).unwrap(),
    ///     Sphere::new(DVec3::new(0.0, 0.0, 9.0), 1.0).unwrap(),
    /// ];
    /// let tree = KdTree::build(&spheres).unwrap();
    /// let ray = Ray::new(DVec3::ZERO, DVec3::Z).unwrap();
    /// assert_eq!(tree.closest_hit(&ray, 0.0, f64::INFINITY), Some((0, 4.0)));
    /// ```
    pub fn build(spheres: &[Sphere<f64>]) -> Result<Self, BuildError> {
        Self::build_with(spheres, SahCosts::default())
    }

    /// Builds the tree with the given cost constants.
    ///
    /// # Errors
    /// As [`KdTree::build`], plus [`BuildError::InvalidCosts`].
    pub fn build_with(spheres: &[Sphere<f64>], costs: SahCosts) -> Result<Self, BuildError> {
        check_costs(&costs)?;
        let prims = sphere_prims(spheres)?;
        Ok(Self::from_prims(spheres, prims, costs))
    }

    /// Builds the tree over spheres moving with constant `velocities` (one per sphere; a zero
    /// velocity is a static sphere), for ray times in `interval = (open, close)`: each sphere is
    /// bounded by its *swept* box, the union of its boxes at `open` and at `close` (linear motion
    /// stays inside it), so the tree holds the sphere at every time of the interval. Query it
    /// with [`KdTree::closest_hit_at`]. The faster a sphere moves, the larger its box and the
    /// more leaves list it: traversal cost grows with speed. When no sphere moves, the tree is
    /// the static one of [`KdTree::build`], with its coarse filter ([`KdTree::walk`]).
    ///
    /// # Errors
    /// [`BuildError::InvalidSphere`] for an invalid sphere or a swept box that is not finite
    /// (also a non-finite velocity or interval), [`BuildError::VelocityCount`] when the slices'
    /// lengths differ, [`BuildError::TooManySpheres`].
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::{Ray, Sphere};
    /// use hw3_render::kdtree::KdTree;
    /// let ball = [Sphere::new(DVec3::ZERO, 1.0).unwrap()];
    /// let tree = KdTree::build_moving(&ball, &[DVec3::X * 4.0], (0.0, 1.0)).unwrap();
    /// let ray = Ray::new(DVec3::new(4.0, 0.0, -5.0), DVec3::Z).unwrap();
    /// assert_eq!(tree.closest_hit_at(&ray, 0.0, f64::INFINITY, 0.0), None);
    /// assert_eq!(tree.closest_hit_at(&ray, 0.0, f64::INFINITY, 1.0), Some((0, 4.0)));
    /// ```
    pub fn build_moving(
        spheres: &[Sphere<f64>],
        velocities: &[DVec3],
        interval: (f64, f64),
    ) -> Result<Self, BuildError> {
        if velocities.len() != spheres.len() {
            return Err(BuildError::VelocityCount { spheres: spheres.len(), velocities: velocities.len() });
        }
        if velocities.iter().all(|v| *v == DVec3::ZERO) {
            return Self::build(spheres);
        }
        let at = |time: f64| -> Vec<Sphere<f64>> {
            spheres.iter().zip(velocities).map(|(&sphere, &velocity)| moved(sphere, velocity, time)).collect()
        };
        let (open, close) = (sphere_prims(&at(interval.0))?, sphere_prims(&at(interval.1))?);
        let swept: Vec<Prim> = open
            .into_iter()
            .zip(close)
            .map(|(a, b)| Prim { index: a.index, bounds: a.bounds.union(b.bounds) })
            .collect();
        let mut tree = Self::from_prims(spheres, swept, SahCosts::default());
        tree.motion = Some(Motion { spheres: spheres.to_vec(), velocities: velocities.to_vec(), interval });
        Ok(tree)
    }

    /// Which walk queries take: the coarse filter needs static spheres that fit its grid.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::Sphere;
    /// use hw3_render::kdtree::{KdTree, Walk};
    /// let ball = [Sphere::new(DVec3::ZERO, 1.0).unwrap()];
    /// assert_eq!(KdTree::build(&ball).unwrap().walk(), Walk::Filtered);
    /// assert_eq!(KdTree::build_moving(&ball, &[DVec3::ZERO], (0.0, 1.0)).unwrap().walk(), Walk::Filtered);
    /// assert_eq!(KdTree::build_moving(&ball, &[DVec3::X], (0.0, 1.0)).unwrap().walk(), Walk::Moving);
    /// ```
    #[must_use]
    pub fn walk(&self) -> Walk {
        match (&self.motion, self.fits) {
            (Some(_), _) => Walk::Moving,
            (None, true) => Walk::Filtered,
            (None, false) => Walk::Exact,
        }
    }

    /// The tree over `spheres` bounded by `prims` (validated boxes, one per sphere, in input order).
    fn from_prims(spheres: &[Sphere<f64>], prims: Vec<Prim>, costs: SahCosts) -> Self {
        Self::from_prims_with(spheres, prims, costs, EXACT_MAX)
    }

    /// [`KdTree::from_prims`] with nodes of at most `exact_max` spheres trying every box face.
    ///
    /// From [`PARALLEL_MIN`] spheres on, the per-sphere passes run on the rayon pool: the quantised
    /// copy of each sphere (it depends on the sphere and the grid alone, so it is made once per
    /// sphere, not once per reference) beside the build, then the leaf arrays, gathered by index.
    /// Every element is computed as in the serial passes and collected in order, so the tree is
    /// the same on any number of threads.
    fn from_prims_with(spheres: &[Sphere<f64>], prims: Vec<Prim>, costs: SahCosts, exact_max: usize) -> Self {
        use rayon::prelude::*;
        let empty = Aabb { min: DVec3::INFINITY, max: DVec3::NEG_INFINITY };
        let bounds = prims.iter().fold(empty, |b, p| b.union(p.bounds));
        let builder = Builder { costs, max_depth: max_depth(spheres.len()), exact_max };
        let grid = Grid::new(&bounds);
        let parallel = spheres.len() >= PARALLEL_MIN;
        let build = || {
            let mut built = Subtree::default();
            if spheres.is_empty() {
                built.nodes.push(Node::leaf(0, 0));
            } else {
                builder.build(bounds, prims, 0, &mut built);
            }
            built
        };
        let pack = |sphere: &Sphere<f64>| grid.pack(sphere);
        let (built, packed): (Subtree, Vec<Option<CoarseSphere>>) = if parallel {
            rayon::join(build, || spheres.par_iter().with_min_len(PARALLEL_CHUNK).map(pack).collect())
        } else {
            (build(), spheres.iter().map(pack).collect())
        };
        // A sphere off the grid leaves a placeholder and clears `fits` (indexed collects write in
        // place; collecting `Option`s would gather pieces and copy them).
        let fits = AtomicBool::new(true);
        let coarse = |&index: &u32| {
            packed[index as usize].unwrap_or_else(|| {
                fits.store(false, Ordering::Relaxed);
                CoarseSphere::KEEP
            })
        };
        // The leaf test reads whole groups of up to `WIDEST_LANES` copies: placeholders after the
        // last leaf's copies keep its group inside the list (chained, so the list is written once).
        let padding = WIDEST_LANES - 1;
        let exact = || ExactLists::new(spheres, &built.indices, parallel);
        let (exact, coarse): (ExactLists, Vec<CoarseSphere>) = if parallel {
            let indices = built.indices.par_iter().with_min_len(PARALLEL_CHUNK);
            rayon::join(exact, || {
                indices.map(coarse).chain(rayon::iter::repeat_n(CoarseSphere::KEEP, padding)).collect()
            })
        } else {
            let coarse = built.indices.iter().map(coarse).chain(std::iter::repeat_n(CoarseSphere::KEEP, padding));
            (exact(), coarse.collect())
        };
        let fits = fits.into_inner();
        // The traversal never reads the copies then; all placeholders, as they always were.
        let coarse = if fits { coarse } else { vec![CoarseSphere::KEEP; exact.len() + padding] };
        let prefetch_exact = prefetches_exact(&built.nodes, bounds, &exact);
        let indices = built.indices;
        Self { nodes: built.nodes, coarse, grid, fits, exact, indices, prefetch_exact, bounds, motion: None }
    }

    /// The spheres of the leaf `(first, count)` with their input indices, in list order.
    pub(super) fn leaf_spheres(&self, first: u32, count: u32) -> impl Iterator<Item = (Sphere<f64>, u32)> + '_ {
        let range = first as usize..(first + count) as usize;
        range.map(|k| (self.exact.sphere(k), self.indices[k]))
    }

    /// Number of nodes (interior and leaf).
    ///
    /// # Examples
    /// ```
    /// let tree = hw3_render::kdtree::KdTree::build(&[]).unwrap();
    /// assert_eq!((tree.node_count(), tree.reference_count()), (1, 0));
    /// ```
    #[must_use]
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The tree's expected cost per ray under the surface area heuristic with `costs`: the sum over
    /// interior nodes of `K_T · A(cell)/A(root)` and over leaves of `K_I · n · A(cell)/A(root)`,
    /// the quantity the builder minimises greedily (without its empty-space bonus). A measure of
    /// tree quality that does not depend on the machine; 0 for an empty tree.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::Sphere;
    /// use hw3_render::kdtree::{KdTree, SahCosts};
    /// let one = KdTree::build(&[Sphere::new(DVec3::ZERO, 1.0).unwrap()]).unwrap();
    /// assert_eq!(one.sah_cost(&SahCosts::default()), SahCosts::default().intersection); // one leaf
    /// ```
    #[must_use]
    pub fn sah_cost(&self, costs: &SahCosts) -> f64 {
        let root_area = self.bounds.surface_area();
        if !(root_area > 0.0) {
            return 0.0;
        }
        let mut total = 0.0;
        visit_cells(&self.nodes, self.bounds, |kind, cell| {
            let p = cell.surface_area() / root_area;
            total += match kind {
                NodeKind::Interior { .. } => costs.traversal * p,
                NodeKind::Leaf { count, .. } => costs.intersection * f64::from(count) * p,
            };
        });
        total
    }

    /// An estimate of how many of a leaf's spheres a random line meets, averaged over the leaves a
    /// random line visits: `Σ_L Σ_{s∈L} min(S(s), S(L)) / Σ_L S(L)` over leaves `L` with cell
    /// surface area `S(L)` and spheres `s` of surface area `S(s) = 4πr²` (for a moving tree, the
    /// spheres at time 0); 0 for an empty tree. Like [`KdTree::sah_cost`], a measure of the tree
    /// that does not depend on the machine.
    ///
    /// The mean area of a convex body's shadows over all directions is a quarter of its surface area
    /// (Cauchy's surface area formula: Tsukerman and Veomett, arXiv:1604.05815, Theorem 1), so the
    /// random lines that meet a convex body (directions uniform, positions uniform across the shadow)
    /// have a measure proportional to its surface area. A random line that meets a convex cell then
    /// meets a convex body inside it with probability `S(body)/S(cell)` (the probability the surface
    /// area heuristic is built on: MacDonald and Booth, "Heuristics for ray tracing using space
    /// subdivision", *The Visual Computer* 6(3), 1990), and random lines visit the leaves in
    /// proportion to their areas. A sphere that sticks out of its cell is counted as
    /// `min(S(s), S(L))`, an upper bound. The coarse test keeps every sphere the line meets (and a few
    /// it misses), so this is close to its survivors for lines; the walk's rays start inside the box
    /// and stop at their first hit, so for them it is an estimate.
    ///
    /// The tree asks for a leaf's exact spheres ahead when this is at least one half and its
    /// exact lists are too large for the cache: then a leaf visit is likely to need them, and the
    /// wait for them is likely to be long.
    ///
    /// # Examples
    /// A ball alone in its bounding cube, one leaf: `4π r² / 24 r² = π/6 ≈ 0.52`.
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::Sphere;
    /// use hw3_render::kdtree::KdTree;
    /// let tree = KdTree::build(&[Sphere::new(DVec3::new(0.5, -2.0, 7.0), 1.5).unwrap()]).unwrap();
    /// let pi_over_6 = std::f64::consts::PI / 6.0;
    /// assert!((tree.survivors_per_leaf_visit() - pi_over_6).abs() <= 4.0 * f64::EPSILON * pi_over_6);
    /// ```
    #[must_use]
    pub fn survivors_per_leaf_visit(&self) -> f64 {
        survivors_per_leaf_visit(&self.nodes, self.bounds, &self.exact)
    }

    /// Number of sphere references in the leaves (≥ the sphere count: straddling spheres repeat).
    #[must_use]
    pub fn reference_count(&self) -> usize {
        self.exact.len()
    }

    /// The closest sphere hit with `t` strictly inside `(t_min, t_max)`: its index in the slice the
    /// tree was built from and its `t`, or `None`. Ties in `t` go to the lowest index, so the
    /// answer equals [`brute_force_closest_hit`]'s.
    ///
    /// Preconditions: a validated ray; `t_min < t_max` (otherwise, or if either is NaN, `None`).
    /// Numerics: every sphere test is [`roots_stable`] (the crate's stable solver), unchanged.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::{Ray, Sphere};
    /// use hw3_render::kdtree::KdTree;
    /// let tree = KdTree::build(&[Sphere::new(DVec3::ZERO, 1.0).unwrap()]).unwrap();
    /// let ray = Ray::new(DVec3::new(0.0, 0.0, -5.0), DVec3::new(-0.0, -0.0, 1.0)).unwrap();
    /// assert_eq!(tree.closest_hit(&ray, 0.0, f64::INFINITY), Some((0, 4.0)));
    /// assert_eq!(tree.closest_hit(&ray, 0.0, 3.0), None);
    /// ```
    #[must_use]
    pub fn closest_hit(&self, ray: &Ray<f64>, t_min: f64, t_max: f64) -> Option<(usize, f64)> {
        self.closest_hit_at(ray, t_min, t_max, self.default_time())
    }

    /// [`KdTree::closest_hit`] with every sphere where its velocity puts it at `time`
    /// (`centre + velocity · time`; a static sphere is used untouched). The same answer as
    /// testing every moved sphere, bit for bit: within the build interval through the tree,
    /// outside it (where the swept boxes do not hold the spheres) by testing every sphere.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::{Ray, Sphere};
    /// use hw3_render::kdtree::KdTree;
    /// let ball = [Sphere::new(DVec3::ZERO, 1.0).unwrap()];
    /// let tree = KdTree::build_moving(&ball, &[DVec3::X], (0.0, 1.0)).unwrap();
    /// let ray = Ray::new(DVec3::new(3.0, 0.0, -5.0), DVec3::Z).unwrap();
    /// assert_eq!(tree.closest_hit_at(&ray, 0.0, f64::INFINITY, 3.0), Some((0, 4.0))); // outside
    /// ```
    #[must_use]
    pub fn closest_hit_at(&self, ray: &Ray<f64>, t_min: f64, t_max: f64, time: f64) -> Option<(usize, f64)> {
        match &self.motion {
            Some(motion) if !(motion.interval.0..=motion.interval.1).contains(&time) => {
                let moved: Vec<Sphere<f64>> =
                    motion.spheres.iter().zip(&motion.velocities).map(|(&s, &v)| moved(s, v, time)).collect();
                brute_force_closest_hit(&moved, ray, t_min, t_max)
            }
            _ => self.traverse(Query { ray, t_min, t_max, time }, &mut ()),
        }
    }

    /// The time a query without one uses: the opening of a moving tree's interval, else 0.
    fn default_time(&self) -> f64 {
        self.motion.as_ref().map_or(0.0, |m| m.interval.0)
    }

    /// The `k`-th listed sphere at `time`: the stored copy, moved by its velocity in a moving tree.
    #[inline(always)]
    fn sphere_at(&self, k: usize, time: f64) -> Sphere<f64> {
        match &self.motion {
            Some(motion) => moved(self.exact.sphere(k), motion.velocities[self.indices[k] as usize], time),
            None => self.exact.sphere(k),
        }
    }

    /// Tests the spheres of the leaf `(first, count)` against `ray` over `(t_min, t_max)` at
    /// `time`, keeping in `best` the closest hit (ties to the lower index): the leaf step of both
    /// walks. With `filtered`, groups of `GROUP` quantised copies are tested at once first
    /// ([`CoarseRay::survivors_of`]: [`LANES`], or [`WIDE_LANES`] only in a walk compiled for
    /// AVX2, or [`WIDEST_LANES`] only in one compiled for AVX-512), and only the copies that may be
    /// hit reach the exact test, in list order; without it (a moving tree, or a sphere off the
    /// grid) every sphere is tested exactly.
    ///
    /// # Safety
    /// With `GROUP` 8 the CPU must have AVX2, with 16 AVX-512F and AVX-512BW ([`LANES`] needs
    /// nothing).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    unsafe fn test_leaf<const GROUP: usize>(
        &self,
        ray: &Ray<f64>,
        coarse: &CoarseRay,
        filtered: bool,
        (first, count): (u32, u32),
        (t_min, t_max): (f64, f64),
        time: f64,
        best: &mut Option<(usize, f64)>,
    ) {
        let (first, count) = (first as usize, count as usize);
        // A mask of the survivors per group, instead of a branch per copy.
        for group in (0..count).step_by(GROUP) {
            let lanes = (1u32 << (count - group).min(GROUP)) - 1;
            let copies = &self.coarse[first + group..];
            // SAFETY: the caller guarantees the features `GROUP` needs (this function's contract).
            let mask = if filtered { unsafe { coarse.survivors_of::<GROUP>(copies) } } else { lanes };
            let mut kept = mask & lanes;
            while kept != 0 {
                let k = first + group + kept.trailing_zeros() as usize;
                kept &= kept - 1;
                let Some(t) =
                    roots_stable(ray, &self.sphere_at(k, time)).and_then(|roots| roots.first_in(t_min, t_max))
                else {
                    continue;
                };
                let i = self.indices[k] as usize;
                if best.is_none_or(|(j, u)| t < u || (t == u && i < j)) {
                    *best = Some((i, t));
                }
            }
        }
    }

    /// [`KdTree::closest_hit`], also adding the work done to `stats`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::{Ray, Sphere};
    /// use hw3_render::kdtree::{HitStats, KdTree};
    /// let tree = KdTree::build(&[Sphere::new(DVec3::ZERO, 1.0).unwrap()]).unwrap();
    /// let ray = Ray::new(DVec3::new(0.0, 0.0, -5.0), DVec3::Z).unwrap();
    /// let mut stats = HitStats::default();
    /// let _ = tree.closest_hit_with_stats(&ray, 0.0, f64::INFINITY, &mut stats);
    /// assert_eq!((stats.nodes_visited, stats.sphere_tests), (1, 1));
    /// ```
    #[must_use]
    pub fn closest_hit_with_stats(
        &self,
        ray: &Ray<f64>,
        t_min: f64,
        t_max: f64,
        stats: &mut HitStats,
    ) -> Option<(usize, f64)> {
        self.traverse(Query { ray, t_min, t_max, time: self.default_time() }, stats)
    }

    /// The walk of one ray: [`KdTree::traverse_with`] with four copies per coarse test, or the
    /// same walk compiled for the CPU's widest vectors: sixteen copies per test with AVX-512F and
    /// AVX-512BW, eight with AVX2. The same answer either way: every lane of every test is the
    /// scalar test's. (The detection macro caches its answer: after the first call, each check is
    /// a load and a test.)
    #[inline]
    fn traverse<C: Counter>(&self, query: Query<'_>, counter: &mut C) -> Option<(usize, f64)> {
        #[cfg(x86_simd)]
        {
            use std::arch::is_x86_feature_detected as has;
            if has!("avx512f") && has!("avx512bw") {
                // SAFETY: the CPU has AVX-512F and AVX-512BW (checked just above).
                return unsafe { self.traverse_avx512(query, counter) };
            }
            if has!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above).
                return unsafe { self.traverse_avx2(query, counter) };
            }
        }
        // SAFETY: four copies per test need no feature beyond the target's baseline.
        unsafe { self.traverse_with::<C, LANES>(query, counter) }
    }

    /// [`KdTree::traverse_with`] compiled for AVX2, eight copies per coarse test.
    ///
    /// # Safety
    /// The CPU must have AVX2.
    #[cfg(x86_simd)]
    #[target_feature(enable = "avx2")]
    unsafe fn traverse_avx2<C: Counter>(&self, query: Query<'_>, counter: &mut C) -> Option<(usize, f64)> {
        // SAFETY: the caller guarantees AVX2 (this function's contract).
        unsafe { self.traverse_with::<C, WIDE_LANES>(query, counter) }
    }

    /// [`KdTree::traverse_with`] compiled for AVX-512 (and AVX2, which it includes), sixteen
    /// copies per coarse test. A processor that lowers its clock for 512-bit instructions may run
    /// the eight-wide walk faster; the walk is chosen by the features alone.
    ///
    /// # Safety
    /// The CPU must have AVX-512F and AVX-512BW.
    #[cfg(x86_simd)]
    #[target_feature(enable = "avx2,avx512f,avx512bw")]
    unsafe fn traverse_avx512<C: Counter>(&self, query: Query<'_>, counter: &mut C) -> Option<(usize, f64)> {
        // SAFETY: the caller guarantees AVX-512F and AVX-512BW (this function's contract).
        unsafe { self.traverse_with::<C, WIDEST_LANES>(query, counter) }
    }

    /// The single-ray walk, counting its work into `counter`, with `GROUP` copies per coarse test
    /// ([`KdTree::test_leaf`]).
    ///
    /// # Safety
    /// As [`KdTree::test_leaf`]: the CPU must have the features `GROUP` needs.
    #[inline(always)]
    unsafe fn traverse_with<C: Counter, const GROUP: usize>(
        &self,
        query: Query<'_>,
        counter: &mut C,
    ) -> Option<(usize, f64)> {
        let Query { ray, t_min, t_max, time } = query;
        if !(t_min < t_max) {
            return None;
        }
        let (mut cell_min, mut cell_max) = self.bounds.clip(ray, t_min, t_max)?;
        let mut best: Option<(usize, f64)> = None;
        let mut stack = FarStack::new();
        let mut node = 0u32;
        // A plain array: indexing a glam vector by a run-time axis is a three-way branch, which the
        // varying split axes make unpredictable.
        let axes = [0, 1, 2].map(|a| ReciprocalAxis::new(ray.origin[a], ray.dir[a]));
        // The coarse copies are of the spheres at time 0: a moving tree tests every sphere exactly.
        let coarse = CoarseRay::new(ray, &self.grid);
        let filtered = self.motion.is_none() && self.fits;
        // Which walk: a ray that starts inside the tree's box (its clipped interval begins at
        // `t_min`: a secondary ray of a path or photon tracer, the benchmark's random rays) takes
        // the interior step without a branch on the rule's outcome, because where such rays start
        // and go varies from ray to ray and the processor's guesses at those branches fail about
        // every other time; a ray from outside (a camera's) takes the branching step, whose
        // guesses consecutive rays make right and which lets the next node's load start early.
        // That step asks for no lines ahead: its rays find their nodes in the cache already. The
        // same nodes either way; the Q3 engineering notes give the price of each step, and what
        // coherent rays that start inside pay.
        let scattered = cell_min == t_min;
        loop {
            counter.node();
            match self.nodes[node as usize].kind() {
                NodeKind::Interior { split, upper, axis } if scattered => {
                    node = self.select_child((node, split, upper, axis), &axes, &mut stack, (cell_min, &mut cell_max));
                    continue;
                }
                NodeKind::Interior { split, upper, axis: a } => {
                    let pieces = split_pieces(axes[a], split, cell_min, cell_max);
                    let (near, far) = match pieces.near {
                        Side::Lower => (node + 1, upper),
                        Side::Upper => (upper, node + 1),
                    };
                    if pieces.near_live & pieces.far_live {
                        stack.push((far, pieces.t_plane, cell_max));
                        cell_max = pieces.t_plane;
                        node = near;
                    } else if pieces.near_live {
                        node = near;
                    } else {
                        node = far;
                    }
                    continue;
                }
                NodeKind::Leaf { first, count } => {
                    counter.sphere_tests(count);
                    if scattered && self.prefetch_exact {
                        self.exact.prefetch(first as usize..(first + count) as usize);
                    }
                    // SAFETY: the caller guarantees the features `GROUP` needs (this function's
                    // contract).
                    unsafe {
                        self.test_leaf::<GROUP>(
                            ray,
                            &coarse,
                            filtered,
                            (first, count),
                            (t_min, t_max),
                            time,
                            &mut best,
                        );
                    }
                }
            }
            // Early exit: the cells still on the stack begin at or after this one ends; one that
            // begins beyond the best hit cannot hold a closer (or equally close) hit.
            let best_t = best.map_or(f64::INFINITY, |(_, t)| t);
            match stack.pop() {
                Some(far) if !(far.1 > best_t) => (node, cell_min, cell_max) = far,
                _ => return best,
            }
        }
    }
}

/// One closest-hit query of the single-ray walk: the ray, its parameter range `(t_min, t_max)`
/// and the time at which a moving tree's spheres are placed.
#[derive(Clone, Copy)]
struct Query<'a> {
    ray: &'a Ray<f64>,
    t_min: f64,
    t_max: f64,
    time: f64,
}

/// Rays [`KdTree::closest_hits`] keeps in flight at once.
const IN_FLIGHT: usize = 8;

/// One ray in flight in [`KdTree::closest_hits`]: the single-ray walk's state between two steps.
#[derive(Clone, Copy)]
struct Flight {
    /// The ray's index in the batch.
    index: usize,
    ray: Ray<f64>,
    axes: [ReciprocalAxis; 3],
    coarse: CoarseRay,
    node: u32,
    cell_min: f64,
    cell_max: f64,
    best: Option<(usize, f64)>,
    stack: FarStack<f64>,
}

impl KdTree {
    /// [`KdTree::closest_hit`] for every ray of `rays`, written to `out` (`out[i]` for
    /// `rays[i]`), the same answers bit for bit. The walk is the single-ray walk, but a few rays
    /// are in flight at once and advance one node step each in turn, so that while one ray waits
    /// for its next node (a load that depends on the step before, and on a branch that random
    /// rays often guess wrong) the others' independent steps run: the "asynchronous memory access
    /// chaining" of Kocberber et al. (VLDB 2015), on a kd-tree. The interior step selects instead
    /// of branching (a wrong guess would flush the other rays' work too), the next node is
    /// prefetched when it is chosen, and a ray that ends is replaced by the next one of the batch.
    ///
    /// It pays for scattered rays (random origins and directions) in trees too large for the
    /// cache, where many rays wait for memory at once; for coherent rays in order (a camera's),
    /// which find their nodes in the cache and whose branches are well guessed, calling
    /// [`KdTree::closest_hit`] ray by ray is faster. The Q3 engineering notes give the current
    /// times of both.
    ///
    /// Preconditions: as [`KdTree::closest_hit`] (a ray or range it answers `None` for gets
    /// `None` here). A tree of moving spheres answers ray by ray.
    ///
    /// # Panics
    /// If `out.len() != rays.len()`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::{Ray, Sphere};
    /// use hw3_render::kdtree::KdTree;
    /// let tree = KdTree::build(&[Sphere::new(DVec3::new(0.0, 0.0, 5.0), 1.0).unwrap()]).unwrap();
    /// let rays = [Ray::new(DVec3::ZERO, DVec3::Z).unwrap(), Ray::new(DVec3::ZERO, DVec3::X).unwrap()];
    /// let mut out = [None; 2];
    /// tree.closest_hits(&rays, 0.0, f64::INFINITY, &mut out);
    /// assert_eq!(out, [Some((0, 4.0)), None]);
    /// ```
    pub fn closest_hits(&self, rays: &[Ray<f64>], t_min: f64, t_max: f64, out: &mut [Option<(usize, f64)>]) {
        assert_eq!(out.len(), rays.len(), "one answer slot per ray");
        if self.motion.is_some() {
            for (answer, ray) in out.iter_mut().zip(rays) {
                *answer = self.closest_hit(ray, t_min, t_max);
            }
            return;
        }
        self.in_flight::<IN_FLIGHT>(rays, t_min, t_max, out);
    }

    /// The interleaved walk of [`KdTree::closest_hits`] with `W` rays in flight, for a tree of
    /// static spheres.
    fn in_flight<const W: usize>(&self, rays: &[Ray<f64>], t_min: f64, t_max: f64, out: &mut [Option<(usize, f64)>]) {
        let idle = Flight {
            index: 0,
            ray: Ray { origin: DVec3::ZERO, dir: DVec3::Z },
            axes: [ReciprocalAxis::new(0.0, 1.0); 3],
            coarse: CoarseRay::new(&Ray { origin: DVec3::ZERO, dir: DVec3::Z }, &self.grid),
            node: 0,
            cell_min: 0.0,
            cell_max: 0.0,
            best: None,
            stack: FarStack::new(),
        };
        let mut flights = [idle; W];
        let mut next = 0;
        // The slots with a ray in flight are `live[..count]`; a slot whose ray ends takes the next
        // ray, or leaves the list when the batch is used up.
        let mut live = [0usize; W];
        let mut count = 0;
        for (slot, flight) in flights.iter_mut().enumerate() {
            if self.launch(flight, rays, &mut next, t_min, t_max, out) {
                live[count] = slot;
                count += 1;
            }
        }
        while count > 0 {
            let mut k = 0;
            while k < count {
                let flight = &mut flights[live[k]];
                if self.step(flight, t_min, t_max) {
                    out[flight.index] = flight.best;
                    if !self.launch(flight, rays, &mut next, t_min, t_max, out) {
                        count -= 1;
                        live[k] = live[count];
                        continue;
                    }
                }
                k += 1;
            }
        }
    }

    /// Loads the next ray of `rays` that needs a walk into `flight` (answering, in `out`, the
    /// rays that end before their first node: an empty range, or a miss of the tree's box);
    /// false when the batch is used up.
    #[inline]
    fn launch(
        &self,
        flight: &mut Flight,
        rays: &[Ray<f64>],
        next: &mut usize,
        t_min: f64,
        t_max: f64,
        out: &mut [Option<(usize, f64)>],
    ) -> bool {
        while let Some(ray) = rays.get(*next) {
            let index = *next;
            *next += 1;
            // As `traverse` begins.
            if !(t_min < t_max) {
                out[index] = None;
                continue;
            }
            let Some((cell_min, cell_max)) = self.bounds.clip(ray, t_min, t_max) else {
                out[index] = None;
                continue;
            };
            flight.index = index;
            flight.ray = *ray;
            flight.axes = [0, 1, 2].map(|a| ReciprocalAxis::new(ray.origin[a], ray.dir[a]));
            flight.coarse = CoarseRay::new(ray, &self.grid);
            (flight.node, flight.cell_min, flight.cell_max) = (0, cell_min, cell_max);
            flight.best = None;
            flight.stack.clear();
            return true;
        }
        false
    }

    /// The interior step of the walk without a branch on the interval rule's outcome, every
    /// choice a select: the step of the batch query, and of the single-ray walk for rays that
    /// start inside the tree's box. At the interior node `node` (split `split` on `axis`, upper
    /// child `upper`) with the cell `[cell_min, cell_max]`, returns the child to visit next,
    /// stores the far child on the stack when both pieces are live, and shortens `cell_max` to
    /// the plane then: the same decisions as the branching step. The far entry is stored every
    /// step and kept only when both pieces are live; at an interior node of tree depth d the stack
    /// holds at most d ≤ 59 entries (the build's depth bound), so the store stays inside the
    /// 64 entries of [`FarStack`]. Prefetches the upper child and the copies of a leaf lower
    /// child: the rays that take this step rarely find them in the cache.
    #[inline(always)]
    fn select_child(
        &self,
        (node, split, upper, axis): (u32, f64, u32, usize),
        axes: &[ReciprocalAxis; 3],
        stack: &mut FarStack<f64>,
        (cell_min, cell_max): (f64, &mut f64),
    ) -> u32 {
        prefetch(&self.nodes, upper);
        if let NodeKind::Leaf { first, .. } = self.nodes[node as usize + 1].kind() {
            prefetch(&self.coarse, first);
        }
        let pieces = split_pieces(axes[axis], split, cell_min, *cell_max);
        let lower = node + 1;
        let swap = u32::from(pieces.near == Side::Upper).wrapping_neg();
        let near = lower ^ ((lower ^ upper) & swap);
        let far = lower ^ upper ^ near;
        let both = pieces.near_live & pieces.far_live;
        stack.push_if((far, pieces.t_plane, *cell_max), both);
        // `t_plane` when both pieces are live, else `cell_max` unchanged (a parallel axis's NaN
        // keeps it too).
        let cut = if pieces.t_plane > cell_min { pieces.t_plane } else { f64::INFINITY };
        *cell_max = if cut < *cell_max { cut } else { *cell_max };
        std::hint::select_unpredictable(pieces.near_live, near, far)
    }

    /// One step of `traverse` (static spheres, no counter) on `flight`: an interior node's
    /// descent, or a leaf's tests and the pop or the end. True when the ray's walk is over (its
    /// answer in `flight.best`). The same operations in the same order as `traverse`, so the same
    /// answers.
    #[inline(always)]
    fn step(&self, flight: &mut Flight, t_min: f64, t_max: f64) -> bool {
        let node = flight.node;
        match self.nodes[node as usize].kind() {
            NodeKind::Interior { split, upper, axis } => {
                flight.node = self.select_child(
                    (node, split, upper, axis),
                    &flight.axes,
                    &mut flight.stack,
                    (flight.cell_min, &mut flight.cell_max),
                );
                // The other rays in flight run before this one's next step: its node can be on
                // the way meanwhile (a single ray reads it at once, so its walk does not ask).
                prefetch(&self.nodes, flight.node);
                return false;
            }
            NodeKind::Leaf { first, count } => {
                let time = self.default_time();
                // SAFETY: four copies per test need no feature beyond the target's baseline.
                unsafe {
                    self.test_leaf::<LANES>(
                        &flight.ray,
                        &flight.coarse,
                        self.fits,
                        (first, count),
                        (t_min, t_max),
                        time,
                        &mut flight.best,
                    );
                }
            }
        }
        let best_t = flight.best.map_or(f64::INFINITY, |(_, t)| t);
        match flight.stack.pop() {
            Some(far) if !(far.1 > best_t) => (flight.node, flight.cell_min, flight.cell_max) = far,
            _ => return true,
        }
        prefetch(&self.nodes, flight.node);
        false
    }
}

/// `sphere` moved by `velocity · time`; a static sphere untouched (no `+ 0·t`, which would turn a
/// `−0.0` coordinate into `+0.0`). The scene's brute-force loop uses it too: the same numbers.
pub(crate) fn moved(sphere: Sphere<f64>, velocity: DVec3, time: f64) -> Sphere<f64> {
    if velocity == DVec3::ZERO {
        sphere
    } else {
        Sphere { center: sphere.center + velocity * time, radius: sphere.radius }
    }
}

/// The reference: tests every sphere and keeps the smallest `t` in `(t_min, t_max)` (lowest index
/// on ties), with the same solver as the tree.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::{Ray, Sphere};
/// use hw3_render::kdtree::brute_force_closest_hit;
/// let spheres = [Sphere::new(DVec3::new(0.0, 0.0, 5.0), 1.0).unwrap()];
/// let ray = Ray::new(DVec3::ZERO, DVec3::Z).unwrap();
/// assert_eq!(brute_force_closest_hit(&spheres, &ray, 0.0, f64::INFINITY), Some((0, 4.0)));
/// ```
#[must_use]
pub fn brute_force_closest_hit(
    spheres: &[Sphere<f64>],
    ray: &Ray<f64>,
    t_min: f64,
    t_max: f64,
) -> Option<(usize, f64)> {
    let mut best: Option<(usize, f64)> = None;
    for (i, sphere) in spheres.iter().enumerate() {
        let hit = roots_stable(ray, sphere).and_then(|roots| roots.first_in(t_min, t_max));
        if let Some(t) = hit
            && best.is_none_or(|(_, u)| t < u)
        {
            best = Some((i, t));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use hw3_core::rng::{Generator, seeded, uniform_in as uniform};
    use rand_core::Rng as _;

    /// Random spheres in the unit cube; some centres and radii snapped to a coarse grid so that
    /// bounding boxes share faces and split planes land on them.
    fn scene(rng: &mut Generator, n: usize) -> Vec<Sphere<f64>> {
        (0..n)
            .map(|_| {
                let mut c = DVec3::new(uniform(rng, 0.0, 1.0), uniform(rng, 0.0, 1.0), uniform(rng, 0.0, 1.0));
                let mut r = uniform(rng, 0.01, 0.25);
                if rng.next_u64().is_multiple_of(4) {
                    c = (c * 8.0).round() / 8.0;
                    r = 0.125;
                }
                Sphere::new(c, r).unwrap()
            })
            .collect()
    }

    /// `spheres` with every centre coordinate and radius rounded to `f32`: a scene whose tree keeps
    /// its exact copies in `f32`.
    fn narrowed(spheres: &[Sphere<f64>]) -> Vec<Sphere<f64>> {
        let narrow = |s: &Sphere<f64>| Sphere::new(s.center.as_vec3().as_dvec3(), f64::from(s.radius as f32));
        spheres.iter().map(|s| narrow(s).unwrap()).collect()
    }

    /// Random rays: origins in a box around the scene (often on the grid), directions on the
    /// sphere, sometimes with exact (±)zero or axis-aligned components.
    fn random_ray(rng: &mut Generator) -> Ray<f64> {
        loop {
            let mut o = DVec3::new(uniform(rng, -0.5, 1.5), uniform(rng, -0.5, 1.5), uniform(rng, -0.5, 1.5));
            if rng.next_u64().is_multiple_of(4) {
                o = (o * 8.0).round() / 8.0;
            }
            let mut d = DVec3::new(uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0));
            for a in 0..3 {
                match rng.next_u64() % 10 {
                    0 => d[a] = 0.0,
                    1 => d[a] = -0.0,
                    _ => {}
                }
            }
            if let Ok(ray) = Ray::new(o, d) {
                return ray;
            }
        }
    }

    /// ≥ 10⁵ random rays over 100 random scenes (sizes 1 … 300): the tree's closest hit equals
    /// brute force exactly (same sphere, same t), in both walks (rays from inside and outside the
    /// tree's box), with four, eight and (where the CPU has AVX-512) sixteen copies per coarse
    /// test, and with the exact lists in `f64` and (every other scene rounded to `f32` values) in
    /// `f32`.
    #[test]
    fn closest_hit_equals_brute_force_on_random_rays() {
        let mut rng = seeded(0x4b44, 0);
        let mut inside = 0;
        let mut rays = 0;
        let mut hits = 0;
        for scene_index in 0..100 {
            let n = 1 + (scene_index * 37) % 300;
            let mut spheres = scene(&mut rng, n);
            let in_f32 = scene_index % 2 == 1;
            if in_f32 {
                spheres = narrowed(&spheres);
            }
            let tree = KdTree::build(&spheres).unwrap();
            assert_eq!(tree.exact.is_f32(), in_f32, "scene {scene_index}");
            for _ in 0..1_000 {
                let ray = random_ray(&mut rng);
                let t_min = if rng.next_u64().is_multiple_of(2) { 0.0 } else { 1e-4 };
                let t_max = if rng.next_u64().is_multiple_of(5) { 0.7 } else { f64::INFINITY };
                let expected = brute_force_closest_hit(&spheres, &ray, t_min, t_max);
                assert_eq!(tree.closest_hit(&ray, t_min, t_max), expected, "{ray:?}");
                // The four-wide walk too (what a CPU without AVX2 runs), and the eight-wide one
                // (AVX2 without AVX-512), whichever walk `closest_hit` takes on this one.
                let query = Query { ray: &ray, t_min, t_max, time: 0.0 };
                // SAFETY: four copies per test need no feature beyond the target's baseline.
                let four = unsafe { tree.traverse_with::<(), LANES>(query, &mut ()) };
                assert_eq!(four, expected, "four-wide: {ray:?}");
                #[cfg(x86_simd)]
                if std::arch::is_x86_feature_detected!("avx2") {
                    // SAFETY: the CPU has AVX2 (checked just above).
                    assert_eq!(unsafe { tree.traverse_avx2(query, &mut ()) }, expected, "eight-wide: {ray:?}");
                }
                rays += 1;
                hits += usize::from(expected.is_some());
                // The walk without branches takes the rays that start inside the tree's box.
                inside += usize::from(tree.bounds.clip(&ray, t_min, t_max).is_some_and(|(t0, _)| t0 == t_min));
            }
        }
        assert_eq!(rays, 100_000);
        assert!((20_000..80_000).contains(&inside), "both walks are exercised: {inside} rays start inside");
        // Coverage guard: about a quarter of these rays hit (26 918 with this seed); the rest miss
        // the scene or stop at t_max, which the comparison checks too.
        assert!(hits > 20_000, "the test exercises hits, got {hits}");
    }

    /// The batch query answers every ray as the single-ray query does, bit for bit: random scenes
    /// and rays (zero and −0 direction components, origins on the grid's planes), batches of 0 to
    /// 300 rays (fewer and more than the rays in flight), ranges that are empty, reversed, NaN or
    /// bounded, unvalidated rays with NaN or infinite components, and a tree of moving spheres;
    /// exact copies in `f64` and (every other scene rounded to `f32` values) in `f32`.
    #[test]
    fn closest_hits_equal_closest_hit_ray_by_ray() {
        let mut rng = seeded(0xBA7C, 0);
        let (mut rays_checked, mut hits) = (0, 0);
        let ranges = [
            (0.0, f64::INFINITY),
            (1e-4, f64::INFINITY),
            (0.0, 0.7),
            (0.5, 0.5),
            (2.0, 1.0),
            (f64::NAN, 1.0),
            (0.0, f64::NAN),
            (-1.0, 1e-3),
            (f64::NEG_INFINITY, f64::INFINITY),
        ];
        for scene_index in 0..60 {
            let n = 1 + (scene_index * 53) % 400;
            let spheres = scene(&mut rng, n);
            // Every other scene in `f32` values: the exact copies in `f32`.
            let spheres = if scene_index % 2 == 1 { narrowed(&spheres) } else { spheres };
            let tree = KdTree::build(&spheres).unwrap();
            assert_eq!(tree.exact.is_f32(), scene_index % 2 == 1);
            let (t_min, t_max) = ranges[scene_index % ranges.len()];
            let count = [0, 1, 3, 7, 8, 9, 17, 300][scene_index % 8];
            let mut rays: Vec<Ray<f64>> = (0..count).map(|_| random_ray(&mut rng)).collect();
            if count > 5 {
                rays[1] = Ray { origin: DVec3::new(f64::NAN, 0.5, 0.5), dir: DVec3::X };
                rays[2] = Ray { origin: DVec3::splat(0.5), dir: DVec3::new(f64::INFINITY, 0.0, 1.0) };
                rays[3] = Ray { origin: DVec3::new(0.5, 0.5, -1.0), dir: DVec3::new(0.0, -0.0, 1.0) };
            }
            let mut out = vec![Some((usize::MAX, -1.0)); count];
            tree.closest_hits(&rays, t_min, t_max, &mut out);
            for (ray, answer) in rays.iter().zip(&out) {
                let expected = tree.closest_hit(ray, t_min, t_max);
                assert_eq!(answer.map(|(i, t)| (i, t.to_bits())), expected.map(|(i, t)| (i, t.to_bits())), "{ray:?}");
                hits += usize::from(expected.is_some());
            }
            rays_checked += count;
        }
        // Many rays per batch on one larger scene, every ray against brute force too.
        let spheres = scene(&mut rng, 2_000);
        let tree = KdTree::build(&spheres).unwrap();
        let rays: Vec<Ray<f64>> = (0..20_000).map(|_| random_ray(&mut rng)).collect();
        let mut out = vec![None; rays.len()];
        tree.closest_hits(&rays, 1e-4, f64::INFINITY, &mut out);
        for (ray, answer) in rays.iter().zip(&out) {
            assert_eq!(*answer, tree.closest_hit(ray, 1e-4, f64::INFINITY), "{ray:?}");
            assert_eq!(*answer, brute_force_closest_hit(&spheres, ray, 1e-4, f64::INFINITY), "{ray:?}");
            hits += usize::from(answer.is_some());
        }
        rays_checked += rays.len();
        assert!(rays_checked > 21_000 && hits > 5_000, "{hits} hits of {rays_checked} rays");
        // A moving tree answers ray by ray, at its default time.
        let velocities: Vec<DVec3> = (0..spheres.len()).map(|i| DVec3::X * (i % 3) as f64 * 0.1).collect();
        let moving = KdTree::build_moving(&spheres, &velocities, (0.0, 1.0)).unwrap();
        let mut out = vec![None; 500];
        moving.closest_hits(&rays[..500], 0.0, f64::INFINITY, &mut out);
        for (ray, answer) in rays.iter().zip(&out) {
            assert_eq!(*answer, moving.closest_hit(ray, 0.0, f64::INFINITY));
        }
    }

    /// Every width of the interleaved walk gives the single-ray answers (the public query uses one).
    #[test]
    fn every_flight_width_answers_alike() {
        let mut rng = seeded(0xBA7D, 0);
        let spheres = scene(&mut rng, 500);
        let tree = KdTree::build(&spheres).unwrap();
        let rays: Vec<Ray<f64>> = (0..2_000).map(|_| random_ray(&mut rng)).collect();
        let expected: Vec<_> = rays.iter().map(|r| tree.closest_hit(r, 0.0, f64::INFINITY)).collect();
        let mut out = vec![None; rays.len()];
        tree.in_flight::<1>(&rays, 0.0, f64::INFINITY, &mut out);
        assert_eq!(out, expected);
        out.fill(None);
        tree.in_flight::<4>(&rays, 0.0, f64::INFINITY, &mut out);
        assert_eq!(out, expected);
        out.fill(None);
        tree.in_flight::<16>(&rays, 0.0, f64::INFINITY, &mut out);
        assert_eq!(out, expected);
        assert!(expected.iter().filter(|h| h.is_some()).count() > 200);
    }

    #[test]
    #[should_panic(expected = "one answer slot per ray")]
    fn closest_hits_refuses_a_short_output() {
        let tree = KdTree::build(&[Sphere::new(DVec3::ZERO, 1.0).unwrap()]).unwrap();
        tree.closest_hits(&[Ray::new(DVec3::ZERO, DVec3::X).unwrap()], 0.0, 1.0, &mut []);
    }

    /// Trying every box face in small nodes (instead of only the binned planes) lowers the tree's
    /// SAH cost on random scenes of the benchmark's kind, and the tree still answers exactly.
    #[test]
    fn exact_candidates_in_small_nodes_lower_the_sah_cost() {
        let mut rng = seeded(11, 0);
        for n in [200, 2_000, 20_000] {
            let r = (3.0 / (std::f64::consts::PI * n as f64)).sqrt();
            let spheres: Vec<_> = (0..n)
                .map(|_| {
                    let c = DVec3::new(
                        uniform(&mut rng, 0.0, 1.0),
                        uniform(&mut rng, 0.0, 1.0),
                        uniform(&mut rng, 0.0, 1.0),
                    );
                    Sphere::new(c, r * uniform(&mut rng, 0.5, 1.5)).unwrap()
                })
                .collect();
            let prims = sphere_prims(&spheres).unwrap();
            // The default costs, and the K_I = 0.3 under which the gain was first measured: with
            // the default K_I = 0.075 nodes of up to 13 spheres are leaves without a search and
            // fewer small nodes split, so at N = 200 the two candidate sets can build equally good
            // trees.
            let at_0_3 = SahCosts { intersection: 0.3, ..SahCosts::default() };
            for (costs, strictly) in [(SahCosts::default(), false), (at_0_3, true)] {
                let binned = KdTree::from_prims_with(&spheres, prims.clone(), costs, 0).sah_cost(&costs);
                let exact = KdTree::from_prims_with(&spheres, prims.clone(), costs, EXACT_MAX).sah_cost(&costs);
                assert!(
                    exact < binned || (!strictly && exact == binned),
                    "N = {n}, K_I = {}: SAH cost {exact} with exact small nodes, {binned} binned",
                    costs.intersection
                );
            }
        }
    }

    /// A build on one thread and one on four give the same tree: the same nodes, the same leaf
    /// lists (index and sphere), the same quantised copies and box. 120 000 small spheres, a
    /// quarter of them snapped to a grid (shared faces, planes on them), so that several levels
    /// lie above the parallel threshold and their planes see ties.
    #[test]
    fn builds_on_one_and_on_four_threads_are_identical() {
        let mut rng = seeded(0x5eed, 6);
        let n = 120_000;
        let r = (3.0 / (std::f64::consts::PI * n as f64)).sqrt();
        let spheres: Vec<_> = (0..n)
            .map(|_| {
                let mut c =
                    DVec3::new(uniform(&mut rng, 0.0, 1.0), uniform(&mut rng, 0.0, 1.0), uniform(&mut rng, 0.0, 1.0));
                if rng.next_u64().is_multiple_of(4) {
                    c = (c * 64.0).round() / 64.0;
                }
                Sphere::new(c, r * uniform(&mut rng, 0.5, 1.5)).unwrap()
            })
            .collect();
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| KdTree::build(&spheres).unwrap())
        };
        let (one, four) = (on(1), on(4));
        assert!(one.node_count() > 10_000, "{} nodes", one.node_count());
        assert_eq!(one.nodes, four.nodes);
        assert_eq!(one.bounds, four.bounds);
        assert_eq!((one.fits, one.grid), (four.fits, four.grid));
        assert_eq!(one.coarse, four.coarse);
        let leaves = |tree: &KdTree| (tree.exact.clone(), tree.indices.clone(), tree.prefetch_exact);
        assert_eq!(leaves(&one), leaves(&four));
    }

    #[test]
    fn tree_prunes_work_on_a_large_scene() {
        let mut rng = seeded(7, 0);
        let spheres: Vec<_> = (0..2_000)
            .map(|_| {
                let c =
                    DVec3::new(uniform(&mut rng, 0.0, 1.0), uniform(&mut rng, 0.0, 1.0), uniform(&mut rng, 0.0, 1.0));
                Sphere::new(c, 0.01).unwrap()
            })
            .collect();
        let tree = KdTree::build(&spheres).unwrap();
        let mut stats = HitStats::default();
        for _ in 0..1_000 {
            let ray = random_ray(&mut rng);
            let _ = tree.closest_hit_with_stats(&ray, 0.0, f64::INFINITY, &mut stats);
        }
        // Brute force would make 2 000 tests per ray.
        assert!(stats.sphere_tests < 1_000 * 50, "{stats:?}");
        assert!(stats.nodes_visited > 0);
    }

    #[test]
    fn negative_zero_direction_hits_like_positive_zero() {
        let spheres: Vec<_> = (0..64)
            .map(|i| {
                let c = DVec3::new(f64::from(i % 4), f64::from((i / 4) % 4), f64::from(i / 16));
                Sphere::new(c * 0.25, 0.1).unwrap()
            })
            .collect();
        let tree = KdTree::build(&spheres).unwrap();
        for sign in [1.0, -1.0] {
            // Origin exactly on split-candidate planes, direction (±0, ±0, −1).
            let ray = Ray::new(DVec3::new(0.5, 0.5, 2.0), DVec3::new(0.0 * sign, 0.0 * sign, -1.0)).unwrap();
            let expected = brute_force_closest_hit(&spheres, &ray, 0.0, f64::INFINITY);
            assert!(expected.is_some());
            assert_eq!(tree.closest_hit(&ray, 0.0, f64::INFINITY), expected);
        }
    }

    #[test]
    fn degenerate_scenes_build_and_answer() {
        let empty = KdTree::build(&[]).unwrap();
        let ray = Ray::new(DVec3::ZERO, DVec3::X).unwrap();
        assert_eq!(empty.closest_hit(&ray, 0.0, f64::INFINITY), None);
        // 100 identical spheres: no split helps, one leaf; the lowest index wins the tie.
        let same = vec![Sphere::new(DVec3::new(5.0, 0.0, 0.0), 1.0).unwrap(); 100];
        let tree = KdTree::build(&same).unwrap();
        assert_eq!(tree.closest_hit(&ray, 0.0, f64::INFINITY), Some((0, 4.0)));
        // Tiny spheres on a line: cells of almost zero area, many ray/box ties along the axis.
        let points: Vec<_> = (0..50).map(|i| Sphere::new(DVec3::new(f64::from(i), 0.0, 0.0), 1e-9).unwrap()).collect();
        let tree = KdTree::build(&points).unwrap();
        let along = Ray::new(DVec3::new(-1.0, 0.0, 0.0), DVec3::X).unwrap();
        assert_eq!(
            tree.closest_hit(&along, 0.0, f64::INFINITY),
            brute_force_closest_hit(&points, &along, 0.0, f64::INFINITY)
        );
    }

    #[test]
    fn empty_or_nan_parameter_range_is_a_miss() {
        let tree = KdTree::build(&[Sphere::new(DVec3::ZERO, 1.0).unwrap()]).unwrap();
        let ray = Ray::new(DVec3::new(0.0, 0.0, -5.0), DVec3::Z).unwrap();
        assert_eq!(tree.closest_hit(&ray, 2.0, 2.0), None);
        assert_eq!(tree.closest_hit(&ray, f64::NAN, 10.0), None);
    }

    /// Moving spheres in the tree by their swept boxes: 300 random spheres, a third of them
    /// moving fast, queried by 2000 random rays at times inside the build interval (through the
    /// tree) and outside it (every sphere tested): the same answers as testing every moved
    /// sphere, bit for bit. Mismatched velocity counts are a typed error.
    #[test]
    fn moving_spheres_are_found_at_every_time() {
        let mut rng = hw3_core::rng::seeded(5, 0);
        let mut uniform = |lo: f64, hi: f64| hw3_core::rng::uniform_in(&mut rng, lo, hi);
        let spheres: Vec<_> = (0..300)
            .map(|_| {
                Sphere::new(DVec3::new(uniform(-10.0, 10.0), uniform(-10.0, 10.0), uniform(-10.0, 10.0)), 0.5).unwrap()
            })
            .collect();
        let velocities: Vec<_> = (0..300)
            .map(|i| if i % 3 == 0 { DVec3::new(uniform(-4.0, 4.0), uniform(-4.0, 4.0), 0.0) } else { DVec3::ZERO })
            .collect();
        let tree = KdTree::build_moving(&spheres, &velocities, (0.0, 1.0)).unwrap();
        let mut hits = 0;
        for case in 0..2000 {
            let origin = DVec3::new(uniform(-15.0, 15.0), uniform(-15.0, 15.0), -15.0);
            let target = DVec3::new(uniform(-10.0, 10.0), uniform(-10.0, 10.0), 10.0);
            let ray = Ray::new(origin, (target - origin).normalize()).unwrap();
            let time = [0.0, 0.3, 1.0, 1.7, -0.5][case % 5];
            let moved: Vec<_> = (0..300).map(|i| super::moved(spheres[i], velocities[i], time)).collect();
            let expected = brute_force_closest_hit(&moved, &ray, 0.0, f64::INFINITY);
            assert_eq!(tree.closest_hit_at(&ray, 0.0, f64::INFINITY, time), expected, "ray {case} at {time}");
            hits += usize::from(expected.is_some());
        }
        assert!(hits > 200, "{hits} of 2000 rays hit");
        assert!(matches!(
            KdTree::build_moving(&spheres, &velocities[..2], (0.0, 1.0)),
            Err(BuildError::VelocityCount { spheres: 300, velocities: 2 })
        ));
    }

    /// The estimate on a tree written by hand, worked out in small numbers: the box
    /// [−2, 2] × [−1, 1] × [−1, 1] split at x = 0 into two cells of area 24 each; the lower leaf
    /// lists a ball of radius 1 (area 4π), the upper one a ball of radius ½ (area π) and one of
    /// radius 2 (area 16π, more than its cell's 24, so counted as 24): (4π + π + 24) / 48.
    #[test]
    fn survivors_per_leaf_visit_caps_a_sphere_at_its_cell_and_weighs_leaves_by_area() {
        let spheres = [
            Sphere::new(DVec3::new(-1.0, 0.0, 0.0), 1.0).unwrap(),
            Sphere::new(DVec3::new(1.0, 0.0, 0.0), 0.5).unwrap(),
            Sphere::new(DVec3::new(1.0, 0.0, 0.0), 2.0).unwrap(),
        ];
        let nodes = [Node::interior(0.0, 0, 2), Node::leaf(0, 1), Node::leaf(1, 2)];
        let bounds = Aabb { min: DVec3::new(-2.0, -1.0, -1.0), max: DVec3::new(2.0, 1.0, 1.0) };
        let estimate = survivors_per_leaf_visit(&nodes, bounds, &ExactLists::new(&spheres, &[0, 1, 2], false));
        let expected = (5.0 * std::f64::consts::PI + 24.0) / 48.0;
        assert!((estimate - expected).abs() <= 4.0 * f64::EPSILON * expected, "{estimate} against {expected}");
    }

    /// Which trees ask for a leaf's exact spheres ahead: 80 000 spheres filling about a tenth of
    /// the unit cube (124 266 listings, 4.0 MB of `f64` copies; 0.81 expected survivors per leaf
    /// visit) do; as many spheres ten times smaller (81 927 listings, 2.6 MB; 0.005 per visit) do
    /// not, and neither do 8 000 spheres filling a tenth of the cube (0.72 per visit, but 11 846
    /// listings, 0.4 MB). A tree that asks answers as brute force does, rays from inside its box
    /// (the walk that asks) and from outside, with its lists in `f64` and, for the same scene
    /// rounded to `f32` values, in `f32`.
    #[test]
    fn only_large_spheres_in_large_lists_are_asked_for_ahead() {
        let mut rng = seeded(0x5EED, 1);
        let n = 80_000;
        // The radius at which `n` spheres fill about a tenth of the unit cube.
        let radius = |n: usize| (0.1 * 3.0 / (4.0 * std::f64::consts::PI * n as f64)).cbrt();
        let scene_of = |rng: &mut Generator, n: usize, radius: f64| -> Vec<Sphere<f64>> {
            (0..n)
                .map(|_| {
                    let c = DVec3::new(uniform(rng, 0.0, 1.0), uniform(rng, 0.0, 1.0), uniform(rng, 0.0, 1.0));
                    Sphere::new(c, radius * uniform(rng, 0.5, 1.5)).unwrap()
                })
                .collect()
        };
        let large_lists = |tree: &KdTree| tree.exact.bytes() > PREFETCH_MIN_BYTES;
        let large = scene_of(&mut rng, n, radius(n));
        let tree = KdTree::build(&large).unwrap();
        let estimate = tree.survivors_per_leaf_visit();
        assert!(large_lists(&tree) && estimate > PREFETCH_SURVIVORS && tree.prefetch_exact, "{estimate}");
        let small = scene_of(&mut rng, n, radius(n) / 10.0);
        let small_tree = KdTree::build(&small).unwrap();
        let estimate = small_tree.survivors_per_leaf_visit();
        assert!(large_lists(&small_tree) && estimate < PREFETCH_SURVIVORS && !small_tree.prefetch_exact, "{estimate}");
        let few = scene_of(&mut rng, n / 10, radius(n / 10));
        let few_tree = KdTree::build(&few).unwrap();
        let estimate = few_tree.survivors_per_leaf_visit();
        assert!(!large_lists(&few_tree) && estimate > PREFETCH_SURVIVORS && !few_tree.prefetch_exact, "{estimate}");
        // The same large scene in `f32` values: its 16-byte lists, asked for ahead too (set by
        // hand, whatever their size), so that the walk's `f32` prefetch runs.
        let narrowed = narrowed(&large);
        let mut narrow_tree = KdTree::build(&narrowed).unwrap();
        assert!(narrow_tree.exact.is_f32());
        narrow_tree.prefetch_exact = true;
        let (mut inside, mut hits) = (0, 0);
        for _ in 0..1_000 {
            let ray = random_ray(&mut rng);
            let expected = brute_force_closest_hit(&large, &ray, 0.0, f64::INFINITY);
            assert_eq!(tree.closest_hit(&ray, 0.0, f64::INFINITY), expected, "{ray:?}");
            let narrow_expected = brute_force_closest_hit(&narrowed, &ray, 0.0, f64::INFINITY);
            assert_eq!(narrow_tree.closest_hit(&ray, 0.0, f64::INFINITY), narrow_expected, "f32 lists: {ray:?}");
            inside += usize::from(tree.bounds.clip(&ray, 0.0, f64::INFINITY).is_some_and(|(t0, _)| t0 == 0.0));
            hits += usize::from(expected.is_some());
        }
        // About an eighth of the origins lie in the cube, and about a fifth of the rays hit.
        assert!(inside > 80 && hits > 150, "{inside} rays from inside, {hits} hits");
    }
}
