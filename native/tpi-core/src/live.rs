//! Live editing: a discretised surface that follows edits of its pattern one point at a time.
//!
//! [`LiveSurface`] holds a surface, its pattern and what the pipeline computed for them. Moving,
//! adding or removing one pattern point updates the dual structure where it changed and
//! recomputes only the facets around it; [`LiveSurface::discretisation`] then assembles the
//! result, which is the [`crate::discretise()`] of the edited pattern, bit for bit (the same
//! facets in the same order, the same vertex positions and numbering, the same report).
//!
//! # The incremental path
//!
//! It applies where the dual structure is the envelope's own: a convex surface (every pattern
//! point strictly convex on the same side, [`crate::neighbours::gradient_embedding`]) with the
//! envelope repair on. There the structure is the regular triangulation of the tangent planes'
//! slopes, which does not depend on how it was reached, so a local update (remove the point:
//! fill its star with regular ears; insert it: split the triangle holding its slopes, then
//! flip by the envelope test) gives the structure of a full run. An edit takes it when
//! - the edited point and every point whose triangles change have simple facets before and
//!   after the edit: closed fans of exact vertices inside the domain (no boundary crossing,
//!   no corner, no ill-conditioned stand-in, no weld), and the new triangles are counter-
//!   clockwise in the pattern's coordinates like the rest;
//! - the surface points' bounding box, which scales the tolerances, does not change;
//! - the moved or added point is not a duplicate, its slopes lie inside the structure's hull,
//!   and no flip meets a non-convex quad.
//!
//! Otherwise (and for a new surface, a mixed or saddle-shaped surface, the envelope repair
//! off, points near the boundary or next to welded vertices) the edit runs the whole pipeline
//! again.
//! [`LiveStats`] counts both kinds.
//!
//! # Cost
//!
//! An incremental move evaluates the point once, re-triangulates its star (about 6 triangles
//! removed, 6 created, a few flips), computes about 12 facet vertices and their feet for the
//! report, all in O(1) (point location by a grid of pattern cells). Removing a point also
//! renumbers the points after it (O(n), as the facets after it move down by one).
//! [`LiveSurface::discretisation`] assembles the mesh in O(n) when asked for after edits
//! (numbering, loops, the report's aggregates), without projecting anything again.
//!
//! # What changed
//!
//! A host that redraws after every edit needs only what the edit changed:
//! [`LiveSurface::take_changes`] lists the facets whose loops or vertex positions changed
//! since the last call, with their loops and planes, and the vertices whose positions are
//! new, in O(what changed). Their vertices are numbered by the live structure (a triangle's
//! slot, a boundary vertex's place), not as in the assembled mesh: an id keeps its position
//! until a later change lists it again, and where an edit ran the whole pipeline the
//! numbering starts over and the changes list everything.

use std::collections::HashMap;

use glam::DVec3;

use crate::diagnostics::{diagnosed_points, Diagnostic};
use crate::diffgeo::LocalGeometry;
use crate::discretise::{
    plane_adjustments, run, Discretisation, DiscretiseOptions, MeshTopology, PipelineState,
    PlaneMode, Seed, Timings,
};
use crate::error::TpiError;
use crate::facets::{single_triangle_vertex, FootHint, TriangleVertex, VertexKind};
use crate::mesh::edge_reversed;
use crate::neighbours::{slope_repairs, NeighbourStats, SlopeFrame};
use crate::planes::Plane;
use crate::predicates::{orient2d, power_illegal};
use crate::progress::NoProgress;
use crate::projection::Wrap;
use crate::quality::{report, resolve_foot, ReportInput};
use crate::regular::hilbert_key;
use crate::samples::curvature_class;
use crate::surface::Surface;
use crate::tolerance::DUPLICATE_UV_TOLERANCE;
use crate::triangulation::{orient, DualTriangulation, NO_TRIANGLE};

/// How many edits took the incremental path and how many ran the whole pipeline.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LiveStats {
    /// Edits applied by a local update.
    pub incremental: usize,
    /// Edits (and constructions) that ran the whole pipeline.
    pub full: usize,
}

/// What changed in the mesh of a [`LiveSurface`] since the last
/// [`LiveSurface::take_changes`] (or since it was made).
///
/// Vertex ids are the live structure's own numbering (see the module doc), below
/// `vertex_id_bound`; a facet's loop is counter-clockwise seen from its normal and starts at
/// the same vertex as in [`LiveSurface::discretisation`], so that with the listed vertices'
/// positions it is that mesh's facet, vertex for vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LiveChanges {
    /// The numbering started over (the first call, an edit that ran the whole pipeline, a
    /// new surface): every facet and every vertex is listed, and ids from before mean
    /// nothing.
    pub everything: bool,
    /// Facets in the mesh now (facet i belongs to pattern point i). Facets from this count
    /// on are gone; a removed point renumbers the facets after it, and those are listed.
    pub facet_count: usize,
    /// The changed facets (pattern indices), ascending.
    pub facets: Vec<u32>,
    /// Changed facet k's loop is `facet_loops[facet_offsets[k]..facet_offsets[k + 1]]`
    /// (`facets.len() + 1` offsets).
    pub facet_offsets: Vec<u32>,
    /// The changed facets' loops, concatenated, in vertex ids.
    pub facet_loops: Vec<u32>,
    /// The changed facets' planes (a point of it, unit normal), as
    /// [`Discretisation::facet_plane`].
    pub planes: Vec<(DVec3, DVec3)>,
    /// Vertices whose position is new (every vertex the changed loops hold that is not
    /// listed kept its position), ascending.
    pub vertex_ids: Vec<u32>,
    /// Their positions.
    pub vertices: Vec<DVec3>,
    /// One more than the largest vertex id in use.
    pub vertex_id_bound: usize,
}

impl LiveChanges {
    /// The loop of the k-th changed facet (of `facets[k]`), in vertex ids.
    pub fn facet_loop(&self, k: usize) -> &[u32] {
        &self.facet_loops[self.facet_offsets[k] as usize..self.facet_offsets[k + 1] as usize]
    }

    /// Everything of a mesh, numbered as the mesh numbers its vertices.
    fn of_mesh(mesh: &Discretisation) -> Self {
        let n = mesh.facet_count();
        Self {
            everything: true,
            facet_count: n,
            facets: (0..n as u32).collect(),
            facet_offsets: mesh.facet_offsets.clone(),
            facet_loops: mesh.facet_loops.clone(),
            planes: (0..n).map(|i| mesh.facet_plane(i)).collect(),
            vertex_ids: (0..mesh.vertices.len() as u32).collect(),
            vertices: mesh.vertices.clone(),
            vertex_id_bound: mesh.vertices.len(),
        }
    }

    /// Nothing changed in a mesh of `facet_count` facets and `vertex_id_bound` ids.
    fn nothing(facet_count: usize, vertex_id_bound: usize) -> Self {
        Self {
            facet_count,
            facet_offsets: vec![0],
            vertex_id_bound,
            ..Self::default()
        }
    }
}

/// A surface with its pattern and discretisation, kept up to date edit by edit.
pub struct LiveSurface {
    surface: Box<dyn Surface>,
    options: DiscretiseOptions,
    points: Vec<[f64; 2]>,
    /// The assembled result, None when edits made it stale.
    mesh: Option<Discretisation>,
    /// A stale result kept so that no edit pays for freeing it (the next assembly drops it).
    stale: Option<Discretisation>,
    /// The incremental state, None where the incremental path does not apply.
    state: Option<State>,
    stats: LiveStats,
    /// The whole pipeline ran since the last [`LiveSurface::take_changes`].
    everything_changed: bool,
}

/// A vertex of the last full run that is not a plain triangle vertex (boundary, corner,
/// stand-in): facets holding one are never touched by a local update.
#[derive(Clone, Copy, Debug)]
struct Other {
    point: DVec3,
    kind: VertexKind,
    foot: Option<[f64; 2]>,
}

/// A vertex of a facet loop: a triangle's (by slot) or one of the last full run's others.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Key {
    Triangle(u32),
    Other(u32),
}

