//! Heckbert's light-path notation as regular languages, decided by position automata.
//!
//! A light path is a word over the letters `L D G S V E` (light, diffuse, glossy, specular,
//! volume scattering, eye), written light first. A [`Lang`] is a regular expression over them;
//! [`shortest_word`] runs the automata of several languages side by side, breadth first, and
//! returns the shortest word whose acceptance pattern satisfies a predicate — inclusion ("a path
//! of A that B misses"), intersection ("a path both contain") and emptiness are all this one
//! search. The renderer's pass plan ([`super::analyze`]) and the Q5 effect tables use this engine,
//! and so does the checker on a student's answer, which is why its cost is bounded:
//!
//! - an expression is at most [`MAX_LENGTH`] characters with at most [`MAX_DEPTH`] nested
//!   parentheses, and is read in one pass (each sequence is built from its right end, so no step
//!   re-walks what came before);
//! - each language becomes Glushkov's position automaton (Berry & Sethi 1986, §2): one state per letter
//!   occurrence, built in time bounded by the expression's length times its number of letters;
//! - the search determinises the automata on the fly (a state is a set of positions per language,
//!   a bit set) and stops with [`GrammarError::TooManyStates`] past [`MAX_STATES`] sets. A
//!   determinised automaton can need exponentially many sets (`L(D|G)*D(D|G)(D|G)…E` needs
//!   2ᵏ for k groups, McNaughton & Yamada 1960); the guard turns that into a refusal with its
//!   reason, in bounded time and memory.

mod automaton;

use automaton::Automaton;
use std::collections::{BTreeSet, HashMap};
use std::fmt;

/// One vertex type of a light path.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub enum Letter {
    /// A light source (first vertex).
    L,
    /// A diffuse (Lambertian) reflection.
    D,
    /// A glossy reflection (a Phong lobe: a highlight).
    G,
    /// A specular (delta) reflection or refraction: mirror, glass.
    S,
    /// A scattering event in a participating medium.
    V,
    /// The eye (last vertex).
    E,
}

impl Letter {
    /// Every letter, in alphabet order.
    pub const ALL: [Letter; 6] = [Letter::L, Letter::D, Letter::G, Letter::S, Letter::V, Letter::E];

    /// The letter's character.
    #[must_use]
    pub fn symbol(self) -> char {
        match self {
            Letter::L => 'L',
            Letter::D => 'D',
            Letter::G => 'G',
            Letter::S => 'S',
            Letter::V => 'V',
            Letter::E => 'E',
        }
    }

    fn from_symbol(c: char) -> Option<Self> {
        Letter::ALL.into_iter().find(|l| l.symbol() == c)
    }
}

/// A word (a light path) printed as letters, `"LDSE"`.
#[must_use]
pub fn word_text(word: &[Letter]) -> String {
    word.iter().map(|l| l.symbol()).collect()
}

/// A regular language over [`Letter`]s, kept in a normal form by the smart constructors.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Lang {
    /// No word at all (∅).
    Empty,
    /// Only the empty word (ε).
    Epsilon,
    /// One one-letter word.
    Letter(Letter),
    /// `A B`, right-associated.
    Concat(Box<Lang>, Box<Lang>),
    /// `A | B | …`: two or more alternatives, sorted and distinct, none a union.
    Union(BTreeSet<Lang>),
    /// `A*`.
    Star(Box<Lang>),
}

/// Why a path expression or a search failed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum GrammarError {
    /// The expression has a character that is not a letter or operator, at `position` (chars).
    #[error("path expression {expression:?}: unexpected {found:?} at position {position}")]
    Syntax {
        /// The whole expression.
        expression: String,
        /// What was found (`"end"` at the end).
        found: String,
        /// Character index.
        position: usize,
    },
    /// The expression is longer than [`MAX_LENGTH`] characters (spaces not counted).
    #[error("path expression of {length} characters: at most {MAX_LENGTH} are read")]
    TooLong {
        /// Its length in characters, without spaces.
        length: usize,
    },
    /// The expression nests parentheses deeper than [`MAX_DEPTH`].
    #[error("path expression nests parentheses more than {MAX_DEPTH} deep (at position {position})")]
    TooDeep {
        /// Character index of the first parenthesis past the limit.
        position: usize,
    },
    /// Telling the languages apart needs more than [`MAX_STATES`] sets of positions (never for
    /// the crate's languages; an expression that repeats a choice after a star can).
    #[error("comparing these classes needs more than {0} automaton states; write the class more simply")]
    TooManyStates(usize),
}

