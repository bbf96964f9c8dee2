/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scheme_ops.h - a scheme's row (struct sw_scheme), what the step layer
 * reads of the scheme it steps with: its order and stability, its advance
 * and re-step, its fixed-step bodies per model, its GSL stepper.  The
 * rows are scheme.c's table; their stability regions stability.c's.
 * Internal. */
#ifndef SWAYWATCH_SCHEME_OPS_H
#define SWAYWATCH_SCHEME_OPS_H

#include <gsl/gsl_odeiv2.h>

#include "model_ops.h"
#include "swaywatch/scheme.h"

typedef struct sw_step_ctx sw_step_ctx_t;
typedef struct sw_stepper sw_stepper_t;

/* One fixed step of length h (s) from (t, y) into yout. */
typedef void (*sw_fixed_step_fn)(const sw_model_t *M, sw_model_scratch_t *S, double t, double h,
                                 const double y[], double yout[]);

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
    /* one step toward t1 (step.c: fixed sub-steps, or GSL's evolve); for
     * the fixed schemes also one per model with its body inlined (NULL:
     * the generic one serves) */
    sw_advance_fn advance;
    sw_advance_fn advance_for[SW_MODEL_KINDS];
    /* the solution at t0 + h inside the step being examined (step.c:
     * re-step from its start, or the Hermite interpolant of a multistep
     * scheme, which cannot restart without losing its history) */
    int (*restep)(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, double h, const double y0[],
                  double y1[]);
    /* fixed steps: the body specialised for a model (the right-hand side
     * inlined per stage), or NULL for the generic body below */
    sw_fixed_step_fn step_for[SW_MODEL_KINDS];
    sw_fixed_step_fn step;                       /* the generic body (the model's rhs per stage) */
    const gsl_odeiv2_step_type *const *gsl_type; /* adaptive schemes */
    int implicit;    /* needs the Jacobian, and a driver for its Newton tolerances */
    int cut_kinks;   /* fixed steps lose their order across a kink of the
                        right-hand side: cut them there */
    int exact_stuck; /* a stuck frame may take its exact solution (the adaptive
                        schemes step it, under their own error control) */
};

#endif
