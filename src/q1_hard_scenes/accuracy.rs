//! The accuracy-versus-time data that `benches/render.rs` commits (`docs/data/q1_accuracy.csv`),
//! and its two charts.

use super::chart::{Series, chart, key, series};
use crate::data::DataError;
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
///
/// # Errors
/// [`DataError::BadField`] for the first record whose `spp`, `seconds` or `rmse` is missing or
/// not a number.
fn parse_accuracy(csv: &str) -> Result<Vec<AccuracyRow>, DataError> {
    crate::data::csv(csv)
        .records
        .into_iter()
        .map(|fields| {
            let number = |index: usize| -> Result<f64, DataError> {
                fields.get(index).and_then(|f| f.trim().parse().ok()).ok_or_else(|| DataError::BadField {
                    file: "q1_accuracy.csv",
                    index,
                    record: fields.join(","),
                })
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
    // The legend names each scene once (its colour) and says once what a line and a dot mean,
    // six entries instead of eight, small enough for a corner the data leave empty.
    let by = |x: fn(&AccuracyRow) -> f64| -> Vec<Series> {
        let mut out = Vec::new();
        for (k, scene) in scenes.iter().enumerate() {
            for (integrator, line) in [("path", true), ("whitted", false)] {
                out.push(series(
                    if line { scene.to_string() } else { String::new() },
                    rows.iter()
                        .filter(|r| r.scene == *scene && r.integrator == integrator)
                        .map(|r| (x(r), r.rmse))
                        .collect(),
                    line,
                    PALETTE[k % PALETTE.len()],
                ));
            }
        }
        out.extend([key("path tracing", true), key("Whitted", false)]);
        out
    };
    let range = |values: Vec<f64>| {
        let low = values.iter().copied().fold(f64::INFINITY, f64::min);
        let high = values.iter().copied().fold(0.0, f64::max);
        Axis::log(low * 0.8, high * 1.25, "")
    };
    // Ticks at 1-2-5 steps (and the measured sample counts): plotters' own log ticks label only
    // the powers of ten, one or two per axis here.
    let ticked = |axis: Axis<'static>, ticks: &'static [f64]| Axis { ticks: Some(ticks), ..axis };
    let rmse_range = || ticked(range(rows.iter().map(|r| r.rmse).collect()), &[0.005, 0.01, 0.02, 0.05, 0.1, 0.2]);
    Ok(vec![
        chart(
            "q1_accuracy_spp.svg",
            "Error against a converged path-traced reference vs samples per pixel",
            ("samples per pixel", "RMS luminance error"),
            (
                ticked(range(rows.iter().map(|r| r.spp).collect()), &[1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0]),
                rmse_range(),
            ),
            SeriesLabelPosition::LowerLeft,
            &by(|r| r.spp),
        )?,
        chart(
            "q1_accuracy_seconds.svg",
            "Error vs render time (48×36 pixels)",
            ("seconds", "RMS luminance error"),
            (
                ticked(
                    range(rows.iter().map(|r| r.seconds).collect()),
                    &[0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5],
                ),
                rmse_range(),
            ),
            SeriesLabelPosition::UpperRight,
            &by(|r| r.seconds),
        )?,
    ])
}

/// The two accuracy charts from the committed CSV.
pub(super) fn committed_accuracy_figures() -> Result<Vec<Figure>, PlotError> {
    let rows = parse_accuracy(crate::data::Q1_ACCURACY).map_err(|e| PlotError::data("q1_accuracy_spp.svg", e))?;
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
        let bad = parse_accuracy("h\nfog,path,x,1,1\n").unwrap_err();
        assert_eq!(bad, DataError::BadField { file: "q1_accuracy.csv", index: 2, record: "fog,path,x,1,1".into() });
        assert_eq!(bad.to_string(), "q1_accuracy.csv: bad field 2 in `fog,path,x,1,1`");
        let charts = accuracy_figures(&rows).unwrap();
        assert_eq!(charts.len(), 2);
    }
}