/// The longest expression read, in characters without spaces: the crate's classes are under 20,
/// and a student's answer that needs more is refused with [`GrammarError::TooLong`].
pub const MAX_LENGTH: usize = 256;

/// The deepest nesting of parentheses read.
pub const MAX_DEPTH: usize = 32;

/// Guard on the number of determinised states (one set of positions per language) a search
/// visits. It bounds a search's memory by `MAX_STATES` tuples of sets and its time by that times
/// six letters times one step per position; the README's table of bounds gives the measured cost
/// of the worst answer the checker reads.
pub const MAX_STATES: usize = 50_000;

impl Lang {
    /// One letter.
    #[must_use]
    pub fn letter(l: Letter) -> Self {
        Lang::Letter(l)
    }

    /// `a b` in normal form (∅ absorbs, ε is the unit, right-associated).
    #[must_use]
    pub fn concat(a: Lang, b: Lang) -> Self {
        match (a, b) {
            (Lang::Empty, _) | (_, Lang::Empty) => Lang::Empty,
            (Lang::Epsilon, x) | (x, Lang::Epsilon) => x,
            (Lang::Concat(a1, a2), b) => Lang::concat(*a1, Lang::concat(*a2, b)),
            (a, b) => Lang::Concat(Box::new(a), Box::new(b)),
        }
    }

    /// `a | b` in normal form (flattened, sorted, deduplicated, ∅ dropped).
    #[must_use]
    pub fn union(a: Lang, b: Lang) -> Self {
        let mut set = BTreeSet::new();
        for part in [a, b] {
            match part {
                Lang::Empty => {}
                Lang::Union(parts) => set.extend(parts),
                other => {
                    set.insert(other);
                }
            }
        }
        match set.len() {
            0 => Lang::Empty,
            1 => set.into_iter().next().unwrap_or(Lang::Empty),
            _ => Lang::Union(set),
        }
    }

    /// `a*` in normal form (`∅* = ε* = ε`, `(a*)* = a*`).
    #[must_use]
    pub fn star(a: Lang) -> Self {
        match a {
            Lang::Empty | Lang::Epsilon => Lang::Epsilon,
            s @ Lang::Star(_) => s,
            other => Lang::Star(Box::new(other)),
        }
    }

    /// `a+ = a a*`.
    #[must_use]
    pub fn plus(a: Lang) -> Self {
        Lang::concat(a.clone(), Lang::star(a))
    }

    /// `a? = ε | a`.
    #[must_use]
    pub fn optional(a: Lang) -> Self {
        Lang::union(Lang::Epsilon, a)
    }

    /// Any one of `letters`.
    #[must_use]
    pub fn any_of(letters: &[Letter]) -> Self {
        letters.iter().fold(Lang::Empty, |acc, &l| Lang::union(acc, Lang::Letter(l)))
    }

    /// Whether `word` is in the language.
    #[must_use]
    pub fn accepts(&self, word: &[Letter]) -> bool {
        Automaton::new(self).accepts_word(word)
    }

    /// Parses Heckbert's notation: letters `LDGSVE`, `|`, postfix `*`, `+`, `?`, parentheses,
    /// classes `[DGS]`, and `…` (or `...`) for any sequence of letters. Spaces are ignored.
    ///
    /// # Errors
    /// [`GrammarError::Syntax`] at the first unexpected character; [`GrammarError::TooLong`]
    /// past [`MAX_LENGTH`] characters and [`GrammarError::TooDeep`] past [`MAX_DEPTH`] nested
    /// parentheses, checked before or while reading so that no input costs more than those allow.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::render::analysis::grammar::{Lang, Letter::*};
    /// let radiosity = Lang::parse("LD*E").unwrap();
    /// assert!(radiosity.accepts(&[L, D, D, E]));
    /// assert!(!radiosity.accepts(&[L, S, D, E]));
    /// assert!(Lang::parse("L(D|").is_err());
    /// ```
    pub fn parse(expression: &str) -> Result<Self, GrammarError> {
        let chars: Vec<char> = expression.replace("...", "…").chars().filter(|c| !c.is_whitespace()).collect();
        if chars.len() > MAX_LENGTH {
            return Err(GrammarError::TooLong { length: chars.len() });
        }
        let mut parser = Parser { expression, chars: &chars, at: 0, depth: 0 };
        let lang = parser.alternation()?;
        match parser.peek() {
            None => Ok(lang),
            Some(_) => Err(parser.error()),
        }
    }
}

