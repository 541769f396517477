//! The quality report: what a designer and a fabricator check before trusting a mesh.
//!
//! - planarity error: max over facets i and their vertices x of |n_i . (x - p_i)|, relative to
//!   the bounding-box diagonal of the pattern's surface points (0 up to rounding, since every
//!   vertex is built in its facets' planes);
//! - deviation: distance of each mesh vertex from its closest surface point (max and mean);
//!   a facet whose farthest vertex stands more than [`FAR_VERTEX_SPACINGS`] times its local
//!   spacing h_i = mean over the facets j sharing an edge with it of |p_i - p_j| off the
//!   surface is flagged [`FLAG_FAR_VERTEX`] (a TPI vertex stands about k r^2 / 2 off, r the
//!   facet's circumradius, so well within one spacing wherever three neighbouring tangent
//!   planes are not nearly parallel); the largest ratio is `max_deviation_spacings`;
//! - convexity and simplicity of each facet, in 2D coordinates of its tangent plane; a facet
//!   whose loop runs clockwise seen from its normal counts as not simple; a facet with fewer
//!   than three distinct vertices is open;
//! - overlap: two simple facets that share a vertex overlap when, projected along the mean of
//!   their two normals, an edge of one crosses an edge of the other properly or a vertex of
//!   one lies strictly inside the other (DESIGN.md, item 8). A pair sharing an edge (a, b)
//!   is first tried by the separating line through a and b: all other vertices of one on one
//!   side and of the other on the other side means no overlap;
//! - validity: open, non-simple and overlapping facets are invalid (`invalid_facets`) and
//!   flagged. Non-convex facets are counted but flagged only where the envelope makes every
//!   facet convex: the seed and the seeds of all the facets sharing an edge with it strictly
//!   convex (K > 0) on the same side, each facet's plane its seed's tangent plane (not an
//!   adjusted one), and the loop turning clockwise at a corner off the boundary (the corners
//!   on the boundary follow the surface's boundary curve). On K < 0 non-convex is the
//!   expected shape (paper, figure 6), not a defect, and so it is next to a parabolic line,
//!   where the planes meeting at a facet's vertices are not all on the envelope;
//! - topology: Euler characteristic V - E + F, boundary loops, valence of interior vertices
//!   (a vertex is interior when no boundary edge, i.e. an edge of only one facet, touches it).

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::facets::{accept_newton, FootHint, FootHints};
use crate::neighbours::NeighbourStats;
use crate::planes::Plane;
use crate::progress::{NoProgress, Progress, Stage, Tally};
use crate::projection::{deviation_at, distance_foot, Wrap};
use crate::sanity::BoundaryLoops;
use crate::surface::Surface;
use crate::tolerance::{FAR_VERTEX_SPACINGS, SEPARATION_MARGIN};
use crate::validity_flips::polygons_overlap;

/// Per-facet flag: not convex.
pub const FLAG_NON_CONVEX: u8 = 1;
/// Per-facet flag: not a simple polygon (self-intersecting, clockwise, or degenerate).
pub const FLAG_NON_SIMPLE: u8 = 2;
/// Per-facet flag: overlaps a neighbour.
pub const FLAG_OVERLAP: u8 = 4;
/// Per-facet flag: a diagnostic names this facet's pattern point.
pub const FLAG_DIAGNOSTIC: u8 = 8;
/// Per-facet flag: fewer than three distinct vertices.
pub const FLAG_OPEN: u8 = 16;
/// Per-facet flag: a vertex stands farther from the surface than [`FAR_VERTEX_SPACINGS`]
/// times the facet's local spacing (the mean distance from its seed to the seeds of the
/// facets it shares an edge with). Not invalid by itself: exact tangent planes nearly
/// parallel (at a parabolic line, or at seeds close together) meet far from the surface.
pub const FLAG_FAR_VERTEX: u8 = 32;
/// The flags that make a facet invalid (DESIGN.md, item 8).
pub const INVALID_FLAGS: u8 = FLAG_NON_SIMPLE | FLAG_OVERLAP | FLAG_OPEN;

