//! The `f64` tree's first sphere test, in `f32` on a quarter of the bytes: a *conservative*
//! rejection that never turns away a sphere the exact `f64` test would keep, so that the tree's
//! answers stay bit for bit those of [`roots_stable`](hw3_core::geometry::sphere::roots_stable).
//!
//! # Why
//! A random ray's time goes to waiting for leaf spheres, not nodes: in a tree of 10⁵ spheres it
//! reads about 20 leaf cache lines of `f64` spheres, most of them not in the cache, against a few
//! misses for its many node steps. Fewer than one sphere per ray passes the discriminant test, so
//! the test that rejects needs only enough precision to reject safely, and the exact sphere is
//! read only for the few it keeps. At 8 bytes a copy (`u16` counts on a grid, below) the copies
//! of a leaf take a quarter of the exact spheres' lines, and far more of them stay in the cache;
//! the Q3 engineering notes give the cache misses per ray of each layout.
//!
//! A leaf's copies lie side by side, so the walk tests four at a time
//! ([`CoarseRay::survivors`], SSE2 on x86-64, one sphere at a time elsewhere), eight at a time on
//! a CPU with AVX2 ([`CoarseRay::survivors_wide`]) or sixteen on one with AVX-512F and AVX-512BW
//! ([`CoarseRay::survivors_widest`]), each in a walk compiled for it, each lane with the scalar
//! test's operations in the same order: the same answers, a bit mask of survivors instead of a
//! branch per copy.
//!
//! # The grid
//! Each tree has one [`Grid`]: a corner `g` (an `f32` at or below its box) and a power-of-two step
//! `h` with 65 535 steps covering the box. A sphere `(c, r)` is stored as the counts `q` of its
//! centre's nearest grid point `c' = g + q h` and a radius `r' = k h ≥ r + |c − c'|` (rounded up,
//! with a margin for the `f64` rounding of `|c − c'|`). Every point within `r` of `c` lies within
//! `r'` of `c'`, so a line that meets the sphere meets the stored one: the exact test on the
//! stored sphere keeps at least what the exact test on the true one keeps. The test runs in steps
//! (everything divided by `h`): a power of two, so the scaling is exact and changes no rounding.
//!
//! # The bound
//! The exact test keeps a sphere when `r² (d·d) − |f × d|² ≥ 0` in `f64` (`f = e − c`), i.e. when
//! the centre lies within about `r` of the ray's line. Here the same expression is evaluated in
//! `f32` on the stored sphere, with `f = fl(e − g) − q h` (the offset of the ray's origin from the
//! corner rounded once to `f32`, then the exact grid offset subtracted), the direction rounded to
//! nearest, and compared with a radius widened by `τ = 2⁻¹⁸ M + 2⁻⁴⁰`, where `M` bounds every
//! coordinate of the ray's origin, of the tree's box, of `g` and of every grid point. With the
//! unit roundoff `u = 2⁻²⁴` of `f32` (Higham, *Accuracy and Stability of Numerical Algorithms*,
//! 2nd ed., §2.2), the rounded offset is within `2uM` of the exact one per coordinate and the
//! subtraction adds at most `u |f| ≤ 2uM`, so `f` moves by at most `4√3 u M`, and the direction by
//! `u |d|`; the cross product's own roundings add at most `8√3 u M |d|`, so the computed
//! `|f × d|` lies within `25 u M |d|` of the exact one (the `f64` test's own error is `2⁻²⁹` times
//! smaller); `τ = 64 u M` covers that with room for the roundings of the comparison itself, which
//! a factor `1 + 2⁻¹⁸` on `d·d` covers. The absolute `2⁻⁴⁰` covers gradual underflow. The bound
//! needs `M ≤ 2²⁴` and every direction with `2⁻²⁴ ≤ max |d_a| ≤ 2²⁴` (no `f32` overflow or flush of
//! the direction); any other ray skips the coarse test and tests every sphere exactly, and so does
//! every ray of a tree with a sphere that does not fit its grid.
//!
//! The widening costs little: on the benchmark's unit cube (its box a little wider than 1)
//! `h = 2⁻¹⁵` and `τ ≈ 8·10⁻⁶`, so the stored radius exceeds the true one by at most
//! `(√3/2 + 1) h + τ ≈ 6·10⁻⁵`, against radii of about `10⁻³` and more.

use super::node::Aabb;
use hw3_core::geometry::{Ray, Sphere};

/// Grid steps per axis: centres and radii are stored as `u16` multiples of the grid's step.
const STEPS: f64 = 65_535.0;

/// The quantisation grid of one tree: a corner `origin` (an `f32` at or below the tree's box) and
/// one power-of-two `step` for all three axes, at least the box's longest extent over 65 535, so
/// that a centre's offset from the corner is a `u16` count of steps, and scaling by the step is
/// exact in floating point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Grid {
    origin: [f32; 3],
    step: f64,
    /// The largest coordinate magnitude of the box, of `origin` and of every grid point
    /// `origin + q · step`: the `M` of the bound (see the module docs), without the ray's origin.
    magnitude: f64,
}

