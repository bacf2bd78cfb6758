//! The `f32` kd-tree: the `f64` tree's nodes with its leaves' spheres narrowed to `f32`, four to a
//! cache line, traversed in `f32`. Half the bytes per sphere and four sphere tests per instruction
//! stream, for an accuracy cost the Q3 benchmark measures (rays on which it names another sphere
//! than the `f64` tree).

use super::KdTree;
use super::node::{Aabb, Node, NodeKind};
use super::prefetch::prefetch;
use super::stack::FarStack;
use glam::Vec3;
use hw3_core::geometry::sphere::roots_stable;
use hw3_core::geometry::{Ray, Sphere};

/// Four leaf spheres side by side (structure of arrays, 64 bytes: one cache line). A lane past the
/// end of its leaf holds NaN, which every test rejects.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
struct SphereQuad {
    x: [f32; 4],
    y: [f32; 4],
    z: [f32; 4],
    radius: [f32; 4],
}

/// A kd-tree over spheres in `f32`: the same nodes as the [`KdTree`] it is made from, with every
/// sphere (centre and radius) rounded to the nearest `f32` and every query evaluated in `f32`.
///
/// Why it exists: Embree and the benchmark's other peers trace in `f32`, and a sphere that takes
/// half the bytes takes half the memory traffic on scenes that outgrow the cache. What it costs:
/// a ray may name a different sphere than the `f64` tree where two hits lie within `f32` rounding
/// of each other, or graze a sphere (the Q3 benchmark counts such rays per million). It is not used
/// by the renderer, which needs the exact [`KdTree`].
///
/// # Examples
/// ```
/// use glam::{DVec3, Vec3};
/// use hw3_core::geometry::Sphere;
/// use hw3_render::kdtree::{KdTree, KdTreeF32};
/// let spheres = [Sphere::new(DVec3::new(0.0, 0.0, 5.0), 1.0).unwrap()];
/// let tree = KdTreeF32::from_tree(&KdTree::build(&spheres).unwrap());
/// assert_eq!(tree.closest_hit(Vec3::ZERO, Vec3::Z, 0.0, f32::INFINITY), Some((0, 4.0)));
/// ```
#[derive(Debug, Clone)]
pub struct KdTreeF32 {
    /// The `f64` tree's nodes; a leaf's `first` indexes [`KdTreeF32::quads`].
    nodes: Vec<Node>,
    quads: Vec<SphereQuad>,
    /// The input index of each lane of [`KdTreeF32::quads`].
    ids: Vec<[u32; 4]>,
    /// The `f64` tree's bounds, rounded outwards.
    bounds: ([f32; 3], [f32; 3]),
}

impl KdTreeF32 {
    /// The `f32` tree of `tree`: its nodes and leaf lists, spheres rounded to nearest. A moving
    /// tree's spheres are taken at time 0 (its swept boxes still hold them).
    ///
    /// # Panics
    /// Never (the `f64` tree's limits bound every count).
    #[must_use]
    pub fn from_tree(tree: &KdTree) -> Self {
        let mut nodes = Vec::with_capacity(tree.nodes.len());
        let mut quads = Vec::new();
        let mut ids = Vec::new();
        for &node in &tree.nodes {
            let NodeKind::Leaf { first, count } = node.kind() else {
                nodes.push(node);
                continue;
            };
            let quad_first = u32::try_from(quads.len()).expect("quad count fits u32");
            let spheres: Vec<(Sphere<f64>, u32)> = tree.leaf_spheres(first, count).collect();
            for chunk in spheres.chunks(4) {
                let mut quad =
                    SphereQuad { x: [f32::NAN; 4], y: [f32::NAN; 4], z: [f32::NAN; 4], radius: [f32::NAN; 4] };
                let mut lane_ids = [u32::MAX; 4];
                for (lane, (sphere, index)) in chunk.iter().enumerate() {
                    let c = sphere.center.as_vec3();
                    (quad.x[lane], quad.y[lane], quad.z[lane]) = (c.x, c.y, c.z);
                    quad.radius[lane] = sphere.radius as f32;
                    lane_ids[lane] = *index;
                }
                quads.push(quad);
                ids.push(lane_ids);
            }
            nodes.push(Node::leaf(quad_first, count));
        }
        Self { nodes, quads, ids, bounds: outward(&tree.bounds) }
    }

