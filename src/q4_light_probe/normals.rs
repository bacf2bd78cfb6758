//! The test normals of the accuracy study and of the oracle tests.

use glam::DVec3;

/// `n` unit normals spread evenly over the sphere (a Fibonacci spiral), deterministic: the
/// renderer's [`fibonacci_sphere`](crate::render::sampling::fibonacci_sphere), bit for bit.
///
/// # Examples
/// ```
/// let normals = hw3::q4_light_probe::fibonacci_normals(64);
/// assert_eq!(normals.len(), 64);
/// assert!(normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-12));
/// ```
#[must_use]
pub fn fibonacci_normals(n: usize) -> Vec<DVec3> {
    crate::render::sampling::fibonacci_sphere(n)
}
