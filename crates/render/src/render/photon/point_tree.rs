//! The photon map's search structure: a balanced kd-tree over points, for k-nearest queries.
//!
//! Jensen (*Realistic Image Synthesis Using Photon Mapping*, 2001, ch. 6) keeps the photons in a
//! balanced kd-tree: split the points at their median along the axis where they spread widest,
//! recurse on both halves; a query walks down to the query point's side first and visits the
//! other side of a split only if it could hold a point nearer than the `k`-th nearest found so
//! far. As in Jensen's, a node is a range of one array, without pointers: the range `lo..hi` holds
//! its median point at `mid = lo + (hi − lo)/2`, whose coordinate on the node's axis splits the
//! children `lo..mid` (not above it) and `mid + 1..hi` (not below it). Beyond Jensen's: ranges of
//! at most [`LEAF_SIZE`] points are leaves, scanned one by one (fewer nodes to walk); the far side
//! is judged by its distance along every axis split on the way down, not only the last one (Arya
//! and Mount's incremental distance, *Algorithms for fast vector quantization*, DCC 1993); and the
//! `k` best are kept in a buffer cut back now and then instead of a heap (`Candidates`).
//!
//! Numerics: squared distances are [`glam::DVec3::distance_squared`]'s, `dx² + dy² + dz²` summed in
//! that order. A far side's distance is the same sum over the query's offsets from the splitting
//! planes ([`glam::DVec3::length_squared`]); every step of it is monotonic under rounding, so it
//! never exceeds the computed distance of a point beyond those planes, and skipping a side never
//! loses a point. Among points at equal squared distance the lower index comes first, so the
//! answer does not depend on how the tree was split.

use glam::DVec3;
use std::cmp::Ordering;

/// Most points in a leaf: smaller leaves mean more nodes to walk, larger ones more distances to
/// compute. 4, 8, 16 and 32 time within noise of each other for the 50 nearest of
/// 10⁵ points on a sphere.
pub const LEAF_SIZE: usize = 8;

/// Ranges larger than this build their two halves on two threads (`rayon::join`); the split is
/// the same either way, so the tree does not depend on the thread count.
const PARALLEL_BUILD: usize = 1 << 14;

/// One answer of [`PointTree::nearest`]: which point, and how far from the query.
///
/// Ordered by squared distance ([`f64::total_cmp`]), then by index: the order of the answers.
/// Equality is that order's (the same bits of the distance, the same index).
#[derive(Debug, Clone, Copy)]
pub struct Neighbour {
    /// Index of the point in the slice the tree was built from.
    pub index: u32,
    /// Squared distance from the query point.
    pub distance_squared: f64,
}

impl Ord for Neighbour {
    fn cmp(&self, other: &Self) -> Ordering {
        self.distance_squared.total_cmp(&other.distance_squared).then(self.index.cmp(&other.index))
    }
}

impl PartialOrd for Neighbour {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl PartialEq for Neighbour {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Neighbour {}

/// A balanced kd-tree over 3-D points (see the module documentation).
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_render::render::photon::PointTree;
/// let points: Vec<DVec3> = (0..100).map(|i| DVec3::new(f64::from(i), 0.0, 0.0)).collect();
/// let tree = PointTree::new(&points);
/// // The three points nearest to x = 41.8: 42, 41, 43, nearest first.
/// let found = tree.nearest(DVec3::new(41.8, 0.0, 0.0), 3, f64::INFINITY);
/// assert_eq!(found.iter().map(|n| n.index).collect::<Vec<_>>(), [42, 41, 43]);
/// ```
#[derive(Debug, Clone)]
pub struct PointTree {
    /// The points in tree order.
    points: Vec<DVec3>,
    /// For each point in tree order, its index in the slice the tree was built from.
    indices: Vec<u32>,
    /// The split axis (0, 1, 2) of the node whose median point is here; unused at leaves.
    axes: Vec<u8>,
}

impl PointTree {
    /// The tree over `points` (any number, repeats allowed).
    ///
    /// Building costs `O(n log n)`: every level partitions each range around its median
    /// (`select_nth_unstable_by`, linear on average).
    ///
    /// # Panics
    /// If there are more than `u32::MAX` points (indices are stored as `u32`), or a coordinate is
    /// NaN (the median of a NaN is undefined; the photon tracer stores only finite hit points).
    #[must_use]
    pub fn new(points: &[DVec3]) -> Self {
        assert!(u32::try_from(points.len()).is_ok(), "a point tree holds at most 2³² − 1 points");
        assert!(points.iter().all(|p| !p.is_nan()), "a point tree's points must not be NaN");
        // Each point travels with its index: the medians are found by moving whole records of
        // one contiguous array, not indices whose comparisons would read the points at random
        // (a cache miss each, once the points outgrow the cache).
        let mut records: Vec<(DVec3, u32)> = points.iter().copied().zip(0..).collect();
        let mut axes = vec![0u8; points.len()];
        build(&mut records, &mut axes);
        let (points, indices) = records.into_iter().unzip();
        Self { points, indices, axes }
    }

