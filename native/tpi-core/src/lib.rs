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
//!   -> fabricate  panel solids with mitred joints, cleat slots, flat parts on sheets, files
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod adjusted_planes;
mod align;
mod analytic;
pub mod benchmark;
mod boundary;
mod closed;
mod density;
mod diagnostics;
mod diffgeo;
mod discretise;
mod error;
mod fabricate;
mod facets;
mod fit;
mod flat;
mod ghosts;
mod hull;
mod live;
mod mesh;
mod neighbours;
mod nurbs;
mod pattern;
mod periodic;
mod planes;
mod polysurface;
mod predicates;
mod progress;
mod projection;
mod quality;
mod regular;
mod relax;
mod rulings;
mod samples;
mod sanity;
mod sizing;
mod spec;
mod structure;
mod surface;
mod surface_pattern;
pub mod tolerance;
mod triangulation;
mod trim;
mod units;
mod validity_flips;

pub use align::{
    aligned_pattern, AlignField, DirectionField, Lattice, ALIGN_NODES, ALIGN_SMOOTHING_SWEEPS,
    MAX_ALIGN_ANISOTROPY, MAX_DIRECTION_NODES,
};
pub use analytic::{AnalyticKind, AnalyticSurface};
pub use closed::{surface_layout, SurfaceLayout};
pub use density::{density_pattern, DensitySpec, DensityTerm, GreyImage, DENSITY_NODES};
pub use diagnostics::Diagnostic;
pub use diffgeo::LocalGeometry;
pub use discretise::{
    discretise, discretise_with_progress, validate_pattern, Discretisation, DiscretiseOptions,
    MeshTopology, PlaneAdjustment, PlaneMode, Seed, Timings,
};
pub use error::{
    bound_message, bounded, Direction, Num, TpiError, MAX_COORDINATE, MAX_WEIGHT_RATIO,
    MESSAGE_LIMIT, MIN_KNOT_DOMAIN, MIN_NET_EXTENT, QUOTE_LIMIT,
};
pub use fabricate::{
    fabricate, Cleat, FabricateOptions, Fabrication, FabricationDiagnostic, FabricationError,
    Panel, PanelSide, Placement, Polyhedron, Sheet, Side, Slot, SlotPlan, ToolpathOptions, Units,
    MAX_SLOTS_PER_EDGE,
};
pub use facets::VertexKind;
pub use fit::{
    fit_pattern, fit_pattern_with_progress, hex_baseline, vertex_deviations, FittedPattern,
    HexBaseline, FIT_ADAPTIVE_POINTS, FIT_LLOYD_ITERATIONS, FIT_MAX_STEP, FIT_POISSON_RADIUS,
    FIT_REFINE_PASSES, FIT_ROUNDS, FIT_SADDLE_ROW_DENSITY, FIT_STALLED_PASSES, FIT_TARGET_RATIO,
    FIT_WALL_INSET, FIT_WALL_SPACING, HEX_BASELINE_SEARCH_FACTOR, MAX_FIT_POINTS, MAX_HEX_COLUMNS,
    MIN_FIT_POINTS,
};
pub use live::{LiveChanges, LiveStats, LiveSurface};
pub use nurbs::{NurbsSpec, NurbsSurface};
pub use pattern::{
    Generator, GridSize, Pattern, SplitMix64, DEFAULT_JITTER_AMOUNT, MAX_GENERATED_POINTS,
};
pub use polysurface::{Polysurface, MAX_POLYSURFACE_FACES};
pub use progress::{NoProgress, Progress, Stage, PROGRESS_CHUNK};
pub use quality::{
    QualityReport, FLAG_DIAGNOSTIC, FLAG_FAR_VERTEX, FLAG_NON_CONVEX, FLAG_NON_SIMPLE, FLAG_OPEN,
    FLAG_OVERLAP, INVALID_FLAGS,
};
pub use relax::{relax, relax_with_progress, MAX_RELAX_ITERATIONS};
pub use rulings::ruling_direction;
pub use sanity::SanityError;
pub use spec::{sampled_bounding_box, SurfaceModel, SurfaceSpec};
pub use surface::{Domain, Interval, Surface, SurfaceDerivatives};
pub use surface_pattern::{aligned_lattice, FitOutcome, SurfacePattern, SurfacePatternSpec};
pub use trim::Trim;
pub use units::{units_label, UnknownUnits};
// The tolerances a caller sets or checks against, also at the root.
pub use tolerance::{
    DEFAULT_FAR_VERTEX_FACTOR, DEFAULT_FLAT_TOLERANCE, DEFAULT_PLANE_CURVATURE,
    DEFAULT_WELD_TOLERANCE, MAX_ANALYTIC_MAGNITUDE, MIN_ANALYTIC_LENGTH, MIN_POISSON_RADIUS,
};
