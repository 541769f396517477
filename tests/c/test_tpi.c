/*
 * The C test of the tpi C ABI: every exported function, the full happy path on a NURBS dome
 * (compared with what the Rust API gives, from the generated tpi_fixture.h, and with an
 * independent evaluation in C: de Casteljau and the paraboloid's closed-form curvatures), and
 * every error path: NULL handles and buffers, too-small capacities, NaN input, invalid NURBS,
 * indices out of range, use after a failed create.
 *
 * Built and run (also under valgrind) by tests/run_c_tests.sh.
 */
#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "tpi_fixture.h"

/* ---------------------------------------------------------------- helpers */

static TpiSurface *dome_scaled(double z_scale) {
    double points[DOME_POINTS_LEN];
    for (size_t k = 0; k < DOME_POINTS_LEN; k++) {
        points[k] = dome_points[k] * (k % 3 == 2 ? z_scale : 1.0);
    }
    TpiSurface *surface = NULL;
    CHECK_OK(tpi_surface_new_nurbs(DOME_DEGREE, DOME_DEGREE, DOME_COUNT, DOME_COUNT, dome_knots,
                                   DOME_KNOTS_LEN, dome_knots, DOME_KNOTS_LEN, points,
                                   DOME_POINTS_LEN, NULL, 0, &surface));
    CHECK(surface != NULL);
    return surface;
}

static TpiSurface *dome(void) { return dome_scaled(1.0); }

static char *discretisation_json(const TpiDiscretisation *d) {
    size_t needed = 0;
    TpiStatus status = tpi_discretisation_json(d, 0, NULL, 0, &needed);
    CHECK(status == TPI_STATUS_BUFFER_TOO_SMALL);
    char *text = malloc(needed);
    if (!text) return NULL;
    size_t again = 0;
    CHECK_OK(tpi_discretisation_json(d, 0, text, needed, &again));
    CHECK(again == needed);
    CHECK(strlen(text) + 1 == needed);
    return text;
}

static TpiOptions default_options(void) {
    TpiOptions options;
    memset(&options, 0, sizeof options);
    options.struct_size = sizeof options;
    CHECK_OK(tpi_options_default(&options));
    return options;
}

/* ---------------------------------------------- de Casteljau (independent) */

typedef struct {
    double x, y, z;
} V3;

static V3 v3_lerp(V3 a, V3 b, double t) {
    V3 r = {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t};
    return r;
}

static V3 v3_sub(V3 a, V3 b) {
    V3 r = {a.x - b.x, a.y - b.y, a.z - b.z};
    return r;
}

static V3 v3_scale(V3 a, double s) {
    V3 r = {a.x * s, a.y * s, a.z * s};
    return r;
}

static V3 v3_cross(V3 a, V3 b) {
    V3 r = {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    return r;
}

static V3 v3_unit(V3 a) {
    double l = sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return v3_scale(a, 1.0 / l);
}

/* Point and first derivative of the cubic Bezier curve b[0..3] at t. */
static void cubic(const V3 b[4], double t, V3 *point, V3 *derivative) {
    V3 b1[3], b2[2];
    for (int i = 0; i < 3; i++) b1[i] = v3_lerp(b[i], b[i + 1], t);
    for (int i = 0; i < 2; i++) b2[i] = v3_lerp(b1[i], b1[i + 1], t);
    *point = v3_lerp(b2[0], b2[1], t);
    *derivative = v3_scale(v3_sub(b2[1], b2[0]), 3.0);
}

/* Point, Su, Sv of the bicubic Bezier dome (control point (i, j) u-major) at (u, v). */
static void dome_bezier(double u, double v, V3 *point, V3 *su, V3 *sv) {
    V3 rows[4], rows_dv[4];
    for (int i = 0; i < 4; i++) {
        V3 column[4];
        for (int j = 0; j < 4; j++) {
            const double *p = &dome_points[3 * (i * 4 + j)];
            V3 c = {p[0], p[1], p[2]};
            column[j] = c;
        }
        cubic(column, v, &rows[i], &rows_dv[i]);
    }
    V3 unused;
    cubic(rows, u, point, su);
    cubic(rows_dv, u, sv, &unused);
}

/* ----------------------------------------------------------------- tests */

static void test_version_and_status_names(void) {
    char expected[64];
    snprintf(expected, sizeof expected, "%d.%d.%d", TPI_VERSION_MAJOR, TPI_VERSION_MINOR,
             TPI_VERSION_PATCH);
    CHECK(tpi_version() != NULL);
    CHECK(strcmp(tpi_version(), expected) == 0);
    CHECK(strcmp(tpi_status_name(TPI_STATUS_OK), "TPI_STATUS_OK") == 0);
    CHECK(strcmp(tpi_status_name(TPI_STATUS_NULL_POINTER), "TPI_STATUS_NULL_POINTER") == 0);
    CHECK(strcmp(tpi_status_name(TPI_STATUS_PANIC), "TPI_STATUS_PANIC") == 0);
    CHECK(strcmp(tpi_status_name(TPI_STATUS_UNAVAILABLE), "TPI_STATUS_UNAVAILABLE") == 0);
    CHECK(strcmp(tpi_status_name(12345), "TPI_STATUS_UNKNOWN") == 0);
    /* The numbers are part of the ABI. */
    CHECK(TPI_STATUS_OK == 0 && TPI_STATUS_NULL_POINTER == 1 && TPI_STATUS_INVALID_ARGUMENT == 2);
    CHECK(TPI_STATUS_BUFFER_TOO_SMALL == 3 && TPI_STATUS_INDEX_OUT_OF_RANGE == 4);
    CHECK(TPI_STATUS_NON_FINITE == 5 && TPI_STATUS_INVALID_NURBS == 6);
    CHECK(TPI_STATUS_INVALID_PATTERN == 7 && TPI_STATUS_DEGENERATE == 8 && TPI_STATUS_PANIC == 9);
    CHECK(TPI_STATUS_OUT_OF_DOMAIN == 10 && TPI_STATUS_UNAVAILABLE == 11);
    /* Struct sizes as the library sees them. */
    CHECK(sizeof(TpiOptions) == TPI_OPTIONS_SIZE_V2);
    CHECK(offsetof(TpiOptions, plane_mode) == TPI_OPTIONS_SIZE_V1);
    CHECK(TPI_PLANES_EXACT == 0 && TPI_PLANES_ADJUSTED == 1);
    CHECK(sizeof(TpiQualityReport) == TPI_QUALITY_REPORT_SIZE_V3);
    CHECK(offsetof(TpiQualityReport, invalid_facets) == TPI_QUALITY_REPORT_SIZE_V1);
    CHECK(offsetof(TpiQualityReport, far_vertex_facets) == TPI_QUALITY_REPORT_SIZE_V2);
    CHECK(TPI_FACET_OPEN == 16 && TPI_FACET_FAR_VERTEX == 32);
    CHECK(sizeof(TpiSample) == 120 && sizeof(TpiSeed) == 80 && sizeof(TpiPlane) == 48);
    CHECK(sizeof(TpiDiagnosticEntry) == 12 && sizeof(TpiDomain) == 32);
}

static void test_last_error(void) {
    TpiPattern *pattern = NULL;
    CHECK_STATUS(tpi_pattern_new_from_spec(NULL, &pattern), TPI_STATUS_NULL_POINTER);
    CHECK(pattern == NULL);
    size_t needed = 0;
    CHECK_STATUS(tpi_last_error_message(NULL, 0, &needed), TPI_STATUS_BUFFER_TOO_SMALL);
    CHECK(needed == strlen("spec is NULL") + 1);
    char small[4] = {'x', 'x', 'x', 'x'};
    CHECK_STATUS(tpi_last_error_message(small, sizeof small, &needed), TPI_STATUS_BUFFER_TOO_SMALL);
    CHECK(small[0] == 'x'); /* nothing written */
    CHECK_STATUS(tpi_last_error_message(NULL, 5, &needed), TPI_STATUS_NULL_POINTER);
    char message[64];
    CHECK_OK(tpi_last_error_message(message, sizeof message, NULL));
    CHECK(strcmp(message, "spec is NULL") == 0); /* reading it changed nothing */
    /* A success clears it. */
    CHECK_OK(tpi_pattern_new_grid(2, 2, &pattern));
    CHECK_OK(tpi_last_error_message(message, sizeof message, &needed));
    CHECK(message[0] == '\0' && needed == 1);
    tpi_pattern_free(pattern);
}

static void test_options(void) {
    TpiOptions options = default_options();
    CHECK(options.struct_size == sizeof options);
    CHECK(options.envelope_repair == 1 && options.quality_report == 1 && options.reserved == 0);
    CHECK(options.far_vertex_factor == 8.0);
    CHECK(options.weld_tolerance == 1e-10);
    CHECK(options.flat_tolerance == 1e-6);
    CHECK(options.plane_mode == TPI_PLANES_EXACT && options.reserved2 == 0);
    CHECK_STATUS(tpi_options_default(NULL), TPI_STATUS_NULL_POINTER);
    TpiOptions unset;
    memset(&unset, 0, sizeof unset);
    CHECK_STATUS(tpi_options_default(&unset), TPI_STATUS_INVALID_ARGUMENT);
    CHECK(last_error_contains("struct_size"));
    CHECK(unset.far_vertex_factor == 0.0); /* nothing written */
}

static void test_dome_sampling(void) {
    TpiSurface *surface = dome();
    TpiDomain domain;
    CHECK_OK(tpi_surface_domain(surface, &domain));
    CHECK(domain.u_min == 0.0 && domain.u_max == 1.0 && domain.v_min == 0.0 && domain.v_max == 1.0);

    enum { N = SAMPLE_UV_LEN / 2 };
    TpiSample samples[N];
    CHECK_OK(tpi_surface_evaluate(surface, sample_uv, SAMPLE_UV_LEN, samples, N));
    const double c = DOME_HEIGHT / 25.0; /* z = h - c (x^2 + y^2) */
    for (size_t k = 0; k < N; k++) {
        const double *e = &expected_samples[14 * k];
        const TpiSample *s = &samples[k];
        /* Same numbers as the Rust API. */
        for (int a = 0; a < 3; a++) {
            CHECK_CLOSE(s->point[a], e[a], 1e-14);
            CHECK_CLOSE(s->normal[a], e[3 + a], 1e-14);
            CHECK_CLOSE(s->d1[a], e[8 + a], 1e-12);
            CHECK_CLOSE(s->d2[a], e[11 + a], 1e-12);
        }
        CHECK_CLOSE(s->curvatures[0], e[6], 1e-12);
        CHECK_CLOSE(s->curvatures[1], e[7], 1e-12);
        CHECK(s->regular == 1 && s->reserved == 0);

        /* Independently: de Casteljau point and normal. */
        V3 p, su, sv;
        dome_bezier(sample_uv[2 * k], sample_uv[2 * k + 1], &p, &su, &sv);
        V3 n = v3_unit(v3_cross(su, sv));
        CHECK_CLOSE(s->point[0], p.x, 1e-12);
        CHECK_CLOSE(s->point[1], p.y, 1e-12);
        CHECK_CLOSE(s->point[2], p.z, 1e-12);
        CHECK_CLOSE(s->normal[0], n.x, 1e-12);
        CHECK_CLOSE(s->normal[1], n.y, 1e-12);
        CHECK_CLOSE(s->normal[2], n.z, 1e-12);
        /* The patch is exactly the paraboloid: z and the curvatures in closed form. */
        double r2 = p.x * p.x + p.y * p.y;
        CHECK_CLOSE(p.z, DOME_HEIGHT - c * r2, 1e-12);
        double w = 1.0 + 4.0 * c * c * r2;
        CHECK_CLOSE(s->curvatures[0], -2.0 * c / sqrt(w), 1e-9);
        CHECK_CLOSE(s->curvatures[1], -2.0 * c / (w * sqrt(w)), 1e-9);
    }
    tpi_surface_free(surface);
}

static void test_rational_dome(void) {
    /* Equal weights do not change a NURBS surface. */
    double weights[DOME_COUNT * DOME_COUNT];
    for (size_t k = 0; k < DOME_COUNT * DOME_COUNT; k++) weights[k] = 2.5;
    TpiSurface *rational = NULL;
    CHECK_OK(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, dome_knots, 6, dome_points,
                                   DOME_POINTS_LEN, weights, DOME_COUNT * DOME_COUNT, &rational));
    TpiSample samples[SAMPLE_UV_LEN / 2];
    CHECK_OK(tpi_surface_evaluate(rational, sample_uv, SAMPLE_UV_LEN, samples, SAMPLE_UV_LEN / 2));
    for (size_t k = 0; k < SAMPLE_UV_LEN / 2; k++) {
        for (int a = 0; a < 3; a++) CHECK_CLOSE(samples[k].point[a], expected_samples[14 * k + a], 1e-12);
    }
    tpi_surface_free(rational);
}

