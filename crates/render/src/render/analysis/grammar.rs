//! Heckbert's light-path notation as regular languages, decided by Brzozowski derivatives.
//!
//! A light path is a word over the letters `L D G S V E` (light, diffuse, glossy, specular,
//! volume scattering, eye), written light first. A [`Lang`] is a regular expression over them;
//! [`shortest_word`] walks the derivatives of several languages at once, breadth first, and returns
//! the shortest word whose acceptance pattern satisfies a predicate — inclusion ("a path of A that
//! B misses"), intersection ("a path both contain") and emptiness are all this one search. The
//! renderer's pass plan ([`super::analyze`]) and the Q5 effect tables use this engine.
//!
//! Derivatives stay finitely many because unions are kept flattened, sorted and deduplicated and
//! concatenation is right-associated (Brzozowski, JACM 1964); the search still stops with
//! [`GrammarError::TooManyStates`] past [`MAX_STATES`] as a guard.

use std::collections::{BTreeMap, BTreeSet, VecDeque};
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
    /// The derivative search met more than [`MAX_STATES`] states (never for the crate's languages).
    #[error("derivative search exceeded {0} states")]
    TooManyStates(usize),
}

/// Guard on the number of derivative tuples a search visits.
pub const MAX_STATES: usize = 100_000;

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

    /// Whether the empty word is in the language.
    #[must_use]
    pub fn nullable(&self) -> bool {
        match self {
            Lang::Empty | Lang::Letter(_) => false,
            Lang::Epsilon | Lang::Star(_) => true,
            Lang::Concat(a, b) => a.nullable() && b.nullable(),
            Lang::Union(parts) => parts.iter().any(Lang::nullable),
        }
    }

    /// The Brzozowski derivative: the words `w` with `letter·w` in the language.
    #[must_use]
    pub fn derivative(&self, letter: Letter) -> Self {
        match self {
            Lang::Empty | Lang::Epsilon => Lang::Empty,
            Lang::Letter(l) => {
                if *l == letter {
                    Lang::Epsilon
                } else {
                    Lang::Empty
                }
            }
            Lang::Concat(a, b) => {
                let first = Lang::concat(a.derivative(letter), (**b).clone());
                if a.nullable() { Lang::union(first, b.derivative(letter)) } else { first }
            }
            Lang::Union(parts) => parts.iter().fold(Lang::Empty, |acc, p| Lang::union(acc, p.derivative(letter))),
            Lang::Star(a) => Lang::concat(a.derivative(letter), self.clone()),
        }
    }

    /// Whether `word` is in the language.
    #[must_use]
    pub fn accepts(&self, word: &[Letter]) -> bool {
        word.iter().fold(self.clone(), |lang, &l| lang.derivative(l)).nullable()
    }

    /// Parses Heckbert's notation: letters `LDGSVE`, `|`, postfix `*`, `+`, `?`, parentheses,
    /// classes `[DGS]`, and `…` (or `...`) for any sequence of letters. Spaces are ignored.
    ///
    /// # Errors
    /// [`GrammarError::Syntax`] at the first unexpected character.
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
        let mut parser = Parser { expression, chars: &chars, at: 0 };
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
        let mut lang = Lang::Epsilon;
        let mut any = false;
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
            lang = Lang::concat(lang, atom);
            any = true;
        }
        if any { Ok(lang) } else { Err(self.error()) }
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
                self.at += 1;
                let inner = self.alternation()?;
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

/// The shortest word `w` (ties broken by alphabet order) for which `wanted` holds of the vector
/// "language k accepts w", or `None` when no word does.
///
/// # Errors
/// [`GrammarError::TooManyStates`] past [`MAX_STATES`] derivative tuples.
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
    let start: Vec<Lang> = languages.to_vec();
    let mut parent: BTreeMap<Vec<Lang>, Option<(Vec<Lang>, Letter)>> = BTreeMap::new();
    parent.insert(start.clone(), None);
    let mut queue = VecDeque::from([start]);
    while let Some(state) = queue.pop_front() {
        let accepts: Vec<bool> = state.iter().map(Lang::nullable).collect();
        if wanted(&accepts) {
            let mut word = Vec::new();
            let mut at = &state;
            while let Some(Some((previous, letter))) = parent.get(at) {
                word.push(*letter);
                at = previous;
            }
            word.reverse();
            return Ok(Some(word));
        }
        if state.iter().all(|l| *l == Lang::Empty) {
            continue;
        }
        for letter in Letter::ALL {
            let next: Vec<Lang> = state.iter().map(|l| l.derivative(letter)).collect();
            if !parent.contains_key(&next) {
                if parent.len() >= MAX_STATES {
                    return Err(GrammarError::TooManyStates(MAX_STATES));
                }
                parent.insert(next.clone(), Some((state.clone(), letter)));
                queue.push_back(next);
            }
        }
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
