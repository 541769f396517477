/*
 * tpi.h: the C interface of tpi, planar-facet discretisation of free-form surfaces by tangent
 * plane intersection (libtpi.so / tpi.dll / libtpi.dylib, or the static libtpi.a / tpi.lib).
 *
 * A surface and pattern points in the unit square go in; a mesh comes out with one exactly
 * planar facet per pattern point (facet i belongs to pattern point i), three facets meeting at
 * most vertices, with a quality report and per-point diagnostics.
 *
 *   TpiSurface *surface = NULL; TpiPattern *pattern = NULL; TpiDiscretisation *mesh = NULL;
 *   if (tpi_surface_new_nurbs(3, 3, 4, 4, knots, 6, knots, 6, points, 48, NULL, 0, &surface)
 *       || tpi_pattern_new_hex(12, 12, &pattern)
 *       || tpi_discretise(surface, pattern, NULL, &mesh)) {
 *       char message[512];
 *       tpi_last_error_message(message, sizeof message, NULL);
 *       fprintf(stderr, "tpi: %s\n", message);
 *   }
 *   ... tpi_discretisation_vertices(mesh, ...) ...
 *   tpi_discretisation_free(mesh); tpi_pattern_free(pattern); tpi_surface_free(surface);
 *
 * CONVENTIONS (every call follows them)
 *
 * Status. Every call that can fail returns a TpiStatus: TPI_STATUS_OK (0) or an error code.
 * The numbers never change and are never reused. A failed call changes nothing: no handle is
 * created, no output buffer is written (except `*needed`, see below), no object is edited.
 *
 * Last error. After a failed call, tpi_last_error_message() gives a message saying what was
 * wrong, naming the argument, index or field (e.g. "knots_u has 5 knots; with count 4 and
 * degree 3 expected 6 (Rhino convention) or 8 (textbook convention)"). The message is kept
 * per thread: read it on the thread that made the failing call, before the next call (every
 * call except tpi_last_error_message and the *_free calls replaces it; success leaves "").
 *
 * Ownership. Opaque handles (TpiSurface, TpiPattern, TpiDiscretisation, TpiDiscreteSurface,
 * TpiFabrication, TpiMeshChanges) are created by tpi_*_new* calls (and tpi_discretise,
 * tpi_discrete_surface_mesh, tpi_discrete_surface_changes, tpi_fabricate), which
 * store the new handle through their last argument `out`; the caller owns it and frees it
 * with the matching tpi_*_free call exactly once. On failure `*out` is set to NULL, so a
 * handle from a failed create stays NULL and a later call on it gives
 * TPI_STATUS_NULL_POINTER. The *_free calls accept NULL. Every handle carries a tag of its
 * kind: a handle of another kind (a TpiDiscretisation where a TpiDiscreteSurface is expected)
 * gives TPI_STATUS_INVALID_HANDLE, and so does a freed handle whose memory still reads as
 * freed (a *_free call overwrites the tag first); a *_free call given a handle of another
 * kind does nothing. No handle refers to another: a call that takes a handle as input
 * copies what it needs, so handles may be freed in any order.
 * Input arrays are only read during the call and never kept. Strings returned as
 * `const char *` (tpi_version, tpi_status_name) are static and never freed.
 *
 * Arrays and lengths. Every array argument comes with its length in elements of its own C
 * type (doubles for `double *`, uint32_t for `uint32_t *`, structs for a struct pointer;
 * never bytes and never points): 2 doubles per (u, v) pair, 3 per point. A pointer may be
 * NULL only when its length is 0. Misaligned pointers give TPI_STATUS_INVALID_ARGUMENT.
 *
 * Copy-out. Calls that return variable-size data take (out, capacity, needed): `*needed` is
 * set to the number of elements the data has (for text, bytes including the terminating NUL)
 * whenever `needed` is not NULL, also on TPI_STATUS_BUFFER_TOO_SMALL; if `capacity` is smaller
 * than that, nothing is written to `out` and the call returns TPI_STATUS_BUFFER_TOO_SMALL;
 * otherwise the data is copied to out[0 .. *needed). `out` may be NULL when `capacity` is 0,
 * so a call with (NULL, 0, &needed) asks for the size (it returns TPI_STATUS_BUFFER_TOO_SMALL,
 * or TPI_STATUS_OK when the data is empty).
 *
 * Parameters. Pattern points are normalised (s, t) in [0, 1]^2, mapped linearly onto the
 * surface's domain. Sampling (tpi_surface_evaluate) takes (u, v) in the surface's own domain.
 * NURBS knots follow Rhino's convention (count + degree - 1 knots, as RhinoCommon's KnotsU and
 * KnotsV give them).
 *
 * Growing structs. TpiOptions and TpiQualityReport start with `struct_size`: set it to
 * sizeof(the struct) before passing the struct in; the library reads and writes only that
 * many bytes, so a program built against an older header keeps working with a newer library.
 *
 * Panics. Every call runs behind a panic boundary: an internal error never unwinds into or
 * aborts the host; it returns TPI_STATUS_PANIC (the *_free calls then return quietly), and
 * the handles passed in stay valid and may be freed.
 *
 * THREAD SAFETY
 *
 * - All calls may be made from any thread.
 * - TpiSurface, TpiPattern, TpiDiscretisation, TpiFabrication and TpiMeshChanges are
 *   immutable after creation: one handle may be used by several threads at the same time.
 * - TpiDiscreteSurface may also be used by several threads at the same time: calls on one
 *   object are serialised by a lock inside it (a recompute blocks the other calls on that
 *   object until it is done). Meshes and changes taken from it are separate immutable
 *   handles.
 * - A *_free call must not overlap any other call on the same handle, and a handle must not
 *   be used after it was freed.
 * - The last error message is per thread (see above).
 * - Discretising uses a pool of worker threads internally (rayon's global pool).
 */


#ifndef TPI_H
#define TPI_H

/* Generated by cbindgen 0.29.4 from native/tpi-ffi (cbindgen.toml). Do not edit: run `TPI_BLESS=1 cargo test -p tpi-ffi --test header`. */

#include <stddef.h>
#include <stdint.h>

/**
 * Major version of the library this header belongs to (semantic versioning: the ABI only
 * breaks with a new major version, or before 1.0 with a new minor version).
 */
#define TPI_VERSION_MAJOR 0

/**
 * Minor version of the library this header belongs to.
 */
#define TPI_VERSION_MINOR 1

/**
 * Patch version of the library this header belongs to.
 */
#define TPI_VERSION_PATCH 0

/**
 * Per-facet flag: the facet is not convex where the envelope of tangent planes makes facets
 * convex (its seed and the seeds of the facets sharing an edge with it strictly convex, K > 0,
 * on one side, and none of their planes adjusted); on saddle-shaped regions, next to
 * parabolic lines and beside adjusted planes non-convex facets are expected and not flagged.
 */
#define TPI_FACET_NON_CONVEX 1

/**
 * Per-facet flag: the facet is not a simple polygon (self-intersecting, clockwise seen from
 * its normal, or degenerate). Invalid.
 */
#define TPI_FACET_NON_SIMPLE 2

/**
 * Per-facet flag: the facet overlaps a facet it shares a vertex with, seen along their mean
 * normal. Invalid.
 */
#define TPI_FACET_OVERLAP 4

/**
 * Per-facet flag: a diagnostic names this facet's pattern point.
 */
#define TPI_FACET_DIAGNOSTIC 8

/**
 * Per-facet flag: fewer than three distinct vertices. Invalid.
 */
#define TPI_FACET_OPEN 16

/**
 * Per-facet flag: a vertex of the facet stands farther from the surface than 3 times the
 * facet's local spacing (the mean distance from its seed to the seeds of the facets it
 * shares an edge with): exact tangent planes nearly parallel (at a parabolic line, or at
 * seeds close together) met far from it. Not invalid by itself.
 */
#define TPI_FACET_FAR_VERTEX 32

/**
 * The `point` of a diagnostic entry that concerns no single pattern point (a domain corner
 * claimed by no facet or by several).
 */
#define TPI_NO_POINT 4294967295

/**
 * Size in bytes of the first version of `TpiQualityReport`: the smallest `struct_size`
 * accepted.
 */
#define TPI_QUALITY_REPORT_SIZE_V1 200

/**
 * Size in bytes of the second version of `TpiQualityReport` (V1 plus `invalid_facets`,
 * `open_facets`, `validity_flips` and `validity_unresolved`).
 */
#define TPI_QUALITY_REPORT_SIZE_V2 232

/**
 * Size in bytes of the third version of `TpiQualityReport` (V2 plus `far_vertex_facets` and
 * `max_deviation_spacings`).
 */
#define TPI_QUALITY_REPORT_SIZE_V3 248

/**
 * Stage of a discretisation reported to a `TpiProgressCallback`: evaluation and curvature at
 * every pattern point.
 */
#define TPI_STAGE_SAMPLES 0

/**
 * Stage: the candidate triangulation (Delaunay, the hull of a closed convex surface, strips).
 */
#define TPI_STAGE_DELAUNAY 1

/**
 * Stage: the neighbour decision (flips, envelope repair, plane adjustment).
 */
#define TPI_STAGE_NEIGHBOURS 2

/**
 * Stage: facet vertices and loops.
 */
#define TPI_STAGE_FACETS 3

/**
 * Stage: mesh assembly (welding, vertex numbering).
 */
#define TPI_STAGE_MESH 4

/**
 * Stage: the quality report.
 */
#define TPI_STAGE_REPORT 5

/**
 * `side` of `tpi_fabricate`: thicken towards the centres of curvature (the concave side).
 */