static void test_nurbs_errors(void) {
    TpiSurface *s = NULL;
    const double bad_knots[5] = {0, 0, 0, 1, 1};
    /* Wrong knot count: INVALID_NURBS, the handle stays NULL, and the message explains. */
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, bad_knots, 5, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN, NULL, 0, &s),
                 TPI_STATUS_INVALID_NURBS);
    CHECK(s == NULL);
    CHECK(last_error_contains("knots_u has 5 knots"));
    /* Use after the failed create: every call on the NULL handle says so. */
    TpiDomain domain;
    CHECK_STATUS(tpi_surface_domain(s, &domain), TPI_STATUS_NULL_POINTER);
    CHECK(last_error_contains("surface is NULL"));
    TpiSample sample;
    const double uv[2] = {0.5, 0.5};
    CHECK_STATUS(tpi_surface_evaluate(s, uv, 2, &sample, 1), TPI_STATUS_NULL_POINTER);
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_grid(4, 4, &pattern));
    TpiDiscretisation *d = NULL;
    CHECK_STATUS(tpi_discretise(s, pattern, NULL, &d), TPI_STATUS_NULL_POINTER);
    CHECK(d == NULL);
    TpiDiscreteSurface *ds = NULL;
    CHECK_STATUS(tpi_discrete_surface_new(s, pattern, NULL, &ds), TPI_STATUS_NULL_POINTER);
    CHECK(ds == NULL);
    tpi_surface_free(s); /* NULL: nothing happens */
    tpi_pattern_free(pattern);

    /* A handle that was not NULL before a failed create becomes NULL. */
    s = (TpiSurface *)&domain;
    CHECK_STATUS(tpi_surface_new_nurbs(0, 3, 4, 4, dome_knots, 6, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN, NULL, 0, &s),
                 TPI_STATUS_INVALID_NURBS);
    CHECK(s == NULL);
    CHECK(last_error_contains("degree"));

    double points[DOME_POINTS_LEN];
    memcpy(points, dome_points, sizeof points);
    points[7] = NAN;
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, dome_knots, 6, points,
                                       DOME_POINTS_LEN, NULL, 0, &s),
                 TPI_STATUS_NON_FINITE);
    CHECK(last_error_contains("points[2][1]"));
    const double nan_knots[6] = {0, 0, 0, NAN, 1, 1};
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, nan_knots, 6, dome_points,
                                       DOME_POINTS_LEN, NULL, 0, &s),
                 TPI_STATUS_NON_FINITE);
    const double decreasing[6] = {0, 0, 0.5, 0.2, 1, 1};
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, decreasing, 6, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN, NULL, 0, &s),
                 TPI_STATUS_INVALID_NURBS);
    /* Lengths. */
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN - 1, NULL, 0, &s),
                 TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN - 3, NULL, 0, &s),
                 TPI_STATUS_INVALID_NURBS);
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, dome_knots, 6, NULL,
                                       DOME_POINTS_LEN, NULL, 0, &s),
                 TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, NULL, 6, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN, NULL, 0, &s),
                 TPI_STATUS_NULL_POINTER);
    /* Weights. */
    double weights[16];
    for (int k = 0; k < 16; k++) weights[k] = 1.0;
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN, NULL, 16, &s),
                 TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN, weights, 15, &s),
                 TPI_STATUS_INVALID_NURBS);
    weights[3] = -1.0;
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN, weights, 16, &s),
                 TPI_STATUS_INVALID_NURBS);
    CHECK(last_error_contains("weights[3]"));
    weights[3] = NAN;
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN, weights, 16, &s),
                 TPI_STATUS_NON_FINITE);
    CHECK_STATUS(tpi_surface_new_nurbs(3, 3, 4, 4, dome_knots, 6, dome_knots, 6, dome_points,
                                       DOME_POINTS_LEN, NULL, 0, NULL),
                 TPI_STATUS_NULL_POINTER);
    CHECK(s == NULL);
}

static void test_evaluate_errors(void) {
    TpiSurface *surface = dome();
    TpiSample samples[2];
    memset(samples, 0xAB, sizeof samples);
    const double nan_uv[4] = {0.5, 0.5, NAN, 0.5};
    CHECK_STATUS(tpi_surface_evaluate(surface, nan_uv, 4, samples, 2), TPI_STATUS_NON_FINITE);
    CHECK(last_error_contains("uv[2]"));
    const double outside[4] = {0.5, 0.5, 0.5, 1.5};
    CHECK_STATUS(tpi_surface_evaluate(surface, outside, 4, samples, 2), TPI_STATUS_OUT_OF_DOMAIN);
    CHECK(last_error_contains("pair 1"));
    CHECK_STATUS(tpi_surface_evaluate(surface, outside, 3, samples, 2), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_evaluate(surface, nan_uv, 4, samples, 1), TPI_STATUS_BUFFER_TOO_SMALL);
    CHECK_STATUS(tpi_surface_evaluate(surface, NULL, 4, samples, 2), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_surface_evaluate(surface, nan_uv, 2, NULL, 1), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_surface_domain(surface, NULL), TPI_STATUS_NULL_POINTER);
    unsigned char untouched[sizeof samples];
    memset(untouched, 0xAB, sizeof untouched);
    CHECK(memcmp(samples, untouched, sizeof samples) == 0); /* failed calls wrote nothing */
    CHECK_OK(tpi_surface_evaluate(surface, NULL, 0, NULL, 0)); /* nothing to do */
    tpi_surface_free(surface);
}

typedef TpiStatus (*MakeSurface)(TpiSurface **out);
static TpiStatus make_elliptic(TpiSurface **o) { return tpi_surface_new_elliptic_paraboloid(0.1, 0.2, -3, 3, -2, 2, o); }
static TpiStatus make_hyperbolic(TpiSurface **o) { return tpi_surface_new_hyperbolic_paraboloid(0.1, 0.2, -3, 3, -2, 2, o); }
static TpiStatus make_sphere(TpiSurface **o) { return tpi_surface_new_sphere_cap(10, -3, 3, -3, 3, o); }
static TpiStatus make_sphere_square(TpiSurface **o) { return tpi_surface_new_sphere_cap_square(10, 4, o); }
static TpiStatus make_ellipsoid(TpiSurface **o) { return tpi_surface_new_ellipsoid_cap(10, 8, 5, -3, 3, -3, 3, o); }
static TpiStatus make_egg_crate(TpiSurface **o) { return tpi_surface_new_egg_crate(1, 0.3, 2.8, 0.3, 2.8, o); }
static TpiStatus make_cylinder(TpiSurface **o) { return tpi_surface_new_cylinder(5, -3, 3, 0, 10, o); }
static TpiStatus make_plane(TpiSurface **o) { return tpi_surface_new_plane(0.1, 0.2, 1, 0, 1, 0, 1, o); }

static double height_elliptic(double x, double y) { return 0.1 * x * x + 0.2 * y * y; }
static double height_hyperbolic(double x, double y) { return 0.1 * x * x - 0.2 * y * y; }
static double height_sphere(double x, double y) { return sqrt(100 - x * x - y * y); }
static double height_ellipsoid(double x, double y) { return 5 * sqrt(1 - x * x / 100 - y * y / 64); }
static double height_egg_crate(double x, double y) { return sin(x) * sin(y); }
static double height_cylinder(double x, double y) { (void)y; return sqrt(25 - x * x); }
static double height_plane(double x, double y) { return 0.1 * x + 0.2 * y + 1; }

static void test_analytic_surfaces(void) {
    struct {
        MakeSurface make;
        double (*height)(double, double);
        TpiStatus discretised;
    } cases[] = {
        {make_elliptic, height_elliptic, TPI_STATUS_OK},
        {make_hyperbolic, height_hyperbolic, TPI_STATUS_OK},
        {make_sphere, height_sphere, TPI_STATUS_OK},
        {make_sphere_square, height_sphere, TPI_STATUS_OK},
        {make_ellipsoid, height_ellipsoid, TPI_STATUS_OK},
        {make_egg_crate, height_egg_crate, TPI_STATUS_OK},
        /* Flat and developable: coincident planes separated by their seeds' bisectors. */
        {make_cylinder, height_cylinder, TPI_STATUS_OK},
        {make_plane, height_plane, TPI_STATUS_OK},
    };
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_hex(6, 6, &pattern));
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        TpiSurface *s = NULL;
        CHECK_OK(cases[k].make(&s));
        TpiDomain d;
        CHECK_OK(tpi_surface_domain(s, &d));
        double uv[2] = {0.3 * d.u_min + 0.7 * d.u_max, 0.6 * d.v_min + 0.4 * d.v_max};
        TpiSample sample;
        CHECK_OK(tpi_surface_evaluate(s, uv, 2, &sample, 1));
        CHECK_CLOSE(sample.point[0], uv[0], 1e-15);
        CHECK_CLOSE(sample.point[1], uv[1], 1e-15);
        CHECK_CLOSE(sample.point[2], cases[k].height(uv[0], uv[1]), 1e-13);
        TpiDiscretisation *mesh = NULL;
        CHECK_STATUS(tpi_discretise(s, pattern, NULL, &mesh), cases[k].discretised);
        CHECK((mesh != NULL) == (cases[k].discretised == TPI_STATUS_OK));
        tpi_discretisation_free(mesh);
        tpi_surface_free(s);
    }
    tpi_pattern_free(pattern);

    TpiSurface *s = NULL;
    CHECK_STATUS(tpi_surface_new_elliptic_paraboloid(1, -1, 0, 1, 0, 1, &s), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_new_hyperbolic_paraboloid(0, 1, 0, 1, 0, 1, &s), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_new_sphere_cap(1, -3, 3, -3, 3, &s), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_new_sphere_cap_square(10, -1, &s), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_new_ellipsoid_cap(-1, 1, 1, 0, 0.1, 0, 0.1, &s), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_new_egg_crate(NAN, 0, 1, 0, 1, &s), TPI_STATUS_NON_FINITE);
    CHECK_STATUS(tpi_surface_new_cylinder(1, -2, 2, 0, 1, &s), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_new_plane(0, 0, 0, 1, 0, 0, 1, &s), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_new_plane(0, 0, INFINITY, 0, 1, 0, 1, &s), TPI_STATUS_NON_FINITE);
    CHECK_STATUS(tpi_surface_new_sphere_cap(10, -3, 3, -3, 3, NULL), TPI_STATUS_NULL_POINTER);
    CHECK(s == NULL);
}

static size_t pattern_size(const TpiPattern *p) {
    size_t n = 0;
    CHECK_OK(tpi_pattern_point_count(p, &n));
    return n;
}

static void test_patterns(void) {
    TpiPattern *p = NULL;
    CHECK_OK(tpi_pattern_new_grid(4, 3, &p));
    CHECK(pattern_size(p) == 12);
    double points[24];
    size_t needed = 0;
    CHECK_OK(tpi_pattern_points(p, points, 24, &needed));
    CHECK(needed == 24);
    CHECK(points[0] == 0.125 && points[1] == 1.0 / 6.0); /* cell centres, u-major */
    CHECK(points[2] == 0.125 && points[3] == 0.5);
    CHECK_STATUS(tpi_pattern_points(p, points, 23, &needed), TPI_STATUS_BUFFER_TOO_SMALL);
    CHECK(needed == 24);
    CHECK_STATUS(tpi_pattern_points(NULL, points, 24, &needed), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_pattern_point_count(p, NULL), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_pattern_point_count(NULL, &needed), TPI_STATUS_NULL_POINTER);
    tpi_pattern_free(p);

    CHECK_OK(tpi_pattern_new_hex(DOME_HEX_N, DOME_HEX_N, &p));
    double hex[DOME_PATTERN_LEN];
    CHECK_OK(tpi_pattern_points(p, hex, DOME_PATTERN_LEN, NULL));
    CHECK(memcmp(hex, dome_pattern, sizeof hex) == 0);
    tpi_pattern_free(p);

    CHECK_OK(tpi_pattern_new_jitter(5, 5, 0.4, 7, &p));
    CHECK(pattern_size(p) == 25);
    tpi_pattern_free(p);
    CHECK_OK(tpi_pattern_new_random(30, 3, &p));
    CHECK(pattern_size(p) == 30);
    tpi_pattern_free(p);
    CHECK_OK(tpi_pattern_new_poisson(0.1, 5, &p));
    CHECK(pattern_size(p) > 20);
    tpi_pattern_free(p);
    CHECK_OK(tpi_pattern_new_from_spec("hex:spacing=0.25", &p));
    CHECK(pattern_size(p) == 4 * 5);
    tpi_pattern_free(p);
    p = NULL;

    CHECK_STATUS(tpi_pattern_new_grid(0, 4, &p), TPI_STATUS_INVALID_PATTERN);
    CHECK_STATUS(tpi_pattern_new_hex(4, 0, &p), TPI_STATUS_INVALID_PATTERN);
    CHECK_STATUS(tpi_pattern_new_jitter(4, 4, 2.0, 0, &p), TPI_STATUS_INVALID_PATTERN);
    CHECK_STATUS(tpi_pattern_new_random(0, 0, &p), TPI_STATUS_INVALID_PATTERN);
    CHECK_STATUS(tpi_pattern_new_poisson(NAN, 0, &p), TPI_STATUS_INVALID_PATTERN);
    CHECK_STATUS(tpi_pattern_new_from_spec("hexagon:4x4", &p), TPI_STATUS_INVALID_PATTERN);
    CHECK(last_error_contains("unknown generator kind"));
    CHECK_STATUS(tpi_pattern_new_grid(3, 3, NULL), TPI_STATUS_NULL_POINTER);
    CHECK(p == NULL);

    const double uv[6] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
    CHECK_OK(tpi_pattern_new(uv, 6, &p));
    CHECK(pattern_size(p) == 3);
    tpi_pattern_free(p);
    p = NULL;
    const double nan_uv[6] = {0.1, 0.2, NAN, 0.4, 0.5, 0.6};
    CHECK_STATUS(tpi_pattern_new(nan_uv, 6, &p), TPI_STATUS_NON_FINITE);
    CHECK(last_error_contains("pattern point 1"));
    const double outside[6] = {0.1, 0.2, 0.3, 1.4, 0.5, 0.6};
    CHECK_STATUS(tpi_pattern_new(outside, 6, &p), TPI_STATUS_INVALID_PATTERN);
    const double duplicate[6] = {0.1, 0.2, 0.3, 0.4, 0.1, 0.2};
    CHECK_STATUS(tpi_pattern_new(duplicate, 6, &p), TPI_STATUS_INVALID_PATTERN);
    CHECK(last_error_contains("duplicates"));
    CHECK_STATUS(tpi_pattern_new(uv, 5, &p), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_pattern_new(NULL, 6, &p), TPI_STATUS_NULL_POINTER);
    CHECK(p == NULL);
    /* A pattern too small to discretise is still a pattern. */
    CHECK_OK(tpi_pattern_new(uv, 4, &p));
    TpiSurface *s = dome();
    TpiDiscretisation *d = NULL;
    CHECK_STATUS(tpi_discretise(s, p, NULL, &d), TPI_STATUS_INVALID_PATTERN);
    CHECK(last_error_contains("at least 3"));
    CHECK(d == NULL);
    tpi_surface_free(s);
    tpi_pattern_free(p);
}

