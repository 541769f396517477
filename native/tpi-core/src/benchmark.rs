//! The benchmark inputs shared by `cargo bench -p tpi-core` and `tpi bench`
//! (docs/performance.md): two convex surfaces, a saddle and uniform random patterns.
//!
//! - [`paraboloid`]: the paraboloid of revolution z = -0.08 (x^2 + y^2) over [-5, 5]^2, the
//!   analytic case (as samples/paraboloid.json).
//! - [`nurbs_dome`]: a bicubic NURBS dome with 12 x 12 control points and non-uniform clamped
//!   knots in both directions, the free-form case the paper benchmarks.
//! - [`saddle`]: a bicubic NURBS saddle, K < 0 everywhere with varying curvature (as
//!   samples/saddle.json): the any-curvature path (ghosts, |II| flips, validity flips).
//! - [`random_pattern`]: n uniform random points in the unit square (SplitMix64, fixed seed per
//!   n), the same generator as `tpi pattern random:N:seed=S`.
//! - [`poisson_pattern`]: about n Poisson-disk points in the unit square (radius
//!   sqrt(0.7 / n), fixed seed per n), the same generator as `tpi pattern poisson:R:seed=S`:
//!   the even spacing designers draw, where uniform random points hold close pairs.
//! - [`floor`]: what any TPI discretisation of the same input cannot avoid, timed stage by
//!   stage: surface evaluation with curvature at every point, one triangulation of the
//!   points' slopes (of their parameters where the slope frame does not apply), one
//!   three-plane solve per triangle, and one write of the result (vertex coordinates and
//!   triangle indices as text, into memory). `tpi bench --floor` prints the pipeline's
//!   ratio to it.

use std::io::Write;
use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;

use crate::analytic::AnalyticSurface;
use crate::diffgeo::LocalGeometry;
use crate::error::TpiError;
use crate::neighbours::{slope_frame, SlopeFrame};
use crate::nurbs::NurbsSurface;
use crate::pattern::Generator;
use crate::planes::{intersect_three, Plane};
use crate::surface::Surface;
use crate::triangulation::DualTriangulation;

/// The benchmark's analytic surface: z = -0.08 (x^2 + y^2) over [-5, 5]^2.
pub fn paraboloid() -> AnalyticSurface {
    // Valid constants: the constructor cannot fail.
    AnalyticSurface::elliptic_paraboloid(-0.08, -0.08, [-5.0, 5.0], [-5.0, 5.0])
        .unwrap_or_else(|e| unreachable_surface(&e.to_string()))
}

/// Knots (Rhino convention, 12 + 3 - 1 = 14) of the dome in u: clamped, non-uniform.
pub const DOME_KNOTS_U: [f64; 14] = [
    0.0, 0.0, 0.0, 0.7, 1.6, 2.2, 3.5, 4.1, 5.6, 6.3, 7.9, 10.0, 10.0, 10.0,
];

/// Knots of the dome in v: clamped, non-uniform, another spacing.
pub const DOME_KNOTS_V: [f64; 14] = [
    0.0, 0.0, 0.0, 1.2, 1.5, 2.9, 3.3, 4.8, 6.0, 6.4, 7.7, 8.0, 8.0, 8.0,
];

/// The benchmark's free-form surface: a bicubic, non-rational NURBS dome of 12 x 12 control
/// points over the Greville abscissae of [`DOME_KNOTS_U`] x [`DOME_KNOTS_V`], mapped to a
/// 12 x 10 rectangle and lifted by z = 4 - 0.09 x^2 - 0.12 y^2 + 0.01 x y plus a small
/// deterministic wobble: strictly convex everywhere (K > 0).
pub fn nurbs_dome() -> NurbsSurface {
    let (p, n) = (3usize, 12usize);
    let greville = |knots: &[f64]| -> Vec<f64> {
        let (lo, hi) = (knots[p - 1], knots[n - 1]);
        (0..n)
            .map(|i| (knots[i..i + p].iter().sum::<f64>() / p as f64 - lo) / (hi - lo))
            .collect()
    };
    let (gu, gv) = (greville(&DOME_KNOTS_U), greville(&DOME_KNOTS_V));
    let mut points = Vec::with_capacity(n * n);
    for (i, &s) in gu.iter().enumerate() {
        for (j, &t) in gv.iter().enumerate() {
            let (x, y) = (12.0 * s - 6.0, 10.0 * t - 5.0);
            let wobble = 0.02 * (((i * 7 + j * 5) % 11) as f64 / 10.0 - 0.5);
            points.push(DVec3::new(
                x,
                y,
                4.0 - 0.09 * x * x - 0.12 * y * y + 0.01 * x * y + wobble,
            ));
        }
    }
    NurbsSurface::new([p, p], [n, n], &DOME_KNOTS_U, &DOME_KNOTS_V, &points, None)
        .unwrap_or_else(|e| unreachable_surface(&e.to_string()))
}

/// Knots (Rhino convention) of the saddle in u: clamped, non-uniform.
pub const SADDLE_KNOTS_U: [f64; 11] = [0.0, 0.0, 0.0, 1.5, 3.0, 5.0, 7.0, 8.5, 10.0, 10.0, 10.0];

/// Knots of the saddle in v.
pub const SADDLE_KNOTS_V: [f64; 9] = [0.0, 0.0, 0.0, 2.0, 4.0, 6.0, 8.0, 8.0, 8.0];

