//! Scene description: shapes, materials, lights, fog and motion, validated on construction.
//!
//! Everything is `f64`. A [`Scene`] can only be built through [`Scene::new`], which rejects NaN or
//! infinite numbers, negative albedos or densities, degenerate quads and cameras, and an inverted
//! shutter, so the integrators never see input that could turn into a silent NaN.

use super::camera::Camera;
use super::environment::Environment;
use crate::kdtree::{BuildError, KdTree, Walk};
use glam::DVec3;
use hw3_core::geometry::sphere::{first_hit_stable, surface_hit};
use hw3_core::geometry::{InputError, Ray, Sphere, require_finite};
use quads::QuadSet;
use std::sync::Arc;

pub(crate) mod quads;

/// The surface's reflection model. Each material is one letter of Heckbert's path notation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Material {
    /// Lambertian, `f = albedo/π` (letter `D`). Albedo components in `[0, 1]`.
    Diffuse {
        /// Reflectance per RGB channel.
        albedo: DVec3,
    },
    /// Modified Phong (energy-normalised): `f = kd/π + ks (n+2)/(2π) cosⁿα`, with `α` the angle
    /// between the mirror direction and the light (letter `G` when `ks > 0`, plus `D` when
    /// `kd > 0`). Requires `kd + ks ≤ 1` per channel so that the albedo stays ≤ 1.
    Glossy {
        /// Diffuse reflectance.
        diffuse: DVec3,
        /// Specular reflectance.
        specular: DVec3,
        /// Phong exponent `n ≥ 0`.
        exponent: f64,
    },
    /// Perfect mirror, `L_o = reflectance · L_i(reflected)` (letter `S`).
    Mirror {
        /// Reflectance per channel, in `[0, 1]`.
        reflectance: DVec3,
    },
    /// Clear dielectric (glass, water) of refractive index `index` in air: Fresnel reflection
    /// plus Snell refraction, no absorption (letter `S`, like a mirror).
    Glass {
        /// Refractive index, in `[1, 4]`.
        index: f64,
    },
    /// A one-sided emitter that reflects nothing (letter `L`). Only on quads, which are then area
    /// lights sampled by next-event estimation; the emitting side is the one the normal points to.
    Emitter {
        /// Emitted radiance.
        radiance: DVec3,
    },
}

/// A geometric primitive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A sphere whose centre moves linearly: `c(t) = center + velocity · t`.
    Sphere {
        /// Position at time 0.
        sphere: Sphere<f64>,
        /// Velocity (zero for a static sphere).
        velocity: DVec3,
    },
    /// The parallelogram `corner + a·edge_u + b·edge_v`, `a, b ∈ [0, 1]`, normal `edge_u × edge_v`.
    Quad {
        /// One corner.
        corner: DVec3,
        /// First edge.
        edge_u: DVec3,
        /// Second edge.
        edge_v: DVec3,
    },
}

/// A shape with its material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Object {
    /// Geometry.
    pub shape: Shape,
    /// Reflection model.
    pub material: Material,
}

impl Object {
    /// The quad `corner + a·edge_u + b·edge_v` with `material` (validated by [`Scene::new`]).
    #[must_use]
    pub fn quad(corner: DVec3, edge_u: DVec3, edge_v: DVec3, material: Material) -> Self {
        Self { shape: Shape::Quad { corner, edge_u, edge_v }, material }
    }

    /// A static sphere with `material`.
    #[must_use]
    pub fn sphere(sphere: Sphere<f64>, material: Material) -> Self {
        Self { shape: Shape::Sphere { sphere, velocity: DVec3::ZERO }, material }
    }
}

/// An isotropic point light: intensity `I` (W/sr per channel), irradiance `I cosθ / r²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLight {
    /// Position.
    pub position: DVec3,
    /// Radiant intensity per channel (≥ 0).
    pub intensity: DVec3,
}