/* Checks the copy-out error paths of a discretisation getter of element type T. */
#define CHECK_COPY_OUT(getter, d, T, expected_len)                                                 \
    do {                                                                                           \
        size_t needed_ = 777;                                                                      \
        CHECK_STATUS(getter(NULL, NULL, 0, &needed_), TPI_STATUS_NULL_POINTER);                    \
        CHECK_STATUS(getter((d), NULL, 1, &needed_), TPI_STATUS_NULL_POINTER);                     \
        needed_ = 777;                                                                             \
        CHECK_STATUS(getter((d), NULL, 0, &needed_),                                               \
                     (expected_len) > 0 ? TPI_STATUS_BUFFER_TOO_SMALL : TPI_STATUS_OK);            \
        CHECK(needed_ == (size_t)(expected_len));                                                  \
        if ((expected_len) > 0) {                                                                  \
            size_t bytes_ = (expected_len) * sizeof(T);                                            \
            T *buf_ = malloc(bytes_);                                                              \
            unsigned char *ref_ = malloc(bytes_);                                                  \
            if (buf_ && ref_) {                                                                    \
                memset(buf_, 0xAB, bytes_);                                                        \
                memset(ref_, 0xAB, bytes_);                                                        \
                needed_ = 0;                                                                       \
                CHECK_STATUS(getter((d), buf_, (expected_len) - 1, &needed_),                      \
                             TPI_STATUS_BUFFER_TOO_SMALL);                                         \
                CHECK(needed_ == (size_t)(expected_len));                                          \
                CHECK(memcmp(buf_, ref_, bytes_) == 0);                                            \
                CHECK_OK(getter((d), buf_, (expected_len), NULL));                                 \
            }                                                                                      \
            free(buf_);                                                                            \
            free(ref_);                                                                            \
        }                                                                                          \
    } while (0)

static void test_dome_discretisation(void) {
    TpiSurface *surface = dome();
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_from_spec(DOME_PATTERN_SPEC, &pattern));
    TpiOptions options = default_options();
    TpiDiscretisation *d = NULL;
    CHECK_OK(tpi_discretise(surface, pattern, &options, &d));
    CHECK(d != NULL);
    /* The result does not refer to its inputs. */
    tpi_surface_free(surface);
    tpi_pattern_free(pattern);

    size_t facets = 0, vertex_count = 0;
    CHECK_OK(tpi_discretisation_facet_count(d, &facets));
    CHECK_OK(tpi_discretisation_vertex_count(d, &vertex_count));
    CHECK(facets == EXPECTED_FACET_COUNT);
    CHECK(vertex_count == EXPECTED_VERTEX_COUNT);

    /* Every array equals what the Rust API gives. */
    double vertices[EXPECTED_VERTICES_LEN];
    size_t needed = 0;
    CHECK_OK(tpi_discretisation_vertices(d, vertices, EXPECTED_VERTICES_LEN, &needed));
    CHECK(needed == EXPECTED_VERTICES_LEN);
    CHECK(memcmp(vertices, expected_vertices, sizeof vertices) == 0);
    uint32_t sizes[EXPECTED_FACET_SIZES_LEN];
    CHECK_OK(tpi_discretisation_facet_sizes(d, sizes, EXPECTED_FACET_SIZES_LEN, &needed));
    CHECK(memcmp(sizes, expected_facet_sizes, sizeof sizes) == 0);
    uint32_t indices[EXPECTED_FACET_INDICES_LEN];
    CHECK_OK(tpi_discretisation_facet_indices(d, indices, EXPECTED_FACET_INDICES_LEN, &needed));
    CHECK(needed == EXPECTED_FACET_INDICES_LEN);
    CHECK(memcmp(indices, expected_facet_indices, sizeof indices) == 0);
    uint8_t flags[EXPECTED_FACET_FLAGS_LEN];
    CHECK_OK(tpi_discretisation_facet_flags(d, flags, EXPECTED_FACET_FLAGS_LEN, &needed));
    CHECK(memcmp(flags, expected_facet_flags, sizeof flags) == 0);
    TpiSeed seeds[EXPECTED_FACET_COUNT];
    CHECK_OK(tpi_discretisation_seeds(d, seeds, EXPECTED_FACET_COUNT, &needed));
    CHECK(needed == EXPECTED_FACET_COUNT);
    for (size_t i = 0; i < EXPECTED_FACET_COUNT; i++) {
        CHECK(memcmp(&seeds[i], &expected_seeds[10 * i], sizeof(TpiSeed)) == 0);
        CHECK(seeds[i].uv[0] == dome_pattern[2 * i] && seeds[i].uv[1] == dome_pattern[2 * i + 1]);
    }
    TpiPlane planes[EXPECTED_FACET_COUNT];
    CHECK_OK(tpi_discretisation_planes(d, planes, EXPECTED_FACET_COUNT, &needed));
    uint32_t pairs[EXPECTED_NEIGHBOUR_PAIRS_LEN];
    CHECK_OK(tpi_discretisation_neighbour_pairs(d, pairs, EXPECTED_NEIGHBOUR_PAIRS_LEN, &needed));
    CHECK(needed == EXPECTED_NEIGHBOUR_PAIRS_LEN);
    CHECK(memcmp(pairs, expected_neighbour_pairs, sizeof pairs) == 0);
    uint32_t triangles[EXPECTED_DUAL_TRIANGLES_LEN];
    CHECK_OK(tpi_discretisation_dual_triangles(d, triangles, EXPECTED_DUAL_TRIANGLES_LEN, &needed));
    CHECK(needed == EXPECTED_DUAL_TRIANGLES_LEN);
    CHECK(memcmp(triangles, expected_dual_triangles, sizeof triangles) == 0);

    /* Independently: every facet is planar (its vertices lie in its tangent plane), its plane is
     * its seed's, and every neighbour pair is an edge of a dual triangle. */
    size_t offset = 0;
    double worst = 0.0;
    for (size_t i = 0; i < EXPECTED_FACET_COUNT; i++) {
        CHECK(memcmp(planes[i].point, seeds[i].point, sizeof planes[i].point) == 0);
        CHECK(memcmp(planes[i].normal, seeds[i].normal, sizeof planes[i].normal) == 0);
        CHECK(sizes[i] >= 3);
        for (uint32_t k = 0; k < sizes[i]; k++) {
            const double *x = &vertices[3 * indices[offset + k]];
            double distance = 0.0;
            for (int a = 0; a < 3; a++) distance += planes[i].normal[a] * (x[a] - planes[i].point[a]);
            worst = fmax(worst, fabs(distance));
        }
        offset += sizes[i];
    }
    CHECK(offset == EXPECTED_FACET_INDICES_LEN);
    CHECK(worst <= 1e-9 * EXPECTED_BOUNDING_BOX_DIAGONAL);
    for (size_t k = 0; k < EXPECTED_NEIGHBOUR_PAIRS_LEN; k += 2) {
        CHECK(pairs[k] < pairs[k + 1] && pairs[k + 1] < EXPECTED_FACET_COUNT);
    }

    /* The quality report as a struct and as JSON. */
    TpiQualityReport quality;
    memset(&quality, 0, sizeof quality);
    quality.struct_size = sizeof quality;
    CHECK_OK(tpi_discretisation_quality(d, &quality));
    CHECK(quality.struct_size == sizeof quality);
    CHECK(quality.facet_count == EXPECTED_FACET_COUNT);
    CHECK(quality.vertex_count == EXPECTED_VERTEX_COUNT);
    CHECK(quality.edge_count == EXPECTED_EDGE_COUNT);
    CHECK(quality.euler_characteristic == EXPECTED_EULER_CHARACTERISTIC);
    CHECK(quality.diagnostic_count == EXPECTED_DIAGNOSTIC_COUNT);
    CHECK(quality.max_deviation == EXPECTED_MAX_DEVIATION);
    CHECK(quality.max_planarity_error == EXPECTED_MAX_PLANARITY_ERROR);
    CHECK(quality.bounding_box_diagonal == EXPECTED_BOUNDING_BOX_DIAGONAL);
    CHECK(quality.all_finite == 1);
    /* The far-vertex count is the number of facets flagged so (V3). */
    size_t far = 0;
    for (size_t k = 0; k < EXPECTED_FACET_FLAGS_LEN; k++) {
        far += (expected_facet_flags[k] & TPI_FACET_FAR_VERTEX) != 0;
    }
    CHECK(quality.far_vertex_facets == far);
    CHECK(quality.max_deviation_spacings > 0.0);
    CHECK((quality.max_deviation_spacings > 3.0) == (far > 0));
    TpiQualityReport too_small;
    memset(&too_small, 0, sizeof too_small);
    too_small.struct_size = 8;
    CHECK_STATUS(tpi_discretisation_quality(d, &too_small), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_discretisation_quality(d, NULL), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discretisation_quality(NULL, &quality), TPI_STATUS_NULL_POINTER);

    char quality_json[sizeof expected_quality_json];
    CHECK_OK(tpi_discretisation_quality_json(d, quality_json, sizeof quality_json, &needed));
    CHECK(needed == sizeof expected_quality_json);
    CHECK(strcmp(quality_json, expected_quality_json) == 0);

    size_t diagnostics = 99;
    CHECK_OK(tpi_discretisation_diagnostic_count(d, &diagnostics));
    CHECK(diagnostics == EXPECTED_DIAGNOSTIC_COUNT);
    char diagnostics_json[sizeof expected_diagnostics_json];
    CHECK_OK(tpi_discretisation_diagnostics_json(d, diagnostics_json, sizeof diagnostics_json, NULL));
    CHECK(strcmp(diagnostics_json, expected_diagnostics_json) == 0);

    char *json = discretisation_json(d);
    CHECK(json && strcmp(json, expected_json) == 0);
    free(json);
    size_t with_timings = 0;
    CHECK_STATUS(tpi_discretisation_json(d, 1, NULL, 0, &with_timings), TPI_STATUS_BUFFER_TOO_SMALL);
    char *timed = malloc(with_timings);
    if (timed) {
        CHECK_OK(tpi_discretisation_json(d, 1, timed, with_timings, NULL));
        CHECK(strstr(timed, "\"timings_ms\"") != NULL);
        free(timed);
    }
    CHECK_STATUS(tpi_discretisation_json(d, 2, NULL, 0, &needed), TPI_STATUS_INVALID_ARGUMENT);

    /* Copy-out error paths of every getter. */
    CHECK_COPY_OUT(tpi_discretisation_vertices, d, double, EXPECTED_VERTICES_LEN);
    CHECK_COPY_OUT(tpi_discretisation_facet_sizes, d, uint32_t, EXPECTED_FACET_SIZES_LEN);
    CHECK_COPY_OUT(tpi_discretisation_facet_indices, d, uint32_t, EXPECTED_FACET_INDICES_LEN);
    CHECK_COPY_OUT(tpi_discretisation_facet_flags, d, uint8_t, EXPECTED_FACET_FLAGS_LEN);
    CHECK_COPY_OUT(tpi_discretisation_seeds, d, TpiSeed, EXPECTED_FACET_COUNT);
    CHECK_COPY_OUT(tpi_discretisation_planes, d, TpiPlane, EXPECTED_FACET_COUNT);
    CHECK_COPY_OUT(tpi_discretisation_neighbour_pairs, d, uint32_t, EXPECTED_NEIGHBOUR_PAIRS_LEN);
    CHECK_COPY_OUT(tpi_discretisation_dual_triangles, d, uint32_t, EXPECTED_DUAL_TRIANGLES_LEN);
    CHECK_COPY_OUT(tpi_discretisation_diagnostic_entries, d, TpiDiagnosticEntry, 0);
    CHECK_COPY_OUT(tpi_discretisation_quality_json, d, char, sizeof expected_quality_json);
    CHECK_COPY_OUT(tpi_discretisation_diagnostics_json, d, char, sizeof expected_diagnostics_json);
    CHECK_STATUS(tpi_discretisation_facet_count(NULL, &needed), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discretisation_facet_count(d, NULL), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discretisation_vertex_count(NULL, &needed), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discretisation_diagnostic_count(NULL, &needed), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discretisation_json(NULL, 0, NULL, 0, &needed), TPI_STATUS_NULL_POINTER);
    tpi_discretisation_free(d);
}

static void test_options_in_use(void) {
    TpiSurface *surface = dome();
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_hex(6, 6, &pattern));
    TpiOptions options = default_options();
    options.quality_report = 0;
    TpiDiscretisation *d = NULL;
    CHECK_OK(tpi_discretise(surface, pattern, &options, &d));
    TpiQualityReport quality;
    memset(&quality, 0, sizeof quality);
    quality.struct_size = sizeof quality;
    CHECK_STATUS(tpi_discretisation_quality(d, &quality), TPI_STATUS_UNAVAILABLE);
    size_t needed = 5;
    CHECK_STATUS(tpi_discretisation_quality_json(d, NULL, 0, &needed), TPI_STATUS_UNAVAILABLE);
    CHECK_OK(tpi_discretisation_facet_flags(d, NULL, 0, &needed));
    CHECK(needed == 0);
    tpi_discretisation_free(d);
    d = NULL;

    options = default_options();
    options.far_vertex_factor = NAN;
    CHECK_STATUS(tpi_discretise(surface, pattern, &options, &d), TPI_STATUS_NON_FINITE);
    CHECK(last_error_contains("far_vertex_factor"));
    options = default_options();
    options.envelope_repair = 7;
    CHECK_STATUS(tpi_discretise(surface, pattern, &options, &d), TPI_STATUS_INVALID_ARGUMENT);
    options = default_options();
    options.struct_size = 0;
    CHECK_STATUS(tpi_discretise(surface, pattern, &options, &d), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_discretise(surface, NULL, NULL, &d), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discretise(surface, pattern, NULL, NULL), TPI_STATUS_NULL_POINTER);
    CHECK(d == NULL);
    tpi_pattern_free(pattern);
    tpi_surface_free(surface);
}

