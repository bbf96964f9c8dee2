/* SPDX-License-Identifier: GPL-3.0-or-later */
/* stability.c - the stability regions of the fixed-step schemes (scheme.h's
 * sw_scheme_amplification and sw_scheme_stable_dt).
 *
 * A scheme's row bounds |lambda h| on the negative real axis (stab), but
 * a lightly damped oscillation has its eigenvalues near the imaginary
 * axis, where the bound is not that: forward Euler is unstable there for
 * any h > 2 zeta / omega, Heun for roughly omega h > 2 zeta^(1/3), RK4 up
 * to 2.83.  So the step is checked against each scheme's stability region
 * |R(lambda h)| <= 1 (the row's region: R is the Taylor polynomial of e^z
 * of that degree), for every mode of the scene about rest
 * (sw_model_modes). */
#include <math.h>

#include "scheme_ops.h"

/* |R(z)|, R the Taylor polynomial of e^z of degree deg (Horner, complex). */
static double amplification(int deg, double re, double im)
{
    double fact = 1.0;
    for (int k = 2; k <= deg; k++) fact *= k;
    double pr = 1.0 / fact, pi = 0.0; /* the leading coefficient 1/deg! */
    for (int k = deg - 1; k >= 0; k--) {
        const double r = pr * re - pi * im, i = pr * im + pi * re;
        fact /= (k + 1);
        pr = r + 1.0 / fact;
        pi = i;
    }
    return hypot(pr, pi);
}

double sw_scheme_amplification(const sw_scheme_t *s, double re, double im)
{
    return s && s->region > 0 ? amplification(s->region, re, im) : NAN;
}

/* The region's edge on the ray of lambda: the largest r = |lambda| h such
 * that every step up to it is stable; 0 if even r = 1e-4 is not (an
 * undamped mode under Euler: no practical step exists).  A step counts as
 * stable when it makes the mode grow by less than 1e-6 per period of the
 * mode (|R| <= exp(1e-6 r / (2 pi))): rounding, and a marginal scheme no
 * run notices (Heun on an undamped mode up to r = 0.011: 0.3 % in 3400
 * periods, an hour at 6 rad/s; Euler's r there is 3e-7, none).
 *
 * The first unstable r of a grid in 1 % steps from R_MIN (r_k = r_{k-1} *
 * 1.01, rounded as it goes), then bisected.  The grid is walked in blocks
 * of BLOCK points and only a block's last point tried; the block whose
 * last point is unstable is then tried point by point.  That finds the
 * grid's first unstable point as trying every point would, in some 130
 * tries instead of 1,100 for an edge near r = 2.8 (every engine made pays
 * them, per package and mode), because a ray of the left half-plane
 * leaves the regions of degree 1, 2 and 4 once and does not come back:
 * no unstable stretch lies between two stable points (seen at 100 points
 * per 1 % step on 2001 rays per degree; test_stability compares this
 * with the point-by-point scan on a dense set of modes, to the bit).  The
 * bisection stops once lo and hi are neighbouring doubles: every further
 * step would try one of them again and change nothing. */
#define GROWTH_PER_PERIOD 1e-6
#define R_MIN 1e-4 /* below this many radians of the mode per step: none */
#define R_MAX 8.0  /* beyond every explicit region's reach */
#define BLOCK 16   /* grid points per block */
static int unstable(int deg, double r, double ure, double uim)
{
    return amplification(deg, r * ure, r * uim) > exp(GROWTH_PER_PERIOD * r / (2.0 * M_PI));
}

static double stable_r(int deg, double ure, double uim)
{
    double lo = 0.0, hi = 0.0;
    double first = R_MIN, last = 0.0; /* the block's first point, the point before it */
    int k = 0;
    for (double r = R_MIN; r < R_MAX; r *= 1.01) {
        const double next = r * 1.01;
        if (++k < BLOCK && next < R_MAX)
            continue;
        /* r ends the block (or the grid) */
        if (unstable(deg, r, ure, uim)) {
            /* the block's first unstable point, and the one before it */
            hi = r;
            lo = last;
            for (double q = first; q < r; q *= 1.01) {
                if (unstable(deg, q, ure, uim)) {
                    hi = q;
                    break;
                }
                lo = q;
            }
            break;
        }
        last = r;
        first = next;
        k = 0;
    }
    if (!(hi > 0.0))
        return INFINITY; /* not expected: every explicit region is bounded */
    if (!(lo > 0.0))
        return 0.0;
    for (int i = 0; i < 60; i++) {
        const double mid = 0.5 * (lo + hi);
        if (mid == lo || mid == hi)
            break; /* neighbours: every further step would try this mid again */
        if (unstable(deg, mid, ure, uim))
            hi = mid;
        else
            lo = mid;
    }
    return lo;
}

double sw_scheme_stable_dt(const sw_scheme_t *s, const sw_mode_t *m, int n, int *worst)
{
    double dt = INFINITY; /* s */
    if (worst)
        *worst = -1;
    if (!s || s->region <= 0 || !m)
        return dt;
    for (int i = 0; i < n; i++) {
        if (!(m[i].omega > 0.0) || !(m[i].re <= 0.0))
            continue; /* growing: the motion itself, not a scheme's instability */
        const double r = stable_r(s->region, m[i].re / m[i].omega, m[i].im / m[i].omega);
        const double dti = r / m[i].omega;
        if (dti < dt) {
            dt = dti;
            if (worst)
                *worst = i;
        }
    }
    return dt;
}
