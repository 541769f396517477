//! Analytic surfaces with closed-form derivatives, for tests, samples and oracles.
//!
//! Every analytic surface is a graph over a rectangle of the xy-plane: the parameters are
//! u = x and v = y, the domain is the rectangle [x0, x1] x [y0, y1], and
//!
//! ```text
//! S(u, v) = (u, v, f(u, v))
//! Su  = (1, 0, fx)     Sv  = (0, 1, fy)
//! Suu = (0, 0, fxx)    Suv = (0, 0, fxy)    Svv = (0, 0, fyy)
//! n   = Su x Sv / |Su x Sv| = (-fx, -fy, 1) / sqrt(1 + fx^2 + fy^2)    (always +z-ish)
//! ```
//!
//! The height functions and their derivatives, all in closed form:
//!
//! | kind | f | fx, fy | fxx, fxy, fyy |
//! |------|---|--------|---------------|
//! | elliptic paraboloid | a x^2 + b y^2 | 2ax, 2by | 2a, 0, 2b |
//! | hyperbolic paraboloid | a x^2 - b y^2 | 2ax, -2by | 2a, 0, -2b |
//! | sphere cap | w = sqrt(r^2 - x^2 - y^2) | -x/w, -y/w | -(r^2 - y^2)/w^3, -xy/w^3, -(r^2 - x^2)/w^3 |
//! | ellipsoid cap | c s, s = sqrt(1 - x^2/a^2 - y^2/b^2) | -cx/(a^2 s), -cy/(b^2 s) | -c(1 - y^2/b^2)/(a^2 s^3), -cxy/(a^2 b^2 s^3), -c(1 - x^2/a^2)/(b^2 s^3) |
//! | egg-crate | A sin x sin y | A cos x sin y, A sin x cos y | -A sin x sin y, A cos x cos y, -A sin x sin y |
//! | cylinder | w = sqrt(r^2 - x^2) | -x/w, 0 | -r^2/w^3, 0, 0 |
//! | plane | p x + q y + c0 | p, q | 0, 0, 0 |
//!
//! Curvature classes (signs relative to the +z-ish normal; k > 0 where the surface bends
//! towards the normal): elliptic paraboloid K > 0 (a, b > 0 opens upwards, k = 2a, 2b at the
//! apex; a, b < 0 opens downwards); hyperbolic paraboloid K < 0; sphere and ellipsoid caps
//! K > 0 with k < 0 (they bend away from the upward normal; the sphere has k1 = k2 = -1/r
//! everywhere); egg-crate mixed (K > 0 near (pi/2, pi/2), K < 0 near the origin); cylinder
//! K = 0 (k = -1/r across, 0 along the axis y); plane K = H = 0.
//!
//! Validation happens once, at construction ([`AnalyticSurface::new`] and the named
//! constructors): every number must be finite and at most [`MAX_ANALYTIC_MAGNITUDE`] in
//! magnitude, every interval non-empty, radii and semi-axes
//! positive (at least [`MIN_ANALYTIC_LENGTH`]), the rectangle strictly inside the disc / ellipse / strip where the height is a
//! square root, and the coefficients must give the curvature class the name promises
//! (an elliptic paraboloid needs a and b non-zero with the same sign, a hyperbolic paraboloid
//! non-zero a and b with the same sign so that a x^2 - b y^2 is a saddle, an egg-crate a
//! non-zero amplitude). Because the square roots are validated at the rectangle's farthest
//! corner, evaluation inside the domain never produces NaN.
//!
//! Evaluation outside the rectangle is clamped onto it, as for every [`Surface`].

// `!(x > 0.0)` is deliberate in the validation: it rejects NaN as well.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use crate::units::Units;
use glam::DVec3;

use crate::error::{check_finite, Direction, TpiError};
use crate::surface::{Domain, Interval, Surface, SurfaceDerivatives};
use crate::tolerance::{MAX_ANALYTIC_MAGNITUDE, MIN_ANALYTIC_LENGTH};

