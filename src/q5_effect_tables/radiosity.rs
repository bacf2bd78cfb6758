//! Radiosity over the renderer's scenes: quads split into patches, form factors from the analytic
//! point-to-polygon formula times ray-cast visibility, three solvers, and display by bilinear
//! interpolation of patch radiosity.
//!
//! Only Lambertian transport is simulated (`LD*E`): diffuse quads become patches (a glossy quad
//! contributes its diffuse part), emitter quads become emitting patches, and mirrors, glass and
//! every sphere only occlude.

use crate::geometry::Ray;
use crate::geometry::sphere::spawn_origin;
use crate::render::Image;
use crate::render::{
    camera::CameraFrame,
    scene::{Material, Scene, Shape},
};
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Why a radiosity system cannot be built.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::radiosity::{Mesh, RadiosityError};
/// use hw3::render::catalogue::{CornellContents, cornell_box};
/// let scene = cornell_box(true, CornellContents::Block).unwrap();
/// assert_eq!(Mesh::new(&scene, 0).unwrap_err(), RadiosityError::ZeroCount { name: "subdivisions" });
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RadiosityError {
    /// A subdivision or sample count of zero.
    #[error("{name} must be at least 1 (got 0)")]
    ZeroCount {
        /// Which count.
        name: &'static str,
    },
    /// The scene has no diffuse or emitting quad, so there is nothing to solve.
    #[error("the scene has no diffuse or emitting quad to mesh")]
    NoPatches,
}

/// One patch: a sub-parallelogram of a scene quad.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{radiosity::Mesh};
/// use hw3::render::catalogue::{CornellContents, cornell_box};
/// // The 2 × 2 floor in 2 × 2 patches: each 1 × 1, facing up.
/// let mesh = Mesh::new(&cornell_box(true, CornellContents::Block).unwrap(), 2).unwrap();
/// let patch = mesh.patches[0];
/// assert_eq!((patch.object, patch.area, patch.normal), (0, 1.0, glam::DVec3::Y));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Patch {
    /// Index of the scene object it belongs to.
    pub object: usize,
    /// Corner of the patch.
    pub corner: DVec3,
    /// First edge (a fraction of the quad's).
    pub edge_u: DVec3,
    /// Second edge.
    pub edge_v: DVec3,
    /// Unit normal (the quad's `edge_u × edge_v`).
    pub normal: DVec3,
    /// Area.
    pub area: f64,
    /// Diffuse reflectance ρ per channel (0 for emitters).
    pub reflectance: DVec3,
    /// Emitted radiosity `E = π L_e` per channel.
    pub emission: DVec3,
}

impl Patch {
    /// The point at patch coordinates `(a, b) ∈ [0, 1]²`.
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::{radiosity::Mesh};
    /// use hw3::render::catalogue::{CornellContents, cornell_box};
    /// let scene = cornell_box(true, CornellContents::Block).unwrap();
    /// let patch = Mesh::new(&scene, 2).unwrap().patches[0];
    /// assert_eq!(patch.point(0.0, 0.0), patch.corner);
    /// assert!((patch.point(1.0, 1.0) - (patch.corner + patch.edge_u + patch.edge_v)).length() < 1e-12);
    /// ```
    #[must_use]
    pub fn point(&self, a: f64, b: f64) -> DVec3 {
        self.corner + self.edge_u * a + self.edge_v * b
    }

    /// The centres of an `s × s` grid of equal sub-cells (deterministic stratified samples).
    fn grid(&self, s: usize) -> impl Iterator<Item = DVec3> + '_ {
        (0..s * s).map(move |k| {
            let (a, b) = (((k % s) as f64 + 0.5) / s as f64, ((k / s) as f64 + 0.5) / s as f64);
            self.point(a, b)
        })
    }
}

/// Patches of a scene, with the `n × n` block of each meshed object.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{radiosity::Mesh};
/// use hw3::render::catalogue::{CornellContents, cornell_box};
/// let mesh = Mesh::new(&cornell_box(true, CornellContents::Block).unwrap(), 3).unwrap();
/// assert_eq!((mesh.patches.len(), mesh.first_patch[1]), (11 * 9, Some(9)));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Every patch; those of one object are contiguous, row-major in `(b, a)`.
    pub patches: Vec<Patch>,
    /// For each scene object, the index of its first patch (None for objects that only occlude).
    pub first_patch: Vec<Option<usize>>,
    /// Patches per quad edge.
    pub subdivisions: usize,
}

