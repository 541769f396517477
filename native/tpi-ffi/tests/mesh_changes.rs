//! Issue 13, item 4: what changed in a discrete surface's mesh (`tpi_discrete_surface_changes`
//! and the `tpi_mesh_changes_*` calls). A host that keeps its copy of the mesh only from the
//! changes has, after every edit, the mesh of `tpi_discrete_surface_mesh` (and of a
//! discretisation from scratch): the same vertex positions facet by facet, the same planes.

mod common;

use common::*;
use tpi::*;

/// The changes snapshot read through every call.
struct Changes {
    everything: bool,
    facet_count: usize,
    vertex_id_bound: usize,
    facets: Vec<u32>,
    sizes: Vec<u32>,
    loops: Vec<u32>,
    planes: Vec<TpiPlane>,
    vertex_ids: Vec<u32>,
    vertices: Vec<f64>,
}

/// Takes and reads the changes of a discrete surface.
fn take_changes(ds: *mut TpiDiscreteSurface) -> Changes {
    let mut c = std::ptr::null_mut();
    // SAFETY: live handle, valid out pointer.
    ok(unsafe { tpi_discrete_surface_changes(ds, &mut c) });
    let (mut everything, mut facet_count, mut vertex_id_bound) = (7u32, 0usize, 0usize);
    // SAFETY (all calls): `c` is a live handle; buffers from read_array.
    let changes = unsafe {
        ok(tpi_mesh_changes_counts(
            c,
            &mut everything,
            &mut facet_count,
            &mut vertex_id_bound,
        ));
        Changes {
            everything: everything == 1,
            facet_count,
            vertex_id_bound,
            facets: read_array(|o, n, k| tpi_mesh_changes_facets(c, o, n, k)),
            sizes: read_array(|o, n, k| tpi_mesh_changes_facet_sizes(c, o, n, k)),
            loops: read_array(|o, n, k| tpi_mesh_changes_facet_indices(c, o, n, k)),
            planes: read_array(|o, n, k| tpi_mesh_changes_planes(c, o, n, k)),
            vertex_ids: read_array(|o, n, k| tpi_mesh_changes_vertex_ids(c, o, n, k)),
            vertices: read_array(|o, n, k| tpi_mesh_changes_vertices(c, o, n, k)),
        }
    };
    assert!(everything <= 1);
    // SAFETY: our handle, freed once.
    unsafe { tpi_mesh_changes_free(c) };
    changes
}

/// A host's copy kept only from the changes.
#[derive(Default)]
struct Replica {
    vertices: Vec<Option<[f64; 3]>>,
    loops: Vec<Vec<u32>>,
    planes: Vec<TpiPlane>,
}

impl Replica {
    /// Applies the changes; returns how many facets they listed.
    fn apply(&mut self, c: &Changes) -> usize {
        assert_eq!(c.sizes.len(), c.facets.len());
        assert_eq!(c.planes.len(), c.facets.len());
        assert_eq!(c.loops.len() as u32, c.sizes.iter().sum::<u32>());
        assert_eq!(c.vertices.len(), 3 * c.vertex_ids.len());
        assert!(c.facets.windows(2).all(|w| w[0] < w[1]));
        assert!(c.vertex_ids.windows(2).all(|w| w[0] < w[1]));
        if c.everything {
            *self = Replica::default();
            assert_eq!(
                c.facets.len(),
                c.facet_count,
                "everything lists every facet"
            );
        }
        self.vertices.resize(c.vertex_id_bound, None);
        self.loops.resize(c.facet_count, Vec::new());
        self.planes.resize(c.facet_count, TpiPlane::default());
        let mut start = 0usize;
        for (k, &f) in c.facets.iter().enumerate() {
            let end = start + c.sizes[k] as usize;
            self.loops[f as usize] = c.loops[start..end].to_vec();
            self.planes[f as usize] = c.planes[k];
            start = end;
        }
        for (k, &id) in c.vertex_ids.iter().enumerate() {
            self.vertices[id as usize] = Some([
                c.vertices[3 * k],
                c.vertices[3 * k + 1],
                c.vertices[3 * k + 2],
            ]);
        }
        c.facets.len()
    }

