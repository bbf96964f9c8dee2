/* engine.c - the streaming integrator: advances every package to each
 * pushed sample at fixed internal steps (or GSL's adaptive steps), locates
 * events inside a step, cuts the step there, applies the event's map and
 * goes on.
 *
 * Event location (GSL has none): after a step, the endpoint values of each
 * event function are checked; a candidate crossing is confirmed on the cubic
 * Hermite interpolant of the event function over the step (values and time
 * derivatives at both ends), split into monotone pieces so that a double
 * crossing inside one step is not missed, and bracketed by bisection.  The
 * root is then polished by re-stepping from the step's start with the same
 * scheme and Newton iterations on the event function, so the event lies on
 * the scheme's own solution and the result does not depend on where the
 * sample grid falls.  Events that change the dynamics (uplift, impact,
 * overturn) cut the step; tipping (|theta| = alpha) is only timed.
 *
 * Steps are aligned to samples: each sample interval (or what is left of
 * it after an event) is split into equal steps no longer than the package's
 * step h, because the input has a kink at every sample.
 *
 * A package at rest costs almost nothing: a stuck bare block has no
 * dynamics (the uplift time is solved for on the linear input), and with
 * the fixed-step schemes a stuck frame is advanced over a whole sample
 * interval, or a gap of any length, with the exact solution of its linear
 * oscillator, uplift located on that solution.
 *
 * A package on a cushion (scene 3) moves from the start: it is never stuck
 * and never impacts.  Overturn cuts its steps, and so, for the fixed-step
 * schemes, does an edge of the base meeting the cushion's surface (a kink
 * in the contact force); tipping, the first lift of an edge (uplift) and
 * the peaks of |theta| are timed inside a step, and "rest" is checked at
 * the end of each step. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "swaywatch/model.h"
#include "swaywatch/status.h"

struct sw_engine {
    size_t n;
    sw_pkg_t *pk;
    const sw_scheme_t *scheme;
    sw_engine_opts_t o;
    double rest_eps;
    int started;
    double t;       /* s, time of the last sample */
    double ag, az;  /* m/s^2, last sample */
    sw_input_t in;  /* input over the interval being integrated */
    int events;     /* events reported during the current call */
    const double *step_y1; /* end of the step being examined (multistep schemes) */
    double step_h;         /* s, its length */
};

enum {
    EV_NONE = 0, EV_IMPACT, EV_OVERTURN, EV_UPLIFT_FWD, EV_UPLIFT_BACK, EV_TIP, EV_TURN,
    /* cushion: an edge leaves / regains the cushion (B below the surface:
     * full <-> partial contact), the last edge does (B above: partial <->
     * free flight); the _IN variants are the reverse crossings */
    EV_LIFT, EV_LIFT_IN, EV_FLY, EV_FLY_IN
};

/* ---- reporting -------------------------------------------------------- */

/* Report an event at time t with the package's current state, or with the
 * state vector y_at when the event lies inside a step (tipping). */
static void emit_at(sw_engine_t *e, sw_pkg_t *P, sw_event_kind kind, double t, double info,
                    const double *y_at)
{
    sw_event_t ev;
    sw_output_t o;
    double keep[SW_NMAX];
    if (y_at) {
        memcpy(keep, P->y, sizeof keep);
        memcpy(P->y, y_at, sizeof(double) * (size_t)P->n);
    }
    sw_model_output(P, t, &o);
    if (y_at) memcpy(P->y, keep, sizeof keep);
    ev.pkg = (size_t)(P - e->pk);
    ev.kind = kind;
    ev.t = t;
    ev.theta = o.state.theta;
    ev.theta_dot = o.state.theta_dot;
    ev.margin = o.margin;
    ev.info = info;
    if (o.margin < P->sum.min_margin) P->sum.min_margin = o.margin;
    e->events++;
    if (e->o.on_event) e->o.on_event(e->o.user, &ev);
}

static void emit(sw_engine_t *e, sw_pkg_t *P, sw_event_kind kind, double t, double info)
{
    emit_at(e, P, kind, t, info, NULL);
}

static void track_theta(sw_pkg_t *P, double th)
{
    const double a = fabs(th);
    if (a > P->sum.max_abs_theta) {
        P->sum.max_abs_theta = a;
        P->sum.max_theta_ratio = a / P->d.alpha;
    }
}

/* ---- stepping --------------------------------------------------------- */

static void herm_state(const sw_pkg_t *P, double h, const double y0[], const double f0[],
                       const double y1[], const double f1[], double tau, double yt[]);

static int step_to(sw_engine_t *e, sw_pkg_t *P, double t0, double h, const double y0[],
                   double y1[])
{
    if (!e->scheme->adaptive) {
        e->scheme->step(P, t0, h, y0, y1);
        return SW_OK;
    }
    if (e->scheme->implicit == 2) {
        /* A multistep method cannot restart from the step's start without
         * losing its history: interpolate the step being examined (cubic
         * Hermite, O(h^4)) instead of re-stepping. */
        double f0[SW_NMAX], f1[SW_NMAX];
        sw_model_rhs(t0, y0, f0, P);
        sw_model_rhs(t0 + e->step_h, e->step_y1, f1, P);
        herm_state(P, e->step_h, y0, f0, e->step_y1, f1, h / e->step_h, y1);
        return SW_OK;
    }
    double yerr[SW_NMAX];
    memcpy(y1, y0, sizeof(double) * (size_t)P->n);
    return gsl_odeiv2_step_apply(P->gstep, t0, h, y1, yerr, NULL, NULL, &P->sys) == GSL_SUCCESS
               ? SW_OK
               : SW_EGSL;
}

/* The state is still inside the model: finite, and a rocking package not
 * turned beyond half a turn (a step may overshoot pi/2 slightly before the
 * overturn event cuts it; one that lands beyond pi computed garbage, and its
 * numbers must not reach the summary). */
/* Every v[i] finite?  0 v is 0 for a finite v and NaN for an infinite or
 * NaN one, so the sum of them is 0 exactly when all are finite: two
 * multiply-adds a number and no branch, in two chains that overlap (the
 * state and the report are checked on every step and sample). */
static int all_finite(const double v[], size_t n)
{
    double s0 = 0.0, s1 = 0.0;
    size_t i = 0;
    for (; i + 1 < n; i += 2) {
        s0 += 0.0 * v[i];
        s1 += 0.0 * v[i + 1];
    }
    if (i < n) s0 += 0.0 * v[i];
    return s0 + s1 == 0.0;
}

static int finite_state(const sw_pkg_t *P, const double y[])
{
    return all_finite(y, (size_t)P->n) &&
           !(P->phase == SW_PHASE_ROCKING && fabs(y[P->ith]) > M_PI);
}

/* max and min of numbers known to be finite: inline where libm's fmax and
 * fmin are calls (they must handle NaN), for the per-step checks. */
static inline double max2(double a, double b)
{
    return a > b ? a : b;
}

static inline double min2(double a, double b)
{
    return a < b ? a : b;
}

/* ---- event functions -------------------------------------------------- */

/* Value and time derivative of event ev at (t, y) with f = y'.  Every
 * event is "the function rises through 0". */
static void event_fn(const sw_pkg_t *P, int ev, double t, const double y[], const double f[],
                     double *val, double *der)
{
    const double s = P->side;
    if (P->d.model == SW_MODEL_CUSHION) {
        /* theta changes sign smoothly on a cushion: events on theta^2 */
        const double th = y[P->ith], w = y[P->idth];
        switch (ev) {
        case EV_OVERTURN:
            *val = th * th - M_PI_2 * M_PI_2;
            *der = 2.0 * th * w;
            return;
        case EV_TIP:
            *val = th * th - P->d.alpha * P->d.alpha;
            *der = 2.0 * th * w;
            return;
        case EV_TURN: /* |theta| stops growing */
            *val = -th * w;
            *der = -(w * w + th * f[P->idth]);
            return;
        case EV_LIFT:
        case EV_LIFT_IN: {
            const double v = sw_cushion_lift(P, y, der), sg = ev == EV_LIFT ? 1.0 : -1.0;
            *val = sg * v;
            *der *= sg;
            return;
        }
        default: { /* b^2 sin^2(theta) + z |z| */
            const double b = P->d.b, sn = sin(th), z = y[P->iz];
            const double sg = ev == EV_FLY_IN ? 1.0 : -1.0; /* rises when the base flies */
            *val = sg * (b * b * sn * sn + z * fabs(z));
            *der = sg * (2.0 * b * b * sn * cos(th) * w + 2.0 * fabs(z) * y[P->idz]);
            return;
        }
        }
    }
    switch (ev) {
    case EV_IMPACT:
        *val = -s * y[P->ith];
        *der = -s * f[P->ith];
        return;
    case EV_OVERTURN:
        *val = s * y[P->ith] - M_PI_2;
        *der = s * f[P->ith];
        return;
    case EV_TIP:
        *val = s * y[P->ith] - P->d.alpha;
        *der = s * f[P->ith];
        return;
    case EV_TURN: /* the package stops swinging outward: the peak of |theta| */
        *val = -s * y[P->idth];
        *der = -s * f[P->idth];
        return;
    default: {
        /* frame stuck: support acceleration W = -(2 z w u' + w^2 u) against
         * the uplift threshold T = tan(alpha) g_eff */
        const double w = P->d.omega_b, c = 2.0 * P->d.zeta_b * w;
        const double W = -(c * y[P->idu] + w * w * y[P->iu]);
        const double Wd = -(c * f[P->idu] + w * w * f[P->iu]);
        const double T = P->tan_alpha * sw_input_geff(P, t);
        const double Td = P->in->fn ? 0.0 : P->tan_alpha * P->in->az_slope;
        const double sg = ev == EV_UPLIFT_BACK ? 1.0 : -1.0; /* back: W >= T; fwd: W <= -T */
        *val = sg * W - T;
        *der = sg * Wd - Td;
        return;
    }
    }
}