/// Summary of a discretisation's quality (serialised into the output contract).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct QualityReport {
    /// Number of facets (= pattern points).
    pub facet_count: usize,
    /// Number of mesh vertices.
    pub vertex_count: usize,
    /// Number of mesh edges.
    pub edge_count: usize,
    /// Facet count per number of sides.
    pub side_histogram: BTreeMap<usize, usize>,
    /// Vertices not on the boundary.
    pub interior_vertex_count: usize,
    /// Fraction of interior vertices where exactly three facets meet.
    pub trivalent_fraction: f64,
    /// Largest distance of a facet vertex from its facet's tangent plane / bbox diagonal.
    pub max_planarity_error: f64,
    /// Largest distance of a mesh vertex from the surface (model units).
    pub max_deviation: f64,
    /// Mean distance of mesh vertices from the surface (model units).
    pub mean_deviation: f64,
    /// Facets that are not convex.
    pub non_convex_facets: usize,
    /// Facets that are not simple polygons.
    pub non_simple_facets: usize,
    /// Pairs of neighbouring facets that overlap.
    pub overlapping_pairs: usize,
    /// Facets with any flag (non-convex where the envelope makes facets convex, non-simple,
    /// overlapping, open, named by a diagnostic, or with a far vertex).
    pub flagged_facets: usize,
    /// Facets with fewer than three distinct vertices.
    #[serde(default)]
    pub open_facets: usize,
    /// Open, non-simple or overlapping facets (each once): 0 for a valid mesh.
    #[serde(default)]
    pub invalid_facets: usize,
    /// Facets with a vertex farther from the surface than [`FAR_VERTEX_SPACINGS`] local
    /// spacings ([`FLAG_FAR_VERTEX`]).
    #[serde(default)]
    pub far_vertex_facets: usize,
    /// The largest, over the facets, of the deviation of a facet's farthest vertex over the
    /// facet's local spacing ([`FLAG_FAR_VERTEX`]): below 1 on a mesh that hugs its surface.
    #[serde(default)]
    pub max_deviation_spacings: f64,
    /// V - E + F (1 for a disc).
    pub euler_characteristic: i64,
    /// Number of boundary loops (1 for a disc); a boundary pinched at a vertex of 2k boundary
    /// edges counts k loops there (two discs touching at a vertex: 2).
    pub boundary_loops: usize,
    /// Edges shared by more than two facets.
    pub non_manifold_edges: usize,
    /// Smallest facet area.
    pub min_facet_area: f64,
    /// Largest facet area.
    pub max_facet_area: f64,
    /// Shortest mesh edge.
    pub min_edge_length: f64,
    /// Longest mesh edge.
    pub max_edge_length: f64,
    /// Bounding-box diagonal used for relative measures.
    pub bounding_box_diagonal: f64,
    /// Whether every vertex coordinate is finite.
    pub all_finite: bool,
    /// What the neighbour decision did.
    pub neighbours: NeighbourStats,
    /// Number of diagnostics.
    pub diagnostic_count: usize,
}

/// Inputs of the report.
pub(crate) struct ReportInput<'a> {
    /// The surface.
    pub surface: &'a dyn Surface,
    /// Seeds' parameters (for projection guesses).
    pub uv: &'a [[f64; 2]],
    /// Tangent planes.
    pub planes: &'a [Plane],
    /// Vertex positions.
    pub vertices: &'a [DVec3],
    /// Facet loop offsets.
    pub offsets: &'a [u32],
    /// Flat loops.
    pub loops: &'a [u32],
    /// Bounding-box diagonal.
    pub diagonal: f64,
    /// Pattern points named by diagnostics.
    pub diagnosed: &'a [bool],
    /// What the neighbour decision did.
    pub neighbours: NeighbourStats,
    /// Number of diagnostics.
    pub diagnostic_count: usize,
    /// Per seed, +1/-1 where strictly convex (K > 0) and the facet's plane is the tangent
    /// plane, 0 elsewhere: where a non-convex facet is a defect (empty: nowhere).
    pub convex_side: &'a [i8],
    /// How the projections continue past the domain's sides (seams, poles).
    pub wrap: &'a Wrap,
}

/// Facet `i`'s loop.
fn facet<'a>(input: &ReportInput<'a>, i: usize) -> &'a [u32] {
    &input.loops[input.offsets[i] as usize..input.offsets[i + 1] as usize]
}

