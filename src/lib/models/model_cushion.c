/* SPDX-License-Identifier: GPL-3.0-or-later */
/* model_cushion.c - scene 3 of physics.md: the package on a Winkler cushion,
 * on the support frame (u, theta, z_B) or directly on the bed (theta, z_B).
 * Pure functions of a package's parameters, state and input: no allocation,
 * no I/O.
 *
 * State vectors:  on a frame  y = (u, theta, z, u', theta', z')
 *                 on the bed  y = (theta, z, theta', z')
 * z is z_B, the downward displacement of the base midpoint B from the
 * unloaded cushion surface (m).  Everything below is per unit package mass:
 * the cushion constants k', beta', c' of physics.md (per unit base length)
 * become kp = k'/m = w_c^2/(2b), bp = beta'/m = (B3/K) w_c^2/(2b) and
 * cp = c'/m = 2 zeta_c w_c/(2b), so the derived quantities of the scene
 * are all that is needed.
 *
 * The cushion's contact (what it does to the package at one state) is
 * cushion_contact.c.
 *
 * Equations of motion M(theta) q'' = r as physics.md writes them, divided
 * by m; the 3x3 (2x2 on the bed) system is solved by its adjugate, det > 0
 * for every theta. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>

#include "cushion_contact.h"
#include "fixed_rk.h"
#include "model_ops.h"
#include "model_traits.h"
#include "numeric.h"
#include "swaywatch/model.h"

/* ---- rest --------------------------------------------------------------- */

double sw_cushion_static_deflection(const sw_derived_t *d, double g)
{
    const double w2 = d->omega_c * d->omega_c;             /* 1/s^2, K/m */
    const double q = d->K > 0.0 ? d->B3 / d->K * w2 : 0.0; /* 1/(s^2 m^2), B3/m */
    if (!(w2 > 0.0))
        return NAN;
    if (q <= 0.0)
        return g / w2;
    /* w2 z + q z^3 = g has one real root; the hyperbolic form of Cardano's
     * formula has no cancellation when the cubic term is small. */
    const double P = w2 / q, Q = g / q;
    double z = 2.0 * sqrt(P / 3.0) * sinh(asinh(1.5 * Q / P * sqrt(3.0 / P)) / 3.0);
    z -= (w2 * z + q * z * z * z - g) / (w2 + 3.0 * q * z * z); /* one Newton polish */
    return z;
}

/* Tangent stiffness K_t/m = (K + 3 B3 z_s^2)/m at the static deflection. */
static double tangent_w2(const sw_derived_t *d, double g)
{
    const double w2 = d->omega_c * d->omega_c, zs = sw_cushion_static_deflection(d, g);
    const double q = d->K > 0.0 ? d->B3 / d->K * w2 : 0.0;
    return w2 + 3.0 * q * zs * zs;
}

void sw_cushion_frequencies(const sw_derived_t *d, double g, double *omega_z, double *omega_theta)
{
    const double kt = tangent_w2(d, g);
    const double J = d->R * d->R / 3.0 + d->h * d->h; /* m^2, (I_C + m h^2)/m */
    const double kr = kt * d->b * d->b / 3.0 - g * d->h;
    if (omega_z)
        *omega_z = sqrt(kt);
    if (omega_theta)
        *omega_theta = kr > 0.0 ? sqrt(kr / J) : 0.0;
}

/* Largest |lambda| of m x'' + c x' + k x = 0 (rad/s). */
static double rate_1dof(double m, double c, double k)
{
    const double disc = c * c - 4.0 * m * k;
    if (disc <= 0.0)
        return sqrt(k / m);
    return (c + sqrt(disc)) / (2.0 * m);
}

double sw_cushion_omega_max(const sw_derived_t *d, double g)
{
    /* Linearised about rest, theta and z decouple: the vertical mode has
     * K_t/m and C/m (damping enters: at zeta_c = 2 its fast real root is
     * 3.7 w_c), the rocking mode the moment K_t b^2/3 - m g h and the
     * Winkler damping moment C b^2/3 about B, coupled to u on a frame.
     * States stiffer than rest (a corner landing of a heavily damped
     * cushion, a cubic cushion compressed hard) are handled step by step,
     * see contact_rate(). */
    const double kt = tangent_w2(d, g), cz = 2.0 * d->zeta_c * d->omega_c;
    const double J = d->R * d->R / 3.0 + d->h * d->h; /* m^2, (I_C + m h^2)/m */
    const double b2 = d->b * d->b / 3.0, kr = kt * b2 - g * d->h, cr = cz * b2;
    double w = rate_1dof(1.0, cz, kt);
    if (!(d->gamma > 0.0))
        return fmax(w, rate_1dof(J, cr, fabs(kr)));
    /* frame: det(l^2 M + l C + K) = 0 with M = [1/gam, h; h, J],
     * C = diag(2 zeta_b w_b/gam, cr), K = diag(w_b^2/gam, kr): a quartic,
     * solved on its companion matrix without allocation */
    const double gi = 1.0 / d->gamma, h = d->h;
    const double c1 = 2.0 * d->zeta_b * d->omega_b * gi, k1 = d->omega_b * d->omega_b * gi;
    const double a[5] = {k1 * kr, c1 * kr + k1 * cr, kr * gi + c1 * cr + k1 * J, cr * gi + c1 * J,
                         J * gi - h * h};
    double mat[16], zr[8];
    gsl_poly_complex_workspace ws = {4, mat};
    if (gsl_poly_complex_solve(a, 5, &ws, zr) == GSL_SUCCESS) {
        for (int i = 0; i < 4; i++) w = fmax(w, hypot(zr[2 * i], zr[2 * i + 1]));
    } else {
        /* not expected for these coefficients: bound each mode by its
         * reduced mass */
        w = fmax(w, rate_1dof(gi - h * h / J, c1, k1));
        w = fmax(w, rate_1dof(J - h * h * d->gamma, cr, fabs(kr)));
    }
    return w;
}