    /// Number of points.
    #[must_use]
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the tree holds no point.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The `k` points nearest to `query` with squared distance at most `max_distance_squared`
    /// (pass `f64::INFINITY` for no limit), nearest first; fewer if fewer lie within the limit.
    /// Ties in distance are ordered by index, so the answer is the first `k` of all points
    /// sorted by (squared distance, index), cut at the limit.
    ///
    /// A query with a NaN coordinate, or a NaN limit, finds nothing; a point whose squared distance
    /// is NaN (∞ − ∞: the point and the query infinite on the same axis) is never found.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_render::render::photon::PointTree;
    /// let points = [DVec3::ZERO, DVec3::X, DVec3::X, DVec3::splat(5.0)];
    /// let tree = PointTree::new(&points);
    /// // Within distance 2 of (1, 0, 0): the two copies of it (index order), then the origin.
    /// let found = tree.nearest(DVec3::X, 10, 4.0);
    /// assert_eq!(found.iter().map(|n| (n.index, n.distance_squared)).collect::<Vec<_>>(), [(1, 0.0), (2, 0.0), (0, 1.0)]);
    /// ```
    #[must_use]
    pub fn nearest(&self, query: DVec3, k: usize, max_distance_squared: f64) -> Vec<Neighbour> {
        if k == 0 || self.points.is_empty() || query.is_nan() || max_distance_squared.is_nan() {
            return Vec::new();
        }
        self.candidates(query, k, max_distance_squared).into_sorted()
    }

    /// The search itself; `k ≥ 1`, a query and limit without NaN, a tree with points.
    fn candidates(&self, query: DVec3, k: usize, max_distance_squared: f64) -> Candidates {
        let mut found = Candidates::new(k, max_distance_squared, self.points.len());
        self.search(0, self.points.len(), query, DVec3::ZERO, &mut found);
        found
    }

    /// Offers the points of `lo..hi` whose cell may hold a winner. `gap[a]` is the query's offset
    /// along axis `a` from the slab of space this subtree covers (0 where the query lies within
    /// it), so `gap · gap` is a lower bound on the squared distance to any point here (Arya and
    /// Mount's incremental distance): summed in the order of a point's squared distance, rounding
    /// keeps it a lower bound of the computed distances too, since every step is monotonic.
    fn search(&self, lo: usize, hi: usize, query: DVec3, gap: DVec3, found: &mut Candidates) {
        if hi - lo <= LEAF_SIZE {
            for (point, &index) in self.points[lo..hi].iter().zip(&self.indices[lo..hi]) {
                found.offer(point.distance_squared(query), index);
            }
            return;
        }
        let mid = lo + (hi - lo) / 2;
        let axis = usize::from(self.axes[mid]);
        found.offer(self.points[mid].distance_squared(query), self.indices[mid]);
        // Points in lo..mid have coordinate ≤ the median's, points in mid + 1..hi ≥ it: the far
        // side lies at least |delta| away along this axis.
        let delta = query[axis] - self.points[mid][axis];
        let ((near_lo, near_hi), (far_lo, far_hi)) =
            if delta < 0.0 { ((lo, mid), (mid + 1, hi)) } else { ((mid + 1, hi), (lo, mid)) };
        self.search(near_lo, near_hi, query, gap, found);
        let mut far_gap = gap;
        far_gap[axis] = delta;
        // Not `<`: a far point at exactly the bound may still win a tie by its index; and a NaN
        // gap (∞ − ∞, a query and a split both at infinity) proves nothing, so it visits.
        if !(far_gap.length_squared() > found.bound) {
            self.search(far_lo, far_hi, query, far_gap, found);
        }
    }
}

/// Orders `records` (points with their indices) into tree order and records each interior
/// node's axis at its middle (`axes` is the part of the tree's axis array for this range).
///
/// Which of several points with the median's coordinate lands on which side is up to the
/// standard library's selection; the answers of [`PointTree::nearest`] do not depend on it (ties
/// go to the lower index), as the brute-force tests below check on grids, copies and planes.
fn build(records: &mut [(DVec3, u32)], axes: &mut [u8]) {
    let n = records.len();
    if n <= LEAF_SIZE {
        return;
    }
    let (lower, upper) = records
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lower, upper), &(p, _)| (lower.min(p), upper.max(p)));
    let axis = (upper - lower).max_position();
    let mid = n / 2;
    records.select_nth_unstable_by(mid, |a, b| a.0[axis].total_cmp(&b.0[axis]));
    axes[mid] = axis as u8;
    let (records_left, records_right) = records.split_at_mut(mid);
    let (axes_left, axes_right) = axes.split_at_mut(mid);
    let (records_right, axes_right) = (&mut records_right[1..], &mut axes_right[1..]);
    if n > PARALLEL_BUILD {
        rayon::join(|| build(records_left, axes_left), || build(records_right, axes_right));
    } else {
        build(records_left, axes_left);
        build(records_right, axes_right);
    }
}

