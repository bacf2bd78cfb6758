//! Q2's figures: the worked example's geometry (roots, hit, normal, reflection), the closest
//! approach, the catalogue table, and the accuracy-versus-time chart drawn from benchmark data.

use super::catalogue::{self, Outcome, VARIANTS, variant_label};
use super::reflection::{Scenario, SpawnPolicy, self_hit_rate};
use super::{closest_approach, worked_example};
use crate::geometry::sphere::{first_hit_stable, roots_stable};
use crate::plot::{
    self, Axis, Chart, Dots, Figure, Legend, LegendMark, PALETTE, PlotError, Series, err, markdown_table,
};
use crate::{data, stats};
use glam::DVec3;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

type Diagram<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Every Q2 figure, as written to `docs/figures/`.
///
/// # Errors
/// [`PlotError`] if drawing fails.
///
/// # Examples
/// ```
/// let figures = hw3::q2_ray_sphere::figures().unwrap();
/// assert!(figures.iter().any(|f| f.file_name == "q2_reflection.svg"));
/// assert!(figures.iter().any(|f| f.file_name == "q2_catalogue.md"));
/// ```
pub fn figures() -> Result<Vec<Figure>, PlotError> {
    let mut figures = vec![
        plot::svg_figure("q2_reflection.svg", (560, 360), draw_reflection)?,
        plot::svg_figure("q2_closest_approach.svg", (560, 360), draw_closest_approach)?,
        Figure { file_name: "q2_catalogue.md".into(), bytes: catalogue::catalogue_table().into_bytes() },
        Figure {
            file_name: "q2_far_sweep.md".into(),
            bytes: catalogue::far_sphere_table(&catalogue::SWEEP_DISTANCES, 2000).into_bytes(),
        },
    ];
    if let Some(cost) = CostTable::load() {
        figures.push(Figure { file_name: "q2_cost.md".into(), bytes: cost.markdown().into_bytes() });
        figures.push(plot::svg_figure("q2_cost.svg", (560, 380), |root| cost.draw(root))?);
    }
    Ok(figures)
}

fn cross_section<'a, 'b>(
    root: &'a DrawingArea<SVGBackend<'b>, Shift>,
    caption: &str,
) -> Result<Diagram<'a, 'b>, String> {
    let area = root.titled(caption, ("sans-serif", 16)).map_err(err)?;
    let (width, height) = area.dim_in_pixel();
    let (margin, x_labels, y_labels) = (6, 20, 26);
    // Equal scales on both axes, so the circle is round: the y range follows from the pixels.
    let (x_min, x_max, y_min) = (-6.0, 3.0, -2.5);
    let units_per_pixel = (x_max - x_min) / f64::from(width - 2 * margin - y_labels);
    let y_max = y_min + units_per_pixel * f64::from(height - 2 * margin - x_labels);
    let mut chart = ChartBuilder::on(&area)
        .margin(margin)
        .x_label_area_size(x_labels)
        .y_label_area_size(y_labels)
        .build_cartesian_2d(x_min..x_max, y_min..y_max)
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_labels(10)
        .y_labels(6)
        .label_style(("sans-serif", 11))
        .draw()
        .map_err(err)?;
    let (_, sphere) = worked_example();
    let circle = (0..=180).map(|i| {
        let a = f64::from(i) / 180.0 * std::f64::consts::TAU;
        (sphere.radius * a.cos(), sphere.radius * a.sin())
    });
    chart.draw_series(LineSeries::new(circle, PALETTE[7].stroke_width(2))).map_err(err)?;
    dot(&mut chart, sphere.center, PALETTE[7])?;
    label(&mut chart, (0.1, -0.15), "o", PALETTE[7])?;
    Ok(chart)
}

fn arrow(chart: &mut Diagram<'_, '_>, from: DVec3, to: DVec3, color: RGBColor) -> Result<(), String> {
    chart.draw_series(LineSeries::new([(from.x, from.y), (to.x, to.y)], color.stroke_width(2))).map_err(err)?;
    let back = (from - to).normalize() * 0.25;
    let side = DVec3::new(-back.y, back.x, 0.0) * 0.4;
    let head = [to, to + back + side, to + back - side].map(|p| (p.x, p.y));
    chart.draw_series(std::iter::once(Polygon::new(head.to_vec(), color.filled()))).map_err(err)?;
    Ok(())
}

fn label(chart: &mut Diagram<'_, '_>, at: (f64, f64), text: &str, color: RGBColor) -> Result<(), String> {
    let style = TextStyle::from(("sans-serif", 13)).color(&color);
    chart.draw_series(std::iter::once(Text::new(text.to_string(), at, style))).map_err(err)?;
    Ok(())
}

fn dot(chart: &mut Diagram<'_, '_>, at: DVec3, color: RGBColor) -> Result<(), String> {
    chart.draw_series(std::iter::once(Circle::new((at.x, at.y), 4, color.filled()))).map_err(err)?;
    Ok(())
}

