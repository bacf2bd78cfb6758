//! Diagrams of the homework's tree: cells and split lines, the ray, and each visited leaf's piece
//! of the ray, coloured and labelled with its parameter interval.

use super::{Axis2, Interval, Node2, Ray2, RayText, student, traverse, write_path};
use crate::kdtree::Side;
use crate::plot::{Axis, Chart, DrawError, Figure, PALETTE, PlotError, Series, Shape, legend_grid, svg_figure};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::fmt;

/// The window drawn: `x ∈ [−2, 8]`, `y ∈ [−3, 7]`.
const WINDOW: [(f64, f64); 2] = [(-2.0, 8.0), (-3.0, 7.0)];

/// The general case drawn next to (d) and (e): it visits all four leaves.
pub(super) const GENERAL_RAY: Ray2 = Ray2 { origin: [0.0, 0.0], dir: [1.0, 0.5] };

pub(super) fn figures() -> Result<Vec<Figure>, PlotError> {
    let mut figures = Vec::new();
    for case in student::cases() {
        let title = format!("case ({}): {}", case.label, RayText(&case.ray));
        figures.push(diagram(&format!("q3_case_{}.svg", case.label), &title, &case.ray)?);
        figures.push(steps(&format!("q3_steps_{}.svg", case.label), &case.ray)?);
    }
    let title = format!("general case: {}", RayText(&GENERAL_RAY));
    figures.push(diagram("q3_general.svg", &title, &GENERAL_RAY)?);
    Ok(figures)
}

