/* SPDX-License-Identifier: GPL-3.0-or-later */
/* model_rigid.h - what the exact solutions of a standing rigid package
 * (stuck.c) read of the bare and frame models (physics.md, scenes 1 and
 * 2): the frame's bearing force and the uplift test, inline.  Their
 * right-hand sides are model_rigid.c's own.
 *
 * y = (theta, theta') bare, (u, theta, u', theta') frame.  Gravity is
 * g_eff = g + a_z in every gravity term. */
#ifndef SWAYWATCH_MODEL_RIGID_H
#define SWAYWATCH_MODEL_RIGID_H

#include "model_ops.h"

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
