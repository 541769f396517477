//! Sizing fields: the spacing a pattern should have at every place of the surface, as a
//! metric, and the variable-density Poisson-disk sampling that follows it.
//!
//! A sizing field is a symmetric positive definite 2x2 tensor M(s, t) over the normalised
//! square (s, t in [0, 1]): neighbouring pattern points should lie at M-distance about 1,
//! `|d|_M = sqrt(d^T M d)` for a step d = (ds, dt). It is tabulated on a grid of nodes and
//! interpolated bilinearly. Two kinds are built:
//!
//! - **isotropic** (density fields, `density.rs`): M = G / h^2 with G the first fundamental
//!   form in normalised parameters (G = J^T J, J = [Su (u1 - u0), Sv (v1 - v0)]) and h(s, t)
//!   the spacing in model units; a unit M-step is a surface step of length h whatever the
//!   parametrisation;
//! - **curvature** (tolerance-driven patterns, `fit.rs`): M = |II| / (6 D), II the second
//!   fundamental form in normalised parameters with its principal curvatures replaced by
//!   their absolute values. Near a point the surface is z = 1/2 x^T II x over its tangent
//!   plane, and the tangent planes of three seeds meet above their circumcentre c in the
//!   metric II at height 1/2 R^2 off the surface, R the circumradius in that metric (DESIGN.md,
//!   items 3, 4, 7): a seed of a hexagonal lattice of spacing a has R = a / sqrt(3), so
//!   R^2 / 2 = D gives a = sqrt(6 D) in the metric |II|, hence M. The curvatures are floored
//!   ([`CurvatureFloors`]) so that flat places and parabolic lines keep a finite spacing.
//!
//! The Poisson-disk sampler ([`metric_poisson`]) is Bridson's algorithm with the distance of
//! the metric: candidates around an active point p at M(p)-distance in [r, 2r), accepted when
//! no point x lies closer than r in the mean metric (M(p) + M(x)) / 2. With a constant metric
//! it is Bridson's uniform sampling seen through a linear map.
//!
//! A field also gives the density of a centroidal tessellation that follows it. Lloyd's
//! iteration (`relax.rs`) moves each point to the centroid of its TPI facet, and a TPI facet
//! is, to second order, the Voronoi cell of its seed in the metric |II| (DESIGN.md, item 7):
//! so the iteration is a centroidal tessellation in that metric, where a density rho_II makes
//! cells of |II|-area proportional to rho_II^(-1/2). Cells of M-size 1 have |II|-area
//! proportional to sqrt(det |II| / det M), so rho_II = det M / det |II|, and per unit surface
//! area (|II|-area = sqrt(|K|) surface area) rho = det M / (det G sqrt(|K|))
//! ([`SizingField::lloyd_density`]; sqrt(|K|) floored at [`ROOT_CURVATURE_FLOOR`] of its
//! largest value, and taken as 1 on a flat surface, whose facets are Euclidean Voronoi cells).

use crate::diffgeo::LocalGeometry;
use crate::pattern::SplitMix64;
use crate::surface::{Surface, SurfaceDerivatives};

/// A symmetric 2x2 tensor [[a, b], [b, c]] as (a, b, c).
pub(crate) type Tensor = [f64; 3];

/// A sizing field tabulated on (n x n) nodes, node (i, j) at (i / (n - 1), j / (n - 1)).
#[derive(Clone, Debug)]
pub(crate) struct SizingField {
    n: usize,
    /// The metric at each node (index i * n + j).
    metric: Vec<Tensor>,
    /// The first fundamental form in normalised parameters at each node.
    first: Vec<Tensor>,
    /// sqrt(|K|) at each node (model units), floored (see [`SizingField::lloyd_density`]).
    root_curvature: Vec<f64>,
}

/// Smallest determinant kept, relative to the largest of the field's.
const MIN_RELATIVE_DETERMINANT: f64 = 1e-12;

/// How curvature is floored in a curvature sizing field: each principal curvature is at
/// least `relative` times the larger one at the same point (bounded anisotropy), and at least
/// `global` times the largest curvature over the surface (bounded spacing ratio).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CurvatureFloors {
    /// Smallest principal curvature kept relative to the larger one at the point.
    pub relative: f64,
    /// Smallest curvature kept relative to the surface's largest.
    pub global: f64,
}

impl SizingField {
    /// Nodes per side.
    pub(crate) fn nodes(&self) -> usize {
        self.n
    }

