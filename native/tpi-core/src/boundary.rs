//! The boundary the facet stage clips on: closed loops in parameter space.
//!
//! An untrimmed surface has one loop, its domain rectangle, with the four domain corners
//! ([`crate::projection`]'s measure and parameter, unchanged). A trimmed surface
//! ([`crate::Trim`]) has its outer loop and holes, every polyline point a corner. For both:
//!
//! - the **inside measure** of a parameter pair is its signed distance from the boundary in
//!   normalised parameters, positive inside (1-Lipschitz, as `facets::surely_inside` needs);
//! - a **position** on the boundary is (loop, arclength along the loop in its own direction,
//!   which keeps the region on the left: counter-clockwise around the outer loop, clockwise
//!   around holes); the rectangle's loop has length 4, corner c at c;
//! - a **corner** is a parameter pair with its position; the facet that leaves the region
//!   just before a corner (along its loop) holds it.
//!
//! A surface closed in one direction and discretised across its seam (a flat ring) is a
//! **band**: its walls are only its open sides (not its seam, nor a pole), each a loop of its
//! own of length 1 without corners, and the inside measure is the distance from the nearest
//! of them, whatever the parameter along the closed direction.

use crate::projection::{boundary_parameter, domain_corners, inside_measure};
use crate::surface::Domain;
use crate::trim::Trim;

/// A point's place on the boundary: its loop and the arclength along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Position {
    /// Which loop (0: the rectangle or the outer loop; 1.. the holes).
    pub(crate) curve: u32,
    /// Arclength from the loop's first point in its own direction (normalised parameters;
    /// the rectangle's sides count 1 each).
    pub(crate) along: f64,
}

/// The boundary of the region that facets are clipped to.
pub(crate) enum Boundary {
    /// The domain rectangle.
    Rectangle(Domain),
    /// A trim's loops.
    Loops(Loops),
    /// The open sides (u0, u1, v0, v1) of a surface closed across the others (module doc).
    Band {
        /// The domain.
        domain: Domain,
        /// Which sides are walls.
        walls: [bool; 4],
        /// The directions (u, v) in which the surface is closed.
        closed: [bool; 2],
    },
}

/// A trim's loops in normalised parameters.
pub(crate) struct Loops {
    domain: Domain,
    /// Per loop, its points in normalised parameters.
    points: Vec<Vec<[f64; 2]>>,
    /// Per loop, the arclength at each point (one more entry: the loop's length).
    arclength: Vec<Vec<f64>>,
    /// Every point of every loop in order: (parameters in the domain, position).
    corners: Vec<([f64; 2], Position)>,
}

impl Boundary {
    /// The boundary of `domain`, trimmed by `trim` when given (validated before).
    pub(crate) fn new(domain: Domain, trim: Option<&Trim>) -> Boundary {
        let Some(trim) = trim else {
            return Boundary::Rectangle(domain);
        };
        let mut loops = Loops {
            domain,
            points: Vec::new(),
            arclength: Vec::new(),
            corners: Vec::new(),
        };
        for (l, raw) in trim.open_loops().into_iter().enumerate() {
            let points: Vec<[f64; 2]> = raw.iter().map(|&p| domain.to_normalised(p)).collect();
            let n = points.len();
            let mut arclength = Vec::with_capacity(n + 1);
            let mut total = 0.0;
            for k in 0..n {
                arclength.push(total);
                loops.corners.push((
                    raw[k],
                    Position {
                        curve: l as u32,
                        along: total,
                    },
                ));
                let (a, b) = (points[k], points[(k + 1) % n]);
                total += (b[0] - a[0]).hypot(b[1] - a[1]);
            }
            arclength.push(total);
            loops.points.push(points);
            loops.arclength.push(arclength);
        }
        Boundary::Loops(loops)
    }

    /// The trim's loops in normalised parameters, each in its own direction (region on the
    /// left); none for the rectangle.
    pub(crate) fn loops(&self) -> &[Vec<[f64; 2]>] {
        match self {
            Boundary::Rectangle(_) | Boundary::Band { .. } => &[],
            Boundary::Loops(loops) => &loops.points,
        }
    }

    /// The directions (u, v) in which parameters wrap around (a band's seam).
    pub(crate) fn periodic(&self) -> [bool; 2] {
        match self {
            Boundary::Band { closed, .. } => *closed,
            _ => [false; 2],
        }
    }