/* Cubic Hermite of a scalar over a step of length h, tau in [0, 1]. */
typedef struct {
    double c0, c1, c2, c3;
} herm_t;

static herm_t herm_make(double v0, double d0, double v1, double d1, double h)
{
    herm_t H;
    H.c0 = v0;
    H.c1 = h * d0;
    H.c2 = -3.0 * v0 - 2.0 * h * d0 + 3.0 * v1 - h * d1;
    H.c3 = 2.0 * v0 + h * d0 - 2.0 * v1 + h * d1;
    return H;
}

static double herm_at(const herm_t *H, double x)
{
    return ((H->c3 * x + H->c2) * x + H->c1) * x + H->c0;
}

/* Critical points of H inside (0, 1), sorted; returns how many (0..2). */
static int herm_crit(const herm_t *H, double x[2])
{
    const double a = 3.0 * H->c3, b = 2.0 * H->c2, c = H->c1;
    int k = 0;
    double r[2];
    if (fabs(a) < 1e-300) {
        if (fabs(b) > 1e-300) r[k++] = -c / b;
    } else {
        const double disc = b * b - 4.0 * a * c;
        if (disc >= 0.0) {
            const double q = -0.5 * (b + copysign(sqrt(disc), b));
            if (q != 0.0) r[k++] = q / a;
            if (q != 0.0) r[k++] = c / q;
            else r[k++] = 0.0;
        }
    }
    int m = 0;
    for (int i = 0; i < k; i++)
        if (r[i] > 0.0 && r[i] < 1.0) x[m++] = r[i];
    if (m == 2 && x[0] > x[1]) {
        const double tmp = x[0];
        x[0] = x[1];
        x[1] = tmp;
    }
    return m;
}

/* Earliest tau in (0, 1] where H rises through 0 from below (the caller
 * handles a function already rising at 0).  A
 * rise must reach tol, so round-off in a function that only touches 0 (a
 * package just lifted, theta = theta' = 0) is not taken for an event.
 * Returns -1 if none. */
static double herm_first_rise(const herm_t *H, double tol)
{
    double knots[4];
    int nk = 0;
    knots[nk++] = 0.0;
    double cr[2];
    const int nc = herm_crit(H, cr);
    for (int i = 0; i < nc; i++) knots[nk++] = cr[i];
    knots[nk++] = 1.0;
    for (int i = 0; i + 1 < nk; i++) {
        double a = knots[i], b = knots[i + 1];
        const double va = herm_at(H, a), vb = herm_at(H, b);
        /* A rise straight from an exact 0 at the start (a package just
         * lifted or just landed, whose true motion starts the other way by
         * construction) is the interpolant's artefact, not a crossing. */
        if (i == 0 && va == 0.0) continue;
        if (!(va <= 0.0 && vb >= tol)) continue;
        for (int it = 0; it < 64 && b - a > 1e-16; it++) { /* monotone piece */
            const double m = 0.5 * (a + b);
            if (herm_at(H, m) >= 0.0) b = m;
            else a = m;
        }
        return b;
    }
    return -1.0;
}

/* ---- one package ------------------------------------------------------ */

static void set_rest(sw_pkg_t *P)
{
    memset(P->y, 0, sizeof P->y);
    P->hold = 0;
    P->t_lift = NAN;
    P->phase = SW_PHASE_STUCK;
    P->side = 1;
    P->beyond_alpha = 0;
    if (P->d.model == SW_MODEL_CUSHION) sw_cushion_rest(P);
}

static void fault(sw_engine_t *e, sw_pkg_t *P, double t, int code)
{
    P->sum.faults++;
    set_rest(P);
    if (P->gevo) gsl_odeiv2_evolve_reset(P->gevo);
    emit(e, P, SW_EV_FAULT, t, code);
}

static void start_rocking(sw_engine_t *e, sw_pkg_t *P, double t, int side)
{
    P->phase = SW_PHASE_ROCKING;
    P->side = side;
    P->t_lift = t;
    P->y[P->ith] = P->y[P->idth] = 0.0;
    P->sum.uplifts++;
    if (isnan(P->sum.uplift_time)) P->sum.uplift_time = t;
    emit(e, P, SW_EV_UPLIFT, t, side);
}

/* After an impact: the cascade ends (rest) when the rebound energy is below
 * rest_eps of the barrier; the package then stands, or starts to rock again
 * at once if its support is still beyond the uplift threshold. */
/* Kinetic energy of theta' below rest_eps of the energy barrier? */
static int below_rest(const sw_engine_t *e, const sw_pkg_t *P, double theta_dot)
{
    const double p = P->d.p;
    return 0.5 * theta_dot * theta_dot / (p * p) < e->rest_eps * (1.0 - cos(P->d.alpha));
}

static void after_impact(sw_engine_t *e, sw_pkg_t *P, double t)
{
    if (!below_rest(e, P, P->y[P->idth])) return;
    P->y[P->idth] = 0.0;
    const int side = sw_model_uplift_side(P, t);
    if (side != 0 && t == P->t_lift) {
        /* Lifted and landed at the same instant: the support is at the
         * threshold and the step's own error pushed the package the wrong
         * way.  Hold it for one step (the support keeps moving), then look
         * again, so that time always advances. */
        P->phase = SW_PHASE_STUCK;
        P->hold = 1;
        return;
    }
    if (side == 0) {
        P->phase = SW_PHASE_STUCK;
        P->sum.rests++;
        emit(e, P, SW_EV_REST, t, 0.0);
    } else {
        P->side = side;
    }
}

/* Bare block, stuck: no dynamics.  Earliest time in [t, t1] at which the bed
 * acceleration reaches the uplift threshold, or -1; *side gets the
 * direction.  Exact for sampled (linear) input; for a function input the
 * interval is scanned at the package's step and the crossing bisected. */
static double bare_uplift_time(sw_pkg_t *P, double t, double t1, int *side)
{
    if ((*side = sw_model_uplift_side(P, t)) != 0) return t;
    const sw_input_t *in = P->in;
    if (!in->fn) {
        const double ta = P->tan_alpha;
        const double a0 = sw_input_ag(in, t), z0 = sw_input_geff(P, t);
        const double best_fwd_q0 = a0 + ta * z0, best_fwd_q1 = in->ag_slope + ta * in->az_slope;
        const double back_q0 = a0 - ta * z0, back_q1 = in->ag_slope - ta * in->az_slope;
        double tu = INFINITY;
        /* forward: a + tan(a) g_eff <= 0; back: a - tan(a) g_eff >= 0 */
        if (best_fwd_q1 < 0.0) {
            const double tc = t - best_fwd_q0 / best_fwd_q1;
            if (tc <= t1 && tc < tu) {
                tu = tc;
                *side = +1;
            }
        }
        if (back_q1 > 0.0) {
            const double tc = t - back_q0 / back_q1;
            if (tc <= t1 && tc < tu) {
                tu = tc;
                *side = -1;
            }
        }
        if (tu == INFINITY) return -1.0;
        return fmax(t, tu);
    }
    const int nsub = (int)ceil((t1 - t) / P->h - 1e-9);
    double ta = t;
    for (int i = 1; i <= (nsub > 0 ? nsub : 1); i++) {
        const double tb = i == nsub ? t1 : t + (t1 - t) * i / nsub;
        const int sb = sw_model_uplift_side(P, tb);
        if (sb != 0) {
            double lo = ta, hi = tb;
            for (int it = 0; it < 60 && hi - lo > 1e-15 * fmax(1.0, fabs(hi)); it++) {
                const double m = 0.5 * (lo + hi);
                if (sw_model_uplift_side(P, m) != 0) hi = m;
                else lo = m;
            }
            *side = sw_model_uplift_side(P, hi);
            if (*side == 0) *side = sb;
            return hi;
        }
        ta = tb;
    }
    return -1.0;
}

/* ---- stuck frame: exact advance --------------------------------------- */

/* While the package is stuck the frame is a linear oscillator,
 *   u'' + 2 zeta w u' + w^2 u = -a_g(t),
 * and between two samples a_g is linear in time, so the motion over any
 * interval has an exact solution (Nigam & Jennings 1969, the recursion of
 * earthquake response spectra).  With g(t) the response to a unit initial
 * velocity (g(0) = 0, g'(0) = 1), I1 = int_0^H g, I2 = int_0^H I1 and
 * a_g = a0 + s t over a step of length H:
 *   u(H) = (g' + 2 zeta w g) u0 + g u0' - a0 I1 - s I2
 *   u'(H) = -w^2 g u0 + g' u0' - a0 g - s I1.
 * For w H small the closed forms of I1 and I2 cancel, so they come from the
 * Taylor series of g (recurrence of the equation itself); otherwise from
 * the closed forms of the under-, critically or over-damped oscillator. */
