/* SPDX-License-Identifier: GPL-3.0-or-later */
/* model_rigid.c - the bare block and the package on a frame (physics.md,
 * scenes 1 and 2) as the engine sees them: their ops tables (layout,
 * events, impact map, uplift test, how they stand, report), their traits,
 * and the margins and energies of model.h.  The right-hand sides and their
 * sin and cos cache are this file's own: the fixed-step schemes' bodies
 * are instantiated here with them inlined per stage (fixed_rk.h).
 *
 * State vectors:  bare   y = (theta, theta')
 *                 frame  y = (u, theta, u', theta')
 * theta > 0 when the top tips forward (rocking about the front corner, side
 * s = +1); A1 = alpha - s theta, A2 = s alpha - theta.  Gravity appears as
 * g_eff = g + a_z in every gravity term; p^2 = kR g with kR = 3/(4R). */
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "fixed_rk.h"
#include "model_ops.h"
#include "model_rigid.h"
#include "model_traits.h"
#include "numeric.h"
#include "swaywatch/model.h"
#include "swaywatch/status.h"

/* ---- the sin and cos cache -------------------------------------------------- */

/* sin and cos of A1 for a right-hand side.  Successive evaluations (the
 * stages of a step, the next steps, the state report) see nearby angles,
 * so they come from the last angle computed by libm, trig = (angle, sin,
 * cos), through the addition formulas with the series of sin and cos of
 * the small difference d (|d| <= 1/64 rad: the first term left out is below
 * 1e-21); libm only when the angle has moved further.  This halves the cost
 * of an RK4 step; the result differs from libm's by an ulp or two.
 * Returns 1 if the cached angle served (trig[0] = NAN: never). */
static inline int sincos_near(const double trig[3], double A, double *sn, double *cs)
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
static inline void rigid_sincos(sw_model_scratch_t *S, double A, double *sn, double *cs)
{
    if (sincos_near(S->trig, A, sn, cs))
        return;
    S->trig[0] = A;
    S->trig[1] = *sn;
    S->trig[2] = *cs;
}

/* ---- margins and energies (model.h) ----------------------------------------- */

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
    if (theta == 0.0 && theta_dot == 0.0)
        return 1.0;
    if (ath < d->alpha)
        return outward ? 1.0 - E : 1.0 - r * r * E;
    if (!outward && E > 1.0)
        return 1.0 - r * r * E;
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
    if (d->gamma <= 0.0)
        return energy_bare_c(d, g_eff, s, cA);
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

/* ---- layout and right-hand sides -------------------------------------------- */

/* Typical sizes: alpha, and the bearings' deflection under 1 g. */
static void bare_setup(sw_model_t *M, const sw_scene_t *sc)
{
    (void)sc;
    M->n = 2;
    M->ith = 0;
    M->idth = 1;
    sw_model_scale(M, M->ith, M->idth, M->d.alpha);
}

static void frame_setup(sw_model_t *M, const sw_scene_t *sc)
{
    (void)sc;
    M->n = 4;
    M->iu = 0;
    M->ith = 1;
    M->idu = 2;
    M->idth = 3;
    sw_model_scale(M, M->ith, M->idth, M->d.alpha);
    sw_model_scale(M, M->iu, M->idu, M->g / (M->d.omega_b * M->d.omega_b));
}

/* f = y' of a bare or framed package under a_g = ag and g_eff = ge (m/s^2),
 * given sn = sin(A1) and c1 = cos(A1) (not read unless rocking).  The
 * layouts are fixed (model.c's sw_model_setup): bare (theta, theta'),
 * frame (u, theta, u', theta'); a caller that passes model as a constant
 * gets one of the two bodies. */
