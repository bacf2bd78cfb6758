#![doc = include_str!(concat!(env!("OUT_DIR"), "/render.md"))]

pub mod analysis;
pub mod bsdf;
pub mod camera;
pub mod catalogue;
pub mod color;
pub mod command;
pub mod environment;
mod error;
pub mod figures;
pub mod integrator;
pub mod medium;
pub mod noise;
pub mod passes;
pub mod photon;
pub mod sampling;
pub mod scene;

pub use error::{MAX_PIXELS, MAX_SIDE, MAX_SPP, RenderError};

use camera::CameraFrame;
use glam::DVec3;
use integrator::{Integrator, Tracer};
use passes::Passes;
use rayon::prelude::*;
use sampling::Sampler;
use scene::Scene;

/// How to render: size, samples, integrator, passes and seed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// The light transport algorithm.
    pub integrator: Integrator,
    /// Which passes run (usually [`analysis::analyze`]'s plan).
    pub passes: Passes,
    /// Seed of every pixel's random streams (and of the caustic photons).
    pub seed: u64,
    /// Photons and gather of the caustic pass ([`passes::Pass::Caustics`]).
    pub caustics: CausticSettings,
}

impl Settings {
    /// Whitted ray tracing (up to 8 mirror reflections), seed 1, with the given plan and the
    /// default caustic settings ([`CausticSettings::DEFAULT`]).
    #[must_use]
    pub fn whitted(width: u32, height: u32, spp: u32, passes: Passes) -> Self {
        let integrator = Integrator::Whitted { max_depth: 8 };
        Self { width, height, spp, integrator, passes, seed: 1, caustics: CausticSettings::DEFAULT }
    }
}

/// The caustic pass's settings: how many photons to aim at the mirrors and glass, and how to
/// gather them at a diffuse hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CausticSettings {
    /// Photons traced once per render (1…[`photon::MAX_PHOTONS`]).
    pub photons: usize,
    /// The `k` nearest photons within a maximum radius.
    pub gather: photon::Gather,
}

impl CausticSettings {
    /// [`photon::CAUSTIC_PHOTONS`] photons, [`photon::CAUSTIC_GATHER`].
    pub const DEFAULT: Self = Self { photons: photon::CAUSTIC_PHOTONS, gather: photon::CAUSTIC_GATHER };
}

/// A rendered image: linear radiance per pixel, row-major, top row first.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height` linear RGB radiances.
    pub pixels: Vec<DVec3>,
}

impl Image {
    /// 8-bit sRGB (radiance clamped to `[0, 1]`, then the sRGB transfer curve).
    #[must_use]
    pub fn to_rgb8(&self) -> crate::plot::RgbImage {
        let encode = |c: f64| {
            let c = c.clamp(0.0, 1.0);
            let s = if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
            (s * 255.0).round() as u8
        };
        let bytes = self.pixels.iter().flat_map(|p| [encode(p.x), encode(p.y), encode(p.z)]).collect();
        crate::plot::RgbImage::from_raw(self.width, self.height, bytes).expect("width × height × 3 bytes")
    }

    /// The [`color::luminance`] of every pixel, in pixel order.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// let image = hw3::render::Image { width: 2, height: 1, pixels: vec![DVec3::ONE, DVec3::X] };
    /// assert_eq!(image.luminance(), vec![hw3::render::color::luminance(DVec3::ONE), 0.2126]);
    /// ```
    #[must_use]
    pub fn luminance(&self) -> Vec<f64> {
        self.pixels.iter().map(|&p| color::luminance(p)).collect()
    }

    /// Mean absolute luminance difference to `other` (same size), the image-change measure of Q1.
    ///
    /// # Panics
    /// If the sizes differ (a programming error: both renders use one [`Settings`]).
    #[must_use]
    pub fn mean_abs_difference(&self, other: &Image) -> f64 {
        assert_eq!((self.width, self.height), (other.width, other.height), "images of one experiment share a size");
        let (a, b) = (self.luminance(), other.luminance());
        a.iter().zip(&b).map(|(x, y)| (x - y).abs()).sum::<f64>() / a.len() as f64
    }

    /// Root-mean-square luminance difference to `other` (same size).
    ///
    /// # Panics
    /// If the sizes differ.
    #[must_use]
    pub fn rms_difference(&self, other: &Image) -> f64 {
        assert_eq!((self.width, self.height), (other.width, other.height));
        let (a, b) = (self.luminance(), other.luminance());
        (a.iter().zip(&b).map(|(x, y)| (x - y).powi(2)).sum::<f64>() / a.len() as f64).sqrt()
    }