typedef struct {
    double g, gd;   /* s, 1: g(H), g'(H) */
    double i1, i2;  /* s^2, s^3 */
} nj_t;

static void nj_coef(const sw_pkg_t *P, double H, nj_t *c)
{
    const double w = P->d.omega_b, z = P->d.zeta_b, zw = z * w, w2 = w * w;
    if (fmax(w, 2.0 * zw) * H <= 2.0) {
        /* g = sum g_k H^k / k!, g_{k+2} = -2 zeta w g_{k+1} - w^2 g_k */
        double gk = 0.0, gk1 = 1.0, tk = 1.0; /* g_k, g_{k+1}, H^k / k! */
        double sg = 0.0, sgd = 0.0, s1 = 0.0, s2 = 0.0;
        for (int k = 0; k < 60; k++) {
            const double t1 = tk * H / (k + 1), t2 = t1 * H / (k + 2);
            sg += gk * tk;
            sgd += gk1 * tk;
            s1 += gk * t1;
            s2 += gk * t2;
            if (k > 2 && fabs(gk1 * tk) <= 1e-18 * fabs(sgd) && fabs(gk * tk) <= 1e-18 * fabs(sg))
                break;
            const double gk2 = -2.0 * zw * gk1 - w2 * gk;
            gk = gk1;
            gk1 = gk2;
            tk = t1;
        }
        c->g = sg;
        c->gd = sgd;
        c->i1 = s1;
        c->i2 = s2;
        return;
    }
    const double kap = w2 * (1.0 - z) * (1.0 + z); /* 1/s^2: squared damped frequency */
    double eC, eS;                                 /* e^{-zwH} C(H), e^{-zwH} S(H) */
    if (fabs(kap) * H * H < 1e-5) {
        const double x = kap * H * H, E = exp(-zw * H);
        eC = E * (1.0 - x / 2.0 + x * x / 24.0);
        eS = E * H * (1.0 - x / 6.0 + x * x / 120.0);
    } else if (kap > 0.0) {
        const double wd = sqrt(kap), E = exp(-zw * H);
        eC = E * cos(wd * H);
        eS = E * sin(wd * H) / wd;
    } else {
        /* overdamped: rates -zw +- wo, the slow one written without cancellation */
        const double wo = w * sqrt((z - 1.0) * (z + 1.0));
        const double e1 = exp(-w2 / (zw + wo) * H), e2 = exp(-(zw + wo) * H);
        eC = 0.5 * (e1 + e2);
        eS = 0.5 * (e1 - e2) / wo;
    }
    c->g = eS;
    c->gd = eC - zw * eS;
    c->i1 = (1.0 - (c->gd + 2.0 * zw * c->g)) / w2;
    c->i2 = (H - c->g - 2.0 * zw * c->i1) / w2;
}

/* nj_coef for the sample interval: sample times such as i / 1000 give
 * intervals that differ in the last bits, so the coefficients of the last
 * interval H0 are reused for H within 1e-6 H0, corrected to first order
 * with their derivatives (g' , g'' = -2 zeta w g' - w^2 g, g, I1); the
 * second-order remainder is below 1e-12 H^2 |g''|, far under round-off. */
static void nj_coef_cached(sw_pkg_t *P, double H, nj_t *c)
{
    double *k = P->nj_cache;
    const double dH = H - k[0];
    if (!(fabs(dH) <= 1e-6 * k[0])) {
        nj_coef(P, H, c);
        k[0] = H;
        k[1] = c->g;
        k[2] = c->gd;
        k[3] = c->i1;
        k[4] = c->i2;
        return;
    }
    const double w = P->d.omega_b, zw = P->d.zeta_b * w;
    c->g = k[1] + dH * k[2];
    c->gd = k[2] + dH * (-2.0 * zw * k[2] - w * w * k[1]);
    c->i1 = k[3] + dH * k[1];
    c->i2 = k[4] + dH * k[3];
}

/* State of the stuck frame after H under a_g = a0 + s t. */
static void nj_state(const sw_pkg_t *P, const nj_t *c, double a0, double s, const double u0[2],
                     double u1[2])
{
    const double w = P->d.omega_b, zw = P->d.zeta_b * w;
    const double u = (c->gd + 2.0 * zw * c->g) * u0[0] + c->g * u0[1] - a0 * c->i1 - s * c->i2;
    const double v = -w * w * c->g * u0[0] + c->gd * u0[1] - a0 * c->g - s * c->i1;
    u1[0] = u;
    u1[1] = v;
}

/* The support's absolute acceleration is W = a_g + D, where D = u'' obeys
 * the free equation D'' + 2 zeta w D' + w^2 D = 0 (the linear input is the
 * particular solution).  D and D' after H from (D0, D0'). */
static void nj_free(const sw_pkg_t *P, const nj_t *c, const double d0[2], double d1[2])
{
    const double w = P->d.omega_b, zw = P->d.zeta_b * w;
    d1[0] = (c->gd + 2.0 * zw * c->g) * d0[0] + c->g * d0[1];
    d1[1] = -w * w * c->g * d0[0] + c->gd * d0[1];
}

/* Bound on |D| over [0, L] from (D, D') at its start: D = e^{-zw t} (D C +
 * q S) with q = D' + zw D, |e^{-zw t} C| <= 1 and |e^{-zw t} S| <= min(t,
 * 1/wd, 1/(e (zw - wo))) in the three cases. */
static double nj_bound(const sw_pkg_t *P, const double d[2], double L)
{
    const double w = P->d.omega_b, z = P->d.zeta_b, zw = z * w;
    const double kap = w * w * (1.0 - z) * (1.0 + z), q = d[1] + zw * d[0];
    double smax = L;
    if (kap > 0.0) {
        smax = fmin(smax, 1.0 / sqrt(kap));
        if (zw > 0.0) smax = fmin(smax, 1.0 / (M_E * zw));
        return fmin(fabs(d[0]) + fabs(q) * smax, sqrt(d[0] * d[0] + q * q / kap));
    }
    const double slow = w * w / (zw + w * sqrt(fmax(0.0, (z - 1.0) * (z + 1.0))));
    smax = fmin(smax, 1.0 / (M_E * slow));
    return fabs(d[0]) + fabs(q) * smax;
}

/* One direction of uplift on a piece: G = sg W - T with W = a_g + D,
 * T = tan(alpha) g_eff; value and first two derivatives at tau (from the
 * piece start, where the free part is d0). */
typedef struct {
    const sw_pkg_t *P;
    double ta;            /* s, absolute time of the piece start */
    double d0[2];         /* D, D' at ta */
    double sg;            /* +1: back (W >= T), -1: forward (W <= -T) */
} nj_piece_t;

static void nj_G(const nj_piece_t *pc, double tau, double G[3])
{
    const sw_pkg_t *P = pc->P;
    nj_t c;
    double d[2];
    nj_coef(P, tau, &c);
    nj_free(P, &c, pc->d0, d);
    const double w = P->d.omega_b, zw = P->d.zeta_b * w;
    const double t = pc->ta + tau, ta = P->tan_alpha;
    const double dd = -2.0 * zw * d[1] - w * w * d[0];
    G[0] = pc->sg * (sw_input_ag(P->in, t) + d[0]) - ta * sw_input_geff(P, t);
    G[1] = pc->sg * (P->in->ag_slope + d[1]) - ta * P->in->az_slope;
    G[2] = pc->sg * dd;
}

/* Bisect for a sign change of G[k] (k = 0 or 1) from below on [a, b]; both
 * values of the ends given.  Returns the first point found with G[k] >= 0
 * (G[0]) or the zero of G[1] from above (k = 1). */
static double nj_bisect(const nj_piece_t *pc, int k, double a, double b)
{
    for (int it = 0; it < 200; it++) {
        const double m = 0.5 * (a + b);
        if (!(m > a && m < b)) break;
        double G[3];
        nj_G(pc, m, G);
        if (k == 0 ? G[0] >= 0.0 : G[1] <= 0.0) b = m;
        else a = m;
    }
    return b;
}

/* Earliest tau in (a, b] where G reaches 0 from below, in a piece where G'
 * is monotone; -1 if none. */
static double nj_rise_mono(const nj_piece_t *pc, double a, double b)
{
    double Ga[3], Gb[3];
    nj_G(pc, a, Ga);
    nj_G(pc, b, Gb);
    if (Ga[0] >= 0.0) return a;
    double top = b;
    if (Ga[1] > 0.0 && Gb[1] < 0.0) top = nj_bisect(pc, 1, a, b); /* the maximum of G */
    else if (Ga[1] <= 0.0 && Gb[1] <= 0.0) return -1.0;             /* G falls */
    double Gt[3];
    nj_G(pc, top, Gt);
    return Gt[0] >= 0.0 ? nj_bisect(pc, 0, a, top) : -1.0;
}

