//! Q4's figures: the blind spot versus distance, the texel solid angle of each format, and the
//! accuracy-versus-time Pareto plot drawn from the benchmark's committed CSV.

use super::blind_spot;
use super::irradiance::{Irradiance, equal_weight};
use super::maps::{AnalyticMap, sun_direction};
use crate::envmap::{BuiltinMap, Probe, ProbeError, ProbeFormat, horizontal_camera, luminance};
use crate::plot::{
    Axis, Chart, Figure, FigureJob, Legend, LegendMark, Note, PALETTE, PlotError, Series, Stroke, compact_tick,
};
use glam::DMat3;
use glam::DVec3;
use plotters::prelude::*;

/// The benchmark's committed results (written by `cargo bench -p hw3-benches --bench q4_irradiance`).
const ACCURACY_CSV: &str = crate::data::Q4_ACCURACY_TIME;

/// Every Q4 figure, deterministic bytes; the [`figure_jobs`] run in parallel.
///
/// # Errors
/// [`PlotError`] if a figure cannot be drawn.
///
/// # Examples
/// ```
/// // `figures()` is `run_jobs(&figure_jobs())`: the 320² sphere render and the probe's unwrap
/// // take seconds in a test build, so the example runs the blind-spot chart's job alone.
/// let jobs = hw3::q4_light_probe::figure_jobs();
/// let blind_spot: Vec<_> = jobs.into_iter().filter(|job| job.name == "q4 blind spot").collect();
/// let figures = hw3::plot::run_jobs(&blind_spot).unwrap();
/// assert_eq!(figures.len(), 1);
/// assert_eq!(figures[0].file_name, "q4_blind_spot.svg");
/// ```
pub fn figures() -> Result<Vec<Figure>, PlotError> {
    crate::plot::run_jobs(&figure_jobs())
}

/// Q4's figures as independent jobs, one per figure, in the chapter's order.
///
/// # Examples
/// ```
/// let jobs = hw3::q4_light_probe::figure_jobs();
/// // The sphere render is the one render (320² per panel): CI's release run checks its bytes.
/// assert_eq!(jobs.iter().filter(|job| job.rendered).count(), 1);
/// assert_eq!(jobs.len(), 8);
/// ```
#[must_use]
pub fn figure_jobs() -> Vec<FigureJob> {
    fn one(figure: Result<Figure, PlotError>) -> Result<Vec<Figure>, PlotError> {
        figure.map(|f| vec![f])
    }
    vec![
        FigureJob::drawn("q4 blind spot", || one(blind_spot_figure())),
        FigureJob::drawn("q4 texel solid angle", || one(solid_angle_figure())),
        FigureJob::drawn("q4 pareto soft", || one(pareto_figure("soft"))),
        FigureJob::drawn("q4 pareto sun", || one(pareto_figure("sun"))),
        FigureJob::drawn("q4 pareto courtyard", || one(pareto_figure("courtyard"))),
        FigureJob::drawn("q4 pareto sunrise", || one(pareto_figure("sunrise"))),
        FigureJob::rendered("q4 sphere render", || one(sphere_render_figure())),
        FigureJob::drawn("q4 probe unwrap", || one(unwrap_figure())),
    ]
}

/// `D/R` of the probe photographed in [`unwrap_figure`]: close enough that the blind cone
/// (half-angle `arcsin(R/D)` = 19.5°) is large enough to see.
const UNWRAP_DISTANCE: f64 = 3.0;

/// Side of the square probe image photographed in [`unwrap_figure`], in texels.
const UNWRAP_PROBE_SIZE: usize = 256;
/// The unwrap figure's panels: the ball at `BALL_PIXELS`², the lat-long at `LONG_PIXELS`.
const BALL_PIXELS: usize = 320;
const LONG_PIXELS: (usize, usize) = (640, 320);

/// The unwrap figure's pixels, row-major, `None` where nothing is seen (outside the ball's disk,
/// or in the blind cone of the lat-long panel).
struct Unwrap {
    ball: Vec<Option<DVec3>>,
    long: Vec<Option<DVec3>>,
}

