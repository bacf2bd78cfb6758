//! The render passes: the switches a plan turns on or off ([`Pass`]) and a plan's set of them
//! ([`Passes`]). The light-path analysis ([`super::analysis`]) decides them; the integrators
//! read them.

use serde::Serialize;

/// A render pass that the planner can switch on or off.
///
/// # Examples
/// ```
/// use hw3_render::render::passes::Pass;
/// assert_eq!(Pass::ALL.len(), 6);
/// assert_eq!(Pass::InScattering.name(), "in_scattering");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Pass {
    /// Recursion through perfect mirrors and glass (`…S+E`).
    SpecularRecursion,
    /// Beer–Lambert attenuation `e^(−σ_t d)` of every ray segment in a medium.
    Transmittance,
    /// Single scattering from point and area lights along every ray segment (`…V…E`).
    InScattering,
    /// A random time in the shutter interval for every camera sample (motion blur).
    TimeSampling,
    /// Diffuse/glossy bounces after the first (`L(D|G)(D|G)+…E`; path tracer only).
    IndirectBounces,
    /// A caustic photon map (`LS+D`) traced once per render from the point and area lights and
    /// read at every diffuse or glossy hit (Whitted only: the path tracer finds area-light
    /// caustics by its own bounces).
    Caustics,
}

impl Pass {
    /// Every pass, in a fixed order.
    pub const ALL: [Pass; 6] = [
        Pass::SpecularRecursion,
        Pass::Transmittance,
        Pass::InScattering,
        Pass::TimeSampling,
        Pass::IndirectBounces,
        Pass::Caustics,
    ];

    /// The pass's name as the CLI and JSON print it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Pass::SpecularRecursion => "specular_recursion",
            Pass::Transmittance => "transmittance",
            Pass::InScattering => "in_scattering",
            Pass::TimeSampling => "time_sampling",
            Pass::IndirectBounces => "indirect_bounces",
            Pass::Caustics => "caustics",
        }
    }
}

/// Which passes a render runs: one flag per [`Pass`], all off by default.
///
/// # Examples
/// ```
/// use hw3_render::render::passes::{Pass, Passes};
/// let plan = Passes::default().with(Pass::Caustics, true);
/// assert!(plan.get(Pass::Caustics) && !plan.get(Pass::Transmittance));
/// assert!(Pass::ALL.iter().all(|&pass| Passes::all().get(pass)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Passes {
    /// See [`Pass::SpecularRecursion`].
    pub specular_recursion: bool,
    /// See [`Pass::Transmittance`].
    pub transmittance: bool,
    /// See [`Pass::InScattering`].
    pub in_scattering: bool,
    /// See [`Pass::TimeSampling`].
    pub time_sampling: bool,
    /// See [`Pass::IndirectBounces`].
    pub indirect_bounces: bool,
    /// See [`Pass::Caustics`].
    pub caustics: bool,
}

impl Passes {
    /// Every pass on (`--effects all`): the brute-force render the plan is tested against.
    #[must_use]
    pub fn all() -> Self {
        Pass::ALL.iter().fold(Self::default(), |p, &pass| p.with(pass, true))
    }

    /// Whether `pass` is on.
    #[must_use]
    pub fn get(&self, pass: Pass) -> bool {
        match pass {
            Pass::SpecularRecursion => self.specular_recursion,
            Pass::Transmittance => self.transmittance,
            Pass::InScattering => self.in_scattering,
            Pass::TimeSampling => self.time_sampling,
            Pass::IndirectBounces => self.indirect_bounces,
            Pass::Caustics => self.caustics,
        }
    }

    /// A copy with `pass` set to `on`.
    #[must_use]
    pub fn with(mut self, pass: Pass, on: bool) -> Self {
        let flag = match pass {
            Pass::SpecularRecursion => &mut self.specular_recursion,
            Pass::Transmittance => &mut self.transmittance,
            Pass::InScattering => &mut self.in_scattering,
            Pass::TimeSampling => &mut self.time_sampling,
            Pass::IndirectBounces => &mut self.indirect_bounces,
            Pass::Caustics => &mut self.caustics,
        };
        *flag = on;
        self
    }
}
