//! A light probe: an image in one [`ProbeFormat`], the direction and solid angle of every texel,
//! and the radiance it recorded.

use super::format::{GaussLegendre, ProbeFormat, Rect};
use glam::{DMat3, DVec2, DVec3};
use hw3_core::geometry::InputError;
use std::path::Path;

/// Why a probe could not be built or read.
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3_render::envmap::{Probe, ProbeError, ProbeFormat};
/// let empty = Probe::from_fn(ProbeFormat::MirrorBall, 0, 8, DMat3::IDENTITY, |_| DVec3::ONE);
/// assert!(matches!(empty, Err(ProbeError::Empty { width: 0, height: 8 })));
/// assert!(matches!(Probe::read_lat_long("missing.hdr"), Err(ProbeError::Read { .. })));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum ProbeError {
    /// An argument is invalid (a non-finite normal, a bad `D/R`, …).
    #[error(transparent)]
    Input(#[from] InputError),
    /// A probe needs at least one texel.
    #[error("probe size must be at least 1×1, got {width}×{height}")]
    Empty {
        /// Requested width.
        width: usize,
        /// Requested height.
        height: usize,
    },
    /// A texel holds a NaN, an infinity or a negative radiance.
    #[error("texel ({column}, {row}) has radiance {value}: every channel must be finite and ≥ 0")]
    BadTexel {
        /// Column of the texel.
        column: usize,
        /// Row of the texel (0 = top).
        row: usize,
        /// The offending radiance, as printed.
        value: String,
    },
    /// The radiance buffer does not have `width × height` entries.
    #[error("expected {expected} texels, got {got}")]
    WrongLength {
        /// `width × height`.
        expected: usize,
        /// The buffer's length.
        got: usize,
    },
    /// A textual description of a map (the CLI's `--env`) is not understood.
    #[error("--env: {0}")]
    Spec(String),
    /// An image file declares more texels in its header than the reader accepts
    /// ([`Probe::MAX_READ_TEXELS`] for [`Probe::read_lat_long`]); nothing was decoded.
    #[error("{path} declares {width}×{height} texels, over the limit of {max_texels}")]
    TooLarge {
        /// The file.
        path: String,
        /// Width its header declares.
        width: u32,
        /// Height its header declares.
        height: u32,
        /// The limit it exceeds.
        max_texels: u64,
    },
    /// An image file could not be read or decoded.
    #[error("cannot read {path}: {message}")]
    Read {
        /// The file.
        path: String,
        /// The decoder's message.
        message: String,
    },
}

/// One texel: where it looks, how much of the sphere it covers, and what it saw.
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3_render::envmap::{Probe, ProbeFormat};
/// let probe = Probe::from_fn(ProbeFormat::LatLong, 4, 2, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
/// let texel = probe.texels()[0]; // top row: next to the zenith
/// assert!(texel.direction.z > 0.5 && texel.centre_inside && texel.radiance == DVec3::ONE);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Texel {
    /// Unit direction (world frame): the solid-angle-weighted mean over the texel's footprint.
    pub direction: DVec3,
    /// Solid angle `Δω` in steradians (0 for texels wholly outside the image disk).
    pub solid_angle: f64,
    /// Image area of the texel inside the format's domain (for sampling within the texel).
    pub area: f64,
    /// Whether the texel's centre lies inside the domain (what a mask drawn on a photo keeps).
    pub centre_inside: bool,
    /// Recorded radiance (RGB), the average over the texel's solid angle.
    pub radiance: DVec3,
}

/// A light probe image with per-texel geometry.
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3_render::envmap::{Probe, ProbeFormat};
/// let sky = |w: DVec3| DVec3::splat(if w.z > 0.0 { 1.0 } else { 0.0 });
/// let probe = Probe::from_fn(ProbeFormat::LatLong, 16, 8, DMat3::IDENTITY, sky).unwrap();
/// assert_eq!((probe.width(), probe.height(), probe.format()), (16, 8, ProbeFormat::LatLong));
/// let up = probe.texel_index_toward(DVec3::Z).unwrap();
/// assert_eq!(probe.radiance_toward(DVec3::Z), probe.texels()[up].radiance);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Probe {
    format: ProbeFormat,
    width: usize,
    height: usize,
    world_from_probe: DMat3,
    texels: Vec<Texel>,
}

/// Subsamples per texel side used to find texel directions and to rasterise smooth maps.
const SUBSAMPLES: usize = 4;

