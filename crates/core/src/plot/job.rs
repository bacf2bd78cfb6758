//! Figure jobs: the independent pieces of the figure work, run at once.
//!
//! A job shares nothing with the others (each builds its own scenes and measurements), so the
//! jobs may run in parallel (rayon) while every render inside them is itself parallel over rows.
//! Each job returns its figures in a fixed order and [`run_jobs`] joins them in the jobs' order,
//! so the list, and every figure's bytes, are the same on every run and thread count.

use super::{Figure, PlotError};
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// One independent piece of the figure work.
#[derive(Debug, Clone, Copy)]
pub struct FigureJob {
    /// What the job draws (printed with its time by [`run_jobs`] under `HW3_FIGURE_TIMINGS`).
    pub name: &'static str,
    /// A render (expensive, seeded per pixel) rather than a drawn figure.
    pub rendered: bool,
    /// Draws the job's figures, in a fixed order.
    pub draw: fn() -> Result<Vec<Figure>, PlotError>,
}

impl FigureJob {
    /// A drawn figure's job (chart, diagram, table).
    #[must_use]
    pub const fn drawn(name: &'static str, draw: fn() -> Result<Vec<Figure>, PlotError>) -> Self {
        Self { name, rendered: false, draw }
    }

    /// A render's job.
    #[must_use]
    pub const fn rendered(name: &'static str, draw: fn() -> Result<Vec<Figure>, PlotError>) -> Self {
        Self { name, rendered: true, draw }
    }
}

/// Runs `jobs` in parallel and joins their figures in the jobs' order.
///
/// With the environment variable `HW3_FIGURE_TIMINGS` set, prints one line per job to stderr:
/// its name and the wall-clock seconds from its start to its end. Jobs overlap, so with more than
/// one thread a job's seconds include the time it shared the cores; `RAYON_NUM_THREADS=1` gives
/// each job's cost alone.
///
/// # Errors
/// The first failing job's [`PlotError`], in the jobs' order.
///
/// # Examples
/// ```
/// use hw3_core::plot::{Figure, FigureJob, run_jobs};
/// let one = || Ok(vec![Figure { file_name: "a.md".into(), bytes: b"a".to_vec() }]);
/// let two = || Ok(vec![Figure { file_name: "b.md".into(), bytes: b"b".to_vec() }]);
/// let figures = run_jobs(&[FigureJob::drawn("a", one), FigureJob::drawn("b", two)]).unwrap();
/// assert_eq!(figures.iter().map(|f| f.file_name.as_str()).collect::<Vec<_>>(), ["a.md", "b.md"]);
/// ```
pub fn run_jobs(jobs: &[FigureJob]) -> Result<Vec<Figure>, PlotError> {
    let timed: Vec<(Result<Vec<Figure>, PlotError>, Duration)> = jobs
        .par_iter()
        .map(|job| {
            let start = Instant::now();
            let figures = (job.draw)();
            (figures, start.elapsed())
        })
        .collect();
    if std::env::var_os("HW3_FIGURE_TIMINGS").is_some() {
        let threads = rayon::current_num_threads();
        for (job, (_, took)) in jobs.iter().zip(&timed) {
            eprintln!("figure job {:<24} {:>7.2} s wall ({threads} threads)", job.name, took.as_secs_f64());
        }
    }
    let mut figures = Vec::new();
    for (result, _) in timed {
        figures.extend(result?);
    }
    Ok(figures)
}
