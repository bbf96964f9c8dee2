/* model.c - equations of motion, impact maps and margins of the rocking
 * models, exactly as physics.md gives them.  Pure functions of a package's
 * parameters, state and input: no allocation, no I/O.
 *
 * State vectors:  bare     y = (theta, theta')
 *                 frame    y = (u, theta, u', theta')
 *                 cushion  y = (u, theta, z, u', theta', z') on a frame,
 *                          y = (theta, z, theta', z') on the bed
 *                          (its physics is in model_cushion.c)
 * theta > 0 when the top tips forward (rocking about the front corner, side
 * s = +1); A1 = alpha - s theta, A2 = s alpha - theta.  Gravity appears as
 * g_eff = g + a_z in every gravity term; p^2 = kR g with kR = 3/(4R). */
#include <math.h>
#include <string.h>

#include "internal.h"
#include "swaywatch/model.h"

void sw_model_setup(sw_pkg_t *P)
{
    P->iu = P->idu = P->iz = P->idz = -1;
    switch (P->d.model) {
    case SW_MODEL_BARE:
        P->n = 2;
        P->ith = 0;
        P->idth = 1;
        break;
    case SW_MODEL_CUSHION:
        if (P->scene.has_frame) {
            P->n = 6;
            P->iu = 0;
            P->ith = 1;
            P->iz = 2;
            P->idu = 3;
            P->idth = 4;
            P->idz = 5;
        } else {
            P->n = 4;
            P->ith = 0;
            P->iz = 1;
            P->idth = 2;
            P->idz = 3;
        }
        break;
    case SW_MODEL_FRAME:
    default:
        P->n = 4;
        P->iu = 0;
        P->ith = 1;
        P->idu = 2;
        P->idth = 3;
        break;
    }
    P->trig[0] = NAN;
    P->g = P->scene.g;
    P->kR = 0.75 / P->d.R;
    P->tan_alpha = tan(P->d.alpha);

    /* Typical sizes of the components, for finite-difference Jacobians:
     * the angle at which an edge of a cushioned base lifts (z_s/b) or
     * alpha, the static deflection, the bearings' deflection under 1 g;
     * rates at the scene's fastest frequency. */
    const double w = fmax(P->d.omega_max, P->d.p); /* rad/s */
    const int cushion = P->d.model == SW_MODEL_CUSHION;
    const double zs = cushion ? sw_cushion_static_deflection(&P->d, P->g) : 0.0; /* m */
    P->yscale[P->ith] = cushion ? zs / P->d.b : P->d.alpha;
    P->yscale[P->idth] = w * P->yscale[P->ith];
    if (P->iu >= 0) {
        P->yscale[P->iu] = P->g / (P->d.omega_b * P->d.omega_b);
        P->yscale[P->idu] = w * P->yscale[P->iu];
    }
    if (P->iz >= 0) {
        P->yscale[P->iz] = zs;
        P->yscale[P->idz] = w * zs;
    }
    if (cushion) sw_cushion_setup(P);
}

double sw_input_ag(const sw_input_t *in, double t)
{
    if (in->fn) return in->fn(in->fn_user, t);
    return in->ag0 + in->ag_slope * (t - in->t0);
}

double sw_input_geff(const sw_pkg_t *P, double t)
{
    const sw_input_t *in = P->in;
    if (in->fn) return P->g;
    return P->g + in->az0 + in->az_slope * (t - in->t0);
}

/* sin and cos of A1 for a right-hand side.  Successive evaluations (the
 * stages of a step, the next steps) see nearby angles, so they come from
 * the last angle computed by libm through the addition formulas, with the
 * series of sin and cos of the small difference d (|d| <= 1/64 rad: the
 * first term left out is below 1e-21); libm only when the angle has moved
 * further.  This halves the cost of an RK4 step; the result differs from
 * libm's by an ulp or two. */
static void rhs_sincos(sw_pkg_t *P, double A, double *sn, double *cs)
{
    const double d = A - P->trig[0];
    if (fabs(d) <= 0.015625) {
        const double d2 = d * d;
        const double sd =
            d * (1.0 - d2 * (1.0 / 6.0) * (1.0 - d2 * (1.0 / 20.0) * (1.0 - d2 * (1.0 / 42.0))));
        const double cd =
            1.0 - d2 * 0.5 *
                      (1.0 - d2 * (1.0 / 12.0) *
                                 (1.0 - d2 * (1.0 / 30.0) * (1.0 - d2 * (1.0 / 56.0))));
        *sn = P->trig[1] * cd + P->trig[2] * sd;
        *cs = P->trig[2] * cd - P->trig[1] * sd;
        return;
    }
    *sn = sin(A);
    *cs = cos(A);
    P->trig[0] = A;
    P->trig[1] = *sn;
    P->trig[2] = *cs;
}

