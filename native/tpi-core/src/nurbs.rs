//! NURBS surfaces (owned by the NURBS work; this is the agreed interface).

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::error::TpiError;
use crate::surface::{Domain, Interval, Surface, SurfaceDerivatives};

/// The surface file's NURBS record, as read and written (docs/formats.md).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NurbsSpec {
    /// Degrees [du, dv].
    pub degree: [usize; 2],
    /// Control point counts [nu, nv].
    pub count: [usize; 2],
    /// Knots in u, Rhino (count + degree - 1) or textbook (count + degree + 1) convention.
    pub knots_u: Vec<f64>,
    /// Knots in v, same conventions.
    pub knots_v: Vec<f64>,
    /// nu * nv Euclidean control points, point (i, j) at index i * nv + j.
    pub points: Vec<[f64; 3]>,
    /// Optional weights, nu * nv, all > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<f64>>,
}

impl NurbsSpec {
    /// Validates and builds the surface.
    pub fn build(&self) -> Result<NurbsSurface, TpiError> {
        NurbsSurface::new(
            self.degree,
            self.count,
            &self.knots_u,
            &self.knots_v,
            &self.points.iter().map(|p| DVec3::from_array(*p)).collect::<Vec<_>>(),
            self.weights.as_deref(),
        )
    }
}

/// A validated NURBS surface.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    domain: Domain,
}

impl NurbsSurface {
    /// Validates and builds a NURBS surface; knots in either convention.
    pub fn new(
        _degree: [usize; 2],
        _count: [usize; 2],
        _knots_u: &[f64],
        _knots_v: &[f64],
        _points: &[DVec3],
        _weights: Option<&[f64]>,
    ) -> Result<Self, TpiError> {
        Err(TpiError::DegenerateSurface { reason: "NURBS evaluation is not implemented yet".into() })
    }

    /// The record that [`NurbsSpec::build`] turns back into this surface (Rhino knot convention).
    pub fn to_spec(&self) -> NurbsSpec {
        NurbsSpec { degree: [1, 1], count: [2, 2], knots_u: vec![], knots_v: vec![], points: vec![], weights: None }
    }
}

impl Surface for NurbsSurface {
    fn domain(&self) -> Domain {
        self.domain
    }

    fn evaluate(&self, _u: f64, _v: f64) -> SurfaceDerivatives {
        let _ = Interval::new(0.0, 1.0);
        SurfaceDerivatives::default()
    }
}
