//! Probe image formats: how an image point maps to a direction and back, and how much solid angle
//! every texel subtends.
//!
//! Directions here are in the *probe frame*. For the three disk formats (mirror ball, perspective
//! ball, angular map) `+z` points back at the camera and the image is the unit disk with `u` right
//! (`+x`) and `v` up (`+y`); a direction at angle `θ` from `+z` lands at radius `ρ(θ)`. For the
//! latitude-longitude format the image is `[0,1]²` with `θ = π v` measured from `+z` (top row) and
//! `φ = 2π u`. [`super::Probe`] rotates the probe frame into the world.
//!
//! The solid angle of a region of a disk image follows from one function: the solid angle inside
//! image radius `ρ` is `2π G(ρ)` with `G(ρ) = 1 − cos θ(ρ)`, so the Jacobian is
//! `dω/dA = G'(ρ)/ρ`. Texel solid angles are integrated exactly (mirror ball: `4 ×` the exact
//! disk ∩ square area; latitude-longitude: `Δφ (cos θ₀ − cos θ₁)`) or, for the angular map and
//! the perspective ball, by integrating `G` along rays from the image centre (Gauss–Legendre in
//! the polar angle, split at every corner and rim crossing), so the sum over texels equals
//! `2π G(1)` to rounding.

use glam::{DVec2, DVec3};
use hw3_core::geometry::InputError;
use std::f64::consts::{PI, TAU};

/// How a light-probe image encodes directions.
///
/// # Examples
/// ```
/// use hw3_render::envmap::ProbeFormat;
/// // The four formats agree on the direction back to the camera / the zenith at θ = 0.
/// for format in [ProbeFormat::MirrorBall, ProbeFormat::AngularMap, ProbeFormat::perspective_ball(5.0).unwrap()] {
///     let p = format.direction_to_image(glam::DVec3::Z).unwrap();
///     assert!(p.length() < 1e-12);
/// }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProbeFormat {
    /// A mirrored ball seen by an orthographic camera: `θ = 2 arcsin ρ`. Equal-area (`dω = 4 dA`),
    /// covers the whole sphere; the rim (`ρ → 1`) is the direction straight behind the ball.
    MirrorBall,
    /// A mirrored ball of radius `R` photographed by a pinhole camera at distance `D` from its
    /// centre, the image scaled so the ball's silhouette is the unit disk. A cone of half-angle
    /// `arcsin(R/D)` behind the ball is never seen: its light would have to pass through the ball.
    PerspectiveBall {
        /// `D/R`, strictly greater than 1.
        distance_over_radius: f64,
    },
    /// Debevec's angular map (the light-probe gallery format): `θ = π ρ`.
    AngularMap,
    /// Latitude-longitude (equirectangular): `θ = π v`, `φ = 2π u` on `[0,1]²`.
    LatLong,
}

/// A 16-point Gauss–Legendre rule on `[-1, 1]`, computed once by Newton's method.
#[derive(Debug, Clone)]
pub(crate) struct GaussLegendre {
    nodes: Vec<(f64, f64)>,
}

impl GaussLegendre {
    pub(crate) fn new(n: usize) -> Self {
        let nodes = (0..n)
            .map(|i| {
                // Tricomi's initial guess, then Newton on the Legendre recurrence.
                let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
                let mut derivative = 1.0;
                for _ in 0..100 {
                    let (p, dp) = legendre(n, x);
                    derivative = dp;
                    let step = p / dp;
                    x -= step;
                    if step.abs() < 1e-16 {
                        break;
                    }
                }
                let weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
                (x, weight)
            })
            .collect();
        Self { nodes }
    }

    /// `∫_a^b f` after the substitution `x = a + (b − a)(3u² − 2u³)`, whose derivative vanishes
    /// at both ends: a `√(x − a)` endpoint behaviour becomes smooth in `u`, so the rule keeps its
    /// fast convergence where a texel edge crosses the perspective ball's rim.
    pub(crate) fn integrate_endpoint_regular(&self, a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
        self.integrate(0.0, 1.0, |u| {
            let x = a + (b - a) * u * u * (3.0 - 2.0 * u);
            f(x) * (b - a) * 6.0 * u * (1.0 - u)
        })
    }

    /// `∫_a^b f`.
    pub(crate) fn integrate(&self, a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (a + b);
        half * self.nodes.iter().map(|&(x, w)| w * f(mid + half * x)).sum::<f64>()
    }
}

