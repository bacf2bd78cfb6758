//! Glushkov's position automaton of a [`Lang`], and sets of its states as bit sets.
//!
//! Every occurrence of a letter in the expression is a *position*; position 0 stands before the
//! first letter. The automaton reads a letter `c` by moving from a position to each position that
//! may follow it in some word and holds `c`. Three sets per sub-expression decide which those are
//! (Glushkov 1961; Berry & Sethi, *Theoretical Computer Science* 48, 1986, §2):
//! - `first`: the positions a word of the sub-expression can start with;
//! - `last`: the positions it can end with;
//! - `nullable`: whether it holds the empty word.
//!
//! In `A B` every last position of `A` is followed by every first position of `B`; in `A*` every
//! last position of `A` is followed by every first position of `A`. The automaton has one state
//! per position plus the start, so it is built in time and memory bounded by the expression's
//! length (times the number of positions, for the follow sets), with no blow-up: a determinised
//! state is a *set* of positions, built only when the search of [`super::shortest_word`] reaches it.

use super::{Lang, Letter};

/// A set of positions, one bit each.
pub(super) type Bits = Vec<u64>;

fn empty(width: usize) -> Bits {
    vec![0; width]
}

fn insert(bits: &mut [u64], position: usize) {
    bits[position / 64] |= 1 << (position % 64);
}

#[cfg(test)]
fn contains(bits: &[u64], position: usize) -> bool {
    bits[position / 64] & (1 << (position % 64)) != 0
}

fn union_into(into: &mut [u64], from: &[u64]) {
    for (a, b) in into.iter_mut().zip(from) {
        *a |= b;
    }
}

/// The positions in `bits`, ascending.
fn members(bits: &[u64]) -> impl Iterator<Item = usize> + '_ {
    bits.iter().enumerate().flat_map(|(word, &w)| {
        let mut rest = w;
        std::iter::from_fn(move || {
            (rest != 0).then(|| {
                let bit = rest.trailing_zeros() as usize;
                rest &= rest - 1;
                word * 64 + bit
            })
        })
    })
}

/// The position automaton of one language.
#[derive(Debug, Clone)]
pub(super) struct Automaton {
    /// Words per set of positions.
    width: usize,
    /// For each position (0 is the start), the positions that may follow it.
    follow: Vec<Bits>,
    /// For each letter of [`Letter::ALL`], the positions that hold it.
    holding: [Bits; 6],
    /// The positions a word may end at (the start too when the language holds the empty word).
    accepting: Bits,
}

/// What the construction knows of a sub-expression.
struct Sets {
    nullable: bool,
    first: Bits,
    last: Bits,
}

fn letter_index(letter: Letter) -> usize {
    Letter::ALL.iter().position(|l| *l == letter).unwrap_or(0)
}

fn count_letters(lang: &Lang) -> usize {
    match lang {
        Lang::Empty | Lang::Epsilon => 0,
        Lang::Letter(_) => 1,
        Lang::Concat(a, b) => count_letters(a) + count_letters(b),
        Lang::Union(parts) => parts.iter().map(count_letters).sum(),
        Lang::Star(a) => count_letters(a),
    }
}

impl Automaton {
    /// The automaton of `lang`: `1 + n` states for `n` letter occurrences.
    pub(super) fn new(lang: &Lang) -> Self {
        let positions = 1 + count_letters(lang);
        let width = positions.div_ceil(64);
        let mut automaton = Automaton {
            width,
            follow: vec![empty(width); positions],
            holding: std::array::from_fn(|_| empty(width)),
            accepting: empty(width),
        };
        let mut next = 1;
        let sets = automaton.walk(lang, &mut next);
        automaton.follow[0] = sets.first;
        automaton.accepting = sets.last;
        if sets.nullable {
            insert(&mut automaton.accepting, 0);
        }
        automaton
    }