/* The modes of sw_cushion_omega_max's linearisation, as eigenvalues: the
 * vertical mode, and the rocking mode on the bed or the two coupled
 * rocking and bearing modes on a frame (model.h). */
static int cushion_modes(const sw_derived_t *d, double g, sw_mode_t m[SW_MODES_MAX])
{
    const double kt = tangent_w2(d, g), cz = 2.0 * d->zeta_c * d->omega_c;
    const double J = d->R * d->R / 3.0 + d->h * d->h; /* m^2, (I_C + m h^2)/m */
    const double b2 = d->b * d->b / 3.0, kr = kt * b2 - g * d->h, cr = cz * b2;
    int n = sw_modes_quadratic(m, 0, 1.0, cz, kt, "cushion's vertical mode");
    if (!(d->gamma > 0.0))
        return sw_modes_quadratic(m, n, J, cr, kr, "cushion's rocking mode");
    const double gi = 1.0 / d->gamma, h = d->h;
    const double c1 = 2.0 * d->zeta_b * d->omega_b * gi, k1 = d->omega_b * d->omega_b * gi;
    const double a[5] = {k1 * kr, c1 * kr + k1 * cr, kr * gi + c1 * cr + k1 * J, cr * gi + c1 * J,
                         J * gi - h * h};
    double mat[16], zr[8];
    gsl_poly_complex_workspace ws = {4, mat};
    if (gsl_poly_complex_solve(a, 5, &ws, zr) != GSL_SUCCESS) {
        /* not expected: each mode with its reduced mass, as omega_max */
        n = sw_modes_quadratic(m, n, gi - h * h / J, c1, k1, "bearing mode");
        return sw_modes_quadratic(m, n, J - h * h * d->gamma, cr, kr, "cushion's rocking mode");
    }
    for (int i = 0; i < 4; i++)
        if (zr[2 * i + 1] >= 0.0) /* one of each conjugate pair; real roots each */
            n = sw_modes_add(m, n, zr[2 * i], zr[2 * i + 1], "cushion's rocking and bearing mode");
    return n;
}

/* Largest eigenvalue of M^-1 A for symmetric 2x2 A (a11, a12, a22) and
 * positive definite M (m11, m12, m22). */
static double eig2(double a11, double a12, double a22, double m11, double m12, double m22)
{
    const double dm = m11 * m22 - m12 * m12, da = a11 * a22 - a12 * a12;
    const double tr = a11 * m22 + a22 * m11 - 2.0 * a12 * m12;
    return (tr + sqrt(fmax(tr * tr - 4.0 * dm * da, 0.0))) / (2.0 * dm);
}

/* The fastest rate of the contact k at tilt th (rad/s), for explicit step
 * control.  With the contact's stiffness and damping matrices K and C in
 * (theta, z) and the mass matrix M (the frame, if any, free to move: the
 * fast modes do not wait for the bearings), every eigenvalue of l^2 M + l C
 * + K has |l| <= max(sqrt(eig(M^-1 K)), eig(M^-1 C)).  That bound, relative
 * to its value at rest, scales omega_max: at rest the rate is omega_max, a
 * corner landing on a heavily damped cushion (the contact's damping no
 * longer balanced by its stiffness, on a lighter effective mass) or a
 * cubic cushion compressed far beyond its static deflection is faster.
 * No contact: 0. */
static double contact_rate(const sw_model_t *M, double th, const contact_t *k)
{
    const sw_derived_t *d = &M->d;
    if (!(k->L0 > 0.0))
        return 0.0;
    const double h = d->h, s = sin(th), co = cos(th);
    const double cp = 2.0 * d->zeta_c * d->omega_c / (2.0 * d->b); /* 1/(s m), c'/m */
    const double m11 = d->R * d->R / 3.0 + h * h - d->gamma * h * h * co * co;
    const double m12 = h * s, m22 = 1.0;
    const double kK = eig2(co * co * k->S2, co * k->S1, k->S, m11, m12, m22);
    const double kC = cp * eig2(co * co * k->L2, co * k->L1, k->L0, m11, m12, m22);
    return d->omega_max * fmax(1.0, fmax(sqrt(kK), kC) / M->rate_rest);
}