impl Grid {
    /// The grid of the tree whose box is `bounds` (finite, as every built tree's is; an empty tree's
    /// inverted box gives a grid no sphere is packed on).
    pub fn new(bounds: &Aabb) -> Self {
        let (lo, hi) = (bounds.min.to_array(), bounds.max.to_array());
        let origin = lo.map(|x| {
            let y = x as f32;
            if f64::from(y) > x { y.next_down() } else { y }
        });
        // From the corner, so that every centre in the box is at most 65 535 steps from it, and a
        // radius (at most half the box's extent) at most about 32 768.
        let extent = (0..3).map(|a| hi[a] - f64::from(origin[a])).fold(0.0f64, f64::max);
        // 2⁻⁶⁰ ≤ step ≤ 2⁶⁰: far past the range in which the coarse test is enabled at either end.
        let mut step = 2.0f64.powi(-60);
        while step * STEPS < extent && step < 2.0f64.powi(60) {
            step *= 2.0;
        }
        let magnitude = (0..3)
            .map(|a| {
                let (o, top) = (f64::from(origin[a]), f64::from(origin[a]) + STEPS * step);
                [lo[a], hi[a], o, top].iter().fold(0.0f64, |m, x| m.max(x.abs()))
            })
            .fold(0.0f64, f64::max);
        Self { origin, step, magnitude }
    }

    /// `sphere` on the grid: its centre rounded to the nearest grid point `c'`, its radius `r'` a
    /// whole number of steps with `r' ≥ r + |c − c'|`, so that the sphere `(c', r')` contains the
    /// sphere; `None` when the counts do not fit `u16` (only for a sphere that sticks out of the
    /// grid's box), and the tree then skips the coarse test.
    pub fn pack(&self, sphere: &Sphere<f64>) -> Option<CoarseSphere> {
        let c = sphere.center.to_array();
        // Multiplying by the power-of-two step's reciprocal (exact: 2⁻⁶⁰ ≤ step ≤ 2⁶⁰) rounds the
        // same real number as dividing by the step, so it gives the same result.
        let per_step = 1.0 / self.step;
        let mut q = [0u16; 4];
        let mut moved = 0.0;
        for a in 0..3 {
            let x = (c[a] - f64::from(self.origin[a])) * per_step;
            // `x.round()` lies in [0, 65 535] exactly when `x` lies in (−0.5, 65 535.5); NaN fails.
            if !(x > -0.5 && x < STEPS + 0.5) {
                return None;
            }
            let steps = round_steps(x);
            q[a] = steps as u16;
            // The grid point is exact in `f64` up to one rounding of the sum, which the margin
            // below covers.
            let d = c[a] - (f64::from(self.origin[a]) + steps * self.step);
            moved += d * d;
        }
        let margin = self.magnitude * 2.0f64.powi(-48);
        let need = (sphere.radius + moved.sqrt() + margin) * (1.0 + 2.0f64.powi(-50));
        let radius = need * per_step;
        // `radius.ceil() ≤ 65 535` exactly when `radius ≤ 65 535`; NaN fails.
        if !(radius <= STEPS) {
            return None;
        }
        q[3] = ceil_steps(radius) as u16;
        Some(CoarseSphere { steps: q })
    }
}

/// `x.round()` (half away from zero) for `x` in (−0.5, 65 535.5), as `+0` for `x` below 0.5 where
/// `round` gives `−0` for negative `x` (the one difference: the grid point `origin + 0 · step` and
/// its distance `d`, squared, are then the same). Inline integer truncation instead of `round`,
/// a library call on x86-64's SSE2 baseline (three per sphere were a third of the packing's
/// instructions).
#[inline]
fn round_steps(x: f64) -> f64 {
    let x = x.max(0.0);
    // Below 2¹⁶ the truncation is exact and so is the fraction `x − t`.
    let t = f64::from(x as u32);
    if x - t >= 0.5 { t + 1.0 } else { t }
}

/// `x.ceil()` for `x` in [0, 65 535], by an inline truncation as in [`round_steps`].
#[inline]
fn ceil_steps(x: f64) -> f64 {
    let t = f64::from(x as u32);
    if t < x { t + 1.0 } else { t }
}

/// A leaf sphere as the coarse test reads it: its centre and radius on the tree's [`Grid`] as
/// counts of steps, 8 bytes (eight to a cache line, a leaf's spheres side by side). The sphere it
/// describes contains the exact one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C, align(8))]
pub(super) struct CoarseSphere {
    steps: [u16; 4],
}

impl CoarseSphere {
    /// A placeholder: every copy of a tree whose spheres do not fit its grid (the tree then skips
    /// the coarse test), and the padding after the last leaf's copies (read by that leaf's last
    /// group, whose mask leaves it out).
    pub const KEEP: Self = Self { steps: [0, 0, 0, u16::MAX] };
}

/// A ray prepared for the coarse test: its origin relative to the grid's corner rounded to `f32`
/// and counted in steps, its direction rounded to `f32`, with the widening of the radius and the
/// scale on `d·d` that make the test conservative, or disabled where the bound does not hold.
#[derive(Debug, Clone, Copy)]
pub(super) struct CoarseRay {
    origin: [f32; 3],
    dir: [f32; 3],
    /// `d·d` in `f32`, times `1 + 2⁻¹⁸`.
    scaled_a: f32,
    /// `τ` in steps, rounded up.
    widening: f32,
    /// False when the ray or the box is out of the bound's range: then every sphere is kept.
    enabled: bool,
}

