//! Trims: the part of a surface's domain that is kept, bounded by closed polylines in the
//! surface's own parameters (issue 16).
//!
//! A [`Trim`] is read from the `"trim"` field of a surface file: one outer loop,
//! counter-clockwise in (u, v), and any number of holes, clockwise, each strictly inside the
//! outer loop and outside each other, no loop touching itself or another. [`Trim::validate`]
//! checks all that against the surface's domain with typed errors naming the loop and point.
//!
//! The trimmed region is where the even-odd rule over all loops says "inside". Walking each
//! loop in its given direction keeps the region on the left, which is how the facet stage
//! walks the boundary ([`crate::boundary`]).

use serde::{Deserialize, Serialize};

use crate::error::TpiError;
use crate::surface::Domain;

/// The trim of a surface: closed polylines in its parameters (not normalised). The closing
/// segment is implied; a last point equal to the first is accepted and ignored.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Trim {
    /// The outer loop, counter-clockwise in (u, v).
    pub outer: Vec<[f64; 2]>,
    /// The holes, each clockwise in (u, v).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub holes: Vec<Vec<[f64; 2]>>,
}

impl Trim {
    /// Every loop with its name in errors: `trim.outer`, `trim.holes[k]`.
    pub(crate) fn loops(&self) -> impl Iterator<Item = (String, &[[f64; 2]])> {
        std::iter::once(("trim.outer".to_string(), self.outer.as_slice())).chain(
            self.holes
                .iter()
                .enumerate()
                .map(|(k, h)| (format!("trim.holes[{k}]"), h.as_slice())),
        )
    }

    /// The loops without an explicit closing point (a last point equal to the first).
    pub(crate) fn open_loops(&self) -> Vec<Vec<[f64; 2]>> {
        self.loops()
            .map(|(_, points)| {
                let mut points = points.to_vec();
                if points.len() > 1 && points[0] == points[points.len() - 1] {
                    points.pop();
                }
                points
            })
            .collect()
    }