/// The shape of an analytic surface: the height function z = f(x, y) and its parameters.
///
/// The variant fields carry the same names as the surface file (docs/formats.md).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AnalyticKind {
    /// z = a x^2 + b y^2 with a, b non-zero and of the same sign (K > 0).
    EllipticParaboloid {
        /// Coefficient of x^2.
        a: f64,
        /// Coefficient of y^2.
        b: f64,
    },
    /// z = sqrt(r^2 - x^2 - y^2): the upper half of the sphere of radius r about the origin.
    SphereCap {
        /// Sphere radius r > 0.
        radius: f64,
    },
    /// z = c sqrt(1 - x^2/a^2 - y^2/b^2): the upper half of the ellipsoid with semi-axes a, b, c.
    EllipsoidCap {
        /// Semi-axis along x, > 0.
        a: f64,
        /// Semi-axis along y, > 0.
        b: f64,
        /// Semi-axis along z, > 0.
        c: f64,
    },
    /// z = a x^2 - b y^2 with a, b non-zero and of the same sign (K < 0).
    HyperbolicParaboloid {
        /// Coefficient of x^2.
        a: f64,
        /// Coefficient of -y^2.
        b: f64,
    },
    /// z = A sin(x) sin(y), A != 0: mixed curvature.
    EggCrate {
        /// Amplitude A.
        amplitude: f64,
    },
    /// z = sqrt(r^2 - x^2): the upper half of the cylinder of radius r about the y axis (K = 0).
    Cylinder {
        /// Cylinder radius r > 0.
        radius: f64,
    },
    /// z = p x + q y + c0 (flat).
    Plane {
        /// Slope in x.
        p: f64,
        /// Slope in y.
        q: f64,
        /// Height at the origin.
        c0: f64,
    },
}

impl AnalyticKind {
    /// The surface file's "type" tag of this kind (snake_case).
    pub fn type_name(&self) -> &'static str {
        match self {
            AnalyticKind::EllipticParaboloid { .. } => "elliptic_paraboloid",
            AnalyticKind::SphereCap { .. } => "sphere_cap",
            AnalyticKind::EllipsoidCap { .. } => "ellipsoid_cap",
            AnalyticKind::HyperbolicParaboloid { .. } => "hyperbolic_paraboloid",
            AnalyticKind::EggCrate { .. } => "egg_crate",
            AnalyticKind::Cylinder { .. } => "cylinder",
            AnalyticKind::Plane { .. } => "plane",
        }
    }
}

/// Height f and its partial derivatives at one (x, y).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Height {
    /// f(x, y).
    pub f: f64,
    /// df/dx.
    pub fx: f64,
    /// df/dy.
    pub fy: f64,
    /// d2f/dx2.
    pub fxx: f64,
    /// d2f/dxdy.
    pub fxy: f64,
    /// d2f/dy2.
    pub fyy: f64,
}

/// A validated analytic graph surface S(x, y) = (x, y, f(x, y)) over a rectangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalyticSurface {
    kind: AnalyticKind,
    domain: Domain,
    /// Length units of the model (the surface file's `"units"`), `None` when unitless.
    units: Option<Units>,
}

fn invalid(field: &str, value: f64, reason: impl Into<String>) -> TpiError {
    TpiError::InvalidParameter {
        field: field.to_string(),
        value,
        reason: reason.into(),
    }
}

/// Finite and at most [`MAX_ANALYTIC_MAGNITUDE`] in magnitude.
fn finite(field: &str, value: f64) -> Result<f64, TpiError> {
    check_finite(|| field.to_string(), value)?;
    if value.abs() > MAX_ANALYTIC_MAGNITUDE {
        return Err(invalid(
            field,
            value,
            format!("magnitude must not exceed {MAX_ANALYTIC_MAGNITUDE:e}"),
        ));
    }
    Ok(value)
}

/// A radius or semi-axis: > 0 (and at least [`MIN_ANALYTIC_LENGTH`]).
fn positive(field: &str, value: f64) -> Result<f64, TpiError> {
    finite(field, value)?;
    if value <= 0.0 {
        return Err(invalid(field, value, "must be > 0"));
    }
    if value < MIN_ANALYTIC_LENGTH {
        return Err(invalid(
            field,
            value,
            format!("must be at least {MIN_ANALYTIC_LENGTH:e}"),
        ));
    }
    Ok(value)
}

