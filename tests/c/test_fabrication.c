/*
 * The C test of the fabrication entry points: panels of a NURBS dome with one cleat slot per
 * interior edge, every file copied out (size query, then copy), the G-code, and the error
 * paths: NaN and negative thickness, a thickness beyond the mesh's limit, a bad side, an
 * unknown file, a tool wider than the gap, NULL handles.
 *
 * Built and run (also under valgrind) by tests/run_c_tests.sh.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "tpi_fixture.h"

static TpiDiscretisation *dome_mesh(TpiSurface **surface, TpiPattern **pattern) {
    CHECK_OK(tpi_surface_new_nurbs(DOME_DEGREE, DOME_DEGREE, DOME_COUNT, DOME_COUNT, dome_knots,
                                   DOME_KNOTS_LEN, dome_knots, DOME_KNOTS_LEN, dome_points,
                                   DOME_POINTS_LEN, NULL, 0, surface));
    CHECK_OK(tpi_pattern_new_hex(8, 8, pattern));
    TpiDiscretisation *d = NULL;
    CHECK_OK(tpi_discretise(*surface, *pattern, NULL, &d));
    CHECK(d != NULL);
    return d;
}

/* Size query, then copy; checks the NUL and returns the text (free it). */
static char *file_text(const TpiFabrication *f, uint32_t file) {
    size_t needed = 0;
    CHECK_STATUS(tpi_fabrication_file(f, file, NULL, 0, &needed), TPI_STATUS_BUFFER_TOO_SMALL);
    char *text = malloc(needed);
    if (!text) return NULL;
    size_t again = 0;
    CHECK_OK(tpi_fabrication_file(f, file, text, needed, &again));
    CHECK(again == needed);
    CHECK(strlen(text) + 1 == needed);
    return text;
}

static void test_fabrication(void) {
    TpiSurface *surface = NULL;
    TpiPattern *pattern = NULL;
    TpiDiscretisation *d = dome_mesh(&surface, &pattern);
    TpiFabrication *f = NULL;
    CHECK_OK(tpi_fabricate(d, 0.05, TPI_SIDE_INSIDE, 1, 6.0, 4.0, 0.03, &f));
    CHECK(f != NULL);
    size_t panels = 0, sheets = 0;
    CHECK_OK(tpi_fabrication_counts(f, &panels, &sheets));
    CHECK(panels == 64);
    CHECK(sheets >= 1);

    char *json = file_text(f, TPI_FILE_PANELS_JSON);
    CHECK(json && strstr(json, "\"thickness\":0.05") != NULL);
    free(json);
    char *obj = file_text(f, TPI_FILE_PANELS_OBJ);
    CHECK(obj && strstr(obj, "o panel_0\n") != NULL);
    free(obj);
    char *svg = file_text(f, TPI_FILE_SHEETS_SVG);
    CHECK(svg && strncmp(svg, "<svg", 4) == 0);
    free(svg);
    char *dxf = file_text(f, TPI_FILE_SHEETS_DXF);
    CHECK(dxf && strstr(dxf, "AC1015") != NULL && strstr(dxf, "EOF") != NULL);
    free(dxf);
    char *csv = file_text(f, TPI_FILE_BEVELS_CSV);
    CHECK(csv && strncmp(csv, "panel,side,neighbour,length,dihedral_deg,bevel_deg\n", 51) == 0);
    free(csv);

    size_t needed = 0;
    CHECK_STATUS(tpi_fabrication_gcode(f, 0.006, NULL, 0, &needed), TPI_STATUS_BUFFER_TOO_SMALL);
    char *gcode = malloc(needed);
    if (gcode) {
        CHECK_OK(tpi_fabrication_gcode(f, 0.006, gcode, needed, NULL));
        CHECK(strstr(gcode, "G3 ") != NULL);
        CHECK(strcmp(gcode + strlen(gcode) - 4, "M30\n") == 0);
        free(gcode);
    }

    /* Errors. */
    CHECK_STATUS(tpi_fabrication_file(f, 5, NULL, 0, &needed), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_fabrication_gcode(f, 0.5, NULL, 0, &needed), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_fabrication_gcode(f, NAN, NULL, 0, &needed), TPI_STATUS_NON_FINITE);
    TpiFabrication *none = NULL;
    CHECK_STATUS(tpi_fabricate(d, NAN, TPI_SIDE_INSIDE, 0, 6.0, 4.0, 0.03, &none),
                 TPI_STATUS_NON_FINITE);
    CHECK(none == NULL);
    CHECK_STATUS(tpi_fabricate(d, -1.0, TPI_SIDE_INSIDE, 0, 6.0, 4.0, 0.03, &none),
                 TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_fabricate(d, 50.0, TPI_SIDE_INSIDE, 0, 600.0, 400.0, 0.03, &none),
                 TPI_STATUS_INVALID_ARGUMENT);
    char message[512];
    CHECK_OK(tpi_last_error_message(message, sizeof message, NULL));
    CHECK(strstr(message, "collapses") != NULL);
    CHECK_STATUS(tpi_fabricate(d, 0.05, 2, 0, 6.0, 4.0, 0.03, &none), TPI_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(tpi_fabricate(NULL, 0.05, TPI_SIDE_OUTSIDE, 0, 6.0, 4.0, 0.03, &none),
                 TPI_STATUS_NULL_POINTER);
    CHECK_STATUS(tpi_fabrication_counts(NULL, &panels, &sheets), TPI_STATUS_NULL_POINTER);
    CHECK(none == NULL);

    tpi_fabrication_free(f);
    tpi_fabrication_free(NULL);
    tpi_discretisation_free(d);
    tpi_pattern_free(pattern);
    tpi_surface_free(surface);
}

int main(void) {
    test_fabrication();
    return finish("test_fabrication");
}
