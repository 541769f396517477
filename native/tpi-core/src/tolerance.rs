//! Tolerances of the core, each a named, documented constant. Lengths are relative to the
//! bounding-box diagonal of the input unless stated otherwise.

/// Two pattern points closer than this in normalised uv ([0, 1]^2) are duplicates.
pub const DUPLICATE_UV_TOLERANCE: f64 = 1e-9;

/// Principal curvatures whose difference is below this fraction of their magnitude are
/// treated as equal (an umbilic): the principal frame is then Su-aligned.
pub const UMBILIC_RELATIVE_TOLERANCE: f64 = 1e-12;

/// Largest NURBS degree evaluated (fixed-size buffers avoid per-call allocation).
pub const MAX_NURBS_DEGREE: usize = 15;

/// [`crate::Discretisation::sanity_check`]: a facet vertex may lie this far (relative to the
/// bounding-box diagonal of the vertices) from its seed's tangent plane. The vertices are
/// computed in that plane, so this only absorbs rounding.
pub const SANITY_PLANARITY_TOLERANCE: f64 = 1e-9;

/// On the convex path, adjacent facet vertices closer than this (relative to the bounding-box
/// diagonal) are tested for an edge reversed by rounding (the weld pass of the facet stage)
/// and welded when it is. Rounding moves a vertex by far less (about 1e-16 times the
/// coordinates times the condition of its three planes); the bound only spares the test on
/// the ordinary edges.
pub const REVERSAL_CHECK_TOLERANCE: f64 = 1e-6;