/// Validates one side of the rectangle: both ends finite, min < max.
fn interval(name: &str, direction: Direction, ends: [f64; 2]) -> Result<Interval, TpiError> {
    finite(&format!("{name}[0]"), ends[0])?;
    finite(&format!("{name}[1]"), ends[1])?;
    if ends[0] >= ends[1] {
        return Err(TpiError::EmptyDomain {
            direction,
            min: ends[0],
            max: ends[1],
        });
    }
    Ok(Interval::new(ends[0], ends[1]))
}

/// The larger absolute value of an interval's ends: the farthest |t| inside it from 0.
fn farthest(i: Interval) -> f64 {
    i.min.abs().max(i.max.abs())
}

/// Non-zero coefficients a and b of the same sign.
fn same_sign_pair(a: f64, b: f64, what: &str) -> Result<(), TpiError> {
    finite("a", a)?;
    finite("b", b)?;
    if a == 0.0 {
        return Err(invalid("a", a, format!("must be non-zero for a {what}")));
    }
    if b == 0.0 {
        return Err(invalid("b", b, format!("must be non-zero for a {what}")));
    }
    if (a > 0.0) != (b > 0.0) {
        return Err(invalid(
            "b",
            b,
            format!("must have the same sign as a = {a} for a {what}"),
        ));
    }
    Ok(())
}

impl AnalyticSurface {
    /// Validates `kind` and the rectangle `x` x `y` (u = x, v = y) and builds the surface.
    ///
    /// Errors: [`TpiError::NonFinite`] naming the field (`a`, `radius`, `x[0]`, ...),
    /// [`TpiError::EmptyDomain`] when `x[0] >= x[1]` (direction u) or `y[0] >= y[1]`
    /// (direction v), [`TpiError::InvalidParameter`] naming the field for a radius or
    /// semi-axis <= 0, a coefficient that breaks the curvature class, or a rectangle that
    /// leaves the sphere's disc (`x`/`y` named as the field `x, y`), the ellipse or the
    /// cylinder's strip.
    pub fn new(kind: AnalyticKind, x: [f64; 2], y: [f64; 2]) -> Result<Self, TpiError> {
        // Parameters first, then the rectangle, then their compatibility.
        match kind {
            AnalyticKind::EllipticParaboloid { a, b } => {
                same_sign_pair(a, b, "elliptic paraboloid")?
            }
            AnalyticKind::HyperbolicParaboloid { a, b } => {
                same_sign_pair(a, b, "hyperbolic paraboloid")?
            }
            AnalyticKind::SphereCap { radius } | AnalyticKind::Cylinder { radius } => {
                positive("radius", radius)?;
            }
            AnalyticKind::EllipsoidCap { a, b, c } => {
                positive("a", a)?;
                positive("b", b)?;
                positive("c", c)?;
            }
            AnalyticKind::EggCrate { amplitude } => {
                finite("amplitude", amplitude)?;
                if amplitude == 0.0 {
                    return Err(invalid(
                        "amplitude",
                        amplitude,
                        "must be non-zero (use type plane for a flat surface)",
                    ));
                }
            }
            AnalyticKind::Plane { p, q, c0 } => {
                finite("p", p)?;
                finite("q", q)?;
                finite("c0", c0)?;
            }
        }
        let xi = interval("x", Direction::U, x)?;
        let yi = interval("y", Direction::V, y)?;
        let (fx, fy) = (farthest(xi), farthest(yi));
        match kind {
            AnalyticKind::SphereCap { radius } => {
                // The rectangle's farthest point from the z axis is a corner; the evaluation
                // computes r^2 - x^2 - y^2 the same way, and it only grows towards the centre.
                let slack = radius * radius - fx * fx - fy * fy;
                if !(slack > 0.0) {
                    return Err(invalid(
                        "x, y",
                        (fx * fx + fy * fy).sqrt(),
                        format!(
                            "the rectangle's corner at distance {} from the z axis must lie strictly inside the sphere's radius {radius} (a centred square of half-width h needs h * sqrt(2) < radius)",
                            (fx * fx + fy * fy).sqrt()
                        ),
                    ));
                }
            }
            AnalyticKind::EllipsoidCap { a, b, .. } => {
                let slack = 1.0 - fx * fx / (a * a) - fy * fy / (b * b);
                if !(slack > 0.0) {
                    return Err(invalid(
                        "x, y",
                        fx * fx / (a * a) + fy * fy / (b * b),
                        format!(
                            "the rectangle's corner ({fx}, {fy}) must lie strictly inside the ellipse x^2/{a}^2 + y^2/{b}^2 < 1"
                        ),
                    ));
                }
            }
            AnalyticKind::Cylinder { radius } if !(radius * radius - fx * fx > 0.0) => {
                return Err(invalid(
                    "x",
                    fx,
                    format!("|x| must stay strictly below the radius {radius}"),
                ));
            }
            _ => {}
        }
        Ok(Self {
            kind,
            domain: Domain::new(xi, yi),
            units: None,
        })
    }