/* Earliest tau in (0, L] where G reaches 0, on a piece short enough
 * (w L <= 0.5) that G'' changes sign at most once; -1 if none. */
static double nj_rise(const nj_piece_t *pc, double L)
{
    double G0[3], G1[3];
    nj_G(pc, 0.0, G0);
    nj_G(pc, L, G1);
    if ((G0[2] > 0.0) != (G1[2] > 0.0)) {
        double a = 0.0, b = L; /* split at the inflection */
        for (int it = 0; it < 200; it++) {
            const double m = 0.5 * (a + b);
            if (!(m > a && m < b)) break;
            double G[3];
            nj_G(pc, m, G);
            if ((G[2] > 0.0) == (G0[2] > 0.0)) a = m;
            else b = m;
        }
        const double r = nj_rise_mono(pc, 0.0, a);
        return r >= 0.0 ? r : nj_rise_mono(pc, a, L);
    }
    return nj_rise_mono(pc, 0.0, L);
}

/* Advance a stuck frame from P->t toward t1 under the sampled (linear)
 * input with the exact solution.  Returns the uplift time (P->t and P->y
 * are then the state there and *side the direction), or -1 with the state
 * at t1.  The uplift condition is checked exactly: on pieces of the
 * interval, a bound on the free part D rules out a crossing at once
 * (always, for a quiet road or a frame at rest across a long gap); pieces
 * it does not clear are halved down to w L <= 0.5 and searched. */
static double frame_stuck_advance(sw_pkg_t *P, double t1, int *side)
{
    const double w = P->d.omega_b, zw = P->d.zeta_b * w, ta = P->tan_alpha;
    const double s = P->in->ag_slope, small = 0.5 / w;
    if ((*side = sw_model_uplift_side(P, P->t)) != 0) return P->t;
    double y[2] = {P->y[P->iu], P->y[P->idu]};
    /* D = u'' and D' at the start */
    double d[2];
    d[0] = -(2.0 * zw * y[1] + w * w * y[0]) - sw_input_ag(P->in, P->t);
    d[1] = -2.0 * zw * d[0] - w * w * y[1] - s;
    double tp = P->t, L = t1 - tp;
    while (tp < t1) {
        const int last = L >= t1 - tp;
        if (last) L = t1 - tp;
        const double tb = last ? t1 : tp + L;
        nj_t c;
        double y1[2], d1[2];
        const double a_tp = sw_input_ag(P->in, tp), a_tb = sw_input_ag(P->in, tb);
        nj_coef_cached(P, L, &c);
        nj_state(P, &c, a_tp, s, y, y1);
        nj_free(P, &c, d, d1);
        /* Largest G = |W| - T on the piece, bounded two ways: |a_g| + |D|
         * (good over long pieces once D has decayed), and the chord of W
         * between its exact end values plus L^2/8 max|W''| with W'' = D''
         * (good over short pieces, where a_g and D nearly cancel). */
        const double T0 = ta * sw_input_geff(P, tp), T1 = ta * sw_input_geff(P, tb);
        const double dd = -2.0 * zw * d[1] - w * w * d[0]; /* D'' and its rate */
        const double ddd[2] = {dd, -2.0 * zw * dd - w * w * d[1]};
        const int clear =
            fmax(fabs(a_tp + d[0]), fabs(a_tb + d1[0])) - fmin(T0, T1) +
                    0.125 * L * L * nj_bound(P, ddd, L) < 0.0 ||
            fmax(fabs(a_tp) - T0, fabs(a_tb) - T1) + nj_bound(P, d, L) < 0.0;
        double tu = -1.0;
        if (!clear) {
            if (L > small) {
                L *= 0.5;
                continue;
            }
            for (int k = 0; k < 2; k++) {
                const nj_piece_t pc = {P, tp, {d[0], d[1]}, k == 0 ? 1.0 : -1.0};
                const double r = nj_rise(&pc, L);
                if (r >= 0.0 && (tu < 0.0 || r < tu)) tu = r;
            }
        }
        for (int it = 0; tu >= 0.0; it++) {
            /* Confirm on the state itself, as the rocking phase will see it
             * (the search works on a_g + D, which rounds differently), moving
             * on by a few ulps if needed: a package lifted a hair before the
             * crossing is pushed the wrong way and lands at once. */
            nj_t cu;
            double yu[2];
            nj_coef(P, tu, &cu);
            nj_state(P, &cu, a_tp, s, y, yu);
            P->y[P->iu] = yu[0];
            P->y[P->idu] = yu[1];
            const int now = sw_model_uplift_side(P, tp + tu);
            if (now != 0) {
                P->t = tp + tu;
                *side = now;
                return P->t;
            }
            P->y[P->iu] = y[0];
            P->y[P->idu] = y[1];
            if (tu >= L || it >= 40) break;
            tu = fmin(L, tu + 4.0 * DBL_EPSILON * fmax(1.0, fabs(tp + tu)) * (double)(1L << it));
        }
        y[0] = y1[0];
        y[1] = y1[1];
        d[0] = d1[0];
        d[1] = d1[1];
        tp = tb;
        L *= 2.0;
    }
    P->y[P->iu] = y[0];
    P->y[P->idu] = y[1];
    P->t = t1;
    return -1.0;
}

static double polish(sw_engine_t *e, sw_pkg_t *P, int ev, double t0, double h, const double y0[],
                     double tau, double y[]);

/* The peak of |theta| inside a step: where theta' changes sign before
 * tau = lim, polished by re-stepping so that max |theta| is as accurate as
 * the scheme, even for long adaptive steps. */
static void track_peak(sw_engine_t *e, sw_pkg_t *P, double t0, double h, const double y0[],
                       const double f0[], const double y1[], const double f1[], double lim)
{
    double v0, d0, v1, d1, yt[SW_NMAX];
    event_fn(P, EV_TURN, t0, y0, f0, &v0, &d0);
    event_fn(P, EV_TURN, t0 + h, y1, f1, &v1, &d1);
    const herm_t H = herm_make(v0, d0, v1, d1, h);
    const double tau = herm_first_rise(&H, 0.0);
    if (tau > 0.0 && tau <= lim) {
        polish(e, P, EV_TURN, t0, h, y0, tau, yt);
        track_theta(P, yt[P->ith]);
    }
}

/* Earliest cutting event inside the step (t0,y0) -> (t0+h,y1), with the
 * Hermite interpolants; also times the tip and tracks max |theta|. */
static int find_event_cushion(sw_engine_t *e, sw_pkg_t *P, double t0, double h,
                              const double y0[], const double y1[], double *tau_out);

static int find_event(sw_engine_t *e, sw_pkg_t *P, double t0, double h, const double y0[],
                      const double y1[], double *tau_out)
{
    if (P->d.model == SW_MODEL_CUSHION) return find_event_cushion(e, P, t0, h, y0, y1, tau_out);
    const double t1 = t0 + h;
    int cands[3], nc = 0;
    const int tipcand = P->phase == SW_PHASE_ROCKING &&
                        ((P->side * y0[P->ith] < P->d.alpha) != (P->side * y1[P->ith] < P->d.alpha));
    int maxcand = 0;
    if (P->phase == SW_PHASE_ROCKING) {
        const double s0 = P->side * y0[P->ith], s1 = P->side * y1[P->ith];
        const double v = h * max2(fabs(y0[P->idth]), fabs(y1[P->idth]));
        if (s1 <= 0.0 || min2(s0, s1) < v) cands[nc++] = EV_IMPACT;
        if (s1 >= M_PI_2 || M_PI_2 - max2(s0, s1) < v) cands[nc++] = EV_OVERTURN;
        maxcand = (y0[P->idth] > 0.0) != (y1[P->idth] > 0.0);
    } else if (P->phase == SW_PHASE_STUCK && P->d.model != SW_MODEL_BARE && !P->hold) {
        cands[nc++] = EV_UPLIFT_FWD;
        cands[nc++] = EV_UPLIFT_BACK;
    }
    if (nc == 0 && !tipcand && !maxcand) return EV_NONE;

    double f0[SW_NMAX], f1[SW_NMAX];
    sw_model_rhs(t0, y0, f0, P);
    sw_model_rhs(t1, y1, f1, P);
    int best = EV_NONE;
    double best_tau = 2.0;
    for (int i = 0; i < nc; i++) {
        double v0, d0, v1, d1;
        event_fn(P, cands[i], t0, y0, f0, &v0, &d0);
        event_fn(P, cands[i], t1, y1, f1, &v1, &d1);
        if (cands[i] >= EV_UPLIFT_FWD && v1 < 0.0 && v0 < 0.0 &&
            fmax(v0, v1) < -0.5 * h * (fabs(d0) + fabs(d1)))
            continue; /* clearly below the threshold all step */
        double tau;
        if (v0 > 0.0 || (v0 == 0.0 && d0 > 0.0)) {
            tau = 0.0; /* already through at the start of the step */
        } else {
            const herm_t H = herm_make(v0, d0, v1, d1, h);
            const double tol =
                64.0 * DBL_EPSILON * (fabs(H.c0) + fabs(H.c1) + fabs(H.c2) + fabs(H.c3));
            tau = herm_first_rise(&H, tol);
            if (tau < 0.0 && v0 < 0.0 && v1 > tol) tau = 1.0; /* round-off in the pieces */
        }
        if (tau >= 0.0 && tau < best_tau) {
            best_tau = tau;
            best = cands[i];
        }
    }
    const double lim = best == EV_NONE ? 1.0 : best_tau;
    if (maxcand) track_peak(e, P, t0, h, y0, f0, y1, f1, lim);
    if (tipcand) {
        double v0, d0, v1, d1;
        event_fn(P, EV_TIP, t0, y0, f0, &v0, &d0);
        event_fn(P, EV_TIP, t1, y1, f1, &v1, &d1);
        const herm_t H = herm_make(v0, d0, v1, d1, h);
        const double tau = herm_first_rise(&H, 0.0);
        if (tau >= 0.0 && tau <= lim) {
            const double tt = t0 + tau * h;
            double yt[SW_NMAX];
            herm_state(P, h, y0, f0, y1, f1, tau, yt);
            if (isnan(P->sum.tip_time)) P->sum.tip_time = tt;
            P->beyond_alpha = 1;
            emit_at(e, P, SW_EV_TIP, tt, P->side * P->d.alpha, yt);
        }
    }
    *tau_out = best_tau;
    return best;
}