static void test_diagnostics(void) {
    /* The egg-crate z = sin x sin y has K = -cos(x + y) cos(x - y): over [-pi/2, pi/2]^2 the
     * 8 x 8 grid points with i + j = 3 or 11 lie on x + y = -pi/2 or pi/2, and those with
     * i - j = 4 or -4 on x - y = pi/2 or -pi/2, where it is flat: 16 flat points. */
    const double half_pi = 1.5707963267948966;
    TpiSurface *surface = NULL;
    CHECK_OK(tpi_surface_new_egg_crate(1.0, -half_pi, half_pi, -half_pi, half_pi, &surface));
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_grid(8, 8, &pattern));
    TpiDiscretisation *d = NULL;
    CHECK_OK(tpi_discretise(surface, pattern, NULL, &d));
    size_t count = 0, entries_len = 0, facets = 0;
    CHECK_OK(tpi_discretisation_diagnostic_count(d, &count));
    CHECK_OK(tpi_discretisation_facet_count(d, &facets));
    CHECK(count > 0);
    TpiStatus status = tpi_discretisation_diagnostic_entries(d, NULL, 0, &entries_len);
    CHECK(status == TPI_STATUS_BUFFER_TOO_SMALL);
    CHECK(entries_len >= count);
    TpiDiagnosticEntry *entries = malloc(entries_len * sizeof *entries);
    uint8_t *flags = malloc(facets);
    size_t json_len = 0;
    CHECK_STATUS(tpi_discretisation_diagnostics_json(d, NULL, 0, &json_len), TPI_STATUS_BUFFER_TOO_SMALL);
    char *json = malloc(json_len);
    if (entries && flags && json) {
        CHECK_OK(tpi_discretisation_diagnostic_entries(d, entries, entries_len, NULL));
        CHECK_OK(tpi_discretisation_facet_flags(d, flags, facets, NULL));
        CHECK_OK(tpi_discretisation_diagnostics_json(d, json, json_len, NULL));
        size_t kinds = 0;
        for (const char *at = json; (at = strstr(at, "\"kind\"")) != NULL; at++) kinds++;
        CHECK(kinds == count);
        uint32_t previous = 0;
        for (size_t k = 0; k < entries_len; k++) {
            CHECK(entries[k].kind >= TPI_DIAGNOSTIC_KIND_ILL_CONDITIONED_VERTEX);
            CHECK(entries[k].kind <= TPI_DIAGNOSTIC_KIND_FACET_PARTS_LEFT_OUT);
            CHECK(entries[k].diagnostic < count && entries[k].diagnostic >= previous);
            previous = entries[k].diagnostic;
            if (entries[k].point != TPI_NO_POINT) {
                CHECK(entries[k].point < facets);
                CHECK(entries[k].point < facets && (flags[entries[k].point] & TPI_FACET_DIAGNOSTIC));
            } else {
                /* The hole the unreachable vertices leave is named once, with no point. */
                CHECK(entries[k].kind == TPI_DIAGNOSTIC_KIND_CORNER_CLAIMS ||
                      entries[k].kind == TPI_DIAGNOSTIC_KIND_UNEXPECTED_TOPOLOGY);
            }
        }
        CHECK(strstr(json, "\"flat_point\"") != NULL);
        size_t flat = 0;
        for (size_t k = 0; k < entries_len; k++) {
            if (entries[k].kind == TPI_DIAGNOSTIC_KIND_FLAT_POINT) {
                flat++;
                uint32_t i = entries[k].point / 8, j = entries[k].point % 8;
                CHECK(i + j == 3 || i + j == 11 || i == j + 4 || j == i + 4);
            }
        }
        CHECK(flat == 16);
    }
    free(entries);
    free(flags);
    free(json);
    tpi_discretisation_free(d);
    tpi_pattern_free(pattern);
    tpi_surface_free(surface);
}

static size_t ds_points(const TpiDiscreteSurface *ds, double **points) {
    size_t needed = 0;
    tpi_discrete_surface_points(ds, NULL, 0, &needed);
    *points = malloc(needed * sizeof **points);
    if (*points) CHECK_OK(tpi_discrete_surface_points(ds, *points, needed, NULL));
    return needed;
}

/* The discrete surface's mesh equals a discretisation from scratch of its current inputs. */
static void check_against_scratch(const TpiDiscreteSurface *ds, const TpiSurface *surface) {
    double *points = NULL;
    size_t len = ds_points(ds, &points);
    size_t count = 0;
    CHECK_OK(tpi_discrete_surface_point_count(ds, &count));
    CHECK(len == 2 * count);
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new(points, len, &pattern));
    TpiDiscretisation *scratch = NULL, *mesh = NULL;
    CHECK_OK(tpi_discretise(surface, pattern, NULL, &scratch));
    CHECK_OK(tpi_discrete_surface_mesh(ds, &mesh));
    char *a = discretisation_json(mesh);
    char *b = discretisation_json(scratch);
    CHECK(a && b && strcmp(a, b) == 0);
    size_t facets = 0;
    CHECK_OK(tpi_discretisation_facet_count(mesh, &facets));
    CHECK(facets == count);
    free(a);
    free(b);
    free(points);
    tpi_discretisation_free(mesh);
    tpi_discretisation_free(scratch);
    tpi_pattern_free(pattern);
}

static size_t pending(const TpiDiscreteSurface *ds) {
    size_t n = 99;
    CHECK_OK(tpi_discrete_surface_pending_edits(ds, &n));
    return n;
}

static void test_discrete_surface(void) {
    TpiSurface *surface = dome();
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_hex(7, 7, &pattern));
    TpiDiscreteSurface *ds = NULL;
    CHECK_OK(tpi_discrete_surface_new(surface, pattern, NULL, &ds));
    tpi_pattern_free(pattern); /* the discrete surface keeps its own copy */
    CHECK(pending(ds) == 0);
    check_against_scratch(ds, surface);

    /* Move: pending until recompute. */
    TpiDiscretisation *before = NULL;
    CHECK_OK(tpi_discrete_surface_mesh(ds, &before));
    CHECK_OK(tpi_discrete_surface_move_point(ds, 10, 0.42, 0.37));
    CHECK(pending(ds) == 1);
    TpiDiscretisation *still = NULL;
    CHECK_OK(tpi_discrete_surface_mesh(ds, &still));
    char *a = discretisation_json(before);
    char *b = discretisation_json(still);
    CHECK(a && b && strcmp(a, b) == 0);
    free(a);
    free(b);
    tpi_discretisation_free(still);
    CHECK_OK(tpi_discrete_surface_recompute(ds));
    CHECK(pending(ds) == 0);
    CHECK_OK(tpi_discrete_surface_recompute(ds)); /* nothing pending: nothing to do */
    check_against_scratch(ds, surface);

    /* Add and remove. */
    size_t index = 0, count = 0;
    CHECK_OK(tpi_discrete_surface_point_count(ds, &count));
    CHECK_OK(tpi_discrete_surface_add_point(ds, 0.04, 0.96, &index));
    CHECK(index == count);
    CHECK_OK(tpi_discrete_surface_add_point(ds, 0.51, 0.49, NULL));
    CHECK_OK(tpi_discrete_surface_remove_point(ds, 3));
    CHECK(pending(ds) == 3);
    CHECK_OK(tpi_discrete_surface_recompute(ds));
    check_against_scratch(ds, surface);

    /* Replace the surface (its control points were edited). */
    TpiSurface *taller = dome_scaled(1.5);
    CHECK_OK(tpi_discrete_surface_set_surface(ds, taller));
    CHECK_OK(tpi_discrete_surface_recompute(ds));
    check_against_scratch(ds, taller);

    /* Errors change nothing. */
    CHECK_OK(tpi_discrete_surface_point_count(ds, &count));
    CHECK_STATUS(tpi_discrete_surface_move_point(ds, count, 0.5, 0.5), TPI_STATUS_INDEX_OUT_OF_RANGE);
    CHECK(last_error_contains("out of range"));
    CHECK_STATUS(tpi_discrete_surface_remove_point(ds, count), TPI_STATUS_INDEX_OUT_OF_RANGE);
    CHECK_STATUS(tpi_discrete_surface_remove_point(ds, (size_t)-1), TPI_STATUS_INDEX_OUT_OF_RANGE);
    CHECK_STATUS(tpi_discrete_surface_move_point(ds, 0, NAN, 0.5), TPI_STATUS_NON_FINITE);
    CHECK_STATUS(tpi_discrete_surface_move_point(ds, 0, 0.5, -0.5), TPI_STATUS_INVALID_PATTERN);
    CHECK_STATUS(tpi_discrete_surface_add_point(ds, INFINITY, 0.5, &index), TPI_STATUS_NON_FINITE);
    CHECK_STATUS(tpi_discrete_surface_set_surface(ds, NULL), TPI_STATUS_NULL_POINTER);
    CHECK(pending(ds) == 0);
    size_t after = 0;
    CHECK_OK(tpi_discrete_surface_point_count(ds, &after));
    CHECK(after == count);

    /* A recompute that fails keeps the edits pending and the last mesh. */
    double *points = NULL;
    ds_points(ds, &points);
    if (points) {
        CHECK_OK(tpi_discrete_surface_move_point(ds, 0, points[2], points[3])); /* onto point 1 */
        CHECK_STATUS(tpi_discrete_surface_recompute(ds), TPI_STATUS_INVALID_PATTERN);
        CHECK(last_error_contains("duplicates"));
        CHECK(pending(ds) == 1);
        CHECK_OK(tpi_discrete_surface_move_point(ds, 0, points[0], points[1])); /* undo */
        CHECK_OK(tpi_discrete_surface_recompute(ds));
        check_against_scratch(ds, taller);
        free(points);
    }

    /* NULL handles and out pointers. */
    CHECK_STATUS(tpi_discrete_surface_point_count(NULL, &count), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_point_count(ds, NULL), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_points(NULL, NULL, 0, &count), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_points(ds, NULL, 4, &count), TPI_STATUS_NULL_POINTER);
    double two[2];
    CHECK_STATUS(tpi_discrete_surface_points(ds, two, 2, &count), TPI_STATUS_BUFFER_TOO_SMALL);
    CHECK(count == 2 * after);
    CHECK_STATUS(tpi_discrete_surface_move_point(NULL, 0, 0.5, 0.5), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_add_point(NULL, 0.5, 0.5, NULL), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_remove_point(NULL, 0), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_set_surface(NULL, surface), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_pending_edits(NULL, &count), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_pending_edits(ds, NULL), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_recompute(NULL), TPI_STATUS_NULL_POINTER);
    TpiDiscretisation *none = NULL;
    CHECK_STATUS(tpi_discrete_surface_mesh(NULL, &none), TPI_STATUS_NULL_POINTER);
    CHECK(none == NULL);
    CHECK_STATUS(tpi_discrete_surface_mesh(ds, NULL), TPI_STATUS_NULL_POINTER);

    /* A mesh taken earlier outlives the discrete surface. */
    tpi_discrete_surface_free(ds);
    size_t facets = 0;
    CHECK_OK(tpi_discretisation_facet_count(before, &facets));
    CHECK(facets == 49);
    tpi_discretisation_free(before);

    /* Use after a failed create. */
    TpiPattern *two_points = NULL;
    const double uv[4] = {0.2, 0.2, 0.8, 0.8};
    CHECK_OK(tpi_pattern_new(uv, 4, &two_points));
    ds = NULL;
    CHECK_STATUS(tpi_discrete_surface_new(surface, two_points, NULL, &ds), TPI_STATUS_INVALID_PATTERN);
    CHECK(ds == NULL);
    CHECK_STATUS(tpi_discrete_surface_move_point(ds, 0, 0.5, 0.5), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_recompute(ds), TPI_STATUS_NULL_POINTER);
    CHECK(last_error_contains("discrete_surface is NULL"));
    CHECK_STATUS(tpi_discrete_surface_new(surface, two_points, NULL, NULL), TPI_STATUS_NULL_POINTER);
    tpi_discrete_surface_free(ds);
    tpi_pattern_free(two_points);
    tpi_surface_free(taller);
    tpi_surface_free(surface);
}

/* ------------------------------------------------------- mesh changes */

/* A host's copy of a discrete surface's mesh kept only from tpi_discrete_surface_changes:
 * vertex positions by id, loops and planes per facet. */
typedef struct {
    double *xyz;      /* 3 per vertex id */
    size_t bound;     /* vertex ids */
    uint32_t **loops; /* per facet */
    uint32_t *sizes;
    TpiPlane *planes;
    size_t facets;
} Replica;

static void replica_free(Replica *r) {
    for (size_t f = 0; f < r->facets; f++) free(r->loops[f]);
    free(r->loops);
    free(r->sizes);
    free(r->planes);
    free(r->xyz);
    memset(r, 0, sizeof *r);
}

