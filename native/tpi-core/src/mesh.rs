//! Stage 4 of the pipeline: facet loops -> mesh.
//!
//! The facet stage ([`crate::facets`]) gives one vertex per dual triangle (the meeting point of
//! three tangent planes) and each facet's loop as items: triangle vertices, boundary crossings,
//! edge points, corners. Assembly turns them into one indexed polygon mesh:
//!
//! 1. **Welding.** The vertices of two adjacent triangles (a, b, c) and (b, a, d) are one mesh
//!    vertex when closer than the weld distance, or, on the convex path, when their edge runs
//!    against the direction of the regular triangulation ([`edge_reversed`]): four or more
//!    planes through (nearly) one point. Welds are resolved by union-find, the smallest
//!    triangle index representing its class.
//! 2. **Numbering.** Vertices are numbered in the order the facets first use them (facet 0's
//!    loop first), so the output does not depend on the threads.
//! 3. **Loops.** Consecutive repeats (welded vertices) are dropped; a loop of fewer than three
//!    vertices is an open facet, diagnosed.
//! 4. **Coincident boundary vertices.** A boundary crossing or corner vertex within the weld
//!    distance of the vertex beside it in every loop that holds it is merged into that vertex
//!    (a facet edge meeting the boundary exactly at a three-plane vertex), so that no
//!    zero-length edge turns facets non-simple.

use std::collections::HashMap;

use glam::DVec3;
use rayon::prelude::*;

use crate::diagnostics::Diagnostic;
use crate::facets::{
    edge_point, Crossing, FacetChunk, FacetParams, Item, TriangleVertex, VertexKind, ITEM_INDEX,
};
use crate::planes::Plane;
use crate::progress::{Stage, Stages, Tally};
use crate::triangulation::{DualTriangulation, NO_TRIANGLE};

/// The indexed polygon mesh before reporting.
#[derive(Clone, Debug, Default)]
pub(crate) struct FacetMesh {
    /// Vertex positions.
    pub vertices: Vec<DVec3>,
    /// What each vertex is.
    pub vertex_kinds: Vec<VertexKind>,
    /// Facet i's loop is `loops[offsets[i]..offsets[i + 1]]`.
    pub offsets: Vec<u32>,
    /// Flat vertex loops.
    pub loops: Vec<u32>,
    /// Problems found.
    pub diagnostics: Vec<Diagnostic>,
    /// Wall-clock time of the assembly (welding, numbering, loops) in milliseconds.
    pub assembly_ms: f64,
    /// The Newton feet of the vertices that are no triangle's (boundary crossings) where the
    /// facet stage computed them, by vertex, ascending: with the triangle vertices' hints
    /// what the quality report's deviation starts from (`FootHints::Mesh`), so that no
    /// projection is done twice.
    pub known_feet: Vec<(u32, [f64; 2])>,
    /// Per triangle of the dual structure, its vertex (for live editing).
    pub(crate) triangle_vertices: Vec<TriangleVertex>,
    /// Per mesh vertex, the triangle it is the meeting point of (welds resolved to the
    /// representative), or `u32::MAX` for boundary, corner and stand-in vertices.
    pub(crate) vertex_source: Vec<u32>,
    /// Per facet, whether its loop is just the vertices of its closed fan of triangles
    /// (all exact and inside): no boundary, no stand-in.
    pub(crate) facet_simple: Vec<bool>,
    /// The triangles whose vertices were welded to another's.
    pub(crate) welded: Vec<u32>,
}

impl FacetMesh {
    /// Facet f's loop of vertex indices.
    pub(crate) fn facet_loop(&self, f: usize) -> &[u32] {
        &self.loops[self.offsets[f] as usize..self.offsets[f + 1] as usize]
    }

    /// Facet f's polygon: the positions of its loop's vertices.
    pub(crate) fn polygon(&self, f: usize) -> Vec<DVec3> {
        self.facet_loop(f)
            .iter()
            .map(|&v| self.vertices[v as usize])
            .collect()
    }
}

