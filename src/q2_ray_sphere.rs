#![doc = include_str!(concat!(env!("OUT_DIR"), "/q2_ray_sphere.md"))]

pub mod catalogue;
pub mod closest_approach;
mod figures;
pub mod reflection;
pub mod student_solver;

use crate::answers::Answers;
use crate::geometry::sphere::{bounded_first_hit_from_f64, closest_approach_t, first_hit_stable, surface_hit};
use crate::geometry::{InputError, ParseVec3Error, Ray, Sphere};
use crate::real::Real;
use catalogue::{Precision, Solver};
use glam::DVec3;
use reflection::{Scenario, SpawnPolicy, reflect_at_hit, self_hit_rate};
use serde::Serialize;
use std::fmt::Write as _;
use student_solver::student_trace;

pub use figures::figures;

/// The ray and sphere of variant 0 (the checker's seed 0): eye `(−5, 1, 0)`, direction
/// `(1, 0, 0)`, sphere of radius 2 at the origin: `A = 1`, `B = −10`, `C = 22`, first hit
/// `t = 5 − √3`. Despite its name it is not the chapter's worked example: that is
/// [`notes_example`], which no variant draws.
///
/// # Examples
/// ```
/// let (ray, sphere) = hw3::q2_ray_sphere::worked_example();
/// assert_eq!(sphere.radius, 2.0);
/// assert_eq!(ray.dir, glam::DVec3::X);
/// ```
#[must_use]
pub fn worked_example() -> (Ray<f64>, Sphere<f64>) {
    (Ray { origin: DVec3::new(-5.0, 1.0, 0.0), dir: DVec3::X }, Sphere { center: DVec3::ZERO, radius: 2.0 })
}

/// The chapter's worked example of the graded parts: eye `(−7, 5, −1)`, direction `(4, 0, 0)`, a
/// sphere of radius 5 centred at `(1, 2, −1)`. Round by hand (`e − o = (−8, 3, 0)`, `A = 16`,
/// `B = −64`, `C = 48`, roots 1 and 3, hit point `(−3, 5, −1)`), with `|d| ≠ 1` so that a
/// parameter and a distance differ; and no variant's (variants draw radii 1 to 4 and direction
/// components −3 to 3).
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::{catalogue::{Precision, Solver}, notes_example, solve};
/// let (ray, sphere) = notes_example();
/// let answer = solve(&ray, &sphere, Solver::Stable, Precision::F64).unwrap();
/// assert_eq!((answer.t, answer.closest_approach_t), (Some(1.0), 2.0));
/// assert_eq!(answer.point, Some([-3.0, 5.0, -1.0]));
/// ```
#[must_use]
pub fn notes_example() -> (Ray<f64>, Sphere<f64>) {
    (
        Ray { origin: DVec3::new(-7.0, 5.0, -1.0), dir: DVec3::new(4.0, 0.0, 0.0) },
        Sphere { center: DVec3::new(1.0, 2.0, -1.0), radius: 5.0 },
    )
}

/// Everything Q2 asks for one ray and sphere: the first hit, point, normal, reflection, and the
/// closest-approach parameter, each number of the hit with a bound on its error. This is what
/// `hw3 sphere --json` prints.
///
/// For the stable method the bounds are the solver's own
/// ([`crate::geometry::sphere::bounded_first_hit_from_f64`]): each is a bound on the distance from
/// the exact answer for the `f64` inputs, the rounding to `f32` included. The naive method (the
/// homework's formula) has no bound of its own: it is checked against the stable method's, its
/// bounds are its distance from the stable answer plus the stable bound, and `warning` says where
/// it is wrong beyond the stable bound (or gets hit or miss wrong).
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::catalogue::{Solver, Precision};
/// use hw3::q2_ray_sphere::{solve, worked_example};
/// let (ray, sphere) = worked_example();
/// let answer = solve(&ray, &sphere, Solver::Stable, Precision::F64).unwrap();
/// assert!(answer.hit);
/// assert_eq!(answer.closest_approach_t, 5.0);
/// assert!(answer.t_error.unwrap() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SphereAnswer {
    /// Whether the ray hits (`t > 0`).
    pub hit: bool,
    /// The first intersection parameter `t_i`.
    pub t: Option<f64>,
    /// `|t − t_exact| ≤ t_error`.
    pub t_error: Option<f64>,
    /// The hit point (reprojected onto the sphere for the stable method, `e + d t_i` for naive).
    pub point: Option<[f64; 3]>,
    /// Per component, the bound on the point's distance from the exact hit point.
    pub point_error: Option<[f64; 3]>,
    /// Outward unit normal at the hit.
    pub normal: Option<[f64; 3]>,
    /// Per component, the bound on the normal's distance from the exact normal.
    pub normal_error: Option<[f64; 3]>,
    /// Unit reflected direction `d̂ − 2(n̂·d̂)n̂`.
    pub reflected_dir: Option<[f64; 3]>,
    /// Per component, the bound on its distance from the exact reflected direction.
    pub reflected_dir_error: Option<[f64; 3]>,
    /// The closest-approach parameter `−(e − o)·d/|d|²` (defined whether or not the ray hits).
    pub closest_approach_t: f64,
    /// For the naive method, where its answer is wrong beyond the stable method's bound: what the
    /// stable method finds instead. `None` otherwise.
    pub warning: Option<String>,
}