/* A bound of contact_rate() over every state, or INFINITY: what lets a
 * step skip the tracking when even this rate is stable (scheme.c).  For a
 * linear cushion (no cubic term) the stiffness density is k' everywhere,
 * so over any pushing part P of [-b, b], for every v,
 *   v' K_P v = k' int_P (v1 cos(theta) sigma + v2)^2 dsigma
 *           <= k' int_{-b}^{b} (v1 sigma + v2)^2 dsigma = v' D v,
 * D = k' diag(2 b^3 / 3, 2 b); the same for C with c' for k'.  Hence
 * eig(M^-1 K) <= eig(M^-1 D) = 1 / eig_min(D^-1/2 M D^-1/2) <= tr/det of
 * that matrix = (m11 d2 + m22 d1) / det M, and m11 <= R^2/3 + h^2 = J,
 * m22 = 1, det M = R^2/3 + h^2 cos^2(theta) (1 - gamma) >= R^2/3 for
 * 0 <= gamma <= 1.  A cubic cushion stiffens without bound: none. */
static double rate_cap(const sw_model_t *M)
{
    const sw_derived_t *d = &M->d;
    if (d->B3 != 0.0 || !(d->gamma >= 0.0 && d->gamma <= 1.0) || !(M->rate_rest > 0.0))
        return INFINITY;
    const double b = d->b, h = d->h, r3 = d->R * d->R / 3.0;       /* m, m, m^2 */
    const double J = r3 + h * h;                                   /* m^2 */
    const double rho = (J * 2.0 * b + 2.0 * b * b * b / 3.0) / r3; /* m, eig(M^-1 D) / k' */
    const double kp = d->omega_c * d->omega_c / (2.0 * b);         /* 1/(s^2 m) */
    const double cp = 2.0 * d->zeta_c * d->omega_c / (2.0 * b);    /* 1/(s m) */
    const double kK = kp * rho, kC = cp * rho;
    /* with room for the rounding of contact_rate()'s own arithmetic */
    return (1.0 + 1e-9) * d->omega_max * fmax(1.0, fmax(sqrt(kK), kC) / M->rate_rest);
}

/* ---- equations of motion ------------------------------------------------ */

/* An adaptive explicit step that grew in free flight can send its trial
 * stages deep into a stiff cushion, where they overflow.  GSL takes a
 * non-finite error estimate for a small one (its comparisons with NaN are
 * false) and would accept the step; a failure status instead makes it
 * halve the step and try again. */
static int finite_or_fail(const sw_model_t *M, const double f[])
{
    for (int i = 0; i < M->n; i++)
        if (!isfinite(f[i]))
            return GSL_ERANGE;
    return GSL_SUCCESS;
}

static SW_ALWAYS_INLINE int cushion_rhs_trig(const sw_model_t *M, sw_model_scratch_t *S,
                                             const sw_input_at_t *u, const double y[], double s,
                                             double co, double f[]);

/* The right-hand side is a function of (a_g, g_eff, y) alone (the mode
 * selects nothing on a cushion), and the fixed steps ask for the same
 * one three times: the event layer evaluates it at the end of each step
 * (ops->events), and the next step's first stage and the event layer's
 * look at that step's start are the same state under the same input
 * (unless the input's interval changed there, or a map moved the state).
 * The answers at the last ends the event layer examined are kept in the
 * scratch with their arguments, compared bit for bit, and give the very
 * same numbers without the contact's cost.  Only those: the other stages
 * never come back.  Not while the rate is tracked: that call must see
 * it. */
static inline int same_bits(double a, double b)
{
    uint64_t x, y;
    memcpy(&x, &a, sizeof x);
    memcpy(&y, &b, sizeof y);
    return x == y;
}

/* f from the memory into f with its status in *rc: the entry's index,
 * or -1. */
static SW_ALWAYS_INLINE int memo_get(const sw_model_t *M, const sw_model_scratch_t *S,
                                     const sw_input_at_t *u, const double y[], double f[], int *rc)
{
    if (!S->memo_on || S->track_rate)
        return -1;
    for (int i = 0; i < S->memo_n; i++) {
        const int k = (S->memo_next + SW_RHS_MEMO - 1 - i) % SW_RHS_MEMO; /* newest first */
        if (!same_bits(S->memo[k].ag, u->ag) || !same_bits(S->memo[k].ge, u->ge))
            continue;
        int j = 0;
        while (j < M->n && same_bits(S->memo[k].y[j], y[j])) j++;
        if (j < M->n)
            continue;
        for (j = 0; j < M->n; j++) f[j] = S->memo[k].f[j];
        *rc = S->memo[k].rc;
        return k;
    }
    return -1;
}

/* Keep f at (u, y), and sin and cos of theta there (s, co), which the
 * events at the next step's start take again. */
static void memo_put(const sw_model_t *M, sw_model_scratch_t *S, const sw_input_at_t *u,
                     const double y[], const double f[], int rc, double s, double co)
{
    const int k = S->memo_next;
    S->memo[k].ag = u->ag;
    S->memo[k].ge = u->ge;
    for (int j = 0; j < M->n; j++) {
        S->memo[k].y[j] = y[j];
        S->memo[k].f[j] = f[j];
    }
    S->memo[k].rc = rc;
    S->memo[k].sin_cos[0] = s;
    S->memo[k].sin_cos[1] = co;
    S->memo_next = (k + 1) % SW_RHS_MEMO;
    if (S->memo_n < SW_RHS_MEMO)
        S->memo_n++;
}