static SW_ALWAYS_INLINE void rigid_rhs_trig(const sw_model_t *M, sw_model_kind model, double ag,
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
static SW_ALWAYS_INLINE void rigid_rhs_of(const sw_model_t *M, sw_model_scratch_t *S,
                                          sw_model_kind model, double ag, double ge,
                                          const double y[], double f[])
{
    double sn = 0.0, c1 = 0.0;
    if (M->phase == SW_PHASE_ROCKING)
        rigid_sincos(S, M->d.alpha - M->side * y[model == SW_MODEL_BARE ? 0 : 1], &sn, &c1);
    rigid_rhs_trig(M, model, ag, ge, y, sn, c1, f);
}

static int bare_rhs(const sw_model_t *M, sw_model_scratch_t *S, const sw_input_at_t *u,
                    const double y[], double f[])
{
    rigid_rhs_of(M, S, SW_MODEL_BARE, u->ag, u->ge, y, f);
    return GSL_SUCCESS;
}

static int frame_rhs(const sw_model_t *M, sw_model_scratch_t *S, const sw_input_at_t *u,
                     const double y[], double f[])
{
    rigid_rhs_of(M, S, SW_MODEL_FRAME, u->ag, u->ge, y, f);
    return GSL_SUCCESS;
}

/* The fixed-step schemes' bodies with the right-hand side inlined into
 * every stage (fixed_rk.h): at one step per 1 kHz sample a function
 * pointer, a model switch and two input evaluations per stage were a
 * third of the cost of a rocking step. */
static SW_ALWAYS_INLINE void bare_stage(const sw_model_t *M, sw_model_scratch_t *S,
                                        const sw_input_at_t *u, const double y[], double f[])
{
    rigid_rhs_of(M, S, SW_MODEL_BARE, u->ag, u->ge, y, f);
}

static SW_ALWAYS_INLINE void frame_stage(const sw_model_t *M, sw_model_scratch_t *S,
                                         const sw_input_at_t *u, const double y[], double f[])
{
    rigid_rhs_of(M, S, SW_MODEL_FRAME, u->ag, u->ge, y, f);
}
SW_FIXED_RK(bare, 2, bare_stage)
SW_FIXED_RK(frame, 4, frame_stage)

/* ---- events ----------------------------------------------------------------- */

/* Rocking: the impact (theta back to 0) and the overturn (pi/2) cut the
 * step when an endpoint is through or close enough that the step's motion
 * could reach it; the peak of |theta| where theta' changes sign; the tip
 * where s theta crosses alpha.  A stuck frame not held: uplift either way
 * (the bare block is never stepped while stuck: stuck.c solves for its
 * uplift).  The rigid right-hand sides are smooth within a phase: no
 * kinks to cut at. */
static int rigid_candidates(const sw_model_t *M, int cut_kinks, double h, const double y0[],
                            const double y1[], sw_evcand_t c[])
{
    (void)cut_kinks;
    int n = 0;
    if (M->phase == SW_PHASE_ROCKING) {
        const double s0 = M->side * y0[M->ith], s1 = M->side * y1[M->ith];
        /* the comparisons themselves, not libm's fmax and fmin (calls, for
         * NaN), on every rocking step */
        const double w0 = fabs(y0[M->idth]), w1 = fabs(y1[M->idth]);
        const double v = h * (w0 > w1 ? w0 : w1);
        if (s1 <= 0.0 || (s0 < s1 ? s0 : s1) < v)
            c[n++] = (sw_evcand_t){SW_EVF_IMPACT, SW_ROLE_CUT, SW_RULE_RISE, 0};
        if (s1 >= M_PI_2 || M_PI_2 - (s0 > s1 ? s0 : s1) < v)
            c[n++] = (sw_evcand_t){SW_EVF_OVERTURN, SW_ROLE_CUT, SW_RULE_RISE, 0};
        if ((y0[M->idth] > 0.0) != (y1[M->idth] > 0.0))
            c[n++] = (sw_evcand_t){SW_EVF_TURN, SW_ROLE_PEAK, SW_RULE_PLAIN, 0};
        if ((s0 < M->d.alpha) != (s1 < M->d.alpha))
            c[n++] = (sw_evcand_t){SW_EVF_TIP, SW_ROLE_TIP, SW_RULE_PLAIN, 0};
    } else if (M->phase == SW_PHASE_STUCK && M->iu >= 0 && !M->held) {
        c[n++] = (sw_evcand_t){SW_EVF_UPLIFT_FWD, SW_ROLE_CUT, SW_RULE_RISE, 1};
        c[n++] = (sw_evcand_t){SW_EVF_UPLIFT_BACK, SW_ROLE_CUT, SW_RULE_RISE, 1};
    }
    return n;
}

/* Value and time derivative of event ev at y with f = y' under the input
 * u.  Every event is "the function rises through 0". */
static void rigid_event_fn(const sw_model_t *M, int ev, const sw_input_at_t *u, const double y[],
                           const double f[], double *val, double *der)
{
    const double s = M->side;
    switch (ev) {
        case SW_EVF_IMPACT:
            *val = -s * y[M->ith];
            *der = -s * f[M->ith];
            return;
        case SW_EVF_OVERTURN:
            *val = s * y[M->ith] - M_PI_2;
            *der = s * f[M->ith];
            return;
        case SW_EVF_TIP:
            *val = s * y[M->ith] - M->d.alpha;
            *der = s * f[M->ith];
            return;
        case SW_EVF_TURN: /* the package stops swinging outward: the peak of |theta| */
            *val = -s * y[M->idth];
            *der = -s * f[M->idth];
            return;
        default: {
            /* frame stuck: support acceleration W = -(2 z w u' + w^2 u) against
             * the uplift threshold T = tan(alpha) g_eff */
            const double w = M->d.omega_b, c = 2.0 * M->d.zeta_b * w;
            const double W = -(c * y[M->idu] + w * w * y[M->iu]);
            const double Wd = -(c * f[M->idu] + w * w * f[M->iu]);
            const double T = M->tan_alpha * u->ge;
            const double Td = M->tan_alpha * u->ge_rate;
            const double sg =
                ev == SW_EVF_UPLIFT_BACK ? 1.0 : -1.0; /* back: W >= T; fwd: W <= -T */
            *val = sg * W - T;
            *der = sg * Wd - Td;
            return;
        }
    }
}

/* f at y, then each event function there: the event layer's one call. */
static SW_ALWAYS_INLINE void rigid_events_of(const sw_model_t *M, sw_model_scratch_t *S,
                                             sw_model_kind model, const sw_input_at_t *u,
                                             const double y[], const sw_evcand_t c[], int n,
                                             double f[], double v[], double d[])
{
    rigid_rhs_of(M, S, model, u->ag, u->ge, y, f);
    for (int i = 0; i < n; i++) rigid_event_fn(M, c[i].ev, u, y, f, &v[i], &d[i]);
}

static void bare_events(const sw_model_t *M, sw_model_scratch_t *S, const sw_input_at_t *u,
                        const double y[], const sw_evcand_t c[], int n, double f[], double v[],
                        double d[])
{
    rigid_events_of(M, S, SW_MODEL_BARE, u, y, c, n, f, v, d);
}

static void frame_events(const sw_model_t *M, sw_model_scratch_t *S, const sw_input_at_t *u,
                         const double y[], const sw_evcand_t c[], int n, double f[], double v[],
                         double d[])
{
    rigid_events_of(M, S, SW_MODEL_FRAME, u, y, c, n, f, v, d);
}

/* ---- maps and tests ------------------------------------------------------------ */

/* At theta = 0 (physics.md): theta' times the impact ratio; on a frame the
 * frame takes the momentum the package loses. */
static void bare_impact(sw_model_t *M, double y[])
{
    y[M->idth] = M->d.eta * y[M->idth];
    y[M->ith] = 0.0;
    M->side = -M->side;
}

static void frame_impact(sw_model_t *M, double y[])
{
    const double before = y[M->idth];
    const double after = M->d.r_frame * before;
    y[M->idth] = after;
    y[M->idu] += M->d.gamma * M->d.h * (before - after);
    y[M->ith] = 0.0;
    M->side = -M->side;
}

/* The rest transition is an impact whose theta'^+ is 0 (physics.md): on
 * the bed the package just stops; on a frame the frame takes its last
 * momentum, u'^+ = u'^- + gamma h theta'^-. */
static void bare_land(const sw_model_t *M, double y[])
{
    y[M->idth] = 0.0;
}

static void frame_land(const sw_model_t *M, double y[])
{
    y[M->idu] += M->d.gamma * M->d.h * y[M->idth];
    y[M->idth] = 0.0;
}

static int bare_uplift_side(const sw_model_t *M, const sw_input_at_t *u, const double y[])
{
    (void)y;
    return sw_bare_uplift_side(M, u->ag, u->ge);
}

static int frame_uplift_side(const sw_model_t *M, const sw_input_at_t *u, const double y[])
{
    return sw_frame_uplift_side(M, u->ge, y);
}

static int bare_moving(const sw_model_t *M, const double y[], double rest_eps)
{
    (void)y;
    (void)rest_eps;
    return M->phase == SW_PHASE_ROCKING;
}

static int frame_moving(const sw_model_t *M, const double y[], double rest_eps)
{
    (void)rest_eps;
    return M->phase == SW_PHASE_ROCKING ||
           (M->phase == SW_PHASE_STUCK && (fabs(y[M->iu]) > 1e-9 || fabs(y[M->idu]) > 1e-9));
}

/* ---- the report ---------------------------------------------------------------- */

/* After the common part (time, state, a_g): the support's acceleration, the
 * uplift ratio and the margins. */
static inline void rigid_output(const sw_model_t *M, const sw_model_scratch_t *S,
                                sw_model_kind model, const sw_input_at_t *u, const double y[],
                                sw_output_t *o)
{
    const double ge_in = u->ge; /* m/s^2, as the right-hand side sees it */
    /* Airborne (g + a_z <= 0): the package flies (flight.c); its energy
     * bound is judged under nominal gravity, not divided by a zero or
     * negative barrier. */
    const double ge = ge_in > 0.0 ? ge_in : M->g;
    double cA = cos_alpha(&M->d); /* cos(alpha - |theta|) */
    /* bare: the support is the bed; frame: a_g + u''.  sin and cos of
     * A1 = alpha - s theta (which is alpha - |theta| but in the instant of
     * a landing) near the right-hand side's last angle. */
    double sn = 0.0, c1 = 0.0;
    if (M->phase == SW_PHASE_ROCKING) {
        const double sth = M->side * y[M->ith];
        sincos_near(S->trig, M->d.alpha - sth, &sn, &c1);
        cA = sth >= 0.0 ? c1 : cos(M->d.alpha + sth);
    }
    o->a_support = o->a_g;
    if (model == SW_MODEL_FRAME && M->flying) {
        /* the frame rings on its own: u'' = -(c_b u' + k_b u) / m_b - a_g */
        const double mb = M->frame_mass; /* kg */
        o->a_support = -(M->d.c_b * y[M->idu] + M->d.k_b * y[M->iu]) / mb;
    } else if (model == SW_MODEL_FRAME) {
        double f[SW_NMAX];
        rigid_rhs_trig(M, SW_MODEL_FRAME, o->a_g, ge_in, y, sn, c1, f);
        o->a_support += f[M->idu];
    }
    o->uplift_ratio = fabs(o->a_support) / (M->tan_alpha * M->g);
    if (M->phase == SW_PHASE_OVERTURNED) {
        o->margin = o->margin_bound = -1.0;
        return;
    }
    if (M->phase == SW_PHASE_STUCK) {
        o->margin = 1.0;
    } else {
        const double r = model == SW_MODEL_BARE ? M->d.eta : M->d.r_frame;
        o->margin = margin_rocking_c(&M->d, r, o->state.theta, o->state.theta_dot, cA);
    }
    if (model == SW_MODEL_BARE)
        o->margin_bound = o->margin;
    else
        o->margin_bound = margin_bound_frame_c(&M->d, ge, &o->state, cA);
}

static void bare_output(const sw_model_t *M, const sw_model_scratch_t *S, const sw_input_at_t *u,
                        const double y[], sw_output_t *o)
{
    rigid_output(M, S, SW_MODEL_BARE, u, y, o);
}

static void frame_output(const sw_model_t *M, const sw_model_scratch_t *S, const sw_input_at_t *u,
                         const double y[], sw_output_t *o)
{
    rigid_output(M, S, SW_MODEL_FRAME, u, y, o);
}

/* g R (1 - cos alpha): the package's centre of mass raised over its
 * corner, whatever the frame does. */
static double rigid_barrier(const sw_derived_t *d, double g)
{
    return g * d->R * (1.0 - d->h / d->R);
}

/* In the bed's frame the input acts as the force -M a on the centre of
 * mass of everything that moves (mass M, horizontal velocity X'): on the
 * bed the block rotates about a corner, KE = (2/3) m R^2 th'^2 and
 * |X'| <= R |th'|, so X'^2 <= (3/2) KE/m; with a frame KE >= M X'^2/2,
 * M = m/gamma. */
static double bare_work_rate(const sw_derived_t *d)
{
    (void)d;
    return sqrt(3.0 / 8.0);
}

static double frame_work_rate(const sw_derived_t *d)
{
    return 1.0 / sqrt(2.0 * d->gamma);
}

/* Standing on the bed, nothing moves it without input. */
static int bare_settled(const sw_derived_t *d, double g, const sw_state_t *s)
{
    (void)d;
    (void)g;
    (void)s;
    return 1;
}

/* Standing on the frame: settled when the bearings' remaining energy
 * E = u'^2/2 + w^2 u^2/2 (per unit mass, which damping only lowers) cannot
 * drive the support's acceleration |A| = |2 z w u' + w^2 u| <=
 * (2 z w + w) sqrt(2 E) up to the uplift threshold g tan(alpha). */
static int frame_settled(const sw_derived_t *d, double g, const sw_state_t *s)
{
    const double w = d->omega_b, u = s->u, v = s->u_dot; /* rad/s, m, m/s */
    const double E = 0.5 * v * v + 0.5 * w * w * u * u;  /* J/kg */
    return (2.0 * d->zeta_b * w + w) * sqrt(2.0 * E) < g * tan(d->alpha);
}

/* The bed and the frame leave their rest contact when the support's
 * acceleration reaches g tan(alpha): an uplift ratio of 1. */
static double rigid_lift_level(const sw_derived_t *d, double g)
{
    (void)d;
    (void)g;
    return 1.0;
}

static double rigid_lift_drive(const sw_derived_t *d, double level, const sw_output_t *o)
{
    (void)d;
    (void)level;
    return o->uplift_ratio;
}

/* Standing on its frame the package moves with it: the bearings' rate. */
static void frame_probe_rates(const sw_derived_t *d, double g, double *fast, double *slow)
{
    (void)g;
    *fast = *slow = d->omega_b;
}

/* The block's rocking saddle at its fastest (|theta| = alpha): its
 * decaying root.  On a frame, that root with the least inertia factor D,
 * and the bearing mode standing and while the package rocks (model.h). */
static int bare_modes(const sw_derived_t *d, double g, sw_mode_t m[SW_MODES_MAX])
{
    (void)g;
    return sw_modes_add(m, 0, -d->p, 0.0, "rocking mode");
}

static int frame_modes(const sw_derived_t *d, double g, sw_mode_t m[SW_MODES_MAX])
{
    (void)g;
    const double D = 1.0 - 0.75 * d->gamma, w = d->omega_b, c = 2.0 * d->zeta_b * w;
    int n = sw_modes_add(m, 0, -d->p / sqrt(D), 0.0, "rocking mode");
    n = sw_modes_quadratic(m, n, 1.0, c, w * w, "bearing mode");
    return sw_modes_quadratic(m, n, D, c, w * w, "bearing mode while rocking");
}

static const sw_model_traits_t bare_traits = {
    .energy = sw_energy_bare,
    .barrier = rigid_barrier,
    .work_rate = bare_work_rate,
    .settled = bare_settled,
    .modes = bare_modes,
    .impacts = 1,
    .lift_direct = 1,
    .free_exact = 1,
    .lift_level = rigid_lift_level,
    .lift_drive = rigid_lift_drive,
};

const sw_model_ops_t sw_model_bare = {
    .name = "bare",
    .traits = &bare_traits,
    .setup = bare_setup,
    .rhs = bare_rhs,
    .fixed = SW_FIXED_RK_ROW(bare),
    .candidates = rigid_candidates,
    .events = bare_events,
    .impact = bare_impact,
    .land = bare_land,
    .uplift_side = bare_uplift_side,
    .stands = SW_STANDS_RIGID,
    .output = bare_output,
    .moving = bare_moving,
    .flies = SW_FLIES_CLOSED,
};

static const sw_model_traits_t frame_traits = {
    .energy = sw_energy_frame,
    .barrier = rigid_barrier,
    .work_rate = frame_work_rate,
    .settled = frame_settled,
    .modes = frame_modes,
    .impacts = 1,
    .stuck_linear = 1,
    .lift_level = rigid_lift_level,
    .lift_drive = rigid_lift_drive,
    .probe_rates = frame_probe_rates,
    .probe_margin = 0.99, /* linear: sampled to 3e-5 of the peak (sweep.c's pulse_lift) */
};

const sw_model_ops_t sw_model_frame = {
    .name = "frame",
    .traits = &frame_traits,
    .setup = frame_setup,
    .rhs = frame_rhs,
    .fixed = SW_FIXED_RK_ROW(frame),
    .candidates = rigid_candidates,
    .events = frame_events,
    .impact = frame_impact,
    .land = frame_land,
    .uplift_side = frame_uplift_side,
    .stands = SW_STANDS_OSCILLATOR,
    .output = frame_output,
    .moving = frame_moving,
    .flies = SW_FLIES_CLOSED,
};
