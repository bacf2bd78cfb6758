//! The numbers Q1's answer states, read from the committed measurement tables (`docs/figures/`),
//! so that `hw3 answers --question q1` and the chapter print the same values from one source.
//! The engineering notes include the tables in full; the chapter states their lessons.
//! The tables are what the code measures: `tests/docs.rs` regenerates every one and
//! compares it with the committed file byte for byte.

use super::fog::{FOG_SIGMAS, visual_range};
use crate::plot::markdown_rows;

/// The committed tables the findings are read from.
const CLUTTER_TABLE: &str = include_str!("../../docs/figures/q1_clutter_table.md");
const CLUTTER_HARDNESS: &str = include_str!("../../docs/figures/q1_clutter_hardness.md");
const FOG_TABLE: &str = include_str!("../../docs/figures/q1_fog_table.md");
const AIRLIGHT_TABLE: &str = include_str!("../../docs/figures/q1_airlight_table.md");
const MIRROR_TABLE: &str = include_str!("../../docs/figures/q1_mirror_table.md");
const DIVERGENCE_TABLE: &str = include_str!("../../docs/figures/q1_mirror_divergence_table.md");
const MOTION_TABLE: &str = include_str!("../../docs/figures/q1_motion_table.md");

/// What Q1's measurements found, each number as the committed tables hold it.
///
/// # Examples
/// ```
/// let found = hw3::q1_hard_scenes::findings();
/// // Every measured gap fraction lies within one standard error of the exact law.
/// assert!(found.clutter_largest_z < 1.0);
/// // The mirror spheres change faster than their diffuse twin at every camera step.
/// assert!(found.sensitivity_ratios.0 > 1.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Findings {
    /// Sphere counts of the clutter table, first and last.
    pub clutter_counts: (u64, u64),
    /// The largest `|gap measured − (1 − p)^N| / s.e.` over the clutter table's rows.
    pub clutter_largest_z: f64,
    /// Spheres a camera ray passes through, at the fewest and the most spheres.
    pub spheres_passed: (f64, f64),
    /// Share of the spheres in view that no pixel sees, at the fewest and the most spheres.
    pub spheres_hidden: (f64, f64),
    /// Share of the pixels whose sphere changes for a small camera step, fewest and most spheres.
    pub pixels_changed: (f64, f64),
    /// Ray/sphere tests per camera ray with the kd-tree, fewest and most spheres.
    pub kd_tests: (f64, f64),
    /// The largest relative difference between the measured transmittance and `e^(−σ_t d)`, in
    /// per cent: the fog probe's path is `ℓ = 1.0062 d`, not `d`.
    pub fog_path_excess_percent: f64,
    /// For each σ_t of the fog table, the target distance after which the airlight falls (`None`
    /// where it grows over every distance measured).
    pub airlight_falls_after: Vec<(f64, Option<f64>)>,
    /// The largest relative error of the renderer's airlight at 32 steps and at 4096 steps.
    pub airlight_errors: (f64, f64),
    /// The lowest and highest ratio of the mirror to the diffuse image change per camera move.
    pub sensitivity_ratios: (f64, f64),
    /// Median growth of a ray pair's separation per bounce between the four mirror spheres.
    pub mirror_growth: f64,
    /// The moving ball's image speed, pixels per frame.
    pub ball_pixels_per_frame: f64,
    /// The noise constants `c` of the moving and the resting ball.
    pub noise_constants: (f64, f64),
    /// Samples per pixel for the noise target, moving and resting.
    pub spp_needed: (u64, u64),
}

fn number(cell: &str) -> f64 {
    cell.trim_start_matches("< ").parse().unwrap_or_else(|_| panic!("a committed table's number: {cell}"))
}

/// The number after `marker` in `text` (up to the next space or `;`).
fn after(text: &str, marker: &str) -> f64 {
    let start = text.find(marker).unwrap_or_else(|| panic!("{marker}")) + marker.len();
    let rest = &text[start..];
    number(rest.split([' ', ';', ',']).next().unwrap_or(""))
}