/// The slope frame's tangent axes and the points' slopes, where the dual structure is the
/// regular triangulation of the slopes (the convex path): what [`edge_reversed`] reads.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SlopeView<'a> {
    /// (e1, e2) of the slope frame.
    pub axes: (DVec3, DVec3),
    /// Per point, its slopes.
    pub slopes: &'a [[f64; 2]],
}

/// Whether the facet edge from x1, the vertex of the triangle (a, b, c), to x2, the vertex of
/// the adjacent triangle (b, a, d), runs against the direction the regular triangulation of
/// the slopes gives it.
///
/// Along the line T_a ∩ T_b the upper envelope max_i (s_i . x + c_i) (in frame coordinates
/// x = (X.e1, X.e2)) leaves plane c behind and meets plane d ahead, so the exact edge satisfies
/// (x2 - x1) . (s_d - s_c) > 0. Where the computed vertices say otherwise, their distance is
/// below their rounding error (four planes nearly through one point, the edge nearly of zero
/// length): the two are one vertex of the mesh, else the edge would turn both facets that
/// hold it non-simple.
pub(crate) fn edge_reversed(
    axes: (DVec3, DVec3),
    x1: DVec3,
    x2: DVec3,
    s_c: [f64; 2],
    s_d: [f64; 2],
) -> bool {
    let w = x2 - x1;
    w.dot(axes.0) * (s_d[0] - s_c[0]) + w.dot(axes.1) * (s_d[1] - s_c[1]) <= 0.0
}

/// What the assembly of facet loops into a mesh reads.
pub(crate) struct Assembly<'a> {
    pub(crate) tri: &'a DualTriangulation,
    pub(crate) triangle_vertices: Vec<TriangleVertex>,
    pub(crate) chunks: Vec<FacetChunk>,
    pub(crate) crossings: &'a [Crossing],
    /// Point and normal over each domain corner; None where no facet holds a corner.
    pub(crate) corners: Option<&'a [(DVec3, DVec3)]>,
    pub(crate) planes: &'a [Plane],
    pub(crate) params: &'a FacetParams,
    /// Points from this index on are ghosts ([`crate::ghosts`]): the vertices of their
    /// triangles are boundary vertices.
    pub(crate) ghosts_from: Option<u32>,
    /// On the convex path: adjacent vertices whose edge is reversed are welded too.
    pub(crate) slopes: Option<SlopeView<'a>>,
    pub(crate) diagnostics: Vec<Diagnostic>,
    /// The assembly is the mesh stage: it starts it, with the facets as its total, and counts
    /// each facet as it is numbered.
    pub(crate) stages: &'a Stages<'a>,
}