static SW_ALWAYS_INLINE int cushion_rhs(const sw_model_t *M, sw_model_scratch_t *S,
                                        const sw_input_at_t *u, const double y[], double f[])
{
    int rc;
    if (memo_get(M, S, u, y, f, &rc) >= 0)
        return rc;
    const double th = y[M->ith];
    return cushion_rhs_trig(M, S, u, y, sin(th), cos(th), f);
}

/* The fixed-step schemes' bodies with the right-hand side inlined into
 * every stage (fixed_rk.h), as the rigid models have them: no call
 * through the ops table per stage. */
static SW_ALWAYS_INLINE void cushion_stage(const sw_model_t *M, sw_model_scratch_t *S,
                                           const sw_input_at_t *u, const double y[], double f[])
{
    cushion_rhs(M, S, u, y, f);
}
SW_FIXED_RK(cushion, M->n, cushion_stage)

/* The same with s = sin(theta), co = cos(theta) given. */
static SW_ALWAYS_INLINE int cushion_rhs_trig(const sw_model_t *M, sw_model_scratch_t *S,
                                             const sw_input_at_t *u, const double y[], double s,
                                             double co, double f[])
{
    const sw_derived_t *d = &M->d;
    const double ag = u->ag, ge = u->ge; /* m/s^2 */
    const double th = y[M->ith], z = y[M->iz], dth = y[M->idth], dz = y[M->idz];
    const double h = d->h;
    contact_t k;
    sw_cushion_contact(d, s, co, z, dth, dz, S->track_rate ? CT_PUSH | CT_MOMENTS : CT_PUSH, &k);
    if (S->track_rate)
        S->rate_seen = fmax(S->rate_seen, contact_rate(M, th, &k));
    const double J = d->R * d->R / 3.0 + h * h; /* m^2, (I_C + m h^2)/m */
    const double hs = h * s, hc = h * co;
    /* right-hand sides of physics.md divided by m */
    const double r2 = -co * k.Ms + ge * hs - ag * hc;
    const double r3 = -k.F + ge - hc * dth * dth;
    f[M->ith] = dth;
    f[M->iz] = dz;
    if (M->iu < 0) {
        /* on the bed: [J, h s; h s, 1] (theta'', z'') = (r2, r3) */
        const double det = J - hs * hs;
        f[M->idth] = (r2 - hs * r3) / det;
        f[M->idz] = (J * r3 - hs * r2) / det;
        return finite_or_fail(M, f);
    }
    /* on a frame: M = [1/gam, h c, 0; h c, J, h s; 0, h s, 1] */
    const double gi = 1.0 / d->gamma, w = d->omega_b;
    const double r1 =
        -(2.0 * d->zeta_b * w * y[M->idu] + w * w * y[M->iu]) * gi + hs * dth * dth - ag * gi;
    const double A11 = J - hs * hs, A12 = -hc, A13 = hc * hs;
    const double A22 = gi, A23 = -gi * hs, A33 = gi * J - hc * hc;
    const double det = gi * A11 - hc * hc; /* = gi (J - h^2 s^2) - h^2 c^2 > 0 */
    f[M->iu] = y[M->idu];
    f[M->idu] = (A11 * r1 + A12 * r2 + A13 * r3) / det;
    f[M->idth] = (A12 * r1 + A22 * r2 + A23 * r3) / det;
    f[M->idz] = (A13 * r1 + A23 * r2 + A33 * r3) / det;
    return finite_or_fail(M, f);
}

static void cushion_rest(sw_model_t *M, double y[])
{
    y[M->iz] = sw_cushion_static_deflection(&M->d, M->g);
    M->phase = SW_PHASE_ROCKING; /* no stuck stage on a compliant cushion */
    M->side = 1;
}

/* The two terms of the contact's event functions at y, b^2 sin^2(theta)
 * and z |z| (m^2), and their time derivatives (m^2/s); s = sin(theta),
 * co = cos(theta).  An edge of the base is off the cushion while
 * P - Q > 0 (b |sin theta| > z), the whole base while P + Q < 0; both
 * smooth through theta = 0 and z = 0. */
typedef struct {
    double P, Q, dP, dQ;
} edge_t;

static edge_t edge_terms(const sw_model_t *M, const double y[], double s, double co)
{
    const double b = M->d.b, z = y[M->iz];
    return (edge_t){.P = b * b * s * s,
                    .Q = z * fabs(z),
                    .dP = 2.0 * b * b * s * co * y[M->idth],
                    .dQ = 2.0 * fabs(z) * y[M->idz]};
}

/* b^2 sin^2(theta) - z |z| (m^2): > 0 while an edge of the base is off
 * the cushion. */
static double cushion_lift(const sw_model_t *M, const double y[])
{
    const double th = y[M->ith];
    const edge_t e = edge_terms(M, y, sin(th), cos(th));
    return e.P - e.Q;
}

/* ---- energies and margins ------------------------------------------------ */

/* Potential energy per unit mass (J/kg) at (theta, z) relative to the
 * package upright at z = 0: cushion strain + gravity. */
static double potential(const sw_derived_t *d, double g, double th, double z)
{
    contact_t k;
    sw_cushion_contact(d, sin(th), cos(th), z, 0.0, 0.0, CT_STRAIN, &k);
    return k.U - g * z + g * d->h * (cos(th) - 1.0);
}