/// The incremental state (see the module doc).
struct State {
    /// Internal number -> pattern index, and back.
    perm: Vec<u32>,
    rank: Vec<u32>,
    /// Pattern coordinates (internal numbering).
    st: Vec<[f64; 2]>,
    uv: Vec<[f64; 2]>,
    seeds: Vec<Seed>,
    tangents: Vec<[DVec3; 2]>,
    planes: Vec<Plane>,
    convex_side: Vec<i8>,
    slopes: Vec<[f64; 2]>,
    frame: SlopeFrame,
    /// +1 where the stored (parameter-space counter-clockwise) triangles are counter-clockwise
    /// in slope space, -1 where they are clockwise there.
    slope_sign: f64,
    /// The dual structure with free slots (a free slot's vertices are all `NO_TRIANGLE`).
    tri: DualTriangulation,
    free: Vec<u32>,
    /// Per slot: its vertex and the report's foot of it.
    vertex: Vec<TriangleVertex>,
    report_foot: Vec<Option<[f64; 2]>>,
    /// How the report's projections continue past the domain's sides (as in a full run).
    wrap: Wrap,
    /// Per point: one live triangle holding it.
    holder: Vec<u32>,
    /// Per facet: None for a simple facet (its loop is its closed fan), else its loop.
    complex: Vec<Option<Vec<Key>>>,
    others: Vec<Other>,
    diagnostics: Vec<Diagnostic>,
    stats: NeighbourStats,
    diagonal: f64,
    bbox: (DVec3, DVec3),
    grid: Grid,
    scratch: Scratch,
    /// Since the last [`LiveSurface::take_changes`]: facets whose loops or vertices changed
    /// (pattern indices, possibly repeated), every facet from `renumbered_from` on (a point
    /// was removed there), and the triangle slots created.
    touched_facets: Vec<u32>,
    renumbered_from: usize,
    touched_slots: Vec<u32>,
}

/// Point location: a square grid over the pattern's unit square, one point per cell.
struct Grid {
    size: usize,
    cell: Vec<u32>,
}

impl Grid {
    fn new(points: &[[f64; 2]]) -> Self {
        let size = ((points.len() as f64 / 4.0).sqrt().ceil() as usize).clamp(1, 4096);
        let mut grid = Self {
            size,
            cell: vec![u32::MAX; size * size],
        };
        for (i, &p) in points.iter().enumerate() {
            let c = grid.index(p);
            grid.cell[c] = i as u32;
        }
        grid
    }

    fn coordinates(&self, p: [f64; 2]) -> (usize, usize) {
        let f = |x: f64| ((x * self.size as f64) as usize).min(self.size - 1);
        (f(p[0]), f(p[1]))
    }

    fn index(&self, p: [f64; 2]) -> usize {
        let (i, j) = self.coordinates(p);
        j * self.size + i
    }

    /// Some point in or near the cell of `p` whose stored position is still in its cell.
    fn near(&self, p: [f64; 2], points: &[[f64; 2]]) -> Option<u32> {
        let (ci, cj) = self.coordinates(p);
        for ring in 0..self.size as isize {
            for dj in -ring..=ring {
                for di in -ring..=ring {
                    if di.abs() != ring && dj.abs() != ring {
                        continue;
                    }
                    let (i, j) = (ci as isize + di, cj as isize + dj);
                    if i < 0 || j < 0 || i >= self.size as isize || j >= self.size as isize {
                        continue;
                    }
                    let c = j as usize * self.size + i as usize;
                    let q = self.cell[c];
                    if let Some(&pq) = points.get(q as usize) {
                        if self.index(pq) == c {
                            return Some(q);
                        }
                    }
                }
            }
            if ring > 3 {
                break;
            }
        }
        None
    }
}

/// The change lists of a live surface are sorted and made unique when they grow beyond this
/// many times the mesh's size (plus [`CHANGE_LIST_FLOOR`]), so that a host that never asks
/// for the changes does not make them grow without bound.
const CHANGE_LIST_SLACK: usize = 2;

/// See [`CHANGE_LIST_SLACK`].
const CHANGE_LIST_FLOOR: usize = 1024;

/// Sorts and removes repeats.
fn sort_unique(list: &mut Vec<u32>) {
    list.sort_unstable();
    list.dedup();
}

/// Why an edit left the incremental path (internal: the edit then runs the whole pipeline).
struct Fallback;

/// Where a point's slopes lie in the structure.
enum Location {
    /// Strictly inside this triangle.
    Inside(u32),
    /// Strictly inside the edge opposite vertex k of this triangle.
    OnEdge(u32, usize),
}

impl LiveSurface {
    /// Discretises `surface` with `pattern` (normalised, as [`crate::discretise()`]) and keeps
    /// what the pipeline computed for later edits. Errors as [`crate::discretise()`].
    pub fn new(
        surface: Box<dyn Surface>,
        pattern: Vec<[f64; 2]>,
        options: DiscretiseOptions,
    ) -> Result<Self, TpiError> {
        let mut live = Self {
            surface,
            options,
            points: pattern,
            mesh: None,
            stale: None,
            stats: LiveStats::default(),
            state: None,
            everything_changed: true,
        };
        live.recompute_all()?;
        Ok(live)
    }

    /// The pattern points (normalised).
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// The surface.
    pub fn surface(&self) -> &dyn Surface {
        self.surface.as_ref()
    }

    /// The options.
    pub fn options(&self) -> &DiscretiseOptions {
        &self.options
    }

    /// How the edits so far were applied.
    pub fn stats(&self) -> LiveStats {
        self.stats
    }

    /// The discretisation of the current pattern (assembled now if edits made it stale).
    pub fn discretisation(&mut self) -> &Discretisation {
        if self.mesh.is_none() {
            self.stale = None;
            let start = std::time::Instant::now();
            let mut mesh = match &self.state {
                Some(state) => state.assemble(self.surface.as_ref(), &self.options),
                // Without incremental state the mesh is never stale.
                None => Discretisation::default(),
            };
            mesh.timings.total = start.elapsed().as_secs_f64() * 1e3;
            self.mesh = Some(mesh);
        }
        self.mesh.get_or_insert_with(Discretisation::default)
    }

    /// Takes the discretisation out (assembling it if needed); the next call assembles again.
    pub fn take_discretisation(&mut self) -> Discretisation {
        self.discretisation();
        let mesh = self.mesh.take().unwrap_or_default();
        if self.state.is_none() {
            // Without incremental state there is nothing to assemble from: keep a copy.
            self.mesh = Some(mesh.clone());
        }
        mesh
    }

    /// What changed in the mesh since the last call (the first call: everything), in
    /// O(what changed) after incremental edits; see [`LiveChanges`]. Only edits that were
    /// applied count; after a failed edit the mesh is as before, but the numbering may have
    /// started over (then everything is listed).
    pub fn take_changes(&mut self) -> LiveChanges {
        let everything = std::mem::take(&mut self.everything_changed);
        match (&mut self.state, &self.mesh) {
            (Some(state), _) => state.take_changes(everything, &self.options),
            // Without incremental state the mesh is never stale.
            (None, Some(mesh)) if everything => LiveChanges::of_mesh(mesh),
            (None, Some(mesh)) => LiveChanges::nothing(mesh.facet_count(), mesh.vertices.len()),
            (None, None) => LiveChanges::nothing(self.points.len(), 0),
        }
    }

    /// Moves pattern point `index` to `st` (normalised). On an error (index out of range,
    /// a point outside the square, a duplicate, a degenerate result) nothing changes.
    pub fn move_point(&mut self, index: usize, st: [f64; 2]) -> Result<(), TpiError> {
        if index >= self.points.len() {
            return Err(TpiError::InvalidParameter {
                field: "index".into(),
                value: index as f64,
                reason: format!("there are {} pattern points", self.points.len()),
            });
        }
        let old = self.points[index];
        self.points[index] = st;
        let local = self
            .state
            .as_mut()
            .map(|s| s.move_point(self.surface.as_ref(), &self.options, index, st));
        self.finish(local, |points| points[index] = old)
    }

    /// Appends the pattern point `st` (normalised) and returns its index. On an error
    /// nothing changes.
    pub fn add_point(&mut self, st: [f64; 2]) -> Result<usize, TpiError> {
        self.points.push(st);
        let index = self.points.len() - 1;
        let local = self
            .state
            .as_mut()
            .map(|s| s.add_point(self.surface.as_ref(), &self.options, st));
        self.finish(local, |points| {
            points.pop();
        })?;
        Ok(index)
    }