impl SphereAnswer {
    /// The answer as `hw3 sphere` prints it without `--json`: one line per quantity, each with its
    /// bound (`±`, per component for vectors).
    ///
    /// # Examples
    /// ```
    /// use hw3::q2_ray_sphere::{catalogue::{Precision, Solver}, notes_example, solve};
    /// let (ray, sphere) = notes_example();
    /// let text = solve(&ray, &sphere, Solver::Stable, Precision::F64).unwrap().text();
    /// assert!(text.starts_with("hit: true\nt = 1 ± 0.0e0\npoint = (-3, 5, -1) ± ("), "{text}");
    /// ```
    #[must_use]
    pub fn text(&self) -> String {
        let vector = |v: [f64; 3]| format!("({}, {}, {})", v[0], v[1], v[2]);
        let bound = |v: [f64; 3]| format!("({:.1e}, {:.1e}, {:.1e})", v[0], v[1], v[2]);
        let mut out = format!("hit: {}\n", self.hit);
        if let (Some(t), Some(point), Some(normal), Some(reflected)) =
            (self.t, self.point, self.normal, self.reflected_dir)
        {
            let with = |value: String, error: Option<String>| match error {
                Some(error) => format!("{value} ± {error}"),
                None => value,
            };
            let _ = writeln!(out, "t = {}", with(t.to_string(), self.t_error.map(|e| format!("{e:.1e}"))));
            let _ = writeln!(out, "point = {}", with(vector(point), self.point_error.map(bound)));
            let _ = writeln!(out, "normal = {}", with(vector(normal), self.normal_error.map(bound)));
            let _ =
                writeln!(out, "reflected direction = {}", with(vector(reflected), self.reflected_dir_error.map(bound)));
        }
        let _ = write!(out, "closest approach t = {}", self.closest_approach_t);
        if let Some(warning) = &self.warning {
            let _ = write!(out, "\nwarning: {warning}");
        }
        out
    }
}

/// Solves Q2 a–c for one ray and sphere with the chosen method and precision.
///
/// # Errors
/// [`InputError`] for a non-finite origin, centre or radius, a negative radius, or a direction
/// whose squared length is zero, subnormal or infinite *in the chosen precision*;
/// [`InputError::Unresolvable`] where the case is out of the precision's reach: a square overflows
/// or underflows, or no answer within the stable method's error bound exists (hit and miss, or the
/// two sides of the eye, or of the sphere, cannot be told apart; see
/// [`crate::geometry::sphere::Unresolved`]). The naive method is refused where the stable one is,
/// since its answer could not be checked, and where its own numbers overflow.
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::{solve, worked_example, catalogue::{Solver, Precision}};
/// let (ray, sphere) = worked_example();
/// let answer = solve(&ray, &sphere, Solver::Stable, Precision::F64).unwrap();
/// assert!((answer.t.unwrap() - (5.0 - 3f64.sqrt())).abs() < 1e-15);
/// assert_eq!(answer.closest_approach_t, 5.0);
/// ```
pub fn solve(
    ray: &Ray<f64>,
    sphere: &Sphere<f64>,
    method: Solver,
    precision: Precision,
) -> Result<SphereAnswer, InputError> {
    match precision {
        Precision::F32 => solve_in::<f32>(ray, sphere, method),
        Precision::F64 => solve_in::<f64>(ray, sphere, method),
    }
}