    /// A coarse `columns × rows` grid of block-mean luminances printed with two decimals: a
    /// snapshot of a render that survives last-bit differences between platforms' `exp`/`powf`.
    #[must_use]
    pub fn thumbnail_text(&self, columns: u32, rows: u32) -> String {
        let luminance = self.luminance();
        let mut text = String::new();
        for row in 0..rows {
            let line: Vec<String> = (0..columns)
                .map(|column| {
                    let xs = (column * self.width / columns)..((column + 1) * self.width / columns);
                    let ys = (row * self.height / rows)..((row + 1) * self.height / rows);
                    let count = (xs.len() * ys.len()).max(1) as f64;
                    let sum: f64 = ys
                        .flat_map(|y| xs.clone().map(move |x| (x, y)))
                        .map(|(x, y)| luminance[(y * self.width + x) as usize])
                        .sum();
                    format!("{:.2}", sum / count)
                })
                .collect();
            text.push_str(&line.join(" "));
            text.push('\n');
        }
        text
    }
}

/// Checks the image size, sample count and caustic photon count against the limits.
///
/// # Errors
/// [`RenderError::ImageSize`], [`RenderError::SamplesPerPixel`] or [`RenderError::Caustics`].
pub fn check_settings(settings: &Settings) -> Result<(), RenderError> {
    let (width, height) = (settings.width, settings.height);
    let pixels = u64::from(width) * u64::from(height);
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE || pixels > MAX_PIXELS {
        return Err(RenderError::ImageSize { width, height });
    }
    if settings.spp == 0 || settings.spp > MAX_SPP {
        return Err(RenderError::SamplesPerPixel(settings.spp));
    }
    let photons = settings.caustics.photons;
    if photons == 0 || photons > photon::MAX_PHOTONS {
        return Err(RenderError::Caustics(photon::PhotonError::PhotonCount(photons)));
    }
    Ok(())
}

/// Renders `scene` in parallel (rayon, one task per row). Each pixel draws from its own random
/// streams seeded by `settings.seed` and its index, so the result is bit-identical for any
/// thread count. `progress` is called with the number of finished rows after each row.
///
/// With [`passes::Pass::Caustics`] on and Whitted tracing, a caustic photon map
/// ([`photon::trace_caustic_photons`], seed `settings.seed`) is traced first, once, and read at
/// every diffuse or glossy hit.
///
/// # Errors
/// [`RenderError`] when the settings are out of range (nothing is rendered).
///
/// # Examples
/// ```
/// use hw3::render::{analysis::analyze, render, catalogue, Settings};
/// let scene = catalogue::mirror_spheres(true).unwrap();
/// let settings = Settings::whitted(16, 12, 1, analyze(&scene).plan);
/// let image = render(&scene, &settings, &|_| {}).unwrap();
/// assert_eq!(image.pixels.len(), 16 * 12);
/// assert!(render(&scene, &Settings { width: 0, ..settings }, &|_| {}).is_err());
/// ```
pub fn render(scene: &Scene, settings: &Settings, progress: &(dyn Fn(u32) + Sync)) -> Result<Image, RenderError> {
    check_settings(settings)?;
    let caustic_map = match settings.integrator {
        Integrator::Whitted { .. } if settings.passes.caustics => {
            Some(photon::trace_caustic_photons(scene, settings.caustics.photons, settings.seed)?)
        }
        Integrator::Whitted { .. } | Integrator::PathTracer { .. } | Integrator::PathTracerWithRoulette { .. } => None,
    };
    let tracer = match &caustic_map {
        Some(map) => Tracer::new(scene, settings.passes).with_caustics(map, settings.caustics.gather),
        None => Tracer::new(scene, settings.passes),
    };
    render_with(&tracer, settings, progress)
}