#define TPI_SIDE_INSIDE 0

/**
 * `side` of `tpi_fabricate`: thicken away from the centres of curvature.
 */
#define TPI_SIDE_OUTSIDE 1

/**
 * File of `tpi_fabrication_file`: panels.json (the contract in docs/fabrication.md).
 */
#define TPI_FILE_PANELS_JSON 0

/**
 * File of `tpi_fabrication_file`: panels.obj, one closed polyhedron per panel and cleat.
 */
#define TPI_FILE_PANELS_OBJ 1

/**
 * File of `tpi_fabrication_file`: sheets.svg.
 */
#define TPI_FILE_SHEETS_SVG 2

/**
 * File of `tpi_fabrication_file`: sheets.dxf (ASCII DXF R2000, `$INSUNITS` from the surface's
 * units, `tpi_surface_with_units`; metres for a unitless surface).
 */
#define TPI_FILE_SHEETS_DXF 3

/**
 * File of `tpi_fabrication_file`: bevels.csv.
 */
#define TPI_FILE_BEVELS_CSV 4

/**
 * Size in bytes of the first version of `TpiOptions`: the smallest `struct_size` accepted.
 */
#define TPI_OPTIONS_SIZE_V1 40

/**
 * Size in bytes of the second version of `TpiOptions` (adds `plane_mode`).
 */
#define TPI_OPTIONS_SIZE_V2 48

/**
 * `plane_mode`: every facet in the exact tangent plane at its seed.
 */
#define TPI_PLANES_EXACT 0

/**
 * `plane_mode`: exact tangent planes, except where they cannot give a valid facet on a
 * surface that is not convex everywhere: there a few planes are tilted by at most 5
 * degrees (`tpi_discretisation_planes` gives each facet's plane).
 */
#define TPI_PLANES_ADJUSTED 1

/**
 * Size in bytes of the first version of `TpiFitReport`: the smallest `struct_size`
 * accepted.
 */
#define TPI_FIT_REPORT_SIZE_V1 40

/**
 * Units of `tpi_surface_with_units` and `tpi_surface_units`: unitless (the default of every
 * new surface). The values are those of Rhino's `UnitSystem` (RhinoCommon and rhino3dm), so
 * that `(int)doc.ModelUnitSystem` passes through.
 */
#define TPI_UNITS_NONE 0

/**
 * Microns (Rhino's `UnitSystem.Microns`).
 */
#define TPI_UNITS_MICRONS 1

/**
 * Millimetres (`UnitSystem.Millimeters`).
 */
#define TPI_UNITS_MILLIMETERS 2

/**
 * Centimetres (`UnitSystem.Centimeters`).
 */
#define TPI_UNITS_CENTIMETERS 3

/**
 * Metres (`UnitSystem.Meters`).
 */
#define TPI_UNITS_METERS 4

/**
 * Kilometres (`UnitSystem.Kilometers`).
 */
#define TPI_UNITS_KILOMETERS 5

/**
 * Inches (`UnitSystem.Inches`).
 */
#define TPI_UNITS_INCHES 8

/**
 * Feet (`UnitSystem.Feet`).
 */
#define TPI_UNITS_FEET 9

/**
 * Miles (`UnitSystem.Miles`).
 */
#define TPI_UNITS_MILES 10

/**
 * Yards (`UnitSystem.Yards`).
 */
#define TPI_UNITS_YARDS 19

/**
 * The result of every fallible call. The numbers are part of the ABI: they are never changed
 * and never reused, and new codes are only ever appended.
 */
typedef enum TpiStatus {
    /**
     * Success.
     */
    TPI_STATUS_OK = 0,
    /**
     * A required pointer argument was NULL (a handle, an output pointer, or an input array
     * whose length is not 0).
     */
    TPI_STATUS_NULL_POINTER = 1,
    /**
     * An argument is invalid: a length that does not fit (an odd number of doubles for
     * (u, v) pairs), a misaligned pointer, an option out of range, a surface parameter out of
     * its range, a string that is not UTF-8.
     */
    TPI_STATUS_INVALID_ARGUMENT = 2,
    /**
     * An output buffer's capacity is smaller than the data; the needed size was stored
     * through `needed` (when not NULL) and nothing was written to the buffer.
     */
    TPI_STATUS_BUFFER_TOO_SMALL = 3,
    /**
     * A pattern point index is not smaller than the number of pattern points.
     */
    TPI_STATUS_INDEX_OUT_OF_RANGE = 4,
    /**
     * A number that must be finite is NaN or infinite.
     */
    TPI_STATUS_NON_FINITE = 5,
    /**
     * The NURBS data is inconsistent: a degree, a count, a knot vector (length, order,
     * multiplicity, empty domain), the number of points or weights, or a weight <= 0.
     */
    TPI_STATUS_INVALID_NURBS = 6,
    /**
     * The pattern is invalid: a point outside [0, 1]^2, two coincident points, fewer than
     * three points, all points collinear, or a malformed generator or pattern spec.
     */
    TPI_STATUS_INVALID_PATTERN = 7,
    /**
     * The surface cannot be discretised by tangent plane intersection (flat or developable
     * at every pattern point).
     */
    TPI_STATUS_DEGENERATE = 8,
    /**
     * An internal error (a panic) was caught at the boundary. The handles passed to the call
     * are still valid and may be freed; please report the message.
     */
    TPI_STATUS_PANIC = 9,
    /**
     * A (u, v) parameter pair lies outside the surface's domain.
     */
    TPI_STATUS_OUT_OF_DOMAIN = 10,
    /**
     * The requested data was not computed (the quality report was switched off in the
     * options).
     */
    TPI_STATUS_UNAVAILABLE = 11,
    /**
     * A handle argument is not a live handle of the kind the call takes: a handle of
     * another kind (a TpiDiscretisation passed where a TpiDiscreteSurface is expected), or
     * one that was already freed and still reads as freed. Nothing was read through it.
     */
    TPI_STATUS_INVALID_HANDLE = 12,
    /**
     * The caller's progress callback asked the call to stop (`tpi_discretise_with_progress`).
     * Nothing was created.
     */
    TPI_STATUS_CANCELLED = 13,
} TpiStatus;

/**
 * What a diagnostic is about. The numbers are never changed nor reused.
 */
typedef enum TpiDiagnosticKind {
    /**
     * Three tangent planes are nearly parallel: their meeting point ran away and a stand-in
     * was used, so the facets of the three points are not exact.
     */
    TPI_DIAGNOSTIC_KIND_ILL_CONDITIONED_VERTEX = 1,
    /**
     * Two neighbouring tangent planes at the boundary are parallel.
     */
    TPI_DIAGNOSTIC_KIND_PARALLEL_PLANES = 2,
    /**
     * The common edge of two facets never reaches the surface's boundary.
     */
    TPI_DIAGNOSTIC_KIND_BOUNDARY_NOT_REACHED = 3,
    /**
     * A facet could not be closed consistently along the boundary.
     */
    TPI_DIAGNOSTIC_KIND_OPEN_FACET = 4,
    /**
     * The tangent plane of a facet holding a domain corner is parallel to the corner's normal.
     */
    TPI_DIAGNOSTIC_KIND_CORNER_UNREACHABLE = 5,
    /**
     * A domain corner was claimed by no facet or by several (point is TPI_NO_POINT).
     */
    TPI_DIAGNOSTIC_KIND_CORNER_CLAIMS = 6,
    /**
     * The point has (nearly) zero Gaussian curvature.
     */
    TPI_DIAGNOSTIC_KIND_FLAT_POINT = 7,
    /**
     * Neighbouring facets with coincident tangent planes (flat or developable) were separated
     * by the bisector of their seeds (point is TPI_NO_POINT).
     */
    TPI_DIAGNOSTIC_KIND_COINCIDENT_PLANES = 8,
    /**
     * The surface is closed in a direction but was discretised as an open patch: its seam
     * stays open (point is TPI_NO_POINT).
     */
    TPI_DIAGNOSTIC_KIND_SEAM_LEFT_OPEN = 9,
    /**
     * The mesh's Euler characteristic or boundary loops are not those expected (a gap or a
     * double cover between facets; point is TPI_NO_POINT).
     */
    TPI_DIAGNOSTIC_KIND_UNEXPECTED_TOPOLOGY = 10,
    /**
     * The surface is developable with its rulings along parameter lines (a cylinder, a cone,
     * an extrusion): its facets are strips between the lines where the tangent planes of
     * neighbouring rulings meet (point is TPI_NO_POINT).
     */
    TPI_DIAGNOSTIC_KIND_RULING_STRIPS = 11,
    /**
     * The boundary or trim cuts the point's facet into several parts: it keeps the part
     * around its seed, the others are left out as gaps beside the boundary.
     */
    TPI_DIAGNOSTIC_KIND_FACET_PARTS_LEFT_OUT = 12,
} TpiDiagnosticKind;

/**
 * A live discrete surface: a surface, its pattern points (normalised, in [0, 1]^2) and the
 * mesh of the last successful recompute.
 *
 * Created by `tpi_discrete_surface_new`, freed by `tpi_discrete_surface_free`. May be used
 * from several threads at once: calls on one discrete surface are serialised by a lock
 * inside it (a recompute blocks the other calls on the same object until it is done).
 */
typedef struct TpiDiscreteSurface TpiDiscreteSurface;

/**
 * The result of a discretisation: an indexed polygon mesh with one planar facet per pattern
 * point (facet i belongs to pattern point i), the dual triangulation, the quality report and
 * the diagnostics. Immutable.
 *
 * Created by `tpi_discretise` or `tpi_discrete_surface_mesh`, freed by
 * `tpi_discretisation_free`. May be used from several threads at once.
 */