    /// The field on `n` x `n` nodes from a function of (first fundamental form, local
    /// geometry, derivatives, normalised point) giving the metric and sqrt(|K|); nodes where
    /// the surface is not regular are evaluated a little inside.
    fn build(
        surface: &dyn Surface,
        n: usize,
        metric: impl Fn(Tensor, &LocalGeometry, &SurfaceDerivatives, [f64; 2]) -> (Tensor, f64) + Sync,
    ) -> SizingField {
        let n = n.max(2);
        let nodes: Vec<((Tensor, f64), Tensor)> = node_geometry(surface, n, |g, geometry, d, q| {
            (metric(g, geometry, d, q), g)
        })
        .into_iter()
        .map(|x| x.unwrap_or((([f64::NAN; 3], f64::NAN), [f64::NAN; 3])))
        .collect();
        let (metric, first): (Vec<(Tensor, f64)>, Vec<Tensor>) = nodes.into_iter().unzip();
        let (metric, mut root_curvature): (Vec<Tensor>, Vec<f64>) = metric.into_iter().unzip();
        // sqrt(|K|) floored at a twentieth of its largest value; all 1 on a flat surface.
        let top = root_curvature
            .iter()
            .copied()
            .filter(|k| k.is_finite())
            .fold(0.0, f64::max);
        for k in &mut root_curvature {
            *k = if top > 0.0 {
                k.max(ROOT_CURVATURE_FLOOR * top)
            } else {
                1.0
            };
            if !k.is_finite() {
                *k = top.max(1.0);
            }
        }
        let mut field = SizingField {
            n,
            metric,
            first,
            root_curvature,
        };
        field.repair();
        field
    }

    /// Replaces non-finite or non-positive tensors by the mean of the valid ones (a surface
    /// that is degenerate at a few nodes), and floors determinants at
    /// [`MIN_RELATIVE_DETERMINANT`] of the largest.
    fn repair(&mut self) {
        for values in [&mut self.metric, &mut self.first] {
            let valid = |t: &Tensor| {
                t.iter().all(|x| x.is_finite()) && t[0] > 0.0 && t[0] * t[2] - t[1] * t[1] > 0.0
            };
            let (mut sum, mut count) = ([0.0; 3], 0usize);
            let mut largest = 0.0f64;
            for t in values.iter().filter(|t| valid(t)) {
                for k in 0..3 {
                    sum[k] += t[k];
                }
                count += 1;
                largest = largest.max(t[0] * t[2] - t[1] * t[1]);
            }
            let fallback = if count > 0 {
                [
                    sum[0] / count as f64,
                    sum[1] / count as f64,
                    sum[2] / count as f64,
                ]
            } else {
                [1.0, 0.0, 1.0]
            };
            let floor = (largest * MIN_RELATIVE_DETERMINANT).sqrt();
            for t in values.iter_mut() {
                if !valid(t) {
                    *t = fallback;
                }
                // Adding floor * I raises both eigenvalues, so the determinant too.
                let det = t[0] * t[2] - t[1] * t[1];
                if det < floor * floor {
                    t[0] += floor;
                    t[2] += floor;
                }
            }
        }
    }

    /// An isotropic field: M = G / h^2, `spacing` giving h in model units (positive) from
    /// the normalised point and the local geometry there.
    pub(crate) fn isotropic(
        surface: &dyn Surface,
        n: usize,
        spacing: impl Fn([f64; 2], &LocalGeometry) -> f64 + Sync,
    ) -> SizingField {
        SizingField::build(surface, n, |g, geometry, _, st| {
            let h = spacing(st, geometry);
            let w = 1.0 / (h * h);
            (
                [g[0] * w, g[1] * w, g[2] * w],
                geometry.gaussian().abs().sqrt(),
            )
        })
    }

    /// The curvature field of a tolerance `max_deviation` (module doc): M = |II| / (6 D), the
    /// principal curvatures floored by `floors`.
    pub(crate) fn curvature(
        surface: &dyn Surface,
        n: usize,
        max_deviation: f64,
        floors: CurvatureFloors,
    ) -> SizingField {
        // The surface's largest curvature on the same nodes, singular nodes left out: the
        // global floor's reference, and the most any node contributes.
        let kmax = largest_regular_curvature(surface, n);
        let global_floor = floors.global * kmax;
        SizingField::build(surface, n, |_, geometry, d, _| {
            // II(x) = k1 (x . d1)^2 + k2 (x . d2)^2 for a tangent x = Su ds + Sv dt, so in
            // normalised parameters |II| = |k1| w1 w1^T + |k2| w2 w2^T, w_k = (Su . d_k, Sv . d_k).
            let (k1, k2) = (geometry.k1.abs().min(kmax), geometry.k2.abs().min(kmax));
            let top = k1.max(k2);
            let floor = (floors.relative * top).max(global_floor);
            let a1 = k1.max(floor);
            let a2 = k2.max(floor);
            let scale = 1.0 / (6.0 * max_deviation);
            let w1 = [d.su.dot(geometry.d1), d.sv.dot(geometry.d1)];
            let w2 = [d.su.dot(geometry.d2), d.sv.dot(geometry.d2)];
            (
                [
                    scale * (a1 * w1[0] * w1[0] + a2 * w2[0] * w2[0]),
                    scale * (a1 * w1[0] * w1[1] + a2 * w2[0] * w2[1]),
                    scale * (a1 * w1[1] * w1[1] + a2 * w2[1] * w2[1]),
                ],
                (a1 * a2).sqrt(),
            )
        })
    }

