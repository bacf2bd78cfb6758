//! Experiments that decide table cells by measurement: each effect gets a scene built to show it
//! and a number with a threshold, measured for every method against the path-traced reference.

use super::budget::Budget;
use super::effect_scenes::{self, GLOSSY_FLOOR, WHITE_FLOOR, lit_floor, mirror_room};
use super::error::ExperimentError;
use super::grammar::{ALGORITHMS, EFFECTS, LightKind, StudentAnswer, Verdict, decide, student_answer};
use super::radiosity::{Mesh, Solver, System};
use super::regions::{bleeding_region, glow_region, grey};
use crate::geometry::Ray;
use crate::plot::markdown_table;
use crate::render::catalogue::{CornellContents, cornell_box};
use crate::render::photon::{Gather, PhotonError, PhotonMaps, trace_photons};
use crate::render::scene::{Material, Scene};
use crate::render::{
    analysis::analyze,
    passes::{Pass, Passes},
};
use crate::render::{
    integrator::{Integrator, Tracer},
    sampling::Sampler,
};
use glam::DVec3;
use serde::Serialize;
use std::sync::{Mutex, OnceLock, PoisonError};

/// Radiosity mesh used by the measured table: patches per quad edge and form-factor samples per
/// patch edge.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{experiments::TABLE_MESH, radiosity::Mesh};
/// use hw3::render::catalogue::{CornellContents, cornell_box};
/// // The box's 11 quads at 6 × 6 patches each.
/// let scene = cornell_box(true, CornellContents::Block).unwrap();
/// assert_eq!(Mesh::new(&scene, TABLE_MESH.0).unwrap().patches.len(), 11 * 36);
/// ```
pub const TABLE_MESH: (usize, usize) = Budget::PUBLISHED.table_mesh;
/// Path-traced reference: samples per measurement point.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{PATH_SPP, experiments::REFERENCE_SPP};
/// // The reference takes 8 times the samples of the smooth pictures (the caustic's take as many).
/// assert!(REFERENCE_SPP >= 8 * PATH_SPP);
/// ```
pub const REFERENCE_SPP: u32 = Budget::PUBLISHED.reference_spp;
/// A cell is Yes when the method captures at least this fraction of the reference's effect.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Measurement, YES_FRACTION, verdict};
/// assert_eq!(verdict(YES_FRACTION), Measurement::Yes);
/// assert_eq!(verdict(YES_FRACTION - 0.01), Measurement::Partial);
/// ```
pub const YES_FRACTION: f64 = 0.8;
/// A cell is No when it captures at most this fraction.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Measurement, NO_FRACTION, verdict};
/// assert_eq!(verdict(NO_FRACTION), Measurement::No);
/// assert_eq!(verdict(NO_FRACTION + 0.01), Measurement::Partial);
/// ```
pub const NO_FRACTION: f64 = 0.2;

/// A method that the experiments run.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Measured, TABLE_METHODS};
/// assert_eq!(TABLE_METHODS.map(Measured::id), ["radiosity", "two_pass", "whitted", "photon_mapping"]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measured {
    /// Radiosity with `subdivisions²` patches per quad and `samples²` form-factor samples per patch.
    Radiosity {
        /// Patches per quad edge.
        subdivisions: usize,
        /// Form-factor samples per patch edge.
        samples: usize,
    },
    /// The renderer's Whitted tracer (16 samples per point).
    Whitted,
    /// The renderer's path tracer, the reference ([`REFERENCE_SPP`] samples per point).
    PathTracing,
    /// The student's two-pass method: eye rays with direct light (Whitted's shadow rays, not traced
    /// further) plus the radiance of the *indirect* photon map ([`PHOTONS`], [`NEIGHBOURS`]).
    TwoPass,
    /// Photon mapping: the two-pass method plus the caustic map's radiance at the eye ray's
    /// first hit (no final gather).
    PhotonMapping,
}

