//! Surfaces closed in one direction that are not convex (a vase with a waist, a cup, a band
//! with saddles, a mug with poles): the general path's dual structure made periodic, so that
//! the seam closes.
//!
//! With the seam in parameter direction k and period P in the triangulation's plane (the
//! plane coordinates are the normalised pattern scaled per axis, so P is that axis's extent),
//! every seed within a band of width b of either seam side gets a *copy* shifted by +P or -P
//! across it: the same surface point and tangent plane, only its plane coordinate moved. The
//! seeds, their copies and the ghosts beyond the open sides are triangulated and decided as
//! one open patch; around the seam, away from the band's outer edges, the structure is then
//! the same on both sides. It is *folded*: of every triangle and its shifted twin exactly one
//! has its centroid's coordinate c_k in a fundamental domain [x, x + P), and those triangles,
//! with copies renamed to their seeds (and ghosts of copies to the seeds' own ghosts), are a
//! triangulation of the annulus. The flips are local but not unique, so the two sides can
//! differ in small patches; where they differ at the cut x, the fold leaves an edge used
//! twice or a seed's fan open. The cut is tried at the seam and at positions on either side
//! of it within the band; where none folds, the caller keeps the open patch.
//!
//! At a pole (a side collapsed to a point) there are no ghosts: stand-ins mirrored across it in
//! the plane keep the triangulation there local, and leave with their triangles before the
//! fold; the seeds nearest the pole then end the folded structure in a ring of seed-to-seed
//! edges, which is capped by the triangles of that polygon (ear clipping in the plane of the
//! ring's mean normal). Two poles give a closed surface, a pole and an open side a disc.
//!
//! The validity flips then run once more on the folded structure (they are combinatorial:
//! they read only the planes), where the seam is an ordinary part of it.

use std::collections::HashMap;

use crate::diffgeo::LocalGeometry;
use crate::error::TpiError;
use crate::ghosts::{augment, Augmented};
use crate::neighbours::{decide, NeighbourInput, NeighbourStats};
use crate::planes::Plane;
use crate::predicates::orient2d;
use crate::surface::Surface;
use crate::tolerance::{PERIODIC_BAND, PERIODIC_CUTS, PERIODIC_TIE, PERIODIC_TIE_ROUNDS};
use crate::triangulation::{DualTriangulation, NO_TRIANGLE};
use crate::validity_flips::validity_flips;

/// The seeds as the general path holds them.
pub(crate) struct Points<'a> {
    /// Domain parameters.
    pub(crate) uv: &'a [[f64; 2]],
    /// Triangulation-plane coordinates.
    pub(crate) plane_uv: &'a [[f64; 2]],
    /// Local geometry.
    pub(crate) geometry: &'a [LocalGeometry],
    /// Convex side per seed.
    pub(crate) convex_side: &'a [i8],
}

/// The general path's neighbour decision on a surface closed in parameter `direction` whose
/// sides across it (`open`) end the surface (module doc): the folded structure over the seeds
/// and their ghosts, with what decided it; None where it does not fold. `extent` is the size
/// of the triangulation plane's rectangle (its `direction` side is the period).
pub(crate) fn decide_folded(
    surface: &dyn Surface,
    seeds: &Points<'_>,
    extent: [f64; 2],
    open: [bool; 4],
    direction: usize,
    envelope_repair: bool,
) -> Result<Option<(DualTriangulation, Augmented, NeighbourStats)>, TpiError> {
    let n = seeds.uv.len();
    // The sides across the seam that are not open are poles.
    let across = if direction == 0 { [2, 3] } else { [0, 1] };
    let poles = across.iter().filter(|&&s| !open[s]).count();
    let spacing = (extent[0] * extent[1] / n as f64).sqrt();
    let period = extent[direction];
    let band = (PERIODIC_BAND * spacing).min(0.5 * period);
    let copies = with_copies(seeds.uv, seeds.plane_uv, direction, period, band);
    let mut augmented = augment(
        surface,
        &copies.uv,
        &copies.plane_uv,
        extent,
        &extended(seeds.geometry, &copies.copy_of),
        &extended(seeds.convex_side, &copies.copy_of),
        open,
    );
    // Across a pole, stand-ins mirrored in the plane keep the triangulation there as local as
    // anywhere else (else its hull joins far seeds); they are no facets' and leave the
    // structure before its pole is capped.
    let pole_from = augmented.planes.len();
    let with_copies = copies.plane_uv.len();
    for s in across.into_iter().filter(|&s| !open[s]) {
        let k = 1 - direction;
        let side = if s % 2 == 0 { 0.0 } else { extent[k] };
        for i in 0..with_copies {
            let p = augmented.plane_uv[i];
            if (p[k] - side).abs() < band {
                let mut q = p;
                q[k] = 2.0 * side - p[k];
                augmented.plane_uv.push(q);
                augmented.geometry.push(augmented.geometry[i]);
                augmented.planes.push(augmented.planes[i]);
                augmented.convex_side.push(augmented.convex_side[i]);
                augmented.source.push(i as u32);
            }
        }
    }
    let mut triangulation = DualTriangulation::delaunay(&augmented.plane_uv)?;
    let seed_of = |x: u32| {
        let s = augmented.source[x as usize] as usize;
        if s < n {
            s as u32
        } else {
            copies.copy_of[s - n]
        }
    };
    let identity = |x: u32| {
        let point = augmented.planes[x as usize].point.to_array();
        (seed_of(x), point.map(f64::to_bits))
    };
    canonical_ties(&mut triangulation, &augmented.plane_uv, &identity);
    let input = NeighbourInput {
        plane_uv: &augmented.plane_uv,
        geometry: &augmented.geometry,
        planes: &augmented.planes,
        convex_side: &augmented.convex_side,
        any_curvature: true,
    };
    // No facet judged yet: the validity flips, greedy in facet order, would decide the two
    // sides of the seam differently; they run on the fold.
    let mut stats = decide(&mut triangulation, &input, envelope_repair, 0);
    Ok(fold(
        &triangulation,
        &augmented,
        n,
        &copies.copy_of,
        direction,
        [period, band],
        (poles, pole_from),
    )
    .map(|(mut folded, points)| {
        let again = validity_flips(&mut folded, &points.plane_uv, &points.planes, n);
        stats.validity_flips += again.flips;
        stats.validity_unresolved = again.unresolved;
        (folded, points, stats)
    }))
}