    /// The metric at normalised (s, t), bilinear between the nodes (clamped to the square).
    pub(crate) fn metric_at(&self, st: [f64; 2]) -> Tensor {
        bilinear(&self.metric, self.n, st)
    }

    /// The density of a centroidal tessellation by TPI facets following the field (module
    /// doc), det M / (det G sqrt(|K|)) at (s, t).
    pub(crate) fn lloyd_density(&self, st: [f64; 2]) -> f64 {
        let m = self.metric_at(st);
        let g = bilinear(&self.first, self.n, st);
        let root_k = scalar_bilinear(&self.root_curvature, self.n, st);
        let dm = m[0] * m[2] - m[1] * m[1];
        let dg = g[0] * g[2] - g[1] * g[1];
        let rho = dm / (dg * root_k);
        if rho.is_finite() && rho > 0.0 {
            rho
        } else {
            0.0
        }
    }

    /// The expected number of points of a maximal Poisson-disk sampling of M-radius
    /// `radius`: about 0.7 per r^2 of M-area, the M-area being the integral of sqrt(det M).
    pub(crate) fn expected_poisson_count(&self, radius: f64) -> f64 {
        let h = 1.0 / (self.n - 1) as f64;
        let area: f64 = (0..self.n - 1)
            .flat_map(|i| (0..self.n - 1).map(move |j| (i, j)))
            .map(|(i, j)| {
                let t = self.metric_at([(i as f64 + 0.5) * h, (j as f64 + 0.5) * h]);
                (t[0] * t[2] - t[1] * t[1]).max(0.0).sqrt() * h * h
            })
            .sum();
        POISSON_PACKING * area / (radius * radius)
    }

    /// Multiplies the spacing at every node by `factor[node]` (the metric by 1 / factor^2).
    pub(crate) fn scale_spacing(&mut self, factor: &[f64]) {
        for (t, &f) in self.metric.iter_mut().zip(factor) {
            if f.is_finite() && f > 0.0 {
                let w = 1.0 / (f * f);
                t[0] *= w;
                t[1] *= w;
                t[2] *= w;
            }
        }
    }
}

/// `f` at every node of an `n` x `n` grid (index i * n + j) from the first fundamental form
/// in normalised parameters, the local geometry, the normalised derivatives and the point
/// where they were taken: the node itself, or where Su x Sv vanishes there (a pole, a
/// collapsed edge) a point a little inside; None where no such point is regular.
pub(crate) fn node_geometry<T: Send>(
    surface: &dyn Surface,
    n: usize,
    f: impl Fn(Tensor, &LocalGeometry, &SurfaceDerivatives, [f64; 2]) -> T + Sync,
) -> Vec<Option<T>> {
    use rayon::prelude::*;
    let n = n.max(2);
    let domain = surface.domain();
    let (lu, lv) = (domain.u.length(), domain.v.length());
    let h = 1.0 / (n - 1) as f64;
    (0..n * n)
        .into_par_iter()
        .map(|k| {
            let (i, j) = (k / n, k % n);
            let st = [i as f64 * h, j as f64 * h];
            for inset in [0.0, 0.25 * h, 0.5 * h] {
                let q = [
                    st[0].clamp(inset, 1.0 - inset),
                    st[1].clamp(inset, 1.0 - inset),
                ];
                let [u, v] = domain.from_normalised(q);
                let mut d = surface.evaluate(u, v);
                d.su *= lu;
                d.sv *= lv;
                d.suu *= lu * lu;
                d.suv *= lu * lv;
                d.svv *= lv * lv;
                let geometry = LocalGeometry::from_derivatives(&d);
                let g = [d.su.dot(d.su), d.su.dot(d.sv), d.sv.dot(d.sv)];
                if geometry.regular && g.iter().all(|x| x.is_finite()) {
                    return Some(f(g, &geometry, &d, q));
                }
            }
            None
        })
        .collect()
}