/// `(P_n(x), P_n'(x))` by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=n {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, dp)
}

/// An axis-aligned rectangle of the image plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// The corner of smallest coordinates.
    pub min: DVec2,
    /// The corner of largest coordinates.
    pub max: DVec2,
}

impl ProbeFormat {
    /// A validated format.
    ///
    /// # Errors
    /// [`InputError::OutOfRange`] for a perspective ball with `D/R ≤ 1` (camera inside the ball)
    /// or [`InputError::NonFinite`] for a non-finite `D/R`.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::envmap::ProbeFormat;
    /// assert!(ProbeFormat::perspective_ball(10.0).is_ok());
    /// assert!(ProbeFormat::perspective_ball(1.0).is_err());
    /// ```
    pub fn perspective_ball(distance_over_radius: f64) -> Result<Self, InputError> {
        if !distance_over_radius.is_finite() {
            return Err(InputError::NonFinite { name: "D/R", value: format!("{distance_over_radius}") });
        }
        if distance_over_radius <= 1.0 {
            return Err(InputError::OutOfRange {
                name: "D/R",
                value: format!("{distance_over_radius}"),
                expected: "> 1 (camera outside the ball)",
            });
        }
        Ok(Self::PerspectiveBall { distance_over_radius })
    }

    /// A short name for tables and figures.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(hw3_render::envmap::ProbeFormat::AngularMap.name(), "angular map");
    /// ```
    #[must_use]
    pub fn name(&self) -> String {
        match self {
            Self::MirrorBall => "mirror ball".into(),
            Self::PerspectiveBall { distance_over_radius } => format!("perspective ball D/R={distance_over_radius}"),
            Self::AngularMap => "angular map".into(),
            Self::LatLong => "lat-long".into(),
        }
    }

    /// The image rectangle: `[-1,1]²` for the disk formats, `[0,1]²` for lat-long.
    pub(crate) fn image_rect(&self) -> Rect {
        if *self == Self::LatLong {
            Rect { min: DVec2::ZERO, max: DVec2::ONE }
        } else {
            Rect { min: DVec2::splat(-1.0), max: DVec2::ONE }
        }
    }

    /// `θ(ρ)` for the disk formats (angle from `+z`, the direction back to the camera).
    fn theta_of_rho(&self, rho: f64) -> f64 {
        match *self {
            Self::MirrorBall => 2.0 * rho.min(1.0).asin(),
            Self::AngularMap => PI * rho,
            Self::PerspectiveBall { distance_over_radius: k } => {
                let (beta, incidence) = perspective_angles(k, rho);
                2.0 * incidence - beta
            }
            Self::LatLong => unreachable!("lat-long is not a disk format"),
        }
    }

    /// `dθ/dρ` for the disk formats (infinite at the rim of both balls).
    fn dtheta_drho(&self, rho: f64) -> f64 {
        match *self {
            Self::MirrorBall => 2.0 / (1.0 - rho * rho).max(0.0).sqrt(),
            Self::AngularMap => PI,
            Self::PerspectiveBall { distance_over_radius: k } => {
                let tan_max = 1.0 / (k * k - 1.0).sqrt();
                let (beta, incidence) = perspective_angles(k, rho);
                let dbeta = tan_max / (1.0 + rho * rho * tan_max * tan_max);
                (2.0 * k * beta.cos() / incidence.cos() - 1.0) * dbeta
            }
            Self::LatLong => unreachable!("lat-long is not a disk format"),
        }
    }

    /// The largest `θ` the disk format sees (`π`, or `π − arcsin(R/D)` for the perspective ball).
    ///
    /// # Examples
    /// ```
    /// use hw3_render::envmap::ProbeFormat;
    /// assert_eq!(ProbeFormat::MirrorBall.max_theta(), std::f64::consts::PI);
    /// let blind = std::f64::consts::PI - ProbeFormat::perspective_ball(2.0).unwrap().max_theta();
    /// assert!((blind.to_degrees() - 30.0).abs() < 1e-9); // arcsin(1/2)
    /// ```
    #[must_use]
    pub fn max_theta(&self) -> f64 {
        match *self {
            Self::PerspectiveBall { distance_over_radius: k } => PI - (1.0 / k).asin(),
            _ => PI,
        }
    }