/// Welding, vertex numbering in facet order, loops (see the module doc).
pub(crate) fn assemble(a: Assembly<'_>) -> FacetMesh {
    let Assembly {
        tri,
        triangle_vertices,
        chunks,
        crossings,
        corners,
        planes,
        params,
        ghosts_from,
        slopes,
        mut diagnostics,
        stages,
    } = a;
    let uv_len = chunks.iter().map(|c| c.ends.len()).sum::<usize>();
    stages.enter(Stage::Mesh, Some(uv_len));
    let mut tally = Tally::new(stages.observer(), Stage::Mesh);
    // 4. Welding of coincident triangle vertices across interior edges.
    let assembly = std::time::Instant::now();
    let weld_pairs: Vec<(u32, u32)> = (0..tri.len())
        .into_par_iter()
        .flat_map_iter(|t| {
            let weld = params.weld_distance;
            let tv = &triangle_vertices;
            (0..3).filter_map(move |k| {
                let other = tri.neighbours[t][k];
                if other == NO_TRIANGLE || (other as usize) < t {
                    return None;
                }
                let (a, b) = (t, other as usize);
                let reversed = || {
                    slopes.is_some_and(|view| {
                        let c = tri.triangles[a][k];
                        let s = view.slopes;
                        tri.opposite(b, a as u32).is_some_and(|d| {
                            edge_reversed(
                                view.axes,
                                tv[a].point,
                                tv[b].point,
                                s[c as usize],
                                s[d as usize],
                            )
                        })
                    })
                };
                let distance = tv[a].point.distance(tv[b].point);
                (tv[a].exact
                    && tv[b].exact
                    && (distance <= weld || (distance <= params.reversal_distance && reversed())))
                .then_some((a as u32, b as u32))
            })
        })
        .collect();
    // Unions in the order of `DualTriangulation::edges` (by triangle, then side): the pairs
    // were collected in that order.
    let welded: Vec<u32> = weld_pairs.iter().flat_map(|&(a, b)| [a, b]).collect();
    let mut representative: Vec<u32> = if weld_pairs.is_empty() {
        Vec::new()
    } else {
        (0..tri.len() as u32).collect()
    };
    for &(a, b) in &weld_pairs {
        let (ra, rb) = (find(&mut representative, a), find(&mut representative, b));
        if ra != rb {
            let (low, high) = (ra.min(rb), ra.max(rb));
            representative[high as usize] = low;
        }
    }

    // 5. Vertex numbering in facet order (deterministic), corners per facet.
    let mut mesh = FacetMesh {
        offsets: Vec::with_capacity(uv_len + 1),
        ..FacetMesh::default()
    };
    let vertex_estimate = tri.len() + crossings.len() + 4;
    mesh.vertices.reserve(vertex_estimate);
    mesh.vertex_kinds.reserve(vertex_estimate);
    mesh.loops
        .reserve(chunks.iter().map(|c| c.items.len()).sum());
    debug_assert!(tri.len() < ITEM_INDEX as usize);
    mesh.offsets.push(0);
    let mut triangle_id = vec![u32::MAX; tri.len()];
    let mut crossing_id = vec![u32::MAX; crossings.len()];
    let mut edge_point_id: HashMap<(u32, u32, u32), u32> = HashMap::new();
    let mut corner_claims = vec![0u32; corners.map_or(4, <[_]>::len)];
    let mut i = 0usize;
    for chunk in chunks {
        let count = chunk.ends.len();
        let mut start_item = 0usize;
        let mut walk_diagnostics = chunk.diagnostics.into_iter().peekable();
        mesh.facet_simple.extend_from_slice(&chunk.simple);
        for &end_item in &chunk.ends {
            // Diagnostics of this facet's walk come before those of its assembly.
            while let Some((_, d)) = walk_diagnostics.next_if(|(f, _)| *f as usize == i) {
                diagnostics.push(d);
            }
            let items = (start_item..end_item as usize).map(|k| chunk.items.get(k));
            start_item = end_item as usize;
            let start = mesh.loops.len();
            for item in items {
                let id = match item {
                    Item::Triangle(t) => {
                        let r = if representative.is_empty() {
                            t as usize
                        } else {
                            find(&mut representative, t) as usize
                        };
                        if triangle_id[r] == u32::MAX {
                            let v = &triangle_vertices[r];
                            let ghost = ghosts_from
                                .is_some_and(|g| tri.triangles[r].iter().any(|&x| x >= g));
                            let kind = if ghost {
                                VertexKind::Boundary
                            } else {
                                VertexKind::Interior
                            };
                            triangle_id[r] = push_vertex(&mut mesh, v.point, kind, None, r as u32);
                        }
                        triangle_id[r]
                    }
                    Item::EdgePoint { triangle, lo, hi } => {
                        let stand_in = triangle_vertices[triangle as usize].point;
                        match edge_point(
                            &planes[lo as usize],
                            &planes[hi as usize],
                            stand_in,
                            params.far_vertex_factor,
                        ) {
                            Some(position) => {
                                *edge_point_id.entry((triangle, lo, hi)).or_insert_with(|| {
                                    push_vertex(
                                        &mut mesh,
                                        position,
                                        VertexKind::Interior,
                                        None,
                                        u32::MAX,
                                    )
                                })
                            }
                            None => {
                                // No usable line: a vertex of this facet alone, in its own plane.
                                let plane = &planes[i];
                                let position =
                                    stand_in - plane.normal * plane.signed_distance(stand_in);
                                push_vertex(
                                    &mut mesh,
                                    position,
                                    VertexKind::Interior,
                                    None,
                                    u32::MAX,
                                )
                            }
                        }
                    }
                    Item::Crossing(c) => {
                        if crossing_id[c as usize] == u32::MAX {
                            let crossing = &crossings[c as usize];
                            crossing_id[c as usize] = push_vertex(
                                &mut mesh,
                                crossing.point,
                                VertexKind::Boundary,
                                crossing.foot,
                                u32::MAX,
                            );
                        }
                        crossing_id[c as usize]
                    }
                    Item::Corner(c) => {
                        corner_claims[c as usize] += 1;
                        let Some(corners) = corners else { continue };
                        let (point, normal) = corners[c as usize];
                        let plane = &planes[i];
                        let denominator = plane.normal.dot(normal);
                        let mu = plane.normal.dot(plane.point - point) / denominator;
                        let position = point + normal * mu;
                        if !position.is_finite() || denominator.abs() < 1e-9 {
                            diagnostics.push(Diagnostic::CornerUnreachable {
                                point: i as u32,
                                corner: c,
                            });
                            continue;
                        }
                        push_vertex(&mut mesh, position, VertexKind::Corner, None, u32::MAX)
                    }
                };
                if mesh.loops.len() == start || mesh.loops[mesh.loops.len() - 1] != id {
                    mesh.loops.push(id);
                }
            }
            while mesh.loops.len() > start + 1
                && mesh.loops[start] == mesh.loops[mesh.loops.len() - 1]
            {
                mesh.loops.pop();
            }
            if mesh.loops.len() - start < 3 {
                diagnostics.push(Diagnostic::OpenFacet {
                    point: i as u32,
                    reason: "fewer than three vertices".into(),
                });
            }
            mesh.offsets.push(mesh.loops.len() as u32);
            i += 1;
        }
        tally.add(count);
    }
    for (corner, &claims) in corner_claims.iter().enumerate() {
        if corners.is_some() && claims != 1 {
            diagnostics.push(Diagnostic::CornerClaims {
                corner: corner as u32,
                claims,
            });
        }
    }
    drop_coincident_crossings(&mut mesh, params.weld_distance);
    mesh.diagnostics = diagnostics;
    mesh.welded = welded;
    mesh.triangle_vertices = triangle_vertices;
    mesh.assembly_ms = assembly.elapsed().as_secs_f64() * 1e3;
    mesh
}