/// An emitting quad (an object of [`Material::Emitter`] on a [`Shape::Quad`]): one-sided, its
/// radiance leaving the side `edge_u × edge_v` points to. Listed by [`Scene::area_lights`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaLight {
    /// Index of the object in [`Scene::objects`].
    pub object: usize,
    /// One corner.
    pub corner: DVec3,
    /// First edge from the corner.
    pub edge_u: DVec3,
    /// Second edge from the corner.
    pub edge_v: DVec3,
    /// Emitted radiance per channel (≥ 0; possibly black).
    pub radiance: DVec3,
}

impl AreaLight {
    /// The point at `(u, v) ∈ [0, 1]²` of the quad: `corner + u·edge_u + v·edge_v`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_render::render::scene::AreaLight;
    /// let light = AreaLight { object: 0, corner: DVec3::ZERO, edge_u: DVec3::X, edge_v: DVec3::Z, radiance: DVec3::ONE };
    /// assert_eq!(light.point(0.5, 1.0), DVec3::new(0.5, 0.0, 1.0));
    /// ```
    #[must_use]
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.corner + self.edge_u * u + self.edge_v * v
    }
}

/// A homogeneous medium filling all space (the camera is always inside it), with an isotropic
/// phase function `1/(4π)`. Extinction `σ_t = σ_a + σ_s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fog {
    /// Absorption coefficient `σ_a ≥ 0` (per unit length).
    pub sigma_a: f64,
    /// Scattering coefficient `σ_s ≥ 0`.
    pub sigma_s: f64,
}

impl Fog {
    /// Extinction coefficient `σ_t = σ_a + σ_s`.
    #[must_use]
    pub fn sigma_t(&self) -> f64 {
        self.sigma_a + self.sigma_s
    }
}

/// A complete, validated scene. Build it with [`Scene::new`].
///
/// Equality compares the scene description only (camera, objects, lights, medium, background),
/// not whether ray queries go through a kd-tree: [`Scene::without_kd_tree`] is the same scene.
#[derive(Debug, Clone)]
pub struct Scene {
    camera: Camera,
    objects: Vec<Object>,
    point_lights: Vec<PointLight>,
    fog: Option<Fog>,
    background: DVec3,
    /// Radiance from infinitely far away; replaces `background` for escaping rays when present.
    environment: Option<Arc<Environment>>,
    /// The kd-tree over the spheres (moving ones swept over the shutter) and the prepared quads,
    /// shared by the clones [`Scene::with_camera`] makes; `None` when acceleration was switched
    /// off ([`Scene::without_kd_tree`]).
    acceleration: Option<Arc<Acceleration>>,
}

impl PartialEq for Scene {
    fn eq(&self, other: &Self) -> bool {
        (self.camera, &self.objects, &self.point_lights, self.fog, self.background, &self.environment)
            == (other.camera, &other.objects, &other.point_lights, other.fog, other.background, &other.environment)
    }
}

/// How a scene's closest-hit and shadow queries find its spheres ([`Scene::sphere_queries`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SphereQueries {
    /// Each sphere tested in turn (at most three: cheaper than a walk).
    OneByOne,
    /// Through the kd-tree, by the walk it takes.
    Tree(Walk),
}

/// The ray-query structures of a scene: its spheres in a kd-tree ([`crate::kdtree`]), moving
/// ones bounded by their swept boxes over the shutter interval ([`KdTree::build_moving`]), and its
/// quads (which the tree does not hold) prepared for plane-first rejection ([`quads`]).
#[derive(Debug, Clone)]
struct Acceleration {
    /// The sphere tree, `None` when the scene has no sphere.
    spheres: Option<SphereTree>,
    quads: QuadSet,
}

/// A kd-tree over a scene's spheres.
#[derive(Debug, Clone)]
struct SphereTree {
    tree: KdTree,
    /// Object index of each sphere in the tree, increasing (tree index `k` is object `tree_objects[k]`).
    tree_objects: Vec<usize>,
    /// Each sphere with its velocity when there are at most [`DIRECT_SPHERES`]: closest-hit and
    /// shadow queries then test them one by one, which costs less than a walk down the tree.
    direct: Option<Vec<(Sphere<f64>, DVec3)>>,
}

