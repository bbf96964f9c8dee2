/* SPDX-License-Identifier: GPL-3.0-or-later */
/* reserve_lift.h - the lift bound of a package stuck on its frame, for the
 * reserve (reserve_lift.c).  Internal. */
#ifndef SWAYWATCH_RESERVE_LIFT_H
#define SWAYWATCH_RESERVE_LIFT_H

#include <stddef.h>

#include "swaywatch/model.h"

/* The stuck frame's linear response to a half-sine of duration T, sampled
 * every h seconds: support acceleration per unit pulse amplitude (A_u, 1),
 * and per unit initial displacement and velocity (A_1 in 1/s^2, A_2 in
 * 1/s), with the states at the table's end. */
typedef struct {
    double T; /* s */
    size_t n; /* samples; 0 = no table (the bearings too stiff to sample) */
    double h; /* s */
    double *Au, *A1, *A2;
    double end_u[2], end_1[2], end_2[2]; /* (u, u') at the end: m, m/s per unit */
} sw_lift_table_t;

/* The table of a frame scene (d) for pulse duration T (s): SW_OK (n may be
 * 0), or SW_ENOMEM. */
int sw_lift_table_make(sw_lift_table_t *t, const sw_derived_t *d, double T);
void sw_lift_table_free(sw_lift_table_t *t); /* NULL accepted */

/* The lowest amplitude (g) of a pulse in direction dir (-1 braking, +1
 * speeding up) that can lift the package off the stuck frame in state s
 * under gravity g (m/s^2), less the sampling's slack; 0 if none is known. */
double sw_lift_table_bound(const sw_lift_table_t *t, const sw_derived_t *d, double g,
                           const sw_state_t *s, int dir);

#endif