/// Computes the report and the per-facet flags, counting each vertex's deviation and then
/// each facet's shape as an item of [`Stage::Report`]. `feet` holds, per vertex, what the
/// facet stage knows about its foot (an empty list: project every vertex from its first
/// facet's seed); it is let go once the deviations are measured.
pub(crate) fn report(
    input: &ReportInput<'_>,
    feet: Vec<FootHint>,
    progress: &dyn Progress,
) -> (QualityReport, Vec<u8>) {
    let facet_count = input.offsets.len().saturating_sub(1);
    let mut r = QualityReport {
        facet_count,
        vertex_count: input.vertices.len(),
        bounding_box_diagonal: input.diagonal,
        neighbours: input.neighbours,
        diagnostic_count: input.diagnostic_count,
        all_finite: input.vertices.iter().all(|v| v.is_finite()),
        min_facet_area: f64::INFINITY,
        min_edge_length: f64::INFINITY,
        ..QualityReport::default()
    };
    let mut flags = vec![0u8; facet_count];

    // Deviation from the surface first, so that the feet's hints are let go before the edges
    // and shapes are built. Per vertex (from its foot, see `resolve_feet`), in vertex
    // order (the order of the sum).
    // One value per vertex, UNUSED where no facet holds it (no distance is -inf): no copy of
    // the used ones is made.
    const UNUSED: f64 = f64::NEG_INFINITY;
    let deviations: Vec<f64> = map_feet(
        input.surface,
        input.wrap,
        input.uv,
        input.vertices,
        input.offsets,
        input.loops,
        FootHints::Listed(&feet),
        UNUSED,
        |v, foot| deviation_at(input.surface, &input.wrap.domain, input.vertices[v], foot).0,
        progress,
    );
    drop(feet);
    let used = || deviations.iter().copied().filter(|&d| d != UNUSED);
    let used_count = used().count();
    if used_count > 0 {
        r.max_deviation = used().fold(0.0, f64::max);
        r.mean_deviation = used().sum::<f64>() / used_count as f64;
    }
    // Per facet, its farthest vertex's deviation (judged against its local spacing once the
    // shared edges are known).
    let facet_deviation: Vec<f64> = (0..facet_count)
        .map(|i| {
            facet(input, i)
                .iter()
                .map(|&v| deviations[v as usize])
                .fold(0.0, f64::max)
        })
        .collect();
    drop(deviations);

    // Edges: (lo, hi, facet) sorted, by a counting sort on lo and a sort of each (short) run.
    let edges = sorted_edges(input, facet_count);
    // Per facet: centroid (for the overlap test) and shape, in parallel.
    let shapes: Vec<(DVec3, FacetShape, f64)> = {
        use rayon::prelude::*;
        (0..facet_count)
            .into_par_iter()
            .map_init(
                || (Vec::new(), Tally::new(progress, Stage::Report)),
                |(buffer, tally), i| {
                    tally.add(1);
                    let l = facet(input, i);
                    let plane = &input.planes[i];
                    let mut planarity = 0.0f64;
                    let mut centroid = DVec3::ZERO;
                    for &v in l {
                        let x = input.vertices[v as usize];
                        planarity = planarity.max(plane.signed_distance(x).abs() / input.diagonal);
                        centroid += x;
                    }
                    let centroid = if l.is_empty() {
                        DVec3::NAN
                    } else {
                        centroid / l.len() as f64
                    };
                    let shape = facet_shape_into(
                        plane,
                        l.iter().map(|&v| input.vertices[v as usize]),
                        buffer,
                    );
                    (centroid, shape, planarity)
                },
            )
            .collect()
    };
    // At most one shared edge per two entries: sized once, not grown by doubling (at a
    // million facets the doubling's copies were the report's peak of memory).
    let mut shared_edges: Vec<(u32, u32, u32, u32)> = Vec::with_capacity(edges.len() / 2);
    let mut boundary = BoundaryLoops::new(input.vertices.len());
    let mut k = 0;
    while k < edges.len() {
        let mut m = k + 1;
        while m < edges.len() && edges[m].0 == edges[k].0 && edges[m].1 == edges[k].1 {
            m += 1;
        }
        let (a, b) = (edges[k].0, edges[k].1);
        r.edge_count += 1;
        let length = input.vertices[a as usize].distance(input.vertices[b as usize]);
        r.min_edge_length = r.min_edge_length.min(length);
        r.max_edge_length = r.max_edge_length.max(length);
        match m - k {
            1 => boundary.add_edge(a, b),
            2 => shared_edges.push((edges[k].2, edges[k + 1].2, a, b)),
            _ => r.non_manifold_edges += 1,
        }
        k = m;
    }
    drop(edges);
    // Overlaps: pairs sharing an edge, then pairs sharing only a vertex (where four or more
    // facets meet), both facets simple.
    let simple: Vec<bool> = shapes.iter().map(|s| s.1.simple).collect();
    let overlapping: Vec<(u32, u32)> = {
        use rayon::prelude::*;
        // One pair of loop buffers per worker: no allocation per pair.
        let mut pairs: Vec<(u32, u32)> = shared_edges
            .par_iter()
            .map_init(LoopBuffers::default, |buffers, &(f, g, a, b)| {
                (f, g, pair_overlaps(input, &shapes, buffers, (f, g, a, b)))
            })
            .filter(|&(_, _, overlaps)| overlaps)
            .map(|(f, g, _)| (f.min(g), f.max(g)))
            .collect();
        pairs.extend(vertex_pairs_overlapping(
            input,
            facet_count,
            &simple,
            &shared_edges,
        ));
        pairs.sort_unstable();
        pairs.dedup();
        pairs
    };
    let enveloped = enveloped_facets(input.convex_side, facet_count, &shared_edges);
    let spacing = local_spacings(input, facet_count, &shared_edges);
    for (i, (&deviation, &h)) in facet_deviation.iter().zip(&spacing).enumerate() {
        let spacings = deviation / h;
        if spacings > FAR_VERTEX_SPACINGS {
            flags[i] |= FLAG_FAR_VERTEX;
            r.far_vertex_facets += 1;
        }
        if spacings.is_finite() {
            r.max_deviation_spacings = r.max_deviation_spacings.max(spacings);
        }
    }
    drop((facet_deviation, spacing));
    drop(shared_edges);
    drop(simple);
    r.overlapping_pairs = overlapping.len();
    for &(f, g) in &overlapping {
        flags[f as usize] |= FLAG_OVERLAP;
        flags[g as usize] |= FLAG_OVERLAP;
    }
    let used: Vec<bool> = {
        let mut used = vec![false; input.vertices.len()];
        for &v in input.loops {
            used[v as usize] = true;
        }
        used
    };
    // A boundary pinched at a vertex counts a loop per pair of its edges there.
    r.boundary_loops = boundary.count();
    let used_count = used.iter().filter(|&&u| u).count();
    r.euler_characteristic = used_count as i64 - r.edge_count as i64 + facet_count as i64;

    // Valence of interior vertices.
    let mut valence = vec![0u32; input.vertices.len()];
    for &v in input.loops {
        valence[v as usize] += 1;
    }
    for v in 0..input.vertices.len() {
        if used[v] && !boundary.on_boundary(v) {
            r.interior_vertex_count += 1;
            if valence[v] == 3 {
                r.trivalent_fraction += 1.0;
            }
        }
    }
    if r.interior_vertex_count > 0 {
        r.trivalent_fraction /= r.interior_vertex_count as f64;
    }

    // Per-facet shape checks and planarity.
    for i in 0..facet_count {
        let l = facet(input, i);
        *r.side_histogram.entry(l.len()).or_insert(0) += 1;
        let (_, shape, planarity) = shapes[i];
        r.max_planarity_error = r.max_planarity_error.max(planarity);
        r.min_facet_area = r.min_facet_area.min(shape.area);
        r.max_facet_area = r.max_facet_area.max(shape.area);
        if !three_distinct(l) {
            flags[i] |= FLAG_OPEN;
            r.open_facets += 1;
        } else if !shape.simple {
            flags[i] |= FLAG_NON_SIMPLE;
        }
        if !shape.convex {
            r.non_convex_facets += 1;
            if enveloped[i]
                && (!shape.simple
                    || reflex_at_interior_corner(input, i, |v| boundary.on_boundary(v)))
            {
                flags[i] |= FLAG_NON_CONVEX;
            }
        }
        if input.diagnosed.get(i).copied().unwrap_or(false) {
            flags[i] |= FLAG_DIAGNOSTIC;
        }
    }
    // Freed before the deviations' projections, the report's largest allocation.
    drop((shapes, used, valence, boundary, overlapping));
    r.non_simple_facets = flags.iter().filter(|&&f| f & FLAG_NON_SIMPLE != 0).count();
    r.invalid_facets = flags.iter().filter(|&&f| f & INVALID_FLAGS != 0).count();
    r.flagged_facets = flags.iter().filter(|&&f| f != 0).count();

    if facet_count == 0 {
        r.min_facet_area = 0.0;
    }
    if r.edge_count == 0 {
        r.min_edge_length = 0.0;
    }
    (r, flags)
}