/// Most spheres that closest-hit and shadow queries test one by one instead of through the tree:
/// on the one-sphere caustic scene a query through the tree took about 345 instructions, one
/// sphere test about 122 (callgrind), so up to three spheres the loop is no dearer.
const DIRECT_SPHERES: usize = 3;

impl SphereTree {
    /// The closest sphere hit with `t ∈ (0, t_max)` at `time` as `(object, t)`, ties to the lowest
    /// index: through the tree, or by the loop of [`Scene::without_kd_tree`] over the spheres,
    /// whose answer the tree reproduces bit for bit.
    fn closest_hit(&self, ray: &Ray<f64>, time: f64, t_max: f64) -> Option<(usize, f64)> {
        let Some(direct) = &self.direct else {
            return self.tree.closest_hit_at(ray, 0.0, t_max, time).map(|(k, t)| (self.tree_objects[k], t));
        };
        let mut best = None;
        for (&object, &(sphere, velocity)) in self.tree_objects.iter().zip(direct) {
            if let Some(t) = first_hit_stable(ray, &position_at(sphere, velocity, time)).filter(|&t| t < t_max) {
                quads::offer(&mut best, object, t);
            }
        }
        best.map(|(t, object)| (object, t))
    }
}

impl Acceleration {
    /// The structures over `objects` for ray times in `shutter`.
    fn build(objects: &[Object], shutter: (f64, f64)) -> Result<Self, InputError> {
        Ok(Self { spheres: SphereTree::build(objects, shutter)?, quads: QuadSet::new(objects) })
    }
}

impl SphereTree {
    /// The tree over the spheres of `objects` for ray times in `shutter`, or `None` when there
    /// is no sphere.
    fn build(objects: &[Object], shutter: (f64, f64)) -> Result<Option<Self>, InputError> {
        let (mut tree_objects, mut spheres, mut velocities) = (Vec::new(), Vec::new(), Vec::new());
        for (index, object) in objects.iter().enumerate() {
            if let Shape::Sphere { sphere, velocity } = object.shape {
                tree_objects.push(index);
                spheres.push(sphere);
                velocities.push(velocity);
            }
        }
        if spheres.is_empty() {
            return Ok(None);
        }
        let tree = KdTree::build_moving(&spheres, &velocities, shutter).map_err(|error| match error {
            BuildError::InvalidSphere { source, .. } => source,
            other => InputError::OutOfRange {
                name: "spheres",
                value: other.to_string(),
                expected: "a set the kd-tree can index",
            },
        })?;
        let direct = (spheres.len() <= DIRECT_SPHERES).then(|| spheres.into_iter().zip(velocities).collect());
        Ok(Some(Self { tree, tree_objects, direct }))
    }
}

/// The closest intersection found along a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Ray parameter (the direction is unit length, so this is a distance).
    pub t: f64,
    /// The point on the surface (reprojected onto it).
    pub point: DVec3,
    /// Unit geometric normal: outward for spheres, `edge_u × edge_v` for quads (not flipped).
    pub normal: DVec3,
    /// Index of the object in [`Scene::objects`].
    pub object: usize,
}

