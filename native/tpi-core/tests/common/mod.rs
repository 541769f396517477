//! Shared helpers of the `discretise_*` integration tests.
//!
//! Everything here is written independently of the production code path: no call into the
//! crate's `neighbours`, `facets`, `quality`, `planes`, `projection` or `triangulation`
//! modules. The crate is used only to build surfaces, to evaluate them (`Surface::evaluate`,
//! `Surface::point_at`) and to run `discretise` itself.
// Test helpers: `pub` is how the test files that include this module reach them.
#![allow(unreachable_pub)]
#![allow(
    dead_code,
    clippy::neg_cmp_op_on_partial_ord,
    clippy::needless_range_loop,
    clippy::unnecessary_map_or
)]

use std::collections::{BTreeMap, BTreeSet, HashMap};

use glam::{DVec2, DVec3};
use tpi_core::VertexKind;
use tpi_core::{Discretisation, Generator, NurbsSurface, Surface};

pub mod saddles;
pub mod validity;

// ---------------------------------------------------------------------------------------
// Random numbers and patterns
// ---------------------------------------------------------------------------------------

/// SplitMix64, written out here so the test data never depends on the crate's generator.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed ^ 0x5DEE_CE66_D1CE_4E5B)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.f64()
    }
}

/// `n` independent uniform points in [0, 1)^2 (no minimum distance: close pairs happen).
pub fn uniform_pattern(rng: &mut Rng, n: usize) -> Vec<[f64; 2]> {
    (0..n).map(|_| [rng.f64(), rng.f64()]).collect()
}

/// A jittered grid of about `n` points: one uniform point per cell of a k x k grid
/// (k = ceil(sqrt(n))), the first `n` cells in a random order.
pub fn jittered_pattern(rng: &mut Rng, n: usize) -> Vec<[f64; 2]> {
    let k = (n as f64).sqrt().ceil() as usize;
    let mut cells: Vec<usize> = (0..k * k).collect();
    for i in (1..cells.len()).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        cells.swap(i, j);
    }
    cells.truncate(n);
    cells
        .into_iter()
        .map(|c| {
            let (i, j) = (c % k, c / k);
            [
                (i as f64 + rng.range(0.05, 0.95)) / k as f64,
                (j as f64 + rng.range(0.05, 0.95)) / k as f64,
            ]
        })
        .collect()
}

// ---------------------------------------------------------------------------------------
// Small linear algebra and plane geometry
// ---------------------------------------------------------------------------------------

