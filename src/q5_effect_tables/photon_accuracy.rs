//! The photon map's accuracy against k and photon count, plotted from the CSV that
//! `cargo bench -p hw3-benches --bench q5_photon` writes (`docs/data/q5_photon_accuracy.csv`), so that
//! [`super::figures`] stays deterministic: timings come only from the benchmark.

use crate::data::DataError;
use crate::plot::{Axis, Chart, Dots, Figure, Legend, PALETTE, PlotError, Series, Stroke, TickFormat};
use plotters::prelude::{BLACK, SeriesLabelPosition};

/// One row of the photon accuracy CSV.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::photon_accuracy::{AccuracyRow, parse};
/// let rows: Vec<AccuracyRow> = parse("header\n10000,19823,8,4.8e-2,1.8e-3,4.2e-1,2.0e-2\n").unwrap();
/// assert_eq!((rows[0].photons, rows[0].rms_error), (10000.0, 0.42));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AccuracyRow {
    /// Photons emitted.
    pub photons: f64,
    /// Photons stored in the map.
    pub stored: f64,
    /// Neighbours of the estimate.
    pub k: f64,
    /// Seconds to trace the photons.
    pub trace_seconds: f64,
    /// Seconds for the 1000 queries.
    pub query_seconds: f64,
    /// Relative RMS error of the irradiance over the query points.
    pub rms_error: f64,
    /// Mean relative error (the bias).
    pub mean_error: f64,
}

/// Parses the CSV (header `photons,stored,k,trace_seconds,query_seconds,rms_error,mean_error`).
///
/// # Errors
/// [`DataError::NotANumber`] for the first record with a non-numeric field,
/// [`DataError::FieldCount`] for the first with other than 7 fields.
///
/// # Examples
/// ```
/// use hw3::data::DataError;
/// use hw3::q5_effect_tables::photon_accuracy::parse;
/// let rows = parse("header\n10000,19823,8,4.8e-2,1.8e-3,4.2e-1,2.0e-2\n").unwrap();
/// assert_eq!(rows[0].k, 8.0);
/// assert!(matches!(parse("header\n1,2,x\n"), Err(DataError::NotANumber { .. })));
/// assert!(matches!(parse("header\n1,2\n"), Err(DataError::FieldCount { expected: 7, got: 2, .. })));
/// ```
pub fn parse(csv: &str) -> Result<Vec<AccuracyRow>, DataError> {
    let file = "q5_photon_accuracy.csv";
    numeric_rows(csv, file)?
        .into_iter()
        .map(|fields| match fields[..] {
            [photons, stored, k, trace_seconds, query_seconds, rms_error, mean_error] => {
                Ok(AccuracyRow { photons, stored, k, trace_seconds, query_seconds, rms_error, mean_error })
            }
            _ => Err(DataError::FieldCount { file, expected: 7, got: fields.len() }),
        })
        .collect()
}

/// The numeric fields of every line of a CSV after its header (blank lines skipped).
///
/// # Errors
/// [`DataError::NotANumber`] naming `file` and the first record with a non-numeric field.
pub(super) fn numeric_rows(csv: &str, file: &'static str) -> Result<Vec<Vec<f64>>, DataError> {
    crate::data::csv(csv)
        .records
        .into_iter()
        .map(|fields| {
            fields
                .iter()
                .map(|f| f.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|source| DataError::NotANumber { file, record: fields.join(","), source })
        })
        .collect()
}

/// Parses committed data (a constant of [`crate::data`]) for the figure `figure`.
///
/// # Errors
/// [`PlotError::Data`] naming the figure, with the [`DataError`] of `parse`, when the data is
/// malformed.
pub(super) fn read_committed<T>(
    csv: &str,
    figure: &str,
    parse: impl Fn(&str) -> Result<Vec<T>, DataError>,
) -> Result<Vec<T>, PlotError> {
    parse(csv).map_err(|e| PlotError::data(figure, e))
}

