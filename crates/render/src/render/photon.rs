//! Photon tracing and photon maps (Jensen 1996): photons shot from the lights, bounced through
//! the scene's materials with Russian roulette, stored at diffuse hits, and read back by a
//! bias-corrected k-nearest-neighbour density estimate.
//!
//! Three maps come out of one trace, because they differ only in which stored photons they keep:
//! - **all** ([`PhotonMaps::all`]): every photon at every diffuse (or glossy-with-diffuse-part)
//!   hit, paths `L(S|D|G)*D`: the complete irradiance, used by the furnace test;
//! - **indirect** ([`PhotonMaps::indirect`]): photons that already bounced off a diffuse or
//!   glossy surface, `L(S|D|G)*(D|G)(S|D|G)*D`: what eye rays with direct light miss;
//! - **caustic** ([`PhotonMaps::caustic`]): photons whose every bounce so far was specular
//!   (mirror or glass), `LS+D`.
//!
//! The estimate ([`PhotonMap::irradiance`], [`PhotonMap::radiance`]) sums the power of the
//! `k − 1` nearest photons over the disc `πr²` reaching the `k`-th: for photons of density `λ`
//! the number inside a disc of area `a` is Poisson, so `λπr_k²` is Gamma(k, 1) distributed and
//! `E[1/(πr_k²)] = λ/(k − 1)`; `(k−1)/(πr_k²)` is unbiased where `k/(πr_k²)` overestimates by
//! `k/(k−1)` (see the renderer chapter).
//!
//! Tracing is deterministic: photon `i` draws from its own [`Sampler`](super::sampling::Sampler) stream (seed, `i`), so the
//! maps are identical for any number of rayon threads.

mod caustic;
mod emission;
mod global;
mod map;
mod point_tree;

pub use caustic::{CAUSTIC_PHOTONS, trace_caustic_photons};
pub use global::{PhotonMaps, trace_photons};
pub use map::{CAUSTIC_GATHER, Gather, MAX_BOUNCES, MAX_PHOTONS, Photon, PhotonError, PhotonMap};
pub use point_tree::{LEAF_SIZE, Neighbour, PointTree};
