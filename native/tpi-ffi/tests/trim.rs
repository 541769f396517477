//! `tpi_surface_with_trim`: a dome trimmed to a disc through the C ABI keeps the pattern
//! points inside, and every malformed input is a typed status naming the item.

#![allow(clippy::type_complexity)]

mod common;

use common::*;
use tpi::*;

/// A counter-clockwise polygon of `n` points approximating the circle of radius `r` around
/// (0.5, 0.5) in the dome's parameters.
fn disc(n: usize, r: f64) -> Vec<f64> {
    (0..n)
        .flat_map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            [0.5 + r * a.cos(), 0.5 + r * a.sin()]
        })
        .collect()
}

fn in_polygon(flat: &[f64], p: [f64; 2]) -> bool {
    let pts: Vec<[f64; 2]> = flat.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
    let mut inside = false;
    let mut j = pts.len() - 1;
    for i in 0..pts.len() {
        let (a, b) = (pts[i], pts[j]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]
        {
            inside = !inside;
        }
        j = i;
    }
    inside
}

fn with_trim(
    surface: *const TpiSurface,
    outer: &[f64],
    holes: &[f64],
    counts: &[usize],
) -> (TpiStatus, *mut TpiSurface) {
    let mut out = 1usize as *mut TpiSurface;
    // SAFETY: valid arrays for their lengths, a live handle and a valid out pointer.
    let status = unsafe {
        tpi_surface_with_trim(
            surface,
            outer.as_ptr(),
            outer.len(),
            holes.as_ptr(),
            holes.len(),
            counts.as_ptr(),
            counts.len(),
            &mut out,
        )
    };
    (status, out)
}

#[test]
fn a_dome_trimmed_to_a_disc_keeps_the_points_inside() {
    let dome = dome(2.0);
    let outer = disc(48, 0.4);
    let (status, trimmed) = with_trim(dome, &outer, &[], &[]);
    ok(status);
    let points = jittered_grid(9);
    let inside = points.iter().filter(|&&p| in_polygon(&outer, p)).count();
    assert!(inside > 10 && inside < points.len());
    let mesh = discretise_from_scratch(trimmed, &points);
    assert_eq!(mesh.facet_sizes.len(), inside);
    let full = discretise_from_scratch(dome, &points);
    assert_eq!(full.facet_sizes.len(), points.len());

    // The domain and evaluation are the untrimmed surface's.
    let (mut d1, mut d2) = (TpiDomain::default(), TpiDomain::default());
    // SAFETY: live handles, valid out pointers.
    ok(unsafe { tpi_surface_domain(dome, &mut d1) });
    ok(unsafe { tpi_surface_domain(trimmed, &mut d2) });
    assert_eq!(d1, d2);
    let uv = [0.1, 0.1];
    let (mut s1, mut s2) = (TpiSample::default(), TpiSample::default());
    // SAFETY: as above, one sample each.
    ok(unsafe { tpi_surface_evaluate(dome, uv.as_ptr(), 2, &mut s1, 1) });
    ok(unsafe { tpi_surface_evaluate(trimmed, uv.as_ptr(), 2, &mut s2, 1) });
    assert_eq!(s1, s2);

    // Units keep the trim; a hole leaves its points out too.
    let mut with_units = std::ptr::null_mut();
    // SAFETY: live handle, valid out pointer.
    ok(unsafe { tpi_surface_with_units(trimmed, TPI_UNITS_METERS, &mut with_units) });
    assert_eq!(
        discretise_from_scratch(with_units, &points)
            .facet_sizes
            .len(),
        inside
    );
    let mut hole = disc(12, 0.1);
    let reversed: Vec<f64> = hole
        .chunks_exact(2)
        .rev()
        .flat_map(|c| [c[0], c[1]])
        .collect();
    hole = reversed;
    let (status, holed) = with_trim(dome, &outer, &hole, &[12]);
    ok(status);
    let kept = points
        .iter()
        .filter(|&&p| in_polygon(&outer, p) && !in_polygon(&hole, p))
        .count();
    assert!(kept < inside);
    assert_eq!(
        discretise_from_scratch(holed, &points).facet_sizes.len(),
        kept
    );

    // Live editing refuses a trim with a typed error.
    let p = pattern(&points);
    let mut ds = 1usize as *mut TpiDiscreteSurface;
    // SAFETY: live handles, valid out pointer.
    let status = unsafe { tpi_discrete_surface_new(trimmed, p, std::ptr::null(), &mut ds) };
    assert_eq!(status, TpiStatus::InvalidArgument, "{}", last_error());
    assert!(ds.is_null());
    assert!(last_error().contains("trim"), "{}", last_error());
    // ...and so does replacing a live surface's surface by a trimmed one, keeping the old one.
    let mut live = std::ptr::null_mut();
    // SAFETY: live handles, valid out pointer.
    ok(unsafe { tpi_discrete_surface_new(dome, p, std::ptr::null(), &mut live) });
    // SAFETY: live handles.
    ok(unsafe { tpi_discrete_surface_set_surface(live, trimmed) });
    let status = unsafe { tpi_discrete_surface_recompute(live) };
    assert_eq!(status, TpiStatus::InvalidArgument, "{}", last_error());
    assert!(last_error().contains("trim"), "{}", last_error());
    assert_eq!(current_mesh(live).facet_sizes.len(), points.len());
    // SAFETY: our handle, freed once.
    unsafe { tpi_discrete_surface_free(live) };

    // SAFETY: our handles, freed once.
    unsafe {
        tpi_pattern_free(p);
        tpi_surface_free(holed);
        tpi_surface_free(with_units);
        tpi_surface_free(trimmed);
        tpi_surface_free(dome);
    }
}

