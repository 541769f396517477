//! Stage 1 of the pipeline: surface + pattern -> samples.
//!
//! Per pattern point (normalised uv in [0, 1]^2, mapped affinely onto the surface's domain):
//! the surface point p, the unit normal n = Su x Sv / |Su x Sv|, the principal curvatures
//! k1 <= k2 and directions (from the first and second fundamental forms, [`LocalGeometry`]),
//! the tangent plane n . (x - p) = 0, and the curvature class: +1 or -1 where strictly convex
//! (K = k1 k2 > 0, the sign of the centres of curvature along n), 0 where saddle-shaped or flat
//! (|K| <= flat_tolerance * max(k1^2, k2^2)). Where every point is convex on one side and all
//! normals lie within the slope frame's cone, also the lifted points (s_i, h_i) of the convex
//! path ([`crate::neighbours::SlopeFrame::lift`]).

use glam::DVec3;
use rayon::prelude::*;

use crate::diagnostics::Diagnostic;
use crate::diffgeo::LocalGeometry;
use crate::discretise::{DiscretiseOptions, Seed};
use crate::error::TpiError;
use crate::neighbours::{gradient_embedding, slope_frame};
use crate::planes::Plane;
use crate::progress::{Progress, Stage, Tally};
use crate::surface::Surface;
use crate::tolerance::DEFAULT_PLANE_CURVATURE;

/// The samples of every pattern point, in pattern order.
pub(crate) struct Samples {
    /// Parameters in the surface's own domain.
    pub(crate) uv: Vec<[f64; 2]>,
    /// Local geometry; emptied on the convex path, where nothing reads it afterwards.
    pub(crate) geometry: Vec<LocalGeometry>,
    /// (Su, Sv).
    pub(crate) tangents: Vec<[DVec3; 2]>,
    /// Tangent planes.
    pub(crate) planes: Vec<Plane>,
    /// Bounding-box diagonal of the surface points.
    pub(crate) diagonal: f64,
    /// Per point: +1 / -1 convex side, 0 saddle or flat.
    pub(crate) convex_side: Vec<i8>,
    /// Normalised pattern coordinates scaled by the surface's mean extents.
    pub(crate) plane_uv: Vec<[f64; 2]>,
    /// Per point, the principal curvatures k1 <= k2 (zero where planar): with `uv` and the
    /// tangent planes what the seeds reported with the facets are built from at the end
    /// ([`Samples::seeds`]), so that no copy of each point and normal is held meanwhile.
    pub(crate) curvatures: Vec<[f64; 2]>,
    /// The tangent planes, where adjusted planes have replaced `planes` (None: `planes` are
    /// the tangent planes).
    pub(crate) tangent_planes: Option<Vec<Plane>>,
    /// The slope frame's normal N where the surface is convex on one side.
    pub(crate) frame: Option<DVec3>,
    /// The lifted points of the convex path.
    pub(crate) lifted: Option<Vec<[f64; 3]>>,
    /// Their slopes.
    pub(crate) slopes: Option<Vec<[f64; 2]>>,
    /// Flat points.
    pub(crate) diagnostics: Vec<Diagnostic>,
}

/// Samples the surface at every (validated) pattern point, counting each evaluation as an
/// item of [`Stage::Samples`].
pub(crate) fn sample(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    options: &DiscretiseOptions,
    progress: &dyn Progress,
) -> Result<Samples, TpiError> {
    let domain = surface.domain();
    let uv: Vec<[f64; 2]> = pattern
        .iter()
        .map(|&st| domain.from_normalised(st))
        .collect();
    let (mut geometry, tangents): (Vec<LocalGeometry>, Vec<[DVec3; 2]>) = uv
        .par_iter()
        .map_init(
            || Tally::new(progress, Stage::Samples),
            |tally, &[u, v]| {
                tally.add(1);
                let d = surface.evaluate(u, v);
                (LocalGeometry::from_derivatives(&d), [d.su, d.sv])
            },
        )
        .unzip();
    if let Some(bad) = geometry
        .iter()
        .position(|g| !(g.point.is_finite() && g.normal.is_finite()))
    {
        return Err(TpiError::NonFinite {
            field: format!("surface point at pattern point {bad}"),
            value: f64::NAN,
        });
    }
    let planes: Vec<Plane> = geometry.iter().map(LocalGeometry::tangent_plane).collect();
    let diagonal = bounding_diagonal(geometry.iter().map(|g| g.point)).max(f64::MIN_POSITIVE);
    let mut diagnostics = Vec::new();
    let convex_side = classify_curvature(&mut geometry, diagonal, options, &mut diagnostics);
    let plane_uv = scaled_parameters(pattern, &geometry, &domain);
    let curvatures: Vec<[f64; 2]> = geometry.iter().map(|g| [g.k1, g.k2]).collect();
    let frame = if options.envelope_repair && convex_side.iter().all(|&s| s != 0) {
        slope_frame(surface)
    } else {
        None
    };
    let lifted = gradient_embedding(&planes, &convex_side, frame);
    let slopes: Option<Vec<[f64; 2]>> = lifted
        .as_ref()
        .map(|l| l.iter().map(|p| [p[0], p[1]]).collect());
    // Only curvature compensation (the mixed path) reads the local geometry from here on.
    let geometry = if slopes.is_some() {
        Vec::new()
    } else {
        geometry
    };
    Ok(Samples {
        uv,
        geometry,
        tangents,
        planes,
        diagonal,
        convex_side,
        plane_uv,
        curvatures,
        tangent_planes: None,
        frame,
        lifted,
        slopes,
        diagnostics,
    })
}

