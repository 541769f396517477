//! Closest-point projection onto a surface, extended beyond its boundary.
//!
//! The foot of x is the (u, v) minimising |S(u, v) - x|^2, found by Newton's method on
//! g = J^T (x - S) = 0 with J = [Su Sv] and Hessian J^T J - [[r.Suu, r.Suv], [r.Suv, r.Svv]],
//! r = x - S. Outside the domain the surface is continued by its tangent plane at the nearest
//! domain point (S_ext(u, v) = S(c) + Su(c) (u - cu) + Sv(c) (v - cv), c the clamped
//! parameters), a C1 extension that gives every point in space a foot, so that "inside" and
//! "outside" the surface's boundary are defined for facet vertices near the edge.
//!
//! At the foot, x - S lies along the surface normal; so x lies on the ruled "wall" spanned by
//! the normals along the boundary curve exactly when its foot lies on the domain boundary.
//! [`inside_measure`] is the signed normalised distance of the foot to the domain boundary.

use glam::DVec3;

use crate::surface::{Domain, Surface};
use crate::tolerance::{
    DISTANCE_FOOT_MIN_FOCAL_FACTOR, DISTANCE_FOOT_STEP_TOLERANCE, MAX_PROJECTION_ITERATIONS,
    POLE_RESTART_BAND, PROJECTION_STEP_TOLERANCE, SIDE_DECISION_MAX_CONTRACTION,
    SIDE_DECISION_SAFETY,
};

/// The foot of `x` on the (extended) surface, starting from `guess`.
pub(crate) fn foot(surface: &dyn Surface, domain: &Domain, x: DVec3, guess: [f64; 2]) -> [f64; 2] {
    periodic_foot(surface, domain, x, guess, [false; 2], [false; 4])
}

/// [`foot`] to the accuracy the distance |S(foot) - x| needs, for the quality report's
/// deviation: Newton stops after a full-Hessian step shorter than
/// [`DISTANCE_FOOT_STEP_TOLERANCE`]. After such a step of length s the foot is off by
/// O(s^2) (quadratic convergence), and the distance, stationary at the foot, by O(s^4):
/// below 1e-20 of the domain's scale, where [`foot`] takes one or two more evaluations to
/// see its last step fall below [`PROJECTION_STEP_TOLERANCE`]. Gauss-Newton steps (where
/// the full Hessian is not positive definite, or outside the domain) converge only linearly,
/// and near the focal surface ((1 - k1 d)(1 - k2 d) below
/// [`DISTANCE_FOOT_MIN_FOCAL_FACTOR`], d the distance) the quadratic constant is unbounded:
/// those keep the strict tolerance.
///
/// On a closed surface the foot is found across the seam and past a pole as by
/// [`periodic_foot`] (`wrap`): clamped at the seam, a vertex near it would be measured from
/// the wrong side, ten times the true distance on Rhino's ellipsoids. Near a pole, where the
/// Jacobian vanishes, Newton may stop on the wrong side of it: there it starts again half a
/// turn round ([`Wrap::across_pole`]) and the nearer foot is kept.
pub(crate) fn distance_foot(
    surface: &dyn Surface,
    wrap: &Wrap,
    x: DVec3,
    guess: [f64; 2],
) -> [f64; 2] {
    let newton = |start: [f64; 2]| {
        newton_foot(
            surface,
            &wrap.domain,
            x,
            start,
            wrap.periodic,
            wrap.poles,
            DISTANCE_FOOT_STEP_TOLERANCE,
            None,
        )
    };
    let foot = newton(guess);
    let Some(start) = wrap.across_pole(foot) else {
        return foot;
    };
    let other = newton(start);
    let distance = |[u, v]: [f64; 2]| {
        let (u, v) = wrap.domain.clamp(u, v);
        surface.point_at(u, v).distance(x)
    };
    if distance(other) < distance(foot) {
        other
    } else {
        foot
    }
}

/// The deviation of `x` as the quality report measures it, given its `foot` (from
/// [`distance_foot`]): the distance from x to the surface at the foot clamped into the
/// domain. Also returns the clamped foot.
pub(crate) fn deviation_at(
    surface: &dyn Surface,
    domain: &Domain,
    x: DVec3,
    foot: [f64; 2],
) -> (f64, [f64; 2]) {
    let (u, v) = domain.clamp(foot[0], foot[1]);
    (surface.point_at(u, v).distance(x), [u, v])
}

/// How a projection continues beyond the sides of a surface's domain: across the seam of a
/// closed direction and past a pole ([`periodic_foot`]), by the tangent plane elsewhere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Wrap {
    /// The surface's domain.
    pub domain: Domain,
    /// Closed in u, in v.
    pub periodic: [bool; 2],
    /// Pole sides (u0, u1, v0, v1) of a surface closed the other way.
    pub poles: [bool; 4],
}