impl Scene {
    /// A validated scene.
    ///
    /// # Errors
    /// [`InputError`] naming the first offending value: non-finite numbers anywhere; a camera
    /// whose view direction is zero or parallel to `up`, a field of view outside `(0°, 180°)`, or a
    /// shutter that closes before it opens; a quad with parallel edges; reflectances outside
    /// `[0, 1]` (or `kd + ks > 1`), negative emission, intensity or fog densities; an emitter on
    /// a sphere; a moving sphere whose box swept over the shutter overflows.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::Sphere;
    /// use hw3_render::render::camera::Camera;
    /// use hw3_render::render::scene::*;
    /// let camera = Camera { eye: DVec3::new(0.0, 0.0, 5.0), look_at: DVec3::ZERO, up: DVec3::Y,
    ///     vfov_degrees: 40.0, shutter: (0.0, 0.0) };
    /// let ball = Object { shape: Shape::Sphere { sphere: Sphere::new(DVec3::ZERO, 1.0).unwrap(),
    ///     velocity: DVec3::ZERO }, material: Material::Diffuse { albedo: DVec3::splat(0.5) } };
    /// let light = PointLight { position: DVec3::new(0.0, 5.0, 5.0), intensity: DVec3::splat(10.0) };
    /// assert!(Scene::new(camera, vec![ball], vec![light], None, DVec3::ZERO).is_ok());
    /// let bad = Camera { vfov_degrees: f64::NAN, ..camera };
    /// assert!(Scene::new(bad, vec![ball], vec![light], None, DVec3::ZERO).is_err());
    /// ```
    pub fn new(
        camera: Camera,
        objects: Vec<Object>,
        point_lights: Vec<PointLight>,
        fog: Option<Fog>,
        background: DVec3,
    ) -> Result<Self, InputError> {
        validate_camera(&camera)?;
        for object in &objects {
            validate_object(object)?;
        }
        for light in &point_lights {
            require_finite::<f64>("light position", light.position)?;
            require_non_negative("light intensity", light.intensity)?;
        }
        if let Some(fog) = fog {
            require_scalar_range("fog sigma_a", fog.sigma_a, 0.0, f64::MAX, "finite and ≥ 0")?;
            require_scalar_range("fog sigma_s", fog.sigma_s, 0.0, f64::MAX, "finite and ≥ 0")?;
        }
        require_non_negative("background", background)?;
        let acceleration = Some(Arc::new(Acceleration::build(&objects, camera.shutter)?));
        Ok(Self { camera, objects, point_lights, fog, background, environment: None, acceleration })
    }

    /// The same scene lit by `environment` too, which escaping rays then see instead of the
    /// background (module [`crate::render::environment`]). The environment was validated when
    /// it was built.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_render::render::{environment::Environment, catalogue};
    /// let scene = catalogue::mirror_spheres(true).unwrap();
    /// let lit = scene.clone().with_environment(Environment::constant(DVec3::ONE).unwrap());
    /// assert!(scene.environment().is_none() && lit.environment().is_some());
    /// ```
    #[must_use]
    pub fn with_environment(self, environment: Environment) -> Self {
        Self { environment: Some(Arc::new(environment)), ..self }
    }

    /// The environment light, if any.
    #[must_use]
    pub fn environment(&self) -> Option<&Environment> {
        self.environment.as_deref()
    }

    /// The same scene with every ray query answered by testing every object (the brute-force
    /// reference that the kd-tree must reproduce bit for bit).
    ///
    /// # Examples
    /// ```
    /// let scene = hw3_render::render::catalogue::clutter_forest(50, 1).unwrap();
    /// assert_eq!(scene.kd_tree_spheres(), 50);
    /// let brute = scene.without_kd_tree();
    /// assert_eq!((brute.kd_tree_spheres(), &brute), (0, &scene));
    /// ```
    #[must_use]
    pub fn without_kd_tree(&self) -> Self {
        Self { acceleration: None, ..self.clone() }
    }

    /// How many spheres the scene's kd-tree holds: every sphere (moving ones by their swept box
    /// over the shutter interval), or 0 after [`Scene::without_kd_tree`]. Quads are never in it.
    #[must_use]
    pub fn kd_tree_spheres(&self) -> usize {
        self.acceleration.as_ref().and_then(|a| a.spheres.as_ref()).map_or(0, |s| s.tree_objects.len())
    }

    /// How closest-hit and shadow queries find the scene's spheres: `None` without spheres (or
    /// after [`Scene::without_kd_tree`]); one by one up to three spheres; else the kd-tree's
    /// [`Walk`] (the coarse-filtered one whenever no sphere moves).
    ///
    /// # Examples
    /// ```
    /// use hw3_render::kdtree::Walk;
    /// use hw3_render::render::{catalogue::by_name, scene::SphereQueries};
    /// assert_eq!(by_name("clutter").unwrap().sphere_queries(), Some(SphereQueries::Tree(Walk::Filtered)));
    /// assert_eq!(by_name("motion").unwrap().sphere_queries(), Some(SphereQueries::OneByOne));
    /// ```
    #[must_use]
    pub fn sphere_queries(&self) -> Option<SphereQueries> {
        let spheres = self.acceleration.as_ref()?.spheres.as_ref()?;
        Some(if spheres.direct.is_some() { SphereQueries::OneByOne } else { SphereQueries::Tree(spheres.tree.walk()) })
    }