/// The largest principal curvature over the `n` x `n` nodes, leaving out singular nodes:
/// those above [`CURVATURE_CEILING_FACTOR`] times the [`CURVATURE_CEILING_QUANTILE`]
/// quantile of the nodes' largest curvatures (0 where no node is regular). Real faces have
/// nodes next to a pole or a collapsed edge where the evaluated curvature is 1e13 while the
/// rest of the surface is below 30 (two of 4,225 nodes on Rhino's Flow2 and HumanHead2
/// examples): taken at face value they set every floor and normalisation of a field, which
/// then asks for 1e14 points. A region that truly is that curved is met by the fit's
/// refinement, which measures deviations rather than predicting them.
pub(crate) fn largest_regular_curvature(surface: &dyn Surface, n: usize) -> f64 {
    let mut largest: Vec<f64> = node_geometry(surface, n, |_, geometry, _, _| {
        geometry.k1.abs().max(geometry.k2.abs())
    })
    .into_iter()
    .flatten()
    .filter(|k| k.is_finite())
    .collect();
    if largest.is_empty() {
        return 0.0;
    }
    let rank = ((largest.len() - 1) as f64 * CURVATURE_CEILING_QUANTILE).round() as usize;
    let (_, quantile, _) = largest.select_nth_unstable_by(rank, f64::total_cmp);
    let ceiling = CURVATURE_CEILING_FACTOR * *quantile;
    largest
        .iter()
        .copied()
        .filter(|&k| k <= ceiling)
        .fold(0.0, f64::max)
}

/// Quantile of the nodes' largest curvatures that [`largest_regular_curvature`] scales.
pub(crate) const CURVATURE_CEILING_QUANTILE: f64 = 0.999;
/// Factor over that quantile beyond which a node's curvature is taken as singular.
pub(crate) const CURVATURE_CEILING_FACTOR: f64 = 10.0;

/// Points of a maximal Poisson-disk sampling per unit area at unit radius (about 0.7).
pub(crate) const POISSON_PACKING: f64 = 0.7;

/// Bilinear interpolation of node values, (s, t) clamped to [0, 1]^2.
fn scalar_bilinear(values: &[f64], n: usize, st: [f64; 2]) -> f64 {
    let m = (n - 1) as f64;
    let x = (st[0].clamp(0.0, 1.0) * m).min(m);
    let y = (st[1].clamp(0.0, 1.0) * m).min(m);
    let i = (x.floor() as usize).min(n - 2);
    let j = (y.floor() as usize).min(n - 2);
    let (fx, fy) = (x - i as f64, y - j as f64);
    let at = |a: usize, b: usize| values[a * n + b];
    (1.0 - fx) * ((1.0 - fy) * at(i, j) + fy * at(i, j + 1))
        + fx * ((1.0 - fy) * at(i + 1, j) + fy * at(i + 1, j + 1))
}

/// Smallest sqrt(|K|) kept in the density of Lloyd's iteration, relative to the largest.
const ROOT_CURVATURE_FLOOR: f64 = 0.05;

/// Bilinear interpolation of node tensors, (s, t) clamped to [0, 1]^2.
fn bilinear(values: &[Tensor], n: usize, st: [f64; 2]) -> Tensor {
    let m = (n - 1) as f64;
    let x = (st[0].clamp(0.0, 1.0) * m).min(m);
    let y = (st[1].clamp(0.0, 1.0) * m).min(m);
    let i = (x.floor() as usize).min(n - 2);
    let j = (y.floor() as usize).min(n - 2);
    let (fx, fy) = (x - i as f64, y - j as f64);
    let at = |a: usize, b: usize| values[a * n + b];
    let (p00, p10, p01, p11) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
    let mut out = [0.0; 3];
    for k in 0..3 {
        out[k] = (1.0 - fx) * ((1.0 - fy) * p00[k] + fy * p01[k])
            + fx * ((1.0 - fy) * p10[k] + fy * p11[k]);
    }
    out
}

