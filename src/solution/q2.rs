//! Q2 worked: `A, B, C`, the discriminant, both roots, the case, the point, the normal, the
//! reflection and the closest approach.
//!
//! The intermediate numbers are the homework's own algorithm ([`student_trace`]), the finals the
//! stable solver's, as in the checker's key; for the variants' small integer settings the two
//! agree to the last printed digit.

use super::text::{num, operand, vector};
use super::{Section, Step, Value};
use crate::geometry::sphere::{closest_approach_t, first_hit_stable, reflect_with_cosine, roots_stable, surface_hit};
use crate::geometry::{Ray, Sphere};
use crate::q2_ray_sphere::student_solver::{StudentBranch, student_trace};

pub(super) fn sections(ray: &Ray<f64>, sphere: &Sphere<f64>) -> Vec<Section> {
    let (ray, sphere) = (*ray, *sphere);
    let (e, d, o, r) = (ray.origin, ray.dir, sphere.center, sphere.radius);
    let trace = student_trace(&ray, &sphere);
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
        StudentBranch::NoRealRoots => a.push(Step::work("B² - 4AC < 0: no real roots, the ray misses")),
        StudentBranch::Tangent => {
            a.push(Step::work(format!("B² - 4AC = 0: one double root t = -B/2A = {}", num(trace.t1))))
        }
        StudentBranch::TwoRootsT1Smaller | StudentBranch::TwoRootsT2Smaller => {
            a.push(Step::work(format!("√(B² - 4AC) = {}", num(trace.discriminant.sqrt()))));
            a.push(Step::work(format!("t1 = (-B + √(B² - 4AC))/2A = {}", num(trace.t1))));
            a.push(Step::work(format!("t2 = (-B - √(B² - 4AC))/2A = {}", num(trace.t2))));
        }
    }
    // The case, as the analysis names it: C's sign says where the eye is, the roots where the sphere is.
    let roots = roots_stable(&ray, &sphere);
    let hit_t = first_hit_stable(&ray, &sphere);
    let (case, why) = match roots {
        _ if trace.c == 0.0 => (
            "on_surface",
            if hit_t.is_some() {
                "C = 0: e is on the sphere; the root t = 0 is the eye itself, not a hit, and the other root is ahead"
            } else {
                "C = 0: e is on the sphere; the root t = 0 is the eye itself, not a hit, and the other root is behind \
                 (the ray leaves the sphere): no hit"
            },
        ),
        None => ("miss", "B² - 4AC < 0: the ray's line misses the sphere, no hit"),
        Some(r) if r.near == r.far => {
            ("tangent", "B² - 4AC = 0 and the double root is ahead: the ray grazes the sphere")
        }
        Some(_) if trace.c < 0.0 => (
            "inside",
            "C < 0: e is inside the sphere; the smaller root is behind the eye, so the hit is the larger root",
        ),
        Some(r) if r.far < 0.0 => {
            ("behind", "C > 0: e is outside, and both roots are negative: the sphere is behind the eye, no hit")
        }
        Some(_) => ("outside", "C > 0: e is outside the sphere; both roots are ahead and the first hit is the smaller"),
    };
    a.push(Step::answer(format!("{why}: case {case}"), "q2a.case", Value::Word(case.into())));
    a.push(Step::answer(format!("hit = {}", hit_t.is_some()), "q2a.hit", Value::Flag(hit_t.is_some())));
    let formulas = [
        ("A = d·d", "q2a.A", "dot(d, d)"),
        ("B = 2 (e - o)·d", "q2a.B", "2*dot(e - o, d)"),
        ("C = |e - o|² - r²", "q2a.C", "dot(e - o, e - o) - r^2"),
        ("from outside the first hit is the smaller root", "q2a.t_formula", "(-B - sqrt(B^2 - 4*A*C))/(2*A)"),
    ];
    let symbols = |steps: &mut Vec<Step>, formulas: &[(&str, &'static str, &str)]| {
        for &(why, key, formula) in formulas {
            steps.push(Step::answer(format!("in symbols, {why}: {formula}"), key, Value::Formula(formula.into())));
        }
    };
    let b_formulas = [
        ("n = (p - o)/r", "q2b.normal_formula", "(p - o)/r"),
        ("r = d^ - 2 (n·d^) n", "q2b.reflected_formula", "dhat - 2*dot(n, dhat)*n"),
    ];
    let c_formulas = [("t = -(e - o)·d/(d·d)", "q2c.t_formula", "-dot(e - o, d)/dot(d, d)")];
    let t_closest = closest_approach_t(&ray, o);
    let closest = ray.at(t_closest);
    let closest_step = Step::answer(
        format!("t = -(e - o)·d/(d·d) = -({})/{} = {}", num(f.dot(d)), num(trace.a), num(t_closest)),
        "q2c.t_closest",
        Value::Number(t_closest),
    );
    let Some(t) = hit_t else {
        // No hit: there is no first intersection, so no point, normal or reflection.
        let none = "there is no t > 0 on the sphere";
        a.push(Step::answer(format!("t: none ({none})"), "q2a.t", Value::None));
        a.push(Step::answer(format!("p: none ({none})"), "q2a.point", Value::None));
        symbols(&mut a, &formulas);
        let mut b = vec![
            Step::answer("n: none (no hit, no surface point)", "q2b.normal", Value::None),
            Step::answer("reflected direction: none (no hit, nothing reflects)", "q2b.reflected_dir", Value::None),
        ];
        symbols(&mut b, &b_formulas);
        let mut c = vec![
            closest_step,
            Step::work(format!(
                "check: the closest point e + d t = {} is {} from o (r = {})",
                v(closest),
                num((closest - o).length()),
                num(r)
            )),
        ];
        symbols(&mut c, &c_formulas);
        return vec![
            Section { title: "(a) the first intersection".into(), steps: a },
            Section { title: "(b) the normal and the reflected direction".into(), steps: b },
            Section { title: "(c) the closest approach".into(), steps: c },
        ];
    };
    let hit = surface_hit(&ray, &sphere, t);
    a.push(Step::answer(format!("t = {}", num(t)), "q2a.t", Value::Number(t)));
    a.push(Step::answer(
        format!("p = e + d t = {} + {} · {} = {}", v(e), num(t), v(d), v(hit.point)),
        "q2a.point",
        Value::Vector(hit.point.to_array()),
    ));
    symbols(&mut a, &formulas);

    let length = d.length();
    let (reflected, cosine) = reflect_with_cosine::<f64>(d, hit.normal);
    let mut b = vec![
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
    symbols(&mut b, &b_formulas);

    let mut c = vec![
        closest_step,
        Step::work(format!(
            "check: (t1 + t2)/2 = {}, the midpoint of the roots; the closest point e + d t = {} is {} from o \
             (at most r = {}: the line does meet the sphere)",
            num(0.5 * (trace.t1 + trace.t2)),
            v(closest),
            num((closest - o).length()),
            num(r)
        )),
    ];
    symbols(&mut c, &c_formulas);
    vec![
        Section { title: "(a) the first intersection".into(), steps: a },
        Section { title: "(b) the normal and the reflected direction".into(), steps: b },
        Section { title: "(c) the closest approach".into(), steps: c },
    ]
}