/// Rotation that puts a ball's camera on the `+x` horizon with the image's up along world `+z`:
/// probe `x` (image right) → world `+y`, probe `y` (image up) → world `+z`, probe `z` (toward the
/// camera) → world `+x`. Lat-long images use the identity (`+z` up already).
///
/// # Examples
/// ```
/// use glam::DVec3;
/// let m = hw3_render::envmap::horizontal_camera();
/// assert_eq!(m * DVec3::Z, DVec3::X); // the camera sits on the +x horizon
/// assert_eq!(m * DVec3::Y, DVec3::Z); // image up is world up
/// ```
#[must_use]
pub fn horizontal_camera() -> DMat3 {
    DMat3::from_cols(DVec3::Y, DVec3::Z, DVec3::X)
}

impl Probe {
    /// Texels [`Probe::read_lat_long`] and [`Probe::decode_lat_long`] accept: 2²⁴ (8192 × 2048, the
    /// largest map `hw3 irradiance --allow-large` reads), checked against the file's header before
    /// any pixel is decoded. Decoding holds about 112 bytes a texel at its peak (4 of RGBE, 12 of
    /// `f32` RGB, 24 of `f64` radiance, 72 of [`Texel`]), so the bound caps one read at about 1.9 GB;
    /// [`Probe::read_lat_long_limited`] takes a smaller bound.
    pub const MAX_READ_TEXELS: u64 = 1 << 24;

    /// A probe whose texels sample `radiance(ω)` (world direction → RGB radiance), each texel the
    /// solid-angle-weighted mean of a 4×4 grid of subsamples inside the domain.
    ///
    /// `world_from_probe` must be a rotation (see [`horizontal_camera`]).
    ///
    /// # Errors
    /// [`ProbeError::Empty`] for a zero size; [`ProbeError::BadTexel`] if `radiance` returns a
    /// non-finite or negative value anywhere it is sampled.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// let probe = Probe::from_fn(ProbeFormat::MirrorBall, 8, 8, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
    /// let total: f64 = probe.texels().iter().map(|t| t.solid_angle).sum();
    /// assert!((total - 4.0 * std::f64::consts::PI).abs() < 1e-12);
    /// ```
    pub fn from_fn(
        format: ProbeFormat,
        width: usize,
        height: usize,
        world_from_probe: DMat3,
        radiance: impl Fn(DVec3) -> DVec3,
    ) -> Result<Self, ProbeError> {
        if width == 0 || height == 0 {
            return Err(ProbeError::Empty { width, height });
        }
        let rule = GaussLegendre::new(16);
        let mut texels = Vec::with_capacity(width * height);
        let checked = |world: DVec3, column: usize, row: usize| {
            let value = radiance(world);
            if value.is_finite() && value.min_element() >= 0.0 {
                Ok(value)
            } else {
                Err(ProbeError::BadTexel { column, row, value: format!("{value}") })
            }
        };
        for row in 0..height {
            for column in 0..width {
                let rect = texel_rect(format, width, height, column, row);
                let solid_angle = format.solid_angle(rect, &rule);
                let area = format.area_inside(rect);
                let centre = 0.5 * (rect.min + rect.max);
                let mut direction_sum = DVec3::ZERO;
                let mut radiance_sum = DVec3::ZERO;
                let mut weight_sum = 0.0;
                let step = (rect.max - rect.min) / SUBSAMPLES as f64;
                for b in 0..SUBSAMPLES {
                    for a in 0..SUBSAMPLES {
                        let p = rect.min + step * DVec2::new(a as f64 + 0.5, b as f64 + 0.5);
                        if let Some(omega) = format.image_to_direction(p) {
                            let world = world_from_probe * omega;
                            let weight = format.jacobian(p);
                            direction_sum += world * weight;
                            radiance_sum += checked(world, column, row)? * weight;
                            weight_sum += weight;
                        }
                    }
                }
                let (direction, value) = if weight_sum > 0.0 {
                    (direction_sum.normalize(), radiance_sum / weight_sum)
                } else {
                    // A rim sliver that no subsample hits: use the rim point nearest its centre.
                    let rim = if centre.length() > 0.0 { centre.normalize() * (1.0 - 1e-12) } else { centre };
                    let world = world_from_probe * format.image_to_direction(rim).unwrap_or(world_from_probe.col(2));
                    (world, checked(world, column, row)?)
                };
                texels.push(Texel {
                    direction,
                    solid_angle,
                    area,
                    centre_inside: format.image_to_direction(centre).is_some(),
                    radiance: if solid_angle > 0.0 { value } else { DVec3::ZERO },
                });
            }
        }
        let probe = Self { format, width, height, world_from_probe, texels };
        probe.validate()?;
        Ok(probe)
    }

