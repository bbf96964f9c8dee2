/* SPDX-License-Identifier: GPL-3.0-or-later */
/* stuck.c - exact solutions of a package standing on its support, so that a
 * package at rest costs almost nothing, as its model stands (ops->stands):
 * a block stuck on the bed has no dynamics (the uplift time is solved for
 * on the linear input), and with the fixed-step schemes a package stuck on
 * its frame is advanced over a whole sample interval, or a gap of any
 * length, with the exact solution of the frame's linear oscillator, uplift
 * located on that solution.  Needs only the package's parameters and the
 * input; the phase machine does what follows an uplift. */
#include <float.h>
#include <math.h>

#include "input.h"
#include "model_ops.h"
#include "model_rigid.h"
#include "numeric.h"
#include "pkg.h"
#include "stuck.h"

/* The input at t: the engine's value at an end of the interval (X) when t
 * is one, else evaluated here. */
static inline sw_input_at_t input_at(const sw_pkg_t *P, const sw_input_ends_t *X, double t)
{
    if (t == X->t[0])
        return X->u[0];
    if (t == X->t[1])
        return X->u[1];
    return sw_input_at(P->m.in, P->m.g, t);
}

/* The bare block's uplift side at t (s), under the input there. */
static inline int bare_side(const sw_pkg_t *P, double t)
{
    return sw_bare_uplift_side(&P->m, sw_input_ag(P->m.in, t), sw_input_geff(P->m.in, P->m.g, t));
}

/* Bare block, stuck: no dynamics.  Earliest time in [t, t1] at which the bed
 * acceleration reaches the uplift threshold (u: the input at t), or -1;
 * *side gets the direction.  Exact for sampled (linear) input; for a
 * function input the interval is scanned at the package's step and the
 * crossing bisected. */
static double bare_uplift(const sw_pkg_t *P, const sw_input_ends_t *X, double t, double t1,
                          int *side)
{
    const sw_input_at_t u = input_at(P, X, t);
    if ((*side = sw_bare_uplift_side(&P->m, u.ag, u.ge)) != 0)
        return t;
    const sw_input_t *in = P->m.in;
    if (!in->fn) {
        const double ta = P->m.tan_alpha;
        const double a0 = u.ag, z0 = u.ge;
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
        if (tu == INFINITY)
            return -1.0;
        /* the threshold tan(alpha) g_eff reached with g_eff itself at 0:
         * the bed falls away, the package leaves level (a take-off, the
         * engine's), it does not tip to a side */
        if (!(sw_input_geff(P->m.in, P->m.g, fmax(t, tu)) > 1e-9 * P->m.g))
            return -1.0;
        return fmax(t, tu);
    }
    /* (capped: a scan of more than 1e8 pieces is a caller's absurd
     * interval, and the count must stay an int) */
    const double pieces = ceil((t1 - t) / P->st.h - 1e-9);
    const int nsub = pieces < 1e8 ? (int)pieces : 100000000;
    double ta = t;
    for (int i = 1; i <= (nsub > 0 ? nsub : 1); i++) {
        const double tb = i == nsub ? t1 : t + (t1 - t) * i / nsub;
        const int sb = bare_side(P, tb);
        if (sb != 0) {
            double lo = ta, hi = tb;
            for (int it = 0; it < 60 && hi - lo > 1e-15 * fmax(1.0, fabs(hi)); it++) {
                const double m = 0.5 * (lo + hi);
                if (bare_side(P, m) != 0)
                    hi = m;
                else
                    lo = m;
            }
            *side = bare_side(P, hi);
            if (*side == 0)
                *side = sb;
            return hi;
        }
        ta = tb;
    }
    return -1.0;
}

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
    double g, gd;  /* s, 1: g(H), g'(H) */
    double i1, i2; /* s^2, s^3 */
} nj_t;