/// The largest coordinate magnitude and the direction range for which the bound holds.
const MAX_COORDINATE: f64 = 16_777_216.0; // 2²⁴
const MIN_DIRECTION: f64 = 1.0 / 16_777_216.0; // 2⁻²⁴

/// The vector tests' lane arithmetic, written once for the three widths: [`CoarseRay::may_hit`]'s
/// `f32` operations in its order (no fused multiply-add), lane by lane, on `ray` (a
/// [`CoarseRay`]), the copies' counts `q` (one vector per coordinate) and their `radius` counts,
/// with the width's intrinsics `$sub`, `$mul`, `$add` and `$set1`. Evaluates to `(lhs, rhs)`: a lane
/// survives where `lhs <= rhs`. Each caller is a function compiled for its width, which the
/// expanded intrinsics need.
#[cfg(x86_simd)]
macro_rules! lane_sides {
    ($ray:expr, $q:expr, $radius:expr, $sub:ident, $mul:ident, $add:ident, $set1:ident) => {{
        let (ray, q, radius) = ($ray, $q, $radius);
        let (o, d) = (ray.origin.map(|x| $set1(x)), ray.dir.map(|x| $set1(x)));
        let f = [$sub(o[0], q[0]), $sub(o[1], q[1]), $sub(o[2], q[2])];
        let p = [
            $sub($mul(f[1], d[2]), $mul(f[2], d[1])),
            $sub($mul(f[2], d[0]), $mul(f[0], d[2])),
            $sub($mul(f[0], d[1]), $mul(f[1], d[0])),
        ];
        let lhs = $add($add($mul(p[0], p[0]), $mul(p[1], p[1])), $mul(p[2], p[2]));
        let s = $add(radius, $set1(ray.widening));
        (lhs, $mul($mul(s, s), $set1(ray.scaled_a)))
    }};
}

impl CoarseRay {
    /// The coarse ray for `ray` in a tree with the grid `grid`.
    pub fn new(ray: &Ray<f64>, grid: &Grid) -> Self {
        let (o, d) = (ray.origin.to_array(), ray.dir.to_array());
        let magnitude = o.iter().fold(grid.magnitude, |m, x| m.max(x.abs()));
        let longest = d.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let enabled =
            magnitude <= MAX_COORDINATE && (MIN_DIRECTION..=MAX_COORDINATE).contains(&longest) && magnitude.is_finite();
        // One rounding to `f32` of the offset, then an exact scaling by a power of two (no overflow:
        // the offset is below 2²⁵ and the step at least 2⁻⁶⁰).
        let inverse = (1.0 / grid.step) as f32;
        let origin = [0, 1, 2].map(|a| (o[a] - f64::from(grid.origin[a])) as f32 * inverse);
        let dir = d.map(|x| x as f32);
        let a = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
        let widening = (magnitude * 2.0f64.powi(-18) + 2.0f64.powi(-40)) / grid.step;
        Self {
            origin,
            dir,
            scaled_a: a * (1.0 + 2.0f32.powi(-18)),
            widening: (widening as f32).next_up(),
            enabled: enabled && origin.iter().all(|x| x.is_finite()),
        }
    }

    /// False only if the exact test rejects the sphere `sphere` was packed from too (see the
    /// module docs); always true for a disabled ray.
    #[inline]
    pub fn may_hit(&self, sphere: &CoarseSphere) -> bool {
        if !self.enabled {
            return true;
        }
        let (o, d, q) = (self.origin, self.dir, sphere.steps);
        let f = [o[0] - f32::from(q[0]), o[1] - f32::from(q[1]), o[2] - f32::from(q[2])];
        let p = [f[1] * d[2] - f[2] * d[1], f[2] * d[0] - f[0] * d[2], f[0] * d[1] - f[1] * d[0]];
        let s = f32::from(q[3]) + self.widening;
        p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= s * s * self.scaled_a
    }

    /// [`CoarseRay::may_hit`] for the first [`LANES`] spheres of `spheres` at once, as a bit mask
    /// (bit `k` set when `may_hit(&spheres[k])`): every bit is exactly the scalar test's answer,
    /// because each lane does the scalar test's `f32` operations in the same order (no fused
    /// multiply-add; a `u16` count converts to `f32` exactly either way). A leaf's copies sit side
    /// by side, so four of them are one 32-byte load, and a leaf of up to four spheres is tested
    /// without a loop whose end a random ray would mispredict.
    ///
    /// # Panics
    /// If `spheres` holds fewer than [`LANES`] copies (the tree pads its list so that every
    /// leaf's last group is whole).
    #[inline]
    pub fn survivors(&self, spheres: &[CoarseSphere]) -> u32 {
        let four: &[CoarseSphere; LANES] = spheres[..LANES].try_into().expect("a group of four copies");
        if !self.enabled {
            return ALL_LANES;
        }
        #[cfg(x86_simd)]
        return self.survivors_sse2(four);
        #[cfg(not(x86_simd))]
        return self.survivors_scalar(four);
    }