    /// A probe holding the given radiance buffer (row-major, top row first), as read from a file.
    ///
    /// # Errors
    /// [`ProbeError::WrongLength`], [`ProbeError::Empty`], or [`ProbeError::BadTexel`] for the
    /// first NaN, infinite or negative channel.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// let bad = vec![DVec3::ONE, DVec3::new(0.0, f64::NAN, 0.0)];
    /// assert!(Probe::from_radiance(ProbeFormat::LatLong, 2, 1, DMat3::IDENTITY, bad).is_err());
    /// ```
    pub fn from_radiance(
        format: ProbeFormat,
        width: usize,
        height: usize,
        world_from_probe: DMat3,
        radiance: Vec<DVec3>,
    ) -> Result<Self, ProbeError> {
        if radiance.len() != width * height {
            return Err(ProbeError::WrongLength { expected: width * height, got: radiance.len() });
        }
        let mut probe = Self::from_fn(format, width, height, world_from_probe, |_| DVec3::ZERO)?;
        for (texel, value) in probe.texels.iter_mut().zip(radiance) {
            // Validated before masking: garbage outside the disk is still a broken file.
            texel.radiance = value;
        }
        probe.validate()?;
        for texel in &mut probe.texels {
            if texel.solid_angle == 0.0 {
                texel.radiance = DVec3::ZERO;
            }
        }
        Ok(probe)
    }

    /// A probe in `format` synthesised from a lat-long `source` by splatting: each source texel
    /// sends its power `L Δω` as 4×4 stratified points (uniform in solid angle over the texel) to
    /// the texels that see them, so energy is conserved whatever the two resolutions (a sun
    /// smaller than a texel is neither lost nor duplicated). Points in a blind cone are lost, as in
    /// a photograph.
    ///
    /// # Errors
    /// [`InputError::OutOfRange`] if `source` is not lat-long; [`ProbeError::Empty`] for size 0.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{horizontal_camera, Probe, ProbeFormat};
    /// let sky = Probe::from_fn(ProbeFormat::LatLong, 16, 8, DMat3::IDENTITY, |w| DVec3::splat(w.z.max(0.0))).unwrap();
    /// let ball = Probe::resample_lat_long(&sky, ProbeFormat::MirrorBall, 16, horizontal_camera()).unwrap();
    /// let power = |p: &Probe| p.texels().iter().map(|t| t.radiance.x * t.solid_angle).sum::<f64>();
    /// assert!((power(&ball) / power(&sky) - 1.0).abs() < 1e-12);
    /// ```
    pub fn resample_lat_long(
        source: &Probe,
        format: ProbeFormat,
        size: usize,
        world_from_probe: DMat3,
    ) -> Result<Self, ProbeError> {
        if source.format != ProbeFormat::LatLong {
            return Err(InputError::OutOfRange {
                name: "source format",
                value: source.format.name(),
                expected: "lat-long",
            }
            .into());
        }
        let mut probe = Self::from_fn(format, size, size, world_from_probe, |_| DVec3::ZERO)?;
        const STRATA: usize = 4;
        for (index, texel) in source.texels.iter().enumerate() {
            if texel.solid_angle <= 0.0 || texel.radiance == DVec3::ZERO {
                continue;
            }
            let rect = source.texel_rect(index);
            let power = texel.radiance * (texel.solid_angle / (STRATA * STRATA) as f64);
            let (z0, z1) = ((std::f64::consts::PI * rect.min.y).cos(), (std::f64::consts::PI * rect.max.y).cos());
            for a in 0..STRATA {
                for b in 0..STRATA {
                    let u = rect.min.x + (rect.max.x - rect.min.x) * (a as f64 + 0.5) / STRATA as f64;
                    let z = z0 + (z1 - z0) * (b as f64 + 0.5) / STRATA as f64;
                    let s = (1.0 - z * z).max(0.0).sqrt();
                    let (sin_p, cos_p) = (std::f64::consts::TAU * u).sin_cos();
                    let omega = source.world_from_probe * DVec3::new(s * cos_p, s * sin_p, z);
                    if let Some(target) = probe.texel_index_toward(omega) {
                        let t = &mut probe.texels[target];
                        t.radiance += power / t.solid_angle;
                    }
                }
            }
        }
        probe.validate()?;
        Ok(probe)
    }