/// Photons emitted for the two-pass and photon-mapping cells.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{NEIGHBOURS, PHOTONS};
/// // Each estimate reads a small fraction of the map.
/// assert!(NEIGHBOURS * 1000 < PHOTONS);
/// ```
pub const PHOTONS: usize = Budget::PUBLISHED.photons;
/// Neighbours of the photon-map radiance estimate for those cells.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::NEIGHBOURS;
/// // A valid gather (k ≥ 2), with no radius limit: the plain k-nearest estimate.
/// assert!(hw3::render::photon::Gather::new(NEIGHBOURS, f64::MAX).is_ok());
/// ```
pub const NEIGHBOURS: usize = 100;

impl Measured {
    /// The method's column id in [`ALGORITHMS`].
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::experiments::Measured;
    /// assert_eq!(Measured::PhotonMapping.id(), "photon_mapping");
    /// ```
    #[must_use]
    pub fn id(self) -> &'static str {
        match self {
            Measured::Radiosity { .. } => "radiosity",
            Measured::Whitted => "whitted",
            Measured::PathTracing => "path_tracing",
            Measured::TwoPass => "two_pass",
            Measured::PhotonMapping => "photon_mapping",
        }
    }
}

/// Specular bounces that photon mapping's eye rays follow (and Whitted's).
pub(super) const SPECULAR_DEPTH: u32 = 5;

/// Mean radiance arriving along the probe rays in `scene` by `method`, with the sample and photon
/// counts of `budget`.
fn mean_radiance(
    scene: &Scene,
    method: Measured,
    probes: &[Ray<f64>],
    budget: &Budget,
) -> Result<DVec3, ExperimentError> {
    let sum: DVec3 = match method {
        Measured::Radiosity { subdivisions, samples } => {
            let system = System::new(scene, Mesh::new(scene, subdivisions)?, samples)?;
            let solution = system.solve(Solver::GaussSeidel, 60).pop().unwrap_or_default();
            // Radiosity has no paths through mirrors or glass: what the probe sees first is all.
            probes
                .iter()
                .map(|ray| {
                    let hit = scene.closest_hit(ray, 0.0, f64::INFINITY);
                    hit.and_then(|h| system.radiance_at(&solution, h.object, h.point)).unwrap_or(DVec3::ZERO)
                })
                .sum()
        }
        Measured::Whitted | Measured::PathTracing => {
            let (integrator, spp) = if method == Measured::Whitted {
                (Integrator::Whitted { max_depth: SPECULAR_DEPTH }, budget.light_samples)
            } else {
                (Integrator::PathTracer { max_depth: 12 }, budget.reference_spp)
            };
            let passes = if method == Measured::PathTracing {
                reference_passes(scene)
            } else {
                integrator.restrict(analyze(scene).plan)
            };
            let tracer = Tracer::new(scene, passes);
            probes
                .iter()
                .enumerate()
                .map(|(k, ray)| {
                    let mut sampler = Sampler::new(5, k as u64, 0);
                    (0..spp).map(|_| tracer.radiance(integrator, ray, 0.0, &mut sampler)).sum::<DVec3>()
                        / f64::from(spp)
                })
                .sum()
        }
        Measured::TwoPass | Measured::PhotonMapping => {
            let maps = trace_photons(scene, budget.photons, PHOTON_SEED)?;
            let (tracer, integrator) =
                photon_eye(scene, &maps, method == Measured::PhotonMapping, budget.light_samples)?;
            probes
                .iter()
                .enumerate()
                .map(|(k, ray)| tracer.radiance(integrator, ray, 0.0, &mut Sampler::new(5, k as u64, 0)))
                .sum()
        }
    };
    Ok(sum / probes.len() as f64)
}

/// The passes of the path-traced reference: the scene's plan with every bounce on, whatever the
/// planner decides. A caustic needs the bounce off a scene's only diffuse surface, which the
/// plan (built for eye-ray effects) leaves out when no second diffuse surface exists.
pub(super) fn reference_passes(scene: &Scene) -> Passes {
    analyze(scene).plan.with(Pass::IndirectBounces, true).with(Pass::SpecularRecursion, true)
}

/// Random seed of the photon pass of the two photon methods.
pub(super) const PHOTON_SEED: u64 = 3;