    /// Every facet's vertex positions and plane, bit for bit, against a mesh read whole.
    fn assert_equals(&self, mesh: &Mesh, what: &str) {
        assert_eq!(self.loops.len(), mesh.facet_sizes.len(), "{what}");
        let bits = |x: [f64; 3]| x.map(f64::to_bits);
        let mut start = 0usize;
        for (f, &size) in mesh.facet_sizes.iter().enumerate() {
            let expected: Vec<_> = mesh.facet_indices[start..start + size as usize]
                .iter()
                .map(|&v| {
                    let v = 3 * v as usize;
                    bits([mesh.vertices[v], mesh.vertices[v + 1], mesh.vertices[v + 2]])
                })
                .collect();
            start += size as usize;
            let got: Vec<_> = self.loops[f]
                .iter()
                .map(|&id| bits(self.vertices[id as usize].expect("a listed vertex")))
                .collect();
            assert_eq!(got, expected, "{what}: facet {f}");
            assert_eq!(self.planes[f], mesh.planes[f], "{what}: plane of facet {f}");
        }
    }
}

fn new_discrete_surface(
    surface: *const TpiSurface,
    points: &[[f64; 2]],
) -> *mut TpiDiscreteSurface {
    let p = pattern(points);
    let mut ds = std::ptr::null_mut();
    // SAFETY: live handles, default options, valid out pointer.
    ok(unsafe { tpi_discrete_surface_new(surface, p, std::ptr::null(), &mut ds) });
    // SAFETY: the discrete surface holds its own copy of the pattern.
    unsafe { tpi_pattern_free(p) };
    ds
}

#[test]
fn a_copy_kept_from_the_changes_is_the_mesh_after_every_edit() {
    let surface = dome(3.0);
    let mut points = jittered_grid(16);
    let ds = new_discrete_surface(surface, &points);
    let mut replica = Replica::default();
    let first = take_changes(ds);
    assert!(first.everything, "the first changes list everything");
    replica.apply(&first);
    replica.assert_equals(&current_mesh(ds), "new");
    let nothing = take_changes(ds);
    assert!(!nothing.everything && nothing.facets.is_empty() && nothing.vertex_ids.is_empty());
    assert_eq!(nothing.facet_count, points.len());
    let mut state = 4242u64;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut small = 0;
    for step in 0..80 {
        let n = points.len();
        let i = ((next() * n as f64) as usize).min(n - 1);
        let kind = step % 8;
        // SAFETY (all calls): live handle.
        match kind {
            0..=5 => {
                let q = [
                    (points[i][0] + 0.02 * (next() - 0.5)).clamp(0.0, 1.0),
                    (points[i][1] + 0.02 * (next() - 0.5)).clamp(0.0, 1.0),
                ];
                ok(unsafe { tpi_discrete_surface_move_point(ds, i, q[0], q[1]) });
                points[i] = q;
            }
            6 => {
                let q = [0.2 + 0.6 * next(), 0.2 + 0.6 * next()];
                ok(unsafe { tpi_discrete_surface_add_point(ds, q[0], q[1], std::ptr::null_mut()) });
                points.push(q);
            }
            _ => {
                ok(unsafe { tpi_discrete_surface_remove_point(ds, i) });
                points.remove(i);
            }
        }
        let pending = take_changes(ds);
        assert!(
            pending.facets.is_empty(),
            "pending edits change nothing yet"
        );
        // SAFETY: live handle.
        ok(unsafe { tpi_discrete_surface_recompute(ds) });
        let changes = take_changes(ds);
        let listed = replica.apply(&changes);
        if kind <= 5 && !changes.everything {
            assert!(listed < 30, "step {step}: a move listed {listed} facets");
            small += 1;
        }
        let what = format!("after edit {step}");
        let mesh = current_mesh(ds);
        replica.assert_equals(&mesh, &what);
        assert_eq!(mesh, discretise_from_scratch(surface, &points), "{what}");
    }
    assert!(small > 20, "most moves take live editing: {small}");
    // Several recomputes between two snapshots, and a batch: one snapshot covers them.
    // SAFETY (all calls): live handle.
    unsafe {
        ok(tpi_discrete_surface_move_point(ds, 100, 0.5, 0.51));
        ok(tpi_discrete_surface_recompute(ds));
        ok(tpi_discrete_surface_remove_point(ds, 40));
        ok(tpi_discrete_surface_recompute(ds));
        ok(tpi_discrete_surface_move_point(ds, 120, 0.47, 0.44));
        ok(tpi_discrete_surface_recompute(ds));
    }
    points[100] = [0.5, 0.51];
    points.remove(40);
    points[120] = [0.47, 0.44];
    let covered = take_changes(ds);
    replica.apply(&covered);
    replica.assert_equals(&current_mesh(ds), "three recomputes, one snapshot");
    let taller = dome(3.5);
    // SAFETY: live handles.
    unsafe {
        ok(tpi_discrete_surface_set_surface(ds, taller));
        ok(tpi_discrete_surface_recompute(ds));
    }
    let everything = take_changes(ds);
    assert!(everything.everything, "a new surface changes everything");
    replica.apply(&everything);
    replica.assert_equals(&current_mesh(ds), "new surface");
    assert_eq!(current_mesh(ds), discretise_from_scratch(taller, &points));
    // SAFETY: our handles, freed once.
    unsafe {
        tpi_discrete_surface_free(ds);
        tpi_surface_free(surface);
        tpi_surface_free(taller);
    }
}

