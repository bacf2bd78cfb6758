//! The `f64` tree's first sphere test, in `f32` on half the bytes: a *conservative* rejection that
//! never turns away a sphere the exact `f64` test would keep, so that the tree's answers stay bit
//! for bit those of [`roots_stable`](crate::geometry::sphere::roots_stable).
//!
//! # Why
//! Under callgrind (N = 10⁵, fixed k, random rays) a random ray read about 20 leaf cache lines of
//! `f64` spheres and missed the 2 MB second-level cache on about 13 of them, against about 2
//! misses for its 61 node steps: the leaf spheres, not the nodes, waited on memory. Fewer than one
//! sphere per ray passes the discriminant test, so the test that rejects needs only enough
//! precision to reject safely, and the exact sphere is read only for the few it keeps.
//!
//! # The bound
//! The exact test keeps a sphere when `r² (d·d) − |f × d|² ≥ 0` in `f64` (`f = e − c`), i.e. when
//! the centre lies within about `r` of the ray's line. Here the same expression is evaluated in
//! `f32` on the ray and the centre rounded to nearest and the radius rounded up, and compared with
//! a radius widened by `τ = 2⁻¹⁸ M + 2⁻⁴⁰`, where `M` bounds every coordinate of the ray's origin
//! and of the tree's box. With the unit roundoff `u = 2⁻²⁴` of `f32` (Higham, *Accuracy and
//! Stability of Numerical Algorithms*, 2nd ed., §2.2), rounding the inputs moves `f` by at most
//! `4√3 u M` and the direction by `u |d|`, and the cross product's own roundings add at most
//! `8√3 u M |d|`, so the computed `|f × d|` lies within `25 u M |d|` of the exact one (the `f64`
//! test's own error is `2⁻²⁹` times smaller); `τ = 64 u M` covers that with room for the roundings
//! of the comparison itself, which a factor `1 + 2⁻¹⁸` on `d·d` covers. The absolute `2⁻⁴⁰`
//! covers gradual underflow. The bound needs `M ≤ 2²⁴` and every direction with
//! `2⁻²⁴ ≤ max |d_a| ≤ 2²⁴` (no `f32` overflow or flush of the direction); any other ray skips
//! the coarse test and tests every sphere exactly.
//!
//! The widening costs little: on the benchmark's unit cube `τ ≈ 2·10⁻⁶`, against radii of
//! `10⁻³` and more.

use crate::geometry::{Ray, Sphere};

/// A leaf sphere as the coarse test reads it: the centre rounded to the nearest `f32`, the radius
/// rounded up, 16 bytes (four to a cache line, a leaf's spheres side by side).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(16))]
pub(super) struct CoarseSphere {
    center: [f32; 3],
    radius: f32,
}

impl CoarseSphere {
    pub fn new(sphere: &Sphere<f64>) -> Self {
        let up = |x: f64| {
            let y = x as f32;
            if f64::from(y) < x { y.next_up() } else { y }
        };
        Self { center: sphere.center.to_array().map(|x| x as f32), radius: up(sphere.radius) }
    }
}

/// A ray prepared for the coarse test: rounded to `f32`, with the widening of the radius and the
/// scale on `d·d` that make the test conservative, or disabled where the bound does not hold.
#[derive(Debug, Clone, Copy)]
pub(super) struct CoarseRay {
    origin: [f32; 3],
    dir: [f32; 3],
    /// `d·d` in `f32`, times `1 + 2⁻¹⁸`.
    scaled_a: f32,
    /// `τ`, rounded up.
    widening: f32,
    /// False when the ray or the box is out of the bound's range: then every sphere is kept.
    enabled: bool,
}

/// The largest coordinate magnitude and the direction range for which the bound holds.
const MAX_COORDINATE: f64 = 16_777_216.0; // 2²⁴
const MIN_DIRECTION: f64 = 1.0 / 16_777_216.0; // 2⁻²⁴

impl CoarseRay {
    /// The coarse ray for `ray` in a tree whose box has corners `min` and `max`.
    pub fn new(ray: &Ray<f64>, min: [f64; 3], max: [f64; 3]) -> Self {
        let (o, d) = (ray.origin.to_array(), ray.dir.to_array());
        let magnitude = o.iter().chain(&min).chain(&max).fold(0.0f64, |m, x| m.max(x.abs()));
        let longest = d.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let enabled =
            magnitude <= MAX_COORDINATE && (MIN_DIRECTION..=MAX_COORDINATE).contains(&longest) && magnitude.is_finite();
        let origin = o.map(|x| x as f32);
        let dir = d.map(|x| x as f32);
        let a = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
        let widening = (magnitude * f64::from(2.0f32.powi(-18)) + f64::from(2.0f32.powi(-40))) as f32;
        Self { origin, dir, scaled_a: a * (1.0 + 2.0f32.powi(-18)), widening: widening.next_up(), enabled }
    }

