//! Editing a discrete surface (move, add, remove a pattern point; replace the surface) and
//! recomputing gives exactly the mesh that discretising the edited inputs from scratch gives,
//! all through the C ABI functions.

mod common;

use common::*;
use tpi::*;

struct Fixture {
    surface: *mut TpiSurface,
    ds: *mut TpiDiscreteSurface,
    points: Vec<[f64; 2]>,
}

impl Fixture {
    fn new() -> Self {
        let surface = dome(3.0);
        let points = jittered_grid(7);
        let p = pattern(&points);
        let mut ds = std::ptr::null_mut();
        // SAFETY: live handles, default options, valid out pointer.
        ok(unsafe { tpi_discrete_surface_new(surface, p, std::ptr::null(), &mut ds) });
        // SAFETY: the discrete surface holds its own copy of the pattern.
        unsafe { tpi_pattern_free(p) };
        Self {
            surface,
            ds,
            points,
        }
    }

    fn pending(&self) -> usize {
        let mut n = usize::MAX;
        // SAFETY: live handle, valid out pointer.
        ok(unsafe { tpi_discrete_surface_pending_edits(self.ds, &mut n) });
        n
    }

    fn recompute(&self) {
        // SAFETY: live handle.
        ok(unsafe { tpi_discrete_surface_recompute(self.ds) });
        assert_eq!(self.pending(), 0);
    }

    /// The discrete surface's points and mesh agree with a discretisation from scratch.
    fn check_against_scratch(&self) {
        assert_eq!(current_points(self.ds), self.points);
        let edited = current_mesh(self.ds);
        let scratch = discretise_from_scratch(self.surface, &self.points);
        assert_eq!(edited.facet_sizes.len(), self.points.len());
        assert_eq!(edited, scratch);
    }
}

impl Drop for Fixture {
    fn drop(&mut self) {
        // SAFETY: our handles, freed once.
        unsafe {
            tpi_discrete_surface_free(self.ds);
            tpi_surface_free(self.surface);
        }
    }
}

#[test]
fn the_first_mesh_is_the_discretisation_of_the_inputs() {
    Fixture::new().check_against_scratch();
}

#[test]
fn moving_a_point_gives_the_mesh_from_scratch() {
    let mut f = Fixture::new();
    let before = current_mesh(f.ds);
    // SAFETY: live handle.
    ok(unsafe { tpi_discrete_surface_move_point(f.ds, 10, 0.41, 0.37) });
    f.points[10] = [0.41, 0.37];
    assert_eq!(f.pending(), 1);
    assert_eq!(
        current_mesh(f.ds),
        before,
        "the mesh changes only at recompute"
    );
    f.recompute();
    assert_ne!(current_mesh(f.ds), before);
    f.check_against_scratch();
}

#[test]
fn adding_a_point_gives_the_mesh_from_scratch() {
    let mut f = Fixture::new();
    let mut index = usize::MAX;
    // SAFETY: live handle, valid out pointer.
    ok(unsafe { tpi_discrete_surface_add_point(f.ds, 0.05, 0.93, &mut index) });
    assert_eq!(index, f.points.len());
    f.points.push([0.05, 0.93]);
    // NULL index is allowed.
    // SAFETY: live handle.
    ok(unsafe { tpi_discrete_surface_add_point(f.ds, 0.52, 0.48, std::ptr::null_mut()) });
    f.points.push([0.52, 0.48]);
    assert_eq!(f.pending(), 2);
    f.recompute();
    f.check_against_scratch();
}

#[test]
fn removing_a_point_gives_the_mesh_from_scratch() {
    let mut f = Fixture::new();
    // SAFETY: live handle.
    ok(unsafe { tpi_discrete_surface_remove_point(f.ds, 3) });
    f.points.remove(3);
    f.recompute();
    f.check_against_scratch();
    // SAFETY: live handle.
    ok(unsafe { tpi_discrete_surface_remove_point(f.ds, f.points.len() - 1) });
    f.points.pop();
    f.recompute();
    f.check_against_scratch();
}

#[test]
fn replacing_the_surface_gives_the_mesh_from_scratch() {
    let mut f = Fixture::new();
    let taller = dome(4.5);
    // SAFETY: live handles.
    ok(unsafe { tpi_discrete_surface_set_surface(f.ds, taller) });
    // The discrete surface copied it: freeing ours must not matter.
    // SAFETY: our handles.
    unsafe { tpi_surface_free(f.surface) };
    f.surface = taller;
    f.recompute();
    f.check_against_scratch();
}