/* Potential at rest (theta = 0, z = z_s), J/kg. */
static double potential_rest(const sw_derived_t *d, double g)
{
    return potential(d, g, 0.0, sw_cushion_static_deflection(d, g));
}

double sw_cushion_barrier(const sw_derived_t *d, double g)
{
    /* least potential over theta = alpha: V(alpha, z) is convex in z, its
     * minimum where the cushion carries the weight, F(alpha, z) = g.  F is
     * increasing and convex in z, so Newton from above converges
     * monotonically; z_s + b sin(alpha) is above (every point of the base
     * is then compressed by at least z_s). */
    const double zs = sw_cushion_static_deflection(d, g);
    double z = zs + d->b * sin(d->alpha);
    for (int it = 0; it < 200; it++) {
        contact_t k;
        sw_cushion_contact(d, sin(d->alpha), cos(d->alpha), z, 0.0, 0.0, CT_PUSH | CT_MOMENTS, &k);
        if (!(k.S > 0.0))
            break;
        const double dz = (k.F - g) / k.S;
        z -= dz;
        if (fabs(dz) <= 1e-14 * (fabs(z) + zs))
            break;
    }
    return potential(d, g, d->alpha, z) - potential_rest(d, g);
}

/* Least energy above rest (J/kg) that lifts an edge off the cushion. */
static double lift_energy(const sw_derived_t *d, double g)
{
    /* least potential above rest on the uplift boundary z = b sin(theta),
     * theta in [0, alpha] (symmetric for theta < 0): a log-spaced scan
     * (the minimum sits near theta ~ z_s/b, tiny for a stiff cushion), then
     * golden-section search between the best point's neighbours */
    const double V0 = potential_rest(d, g);
    double best_th = 0.0, best = potential(d, g, 0.0, 0.0) - V0;
    double lo = 0.0, hi = d->alpha, prev = 0.0;
    const int nk = 96;
    for (int k = nk; k >= 0; k--) { /* theta from alpha 1e-12 up to alpha */
        const double th = d->alpha * pow(10.0, -12.0 * k / nk);
        const double v = potential(d, g, th, d->b * sin(th)) - V0;
        if (v < best) {
            best = v;
            best_th = th;
            lo = prev;
            hi = k > 0 ? d->alpha * pow(10.0, -12.0 * (k - 1) / nk) : d->alpha;
        }
        prev = th;
    }
    if (best_th == 0.0)
        return best;
    const double gr = 0.5 * (sqrt(5.0) - 1.0);
    double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
    double v1 = potential(d, g, x1, d->b * sin(x1)) - V0;
    double v2 = potential(d, g, x2, d->b * sin(x2)) - V0;
    for (int it = 0; it < 120 && hi - lo > 1e-15 * d->alpha; it++) {
        if (v1 < v2) {
            hi = x2;
            x2 = x1;
            v2 = v1;
            x1 = hi - gr * (hi - lo);
            v1 = potential(d, g, x1, d->b * sin(x1)) - V0;
        } else {
            lo = x1;
            x1 = x2;
            v1 = v2;
            x2 = lo + gr * (hi - lo);
            v2 = potential(d, g, x2, d->b * sin(x2)) - V0;
        }
    }
    return fmin(best, fmin(v1, v2));
}

/* Kinetic energy per unit mass of the package relative to its support
 * (u' = 0) and of package + frame (J/kg). */
static void kinetic(const sw_derived_t *d, const sw_state_t *s, double *rel, double *tot)
{
    const double h = d->h, J = d->R * d->R / 3.0 + h * h;
    const double st = sin(s->theta), ct = cos(s->theta), w = s->theta_dot;
    *rel = 0.5 * J * w * w + h * st * w * s->z_dot + 0.5 * s->z_dot * s->z_dot;
    *tot = *rel;
    if (d->gamma > 0.0)
        *tot += 0.5 * s->u_dot * s->u_dot / d->gamma + h * ct * s->u_dot * w;
}

/* The energy of s given the potential at rest V0 (J/kg) under g_eff. */
static double energy_with(const sw_derived_t *d, double g_eff, double V0, const sw_state_t *s)
{
    double rel, tot;
    kinetic(d, s, &rel, &tot);
    double E = tot + potential(d, g_eff, s->theta, s->z) - V0;
    if (d->gamma > 0.0)
        E += 0.5 * d->omega_b * d->omega_b * s->u * s->u / d->gamma;
    return E;
}

double sw_energy_cushion(const sw_derived_t *d, double g_eff, const sw_state_t *s)
{
    return energy_with(d, g_eff, potential_rest(d, g_eff), s);
}

/* The margins given the barrier Eb and the potential at rest V0 (J/kg)
 * under g_eff: the engine passes the values it computed once for nominal
 * gravity, which are the same numbers, bit for bit. */