/// Photographs `source` (a lat-long map) as a perspective-ball probe at `D/R` =
/// [`UNWRAP_DISTANCE`] seen from the `+x` horizon, and unwraps that probe to lat-long.
///
/// The probe is what a camera records: each texel the solid-angle-weighted mean of the map over
/// its footprint ([`Probe::from_fn`]), the map read bilinearly. It is not splatted
/// ([`Probe::resample_lat_long`], which conserves a sun's energy for the estimators): splatting
/// a 256 × 128 map's 16 points per texel into a 256² ball lands 4 to 8 points in a texel, so a
/// uniform map comes out with 17 % texel-to-texel noise, a grid over the ball and, at its rim,
/// where the texels on the image's axes catch 1.33 and 0.55 of their share, two lines through
/// the blind cone of the unwrap. Both panels read the probe bilinearly.
///
/// # Errors
/// [`ProbeError::Input`] if [`UNWRAP_DISTANCE`] is not a valid `D/R`, and the [`ProbeError`] of
/// [`Probe::from_fn`] if the probe cannot be built (a texel of `source` that is not finite).
fn unwrap_pixels(source: &Probe) -> Result<Unwrap, ProbeError> {
    use rayon::prelude::*;
    let format = ProbeFormat::perspective_ball(UNWRAP_DISTANCE)?;
    let probe = Probe::from_fn(format, UNWRAP_PROBE_SIZE, UNWRAP_PROBE_SIZE, horizontal_camera(), |w| {
        source.radiance_bilinear(w)
    })?;
    let ball = (0..BALL_PIXELS * BALL_PIXELS)
        .into_par_iter()
        .map(|index| {
            let pixel = |i: usize| (i as f64 + 0.5) / BALL_PIXELS as f64 * 2.0 - 1.0;
            let p = glam::DVec2::new(pixel(index % BALL_PIXELS), -pixel(index / BALL_PIXELS));
            format.image_to_direction(p).map(|_| probe.radiance_bilinear_at(p))
        })
        .collect();
    let (width, height) = LONG_PIXELS;
    let long = (0..width * height)
        .into_par_iter()
        .map(|index| {
            let uv = glam::DVec2::new(
                ((index % width) as f64 + 0.5) / width as f64,
                ((index / width) as f64 + 0.5) / height as f64,
            );
            let omega = ProbeFormat::LatLong.image_to_direction(uv)?;
            probe.world_to_image(omega).map(|p| probe.radiance_bilinear_at(p))
        })
        .collect();
    Ok(Unwrap { ball, long })
}