    /// Adds a uniform spherical cap of grey radiance `radiance`, unit centre `centre` and
    /// half-angle `half_angle` (radians) by splatting `m²` stratified points, uniform in solid
    /// angle over the cap, each carrying its share `L Ω_cap / m²` of the cap's power into the
    /// texel that sees it. A cap smaller than a texel (a sun) so keeps its exact energy, which
    /// point-sampling its radiance would miss or overcount. Points in a blind cone are lost, as
    /// they are in a photograph.
    ///
    /// # Errors
    /// [`InputError::OutOfRange`] unless `radiance` is finite and ≥ 0 and `half_angle` is finite
    /// (the probe is then unchanged); [`ProbeError::BadTexel`] if a texel overflows to infinity.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// let mut probe = Probe::from_fn(ProbeFormat::MirrorBall, 16, 16, DMat3::IDENTITY, |_| DVec3::ZERO).unwrap();
    /// let half_angle = 0.01_f64; // far smaller than a texel
    /// probe.splat_cap(1.0, DVec3::X, half_angle, 16).unwrap();
    /// let power: f64 = probe.texels().iter().map(|t| t.radiance.x * t.solid_angle).sum();
    /// let cap = 2.0 * std::f64::consts::PI * (1.0 - half_angle.cos());
    /// assert!((power / cap - 1.0).abs() < 1e-9);
    /// assert!(probe.splat_cap(f64::NAN, DVec3::X, half_angle, 16).is_err());
    /// ```
    pub fn splat_cap(&mut self, radiance: f64, centre: DVec3, half_angle: f64, m: usize) -> Result<(), ProbeError> {
        if !(radiance.is_finite() && radiance >= 0.0 && half_angle.is_finite()) {
            return Err(InputError::OutOfRange {
                name: "cap",
                value: format!("radiance {radiance}, half-angle {half_angle}"),
                expected: "finite, radiance ≥ 0",
            }
            .into());
        }
        let cap_solid_angle = std::f64::consts::TAU * 2.0 * (0.5 * half_angle).sin().powi(2);
        let power = radiance * cap_solid_angle / (m * m) as f64;
        let (t1, t2) = centre.any_orthonormal_pair();
        let one_minus_cos = 1.0 - half_angle.cos();
        for a in 0..m {
            for b in 0..m {
                // Stratified, uniform in solid angle over the cap.
                let z = 1.0 - (a as f64 + 0.5) / m as f64 * one_minus_cos;
                let phi = std::f64::consts::TAU * (b as f64 + 0.5) / m as f64;
                let s = (1.0 - z * z).max(0.0).sqrt();
                let omega = centre * z + t1 * (s * phi.cos()) + t2 * (s * phi.sin());
                if let Some(index) = self.texel_index_toward(omega) {
                    let texel = &mut self.texels[index];
                    texel.radiance += DVec3::splat(power / texel.solid_angle);
                }
            }
        }
        self.validate()
    }

    fn validate(&self) -> Result<(), ProbeError> {
        for (index, texel) in self.texels.iter().enumerate() {
            let v = texel.radiance;
            if !(v.is_finite() && v.min_element() >= 0.0) {
                return Err(ProbeError::BadTexel {
                    column: index % self.width,
                    row: index / self.width,
                    value: format!("{v}"),
                });
            }
        }
        Ok(())
    }

    /// Reads a latitude-longitude Radiance `.hdr` file (top row = `+z`, the zenith) of at most
    /// [`Probe::MAX_READ_TEXELS`] texels. The file is read as Radiance whatever its name or content (a
    /// PNG renamed `.hdr` is refused, not decoded as a PNG).
    ///
    /// # Errors
    /// [`ProbeError::TooLarge`] if the header declares more than [`Probe::MAX_READ_TEXELS`] texels
    /// (checked before decoding); [`ProbeError::Read`] if the file is missing, truncated or not a
    /// Radiance image; [`ProbeError::BadTexel`] for negative or non-finite texels.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::envmap::Probe;
    /// assert!(Probe::read_lat_long("no/such/file.hdr").is_err());
    /// ```
    pub fn read_lat_long(path: impl AsRef<Path>) -> Result<Self, ProbeError> {
        Self::read_lat_long_limited(path, Self::MAX_READ_TEXELS)
    }

