/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scheme.c - the table of time-stepping schemes, looked up by name like
 * GSL's step types.  Fixed-step explicit Runge-Kutta schemes are our own
 * (GSL's rk4 does step doubling, 11 evaluations a step), their bodies
 * written once in fixed_rk.h, instantiated here generic and by the models
 * that inline their right-hand side (model_rigid.c); the adaptive
 * schemes are GSL odeiv2 steppers driven by the engine with error control.
 * The implicit ones (rk4imp, bsimp, msbdf) are offered for stiff cushions
 * (docs/cushion.md measures them against rkck, the default there); they
 * need the Jacobian (GSL does not check: without one they crash), which
 * the model takes by forward differences (sw_model_jacobian).  The fixed
 * steps' advance (sub-steps aligned to samples) is here, and their
 * re-step is their body (the model's or the generic one, bound by the
 * stepper); GSL's are the step layer's (step.c).
 *
 * stab is the scheme's stability bound |lambda h| on the negative real axis
 * (Euler and Heun 2, RK4 2.785), the bound of the input's stiffness of the
 * rocking equation (sw_step_input_unstable); region, the degree of its
 * stability function, against which every step is checked
 * (stability.c). */
#include <math.h>
#include <string.h>

#include "fixed_rk.h"
#include "numeric.h"
#include "scheme_ops.h"
#include "step.h"
#include "swaywatch/status.h"

/* The fixed-step schemes' bodies are written once (fixed_rk.h); a model
 * that instantiates them with its right-hand side inlined per stage (the
 * bare and frame models, model_rigid.c; the cushion, model_cushion.c) has
 * its own, and the generic ones here serve any model added without them:
 * the
 * model's right-hand side through its ops table, once per stage.  The
 * package picks its body once, when it is built (step.c): no dispatch per
 * step or per stage. */
static SW_ALWAYS_INLINE void generic_stage(const sw_model_t *M, sw_model_scratch_t *S,
                                           const sw_input_at_t *u, const double y[], double f[])
{
    M->ops->rhs(M, S, u, y, f);
}
SW_FIXED_RK(generic, M->n, generic_stage)

/* One fixed step from (t0, y0) into y1, no longer than the package's
 * step h nor than what is left of the interval, splitting that into equal
 * steps: its length (s). */
static inline double fixed_h(double rem, double hmax)
{
    if (rem <= hmax)
        return rem; /* the common case: a step per sample */
    const double nst = ceil(rem / hmax - 1e-9);
    return nst <= 1.0 ? rem : rem / nst;
}

/* A model that tracks its contact rate can pass through states far
 * stiffer than rest (a cushion landing on a corner or flat, a cubic
 * cushion compressed hard) where a step that is stable at rest blows up
 * or skips the landing: its right-hand side reports the fastest contact
 * rate its stages met, and the step is retaken shorter until that rate
 * times h is within the bound the package's h keeps at rest (0.5, or the
 * scheme's stability bound for a forced dt).  Where the model's proven
 * bound of every rate it can meet (M->rate_cap) is within it already,
 * the step is taken untracked: tracking would accept it. */
static SW_NOINLINE int fixed_tracked(const sw_step_ctx_t *C, sw_stepper_t *W, double t0,
                                     const double y0[], double t1, double y1[], double *hout)
{
    const sw_model_t *M = W->ms.m;
    sw_model_scratch_t *S = W->ms.s;
    const double rem = t1 - t0;
    double hmax = W->h; /* s */
    for (int tries = 0;; tries++) {
        const double h = fixed_h(rem, hmax); /* s */
        const double lim = C->dt_forced ? C->scheme->stab : 0.5;
        const double bound = lim < W->stab_rate ? lim : W->stab_rate;
        *hout = h;
        if (M->rate_cap * h <= bound) {
            W->step(&W->ms, t0, h, y0, y1);
            return SW_OK;
        }
        S->rate_seen = 0.0;
        S->track_rate = 1;
        W->step(&W->ms, t0, h, y0, y1);
        S->track_rate = 0;
        if (S->rate_seen * h <= bound * (1.0 + 1e-9) || tries >= 60)
            return SW_OK;
        hmax = fmin(0.5 * h, bound / S->rate_seen);
    }
}

/* The fixed schemes' advance: the package's body (W->step) over the step,
 * one call into the model for a model with its own bodies; the fixed
 * schemes' re-step is the body from (t0, y0), which the stepper calls
 * itself (W->restep). */
static int fixed_step(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, const double y0[],
                      double t1, double y1[], double *hout)
{
    const sw_model_t *M = W->ms.m;
    if (M->ops->tracks_rate)
        return fixed_tracked(C, W, t0, y0, t1, y1, hout);
    const double h = fixed_h(t1 - t0, W->h); /* s */
    *hout = h;
    return W->step(&W->ms, t0, h, y0, y1); /* a jump: the body is the step's cost */
}

/* One row per scheme: adding a scheme is adding a row.  stab: see the top
 * of this file.  gsl_odeiv2_step_* are variables, not constants: the rows
 * store their addresses. */
#define FIXED(kind, body)                                                              \
    .advance = fixed_step, .rk = SW_RK_##kind, .step = generic_##body, .cut_kinks = 1, \
    .exact_stuck = 1
#define ADAPTIVE(type) .adaptive = 1, .advance = sw_step_evolve, .gsl_type = &type
static const sw_scheme_t schemes[] = {
    {.name = "rk4", .order = 4, .stab = 2.785, .region = 4, .default_dt = 1e-3, FIXED(RK4, rk4)},
    {.name = "heun", .order = 2, .stab = 2.0, .region = 2, .default_dt = 2.5e-4, FIXED(HEUN, heun)},
    {.name = "euler",
     .order = 1,
     .stab = 2.0,
     .region = 1,
     .default_dt = 1e-5,
     FIXED(EULER, euler)},
    {.name = "rkf45",
     .order = 5,
     .default_dt = 1e-3,
     ADAPTIVE(gsl_odeiv2_step_rkf45),
     .restep = sw_restep_gsl},
    {.name = "rkck",
     .order = 5,
     .default_dt = 1e-3,
     ADAPTIVE(gsl_odeiv2_step_rkck),
     .restep = sw_restep_gsl},
    {.name = "rk8pd",
     .order = 8,
     .default_dt = 1e-3,
     ADAPTIVE(gsl_odeiv2_step_rk8pd),
     .restep = sw_restep_gsl},
    /* implicit Gauss RK (step doubling for the error), Bader-Deuflhard
     * semi-implicit extrapolation, variable-order BDF; order as GSL reports
     * it (the highest for bsimp and msbdf, which vary it); msbdf, a
     * multistep method, is re-stepped on the Hermite interpolant */
    {.name = "rk4imp",
     .order = 4,
     .default_dt = 1e-3,
     ADAPTIVE(gsl_odeiv2_step_rk4imp),
     .restep = sw_restep_gsl,
     .implicit = 1},
    {.name = "bsimp",
     .order = 12,
     .default_dt = 1e-3,
     ADAPTIVE(gsl_odeiv2_step_bsimp),
     .restep = sw_restep_gsl,
     .implicit = 1},
    {.name = "msbdf",
     .order = 5,
     .default_dt = 1e-3,
     ADAPTIVE(gsl_odeiv2_step_msbdf),
     .restep = sw_restep_hermite,
     .implicit = 1},
};

const sw_scheme_t *sw_scheme_at(size_t i)
{
    return i < sizeof schemes / sizeof schemes[0] ? &schemes[i] : NULL;
}

const sw_scheme_t *sw_scheme_lookup(const char *name)
{
    for (size_t i = 0; i < sizeof schemes / sizeof schemes[0]; i++)
        if (name && !strcmp(name, schemes[i].name))
            return &schemes[i];
    return NULL;
}

const char *sw_scheme_name(const sw_scheme_t *s)
{
    return s->name;
}

int sw_scheme_order(const sw_scheme_t *s)
{
    return s->order;
}

int sw_scheme_adaptive(const sw_scheme_t *s)
{
    return s->adaptive;
}

int sw_scheme_implicit(const sw_scheme_t *s)
{
    return s->implicit;
}

double sw_scheme_default_dt(const sw_scheme_t *s)
{
    return s->default_dt;
}