/// The eye pass of the two photon methods, as the renderer's [`Tracer`] and the integrator to
/// run it with. The student's two-pass method: the eye ray's first hit gets direct light from shadow
/// rays (Whitted at depth 0, the mean of `light_samples` light samples: a mirror or glass hit stays
/// black, the ray is not traced further) plus the *indirect* photon map (photons after a diffuse
/// bounce). Photon mapping (`caustics`, Jensen): eye rays are traced through up to
/// [`SPECULAR_DEPTH`] mirror and glass bounces, and the diffuse hit adds the *caustic* map of the
/// same photon pass too. Both maps are read with the plain [`NEIGHBOURS`]-nearest estimate (no
/// radius limit), which is zero on a map of fewer photons (an open scene with no second diffuse
/// surface holds no measurable density).
///
/// # Errors
/// [`PhotonError`] never for the built-in neighbour count (a [`Gather`] needs k ≥ 2).
pub(super) fn photon_eye<'a>(
    scene: &'a Scene,
    maps: &'a PhotonMaps,
    caustics: bool,
    light_samples: u32,
) -> Result<(Tracer<'a>, Integrator), PhotonError> {
    let gather = Gather::new(NEIGHBOURS, f64::MAX)?;
    let integrator = Integrator::Whitted { max_depth: if caustics { SPECULAR_DEPTH } else { 0 } };
    let passes = integrator.restrict(analyze(scene).plan).with(Pass::SpecularRecursion, caustics);
    let tracer = Tracer::new(scene, passes).with_light_samples(light_samples).with_indirect(&maps.indirect, gather);
    Ok((if caustics { tracer.with_caustics(&maps.caustic, gather) } else { tracer }, integrator))
}

/// A measured cell.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{StudentAnswer, Verdict, experiments::{MeasuredCell, verdict}};
/// let (value, reference) = (0.29, 0.30);
/// let cell = MeasuredCell {
///     effect: "d_mirror",
///     algorithm: "whitted",
///     value,
///     reference,
///     fraction: value / reference,
///     verdict: verdict(value / reference),
///     grammar: Verdict::Yes,
///     student: StudentAnswer::NotAsked,
/// };
/// assert!(cell.verdict.agrees_with(cell.grammar));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredCell {
    /// Effect id (a row of [`EFFECTS`]).
    pub effect: &'static str,
    /// Algorithm id (a column of [`ALGORITHMS`]).
    // The JSON keeps its published field names (`method`, `seed`), so scripts reading it keep working.
    #[serde(rename = "method")]
    pub algorithm: &'static str,
    /// The measured size of the effect for this method.
    pub value: f64,
    /// The same measurement on the path-traced reference.
    pub reference: f64,
    /// `value / reference`: the fraction of the effect the method captures.
    pub fraction: f64,
    /// Yes (≥ [`YES_FRACTION`]), No (≤ [`NO_FRACTION`]) or Partial (between).
    pub verdict: Measurement,
    /// The grammar's verdict for the same cell (area light).
    pub grammar: Verdict,
    /// The student's answer for the cell (`NotAsked` for the columns the homework does not have).
    #[serde(rename = "seed")]
    pub student: StudentAnswer,
}

/// (a) Highlight: the radiance of the glossy floor of [`lit_floor`] at the mirror direction of
/// the light (probes from [`HIGHLIGHT_EYE`](effect_scenes::HIGHLIGHT_EYE)) minus the diffuse
/// level there, i.e. the same floor with the specular lobe removed (`ks = 0`, same `kd`).
///
/// # Errors
/// [`ExperimentError`] if a method fails on the scene (never for the built-in ones).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Measured, highlight};
/// use hw3::q5_effect_tables::Budget;
/// // Whitted's shadow rays evaluate the Phong lobe; radiosity keeps only the diffuse part.
/// assert!(highlight(Measured::Whitted, &Budget::PUBLISHED).unwrap() > 1.0);
/// assert_eq!(highlight(Measured::Radiosity { subdivisions: 2, samples: 1 }, &Budget::PUBLISHED).unwrap(), 0.0);
/// ```
pub fn highlight(method: Measured, budget: &Budget) -> Result<f64, ExperimentError> {
    let Material::Glossy { diffuse, .. } = GLOSSY_FLOOR else { return Err(ExperimentError::UnknownId("glossy")) };
    let probes = effect_scenes::highlight_probes();
    let glossy = mean_radiance(&lit_floor(GLOSSY_FLOOR, false)?, method, &probes, budget)?;
    let matte = mean_radiance(&lit_floor(Material::Diffuse { albedo: diffuse }, false)?, method, &probes, budget)?;
    Ok(grey(glossy - matte))
}