/// Per facet, whether the envelope makes it convex, so that a non-convex shape is a defect:
/// its seed and the seeds of every facet it shares an edge with (the planes that meet at its
/// vertices) are strictly convex on the same side. Next to a parabolic line a seed with K > 0
/// has neighbours with K <= 0, its vertices are not the envelope's, and a non-convex facet
/// there is the expected shape, as on K < 0.
fn enveloped_facets(
    convex_side: &[i8],
    facet_count: usize,
    shared_edges: &[(u32, u32, u32, u32)],
) -> Vec<bool> {
    let side = |i: u32| convex_side.get(i as usize).copied().unwrap_or(0);
    let mut enveloped: Vec<bool> = (0..facet_count as u32).map(|i| side(i) != 0).collect();
    for &(f, g, _, _) in shared_edges {
        if side(f) != side(g) {
            enveloped[f as usize] = false;
            enveloped[g as usize] = false;
        }
    }
    enveloped
}

/// Whether facet `i` turns clockwise (seen from its plane's normal) at a corner off the
/// boundary, where three of the envelope's planes meet. Its corners on the boundary follow the
/// surface's boundary curve, whose bends the envelope does not decide.
fn reflex_at_interior_corner(
    input: &ReportInput<'_>,
    i: usize,
    on_boundary: impl Fn(usize) -> bool,
) -> bool {
    let l = facet(input, i);
    let mut p = Vec::with_capacity(l.len());
    project_loop_into(
        &input.planes[i],
        l.iter().map(|&v| input.vertices[v as usize]),
        &mut p,
    );
    let reflex_inside = reflex_corners(&p).any(|k| !on_boundary(l[k] as usize));
    reflex_inside
}