static void margin_with(const sw_derived_t *d, double g_eff, double Eb, double V0,
                        const sw_state_t *s, double *margin, double *margin_bound)
{
    double rel, tot;
    kinetic(d, s, &rel, &tot);
    const double V = potential(d, g_eff, s->theta, s->z) - V0;
    const double PE = V / Eb, KE = rel / Eb, E = PE + KE;
    const int inside = fabs(s->theta) < d->alpha;
    if (margin) {
        if (inside) {
            *margin = 1.0 - E;
        } else {
            /* beyond alpha: coming back over the barrier with energy to
             * spare, or falling; either way not positive */
            const int inward = s->theta * s->theta_dot < 0.0;
            *margin = fmin(0.0, inward && E > 1.0 ? 1.0 - E : PE - KE - 1.0);
        }
    }
    if (margin_bound) {
        double Et = tot + V;
        if (d->gamma > 0.0)
            Et += 0.5 * d->omega_b * d->omega_b * s->u * s->u / d->gamma;
        const double mb = 1.0 - Et / Eb;
        *margin_bound = inside ? mb : fmin(mb, 0.0);
    }
}

void sw_margin_cushion(const sw_derived_t *d, double g_eff, const sw_state_t *s, double *margin,
                       double *margin_bound)
{
    margin_with(d, g_eff, sw_cushion_barrier(d, g_eff), potential_rest(d, g_eff), s, margin,
                margin_bound);
}

static double motion_energy(const sw_model_t *M, const double y[])
{
    sw_state_t s;
    memset(&s, 0, sizeof s);
    s.theta = y[M->ith];
    s.theta_dot = y[M->idth];
    s.z = y[M->iz];
    s.z_dot = y[M->idz];
    if (M->iu >= 0) {
        s.u = y[M->iu];
        s.u_dot = y[M->idu];
    }
    return energy_with(&M->d, M->g, M->v_rest, &s);
}

/* ---- the engine's view: layout, events, rest -------------------------------- */

static void cushion_setup(sw_model_t *M, const sw_scene_t *sc)
{
    if (sc->has_frame) {
        M->n = 6;
        M->iu = 0;
        M->ith = 1;
        M->iz = 2;
        M->idu = 3;
        M->idth = 4;
        M->idz = 5;
    } else {
        M->n = 4;
        M->ith = 0;
        M->iz = 1;
        M->idth = 2;
        M->idz = 3;
    }
    /* typical sizes: the angle at which an edge of the base lifts
     * (z_s/b), the static deflection, the bearings' deflection under 1 g */
    const double zs = sw_cushion_static_deflection(&M->d, M->g); /* m */
    sw_model_scale(M, M->ith, M->idth, zs / M->d.b);
    if (M->iu >= 0)
        sw_model_scale(M, M->iu, M->idu, M->g / (M->d.omega_b * M->d.omega_b));
    sw_model_scale(M, M->iz, M->idz, zs);
    /* contact_rate()'s bound at rest: full contact, theta = 0, where
     * M^-1 K and M^-1 C have the vertical mode's K_t/m and C/m as their
     * largest eigenvalues */
    M->rate_rest = fmax(sqrt(tangent_w2(&M->d, M->g)), 2.0 * M->d.zeta_c * M->d.omega_c);
    M->rate_cap = rate_cap(M);
    M->e_lift = lift_energy(&M->d, M->g);
    /* constants of every output and rest test under nominal gravity: the
     * barrier alone is a Newton solve, most of an output's cost */
    M->e_barrier = sw_cushion_barrier(&M->d, M->g);
    M->v_rest = potential_rest(&M->d, M->g);
}

/* A package on a cushion moves from the start: it is never stuck and never
 * impacts.  Overturn cuts its steps, and so, for the fixed-step schemes,
 * does an edge of the base meeting the cushion's surface (a kink in the
 * contact force); tipping, the first lift of an edge (uplift) and the
 * peaks of |theta| are timed inside a step, and "rest" is checked at the
 * end of each step. */
static int cushion_candidates(const sw_model_t *M, int cut_kinks, double h, const double y0[],
                              const double y1[], sw_evcand_t c[])
{
    const double al = M->d.alpha;
    /* the comparisons themselves, not libm's fmax (a call, for NaN: the
     * engine has checked both states finite), on every step */
    const double a0 = fabs(y0[M->ith]), a1 = fabs(y1[M->ith]), amax = a0 > a1 ? a0 : a1;
    const double w0 = fabs(y0[M->idth]), w1 = fabs(y1[M->idth]);
    const double v = h * (w0 > w1 ? w0 : w1);
    int n = 0;
    if (a1 >= M_PI_2 || M_PI_2 - amax < v)
        c[n++] = (sw_evcand_t){SW_EVF_OVERTURN, SW_ROLE_CUT, SW_RULE_RISE, 0};
    /* Where an edge of the base reaches the cushion's surface the contact
     * force has a kink (with damping, a kink in F itself): a fixed step
     * across it loses the scheme's order, so the step is cut there.  The
     * adaptive schemes' error control shortens their steps instead (a cut
     * would also restart msbdf at order 1, and chatter where a loose
     * tolerance leaves the contact unresolved).  These and the first lift
     * are marked clear: a step whose ends are both well below the level
     * (event.c's root_of) has no rise on its interpolant to search for,
     * the common case while the base rests on the cushion. */
    if (cut_kinks)
        for (int ev = SW_EVF_LIFT; ev <= SW_EVF_FLY_IN; ev++)
            c[n++] = (sw_evcand_t){(unsigned char)ev, SW_ROLE_CUT, SW_RULE_KINK, 1};
    if ((y0[M->ith] * y0[M->idth] > 0.0) != (y1[M->ith] * y1[M->idth] > 0.0))
        c[n++] = (sw_evcand_t){SW_EVF_TURN, SW_ROLE_PEAK, SW_RULE_PLAIN, 0};
    if (a0 < al && (a1 >= al || al - amax < v))
        c[n++] = (sw_evcand_t){SW_EVF_TIP, SW_ROLE_TIP, SW_RULE_RISE, 0};
    if (isnan(M->t_lift))
        c[n++] = (sw_evcand_t){SW_EVF_LIFT, SW_ROLE_LIFT, SW_RULE_RISE, 1};
    return n;
}