fn draw_reflection(root: &DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), String> {
    let mut chart = cross_section(root, "Q2a/b: e + d t meets the sphere at t2 and t1; reflection at the first hit")?;
    let (ray, sphere) = worked_example();
    let roots = roots_stable(&ray, &sphere).ok_or("worked example must hit")?;
    let t_hit = first_hit_stable(&ray, &sphere).ok_or("worked example must hit")?;
    let (near, far) = (ray.at(roots.near), ray.at(roots.far));
    chart
        .draw_series(LineSeries::new([(ray.origin.x, ray.origin.y), (2.8, ray.origin.y)], PALETTE[0].stroke_width(1)))
        .map_err(err)?;
    arrow(&mut chart, ray.origin, ray.at(1.0), PALETTE[0])?;
    dot(&mut chart, ray.origin, PALETTE[0])?;
    label(&mut chart, (ray.origin.x, ray.origin.y + 0.45), "e", PALETTE[0])?;
    label(&mut chart, (ray.at(0.35).x, ray.origin.y - 0.2), "d", PALETTE[0])?;
    dot(&mut chart, near, PALETTE[1])?;
    dot(&mut chart, far, PALETTE[2])?;
    label(&mut chart, (near.x + 0.1, near.y - 0.1), &format!("t2 = {:.3} (hit)", roots.near), PALETTE[1])?;
    label(&mut chart, (far.x - 0.3, far.y + 0.35), &format!("t1 = {:.3}", roots.far), PALETTE[2])?;
    let hit = ray.at(t_hit);
    let normal = (hit - sphere.center) / sphere.radius;
    arrow(&mut chart, hit, hit + normal * 1.3, PALETTE[3])?;
    label(&mut chart, ((hit + normal * 1.3).x - 0.4, (hit + normal * 1.3).y + 0.1), "n", PALETTE[3])?;
    let reflected = crate::geometry::sphere::reflect::<f64>(ray.dir, normal);
    arrow(&mut chart, hit, hit + reflected * 1.8, PALETTE[4])?;
    label(
        &mut chart,
        ((hit + reflected * 1.8).x + 0.15, (hit + reflected * 1.8).y + 0.15),
        "r = d - 2(n.d)n",
        PALETTE[4],
    )?;
    Ok(())
}

fn draw_closest_approach(root: &DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), String> {
    let mut chart = cross_section(root, "Q2c: t = -(e - o).d / |d|^2 is the foot of the perpendicular from o")?;
    let (ray, sphere) = worked_example();
    let t = closest_approach::closest_approach_algebraic(&ray, sphere.center);
    let foot = ray.at(t);
    chart
        .draw_series(LineSeries::new([(ray.origin.x, ray.origin.y), (2.8, ray.origin.y)], PALETTE[0].stroke_width(1)))
        .map_err(err)?;
    arrow(&mut chart, ray.origin, ray.at(1.0), PALETTE[0])?;
    label(&mut chart, (ray.origin.x, ray.origin.y + 0.45), "e", PALETTE[0])?;
    let dashed = DashedLineSeries::new([(0.0, 0.0), (foot.x, foot.y)], 6, 4, PALETTE[1].stroke_width(2));
    chart.draw_series(dashed).map_err(err)?;
    dot(&mut chart, foot, PALETTE[1])?;
    label(&mut chart, (foot.x + 0.1, foot.y + 0.4), &format!("p(t) with t = {t}"), PALETTE[1])?;
    let half_chord = (sphere.radius.powi(2) - (foot - sphere.center).length_squared()).sqrt();
    let chord = [foot - ray.dir * half_chord, foot + ray.dir * half_chord];
    chart.draw_series(LineSeries::new(chord.iter().map(|p| (p.x, p.y)), PALETTE[2].stroke_width(3))).map_err(err)?;
    label(&mut chart, (-5.9, 0.75), "green: half-chord sqrt(r^2 - |l|^2)", PALETTE[2])?;
    label(&mut chart, (0.1, 0.6), "l", PALETTE[1])?;
    Ok(())
}

/// One measured row of `docs/data/q2_cost.csv` (written by `cargo bench --bench q2_cost`).
#[derive(Debug, Clone, PartialEq)]
struct CostRow {
    kind: String,
    variant: String,
    median_ns: f64,
    ratio: f64,
}

/// The benchmark's timings joined with the catalogue's (deterministic) errors.
struct CostTable {
    rows: Vec<CostRow>,
    meta: String,
}

impl CostTable {
    /// The committed measurements; `None` when the file holds no intersection timing.
    fn load() -> Option<Self> {
        let csv = data::csv(data::Q2_COST);
        let rows: Vec<CostRow> = csv
            .records
            .iter()
            .filter_map(|fields| {
                let [kind, variant, median, ratio] = fields[..] else { return None };
                let (median_ns, ratio) = (median.parse().ok()?, ratio.parse().ok()?);
                Some(CostRow { kind: kind.to_string(), variant: variant.to_string(), median_ns, ratio })
            })
            .collect();
        let meta = csv.comments.concat();
        rows.iter().any(|r| r.kind == "intersect").then_some(Self { rows, meta })
    }

