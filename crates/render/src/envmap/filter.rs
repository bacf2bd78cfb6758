//! Bilinear lookup of a probe: what a camera looking at the map sees, without the texel blocks
//! of a nearest-texel lookup.
//!
//! The probe's texels are piecewise constant ([`Probe::radiance_toward`]), which is what the
//! estimators integrate and what importance sampling draws from. A picture of the map, though,
//! magnifies it: a 256-texel-wide lat-long map seen through a 60° lens spans about 43 texels
//! across a 640-pixel image, so each texel is a 15-pixel block. Interpolating between the four
//! texel centres around a direction (bilinear filtering, pbrt-v4 §10.4.3 for image textures)
//! hides the blocks.
//!
//! - **Lat-long** maps wrap in longitude: the column left of the first is the last, so the map
//!   has no seam at `φ = 0 = 2π`. Rows clamp at the poles (the first and last rows' centres are
//!   half a texel from the pole).
//! - **Disk formats** (balls, angular map) interpolate only among texels that lie in the disk
//!   (a texel outside it has zero solid angle and no radiance), the weights renormalised; a
//!   direction in a blind cone, which no texel sees, stays black.

use super::Probe;
use super::format::ProbeFormat;
use glam::{DVec2, DVec3};

impl Probe {
    /// The radiance toward unit world direction `omega`, bilinearly interpolated between the
    /// four texel centres around it (a lat-long map wraps in longitude and clamps at the poles; a
    /// disk format blends only the texels inside its disk); zero in a blind cone.
    ///
    /// Equal to [`Probe::radiance_toward`] at every texel centre, continuous across texel
    /// edges, and for a lat-long map across the `φ = 0 = 2π` meridian.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// // Four columns of radiance 0, 1, 2, 3: halfway between column centres 3 and 0 (across
    /// // the wrap at φ = 0) is the mean of their radiances, on both sides of the meridian.
    /// let texels = (0..8).map(|i| DVec3::splat(f64::from(i % 4))).collect();
    /// let map = Probe::from_radiance(ProbeFormat::LatLong, 4, 2, DMat3::IDENTITY, texels).unwrap();
    /// let east = map.radiance_bilinear(DVec3::new(1.0, 1e-9, 0.0));
    /// let west = map.radiance_bilinear(DVec3::new(1.0, -1e-9, 0.0));
    /// assert!((east.x - 1.5).abs() < 1e-6 && (west.x - 1.5).abs() < 1e-6);
    /// ```
    #[must_use]
    pub fn radiance_bilinear(&self, omega: DVec3) -> DVec3 {
        self.world_to_image(omega).map_or(DVec3::ZERO, |p| self.radiance_bilinear_at(p))
    }

    /// The radiance seen at image point `p` (the format's image coordinates, `[0,1]²` for
    /// lat-long, `[-1,1]²` with `y` up for the disk formats), bilinearly interpolated between
    /// the four texel centres around it; zero outside the disk of a disk format.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec2, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// let ball = Probe::from_fn(ProbeFormat::MirrorBall, 8, 8, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
    /// assert!((ball.radiance_bilinear_at(DVec2::new(0.0, 0.99)) - DVec3::ONE).length() < 1e-12); // near the rim
    /// assert_eq!(ball.radiance_bilinear_at(DVec2::new(0.9, 0.9)), DVec3::ZERO); // outside the disk
    /// ```
    #[must_use]
    pub fn radiance_bilinear_at(&self, p: DVec2) -> DVec3 {
        let lat_long = self.format() == ProbeFormat::LatLong;
        if !lat_long && !(p.length() <= 1.0) {
            return DVec3::ZERO;
        }
        let rect = self.format().image_rect();
        let unit = (p - rect.min) / (rect.max - rect.min);
        let (width, height) = (self.width(), self.height());
        let from_top = if lat_long { unit.y } else { 1.0 - unit.y };
        // Texel (c, r) has its centre at ((c + ½)/width, (r + ½)/height).
        let x = unit.x * width as f64 - 0.5;
        let y = from_top * height as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let column = |c: f64| -> Option<usize> {
            if lat_long {
                Some((c as i64).rem_euclid(width as i64) as usize)
            } else {
                (0.0..width as f64).contains(&c).then_some(c as usize)
            }
        };
        let row = |r: f64| -> Option<usize> {
            if lat_long {
                Some(r.clamp(0.0, (height - 1) as f64) as usize)
            } else {
                (0.0..height as f64).contains(&r).then_some(r as usize)
            }
        };
        let mut sum = DVec3::ZERO;
        let mut weight_sum = 0.0;
        for (dx, wx) in [(0.0, 1.0 - fx), (1.0, fx)] {
            for (dy, wy) in [(0.0, 1.0 - fy), (1.0, fy)] {
                let (Some(c), Some(r)) = (column(x0 + dx), row(y0 + dy)) else { continue };
                let texel = &self.texels()[r * width + c];
                if texel.solid_angle > 0.0 && wx * wy > 0.0 {
                    sum += texel.radiance * (wx * wy);
                    weight_sum += wx * wy;
                }
            }
        }
        if weight_sum > 0.0 { sum / weight_sum } else { self.texels()[self.texel_index_at(p)].radiance }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DMat3;

    #[test]
    fn bilinear_equals_nearest_at_texel_centres_and_interpolates_between() {
        let texels: Vec<DVec3> = (0..32).map(|i| DVec3::new(f64::from(i), 0.0, 1.0)).collect();
        let map = Probe::from_radiance(ProbeFormat::LatLong, 8, 4, DMat3::IDENTITY, texels).unwrap();
        for (index, texel) in map.texels().iter().enumerate() {
            let centre = DVec2::new((index % 8) as f64 + 0.5, (index / 8) as f64 + 0.5) / DVec2::new(8.0, 4.0);
            assert!((map.radiance_bilinear_at(centre) - texel.radiance).length() < 1e-12, "{index}");
        }
        // Halfway between the centres of texels 9 and 10 (row 1): their mean.
        let between = map.radiance_bilinear_at(DVec2::new(2.0 / 8.0, 1.5 / 4.0));
        assert!((between.x - 9.5).abs() < 1e-12);
    }

    #[test]
    fn a_lat_long_map_has_no_seam_at_phi_zero() {
        let map = Probe::from_fn(ProbeFormat::LatLong, 64, 32, DMat3::IDENTITY, |w| {
            DVec3::new(w.x.max(0.0), (w.y + 1.0) * 0.5, w.z * w.z)
        })
        .unwrap();
        for k in 0..32 {
            let v = (f64::from(k) + 0.25) / 32.0;
            let first = map.radiance_bilinear_at(DVec2::new(1e-12, v));
            let last = map.radiance_bilinear_at(DVec2::new(1.0 - 1e-12, v));
            assert!((first - last).length() < 1e-9, "row {k}: {first} vs {last}");
        }
    }

    #[test]
    fn disk_formats_use_only_texels_inside_the_disk_and_stay_black_in_the_blind_cone() {
        let ball = ProbeFormat::perspective_ball(3.0).unwrap();
        let probe = Probe::from_fn(ball, 32, 32, DMat3::IDENTITY, |_| DVec3::splat(2.0)).unwrap();
        for k in 0..360 {
            let angle = f64::from(k).to_radians();
            let rim = DVec2::new(angle.cos(), angle.sin()) * (1.0 - 1e-9);
            assert!((probe.radiance_bilinear_at(rim) - DVec3::splat(2.0)).length() < 1e-12, "{k}°");
        }
        assert_eq!(probe.radiance_bilinear(-DVec3::Z), DVec3::ZERO);
    }
}