/// The part `[0, t_exit]` of the ray inside the drawing window (the window holds every origin).
fn window_exit(ray: &Ray2) -> f64 {
    [Axis2::X, Axis2::Y]
        .into_iter()
        .filter(|axis| ray.dir[axis.index()] != 0.0)
        .map(|axis| {
            let (lo, hi) = WINDOW[axis.index()];
            let (e, d) = (ray.origin[axis.index()], ray.dir[axis.index()]);
            ((lo - e) / d).max((hi - e) / d)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Every split line of `node`, clipped to `bounds` (the node's cell within the window).
fn split_lines(node: &Node2, bounds: [(f64, f64); 2], out: &mut Vec<[(f64, f64); 2]>) {
    let Node2::Split { axis, split, lower, upper } = node else {
        return;
    };
    let a = axis.index();
    let (lo, hi) = bounds[1 - a];
    out.push(match axis {
        Axis2::X => [(*split, lo), (*split, hi)],
        Axis2::Y => [(lo, *split), (hi, *split)],
    });
    for (side, child) in [(Side::Lower, lower), (Side::Upper, upper)] {
        let mut child_bounds = bounds;
        match side {
            Side::Lower => child_bounds[a].1 = split.min(bounds[a].1),
            Side::Upper => child_bounds[a].0 = split.max(bounds[a].0),
        }
        split_lines(child, child_bounds, out);
    }
}

/// Width in pixels of a diagram drawn alone; a step panel is narrower ([`STEPS_WIDTH`]).
const DIAGRAM_WIDTH: u32 = 560;
/// Largest width in pixels of a steps figure, all its panels together: the notes' text column,
/// so that the figure is shown at its own size and its labels keep their pixel sizes on screen
/// (a panel is never wider than [`DIAGRAM_WIDTH`]).
const STEPS_WIDTH: u32 = 936;

/// Approximate size of a 13 px cell label in plot units, in a panel `width` pixels wide (at
/// [`DIAGRAM_WIDTH`] 10 units span about 480 px: 0.14 per character wide, 0.3 high).
fn label_size(text: &str, width: u32) -> (f64, f64) {
    let scale = f64::from(DIAGRAM_WIDTH) / f64::from(width);
    (0.14 * text.chars().count() as f64 * scale, 0.3 * scale)
}

/// [`label_size`] of a 14 px interval label: 0.15 per character wide.
fn interval_label_size(text: &str, width: u32) -> (f64, f64) {
    let (w, h) = label_size(text, width);
    (w * 15.0 / 14.0, h)
}

/// Distance from the box `[x0, x1] × [y0, y1]` to the segment `a`–`b` (0 when they meet),
/// measured at 64 points along the segment: finer than any label is wide.
fn box_clearance([(x0, x1), (y0, y1)]: [(f64, f64); 2], a: (f64, f64), b: (f64, f64)) -> f64 {
    (0..=64)
        .map(|i| {
            let s = f64::from(i) / 64.0;
            let (px, py) = (a.0 + s * (b.0 - a.0), a.1 + s * (b.1 - a.1));
            (x0 - px).max(px - x1).max(0.0).hypot((y0 - py).max(py - y1).max(0.0))
        })
        .fold(f64::INFINITY, f64::min)
}

/// Distance from the point `p` to the segment `a`–`b`.
fn distance_to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (ux, uy) = (b.0 - a.0, b.1 - a.1);
    let length2 = ux * ux + uy * uy;
    let s = if length2 > 0.0 { (((p.0 - a.0) * ux + (p.1 - a.1) * uy) / length2).clamp(0.0, 1.0) } else { 0.0 };
    (p.0 - a.0 - s * ux).hypot(p.1 - a.1 - s * uy)
}

/// Where to anchor (top-left) a cell's label: the inner corner of the cell's visible box whose
/// label box lies farthest from the drawn ray (ties: the first of top-left, top-right,
/// bottom-left, bottom-right).
fn label_anchor(text: &str, bounds: [(f64, f64); 2], ray: [(f64, f64); 2], width: u32) -> (f64, f64) {
    let (w, h) = label_size(text, width);
    let margin = 0.15;
    let [(x0, x1), (y0, y1)] = bounds;
    let corners = [
        (x0 + margin, y1 - margin),
        (x1 - margin - w, y1 - margin),
        (x0 + margin, y0 + margin + h),
        (x1 - margin - w, y0 + margin + h),
    ];
    let clearance = |(x, y): (f64, f64)| {
        [(x, y), (x + w, y), (x, y - h), (x + w, y - h), (x + w / 2.0, y - h / 2.0)]
            .into_iter()
            .map(|p| distance_to_segment(p, ray[0], ray[1]))
            .fold(f64::INFINITY, f64::min)
    };
    corners
        .into_iter()
        .fold((corners[0], f64::NEG_INFINITY), |best, c| {
            let d = clearance(c);
            if d > best.1 { (c, d) } else { best }
        })
        .0
}

/// A path printed as in the trace (`x>=3, y<3`).
struct PathText<'a>(&'a [super::Branch]);

impl fmt::Display for PathText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_path(f, self.0)
    }
}

/// Where to anchor (top-left) the label `text` of the leaf piece `[from, to]` of `ray`, in the
/// leaf's visible cell `bounds`: beside the piece's middle on its right-hand side ([`beside`])
/// when that box stays inside the cell; otherwise the first box, off the piece's middle or
/// nearer either end, on either side, ever farther out, that lies inside the cell (pushed in
/// from its edges) and 0.12 units clear of the drawn ray, so that no label sits on a split line
/// or on the ray. Falls back to [`beside`] when no box fits.
fn interval_anchor(
    text: &str,
    ray: &Ray2,
    (from, to): (f64, f64),
    bounds: [(f64, f64); 2],
    drawn_ray: [(f64, f64); 2],
    width: u32,
) -> (f64, f64) {
    let (w, h) = interval_label_size(text, width);
    let margin = 0.06;
    let [(x0, x1), (y0, y1)] = bounds;
    let boxed = |(x, y): (f64, f64)| [(x, x + w), (y - h, y)];
    let inside = |[(a0, a1), (b0, b1)]: [(f64, f64); 2]| {
        a0 >= x0 + margin && a1 <= x1 - margin && b0 >= y0 + margin && b1 <= y1 - margin
    };
    let clear = |corners| box_clearance(corners, drawn_ray[0], drawn_ray[1]) >= 0.12;
    let middle = beside(ray, (from + to) / 2.0);
    if inside(boxed(middle)) && clear(boxed(middle)) {
        return middle;
    }
    let [dx, dy] = ray.dir;
    let length = dx.hypot(dy);
    let normal = (dy / length, -dx / length);
    for offset in (3..=15).map(|k| f64::from(k) / 10.0) {
        for fraction in [0.5, 0.3, 0.7] {
            let p = ray.at(from + fraction * (to - from));
            for side in [1.0, -1.0] {
                let centre = (p[0] + side * offset * normal.0, p[1] + side * offset * normal.1);
                let x = (centre.0 - w / 2.0).clamp(x0 + margin, (x1 - margin - w).max(x0 + margin));
                let y = (centre.1 + h / 2.0).clamp((y0 + margin + h).min(y1 - margin), y1 - margin);
                if inside(boxed((x, y))) && clear(boxed((x, y))) {
                    return (x, y);
                }
            }
        }
    }
    middle
}