typedef struct TpiDiscretisation TpiDiscretisation;

/**
 * Fabricated panels, cleats and sheets. Immutable.
 */
typedef struct TpiFabrication TpiFabrication;

/**
 * What changed in a discrete surface's mesh between two `tpi_discrete_surface_changes`
 * calls: an immutable snapshot, read with the `tpi_mesh_changes_*` calls and freed with
 * `tpi_mesh_changes_free`.
 *
 * Vertices are named by ids of the discrete surface's live structure, not by the vertex
 * numbers of `tpi_discrete_surface_mesh`: an id keeps its position until a later snapshot
 * lists it with a new one. When `everything` is set (the first snapshot, and after a
 * recompute that ran the whole pipeline: a batch of edits, a new surface, an edit near the
 * boundary or on a surface without live editing) the numbering started over and every
 * facet and every vertex is listed.
 */
typedef struct TpiMeshChanges TpiMeshChanges;

/**
 * A set of pattern points (s, t) in the normalised square [0, 1]^2, mapped linearly onto a
 * surface's domain: u = u_min + s (u_max - u_min), v = v_min + t (v_max - v_min). Immutable
 * once created.
 *
 * Created by the `tpi_pattern_new*` calls, freed by `tpi_pattern_free`. May be used from
 * several threads at once.
 */
typedef struct TpiPattern TpiPattern;

/**
 * A surface: a NURBS surface or an analytic one. Immutable once created.
 *
 * Created by the `tpi_surface_new_*` calls, freed by `tpi_surface_free`. May be used from
 * several threads at once.
 */
typedef struct TpiSurface TpiSurface;

/**
 * Options of a discretisation.
 *
 * Growth: fields are only ever appended. `struct_size` must hold `sizeof(TpiOptions)` as the
 * caller compiled it; the library reads (and `tpi_options_default` writes) only that many
 * bytes, and gives fields beyond them their defaults. So a program compiled against an
 * older header keeps working with a newer library. Always start from `tpi_options_default`:
 *
 * ```c
 * TpiOptions options;
 * options.struct_size = sizeof options;
 * tpi_options_default(&options);
 * options.envelope_repair = 0;
 * ```
 */
typedef struct TpiOptions {
    /**
     * sizeof(TpiOptions) as compiled by the caller; at least TPI_OPTIONS_SIZE_V1.
     */
    uint32_t struct_size;
    /**
     * 1: verify and repair the neighbours against the envelope of tangent planes where the
     * Gaussian curvature is positive; 0: the paper's method alone. Default value: 1.
     */
    uint32_t envelope_repair;
    /**
     * 1: compute the quality report and the per-facet flags; 0: skip them
     * (`tpi_discretisation_quality` then gives TPI_STATUS_UNAVAILABLE). Default value: 1.
     */
    uint32_t quality_report;
    /**
     * Always 0 (padding, kept explicit for other languages).
     */
    uint32_t reserved;
    /**
     * A facet vertex farther than this many times its dual triangle's longest side from the
     * triangle's centroid is ill-conditioned (nearly parallel planes) and replaced by a
     * stand-in, with a diagnostic. Finite, > 0. Default value: 8.
     */
    double far_vertex_factor;
    /**
     * Vertices closer than this times the bounding-box diagonal are welded. Finite, >= 0.
     * Default value: 1e-10.
     */
    double weld_tolerance;
    /**
     * A point is flat when |K| <= flat_tolerance * max(k1^2, k2^2). Finite, >= 0.
     * Default value: 1e-6.
     */
    double flat_tolerance;
    /**
     * TPI_PLANES_EXACT or TPI_PLANES_ADJUSTED (since TPI_OPTIONS_SIZE_V2). Default value:
     * TPI_PLANES_EXACT.
     */
    uint32_t plane_mode;
    /**
     * Always 0 (padding, kept explicit for other languages).
     */
    uint32_t reserved2;
} TpiOptions;

/**
 * A facet's plane: the plane through `point` with unit normal `normal`. Every vertex of the
 * facet lies in it.
 */
typedef struct TpiPlane {
    /**
     * A point of the plane (the seed's surface point, unless the adjusted plane is offset).
     */
    double point[3];
    /**
     * Unit normal (the surface normal at the seed, unless the plane is adjusted).
     */
    double normal[3];
} TpiPlane;

/**
 * A progress callback for `tpi_discretise_with_progress`: `stage` is a TPI_STAGE_* number,
 * `done` the work items of that stage done so far, `total` its number of items (0 when the
 * stage cannot know it beforehand: then `done` stays 0). Returns 0 to go on, anything else to
 * cancel the call.
 *
 * It is called when a stage starts (`done` 0), as its items get done where the calling
 * thread does them (at most about once per percent of `total`; the items the library's
 * worker threads do are only seen in the next call), and when it ends (`done` == `total`).
 * Calls come only from the thread that called `tpi_discretise_with_progress` (a runtime
 * such as Mono waits at exit for every foreign thread that ever called into it); the
 * callback must return quickly, must not unwind (no C++ exception, no .NET exception
 * crossing it), and must not call the library.
 */
typedef int32_t (*TpiProgressCallback)(void *user_data, uint32_t stage, uint64_t done, uint64_t total);

/**
 * The pattern point behind a facet: its parameters in the surface's own domain, surface
 * point, unit normal (Su x Sv) and principal curvatures k1 <= k2.
 */
typedef struct TpiSeed {
    /**
     * (u, v) in the surface's domain.
     */
    double uv[2];
    /**
     * Surface point.
     */
    double point[3];
    /**
     * Unit normal.
     */
    double normal[3];
    /**
     * Principal curvatures k1 <= k2 (signed relative to the normal).
     */
    double curvatures[2];
} TpiSeed;

/**
 * The quality report as numbers; `tpi_discretisation_quality_json` has the same and the
 * histogram of facet sizes.
 *
 * Growth: fields are only ever appended; set `struct_size` to sizeof(TpiQualityReport)
 * before the call, and the library writes only that many bytes (and stores in
 * `struct_size` how many it filled in).
 */
typedef struct TpiQualityReport {
    /**
     * sizeof(TpiQualityReport) as compiled by the caller; at least
     * TPI_QUALITY_REPORT_SIZE_V1.
     */
    uint32_t struct_size;
    /**
     * 1 if every vertex coordinate is finite.
     */
    uint32_t all_finite;
    /**
     * Number of facets (= pattern points).
     */
    uint64_t facet_count;
    /**
     * Number of mesh vertices.
     */
    uint64_t vertex_count;
    /**
     * Number of mesh edges.
     */
    uint64_t edge_count;
    /**
     * Vertices not on the boundary.
     */
    uint64_t interior_vertex_count;
    /**
     * Fraction of interior vertices where exactly three facets meet.
     */
    double trivalent_fraction;
    /**
     * Largest distance of a facet vertex from its facet's tangent plane, relative to the
     * bounding-box diagonal (0 up to rounding).
     */
    double max_planarity_error;
    /**
     * Largest distance of a mesh vertex from the surface (model units).
     */
    double max_deviation;
    /**
     * Mean distance of mesh vertices from the surface (model units).
     */
    double mean_deviation;
    /**
     * Facets that are not convex.
     */
    uint64_t non_convex_facets;
    /**
     * Facets that are not simple polygons.
     */
    uint64_t non_simple_facets;
    /**
     * Pairs of neighbouring facets that overlap.
     */
    uint64_t overlapping_pairs;
    /**
     * Facets with any flag.
     */
    uint64_t flagged_facets;
    /**
     * V - E + F (1 for a disc).
     */
    int64_t euler_characteristic;
    /**
     * Number of boundary loops (1 for a disc).
     */
    uint64_t boundary_loops;
    /**
     * Edges shared by more than two facets.
     */
    uint64_t non_manifold_edges;
    /**
     * Smallest facet area.
     */
    double min_facet_area;
    /**
     * Largest facet area.
     */
    double max_facet_area;
    /**
     * Shortest mesh edge.
     */
    double min_edge_length;
    /**
     * Longest mesh edge.
     */
    double max_edge_length;
    /**
     * Bounding-box diagonal used for relative measures.
     */
    double bounding_box_diagonal;
    /**
     * Flips made by the curvature-compensated in-circle test.
     */
    uint64_t compensation_flips;
    /**
     * Flips made by the envelope repair.
     */
    uint64_t envelope_repairs;
    /**
     * Edges the envelope rejects that could not be flipped.
     */
    uint64_t envelope_unresolved;
    /**
     * Number of diagnostics.
     */
    uint64_t diagnostic_count;
    /**
     * Open, non-simple or overlapping facets (each once): 0 for a valid mesh. Since V2.
     */
    uint64_t invalid_facets;
    /**
     * Facets with fewer than three distinct vertices. Since V2.
     */
    uint64_t open_facets;
    /**
     * Flips kept by the validity repair (saddles, mixed curvature). Since V2.
     */
    uint64_t validity_flips;
    /**
     * Facets the validity repair could not make valid. Since V2.
     */
    uint64_t validity_unresolved;
    /**
     * Facets with a vertex farther from the surface than 3 local spacings
     * (`TPI_FACET_FAR_VERTEX`). Since V3.
     */
    uint64_t far_vertex_facets;
    /**
     * The largest, over the facets, of the deviation of a facet's farthest vertex over the
     * facet's local spacing: below 1 on a mesh that hugs its surface. Since V3.
     */
    double max_deviation_spacings;
} TpiQualityReport;

