//! The photon tracer's tests: furnace, flux, determinism, errors, bias correction, materials, caustics.

use crate::render::bsdf::{brdf, dielectric_split};
use crate::render::catalogue::furnace_sphere;
use crate::render::photon::*;
use crate::render::sampling::{Sampler, fibonacci_sphere, phong_direction};
use crate::render::{
    camera::Camera,
    scene::{Material, Object, PointLight, Scene},
};
use glam::DVec3;
use hw3_core::geometry::{Ray, Sphere};
use std::f64::consts::PI;

fn closed_sphere(albedo: f64, intensity: f64) -> Scene {
    furnace_sphere(albedo, intensity).unwrap()
}

/// White furnace: inside a closed unit sphere of albedo ρ with a point light `I` at the
/// centre, every point receives `E = Φ/(A(1 − ρ)) = I/(1 − ρ)` (direct `I/r²` plus the
/// geometric series of uniform interreflection). The cap within chord distance r of a sphere
/// has area exactly πr² (Archimedes), so the disc assumption adds no curvature bias. The noise
/// left is the count of photons Russian roulette keeps: with 2·10⁵ photons the indirect map
/// holds ≥ 8·10⁴, a relative spread ≈ 1/√(8·10⁴) ≈ 0.35 % (measured over seeds 1–4 at
/// 6·10⁴ photons: within 1.3 %, as that size predicts); the 1000 query points at k = 100
/// cover the sphere about once, so the kNN estimate adds little on top: tolerance 1 %.
#[test]
fn photon_map_furnace_gives_the_analytic_irradiance_within_one_percent() {
    for albedo in [0.3, 0.7] {
        let intensity = 2.0;
        let maps = trace_photons(&closed_sphere(albedo, intensity), 200_000, 5).unwrap();
        let points = fibonacci_sphere(1000);
        let mean = points.iter().map(|&p| maps.all().irradiance(p, 100).unwrap().x).sum::<f64>() / 1000.0;
        let exact = intensity / (1.0 - albedo);
        assert!((mean / exact - 1.0).abs() < 0.01, "ρ = {albedo}: {mean} vs {exact}");
        // The indirect map alone carries the interreflected part ρ/(1 − ρ) · I.
        let indirect = points.iter().map(|&p| maps.indirect.irradiance(p, 100).unwrap().x).sum::<f64>() / 1000.0;
        let exact_indirect = intensity * albedo / (1.0 - albedo);
        assert!((indirect / exact_indirect - 1.0).abs() < 0.01, "ρ = {albedo}: {indirect}");
        assert!(maps.caustic.is_empty(), "no specular surface, no caustic photon");
    }
}

/// Emission carries the light's flux: inside a closed grey sphere every emitted photon lands
/// once before any bounce, so the first-hit powers (the `all` map less the `indirect` one)
/// sum to `Φ = πLA` for a quad light and `Φ = 4πI` for a point light, per channel, to
/// rounding.
#[test]
fn first_hit_powers_sum_to_the_light_flux() {
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.5), DVec3::ZERO, 40.0);
    let grey = Object::sphere(Sphere::new(DVec3::ZERO, 5.0).unwrap(), Material::Diffuse { albedo: DVec3::splat(0.5) });
    let radiance = DVec3::new(1.0, 2.0, 3.0);
    let panel = Object::quad(
        DVec3::new(-0.5, 1.0, -0.5),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 2.0),
        Material::Emitter { radiance },
    );
    let intensity = DVec3::new(0.25, 0.5, 1.0);
    let lamp = PointLight { position: DVec3::ZERO, intensity };
    let cases = [(vec![grey, panel], vec![], radiance * (PI * 2.0)), (vec![grey], vec![lamp], intensity * (4.0 * PI))];
    for (objects, lights, flux) in cases {
        let scene = Scene::new(camera, objects, lights, None, DVec3::ZERO).unwrap();
        let maps = trace_photons(&scene, 5000, 3).unwrap();
        let power = |photons: &[Photon]| photons.iter().map(|p| p.power).sum::<DVec3>();
        let direct = power(maps.photons()) - power(maps.indirect.photons());
        assert!(((direct - flux) / flux).abs().max_element() < 1e-9, "{direct} vs {flux}");
        assert_eq!(maps.photons().len() - maps.indirect.len(), 5000, "one first hit per photon");
    }
}

