/* Minimal check macros for the C tests of the tpi C ABI: count, report, never abort. */
#ifndef TPI_TEST_CHECK_H
#define TPI_TEST_CHECK_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tpi.h"

static int checks_run;
static int checks_failed;

static inline void report_failure(const char *file, int line, const char *what) {
    char message[1024];
    message[0] = '\0';
    tpi_last_error_message(message, sizeof message, NULL);
    checks_failed++;
    fprintf(stderr, "%s:%d: FAILED: %s (last error: \"%s\")\n", file, line, what, message);
}

#define CHECK(cond)                                                                                \
    do {                                                                                           \
        checks_run++;                                                                              \
        if (!(cond)) report_failure(__FILE__, __LINE__, #cond);                                    \
    } while (0)

/* Checks that `call` returns `expected`; prints both names otherwise. */
#define CHECK_STATUS(call, expected)                                                               \
    do {                                                                                           \
        TpiStatus got_ = (call);                                                                   \
        checks_run++;                                                                              \
        if (got_ != (expected)) {                                                                  \
            char what_[512];                                                                       \
            snprintf(what_, sizeof what_, "%s returned %s, expected %s", #call,                   \
                     tpi_status_name((uint32_t)got_), tpi_status_name((uint32_t)(expected)));      \
            report_failure(__FILE__, __LINE__, what_);                                             \
        }                                                                                          \
    } while (0)

#define CHECK_OK(call) CHECK_STATUS(call, TPI_STATUS_OK)

/* |a - b| <= tol * max(1, |a|, |b|) */
static inline int close_to(double a, double b, double tol) {
    double scale = fmax(1.0, fmax(fabs(a), fabs(b)));
    return fabs(a - b) <= tol * scale;
}

#define CHECK_CLOSE(a, b, tol)                                                                     \
    do {                                                                                           \
        double a_ = (a), b_ = (b);                                                                 \
        checks_run++;                                                                              \
        if (!close_to(a_, b_, (tol))) {                                                            \
            char what_[512];                                                                       \
            snprintf(what_, sizeof what_, "%s = %.17g, expected %s = %.17g", #a, a_, #b, b_);      \
            report_failure(__FILE__, __LINE__, what_);                                             \
        }                                                                                          \
    } while (0)

/* The last error message contains `needle`. */
static inline int last_error_contains(const char *needle) {
    char message[1024];
    message[0] = '\0';
    if (tpi_last_error_message(message, sizeof message, NULL) != TPI_STATUS_OK) return 0;
    return strstr(message, needle) != NULL;
}

static inline int finish(const char *name) {
    printf("%s: %d checks, %d failed\n", name, checks_run, checks_failed);
    return checks_failed == 0 ? 0 : 1;
}

#endif /* TPI_TEST_CHECK_H */
