/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_cushion.c - the package on a Winkler cushion (scene 3), on the bed
 * and on the support frame, each check against a reference that does not
 * come from the engine: the static deflection by bisection, the vertical
 * and rocking frequencies of the linearised model, the quasi-static uplift
 * under a slow ramp, energy conservation through partial contact and
 * lift-off, the stiff limit against the frame scene (with physics.md's
 * numbers for how slowly it is approached), the energy guarantee behind
 * margin_bound, and a sweep of stiff and soft, undamped and overdamped,
 * linear and cubic cushions against tight GSL rk8pd runs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>

#include "model_ops.h"
#include "testutil.h"

#define G 9.81
#define MASS 1000.0 /* kg, tu_bare's package */

/* A package 2h x 2b (m) of 1000 kg on a cushion given as omega_c (rad/s),
 * zeta_c and the cubic B3 (N/m^3); on a 250 kg frame with omega_b (rad/s,
 * 0: no frame) and zeta_b. */
static sw_scene_t cushion(double height, double width, double wc, double zc, double B3,
                          double omega_b, double zeta_b)
{
    sw_scene_t sc =
        omega_b > 0.0 ? tu_frame(height, width, 250.0, omega_b, zeta_b) : tu_bare(height, width);
    sc = tu_cushion(sc, wc, zc);
    sc.cushion_cubic = B3;
    return sc;
}

/* B3 (N/m^3) whose cubic force equals the linear one at the linear static
 * deflection g/w^2: a strongly progressive cushion. */
static double progressive(double wc)
{
    const double K = MASS * wc * wc, z0 = G / (wc * wc);
    return K / (z0 * z0);
}

/* Root of K z + B3 z^3 = W by bisection on [0, W/K]. */
static double static_root(double K, double B3, double W)
{
    double lo = 0.0, hi = W / K;
    for (int i = 0; i < 300; i++) {
        const double m = 0.5 * (lo + hi);
        if (K * m + B3 * m * m * m < W)
            lo = m;
        else
            hi = m;
    }
    return 0.5 * (lo + hi);
}

static sw_engine_t *engine(const sw_scene_t *sc, const char *scheme, double dt, tu_events_t *rec)
{
    sw_engine_t *e = tu_engine(sc, scheme, dt, rec);
    assert_non_null(e);
    return e;
}

/* ---- the contact's rate, bounded ------------------------------------------ */

/* The model of scene sc, set up as the engine sets it up. */
static void model_of(const sw_scene_t *sc, sw_model_t *M, sw_model_scratch_t *S)
{
    memset(M, 0, sizeof *M);
    memset(S, 0, sizeof *S);
    assert_int_equal(sw_scene_validate(sc, &M->d, NULL, NULL, NULL), SW_OK);
    sw_model_setup(M, S, sc);
}

/* The rate the right-hand side tracks at state y (rad/s). */
static double tracked_rate(const sw_model_t *M, sw_model_scratch_t *S, const double y[])
{
    const sw_input_at_t u = {.ag = 3.0, .ge = G};
    double f[SW_NMAX];
    S->track_rate = 1;
    S->rate_seen = 0.0;
    M->ops->rhs(M, S, &u, y, f);
    S->track_rate = 0;
    return S->rate_seen;
}

/* A linear cushion's rate cap (model_cushion.c) holds at every state: on
 * the bed and on a frame, slender and squat, soft and hard, lightly and
 * heavily damped, in full and partial contact, tilted up to the overturn,
 * compressed up to 50 static deflections and moving fast.  The states are
 * random (a fixed seed); the cap is a proof (the moments of a part of the
 * base are below those of the whole), the tracked rate the exact
 * eigenvalues of the contact the states meet.  A cubic cushion has none. */
static void test_rate_cap(void **state)
{
    (void)state;
    const struct {
        double h, w, wc, zc, wb;
    } cases[] = {{2.0, 0.728, 30.0, 0.1, 0.0}, {2.0, 0.728, 30.0, 0.1, 5.59},
                 {0.5, 1.0, 80.0, 0.05, 0.0},  {3.0, 0.6, 25.0, 1.5, 0.0},
                 {1.2, 0.6, 200.0, 0.5, 12.6}, {0.2, 0.2, 50.0, 0.01, 3.0}};
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    assert_non_null(rng);
    gsl_rng_set(rng, 12345);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const sw_scene_t sc =
            cushion(cases[c].h, cases[c].w, cases[c].wc, cases[c].zc, 0.0, cases[c].wb, 0.1);
        sw_model_t M;
        sw_model_scratch_t S;
        model_of(&sc, &M, &S);
        assert_true(isfinite(M.rate_cap));
        const double zs = G / (cases[c].wc * cases[c].wc); /* m, static deflection */
        double worst = 0.0;
        for (int k = 0; k < 20000; k++) {
            double r[6];
            for (int j = 0; j < 6; j++) r[j] = gsl_rng_uniform(rng); /* [0, 1) */
            double y[SW_NMAX] = {0};
            y[M.ith] = (2.0 * r[0] - 1.0) * 1.55;
            y[M.iz] = (r[1] * 51.0 - 1.0) * zs;
            y[M.idth] = (2.0 * r[2] - 1.0) * 20.0;
            y[M.idz] = (2.0 * r[3] - 1.0) * 5.0;
            if (M.iu >= 0) {
                y[M.iu] = (2.0 * r[4] - 1.0) * 0.05;
                y[M.idu] = (2.0 * r[5] - 1.0) * 0.5;
            }
            const double rate = tracked_rate(&M, &S, y);
            assert_true(rate <= M.rate_cap);
            worst = fmax(worst, rate / M.rate_cap);
        }
        /* not vacuous: the states met rates near the cap's scale */
        assert_true(worst > 0.2);
    }
    gsl_rng_free(rng);
    const sw_scene_t cubic = cushion(2.0, 0.728, 30.0, 0.1, progressive(30.0), 0.0, 0.1);
    sw_model_t M;
    sw_model_scratch_t S;
    model_of(&cubic, &M, &S);
    assert_true(M.rate_cap == INFINITY);
}

