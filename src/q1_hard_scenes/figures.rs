//! Every Q1 figure: renders of the four scenes and their easy twins, one chart per metric, and
//! the measured tables that the chapter includes.

use super::accuracy::committed_accuracy_figures;
use super::chart::{chart, series};
use super::clutter::{CLUTTER_COUNTS, ClutterRow, clutter_hardness_table, clutter_row, clutter_table};
use super::fog::{
    FOG_SIGMAS, FogRow, airlight_convergence, airlight_convergence_table, airlight_rows, airlight_table,
    fog_path_factor, fog_rows, fog_table,
};
use super::mirrors::{
    DIVERGENCE_TRIALS, MIRROR_SPP, MIRROR_STEPS, MirrorDivergence, divergence_table, mirror_divergence,
    mirror_sensitivity, mirror_table,
};
use super::motion::{
    MOTION_REFERENCE_SPP, MOTION_SPEED, MOTION_SPP, MotionChange, MotionNoise, motion_change, motion_noise,
    motion_tables,
};
use crate::geometry::InputError;
use crate::plot::{self, Axis, Figure, FigureJob, PALETTE, PlotError};
use crate::render::analysis::analyze;
use crate::render::camera::Camera;
use crate::render::catalogue;
use crate::render::scene::Scene;
use crate::render::{Settings, render};
use glam::DVec3;
use plotters::prelude::*;

/// A text file placed among the figures (the chapter includes it as a generated table).
fn table_figure(file_name: &str, text: String) -> Figure {
    Figure { file_name: file_name.into(), bytes: text.into_bytes() }
}

/// Width and height of a render shown alone (a pair shows two panels of half this width and height).
const FULL: (u32, u32) = (640, 480);
/// Width and height of each panel of a side-by-side pair.
const HALF: (u32, u32) = (320, 240);

/// Renders `scene` (Whitted, its own plan, seed 1: the same bytes on every run and thread count).
fn render_image(scene: &Scene, (width, height): (u32, u32), spp: u32) -> crate::plot::RgbImage {
    let settings = Settings::whitted(width, height, spp, analyze(scene).plan);
    render(scene, &settings, &|_| {}).expect("the figure settings are within limits").to_rgb8()
}

/// A pair of renders side by side at `size` each ([`HALF`] in the notes), labelled, as one PNG;
/// the right panel's label states its measured difference from the left
/// ([`plot::rms_difference`]), how much the effect changes the picture.
fn pair_figure(
    file_name: &str,
    size: (u32, u32),
    [left, right]: [(&Scene, u32, &str); 2],
) -> Result<Figure, PlotError> {
    let label = |spp: u32, what: &str| format!("{what}\nWhitted, {spp} spp");
    let left_image = render_image(left.0, size, left.1);
    let right_image = render_image(right.0, size, right.1);
    let difference = plot::difference_line("left", &right_image, &left_image);
    let panels = [
        plot::Panel { image: left_image, label: label(left.1, left.2) },
        plot::Panel { image: right_image, label: format!("{}\n{difference}", label(right.1, right.2)) },
    ];
    plot::panel_grid(file_name, &panels, 2)
}

fn input_error(figure: &str, e: InputError) -> PlotError {
    PlotError::data(figure, e)
}

/// The clutter chart's sphere-count ticks: the measured counts ([`CLUTTER_COUNTS`]), which
/// plotters' own log ticks leave unlabelled below 1000.
const CLUTTER_TICKS: [f64; CLUTTER_COUNTS.len()] = {
    let mut ticks = [0.0; CLUTTER_COUNTS.len()];
    let mut i = 0;
    while i < ticks.len() {
        ticks[i] = CLUTTER_COUNTS[i] as f64;
        i += 1;
    }
    ticks
};

