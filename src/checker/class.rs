//! A class at once: many answers files graded in one run, and one report for the course (text,
//! JSON, CSV, Gradescope) with per-part statistics: the mean score, how many got the part right,
//! and the most common recognised mistake.
//!
//! A file that cannot be graded (unreadable, not UTF-8, not TOML, a value of the wrong type) is a
//! row of the report with its one-line reason; the other files are still graded. The bounds
//! ([`MAX_CLASS_FILES`], [`MAX_CLASS_BYTES`]) are checked from the file list and the files' sizes
//! before any file is read.

use super::grading::{Report, check};
use super::policy::Rule;
use super::reports::report_gradescope;
use crate::cli::{ANSWERS_FILE_BYTES, ReadError, escape, one_line, quote, read_text_bounded};
use crate::fsio::io_reason;
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Most answers files one run grades: a large course's sections together, graded in seconds.
pub const MAX_CLASS_FILES: usize = 2000;

/// Most bytes one run reads, summed over the files' sizes (a complete answers file is about
/// 3 KB, so this is far above any real class; each file is also bounded by
/// [`ANSWERS_FILE_BYTES`]).
pub const MAX_CLASS_BYTES: u64 = 64 * 1024 * 1024;

/// One file of the class: its name as given, and its report or why it could not be graded
/// (exactly one of `report` and `error` is set).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Submission {
    /// The file's path, as given or as found in a folder.
    pub file: String,
    /// The graded file.
    pub report: Option<Report>,
    /// Why the file could not be graded, in one line.
    pub error: Option<String>,
}

/// How the class did on one part, over the files that could be graded.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PartStatistics {
    /// TOML path of the part (`q2a.t`).
    pub key: &'static str,
    /// Points available.
    pub max_score: f64,
    /// Mean points earned (rounded to 0.01).
    pub mean_score: f64,
    /// Files that got it right.
    pub correct: usize,
    /// Files with partial credit.
    pub partial: usize,
    /// Files with no credit for an answer given.
    pub wrong: usize,
    /// Files with no answer.
    pub missing: usize,
    /// The recognised mistake made most often, if any was (ties: the first in alphabetical order).
    pub most_common_mistake: Option<&'static str>,
    /// How many files made it.
    pub most_common_mistake_count: usize,
}

/// The class graded: every file, and the per-part statistics of those that could be graded.
///
/// # Examples
/// ```
/// use hw3::checker::{answer_key, check_class};
/// let files = vec![
///     ("key.toml".to_string(), Ok(answer_key(0).unwrap())),
///     ("blank.toml".to_string(), Ok(String::new())),
///     ("broken.toml".to_string(), Ok("[q2a".to_string())),
/// ];
/// let class = check_class(&files, None);
/// assert_eq!((class.graded, class.ungraded), (2, 1));
/// let t = class.parts.iter().find(|p| p.key == "q2a.t").unwrap();
/// assert_eq!((t.correct, t.missing, t.mean_score), (1, 1, 1.0));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClassReport {
    /// Every file, in the order given.
    pub submissions: Vec<Submission>,
    /// Files graded.
    pub graded: usize,
    /// Files that could not be graded.
    pub ungraded: usize,
    /// Mean total over the graded files (rounded to 0.01; 0 when none was).
    pub mean_score: f64,
    /// Points available in one file (0 when none was graded).
    pub max_score: f64,
    /// One entry per part, in question order.
    pub parts: Vec<PartStatistics>,
}

impl ClassReport {
    /// True when every file was graded and every part of every file is correct.
    #[must_use]
    pub fn all_correct(&self) -> bool {
        self.submissions.iter().all(|s| s.report.as_ref().is_some_and(Report::all_correct))
    }
}