/* The right-hand side remembers its answers at the last ends of a step
 * the event layer examined (ops->events, model_cushion.c): an answer
 * given again, by either call, is the one a fresh evaluation gives, bit
 * for bit, whatever came between, and a changed input or state is
 * evaluated anew. */
static void test_rhs_memo(void **state)
{
    (void)state;
    const sw_scene_t sc = cushion(2.0, 0.728, 30.0, 0.1, 0.0, 5.59, 0.1);
    sw_model_t M;
    sw_model_scratch_t S, fresh;
    model_of(&sc, &M, &S);
    model_of(&sc, &M, &fresh);
    S.memo_on = 1;     /* as the fixed steps set it */
    fresh.memo_on = 0; /* every call evaluated */
    const double zs = G / (30.0 * 30.0);
    double ys[8][SW_NMAX];
    sw_input_at_t us[8];
    for (int k = 0; k < 8; k++) {
        memset(ys[k], 0, sizeof ys[k]);
        ys[k][M.ith] = 0.01 * (k % 3) - 0.005;
        ys[k][M.iz] = zs * (1.0 + 0.1 * k);
        ys[k][M.idth] = 0.2 * (k % 2);
        ys[k][M.idz] = -0.01 * k;
        us[k] = (sw_input_at_t){.ag = 0.5 * (k % 4), .ge = G + 0.1 * (k % 2)};
    }
    /* the same states in an order that hits and misses the memory, asked
     * by the event layer (even places) and by a stage (odd places) */
    const int order[] = {0, 1, 2, 0, 3, 4, 5, 6, 7, 1, 0, 7, 7, 2, 6, 3, 0, 3, 3, 2};
    const sw_evcand_t lift = {.ev = SW_EVF_LIFT, .role = SW_ROLE_LIFT, .rule = SW_RULE_RISE};
    for (size_t i = 0; i < sizeof order / sizeof order[0]; i++) {
        const int k = order[i];
        double f[SW_NMAX], g[SW_NMAX], v, d, vg, dg;
        int rc = 0, rg = 0;
        if (i % 2 == 0) {
            M.ops->events(&M, &S, &us[k], ys[k], &lift, 1, f, &v, &d);
            M.ops->events(&M, &fresh, &us[k], ys[k], &lift, 1, g, &vg, &dg);
            assert_memory_equal(&v, &vg, sizeof v);
            assert_memory_equal(&d, &dg, sizeof d);
        } else {
            rc = M.ops->rhs(&M, &S, &us[k], ys[k], f);
            rg = M.ops->rhs(&M, &fresh, &us[k], ys[k], g);
        }
        assert_int_equal(rc, rg);
        assert_memory_equal(f, g, (size_t)M.n * sizeof f[0]);
    }
    assert_int_equal(S.memo_n, SW_RHS_MEMO);
    assert_int_equal(fresh.memo_n, 0);
    /* the same state under another input is another answer */
    double f1[SW_NMAX], f2[SW_NMAX];
    sw_input_at_t u = us[0];
    M.ops->rhs(&M, &S, &u, ys[0], f1);
    u.ag += 1.0;
    M.ops->rhs(&M, &S, &u, ys[0], f2);
    assert_true(f1[M.idth] != f2[M.idth]);
}

/* ---- rest ---------------------------------------------------------------- */

/* At rest the cushion carries the weight uniformly: z_B = m g / K, or the
 * root of K z + B3 z^3 = m g; the package stays there with no input and
 * its margins are 1. */
static void test_static_deflection(void **state)
{
    (void)state;
    const struct {
        double wc, B3, wb;
    } cases[] = {{200.0, 0.0, 0.0},
                 {200.0, progressive(200.0), 0.0},
                 {1e5, 0.0, 5.59},
                 {1e5, 5.0 * progressive(1e5), 0.0}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const sw_scene_t sc = cushion(2.0, 0.728, cases[k].wc, 0.1, cases[k].B3, cases[k].wb, 0.1);
        const double K = MASS * cases[k].wc * cases[k].wc;
        const double zs = static_root(K, cases[k].B3, MASS * G);
        if (cases[k].B3 == 0.0)
            tu_near(zs, MASS * G / K, 1e-15 * zs);
        sw_engine_t *e = engine(&sc, NULL, 0.0, NULL);
        const double zs_lib = sw_cushion_static_deflection(sw_engine_derived(e, 0), G);
        tu_near(zs_lib, zs, 1e-13 * zs);
        for (int i = 0; i <= 200; i++) sw_engine_push(e, i * 1e-3, 0.0, 0.0);
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        tu_near(o.state.z, zs, 1e-9 * zs);
        assert_true(fabs(o.state.theta) < 1e-15);
        assert_int_equal(o.state.phase, SW_PHASE_ROCKING); /* no stuck stage on a cushion */
        tu_near(o.margin, 1.0, 1e-9);
        tu_near(o.margin_bound, 1.0, 1e-9);
        sw_summary_t s;
        sw_engine_summary(e, 0, &s);
        assert_int_equal(s.uplifts, 0);
        assert_int_equal(s.faults, 0);
        sw_engine_destroy(e);
    }
}

/* ---- small oscillations ------------------------------------------------- */

/* Angular frequency of x(t) from its zero crossings (linear interpolation
 * between samples; a constant offset of every crossing cancels). */
static double crossing_frequency(const double *x, int n, double dt)
{
    double first = NAN, last = NAN;
    int count = 0;
    for (int i = 1; i < n; i++) {
        if ((x[i - 1] < 0.0) == (x[i] < 0.0))
            continue;
        const double t = dt * (i - 1 + x[i - 1] / (x[i - 1] - x[i]));
        if (count == 0)
            first = t;
        last = t;
        count++;
    }
    assert_true(count >= 8);
    return M_PI * (count - 1) / (last - first);
}

/* Run from state st with no input, sampling component comp (0: z - z0,
 * 1: theta) every dt for n samples. */