    fn intersections(&self) -> impl Iterator<Item = &CostRow> {
        self.rows.iter().filter(|r| r.kind == "intersect")
    }

    /// Worst-case and median error of each variant over the catalogue cases that `f32` can hold
    /// (the † rows are excluded: there every `f32` variant fails and only `f64` is meaningful).
    /// A wrong hit/miss counts as error 1.
    fn errors(label: &str) -> Option<(f64, f64)> {
        let index = VARIANTS.iter().position(|&(m, p)| variant_label(m, p) == label)?;
        let mut errors: Vec<f64> = catalogue::score_catalogue()
            .iter()
            .filter(|r| !r.case.beyond_f32)
            .map(|r| Outcome::error(r.outcomes[index]))
            .collect();
        let median = (!errors.is_empty()).then(|| stats::median(&mut errors))?;
        Some((*errors.last()?, median))
    }

    fn markdown(&self) -> String {
        let header = [
            "method",
            "median ns / call",
            "time vs naive f32",
            "worst catalogue error (no † rows)",
            "median catalogue error",
        ];
        let intersections = self.intersections().map(|row| {
            let (worst, median) = Self::errors(&row.variant)
                .map_or(("n/a".into(), "n/a".into()), |(w, m)| (format!("{w:.1e}"), format!("{m:.1e}")));
            [row.variant.clone(), format!("{:.2}", row.median_ns), format!("{:.2}×", row.ratio), worst, median]
        });
        let mut out = markdown_table(&header, intersections);
        let header = [
            "spawn policy (f32 hit + reflect)",
            "median ns / call",
            "time vs AtComputedPoint",
            "self-hits, 20000 near rays",
        ];
        let spawns = self.rows.iter().filter(|r| r.kind == "spawn").map(|row| {
            let policy = SpawnPolicy::ALL.into_iter().find(|p| format!("{p:?}") == row.variant);
            let rate = policy.map_or("n/a".into(), |p| {
                let count = self_hit_rate::<f32>(Scenario::Near, p, 20_000, 11);
                format!("{:.2} %", 100.0 * count.self_hits as f64 / count.reflected as f64)
            });
            [row.variant.clone(), format!("{:.2}", row.median_ns), format!("{:.2}×", row.ratio), rate]
        });
        out.push('\n');
        out.push_str(&markdown_table(&header, spawns));
        out.push_str(&format!("\nMeasured by `cargo bench --bench q2_cost`: {}\n", self.meta));
        out
    }

    fn draw(&self, root: &DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), String> {
        let points: Vec<(String, f64, f64, f64)> = self
            .intersections()
            .filter_map(|r| {
                Self::errors(&r.variant).map(|(w, m)| (r.variant.clone(), r.median_ns, w.max(1e-17), m.max(1e-17)))
            })
            .collect();
        let max_ns = points.iter().map(|p| p.1).fold(1.0, f64::max) * 1.3;
        // Per variant: a filled dot at its worst error (with the legend entry), a ring at its median.
        let series = points
            .iter()
            .enumerate()
            .flat_map(|(i, (name, ns, worst, median))| {
                let colour = PALETTE[i % PALETTE.len()];
                let worst = Series {
                    legend: LegendMark::Dot { dx: 0, radius: 4 },
                    ..Series::dots(name.as_str(), vec![(*ns, *worst)], colour, 5)
                };
                let median = Series {
                    label: None,
                    dots: Some(Dots { radius: 5, ring: Some(2) }),
                    ..Series::dots("", vec![(*ns, *median)], colour, 5)
                };
                [worst, median]
            })
            .collect();
        Chart {
            caption_size: 16,
            margin: 8,
            label_areas: (36, 56),
            label_size: 11,
            series,
            legend: Some(Legend { position: Some(SeriesLabelPosition::LowerRight), font: 11, opacity: 0.9 }),
            ..Chart::new(
                "Q2: catalogue error vs time per intersection",
                Axis::linear(0.0, max_ns, "median ns per call (one run)"),
                Axis {
                    format: Some(|y| format!("{y:.0e}")),
                    ..Axis::log(1e-17, 1e-2, "relative error of t (0 drawn at 1e-17)")
                },
            )
        }
        .draw(root)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagrams_snapshot() {
        let settings = crate::test_support::insta_settings();
        for name in ["q2_reflection.svg", "q2_closest_approach.svg"] {
            let figure = figures().unwrap().into_iter().find(|f| f.file_name == name).unwrap();
            let svg = String::from_utf8(figure.bytes).unwrap();
            settings.bind(|| insta::assert_snapshot!(name.replace(".svg", "_svg"), svg));
        }
    }
}
