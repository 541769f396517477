//! Exact predicates for the combinatorial decisions of the convex path.
//!
//! The envelope of the tangent planes of a strictly convex surface is dual to the regular
//! triangulation of the lifted points P_i = (s_i, h_i): the planes' slopes s_i in the slope
//! frame and their heights h_i = -sigma c_i (see [`crate::neighbours::SlopeFrame::lift`]).
//! Every decision that chooses the combinatorics is one of two signs, computed exactly for the
//! given f64 inputs with Shewchuk's adaptive-precision predicates (the `robust` crate: a
//! floating-point filter, exact expansion arithmetic only where the filter cannot decide):
//!
//! - orientation: orient2d(a, b, c) = det [b - a, c - a], positive when (a, b, c) turn
//!   counter-clockwise;
//! - power test: for the quad (c, a, b, d) around the edge (a, b), the edge is illegal when
//!   P_d lies strictly below the plane through P_c, P_a, P_b, i.e. when
//!   sign(orient2d(c, a, b)) * orient3d(P_c, P_a, P_b, P_d) > 0.
//!
//! Exact ties (four lifted points on one plane, e.g. four cocircular slopes of a paraboloid of
//! revolution) are broken by symbolic perturbation: every height is raised by
//! epsilon^(rank of its key), the point with the smallest key raised most. orient3d is linear
//! in the heights, det(h + e) = det(h) + sum_i e_i C_i with C_i = orient3d of the same points
//! with heights the unit vector at i (an orientation of the other three slopes), so the sign of
//! a tie is the sign of C_i for the smallest key i with C_i != 0. The perturbed heights are one
//! generic lifting, so every decision agrees with every other: the flips converge to one
//! regular triangulation, whatever their order.

use robust::{Coord, Coord3D};

/// Twice the signed area of (a, b, c), exact in sign: positive when counter-clockwise.
///
/// The `robust` crate's filter inlined (its expression and its error bound, so the same value
/// where it decides), the call to the crate only where the filter cannot decide.
#[inline]
pub(crate) fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let detleft = (a[0] - c[0]) * (b[1] - c[1]);
    let detright = (a[1] - c[1]) * (b[0] - c[0]);
    let det = detleft - detright;
    let errbound = ORIENT2D_THETA * (detleft + detright).abs();
    if det >= errbound || -det >= errbound {
        det
    } else {
        robust::orient2d(xy(a), xy(b), xy(c))
    }
}

/// The `robust` crate's orient2d filter constant (Ozaki et al.'s bound).
const ORIENT2D_THETA: f64 = 3.330_669_062_177_372_2e-16;

/// The `robust` crate's first orient3d error bound, (7 + 56 eps) eps.
const ORIENT3D_BOUND_A: f64 = (7.0 + 56.0 * f64::EPSILON / 2.0) * (f64::EPSILON / 2.0);

/// orient3d(a, b, c, d), exact in sign: the `robust` crate's filter inlined (its expression
/// and its first error bound), the call to the crate only where the filter cannot decide.
#[inline]
fn orient3d(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    let (adx, bdx, cdx) = (a[0] - d[0], b[0] - d[0], c[0] - d[0]);
    let (ady, bdy, cdy) = (a[1] - d[1], b[1] - d[1], c[1] - d[1]);
    let (adz, bdz, cdz) = (a[2] - d[2], b[2] - d[2], c[2] - d[2]);
    let (bdxcdy, cdxbdy) = (bdx * cdy, cdx * bdy);
    let (cdxady, adxcdy) = (cdx * ady, adx * cdy);
    let (adxbdy, bdxady) = (adx * bdy, bdx * ady);
    let det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * adz.abs()
        + (cdxady.abs() + adxcdy.abs()) * bdz.abs()
        + (adxbdy.abs() + bdxady.abs()) * cdz.abs();
    let errbound = ORIENT3D_BOUND_A * permanent;
    if det > errbound || -det > errbound {
        det
    } else {
        robust::orient3d(xyz(*a), xyz(*b), xyz(*c), xyz(*d))
    }
}

/// Whether the edge (a, b) of the quad (c, a, b, d) is illegal in the regular triangulation
/// of the lifted points `[c, a, b, d]`: the fourth lies strictly below the plane of the first
/// three, ties broken by the perturbation of the module doc with the given `keys`. False when
/// c, a, b are collinear (no triangle to test against).
pub(crate) fn power_illegal(lifted: [[f64; 3]; 4], keys: [u32; 4]) -> bool {
    let [c, a, b, d] = lifted;
    let turn = orient2d([c[0], c[1]], [a[0], a[1]], [b[0], b[1]]);
    if turn == 0.0 {
        return false;
    }
    let below = orient3d(&c, &a, &b, &d);
    let sign = if below != 0.0 {
        below
    } else {
        tie_sign(lifted, keys)
    };
    sign * turn > 0.0
}