static void free_run(const sw_scene_t *sc, const sw_state_t *st, double z0, int comp, double dt,
                     int n, double *x)
{
    sw_engine_t *e = engine(sc, NULL, 0.0, NULL);
    sw_engine_push(e, 0.0, 0.0, 0.0);
    sw_engine_set_state(e, 0, st);
    for (int i = 0; i < n; i++) {
        if (i > 0)
            sw_engine_push(e, i * dt, 0.0, 0.0);
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        x[i] = comp == 0 ? o.state.z - z0 : o.state.theta;
    }
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_int_equal(s.uplifts, 0); /* stayed in full contact: the linear regime */
    sw_engine_destroy(e);
}

/* Vertical: m z'' + C z' + K_t z = 0 about the static deflection, with the
 * tangent stiffness K_t = K + 3 B3 z_s^2: damped frequency
 * sqrt(K_t/m) sqrt(1 - zeta^2), zeta = C / (2 sqrt(K_t m)); for B3 = 0
 * that is omega_c sqrt(1 - zeta_c^2). */
static void test_vertical_frequency(void **state)
{
    (void)state;
    const struct {
        double wc, zc, B3;
    } cases[] = {{200.0, 0.0, 0.0},
                 {200.0, 0.05, 0.0},
                 {200.0, 0.3, 0.0},
                 {5000.0, 0.05, 0.0},
                 {200.0, 0.05, progressive(200.0)}};
    enum { N = 6000 };
    static double x[N];
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const double wc = cases[k].wc, zc = cases[k].zc, B3 = cases[k].B3;
        const sw_scene_t sc = cushion(2.0, 0.728, wc, zc, B3, 0, 0.0);
        const double K = MASS * wc * wc, C = 2.0 * zc * MASS * wc;
        const double zs = static_root(K, B3, MASS * G);
        const double Kt = K + 3.0 * B3 * zs * zs;
        const double zt = C / (2.0 * sqrt(Kt * MASS));
        const double wd = sqrt(Kt / MASS) * sqrt(1.0 - zt * zt);
        sw_state_t st = {0};
        st.z = zs * (1.0 + 1e-3);
        st.phase = SW_PHASE_ROCKING;
        const double dt = 2.0 * M_PI / wd / 400.0;
        /* a damped oscillation only as long as it stands above round-off */
        const int n = zt > 0.0 ? (int)fmin(N, 400.0 * ceil(1.5 / zt)) : N;
        free_run(&sc, &st, zs, 0, dt, n, x);
        const double w = crossing_frequency(x, n, dt);
        print_message("w_c %g zeta %g B3 %g: %.8g rad/s, expected %.8g\n", wc, zc, B3, w, wd);
        tu_near(w, wd, 1e-5 * wd);
    }
}

/* Rocking about B in full contact (frame absent, C = 0): the moment K b^2/3
 * per radian against gravity's m g h, inertia I_C + m h^2. */
static void test_rocking_frequency(void **state)
{
    (void)state;
    const double wcs[] = {300.0, 3000.0};
    const double h = 1.0, b = 0.364;
    enum { N = 6000 };
    static double x[N];
    for (size_t k = 0; k < 2; k++) {
        const double wc = wcs[k], K = MASS * wc * wc;
        const sw_scene_t sc = cushion(2.0 * h, 2.0 * b, wc, 0.0, 0.0, 0, 0.0);
        const double IC = MASS * (h * h + b * b) / 3.0;
        const double wr = sqrt((K * b * b / 3.0 - MASS * G * h) / (IC + MASS * h * h));
        const double zs = MASS * G / K;
        sw_state_t st = {0};
        st.z = zs;
        st.theta = 0.3 * zs / b; /* the edges stay compressed */
        st.phase = SW_PHASE_ROCKING;
        const double dt = 2.0 * M_PI / wr / 400.0;
        free_run(&sc, &st, 0.0, 1, dt, N, x);
        const double w = crossing_frequency(x, N, dt);
        print_message("w_c %g: rocking %.8g rad/s, expected %.8g\n", wc, w, wr);
        tu_near(w, wr, 1e-5 * wr);
    }
}

/* A slow braking ramp a_g = -r t tilts the package forward quasi-statically;
 * linearised, (I_C + m h^2) theta'' + (C b^2/3) theta' + kappa theta =
 * -m h a_g with kappa = K b^2/3 - m g h, whose response to the ramp is
 * theta = (m h r / kappa) (t - c / kappa), c = C b^2/3, once the start
 * transient has died out.  The rear edge lifts when b theta = z_s.  Then
 * the bed stops and the package settles back: rest. */
static void test_quasistatic_uplift(void **state)
{
    (void)state;
    const double h = 1.0, b = 0.364, wc = 300.0, zc = 0.5, r = 0.5; /* r in m/s^3 */
    const sw_scene_t sc = cushion(2.0 * h, 2.0 * b, wc, zc, 0.0, 0, 0.0);
    const double K = MASS * wc * wc, C = 2.0 * zc * MASS * wc, zs = MASS * G / K;
    const double kappa = K * b * b / 3.0 - MASS * G * h, c = C * b * b / 3.0;
    const double t_lift = kappa * zs / (MASS * h * r * b) + c / kappa;
    tu_events_t rec = {0};
    sw_engine_t *e = engine(&sc, NULL, 0.0, &rec);
    const double t_stop = 1.5 * t_lift;
    for (int i = 0; i <= 4000; i++) {
        const double t = i * 1e-3;
        sw_engine_push(e, t, t < t_stop ? -r * t : 0.0, 0.0);
    }
    const sw_event_t *up = tu_first(&rec, SW_EV_UPLIFT);
    assert_non_null(up);
    print_message("uplift at %.6f s, quasi-static %.6f s\n", up->t, t_lift);
    tu_near(up->t, t_lift, 2e-4 * t_lift);
    assert_int_equal((int)up->info, 1); /* braking: the rear edge lifts, the top tips forward */
    assert_int_equal(tu_count(&rec, SW_EV_UPLIFT), 1);
    const sw_event_t *rest = tu_first(&rec, SW_EV_REST);
    assert_non_null(rest);
    assert_true(rest->t > t_stop);
    sw_engine_destroy(e);
}