#[test]
fn a_batch_of_edits_then_one_recompute_gives_the_mesh_from_scratch() {
    let mut f = Fixture::new();
    let other = dome(2.0);
    // SAFETY: live handles throughout.
    unsafe {
        ok(tpi_discrete_surface_move_point(f.ds, 0, 0.02, 0.03));
        ok(tpi_discrete_surface_remove_point(f.ds, 20));
        ok(tpi_discrete_surface_add_point(
            f.ds,
            0.97,
            0.5,
            std::ptr::null_mut(),
        ));
        ok(tpi_discrete_surface_move_point(f.ds, 30, 0.6, 0.66));
        ok(tpi_discrete_surface_set_surface(f.ds, other));
        tpi_surface_free(f.surface);
    }
    f.surface = other;
    f.points[0] = [0.02, 0.03];
    f.points.remove(20);
    f.points.push([0.97, 0.5]);
    f.points[30] = [0.6, 0.66];
    assert_eq!(f.pending(), 5);
    f.recompute();
    f.check_against_scratch();
}

#[test]
fn a_recompute_that_fails_keeps_the_edits_pending_and_the_last_mesh() {
    let mut f = Fixture::new();
    let before = current_mesh(f.ds);
    let duplicate = f.points[1];
    // SAFETY: live handle.
    ok(unsafe { tpi_discrete_surface_move_point(f.ds, 0, duplicate[0], duplicate[1]) });
    // SAFETY: live handle.
    let status = unsafe { tpi_discrete_surface_recompute(f.ds) };
    assert_eq!(status, TpiStatus::InvalidPattern);
    assert!(last_error().contains("duplicates"), "{}", last_error());
    assert_eq!(f.pending(), 1);
    assert_eq!(current_mesh(f.ds), before);
    // Fix the edit and recompute.
    // SAFETY: live handle.
    ok(unsafe { tpi_discrete_surface_move_point(f.ds, 0, 0.01, 0.01) });
    f.points[0] = [0.01, 0.01];
    f.recompute();
    f.check_against_scratch();
}

#[test]
fn rejected_edits_change_nothing() {
    let f = Fixture::new();
    let n = f.points.len();
    // SAFETY: live handle throughout.
    unsafe {
        assert_eq!(
            tpi_discrete_surface_move_point(f.ds, n, 0.5, 0.5),
            TpiStatus::IndexOutOfRange
        );
        assert!(last_error().contains(&n.to_string()));
        assert_eq!(
            tpi_discrete_surface_remove_point(f.ds, n),
            TpiStatus::IndexOutOfRange
        );
        assert_eq!(
            tpi_discrete_surface_remove_point(f.ds, usize::MAX),
            TpiStatus::IndexOutOfRange
        );
        assert_eq!(
            tpi_discrete_surface_move_point(f.ds, 0, f64::NAN, 0.5),
            TpiStatus::NonFinite
        );
        assert_eq!(
            tpi_discrete_surface_move_point(f.ds, 0, 0.5, f64::INFINITY),
            TpiStatus::NonFinite
        );
        assert_eq!(
            tpi_discrete_surface_move_point(f.ds, 0, 1.5, 0.5),
            TpiStatus::InvalidPattern
        );
        assert_eq!(
            tpi_discrete_surface_add_point(f.ds, -0.1, 0.5, std::ptr::null_mut()),
            TpiStatus::InvalidPattern
        );
        assert_eq!(
            tpi_discrete_surface_add_point(f.ds, f64::NAN, 0.5, std::ptr::null_mut()),
            TpiStatus::NonFinite
        );
        assert_eq!(
            tpi_discrete_surface_set_surface(f.ds, std::ptr::null()),
            TpiStatus::NullPointer
        );
    }
    assert_eq!(f.pending(), 0);
    f.check_against_scratch();
}

#[test]
fn a_mesh_taken_from_a_discrete_surface_outlives_it_and_later_edits() {
    let f = Fixture::new();
    let mut d = std::ptr::null_mut();
    // SAFETY: live handle, valid out pointer.
    ok(unsafe { tpi_discrete_surface_mesh(f.ds, &mut d) });
    let before = read_mesh(d);
    // SAFETY: live handle.
    ok(unsafe { tpi_discrete_surface_move_point(f.ds, 5, 0.3, 0.31) });
    f.recompute();
    drop(f);
    assert_eq!(read_mesh(d), before);
    // SAFETY: our handle.
    unsafe { tpi_discretisation_free(d) };
}

#[test]
fn concurrent_edits_on_one_discrete_surface_are_serialised() {
    let f = Fixture::new();
    let ds = f.ds as usize;
    let threads: Vec<_> = (0..4)
        .map(|k| {
            std::thread::spawn(move || {
                let ds = ds as *mut TpiDiscreteSurface;
                for m in 0..5 {
                    let s = 0.02 + 0.2 * k as f64 + 0.03 * m as f64;
                    // SAFETY: the handle outlives the threads (joined below).
                    ok(unsafe {
                        tpi_discrete_surface_add_point(
                            ds,
                            s,
                            0.999 - 0.001 * k as f64,
                            std::ptr::null_mut(),
                        )
                    });
                }
                // SAFETY: as above.
                ok(unsafe { tpi_discrete_surface_recompute(ds) });
            })
        })
        .collect();
    for t in threads {
        t.join().expect("no thread may die");
    }
    let points = current_points(f.ds);
    assert_eq!(points.len(), f.points.len() + 20);
    assert_eq!(f.pending(), 0);
    let scratch = discretise_from_scratch(f.surface, &points);
    assert_eq!(current_mesh(f.ds), scratch);
}