/// The best `k` offers so far, kept lazily: offers go into a buffer of up to `2k`, which is cut
/// back to its best `k` (`select_nth_unstable`, linear) whenever it fills, so each offer costs
/// O(1) amortised instead of a heap's O(log k). The `k`-th distance of the last cut bounds what
/// may still enter: looser than the exact `k`-th between cuts, never wrong. (A `BinaryHeap` of
/// `k` is about 1.1× slower at k = 50 and 1.9× at k = 2048 for 1000 queries among 10⁵ points on
/// a sphere; a sorted array is slower than the heap.)
struct Candidates {
    buffer: Vec<Neighbour>,
    /// Squared distances computed (offers made), for the test that the walk prunes.
    offers: usize,
    k: usize,
    /// The squared distance beyond which no point can enter: the limit until the first cut, then
    /// the `k`-th squared distance at the last cut.
    bound: f64,
}

impl Candidates {
    /// `k ≥ 1` best of `points ≥ 1`; a `k` above `points` is cut to it (so `2k` cannot overflow).
    fn new(k: usize, limit: f64, points: usize) -> Self {
        let k = k.min(points);
        Self { buffer: Vec::with_capacity(2 * k), offers: 0, k, bound: limit }
    }

    fn offer(&mut self, distance_squared: f64, index: u32) {
        self.offers += 1;
        // Also refuses NaN: ∞ − ∞ when a point and the query are infinite on the same axis.
        if !(distance_squared <= self.bound) {
            return;
        }
        self.buffer.push(Neighbour { index, distance_squared });
        if self.buffer.len() == 2 * self.k {
            self.keep_best();
        }
    }

    /// Cuts the buffer to its best `k` (if it holds more) and tightens the bound.
    fn keep_best(&mut self) {
        let k = self.k;
        if self.buffer.len() >= k {
            self.buffer.select_nth_unstable(k - 1);
            self.buffer.truncate(k);
            self.bound = self.buffer[k - 1].distance_squared;
        }
    }