static void *read_changes_array(TpiStatus (*call)(const TpiMeshChanges *, void *, size_t, size_t *),
                                const TpiMeshChanges *c, size_t element, size_t *count) {
    *count = 0;
    call(c, NULL, 0, count);
    void *data = malloc(*count ? *count * element : 1);
    if (data) CHECK_OK(call(c, data, *count, NULL));
    return data;
}

/* Typed adapters for read_changes_array. */
static TpiStatus facets_of(const TpiMeshChanges *c, void *o, size_t n, size_t *k) { return tpi_mesh_changes_facets(c, o, n, k); }
static TpiStatus sizes_of(const TpiMeshChanges *c, void *o, size_t n, size_t *k) { return tpi_mesh_changes_facet_sizes(c, o, n, k); }
static TpiStatus loops_of(const TpiMeshChanges *c, void *o, size_t n, size_t *k) { return tpi_mesh_changes_facet_indices(c, o, n, k); }
static TpiStatus planes_of(const TpiMeshChanges *c, void *o, size_t n, size_t *k) { return tpi_mesh_changes_planes(c, o, n, k); }
static TpiStatus ids_of(const TpiMeshChanges *c, void *o, size_t n, size_t *k) { return tpi_mesh_changes_vertex_ids(c, o, n, k); }
static TpiStatus xyz_of(const TpiMeshChanges *c, void *o, size_t n, size_t *k) { return tpi_mesh_changes_vertices(c, o, n, k); }

/* Takes the changes and applies them; returns the number of facets listed, *everything set. */
static size_t replica_follow(Replica *r, TpiDiscreteSurface *ds, uint32_t *everything) {
    TpiMeshChanges *c = NULL;
    CHECK_OK(tpi_discrete_surface_changes(ds, &c));
    size_t facet_count = 0, bound = 0, n = 0, n_sizes = 0, n_loops = 0, n_planes = 0, n_ids = 0, n_xyz = 0;
    CHECK_OK(tpi_mesh_changes_counts(c, everything, &facet_count, &bound));
    uint32_t *facets = read_changes_array(facets_of, c, sizeof(uint32_t), &n);
    uint32_t *sizes = read_changes_array(sizes_of, c, sizeof(uint32_t), &n_sizes);
    uint32_t *loops = read_changes_array(loops_of, c, sizeof(uint32_t), &n_loops);
    TpiPlane *planes = read_changes_array(planes_of, c, sizeof(TpiPlane), &n_planes);
    uint32_t *ids = read_changes_array(ids_of, c, sizeof(uint32_t), &n_ids);
    double *xyz = read_changes_array(xyz_of, c, sizeof(double), &n_xyz);
    tpi_mesh_changes_free(c);
    CHECK(n_sizes == n && n_planes == n && n_xyz == 3 * n_ids);
    if (*everything) {
        CHECK(n == facet_count);
        replica_free(r);
    }
    /* Resize to the facet count and the id bound. */
    for (size_t f = facet_count; f < r->facets; f++) free(r->loops[f]);
    r->loops = realloc(r->loops, (facet_count + 1) * sizeof *r->loops);
    r->sizes = realloc(r->sizes, (facet_count + 1) * sizeof *r->sizes);
    r->planes = realloc(r->planes, (facet_count + 1) * sizeof *r->planes);
    for (size_t f = r->facets; f < facet_count; f++) {
        r->loops[f] = NULL;
        r->sizes[f] = 0;
    }
    r->facets = facet_count;
    r->xyz = realloc(r->xyz, (bound + 1) * 3 * sizeof *r->xyz);
    for (size_t v = r->bound; v < bound; v++) r->xyz[3 * v] = r->xyz[3 * v + 1] = r->xyz[3 * v + 2] = NAN;
    r->bound = bound;
    size_t start = 0;
    for (size_t k = 0; k < n && facets && sizes && loops && planes; k++) {
        size_t f = facets[k];
        CHECK(f < facet_count && (k == 0 || facets[k - 1] < f));
        if (f >= facet_count || start + sizes[k] > n_loops) break;
        free(r->loops[f]);
        r->loops[f] = malloc(sizes[k] * sizeof(uint32_t));
        if (r->loops[f]) memcpy(r->loops[f], loops + start, sizes[k] * sizeof(uint32_t));
        r->sizes[f] = sizes[k];
        r->planes[f] = planes[k];
        start += sizes[k];
    }
    for (size_t k = 0; k < n_ids && ids && xyz; k++) {
        CHECK(ids[k] < bound);
        if (ids[k] < bound) memcpy(r->xyz + 3 * ids[k], xyz + 3 * k, 3 * sizeof(double));
    }
    free(facets);
    free(sizes);
    free(loops);
    free(planes);
    free(ids);
    free(xyz);
    return n;
}

/* Every facet of the copy has the vertex positions (bit for bit) and plane of the mesh. */
static void replica_check(const Replica *r, const TpiDiscreteSurface *ds) {
    TpiDiscretisation *mesh = NULL;
    CHECK_OK(tpi_discrete_surface_mesh(ds, &mesh));
    size_t facets = 0, n_vertices = 0, n_sizes = 0, n_indices = 0, n_planes = 0;
    CHECK_OK(tpi_discretisation_facet_count(mesh, &facets));
    CHECK(facets == r->facets);
    tpi_discretisation_vertices(mesh, NULL, 0, &n_vertices);
    tpi_discretisation_facet_sizes(mesh, NULL, 0, &n_sizes);
    tpi_discretisation_facet_indices(mesh, NULL, 0, &n_indices);
    tpi_discretisation_planes(mesh, NULL, 0, &n_planes);
    double *vertices = malloc(n_vertices * sizeof *vertices);
    uint32_t *sizes = malloc(n_sizes * sizeof *sizes);
    uint32_t *indices = malloc(n_indices * sizeof *indices);
    TpiPlane *planes = malloc(n_planes * sizeof *planes);
    int same = vertices && sizes && indices && planes && facets == r->facets;
    if (same) {
        CHECK_OK(tpi_discretisation_vertices(mesh, vertices, n_vertices, NULL));
        CHECK_OK(tpi_discretisation_facet_sizes(mesh, sizes, n_sizes, NULL));
        CHECK_OK(tpi_discretisation_facet_indices(mesh, indices, n_indices, NULL));
        CHECK_OK(tpi_discretisation_planes(mesh, planes, n_planes, NULL));
        size_t start = 0;
        for (size_t f = 0; f < facets && same; f++) {
            same = sizes[f] == r->sizes[f] && memcmp(&planes[f], &r->planes[f], sizeof planes[f]) == 0;
            for (uint32_t k = 0; same && k < sizes[f]; k++) {
                uint32_t id = r->loops[f][k];
                same = id < r->bound && memcmp(vertices + 3 * indices[start + k], r->xyz + 3 * id, 3 * sizeof(double)) == 0;
            }
            start += sizes[f];
        }
    }
    CHECK(same);
    free(vertices);
    free(sizes);
    free(indices);
    free(planes);
    tpi_discretisation_free(mesh);
}

static void test_mesh_changes(void) {
    TpiSurface *surface = dome();
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_hex(16, 16, &pattern));
    TpiDiscreteSurface *ds = NULL;
    CHECK_OK(tpi_discrete_surface_new(surface, pattern, NULL, &ds));
    tpi_pattern_free(pattern);
    Replica r;
    memset(&r, 0, sizeof r);
    uint32_t everything = 0;
    CHECK(replica_follow(&r, ds, &everything) == 256 && everything == 1); /* the first: all */
    replica_check(&r, ds);
    CHECK(replica_follow(&r, ds, &everything) == 0 && everything == 0); /* nothing since */

    /* Drags of interior points, an add and a remove: the copy stays the mesh. */
    double *points = NULL;
    ds_points(ds, &points);
    int small = 0;
    for (int step = 0; step < 24 && points; step++) {
        size_t i = (size_t)(40 + 7 * step) % 256;
        if (step == 20) {
            CHECK_OK(tpi_discrete_surface_add_point(ds, 0.503, 0.497, NULL));
        } else if (step == 22) {
            CHECK_OK(tpi_discrete_surface_remove_point(ds, 17));
        } else {
            double s = points[2 * i] + 0.2 / 16, t = points[2 * i + 1] + (step % 3 - 1) * 0.1 / 16;
            if (s > 0.99) s = 0.99;
            CHECK_OK(tpi_discrete_surface_move_point(ds, i, s, t));
            points[2 * i] = s;
            points[2 * i + 1] = t;
        }
        CHECK(replica_follow(&r, ds, &everything) == 0); /* pending edits change nothing */
        CHECK_OK(tpi_discrete_surface_recompute(ds));
        size_t listed = replica_follow(&r, ds, &everything);
        if (!everything && step < 20) {
            CHECK(listed > 0 && listed < 30);
            small++;
        }
        replica_check(&r, ds);
    }
    CHECK(small >= 10);
    free(points);
    check_against_scratch(ds, surface);

    /* A new surface: everything. */
    TpiSurface *taller = dome_scaled(1.5);
    CHECK_OK(tpi_discrete_surface_set_surface(ds, taller));
    CHECK_OK(tpi_discrete_surface_recompute(ds));
    replica_follow(&r, ds, &everything);
    CHECK(everything == 1);
    replica_check(&r, ds);

    /* Conventions and errors. */
    TpiMeshChanges *c = NULL, *none = NULL;
    TpiDiscretisation *mesh = NULL;
    CHECK_OK(tpi_discrete_surface_changes(ds, &c));
    CHECK_OK(tpi_discrete_surface_mesh(ds, &mesh));
    CHECK_OK(tpi_mesh_changes_counts(c, NULL, NULL, NULL));
    size_t count = 0, needed = 0;
    uint32_t one[1];
    CHECK_OK(tpi_mesh_changes_facets(c, NULL, 0, &needed)); /* nothing changed: empty */
    CHECK(needed == 0);
    CHECK_STATUS(tpi_mesh_changes_facet_sizes(c, NULL, 1, &needed), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_discrete_surface_changes(NULL, &none), TPI_STATUS_NULL_POINTER);
    CHECK(none == NULL);
    CHECK_STATUS(tpi_discrete_surface_changes(ds, NULL), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_mesh_changes_counts(NULL, NULL, &count, NULL), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_mesh_changes_vertex_ids((const TpiMeshChanges *)mesh, one, 1, &needed), TPI_STATUS_INVALID_HANDLE);
    CHECK(last_error_contains("TpiMeshChanges"));
    CHECK_STATUS(tpi_discretisation_facet_count((const TpiDiscretisation *)c, &count), TPI_STATUS_INVALID_HANDLE);
    CHECK_STATUS(tpi_discrete_surface_changes((TpiDiscreteSurface *)c, &none), TPI_STATUS_INVALID_HANDLE);
    tpi_mesh_changes_free((TpiMeshChanges *)mesh); /* the wrong kind: ignored */
    CHECK_OK(tpi_discretisation_facet_count(mesh, &count));
    tpi_discrete_surface_free(ds); /* the snapshot outlives it */
    CHECK_OK(tpi_mesh_changes_counts(c, &everything, &count, NULL));
    CHECK(everything == 0 && count == 256);
    tpi_mesh_changes_free(c);
    tpi_discretisation_free(mesh);
    replica_free(&r);
    tpi_surface_free(taller);
    tpi_surface_free(surface);
}

static void test_free_null(void) {
    tpi_surface_free(NULL);
    tpi_pattern_free(NULL);
    tpi_discretisation_free(NULL);
    tpi_discrete_surface_free(NULL);
    tpi_mesh_changes_free(NULL);
    CHECK(1);
}

/* ------------------------------------------------------------- threads */

typedef struct {
    const TpiSurface *surface;
    const TpiPattern *pattern;
    TpiDiscreteSurface *ds;
    int id;
    int failures;
} ThreadArgs;

static void *worker(void *opaque) {
    ThreadArgs *args = opaque;
    /* Shared immutable handles: same result as on the main thread. */
    TpiDiscretisation *d = NULL;
    if (tpi_discretise(args->surface, args->pattern, NULL, &d) != TPI_STATUS_OK) args->failures++;
    size_t needed = 0;
    tpi_discretisation_json(d, 0, NULL, 0, &needed);
    char *json = malloc(needed ? needed : 1);
    if (!json || tpi_discretisation_json(d, 0, json, needed, NULL) != TPI_STATUS_OK ||
        strcmp(json, expected_json) != 0) {
        args->failures++;
    }
    free(json);
    tpi_discretisation_free(d);
    /* A per-thread last error. */
    char spec[32];
    snprintf(spec, sizeof spec, "bogus%d:1", args->id);
    TpiPattern *p = NULL;
    if (tpi_pattern_new_from_spec(spec, &p) != TPI_STATUS_INVALID_PATTERN) args->failures++;
    char message[512];
    char mine[32];
    snprintf(mine, sizeof mine, "`bogus%d`", args->id);
    if (tpi_last_error_message(message, sizeof message, NULL) != TPI_STATUS_OK ||
        strstr(message, mine) == NULL) {
        args->failures++;
    }
    /* Concurrent edits of one discrete surface. */
    for (int k = 0; k < 3; k++) {
        double s = 0.03 + 0.25 * args->id + 0.05 * k;
        if (tpi_discrete_surface_add_point(args->ds, s, 0.995, NULL) != TPI_STATUS_OK) args->failures++;
    }
    if (tpi_discrete_surface_recompute(args->ds) != TPI_STATUS_OK) args->failures++;
    return NULL;
}

