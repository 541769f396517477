//! The `Surface` abstraction: a parametric surface S(u, v) over a rectangular domain
//! [u0, u1] x [v0, v1], evaluated to second order.
//!
//! Everything downstream (tangent planes, curvature compensation, facet vertices) reads a
//! surface only through [`Surface::evaluate`], which returns the point and the partial
//! derivatives Su, Sv, Suu, Suv, Svv at one parameter pair.
//!
//! Evaluation outside the domain is **clamped** to the domain: implementations evaluate at
//! `domain.clamp(u, v)`. Callers that must reject out-of-domain input (pattern files, the C ABI)
//! check with [`Domain::check`] first, which returns [`TpiError::OutOfDomain`].

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::error::TpiError;

/// A closed interval `[min, max]` with `min < max`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Interval {
    /// Lower end.
    pub min: f64,
    /// Upper end.
    pub max: f64,
}

impl Interval {
    /// A new interval; the caller guarantees `min < max` (validated constructors check it).
    pub const fn new(min: f64, max: f64) -> Self {
        Self { min, max }
    }

    /// `max - min`.
    pub fn length(&self) -> f64 {
        self.max - self.min
    }

    /// Maps a normalised parameter `s` in [0, 1] linearly onto the interval.
    pub fn lerp(&self, s: f64) -> f64 {
        self.min + s * (self.max - self.min)
    }

    /// Inverse of [`Interval::lerp`].
    pub fn normalise(&self, t: f64) -> f64 {
        (t - self.min) / (self.max - self.min)
    }

    /// `t` clamped into the interval.
    pub fn clamp(&self, t: f64) -> f64 {
        t.clamp(self.min, self.max)
    }

    /// Whether `t` lies in the interval (closed).
    pub fn contains(&self, t: f64) -> bool {
        t >= self.min && t <= self.max
    }
}

/// The rectangular parameter domain of a surface.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Domain {
    /// Domain in u.
    pub u: Interval,
    /// Domain in v.
    pub v: Interval,
}

impl Domain {
    /// A new domain from its two intervals.
    pub const fn new(u: Interval, v: Interval) -> Self {
        Self { u, v }
    }

    /// Maps normalised pattern coordinates (s, t) in [0, 1]^2 onto the domain.
    pub fn from_normalised(&self, st: [f64; 2]) -> [f64; 2] {
        [self.u.lerp(st[0]), self.v.lerp(st[1])]
    }

    /// Maps domain parameters back to normalised coordinates.
    pub fn to_normalised(&self, uv: [f64; 2]) -> [f64; 2] {
        [self.u.normalise(uv[0]), self.v.normalise(uv[1])]
    }

    /// (u, v) clamped into the domain.
    pub fn clamp(&self, u: f64, v: f64) -> (f64, f64) {
        (self.u.clamp(u), self.v.clamp(v))
    }

    /// `Ok(())` when (u, v) is finite and inside the domain, otherwise the typed error.
    pub fn check(&self, u: f64, v: f64) -> Result<(), TpiError> {
        if !u.is_finite() || !v.is_finite() || !self.u.contains(u) || !self.v.contains(v) {
            return Err(TpiError::OutOfDomain {
                u,
                v,
                domain: *self,
            });
        }
        Ok(())
    }
}

/// Point and partial derivatives up to second order at one (u, v).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceDerivatives {
    /// S(u, v).
    pub point: DVec3,
    /// dS/du.
    pub su: DVec3,
    /// dS/dv.
    pub sv: DVec3,
    /// d2S/du2.
    pub suu: DVec3,
    /// d2S/dudv.
    pub suv: DVec3,
    /// d2S/dv2.
    pub svv: DVec3,
}

/// A parametric surface evaluated to second order.
///
/// Implementations must never panic and never return NaN for parameters inside the domain;
/// parameters outside it are clamped (see the module doc).
pub trait Surface: Send + Sync {
    /// The parameter domain.
    fn domain(&self) -> Domain;

    /// Point and first and second partial derivatives at (u, v), clamped into the domain.
    fn evaluate(&self, u: f64, v: f64) -> SurfaceDerivatives;

    /// The point S(u, v) alone; implementations may override with a cheaper path.
    fn point_at(&self, u: f64, v: f64) -> DVec3 {
        self.evaluate(u, v).point
    }

    /// The point and first partial derivatives (S, Su, Sv) at (u, v), clamped into the
    /// domain: bit for bit those of [`Surface::evaluate`], without the second derivatives
    /// (for Gauss-Newton steps, which never read them); implementations may override with a
    /// cheaper path that computes the same sums in the same order.
    fn first_derivatives(&self, u: f64, v: f64) -> [DVec3; 3] {
        let d = self.evaluate(u, v);
        [d.point, d.su, d.sv]
    }

    /// The model's length units (the surface file's `"units"`), `None` when unitless: carried
    /// to the discretisation and every output, never used to rescale.
    fn units(&self) -> Option<crate::units::Units> {
        None
    }

    /// The trim: the part of the domain kept ([`crate::Trim`]); None (the default) keeps the
    /// whole domain.
    fn trim(&self) -> Option<&crate::Trim> {
        None
    }
}