    /// Checks the trim against the surface's domain.
    ///
    /// Errors: [`TpiError::NonFinite`] for a NaN or infinite coordinate
    /// (`trim.holes[0][5][1]`); [`TpiError::InvalidTrim`] for a loop with fewer than three
    /// points, two consecutive equal points, a point outside the domain, an outer loop that
    /// is not counter-clockwise or a hole that is not clockwise, two segments that touch or
    /// cross (in one loop or between loops), a hole outside the outer loop or inside another
    /// hole.
    pub fn validate(&self, domain: &Domain) -> Result<(), TpiError> {
        let invalid = |item: String, reason: String| TpiError::InvalidTrim { item, reason };
        for (name, points) in self.loops() {
            for (k, p) in points.iter().enumerate() {
                for (axis, &x) in p.iter().enumerate() {
                    if !x.is_finite() {
                        return Err(TpiError::NonFinite {
                            field: format!("{name}[{k}][{axis}]"),
                            value: x,
                        });
                    }
                }
                if !domain.u.contains(p[0]) || !domain.v.contains(p[1]) {
                    return Err(invalid(
                        format!("{name}[{k}]"),
                        format!(
                            "({}, {}) lies outside the surface's domain [{}, {}] x [{}, {}]",
                            p[0], p[1], domain.u.min, domain.u.max, domain.v.min, domain.v.max
                        ),
                    ));
                }
            }
        }
        let loops = self.open_loops();
        let names: Vec<String> = self.loops().map(|(name, _)| name).collect();
        for (l, points) in loops.iter().enumerate() {
            if points.len() < 3 {
                return Err(invalid(
                    names[l].clone(),
                    format!(
                        "a loop needs at least 3 distinct points, found {}",
                        points.len()
                    ),
                ));
            }
            for k in 0..points.len() {
                if points[k] == points[(k + 1) % points.len()] {
                    return Err(invalid(
                        format!("{}[{}]", names[l], (k + 1) % points.len()),
                        format!("repeats the point before it ({k})"),
                    ));
                }
            }
            let area = signed_area(points);
            if l == 0 && !(area > 0.0) {
                return Err(invalid(
                    names[l].clone(),
                    "the outer loop must run counter-clockwise in (u, v) (its signed area is not positive); reverse its points".into(),
                ));
            }
            if l > 0 && !(area < 0.0) {
                return Err(invalid(
                    names[l].clone(),
                    "a hole must run clockwise in (u, v) (its signed area is not negative); reverse its points".into(),
                ));
            }
        }
        check_crossings(&loops, &names)?;
        // No segment touches another, so each hole is wholly inside or outside each loop:
        // its first point decides.
        for h in 1..loops.len() {
            let p = loops[h][0];
            if !in_polygon(&loops[0], p) {
                return Err(invalid(
                    names[h].clone(),
                    "the hole lies outside the outer loop".into(),
                ));
            }
            for (other, points) in loops.iter().enumerate().skip(1) {
                if other != h && in_polygon(points, p) {
                    return Err(invalid(
                        names[h].clone(),
                        format!("the hole lies inside another hole, {}", names[other]),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Whether (u, v) lies inside the trimmed region: the even-odd rule over all loops, by
    /// the classic crossing test (a ray towards +u, a segment counted when exactly one end
    /// lies above v). A point on a loop is decided by that rule too (so the left and bottom
    /// of a loop count as inside, the right and top as outside).
    pub fn contains(&self, uv: [f64; 2]) -> bool {
        self.open_loops()
            .iter()
            .fold(false, |inside, points| inside ^ in_polygon(points, uv))
    }
}

/// The shoelace area, positive counter-clockwise.
fn signed_area(points: &[[f64; 2]]) -> f64 {
    let n = points.len();
    let mut sum = 0.0;
    for k in 0..n {
        let (a, b) = (points[k], points[(k + 1) % n]);
        sum += a[0] * b[1] - b[0] * a[1];
    }
    0.5 * sum
}

/// Even-odd point-in-polygon test (crossings of the ray to +u; W. R. Franklin's form).
pub(crate) fn in_polygon(points: &[[f64; 2]], p: [f64; 2]) -> bool {
    let n = points.len();
    let mut inside = false;
    let mut j = n - 1;
    for i in 0..n {
        let (a, b) = (points[i], points[j]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]
        {
            inside = !inside;
        }
        j = i;
    }
    inside
}

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    crate::predicates::orient2d(a, b, c)
}

/// Whether the closed segments ab and cd share a point.
fn segments_meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return true;
    }
    let within = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        r[0] >= p[0].min(q[0])
            && r[0] <= p[0].max(q[0])
            && r[1] >= p[1].min(q[1])
            && r[1] <= p[1].max(q[1])
    };
    (o1 == 0.0 && within(a, b, c))
        || (o2 == 0.0 && within(a, b, d))
        || (o3 == 0.0 && within(c, d, a))
        || (o4 == 0.0 && within(c, d, b))
}

/// Rejects two segments that meet, other than consecutive segments of one loop at their
/// shared point. Segments are sorted by their smallest u, and each is tested against those
/// whose u-range overlaps it.
fn check_crossings(loops: &[Vec<[f64; 2]>], names: &[String]) -> Result<(), TpiError> {
    // (loop, index of the segment's first point)
    let mut segments: Vec<(usize, usize, [f64; 2], [f64; 2])> = Vec::new();
    for (l, points) in loops.iter().enumerate() {
        for k in 0..points.len() {
            segments.push((l, k, points[k], points[(k + 1) % points.len()]));
        }
    }
    segments.sort_by(|x, y| x.2[0].min(x.3[0]).total_cmp(&y.2[0].min(y.3[0])));
    for (i, &(l, k, a, b)) in segments.iter().enumerate() {
        let hi = a[0].max(b[0]);
        for &(m, j, c, d) in &segments[i + 1..] {
            if c[0].min(d[0]) > hi {
                break;
            }
            if l == m {
                let n = loops[l].len();
                let adjacent = (k + 1) % n == j || (j + 1) % n == k;
                if adjacent {
                    // Consecutive segments meet at their shared point only; they overlap
                    // when the loop turns back on itself.
                    let (shared, p, q) = if (k + 1) % n == j {
                        (b, a, d)
                    } else {
                        (a, b, c)
                    };
                    let _ = shared;
                    let turn = orient(p, shared, q);
                    let back = (q[0] - shared[0]) * (p[0] - shared[0])
                        + (q[1] - shared[1]) * (p[1] - shared[1]);
                    if turn == 0.0 && back > 0.0 && n > 3 {
                        return Err(TpiError::InvalidTrim {
                            item: names[l].clone(),
                            reason: format!(
                                "the loop turns back on itself at point {}",
                                if (k + 1) % n == j { j } else { k }
                            ),
                        });
                    }
                    continue;
                }
            }
            if segments_meet(a, b, c, d) {
                let (first, second) = if (l, k) < (m, j) {
                    ((l, k), (m, j))
                } else {
                    ((m, j), (l, k))
                };
                let reason = if first.0 == second.0 {
                    format!(
                        "the loop intersects itself: segment {} and segment {} meet",
                        first.1, second.1
                    )
                } else {
                    format!(
                        "segment {} meets segment {} of {}",
                        second.1, first.1, names[first.0]
                    )
                };
                return Err(TpiError::InvalidTrim {
                    item: names[second.0].clone(),
                    reason,
                });
            }
        }
    }
    Ok(())
}