impl Wrap {
    /// Where `uv` lies within [`POLE_RESTART_BAND`] (normalised) of a pole side: the same
    /// distance from the pole, half a turn round it (a second start for Newton). None
    /// elsewhere.
    pub(crate) fn across_pole(&self, [u, v]: [f64; 2]) -> Option<[f64; 2]> {
        let [s, t] = self.domain.to_normalised([u, v]);
        let near = |k: usize, x: f64| {
            (self.poles[2 * k] && x < POLE_RESTART_BAND)
                || (self.poles[2 * k + 1] && x > 1.0 - POLE_RESTART_BAND)
        };
        if self.periodic[0] && near(1, t) {
            Some([u + 0.5 * self.domain.u.length(), v])
        } else if self.periodic[1] && near(0, s) {
            Some([u, v + 0.5 * self.domain.v.length()])
        } else {
            None
        }
    }

    /// The wrap of `surface`, from its sampled layout ([`crate::closed::surface_layout`]).
    pub(crate) fn of(surface: &dyn Surface) -> Self {
        Wrap::from_layout(surface.domain(), &crate::closed::surface_layout(surface))
    }

    /// The wrap of a surface with this domain and layout.
    pub(crate) fn from_layout(domain: Domain, layout: &crate::closed::SurfaceLayout) -> Self {
        Wrap {
            domain,
            periodic: layout.closed,
            poles: layout.poles,
        }
    }
}

/// [`foot`] on a surface closed in the directions marked `periodic` (u, v): there the
/// parameter wraps around the domain at every step instead of leaving it, so the foot is
/// found across the seam, and it is returned within the domain in those directions. Across a
/// side marked in `poles` (u0, u1, v0, v1) of a surface closed the other way, the surface
/// goes on at the opposite side of the pole: the parameter is reflected across the side and
/// the other one turned by half a period (exact for a surface of revolution).
pub(crate) fn periodic_foot(
    surface: &dyn Surface,
    domain: &Domain,
    x: DVec3,
    guess: [f64; 2],
    periodic: [bool; 2],
    poles: [bool; 4],
) -> [f64; 2] {
    newton_foot(
        surface,
        domain,
        x,
        guess,
        periodic,
        poles,
        PROJECTION_STEP_TOLERANCE,
        None,
    )
}

/// [`periodic_foot`] where only the side of the boundary the foot lies on matters, and the
/// foot itself only as a guess for later projections: Newton stops as soon as the iterates
/// show the foot outside (`inside_measure` negative, 1-Lipschitz in normalised parameters)
/// by more than their remaining error can reach, by the a-posteriori estimate of a
/// contracting iteration. After steps s_(k-1), s_k (normalised, L1) with contraction
/// q = s_k / s_(k-1) <= [`SIDE_DECISION_MAX_CONTRACTION`], the iterates still move by at
/// most s_k q / (1 - q) <= s_k; Newton stops when the measure of the current iterate is
/// below -[`SIDE_DECISION_SAFETY`] s_k. A foot inside, or not decided so, is converged as by
/// [`periodic_foot`].
pub(crate) fn outside_foot(
    surface: &dyn Surface,
    domain: &Domain,
    x: DVec3,
    guess: [f64; 2],
    (periodic, poles): ([bool; 2], [bool; 4]),
    inside_measure: &dyn Fn([f64; 2]) -> f64,
) -> [f64; 2] {
    newton_foot(
        surface,
        domain,
        x,
        guess,
        periodic,
        poles,
        PROJECTION_STEP_TOLERANCE,
        Some(inside_measure),
    )
}

