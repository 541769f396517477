//! Aligned patterns: hexagonal and square lattices laid along a direction field on the
//! surface, so that the TPI facets' edges follow the field (issue 15, item 3).
//!
//! ## The geometry
//!
//! Near a seed the surface is z = 1/2 x^T A x over its tangent plane, A the second
//! fundamental form in an orthonormal tangent frame (a = Su / |Su|, b = n x a). The tangent
//! planes of two seeds x and x + d meet in a line whose top view satisfies
//! d^T A x = const: the facet edge between the two seeds runs along the direction e
//! **conjugate** to d (e^T A d = 0), whatever the sign of the Gaussian curvature. So the
//! edges follow chosen directions e_k when the neighbours lie along d_k = A^-1 J e_k
//! (J the quarter turn): a lattice whose edge directions are e_k = R_phi l_k (l_k the unit
//! lattice's vectors, phi the field's angle) is the lattice
//!
//! ```text
//!     F = A'^-1 J R_phi,   lattice points x = F l,  l in the unit hexagonal or square lattice
//! ```
//!
//! scaled so that a cell has the surface area (total area) / (point count). On a quadratic
//! surface every facet of such a lattice is a translate of the others (the affine maps that
//! carry the paraboloid into itself carry tangent planes into tangent planes), and its edges
//! lie exactly along R_phi l_k, provided the lattice's triangles are the ones the
//! discretiser's neighbour search picks: the Delaunay triangles in the metric |A| (issue 10).
//! They are when the lattice's triangle, seen through |A|^(1/2), has no angle above
//! [`ALIGN_MAX_TRIANGLE_ANGLE_DEG`] (hexagons; squares: the parallelogram's angle within
//! 90 +- [`ALIGN_MAX_SHEAR_DEG`]). A' is A with its smaller |eigenvalue| raised to at least
//! 1/rho of the larger (sign kept), rho taken from [`MAX_ALIGN_ANISOTROPY`] down to 1 until
//! the triangle passes; at rho = 1 the lattice is regular in |A| and always passes. Where the
//! surface is flat (|A| below [`ALIGN_FLAT_CURVATURE`] of the surface's largest curvature)
//! A' = I: the lattice is regular on the surface. For a square lattice along principal
//! directions the four neighbours are conjugate pairs and the facets are exact quads
//! (four planes meet at each corner), the classic planar quad net.
//!
//! ## The fields
//!
//! - `principal`: the principal direction of the smaller curvature of s A, s = +-1 the sign
//!   that makes the mean curvature's average over the surface non-negative (on a dome:
//!   the direction of the smaller |curvature|, which keeps the hexagons' triangles acute);
//! - `asymptotic`: where K < 0, that direction turned by alpha towards the other principal
//!   direction (n x d), tan^2 alpha = -k1 / k2 (an asymptotic direction, II(e, e) = 0);
//!   where K >= 0 the principal direction (the two agree where k1 reaches 0);
//! - `uv:ANGLE`: the constant direction (cos ANGLE, sin ANGLE) in normalised parameters,
//!   mapped onto the tangent plane by (Su (u1 - u0), Sv (v1 - v0));
//! - a direction file ([`DirectionField`]): directions in normalised parameters on a grid.
//!
//! Each field is a line field (direction and its opposite). It is tabulated on
//! [`ALIGN_NODES`]^2 nodes as the doubled-angle vector w (cos 2 phi, sin 2 phi) in the node's
//! frame (a, b), with weight w = k2 - k1 for the curvature fields (zero at umbilics, where
//! principal directions are undefined) and 1 for the others (0 for a zero direction in a
//! file). The field is then smoothed by [`ALIGN_SMOOTHING_SWEEPS`] Gauss-Seidel sweeps of
//! x_i = (w_i u_i + sum_j x_j) / (w_i + deg_i) (u_i the unit data, j over the 4
//! neighbours, weights relative to the largest): a screened Laplace equation that keeps the
//! field where it is reliable and fills umbilic regions harmonically from around them. The
//! angle is halved without trigonometry: cos phi = sqrt((1 + c) / 2),
//! sin phi = sign(s) sqrt((1 - c) / 2). A field that vanishes everywhere (a sphere, a plane)
//! falls back to phi = 0, the direction of Su.
//!
//! ## Generation
//!
//! Each node stores F in normalised parameters, F_st = P^-1 F (P maps (ds, dt) to the
//! frame (a, b)). Between nodes F is interpolated bilinearly after each corner's matrix is
//! replaced by the copy F G closest to the others' reference (G over the lattice's symmetry
//! group: the 12 rotations by 60 degrees and reflections of the hexagonal lattice, the 8 of
//! the square one). The lattice is grown by an advancing front from the centre of the square:
//! each point p with frame F_p proposes p + F_m l for the 6 (4) unit steps l, F_m the frame at
//! the step's midpoint aligned to F_p; a proposal inside [0, 1]^2 is accepted unless an
//! accepted point lies closer than [`ALIGN_MIN_SEPARATION`] in the metric of its own frame
//! (so proposals of the same lattice site from different parents merge, and gaps left where
//! the field turns are filled by the next proposals). The front is a FIFO queue, so the
//! result is deterministic; every point is visited once and the count is capped
//! ([`aligned_pattern`]), so it always ends.