/* A level base rising faster than the springs relax: k' z + c' z' < 0
 * everywhere, the cushion cannot pull (the clamp f >= 0), so the package
 * flies as a projectile from the start, z = z0 + v0 t + g t^2 / 2, until
 * the springs catch up. */
static void test_damping_clamp(void **state)
{
    (void)state;
    const double wc = 300.0, zc = 1.0, zs = G / (wc * wc);
    const double v0 = -2.0 * wc * zs; /* m/s, up: c' v0 = -4 k' z_s... */
    const sw_scene_t sc = cushion(2.0, 0.728, wc, zc, 0.0, 0.0, 0.0);
    sw_engine_t *e = engine(&sc, NULL, 0.0, NULL);
    sw_engine_push(e, 0.0, 0.0, 0.0);
    sw_state_t st = {0};
    st.z = zs;
    st.z_dot = v0;
    st.phase = SW_PHASE_ROCKING;
    sw_engine_set_state(e, 0, &st);
    /* while z > 0: k' z + c' z' = k' (z + 2 zeta z' / w) < 0 holds for
     * z' < -w z / (2 zeta); the first microseconds qualify */
    const double T = 0.2 * zs / fabs(v0);
    for (int i = 1; i <= 10; i++) {
        const double t = T * i / 10.0;
        sw_engine_push(e, t, 0.0, 0.0);
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        const double z = zs + v0 * t + 0.5 * G * t * t;
        assert_true(o.state.z + 2.0 * zc * o.state.z_dot / wc < 0.0);
        tu_near(o.state.z, z, 1e-9 * zs);
        tu_near(o.state.z_dot, v0 + G * t, 1e-9 * fabs(v0));
        assert_true(o.state.theta == 0.0);
    }
    sw_engine_destroy(e);
}

/* Linear cushion, partial contact, closed forms: with w = z + b sin(theta)
 * the front edge's compression and the base compressed on [-z/s, b],
 *   F = k' w^2 / (2 s),   int f sigma = (k'/s) (w^3 / (3 s) - z w^2 / (2 s)).
 * Static tilt under a constant braking a: F = m g and
 * -cos(theta) int f sigma + m g h sin(theta) - m h a cos(theta) = 0. */
static double partial_moment(double th, double a, double K, double h, double b)
{
    const double kp = K / (2.0 * b), s = sin(th), c = cos(th);
    const double w = sqrt(2.0 * MASS * G * s / kp), z = w - b * s;
    const double Ms = kp / s * (w * w * w / (3.0 * s) - z * w * w / (2.0 * s));
    return -c * Ms + MASS * G * h * s - MASS * h * a * c;
}

/* A soft cushion under a steady braking tilts the package onto its front
 * part with the rear edge lifted: the settled tilt matches the closed
 * form above (solved here by bisection). */
static void test_partial_contact_equilibrium(void **state)
{
    (void)state;
    const double h = 1.0, b = 0.364, wc = 60.0, K = MASS * wc * wc;
    const double a = -0.5 * G * b / h; /* m/s^2, half the rigid uplift threshold */
    const sw_scene_t sc = cushion(2.0 * h, 2.0 * b, wc, 2.0, 0.0, 0.0, 0.0);
    /* the stable root: the net moment tips the package forward from where
     * the rear edge lifts, sin(theta) = m g / (2 k' b^2), up to the tilt
     * where the cushion's moment takes over (beyond it, gravity wins again
     * at a second, unstable root) */
    double lo = asin(MASS * G / (2.0 * K / (2.0 * b) * b * b)), hi = lo;
    assert_true(partial_moment(lo, a, K, h, b) > 0.0);
    while (partial_moment(hi, a, K, h, b) > 0.0) hi *= 1.2;
    for (int i = 0; i < 200; i++) {
        const double m = 0.5 * (lo + hi);
        if (partial_moment(m, a, K, h, b) > 0.0)
            lo = m;
        else
            hi = m;
    }
    const double th_eq = 0.5 * (lo + hi);
    const double w = sqrt(2.0 * MASS * G * sin(th_eq) / (K / (2.0 * b)));
    const double z_eq = w - b * sin(th_eq);
    assert_true(z_eq < b * sin(th_eq)); /* partial contact indeed */
    tu_events_t rec = {0};
    sw_engine_t *e = engine(&sc, NULL, 0.0, &rec);
    for (int i = 0; i <= 16000; i++) { /* ramp over 4 s, then hold until settled */
        const double t = i * 1e-3;
        sw_engine_push(e, t, a * fmin(1.0, t / 4.0), 0.0);
    }
    sw_output_t o;
    sw_engine_get_output(e, 0, &o);
    print_message("tilt %.9f rad, closed form %.9f; z %.6g m, closed form %.6g\n", o.state.theta,
                  th_eq, o.state.z, z_eq);
    tu_near(o.state.theta, th_eq, 1e-7 * th_eq);
    tu_near(o.state.z, z_eq, 1e-7 * fabs(z_eq) + 1e-12);
    assert_int_equal(tu_count(&rec, SW_EV_UPLIFT), 1);
    assert_int_equal(tu_count(&rec, SW_EV_TIP), 0);
    sw_engine_destroy(e);
}

/* ---- energy --------------------------------------------------------------- */

typedef struct {
    double k, beta, z, s; /* k', beta' per unit length; z_B; sin(theta) */
} strain_t;

static double strain_density(double sigma, void *u)
{
    const strain_t *q = u;
    const double z = q->z + sigma * q->s;
    return z > 0.0 ? 0.5 * q->k * z * z + 0.25 * q->beta * z * z * z * z : 0.0;
}

/* Total energy (J) of package + frame + bearing + cushion, written out
 * from physics.md's kinetic energy and potentials; the strain integral by
 * GSL quadrature over the compressed part. */