impl Mesh {
    /// Splits every diffuse, glossy or emitting quad of `scene` into `n × n` patches.
    ///
    /// # Errors
    /// [`RadiosityError::ZeroCount`] for `n = 0`; [`RadiosityError::NoPatches`] when no quad
    /// qualifies. (Degenerate quads cannot occur: [`Scene::new`] rejects parallel edges.)
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::radiosity::Mesh;
    /// let scene = hw3::render::catalogue::cornell_box(true, hw3::render::catalogue::CornellContents::Block).unwrap();
    /// let mesh = Mesh::new(&scene, 2).unwrap();
    /// assert_eq!(mesh.patches.len() % 4, 0);
    /// assert!(Mesh::new(&scene, 0).is_err());
    /// ```
    pub fn new(scene: &Scene, n: usize) -> Result<Self, RadiosityError> {
        if n == 0 {
            return Err(RadiosityError::ZeroCount { name: "subdivisions" });
        }
        let mut patches = Vec::new();
        let mut first_patch = Vec::new();
        for (index, object) in scene.objects().iter().enumerate() {
            let (reflectance, emission) = match object.material {
                Material::Diffuse { albedo } => (albedo, DVec3::ZERO),
                Material::Glossy { diffuse, .. } => (diffuse, DVec3::ZERO),
                Material::Emitter { radiance } => (DVec3::ZERO, radiance * PI),
                Material::Mirror { .. } | Material::Glass { .. } => {
                    first_patch.push(None);
                    continue;
                }
            };
            let Shape::Quad { corner, edge_u, edge_v } = object.shape else {
                first_patch.push(None);
                continue;
            };
            first_patch.push(Some(patches.len()));
            let (du, dv) = (edge_u / n as f64, edge_v / n as f64);
            let normal = edge_u.cross(edge_v).normalize();
            let area = du.cross(dv).length();
            for b in 0..n {
                for a in 0..n {
                    patches.push(Patch {
                        object: index,
                        corner: corner + du * a as f64 + dv * b as f64,
                        edge_u: du,
                        edge_v: dv,
                        normal,
                        area,
                        reflectance,
                        emission,
                    });
                }
            }
        }
        if patches.is_empty() {
            return Err(RadiosityError::NoPatches);
        }
        Ok(Self { patches, first_patch, subdivisions: n })
    }
}

/// The form factor from a differential area at `point` (normal `normal`) to the polygon
/// `vertices`: `F = (1/2π) |Σ_k β_k n·γ_k|` (Lambert), after clipping the polygon to the
/// hemisphere above the point. Exact without occluders; 0 when the point sees the polygon's back.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::q5_effect_tables::radiosity::point_to_polygon;
/// // A square 2000 wide, 1 above the point, fills nearly all of its hemisphere; from below, none.
/// let square = [(-1e3, -1e3), (1e3, -1e3), (1e3, 1e3), (-1e3, 1e3)].map(|(x, y)| DVec3::new(x, y, 1.0));
/// assert!((point_to_polygon(DVec3::ZERO, DVec3::Z, &square) - 1.0).abs() < 1e-3);
/// assert_eq!(point_to_polygon(DVec3::ZERO, DVec3::NEG_Z, &square), 0.0);
/// ```
#[must_use]
pub fn point_to_polygon(point: DVec3, normal: DVec3, vertices: &[DVec3]) -> f64 {
    // Sutherland–Hodgman against the tangent plane: the formula holds for polygons above it.
    let height = |v: DVec3| normal.dot(v - point);
    let mut clipped = Vec::with_capacity(vertices.len() + 2);
    for (k, &v) in vertices.iter().enumerate() {
        let w = vertices[(k + 1) % vertices.len()];
        let (hv, hw) = (height(v), height(w));
        if hv >= 0.0 {
            clipped.push(v);
        }
        if (hv >= 0.0) != (hw >= 0.0) {
            clipped.push(v + (w - v) * (hv / (hv - hw)));
        }
    }
    if clipped.len() < 3 {
        return 0.0;
    }
    let mut sum = 0.0;
    for k in 0..clipped.len() {
        let r0 = (clipped[k] - point).normalize();
        let r1 = (clipped[(k + 1) % clipped.len()] - point).normalize();
        let cross = r0.cross(r1);
        let length = cross.length();
        if length > 0.0 {
            sum += r0.dot(r1).clamp(-1.0, 1.0).acos() * normal.dot(cross / length);
        }
    }
    sum.abs() / (2.0 * PI)
}