/// (c) Direct diffuse shading: the falloff of direct light across the white floor of [`lit_floor`], the
/// radiance under the light minus the radiance 1.5 units aside (16 probes each; the law is
/// `L = ρ/π · L_e A cosθ cosθ' / r²`, (16/18.25)² ≈ 0.77 of the peak there).
///
/// # Errors
/// As [`highlight`].
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Measured, direct_shading};
/// use hw3::q5_effect_tables::Budget;
/// assert!(direct_shading(Measured::Whitted, &Budget::PUBLISHED).unwrap() > 0.03);
/// ```
pub fn direct_shading(method: Measured, budget: &Budget) -> Result<f64, ExperimentError> {
    let scene = lit_floor(WHITE_FLOOR, false)?;
    let near = mean_radiance(&scene, method, &effect_scenes::floor_probes(DVec3::ZERO, 0.05), budget)?;
    let far = mean_radiance(&scene, method, &effect_scenes::floor_probes(DVec3::X * 1.5, 0.05), budget)?;
    Ok(grey(near - far))
}

/// (d mirror) A diffuse object seen in a mirror: the radiance along probes that hit the mirror
/// of [`mirror_room`] and, reflected, the lit red panel. The mirror gets no direct light, so a
/// method without `LDS+E` sees it black.
///
/// # Errors
/// As [`highlight`].
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Measured, mirror_image};
/// use hw3::q5_effect_tables::Budget;
/// assert!(mirror_image(Measured::Whitted, &Budget::PUBLISHED).unwrap() > 0.2);
/// assert_eq!(mirror_image(Measured::Radiosity { subdivisions: 2, samples: 1 }, &Budget::PUBLISHED).unwrap(), 0.0);
/// ```
pub fn mirror_image(method: Measured, budget: &Budget) -> Result<f64, ExperimentError> {
    Ok(grey(mean_radiance(&mirror_room()?, method, &effect_scenes::mirror_probes(), budget)?))
}

/// (d caustic) Light focused under a glass ball: the radiance of the white floor in the focus
/// (16 probes within ±0.015 of the point under the ball, all in the ball's shadow) relative to the
/// same points without the ball. 0 for a method without `LS+DE` paths: the ball's shadow.
///
/// # Errors
/// As [`highlight`].
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Measured, caustic};
/// use hw3::q5_effect_tables::Budget;
/// // Whitted's shadow ray from the focus is blocked by the glass: the shadow, no caustic.
/// assert_eq!(caustic(Measured::Whitted, &Budget::PUBLISHED).unwrap(), 0.0);
/// ```
pub fn caustic(method: Measured, budget: &Budget) -> Result<f64, ExperimentError> {
    let probes = effect_scenes::floor_probes(DVec3::ZERO, 0.01);
    let focused = mean_radiance(&lit_floor(WHITE_FLOOR, true)?, method, &probes, budget)?;
    let open = mean_radiance(&lit_floor(WHITE_FLOOR, false)?, method, &probes, budget)?;
    Ok(grey(focused) / grey(open))
}

/// (b) Colour bleeding: the red-to-green ratio on the floor strip beside the left wall, red wall
/// over white wall, minus 1 (0 = no red tint).
///
/// # Errors
/// As [`highlight`].
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Measured, bleeding};
/// use hw3::q5_effect_tables::Budget;
/// // Red light reaches the floor only by a diffuse bounce off the wall: radiosity has it, direct light not.
/// assert!(bleeding(Measured::Radiosity { subdivisions: 2, samples: 1 }, &Budget::PUBLISHED).unwrap() > 0.05);
/// assert!(bleeding(Measured::Whitted, &Budget::PUBLISHED).unwrap().abs() < 1e-12);
/// ```
pub fn bleeding(method: Measured, budget: &Budget) -> Result<f64, ExperimentError> {
    let ratio = |red: bool| -> Result<f64, ExperimentError> {
        let l = mean_radiance(&cornell_box(red, CornellContents::Block)?, method, &bleeding_region(), budget)?;
        Ok(l.x / l.y)
    };
    Ok(ratio(true)? / ratio(false)? - 1.0)
}

