//! The peers of the crate's kd-tree, measured in the same run on the same rays: the `bvh` crate
//! (0.13, svenstaro) and `obvhs` (0.4: BVH2 and CWBVH). Both need an `f32` scene; the benchmark's
//! scenes and rays are generated in `f32` and widened exactly, so narrowing them back is exact.
//!
//! Every peer answers with the same `f32` ray/sphere test ([`sphere_t`], the benchmark's
//! `r² − |oc − b d|²` form), so the peers differ only in their acceleration structure.
//!
//! The `bvh` crate has no pruned closest-hit query (its ray APIs yield AABB candidates), so it is
//! driven here through its best public API for this job: its public node array
//! (`Bvh::nodes`, inner nodes carry both child boxes) walked by a front-to-back stack loop that
//! skips any child box entered beyond the best hit so far (the note measured this 1.05–1.6× faster
//! than `nearest_traverse_iterator` with early exit).

use bvh::aabb::{Aabb as BvhAabb, Bounded};
use bvh::bounding_hierarchy::BHShape;
use bvh::bvh::{Bvh, BvhNode};
// Every `f32` vector here is hw3's glam `Vec3A`; obvhs's (whichever glam it resolves to) is met
// through arrays, `to_array()` and `.into()`, which compile to plain moves of the same layout.
use glam::Vec3A;
use hw3::geometry::{Ray, Sphere};
use nalgebra::Point3;
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb as ObvhsAabb;
use obvhs::bvh2::Bvh2;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray as ObvhsRay, RayHit};
use std::time::Duration;

/// A sphere in `f32`, as the peers need it.
#[derive(Debug, Clone, Copy)]
pub struct SphereF32 {
    center: Vec3A,
    radius: f32,
    /// The `bvh` crate's back-reference to the node that holds this shape.
    bvh_node: usize,
}

/// A ray in `f32` (unit direction) with its component-wise reciprocal for slab tests.
#[derive(Debug, Clone, Copy)]
pub struct RayF32 {
    pub origin: Vec3A,
    pub dir: Vec3A,
    inv_dir: Vec3A,
}

/// The narrowing is exact for the benchmark's workload (generated in `f32`, widened to `f64`).
pub fn spheres_f32(spheres: &[Sphere<f64>]) -> Vec<SphereF32> {
    spheres.iter().map(|s| SphereF32 { center: narrow(s.center), radius: s.radius as f32, bvh_node: 0 }).collect()
}

/// As [`spheres_f32`], for rays. `1/±0 = ±∞` keeps the sign of a zero component.
pub fn rays_f32(rays: &[Ray<f64>]) -> Vec<RayF32> {
    rays.iter()
        .map(|r| {
            let dir = narrow(r.dir);
            RayF32 { origin: narrow(r.origin), dir, inv_dir: dir.recip() }
        })
        .collect()
}

/// A `DVec3` as a `Vec3A`, each component rounded to `f32`.
fn narrow(v: glam::DVec3) -> Vec3A {
    Vec3A::from_array(v.as_vec3().to_array())
}

/// The smallest root of the unit-direction ray/sphere equation in `(t_min, t_max)`, else `+∞`.
/// The discriminant is `r² − |oc − (oc·d) d|²`, which keeps its precision for distant spheres.
#[inline]
fn sphere_t(sphere: &SphereF32, origin: Vec3A, dir: Vec3A, t_min: f32, t_max: f32) -> f32 {
    let oc = origin - sphere.center;
    let b = oc.dot(dir);
    let off_axis = oc - b * dir;
    let h = sphere.radius * sphere.radius - off_axis.length_squared();
    if h < 0.0 {
        return f32::INFINITY;
    }
    let h = h.sqrt();
    for t in [-b - h, -b + h] {
        if t > t_min && t < t_max {
            return t;
        }
    }
    f32::INFINITY
}

/// A closest-hit answer of a peer: sphere index and `t`.
pub type HitF32 = Option<(usize, f32)>;

/// The structures measured. Each is built from the same `f32` spheres.
pub enum Peer {
    /// Embree 3 (system library, `embree` feature): native sphere points, `rtcIntersect1`, one
    /// thread. Its ray/sphere test is its own, not [`sphere_t`].
    #[cfg(feature = "embree")]
    Embree(crate::embree::Embree),
    /// `bvh` 0.13 (binary SAH BVH, one shape per leaf), own front-to-back loop over its nodes.
    BvhCrate(Bvh<f32, 3>),
    /// `obvhs` 0.4 BVH2 (PLOC + reinsertion + leaf collapse), `medium_build` preset.
    ObvhsBvh2(Bvh2),
    /// `obvhs` 0.4 CWBVH (8-wide compressed), `medium_build` preset.
    ObvhsCwbvh(CwBvh),
}