    /// The same surface with these length units (`None`: unitless); nothing is rescaled.
    pub fn with_units(mut self, units: Option<Units>) -> Self {
        self.units = units;
        self
    }

    /// z = a x^2 + b y^2 over `x` x `y`; see [`AnalyticSurface::new`] for the errors.
    pub fn elliptic_paraboloid(a: f64, b: f64, x: [f64; 2], y: [f64; 2]) -> Result<Self, TpiError> {
        Self::new(AnalyticKind::EllipticParaboloid { a, b }, x, y)
    }

    /// z = sqrt(r^2 - x^2 - y^2) over `x` x `y`, which must lie strictly inside the disc of radius r.
    pub fn sphere_cap(radius: f64, x: [f64; 2], y: [f64; 2]) -> Result<Self, TpiError> {
        Self::new(AnalyticKind::SphereCap { radius }, x, y)
    }

    /// The sphere cap over the centred square [-h, h]^2 (needs h * sqrt(2) < radius, h > 0).
    pub fn sphere_cap_square(radius: f64, half_width: f64) -> Result<Self, TpiError> {
        finite("half_width", half_width)?;
        if !(half_width > 0.0) {
            return Err(invalid("half_width", half_width, "must be > 0"));
        }
        Self::sphere_cap(radius, [-half_width, half_width], [-half_width, half_width])
    }

    /// z = c sqrt(1 - x^2/a^2 - y^2/b^2) over `x` x `y`, strictly inside the ellipse.
    pub fn ellipsoid_cap(
        a: f64,
        b: f64,
        c: f64,
        x: [f64; 2],
        y: [f64; 2],
    ) -> Result<Self, TpiError> {
        Self::new(AnalyticKind::EllipsoidCap { a, b, c }, x, y)
    }

    /// z = a x^2 - b y^2 over `x` x `y`.
    pub fn hyperbolic_paraboloid(
        a: f64,
        b: f64,
        x: [f64; 2],
        y: [f64; 2],
    ) -> Result<Self, TpiError> {
        Self::new(AnalyticKind::HyperbolicParaboloid { a, b }, x, y)
    }

    /// z = A sin(x) sin(y) over `x` x `y`.
    pub fn egg_crate(amplitude: f64, x: [f64; 2], y: [f64; 2]) -> Result<Self, TpiError> {
        Self::new(AnalyticKind::EggCrate { amplitude }, x, y)
    }

    /// z = sqrt(r^2 - x^2) over `x` x `y`, with |x| < r.
    pub fn cylinder(radius: f64, x: [f64; 2], y: [f64; 2]) -> Result<Self, TpiError> {
        Self::new(AnalyticKind::Cylinder { radius }, x, y)
    }

    /// z = p x + q y + c0 over `x` x `y`.
    pub fn plane(p: f64, q: f64, c0: f64, x: [f64; 2], y: [f64; 2]) -> Result<Self, TpiError> {
        Self::new(AnalyticKind::Plane { p, q, c0 }, x, y)
    }

    /// The kind and its parameters.
    pub fn kind(&self) -> AnalyticKind {
        self.kind
    }

    /// The x range [x0, x1] (the u domain).
    pub fn x_range(&self) -> [f64; 2] {
        [self.domain.u.min, self.domain.u.max]
    }

