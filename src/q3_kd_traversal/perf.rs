//! The cost-versus-N plots of the 3-D kd-tree, drawn from the committed benchmark CSV
//! (`docs/data/q3_kdtree_perf.csv`, written by `cargo bench -p hw3-benches --bench q3_kdtree`), so that
//! `cargo run` stays deterministic: timings come only from the benchmark. The chapter's plot
//! (`q3_kdtree_scaling.svg`) shows the crate's tree against testing every sphere, what an
//! acceleration structure buys; the engineering notes' plot (`q3_kdtree_cost.svg`) adds the peer
//! libraries measured in the same run.

use crate::data;
use crate::plot::{
    Axis, Chart, Dots, DrawError, Figure, LegendMark, PALETTE, PlotError, Series, Stroke, legend_grid, svg_figure,
};
use plotters::prelude::*;
use std::collections::BTreeMap;

/// The committed measurements.
const CSV: &str = data::Q3_KDTREE_PERF;

/// Which ray set a panel shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Rays {
    Camera,
    Random,
}

/// One measured row: density label, N, and every field of the row by its CSV column name.
#[derive(Debug, Clone, PartialEq)]
struct Row {
    density: String,
    n: f64,
    fields: BTreeMap<String, String>,
}

/// A plotted method: legend label, the CSV column names of its camera and random Mrays/s, and its
/// colour in [`PALETTE`].
struct Structure {
    label: &'static str,
    camera_column: &'static str,
    random_column: &'static str,
    colour: usize,
}

/// The methods of the plot. The peers (`bvh` crate with the bench's own front-to-back loop,
/// `obvhs` BVH2 and CWBVH, Embree 3) are measured in the same run as the kd-tree, on an `f32`
/// scene. Columns are found by name, so that the benchmark may add columns anywhere.
const STRUCTURES: [Structure; 6] = [
    Structure {
        label: "kd-tree (this crate, f64)",
        camera_column: "camera_mrays",
        random_column: "random_mrays",
        colour: 0,
    },
    Structure {
        label: "brute force",
        camera_column: "brute_camera_mrays",
        random_column: "brute_random_mrays",
        colour: 3,
    },
    Structure {
        label: "bvh 0.13 + own loop",
        camera_column: "bvh_camera_mrays",
        random_column: "bvh_random_mrays",
        colour: 4,
    },
    Structure {
        label: "obvhs BVH2",
        camera_column: "obvhs_bvh2_camera_mrays",
        random_column: "obvhs_bvh2_random_mrays",
        colour: 2,
    },
    Structure {
        label: "obvhs CWBVH",
        camera_column: "obvhs_cwbvh_camera_mrays",
        random_column: "obvhs_cwbvh_random_mrays",
        colour: 1,
    },
    Structure {
        label: "Embree 3.13",
        camera_column: "embree3_camera_mrays",
        random_column: "embree3_random_mrays",
        colour: 7,
    },
];

impl Row {
    /// Microseconds per ray from a Mrays/s field (`-`, absent or zero: not measured).
    fn us_per_ray(&self, column: &str) -> Option<f64> {
        self.fields.get(column)?.parse::<f64>().ok().filter(|m| *m > 0.0).map(|m| 1.0 / m)
    }
}

fn rows(text: &str) -> Vec<Row> {
    let table = data::csv(text);
    table
        .records
        .into_iter()
        .filter_map(|fields| {
            let density = (*fields.first()?).to_string();
            let n = fields.get(1)?.parse().ok()?;
            let fields =
                table.header.iter().zip(fields).map(|(&name, field)| (name.to_string(), field.to_string())).collect();
            Some(Row { density, n, fields })
        })
        .collect()
}

/// Width of the cost figure in pixels: the notes' text column, so that it is shown at its own
/// size (its 12 px labels stay 12 px on screen).
const WIDTH: u32 = 936;
/// Height of each panel, and of the legend strip below both.
const PANEL_HEIGHT: u32 = 430;
const LEGEND_HEIGHT: u32 = 88;

/// Which methods a plot shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shown {
    /// The crate's kd-tree and testing every sphere (the chapter's plot).
    TreeAndBruteForce,
    /// Every method of [`STRUCTURES`] (the engineering notes' plot).
    WithPeers,
}

/// Height of the chapter's legend strip: its three entries fit one row.
const SCALING_LEGEND_HEIGHT: u32 = 36;

/// The engineering notes' plot: every method, both ray sets.
pub(super) fn figure() -> Result<Figure, PlotError> {
    draw("q3_kdtree_cost.svg", Shown::WithPeers, LEGEND_HEIGHT)
}

/// The chapter's plot: the crate's kd-tree at both densities against testing every sphere.
pub(super) fn scaling_figure() -> Result<Figure, PlotError> {
    draw("q3_kdtree_scaling.svg", Shown::TreeAndBruteForce, SCALING_LEGEND_HEIGHT)
}

