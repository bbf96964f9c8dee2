/* SPDX-License-Identifier: GPL-3.0-or-later */
/* step.c - the step layer (GSL's step/evolve): a package's stepper, set up
 * for the engine's scheme (its step inside the scheme's stability region,
 * GSL's work space), and the adaptive schemes' step and re-steps: GSL
 * odeiv2 steppers under its error control, and a multistep scheme's
 * re-step on the interpolant.  The fixed-step schemes' advance is
 * scheme.c's, beside their bodies, and their re-step is the body itself;
 * the stepper binds the row's advance and re-step (or the body) once.
 * Nothing here knows which model it steps. */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "hermite.h"
#include "input.h"
#include "model_ops.h"
#include "step.h"
#include "swaywatch/status.h"

/* A fixed step inside the scheme's stability region for every mode of the
 * scene about rest (sw_model_modes, sw_scheme_stable_dt): a forced dt
 * outside it is refused, naming a stable dt or the default scheme; an
 * unforced one is shortened to 0.9 of the region's edge (the engine's
 * sw_engine_dt_requested and sw_engine_dt then differ, which the commands
 * say).  No stable step at all (an undamped mode under euler) is
 * refused either way.  W->stab_rate gets omega_max times the stable step,
 * the bound of a tracked contact rate times h (scheme.c's fixed steps): at
 * rest the two agree, and a stiffer contact shortens the step in
 * proportion. */
static int stable_step(const sw_step_ctx_t *C, sw_stepper_t *W, const sw_model_t *M,
                       const char *name, double dt, char *msg, size_t msglen)
{
    const sw_scheme_t *S = C->scheme;
    sw_mode_t m[SW_MODES_MAX];
    const int n = sw_model_modes(&M->d, M->g, m);
    int w = -1;
    const double hs = sw_scheme_stable_dt(S, m, n, &w); /* s */
    /* in the units of a tracked contact rate, omega_max at rest */
    if (M->d.omega_max > 0.0 && hs < INFINITY)
        W->stab_rate = hs * M->d.omega_max;
    if (w < 0 || !(C->dt_forced ? dt > hs : hs == 0.0))
        goto ok;
    if (msg && msglen && hs > 0.0) {
        const double amp = sw_scheme_amplification(S, m[w].re * dt, m[w].im * dt);
        char a[32];
        if (amp < 1.001)
            snprintf(a, sizeof a, "1 + %.2g", amp - 1.0);
        else
            snprintf(a, sizeof a, "%.4g", amp);
        snprintf(msg, msglen,
                 "scene '%s': dt = %g s is above the %s stability bound for its %s (omega = "
                 "%.4g rad/s, zeta = %.3g: |R(lambda dt)| = %s > 1): use dt <= %.3g s, or the "
                 "default scheme %s",
                 name, dt, S->name, m[w].name, m[w].omega, m[w].zeta, a, hs, SW_DEFAULT_SCHEME);
    } else if (msg && msglen) {
        snprintf(msg, msglen,
                 "scene '%s': %s is unstable for its %s (omega = %.4g rad/s, zeta = %.3g) at "
                 "every step: use the default scheme %s or an adaptive one",
                 name, S->name, m[w].name, m[w].omega, m[w].zeta, SW_DEFAULT_SCHEME);
    }
    return SW_EUNSTABLE;
ok:
    if (!C->dt_forced && W->h > 0.9 * hs)
        W->h = 0.9 * hs;
    return SW_OK;
}