/// (e) Ambient glow: the channel-mean radiance on the ceiling away from the light.
///
/// # Errors
/// As [`highlight`].
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Measured, glow};
/// use hw3::q5_effect_tables::Budget;
/// assert!(glow(Measured::Radiosity { subdivisions: 2, samples: 1 }, &Budget::PUBLISHED).unwrap() > 0.0);
/// assert_eq!(glow(Measured::Whitted, &Budget::PUBLISHED).unwrap(), 0.0);
/// ```
pub fn glow(method: Measured, budget: &Budget) -> Result<f64, ExperimentError> {
    Ok(grey(mean_radiance(&cornell_box(true, CornellContents::Block)?, method, &glow_region(), budget)?))
}

/// A measurement: the size of one effect for one method.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Experiment, Measured, glow};
/// use hw3::q5_effect_tables::Budget;
/// let measure: Experiment = glow;
/// assert_eq!(measure(Measured::Whitted, &Budget::TINY).unwrap(), 0.0);
/// ```
pub type Experiment = fn(Measured, &Budget) -> Result<f64, ExperimentError>;

/// Every effect row of [`EFFECTS`] with its experiment, in table order.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{EFFECTS, experiments::EXPERIMENTS};
/// assert_eq!(EXPERIMENTS.map(|(id, _)| id), EFFECTS.map(|e| e.id));
/// ```
pub const EXPERIMENTS: [(&str, Experiment); 6] = [
    ("a", highlight),
    ("b", bleeding),
    ("c", direct_shading),
    ("d_mirror", mirror_image),
    ("d_caustic", caustic),
    ("e", glow),
];

/// The methods of the measured table at the published budget, in column order
/// ([`table_methods`]).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{ALGORITHMS, experiments::TABLE_METHODS};
/// // Every measured method is a column of the grammar's table.
/// assert!(TABLE_METHODS.iter().all(|m| ALGORITHMS.iter().any(|column| column.id == m.id())));
/// ```
pub const TABLE_METHODS: [Measured; 4] = table_methods(&Budget::PUBLISHED);

/// The methods of the measured table at `budget`, in column order: radiosity at the budget's
/// [`table_mesh`](Budget::table_mesh), the two-pass method, Whitted ray tracing and photon mapping.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{Budget, experiments::{Measured, TABLE_METHODS, table_methods}};
/// assert_eq!(table_methods(&Budget::PUBLISHED), TABLE_METHODS);
/// assert_eq!(table_methods(&Budget::TINY)[0], Measured::Radiosity { subdivisions: 2, samples: 1 });
/// ```
#[must_use]
pub const fn table_methods(budget: &Budget) -> [Measured; 4] {
    let (subdivisions, samples) = budget.table_mesh;
    [Measured::Radiosity { subdivisions, samples }, Measured::TwoPass, Measured::Whitted, Measured::PhotonMapping]
}

/// What a measured fraction of an effect says about a method.
///
/// A measurement sees how much of the effect a method's estimate holds, not how the method finds
/// it: a method that reaches some of the effect's paths only by chance (the grammar's
/// [`Verdict::Impractical`]) still averages to the whole effect once it has enough samples, and
/// only its noise tells. So the measurement has no word for *impractical*; its middle band is a
/// method that holds part of the effect.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Measurement {
    /// At least [`YES_FRACTION`] of the effect.
    Yes,
    /// Between [`NO_FRACTION`] and [`YES_FRACTION`]: part of the effect.
    Partial,
    /// At most [`NO_FRACTION`] of the effect.
    No,
}

