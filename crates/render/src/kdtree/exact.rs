//! The leaves' exact sphere lists: the copy of each listed sphere that the exact `f64` test reads
//! after the coarse test keeps it, stored in `f32` when that loses nothing.
//!
//! A random ray at N = 10⁵ keeps about one sphere in all its leaves, and that sphere's line is
//! rarely in a near cache: the lists are too large (119 987 copies at fixed k, 32 bytes each, 3.8
//! MB), so each kept sphere waits for memory. Most scenes are made in `f32` (a scene file, a mesh,
//! this crate's benchmark), and an `f32` value widens to `f64` exactly. So when every sphere's
//! centre and radius is an `f32` value, the lists hold 16-byte `f32` copies ([`ExactSphereF32`]:
//! half the bytes, four to a line) and the test widens them back: the same `f64` sphere, so the
//! same answers bit for bit. One sphere that `f32` cannot hold keeps the whole tree on 32-byte
//! `f64` copies ([`ExactSphere`]); a tree never mixes the two, so the walk's choice between them
//! is the same at every leaf.

use super::build::PARALLEL_CHUNK;
use super::prefetch::prefetch_lines;
use glam::DVec3;
use hw3_core::geometry::Sphere;

/// A leaf's sphere in `f64`, aligned so that none straddles two cache lines.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub(super) struct ExactSphere(Sphere<f64>);

const _: () = assert!(std::mem::size_of::<ExactSphere>() == 32);

/// A leaf's sphere whose centre and radius are `f32` values, stored as they are: `(x, y, z, r)`,
/// aligned so that none straddles two cache lines.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(16))]
pub(super) struct ExactSphereF32([f32; 4]);

const _: () = assert!(std::mem::size_of::<ExactSphereF32>() == 16);

impl ExactSphereF32 {
    /// `sphere` in `f32`, or `None` if one of its four numbers is not an `f32` value (it would
    /// round).
    fn of(sphere: &Sphere<f64>) -> Option<Self> {
        let values = [sphere.center.x, sphere.center.y, sphere.center.z, sphere.radius];
        let narrowed = values.map(|x| x as f32);
        values.iter().zip(&narrowed).all(|(&x, &y)| f64::from(y) == x).then_some(Self(narrowed))
    }

    /// The sphere in `f64`: every widening is exact.
    #[inline(always)]
    fn widened(self) -> Sphere<f64> {
        let [x, y, z, r] = self.0.map(f64::from);
        Sphere { center: DVec3::new(x, y, z), radius: r }
    }
}

/// The exact copies of the leaves' lists, concatenated in node order (a leaf's `first` and
/// `count` index them): all `f32` when every sphere of the scene is an `f32` value, else all `f64`.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum ExactLists {
    F64(Vec<ExactSphere>),
    F32(Vec<ExactSphereF32>),
}

impl ExactLists {
    /// The copies of `spheres[i]` for each `i` of `listed` (the leaves' lists), in that order: in
    /// `f32` when `spheres` are all `f32` values, else in `f64`; on the thread pool in chunks of
    /// at least [`PARALLEL_CHUNK`] when `parallel`.
    pub fn new(spheres: &[Sphere<f64>], listed: &[u32], parallel: bool) -> Self {
        use rayon::prelude::*;
        let narrow = |sphere: &Sphere<f64>| ExactSphereF32::of(sphere).is_some();
        let all_narrow = if parallel {
            spheres.par_iter().with_min_len(PARALLEL_CHUNK).all(narrow)
        } else {
            spheres.iter().all(narrow)
        };
        fn gather<T: Send>(listed: &[u32], parallel: bool, copy: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
            if parallel {
                listed.par_iter().with_min_len(PARALLEL_CHUNK).map(|&i| copy(i as usize)).collect()
            } else {
                listed.iter().map(|&i| copy(i as usize)).collect()
            }
        }
        if all_narrow {
            Self::F32(gather(listed, parallel, |i| ExactSphereF32::of(&spheres[i]).expect("an f32 sphere")))
        } else {
            Self::F64(gather(listed, parallel, |i| ExactSphere(spheres[i])))
        }
    }

    /// The `k`-th copy, as the `f64` sphere it stands for.
    #[inline(always)]
    pub fn sphere(&self, k: usize) -> Sphere<f64> {
        match self {
            Self::F64(copies) => copies[k].0,
            Self::F32(copies) => copies[k].widened(),
        }
    }

    /// Asks for every cache line of copies `range` (see [`prefetch_lines`]).
    #[inline(always)]
    pub fn prefetch(&self, range: std::ops::Range<usize>) {
        match self {
            Self::F64(copies) => prefetch_lines(&copies[range]),
            Self::F32(copies) => prefetch_lines(&copies[range]),
        }
    }

    /// The number of copies.
    pub fn len(&self) -> usize {
        match self {
            Self::F64(copies) => copies.len(),
            Self::F32(copies) => copies.len(),
        }
    }

    /// The bytes the copies take.
    pub fn bytes(&self) -> usize {
        match self {
            Self::F64(copies) => std::mem::size_of_val(copies.as_slice()),
            Self::F32(copies) => std::mem::size_of_val(copies.as_slice()),
        }
    }

    /// Whether the copies are `f32` (16 bytes each).
    #[cfg(test)]
    pub fn is_f32(&self) -> bool {
        matches!(self, Self::F32(_))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere(x: f64, y: f64, z: f64, r: f64) -> Sphere<f64> {
        Sphere { center: DVec3::new(x, y, z), radius: r }
    }

    /// `f32` copies only when all four numbers of every sphere are `f32` values, and then the
    /// widened copy is the sphere itself, bit for bit.
    #[test]
    fn f32_copies_only_when_nothing_rounds() {
        let exact =
            [sphere(0.5, -3.25, f64::from(1e30f32), f64::from(0.1f32)), sphere(-0.0, 2.0f64.powi(-140), 7.0, 1.5)];
        let lists = ExactLists::new(&exact, &[1, 0, 1], false);
        assert_eq!(ExactLists::new(&exact, &[1, 0, 1], true), lists);
        assert!(lists.is_f32());
        assert_eq!((lists.len(), lists.bytes()), (3, 48));
        for (k, &i) in [1usize, 0, 1].iter().enumerate() {
            let (got, want) = (lists.sphere(k), exact[i]);
            let bits = |s: Sphere<f64>| [s.center.x, s.center.y, s.center.z, s.radius].map(f64::to_bits);
            assert_eq!(bits(got), bits(want), "copy {k}");
        }
        // 0.1 rounds in f32; so do 1e-50 (below the smallest f32 subnormal, 2^-149) and
        // 2^-140 + 2^-150 (halfway between two neighbouring f32 subnormals, which lie 2^-149
        // apart); 1e39 overflows it.
        for odd in [0.1, 1e-50, 1e39, 2.0f64.powi(-140) + 2.0f64.powi(-150)] {
            let lists = ExactLists::new(&[exact[0], sphere(1.0, 1.0, odd, 1.0)], &[0, 1], false);
            assert!(!lists.is_f32(), "{odd}");
            assert_eq!((lists.sphere(1).center.z, lists.bytes()), (odd, 64));
        }
    }
}
