//! The test normals of the accuracy study and of the oracle tests.

use glam::DVec3;

/// `n` unit normals spread evenly over the sphere (a Fibonacci spiral), deterministic.
///
/// # Examples
/// ```
/// let normals = hw3::q4_light_probe::fibonacci_normals(64);
/// assert_eq!(normals.len(), 64);
/// assert!(normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-12));
/// ```
#[must_use]
pub fn fibonacci_normals(n: usize) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * i as f64;
            DVec3::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}
