/* SPDX-License-Identifier: GPL-3.0-or-later */
/* reserve_min.h - the smallest reserve over states taken along a run,
 * the most threatened first (reserve_log.c): what sw_reserve_log_min and
 * the minimum-only reserve of risk.c share.  Internal. */
#ifndef SWAYWATCH_RESERVE_MIN_H
#define SWAYWATCH_RESERVE_MIN_H

#include <stddef.h>

#include "swaywatch/reserve.h"

/* One state taken. */
typedef struct {
    double t;  /* s, log time */
    double lb; /* g: the proven lower bound of its reserve; the value at rest */
    int rest;  /* at rest: lb is its reserve */
    sw_state_t s;
} sw_rmin_state_t;

/* The search: the full evaluation (the caller's object) and an
 * evaluation capped just above the smallest reserve found so far, made
 * when that changes. */
typedef struct {
    sw_scene_t sc;
    sw_reserve_opts_t opts;
    sw_reserve_t *r;   /* the caller's */
    sw_reserve_t *cap; /* max_g = cap_g; NULL: none */
    double cap_g;      /* g */
} sw_rmin_t;

void sw_rmin_init(sw_rmin_t *m, const sw_scene_t *sc, const sw_reserve_opts_t *o, sw_reserve_t *r);
void sw_rmin_free(sw_rmin_t *m); /* the capped object; not r */

/* The n states v (reordered) evaluated in the order of their lower
 * bounds, smallest first, until none left can have a reserve smaller than
 * out->min_g (or as small and earlier), at most max_evals evaluations in
 * all (0: no limit).  out holds the smallest found so far on entry
 * (min_g INFINITY for none) and on return; its evaluated, faults and exact
 * are added to, lower_g set when the limit stopped the search.  SW_OK, or
 * an evaluation's error (not SW_EFAULT: counted). */
int sw_rmin_search(sw_rmin_t *m, sw_rmin_state_t *v, size_t n, long max_evals,
                   sw_reserve_log_t *out);

#endif
