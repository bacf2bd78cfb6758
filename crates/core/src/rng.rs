//! Seeded, portable random numbers: every generator the crate uses, and why there is more than one.
//!
//! Figures and snapshots must not change from machine to machine, so every generator has a fixed,
//! value-stable algorithm (from `rand_pcg` 0.10, whose output is pinned by its own tests) and only
//! 64-bit integers are drawn from it, turned into floats here by bit arithmetic ([`unit_f64`], no
//! platform libm). There are three, each for a reason:
//!
//! - [`Generator`] (PCG 64-bit MCG, [`seeded`]): the experiments' generator: question variants,
//!   the checker's random cases, Q2's and Q4's Monte Carlo studies. One 128-bit state, no stream
//!   selection; a `(seed, stream)` pair is mixed into the seed.
//! - [`SampleGenerator`] (PCG32, [`sample_stream`]): the renderer's per-sample generator
//!   (`Sampler` in the renderer, `hw3-render`) and the clutter scene's sphere positions
//!   ([`pcg32`]). PCG32 selects one of 2⁶³ independent streams by its increment, which is what the
//!   renderer needs: pixel jitter and shutter times on separate streams of one pixel, so that a
//!   pass that draws no number leaves every other draw in place (the "forced on, image
//!   identical" tests), and photons on streams of their own. Its state is 128 bits like
//!   [`Generator`]'s, but with a 64-bit multiply. Every committed render and figure was made
//!   with it, so it stays.
//! - SplitMix64 (Steele, Lea & Flood 2014): the Q3 kd-tree benchmark's workload only (random
//!   spheres and rays, with the benchmarks), which must reproduce a fixed workload and its
//!   checksums bit for bit, so it keeps the generator that workload was defined with. Its finaliser
//!   ([`splitmix64_finalise`]) also whitens the per-pixel seeds of [`sample_stream`].

use rand_core::{Rng, SeedableRng};
use rand_pcg::{Pcg32, Pcg64Mcg};

/// The experiments' random generator (see the module docs for the others).
pub type Generator = Pcg64Mcg;

/// The renderer's per-sample generator: PCG32 with a selectable stream (see the module docs).
pub type SampleGenerator = Pcg32;

/// A generator for stream `stream` of experiment `seed`. Distinct `(seed, stream)` pairs give
/// independent-looking sequences (the pair is mixed with a 64-bit golden-ratio multiply), which is
/// how per-thread generators stay reproducible under any thread count.
///
/// # Examples
/// ```
/// let mut a = hw3_core::rng::seeded(7, 0);
/// let mut b = hw3_core::rng::seeded(7, 0);
/// assert_eq!(hw3_core::rng::uniform(&mut a), hw3_core::rng::uniform(&mut b));
/// ```
#[must_use]
pub fn seeded(seed: u64, stream: u64) -> Generator {
    Pcg64Mcg::seed_from_u64(seed ^ stream.wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15))
}

/// PCG32 with state `state` on stream `stream` (the increment selector), unmixed: for a caller
/// whose seeds are already distinct numbers (the clutter scene's sphere positions).
///
/// # Examples
/// ```
/// let mut a = hw3_core::rng::pcg32(1, 0xC1);
/// let mut b = hw3_core::rng::pcg32(1, 0xC2);
/// assert_ne!(hw3_core::rng::uniform(&mut a), hw3_core::rng::uniform(&mut b));
/// ```
#[must_use]
pub fn pcg32(state: u64, stream: u64) -> SampleGenerator {
    Pcg32::new(state, stream)
}