/// The courtyard map as a perspective mirror-ball probe (`D/R` = [`UNWRAP_DISTANCE`], camera on
/// the `+x` horizon), beside that probe unwrapped to latitude-longitude ([`unwrap_pixels`]), the
/// blind cone behind the ball (directions no ball texel sees) marked in vermillion with its
/// outline. One exposure for both (Reinhard `L/(1 + L)`, gamma 2.2).
fn unwrap_figure() -> Result<Figure, PlotError> {
    let name = "q4_probe_unwrap.png";
    let courtyard = BuiltinMap::Courtyard.probe().map_err(|e| PlotError::data(name, e))?;
    let pixels = unwrap_pixels(&courtyard).map_err(|e| PlotError::data(name, e))?;
    let exposure = |radiance: DVec3| {
        let byte = |c: f64| (255.0 * (c / (1.0 + c)).max(0.0).powf(1.0 / 2.2)).round() as u8;
        RGBColor(byte(radiance.x), byte(radiance.y), byte(radiance.z))
    };
    let band = 26_i32;
    let (ball_size, (long_width, long_height)) = (BALL_PIXELS as i32, (LONG_PIXELS.0 as i32, LONG_PIXELS.1 as i32));
    let blind = PALETTE[1];
    let half_angle = blind_spot::half_angle(UNWRAP_DISTANCE).map_err(|e| PlotError::data(name, e))?;
    crate::plot::png_figure(name, ((ball_size + 12 + long_width) as u32, (long_height + band) as u32), |root| {
        let ball_label = format!("perspective mirror ball, D/R = {UNWRAP_DISTANCE}");
        root.draw(&Text::new(ball_label, (4, 5), ("sans-serif", 14)))?;
        for (index, radiance) in pixels.ball.iter().enumerate() {
            if let Some(radiance) = radiance {
                let (x, y) = ((index % BALL_PIXELS) as i32, (index / BALL_PIXELS) as i32);
                root.draw_pixel((x, y + band), &exposure(*radiance))?;
            }
        }
        let x0 = ball_size + 12;
        let long_label = format!("unwrapped to lat-long; vermillion: the blind cone, {:.1}°", half_angle.to_degrees());
        root.draw(&Text::new(long_label, (x0 + 4, 5), ("sans-serif", 14)))?;
        let seen = |x: i32, y: i32| {
            let (x, y) = (x.rem_euclid(long_width), y.clamp(0, long_height - 1));
            pixels.long[(y * long_width + x) as usize]
        };
        for y in 0..long_height {
            for x in 0..long_width {
                // The cone's outline: the pixels that see the probe while a neighbour does not.
                let colour = match seen(x, y) {
                    Some(_)
                        if [(1, 0), (-1, 0), (0, 1), (0, -1)].iter().any(|(dx, dy)| seen(x + dx, y + dy).is_none()) =>
                    {
                        BLACK
                    }
                    Some(radiance) => exposure(radiance),
                    None => blind,
                };
                root.draw_pixel((x0 + x, y + band), &colour)?;
            }
        }
        Ok(())
    })
}

/// A labelled function of D/R.
type Curve = Box<dyn Fn(f64) -> f64>;

/// The legend box every Q4 chart uses.
const LEGEND: Legend = Legend { position: Some(SeriesLabelPosition::LowerLeft), font: 12, opacity: 0.85 };

/// The blind-spot chart's distance ticks: plotters' own log ticks label only 10, 20, 30, 40 and
/// 50, none of the close distances where the curves change fastest.
const BLIND_SPOT_DISTANCES: [f64; 8] = [1.5, 2.0, 3.0, 5.0, 7.0, 10.0, 20.0, 50.0];

fn blind_spot_figure() -> Result<Figure, PlotError> {
    let distances: Vec<f64> = (0..=200).map(|k| 1.2 * (50.0_f64 / 1.2).powf(k as f64 / 200.0)).collect();
    let curves: [(&str, Curve); 3] = [
        (
            "blind half-angle arcsin(R/D), degrees",
            Box::new(|d| blind_spot::half_angle(d).map_or(f64::NAN, f64::to_degrees)),
        ),
        (
            "blind solid angle, % of 4π",
            Box::new(|d| blind_spot::solid_angle(d).map_or(f64::NAN, |s| 100.0 * s / (4.0 * std::f64::consts::PI))),
        ),
        (
            "irradiance lost at n = away (uniform map), %",
            Box::new(|d| 100.0 * blind_spot::lost_fraction(d, 0.0).unwrap_or(f64::NAN)),
        ),
    ];
    let series = curves
        .iter()
        .enumerate()
        .map(|(index, (label, f))| Series {
            legend: LegendMark::Line { length: 18, width: 2 },
            ..Series::line(*label, distances.iter().map(|&d| (d, f(d))).collect(), PALETTE[index], 2)
        })
        .collect();
    Chart {
        caption_size: 17,
        margin: 10,
        label_areas: (40, 55),
        series,
        legend: Some(LEGEND),
        ..Chart::new(
            "What a mirrored ball misses, vs camera distance D/R",
            Axis {
                ticks: Some(&BLIND_SPOT_DISTANCES),
                format: Some(compact_tick),
                ..Axis::log(1.2, 50.0, "D/R (camera distance in ball radii)")
            },
            Axis {
                ticks: Some(&[0.01, 0.1, 1.0, 10.0, 100.0]),
                format: Some(compact_tick),
                ..Axis::log(0.01, 100.0, "degrees  /  percent")
            },
        )
    }
    .svg("q4_blind_spot.svg", (640, 400))
}

