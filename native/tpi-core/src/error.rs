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
    #[error("{field} is not a finite number ({})", Num(*value))]
    NonFinite {
        /// Path of the offending number.
        field: String,
        /// The value found.
        value: f64,
    },
    /// A scalar parameter is out of its valid range (for example a radius <= 0).
    #[error("{field} = {} is invalid: {reason}", Num(*value))]
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
    #[error("knots_{direction}[{index}] = {} is smaller than knots_{direction}[{}] = {}; knots must not decrease", Num(*value), index - 1, Num(*previous))]
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
        "knots_{direction}[{index}] = {} has multiplicity {multiplicity} > degree {degree}", Num(*value)
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
    #[error("the {direction} domain [{}, {}] is empty", Num(*min), Num(*max))]
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
    #[error("weights[{index}] = {} must be > 0", Num(*value))]
    NonPositiveWeight {
        /// Index of the weight (point (i, j) is at i * nv + j).
        index: usize,
        /// The weight found.
        value: f64,
    },
    /// A parameter pair lies outside the surface's domain.
    #[error("(u, v) = ({}, {}) lies outside the domain [{}, {}] x [{}, {}]", Num(*u), Num(*v), Num(domain.u.min), Num(domain.u.max), Num(domain.v.min), Num(domain.v.max))]
    OutOfDomain {
        /// u found.
        u: f64,
        /// v found.
        v: f64,
        /// The surface's domain.
        domain: Domain,
    },
    /// A pattern point is NaN/infinite or lies outside [0, 1]^2.
    #[error("pattern point {index} = ({}, {}) is not inside [0, 1]^2", Num(*s), Num(*t))]
    PatternPointOutOfRange {
        /// Index in the pattern.
        index: usize,
        /// Normalised u.
        s: f64,
        /// Normalised v.
        t: f64,
    },
    /// Two pattern points coincide (or lie closer than the duplicate tolerance).
    #[error("pattern point {index} duplicates pattern point {duplicate_of} (distance {} in normalised uv)", Num(*distance))]
    DuplicatePatternPoint {
        /// The later point.
        index: usize,
        /// The earlier point it coincides with.
        duplicate_of: usize,
        /// Their distance in normalised uv.
        distance: f64,
    },
    /// Two pattern points map to the same surface point: across the seam of a closed surface
    /// (u = 0 and u = 1), or on a pole. Their tangent planes coincide, and on a closed
    /// surface only one of them can have a facet.
    #[error("pattern point {index} lies on the same surface point as pattern point {duplicate_of} ({place})")]
    SameSurfacePoint {
        /// The later point.
        index: usize,
        /// The earlier point.
        duplicate_of: usize,
        /// Where: "across the seam" or "on a pole".
        place: String,
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
    #[error(
        "invalid pattern generator `{}`: {}",
        bounded(spec, QUOTE_LIMIT),
        bound_message(reason)
    )]
    InvalidGenerator {
        /// The specification given.
        spec: String,
        /// What is wrong and what is expected.
        reason: String,
    },
    /// A surface-aware pattern spec ([`crate::SurfacePatternSpec`]) is malformed: `part` is
    /// the piece of the spec that is wrong (e.g. `relax:abc`, `fit:-1`, `@grain.json`).
    #[error(
        "invalid pattern spec: `{}`: {}",
        bounded(part, QUOTE_LIMIT),
        bound_message(reason)
    )]
    InvalidPatternSpec {
        /// The offending piece of the spec.
        part: String,
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
    /// A number of a NURBS surface beyond what evaluation can represent: a control point
    /// coordinate, a knot or a weight (or the weights' ratio) whose use in evaluation would
    /// overflow or underflow to a non-finite or meaningless result. (Analytic surfaces have
    /// their own bound, [`crate::MAX_ANALYTIC_MAGNITUDE`], reported as `InvalidParameter`.) Scale the model (or the
    /// knots) into range; the bounds are [`MAX_COORDINATE`] and [`MAX_WEIGHT_RATIO`].
    #[error("{field} = {} is out of bounds: {requirement} ({reason})", Num(*value))]
    OutOfBounds {
        /// The offending number, e.g. `points[12][0] (control point u 3, v 0)`.
        field: String,
        /// The value found.
        value: f64,
        /// The bound it breaks, e.g. `|x| <= 1e15`.
        requirement: String,
        /// Why the bound exists and what to do.
        reason: String,
    },
    /// A surface's trim is malformed (see [`crate::Trim::validate`]).
    #[error("{item}: {}", bound_message(reason))]
    InvalidTrim {
        /// The offending loop or point, e.g. `trim.holes[1]` or `trim.outer[17]`.
        item: String,
        /// What is wrong.
        reason: String,
    },
    /// The run cannot honour the surface's trim on this path (it is never ignored).
    #[error(
        "this trimmed surface cannot be discretised with its trim (it is never ignored): {reason}"
    )]
    TrimUnsupported {
        /// Why.
        reason: String,
    },
    /// A polysurface's faces cannot be laid out as one surface (see
    /// [`crate::Polysurface::new`]).
    #[error("{item}: {}", bound_message(reason))]
    InvalidPolysurface {
        /// The offending face, e.g. `faces[3]`, or `faces` for the whole layout.
        item: String,
        /// What is wrong and what is supported.
        reason: String,
    },
    /// The caller's progress observer asked the run to stop ([`crate::Progress::cancelled`]).
    /// Nothing of the run is kept: no result, and no state changed anywhere.
    #[error("cancelled by the caller ({stage} stage)")]
    Cancelled {
        /// The stage the run had reached, as in [`crate::Stage::name`] (`samples` when it had
        /// not started).
        stage: String,
    },
    /// Malformed input document (JSON syntax or structure).
    #[error(
        "{}: line {line}, column {column}: {}",
        bounded(context, QUOTE_LIMIT),
        bound_message(message)
    )]
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

