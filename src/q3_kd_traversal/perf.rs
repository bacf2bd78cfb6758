//! The cost-versus-N plot of the 3-D kd-tree, drawn from the committed benchmark CSV
//! (`docs/data/q3_kdtree_perf.csv`, written by `cargo bench --bench q3_kdtree`), so that
//! `cargo run` stays deterministic: timings come only from the benchmark.

use crate::plot::{Figure, PALETTE, PlotError, err, svg_figure};
use plotters::prelude::*;

/// The committed measurements.
const CSV: &str = include_str!("../../docs/data/q3_kdtree_perf.csv");

/// One measured row: density label, N, and microseconds per ray (camera, random; kd-tree, then
/// brute force where measured).
#[derive(Debug, Clone, PartialEq)]
struct Row {
    density: String,
    n: f64,
    kd_camera_us: f64,
    kd_random_us: f64,
    brute_camera_us: Option<f64>,
    brute_random_us: Option<f64>,
}

/// Microseconds per ray from a Mrays/s field (`-` means not measured).
fn us_per_ray(field: &str) -> Option<f64> {
    field.parse::<f64>().ok().filter(|m| *m > 0.0).map(|m| 1.0 / m)
}

fn rows(csv: &str) -> Vec<Row> {
    csv.lines()
        .skip(1)
        .filter_map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            Some(Row {
                density: f.first()?.to_string(),
                n: f.get(1)?.parse().ok()?,
                kd_camera_us: us_per_ray(f.get(5)?)?,
                kd_random_us: us_per_ray(f.get(10)?)?,
                brute_camera_us: us_per_ray(f.get(15)?),
                brute_random_us: us_per_ray(f.get(16)?),
            })
        })
        .collect()
}

pub(super) fn figure() -> Result<Figure, PlotError> {
    let rows = rows(CSV);
    let n_max = rows.iter().map(|r| r.n).fold(100.0, f64::max);
    svg_figure("q3_kdtree_cost.svg", (640, 440), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption("kd-tree closest hit: time per ray vs N (1 thread)", ("sans-serif", 17))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(52)
            .build_cartesian_2d((50.0..2.0 * n_max).log_scale(), (0.05..300.0).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("N spheres")
            .y_desc("µs per ray")
            .label_style(("sans-serif", 12))
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v}"))
            .draw()
            .map_err(err)?;
        type Pick = fn(&Row) -> Option<f64>;
        let series: [(&str, &str, Pick, usize); 6] = [
            ("fixed_k", "kd camera, fixed k", |r| Some(r.kd_camera_us), 0),
            ("fixed_k", "kd random, fixed k", |r| Some(r.kd_random_us), 1),
            ("fixed_volume", "kd camera, fixed volume", |r| Some(r.kd_camera_us), 2),
            ("fixed_volume", "kd random, fixed volume", |r| Some(r.kd_random_us), 3),
            ("fixed_k", "brute camera, fixed k", |r| r.brute_camera_us, 4),
            ("fixed_k", "brute random, fixed k", |r| r.brute_random_us, 7),
        ];
        for (density, label, pick, colour) in series {
            let colour = PALETTE[colour];
            let points: Vec<(f64, f64)> =
                rows.iter().filter(|r| r.density == density).filter_map(|r| Some((r.n, pick(r)?))).collect();
            chart
                .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))
                .map_err(err)?
                .label(label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2)));
            chart.draw_series(points.into_iter().map(|p| Circle::new(p, 3, colour.filled()))).map_err(err)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .label_font(("sans-serif", 12))
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(err)
    })
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

    #[test]
    fn cost_plot_is_pinned() {
        let _guard = crate::test_support::insta_settings().bind_to_scope();
        let figure = figure().unwrap();
        insta::assert_snapshot!("q3_kdtree_cost", String::from_utf8(figure.bytes).unwrap());
    }
}