impl Samples {
    /// The seeds reported with the facets: each point's parameters, surface point, unit normal
    /// (those of its tangent plane) and principal curvatures.
    pub(crate) fn seeds(&self) -> Vec<Seed> {
        let tangent = self.tangent_planes.as_ref().unwrap_or(&self.planes);
        self.uv
            .iter()
            .zip(tangent)
            .zip(&self.curvatures)
            .map(|((&uv, plane), &curvatures)| Seed {
                uv,
                point: plane.point,
                normal: plane.normal,
                curvatures,
            })
            .collect()
    }
}

/// The points' axis-aligned bounding box (min, max corners).
pub(crate) fn bounding_box(points: impl Iterator<Item = DVec3>) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in points {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    (lo, hi)
}

/// Length of the diagonal of the points' axis-aligned bounding box.
pub(crate) fn bounding_diagonal(points: impl Iterator<Item = DVec3>) -> f64 {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in points {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    if lo.is_finite() && hi.is_finite() {
        (hi - lo).length()
    } else {
        0.0
    }
}

/// Per point: +1/-1 where strictly convex (the side of the centres of curvature), 0 where
/// saddle-shaped or flat. Flat points get a diagnostic. Planar points get zero curvatures, so
/// that rounding noise does not steer the neighbour metric: the triangulation of a flat
/// region is then the Delaunay triangulation in the surface's own metric, and its facets the
/// Voronoi cells of their seeds ([`crate::planes::meeting_point`]).
fn classify_curvature(
    geometry: &mut [LocalGeometry],
    diagonal: f64,
    options: &DiscretiseOptions,
    diagnostics: &mut Vec<Diagnostic>,
) -> Vec<i8> {
    let mut sides = Vec::with_capacity(geometry.len());
    for (i, g) in geometry.iter_mut().enumerate() {
        let (side, is_planar, is_flat) = curvature_class(g, diagonal, options);
        if is_flat {
            diagnostics.push(Diagnostic::FlatPoint {
                point: i as u32,
                gaussian_curvature: g.k1 * g.k2,
            });
        }
        if is_planar {
            g.k1 = 0.0;
            g.k2 = 0.0;
        }
        sides.push(side);
    }
    sides
}

/// One point's class: (convex side or 0, planar, flat), see [`classify_curvature`].
pub(crate) fn curvature_class(
    g: &LocalGeometry,
    diagonal: f64,
    options: &DiscretiseOptions,
) -> (i8, bool, bool) {
    let largest = g.k1.abs().max(g.k2.abs());
    let gaussian = g.k1 * g.k2;
    let is_planar = largest * diagonal <= DEFAULT_PLANE_CURVATURE;
    let is_flat = is_planar || gaussian.abs() <= options.flat_tolerance * largest * largest;
    let side = if !is_flat && gaussian > 0.0 {
        if g.k1 > 0.0 {
            1
        } else {
            -1
        }
    } else {
        0
    };
    (side, is_planar, is_flat)
}

/// Normalised pattern coordinates scaled by the surface's mean extent in u and v, so that
/// the candidate triangulation sees roughly isotropic distances.
fn scaled_parameters(
    pattern: &[[f64; 2]],
    geometry: &[LocalGeometry],
    domain: &crate::surface::Domain,
) -> Vec<[f64; 2]> {
    let n = geometry.len() as f64;
    let mean_su = geometry.iter().map(|g| g.first_form[0].sqrt()).sum::<f64>() / n;
    let mean_sv = geometry.iter().map(|g| g.first_form[2].sqrt()).sum::<f64>() / n;
    let mut su = mean_su * domain.u.length();
    let mut sv = mean_sv * domain.v.length();
    if !(su > 0.0 && su.is_finite() && sv > 0.0 && sv.is_finite()) {
        su = 1.0;
        sv = 1.0;
    }
    let (su, sv) = (su / su.max(sv), sv / su.max(sv));
    pattern.iter().map(|&[s, t]| [s * su, t * sv]).collect()
}