    /// `ρ(θ)`, the inverse of `θ(ρ)`; `None` beyond [`Self::max_theta`] (the blind cone).
    fn rho_of_theta(&self, theta: f64) -> Option<f64> {
        match *self {
            Self::MirrorBall => Some((0.5 * theta).sin()),
            Self::AngularMap => Some(theta / PI),
            Self::PerspectiveBall { distance_over_radius: k } => {
                if theta > self.max_theta() {
                    return None;
                }
                // θ(ρ) increases monotonically on [0, 1]: bisection is robust up to the rim, where
                // dθ/dρ is infinite and Newton on ρ would stall. A guess may skip its first steps.
                let below = |rho: f64| self.theta_of_rho(rho) < theta;
                Some(match perspective_bracket(k, theta, below) {
                    Some(bracket) => bisect(bracket, BISECTION_STEPS - SKIPPED_STEPS, below),
                    None => bisect((0.0, 1.0), BISECTION_STEPS, below),
                })
            }
            Self::LatLong => unreachable!("lat-long is not a disk format"),
        }
    }

    /// `G(ρ) = 1 − cos θ(ρ)`: the solid angle inside image radius `ρ` is `2π G(ρ)`.
    fn cap_fraction(&self, rho: f64) -> f64 {
        let theta = self.theta_of_rho(rho);
        // 2 sin²(θ/2) keeps digits near θ = 0, where 1 − cos θ cancels.
        2.0 * (0.5 * theta).sin().powi(2)
    }

    /// The direction seen at image point `p`, or `None` outside the image (or outside the disk).
    ///
    /// # Examples
    /// ```
    /// use glam::{DVec2, DVec3};
    /// use hw3_render::envmap::ProbeFormat;
    /// // The centre of a mirror ball reflects the camera; halfway out (ρ = sin 45°) looks sideways.
    /// let centre = ProbeFormat::MirrorBall.image_to_direction(DVec2::ZERO).unwrap();
    /// assert!((centre - DVec3::Z).length() < 1e-15);
    /// let side = ProbeFormat::MirrorBall
    ///     .image_to_direction(DVec2::new(0.5_f64.sqrt(), 0.0))
    ///     .unwrap();
    /// assert!((side - DVec3::X).length() < 1e-12);
    /// ```
    #[must_use]
    pub fn image_to_direction(&self, p: DVec2) -> Option<DVec3> {
        if *self == Self::LatLong {
            if !(0.0..=1.0).contains(&p.x) || !(0.0..=1.0).contains(&p.y) {
                return None;
            }
            let (sin_t, cos_t) = (PI * p.y).sin_cos();
            let (sin_p, cos_p) = (TAU * p.x).sin_cos();
            return Some(DVec3::new(sin_t * cos_p, sin_t * sin_p, cos_t));
        }
        let rho = p.length();
        if rho.is_nan() || rho > 1.0 {
            return None;
        }
        let (sin_t, cos_t) = self.theta_of_rho(rho).sin_cos();
        let (cos_p, sin_p) = if rho > 0.0 { (p.x / rho, p.y / rho) } else { (1.0, 0.0) };
        Some(DVec3::new(sin_t * cos_p, sin_t * sin_p, cos_t))
    }

    /// The image point where `direction` (unit length) is seen; `None` in a blind cone.
    ///
    /// Numerics: exact round trips to ~1e-15 in the image; the direction round trip of the mirror
    /// ball loses digits within a few degrees of the rim, where `dθ/dρ → ∞`.
    ///
    /// # Examples
    /// ```
    /// use glam::{DVec2, DVec3};
    /// use hw3_render::envmap::ProbeFormat;
    /// let p = ProbeFormat::AngularMap.direction_to_image(DVec3::X).unwrap();
    /// assert!((p - DVec2::new(0.5, 0.0)).length() < 1e-15); // θ = 90° → ρ = ½
    /// let ball = ProbeFormat::perspective_ball(3.0).unwrap();
    /// assert!(ball.direction_to_image(-DVec3::Z).is_none()); // straight behind: blind
    /// ```
    #[must_use]
    pub fn direction_to_image(&self, direction: DVec3) -> Option<DVec2> {
        let planar = direction.x.hypot(direction.y);
        let theta = planar.atan2(direction.z);
        if *self == Self::LatLong {
            let phi = direction.y.atan2(direction.x).rem_euclid(TAU);
            return Some(DVec2::new(phi / TAU, theta / PI));
        }
        let rho = self.rho_of_theta(theta)?;
        if planar > 0.0 {
            Some(DVec2::new(direction.x, direction.y) * (rho / planar))
        } else {
            Some(DVec2::new(rho, 0.0))
        }
    }