/// Side of each panel of the texel solid-angle figure, in pixels: one texel per pixel, and
/// large enough that a 13 px label fits under every panel of a figure as wide as the notes' text
/// column.
const SOLID_ANGLE_PANEL: usize = 192;

/// A false-colour image of `Δω / share` per texel for each disk format and lat-long, on a shared
/// logarithmic scale (one colour bar, its ticks the ratio): where the format spends its
/// resolution. The share is the one the unweighted sum gives every texel used,
/// [`equal_weight`]: the solid angle the image covers divided among the texels whose centre it
/// uses (`4π/N` on the orthographic ball, as in the chapter's Part q4c). Each panel's label names
/// the format and states the share, in steradians.
fn solid_angle_figure() -> Result<Figure, PlotError> {
    let name = "q4_texel_solid_angle.png";
    let size = SOLID_ANGLE_PANEL;
    let formats = [
        (ProbeFormat::MirrorBall, "orthographic mirror ball"),
        (ProbeFormat::PerspectiveBall { distance_over_radius: 3.0 }, "perspective ball, D/R = 3"),
        (ProbeFormat::AngularMap, "angular map"),
        (ProbeFormat::LatLong, "latitude-longitude"),
    ];
    let mut panels = Vec::new();
    for (format, label) in formats {
        let (w, h) = if format == ProbeFormat::LatLong { (size, size / 2) } else { (size, size) };
        let probe = Probe::from_fn(format, w, h, DMat3::IDENTITY, |_| glam::DVec3::ZERO)
            .map_err(|e| PlotError::data(name, e))?;
        let share = equal_weight(probe.texels());
        // log10 of the ratio, −1 (10× smaller) … 1 (10× larger); `None` outside the image's disk.
        let ratios: Vec<Option<f64>> = probe
            .texels()
            .iter()
            .map(|texel| (texel.solid_angle > 0.0).then(|| (texel.solid_angle / share).log10().clamp(-1.0, 1.0)))
            .collect();
        panels.push((label, format!("{w}×{h} texels, share {share:.1e} sr"), (w, h), ratios));
    }
    // A diverging ramp: blue (10× smaller) → pale grey (the share) → vermillion (10× larger).
    let ramp = |t: f64| {
        let end = if t < 0.0 { PALETTE[0] } else { PALETTE[1] };
        let mid = 235.0;
        let mix = |y: u8| (mid + (f64::from(y) - mid) * t.abs()).round() as u8;
        RGBColor(mix(end.0), mix(end.1), mix(end.2))
    };
    let (gap, label_band, bar_band) = (12_usize, 44_usize, 96_usize);
    let width = formats.len() * (size + gap) - gap + bar_band;
    crate::plot::png_figure(name, (width as u32, (size + label_band) as u32), |root| {
        for (slot, (label, share, (w, h), ratios)) in panels.iter().enumerate() {
            let x0 = slot * (size + gap);
            let y0 = (size - h) / 2;
            for (index, ratio) in ratios.iter().enumerate() {
                if let Some(t) = ratio {
                    root.draw_pixel(((x0 + index % w) as i32, (y0 + index / w) as i32), &ramp(*t))?;
                }
            }
            let text_at = |line: usize| (x0 as i32 + 2, (size + 6 + 17 * line) as i32);
            root.draw(&Text::new(*label, text_at(0), ("sans-serif", 13)))?;
            root.draw(&Text::new(share.as_str(), text_at(1), ("sans-serif", 12)))?;
        }
        let bar_x = (formats.len() * (size + gap)) as i32 + 4;
        let at = |ratio: f64| (ratio.log10() + 1.0) / 2.0;
        let ticks = [(at(0.1), "0.1×"), (at(0.3), "0.3×"), (at(1.0), "1× share"), (at(3.0), "3×"), (at(10.0), "10×")];
        crate::plot::color_bar(root, (bar_x, 8), (14, size as i32 - 16), &|v| ramp(2.0 * v - 1.0), &ticks)?;
        let title = ("sans-serif", 12);
        root.draw(&Text::new("texel Δω / share", (bar_x - 4, size as i32 + 6), title))?;
        root.draw(&Text::new("(log scale)", (bar_x - 4, size as i32 + 23), title))?;
        Ok(())
    })
}

