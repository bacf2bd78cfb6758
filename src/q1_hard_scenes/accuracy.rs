//! The accuracy-versus-time data that `benches/render.rs` commits (`docs/data/q1_accuracy.csv`),
//! and its two charts.

use super::chart::{Series, chart, series};
use crate::plot::{Axis, Figure, PALETTE, PlotError};
use plotters::prelude::*;

/// One measurement of the accuracy-versus-time benchmark (`benches/render.rs`).
#[derive(Debug, Clone, PartialEq)]
struct AccuracyRow {
    scene: String,
    integrator: String,
    spp: f64,
    seconds: f64,
    rmse: f64,
}

/// Parses `docs/data/q1_accuracy.csv` (header `scene,integrator,spp,seconds,rmse`).
fn parse_accuracy(csv: &str) -> Result<Vec<AccuracyRow>, String> {
    crate::data::csv(csv)
        .records
        .into_iter()
        .map(|fields| {
            let number = |i: usize| -> Result<f64, String> {
                fields
                    .get(i)
                    .and_then(|f| f.trim().parse().ok())
                    .ok_or_else(|| format!("q1_accuracy.csv: bad field {i} in `{}`", fields.join(",")))
            };
            Ok(AccuracyRow {
                scene: fields.first().unwrap_or(&"").to_string(),
                integrator: fields.get(1).unwrap_or(&"").to_string(),
                spp: number(2)?,
                seconds: number(3)?,
                rmse: number(4)?,
            })
        })
        .collect()
}

/// The accuracy-versus-samples and accuracy-versus-seconds charts, from the committed CSV that
/// the benchmark writes (timings come only from benchmarks, so `figures()` stays deterministic).
fn accuracy_figures(rows: &[AccuracyRow]) -> Result<Vec<Figure>, PlotError> {
    let scenes: Vec<&str> = rows.iter().fold(Vec::new(), |mut names, r| {
        if !names.contains(&r.scene.as_str()) {
            names.push(r.scene.as_str());
        }
        names
    });
    let by = |x: fn(&AccuracyRow) -> f64| -> Vec<Series> {
        let mut out = Vec::new();
        for (k, scene) in scenes.iter().enumerate() {
            for (integrator, name, line) in [("path", "path", true), ("whitted", "Whitted", false)] {
                out.push(series(
                    format!("{scene}, {name}"),
                    rows.iter()
                        .filter(|r| r.scene == *scene && r.integrator == integrator)
                        .map(|r| (x(r), r.rmse))
                        .collect(),
                    line,
                    PALETTE[k % PALETTE.len()],
                ));
            }
        }
        out
    };
    let range = |values: Vec<f64>| {
        let low = values.iter().copied().fold(f64::INFINITY, f64::min);
        let high = values.iter().copied().fold(0.0, f64::max);
        Axis::log(low * 0.8, high * 1.25, "")
    };
    // The error axis reaches 16 times below the smallest error: the legend (lower left) sits in
    // that band instead of on the data.
    let rmse_range = || {
        let axis = range(rows.iter().map(|r| r.rmse).collect());
        Axis::log(axis.range.0 / 16.0, axis.range.1, "")
    };
    Ok(vec![
        chart(
            "q1_accuracy_spp.svg",
            "Error against a converged path-traced reference vs samples per pixel",
            ("samples per pixel", "RMS luminance error"),
            (range(rows.iter().map(|r| r.spp).collect()), rmse_range()),
            SeriesLabelPosition::LowerLeft,
            &by(|r| r.spp),
        )?,
        chart(
            "q1_accuracy_seconds.svg",
            "Error vs render time (benchmark machine, 48×36 pixels)",
            ("seconds", "RMS luminance error"),
            (range(rows.iter().map(|r| r.seconds).collect()), rmse_range()),
            SeriesLabelPosition::LowerLeft,
            &by(|r| r.seconds),
        )?,
    ])
}

/// The two accuracy charts from the committed CSV.
pub(super) fn committed_accuracy_figures() -> Result<Vec<Figure>, PlotError> {
    let rows = parse_accuracy(crate::data::Q1_ACCURACY)
        .map_err(|message| PlotError::Draw { figure: "q1_accuracy_spp.svg".into(), message })?;
    accuracy_figures(&rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accuracy_csv_parses_and_bad_rows_are_errors() {
        let rows = parse_accuracy("scene,integrator,spp,seconds,rmse\nfog,path,4,1e-2,3e-2\n").unwrap();
        assert_eq!(rows.len(), 1);
        assert_eq!((rows[0].spp, rows[0].seconds, rows[0].rmse), (4.0, 1e-2, 3e-2));
        assert!(parse_accuracy("h\nfog,path,x,1,1\n").is_err());
        let charts = accuracy_figures(&rows).unwrap();
        assert_eq!(charts.len(), 2);
    }
}
