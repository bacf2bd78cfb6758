//! Q4 worked: the irradiance of the variant's linear sky as the sum of its two closed-form terms,
//! the mirror ball's blind cone and the share of irradiance it removes, then the homework's own
//! question on the variant's probe image: each listed texel's direction and solid angle, the
//! weighted and unweighted texel sums, the bias, the masked solid angle and the blind direction.

use super::text::{num, operand, vector};
use super::{Section, Step, Value};
use crate::checker::{Q4Image, Q4Setting};
use crate::envmap::{Probe, ProbeFormat, horizontal_camera};
use crate::q4_light_probe::blind_spot;
use crate::q4_light_probe::irradiance::{centre_texels, equal_weight, unweighted_sum, weighted_sum};
use crate::q4_light_probe::maps::{AnalyticMap, Term};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

pub(super) fn sections(s: &Q4Setting) -> Vec<Section> {
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
    // A variant's ball is seen from outside it: D ≥ 2R.
    let outside = "a variant's camera lies outside the ball";
    let gamma = blind_spot::half_angle(d).expect(outside);
    let lost = blind_spot::lost_fraction(d, 0.0).expect(outside);
    let share = blind_spot::solid_angle(d).expect(outside) / (4.0 * PI);
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
    let c = probe_steps(&s.image, normal);
    vec![
        Section { title: "(a) the irradiance E(n)".into(), steps: a },
        Section { title: "(b) the blind cone".into(), steps: b },
        Section { title: "(c) lighting from the probe image".into(), steps: c },
    ]
}

/// The answer keys of the listed texels, in the order the statement lists them.
const LISTED: [(&str, &str); 3] = [
    ("q4c.texel1_direction", "q4c.texel1_solid_angle"),
    ("q4c.texel2_direction", "q4c.texel2_solid_angle"),
    ("q4c.texel3_direction", "q4c.texel3_solid_angle"),
];

fn probe_steps(image: &Q4Image, normal: DVec3) -> Vec<Step> {
    let n = image.size;
    let radiance = image.radiance.iter().map(|l| DVec3::splat(l.unwrap_or(0.0))).collect();
    let probe = Probe::from_radiance(ProbeFormat::MirrorBall, n, n, horizontal_camera(), radiance)
        .expect("a variant's radiances are finite and ≥ 0");
    let texels = centre_texels(&probe);
    let camera = horizontal_camera();
    let side = 2.0 / n as f64;
    let mut steps = vec![Step::work(format!(
        "the image spans [-1, 1]² in {n} × {n} texels of side 2/{n} = {}; texel (row, column) has its centre at \
         u = -1 + {} (column + ½), v = 1 - {} (row + ½)",
        num(side),
        num(side),
        num(side)
    ))];
    for (&(row, column), (direction_key, solid_angle_key)) in image.listed.iter().zip(LISTED) {
        let texel = texels[row * n + column];
        let (u, v) = (-1.0 + side * (column as f64 + 0.5), 1.0 - side * (row as f64 + 0.5));
        let rho = DVec2::new(u, v).length();
        let local = camera.transpose() * texel.direction;
        steps.push(Step::work(format!(
            "texel ({row}, {column}): centre (u, v) = ({}, {}), ρ = {}; the orthographic ball reflects it to \
             θ = 2 arcsin ρ = {}° from the camera axis: in the camera's frame w = {}",
            num(u),
            num(v),
            num(rho),
            num(local.z.clamp(-1.0, 1.0).acos().to_degrees()),
            vector(local.to_array())
        )));
        steps.push(Step::answer(
            format!(
                "in the world (image right +y, up +z, toward the camera +x): w = {}",
                vector(texel.direction.to_array())
            ),
            direction_key,
            Value::Vector(texel.direction.to_array()),
        ));
        let whole = (texel.area - side * side).abs() < 1e-12;
        let how = if whole {
            format!("the texel lies wholly inside the disc, A = {}²", num(side))
        } else {
            "the rim cuts the texel: A is its area inside the disc".to_owned()
        };
        steps.push(Step::answer(
            format!(
                "the ball is equal-area, dω = 4 dA; {how} = {}, so Δω = 4A = {}",
                num(texel.area),
                num(texel.solid_angle)
            ),
            solid_angle_key,
            Value::Number(texel.solid_angle),
        ));
    }
    let used: Vec<(usize, &crate::envmap::Texel)> =
        texels.iter().enumerate().filter(|(_, t)| t.centre_inside).collect();
    let lit: Vec<String> = used
        .iter()
        .filter(|(_, t)| normal.dot(t.direction) > 0.0 && t.radiance.x > 0.0)
        .map(|(i, t)| {
            format!(
                "({}, {}) {}·{}·{}",
                i / n,
                i % n,
                num(t.radiance.x),
                num(normal.dot(t.direction)),
                num(t.solid_angle)
            )
        })
        .collect();
    steps.push(Step::work(format!(
        "L · max(0, n·w) · Δω of every used texel facing n (the other {} face away or are dark): {}",
        used.len() - lit.len(),
        lit.join(", ")
    )));
    let weighted = weighted_sum(normal, &texels).x;
    steps.push(Step::answer(format!("E = their sum = {}", num(weighted)), "q4c.weighted_sum", Value::Number(weighted)));
    let weight = equal_weight(&texels);
    let plain = unweighted_sum(normal, &texels, 1.0).x;
    let unweighted = unweighted_sum(normal, &texels, weight).x;
    steps.push(Step::work(format!(
        "N = {} texels used, each given 4π/N = {} sr; Σ L max(0, n·w) = {}",
        used.len(),
        num(weight),
        num(plain)
    )));
    steps.push(Step::answer(
        format!("unweighted = {} · {} = {}", num(weight), num(plain), num(unweighted)),
        "q4c.unweighted_sum",
        Value::Number(unweighted),
    ));
    steps.push(Step::answer(
        format!(
            "bias: unweighted/weighted = {} / {} = {} (texels wholly inside hold 4·{}² = {} sr, more than 4π/N; rim \
             texels less)",
            num(unweighted),
            num(weighted),
            num(unweighted / weighted),
            num(side),
            num(4.0 * side * side)
        ),
        "q4c.bias_ratio",
        Value::Number(unweighted / weighted),
    ));
    let masked: f64 = texels.iter().filter(|t| !t.centre_inside).map(|t| t.solid_angle).sum();
    steps.push(Step::answer(
        format!(
            "the {} masked texels still hold part of the disc: 4π - ΣΔω = {}",
            texels.len() - used.len(),
            num(masked)
        ),
        "q4c.masked_solid_angle",
        Value::Number(masked),
    ));
    let blind = probe.image_to_world(DVec2::X).map_or(-(camera * DVec3::Z), |(w, _)| w);
    steps.push(Step::answer(
        format!("the rim, ρ = 1, reflects to θ = 180°: straight behind the ball, w = {}", vector(blind.to_array())),
        "q4c.blind_direction",
        Value::Vector(blind.to_array()),
    ));
    let term = "L*max(0, dot(n, w))*dw";
    steps.push(Step::answer(
        format!("in symbols, one texel's term: {term}"),
        "q4c.term_formula",
        Value::Formula(term.into()),
    ));
    steps
}