/// The largest magnitude accepted for a NURBS control point coordinate or knot (1e15 model
/// units: coordinates, their squares and the products that
/// curvature takes stay far from overflow, and a coordinate still resolves 0.1 units).
pub const MAX_COORDINATE: f64 = 1e15;
/// The largest ratio of the largest weight to the smallest accepted: at a clamped corner
/// the derivatives grow with this ratio and their products with its square (a weight of
/// 1e-300 beside weights of 1 made every derivative there overflow).
pub const MAX_WEIGHT_RATIO: f64 = 1e6;
/// The smallest length accepted for a NURBS domain in each direction (the knots' last
/// minus first value in use). Derivatives grow as the domain's inverse, their products
/// (the first fundamental form) as its fourth power: knots of a dome scaled by 1e-80 made
/// them overflow, and the surface was called developable. With |knot| <= [`MAX_COORDINATE`]
/// the domain's length lies within 1e+-15, so these products stay within about 1e+-120.
pub const MIN_KNOT_DOMAIN: f64 = 1e-15;
/// The smallest bounding-box diagonal accepted for a NURBS control net. A net smaller (or a
/// single point repeated) has derivatives whose products underflow to zero: a dome scaled
/// by 1e-100 had every normal vanish, and the surface was called developable.
pub const MIN_NET_EXTENT: f64 = 1e-15;

/// Checks `|value| <= MAX_COORDINATE`, naming `field` otherwise.
pub(crate) fn check_magnitude(field: impl FnOnce() -> String, value: f64) -> Result<f64, TpiError> {
    if value.abs() <= MAX_COORDINATE {
        Ok(value)
    } else {
        Err(TpiError::OutOfBounds {
            field: field(),
            value,
            requirement: format!("|value| <= {}", Num(MAX_COORDINATE)),
            reason: "evaluation would overflow; scale the model into range".to_string(),
        })
    }
}

/// A number as a message shows it: the shortest text that reads back as the same f64, in
/// decimal for 1e-5 <= |x| < 1e15 and in exponent form otherwise (so 5e-324 prints as
/// `5e-324`, not as a 324-digit decimal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        let a = x.abs();
        if x == 0.0 || !x.is_finite() || (1e-5..1e15).contains(&a) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// How many characters of an offending value a message quotes at most.
pub const QUOTE_LIMIT: usize = 80;
/// The longest message, in characters, that [`bound_message`] lets through.
pub const MESSAGE_LIMIT: usize = 480;

/// `text` cut to at most `limit` characters (for a limit of at least 30 or so): the first
/// ones, then `...` and the length of the whole (`aaaa... (52428800 characters)`).
pub fn bounded(text: &str, limit: usize) -> std::borrow::Cow<'_, str> {
    let count = text.chars().count();
    if count <= limit {
        return std::borrow::Cow::Borrowed(text);
    }
    // The suffix counts against the limit: the result never exceeds it.
    let suffix = format!("... ({count} characters)");
    let keep = limit.saturating_sub(suffix.len());
    let head: String = text.chars().take(keep).collect();
    std::borrow::Cow::Owned(format!("{head}{suffix}"))
}