    /// The y range [y0, y1] (the v domain).
    pub fn y_range(&self) -> [f64; 2] {
        [self.domain.v.min, self.domain.v.max]
    }

    /// The height f and its derivatives at (x, y), clamped into the rectangle.
    pub fn height(&self, x: f64, y: f64) -> Height {
        let (x, y) = self.domain.clamp(x, y);
        match self.kind {
            AnalyticKind::EllipticParaboloid { a, b } => Height {
                f: a * x * x + b * y * y,
                fx: 2.0 * a * x,
                fy: 2.0 * b * y,
                fxx: 2.0 * a,
                fxy: 0.0,
                fyy: 2.0 * b,
            },
            AnalyticKind::HyperbolicParaboloid { a, b } => Height {
                f: a * x * x - b * y * y,
                fx: 2.0 * a * x,
                fy: -2.0 * b * y,
                fxx: 2.0 * a,
                fxy: 0.0,
                fyy: -2.0 * b,
            },
            AnalyticKind::SphereCap { radius } => {
                let r2 = radius * radius;
                let w2 = r2 - x * x - y * y;
                let w = w2.sqrt();
                let w3 = w2 * w;
                Height {
                    f: w,
                    fx: -x / w,
                    fy: -y / w,
                    fxx: -(r2 - y * y) / w3,
                    fxy: -x * y / w3,
                    fyy: -(r2 - x * x) / w3,
                }
            }
            AnalyticKind::EllipsoidCap { a, b, c } => {
                let (a2, b2) = (a * a, b * b);
                let g = 1.0 - x * x / a2 - y * y / b2;
                let s = g.sqrt();
                let s3 = g * s;
                Height {
                    f: c * s,
                    fx: -c * x / (a2 * s),
                    fy: -c * y / (b2 * s),
                    fxx: -c * (1.0 - y * y / b2) / (a2 * s3),
                    fxy: -c * x * y / (a2 * b2 * s3),
                    fyy: -c * (1.0 - x * x / a2) / (b2 * s3),
                }
            }
            AnalyticKind::EggCrate { amplitude } => {
                let (sx, cx) = x.sin_cos();
                let (sy, cy) = y.sin_cos();
                Height {
                    f: amplitude * sx * sy,
                    fx: amplitude * cx * sy,
                    fy: amplitude * sx * cy,
                    fxx: -amplitude * sx * sy,
                    fxy: amplitude * cx * cy,
                    fyy: -amplitude * sx * sy,
                }
            }
            AnalyticKind::Cylinder { radius } => {
                let r2 = radius * radius;
                let w2 = r2 - x * x;
                let w = w2.sqrt();
                Height {
                    f: w,
                    fx: -x / w,
                    fy: 0.0,
                    fxx: -r2 / (w2 * w),
                    fxy: 0.0,
                    fyy: 0.0,
                }
            }
            AnalyticKind::Plane { p, q, c0 } => Height {
                f: p * x + q * y + c0,
                fx: p,
                fy: q,
                fxx: 0.0,
                fxy: 0.0,
                fyy: 0.0,
            },
        }
    }
}

impl Surface for AnalyticSurface {
    fn domain(&self) -> Domain {
        self.domain
    }

    fn units(&self) -> Option<Units> {
        self.units
    }

    fn evaluate(&self, u: f64, v: f64) -> SurfaceDerivatives {
        let (x, y) = self.domain.clamp(u, v);
        let h = self.height(x, y);
        SurfaceDerivatives {
            point: DVec3::new(x, y, h.f),
            su: DVec3::new(1.0, 0.0, h.fx),
            sv: DVec3::new(0.0, 1.0, h.fy),
            suu: DVec3::new(0.0, 0.0, h.fxx),
            suv: DVec3::new(0.0, 0.0, h.fxy),
            svv: DVec3::new(0.0, 0.0, h.fyy),
        }
    }

    fn point_at(&self, u: f64, v: f64) -> DVec3 {
        let (x, y) = self.domain.clamp(u, v);
        DVec3::new(x, y, self.height(x, y).f)
    }
}
