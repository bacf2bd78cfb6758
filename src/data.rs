//! Committed data: the benchmark measurements under `docs/data/` that figures and tables are drawn
//! from, compiled into the binary (so `hw3` draws the same figures from any directory, and after
//! `cargo install`), and one reader for them.
//!
//! Timings come only from `cargo bench`, which rewrites these files; `cargo run` and `cargo test`
//! read them and never measure.

/// `docs/data/q2_cost.csv`: ns per ray/sphere intersection and per spawn policy (written by
/// `cargo bench -p hw3-benches --bench q2_cost`).
pub const Q2_COST: &str = include_str!("../docs/data/q2_cost.csv");

/// `docs/data/q3_kdtree_perf.csv`: build time, node counts and Mrays/s of the kd-tree and its
/// peers against scene size (written by `cargo bench -p hw3-benches --bench q3_kdtree`).
pub const Q3_KDTREE_PERF: &str = include_str!("../docs/data/q3_kdtree_perf.csv");

/// `docs/data/q1_accuracy.csv`: RMS error and seconds per scene, integrator and samples per pixel
/// (written by `cargo bench -p hw3-benches --bench render`).
pub const Q1_ACCURACY: &str = include_str!("../docs/data/q1_accuracy.csv");

/// `docs/data/q4_accuracy_time.csv`: error and nanoseconds per normal of every irradiance estimator
/// (written by `cargo bench -p hw3-benches --bench q4_irradiance`).
pub const Q4_ACCURACY_TIME: &str = include_str!("../docs/data/q4_accuracy_time.csv");

/// `docs/data/q5_photon_accuracy.csv`: the photon map's error in the white furnace against k and
/// photon count (written by `cargo bench -p hw3-benches --bench q5_photon`).
pub const Q5_PHOTON_ACCURACY: &str = include_str!("../docs/data/q5_photon_accuracy.csv");

/// `docs/data/q5_photon_cornell.csv`: the photon map's error in the Cornell box against k and photon
/// count (written by `cargo bench -p hw3-benches --bench q5_photon`).
pub const Q5_PHOTON_CORNELL: &str = include_str!("../docs/data/q5_photon_cornell.csv");

/// `docs/data/q5_cornell_reference.csv`: the converged path-traced radiance and its standard error
/// at the published Cornell box's 20 wall probes (written once by an ignored test, see
/// `q5_effect_tables::cornell_published::converged_reference`).
pub const Q5_CORNELL_REFERENCE: &str = include_str!("../docs/data/q5_cornell_reference.csv");

/// Why a committed CSV could not be read: what is wrong, in which file and which record. The
/// files are compiled in and pinned by tests, so these name a bad commit of the data, never a
/// user's input.
///
/// # Examples
/// ```
/// use hw3::data::DataError;
/// let error = DataError::FieldCount { file: "q5_photon_accuracy.csv", expected: 7, got: 2 };
/// assert_eq!(error.to_string(), "q5_photon_accuracy.csv: expected 7 fields, got 2");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DataError {
    /// A field that should be a number is missing or is not one.
    #[error("{file}: bad field {index} in `{record}`")]
    BadField {
        /// The CSV file's name (`q1_accuracy.csv`).
        file: &'static str,
        /// The field's index in its record, from 0.
        index: usize,
        /// The record, its fields joined by commas.
        record: String,
    },
    /// A field of an all-numeric record is not a number.
    #[error("{file}: `{record}`: {source}")]
    NotANumber {
        /// The CSV file's name.
        file: &'static str,
        /// The record, its fields joined by commas.
        record: String,
        /// The number parser's error.
        source: std::num::ParseFloatError,
    },
    /// A record has the wrong number of fields.
    #[error("{file}: expected {expected} fields, got {got}")]
    FieldCount {
        /// The CSV file's name.
        file: &'static str,
        /// The number of fields of every record.
        expected: usize,
        /// The number this record has.
        got: usize,
    },
    /// The header is not the one expected.
    #[error("{file}: header {header:?}")]
    Header {
        /// The CSV file's name.
        file: &'static str,
        /// The header's fields, as read.
        header: Vec<String>,
    },
    /// A record of a per-probe file is not `index,radiance,error` with its own index, a positive
    /// radiance and a non-negative error.
    #[error("{file}: record {} is not `{index},radiance,error`", .index + 1)]
    ProbeRecord {
        /// The CSV file's name.
        file: &'static str,
        /// The record's index, from 0 (the probe it should hold).
        index: usize,
    },
    /// A per-probe file holds a record count other than the probes'.
    #[error("{file}: {got} probes, expected {expected}")]
    ProbeCount {
        /// The CSV file's name.
        file: &'static str,
        /// The records the file holds.
        got: usize,
        /// The number of probes.
        expected: usize,
    },
}

/// A committed CSV file, split: its `#` comment lines, its header and its records.
///
/// The committed files are plain comma-separated fields, with no quoting (no field holds a comma).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Csv<'a> {
    /// The text after `#` of each comment line, trimmed, in file order.
    pub comments: Vec<&'a str>,
    /// The fields of the first line that is not a comment (empty for an empty file).
    pub header: Vec<&'a str>,
    /// The fields of every later non-empty, non-comment line.
    pub records: Vec<Vec<&'a str>>,
}

/// Splits a committed CSV text into comments, header and records.
///
/// # Examples
/// ```
/// let csv = hw3::data::csv("# one run\nn,ns\n1,2.5\n\n4,9.0\n");
/// assert_eq!(csv.comments, ["one run"]);
/// assert_eq!(csv.header, ["n", "ns"]);
/// assert_eq!(csv.records, [["1", "2.5"], ["4", "9.0"]]);
/// ```
#[must_use]
pub fn csv(text: &str) -> Csv<'_> {
    let mut comments = Vec::new();
    let mut lines = Vec::new();
    for line in text.lines() {
        match line.strip_prefix('#') {
            Some(comment) => comments.push(comment.trim()),
            None if !line.is_empty() => lines.push(line.split(',').collect::<Vec<_>>()),
            None => {}
        }
    }
    let mut lines = lines.into_iter();
    let header = lines.next().unwrap_or_default();
    Csv { comments, header, records: lines.collect() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn committed_files_have_a_header_and_records() {
        for (text, first) in [
            (Q1_ACCURACY, "scene"),
            (Q2_COST, "kind"),
            (Q3_KDTREE_PERF, "density"),
            (Q4_ACCURACY_TIME, "map"),
            (Q5_PHOTON_ACCURACY, "photons"),
            (Q5_PHOTON_CORNELL, "photons"),
            (Q5_CORNELL_REFERENCE, "probe"),
        ] {
            let csv = csv(text);
            assert_eq!(csv.header[0], first);
            assert!(!csv.records.is_empty());
            assert!(csv.records.iter().all(|r| r.len() == csv.header.len()), "{first}: every record is complete");
        }
    }
}