/// [`periodic_foot`], stopping after a full-Hessian step shorter than `quadratic_stop`
/// (normalised) or any step shorter than [`PROJECTION_STEP_TOLERANCE`], or, given
/// `outside_by`, as soon as the foot is decided outside ([`outside_foot`]).
// The surface, its domain and wrap, the point, the start and the two stopping rules.
#[allow(clippy::too_many_arguments)]
fn newton_foot(
    surface: &dyn Surface,
    domain: &Domain,
    x: DVec3,
    guess: [f64; 2],
    periodic: [bool; 2],
    poles: [bool; 4],
    quadratic_stop: f64,
    outside_by: Option<&dyn Fn([f64; 2]) -> f64>,
) -> [f64; 2] {
    let interval = |k: usize| if k == 0 { domain.u } else { domain.v };
    let wrap = |[mut u, mut v]: [f64; 2]| {
        for k in 0..2 {
            let other = 1 - k;
            if !periodic[other] {
                continue;
            }
            let (value, turned) = if k == 0 {
                (&mut u, &mut v)
            } else {
                (&mut v, &mut u)
            };
            let range = interval(k);
            let half = 0.5 * interval(other).length();
            if poles[2 * k] && *value < range.min {
                *value = 2.0 * range.min - *value;
                *turned += half;
            } else if poles[2 * k + 1] && *value > range.max {
                *value = 2.0 * range.max - *value;
                *turned += half;
            }
        }
        let mut uv = [u, v];
        for (k, value) in uv.iter_mut().enumerate() {
            let range = interval(k);
            if periodic[k] && value.is_finite() {
                *value = range.min + (*value - range.min).rem_euclid(range.length());
            }
        }
        uv
    };
    let [mut u, mut v] = wrap(guess);
    let (du_scale, dv_scale) = (domain.u.length(), domain.v.length());
    // Outside the domain the step is Gauss-Newton's on the tangent-plane extension, which reads
    // the first derivatives alone; they are kept for the next iteration, which often clamps to
    // the same boundary point (beyond a corner always).
    // (Compared bit for bit: -0.0 and 0.0 are different arguments.)
    let mut outside: Option<([u64; 2], [DVec3; 3])> = None;
    let mut previous_step = f64::INFINITY;
    for _ in 0..MAX_PROJECTION_ITERATIONS {
        let (cu, cv) = domain.clamp(u, v);
        let inside = cu == u && cv == v;
        let (point, su, sv, second) = if inside {
            let d = surface.evaluate(cu, cv);
            (d.point, d.su, d.sv, Some([d.suu, d.suv, d.svv]))
        } else {
            let at = [cu.to_bits(), cv.to_bits()];
            let first = match outside {
                Some((last, first)) if last == at => first,
                _ => surface.first_derivatives(cu, cv),
            };
            outside = Some((at, first));
            let [point, su, sv] = first;
            (point, su, sv, None)
        };
        let s = point + su * (u - cu) + sv * (v - cv);
        let r = x - s;
        let g = [su.dot(r), sv.dot(r)];
        let mut h = [su.dot(su), su.dot(sv), sv.dot(sv)];
        let mut quadratic = false;
        if let Some([suu, suv, svv]) = second {
            let full = [h[0] - r.dot(suu), h[1] - r.dot(suv), h[2] - r.dot(svv)];
            let full_det = full[0] * full[2] - full[1] * full[1];
            if full[0] > 0.0 && full_det > 0.0 {
                // det(J^T J - r.II) / det(J^T J) = (1 - k1 d)(1 - k2 d): near the focal
                // surface Newton's quadratic constant grows without bound.
                let metric_det = h[0] * h[2] - h[1] * h[1];
                quadratic = full_det > DISTANCE_FOOT_MIN_FOCAL_FACTOR * metric_det;
                h = full;
            }
        }
        let det = h[0] * h[2] - h[1] * h[1];
        if !(det.abs() > 0.0) || !det.is_finite() {
            break;
        }
        let step_u = (h[2] * g[0] - h[1] * g[1]) / det;
        let step_v = (h[0] * g[1] - h[1] * g[0]) / det;
        if !step_u.is_finite() || !step_v.is_finite() {
            break;
        }
        [u, v] = wrap([u + step_u, v + step_v]);
        let step = (step_u / du_scale).abs() + (step_v / dv_scale).abs();
        if step < PROJECTION_STEP_TOLERANCE || (quadratic && step < quadratic_stop) {
            break;
        }
        if let Some(measure) = outside_by {
            if step <= SIDE_DECISION_MAX_CONTRACTION * previous_step
                && measure([u, v]) < -SIDE_DECISION_SAFETY * step
            {
                break;
            }
        }
        previous_step = step;
    }
    [u, v]
}

/// Signed distance of `uv` from the domain boundary in normalised parameters:
/// min(s, 1 - s, t, 1 - t), positive inside.
pub(crate) fn inside_measure(domain: &Domain, uv: [f64; 2]) -> f64 {
    let [s, t] = domain.to_normalised(uv);
    s.min(1.0 - s).min(t).min(1.0 - t)
}

/// Position along the boundary loop, in [0, 4): side 0 is v = v0 (u rising), side 1 is
/// u = u1 (v rising), side 2 is v = v1 (u falling), side 3 is u = u0 (v falling), so that
/// the loop runs counter-clockwise in parameter space and corner c sits at c.
pub(crate) fn boundary_parameter(domain: &Domain, uv: [f64; 2]) -> f64 {
    let [s, t] = domain.to_normalised(uv);
    let s = s.clamp(0.0, 1.0);
    let t = t.clamp(0.0, 1.0);
    let distances = [t, 1.0 - s, 1.0 - t, s];
    let mut side = 0;
    for k in 1..4 {
        if distances[k] < distances[side] {
            side = k;
        }
    }
    match side {
        0 => s,
        1 => 1.0 + t,
        2 => 2.0 + (1.0 - s),
        _ => (3.0 + (1.0 - t)) % 4.0,
    }
}

/// The corners of the domain in boundary-loop order (corner c at boundary parameter c).
pub(crate) fn domain_corners(domain: &Domain) -> [[f64; 2]; 4] {
    [
        [domain.u.min, domain.v.min],
        [domain.u.max, domain.v.min],
        [domain.u.max, domain.v.max],
        [domain.u.min, domain.v.max],
    ]
}