/* State at tau in [0, 1] of the step, on the Hermite interpolants. */
static void herm_state(const sw_pkg_t *P, double h, const double y0[], const double f0[],
                       const double y1[], const double f1[], double tau, double yt[])
{
    for (int i = 0; i < P->n; i++) {
        const herm_t Hi = herm_make(y0[i], f0[i], y1[i], f1[i], h);
        yt[i] = herm_at(&Hi, tau);
    }
}

/* Earliest rise through 0 of event ev over the step, or -1. */
static double cushion_rise(const sw_pkg_t *P, int ev, double t0, double h, const double y0[],
                           const double f0[], const double y1[], const double f1[])
{
    double v0, d0, v1, d1;
    event_fn(P, ev, t0, y0, f0, &v0, &d0);
    event_fn(P, ev, t0 + h, y1, f1, &v1, &d1);
    if (v0 > 0.0 || (v0 == 0.0 && d0 > 0.0)) return 0.0;
    const herm_t H = herm_make(v0, d0, v1, d1, h);
    const double tol = 64.0 * DBL_EPSILON * (fabs(H.c0) + fabs(H.c1) + fabs(H.c2) + fabs(H.c3));
    double tau = herm_first_rise(&H, tol);
    if (tau < 0.0 && v0 < 0.0 && v1 > tol) tau = 1.0;
    return tau;
}

/* The cushion's events inside the step (t0,y0) -> (t0+h,y1): overturn, and
 * for fixed steps an edge meeting the surface, cut it (the earliest is
 * returned); the peaks of |theta| are tracked, tipping and the first lift
 * of an edge since rest are reported where they happen. */
static int find_event_cushion(sw_engine_t *e, sw_pkg_t *P, double t0, double h,
                              const double y0[], const double y1[], double *tau_out)
{
    const double t1 = t0 + h, al = P->d.alpha;
    const double a0 = fabs(y0[P->ith]), a1 = fabs(y1[P->ith]);
    const double v = h * fmax(fabs(y0[P->idth]), fabs(y1[P->idth]));
    const int ovcand = a1 >= M_PI_2 || M_PI_2 - fmax(a0, a1) < v;
    const int tipcand = a0 < al && (a1 >= al || al - fmax(a0, a1) < v);
    const int maxcand = (y0[P->ith] * y0[P->idth] > 0.0) != (y1[P->ith] * y1[P->idth] > 0.0);
    const int liftcand = isnan(P->t_lift);
    /* Where an edge of the base reaches the cushion's surface the contact
     * force has a kink (with damping, a kink in F itself): a fixed step
     * across it loses the scheme's order, so the step is cut there.  The
     * adaptive schemes' error control shortens their steps instead (a cut
     * would also restart msbdf at order 1, and chatter where a loose
     * tolerance leaves the contact unresolved). */
    const int kinks = !e->scheme->adaptive;
    if (!ovcand && !tipcand && !maxcand && !liftcand && !kinks) return EV_NONE;

    double f0[SW_NMAX], f1[SW_NMAX], yt[SW_NMAX];
    sw_model_rhs(t0, y0, f0, P);
    sw_model_rhs(t1, y1, f1, P);
    int best = EV_NONE;
    double lim = 1.0;
    if (ovcand) {
        const double tau = cushion_rise(P, EV_OVERTURN, t0, h, y0, f0, y1, f1);
        if (tau >= 0.0) {
            best = EV_OVERTURN;
            lim = tau;
        }
    }
    for (int ev = EV_LIFT; kinks && ev <= EV_FLY_IN; ev++) {
        double v0, d0, v1, d1;
        event_fn(P, ev, t0, y0, f0, &v0, &d0);
        event_fn(P, ev, t1, y1, f1, &v1, &d1);
        if (v0 > 0.0) continue; /* crossed already: we are past this kink */
        const herm_t H = herm_make(v0, d0, v1, d1, h);
        const double tol =
            64.0 * DBL_EPSILON * (fabs(H.c0) + fabs(H.c1) + fabs(H.c2) + fabs(H.c3));
        double tau = herm_first_rise(&H, tol);
        if (tau < 0.0 && v0 < 0.0 && v1 > tol) tau = 1.0;
        if (tau > 0.0 && tau < lim) {
            best = ev;
            lim = tau;
        }
    }
    if (maxcand) track_peak(e, P, t0, h, y0, f0, y1, f1, lim);
    if (tipcand) {
        const double tau = cushion_rise(P, EV_TIP, t0, h, y0, f0, y1, f1);
        if (tau >= 0.0 && tau <= lim) {
            const double tt = t0 + tau * h;
            herm_state(P, h, y0, f0, y1, f1, tau, yt);
            if (isnan(P->sum.tip_time)) P->sum.tip_time = tt;
            P->beyond_alpha = 1;
            emit_at(e, P, SW_EV_TIP, tt, (yt[P->ith] < 0.0 ? -1.0 : 1.0) * al, yt);
        }
    }
    if (liftcand) {
        const double tau = cushion_rise(P, EV_LIFT, t0, h, y0, f0, y1, f1);
        if (tau >= 0.0 && tau <= lim) {
            const double tt = t0 + tau * h;
            herm_state(P, h, y0, f0, y1, f1, tau, yt);
            /* info: +1 when the rear edge lifts (the top tips forward), -1
             * the front, 0 when the level base leaves the cushion at once */
            const double th = yt[P->ith];
            const double side = th == 0.0 ? 0.0 : th < 0.0 ? -1.0 : 1.0;
            P->t_lift = tt;
            P->sum.uplifts++;
            if (isnan(P->sum.uplift_time)) P->sum.uplift_time = tt;
            emit_at(e, P, SW_EV_UPLIFT, tt, side, yt);
        }
    }
    *tau_out = lim;
    return best;
}

/* After an accepted cushion step: side follows theta; "rest" once the
 * package, lifted before, is back in full contact with less energy than
 * it takes to lift an edge again (with no input it never will). */
static void cushion_after_step(sw_engine_t *e, sw_pkg_t *P, double t)
{
    P->side = P->y[P->ith] < 0.0 ? -1 : 1;
    if (P->phase != SW_PHASE_ROCKING || isnan(P->t_lift)) return;
    if (sw_cushion_lift(P, P->y, NULL) >= 0.0) return;
    if (sw_cushion_motion_energy(P, P->y) >= P->e_lift) return;
    P->t_lift = NAN;
    P->beyond_alpha = 0;
    P->sum.rests++;
    emit(e, P, SW_EV_REST, t, 0.0);
}

/* Polish the event time: re-step from (t0, y0) with Newton iterations on
 * the event function, then make sure the returned instant is at or just
 * past the crossing (value >= 0): an uplift placed a hair early would leave
 * the package pushed the wrong way and chatter.  Leaves the state at the
 * event in y and returns its time. */
static double polish(sw_engine_t *e, sw_pkg_t *P, int ev, double t0, double h, const double y0[],
                     double tau, double y[])
{
    double ts = t0 + tau * h, f[SW_NMAX], v = 0.0, d = 0.0;
    if (tau == 0.0) {
        memcpy(y, y0, sizeof(double) * (size_t)P->n);
        return t0;
    }
    const double t1 = t0 + h;
    for (int it = 0; it < 8; it++) {
        if (step_to(e, P, t0, ts - t0, y0, y) != SW_OK) return ts;
        sw_model_rhs(ts, y, f, P);
        event_fn(P, ev, ts, y, f, &v, &d);
        if (v == 0.0 || d == 0.0) break;
        double tn = ts - v / d;
        if (tn <= t0) tn = 0.5 * (t0 + ts);
        if (tn > t1) tn = t1;
        const double dt = fabs(tn - ts);
        if (dt <= 4.0 * DBL_EPSILON * fmax(1.0, fabs(ts))) break;
        ts = tn;
    }
    for (int it = 0; it < 8 && v < 0.0 && ts < t1; it++) {
        double dt = d > 0.0 ? -2.0 * v / d : 0.0;
        dt = fmax(dt, 8.0 * DBL_EPSILON * fmax(1.0, fabs(ts)) * (1 << it));
        ts = fmin(t1, ts + dt);
        if (step_to(e, P, t0, ts - t0, y0, y) != SW_OK) break;
        sw_model_rhs(ts, y, f, P);
        event_fn(P, ev, ts, y, f, &v, &d);
    }
    return ts;
}