/// Side length of a rendered sphere panel, in pixels: three across span about the notes' text column.
const RENDER_SIZE: usize = 320;

/// One rendered row: per pixel (row-major, `None` outside the sphere) the reference, SH9 and
/// 16-sample MIS irradiance (luminance), and the peak used for tone mapping.
struct RenderRow {
    title: &'static str,
    reference: Vec<Option<f64>>,
    sh9: Vec<Option<f64>>,
    mis: Vec<Option<f64>>,
    peak: f64,
}

impl RenderRow {
    /// The mean and the largest `|estimate − reference| / peak` over the sphere's pixels: the
    /// numbers printed over the row's error maps.
    fn error_of(&self, estimate: &[Option<f64>]) -> (f64, f64) {
        let errors: Vec<f64> = self
            .reference
            .iter()
            .zip(estimate)
            .filter_map(|(r, e)| Some((e.as_ref()? - r.as_ref()?).abs() / self.peak))
            .collect();
        let mean = errors.iter().sum::<f64>() / errors.len().max(1) as f64;
        (mean, errors.iter().copied().fold(0.0, f64::max))
    }
}

/// Renders a white diffuse sphere (orthographic view, image up = world `+z`, the sun's azimuth to
/// the right) lit through `probe`. Pixels are independent, each with its own generator stream,
/// so the parallel loop gives the same bytes on any thread count.
fn render_row(title: &'static str, probe: &Probe, reference: &(dyn Fn(DVec3) -> f64 + Sync), sun: DVec3) -> RenderRow {
    use rayon::prelude::*;
    let prepared = Irradiance::new(probe);
    let right = DVec3::new(sun.x, sun.y, 0.0).normalize();
    let up = DVec3::Z;
    let toward_viewer = right.cross(up);
    let pixels: Vec<Option<(f64, f64, f64)>> = (0..RENDER_SIZE * RENDER_SIZE)
        .into_par_iter()
        .map(|index| {
            let a = ((index % RENDER_SIZE) as f64 + 0.5) / RENDER_SIZE as f64 * 2.0 - 1.0;
            let b = 1.0 - ((index / RENDER_SIZE) as f64 + 0.5) / RENDER_SIZE as f64 * 2.0;
            let r2 = a * a + b * b;
            (r2 < 1.0).then(|| {
                let n = right * a + up * b + toward_viewer * (1.0 - r2).sqrt();
                let mut rng = crate::rng::seeded(0, index as u64);
                (reference(n), luminance(prepared.sh9().irradiance(n)), luminance(prepared.mis(n, 16, &mut rng)))
            })
        })
        .collect();
    RenderRow {
        title,
        reference: pixels.iter().map(|p| p.map(|v| v.0)).collect(),
        sh9: pixels.iter().map(|p| p.map(|v| v.1)).collect(),
        mis: pixels.iter().map(|p| p.map(|v| v.2)).collect(),
        peak: reference(sun),
    }
}

