//! How much work Q5's measurements and pictures do: the published budget, which writes the
//! committed tables and figures, and a tiny one that runs the same code in a fraction of a second.
//!
//! The published budget's numbers live here and nowhere else: the named constants of the other files
//! ([`PHOTONS`](super::experiments::PHOTONS), [`LEVELS`](super::cornell_published::LEVELS), …)
//! read them from [`Budget::PUBLISHED`], so this file imports none of its siblings.

/// The sample counts, photon count, meshes and image sizes of Q5's measured table
/// ([`measured_table`](super::experiments::measured_table)), validation table
/// ([`validation_table`](super::cornell_published::validation_table)), effect grid
/// ([`figure`](super::effect_grid::figure)) and renders ([`renders`](super::renders)).
///
/// [`Budget::PUBLISHED`] is the one behind every committed file; [`Budget::TINY`] runs the same
/// code on a few pixels with a sample or two and the coarsest meshes, so its numbers are noise:
/// it checks that the pipeline runs and what shape it returns, not what it measures.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::Budget;
/// let (published, tiny) = (Budget::PUBLISHED, Budget::TINY);
/// assert!(tiny.reference_spp < published.reference_spp && tiny.photons < published.photons);
/// assert!(tiny.levels.len() < published.levels.len() && tiny.image_divisor > published.image_divisor);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Budget {
    /// Path-traced samples per probe of the measured table's reference.
    pub reference_spp: u32,
    /// Light samples per probe (and per pixel of the effect grid) of the eye rays' direct light in
    /// the Whitted, two-pass and photon-mapping measurements.
    pub light_samples: u32,
    /// Photons emitted for the two-pass and photon-mapping cells and panels.
    pub photons: usize,
    /// The measured table's radiosity mesh: patches per quad edge and form-factor samples per
    /// patch edge.
    pub table_mesh: (usize, usize),
    /// Patches per quad edge of the validation table's rows, coarse to fine.
    pub levels: &'static [usize],
    /// Samples per pixel of the path-traced montage's highlight, direct-light and mirror panels.
    pub path_spp: u32,
    /// Samples per pixel of the montage's caustic panel (its fireflies fade slowly).
    pub caustic_spp: u32,
    /// Samples per pixel of the published Cornell box's noisy path-traced panel.
    pub noisy_spp: u32,
    /// Samples per pixel of the published Cornell box's close-to-converged path-traced panel, the
    /// reference its other two panels are compared with.
    pub converged_spp: u32,
    /// The radiosity Cornell box render's mesh: patches per quad edge and form-factor samples per
    /// patch edge.
    pub render_mesh: (usize, usize),
    /// Radiosity's patches per quad edge beside the path tracer in the published box's picture.
    pub side_by_side_patches: usize,
    /// Every picture's width and height are divided by this (1: the published sizes).
    pub image_divisor: u32,
}

impl Budget {
    /// The budget of the committed tables and figures.
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::{Budget, PATH_SPP, experiments::{PHOTONS, REFERENCE_SPP}};
    /// let published = Budget::PUBLISHED;
    /// assert_eq!((published.reference_spp, published.photons, published.path_spp), (REFERENCE_SPP, PHOTONS, PATH_SPP));
    /// assert_eq!(published.image_divisor, 1);
    /// ```
    pub const PUBLISHED: Budget = Budget {
        reference_spp: 1024,
        light_samples: 16,
        photons: 200_000,
        table_mesh: (6, 2),
        levels: &[4, 6, 8, 12],
        path_spp: 128,
        caustic_spp: 1024,
        noisy_spp: 32,
        converged_spp: 256,
        render_mesh: (8, 2),
        side_by_side_patches: 12,
        image_divisor: 1,
    };

    /// A budget for examples and smoke tests: two samples per reference probe, one light sample,
    /// 1000 photons, 2 × 2 patches, pictures a fortieth of the published size.
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::{Budget, effect_grid::PANEL_SIZE};
    /// // Grid panels of 8 × 6 pixels: still whole pixels.
    /// assert_eq!((PANEL_SIZE.0 / Budget::TINY.image_divisor, PANEL_SIZE.1 / Budget::TINY.image_divisor), (8, 6));
    /// ```
    pub const TINY: Budget = Budget {
        reference_spp: 2,
        light_samples: 1,
        photons: 1000,
        table_mesh: (2, 1),
        levels: &[2, 3],
        path_spp: 1,
        caustic_spp: 1,
        noisy_spp: 1,
        converged_spp: 2,
        render_mesh: (2, 1),
        side_by_side_patches: 2,
        image_divisor: 40,
    };

    /// `(width, height)` divided by [`Budget::image_divisor`].
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::Budget;
    /// assert_eq!(Budget::PUBLISHED.image_size((640, 480)), (640, 480));
    /// assert_eq!(Budget::TINY.image_size((640, 480)), (16, 12));
    /// ```
    #[must_use]
    pub const fn image_size(&self, (width, height): (u32, u32)) -> (u32, u32) {
        (width / self.image_divisor, height / self.image_divisor)
    }
}