static void test_threads(void) {
    TpiSurface *surface = dome();
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_from_spec(DOME_PATTERN_SPEC, &pattern));
    TpiDiscreteSurface *ds = NULL;
    CHECK_OK(tpi_discrete_surface_new(surface, pattern, NULL, &ds));
    enum { THREADS = 4 };
    pthread_t threads[THREADS];
    ThreadArgs args[THREADS];
    for (int t = 0; t < THREADS; t++) {
        ThreadArgs a = {surface, pattern, ds, t, 0};
        args[t] = a;
        CHECK(pthread_create(&threads[t], NULL, worker, &args[t]) == 0);
    }
    for (int t = 0; t < THREADS; t++) {
        CHECK(pthread_join(threads[t], NULL) == 0);
        CHECK(args[t].failures == 0);
    }
    size_t count = 0;
    CHECK_OK(tpi_discrete_surface_point_count(ds, &count));
    CHECK(count == EXPECTED_FACET_COUNT + 3 * THREADS);
    CHECK(pending(ds) == 0);
    check_against_scratch(ds, surface);
    tpi_discrete_surface_free(ds);
    tpi_pattern_free(pattern);
    tpi_surface_free(surface);
}

/* Adjusted planes on a saddle with a uniform random pattern: every facet valid, each facet's
 * plane (tpi_discretisation_planes) holds its vertices and is tilted at most 5 degrees from
 * its seed's normal, some are tilted; an unknown plane mode is refused by name. */
static void test_adjusted_planes(void) {
    TpiSurface *s = NULL;
    TpiPattern *p = NULL;
    TpiDiscretisation *d = NULL;
    CHECK_OK(tpi_surface_new_hyperbolic_paraboloid(0.1, 0.1, -3, 3, -3, 3, &s));
    CHECK_OK(tpi_pattern_new_random(1500, 11, &p));
    TpiOptions options = default_options();
    options.plane_mode = 7;
    CHECK_STATUS(tpi_discretise(s, p, &options, &d), TPI_STATUS_INVALID_ARGUMENT);
    CHECK(last_error_contains("plane_mode"));
    options.plane_mode = TPI_PLANES_ADJUSTED;
    CHECK_OK(tpi_discretise(s, p, &options, &d));
    size_t facets = 0, needed = 0;
    CHECK_OK(tpi_discretisation_facet_count(d, &facets));
    TpiPlane *planes = calloc(facets, sizeof *planes);
    TpiSeed *seeds = calloc(facets, sizeof *seeds);
    uint32_t *sizes = calloc(facets, sizeof *sizes);
    size_t vertex_count = 0, index_count = 0;
    CHECK_OK(tpi_discretisation_planes(d, planes, facets, &needed));
    CHECK_OK(tpi_discretisation_seeds(d, seeds, facets, &needed));
    CHECK_OK(tpi_discretisation_facet_sizes(d, sizes, facets, &needed));
    CHECK_OK(tpi_discretisation_vertex_count(d, &vertex_count));
    tpi_discretisation_facet_indices(d, NULL, 0, &index_count);
    double *xyz = calloc(3 * vertex_count, sizeof *xyz);
    uint32_t *indices = calloc(index_count, sizeof *indices);
    CHECK_OK(tpi_discretisation_vertices(d, xyz, 3 * vertex_count, &needed));
    CHECK_OK(tpi_discretisation_facet_indices(d, indices, index_count, &needed));
    size_t tilted = 0, at = 0, off_plane = 0, too_steep = 0;
    for (size_t f = 0; f < facets; f++) {
        const double *n = planes[f].normal, *m = seeds[f].normal;
        double cosine = n[0] * m[0] + n[1] * m[1] + n[2] * m[2];
        /* cos(5 degrees) = 0.996194698 */
        if (cosine < 0.9961946) too_steep++;
        if (cosine < 1.0 - 1e-15) tilted++;
        for (uint32_t k = 0; k < sizes[f]; k++, at++) {
            const double *x = xyz + 3 * indices[at];
            double dist = 0.0;
            for (int c = 0; c < 3; c++) dist += n[c] * (x[c] - planes[f].point[c]);
            if (dist > 1e-9 || dist < -1e-9) off_plane++;
        }
    }
    CHECK(at == index_count);
    CHECK(off_plane == 0 && too_steep == 0);
    CHECK(tilted > 0);
    TpiQualityReport quality;
    memset(&quality, 0, sizeof quality);
    quality.struct_size = sizeof quality;
    CHECK_OK(tpi_discretisation_quality(d, &quality));
    CHECK(quality.invalid_facets == 0);
    free(planes);
    free(seeds);
    free(sizes);
    free(xyz);
    free(indices);
    tpi_discretisation_free(d);
    tpi_pattern_free(p);
    tpi_surface_free(s);
}

/* Units (issue 16): a copy of a surface with Rhino's UnitSystem value, carried to the JSON. */
static void test_units(void) {
    TpiSurface *plain = dome();
    int32_t units = -1;
    CHECK_OK(tpi_surface_units(plain, &units));
    CHECK(units == TPI_UNITS_NONE);
    TpiSurface *mm = NULL;
    CHECK_OK(tpi_surface_with_units(plain, TPI_UNITS_MILLIMETERS, &mm));
    CHECK(mm != NULL);
    CHECK_OK(tpi_surface_units(mm, &units));
    CHECK(units == TPI_UNITS_MILLIMETERS && units == 2);
    CHECK_OK(tpi_surface_units(plain, &units));
    CHECK(units == TPI_UNITS_NONE);
    TpiSurface *yards = NULL;
    CHECK_OK(tpi_surface_with_units(mm, TPI_UNITS_YARDS, &yards));
    CHECK_OK(tpi_surface_units(yards, &units));
    CHECK(units == 19);
    TpiSurface *bad = mm;
    CHECK_STATUS(tpi_surface_with_units(plain, 6, &bad), TPI_STATUS_INVALID_ARGUMENT);
    CHECK(bad == NULL);
    CHECK_STATUS(tpi_surface_with_units(NULL, TPI_UNITS_METERS, &bad), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_surface_units(mm, NULL), TPI_STATUS_NULL_POINTER);

    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_grid(6, 6, &pattern));
    TpiDiscretisation *with = NULL, *without = NULL;
    CHECK_OK(tpi_discretise(mm, pattern, NULL, &with));
    CHECK_OK(tpi_discretise(plain, pattern, NULL, &without));
    char *a = discretisation_json(with);
    char *b = discretisation_json(without);
    CHECK(a && strstr(a, "\"units\":\"mm\""));
    CHECK(b && strstr(b, "\"units\":null"));
    free(a);
    free(b);
    tpi_discretisation_free(with);
    tpi_discretisation_free(without);
    tpi_pattern_free(pattern);
    tpi_surface_free(yards);
    tpi_surface_free(mm);
    tpi_surface_free(plain);
}

/* Point-in-polygon by the crossing rule (n points, u then v per point). */
static int in_polygon(const double *loop, size_t n, double u, double v) {
    int inside = 0;
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
        double ui = loop[2 * i], vi = loop[2 * i + 1], uj = loop[2 * j], vj = loop[2 * j + 1];
        if ((vi > v) != (vj > v) && u < (uj - ui) * (v - vi) / (vj - vi) + ui) inside = !inside;
    }
    return inside;
}

/* The dome trimmed to a disc polyline: one facet per pattern point inside the disc. */
static void test_trim(void) {
    enum { N = 40, GRID = 9 };
    double outer[2 * N], clockwise[2 * N];
    for (size_t k = 0; k < N; k++) {
        double a = 2.0 * 3.14159265358979323846 * (double)k / N;
        outer[2 * k] = 0.5 + 0.4 * cos(a);
        outer[2 * k + 1] = 0.5 + 0.4 * sin(a);
    }
    for (size_t k = 0; k < N; k++) {
        clockwise[2 * k] = outer[2 * (N - 1 - k)];
        clockwise[2 * k + 1] = outer[2 * (N - 1 - k) + 1];
    }
    double points[2 * GRID * GRID];
    size_t inside = 0;
    for (size_t i = 0; i < GRID; i++) {
        for (size_t j = 0; j < GRID; j++) {
            double s = (i + 0.5 + 0.2 * ((double)((i * 7 + j * 3) % 5) - 2.0) / 5.0) / GRID;
            double t = (j + 0.5 + 0.2 * ((double)((i * 3 + j * 5) % 5) - 2.0) / 5.0) / GRID;
            points[2 * (i * GRID + j)] = s;
            points[2 * (i * GRID + j) + 1] = t;
            inside += (size_t)in_polygon(outer, N, s, t);
        }
    }
    CHECK(inside > 10 && inside < GRID * GRID);

    TpiSurface *surface = dome();
    TpiSurface *trimmed = NULL;
    CHECK_OK(tpi_surface_with_trim(surface, outer, 2 * N, NULL, 0, NULL, 0, &trimmed));
    CHECK(trimmed != NULL);
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new(points, 2 * GRID * GRID, &pattern));
    TpiDiscretisation *d = NULL;
    CHECK_OK(tpi_discretise(trimmed, pattern, NULL, &d));
    size_t facets = 0;
    CHECK_OK(tpi_discretisation_facet_count(d, &facets));
    CHECK(facets == inside);
    tpi_discretisation_free(d);

    /* Domain and evaluation are the untrimmed surface's. */
    TpiDomain domain;
    CHECK_OK(tpi_surface_domain(trimmed, &domain));
    CHECK(domain.u_min == 0.0 && domain.u_max == 1.0);
    double uv[2] = {0.05, 0.05};
    TpiSample a, b;
    CHECK_OK(tpi_surface_evaluate(surface, uv, 2, &a, 1));
    CHECK_OK(tpi_surface_evaluate(trimmed, uv, 2, &b, 1));
    CHECK(memcmp(&a, &b, sizeof a) == 0);

    /* Live editing refuses a trim. */
    TpiDiscreteSurface *ds = (TpiDiscreteSurface *)1;
    CHECK_STATUS(tpi_discrete_surface_new(trimmed, pattern, NULL, &ds), TPI_STATUS_INVALID_ARGUMENT);
    CHECK(ds == NULL);

    /* Errors, each naming the item. */
    char message[512];
    TpiSurface *bad = trimmed;
    CHECK_STATUS(tpi_surface_with_trim(surface, clockwise, 2 * N, NULL, 0, NULL, 0, &bad),
                 TPI_STATUS_INVALID_ARGUMENT);
    CHECK(bad == NULL);
    tpi_last_error_message(message, sizeof message, NULL);
    CHECK(strstr(message, "trim.outer") && strstr(message, "counter-clockwise"));
    CHECK_STATUS(tpi_surface_with_trim(surface, outer, 2 * N - 1, NULL, 0, NULL, 0, &bad),
                 TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_surface_with_trim(surface, NULL, 2 * N, NULL, 0, NULL, 0, &bad),
                 TPI_STATUS_NULL_POINTER);
    size_t count = 5;
    CHECK_STATUS(tpi_surface_with_trim(surface, outer, 2 * N, clockwise, 12, &count, 1, &bad),
                 TPI_STATUS_INVALID_ARGUMENT);
    tpi_last_error_message(message, sizeof message, NULL);
    CHECK(strstr(message, "hole_point_counts") != NULL);
    double nan_outer[2 * N];
    memcpy(nan_outer, outer, sizeof outer);
    nan_outer[3] = NAN;
    CHECK_STATUS(tpi_surface_with_trim(surface, nan_outer, 2 * N, NULL, 0, NULL, 0, &bad),
                 TPI_STATUS_NON_FINITE);
    CHECK_STATUS(tpi_surface_with_trim(NULL, outer, 2 * N, NULL, 0, NULL, 0, &bad),
                 TPI_STATUS_NULL_POINTER);

    tpi_pattern_free(pattern);
    tpi_surface_free(trimmed);
    tpi_surface_free(surface);
}

/* A rational sphere of one face (closed in u, poles at both ends of v, as Rhino makes it):
 * the mesh is closed. Checked here from the arrays: every directed edge of a facet loop is
 * run backwards by exactly one other loop, and V - E + F = 2; every vertex lies on or behind
 * every seed's tangent plane (the sphere's closed form: the plane at p is p . x = r^2). */
/* A cylinder with random points: the planes of three rulings meet at infinity, so the facets
 * are strips, one per seed, and each strip's neighbours are the seeds with the next smaller
 * and larger x (the order of the rulings); every vertex lies on an end line, y = y0 or y1. */
static void test_ruling_strips(void) {
    TpiSurface *s = NULL;
    CHECK_OK(tpi_surface_new_cylinder(1.0, -0.8, 0.8, 0.0, 3.0, &s));
    TpiPattern *p = NULL;
    CHECK_OK(tpi_pattern_new_random(150, 11, &p));
    TpiDiscretisation *d = NULL;
    CHECK_OK(tpi_discretise(s, p, NULL, &d));
    size_t facets = 0, vertex_count = 0, needed = 0, pairs_len = 0, count = 0, entries_len = 0;
    CHECK_OK(tpi_discretisation_facet_count(d, &facets));
    CHECK_OK(tpi_discretisation_vertex_count(d, &vertex_count));
    CHECK(facets == 150);
    double *xyz = malloc(3 * vertex_count * sizeof *xyz);
    CHECK_OK(tpi_discretisation_vertices(d, xyz, 3 * vertex_count, &needed));
    for (size_t v = 0; v < vertex_count; v++) {
        double y = xyz[3 * v + 1];
        CHECK(fabs(y) < 1e-9 || fabs(y - 3.0) < 1e-9);
    }
    TpiSeed *seeds = malloc(facets * sizeof *seeds);
    CHECK_OK(tpi_discretisation_seeds(d, seeds, facets, &needed));
    CHECK_STATUS(tpi_discretisation_neighbour_pairs(d, NULL, 0, &pairs_len), TPI_STATUS_BUFFER_TOO_SMALL);
    CHECK(pairs_len == 2 * (facets - 1));
    uint32_t *pairs = malloc(pairs_len * sizeof *pairs);
    CHECK_OK(tpi_discretisation_neighbour_pairs(d, pairs, pairs_len, &needed));
    for (size_t k = 0; k < pairs_len / 2; k++) {
        double a = seeds[pairs[2 * k]].point[0], b = seeds[pairs[2 * k + 1]].point[0];
        double lo = a < b ? a : b, hi = a < b ? b : a;
        /* No seed's ruling lies strictly between two neighbours'. */
        for (size_t f = 0; f < facets; f++) CHECK(!(seeds[f].point[0] > lo && seeds[f].point[0] < hi));
    }
    CHECK_OK(tpi_discretisation_diagnostic_count(d, &count));
    CHECK_STATUS(tpi_discretisation_diagnostic_entries(d, NULL, 0, &entries_len), TPI_STATUS_BUFFER_TOO_SMALL);
    TpiDiagnosticEntry *entries = malloc(entries_len * sizeof *entries);
    CHECK_OK(tpi_discretisation_diagnostic_entries(d, entries, entries_len, &needed));
    size_t strips = 0;
    for (size_t k = 0; k < entries_len; k++) strips += entries[k].kind == TPI_DIAGNOSTIC_KIND_RULING_STRIPS;
    CHECK(strips == 1);
    TpiQualityReport q;
    memset(&q, 0, sizeof q);
    q.struct_size = sizeof q;
    CHECK_OK(tpi_discretisation_quality(d, &q));
    CHECK(q.invalid_facets == 0);
    free(entries);
    free(pairs);
    free(seeds);
    free(xyz);
    tpi_discretisation_free(d);
    tpi_pattern_free(p);
    tpi_surface_free(s);
}