/// Why a class run's files were refused before any was read ([`class_files`]).
///
/// # Examples
/// ```
/// use hw3::checker::{ClassError, class_files};
/// let empty = std::env::temp_dir().join(format!("hw3-class-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&empty).unwrap();
/// let error = class_files(&[empty.clone()]).unwrap_err();
/// assert!(matches!(&error, ClassError::NoAnswersFiles { dir } if *dir == empty));
/// assert!(error.to_string().ends_with("` holds no *.toml file"));
/// std::fs::remove_dir(&empty).unwrap();
/// ```
#[derive(Debug, thiserror::Error)]
pub enum ClassError {
    /// A folder cannot be listed.
    #[error("cannot list `{}`: {}", quote(&.dir.display().to_string()), io_reason(.source))]
    List {
        /// The folder.
        dir: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// A folder holds no `*.toml` file.
    #[error("`{}` holds no *.toml file", quote(&.dir.display().to_string()))]
    NoAnswersFiles {
        /// The folder.
        dir: PathBuf,
    },
    /// More answers files than [`MAX_CLASS_FILES`].
    #[error("more than {limit} answers files: grade the class in parts")]
    TooManyFiles {
        /// [`MAX_CLASS_FILES`].
        limit: usize,
    },
    /// The files' summed size is over [`MAX_CLASS_BYTES`].
    #[error("the answers files hold {bytes} bytes, over the limit of {limit}")]
    TooManyBytes {
        /// The summed size.
        bytes: u64,
        /// [`MAX_CLASS_BYTES`].
        limit: u64,
    },
}

/// The files of a class run: each path as given, and for a folder its `*.toml` files (not its
/// sub-folders), sorted by name. The count and the summed size are checked here, before any file
/// is read; a file that is not a regular file (a device) counts as [`ANSWERS_FILE_BYTES`], the
/// most that is read of it.
///
/// # Errors
/// [`ClassError::List`] for a folder that cannot be listed, [`ClassError::NoAnswersFiles`] for
/// one that holds no `*.toml` file, [`ClassError::TooManyFiles`] for more than
/// [`MAX_CLASS_FILES`] files, [`ClassError::TooManyBytes`] for more than [`MAX_CLASS_BYTES`]
/// bytes. A single file that cannot be read is not an error here: it is reported in the class
/// report.
///
/// # Examples
/// ```
/// let folder = std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/answers"));
/// let files = hw3::checker::class_files(&[folder]).unwrap();
/// assert!(files.iter().any(|f| f.ends_with("seed_hw3.toml")));
/// assert!(files.windows(2).all(|w| w[0] < w[1]));
/// ```
pub fn class_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, ClassError> {
    let mut files = Vec::new();
    for path in paths {
        if !path.is_dir() {
            files.push(path.clone());
            continue;
        }
        let listing = std::fs::read_dir(path).map_err(|source| ClassError::List { dir: path.clone(), source })?;
        let mut found: Vec<PathBuf> = listing
            .filter_map(Result::ok)
            .map(|entry| entry.path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml") && !p.is_dir())
            .collect();
        if found.is_empty() {
            return Err(ClassError::NoAnswersFiles { dir: path.clone() });
        }
        found.sort();
        files.extend(found);
        if files.len() > MAX_CLASS_FILES {
            break;
        }
    }
    if files.len() > MAX_CLASS_FILES {
        return Err(ClassError::TooManyFiles { limit: MAX_CLASS_FILES });
    }
    let bytes: u64 = files
        .iter()
        .map(|f| match std::fs::metadata(f) {
            Ok(m) if m.is_file() => m.len(),
            Ok(_) => ANSWERS_FILE_BYTES,
            Err(_) => 0,
        })
        .sum();
    if bytes > MAX_CLASS_BYTES {
        return Err(ClassError::TooManyBytes { bytes, limit: MAX_CLASS_BYTES });
    }
    Ok(files)
}

/// Reads each file (at most [`ANSWERS_FILE_BYTES`] of UTF-8 text): its name, and its text or why
/// it cannot be read.
#[must_use]
pub fn read_class(files: &[PathBuf]) -> Vec<(String, Result<String, ReadError>)> {
    // A file's name is shown escaped wherever the report goes: a name may hold a line break or a
    // terminal escape.
    files.iter().map(|f| (escape(&f.display().to_string()), read_text_bounded(f, ANSWERS_FILE_BYTES))).collect()
}

/// Grades every file of a class: `files` pairs each name with its text, or with why it could not
/// be read. The seed of each file comes from `seed_override`, else its own `[meta] seed`.
///
/// # Examples
/// ```
/// use hw3::cli::ReadError;
/// let gone = ReadError::Io { path: "gone.toml".into(), source: std::io::ErrorKind::NotFound.into() };
/// let files = vec![("gone.toml".to_string(), Err(gone))];
/// let class = hw3::checker::check_class(&files, None);
/// assert_eq!((class.graded, class.ungraded, class.max_score), (0, 1, 0.0));
/// assert!(class.submissions[0].error.as_deref().unwrap().starts_with("cannot read gone.toml: "));
/// ```
#[must_use]
pub fn check_class(files: &[(String, Result<String, ReadError>)], seed_override: Option<u64>) -> ClassReport {
    let submissions: Vec<Submission> = files
        .iter()
        .map(|(file, text)| {
            let graded = text
                .as_ref()
                .map_err(ToString::to_string)
                .and_then(|t| check(t, seed_override).map_err(|e| e.to_string()));
            match graded {
                Ok(report) => Submission { file: file.clone(), report: Some(report), error: None },
                Err(error) => Submission { file: file.clone(), report: None, error: Some(one_line(&error)) },
            }
        })
        .collect();
    let reports: Vec<&Report> = submissions.iter().filter_map(|s| s.report.as_ref()).collect();
    let graded = reports.len();
    let mean = |total: f64| if graded == 0 { 0.0 } else { round2(total / graded as f64) };
    let mut parts = Vec::new();
    if let Some(first) = reports.first() {
        for (i, part) in first.parts.iter().enumerate() {
            // Every variant lists the same parts in the same order, so the i-th result of each
            // report is this part.
            let results: Vec<_> = reports.iter().filter_map(|r| r.parts.get(i)).filter(|p| p.key == part.key).collect();
            let count = |status: &str| results.iter().filter(|p| p.status == status).count();
            let mut mistakes: BTreeMap<&'static str, usize> = BTreeMap::new();
            // Credit carried forward marks a right step, not a mistake.
            for mistake in results.iter().filter_map(|p| p.mistake).filter(|m| *m != Rule::CarriedForward.id()) {
                *mistakes.entry(mistake).or_default() += 1;
            }
            // The largest count; among equals, the first key (BTreeMap order), since max_by_key
            // keeps the last maximum of an iterator, which is reversed here.
            let most = mistakes.iter().rev().max_by_key(|(_, n)| **n).map(|(m, n)| (*m, *n));
            parts.push(PartStatistics {
                key: part.key,
                max_score: part.max_score,
                mean_score: mean(results.iter().map(|p| p.score).sum()),
                correct: count("correct"),
                partial: count("partial"),
                wrong: count("wrong"),
                missing: count("missing"),
                most_common_mistake: most.map(|(m, _)| m),
                most_common_mistake_count: most.map_or(0, |(_, n)| n),
            });
        }
    }
    ClassReport {
        graded,
        ungraded: submissions.len() - graded,
        mean_score: mean(reports.iter().map(|r| r.score).sum()),
        max_score: reports.first().map_or(0.0, |r| r.max_score),
        parts,
        submissions,
    }
}

/// The class report as text: one line per file (its score, or why it was not graded), the class
/// mean, then one line per part (mean, how many right, partial, wrong, missing) and the most
/// common recognised mistake of each part that has one.
///
/// # Examples
/// ```
/// use hw3::checker::{answer_key, check_class, class_text};
/// let files = vec![("key.toml".to_string(), Ok(answer_key(0).unwrap()))];
/// let text = class_text(&check_class(&files, None));
/// assert!(text.contains("key.toml") && text.contains("1 graded, 0 not graded"));
/// ```
#[must_use]
pub fn class_text(class: &ClassReport) -> String {
    let mut out = format!(
        "class of {} files: {} graded, {} not graded\n\n",
        class.submissions.len(),
        class.graded,
        class.ungraded
    );
    let width = class.submissions.iter().map(|s| s.file.chars().count()).max().unwrap_or(4).max(4);
    for s in &class.submissions {
        match (&s.report, &s.error) {
            (Some(r), _) => {
                let wrong = r.parts.iter().filter(|p| p.status != "correct").count();
                let mut verdict =
                    if wrong == 0 { "all correct".to_string() } else { format!("{wrong} parts not correct") };
                // A warning (a file without its seed, a key graded under a guessed name) is the
                // grader's to see in the class's list, not only in the student's own report.
                for warning in &r.warnings {
                    let _ = write!(verdict, "; {warning}");
                }
                let _ = writeln!(
                    out,
                    "{:<width$}  {:>6.2} / {:.2}  seed {}  {verdict}",
                    s.file, r.score, r.max_score, r.seed
                );
            }
            (None, error) => {
                let _ = writeln!(out, "{:<width$}  not graded: {}", s.file, error.as_deref().unwrap_or("unknown"));
            }
        }
    }
    let _ = writeln!(out, "\nmean {:.2} / {:.2} over {} graded files", class.mean_score, class.max_score, class.graded);
    if class.parts.is_empty() {
        return out.trim_end().to_owned();
    }
    let _ = writeln!(out, "\n{:<26} {:<13}  right partial wrong missing", "part", "mean");
    for p in &class.parts {
        let _ = writeln!(
            out,
            "{:<26} {:>6.2} / {:<4}  {:>5} {:>7} {:>5} {:>7}",
            p.key, p.mean_score, p.max_score, p.correct, p.partial, p.wrong, p.missing
        );
    }
    let mistakes: Vec<_> = class.parts.iter().filter(|p| p.most_common_mistake.is_some()).collect();
    if !mistakes.is_empty() {
        let _ = writeln!(out, "\nmost common recognised mistake per part");
        for p in mistakes {
            let _ = writeln!(
                out,
                "{:<26} {} of {}: {}",
                p.key,
                p.most_common_mistake_count,
                class.graded,
                p.most_common_mistake.unwrap_or_default()
            );
        }
    }
    out.trim_end().to_owned()
}

/// One CSV field (RFC 4180): quoted when it holds a comma, a quote or a line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) { format!("\"{}\"", text.replace('"', "\"\"")) } else { text.to_owned() }
}

/// The class report as CSV (RFC 4180), a gradebook: a header, one row per file (`file, seed,
/// score, max_score, error`, then each part's points), and two summary rows whose `file` is
/// `(mean)` (each part's mean points) and `(right)` (how many files got it right).
///
/// # Examples
/// ```
/// use hw3::checker::{answer_key, check_class, class_csv};
/// let files = vec![("a.toml".to_string(), Ok(answer_key(0).unwrap())), ("b.toml".to_string(), Ok("x = [".into()))];
/// let csv = class_csv(&check_class(&files, None));
/// let rows: Vec<&str> = csv.lines().collect();
/// assert!(rows[0].starts_with("file,seed,score,max_score,error,q1a.gap_fraction,"));
/// assert!(rows[2].starts_with("b.toml,,,,\"not valid TOML"));
/// assert_eq!(rows.len(), 5);
/// ```
#[must_use]
pub fn class_csv(class: &ClassReport) -> String {
    let mut rows = vec![
        ["file", "seed", "score", "max_score", "error"]
            .into_iter()
            .map(str::to_owned)
            .chain(class.parts.iter().map(|p| p.key.to_owned()))
            .collect::<Vec<_>>(),
    ];
    for s in &class.submissions {
        let mut row = vec![s.file.clone()];
        match &s.report {
            Some(r) => {
                row.extend([r.seed.to_string(), r.score.to_string(), r.max_score.to_string(), String::new()]);
                row.extend(
                    class.parts.iter().map(|p| {
                        r.parts.iter().find(|q| q.key == p.key).map_or(String::new(), |q| q.score.to_string())
                    }),
                );
            }
            None => {
                row.extend([String::new(), String::new(), String::new(), s.error.clone().unwrap_or_default()]);
                row.extend(class.parts.iter().map(|_| String::new()));
            }
        }
        rows.push(row);
    }
    let summary = |name: &str, value: &dyn Fn(&PartStatistics) -> String| {
        let mut row = vec![name.to_owned(), String::new(), String::new(), String::new(), String::new()];
        row.extend(class.parts.iter().map(value));
        row
    };
    if !class.parts.is_empty() {
        let mut mean = summary("(mean)", &|p| p.mean_score.to_string());
        mean[2] = class.mean_score.to_string();
        mean[3] = class.max_score.to_string();
        rows.push(mean);
        rows.push(summary("(right)", &|p| p.correct.to_string()));
    }
    let lines: Vec<String> =
        rows.iter().map(|row| row.iter().map(|f| csv_field(f)).collect::<Vec<_>>().join(",")).collect();
    lines.join("\n")
}

/// Gradescope's `results.json` of one submission: [`report_gradescope`] for a graded file, and for
/// one that could not be graded a score of 0 with the reason as its output.
fn gradescope_of(submission: &Submission) -> serde_json::Value {
    match &submission.report {
        Some(report) => report_gradescope(report),
        None => serde_json::json!({
            "score": 0.0,
            "output": format!("not graded: {}", submission.error.as_deref().unwrap_or("unknown")),
            "tests": [],
        }),
    }
}

/// The class in Gradescope's shape: one JSON object, `{"submissions": [{"file", "results"}]}`,
/// where each `results` is that student's autograder `results.json` (see [`report_gradescope`]).
///
/// # Examples
/// ```
/// use hw3::checker::{answer_key, check_class, class_gradescope};
/// let files = vec![("a.toml".to_string(), Ok(answer_key(0).unwrap()))];
/// let json = class_gradescope(&check_class(&files, None));
/// assert_eq!(json["submissions"][0]["file"], "a.toml");
/// let full = hw3::checker::check(&answer_key(0).unwrap(), None).unwrap().max_score;
/// assert_eq!(json["submissions"][0]["results"]["score"].as_f64(), Some(full));
/// ```
#[must_use]
pub fn class_gradescope(class: &ClassReport) -> serde_json::Value {
    let submissions: Vec<serde_json::Value> =
        class.submissions.iter().map(|s| serde_json::json!({ "file": s.file, "results": gradescope_of(s) })).collect();
    serde_json::json!({ "submissions": submissions })
}

/// Why a class's Gradescope results cannot be written one file per student ([`gradescope_files`]).
///
/// # Examples
/// ```
/// use hw3::checker::{GradescopeError, check_class, gradescope_files};
/// let files = vec![("x/a.toml".to_string(), Ok(String::new())), ("y/a.toml".to_string(), Ok(String::new()))];
/// let error = gradescope_files(&check_class(&files, None)).unwrap_err();
/// assert!(matches!(&error, GradescopeError::SameResultsFile { name, .. } if name == "a.json"));
/// assert_eq!(error.to_string(), "`x/a.toml` and `y/a.toml` would both write a.json");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum GradescopeError {
    /// An answers file's name has no stem (or one that is not UTF-8) to name its results after.
    #[error("`{}` has no file name to name its results after", quote(.file))]
    NoFileStem {
        /// The answers file, as given.
        file: String,
    },
    /// Two answers files share a stem, so their results would overwrite each other.
    #[error("`{}` and `{}` would both write {name}", quote(.first), quote(.second))]
    SameResultsFile {
        /// The first answers file with the stem.
        first: String,
        /// The second.
        second: String,
        /// The results file both would write (`alice.json`).
        name: String,
    },
}

