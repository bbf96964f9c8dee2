/* SPDX-License-Identifier: GPL-3.0-or-later */
/* search_int.h - the resumable threshold search (search.c) as a machine
 * the caller drives: sw_search_points() gives a round's values, the
 * caller runs them (on any threads, in any order) and sw_search_feed()
 * takes their results.  A round's points do not depend on who ran them,
 * so neither does any result.  Internal: the safety factors (safety.c)
 * run their searches this way; sw_threshold_search() (search.h) is the
 * blocking search.
 *
 * The scan takes SW_SEARCH_SECTIONS points of its grid at a time, with a
 * step that grows where the package stays far from tipping, and a bracket
 * is cut into SW_SEARCH_SECTIONS + 1 pieces, keeping the lowest change
 * from safe to overturning. */
#ifndef SWAYWATCH_SEARCH_INT_H
#define SWAYWATCH_SEARCH_INT_H

#include "swaywatch/run.h"
#include "swaywatch/search.h"

#define SW_SEARCH_SECTIONS 4 /* trials per round of a search */
/* peak |theta| / alpha from which the scan takes its finest step (the safety
 * factors' trials that set the step know it, safety_prep.h) */
#define SW_SEARCH_NEAR_PEAK 0.25

enum { SW_SEARCH_SCAN, SW_SEARCH_SECT, SW_SEARCH_DONE };

/* One resumable search: where it is between rounds. */
typedef struct {
    sw_search_opts_t o; /* resolved: step, tol set */
    int phase;
    long k;           /* scan: points run so far */
    double x_last;    /* scan: the last point run (safe) */
    double peak_last; /* its largest |theta| / alpha */
    double lo, hi;    /* bracket: lo safe, hi overturns */
    sw_run_result_t r_hi;
    double x[SW_SEARCH_SECTIONS];
    sw_run_result_t r[SW_SEARCH_SECTIONS];
    int n; /* points of the current round */
    sw_threshold_t *out;
} sw_search_t;

/* Start a search over o's range into out (zeroed).  Returns SW_OK, or
 * SW_EINVAL for a bad range (the search is then done). */
int sw_search_init(sw_search_t *S, const sw_search_opts_t *o, sw_threshold_t *out);

/* The values of the next round into S->x (S->n of them, returned; 0 when
 * the search is done). */
int sw_search_points(sw_search_t *S);

/* The round's results, S->r[0 .. S->n), are in: the search moves on. */
void sw_search_feed(sw_search_t *S);

#endif