    /// The best `k` (or fewer), nearest first.
    fn into_sorted(mut self) -> Vec<Neighbour> {
        self.keep_best();
        self.buffer.sort_unstable();
        self.buffer
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::sampling::{Sampler, fibonacci_sphere, uniform_sphere};

    /// A point uniform in the unit cube.
    fn in_unit_cube(sampler: &mut Sampler) -> DVec3 {
        DVec3::new(sampler.uniform(), sampler.uniform(), sampler.uniform())
    }

    /// All points sorted by (squared distance, index), cut at the limit and at `k`: what
    /// [`PointTree::nearest`] promises.
    fn brute_force(points: &[DVec3], query: DVec3, k: usize, limit: f64) -> Vec<Neighbour> {
        let mut all: Vec<Neighbour> = points
            .iter()
            .enumerate()
            .map(|(i, p)| Neighbour { index: i as u32, distance_squared: p.distance_squared(query) })
            .filter(|n| n.distance_squared <= limit)
            .collect();
        all.sort();
        all.truncate(k);
        all
    }

    /// Point sets that stress the splits: uniform in a cube, on a plane (one axis never spreads),
    /// on a coarse grid (many equal coordinates and equal distances), clustered copies of a few
    /// points, and collinear; sizes around the leaf size and the parallel build's threshold.
    fn point_sets() -> Vec<(&'static str, Vec<DVec3>)> {
        let mut sampler = Sampler::new(7, 0, 0);
        let mut uniform = |n: usize| -> Vec<DVec3> { (0..n).map(|_| in_unit_cube(&mut sampler)).collect() };
        let cube = uniform(40_000);
        let plane: Vec<DVec3> = uniform(3000).into_iter().map(|p| DVec3::new(p.x, p.y, 0.25)).collect();
        let grid: Vec<DVec3> =
            (0..4096).map(|i| DVec3::new(f64::from(i % 16), f64::from(i / 16 % 16), f64::from(i / 256))).collect();
        let copies: Vec<DVec3> = (0..5000).map(|i| DVec3::splat(f64::from(i % 5))).collect();
        let line: Vec<DVec3> = (0..1000).map(|i| DVec3::new(f64::from(i) * 0.5, 0.0, 0.0)).collect();
        let mut sets = vec![("cube", cube), ("plane", plane), ("grid", grid), ("copies", copies), ("line", line)];
        for n in [0, 1, LEAF_SIZE, LEAF_SIZE + 1, 3 * LEAF_SIZE + 2] {
            sets.push(("small", uniform(n)));
        }
        sets
    }

    /// Random queries (inside, outside and on the points), with k from 1 to past the point count
    /// and limits from none to tiny: the tree's answer equals brute force exactly (indices,
    /// squared distances and order) on every point set.
    #[test]
    fn nearest_equals_brute_force_on_every_point_set() {
        let mut sampler = Sampler::new(11, 0, 0);
        for (name, points) in point_sets() {
            let tree = PointTree::new(&points);
            assert_eq!(tree.len(), points.len());
            for q in 0..60 {
                let query = match q % 3 {
                    0 => in_unit_cube(&mut sampler) * 20.0 - 5.0,
                    1 if !points.is_empty() => {
                        points[(sampler.uniform() * points.len() as f64) as usize % points.len()]
                    }
                    _ => in_unit_cube(&mut sampler),
                };
                let k = [1, 2, 7, 50, 600][q % 5];
                let limit = [f64::INFINITY, 1.0, 0.01, 0.0][q % 4];
                assert_eq!(
                    tree.nearest(query, k, limit),
                    brute_force(&points, query, k, limit),
                    "{name}, query {query}, k {k}, limit {limit}"
                );
            }
            // Every point, asked for all: each one, in brute force's order.
            let everything = tree.nearest(DVec3::splat(0.5), points.len() + 3, f64::INFINITY);
            assert_eq!(everything, brute_force(&points, DVec3::splat(0.5), points.len(), f64::INFINITY), "{name}");
        }
    }

    /// The input order and the thread count do not change an answer: the same points reversed
    /// give the same neighbours (by position: no two of these random points lie at equal distance
    /// from a query, so index order never decides), and building on one thread gives the same
    /// arrays as on two (50 000 points: the build splits its top ranges in parallel).
    #[test]
    fn the_tree_does_not_depend_on_input_order_or_threads() {
        let mut sampler = Sampler::new(3, 0, 0);
        let points: Vec<DVec3> = (0..50_000).map(|_| in_unit_cube(&mut sampler)).collect();
        let on_threads = |threads| {
            rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| PointTree::new(&points))
        };
        let (tree, serial) = (on_threads(2), on_threads(1));
        assert_eq!((&tree.points, &tree.indices, &tree.axes), (&serial.points, &serial.indices, &serial.axes));
        let reversed: Vec<DVec3> = points.iter().rev().copied().collect();
        let other = PointTree::new(&reversed);
        for q in 0..50 {
            let query = DVec3::new(sampler.uniform(), sampler.uniform(), f64::from(q) / 50.0);
            let position = |tree_points: &[DVec3], found: Vec<Neighbour>| -> Vec<(DVec3, f64)> {
                found.into_iter().map(|n| (tree_points[n.index as usize], n.distance_squared)).collect()
            };
            assert_eq!(
                position(&points, tree.nearest(query, 50, f64::INFINITY)),
                position(&reversed, other.nearest(query, 50, f64::INFINITY))
            );
        }
    }