/// The class as one Gradescope `results.json` per student, for a folder: the file name is the
/// answers file's stem with `.json` (`alice.toml` → `alice.json`).
///
/// # Errors
/// [`GradescopeError::SameResultsFile`] when two answers files share a stem (their results would
/// overwrite each other), [`GradescopeError::NoFileStem`] when a file has no stem or one that is
/// not valid UTF-8 text.
///
/// # Examples
/// ```
/// use hw3::checker::{check_class, gradescope_files};
/// let files = vec![("x/a.toml".to_string(), Ok(String::new())), ("y/a.toml".to_string(), Ok(String::new()))];
/// assert!(gradescope_files(&check_class(&files[..1], None)).unwrap()[0].0 == "a.json");
/// assert!(gradescope_files(&check_class(&files, None)).is_err());
/// ```
pub fn gradescope_files(class: &ClassReport) -> Result<Vec<(String, serde_json::Value)>, GradescopeError> {
    let mut seen = BTreeMap::new();
    let mut out = Vec::new();
    for s in &class.submissions {
        let stem = Path::new(&s.file).file_stem().and_then(|s| s.to_str()).unwrap_or_default();
        if stem.is_empty() {
            return Err(GradescopeError::NoFileStem { file: s.file.clone() });
        }
        let name = format!("{stem}.json");
        if let Some(other) = seen.insert(name.clone(), s.file.clone()) {
            return Err(GradescopeError::SameResultsFile { first: other, second: s.file.clone(), name });
        }
        out.push((name, gradescope_of(s)));
    }
    Ok(out)
}