int sw_step_init(const sw_step_ctx_t *C, sw_stepper_t *W, const sw_model_t *M,
                 sw_model_scratch_t *S, const char *name, double dt, double rtol, double atol,
                 char *msg, size_t msglen)
{
    const sw_scheme_t *R = C->scheme;
    W->h = fmin(dt, C->hmax);
    W->stab_rate = INFINITY;
    if (R->region > 0) {
        const int r = stable_step(C, W, M, name, dt, msg, msglen);
        if (r != SW_OK)
            return r;
    }
    if (R->stab > 0.0 && M->d.omega_max > 0.0) {
        const double bound = R->stab / M->d.omega_max; /* s */
        if (C->dt_forced && dt > bound) {
            if (msg && msglen)
                snprintf(msg, msglen,
                         "scene '%s': dt = %g s gives omega*dt = %.3g, above the %s stability "
                         "bound %.3g for the scene's fastest frequency omega = %.4g rad/s "
                         "(use dt <= %.3g s)",
                         name, dt, M->d.omega_max * dt, R->name, R->stab, M->d.omega_max, bound);
            return SW_EUNSTABLE;
        }
        /* Sub-step so that omega_max h <= 0.5: inside every explicit
         * scheme's stability bound, and accurate enough for the fast
         * bearing mode that decides uplift. */
        if (!C->dt_forced && W->h > 0.5 / M->d.omega_max)
            W->h = 0.5 / M->d.omega_max;
    }
    /* a fixed step's event layer asks again for the states the step
     * evaluated (its first stage); an adaptive GSL step's stages are
     * never asked twice */
    S->memo_on = !R->adaptive;
    W->step = R->rk && M->ops->fixed[R->rk] ? M->ops->fixed[R->rk] : R->step;
    W->restep = R->restep ? R->restep : W->step;
    W->advance = R->advance;
    W->sys.function = sw_model_rhs;
    W->sys.jacobian = R->implicit ? sw_model_jacobian : NULL;
    W->sys.dimension = (size_t)M->n;
    W->ms = (sw_model_sys_t){M, S};
    W->sys.params = &W->ms;
    if (!R->gsl_type)
        return SW_OK;
    rtol = rtol > 0.0 ? rtol : 1e-10;
    atol = atol > 0.0 ? atol : 1e-12;
    if (M->iz >= 0) {
        /* resolve the contact: an absolute tolerance above the static
         * deflection (m) or the lift angle z_s/b (rad) of a very stiff
         * cushion would leave it to noise */
        const double zs = M->yscale[M->iz];
        atol = fmin(atol, 1e-3 * fmin(zs, zs / M->d.b));
    }
    W->gstep = gsl_odeiv2_step_alloc(*R->gsl_type, (size_t)M->n);
    W->gctl = gsl_odeiv2_control_y_new(atol, rtol);
    W->gevo = gsl_odeiv2_evolve_alloc((size_t)M->n);
    if (!W->gstep || !W->gctl || !W->gevo) {
        if (msg && msglen)
            snprintf(msg, msglen, "out of memory");
        return SW_ENOMEM;
    }
    sw_step_bind(W, M, S);
    return SW_OK;
}

void sw_step_bind(sw_stepper_t *W, const sw_model_t *M, sw_model_scratch_t *S)
{
    W->ms = (sw_model_sys_t){M, S};
    W->sys.params = &W->ms;
    if (!W->gstep || !W->sys.jacobian)
        return;
    /* GSL's implicit steppers read their Newton tolerances from the
     * control through a driver (without one they fail with GSL_EFAULT):
     * hand them one that only points at ours */
    W->gdrv = (gsl_odeiv2_driver){
        .sys = &W->sys, .s = W->gstep, .c = W->gctl, .e = W->gevo, .h = W->h, .hmax = DBL_MAX};
    gsl_odeiv2_step_set_driver(W->gstep, &W->gdrv);
}

void sw_step_free(sw_stepper_t *W)
{
    if (W->gevo)
        gsl_odeiv2_evolve_free(W->gevo);
    if (W->gctl)
        gsl_odeiv2_control_free(W->gctl);
    if (W->gstep)
        gsl_odeiv2_step_free(W->gstep);
    W->gevo = NULL;
    W->gctl = NULL;
    W->gstep = NULL;
}

void sw_step_reset(sw_stepper_t *W)
{
    W->restart = 0;
    if (!W->gevo)
        return;
    gsl_odeiv2_evolve_reset(W->gevo);
    gsl_odeiv2_step_reset(W->gstep);
}