fn solve_in<T: Real>(ray: &Ray<f64>, sphere: &Sphere<f64>, method: Solver) -> Result<SphereAnswer, InputError> {
    let stable = bounded_first_hit_from_f64::<T>(ray, sphere)?.into_result()?;
    let ray = Ray::<T>::new(T::vec_from_f64(ray.origin), T::vec_from_f64(ray.dir))?;
    let sphere = Sphere::<T>::new(T::vec_from_f64(sphere.center), T::from_f64(sphere.radius))?;
    let closest_approach_t = closest_approach_t(&ray, sphere.center).to_f64();
    let array = |v: T::Vec3| T::vec_to_f64(v).to_array();
    let stable = stable.map(|hit| SphereAnswer {
        hit: true,
        t: Some(hit.t.to_f64()),
        t_error: Some(hit.t_error),
        point: Some(array(hit.point)),
        point_error: Some(hit.point_error),
        normal: Some(array(hit.normal)),
        normal_error: Some(hit.normal_error),
        reflected_dir: Some(array(hit.reflected)),
        reflected_dir_error: Some(hit.reflected_error),
        closest_approach_t,
        warning: None,
    });
    let miss = SphereAnswer {
        hit: false,
        t: None,
        t_error: None,
        point: None,
        point_error: None,
        normal: None,
        normal_error: None,
        reflected_dir: None,
        reflected_dir_error: None,
        closest_approach_t,
        warning: None,
    };
    match method {
        Solver::Stable => Ok(stable.unwrap_or(miss)),
        Solver::Naive => {
            let answer = naive_checked(&ray, &sphere, stable, miss);
            let numbers = [answer.t.map(|t| [t; 3]), answer.point, answer.normal, answer.reflected_dir];
            if numbers.iter().flatten().flatten().all(|x| x.is_finite()) {
                Ok(answer)
            } else {
                Err(InputError::Unresolvable {
                    precision: T::NAME,
                    reason: "the homework's formula overflows: its hit point, normal or reflection is not finite"
                        .into(),
                })
            }
        }
    }
}

/// The homework's answer, checked against the stable method's bounded one (`stable`, `None` for a
/// certain miss): each bound is the distance from the stable value plus the stable bound, and the
/// warning says where the naive answer is wrong beyond it.
fn naive_checked<T: Real>(
    ray: &Ray<T>,
    sphere: &Sphere<T>,
    stable: Option<SphereAnswer>,
    miss: SphereAnswer,
) -> SphereAnswer {
    let array = |v: T::Vec3| T::vec_to_f64(v).to_array();
    let Some(t) = student_trace(ray, sphere).chosen else {
        let warning = stable.as_ref().map(|s| {
            format!(
                "the homework's formula misses, but the ray hits the sphere at t = {} ± {:.1e} (stable method)",
                s.t.unwrap_or(f64::NAN),
                s.t_error.unwrap_or(f64::NAN)
            )
        });
        return SphereAnswer { warning, ..miss };
    };
    let bounce = reflect_at_hit(ray, sphere, t, SpawnPolicy::AtComputedPoint);
    let (t, point, normal, reflected) = (t.to_f64(), array(bounce.point), array(bounce.normal), array(bounce.ray.dir));
    let Some(stable) = stable else {
        return SphereAnswer {
            hit: true,
            t: Some(t),
            point: Some(point),
            normal: Some(normal),
            reflected_dir: Some(reflected),
            warning: Some(format!(
                "the homework's formula hits at t = {t}, but the ray misses the sphere (stable method)"
            )),
            ..miss
        };
    };
    // |x − exact| ≤ |x − stable| + |stable − exact|, rounded up.
    let widen = |x: f64, s: f64, e: f64| ((x - s).abs() + e) * (1.0 + 4.0 * f64::EPSILON);
    let widen3 = |x: [f64; 3], s: Option<[f64; 3]>, e: Option<[f64; 3]>| {
        let (s, e) = (s.unwrap_or([f64::NAN; 3]), e.unwrap_or([f64::NAN; 3]));
        std::array::from_fn(|i| widen(x[i], s[i], e[i]))
    };
    let (t_stable, t_bound) = (stable.t.unwrap_or(f64::NAN), stable.t_error.unwrap_or(f64::NAN));
    let off = (t - t_stable).abs();
    let warning = (off > t_bound).then(|| {
        format!(
            "the homework's formula is off by at least {:.1e} in t: the stable method finds t = {t_stable} ± {t_bound:.1e}",
            (off - t_bound) * (1.0 - 4.0 * f64::EPSILON)
        )
    });
    SphereAnswer {
        hit: true,
        t: Some(t),
        t_error: Some(widen(t, t_stable, t_bound)),
        point: Some(point),
        point_error: Some(widen3(point, stable.point, stable.point_error)),
        normal: Some(normal),
        normal_error: Some(widen3(normal, stable.normal, stable.normal_error)),
        reflected_dir: Some(reflected),
        reflected_dir_error: Some(widen3(reflected, stable.reflected_dir, stable.reflected_dir_error)),
        closest_approach_t: stable.closest_approach_t,
        warning,
    }
}