static double total_energy(const sw_scene_t *sc, const sw_state_t *st, gsl_integration_workspace *w)
{
    const double m = sc->mass, mb = sc->frame_mass, h = sc->height / 2, b = sc->width / 2;
    const double R2 = h * h + b * b, IC = m * R2 / 3.0;
    const double wc = sc->cushion_omega, K = m * wc * wc;
    const double kb = sc->frame_omega * sc->frame_omega * (m + mb);
    const double s = sin(st->theta), c = cos(st->theta);
    const double T = 0.5 * (m + mb) * st->u_dot * st->u_dot +
                     m * h * c * st->u_dot * st->theta_dot +
                     0.5 * (IC + m * h * h) * st->theta_dot * st->theta_dot +
                     m * h * s * st->theta_dot * st->z_dot + 0.5 * m * st->z_dot * st->z_dot;
    strain_t q = {K / (2 * b), sc->cushion_cubic / (2 * b), st->z, s};
    double lo = -b, hi = b; /* the compressed part, where the integrand is smooth */
    if (s != 0.0) {
        const double s0 = -st->z / s;
        if (s > 0.0)
            lo = fmax(lo, s0);
        else
            hi = fmin(hi, s0);
    }
    double U = 0.0, err;
    if (hi > lo && (st->z + lo * s > 0.0 || st->z + hi * s > 0.0)) {
        gsl_function F = {strain_density, &q};
        gsl_integration_qag(&F, lo, hi, 0.0, 1e-13, 100, GSL_INTEG_GAUSS61, w, &U, &err);
    }
    const double V = -m * G * st->z + m * G * h * c + 0.5 * kb * st->u * st->u + U;
    return T + V;
}

/* Worst energy error over a run (relative to the package's rocking barrier
 * m g R (1 - cos alpha)) on a cushion with B3 = cubic * progressive();
 * counts samples in free flight / partial / full contact. */
static double energy_drift(const char *scheme, double dt, double cubic, int seen[3])
{
    const sw_scene_t sc = cushion(2.0, 0.728, 200.0, 0.0, cubic * progressive(200.0), 5.59, 0.0);
    sw_engine_t *e = engine(&sc, scheme, dt, NULL);
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(100);
    sw_engine_push(e, 0.0, 0.0, 0.0);
    /* thrown up off its rest state, spinning, the frame displaced */
    sw_state_t st = {0};
    st.z = sw_cushion_static_deflection(sw_engine_derived(e, 0), G);
    st.z_dot = -0.1; /* m/s, up */
    st.theta_dot = 0.1;
    st.u = 0.01;
    st.phase = SW_PHASE_ROCKING;
    sw_engine_set_state(e, 0, &st);
    const double E0 = total_energy(&sc, &st, w);
    const double h = 1.0, b = 0.364, R = hypot(h, b);
    const double Eb = MASS * G * R * (1.0 - h / R);
    double worst = 0.0;
    for (int i = 1; i <= 1500; i++) { /* 1.5 s, sampled every 1 ms (a multiple of every dt) */
        sw_engine_push(e, i * 1e-3, 0.0, 0.0);
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        const double edge = b * fabs(sin(o.state.theta));
        seen[o.state.z + edge <= 0.0 ? 0 : o.state.z - edge <= 0.0 ? 1 : 2]++;
        worst = fmax(worst, fabs(total_energy(&sc, &o.state, w) - E0) / Eb);
    }
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_int_equal(s.faults, 0);
    assert_false(s.overturned);
    gsl_integration_workspace_free(w);
    sw_engine_destroy(e);
    return worst;
}

/* With C = 0, c_b = 0 and no input the total energy is conserved, also
 * while the base flies, lands on a corner, flattens and bounces; rk4 loses
 * it as dt^4 (its steps are cut where an edge meets the surface, where the
 * force has a kink).  With a cubic term the landings stiffen the contact
 * so much that dt = 5e-4 s is not yet asymptotic there: the error falls
 * faster than dt^4, and the ratio is only bounded below. */
static void test_energy_conservation(void **state)
{
    (void)state;
    int seen[3] = {0, 0, 0}, seen2[3] = {0, 0, 0};
    double e1 = energy_drift("rk4", 1e-3, 0.0, seen);
    double e2 = energy_drift("rk4", 5e-4, 0.0, seen2);
    print_message(
        "linear, rk4: drift %.3g -> %.3g, ratio %.2f; samples flying %d, partial %d, "
        "full %d\n",
        e1, e2, e1 / e2, seen[0], seen[1], seen[2]);
    assert_true(seen[0] > 20 && seen[1] > 20 && seen[2] > 20);
    assert_true(e1 < 1e-5);
    assert_true(e1 / e2 > 10.0 && e1 / e2 < 22.0);

    memset(seen, 0, sizeof seen);
    e1 = energy_drift("rk4", 5e-4, 0.2, seen);
    e2 = energy_drift("rk4", 2.5e-4, 0.2, seen2);
    print_message(
        "cubic, rk4: drift %.3g -> %.3g, ratio %.2f; samples flying %d, partial %d, "
        "full %d\n",
        e1, e2, e1 / e2, seen[0], seen[1], seen[2]);
    assert_true(seen[0] > 20 && seen[1] > 20 && seen[2] > 20);
    assert_true(e1 < 1e-5);
    assert_true(e1 / e2 > 10.0);

    const double e3 = energy_drift("rk8pd", 1e-3, 0.2, seen);
    print_message("cubic, rk8pd: drift %.3g\n", e3);
    assert_true(e3 < 1e-8);
}

/* ---- the stiff limit ------------------------------------------------------- */

/* Peak |theta|/alpha of the first swing: until theta changes sign after it
 * has grown past 5 % of alpha (or overturn). */
static double first_swing(const sw_scene_t *sc, const sw_pulse_t *pulse)
{
    sw_engine_t *e = engine(sc, NULL, 0.0, NULL);
    const double alpha = sw_engine_derived(e, 0)->alpha;
    sw_pulse_t p = *pulse;
    double peak = 0.0;
    int sgn = 0;
    for (int i = 1; i <= 20000; i++) {
        sw_engine_advance_fn(e, i * 1e-4, sw_pulse_eval, &p);
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        const double th = o.state.theta;
        if (o.state.phase == SW_PHASE_OVERTURNED) {
            peak = M_PI_2;
            break;
        }
        if (sgn == 0 && fabs(th) > 0.05 * alpha)
            sgn = th > 0.0 ? 1 : -1;
        if (sgn != 0 && th * sgn < 0.0)
            break;
        peak = fmax(peak, fabs(th));
    }
    sw_engine_destroy(e);
    return peak / alpha;
}

