/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scheme.c - the table of time-stepping schemes, looked up by name like
 * GSL's step types.  Fixed-step explicit Runge-Kutta schemes are written out
 * here (GSL's rk4 does step doubling, 11 evaluations a step); the adaptive
 * schemes are GSL odeiv2 steppers driven by the engine with error control.
 * The implicit ones (rk4imp, bsimp, msbdf) are offered for stiff cushions
 * (docs/cushion.md measures them against rkck, the default there); they
 * need the Jacobian (GSL does not check: without one they crash), which
 * the model takes by forward differences (sw_model_jacobian).  The fixed
 * steps' advance (sub-steps aligned to samples) and re-step are here with
 * their bodies; GSL's are the step layer's (step.c).
 *
 * stab is the scheme's stability bound |lambda h| on the negative real axis
 * (Euler and Heun 2, RK4 2.785), the bound of the input's stiffness of the
 * rocking equation (sw_step_input_unstable); region, the degree of its
 * stability function, against which every step is checked
 * (stability.c). */
#include <math.h>
#include <string.h>

#include "model_rigid.h"
#include "numeric.h"
#include "scheme_ops.h"
#include "step.h"
#include "swaywatch/status.h"

/* The fixed-step schemes are written once, as inline bodies taking the
 * model and the state's length; the step functions in the table call them
 * with constants, so that the bare and frame models each get a body with
 * their right-hand side inlined into every stage (the cushion's is a
 * call).  The input is evaluated once per distinct stage time and handed
 * to the right-hand side (input.h). */

/* The bodies below are specialised for a model kind, or generic: the
 * model's right-hand side through its ops table, once per stage. */
#define GENERIC (-1)

/* One stage: f = y'(y) under the input u at the stage's time (evaluated
 * once per distinct stage time): the bare and framed packages'
 * right-hand side inlined, a generic body's through the ops. */
static SW_ALWAYS_INLINE void stage(const sw_model_t *M, sw_model_scratch_t *S, int model,
                                   const sw_input_at_t *u, const double y[], double f[])
{
    if (model == GENERIC)
        M->ops->rhs(M, S, u, y, f);
    else
        sw_rigid_rhs_of(M, S, (sw_model_kind)model, u->ag, u->ge, y, f);
}

static SW_ALWAYS_INLINE void euler_of(const sw_model_t *M, sw_model_scratch_t *S, int model, int n,
                                      double t, double h, const double y[], double yout[])
{
    double k1[SW_NMAX];
    const sw_input_at_t u = sw_input_at(M->in, M->g, t);
    stage(M, S, model, &u, y, k1);
    for (int i = 0; i < n; i++) yout[i] = y[i] + h * k1[i];
}

static SW_ALWAYS_INLINE void heun_of(const sw_model_t *M, sw_model_scratch_t *S, int model, int n,
                                     double t, double h, const double y[], double yout[])
{
    double k1[SW_NMAX], k2[SW_NMAX], yt[SW_NMAX];
    sw_input_at_t u = sw_input_at(M->in, M->g, t);
    stage(M, S, model, &u, y, k1);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h * k1[i];
    u = sw_input_at(M->in, M->g, t + h);
    stage(M, S, model, &u, yt, k2);
    for (int i = 0; i < n; i++) yout[i] = y[i] + 0.5 * h * (k1[i] + k2[i]);
}

static SW_ALWAYS_INLINE void rk4_of(const sw_model_t *M, sw_model_scratch_t *S, int model, int n,
                                    double t, double h, const double y[], double yout[])
{
    double k1[SW_NMAX], k2[SW_NMAX], k3[SW_NMAX], k4[SW_NMAX], yt[SW_NMAX];
    const double h2 = 0.5 * h;
    sw_input_at_t u = sw_input_at(M->in, M->g, t);
    stage(M, S, model, &u, y, k1);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h2 * k1[i];
    u = sw_input_at(M->in, M->g, t + h2);
    stage(M, S, model, &u, yt, k2);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h2 * k2[i];
    stage(M, S, model, &u, yt, k3);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h * k3[i];
    u = sw_input_at(M->in, M->g, t + h);
    stage(M, S, model, &u, yt, k4);
    for (int i = 0; i < n; i++)
        yout[i] = y[i] + (h / 6.0) * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

/* The bodies of a scheme: the bare and frame models with their right-hand
 * side inlined per stage, and the generic one (the cushion; any model
 * added without a body of its own).  The package picks its body once, when
 * it is built: no dispatch per step or per stage. */
#define SW_FIXED_STEPS(name, body)                                                             \
    static void name##_bare(const sw_model_t *M, sw_model_scratch_t *S, double t, double h,    \
                            const double y[], double yout[])                                   \
    {                                                                                          \
        body(M, S, SW_MODEL_BARE, 2, t, h, y, yout);                                           \
    }                                                                                          \
    static void name##_frame(const sw_model_t *M, sw_model_scratch_t *S, double t, double h,   \
                             const double y[], double yout[])                                  \
    {                                                                                          \
        body(M, S, SW_MODEL_FRAME, 4, t, h, y, yout);                                          \
    }                                                                                          \
    static void name##_generic(const sw_model_t *M, sw_model_scratch_t *S, double t, double h, \
                               const double y[], double yout[])                                \
    {                                                                                          \
        body(M, S, GENERIC, M->n, t, h, y, yout);                                              \
    }
