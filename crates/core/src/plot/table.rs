//! One markdown-table writer, for the tables the chapters include among their figures.
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
