//! Q2 worked: `A, B, C`, the discriminant, both roots, the case, the point, the normal, the
//! reflection and the closest approach.
//!
//! The intermediate numbers are the homework's own algorithm ([`seed_trace`]), the finals the
//! stable solver's, as in the checker's key; for the variants' small integer settings the two
//! agree to the last printed digit.

use super::render::{num, operand, vector};
use super::{Section, SolutionError, Step, Value, setting};
use crate::checker::Variant;
use crate::geometry::sphere::{closest_approach_t, first_hit_stable, reflect_with_cosine, surface_hit};
use crate::q2_ray_sphere::seed_solver::{SeedBranch, seed_trace};

pub(super) fn sections(variant: &Variant) -> Result<Vec<Section>, SolutionError> {
    let (ray, sphere) = setting::q2(variant)?;
    let (e, d, o, r) = (ray.origin, ray.dir, sphere.center, sphere.radius);
    let trace = seed_trace(&ray, &sphere);
    let f = e - o;
    let v = |x: glam::DVec3| vector(x.to_array());

    let mut a = vec![
        Step::work(format!("f = e - o = {} - {} = {}", v(e), v(o), v(f))),
        Step::work(format!("A = d·d = {}", num(trace.a))),
        Step::work(format!("B = 2 f·d = {}", num(trace.b))),
        Step::work(format!("C = f·f - r² = {} - {} = {}", num(f.dot(f)), num(r * r), num(trace.c))),
        Step::work(format!(
            "B² - 4AC = {} - {} = {}",
            num(trace.b * trace.b),
            operand(4.0 * trace.a * trace.c),
            num(trace.discriminant)
        )),
    ];
    match trace.branch {
        SeedBranch::NoRealRoots => a.push(Step::work("B² - 4AC < 0: no real roots, the ray misses")),
        SeedBranch::Tangent => {
            a.push(Step::work(format!("B² - 4AC = 0: one double root t = -B/2A = {}", num(trace.t1))))
        }
        SeedBranch::TwoRootsT1Smaller | SeedBranch::TwoRootsT2Smaller => {
            a.push(Step::work(format!("√(B² - 4AC) = {}", num(trace.discriminant.sqrt()))));
            a.push(Step::work(format!("t1 = (-B + √(B² - 4AC))/2A = {}", num(trace.t1))));
            a.push(Step::work(format!("t2 = (-B - √(B² - 4AC))/2A = {}", num(trace.t2))));
            let case = if trace.c > 0.0 && trace.t2 > 0.0 {
                "C > 0: e is outside the sphere; t2 > 0, so both roots are ahead and the first hit is the \
                 smaller, t2"
            } else if trace.c > 0.0 {
                "C > 0: e is outside the sphere, and both roots are negative: the sphere is behind the eye"
            } else if trace.c < 0.0 {
                "C < 0: e is inside the sphere; t2 < 0 is behind the eye, so the hit is the larger root, t1"
            } else {
                "C = 0: e is on the sphere; the root t = 0 is the eye itself, not a hit"
            };
            a.push(Step::work(case));
        }
    }
    let Some(t) = first_hit_stable(&ray, &sphere) else {
        // The checker draws only variants that hit; a miss has no point, normal or reflection.
        return Ok(vec![Section { title: "(a) the first intersection".into(), steps: a }]);
    };
    let hit = surface_hit(&ray, &sphere, t);
    a.push(Step::answer(format!("t = {}", num(t)), "q2a.t", Value::Number(t)));
    a.push(Step::answer(
        format!("p = e + d t = {} + {} · {} = {}", v(e), num(t), v(d), v(hit.point)),
        "q2a.point",
        Value::Vector(hit.point.to_array()),
    ));

    let length = d.length();
    let (reflected, cosine) = reflect_with_cosine::<f64>(d, hit.normal);
    let b = vec![
        Step::answer(
            format!("n = (p - o)/r = {}/{} = {}", v(hit.point - o), num(r), v(hit.normal)),
            "q2b.normal",
            Value::Vector(hit.normal.to_array()),
        ),
        Step::work(format!("|d| = {}, d^ = d/|d| = {}", num(length), v(d / length))),
        Step::work(format!(
            "n·d^ = {} ({})",
            num(cosine),
            if cosine < 0.0 {
                "negative: the ray meets the outside of the surface"
            } else {
                "the ray leaves from inside"
            }
        )),
        Step::answer(
            format!(
                "r = d^ - 2 (n·d^) n = {} - {} {} = {}",
                v(d / length),
                operand(2.0 * cosine),
                v(hit.normal),
                v(reflected)
            ),
            "q2b.reflected_dir",
            Value::Vector(reflected.to_array()),
        ),
        Step::work(format!(
            "check: |r| = {}, n·r = {} = -n·d^ (the angle of reflection equals the angle of incidence)",
            num(reflected.length()),
            num(hit.normal.dot(reflected))
        )),
    ];

    let t_closest = closest_approach_t(&ray, o);
    let closest = ray.at(t_closest);
    let c = vec![
        Step::answer(
            format!("t = -(e - o)·d/(d·d) = -({})/{} = {}", num(f.dot(d)), num(trace.a), num(t_closest)),
            "q2c.t_closest",
            Value::Number(t_closest),
        ),
        Step::work(format!(
            "check: (t1 + t2)/2 = {}, the midpoint of the roots; the closest point e + d t = {} is {} from o \
             (less than r = {}: the ray does hit)",
            num(0.5 * (trace.t1 + trace.t2)),
            v(closest),
            num((closest - o).length()),
            num(r)
        )),
    ];
    Ok(vec![
        Section { title: "(a) the first intersection".into(), steps: a },
        Section { title: "(b) the normal and the reflected direction".into(), steps: b },
        Section { title: "(c) the closest approach".into(), steps: c },
    ])
}