/// Solves the 3x3 system `a x = b` by Gaussian elimination with partial pivoting.
/// None when a pivot vanishes (relative to the matrix's largest entry).
pub fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let mut m = [[0.0f64; 4]; 3];
    let mut scale = 0.0f64;
    for r in 0..3 {
        for c in 0..3 {
            m[r][c] = a[r][c];
            scale = scale.max(a[r][c].abs());
        }
        m[r][3] = b[r];
    }
    for col in 0..3 {
        let pivot = (col..3).max_by(|&x, &y| m[x][col].abs().total_cmp(&m[y][col].abs()))?;
        if !(m[pivot][col].abs() > 1e-300_f64.max(scale * 1e-17)) {
            return None;
        }
        m.swap(col, pivot);
        for r in col + 1..3 {
            let f = m[r][col] / m[col][col];
            for c in col..4 {
                m[r][c] -= f * m[col][c];
            }
        }
    }
    let mut x = [0.0f64; 3];
    for r in (0..3).rev() {
        let mut s = m[r][3];
        for c in r + 1..3 {
            s -= m[r][c] * x[c];
        }
        x[r] = s / m[r][r];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The meeting point of the planes through `p[k]` with normals `n[k]`, solved relative to
/// the first point to keep the right-hand side small.
pub fn meet3(p: [DVec3; 3], n: [DVec3; 3]) -> Option<DVec3> {
    let o = p[0];
    let a = [n[0].to_array(), n[1].to_array(), n[2].to_array()];
    let b = [0.0, n[1].dot(p[1] - o), n[2].dot(p[2] - o)];
    solve3(a, b).map(|x| o + DVec3::from_array(x))
}

/// A right-handed orthonormal frame (e1, e2) of the plane with unit normal `n`: e1 x e2 = n.
pub fn frame(n: DVec3) -> (DVec3, DVec3) {
    let a = if n.x.abs() <= n.y.abs() && n.x.abs() <= n.z.abs() {
        DVec3::X
    } else if n.y.abs() <= n.z.abs() {
        DVec3::Y
    } else {
        DVec3::Z
    };
    let e1 = (a - n * a.dot(n)).normalize();
    let e2 = n.cross(e1);
    (e1, e2)
}

/// Coordinates of `x` in the frame of the plane through `o` with unit normal `n`.
pub fn to_2d(o: DVec3, n: DVec3, xs: &[DVec3]) -> Vec<DVec2> {
    let (e1, e2) = frame(n);
    xs.iter()
        .map(|&x| DVec2::new((x - o).dot(e1), (x - o).dot(e2)))
        .collect()
}

pub fn cross2(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Signed area (positive counter-clockwise).
pub fn signed_area(p: &[DVec2]) -> f64 {
    let n = p.len();
    (0..n).map(|k| cross2(p[k], p[(k + 1) % n])).sum::<f64>() * 0.5
}

/// Whether the open segments ab and cd cross properly (strictly opposite sides both ways).
pub fn proper_crossing(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let d1 = cross2(b - a, c - a);
    let d2 = cross2(b - a, d - a);
    let d3 = cross2(d - c, a - c);
    let d4 = cross2(d - c, b - c);
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// Simple: at least 3 vertices, positive (counter-clockwise) area, and no two non-adjacent
/// edges crossing properly.
pub fn is_simple(p: &[DVec2]) -> bool {
    let n = p.len();
    if n < 3 || !(signed_area(p) > 0.0) {
        return false;
    }
    for a in 0..n {
        for b in a + 2..n {
            if a == 0 && b == n - 1 {
                continue;
            }
            if proper_crossing(p[a], p[(a + 1) % n], p[b], p[(b + 1) % n]) {
                return false;
            }
        }
    }
    true
}

/// Convex: simple and no right turn; a turn counts as right when its cross product is below
/// -1e-12 times the squared longest edge (collinear runs are allowed).
pub fn is_convex(p: &[DVec2]) -> bool {
    if !is_simple(p) {
        return false;
    }
    let n = p.len();
    let scale = (0..n)
        .map(|k| (p[(k + 1) % n] - p[k]).length())
        .fold(0.0, f64::max);
    let tolerance = 1e-12 * scale * scale;
    (0..n).all(|k| cross2(p[(k + 1) % n] - p[k], p[(k + 2) % n] - p[(k + 1) % n]) >= -tolerance)
}

/// Length of the bounding-box diagonal.
pub fn bbox_diagonal(points: impl IntoIterator<Item = DVec3>) -> f64 {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in points {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    (hi - lo).length()
}

/// The diagonal of the seeds' surface points (the report's reference length).
pub fn seed_diagonal(d: &Discretisation) -> f64 {
    bbox_diagonal(d.seeds.iter().map(|s| s.point))
}

/// The unit normal Su x Sv of a surface at (u, v), from its derivatives.
pub fn unit_normal(surface: &dyn Surface, u: f64, v: f64) -> DVec3 {
    let d = surface.evaluate(u, v);
    d.su.cross(d.sv).normalize()
}

/// Gaussian curvature and max |k|^2 proxy from the derivatives (own formulas):
/// returns (K, |H|).
pub fn gaussian_and_mean(surface: &dyn Surface, u: f64, v: f64) -> (f64, f64) {
    let d = surface.evaluate(u, v);
    let n = d.su.cross(d.sv).normalize();
    let (e, f, g) = (d.su.dot(d.su), d.su.dot(d.sv), d.sv.dot(d.sv));
    let (l, m, nn) = (d.suu.dot(n), d.suv.dot(n), d.svv.dot(n));
    let det = e * g - f * f;
    (
        (l * nn - m * m) / det,
        (e * nn + g * l - 2.0 * f * m) / (2.0 * det),
    )
}

// ---------------------------------------------------------------------------------------
// Mesh checks
// ---------------------------------------------------------------------------------------

/// The facet loops as 3D polygons.
pub fn facet_points(d: &Discretisation, i: usize) -> Vec<DVec3> {
    d.facet(i).iter().map(|&v| d.vertices[v as usize]).collect()
}

/// Largest |n_i . (x - p_i)| / diagonal over all facets i and their vertices x.
pub fn max_planarity(d: &Discretisation, diagonal: f64) -> (f64, usize) {
    let mut worst = (0.0f64, usize::MAX);
    for i in 0..d.facet_count() {
        let s = &d.seeds[i];
        for &v in d.facet(i) {
            let e = s.normal.dot(d.vertices[v as usize] - s.point).abs() / diagonal;
            if !(e <= worst.0) {
                worst = (e, i);
            }
        }
    }
    worst
}

/// Topology of an indexed polygon mesh, computed from the loops alone.
#[derive(Debug, Default)]
pub struct Topology {
    /// Used vertices.
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub euler: i64,
    pub boundary_loops: usize,
    /// Connected components of facets (through shared edges).
    pub components: usize,
    /// Human-readable problems (non-manifold edges or vertices, inconsistent orientation,
    /// degenerate loops).
    pub problems: Vec<String>,
    /// For every facet, the facets sharing an edge with it.
    pub neighbours: Vec<BTreeSet<usize>>,
    /// Vertices on a boundary edge.
    pub on_boundary: Vec<bool>,
    /// Number of facets using each vertex.
    pub valence: Vec<usize>,
    /// Undirected edge -> facets using it.
    pub edge_facets: BTreeMap<(u32, u32), Vec<usize>>,
}

fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

pub fn topology(d: &Discretisation) -> Topology {
    let nf = d.facet_count();
    let nv = d.vertices.len();
    let mut t = Topology {
        faces: nf,
        neighbours: vec![BTreeSet::new(); nf],
        on_boundary: vec![false; nv],
        valence: vec![0; nv],
        ..Default::default()
    };
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for i in 0..nf {
        let l = d.facet(i);
        let distinct: BTreeSet<u32> = l.iter().copied().collect();
        if l.len() < 3 || distinct.len() != l.len() {
            t.problems.push(format!("facet {i}: degenerate loop {l:?}"));
        }
        for k in 0..l.len() {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            if let Some(other) = directed.insert((a, b), i) {
                t.problems.push(format!("directed edge ({a}, {b}) used by facets {other} and {i} (inconsistent orientation)"));
            }
            t.edge_facets
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push(i);
        }
        for &v in &distinct {
            t.valence[v as usize] += 1;
        }
    }
    t.vertices = t.valence.iter().filter(|&&c| c > 0).count();
    t.edges = t.edge_facets.len();
    t.euler = t.vertices as i64 - t.edges as i64 + t.faces as i64;
    let mut parent: Vec<usize> = (0..nf).collect();
    let mut boundary_next: HashMap<u32, Vec<u32>> = HashMap::new();
    for (&(a, b), fs) in &t.edge_facets {
        match fs.len() {
            1 => {
                t.on_boundary[a as usize] = true;
                t.on_boundary[b as usize] = true;
                // Orientation of the boundary edge as its facet walks it.
                let i = fs[0];
                let (from, to) = if directed.get(&(a, b)) == Some(&i) {
                    (a, b)
                } else {
                    (b, a)
                };
                boundary_next.entry(from).or_default().push(to);
            }
            2 => {
                let (f, g) = (fs[0], fs[1]);
                if f == g {
                    t.problems
                        .push(format!("edge ({a}, {b}) used twice by facet {f}"));
                }
                t.neighbours[f].insert(g);
                t.neighbours[g].insert(f);
                let (rf, rg) = (find(&mut parent, f), find(&mut parent, g));
                parent[rf.max(rg)] = rf.min(rg);
            }
            n => t
                .problems
                .push(format!("edge ({a}, {b}) shared by {n} facets {fs:?}")),
        }
    }
    t.components = (0..nf).filter(|&i| find(&mut parent, i) == i).count();
    // Boundary loops: every boundary vertex must have exactly one outgoing boundary edge.
    let mut visited: BTreeSet<u32> = BTreeSet::new();
    let mut starts: Vec<u32> = boundary_next.keys().copied().collect();
    starts.sort_unstable();
    for (&v, next) in &boundary_next {
        if next.len() != 1 {
            t.problems.push(format!(
                "boundary vertex {v} has {} outgoing boundary edges",
                next.len()
            ));
        }
    }
    for s in starts {
        if visited.contains(&s) {
            continue;
        }
        t.boundary_loops += 1;
        let mut v = s;
        let mut steps = 0;
        while visited.insert(v) {
            steps += 1;
            let Some(next) = boundary_next.get(&v).and_then(|n| n.first()) else {
                t.problems
                    .push(format!("boundary path stops at vertex {v}"));
                break;
            };
            v = *next;
            if steps > nv + 1 {
                break;
            }
        }
        if v != s && !t.problems.iter().any(|p| p.contains("boundary")) {
            t.problems.push(format!(
                "boundary walk from {s} does not close (ends at {v})"
            ));
        }
    }
    // Vertex manifoldness: the corners around each vertex form one fan (a cycle inside, a
    // path on the boundary).
    let mut corners: HashMap<u32, Vec<(u32, u32)>> = HashMap::new();
    for i in 0..nf {
        let l = d.facet(i);
        let m = l.len();
        for k in 0..m {
            corners
                .entry(l[k])
                .or_default()
                .push((l[(k + m - 1) % m], l[(k + 1) % m]));
        }
    }
    for (&v, list) in &corners {
        // Corner (prev, next): the facet enters v from prev and leaves to next. The next
        // corner counter-clockwise... chain corners through shared edges: corner c's `next`
        // equals another corner's `prev`.
        let by_prev: HashMap<u32, usize> = list.iter().enumerate().map(|(k, c)| (c.0, k)).collect();
        if by_prev.len() != list.len() {
            t.problems.push(format!(
                "vertex {v}: two facets enter it along the same edge"
            ));
            continue;
        }
        let start = if t.on_boundary[v as usize] {
            // The chain starts at the corner whose `prev` edge is a boundary edge.
            match list.iter().position(|c| {
                t.edge_facets
                    .get(&(c.0.min(v), c.0.max(v)))
                    .map_or(false, |f| f.len() == 1)
            }) {
                Some(k) => k,
                None => {
                    t.problems
                        .push(format!("boundary vertex {v}: no boundary corner"));
                    continue;
                }
            }
        } else {
            0
        };
        let mut seen = vec![false; list.len()];
        let mut k = start;
        let mut count = 0;
        loop {
            if seen[k] {
                break;
            }
            seen[k] = true;
            count += 1;
            // The corner after k around v (clockwise in the facet order): the facet whose
            // loop enters v along the edge that corner k leaves by, reversed... Corner k leaves
            // v towards `next`; the facet on the other side of edge (v, next) enters v from
            // `next`.
            match by_prev.get(&list[k].1) {
                Some(&n) => k = n,
                None => break,
            }
        }
        if count != list.len() {
            t.problems.push(format!("vertex {v}: {} facets meet there but only {count} form one fan (non-manifold vertex)", list.len()));
        }
    }
    t
}

/// The facets (from the loops) that contain each vertex.
pub fn vertex_facets(d: &Discretisation) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new(); d.vertices.len()];
    for i in 0..d.facet_count() {
        for &v in d.facet(i) {
            if !out[v as usize].contains(&i) {
                out[v as usize].push(i);
            }
        }
    }
    out
}

/// Whether facet i has a vertex that is not Interior.
pub fn touches_boundary(d: &Discretisation, i: usize) -> bool {
    d.facet(i)
        .iter()
        .any(|&v| d.vertex_kinds[v as usize] != VertexKind::Interior)
}

// ---------------------------------------------------------------------------------------
// Projection onto a surface (own implementation)
// ---------------------------------------------------------------------------------------

/// The closest point of the surface (restricted to its closed domain) to `x`: brute force on
/// a grid, then projected Newton steps on |S - x|^2. Returns the parameters.
pub fn closest_parameters(surface: &dyn Surface, x: DVec3, grid: usize) -> [f64; 2] {
    let dom = surface.domain();
    let mut best = (f64::INFINITY, [dom.u.min, dom.v.min]);
    for i in 0..=grid {
        for j in 0..=grid {
            let uv = dom.from_normalised([i as f64 / grid as f64, j as f64 / grid as f64]);
            let dist = surface.point_at(uv[0], uv[1]).distance_squared(x);
            if dist < best.0 {
                best = (dist, uv);
            }
        }
    }
    let [mut u, mut v] = best.1;
    for _ in 0..60 {
        let d = surface.evaluate(u, v);
        let r = d.point - x;
        let g = [r.dot(d.su), r.dot(d.sv)];
        let h = [
            d.su.dot(d.su) + r.dot(d.suu),
            d.su.dot(d.sv) + r.dot(d.suv),
            d.sv.dot(d.sv) + r.dot(d.svv),
        ];
        let det = h[0] * h[2] - h[1] * h[1];
        let (mut du, mut dv) = if det > 0.0 && h[0] > 0.0 {
            (
                -(h[2] * g[0] - h[1] * g[1]) / det,
                -(h[0] * g[1] - h[1] * g[0]) / det,
            )
        } else {
            (-g[0] / d.su.length_squared(), -g[1] / d.sv.length_squared())
        };
        // Projected step: clamp into the domain.
        let (nu, nv) = dom.clamp(u + du, v + dv);
        du = nu - u;
        dv = nv - v;
        u = nu;
        v = nv;
        if du.abs() / dom.u.length() + dv.abs() / dom.v.length() < 1e-16 {
            break;
        }
    }
    [u, v]
}

/// Per facet, the distance of its farthest vertex from the surface (`closest_parameters`
/// on a 24 x 24 grid) over its local spacing: the mean distance from its seed to the seeds of
/// the facets it shares a mesh edge with (the edges of [`topology`]), or the seeds'
/// diagonal over the square root of the facet count where it shares none. What the report's
/// far-vertex flag judges, computed independently.
pub fn deviation_spacings(surface: &dyn Surface, d: &Discretisation) -> Vec<f64> {
    let n = d.facet_count();
    let mut deviation = vec![f64::NAN; d.vertices.len()];
    let mut sum = vec![0.0; n];
    let mut count = vec![0usize; n];
    for facets in topology(d).edge_facets.values() {
        if let [f, g] = facets[..] {
            if f != g {
                let h = d.seeds[f].point.distance(d.seeds[g].point);
                for x in [f, g] {
                    sum[x] += h;
                    count[x] += 1;
                }
            }
        }
    }
    let pattern = seed_diagonal(d) / (n.max(1) as f64).sqrt();
    (0..n)
        .map(|i| {
            let mut farthest = 0.0f64;
            for &v in d.facet(i) {
                let v = v as usize;
                if deviation[v].is_nan() {
                    let x = d.vertices[v];
                    let [u, w] = closest_parameters(surface, x, 24);
                    deviation[v] = surface.point_at(u, w).distance(x);
                }
                farthest = farthest.max(deviation[v]);
            }
            let spacing = if count[i] > 0 && sum[i] > 0.0 {
                sum[i] / count[i] as f64
            } else {
                pattern
            };
            farthest / spacing
        })
        .collect()
}

/// min(s, 1 - s, t, 1 - t) of the normalised parameters.
pub fn inside_measure(surface: &dyn Surface, uv: [f64; 2]) -> f64 {
    let [s, t] = surface.domain().to_normalised(uv);
    s.min(1.0 - s).min(t).min(1.0 - t)
}

// ---------------------------------------------------------------------------------------
// The envelope oracle (half-plane intersection inside one tangent plane)
// ---------------------------------------------------------------------------------------

/// Label of the edges of the starting square (no plane).
pub const SQUARE: usize = usize::MAX;

/// The face of plane i on the envelope of the half-spaces {x : s_j n_j.(x - p_j) >= 0}.
#[derive(Debug, Clone)]
pub struct EnvelopeFace {
    /// Vertices, counter-clockwise seen from n_i, short edges merged.
    pub vertices: Vec<DVec3>,
    /// The plane that produced the edge from vertex k to vertex k + 1.
    pub labels: Vec<usize>,
    /// Planes whose edge is shorter than the merge tolerance (ambiguous neighbours).
    pub ambiguous: Vec<usize>,
    /// Whether the face is bounded inside the starting square.
    pub bounded: bool,
}

impl EnvelopeFace {
    pub fn neighbours(&self) -> BTreeSet<usize> {
        self.labels
            .iter()
            .copied()
            .filter(|&l| l != SQUARE)
            .collect()
    }
}

/// Sutherland-Hodgman clipping of a convex polygon by `a . q + c >= 0`; `labels[k]` labels
/// the edge from vertex k to k + 1; the new edge along the clip line gets `label`.
fn clip(
    poly: &mut Vec<(DVec2, usize)>,
    a: DVec2,
    c: f64,
    label: usize,
    scratch: &mut Vec<(DVec2, usize)>,
) {
    scratch.clear();
    let n = poly.len();
    if n == 0 {
        return;
    }
    let mut all_in = true;
    let values: Vec<f64> = poly.iter().map(|(q, _)| a.dot(*q) + c).collect();
    for &f in &values {
        if f < 0.0 {
            all_in = false;
            break;
        }
    }
    if all_in {
        return;
    }
    for k in 0..n {
        let (p, lp) = poly[k];
        let (q, _) = poly[(k + 1) % n];
        let (fp, fq) = (values[k], values[(k + 1) % n]);
        let p_in = fp >= 0.0;
        let q_in = fq >= 0.0;
        if p_in {
            scratch.push((p, lp));
            if !q_in {
                let t = fp / (fp - fq);
                scratch.push((p + (q - p) * t, label));
            }
        } else if q_in {
            let t = fp / (fp - fq);
            scratch.push((p + (q - p) * t, lp));
        }
    }
    std::mem::swap(poly, scratch);
}

/// The envelope face of plane `i` among all planes (points `p`, unit normals `n`, signs `s`
/// orienting each normal towards the centres of curvature). The square starts at
/// `half_width` around p_i; all other planes clip it (nearest first, which only matters for
/// speed). Vertices are recomputed as exact three-plane meeting points by [`meet3`], and
/// vertices closer than `merge` are merged (the plane of the vanishing edge becomes
/// ambiguous).
pub fn envelope_face(
    i: usize,
    p: &[DVec3],
    n: &[DVec3],
    s: &[f64],
    half_width: f64,
    merge: f64,
) -> EnvelopeFace {
    let (e1, e2) = frame(n[i] * s[i]);
    let h = half_width;
    let mut poly: Vec<(DVec2, usize)> = vec![
        (DVec2::new(-h, -h), SQUARE),
        (DVec2::new(h, -h), SQUARE),
        (DVec2::new(h, h), SQUARE),
        (DVec2::new(-h, h), SQUARE),
    ];
    let mut order: Vec<(f64, usize)> = (0..p.len())
        .filter(|&j| j != i)
        .map(|j| (p[j].distance_squared(p[i]), j))
        .collect();
    let near = order.len().min(48);
    if near < order.len() {
        order.select_nth_unstable_by(near, |a, b| a.0.total_cmp(&b.0));
    }
    order[..near].sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    let mut scratch = Vec::new();
    for &(_, j) in &order {
        // s_j n_j . (p_i + a e1 + b e2 - p_j) >= 0.
        let m = n[j] * s[j];
        let a = DVec2::new(m.dot(e1), m.dot(e2));
        let c = m.dot(p[i] - p[j]);
        clip(&mut poly, a, c, j, &mut scratch);
    }
    let bounded = poly.iter().all(|&(_, l)| l != SQUARE) && poly.len() >= 3;
    let m = poly.len();
    let mut vertices = Vec::with_capacity(m);
    for k in 0..m {
        let (q, l_next) = poly[k];
        let l_prev = poly[(k + m - 1) % m].1;
        let exact = if l_prev != SQUARE && l_next != SQUARE && l_prev != l_next {
            meet3([p[i], p[l_prev], p[l_next]], [n[i], n[l_prev], n[l_next]])
        } else {
            None
        };
        vertices.push(exact.unwrap_or(p[i] + e1 * q.x + e2 * q.y));
    }
    let mut labels: Vec<usize> = poly.iter().map(|x| x.1).collect();
    // Merge vertices joined by an edge shorter than `merge`.
    let mut ambiguous = Vec::new();
    let mut k = 0;
    while vertices.len() > 3 && k < vertices.len() {
        let next = (k + 1) % vertices.len();
        if vertices[k].distance(vertices[next]) < merge {
            ambiguous.push(labels[k]);
            labels.remove(k);
            vertices.remove(k);
        } else {
            k += 1;
        }
    }
    // Orientation: the frame is right-handed about s_i n_i; report counter-clockwise about n_i.
    if s[i] < 0.0 {
        // Reversing the vertex order: edge k (vertex k -> k+1) becomes edge from vertex k+1
        // to k; relabel accordingly.
        let m = vertices.len();
        let v: Vec<DVec3> = (0..m).rev().map(|k| vertices[k]).collect();
        let l: Vec<usize> = (0..m).rev().map(|k| labels[(k + m - 1) % m]).collect();
        vertices = v;
        labels = l;
    }
    EnvelopeFace {
        vertices,
        labels,
        ambiguous,
        bounded,
    }
}

/// Merges consecutive points of a closed loop closer than `merge`.
pub fn merge_loop(points: &[DVec3], merge: f64) -> Vec<DVec3> {
    let mut v = points.to_vec();
    let mut k = 0;
    while v.len() > 3 && k < v.len() {
        let next = (k + 1) % v.len();
        if v[k].distance(v[next]) < merge {
            v.remove(k);
        } else {
            k += 1;
        }
    }
    v
}

/// Largest distance between two loops matched in cyclic order (same length required);
/// None when no rotation matches within `tol`.
pub fn cyclic_match(a: &[DVec3], b: &[DVec3], tol: f64) -> Option<f64> {
    if a.len() != b.len() || a.is_empty() {
        return None;
    }
    let m = a.len();
    let mut best: Option<f64> = None;
    for r in 0..m {
        if a[0].distance(b[r]) > tol {
            continue;
        }
        let worst = (0..m)
            .map(|k| a[k].distance(b[(k + r) % m]))
            .fold(0.0, f64::max);
        if worst <= tol && best.map_or(true, |b| worst < b) {
            best = Some(worst);
        }
    }
    best
}

// ---------------------------------------------------------------------------------------
// NURBS domes built from control nets
// ---------------------------------------------------------------------------------------

/// Greville abscissae of a knot vector in Rhino's convention (count + degree - 1 knots):
/// xi_i = (k_i + ... + k_(i+p-1)) / p.
pub fn greville(knots: &[f64], degree: usize, count: usize) -> Vec<f64> {
    (0..count)
        .map(|i| knots[i..i + degree].iter().sum::<f64>() / degree as f64)
        .collect()
}

/// A bicubic (or other degree) NURBS whose control points sit over the Greville abscissae
/// mapped by `xy`, lifted by `z`, with optional weights from `w`.
#[allow(clippy::too_many_arguments)]
pub fn lifted_net(
    degree: [usize; 2],
    knots_u: &[f64],
    knots_v: &[f64],
    xy: impl Fn(f64, f64) -> (f64, f64),
    z: impl Fn(f64, f64, usize, usize) -> f64,
    w: Option<&dyn Fn(usize, usize) -> f64>,
) -> NurbsSurface {
    let count = [knots_u.len() + 1 - degree[0], knots_v.len() + 1 - degree[1]];
    let gu = greville(knots_u, degree[0], count[0]);
    let gv = greville(knots_v, degree[1], count[1]);
    let (u0, u1) = (knots_u[degree[0] - 1], knots_u[count[0] - 1]);
    let (v0, v1) = (knots_v[degree[1] - 1], knots_v[count[1] - 1]);
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..count[0] {
        for j in 0..count[1] {
            // Normalised Greville position in [0, 1].
            let (s, t) = ((gu[i] - u0) / (u1 - u0), (gv[j] - v0) / (v1 - v0));
            let (x, y) = xy(s, t);
            points.push(DVec3::new(x, y, z(x, y, i, j)));
            if let Some(w) = w {
                weights.push(w(i, j));
            }
        }
    }
    NurbsSurface::new(
        degree,
        count,
        knots_u,
        knots_v,
        &points,
        w.map(|_| weights.as_slice()),
    )
    .unwrap_or_else(|e| panic!("test NURBS rejected: {e}"))
}

/// Checks strict convexity: K > 0 with consistent sign on a dense grid, and every sampled
/// surface point on one side of the tangent planes at a coarser grid. Returns the side
/// (+1 when the surface bends towards Su x Sv) and the smallest K / H^2 seen.
pub fn assert_strictly_convex(name: &str, surface: &dyn Surface) -> (f64, f64) {
    let dom = surface.domain();
    let mut min_ratio = f64::INFINITY;
    let mut mean_sign = 0.0;
    let g = 40;
    for i in 0..=g {
        for j in 0..=g {
            let [u, v] = dom.from_normalised([i as f64 / g as f64, j as f64 / g as f64]);
            let (k, h) = gaussian_and_mean(surface, u, v);
            assert!(k > 0.0, "{name}: K = {k} <= 0 at ({u}, {v})");
            min_ratio = min_ratio.min(k / (h * h));
            if mean_sign == 0.0 {
                mean_sign = h.signum();
            }
            assert_eq!(
                h.signum(),
                mean_sign,
                "{name}: mean curvature changes sign at ({u}, {v})"
            );
        }
    }
    // Global: the surface on one side of every tangent plane.
    let samples: Vec<DVec3> = (0..=24)
        .flat_map(|i| (0..=24).map(move |j| (i, j)))
        .map(|(i, j)| {
            let [u, v] = dom.from_normalised([i as f64 / 24.0, j as f64 / 24.0]);
            surface.point_at(u, v)
        })
        .collect();
    for i in 0..=12 {
        for j in 0..=12 {
            let [u, v] = dom.from_normalised([i as f64 / 12.0, j as f64 / 12.0]);
            let p = surface.point_at(u, v);
            let n = unit_normal(surface, u, v);
            for q in &samples {
                let side = mean_sign * n.dot(*q - p);
                assert!(side >= -1e-12, "{name}: sample {q} on the wrong side ({side}) of the tangent plane at ({u}, {v})");
            }
        }
    }
    (mean_sign, min_ratio)
}

/// Per seed, the side of its tangent plane that the surface lies on (+1: along the normal),
/// from surface samples (independent of the seeds' curvatures).
pub fn sides_from_samples(surface: &dyn Surface, points: &[DVec3], normals: &[DVec3]) -> Vec<f64> {
    let dom = surface.domain();
    let samples: Vec<DVec3> = (0..=8)
        .flat_map(|i| (0..=8).map(move |j| (i, j)))
        .map(|(i, j)| {
            let [u, v] = dom.from_normalised([i as f64 / 8.0, j as f64 / 8.0]);
            surface.point_at(u, v)
        })
        .collect();
    points
        .iter()
        .zip(normals)
        .map(|(&p, &n)| {
            let sum: f64 = samples.iter().map(|&q| n.dot(q - p)).sum();
            assert!(sum != 0.0);
            sum.signum()
        })
        .collect()
}

// ---- strictly convex NURBS test domes, shared by the envelope and stress tests ----

/// Bicubic 6 x 6, clamped non-uniform knots in both directions (domain [1, 3] x [0, 2]),
/// lifted on a tilted paraboloid-like bump with a small random jitter.
pub fn dome_a() -> NurbsSurface {
    let mut rng = Rng::new(101);
    let jitter: Vec<f64> = (0..36).map(|_| rng.range(-0.01, 0.01)).collect();
    lifted_net(
        [3, 3],
        &[1.0, 1.0, 1.0, 1.4, 2.3, 3.0, 3.0, 3.0],
        &[0.0, 0.0, 0.0, 0.55, 0.7, 2.0, 2.0, 2.0],
        |s, t| (-1.0 + 2.0 * s, -1.0 + 2.0 * t),
        |x, y, i, j| 1.0 - 0.55 * x * x - 0.35 * y * y + 0.06 * x * y + jitter[i * 6 + j],
        None,
    )
}

/// Bicubic 7 x 5 with a warped x spacing and strongly non-uniform knots.
pub fn dome_b() -> NurbsSurface {
    let mut rng = Rng::new(202);
    let jitter: Vec<f64> = (0..35).map(|_| rng.range(-0.006, 0.006)).collect();
    lifted_net(
        [3, 3],
        &[0.0, 0.0, 0.0, 0.12, 0.3, 0.75, 1.0, 1.0, 1.0],
        &[0.0, 0.0, 0.0, 0.35, 1.0, 1.0, 1.0],
        |s, t| {
            let a = 2.0 * s - 1.0;
            (1.6 * a + 0.2 * a * a * a, 0.8 * (2.0 * t - 1.0))
        },
        |x, y, i, j| {
            0.9 - 0.25 * x * x - 0.8 * y * y - 0.02 * x * x * x + 0.05 * x * y + jitter[i * 5 + j]
        },
        None,
    )
}

/// Rational, degrees (2, 3), 6 x 6, non-uniform knots, non-separable weights in [0.45, 1.55].
pub fn dome_c() -> NurbsSurface {
    let w = |i: usize, j: usize| {
        1.0 + 0.55
            * (1.3 * i as f64 + 0.7 * j as f64).sin()
            * (0.9 * j as f64 - 0.4 * i as f64).cos()
    };
    lifted_net(
        [2, 3],
        &[0.0, 0.0, 0.2, 0.5, 0.6, 1.0, 1.0],
        &[-1.0, -1.0, -1.0, -0.2, 0.6, 1.0, 1.0, 1.0],
        |s, t| (-1.2 + 2.4 * s, -1.0 + 2.0 * t),
        |x, y, _, _| 1.2 - 0.45 * x * x - 0.5 * y * y,
        Some(&w),
    )
}

/// The rational quadratic full circle of radius 1 about z, as (x, y, weight) control points:
/// four 90-degree arcs, the first point repeated at the end (knots 0 0 1 1 2 2 3 3 4 4).
pub fn rational_circle() -> [(f64, f64, f64); 9] {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    [
        (1.0, 0.0, 1.0),
        (1.0, 1.0, w),
        (0.0, 1.0, 1.0),
        (-1.0, 1.0, w),
        (-1.0, 0.0, 1.0),
        (-1.0, -1.0, w),
        (0.0, -1.0, 1.0),
        (1.0, -1.0, w),
        (1.0, 0.0, 1.0),
    ]
}

/// The unit circle as a rational quadratic NURBS curve: nine control points (x, y, weight) on
/// the square around it, the corners weighted 1/sqrt 2.
pub const RATIONAL_CIRCLE: [(f64, f64, f64); 9] = {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    [
        (1.0, 0.0, 1.0),
        (1.0, 1.0, w),
        (0.0, 1.0, 1.0),
        (-1.0, 1.0, w),
        (-1.0, 0.0, 1.0),
        (-1.0, -1.0, w),
        (0.0, -1.0, 1.0),
        (1.0, -1.0, w),
        (1.0, 0.0, 1.0),
    ]
};

/// The knots of [`RATIONAL_CIRCLE`] (Rhino's convention: no extra end knots).
pub const RATIONAL_CIRCLE_KNOTS: [f64; 10] = [0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0];

/// A surface of the repository's `samples/` folder, by file name.
pub fn sample_surface(name: &str) -> tpi_core::SurfaceModel {
    let path = format!("{}/../../samples/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    tpi_core::SurfaceSpec::from_json(&text, name)
        .unwrap()
        .build()
        .unwrap()
}

/// Distance from x to the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1, from its closed form:
/// the nearest point is p_i = a_i^2 x_i / (a_i^2 + l), l the root of
/// f(l) = sum (a_i x_i / (a_i^2 + l))^2 - 1 on (-min a_i^2, inf), where f falls from +inf
/// to -1 (bisection to the last bit). For x on an axis inside the ellipsoid the root may not
/// exist; no mesh vertex of these tests lies there.
pub fn ellipsoid_distance(axes: [f64; 3], x: DVec3) -> f64 {
    let x = x.to_array();
    let f = |l: f64| {
        (0..3)
            .map(|i| (axes[i] * x[i] / (axes[i] * axes[i] + l)).powi(2))
            .sum::<f64>()
            - 1.0
    };
    let smallest = axes.iter().map(|a| a * a).fold(f64::INFINITY, f64::min);
    let (mut lo, mut hi) = (-smallest, 1.0);
    while f(hi) > 0.0 {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let l = 0.5 * (lo + hi);
    let p: Vec<f64> = (0..3)
        .map(|i| axes[i] * axes[i] * x[i] / (axes[i] * axes[i] + l))
        .collect();
    ((p[0] - x[0]).powi(2) + (p[1] - x[1]).powi(2) + (p[2] - x[2]).powi(2)).sqrt()
}

/// The largest `distance(x)` over the mesh vertices that some facet uses (vertices no facet
/// uses are left out, as the report leaves them out).
pub fn max_over_used_vertices(d: &Discretisation, distance: impl Fn(DVec3) -> f64) -> f64 {
    let mut used = vec![false; d.vertices.len()];
    for &v in &d.facet_loops {
        used[v as usize] = true;
    }
    d.vertices
        .iter()
        .zip(&used)
        .filter(|(_, &u)| u)
        .map(|(&x, _)| distance(x))
        .fold(0.0, f64::max)
}

/// A hex (triangular-lattice) pattern of about `n` points in the unit square, rotated by
/// `degrees` about the square's centre.
pub fn rotated_hex(n: usize, degrees: f64) -> Vec<[f64; 2]> {
    let h = (2.0 / (3f64.sqrt() * n as f64)).sqrt();
    let (s, c) = degrees.to_radians().sin_cos();
    let reach = (0.75f64).sqrt() + 2.0 * h;
    let rows = (2.0 * reach / (h * 0.75f64.sqrt())).ceil() as i64;
    let cols = (2.0 * reach / h).ceil() as i64;
    let mut out = Vec::new();
    for r in -rows..=rows {
        for q in -cols..=cols {
            let x = (q as f64 + 0.5 * (r.rem_euclid(2)) as f64) * h + 0.25 * h;
            let y = r as f64 * h * 0.75f64.sqrt() + 0.2 * h;
            let (u, v) = (0.5 + c * x - s * y, 0.5 + s * x + c * y);
            if (0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v) {
                out.push([u, v]);
            }
        }
    }
    out
}

// ---------------------------------------------------------------------------------------
// Sweeps (examples mixed_sweep and saddle_sweep)
// ---------------------------------------------------------------------------------------

/// One random mixed surface: z(x, y) over [-5, 5] x [-4, 4], in a frame turned by a random
/// angle, the sum of a crest a cos(k x'), a quadratic b y'^2 + c x' y', and a Gaussian bump
/// (or dip) of height h; drawn again until K takes both signs on a 24 x 24 grid.
pub fn mixed_surface(seed: u64) -> NurbsSurface {
    let mut rng = Rng::new(0x6d_6978_6564 ^ seed.wrapping_mul(0x9e37_79b9_7f4a_7c15));
    loop {
        let angle = rng.range(0.0, std::f64::consts::PI);
        let a = rng.range(1.0, 2.5) * if rng.f64() < 0.5 { 1.0 } else { -1.0 };
        let k = rng.range(0.3, 0.6);
        let phase = rng.range(-0.8, 0.8);
        let b = rng.range(-0.08, 0.08);
        let c = rng.range(-0.05, 0.05);
        let h = rng.range(-1.5, 1.5);
        let (x0, y0) = (rng.range(-3.0, 3.0), rng.range(-2.5, 2.5));
        let r = rng.range(1.5, 3.0);
        let (sn, cs) = (angle.sin(), angle.cos());
        let z = move |x: f64, y: f64| {
            let (xr, yr) = (cs * x + sn * y, -sn * x + cs * y);
            a * (k * xr + phase).cos()
                + b * yr * yr
                + c * xr * yr
                + h * (-((x - x0).powi(2) + (y - y0).powi(2)) / (r * r)).exp()
        };
        let knots = [
            0.0, 0.0, 0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0, 1.0, 1.0,
        ];
        let surface = lifted_net(
            [3, 3],
            &knots,
            &knots,
            |s, t| (-5.0 + 10.0 * s, -4.0 + 8.0 * t),
            |x, y, _, _| z(x, y),
            None,
        );
        let (mut positive, mut negative) = (0, 0);
        for i in 0..24 {
            for j in 0..24 {
                let (u, v) = ((i as f64 + 0.5) / 24.0, (j as f64 + 0.5) / 24.0);
                let (gauss, _) = gaussian_and_mean(&surface, u, v);
                if gauss > 1e-4 {
                    positive += 1;
                } else if gauss < -1e-4 {
                    negative += 1;
                }
            }
        }
        // Both signs over a sizeable share of the surface: a truly mixed roof.
        if positive >= 60 && negative >= 60 {
            return surface;
        }
    }
}

/// The patterns of the sweep at size `n`: hex at 0, 30 and 72 degrees, a square grid, a
/// Poisson-disk pattern and uniform random points (seeded by `seed`).
pub fn sweep_patterns(n: usize, seed: u64) -> Vec<(String, Vec<[f64; 2]>)> {
    let k = (n as f64).sqrt().round() as usize;
    let grid: Vec<[f64; 2]> = (0..k)
        .flat_map(|i| {
            (0..k).map(move |j| [(i as f64 + 0.5) / k as f64, (j as f64 + 0.5) / k as f64])
        })
        .collect();
    let poisson = Generator::Poisson {
        radius: (0.7 / n as f64).sqrt(),
        seed: seed + n as u64,
    }
    .generate()
    .uv;
    let random = Generator::Random {
        count: n,
        seed: seed + 1000 + n as u64,
    }
    .generate()
    .uv;
    vec![
        (format!("hex{n}@0"), rotated_hex(n, 0.0)),
        (format!("hex{n}@30"), rotated_hex(n, 30.0)),
        (format!("hex{n}@72"), rotated_hex(n, 72.0)),
        (format!("grid{n}"), grid),
        (format!("poisson{n}"), poisson),
        (format!("random{n}"), random),
    ]
}

/// The tilts (degrees) of the adjusted facets' planes, those above 0, in increasing order.
pub fn sorted_tilts(d: &Discretisation) -> Vec<f64> {
    let mut tilted: Vec<f64> = d
        .plane_adjustments
        .iter()
        .map(|a| a.tilt_degrees)
        .filter(|&t| t > 0.0)
        .collect();
    tilted.sort_by(f64::total_cmp);
    tilted
}

/// How far the mesh's edge stays from the surface's edge: for `samples` points per side of
/// the domain rectangle's boundary curve, the distance of the surface point to the nearest
/// mesh boundary edge (an edge held by one facet, from the loops), over the mean seed spacing
/// (seed bounding diagonal / sqrt(2 n)); ascending.
pub fn boundary_gaps(surface: &dyn Surface, d: &Discretisation, samples: usize) -> Vec<f64> {
    let t = topology(d);
    let edges: Vec<(DVec3, DVec3)> = t
        .edge_facets
        .iter()
        .filter(|(_, f)| f.len() == 1)
        .map(|(&(a, b), _)| (d.vertices[a as usize], d.vertices[b as usize]))
        .collect();
    let spacing = seed_diagonal(d) / (2.0 * d.facet_count() as f64).sqrt();
    let segment_distance = |p: DVec3, a: DVec3, b: DVec3| {
        let ab = b - a;
        let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
        (a + ab * t - p).length()
    };
    let dom = surface.domain();
    let (u, v) = (dom.u, dom.v);
    let mut gaps = Vec::with_capacity(4 * samples);
    for k in 0..samples {
        let s = k as f64 / samples as f64;
        for [a, b] in [
            [u.min + s * u.length(), v.min],
            [u.max, v.min + s * v.length()],
            [u.max - s * u.length(), v.max],
            [u.min, v.max - s * v.length()],
        ] {
            let p = surface.point_at(a, b);
            let nearest = edges
                .iter()
                .map(|&(e0, e1)| segment_distance(p, e0, e1))
                .fold(f64::INFINITY, f64::min);
            gaps.push(nearest / spacing);
        }
    }
    gaps.sort_by(f64::total_cmp);
    gaps
}