    /// [`Probe::read_lat_long`] with a bound of `max_texels` texels instead of
    /// [`Probe::MAX_READ_TEXELS`] (for a caller that wants less memory at stake; a larger bound is
    /// allowed, at about 112 bytes a texel).
    ///
    /// # Errors
    /// As [`Probe::read_lat_long`], with [`ProbeError::TooLarge`] above `max_texels`.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::envmap::{Probe, ProbeError};
    /// let map = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/data/q4/courtyard_256x128.hdr");
    /// assert_eq!(Probe::read_lat_long_limited(map, 256 * 128).unwrap().width(), 256);
    /// let refused = Probe::read_lat_long_limited(map, 1000);
    /// assert!(matches!(refused, Err(ProbeError::TooLarge { width: 256, height: 128, max_texels: 1000, .. })));
    /// ```
    pub fn read_lat_long_limited(path: impl AsRef<Path>, max_texels: u64) -> Result<Self, ProbeError> {
        let path = path.as_ref();
        let name = path.display().to_string();
        let file =
            std::fs::File::open(path).map_err(|e| ProbeError::Read { path: name.clone(), message: e.to_string() })?;
        Self::decode_bounded(std::io::BufReader::new(file), &name, max_texels)
    }

    /// Decodes a latitude-longitude Radiance `.hdr` image held in memory (top row = `+z`), such
    /// as a [`super::BuiltinMap`]'s bytes, of at most [`Probe::MAX_READ_TEXELS`] texels; `name` stands
    /// for the file in error messages.
    ///
    /// # Errors
    /// [`ProbeError::TooLarge`] above [`Probe::MAX_READ_TEXELS`]; [`ProbeError::Read`] if `bytes` are
    /// not a decodable `.hdr` image; [`ProbeError::BadTexel`] for negative or non-finite texels.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::envmap::{BuiltinMap, Probe, ProbeError};
    /// let probe = Probe::decode_lat_long(BuiltinMap::Courtyard.hdr_bytes(), "courtyard").unwrap();
    /// assert_eq!((probe.width(), probe.height()), (256, 128));
    /// let broken = Probe::decode_lat_long(b"#?RADIANCE\n", "broken");
    /// assert!(matches!(broken, Err(ProbeError::Read { .. })));
    /// ```
    pub fn decode_lat_long(bytes: &[u8], name: &str) -> Result<Self, ProbeError> {
        Self::decode_bounded(bytes, name, Self::MAX_READ_TEXELS)
    }

    /// Reads the header, refuses more than `max_texels`, then decodes.
    fn decode_bounded<R: std::io::BufRead>(mut reader: R, name: &str, max_texels: u64) -> Result<Self, ProbeError> {
        let read_error =
            |e: super::radiance::RadianceError| ProbeError::Read { path: name.to_string(), message: e.to_string() };
        let (width, height) = super::radiance::read_header(&mut reader).map_err(read_error)?;
        if u64::from(width) * u64::from(height) > max_texels {
            return Err(ProbeError::TooLarge { path: name.to_string(), width, height, max_texels });
        }
        let rgb = super::radiance::read_pixels(&mut reader, width, height).map_err(read_error)?;
        let radiance = rgb.iter().map(|&[r, g, b]| DVec3::new(r.into(), g.into(), b.into())).collect();
        Self::from_radiance(ProbeFormat::LatLong, width as usize, height as usize, DMat3::IDENTITY, radiance)
    }

    /// The image format.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// let probe = Probe::from_fn(ProbeFormat::AngularMap, 4, 4, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
    /// assert_eq!(probe.format(), ProbeFormat::AngularMap);
    /// ```
    #[must_use]
    pub fn format(&self) -> ProbeFormat {
        self.format
    }

    /// Width in texels.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// let probe = Probe::from_fn(ProbeFormat::LatLong, 6, 3, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
    /// assert_eq!(probe.width(), 6);
    /// ```
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in texels.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// let probe = Probe::from_fn(ProbeFormat::LatLong, 6, 3, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
    /// assert_eq!(probe.height(), 3);
    /// ```
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// Every texel, row-major from the top row.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// let probe = Probe::from_fn(ProbeFormat::MirrorBall, 8, 8, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
    /// assert_eq!(probe.texels().len(), 64);
    /// // The corners of a disk image see nothing.
    /// assert_eq!(probe.texels()[0].solid_angle, 0.0);
    /// ```
    #[must_use]
    pub fn texels(&self) -> &[Texel] {
        &self.texels
    }

