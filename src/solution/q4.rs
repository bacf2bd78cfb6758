//! Q4 worked: the irradiance of the variant's linear sky as the sum of its two closed-form terms,
//! then the mirror ball's blind cone and the share of irradiance it removes.

use super::render::{num, operand, vector};
use super::{Section, SolutionError, Step, Value, setting};
use crate::checker::Variant;
use crate::q4_light_probe::blind_spot;
use crate::q4_light_probe::maps::{AnalyticMap, Term};
use glam::DVec3;
use std::f64::consts::PI;

pub(super) fn sections(variant: &Variant) -> Result<Vec<Section>, SolutionError> {
    let s = setting::q4(variant)?;
    let distance_error = || SolutionError::Statement { question: "q4", seed: variant.seed, what: "a distance D > R" };
    let tilt = s.tilt_deg.to_radians();
    let normal = DVec3::new(tilt.sin(), 0.0, tilt.cos());
    let constant = Term::Constant { radiance: s.a }.irradiance(normal);
    let gradient = Term::Linear { a: 0.0, b: s.b, axis: DVec3::Z }.irradiance(normal);
    let irradiance = AnalyticMap::new(vec![Term::Linear { a: s.a, b: s.b, axis: DVec3::Z }]).irradiance(normal);
    let a = vec![
        Step::work(format!(
            "n = (sin θ, 0, cos θ) with θ = {}°: n = {}, n_z = {}",
            num(s.tilt_deg),
            vector(normal.to_array()),
            num(normal.z)
        )),
        Step::work(format!(
            "L = {} {} {} w_z is never negative (A ≥ |B|), so no clamping: E = A ∫ max(0, n·w) dw + B ∫ w_z max(0, n·w) dw \
             = πA + (2π/3) B n_z",
            num(s.a),
            if s.b < 0.0 { '-' } else { '+' },
            num(s.b.abs())
        )),
        Step::work(format!("πA = π · {} = {}", num(s.a), num(constant))),
        Step::work(format!("(2π/3) B n_z = (2π/3) · {} · {} = {}", operand(s.b), operand(normal.z), num(gradient))),
        Step::answer(
            format!("E = {} + {} = {}", num(constant), operand(gradient), num(irradiance)),
            "q4a.irradiance",
            Value::Number(irradiance),
        ),
    ];

    let d = s.distance_over_radius;
    let gamma = blind_spot::half_angle(d).map_err(|_| distance_error())?;
    let lost = blind_spot::lost_fraction(d, 0.0).map_err(|_| distance_error())?;
    let share = blind_spot::solid_angle(d).map_err(|_| distance_error())? / (4.0 * PI);
    let b = vec![
        Step::work(format!("R/D = 1/{} = {}", num(d), num(1.0 / d))),
        Step::work(format!("γ = arcsin(R/D) = {} rad", num(gamma))),
        Step::answer(
            format!("γ = {} rad · 180/π = {}°", num(gamma), num(gamma.to_degrees())),
            "q4b.blind_half_angle_deg",
            Value::Number(gamma.to_degrees()),
        ),
        Step::work(
            "a normal pointing straight into the cone loses the cone's light, π L sin²γ, out of the uniform map's \
             π L",
        ),
        Step::answer(
            format!("lost fraction = sin²γ = (R/D)² = {}", num(lost)),
            "q4b.lost_fraction",
            Value::Number(lost),
        ),
        Step::work(format!(
            "(not the cone's share of all directions, Ω/4π = 2π(1 - cos γ)/4π = {}: irradiance weights each \
             direction by its cosine)",
            num(share)
        )),
    ];
    Ok(vec![
        Section { title: "(a) the irradiance E(n)".into(), steps: a },
        Section { title: "(b) the blind cone".into(), steps: b },
    ])
}