/// A radiosity system: the mesh and its form-factor matrix `F[i][j]` (fraction of the energy
/// leaving patch i that reaches patch j).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::radiosity::{Mesh, System};
/// use hw3::render::catalogue::{CornellContents, cornell_box};
/// // The box is open at the front: every row of form factors sums to at most 1.
/// let scene = cornell_box(true, CornellContents::Block).unwrap();
/// let system = System::new(&scene, Mesh::new(&scene, 2).unwrap(), 1).unwrap();
/// assert!(system.form_factors.iter().all(|row| row.iter().sum::<f64>() <= 1.0 + 1e-9));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct System {
    /// The patches.
    pub mesh: Mesh,
    /// Dense form factors: `form_factors[i][j] = F_ij`, the fraction of the energy leaving
    /// patch i that arrives at patch j (equivalently, the weight of `B_j` in what i gathers).
    pub form_factors: Vec<Vec<f64>>,
}

impl System {
    /// Form factors for `mesh`: each row averages the point-to-polygon factor over `samples²`
    /// points of patch i, each weighted by the fraction of `samples²` points of patch j that the
    /// point sees (shadow rays through `scene`). Patches of one planar quad see each other not at all.
    ///
    /// Cost: `N² samples⁴` shadow rays at most (rows in parallel; the bytes do not depend on threads).
    ///
    /// # Errors
    /// [`RadiosityError::ZeroCount`] for `samples = 0`.
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::radiosity::{Mesh, System};
    /// use hw3::render::catalogue::{CornellContents, cornell_box};
    /// let scene = cornell_box(true, CornellContents::Block).unwrap();
    /// assert!(System::new(&scene, Mesh::new(&scene, 2).unwrap(), 1).is_ok());
    /// assert!(System::new(&scene, Mesh::new(&scene, 2).unwrap(), 0).is_err());
    /// ```
    pub fn new(scene: &Scene, mesh: Mesh, samples: usize) -> Result<Self, RadiosityError> {
        if samples == 0 {
            return Err(RadiosityError::ZeroCount { name: "samples" });
        }
        let patches = &mesh.patches;
        let form_factors = patches
            .par_iter()
            .map(|receiver| {
                patches
                    .iter()
                    .map(|source| {
                        if source.object == receiver.object {
                            return 0.0;
                        }
                        let quad = [
                            source.corner,
                            source.corner + source.edge_u,
                            source.corner + source.edge_u + source.edge_v,
                            source.corner + source.edge_v,
                        ];
                        let total: f64 = receiver
                            .grid(samples)
                            .map(|x| {
                                if source.normal.dot(x - source.corner) <= 0.0 {
                                    return 0.0;
                                }
                                let factor = point_to_polygon(x, receiver.normal, &quad);
                                if factor == 0.0 {
                                    return 0.0;
                                }
                                factor * visible_fraction(scene, x, receiver.normal, source, samples)
                            })
                            .sum();
                        total / (samples * samples) as f64
                    })
                    .collect()
            })
            .collect();
        Ok(Self { mesh, form_factors })
    }

    /// The emitted radiosities `E_i`.
    fn emission(&self) -> Vec<DVec3> {
        self.mesh.patches.iter().map(|p| p.emission).collect()
    }

    /// `E_i + ρ_i Σ_j F_ij B_j` for one patch.
    fn gather(&self, i: usize, radiosity: &[DVec3]) -> DVec3 {
        let patch = &self.mesh.patches[i];
        let incoming: DVec3 = self.form_factors[i].iter().zip(radiosity).map(|(&f, &b)| b * f).sum();
        patch.emission + patch.reflectance * incoming
    }