fn round2(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::checker::answer_key;

    fn class(texts: &[&str]) -> ClassReport {
        let files: Vec<_> = texts.iter().enumerate().map(|(i, t)| (format!("s{i}.toml"), Ok(t.to_string()))).collect();
        check_class(&files, None)
    }

    #[test]
    fn statistics_count_each_status_and_the_commonest_mistake() {
        let key = answer_key(0).unwrap();
        let with_t = |t: f64| {
            let mut file: toml::Table = toml::from_str(&key).unwrap();
            file["q2a"].as_table_mut().unwrap().insert("t".into(), toml::Value::Float(t));
            toml::to_string(&file).unwrap()
        };
        // t = 5 + √3 is the larger root (a recognised mistake); t = 4 is an unrecognised one.
        let (larger, unknown) = (with_t(5.0 + 3f64.sqrt()), with_t(4.0));
        let report = class(&[&key, &larger, &larger, &unknown, "", "[q2a"]);
        assert_eq!((report.graded, report.ungraded), (5, 1));
        let t = report.parts.iter().find(|p| p.key == "q2a.t").unwrap();
        assert_eq!((t.correct, t.partial, t.wrong, t.missing), (1, 0, 3, 1));
        assert_eq!(t.mean_score, round2(2.0 / 5.0));
        // The larger root is an instance of the policy's wrong-root rule, which the report names.
        assert_eq!(t.most_common_mistake, Some(crate::checker::Rule::WrongRoot.id()), "{t:?}");
        assert_eq!(t.most_common_mistake_count, 2);
        // A point that follows from the larger root earns credit carried forward, which marks a
        // right step, not a mistake.
        let crate::checker::Setting::Q2 { ray, .. } = crate::checker::variant("q2", 0).unwrap().setting else {
            unreachable!()
        };
        let followed = {
            let t = 5.0 + 3f64.sqrt();
            let mut file: toml::Table = toml::from_str(&larger).unwrap();
            let point = ray.origin + ray.dir * t;
            let point = toml::Value::Array(point.to_array().iter().map(|&x| toml::Value::Float(x)).collect());
            file["q2a"].as_table_mut().unwrap().insert("point".into(), point);
            toml::to_string(&file).unwrap()
        };
        let carried = class(&[&followed, &followed]);
        let point = carried.parts.iter().find(|p| p.key == "q2a.point").unwrap();
        assert_eq!((point.partial + point.correct, point.most_common_mistake), (2, None), "{point:?}");
        assert!(!report.all_correct());
        let first = &report.submissions[0];
        assert_eq!(
            report.mean_score,
            round2(report.submissions[..5].iter().map(|s| s.report.as_ref().unwrap().score).sum::<f64>() / 5.0)
        );
        assert!(first.report.as_ref().unwrap().all_correct());
        assert!(report.submissions[5].error.as_deref().unwrap().starts_with("not valid TOML"));
    }

    #[test]
    fn a_class_of_keys_is_all_correct() {
        let keys: Vec<String> = (0..4).map(|s| answer_key(s).unwrap()).collect();
        let report = class(&keys.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(report.all_correct());
        assert_eq!(report.mean_score, report.max_score);
        assert!(report.parts.iter().all(|p| p.correct == 4 && p.most_common_mistake.is_none()));
    }

    #[test]
    fn csv_fields_are_quoted_only_when_needed() {
        assert_eq!(csv_field("plain"), "plain");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"x\""), "\"say \"\"x\"\"\"");
    }

    #[test]
    fn bounds_are_checked_before_reading() {
        let dir = std::env::temp_dir().join(format!("hw3-class-bounds-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let empty = class_files(std::slice::from_ref(&dir)).unwrap_err();
        assert!(matches!(empty, ClassError::NoAnswersFiles { .. }), "{empty:?}");
        assert!(empty.to_string().contains("no *.toml"));
        let many: Vec<PathBuf> = (0..=MAX_CLASS_FILES).map(|i| dir.join(format!("{i}.toml"))).collect();
        let too_many = class_files(&many).unwrap_err();
        assert!(matches!(too_many, ClassError::TooManyFiles { limit: MAX_CLASS_FILES }), "{too_many:?}");
        assert_eq!(too_many.to_string(), "more than 2000 answers files: grade the class in parts");
        std::fs::remove_dir_all(&dir).ok();
    }
}