/// The findings of Q1's measurements, read from the committed tables.
///
/// # Panics
/// Never for the committed tables (a test reads every field).
///
/// # Examples
/// ```
/// let found = hw3::q1_hard_scenes::findings();
/// assert_eq!(found.clutter_counts, (250, 4000));
/// assert!(found.ball_pixels_per_frame > 0.5);
/// ```
#[must_use]
pub fn findings() -> Findings {
    let clutter = markdown_rows(CLUTTER_TABLE);
    let clutter_largest_z =
        clutter.iter().map(|r| ((number(r[2]) - number(r[4])) / number(r[3])).abs()).fold(0.0, f64::max);
    let hardness = markdown_rows(CLUTTER_HARDNESS);
    let ends = |column: usize| {
        let (first, last) = (hardness.first().expect("rows"), hardness.last().expect("rows"));
        (number(first[column]), number(last[column]))
    };
    let fog = markdown_rows(FOG_TABLE);
    let fog_path_excess_percent = fog
        .iter()
        .map(|r| (1.0 - number(r[2]) / (-number(r[0]) * number(r[1])).exp()).abs() * 100.0)
        .fold(0.0, f64::max);
    let airlight_falls_after = FOG_SIGMAS
        .iter()
        .map(|&sigma| {
            let of_sigma: Vec<(f64, f64)> =
                fog.iter().filter(|r| number(r[0]) == sigma).map(|r| (number(r[1]), number(r[5]))).collect();
            let falls = of_sigma.windows(2).find(|w| w[1].1 < w[0].1).map(|w| w[0].0);
            (sigma, falls)
        })
        .collect();
    let airlight = markdown_rows(AIRLIGHT_TABLE);
    let worst = |column: usize| airlight.iter().map(|r| number(r[column])).fold(0.0, f64::max);
    // The motion table's last line: "slope moving …, resting …; c moving C, resting C; spp for
    // RMSE …: moving N, resting N".
    let fit_line = MOTION_TABLE.lines().find(|l| l.starts_with("slope moving")).expect("the motion fit line");
    let noise_fit = &fit_line[fit_line.find("; c moving").expect("c")..];
    let constants = noise_fit["; c moving ".len()..].split(',').next().unwrap_or("");
    let spp = &fit_line[fit_line.find("spp for RMSE").expect("spp")..];
    let ratios: Vec<f64> = markdown_rows(MIRROR_TABLE).iter().map(|r| number(r[3])).collect();
    let sensitivity_ratios =
        (ratios.iter().copied().fold(f64::INFINITY, f64::min), ratios.iter().copied().fold(0.0, f64::max));
    Findings {
        clutter_counts: (number(clutter[0][0]) as u64, number(clutter[clutter.len() - 1][0]) as u64),
        clutter_largest_z,
        spheres_passed: ends(1),
        spheres_hidden: ends(3),
        pixels_changed: ends(4),
        kd_tests: ends(6),
        fog_path_excess_percent,
        airlight_falls_after,
        airlight_errors: (worst(5), worst(7)),
        sensitivity_ratios,
        mirror_growth: after(DIVERGENCE_TABLE, "median growth ×"),
        ball_pixels_per_frame: after(MOTION_TABLE, "image speed of the ball: "),
        noise_constants: (after(noise_fit, "c moving "), after(noise_fit, &format!("{constants}, resting "))),
        spp_needed: (after(spp, ": moving ") as u64, after(spp, "resting ") as u64),
    }
}

impl Findings {
    /// The ratio of the moving to the resting ball's noise constant, as the chapter prints it.
    #[must_use]
    pub fn noise_constant_ratio(&self) -> String {
        format!("{:.2}", self.noise_constants.0 / self.noise_constants.1)
    }

    /// The ratio of the samples the moving ball needs to the resting ball's, as printed.
    #[must_use]
    pub fn spp_ratio(&self) -> String {
        format!("{:.2}", (self.noise_constants.0 / self.noise_constants.1).powi(2))
    }

    /// The range of the mirror-to-diffuse sensitivity ratios, as printed (`1.155–1.690`).
    #[must_use]
    pub fn sensitivity_range(&self) -> String {
        format!("{:.3}–{:.3}", self.sensitivity_ratios.0, self.sensitivity_ratios.1)
    }

    /// The visual ranges of the fog table's densities, as printed (`78.2 / 39.1 / 19.6`).
    #[must_use]
    pub fn visual_ranges(&self) -> String {
        FOG_SIGMAS.map(|s| format!("{:.1}", visual_range(s))).join(" / ")
    }

    /// Where the airlight stops growing, in words: `σ_t = 0.2 beyond d = 5`.
    #[must_use]
    pub fn airlight_turn(&self) -> String {
        let falling: Vec<String> = self
            .airlight_falls_after
            .iter()
            .filter_map(|(sigma, d)| d.map(|d| format!("σ_t = {sigma} beyond d = {d}")))
            .collect();
        if falling.is_empty() { "nowhere in the table".into() } else { falling.join(" and ") }
    }

    /// The phrases the chapter and `hw3 answers` share, each exactly as both print it.
    #[must_use]
    pub fn shared_phrases(&self) -> Vec<String> {
        vec![
            format!("within {:.2} standard errors", self.clutter_largest_z),
            format!("{:.0} % to {:.0} %", self.pixels_changed.0 * 100.0, self.pixels_changed.1 * 100.0),
            format!("{:.0} to {:.0} spheres per ray", self.kd_tests.0, self.kd_tests.1),
            self.airlight_turn(),
            self.visual_ranges(),
            format!("{}×", self.sensitivity_range()),
            format!("×{:.2} per bounce", self.mirror_growth),
            format!("{:.1} pixels per frame", self.ball_pixels_per_frame),
            format!("{}× the noise constant", self.noise_constant_ratio()),
            format!("{}× the samples", self.spp_ratio()),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The findings are read from tables whose rows are those the code measures: the
    /// clutter table's exact law, the fog probe's path factor, and the motion table's counts.
    #[test]
    fn findings_are_the_tables_numbers() {
        let found = findings();
        assert_eq!(found.clutter_counts, (250, 4000));
        assert!(found.clutter_largest_z > 0.0 && found.clutter_largest_z < 2.0);
        let path_excess = (1.0 - (-0.2 * 40.0 * (super::super::fog::fog_path_factor() - 1.0)).exp()) * 100.0;
        assert!((found.fog_path_excess_percent - path_excess).abs() < 1e-3, "{found:?}");
        let (moving, resting) = found.spp_needed;
        let needed = |c: f64| (c / super::super::motion::NOISE_TARGET).powi(2).ceil() as u64;
        assert_eq!((needed(found.noise_constants.0), needed(found.noise_constants.1)), (moving, resting));
        assert!(found.sensitivity_ratios.0 > 1.0 && found.sensitivity_ratios.1 > found.sensitivity_ratios.0);
        assert!(found.kd_tests.1 < found.clutter_counts.1 as f64 / 10.0);
    }
}
