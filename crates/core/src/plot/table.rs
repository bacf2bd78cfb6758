//! One markdown-table writer, for the tables the chapters include among their figures, and its
//! reader, for the code and tests that read numbers back from a committed table.
//!
//! No table crate is used: the ones on crates.io pad columns to equal widths, and the committed
//! tables are unpadded (`| a | b |`), which keeps their diffs to the cells that changed.

use std::fmt::Write;

/// A GitHub-flavoured markdown table: the header row, the `|---|` rule, then one line per row, each
/// ending in a newline. Cells are written as given (a `|` inside a cell must already be escaped).
///
/// # Panics
/// If a row's cell count differs from the header's.
///
/// # Examples
/// ```
/// let table = hw3_core::plot::markdown_table(&["n", "n²"], (1..=2).map(|n| vec![n.to_string(), (n * n).to_string()]));
/// assert_eq!(table, "| n | n² |\n|---|---|\n| 1 | 1 |\n| 2 | 4 |\n");
/// ```
#[must_use]
pub fn markdown_table<I, R, C>(header: &[&str], rows: I) -> String
where
    I: IntoIterator<Item = R>,
    R: IntoIterator<Item = C>,
    C: AsRef<str>,
{
    let mut out = format!("| {} |\n|{}\n", header.join(" | "), "---|".repeat(header.len()));
    for row in rows {
        let cells: Vec<C> = row.into_iter().collect();
        assert_eq!(cells.len(), header.len(), "a row has as many cells as the header");
        out.push('|');
        for cell in &cells {
            let _ = write!(out, " {} |", cell.as_ref());
        }
        out.push('\n');
    }
    out
}

/// The body rows of the markdown tables in `text`, each split at `|` into trimmed cells: every
/// line that starts with `|`, except each table's header row and its `|---|` rule. Lines that are
/// not table rows end a table, so several tables in one text are all read.
///
/// # Examples
/// ```
/// let text = "| n | n² |\n|---|---|\n| 1 | 1 |\n| 2 | 4 |\n\ntext\n\n| a |\n|---|\n| x |\n";
/// assert_eq!(hw3_core::plot::markdown_rows(text), [vec!["1", "1"], vec!["2", "4"], vec!["x"]]);
/// ```
#[must_use]
pub fn markdown_rows(text: &str) -> Vec<Vec<&str>> {
    let mut rows = Vec::new();
    let mut header_next = true;
    for line in text.lines() {
        if !line.starts_with('|') {
            header_next = true;
            continue;
        }
        if header_next || line.starts_with("|---") {
            header_next = false;
            continue;
        }
        rows.push(line.trim_matches('|').split('|').map(str::trim).collect());
    }
    rows
}