    /// Removes pattern point `index` (the points after it move down by one). On an error
    /// nothing changes.
    pub fn remove_point(&mut self, index: usize) -> Result<(), TpiError> {
        if index >= self.points.len() {
            return Err(TpiError::InvalidParameter {
                field: "index".into(),
                value: index as f64,
                reason: format!("there are {} pattern points", self.points.len()),
            });
        }
        let old = self.points.remove(index);
        let local = self
            .state
            .as_mut()
            .map(|s| s.remove_point(self.surface.as_ref(), &self.options, index));
        self.finish(local, |points| points.insert(index, old))
    }

    /// Replaces the surface (e.g. after its control points were edited): everything is
    /// recomputed. On an error the previous surface stays.
    pub fn set_surface(&mut self, surface: Box<dyn Surface>) -> Result<(), TpiError> {
        let previous = std::mem::replace(&mut self.surface, surface);
        if let Err(e) = self.recompute_all() {
            self.surface = previous;
            self.recompute_all()?;
            return Err(e);
        }
        Ok(())
    }

    /// After an edit of `points`: keep the local update, or run the whole pipeline; on an
    /// error undo the edit of the points (`undo`) and restore the previous state.
    fn finish(
        &mut self,
        local: Option<Result<(), Fallback>>,
        undo: impl FnOnce(&mut Vec<[f64; 2]>),
    ) -> Result<(), TpiError> {
        if let Some(Ok(())) = local {
            self.stats.incremental += 1;
            if let Some(mesh) = self.mesh.take() {
                // Freeing a large mesh costs more than an edit: later.
                self.stale = Some(mesh);
            }
            return Ok(());
        }
        match self.recompute_all() {
            Ok(()) => Ok(()),
            Err(e) => {
                undo(&mut self.points);
                self.recompute_all()?;
                self.stats.full -= 1;
                Err(e)
            }
        }
    }

    /// Runs the whole pipeline on the current inputs and keeps its state.
    fn recompute_all(&mut self) -> Result<(), TpiError> {
        let (result, pipeline) = run(
            self.surface.as_ref(),
            &self.points,
            &self.options,
            true,
            &NoProgress,
        )?;
        self.stats.full += 1;
        self.everything_changed = true;
        self.state = pipeline.and_then(|p| State::from_pipeline(p, &result, &self.points));
        self.mesh = Some(result);
        Ok(())
    }
}

impl State {
    /// The incremental state of a full run, or None where the incremental path does not apply.
    ///
    /// Inside the state the points are numbered along a Hilbert curve over the pattern square
    /// (and the triangles by their first point), so that the points and triangles an edit
    /// touches lie close together in memory whatever the pattern's own order; `perm` and
    /// `rank` translate. Every computation whose rounding depends on the order of its points
    /// takes them in pattern order, as the full run does.
    fn from_pipeline(
        p: PipelineState,
        result: &Discretisation,
        points: &[[f64; 2]],
    ) -> Option<Self> {
        let (frame, slopes) = p.slopes?;
        if p.neighbours.envelope_unresolved > 0 || p.triangulation.is_empty() {
            return None;
        }
        let n = points.len();
        // perm: internal -> pattern index; rank: pattern index -> internal.
        let mut perm: Vec<u32> = (0..n as u32).collect();
        perm.sort_by_key(|&i| hilbert_key(points[i as usize]));
        let mut rank = vec![0u32; n];
        for (internal, &i) in perm.iter().enumerate() {
            rank[i as usize] = internal as u32;
        }
        let by_rank = |v: &[u32; 3]| v.map(|x| rank[x as usize]);
        // Triangles in the order of their smallest internal point.
        let old = p.triangulation;
        let mut order: Vec<u32> = (0..old.len() as u32).collect();
        order.sort_by_key(|&t| {
            by_rank(&old.triangles[t as usize])
                .into_iter()
                .min()
                .unwrap_or(0)
        });
        let mut slot_of = vec![0u32; old.len()];
        for (slot, &t) in order.iter().enumerate() {
            slot_of[t as usize] = slot as u32;
        }
        let tri = DualTriangulation {
            triangles: order
                .iter()
                .map(|&t| by_rank(&old.triangles[t as usize]))
                .collect(),
            neighbours: order
                .iter()
                .map(|&t| {
                    old.neighbours[t as usize].map(|x| {
                        if x == NO_TRIANGLE {
                            x
                        } else {
                            slot_of[x as usize]
                        }
                    })
                })
                .collect(),
        };
        let t0 = tri.triangles[0].map(|v| slopes[perm[v as usize] as usize]);
        let slope_sign = orient(t0[0], t0[1], t0[2]).signum();
        if slope_sign == 0.0 {
            return None;
        }
        let vertex: Vec<TriangleVertex> = order
            .iter()
            .map(|&t| p.triangle_vertices[t as usize])
            .collect();
        let mut report_foot = vec![None; tri.len()];
        let mut others = Vec::new();
        let mut key_of = Vec::with_capacity(result.vertices.len());
        for (v, &source) in p.vertex_source.iter().enumerate() {
            let foot = p.feet.get(v).copied().flatten();
            if source != u32::MAX {
                let slot = slot_of[source as usize];
                report_foot[slot as usize] = foot;
                key_of.push(Key::Triangle(slot));
            } else {
                key_of.push(Key::Other(others.len() as u32));
                others.push(Other {
                    point: result.vertices[v],
                    kind: result.vertex_kinds[v],
                    foot,
                });
            }
        }
        // Facets around welded vertices (four or more planes through one point) keep their
        // loops as the full run made them, like facets at the boundary: edits there run the
        // whole pipeline.
        let mut simple = p.facet_simple;
        for &t in &p.welded {
            for &v in &old.triangles[t as usize] {
                simple[v as usize] = false;
            }
        }
        let complex = perm
            .iter()
            .map(|&i| {
                let i = i as usize;
                (!simple[i]).then(|| {
                    result
                        .facet(i)
                        .iter()
                        .map(|&v| key_of[v as usize])
                        .collect()
                })
            })
            .collect();
        let mut holder = vec![NO_TRIANGLE; n];
        for (t, tv) in tri.triangles.iter().enumerate() {
            for &v in tv {
                holder[v as usize] = t as u32;
            }
        }
        let pick = |i: &u32| *i as usize;
        let st: Vec<[f64; 2]> = perm.iter().map(|i| points[pick(i)]).collect();
        Some(Self {
            uv: perm.iter().map(|i| p.uv[pick(i)]).collect(),
            seeds: perm.iter().map(|i| p.seeds[pick(i)]).collect(),
            tangents: perm.iter().map(|i| p.tangents[pick(i)]).collect(),
            planes: perm.iter().map(|i| p.planes[pick(i)]).collect(),
            convex_side: perm.iter().map(|i| p.convex_side[pick(i)]).collect(),
            slopes: perm.iter().map(|i| slopes[pick(i)]).collect(),
            grid: Grid::new(&st),
            st,
            perm,
            rank,
            frame,
            slope_sign,
            vertex,
            report_foot,
            wrap: p.wrap,
            tri,
            free: Vec::new(),
            holder,
            complex,
            others,
            diagnostics: result.diagnostics.clone(),
            stats: p.neighbours,
            diagonal: p.diagonal,
            bbox: p.bbox,
            scratch: Scratch::default(),
            touched_facets: Vec::new(),
            renumbered_from: usize::MAX,
            touched_slots: Vec::new(),
        })
    }

    // ---- edits (pattern indices in, internal numbers inside) ---------------------------

    fn move_point(
        &mut self,
        surface: &dyn Surface,
        options: &DiscretiseOptions,
        index: usize,
        to: [f64; 2],
    ) -> Result<(), Fallback> {
        let i = self.rank[index] as usize;
        let (geometry, tangents, plane, slopes, uv) = self.sample(surface, options, to, i)?;
        if on_box(self.planes[i].point, self.bbox) {
            return Err(Fallback);
        }
        let old = self.st[i];
        let mut changed = self.changed();
        self.remove_from_structure(i as u32, &mut changed)?;
        let start = self.hole_triangle(&changed);
        self.st[i] = to;
        self.uv[i] = uv;
        self.seeds[i] = seed(&geometry, uv);
        self.tangents[i] = tangents;
        self.planes[i] = plane;
        self.slopes[i] = slopes;
        let near =
            (to[0] - old[0]).abs().max((to[1] - old[1]).abs()) * self.grid.size as f64 <= 2.0;
        let start = if near {
            start
        } else {
            self.grid
                .near(to, &self.st)
                .map(|q| self.holder[q as usize])
                .unwrap_or(start)
        };
        self.insert_into_structure(i as u32, start, &mut changed)?;
        self.finish_edit(surface, options, &changed)?;
        self.record(&changed);
        self.recycle(changed);
        let old_cell = self.grid.index(old);
        if self.grid.cell[old_cell] == i as u32 {
            self.grid.cell[old_cell] = u32::MAX;
        }
        let new_cell = self.grid.index(to);
        self.grid.cell[new_cell] = i as u32;
        Ok(())
    }

