/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fixed_rk.h - the fixed-step explicit Runge-Kutta schemes' bodies
 * (Euler, Heun, RK4) written once, as a template a file instantiates
 * with its own stage: a model that has its right-hand side at hand
 * (model_rigid.c) gets bodies with it inlined into every stage, the sin
 * and cos cache and the right-hand side staying the model file's own, and
 * the scheme reaches the model once per step; scheme.c instantiates the
 * generic bodies (the model's ops->rhs per stage) for the others.  The
 * input is evaluated once per distinct stage time and handed to the stage
 * (input.h).  A leaf: macros only.  Internal. */
#ifndef SWAYWATCH_FIXED_RK_H
#define SWAYWATCH_FIXED_RK_H

#include "input.h"
#include "model_ops.h"
#include "swaywatch/status.h"

/* Defines prefix_euler, prefix_heun and prefix_rk4, the sw_fixed_step_fn
 * of each scheme: one step of length h (s) from (t, y) into yout (SW_OK) of the
 * system ms_ (its model M and scratch S), for a state of n components, where stage(M, S, &u, y, f)
 * writes f = y' at y under the input's value u.  (Macros, not inline functions, so that the bodies
 * are the instantiating file's.) */
#define SW_FIXED_RK(prefix, n, stage)                                                    \
    static int prefix##_euler(sw_model_sys_t *ms_, double t, double h, const double y[], \
                              double yout[])                                             \
    {                                                                                    \
        const sw_model_t *M = ms_->m;                                                    \
        sw_model_scratch_t *S = ms_->s;                                                  \
        const int n_ = (n);                                                              \
        double k1[SW_NMAX];                                                              \
        const sw_input_at_t u = sw_input_at(M->in, M->g, t);                             \
        stage(M, S, &u, y, k1);                                                          \
        for (int i = 0; i < n_; i++) yout[i] = y[i] + h * k1[i];                         \
        return SW_OK;                                                                    \
    }                                                                                    \
    static int prefix##_heun(sw_model_sys_t *ms_, double t, double h, const double y[],  \
                             double yout[])                                              \
    {                                                                                    \
        const sw_model_t *M = ms_->m;                                                    \
        sw_model_scratch_t *S = ms_->s;                                                  \
        const int n_ = (n);                                                              \
        double k1[SW_NMAX], k2[SW_NMAX], yt[SW_NMAX];                                    \
        sw_input_at_t u = sw_input_at(M->in, M->g, t);                                   \
        stage(M, S, &u, y, k1);                                                          \
        for (int i = 0; i < n_; i++) yt[i] = y[i] + h * k1[i];                           \
        u = sw_input_at(M->in, M->g, t + h);                                             \
        stage(M, S, &u, yt, k2);                                                         \
        for (int i = 0; i < n_; i++) yout[i] = y[i] + 0.5 * h * (k1[i] + k2[i]);         \
        return SW_OK;                                                                    \
    }                                                                                    \
    static int prefix##_rk4(sw_model_sys_t *ms_, double t, double h, const double y[],   \
                            double yout[])                                               \
    {                                                                                    \
        const sw_model_t *M = ms_->m;                                                    \
        sw_model_scratch_t *S = ms_->s;                                                  \
        const int n_ = (n);                                                              \
        double k1[SW_NMAX], k2[SW_NMAX], k3[SW_NMAX], k4[SW_NMAX], yt[SW_NMAX];          \
        const double h2 = 0.5 * h;                                                       \
        sw_input_at_t u = sw_input_at(M->in, M->g, t);                                   \
        stage(M, S, &u, y, k1);                                                          \
        for (int i = 0; i < n_; i++) yt[i] = y[i] + h2 * k1[i];                          \
        u = sw_input_at(M->in, M->g, t + h2);                                            \
        stage(M, S, &u, yt, k2);                                                         \
        for (int i = 0; i < n_; i++) yt[i] = y[i] + h2 * k2[i];                          \
        stage(M, S, &u, yt, k3);                                                         \
        for (int i = 0; i < n_; i++) yt[i] = y[i] + h * k3[i];                           \
        u = sw_input_at(M->in, M->g, t + h);                                             \
        stage(M, S, &u, yt, k4);                                                         \
        for (int i = 0; i < n_; i++)                                                     \
            yout[i] = y[i] + (h / 6.0) * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);    \
        return SW_OK;                                                                    \
    }

/* The bodies of SW_FIXED_RK(prefix, ...) as a row of sw_fixed_step_fn
 * indexed by SW_RK_* (a model's ops->fixed). */
#define SW_FIXED_RK_ROW(prefix)                                                                  \
    {                                                                                            \
        [SW_RK_EULER] = prefix##_euler, [SW_RK_HEUN] = prefix##_heun, [SW_RK_RK4] = prefix##_rk4 \
    }

#endif