fn draw(name: &str, shown: Shown, legend_height: u32) -> Result<Figure, PlotError> {
    let rows = rows(CSV);
    let n_max = rows.iter().map(|r| r.n).fold(100.0, f64::max);
    svg_figure(name, (WIDTH, PANEL_HEIGHT + legend_height), |root| {
        let (panels, legend) = root.split_vertically(PANEL_HEIGHT);
        let (left, right) = panels.split_horizontally(WIDTH / 2);
        panel(&left, &rows, n_max, Rays::Camera, shown)?;
        panel(&right, &rows, n_max, Rays::Random, shown)?;
        // One legend for both panels, below them, so that it hides no line.
        legend_grid(&legend, &series(&rows, Rays::Camera, shown), 3, 13)
    })
}

/// µs per ray against N for the methods shown, on one ray set: each at fixed k (the main
/// workload), and the kd-tree also at fixed volume fraction, dashed and in sky blue, to show the
/// density scaling.
fn series(rows: &[Row], rays: Rays, shown: Shown) -> Vec<Series> {
    let methods = STRUCTURES
        .iter()
        .filter(|m| shown == Shown::WithPeers || m.camera_column == "camera_mrays" || m.label == "brute force")
        .map(|m| (m, "fixed_k"))
        .chain(std::iter::once((&STRUCTURES[0], "fixed_volume")));
    methods
        .map(|(method, density)| {
            let column = match rays {
                Rays::Camera => method.camera_column,
                Rays::Random => method.random_column,
            };
            let (colour, dash, scaling) = match density {
                "fixed_k" => (PALETTE[method.colour], None, "fixed k"),
                _ => (PALETTE[5], Some((7, 4)), "fixed volume"),
            };
            let points = rows
                .iter()
                .filter(|r| r.density == density)
                .filter_map(|r| Some((r.n, r.us_per_ray(column)?)))
                .collect();
            Series {
                line: Some(Stroke { width: 2, dash }),
                dots: Some(Dots { radius: 3, ring: None }),
                legend: LegendMark::Line { length: 18, width: 2 },
                ..Series::line(format!("{}, {scaling}", method.label), points, colour, 2)
            }
        })
        .collect()
}

/// One log-log panel: µs per ray against N for the methods shown.
fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    rows: &[Row],
    n_max: f64,
    rays: Rays,
    shown: Shown,
) -> Result<(), DrawError> {
    let title = match (rays, shown) {
        (Rays::Camera, Shown::WithPeers) => "camera rays 512×512 (1 thread)",
        (Rays::Random, Shown::WithPeers) => "10⁶ random rays (1 thread)",
        (Rays::Camera, Shown::TreeAndBruteForce) => "rays from a camera outside the scene",
        (Rays::Random, Shown::TreeAndBruteForce) => "rays from random points inside the scene",
    };
    Chart {
        caption_size: 16,
        label_areas: (40, 56),
        label_size: 13,
        series: series(rows, rays, shown),
        legend: None,
        ..Chart::new(
            title,
            Axis { format: Some(|v| format!("{v:.0e}")), ..Axis::log(50.0, 2.0 * n_max, "N spheres") },
            Axis { format: Some(|v| format!("{v}")), ..Axis::log(0.05, 100.0, "µs per ray") },
        )
    }
    .draw(area)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn committed_csv_parses_into_both_densities() {
        let rows = rows(CSV);
        for density in ["fixed_k", "fixed_volume"] {
            let ns: Vec<f64> = rows.iter().filter(|r| r.density == density).map(|r| r.n).collect();
            assert!(ns.len() >= 4, "{density}: {ns:?}");
            assert!(ns.windows(2).all(|w| w[0] < w[1]));
        }
    }

    /// Every peer's camera and random rates are present for every committed row (they are measured
    /// in the same run as the kd-tree), so the plot shows no silently missing series. Embree's
    /// columns need the benchmark's `embree` feature: the committed data come from
    /// `HW3_Q3_MAX_N=1000000 cargo bench -p hw3-benches --bench q3_kdtree --features embree`.
    #[test]
    fn committed_csv_has_every_peer_for_every_row() {
        for row in rows(CSV) {
            for method in STRUCTURES.iter().filter(|m| m.label != "brute force") {
                assert!(row.us_per_ray(method.camera_column).is_some(), "{} N={} {}", row.density, row.n, method.label);
                assert!(row.us_per_ray(method.random_column).is_some(), "{} N={} {}", row.density, row.n, method.label);
            }
        }
    }

    #[test]
    fn cost_plot_is_pinned() {
        let _guard = crate::testing::insta_settings().bind_to_scope();
        let figure = figure().unwrap();
        insta::assert_snapshot!("q3_kdtree_cost", String::from_utf8(figure.bytes).unwrap());
    }

    /// The chapter's plot shows the crate's tree at both densities and testing every sphere, and
    /// no peer library.
    #[test]
    fn the_chapters_plot_shows_no_peer() {
        let svg = String::from_utf8(scaling_figure().unwrap().bytes).unwrap();
        for label in
            ["kd-tree (this crate, f64), fixed k", "kd-tree (this crate, f64), fixed volume", "brute force, fixed k"]
        {
            assert!(svg.contains(label), "{label}");
        }
        for peer in ["bvh", "obvhs", "Embree", "thread"] {
            assert!(!svg.contains(peer), "{peer}");
        }
    }
}