    /// [`CoarseRay::survivors`] one sphere at a time: the reference the vector code is tested
    /// against, and the code of other targets.
    #[cfg_attr(all(x86_simd, not(test)), allow(dead_code))]
    fn survivors_scalar(&self, four: &[CoarseSphere; LANES]) -> u32 {
        four.iter().enumerate().fold(0, |mask, (k, sphere)| mask | (u32::from(self.may_hit(sphere)) << k))
    }

    /// [`CoarseRay::survivors`] in SSE2, x86-64's baseline: no run-time check.
    #[cfg(x86_simd)]
    #[inline]
    fn survivors_sse2(&self, four: &[CoarseSphere; LANES]) -> u32 {
        use std::arch::x86_64::{
            _mm_add_ps, _mm_cmple_ps, _mm_cvtepi32_ps, _mm_loadu_si128, _mm_movehl_ps, _mm_movelh_ps, _mm_movemask_ps,
            _mm_mul_ps, _mm_set1_ps, _mm_setzero_si128, _mm_sub_ps, _mm_unpackhi_epi16, _mm_unpackhi_ps,
            _mm_unpacklo_epi16, _mm_unpacklo_ps,
        };
        // SAFETY: SSE and SSE2 are part of every x86-64 CPU (the baseline the crate is compiled
        // for); the only memory touched is two unaligned 16-byte loads of `four`'s halves: four
        // `#[repr(C)]` copies of four `u16`s, 32 bytes without padding.
        unsafe {
            let at = four.as_ptr().cast::<std::arch::x86_64::__m128i>();
            let (front, back) = (_mm_loadu_si128(at), _mm_loadu_si128(at.add(1)));
            let zero = _mm_setzero_si128();
            // Each sphere's four counts, zero-extended to 32 bits and converted exactly: rows
            // (x, y, z, r) of spheres 0..3 ...
            let rows = [
                _mm_cvtepi32_ps(_mm_unpacklo_epi16(front, zero)),
                _mm_cvtepi32_ps(_mm_unpackhi_epi16(front, zero)),
                _mm_cvtepi32_ps(_mm_unpacklo_epi16(back, zero)),
                _mm_cvtepi32_ps(_mm_unpackhi_epi16(back, zero)),
            ];
            // ... transposed into one vector per coordinate (lane k: sphere k).
            let (xy01, xy23) = (_mm_unpacklo_ps(rows[0], rows[1]), _mm_unpacklo_ps(rows[2], rows[3]));
            let (zr01, zr23) = (_mm_unpackhi_ps(rows[0], rows[1]), _mm_unpackhi_ps(rows[2], rows[3]));
            let q = [_mm_movelh_ps(xy01, xy23), _mm_movehl_ps(xy23, xy01), _mm_movelh_ps(zr01, zr23)];
            let radius = _mm_movehl_ps(zr23, zr01);
            let (lhs, rhs) = lane_sides!(self, q, radius, _mm_sub_ps, _mm_mul_ps, _mm_add_ps, _mm_set1_ps);
            _mm_movemask_ps(_mm_cmple_ps(lhs, rhs)) as u32
        }
    }