fn diagram(file_name: &str, title: &str, ray: &Ray2) -> Result<Figure, PlotError> {
    svg_figure(file_name, (DIAGRAM_WIDTH, DIAGRAM_WIDTH + 80), |root| draw(root, title, ray, None))
}

/// The traversal of `ray` cell by cell: one panel per visited leaf, in the order the traversal
/// visits them, the current leaf's cell shaded and the ray drawn only as far as that leaf.
fn steps(file_name: &str, ray: &Ray2) -> Result<Figure, PlotError> {
    let leaves = traverse(&Node2::homework(), ray).leaves();
    let count = leaves.len().max(1);
    let panel = (STEPS_WIDTH / count as u32).min(DIAGRAM_WIDTH);
    svg_figure(file_name, (panel * count as u32, panel + 80), |root| {
        for (k, area) in root.split_evenly((1, count)).iter().enumerate() {
            let Some(leaf) = leaves.get(k) else { continue };
            let title = format!("step {} of {count}: leaf {}, t in {}", k + 1, PathText(&leaf.path), leaf.interval);
            draw(area, &title, ray, Some(k))?;
        }
        Ok(())
    })
}

/// Draws the tree, the ray and the visited leaves' pieces; with `step = Some(k)`, only the first
/// `k + 1` leaves, the `k`-th one's cell shaded in its colour.
fn draw(
    root: &DrawingArea<SVGBackend<'_>, Shift>,
    title: &str,
    ray: &Ray2,
    step: Option<usize>,
) -> Result<(), DrawError> {
    let tree = Node2::homework();
    let [(x0, x1), (y0, y1)] = WINDOW;
    let width = root.dim_in_pixel().0;
    let (plot_area, legend_area) = root.split_vertically(width);
    let visible = |cell: &super::Cell| {
        [Axis2::X, Axis2::Y].map(|axis| {
            let (lo, hi) = cell.bounds(axis);
            let (wlo, whi) = WINDOW[axis.index()];
            (lo.max(wlo), hi.min(whi))
        })
    };
    let mut shapes = Vec::new();
    let leaves = traverse(&tree, ray).leaves();
    if let Some(leaf) = step.and_then(|k| leaves.get(k)) {
        let [(a0, a1), (b0, b1)] = visible(&super::Cell { path: leaf.path.clone() });
        let colour = PALETTE[step.unwrap_or(0) % PALETTE.len()];
        shapes.push(Shape::Rectangle { corners: [(a0, b0), (a1, b1)], colour, opacity: 0.15 });
    }
    let grey = RGBColor(110, 110, 110);
    let mut lines = Vec::new();
    split_lines(&tree, WINDOW, &mut lines);
    shapes.extend(lines.into_iter().map(|line| Shape::line(line.to_vec(), grey, 2)));
    let t_exit = window_exit(ray);
    let drawn_ray = [tuple(ray.at(0.0)), tuple(ray.at(t_exit))];
    for cell in tree.cells() {
        let text = PathText(&cell.path).to_string();
        let anchor = label_anchor(&text, visible(&cell), drawn_ray, width);
        shapes.push(Shape::text(text, anchor, 13, grey));
    }
    shapes.push(Shape::line(drawn_ray.to_vec(), BLACK, 1));
    let shown = step.map_or(leaves.len(), |k| k + 1);
    for (i, leaf) in leaves.iter().take(shown).enumerate() {
        let colour = PALETTE[i % PALETTE.len()];
        let Interval { t_min, t_max } = leaf.interval;
        let (from, to) = (t_min.min(t_exit), t_max.min(t_exit));
        shapes.push(Shape::line(vec![tuple(ray.at(from)), tuple(ray.at(to))], colour, 5));
        let text = leaf.interval.to_string();
        let bounds = visible(&super::Cell { path: leaf.path.clone() });
        let anchor = interval_anchor(&text, ray, (from, to), bounds, drawn_ray, width);
        shapes.push(Shape::text(text, anchor, 14, colour));
    }
    shapes.push(Shape::dot(tuple(ray.origin), 4, BLACK));
    shapes.push(Shape::text("e", (ray.origin[0] + 0.12, ray.origin[1] + 0.35), 15, BLACK));
    let axis = |(low, high), desc| Axis { format: Some(|v| format!("{v}")), ..Axis::linear(low, high, desc) };
    Chart {
        caption_size: 17,
        label_areas: (36, 40),
        // 13 px ticks, as the cell labels: the figure is shown at its own width.
        label_size: 13,
        light_grid: false,
        grid_colour: Some(RGBColor(230, 230, 230)),
        shapes,
        legend: None,
        ..Chart::new(title, axis((x0, x1), "x"), axis((y0, y1), "y"))
    }
    .draw(&plot_area)?;
    // The legend sits below the chart, so it never hides a cell: two entries per row, one in a
    // step panel (too narrow for two).
    let entries: Vec<Series> = leaves
        .iter()
        .take(shown)
        .enumerate()
        .map(|(i, leaf)| {
            let text = format!("leaf {}: t in {}", PathText(&leaf.path), leaf.interval);
            Series::line(text, Vec::new(), PALETTE[i % PALETTE.len()], 5)
        })
        .collect();
    legend_grid(&legend_area, &entries, if width >= DIAGRAM_WIDTH { 2 } else { 1 }, 13)
}

