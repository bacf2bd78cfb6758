//! A small physically based renderer: pinhole camera with a shutter, spheres and quads, diffuse,
//! glossy, mirror and glass materials, point, area and environment lights, homogeneous fog;
//! Whitted ray tracing and a path tracer; photon maps; and a plan of passes derived from the light
//! paths a scene can carry ([`analysis`], [`passes`]). Every input is validated, and an image's
//! bytes are the same whatever the number of threads.
//!
//! How it renders each effect the homework asks about is the renderer chapter of the course notes
//! (`hw3::render`); how it is built and measured, the renderer's engineering notes.

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
    pub fn to_rgb8(&self) -> hw3_core::plot::RgbImage {
        let encode = |c: f64| {
            let c = c.clamp(0.0, 1.0);
            let s = if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
            (s * 255.0).round() as u8
        };
        let bytes = self.pixels.iter().flat_map(|p| [encode(p.x), encode(p.y), encode(p.z)]).collect();
        hw3_core::plot::RgbImage::from_raw(self.width, self.height, bytes).expect("width × height × 3 bytes")
    }

    /// The [`color::luminance`] of every pixel, in pixel order.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// let image = hw3_render::render::Image { width: 2, height: 1, pixels: vec![DVec3::ONE, DVec3::X] };
    /// assert_eq!(image.luminance(), vec![hw3_render::render::color::luminance(DVec3::ONE), 0.2126]);
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
/// use hw3_render::render::{analysis::analyze, render, catalogue, Settings};
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
/// use hw3_render::render::{Settings, analysis::analyze, catalogue, integrator::Tracer, passes::Pass, render, render_with};
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
mod tests;