/* A very stiff, well-damped cushion on the frame approaches the frame
 * scene, slowly: physics.md quotes first-swing peak differences of about
 * 0.127, 0.052, 0.024, 0.013 (in theta/alpha) for omega_c/p = 100, 300,
 * 1000, 3000 from an independent implementation, for a pulse and scene it
 * does not give.  Our pulse (half-sine, 1.0 g tan(alpha), omega_e = 2 p,
 * braking) is a different one, so the bound is twice the quoted
 * difference, and the difference must shrink as the cushion stiffens. */
static void test_stiff_limit_is_frame(void **state)
{
    (void)state;
    const double R = hypot(1.0, 0.364), p = sqrt(3.0 * G / (4.0 * R));
    const sw_pulse_t pulse = {SW_PULSE_HALF_SINE, -1.0 * G * 0.364, 2.0 * p};
    const sw_scene_t fr = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    const double rigid = first_swing(&fr, &pulse);
    assert_true(rigid > 0.1 && rigid < 1.0);
    const double ratio[] = {100.0, 300.0, 1000.0, 3000.0};
    const double quoted[] = {0.127, 0.052, 0.024, 0.013};
    double prev = INFINITY;
    for (int k = 0; k < 4; k++) {
        const sw_scene_t sc = cushion(2.0, 0.728, ratio[k] * p, 1.0, 0.0, 5.59, 0.1);
        const double peak = first_swing(&sc, &pulse);
        const double diff = fabs(peak - rigid);
        print_message("w_c/p %5.0f: peak %.4f, frame scene %.4f, difference %.4f (quoted %.3f)\n",
                      ratio[k], peak, rigid, diff, quoted[k]);
        assert_true(diff < 2.0 * quoted[k]);
        assert_true(diff < prev);
        prev = diff;
    }
}

/* ---- margins ----------------------------------------------------------- */

/* The barrier at theta = alpha tends to the rigid block's m g R (1 - cos a)
 * as the cushion stiffens, and is lower on a soft one (the package sinks
 * into it). */
static void test_barrier_limit(void **state)
{
    (void)state;
    const double h = 1.0, b = 0.364, R = hypot(h, b), Eb = G * R * (1.0 - h / R); /* J/kg */
    sw_derived_t d;
    sw_scene_t sc = cushion(2.0 * h, 2.0 * b, 1e5, 0.1, 0.0, 0, 0.0);
    assert_int_equal(sw_scene_validate(&sc, &d, NULL, NULL, NULL), SW_OK);
    tu_near(sw_cushion_barrier(&d, G), Eb, 1e-3 * Eb);
    sc = cushion(2.0 * h, 2.0 * b, 50.0, 0.1, 0.0, 0, 0.0);
    assert_int_equal(sw_scene_validate(&sc, &d, NULL, NULL, NULL), SW_OK);
    assert_true(sw_cushion_barrier(&d, G) < 0.9 * Eb);
}

/* margin_bound is a guarantee (physics.md): once the input stops the
 * total energy can only fall (the cushion's clamp and dampers and the
 * bearing dampers only dissipate), and reaching |theta| = alpha costs the
 * barrier; so a state with margin_bound > 0 never tips in free motion.
 * Random states on the bed and on the frame. */
static void test_margin_bound_guarantee(void **state)
{
    (void)state;
    srand(12345);
    int guaranteed = 0, tipped = 0;
    for (int i = 0; i < 120; i++) {
        const int frame = i % 2;
        const sw_scene_t sc =
            cushion(2.0, 0.728, 400.0, i % 3 == 0 ? 0.0 : 0.2, 0.0, frame ? 5.59 : 0.0, 0.1);
        tu_events_t *rec = calloc(1, sizeof *rec);
        sw_engine_t *e = engine(&sc, NULL, 0.0, rec);
        sw_engine_push(e, 0.0, 0.0, 0.0);
        const sw_derived_t *d = sw_engine_derived(e, 0);
        const double zs = sw_cushion_static_deflection(d, G);
        const double u01 = rand() / (double)RAND_MAX, u02 = rand() / (double)RAND_MAX;
        const double u03 = rand() / (double)RAND_MAX, u04 = rand() / (double)RAND_MAX;
        sw_state_t st = {0};
        st.theta = (2.0 * u01 - 1.0) * 0.6 * d->alpha;
        st.theta_dot = (2.0 * u02 - 1.0) * 0.3 * d->p;
        /* resting on the lower edge, compressed by about z_s */
        st.z = zs * (1.0 + (2.0 * u03 - 1.0) * 0.5) - d->b * fabs(sin(st.theta));
        st.z_dot = (2.0 * u04 - 1.0) * 0.02;
        if (frame) {
            st.u = (2.0 * u02 - 1.0) * 0.03;
            st.u_dot = (2.0 * u01 - 1.0) * 0.1;
        }
        st.phase = SW_PHASE_ROCKING;
        sw_engine_set_state(e, 0, &st);
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        for (int k = 1; k <= 400; k++) sw_engine_push(e, k * 1e-2, 0.0, 0.0);
        sw_summary_t s;
        sw_engine_summary(e, 0, &s);
        const int tip = !isnan(s.tip_time);
        if (o.margin_bound > 0.01) {
            guaranteed++;
            assert_false(tip);
        }
        tipped += tip;
        assert_int_equal(s.faults, 0);
        sw_engine_destroy(e);
        free(rec);
    }
    print_message("%d states guaranteed, %d of all tipped\n", guaranteed, tipped);
    assert_true(guaranteed >= 20 && tipped >= 10);
}

/* ---- events against the reference --------------------------------------- */

