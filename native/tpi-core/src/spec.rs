//! The surface file: a JSON object tagged by `"type"` (docs/formats.md).
//!
//! ```json
//! {"type": "elliptic_paraboloid", "a": 1.0, "b": 0.1, "x": [-1, 1], "y": [-1, 1]}
//! {"type": "nurbs", "degree": [3, 3], "count": [4, 4], "knots_u": [...], "knots_v": [...],
//!  "points": [[x, y, z], ...], "weights": [...]}
//! ```
//!
//! [`SurfaceSpec`] is the record as read and written (no validation beyond JSON structure;
//! unknown types and unknown fields are rejected). [`SurfaceSpec::build`] validates it into a
//! [`SurfaceModel`], the one surface type the rest of the pipeline takes, which evaluates by
//! dispatch to the NURBS or analytic implementation and turns back into its record with
//! [`SurfaceModel::to_spec`].
//!
//! Analytic records (all coordinates in model units, u = x, v = y):
//!
//! | type | fields | height |
//! |------|--------|--------|
//! | `elliptic_paraboloid` | `a`, `b`, `x`, `y` | z = a x^2 + b y^2 |
//! | `sphere_cap` | `radius`, `x`, `y` | z = sqrt(radius^2 - x^2 - y^2) |
//! | `ellipsoid_cap` | `a`, `b`, `c`, `x`, `y` | z = c sqrt(1 - x^2/a^2 - y^2/b^2) |
//! | `hyperbolic_paraboloid` | `a`, `b`, `x`, `y` | z = a x^2 - b y^2 |
//! | `egg_crate` | `amplitude`, `x`, `y` | z = amplitude sin(x) sin(y) |
//! | `cylinder` | `radius`, `x`, `y` | z = sqrt(radius^2 - x^2) |
//! | `plane` | `p`, `q`, `c0`, `x`, `y` | z = p x + q y + c0 |
//!
//! `x` and `y` are `[min, max]` pairs giving the rectangle (the parameter domain).
//!
//! Every record may have `"units"` (`"mm"`, `"Millimeters"`, ..., see [`Units::from_name`]):
//! the model's length units, carried to every output; absent, the model is unitless.

use glam::DVec3;
use serde::de::{MapAccess, Visitor};
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;

use crate::analytic::{AnalyticKind, AnalyticSurface};
use crate::error::TpiError;
use crate::nurbs::{NurbsSpec, NurbsSurface};
use crate::polysurface::Polysurface;
use crate::surface::{Domain, Surface, SurfaceDerivatives};
use crate::trim::Trim;
use crate::units::Units;