    /// Hard inputs: no points, k = 0, a NaN or infinite query, a NaN limit, huge and tiny
    /// coordinates (squared distances overflow to ∞ or underflow to 0 and still sort), points
    /// all at one place.
    #[test]
    fn hard_inputs_give_an_answer_or_nothing_never_a_panic() {
        let empty = PointTree::new(&[]);
        assert!(empty.is_empty() && empty.nearest(DVec3::ZERO, 5, f64::INFINITY).is_empty());
        let points: Vec<DVec3> =
            (0..100).map(|i| DVec3::new(f64::from(i) * 1e300, f64::from(i) * 1e-300, 0.0)).collect();
        let tree = PointTree::new(&points);
        assert!(tree.nearest(DVec3::ZERO, 0, f64::INFINITY).is_empty());
        assert_eq!(
            tree.nearest(DVec3::ZERO, usize::MAX, f64::INFINITY),
            brute_force(&points, DVec3::ZERO, 100, f64::INFINITY)
        );
        assert!(tree.nearest(DVec3::NAN, 5, f64::INFINITY).is_empty());
        assert!(tree.nearest(DVec3::ZERO, 5, f64::NAN).is_empty());
        // Squared distances that overflow to ∞ (from 5e301, and from a query at infinity) or
        // underflow to 0 (the 1e-300 offsets) still sort, by index among equals.
        for query in [DVec3::ZERO, DVec3::new(5e301, 0.0, 0.0), DVec3::new(0.0, 3e-299, 0.0), DVec3::INFINITY] {
            assert_eq!(tree.nearest(query, 7, f64::INFINITY), brute_force(&points, query, 7, f64::INFINITY), "{query}");
        }
        // A point at infinity and a query there: ∞ − ∞ is NaN, so that point is never found.
        let far = PointTree::new(&[DVec3::ZERO, DVec3::INFINITY]);
        assert_eq!(
            far.nearest(DVec3::INFINITY, 2, f64::INFINITY),
            [Neighbour { index: 0, distance_squared: f64::INFINITY }]
        );
        // Half the points at x = +∞: the root's median is one of them, so the split's offset is
        // ∞ − ∞ = NaN for a query at x = +∞, and the far side (every finite point, each at
        // distance ∞) must still be searched.
        let half: Vec<DVec3> = (0..200)
            .map(|i| DVec3::new(if i % 2 == 0 { f64::INFINITY } else { f64::from(i) }, f64::from(i), 0.0))
            .collect();
        let query = DVec3::new(f64::INFINITY, 3.0, 0.0);
        let found = PointTree::new(&half).nearest(query, 7, f64::INFINITY);
        assert_eq!(found, brute_force(&half, query, 7, f64::INFINITY));
        assert_eq!(found.iter().map(|n| n.index).collect::<Vec<_>>(), [1, 3, 5, 7, 9, 11, 13]);
        let same = PointTree::new(&vec![DVec3::ONE; 1000]);
        let found = same.nearest(DVec3::ONE, 1000, 0.0);
        assert_eq!(found.iter().map(|n| n.index).collect::<Vec<_>>(), (0..1000).collect::<Vec<u32>>());
    }

    /// The walk prunes: among 10⁵ points spread evenly over the unit sphere, 1000 random queries on
    /// it compute on average 199.1 squared distances for the 50 nearest and 25.2 for the nearest
    /// one (the renderer's engineering notes quote the first), not 10⁵; the bands allow a tenth
    /// either way.
    #[test]
    fn the_walk_measures_a_few_hundred_distances_not_every_point() {
        let points = fibonacci_sphere(100_000);
        let tree = PointTree::new(&points);
        let mut sampler = Sampler::new(5, 0, 0);
        let queries: Vec<DVec3> = (0..1000).map(|_| uniform_sphere(sampler.uniform(), sampler.uniform())).collect();
        let mean_offers =
            |k| queries.iter().map(|&q| tree.candidates(q, k, f64::INFINITY).offers).sum::<usize>() as f64 / 1000.0;
        let (fifty, one) = (mean_offers(50), mean_offers(1));
        assert!((180.0..=220.0).contains(&fifty), "k = 50: {fifty} distances per query");
        assert!((20.0..=30.0).contains(&one), "k = 1: {one} distances per query");
    }

    #[test]
    #[should_panic = "must not be NaN"]
    fn a_nan_point_is_refused() {
        let _ = PointTree::new(&[DVec3::ZERO, DVec3::new(0.0, f64::NAN, 0.0)]);
    }
}