    /// The Jacobian `dω/dA` (steradians per unit image area) at image point `p` inside the image.
    ///
    /// Mirror ball: 4 everywhere. Angular map: `π sin(πρ)/ρ`. Perspective ball: `(2D−1)²/(D²−1)`
    /// at the centre (with `R = 1`), diverging integrably at the rim. Lat-long: `2π² sin θ`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec2;
    /// use hw3_render::envmap::ProbeFormat;
    /// assert_eq!(ProbeFormat::MirrorBall.jacobian(DVec2::new(0.3, 0.2)), 4.0);
    /// let ball = ProbeFormat::perspective_ball(10.0).unwrap();
    /// assert!((ball.jacobian(DVec2::ZERO) - 19.0 * 19.0 / 99.0).abs() < 1e-9);
    /// ```
    #[must_use]
    pub fn jacobian(&self, p: DVec2) -> f64 {
        match self {
            Self::LatLong => 2.0 * PI * PI * (PI * p.y).sin(),
            Self::MirrorBall => 4.0,
            _ => {
                let rho = p.length();
                if rho < 1e-7 {
                    // sin θ / ρ → θ'(0) at the centre.
                    self.dtheta_drho(0.0).powi(2)
                } else {
                    self.theta_of_rho(rho).sin() * self.dtheta_drho(rho) / rho
                }
            }
        }
    }

    /// The image area of `rect` that lies inside the format's domain.
    pub(crate) fn area_inside(&self, rect: Rect) -> f64 {
        if *self == Self::LatLong { (rect.max - rect.min).element_product() } else { disk_rect_area(rect) }
    }

    /// The solid angle seen through image rectangle `rect` (the part inside the domain).
    pub(crate) fn solid_angle(&self, rect: Rect, rule: &GaussLegendre) -> f64 {
        match self {
            Self::LatLong => TAU * (rect.max.x - rect.min.x) * ((PI * rect.min.y).cos() - (PI * rect.max.y).cos()),
            Self::MirrorBall => 4.0 * disk_rect_area(rect),
            _ => self.polar_solid_angle(rect, rule),
        }
    }

    /// `∫ dφ [G(min(t_exit,1)) − G(min(t_enter,1))]` over the rays from the image centre that
    /// cross `rect`; the φ axis is split at every corner and every rim crossing so that each piece
    /// is smooth and Gauss–Legendre converges fast.
    fn polar_solid_angle(&self, rect: Rect, rule: &GaussLegendre) -> f64 {
        let corners = [rect.min, DVec2::new(rect.max.x, rect.min.y), rect.max, DVec2::new(rect.min.x, rect.max.y)];
        let contains_origin = rect.min.x <= 0.0 && rect.max.x >= 0.0 && rect.min.y <= 0.0 && rect.max.y >= 0.0;
        let centre = 0.5 * (rect.min + rect.max);
        let reference = if contains_origin { 0.0 } else { centre.y.atan2(centre.x) };
        let relative = |p: DVec2| {
            let a = p.y.atan2(p.x) - reference;
            (a + PI).rem_euclid(TAU) - PI
        };
        let mut breaks: Vec<f64> = corners.iter().filter(|c| c.length_squared() > 0.0).map(|&c| relative(c)).collect();
        let (lo, hi) = if contains_origin {
            (-PI, PI)
        } else {
            let lo = breaks.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = breaks.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (lo, hi)
        };
        for crossing in rim_crossings(rect) {
            breaks.push(relative(crossing));
        }
        breaks.retain(|b| *b > lo && *b < hi);
        breaks.push(lo);
        breaks.push(hi);
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        let integrand = |phi: f64| {
            let (sin_p, cos_p) = (phi + reference).sin_cos();
            match ray_rect_span(DVec2::new(cos_p, sin_p), rect) {
                Some((t_in, t_out)) if t_in < 1.0 => self.cap_fraction(t_out.min(1.0)) - self.cap_fraction(t_in),
                _ => 0.0,
            }
        };
        breaks.windows(2).map(|w| rule.integrate_endpoint_regular(w[0], w[1], integrand)).sum()
    }
}