/// The clutter figures: render, gap-fraction chart, table.
fn clutter_figures(rows: &[ClutterRow]) -> Result<Vec<Figure>, PlotError> {
    let counts: Vec<f64> = rows.iter().map(|r| r.count as f64).collect();
    let pick =
        |f: fn(&ClutterRow) -> f64| -> Vec<(f64, f64)> { counts.iter().copied().zip(rows.iter().map(f)).collect() };
    let gap = chart(
        "q1_clutter_gap.svg",
        "Clutter: gap fraction and visible fraction vs sphere count",
        ("spheres N in the slab", "fraction"),
        (Axis { ticks: Some(&CLUTTER_TICKS), ..Axis::log(200.0, 5000.0, "") }, Axis::linear(0.0, 1.05, "")),
        SeriesLabelPosition::LowerLeft,
        &[
            series("gap fraction, measured", pick(|r| r.gap_fraction), false, PALETTE[0]),
            series("law (1−p)^N", pick(|r| r.gap_exact), true, PALETTE[0]),
            series("visible fraction (3 cameras, 64×48)", pick(|r| r.visible_fraction), false, PALETTE[1]),
            series(
                "centre-ray estimate (1 − e^(−τ))/τ",
                pick(|r| -(-r.optical_depth).exp_m1() / r.optical_depth),
                true,
                PALETTE[1],
            ),
        ],
    )?;
    Ok(vec![
        gap,
        table_figure("q1_clutter_table.md", clutter_table(rows)),
        table_figure("q1_clutter_hardness.md", clutter_hardness_table(rows)),
    ])
}

fn fog_figures(rows: &[FogRow]) -> Result<Vec<Figure>, PlotError> {
    let mut plotted = Vec::new();
    for (k, &sigma) in FOG_SIGMAS.iter().enumerate() {
        let of_sigma = rows.iter().filter(|r| r.sigma_t == sigma);
        plotted.push(series(
            format!("σ_t = {sigma}: measured"),
            of_sigma.clone().map(|r| (r.distance, r.transmittance)).collect(),
            false,
            PALETTE[k],
        ));
        let path_factor = fog_path_factor();
        plotted.push(series(
            format!("e^(−σ_t ℓ), σ_t = {sigma}"),
            (0..=80)
                .map(|i| {
                    let d = f64::from(i) * 0.5;
                    (d, (-sigma * d * path_factor).exp())
                })
                .collect(),
            true,
            PALETTE[k],
        ));
    }
    let transmittance = chart(
        "q1_fog_transmittance.svg",
        "Fog: transmittance vs distance",
        ("target distance d", "transmittance T = ΔL / L_emitted"),
        (Axis::linear(0.0, 41.0, ""), Axis::log(1e-4, 1.2, "")),
        SeriesLabelPosition::LowerLeft,
        &plotted,
    )?;
    Ok(vec![
        transmittance,
        table_figure("q1_fog_table.md", fog_table(rows)),
        table_figure(
            "q1_airlight_table.md",
            airlight_table(&airlight_rows().map_err(|e| input_error("q1_airlight_table.md", e))?),
        ),
        table_figure(
            "q1_airlight_steps.md",
            airlight_convergence_table(&airlight_convergence().map_err(|e| input_error("q1_airlight_steps.md", e))?),
        ),
    ])
}

fn mirror_figures(rows: &[(f64, f64, f64)], divergence: &MirrorDivergence) -> Result<Vec<Figure>, PlotError> {
    let sensitivity = chart(
        "q1_mirror_sensitivity.svg",
        "Mirrors: image change per unit camera move (sphere pixels)",
        ("camera displacement δ", "S(δ) = mean |ΔI| / δ"),
        (Axis { ticks: Some(&MIRROR_STEPS), ..Axis::log(0.004, 0.12, "") }, Axis::linear(0.0, 0.6, "")),
        SeriesLabelPosition::LowerRight,
        &[
            series("mirror spheres", rows.iter().map(|r| (r.0, r.1)).collect(), true, PALETTE[0]),
            series("same spheres, diffuse", rows.iter().map(|r| (r.0, r.2)).collect(), true, PALETTE[1]),
        ],
    )?;
    Ok(vec![
        sensitivity,
        table_figure("q1_mirror_table.md", mirror_table(rows)),
        table_figure("q1_mirror_divergence_table.md", divergence_table(divergence)),
    ])
}