    /// [`CoarseRay::survivors`] for the first [`WIDE_LANES`] spheres of `spheres` at once, eight
    /// `f32` lanes per instruction: every bit is again exactly the scalar test's answer (the same
    /// operations in the same order in every lane, no fused multiply-add). A leaf of five to eight
    /// spheres is then one test instead of two.
    ///
    /// # Safety
    /// The CPU must have AVX2 (the caller checks once, and calls this from code compiled for it).
    ///
    /// # Panics
    /// If `spheres` holds fewer than [`WIDE_LANES`] copies.
    #[cfg(x86_simd)]
    #[target_feature(enable = "avx2")]
    #[inline]
    pub unsafe fn survivors_wide(&self, spheres: &[CoarseSphere]) -> u32 {
        use std::arch::x86_64::{
            __m128i, _CMP_LE_OQ, _mm_loadu_si128, _mm_unpackhi_epi64, _mm_unpacklo_epi64, _mm256_add_ps,
            _mm256_castpd_ps, _mm256_castps_pd, _mm256_cmp_ps, _mm256_cvtepi32_ps, _mm256_cvtepu16_epi32,
            _mm256_movemask_ps, _mm256_mul_ps, _mm256_set1_ps, _mm256_sub_ps, _mm256_unpackhi_pd, _mm256_unpackhi_ps,
            _mm256_unpacklo_pd, _mm256_unpacklo_ps,
        };
        let eight: &[CoarseSphere; WIDE_LANES] = spheres[..WIDE_LANES].try_into().expect("a group of eight copies");
        if !self.enabled {
            return (1 << WIDE_LANES) - 1;
        }
        // SAFETY: the caller guarantees AVX2; the only memory touched is four unaligned 16-byte
        // loads of `eight`: eight `#[repr(C)]` copies of four `u16`s, 64 bytes without padding.
        unsafe {
            let at = eight.as_ptr().cast::<__m128i>();
            // Spheres (0, 1), (2, 3), (4, 5), (6, 7), then paired k with k + 4, so that after the
            // transposition within each 128-bit half lane k holds sphere k.
            let pairs = [0, 1, 2, 3].map(|k| _mm_loadu_si128(at.add(k)));
            let halves = [
                _mm_unpacklo_epi64(pairs[0], pairs[2]),
                _mm_unpackhi_epi64(pairs[0], pairs[2]),
                _mm_unpacklo_epi64(pairs[1], pairs[3]),
                _mm_unpackhi_epi64(pairs[1], pairs[3]),
            ];
            // Row j: (x, y, z, r) of sphere j in the low half and of sphere j + 4 in the high one.
            let rows = halves.map(|h| _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(h)));
            let (xy01, xy23) = (_mm256_unpacklo_ps(rows[0], rows[1]), _mm256_unpacklo_ps(rows[2], rows[3]));
            let (zr01, zr23) = (_mm256_unpackhi_ps(rows[0], rows[1]), _mm256_unpackhi_ps(rows[2], rows[3]));
            // Within each half, 64-bit pieces of two rows side by side (SSE's `movelh` and `movehl`).
            let (xy01, xy23, zr01, zr23) =
                (_mm256_castps_pd(xy01), _mm256_castps_pd(xy23), _mm256_castps_pd(zr01), _mm256_castps_pd(zr23));
            let q = [
                _mm256_castpd_ps(_mm256_unpacklo_pd(xy01, xy23)),
                _mm256_castpd_ps(_mm256_unpackhi_pd(xy01, xy23)),
                _mm256_castpd_ps(_mm256_unpacklo_pd(zr01, zr23)),
            ];
            let radius = _mm256_castpd_ps(_mm256_unpackhi_pd(zr01, zr23));
            let (lhs, rhs) = lane_sides!(self, q, radius, _mm256_sub_ps, _mm256_mul_ps, _mm256_add_ps, _mm256_set1_ps);
            _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(lhs, rhs)) as u32
        }
    }

    /// [`CoarseRay::survivors`] for the first [`WIDEST_LANES`] spheres of `spheres` at once,
    /// sixteen `f32` lanes per instruction (AVX-512): every bit is again exactly the scalar test's
    /// answer (the same operations in the same order in every lane, no fused multiply-add). The
    /// copies need no transposition here: one two-source word shuffle (`vpermt2w`) gathers the 16
    /// x and 16 y counts of the two 64-byte halves into one register, another the z counts and the
    /// radii, and the comparison writes its mask straight to a mask register. A leaf of 9 to 16
    /// spheres is then one test instead of two, one of 17 to 32 two instead of four.
    ///
    /// # Safety
    /// The CPU must have AVX-512F and AVX-512BW (the caller checks once, and calls this from code
    /// compiled for them).
    ///
    /// # Panics
    /// If `spheres` holds fewer than [`WIDEST_LANES`] copies.
    #[cfg(x86_simd)]
    #[target_feature(enable = "avx512f,avx512bw")]
    #[inline]
    pub unsafe fn survivors_widest(&self, spheres: &[CoarseSphere]) -> u32 {
        use std::arch::x86_64::{
            __m512i, _CMP_LE_OQ, _mm512_add_ps, _mm512_castsi512_si256, _mm512_cmp_ps_mask, _mm512_cvtepi32_ps,
            _mm512_cvtepu16_epi32, _mm512_extracti64x4_epi64, _mm512_loadu_si512, _mm512_mul_ps,
            _mm512_permutex2var_epi16, _mm512_set1_ps, _mm512_sub_ps,
        };
        let sixteen: &[CoarseSphere; WIDEST_LANES] =
            spheres[..WIDEST_LANES].try_into().expect("a group of sixteen copies");
        if !self.enabled {
            return (1 << WIDEST_LANES) - 1;
        }
        // SAFETY: the caller guarantees AVX-512F and AVX-512BW; the only memory touched is two
        // unaligned 64-byte loads of `sixteen` (sixteen `#[repr(C)]` copies of four `u16`s, 128
        // bytes without padding) and one of each 64-byte word table (32 `i16`s).
        unsafe {
            let at = sixteen.as_ptr().cast::<__m512i>();
            let (front, back) = (_mm512_loadu_si512(at), _mm512_loadu_si512(at.add(1)));
            let table = |words: &[i16; 32]| _mm512_loadu_si512(words.as_ptr().cast());
            let xy = _mm512_permutex2var_epi16(front, table(&XY_WORDS), back);
            let zr = _mm512_permutex2var_epi16(front, table(&ZR_WORDS), back);
            let counts = |words: __m512i, high: bool| {
                let half = if high { _mm512_extracti64x4_epi64::<1>(words) } else { _mm512_castsi512_si256(words) };
                _mm512_cvtepi32_ps(_mm512_cvtepu16_epi32(half))
            };
            let q = [counts(xy, false), counts(xy, true), counts(zr, false)];
            let radius = counts(zr, true);
            let (lhs, rhs) = lane_sides!(self, q, radius, _mm512_sub_ps, _mm512_mul_ps, _mm512_add_ps, _mm512_set1_ps);
            u32::from(_mm512_cmp_ps_mask::<_CMP_LE_OQ>(lhs, rhs))
        }
    }

    /// The test of one group of `GROUP` copies of a leaf, for a walk compiled for it:
    /// [`CoarseRay::survivors_widest`] (16), [`CoarseRay::survivors_wide`] (8), else
    /// [`CoarseRay::survivors`] (4).
    ///
    /// # Safety
    /// With `GROUP` 16, the CPU must have AVX-512F and AVX-512BW; with 8, AVX2.
    ///
    /// # Panics
    /// If `spheres` holds fewer than `GROUP` copies, or (on a target other than x86-64) `GROUP`
    /// is 8 or 16. A `GROUP` other than 4, 8 and 16 does not compile.
    #[inline(always)]
    pub unsafe fn survivors_of<const GROUP: usize>(&self, spheres: &[CoarseSphere]) -> u32 {
        const { assert!(GROUP == LANES || GROUP == WIDE_LANES || GROUP == WIDEST_LANES, "4, 8 or 16 copies") };
        match GROUP {
            #[cfg(x86_simd)]
            // SAFETY: the caller guarantees AVX-512F and AVX-512BW when `GROUP` is 16.
            WIDEST_LANES => unsafe { self.survivors_widest(spheres) },
            #[cfg(x86_simd)]
            // SAFETY: the caller guarantees AVX2 when `GROUP` is 8.
            WIDE_LANES => unsafe { self.survivors_wide(spheres) },
            LANES => self.survivors(spheres),
            _ => panic!("no coarse test of {GROUP} copies at once on this target"),
        }
    }
}

