/* SPDX-License-Identifier: GPL-3.0-or-later */
/* model_rigid.h - the right-hand sides of the bare and frame models
 * (physics.md, scenes 1 and 2), inline.  The models' ops call them for GSL
 * and the event layer; the fixed-step schemes call them per stage directly,
 * with the input evaluated once per distinct stage time, because at one
 * step per 1 kHz sample a function pointer, a model switch and two input
 * evaluations per stage were a third of the cost of a rocking step.
 *
 * y = (theta, theta') bare, (u, theta, u', theta') frame; theta > 0 when
 * the top tips forward (side s = +1); A1 = alpha - s theta.  Gravity is
 * g_eff = g + a_z in every gravity term; p^2 = kR g with kR = 3/(4R). */
#ifndef SWAYWATCH_MODEL_RIGID_H
#define SWAYWATCH_MODEL_RIGID_H

#include <math.h>

#include "model_ops.h"
#include "numeric.h"

/* sin and cos of A1 for a right-hand side.  Successive evaluations (the
 * stages of a step, the next steps, the state report) see nearby angles,
 * so they come from the last angle computed by libm, trig = (angle, sin,
 * cos), through the addition formulas with the series of sin and cos of
 * the small difference d (|d| <= 1/64 rad: the first term left out is below
 * 1e-21); libm only when the angle has moved further.  This halves the cost
 * of an RK4 step; the result differs from libm's by an ulp or two.
 * Returns 1 if the cached angle served (trig[0] = NAN: never). */
static inline int sw_rigid_sincos_near(const double trig[3], double A, double *sn, double *cs)
{
    const double d = A - trig[0];
    if (!(fabs(d) <= 0.015625)) {
        *sn = sin(A);
        *cs = cos(A);
        return 0;
    }
    const double d2 = d * d;
    const double sd = d * (1.0 + d2 * (-1.0 / 6.0 + d2 * (1.0 / 120.0 + d2 * (-1.0 / 5040.0))));
    const double cd =
        1.0 + d2 * (-0.5 + d2 * (1.0 / 24.0 + d2 * (-1.0 / 720.0 + d2 * (1.0 / 40320.0))));
    *sn = trig[1] * cd + trig[2] * sd;
    *cs = trig[2] * cd - trig[1] * sd;
    return 1;
}

/* The same, moving the scratch's cache to A when libm was called. */
static inline void sw_rigid_sincos(sw_model_scratch_t *S, double A, double *sn, double *cs)
{
    if (sw_rigid_sincos_near(S->trig, A, sn, cs))
        return;
    S->trig[0] = A;
    S->trig[1] = *sn;
    S->trig[2] = *cs;
}

/* Bearing force per unit total mass (m/s^2): 2 zeta_b w_b u' + w_b^2 u,
 * from u and u' (m, m/s). */
static inline double sw_rigid_bearing_of(const sw_model_t *M, double u, double du)
{
    const double w = M->d.omega_b;
    return 2.0 * M->d.zeta_b * w * du + w * w * u;
}

static inline double sw_rigid_bearing(const sw_model_t *M, const double y[])
{
    return sw_rigid_bearing_of(M, y[M->iu], y[M->idu]);
}

/* f = y' of a bare or framed package under a_g = ag and g_eff = ge (m/s^2),
 * given sn = sin(A1) and c1 = cos(A1) (not read unless rocking).  The
 * layouts are fixed (model.c's sw_model_setup): bare (theta, theta'),
 * frame (u, theta, u', theta'); a caller that passes model as a constant
 * gets one of the two bodies. */
static SW_ALWAYS_INLINE void sw_rigid_rhs_trig(const sw_model_t *M, sw_model_kind model, double ag,
                                               double ge, const double y[], double sn, double c1,
                                               double f[])
{
    const double s = M->side;
    /* A2 = s A1 exactly (s = +-1), so sin(A2) = s sin(A1): one angle. */
    const double s2 = s * sn;
    if (model == SW_MODEL_BARE) {
        f[0] = y[1];
        f[1] = M->phase == SW_PHASE_ROCKING ? -M->kR * (ge * s2 + ag * c1) : 0.0;
        return;
    }
    const double dth = y[3];
    const double F = sw_rigid_bearing_of(M, y[0], y[2]);
    f[0] = y[2];
    f[1] = dth;
    if (M->phase == SW_PHASE_ROCKING) {
        const double gR = M->d.gamma * M->d.R;
        const double iD = 1.0 / (1.0 - 0.75 * M->d.gamma * c1 * c1);
        const double kg = M->kR * ge, gdd = gR * dth * dth;
        f[2] = (-F + s2 * (gR * kg * c1 - gdd)) * iD - ag;
        f[3] = M->kR * (c1 * (F + gdd * s2) - ge * s2) * iD;
    } else {
        f[2] = -F - ag;
        f[3] = 0.0;
    }
}

/* The same, taking sin and cos of A1 = alpha - s theta from the cache. */
static SW_ALWAYS_INLINE void sw_rigid_rhs_of(const sw_model_t *M, sw_model_scratch_t *S,
                                             sw_model_kind model, double ag, double ge,
                                             const double y[], double f[])
{
    double sn = 0.0, c1 = 0.0;
    if (M->phase == SW_PHASE_ROCKING)
        sw_rigid_sincos(S, M->d.alpha - M->side * y[model == SW_MODEL_BARE ? 0 : 1], &sn, &c1);
    sw_rigid_rhs_trig(M, model, ag, ge, y, sn, c1, f);
}

/* While stuck the support's acceleration A is a_g (bare) or a_g + u'' =
 * -(2 zeta_b w_b u' + w_b^2 u) (frame); it does not depend on theta.
 * +1 / -1 if A is beyond the uplift threshold tan(alpha) g_eff, for the
 * input's g_eff = ge (m/s^2) there (the direction the top tips), else 0.
 * The caller evaluates the input (stuck.c, the ops' uplift_side). */
static inline int sw_rigid_side_of(const sw_model_t *M, double A, double ge)
{
    if (!(ge > 0.0))
        return 0; /* airborne: outside the model (the engine faults) */
    const double thr = M->tan_alpha * ge;
    if (A <= -thr)
        return +1; /* braking tips the top forward */
    if (A >= thr)
        return -1;
    return 0;
}

/* ... the bare block's under a_g = ag, the frame's at state y, g_eff = ge
 * (m/s^2). */
static inline int sw_bare_uplift_side(const sw_model_t *M, double ag, double ge)
{
    return sw_rigid_side_of(M, ag, ge);
}

static inline int sw_frame_uplift_side(const sw_model_t *M, double ge, const double y[])
{
    return sw_rigid_side_of(M, -sw_rigid_bearing(M, y), ge);
}

#endif
