//! The quads of a scene, prepared for ray queries: each quad's plane normal, the tolerance of its
//! parallel-ray test and the dual basis of its edges are computed once when the scene is built,
//! and a ray meets the plane first, so a quad whose plane lies beyond the closest hit found so far
//! is rejected before its edge coordinates are computed (plane-first rejection).
//!
//! Every number is the one [`super::intersect`] computes for the same quad, in the same order of
//! operations, so a query through the set returns the brute-force `t` bit for bit.

use super::{Object, Shape};
use crate::geometry::Ray;
use glam::DVec3;

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
    fn plane_t(&self, ray: &Ray<f64>, dir_length: f64) -> Option<f64> {
        let denominator = ray.dir.dot(self.normal);
        if denominator.is_nan() || denominator.abs() <= self.parallel_tolerance * dir_length {
            return None;
        }
        let t = (self.corner - ray.origin).dot(self.normal) / denominator;
        (!t.is_nan() && t > 0.0).then_some(t)
    }

    /// Whether the plane point at `t` lies inside the parallelogram (the second half).
    fn contains(&self, ray: &Ray<f64>, t: f64) -> bool {
        let offset = ray.at(t) - self.corner;
        let a = offset.cross(self.edge_v).dot(self.dual);
        let b = self.edge_u.cross(offset).dot(self.dual);
        (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)
    }

    /// The hit `t ∈ (0, limit]`, or `None`; a plane beyond `limit` costs no edge test.
    fn hit_within(&self, ray: &Ray<f64>, dir_length: f64, limit: f64) -> Option<f64> {
        self.plane_t(ray, dir_length).filter(|&t| t <= limit && self.contains(ray, t))
    }
}

/// The quads of a scene in object order, prepared for closest-hit and any-hit queries.
#[derive(Debug, Clone, Default)]
pub(super) struct QuadSet {
    quads: Vec<PreparedQuad>,
}

impl QuadSet {
    /// The quads among `objects`, in increasing object index.
    pub(super) fn new(objects: &[Object]) -> Self {
        let quads = objects
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
        Self { quads }
    }

    /// Lowers `best` (the closest `(t, object)` so far, `t < t_max`) to every quad hit that
    /// beats it by [`offer`]'s rule; a quad whose plane lies beyond `best` costs no edge test.
    pub(super) fn closest(&self, ray: &Ray<f64>, t_max: f64, best: &mut Option<(f64, usize)>) {
        let dir_length = ray.dir.length();
        for quad in &self.quads {
            let hit = match *best {
                Some((limit, _)) => quad.hit_within(ray, dir_length, limit),
                None => quad.hit_within(ray, dir_length, t_max).filter(|&t| t < t_max),
            };
            if let Some(t) = hit {
                offer(best, quad.object, t);
            }
        }
    }

    /// Whether some quad is hit with `t ∈ (0, t_max)`; stops at the first one found.
    pub(super) fn any_before(&self, ray: &Ray<f64>, t_max: f64) -> bool {
        let dir_length = ray.dir.length();
        self.quads.iter().any(|quad| quad.hit_within(ray, dir_length, t_max).is_some_and(|t| t < t_max))
    }

    /// How many quads are hit with `t ∈ (0, t_max)`.
    pub(super) fn count_before(&self, ray: &Ray<f64>, t_max: f64) -> usize {
        let dir_length = ray.dir.length();
        self.quads.iter().filter(|quad| quad.hit_within(ray, dir_length, t_max).is_some_and(|t| t < t_max)).count()
    }
}

/// Makes `(t, object)` the closest hit when it is nearer than `best`, or as near with a lower
/// object index (the tie rule of every closest-hit query).
pub(super) fn offer(best: &mut Option<(f64, usize)>, object: usize, t: f64) {
    if best.is_none_or(|(u, j)| t < u || (t == u && object < j)) {
        *best = Some((t, object));
    }
}

#[cfg(test)]
mod tests {
    use crate::geometry::Ray;
    use crate::render::catalogue;
    use crate::render::scene::{Material, Object, Scene};
    use glam::DVec3;

    /// Plane-first rejection changes no answer: on the Cornell box (quads and spheres) with a
    /// quad duplicated bit for bit and one sharing an edge (exact ties, decided by object index),
    /// every query equals the brute-force loop's over rays from inside and outside the box.
    #[test]
    fn prepared_quads_answer_every_query_as_the_brute_force_loop() {
        let cornell = catalogue::cornell_mirror().unwrap();
        let mut objects = cornell.objects().to_vec();
        let grey = Material::Diffuse { albedo: DVec3::splat(0.5) };
        let panel = Object::quad(DVec3::new(-0.5, -0.5, -0.5), DVec3::X, DVec3::Y, grey);
        let neighbour = Object::quad(DVec3::new(0.5, -0.5, -0.5), DVec3::X, DVec3::Y, grey);
        objects.extend([panel, neighbour, panel]);
        let scene = Scene::new(*cornell.camera(), objects, vec![], None, DVec3::ZERO).unwrap();
        let brute = scene.without_kd_tree();
        let mut rng = crate::rng::seeded(5, 0);
        let mut coordinate = |half: f64| crate::rng::uniform_in(&mut rng, -half, half);
        let (mut hits, mut ties) = (0, 0);
        for case in 0..4000 {
            let half = if case % 2 == 0 { 1.0 } else { 4.0 };
            let origin = DVec3::new(coordinate(half), coordinate(half), coordinate(half) + 2.0);
            let target = if case % 4 == 1 {
                DVec3::new(0.5, coordinate(0.5), -0.5) // the shared edge and the duplicate
            } else {
                DVec3::new(coordinate(1.5), coordinate(1.5), coordinate(1.5))
            };
            let Ok(ray) = Ray::<f64>::new(origin, (target - origin).normalize()) else { continue };
            let t_max = if case % 3 == 0 { 2.0 } else { f64::INFINITY };
            let hit = scene.closest_hit(&ray, 0.0, t_max);
            assert_eq!(hit, brute.closest_hit(&ray, 0.0, t_max), "ray {case}");
            assert_eq!(scene.occluded(&ray, 0.0, t_max), brute.occluded(&ray, 0.0, t_max), "ray {case}");
            assert_eq!(scene.objects_pierced(&ray, 0.0, t_max), brute.objects_pierced(&ray, 0.0, t_max), "ray {case}");
            hits += usize::from(hit.is_some());
            ties += usize::from(hit.is_some_and(|h| h.object == cornell.objects().len()));
        }
        assert!(hits > 2000 && ties > 10, "the rays hit the box and the tied panels: {hits} hits, {ties} ties");
    }
}