/* Value and time derivative of event ev at y with f = y' (none depends
 * on the input), e the contact's terms there (edge_terms) for the
 * contact's events; theta changes sign smoothly on a cushion: events on
 * theta^2. */
static void cushion_event_fn(const sw_model_t *M, int ev, const double y[], const double f[],
                             const edge_t *e, double *val, double *der)
{
    const double th = y[M->ith], w = y[M->idth];
    switch (ev) {
        case SW_EVF_OVERTURN:
            *val = th * th - M_PI_2 * M_PI_2;
            *der = 2.0 * th * w;
            return;
        case SW_EVF_TIP:
            *val = th * th - M->d.alpha * M->d.alpha;
            *der = 2.0 * th * w;
            return;
        case SW_EVF_TURN: /* |theta| stops growing */
            *val = -th * w;
            *der = -(w * w + th * f[M->idth]);
            return;
        case SW_EVF_LIFT: /* an edge leaves the cushion */
            *val = e->P - e->Q;
            *der = e->dP - e->dQ;
            return;
        case SW_EVF_LIFT_IN:
            *val = -(e->P - e->Q);
            *der = -(e->dP - e->dQ);
            return;
        case SW_EVF_FLY: /* the last edge leaves it */
            *val = -(e->P + e->Q);
            *der = -(e->dP + e->dQ);
            return;
        default: /* SW_EVF_FLY_IN */
            *val = e->P + e->Q;
            *der = e->dP + e->dQ;
            return;
    }
}

/* f at y, then each event function there, with one sine and cosine of
 * theta for the right-hand side and the contact's events alike (kept with
 * f where it is remembered: the next step's start is this end). */
static void cushion_events(const sw_model_t *M, sw_model_scratch_t *S, const sw_input_at_t *u,
                           const double y[], const sw_evcand_t c[], int n, double f[], double v[],
                           double d[])
{
    double s, co;
    int rc, terms = 0;
    edge_t e = {0};
    const int k = memo_get(M, S, u, y, f, &rc);
    if (k >= 0) {
        s = S->memo[k].sin_cos[0]; /* of the same theta, bit for bit */
        co = S->memo[k].sin_cos[1];
    } else {
        const double th = y[M->ith];
        s = sin(th);
        co = cos(th);
        rc = cushion_rhs_trig(M, S, u, y, s, co, f);
        if (S->memo_on)
            memo_put(M, S, u, y, f, rc, s, co);
    }
    for (int i = 0; i < n; i++) {
        if (!terms && c[i].ev >= SW_EVF_LIFT) {
            e = edge_terms(M, y, s, co);
            terms = 1;
        }
        cushion_event_fn(M, c[i].ev, y, f, &e, &v[i], &d[i]);
    }
}

static int cushion_uplift_side(const sw_model_t *M, const sw_input_at_t *u, const double y[])
{
    (void)M;
    (void)u;
    (void)y;
    return 0; /* never stuck: its uplift is the first lift of an edge */
}

/* On a cushion the side is the sign of theta. */
static void cushion_follow(sw_model_t *M, const double y[])
{
    M->side = y[M->ith] < 0.0 ? -1 : 1;
}

/* After a step: the side, and, lifted, back at rest: in full contact
 * with less energy than it takes to lift an edge again (with no input it
 * never will). */
static int cushion_stepped(sw_model_t *M, const double y[], int lifted)
{
    cushion_follow(M, y);
    return lifted && cushion_lift(M, y) < 0.0 && motion_energy(M, y) < M->e_lift;
}

/* Moving unless its energy of motion is below rest_eps of the barrier. */
static int cushion_moving(const sw_model_t *M, const double y[], double rest_eps)
{
    return M->phase == SW_PHASE_ROCKING && !(motion_energy(M, y) < rest_eps * M->e_barrier);
}

/* After the common part: the support's acceleration (the bed, or a_g + u''
 * on a frame), the uplift ratio and the margins. */