/**
 * One (pattern point, diagnostic) pair: a diagnostic naming three points gives three
 * entries, one naming none gives one entry with `point` = TPI_NO_POINT.
 */
typedef struct TpiDiagnosticEntry {
    /**
     * The pattern point (= facet) index, or TPI_NO_POINT.
     */
    uint32_t point;
    /**
     * A TpiDiagnosticKind value.
     */
    uint32_t kind;
    /**
     * Index of the diagnostic in the array of `tpi_discretisation_diagnostics_json`.
     */
    uint32_t diagnostic;
} TpiDiagnosticEntry;

/**
 * How a `fit:D` pattern went (`tpi_pattern_fit_report`).
 *
 * Growth: fields are only ever appended; set `struct_size` to sizeof(TpiFitReport) before
 * the call, and the library writes only that many bytes (and stores in `struct_size` how
 * many it filled in).
 */
typedef struct TpiFitReport {
    /**
     * sizeof(TpiFitReport) as compiled by the caller; at least TPI_FIT_REPORT_SIZE_V1.
     */
    uint32_t struct_size;
    /**
     * 1 if every vertex of the pattern's mesh lies within `tolerance` of the surface, else
     * 0 (the pattern is then the closest attempt).
     */
    uint32_t met;
    /**
     * The tolerance asked for, D (model units).
     */
    double tolerance;
    /**
     * The largest vertex deviation of the pattern's mesh (model units).
     */
    double max_deviation;
    /**
     * Invalid facets of the pattern's mesh.
     */
    uint64_t invalid_facets;
    /**
     * Discretisations run to find the pattern.
     */
    uint64_t discretisations;
} TpiFitReport;

/**
 * The parameter domain [u_min, u_max] x [v_min, v_max] of a surface.
 */
typedef struct TpiDomain {
    /**
     * Start of the u interval.
     */
    double u_min;
    /**
     * End of the u interval.
     */
    double u_max;
    /**
     * Start of the v interval.
     */
    double v_min;
    /**
     * End of the v interval.
     */
    double v_max;
} TpiDomain;

/**
 * Point, normal, principal curvatures and principal directions at one (u, v).
 *
 * The normal is Su x Sv normalised (as RhinoCommon's `NormalAt`). Curvatures are signed
 * relative to the normal: k > 0 where the surface bends towards it; k1 <= k2. (d1, d2,
 * normal) is a right-handed orthonormal frame. Where Su x Sv vanishes (a pole, a collapsed
 * edge) `regular` is 0, the normal is a fallback and the curvatures are 0.
 */
typedef struct TpiSample {
    /**
     * Surface point (x, y, z).
     */
    double point[3];
    /**
     * Unit normal.
     */
    double normal[3];
    /**
     * Principal curvatures k1 <= k2.
     */
    double curvatures[2];
    /**
     * Unit principal direction of k1.
     */
    double d1[3];
    /**
     * Unit principal direction of k2.
     */
    double d2[3];
    /**
     * 1 where the surface is regular at this point, 0 where Su x Sv vanishes.
     */
    uint32_t regular;
    /**
     * Always 0 (padding, kept explicit for other languages).
     */
    uint32_t reserved;
} TpiSample;