    fn add_point(
        &mut self,
        surface: &dyn Surface,
        options: &DiscretiseOptions,
        to: [f64; 2],
    ) -> Result<(), Fallback> {
        let i = self.st.len();
        let (geometry, tangents, plane, slopes, uv) =
            self.sample(surface, options, to, usize::MAX)?;
        self.perm.push(self.rank.len() as u32);
        self.rank.push(i as u32);
        self.st.push(to);
        self.uv.push(uv);
        self.seeds.push(seed(&geometry, uv));
        self.tangents.push(tangents);
        self.planes.push(plane);
        self.slopes.push(slopes);
        self.convex_side.push(self.convex_side[0]);
        self.holder.push(NO_TRIANGLE);
        self.complex.push(None);
        let start = self
            .grid
            .near(to, &self.st)
            .map(|q| self.holder[q as usize])
            .unwrap_or(0);
        let start = self.live_slot(start);
        let mut changed = self.changed();
        self.insert_into_structure(i as u32, start, &mut changed)?;
        self.finish_edit(surface, options, &changed)?;
        self.record(&changed);
        self.recycle(changed);
        let cell = self.grid.index(to);
        self.grid.cell[cell] = i as u32;
        Ok(())
    }

    fn remove_point(
        &mut self,
        surface: &dyn Surface,
        options: &DiscretiseOptions,
        index: usize,
    ) -> Result<(), Fallback> {
        let k = self.rank[index] as usize;
        if self.st.len() <= 3 || on_box(self.planes[k].point, self.bbox) {
            return Err(Fallback);
        }
        let mut changed = self.changed();
        self.remove_from_structure(k as u32, &mut changed)?;
        // The points around the hole must have had simple facets (old numbering).
        self.check_simple(&changed, Some(k as u32))?;
        // Renumber: every internal number after k moves down by one, and every pattern index
        // after `index` (facets, diagnostics, the grid, the translations).
        let kk = k as u32;
        let shift = |v: &mut u32| {
            if *v != NO_TRIANGLE && *v > kk {
                *v -= 1;
            }
        };
        for t in self.tri.triangles.iter_mut() {
            t.iter_mut().for_each(shift);
        }
        changed.points.retain(|&p| p != kk);
        changed.points.iter_mut().for_each(shift);
        self.st.remove(k);
        self.uv.remove(k);
        self.seeds.remove(k);
        self.tangents.remove(k);
        self.planes.remove(k);
        self.slopes.remove(k);
        self.convex_side.remove(k);
        self.holder.remove(k);
        self.complex.remove(k);
        let removed = index as u32;
        self.perm.remove(k);
        for i in self.perm.iter_mut() {
            if *i > removed {
                *i -= 1;
            }
        }
        self.rank.remove(index);
        self.rank.iter_mut().for_each(shift);
        for d in &mut self.diagnostics {
            renumber_diagnostic(d, removed);
        }
        for c in self.grid.cell.iter_mut() {
            if *c == kk {
                *c = u32::MAX;
            } else if *c != u32::MAX && *c > kk {
                *c -= 1;
            }
        }
        self.finish_vertices(surface, options, &changed)?;
        // Every facet after the removed one moved down by one index.
        self.renumbered_from = self.renumbered_from.min(index);
        self.touched_facets.retain(|&f| (f as usize) < index);
        self.record(&changed);
        self.recycle(changed);
        Ok(())
    }

    /// Geometry of a point at `st` (to be internal point `exclude`, or a new one), with the
    /// checks of the incremental path: finite, strictly convex on the surface's side, slopes
    /// defined, strictly inside the bounding box, no duplicate in its grid cell.
    #[allow(clippy::type_complexity)]
    fn sample(
        &self,
        surface: &dyn Surface,
        options: &DiscretiseOptions,
        st: [f64; 2],
        exclude: usize,
    ) -> Result<(LocalGeometry, [DVec3; 2], Plane, [f64; 2], [f64; 2]), Fallback> {
        if !(st[0].is_finite()
            && st[1].is_finite()
            && (0.0..=1.0).contains(&st[0])
            && (0.0..=1.0).contains(&st[1]))
        {
            return Err(Fallback);
        }
        // Duplicates: any point closer than the tolerance sends the edit to the full
        // pipeline, which reports it exactly as a fresh run would.
        if self.has_duplicate(st, exclude) {
            return Err(Fallback);
        }
        let uv = surface.domain().from_normalised(st);
        let d = surface.evaluate(uv[0], uv[1]);
        let geometry = LocalGeometry::from_derivatives(&d);
        if !(geometry.point.is_finite() && geometry.normal.is_finite()) {
            return Err(Fallback);
        }
        let (side, _, _) = curvature_class(&geometry, self.diagonal, options);
        if side != self.convex_side[0] {
            return Err(Fallback);
        }
        let plane = Plane {
            point: geometry.point,
            normal: geometry.normal,
        };
        let slopes = self.frame.slopes(&plane).ok_or(Fallback)?;
        if !strictly_inside_box(plane.point, self.bbox) {
            return Err(Fallback);
        }
        Ok((geometry, [d.su, d.sv], plane, slopes, uv))
    }

    /// Whether the grid's point in the cell of `p` (other than `exclude`) is a duplicate of
    /// it. A duplicate elsewhere would be a neighbour of the point in the updated structure,
    /// which `finish_vertices` checks.
    fn has_duplicate(&self, p: [f64; 2], exclude: usize) -> bool {
        let q = self.grid.cell[self.grid.index(p)] as usize;
        q != exclude
            && q < self.st.len()
            && (self.st[q][0] - p[0]).hypot(self.st[q][1] - p[1]) < DUPLICATE_UV_TOLERANCE
    }

    /// The internal points sorted by pattern index (the order of the full run's sums).
    fn in_pattern_order(&self, mut ids: [u32; 3]) -> [u32; 3] {
        ids.sort_unstable_by_key(|&v| self.perm[v as usize]);
        ids
    }

    fn live_slot(&self, t: u32) -> u32 {
        if (t as usize) < self.tri.len() && self.tri.triangles[t as usize][0] != NO_TRIANGLE {
            return t;
        }
        self.tri
            .triangles
            .iter()
            .position(|t| t[0] != NO_TRIANGLE)
            .map_or(0, |t| t as u32)
    }

    fn hole_triangle(&self, changed: &Changed) -> u32 {
        changed
            .created
            .iter()
            .copied()
            .find(|&t| self.tri.triangles[t as usize][0] != NO_TRIANGLE)
            .unwrap_or(0)
    }

    /// An empty change record on the scratch buffers.
    fn changed(&mut self) -> Changed {
        let mut created = std::mem::take(&mut self.scratch.created);
        let mut points = std::mem::take(&mut self.scratch.points);
        created.clear();
        points.clear();
        Changed { created, points }
    }

    /// Gives the change record's buffers back.
    fn recycle(&mut self, changed: Changed) {
        self.scratch.created = changed.created;
        self.scratch.points = changed.points;
    }

    // ---- what changed -----------------------------------------------------------------

    /// Notes an applied edit's changed facets and created slots for
    /// [`LiveSurface::take_changes`].
    fn record(&mut self, changed: &Changed) {
        let perm = &self.perm;
        self.touched_facets
            .extend(changed.points.iter().map(|&p| perm[p as usize]));
        self.touched_slots.extend_from_slice(&changed.created);
        // A host that never asks keeps the lists bounded by the mesh's size.
        if self.touched_facets.len() > CHANGE_LIST_SLACK * self.st.len() + CHANGE_LIST_FLOOR {
            sort_unique(&mut self.touched_facets);
        }
        if self.touched_slots.len() > CHANGE_LIST_SLACK * self.tri.len() + CHANGE_LIST_FLOOR {
            sort_unique(&mut self.touched_slots);
        }
    }

    /// The vertex id of a loop key: boundary and other vertices of the full run first, then
    /// the triangle slots.
    fn vertex_id(&self, key: Key) -> u32 {
        match key {
            Key::Other(o) => o,
            Key::Triangle(t) => self.others.len() as u32 + t,
        }
    }

