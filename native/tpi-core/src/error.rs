//! The one error type of the core. Every variant names the offending item (which knot, which
//! point index, which field) so that a designer can find and fix it.

use std::fmt;

use crate::surface::Domain;

/// A parameter direction of a surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Direction {
    /// The u direction (first index of the control net).
    U,
    /// The v direction (second index of the control net).
    V,
}

impl fmt::Display for Direction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Direction::U => "u",
            Direction::V => "v",
        })
    }
}

/// Everything that can be wrong with input to the core.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TpiError {
    /// A number that must be finite is NaN or infinite. `field` is a path such as `points[12][1]`.
    #[error("{field} is not a finite number ({value})")]
    NonFinite {
        /// Path of the offending number.
        field: String,
        /// The value found.
        value: f64,
    },
    /// A scalar parameter is out of its valid range (for example a radius <= 0).
    #[error("{field} = {value} is invalid: {reason}")]
    InvalidParameter {
        /// Name of the parameter.
        field: String,
        /// The value found.
        value: f64,
        /// What the valid range is.
        reason: String,
    },
    /// Degree 0, or degree >= control point count, or degree above the supported maximum.
    #[error("degree in {direction} is {degree} with {count} control points: {reason}")]
    InvalidDegree {
        /// Which direction.
        direction: Direction,
        /// Degree found.
        degree: usize,
        /// Control point count in that direction.
        count: usize,
        /// Why it is rejected.
        reason: String,
    },
    /// The knot vector length fits neither Rhino's convention (count + degree - 1) nor the
    /// textbook one (count + degree + 1).
    #[error("knots_{direction} has {found} knots; with count {count} and degree {degree} expected {rhino} (Rhino convention) or {full} (textbook convention)")]
    KnotCount {
        /// Which direction.
        direction: Direction,
        /// Knots found.
        found: usize,
        /// Control point count.
        count: usize,
        /// Degree.
        degree: usize,
        /// Expected length in Rhino's convention.
        rhino: usize,
        /// Expected length in the textbook convention.
        full: usize,
    },
    /// A knot is smaller than its predecessor.
    #[error("knots_{direction}[{index}] = {value} is smaller than knots_{direction}[{}] = {previous}; knots must not decrease", index - 1)]
    KnotsDecreasing {
        /// Which direction.
        direction: Direction,
        /// Index of the offending knot (in the vector as given).
        index: usize,
        /// The knot before it.
        previous: f64,
        /// The offending knot.
        value: f64,
    },
    /// An interior knot repeats more often than the degree allows (the surface would be discontinuous).
    #[error(
        "knots_{direction}[{index}] = {value} has multiplicity {multiplicity} > degree {degree}"
    )]
    KnotMultiplicity {
        /// Which direction.
        direction: Direction,
        /// Index of the first copy of the knot.
        index: usize,
        /// The knot value.
        value: f64,
        /// How often it occurs.
        multiplicity: usize,
        /// The degree.
        degree: usize,
    },
    /// The knot vector spans an empty domain.
    #[error("the {direction} domain [{min}, {max}] is empty")]
    EmptyDomain {
        /// Which direction.
        direction: Direction,
        /// Start of the domain.
        min: f64,
        /// End of the domain.
        max: f64,
    },
    /// Control point count differs from nu * nv.
    #[error("points has {found} entries, expected count[0] * count[1] = {expected}")]
    PointCount {
        /// Expected number.
        expected: usize,
        /// Number found.
        found: usize,
    },
    /// Weight count differs from nu * nv.
    #[error("weights has {found} entries, expected {expected}")]
    WeightCount {
        /// Expected number.
        expected: usize,
        /// Number found.
        found: usize,
    },
    /// A weight is zero or negative.
    #[error("weights[{index}] = {value} must be > 0")]
    NonPositiveWeight {
        /// Index of the weight (point (i, j) is at i * nv + j).
        index: usize,
        /// The weight found.
        value: f64,
    },
    /// A parameter pair lies outside the surface's domain.
    #[error("(u, v) = ({u}, {v}) lies outside the domain [{}, {}] x [{}, {}]", domain.u.min, domain.u.max, domain.v.min, domain.v.max)]
    OutOfDomain {
        /// u found.
        u: f64,
        /// v found.
        v: f64,
        /// The surface's domain.
        domain: Domain,
    },
    /// A pattern point is NaN/infinite or lies outside [0, 1]^2.
    #[error("pattern point {index} = ({s}, {t}) is not inside [0, 1]^2")]
    PatternPointOutOfRange {
        /// Index in the pattern.
        index: usize,
        /// Normalised u.
        s: f64,
        /// Normalised v.
        t: f64,
    },
    /// Two pattern points coincide (or lie closer than the duplicate tolerance).
    #[error("pattern point {index} duplicates pattern point {duplicate_of} (distance {distance:e} in normalised uv)")]
    DuplicatePatternPoint {
        /// The later point.
        index: usize,
        /// The earlier point it coincides with.
        duplicate_of: usize,
        /// Their distance in normalised uv.
        distance: f64,
    },
    /// Too few pattern points to form a mesh.
    #[error("the pattern has {found} points; at least {needed} are needed")]
    TooFewPatternPoints {
        /// Points found.
        found: usize,
        /// Points needed.
        needed: usize,
    },
    /// All pattern points lie on one line, so no facet can close.
    #[error("all {count} pattern points are collinear")]
    CollinearPattern {
        /// Number of points.
        count: usize,
    },
    /// A pattern generator specification is malformed.
    #[error("invalid pattern generator `{spec}`: {reason}")]
    InvalidGenerator {
        /// The specification given.
        spec: String,
        /// What is wrong and what is expected.
        reason: String,
    },
    /// The surface cannot be discretised by tangent plane intersection at all
    /// (a plane, or developable everywhere).
    #[error("the surface cannot be discretised by tangent plane intersection: {reason}")]
    DegenerateSurface {
        /// Why.
        reason: String,
    },
    /// Malformed input document (JSON syntax or structure).
    #[error("{context}: line {line}, column {column}: {message}")]
    Parse {
        /// What was being read (a file name or "surface").
        context: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
}

/// Checks that `value` is finite, naming `field` otherwise.
pub(crate) fn check_finite(field: impl FnOnce() -> String, value: f64) -> Result<f64, TpiError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(TpiError::NonFinite {
            field: field(),
            value,
        })
    }
}