    /// A band's wall nearest to `uv` (u0, u1, v0, v1 as 0..4) and its normalised distance,
    /// negative beyond it; None for other boundaries, or a band without walls.
    fn nearest_wall(&self, uv: [f64; 2]) -> Option<(usize, f64)> {
        let Boundary::Band {
            domain,
            walls,
            closed,
        } = self
        else {
            return None;
        };
        let [s, t] = band_parameters(domain, walls, closed, uv);
        let distances = [s, 1.0 - s, t, 1.0 - t];
        (0..4)
            .filter(|&k| walls[k])
            .map(|k| (k, distances[k]))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// The sides (u0, u1, v0, v1) that are poles of a band (no wall, across its seam).
    pub(crate) fn poles(&self) -> [bool; 4] {
        match self {
            Boundary::Band { walls, closed, .. } => {
                let pole = |side: usize| !walls[side] && !closed[side / 2];
                [pole(0), pole(1), pole(2), pole(3)]
            }
            _ => [false; 4],
        }
    }

    /// Whether the region is convex in normalised parameters (the domain rectangle), so that
    /// a segment between two inside points stays inside.
    pub(crate) fn is_convex(&self) -> bool {
        matches!(self, Boundary::Rectangle(_))
    }

    /// Whether this is a trim's boundary.
    pub(crate) fn is_trim(&self) -> bool {
        matches!(self, Boundary::Loops(_))
    }

    /// Signed normalised distance of `uv` from the boundary, positive inside.
    pub(crate) fn inside_measure(&self, uv: [f64; 2]) -> f64 {
        match self {
            Boundary::Rectangle(domain) => inside_measure(domain, uv),
            Boundary::Band { .. } => self.nearest_wall(uv).map_or(f64::INFINITY, |w| w.1),
            Boundary::Loops(loops) => {
                let (distance, _) = loops.nearest(uv);
                if loops.contains_normalised(loops.domain.to_normalised(uv)) {
                    distance
                } else {
                    -distance
                }
            }
        }
    }

    /// The position on the boundary nearest to `uv`.
    pub(crate) fn position(&self, uv: [f64; 2]) -> Position {
        match self {
            Boundary::Rectangle(domain) => Position {
                curve: 0,
                along: boundary_parameter(domain, uv),
            },
            Boundary::Band {
                domain,
                walls,
                closed,
            } => {
                let [s, t] = band_parameters(domain, walls, closed, uv);
                let wall = self.nearest_wall(uv).map_or(0, |w| w.0);
                // Along each wall with the region on the left (as the rectangle's sides run).
                let along = match wall {
                    0 => 1.0 - t.rem_euclid(1.0),
                    1 => t.rem_euclid(1.0),
                    2 => s.rem_euclid(1.0),
                    _ => 1.0 - s.rem_euclid(1.0),
                };
                Position {
                    curve: wall as u32,
                    along,
                }
            }
            Boundary::Loops(loops) => loops.nearest(uv).1,
        }
    }

    /// The corners in order: parameters in the domain and position.
    pub(crate) fn corners(&self) -> Vec<([f64; 2], Position)> {
        match self {
            Boundary::Rectangle(domain) => domain_corners(domain)
                .into_iter()
                .enumerate()
                .map(|(c, uv)| {
                    (
                        uv,
                        Position {
                            curve: 0,
                            along: c as f64,
                        },
                    )
                })
                .collect(),
            Boundary::Loops(loops) => loops.corners.clone(),
            Boundary::Band { .. } => Vec::new(),
        }
    }

    /// The fractions tau in (0, 1), ascending, at which the parameter segment from `a` to `b`
    /// (a + tau (b - a)) crosses a boundary loop, in normalised parameters.
    pub(crate) fn segment_crossings(&self, a: [f64; 2], b: [f64; 2]) -> Vec<f64> {
        // The boundary as segments in normalised parameters: the rectangle's sides in loop
        // order (v0, u1, v1, u0), a band's walls among them, or the trim's loops.
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let side = |k: usize| (corners[k], corners[(k + 1) % 4]);
        let (domain, segments): (Domain, Vec<Segment>) = match self {
            Boundary::Rectangle(d) => (*d, (0..4).map(side).collect()),
            Boundary::Band { domain, walls, .. } => {
                // Loop side k is the wall [v0, u1, v1, u0][k].
                let wall = [2, 1, 3, 0];
                let open = (0..4).filter(|&k| walls[wall[k]]).map(side).collect();
                (*domain, open)
            }
            Boundary::Loops(loops) => (
                loops.domain,
                loops
                    .points
                    .iter()
                    .flat_map(|l| (0..l.len()).map(move |k| (l[k], l[(k + 1) % l.len()])))
                    .collect(),
            ),
        };
        let (p, q) = (domain.to_normalised(a), domain.to_normalised(b));
        let d = [q[0] - p[0], q[1] - p[1]];
        let mut found = Vec::new();
        for (c, e) in segments {
            let f = [e[0] - c[0], e[1] - c[1]];
            let denominator = d[0] * f[1] - d[1] * f[0];
            if denominator == 0.0 {
                continue;
            }
            let w = [c[0] - p[0], c[1] - p[1]];
            let tau = (w[0] * f[1] - w[1] * f[0]) / denominator;
            let sigma = (w[0] * d[1] - w[1] * d[0]) / denominator;
            if tau > 0.0 && tau < 1.0 && (0.0..=1.0).contains(&sigma) {
                found.push(tau);
            }
        }
        found.sort_by(f64::total_cmp);
        found
    }

    /// How far `to` lies ahead of `from` along their loop (in its direction), or None when
    /// they lie on different loops.
    pub(crate) fn ahead(&self, from: Position, to: Position) -> Option<f64> {
        if from.curve != to.curve {
            return None;
        }
        Some((to.along - from.along).rem_euclid(self.loop_length(from.curve)))
    }

    /// As [`Boundary::ahead`], but a `to` less than `slack` behind `from` is that far behind
    /// (negative) rather than almost a whole loop ahead.
    pub(crate) fn ahead_or_just_behind(
        &self,
        from: Position,
        to: Position,
        slack: f64,
    ) -> Option<f64> {
        let ahead = self.ahead(from, to)?;
        let length = self.loop_length(from.curve);
        Some(if ahead > length - slack {
            ahead - length
        } else {
            ahead
        })
    }

    /// The length of loop `curve` (normalised parameters).
    fn loop_length(&self, curve: u32) -> f64 {
        match self {
            Boundary::Rectangle(_) => 4.0,
            Boundary::Band { .. } => 1.0,
            Boundary::Loops(loops) => {
                let a = &loops.arclength[curve as usize];
                a[a.len() - 1]
            }
        }
    }
}

/// A segment between two points in normalised parameters.
type Segment = ([f64; 2], [f64; 2]);

/// Normalised parameters of `uv` on a band: beyond a pole (a side of the open direction that
/// is no wall) the surface continues on the other side of the pole, so the parameter there
/// is reflected across it.
fn band_parameters(
    domain: &Domain,
    walls: &[bool; 4],
    closed: &[bool; 2],
    uv: [f64; 2],
) -> [f64; 2] {
    let mut st = domain.to_normalised(uv);
    for k in 0..2 {
        if closed[k] {
            continue;
        }
        if !walls[2 * k] && st[k] < 0.0 {
            st[k] = -st[k];
        }
        if !walls[2 * k + 1] && st[k] > 1.0 {
            st[k] = 2.0 - st[k];
        }
    }
    st
}

impl Loops {
    /// Distance (normalised) of `uv` from the nearest loop point, and that point's position.
    fn nearest(&self, uv: [f64; 2]) -> (f64, Position) {
        let p = self.domain.to_normalised(uv);
        let mut best = (f64::INFINITY, 0usize, 0usize, 0.0f64);
        for (l, points) in self.points.iter().enumerate() {
            let n = points.len();
            for k in 0..n {
                let (a, b) = (points[k], points[(k + 1) % n]);
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let length2 = dx * dx + dy * dy;
                let tau = if length2 > 0.0 {
                    (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let (x, y) = (a[0] + tau * dx - p[0], a[1] + tau * dy - p[1]);
                let d2 = x * x + y * y;
                if d2 < best.0 {
                    best = (d2, l, k, tau);
                }
            }
        }
        let (d2, l, k, tau) = best;
        let arclength = &self.arclength[l];
        let along = arclength[k] + tau * (arclength[k + 1] - arclength[k]);
        (
            d2.sqrt(),
            Position {
                curve: l as u32,
                along,
            },
        )
    }

    /// Even-odd test over all loops, in normalised parameters.
    fn contains_normalised(&self, p: [f64; 2]) -> bool {
        self.points.iter().fold(false, |inside, points| {
            inside ^ crate::trim::in_polygon(points, p)
        })
    }
}
