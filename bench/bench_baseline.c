/* SPDX-License-Identifier: GPL-3.0-or-later */
/* bench_baseline.c - the straightforward way to integrate the rocking
 * models, kept to measure what the engine's design buys: GSL's adaptive
 * driver (gsl_odeiv2_driver_apply, rkf45, reset at every sample because the
 * input has a kink there) from one sample to the next, in every phase, and
 * events found by looking at the state at the end of each sample interval,
 * then bisecting the event time by re-integrating from the interval's start.
 * The equations are those of physics.md, written again here so that the
 * baseline shares no code with the engine. */
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "bench.h"

typedef struct {
    sw_derived_t d;
    double g, kR, ta; /* m/s^2, 1/m, tan(alpha) */
    int frame, rocking, side;
    double t0, a0, slope; /* input over the current interval */
} bl_t;

static double bl_ag(const bl_t *B, double t)
{
    return B->a0 + B->slope * (t - B->t0);
}

static int bl_rhs(double t, const double y[], double f[], void *par)
{
    const bl_t *B = par;
    const double a = bl_ag(B, t), s = B->side;
    if (!B->frame) {
        f[0] = y[1];
        f[1] = B->rocking
                   ? -B->kR * (B->g * sin(s * B->d.alpha - y[0]) + a * cos(B->d.alpha - s * y[0]))
                   : 0.0;
        return GSL_SUCCESS;
    }
    const double w = B->d.omega_b, F = 2.0 * B->d.zeta_b * w * y[2] + w * w * y[0];
    f[0] = y[2];
    f[1] = y[3];
    if (!B->rocking) {
        f[2] = -F - a;
        f[3] = 0.0;
        return GSL_SUCCESS;
    }
    const double c1 = cos(B->d.alpha - s * y[1]), s2 = sin(s * B->d.alpha - y[1]);
    const double gR = B->d.gamma * B->d.R, D = 1.0 - 0.75 * B->d.gamma * c1 * c1;
    f[2] = (-F + gR * s2 * (B->kR * B->g * c1 - y[3] * y[3])) / D - a;
    f[3] = (B->kR * c1 * (F + gR * y[3] * y[3] * s2) - B->kR * B->g * s2) / D;
    return GSL_SUCCESS;
}

/* Support acceleration while stuck. */
static double bl_support(const bl_t *B, double t, const double y[])
{
    if (!B->frame)
        return bl_ag(B, t);
    const double w = B->d.omega_b;
    return -(2.0 * B->d.zeta_b * w * y[2] + w * w * y[0]);
}

/* 0 none, 1 impact, 2 overturn, 3 uplift forward, 4 uplift back */
static int bl_event(const bl_t *B, double t, const double y[])
{
    const int ith = B->frame ? 1 : 0;
    if (B->rocking) {
        if (B->side * y[ith] <= 0.0)
            return 1;
        if (B->side * y[ith] >= M_PI_2)
            return 2;
        return 0;
    }
    const double A = bl_support(B, t, y), thr = B->ta * B->g;
    return A <= -thr ? 3 : A >= thr ? 4 : 0;
}

int bench_baseline_run(const sw_scene_t *sc, const bench_log_t *log, double eps, sw_summary_t *s)
{
    bl_t B;
    memset(&B, 0, sizeof B);
    memset(s, 0, sizeof *s);
    if (sw_scene_validate(sc, &B.d, NULL, NULL, NULL) != SW_OK)
        return SW_EINVAL;
    if (B.d.model == SW_MODEL_CUSHION)
        return SW_EINVAL;
    B.frame = B.d.model == SW_MODEL_FRAME;
    B.g = sc->g;
    B.kR = 0.75 / B.d.R;
    B.ta = tan(B.d.alpha);
    B.side = 1;
    const size_t n = B.frame ? 4 : 2;
    const int ith = B.frame ? 1 : 0, idth = B.frame ? 3 : 1;
    gsl_odeiv2_system sys = {bl_rhs, NULL, n, &B};
    gsl_odeiv2_driver *drv =
        gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rkf45, 1e-4, eps * 1e-2, eps);
    if (!drv)
        return SW_ENOMEM;
    double y[4] = {0}, ys[4];
    int over = 0, rc = SW_OK;
    s->overturn_time = s->uplift_time = s->tip_time = NAN;
    for (size_t i = 0; i + 1 < log->n && !over && rc == SW_OK; i++) {
        const double ti = log->t[i], t1 = log->t[i + 1];
        B.t0 = ti;
        B.a0 = log->a[i];
        B.slope = (log->a[i + 1] - log->a[i]) / (t1 - ti);
        double t = ti;
        for (int guard = 0; t < t1 && guard < 1000; guard++) {
            const double tstart = t;
            memcpy(ys, y, sizeof ys);
            if (!B.frame && !B.rocking) {
                /* no dynamics: look at the input only */
                if (!bl_event(&B, t1, y))
                    break;
            } else {
                gsl_odeiv2_driver_reset(drv);
                if (gsl_odeiv2_driver_apply(drv, &t, t1, y) != GSL_SUCCESS) {
                    rc = SW_EGSL;
                    break;
                }
                s->steps++;
            }
            int ev = bl_event(&B, t1, y);
            if (!ev) {
                t = t1;
                break;
            }
            /* bisect the event time, re-integrating from tstart each time */
            double lo = tstart, hi = t1;
            for (int it = 0; it < 50; it++) {
                const double m = 0.5 * (lo + hi);
                double ym[4];
                memcpy(ym, ys, sizeof ym);
                double tm = tstart;
                if (B.frame || B.rocking) {
                    gsl_odeiv2_driver_reset(drv);
                    gsl_odeiv2_driver_apply(drv, &tm, m, ym);
                }
                if (bl_event(&B, m, ym))
                    hi = m;
                else
                    lo = m;
            }
            memcpy(y, ys, sizeof y);
            t = tstart;
            if (B.frame || B.rocking) {
                gsl_odeiv2_driver_reset(drv);
                gsl_odeiv2_driver_apply(drv, &t, hi, y);
            }
            t = hi;
            ev = bl_event(&B, t, y);
            if (ev == 2) {
                s->overturned = 1;
                s->overturn_time = t;
                s->max_abs_theta = M_PI_2;
                over = 1;
                break;
            }
            if (ev == 1) {
                const double r = B.frame ? B.d.r_frame : B.d.eta, before = y[idth];
                y[ith] = 0.0;
                y[idth] = r * before;
                if (B.frame)
                    y[2] += B.d.gamma * B.d.h * (before - y[idth]);
                B.side = -B.side;
                s->impacts++;
                if (0.5 * y[idth] * y[idth] / (B.d.p * B.d.p) < 1e-9 * (1.0 - cos(B.d.alpha))) {
                    y[idth] = 0.0;
                    B.rocking = 0;
                    const int up = bl_event(&B, t, y);
                    if (up) {
                        B.rocking = 1;
                        B.side = up == 3 ? 1 : -1;
                    } else {
                        s->rests++;
                    }
                }
            } else if (ev >= 3) {
                B.rocking = 1;
                B.side = ev == 3 ? 1 : -1;
                y[ith] = y[idth] = 0.0;
                s->uplifts++;
                if (isnan(s->uplift_time))
                    s->uplift_time = t;
            }
        }
        if (fabs(y[ith]) > s->max_abs_theta)
            s->max_abs_theta = fabs(y[ith]);
    }
    s->max_theta_ratio = s->max_abs_theta / B.d.alpha;
    gsl_odeiv2_driver_free(drv);
    return rc;
}
