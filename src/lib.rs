#![doc = include_str!(concat!(env!("OUT_DIR"), "/index.md"))]
#![warn(missing_docs)]
#![allow(
    clippy::neg_cmp_op_on_partial_ord,
    reason = "`!(x >= 0)` is how the numerics say 'negative or NaN': NaN must fail every test"
)]

pub mod answers;
pub mod cli;
pub mod data;

#[doc(inline)]
pub use hw3_core::{fsio, geometry, plot, real, rng, stats};
#[doc(inline)]
pub use hw3_render::{envmap, kdtree};

/// The renderer chapter: how the renderer produces each effect that Q1 and Q5 ask about.
pub mod render {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/render.md"))]
    #[doc(inline)]
    pub use hw3_render::render::*;
}

pub mod q1_hard_scenes;
pub mod q2_ray_sphere;
pub mod q3_kd_traversal;
pub mod q4_light_probe;
pub mod q5_effect_tables;

pub mod checker;
pub mod notes;
pub mod solution;

pub use answers::Answers;

/// Every question's answers, in homework order.
///
/// # Examples
/// ```
/// let all = hw3::all_answers();
/// assert!(all.iter().all(|a| !a.text.is_empty()));
/// ```
#[must_use]
pub fn all_answers() -> Vec<Answers> {
    vec![
        q1_hard_scenes::answers(),
        q2_ray_sphere::answers(),
        q3_kd_traversal::answers(),
        q4_light_probe::answers(),
        q5_effect_tables::answers(),
    ]
}

/// Every figure of the course notes: [`drawn_figures`] and [`rendered_figures`], each file name
/// once (two figures of one name would overwrite each other in `docs/figures/`).
///
/// The [`figure_jobs`] run in parallel ([`plot::run_jobs`]: the same list and bytes on every run
/// and thread count; with `HW3_FIGURE_TIMINGS` set, each job's seconds on stderr).
///
/// # Errors
/// [`plot::PlotError`] if a figure cannot be drawn, [`plot::PlotError::DuplicateName`] if two
/// figures share a file name.
pub fn all_figures() -> Result<Vec<plot::Figure>, plot::PlotError> {
    // Two jobs read the Q5 measured table (the Q5 figures and the effect grid), and a pool worker
    // never waits for another thread's measurement of it (`measured_table` says why): measured
    // here first, from this thread outside the pool, it is measured once. A failure is reported
    // by those jobs.
    let _ = q5_effect_tables::experiments::measured_table(&q5_effect_tables::Budget::PUBLISHED);
    let figures = plot::run_jobs(&figure_jobs())?;
    let mut names: Vec<&str> = figures.iter().map(|f| f.file_name.as_str()).collect();
    names.sort_unstable();
    if let Some(pair) = names.windows(2).find(|pair| pair[0] == pair[1]) {
        return Err(plot::PlotError::DuplicateName { figure: pair[0].to_owned() });
    }
    Ok(figures)
}

/// The renders of the course notes (Q1, the renderer chapter, Q5), the expensive figures:
/// deterministic bytes, seeded per pixel.
///
/// # Errors
/// [`plot::PlotError`] if a render cannot be drawn.
pub fn rendered_figures() -> Result<Vec<plot::Figure>, plot::PlotError> {
    plot::run_jobs(&figure_jobs().into_iter().filter(|job| job.rendered).collect::<Vec<_>>())
}

/// The drawn figures of the course notes, in homework order: charts, diagrams, tables and the
/// small analytic images (deterministic bytes, cheap to regenerate).
///
/// # Errors
/// [`plot::PlotError`] if a figure cannot be drawn.
pub fn drawn_figures() -> Result<Vec<plot::Figure>, plot::PlotError> {
    plot::run_jobs(&figure_jobs().into_iter().filter(|job| !job.rendered).collect::<Vec<_>>())
}

/// Every figure job, drawn figures first in homework order, then the renders.
///
/// # Examples
/// ```
/// let jobs = hw3::figure_jobs();
/// assert!(jobs.iter().any(|job| job.rendered) && jobs.iter().any(|job| !job.rendered));
/// ```
#[must_use]
pub fn figure_jobs() -> Vec<plot::FigureJob> {
    use plot::FigureJob;
    let mut jobs = q1_hard_scenes::figure_jobs();
    jobs.extend([
        FigureJob::drawn("q2 figures", q2_ray_sphere::figures),
        FigureJob::drawn("q3 figures", q3_kd_traversal::figures),
    ]);
    jobs.extend(q4_light_probe::figure_jobs());
    jobs.extend([
        FigureJob::drawn("q5 figures", || q5_effect_tables::figures(&q5_effect_tables::Budget::PUBLISHED)),
        FigureJob::drawn("answer key", solution::figures),
    ]);
    jobs.extend(q1_hard_scenes::render_jobs());
    jobs.extend(render::figures::jobs());
    jobs.push(FigureJob::rendered("q5 renders", || q5_effect_tables::renders(&q5_effect_tables::Budget::PUBLISHED)));
    // The grid is the longest render job: on its own it runs beside the others.
    jobs.push(FigureJob::rendered("q5 effect grid", || {
        Ok(vec![q5_effect_tables::effect_grid::figure(&q5_effect_tables::Budget::PUBLISHED)?])
    }));
    jobs
}

/// What the unit tests share: snapshot settings.
#[cfg(test)]
mod testing {
    /// insta settings shared by every snapshot test in the crate: snapshots live in the top-level
    /// `snapshots/` folder, named by the snapshot name alone.
    pub(crate) fn insta_settings() -> insta::Settings {
        let mut settings = insta::Settings::clone_current();
        settings.set_snapshot_path(hw3_core::SNAPSHOTS);
        settings.set_prepend_module_to_snapshot(false);
        settings
    }
}