/// A white diffuse sphere lit through a 128² mirror-ball probe by the analytic sun map (top row)
/// and by the real sunrise map (bottom row): reference, SH9, MIS with 16 samples per pixel, and
/// the two methods' errors as a fraction of the peak irradiance (white 0 → vermillion ≥ 10 %,
/// with the colour bar and its scale beside them), each map on two rows of three panels.
fn sphere_render_figure() -> Result<Figure, PlotError> {
    let name = "q4_sphere_render.png";
    let failed = |e: ProbeError| PlotError::data(name, e);
    let sun_map = AnalyticMap::sun();
    let sun_probe = sun_map.rasterise(ProbeFormat::MirrorBall, 128, horizontal_camera()).map_err(failed)?;
    let sunrise = BuiltinMap::Sunrise.probe().map_err(failed)?;
    let sunrise_ball =
        Probe::resample_lat_long(&sunrise, ProbeFormat::MirrorBall, 128, horizontal_camera()).map_err(failed)?;
    let sunrise_reference = Irradiance::new(&sunrise);
    let brightest = sunrise
        .texels()
        .iter()
        .max_by(|a, b| luminance(a.radiance).total_cmp(&luminance(b.radiance)))
        .map_or(DVec3::X, |t| t.direction);
    let rows = [
        render_row("analytic sun", &sun_probe, &|n| sun_map.irradiance(n), sun_direction()),
        render_row("sunrise (CC0)", &sunrise_ball, &|n| luminance(sunrise_reference.weighted(n)), brightest),
    ];
    // Each map takes two rows of three panels: its pictures (reference, SH9, MIS), then the two
    // methods' error maps with the colour bar in the third place.
    let gap = 8_usize;
    let label_band = 36_usize;
    let columns = 3;
    let width = columns * (RENDER_SIZE + gap) - gap;
    let height = 2 * rows.len() * (RENDER_SIZE + label_band);
    crate::plot::png_figure(name, (width as u32, height as u32), |root| {
        for (row_index, row) in rows.iter().enumerate() {
            // Tone mapping: E / peak, gamma 2.2 (L_o = E/π for albedo 1, up to exposure).
            let tone = |e: f64| {
                let byte = (255.0 * (e / row.peak).clamp(0.0, 1.0).powf(1.0 / 2.2)).round() as u8;
                RGBColor(byte, byte, byte)
            };
            let heat = |error: f64| {
                let t = (error / (0.1 * row.peak)).clamp(0.0, 1.0);
                let end = PALETTE[1];
                let mix = |y: u8| (255.0 + (y as f64 - 255.0) * t).round() as u8;
                RGBColor(mix(end.0), mix(end.1), mix(end.2))
            };
            let pixel = |panel: usize, i: usize| -> Option<RGBColor> {
                let (reference, sh9, mis) = (row.reference[i]?, row.sh9[i]?, row.mis[i]?);
                Some(match panel {
                    0 => tone(reference),
                    1 => tone(sh9),
                    2 => tone(mis),
                    3 => heat((sh9 - reference).abs()),
                    _ => heat((mis - reference).abs()),
                })
            };
            let labels = [row.title, "SH9", "MIS, 16 samples", "SH9 error", "MIS error"];
            let (sh9_error, mis_error) = (row.error_of(&row.sh9), row.error_of(&row.mis));
            let measured = |(mean, max): (f64, f64)| format!("mean {:.1} %, max {:.1} %", 100.0 * mean, 100.0 * max);
            let second_lines = [String::new(), String::new(), String::new(), measured(sh9_error), measured(mis_error)];
            let corner = |panel: usize| {
                let (x, y) = (panel % columns, 2 * row_index + panel / columns);
                (x * (RENDER_SIZE + gap), y * (RENDER_SIZE + label_band))
            };
            let (bar_x, bar_y) = corner(5);
            let ramp = |v: f64| heat(v * 0.1 * row.peak);
            let bar_at = (bar_x as i32 + 24, (bar_y + label_band) as i32 + 8);
            let ticks = [(0.0, "0"), (0.5, "5 %"), (1.0, "≥ 10 %")];
            root.draw(&Text::new("|error|/peak", (bar_x as i32 + 20, bar_y as i32 + 4), ("sans-serif", 13)))?;
            crate::plot::color_bar(root, bar_at, (16, RENDER_SIZE as i32 - 16), &ramp, &ticks)?;
            for (panel, label) in labels.iter().enumerate() {
                let (x0, y0) = corner(panel);
                root.draw(&Text::new(*label, (x0 as i32 + 4, y0 as i32 + 4), ("sans-serif", 13)))?;
                let second = &second_lines[panel];
                root.draw(&Text::new(second.as_str(), (x0 as i32 + 4, y0 as i32 + 19), ("sans-serif", 12)))?;
                for index in 0..RENDER_SIZE * RENDER_SIZE {
                    if let Some(c) = pixel(panel, index) {
                        let x = (x0 + index % RENDER_SIZE) as i32;
                        let y = (y0 + label_band + index / RENDER_SIZE) as i32;
                        root.draw_pixel((x, y), &c)?;
                    }
                }
            }
        }
        Ok(())
    })
}