static void handle_event(sw_engine_t *e, sw_pkg_t *P, int ev, double t)
{
    switch (ev) {
    case EV_IMPACT: {
        const double before = P->y[P->idth];
        if (below_rest(e, P, before)) {
            /* arriving with less than the rest energy: a landing, not an
             * impact (the step's round-off after a lift, or the end of a
             * cascade) */
            P->y[P->ith] = 0.0;
            P->y[P->idth] = 0.0;
            after_impact(e, P, t);
            break;
        }
        P->y[P->ith] = 0.0;
        sw_model_impact(P);
        P->beyond_alpha = 0;
        P->sum.impacts++;
        emit(e, P, SW_EV_IMPACT, t, before);
        after_impact(e, P, t);
        break;
    }
    case EV_OVERTURN: {
        const double rate = P->y[P->idth];
        P->y[P->ith] = P->side * M_PI_2;
        track_theta(P, M_PI_2);
        P->phase = SW_PHASE_OVERTURNED;
        P->sum.overturned = 1;
        P->sum.overturn_time = t;
        emit(e, P, SW_EV_OVERTURN, t, rate);
        for (int i = 0; i < P->n; i++)
            if (i != P->ith) P->y[i] = 0.0;
        break;
    }
    case EV_UPLIFT_FWD:
    case EV_UPLIFT_BACK:
        start_rocking(e, P, t, ev == EV_UPLIFT_FWD ? +1 : -1);
        break;
    default: break;
    }
    if (P->gevo) {
        gsl_odeiv2_evolve_reset(P->gevo);
        gsl_odeiv2_step_reset(P->gstep);
    }
}

/* The input sets the stiffness of the rocking equation: theta'' is of the
 * order kR |a| theta for an acceleration a (bed or gravity), a rate of
 * sqrt(kR |a|).  A fixed step beyond the scheme's stability bound for that
 * rate computes garbage, not a motion (states of 1e260 that still look
 * finite): a fault, not an integration.  Checked at the ends of the
 * interval, where the sampled input is largest. */
static int input_unstable(const sw_engine_t *e, const sw_pkg_t *P, double t0, double t1)
{
    if (e->scheme->adaptive) return 0; /* GSL shortens its steps itself */
    const double a = max2(max2(fabs(sw_input_ag(P->in, t0)), fabs(sw_input_ag(P->in, t1))),
                          max2(fabs(sw_input_geff(P, t0)), fabs(sw_input_geff(P, t1))));
    const double stab = e->scheme->stab;
    return !(P->kR * a * P->h * P->h <= stab * stab); /* NaN: unstable */
}

/* One fixed step from (P->t, P->y) into y1, no longer than the package's
 * step h nor than rem, splitting rem into equal steps; returns its length.
 * A cushion can pass through states far stiffer than rest (a landing on a
 * corner or flat, a cubic cushion compressed hard) where a step that is
 * stable at rest blows up or skips the landing: its right-hand side reports
 * the fastest contact rate its stages met, and the step is retaken shorter
 * until that rate times h is within the bound the package's h keeps at
 * rest (0.5, or the scheme's stability bound for a forced dt). */
static double fixed_step(sw_engine_t *e, sw_pkg_t *P, double t0, double rem, double y1[])
{
    double hmax = P->h, h = rem; /* s */
    const double bound = e->o.dt_forced ? e->scheme->stab : 0.5;
    for (int tries = 0;; tries++) {
        if (rem <= hmax) {
            h = rem; /* the common case: a step per sample */
        } else {
            const double nst = ceil(rem / hmax - 1e-9);
            h = nst <= 1.0 ? rem : rem / nst;
        }
        if (P->d.model != SW_MODEL_CUSHION) {
            e->scheme->step(P, t0, h, P->y, y1);
            return h;
        }
        P->rate_seen = 0.0;
        P->track_rate = 1;
        e->scheme->step(P, t0, h, P->y, y1);
        P->track_rate = 0;
        if (P->rate_seen * h <= bound * (1.0 + 1e-9) || tries >= 60) return h;
        hmax = fmin(0.5 * h, bound / P->rate_seen);
    }
}

/* Advance one package from P->t to t1 under the input e->in. */
static void advance_pkg(sw_engine_t *e, sw_pkg_t *P, double t1)
{
    double y1[SW_NMAX], ys[SW_NMAX];
    int guard = 0, same_t = 0, checked = 0;
    if (sw_input_geff(P, P->t) <= 0.0 || sw_input_geff(P, t1) <= 0.0) {
        /* airborne: outside the model, never integrated */
        if (P->phase != SW_PHASE_OVERTURNED) fault(e, P, P->t, SW_EFAULT);
        P->t = t1;
        return;
    }
    while (P->t < t1) {
        if (++guard > 100000000) { /* cannot happen with a finite event count */
            fault(e, P, P->t, SW_EFAULT);
            break;
        }
        if (P->phase == SW_PHASE_OVERTURNED) break;
        if (P->phase == SW_PHASE_STUCK && P->d.model == SW_MODEL_BARE) {
            int side;
            if (P->hold) { /* see after_impact: stand for one step, then look again */
                P->hold = 0;
                if (t1 - P->t <= P->h) break;
                P->t += P->h;
                continue;
            }
            const double tu = bare_uplift_time(P, P->t, t1, &side);
            if (tu < 0.0) break;
            P->t = tu;
            start_rocking(e, P, tu, side);
            if (tu >= t1) break;
            continue;
        }
        if (P->phase == SW_PHASE_STUCK && P->d.model == SW_MODEL_FRAME && !P->in->fn &&
            !P->hold && !e->scheme->adaptive && !e->o.stuck_stepped) {
            int side;
            P->sum.steps++;
            if (frame_stuck_advance(P, t1, &side) < 0.0) break;
            start_rocking(e, P, P->t, side);
            continue;
        }
        const double t0 = P->t, rem = t1 - t0;
        double h;
        if (!checked) {
            if (input_unstable(e, P, t0, t1)) {
                fault(e, P, t0, SW_EUNSTABLE);
                break;
            }
            checked = 1;
        }
        if (e->scheme->adaptive) {
            double tt = t0;
            memcpy(y1, P->y, sizeof(double) * (size_t)P->n);
            if (P->h_adapt > rem) P->h_adapt = rem;
            int st = gsl_odeiv2_evolve_apply(P->gevo, P->gctl, P->gstep, &P->sys, &tt, t1,
                                             &P->h_adapt, y1);
            if (st != GSL_SUCCESS || !(tt > t0)) {
                fault(e, P, t0, SW_EGSL);
                break;
            }
            h = tt - t0;
        } else {
            h = fixed_step(e, P, t0, rem, y1);
        }
        P->sum.steps++;
        if (!finite_state(P, y1)) {
            fault(e, P, t0, SW_EFAULT);
            break;
        }
        e->step_y1 = y1;
        e->step_h = h;
        double tau;
        const int ev = find_event(e, P, t0, h, P->y, y1, &tau);
        P->hold = 0;
        if (ev == EV_NONE) {
            memcpy(P->y, y1, sizeof(double) * (size_t)P->n);
            P->t = (h == rem) ? t1 : t0 + h;
            if (P->phase == SW_PHASE_ROCKING) track_theta(P, P->y[P->ith]);
            if (P->d.model == SW_MODEL_CUSHION) cushion_after_step(e, P, P->t);
            continue;
        }
        const double te = polish(e, P, ev, t0, h, P->y, tau, ys);
        same_t = te - t0 <= 1e-12 * fmax(1.0, fabs(t0)) ? same_t + 1 : 0;
        if (same_t > 64) { /* a map that keeps re-triggering without progress */
            fault(e, P, t0, SW_EFAULT);
            break;
        }
        memcpy(P->y, ys, sizeof(double) * (size_t)P->n);
        P->t = te;
        /* At an overturn the polished state lies just past pi/2 (by up to
         * a step's worth of theta'); the overturn map records pi/2. */
        if (P->phase == SW_PHASE_ROCKING && ev != EV_OVERTURN) track_theta(P, P->y[P->ith]);
        if (P->d.model == SW_MODEL_CUSHION) P->side = P->y[P->ith] < 0.0 ? -1 : 1;
        handle_event(e, P, ev, te);
    }
    P->t = t1;
}

int sw_output_finite(const sw_output_t *o)
{
    const double v[] = {o->t,         o->state.u,      o->state.u_dot,  o->state.theta,
                        o->state.theta_dot, o->state.z,    o->state.z_dot, o->margin,
                        o->margin_bound, o->uplift_ratio, o->a_g,          o->a_support};
    return all_finite(v, sizeof v / sizeof v[0]);
}