    /// The closest sphere hit with `t` strictly inside `(t_min, t_max)`, all in `f32`: its index in
    /// the slice the tree was built from and its `t`, or `None`; ties in `t` go to the lowest index.
    ///
    /// Preconditions: finite `origin`, finite non-zero `dir`; `t_min < t_max` (otherwise, or if
    /// either is NaN, `None`).
    /// Numerics: the interval rule of [`super::split_interval`] with `t = (s − e_a)·(1/d_a)` in
    /// `f32`, and the crate's stable solver [`roots_stable`] in `f32`; each sphere is first rejected
    /// with exactly the solver's own discriminant test, four at a time.
    ///
    /// # Examples
    /// ```
    /// use glam::{DVec3, Vec3};
    /// use hw3_core::geometry::Sphere;
    /// use hw3_render::kdtree::{KdTree, KdTreeF32};
    /// let ball = [Sphere::new(DVec3::ZERO, 1.0).unwrap()];
    /// let tree = KdTreeF32::from_tree(&KdTree::build(&ball).unwrap());
    /// let down = Vec3::new(-0.0, -0.0, 1.0);
    /// assert_eq!(tree.closest_hit(Vec3::new(0.0, 0.0, -5.0), down, 0.0, f32::INFINITY), Some((0, 4.0)));
    /// assert_eq!(tree.closest_hit(Vec3::new(0.0, 0.0, -5.0), down, 0.0, 3.0), None);
    /// ```
    #[must_use]
    pub fn closest_hit(&self, origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> Option<(usize, f32)> {
        if !(t_min < t_max) {
            return None;
        }
        let o = origin.to_array();
        let d = dir.to_array();
        let inv = d.map(|x| 1.0 / x);
        let (mut cell_min, mut cell_max) = clip(self.bounds, o, d, t_min, t_max)?;
        let ray = Ray { origin, dir };
        let a = dir.dot(dir);
        let mut best: Option<(usize, f32)> = None;
        let mut stack = FarStack::new();
        let mut node = 0u32;
        loop {
            match self.nodes[node as usize].kind() {
                NodeKind::Interior { split, upper, axis } => {
                    prefetch(&self.nodes, upper);
                    let split = split as f32;
                    if inv[axis].is_infinite() {
                        // Parallel (±0 or subnormal): the origin's side, no product 0·∞.
                        node = if o[axis] < split { node + 1 } else { upper };
                        continue;
                    }
                    let t_plane = (split - o[axis]) * inv[axis];
                    let (near, far) = if inv[axis] > 0.0 { (node + 1, upper) } else { (upper, node + 1) };
                    let (near_live, far_live) = (t_plane > cell_min, t_plane < cell_max);
                    if near_live & far_live {
                        stack.push((far, t_plane, cell_max));
                        cell_max = t_plane;
                        node = near;
                    } else if near_live {
                        node = near;
                    } else {
                        node = far;
                    }
                    continue;
                }
                NodeKind::Leaf { first, count } => {
                    let quads = first as usize..first as usize + count.div_ceil(4) as usize;
                    for (quad, lane_ids) in self.quads[quads.clone()].iter().zip(&self.ids[quads]) {
                        let live = quad_candidates(quad, o, d, a);
                        if live == 0 {
                            continue;
                        }
                        for (lane, &id) in lane_ids.iter().enumerate() {
                            if live & (1 << lane) == 0 {
                                continue;
                            }
                            let sphere = Sphere {
                                center: Vec3::new(quad.x[lane], quad.y[lane], quad.z[lane]),
                                radius: quad.radius[lane],
                            };
                            let Some(t) = roots_stable(&ray, &sphere).and_then(|r| r.first_in(t_min, t_max)) else {
                                continue;
                            };
                            let i = id as usize;
                            if best.is_none_or(|(j, u)| t < u || (t == u && i < j)) {
                                best = Some((i, t));
                            }
                        }
                    }
                }
            }
            let best_t = best.map_or(f32::INFINITY, |(_, t)| t);
            match stack.pop() {
                Some(far) if !(far.1 > best_t) => (node, cell_min, cell_max) = far,
                _ => return best,
            }
        }
    }
}

/// The lanes of `quad` whose discriminant [`roots_stable`] would find non-negative, as a bit mask:
/// the solver's own expressions (`|f × d|²` against `r² d·d`), evaluated lane by lane in the same
/// order, so a rejected lane is one the solver rejects.
#[inline]
fn quad_candidates(quad: &SphereQuad, o: [f32; 3], d: [f32; 3], a: f32) -> u32 {
    let mut disc = [0.0f32; 4];
    for (lane, disc) in disc.iter_mut().enumerate() {
        let f = [o[0] - quad.x[lane], o[1] - quad.y[lane], o[2] - quad.z[lane]];
        let p = [f[1] * d[2] - f[2] * d[1], f[2] * d[0] - f[0] * d[2], f[0] * d[1] - f[1] * d[0]];
        let r = quad.radius[lane];
        *disc = r * r * a - (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    }
    disc.iter().enumerate().fold(0, |mask, (lane, &x)| mask | (u32::from(x >= 0.0) << lane))
}

/// `bounds` rounded outwards to `f32`, so that no sphere the `f64` box holds is clipped away.
fn outward(bounds: &Aabb) -> ([f32; 3], [f32; 3]) {
    let down = |x: f64| {
        let y = x as f32;
        if f64::from(y) > x { y.next_down() } else { y }
    };
    let up = |x: f64| {
        let y = x as f32;
        if f64::from(y) < x { y.next_up() } else { y }
    };
    (bounds.min.to_array().map(down), bounds.max.to_array().map(up))
}

/// The part of `[t_min, t_max]` where the ray is inside the closed box (the `f64` tree's clip, in
/// `f32`), or `None`.
fn clip(bounds: ([f32; 3], [f32; 3]), o: [f32; 3], d: [f32; 3], t_min: f32, t_max: f32) -> Option<(f32, f32)> {
    let (mut t0, mut t1) = (t_min, t_max);
    for a in 0..3 {
        let (lo, hi) = (bounds.0[a], bounds.1[a]);
        if d[a] == 0.0 {
            if !(lo <= o[a] && o[a] <= hi) {
                return None;
            }
            continue;
        }
        let (t_lo, t_hi) = ((lo - o[a]) / d[a], (hi - o[a]) / d[a]);
        t0 = t0.max(t_lo.min(t_hi));
        t1 = t1.min(t_lo.max(t_hi));
    }
    (t0 <= t1).then_some((t0, t1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kdtree::brute_force_closest_hit;
    use glam::DVec3;
    use hw3_core::rng::{seeded, uniform_in as uniform};

    /// Spheres and rays exactly representable in `f32` (coordinates on a 2⁻¹⁰ grid): the `f32`
    /// tree names the same sphere as `f64` brute force on all but the rays where two hits lie
    /// within `f32` rounding, which must stay rare (under 1 in 2 000 here).
    #[test]
    fn f32_tree_agrees_with_f64_brute_force_on_nearly_every_ray() {
        let mut rng = seeded(0x4b45, 0);
        let grid = |x: f64| (x * 1024.0).round() / 1024.0;
        let (mut rays, mut differ, mut hits) = (0, 0, 0);
        for scene_index in 0..20 {
            let n = 1 + scene_index * 50;
            let spheres: Vec<_> = (0..n)
                .map(|_| {
                    let c = DVec3::new(
                        uniform(&mut rng, 0.0, 1.0),
                        uniform(&mut rng, 0.0, 1.0),
                        uniform(&mut rng, 0.0, 1.0),
                    );
                    Sphere::new(c.to_array().map(grid).into(), grid(uniform(&mut rng, 0.01, 0.1)).max(1.0 / 1024.0))
                        .unwrap()
                })
                .collect();
            let tree64 = KdTree::build(&spheres).unwrap();
            let tree = KdTreeF32::from_tree(&tree64);
            for _ in 0..1_000 {
                let o = DVec3::new(
                    uniform(&mut rng, -0.5, 1.5),
                    uniform(&mut rng, -0.5, 1.5),
                    uniform(&mut rng, -0.5, 1.5),
                );
                let target =
                    DVec3::new(uniform(&mut rng, 0.0, 1.0), uniform(&mut rng, 0.0, 1.0), uniform(&mut rng, 0.0, 1.0));
                let d = (target - o).normalize().as_vec3();
                let (o, d64) = (o.as_vec3(), d.as_dvec3());
                let ray = Ray::new(o.as_dvec3(), d64).unwrap();
                let expected = brute_force_closest_hit(&spheres, &ray, 0.0, f64::INFINITY).map(|h| h.0);
                let got = tree.closest_hit(o, d, 0.0, f32::INFINITY).map(|h| h.0);
                rays += 1;
                differ += usize::from(expected != got);
                hits += usize::from(expected.is_some());
            }
        }
        assert!(hits > 5_000, "the test exercises hits, got {hits}");
        assert!(differ * 2_000 < rays, "{differ} of {rays} rays differ");
    }

    #[test]
    fn parallel_and_negative_zero_directions_hit() {
        let spheres: Vec<_> = (0..64)
            .map(|i| {
                let c = DVec3::new(f64::from(i % 4), f64::from((i / 4) % 4), f64::from(i / 16));
                Sphere::new(c * 0.25, 0.1).unwrap()
            })
            .collect();
        let tree = KdTreeF32::from_tree(&KdTree::build(&spheres).unwrap());
        for sign in [1.0, -1.0] {
            let (o, d) = (Vec3::new(0.5, 0.5, 2.0), Vec3::new(0.0 * sign, 0.0 * sign, -1.0));
            let ray = Ray::new(o.as_dvec3(), d.as_dvec3()).unwrap();
            let expected = brute_force_closest_hit(&spheres, &ray, 0.0, f64::INFINITY).map(|h| h.0);
            assert!(expected.is_some());
            assert_eq!(tree.closest_hit(o, d, 0.0, f32::INFINITY).map(|h| h.0), expected);
        }
        assert_eq!(tree.closest_hit(Vec3::ZERO, Vec3::Z, 1.0, 1.0), None);
        let empty = KdTreeF32::from_tree(&KdTree::build(&[]).unwrap());
        assert_eq!(empty.closest_hit(Vec3::ZERO, Vec3::X, 0.0, f32::INFINITY), None);
    }
}
