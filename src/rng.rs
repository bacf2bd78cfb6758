//! Seeded, portable random numbers for every experiment in the crate.
//!
//! Figures and snapshots must not change from machine to machine, so the crate uses one generator
//! with a fixed algorithm (PCG 64-bit MCG from `rand_pcg`, whose output is value-stable) and draws
//! only 64-bit integers from it, turned into floats here by bit arithmetic (no platform libm).

use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// The crate's random generator.
pub type Generator = Pcg64Mcg;

/// A generator for stream `stream` of experiment `seed`. Distinct `(seed, stream)` pairs give
/// independent-looking sequences (the pair is mixed with a 64-bit golden-ratio multiply), which is
/// how per-pixel and per-thread generators stay reproducible under any thread count.
///
/// # Examples
/// ```
/// let mut a = hw3::rng::seeded(7, 0);
/// let mut b = hw3::rng::seeded(7, 0);
/// assert_eq!(hw3::rng::uniform(&mut a), hw3::rng::uniform(&mut b));
/// ```
#[must_use]
pub fn seeded(seed: u64, stream: u64) -> Generator {
    Pcg64Mcg::seed_from_u64(seed ^ stream.wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15))
}

/// A uniform `f64` in `[0, 1)` with 53 random bits.
///
/// # Examples
/// ```
/// let mut g = hw3::rng::seeded(1, 2);
/// let u = hw3::rng::uniform(&mut g);
/// assert!((0.0..1.0).contains(&u));
/// ```
pub fn uniform(generator: &mut Generator) -> f64 {
    (generator.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A uniform `f64` in `[low, high)`.
///
/// # Examples
/// ```
/// let mut g = hw3::rng::seeded(1, 2);
/// assert!((-2.0..3.0).contains(&hw3::rng::uniform_in(&mut g, -2.0, 3.0)));
/// ```
pub fn uniform_in(generator: &mut Generator, low: f64, high: f64) -> f64 {
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
        insta::with_settings!({snapshot_path => concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"), prepend_module_to_snapshot => false}, {
            insta::assert_snapshot!("rng_value_stability", format!("{first:?}"));
        });
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
