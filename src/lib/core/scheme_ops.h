/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scheme_ops.h - a scheme's row (struct sw_scheme), what the step layer
 * reads of the scheme it steps with: its order and stability, its advance
 * and re-step, its fixed-step body, its GSL stepper.  The
 * rows are scheme.c's table; their stability regions stability.c's.
 * Internal. */
#ifndef SWAYWATCH_SCHEME_OPS_H
#define SWAYWATCH_SCHEME_OPS_H

#include <gsl/gsl_odeiv2.h>

#include "model_ops.h"
#include "swaywatch/scheme.h"

typedef struct sw_step_ctx sw_step_ctx_t;
typedef struct sw_stepper sw_stepper_t;

/* One step from (t0, y0) toward t1 into y1; *h gets its length. */
typedef int (*sw_advance_fn)(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, const double y0[],
                             double t1, double y1[], double *h);

/* A scheme's behaviour.  The engine reads its row, never its name. */
struct sw_scheme {
    const char *name;
    int order;
    int adaptive;      /* GSL's error control chooses the steps */
    double stab;       /* |lambda h| bound on the negative real axis (fixed steps; 0:
                          none to check, the error control keeps it) */
    int region;        /* fixed steps: the stability function R(z) is the Taylor
                          polynomial of e^z of this degree (an explicit Runge-Kutta
                          scheme with as many stages as its order, up to 4); its
                          stability region is |R(z)| <= 1.  0: adaptive */
    double default_dt; /* s */
    /* one step toward t1 (scheme.c: fixed sub-steps, or step.c: GSL's
     * evolve) */
    sw_advance_fn advance;
    /* the solution at t0 + h inside the step being examined (step.c:
     * re-step from its start, or the Hermite interpolant of a multistep
     * scheme, which cannot restart without losing its history) */
    sw_fixed_step_fn restep; /* NULL for the fixed steps: their body is their
                                re-step (the stepper binds it, sw_step_init) */
    /* fixed steps: which body (SW_RK_*, fixed_rk.h), the model's own
     * instantiation of it if it has one (ops->fixed), else this generic
     * one (the model's rhs per stage) */
    int rk;
    sw_fixed_step_fn step;
    const gsl_odeiv2_step_type *const *gsl_type; /* adaptive schemes */
    int implicit;    /* needs the Jacobian, and a driver for its Newton tolerances */
    int cut_kinks;   /* fixed steps lose their order across a kink of the
                        right-hand side: cut them there */
    int exact_stuck; /* a stuck frame may take its exact solution (the adaptive
                        schemes step it, under their own error control) */
};

#endif
