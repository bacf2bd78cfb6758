//! What both photon traces share: the scene's emitters with their powers, and tracing photons
//! in parallel so that the result does not depend on the number of threads.

use crate::render::color::luminance;
use crate::render::scene::{Material, Scene, Shape};
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// An emitter of the scene with its power (W per channel).
#[derive(Debug, Clone, Copy)]
pub(super) enum Emitter {
    Point { position: DVec3, power: DVec3 },
    Quad { corner: DVec3, edge_u: DVec3, edge_v: DVec3, power: DVec3 },
}

impl Emitter {
    pub(super) fn power(&self) -> DVec3 {
        match *self {
            Emitter::Point { power, .. } | Emitter::Quad { power, .. } => power,
        }
    }
}

/// The scene's lights with their powers: `Φ = 4πI` for a point light, `Φ = π L A` for a
/// one-sided Lambertian quad of radiance `L` and area `A`.
pub(super) fn emitters(scene: &Scene) -> Vec<Emitter> {
    let points = scene
        .point_lights()
        .iter()
        .map(|light| Emitter::Point { position: light.position, power: light.intensity * (4.0 * PI) });
    let quads = scene.objects().iter().filter_map(|object| match (object.material, object.shape) {
        (Material::Emitter { radiance }, Shape::Quad { corner, edge_u, edge_v }) => {
            let area = edge_u.cross(edge_v).length();
            Some(Emitter::Quad { corner, edge_u, edge_v, power: radiance * (PI * area) })
        }
        _ => None,
    });
    points.chain(quads).filter(|e| luminance(e.power()) > 0.0).collect()
}

/// Photon `index` of `count` traced by `trace` into its own output, in parallel chunks of fixed
/// size concatenated in order: the result does not depend on the number of threads.
pub(super) fn in_ordered_chunks<T: Send>(count: usize, trace: impl Fn(usize, &mut Vec<T>) + Sync) -> Vec<T> {
    let chunk = 4096;
    let stored: Vec<Vec<T>> = (0..count.div_ceil(chunk))
        .into_par_iter()
        .map(|c| {
            let mut out = Vec::new();
            for index in (c * chunk)..((c + 1) * chunk).min(count) {
                trace(index, &mut out);
            }
            out
        })
        .collect();
    stored.into_iter().flatten().collect()
}
