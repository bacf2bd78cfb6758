//! The questions the checker knows, and their variants by seed.
//!
//! Building a variant is the costly part of a check (every key is computed from the seed, five
//! questions at once), and a grader checks many files of one seed, so [`variant`] keeps the most
//! recently used variants: at most [`CACHED_VARIANTS`] of them (the five questions of the last
//! 32 seeds; a variant is a few kilobytes of statement and key, so the cache stays below about a
//! megabyte), least recently used dropped first. A variant is a pure function of its question and
//! seed, so a cached one is equal to a fresh one, and a report does not depend on the cache.

use super::error::CheckError;
use super::key::Variant;
use super::{q1, q2, q3, q4, q5};
use std::cell::Cell;
use std::collections::VecDeque;
use std::sync::{Arc, Mutex};

/// The questions the checker grades, in order.
///
/// # Examples
/// ```
/// for question in hw3::checker::QUESTIONS {
///     assert!(hw3::checker::variant(question, 1).is_ok());
/// }
/// ```
pub const QUESTIONS: [&str; 5] = ["q1", "q2", "q3", "q4", "q5"];

/// Variants [`variant`] keeps: the five questions of 32 seeds.
pub(crate) const CACHED_VARIANTS: usize = 5 * 32;

/// The cache: `(question index, seed)` and the variant, most recently used first (a linear scan
/// of 160 entries costs nanoseconds next to building one variant).
pub(super) static CACHE: Mutex<VecDeque<CacheEntry>> = Mutex::new(VecDeque::new());

/// One cached variant: `(question index, seed)` and the variant.
type CacheEntry = ((usize, u64), Arc<Variant>);

thread_local! {
    /// Set while [`uncached`] runs on this thread: [`variant`] then builds every variant afresh.
    static BYPASS: Cell<bool> = const { Cell::new(false) };
}

/// The variant of `question` for `seed`, from the cache of recent variants when it holds it
/// (the module's doc says how it is bounded); equal to a freshly built one either way.
///
/// # Errors
/// [`CheckError::UnknownQuestion`] for a question id not in [`QUESTIONS`].
///
/// # Examples
/// ```
/// let variant = hw3::checker::variant("q2", 0).unwrap();
/// assert!(variant.parts.iter().any(|p| p.key == "q2a.t"));
/// assert_eq!(hw3::checker::variant("q2", 0).unwrap(), variant); // the second one is cached
/// ```
pub fn variant(question: &str, seed: u64) -> Result<Variant, CheckError> {
    let index = QUESTIONS
        .iter()
        .position(|&q| q == question)
        .ok_or_else(|| CheckError::UnknownQuestion(question.to_string()))?;
    if BYPASS.get() {
        return Ok(build(index, seed));
    }
    let key = (index, seed);
    // A poisoned lock only means another thread panicked mid-update of a list of finished
    // entries: every entry in it is still whole, so the cache stays usable.
    let cached = {
        let mut cache = CACHE.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        cache.iter().position(|(k, _)| *k == key).and_then(|at| cache.remove(at)).inspect(|entry| {
            cache.push_front(entry.clone());
        })
    };
    if let Some((_, variant)) = cached {
        return Ok(Variant::clone(&variant));
    }
    // Built outside the lock, so that threads checking different seeds do not wait for each other.
    let variant = Arc::new(build(index, seed));
    let mut cache = CACHE.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if !cache.iter().any(|(k, _)| *k == key) {
        cache.push_front((key, Arc::clone(&variant)));
        cache.truncate(CACHED_VARIANTS);
    }
    Ok(Variant::clone(&variant))
}

/// Runs `f` with the cache of [`variant`] bypassed on this thread (every variant built afresh).
#[cfg(test)]
pub(crate) fn uncached<T>(f: impl FnOnce() -> T) -> T {
    /// Restores the bypass flag even when `f` panics: the unit tests' runner reuses its threads.
    struct Restore(bool);
    impl Drop for Restore {
        fn drop(&mut self) {
            BYPASS.set(self.0);
        }
    }
    let _restore = Restore(BYPASS.replace(true));
    f()
}

/// Builds the variant of question `QUESTIONS[index]` for `seed`.
fn build(index: usize, seed: u64) -> Variant {
    match index {
        0 => q1::variant(seed),
        1 => q2::variant(seed),
        2 => q3::variant(seed),
        3 => q4::variant(seed),
        _ => q5::variant(seed),
    }
}