    /// Runs `solver` for `sweeps` sweeps (Southwell: `N` shots per sweep), starting from `B = E`,
    /// and returns the radiosity after each sweep (index 0 = the start).
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::{experiments::cornell_system, radiosity::Solver};
    /// let (_, system) = cornell_system(2, 1).unwrap();
    /// let history = system.solve(Solver::GaussSeidel, 5);
    /// assert_eq!(history.len(), 6);
    /// let total = |b: &[glam::DVec3]| b.iter().map(|x| x.element_sum()).sum::<f64>();
    /// assert!(total(&history[5]) > total(&history[0]));
    /// ```
    #[must_use]
    pub fn solve(&self, solver: Solver, sweeps: usize) -> Vec<Vec<DVec3>> {
        let n = self.mesh.patches.len();
        let mut radiosity = self.emission();
        let mut unshot = radiosity.clone();
        let mut history = vec![radiosity.clone()];
        for _ in 0..sweeps {
            match solver {
                Solver::Jacobi => {
                    radiosity = (0..n).map(|i| self.gather(i, &radiosity)).collect();
                }
                Solver::GaussSeidel => {
                    for i in 0..n {
                        radiosity[i] = self.gather(i, &radiosity);
                    }
                }
                Solver::Southwell => {
                    for _ in 0..n {
                        self.shoot(&mut radiosity, &mut unshot);
                    }
                }
            }
            history.push(radiosity.clone());
        }
        history
    }

    /// One progressive-refinement shot: the patch with the most unshot power `|ΔB_i| A_i` sends
    /// `ρ_j F_ji ΔB_i` to every patch j.
    fn shoot(&self, radiosity: &mut [DVec3], unshot: &mut [DVec3]) {
        let patches = &self.mesh.patches;
        let power = |i: usize| unshot[i].element_sum() * patches[i].area;
        let Some(shooter) = (0..patches.len()).max_by(|&a, &b| power(a).total_cmp(&power(b))) else { return };
        let sent = unshot[shooter];
        unshot[shooter] = DVec3::ZERO;
        for (j, patch) in patches.iter().enumerate() {
            let gained = patch.reflectance * sent * self.form_factors[j][shooter];
            radiosity[j] += gained;
            unshot[j] += gained;
        }
    }

    /// The radiance (`B/π`) leaving the meshed surface at `point` on object `object`, bilinearly
    /// interpolated between patch centres; None for objects without patches.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::q5_effect_tables::{experiments::cornell_system, radiosity::Solver};
    /// let (_, system) = cornell_system(2, 1).unwrap();
    /// let b = system.solve(Solver::GaussSeidel, 20).pop().unwrap();
    /// // Object 0 is the floor; there is no object 99.
    /// assert!(system.radiance_at(&b, 0, DVec3::new(0.0, -1.0, 0.5)).unwrap().min_element() > 0.0);
    /// assert!(system.radiance_at(&b, 99, DVec3::ZERO).is_none());
    /// ```
    #[must_use]
    pub fn radiance_at(&self, radiosity: &[DVec3], object: usize, point: DVec3) -> Option<DVec3> {
        let first = (*self.mesh.first_patch.get(object)?)?;
        let n = self.mesh.subdivisions;
        let base = &self.mesh.patches[first];
        let (u, v) = (base.edge_u * n as f64, base.edge_v * n as f64);
        // Coordinates in the quad's (non-orthogonal) basis by the dual basis.
        let normal = u.cross(v);
        let offset = point - base.corner;
        let a = offset.cross(v).dot(normal) / normal.length_squared();
        let b = u.cross(offset).dot(normal) / normal.length_squared();
        let cell = |x: f64| (x * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
        let (ga, gb) = (cell(a), cell(b));
        let (a0, b0) = (ga.floor() as usize, gb.floor() as usize);
        let (a1, b1) = ((a0 + 1).min(n - 1), (b0 + 1).min(n - 1));
        let (fa, fb) = (ga - a0 as f64, gb - b0 as f64);
        let at = |ia: usize, ib: usize| radiosity[first + ib * n + ia];
        let value =
            (at(a0, b0) * (1.0 - fa) + at(a1, b0) * fa) * (1.0 - fb) + (at(a0, b1) * (1.0 - fa) + at(a1, b1) * fa) * fb;
        Some(value / PI)
    }

    /// An image of the solution seen from the scene's camera (one ray per pixel centre;
    /// unmeshed objects and the background are black: radiosity has no paths through them).
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::{experiments::cornell_system, radiosity::Solver};
    /// let (scene, system) = cornell_system(2, 1).unwrap();
    /// let b = system.solve(Solver::GaussSeidel, 20).pop().unwrap();
    /// let image = system.render(&scene, &b, 8, 6);
    /// assert_eq!(image.pixels.len(), 48);
    /// assert!(image.pixels.iter().any(|p| p.max_element() > 0.0));
    /// ```
    #[must_use]
    pub fn render(&self, scene: &Scene, radiosity: &[DVec3], width: u32, height: u32) -> Image {
        let frame = CameraFrame::new(scene.camera());
        let aspect = f64::from(width) / f64::from(height);
        let pixels = (0..height)
            .into_par_iter()
            .flat_map_iter(|y| {
                (0..width)
                    .map(|x| {
                        let ray = frame.ray(
                            (f64::from(x) + 0.5) / f64::from(width),
                            (f64::from(y) + 0.5) / f64::from(height),
                            aspect,
                        );
                        scene
                            .closest_hit(&ray, 0.0, f64::INFINITY)
                            .and_then(|hit| self.radiance_at(radiosity, hit.object, hit.point))
                            .unwrap_or(DVec3::ZERO)
                    })
                    .collect::<Vec<_>>()
            })
            .collect();
        Image { width, height, pixels }
    }
}

/// The fraction of the `samples²` grid points of `source` that `point` sees unoccluded.
fn visible_fraction(scene: &Scene, point: DVec3, normal: DVec3, source: &Patch, samples: usize) -> f64 {
    let seen = source
        .grid(samples)
        .filter(|&y| {
            let to = y - point;
            let distance = to.length();
            let dir = to / distance;
            let ray = Ray { origin: spawn_origin::<f64>(point, normal, dir), dir };
            !scene.occluded(&ray, 0.0, distance * (1.0 - 1e-6))
        })
        .count();
    seen as f64 / (samples * samples) as f64
}

/// A radiosity solver.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{experiments::cornell_system, radiosity::Solver};
/// // Jacobi and Gauss–Seidel reach one fixed point.
/// let (_, system) = cornell_system(2, 1).unwrap();
/// let last = |solver| system.solve(solver, 60).pop().unwrap();
/// let (jacobi, gauss_seidel) = (last(Solver::Jacobi), last(Solver::GaussSeidel));
/// assert!(jacobi.iter().zip(&gauss_seidel).all(|(a, b)| (*a - *b).abs().max_element() < 1e-6));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Solver {
    /// Every patch gathers from the previous sweep's radiosities.
    Jacobi,
    /// Every patch gathers from the newest radiosities (in place).
    GaussSeidel,
    /// Progressive refinement: shoot the largest unshot power (Southwell iteration).
    Southwell,
}