/// The log-log chart of RMS error against k, one line per photon count, with the noise law
/// `1/√(k − 2)` of the (k − 1)/(πr²) estimate dashed.
///
/// # Errors
/// [`PlotError`] when the CSV is missing or malformed, or drawing fails.
///
/// # Examples
/// ```
/// let figure = hw3::q5_effect_tables::photon_accuracy::figure().unwrap();
/// assert_eq!(figure.file_name, "q5_photon_accuracy.svg");
/// ```
pub fn figure() -> Result<Figure, PlotError> {
    let name = "q5_photon_accuracy.svg";
    let rows = read_committed(crate::data::Q5_PHOTON_ACCURACY, name, parse)?;
    let mut counts: Vec<f64> = rows.iter().map(|r| r.photons).collect();
    counts.dedup();
    let lines = counts
        .iter()
        .map(|&count| {
            let points = rows.iter().filter(|r| r.photons == count).map(|r| (r.k, r.rms_error)).collect();
            (format!("{count:.0} photons"), points)
        })
        .collect();
    let law: Vec<(f64, f64)> = (3..=12).map(|e| 2f64.powi(e)).map(|k| (k, 1.0 / (k - 2.0).sqrt())).collect();
    LogLogChart {
        name,
        caption: "Photon map in the white furnace: error vs k",
        x_range: (4.0, 4096.0),
        y_range: (0.01, 1.0),
        x_desc: "k (neighbours)",
        y_desc: "relative RMS error of E",
        lines,
        dashed: ("1/√(k − 2)".to_string(), law),
        tick_formats: None,
        legend: None,
    }
    .draw()
}

/// A log-log chart of marked lines and one dashed reference line (the photon accuracy figures).
pub(super) struct LogLogChart<'a> {
    /// File name.
    pub name: &'a str,
    /// Title.
    pub caption: &'a str,
    /// x range (both ends positive).
    pub x_range: (f64, f64),
    /// y range (both ends positive).
    pub y_range: (f64, f64),
    /// x-axis label.
    pub x_desc: &'a str,
    /// y-axis label.
    pub y_desc: &'a str,
    /// Legend label and points of each marked line.
    pub lines: Vec<(String, Vec<(f64, f64)>)>,
    /// Legend label and points of the dashed line.
    pub dashed: (String, Vec<(f64, f64)>),
    /// Tick formats of the x and y axes (plotters' defaults when `None`).
    pub tick_formats: Option<(TickFormat, TickFormat)>,
    /// Where the legend goes (plotters' default when `None`).
    pub legend: Option<SeriesLabelPosition>,
}

impl LogLogChart<'_> {
    /// The chart as an SVG figure (640 × 400), drawn by [`Chart`]: each line solid (2 px) with a
    /// 3 px dot at every point, the reference line dashed black, the legend box at 80 % opacity.
    pub(super) fn draw(self) -> Result<Figure, PlotError> {
        let axis = |(low, high), desc, format| Axis { format, ..Axis::log(low, high, desc) };
        let (x_format, y_format) = self.tick_formats.map_or((None, None), |(x, y)| (Some(x), Some(y)));
        let mut series: Vec<Series> = self
            .lines
            .into_iter()
            .enumerate()
            .map(|(index, (label, points))| Series {
                dots: Some(Dots { radius: 3, ring: None }),
                ..Series::line(label, points, PALETTE[index % PALETTE.len()], 2)
            })
            .collect();
        let (label, points) = self.dashed;
        series.push(Series {
            line: Some(Stroke { width: 1, dash: Some((6, 4)) }),
            ..Series::line(label, points, BLACK, 1)
        });
        Chart {
            fill: true,
            series,
            legend: Some(Legend { position: self.legend, font: 13, opacity: 0.8 }),
            ..Chart::new(
                self.caption,
                axis(self.x_range, self.x_desc, x_format),
                axis(self.y_range, self.y_desc, y_format),
            )
        }
        .svg(self.name, (640, 400))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed measurement obeys the estimate's noise law: the RMS error is within 25 % of
    /// 1/√(k − 2) on every row (the furnace has no gradient, so no blur adds to it), and the bias
    /// stays within ±3 %.
    #[test]
    fn committed_photon_accuracy_follows_the_noise_law() {
        let rows = read_committed(crate::data::Q5_PHOTON_ACCURACY, "test", parse).unwrap();
        assert!(rows.len() >= 12);
        for r in &rows {
            let law = 1.0 / (r.k - 2.0).sqrt();
            assert!((r.rms_error / law - 1.0).abs() < 0.25, "{r:?} vs {law}");
            assert!(r.mean_error.abs() < 0.03, "{r:?}");
            assert!(r.stored >= r.photons, "each photon lands at least once in a closed sphere");
        }
        assert!(parse("h\n1,2,3,4,5,6\n").is_err(), "six fields");
    }
}