/// The word order of [`CoarseRay::survivors_widest`]'s two shuffles. Word `4k + j` of the 128
/// bytes of sixteen copies (the first 64-byte half's 32 words, then the second's) is count `j` of
/// copy `k`; word `p` of a shuffle's result is count `first` of copy `p` for `p < 16` and count
/// `second` of copy `p − 16` above.
#[cfg(x86_simd)]
const fn shuffle_words(first: i16, second: i16) -> [i16; 32] {
    let mut words = [0; 32];
    let mut p = 0;
    while p < 32 {
        words[p] = if p < 16 { 4 * p as i16 + first } else { 4 * (p as i16 - 16) + second };
        p += 1;
    }
    words
}

/// The x counts of sixteen copies, then their y counts ([`shuffle_words`]).
#[cfg(x86_simd)]
const XY_WORDS: [i16; 32] = shuffle_words(0, 1);

/// The z counts of sixteen copies, then their radii ([`shuffle_words`]).
#[cfg(x86_simd)]
const ZR_WORDS: [i16; 32] = shuffle_words(2, 3);

/// How many coarse copies [`CoarseRay::survivors_widest`] tests at once.
pub(super) const WIDEST_LANES: usize = 16;

/// How many coarse copies [`CoarseRay::survivors_wide`] tests at once.
pub(super) const WIDE_LANES: usize = 8;

/// How many coarse copies [`CoarseRay::survivors`] tests at once.
pub(super) const LANES: usize = 4;

