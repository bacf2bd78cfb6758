//! "Did you mean": keys in the file that no part asks for, with the closest known key.

use super::key::Part;

pub(super) fn unknown_keys(table: &toml::Table, parts: &[&Part]) -> Vec<String> {
    let known: Vec<&str> = parts.iter().map(|p| p.key).collect();
    let mut unknown = Vec::new();
    for (section, value) in table {
        if section == "meta" {
            continue;
        }
        let Some(inner) = value.as_table() else {
            unknown.push(format!("`{section}` (answers go in tables such as [q2a])"));
            continue;
        };
        for name in inner.keys() {
            let key = format!("{section}.{name}");
            if known.contains(&key.as_str()) {
                continue;
            }
            let suggestion =
                known.iter().min_by_key(|k| edit_distance(k, &key)).filter(|k| edit_distance(k, &key) <= 3);
            unknown.push(match suggestion {
                Some(s) => format!("`{key}` (did you mean `{s}`?)"),
                None => format!("`{key}`"),
            });
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
    use crate::checker::check;

    #[test]
    fn misspelt_key_gets_a_suggestion() {
        let report = check("[q2a]\npiont = [1, 2, 3]\n[q2c]\nt_closet = 5.0\nwhatever = 1", None).unwrap();
        assert_eq!(
            report.unknown_keys,
            vec![
                "`q2a.piont` (did you mean `q2a.point`?)".to_string(),
                "`q2c.t_closet` (did you mean `q2c.t_closest`?)".to_string(),
                "`q2c.whatever`".to_string(),
            ]
        );
    }

    #[test]
    fn edit_distance_basics() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("same", "same"), 0);
    }
}