/// The seeds with their copies across the seam.
struct WithCopies {
    /// Domain parameters (copies: those of their seed).
    pub(crate) uv: Vec<[f64; 2]>,
    /// Triangulation-plane coordinates (copies shifted by the period).
    pub(crate) plane_uv: Vec<[f64; 2]>,
    /// Per copy (point `seeds + c`), its seed.
    pub(crate) copy_of: Vec<u32>,
}

/// Copies of the seeds within `band` of either seam side (module doc), appended after them.
fn with_copies(
    uv: &[[f64; 2]],
    plane_uv: &[[f64; 2]],
    direction: usize,
    period: f64,
    band: f64,
) -> WithCopies {
    let mut out = WithCopies {
        uv: uv.to_vec(),
        plane_uv: plane_uv.to_vec(),
        copy_of: Vec::new(),
    };
    for (i, p) in plane_uv.iter().enumerate() {
        for shift in [period, -period] {
            let moved = p[direction] + shift;
            if moved >= -band && moved <= period + band {
                let mut q = *p;
                q[direction] = moved;
                out.uv.push(uv[i]);
                out.plane_uv.push(q);
                out.copy_of.push(i as u32);
            }
        }
    }
    out
}

/// `values` of the seeds followed by those of their copies (`copy_of`: each copy's seed).
fn extended<T: Copy>(values: &[T], copy_of: &[u32]) -> Vec<T> {
    values
        .iter()
        .copied()
        .chain(copy_of.iter().map(|&i| values[i as usize]))
        .collect()
}