impl fmt::Display for Lang {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Lang::Empty => write!(f, "∅"),
            Lang::Epsilon => write!(f, "ε"),
            Lang::Letter(l) => write!(f, "{}", l.symbol()),
            Lang::Concat(a, b) => write!(f, "{a}{b}"),
            Lang::Union(parts) => {
                let texts: Vec<String> = parts.iter().map(ToString::to_string).collect();
                write!(f, "({})", texts.join("|"))
            }
            Lang::Star(a) => match **a {
                Lang::Letter(l) => write!(f, "{}*", l.symbol()),
                Lang::Union(_) => write!(f, "{a}*"),
                _ => write!(f, "({a})*"),
            },
        }
    }
}

struct Parser<'a> {
    expression: &'a str,
    chars: &'a [char],
    at: usize,
    /// Open parentheses around `at`.
    depth: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Option<char> {
        self.chars.get(self.at).copied()
    }

    fn error(&self) -> GrammarError {
        GrammarError::Syntax {
            expression: self.expression.to_string(),
            found: self.peek().map_or_else(|| "end".to_string(), |c| c.to_string()),
            position: self.at,
        }
    }

    fn alternation(&mut self) -> Result<Lang, GrammarError> {
        let mut lang = self.sequence()?;
        while self.peek() == Some('|') {
            self.at += 1;
            lang = Lang::union(lang, self.sequence()?);
        }
        Ok(lang)
    }

    fn sequence(&mut self) -> Result<Lang, GrammarError> {
        let mut atoms = Vec::new();
        while let Some(c) = self.peek() {
            if c == '|' || c == ')' {
                break;
            }
            let mut atom = self.atom()?;
            while let Some(op) = self.peek() {
                atom = match op {
                    '*' => Lang::star(atom),
                    '+' => Lang::plus(atom),
                    '?' => Lang::optional(atom),
                    _ => break,
                };
                self.at += 1;
            }
            atoms.push(atom);
        }
        if atoms.is_empty() {
            return Err(self.error());
        }
        // From the right end, so that each step prepends one atom to a right-associated chain.
        Ok(atoms.into_iter().rev().fold(Lang::Epsilon, |rest, atom| Lang::concat(atom, rest)))
    }

    fn atom(&mut self) -> Result<Lang, GrammarError> {
        let c = self.peek().ok_or_else(|| self.error())?;
        if let Some(letter) = Letter::from_symbol(c) {
            self.at += 1;
            return Ok(Lang::letter(letter));
        }
        match c {
            '…' => {
                self.at += 1;
                Ok(Lang::star(Lang::any_of(&Letter::ALL)))
            }
            '(' => {
                if self.depth == MAX_DEPTH {
                    return Err(GrammarError::TooDeep { position: self.at });
                }
                self.at += 1;
                self.depth += 1;
                let inner = self.alternation()?;
                self.depth -= 1;
                if self.peek() != Some(')') {
                    return Err(self.error());
                }
                self.at += 1;
                Ok(inner)
            }
            '[' => {
                self.at += 1;
                let mut letters = Vec::new();
                while let Some(letter) = self.peek().and_then(Letter::from_symbol) {
                    letters.push(letter);
                    self.at += 1;
                }
                if letters.is_empty() || self.peek() != Some(']') {
                    return Err(self.error());
                }
                self.at += 1;
                Ok(Lang::any_of(&letters))
            }
            _ => Err(self.error()),
        }
    }
}

/// A tuple of position sets, and the tuple (by index) and letter it was first reached from.
type Reached = (Box<[u64]>, Option<(usize, Letter)>);