    /// The index of the texel that sees world direction `omega` (unit), `None` in a blind cone.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// let ball = ProbeFormat::perspective_ball(3.0).unwrap();
    /// let probe = Probe::from_fn(ball, 8, 8, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
    /// assert!(probe.texel_index_toward(DVec3::Z).is_some()); // the direction back to the camera
    /// assert_eq!(probe.texel_index_toward(-DVec3::Z), None); // straight behind the ball: blind
    /// ```
    #[must_use]
    pub fn texel_index_toward(&self, omega: DVec3) -> Option<usize> {
        let local = self.world_from_probe.transpose() * omega;
        let p = self.format.direction_to_image(local)?;
        let index = self.texel_index_at(p);
        (self.texels[index].solid_angle > 0.0).then_some(index)
    }

    /// The texel containing image point `p` (clamped to the image).
    pub(crate) fn texel_index_at(&self, p: DVec2) -> usize {
        let rect = self.format.image_rect();
        let unit = (p - rect.min) / (rect.max - rect.min);
        let column = ((unit.x * self.width as f64) as usize).min(self.width - 1);
        let from_top = if self.format == ProbeFormat::LatLong { unit.y } else { 1.0 - unit.y };
        let row = ((from_top * self.height as f64).max(0.0) as usize).min(self.height - 1);
        row * self.width + column
    }

    /// The image rectangle of texel `index`.
    #[must_use]
    pub fn texel_rect(&self, index: usize) -> Rect {
        texel_rect(self.format, self.width, self.height, index % self.width, index / self.width)
    }

    /// World direction of image point `p` and the Jacobian there, `None` outside the domain.
    #[must_use]
    pub fn image_to_world(&self, p: DVec2) -> Option<(DVec3, f64)> {
        let local = self.format.image_to_direction(p)?;
        Some((self.world_from_probe * local, self.format.jacobian(p)))
    }

    /// World to image: the image point seeing `omega`, `None` in a blind cone.
    #[must_use]
    pub fn world_to_image(&self, omega: DVec3) -> Option<DVec2> {
        self.format.direction_to_image(self.world_from_probe.transpose() * omega)
    }

    /// The piecewise-constant radiance the probe records toward `omega` (zero in a blind cone).
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// let ball = ProbeFormat::perspective_ball(3.0).unwrap();
    /// let probe = Probe::from_fn(ball, 8, 8, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
    /// assert_eq!(probe.radiance_toward(DVec3::X), DVec3::ONE);
    /// assert_eq!(probe.radiance_toward(-DVec3::Z), DVec3::ZERO); // blind cone
    /// ```
    #[must_use]
    pub fn radiance_toward(&self, omega: DVec3) -> DVec3 {
        self.texel_index_toward(omega).map_or(DVec3::ZERO, |i| self.texels[i].radiance)
    }
}

