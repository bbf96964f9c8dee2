/* SPDX-License-Identifier: GPL-3.0-or-later */
/* search_int.h - the resumable threshold search (search.c) as a machine
 * the caller drives: sw_search_points() gives a round's values, the
 * caller runs them (on any threads, in any order) and sw_search_feed()
 * takes their results.  A round's points do not depend on who ran them,
 * so neither does any result.  Internal: the safety factors (safety.c)
 * and the reserve (reserve.c) run their searches this way, and
 * sw_threshold_search() (search.h, the boundary curves) drives one to
 * its threshold before it maps the safe islands above.
 *
 * One algorithm: a scan upward from x_min in relative steps until a point
 * overturns, then the bracket from the last safe point to it cut into
 * per_round + 1 geometric pieces a round, keeping the lowest change from
 * safe to overturning, until it is tol wide.  Its options
 * (sw_search_how_t) say how many points a round takes and whether the
 * scan's step may grow; sw_search_probe() tries a value of the caller's
 * above the scan's points (the reserve's other scans at the bracket
 * another one found).  The zero options are the safety factors' search:
 * SW_SEARCH_SECTIONS points a round, the step growing where the package
 * stays far from tipping; the reserve and sw_threshold_search() take one
 * point a round on a fixed grid, a bisection. */
#ifndef SWAYWATCH_SEARCH_INT_H
#define SWAYWATCH_SEARCH_INT_H

#include "swaywatch/run.h"
#include "swaywatch/search.h"

#define SW_SEARCH_SECTIONS 4 /* trials per round of a search, at most */
/* peak |theta| / alpha from which the scan takes its finest step (the safety
 * factors' trials that set the step know it, safety_prep.h) */
#define SW_SEARCH_NEAR_PEAK 0.25

enum { SW_SEARCH_SCAN, SW_SEARCH_SECT, SW_SEARCH_DONE, SW_SEARCH_PROBE };

/* How a search picks its points.  Zero: the safety factors' search. */
typedef struct {
    int per_round;  /* points a round, 1 .. SW_SEARCH_SECTIONS (0: SW_SEARCH_SECTIONS); with 1
                       a bracket is cut at sqrt(lo hi): a geometric bisection */
    int fixed_step; /* the scan's k-th point is x_min (1 + step)^k, clipped to x_max, whatever
                       the runs' peaks (else the step grows far from tipping) */
    double safe;    /* known safe up to here below x_min (a proven bound), or 0: the
                       bracket's safe end when x_min itself overturns */
} sw_search_how_t;

/* One resumable search: where it is between rounds. */
typedef struct {
    sw_search_opts_t o; /* resolved: step, tol set */
    sw_search_how_t how;
    int phase;
    long k;           /* scan: points run so far */
    double x_last;    /* scan: the last point run (safe) */
    double peak_last; /* its largest |theta| / alpha */
    double lo, hi;    /* lo: no point up to it overturned (how.safe, then each safe point
                         run, in increasing order); bracket: hi overturns */
    sw_run_result_t r_hi;
    double x[SW_SEARCH_SECTIONS];
    sw_run_result_t r[SW_SEARCH_SECTIONS];
    int n; /* points of the current round */
    sw_threshold_t *out;
} sw_search_t;

/* Start a search over o's range into out (zeroed), the safety factors'
 * way.  Returns SW_OK, or SW_EINVAL for a bad range (the search is then
 * done). */
int sw_search_init(sw_search_t *S, const sw_search_opts_t *o, sw_threshold_t *out);

/* The same, picking its points as how says (NULL: as sw_search_init). */
int sw_search_init_how(sw_search_t *S, const sw_search_opts_t *o, const sw_search_how_t *how,
                       sw_threshold_t *out);

/* The values of the next round into S->x (S->n of them, returned; 0 when
 * the search is done).  Calling it again without a feed gives the same
 * round. */
int sw_search_points(sw_search_t *S);

/* The round's results, S->r[0 .. S->n), are in: the search moves on. */
void sw_search_feed(sw_search_t *S);

/* The next round is x alone, instead of the scan's next points (x at or
 * above every point run; a search still scanning): if x overturns, the
 * bracket below it is cut as any; if not, the search ends with lo = x and
 * nothing found. */
void sw_search_probe(sw_search_t *S, double x);

#endif
