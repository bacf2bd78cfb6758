//! "Did you mean": keys in the file that no part asks for, with the closest known key; a key close
//! enough to exactly one unanswered part is graded under that part.

use super::key::Part;
use super::reading::lookup;

/// The largest edit distance at which a misspelt key is graded under the part it suggests
/// (a suggestion alone goes up to 3).
const GRADED_DISTANCE: usize = 2;

/// A key of the file that no part asks for.
pub(super) struct Unknown {
    /// How the report lists it.
    pub described: String,
    /// The file's key (`q2a.tt`), when it is one inside a table.
    pub key: Option<String>,
    /// The one unanswered part it is graded under, when its spelling points to exactly one.
    pub graded_as: Option<&'static str>,
}

pub(super) fn unknown_keys(table: &toml::Table, parts: &[&Part]) -> Vec<Unknown> {
    let known: Vec<&'static str> = parts.iter().map(|p| p.key).collect();
    let mut unknown = Vec::new();
    for (section, value) in table {
        if section == "meta" {
            continue;
        }
        let Some(inner) = value.as_table() else {
            let described = format!("`{section}` (answers go in tables such as [q2a])");
            unknown.push(Unknown { described, key: None, graded_as: None });
            continue;
        };
        for name in inner.keys() {
            let key = format!("{section}.{name}");
            if known.contains(&key.as_str()) {
                continue;
            }
            let nearest = known.iter().map(|k| edit_distance(k, &key)).min().filter(|&d| d <= 3);
            let candidates: Vec<&'static str> =
                known.iter().copied().filter(|k| Some(edit_distance(k, &key)) == nearest).collect();
            let described = match candidates.first() {
                Some(s) => format!("`{key}` (did you mean `{s}`?)"),
                None => format!("`{key}`"),
            };
            let graded_as = match (candidates.as_slice(), nearest) {
                ([only], Some(d)) if d <= GRADED_DISTANCE && lookup(table, only).is_none() => Some(*only),
                _ => None,
            };
            unknown.push(Unknown { described, key: Some(key), graded_as });
        }
    }
    // Two misspellings of one part: neither is graded (which one meant it is a guess).
    let targets: Vec<&'static str> = unknown.iter().filter_map(|u| u.graded_as).collect();
    for u in &mut unknown {
        if u.graded_as.is_some_and(|t| targets.iter().filter(|&&x| x == t).count() > 1) {
            u.graded_as = None;
        }
    }
    unknown
}

/// Levenshtein distance, for "did you mean" suggestions.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut previous = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitution = previous + usize::from(ca != cb);
            previous = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(previous + 1);
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_basics() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("same", "same"), 0);
    }
}