/// The shortest word `w` (ties broken by alphabet order) for which `wanted` holds of the vector
/// "language k accepts w", or `None` when no word does.
///
/// # Numerics
/// A breadth-first search over tuples of position sets, one per language (the subset
/// construction, run only as far as the search goes): letters are tried in alphabet order and
/// each tuple is kept with the first word that reached it, so the first tuple that satisfies
/// `wanted` gives the shortest word and, among those, the first in alphabet order. Each step costs
/// the languages' lengths times their positions over 64; the number of tuples is capped.
///
/// # Errors
/// [`GrammarError::TooManyStates`] past [`MAX_STATES`] tuples.
///
/// # Examples
/// ```
/// use hw3_render::render::analysis::grammar::{shortest_word, word_text, Lang};
/// let radiosity = Lang::parse("LD*E").unwrap();
/// let highlight = Lang::parse("LGE").unwrap();
/// // A path of the highlight that radiosity misses:
/// let missed = shortest_word(&[highlight, radiosity], |acc| acc[0] && !acc[1]).unwrap();
/// assert_eq!(missed.map(|w| word_text(&w)), Some("LGE".to_string()));
/// ```
pub fn shortest_word(
    languages: &[Lang],
    wanted: impl Fn(&[bool]) -> bool,
) -> Result<Option<Vec<Letter>>, GrammarError> {
    let automata: Vec<Automaton> = languages.iter().map(Automaton::new).collect();
    // A tuple of sets is stored as one bit vector, the languages' sets end to end.
    let offsets: Vec<usize> = automata
        .iter()
        .scan(0, |at, a| {
            let start = *at;
            *at += a.width();
            Some(start)
        })
        .collect();
    let width: usize = automata.iter().map(Automaton::width).sum();
    let start: Vec<u64> = automata.iter().flat_map(Automaton::start).collect();
    // Every tuple met, with the tuple and letter it was first reached from.
    let mut tuples: Vec<Reached> = vec![(start.clone().into(), None)];
    let mut index: HashMap<Box<[u64]>, usize> = HashMap::from([(start.into(), 0)]);
    let mut next = vec![0; width];
    let mut at = 0;
    while at < tuples.len() {
        let state = tuples[at].0.clone();
        let accepts: Vec<bool> =
            automata.iter().zip(&offsets).map(|(a, &o)| a.accepts(&state[o..o + a.width()])).collect();
        if wanted(&accepts) {
            let mut word = Vec::new();
            let mut back = at;
            while let Some((previous, letter)) = tuples[back].1 {
                word.push(letter);
                back = previous;
            }
            word.reverse();
            return Ok(Some(word));
        }
        if state.iter().all(|w| *w == 0) {
            at += 1;
            continue;
        }
        for letter in Letter::ALL {
            for (a, &o) in automata.iter().zip(&offsets) {
                let w = a.width();
                a.step(&state[o..o + w], letter, &mut next[o..o + w]);
            }
            if !index.contains_key(next.as_slice()) {
                if tuples.len() >= MAX_STATES {
                    return Err(GrammarError::TooManyStates(MAX_STATES));
                }
                let key: Box<[u64]> = next.clone().into();
                index.insert(key.clone(), tuples.len());
                tuples.push((key, Some((at, letter))));
            }
        }
        at += 1;
    }
    Ok(None)
}

/// The shortest word in both `a` and `b`, if the languages meet.
///
/// # Errors
/// As [`shortest_word`].
pub fn common_word(a: &Lang, b: &Lang) -> Result<Option<Vec<Letter>>, GrammarError> {
    shortest_word(&[a.clone(), b.clone()], |acc| acc[0] && acc[1])
}

#[cfg(test)]
mod tests {
    use super::Letter::*;
    use super::*;
    use proptest::prelude::*;

    fn parse(text: &str) -> Lang {
        Lang::parse(text).unwrap()
    }

    /// Same language: no word in the symmetric difference.
    fn equivalent(a: &str, b: &str) -> bool {
        shortest_word(&[parse(a), parse(b)], |x| x[0] != x[1]).unwrap().is_none()
    }

