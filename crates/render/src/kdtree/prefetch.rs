//! Requests to the processor to start loading cache lines a walk will read soon, without waiting
//! for them: the one place the walks' prefetch instructions are written.

/// The cache line of the x86-64 processors measured (and most others).
const LINE: usize = 64;

/// Asks the CPU to start loading `items[index]`'s cache line without waiting for it.
#[inline]
pub(super) fn prefetch<T>(items: &[T], index: u32) {
    prefetch_address(items.as_ptr().wrapping_add(index as usize).cast());
}

/// Asks the CPU to start loading every cache line `items` occupies (none for an empty slice).
#[inline]
pub(super) fn prefetch_lines<T>(items: &[T]) {
    let (start, bytes) = (items.as_ptr().cast::<i8>(), std::mem::size_of_val(items));
    if bytes == 0 {
        return;
    }
    // From the start of the line holding the first byte, one address per line.
    let skip = start.addr() % LINE;
    for offset in (0..skip + bytes).step_by(LINE) {
        prefetch_address(start.wrapping_sub(skip).wrapping_add(offset));
    }
}

/// Asks the CPU to start loading the cache line holding `at`.
#[inline]
fn prefetch_address(at: *const i8) {
    #[cfg(x86_simd)]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        // SAFETY: a prefetch is only a hint: it never faults, whatever the address, and changes no
        // memory; SSE is part of every x86-64 CPU.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(at) };
    }
    #[cfg(not(x86_simd))]
    let _ = at;
}
