/* SPDX-License-Identifier: GPL-3.0-or-later */
/* event.h - the event layer (CVODE's root finding; GSL has none): the
 * events inside a step, from the model's candidates, found on the step's
 * interpolant and polished by re-stepping (event.c).  It hands back the
 * earliest cut, polished, and the timed events before it; the phase
 * machine (pkg.h) does what follows from them.  Internal. */
#ifndef SWAYWATCH_EVENT_H
#define SWAYWATCH_EVENT_H

#include "model_ops.h"
#include "step.h"

/* An event inside a step, handed back as CVODE's rootsfound are, with
 * the input's value where it lies (the layer that found the time owns
 * it): the package's phase machine reports it (sw_pkg_timed, and
 * sw_pkg_stepped for the cut). */
typedef struct {
    int role;          /* SW_ROLE_PEAK, SW_ROLE_TIP, SW_ROLE_LIFT, or SW_ROLE_CUT */
    double t;          /* s */
    double y[SW_NMAX]; /* the state at t */
    sw_input_at_t u;   /* the input at t */
} sw_timed_t;

/* The earliest cutting event among the model's candidates c[0..nc) inside
 * the step (t0, y0) -> (t0 + h, y1) (SW_EVF_NONE if none; X: the input at
 * the ends of the interval the engine advances over, as it evaluated
 * them, taken at a step's end that is one of these), polished by
 * re-stepping: its time, the state and the input there in *cut; the
 * timed events before it in timed[0..*ntimed), in the order of the
 * candidates (timed has room for nc), as CVODE hands back its root and
 * rootsfound. */
int sw_event_locate(sw_stepper_t *W, const sw_input_ends_t *X, double t0, double h,
                    const double y0[], const double y1[], const sw_evcand_t c[], int nc,
                    sw_timed_t *cut, sw_timed_t timed[], int *ntimed);
/* Keep the candidates that end a step (the dynamics), drop those that only
 * time a peak, a tip or a cushion's lift (the report); the count left. */
int sw_event_keep_outcome(sw_evcand_t c[], int nc);
/* The same, asking the model for its candidates first: inline, because
 * most steps have none and the question is then all the work. */
static inline int sw_event_find(const sw_step_ctx_t *C, sw_stepper_t *W, const sw_input_ends_t *X,
                                double t0, double h, const double y0[], const double y1[],
                                sw_timed_t *cut, sw_timed_t timed[SW_MAX_CANDS], int *ntimed)
{
    sw_evcand_t c[SW_MAX_CANDS];
    const sw_model_t *M = W->ms.m;
    int nc = M->ops->candidates(M, C->scheme->cut_kinks, h, y0, y1, c);
    if (nc && C->outcome_only)
        nc = sw_event_keep_outcome(c, nc);
    *ntimed = 0;
    return nc ? sw_event_locate(W, X, t0, h, y0, y1, c, nc, cut, timed, ntimed) : SW_EVF_NONE;
}
/* Polish the time of event ev found at tau (a fraction of the step) by
 * re-stepping: its time, the state and the input there in *at. */
void sw_event_polish(sw_stepper_t *W, int ev, double t0, double h, const double y0[], double tau,
                     sw_timed_t *at);

#endif