/// One row of the benchmark CSV.
struct Row {
    map: String,
    method: String,
    label: String,
    mean_percent: f64,
    nanoseconds: f64,
}

fn parse_csv(text: &str) -> Vec<Row> {
    crate::data::csv(text)
        .records
        .into_iter()
        .filter_map(|f| {
            Some(Row {
                map: f.first()?.to_string(),
                method: f.get(1)?.to_string(),
                label: f.get(2)?.to_string(),
                mean_percent: f.get(5)?.parse().ok()?,
                nanoseconds: f.get(7)?.parse().ok()?,
            })
        })
        .collect()
}

fn pareto_figure(map: &str) -> Result<Figure, PlotError> {
    let rows: Vec<Row> = parse_csv(ACCURACY_CSV)
        .into_iter()
        .filter(|r| r.map == map && r.mean_percent > 0.0 && r.nanoseconds > 0.0)
        .collect();
    let (t_min, t_max) =
        rows.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), r| (lo.min(r.nanoseconds), hi.max(r.nanoseconds)));
    let (e_min, e_max) =
        rows.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), r| (lo.min(r.mean_percent), hi.max(r.mean_percent)));
    let methods = ["unweighted", "weighted", "sh9", "uniform", "cosine", "map", "mis"];
    // Per method: a thin line through its points, then the dots, which carry the legend entry.
    let series = methods
        .iter()
        .enumerate()
        .map(|(index, method)| {
            let points = rows.iter().filter(|r| r.method == *method).map(|r| (r.nanoseconds, r.mean_percent)).collect();
            Series {
                line: Some(Stroke { width: 1, dash: None }),
                ..Series::dots(method_name(method), points, pareto_colour(index), 4)
            }
        })
        .collect();
    // Name the SH9 and 256² weighted points, the chapter's comparison pair.
    let notes = rows
        .iter()
        .filter(|r| r.label == "sh9 256²" || r.label == "weighted 256²")
        .map(|r| Note::new(r.label.replace("sh9", "SH9"), (r.nanoseconds * 1.15, r.mean_percent), 11))
        .collect();
    let caption = format!("Error vs time per normal, {map} map (benchmark data)");
    Chart {
        caption_size: 17,
        margin: 10,
        series,
        notes,
        legend: Some(LEGEND),
        ..Chart::new(
            &caption,
            Axis {
                format: Some(compact_tick),
                ..Axis::log(t_min.min(1.0) * 0.5, t_max.max(10.0) * 2.0, "time per normal, ns (log)")
            },
            Axis {
                format: Some(compact_tick),
                ..Axis::log(e_min.min(1e-3) * 0.5, e_max.max(1.0) * 2.0, "mean error, % of peak E (log)")
            },
        )
    }
    .svg(&format!("q4_pareto_{map}.svg"), (680, 440))
}

/// The colour of the `index`-th method of the Pareto charts: [`PALETTE`] in order, but black for
/// the seventh (MIS) instead of the palette's yellow, which barely shows on white.
fn pareto_colour(index: usize) -> RGBColor {
    if index == 6 { PALETTE[7] } else { PALETTE[index % PALETTE.len()] }
}