#[test]
fn traces_are_identical_for_one_and_two_threads() {
    let scene = crate::render::catalogue::cornell_mirror().unwrap();
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| trace_photons(&scene, 10_000, 9).unwrap())
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.photons(), two.photons());
    assert_eq!(one.caustic.photons(), two.caustic.photons());
    assert!(!one.caustic.is_empty(), "the mirror makes caustic photons");
}

#[test]
fn bad_counts_and_neighbour_numbers_are_typed_errors() {
    let scene = closed_sphere(0.5, 1.0);
    assert_eq!(trace_photons(&scene, 0, 1).unwrap_err(), PhotonError::PhotonCount(0));
    assert_eq!(trace_photons(&scene, MAX_PHOTONS + 1, 1).unwrap_err(), PhotonError::PhotonCount(MAX_PHOTONS + 1));
    let dark = closed_sphere(0.5, 0.0);
    assert_eq!(trace_photons(&dark, 10, 1).unwrap_err(), PhotonError::NoLight);
    let maps = trace_photons(&scene, 100, 1).unwrap();
    let stored = maps.all().len();
    for k in [0, 1] {
        assert_eq!(maps.all().irradiance(DVec3::Z, k).unwrap_err(), PhotonError::NeighbourCount(k));
    }
    assert_eq!(
        maps.all().irradiance(DVec3::Z, stored + 1).unwrap_err(),
        PhotonError::TooFewPhotons { requested: stored + 1, stored }
    );
    assert!(maps.all().irradiance(DVec3::Z, stored).is_ok());
    let empty = PhotonMap::new(vec![]);
    assert_eq!(empty.irradiance(DVec3::Z, 2).unwrap_err(), PhotonError::TooFewPhotons { requested: 2, stored: 0 });
}

/// Many photons sharing coordinates (a median split cannot separate them): 5000 photons at one
/// point plus a ring around it: the k nearest are found, and a query whose k nearest all
/// coincide with it is a typed error, not an infinite irradiance; a query point that is not
/// finite is refused.
#[test]
fn duplicate_photon_positions_are_handled() {
    let photon = |position| Photon { position, direction: DVec3::NEG_Z, normal: DVec3::Z, power: DVec3::ONE };
    let mut photons = vec![photon(DVec3::ZERO); 5000];
    photons.extend((0..100).map(|i| {
        let angle = f64::from(i) * 2.0 * PI / 100.0;
        photon(DVec3::new(angle.cos(), angle.sin(), 0.0))
    }));
    let map = PhotonMap::new(photons);
    assert_eq!(map.irradiance(DVec3::ZERO, 100).unwrap_err(), PhotonError::CoincidentPhotons(100));
    // From 2 units away the 5000 duplicates are the nearest; the 5001st is on the ring.
    let (nearest, r2) = map.nearest(DVec3::new(0.0, 0.0, 2.0), 5001).unwrap();
    assert_eq!(nearest.iter().filter(|p| p.position == DVec3::ZERO).count(), 5000);
    assert!((r2 - 5.0).abs() < 1e-12);
    let white = Material::Diffuse { albedo: DVec3::ONE };
    let gather = Gather::new(10, 0.5).unwrap();
    for point in [DVec3::NAN, DVec3::new(0.0, f64::INFINITY, 0.0)] {
        assert_eq!(map.irradiance(point, 10).unwrap_err(), PhotonError::QueryPoint);
        assert_eq!(map.radiance_gathered(&white, point, DVec3::Z, DVec3::Z, gather), DVec3::ZERO);
    }
}