static void test_closed_sphere(void) {
    const double w = 0.70710678118654752440;
    const double circle[9][3] = {{1, 0, 1}, {1, 1, w}, {0, 1, 1}, {-1, 1, w}, {-1, 0, 1},
                                 {-1, -1, w}, {0, -1, 1}, {1, -1, w}, {1, 0, 1}};
    const double meridian[5][3] = {{0, -1, 1}, {1, -1, w}, {1, 0, 1}, {1, 1, w}, {0, 1, 1}};
    const double r = 2.5;
    double points[9 * 5 * 3], weights[9 * 5];
    for (int i = 0; i < 9; i++) {
        for (int j = 0; j < 5; j++) {
            double *p = &points[3 * (5 * i + j)];
            p[0] = r * circle[i][0] * meridian[j][0];
            p[1] = r * circle[i][1] * meridian[j][0];
            p[2] = r * meridian[j][1];
            weights[5 * i + j] = circle[i][2] * meridian[j][2];
        }
    }
    const double knots_u[10] = {0, 0, 1, 1, 2, 2, 3, 3, 4, 4};
    const double knots_v[6] = {0, 0, 1, 1, 2, 2};
    TpiSurface *s = NULL;
    CHECK_OK(tpi_surface_new_nurbs(2, 2, 9, 5, knots_u, 10, knots_v, 6, points, 135, weights, 45, &s));
    TpiPattern *p = NULL;
    CHECK_OK(tpi_pattern_new_from_spec("random:200:seed=3", &p));
    TpiDiscretisation *d = NULL;
    CHECK_OK(tpi_discretise(s, p, NULL, &d));
    size_t facets = 0, vertex_count = 0, needed = 0, total = 0;
    CHECK_OK(tpi_discretisation_facet_count(d, &facets));
    CHECK_OK(tpi_discretisation_vertex_count(d, &vertex_count));
    CHECK(facets == 200);
    uint32_t *sizes = malloc(facets * sizeof *sizes);
    CHECK_OK(tpi_discretisation_facet_sizes(d, sizes, facets, &needed));
    for (size_t f = 0; f < facets; f++) total += sizes[f];
    uint32_t *indices = malloc(total * sizeof *indices);
    CHECK_OK(tpi_discretisation_facet_indices(d, indices, total, &needed));
    double *xyz = malloc(3 * vertex_count * sizeof *xyz);
    CHECK_OK(tpi_discretisation_vertices(d, xyz, 3 * vertex_count, &needed));
    TpiSeed *seeds = malloc(facets * sizeof *seeds);
    CHECK_OK(tpi_discretisation_seeds(d, seeds, facets, &needed));
    /* Directed edges (a, b): each must meet its reverse exactly once. */
    size_t unmatched = 0, start = 0;
    for (size_t f = 0; f < facets; f++) {
        for (uint32_t k = 0; k < sizes[f]; k++) {
            uint32_t a = indices[start + k], b = indices[start + (k + 1) % sizes[f]];
            size_t reverse = 0, other = 0;
            for (size_t g = 0; g < facets; g++) {
                for (uint32_t m = 0; m < sizes[g]; m++) {
                    uint32_t c = indices[other + m], e = indices[other + (m + 1) % sizes[g]];
                    if (c == b && e == a) reverse++;
                }
                other += sizes[g];
            }
            if (reverse != 1) unmatched++;
        }
        start += sizes[f];
    }
    CHECK(unmatched == 0);
    CHECK((long)vertex_count - (long)(total / 2) + (long)facets == 2);
    double worst = -1;
    for (size_t v = 0; v < vertex_count; v++) {
        for (size_t f = 0; f < facets; f++) {
            const double *q = seeds[f].point, *x = &xyz[3 * v];
            double ahead = (q[0] * x[0] + q[1] * x[1] + q[2] * x[2]) / r - r;
            if (ahead > worst) worst = ahead;
        }
    }
    CHECK(worst <= 1e-9 * r);
    free(sizes);
    free(indices);
    free(xyz);
    free(seeds);
    tpi_discretisation_free(d);
    tpi_pattern_free(p);
    tpi_surface_free(s);
}

/* Facet loops of a discretisation: sizes, indices (concatenated) and vertices (x, y, z). */
typedef struct {
    size_t facets, vertices, total;
    uint32_t *sizes, *indices;
    double *xyz;
} Loops;

static Loops read_loops(const TpiDiscretisation *d) {
    Loops m;
    size_t needed = 0;
    memset(&m, 0, sizeof m);
    CHECK_OK(tpi_discretisation_facet_count(d, &m.facets));
    CHECK_OK(tpi_discretisation_vertex_count(d, &m.vertices));
    m.sizes = malloc(m.facets * sizeof *m.sizes);
    CHECK_OK(tpi_discretisation_facet_sizes(d, m.sizes, m.facets, &needed));
    for (size_t f = 0; f < m.facets; f++) m.total += m.sizes[f];
    m.indices = malloc(m.total * sizeof *m.indices);
    CHECK_OK(tpi_discretisation_facet_indices(d, m.indices, m.total, &needed));
    m.xyz = malloc(3 * m.vertices * sizeof *m.xyz);
    CHECK_OK(tpi_discretisation_vertices(d, m.xyz, 3 * m.vertices, &needed));
    return m;
}

static void free_loops(Loops *m) {
    free(m->sizes);
    free(m->indices);
    free(m->xyz);
}

/* Two halves of the saddle z = 0.4 x^2 - 0.4 y^2 (x in [-1, 0] and [0, 1], y in [-1, 1]),
 * given right half first, joined into one polysurface: its mesh is the single face's over
 * [-1, 1]^2 facet by facet, vertex by vertex; from the facet loops alone it is a disc
 * (V - E + F = 1, every inner edge run once each way, the boundary edges one closed loop).
 * Then every refused input, named. */
static void test_polysurface(void) {
    TpiSurface *left = NULL, *right = NULL, *single = NULL, *joined = NULL;
    CHECK_OK(tpi_surface_new_hyperbolic_paraboloid(0.4, 0.4, -1, 0, -1, 1, &left));
    CHECK_OK(tpi_surface_new_hyperbolic_paraboloid(0.4, 0.4, 0, 1, -1, 1, &right));
    CHECK_OK(tpi_surface_new_hyperbolic_paraboloid(0.4, 0.4, -1, 1, -1, 1, &single));
    const TpiSurface *faces[2] = {right, left};
    CHECK_OK(tpi_surface_new_polysurface(faces, 2, &joined));
    CHECK(joined != NULL);

    /* Hostile input, while the faces are alive. */
    char message[512];
    TpiSurface *bad = (TpiSurface *)1;
    CHECK_STATUS(tpi_surface_new_polysurface(NULL, 2, &bad), TPI_STATUS_NULL_POINTER);
    CHECK(bad == NULL);
    CHECK(last_error_contains("faces is NULL"));
    bad = (TpiSurface *)1;
    CHECK_STATUS(tpi_surface_new_polysurface(faces, 0, &bad), TPI_STATUS_INVALID_ARGUMENT);
    CHECK(bad == NULL);
    CHECK(last_error_contains("faces: "));
    const TpiSurface *with_null[2] = {left, NULL};
    CHECK_STATUS(tpi_surface_new_polysurface(with_null, 2, &bad), TPI_STATUS_NULL_POINTER);
    CHECK(last_error_contains("faces[1] is NULL"));
    CHECK_STATUS(tpi_surface_new_polysurface(faces, 2, NULL), TPI_STATUS_NULL_POINTER);
    TpiSurface *apart = NULL;
    CHECK_OK(tpi_surface_new_hyperbolic_paraboloid(0.4, 0.4, 2, 3, -1, 1, &apart));
    const TpiSurface *separate[2] = {left, apart};
    bad = (TpiSurface *)1;
    CHECK_STATUS(tpi_surface_new_polysurface(separate, 2, &bad), TPI_STATUS_INVALID_ARGUMENT);
    CHECK(bad == NULL);
    tpi_last_error_message(message, sizeof message, NULL);
    CHECK(strncmp(message, "faces[1]: ", 10) == 0 && strstr(message, "shares no whole side"));
    const TpiSurface *nested[2] = {joined, apart};
    CHECK_STATUS(tpi_surface_new_polysurface(nested, 2, &bad), TPI_STATUS_INVALID_ARGUMENT);
    CHECK(last_error_contains("faces[0]: "));
    tpi_surface_free(apart);

    /* The faces are borrowed: the polysurface outlives them. */
    tpi_surface_free(left);
    tpi_surface_free(right);

    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_from_spec("hex:12x14", &pattern));
    TpiDiscretisation *d1 = NULL, *d2 = NULL;
    CHECK_OK(tpi_discretise(single, pattern, NULL, &d1));
    CHECK_OK(tpi_discretise(joined, pattern, NULL, &d2));
    Loops a = read_loops(d1), b = read_loops(d2);
    CHECK(a.facets > 100 && a.facets == b.facets && a.total == b.total);
    if (a.facets == b.facets && a.total == b.total) {
        double worst = 0;
        size_t start = 0, sizes_differ = 0;
        for (size_t f = 0; f < a.facets; f++) {
            if (a.sizes[f] != b.sizes[f]) {
                sizes_differ++;
                break;
            }
            for (uint32_t k = 0; k < a.sizes[f]; k++) {
                const double *p = &a.xyz[3 * a.indices[start + k]];
                const double *q = &b.xyz[3 * b.indices[start + k]];
                double dist = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                   (p[2] - q[2]) * (p[2] - q[2]));
                if (dist > worst) worst = dist;
            }
            start += a.sizes[f];
        }
        CHECK(sizes_differ == 0);
        CHECK(worst <= 1e-9);
    }

    /* Topology from the joined mesh's loops alone. */
    size_t start = 0, inner = 0, boundary = 0, doubled = 0;
    uint32_t *next = malloc(b.vertices * sizeof *next);
    unsigned char *used = calloc(b.vertices, 1);
    for (size_t v = 0; v < b.vertices; v++) next[v] = UINT32_MAX;
    for (size_t f = 0; f < b.facets; f++) {
        for (uint32_t k = 0; k < b.sizes[f]; k++) {
            uint32_t u = b.indices[start + k], w = b.indices[start + (k + 1) % b.sizes[f]];
            used[u] = 1;
            size_t reverse = 0, same = 0, other = 0;
            for (size_t g = 0; g < b.facets; g++) {
                for (uint32_t m = 0; m < b.sizes[g]; m++) {
                    uint32_t c = b.indices[other + m], e = b.indices[other + (m + 1) % b.sizes[g]];
                    if (c == w && e == u) reverse++;
                    if (c == u && e == w) same++;
                }
                other += b.sizes[g];
            }
            if (same != 1 || reverse > 1) doubled++;
            if (reverse == 1) {
                inner++;
            } else {
                boundary++;
                if (next[u] != UINT32_MAX) doubled++;
                next[u] = w;
            }
        }
        start += b.sizes[f];
    }
    size_t vertex_used = 0;
    for (size_t v = 0; v < b.vertices; v++) vertex_used += used[v];
    CHECK(doubled == 0 && inner % 2 == 0 && boundary >= 4);
    CHECK(vertex_used == b.vertices);
    size_t edges = inner / 2 + boundary;
    CHECK((long)b.vertices - (long)edges + (long)b.facets == 1);
    /* Follow the boundary from one of its edges: one loop runs through all of them. */
    size_t loop_length = 0;
    uint32_t first = UINT32_MAX;
    for (size_t v = 0; v < b.vertices && first == UINT32_MAX; v++) {
        if (next[v] != UINT32_MAX) first = (uint32_t)v;
    }
    if (first != UINT32_MAX) {
        uint32_t v = first;
        do {
            v = next[v];
            loop_length++;
        } while (v != UINT32_MAX && v != first && loop_length <= boundary);
    }
    CHECK(loop_length == boundary);
    free(next);
    free(used);
    free_loops(&a);
    free_loops(&b);
    tpi_discretisation_free(d1);
    tpi_discretisation_free(d2);
    tpi_pattern_free(pattern);
    tpi_surface_free(joined);
    tpi_surface_free(single);
}

/* Progress and cancelling (tpi_discretise_with_progress). The callback keeps what it saw; the
 * library never calls it twice at once, so plain fields will do. */