    /// The changes since the last call (everything when `everything`), and a fresh start.
    fn take_changes(&mut self, everything: bool, options: &DiscretiseOptions) -> LiveChanges {
        let n = self.st.len();
        let mut facets = std::mem::take(&mut self.touched_facets);
        let mut slots = std::mem::take(&mut self.touched_slots);
        let from = std::mem::replace(&mut self.renumbered_from, usize::MAX);
        if everything {
            facets.clear();
            facets.extend(0..n as u32);
            slots.clear();
            slots.extend(0..self.tri.len() as u32);
        } else {
            facets.retain(|&f| (f as usize) < n);
            facets.extend(from.min(n) as u32..n as u32);
            sort_unique(&mut facets);
            sort_unique(&mut slots);
        }
        slots.retain(|&t| self.tri.triangles[t as usize][0] != NO_TRIANGLE);
        let mut changes = LiveChanges::nothing(n, self.others.len() + self.tri.len());
        changes.everything = everything;
        changes.facet_offsets.reserve(facets.len());
        changes.planes.reserve(facets.len());
        let mut fan = Vec::new();
        for &f in &facets {
            let p = self.rank[f as usize];
            match &self.complex[p as usize] {
                Some(keys) => {
                    let ids = keys.iter().map(|&k| self.vertex_id(k));
                    changes.facet_loops.extend(ids);
                }
                None => {
                    self.canonical_fan(p, &mut fan);
                    let ids = fan.iter().map(|&t| self.vertex_id(Key::Triangle(t)));
                    changes.facet_loops.extend(ids);
                }
            }
            changes.facet_offsets.push(changes.facet_loops.len() as u32);
            changes.planes.push(self.facet_plane(p as usize, options));
        }
        if everything {
            changes.vertex_ids.extend(0..self.others.len() as u32);
            changes.vertices.extend(self.others.iter().map(|o| o.point));
        }
        for &t in &slots {
            changes.vertex_ids.push(self.vertex_id(Key::Triangle(t)));
            changes.vertices.push(self.vertex[t as usize].point);
        }
        changes.facets = facets;
        // The buffers go back empty for the next edits.
        slots.clear();
        self.touched_slots = slots;
        changes
    }

    /// The closed fan of a simple facet's point p, starting where the assembled mesh's loop
    /// starts: after the fan's first triangle in canonical order (see [`State::assemble`]).
    fn canonical_fan(&self, p: u32, fan: &mut Vec<u32>) {
        // A simple facet's fan is closed (checked by every edit); were it not, its triangles
        // are listed as found.
        let _ = self.tri.fan(p, self.holder[p as usize], fan);
        let key = |t: u32| {
            let tv = self.tri.triangles[t as usize].map(|v| self.perm[v as usize]);
            let k = (0..3).min_by_key(|&k| tv[k]).unwrap_or(0);
            (tv[k], tv[(k + 1) % 3])
        };
        let len = fan.len();
        if let Some(first) = (0..len).min_by_key(|&j| key(fan[j])) {
            fan.rotate_left((first + 1) % len);
        }
    }

    /// Facet p's plane (internal number) as the assembled mesh gives it
    /// ([`Discretisation::facet_plane`]).
    fn facet_plane(&self, p: usize, options: &DiscretiseOptions) -> (DVec3, DVec3) {
        let seed = &self.seeds[p];
        if options.planes == PlaneMode::Adjusted {
            let adjusted = plane_adjustments(std::slice::from_ref(seed), &self.planes[p..=p]);
            if let Some(a) = adjusted.first() {
                return (seed.point + a.normal * a.offset, a.normal);
            }
        }
        (seed.point, seed.normal)
    }

    // ---- the structure ----------------------------------------------------------------

    fn new_slot(&mut self, vertices: [u32; 3], neighbours: [u32; 3]) -> u32 {
        if let Some(t) = self.free.pop() {
            self.tri.triangles[t as usize] = vertices;
            self.tri.neighbours[t as usize] = neighbours;
            t
        } else {
            self.tri.triangles.push(vertices);
            self.tri.neighbours.push(neighbours);
            self.vertex.push(self.vertex[0]);
            self.report_foot.push(None);
            (self.tri.triangles.len() - 1) as u32
        }
    }

    fn free_slot(&mut self, t: u32) {
        self.tri.triangles[t as usize] = [NO_TRIANGLE; 3];
        self.tri.neighbours[t as usize] = [NO_TRIANGLE; 3];
        self.free.push(t);
    }

    /// Sets the neighbour of t across the edge (a, b) (t holds it) to `other`.
    fn link(&mut self, t: u32, a: u32, b: u32, other: u32) {
        if t == NO_TRIANGLE {
            return;
        }
        let tv = self.tri.triangles[t as usize];
        for k in 0..3 {
            let (x, y) = (tv[(k + 1) % 3], tv[(k + 2) % 3]);
            if (x == a && y == b) || (x == b && y == a) {
                self.tri.neighbours[t as usize][k] = other;
            }
        }
    }

    /// Slope-space orientation of (a, b, c) in the stored convention (positive: like the
    /// stored triangles).
    fn orientation(&self, a: u32, b: u32, c: u32) -> f64 {
        let s = &self.slopes;
        self.slope_sign * orient2d(s[a as usize], s[b as usize], s[c as usize])
    }

    /// The lifted point of v ([`SlopeFrame::lift`], from the kept slopes).
    fn lifted(&self, v: u32) -> [f64; 3] {
        let [a, b] = self.slopes[v as usize];
        [a, b, self.frame.height(&self.planes[v as usize])]
    }

    /// The exact power test of the full run ([`crate::predicates::power_illegal`]) on the
    /// quad (c, a, b, d), with ties broken by pattern index as there.
    fn power_illegal(&self, quad: [u32; 4]) -> bool {
        power_illegal(
            quad.map(|v| self.lifted(v)),
            quad.map(|v| self.perm[v as usize]),
        )
    }

    /// Removes point v: its star becomes a hole, filled with regular ears.
    fn remove_from_structure(&mut self, v: u32, changed: &mut Changed) -> Result<(), Fallback> {
        let start = self.holder[v as usize];
        if start == NO_TRIANGLE || self.complex[v as usize].is_some() {
            return Err(Fallback);
        }
        let mut fan = std::mem::take(&mut self.scratch.fan);
        if self.tri.fan(v, start, &mut fan) != crate::triangulation::Fan::Closed {
            return Err(Fallback);
        }
        // The link: for each fan triangle (v, a, b) counter-clockwise, the edge (a, b) and the
        // triangle beyond it.
        let mut link = std::mem::take(&mut self.scratch.link);
        let mut outer = std::mem::take(&mut self.scratch.outer);
        link.clear();
        outer.clear();
        for &t in &fan {
            let tv = self.tri.triangles[t as usize];
            let k = tv.iter().position(|&x| x == v).ok_or(Fallback)?;
            link.push(tv[(k + 1) % 3]);
            outer.push(self.tri.neighbours[t as usize][k]);
        }
        for &t in &fan {
            self.free_slot(t);
        }
        self.scratch.fan = fan;
        changed.points.extend_from_slice(&link);
        // Ears: (link[k-1], link[k], link[k+1]) convex in slope space, holding no other link
        // point, and whose vertex no other link point's tangent plane cuts off.
        // `edge_out[k]` is the triangle beyond the polygon edge (link[k], link[k+1]).
        let mut poly = link;
        let mut edge_out = outer;
        while poly.len() > 3 {
            let m = poly.len();
            let ear = (0..m).find(|&k| {
                let (a, b, c) = (poly[(k + m - 1) % m], poly[k], poly[(k + 1) % m]);
                self.orientation(a, b, c) > 0.0
                    && poly
                        .iter()
                        .all(|&x| x == a || x == b || x == c || !self.in_triangle(x, a, b, c))
                    && self.regular_ear(a, b, c, &poly)
            });
            let k = ear.ok_or(Fallback)?;
            let (kp, kn) = ((k + m - 1) % m, (k + 1) % m);
            let (a, b, c) = (poly[kp], poly[k], poly[kn]);
            // Triangle (a, b, c): opposite a is edge (b, c) = polygon edge k; opposite c is
            // edge (a, b) = polygon edge k-1; opposite b is the new diagonal (c, a).
            let (out_bc, out_ab) = (edge_out[k], edge_out[kp]);
            let t = self.new_slot([a, b, c], [out_bc, NO_TRIANGLE, out_ab]);
            self.link(out_bc, b, c, t);
            self.link(out_ab, a, b, t);
            changed.created.push(t);
            // The polygon loses b; the edge (a, c) is now bounded by t.
            poly.remove(k);
            edge_out.remove(k);
            let kp = if k == 0 { poly.len() - 1 } else { k - 1 };
            edge_out[kp] = t;
        }
        let (a, b, c) = (poly[0], poly[1], poly[2]);
        if self.orientation(a, b, c) <= 0.0 {
            return Err(Fallback);
        }
        // edge_out[k] lies beyond (poly[k], poly[k+1]): opposite poly[k+2].
        let t = self.new_slot([a, b, c], [edge_out[1], edge_out[2], edge_out[0]]);
        for k in 0..3 {
            self.link(edge_out[k], poly[k], poly[(k + 1) % 3], t);
        }
        changed.created.push(t);
        self.scratch.link = poly;
        self.scratch.outer = edge_out;
        self.holder[v as usize] = NO_TRIANGLE;
        for &t in &changed.created {
            for &x in &self.tri.triangles[t as usize] {
                self.holder[x as usize] = t;
            }
        }
        // The ears are regular among the link points; make sure no edge needs a flip.
        let mut stack = std::mem::take(&mut self.scratch.stack);
        stack.clear();
        stack.extend(
            changed
                .created
                .iter()
                .flat_map(|&t| (0..3).map(move |k| (t, k))),
        );
        self.legalise(&mut stack, changed)?;
        self.scratch.stack = stack;
        Ok(())
    }

