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

use glam::DVec3;

use crate::diffgeo::LocalGeometry;
use crate::error::TpiError;
use crate::ghosts::{augment, Augmented};
use crate::hull::convex_hull;
use crate::neighbours::{decide, envelope_quad_illegal, NeighbourInput, NeighbourStats};
use crate::planes::{intersect_three, Plane};
use crate::predicates::orient2d;
use crate::surface::Surface;
use crate::tolerance::{
    METRIC_REGULARISATION, PERIODIC_BAND, PERIODIC_CUTS, PERIODIC_TIE, PERIODIC_TIE_ROUNDS,
    POLE_CAP_COSINE, POLE_CAP_FLIPS,
};
use crate::triangulation::{DualTriangulation, NO_TRIANGLE};
use crate::validity_flips::{gaussian_signs, validity_flips};

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
        metric_regularisation: METRIC_REGULARISATION,
        stop: None,
        runaway_limit: false,
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
        let again = validity_flips(
            &mut folded,
            &points.plane_uv,
            &points.planes,
            n,
            &gaussian_signs(&points.geometry),
            None,
            false,
        );
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
            folded = cap_poles(
                folded,
                &augmented.planes[..seeds],
                &augmented.convex_side[..seeds],
                poles,
            )?;
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
    convex_side: &[i8],
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
    let mut directed: std::collections::HashSet<(u32, u32)> = triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .collect();
    let mut axes = Vec::with_capacity(cycles.len());
    for cycle in &cycles {
        // The cap runs each boundary edge the other way.
        let ring: Vec<u32> = cycle.iter().rev().copied().collect();
        // The envelope, else ears nearest to it, else the first ears: the first whose chords
        // are not edges of the structure already (a ring pinched round the pole), which
        // would join two facets twice.
        let fits = |cap: &Vec<[u32; 3]>| {
            cap.iter()
                .all(|t| (0..3).all(|k| !directed.contains(&(t[k], t[(k + 1) % 3]))))
        };
        let cap = envelope_cap(&ring, planes)
            .filter(fits)
            .or_else(|| ear_clipping(&ring, planes, true).filter(fits))
            .or_else(|| ear_clipping(&ring, planes, false))?;
        directed.extend(
            cap.iter()
                .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3]))),
        );
        triangles.extend(cap);
        axes.extend(ring_sides(&ring, planes).map(|(normal, _)| normal));
    }
    let mut capped = DualTriangulation::from_triangles(triangles)?;
    for axis in axes {
        pole_envelope_flips(&mut capped, planes, convex_side, axis);
    }
    Some(capped)
}

/// Around a pole, the general path's structure was decided in parameters, which a pole
/// distorts without bound (a ring of seeds round it spans the whole closed direction). Where
/// the surface there is convex, its facets are the envelope of the tangent planes, whatever
/// the parameters: Lawson flips with the envelope test
/// ([`crate::neighbours::envelope_quad_illegal`]: T_d cuts off T_a ∩ T_b ∩ T_c and T_c cuts
/// off T_a ∩ T_b ∩ T_d, for four seeds on one convex side) on the edges whose four seeds
/// face the pole's axis (n . axis >= [`POLE_CAP_COSINE`]), a flip made where the quad is strictly convex in
/// the plane normal to the axis (the seeds' projections). Each flip lowers the envelope, so
/// the flips end; [`POLE_CAP_FLIPS`] per triangle bounds them all the same.
fn pole_envelope_flips(
    tri: &mut DualTriangulation,
    planes: &[Plane],
    convex_side: &[i8],
    axis: DVec3,
) {
    let seeds = planes.len();
    let e1 = axis.any_orthonormal_vector();
    let e2 = axis.cross(e1);
    let chart = |i: u32| {
        let p = planes[i as usize].point;
        [p.dot(e1), p.dot(e2)]
    };
    let on_cap =
        |i: u32| (i as usize) < seeds && planes[i as usize].normal.dot(axis) >= POLE_CAP_COSINE;
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    // On a closed structure the new diagonal may already be an edge elsewhere (a tangle the
    // parameters left round the pole): such a flip would join two facets twice.
    let mut edges: std::collections::HashSet<(u32, u32)> = tri
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| key(t[k], t[(k + 1) % 3])))
        .collect();
    let mut stack: Vec<(u32, u32)> = Vec::new();
    for (t, nb) in tri.neighbours.iter().enumerate() {
        for &across in nb {
            if across != NO_TRIANGLE && (t as u32) < across {
                stack.push((t as u32, across));
            }
        }
    }
    let mut budget = POLE_CAP_FLIPS * tri.triangles.len();
    while let Some((t, across)) = stack.pop() {
        if budget == 0 {
            return;
        }
        let Some(k) = tri.neighbours[t as usize].iter().position(|&x| x == across) else {
            continue;
        };
        let t1 = tri.triangles[t as usize];
        let [c, a, b] = [t1[k], t1[(k + 1) % 3], t1[(k + 2) % 3]];
        let Some(d) = tri.opposite(across as usize, t) else {
            continue;
        };
        if ![a, b, c, d].into_iter().all(on_cap) {
            continue;
        }
        let [pa, pb, pc, pd] = [a, b, c, d].map(chart);
        let strictly_convex = orient2d(pa, pb, pc) * orient2d(pa, pb, pd) < 0.0
            && orient2d(pc, pd, pa) * orient2d(pc, pd, pb) < 0.0;
        if !strictly_convex
            || edges.contains(&key(c, d))
            || !envelope_quad_illegal(planes, convex_side, [c, a, b, d])
        {
            continue;
        }
        edges.remove(&key(a, b));
        edges.insert(key(c, d));
        budget -= 1;
        let (t1, t2) = tri.flip(t, k);
        for x in [t1, t2] {
            for &y in &tri.neighbours[x as usize] {
                if y != NO_TRIANGLE && y != t1 && y != t2 {
                    stack.push((x, y));
                }
            }
        }
    }
}