/* Bearing force per unit total mass (m/s^2): 2 zeta_b w_b u' + w_b^2 u. */
static double bearing(const sw_pkg_t *P, const double y[])
{
    const double w = P->d.omega_b;
    return 2.0 * P->d.zeta_b * w * y[P->idu] + w * w * y[P->iu];
}

int sw_model_rhs(double t, const double y[], double f[], void *pkg)
{
    sw_pkg_t *P = pkg; /* not const: the sin/cos cache, the cushion's state */
    const double ag = sw_input_ag(P->in, t);
    const double ge = sw_input_geff(P, t);
    const double s = P->side;
    const double th = y[P->ith], dth = y[P->idth];

    if (P->d.model == SW_MODEL_CUSHION) return sw_cushion_rhs(P, t, y, f);
    /* A2 = s A1 exactly (s = +-1), so sin(A2) = s sin(A1): one angle. */
    if (P->d.model == SW_MODEL_BARE) {
        f[0] = dth;
        if (P->phase == SW_PHASE_ROCKING) {
            double sn, cs;
            rhs_sincos(P, P->d.alpha - s * th, &sn, &cs);
            f[1] = -P->kR * (ge * s * sn + ag * cs);
        } else {
            f[1] = 0.0;
        }
        return GSL_SUCCESS;
    }
    /* frame */
    const double F = bearing(P, y);
    f[P->iu] = y[P->idu];
    f[P->ith] = dth;
    if (P->phase == SW_PHASE_ROCKING) {
        double sn, c1;
        rhs_sincos(P, P->d.alpha - s * th, &sn, &c1);
        const double s2 = s * sn;
        const double gR = P->d.gamma * P->d.R;
        const double D = 1.0 - 0.75 * P->d.gamma * c1 * c1;
        f[P->idu] = (-F + gR * s2 * (P->kR * ge * c1 - dth * dth)) / D - ag;
        f[P->idth] = (P->kR * c1 * (F + gR * dth * dth * s2) - P->kR * ge * s2) / D;
    } else {
        f[P->idu] = -F - ag;
        f[P->idth] = 0.0;
    }
    return GSL_SUCCESS;
}

double sw_model_support_accel(const sw_pkg_t *P, double t, const double f[])
{
    if (P->iu < 0) return sw_input_ag(P->in, t); /* bare, or cushion on the bed */
    return sw_input_ag(P->in, t) + f[P->idu];
}

int sw_model_uplift_side(const sw_pkg_t *P, double t)
{
    /* While stuck the support's acceleration is a_g (bare) or a_g + u'' =
     * -(2 zeta_b w_b u' + w_b^2 u) (frame); it does not depend on theta.
     * A cushioned package is never stuck. */
    if (P->d.model == SW_MODEL_CUSHION) return 0;
    const double A = P->d.model == SW_MODEL_BARE ? sw_input_ag(P->in, t) : -bearing(P, P->y);
    const double ge = sw_input_geff(P, t);
    if (!(ge > 0.0)) return 0; /* airborne: outside the model (the engine faults) */
    const double thr = P->tan_alpha * ge;
    if (A <= -thr) return +1; /* braking tips the top forward */
    if (A >= thr) return -1;
    return 0;
}

void sw_model_impact(sw_pkg_t *P)
{
    const double before = P->y[P->idth];
    if (P->d.model == SW_MODEL_BARE) {
        P->y[P->idth] = P->d.eta * before;
    } else {
        const double after = P->d.r_frame * before;
        P->y[P->idth] = after;
        P->y[P->idu] += P->d.gamma * P->d.h * (before - after);
    }
    P->y[P->ith] = 0.0;
    P->side = -P->side;
}

void sw_model_to_state(const sw_pkg_t *P, sw_state_t *s)
{
    memset(s, 0, sizeof *s);
    s->theta = P->y[P->ith];
    s->theta_dot = P->y[P->idth];
    if (P->iu >= 0) {
        s->u = P->y[P->iu];
        s->u_dot = P->y[P->idu];
    }
    if (P->iz >= 0) {
        s->z = P->y[P->iz];
        s->z_dot = P->y[P->idz];
    }
    s->phase = P->phase;
    s->side = P->phase == SW_PHASE_STUCK ? 0 : P->side;
}