fn motion_figures(change: &MotionChange, noise: &MotionNoise) -> Result<Vec<Figure>, PlotError> {
    let law = |c: f64| -> Vec<(f64, f64)> { [1.0, 32.0].iter().map(|&s| (s, c / f64::sqrt(s))).collect() };
    let curve = chart(
        "q1_motion_noise.svg",
        "Motion blur: RMS error vs samples per pixel",
        ("samples per pixel", "RMS luminance error"),
        (
            Axis { ticks: Some(&[1.0, 2.0, 4.0, 8.0, 16.0, 32.0]), ..Axis::log(0.8, 40.0, "") },
            Axis { ticks: Some(&[0.005, 0.01, 0.02, 0.04]), ..Axis::log(4e-3, 5e-2, "") },
        ),
        SeriesLabelPosition::LowerLeft,
        &[
            series("moving ball", noise.rows.iter().map(|r| (f64::from(r.0), r.1)).collect(), false, PALETTE[0]),
            series("c/√spp, moving", law(noise.constant_moving), true, PALETTE[0]),
            series("ball at rest", noise.rows.iter().map(|r| (f64::from(r.0), r.2)).collect(), false, PALETTE[1]),
            series("c/√spp, at rest", law(noise.constant_resting), true, PALETTE[1]),
        ],
    )?;
    Ok(vec![curve, table_figure("q1_motion_table.md", motion_tables(change, noise))])
}

/// Q1's drawn figures: one chart per metric (SVG) and the measured tables (Markdown, included by
/// the chapter); the renders are [`renders`]. The [`figure_jobs`] run in parallel.
///
/// # Errors
/// [`PlotError`] if a chart cannot be drawn.
///
/// # Examples
/// ```
/// // `figures()` runs every job of `figure_jobs()`: every Q1 measurement, about two seconds in
/// // a test build. The example runs the first two, clutter and fog (about a quarter of that);
/// // `tests/docs.rs` compares all twelve drawn figures with the committed files byte for byte.
/// let first_two = &hw3::q1_hard_scenes::figure_jobs()[..2];
/// let figures = hw3::plot::run_jobs(first_two).unwrap();
/// let names: Vec<&str> = figures.iter().map(|f| f.file_name.as_str()).collect();
/// let clutter = ["q1_clutter_gap.svg", "q1_clutter_table.md", "q1_clutter_hardness.md"];
/// let fog = ["q1_fog_transmittance.svg", "q1_fog_table.md", "q1_airlight_table.md", "q1_airlight_steps.md"];
/// assert_eq!(names, [&clutter[..], &fog].concat());
/// for figure in &figures {
///     let text = std::str::from_utf8(&figure.bytes).unwrap();
///     // Charts are SVG documents; tables are markdown with a header rule.
///     assert!(if figure.file_name.ends_with(".svg") { text.contains("<svg") } else { text.contains("|---") });
/// }
/// ```
pub fn figures() -> Result<Vec<Figure>, PlotError> {
    plot::run_jobs(&figure_jobs())
}

/// Q1's drawn figures as independent jobs, one per scene's measurements (and the committed
/// accuracy data), in the chapter's order.
///
/// # Examples
/// ```
/// let jobs = hw3::q1_hard_scenes::figure_jobs();
/// assert!(jobs.iter().all(|job| !job.rendered) && jobs.len() == 5);
/// ```
#[must_use]
pub fn figure_jobs() -> Vec<FigureJob> {
    vec![
        FigureJob::drawn("q1 clutter measurements", || {
            let rows: Vec<ClutterRow> = CLUTTER_COUNTS
                .iter()
                .map(|&n| clutter_row(n))
                .collect::<Result<_, _>>()
                .map_err(|e| input_error("q1_clutter_table.md", e))?;
            clutter_figures(&rows)
        }),
        FigureJob::drawn("q1 fog measurements", || {
            fog_figures(&fog_rows().map_err(|e| input_error("q1_fog_table.md", e))?)
        }),
        FigureJob::drawn("q1 mirror measurements", || {
            let mirrors =
                mirror_sensitivity(&MIRROR_STEPS, MIRROR_SPP).map_err(|e| input_error("q1_mirror_table.md", e))?;
            let divergence =
                mirror_divergence(DIVERGENCE_TRIALS).map_err(|e| input_error("q1_mirror_divergence_table.md", e))?;
            mirror_figures(&mirrors, &divergence)
        }),
        FigureJob::drawn("q1 motion measurements", || {
            let change = motion_change().map_err(|e| input_error("q1_motion_table.md", e))?;
            let noise =
                motion_noise(&MOTION_SPP, MOTION_REFERENCE_SPP).map_err(|e| input_error("q1_motion_table.md", e))?;
            motion_figures(&change, &noise)
        }),
        FigureJob::drawn("q1 accuracy data", committed_accuracy_figures),
    ]
}