/// A worked trace of one ray through every step of Q2 (the homework's algorithm, the stable
/// solver, the surface frame, the reflection and the closest approach), as pinned by snapshots.
///
/// # Examples
/// ```
/// let (ray, sphere) = hw3::q2_ray_sphere::worked_example();
/// let trace = hw3::q2_ray_sphere::worked_trace(&ray, &sphere);
/// assert!(trace.contains("B = -1.000000e1"));
/// ```
#[must_use]
pub fn worked_trace(ray: &Ray<f64>, sphere: &Sphere<f64>) -> String {
    let g = |x: f64| format!("{x:.6e}");
    let v = |v: DVec3| format!("({}, {}, {})", g(v.x), g(v.y), g(v.z));
    let mut out = String::new();
    let _ = writeln!(
        out,
        "ray e = {}, d = {}; sphere o = {}, r = {}",
        v(ray.origin),
        v(ray.dir),
        v(sphere.center),
        g(sphere.radius)
    );
    let _ = writeln!(out, "-- homework algorithm (f64) --\n{}", student_trace(ray, sphere));
    let stable = first_hit_stable(ray, sphere);
    let _ = writeln!(out, "-- stable solver --\nfirst hit t = {}", stable.map_or("none".into(), g));
    let _ = writeln!(out, "closest approach t = {}", g(closest_approach_t(ray, sphere.center)));
    if let Some(t) = stable {
        let hit = surface_hit(ray, sphere, t);
        let bounce = reflect_at_hit(ray, sphere, t, SpawnPolicy::ReprojectAndOffset);
        let _ = writeln!(
            out,
            "point = {}\nnormal = {}\nreflected direction = {}",
            v(hit.point),
            v(hit.normal),
            v(bounce.ray.dir)
        );
    }
    out
}

/// The rays the snapshot traces cover: the worked example and one per policy the notes state.
///
/// # Examples
/// ```
/// let cases = hw3::q2_ray_sphere::trace_cases();
/// assert_eq!(cases[0].0, "worked example");
/// assert!(cases.iter().any(|(name, ..)| *name == "tangent"));
/// ```
#[must_use]
pub fn trace_cases() -> Vec<(&'static str, Ray<f64>, Sphere<f64>)> {
    let (ray, sphere) = worked_example();
    let unit = Sphere { center: DVec3::ZERO, radius: 1.0 };
    vec![
        ("worked example", ray, sphere),
        ("eye inside", Ray { origin: DVec3::ZERO, dir: DVec3::new(0.0, 0.0, 2.0) }, unit),
        ("tangent", Ray { origin: DVec3::new(-3.0, 1.0, 0.0), dir: DVec3::X }, unit),
        ("sphere behind", Ray { origin: DVec3::new(0.0, 0.0, 5.0), dir: DVec3::Z }, unit),
        ("miss", Ray { origin: DVec3::new(0.0, 2.0, -5.0), dir: DVec3::Z }, unit),
    ]
}

/// The share of reflected `f32` rays that re-hit their own sphere, in per cent, for a spawn
/// policy and a scenario (20 000 random hits, the chapter's sample), as the chapter prints it.
fn self_hit_percent(scenario: Scenario, policy: SpawnPolicy) -> f64 {
    let count = self_hit_rate::<f32>(scenario, policy, 20_000, 11);
    100.0 * count.self_hits as f64 / count.reflected as f64
}

/// `[x, y, z]` as the chapter writes a vector in prose, `(x, y, z)`: whole numbers without a
/// point, and the last bits of rounding (below 10⁻⁹) left out, as a hand computation writes them.
fn tuple(v: [f64; 3]) -> String {
    let tidy = |x: f64| (x * 1e9).round() / 1e9 + 0.0;
    format!("({}, {}, {})", tidy(v[0]), tidy(v[1]), tidy(v[2]))
}