/// The peers' names, in [`Peer::build`] order (also the CSV column prefixes). Embree is last and
/// present only with the `embree` feature; its CSV columns are written either way (`-` without it).
#[cfg(not(feature = "embree"))]
pub const NAMES: &[&str] = &["bvh", "obvhs_bvh2", "obvhs_cwbvh"];
/// As above, with Embree.
#[cfg(feature = "embree")]
pub const NAMES: &[&str] = &["bvh", "obvhs_bvh2", "obvhs_cwbvh", EMBREE];

/// Embree's scene, for the batch calls.
#[cfg(feature = "embree")]
pub use crate::embree::Embree;

/// Without the `embree` feature there is no Embree scene: an uninhabited stand-in with the same
/// calls, so that the batch rounds compile either way.
#[cfg(not(feature = "embree"))]
pub enum Embree {}

#[cfg(not(feature = "embree"))]
impl Embree {
    pub fn closest_hit(&self, _: [f32; 3], _: [f32; 3], _: f32, _: bool) -> HitF32 {
        match *self {}
    }
    pub fn closest_hits_stream(&self, _: &[([f32; 3], [f32; 3])], _: f32, _: bool) -> Vec<HitF32> {
        match *self {}
    }
    pub fn closest_hits_packet8(&self, _: &[([f32; 3], [f32; 3])], _: f32, _: bool) -> Vec<HitF32> {
        match *self {}
    }
}

/// The name (and CSV column prefix) of the Embree peer.
pub const EMBREE: &str = "embree3";

impl Peer {
    /// Builds the peer `index` of [`NAMES`] (single thread: `bvh`'s serial `build`, `obvhs`
    /// without its `parallel` feature).
    pub fn build(index: usize, spheres: &mut [SphereF32]) -> Self {
        let params = BvhBuildParams::medium_build();
        let mut core_time = Duration::ZERO;
        match index {
            0 => Self::BvhCrate(Bvh::build(spheres)),
            1 => Self::ObvhsBvh2(obvhs::bvh2::builder::build_bvh2(spheres, params, &mut core_time)),
            2 => Self::ObvhsCwbvh(obvhs::cwbvh::builder::build_cwbvh(spheres, params, &mut core_time)),
            #[cfg(feature = "embree")]
            3 => Self::Embree(crate::embree::Embree::new(
                &spheres.iter().map(|s| [s.center.x, s.center.y, s.center.z, s.radius]).collect::<Vec<_>>(),
            )),
            _ => unreachable!("peer index {index} out of range"),
        }
    }

    /// The Embree scene, if this peer is Embree.
    pub fn embree(&self) -> Option<&Embree> {
        match self {
            #[cfg(feature = "embree")]
            Self::Embree(scene) => Some(scene),
            _ => None,
        }
    }

    /// The closest hit in `(t_min, ∞)`; `coherent` tells a peer that takes the hint (Embree) that
    /// the rays come from a camera.
    pub fn closest_hit(&self, spheres: &[SphereF32], ray: &RayF32, t_min: f32, coherent: bool) -> HitF32 {
        let _ = coherent;
        match self {
            #[cfg(feature = "embree")]
            Self::Embree(scene) => scene.closest_hit(ray.origin.into(), ray.dir.into(), t_min, coherent),
            Self::BvhCrate(bvh) => bvh_closest_hit(bvh, spheres, ray, t_min),
            Self::ObvhsBvh2(bvh) => {
                let mut hit = RayHit::none();
                let found =
                    bvh.ray_traverse(obvhs_ray(ray, t_min), &mut hit, obvhs_test(spheres, &bvh.primitive_indices));
                obvhs_answer(found, &hit, &bvh.primitive_indices)
            }
            Self::ObvhsCwbvh(bvh) => {
                let mut hit = RayHit::none();
                let found =
                    bvh.ray_traverse(obvhs_ray(ray, t_min), &mut hit, obvhs_test(spheres, &bvh.primitive_indices));
                obvhs_answer(found, &hit, &bvh.primitive_indices)
            }
        }
    }
}