/// Samples per pixel of each Q1 render, chosen from the measured error against samples per pixel
/// (`docs/data/q1_accuracy.md`, Whitted): where the error stops falling fast, so that more samples
/// would cost time without changing what the picture shows; and from each render's noise at
/// 100 % zoom ([`crate::render::noise`], display levels): the clutter slab's 1500 small spheres
/// flicker by 5.8 levels at 16 spp and 4.0 at 32, the fog street 0.55 at 16 (about 0.8 at its 8), the mirror spheres 2.2
/// at 16, the moving ball 1.4 at 64.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::RENDER_SPP;
/// // One entry per hard scene; the moving ball's motion blur needs the most samples.
/// let names: Vec<&str> = RENDER_SPP.iter().map(|(name, _)| *name).collect();
/// assert_eq!(names, ["clutter", "fog", "mirrors", "motion"]);
/// assert_eq!(RENDER_SPP.iter().map(|(_, spp)| *spp).max(), Some(RENDER_SPP[3].1));
/// ```
pub const RENDER_SPP: [(&str, u32); 4] = [("clutter", 32), ("fog", 8), ("mirrors", 16), ("motion", 64)];

fn spp_of(scene: &str) -> u32 {
    RENDER_SPP.iter().find(|(name, _)| *name == scene).map_or(1, |&(_, spp)| spp)
}

/// Q1's renders (PNG): the cluttered slab alone at 640×480, and each other scene beside its easy
/// twin (fog beside no medium, mirror spheres beside diffuse ones, the moving ball beside the ball
/// at rest) at 320×240 per panel, labelled with the scene, the method and the samples per pixel.
/// Whitted tracing with seed 1, so the bytes are the same on every run and thread count. The
/// [`render_jobs`] run in parallel.
///
/// At [`Budget::Published`] these are the committed files (CI's release run compares them byte
/// for byte); at [`Budget::Tiny`] the same scenes at a fortieth of the size and samples per pixel
/// (at least 1), in well under a second.
///
/// # Errors
/// [`PlotError`] if a scene cannot be built or a label cannot be drawn.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{Budget, renders};
/// let renders = renders(Budget::Tiny).unwrap();
/// let names: Vec<&str> = renders.iter().map(|f| f.file_name.as_str()).collect();
/// assert_eq!(names, ["q1_clutter.png", "q1_fog.png", "q1_mirrors.png", "q1_motion.png"]);
/// // The slab alone, 640 / 40 pixels wide; each other scene beside its twin, 2 × 320 / 40.
/// let width = |i: usize| hw3::plot::decode_png(&renders[i].bytes).unwrap().width();
/// assert_eq!((width(0), width(1)), (16, 16));
/// ```
pub fn renders(budget: Budget) -> Result<Vec<Figure>, PlotError> {
    match budget {
        Budget::Published => plot::run_jobs(&render_jobs()),
        Budget::Tiny => plot::run_jobs(&scaled_render_jobs::<TINY_DIVISOR>()),
    }
}

/// How much work [`renders`] does: the committed pictures, or a tiny version of each for examples
/// and smoke tests (its pixels are noise: it checks that the pipeline runs and what it returns).
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::Budget;
/// assert_ne!(Budget::Published, Budget::Tiny);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Budget {
    /// The committed sizes and samples per pixel ([`RENDER_SPP`]).
    Published,
    /// A fortieth of the published sizes and samples per pixel (at least one sample).
    Tiny,
}

/// What [`Budget::Tiny`] divides the renders' sizes and samples per pixel by.
const TINY_DIVISOR: u32 = 40;

/// `(width, height)` and `spp` divided by `DIVISOR` (samples at least 1).
const fn scaled<const DIVISOR: u32>((width, height): (u32, u32), spp: u32) -> ((u32, u32), u32) {
    let spp = spp / DIVISOR;
    ((width / DIVISOR, height / DIVISOR), if spp == 0 { 1 } else { spp })
}

/// Q1's renders as independent jobs, one per figure, in the chapter's order.
///
/// # Examples
/// ```
/// let jobs = hw3::q1_hard_scenes::render_jobs();
/// assert!(jobs.iter().all(|job| job.rendered) && jobs.len() == 4);
/// ```
#[must_use]
pub fn render_jobs() -> Vec<FigureJob> {
    scaled_render_jobs::<1>()
}