use crate::error::TpiError;
use crate::pattern::{validate_uv, MAX_GENERATED_POINTS};
use crate::sizing::node_geometry;
use crate::surface::Surface;
use crate::tolerance::{
    ALIGN_FLAT_CURVATURE, ALIGN_MAX_SHEAR_DEG, ALIGN_MAX_TRIANGLE_ANGLE_DEG, ALIGN_MIN_SEPARATION,
};

/// Nodes per side of the grid on which the direction field and the lattice frames are
/// tabulated.
pub const ALIGN_NODES: usize = 65;

/// Gauss-Seidel sweeps of the field's smoothing.
pub const ALIGN_SMOOTHING_SWEEPS: usize = 200;

/// Largest ratio of the principal curvatures the lattice follows (A' in the module doc);
/// beyond it the lattice is less stretched than the curvature and the edges follow the field
/// less exactly.
pub const MAX_ALIGN_ANISOTROPY: f64 = 8.0;

/// Largest number of cells per side of the proposal hash.
const MAX_HASH_SIDE: usize = 4096;

/// The lattice an aligned pattern follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lattice {
    /// Hexagonal facets (a triangular lattice of seeds): edge directions 60 degrees apart.
    Hex,
    /// Quadrilateral facets (a square lattice of seeds): edge directions 90 degrees apart.
    Grid,
}

impl Lattice {
    /// The unit lattice's steps to its nearest neighbours.
    fn steps(self) -> &'static [[f64; 2]] {
        const H: f64 = 0.866_025_403_784_438_6; // sqrt(3) / 2
        match self {
            Lattice::Hex => &[
                [1.0, 0.0],
                [0.5, H],
                [-0.5, H],
                [-1.0, 0.0],
                [-0.5, -H],
                [0.5, -H],
            ],
            Lattice::Grid => &[[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]],
        }
    }

    /// Area of the unit lattice's cell.
    fn cell_area(self) -> f64 {
        match self {
            Lattice::Hex => 0.866_025_403_784_438_6,
            Lattice::Grid => 1.0,
        }
    }

    /// The symmetry group of the unit lattice (rotations, then the same times a reflection).
    fn symmetries(self) -> Vec<M2> {
        let (c, s) = match self {
            Lattice::Hex => (0.5, 0.866_025_403_784_438_6),
            Lattice::Grid => (0.0, 1.0),
        };
        let step = [c, -s, s, c];
        let order = match self {
            Lattice::Hex => 6,
            Lattice::Grid => 4,
        };
        let mut out = Vec::with_capacity(2 * order);
        let mut r = [1.0, 0.0, 0.0, 1.0];
        for _ in 0..order {
            out.push(r);
            r = mul(r, step);
        }
        let mirror = [1.0, 0.0, 0.0, -1.0];
        for k in 0..order {
            out.push(mul(out[k], mirror));
        }
        out
    }
}

/// A direction field given in a file: line directions in normalised parameters (ds, dt) on
/// a grid of `size[0]` x `size[1]` nodes, node (i, j) at `(i / (size[0] - 1), j / (size[1] - 1))`
/// with index `i * size[1] + j` (u-major, as grid patterns). Directions are lines (d and -d
/// are the same); a zero vector means no preference there (filled by the smoothing).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DirectionField {
    /// Nodes along s and along t, each at least 2.
    pub size: [usize; 2],
    /// One direction per node.
    pub directions: Vec<[f64; 2]>,
}