    #[test]
    fn parser_reads_heckbert_forms_and_rejects_garbage() {
        assert!(equivalent("L(D|G)?S+E", "LS+E|LDS+E|LGS+E"));
        assert!(!equivalent("L(D|G)?S+E", "L(D|G)S+E"));
        assert_eq!(parse("[DG]"), parse("G|D"));
        assert!(equivalent("L(S*D)*S*E", "L(D|S)*E"), "Heckbert's two forms of his method");
        assert!(parse("LS+(D|G)…E").accepts(&[L, S, D, V, S, E]));
        assert!(parse("LS+(D|G)...E").accepts(&[L, S, G, E]));
        for bad in ["", "L(D", "LX", "L|", "[]", "L)"] {
            assert!(Lang::parse(bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn shortest_missed_paths_are_the_ones_the_note_prints() {
        let radiosity = parse("LD*E");
        let missed = |effect: &str| {
            shortest_word(&[parse(effect), radiosity.clone()], |a| a[0] && !a[1]).unwrap().map(|w| word_text(&w))
        };
        assert_eq!(missed("LGE").as_deref(), Some("LGE"));
        assert_eq!(missed("LDS+E").as_deref(), Some("LDSE"));
        assert_eq!(missed("LS+DE").as_deref(), Some("LSDE"));
        assert_eq!(missed("LDD+E"), None);
        assert_eq!(common_word(&parse("LS+E"), &radiosity).unwrap(), None);
    }

    #[test]
    fn long_or_deep_expressions_are_refused_before_any_work() {
        let long = format!("L{}E", "D".repeat(MAX_LENGTH));
        assert_eq!(Lang::parse(&long), Err(GrammarError::TooLong { length: MAX_LENGTH + 2 }));
        let spaced = format!("L {} E", "D ".repeat(MAX_LENGTH - 2));
        assert!(Lang::parse(&spaced).is_ok(), "spaces are not counted");
        let deep = format!("{}L{}", "(".repeat(MAX_DEPTH + 1), ")".repeat(MAX_DEPTH + 1));
        assert_eq!(Lang::parse(&deep), Err(GrammarError::TooDeep { position: MAX_DEPTH }));
        let deepest = format!("{}L{}", "(".repeat(MAX_DEPTH), ")".repeat(MAX_DEPTH));
        assert_eq!(Lang::parse(&deepest), Ok(Lang::letter(L)));
    }

    #[test]
    fn a_choice_repeated_after_a_star_is_refused_at_the_state_limit() {
        // L(D|G)*D(D|G)^k E tells L D^(k+1) E from LGE only after 2^(k+1) position sets.
        let blow_up = |k: usize| parse(&format!("LGE|L(D|G)*D{}E", "(D|G)".repeat(k)));
        let small = shortest_word(&[parse("LGE"), blow_up(4)], |x| x[0] != x[1]).unwrap();
        assert_eq!(small.map(|w| word_text(&w)).as_deref(), Some("LDDDDDE"));
        let big = shortest_word(&[parse("LGE"), blow_up(40)], |x| x[0] != x[1]);
        assert_eq!(big, Err(GrammarError::TooManyStates(MAX_STATES)));
    }

    /// Every word up to `length` letters over the alphabet.
    fn words(length: usize) -> Vec<Vec<Letter>> {
        let mut all = vec![vec![]];
        let mut frontier = vec![vec![]];
        for _ in 0..length {
            frontier = frontier
                .iter()
                .flat_map(|w: &Vec<Letter>| Letter::ALL.map(|l| [w.clone(), vec![l]].concat()))
                .collect();
            all.extend(frontier.iter().cloned());
        }
        all
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]
        /// The search agrees with brute-force enumeration of all words up to 4 letters.
        #[test]
        fn inclusion_search_agrees_with_enumeration(a in 0usize..8, b in 0usize..8) {
            const FORMS: [&str; 8] = ["LD*E", "L(D|G)?S*E", "LS+DE", "L(D|G|S)*E", "LDD+E", "L(D|G)E|L(D|S)*DE", "LGE", "L[DG][DGS]*E"];
            let (la, lb) = (parse(FORMS[a]), parse(FORMS[b]));
            let found = shortest_word(&[la.clone(), lb.clone()], |x| x[0] && !x[1]).unwrap();
            let brute = words(4).into_iter().find(|w| la.accepts(w) && !lb.accepts(w));
            if let Some(w) = &found {
                prop_assert!(la.accepts(w) && !lb.accepts(w));
            }
            match (&found, &brute) {
                (Some(f), Some(b)) => prop_assert!(f.len() <= b.len()),
                (None, Some(b)) => prop_assert!(false, "missed {}", word_text(b)),
                _ => {}
            }
        }
    }
}