/// [`render_jobs`] with sizes and samples divided by `DIVISOR` ([`scaled`]); a const parameter,
/// since a job is a plain function and cannot capture a value.
fn scaled_render_jobs<const DIVISOR: u32>() -> Vec<FigureJob> {
    vec![
        FigureJob::rendered("q1 clutter render", || {
            let forest = catalogue::clutter_forest(1500, 1).map_err(|e| input_error("q1_clutter.png", e))?;
            let (size, spp) = scaled::<DIVISOR>(FULL, spp_of("clutter"));
            let image = render_image(&forest, size, spp);
            let label = format!("1500 spheres, τ = 0.70\nWhitted, {spp} spp");
            Ok(vec![plot::panel_grid("q1_clutter.png", &[plot::Panel { image, label }], 1)?])
        }),
        FigureJob::rendered("q1 fog renders", || {
            let fog = |sigma| catalogue::fog_street(sigma).map_err(|e| input_error("q1_fog.png", e));
            let (clear, foggy) = (fog(0.0)?, fog(0.08)?);
            let (half, f) = scaled::<DIVISOR>(HALF, spp_of("fog"));
            Ok(vec![pair_figure("q1_fog.png", half, [(&clear, f, "no medium"), (&foggy, f, "fog, σ_s = 0.08")])?])
        }),
        FigureJob::rendered("q1 mirror renders", || {
            let mirrors = |m| {
                catalogue::mirror_spheres(m)
                    .and_then(|scene| scene.with_camera(mirror_figure_camera()))
                    .map_err(|e| input_error("q1_mirrors.png", e))
            };
            let (mirror, diffuse) = (mirrors(true)?, mirrors(false)?);
            let (half, m) = scaled::<DIVISOR>(HALF, spp_of("mirrors"));
            let pair = [(&mirror, m, "mirror spheres"), (&diffuse, m, "the same spheres, diffuse")];
            Ok(vec![pair_figure("q1_mirrors.png", half, pair)?])
        }),
        FigureJob::rendered("q1 motion renders", || {
            let ball = |speed| catalogue::moving_ball(speed).map_err(|e| input_error("q1_motion.png", e));
            let (moving, still) = (ball(MOTION_SPEED)?, ball(0.0)?);
            let (half, b) = scaled::<DIVISOR>(HALF, spp_of("motion"));
            let pair = [(&moving, b, "ball moving during the shutter"), (&still, b, "ball at rest")];
            Ok(vec![pair_figure("q1_motion.png", half, pair)?])
        }),
    ]
}

/// The camera of the mirror render: not the measurements' camera ([`catalogue::mirror_camera`],
/// which looks along the block's axis, so that the back pair of spheres hides behind the front
/// pair) but one looking down at about 55° along the 2×2 block's diagonal, from which all four
/// spheres stand apart and the gaps between them, where the inter-reflections are, show.
fn mirror_figure_camera() -> Camera {
    Camera::looking_at(DVec3::new(2.45, 5.4, -0.55), DVec3::new(0.0, 0.45, -3.0), 40.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The labelled pairs are the same bytes on one thread and on two (per-pixel seeds), at a
    /// size the test profile renders quickly, through the code path of the notes' renders.
    #[test]
    fn labelled_renders_are_byte_identical_across_thread_counts() {
        let moving = catalogue::moving_ball(MOTION_SPEED).unwrap();
        let still = catalogue::moving_ball(0.0).unwrap();
        let on = |threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| pair_figure("t.png", (48, 36), [(&moving, 4, "moving"), (&still, 4, "still")]).unwrap())
        };
        let one = on(1);
        assert_eq!(one, on(2));
        assert_eq!(one, on(1), "and from run to run");
        let image = crate::plot::decode_png(&one.bytes).unwrap();
        assert_eq!(image.dimensions(), (96, 36));
    }

    #[test]
    fn charts_are_deterministic() {
        let rows = [(0.01, 0.5, 0.3), (0.1, 0.3, 0.25)];
        let divergence = MirrorDivergence { trials: 2, trapped: 1, median_factor: 2.5, flat: vec![(10, 1e-11, 1e-11)] };
        let a = mirror_figures(&rows, &divergence).unwrap();
        let b = mirror_figures(&rows, &divergence).unwrap();
        assert_eq!(a, b);
        assert!(String::from_utf8_lossy(&a[0].bytes).contains("mirror spheres"));
    }
}