/// Bridson's Poisson-disk sampling of [0, 1)^2 in the metric of `field` (module doc): points
/// at least `radius` apart in the mean metric of each pair, at most `max_points` of them
/// (the sampling stops there). Deterministic for a seed.
pub(crate) fn metric_poisson(
    field: &SizingField,
    radius: f64,
    seed: u64,
    max_points: usize,
) -> Vec<[f64; 2]> {
    const NONE: u32 = u32::MAX;
    let r2 = radius * radius;
    // Buckets: about two expected points per cell.
    let expected = field.expected_poisson_count(radius).clamp(1.0, 4.0e7);
    let cells = ((expected / 2.0).sqrt().ceil() as usize).clamp(1, 4096);
    let cell = 1.0 / cells as f64;
    let cell_of = |x: f64| ((x / cell) as usize).min(cells - 1);
    let mut head = vec![NONE; cells * cells];
    let mut next: Vec<u32> = Vec::new();
    let mut points: Vec<[f64; 2]> = Vec::new();
    let mut metrics: Vec<Tensor> = Vec::new();
    let mut active: Vec<usize> = Vec::new();
    let mut rng = SplitMix64::new(seed);
    let insert = |q: [f64; 2],
                  m: Tensor,
                  points: &mut Vec<[f64; 2]>,
                  metrics: &mut Vec<Tensor>,
                  next: &mut Vec<u32>,
                  head: &mut Vec<u32>,
                  active: &mut Vec<usize>| {
        let c = cell_of(q[1]) * cells + cell_of(q[0]);
        next.push(head[c]);
        head[c] = points.len() as u32;
        active.push(points.len());
        points.push(q);
        metrics.push(m);
    };
    let first = [rng.next_f64(), rng.next_f64()];
    insert(
        first,
        field.metric_at(first),
        &mut points,
        &mut metrics,
        &mut next,
        &mut head,
        &mut active,
    );
    while !active.is_empty() && points.len() < max_points {
        let slot = rng.below(active.len());
        let p = points[active[slot]];
        let m = metrics[active[slot]];
        // Cholesky M = R^T R, R = [[r11, r12], [0, r22]]: d = R^-1 w has |d|_M = |w|.
        let r11 = m[0].sqrt();
        let r12 = m[1] / r11;
        let r22 = (m[2] - r12 * r12).max(0.0).sqrt();
        if !(r11 > 0.0 && r22 > 0.0) {
            active.swap_remove(slot);
            continue;
        }
        let mut accepted = false;
        for _ in 0..crate::pattern::POISSON_CANDIDATES {
            let (wx, wy) = loop {
                let wx = (2.0 * rng.next_f64() - 1.0) * 2.0 * radius;
                let wy = (2.0 * rng.next_f64() - 1.0) * 2.0 * radius;
                let w2 = wx * wx + wy * wy;
                if w2 >= r2 && w2 < 4.0 * r2 {
                    break (wx, wy);
                }
            };
            let dy = wy / r22;
            let dx = (wx - r12 * dy) / r11;
            let q = [p[0] + dx, p[1] + dy];
            if !(q[0] >= 0.0 && q[0] < 1.0 && q[1] >= 0.0 && q[1] < 1.0) {
                continue;
            }
            let mq = field.metric_at(q);
            // A conflicting x has d^T ((M(q) + M(x)) / 2) d < r^2, so d^T M(q) d < 2 r^2:
            // within sqrt(2) r of q in M(q), whose box has half-sides r sqrt(2 (M^-1)_kk).
            let det = mq[0] * mq[2] - mq[1] * mq[1];
            if !(det > 0.0) {
                continue;
            }
            let ex = (2.0 * r2 * mq[2] / det).sqrt();
            let ey = (2.0 * r2 * mq[0] / det).sqrt();
            let (i0, i1) = (cell_of((q[0] - ex).max(0.0)), cell_of((q[0] + ex).min(1.0)));
            let (j0, j1) = (cell_of((q[1] - ey).max(0.0)), cell_of((q[1] + ey).min(1.0)));
            let mut far = true;
            'search: for cj in j0..=j1 {
                for ci in i0..=i1 {
                    let mut k = head[cj * cells + ci];
                    while k != NONE {
                        let x = points[k as usize];
                        let mx = metrics[k as usize];
                        let (a, b) = (q[0] - x[0], q[1] - x[1]);
                        let d2 = 0.5
                            * ((mq[0] + mx[0]) * a * a
                                + 2.0 * (mq[1] + mx[1]) * a * b
                                + (mq[2] + mx[2]) * b * b);
                        if d2 < r2 {
                            far = false;
                            break 'search;
                        }
                        k = next[k as usize];
                    }
                }
            }
            if far {
                insert(
                    q,
                    mq,
                    &mut points,
                    &mut metrics,
                    &mut next,
                    &mut head,
                    &mut active,
                );
                accepted = true;
                break;
            }
        }
        if !accepted {
            active.swap_remove(slot);
        }
    }
    points
}