/// A surface record as stored in a surface file, tagged by `"type"` (snake_case).
///
/// Unknown `"type"` values and unknown fields are rejected when reading.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum SurfaceSpec {
    /// A NURBS surface (the record of issue 2, see [`NurbsSpec`]).
    Nurbs(NurbsSpec),
    /// z = a x^2 + b y^2, a and b non-zero with the same sign.
    EllipticParaboloid {
        /// Coefficient of x^2.
        a: f64,
        /// Coefficient of y^2.
        b: f64,
        /// x range [min, max] (u domain).
        x: [f64; 2],
        /// y range [min, max] (v domain).
        y: [f64; 2],
        /// Length units (`"units"`, see [`Units::from_name`]); absent = unitless.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        units: Option<Units>,
        /// The trim (closed loops in (u, v)); None: the whole rectangle.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        trim: Option<Trim>,
    },
    /// z = sqrt(radius^2 - x^2 - y^2), rectangle strictly inside the disc.
    SphereCap {
        /// Sphere radius > 0.
        radius: f64,
        /// x range [min, max] (u domain).
        x: [f64; 2],
        /// y range [min, max] (v domain).
        y: [f64; 2],
        /// Length units (`"units"`, see [`Units::from_name`]); absent = unitless.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        units: Option<Units>,
        /// The trim (closed loops in (u, v)); None: the whole rectangle.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        trim: Option<Trim>,
    },
    /// z = c sqrt(1 - x^2/a^2 - y^2/b^2), rectangle strictly inside the ellipse.
    EllipsoidCap {
        /// Semi-axis along x, > 0.
        a: f64,
        /// Semi-axis along y, > 0.
        b: f64,
        /// Semi-axis along z, > 0.
        c: f64,
        /// x range [min, max] (u domain).
        x: [f64; 2],
        /// y range [min, max] (v domain).
        y: [f64; 2],
        /// Length units (`"units"`, see [`Units::from_name`]); absent = unitless.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        units: Option<Units>,
        /// The trim (closed loops in (u, v)); None: the whole rectangle.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        trim: Option<Trim>,
    },
    /// z = a x^2 - b y^2, a and b non-zero with the same sign.
    HyperbolicParaboloid {
        /// Coefficient of x^2.
        a: f64,
        /// Coefficient of -y^2.
        b: f64,
        /// x range [min, max] (u domain).
        x: [f64; 2],
        /// y range [min, max] (v domain).
        y: [f64; 2],
        /// Length units (`"units"`, see [`Units::from_name`]); absent = unitless.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        units: Option<Units>,
        /// The trim (closed loops in (u, v)); None: the whole rectangle.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        trim: Option<Trim>,
    },
    /// z = amplitude sin(x) sin(y), amplitude non-zero.
    EggCrate {
        /// Amplitude.
        amplitude: f64,
        /// x range [min, max] (u domain).
        x: [f64; 2],
        /// y range [min, max] (v domain).
        y: [f64; 2],
        /// Length units (`"units"`, see [`Units::from_name`]); absent = unitless.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        units: Option<Units>,
        /// The trim (closed loops in (u, v)); None: the whole rectangle.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        trim: Option<Trim>,
    },
    /// z = sqrt(radius^2 - x^2), |x| < radius.
    Cylinder {
        /// Cylinder radius > 0.
        radius: f64,
        /// x range [min, max] (u domain).
        x: [f64; 2],
        /// y range [min, max] (v domain).
        y: [f64; 2],
        /// Length units (`"units"`, see [`Units::from_name`]); absent = unitless.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        units: Option<Units>,
        /// The trim (closed loops in (u, v)); None: the whole rectangle.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        trim: Option<Trim>,
    },
    /// z = p x + q y + c0.
    Plane {
        /// Slope in x.
        p: f64,
        /// Slope in y.
        q: f64,
        /// Height at the origin.
        c0: f64,
        /// x range [min, max] (u domain).
        x: [f64; 2],
        /// y range [min, max] (v domain).
        y: [f64; 2],
        /// Length units (`"units"`, see [`Units::from_name`]); absent = unitless.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        units: Option<Units>,
        /// The trim (closed loops in (u, v)); None: the whole rectangle.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        trim: Option<Trim>,
    },
    /// Several untrimmed faces joined along whole sides, discretised as one shell
    /// ([`crate::Polysurface`]): rows and columns of four-sided faces, found from the geometry.
    Polysurface {
        /// The faces, each a record of any other type, untrimmed; without a polysurface
        /// `"units"`, the faces' own units must agree.
        faces: Vec<SurfaceSpec>,
        /// Length units of every face (`"units"`): when given, they replace the faces' own;
        /// absent, the faces' own (all equal) or unitless.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        units: Option<Units>,
    },
}