/// Q2's answers as `hw3 answers --question q2` prints them: the chapter's formulas, its worked
/// example and its findings, each number as the chapter prints it (`tests/chapters_q1_q2.rs`
/// checks that every number printed here is one the chapter prints).
///
/// # Examples
/// ```
/// let answers = hw3::q2_ray_sphere::answers();
/// assert_eq!(answers.question, "q2");
/// assert!(answers.text.contains("t1 < t2"));
/// assert!(answers.text.contains("t = 1, point (-3, 5, -1)"));
/// ```
#[must_use]
pub fn answers() -> Answers {
    let (ray, sphere) = notes_example();
    let solved = solve(&ray, &sphere, Solver::Stable, Precision::F64).ok();
    let f = ray.origin - sphere.center;
    let (a, b, c) = (ray.dir.dot(ray.dir), 2.0 * f.dot(ray.dir), f.dot(f) - sphere.radius * sphere.radius);
    let mut text = String::new();
    let _ =
        writeln!(text, "(a) A = d.d, B = 2(e - o).d, C = |e - o|^2 - r^2; the first hit is the smallest root t > 0");
    let _ = writeln!(
        text,
        "    (t = 0 is the eye itself, not a hit). The homework's case analysis is right, with two errata:"
    );
    let _ = writeln!(text, "    - its 't1 < t2' branch is dead code: t1 takes +sqrt, so t1 >= t2 whenever A > 0;");
    let _ =
        writeln!(text, "    - the tangent case accepts t >= 0 but the two-root case t > 0 (inconsistent at t = 0).");
    let _ = writeln!(
        text,
        "    Worked example: e = {}, d = {}, o = {}, r = {}: A = {a}, B = {b}, C = {c}, B^2 - 4AC = {};",
        tuple(ray.origin.to_array()),
        tuple(ray.dir.to_array()),
        tuple(sphere.center.to_array()),
        sphere.radius,
        b * b - 4.0 * a * c,
    );
    // The chapter's case rule (part q2a, step 3): the discriminant's sign, then C's, then B's.
    let discriminant = b * b - 4.0 * a * c;
    let case = if discriminant < 0.0 {
        "miss"
    } else if discriminant == 0.0 {
        "tangent"
    } else if c == 0.0 {
        "on_surface"
    } else if c < 0.0 {
        "inside"
    } else if b < 0.0 {
        "outside"
    } else {
        "behind"
    };
    if let Some(answer) = &solved {
        let _ = writeln!(
            text,
            "    case {case}, t = {}, point {}.",
            answer.t.map_or("none".into(), |t| t.to_string()),
            answer.point.map_or("none".into(), tuple),
        );
    }
    let rows = catalogue::score_catalogue();
    let far = rows.iter().find(|r| r.case.name == "far: r = 1 at distance 1e5, offset 0.9 r");
    if let Some(row) = far {
        let missed = if matches!(row.outcomes[0], catalogue::Outcome::Missed) { "misses" } else { "hits" };
        let _ = writeln!(
            text,
            "    In f32 the homework formula {missed} a unit sphere 10^5 away aimed 0.9 r off-centre; the stable \
             form's relative error there is {:.1e}.",
            row.outcomes[1].error()
        );
    }
    if let Some(answer) = &solved {
        let _ = writeln!(
            text,
            "(b) n = (p - o)/r, reflected = dhat - 2(n.dhat)n: in the worked example n = {}, reflected {}.",
            answer.normal.map_or("none".into(), tuple),
            answer.reflected_dir.map_or("none".into(), tuple),
        );
    }
    let _ = writeln!(
        text,
        "    The reflected ray must not start at the computed hit point: in f32 {:.0} % of such rays re-hit \
         their own sphere near the world origin. A fixed t_min = {} still leaves {:.1} % on a huge sphere \
         (r = 10^6) and {:.1} % in a scene moved 10^4 units away; reprojecting onto the sphere and \
         offsetting along the normal leaves 0.",
        self_hit_percent(Scenario::Near, SpawnPolicy::AtComputedPoint),
        reflection::FIXED_T_MIN,
        self_hit_percent(Scenario::HugeSphere, SpawnPolicy::FixedEpsilon),
        self_hit_percent(Scenario::Translated, SpawnPolicy::FixedEpsilon),
    );
    let t_alg = closest_approach::closest_approach_algebraic(&ray, sphere.center);
    let t_geo = closest_approach::closest_approach_geometric(&ray, sphere.center);
    let l = f + ray.dir * t_alg;
    let half_chord = (sphere.radius * sphere.radius - l.length_squared()).sqrt() / ray.dir.length();
    let _ = write!(
        text,
        "(c) t = -(e - o).d/|d|^2: in the worked example {t_alg} from the quadratic's vertex -B/2A, and {t_geo} \
         from the perpendicular; the half-chord sqrt(r^2 - |l|^2)/|d| = {half_chord} in t gives the roots {} \
         and {}.",
        t_alg - half_chord,
        t_alg + half_chord,
    );
    Answers { question: "q2", title: "Ray/sphere intersection, reflection, closest approach", text }
}

