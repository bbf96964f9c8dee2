/* SPDX-License-Identifier: GPL-3.0-or-later */
/* stuck.h - exact solutions of a package standing on its support
 * (stuck.c), as its model stands (ops->stands), and the exact step of a
 * damped oscillator under linear input they use.  Internal. */
#ifndef SWAYWATCH_STUCK_H
#define SWAYWATCH_STUCK_H

#include "input.h"

typedef struct sw_pkg sw_pkg_t;

/* What a stuck package's exact advance did (stuck.c). */
enum {
    SW_STUCK_STEP = -1, /* not handled: step the package with the scheme */
    SW_STUCK_STILL = 0, /* stuck up to the end of the interval */
    SW_STUCK_MOVED = 1, /* the package's time moved on: look again */
    SW_STUCK_LIFT = 2,  /* lifted at the package's time, direction *side */
    SW_STUCK_FAULT = 3  /* the exact advance made no progress: a fault, never a hang */
};

/* Advance a stuck package from P->t toward t1 exactly (X: the input at
 * the interval's ends, which the engine evaluated there), one way per how
 * its model
 * stands (indexed by ops->stands; SW_STANDS_RIGID, the bare block: its
 * uplift time solved for on the linear input, or the pulse scanned at the
 * package's step and the crossing bisected; SW_STANDS_OSCILLATOR, the
 * frame: its linear oscillator in closed form under sampled input where
 * exact is set (the scheme allows it), else SW_STUCK_STEP).  A table, as
 * an ops member was: the engine calls it on every sample of a package at
 * rest.  On SW_STUCK_LIFT, *side is the direction. */
typedef int (*sw_stuck_fn)(sw_pkg_t *P, const sw_input_ends_t *X, double t1, int exact, int *side);
extern const sw_stuck_fn sw_stuck_advance[]; /* SW_STANDS_KINDS rows */

/* The exact step of the damped oscillator u'' + 2 zeta w u' + w^2 u = -a(t),
 * a = a0 + s t, over H (s) from (u, u') = u0 into u1 (Nigam & Jennings, as
 * a stuck frame takes it): for the linear response of other models. */
void sw_nj_step(double w, double zeta, double H, double a0, double s, const double u0[2],
                double u1[2]);

#endif