    /// The camera.
    #[must_use]
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The objects, in the order given.
    #[must_use]
    pub fn objects(&self) -> &[Object] {
        &self.objects
    }

    /// The point lights.
    #[must_use]
    pub fn point_lights(&self) -> &[PointLight] {
        &self.point_lights
    }

    /// Every emitting quad, in object order (black ones included: callers that weigh lights by
    /// power skip them themselves). Emitters are quads only ([`Scene::new`] refuses an emitting
    /// sphere).
    ///
    /// # Examples
    /// ```
    /// let cornell = hw3_render::render::catalogue::cornell_mirror().unwrap();
    /// assert_eq!(cornell.area_lights().count(), 1);
    /// let light = cornell.area_lights().next().unwrap();
    /// assert_eq!(light.point(0.0, 0.0), light.corner);
    /// ```
    pub fn area_lights(&self) -> impl Iterator<Item = AreaLight> + '_ {
        self.objects.iter().enumerate().filter_map(|(object, o)| match (o.material, o.shape) {
            (Material::Emitter { radiance }, Shape::Quad { corner, edge_u, edge_v }) => {
                Some(AreaLight { object, corner, edge_u, edge_v, radiance })
            }
            _ => None,
        })
    }

    /// The radiance seen along an escaping ray of unit direction `direction`: the environment
    /// if the scene has one ([`Environment::radiance_seen`], read bilinearly), else the constant
    /// background.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_render::render::{environment::Environment, catalogue};
    /// let scene = catalogue::mirror_spheres(true).unwrap();
    /// assert_eq!(scene.escaped_radiance(DVec3::Y), scene.background());
    /// let lit = scene.with_environment(Environment::constant(DVec3::ONE).unwrap());
    /// assert_eq!(lit.escaped_radiance(DVec3::Y), DVec3::ONE);
    /// ```
    #[must_use]
    pub fn escaped_radiance(&self, direction: DVec3) -> DVec3 {
        self.environment().map_or_else(|| self.background(), |environment| environment.radiance_seen(direction))
    }

    /// The medium, if any.
    #[must_use]
    pub fn fog(&self) -> Option<Fog> {
        self.fog
    }

    /// Radiance of rays that leave the scene.
    #[must_use]
    pub fn background(&self) -> DVec3 {
        self.background
    }

    /// The same scene seen from another camera.
    ///
    /// # Errors
    /// [`InputError`] when `camera` is invalid (see [`Scene::new`]).
    pub fn with_camera(&self, camera: Camera) -> Result<Self, InputError> {
        validate_camera(&camera)?;
        Ok(Self { camera, ..self.clone() })
    }

    /// The closest hit with `t` in `(0, t_max)` at time `time` (ties go to the lowest object
    /// index). Spheres are found through the kd-tree (a time outside the shutter the tree was
    /// built for makes it test every sphere), then quads by their planes, skipping those beyond
    /// the closest hit so far; the answer is the brute-force one bit for bit (same solver, same
    /// sphere position, same quad arithmetic, same tie rule).
    #[must_use]
    pub fn closest_hit(&self, ray: &Ray<f64>, time: f64, t_max: f64) -> Option<Hit> {
        let mut best: Option<(f64, usize)> = None;
        match &self.acceleration {
            Some(accel) => {
                if let Some(spheres) = &accel.spheres
                    && let Some((object, t)) = spheres.closest_hit(ray, time, t_max)
                {
                    quads::offer(&mut best, object, t);
                }
                accel.quads.closest(ray, t_max, &mut best);
            }
            None => {
                for (index, object) in self.objects.iter().enumerate() {
                    if let Some(t) = intersect(&object.shape, ray, time).filter(|&t| t < t_max) {
                        quads::offer(&mut best, index, t);
                    }
                }
            }
        }
        best.map(|(t, object)| self.hit_record(ray, time, t, object))
    }

    /// Whether anything blocks the open segment `(0, t_max)` of `ray` at `time` (shadow rays).
    /// The quads are tried first and the first blocker found ends the query.
    #[must_use]
    pub fn occluded(&self, ray: &Ray<f64>, time: f64, t_max: f64) -> bool {
        match &self.acceleration {
            Some(accel) => {
                accel.quads.any_before(ray, t_max)
                    || accel.spheres.as_ref().is_some_and(|spheres| spheres.closest_hit(ray, time, t_max).is_some())
            }
            None => self.objects.iter().any(|object| intersect(&object.shape, ray, time).is_some_and(|t| t < t_max)),
        }
    }

    /// Every object whose surface the ray crosses in `(0, t_max)`, counted once per crossing
    /// surface (a sphere pierced through counts once): the depth complexity of the ray.
    ///
    /// With the kd-tree, the spheres are walked hit by hit (each query starts where the
    /// last hit was), so the cost grows with the number of crossings, not with the scene. Two
    /// spheres whose crossings coincide bit for bit (a duplicated sphere) are then counted once:
    /// the tree reports one sphere per `t`.
    #[must_use]
    pub fn objects_pierced(&self, ray: &Ray<f64>, time: f64, t_max: f64) -> usize {
        let Some(accel) = &self.acceleration else {
            return self
                .objects
                .iter()
                .filter(|object| intersect(&object.shape, ray, time).is_some_and(|t| t < t_max))
                .count();
        };
        let mut pierced: Vec<usize> = Vec::new();
        if let Some(spheres) = &accel.spheres {
            let mut t_min = 0.0;
            while let Some((k, t)) = spheres.tree.closest_hit_at(ray, t_min, t_max, time) {
                if !pierced.contains(&k) {
                    pierced.push(k);
                }
                t_min = t;
            }
        }
        pierced.len() + accel.quads.count_before(ray, t_max)
    }

    fn hit_record(&self, ray: &Ray<f64>, time: f64, t: f64, object: usize) -> Hit {
        match self.objects[object].shape {
            Shape::Sphere { sphere, velocity } => {
                let frame = surface_hit(ray, &position_at(sphere, velocity, time), t);
                Hit { t, point: frame.point, normal: frame.normal, object }
            }
            Shape::Quad { corner, edge_u, edge_v } => {
                let normal = edge_u.cross(edge_v).normalize();
                let raw = ray.at(t);
                // Reprojection onto the plane removes the error of `t`, as for spheres.
                let point = raw - normal * (raw - corner).dot(normal);
                Hit { t, point, normal, object }
            }
        }
    }
}