/// Largest number of nodes of a direction file.
pub const MAX_DIRECTION_NODES: usize = 1_000_000;

impl DirectionField {
    /// Reads a direction file and validates it.
    ///
    /// Errors: [`TpiError::Parse`] for malformed JSON, then those of
    /// [`DirectionField::validate`].
    pub fn from_json(text: &str, context: &str) -> Result<DirectionField, TpiError> {
        let field: DirectionField = crate::spec::read(text, context)?;
        field.validate()?;
        Ok(field)
    }

    /// Checks the sizes (each at least 2, at most [`MAX_DIRECTION_NODES`] nodes, one
    /// direction per node), finite directions and at least one non-zero direction.
    pub fn validate(&self) -> Result<(), TpiError> {
        let [ns, nt] = self.size;
        let invalid = |field: &str, value: f64, reason: &str| TpiError::InvalidParameter {
            field: field.into(),
            value,
            reason: reason.into(),
        };
        if ns < 2 || nt < 2 {
            return Err(invalid(
                "size",
                ns.min(nt) as f64,
                "a direction field needs at least 2 nodes along s and along t",
            ));
        }
        match ns.checked_mul(nt) {
            Some(n) if n <= MAX_DIRECTION_NODES => {
                if self.directions.len() != n {
                    return Err(invalid(
                        "directions",
                        self.directions.len() as f64,
                        &format!("expected size[0] * size[1] = {n} directions"),
                    ));
                }
            }
            _ => {
                return Err(invalid(
                    "size",
                    ns as f64 * nt as f64,
                    &format!("at most {MAX_DIRECTION_NODES} nodes"),
                ))
            }
        }
        for (k, d) in self.directions.iter().enumerate() {
            for (c, &x) in d.iter().enumerate() {
                if !x.is_finite() {
                    return Err(TpiError::NonFinite {
                        field: format!("directions[{k}][{c}]"),
                        value: x,
                    });
                }
            }
        }
        if self.directions.iter().all(|d| d[0] == 0.0 && d[1] == 0.0) {
            return Err(invalid(
                "directions",
                0.0,
                "every direction is zero: give at least one non-zero direction",
            ));
        }
        Ok(())
    }

    /// The doubled-angle vector of the field at (s, t), bilinear between nodes (a unit
    /// direction (c, s) becomes (c^2 - s^2, 2 c s); its length is the interpolated weight).
    fn doubled_at(&self, st: [f64; 2]) -> [f64; 2] {
        let [ns, nt] = self.size;
        let x = st[0].clamp(0.0, 1.0) * (ns - 1) as f64;
        let y = st[1].clamp(0.0, 1.0) * (nt - 1) as f64;
        let i = (x.floor() as usize).min(ns - 2);
        let j = (y.floor() as usize).min(nt - 2);
        let (fx, fy) = (x - i as f64, y - j as f64);
        let mut out = [0.0; 2];
        for (di, wx) in [(0, 1.0 - fx), (1, fx)] {
            for (dj, wy) in [(0, 1.0 - fy), (1, fy)] {
                let [a, b] = self.directions[(i + di) * nt + j + dj];
                let len2 = a * a + b * b;
                if len2 > 0.0 {
                    out[0] += wx * wy * (a * a - b * b) / len2;
                    out[1] += wx * wy * 2.0 * a * b / len2;
                }
            }
        }
        out
    }
}

/// The direction field an aligned pattern follows (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub enum AlignField {
    /// Principal curvature directions (of the smaller curvature after orienting the surface
    /// so that its mean curvature is on average non-negative).
    Principal,
    /// Asymptotic directions where K < 0, principal directions elsewhere.
    Asymptotic,
    /// A constant direction in normalised parameters, in degrees from the s axis.
    Uv(f64),
    /// Directions from a file.
    File(DirectionField),
}

impl AlignField {
    /// Parses `principal`, `asymptotic` or `uv:ANGLE` (degrees); a direction file is read
    /// with [`DirectionField::from_json`] by the caller.
    pub fn parse(text: &str) -> Result<AlignField, TpiError> {
        let invalid = |reason: String| TpiError::InvalidParameter {
            field: format!("alignment `{}`", crate::error::bounded(text, 40)),
            value: f64::NAN,
            reason,
        };
        match text {
            "principal" => Ok(AlignField::Principal),
            "asymptotic" => Ok(AlignField::Asymptotic),
            _ => match text.strip_prefix("uv:") {
                Some(angle) => match angle.parse::<f64>() {
                    Ok(a) if a.is_finite() && a.abs() <= 360.0 => Ok(AlignField::Uv(a)),
                    _ => Err(invalid(
                        "uv:ANGLE needs an angle in degrees from -360 to 360".into(),
                    )),
                },
                None => Err(invalid(
                    "expected principal, asymptotic, uv:ANGLE or field:FILE.json".into(),
                )),
            },
        }
    }
}