/// A message with every quoted part (between `"` or between backticks) longer than
/// [`QUOTE_LIMIT`] characters shortened, and the whole cut to [`MESSAGE_LIMIT`] characters:
/// a 50 MB string in an input file gives a message of a few hundred characters, not of
/// 50 MB. Messages of the core, the command line and the C ABI all pass through it.
pub fn bound_message(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(MESSAGE_LIMIT + 64));
    let mut rest = message;
    while let Some(open) = rest.find(['"', '`']) {
        let quote = rest.as_bytes()[open] as char;
        out.push_str(&rest[..=open]);
        let after = &rest[open + 1..];
        match after.find(quote) {
            Some(close) => {
                out.push_str(&bounded(&after[..close], QUOTE_LIMIT));
                out.push(quote);
                rest = &after[close + 1..];
            }
            None => {
                out.push_str(&bounded(after, QUOTE_LIMIT));
                rest = "";
            }
        }
        if out.chars().count() > MESSAGE_LIMIT * 2 {
            break;
        }
    }
    out.push_str(rest);
    bounded(&out, MESSAGE_LIMIT).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_print_short_and_round_trip() {
        for (x, text) in [
            (5e-324, "5e-324"),
            (1e308, "1e308"),
            (0.1, "0.1"),
            (-2.0, "-2"),
            (0.0, "0"),
            (1e15, "1e15"),
            (123456.5, "123456.5"),
        ] {
            assert_eq!(Num(x).to_string(), text);
            assert_eq!(text.parse::<f64>(), Ok(x));
        }
        let e = TpiError::NonPositiveWeight {
            index: 0,
            value: -5e-324,
        };
        assert_eq!(e.to_string(), "weights[0] = -5e-324 must be > 0");
    }

    /// Found by the surface_json fuzz target (fuzz/, issue 14): cutting a message to
    /// MESSAGE_LIMIT appended the length after the limit, so the result was longer than it.
    #[test]
    fn fuzz_regression_bounded_never_exceeds_its_limit() {
        let text = format!(
            "unknown variant `{}`, expected one of `nurbs`",
            "z".repeat(500)
        );
        for limit in [30, QUOTE_LIMIT, MESSAGE_LIMIT] {
            assert!(bounded(&text, limit).chars().count() <= limit);
        }
        let json = format!("{{\"type\" :\"pected `,8{}`]\"}}", "z/7 ".repeat(200));
        let e = crate::SurfaceSpec::from_json(&json, "fuzz.json").unwrap_err();
        assert!(bound_message(&e.to_string()).chars().count() <= MESSAGE_LIMIT);
        assert!(e.to_string().len() < 1024, "{e}");
    }

    /// Found by the pattern_input fuzz target (fuzz/, issue 14): a 27 kB text read as a
    /// generator spec gave a 27 kB message, the reason quoting the whole unknown kind.
    #[test]
    fn fuzz_regression_long_generator_reason_is_bounded() {
        let spec = format!("h~x\"y\"x   $ {}", "R".repeat(27_000));
        let e = crate::Generator::parse(&spec).unwrap_err();
        assert!(e.to_string().len() < 1024, "{}", e.to_string().len());
        let spec = format!("grid:{}x3", "9".repeat(27_000));
        let e = crate::Generator::parse(&spec).unwrap_err();
        assert!(e.to_string().len() < 1024, "{}", e.to_string().len());
    }

    #[test]
    fn long_quoted_values_are_cut() {
        let long = "x".repeat(1_000_000);
        let m = bound_message(&format!("invalid type: string \"{long}\", expected f64"));
        assert!(m.len() < 200, "{}", m.len());
        assert!(m.starts_with("invalid type: string \"xxx"), "{m}");
        assert!(
            m.contains("... (1000000 characters)\", expected f64"),
            "{m}"
        );
        let m = bound_message(&format!("unknown field `{long}`"));
        assert!(m.len() < 200 && m.ends_with("characters)`"), "{m}");
        // Short messages pass unchanged; a message of many short quotes is still capped.
        assert_eq!(bound_message("unknown field `c`"), "unknown field `c`");
        let many = "`a` ".repeat(100_000);
        assert!(bound_message(&many).chars().count() <= MESSAGE_LIMIT);
    }
}