/// The (k−1)/(πr²) estimate is unbiased for uniformly scattered photons; k/(πr²) is high by
/// k/(k−1). 400 independent maps of 2000 unit photons on the unit square (density 2000),
/// queried at the centre with k = 4: mean of (k−1) form within 3σ of 2000, k form ≈ 4/3 high.
#[test]
fn bias_correction_removes_the_k_over_k_minus_one_factor() {
    let k = 4;
    let trials = 400;
    let mut corrected = 0.0;
    for trial in 0..trials {
        let mut sampler = Sampler::new(17, trial, 0);
        let photons = (0..2000)
            .map(|_| Photon {
                position: DVec3::new(sampler.uniform(), sampler.uniform(), 0.0),
                direction: DVec3::NEG_Z,
                normal: DVec3::Z,
                power: DVec3::ONE,
            })
            .collect();
        corrected += PhotonMap::new(photons).irradiance(DVec3::new(0.5, 0.5, 0.0), k).unwrap().x;
    }
    let mean = corrected / trials as f64;
    // Var of (k−1)/(πr²) is λ²/(k−2): std of the mean = 2000/√(2·400) ≈ 71.
    assert!((mean - 2000.0).abs() < 3.0 * 71.0, "corrected {mean}");
    let uncorrected = mean * k as f64 / (k - 1) as f64;
    assert!((uncorrected - 2000.0).abs() > 3.0 * 71.0, "k/(πr²) would be visibly high: {uncorrected}");
}

#[test]
fn phong_directions_follow_the_lobe() {
    let axis = DVec3::new(0.0, 0.6, 0.8);
    let mut sampler = Sampler::new(3, 0, 0);
    let exponent = 20.0;
    let n = 20_000;
    let mean: f64 =
        (0..n).map(|_| phong_direction(axis, exponent, sampler.uniform(), sampler.uniform()).dot(axis)).sum::<f64>()
            / f64::from(n);
    // E[cosα] = (n+1)/(n+2) for the density (n+1)/(2π) cosⁿα.
    assert!((mean - 21.0 / 22.0).abs() < 2e-3, "{mean}");
}

/// Directional albedo `∫ f_r(ω_o, ω_i) cosθ_i dω_i` of a diffuse or glossy material at
/// incidence angle `theta` (radians), by the midpoint rule in polar coordinates about the
/// mirror direction, where the Phong lobe is narrow (`steps` angles from it × 256 azimuths).
fn directional_albedo(material: &Material, theta: f64, steps: usize) -> f64 {
    let normal = DVec3::Z;
    let to_eye = DVec3::new(theta.sin(), 0.0, theta.cos());
    let mirror = hw3_core::geometry::sphere::reflect::<f64>(-to_eye, normal);
    let (tangent, bitangent) = mirror.any_orthonormal_pair();
    let azimuths = 256;
    let (d_alpha, d_phi) = (PI / steps as f64, 2.0 * PI / f64::from(azimuths));
    let mut total = 0.0;
    for i in 0..steps {
        let alpha = (i as f64 + 0.5) * d_alpha;
        for j in 0..azimuths {
            let phi = (f64::from(j) + 0.5) * d_phi;
            let dir =
                tangent * (alpha.sin() * phi.cos()) + bitangent * (alpha.sin() * phi.sin()) + mirror * alpha.cos();
            let cosine = dir.dot(normal);
            if cosine > 0.0 {
                total += brdf(material, to_eye, dir, normal).x * cosine * alpha.sin() * d_alpha * d_phi;
            }
        }
    }
    total
}