/// A 2x2 matrix, row-major [m00, m01, m10, m11].
type M2 = [f64; 4];

fn mul(a: M2, b: M2) -> M2 {
    [
        a[0] * b[0] + a[1] * b[2],
        a[0] * b[1] + a[1] * b[3],
        a[2] * b[0] + a[3] * b[2],
        a[2] * b[1] + a[3] * b[3],
    ]
}

fn det(a: M2) -> f64 {
    a[0] * a[3] - a[1] * a[2]
}

fn inverse(a: M2) -> Option<M2> {
    let d = det(a);
    if !(d.abs() > 0.0) || !d.is_finite() {
        return None;
    }
    let m = [a[3] / d, -a[1] / d, -a[2] / d, a[0] / d];
    m.iter().all(|x| x.is_finite()).then_some(m)
}

fn apply(a: M2, v: [f64; 2]) -> [f64; 2] {
    [a[0] * v[0] + a[1] * v[1], a[2] * v[0] + a[3] * v[1]]
}

/// Largest singular value.
fn norm2(a: M2) -> f64 {
    let f = a.iter().map(|x| x * x).sum::<f64>();
    let d = det(a);
    (0.5 * (f + (f * f - 4.0 * d * d).max(0.0).sqrt())).sqrt()
}

/// Smallest singular value.
fn smallest_singular(a: M2) -> f64 {
    let top = norm2(a);
    if top > 0.0 {
        det(a).abs() / top
    } else {
        0.0
    }
}

/// The copy a G (G in the group) closest to `reference` in the Frobenius norm (ties: first).
fn align(a: M2, reference: M2, group: &[M2]) -> M2 {
    let mut best = a;
    let mut best_d = f64::INFINITY;
    for &g in group {
        let c = mul(a, g);
        let d: f64 = (0..4).map(|k| (c[k] - reference[k]).powi(2)).sum();
        if d < best_d {
            best_d = d;
            best = c;
        }
    }
    best
}

/// What is known at one node: P (normalised parameters to the frame (a, b)), A in that
/// frame, sqrt(det G) (surface area per unit parameter area).
#[derive(Clone, Copy, Debug)]
struct Node {
    p: M2,
    a: [f64; 3],
    area: f64,
}

/// The half angle of a doubled-angle vector, as a unit vector (c, s).
fn half_angle(x: f64, y: f64) -> [f64; 2] {
    let r = x.hypot(y);
    if !(r > 0.0) {
        return [1.0, 0.0];
    }
    let c = (x / r).clamp(-1.0, 1.0);
    let cos = (0.5 * (1.0 + c)).sqrt();
    let sin = (0.5 * (1.0 - c)).sqrt();
    [cos, if y < 0.0 { -sin } else { sin }]
}

/// Eigen-decomposition of a symmetric [[a, b], [b, c]]: (smaller, larger, unit eigenvector of
/// the larger).
fn eigen(t: [f64; 3]) -> (f64, f64, [f64; 2]) {
    let m = 0.5 * (t[0] + t[2]);
    let r = 0.5 * (t[0] - t[2]).hypot(2.0 * t[1]);
    (m - r, m + r, half_angle(t[0] - t[2], 2.0 * t[1]))
}