    /// Whether x lies strictly inside triangle (a, b, c) in slope space.
    fn in_triangle(&self, x: u32, a: u32, b: u32, c: u32) -> bool {
        self.orientation(a, b, x) > 0.0
            && self.orientation(b, c, x) > 0.0
            && self.orientation(c, a, x) > 0.0
    }

    /// Whether no other polygon point's lifted point lies below the plane of (a, b, c)'s, by
    /// the exact power test: no other tangent plane cuts off the vertex of (a, b, c).
    fn regular_ear(&self, a: u32, b: u32, c: u32, poly: &[u32]) -> bool {
        let ear = [a, b, c].map(|v| self.lifted(v));
        let keys = [a, b, c].map(|v| self.perm[v as usize]);
        poly.iter().all(|&x| {
            x == a
                || x == b
                || x == c
                || !power_illegal(
                    [ear[0], ear[1], ear[2], self.lifted(x)],
                    [keys[0], keys[1], keys[2], self.perm[x as usize]],
                )
        })
    }

    /// Inserts point v (not in the structure) at its slopes, starting the search at `start`:
    /// the triangle holding them is split in three, or, where the slopes lie on an edge (a
    /// pattern row dragged along itself on a surface whose slopes follow the parameters), the
    /// two triangles of that edge in four; then the new triangles are legalised.
    fn insert_into_structure(
        &mut self,
        v: u32,
        start: u32,
        changed: &mut Changed,
    ) -> Result<(), Fallback> {
        let mut stack = std::mem::take(&mut self.scratch.stack);
        stack.clear();
        match self.locate(v, start)? {
            Location::Inside(t) => self.split_triangle(v, t, changed, &mut stack),
            Location::OnEdge(t, k) => self.split_edge(v, t, k, changed, &mut stack)?,
        }
        self.legalise(&mut stack, changed)?;
        self.scratch.stack = stack;
        Ok(())
    }

    /// Splits triangle t at v (inside it) into three; their outer edges go on `stack`.
    fn split_triangle(
        &mut self,
        v: u32,
        t: u32,
        changed: &mut Changed,
        stack: &mut Vec<(u32, usize)>,
    ) {
        let [a, b, c] = self.tri.triangles[t as usize];
        let [n_a, n_b, n_c] = self.tri.neighbours[t as usize];
        self.free_slot(t);
        // Three triangles (v, b, c), (v, c, a), (v, a, b); across the edge opposite v lies
        // the old neighbour, the other two are each other.
        let t1 = self.new_slot([v, b, c], [n_a, NO_TRIANGLE, NO_TRIANGLE]);
        let t2 = self.new_slot([v, c, a], [n_b, NO_TRIANGLE, NO_TRIANGLE]);
        let t3 = self.new_slot([v, a, b], [n_c, NO_TRIANGLE, NO_TRIANGLE]);
        // In (v, b, c): opposite b is (c, v) = t2's (v, c); opposite c is (v, b) = t3's (b, v).
        self.tri.neighbours[t1 as usize] = [n_a, t2, t3];
        self.tri.neighbours[t2 as usize] = [n_b, t3, t1];
        self.tri.neighbours[t3 as usize] = [n_c, t1, t2];
        self.link(n_a, b, c, t1);
        self.link(n_b, c, a, t2);
        self.link(n_c, a, b, t3);
        changed.created.extend_from_slice(&[t1, t2, t3]);
        changed.points.extend_from_slice(&[v, a, b, c]);
        for (x, t) in [(v, t1), (a, t2), (b, t3), (c, t1)] {
            self.holder[x as usize] = t;
        }
        stack.extend_from_slice(&[(t1, 0), (t2, 0), (t3, 0)]);
    }

    /// Splits the edge opposite vertex k of triangle t at v (strictly inside the edge) and
    /// the two triangles sharing it into four; their outer edges go on `stack`. Fallback on
    /// a hull edge.
    fn split_edge(
        &mut self,
        v: u32,
        t: u32,
        k: usize,
        changed: &mut Changed,
        stack: &mut Vec<(u32, usize)>,
    ) -> Result<(), Fallback> {
        // t = (r, p, q) counter-clockwise with the edge (p, q) opposite r; u = (s, q, p)
        // beyond it.
        let tv = self.tri.triangles[t as usize];
        let tn = self.tri.neighbours[t as usize];
        let (r, p, q) = (tv[k], tv[(k + 1) % 3], tv[(k + 2) % 3]);
        let (n_qr, n_rp) = (tn[(k + 1) % 3], tn[(k + 2) % 3]);
        let u = tn[k];
        if u == NO_TRIANGLE {
            return Err(Fallback);
        }
        let uv = self.tri.triangles[u as usize];
        let un = self.tri.neighbours[u as usize];
        let k2 = un.iter().position(|&x| x == t).ok_or(Fallback)?;
        let s = uv[k2];
        if uv[(k2 + 1) % 3] != q || uv[(k2 + 2) % 3] != p {
            return Err(Fallback);
        }
        let (n_ps, n_sq) = (un[(k2 + 1) % 3], un[(k2 + 2) % 3]);
        self.free_slot(t);
        self.free_slot(u);
        // Around v counter-clockwise: (v, r, p), (v, q, r), (v, s, q), (v, p, s); each one's
        // edge opposite v is an outer edge, its other two edges its ring neighbours'.
        let t1 = self.new_slot([v, r, p], [n_rp, NO_TRIANGLE, NO_TRIANGLE]);
        let t2 = self.new_slot([v, q, r], [n_qr, NO_TRIANGLE, NO_TRIANGLE]);
        let t3 = self.new_slot([v, s, q], [n_sq, NO_TRIANGLE, NO_TRIANGLE]);
        let t4 = self.new_slot([v, p, s], [n_ps, NO_TRIANGLE, NO_TRIANGLE]);
        // In (v, r, p): opposite r is (p, v), shared with (v, p, s); opposite p is (v, r),
        // shared with (v, q, r); and so on around v.
        self.tri.neighbours[t1 as usize] = [n_rp, t4, t2];
        self.tri.neighbours[t2 as usize] = [n_qr, t1, t3];
        self.tri.neighbours[t3 as usize] = [n_sq, t2, t4];
        self.tri.neighbours[t4 as usize] = [n_ps, t3, t1];
        self.link(n_rp, r, p, t1);
        self.link(n_qr, q, r, t2);
        self.link(n_sq, s, q, t3);
        self.link(n_ps, p, s, t4);
        changed.created.extend_from_slice(&[t1, t2, t3, t4]);
        changed.points.extend_from_slice(&[v, r, p, q, s]);
        for (x, t) in [(v, t1), (r, t1), (p, t1), (q, t2), (s, t3)] {
            self.holder[x as usize] = t;
        }
        stack.extend_from_slice(&[(t1, 0), (t2, 0), (t3, 0), (t4, 0)]);
        Ok(())
    }