#[test]
fn changes_follow_the_conventions_and_refuse_other_handles() {
    let surface = dome(3.0);
    let ds = new_discrete_surface(surface, &jittered_grid(6));
    let mut c = std::ptr::null_mut();
    let mut mesh = std::ptr::null_mut();
    // SAFETY: every pointer is NULL or a live handle of this library (of the wrong kind on
    // purpose), buffers as declared.
    unsafe {
        ok(tpi_discrete_surface_changes(ds, &mut c));
        ok(tpi_discrete_surface_mesh(ds, &mut mesh));
        // Counts: any out pointer may be NULL.
        ok(tpi_mesh_changes_counts(
            c,
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
        ));
        let mut n = 0usize;
        ok(tpi_mesh_changes_counts(
            c,
            std::ptr::null_mut(),
            &mut n,
            std::ptr::null_mut(),
        ));
        assert_eq!(n, 36);
        // Copy-out: too small a buffer writes nothing and says how much is needed.
        let mut small = [u32::MAX; 3];
        let mut needed = 0usize;
        assert_eq!(
            tpi_mesh_changes_facets(c, small.as_mut_ptr(), small.len(), &mut needed),
            TpiStatus::BufferTooSmall
        );
        assert_eq!(needed, 36);
        assert_eq!(small, [u32::MAX; 3]);
        assert_eq!(
            tpi_mesh_changes_vertices(c, std::ptr::null_mut(), 5, &mut needed),
            TpiStatus::NullPointer
        );
        // NULL and wrong handles.
        let mut out = std::ptr::null_mut();
        assert_eq!(
            tpi_discrete_surface_changes(std::ptr::null_mut(), &mut out),
            TpiStatus::NullPointer
        );
        assert!(out.is_null());
        assert_eq!(
            tpi_discrete_surface_changes(ds, std::ptr::null_mut()),
            TpiStatus::NullPointer
        );
        assert_eq!(
            tpi_mesh_changes_counts(
                std::ptr::null(),
                std::ptr::null_mut(),
                &mut n,
                std::ptr::null_mut()
            ),
            TpiStatus::NullPointer
        );
        assert_eq!(
            tpi_mesh_changes_facets(mesh.cast(), std::ptr::null_mut(), 0, &mut needed),
            TpiStatus::InvalidHandle
        );
        let message = last_error();
        assert!(
            message.contains("TpiDiscretisation") && message.contains("TpiMeshChanges"),
            "{message}"
        );
        assert_eq!(
            tpi_discrete_surface_changes(c.cast(), &mut out),
            TpiStatus::InvalidHandle
        );
        assert!(last_error().contains("TpiMeshChanges"), "{}", last_error());
        assert_eq!(
            tpi_discretisation_facet_count(c.cast(), &mut n),
            TpiStatus::InvalidHandle
        );
        // Freeing with the wrong kind is ignored; NULL is allowed.
        tpi_mesh_changes_free(mesh.cast());
        tpi_discretisation_free(c.cast());
        tpi_mesh_changes_free(std::ptr::null_mut());
        ok(tpi_mesh_changes_counts(
            c,
            std::ptr::null_mut(),
            &mut n,
            std::ptr::null_mut(),
        ));
        ok(tpi_discretisation_facet_count(mesh, &mut n));
        // A snapshot outlives its discrete surface.
        tpi_discrete_surface_free(ds);
        let mut everything = 0u32;
        ok(tpi_mesh_changes_counts(
            c,
            &mut everything,
            &mut n,
            std::ptr::null_mut(),
        ));
        assert_eq!((everything, n), (1, 36));
        tpi_mesh_changes_free(c);
        tpi_discretisation_free(mesh);
        tpi_surface_free(surface);
    }
}