/// The lattice frame in the orthonormal frame (a, b) (before scaling): A'^-1 J R_phi with the
/// anisotropy reduced until the lattice's triangle seen through |A'|^(1/2) passes.
fn lattice_frame(a: [f64; 3], e0: [f64; 2], kmax: f64, lattice: Lattice) -> M2 {
    let rotation = [e0[0], -e0[1], e0[1], e0[0]];
    let jr = mul([0.0, -1.0, 1.0, 0.0], rotation);
    let (l1, l2, v2) = eigen(a);
    let big = l1.abs().max(l2.abs());
    if !(big > ALIGN_FLAT_CURVATURE * kmax) {
        return jr;
    }
    let v1 = [v2[1], -v2[0]];
    let outer = |v: [f64; 2], w: f64| {
        [
            w * v[0] * v[0],
            w * v[0] * v[1],
            w * v[1] * v[0],
            w * v[1] * v[1],
        ]
    };
    let add = |x: M2, y: M2| [x[0] + y[0], x[1] + y[1], x[2] + y[2], x[3] + y[3]];
    let steps = lattice.steps();
    let mut last = jr;
    for rho in [MAX_ALIGN_ANISOTROPY, 4.0, 2.5, 1.6, 1.0] {
        let clamp = |l: f64| {
            let m = l.abs().max(big / rho);
            if l < 0.0 {
                -m
            } else {
                m
            }
        };
        let (c1, c2) = (clamp(l1), clamp(l2));
        let inv = add(outer(v1, 1.0 / c1), outer(v2, 1.0 / c2));
        let root = add(outer(v1, c1.abs().sqrt()), outer(v2, c2.abs().sqrt()));
        let f = mul(inv, jr);
        last = f;
        let y = mul(root, f);
        let p = apply(y, steps[0]);
        let q = apply(y, steps[1]);
        if lattice_passes(p, q, lattice) {
            return f;
        }
    }
    last
}

/// Whether the lattice spanned by p, q (images of the unit steps 0 and 1) is one whose
/// |A|-Delaunay triangles are its own (see the module doc).
fn lattice_passes(p: [f64; 2], q: [f64; 2], lattice: Lattice) -> bool {
    let cos = |x: [f64; 2], y: [f64; 2]| {
        let d = (x[0] * x[0] + x[1] * x[1]).sqrt() * (y[0] * y[0] + y[1] * y[1]).sqrt();
        if d > 0.0 {
            (x[0] * y[0] + x[1] * y[1]) / d
        } else {
            f64::NAN
        }
    };
    match lattice {
        Lattice::Hex => {
            let limit = ALIGN_MAX_TRIANGLE_ANGLE_DEG.to_radians().cos();
            let pq = [q[0] - p[0], q[1] - p[1]];
            let angles = [
                cos(p, q),
                cos([-p[0], -p[1]], pq),
                cos([-q[0], -q[1]], [-pq[0], -pq[1]]),
            ];
            angles.iter().all(|&c| c >= limit)
        }
        Lattice::Grid => {
            let limit = ALIGN_MAX_SHEAR_DEG.to_radians().sin();
            cos(p, q).abs() <= limit
        }
    }
}

/// The frames of an aligned lattice over the normalised square.
struct FrameField {
    n: usize,
    /// F_st at each node (index i * n + j).
    frames: Vec<M2>,
    group: Vec<M2>,
}

impl FrameField {
    /// F_st at (s, t), bilinear between the nodes after aligning them; aligned to `hint`.
    fn at(&self, st: [f64; 2], hint: Option<M2>) -> M2 {
        let m = (self.n - 1) as f64;
        let x = st[0].clamp(0.0, 1.0) * m;
        let y = st[1].clamp(0.0, 1.0) * m;
        let i = (x.floor() as usize).min(self.n - 2);
        let j = (y.floor() as usize).min(self.n - 2);
        let (fx, fy) = (x - i as f64, y - j as f64);
        let corners = [
            (self.frames[i * self.n + j], (1.0 - fx) * (1.0 - fy)),
            (self.frames[(i + 1) * self.n + j], fx * (1.0 - fy)),
            (self.frames[i * self.n + j + 1], (1.0 - fx) * fy),
            (self.frames[(i + 1) * self.n + j + 1], fx * fy),
        ];
        let reference = match hint {
            Some(h) => align(corners[0].0, h, &self.group),
            None => corners[0].0,
        };
        let mut sum = [0.0; 4];
        for (f, w) in corners {
            let g = align(f, reference, &self.group);
            for k in 0..4 {
                sum[k] += w * g[k];
            }
        }
        // Corners too different to average (a turn of the field across one cell): take the
        // nearest one.
        let smallest = corners
            .iter()
            .map(|(f, _)| det(*f).abs())
            .fold(f64::INFINITY, f64::min);
        let result = if det(sum).abs() >= 0.25 * smallest {
            sum
        } else {
            let nearest = corners
                .iter()
                .fold(
                    (reference, -1.0),
                    |best, &(f, w)| if w > best.1 { (f, w) } else { best },
                )
                .0;
            align(nearest, reference, &self.group)
        };
        match hint {
            Some(h) => align(result, h, &self.group),
            None => result,
        }
    }
}

