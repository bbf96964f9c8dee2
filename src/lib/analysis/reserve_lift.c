/* SPDX-License-Identifier: GPL-3.0-or-later */
/* reserve_lift.c - the lift bound of the reserve (reserve_lift.h): a
 * package stuck on its frame cannot overturn before it lifts, and until
 * then the frame is a linear oscillator, so the lowest pulse amplitude
 * that can lift it is read off the frame's linear response to the pulse
 * and to its present state, tabulated once per design pulse.
 * test_reserve.c (test_lift_bound_tight) finds by brute force that
 * nothing below the bound lifts and that 1 % above it does. */
#include "reserve_lift.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/reserve.h"
#include "swaywatch/status.h"

#define LIFT_SAMPLES 400.0     /* samples per shortest period of the frame's lift table */
#define LIFT_RINGING 2.0       /* bearing periods sampled after the pulse */
#define LIFT_MAX_SAMPLES 50000 /* larger tables (very stiff bearings): no lift bound */
#define LIFT_SLACK 0.995       /* sampled peaks are within 3e-5 of the true ones */

/* The stuck frame's support acceleration A = -(2 zeta w u' + w^2 u), and
 * its linear response tables (sw_lift_table_t), by RK4 at LIFT_SAMPLES
 * steps per shortest period (error ~1e-10 relative). */
static void frame_deriv(const sw_derived_t *d, double a, const double y[2], double f[2])
{
    const double w = d->omega_b, z = d->zeta_b;
    f[0] = y[1];
    f[1] = -2.0 * z * w * y[1] - w * w * y[0] - a;
}

static double frame_accel(const sw_derived_t *d, const double y[2])
{
    const double w = d->omega_b, z = d->zeta_b;
    return -(2.0 * z * w * y[1] + w * w * y[0]);
}

static void frame_rk4(const sw_derived_t *d, double T, double t, double h, double y[2], int forced)
{
    double k1[2], k2[2], k3[2], k4[2], yt[2];
    const double w = M_PI / T;
#define IN(tt) (forced && (tt) <= T ? sin(w * (tt)) : 0.0)
    frame_deriv(d, IN(t), y, k1);
    for (int i = 0; i < 2; i++) yt[i] = y[i] + 0.5 * h * k1[i];
    frame_deriv(d, IN(t + 0.5 * h), yt, k2);
    for (int i = 0; i < 2; i++) yt[i] = y[i] + 0.5 * h * k2[i];
    frame_deriv(d, IN(t + 0.5 * h), yt, k3);
    for (int i = 0; i < 2; i++) yt[i] = y[i] + h * k3[i];
    frame_deriv(d, IN(t + h), yt, k4);
#undef IN
    for (int i = 0; i < 2; i++) y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

int sw_lift_table_make(sw_lift_table_t *P, const sw_derived_t *d, double T)
{
    memset(P, 0, sizeof *P);
    P->T = T;
    const double Tb = 2.0 * M_PI / d->omega_b; /* s, bearing period */
    const double span = P->T + LIFT_RINGING * Tb;
    const double h = fmin(Tb, 2.0 * P->T) / LIFT_SAMPLES;
    const double nd = ceil(span / h) + 1.0;
    if (nd > LIFT_MAX_SAMPLES)
        return SW_OK; /* no table: the energy bound alone */
    P->n = (size_t)nd;
    P->h = span / (double)(P->n - 1);
    P->Au = malloc(3 * P->n * sizeof *P->Au);
    if (!P->Au)
        return SW_ENOMEM;
    P->A1 = P->Au + P->n;
    P->A2 = P->A1 + P->n;
    double yu[2] = {0.0, 0.0}, y1[2] = {1.0, 0.0}, y2[2] = {0.0, 1.0};
    for (size_t k = 0; k < P->n; k++) {
        const double t = (double)k * P->h;
        P->Au[k] = frame_accel(d, yu);
        P->A1[k] = frame_accel(d, y1);
        P->A2[k] = frame_accel(d, y2);
        if (k + 1 == P->n)
            break;
        frame_rk4(d, P->T, t, P->h, yu, 1);
        frame_rk4(d, P->T, t, P->h, y1, 0);
        frame_rk4(d, P->T, t, P->h, y2, 0);
    }
    memcpy(P->end_u, yu, sizeof yu);
    memcpy(P->end_1, y1, sizeof y1);
    memcpy(P->end_2, y2, sizeof y2);
    return SW_OK;
}

/* The lowest amplitude (g) of a pulse in direction dir that can lift the
 * package off the stuck frame in state s, or 0 if none is known.  On the
 * samples: |x U(t) + F(t)| >= L, with U the pulse's and F the initial
 * state's share of the support acceleration.  After them, with no input,
 * the bearing's energy e = (u'^2 + w^2 u^2)/2 can only fall and
 * |A| <= w sqrt(1 + 4 zeta^2) sqrt(2 e), which bounds every later peak. */
double sw_lift_table_bound(const sw_lift_table_t *P, const sw_derived_t *d, double g,
                           const sw_state_t *s, int dir)
{
    if (!P->n)
        return 0.0;
    const double L = g * tan(d->alpha); /* m/s^2 */
    const double k = dir * SW_G0;       /* m/s^2 per g */
    double x = INFINITY;
    for (size_t i = 0; i < P->n; i++) {
        const double U = k * P->Au[i];
        const double F = s->u * P->A1[i] + s->u_dot * P->A2[i];
        if (fabs(F) >= L)
            return 0.0;
        if (U != 0.0) {
            const double need = (L - (U > 0.0 ? F : -F)) / fabs(U);
            if (need < x)
                x = need;
        }
    }
    /* the ringing after the table */
    const double w = d->omega_b;
    const double Lp = L / (w * sqrt(1.0 + 4.0 * d->zeta_b * d->zeta_b));
    const double a0 = k * P->end_u[0] * w, a1 = k * P->end_u[1];
    const double b0 = (s->u * P->end_1[0] + s->u_dot * P->end_2[0]) * w;
    const double b1 = s->u * P->end_1[1] + s->u_dot * P->end_2[1];
    const double aa = a0 * a0 + a1 * a1, ab = a0 * b0 + a1 * b1, bb = b0 * b0 + b1 * b1;
    if (bb >= Lp * Lp)
        return 0.0;
    if (aa > 0.0) {
        const double xt = (-ab + sqrt(ab * ab - aa * (bb - Lp * Lp))) / aa;
        if (xt < x)
            x = xt;
    }
    return isfinite(x) ? LIFT_SLACK * x : 0.0;
}

void sw_lift_table_free(sw_lift_table_t *P)
{
    if (P) {
        free(P->Au);
        P->Au = P->A1 = P->A2 = NULL;
        P->n = 0;
    }
}
