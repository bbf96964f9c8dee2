/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cushion_contact.c - what a Winkler cushion does to the package at one
 * state: the push, its moments and the strain energy, per unit mass
 * (cushion_contact.h); the model's equations are in model_cushion.c.
 *
 * Contact.  A base point at sigma in [-b, b] sinks by z + sigma sin(theta)
 * and pushes back with f = kp z + bp z^3 + cp z' where it is compressed and
 * f > 0.  Where it is compressed f is a cubic in sigma whose second
 * derivative 6 bp sin^2(theta) z(sigma) is >= 0: f is convex there, so the
 * set where it pushes is the compressed interval minus at most one
 * sub-interval where damping would pull (the trailing edge of a rising
 * base).  That one rule covers full contact, partial contact (an edge or
 * both ends lifted) and free flight.  The ends where f = 0 are found by
 * Newton's method started from the side where f > 0: on a convex function
 * it converges monotonically, and exactly in one step when bp = 0.  (Not
 * gsl_poly_solve_cubic: the cubic's leading coefficient bp sin^3(theta)
 * vanishes with theta, where its monic form loses all accuracy.)  The
 * integrands of F_B, M_B and of the strain energy are polynomials in sigma
 * of degree <= 4, so the 3-point Gauss-Legendre rule integrates them
 * exactly: a closed form that stays free of cancellation for short pieces. */
#include "cushion_contact.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* Cushion constants per unit package mass and base length, from the
 * scene's derived quantities at every call (the same numbers each time). */
typedef struct {
    double b;  /* m, half width */
    double kp; /* 1/(s^2 m): k'/m */
    double bp; /* 1/(s^2 m^3): beta'/m */
    double cp; /* 1/(s m): c'/m */
} cush_t;

static cush_t cush_of(const sw_derived_t *d)
{
    cush_t c;
    const double w2 = d->omega_c * d->omega_c, len = 2.0 * d->b;
    c.b = d->b;
    c.kp = w2 / len;
    c.bp = d->K > 0.0 ? d->B3 / d->K * w2 / len : 0.0;
    c.cp = 2.0 * d->zeta_c * d->omega_c / len;
    return c;
}

/* Base kinematics: z(sigma) = z0 + s1 sigma, z'(sigma) = v0 + v1 sigma. */
typedef struct {
    double z0, s1, v0, v1;
} kin_t;

static double f_at(const cush_t *c, const kin_t *k, double x)
{
    const double z = k->z0 + k->s1 * x;
    return c->kp * z + c->bp * z * z * z + c->cp * (k->v0 + k->v1 * x);
}

static double df_at(const cush_t *c, const kin_t *k, double x)
{
    const double z = k->z0 + k->s1 * x;
    return (c->kp + 3.0 * c->bp * z * z) * k->s1 + c->cp * k->v1;
}

/* Root of the convex f on [p, q], f(p) and f(q) of opposite signs: Newton
 * from the end where f > 0 never overshoots. */
static double f_root(const cush_t *c, const kin_t *k, double p, double q)
{
    double x = f_at(c, k, p) > 0.0 ? p : q;
    for (int it = 0; it < 60; it++) {
        const double fx = f_at(c, k, x), dx = df_at(c, k, x);
        if (fx == 0.0 || dx == 0.0)
            break;
        double xn = x - fx / dx;
        if (xn < p)
            xn = p;
        if (xn > q)
            xn = q;
        const double step = fabs(xn - x);
        x = xn;
        if (step <= 4.0 * DBL_EPSILON * (c->b + fabs(x)))
            break;
    }
    return x;
}

/* 3-point Gauss-Legendre nodes on [-1, 1] and weights: exact to degree 5. */
static const double GL_X = 0.77459666924148337704; /* sqrt(3/5) */
static const double GL_W0 = 8.0 / 9.0, GL_W1 = 5.0 / 9.0;

/* Add F and Ms, and with CT_MOMENTS the moments, of the pushing piece
 * [p, q]. */