static void nj_coef_wz(double w, double z, double H, nj_t *c)
{
    const double zw = z * w, w2 = w * w;
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

static void nj_coef(const sw_pkg_t *P, double H, nj_t *c)
{
    nj_coef_wz(P->m.d.omega_b, P->m.d.zeta_b, H, c);
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
    const double w = P->m.d.omega_b, zw = P->m.d.zeta_b * w;
    c->g = k[1] + dH * k[2];
    c->gd = k[2] + dH * (-2.0 * zw * k[2] - w * w * k[1]);
    c->i1 = k[3] + dH * k[1];
    c->i2 = k[4] + dH * k[3];
}

/* State of the oscillator (w, z) after H under a_g = a0 + s t. */
static void nj_state_wz(double w, double z, const nj_t *c, double a0, double s, const double u0[2],
                        double u1[2])
{
    const double zw = z * w;
    const double u = (c->gd + 2.0 * zw * c->g) * u0[0] + c->g * u0[1] - a0 * c->i1 - s * c->i2;
    const double v = -w * w * c->g * u0[0] + c->gd * u0[1] - a0 * c->g - s * c->i1;
    u1[0] = u;
    u1[1] = v;
}

/* State of the stuck frame after H under a_g = a0 + s t. */
static void nj_state(const sw_pkg_t *P, const nj_t *c, double a0, double s, const double u0[2],
                     double u1[2])
{
    nj_state_wz(P->m.d.omega_b, P->m.d.zeta_b, c, a0, s, u0, u1);
}

void sw_nj_step(double w, double zeta, double H, double a0, double s, const double u0[2],
                double u1[2])
{
    nj_t c;
    nj_coef_wz(w, zeta, H, &c);
    nj_state_wz(w, zeta, &c, a0, s, u0, u1);
}

/* The support's absolute acceleration is W = a_g + D, where D = u'' obeys
 * the free equation D'' + 2 zeta w D' + w^2 D = 0 (the linear input is the
 * particular solution).  D and D' after H from (D0, D0'). */
static void nj_free(const sw_pkg_t *P, const nj_t *c, const double d0[2], double d1[2])
{
    const double w = P->m.d.omega_b, zw = P->m.d.zeta_b * w;
    d1[0] = (c->gd + 2.0 * zw * c->g) * d0[0] + c->g * d0[1];
    d1[1] = -w * w * c->g * d0[0] + c->gd * d0[1];
}

/* Bound on |D| over [0, L] from (D, D') at its start: D = e^{-zw t} (D C +
 * q S) with q = D' + zw D, |e^{-zw t} C| <= 1 and |e^{-zw t} S| <= min(t,
 * 1/wd, 1/(e (zw - wo))) in the three cases. */
static double nj_bound(const sw_pkg_t *P, const double d[2], double L)
{
    const double w = P->m.d.omega_b, z = P->m.d.zeta_b, zw = z * w;
    const double kap = w * w * (1.0 - z) * (1.0 + z), q = d[1] + zw * d[0];
    double smax = L;
    if (kap > 0.0) {
        smax = fmin(smax, 1.0 / sqrt(kap));
        if (zw > 0.0)
            smax = fmin(smax, 1.0 / (M_E * zw));
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
    double ta;    /* s, absolute time of the piece start */
    double d0[2]; /* D, D' at ta */
    double sg;    /* +1: back (W >= T), -1: forward (W <= -T) */
} nj_piece_t;

static void nj_G(const nj_piece_t *pc, double tau, double G[3])
{
    const sw_pkg_t *P = pc->P;
    nj_t c;
    double d[2];
    nj_coef(P, tau, &c);
    nj_free(P, &c, pc->d0, d);
    const double w = P->m.d.omega_b, zw = P->m.d.zeta_b * w;
    const double t = pc->ta + tau, ta = P->m.tan_alpha;
    const double dd = -2.0 * zw * d[1] - w * w * d[0];
    G[0] = pc->sg * (sw_input_ag(P->m.in, t) + d[0]) - ta * sw_input_geff(P->m.in, P->m.g, t);
    G[1] = pc->sg * (P->m.in->ag_slope + d[1]) - ta * P->m.in->az_slope;
    G[2] = pc->sg * dd;
}

/* Bisect for a sign change of G[k] (k = 0 or 1) from below on [a, b]; both
 * values of the ends given.  Returns the first point found with G[k] >= 0
 * (G[0]) or the zero of G[1] from above (k = 1). */
static double nj_bisect(const nj_piece_t *pc, int k, double a, double b)
{
    for (int it = 0; it < 200; it++) {
        const double m = 0.5 * (a + b);
        if (!(m > a && m < b))
            break;
        double G[3];
        nj_G(pc, m, G);
        if (k == 0 ? G[0] >= 0.0 : G[1] <= 0.0)
            b = m;
        else
            a = m;
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
    if (Ga[0] >= 0.0)
        return a;
    double top = b;
    if (Ga[1] > 0.0 && Gb[1] < 0.0)
        top = nj_bisect(pc, 1, a, b); /* the maximum of G */
    else if (Ga[1] <= 0.0 && Gb[1] <= 0.0)
        return -1.0; /* G falls */
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
            if (!(m > a && m < b))
                break;
            double G[3];
            nj_G(pc, m, G);
            if ((G[2] > 0.0) == (G0[2] > 0.0))
                a = m;
            else
                b = m;
        }
        const double r = nj_rise_mono(pc, 0.0, a);
        return r >= 0.0 ? r : nj_rise_mono(pc, a, L);
    }
    return nj_rise_mono(pc, 0.0, L);
}

/* The uplift found tu (s) into the piece at tp of length L (s), from the
 * state y = (u, u') at tp under input a_tp + s t: confirm it on the state
 * itself, as the rocking phase will see it (the search works on a_g + D,
 * which rounds differently), moving on by a few ulps if needed: a package
 * lifted a hair before the crossing is pushed the wrong way and lands at
 * once.  1 with P->t, P->y and *side at the uplift; 0 with P->y as it
 * was. */
static int confirm_uplift(sw_pkg_t *P, double tp, double tu, double L, const double y[2],
                          double a_tp, int *side)
{
    const double s = P->m.in->ag_slope;
    for (int it = 0;; it++) {
        nj_t cu;
        double yu[2];
        nj_coef(P, tu, &cu);
        nj_state(P, &cu, a_tp, s, y, yu);
        P->y[P->m.iu] = yu[0];
        P->y[P->m.idu] = yu[1];
        const int now = sw_frame_uplift_side(&P->m, sw_input_geff(P->m.in, P->m.g, tp + tu), P->y);
        if (now != 0) {
            P->t = tp + tu;
            *side = now;
            return 1;
        }
        P->y[P->m.iu] = y[0];
        P->y[P->m.idu] = y[1];
        if (tu >= L || it >= 40)
            return 0;
        tu = fmin(L, tu + 4.0 * DBL_EPSILON * fmax(1.0, fabs(tp + tu)) * (double)(1L << it));
    }
}

/* Advance a stuck frame from P->t toward t1 under the sampled (linear)
 * input with the exact solution.  Returns the uplift time (P->t and P->y
 * are then the state there and *side the direction), -1 with the state
 * at t1, or -2 when it cannot make progress.  The uplift condition is checked exactly: on pieces of
 * the interval, a bound on the free part D rules out a crossing at once (always, for a quiet road
 * or a frame at rest across a long gap); pieces it does not clear are halved down to w L <= 0.5 and
 * searched. */
static SW_ALWAYS_INLINE double frame_advance(sw_pkg_t *P, const sw_input_ends_t *X, double t1,
                                             int *side)
{
    const double w = P->m.d.omega_b, zw = P->m.d.zeta_b * w, ta = P->m.tan_alpha;
    const double s = P->m.in->ag_slope, small = 0.5 / w;
    const sw_input_at_t u = input_at(P, X, P->t);
    if ((*side = sw_frame_uplift_side(&P->m, u.ge, P->y)) != 0)
        return P->t;
    double y[2] = {P->y[P->m.iu], P->y[P->m.idu]};
    /* D = u'' and D' at the start */
    double d[2];
    d[0] = -(2.0 * zw * y[1] + w * w * y[0]) - u.ag;
    d[1] = -2.0 * zw * d[0] - w * w * y[1] - s;
    double tp = P->t, L = t1 - tp;
    long pieces = 0;
    while (tp < t1) {
        /* Each piece moves on or halves down to w L = 0.5, so an interval T
         * takes at most about 2 w T pieces; ten million (days bridged) or a
         * piece that cannot move tp (an interval beyond the arithmetic's
         * resolution) is a fault, never a hang (-2). */
        if (++pieces > 10000000L)
            return -2.0;
        const int last = L >= t1 - tp;
        if (last)
            L = t1 - tp;
        const double tb = last ? t1 : tp + L;
        if (!(tb > tp))
            return -2.0;
        nj_t c;
        double y1[2], d1[2];
        const sw_input_at_t up = input_at(P, X, tp), ub = input_at(P, X, tb);
        const double a_tp = up.ag, a_tb = ub.ag;
        nj_coef_cached(P, L, &c);
        nj_state(P, &c, a_tp, s, y, y1);
        nj_free(P, &c, d, d1);
        /* Largest G = |W| - T on the piece, bounded two ways: |a_g| + |D|
         * (good over long pieces once D has decayed), and the chord of W
         * between its exact end values plus L^2/8 max|W''| with W'' = D''
         * (good over short pieces, where a_g and D nearly cancel). */
        const double T0 = ta * up.ge, T1 = ta * ub.ge;
        const double dd = -2.0 * zw * d[1] - w * w * d[0]; /* D'' and its rate */
        const double ddd[2] = {dd, -2.0 * zw * dd - w * w * d[1]};
        const int clear = fmax(fabs(a_tp + d[0]), fabs(a_tb + d1[0])) - fmin(T0, T1) +
                                  0.125 * L * L * nj_bound(P, ddd, L) <
                              0.0 ||
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
                if (r >= 0.0 && (tu < 0.0 || r < tu))
                    tu = r;
            }
        }
        if (tu >= 0.0 && confirm_uplift(P, tp, tu, L, y, a_tp, side))
            return P->t;
        y[0] = y1[0];
        y[1] = y1[1];
        d[0] = d1[0];
        d[1] = d1[1];
        tp = tb;
        L *= 2.0;
    }
    P->y[P->m.iu] = y[0];
    P->y[P->m.idu] = y[1];
    P->t = t1;
    return -1.0;
}