/// Per facet, the mean distance from its seed to the seeds of the facets it shares an edge
/// with; where it shares none, the pattern spacing (the diagonal over the square root of the
/// facet count).
fn local_spacings(
    input: &ReportInput<'_>,
    facet_count: usize,
    shared_edges: &[(u32, u32, u32, u32)],
) -> Vec<f64> {
    let mut sum = vec![0.0f64; facet_count];
    let mut count = vec![0u32; facet_count];
    for &(f, g, _, _) in shared_edges.iter().filter(|e| e.0 != e.1) {
        let d = input.planes[f as usize]
            .point
            .distance(input.planes[g as usize].point);
        for x in [f, g] {
            sum[x as usize] += d;
            count[x as usize] += 1;
        }
    }
    let pattern = input.diagonal / (facet_count.max(1) as f64).sqrt();
    sum.iter()
        .zip(&count)
        .map(|(&s, &c)| {
            let mean = s / f64::from(c);
            if c > 0 && mean > 0.0 {
                mean
            } else {
                pattern
            }
        })
        .collect()
}

/// Whether `l` holds at least three distinct vertices (one pass, no copy of the loop).
fn three_distinct(l: &[u32]) -> bool {
    let mut first = None;
    let mut second = None;
    for &v in l {
        match (first, second) {
            (None, _) => first = Some(v),
            (Some(a), None) if v != a => second = Some(v),
            (Some(a), Some(b)) if v != a && v != b => return true,
            _ => {}
        }
    }
    false
}

/// The foot (closest point's parameters) of every vertex used by a facet, None for unused
/// vertices: known feet as given; a first-order guess refined by Newton and kept if it stays
/// with its triangle ([`accept_newton`]); otherwise Newton from the parameters of the first
/// facet that holds the vertex. Missing hints count as [`FootHint::FromSeed`].
pub(crate) fn resolve_feet(
    surface: &dyn Surface,
    wrap: &Wrap,
    uv: &[[f64; 2]],
    vertices: &[DVec3],
    offsets: &[u32],
    loops: &[u32],
    hints: FootHints<'_>,
) -> Vec<Option<[f64; 2]>> {
    map_feet(
        surface,
        wrap,
        uv,
        vertices,
        offsets,
        loops,
        hints,
        None,
        |_, f| Some(f),
        &NoProgress,
    )
}

/// The report's foot of the vertex `x` from what the facet stage knows of it (`hint`): as
/// known; a first-order guess refined by Newton and kept if it stays with its triangle
/// ([`accept_newton`]); otherwise Newton from `seed_uv`, the parameters of the first facet
/// that holds the vertex. Each to the accuracy the deviation needs ([`distance_foot`]).
pub(crate) fn resolve_foot(
    surface: &dyn Surface,
    wrap: &Wrap,
    x: DVec3,
    hint: FootHint,
    seed_uv: [f64; 2],
) -> [f64; 2] {
    match hint {
        FootHint::Known(f) => f,
        FootHint::Guess { linear, reach } => {
            let newton = distance_foot(surface, wrap, x, linear);
            if accept_newton(&wrap.domain, newton, linear, reach) {
                newton
            } else {
                distance_foot(surface, wrap, x, seed_uv)
            }
        }
        FootHint::FromSeed => distance_foot(surface, wrap, x, seed_uv),
    }
}