/// Energy conservation, which Russian roulette relies on (a survival probability is an
/// albedo): every material reflects at most what arrives. Diffuse: exactly its albedo. The
/// normalised Phong lobe: exactly `kd + ks` at normal incidence (the lobe lies inside the
/// hemisphere), less towards grazing where the horizon clips it, for exponents 1 to 10⁴.
/// Glass: Fresnel reflectance plus the transmittance computed from the transmission
/// amplitudes, `T = (n₂cosθ_t)/(n₁cosθ_i)·(t_s² + t_p²)/2`, is 1 (from either side).
#[test]
fn every_material_reflects_at_most_what_arrives() {
    let diffuse = Material::Diffuse { albedo: DVec3::splat(0.8) };
    for degrees in [0.0, 30.0, 60.0, 85.0] {
        let albedo = directional_albedo(&diffuse, f64::to_radians(degrees), 400);
        // Around the mirror direction the hemisphere's edge cuts cells: 1e-3 is quadrature.
        assert!((albedo - 0.8).abs() < 2e-3, "diffuse at {degrees}°: {albedo}");
    }
    for exponent in [1.0, 10.0, 100.0, 1e4] {
        let glossy = Material::Glossy { diffuse: DVec3::splat(0.2), specular: DVec3::splat(0.8), exponent };
        let normal_incidence = directional_albedo(&glossy, 0.0, 2000);
        assert!((normal_incidence - 1.0).abs() < 2e-3, "n = {exponent}: {normal_incidence}");
        let mut previous = normal_incidence;
        for degrees in [30.0, 60.0, 85.0] {
            let albedo = directional_albedo(&glossy, f64::to_radians(degrees), 2000);
            assert!(albedo <= 1.0 + 2e-3 && albedo <= previous + 2e-3, "n = {exponent} at {degrees}°: {albedo}");
            previous = albedo;
        }
    }
    let hit = crate::render::scene::Hit { t: 1.0, point: DVec3::ZERO, normal: DVec3::Z, object: 0 };
    for index in [1.0, 1.33, 1.5, 2.4] {
        for degrees in [0.0, 20.0, 40.0, 70.0, 89.0] {
            for inside in [false, true] {
                let theta = f64::to_radians(degrees);
                let side = if inside { 1.0 } else { -1.0 };
                let ray = Ray { origin: DVec3::ZERO, dir: DVec3::new(theta.sin(), 0.0, side * theta.cos()) };
                let split = dielectric_split(&ray, &hit, index);
                let (n1, n2) = if inside { (index, 1.0) } else { (1.0, index) };
                let transmitted = split.refracted.map_or(0.0, |refracted| {
                    let (cos_i, cos_t) = (theta.cos(), refracted.dir.z.abs());
                    let t_s = 2.0 * n1 * cos_i / (n1 * cos_i + n2 * cos_t);
                    let t_p = 2.0 * n1 * cos_i / (n2 * cos_i + n1 * cos_t);
                    n2 * cos_t / (n1 * cos_i) * (t_s * t_s + t_p * t_p) / 2.0
                });
                let sum = split.reflectance + transmitted;
                assert!((sum - 1.0).abs() < 1e-12, "n = {index}, {degrees}°, inside {inside}: R + T = {sum}");
            }
        }
    }
}

/// Aimed photons carry exactly the flux into the cone: a point light at the centre of a
/// closed grey sphere (radius 5) and a glass ball (radius 1) 3 units away. Every direction
/// in the ball's cone (half-angle asin(1/3)) hits the ball, glass absorbs nothing and a ray
/// leaving a sphere is never totally reflected, so every photon lands on the shell, and
/// their powers add up to `I · 2π(1 − cos α)` to rounding.
#[test]
fn caustic_photons_carry_the_flux_into_the_target_cone() {
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.5), DVec3::ZERO, 40.0);
    let shell = Object::sphere(Sphere::new(DVec3::ZERO, 5.0).unwrap(), Material::Diffuse { albedo: DVec3::splat(0.5) });
    let ball = Object::sphere(Sphere::new(DVec3::new(0.0, 3.0, 0.0), 1.0).unwrap(), Material::Glass { index: 1.5 });
    let intensity = DVec3::new(1.0, 2.0, 3.0);
    let lamp = PointLight { position: DVec3::ZERO, intensity };
    let scene = Scene::new(camera, vec![shell, ball], vec![lamp], None, DVec3::ZERO).unwrap();
    let map = trace_caustic_photons(&scene, 20_000, 4).unwrap();
    assert_eq!(map.len(), 20_000, "every aimed photon is stored once");
    let cos_alpha = (1.0 - 1.0 / 9.0f64).sqrt();
    let flux = intensity * (2.0 * PI * (1.0 - cos_alpha));
    let stored: DVec3 = map.photons().iter().map(|p| p.power).sum();
    assert!(((stored - flux) / flux).abs().max_element() < 1e-9, "{stored} vs {flux}");
    let none = Scene::new(camera, vec![shell], vec![lamp], None, DVec3::ZERO).unwrap();
    assert!(trace_caustic_photons(&none, 20_000, 4).unwrap().is_empty(), "no glass, nothing traced");
    assert_eq!(trace_caustic_photons(&scene, 0, 4).unwrap_err(), PhotonError::PhotonCount(0));
}

