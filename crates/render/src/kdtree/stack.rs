//! The traversal's stack of far cells, left unwritten until used.
//!
//! Every closest-hit walk keeps the far children it has still to visit on a fixed stack of
//! [`STACK`] entries (node, where its cell begins, where it ends). Declared as a plain array, it
//! was zeroed at the start of every ray: 64 entries of 24 bytes, 1.5 KB of stores per query. On
//! camera rays at N = 10⁵ (about 30 nodes and 75 sphere tests a ray) a profile put a sixth of the
//! walk's samples on those stores, for entries most rays never reach. Here the entries are
//! [`MaybeUninit`]: a slot is written when a cell is pushed, and only written slots are read.

use super::build::MAX_DEPTH;
use std::mem::MaybeUninit;

/// Entries a traversal stack holds. A walk pushes at most one cell per level it descends, so the
/// build's depth bound keeps pushes below it (checked when compiling, just below).
pub(super) const STACK: usize = 64;
const _: () = assert!(MAX_DEPTH < STACK, "the traversal stack must outgrow the deepest tree");

/// A far cell: its node and the ray interval `[cell_min, cell_max]` inside it, in the tree's
/// float type `T` (`f64` or `f32`).
pub(super) type Far<T> = (u32, T, T);

/// A stack of at most [`STACK`] far cells whose slots above the top are never read.
///
/// Invariant: `entries[..depth]` are written. Every way to raise `depth` writes the slot first,
/// so the reads below it are sound; a push past [`STACK`] panics at the index (the build's
/// depth bound makes that unreachable).
#[derive(Clone, Copy)]
pub(super) struct FarStack<T: Copy> {
    entries: [MaybeUninit<Far<T>>; STACK],
    depth: usize,
}

impl<T: Copy> FarStack<T> {
    /// An empty stack; nothing is written.
    #[inline(always)]
    pub fn new() -> Self {
        Self { entries: [const { MaybeUninit::uninit() }; STACK], depth: 0 }
    }

    /// Pushes `far`.
    ///
    /// # Panics
    /// If the stack already holds [`STACK`] entries.
    #[inline(always)]
    pub fn push(&mut self, far: Far<T>) {
        self.entries[self.depth] = MaybeUninit::new(far);
        self.depth += 1;
    }

    /// Writes `far` into the slot above the top and keeps it (a push) only when `keep`: the
    /// branch-free form of `if keep { push(far) }` for steps whose outcome is hard to guess.
    ///
    /// # Panics
    /// If the stack already holds [`STACK`] entries.
    #[inline(always)]
    pub fn push_if(&mut self, far: Far<T>, keep: bool) {
        self.entries[self.depth] = MaybeUninit::new(far);
        self.depth += usize::from(keep);
    }

    /// The top entry, or `None` when the stack is empty.
    #[inline(always)]
    pub fn top(&self) -> Option<&Far<T>> {
        let top = self.depth.checked_sub(1)?;
        // SAFETY: `top < depth`, and `entries[..depth]` are written (the type's invariant).
        Some(unsafe { self.entries[top].assume_init_ref() })
    }

    /// Removes and returns the top entry, or `None` when the stack is empty.
    #[inline(always)]
    pub fn pop(&mut self) -> Option<Far<T>> {
        let far = *self.top()?;
        self.depth -= 1;
        Some(far)
    }

    /// Empties the stack (its slots stay as they are, unread).
    #[inline(always)]
    pub fn clear(&mut self) {
        self.depth = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pushes_pop_in_reverse_and_a_kept_slot_only_when_asked() {
        let mut stack = FarStack::<f64>::new();
        assert!(stack.top().is_none() && stack.pop().is_none());
        stack.push((1, 0.5, 1.0));
        stack.push_if((2, 1.0, 2.0), false);
        stack.push_if((3, 1.5, 3.0), true);
        assert_eq!(stack.top(), Some(&(3, 1.5, 3.0)));
        assert_eq!(stack.pop(), Some((3, 1.5, 3.0)));
        assert_eq!(stack.pop(), Some((1, 0.5, 1.0)));
        assert_eq!(stack.pop(), None);
        stack.push((4, 0.0, 0.0));
        stack.clear();
        assert!(stack.top().is_none());
    }

    #[test]
    #[should_panic(expected = "index out of bounds")]
    fn a_push_past_the_capacity_panics_instead_of_writing_beyond() {
        let mut stack = FarStack::<f32>::new();
        for node in 0..=STACK as u32 {
            stack.push((node, 0.0, 0.0));
        }
    }
}