/// The benchmark's saddle: bicubic 9 x 7 control points over the Greville abscissae of
/// [`SADDLE_KNOTS_U`] x [`SADDLE_KNOTS_V`], mapped to [-6, 6] x [-4.5, 4.5] and lifted by
/// z = 0.05 x^2 - 0.09 y^2 + 0.03 x y + 0.003 x^3 (samples/saddle.json).
pub fn saddle() -> NurbsSurface {
    let p = 3usize;
    let greville = |knots: &[f64]| -> Vec<f64> {
        let n = knots.len() + 1 - p;
        let (lo, hi) = (knots[p - 1], knots[n - 1]);
        (0..n)
            .map(|i| (knots[i..i + p].iter().sum::<f64>() / p as f64 - lo) / (hi - lo))
            .collect()
    };
    let (gu, gv) = (greville(&SADDLE_KNOTS_U), greville(&SADDLE_KNOTS_V));
    let mut points = Vec::with_capacity(gu.len() * gv.len());
    for &s in &gu {
        for &t in &gv {
            let (x, y) = (12.0 * s - 6.0, 9.0 * t - 4.5);
            points.push(DVec3::new(
                x,
                y,
                0.05 * x * x - 0.09 * y * y + 0.03 * x * y + 0.003 * x * x * x,
            ));
        }
    }
    NurbsSurface::new(
        [p, p],
        [gu.len(), gv.len()],
        &SADDLE_KNOTS_U,
        &SADDLE_KNOTS_V,
        &points,
        None,
    )
    .unwrap_or_else(|e| unreachable_surface(&e.to_string()))
}

/// `n` uniform random points in [0, 1]^2 (no duplicates), deterministic for a given `n`:
/// the pattern of `tpi pattern random:N:seed=S` with S = 7 + n.
pub fn random_pattern(n: usize) -> Vec<[f64; 2]> {
    Generator::Random {
        count: n.max(1),
        seed: 7 + n as u64,
    }
    .generate()
    .uv
}

/// About `n` Poisson-disk points in [0, 1]^2 (Bridson's sampling gives about 0.7 / R^2 points
/// for radius R, so R = sqrt(0.7 / n)), deterministic for a given `n`: the pattern of
/// `tpi pattern poisson:R:seed=S` with S = 7 + n.
pub fn poisson_pattern(n: usize) -> Vec<[f64; 2]> {
    let radius = (0.7 / n.max(1) as f64)
        .sqrt()
        .max(crate::tolerance::MIN_POISSON_RADIUS);
    Generator::Poisson {
        radius,
        seed: 7 + n as u64,
    }
    .generate()
    .uv
}

/// The Delaunay triangulation the pipeline starts from (spade's bulk loader, converted to the
/// dual structure's flat arrays), for timing that stage alone: its triangle count.
pub fn delaunay_triangle_count(points: &[[f64; 2]]) -> Result<usize, TpiError> {
    DualTriangulation::delaunay(points).map(|t| t.len())
}

/// The floor's stage times in milliseconds (see the module doc).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct FloorTimings {
    /// Evaluation with derivatives and curvature at every point, tangent planes.
    pub samples: f64,
    /// One Delaunay triangulation of the slopes (spade's bulk loader).
    pub triangulation: f64,
    /// One three-plane intersection per triangle.
    pub plane_solves: f64,
    /// Vertex coordinates and triangle indices written as text into memory.
    pub write: f64,
    /// samples + triangulation + plane solves: what `discretise` itself cannot avoid.
    pub compute: f64,
}

/// Times the floor on `surface` and `pattern` (normalised uv), in the current rayon pool.
pub fn floor(surface: &dyn Surface, pattern: &[[f64; 2]]) -> Result<FloorTimings, TpiError> {
    let ms = |since: Instant| since.elapsed().as_secs_f64() * 1e3;
    let mut t = FloorTimings::default();
    let start = Instant::now();
    let domain = surface.domain();
    let planes: Vec<Plane> = pattern
        .par_iter()
        .map(|&st| {
            let [u, v] = domain.from_normalised(st);
            LocalGeometry::from_derivatives(&surface.evaluate(u, v)).tangent_plane()
        })
        .collect();
    t.samples = ms(start);
    let stage = Instant::now();
    let frame = slope_frame(surface).map(|n| SlopeFrame::new(n, 1));
    let slopes: Option<Vec<[f64; 2]>> =
        frame.and_then(|f| planes.iter().map(|p| f.slopes(p)).collect());
    // Folded slopes (a saddle's can repeat) fall back to the parameters.
    let triangulation = match slopes.as_deref().map(DualTriangulation::delaunay) {
        Some(Ok(triangulation)) => triangulation,
        _ => DualTriangulation::delaunay(pattern)?,
    };
    t.triangulation = ms(stage);
    let stage = Instant::now();
    let vertices: Vec<DVec3> = triangulation
        .triangles
        .par_iter()
        .map(|&[a, b, c]| {
            intersect_three(
                &planes[a as usize],
                &planes[b as usize],
                &planes[c as usize],
            )
            .point
        })
        .collect();
    t.plane_solves = ms(stage);
    t.compute = ms(start);
    let stage = Instant::now();
    let mut out: Vec<u8> = Vec::with_capacity(vertices.len() * 64);
    for v in &vertices {
        let _ = writeln!(out, "v {} {} {}", v.x, v.y, v.z);
    }
    for [a, b, c] in &triangulation.triangles {
        let _ = writeln!(out, "f {} {} {}", a + 1, b + 1, c + 1);
    }
    std::hint::black_box(&out);
    t.write = ms(stage);
    Ok(t)
}

#[cold]
fn unreachable_surface(message: &str) -> ! {
    panic!("benchmark surface rejected (a bug in its constants): {message}")
}