    fn walk(&mut self, lang: &Lang, next: &mut usize) -> Sets {
        let width = self.width;
        match lang {
            Lang::Empty | Lang::Epsilon => {
                Sets { nullable: matches!(lang, Lang::Epsilon), first: empty(width), last: empty(width) }
            }
            Lang::Letter(letter) => {
                let position = *next;
                *next += 1;
                insert(&mut self.holding[letter_index(*letter)], position);
                let mut only = empty(width);
                insert(&mut only, position);
                Sets { nullable: false, first: only.clone(), last: only }
            }
            Lang::Concat(a, b) => {
                let a = self.walk(a, next);
                let b = self.walk(b, next);
                for p in members(&a.last) {
                    union_into(&mut self.follow[p], &b.first);
                }
                let mut first = a.first;
                if a.nullable {
                    union_into(&mut first, &b.first);
                }
                let mut last = b.last;
                if b.nullable {
                    union_into(&mut last, &a.last);
                }
                Sets { nullable: a.nullable && b.nullable, first, last }
            }
            Lang::Union(parts) => {
                let mut sets = Sets { nullable: false, first: empty(width), last: empty(width) };
                for part in parts {
                    let part = self.walk(part, next);
                    sets.nullable |= part.nullable;
                    union_into(&mut sets.first, &part.first);
                    union_into(&mut sets.last, &part.last);
                }
                sets
            }
            Lang::Star(a) => {
                let a = self.walk(a, next);
                for p in members(&a.last) {
                    union_into(&mut self.follow[p], &a.first);
                }
                Sets { nullable: true, first: a.first, last: a.last }
            }
        }
    }

    /// Words per set of positions.
    pub(super) fn width(&self) -> usize {
        self.width
    }

    /// The set holding only the start.
    pub(super) fn start(&self) -> Bits {
        let mut start = empty(self.width);
        insert(&mut start, 0);
        start
    }

    /// The positions reached from any of `from` by reading `letter`, written into `into`.
    pub(super) fn step(&self, from: &[u64], letter: Letter, into: &mut [u64]) {
        into.fill(0);
        for p in members(from) {
            union_into(into, &self.follow[p]);
        }
        for (a, b) in into.iter_mut().zip(&self.holding[letter_index(letter)]) {
            *a &= b;
        }
    }

    /// Whether a word that leads to `set` is in the language.
    pub(super) fn accepts(&self, set: &[u64]) -> bool {
        set.iter().zip(&self.accepting).any(|(a, b)| a & b != 0)
    }

    /// Whether `word` is in the language.
    pub(super) fn accepts_word(&self, word: &[Letter]) -> bool {
        let mut set = self.start();
        let mut next = empty(self.width);
        for &letter in word {
            self.step(&set, letter, &mut next);
            std::mem::swap(&mut set, &mut next);
        }
        self.accepts(&set)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn follow_sets_are_glushkovs() {
        // L(D|G)*E: positions 1 L, 2 D, 3 G, 4 E.
        let automaton = Automaton::new(&Lang::parse("L(D|G)*E").unwrap());
        let set = |bits: &Bits| members(bits).collect::<Vec<_>>();
        assert_eq!(set(&automaton.follow[0]), [1]);
        assert_eq!(set(&automaton.follow[1]), [2, 3, 4]);
        assert_eq!(set(&automaton.follow[2]), [2, 3, 4]);
        assert_eq!(set(&automaton.follow[4]), Vec::<usize>::new());
        assert_eq!(set(&automaton.accepting), [4]);
        assert!(contains(&automaton.holding[letter_index(Letter::G)], 3));
    }

    #[test]
    fn sets_wider_than_one_word_keep_every_position() {
        let long = format!("L{}E", "D".repeat(130));
        let automaton = Automaton::new(&Lang::parse(&long).unwrap());
        let mut word = vec![Letter::L];
        word.extend(std::iter::repeat_n(Letter::D, 130));
        word.push(Letter::E);
        assert!(automaton.accepts_word(&word));
        word.remove(1);
        assert!(!automaton.accepts_word(&word));
    }
}