/// The image rectangle of texel (`column`, `row`), row 0 at the top of the image.
fn texel_rect(format: ProbeFormat, width: usize, height: usize, column: usize, row: usize) -> Rect {
    let image = format.image_rect();
    let step = (image.max - image.min) / DVec2::new(width as f64, height as f64);
    let x0 = image.min.x + step.x * column as f64;
    let (y0, y1) = if format == ProbeFormat::LatLong {
        let v0 = image.min.y + step.y * row as f64;
        (v0, v0 + step.y)
    } else {
        let top = image.max.y - step.y * row as f64;
        (top - step.y, top)
    };
    Rect { min: DVec2::new(x0, y0), max: DVec2::new(x0 + step.x, y1) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn every_texel_is_found_by_its_own_direction() {
        for format in [
            ProbeFormat::MirrorBall,
            ProbeFormat::AngularMap,
            ProbeFormat::perspective_ball(4.0).unwrap(),
            ProbeFormat::LatLong,
        ] {
            let probe = Probe::from_fn(format, 16, 16, horizontal_camera(), |_| DVec3::ONE).unwrap();
            for (index, texel) in probe.texels().iter().enumerate() {
                if texel.centre_inside {
                    let rect = probe.texel_rect(index);
                    let centre = 0.5 * (rect.min + rect.max);
                    let (omega, _) = probe.image_to_world(centre).unwrap();
                    assert_eq!(probe.texel_index_toward(omega), Some(index), "{}", format.name());
                }
            }
        }
    }

    #[test]
    fn one_by_one_probe_covers_the_sphere() {
        let probe = Probe::from_fn(ProbeFormat::MirrorBall, 1, 1, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
        assert_eq!(probe.texels().len(), 1);
        assert!((probe.texels()[0].solid_angle - 4.0 * PI).abs() < 1e-12);
    }

    #[test]
    fn bad_texels_are_typed_errors() {
        for bad in [f64::NAN, f64::INFINITY, -1.0] {
            let error = Probe::from_fn(ProbeFormat::LatLong, 4, 2, DMat3::IDENTITY, |omega| {
                DVec3::splat(if omega.z > 0.9 { bad } else { 1.0 })
            })
            .unwrap_err();
            assert!(matches!(error, ProbeError::BadTexel { .. }), "{error}");
        }
        let error = Probe::from_fn(ProbeFormat::MirrorBall, 0, 3, DMat3::IDENTITY, |_| DVec3::ONE).unwrap_err();
        assert!(matches!(error, ProbeError::Empty { .. }));
        let error = Probe::from_radiance(ProbeFormat::LatLong, 2, 2, DMat3::IDENTITY, vec![DVec3::ONE]).unwrap_err();
        assert!(matches!(error, ProbeError::WrongLength { .. }));
    }

    #[test]
    fn unreadable_and_truncated_files_are_typed_errors() {
        let dir = std::env::temp_dir().join(format!("hw3-envmap-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let truncated = dir.join("truncated.hdr");
        std::fs::write(&truncated, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n\x02\x02").unwrap();
        let garbage = dir.join("garbage.hdr");
        std::fs::write(&garbage, b"not an image at all").unwrap();
        for path in [truncated.as_path(), garbage.as_path(), Path::new("/no/such.hdr")] {
            let error = Probe::read_lat_long(path).unwrap_err();
            assert!(matches!(error, ProbeError::Read { .. }), "{error}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_hdr_file_round_trips_through_the_reader() {
        let dir = std::env::temp_dir().join(format!("hw3-envmap-rt-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("map.hdr");
        let pixels: Vec<[f32; 3]> = (0..8 * 4).map(|i| [i as f32 * 0.25, 1.0, 2.0]).collect();
        std::fs::write(&path, super::super::radiance::flat_file(8, 4, &pixels)).unwrap();
        let probe = Probe::read_lat_long(&path).unwrap();
        assert_eq!((probe.width(), probe.height()), (8, 4));
        // RGBE keeps 8 mantissa bits: 1.75 and 2.0 are exact.
        assert_eq!(probe.texels()[7].radiance, DVec3::new(1.75, 1.0, 2.0));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// The size bound is read from the header: a 16-byte file declaring 2¹⁵ × 2¹⁵ texels (a
    /// 12 GB decode) is refused as too large before any allocation, at the default bound and at
    /// a caller's; a map within the bound still reads; a PNG renamed `.hdr` is not decoded.
    #[test]
    fn a_header_over_the_texel_bound_is_refused_before_decoding() {
        let dir = std::env::temp_dir().join(format!("hw3-envmap-bound-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let bomb = dir.join("bomb.hdr");
        std::fs::write(&bomb, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32768 +X 32768\n\x02\x02").unwrap();
        let error = Probe::read_lat_long(&bomb).unwrap_err();
        assert!(
            matches!(
                error,
                ProbeError::TooLarge { width: 32768, height: 32768, max_texels: Probe::MAX_READ_TEXELS, .. }
            ),
            "{error}"
        );
        assert!(error.to_string().contains("32768×32768"), "{error}");
        let small = dir.join("small.hdr");
        std::fs::write(&small, super::super::radiance::flat_file(32, 16, &[[1.0; 3]; 32 * 16])).unwrap();
        assert!(matches!(Probe::read_lat_long_limited(&small, 511), Err(ProbeError::TooLarge { .. })));
        assert_eq!(Probe::read_lat_long_limited(&small, 512).unwrap().texels().len(), 512);
        let png = dir.join("picture.hdr");
        std::fs::write(&png, hw3_core::plot::encode_png(&hw3_core::plot::RgbImage::new(4, 4)).unwrap()).unwrap();
        assert!(matches!(Probe::read_lat_long(&png), Err(ProbeError::Read { .. })));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
