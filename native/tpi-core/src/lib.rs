//! # tpi-core: planar-facet discretisation of free-form surfaces by tangent plane intersection
//!
//! After Manahl and Stavric, "Ornamental Discretisation of Free-form Surfaces". Pattern points
//! in the unit square are mapped onto a surface's parameter domain; each point's tangent plane
//! is intersected with the tangent planes of its true neighbours, so that every facet is exactly
//! planar and three facets meet at most vertices.
//!
//! The pipeline runs in one direction:
//!
//! ```text
//! surface + pattern (uv in [0,1]^2)
//!   -> samples    point, normal, principal frame and curvatures per pattern point
//!   -> neighbours uv Delaunay candidates, curvature compensation, one consistent dual triangulation
//!   -> facets     one vertex per dual triangle: the meeting point of three tangent planes
//!   -> mesh       shared vertices, boundary closed on the surface's boundary
//!   -> report     planarity, deviation, validity flags, diagnostics
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod analytic;
pub mod benchmark;
pub mod diagnostics;
pub mod diffgeo;
pub mod discretise;
pub mod error;
pub mod facets;
mod ghosts;
pub mod live;
pub mod neighbours;
pub mod nurbs;
pub mod pattern;
pub mod planes;
mod predicates;
pub mod projection;
pub mod quality;
mod samples;
pub mod sanity;
pub mod spec;
pub mod surface;
pub mod tolerance;
pub mod triangulation;
pub mod validity_flips;

pub use analytic::{AnalyticKind, AnalyticSurface};
pub use diagnostics::Diagnostic;
pub use diffgeo::LocalGeometry;
pub use discretise::{
    discretise, validate_pattern, Discretisation, DiscretiseOptions, Seed, Timings,
};
pub use error::{Direction, TpiError};
pub use live::{LiveStats, LiveSurface};
pub use nurbs::{NurbsSpec, NurbsSurface};
pub use pattern::{Generator, GridSize, Pattern};
pub use quality::QualityReport;
pub use sanity::SanityError;
pub use spec::{SurfaceModel, SurfaceSpec};
pub use surface::{Domain, Interval, Surface, SurfaceDerivatives};
