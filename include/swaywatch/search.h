/* SPDX-License-Identifier: GPL-3.0-or-later */
/* search.h - the lowest value that overturns a package: a scan upward in
 * small relative steps, then bisection of the first change from safe to
 * overturning, over a caller's trial function.
 *
 * Overturning is not monotonic in the amplitude (a full-sine pulse that is
 * larger can be survived: the package is thrown back before it falls), so
 * the search scans before it bisects, and reports the lowest overturning
 * value it found and, on request, the safe islands above it.  A window of
 * overturning narrower than one scan step can be missed; the step is an
 * option. */
#ifndef SWAYWATCH_SEARCH_H
#define SWAYWATCH_SEARCH_H

#include "export.h"
#include "run.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One trial: does x overturn?  Fill r; return SW_OK or a negative code,
 * which ends the search. */
typedef int (*sw_trial_fn)(void *user, double x, sw_run_result_t *r);

typedef struct {
    double x_min, x_max; /* scan range; both > 0, x_min < x_max */
    double step;         /* relative scan step, x_{k+1} = x_k (1 + step); 0 = 0.02 */
    double tol;          /* relative width of the final brackets; 0 = 1e-3 */
    int islands;         /* non-zero: go on scanning above the lowest overturn and map the
                            safe islands up to x_max */
} sw_search_opts_t;

#define SW_MAX_ISLANDS 16

/* Amplitudes x with lo < x < hi were found safe (the ends are bracketed to
 * tol: lo overturns just below, hi just above); open: safe up to x_max. */
typedef struct {
    double lo, hi;
    int open;
} sw_island_t;

typedef struct {
    int found;            /* some x in [x_min, x_max] overturned */
    int at_min;           /* x_min itself overturned: the threshold may be lower */
    double x;             /* lowest overturning x found: the upper end of the final
                             bracket, a value that was run and overturned */
    double x_safe;        /* the lower end of that bracket: run and safe (0 if at_min) */
    sw_run_result_t at_x; /* the run at x */
    int n_islands;
    int islands_truncated; /* more than SW_MAX_ISLANDS islands */
    sw_island_t islands[SW_MAX_ISLANDS];
    long trials; /* runs made */
} sw_threshold_t;

/* Scan x_min, x_min (1 + step), ... up to x_max (the last point clipped to
 * x_max) until a trial overturns, then bisect the last safe / first
 * overturning pair to tol.  Returns SW_OK (found or not), SW_EINVAL for bad
 * options, or the first error of a trial. */
SW_API int sw_threshold_search(sw_trial_fn f, void *user, const sw_search_opts_t *o,
                               sw_threshold_t *out);

#ifdef __cplusplus
}
#endif
#endif
