//! The pinhole camera and the frame its primary rays are generated in.

use glam::DVec3;
use hw3_core::geometry::Ray;

/// A pinhole camera with a shutter interval (distribution ray tracing samples times inside it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// The pinhole.
    pub eye: DVec3,
    /// A point the camera looks at (the image centre).
    pub look_at: DVec3,
    /// Approximate up direction (must not be parallel to the view direction).
    pub up: DVec3,
    /// Vertical field of view in degrees, in `(0, 180)`.
    pub vfov_degrees: f64,
    /// Shutter open and close times, `open ≤ close`. Equal times give an instantaneous exposure.
    pub shutter: (f64, f64),
}

impl Camera {
    /// A camera at `eye` looking at `look_at` with `+y` up, a vertical field of view of
    /// `vfov_degrees`, and an instantaneous shutter at time 0 (validated by [`Scene::new`](super::scene::Scene::new)).
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// let camera = hw3_render::render::camera::Camera::looking_at(DVec3::Z, DVec3::ZERO, 40.0);
    /// assert_eq!(camera.shutter, (0.0, 0.0));
    /// ```
    #[must_use]
    pub fn looking_at(eye: DVec3, look_at: DVec3, vfov_degrees: f64) -> Self {
        Self { eye, look_at, up: DVec3::Y, vfov_degrees, shutter: (0.0, 0.0) }
    }
}

/// The camera's orthonormal frame and image-plane extents, precomputed once per render.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraFrame {
    eye: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    half_height: f64,
}

impl CameraFrame {
    /// The frame of `camera`; assumes `camera` was validated by [`Scene::new`](super::scene::Scene::new).
    #[must_use]
    pub fn new(camera: &Camera) -> Self {
        let forward = (camera.look_at - camera.eye).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        let half_height = (camera.vfov_degrees.to_radians() / 2.0).tan();
        Self { eye: camera.eye, forward, right, up, half_height }
    }

    /// Whether `point` projects inside the image of aspect ratio `aspect` (and lies in front).
    #[must_use]
    pub fn sees(&self, point: DVec3, aspect: f64) -> bool {
        let offset = point - self.eye;
        let depth = offset.dot(self.forward);
        depth > 0.0
            && (offset.dot(self.right) / depth).abs() <= self.half_height * aspect
            && (offset.dot(self.up) / depth).abs() <= self.half_height
    }

    /// The primary ray through image-plane point `(u, v)` in `[0, 1]²` (`v = 0` is the top row)
    /// for an image of aspect ratio `aspect = width / height`. The direction is unit length.
    #[must_use]
    pub fn ray(&self, u: f64, v: f64, aspect: f64) -> Ray<f64> {
        let x = (2.0 * u - 1.0) * self.half_height * aspect;
        let y = (1.0 - 2.0 * v) * self.half_height;
        let dir = (self.forward + self.right * x + self.up * y).normalize();
        Ray { origin: self.eye, dir }
    }
}
