//! Q4 variants: irradiance from an analytic sky with a closed form, and the mirror ball's blind spot.

use super::key::{Derivation, Expected, Follows, MalRule, Part, Variant};
use super::policy::Rule;
use crate::q4_light_probe::blind_spot;
use crate::q4_light_probe::maps::{AnalyticMap, Term};
use crate::rng;
use glam::DVec3;
use rand_core::Rng;
use std::f64::consts::PI;

/// The RNG stream of Q4 variants.
const STREAM: u64 = 4;

/// The chapter's sections each part is explained in.
const IRRADIANCE_NOTES: &str = "hw3/q4_light_probe/index.html#oracles";
const BLIND_NOTES: &str = "hw3/q4_light_probe/index.html#the-blind-spot";

fn number(value: f64) -> Expected {
    Expected::Number { value, rtol: 1e-3, atol: 1e-9 }
}

pub(super) fn variant(seed: u64) -> Variant {
    // Seed 0: a sky of radiance 1 + 1·ω_z, a normal tilted 60° from up, a ball seen from 3 radii.
    let (a, b, tilt_deg, distance_over_radius) = if seed == 0 {
        (1.0, 1.0, 60.0, 3.0)
    } else {
        let mut g = rng::seeded(seed, STREAM);
        let mut pick = |n: u64| g.next_u64() % n;
        let a = 1.0 + pick(4) as f64;
        let b = [-1.0, 1.0, 2.0][pick(3) as usize];
        // Radiance is never negative: with A ≥ |B| the sky is ≥ 0 straight down too, so the
        // closed form (which integrates L as given) is the irradiance of a physical sky.
        let a = a.max(f64::abs(b));
        let tilt = [0.0, 30.0, 45.0, 60.0, 90.0, 120.0][pick(6) as usize];
        let d = [2.0, 3.0, 4.0, 5.0, 10.0][pick(5) as usize];
        (a, b, tilt, d)
    };
    let tilt = f64::to_radians(tilt_deg);
    let normal = DVec3::new(tilt.sin(), 0.0, tilt.cos());
    let map = AnalyticMap::new(vec![Term::Linear { a, b, axis: DVec3::Z }]);
    let irradiance = map.irradiance(normal);
    let gamma = blind_spot::half_angle(distance_over_radius).expect("variant distances exceed one radius");
    let lost = blind_spot::lost_fraction(distance_over_radius, 0.0).expect("variant distances exceed one radius");
    let (sign, b_abs) = if b < 0.0 { ('-', -b) } else { ('+', b) };
    let statement = format!(
        "Q4 (variant {seed}). An environment of radiance L(w) = {a} {sign} {b_abs} w_z (z up) lights a diffuse surface.\n\
         (a) the irradiance E(n) = integral of L(w) max(0, n . w) dw for the unit normal n tilted {tilt_deg} degrees \
         from up towards +x;\n\
         (b) a mirrored ball of radius R photographed from distance D = {distance_over_radius} R: the half-angle, \
         in degrees, of the cone of directions the ball cannot show, and the fraction of a uniform environment's \
         irradiance lost for a normal pointing straight into that cone."
    );
    // Without the cosine: ∫ over the hemisphere of L alone, 2πA + πB n_z.
    let no_cosine = 2.0 * PI * a + PI * b * normal.z;
    let parts = vec![
        Part {
            key: "q4a.irradiance",
            prompt: "irradiance E(n)",
            points: 3.0,
            expected: number(irradiance),
            mal_rules: vec![
                MalRule {
                    value: number(no_cosine),
                    message: "the cosine factor max(0, n . w) is missing: that is the integral of L alone",
                    rule: Rule::OtherQuantity,
                },
                MalRule {
                    value: number(irradiance / PI),
                    message: "that is E/π, the outgoing radiance of a white diffuse surface, not the irradiance",
                    rule: Rule::Factor,
                },
            ],
            explained_in: IRRADIANCE_NOTES,
            method: "Integrate L(w) max(0, n . w) over the sphere: a constant A gives pi A, a linear B w_z gives (2 pi/3) B n_z.",
        },
        Part {
            key: "q4b.blind_half_angle_deg",
            prompt: "blind cone half-angle arcsin(R/D), in degrees",
            points: 2.0,
            expected: number(gamma.to_degrees()),
            mal_rules: vec![
                MalRule {
                    value: number(gamma),
                    message: "that is the angle in radians; degrees are asked",
                    rule: Rule::Unit,
                },
                MalRule {
                    value: number(2.0 * gamma.to_degrees()),
                    message: "that is the full cone angle; the half-angle is arcsin(R/D)",
                    rule: Rule::FullForHalfAngle,
                },
            ],
            explained_in: BLIND_NOTES,
            method: "The camera's rays graze the ball where they are tangent to it: the hidden cone behind the ball has half-angle arcsin(R/D).",
        },
        Part {
            key: "q4b.lost_fraction",
            prompt: "fraction of a uniform map's irradiance lost, normal into the cone",
            points: 2.0,
            expected: number(lost),
            mal_rules: vec![MalRule {
                value: number(blind_spot::solid_angle(distance_over_radius).expect("D > R") / (4.0 * PI)),
                message: "that is the cone's share of the sphere of directions; irradiance weights by the cosine",
                rule: Rule::OtherQuantity,
            }],
            explained_in: BLIND_NOTES,
            method: "Weight the hidden cone by the cosine: for a normal along its axis the lost share of pi is sin^2 of the half-angle, (R/D)^2.",
        },
    ];
    let follows = vec![Follows {
        key: "q4b.lost_fraction",
        from: "q4b.blind_half_angle_deg",
        derivation: Derivation::LostFromHalfAngle,
    }];
    Variant { question: "q4", seed, statement, parts, follows }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_zero_by_hand() {
        // E = πA + (2π/3) B cos 60° = π + π/3; γ = arcsin(1/3) = 19.47°; lost = (R/D)² = 1/9.
        let v = variant(0);
        let value = |key| match v.parts.iter().find(|p| p.key == key).unwrap().expected {
            Expected::Number { value, .. } => value,
            _ => unreachable!(),
        };
        assert!((value("q4a.irradiance") - 4.0 * PI / 3.0).abs() < 1e-12);
        assert!((value("q4b.blind_half_angle_deg") - 19.471_220_634_490_69).abs() < 1e-9);
        assert!((value("q4b.lost_fraction") - 1.0 / 9.0).abs() < 1e-12);
    }

    /// E(n) by midpoint quadrature over the sphere of the sky clamped at 0, written out here
    /// without the crate's maps: if a variant's sky went negative anywhere, its closed-form key
    /// would differ from this.
    fn clamped_quadrature(a: f64, b: f64, normal: DVec3) -> f64 {
        let (n_theta, n_phi) = (400, 800);
        let (d_theta, d_phi) = (PI / f64::from(n_theta), 2.0 * PI / f64::from(n_phi));
        let mut sum = 0.0;
        for i in 0..n_theta {
            let theta = (f64::from(i) + 0.5) * d_theta;
            for j in 0..n_phi {
                let phi = (f64::from(j) + 0.5) * d_phi;
                let w = DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
                sum += (a + b * w.z).max(0.0) * normal.dot(w).max(0.0) * theta.sin() * d_theta * d_phi;
            }
        }
        sum
    }

    #[test]
    fn every_variant_sky_is_physical_and_its_key_matches_the_clamped_integral() {
        for seed in 0..60 {
            let v = variant(seed);
            // The statement names the sky and the tilt; read them back rather than re-drawing.
            let words: Vec<&str> = v.statement.split_whitespace().collect();
            let at = words.iter().position(|w| *w == "L(w)").unwrap();
            let a: f64 = words[at + 2].parse().unwrap();
            let sign = if words[at + 3] == "-" { -1.0 } else { 1.0 };
            let b = sign * words[at + 4].parse::<f64>().unwrap();
            assert!(a >= b.abs(), "seed {seed}: L = {a} + {b} w_z goes negative");
            let tilt_at = words.iter().position(|w| *w == "tilted").unwrap();
            let tilt = words[tilt_at + 1].parse::<f64>().unwrap().to_radians();
            let normal = DVec3::new(tilt.sin(), 0.0, tilt.cos());
            let Expected::Number { value, .. } = v.parts[0].expected else { unreachable!() };
            let brute = clamped_quadrature(a, b, normal);
            assert!((value - brute).abs() < 1e-4 * value, "seed {seed}: key {value}, clamped integral {brute}");
        }
    }
}