    /// False only if the exact test rejects `sphere` too (see the module docs); always true for a
    /// disabled ray.
    #[inline]
    pub fn may_hit(&self, sphere: &CoarseSphere) -> bool {
        if !self.enabled {
            return true;
        }
        let (o, d, c) = (self.origin, self.dir, sphere.center);
        let f = [o[0] - c[0], o[1] - c[1], o[2] - c[2]];
        let p = [f[1] * d[2] - f[2] * d[1], f[2] * d[0] - f[0] * d[2], f[0] * d[1] - f[1] * d[0]];
        let s = sphere.radius + self.widening;
        p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= s * s * self.scaled_a
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sphere::roots_stable;
    use crate::rng::{seeded, uniform_in as uniform};
    use glam::DVec3;

    /// The exact test's acceptance: the stable solver finds real roots.
    fn exact_keeps(ray: &Ray<f64>, sphere: &Sphere<f64>) -> bool {
        roots_stable(ray, sphere).is_some()
    }

    /// Rays aimed to graze spheres (within 10⁻⁹ of tangent, relative, from both sides) at several
    /// scales and offsets: whenever the exact test keeps a sphere, the coarse test keeps it.
    #[test]
    fn coarse_test_never_rejects_a_sphere_the_exact_test_keeps() {
        let mut rng = seeded(0xC0A5, 0);
        let (mut kept, mut coarse_kept, mut cases) = (0, 0, 0);
        for &scale in &[1e-6, 1e-3, 1.0, 1e3, 1e6] {
            for &offset in &[0.0, 1.0, -7.5, 1e4] {
                for _ in 0..20_000 {
                    let c = DVec3::new(
                        uniform(&mut rng, -1.0, 1.0),
                        uniform(&mut rng, -1.0, 1.0),
                        uniform(&mut rng, -1.0, 1.0),
                    ) * scale
                        + DVec3::splat(offset * scale);
                    let r = scale * uniform(&mut rng, 1e-4, 0.3);
                    let sphere = Sphere::new(c, r).unwrap();
                    let o = c + DVec3::new(
                        uniform(&mut rng, -3.0, 3.0),
                        uniform(&mut rng, -3.0, 3.0),
                        uniform(&mut rng, -3.0, 3.0),
                    ) * scale;
                    // A direction whose line passes at distance r' = r·(1 + ε) from the centre, ε
                    // tiny: aimed at a point a distance s = r' t / √(t² − r'²) aside of the centre.
                    let to_c = c - o;
                    let (t, r_line) = (to_c.length(), r * (1.0 + uniform(&mut rng, -1e-9, 1e-9)));
                    if t < 1.01 * r_line {
                        continue;
                    }
                    let side = to_c.any_orthonormal_vector() * (r_line * t / (t * t - r_line * r_line).sqrt());
                    let length = uniform(&mut rng, 1e-3, 1e3);
                    let Ok(ray) = Ray::new(o, (to_c + side).normalize() * length) else {
                        continue;
                    };
                    let bounds = (c - DVec3::splat(r)).to_array();
                    let coarse = CoarseRay::new(&ray, bounds, (c + DVec3::splat(r)).to_array());
                    let exact = exact_keeps(&ray, &sphere);
                    let may = coarse.may_hit(&CoarseSphere::new(&sphere));
                    assert!(may || !exact, "coarse test rejects a kept sphere: {ray:?} {sphere:?}");
                    cases += 1;
                    kept += usize::from(exact);
                    coarse_kept += usize::from(may);
                }
            }
        }
        // The grazing cases really straddle the boundary, and the widening stays narrow: the
        // coarse test keeps almost only what the exact one keeps.
        assert!(kept > cases / 10 && kept < 9 * cases / 10, "{kept} of {cases} kept");
        assert!(coarse_kept < kept + cases / 5, "coarse keeps {coarse_kept}, exact {kept} of {cases}");
    }

    #[test]
    fn out_of_range_rays_keep_every_sphere() {
        let sphere = CoarseSphere::new(&Sphere::new(DVec3::ZERO, 1.0).unwrap());
        let far = Ray::new(DVec3::splat(1e30), DVec3::X).unwrap();
        assert!(CoarseRay::new(&far, [-1.0; 3], [1.0; 3]).may_hit(&sphere));
        let tiny = Ray::new(DVec3::new(0.0, 5.0, 0.0), DVec3::X * 1e-30).unwrap();
        assert!(CoarseRay::new(&tiny, [-1.0; 3], [1.0; 3]).may_hit(&sphere));
        let miss = Ray::new(DVec3::new(0.0, 5.0, 0.0), DVec3::X).unwrap();
        assert!(!CoarseRay::new(&miss, [-1.0; 3], [1.0; 3]).may_hit(&sphere));
    }
}