#ifdef __cplusplus
extern "C" {
#endif // __cplusplus

/**
 * The library's version, "MAJOR.MINOR.PATCH", as a static NUL-terminated string (never
 * freed). Compare it with the TPI_VERSION_* macros to detect a header/library mismatch.
 */
const char *tpi_version(void);

/**
 * The name of a status code as a static NUL-terminated string (e.g. "TPI_STATUS_OK"), or
 * "TPI_STATUS_UNKNOWN" for a number that is not a status. Never NULL, never freed.
 */
const char *tpi_status_name(uint32_t status);

/**
 * Copies the message of the last failed call on the calling thread, NUL terminated, UTF-8.
 *
 * Every call except this one and the `*_free` calls replaces the message: a call that fails
 * stores what went wrong (naming the argument, index or field), a call that succeeds stores
 * "". The message is per thread: a call on another thread never changes it. Copy-out
 * convention; `*needed` counts the NUL (1 for an empty message). This call leaves the
 * message as it is, also when it fails itself, so a too-small buffer can be retried.
 *
 * Errors: TPI_STATUS_NULL_POINTER (`buf` NULL with `capacity` > 0),
 * TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `buf` is NULL or valid for writing `capacity` chars; `needed` is NULL or valid for
 * writing a `size_t`.
 */
enum TpiStatus tpi_last_error_message(char *buf, size_t capacity, size_t *needed);

/**
 * Creates a discrete surface from copies of `surface` and `pattern` (the caller keeps its
 * handles and may free them at once) and computes its first mesh. `options` may be NULL for
 * the defaults; they hold for the object's life.
 *
 * On success `*out` is a new handle (free with `tpi_discrete_surface_free`), else NULL.
 * Errors: as `tpi_discretise`.
 *
 * # Safety
 * `surface` and `pattern` are NULL or live handles; `options` is NULL or a `TpiOptions`
 * with `struct_size` readable bytes; `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_discrete_surface_new(const struct TpiSurface *surface, const struct TpiPattern *pattern, const struct TpiOptions *options, struct TpiDiscreteSurface **out);

/**
 * Frees a discrete surface. NULL is allowed and does nothing. Meshes taken from it with
 * `tpi_discrete_surface_mesh` stay valid.
 *
 * # Safety
 * `discrete_surface` is NULL or a handle that was not freed yet, and no other call is using
 * it.
 */
void tpi_discrete_surface_free(struct TpiDiscreteSurface *discrete_surface);

/**
 * Stores the current number of pattern points in `*out` (edits included, recomputed or not).
 *
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `discrete_surface` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discrete_surface_point_count(const struct TpiDiscreteSurface *discrete_surface, size_t *out);

/**
 * Copies the current pattern points s0, t0, s1, t1, ... (edits included). Copy-out
 * convention; `*needed` = 2 * point count.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discrete_surface` is NULL or a live handle; `out` is NULL or valid for writing
 * `capacity` doubles; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discrete_surface_points(const struct TpiDiscreteSurface *discrete_surface, double *out, size_t capacity, size_t *needed);

/**
 * Moves pattern point `index` to (s, t) in [0, 1]^2. A pending edit: the mesh changes at
 * the next `tpi_discrete_surface_recompute`.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INDEX_OUT_OF_RANGE, TPI_STATUS_NON_FINITE,
 * TPI_STATUS_INVALID_PATTERN (outside the square). On an error nothing changes.
 *
 * # Safety
 * `discrete_surface` is NULL or a live handle.
 */
enum TpiStatus tpi_discrete_surface_move_point(struct TpiDiscreteSurface *discrete_surface, size_t index, double s, double t);

/**
 * Appends the pattern point (s, t) in [0, 1]^2; its index (the previous point count) is
 * stored in `*index` unless `index` is NULL. A pending edit.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_NON_FINITE, TPI_STATUS_INVALID_PATTERN. On
 * an error nothing changes.
 *
 * # Safety
 * `discrete_surface` is NULL or a live handle; `index` is NULL or valid for writing a
 * `size_t`.
 */
enum TpiStatus tpi_discrete_surface_add_point(struct TpiDiscreteSurface *discrete_surface, double s, double t, size_t *index);

/**
 * Removes pattern point `index`; the points after it move down by one index (as the facets
 * of the next mesh do). A pending edit.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INDEX_OUT_OF_RANGE. On an error nothing
 * changes.
 *
 * # Safety
 * `discrete_surface` is NULL or a live handle.
 */
enum TpiStatus tpi_discrete_surface_remove_point(struct TpiDiscreteSurface *discrete_surface, size_t index);

/**
 * Replaces the surface with a copy of `surface` (e.g. after its control points were
 * edited); the pattern points stay where they are in the normalised square. The caller
 * keeps its handle. A pending edit.
 *
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `discrete_surface` and `surface` are NULL or live handles.
 */
enum TpiStatus tpi_discrete_surface_set_surface(struct TpiDiscreteSurface *discrete_surface, const struct TpiSurface *surface);

/**
 * Stores the number of edits since the last successful recompute in `*out`; 0 means the
 * mesh is up to date.
 *
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `discrete_surface` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discrete_surface_pending_edits(const struct TpiDiscreteSurface *discrete_surface, size_t *out);

/**
 * Brings the mesh up to date with the pending edits. With no pending edits this does
 * nothing and succeeds.
 *
 * On an error the edits stay (still pending), the previous mesh stays current, and the
 * message says what is wrong with the edited input (e.g. a moved point duplicating
 * another), so the host can undo or fix an edit and recompute again.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_PATTERN, TPI_STATUS_DEGENERATE,
 * TPI_STATUS_NON_FINITE.
 *
 * # Safety
 * `discrete_surface` is NULL or a live handle.
 */
enum TpiStatus tpi_discrete_surface_recompute(struct TpiDiscreteSurface *discrete_surface);

/**
 * Stores in `*out` a new discretisation handle for the current mesh (that of the last
 * successful recompute), to be read with the `tpi_discretisation_*` calls and freed with
 * `tpi_discretisation_free`. The mesh is shared, not copied, and it is immutable: later
 * edits and recomputes make new meshes and leave this one as it is, and it outlives the
 * discrete surface.
 *
 * Errors: TPI_STATUS_NULL_POINTER. On an error `*out` is NULL.
 *
 * # Safety
 * `discrete_surface` is NULL or a live handle; `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_discrete_surface_mesh(const struct TpiDiscreteSurface *discrete_surface, struct TpiDiscretisation **out);

/**
 * Stores in `*out` a new handle holding what changed in the mesh since the last call on
 * this discrete surface (the first call: since it was created, so everything), and starts
 * the next such list empty. Only successful recomputes change the mesh; pending edits do
 * not count. After one point edit recomputed by live editing the snapshot holds the few
 * facets around the point (about 7 for a move) and costs microseconds whatever the mesh's
 * size; after a recompute that ran the whole pipeline it lists everything (`everything`
 * is 1). See `TpiMeshChanges` for the vertex numbering.
 *
 * On success `*out` is a new handle (free with `tpi_mesh_changes_free`), else NULL.
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `discrete_surface` is NULL or a live handle; `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_discrete_surface_changes(struct TpiDiscreteSurface *discrete_surface, struct TpiMeshChanges **out);

/**
 * Frees a changes snapshot. NULL is allowed and does nothing.
 *
 * # Safety
 * `changes` is NULL or a handle that was not freed yet, and no other call is using it.
 */
void tpi_mesh_changes_free(struct TpiMeshChanges *changes);

/**
 * Stores whether everything changed (1: the vertex numbering started over and every facet
 * and vertex is listed; 0: only what is listed changed) in `*everything`, the number of
 * facets of the mesh now in `*facet_count` (facets from it on are gone), and one more than
 * the largest vertex id in use in `*vertex_id_bound`. Any of the three may be NULL.
 *
 * Errors: TPI_STATUS_NULL_POINTER (`changes`).
 *
 * # Safety
 * `changes` is NULL or a live handle; `everything` is NULL or valid for writing a
 * `uint32_t`, `facet_count` and `vertex_id_bound` NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_mesh_changes_counts(const struct TpiMeshChanges *changes, uint32_t *everything, size_t *facet_count, size_t *vertex_id_bound);

/**
 * Copies the indices of the changed facets (= pattern point indices), ascending: every
 * facet whose loop or vertex positions changed, a new facet, and the facets renumbered by a
 * removed point. Copy-out convention; `*needed` = number of changed facets.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * uint32_t; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_mesh_changes_facets(const struct TpiMeshChanges *changes, uint32_t *out, size_t capacity, size_t *needed);

/**
 * Copies the vertex count of each changed facet, in the order of
 * `tpi_mesh_changes_facets`. Copy-out convention; `*needed` = number of changed facets.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * uint32_t; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_mesh_changes_facet_sizes(const struct TpiMeshChanges *changes, uint32_t *out, size_t capacity, size_t *needed);

/**
 * Copies the changed facets' loops, facet after facet in the order of
 * `tpi_mesh_changes_facets`, as vertex ids (see `TpiMeshChanges`): counter-clockwise seen
 * from the facet's normal and starting at the same vertex as the facet's loop in
 * `tpi_discrete_surface_mesh`. Copy-out convention; `*needed` = the sum of the sizes.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * uint32_t; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_mesh_changes_facet_indices(const struct TpiMeshChanges *changes, uint32_t *out, size_t capacity, size_t *needed);

/**
 * Copies the changed facets' planes in the order of `tpi_mesh_changes_facets`, as
 * `tpi_discretisation_planes` gives them. Copy-out convention; `*needed` = number of
 * changed facets.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * TpiPlane; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_mesh_changes_planes(const struct TpiMeshChanges *changes, struct TpiPlane *out, size_t capacity, size_t *needed);

/**
 * Copies the ids of the vertices whose position is new, ascending (every other vertex id
 * the listed loops hold kept its position). Copy-out convention; `*needed` = number of
 * listed vertices.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * uint32_t; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_mesh_changes_vertex_ids(const struct TpiMeshChanges *changes, uint32_t *out, size_t capacity, size_t *needed);

/**
 * Copies the new positions of the listed vertices, x0, y0, z0, x1, ... in the order of
 * `tpi_mesh_changes_vertex_ids`. Copy-out convention; `*needed` = 3 * number of listed
 * vertices.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * doubles; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_mesh_changes_vertices(const struct TpiMeshChanges *changes, double *out, size_t capacity, size_t *needed);

/**
 * Discretises `surface` with `pattern`: one planar facet per pattern point.
 *
 * `options` may be NULL for the defaults. The surface and the pattern are only read; the
 * result does not refer to them, so they may be freed afterwards.
 *
 * On success `*out` is a new handle (free with `tpi_discretisation_free`), else NULL.
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (bad options),
 * TPI_STATUS_NON_FINITE, TPI_STATUS_INVALID_PATTERN (fewer than three points, duplicates,
 * all collinear), TPI_STATUS_DEGENERATE (a flat or developable surface).
 *
 * # Safety
 * `surface` and `pattern` are NULL or live handles; `options` is NULL or a `TpiOptions`
 * with `struct_size` readable bytes; `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_discretise(const struct TpiSurface *surface, const struct TpiPattern *pattern, const struct TpiOptions *options, struct TpiDiscretisation **out);

/**
 * `tpi_discretise`, reporting progress to `callback` (see `TpiProgressCallback`), which can
 * cancel it by returning nonzero.
 *
 * `callback` may be NULL (no reports, no cancelling: the same as `tpi_discretise`);
 * `user_data` is handed to every call of `callback` and never read by the library. The
 * result is the same as `tpi_discretise`'s. Once the callback has returned nonzero, the call
 * stops where the running stage ends (the facets and the mesh assembly count as one; every
 * stage is under a second at a million points on two cores) and returns
 * TPI_STATUS_CANCELLED with `*out` NULL and nothing created; the last error message names
 * the stage it stopped in.
 *
 * Errors: those of `tpi_discretise`, and TPI_STATUS_CANCELLED.
 *
 * # Safety
 * As `tpi_discretise`; `callback` is NULL or a function that may be called with `user_data`
 * on the calling thread until this call returns.
 */
enum TpiStatus tpi_discretise_with_progress(const struct TpiSurface *surface, const struct TpiPattern *pattern, const struct TpiOptions *options, TpiProgressCallback callback, void *user_data, struct TpiDiscretisation **out);

/**
 * Frees a discretisation. NULL is allowed and does nothing.
 *
 * # Safety
 * `discretisation` is NULL or a handle that was not freed yet, and no other call is using
 * it.
 */
void tpi_discretisation_free(struct TpiDiscretisation *discretisation);

/**
 * Stores the number of facets (= pattern points) in `*out`.
 *
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_facet_count(const struct TpiDiscretisation *discretisation, size_t *out);

/**
 * Stores the number of mesh vertices in `*out`.
 *
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_vertex_count(const struct TpiDiscretisation *discretisation, size_t *out);

/**
 * Copies the vertex coordinates x0, y0, z0, x1, ... (3 doubles per vertex). Copy-out
 * convention; `*needed` = 3 * vertex count.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * doubles; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_vertices(const struct TpiDiscretisation *discretisation, double *out, size_t capacity, size_t *needed);

/**
 * Copies the number of vertices of each facet (one uint32_t per facet, in facet order).
 * Copy-out convention; `*needed` = facet count.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * uint32_t; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_facet_sizes(const struct TpiDiscretisation *discretisation, uint32_t *out, size_t capacity, size_t *needed);

/**
 * Copies the facets' vertex indices, facet after facet, each loop counter-clockwise seen
 * from the facet's normal; facet i's loop starts after the sizes of facets 0..i-1.
 * Copy-out convention; `*needed` = sum of the facet sizes.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * uint32_t; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_facet_indices(const struct TpiDiscretisation *discretisation, uint32_t *out, size_t capacity, size_t *needed);

/**
 * Copies the per-facet flags (TPI_FACET_* bits; one uint8_t per facet). Copy-out
 * convention; `*needed` = facet count, or 0 when the quality report was switched off.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * uint8_t; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_facet_flags(const struct TpiDiscretisation *discretisation, uint8_t *out, size_t capacity, size_t *needed);

/**
 * Copies the seed of each facet (one TpiSeed per facet; facet i belongs to pattern point
 * i). Copy-out convention; `*needed` = facet count.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * TpiSeed; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_seeds(const struct TpiDiscretisation *discretisation, struct TpiSeed *out, size_t capacity, size_t *needed);

/**
 * Copies the plane of each facet (one TpiPlane per facet): the tangent plane at its seed,
 * or with `plane_mode` TPI_PLANES_ADJUSTED the facet's adjusted plane (its tilt is the angle
 * between its normal and the seed's, from `tpi_discretisation_seeds`). Copy-out convention;
 * `*needed` = facet count.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * TpiPlane; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_planes(const struct TpiDiscretisation *discretisation, struct TpiPlane *out, size_t capacity, size_t *needed);

/**
 * Copies the neighbour pairs of the final dual structure: i0, j0, i1, j1, ... (2 uint32_t
 * per pair, i < j, sorted). Two facets are neighbours when they share an edge. Copy-out
 * convention; `*needed` = 2 * pair count.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * uint32_t; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_neighbour_pairs(const struct TpiDiscretisation *discretisation, uint32_t *out, size_t capacity, size_t *needed);

/**
 * Copies the triangles of the final dual structure (3 uint32_t pattern point indices per
 * triangle, counter-clockwise in parameter space); each triangle is one interior mesh
 * vertex, where its three tangent planes meet. Copy-out convention; `*needed` =
 * 3 * triangle count.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * uint32_t; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_dual_triangles(const struct TpiDiscretisation *discretisation, uint32_t *out, size_t capacity, size_t *needed);

/**
 * Fills `*out` with the quality report. Set `out->struct_size` = sizeof(TpiQualityReport)
 * first; only that many bytes are written, and on return `struct_size` holds the number of
 * bytes filled in (smaller than the caller's size when the library is older than the
 * caller's header).
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (`struct_size` below
 * TPI_QUALITY_REPORT_SIZE_V1), TPI_STATUS_UNAVAILABLE (the report was switched off).
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for reading and writing
 * `out->struct_size` bytes.
 */
enum TpiStatus tpi_discretisation_quality(const struct TpiDiscretisation *discretisation, struct TpiQualityReport *out);

/**
 * Copies the quality report as JSON text (an object with the fields of TpiQualityReport,
 * `neighbours` nested, and `side_histogram`: facet count per number of sides), NUL
 * terminated. Copy-out convention; `*needed` counts the NUL.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL, TPI_STATUS_UNAVAILABLE.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * chars; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_quality_json(const struct TpiDiscretisation *discretisation, char *out, size_t capacity, size_t *needed);

/**
 * Stores the number of diagnostics (local problems, each naming its pattern points) in
 * `*out`; the entries of `tpi_discretisation_diagnostic_entries` may be more.
 *
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_diagnostic_count(const struct TpiDiscretisation *discretisation, size_t *out);

/**
 * Copies the per-point diagnostics as (point, kind, diagnostic) entries, in diagnostic
 * order. Copy-out convention; `*needed` = number of entries.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * entries; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_diagnostic_entries(const struct TpiDiscretisation *discretisation, struct TpiDiagnosticEntry *out, size_t capacity, size_t *needed);

/**
 * Copies the diagnostics as a JSON array, NUL terminated: each element has a `kind`
 * (snake_case of the TpiDiagnosticKind name, e.g. "flat_point") and its fields (`point` or
 * `points`, and numbers such as `gaussian_curvature`). Copy-out convention; `*needed`
 * counts the NUL.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * chars; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_diagnostics_json(const struct TpiDiscretisation *discretisation, char *out, size_t capacity, size_t *needed);

/**
 * Copies the whole result as JSON text in the project's output contract (the command
 * line's output: vertices, facets with seed, uv, point, normal, vertices and flags,
 * dual_triangles, quality, diagnostics), NUL terminated. `include_timings` 1 adds
 * `timings_ms` (which differ between runs); 0 leaves it out. Copy-out convention;
 * `*needed` counts the NUL.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (`include_timings` not 0 or
 * 1), TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * chars; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_discretisation_json(const struct TpiDiscretisation *discretisation, uint32_t include_timings, char *out, size_t capacity, size_t *needed);

/**
 * Builds the panels of `discretisation`: thickness `thickness` (> 0, below the limit the
 * mesh allows), `side` TPI_SIDE_INSIDE or TPI_SIDE_OUTSIDE, `slots_per_edge` cleat slots
 * evenly along every interior edge (0 for none; default slot size 4T x 2T; slots that do
 * not fit are left out), parts nested on sheets of `sheet_width` x `sheet_height` kept `gap`
 * apart. Lengths in model units.
 *
 * On success `*out` is a new handle (free with `tpi_fabrication_free`), else NULL.
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_NON_FINITE (a NaN or infinite length),
 * TPI_STATUS_INVALID_ARGUMENT (a length <= 0, a thickness for which no panel solid exists, a part
 * larger than the sheet, `side` not 0 or 1), TPI_STATUS_DEGENERATE (a facet that cannot be
 * a panel). The message names the option, or the panel.
 *
 * # Safety
 * `discretisation` is NULL or a live handle; `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_fabricate(const struct TpiDiscretisation *discretisation, double thickness, uint32_t side, uint32_t slots_per_edge, double sheet_width, double sheet_height, double gap, struct TpiFabrication **out);

/**
 * Frees a fabrication. NULL is allowed and does nothing.
 *
 * # Safety
 * `fabrication` is NULL or a handle that was not freed yet, and no other call is using it.
 */
void tpi_fabrication_free(struct TpiFabrication *fabrication);

/**
 * Stores the number of panels (one per facet) in `*panels` and of sheets in `*sheets`.
 *
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `fabrication` is NULL or a live handle; `panels` and `sheets` are NULL or valid for
 * writing a `size_t`.
 */
enum TpiStatus tpi_fabrication_counts(const struct TpiFabrication *fabrication, size_t *panels, size_t *sheets);

/**
 * Copies one of the files (`file`: a TPI_FILE_* number) as text, NUL terminated.
 * Copy-out convention; `*needed` counts the NUL.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (an unknown `file`),
 * TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `fabrication` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * chars; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_fabrication_file(const struct TpiFabrication *fabrication, uint32_t file, char *out, size_t capacity, size_t *needed);

/**
 * Copies the G-code for a 3-axis router with a tool of `tool_diameter` (model units; at
 * most the gap), NUL terminated: one program per sheet (docs/fabrication.md). Copy-out
 * convention; `*needed` counts the NUL. Not cached: a call that only asks for the size
 * computes the text too.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_NON_FINITE, TPI_STATUS_INVALID_ARGUMENT (a
 * diameter <= 0 or larger than the gap), TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `fabrication` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
 * chars; `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_fabrication_gcode(const struct TpiFabrication *fabrication, double tool_diameter, char *out, size_t capacity, size_t *needed);

/**
 * Fills `*options` with the defaults (see each field). `options->struct_size` must be set
 * to sizeof(TpiOptions) first; only that many bytes are written, and `struct_size` is left
 * as it is.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (`struct_size` smaller than
 * TPI_OPTIONS_SIZE_V1, e.g. not set).
 *
 * # Safety
 * `options` is NULL or valid for reading and writing `options->struct_size` bytes.
 */
enum TpiStatus tpi_options_default(struct TpiOptions *options);

/**
 * Creates a pattern from `uv_len / 2` points: `uv` holds s0, t0, s1, t1, ... in [0, 1].
 *
 * The points are validated: each finite and inside [0, 1]^2, no two closer than 1e-9.
 * Fewer than three points make a valid pattern, but discretising it fails.
 *
 * On success `*out` is a new handle (free with `tpi_pattern_free`), else NULL. Errors:
 * TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (odd `uv_len`),
 * TPI_STATUS_NON_FINITE, TPI_STATUS_INVALID_PATTERN (a point outside the square, a
 * duplicate; the message names the point).
 *
 * # Safety
 * `uv` is NULL or valid for reading `uv_len` doubles; `out` is NULL or valid for writing a
 * pointer.
 */
enum TpiStatus tpi_pattern_new(const double *uv, size_t uv_len, struct TpiPattern **out);

/**
 * Creates the square grid of `nu` x `nv` cell centres ((i + 1/2)/nu, (j + 1/2)/nv), point
 * (i, j) at index i * nv + j (generator `grid:NUxNV`).
 *
 * On success `*out` is a new handle, else NULL. Errors: TPI_STATUS_NULL_POINTER,
 * TPI_STATUS_INVALID_PATTERN (a count of 0, more than 10^7 points).
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_pattern_new_grid(size_t nu, size_t nv, struct TpiPattern **out);

/**
 * Creates the hexagonal grid of `nu` x `nv` points: rows at t = (j + 1/2)/nv, points at
 * s = (i + 1/4)/nu in even rows and (i + 3/4)/nu in odd rows (generator `hex:NUxNV`).
 *
 * On success `*out` is a new handle, else NULL. Errors as `tpi_pattern_new_grid`.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_pattern_new_hex(size_t nu, size_t nv, struct TpiPattern **out);

/**
 * Creates the `nu` x `nv` grid with each cell centre moved by uniform random offsets in
 * [-amount/2, amount/2) of the cell's size; `amount` in [0, 1] (generator
 * `jitter:NUxNV:amount=A:seed=S`). Deterministic for a given seed.
 *
 * On success `*out` is a new handle, else NULL. Errors: TPI_STATUS_NULL_POINTER,
 * TPI_STATUS_INVALID_PATTERN.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_pattern_new_jitter(size_t nu, size_t nv, double amount, uint64_t seed, struct TpiPattern **out);

/**
 * Creates `count` uniform random points (generator `random:N:seed=S`). Deterministic for a
 * given seed.
 *
 * On success `*out` is a new handle, else NULL. Errors: TPI_STATUS_NULL_POINTER,
 * TPI_STATUS_INVALID_PATTERN.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_pattern_new_random(size_t count, uint64_t seed, struct TpiPattern **out);

/**
 * Creates a Poisson-disk sampling with minimum distance `radius` (>= 0.001) in normalised
 * units (generator `poisson:R:seed=S`). Deterministic for a given seed; the number of points
 * depends on the radius (about 0.7 / radius^2).
 *
 * On success `*out` is a new handle, else NULL. Errors: TPI_STATUS_NULL_POINTER,
 * TPI_STATUS_INVALID_PATTERN.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_pattern_new_poisson(double radius, uint64_t seed, struct TpiPattern **out);

/**
 * Creates a pattern from a generator spec, the command line's syntax: `grid:NUxNV`,
 * `grid:spacing=D`, `hex:NUxNV`, `hex:spacing=D`, `jitter:NUxNV[:amount=A][:seed=S]`,
 * `jitter:spacing=D[...]`, `random:N[:seed=S]`, `poisson:R[:seed=S]`.
 *
 * On success `*out` is a new handle, else NULL. Errors: TPI_STATUS_NULL_POINTER,
 * TPI_STATUS_INVALID_ARGUMENT (not UTF-8), TPI_STATUS_INVALID_PATTERN (malformed spec, with
 * the accepted syntax in the message).
 *
 * # Safety
 * `spec` is NULL or a NUL-terminated string; `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_pattern_new_from_spec(const char *spec, struct TpiPattern **out);

/**
 * Creates a pattern made on `surface` from a pattern spec: a generator (as
 * `tpi_pattern_new_from_spec`) or one of the forms that look at the surface (the grammar of
 * the command line's `tpi discretise --pattern`, tpi_core::SurfacePatternSpec):
 *
 * - `fit:D[:seed=S]`: few points whose TPI mesh keeps every vertex within D model units of
 *   the surface (D > 0); `tpi_pattern_fit_report` tells whether D was met. A fit that does
 *   not meet D still creates the pattern (the closest attempt): check `met`.
 * - `relax:N:SPEC`: SPEC's points after N (0 to 1000) Lloyd iterations on the surface,
 *   areas measured on the surface; SPEC is any form but `fit:` and `relax:` (of a density,
 *   the iterations follow the density).
 * - `align:LATTICE:FIELD`: LATTICE `hex:NUxNV`, `hex:spacing=A`, `grid:NUxNV` or
 *   `grid:spacing=A` (about that many points) laid along FIELD: `principal`, `asymptotic`,
 *   `uv:ANGLE` (degrees) or a direction field as inline JSON
 *   `{"size": [NS, NT], "directions": [[ds, dt], ...]}`.
 * - `density:{JSON}`: a Poisson-disk sampling following a density field (the JSON of a
 *   density file, docs/formats.md, inline).
 *
 * The field and the density run to the end of the spec, so their JSON may hold colons. The
 * library reads no files: `@FILE` and density `image` terms (which name a file) are refused
 * with TPI_STATUS_INVALID_PATTERN; read the file and put its JSON text in the spec.
 * `options` (NULL for the defaults) are those of the discretisations the form runs (the
 * plane mode decides what a fit measures). Deterministic for a given spec, surface and
 * options. A fit or a relaxation runs many discretisations and may take seconds.
 *
 * On success `*out` is a new handle (free with `tpi_pattern_free`), else NULL. Errors:
 * TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (not UTF-8, bad options, a bad
 * number in the JSON), TPI_STATUS_INVALID_PATTERN (a malformed spec: the message quotes the
 * piece that is wrong), TPI_STATUS_NON_FINITE, TPI_STATUS_DEGENERATE (a surface the form
 * cannot work on).
 *
 * # Safety
 * `surface` is NULL or a live handle; `spec` is NULL or a NUL-terminated string; `options`
 * is NULL or a `TpiOptions` with `struct_size` readable bytes; `out` is NULL or valid for
 * writing a pointer.
 */
enum TpiStatus tpi_pattern_new_for_surface(const struct TpiSurface *surface, const char *spec, const struct TpiOptions *options, struct TpiPattern **out);

/**
 * `tpi_pattern_new_for_surface`, reporting progress to `callback` (see
 * `TpiProgressCallback`), which can cancel it by returning nonzero. A fit or a relaxation
 * runs many discretisations (a fit tens of them, seconds on a large surface): each one's
 * stages are reported as `tpi_discretise_with_progress` reports them, from TPI_STAGE_SAMPLES
 * again for the next; a form that runs none (a generator, an aligned lattice, a density
 * without relaxation) reports nothing.
 *
 * `callback` may be NULL (the same as `tpi_pattern_new_for_surface`); `user_data` is handed
 * to every call of `callback` and never read by the library. The points are the same as
 * `tpi_pattern_new_for_surface`'s. Once the callback has returned nonzero, the call stops
 * where the running stage of the running discretisation ends and returns
 * TPI_STATUS_CANCELLED with `*out` NULL and nothing created.
 *
 * Errors: those of `tpi_pattern_new_for_surface`, and TPI_STATUS_CANCELLED.
 *
 * # Safety
 * As `tpi_pattern_new_for_surface`; `callback` is NULL or a function that may be called with
 * `user_data` on the calling thread until this call returns.
 */
enum TpiStatus tpi_pattern_new_for_surface_with_progress(const struct TpiSurface *surface, const char *spec, const struct TpiOptions *options, TpiProgressCallback callback, void *user_data, struct TpiPattern **out);

/**
 * Fills `*out` with how the fit went, for a pattern made by `tpi_pattern_new_for_surface`
 * with a `fit:D` spec (the point count is `tpi_pattern_point_count`). Set
 * `out->struct_size` = sizeof(TpiFitReport) first; only that many bytes are written, and on
 * return `struct_size` holds the number of bytes filled in.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (`struct_size` below
 * TPI_FIT_REPORT_SIZE_V1), TPI_STATUS_UNAVAILABLE (the pattern was not made by a fit).
 *
 * # Safety
 * `pattern` is NULL or a live handle; `out` is NULL or valid for reading and writing
 * `out->struct_size` bytes.
 */
enum TpiStatus tpi_pattern_fit_report(const struct TpiPattern *pattern, struct TpiFitReport *out);

/**
 * The smallest uniform hexagonal pattern `hex:spacing=1/N` whose mesh on `surface` keeps
 * every vertex within `max_deviation` (model units, > 0) of the surface, found by doubling N,
 * bisection, and every N down to 0.85 of the bisection's (the deviation is not monotone in
 * N), looking at patterns of at most `max_points` points (the baseline a fitted pattern is
 * compared with). `options`: NULL for the defaults.
 *
 * On success `*count` is its number of points and `*deviation` its mesh's largest vertex
 * deviation; when no such pattern has at most `max_points` points, `*count` is 0 and
 * `*deviation` NaN. Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT
 * (`max_deviation` not > 0, bad options), TPI_STATUS_NON_FINITE, TPI_STATUS_DEGENERATE.
 *
 * # Safety
 * `surface` is NULL or a live handle; `options` is NULL or a `TpiOptions` with
 * `struct_size` readable bytes; `count` and `deviation` are NULL or valid for writing.
 */
enum TpiStatus tpi_pattern_hex_baseline(const struct TpiSurface *surface, double max_deviation, size_t max_points, const struct TpiOptions *options, size_t *count, double *deviation);

/**
 * Frees a pattern. NULL is allowed and does nothing.
 *
 * # Safety
 * `pattern` is NULL or a handle from a `tpi_pattern_new*` call that was not freed yet, and
 * no other call is using it.
 */
void tpi_pattern_free(struct TpiPattern *pattern);

/**
 * Stores the number of points in `*out`.
 *
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `pattern` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_pattern_point_count(const struct TpiPattern *pattern, size_t *out);

/**
 * Copies the points to `out` as s0, t0, s1, t1, ... (2 doubles per point); the copy-out
 * convention (see the header's introduction): `*needed` = 2 * point count.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
 *
 * # Safety
 * `pattern` is NULL or a live handle; `out` is NULL or valid for writing `capacity` doubles;
 * `needed` is NULL or valid for writing a `size_t`.
 */
enum TpiStatus tpi_pattern_points(const struct TpiPattern *pattern, double *out, size_t capacity, size_t *needed);

/**
 * Creates a NURBS surface from the arrays RhinoCommon hands over.
 *
 * - `degree_u`, `degree_v`: degrees (1 to 11, Rhino's limit).
 * - `count_u`, `count_v`: control point counts (count > degree).
 * - `knots_u` (`knots_u_len` doubles) and `knots_v`: knot vectors in **Rhino's convention**,
 *   count + degree - 1 knots each, as `NurbsSurface.KnotsU`/`KnotsV` give them; the domain is
 *   [knots[degree - 1], knots[count - 1]]. (The textbook convention with two more knots,
 *   count + degree + 1, is recognised by its length and accepted too.)
 * - `points` (`points_len` doubles): the Euclidean control points, u-major: point (i, j) is
 *   `points[3 * (i * count_v + j) + 0..3]`, i.e. `Points.GetControlPoint(i, j).Location`;
 *   `points_len` must be 3 * count_u * count_v.
 * - `weights` (`weights_len` doubles): the weights in the same order, all > 0, or NULL (with
 *   `weights_len` 0) for a non-rational surface. The points are **not** premultiplied.
 *
 * On success stores a new handle in `*out`, which the caller frees with `tpi_surface_free`;
 * on failure `*out` is NULL. Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT
 * (a length not a multiple of 3, weights_len without weights), TPI_STATUS_NON_FINITE (a NaN
 * or infinite knot, coordinate or weight), TPI_STATUS_INVALID_NURBS (everything else wrong
 * with the data, e.g. a wrong number of knots).
 *
 * # Safety
 * Each array pointer is NULL or valid for reading its length in doubles; `out` is NULL or
 * valid for writing a pointer.
 */
enum TpiStatus tpi_surface_new_nurbs(size_t degree_u, size_t degree_v, size_t count_u, size_t count_v, const double *knots_u, size_t knots_u_len, const double *knots_v, size_t knots_v_len, const double *points, size_t points_len, const double *weights, size_t weights_len, struct TpiSurface **out);

/**
 * Creates the elliptic paraboloid z = a x^2 + b y^2 over [x0, x1] x [y0, y1] (u = x,
 * v = y); a and b non-zero with the same sign.
 *
 * On success `*out` is a new handle (free with `tpi_surface_free`), else NULL. Errors:
 * TPI_STATUS_NULL_POINTER, TPI_STATUS_NON_FINITE, TPI_STATUS_INVALID_ARGUMENT.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_new_elliptic_paraboloid(double a, double b, double x0, double x1, double y0, double y1, struct TpiSurface **out);

/**
 * Creates the hyperbolic paraboloid z = a x^2 - b y^2 over [x0, x1] x [y0, y1]; a and b
 * non-zero with the same sign.
 *
 * On success `*out` is a new handle, else NULL. Errors as
 * `tpi_surface_new_elliptic_paraboloid`.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_new_hyperbolic_paraboloid(double a, double b, double x0, double x1, double y0, double y1, struct TpiSurface **out);

/**
 * Creates the sphere cap z = sqrt(r^2 - x^2 - y^2) over [x0, x1] x [y0, y1], which must lie
 * strictly inside the disc of radius r.
 *
 * On success `*out` is a new handle, else NULL. Errors as
 * `tpi_surface_new_elliptic_paraboloid`.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_new_sphere_cap(double radius, double x0, double x1, double y0, double y1, struct TpiSurface **out);

/**
 * Creates the sphere cap over the centred square [-h, h]^2 (needs h > 0 and
 * h * sqrt(2) < radius).
 *
 * On success `*out` is a new handle, else NULL. Errors as
 * `tpi_surface_new_elliptic_paraboloid`.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_new_sphere_cap_square(double radius, double half_width, struct TpiSurface **out);

/**
 * Creates the ellipsoid cap z = c sqrt(1 - x^2/a^2 - y^2/b^2) over [x0, x1] x [y0, y1],
 * strictly inside the ellipse; a, b, c > 0.
 *
 * On success `*out` is a new handle, else NULL. Errors as
 * `tpi_surface_new_elliptic_paraboloid`.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_new_ellipsoid_cap(double a, double b, double c, double x0, double x1, double y0, double y1, struct TpiSurface **out);

/**
 * Creates the egg-crate z = A sin(x) sin(y) over [x0, x1] x [y0, y1]; A non-zero.
 *
 * On success `*out` is a new handle, else NULL. Errors as
 * `tpi_surface_new_elliptic_paraboloid`.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_new_egg_crate(double amplitude, double x0, double x1, double y0, double y1, struct TpiSurface **out);

/**
 * Creates the cylinder z = sqrt(r^2 - x^2) over [x0, x1] x [y0, y1] with |x| < r. Its
 * Gaussian curvature is 0 everywhere and its rulings run along y: it is discretised as
 * strips between the lines where the tangent planes of neighbouring rulings meet
 * (TPI_DIAGNOSTIC_KIND_RULING_STRIPS).
 *
 * On success `*out` is a new handle, else NULL. Errors as
 * `tpi_surface_new_elliptic_paraboloid`.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_new_cylinder(double radius, double x0, double x1, double y0, double y1, struct TpiSurface **out);

/**
 * Creates the plane z = p x + q y + c0 over [x0, x1] x [y0, y1]. Its tangent planes all
 * coincide, so its facets are the Voronoi cells of their seeds in the plane
 * (TPI_DIAGNOSTIC_KIND_COINCIDENT_PLANES).
 *
 * On success `*out` is a new handle, else NULL. Errors as
 * `tpi_surface_new_elliptic_paraboloid`.
 *
 * # Safety
 * `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_new_plane(double p, double q, double c0, double x0, double x1, double y0, double y1, struct TpiSurface **out);

/**
 * Frees a surface. NULL is allowed and does nothing. Handles created from this surface
 * (patterns do not depend on it; discretisations and discrete surfaces hold their own copy)
 * stay valid.
 *
 * # Safety
 * `surface` is NULL or a handle from a `tpi_surface_new_*` call that was not freed yet, and
 * no other call is using it.
 */
void tpi_surface_free(struct TpiSurface *surface);

/**
 * Stores the surface's parameter domain in `*out`.
 *
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `surface` is NULL or a live handle; `out` is NULL or valid for writing a `TpiDomain`.
 */
enum TpiStatus tpi_surface_domain(const struct TpiSurface *surface, struct TpiDomain *out);

/**
 * Evaluates the surface at `uv_len / 2` parameter pairs: `uv` holds u0, v0, u1, v1, ... in
 * the surface's own domain (not normalised). Writes one `TpiSample` per pair to `out`, which
 * has room for `out_capacity` samples.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (odd `uv_len`),
 * TPI_STATUS_BUFFER_TOO_SMALL (`out_capacity < uv_len / 2`; nothing written),
 * TPI_STATUS_NON_FINITE (a NaN or infinite parameter), TPI_STATUS_OUT_OF_DOMAIN (a pair
 * outside the domain). On an error nothing is written to `out`; the message names the first
 * offending pair.
 *
 * # Safety
 * `surface` is NULL or a live handle; `uv` is NULL or valid for reading `uv_len` doubles;
 * `out` is NULL or valid for writing `out_capacity` samples.
 */
enum TpiStatus tpi_surface_evaluate(const struct TpiSurface *surface, const double *uv, size_t uv_len, struct TpiSample *out, size_t out_capacity);

/**
 * Creates a copy of `surface` with the model's length units `units` (a `TPI_UNITS_*` value,
 * Rhino's `UnitSystem` numbering; `TPI_UNITS_NONE` for unitless). Nothing is rescaled: the
 * units are carried to the outputs (the discretisation JSON's `"units"`, the fabrication's
 * panels.json and DXF `$INSUNITS`). Surfaces are immutable, hence a new handle; free both.
 *
 * Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (a value that is no
 * `TPI_UNITS_*`, the message lists them). On an error `*out` is set to NULL.
 *
 * # Safety
 * `surface` is NULL or a live handle; `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_with_units(const struct TpiSurface *surface, int32_t units, struct TpiSurface **out);

/**
 * Creates a copy of `surface` trimmed to the region bounded by closed polylines in the
 * surface's own (u, v) parameters (not normalised): the outer loop `outer_uv`
 * (`outer_len` doubles, u then v per point, counter-clockwise) and `hole_count` holes,
 * clockwise, whose points follow one another in `holes_uv` (`holes_len` doubles), hole `k`
 * having `hole_point_counts[k]` points. The closing segment of a loop is implied; a last
 * point equal to the first is accepted and ignored. A trimmed surface's trim is replaced.
 * Surfaces are immutable, hence a new handle; free both.
 *
 * Discretising a trimmed surface leaves the pattern points outside the trim out and ends
 * the facets on it (convex surfaces; elsewhere TPI_STATUS_INVALID_ARGUMENT, the trim is
 * never ignored). `tpi_discrete_surface_new` refuses a trimmed surface with
 * TPI_STATUS_INVALID_ARGUMENT. Evaluation and the domain are those of the untrimmed surface.
 *
 * Errors: TPI_STATUS_NULL_POINTER (`surface`, `out`, or an array whose length is not 0);
 * TPI_STATUS_INVALID_ARGUMENT (an odd number of doubles, hole point counts that do not add
 * up to `holes_len / 2`, and the trim's validation: a loop with fewer than 3 points, two
 * consecutive equal points, a point outside the domain, an outer loop that is not
 * counter-clockwise or a hole that is not clockwise, segments that touch or cross, a hole
 * outside the outer loop or inside another; the message names the loop and point, e.g.
 * `trim.holes[1][4]`); TPI_STATUS_NON_FINITE (a NaN or infinite coordinate). On an error
 * `*out` is set to NULL.
 *
 * # Safety
 * `surface` is NULL or a live handle; `outer_uv` and `holes_uv` are NULL or valid for
 * reading `outer_len` and `holes_len` doubles; `hole_point_counts` is NULL or valid for
 * reading `hole_count` values; `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_with_trim(const struct TpiSurface *surface, const double *outer_uv, size_t outer_len, const double *holes_uv, size_t holes_len, const size_t *hole_point_counts, size_t hole_count, struct TpiSurface **out);

/**
 * Creates a polysurface: several untrimmed four-sided faces that share whole sides, joined
 * as one surface. The faces are laid out as rows and columns of a rectangle, found from the
 * geometry (two faces share a side when their points along it agree to a small fraction of
 * the size), so they may come in any order and orientation; a ring of faces closes the
 * surface in that direction. The polysurface's domain is [0, sum of column widths] x
 * [0, sum of row heights] (widths and heights are the faces' mid-line lengths), so a pattern
 * in [0, 1]^2 spreads over the faces by length; its tangent planes are the faces' own, and
 * the facets of neighbouring faces meet along common edges.
 *
 * `faces` is an array of `count` surface handles, which are **borrowed**: the new handle
 * holds its own copy of each, so the caller still frees every face (and may do so right
 * away). The faces' units must agree; the polysurface carries them.
 *
 * Errors: TPI_STATUS_NULL_POINTER (`faces` with `count > 0`, a NULL element, named as
 * `faces[k]`, or `out`); TPI_STATUS_INVALID_HANDLE (an element that is not a live
 * surface handle); TPI_STATUS_INVALID_ARGUMENT (`count` 0 or more than 1000; a face that is
 * trimmed or itself a polysurface; faces whose units differ; a face that shares no whole side
 * with the others; faces that do not fill a rectangle of rows and columns; the message names
 * the face, e.g. `faces[1]: shares no whole side ...`, or `faces` for the layout as a whole).
 * On an error `*out` is set to NULL.
 *
 * # Safety
 * `faces` is NULL or valid for reading `count` pointers, each NULL or a surface handle from
 * this library that stays alive during the call; `out` is NULL or valid for writing a pointer.
 */
enum TpiStatus tpi_surface_new_polysurface(const struct TpiSurface *const *faces, size_t count, struct TpiSurface **out);

/**
 * Stores the surface's units in `*out`: a `TPI_UNITS_*` value, `TPI_UNITS_NONE` when unitless.
 *
 * Errors: TPI_STATUS_NULL_POINTER.
 *
 * # Safety
 * `surface` is NULL or a live handle; `out` is NULL or valid for writing an `int32_t`.
 */
enum TpiStatus tpi_surface_units(const struct TpiSurface *surface, int32_t *out);

#ifdef __cplusplus
}  // extern "C"
#endif  // __cplusplus

#endif  /* TPI_H */