static void report_states(sw_engine_t *e, double t)
{
    for (size_t i = 0; i < e->n; i++) {
        sw_pkg_t *P = &e->pk[i];
        sw_output_t o;
        sw_model_output(P, t, &o);
        /* Last line of defence: a non-finite number is never reported; the
         * package faults and is reported at rest instead. */
        if (!sw_output_finite(&o)) {
            fault(e, P, t, SW_EFAULT);
            sw_model_output(P, t, &o);
        }
        o.pkg = i;
        if (o.margin < P->sum.min_margin) P->sum.min_margin = o.margin;
        if (o.margin_bound < P->sum.min_margin_bound) P->sum.min_margin_bound = o.margin_bound;
        if (o.uplift_ratio > P->sum.max_uplift_ratio) P->sum.max_uplift_ratio = o.uplift_ratio;
        if (e->o.on_state) e->o.on_state(e->o.user, &o);
    }
}

/* ---- public API ------------------------------------------------------- */

static void pkg_reset(sw_pkg_t *P)
{
    set_rest(P);
    P->t = 0.0;
    P->h_adapt = P->h;
    memset(&P->sum, 0, sizeof P->sum);
    snprintf(P->sum.name, sizeof P->sum.name, "%s", P->scene.name);
    P->sum.model = P->d.model;
    P->sum.overturn_time = P->sum.tip_time = P->sum.uplift_time = NAN;
    P->sum.min_margin = P->sum.min_margin_bound = 1.0;
    if (P->gevo) {
        gsl_odeiv2_evolve_reset(P->gevo);
        gsl_odeiv2_step_reset(P->gstep);
    }
}

void sw_engine_reset(sw_engine_t *e)
{
    if (!e) return;
    e->started = 0;
    e->t = NAN;
    e->ag = e->az = 0.0;
    memset(&e->in, 0, sizeof e->in);
    for (size_t i = 0; i < e->n; i++) pkg_reset(&e->pk[i]);
}

void sw_engine_destroy(sw_engine_t *e)
{
    if (!e) return;
    for (size_t i = 0; i < e->n; i++) {
        sw_pkg_t *P = &e->pk[i];
        if (P->gevo) gsl_odeiv2_evolve_free(P->gevo);
        if (P->gctl) gsl_odeiv2_control_free(P->gctl);
        if (P->gstep) gsl_odeiv2_step_free(P->gstep);
    }
    free(e->pk);
    free(e);
}

static int fail(int *err, int code, char *msg, size_t msglen, const char *text)
{
    if (err) *err = code;
    if (msg && msglen) snprintf(msg, msglen, "%s", text);
    return code;
}

/* The scheme when none is asked for: rk4 at its default step, unless a
 * cushion is stiff, omega_max dt > 0.05 (a landing on the cushion then
 * lasts fewer than about 20 fixed steps and rk4's error there grows to
 * 1e-5..1e-3 rad); then GSL's adaptive rkck, which was the fastest for a
 * given accuracy on every stiff cushion measured, ahead of the implicit
 * schemes and far ahead of sub-stepped rk4 (docs/cushion.md).  A forced dt
 * keeps rk4, so that the dt is honoured or refused. */
static const char *default_scheme(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *o)
{
    if (o->dt_forced) return SW_DEFAULT_SCHEME;
    const double dt = o->dt > 0.0 ? o->dt : SW_DEFAULT_DT; /* s */
    for (size_t i = 0; i < n; i++) {
        sw_derived_t d;
        if (sw_scene_validate(&scenes[i], &d, NULL, NULL, NULL) != SW_OK) continue;
        if (d.model == SW_MODEL_CUSHION && d.omega_max * dt > SW_STIFF_OMEGA_DT)
            return SW_STIFF_SCHEME;
    }
    return SW_DEFAULT_SCHEME;
}

sw_engine_t *sw_engine_create(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *opts,
                              int *err, char *msg, size_t msglen)
{
    char buf[512];
    if (err) *err = SW_OK;
    if (msg && msglen) msg[0] = '\0';
    if (!scenes || n == 0) {
        fail(err, SW_EINVAL, msg, msglen, "no scene");
        return NULL;
    }
    sw_engine_t *e = calloc(1, sizeof *e);
    if (!e || !(e->pk = calloc(n, sizeof *e->pk))) {
        free(e);
        fail(err, SW_ENOMEM, msg, msglen, "out of memory");
        return NULL;
    }
    e->n = n;
    if (opts) e->o = *opts;
    if (e->o.accuracy != 0.0) {
        if (e->o.scheme || e->o.dt != 0.0 || !(e->o.accuracy > 0.0)) {
            fail(err, SW_EINVAL, msg, msglen,
                 "accuracy must be > 0 and chooses the scheme and the step: give it without "
                 "scheme and dt");
            goto out_fail;
        }
        size_t bad = 0;
        const int r = sw_scheme_for_accuracy_n(scenes, n, e->o.accuracy, &e->o.scheme, &e->o.dt,
                                               &bad);
        if (r != SW_OK) {
            snprintf(buf, sizeof buf, "accuracy %g rad, scene '%s': %s", e->o.accuracy,
                     scenes[bad].name,
                     r == SW_ENOTFOUND ? "tighter than any measured setting reaches (about "
                                         "1e-14 rad); choose the scheme rk8pd and rtol instead"
                                       : "no measured table for this model; choose the scheme "
                                         "and dt or rtol instead");
            fail(err, r, msg, msglen, buf);
            goto out_fail;
        }
        e->o.dt_forced = 0;
        e->o.accuracy = 0.0; /* resolved: e->o now names the scheme (sw_engine_replace) */
    }
    e->scheme = sw_scheme_lookup(e->o.scheme ? e->o.scheme : default_scheme(scenes, n, &e->o));
    if (!e->scheme) {
        snprintf(buf, sizeof buf, "unknown scheme '%s'", e->o.scheme);
        fail(err, SW_ENOTFOUND, msg, msglen, buf);
        goto out_fail;
    }
    if (e->o.dt < 0.0 || !isfinite(e->o.dt) || e->o.rtol < 0.0 || e->o.atol < 0.0 ||
        e->o.rest_eps < 0.0) {
        fail(err, SW_EINVAL, msg, msglen, "dt, rtol, atol and rest_eps must be >= 0");
        goto out_fail;
    }
    e->rest_eps = e->o.rest_eps > 0.0 ? e->o.rest_eps : 1e-9;
    const double dt = e->o.dt > 0.0 ? e->o.dt : e->scheme->default_dt;
    for (size_t i = 0; i < n; i++) {
        sw_pkg_t *P = &e->pk[i];
        P->scene = scenes[i];
        if (sw_scene_validate(&P->scene, &P->d, NULL, NULL, NULL) != SW_OK) {
            snprintf(buf, sizeof buf, "scene '%s' is not valid", scenes[i].name);
            fail(err, SW_EINVAL, msg, msglen, buf);
            goto out_fail;
        }
        sw_model_setup(P);
        P->in = &e->in;
        P->h = dt;
        if (!e->scheme->adaptive && P->d.omega_max > 0.0) {
            const double bound = e->scheme->stab / P->d.omega_max; /* s */
            if (e->o.dt_forced && dt > bound) {
                snprintf(buf, sizeof buf,
                         "scene '%s': dt = %g s gives omega*dt = %.3g, above the %s stability "
                         "bound %.3g for the scene's fastest frequency omega = %.4g rad/s "
                         "(use dt <= %.3g s)",
                         scenes[i].name, dt, P->d.omega_max * dt, e->scheme->name,
                         e->scheme->stab, P->d.omega_max, bound);
                fail(err, SW_EUNSTABLE, msg, msglen, buf);
                goto out_fail;
            }
            /* Sub-step so that omega_max h <= 0.5: inside every explicit
             * scheme's stability bound, and accurate enough for the fast
             * bearing mode that decides uplift. */
            if (!e->o.dt_forced && P->h > 0.5 / P->d.omega_max) P->h = 0.5 / P->d.omega_max;
        }
        P->sys.function = sw_model_rhs;
        P->sys.jacobian = e->scheme->implicit ? sw_model_jacobian : NULL;
        P->sys.dimension = (size_t)P->n;
        P->sys.params = P;
        if (e->scheme->adaptive) {
            const double rtol = e->o.rtol > 0.0 ? e->o.rtol : 1e-10;
            double atol = e->o.atol > 0.0 ? e->o.atol : 1e-12;
            if (P->d.model == SW_MODEL_CUSHION) {
                /* resolve the contact: an absolute tolerance above the
                 * static deflection (m) or the lift angle z_s/b (rad) of
                 * a very stiff cushion would leave it to noise */
                const double zs = P->yscale[P->iz];
                atol = fmin(atol, 1e-3 * fmin(zs, zs / P->d.b));
            }
            P->gstep = gsl_odeiv2_step_alloc(*e->scheme->gsl_type, (size_t)P->n);
            P->gctl = gsl_odeiv2_control_y_new(atol, rtol);
            P->gevo = gsl_odeiv2_evolve_alloc((size_t)P->n);
            if (!P->gstep || !P->gctl || !P->gevo) {
                fail(err, SW_ENOMEM, msg, msglen, "out of memory");
                goto out_fail;
            }
            if (e->scheme->implicit) {
                /* GSL's implicit steppers read their Newton tolerances from
                 * the control through a driver (without one they fail with
                 * GSL_EFAULT): hand them one that only points at ours */
                P->gdrv = (gsl_odeiv2_driver){.sys = &P->sys, .s = P->gstep, .c = P->gctl,
                                              .e = P->gevo, .h = P->h, .hmax = DBL_MAX};
                gsl_odeiv2_step_set_driver(P->gstep, &P->gdrv);
            }
        }
    }
    sw_engine_reset(e);
    return e;
out_fail:
    sw_engine_destroy(e);
    return NULL;
}