/// The first hit `t > 0` of `ray` with `shape` at time `time`, or `None`.
///
/// A quad is missed by rays parallel to its plane (including rays lying in it: a grazing ray
/// sees a quad edge-on, which has zero area).
#[must_use]
pub fn intersect(shape: &Shape, ray: &Ray<f64>, time: f64) -> Option<f64> {
    match *shape {
        Shape::Sphere { sphere, velocity } => first_hit_stable(ray, &position_at(sphere, velocity, time)),
        Shape::Quad { corner, edge_u, edge_v } => {
            let n = edge_u.cross(edge_v);
            let denominator = ray.dir.dot(n);
            // Relative test: parallel (or NaN) within rounding is a miss, never a huge `t`.
            if denominator.is_nan() || denominator.abs() <= 1e-12 * n.length() * ray.dir.length() {
                return None;
            }
            let t = (corner - ray.origin).dot(n) / denominator;
            if t.is_nan() || t <= 0.0 {
                return None;
            }
            let offset = ray.at(t) - corner;
            // Barycentric-style coordinates from the dual basis of (edge_u, edge_v).
            let w = n / n.dot(n);
            let a = offset.cross(edge_v).dot(w);
            let b = edge_u.cross(offset).dot(w);
            ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)).then_some(t)
        }
    }
}

/// The sphere at `time`. A static sphere is returned untouched (no `+ 0·t`, which would turn a
/// `−0.0` coordinate into `+0.0`), so the kd-tree and the brute-force loop test the same numbers.
fn position_at(sphere: Sphere<f64>, velocity: DVec3, time: f64) -> Sphere<f64> {
    crate::kdtree::moved(sphere, velocity, time)
}