impl Measurement {
    /// The word the table prints.
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::experiments::Measurement;
    /// assert_eq!([Measurement::Yes, Measurement::Partial, Measurement::No].map(Measurement::text), ["Yes", "Partial", "No"]);
    /// ```
    #[must_use]
    pub fn text(self) -> &'static str {
        match self {
            Measurement::Yes => "Yes",
            Measurement::Partial => "Partial",
            Measurement::No => "No",
        }
    }

    /// Whether the measurement bears out the grammar's verdict: Yes for Yes, No for No. A partial
    /// measurement bears out no verdict, and an impractical cell cannot be told from a Yes by its
    /// average (see [`Measurement`]), so it is never borne out by one.
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::{Verdict, experiments::Measurement};
    /// assert!(Measurement::No.agrees_with(Verdict::No));
    /// assert!(!Measurement::Yes.agrees_with(Verdict::Impractical));
    /// ```
    #[must_use]
    pub fn agrees_with(self, grammar: Verdict) -> bool {
        matches!((self, grammar), (Measurement::Yes, Verdict::Yes) | (Measurement::No, Verdict::No))
    }
}

/// The measurement's word for a fraction of the effect: Yes at [`YES_FRACTION`] or more, No at
/// [`NO_FRACTION`] or less, Partial in between.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{Measurement, verdict};
/// assert_eq!((verdict(0.97), verdict(0.5), verdict(0.0)), (Measurement::Yes, Measurement::Partial, Measurement::No));
/// ```
#[must_use]
pub fn verdict(fraction: f64) -> Measurement {
    if fraction >= YES_FRACTION {
        Measurement::Yes
    } else if fraction <= NO_FRACTION {
        Measurement::No
    } else {
        Measurement::Partial
    }
}

/// The measured table: every effect of [`EXPERIMENTS`] for radiosity, the two-pass method,
/// Whitted ray tracing and photon mapping ([`table_methods`]) against the path tracer,
/// with the sample and photon counts of `budget`.
///
/// At [`Budget::PUBLISHED`] (the committed `q5_measured_table.md`, pinned by
/// `experiments::tests`) it is computed once per process and then cloned: the test, the figures
/// and `hw3 effect-tables` share it (that command prints little more than the table). Any other budget is measured afresh on every call.
///
/// Threads outside the rayon pool wait for one another, so such callers measure it once. A pool
/// thread never waits for it: while a worker waits inside rayon for part of its own work, it runs
/// other queued jobs, so a worker that waited here could be the very thread that is measuring the
/// table (re-entered), or could hold beneath its wait a piece the measurement needs; either way it
/// would wait for itself (possible when two pool jobs read the table, on three or more threads).
/// A worker that finds no table measures one itself, and whichever table is stored first is kept;
/// the measurements are seeded, so every copy is the same. Pool jobs that read it are best run
/// after one measurement outside them, as `all_figures` does.
///
/// # Errors
/// [`ExperimentError`] if an experiment fails (never for the built-in scenes).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{Budget, experiments::{EXPERIMENTS, measured_table}};
/// let cells = measured_table(&Budget::TINY).unwrap();
/// assert_eq!(cells.len(), EXPERIMENTS.len() * 4);
/// // Whatever the budget, radiosity sees no highlight and nothing in a mirror: exactly 0.
/// let radiosity = |effect: &str| cells.iter().find(|c| c.effect == effect && c.algorithm == "radiosity").unwrap().value;
/// assert_eq!((radiosity("a"), radiosity("d_mirror")), (0.0, 0.0));
/// ```
pub fn measured_table(budget: &Budget) -> Result<Vec<MeasuredCell>, ExperimentError> {
    static TABLE: OnceLock<Result<Vec<MeasuredCell>, ExperimentError>> = OnceLock::new();
    // Whose turn it is to measure, among threads outside the pool; it guards no data, so a
    // panicking measurement's poison is ignored.
    static MEASURING: Mutex<()> = Mutex::new(());
    if *budget != Budget::PUBLISHED {
        return measure_table(budget);
    }
    if let Some(table) = TABLE.get() {
        return table.clone();
    }
    let _turn =
        rayon::current_thread_index().is_none().then(|| MEASURING.lock().unwrap_or_else(PoisonError::into_inner));
    if let Some(table) = TABLE.get() {
        return table.clone();
    }
    let table = measure_table(&Budget::PUBLISHED);
    // Only a finished table is moved into the cell: no thread ever waits here on a measurement.
    TABLE.get_or_init(|| table).clone()
}