void sw_model_from_state(sw_pkg_t *P, const sw_state_t *s)
{
    memset(P->y, 0, sizeof P->y);
    P->y[P->ith] = s->theta;
    P->y[P->idth] = s->theta_dot;
    if (P->iu >= 0) {
        P->y[P->iu] = s->u;
        P->y[P->idu] = s->u_dot;
    }
    if (P->iz >= 0) {
        P->y[P->iz] = s->z;
        P->y[P->idz] = s->z_dot;
    }
    P->phase = s->phase;
    P->side = s->side ? (s->side > 0 ? 1 : -1) : (s->theta < 0 ? -1 : 1);
    if (P->d.model == SW_MODEL_CUSHION) {
        /* nothing is stuck on a cushion; side follows theta */
        if (P->phase == SW_PHASE_STUCK) P->phase = SW_PHASE_ROCKING;
        P->side = s->theta < 0.0 ? -1 : 1;
        return;
    }
    if (P->phase == SW_PHASE_STUCK) {
        P->y[P->ith] = P->y[P->idth] = 0.0;
    }
}

/* cos(alpha) = h/R exactly: no cos() per output sample. */
static double cos_alpha(const sw_derived_t *d)
{
    return d->h / d->R;
}

double sw_margin_rocking(const sw_derived_t *d, double r, double theta, double theta_dot)
{
    const double ca = cos_alpha(d), one = 1.0 - ca;
    const double ath = fabs(theta);
    const double PE = (cos(d->alpha - ath) - ca) / one;
    const double KE = theta_dot * theta_dot / (2.0 * d->p * d->p * one);
    const double E = PE + KE;
    const int outward = theta * theta_dot > 0.0 || (theta == 0.0 && theta_dot != 0.0);
    if (theta == 0.0 && theta_dot == 0.0) return 1.0;
    if (ath < d->alpha) return outward ? 1.0 - E : 1.0 - r * r * E;
    if (!outward && E > 1.0) return 1.0 - r * r * E;
    return PE - KE - 1.0;
}

double sw_energy_bare(const sw_derived_t *d, double g_eff, const sw_state_t *s)
{
    const double A1 = d->alpha - fabs(s->theta);
    return (2.0 / 3.0) * d->R * d->R * s->theta_dot * s->theta_dot +
           g_eff * d->R * (cos(A1) - cos_alpha(d));
}

double sw_energy_frame(const sw_derived_t *d, double g_eff, const sw_state_t *s)
{
    if (d->gamma <= 0.0) return sw_energy_bare(d, g_eff, s);
    /* upright (stuck, most of the time): no cos() */
    const double cA1 = s->theta == 0.0 ? cos_alpha(d) : cos(d->alpha - fabs(s->theta));
    return 0.5 * s->u_dot * s->u_dot / d->gamma + d->R * cA1 * s->u_dot * s->theta_dot +
           (2.0 / 3.0) * d->R * d->R * s->theta_dot * s->theta_dot +
           g_eff * d->R * (cA1 - cos_alpha(d)) +
           0.5 * d->omega_b * d->omega_b * s->u * s->u / d->gamma;
}

double sw_margin_bound_frame(const sw_derived_t *d, double g_eff, const sw_state_t *s)
{
    const double Eb = g_eff * d->R * (1.0 - cos_alpha(d));
    const double m = 1.0 - sw_energy_frame(d, g_eff, s) / Eb;
    return fabs(s->theta) < d->alpha ? m : fmin(m, 0.0);
}

void sw_model_output(const sw_pkg_t *P, double t, sw_output_t *o)
{
    double f[SW_NMAX];
    memset(o, 0, sizeof *o);
    o->t = t;
    sw_model_to_state(P, &o->state);
    double ge = sw_input_geff(P, t);
    /* Airborne (g + a_z <= 0): the engine has faulted the package and reset
     * it; its energy bound is judged under nominal gravity, not divided by
     * a zero or negative barrier. */
    if (!(ge > 0.0)) ge = P->g;
    if (P->d.model == SW_MODEL_BARE) f[0] = f[1] = 0.0; /* the support is the bed */
    else sw_model_rhs(t, P->y, f, (void *)P);
    o->a_g = sw_input_ag(P->in, t);
    o->a_support = sw_model_support_accel(P, t, f);
    o->uplift_ratio = fabs(o->a_support) / (P->tan_alpha * P->g);
    if (P->phase == SW_PHASE_OVERTURNED) {
        o->margin = o->margin_bound = -1.0;
        return;
    }
    if (P->d.model == SW_MODEL_CUSHION) {
        sw_margin_cushion(&P->d, ge, &o->state, &o->margin, &o->margin_bound);
        return;
    }
    if (P->phase == SW_PHASE_STUCK) {
        o->margin = 1.0;
    } else {
        const double r = P->d.model == SW_MODEL_BARE ? P->d.eta : P->d.r_frame;
        o->margin = sw_margin_rocking(&P->d, r, o->state.theta, o->state.theta_dot);
    }
    if (P->d.model == SW_MODEL_BARE)
        o->margin_bound = o->margin;
    else
        o->margin_bound = sw_margin_bound_frame(&P->d, ge, &o->state);
}
