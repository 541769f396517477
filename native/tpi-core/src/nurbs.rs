//! NURBS surfaces: validation and exact evaluation to second order, agreeing with openNURBS.
//!
//! # Geometry
//!
//! A NURBS surface of degrees (p, q) with nu x nv control points P_ij and weights w_ij > 0 is
//!
//! ```text
//!            sum_ij N_i,p(u) N_j,q(v) w_ij P_ij      A(u, v)
//! S(u, v) = ------------------------------------ = ---------
//!            sum_ij N_i,p(u) N_j,q(v) w_ij           w(u, v)
//! ```
//!
//! where A = (x w, y w, z w) and w are the tensor-product B-splines of the homogeneous control
//! points [x w, y w, z w, w]. A surface without weights has all w_ij = 1.
//!
//! The B-spline basis over the full (textbook) knot vector U_0 <= ... <= U_(n+p) follows the
//! Cox-de Boor recursion (The NURBS Book, eq. 2.5), with 0/0 read as 0:
//!
//! ```text
//! N_i,0(u) = 1 if U_i <= u < U_(i+1), else 0
//! N_i,p(u) = (u - U_i) / (U_(i+p) - U_i) N_i,p-1(u) + (U_(i+p+1) - u) / (U_(i+p+1) - U_(i+1)) N_(i+1),p-1(u)
//! ```
//!
//! and its derivatives (eq. 2.7), applied once for the first and twice for the second:
//!
//! ```text
//! N'_i,p(u) = p N_i,p-1(u) / (U_(i+p) - U_i) - p N_(i+1),p-1(u) / (U_(i+p+1) - U_(i+1))
//! ```
//!
//! On the span U_s <= u < U_(s+1) only N_(s-p),p .. N_s,p are non-zero; they are computed as the
//! triangle of The NURBS Book A2.2, keeping the rows of degree p-2 and p-1 for the derivatives
//! (the content of A2.3), in fixed-size stack buffers: an evaluation allocates nothing. Every
//! denominator spans a range of knots that contains the (non-empty) span, so none is zero.
//!
//! The derivatives of S are exact, from the derivatives of A and w by the quotient rule
//! (subscripts are partial derivatives):
//!
//! ```text
//! S   = A / w
//! Su  = (Au - wu S) / w
//! Sv  = (Av - wv S) / w
//! Suu = (Auu - 2 wu Su - wuu S) / w
//! Suv = (Auv - wu Sv - wv Su - wuv S) / w
//! Svv = (Avv - 2 wv Sv - wvv S) / w
//! ```
//!
//! # Knot conventions
//!
//! - **Rhino (openNURBS)**: count + degree - 1 knots k_0 .. k_(n+p-2). This is what
//!   RhinoCommon's `KnotsU`/`KnotsV` and rhino3dm return, and what [`NurbsSurface::to_spec`] and
//!   [`NurbsSurface::knots_u`] emit. The domain is [k_(p-1), k_(n-1)].
//! - **Textbook**: count + degree + 1 knots U_0 .. U_(n+p), the Rhino vector with one more knot
//!   at each end: U_(i+1) = k_i. The two end knots U_0 and U_(n+p) are superfluous: they do not
//!   affect the surface inside its domain [U_p, U_n], so they are checked (finite, non-decreasing)
//!   and then dropped.
//!
//! Either convention is accepted on input; the length tells them apart (they differ by two).
//! Knots need not be clamped nor uniform, and the domain need not start at 0.
//!
//! # Validation
//!
//! [`NurbsSurface::new`] returns the first problem found, as a typed [`TpiError`], in this order:
//! degrees ([`TpiError::InvalidDegree`]: degree 0, degree > [`MAX_NURBS_DEGREE`], or
//! degree >= count; count = degree + 1 is valid, a Bezier patch), point count
//! ([`TpiError::PointCount`]), knot counts ([`TpiError::KnotCount`]), knot values
//! ([`TpiError::NonFinite`] naming e.g. `knots_u[3]`, [`TpiError::KnotsDecreasing`],
//! [`TpiError::EmptyDomain`], [`TpiError::KnotMultiplicity`]), control points
//! ([`TpiError::NonFinite`] naming e.g. `points[12][1]`), weights ([`TpiError::WeightCount`],
//! [`TpiError::NonFinite`] naming e.g. `weights[5]`, [`TpiError::NonPositiveWeight`]).
//!
//! Bounds ([`TpiError::OutOfBounds`], naming the control point and the bound): knots and
//! control point coordinates have |x| <= [`crate::MAX_COORDINATE`] (1e15), and the largest
//! weight is at most [`crate::MAX_WEIGHT_RATIO`] (1e6) times the smallest (equal weights of
//! any size are fine). Beyond them evaluation overflows (a control point at 1e308 gave
//! infinite points and NaN normals). From below, each direction's domain is at least
//! [`crate::MIN_KNOT_DOMAIN`] long and the control net's bounding-box diagonal at least
//! [`crate::MIN_NET_EXTENT`] (both 1e-15): smaller, the derivatives' products overflow or
//! underflow and a curved surface looked developable. They are checked after the finiteness
//! checks above.
//!
//! Knot multiplicity follows openNURBS: in the Rhino convention no knot value may occur more than
//! `degree` times (an interior knot of multiplicity degree + 1 would break the surface apart; an
//! end knot repeated more often than a clamped end needs makes a control point meaningless). For
//! textbook input the superfluous end knots are not counted, so a clamped textbook vector with
//! degree + 1 equal end knots is valid. Indices in errors refer to the vector as given.
//!
//! # Evaluation
//!
//! Evaluation outside the domain is **clamped** to the domain (as the [`Surface`] trait says);
//! check with [`Domain::check`] first where out-of-domain input must be rejected. A NaN parameter
//! gives a NaN result, never a panic. At a knot, the span to the right is used (the derivatives
//! from above, as openNURBS does by default), and at the end of the domain the last non-empty
//! span (as openNURBS does).

use glam::{DVec3, DVec4};
use serde::{Deserialize, Serialize};

