//! Sequences of C ABI calls as a host would make them (create, edit, recompute, copy out,
//! free), including handles of the wrong kind: never a panic, a hang or a status outside the
//! enum; a wrong-kind handle is always TPI_STATUS_INVALID_HANDLE; messages are bounded.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use tpi::*;

#[derive(Arbitrary, Debug)]
enum Call {
    NewSurface {
        height: i8,
    },
    NewPattern {
        n: u8,
        seed: u8,
    },
    Discretise {
        surface: u8,
        pattern: u8,
    },
    NewLive {
        surface: u8,
        pattern: u8,
    },
    Move {
        live: u8,
        index: u16,
        s: u16,
        t: u16,
    },
    Add {
        live: u8,
        s: u16,
        t: u16,
    },
    Remove {
        live: u8,
        index: u16,
    },
    Recompute {
        live: u8,
    },
    Mesh {
        live: u8,
    },
    CopyVertices {
        mesh: u8,
    },
    WrongKindMove {
        mesh: u8,
    },
    FreeMesh {
        mesh: u8,
    },
    FreeLive {
        live: u8,
    },
}

struct Handles {
    surfaces: Vec<*mut TpiSurface>,
    patterns: Vec<*mut TpiPattern>,
    meshes: Vec<*mut TpiDiscretisation>,
    lives: Vec<*mut TpiDiscreteSurface>,
}

fn pick<T>(v: &[*mut T], k: u8) -> Option<*mut T> {
    (!v.is_empty()).then(|| v[usize::from(k) % v.len()])
}

/// The last error message fits in 4 kB (bounded messages).
fn check_message() {
    let mut buf = vec![0 as std::ffi::c_char; 4096];
    let mut needed = 0usize;
    // SAFETY: buf holds 4096 chars, needed is valid.
    let status = unsafe { tpi_last_error_message(buf.as_mut_ptr(), buf.len(), &mut needed) };
    assert!(
        status == TpiStatus::Ok,
        "message longer than 4 kB: {needed} bytes"
    );
}

fn dome(height: f64) -> *mut TpiSurface {
    const A: [f64; 4] = [-1.0, -1.0 / 3.0, 1.0 / 3.0, 1.0];
    const Q: [f64; 4] = [1.0, -1.0 / 3.0, -1.0 / 3.0, 1.0];
    let mut points = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            points.extend([5.0 * A[i], 5.0 * A[j], height * (1.0 - Q[i] - Q[j])]);
        }
    }
    let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let mut out = std::ptr::null_mut();
    // SAFETY: arrays valid for their lengths, valid out pointer.
    unsafe {
        tpi_surface_new_nurbs(
            3,
            3,
            4,
            4,
            knots.as_ptr(),
            6,
            knots.as_ptr(),
            6,
            points.as_ptr(),
            points.len(),
            std::ptr::null(),
            0,
            &mut out,
        )
    };
    out
}