/* A braking pulse that overturns the package: uplift, then tip at |theta|
 * = alpha, then overturn at pi/2, frozen there; the times agree with a
 * tight rk8pd run. */
static void test_tip_and_overturn(void **state)
{
    (void)state;
    const double R = hypot(1.0, 0.364), p = sqrt(3.0 * G / (4.0 * R));
    sw_pulse_t pulse = {SW_PULSE_HALF_SINE, -2.0 * G * 0.364, 2.0 * p};
    const double wcs[] = {300.0, 3000.0};
    for (int k = 0; k < 2; k++) {
        const sw_scene_t sc = cushion(2.0, 0.728, wcs[k], 0.3, 0.0, k ? 5.59 : 0.0, 0.1);
        sw_summary_t s[2];
        const char *schemes[] = {NULL, "rk8pd"};
        for (int j = 0; j < 2; j++) {
            sw_engine_opts_t o = {0};
            o.scheme = schemes[j];
            o.rtol = j ? 1e-12 : 0.0;
            o.atol = j ? 1e-16 : 0.0;
            tu_events_t *rec = calloc(1, sizeof *rec);
            o.on_event = tu_on_event;
            o.user = rec;
            sw_engine_t *e = sw_engine_create(&sc, 1, &o, NULL, NULL, 0);
            assert_non_null(e);
            sw_engine_advance_fn(e, 3.0, sw_pulse_eval, &pulse);
            sw_engine_summary(e, 0, &s[j]);
            sw_output_t out;
            sw_engine_get_output(e, 0, &out);
            assert_true(s[j].overturned);
            assert_int_equal(out.state.phase, SW_PHASE_OVERTURNED);
            tu_near(out.state.theta, M_PI_2, 1e-15); /* braking: forward */
            assert_true(s[j].uplift_time < s[j].tip_time && s[j].tip_time < s[j].overturn_time);
            const sw_event_t *tip = tu_first(rec, SW_EV_TIP);
            assert_non_null(tip);
            tu_near(tip->theta, sw_engine_derived(e, 0)->alpha, 1e-6);
            assert_non_null(tu_first(rec, SW_EV_OVERTURN));
            assert_int_equal(tu_count(rec, SW_EV_IMPACT), 0);
            sw_engine_destroy(e);
            free(rec);
        }
        print_message("w_c %g: tip %.9f / %.9f s, overturn %.9f / %.9f s\n", wcs[k], s[0].tip_time,
                      s[1].tip_time, s[0].overturn_time, s[1].overturn_time);
        tu_near(s[0].tip_time, s[1].tip_time, 1e-7);
        tu_near(s[0].overturn_time, s[1].overturn_time, 1e-7);
    }
}

/* ---- the extremes --------------------------------------------------------- */

#define NSAMP 401
typedef struct {
    double theta[NSAMP];
    int finite;
    long faults;
} sweep_run_t;

/* A squat package (0.6 m x 0.8 m, so that omega_c = 10 rad/s still holds it
 * up) hit by a short braking pulse, sampled at 1 kHz. */
static void sweep_run(const sw_scene_t *sc, const char *scheme, double rtol, double T,
                      sweep_run_t *r)
{
    sw_engine_opts_t o = {0};
    o.scheme = scheme;
    o.rtol = rtol;
    o.atol = rtol > 0.0 ? 1e-20 : 0.0;
    sw_engine_t *e = sw_engine_create(sc, 1, &o, NULL, NULL, 0);
    assert_non_null(e);
    const double g_tan = G * 0.4 / 0.3;
    sw_pulse_t p = {SW_PULSE_HALF_SINE, -1.5 * g_tan, 25.0};
    r->finite = 1;
    const int n = (int)lround(T / 1e-3);
    for (int i = 0; i <= n && i < NSAMP; i++) {
        const double t = i * 1e-3;
        sw_engine_push(e, t, sw_pulse_eval(&p, t), 0.0);
        sw_output_t out;
        sw_engine_get_output(e, 0, &out);
        r->theta[i] = out.state.theta;
        const double v[] = {out.state.theta, out.state.theta_dot, out.state.z,
                            out.state.z_dot, out.state.u,         out.state.u_dot,
                            out.margin,      out.margin_bound,    out.uplift_ratio};
        for (size_t j = 0; j < sizeof v / sizeof v[0]; j++) r->finite &= isfinite(v[j]);
    }
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    r->faults = s.faults;
    sw_engine_destroy(e);
}

/* omega_c from 10 to 1e5 rad/s, zeta_c 0, 0.05, 1, 2, with and without a
 * progressive cubic term, on the bed and on a 40 rad/s frame: the default
 * scheme (rk4 for the softest, rkck for the others) stays finite and
 * within 1e-6 rad of GSL rk8pd at rtol 1e-12 (measured: 1e-8).  rk4 asked
 * for on the stiff ones is sub-stepped and stays finite; it is stable, not
 * accurate -- a fixed step cannot follow a landing of a few microseconds
 * as the error control of rkck does -- so its bound is 5 % of the peak
 * (measured: 2 %).  The stiffest runs are short. */