/// `f(vertex, foot)` for every vertex used by a facet (`unused` for the others), in parallel,
/// with the feet of [`resolve_feet`]; each vertex counts as an item of [`Stage::Report`].
// The mesh's arrays, the feet's hints, the value of unused vertices, the map and the observer.
#[allow(clippy::too_many_arguments)]
fn map_feet<T: Send + Sync + Copy>(
    surface: &dyn Surface,
    wrap: &Wrap,
    uv: &[[f64; 2]],
    vertices: &[DVec3],
    offsets: &[u32],
    loops: &[u32],
    hints: FootHints<'_>,
    unused: T,
    f: impl Fn(usize, [f64; 2]) -> T + Sync,
    progress: &dyn Progress,
) -> Vec<T> {
    use rayon::prelude::*;
    let facet_count = offsets.len().saturating_sub(1);
    let mut seed_of = vec![u32::MAX; vertices.len()];
    for i in 0..facet_count {
        for &v in &loops[offsets[i] as usize..offsets[i + 1] as usize] {
            if seed_of[v as usize] == u32::MAX {
                seed_of[v as usize] = i as u32;
            }
        }
    }
    (0..vertices.len())
        .into_par_iter()
        .map_init(
            || Tally::new(progress, Stage::Report),
            |tally, v| {
                tally.add(1);
                let Some(&seed) = seed_of.get(v).filter(|&&s| s != u32::MAX) else {
                    return unused;
                };
                let hint = hints.get(v);
                let resolved = resolve_foot(surface, wrap, vertices[v], hint, uv[seed as usize]);
                f(v, resolved)
            },
        )
        .collect()
}

/// 2D coordinates in a plane: (x - p) . (e1, e2) with e1, e2, n right-handed.
pub(crate) fn plane_frame(plane: &Plane) -> (DVec3, DVec3) {
    let (e1, e2) = plane.normal.any_orthonormal_pair();
    (e1, e2)
}

/// Shape measures of a polygon in its plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FacetShape {
    /// Area (positive when counter-clockwise seen from the normal).
    pub area: f64,
    /// Counter-clockwise, at least 3 vertices, no two non-adjacent edges intersecting.
    pub simple: bool,
    /// Simple and every turn to the left.
    pub convex: bool,
}

/// The loop `points` in `plane`'s frame ([`plane_frame`], origin at its point), into `p`.
pub(crate) fn project_loop_into(
    plane: &Plane,
    points: impl Iterator<Item = DVec3>,
    p: &mut Vec<DVec2>,
) {
    let (e1, e2) = plane_frame(plane);
    p.clear();
    p.extend(points.map(|x| {
        let d = x - plane.point;
        DVec2::new(d.dot(e1), d.dot(e2))
    }));
}

/// The signed area of the loop `p`, half the sum of p_k x p_(k+1) from k = 0 in this order
/// (as [`facet_shape_into`] sums it).
pub(crate) fn loop_area(p: &[DVec2]) -> f64 {
    let n = p.len();
    let mut area = 0.0;
    for k in 0..n {
        area += p[k].perp_dot(p[(k + 1) % n]);
    }
    area * 0.5
}

/// Whether two non-adjacent edges of the loop `p` touch ([`crate::sanity::crosses`], the same
/// test as `sanity_check`: touching counts, so the two never disagree). That test is
/// symmetric in its two edges, so the verdict is the same for the loop started at any of its
/// vertices.
pub(crate) fn loop_crosses(p: &[DVec2]) -> bool {
    let n = p.len();
    for a in 0..n {
        for b in a + 2..n {
            if a == 0 && b == n - 1 {
                continue;
            }
            if crate::sanity::crosses(p[a], p[(a + 1) % n], p[b], p[(b + 1) % n]) {
                return true;
            }
        }
    }
    false
}