fuzz_target!(|calls: Vec<Call>| {
    let mut h = Handles {
        surfaces: vec![],
        patterns: vec![],
        meshes: vec![],
        lives: vec![],
    };
    for call in calls.iter().take(64) {
        // SAFETY: every handle comes from this library and is freed once (removed from its
        // list when freed); the wrong-kind calls pass live handles of another kind.
        let status = unsafe {
            match *call {
                Call::NewSurface { height } => {
                    let s = dome(f64::from(height) / 8.0);
                    if !s.is_null() {
                        h.surfaces.push(s);
                    }
                    TpiStatus::Ok
                }
                Call::NewPattern { n, seed } => {
                    let mut p = std::ptr::null_mut();
                    let st = tpi_pattern_new_random(usize::from(n % 200), u64::from(seed), &mut p);
                    if st == TpiStatus::Ok {
                        h.patterns.push(p);
                    }
                    st
                }
                Call::Discretise { surface, pattern } => {
                    match (pick(&h.surfaces, surface), pick(&h.patterns, pattern)) {
                        (Some(s), Some(p)) => {
                            let mut m = std::ptr::null_mut();
                            let st = tpi_discretise(s, p, std::ptr::null(), &mut m);
                            if st == TpiStatus::Ok {
                                h.meshes.push(m);
                            }
                            st
                        }
                        _ => TpiStatus::Ok,
                    }
                }
                Call::NewLive { surface, pattern } => {
                    match (pick(&h.surfaces, surface), pick(&h.patterns, pattern)) {
                        (Some(s), Some(p)) => {
                            let mut l = std::ptr::null_mut();
                            let st = tpi_discrete_surface_new(s, p, std::ptr::null(), &mut l);
                            if st == TpiStatus::Ok {
                                h.lives.push(l);
                            }
                            st
                        }
                        _ => TpiStatus::Ok,
                    }
                }
                Call::Move { live, index, s, t } => match pick(&h.lives, live) {
                    Some(l) => tpi_discrete_surface_move_point(
                        l,
                        usize::from(index),
                        f64::from(s) / 65535.0,
                        f64::from(t) / 65535.0,
                    ),
                    None => TpiStatus::Ok,
                },
                Call::Add { live, s, t } => match pick(&h.lives, live) {
                    Some(l) => {
                        let mut index = 0usize;
                        tpi_discrete_surface_add_point(
                            l,
                            f64::from(s) / 65535.0,
                            f64::from(t) / 65535.0,
                            &mut index,
                        )
                    }
                    None => TpiStatus::Ok,
                },
                Call::Remove { live, index } => match pick(&h.lives, live) {
                    Some(l) => tpi_discrete_surface_remove_point(l, usize::from(index)),
                    None => TpiStatus::Ok,
                },
                Call::Recompute { live } => match pick(&h.lives, live) {
                    Some(l) => tpi_discrete_surface_recompute(l),
                    None => TpiStatus::Ok,
                },
                Call::Mesh { live } => match pick(&h.lives, live) {
                    Some(l) => {
                        let mut m = std::ptr::null_mut();
                        let st = tpi_discrete_surface_mesh(l, &mut m);
                        if st == TpiStatus::Ok {
                            h.meshes.push(m);
                        }
                        st
                    }
                    None => TpiStatus::Ok,
                },
                Call::CopyVertices { mesh } => match pick(&h.meshes, mesh) {
                    Some(m) => {
                        let mut needed = 0usize;
                        let st =
                            tpi_discretisation_vertices(m, std::ptr::null_mut(), 0, &mut needed);
                        if st == TpiStatus::Ok || st == TpiStatus::BufferTooSmall {
                            let mut buf = vec![0.0f64; needed];
                            let st = tpi_discretisation_vertices(
                                m,
                                buf.as_mut_ptr(),
                                buf.len(),
                                &mut needed,
                            );
                            assert_eq!(st, TpiStatus::Ok);
                            assert!(buf.iter().all(|x| x.is_finite()));
                        }
                        TpiStatus::Ok
                    }
                    None => TpiStatus::Ok,
                },
                Call::WrongKindMove { mesh } => match pick(&h.meshes, mesh) {
                    Some(m) => {
                        let st = tpi_discrete_surface_move_point(m.cast(), 0, 0.5, 0.5);
                        assert_eq!(st, TpiStatus::InvalidHandle);
                        st
                    }
                    None => TpiStatus::Ok,
                },
                Call::FreeMesh { mesh } => {
                    if !h.meshes.is_empty() {
                        let k = usize::from(mesh) % h.meshes.len();
                        tpi_discretisation_free(h.meshes.swap_remove(k));
                    }
                    TpiStatus::Ok
                }
                Call::FreeLive { live } => {
                    if !h.lives.is_empty() {
                        let k = usize::from(live) % h.lives.len();
                        tpi_discrete_surface_free(h.lives.swap_remove(k));
                    }
                    TpiStatus::Ok
                }
            }
        };
        assert!(TpiStatus::from_u32(status as u32).is_some());
        assert_ne!(status, TpiStatus::Panic, "{call:?}");
        check_message();
    }
    // SAFETY: every remaining handle is ours and freed once.
    unsafe {
        for m in h.meshes {
            tpi_discretisation_free(m);
        }
        for l in h.lives {
            tpi_discrete_surface_free(l);
        }
        for p in h.patterns {
            tpi_pattern_free(p);
        }
        for s in h.surfaces {
            tpi_surface_free(s);
        }
    }
});