/// Every measurement of the table (each effect's reference, then its methods) is independent of
/// the others and seeded by its own probes and photon seed, so they run on the rayon pool and are
/// gathered in table order: the same cells on any number of threads. The results are then read in
/// the order the one-thread loop took them, so a failing table returns the error that loop would
/// have met first (a parallel `collect` into `Result` keeps whichever failed first in time).
fn measure_table(budget: &Budget) -> Result<Vec<MeasuredCell>, ExperimentError> {
    use rayon::prelude::*;
    let methods = table_methods(budget);
    let runs: Vec<(usize, Measured)> = (0..EXPERIMENTS.len())
        .flat_map(|e| std::iter::once(Measured::PathTracing).chain(methods).map(move |m| (e, m)))
        .collect();
    let results: Vec<Result<f64, ExperimentError>> =
        runs.par_iter().map(|&(e, method)| (EXPERIMENTS[e].1)(method, budget)).collect();
    let mut results = results.into_iter();
    let mut next = || results.next().expect("one result per run");
    let mut cells = Vec::new();
    for &(effect, _) in &EXPERIMENTS {
        let reference = next()?;
        let row = EFFECTS.iter().find(|e| e.id == effect).ok_or(ExperimentError::UnknownId(effect))?;
        for method in methods {
            let value = next()?;
            let fraction = value / reference;
            let column =
                ALGORITHMS.iter().find(|m| m.id == method.id()).ok_or(ExperimentError::UnknownId(method.id()))?;
            let grammar = decide(row, column, LightKind::Area).map(|c| c.verdict).unwrap_or(Verdict::No);
            let verdict = verdict(fraction);
            let student = student_answer(column, row);
            cells.push(MeasuredCell {
                effect,
                algorithm: method.id(),
                value,
                reference,
                fraction,
                verdict,
                grammar,
                student,
            });
        }
    }
    Ok(cells)
}

/// The measured table as markdown.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::{MeasuredCell, Measurement, measured_table_markdown};
/// use hw3::q5_effect_tables::{StudentAnswer, Verdict};
/// let cell = MeasuredCell {
///     effect: "d_caustic",
///     algorithm: "two_pass",
///     value: 0.017,
///     reference: 57.6,
///     fraction: 0.017 / 57.6,
///     verdict: Measurement::No,
///     grammar: Verdict::No,
///     student: StudentAnswer::No,
/// };
/// let table = measured_table_markdown(&[cell]);
/// assert!(table.ends_with("| (d caustic) | two_pass | 0.0170 | 57.6000 | 0.000 | No | No | No |\n"));
/// ```
#[must_use]
pub fn measured_table_markdown(cells: &[MeasuredCell]) -> String {
    let header =
        ["effect", "method", "measured", "path-traced reference", "fraction", "measured verdict", "grammar", "student"];
    markdown_table(
        &header,
        cells.iter().map(|c| {
            [
                format!("({})", c.effect.replace('_', " ")),
                c.algorithm.to_string(),
                format!("{:.4}", c.value),
                format!("{:.4}", c.reference),
                format!("{:.3}", c.fraction),
                c.verdict.text().to_string(),
                c.grammar.text().to_string(),
                c.student.text().to_string(),
            ]
        }),
    )
}