use crate::error::{
    check_finite, check_magnitude, Direction, Num, TpiError, MAX_WEIGHT_RATIO, MIN_KNOT_DOMAIN,
    MIN_NET_EXTENT,
};
use crate::surface::{Domain, Interval, Surface, SurfaceDerivatives};
use crate::tolerance::MAX_NURBS_DEGREE;
use crate::units::Units;

/// Length of the fixed-size basis buffers: at most degree + 1 basis functions are non-zero.
const BASIS_LEN: usize = MAX_NURBS_DEGREE + 1;

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
    /// Length units (`"units"`, see [`Units::from_name`]); absent = unitless.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub units: Option<Units>,
    /// Optional trim (see [`crate::Trim`]); checked by [`crate::SurfaceSpec::build`], not by
    /// [`NurbsSpec::build`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub trim: Option<crate::Trim>,
}

impl NurbsSpec {
    /// Validates and builds the surface (see [`NurbsSurface::new`] for the errors).
    pub fn build(&self) -> Result<NurbsSurface, TpiError> {
        NurbsSurface::new(
            self.degree,
            self.count,
            &self.knots_u,
            &self.knots_v,
            &self
                .points
                .iter()
                .map(|p| DVec3::from_array(*p))
                .collect::<Vec<_>>(),
            self.weights.as_deref(),
        )
        .map(|s| s.with_units(self.units))
    }
}

/// The basis of one parameter direction: degree, control point count and the full knot vector.
#[derive(Clone, Debug, PartialEq)]
struct KnotVector {
    /// Degree p (1..=MAX_NURBS_DEGREE).
    degree: usize,
    /// Control point count n (>= p + 1).
    count: usize,
    /// Textbook knot vector U_0 .. U_(n+p); the superfluous ends repeat their neighbours.
    knots: Vec<f64>,
    /// The last non-empty span s (U_s < U_(s+1)) with p <= s <= n - 1, used at the domain end.
    last_span: usize,
}

/// Values (row 0), first (row 1) and second (row 2) derivatives of the degree + 1 basis functions
/// that are non-zero on one span.
type BasisDerivatives<const N: usize> = [[f64; N]; 3];

/// Buffer length for degrees up to 3 (the common bicubic case gets small, fully unrollable
/// buffers; the arithmetic is the same as with [`BASIS_LEN`], so are the results).
const SMALL_BASIS_LEN: usize = 4;

impl KnotVector {
    /// Validates the knots given in either convention; degree and count are already valid.
    fn new(
        direction: Direction,
        degree: usize,
        count: usize,
        given: &[f64],
    ) -> Result<Self, TpiError> {
        let field = match direction {
            Direction::U => "knots_u",
            Direction::V => "knots_v",
        };
        let rhino_len = count.saturating_add(degree).saturating_sub(1);
        let full_len = count.saturating_add(degree).saturating_add(1);
        // Offset of the Rhino-convention part inside the given vector.
        let rhino_offset = if given.len() == rhino_len {
            0
        } else if given.len() == full_len {
            1
        } else {
            return Err(TpiError::KnotCount {
                direction,
                found: given.len(),
                count,
                degree,
                rhino: rhino_len,
                full: full_len,
            });
        };

        for (index, &value) in given.iter().enumerate() {
            check_finite(|| format!("{field}[{index}]"), value)?;
        }
        for index in 1..given.len() {
            let (previous, value) = (given[index - 1], given[index]);
            if value < previous {
                return Err(TpiError::KnotsDecreasing {
                    direction,
                    index,
                    previous,
                    value,
                });
            }
        }
        // Finite knots can still span an infinite range, which would overflow every formula.
        let (first, last) = (given[0], given[given.len() - 1]);
        check_finite(
            || format!("{field}[{}] - {field}[0]", given.len() - 1),
            last - first,
        )?;
        for (index, &value) in given.iter().enumerate() {
            check_magnitude(|| format!("{field}[{index}]"), value)?;
        }

        let rhino = &given[rhino_offset..rhino_offset + rhino_len];
        let (min, max) = (rhino[degree - 1], rhino[count - 1]);
        if min >= max {
            return Err(TpiError::EmptyDomain {
                direction,
                min,
                max,
            });
        }
        // A tiny domain makes the derivatives and their products overflow (issue 14).
        if max - min < MIN_KNOT_DOMAIN {
            return Err(TpiError::OutOfBounds {
                field: format!(
                    "{field}[{}] - {field}[{}]",
                    rhino_offset + count - 1,
                    rhino_offset + degree - 1
                ),
                value: max - min,
                requirement: format!("domain length >= {}", Num(MIN_KNOT_DOMAIN)),
                reason: "derivatives grow as the domain shrinks and would overflow; scale the knots into range".to_string(),
            });
        }

        let mut run_start = 0;
        for index in 1..=rhino.len() {
            if index == rhino.len() || rhino[index] != rhino[run_start] {
                let multiplicity = index - run_start;
                if multiplicity > degree {
                    return Err(TpiError::KnotMultiplicity {
                        direction,
                        index: run_start + rhino_offset,
                        value: rhino[run_start],
                        multiplicity,
                        degree,
                    });
                }
                run_start = index;
            }
        }

        let mut knots = Vec::with_capacity(full_len);
        knots.push(rhino[0]);
        knots.extend_from_slice(rhino);
        knots.push(rhino[rhino_len - 1]);
        // The domain [U_p, U_n] is non-empty, so some span p <= s <= n - 1 is non-empty.
        let last_span = (degree..count)
            .rev()
            .find(|&s| knots[s] < knots[s + 1])
            .unwrap_or(degree);
        Ok(Self {
            degree,
            count,
            knots,
            last_span,
        })
    }

    /// The parameter interval [U_p, U_n].
    fn interval(&self) -> Interval {
        Interval::new(self.knots[self.degree], self.knots[self.count])
    }

    /// The knots in Rhino's convention (count + degree - 1).
    fn rhino_knots(&self) -> &[f64] {
        &self.knots[1..self.knots.len() - 1]
    }

