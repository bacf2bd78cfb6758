//! One markdown-table writer, for the tables the chapters include among their figures, and its
//! reader, for the code and tests that read numbers back from a committed table; and the one way a
//! number is shown to a reader with its significant digits kept ([`significant`]).
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
/// `x` with at least six significant digits: six decimals from 0.1 up to 10¹⁵, more decimals
/// below 0.1, and an exponent below 10⁻³ or from 10¹⁵ up, so that a small or subnormal value is
/// never printed as 0 and a huge one is not a run of digits. −0 is shown as 0; ±∞ and NaN as
/// `inf`, `-inf`, `NaN`.
///
/// # Examples
/// ```
/// use hw3_core::plot::significant;
/// assert_eq!(significant(4.188790204786391), "4.188790");
/// assert_eq!(significant(0.0123), "0.0123000");
/// assert_eq!(significant(2.5e-40), "2.50000e-40");
/// assert_eq!(significant(1.5e308), "1.50000e308");
/// assert_eq!(significant(-0.0), "0.000000");
/// ```
#[must_use]
pub fn significant(x: f64) -> String {
    let x = x + 0.0; // -0 prints as 0
    if x == 0.0 || !x.is_finite() {
        return format!("{x:.6}");
    }
    let magnitude = x.abs().log10().floor();
    if (-3.0..15.0).contains(&magnitude) {
        // 0.0123 has magnitude -2: seven decimals give it six significant digits.
        let decimals = (5.0 - magnitude).max(6.0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.5e}")
    }
}
