//! Light-path classes as answers: Heckbert's notation, graded by language equivalence with the
//! crate's grammar (so `LDD*E` and `LD+E` are the same answer).

use crate::render::analysis::grammar::{GrammarError, Lang, shortest_word, word_text};

/// A light-path class: Heckbert's notation as the crate's grammar reads it, or `none` (∅).
/// Letters are read in either case (`lds+e` is `LDS+E`), as the Q5 verdicts are: the notation's
/// letters are all capitals, so no answer changes meaning by it.
///
/// # Errors
/// [`GrammarError::Syntax`] with the expression (trimmed, in capitals), what was found and where,
/// when it is neither `none` nor a path expression.
pub(super) fn paths(source: &str) -> Result<Lang, GrammarError> {
    let trimmed = source.trim();
    if trimmed.eq_ignore_ascii_case("none") || trimmed == "∅" {
        return Ok(Lang::Empty);
    }
    Lang::parse(&trimmed.to_ascii_uppercase())
}

/// Whether `given` is the same class of paths as `key`; if not, the shortest path in one and
/// not the other, in words.
pub(super) fn compare_paths(key: &str, given: &str) -> (bool, String) {
    let (Ok(key_lang), Ok(given_lang)) = (paths(key), paths(given)) else {
        return (false, "not a light-path class".into());
    };
    match shortest_word(&[key_lang, given_lang], |x| x[0] != x[1]) {
        Ok(None) => (true, format!("the same paths as {key}")),
        Ok(Some(word)) => {
            let path = word_text(&word);
            let inside = paths(key).is_ok_and(|k| k.accepts(&word));
            if inside {
                (false, format!("the key's class {key} contains {path}, yours does not"))
            } else {
                (false, format!("yours contains {path}, the key's class {key} does not"))
            }
        }
        Err(e) => (false, format!("could not compare: {e}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equivalent_spellings_are_the_same_answer() {
        assert!(compare_paths("LD+E", "LDD*E").0);
        assert!(compare_paths("LD+E", "L(D)+E").0);
        assert!(compare_paths("none", "∅").0);
        assert!(compare_paths("L(D|G)E", "L[GD]E").0);
    }

    #[test]
    fn a_different_class_names_a_path_that_tells_them_apart() {
        let (ok, words) = compare_paths("LDD+E", "LD*E");
        assert!(!ok);
        assert!(words.contains("yours contains LE"), "{words}");
        let (ok, words) = compare_paths("LS+DE", "LSDE");
        assert!(!ok);
        assert!(words.contains("contains LSSDE, yours does not"), "{words}");
        assert!(!compare_paths("none", "LGE").0);
    }

    #[test]
    fn a_class_that_does_not_parse_is_a_syntax_error() {
        assert_eq!(paths(" None "), Ok(Lang::Empty));
        assert_eq!(paths("lds+e"), paths("LDS+E"));
        assert!(compare_paths("LGE", "lge").0);
        let error = paths(" L(D| ").unwrap_err();
        assert!(matches!(&error, GrammarError::Syntax { expression, .. } if expression == "L(D|"), "{error:?}");
    }
}