/// The folded structure (module doc) of `tri`, built over `augmented` (the `seeds`, then their
/// copies `copy_of`, then ghosts), and the points it uses: the seeds followed by their own
/// ghosts. None where the fold is not a triangulation of the annulus.
fn fold(
    tri: &DualTriangulation,
    augmented: &Augmented,
    seeds: usize,
    copy_of: &[u32],
    direction: usize,
    [period, band]: [f64; 2],
    (poles, pole_from): (usize, usize),
) -> Option<(DualTriangulation, Augmented)> {
    let with_copies = seeds + copy_of.len();
    let key = |plane: &Plane| {
        (
            plane.point.to_array().map(f64::to_bits),
            plane.normal.to_array().map(f64::to_bits),
        )
    };
    // The seeds' own ghosts keep their order after the seeds; a copy's ghost is the ghost of
    // its seed with the same plane (the same surface point, so the same continued surface).
    let mut rename: Vec<u32> = (0..seeds as u32).collect();
    rename.extend(copy_of.iter().copied());
    let mut own_ghosts: HashMap<(u32, _), u32> = HashMap::new();
    let mut kept: Vec<usize> = (0..seeds).collect();
    for g in with_copies..pole_from {
        let source = augmented.source[g];
        if (source as usize) < seeds {
            let index = kept.len() as u32;
            own_ghosts.insert((source, key(&augmented.planes[g])), index);
            kept.push(g);
        }
    }
    for g in with_copies..pole_from {
        let source = augmented.source[g] as usize;
        let seed = if source < seeds {
            source as u32
        } else {
            copy_of[source - seeds]
        };
        rename.push(*own_ghosts.get(&(seed, key(&augmented.planes[g])))?);
    }
    // The first cut, of those tried from the seam outwards, where the two sides agree.
    let folded = cuts(band, period).into_iter().find_map(|cut| {
        let triangles: Vec<[u32; 3]> = tri
            .triangles
            .iter()
            // The stand-ins across poles leave with their triangles.
            .filter(|t| t.iter().all(|&v| (v as usize) < pole_from))
            .filter(|t| {
                let centre = t
                    .iter()
                    .map(|&v| augmented.plane_uv[v as usize][direction])
                    .sum::<f64>()
                    / 3.0;
                (cut..cut + period).contains(&centre)
            })
            .map(|t| t.map(|v| rename[v as usize]))
            // Triangles of ghosts alone are no facet's: slivers along the outer hull, whose
            // near-ties may fall either way.
            .filter(|t| t.iter().any(|&v| (v as usize) < seeds))
            .collect();
        let mut folded = DualTriangulation::from_triangles(triangles)?;
        if poles > 0 {
            folded = cap_poles(folded, &augmented.planes[..seeds], poles)?;
        }
        // Only ghosts may end the structure: an open edge at a seed is a gap at the seam.
        let gap = folded
            .triangles
            .iter()
            .zip(&folded.neighbours)
            .any(|(t, nb)| {
                (0..3).any(|k| {
                    nb[k] == NO_TRIANGLE
                        && ((t[(k + 1) % 3] as usize) < seeds || (t[(k + 2) % 3] as usize) < seeds)
                })
            });
        (!gap).then_some(folded)
    })?;
    let points = Augmented {
        plane_uv: kept.iter().map(|&i| augmented.plane_uv[i]).collect(),
        geometry: kept.iter().map(|&i| augmented.geometry[i]).collect(),
        planes: kept.iter().map(|&i| augmented.planes[i]).collect(),
        convex_side: kept.iter().map(|&i| augmented.convex_side[i]).collect(),
        source: kept.iter().map(|&i| augmented.source[i]).collect(),
    };
    Some((folded, points))
}

/// Where the fundamental domain [cut, cut + P) may start: the seam, then
/// [`PERIODIC_CUTS`] positions on either side of it, out to half the copies' band.
fn cuts(band: f64, period: f64) -> Vec<f64> {
    let step = 0.5 * band.min(0.5 * period) / PERIODIC_CUTS as f64;
    let mut at = vec![0.0];
    for k in 1..=PERIODIC_CUTS {
        at.extend([k as f64 * step, -(k as f64) * step]);
    }
    at
}

/// Breaks the Delaunay ties of `tri` over the points at `positions` the same way on both sides
/// of the seam: a ghost mirrored across an open side makes an isosceles trapezoid with another
/// seed and its ghost, four cocircular points whose diagonal the triangulator picks by its
/// own order, which differs between a seed and its copy. Wherever the quad around an edge is
/// strictly convex and cocircular to [`PERIODIC_TIE`] of its size to the fourth power, the
/// diagonal kept is the one whose endpoints' `identity` (a point's seed and plane, the same
/// for a copy) is smaller.
fn canonical_ties<K: Ord + Copy>(
    tri: &mut DualTriangulation,
    positions: &[[f64; 2]],
    identity: &dyn Fn(u32) -> K,
) {
    let pair = |x: u32, y: u32| {
        let (a, b) = (identity(x), identity(y));
        if a <= b {
            (a, b)
        } else {
            (b, a)
        }
    };
    for _ in 0..PERIODIC_TIE_ROUNDS {
        let mut flipped = false;
        for t in 0..tri.triangles.len() {
            for k in 0..3 {
                let other = tri.neighbours[t][k];
                if other == NO_TRIANGLE {
                    continue;
                }
                let tr = tri.triangles[t];
                let (c, a, b) = (tr[k], tr[(k + 1) % 3], tr[(k + 2) % 3]);
                let Some(d) = tri.triangles[other as usize]
                    .into_iter()
                    .find(|&x| x != a && x != b)
                else {
                    continue;
                };
                let p = |x: u32| positions[x as usize];
                if !(orient2d(p(c), p(a), p(d)) > 0.0 && orient2d(p(c), p(d), p(b)) > 0.0) {
                    continue;
                }
                let size = [a, b, d]
                    .iter()
                    .map(|&x| (p(x)[0] - p(c)[0]).hypot(p(x)[1] - p(c)[1]))
                    .fold(0.0f64, f64::max);
                let circle = robust::incircle(
                    robust::Coord {
                        x: p(a)[0],
                        y: p(a)[1],
                    },
                    robust::Coord {
                        x: p(b)[0],
                        y: p(b)[1],
                    },
                    robust::Coord {
                        x: p(c)[0],
                        y: p(c)[1],
                    },
                    robust::Coord {
                        x: p(d)[0],
                        y: p(d)[1],
                    },
                );
                if circle.abs() <= PERIODIC_TIE * size.powi(4) && pair(c, d) < pair(a, b) {
                    tri.flip(t as u32, k);
                    flipped = true;
                }
            }
        }
        if !flipped {
            return;
        }
    }
}