#[test]
fn bad_trims_are_typed_errors_naming_the_item() {
    let dome = dome(2.0);
    let outer = disc(16, 0.4);
    let clockwise: Vec<f64> = outer
        .chunks_exact(2)
        .rev()
        .flat_map(|c| [c[0], c[1]])
        .collect();
    let mut nan = outer.clone();
    nan[7] = f64::NAN;
    let mut outside = outer.clone();
    outside[4] = 1.5;
    let hole_ccw = disc(6, 0.1);
    let cases: Vec<(&str, Vec<f64>, Vec<f64>, Vec<usize>, TpiStatus, &str)> = vec![
        (
            "clockwise outer",
            clockwise,
            vec![],
            vec![],
            TpiStatus::InvalidArgument,
            "trim.outer",
        ),
        (
            "odd length",
            outer[..5].to_vec(),
            vec![],
            vec![],
            TpiStatus::InvalidArgument,
            "outer_uv",
        ),
        (
            "non-finite",
            nan,
            vec![],
            vec![],
            TpiStatus::NonFinite,
            "trim.outer[3][1]",
        ),
        (
            "outside the domain",
            outside,
            vec![],
            vec![],
            TpiStatus::InvalidArgument,
            "trim.outer[2]",
        ),
        (
            "two points",
            outer[..4].to_vec(),
            vec![],
            vec![],
            TpiStatus::InvalidArgument,
            "trim.outer",
        ),
        (
            "counter-clockwise hole",
            outer.clone(),
            hole_ccw.clone(),
            vec![6],
            TpiStatus::InvalidArgument,
            "trim.holes[0]",
        ),
        (
            "counts not adding up",
            outer.clone(),
            hole_ccw.clone(),
            vec![5],
            TpiStatus::InvalidArgument,
            "hole_point_counts",
        ),
        (
            "odd hole length",
            outer.clone(),
            hole_ccw[..11].to_vec(),
            vec![5],
            TpiStatus::InvalidArgument,
            "holes_uv",
        ),
    ];
    for (what, o, h, c, status, item) in cases {
        let (got, out) = with_trim(dome, &o, &h, &c);
        assert_eq!(got, status, "{what}: {}", last_error());
        assert!(out.is_null(), "{what}");
        assert!(last_error().contains(item), "{what}: {}", last_error());
    }

    // NULL pointers with non-zero lengths, a NULL surface, a NULL out.
    let mut out = std::ptr::null_mut();
    // SAFETY: every non-NULL pointer is valid; the NULL ones are what is tested.
    unsafe {
        let null = std::ptr::null::<f64>();
        let nc = std::ptr::null::<usize>();
        assert_eq!(
            tpi_surface_with_trim(dome, null, 6, null, 0, nc, 0, &mut out),
            TpiStatus::NullPointer
        );
        assert!(last_error().contains("outer_uv"));
        assert_eq!(
            tpi_surface_with_trim(dome, outer.as_ptr(), outer.len(), null, 4, nc, 0, &mut out),
            TpiStatus::NullPointer
        );
        assert!(last_error().contains("holes_uv"));
        assert_eq!(
            tpi_surface_with_trim(dome, outer.as_ptr(), outer.len(), null, 0, nc, 1, &mut out),
            TpiStatus::NullPointer
        );
        assert!(last_error().contains("hole_point_counts"));
        assert_eq!(
            tpi_surface_with_trim(
                std::ptr::null(),
                outer.as_ptr(),
                outer.len(),
                null,
                0,
                nc,
                0,
                &mut out
            ),
            TpiStatus::NullPointer
        );
        assert_eq!(
            tpi_surface_with_trim(
                dome,
                outer.as_ptr(),
                outer.len(),
                null,
                0,
                nc,
                0,
                std::ptr::null_mut()
            ),
            TpiStatus::NullPointer
        );
        tpi_surface_free(dome);
    }
}