/// The doubled-angle data of the field at every node, in the node's frame (a, b).
fn field_data(field: &AlignField, nodes: &[Node], n: usize, sign: f64) -> Vec<[f64; 2]> {
    let h = 1.0 / (n - 1) as f64;
    nodes
        .iter()
        .enumerate()
        .map(|(k, node)| {
            let a = [sign * node.a[0], sign * node.a[1], sign * node.a[2]];
            // Doubled angle of the smaller eigenvalue's direction: -(a00 - a11, 2 a01); its
            // length is k2 - k1.
            let principal = [a[2] - a[0], -2.0 * a[1]];
            let from_st = |d: [f64; 2]| {
                let t = apply(node.p, d);
                let len2 = t[0] * t[0] + t[1] * t[1];
                if len2 > 0.0 {
                    [(t[0] * t[0] - t[1] * t[1]) / len2, 2.0 * t[0] * t[1] / len2]
                } else {
                    [0.0, 0.0]
                }
            };
            match field {
                AlignField::Principal => principal,
                AlignField::Asymptotic => {
                    let (k1, k2, _) = eigen(a);
                    if k1 < 0.0 && k2 > 0.0 {
                        let spread = k2 - k1;
                        // (cos 2 alpha, sin 2 alpha), tan^2 alpha = -k1 / k2.
                        let c = (k2 + k1) / spread;
                        let s = 2.0 * (-k1 * k2).sqrt() / spread;
                        [
                            principal[0] * c - principal[1] * s,
                            principal[0] * s + principal[1] * c,
                        ]
                    } else {
                        principal
                    }
                }
                AlignField::Uv(degrees) => {
                    let (s, c) = degrees.to_radians().sin_cos();
                    from_st([c, s])
                }
                AlignField::File(grid) => {
                    let st = [(k / n) as f64 * h, (k % n) as f64 * h];
                    let d = grid.doubled_at(st);
                    let w = d[0].hypot(d[1]);
                    let dir = half_angle(d[0], d[1]);
                    let t = from_st(dir);
                    [w * t[0], w * t[1]]
                }
            }
        })
        .collect()
}

/// The smoothed unit field (doubled angle) from its data (see the module doc).
fn smooth(data: &[[f64; 2]], n: usize) -> Vec<[f64; 2]> {
    let top = data
        .iter()
        .map(|d| d[0].hypot(d[1]))
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max);
    if !(top > 0.0) {
        return vec![[1.0, 0.0]; data.len()];
    }
    let weighted: Vec<[f64; 2]> = data
        .iter()
        .map(|d| {
            if d[0].is_finite() && d[1].is_finite() {
                [d[0] / top, d[1] / top]
            } else {
                [0.0, 0.0]
            }
        })
        .collect();
    let mut x = weighted.clone();
    for _ in 0..ALIGN_SMOOTHING_SWEEPS {
        for i in 0..n {
            for j in 0..n {
                let k = i * n + j;
                let w = weighted[k][0].hypot(weighted[k][1]);
                let mut sum = weighted[k];
                let mut deg = 0.0;
                for (di, dj) in [(-1i64, 0i64), (1, 0), (0, -1), (0, 1)] {
                    let (a, b) = (i as i64 + di, j as i64 + dj);
                    if a >= 0 && b >= 0 && (a as usize) < n && (b as usize) < n {
                        let q = x[a as usize * n + b as usize];
                        sum[0] += q[0];
                        sum[1] += q[1];
                        deg += 1.0;
                    }
                }
                x[k] = [sum[0] / (w + deg), sum[1] / (w + deg)];
            }
        }
    }
    x
}