/// Step 4 of the module doc: a boundary crossing or corner vertex v that lies within the weld distance of a
/// neighbour w in its loop, and has w beside it in the loop of every facet that holds it, is
/// merged into w (a facet edge reaching the boundary, or a corner's normal line meeting a
/// facet, exactly at a vertex where three planes meet): kept, the zero-length edge v-w would
/// turn the facets non-simple. A merge that would leave a facet fewer than three vertices is
/// not made. Vertices are renumbered in order; nothing changes when no such pair is found.
pub(crate) fn drop_coincident_crossings(mesh: &mut FacetMesh, weld: f64) {
    let is_crossing = |mesh: &FacetMesh, v: u32| match mesh.vertex_kinds[v as usize] {
        VertexKind::Corner => true,
        VertexKind::Boundary => mesh.vertex_source[v as usize] == u32::MAX,
        VertexKind::Interior => false,
    };
    let facets = mesh.offsets.len() - 1;
    let loop_of = |mesh: &FacetMesh, f: usize| mesh.facet_loop(f).to_vec();
    // Candidate pairs (v, w), in loop order (read in place: this runs on every mesh).
    let mut candidates: Vec<(u32, u32)> = Vec::new();
    for f in 0..facets {
        let lp = mesh.facet_loop(f);
        let n = lp.len();
        for k in 0..n {
            let v = lp[k];
            if !is_crossing(mesh, v) {
                continue;
            }
            for w in [lp[(k + 1) % n], lp[(k + n - 1) % n]] {
                if w != v && mesh.vertices[v as usize].distance(mesh.vertices[w as usize]) <= weld {
                    candidates.push((v, w));
                }
            }
        }
    }
    if candidates.is_empty() {
        return;
    }
    // Per candidate v, the facets holding it (ascending, once per appearance): `slot[v]`
    // indexes its list.
    let mut slot = vec![u32::MAX; mesh.vertices.len()];
    let mut holders: Vec<Vec<usize>> = Vec::new();
    for &(v, _) in &candidates {
        if slot[v as usize] == u32::MAX {
            slot[v as usize] = holders.len() as u32;
            holders.push(Vec::new());
        }
    }
    for f in 0..facets {
        for &v in mesh.facet_loop(f) {
            if let Some(list) = holders.get_mut(slot[v as usize] as usize) {
                list.push(f);
            }
        }
    }
    let mut merged: Vec<u32> = (0..mesh.vertices.len() as u32).collect();
    let mut any = false;
    for (v, w) in candidates {
        if merged[v as usize] != v || merged[w as usize] != w {
            continue;
        }
        let facets_of_v = &holders[slot[v as usize] as usize];
        let beside = |lp: &[u32]| {
            let n = lp.len();
            (0..n).any(|k| lp[k] == v && (lp[(k + 1) % n] == w || lp[(k + n - 1) % n] == w))
        };
        // Every facet holding v holds w beside it, and keeps three vertices without v.
        let ok = facets_of_v.iter().all(|&f| {
            let lp = loop_of(mesh, f);
            let distinct = lp
                .iter()
                .map(|&x| merged[x as usize])
                .filter(|&x| x != v)
                .collect::<std::collections::BTreeSet<u32>>()
                .len();
            beside(&lp) && distinct >= 3
        });
        if ok {
            merged[v as usize] = w;
            any = true;
        }
    }
    if any {
        apply_merges(mesh, &mut merged);
    }
}

