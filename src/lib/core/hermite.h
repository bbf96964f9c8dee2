/* SPDX-License-Identifier: GPL-3.0-or-later */
/* hermite.h - the cubic Hermite interpolant over one step: the dense output
 * that GSL's steppers lack.  The event layer finds roots of an event
 * function on it; the step layer re-steps a multistep scheme with it.  A
 * leaf: it knows nothing of packages or engines.
 *
 * Over a step of length h with values v0, v1 and time derivatives d0, d1
 * at its ends, H(x) = c0 + c1 x + c2 x^2 + c3 x^3 for x = (t - t0)/h in
 * [0, 1]; O(h^4) for a smooth function. */
#ifndef SWAYWATCH_HERMITE_H
#define SWAYWATCH_HERMITE_H

#include <float.h>
#include <math.h>

typedef struct {
    double c0, c1, c2, c3;
} sw_herm_t;

static inline sw_herm_t sw_herm_make(double v0, double d0, double v1, double d1, double h)
{
    sw_herm_t H;
    H.c0 = v0;
    H.c1 = h * d0;
    H.c2 = -3.0 * v0 - 2.0 * h * d0 + 3.0 * v1 - h * d1;
    H.c3 = 2.0 * v0 + h * d0 - 2.0 * v1 + h * d1;
    return H;
}

static inline double sw_herm_at(const sw_herm_t *H, double x)
{
    return ((H->c3 * x + H->c2) * x + H->c1) * x + H->c0;
}

/* The round-off floor of H's values: a rise must reach it to count (an
 * event function that only touches 0 is not crossing it). */
static inline double sw_herm_tol(const sw_herm_t *H)
{
    return 64.0 * DBL_EPSILON * (fabs(H->c0) + fabs(H->c1) + fabs(H->c2) + fabs(H->c3));
}

/* Critical points of H inside (0, 1), sorted; returns how many (0..2). */
static inline int sw_herm_crit(const sw_herm_t *H, double x[2])
{
    const double a = 3.0 * H->c3, b = 2.0 * H->c2, c = H->c1;
    int k = 0;
    double r[2];
    if (fabs(a) < 1e-300) {
        if (fabs(b) > 1e-300)
            r[k++] = -c / b;
    } else {
        const double disc = b * b - 4.0 * a * c;
        if (disc >= 0.0) {
            const double q = -0.5 * (b + copysign(sqrt(disc), b));
            if (q != 0.0)
                r[k++] = q / a;
            if (q != 0.0)
                r[k++] = c / q;
            else
                r[k++] = 0.0;
        }
    }
    int m = 0;
    for (int i = 0; i < k; i++)
        if (r[i] > 0.0 && r[i] < 1.0)
            x[m++] = r[i];
    if (m == 2 && x[0] > x[1]) {
        const double tmp = x[0];
        x[0] = x[1];
        x[1] = tmp;
    }
    return m;
}

/* Earliest x in (0, 1] where H rises through 0 from below, on the monotone
 * pieces between its critical points (so a double crossing inside one step
 * is not missed), bracketed by bisection; -1 if none.  A rise must reach
 * tol, so round-off in a function that only touches 0 (a package just
 * lifted, theta = theta' = 0) is not taken for an event.  A function
 * already rising at 0 is the caller's to handle. */
static inline double sw_herm_first_rise(const sw_herm_t *H, double tol)
{
    double knots[4];
    int nk = 0;
    knots[nk++] = 0.0;
    double cr[2];
    const int nc = sw_herm_crit(H, cr);
    for (int i = 0; i < nc; i++) knots[nk++] = cr[i];
    knots[nk++] = 1.0;
    for (int i = 0; i + 1 < nk; i++) {
        double a = knots[i], b = knots[i + 1];
        const double va = sw_herm_at(H, a), vb = sw_herm_at(H, b);
        /* A rise straight from an exact 0 at the start (a package just
         * lifted or just landed, whose true motion starts the other way by
         * construction) is the interpolant's artefact, not a crossing. */
        if (i == 0 && va == 0.0)
            continue;
        if (!(va <= 0.0 && vb >= tol))
            continue;
        for (int it = 0; it < 64 && b - a > 1e-16; it++) { /* monotone piece */
            const double m = 0.5 * (a + b);
            if (sw_herm_at(H, m) >= 0.0)
                b = m;
            else
                a = m;
        }
        return b;
    }
    return -1.0;
}

/* The first rise through 0 of the interpolant of a function with values
 * v0, v1 and time derivatives d0, d1 at the ends of a step of length h
 * (s), by sw_herm_first_rise: above its round-off floor (sw_herm_tol,
 * which *tol then gets) unless tol is NULL.  The event layer's one call
 * per candidate. */
static inline double sw_herm_rise(double v0, double d0, double v1, double d1, double h, double *tol)
{
    const sw_herm_t H = sw_herm_make(v0, d0, v1, d1, h);
    if (!tol)
        return sw_herm_first_rise(&H, 0.0);
    *tol = sw_herm_tol(&H);
    return sw_herm_first_rise(&H, *tol);
}

/* The state at x in [0, 1] of a step of length h (s) from (y0, f0) to
 * (y1, f1), n components, each on its own interpolant. */
static inline void sw_herm_state(int n, double h, const double y0[], const double f0[],
                                 const double y1[], const double f1[], double x, double yt[])
{
    for (int i = 0; i < n; i++) {
        const sw_herm_t Hi = sw_herm_make(y0[i], f0[i], y1[i], f1[i], h);
        yt[i] = sw_herm_at(&Hi, x);
    }
}

#endif