static void add_piece(const cush_t *c, const kin_t *k, double p, double q, int what, contact_t *o)
{
    const double mid = 0.5 * (p + q), half = 0.5 * (q - p);
    const double xs[3] = {mid - half * GL_X, mid, mid + half * GL_X};
    const double ws[3] = {GL_W1 * half, GL_W0 * half, GL_W1 * half};
    for (int i = 0; i < 3; i++) {
        const double z = k->z0 + k->s1 * xs[i];
        const double f = c->kp * z + c->bp * z * z * z + c->cp * (k->v0 + k->v1 * xs[i]);
        o->F += ws[i] * f;
        o->Ms += ws[i] * f * xs[i];
        if (!(what & CT_MOMENTS))
            continue;
        const double kt = c->kp + 3.0 * c->bp * z * z;
        o->S += ws[i] * kt;
        o->S1 += ws[i] * kt * xs[i];
        o->S2 += ws[i] * kt * xs[i] * xs[i];
        o->L0 += ws[i];
        o->L1 += ws[i] * xs[i];
        o->L2 += ws[i] * xs[i] * xs[i];
    }
}

/* Forces, tangent stiffness and strain energy of the cushion at (theta, z)
 * moving at (theta', z'), given s = sin(theta) and co = cos(theta): the
 * right-hand side needs them too, and they are a fifth of its cost. */
void sw_cushion_contact(const sw_derived_t *d, double s, double co, double z, double dth, double dz,
                        int what, contact_t *o)
{
    const cush_t cd = cush_of(d), *c = &cd;
    memset(o, 0, sizeof *o);
    const double b = c->b;
    const double zr = z - b * s, zf = z + b * s; /* m, compression of the rear / front edge */
    if (zr <= 0.0 && zf <= 0.0)
        return; /* free flight */
    /* the compressed interval [l, r]; where an edge is not compressed the
     * end is the zero of z(sigma), which lies inside [-b, b] */
    const double l = zr > 0.0 ? -b : -z / s;
    const double r = zf > 0.0 ? b : -z / s;
    const kin_t k = {z, s, dz, dth * co};

    /* strain energy, over the compressed part whatever the damping does */
    if (what & CT_STRAIN) {
        const double mid = 0.5 * (l + r), half = 0.5 * (r - l);
        const double xs[3] = {mid - half * GL_X, mid, mid + half * GL_X};
        const double ws[3] = {GL_W1 * half, GL_W0 * half, GL_W1 * half};
        for (int i = 0; i < 3; i++) {
            const double zi = z + s * xs[i], z2 = zi * zi;
            o->U += ws[i] * (0.5 * c->kp * z2 + 0.25 * c->bp * z2 * z2);
        }
    }

    if (!(what & (CT_PUSH | CT_MOMENTS)))
        return;
    /* f is convex on [l, r]: find its lowest point m */
    const double dl = df_at(c, &k, l), dr = df_at(c, &k, r);
    double m;
    if (dl >= 0.0) {
        m = l;
    } else if (dr <= 0.0) {
        m = r;
    } else {
        /* bp s != 0 here (otherwise f' would be constant): f' = 0 where
         * z^2 = -(kp s + cp v1) / (3 bp s) */
        const double z2 = -(c->kp * s + c->cp * k.v1) / (3.0 * c->bp * s);
        m = z2 > 0.0 ? (sqrt(z2) - z) / s : 0.5 * (l + r);
        if (!(m > l && m < r))
            m = 0.5 * (l + r);
    }
    const double fl = f_at(c, &k, l), fr = f_at(c, &k, r), fm = f_at(c, &k, m);
    if (fm >= 0.0) {
        /* pushes everywhere (an end can only be < 0 by round-off in m) */
        add_piece(c, &k, fl < 0.0 ? f_root(c, &k, l, m) : l, fr < 0.0 ? f_root(c, &k, m, r) : r,
                  what, o);
        return;
    }
    /* convex: f < 0 on one interval around m, >= 0 outside it */
    if (fl > 0.0)
        add_piece(c, &k, l, f_root(c, &k, l, m), what, o);
    if (fr > 0.0)
        add_piece(c, &k, f_root(c, &k, m, r), r, what, o);
}
