/* SPDX-License-Identifier: GPL-3.0-or-later */
/* step.h - the step layer (GSL's step and evolve): a package's stepper,
 * the scheme's work space bound to the package's model, and one step of
 * it with the engine's scheme, or a re-step inside the step being
 * examined for the event layer.  It knows the model only as a system to
 * step (model_ops.h) and the scheme only by its row (scheme_ops.h).
 * Internal. */
#ifndef SWAYWATCH_STEP_H
#define SWAYWATCH_STEP_H

#include <gsl/gsl_odeiv2.h>

#include "model_ops.h"
#include "scheme_ops.h"

/* What the step and event layers of one engine share: its scheme and the
 * options they read.  Owned by the engine, embedded in it. */
struct sw_step_ctx {
    const sw_scheme_t *scheme;
    int dt_forced;    /* a forced dt is refused, never sub-stepped */
    int outcome_only; /* peaks and tips are not timed (sw_engine_opts_t) */
    double hmax;      /* s, longest step (SW_ACCURACY_HMAX under the accuracy option,
                         else INFINITY) */
};

/* The scheme's work space for one package (step.c), as GSL's step,
 * control and evolve objects are theirs: bound to the package's model. */
struct sw_stepper {
    sw_model_sys_t ms;     /* the model it steps and its scratch (GSL's params); first:
                              a re-step reaches its stepper from it */
    double h;              /* s, largest internal step for this package */
    double stab_rate;      /* omega_max h at the edge of the scheme's stability region
                              for the modes at rest (INFINITY: adaptive, or no mode) */
    sw_advance_fn advance; /* the scheme's advance for this model */
    sw_fixed_step_fn step; /* fixed-step schemes: the body for this model */
    /* the solution at t0 + h inside the step being examined, from its
     * start (t0, y0): the fixed schemes' body, GSL's step, or a multistep
     * scheme's interpolant (the scheme's row, bound here once);
     * W->restep(&W->ms, t0, h, y0, y1) */
    sw_fixed_step_fn restep;
    const double *step_y1; /* end of the step being examined (the engine's) */
    double step_h;         /* s, its length */
    gsl_odeiv2_system sys;
    gsl_odeiv2_step *gstep; /* adaptive schemes only */
    gsl_odeiv2_control *gctl;
    gsl_odeiv2_evolve *gevo;
    double h_adapt;         /* s, GSL's proposed next step */
    int restart;            /* the state was mapped: GSL's history is forgotten before
                               its next step (sw_step_restart) */
    gsl_odeiv2_driver gdrv; /* not allocated: hands gctl to GSL's implicit steppers */
};

/* The adaptive schemes' rows (GSL's evolve and step), and the re-step of
 * a multistep scheme on the interpolant of the step being examined; ms
 * is the stepper's (&W->ms) */
int sw_step_evolve(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, const double y0[], double t1,
                   double y1[], double *h);
int sw_restep_gsl(sw_model_sys_t *ms, double t0, double h, const double y0[], double y1[]);
int sw_restep_hermite(sw_model_sys_t *ms, double t0, double h, const double y0[], double y1[]);

/* Set up the scheme's work space for P (after the model's set-up).
 * Returns SW_OK, SW_EUNSTABLE (forced dt above the stability bound; msg
 * says why) or SW_ENOMEM. */
int sw_step_init(const sw_step_ctx_t *C, sw_stepper_t *W, const sw_model_t *M,
                 sw_model_scratch_t *S, const char *name, double dt, double rtol, double atol,
                 char *msg, size_t msglen);
/* Point the package's GSL system (and an implicit stepper's driver) at P:
 * after sw_step_init, and again after the package is moved in memory. */
void sw_step_bind(sw_stepper_t *W, const sw_model_t *M, sw_model_scratch_t *S);
void sw_step_free(sw_stepper_t *W);
void sw_step_reset(sw_stepper_t *W); /* forget the scheme's history (after a map) */
/* The same, done when the scheme next steps (sw_step_evolve): the engine
 * marks its stepper after a cut's map, and the step layer, which owns
 * the history, forgets it before it uses it again. */
static inline void sw_step_restart(sw_stepper_t *W)
{
    W->restart = 1;
}
void sw_step_forget(sw_stepper_t *W); /* restart the error control's count (after a fault) */
/* The input over [t0, t1], u0 and u1 at its ends (the engine's values),
 * makes a fixed step unstable for P? */
int sw_step_input_unstable(const sw_step_ctx_t *C, const sw_stepper_t *W, const sw_input_at_t *u0,
                           const sw_input_at_t *u1);
#endif