/// A benchmark method key as the chapter writes it: SH9 and MIS are acronyms, the other keys
/// (unweighted, weighted, uniform, cosine, map) are words.
fn method_name(method: &str) -> String {
    match method {
        "sh9" | "mis" => method.to_uppercase(),
        _ => method.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // That these figures are deterministic is checked by the integration test
    // `docs::committed_figures_are_what_the_code_generates`: every drawn figure, generated there
    // (test profile, the machine's threads), equals byte for byte the committed file that
    // `cargo run --release` wrote. Drawing them twice more here (5.5 s of CPU) added nothing.

    /// The seam's cause and its cure: a uniform map photographed and unwrapped for the figure
    /// is uniform in both panels (every seen pixel equals the map), while the splatting
    /// resampler leaves the texel noise that drew a grid over the ball and lines through the
    /// blind cone.
    #[test]
    fn a_uniform_map_unwraps_to_a_uniform_picture_with_no_seam() {
        let flat = Probe::from_fn(ProbeFormat::LatLong, 256, 128, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
        let pixels = unwrap_pixels(&flat).unwrap();
        for (panel, values) in [("ball", &pixels.ball), ("lat-long", &pixels.long)] {
            let seen: Vec<DVec3> = values.iter().flatten().copied().collect();
            assert!(seen.len() > values.len() / 2, "{panel}");
            let worst = seen.iter().map(|v| (*v - DVec3::ONE).abs().max_element()).fold(0.0, f64::max);
            assert!(worst < 1e-9, "{panel}: worst deviation {worst}");
        }
        // The lat-long panel's first and last columns meet at φ = 0 = 2π (the ball's centre).
        let (width, height) = LONG_PIXELS;
        let row = height / 3;
        assert!(pixels.long[row * width].is_some() && pixels.long[row * width + width - 1].is_some());
        let format = ProbeFormat::perspective_ball(UNWRAP_DISTANCE).unwrap();
        let splatted = Probe::resample_lat_long(&flat, format, UNWRAP_PROBE_SIZE, horizontal_camera()).unwrap();
        let worst = splatted
            .texels()
            .iter()
            .filter(|t| t.solid_angle > 0.0)
            .map(|t| (t.radiance.x - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(worst > 0.3, "the splatted probe's worst texel is off by {worst}");
    }

    /// The lat-long panel of a map that varies with longitude is continuous across the φ = 0
    /// meridian: its first and last columns differ by no more than neighbouring columns do.
    #[test]
    fn the_unwrap_is_continuous_across_the_meridian() {
        let source = Probe::from_fn(ProbeFormat::LatLong, 256, 128, DMat3::IDENTITY, |w| {
            DVec3::new(1.0 + w.y, 1.0 + w.x, 1.0 + w.z)
        })
        .unwrap();
        let pixels = unwrap_pixels(&source).unwrap();
        let (width, height) = LONG_PIXELS;
        for row in (0..height).step_by(16) {
            let at = |x: usize| pixels.long[row * width + x];
            let (Some(first), Some(last), Some(second)) = (at(0), at(width - 1), at(1)) else { continue };
            let across = (first - last).abs().max_element();
            let step = (second - first).abs().max_element();
            assert!(across <= 1.5 * step + 1e-6, "row {row}: across the meridian {across}, one column {step}");
        }
    }

    #[test]
    fn error_map_labels_state_the_mean_and_largest_error_over_the_sphere() {
        let row = RenderRow {
            title: "t",
            reference: vec![Some(1.0), Some(2.0), None],
            sh9: vec![Some(1.5), Some(2.0), None],
            mis: vec![Some(0.0), Some(2.0), None],
            peak: 2.0,
        };
        assert_eq!(row.error_of(&row.sh9), (0.125, 0.25));
        assert_eq!(row.error_of(&row.mis), (0.25, 0.5));
    }

    #[test]
    fn the_committed_csv_parses() {
        let rows = parse_csv(ACCURACY_CSV);
        assert!(!rows.is_empty(), "run cargo bench -p hw3-benches --bench q4_irradiance");
        for map in ["soft", "sun", "courtyard", "sunrise"] {
            assert!(rows.iter().any(|r| r.map == map && r.method == "sh9"));
        }
    }
}