/// The SplitMix64 output finaliser (Steele, Lea & Flood 2014): a bijection of `u64` that sends
/// neighbouring inputs to unrelated outputs.
///
/// # Examples
/// ```
/// // SplitMix64's first output for seed 0 is the finaliser of its first state, the golden ratio.
/// assert_eq!(hw3_core::rng::splitmix64_finalise(0x9E37_79B9_7F4A_7C15), 0xE220_A839_7B1D_CDAF);
/// ```
#[must_use]
pub fn splitmix64_finalise(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The renderer's stream `stream` of item `index` (a pixel or a photon) for image seed `seed`:
/// PCG32 whose state is the SplitMix64 finaliser of `seed ^ index·φ`, so neighbouring pixels get
/// unrelated states, and the result never depends on which thread draws it.
///
/// # Examples
/// ```
/// let mut pixel = hw3_core::rng::sample_stream(1, 42, 0);
/// let mut shutter = hw3_core::rng::sample_stream(1, 42, 1);
/// assert_ne!(hw3_core::rng::uniform(&mut pixel), hw3_core::rng::uniform(&mut shutter));
/// ```
#[must_use]
pub fn sample_stream(seed: u64, index: u64, stream: u64) -> SampleGenerator {
    Pcg32::new(splitmix64_finalise(seed ^ index.wrapping_mul(0x9E37_79B9_7F4A_7C15)), stream)
}

/// The `f64` in `[0, 1)` made of the top 53 bits of `bits` (exact: a multiple of 2⁻⁵³).
///
/// # Examples
/// ```
/// assert_eq!(hw3_core::rng::unit_f64(0), 0.0);
/// assert_eq!(hw3_core::rng::unit_f64(u64::MAX), 1.0 - f64::EPSILON / 2.0);
/// ```
#[must_use]
pub fn unit_f64(bits: u64) -> f64 {
    (bits >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A uniform `f64` in `[0, 1)` with 53 random bits from any of the crate's generators.
///
/// # Examples
/// ```
/// let mut g = hw3_core::rng::seeded(1, 2);
/// let u = hw3_core::rng::uniform(&mut g);
/// assert!((0.0..1.0).contains(&u));
/// ```
pub fn uniform<R: Rng + ?Sized>(generator: &mut R) -> f64 {
    unit_f64(generator.next_u64())
}

/// A uniform `f64` in `[low, high)`.
///
/// # Examples
/// ```
/// let mut g = hw3_core::rng::seeded(1, 2);
/// assert!((-2.0..3.0).contains(&hw3_core::rng::uniform_in(&mut g, -2.0, 3.0)));
/// ```
pub fn uniform_in<R: Rng + ?Sized>(generator: &mut R, low: f64, high: f64) -> f64 {
    low + (high - low) * uniform(generator)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn value_stability_vector() {
        // Pins the generator's output: a change here silently changes every figure and snapshot.
        let mut g = seeded(42, 0);
        let first: Vec<u64> = (0..3).map(|_| g.next_u64()).collect();
        let mut again = seeded(42, 0);
        assert_eq!(first, (0..3).map(|_| again.next_u64()).collect::<Vec<_>>());
        assert_ne!(seeded(42, 1).next_u64(), first[0], "streams differ");
        insta::with_settings!({snapshot_path => crate::SNAPSHOTS, prepend_module_to_snapshot => false}, {
            insta::assert_snapshot!("rng_value_stability", format!("{first:?}"));
        });
    }

    #[test]
    fn sample_streams_are_the_renderers_original_construction() {
        // The per-pixel construction the committed renders were made with, written out: a change
        // in `sample_stream` changes every render.
        let (seed, pixel, stream) = (1u64, 12_345u64, 1u64);
        let mut z = seed ^ pixel.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        let mut original = Pcg32::new(z ^ (z >> 31), stream);
        let mut ours = sample_stream(seed, pixel, stream);
        for _ in 0..4 {
            assert_eq!(ours.next_u64(), original.next_u64());
        }
        // Division by 2⁵³ and multiplication by 2⁻⁵³ are both exact: the clutter scene's form.
        let bits = 0xDEAD_BEEF_0123_4567u64;
        assert_eq!(unit_f64(bits), (bits >> 11) as f64 / (1u64 << 53) as f64);
    }

    #[test]
    fn uniform_mean_is_one_half() {
        let mut g = seeded(3, 0);
        let n = 100_000;
        let mean = (0..n).map(|_| uniform(&mut g)).sum::<f64>() / n as f64;
        // Standard error is 1/sqrt(12 n) ≈ 9e-4; 5 standard errors.
        assert!((mean - 0.5).abs() < 5.0 * (1.0 / (12.0 * n as f64)).sqrt(), "mean {mean}");
    }
}