void sw_step_forget(sw_stepper_t *W)
{
    if (W->gevo)
        gsl_odeiv2_evolve_reset(W->gevo);
}

/* The input sets the stiffness of the rocking equation: theta'' is of the
 * order kR |a| theta for an acceleration a (bed or gravity), a rate of
 * sqrt(kR |a|).  A fixed step beyond the scheme's stability bound for that
 * rate computes garbage, not a motion (states of 1e260 that still look
 * finite): a fault, not an integration.  Checked at the ends of the
 * interval, where the sampled input is largest: the engine evaluated it
 * there and hands the values down. */
int sw_step_input_unstable(const sw_step_ctx_t *C, const sw_stepper_t *W, const sw_input_at_t *u0,
                           const sw_input_at_t *u1)
{
    const double stab = C->scheme->stab;
    if (!(stab > 0.0))
        return 0; /* GSL shortens its steps itself */
    const sw_model_t *M = W->ms.m;
    const double ag0 = fabs(u0->ag), ag1 = fabs(u1->ag), ge0 = fabs(u0->ge), ge1 = fabs(u1->ge);
    const double ag = ag0 > ag1 ? ag0 : ag1, ge = ge0 > ge1 ? ge0 : ge1; /* m/s^2 */
    const double a = ag > ge ? ag : ge;
    return !(M->kR * a * W->h * W->h <= stab * stab); /* NaN: unstable */
}

/* One step of GSL's evolve under its error control, toward t1. */
int sw_step_evolve(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, const double y0[], double t1,
                   double y1[], double *h)
{
    const double span = t1 - t0, rem = span < C->hmax ? span : C->hmax; /* s */
    double tt = t0;
    if (W->restart)
        sw_step_reset(W);
    memcpy(y1, y0, sizeof(double) * (size_t)W->ms.m->n);
    if (W->h_adapt > rem)
        W->h_adapt = rem;
    const int st =
        gsl_odeiv2_evolve_apply(W->gevo, W->gctl, W->gstep, &W->sys, &tt, t1, &W->h_adapt, y1);
    if (st != GSL_SUCCESS || !(tt > t0))
        return SW_EGSL;
    *h = tt - t0;
    return SW_OK;
}

/* The stepper of a re-step's system: ms is its first member. */
static sw_stepper_t *stepper_of(sw_model_sys_t *ms)
{
    return (sw_stepper_t *)(void *)((char *)ms - offsetof(sw_stepper_t, ms));
}

int sw_restep_gsl(sw_model_sys_t *ms, double t0, double h, const double y0[], double y1[])
{
    sw_stepper_t *W = stepper_of(ms);
    double yerr[SW_NMAX];
    memcpy(y1, y0, sizeof(double) * (size_t)W->ms.m->n);
    return gsl_odeiv2_step_apply(W->gstep, t0, h, y1, yerr, NULL, NULL, &W->sys) == GSL_SUCCESS
               ? SW_OK
               : SW_EGSL;
}

/* A multistep method cannot restart from the step's start without losing
 * its history: interpolate the step being examined (cubic Hermite, O(h^4))
 * instead of re-stepping. */
int sw_restep_hermite(sw_model_sys_t *ms, double t0, double h, const double y0[], double y1[])
{
    const sw_stepper_t *W = stepper_of(ms);
    double f0[SW_NMAX], f1[SW_NMAX];
    const sw_model_t *M = W->ms.m;
    const sw_input_at_t u0 = sw_input_at(M->in, M->g, t0),
                        u1 = sw_input_at(M->in, M->g, t0 + W->step_h);
    M->ops->rhs(M, W->ms.s, &u0, y0, f0);
    M->ops->rhs(M, W->ms.s, &u1, W->step_y1, f1);
    sw_herm_state(W->ms.m->n, W->step_h, y0, f0, W->step_y1, f1, h / W->step_h, y1);
    return SW_OK;
}