/// Aiming changes the noise, not the answer: on the `caustic` scene (a quad light, whose
/// aimed photons carry `L A cos θ_l Ω / (p N)`) the total caustic power stored by
/// [`trace_caustic_photons`] equals that of the untargeted [`trace_photons`]' caustic map,
/// whose photons each carry `Φ/N` and of which a binomial number land: within 4 of that
/// count's standard deviations.
#[test]
fn aimed_and_untargeted_caustic_maps_carry_the_same_power() {
    let scene = crate::render::catalogue::glass_ball_caustic().unwrap();
    let aimed: f64 = trace_caustic_photons(&scene, 20_000, 5).unwrap().photons().iter().map(|p| p.power.x).sum();
    let maps = trace_photons(&scene, 200_000, 6).unwrap();
    let caustic = maps.caustic.photons();
    let each = caustic[0].power.x;
    let untargeted = each * caustic.len() as f64;
    let sigma = each * (caustic.len() as f64).sqrt();
    assert!((aimed - untargeted).abs() < 4.0 * sigma, "aimed {aimed}, untargeted {untargeted} ± {sigma}");
}

/// A caustic in the caustic map: a glass ball (n = 1.5, radius 1, focal length 1.5 from its
/// centre) over a white floor, lit by a point light 10 units up. Under the ball the caustic
/// map's irradiance exceeds the unobstructed direct irradiance `I/h²` fifty times over (the
/// ball gathers the light of its cross-section π into a small spot), while in the open
/// floor beside it the caustic map is empty of photons nearby: only `LS+D` photons are in it.
#[test]
fn a_glass_ball_focuses_photons_into_the_caustic_map() {
    let camera = Camera::looking_at(DVec3::new(0.0, 3.0, 6.0), DVec3::ZERO, 40.0);
    let floor = Object::quad(
        DVec3::new(-10.0, 0.0, 10.0),
        DVec3::new(20.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -20.0),
        Material::Diffuse { albedo: DVec3::splat(0.5) },
    );
    let ball = Object::sphere(Sphere::new(DVec3::new(0.0, 1.5, 0.0), 1.0).unwrap(), Material::Glass { index: 1.5 });
    let intensity = 100.0;
    let lamp = PointLight { position: DVec3::new(0.0, 11.5, 0.0), intensity: DVec3::splat(intensity) };
    let scene = Scene::new(camera, vec![floor, ball], vec![lamp], None, DVec3::ZERO).unwrap();
    let maps = trace_photons(&scene, 100_000, 2).unwrap();
    let open_floor = intensity / (11.5 * 11.5);
    let focus = maps.caustic.irradiance(DVec3::ZERO, 50).unwrap().x;
    // Measured 351× (seed 2, k = 50); a ball without focusing would leave only its shadow.
    assert!(focus > 50.0 * open_floor, "caustic {focus} vs open floor {open_floor}");
    let (_, r2) = maps.caustic.nearest(DVec3::new(6.0, 0.0, 0.0), 2).unwrap();
    assert!(r2 > 1.0, "no caustic photon within 1 unit of a point 6 units from the ball");
}