#[test]
fn single_edits_recomputed_one_by_one_give_the_mesh_from_scratch() {
    // One edit per recompute takes the core's live editing where it can (interior points of
    // this convex dome); every mesh must still be the one from scratch.
    let surface = dome(3.0);
    let mut points = jittered_grid(13);
    let p = pattern(&points);
    let mut ds = std::ptr::null_mut();
    // SAFETY: live handles, default options, valid out pointer.
    ok(unsafe { tpi_discrete_surface_new(surface, p, std::ptr::null(), &mut ds) });
    // SAFETY: the discrete surface holds its own copy of the pattern.
    unsafe { tpi_pattern_free(p) };
    let mut state = 12345u64;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for step in 0..60 {
        let n = points.len();
        let i = ((next() * n as f64) as usize).min(n - 1);
        // SAFETY (all calls): live handle.
        match step % 6 {
            0..=3 => {
                let q = [
                    (points[i][0] + 0.03 * (next() - 0.5)).clamp(0.0, 1.0),
                    (points[i][1] + 0.03 * (next() - 0.5)).clamp(0.0, 1.0),
                ];
                ok(unsafe { tpi_discrete_surface_move_point(ds, i, q[0], q[1]) });
                points[i] = q;
            }
            4 => {
                let q = [0.2 + 0.6 * next(), 0.2 + 0.6 * next()];
                ok(unsafe { tpi_discrete_surface_add_point(ds, q[0], q[1], std::ptr::null_mut()) });
                points.push(q);
            }
            _ => {
                ok(unsafe { tpi_discrete_surface_remove_point(ds, i) });
                points.remove(i);
            }
        }
        // SAFETY: live handle.
        ok(unsafe { tpi_discrete_surface_recompute(ds) });
        assert_eq!(current_points(ds), points);
        assert_eq!(
            current_mesh(ds),
            discretise_from_scratch(surface, &points),
            "after edit {step}"
        );
    }
    // SAFETY: our handles, freed once.
    unsafe {
        tpi_discrete_surface_free(ds);
        tpi_surface_free(surface);
    }
}

/// Issue 14: a discretisation handle passed where a discrete surface is expected (a C# host
/// passing the wrong IntPtr) used to be read as a discrete surface's lock and hang forever.
/// Every call refuses a handle of another kind with TPI_STATUS_INVALID_HANDLE, names both
/// kinds, and changes nothing; a `*_free` call given the wrong kind does nothing.
#[test]
fn a_handle_of_another_kind_is_refused_not_read() {
    let f = Fixture::new();
    let mut mesh = std::ptr::null_mut();
    // SAFETY: live handle, valid out pointer.
    ok(unsafe { tpi_discrete_surface_mesh(f.ds, &mut mesh) });
    let wrong_ds = mesh.cast::<TpiDiscreteSurface>();
    // SAFETY: every pointer is a live handle of this library (of the wrong kind on purpose).
    unsafe {
        assert_eq!(
            tpi_discrete_surface_move_point(wrong_ds, 0, 0.5, 0.5),
            TpiStatus::InvalidHandle
        );
        let message = last_error();
        assert!(
            message.contains("TpiDiscretisation") && message.contains("TpiDiscreteSurface"),
            "{message}"
        );
        assert_eq!(
            tpi_discrete_surface_recompute(wrong_ds),
            TpiStatus::InvalidHandle
        );
        let mut n = 0usize;
        assert_eq!(
            tpi_discretisation_facet_count(f.ds.cast(), &mut n),
            TpiStatus::InvalidHandle
        );
        assert_eq!(
            tpi_surface_domain(f.ds.cast(), &mut TpiDomain::default()),
            TpiStatus::InvalidHandle
        );
        let mut out = std::ptr::null_mut();
        assert_eq!(
            tpi_discretise(f.surface, f.surface.cast(), std::ptr::null(), &mut out),
            TpiStatus::InvalidHandle
        );
        assert!(out.is_null());
        // Freeing with the wrong kind is ignored: both objects stay usable.
        tpi_surface_free(mesh.cast());
        tpi_pattern_free(f.ds.cast());
        ok(tpi_discretisation_facet_count(mesh, &mut n));
        assert_eq!(n, f.points.len());
        tpi_discretisation_free(mesh);
    }
    f.check_against_scratch();
}