    /// Clamps `t` into the domain and finds its non-empty span s, U_s <= t < U_(s+1), by binary
    /// search; at (or beyond) the domain end the last non-empty span. NaN yields some valid span.
    fn span(&self, t: f64) -> (usize, f64) {
        let t = self.interval().clamp(t);
        if t >= self.knots[self.count] {
            return (self.last_span, t);
        }
        // Invariant: U_low <= t < U_high.
        let (mut low, mut high) = (self.degree, self.count);
        while high - low > 1 {
            let middle = (low + high) / 2;
            if t < self.knots[middle] {
                high = middle;
            } else {
                low = middle;
            }
        }
        (low, t)
    }

    /// The degree + 1 basis functions N_(s-p),p .. N_s,p non-zero on span s, at t (The NURBS
    /// Book A2.2), with the rows of degree p-1 (N_(s-p+1),p-1 ..) and p-2 (N_(s-p+2),p-2 ..)
    /// of the same triangle.
    #[inline]
    fn basis_triangle<const N: usize>(
        &self,
        span: usize,
        t: f64,
    ) -> ([f64; N], [f64; N], [f64; N]) {
        let p = self.degree;
        debug_assert!(p < N);
        let knots = &self.knots;
        let mut left = [0.0; N];
        let mut right = [0.0; N];
        let mut values = [0.0; N];
        let mut degree_minus_1 = [0.0; N];
        let mut degree_minus_2 = [0.0; N];
        values[0] = 1.0;
        for j in 1..=p {
            // `values` holds the basis of degree j - 1 here.
            if j + 1 == p {
                degree_minus_2 = values;
            } else if j == p {
                degree_minus_1 = values;
            }
            left[j] = t - knots[span + 1 - j];
            right[j] = knots[span + j] - t;
            let mut saved = 0.0;
            for r in 0..j {
                // right[r + 1] + left[j - r] = U_(s+r+1) - U_(s+1-j+r) > 0: the range holds the span.
                let temp = values[r] / (right[r + 1] + left[j - r]);
                values[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            values[j] = saved;
        }
        (values, degree_minus_1, degree_minus_2)
    }

    /// Basis values only.
    #[inline]
    fn basis<const N: usize>(&self, span: usize, t: f64) -> [f64; N] {
        let p = self.degree;
        debug_assert!(p < N);
        let knots = &self.knots;
        let mut left = [0.0; N];
        let mut right = [0.0; N];
        let mut values = [0.0; N];
        values[0] = 1.0;
        for j in 1..=p {
            left[j] = t - knots[span + 1 - j];
            right[j] = knots[span + j] - t;
            let mut saved = 0.0;
            for r in 0..j {
                let temp = values[r] / (right[r + 1] + left[j - r]);
                values[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            values[j] = saved;
        }
        values
    }

    /// Values, first and second derivatives of the basis functions non-zero on span s, by
    /// N'_k,p = p (N_k,p-1 / (U_(k+p) - U_k) - N_(k+1),p-1 / (U_(k+p+1) - U_(k+1))), applied to
    /// the rows of degree p-1 (first derivative) and, twice, p-2 (second derivative).
    #[inline]
    fn basis_derivatives<const N: usize>(&self, span: usize, t: f64) -> BasisDerivatives<N> {
        let p = self.degree;
        let knots = &self.knots;
        let (values, degree_minus_1, degree_minus_2) = self.basis_triangle::<N>(span, t);
        let mut first = [0.0; N];
        let mut second = [0.0; N];

        // Row p-1 holds N_(s-p+1+i),p-1 for i in 0..p; its support is [U_(s-p+1+i), U_(s+1+i)].
        let mut inverse_width = [0.0; N];
        for (i, inverse) in inverse_width.iter_mut().enumerate().take(p) {
            *inverse = 1.0 / (knots[span + 1 + i] - knots[span + 1 + i - p]);
        }
        let p_f = p as f64;
        let mut previous = 0.0;
        for i in 0..p {
            let scaled = degree_minus_1[i] * inverse_width[i];
            first[i] = p_f * (previous - scaled);
            previous = scaled;
        }
        first[p] = p_f * previous;

        if p >= 2 {
            // First derivatives of row p-1 from row p-2 (N_(s-p+2+i),p-2, support [U_(s-p+2+i), U_(s+1+i)]).
            let q_f = (p - 1) as f64;
            let mut lower_first = [0.0; N];
            let mut previous = 0.0;
            for i in 0..p - 1 {
                let scaled = degree_minus_2[i] / (knots[span + 1 + i] - knots[span + 2 + i - p]);
                lower_first[i] = q_f * (previous - scaled);
                previous = scaled;
            }
            lower_first[p - 1] = q_f * previous;

            let mut previous = 0.0;
            for i in 0..p {
                let scaled = lower_first[i] * inverse_width[i];
                second[i] = p_f * (previous - scaled);
                previous = scaled;
            }
            second[p] = p_f * previous;
        }
        [values, first, second]
    }
}

/// A validated NURBS surface, evaluated exactly to second order.
///
/// Control points are stored u-major as homogeneous [x w, y w, z w, w] for evaluation, beside the
/// Euclidean points and weights as given (so that [`NurbsSurface::to_spec`] round-trips exactly).
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    basis_u: KnotVector,
    basis_v: KnotVector,
    /// Euclidean control points as given, point (i, j) at i * nv + j.
    points: Vec<DVec3>,
    /// Weights as given, if any.
    weights: Option<Vec<f64>>,
    /// [x w, y w, z w, w] per control point, same layout as `points`.
    homogeneous: Vec<DVec4>,
    /// Bezier patches of every span pair (degrees <= 3 only, else empty), see [`BezierPatches`].
    bezier: BezierPatches,
    domain: Domain,
    net_diagonal: f64,
    /// Length units of the model (the surface file's `"units"`), `None` when unitless.
    units: Option<Units>,
}

impl NurbsSurface {
    /// Validates and builds a NURBS surface.
    ///
    /// - `degree`, `count`: [u, v] degrees (1..=[`MAX_NURBS_DEGREE`]) and control point counts
    ///   (>= degree + 1).
    /// - `knots_u`, `knots_v`: Rhino convention (count + degree - 1 knots) or textbook
    ///   convention (count + degree + 1), see the module doc.
    /// - `points`: `count[0] * count[1]` Euclidean control points, point (i, j) at index
    ///   `i * count[1] + j`.
    /// - `weights`: optional, same layout, all > 0; `None` is a non-rational surface.
    ///
    /// Returns the first problem found as a typed error (order and variants in the module doc);
    /// never panics.
    pub fn new(
        degree: [usize; 2],
        count: [usize; 2],
        knots_u: &[f64],
        knots_v: &[f64],
        points: &[DVec3],
        weights: Option<&[f64]>,
    ) -> Result<Self, TpiError> {
        for (direction, degree, count) in [
            (Direction::U, degree[0], count[0]),
            (Direction::V, degree[1], count[1]),
        ] {
            let reason = if degree == 0 {
                Some("the degree must be at least 1".to_string())
            } else if degree > MAX_NURBS_DEGREE {
                Some(format!(
                    "degree {degree} is above {MAX_NURBS_DEGREE}, the largest supported (Rhino's limit)"
                ))
            } else if degree >= count {
                Some(
                    "a NURBS surface needs at least degree + 1 control points in each direction"
                        .to_string(),
                )
            } else {
                None
            };
            if let Some(reason) = reason {
                return Err(TpiError::InvalidDegree {
                    direction,
                    degree,
                    count,
                    reason,
                });
            }
        }

        // A product that overflows cannot match any slice length; it is reported saturated.
        let point_count = count[0].saturating_mul(count[1]);
        if points.len() != point_count {
            return Err(TpiError::PointCount {
                expected: point_count,
                found: points.len(),
            });
        }

        let basis_u = KnotVector::new(Direction::U, degree[0], count[0], knots_u)?;
        let basis_v = KnotVector::new(Direction::V, degree[1], count[1], knots_v)?;

        let control_point = |index: usize, coordinate: usize| {
            format!(
                "points[{index}][{coordinate}] (control point u {}, v {})",
                index / count[1],
                index % count[1]
            )
        };
        for (index, point) in points.iter().enumerate() {
            for (coordinate, &value) in point.to_array().iter().enumerate() {
                check_finite(|| format!("points[{index}][{coordinate}]"), value)?;
            }
        }

        if let Some(weights) = weights {
            if weights.len() != point_count {
                return Err(TpiError::WeightCount {
                    expected: point_count,
                    found: weights.len(),
                });
            }
            for (index, &value) in weights.iter().enumerate() {
                check_finite(|| format!("weights[{index}]"), value)?;
                if value <= 0.0 {
                    return Err(TpiError::NonPositiveWeight { index, value });
                }
            }
        }

        let homogeneous: Vec<DVec4> = match weights {
            Some(weights) => points
                .iter()
                .zip(weights)
                .map(|(p, &w)| (*p * w).extend(w))
                .collect(),
            None => points.iter().map(|p| p.extend(1.0)).collect(),
        };
        // Finite points and weights can still overflow to infinity in x * w.
        check_homogeneous_finite(&homogeneous)?;
        if let Some(weights) = weights {
            // Both exist: the weights are non-empty (point_count >= 4) and all > 0. Only the
            // ratio matters: equal weights of any size (even subnormal) evaluate as weights 1.
            let (lowest, highest) = weights
                .iter()
                .enumerate()
                .fold((0, 0), |(lo, hi), (k, &w)| {
                    (
                        if w < weights[lo] { k } else { lo },
                        if w > weights[hi] { k } else { hi },
                    )
                });
            if weights[highest] / weights[lowest] > MAX_WEIGHT_RATIO {
                return Err(TpiError::OutOfBounds {
                field: format!(
                    "weights[{lowest}] (control point u {}, v {})",
                    lowest / count[1],
                    lowest % count[1],
                ),
                value: weights[lowest],
                requirement: format!(
                    "weights[{highest}] / weights[{lowest}] <= {} (weights[{highest}] = {})",
                    Num(MAX_WEIGHT_RATIO),
                    Num(weights[highest])
                ),
                reason: "derivatives at that control point would grow with the ratio and overflow; rescale the weights or the model".to_string(),
            });
            }
        }
        // Finite coordinates beyond MAX_COORDINATE overflow in evaluation (issue 14).
        for (index, point) in points.iter().enumerate() {
            for (coordinate, &value) in point.to_array().iter().enumerate() {
                check_magnitude(|| control_point(index, coordinate), value)?;
            }
        }

        let (net_min, net_max) = points
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let net_diagonal = robust_length(net_max - net_min);
        check_finite(
            || "bounding-box diagonal of points".to_string(),
            net_diagonal,
        )?;
        // A tiny net (or one point repeated) has normals that underflow to zero (issue 14).
        if net_diagonal < MIN_NET_EXTENT {
            return Err(TpiError::OutOfBounds {
                field: "bounding-box diagonal of points".to_string(),
                value: net_diagonal,
                requirement: format!(">= {}", Num(MIN_NET_EXTENT)),
                reason: "a control net this small (or a single point) has no representable normals; scale the model into range".to_string(),
            });
        }

        let domain = Domain::new(basis_u.interval(), basis_v.interval());
        let bezier = BezierPatches::extract(&basis_u, &basis_v, &homogeneous);
        Ok(Self {
            basis_u,
            basis_v,
            points: points.to_vec(),
            weights: weights.map(<[f64]>::to_vec),
            homogeneous,
            bezier,
            domain,
            net_diagonal,
            units: None,
        })
    }

    /// The same surface with these length units (`None`: unitless); nothing is rescaled.
    pub fn with_units(mut self, units: Option<Units>) -> Self {
        self.units = units;
        self
    }

    /// The record that [`NurbsSpec::build`] turns back into this surface (Rhino knot convention).
    pub fn to_spec(&self) -> NurbsSpec {
        NurbsSpec {
            degree: self.degree(),
            count: self.count(),
            knots_u: self.knots_u().to_vec(),
            knots_v: self.knots_v().to_vec(),
            points: self.points.iter().map(|p| p.to_array()).collect(),
            weights: self.weights.clone(),
            units: self.units,
            trim: None,
        }
    }

    /// Degrees [du, dv].
    pub fn degree(&self) -> [usize; 2] {
        [self.basis_u.degree, self.basis_v.degree]
    }

    /// Control point counts [nu, nv].
    pub fn count(&self) -> [usize; 2] {
        [self.basis_u.count, self.basis_v.count]
    }

    /// Knots in u, Rhino convention (count + degree - 1).
    pub fn knots_u(&self) -> &[f64] {
        self.basis_u.rhino_knots()
    }

    /// Knots in v, Rhino convention (count + degree - 1).
    pub fn knots_v(&self) -> &[f64] {
        self.basis_v.rhino_knots()
    }

    /// Euclidean control points, point (i, j) at index i * nv + j.
    pub fn control_points(&self) -> &[DVec3] {
        &self.points
    }

    /// The weights as given, or `None` for a non-rational surface.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// Whether the surface was given weights (even if they are all equal).
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }

    /// Length of the diagonal of the control points' axis-aligned bounding box: the scale of
    /// the surface, for relative tolerances.
    pub fn bounding_box_diagonal(&self) -> f64 {
        self.net_diagonal
    }

    /// `len` homogeneous control points [x w, y w, z w, w] of row i, from column `first_j` on.
    #[inline]
    fn homogeneous_row(&self, i: usize, first_j: usize, len: usize) -> &[DVec4] {
        let start = i * self.basis_v.count + first_j;
        &self.homogeneous[start..start + len]
    }
}

/// S and its derivatives from the homogeneous A = (x w, y w, z w, w) and its derivatives.
#[inline(always)]
fn quotient_rule(
    a: DVec4,
    a_u: DVec4,
    a_v: DVec4,
    a_uu: DVec4,
    a_uv: DVec4,
    a_vv: DVec4,
) -> SurfaceDerivatives {
    let w = a.w;
    let (w_u, w_v, w_uu, w_uv, w_vv) = (a_u.w, a_v.w, a_uu.w, a_uv.w, a_vv.w);
    // Multiplying by 1 / w is faster than dividing; subnormal weights make 1 / w overflow.
    let inverse_w = 1.0 / w;
    let divide_by_w = |x: DVec3| {
        if inverse_w.is_finite() {
            x * inverse_w
        } else {
            x / w
        }
    };
    let point = divide_by_w(a.truncate());
    let su = divide_by_w(a_u.truncate() - w_u * point);
    let sv = divide_by_w(a_v.truncate() - w_v * point);
    let suu = divide_by_w(a_uu.truncate() - 2.0 * w_u * su - w_uu * point);
    let suv = divide_by_w(a_uv.truncate() - w_u * sv - w_v * su - w_uv * point);
    let svv = divide_by_w(a_vv.truncate() - 2.0 * w_v * sv - w_vv * point);
    SurfaceDerivatives {
        point,
        su,
        sv,
        suu,
        suv,
        svv,
    }
}

/// Largest degree evaluated through Bezier patches.
const BEZIER_MAX_DEGREE: usize = 3;

/// Largest number of homogeneous points held in Bezier patches (32 bytes each, 64 MiB); a
/// surface with more spans is evaluated by de Boor's recurrence instead.
const BEZIER_MAX_POINTS: usize = 1 << 21;

/// The surface cut into Bezier patches, one per pair of spans (The NURBS Book, section 5.4):
/// on span pair (s, r) the surface's homogeneous form is the tensor-product Bernstein
/// polynomial of the local parameters ((u - U_s) / (U_(s+1) - U_s), (v - U_r) / ...) with
/// these (p + 1) x (q + 1) control points. Evaluating Bernstein polynomials needs no division,
/// which makes an evaluation several times cheaper than de Boor's recurrence (whose divisions
/// form a serial chain); the patches are computed once, exactly as blossoms of the B-spline
/// (`blossom`), so the two agree to rounding.
#[derive(Clone, Debug, Default, PartialEq)]
struct BezierPatches {
    /// Patch of span pair (s, r) at ((s - p) * (nv - q) + (r - q)) * (p + 1) * (q + 1), u-major.
    patches: Vec<DVec4>,
    /// The same points in Euclidean form where every weight is 1 (a non-rational surface:
    /// w = 1 and its derivatives vanish), else empty.
    euclidean: Vec<DVec3>,
    /// 1 / (U_(s+1) - U_s) per span index s in u (0 for an empty span).
    inverse_width_u: Vec<f64>,
    /// Same in v.
    inverse_width_v: Vec<f64>,
}

impl BezierPatches {
    fn extract(basis_u: &KnotVector, basis_v: &KnotVector, homogeneous: &[DVec4]) -> Self {
        let (p, q) = (basis_u.degree, basis_v.degree);
        let (nu, nv) = (basis_u.count, basis_v.count);
        let spans = (nu - p) * (nv - q);
        let size = (p + 1) * (q + 1);
        if p > BEZIER_MAX_DEGREE
            || q > BEZIER_MAX_DEGREE
            || spans.saturating_mul(size) > BEZIER_MAX_POINTS
        {
            return Self::default();
        }
        let widths = |b: &KnotVector| -> Vec<f64> {
            (0..b.knots.len() - 1)
                .map(|s| {
                    let w = b.knots[s + 1] - b.knots[s];
                    if w > 0.0 {
                        1.0 / w
                    } else {
                        0.0
                    }
                })
                .collect()
        };
        let mut patches = vec![DVec4::ZERO; spans * size];
        // Step 1, in u: for every control column j and u-span s, the p + 1 Bezier points of
        // the curve of column j. Step 2, in v: the same on each of those rows.
        let mut column = vec![DVec4::ZERO; nu];
        let mut in_u = vec![DVec4::ZERO; (nu - p) * (p + 1) * nv];
        for j in 0..nv {
            for (i, c) in column.iter_mut().enumerate() {
                *c = homogeneous[i * nv + j];
            }
            for s in p..nu {
                if basis_u.knots[s] >= basis_u.knots[s + 1] {
                    continue;
                }
                for k in 0..=p {
                    in_u[((s - p) * (p + 1) + k) * nv + j] = blossom(basis_u, &column, s, k);
                }
            }
        }
        let mut row = vec![DVec4::ZERO; nv];
        for s in p..nu {
            if basis_u.knots[s] >= basis_u.knots[s + 1] {
                continue;
            }
            for k in 0..=p {
                row.copy_from_slice(
                    &in_u[((s - p) * (p + 1) + k) * nv..((s - p) * (p + 1) + k + 1) * nv],
                );
                for r in q..nv {
                    if basis_v.knots[r] >= basis_v.knots[r + 1] {
                        continue;
                    }
                    let base = ((s - p) * (nv - q) + (r - q)) * size;
                    for l in 0..=q {
                        patches[base + k * (q + 1) + l] = blossom(basis_v, &row, r, l);
                    }
                }
            }
        }
        let euclidean = if homogeneous.iter().all(|h| h.w == 1.0) {
            patches.iter().map(|h| h.truncate()).collect()
        } else {
            Vec::new()
        };
        Self {
            patches,
            euclidean,
            inverse_width_u: widths(basis_u),
            inverse_width_v: widths(basis_v),
        }
    }

    /// The Euclidean patch of span pair (s, r) (non-rational surfaces only).
    #[inline]
    fn euclidean_patch(
        &self,
        basis_u: &KnotVector,
        basis_v: &KnotVector,
        s: usize,
        r: usize,
    ) -> &[DVec3] {
        let (p, q) = (basis_u.degree, basis_v.degree);
        let size = (p + 1) * (q + 1);
        let base = ((s - p) * (basis_v.count - q) + (r - q)) * size;
        &self.euclidean[base..base + size]
    }

    /// The patch of span pair (s, r) and the inverse span widths.
    #[inline]
    fn patch(
        &self,
        basis_u: &KnotVector,
        basis_v: &KnotVector,
        s: usize,
        r: usize,
    ) -> (&[DVec4], f64, f64) {
        let (p, q) = (basis_u.degree, basis_v.degree);
        let size = (p + 1) * (q + 1);
        let base = ((s - p) * (basis_v.count - q) + (r - q)) * size;
        (
            &self.patches[base..base + size],
            self.inverse_width_u[s],
            self.inverse_width_v[r],
        )
    }
}

/// The k-th Bezier point of span s of the B-spline curve with control points `points`: its
/// blossom at (U_s, ..., U_s, U_(s+1), ..., U_(s+1)) with p - k copies of U_s and k of
/// U_(s+1), by de Boor's recurrence with a different parameter at each level.
fn blossom(basis: &KnotVector, points: &[DVec4], s: usize, k: usize) -> DVec4 {
    let p = basis.degree;
    let knots = &basis.knots;
    let mut d: Vec<DVec4> = points[s - p..=s].to_vec();
    for level in 1..=p {
        let t = if level <= k { knots[s + 1] } else { knots[s] };
        for j in (level..=p).rev() {
            let i = s - p + j;
            let (lo, hi) = (knots[i], knots[i + p + 1 - level]);
            let alpha = (t - lo) / (hi - lo);
            d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j];
        }
    }
    d[p]
}

/// Bernstein polynomials of degree p (<= 3) at t.
#[inline(always)]
fn bernstein(p: usize, t: f64) -> [f64; BEZIER_MAX_DEGREE + 1] {
    let s = 1.0 - t;
    match p {
        3 => [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t],
        2 => [s * s, 2.0 * t * s, t * t, 0.0],
        _ => [s, t, 0.0, 0.0],
    }
}

/// The non-rational bicubic patch's point and derivatives from the Bernstein rows `nu`, `nv`
/// ([`bernstein_derivatives`]): the contraction of [`NurbsSurface::evaluate_bezier`] with
/// constant loop bounds (unrolled), the same operations in the same order.
// Indices, not iterators: the sums run over rows and columns of three tables at once.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn bicubic_derivatives(
    patch: &[DVec3; 16],
    nu: &[[f64; BEZIER_MAX_DEGREE + 1]; 3],
    nv: &[[f64; BEZIER_MAX_DEGREE + 1]; 3],
) -> SurfaceDerivatives {
    let (mut point, mut su, mut sv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    let (mut suu, mut suv, mut svv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    for k in 0..4 {
        let (mut t0, mut t1, mut t2) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        for l in 0..4 {
            let cp = patch[4 * k + l];
            t0 += nv[0][l] * cp;
            t1 += nv[1][l] * cp;
            t2 += nv[2][l] * cp;
        }
        let (n0, n1, n2) = (nu[0][k], nu[1][k], nu[2][k]);
        point += n0 * t0;
        su += n1 * t0;
        suu += n2 * t0;
        sv += n0 * t1;
        suv += n1 * t1;
        svv += n0 * t2;
    }
    SurfaceDerivatives {
        point,
        su,
        sv,
        suu,
        suv,
        svv,
    }
}

/// The point and first derivatives of [`bicubic_derivatives`]: the same sums in the same
/// order, without the second derivatives' (bit for bit its `point`, `su` and `sv`).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn bicubic_first_derivatives(
    patch: &[DVec3; 16],
    nu: &[[f64; BEZIER_MAX_DEGREE + 1]; 3],
    nv: &[[f64; BEZIER_MAX_DEGREE + 1]; 3],
) -> [DVec3; 3] {
    let (mut point, mut su, mut sv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    for k in 0..4 {
        let (mut t0, mut t1) = (DVec3::ZERO, DVec3::ZERO);
        for l in 0..4 {
            let cp = patch[4 * k + l];
            t0 += nv[0][l] * cp;
            t1 += nv[1][l] * cp;
        }
        let (n0, n1) = (nu[0][k], nu[1][k]);
        point += n0 * t0;
        su += n1 * t0;
        sv += n0 * t1;
    }
    [point, su, sv]
}

/// The non-rational bicubic patch's point from the Bernstein values `nu`, `nv`: the
/// contraction of [`NurbsSurface::point_bezier`] with constant loop bounds.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn bicubic_point(
    patch: &[DVec3; 16],
    nu: &[f64; BEZIER_MAX_DEGREE + 1],
    nv: &[f64; BEZIER_MAX_DEGREE + 1],
) -> DVec3 {
    let mut point = DVec3::ZERO;
    for k in 0..4 {
        let mut t0 = DVec3::ZERO;
        for l in 0..4 {
            t0 += nv[l] * patch[4 * k + l];
        }
        point += nu[k] * t0;
    }
    point
}

/// Values, first and second derivatives (with respect to the knot parameter, through the
/// span's inverse width `scale`) of the Bernstein polynomials of degree p (<= 3) at t:
/// B'_k = p (B^(p-1)_(k-1) - B^(p-1)_k), B''_k = p (p-1) (B^(p-2)_(k-2) - 2 B^(p-2)_(k-1) + B^(p-2)_k).
#[inline(always)]
fn bernstein_derivatives(p: usize, t: f64, scale: f64) -> [[f64; BEZIER_MAX_DEGREE + 1]; 3] {
    let s = 1.0 - t;
    match p {
        3 => {
            let (d, dd) = (3.0 * scale, 6.0 * scale * scale);
            [
                [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t],
                [
                    -d * (s * s),
                    d * (s * s - 2.0 * t * s),
                    d * (2.0 * t * s - t * t),
                    d * (t * t),
                ],
                [dd * s, dd * (t - 2.0 * s), dd * (s - 2.0 * t), dd * t],
            ]
        }
        2 => {
            let (d, dd) = (2.0 * scale, 2.0 * scale * scale);
            [
                [s * s, 2.0 * t * s, t * t, 0.0],
                [-d * s, d * (s - t), d * t, 0.0],
                [dd, -2.0 * dd, dd, 0.0],
            ]
        }
        _ => [
            [s, t, 0.0, 0.0],
            [-scale, scale, 0.0, 0.0],
            [0.0; BEZIER_MAX_DEGREE + 1],
        ],
    }
}

/// |v| without overflow in the squares (coordinates up to f64::MAX / sqrt(3) stay finite).
fn robust_length(v: DVec3) -> f64 {
    let largest = v.abs().max_element();
    if largest == 0.0 || !largest.is_finite() {
        return largest;
    }
    largest * (v / largest).length()
}

/// Reports the first homogeneous coordinate x * w that overflowed.
fn check_homogeneous_finite(homogeneous: &[DVec4]) -> Result<(), TpiError> {
    for (index, h) in homogeneous.iter().enumerate() {
        for coordinate in 0..3 {
            check_finite(
                || format!("points[{index}][{coordinate}] * weights[{index}]"),
                h[coordinate],
            )?;
        }
    }
    Ok(())
}

impl Surface for NurbsSurface {
    fn domain(&self) -> Domain {
        self.domain
    }

    fn units(&self) -> Option<Units> {
        self.units
    }

    fn evaluate(&self, u: f64, v: f64) -> SurfaceDerivatives {
        if !self.bezier.patches.is_empty() {
            return self.evaluate_bezier(u, v);
        }
        if self.basis_u.degree < SMALL_BASIS_LEN && self.basis_v.degree < SMALL_BASIS_LEN {
            self.evaluate_with::<SMALL_BASIS_LEN>(u, v)
        } else {
            self.evaluate_with::<BASIS_LEN>(u, v)
        }
    }

    fn first_derivatives(&self, u: f64, v: f64) -> [DVec3; 3] {
        let (pu, pv) = (self.basis_u.degree, self.basis_v.degree);
        if (pu, pv) == (3, 3) && !self.bezier.euclidean.is_empty() {
            // The non-rational bicubic patch (as `evaluate_bezier`), rows 0 and 1 only.
            let site = self.bezier_site(u, v);
            let nu = bernstein_derivatives(pu, site.local[0], site.scale[0]);
            let nv = bernstein_derivatives(pv, site.local[1], site.scale[1]);
            let patch =
                self.bezier
                    .euclidean_patch(&self.basis_u, &self.basis_v, site.span_u, site.span_v);
            if let Ok(cubic) = <&[DVec3; 16]>::try_from(patch) {
                return bicubic_first_derivatives(cubic, &nu, &nv);
            }
        }
        let d = self.evaluate(u, v);
        [d.point, d.su, d.sv]
    }

    fn point_at(&self, u: f64, v: f64) -> DVec3 {
        if !self.bezier.patches.is_empty() {
            return self.point_bezier(u, v);
        }
        if self.basis_u.degree < SMALL_BASIS_LEN && self.basis_v.degree < SMALL_BASIS_LEN {
            self.point_with::<SMALL_BASIS_LEN>(u, v)
        } else {
            self.point_with::<BASIS_LEN>(u, v)
        }
    }
}

/// Where (u, v) falls among the Bezier patches ([`NurbsSurface::bezier_site`]).
struct BezierSite<'a> {
    span_u: usize,
    span_v: usize,
    /// The patch's homogeneous control points.
    patch: &'a [DVec4],
    /// The local parameters (u - u_s) / (u_{s+1} - u_s) and the same in v, in [0, 1].
    local: [f64; 2],
    /// The inverse span widths: the chain-rule factors of the derivatives.
    scale: [f64; 2],
}