/// A hexagonal or square pattern of about `count` points laid along `field` on `surface`
/// (the module doc has the construction). The points are in normalised [0, 1]^2, ordered as
/// the advancing front accepted them; the count follows the surface area (cells of equal
/// area) and differs from `count` by the boundary's share.
///
/// Errors: [`TpiError::InvalidParameter`] for a count of 0 or above [`MAX_GENERATED_POINTS`]
/// or a growth that would exceed four times the count (a field too irregular to follow);
/// [`TpiError::DegenerateSurface`] when the surface has no regular point or no area; the
/// errors of [`DirectionField::validate`] for a direction file.
pub fn aligned_pattern(
    surface: &dyn Surface,
    lattice: Lattice,
    count: usize,
    field: &AlignField,
) -> Result<Vec<[f64; 2]>, TpiError> {
    if count == 0 || count > MAX_GENERATED_POINTS {
        return Err(TpiError::InvalidParameter {
            field: "point count".into(),
            value: count as f64,
            reason: format!("an aligned pattern has 1 to {MAX_GENERATED_POINTS} points"),
        });
    }
    if let AlignField::File(grid) = field {
        grid.validate()?;
    }
    let n = ALIGN_NODES;
    let raw = node_geometry(surface, n, |g, geometry, d, _| {
        let su_len = d.su.length();
        let a = d.su / su_len;
        let nrm = geometry.normal;
        let b = nrm.cross(a);
        let p = [su_len, d.sv.dot(a), 0.0, d.sv.dot(b)];
        // A = P^-T II P^-1 in the frame (a, b).
        let ii = [d.suu.dot(nrm), d.suv.dot(nrm), d.svv.dot(nrm)];
        let pi = inverse(p).unwrap_or([f64::NAN; 4]);
        let t00 = ii[0] * pi[0] + ii[1] * pi[2];
        let t01 = ii[0] * pi[1] + ii[1] * pi[3];
        let t10 = ii[1] * pi[0] + ii[2] * pi[2];
        let t11 = ii[1] * pi[1] + ii[2] * pi[3];
        let a_frame = [
            pi[0] * t00 + pi[2] * t10,
            pi[0] * t01 + pi[2] * t11,
            pi[1] * t01 + pi[3] * t11,
        ];
        Node {
            p,
            a: a_frame,
            area: (g[0] * g[2] - g[1] * g[1]).max(0.0).sqrt(),
        }
    });
    let ok = |x: &Option<Node>| {
        x.as_ref().is_some_and(|node| {
            node.p.iter().chain(&node.a).all(|v| v.is_finite())
                && node.area.is_finite()
                && inverse(node.p).is_some()
        })
    };
    let Some(first_valid) = raw.iter().position(ok) else {
        return Err(TpiError::DegenerateSurface {
            reason: "no regular point to lay an aligned pattern on".into(),
        });
    };
    // Irregular nodes take the nearest valid node before them (or the first valid one).
    let mut nodes: Vec<Node> = Vec::with_capacity(raw.len());
    let mut last = raw[first_valid].unwrap_or(Node {
        p: [1.0, 0.0, 0.0, 1.0],
        a: [0.0; 3],
        area: 0.0,
    });
    for x in &raw {
        if ok(x) {
            if let Some(node) = x {
                last = *node;
            }
        }
        nodes.push(last);
    }
    // Surface area by the trapezoid rule over the nodes.
    let h = 1.0 / (n - 1) as f64;
    let mut area = 0.0;
    for i in 0..n {
        for j in 0..n {
            let wi = if i == 0 || i == n - 1 { 0.5 } else { 1.0 };
            let wj = if j == 0 || j == n - 1 { 0.5 } else { 1.0 };
            area += wi * wj * h * h * nodes[i * n + j].area;
        }
    }
    if !(area > 0.0 && area.is_finite()) {
        return Err(TpiError::DegenerateSurface {
            reason: "the surface has no area to lay an aligned pattern on".into(),
        });
    }
    let sign = if nodes.iter().map(|x| x.a[0] + x.a[2]).sum::<f64>() < 0.0 {
        -1.0
    } else {
        1.0
    };
    let kmax = nodes
        .iter()
        .map(|x| {
            let (k1, k2, _) = eigen(x.a);
            k1.abs().max(k2.abs())
        })
        .fold(0.0, f64::max);
    let doubled = smooth(&field_data(field, &nodes, n, sign), n);
    let cell = area / count as f64;
    let frames: Vec<M2> = nodes
        .iter()
        .zip(&doubled)
        .map(|(node, d)| {
            let e0 = half_angle(d[0], d[1]);
            let a = [sign * node.a[0], sign * node.a[1], sign * node.a[2]];
            let f = lattice_frame(a, e0, kmax, lattice);
            let scale = (cell / (det(f).abs() * lattice.cell_area())).sqrt();
            let f = [f[0] * scale, f[1] * scale, f[2] * scale, f[3] * scale];
            inverse(node.p).map_or([f64::NAN; 4], |pi| mul(pi, f))
        })
        .collect();
    if frames
        .iter()
        .any(|f| !f.iter().all(|x| x.is_finite()) || !(det(*f).abs() > 0.0))
    {
        return Err(TpiError::DegenerateSurface {
            reason: "the lattice frame degenerates (a vanishing parametrisation)".into(),
        });
    }
    let frames = FrameField {
        n,
        frames,
        group: lattice.symmetries(),
    };
    let points = grow(&frames, lattice, count)?;
    validate_uv(&points)?;
    Ok(points)
}

