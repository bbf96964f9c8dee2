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
#include "model_rigid.h"
#include "swaywatch/model.h"

const char *sw_phase_name(sw_phase p)
{
    switch (p) {
    case SW_PHASE_STUCK: return "stuck";
    case SW_PHASE_ROCKING: return "rocking";
    case SW_PHASE_OVERTURNED: return "overturned";
    }
    return "unknown";
}

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

int sw_model_rhs(double t, const double y[], double f[], void *pkg)
{
    sw_pkg_t *P = pkg; /* not const: the sin/cos cache, the cushion's state */
    if (P->d.model == SW_MODEL_CUSHION) return sw_cushion_rhs(P, t, y, f);
    sw_rigid_rhs(P, sw_input_ag(P->in, t), sw_input_geff(P, t), y, f);
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
    const double A = P->d.model == SW_MODEL_BARE ? sw_input_ag(P->in, t) : -sw_rigid_bearing(P, P->y);
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

/* The margins and energies below take cA = cos(alpha - |theta|) from the
 * caller: the state report gets it from the right-hand side's sin/cos
 * cache instead of calling cos() twice per sample. */
static double margin_rocking_c(const sw_derived_t *d, double r, double theta, double theta_dot,
                               double cA)
{
    /* energy above rest in units of the barrier, potential and kinetic */
    const double ca = cos_alpha(d), p2 = 2.0 * d->p * d->p;
    const double k = 1.0 / (p2 * (1.0 - ca)); /* one division per report */
    const double ath = fabs(theta);
    const double PE = (cA - ca) * p2 * k;
    const double KE = theta_dot * theta_dot * k;
    const double E = PE + KE;
    const int outward = theta * theta_dot > 0.0 || (theta == 0.0 && theta_dot != 0.0);
    if (theta == 0.0 && theta_dot == 0.0) return 1.0;
    if (ath < d->alpha) return outward ? 1.0 - E : 1.0 - r * r * E;
    if (!outward && E > 1.0) return 1.0 - r * r * E;
    return PE - KE - 1.0;
}

/* cos(alpha - |theta|); upright (stuck, most of the time) without cos(). */
static double cos_A(const sw_derived_t *d, double theta)
{
    return theta == 0.0 ? cos_alpha(d) : cos(d->alpha - fabs(theta));
}

double sw_margin_rocking(const sw_derived_t *d, double r, double theta, double theta_dot)
{
    return margin_rocking_c(d, r, theta, theta_dot, cos_A(d, theta));
}

static double energy_bare_c(const sw_derived_t *d, double g_eff, const sw_state_t *s, double cA)
{
    return (2.0 / 3.0) * d->R * d->R * s->theta_dot * s->theta_dot +
           g_eff * d->R * (cA - cos_alpha(d));
}

double sw_energy_bare(const sw_derived_t *d, double g_eff, const sw_state_t *s)
{
    return energy_bare_c(d, g_eff, s, cos_A(d, s->theta));
}

static double energy_frame_c(const sw_derived_t *d, double g_eff, const sw_state_t *s, double cA)
{
    if (d->gamma <= 0.0) return energy_bare_c(d, g_eff, s, cA);
    const double wb = d->omega_b;
    return (0.5 / d->gamma) * (s->u_dot * s->u_dot + wb * wb * s->u * s->u) +
           d->R * cA * s->u_dot * s->theta_dot +
           (2.0 / 3.0) * d->R * d->R * s->theta_dot * s->theta_dot +
           g_eff * d->R * (cA - cos_alpha(d));
}

double sw_energy_frame(const sw_derived_t *d, double g_eff, const sw_state_t *s)
{
    return energy_frame_c(d, g_eff, s, cos_A(d, s->theta));
}

static double margin_bound_frame_c(const sw_derived_t *d, double g_eff, const sw_state_t *s,
                                   double cA)
{
    const double Eb = g_eff * d->R * (1.0 - cos_alpha(d));
    const double m = 1.0 - energy_frame_c(d, g_eff, s, cA) / Eb;
    return fabs(s->theta) < d->alpha ? m : fmin(m, 0.0);
}

double sw_margin_bound_frame(const sw_derived_t *d, double g_eff, const sw_state_t *s)
{
    return margin_bound_frame_c(d, g_eff, s, cos_A(d, s->theta));
}

void sw_model_output(const sw_pkg_t *P, double t, sw_output_t *o)
{
    memset(o, 0, sizeof *o);
    o->t = t;
    sw_model_to_state(P, &o->state);
    o->a_g = sw_input_ag(P->in, t);
    const double ge_in = sw_input_geff(P, t); /* m/s^2, as the right-hand side sees it */
    double ge = ge_in;
    if (P->d.model == SW_MODEL_CUSHION) {
        double f[SW_NMAX];
        sw_cushion_rhs((sw_pkg_t *)P, t, P->y, f); /* const but for its rate tracking, off here */
        o->a_support = sw_model_support_accel(P, t, f);
    }
    /* Airborne (g + a_z <= 0): the engine has faulted the package and reset
     * it; its energy bound is judged under nominal gravity, not divided by
     * a zero or negative barrier. */
    if (!(ge > 0.0)) ge = P->g;
    double cA = cos_alpha(&P->d); /* cos(alpha - |theta|) */
    if (P->d.model != SW_MODEL_CUSHION) {
        /* bare: the support is the bed; frame: a_g + u''.  sin and cos of
         * A1 = alpha - s theta (which is alpha - |theta| but in the
         * instant of a landing) near the right-hand side's last angle. */
        double sn = 0.0, c1 = 0.0;
        if (P->phase == SW_PHASE_ROCKING) {
            const double sth = P->side * P->y[P->ith];
            sw_rigid_sincos_near(P->trig, P->d.alpha - sth, &sn, &c1);
            cA = sth >= 0.0 ? c1 : cos(P->d.alpha + sth);
        }
        o->a_support = o->a_g;
        if (P->d.model == SW_MODEL_FRAME) {
            double f[SW_NMAX];
            sw_rigid_rhs_trig(P, SW_MODEL_FRAME, o->a_g, ge_in, P->y, sn, c1, f);
            o->a_support += f[P->idu];
        }
    }
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
        o->margin = margin_rocking_c(&P->d, r, o->state.theta, o->state.theta_dot, cA);
    }
    if (P->d.model == SW_MODEL_BARE)
        o->margin_bound = o->margin;
    else
        o->margin_bound = margin_bound_frame_c(&P->d, ge, &o->state, cA);
}