    /// Where point v's slopes lie, by a walk from `start`: inside a live triangle, or on the
    /// inside of one of its edges (Fallback outside the hull, on a point's slopes, or when
    /// the walk takes too long).
    fn locate(&self, v: u32, start: u32) -> Result<Location, Fallback> {
        let mut t = self.live_slot(start);
        let limit = 4 * self.tri.len() + 16;
        let mut turn = 0usize;
        for _ in 0..limit {
            let tv = self.tri.triangles[t as usize];
            let mut next = None;
            let mut on = None;
            let mut zeros = 0;
            // Try the edges in a rotating order (a walk that cannot cycle for long).
            turn = turn.wrapping_add(1);
            for j in 0..3 {
                let k = (j + turn) % 3;
                let (a, b) = (tv[(k + 1) % 3], tv[(k + 2) % 3]);
                let o = self.orientation(a, b, v);
                if o < 0.0 {
                    next = Some(self.tri.neighbours[t as usize][k]);
                    break;
                }
                if o == 0.0 {
                    zeros += 1;
                    on = Some(k);
                }
            }
            match (next, on) {
                (Some(NO_TRIANGLE), _) => return Err(Fallback),
                (Some(n), _) => t = n,
                (None, None) => return Ok(Location::Inside(t)),
                (None, Some(k)) if zeros == 1 => return Ok(Location::OnEdge(t, k)),
                (None, Some(_)) => return Err(Fallback),
            }
        }
        Err(Fallback)
    }

    /// Lawson's flips by the envelope test from the given (triangle, side) pairs.
    fn legalise(
        &mut self,
        stack: &mut Vec<(u32, usize)>,
        changed: &mut Changed,
    ) -> Result<(), Fallback> {
        let mut budget = 64 + 8 * stack.len();
        while let Some((t, k)) = stack.pop() {
            if self.tri.triangles[t as usize][0] == NO_TRIANGLE {
                continue;
            }
            let other = self.tri.neighbours[t as usize][k];
            if other == NO_TRIANGLE {
                continue;
            }
            let tv = self.tri.triangles[t as usize];
            let [c, a, b] = [tv[k], tv[(k + 1) % 3], tv[(k + 2) % 3]];
            let k2 = self.tri.neighbours[other as usize]
                .iter()
                .position(|&x| x == t)
                .ok_or(Fallback)?;
            let d = self.tri.triangles[other as usize][k2];
            if !self.power_illegal([c, a, b, d]) {
                continue;
            }
            if self.orientation(c, a, d) <= 0.0 || self.orientation(d, b, c) <= 0.0 || budget == 0 {
                return Err(Fallback);
            }
            budget -= 1;
            let (t1, t2) = self.tri.flip(t, k);
            changed.created.extend_from_slice(&[t1, t2]);
            changed.points.extend_from_slice(&[a, b, c, d]);
            for (x, s) in [(c, t1), (a, t1), (d, t1), (b, t2)] {
                self.holder[x as usize] = s;
            }
            // New triangles (c, a, d) and (d, b, c): test their outer edges.
            for (s, vertices) in [(t1, [c, a, d]), (t2, [d, b, c])] {
                for k in 0..3 {
                    if self.tri.neighbours[s as usize][k] != if s == t1 { t2 } else { t1 } {
                        let _ = vertices;
                        stack.push((s, k));
                    }
                }
            }
        }
        Ok(())
    }

    /// After a move or an add: every changed point's facet was simple; the new triangles'
    /// vertices are computed and checked, and the changed points' facets are simple again.
    fn finish_edit(
        &mut self,
        surface: &dyn Surface,
        options: &DiscretiseOptions,
        changed: &Changed,
    ) -> Result<(), Fallback> {
        self.check_simple(changed, None)?;
        self.finish_vertices(surface, options, changed)
    }

    /// The points whose triangles changed must have had simple facets.
    fn check_simple(&self, changed: &Changed, removed: Option<u32>) -> Result<(), Fallback> {
        for &p in &changed.points {
            if Some(p) == removed {
                continue;
            }
            if self.complex.get(p as usize).map_or(true, |c| c.is_some()) {
                return Err(Fallback);
            }
        }
        Ok(())
    }

    /// Vertices and report feet of the live created triangles, with the checks of the
    /// incremental path (exact, inside, counter-clockwise in the pattern, no weld, no
    /// duplicate point), and the changed points' fans closed.
    fn finish_vertices(
        &mut self,
        surface: &dyn Surface,
        options: &DiscretiseOptions,
        changed: &Changed,
    ) -> Result<(), Fallback> {
        let points = &self.st;
        let mut created = std::mem::take(&mut self.scratch.list);
        created.clear();
        created.extend(
            changed
                .created
                .iter()
                .copied()
                .filter(|&t| self.tri.triangles[t as usize][0] != NO_TRIANGLE),
        );
        created.sort_unstable();
        created.dedup();
        for &t in &created {
            let ids = self.tri.triangles[t as usize];
            let [a, b, c] = ids.map(|v| points[v as usize]);
            if orient(a, b, c) <= 0.0 {
                return Err(Fallback);
            }
            let ids = self.in_pattern_order(ids);
            let vertex = single_triangle_vertex(
                surface,
                &self.uv,
                &self.tangents,
                &self.planes,
                &self.convex_side,
                ids,
                options.far_vertex_factor,
            );
            if !(vertex.exact && vertex.inside > 0.0) {
                return Err(Fallback);
            }
            self.vertex[t as usize] = vertex;
        }
        let weld = options.weld_tolerance * self.diagonal;
        for &t in &created {
            for &u in &self.tri.neighbours[t as usize] {
                if u == NO_TRIANGLE {
                    return Err(Fallback);
                }
                let (x1, x2) = (self.vertex[t as usize].point, self.vertex[u as usize].point);
                let quad = self
                    .tri
                    .opposite(t as usize, u)
                    .zip(self.tri.opposite(u as usize, t));
                // The full run welds these (facets::assemble): the edit runs it.
                let reversed = quad.map_or(true, |(c, d)| {
                    edge_reversed(
                        self.frame.axes,
                        x1,
                        x2,
                        self.slopes[c as usize],
                        self.slopes[d as usize],
                    )
                });
                if x1.distance(x2) <= weld || reversed {
                    return Err(Fallback);
                }
            }
        }
        let mut fan = std::mem::take(&mut self.scratch.fan);
        let mut seen = std::mem::take(&mut self.scratch.link);
        seen.clear();
        seen.extend_from_slice(&changed.points);
        seen.sort_unstable();
        seen.dedup();
        for &p in &seen {
            let t = self.holder[p as usize];
            if t == NO_TRIANGLE || self.tri.fan(p, t, &mut fan) != crate::triangulation::Fan::Closed
            {
                return Err(Fallback);
            }
            // A duplicate of a moved or added point would be its neighbour.
            for &t in &fan {
                for &q in &self.tri.triangles[t as usize] {
                    if q != p
                        && (points[q as usize][0] - points[p as usize][0])
                            .hypot(points[q as usize][1] - points[p as usize][1])
                            < DUPLICATE_UV_TOLERANCE
                    {
                        return Err(Fallback);
                    }
                }
            }
        }
        if options.quality_report {
            for &t in &created {
                // The first facet holding the vertex: its point of smallest pattern index.
                let first = self.in_pattern_order(self.tri.triangles[t as usize])[0];
                self.report_foot[t as usize] = Some(report_foot(
                    surface,
                    &self.wrap,
                    &self.vertex[t as usize],
                    self.uv[first as usize],
                ));
            }
        }
        self.scratch.fan = fan;
        self.scratch.link = seen;
        self.scratch.list = created;
        Ok(())
    }

    // ---- assembly ---------------------------------------------------------------------