/* One fixed step from (t0, y0) into y1, no longer than the package's
 * step h nor than what is left of the interval, splitting that into equal
 * steps; body is the scheme's step for the model.  A model that tracks its
 * contact rate (track: it may) can pass through states far stiffer than
 * rest (a cushion landing on a corner or flat, a cubic cushion compressed
 * hard) where a step that is stable at rest blows up or skips the
 * landing: its right-hand side reports the fastest contact rate its
 * stages met, and the step is retaken shorter until that rate times h is
 * within the bound the package's h keeps at rest (0.5, or the scheme's
 * stability bound for a forced dt).  A template, instantiated per scheme
 * and model with the body known, so that a step is one call. */
static SW_ALWAYS_INLINE int fixed_with(const sw_step_ctx_t *C, sw_stepper_t *W, double t0,
                                       const double y0[], double t1, double y1[], double *hout,
                                       sw_fixed_step_fn body, int track)
{
    const sw_model_t *M = W->ms.m;
    sw_model_scratch_t *S = W->ms.s;
    const double rem = t1 - t0;
    double hmax = W->h, h = rem; /* s */
    for (int tries = 0;; tries++) {
        if (rem <= hmax) {
            h = rem; /* the common case: a step per sample */
        } else {
            const double nst = ceil(rem / hmax - 1e-9);
            h = nst <= 1.0 ? rem : rem / nst;
        }
        if (!track || !M->ops->tracks_rate) {
            body(M, S, t0, h, y0, y1);
            break;
        }
        const double lim = C->dt_forced ? C->scheme->stab : 0.5;
        const double bound = lim < W->stab_rate ? lim : W->stab_rate;
        if (M->rate_cap * h <= bound) {
            /* every rate the model can meet is stable at h: the step
             * that tracking would accept, without tracking */
            body(M, S, t0, h, y0, y1);
            break;
        }
        S->rate_seen = 0.0;
        S->track_rate = 1;
        body(M, S, t0, h, y0, y1);
        S->track_rate = 0;
        if (S->rate_seen * h <= bound * (1.0 + 1e-9) || tries >= 60)
            break;
        hmax = fmin(0.5 * h, bound / S->rate_seen);
    }
    *hout = h;
    return SW_OK;
}

/* ... and the advance of each, the sub-step logic around the body. */
#define SW_FIXED_ADVANCES(name)                                                       \
    static int name##_adv_bare(const sw_step_ctx_t *C, sw_stepper_t *W, double t0,    \
                               const double y0[], double t1, double y1[], double *h)  \
    {                                                                                 \
        return fixed_with(C, W, t0, y0, t1, y1, h, name##_bare, 0);                   \
    }                                                                                 \
    static int name##_adv_frame(const sw_step_ctx_t *C, sw_stepper_t *W, double t0,   \
                                const double y0[], double t1, double y1[], double *h) \
    {                                                                                 \
        return fixed_with(C, W, t0, y0, t1, y1, h, name##_frame, 0);                  \
    }
SW_FIXED_STEPS(euler_step, euler_of)
SW_FIXED_STEPS(heun_step, heun_of)
SW_FIXED_STEPS(rk4_step, rk4_of)
SW_FIXED_ADVANCES(euler_step)
SW_FIXED_ADVANCES(heun_step)
SW_FIXED_ADVANCES(rk4_step)

/* The generic fixed advance (the package's body, its rate tracked if its
 * model asks), and the fixed schemes' re-step: the body from (t0, y0). */
static int fixed_step(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, const double y0[],
                      double t1, double y1[], double *hout)
{
    return fixed_with(C, W, t0, y0, t1, y1, hout, W->step, 1);
}

static int fixed_restep(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, double h,
                        const double y0[], double y1[])
{
    (void)C;
    W->step(W->ms.m, W->ms.s, t0, h, y0, y1);
    return SW_OK;
}

/* One row per scheme: adding a scheme is adding a row.  stab: see the top
 * of this file.  gsl_odeiv2_step_* are variables, not constants: the rows
 * store their addresses. */
#define FIXED(body)                                                                          \
    .advance = fixed_step, .restep = fixed_restep,                                           \
    .advance_for = {[SW_MODEL_BARE] = body##_adv_bare, [SW_MODEL_FRAME] = body##_adv_frame}, \
    .step_for = {[SW_MODEL_BARE] = body##_bare, [SW_MODEL_FRAME] = body##_frame},            \
    .step = body##_generic, .cut_kinks = 1, .exact_stuck = 1
#define ADAPTIVE(type) .adaptive = 1, .advance = sw_step_evolve, .gsl_type = &type
static const sw_scheme_t schemes[] = {
    {.name = "rk4", .order = 4, .stab = 2.785, .region = 4, .default_dt = 1e-3, FIXED(rk4_step)},
    {.name = "heun", .order = 2, .stab = 2.0, .region = 2, .default_dt = 2.5e-4, FIXED(heun_step)},
    {.name = "euler", .order = 1, .stab = 2.0, .region = 1, .default_dt = 1e-5, FIXED(euler_step)},
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