/// The mean normal N of a pole's ring of seeds, and how the surface bends there: per ordered
/// pair (i, j) of ring seeds, the side of seed i's plane (normal turned towards N) on which
/// seed j lies, counted [behind, in front] (module doc of [`envelope_cap`]).
fn ring_sides(ring: &[u32], planes: &[Plane]) -> Option<(DVec3, [usize; 2])> {
    let normal = ring
        .iter()
        .map(|&i| planes[i as usize].normal)
        .sum::<DVec3>()
        .try_normalize()?;
    let mut sides = [0usize; 2];
    for &i in ring {
        let plane = &planes[i as usize];
        let towards = plane.normal.dot(normal).signum();
        for &j in ring {
            if i != j {
                let d = towards * plane.signed_distance(planes[j as usize].point);
                sides[usize::from(d > 0.0)] += usize::from(d != 0.0);
            }
        }
    }
    Some((normal, sides))
}

/// The cap of a pole where the surface there is convex: the triangles of the polygon `ring`
/// (seed indices, in the order the triangles must keep) whose vertices are those of the
/// envelope of the ring's tangent planes, as on the convex path (module doc of
/// [`crate::closed`]). In the frame (e1, e2, N) of the ring's mean normal N, plane i,
/// n_i . x = n_i . p_i, is the graph z = s_i . (x, y) + h_i with slope
/// s_i = -(n_i . e1, n_i . e2) / (n_i . N) and height h_i = n_i . p_i / (n_i . N). Where every
/// seed of the ring lies behind every other seed's plane (the surface bends away from N), the
/// facets around the pole are the lower envelope min_i (s_i . (x, y) + h_i), whose triples
/// meeting at a vertex are the lower convex hull of the lifted points (s_i, h_i); in front of
/// them all (bending towards N), the upper envelope and the upper hull. The hull's exact
/// orientation tests and symbolic perturbation decide near-ties (a ring of cocircular seeds)
/// consistently. None where the ring does not bend one way, the hull does not exist, or its
/// lower (upper) faces do not triangulate exactly the ring polygon (the ring's slopes not in
/// convex position): the caller clips ears instead ([`ear_clipping`]).
fn envelope_cap(ring: &[u32], planes: &[Plane]) -> Option<Vec<[u32; 3]>> {
    if ring.len() < 4 {
        return None;
    }
    let (normal, sides) = ring_sides(ring, planes)?;
    let lower = match sides {
        [_, 0] => true,
        [0, _] => false,
        _ => return None,
    };
    let e1 = normal.any_orthonormal_vector();
    let e2 = normal.cross(e1);
    let mut lifted = Vec::with_capacity(ring.len());
    for &i in ring {
        let plane = &planes[i as usize];
        let along = plane.normal.dot(normal);
        let point = [
            -plane.normal.dot(e1) / along,
            -plane.normal.dot(e2) / along,
            plane.normal.dot(plane.point) / along,
        ];
        if !point.iter().all(|x| x.is_finite()) {
            return None;
        }
        lifted.push(point);
    }
    let (faces, _, _) = convex_hull(&lifted).ok()?;
    // Faces are counter-clockwise seen from outside: a lower face turns clockwise seen from
    // above (orient2d of its slopes < 0), an upper face counter-clockwise.
    let slope = |k: u32| [lifted[k as usize][0], lifted[k as usize][1]];
    let mut cap: Vec<[u32; 3]> = faces
        .iter()
        .filter(|f| {
            let turn = orient2d(slope(f[0]), slope(f[1]), slope(f[2]));
            if lower {
                turn < 0.0
            } else {
                turn > 0.0
            }
        })
        .map(|f| f.map(|k| ring[k as usize]))
        .collect();
    // The cap's boundary must be the ring: each ring edge on one cap triangle and no other
    // edge without its twin; the triangles turned to run the ring's edges its own way.
    let mut edges: HashMap<(u32, u32), usize> = HashMap::new();
    for t in &cap {
        for k in 0..3 {
            *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    let m = ring.len();
    let ring_edges = || (0..m).map(|k| (ring[k], ring[(k + 1) % m]));
    let same = ring_edges().all(|e| edges.contains_key(&e));
    let reversed = ring_edges().all(|(a, b)| edges.contains_key(&(b, a)));
    let open = edges
        .keys()
        .filter(|&&(a, b)| !edges.contains_key(&(b, a)))
        .count();
    if !(same || reversed) || open != m || edges.values().any(|&c| c != 1) {
        return None;
    }
    if reversed {
        for t in &mut cap {
            t.swap(1, 2);
        }
    }
    Some(cap)
}

/// Triangles of the polygon `ring` (seed indices, in the order the triangles must keep), its
/// points projected into the plane of their mean normal; None where it is not simple there.
/// With `scored`, of the ears, the one clipped first is the one whose three planes meet nearest to the
/// envelope of the ring's planes, on the side most seeds lie ([`ring_sides`]): the vertex x
/// of planes (a, b, c) is scored by max_i of the signed distance of x from ring plane i,
/// turned so that the envelope's vertices have none positive. Where the envelope
/// triangulates the ring, every ear clipped is one of its triangles (removing one leaves the
/// others on it); elsewhere the ears keep each cap vertex as near to it as they can, instead
/// of fanning the cap out from one seed. Without, the first ear in the ring's order.
fn ear_clipping(ring: &[u32], planes: &[Plane], scored: bool) -> Option<Vec<[u32; 3]>> {
    if ring.len() < 3 {
        return None;
    }
    let (normal, sides) = ring_sides(ring, planes)?;
    let behind = if sides[1] > sides[0] { -1.0 } else { 1.0 };
    let outside = |a: u32, b: u32, c: u32| {
        let [a, b, c] = [a, b, c].map(|i| &planes[i as usize]);
        let corner = intersect_three(a, b, c).point;
        let reach = ring
            .iter()
            .map(|&i| {
                let plane = &planes[i as usize];
                behind * plane.normal.dot(normal).signum() * plane.signed_distance(corner)
            })
            .fold(f64::NEG_INFINITY, f64::max);
        if reach.is_nan() {
            f64::INFINITY
        } else {
            reach
        }
    };
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
        let corners = |k: usize| (polygon[(k + m - 1) % m], polygon[k], polygon[(k + 1) % m]);
        let ear = (0..m)
            .filter(|&k| {
                let (a, b, c) = corners(k);
                turn(a, b, c) > 0.0
                    && polygon.iter().all(|&x| {
                        x == a
                            || x == b
                            || x == c
                            || !(turn(a, b, x) >= 0.0
                                && turn(b, c, x) >= 0.0
                                && turn(c, a, x) >= 0.0)
                    })
            })
            .map(|k| {
                let (a, b, c) = corners(k);
                (if scored { outside(a, b, c) } else { 0.0 }, k)
            })
            // The first of equal scores: deterministic, as the ring's order is.
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))?
            .1;
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