impl Solver {
    /// All three, in the order the plots use.
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::radiosity::Solver;
    /// assert_eq!(Solver::ALL.len(), 3);
    /// ```
    pub const ALL: [Solver; 3] = [Solver::Jacobi, Solver::GaussSeidel, Solver::Southwell];

    /// Display name.
    ///
    /// # Examples
    /// ```
    /// use hw3::q5_effect_tables::radiosity::Solver;
    /// assert_eq!(Solver::ALL.map(Solver::name), ["Jacobi", "Gauss–Seidel", "progressive (Southwell)"]);
    /// ```
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Solver::Jacobi => "Jacobi",
            Solver::GaussSeidel => "Gauss–Seidel",
            Solver::Southwell => "progressive (Southwell)",
        }
    }
}

/// Relative error `max_i |B_i − B*_i| / max_i B*_i` (over channels) of each solution in `history`.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{experiments::cornell_system, radiosity::{Solver, relative_errors}};
/// let (_, system) = cornell_system(2, 1).unwrap();
/// let reference = system.solve(Solver::GaussSeidel, 60).pop().unwrap();
/// let errors = relative_errors(&system.solve(Solver::Jacobi, 10), &reference);
/// assert!(errors[10] < 0.1 * errors[0]);
/// ```
#[must_use]
pub fn relative_errors(history: &[Vec<DVec3>], reference: &[DVec3]) -> Vec<f64> {
    let scale = reference.iter().map(|b| b.max_element()).fold(0.0, f64::max);
    history
        .iter()
        .map(|b| b.iter().zip(reference).map(|(x, y)| (*x - *y).abs().max_element()).fold(0.0, f64::max) / scale)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::catalogue::{CornellContents, cornell_box, furnace_box};

    #[test]
    fn point_to_polygon_matches_the_disc_and_the_closed_cube() {
        // From any floor point of a closed cube the five other faces sum to 1.
        let faces = [
            [DVec3::new(-1., -1., 1.), DVec3::new(1., -1., 1.), DVec3::new(1., 1., 1.), DVec3::new(-1., 1., 1.)],
            [DVec3::new(-1., -1., -1.), DVec3::new(-1., -1., 1.), DVec3::new(-1., 1., 1.), DVec3::new(-1., 1., -1.)],
            [DVec3::new(1., -1., -1.), DVec3::new(1., -1., 1.), DVec3::new(1., 1., 1.), DVec3::new(1., 1., -1.)],
            [DVec3::new(-1., -1., -1.), DVec3::new(1., -1., -1.), DVec3::new(1., -1., 1.), DVec3::new(-1., -1., 1.)],
            [DVec3::new(-1., 1., -1.), DVec3::new(1., 1., -1.), DVec3::new(1., 1., 1.), DVec3::new(-1., 1., 1.)],
        ];
        let point = DVec3::new(0.3, -0.2, -1.0);
        let sum: f64 = faces.iter().map(|f| point_to_polygon(point, DVec3::Z, f)).sum();
        assert!((sum - 1.0).abs() < 1e-12, "{sum}");
        // The opposite face (2 × 2 at distance 2) from the floor's centre: four 1 × 1 rectangles with
        // a corner above the point, each (1/2π)·2·X/√(1+X²)·atan(Y/√(1+X²)) at X = Y = 1/2.
        let x: f64 = 0.5;
        let quarter = 2.0 * x / (1.0 + x * x).sqrt() * (x / (1.0 + x * x).sqrt()).atan() / (2.0 * PI);
        let top = point_to_polygon(DVec3::new(0.0, 0.0, -1.0), DVec3::Z, &faces[0]);
        assert!((top - 4.0 * quarter).abs() < 1e-14, "{top}");
        // A polygon behind the tangent plane contributes nothing.
        assert_eq!(point_to_polygon(DVec3::new(0.0, 0.0, 1.5), DVec3::Z, &faces[0]), 0.0);
    }

    #[test]
    fn white_furnace_closed_box_matches_the_analytic_radiance() {
        // Every wall emits L_e = 1 and reflects ρ = 0.6: L = L_e/(1 − ρ) = 2.5 everywhere.
        let scene = furnace_box(DVec3::splat(0.6)).unwrap();
        let mut mesh = Mesh::new(&scene, 3).unwrap();
        for patch in &mut mesh.patches {
            patch.emission = DVec3::splat(PI);
        }
        let system = System::new(&scene, mesh, 2).unwrap();
        for row in &system.form_factors {
            assert!((row.iter().sum::<f64>() - 1.0).abs() < 1e-10);
        }
        let history = system.solve(Solver::GaussSeidel, 80);
        let last = history.last().unwrap();
        for (patch, b) in system.mesh.patches.iter().zip(last) {
            let radiance = system.radiance_at(last, patch.object, patch.point(0.5, 0.5)).unwrap();
            assert!((radiance.x / 2.5 - 1.0).abs() < 0.01, "{radiance}");
            assert!((b.x / PI / 2.5 - 1.0).abs() < 0.01, "{b}");
        }
    }

    #[test]
    fn solvers_reach_the_same_fixed_point_and_gauss_seidel_is_faster_than_jacobi() {
        let scene = cornell_box(true, CornellContents::Block).unwrap();
        let system = System::new(&scene, Mesh::new(&scene, 2).unwrap(), 1).unwrap();
        let reference = system.solve(Solver::GaussSeidel, 100).pop().unwrap();
        let errors: Vec<Vec<f64>> =
            Solver::ALL.iter().map(|&s| relative_errors(&system.solve(s, 12), &reference)).collect();
        for e in &errors {
            assert!(e[12] < 1e-3, "{e:?}");
        }
        assert!(errors[1][8] < errors[0][8], "Gauss–Seidel beats Jacobi");
    }

    #[test]
    fn zero_counts_and_patchless_scenes_are_typed_errors() {
        let scene = cornell_box(true, CornellContents::Block).unwrap();
        assert_eq!(Mesh::new(&scene, 0), Err(RadiosityError::ZeroCount { name: "subdivisions" }));
        let mesh = Mesh::new(&scene, 1).unwrap();
        assert_eq!(System::new(&scene, mesh, 0), Err(RadiosityError::ZeroCount { name: "samples" }));
        let ball = crate::render::scene::Object::sphere(
            crate::geometry::Sphere::new(DVec3::ZERO, 1.0).unwrap(),
            Material::Diffuse { albedo: DVec3::splat(0.5) },
        );
        let only_spheres = Scene::new(*scene.camera(), vec![ball], vec![], None, DVec3::ZERO).unwrap();
        assert_eq!(Mesh::new(&only_spheres, 2), Err(RadiosityError::NoPatches));
    }
}