impl SurfaceSpec {
    /// Reads a surface record from JSON text. `context` names the source (a file name, or
    /// "surface") in the error.
    ///
    /// Errors: [`TpiError::Parse`] with the 1-based line and column (in bytes) of the problem:
    /// malformed JSON, a document that is not an object, a missing, repeated or unknown
    /// `"type"` (the message lists the known types), an unknown field (the message names it
    /// and lists the accepted ones), a missing field, or a value of the wrong kind. The
    /// values themselves are checked by [`SurfaceSpec::build`].
    ///
    /// The record is read by type, not through serde's buffered internally-tagged path, so
    /// that every error carries the exact position of the offending value; the result equals
    /// what `serde_json::from_str::<SurfaceSpec>` gives for valid input.
    pub fn from_json(text: &str, context: &str) -> Result<SurfaceSpec, TpiError> {
        let at = |offset: usize, message: String| {
            let (line, column) = line_column(text, offset);
            TpiError::Parse {
                context: context.to_string(),
                line,
                column,
                message,
            }
        };
        // Syntax first, with serde_json's own positions: the whole document parsed (numbers in
        // range, escapes valid, nesting within serde_json's limit, nothing after the end).
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| parse_error(e, context))?;
        let start = text.len() - text.trim_start().len();
        if !value.is_object() {
            return Err(at(
                start,
                format!(
                    "expected a JSON object with a \"type\" field, found {}",
                    json_kind(&value)
                ),
            ));
        }
        drop(value);
        // The top level's members as slices of the text, whose places in it are the positions
        // of what they hold.
        let members = top_level_members(text).map_err(|e| parse_error(e, context))?;
        // Keys compared after unescaping (`"typ\u0065"` is `type`).
        let is_type =
            |key: &RawValue| serde_json::from_str::<String>(key.get()).is_ok_and(|k| k == "type");
        let tags: Vec<usize> = (0..members.len())
            .filter(|&k| is_type(members[k].0))
            .collect();
        let place = |raw: &RawValue| span_in(text, raw.get());
        let tag = match tags.as_slice() {
            [] => {
                return Err(at(
                    start,
                    format!("missing field `type` (one of {})", type_list()),
                ))
            }
            [tag] => *tag,
            [_, second, ..] => {
                return Err(at(
                    place(members[*second].0).start,
                    "duplicate field `type`".to_string(),
                ))
            }
        };
        let (key, value) = members[tag];
        let Ok(name) = serde_json::from_str::<String>(value.get()) else {
            return Err(at(
                place(value).start,
                format!("`type` must be a string, one of {}", type_list()),
            ));
        };
        // The tag is blanked out with one comma beside it (same length, so every position
        // stays): from its key to the next key, or else from the end of the previous value.
        let member = match (members.get(tag + 1), tag.checked_sub(1)) {
            (Some(next), _) => place(key).start..place(next.0).start,
            (None, Some(previous)) => place(members[previous].1).end..place(value).end,
            (None, None) => place(key).start..place(value).end,
        };
        let mut blanked = text.as_bytes().to_vec();
        for byte in blanked.get_mut(member).into_iter().flatten() {
            if *byte != b'\n' {
                *byte = b' ';
            }
        }
        // The blanked span is all spaces and newlines now, so the bytes stay valid UTF-8; the
        // fallback is never taken.
        let body = String::from_utf8(blanked).unwrap_or_default();
        Ok(match name.as_str() {
            "nurbs" => SurfaceSpec::Nurbs(read(&body, context)?),
            "elliptic_paraboloid" => {
                let r: TwoCoefficients = read(&body, context)?;
                SurfaceSpec::EllipticParaboloid {
                    a: r.a,
                    b: r.b,
                    x: r.x,
                    y: r.y,
                    units: r.units,
                    trim: r.trim,
                }
            }
            "hyperbolic_paraboloid" => {
                let r: TwoCoefficients = read(&body, context)?;
                SurfaceSpec::HyperbolicParaboloid {
                    a: r.a,
                    b: r.b,
                    x: r.x,
                    y: r.y,
                    units: r.units,
                    trim: r.trim,
                }
            }
            "sphere_cap" => {
                let r: Radius = read(&body, context)?;
                SurfaceSpec::SphereCap {
                    radius: r.radius,
                    x: r.x,
                    y: r.y,
                    units: r.units,
                    trim: r.trim,
                }
            }
            "cylinder" => {
                let r: Radius = read(&body, context)?;
                SurfaceSpec::Cylinder {
                    radius: r.radius,
                    x: r.x,
                    y: r.y,
                    units: r.units,
                    trim: r.trim,
                }
            }
            "ellipsoid_cap" => {
                let r: SemiAxes = read(&body, context)?;
                SurfaceSpec::EllipsoidCap {
                    a: r.a,
                    b: r.b,
                    c: r.c,
                    x: r.x,
                    y: r.y,
                    units: r.units,
                    trim: r.trim,
                }
            }
            "egg_crate" => {
                let r: Amplitude = read(&body, context)?;
                SurfaceSpec::EggCrate {
                    amplitude: r.amplitude,
                    x: r.x,
                    y: r.y,
                    units: r.units,
                    trim: r.trim,
                }
            }
            "polysurface" => {
                let r: PolysurfaceRecord = read(&body, context)?;
                SurfaceSpec::Polysurface {
                    faces: r.faces,
                    units: r.units,
                }
            }
            "plane" => {
                let r: PlaneRecord = read(&body, context)?;
                SurfaceSpec::Plane {
                    p: r.p,
                    q: r.q,
                    c0: r.c0,
                    x: r.x,
                    y: r.y,
                    units: r.units,
                    trim: r.trim,
                }
            }
            other => {
                return Err(at(
                    place(value).start,
                    format!(
                        "unknown surface type `{other}`, expected one of {}",
                        type_list()
                    ),
                ))
            }
        })
    }

    /// Every `"type"` tag, in the order of the enum.
    pub const TYPE_NAMES: [&'static str; 9] = [
        "nurbs",
        "elliptic_paraboloid",
        "sphere_cap",
        "ellipsoid_cap",
        "hyperbolic_paraboloid",
        "egg_crate",
        "cylinder",
        "plane",
        "polysurface",
    ];

    /// The `"type"` tag of this record.
    pub fn type_name(&self) -> &'static str {
        match self.parts() {
            Parts::Nurbs(_) => "nurbs",
            Parts::Polysurface(..) => "polysurface",
            Parts::Analytic(kind, _, _) => kind.type_name(),
        }
    }

    /// The record split into NURBS or analytic kind plus rectangle.
    fn parts(&self) -> Parts<'_> {
        let (kind, x, y) = match *self {
            SurfaceSpec::Nurbs(ref n) => return Parts::Nurbs(n),
            SurfaceSpec::Polysurface { ref faces, units } => {
                return Parts::Polysurface(faces, units)
            }
            SurfaceSpec::EllipticParaboloid { a, b, x, y, .. } => {
                (AnalyticKind::EllipticParaboloid { a, b }, x, y)
            }
            SurfaceSpec::SphereCap { radius, x, y, .. } => {
                (AnalyticKind::SphereCap { radius }, x, y)
            }
            SurfaceSpec::EllipsoidCap { a, b, c, x, y, .. } => {
                (AnalyticKind::EllipsoidCap { a, b, c }, x, y)
            }
            SurfaceSpec::HyperbolicParaboloid { a, b, x, y, .. } => {
                (AnalyticKind::HyperbolicParaboloid { a, b }, x, y)
            }
            SurfaceSpec::EggCrate {
                amplitude, x, y, ..
            } => (AnalyticKind::EggCrate { amplitude }, x, y),
            SurfaceSpec::Cylinder { radius, x, y, .. } => (AnalyticKind::Cylinder { radius }, x, y),
            SurfaceSpec::Plane { p, q, c0, x, y, .. } => (AnalyticKind::Plane { p, q, c0 }, x, y),
        };
        Parts::Analytic(kind, x, y)
    }

    /// The record's trim, if any.
    pub fn trim(&self) -> Option<&Trim> {
        match self {
            SurfaceSpec::Nurbs(n) => n.trim.as_ref(),
            SurfaceSpec::Polysurface { .. } => None,
            SurfaceSpec::EllipticParaboloid { trim, .. }
            | SurfaceSpec::SphereCap { trim, .. }
            | SurfaceSpec::EllipsoidCap { trim, .. }
            | SurfaceSpec::HyperbolicParaboloid { trim, .. }
            | SurfaceSpec::EggCrate { trim, .. }
            | SurfaceSpec::Cylinder { trim, .. }
            | SurfaceSpec::Plane { trim, .. } => trim.as_ref(),
        }
    }

    /// The record with its trim replaced (a polysurface has none of its own: unchanged).
    pub fn with_trim(mut self, new: Option<Trim>) -> SurfaceSpec {
        match &mut self {
            SurfaceSpec::Nurbs(n) => n.trim = new,
            SurfaceSpec::Polysurface { .. } => {}
            SurfaceSpec::EllipticParaboloid { trim, .. }
            | SurfaceSpec::SphereCap { trim, .. }
            | SurfaceSpec::EllipsoidCap { trim, .. }
            | SurfaceSpec::HyperbolicParaboloid { trim, .. }
            | SurfaceSpec::EggCrate { trim, .. }
            | SurfaceSpec::Cylinder { trim, .. }
            | SurfaceSpec::Plane { trim, .. } => *trim = new,
        }
        self
    }

    /// Validates the record and builds the surface.
    ///
    /// Errors: the NURBS validation errors of [`NurbsSpec::build`], or the analytic ones of
    /// [`AnalyticSurface::new`], each naming the offending field; then the trim's errors
    /// ([`Trim::validate`]) against the surface's domain.
    pub fn build(&self) -> Result<SurfaceModel, TpiError> {
        let model = match self.parts() {
            Parts::Nurbs(n) => SurfaceModel::Nurbs(n.build()?),
            Parts::Polysurface(faces, units) => {
                let mut built = Vec::with_capacity(faces.len());
                for (k, face) in faces.iter().enumerate() {
                    let face = face.build().map_err(|e| TpiError::InvalidPolysurface {
                        item: format!("faces[{k}]"),
                        reason: e.to_string(),
                    })?;
                    // The polysurface's units, when given, are every face's.
                    built.push(match units {
                        Some(_) => face.with_units(units),
                        None => face,
                    });
                }
                SurfaceModel::Polysurface(Box::new(Polysurface::new(built)?))
            }
            Parts::Analytic(kind, x, y) => {
                SurfaceModel::Analytic(AnalyticSurface::new(kind, x, y)?.with_units(self.units()))
            }
        };
        match self.trim() {
            None => Ok(model),
            Some(trim) => SurfaceModel::trimmed(model, trim.clone()),
        }
    }

    /// The record's length units (`"units"`), `None` when unitless.
    pub fn units(&self) -> Option<Units> {
        match *self {
            SurfaceSpec::Nurbs(ref n) => n.units,
            SurfaceSpec::Polysurface { ref faces, units } => {
                units.or_else(|| faces.first().and_then(SurfaceSpec::units))
            }
            SurfaceSpec::EllipticParaboloid { units, .. }
            | SurfaceSpec::SphereCap { units, .. }
            | SurfaceSpec::EllipsoidCap { units, .. }
            | SurfaceSpec::HyperbolicParaboloid { units, .. }
            | SurfaceSpec::EggCrate { units, .. }
            | SurfaceSpec::Cylinder { units, .. }
            | SurfaceSpec::Plane { units, .. } => units,
        }
    }

    /// The record of an analytic surface (untrimmed).
    pub fn from_analytic(surface: &AnalyticSurface) -> SurfaceSpec {
        let (x, y, units) = (surface.x_range(), surface.y_range(), surface.units());
        let trim = None;
        match surface.kind() {
            AnalyticKind::EllipticParaboloid { a, b } => SurfaceSpec::EllipticParaboloid {
                a,
                b,
                x,
                y,
                units,
                trim,
            },
            AnalyticKind::SphereCap { radius } => SurfaceSpec::SphereCap {
                radius,
                x,
                y,
                units,
                trim,
            },
            AnalyticKind::EllipsoidCap { a, b, c } => SurfaceSpec::EllipsoidCap {
                a,
                b,
                c,
                x,
                y,
                units,
                trim,
            },
            AnalyticKind::HyperbolicParaboloid { a, b } => SurfaceSpec::HyperbolicParaboloid {
                a,
                b,
                x,
                y,
                units,
                trim,
            },
            AnalyticKind::EggCrate { amplitude } => SurfaceSpec::EggCrate {
                amplitude,
                x,
                y,
                units,
                trim,
            },
            AnalyticKind::Cylinder { radius } => SurfaceSpec::Cylinder {
                radius,
                x,
                y,
                units,
                trim,
            },
            AnalyticKind::Plane { p, q, c0 } => SurfaceSpec::Plane {
                p,
                q,
                c0,
                x,
                y,
                units,
                trim,
            },
        }
    }
}

