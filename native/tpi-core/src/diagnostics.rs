//! Typed diagnostics: what went wrong locally, naming the pattern points affected.

use serde::{Deserialize, Serialize};

/// One local problem found while building the mesh. The rest of the mesh stays valid.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Diagnostic {
    /// Three tangent planes are nearly parallel (flat or developable region): their meeting
    /// point ran away, and a finite stand-in near the three points was used instead, so the
    /// facets of these points are not exact.
    IllConditionedVertex {
        /// The three pattern points.
        points: [u32; 3],
        /// n_i . (n_j x n_k).
        determinant: f64,
        /// Distance of the exact meeting point from the points' centroid (inf if none).
        distance: f64,
    },
    /// Two neighbouring tangent planes at the boundary are parallel, so their common edge
    /// cannot be followed to the surface's boundary.
    ParallelPlanes {
        /// The two pattern points.
        points: [u32; 2],
    },
    /// The common edge of two facets never reaches the surface's boundary.
    BoundaryNotReached {
        /// The two pattern points.
        points: [u32; 2],
    },
    /// A facet could not be closed consistently along the boundary.
    OpenFacet {
        /// The pattern point.
        point: u32,
        /// What went wrong.
        reason: String,
    },
    /// The tangent plane of a facet holding a domain corner is parallel to the corner's normal.
    CornerUnreachable {
        /// The pattern point.
        point: u32,
        /// Corner index (0: (u0, v0), 1: (u1, v0), 2: (u1, v1), 3: (u0, v1)); on a trimmed
        /// surface, the index of the trim point counting the outer loop's points first,
        /// then each hole's.
        corner: u32,
    },
    /// A domain corner was claimed by no facet or by several.
    CornerClaims {
        /// Corner index (as in `CornerUnreachable`).
        corner: u32,
        /// How many facets claimed it.
        claims: u32,
    },
    /// The point has (nearly) zero Gaussian curvature: tangent planes around it are close to
    /// parallel in at least one direction.
    FlatPoint {
        /// The pattern point.
        point: u32,
        /// Its Gaussian curvature.
        gaussian_curvature: f64,
    },
    /// Neighbouring facets whose tangent planes coincide (a flat region, or one ruling of a
    /// developable surface) were separated by the perpendicular bisector of their seeds in
    /// that plane: their Voronoi diagram, the limit of TPI as the curvature vanishes
    /// ([`crate::tolerance::PLANE_COINCIDENCE`]). Their facets are exact; one diagnostic per
    /// discretisation.
    CoincidentPlanes {
        /// How many neighbour pairs were separated so.
        pairs: u32,
    },
    /// The surface is closed in a direction, but it was discretised as an open patch: the
    /// mesh leaves the seam open (a trimmed surface, one closed both ways, or a structure that
    /// did not fold across its seam: `crate::periodic`). One diagnostic per discretisation.
    SeamLeftOpen {
        /// 0: closed in u, 1: closed in v.
        direction: u8,
    },
    /// The surface is developable with its rulings along parameter lines (a cylinder, a cone,
    /// an extrusion): tangent planes of three different rulings never meet near it, so its
    /// facets are strips between the lines where the planes of neighbouring rulings meet,
    /// shared by the seeds of one ruling along their bisectors
    /// ([`crate::tolerance::RULING_TOLERANCE`]). One diagnostic per discretisation.
    RulingStrips {
        /// The parameter along the rulings (0: u, 1: v).
        direction: u8,
        /// Closed across the rulings: the strips close up into an annulus.
        closed: bool,
    },
    /// The boundary or trim cuts this point's facet into several parts (a long strip of a
    /// developable surface across a hole or a notch of a trim, or a saddle's boundary facet
    /// whose edge dips beyond the wall and back): the facet keeps the part around its seed,
    /// and the other parts, which no other facet's plane can cover, are left out of the mesh
    /// as gaps beside the boundary.
    FacetPartsLeftOut {
        /// The pattern point.
        point: u32,
        /// How many parts the trim cut the facet into (at least 2).
        parts: u32,
    },
    /// The mesh is not the surface the run expected (a disc, an annulus, a sphere, a trimmed
    /// disc with its holes): its facets leave a gap, or cover a part twice, that no single
    /// facet shows. Named so that a mesh of valid facets with such a defect is never taken for
    /// a valid mesh. One diagnostic per discretisation.
    UnexpectedTopology {
        /// Euler characteristic V - E + F of the mesh.
        euler: i64,
        /// Boundary loops of the mesh.
        boundary_loops: u32,
        /// The Euler characteristic expected.
        expected_euler: i64,
        /// The boundary loops expected.
        expected_loops: u32,
    },
}

impl Diagnostic {
    /// Renames every pattern point `p` this diagnostic names to `f(p)`.
    pub(crate) fn map_points(&mut self, f: impl Fn(u32) -> u32) {
        match self {
            Diagnostic::IllConditionedVertex { points, .. } => {
                *points = points.map(&f);
            }
            Diagnostic::ParallelPlanes { points } | Diagnostic::BoundaryNotReached { points } => {
                *points = points.map(&f);
            }
            Diagnostic::OpenFacet { point, .. }
            | Diagnostic::CornerUnreachable { point, .. }
            | Diagnostic::FlatPoint { point, .. }
            | Diagnostic::FacetPartsLeftOut { point, .. } => *point = f(*point),
            Diagnostic::CornerClaims { .. }
            | Diagnostic::CoincidentPlanes { .. }
            | Diagnostic::SeamLeftOpen { .. }
            | Diagnostic::RulingStrips { .. }
            | Diagnostic::UnexpectedTopology { .. } => {}
        }
    }

    /// The pattern points this diagnostic concerns.
    pub fn points(&self) -> Vec<u32> {
        match self {
            Diagnostic::IllConditionedVertex { points, .. } => points.to_vec(),
            Diagnostic::ParallelPlanes { points } | Diagnostic::BoundaryNotReached { points } => {
                points.to_vec()
            }
            Diagnostic::OpenFacet { point, .. }
            | Diagnostic::CornerUnreachable { point, .. }
            | Diagnostic::FlatPoint { point, .. }
            | Diagnostic::FacetPartsLeftOut { point, .. } => vec![*point],
            Diagnostic::CornerClaims { .. }
            | Diagnostic::CoincidentPlanes { .. }
            | Diagnostic::SeamLeftOpen { .. }
            | Diagnostic::RulingStrips { .. }
            | Diagnostic::UnexpectedTopology { .. } => Vec::new(),
        }
    }
}

/// Per pattern point (of `count`), whether a diagnostic names it (the report's
/// [`crate::FLAG_DIAGNOSTIC`]).
pub(crate) fn diagnosed_points(diagnostics: &[Diagnostic], count: usize) -> Vec<bool> {
    let mut diagnosed = vec![false; count];
    for d in diagnostics {
        for p in d.points() {
            diagnosed[p as usize] = true;
        }
    }
    diagnosed
}