/// Why `hw3 sphere`'s arguments were refused ([`parse_sphere_args`]): the message names the bad
/// argument.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SphereArgsError {
    /// `--origin`, `--dir` or `--center` is not three comma-separated numbers.
    #[error(transparent)]
    Syntax(#[from] ParseVec3Error),
    /// The ray or the sphere is invalid (a non-finite coordinate, a zero direction, a radius that
    /// is not positive).
    #[error(transparent)]
    Input(#[from] InputError),
}

/// Parses the CLI's `--origin`, `--dir`, `--center`, `--radius` into validated `f64` inputs.
///
/// # Errors
/// [`SphereArgsError::Syntax`] for a vector that is not three numbers, [`SphereArgsError::Input`]
/// for an invalid ray or sphere; either names the bad argument.
///
/// # Examples
/// ```
/// use hw3::q2_ray_sphere::{SphereArgsError, parse_sphere_args};
/// let (ray, sphere) = parse_sphere_args("0,0,0", "0,0,1", "0,0,5", 1.0).unwrap();
/// assert_eq!(sphere.center.z, 5.0);
/// assert!(matches!(parse_sphere_args("0,0,0", "0,0,0", "0,0,5", 1.0), Err(SphereArgsError::Input(_))));
/// assert!(matches!(parse_sphere_args("0,0", "0,0,1", "0,0,5", 1.0), Err(SphereArgsError::Syntax(_))));
/// ```
pub fn parse_sphere_args(
    origin: &str,
    dir: &str,
    center: &str,
    radius: f64,
) -> Result<(Ray<f64>, Sphere<f64>), SphereArgsError> {
    let origin = crate::geometry::parse_vec3("--origin", origin)?;
    let dir = crate::geometry::parse_vec3("--dir", dir)?;
    let center = crate::geometry::parse_vec3("--center", center)?;
    let ray = Ray::new(origin, dir)?;
    let sphere = Sphere::new(center, radius)?;
    Ok((ray, sphere))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn worked_traces_snapshot() {
        let text: String = trace_cases()
            .into_iter()
            .map(|(name, ray, sphere)| format!("## {name}\n{}\n", worked_trace(&ray, &sphere)))
            .collect();
        crate::testing::insta_settings().bind(|| insta::assert_snapshot!("q2_worked_traces", text));
    }

    #[test]
    fn worked_example_by_hand() {
        let (ray, sphere) = worked_example();
        let answer = solve(&ray, &sphere, Solver::Naive, Precision::F64).unwrap();
        let t = 5.0 - 3f64.sqrt();
        approx::assert_relative_eq!(answer.t.unwrap(), t, max_relative = 1e-15);
        let n = DVec3::new(-3f64.sqrt() / 2.0, 0.5, 0.0);
        approx::assert_relative_eq!(DVec3::from(answer.normal.unwrap()), n, max_relative = 1e-15);
        approx::assert_relative_eq!(
            DVec3::from(answer.reflected_dir.unwrap()),
            DVec3::new(-0.5, 3f64.sqrt() / 2.0, 0.0),
            epsilon = 1e-15
        );
    }

    #[test]
    fn all_four_variants_agree_on_easy_rays() {
        let (ray, sphere) = worked_example();
        let answers: Vec<f64> =
            catalogue::VARIANTS.iter().map(|&(m, p)| solve(&ray, &sphere, m, p).unwrap().t.unwrap()).collect();
        for t in &answers {
            approx::assert_relative_eq!(*t, answers[3], max_relative = 1e-6);
        }
    }

    #[test]
    fn zero_radius_is_refused() {
        let ray = Ray { origin: DVec3::ZERO, dir: DVec3::Z };
        let point = Sphere { center: DVec3::new(0.0, 0.0, 5.0), radius: 0.0 };
        assert!(matches!(
            solve(&ray, &point, Solver::Stable, Precision::F64),
            Err(InputError::OutOfRange { name: "radius", .. })
        ));
    }
}