/// Measures a polygon lying (nearly) in `plane`, with a caller's buffer for the 2D points (no
/// allocation per facet).
pub(crate) fn facet_shape_into(
    plane: &Plane,
    points: impl Iterator<Item = DVec3>,
    p: &mut Vec<DVec2>,
) -> FacetShape {
    project_loop_into(plane, points, p);
    let n = p.len();
    if n < 3 {
        return FacetShape {
            area: 0.0,
            simple: false,
            convex: false,
        };
    }
    let mut area = 0.0;
    for k in 0..n {
        area += p[k].perp_dot(p[(k + 1) % n]);
    }
    area *= 0.5;
    let simple = area > 0.0 && !loop_crosses(p);
    let convex = simple && reflex_corners(p).next().is_none();
    FacetShape {
        area,
        simple,
        convex,
    }
}

/// The corners k of the loop `p` (at least 3 points) where it does not turn
/// counter-clockwise: the turn (p_k - p_(k-1)) x (p_(k+1) - p_k) is below -1e-12 times the
/// longest edge squared, or not a number.
fn reflex_corners(p: &[DVec2]) -> impl Iterator<Item = usize> + '_ {
    let n = p.len();
    let scale = (0..n)
        .map(|k| (p[(k + 1) % n] - p[k]).length())
        .fold(0.0, f64::max);
    let tolerance = 1e-12 * scale * scale;
    (0..n).filter(move |&k| {
        let (a, b, c) = (p[(k + n - 1) % n], p[k], p[(k + 1) % n]);
        !((b - a).perp_dot(c - b) >= -tolerance)
    })
}

/// Reusable buffers for the loop points of the two facets of a pair.
#[derive(Default)]
struct LoopBuffers {
    f: Vec<DVec3>,
    g: Vec<DVec3>,
}

/// Whether the facets f and g sharing the edge (a, b) overlap (both simple; convex pairs by
/// their centroids' sides, the others by [`edge_pair_overlaps`]).
fn pair_overlaps(
    input: &ReportInput<'_>,
    shapes: &[(DVec3, FacetShape, f64)],
    buffers: &mut LoopBuffers,
    (f, g, a, b): (u32, u32, u32, u32),
) -> bool {
    let (sf, sg) = (&shapes[f as usize], &shapes[g as usize]);
    if !(sf.1.simple && sg.1.simple) {
        return false;
    }
    if sf.1.convex && sg.1.convex {
        // Two convex polygons sharing the edge (a, b) (convex also seen along the mean
        // normal, an affine image) overlap exactly when they lie on the same side of its
        // line: their centroids do.
        let (pa, pb) = (input.vertices[a as usize], input.vertices[b as usize]);
        let normal = input.planes[f as usize].normal + input.planes[g as usize].normal;
        let side = |c: DVec3| (pb - pa).cross(c - pa).dot(normal);
        return side(sf.0) * side(sg.0) > 0.0;
    }
    edge_pair_overlaps(input, f, g, a, b, buffers)
}

/// The points of facet f's loop.
fn loop_points(input: &ReportInput<'_>, f: u32) -> Vec<DVec3> {
    let mut out = Vec::new();
    loop_points_into(input, f, &mut out);
    out
}

/// The points of facet f's loop, into `out` (cleared first).
fn loop_points_into(input: &ReportInput<'_>, f: u32, out: &mut Vec<DVec3>) {
    out.clear();
    out.extend(
        facet(input, f as usize)
            .iter()
            .map(|&v| input.vertices[v as usize]),
    );
}

/// Whether simple facets f and g, sharing the edge (a, b), overlap seen along their mean
/// normal (module doc): the line through a and b separates them, or the full test decides.
fn edge_pair_overlaps(
    input: &ReportInput<'_>,
    f: u32,
    g: u32,
    a: u32,
    b: u32,
    buffers: &mut LoopBuffers,
) -> bool {
    let normal = input.planes[f as usize].normal + input.planes[g as usize].normal;
    let Some(normal) = normal.try_normalize() else {
        return false;
    };
    let (e1, e2) = normal.any_orthonormal_pair();
    let origin = input.vertices[a as usize];
    let to2 = |x: DVec3| DVec2::new((x - origin).dot(e1), (x - origin).dot(e2));
    let direction = to2(input.vertices[b as usize]);
    let length = direction.length();
    let overlap = |buffers: &mut LoopBuffers| {
        loop_points_into(input, f, &mut buffers.f);
        loop_points_into(input, g, &mut buffers.g);
        polygons_overlap(&buffers.f, &buffers.g, normal)
    };
    if !(length > 0.0) {
        return overlap(buffers);
    }
    // Signed distances of the other vertices from the line, beyond a rounding margin.
    let side = |h: u32| {
        let (mut positive, mut negative) = (false, false);
        for &v in facet(input, h as usize) {
            if v == a || v == b {
                continue;
            }
            let d = direction.perp_dot(to2(input.vertices[v as usize])) / length;
            positive |= d > SEPARATION_MARGIN * length;
            negative |= d < -SEPARATION_MARGIN * length;
        }
        (positive, negative)
    };
    let (fp, fn_) = side(f);
    let (gp, gn) = side(g);
    let separated = (fp && !fn_ && gn && !gp) || (fn_ && !fp && gp && !gn);
    !separated && overlap(buffers)
}