fn obvhs_ray(ray: &RayF32, t_min: f32) -> ObvhsRay {
    ObvhsRay::new(ray.origin.to_array().into(), ray.dir.to_array().into(), t_min, f32::INFINITY)
}

/// `obvhs` hands the intersection callback an index into its `primitive_indices` (its builders
/// reorder primitives); the callback maps it back to the input sphere.
fn obvhs_test<'a>(spheres: &'a [SphereF32], order: &'a [u32]) -> impl FnMut(&ObvhsRay, usize) -> f32 + 'a {
    move |r, id| {
        let (origin, dir) = (Vec3A::from_array(r.origin.to_array()), Vec3A::from_array(r.direction.to_array()));
        sphere_t(&spheres[order[id] as usize], origin, dir, r.tmin, r.tmax)
    }
}

fn obvhs_answer(found: bool, hit: &RayHit, order: &[u32]) -> HitF32 {
    found.then(|| (order[hit.primitive_id as usize] as usize, hit.t))
}

/// Entry parameter of the ray into a `bvh` box over `[t_min, t_max]`, or `None`. A `0 · ∞ = NaN`
/// slab (origin on a face, parallel ray) is ignored by `max`/`min`, which return the other operand.
#[inline]
fn bvh_box_entry(b: &BvhAabb<f32, 3>, ray: &RayF32, t_min: f32, t_max: f32) -> Option<f32> {
    let lo = (Vec3A::new(b.min.x, b.min.y, b.min.z) - ray.origin) * ray.inv_dir;
    let hi = (Vec3A::new(b.max.x, b.max.y, b.max.z) - ray.origin) * ray.inv_dir;
    let (near, far) = (lo.min(hi), lo.max(hi));
    let t0 = t_min.max(near.x).max(near.y).max(near.z);
    let t1 = t_max.min(far.x).min(far.y).min(far.z);
    (t0 <= t1).then_some(t0)
}

/// Front-to-back walk of the `bvh` crate's node array: the nearer child box first, the farther one
/// on a stack with its entry parameter, popped only while it begins before the best hit.
fn bvh_closest_hit(bvh: &Bvh<f32, 3>, spheres: &[SphereF32], ray: &RayF32, t_min: f32) -> HitF32 {
    let mut best: HitF32 = None;
    let mut best_t = f32::INFINITY;
    let mut stack: Vec<(usize, f32)> = Vec::with_capacity(64);
    if bvh.nodes.is_empty() {
        return None;
    }
    stack.push((0, t_min));
    while let Some((index, entry)) = stack.pop() {
        if entry > best_t {
            continue;
        }
        match bvh.nodes[index] {
            BvhNode::Leaf { shape_index, .. } => {
                let t = sphere_t(&spheres[shape_index], ray.origin, ray.dir, t_min, best_t);
                if t < best_t {
                    (best, best_t) = (Some((shape_index, t)), t);
                }
            }
            BvhNode::Node { child_l_index, child_l_aabb, child_r_index, child_r_aabb, .. } => {
                let left = bvh_box_entry(&child_l_aabb, ray, t_min, best_t).map(|t| (child_l_index, t));
                let right = bvh_box_entry(&child_r_aabb, ray, t_min, best_t).map(|t| (child_r_index, t));
                match (left, right) {
                    (Some(l), Some(r)) => {
                        let (near, far) = if l.1 <= r.1 { (l, r) } else { (r, l) };
                        stack.push(far);
                        stack.push(near);
                    }
                    (Some(only), None) | (None, Some(only)) => stack.push(only),
                    (None, None) => {}
                }
            }
        }
    }
    best
}

impl Bounded<f32, 3> for SphereF32 {
    fn aabb(&self) -> BvhAabb<f32, 3> {
        let (lo, hi) = (self.center - self.radius, self.center + self.radius);
        BvhAabb::with_bounds(Point3::new(lo.x, lo.y, lo.z), Point3::new(hi.x, hi.y, hi.z))
    }
}

impl BHShape<f32, 3> for SphereF32 {
    fn set_bh_node_index(&mut self, index: usize) {
        self.bvh_node = index;
    }

    fn bh_node_index(&self) -> usize {
        self.bvh_node
    }
}

impl obvhs::Boundable for SphereF32 {
    fn aabb(&self) -> ObvhsAabb {
        ObvhsAabb::new((self.center - self.radius).to_array().into(), (self.center + self.radius).to_array().into())
    }
}