typedef struct {
    int calls;
    uint32_t last_stage;
    uint32_t max_stage;
    int out_of_order;  /* a stage going back, done going back or above total */
    uint64_t last_done;
    uint64_t last_total;
    int ended_at_total; /* stages whose last report had done == total */
    uint32_t cancel_at; /* cancel at the first report of this stage; 99: never */
} ProgressLog;

static int32_t progress_record(void *user_data, uint32_t stage, uint64_t done, uint64_t total) {
    ProgressLog *log = (ProgressLog *)user_data;
    if (log->calls > 0 && stage != log->last_stage) {
        if (stage < log->last_stage) log->out_of_order++;
        if (log->last_done == log->last_total) log->ended_at_total++;
        log->last_done = 0;
    }
    if (done < log->last_done || done > total) log->out_of_order++;
    log->calls++;
    log->last_stage = stage;
    log->last_done = done;
    log->last_total = total;
    if (stage > log->max_stage) log->max_stage = stage;
    return stage == log->cancel_at ? 1 : 0;
}

static void test_progress(void) {
    TpiSurface *surface = dome();
    TpiPattern *pattern = NULL;
    CHECK_OK(tpi_pattern_new_hex(40, 40, &pattern));

    /* Not cancelled: every stage in order, each ending at its total; the result is
     * tpi_discretise's, byte for byte. */
    ProgressLog log;
    memset(&log, 0, sizeof log);
    log.cancel_at = 99;
    TpiDiscretisation *watched = NULL, *plain = NULL;
    CHECK_OK(tpi_discretise_with_progress(surface, pattern, NULL, progress_record, &log, &watched));
    CHECK_OK(tpi_discretise(surface, pattern, NULL, &plain));
    CHECK(log.calls >= 12 && log.out_of_order == 0);
    CHECK(log.max_stage == TPI_STAGE_REPORT && log.last_stage == TPI_STAGE_REPORT);
    CHECK(log.last_done == log.last_total && log.ended_at_total == 5);
    char *a = discretisation_json(watched);
    char *b = discretisation_json(plain);
    CHECK(a && b && strcmp(a, b) == 0);
    free(a);
    free(b);
    tpi_discretisation_free(watched);
    tpi_discretisation_free(plain);

    /* Cancelled from the callback at the start of each stage: TPI_STATUS_CANCELLED, no handle,
     * the message naming where it stopped, no later stage started (the facets and the mesh
     * assembly are one step). valgrind checks that nothing of the stopped run leaks. */
    const char *names[] = {"samples", "delaunay", "neighbours", "facets", "mesh", "report"};
    for (uint32_t stage = TPI_STAGE_SAMPLES; stage <= TPI_STAGE_REPORT; stage++) {
        uint32_t stops = stage == TPI_STAGE_FACETS ? TPI_STAGE_MESH : stage;
        memset(&log, 0, sizeof log);
        log.cancel_at = stage;
        TpiDiscretisation *d = (TpiDiscretisation *)&log; /* must be set to NULL */
        CHECK_STATUS(tpi_discretise_with_progress(surface, pattern, NULL, progress_record, &log, &d),
                     TPI_STATUS_CANCELLED);
        CHECK(d == NULL);
        CHECK(last_error_contains("cancelled") && last_error_contains(names[stops]));
        CHECK(log.max_stage == stops && log.last_stage == stops);
    }
    CHECK(strcmp(tpi_status_name(TPI_STATUS_CANCELLED), "TPI_STATUS_CANCELLED") == 0);

    /* No callback: tpi_discretise. NULL handles are refused before any report. */
    TpiDiscretisation *d = NULL;
    CHECK_OK(tpi_discretise_with_progress(surface, pattern, NULL, NULL, NULL, &d));
    CHECK(d != NULL);
    tpi_discretisation_free(d);
    memset(&log, 0, sizeof log);
    CHECK_STATUS(tpi_discretise_with_progress(NULL, pattern, NULL, progress_record, &log, &d),
                 TPI_STATUS_NULL_POINTER);
    CHECK(d == NULL && log.calls == 0);

    tpi_pattern_free(pattern);
    tpi_surface_free(surface);
}

/* Counts the discretisations a pattern runs (a samples-stage call with done 0 starts one)
 * and cancels once `cancel_at` of them have started (0: never). */
struct fit_runs {
    uint64_t started;
    uint64_t cancel_at;
};

static int32_t count_fit_runs(void *user_data, uint32_t stage, uint64_t done, uint64_t total) {
    struct fit_runs *runs = user_data;
    (void)total;
    if (stage == TPI_STAGE_SAMPLES && done == 0) runs->started++;
    return runs->cancel_at != 0 && runs->started >= runs->cancel_at;
}

/* Patterns made on a surface from a spec (tpi_pattern_new_for_surface): a relaxation gives
 * the Rust API's own relaxed points (from the fixture), and a fit meets its tolerance at every
 * mesh vertex by a check made here, on the sphere cap where the distance from the surface has
 * a closed form: | |x - centre| - radius | (the distance to the whole sphere; a vertex
 * beyond the cap's edge is at least that far from the cap, so the check can only be
 * stricter than needed, never looser). */
static void test_surface_patterns(void) {
    TpiSurface *dome_surface = dome();
    TpiPattern *p = NULL;
    CHECK_OK(tpi_pattern_new_for_surface(dome_surface, RELAXED_SPEC, NULL, &p));
    CHECK(pattern_size(p) == EXPECTED_RELAXED_LEN / 2);
    double relaxed[EXPECTED_RELAXED_LEN];
    CHECK_OK(tpi_pattern_points(p, relaxed, EXPECTED_RELAXED_LEN, NULL));
    int moved = 0;
    for (size_t k = 0; k < EXPECTED_RELAXED_LEN; k++) {
        CHECK_CLOSE(relaxed[k], expected_relaxed[k], 1e-12);
        if (fabs(relaxed[k] - dome_pattern[k]) > 1e-6) moved = 1;
    }
    CHECK(moved); /* the relaxation did something */
    TpiFitReport report;
    memset(&report, 0, sizeof report);
    report.struct_size = sizeof report;
    CHECK_STATUS(tpi_pattern_fit_report(p, &report), TPI_STATUS_UNAVAILABLE);
    CHECK(last_error_contains("fit:D"));
    tpi_pattern_free(p);
    p = NULL;

    /* Malformed specs name the piece that is wrong; nothing is created. */
    CHECK_STATUS(tpi_pattern_new_for_surface(dome_surface, "relax:abc:hex:4x4", NULL, &p), TPI_STATUS_INVALID_PATTERN);
    CHECK(p == NULL && last_error_contains("relax:abc"));
    CHECK_STATUS(tpi_pattern_new_for_surface(dome_surface, "fit:-1", NULL, &p), TPI_STATUS_INVALID_PATTERN);
    CHECK(last_error_contains("fit:-1"));
    CHECK_STATUS(tpi_pattern_new_for_surface(dome_surface, "density:@graded.json", NULL, &p), TPI_STATUS_INVALID_PATTERN);
    CHECK(last_error_contains("inline"));
    CHECK_STATUS(tpi_pattern_new_for_surface(dome_surface, "align:random:40:principal", NULL, &p), TPI_STATUS_INVALID_PATTERN);
    CHECK(last_error_contains("align:random"));
    CHECK_STATUS(tpi_pattern_new_for_surface(NULL, "hex:4x4", NULL, &p), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_pattern_new_for_surface(dome_surface, NULL, NULL, &p), TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_pattern_new_for_surface(dome_surface, "hex:4x4", NULL, NULL), TPI_STATUS_NULL_POINTER);
    CHECK(p == NULL);

    /* An aligned lattice along a direction field given as inline JSON (colons and all). */
    CHECK_OK(tpi_pattern_new_for_surface(dome_surface,
        "align:hex:6x6:{\"size\": [2, 2], \"directions\": [[1, 0], [1, 0], [1, 1], [1, 1]]}", NULL, &p));
    CHECK(pattern_size(p) >= 18 && pattern_size(p) <= 72);
    tpi_pattern_free(p);
    p = NULL;
    tpi_surface_free(dome_surface);

    TpiSurface *sphere = NULL;
    const double radius = 10.0, tolerance = 0.01;
    CHECK_OK(tpi_surface_new_sphere_cap(radius, -3, 3, -3, 3, &sphere));
    CHECK_OK(tpi_pattern_new_for_surface(sphere, "fit:0.01:seed=2", NULL, &p));
    memset(&report, 0, sizeof report);
    report.struct_size = sizeof report;
    CHECK_OK(tpi_pattern_fit_report(p, &report));
    CHECK(report.struct_size == sizeof report && sizeof report == TPI_FIT_REPORT_SIZE_V1);
    CHECK(report.met == 1 && report.tolerance == tolerance);
    CHECK(report.max_deviation > 0.0 && report.max_deviation <= tolerance);
    CHECK(report.discretisations >= 1);
    size_t count = pattern_size(p);
    CHECK(count >= 12);
    TpiDiscretisation *mesh = NULL;
    CHECK_OK(tpi_discretise(sphere, p, NULL, &mesh));
    size_t n_indices = 0, n_vertices = 0;
    CHECK_STATUS(tpi_discretisation_facet_indices(mesh, NULL, 0, &n_indices), TPI_STATUS_BUFFER_TOO_SMALL);
    CHECK_OK(tpi_discretisation_vertex_count(mesh, &n_vertices));
    uint32_t *indices = malloc(n_indices * sizeof *indices);
    double *vertices = malloc(3 * n_vertices * sizeof *vertices);
    CHECK(indices != NULL && vertices != NULL);
    CHECK_OK(tpi_discretisation_facet_indices(mesh, indices, n_indices, NULL));
    CHECK_OK(tpi_discretisation_vertices(mesh, vertices, 3 * n_vertices, NULL));
    double worst = 0.0;
    for (size_t k = 0; k < n_indices; k++) {
        const double *x = vertices + 3 * (size_t)indices[k];
        double off = fabs(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - radius);
        if (off > worst) worst = off;
    }
    CHECK(worst > 0.0 && worst <= tolerance * (1.0 + 1e-9));
    free(indices);
    free(vertices);
    tpi_discretisation_free(mesh);
    tpi_pattern_free(p);
    p = NULL;

    /* The same fit with a progress callback: the same points, one samples-stage start per
     * discretisation the fit reports having run, and a nonzero return cancels it: no handle,
     * no further discretisation started. */
    {
        TpiPattern *plain = NULL, *watched = NULL, *cancelled = NULL;
        CHECK_OK(tpi_pattern_new_for_surface(sphere, "fit:0.01:seed=2", NULL, &plain));
        struct fit_runs counter = {0, 0};
        CHECK_OK(tpi_pattern_new_for_surface_with_progress(sphere, "fit:0.01:seed=2", NULL, count_fit_runs, &counter, &watched));
        size_t n = pattern_size(plain);
        CHECK(n == pattern_size(watched));
        double *a = malloc(2 * n * sizeof *a), *b = malloc(2 * n * sizeof *b);
        CHECK(a != NULL && b != NULL);
        CHECK_OK(tpi_pattern_points(plain, a, 2 * n, NULL));
        CHECK_OK(tpi_pattern_points(watched, b, 2 * n, NULL));
        CHECK(memcmp(a, b, 2 * n * sizeof *a) == 0);
        free(a);
        free(b);
        CHECK(counter.started == report.discretisations && counter.started >= 3);
        struct fit_runs stopper = {0, 2};
        CHECK_STATUS(tpi_pattern_new_for_surface_with_progress(sphere, "fit:0.01:seed=2", NULL, count_fit_runs, &stopper, &cancelled),
                     TPI_STATUS_CANCELLED);
        CHECK(cancelled == NULL && stopper.started == 2 && last_error_contains("cancelled"));
        tpi_pattern_free(plain);
        tpi_pattern_free(watched);
    }

    /* The uniform hexagonal baseline of the same tolerance. */
    size_t hex_count = 0;
    double hex_deviation = 0.0;
    CHECK_OK(tpi_pattern_hex_baseline(sphere, tolerance, 100000, NULL, &hex_count, &hex_deviation));
    CHECK(hex_count > 0 && hex_deviation > 0.0 && hex_deviation <= tolerance);
    CHECK_OK(tpi_pattern_hex_baseline(sphere, tolerance, 10, NULL, &hex_count, &hex_deviation));
    CHECK(hex_count == 0 && isnan(hex_deviation)); /* none of at most 10 points meets it */
    CHECK_STATUS(tpi_pattern_hex_baseline(sphere, -1.0, 100, NULL, &hex_count, &hex_deviation), TPI_STATUS_INVALID_ARGUMENT);
    CHECK(last_error_contains("max_deviation"));
    CHECK_STATUS(tpi_pattern_hex_baseline(sphere, 0.1, 100, NULL, NULL, &hex_deviation), TPI_STATUS_NULL_POINTER);
    report.struct_size = 4;
    CHECK_STATUS(tpi_pattern_fit_report(NULL, &report), TPI_STATUS_NULL_POINTER);
    tpi_surface_free(sphere);
}

int main(void) {
    test_version_and_status_names();
    test_last_error();
    test_options();
    test_dome_sampling();
    test_rational_dome();
    test_nurbs_errors();
    test_evaluate_errors();
    test_analytic_surfaces();
    test_patterns();
    test_surface_patterns();
    test_dome_discretisation();
    test_options_in_use();
    test_adjusted_planes();
    test_closed_sphere();
    test_ruling_strips();
    test_diagnostics();
    test_discrete_surface();
    test_mesh_changes();
    test_progress();
    test_free_null();
    test_threads();
    test_units();
    test_trim();
    test_polysurface();
    return finish("test_tpi");
}
