//! Q2's figures: the worked example's geometry (roots, hit, normal, reflection), the closest
//! approach, the catalogue table, and the accuracy-versus-time chart drawn from benchmark data.

use super::catalogue::{self, Outcome, VARIANTS, variant_label};
use super::reflection::{Scenario, SpawnPolicy, self_hit_rate};
use super::{closest_approach, notes_example};
use crate::geometry::sphere::{Roots, first_hit_stable, roots_stable};
use crate::geometry::{InputError, Ray};
use crate::plot::{
    self, Axis, Chart, Dots, DrawError, Figure, Legend, LegendMark, Mesh, PALETTE, PlotError, Series, Shape, Stroke,
    markdown_table,
};
use crate::{data, stats};
use glam::DVec3;
use plotters::coord::Shift;
use plotters::prelude::*;

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
    let reflection = worked_hit().map_err(|e| PlotError::data("q2_reflection.svg", e))?;
    let reflection = plot::svg_figure("q2_reflection.svg", (560, 400), |root| draw_reflection(root, reflection))?;
    let closest_approach = plot::svg_figure("q2_closest_approach.svg", (560, 400), draw_closest_approach)?;
    let cases = case_rays().map_err(|e| PlotError::data("q2_cases.svg", e))?;
    let mut figures = vec![
        reflection,
        closest_approach,
        plot::svg_figure("q2_cases.svg", (900, 520), |root| draw_cases(root, &cases))?,
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

/// Why the geometry a Q2 figure shows could not be computed (never for the built-in example and
/// cases, which the tests draw).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
enum GeometryError {
    /// A case's ray is invalid.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The worked example's ray misses its sphere.
    #[error("the worked example must hit")]
    NoHit,
}

/// The worked example's two roots and its first hit with t ≥ 0.
///
/// # Errors
/// [`GeometryError::NoHit`] if the ray misses the sphere.
fn worked_hit() -> Result<(Roots<f64>, f64), GeometryError> {
    let (ray, sphere) = notes_example();
    let roots = roots_stable(&ray, &sphere).ok_or(GeometryError::NoHit)?;
    let t_hit = first_hit_stable(&ray, &sphere).ok_or(GeometryError::NoHit)?;
    Ok((roots, t_hit))
}

/// The [`CASES`] as rays, with their names.
///
/// # Errors
/// [`GeometryError::Input`] for a case whose ray is invalid.
fn case_rays() -> Result<Vec<(&'static str, Ray<f64>)>, GeometryError> {
    CASES.iter().map(|&(name, origin, dir)| Ok((name, Ray::new(DVec3::from(origin), DVec3::from(dir))?))).collect()
}

/// The worked example's cross-section at `z = 0` with equal scales (the circle is round), axes
/// and tick labels but no grid: the sphere, its centre `o`, and what `shapes` add on top.
fn cross_section(
    root: &DrawingArea<SVGBackend<'_>, Shift>,
    caption: &str,
    shapes: Vec<Shape>,
) -> Result<(), DrawError> {
    let area = root.titled(caption, ("sans-serif", 16))?;
    let (_, sphere) = notes_example();
    let mut sphere_shapes = vec![
        Shape::line(circle(sphere.center, sphere.radius), PALETTE[7], 2),
        dot(sphere.center, PALETTE[7]),
        label((sphere.center.x + 0.25, sphere.center.y - 0.4), "o", PALETTE[7]),
    ];
    sphere_shapes.extend(shapes);
    let ticks = |axis: Axis<'static>, labels| Axis { labels: Some(labels), ..axis };
    Chart {
        margin: 6,
        label_areas: (20, 26),
        label_size: 11,
        mesh: Mesh::Axes,
        equal_scale: true,
        shapes: sphere_shapes,
        legend: None,
        ..Chart::new("", ticks(Axis::linear(-10.0, 9.5, ""), 10), ticks(Axis::linear(-4.2, -4.2, ""), 7))
    }
    .draw(&area)
}

/// The circle of `radius` about `center`'s `x` and `y`, as 181 points (the first repeated last).
fn circle(center: DVec3, radius: f64) -> Vec<(f64, f64)> {
    (0..=180)
        .map(|i| {
            let a = f64::from(i) / 180.0 * std::f64::consts::TAU;
            (center.x + radius * a.cos(), center.y + radius * a.sin())
        })
        .collect()
}

/// An arrow from `from` to `to` (their `x` and `y`): a 2 px shaft and a filled head [`HEAD`]
/// units long.
fn arrow(from: DVec3, to: DVec3, color: RGBColor) -> [Shape; 2] {
    let back = (from - to).normalize() * HEAD;
    let side = DVec3::new(-back.y, back.x, 0.0) * 0.4;
    let head = [to, to + back + side, to + back - side].map(|p| (p.x, p.y));
    [
        Shape::line(vec![(from.x, from.y), (to.x, to.y)], color, 2),
        Shape::Polygon { points: head.to_vec(), colour: color },
    ]
}

/// The length of an arrow's head, in the diagrams' units (the worked example's sphere has radius 5).
const HEAD: f64 = 0.6;

/// A 13 px label in `color` with its top-left corner at `at`.
fn label(at: (f64, f64), text: &str, color: RGBColor) -> Shape {
    Shape::text(text, at, 13, color)
}

/// A 4 px dot at `at`'s `x` and `y`.
fn dot(at: DVec3, color: RGBColor) -> Shape {
    Shape::dot((at.x, at.y), 4, color)
}

/// Font size of a case panel's title (the figure is 900 px wide and shown scaled down in the
/// chapter's column, so its text is drawn larger than the single diagrams').
const CASE_TITLE_PX: u32 = 17;
/// Font size of a case panel's roots line and its eye label.
const CASE_TEXT_PX: u32 = 16;

/// The cases of the homework's root analysis, one panel each, named by the template's case words:
/// (name, eye, direction), all against the sphere of the chapter's worked example (centre
/// `(1, 2, −1)`, radius 5) with its direction `(4, 0, 0)`.
const CASES: [(&str, [f64; 3], [f64; 3]); 6] = [
    ("outside", [-7.0, 5.0, -1.0], [4.0, 0.0, 0.0]),
    ("inside", [-2.0, 5.0, -1.0], [4.0, 0.0, 0.0]),
    ("behind", [9.0, 5.0, -1.0], [4.0, 0.0, 0.0]),
    ("tangent", [-7.0, 7.0, -1.0], [4.0, 0.0, 0.0]),
    ("miss", [-7.0, 8.0, -1.0], [4.0, 0.0, 0.0]),
    ("on_surface", [-3.0, -1.0, -1.0], [4.0, 0.0, 0.0]),
];

/// The six cases of the root analysis as a small multiple: in each panel the sphere, the ray
/// from its eye (the part with t < 0 dashed grey), both roots as computed by
/// [`roots_stable`], and the first hit with t ≥ 0 by [`first_hit_stable`] (ringed); `cases` are
/// the [`CASES`]' rays ([`case_rays`]).
fn draw_cases(root: &DrawingArea<SVGBackend<'_>, Shift>, cases: &[(&str, Ray<f64>)]) -> Result<(), DrawError> {
    let (_, sphere) = notes_example();
    for (area, &(name, ray)) in root.split_evenly((2, 3)).iter().zip(cases.iter()) {
        let roots = roots_stable(&ray, &sphere);
        let hit = first_hit_stable(&ray, &sphere);
        let numbers = match roots {
            Some(r) if r.near == r.far => format!("one double root t = {:.3}", r.near),
            Some(r) => format!("roots t = {:.3}, {:.3}", r.near, r.far),
            None => "no real root".into(),
        };
        let verdict = hit.map_or("no hit".into(), |t| format!("first hit t = {t:.3}"));
        let area = area.margin(4, 4, 4, 4).titled(&format!("{name}: {verdict}"), ("sans-serif", CASE_TITLE_PX))?;
        let (behind, ahead) = (ray.at(-8.0), ray.at(8.0));
        let mut shapes = vec![
            Shape::line(circle(sphere.center, sphere.radius), PALETTE[7], 2),
            Shape::Series(Series {
                line: Some(Stroke { width: 1, dash: Some((4, 4)) }),
                ..Series::line("", vec![(behind.x, behind.y), (ray.origin.x, ray.origin.y)], RGBColor(150, 150, 150), 1)
            }),
            Shape::line(vec![(ray.origin.x, ray.origin.y), (ahead.x, ahead.y)], PALETTE[0], 1),
        ];
        shapes.extend(arrow(ray.origin, ray.at(0.75), PALETTE[0]));
        shapes.push(dot(ray.origin, PALETTE[0]));
        shapes.push(Shape::text("e", (ray.origin.x - 0.75, ray.origin.y + 2.25), CASE_TEXT_PX, PALETTE[0]));
        if let Some(r) = roots {
            for t in [r.near, r.far] {
                shapes.push(dot(ray.at(t), if t < 0.0 { PALETTE[5] } else { PALETTE[1] }));
            }
        }
        if let Some(t) = hit {
            let p = ray.at(t);
            shapes.push(Shape::Series(Series {
                label: None,
                dots: Some(Dots { radius: 8, ring: Some(2) }),
                ..Series::dots("", vec![(p.x, p.y)], PALETTE[1], 8)
            }));
        }
        // No mesh: the 26 px under the plotting area, its x label area, holds the roots' line.
        Chart {
            margin: 0,
            label_areas: (26, 0),
            mesh: Mesh::Hidden,
            equal_scale: true,
            shapes,
            legend: None,
            ..Chart::new("", Axis::linear(-14.0, 16.0, ""), Axis::linear(-6.75, -6.75, ""))
        }
        .draw(&area)?;
        let height = area.dim_in_pixel().1;
        let style = TextStyle::from(("sans-serif", CASE_TEXT_PX)).color(&PALETTE[7]);
        area.draw(&Text::new(numbers, (6, i32::try_from(height).unwrap_or(0) - 22), style))?;
    }
    Ok(())
}

/// The worked example's ray, its roots and the reflection at its first hit ([`worked_hit`]:
/// `(roots, t_hit)`).
fn draw_reflection(
    root: &DrawingArea<SVGBackend<'_>, Shift>,
    (roots, t_hit): (Roots<f64>, f64),
) -> Result<(), DrawError> {
    let (ray, sphere) = notes_example();
    let (near, far) = (ray.at(roots.near), ray.at(roots.far));
    let mut shapes = vec![Shape::line(vec![(ray.origin.x, ray.origin.y), (7.0, ray.origin.y)], PALETTE[0], 1)];
    shapes.extend(arrow(ray.origin, ray.at(0.5), PALETTE[0]));
    shapes.extend([
        dot(ray.origin, PALETTE[0]),
        label((ray.origin.x - 0.2, ray.origin.y + 1.1), "e", PALETTE[0]),
        label((ray.at(0.2).x, ray.origin.y - 0.4), "d", PALETTE[0]),
        dot(near, PALETTE[1]),
        dot(far, PALETTE[2]),
        label((near.x + 0.25, near.y - 0.25), &format!("t = {} (first hit)", roots.near), PALETTE[1]),
        label((far.x - 0.75, far.y + 0.9), &format!("t = {}", roots.far), PALETTE[2]),
    ]);
    let hit = ray.at(t_hit);
    let normal = (hit - sphere.center) / sphere.radius;
    let normal_tip = hit + normal * 2.5;
    shapes.extend(arrow(hit, normal_tip, PALETTE[3]));
    shapes.push(label((normal_tip.x - 0.9, normal_tip.y + 0.3), "n", PALETTE[3]));
    let reflected = crate::geometry::sphere::reflect::<f64>(ray.dir.normalize(), normal);
    let tip = hit + reflected * 2.8;
    shapes.extend(arrow(hit, tip, PALETTE[4]));
    shapes.push(label((tip.x + 0.4, tip.y + 0.3), "r = dhat - 2(n.dhat)n", PALETTE[4]));
    cross_section(root, "Q2a/b: e + d t meets the sphere at t = 1 and t = 3; reflection at the first hit", shapes)
}

fn draw_closest_approach(root: &DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), DrawError> {
    let (ray, sphere) = notes_example();
    let t = closest_approach::closest_approach_algebraic(&ray, sphere.center);
    let foot = ray.at(t);
    let mut shapes = vec![Shape::line(vec![(ray.origin.x, ray.origin.y), (7.0, ray.origin.y)], PALETTE[0], 1)];
    shapes.extend(arrow(ray.origin, ray.at(0.5), PALETTE[0]));
    shapes.push(label((ray.origin.x - 0.2, ray.origin.y + 1.1), "e", PALETTE[0]));
    shapes.push(Shape::Series(Series {
        line: Some(Stroke { width: 2, dash: Some((6, 4)) }),
        ..Series::line("", vec![(sphere.center.x, sphere.center.y), (foot.x, foot.y)], PALETTE[1], 2)
    }));
    shapes.push(dot(foot, PALETTE[1]));
    shapes.push(label((foot.x + 0.3, foot.y - 0.4), &format!("e + d t with t = {t}"), PALETTE[1]));
    // The half-chord is a length; along the ray it spans sqrt(r² − |l|²)/|d| of the parameter t.
    let half_chord = (sphere.radius.powi(2) - (foot - sphere.center).length_squared()).sqrt();
    let unit = ray.dir.normalize();
    let chord = [foot - unit * half_chord, foot + unit * half_chord];
    shapes.push(Shape::line(chord.iter().map(|p| (p.x, p.y)).collect(), PALETTE[2], 3));
    let at = |dx: f64, dy: f64| (sphere.center.x + dx, sphere.center.y + dy);
    shapes.push(label(at(-10.8, -3.8), "green: the half-chords, each", PALETTE[2]));
    shapes.push(label(at(-10.8, -4.6), "sqrt(r^2 - |l|^2) long, that is", PALETTE[2]));
    shapes.push(label(at(-10.8, -5.4), "sqrt(r^2 - |l|^2)/|d| in t", PALETTE[2]));
    shapes.push(label(at(-0.9, 1.8), "l", PALETTE[1]));
    cross_section(root, "Q2c: t = -(e - o).d / |d|^2 is the foot of the perpendicular from o", shapes)
}

/// One measured row of `docs/data/q2_cost.csv` (written by `cargo bench -p hw3-benches --bench q2_cost`).
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
        // The CSV's comment is the benchmark's method; how many runs wrote the file is not part of it.
        let method = self.meta.replace("one run, ", "");
        out.push_str(&format!("\nMeasured by `cargo bench -p hw3-benches --bench q2_cost`: {method}\n"));
        out
    }

    fn draw(&self, root: &DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), DrawError> {
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
                Axis::linear(0.0, max_ns, "median ns per call"),
                Axis {
                    format: Some(|y| format!("{y:.0e}")),
                    ..Axis::log(1e-17, 10.0, "relative error of t (0 drawn at 1e-17)")
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
        let settings = crate::testing::insta_settings();
        for name in ["q2_reflection.svg", "q2_closest_approach.svg"] {
            let figure = figures().unwrap().into_iter().find(|f| f.file_name == name).unwrap();
            let svg = String::from_utf8(figure.bytes).unwrap();
            settings.bind(|| insta::assert_snapshot!(name.replace(".svg", "_svg"), svg));
        }
    }
}