/// [`power_illegal`] for (c, a, b) known to turn counter-clockwise: whether P_d lies strictly
/// below the plane through P_c, P_a, P_b (ties broken as there).
///
/// The points are passed by reference: copied into an array of arrays on the stack, they were
/// read back before their stores completed (a stall of this hot test).
pub(crate) fn power_below(lifted: [&[f64; 3]; 4], keys: [u32; 4]) -> bool {
    let [c, a, b, d] = lifted;
    let below = orient3d(c, a, b, d);
    let sign = if below != 0.0 {
        below
    } else {
        tie_sign([*c, *a, *b, *d], keys)
    };
    sign > 0.0
}

/// The sign of orient3d(P_c, P_a, P_b, P_d) under the symbolic raising of the heights.
fn tie_sign(lifted: [[f64; 3]; 4], keys: [u32; 4]) -> f64 {
    let mut order = [0usize, 1, 2, 3];
    order.sort_unstable_by_key(|&i| keys[i]);
    for i in order {
        let unit = |j: usize| {
            let p = lifted[j];
            xyz([p[0], p[1], if j == i { 1.0 } else { 0.0 }])
        };
        let cofactor = robust::orient3d(unit(0), unit(1), unit(2), unit(3));
        if cofactor != 0.0 {
            return cofactor;
        }
    }
    0.0
}

fn xy(p: [f64; 2]) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

fn xyz(p: [f64; 3]) -> Coord3D<f64> {
    Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paraboloid(p: [f64; 2]) -> [f64; 3] {
        [p[0], p[1], p[0] * p[0] + p[1] * p[1]]
    }

    #[test]
    fn power_test_on_the_paraboloid_is_the_in_circle_test() {
        // c, a, b counter-clockwise on the unit circle; d inside, outside, on it.
        let [c, a, b] = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]];
        for (d, inside) in [([0.0, -0.5], true), ([0.0, -1.5], false)] {
            let lifted = [c, a, b, d].map(paraboloid);
            assert_eq!(power_illegal(lifted, [0, 1, 2, 3]), inside);
            // The same quad with (c, a, b) clockwise gives the same answer.
            let lifted = [c, b, a, d].map(paraboloid);
            assert_eq!(power_illegal(lifted, [0, 2, 1, 3]), inside);
        }
    }

    #[test]
    fn exact_ties_are_broken_consistently() {
        // Four cocircular points: in the square (p0, p1, p2, p3), exactly one of the two
        // diagonals must be legal, whichever order the quads are written in.
        let p = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]].map(paraboloid);
        for keys in [[0u32, 1, 2, 3], [3, 2, 1, 0], [2, 0, 3, 1], [1, 3, 0, 2]] {
            // Diagonal (p1, p3) in the quad (p0, p1, p3, p2)... as (c, a, b, d):
            let diag13 = power_illegal(
                [p[0], p[1], p[3], p[2]],
                [keys[0], keys[1], keys[3], keys[2]],
            );
            let diag13_other_side = power_illegal(
                [p[2], p[3], p[1], p[0]],
                [keys[2], keys[3], keys[1], keys[0]],
            );
            let diag02 = power_illegal(
                [p[1], p[2], p[0], p[3]],
                [keys[1], keys[2], keys[0], keys[3]],
            );
            let diag02_other_side = power_illegal(
                [p[3], p[0], p[2], p[1]],
                [keys[3], keys[0], keys[2], keys[1]],
            );
            assert_eq!(diag13, diag13_other_side, "keys {keys:?}");
            assert_eq!(diag02, diag02_other_side, "keys {keys:?}");
            assert_ne!(
                diag13, diag02,
                "keys {keys:?}: exactly one diagonal is illegal"
            );
        }
    }

    #[test]
    fn near_ties_are_decided_exactly() {
        // d a hair inside the circle through c, a, b: the naive determinant rounds to zero or
        // either sign; the exact one sees the hair.
        let [c, a, b] = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]];
        let d = [0.0, -1.0 + f64::EPSILON];
        assert!(power_illegal([c, a, b, d].map(paraboloid), [0, 1, 2, 3]));
        let d = [0.0, -1.0 - f64::EPSILON];
        assert!(!power_illegal([c, a, b, d].map(paraboloid), [0, 1, 2, 3]));
    }
}