/* A first sample already beyond the threshold lifts a bare block at once. */
static void initial_uplift(sw_engine_t *e, sw_pkg_t *P, double t)
{
    P->t = t;
    if (!(sw_input_geff(P, t) > 0.0)) {
        fault(e, P, t, SW_EFAULT);
        return;
    }
    if (P->d.model != SW_MODEL_BARE || P->phase != SW_PHASE_STUCK) return;
    const int side = sw_model_uplift_side(P, t);
    if (side) start_rocking(e, P, t, side);
}

static void start_at(sw_engine_t *e, double t, double ag, double az)
{
    e->started = 1;
    e->t = t;
    e->ag = ag;
    e->az = az;
    e->in = (sw_input_t){.t0 = t, .ag0 = ag, .az0 = az};
    for (size_t i = 0; i < e->n; i++) initial_uplift(e, &e->pk[i], t);
}

int sw_engine_push(sw_engine_t *e, double t, double a_g, double a_z)
{
    if (!e) return SW_EINVAL;
    if (!isfinite(t) || !isfinite(a_g) || !isfinite(a_z)) return SW_ENONFINITE;
    if (fabs(a_g) > SW_MAX_ACCEL || fabs(a_z) > SW_MAX_ACCEL) return SW_ETOOBIG;
    e->events = 0;
    if (!e->started) {
        start_at(e, t, a_g, a_z);
        report_states(e, t);
        return e->events ? SW_EVENT : SW_OK;
    }
    if (!(t > e->t)) return SW_EORDER;
    const double span = t - e->t;
    e->in = (sw_input_t){.t0 = e->t,
                         .ag0 = e->ag,
                         .ag_slope = (a_g - e->ag) / span,
                         .az0 = e->az,
                         .az_slope = (a_z - e->az) / span};
    for (size_t i = 0; i < e->n; i++) advance_pkg(e, &e->pk[i], t);
    e->t = t;
    e->ag = a_g;
    e->az = a_z;
    e->in = (sw_input_t){.t0 = t, .ag0 = a_g, .az0 = a_z};
    report_states(e, t);
    return e->events ? SW_EVENT : SW_OK;
}

int sw_engine_advance_fn(sw_engine_t *e, double t1, sw_input_fn f, void *user)
{
    if (!e || !f || !isfinite(t1)) return SW_EINVAL;
    e->events = 0;
    e->in = (sw_input_t){.fn = f, .fn_user = user};
    if (!e->started) {
        e->started = 1;
        e->t = 0.0;
        for (size_t i = 0; i < e->n; i++) initial_uplift(e, &e->pk[i], 0.0);
    }
    if (!(t1 > e->t)) return t1 == e->t ? SW_OK : SW_EORDER;
    for (size_t i = 0; i < e->n; i++) advance_pkg(e, &e->pk[i], t1);
    e->t = t1;
    e->ag = f(user, t1);
    e->az = 0.0;
    report_states(e, t1);
    e->in = (sw_input_t){.t0 = t1, .ag0 = e->ag};
    return e->events ? SW_EVENT : SW_OK;
}

static double zero_input(void *user, double t)
{
    (void)user;
    (void)t;
    return 0.0;
}

/* A cushioned package whose energy of motion is below rest_eps of the
 * barrier: settled, for sw_engine_finish(). */
static int cushion_quiet(const sw_engine_t *e, const sw_pkg_t *P)
{
    if (P->d.model != SW_MODEL_CUSHION) return 0;
    return sw_cushion_motion_energy(P, P->y) < e->rest_eps * sw_cushion_barrier(&P->d, P->g);
}

int sw_engine_finish(sw_engine_t *e, double settle)
{
    if (!e) return SW_EINVAL;
    int any = 0;
    if (!(settle > 0.0) || !e->started) return SW_OK;
    const double t_end = e->t + settle;
    const double chunk = 1e-3; /* s, state reports while settling */
    while (e->t < t_end) {
        int moving = 0;
        for (size_t i = 0; i < e->n; i++)
            if ((e->pk[i].phase == SW_PHASE_ROCKING && !cushion_quiet(e, &e->pk[i])) ||
                (e->pk[i].phase == SW_PHASE_STUCK && e->pk[i].d.model != SW_MODEL_BARE &&
                 (fabs(e->pk[i].y[e->pk[i].iu]) > 1e-9 || fabs(e->pk[i].y[e->pk[i].idu]) > 1e-9)))
                moving = 1;
        if (!moving) break;
        const double tn = fmin(t_end, e->t + chunk);
        if (sw_engine_advance_fn(e, tn, zero_input, NULL) == SW_EVENT) any = 1;
    }
    return any ? SW_EVENT : SW_OK;
}

int sw_engine_set_state(sw_engine_t *e, size_t pkg, const sw_state_t *s)
{
    if (!e || pkg >= e->n || !s) return SW_EINVAL;
    sw_pkg_t *P = &e->pk[pkg];
    sw_model_from_state(P, s);
    P->beyond_alpha = fabs(P->y[P->ith]) >= P->d.alpha;
    if (P->gevo) {
        gsl_odeiv2_evolve_reset(P->gevo);
        gsl_odeiv2_step_reset(P->gstep);
    }
    return SW_OK;
}

int sw_engine_get_output(const sw_engine_t *e, size_t pkg, sw_output_t *out)
{
    if (!e || pkg >= e->n || !out) return SW_EINVAL;
    const sw_pkg_t *P = &e->pk[pkg];
    sw_model_output(P, e->started ? e->t : 0.0, out);
    out->pkg = pkg;
    return SW_OK;
}

size_t sw_engine_count(const sw_engine_t *e)
{
    return e ? e->n : 0;
}

double sw_engine_time(const sw_engine_t *e)
{
    return e && e->started ? e->t : NAN;
}

const sw_derived_t *sw_engine_derived(const sw_engine_t *e, size_t pkg)
{
    return e && pkg < e->n ? &e->pk[pkg].d : NULL;
}

int sw_engine_summary(const sw_engine_t *e, size_t pkg, sw_summary_t *s)
{
    if (!e || pkg >= e->n || !s) return SW_EINVAL;
    *s = e->pk[pkg].sum;
    return SW_OK;
}

const char *sw_engine_scheme(const sw_engine_t *e)
{
    return e ? e->scheme->name : NULL;
}

double sw_engine_dt(const sw_engine_t *e, size_t pkg)
{
    return e && pkg < e->n ? e->pk[pkg].h : NAN;
}

const char *sw_event_name(sw_event_kind k)
{
    switch (k) {
    case SW_EV_UPLIFT: return "uplift";
    case SW_EV_IMPACT: return "impact";
    case SW_EV_REST: return "rest";
    case SW_EV_TIP: return "tip";
    case SW_EV_OVERTURN: return "overturn";
    case SW_EV_FAULT: return "fault";
    }
    return "unknown";
}

/* ---- replacing one package ---------------------------------------------- */

static void pkg_free(sw_pkg_t *P)
{
    if (P->gevo) gsl_odeiv2_evolve_free(P->gevo);
    if (P->gctl) gsl_odeiv2_control_free(P->gctl);
    if (P->gstep) gsl_odeiv2_step_free(P->gstep);
}

/* The new package is built by sw_engine_create() itself (one scene, same
 * options), so it is checked and set up exactly like the others, then moved
 * into place.  Its GSL work space moves with it; the pointers that lead
 * back into the package or its engine (the input, the ODE system's
 * parameters, an implicit stepper's driver) are set again. */
int sw_engine_replace(sw_engine_t *e, size_t pkg, const sw_scene_t *scene, char *msg,
                      size_t msglen)
{
    if (msg && msglen) msg[0] = '\0';
    if (!e || !scene || pkg >= e->n) {
        if (msg && msglen) snprintf(msg, msglen, "no such package");
        return SW_EINVAL;
    }
    int err = SW_OK;
    sw_engine_opts_t o = e->o;
    o.on_event = NULL;
    o.on_state = NULL;
    sw_engine_t *tmp = sw_engine_create(scene, 1, &o, &err, msg, msglen);
    if (!tmp) return err != SW_OK ? err : SW_ENOMEM;

    sw_pkg_t *P = &e->pk[pkg];
    pkg_free(P);
    *P = tmp->pk[0];
    P->in = &e->in;
    P->sys.params = P;
    if (P->gstep && P->gdrv.s) {
        P->gdrv.sys = &P->sys;
        gsl_odeiv2_step_set_driver(P->gstep, &P->gdrv);
    }
    P->t = e->started ? e->t : 0.0;
    free(tmp->pk);
    free(tmp);
    return SW_OK;
}