static void test_extremes(void **state)
{
    (void)state;
    static sweep_run_t ref, run;
    const double wcs[] = {10.0, 100.0, 1e3, 1e4, 1e5};
    const double zcs[] = {0.0, 0.05, 1.0, 2.0};
    double worst = 0.0, worst_rk4 = 0.0;
    for (int iw = 0; iw < 5; iw++)
        for (int iz = 0; iz < 4; iz++)
            for (int ic = 0; ic < 2; ic++) {
                const double wc = wcs[iw];
                const int frame = (iw + iz + ic) % 2;
                const sw_scene_t sc = cushion(0.6, 0.8, wc, zcs[iz], ic ? progressive(wc) : 0.0,
                                              frame ? 40.0 : 0.0, 0.1);
                const double T = wc >= 1e5 ? 0.2 : wc >= 1e4 ? 0.3 : 0.4; /* s */
                sweep_run(&sc, "rk8pd", 1e-12, T, &ref);
                if (ref.faults || !ref.finite)
                    print_message("reference: w_c %g zeta %g cubic %d frame %d: faults %ld\n", wc,
                                  zcs[iz], ic, frame, ref.faults);
                assert_true(ref.finite);
                assert_int_equal(ref.faults, 0);
                const int n = (int)lround(T / 1e-3) + 1;
                for (int pass = 0; pass < (wc >= 1e3 ? 2 : 1); pass++) {
                    sweep_run(&sc, pass ? "rk4" : NULL, 0.0, T, &run);
                    double err = 0.0, peak = 0.0;
                    for (int i = 0; i < n; i++) {
                        err = fmax(err, fabs(run.theta[i] - ref.theta[i]));
                        peak = fmax(peak, fabs(ref.theta[i]));
                    }
                    if (getenv("SWEEP") || !run.finite || run.faults || (!pass && err > 1e-6))
                        print_message(
                            "w_c %g zeta %g cubic %d frame %d %s: err %.3g peak %.3g "
                            "finite %d faults %ld\n",
                            wc, zcs[iz], ic, frame, pass ? "rk4" : "default", err, peak, run.finite,
                            run.faults);
                    assert_true(run.finite);
                    assert_int_equal(run.faults, 0);
                    assert_true(pass ? err < 0.05 * peak + 1e-12 : err < 1e-6);
                    if (pass)
                        worst_rk4 = fmax(worst_rk4, err);
                    else
                        worst = fmax(worst, err);
                }
            }
    print_message("worst |theta - reference|: default %.3g rad, rk4 sub-stepped %.3g rad\n", worst,
                  worst_rk4);
}

/* ---- steps and schemes ------------------------------------------------------ */

/* The default scheme: rk4 for a soft cushion, rkck for one rk4 would have
 * to sub-step; omega_max includes damping (3.73 omega_c at zeta_c = 2),
 * and a forced dt above the bound is refused with the numbers. */
static void test_schemes_and_forced_dt(void **state)
{
    (void)state;
    sw_scene_t sc = cushion(2.0, 0.728, 30.0, 0.1, 0.0, 0, 0.0);
    sw_engine_t *e = engine(&sc, NULL, 0.0, NULL);
    assert_string_equal(sw_engine_scheme(e), "rk4");
    tu_near(sw_engine_dt(e, 0), 1e-3, 1e-15);
    sw_engine_destroy(e);
    sc = cushion(2.0, 0.728, 1e4, 2.0, 0.0, 1, 0.1);
    e = engine(&sc, NULL, 0.0, NULL);
    assert_string_equal(sw_engine_scheme(e), SW_STIFF_SCHEME);
    const double wmax = sw_engine_derived(e, 0)->omega_max;
    tu_near(wmax, 1e4 * (2.0 + sqrt(3.0)), 1e-9 * wmax);
    sw_engine_destroy(e);
    /* rk4 asked for: sub-stepped to omega_max h <= 0.5 */
    e = engine(&sc, "rk4", 1e-3, NULL);
    tu_near(sw_engine_dt(e, 0), 0.5 / wmax, 1e-12);
    sw_engine_destroy(e);

    sw_engine_opts_t o = {0};
    o.scheme = "rk4";
    o.dt_forced = 1;
    o.dt = 1.05 * 2.785 / wmax;
    int err = 0;
    char msg[512];
    e = sw_engine_create(&sc, 1, &o, &err, msg, sizeof msg);
    assert_null(e);
    assert_int_equal(err, SW_EUNSTABLE);
    assert_non_null(strstr(msg, "stability bound"));
    assert_non_null(strstr(msg, "3.732e+04"));
    o.dt = 0.95 * 2.785 / wmax;
    e = sw_engine_create(&sc, 1, &o, &err, msg, sizeof msg);
    assert_non_null(e);
    sw_engine_destroy(e);
    /* a forced dt without a scheme keeps rk4, so that it is refused too */
    o.scheme = NULL;
    o.dt = 1e-3;
    e = sw_engine_create(&sc, 1, &o, &err, msg, sizeof msg);
    assert_null(e);
    assert_int_equal(err, SW_EUNSTABLE);
}

/* The implicit schemes run the cushion too (GSL needs a Jacobian for them,
 * or it crashes), and agree with rk8pd. */
static void test_implicit_schemes(void **state)
{
    (void)state;
    static sweep_run_t ref, run;
    const sw_scene_t sc = cushion(0.6, 0.8, 1e4, 0.05, 0.0, 40.0, 0.1);
    sweep_run(&sc, "rk8pd", 1e-12, 0.2, &ref);
    const char *schemes[] = {"rk4imp", "bsimp", "msbdf"};
    const double tol[] = {1e-8, 1e-8, 1e-6};
    for (int k = 0; k < 3; k++) {
        sweep_run(&sc, schemes[k], 1e-10, 0.2, &run);
        double err = 0.0;
        for (int i = 0; i <= 200; i++) err = fmax(err, fabs(run.theta[i] - ref.theta[i]));
        print_message("%s: err %.3g rad\n", schemes[k], err);
        assert_true(run.finite);
        assert_int_equal(run.faults, 0);
        assert_true(err < tol[k]);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_static_deflection),
        cmocka_unit_test(test_vertical_frequency),
        cmocka_unit_test(test_rocking_frequency),
        cmocka_unit_test(test_quasistatic_uplift),
        cmocka_unit_test(test_damping_clamp),
        cmocka_unit_test(test_partial_contact_equilibrium),
        cmocka_unit_test(test_energy_conservation),
        cmocka_unit_test(test_stiff_limit_is_frame),
        cmocka_unit_test(test_barrier_limit),
        cmocka_unit_test(test_margin_bound_guarantee),
        cmocka_unit_test(test_tip_and_overturn),
        cmocka_unit_test(test_extremes),
        cmocka_unit_test(test_schemes_and_forced_dt),
        cmocka_unit_test(test_implicit_schemes),
        cmocka_unit_test(test_rate_cap),
        cmocka_unit_test(test_rhs_memo),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