/// Renders [`Tracer::scene`] with `tracer` as given (its passes, photon maps and options; the
/// passes of `settings` only decide time sampling, its caustic settings are unused), by
/// [`render`]'s pixel loop: the same streams, so the same bytes for any thread count.
///
/// # Errors
/// As [`render`].
///
/// # Examples
/// ```
/// use hw3::render::{Settings, analysis::analyze, catalogue, integrator::Tracer, passes::Pass, render, render_with};
/// let scene = catalogue::mirror_spheres(true).unwrap();
/// // Without the caustic pass, `render` builds exactly this tracer.
/// let settings = Settings::whitted(16, 12, 1, analyze(&scene).plan.with(Pass::Caustics, false));
/// let tracer = Tracer::new(&scene, settings.passes);
/// assert_eq!(render_with(&tracer, &settings, &|_| {}).unwrap(), render(&scene, &settings, &|_| {}).unwrap());
/// ```
pub fn render_with(
    tracer: &Tracer,
    settings: &Settings,
    progress: &(dyn Fn(u32) + Sync),
) -> Result<Image, RenderError> {
    check_settings(settings)?;
    let scene = tracer.scene();
    let frame = CameraFrame::new(scene.camera());
    let (open, close) = scene.camera().shutter;
    let (width, height) = (settings.width, settings.height);
    let aspect = f64::from(width) / f64::from(height);
    let rows_done = std::sync::atomic::AtomicU32::new(0);
    let rows: Vec<Vec<DVec3>> = (0..height)
        .into_par_iter()
        .map(|y| {
            let row = (0..width)
                .map(|x| {
                    let pixel = u64::from(y) * u64::from(width) + u64::from(x);
                    let mut sampler = Sampler::new(settings.seed, pixel, 0);
                    let mut clock = Sampler::new(settings.seed, pixel, 1);
                    let mut sum = DVec3::ZERO;
                    for _ in 0..settings.spp {
                        let u = (f64::from(x) + sampler.uniform()) / f64::from(width);
                        let v = (f64::from(y) + sampler.uniform()) / f64::from(height);
                        let time =
                            if settings.passes.time_sampling { open + (close - open) * clock.uniform() } else { open };
                        let ray = frame.ray(u, v, aspect);
                        sum += tracer.radiance(settings.integrator, &ray, time, &mut sampler);
                    }
                    sum / f64::from(settings.spp)
                })
                .collect();
            let done = rows_done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(done);
            row
        })
        .collect();
    Ok(Image { width, height, pixels: rows.into_iter().flatten().collect() })
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::{analysis::analyze, passes::Pass};

    fn small(scene: &Scene, passes: Passes, spp: u32) -> Image {
        render(scene, &Settings::whitted(48, 36, spp, passes), &|_| {}).unwrap()
    }

    fn in_pool(threads: usize, f: impl FnOnce() -> Image + Send) -> Image {
        rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(f)
    }

    #[test]
    fn image_bytes_are_identical_for_one_and_two_threads() {
        for scene in [
            catalogue::moving_ball(2.0).unwrap(),
            catalogue::fog_street(0.1).unwrap(),
            catalogue::glass_ball_caustic().unwrap(),
        ] {
            let plan = analyze(&scene).plan;
            let one = in_pool(1, || small(&scene, plan, 3));
            let two = in_pool(2, || small(&scene, plan, 3));
            assert_eq!(one.to_rgb8().into_raw(), two.to_rgb8().into_raw());
            assert_eq!(one, two, "linear radiances identical too");
        }
    }

    #[test]
    fn path_tracer_is_deterministic_across_thread_counts() {
        let scene = catalogue::cornell_mirror().unwrap();
        let settings = Settings {
            integrator: Integrator::PathTracer { max_depth: 4 },
            ..Settings::whitted(24, 18, 2, analyze(&scene).plan)
        };
        let run = |threads| in_pool(threads, || render(&scene, &settings, &|_| {}).unwrap());
        assert_eq!(run(1), run(2));
    }

    /// For every scene and every pass the plan skips, forcing it on gives the same image bit for
    /// bit (Whitted, and the path tracer); for every pass the plan runs, forcing it off changes
    /// the mean luminance by more than 1 % of the image's mean.
    #[test]
    fn the_plan_skips_only_passes_that_change_nothing_and_keeps_those_that_matter() {
        let scenes = [
            catalogue::mirror_spheres(true).unwrap(),
            catalogue::mirror_spheres(false).unwrap(),
            catalogue::fog_street(0.15).unwrap(),
            catalogue::fog_street(0.0).unwrap(),
            catalogue::moving_ball(2.0).unwrap(),
            catalogue::moving_ball(0.0).unwrap(),
            catalogue::cornell_mirror().unwrap(),
            catalogue::probe_lit().unwrap(),
            catalogue::fog_panel(0.15).unwrap(),
            catalogue::fog_panel(0.0).unwrap(),
            catalogue::glass_ball_caustic().unwrap(),
        ];
        let mut skipped_checked = 0;
        let mut needed_checked = 0;
        for scene in &scenes {
            for integrator in [Integrator::Whitted { max_depth: 8 }, Integrator::PathTracer { max_depth: 3 }] {
                let plan = integrator.restrict(analyze(scene).plan);
                let run = |passes| {
                    let settings = Settings { integrator, ..Settings::whitted(32, 24, 2, passes) };
                    render(scene, &settings, &|_| {}).unwrap()
                };
                let planned = run(plan);
                let mean = planned.luminance().iter().sum::<f64>() / planned.pixels.len() as f64;
                for pass in Pass::ALL {
                    if plan.get(pass) {
                        let without = run(plan.with(pass, false));
                        let change = planned.mean_abs_difference(&without);
                        assert!(
                            change > 0.01 * mean,
                            "{pass:?} is planned but removing it changes only {change:e} (mean {mean:e})"
                        );
                        needed_checked += 1;
                    } else {
                        assert_eq!(run(plan.with(pass, true)), planned, "{pass:?} forced on");
                        skipped_checked += 1;
                    }
                }
            }
        }
        assert!(skipped_checked >= 30 && needed_checked >= 8);
    }

    /// Mean floor radiance of the `caustic` scene over `points` (rays straight down from 0.01
    /// above the floor), `samples` per point, by `tracer` with `integrator`; and its standard
    /// error over the points × samples estimates.
    fn footprint_radiance(tracer: &Tracer, integrator: Integrator, points: &[DVec3], samples: u64) -> (f64, f64) {
        let values: Vec<f64> = points
            .iter()
            .enumerate()
            .flat_map(|(i, &p)| {
                let mut sampler = Sampler::new(7, i as u64, 0);
                let ray = crate::geometry::Ray { origin: p + DVec3::Y * 0.01, dir: DVec3::NEG_Y };
                (0..samples).map(move |_| tracer.radiance(integrator, &ray, 0.0, &mut sampler).x).collect::<Vec<_>>()
            })
            .collect();
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, (variance / n).sqrt())
    }

    /// The caustic pass on the `caustic` scene, measured on the floor under the glass ball (mean
    /// radiance over [`catalogue::caustic_footprint`], rays straight down):
    /// - without the pass Whitted tracing leaves the footprint exactly black (its shadow rays to
    ///   the light are blocked by the glass), with it the footprint is more than 10× as bright
    ///   as the open floor beside the ball (12.8× with seed 1);
    /// - the path tracer (256 paths per point, depth 8; it finds the caustic by bouncing off the
    ///   floor through the ball into the light) agrees with Whitted + caustic map within 4 of its
    ///   standard errors;
    /// - the k-nearest estimate blurs the spot but keeps its flux: averaged over the disc it is
    ///   within 2 % of the photons' own histogram, the stored power inside the disc over its
    ///   area (no blur at all; the 2 % is light moved across the disc's rim by the 0.1 gather).
    #[test]
    fn the_caustic_pass_lights_the_shadow_under_the_glass_ball_as_the_path_tracer_does() {
        let scene = catalogue::glass_ball_caustic().unwrap();
        let plan = analyze(&scene).plan;
        assert!(plan.caustics);
        let map = photon::trace_caustic_photons(&scene, photon::CAUSTIC_PHOTONS, 1).unwrap();
        let with = Tracer::new(&scene, plan).with_caustics(&map, photon::CAUSTIC_GATHER);
        let without = Tracer::new(&scene, plan.with(passes::Pass::Caustics, false));
        let reference = Tracer::new(&scene, plan.with(passes::Pass::IndirectBounces, true));
        let whitted = Integrator::Whitted { max_depth: 8 };
        let (center, radius, points) = catalogue::caustic_footprint(400);
        let (lit, _) = footprint_radiance(&with, whitted, &points, 1);
        let (dark, _) = footprint_radiance(&without, whitted, &points, 1);
        let (path, standard_error) =
            footprint_radiance(&reference, Integrator::PathTracer { max_depth: 8 }, &points, 256);
        let open_points: Vec<DVec3> = points.iter().map(|p| *p + DVec3::new(0.0, 0.0, 3.0)).collect();
        let (open_floor, _) = footprint_radiance(&without, whitted, &open_points, 4);
        let inside: f64 =
            map.photons().iter().filter(|p| (p.position - center).length() < radius).map(|p| p.power.x).sum();
        let histogram = 0.7 / std::f64::consts::PI * inside / (std::f64::consts::PI * radius * radius);
        assert_eq!(dark, 0.0, "Whitted without the pass: the glass casts a black shadow");
        assert!(lit > 10.0 * open_floor, "caustic {lit} vs open floor {open_floor}");
        assert!(
            (lit - path).abs() < 4.0 * standard_error,
            "Whitted + caustics {lit}, path tracer {path} ± {standard_error}"
        );
        assert!((lit / histogram - 1.0).abs() < 0.02, "kNN {lit} vs histogram {histogram}");
    }

    /// Every built-in scene renders to the same linear radiances with the kd-tree and with the
    /// brute-force loop, for both integrators (so every closest-hit and shadow query agreed).
    #[test]
    fn kd_tree_renders_are_identical_to_brute_force_on_every_built_in_scene() {
        for (name, _) in catalogue::CATALOGUE {
            let scene = catalogue::by_name(name).unwrap();
            let brute = scene.without_kd_tree();
            assert_eq!(brute.kd_tree_spheres(), 0);
            for integrator in [Integrator::Whitted { max_depth: 8 }, Integrator::PathTracer { max_depth: 3 }] {
                let plan = integrator.restrict(analyze(&scene).plan);
                let settings = Settings { integrator, ..Settings::whitted(24, 18, 2, plan) };
                let fast = render(&scene, &settings, &|_| {}).unwrap();
                let slow = render(&brute, &settings, &|_| {}).unwrap();
                assert_eq!(fast, slow, "{name} with {integrator:?}");
            }
        }
    }

    #[test]
    fn bad_sizes_and_sample_counts_are_refused() {
        let scene = catalogue::moving_ball(0.0).unwrap();
        let plan = analyze(&scene).plan;
        for (w, h) in [(0, 10), (10, 0), (MAX_SIDE + 1, 1), (5000, 5000)] {
            assert_eq!(
                render(&scene, &Settings::whitted(w, h, 1, plan), &|_| {}),
                Err(RenderError::ImageSize { width: w, height: h })
            );
        }
        for spp in [0, MAX_SPP + 1] {
            assert_eq!(
                render(&scene, &Settings::whitted(4, 4, spp, plan), &|_| {}),
                Err(RenderError::SamplesPerPixel(spp))
            );
        }
    }

    /// A point light inside a closed sphere lights nothing outside it, and a camera inside a
    /// mirror sphere sees a finite, black image (light cannot get in; recursion stops at depth 8).
    #[test]
    fn enclosed_lights_and_cameras_stay_dark_and_finite() {
        use crate::geometry::Sphere;
        use camera::Camera;
        use scene::{Material, Object, PointLight};
        let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 40.0);
        let shell = |material| Object::sphere(Sphere::new(DVec3::ZERO, 1.0).unwrap(), material);
        let lamp = PointLight { position: DVec3::ZERO, intensity: DVec3::splat(100.0) };
        let diffuse = Material::Diffuse { albedo: DVec3::splat(0.8) };
        let enclosed = Scene::new(camera, vec![shell(diffuse)], vec![lamp], None, DVec3::ZERO).unwrap();
        let outside = small(&enclosed, analyze(&enclosed).plan, 1);
        assert!(outside.pixels.iter().all(|p| *p == DVec3::ZERO));
        let mirror = Material::Mirror { reflectance: DVec3::splat(0.9) };
        let inside_camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.5), DVec3::ZERO, 40.0);
        let outside_lamp = PointLight { position: DVec3::new(0.0, 5.0, 0.0), ..lamp };
        let trapped = Scene::new(inside_camera, vec![shell(mirror)], vec![outside_lamp], None, DVec3::ONE).unwrap();
        let image = small(&trapped, analyze(&trapped).plan, 1);
        assert!(image.pixels.iter().all(|p| *p == DVec3::ZERO));
    }

    #[test]
    fn thumbnail_averages_blocks() {
        let image = Image {
            width: 4,
            height: 2,
            pixels: vec![
                DVec3::ONE,
                DVec3::ONE,
                DVec3::ZERO,
                DVec3::ZERO,
                DVec3::ONE,
                DVec3::ONE,
                DVec3::ZERO,
                DVec3::ZERO,
            ],
        };
        assert_eq!(image.thumbnail_text(2, 1), "1.00 0.00\n");
    }
}