/// Merges each boundary crossing with every vertex within `weld` of it into one vertex,
/// whichever facets hold them: where a triangle vertex lies exactly on the wall (as a grid on a
/// ruled surface gives), the edges ending there get crossings at that point too, and kept
/// apart they would give zero-length edges. Points that coincide lie in every plane either
/// lies in, so every facet stays planar. Loops lose the repeated vertex; nothing changes
/// without such a pair.
pub(crate) fn weld_coincident_crossings(mesh: &mut FacetMesh, weld: f64) {
    let is_crossing = |v: u32| {
        mesh.vertex_kinds[v as usize] == VertexKind::Boundary
            && mesh.vertex_source[v as usize] == u32::MAX
    };
    // A pair welds when one of them is a crossing, their x differ by at most `weld` and
    // their distance is at most `weld`; a vertex with a coordinate that is not finite never
    // does (its distance is not finite). So only the crossings are sorted by x, and each
    // vertex looks up those whose x lies within `weld` of its own: fl(x_v - x_c) and
    // fl(x_c - x_v) are monotone in x_c, so they are a run of the sorted crossings.
    let mut by_x: Vec<u32> = (0..mesh.vertices.len() as u32)
        .filter(|&v| is_crossing(v) && mesh.vertices[v as usize].is_finite())
        .collect();
    if by_x.is_empty() {
        return;
    }
    by_x.sort_by(|&a, &b| {
        mesh.vertices[a as usize]
            .x
            .total_cmp(&mesh.vertices[b as usize].x)
    });
    let xs: Vec<f64> = by_x.iter().map(|&c| mesh.vertices[c as usize].x).collect();
    let mut merged: Vec<u32> = (0..mesh.vertices.len() as u32).collect();
    let mut any = false;
    for a in 0..mesh.vertices.len() as u32 {
        let pa = mesh.vertices[a as usize];
        if !pa.is_finite() {
            continue;
        }
        let first = xs.partition_point(|&cx| pa.x - cx > weld);
        for (&b, &cx) in by_x[first..].iter().zip(&xs[first..]) {
            if cx - pa.x > weld {
                break;
            }
            let pb = mesh.vertices[b as usize];
            if b == a || pa.distance(pb) > weld || pa.distance(pb).is_nan() {
                continue;
            }
            let (ra, rb) = (find(&mut merged, a), find(&mut merged, b));
            if ra != rb {
                // A triangle vertex stays what it is: the crossings go into it. The vertex
                // kept is the least by (crossing, index), whatever the order of the pairs.
                let (keep, gone) = match (is_crossing(ra), is_crossing(rb)) {
                    (true, false) => (rb, ra),
                    (false, true) => (ra, rb),
                    _ => (ra.min(rb), ra.max(rb)),
                };
                merged[gone as usize] = keep;
                any = true;
            }
        }
    }
    if any {
        apply_merges(mesh, &mut merged);
    }
}