/* The bare block: stands until the input reaches the threshold. */
static int stuck_bare(sw_pkg_t *P, const sw_input_ends_t *X, double t1, int exact, int *side)
{
    (void)exact;
    if (P->m.held) { /* see pkg.c's after_impact: stand for one step, then look again */
        P->m.held = 0;
        if (t1 - P->t <= P->st.h)
            return SW_STUCK_STILL;
        P->t += P->st.h;
        return SW_STUCK_MOVED;
    }
    const double tu = bare_uplift(P, X, P->t, t1, side);
    if (tu < 0.0)
        return SW_STUCK_STILL;
    P->t = tu;
    return SW_STUCK_LIFT;
}

/* The exact solution serves sampled input under the fixed-step schemes;
 * pulses (a function input), a package held for a step, the adaptive
 * schemes and comparisons (stuck_stepped) step the stuck frame. */
static int stuck_frame(sw_pkg_t *P, const sw_input_ends_t *X, double t1, int exact, int *side)
{
    if (P->m.in->fn || P->m.held || !exact)
        return SW_STUCK_STEP;
    P->sum.steps++;
    const double tu = frame_advance(P, X, t1, side);
    return tu >= 0.0 ? SW_STUCK_LIFT : tu == -1.0 ? SW_STUCK_STILL : SW_STUCK_FAULT;
}

const sw_stuck_fn sw_stuck_advance[SW_STANDS_KINDS] = {
    [SW_STANDS_RIGID] = stuck_bare,
    [SW_STANDS_OSCILLATOR] = stuck_frame,
};