/// The radiosity system of the Cornell box with the block and the red wall ([`cornell_box`]),
/// its quads cut into `n × n` patches, `samples²` form-factor samples per patch (figures and
/// benchmarks).
///
/// # Errors
/// As [`System::new`].
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::experiments::cornell_system;
/// // 11 quads of 2 × 2 patches.
/// let (_, system) = cornell_system(2, 1).unwrap();
/// assert_eq!(system.mesh.patches.len(), 44);
/// ```
pub fn cornell_system(n: usize, samples: usize) -> Result<(Scene, System), ExperimentError> {
    let scene = cornell_box(true, CornellContents::Block)?;
    let system = System::new(&scene, Mesh::new(&scene, n)?, samples)?;
    Ok((scene, system))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{camera::Camera, scene::Object};
    use std::f64::consts::PI;

    /// Every measured verdict equals the grammar's. The two-pass caustic is the telling cell:
    /// its photon map keeps only photons that already bounced off a diffuse surface, so the
    /// `LS+D` photons that make a caustic never reach it (the grammar's No), and the focus
    /// measures as dark as the ball's shadow; photon mapping, which reads its caustic map at the
    /// same first hit, captures it.
    #[test]
    fn measured_cells_agree_with_the_grammar_and_are_pinned() {
        let cells = measured_table(&Budget::PUBLISHED).unwrap();
        assert_eq!(cells.len(), EXPERIMENTS.len() * TABLE_METHODS.len());
        for c in &cells {
            assert!(c.reference > 0.0 && c.fraction.is_finite(), "{c:?}");
            assert!(c.verdict.agrees_with(c.grammar), "{c:?}");
        }
        let caustic = |method| cells.iter().find(|c| (c.effect, c.algorithm) == ("d_caustic", method)).unwrap();
        // Only photons that bounced off the floor, into the ball and back reach the focus.
        assert!(caustic("two_pass").fraction < 0.01, "{:?}", caustic("two_pass"));
        assert!(caustic("photon_mapping").fraction > 0.8, "{:?}", caustic("photon_mapping"));
        crate::testing::insta_settings().bind(|| {
            insta::assert_snapshot!("q5_measured_table", measured_table_markdown(&cells));
        });
    }

    /// White furnace with variance, for the path tracer that is the table's reference: inside a
    /// closed unit sphere of albedo ρ with a point light I off the centre (at 0.3, 0, 0), the
    /// irradiance from a Lambertian sphere's own walls is the same everywhere (the kernel
    /// cosθ cosθ′/r² is 1/(4R²) for any two points of a sphere), so every point receives the
    /// direct `I cosθ/r²` plus `ρ Φ/(A(1 − ρ)) = ρI/(R²(1 − ρ))`, and
    /// `L = ρ/π · (I cosθ/r² + ρI/(1 − ρ))`. Unlike the centred light (pbrt's test, exact to
    /// rounding in `render::integrator::tests`), the bounces now vary; 2·10⁴ paths per probe put
    /// the standard error near 0.2 %: within 1 % and within 4 standard errors at five probes.
    #[test]
    fn path_tracer_furnace_with_an_off_centre_light_is_within_one_percent() {
        let albedo = 0.5;
        let shell = Object::sphere(
            crate::geometry::Sphere::new(DVec3::ZERO, 1.0).unwrap(),
            Material::Diffuse { albedo: DVec3::splat(albedo) },
        );
        let light = crate::render::scene::PointLight { position: DVec3::new(0.3, 0.0, 0.0), intensity: DVec3::ONE };
        let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.5), DVec3::ZERO, 40.0);
        let scene = Scene::new(camera, vec![shell], vec![light], None, DVec3::ZERO).unwrap();
        let tracer = Tracer::new(&scene, reference_passes(&scene));
        let samples = 20_000;
        for (k, dir) in [DVec3::X, DVec3::NEG_X, DVec3::Y, DVec3::new(0.3, -0.5, 0.8), DVec3::new(-0.6, 0.2, -0.7)]
            .into_iter()
            .enumerate()
        {
            let ray = Ray { origin: DVec3::new(0.0, 0.1, 0.0), dir: dir.normalize() };
            let p = scene.closest_hit(&ray, 0.0, f64::INFINITY).unwrap().point;
            let to_light = light.position - p;
            let r = to_light.length();
            let cosine = (-p).dot(to_light) / r;
            let exact = albedo / PI * (cosine / (r * r) + albedo / (1.0 - albedo));
            let mut sampler = Sampler::new(11, k as u64, 0);
            let values: Vec<f64> = (0..samples)
                .map(|_| tracer.radiance(Integrator::PathTracer { max_depth: 60 }, &ray, 0.0, &mut sampler).x)
                .collect();
            let n = f64::from(samples);
            let mean = values.iter().sum::<f64>() / n;
            let error = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
            assert!((mean / exact - 1.0).abs() < 0.01, "probe {k}: {mean} vs {exact}");
            assert!((mean - exact).abs() < 4.0 * error, "probe {k}: {mean} vs {exact} ± {error}");
        }
    }

    #[test]
    fn the_glow_region_gets_no_direct_light() {
        // Direct light only (Whitted) sees nothing on the ceiling: the region is lit indirectly.
        assert_eq!(glow(Measured::Whitted, &Budget::PUBLISHED).unwrap(), 0.0);
    }
}
