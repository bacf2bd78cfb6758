//! Oracle tests for every method (see the chapter's "tests" section).

use super::irradiance::{Irradiance, Method};
use super::maps::{AnalyticMap, Term};
use super::{Probe, ProbeFormat, fibonacci_normals, horizontal_camera, study};
use glam::DVec3;

fn oracle_maps() -> Vec<(&'static str, AnalyticMap)> {
    let axis = DVec3::new(0.3, -0.5, 0.8).normalize();
    vec![
        ("constant", AnalyticMap::constant(1.0)),
        ("linear", AnalyticMap::new(vec![Term::Linear { a: 1.0, b: 0.9, axis }])),
        ("quadratic", AnalyticMap::new(vec![Term::Quadratic { axis }])),
        ("hemisphere", AnalyticMap::sky()),
        ("lobe", AnalyticMap::new(vec![Term::ClampedLobe { axis }])),
        ("overcast", AnalyticMap::new(vec![Term::Overcast { zenith: 1.0, axis: DVec3::Z }])),
        ("cap15", AnalyticMap::new(vec![Term::Cap { radiance: 1.0, centre: DVec3::new(1.0, 0.2, 0.1).normalize(), half_angle: 15f64.to_radians() }])),
    ]
}

#[test]
fn measure() {
    let normals = fibonacci_normals(64);
    for size in [64, 128] {
        for (name, map) in oracle_maps() {
            let probe = Probe::from_map(&map, ProbeFormat::MirrorBall, size, horizontal_camera()).unwrap();
            let prepared = Irradiance::new(&probe);
            let mut line = format!("{size} {name:>10}");
            for method in [Method::Unweighted, Method::Weighted, Method::Sh9] {
                let e = study::method_error(&map, &prepared, method, 1, &[0], &normals);
                line += &format!("  {}: {:.4}/{:.4}", method.name(), e.mean_percent, e.max_percent);
            }
            for method in [Method::Uniform, Method::Cosine, Method::Map, Method::Mis] {
                let e = study::method_error(&map, &prepared, method, 256, &[1,2,3,4,5,6,7,8], &normals[..16]);
                line += &format!("  {}: {:.3}/{:.3}", method.name(), e.mean_percent, e.max_percent);
            }
            println!("{line}");
        }
    }
}