/// A text anchor (top-left) beside the ray at `t`: 0.3 units off the line on its right-hand
/// side (normal with positive x), raised by a text height when that side is above the line.
fn beside(ray: &Ray2, t: f64) -> (f64, f64) {
    let [dx, dy] = ray.dir;
    let length = dx.hypot(dy);
    let (mut nx, mut ny) = (dy / length, -dx / length);
    if nx < 0.0 || (nx == 0.0 && ny < 0.0) {
        (nx, ny) = (-nx, -ny);
    }
    let p = ray.at(t);
    let raise = if ny > 0.0 { 0.3 } else { 0.0 };
    (p[0] + 0.3 * nx, p[1] + 0.3 * ny + raise)
}

fn tuple(p: [f64; 2]) -> (f64, f64) {
    (p[0], p[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagrams_are_pinned() {
        let _guard = crate::testing::insta_settings().bind_to_scope();
        for figure in figures().unwrap() {
            let name = figure.file_name.trim_end_matches(".svg").to_owned();
            insta::assert_snapshot!(name, String::from_utf8(figure.bytes).unwrap());
        }
    }

    #[test]
    fn split_lines_stop_at_their_cells() {
        let mut lines = Vec::new();
        split_lines(&Node2::homework(), WINDOW, &mut lines);
        assert_eq!(lines, [[(3.0, -3.0), (3.0, 7.0)], [(-2.0, 1.0), (3.0, 1.0)], [(3.0, 3.0), (8.0, 3.0)]]);
    }

    #[test]
    fn window_exit_is_where_the_ray_leaves_the_drawing() {
        // Case (d): from (5, 0) along (−1, 1), the top edge y = 7 is reached at t = 7.
        assert_eq!(window_exit(&student::cases()[0].ray), 7.0);
    }
}