/// The mask of all [`LANES`] lanes.
const ALL_LANES: u32 = (1 << LANES) - 1;

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use hw3_core::geometry::sphere::roots_stable;
    use hw3_core::rng::{seeded, uniform_in as uniform};

    /// The exact test's acceptance: the stable solver finds real roots.
    fn exact_keeps(ray: &Ray<f64>, sphere: &Sphere<f64>) -> bool {
        roots_stable(ray, sphere).is_some()
    }

    /// Rays aimed to graze spheres (within 10⁻⁹ of tangent, relative, from both sides) at several
    /// scales and offsets, in tree boxes from the sphere's own box (the finest grid) to one 3 000
    /// times wider (a step of a tenth of the radius): whenever the exact test keeps a sphere, the
    /// coarse test keeps it.
    #[test]
    fn coarse_test_never_rejects_a_sphere_the_exact_test_keeps() {
        let mut rng = seeded(0xC0A5, 0);
        for &widen in &[1.0, 30.0, 3_000.0] {
            grazing_cases(&mut rng, widen);
        }
    }

    fn grazing_cases(rng: &mut hw3_core::rng::Generator, widen: f64) {
        let (mut kept, mut coarse_kept, mut cases) = (0, 0, 0);
        for &scale in &[1e-6, 1e-3, 1.0, 1e3, 1e6] {
            for &offset in &[0.0, 1.0, -7.5, 1e4] {
                for _ in 0..20_000 / 3 {
                    let c = DVec3::new(uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0))
                        * scale
                        + DVec3::splat(offset * scale);
                    let r = scale * uniform(rng, 1e-4, 0.3);
                    let sphere = Sphere::new(c, r).unwrap();
                    let o = c + DVec3::new(uniform(rng, -3.0, 3.0), uniform(rng, -3.0, 3.0), uniform(rng, -3.0, 3.0))
                        * scale;
                    // A direction whose line passes at distance r' = r·(1 + ε) from the centre, ε
                    // tiny: aimed at a point a distance s = r' t / √(t² − r'²) aside of the centre.
                    let to_c = c - o;
                    let (t, r_line) = (to_c.length(), r * (1.0 + uniform(rng, -1e-9, 1e-9)));
                    if t < 1.01 * r_line {
                        continue;
                    }
                    let side = to_c.any_orthonormal_vector() * (r_line * t / (t * t - r_line * r_line).sqrt());
                    let length = uniform(rng, 1e-3, 1e3);
                    let Ok(ray) = Ray::new(o, (to_c + side).normalize() * length) else {
                        continue;
                    };
                    // The box around the sphere, off-centre when wider, as a tree's would be.
                    let half = DVec3::splat(r * widen);
                    let shift = DVec3::new(uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0));
                    let middle = c + shift * (r * (widen - 1.0));
                    let grid = Grid::new(&Aabb { min: middle - half, max: middle + half });
                    let packed = grid.pack(&sphere).expect("a sphere inside the box fits the grid");
                    let exact = exact_keeps(&ray, &sphere);
                    let may = CoarseRay::new(&ray, &grid).may_hit(&packed);
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
        if widen == 1.0 {
            assert!(coarse_kept < kept + cases / 5, "coarse keeps {coarse_kept}, exact {kept} of {cases}");
        }
    }

    /// The four-, eight- and sixteen-at-once tests give every copy the scalar test's answer, bit
    /// for bit: random and grazing rays (about half of the grazing copies kept), copies at the
    /// grid's extremes (counts 0 and 65 535), and disabled rays, which keep every copy. (The wider
    /// tests run where the CPU has them: AVX2, and AVX-512F with AVX-512BW; the test prints on
    /// how many groups the sixteen-wide one ran.)
    #[test]
    fn survivors_equal_the_scalar_test_lane_by_lane() {
        let mut rng = seeded(0x5EED, 4);
        let grid = Grid::new(&Aabb { min: DVec3::splat(-1.0), max: DVec3::splat(1.0) });
        let (mut groups, mut kept, mut lanes) = (0, 0, 0);
        #[cfg_attr(not(x86_simd), allow(unused_mut))]
        let mut widest = 0;
        for round in 0..20_000 {
            let spheres: Vec<Sphere<f64>> = (0..WIDEST_LANES)
                .map(|_| {
                    let c = DVec3::new(
                        uniform(&mut rng, -1.0, 1.0),
                        uniform(&mut rng, -1.0, 1.0),
                        uniform(&mut rng, -1.0, 1.0),
                    );
                    Sphere::new(c * 0.9, uniform(&mut rng, 1e-4, 0.1)).unwrap()
                })
                .collect();
            let mut group: Vec<CoarseSphere> = spheres.iter().map(|s| grid.pack(s).unwrap()).collect();
            if round % 7 == 0 {
                group[round % WIDEST_LANES] = CoarseSphere { steps: [0, u16::MAX, 0, u16::MAX] };
            }
            let o =
                DVec3::new(uniform(&mut rng, -2.0, 2.0), uniform(&mut rng, -2.0, 2.0), uniform(&mut rng, -2.0, 2.0));
            // Every other ray is aimed at the first sphere's rim: grazing, kept or not by a hair.
            let target = spheres[0].center + DVec3::X * spheres[0].radius * (1.0 + uniform(&mut rng, -1e-6, 1e-6));
            let random =
                DVec3::new(uniform(&mut rng, -1.0, 1.0), uniform(&mut rng, -1.0, 1.0), uniform(&mut rng, -1.0, 1.0));
            let dir = if round % 2 == 0 { target - o } else { random };
            let scale = [1.0, 1e-30, 1e3][round % 3];
            let Ok(ray) = Ray::new(o, dir * scale) else { continue };
            let coarse = CoarseRay::new(&ray, &grid);
            let mask = coarse.survivors(&group);
            assert_eq!(mask, coarse.survivors_scalar(group[..LANES].try_into().unwrap()), "{ray:?} {group:?}");
            let scalar = group.iter().enumerate().fold(0, |m, (k, c)| m | (u32::from(coarse.may_hit(c)) << k));
            assert_eq!(mask, scalar & ALL_LANES, "four at once: {ray:?} {group:?}");
            #[cfg(x86_simd)]
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above).
                let eight = unsafe { coarse.survivors_wide(&group) };
                assert_eq!(eight, scalar & 0xff, "eight at once: {ray:?} {group:?}");
            }
            #[cfg(x86_simd)]
            if std::arch::is_x86_feature_detected!("avx512f") && std::arch::is_x86_feature_detected!("avx512bw") {
                // SAFETY: the CPU has AVX-512F and AVX-512BW (checked just above).
                assert_eq!(unsafe { coarse.survivors_widest(&group) }, scalar, "sixteen at once: {ray:?} {group:?}");
                widest += 1;
            }
            if !coarse.enabled {
                assert_eq!(mask, ALL_LANES);
            }
            groups += 1;
            kept += mask.count_ones();
            lanes += LANES as u32;
        }
        assert!(groups > 19_000 && kept > lanes / 20 && kept < lanes / 2, "{kept} of {lanes} lanes kept");
        eprintln!("sixteen-wide test compared on {widest} of {groups} groups (0 on a CPU without AVX-512BW)");
    }

    #[test]
    fn out_of_range_rays_keep_every_sphere() {
        let grid = Grid::new(&Aabb { min: DVec3::splat(-1.0), max: DVec3::splat(1.0) });
        let sphere = grid.pack(&Sphere::new(DVec3::ZERO, 1.0).unwrap()).unwrap();
        let far = Ray::new(DVec3::splat(1e30), DVec3::X).unwrap();
        assert!(CoarseRay::new(&far, &grid).may_hit(&sphere));
        let tiny = Ray::new(DVec3::new(0.0, 5.0, 0.0), DVec3::X * 1e-30).unwrap();
        assert!(CoarseRay::new(&tiny, &grid).may_hit(&sphere));
        let miss = Ray::new(DVec3::new(0.0, 5.0, 0.0), DVec3::X).unwrap();
        assert!(!CoarseRay::new(&miss, &grid).may_hit(&sphere));
    }

    /// Every sphere inside the box fits the grid with a radius of at most about half the box's
    /// steps, and a sphere outside it does not (the tree then tests exactly).
    /// [`Grid::pack`] as first written, with the library's `round` and `ceil` and a division by
    /// the step: the reference the inline rounding is compared with.
    fn pack_reference(grid: &Grid, sphere: &Sphere<f64>) -> Option<CoarseSphere> {
        let c = sphere.center.to_array();
        let mut q = [0u16; 4];
        let mut moved = 0.0;
        for a in 0..3 {
            let steps = ((c[a] - f64::from(grid.origin[a])) / grid.step).round();
            if !(0.0..=STEPS).contains(&steps) {
                return None;
            }
            q[a] = steps as u16;
            let d = c[a] - (f64::from(grid.origin[a]) + steps * grid.step);
            moved += d * d;
        }
        let margin = grid.magnitude * 2.0f64.powi(-48);
        let need = (sphere.radius + moved.sqrt() + margin) * (1.0 + 2.0f64.powi(-50));
        let radius = (need / grid.step).ceil();
        if !(radius <= STEPS) {
            return None;
        }
        q[3] = radius as u16;
        Some(CoarseSphere { steps: q })
    }

    /// The inline rounding packs every sphere as the library's `round` and `ceil` did: random
    /// spheres in and around boxes of several scales (some off the grid, some of radius 10⁻³⁰⁰), and
    /// centres exactly on grid points, on half steps and half a step outside either end.
    #[test]
    fn inline_rounding_packs_as_round_and_ceil() {
        let mut rng = seeded(0x9ac4, 0);
        for (lo, size) in [(0.0, 1.0), (-3.0, 8.0), (1e4, 0.01), (-1e-3, 2e-3), (-0.0, 1e6)] {
            let bounds = Aabb { min: DVec3::splat(lo), max: DVec3::splat(lo + size) };
            let grid = Grid::new(&bounds);
            let (g, h) = (f64::from(grid.origin[0]), grid.step);
            let mut spheres = Vec::new();
            for _ in 0..20_000 {
                let c = DVec3::new(
                    uniform(&mut rng, lo - 0.1 * size, lo + 1.1 * size),
                    uniform(&mut rng, lo, lo + size),
                    uniform(&mut rng, lo, lo + size),
                );
                let r = if spheres.len() % 5 == 0 { 1e-300 } else { uniform(&mut rng, 0.0, 0.6 * size) };
                spheres.push(Sphere::new(c, r).unwrap());
            }
            for k in [-0.5, -0.25, 0.0, 0.5, 1.0, 1.5, 2.5, 1000.5, STEPS - 0.5, STEPS, STEPS + 0.5, STEPS + 1.0] {
                let x = g + k * h;
                spheres.push(Sphere::new(DVec3::new(x, lo, lo + 0.5 * size), 1e-300).unwrap());
                spheres.push(Sphere::new(DVec3::splat(lo), (k * h).clamp(1e-300, size)).unwrap());
            }
            let mut packed = 0;
            for sphere in &spheres {
                let expected = pack_reference(&grid, sphere);
                assert_eq!(grid.pack(sphere), expected, "{sphere:?} on {grid:?}");
                packed += usize::from(expected.is_some());
            }
            assert!(packed > spheres.len() / 2 && packed < spheres.len(), "{packed} of {} packed", spheres.len());
        }
    }

    #[test]
    fn spheres_in_the_box_fit_and_others_do_not() {
        let grid = Grid::new(&Aabb { min: DVec3::new(-3.0, 0.0, 1e4), max: DVec3::new(5.0, 8.0, 1e4 + 8.0) });
        let whole = grid.pack(&Sphere::new(DVec3::new(1.0, 4.0, 1e4 + 4.0), 4.0).unwrap()).unwrap();
        assert!(whole.steps[3] <= 32_770, "{whole:?}");
        let corner = grid.pack(&Sphere::new(DVec3::new(4.999, 7.999, 1e4 + 7.999), 0.001).unwrap()).unwrap();
        assert!(corner.steps[..3].iter().all(|&q| q > 32_700), "{corner:?}");
        assert_eq!(grid.pack(&Sphere::new(DVec3::new(30.0, 4.0, 1e4), 1.0).unwrap()), None);
    }
}