/// Bisection steps of the perspective ball's `ρ(θ)` on `[0, 1]`: after 53 the bracket is one unit
/// in the last place wide for `ρ` near 1, and the last seven narrow it for smaller `ρ` (down to
/// `2⁻⁸`, where a bracket of `2⁻⁶⁰` is one unit in the last place).
const BISECTION_STEPS: u32 = 60;

/// The midpoint of `bracket` after `steps` halvings, each keeping the half whose ends `below`
/// separates (`below(lo)` true, `below(hi)` false).
fn bisect((mut lo, mut hi): (f64, f64), steps: u32, below: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..steps {
        let mid = 0.5 * (lo + hi);
        if below(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Steps of that bisection a verified guess skips ([`perspective_bracket`]).
const SKIPPED_STEPS: u32 = 40;

/// The bracket the perspective ball's bisection for `ρ(θ)` holds after [`SKIPPED_STEPS`] steps,
/// found without taking them, or `None` (the caller then bisects from `[0, 1]`). `below(ρ)` is the
/// bisection's test, `θ(ρ) < theta` as computed.
///
/// The guess solves the ball's reflection for the ray angle `β` by Newton's method: with
/// `i = (θ + β)/2` the angle of incidence and `sin i = (D/R) sin β` (the law of sines in the
/// triangle camera–centre–hit point), `g(β) = sin((θ + β)/2) − (D/R) sin β = 0`. Unlike `θ(ρ)`,
/// whose slope is infinite at the rim, `g` has slope `½ cos i − (D/R) cos β < 0` there too, so the
/// root stays simple. Then `ρ = tan β / tan β_max`.
///
/// The bisection's brackets after `n` steps are the dyadic intervals `[j, j + 1]·2⁻ⁿ`, and it
/// reaches the one whose ends `below` separates (an end at 0 or 1 untested, as in the bisection)
/// provided `below` is monotone at that spacing. For `D/R ≥ 1.1`, `θ(ρ)` rises by at least 1.36
/// per unit of `ρ` (by `√3` at `D/R = 2`; only a camera nearer the ball flattens it: 0.05 at
/// `D/R = 1.0001`), so by at least `1.2·10⁻¹²` across `2⁻⁴⁰`: thousands of times the few units in
/// the last place its computation may be off. At the rim `asin` magnifies its argument's rounding,
/// but there the argument `(D/R) sin β` itself moves by over a thousand units in the last place per
/// `2⁻⁴⁰`, so its computed values still rise. So this bracket is the one the full bisection
/// passes through, and the answer is the same double, bit for bit (a test compares the two on hard
/// and random inputs); the skipped tests become a few `sin`/`cos` and two evaluations of `θ(ρ)`
/// (22 in all instead of 60). Nearer cameras, `D/R < 1.1`, bisect in full.
fn perspective_bracket(k: f64, theta: f64, below: impl Fn(f64) -> bool) -> Option<(f64, f64)> {
    if k < 1.1 {
        return None;
    }
    let beta_max = (1.0 / k).asin();
    // Near the centre θ ≈ (2k − 1) β.
    let mut beta = (theta / (2.0 * k - 1.0)).clamp(0.0, beta_max);
    for _ in 0..8 {
        let (sin_i, cos_i) = (0.5 * (theta + beta)).sin_cos();
        let (sin_b, cos_b) = beta.sin_cos();
        let step = (sin_i - k * sin_b) / (0.5 * cos_i - k * cos_b);
        beta = (beta - step).clamp(0.0, beta_max);
        if step.abs() < 1e-15 {
            break;
        }
    }
    let guess = beta.tan() * (k * k - 1.0).sqrt();
    if !guess.is_finite() {
        return None;
    }
    // 2⁴⁰ cells of [0, 1]; every bracket end below is a multiple of 2⁻⁴⁰, exact in a double.
    let cells = (1_u64 << SKIPPED_STEPS) as f64;
    let j = (guess.clamp(0.0, 1.0) * cells).floor().min(cells - 1.0);
    let (lo, hi) = (j / cells, (j + 1.0) / cells);
    ((lo == 0.0 || below(lo)) && (hi == 1.0 || !below(hi))).then_some((lo, hi))
}

/// `(β, i)` of the perspective ball at image radius `ρ`: the ray's angle to the optical axis and
/// its angle of incidence on the ball, `sin i = (D/R) sin β`.
fn perspective_angles(k: f64, rho: f64) -> (f64, f64) {
    let tan_max = 1.0 / (k * k - 1.0).sqrt();
    let beta = (rho * tan_max).atan();
    let incidence = (k * beta.sin()).min(1.0).asin();
    (beta, incidence)
}

/// The parameter interval `[t_in, t_out]` (t ≥ 0) where the ray `t·dir` from the origin is inside
/// `rect`, if any (slab test).
fn ray_rect_span(dir: DVec2, rect: Rect) -> Option<(f64, f64)> {
    let mut t_in = 0.0_f64;
    let mut t_out = f64::INFINITY;
    for (d, lo, hi) in [(dir.x, rect.min.x, rect.max.x), (dir.y, rect.min.y, rect.max.y)] {
        if d == 0.0 {
            if lo > 0.0 || hi < 0.0 {
                return None;
            }
        } else {
            let (a, b) = (lo / d, hi / d);
            t_in = t_in.max(a.min(b));
            t_out = t_out.min(a.max(b));
        }
    }
    (t_out > t_in).then_some((t_in, t_out))
}

/// Points where the rectangle's edges cross the unit circle.
fn rim_crossings(rect: Rect) -> Vec<DVec2> {
    // The horizontal edges are the vertical edges of the transposed rectangle.
    let transpose = |p: DVec2| DVec2::new(p.y, p.x);
    let transposed = Rect { min: transpose(rect.min), max: transpose(rect.max) };
    let mut points = vertical_edge_crossings(rect);
    points.extend(vertical_edge_crossings(transposed).into_iter().map(transpose));
    points
}

/// Points where the edges `x = min.x` and `x = max.x` cross the unit circle.
fn vertical_edge_crossings(rect: Rect) -> Vec<DVec2> {
    [rect.min.x, rect.max.x]
        .into_iter()
        .filter(|x| x.abs() < 1.0)
        .flat_map(|x| {
            let y = (1.0 - x * x).sqrt();
            [DVec2::new(x, y), DVec2::new(x, -y)]
        })
        .filter(|p| (rect.min.y..=rect.max.y).contains(&p.y))
        .collect()
}

/// `∫_{-1}^{x} √(1−s²) ds` for `x ∈ [-1, 1]`.
fn half_disk_primitive(x: f64) -> f64 {
    let x = x.clamp(-1.0, 1.0);
    0.5 * (x * (1.0 - x * x).sqrt() + x.asin()) + 0.25 * PI
}

/// The exact area of `rect ∩ unit disk`: `∫ max(0, min(y₁, s) − max(y₀, −s)) dx` with
/// `s = √(1−x²)`, split where `s` crosses `|y₀|` and `|y₁|`, so that every piece integrates in
/// closed form.
pub(crate) fn disk_rect_area(rect: Rect) -> f64 {
    let x0 = rect.min.x.max(-1.0);
    let x1 = rect.max.x.min(1.0);
    if x1 <= x0 {
        return 0.0;
    }
    let mut breaks = vec![x0, x1];
    for y in [rect.min.y, rect.max.y] {
        if y.abs() < 1.0 {
            let x = (1.0 - y * y).sqrt();
            breaks.extend([x, -x].into_iter().filter(|b| *b > x0 && *b < x1));
        }
    }
    breaks.sort_by(f64::total_cmp);
    let chord = |x: f64| (1.0 - x * x).max(0.0).sqrt();
    breaks
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let s = chord(0.5 * (a + b));
            // Which of the four shapes the clipped chord has on this piece (decided at its middle).
            // Ties (the circle tangent to an edge at the midpoint) belong to the circle: pieces are
            // split at every crossing, so elsewhere on the piece the circle is strictly inside.
            let upper_is_circle = s <= rect.max.y;
            let lower_is_circle = -s >= rect.min.y;
            if s <= rect.min.y || -s >= rect.max.y {
                return 0.0;
            }
            let circle = half_disk_primitive(b) - half_disk_primitive(a);
            let upper = if upper_is_circle { circle } else { rect.max.y * (b - a) };
            let lower = if lower_is_circle { -circle } else { rect.min.y * (b - a) };
            upper - lower
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn all_formats() -> Vec<ProbeFormat> {
        vec![
            ProbeFormat::MirrorBall,
            ProbeFormat::AngularMap,
            ProbeFormat::perspective_ball(3.0).unwrap(),
            ProbeFormat::perspective_ball(10.0).unwrap(),
            ProbeFormat::LatLong,
        ]
    }

    #[test]
    fn gauss_legendre_integrates_degree_31_exactly() {
        let rule = GaussLegendre::new(16);
        let integral = rule.integrate(-1.0, 2.0, |x| x.powi(31));
        let exact = (2.0_f64.powi(32) - 1.0) / 32.0;
        assert!((integral / exact - 1.0).abs() < 1e-13);
    }

    #[test]
    fn disk_rect_area_matches_the_whole_disk_and_quadrants() {
        let whole = Rect { min: DVec2::splat(-2.0), max: DVec2::splat(2.0) };
        assert!((disk_rect_area(whole) - PI).abs() < 1e-14);
        let quadrant = Rect { min: DVec2::ZERO, max: DVec2::ONE };
        assert!((disk_rect_area(quadrant) - PI / 4.0).abs() < 1e-14);
        let inside = Rect { min: DVec2::new(-0.1, 0.2), max: DVec2::new(0.3, 0.5) };
        assert!((disk_rect_area(inside) - 0.12).abs() < 1e-15);
    }

    #[test]
    fn texel_solid_angles_sum_to_the_visible_sphere() {
        let rule = GaussLegendre::new(16);
        for format in all_formats() {
            for size in [1_usize, 2, 7, 32] {
                let rect = format.image_rect();
                let step = (rect.max - rect.min) / size as f64;
                let mut total = 0.0;
                for j in 0..size {
                    for i in 0..size {
                        let min = rect.min + step * DVec2::new(i as f64, j as f64);
                        total += format.solid_angle(Rect { min, max: min + step }, &rule);
                    }
                }
                let blind = 2.0 * PI * (1.0 + format.max_theta().cos());
                let expected = 4.0 * PI - blind;
                assert!((total - expected).abs() < 2e-9, "{} at {size}²: {total} vs {expected}", format.name());
            }
        }
    }

    #[test]
    fn polar_solid_angle_agrees_with_the_exact_mirror_ball_area() {
        // The mirror ball has a closed form; the polar quadrature must reproduce it texel by texel.
        let rule = GaussLegendre::new(16);
        let step = 2.0 / 9.0;
        for j in 0..9 {
            for i in 0..9 {
                let min = DVec2::new(-1.0 + step * i as f64, -1.0 + step * j as f64);
                let rect = Rect { min, max: min + DVec2::splat(step) };
                let exact = ProbeFormat::MirrorBall.solid_angle(rect, &rule);
                let polar = ProbeFormat::MirrorBall.polar_solid_angle(rect, &rule);
                assert!((exact - polar).abs() < 1e-7, "texel {i},{j}: {exact} vs {polar}");
            }
        }
    }

    /// The skipped bisection steps change no bit: on the hard angles (zero, the smallest, the blind
    /// cone's edge and the last doubles before it, and the `θ` of bracket ends of the skipped steps
    /// and their neighbours, where a guess lands on a cell's edge) and on a low-discrepancy sweep,
    /// for cameras from the nearest that skips (`D/R = 1.1`) to a far one, and for one nearer that
    /// bisects in full. The guess is verified on nearly every sweep angle, or nothing is saved.
    #[test]
    fn perspective_rho_of_theta_is_the_full_bisection_bit_for_bit() {
        let cells = (1_u64 << SKIPPED_STEPS) as f64;
        for k in [1.05, 1.1, 1.1000001, 1.5, 2.0, 3.0, 4.0, 10.0, 1e3, 1e6, 1e12] {
            let format = ProbeFormat::perspective_ball(k).unwrap();
            let max = format.max_theta();
            let mut hard =
                vec![0.0, f64::MIN_POSITIVE, 1e-300, 1e-12, max, max.next_down(), max.next_down().next_down()];
            hard.extend((1..16).map(|e| max * (1.0 - 10f64.powi(-e))));
            for j in [1.0, 2.0, 3.0, 0.25 * cells, 0.5 * cells, 0.9 * cells, cells - 2.0, cells - 1.0] {
                let theta = format.theta_of_rho(j / cells);
                hard.extend([theta.next_down(), theta, theta.next_up()]);
            }
            let golden = 0.5 * (5f64.sqrt() - 1.0);
            let sweep: Vec<f64> = (0..2000).map(|n| (n as f64 * golden).fract() * max).collect();
            for &theta in hard.iter().chain(&sweep).filter(|t| **t <= max) {
                let fast = format.rho_of_theta(theta).unwrap();
                // The full bisection from [0, 1], which `perspective_bracket` shortens.
                let full = bisect((0.0, 1.0), BISECTION_STEPS, |r| format.theta_of_rho(r) < theta);
                assert_eq!(fast.to_bits(), full.to_bits(), "D/R = {k}, θ = {theta:e}: {fast:e} vs {full:e}");
            }
            let skipped =
                sweep.iter().filter(|&&t| perspective_bracket(k, t, |r| format.theta_of_rho(r) < t).is_some()).count();
            if k < 1.1 {
                assert_eq!(skipped, 0, "D/R = {k}");
            } else {
                assert!(skipped >= 1990, "D/R = {k}: the guess held for {skipped} of 2000 angles");
            }
        }
    }

    #[test]
    fn perspective_ball_tends_to_the_orthographic_ball() {
        let far = ProbeFormat::perspective_ball(1e6).unwrap();
        for rho in [0.0, 0.3, 0.7, 0.95] {
            let p = DVec2::new(rho, 0.0);
            let a = far.image_to_direction(p).unwrap();
            let b = ProbeFormat::MirrorBall.image_to_direction(p).unwrap();
            assert!((a - b).length() < 1e-5, "ρ = {rho}");
        }
    }

    #[test]
    fn jacobian_integrates_to_the_visible_sphere() {
        // Independent of the texel quadrature: a radial integral of J ρ dρ dφ.
        let rule = GaussLegendre::new(16);
        for format in all_formats().into_iter().filter(|f| *f != ProbeFormat::LatLong) {
            // ρ = 1 − (1 − x)² removes the perspective ball's 1/√(1 − ρ) rim singularity.
            let pieces = 200;
            let total: f64 = (0..pieces)
                .map(|k| {
                    let a = k as f64 / pieces as f64;
                    let b = (k + 1) as f64 / pieces as f64;
                    rule.integrate(a, b, |x| {
                        let r = 1.0 - (1.0 - x) * (1.0 - x);
                        TAU * r * format.jacobian(DVec2::new(r, 0.0)) * 2.0 * (1.0 - x)
                    })
                })
                .sum();
            let expected = TAU * (1.0 - format.max_theta().cos());
            assert!((total - expected).abs() < 1e-9, "{}: {total} vs {expected}", format.name());
        }
    }

    proptest! {
        #[test]
        fn image_round_trips(x in -1.0_f64..1.0, y in -1.0_f64..1.0, which in 0_usize..5) {
            let format = all_formats()[which];
            let p = if format == ProbeFormat::LatLong {
                DVec2::new(0.5 * (x + 1.0), 0.5 * (y + 1.0))
            } else {
                DVec2::new(x, y)
            };
            if let Some(dir) = format.image_to_direction(p) {
                prop_assert!((dir.length() - 1.0).abs() < 1e-14);
                let back = format.direction_to_image(dir).unwrap();
                // lat-long wraps at φ = 2π and collapses at the poles; compare directions there.
                let again = format.image_to_direction(back).unwrap();
                prop_assert!((again - dir).length() < 1e-9, "{p} -> {dir} -> {back}");
                if format != ProbeFormat::LatLong {
                    prop_assert!((back - p).length() < 1e-9, "{p} -> {back}");
                }
            }
        }

        #[test]
        fn direction_round_trips(z in -1.0_f64..1.0, phi in 0.0_f64..TAU, which in 0_usize..5) {
            let format = all_formats()[which];
            let s = (1.0 - z * z).sqrt();
            let dir = DVec3::new(s * phi.cos(), s * phi.sin(), z);
            match format.direction_to_image(dir) {
                Some(p) => {
                    let back = format.image_to_direction(p).unwrap();
                    // Near the ball's rim θ(ρ) is ill-conditioned (dθ/dρ → ∞): allow √ε there.
                    let tolerance = if z < -0.999 { 1e-6 } else { 1e-10 };
                    prop_assert!((back - dir).length() < tolerance, "{dir} -> {p} -> {back}");
                }
                None => prop_assert!(dir.z.acos() > format.max_theta() - 1e-12),
            }
        }
    }
}