/// Closes the folded structure at its poles: without ghosts there, the seeds nearest each pole
/// end it in a cycle of seed-to-seed edges, which is capped by the triangles of that polygon
/// (ear clipping in the plane of the cycle's mean normal). None unless there are exactly
/// `poles` such cycles, each a simple polygon in that plane.
fn cap_poles(
    folded: DualTriangulation,
    planes: &[Plane],
    poles: usize,
) -> Option<DualTriangulation> {
    let seeds = planes.len();
    let mut next: HashMap<u32, u32> = HashMap::new();
    for (t, nb) in folded.triangles.iter().zip(&folded.neighbours) {
        for k in 0..3 {
            let (a, b) = (t[(k + 1) % 3], t[(k + 2) % 3]);
            if nb[k] == NO_TRIANGLE
                && (a as usize) < seeds
                && (b as usize) < seeds
                && next.insert(a, b).is_some()
            {
                return None;
            }
        }
    }
    let mut starts: Vec<u32> = next.keys().copied().collect();
    starts.sort_unstable();
    let mut seen = std::collections::HashSet::new();
    let mut cycles = Vec::new();
    for start in starts {
        if seen.contains(&start) {
            continue;
        }
        let mut cycle = Vec::new();
        let mut x = start;
        loop {
            if !seen.insert(x) {
                return None;
            }
            cycle.push(x);
            x = *next.get(&x)?;
            if x == start {
                break;
            }
        }
        cycles.push(cycle);
    }
    if cycles.len() != poles {
        return None;
    }
    let mut triangles = folded.triangles;
    for cycle in &cycles {
        // The cap runs each boundary edge the other way.
        let ring: Vec<u32> = cycle.iter().rev().copied().collect();
        triangles.extend(ear_clipping(&ring, planes)?);
    }
    DualTriangulation::from_triangles(triangles)
}

/// Triangles of the polygon `ring` (seed indices, in the order the triangles must keep), its
/// points projected into the plane of their mean normal; None where it is not simple there.
fn ear_clipping(ring: &[u32], planes: &[Plane]) -> Option<Vec<[u32; 3]>> {
    if ring.len() < 3 {
        return None;
    }
    let normal = ring
        .iter()
        .map(|&i| planes[i as usize].normal)
        .sum::<glam::DVec3>()
        .try_normalize()?;
    let e1 = normal.any_orthonormal_vector();
    let e2 = normal.cross(e1);
    let mut at: HashMap<u32, [f64; 2]> = HashMap::new();
    for &i in ring {
        let p = planes[i as usize].point;
        at.insert(i, [p.dot(e1), p.dot(e2)]);
    }
    let area: f64 = (0..ring.len())
        .map(|k| {
            let (a, b) = (at[&ring[k]], at[&ring[(k + 1) % ring.len()]]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum();
    if !(area != 0.0 && area.is_finite()) {
        return None;
    }
    let sign = area.signum();
    let turn = |a: u32, b: u32, c: u32| sign * orient2d(at[&a], at[&b], at[&c]);
    let mut polygon = ring.to_vec();
    let mut triangles = Vec::with_capacity(ring.len() - 2);
    while polygon.len() > 3 {
        let m = polygon.len();
        let ear = (0..m).find(|&k| {
            let (a, b, c) = (polygon[(k + m - 1) % m], polygon[k], polygon[(k + 1) % m]);
            turn(a, b, c) > 0.0
                && polygon.iter().all(|&x| {
                    x == a
                        || x == b
                        || x == c
                        || !(turn(a, b, x) >= 0.0 && turn(b, c, x) >= 0.0 && turn(c, a, x) >= 0.0)
                })
        })?;
        triangles.push([
            polygon[(ear + m - 1) % m],
            polygon[ear],
            polygon[(ear + 1) % m],
        ]);
        polygon.remove(ear);
    }
    triangles.push([polygon[0], polygon[1], polygon[2]]);
    Some(triangles)
}