/// Overlapping pairs of simple facets that share a vertex but no edge: where four or more
/// facets meet at a vertex, and at a boundary vertex whose fan of facets (the first and the
/// last share no edge) may wrap past a full turn.
fn vertex_pairs_overlapping(
    input: &ReportInput<'_>,
    facet_count: usize,
    simple: &[bool],
    shared_edges: &[(u32, u32, u32, u32)],
) -> Vec<(u32, u32)> {
    // Each vertex's facets (in facet order) by a counting sort: one flat array, no list per
    // vertex.
    let vertex_count = input.vertices.len();
    let mut start = vec![0u32; vertex_count + 1];
    for f in 0..facet_count {
        for &v in facet(input, f) {
            start[v as usize + 1] += 1;
        }
    }
    // A vertex of k facets has k (k - 1) / 2 pairs; where fewer edges of two facets end
    // there, some pair shares only the vertex (usually k = 3 on an interior vertex: three
    // edges, no such pair).
    let mut shared_at = vec![0u32; vertex_count];
    for &(_, _, a, b) in shared_edges {
        shared_at[a as usize] += 1;
        shared_at[b as usize] += 1;
    }
    let loose = |v: usize| {
        let k = start[v + 1];
        k * k.saturating_sub(1) / 2 > shared_at[v]
    };
    if !(0..vertex_count).any(loose) {
        return Vec::new();
    }
    let loose: Vec<bool> = (0..vertex_count).map(loose).collect();
    drop(shared_at);
    for v in 0..vertex_count {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut incident = vec![0u32; start[vertex_count] as usize];
    for f in 0..facet_count {
        for &v in facet(input, f) {
            incident[fill[v as usize] as usize] = f as u32;
            fill[v as usize] += 1;
        }
    }
    let adjacent: std::collections::HashSet<(u32, u32)> = shared_edges
        .iter()
        .map(|&(f, g, _, _)| (f.min(g), f.max(g)))
        .collect();
    let mut out = Vec::new();
    let lists = (0..vertex_count)
        .filter(|&v| loose[v])
        .map(|v| &incident[start[v] as usize..start[v + 1] as usize]);
    for list in lists {
        for (k, &f) in list.iter().enumerate() {
            for &g in &list[k + 1..] {
                let pair = (f.min(g), f.max(g));
                if f == g || adjacent.contains(&pair) || !simple[f as usize] || !simple[g as usize]
                {
                    continue;
                }
                let normal = input.planes[f as usize].normal + input.planes[g as usize].normal;
                if let Some(normal) = normal.try_normalize() {
                    if polygons_overlap(&loop_points(input, f), &loop_points(input, g), normal) {
                        out.push(pair);
                    }
                }
            }
        }
    }
    out
}

/// Every loop edge as (lo, hi, facet), sorted: counting sort on lo, then each run of equal
/// lo (a vertex's few edges) sorted, which is the order of a full sort.
fn sorted_edges(input: &ReportInput<'_>, facet_count: usize) -> Vec<(u32, u32, u32)> {
    let vertex_count = input.vertices.len();
    let mut start = vec![0u32; vertex_count + 1];
    let each = |f: &mut dyn FnMut(u32, u32, u32)| {
        for i in 0..facet_count {
            let l = facet(input, i);
            for k in 0..l.len() {
                let (a, b) = (l[k], l[(k + 1) % l.len()]);
                f(a.min(b), a.max(b), i as u32);
            }
        }
    };
    each(&mut |lo, _, _| start[lo as usize + 1] += 1);
    for v in 0..vertex_count {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut edges = vec![(0u32, 0u32, 0u32); start[vertex_count] as usize];
    each(&mut |lo, hi, f| {
        edges[fill[lo as usize] as usize] = (lo, hi, f);
        fill[lo as usize] += 1;
    });
    for v in 0..vertex_count {
        let run = &mut edges[start[v] as usize..start[v + 1] as usize];
        if run.len() > 1 {
            run.sort_unstable();
        }
    }
    edges
}