/// The advancing front (module doc).
fn grow(frames: &FrameField, lattice: Lattice, count: usize) -> Result<Vec<[f64; 2]>, TpiError> {
    let cap = count
        .saturating_mul(4)
        .max(count + 1000)
        .min(MAX_GENERATED_POINTS);
    let mut sizes: Vec<f64> = frames
        .frames
        .iter()
        .map(|&f| smallest_singular(f))
        .collect();
    sizes.sort_by(f64::total_cmp);
    let typical = sizes[sizes.len() / 2];
    let side = ((1.0 / (ALIGN_MIN_SEPARATION * typical)).ceil() as usize)
        .clamp(1, MAX_HASH_SIDE)
        .min(((4 * cap) as f64).sqrt() as usize + 1);
    let cell = 1.0 / side as f64;
    let key = |p: [f64; 2]| {
        let i = ((p[0] / cell) as usize).min(side - 1);
        let j = ((p[1] / cell) as usize).min(side - 1);
        i * side + j
    };
    const NONE: u32 = u32::MAX;
    let mut head = vec![NONE; side * side];
    let mut next: Vec<u32> = Vec::new();
    let mut points: Vec<[f64; 2]> = Vec::new();
    let mut point_frames: Vec<M2> = Vec::new();
    let too_close = |q: [f64; 2], f: M2, points: &[[f64; 2]], head: &[u32], next: &[u32]| {
        let Some(inv) = inverse(f) else { return true };
        let reach = ALIGN_MIN_SEPARATION * norm2(f);
        let r = (reach / cell).ceil() as i64;
        let ci = ((q[0] / cell) as i64).min(side as i64 - 1);
        let cj = ((q[1] / cell) as i64).min(side as i64 - 1);
        let r = r.min(side as i64);
        for i in (ci - r).max(0)..=(ci + r).min(side as i64 - 1) {
            for j in (cj - r).max(0)..=(cj + r).min(side as i64 - 1) {
                let mut k = head[i as usize * side + j as usize];
                while k != NONE {
                    let x = points[k as usize];
                    let d = apply(inv, [x[0] - q[0], x[1] - q[1]]);
                    if d[0] * d[0] + d[1] * d[1] < ALIGN_MIN_SEPARATION * ALIGN_MIN_SEPARATION {
                        return true;
                    }
                    k = next[k as usize];
                }
            }
        }
        false
    };
    let start = [0.5, 0.5];
    points.push(start);
    point_frames.push(frames.at(start, None));
    head[key(start)] = 0;
    next.push(NONE);
    let mut index = 0;
    while index < points.len() {
        let p = points[index];
        let fp = point_frames[index];
        for &l in lattice.steps() {
            let half = apply(fp, [0.5 * l[0], 0.5 * l[1]]);
            let fm = frames.at([p[0] + half[0], p[1] + half[1]], Some(fp));
            let step = apply(fm, l);
            let q = [p[0] + step[0], p[1] + step[1]];
            if !(q[0] >= 0.0 && q[0] <= 1.0 && q[1] >= 0.0 && q[1] <= 1.0) {
                continue;
            }
            let fq = frames.at(q, Some(fm));
            if too_close(q, fq, &points, &head, &next) {
                continue;
            }
            if points.len() >= cap {
                return Err(TpiError::InvalidParameter {
                    field: "aligned pattern".into(),
                    value: points.len() as f64,
                    reason: format!(
                        "the lattice grew beyond {cap} points for a target of {count}: the \
                         direction field turns too fast to follow"
                    ),
                });
            }
            let k = key(q);
            next.push(head[k]);
            head[k] = points.len() as u32;
            points.push(q);
            point_frames.push(fq);
        }
        index += 1;
    }
    Ok(points)
}