/// A record seen as NURBS or as analytic kind plus rectangle.
enum Parts<'a> {
    Nurbs(&'a NurbsSpec),
    Polysurface(&'a [SurfaceSpec], Option<Units>),
    Analytic(AnalyticKind, [f64; 2], [f64; 2]),
}

/// The analytic records as read by [`SurfaceSpec::from_json`], one struct per field set;
/// the field names must stay those of the [`SurfaceSpec`] variants (a test reads every type
/// both ways).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PolysurfaceRecord {
    faces: Vec<SurfaceSpec>,
    #[serde(default)]
    units: Option<Units>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TwoCoefficients {
    a: f64,
    b: f64,
    x: [f64; 2],
    y: [f64; 2],
    #[serde(default)]
    units: Option<Units>,
    trim: Option<Trim>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Radius {
    radius: f64,
    x: [f64; 2],
    y: [f64; 2],
    #[serde(default)]
    units: Option<Units>,
    trim: Option<Trim>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SemiAxes {
    a: f64,
    b: f64,
    c: f64,
    x: [f64; 2],
    y: [f64; 2],
    #[serde(default)]
    units: Option<Units>,
    trim: Option<Trim>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Amplitude {
    amplitude: f64,
    x: [f64; 2],
    y: [f64; 2],
    #[serde(default)]
    units: Option<Units>,
    trim: Option<Trim>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PlaneRecord {
    p: f64,
    q: f64,
    c0: f64,
    x: [f64; 2],
    y: [f64; 2],
    #[serde(default)]
    units: Option<Units>,
    trim: Option<Trim>,
}

fn json_kind(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Null => "null",
        serde_json::Value::Bool(_) => "a boolean",
        serde_json::Value::Number(_) => "a number",
        serde_json::Value::String(_) => "a string",
        serde_json::Value::Array(_) => "an array",
        serde_json::Value::Object(_) => "an object",
    }
}

fn type_list() -> String {
    SurfaceSpec::TYPE_NAMES
        .iter()
        .map(|t| format!("`{t}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Reads a record from JSON text (a whole document) with the path of the offending value in
/// the message of a wrong value (serde_path_to_error): `points[3][1]: invalid type: string
/// "a", expected f64`, at serde_json's line and column.
pub(crate) fn read<T: serde::de::DeserializeOwned>(
    text: &str,
    context: &str,
) -> Result<T, TpiError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let value: T = serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        let named = path != "."
            && !["unknown field", "missing field", "duplicate field"]
                .iter()
                .any(|kind| inner.to_string().starts_with(kind));
        let mut error = parse_error(inner, context);
        if let TpiError::Parse { message, .. } = &mut error {
            if named {
                *message = format!("{path}: {message}");
            }
        }
        error
    })?;
    de.end().map_err(|e| parse_error(e, context))?;
    Ok(value)
}

/// Maps a serde_json error to [`TpiError::Parse`], keeping its line and column out of the
/// message.
pub(crate) fn parse_error(e: serde_json::Error, context: &str) -> TpiError {
    let message = e.to_string();
    // serde_json appends " at line L column C"; the position is reported separately.
    let message = match message.rfind(" at line ") {
        Some(i) if e.line() > 0 => message[..i].to_string(),
        _ => message,
    };
    // serde_json says only this for both `[1, 2, 3]` read as a pair and text after the end.
    let message = if message == "trailing characters" {
        "trailing characters (an array with more elements than expected, or text after the document)"
            .to_string()
    } else {
        message
    };
    TpiError::Parse {
        context: context.to_string(),
        line: e.line(),
        column: e.column(),
        // serde_json quotes a wrong value whole (a 50 MB string gave a 50 MB message).
        message: crate::error::bound_message(&message),
    }
}

/// 1-based line and column (in bytes, as serde_json counts) of a byte offset.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text.as_bytes()[..offset.min(text.len())];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    (line, before.len() - line_start + 1)
}

/// The members of the top-level object of `text` (a valid JSON object), key and value in
/// order, repeated keys kept, as slices of `text`.
fn top_level_members(text: &str) -> Result<Vec<(&RawValue, &RawValue)>, serde_json::Error> {
    let mut de = serde_json::Deserializer::from_str(text);
    let members = serde::Deserializer::deserialize_map(&mut de, MembersVisitor)?;
    de.end()?;
    Ok(members)
}

struct MembersVisitor;

impl<'de> Visitor<'de> for MembersVisitor {
    type Value = Vec<(&'de RawValue, &'de RawValue)>;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a JSON object")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut members = Vec::new();
        while let Some(member) = map.next_entry::<&'de RawValue, &'de RawValue>()? {
            members.push(member);
        }
        Ok(members)
    }
}

/// The byte range in `text` of `part`, a slice of it (what a borrowed [`RawValue`] is).
fn span_in(text: &str, part: &str) -> std::ops::Range<usize> {
    let start = (part.as_ptr() as usize)
        .saturating_sub(text.as_ptr() as usize)
        .min(text.len());
    start..(start + part.len()).min(text.len())
}

/// A validated surface of any supported kind: what the pipeline samples.
#[derive(Clone, Debug, PartialEq)]
// Built once per run and evaluated millions of times: a box would only add an indirection.
#[allow(clippy::large_enum_variant)]
pub enum SurfaceModel {
    /// A NURBS surface.
    Nurbs(NurbsSurface),
    /// An analytic graph surface.
    Analytic(AnalyticSurface),
    /// Faces laid out as one surface.
    Polysurface(Box<Polysurface>),
    /// A surface with a trim (never itself trimmed).
    Trimmed {
        /// The untrimmed surface.
        surface: Box<SurfaceModel>,
        /// Its trim, validated against its domain.
        trim: Trim,
    },
}

impl SurfaceModel {
    /// The same surface (and trim) with its length units replaced.
    pub fn with_units(self, units: Option<Units>) -> SurfaceModel {
        match self {
            SurfaceModel::Nurbs(n) => SurfaceModel::Nurbs(n.with_units(units)),
            SurfaceModel::Analytic(a) => SurfaceModel::Analytic(a.with_units(units)),
            SurfaceModel::Polysurface(p) => {
                SurfaceModel::Polysurface(Box::new(p.with_units(units)))
            }
            SurfaceModel::Trimmed { surface, trim } => SurfaceModel::Trimmed {
                surface: Box::new(surface.with_units(units)),
                trim,
            },
        }
    }
    /// The record that [`SurfaceSpec::build`] turns back into this surface (NURBS knots in
    /// Rhino's convention).
    pub fn to_spec(&self) -> SurfaceSpec {
        match self {
            SurfaceModel::Nurbs(n) => SurfaceSpec::Nurbs(n.to_spec()),
            SurfaceModel::Analytic(a) => SurfaceSpec::from_analytic(a),
            SurfaceModel::Polysurface(p) => SurfaceSpec::Polysurface {
                faces: p.faces().iter().map(SurfaceModel::to_spec).collect(),
                units: p.units(),
            },
            SurfaceModel::Trimmed { surface, trim } => {
                surface.to_spec().with_trim(Some(trim.clone()))
            }
        }
    }

    /// `surface` trimmed by `trim` (a trimmed surface's trim is replaced).
    ///
    /// Errors: those of [`Trim::validate`] against the surface's domain.
    pub fn trimmed(surface: SurfaceModel, trim: Trim) -> Result<SurfaceModel, TpiError> {
        let surface = match surface {
            SurfaceModel::Trimmed { surface, .. } => *surface,
            other => other,
        };
        trim.validate(&surface.domain())?;
        Ok(SurfaceModel::Trimmed {
            surface: Box::new(surface),
            trim,
        })
    }

    /// The surface without its trim.
    pub fn untrimmed(&self) -> &SurfaceModel {
        match self {
            SurfaceModel::Trimmed { surface, .. } => surface,
            other => other,
        }
    }

    /// Evaluation that rejects (u, v) outside the domain (or non-finite) with
    /// [`TpiError::OutOfDomain`] instead of clamping.
    pub fn evaluate_checked(&self, u: f64, v: f64) -> Result<SurfaceDerivatives, TpiError> {
        self.domain().check(u, v)?;
        Ok(self.evaluate(u, v))
    }
}

impl Surface for SurfaceModel {
    fn domain(&self) -> Domain {
        match self {
            SurfaceModel::Nurbs(n) => n.domain(),
            SurfaceModel::Analytic(a) => a.domain(),
            SurfaceModel::Polysurface(p) => p.domain(),
            SurfaceModel::Trimmed { surface, .. } => surface.domain(),
        }
    }

    fn evaluate(&self, u: f64, v: f64) -> SurfaceDerivatives {
        match self {
            SurfaceModel::Nurbs(n) => n.evaluate(u, v),
            SurfaceModel::Analytic(a) => a.evaluate(u, v),
            SurfaceModel::Polysurface(p) => p.evaluate(u, v),
            SurfaceModel::Trimmed { surface, .. } => surface.evaluate(u, v),
        }
    }

    fn point_at(&self, u: f64, v: f64) -> DVec3 {
        match self {
            SurfaceModel::Nurbs(n) => n.point_at(u, v),
            SurfaceModel::Analytic(a) => a.point_at(u, v),
            SurfaceModel::Polysurface(p) => p.point_at(u, v),
            SurfaceModel::Trimmed { surface, .. } => surface.point_at(u, v),
        }
    }

    fn first_derivatives(&self, u: f64, v: f64) -> [DVec3; 3] {
        match self {
            SurfaceModel::Nurbs(n) => n.first_derivatives(u, v),
            SurfaceModel::Analytic(a) => a.first_derivatives(u, v),
            SurfaceModel::Polysurface(p) => p.first_derivatives(u, v),
            SurfaceModel::Trimmed { surface, .. } => surface.first_derivatives(u, v),
        }
    }

    fn trim(&self) -> Option<&Trim> {
        match self {
            SurfaceModel::Trimmed { trim, .. } => Some(trim),
            _ => None,
        }
    }

    fn units(&self) -> Option<Units> {
        match self {
            SurfaceModel::Nurbs(n) => n.units(),
            SurfaceModel::Analytic(a) => a.units(),
            SurfaceModel::Polysurface(p) => p.units(),
            SurfaceModel::Trimmed { surface, .. } => surface.units(),
        }
    }
}

impl From<AnalyticSurface> for SurfaceModel {
    fn from(s: AnalyticSurface) -> Self {
        SurfaceModel::Analytic(s)
    }
}

impl From<NurbsSurface> for SurfaceModel {
    fn from(s: NurbsSurface) -> Self {
        SurfaceModel::Nurbs(s)
    }
}

/// Axis-aligned bounding box `[min, max]` of the surface points sampled on a regular grid of
/// `samples_per_side` x `samples_per_side` parameters (borders and corners included; at least
/// 2 per side are used). Non-finite points are skipped; a surface with none finite gives
/// `[DVec3::ZERO, DVec3::ZERO]`.
///
/// This is an approximation from inside (the true box can be slightly larger between
/// samples); use it for scale (its diagonal), not for containment.
pub fn sampled_bounding_box<S: Surface + ?Sized>(
    surface: &S,
    samples_per_side: usize,
) -> [DVec3; 2] {
    let n = samples_per_side.max(2);
    let domain = surface.domain();
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for i in 0..n {
        let s = i as f64 / (n - 1) as f64;
        for j in 0..n {
            let t = j as f64 / (n - 1) as f64;
            let [u, v] = domain.from_normalised([s, t]);
            let p = surface.point_at(u, v);
            if p.is_finite() {
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
    }
    if lo.is_finite() && hi.is_finite() {
        [lo, hi]
    } else {
        [DVec3::ZERO, DVec3::ZERO]
    }
}