impl NurbsSurface {
    /// The span pair of (u, v) (clamped to the domain), its Bezier patch and (u, v)'s local
    /// parameters in it: what every Bezier evaluation starts from.
    #[inline]
    fn bezier_site(&self, u: f64, v: f64) -> BezierSite<'_> {
        let (span_u, u) = self.basis_u.span(u);
        let (span_v, v) = self.basis_v.span(v);
        let (patch, su, sv) = self
            .bezier
            .patch(&self.basis_u, &self.basis_v, span_u, span_v);
        BezierSite {
            span_u,
            span_v,
            patch,
            local: [
                (u - self.basis_u.knots[span_u]) * su,
                (v - self.basis_v.knots[span_v]) * sv,
            ],
            scale: [su, sv],
        }
    }

    /// [`Surface::evaluate`] on the Bezier patch of (u, v)'s span pair: Bernstein values and
    /// derivatives (no division), then the same contraction and quotient rule as
    /// [`NurbsSurface::evaluate_with`].
    #[inline]
    fn evaluate_bezier(&self, u: f64, v: f64) -> SurfaceDerivatives {
        let (pu, pv) = (self.basis_u.degree, self.basis_v.degree);
        let site = self.bezier_site(u, v);
        let (span_u, span_v, patch) = (site.span_u, site.span_v, site.patch);
        let nu = bernstein_derivatives(pu, site.local[0], site.scale[0]);
        let nv = bernstein_derivatives(pv, site.local[1], site.scale[1]);
        if !self.bezier.euclidean.is_empty() {
            // Non-rational: S itself is the polynomial, w = 1.
            let patch = self
                .bezier
                .euclidean_patch(&self.basis_u, &self.basis_v, span_u, span_v);
            if let (3, 3, Ok(cubic)) = (pu, pv, <&[DVec3; 16]>::try_from(patch)) {
                return bicubic_derivatives(cubic, &nu, &nv);
            }
            let (mut point, mut su, mut sv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
            let (mut suu, mut suv, mut svv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
            for k in 0..=pu {
                let row = &patch[k * (pv + 1)..(k + 1) * (pv + 1)];
                let (mut t0, mut t1, mut t2) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
                for (l, &cp) in row.iter().enumerate() {
                    t0 += nv[0][l] * cp;
                    t1 += nv[1][l] * cp;
                    t2 += nv[2][l] * cp;
                }
                let (n0, n1, n2) = (nu[0][k], nu[1][k], nu[2][k]);
                point += n0 * t0;
                su += n1 * t0;
                suu += n2 * t0;
                sv += n0 * t1;
                suv += n1 * t1;
                svv += n0 * t2;
            }
            return SurfaceDerivatives {
                point,
                su,
                sv,
                suu,
                suv,
                svv,
            };
        }
        let (mut a, mut a_u, mut a_v) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        let (mut a_uu, mut a_uv, mut a_vv) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        for k in 0..=pu {
            let row = &patch[k * (pv + 1)..(k + 1) * (pv + 1)];
            let (mut t0, mut t1, mut t2) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
            for (l, &cp) in row.iter().enumerate() {
                t0 += nv[0][l] * cp;
                t1 += nv[1][l] * cp;
                t2 += nv[2][l] * cp;
            }
            let (n0, n1, n2) = (nu[0][k], nu[1][k], nu[2][k]);
            a += n0 * t0;
            a_u += n1 * t0;
            a_uu += n2 * t0;
            a_v += n0 * t1;
            a_uv += n1 * t1;
            a_vv += n0 * t2;
        }
        quotient_rule(a, a_u, a_v, a_uu, a_uv, a_vv)
    }

    /// [`Surface::point_at`] on the Bezier patch of (u, v)'s span pair.
    #[inline]
    fn point_bezier(&self, u: f64, v: f64) -> DVec3 {
        let (pu, pv) = (self.basis_u.degree, self.basis_v.degree);
        let site = self.bezier_site(u, v);
        let (span_u, span_v, patch) = (site.span_u, site.span_v, site.patch);
        let nu = bernstein(pu, site.local[0]);
        let nv = bernstein(pv, site.local[1]);
        if !self.bezier.euclidean.is_empty() {
            let patch = self
                .bezier
                .euclidean_patch(&self.basis_u, &self.basis_v, span_u, span_v);
            if let (3, 3, Ok(cubic)) = (pu, pv, <&[DVec3; 16]>::try_from(patch)) {
                return bicubic_point(cubic, &nu, &nv);
            }
            let mut point = DVec3::ZERO;
            for k in 0..=pu {
                let row = &patch[k * (pv + 1)..(k + 1) * (pv + 1)];
                let mut t0 = DVec3::ZERO;
                for (l, &cp) in row.iter().enumerate() {
                    t0 += nv[l] * cp;
                }
                point += nu[k] * t0;
            }
            return point;
        }
        let mut a = DVec4::ZERO;
        for k in 0..=pu {
            let row = &patch[k * (pv + 1)..(k + 1) * (pv + 1)];
            let mut t0 = DVec4::ZERO;
            for (l, &cp) in row.iter().enumerate() {
                t0 += nv[l] * cp;
            }
            a += nu[k] * t0;
        }
        a.truncate() / a.w
    }

    /// [`Surface::evaluate`] with basis buffers of length N (> both degrees).
    #[inline]
    fn evaluate_with<const N: usize>(&self, u: f64, v: f64) -> SurfaceDerivatives {
        let (pu, pv) = (self.basis_u.degree, self.basis_v.degree);
        let (span_u, u) = self.basis_u.span(u);
        let (span_v, v) = self.basis_v.span(v);
        let nu = self.basis_u.basis_derivatives::<N>(span_u, u);
        let nv = self.basis_v.basis_derivatives::<N>(span_v, v);

        // Homogeneous A (xyz) and w with their partial derivatives.
        let (mut a, mut a_u, mut a_v) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        let (mut a_uu, mut a_uv, mut a_vv) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        let [nu_0, nu_1, nu_2] = &nu;
        for (k, ((&n0, &n1), &n2)) in nu_0.iter().zip(nu_1).zip(nu_2).take(pu + 1).enumerate() {
            let row = self.homogeneous_row(span_u - pu + k, span_v - pv, pv + 1);
            let (mut t0, mut t1, mut t2) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
            for (l, &cp) in row.iter().enumerate() {
                t0 += nv[0][l] * cp;
                t1 += nv[1][l] * cp;
                t2 += nv[2][l] * cp;
            }
            a += n0 * t0;
            a_u += n1 * t0;
            a_uu += n2 * t0;
            a_v += n0 * t1;
            a_uv += n1 * t1;
            a_vv += n0 * t2;
        }

        quotient_rule(a, a_u, a_v, a_uu, a_uv, a_vv)
    }

    /// [`Surface::point_at`] with basis buffers of length N (> both degrees).
    #[inline]
    fn point_with<const N: usize>(&self, u: f64, v: f64) -> DVec3 {
        let (pu, pv) = (self.basis_u.degree, self.basis_v.degree);
        let (span_u, u) = self.basis_u.span(u);
        let (span_v, v) = self.basis_v.span(v);
        let nu = self.basis_u.basis::<N>(span_u, u);
        let nv = self.basis_v.basis::<N>(span_v, v);
        let mut a = DVec4::ZERO;
        for (k, &basis_u) in nu.iter().enumerate().take(pu + 1) {
            let row = self.homogeneous_row(span_u - pu + k, span_v - pv, pv + 1);
            let mut t0 = DVec4::ZERO;
            for (l, &cp) in row.iter().enumerate() {
                t0 += nv[l] * cp;
            }
            a += basis_u * t0;
        }
        a.truncate() / a.w
    }
}