    /// The discretisation of the current state, as a full run would give it.
    fn assemble(&self, surface: &dyn Surface, options: &DiscretiseOptions) -> Discretisation {
        let n = self.uv.len();
        // Canonical triangles (see DualTriangulation::canonicalise), slot -> index.
        let mut live: Vec<u32> = (0..self.tri.len() as u32)
            .filter(|&t| self.tri.triangles[t as usize][0] != NO_TRIANGLE)
            .collect();
        // In pattern indices.
        let external = |t: u32| self.tri.triangles[t as usize].map(|v| self.perm[v as usize]);
        let rotated = |t: u32| {
            let tv = external(t);
            let k = (0..3).min_by_key(|&k| tv[k]).unwrap_or(0);
            [tv[k], tv[(k + 1) % 3], tv[(k + 2) % 3]]
        };
        live.sort_unstable_by_key(|&t| {
            let r = rotated(t);
            (u64::from(r[0]) << 32) | u64::from(r[1])
        });
        let mut index_of = vec![NO_TRIANGLE; self.tri.len()];
        for (k, &t) in live.iter().enumerate() {
            index_of[t as usize] = k as u32;
        }
        let triangles: Vec<[u32; 3]> = live.iter().map(|&t| rotated(t)).collect();
        let neighbours: Vec<[u32; 3]> = live
            .iter()
            .map(|&t| {
                let tv = external(t);
                let k = (0..3).min_by_key(|&k| tv[k]).unwrap_or(0);
                let nb = self.tri.neighbours[t as usize];
                [nb[k], nb[(k + 1) % 3], nb[(k + 2) % 3]].map(|x| {
                    if x == NO_TRIANGLE {
                        x
                    } else {
                        index_of[x as usize]
                    }
                })
            })
            .collect();
        let canonical = DualTriangulation {
            triangles,
            neighbours,
        };
        // First triangle (canonical order) of each point: where its loop starts.
        let incident = canonical.incident_triangles(n);

        // Loops and numbering.
        let mut vertices = Vec::with_capacity(canonical.len() + self.others.len());
        let mut vertex_kinds = Vec::with_capacity(vertices.capacity());
        let mut feet: Vec<FootHint> = Vec::with_capacity(vertices.capacity());
        let mut id_of: HashMap<Key, u32> = HashMap::new();
        let mut triangle_id = vec![u32::MAX; self.tri.len()];
        let mut facet_offsets = Vec::with_capacity(n + 1);
        let mut facet_loops = Vec::with_capacity(canonical.len() * 3);
        facet_offsets.push(0u32);
        let mut fan = Vec::new();
        let mut keys: Vec<Key> = Vec::new();
        for (i, &first) in incident.iter().enumerate() {
            keys.clear();
            match &self.complex[self.rank[i] as usize] {
                Some(list) => keys.extend_from_slice(list),
                None => {
                    canonical.fan(i as u32, first, &mut fan);
                    keys.extend(fan.iter().map(|&c| Key::Triangle(live[c as usize])));
                }
            }
            let start = facet_loops.len();
            for &key in &keys {
                let id = match key {
                    Key::Triangle(t) => {
                        if triangle_id[t as usize] == u32::MAX {
                            triangle_id[t as usize] = vertices.len() as u32;
                            vertices.push(self.vertex[t as usize].point);
                            vertex_kinds.push(VertexKind::Interior);
                            feet.push(
                                self.report_foot[t as usize]
                                    .map_or(FootHint::FromSeed, FootHint::Known),
                            );
                        }
                        triangle_id[t as usize]
                    }
                    Key::Other(o) => *id_of.entry(key).or_insert_with(|| {
                        let other = self.others[o as usize];
                        vertices.push(other.point);
                        vertex_kinds.push(other.kind);
                        feet.push(other.foot.map_or(FootHint::FromSeed, FootHint::Known));
                        (vertices.len() - 1) as u32
                    }),
                };
                if facet_loops.len() == start || facet_loops[facet_loops.len() - 1] != id {
                    facet_loops.push(id);
                }
            }
            while facet_loops.len() > start + 1
                && facet_loops[start] == facet_loops[facet_loops.len() - 1]
            {
                facet_loops.pop();
            }
            facet_offsets.push(facet_loops.len() as u32);
        }
        // Per-point data in pattern order.
        let internal = |i: usize| self.rank[i] as usize;
        let seeds: Vec<Seed> = (0..n).map(|i| self.seeds[internal(i)]).collect();
        let uv: Vec<[f64; 2]> = (0..n).map(|i| self.uv[internal(i)]).collect();
        let planes: Vec<Plane> = (0..n).map(|i| self.planes[internal(i)]).collect();
        let slopes: Vec<[f64; 2]> = (0..n).map(|i| self.slopes[internal(i)]).collect();
        let stats = NeighbourStats {
            envelope_repairs: slope_repairs(&canonical, &slopes),
            ..self.stats
        };
        // The incremental path runs only on convex surfaces, whose exact planes stay.
        let adjustments = if options.planes == PlaneMode::Adjusted {
            plane_adjustments(&seeds, &planes)
        } else {
            Vec::new()
        };
        let mut result = Discretisation {
            vertices,
            vertex_kinds,
            facet_offsets,
            facet_loops,
            seeds,
            pattern_indices: Vec::new(),
            outside_trim: 0,
            dual_triangles: canonical.triangles,
            ghost_neighbours: Vec::new(),
            quality: None,
            facet_flags: Vec::new(),
            diagnostics: self.diagnostics.clone(),
            plane_adjustments: adjustments,
            timings: Timings::default(),
            units: surface.units(),
            topology: MeshTopology::DISC,
        };
        if options.quality_report {
            let diagnosed = diagnosed_points(&result.diagnostics, n);
            let (quality, flags) = report(
                &ReportInput {
                    surface,
                    uv: &uv,
                    planes: &planes,
                    vertices: &result.vertices,
                    offsets: &result.facet_offsets,
                    loops: &result.facet_loops,
                    diagonal: self.diagonal,
                    diagnosed: &diagnosed,
                    neighbours: stats,
                    diagnostic_count: result.diagnostics.len(),
                    convex_side: &self.convex_side,
                    wrap: &self.wrap,
                },
                feet,
                &NoProgress,
            );
            result.quality = Some(quality);
            result.facet_flags = flags;
            crate::discretise::note_topology(&mut result, false);
        }
        result
    }
}

/// Buffers reused from edit to edit (no heap allocation on the incremental path).
#[derive(Default)]
struct Scratch {
    created: Vec<u32>,
    points: Vec<u32>,
    fan: Vec<u32>,
    link: Vec<u32>,
    outer: Vec<u32>,
    stack: Vec<(u32, usize)>,
    list: Vec<u32>,
}

/// What an edit changed in the structure.
#[derive(Default)]
struct Changed {
    /// Slots created (some may have been freed again by later flips).
    created: Vec<u32>,
    /// Points whose triangles changed.
    points: Vec<u32>,
}

/// A facet's seed from the point's local geometry, as the pipeline makes it.
fn seed(g: &LocalGeometry, uv: [f64; 2]) -> Seed {
    Seed {
        uv,
        point: g.point,
        normal: g.normal,
        curvatures: [g.k1, g.k2],
    }
}

/// Whether x attains a coordinate of the box (it may bound it).
fn on_box(x: DVec3, (lo, hi): (DVec3, DVec3)) -> bool {
    (0..3).any(|k| x[k] <= lo[k] || x[k] >= hi[k])
}

/// Whether x lies strictly inside the box in every coordinate.
fn strictly_inside_box(x: DVec3, bbox: (DVec3, DVec3)) -> bool {
    !on_box(x, bbox)
}

/// Renumbers a diagnostic's points after point k was removed.
fn renumber_diagnostic(d: &mut Diagnostic, k: u32) {
    let shift = |p: &mut u32| {
        if *p > k {
            *p -= 1;
        }
    };
    match d {
        Diagnostic::IllConditionedVertex { points, .. } => points.iter_mut().for_each(shift),
        Diagnostic::ParallelPlanes { points } | Diagnostic::BoundaryNotReached { points } => {
            points.iter_mut().for_each(shift)
        }
        Diagnostic::OpenFacet { point, .. }
        | Diagnostic::CornerUnreachable { point, .. }
        | Diagnostic::FlatPoint { point, .. }
        | Diagnostic::FacetPartsLeftOut { point, .. } => shift(point),
        Diagnostic::CornerClaims { .. }
        | Diagnostic::CoincidentPlanes { .. }
        | Diagnostic::SeamLeftOpen { .. }
        | Diagnostic::RulingStrips { .. }
        | Diagnostic::UnexpectedTopology { .. } => {}
    }
}

/// The report's foot of a triangle vertex whose first facet is `seed`
/// ([`crate::quality::resolve_foot`]).
fn report_foot(
    surface: &dyn Surface,
    wrap: &Wrap,
    vertex: &TriangleVertex,
    seed_uv: [f64; 2],
) -> [f64; 2] {
    resolve_foot(surface, wrap, vertex.point, vertex.hint(), seed_uv)
}
