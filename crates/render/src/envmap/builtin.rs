//! The two CC0 environment maps compiled into the binary: a soft overcast `courtyard` and a hard
//! `sunrise`, both 256×128 latitude-longitude Radiance `.hdr` images (provenance, licence and
//! conversion in `docs/data/q4/README.md`). Compiling them in means `hw3` reads no file of the
//! source tree at run time, so it works from any directory and after `cargo install`.

use super::probe::{Probe, ProbeError};

/// A map compiled into the binary.
///
/// # Examples
/// ```
/// use hw3_render::envmap::BuiltinMap;
/// assert_eq!(BuiltinMap::ALL.map(BuiltinMap::name), ["courtyard", "sunrise"]);
/// assert_eq!(BuiltinMap::from_name("sunrise"), Some(BuiltinMap::Sunrise));
/// assert_eq!(BuiltinMap::from_name("beach"), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BuiltinMap {
    /// Soft: an overcast courtyard, 2.5 % of its light in the brightest 0.1 % of solid angle.
    Courtyard,
    /// Hard: a low sun, 61 % of its light in the brightest 0.1 % of solid angle.
    Sunrise,
}

impl BuiltinMap {
    /// Every built-in map, soft first.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::envmap::BuiltinMap;
    /// assert!(BuiltinMap::ALL.iter().all(|m| BuiltinMap::from_name(m.name()) == Some(*m)));
    /// ```
    pub const ALL: [BuiltinMap; 2] = [BuiltinMap::Courtyard, BuiltinMap::Sunrise];

    /// The map's name (`"courtyard"`, `"sunrise"`).
    ///
    /// # Examples
    /// ```
    /// assert_eq!(hw3_render::envmap::BuiltinMap::Courtyard.name(), "courtyard");
    /// ```
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Courtyard => "courtyard",
            Self::Sunrise => "sunrise",
        }
    }

    /// The map called `name`, `None` for any other name.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::envmap::BuiltinMap;
    /// assert_eq!(BuiltinMap::from_name("courtyard"), Some(BuiltinMap::Courtyard));
    /// ```
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The `.hdr` file's bytes, as committed under `docs/data/q4/`.
    ///
    /// # Examples
    /// ```
    /// assert!(hw3_render::envmap::BuiltinMap::Sunrise.hdr_bytes().starts_with(b"#?RADIANCE"));
    /// ```
    #[must_use]
    pub fn hdr_bytes(self) -> &'static [u8] {
        match self {
            Self::Courtyard => include_bytes!("../../../../docs/data/q4/courtyard_256x128.hdr"),
            Self::Sunrise => include_bytes!("../../../../docs/data/q4/sunrise_256x128.hdr"),
        }
    }

    /// The map as a latitude-longitude [`Probe`] (`+z` up), decoded from [`Self::hdr_bytes`].
    ///
    /// # Errors
    /// None in practice (the bytes are fixed and tested); the type is that of
    /// [`Probe::decode_lat_long`].
    ///
    /// # Examples
    /// ```
    /// let probe = hw3_render::envmap::BuiltinMap::Courtyard.probe().unwrap();
    /// assert_eq!((probe.width(), probe.height()), (256, 128));
    /// ```
    pub fn probe(self) -> Result<Probe, ProbeError> {
        Probe::decode_lat_long(self.hdr_bytes(), self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::envmap::luminance;

    #[test]
    fn compiled_in_maps_equal_the_committed_files() {
        for map in BuiltinMap::ALL {
            let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../docs")
                .join("data")
                .join("q4")
                .join(format!("{}_256x128.hdr", map.name()));
            let from_file = Probe::read_lat_long(&path).unwrap();
            assert_eq!(map.probe().unwrap(), from_file, "{}", map.name());
        }
    }

    /// The hardness quoted on the variants (and in `docs/data/q4/README.md`): the share of
    /// `luminance × Δω` in the brightest 0.1 % of solid angle, measured: courtyard 2.5 %,
    /// sunrise 61 %.
    #[test]
    fn the_soft_map_is_soft_and_the_hard_map_is_hard() {
        let share = |map: BuiltinMap| {
            let probe = map.probe().unwrap();
            let mut texels: Vec<_> = probe.texels().iter().filter(|t| t.solid_angle > 0.0).collect();
            texels.sort_by(|a, b| luminance(b.radiance).total_cmp(&luminance(a.radiance)));
            let total: f64 = texels.iter().map(|t| luminance(t.radiance) * t.solid_angle).sum();
            let budget = 1e-3 * 4.0 * std::f64::consts::PI;
            let (mut covered, mut bright) = (0.0, 0.0);
            for t in texels {
                if covered >= budget {
                    break;
                }
                let take = (budget - covered).min(t.solid_angle);
                covered += take;
                bright += luminance(t.radiance) * take;
            }
            100.0 * bright / total
        };
        let (soft, hard) = (share(BuiltinMap::Courtyard), share(BuiltinMap::Sunrise));
        assert!((soft - 2.5).abs() < 0.5, "courtyard {soft} %");
        assert!((hard - 61.0).abs() < 1.0, "sunrise {hard} %");
    }
}