/// Rewrites the mesh after merges: `merged` holds, per vertex, the vertex it was merged into
/// (itself when kept; chains are followed to their end). Kept vertices are renumbered in
/// order, the others removed, and each loop takes the kept vertices, dropping a vertex that
/// repeats its predecessor (also across the loop's end).
fn apply_merges(mesh: &mut FacetMesh, merged: &mut [u32]) {
    let drop: Vec<bool> = (0..mesh.vertices.len() as u32)
        .map(|v| find(merged, v) != v)
        .collect();
    let mut renumber = vec![u32::MAX; mesh.vertices.len()];
    let mut next = 0u32;
    for (v, slot) in renumber.iter_mut().enumerate() {
        if !drop[v] {
            *slot = next;
            next += 1;
        }
    }
    let facets = mesh.offsets.len() - 1;
    let mut loops = Vec::with_capacity(mesh.loops.len());
    let mut offsets = Vec::with_capacity(mesh.offsets.len());
    offsets.push(0);
    for f in 0..facets {
        let start = loops.len();
        for k in mesh.offsets[f] as usize..mesh.offsets[f + 1] as usize {
            let id = renumber[find(merged, mesh.loops[k]) as usize];
            if loops.len() == start || loops[loops.len() - 1] != id {
                loops.push(id);
            }
        }
        while loops.len() > start + 1 && loops[start] == loops[loops.len() - 1] {
            loops.pop();
        }
        offsets.push(loops.len() as u32);
    }
    retain_indexed(&mut mesh.vertices, &drop);
    retain_indexed(&mut mesh.vertex_kinds, &drop);
    // Kept vertices keep their order: the feet stay ascending.
    mesh.known_feet.retain(|&(v, _)| !drop[v as usize]);
    for (v, _) in &mut mesh.known_feet {
        *v = renumber[*v as usize];
    }
    retain_indexed(&mut mesh.vertex_source, &drop);
    mesh.loops = loops;
    mesh.offsets = offsets;
}

/// Removes the items whose index is marked in `drop`, keeping the order.
fn retain_indexed<T>(values: &mut Vec<T>, drop: &[bool]) {
    let mut index = 0;
    values.retain(|_| {
        index += 1;
        !drop[index - 1]
    });
}

/// Adds a vertex: the vertex of triangle `source` (its foot hint is the triangle vertex's), or
/// with `source` `u32::MAX` another, whose Newton foot is `known` where computed.
fn push_vertex(
    mesh: &mut FacetMesh,
    position: DVec3,
    kind: VertexKind,
    known: Option<[f64; 2]>,
    source: u32,
) -> u32 {
    let v = mesh.vertices.len() as u32;
    mesh.vertex_source.push(source);
    mesh.vertices.push(position);
    mesh.vertex_kinds.push(kind);
    if let Some(foot) = known.filter(|_| source == u32::MAX) {
        mesh.known_feet.push((v, foot));
    }
    v
}

/// The root of x in a union-find forest (`parent[r] == r` at a root), halving the path.
pub(crate) fn find(representative: &mut [u32], mut x: u32) -> u32 {
    while representative[x as usize] != x {
        let parent = representative[x as usize];
        representative[x as usize] = representative[parent as usize];
        x = parent;
    }
    x
}