static void cushion_output(const sw_model_t *M, const sw_model_scratch_t *S, const sw_input_at_t *u,
                           const double y[], sw_output_t *o)
{
    (void)S;
    double ge = u->ge;    /* m/s^2, as the right-hand side sees it */
    o->a_support = u->ag; /* on the bed */
    if (M->iu >= 0) {
        /* on a frame, a_g + u'' from the equations of motion */
        double f[SW_NMAX];
        sw_model_scratch_t quiet = {.track_rate = 0}; /* the report tracks no rate */
        cushion_rhs(M, &quiet, u, y, f);
        o->a_support += f[M->idu];
    }
    /* Airborne (g + a_z <= 0): the engine has faulted the package and
     * reset it; its energy is judged under nominal gravity. */
    if (!(ge > 0.0))
        ge = M->g;
    o->uplift_ratio = fabs(o->a_support) / (M->tan_alpha * M->g);
    if (M->phase == SW_PHASE_OVERTURNED) {
        o->margin = o->margin_bound = -1.0;
        return;
    }
    if (ge == M->g)
        margin_with(&M->d, ge, M->e_barrier, M->v_rest, &o->state, &o->margin, &o->margin_bound);
    else
        sw_margin_cushion(&M->d, ge, &o->state, &o->margin, &o->margin_bound);
}

/* As the rigid models' (model_rigid.c); on the bed B holds still:
 * X' = h cos(th) th', and KE >= m X'^2/2 + I_C th'^2/2 >= (m + I_C/h^2)
 * X'^2/2, I_C/m = R^2/3. */
static double cushion_work_rate(const sw_derived_t *d)
{
    if (d->gamma > 0.0)
        return 1.0 / sqrt(2.0 * d->gamma);
    return sqrt(d->h * d->h / (2.0 * (d->h * d->h + d->R * d->R / 3.0)));
}

/* An edge leaves the cushion when its lift drive b |sin theta| - (z -
 * z_s) (m) reaches the static deflection z_s. */
static double cushion_lift_level(const sw_derived_t *d, double g)
{
    return sw_cushion_static_deflection(d, g);
}

static double cushion_lift_drive(const sw_derived_t *d, double level, const sw_output_t *o)
{
    return d->b * fabs(sin(o->state.theta)) - (o->state.z - level);
}

/* The rocking mode on the cushion, and the bearings' on a frame. */
static void cushion_probe_rates(const sw_derived_t *d, double g, double *fast, double *slow)
{
    double wz, wth; /* rad/s */
    sw_cushion_frequencies(d, g, &wz, &wth);
    *fast = fmax(d->omega_b, wth);
    *slow = d->omega_b > 0.0 ? fmin(d->omega_b, wth) : wth;
}

/* Decay rate (1/s) of the slower mode of a damped oscillator. */
static double decay_rate(double w, double zeta)
{
    return zeta < 1.0 ? zeta * w : w * (zeta - sqrt((zeta - 1.0) * (zeta + 1.0)));
}

/* A linear cushion on the bed: the rocking about rest to first order,
 *   (I_C + m h^2) theta'' + C b^2/3 theta' + (K b^2/3 - m g h) theta = -m h a_g,
 * theta = gain u, and apart from it the vertical mode m z'' = -K z - C z'
 * (in full contact the force K z_B does not depend on theta); an edge
 * lifts when b |theta| - (z - z_s) reaches z_s.  None on a
 * frame, with a cubic term, or without restoring stiffness and damping. */
static int cushion_rock_linear(const sw_derived_t *d, double m, double g, sw_rock_linear_t *r)
{
    if (d->gamma > 0.0 || d->B3 != 0.0)
        return 0;
    const double I = d->I_C + m * d->h * d->h;                /* kg m^2 */
    const double k = d->K * d->b * d->b / 3.0 - m * g * d->h; /* N m/rad */
    const double c = d->C * d->b * d->b / 3.0;                /* N m s/rad */
    if (!(k > 0.0) || !(c > 0.0))
        return 0;
    r->w = sqrt(k / I);
    r->zeta = c / (2.0 * I * r->w);
    r->gain = m * d->h / I;
    r->lam = fmin(decay_rate(r->w, r->zeta), decay_rate(d->omega_c, d->zeta_c));
    const double zs = sw_cushion_static_deflection(d, g); /* m */
    r->per = d->b * r->gain / zs;
    /* without a frame or a cubic term the vertical mode is m z'' = -K z - C z' */
    r->wz = d->omega_c;
    r->zetaz = d->zeta_c;
    r->per_z = 1.0 / zs; /* the drive b sin(theta) - (z - z_s) over z_s */
    return 1;
}

static const sw_model_traits_t cushion_traits = {
    .energy = sw_energy_cushion,
    .barrier = sw_cushion_barrier,
    .work_rate = cushion_work_rate,
    .modes = cushion_modes,
    .lift_level = cushion_lift_level,
    .lift_drive = cushion_lift_drive,
    .probe_rates = cushion_probe_rates,
    .probe_margin = 0.9, /* linear only to O(theta^2), and its probe's sampling is capped */
    .rock_linear = cushion_rock_linear,
};

const sw_model_ops_t sw_model_cushion = {
    .name = "cushion",
    .traits = &cushion_traits,
    .setup = cushion_setup,
    .rhs = cushion_rhs,
    .fixed = SW_FIXED_RK_ROW(cushion),
    .rest = cushion_rest,
    .candidates = cushion_candidates,
    .events = cushion_events,
    .uplift_side = cushion_uplift_side,
    .output = cushion_output,
    .follow = cushion_follow,
    .stepped = cushion_stepped,
    .moving = cushion_moving,
    .tracks_rate = 1,
    .flies = SW_FLIES_INTEGRATED,
};