fn validate_camera(camera: &Camera) -> Result<(), InputError> {
    require_finite::<f64>("camera eye", camera.eye)?;
    require_finite::<f64>("camera look_at", camera.look_at)?;
    require_finite::<f64>("camera up", camera.up)?;
    let forward = camera.look_at - camera.eye;
    let side = forward.cross(camera.up);
    if !(forward.length_squared() > f64::MIN_POSITIVE && side.length_squared() > 1e-20) {
        return Err(InputError::DegenerateDirection {
            name: "camera view direction",
            value: format!("look_at − eye = {forward:?} with up = {:?}", camera.up),
        });
    }
    require_scalar_range("camera vfov_degrees", camera.vfov_degrees, f64::MIN_POSITIVE, 179.0, "in (0°, 179°]")?;
    let (open, close) = camera.shutter;
    require_scalar_range("shutter open", open, f64::MIN, f64::MAX, "finite")?;
    require_scalar_range("shutter close", close, open, f64::MAX, "finite and ≥ open")?;
    Ok(())
}

fn validate_object(object: &Object) -> Result<(), InputError> {
    match object.shape {
        Shape::Sphere { sphere, velocity } => {
            Sphere::new(sphere.center, sphere.radius)?;
            require_finite::<f64>("sphere velocity", velocity)?;
            if matches!(object.material, Material::Emitter { .. }) {
                return Err(InputError::OutOfRange {
                    name: "sphere material",
                    value: "Emitter".into(),
                    expected: "not an emitter (area lights are quads)",
                });
            }
        }
        Shape::Quad { corner, edge_u, edge_v } => {
            require_finite::<f64>("quad corner", corner)?;
            require_finite::<f64>("quad edge_u", edge_u)?;
            require_finite::<f64>("quad edge_v", edge_v)?;
            let area = edge_u.cross(edge_v).length();
            if !(area > 1e-12 * edge_u.length() * edge_v.length() && area.is_finite()) {
                return Err(InputError::DegenerateDirection {
                    name: "quad edges",
                    value: format!("{edge_u:?} × {edge_v:?}"),
                });
            }
        }
    }
    match object.material {
        Material::Diffuse { albedo } => require_unit_interval("diffuse albedo", albedo),
        Material::Mirror { reflectance } => require_unit_interval("mirror reflectance", reflectance),
        Material::Glossy { diffuse, specular, exponent } => {
            require_unit_interval("glossy diffuse", diffuse)?;
            require_unit_interval("glossy specular", specular)?;
            require_unit_interval("glossy diffuse + specular", diffuse + specular)?;
            require_scalar_range("glossy exponent", exponent, 0.0, 1e6, "in [0, 10⁶]")
        }
        Material::Glass { index } => require_scalar_range("glass index", index, 1.0, 4.0, "in [1, 4]"),
        Material::Emitter { radiance } => require_non_negative("emitter radiance", radiance),
    }
}

fn require_scalar_range(
    name: &'static str,
    value: f64,
    low: f64,
    high: f64,
    expected: &'static str,
) -> Result<(), InputError> {
    if !value.is_finite() {
        return Err(InputError::NonFinite { name, value: format!("{value}") });
    }
    if value < low || value > high {
        return Err(InputError::OutOfRange { name, value: format!("{value}"), expected });
    }
    Ok(())
}

fn require_non_negative(name: &'static str, v: DVec3) -> Result<(), InputError> {
    require_finite::<f64>(name, v)?;
    if v.min_element() < 0.0 {
        return Err(InputError::OutOfRange { name, value: format!("{v:?}"), expected: "≥ 0 in every channel" });
    }
    Ok(())
}

fn require_unit_interval(name: &'static str, v: DVec3) -> Result<(), InputError> {
    require_non_negative(name, v)?;
    if v.max_element() > 1.0 {
        return Err(InputError::OutOfRange { name, value: format!("{v:?}"), expected: "in [0, 1] in every channel" });
    }
    Ok(())
}
