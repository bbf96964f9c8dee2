/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_stuck_frame.c - the exact advance of a stuck frame (a linear
 * oscillator under piecewise-linear input, Nigam-Jennings): against the
 * closed-form step and ramp responses for under-, critically and
 * over-damped bearings, across a long gap between samples, uplift located
 * on the exact solution, and agreement with the frame stepped by RK4. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
/* cmocka needs the four above first */
#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define G 9.81

/* Response of u'' + 2 z w u' + w^2 u = -(a + k t) from rest: the
 * particular solution u_p = c0 + c1 t (c1 = -k/w^2, c0 = (-a - 2 z w c1)/w^2)
 * plus the free motion from (-c0, -c1), written out per damping case. */
static void closed_form(double a, double k, double w, double z, double t, double *u, double *ud)
{
    const double c1 = -k / (w * w), c0 = (-a - 2.0 * z * w * c1) / (w * w);
    const double x0 = -c0, v0 = -c1;
    double x, v;
    if (z < 1.0) {
        const double wd = w * sqrt(1.0 - z * z), ex = exp(-z * w * t);
        const double A = x0, B = (v0 + z * w * x0) / wd;
        x = ex * (A * cos(wd * t) + B * sin(wd * t));
        v = ex * ((-z * w * A + wd * B) * cos(wd * t) + (-z * w * B - wd * A) * sin(wd * t));
    } else if (z == 1.0) {
        const double ex = exp(-w * t), B = v0 + w * x0;
        x = ex * (x0 + B * t);
        v = ex * (B - w * (x0 + B * t));
    } else {
        const double r1 = -z * w + w * sqrt(z * z - 1.0), r2 = -z * w - w * sqrt(z * z - 1.0);
        const double A = (v0 - r2 * x0) / (r1 - r2), B = x0 - A;
        x = A * exp(r1 * t) + B * exp(r2 * t);
        v = A * r1 * exp(r1 * t) + B * r2 * exp(r2 * t);
    }
    *u = c0 + c1 * t + x;
    *ud = c1 + v;
}

/* Sampled step (a constant from t = 0) and ramp inputs below the uplift
 * threshold: the frame follows the closed form at every sample to round-off,
 * for several sample intervals (the exact advance has no step size). */
static void test_step_and_ramp(void **state)
{
    (void)state;
    const double w = 5.59;
    const double zetas[] = {0.0, 0.1, 1.0, 3.0};
    const double dts[] = {1e-3, 0.0137, 0.25};
    const double thr = G * 0.364;
    for (size_t iz = 0; iz < 4; iz++)
        for (size_t id = 0; id < 3; id++)
            for (int ramp = 0; ramp < 2; ramp++) {
                const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, w, zetas[iz]);
                tu_events_t rec = {0};
                sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, &rec);
                const double a = ramp ? 0.0 : -0.4 * thr, k = ramp ? -0.02 * thr : 0.0;
                const double U = 0.4 * thr / (w * w); /* m, scale of the motion */
                double worst = 0.0, worst_v = 0.0;
                for (int i = 0; i * dts[id] <= 20.0; i++) {
                    const double t = i * dts[id];
                    sw_engine_push(e, t, a + k * t, 0.0);
                    sw_output_t o;
                    sw_engine_get_output(e, 0, &o);
                    double u, ud;
                    closed_form(a, k, w, zetas[iz], t, &u, &ud);
                    worst = fmax(worst, fabs(o.state.u - u));
                    worst_v = fmax(worst_v, fabs(o.state.u_dot - ud));
                }
                assert_int_equal(rec.n, 0); /* stays stuck */
                if (worst > 1e-12 * U || worst_v > 1e-12 * U * w)
                    print_message("zeta %g dt %g ramp %d: |du| %.3g |dv| %.3g (U %.3g)\n",
                                  zetas[iz], dts[id], ramp, worst, worst_v, U);
                assert_true(worst <= 1e-12 * U);
                assert_true(worst_v <= 1e-12 * U * w);
                sw_engine_destroy(e);
            }
}

/* A ramp that crosses the uplift threshold of the moving frame between
 * samples: uplift at the crossing of the closed form, found here by
 * bisection on it, to round-off. */
static void test_uplift_on_ramp(void **state)
{
    (void)state;
    const double w = 5.59, z = 0.1, k = -0.5 * G * 0.364, T = G * 0.364;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, w, z);
    /* A = -(2 z w u' + w^2 u) reaches -T; scan then bisect the closed form */
    double lo = 0.0, hi = 0.0;
    for (double t = 0.0; t < 10.0; t += 1e-3) {
        double u, ud;
        closed_form(0.0, k, w, z, t, &u, &ud);
        if (-(2.0 * z * w * ud + w * w * u) <= -T) {
            hi = t;
            break;
        }
        lo = t;
    }
    assert_true(hi > 0.0);
    for (int i = 0; i < 200; i++) {
        const double m = 0.5 * (lo + hi);
        double u, ud;
        closed_form(0.0, k, w, z, m, &u, &ud);
        if (-(2.0 * z * w * ud + w * w * u) <= -T)
            hi = m;
        else
            lo = m;
    }
    const double dts[] = {1e-3, 0.01, 0.3};
    for (int id = 0; id < 3; id++) {
        tu_events_t rec = {0};
        sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, &rec);
        for (int i = 0; i * dts[id] <= hi + 1.0; i++)
            sw_engine_push(e, i * dts[id], k * i * dts[id], 0.0);
        const sw_event_t *up = tu_first(&rec, SW_EV_UPLIFT);
        assert_non_null(up);
        tu_near(up->t, hi, 1e-11);
        assert_int_equal((int)up->info, 1);
        sw_engine_destroy(e);
    }
}

/* A frame still swinging when the log stops for an hour, then resumes at
 * the same acceleration: the gap costs a handful of steps, not 3.6 million,
 * and the state after it is the closed form's. */
static void test_long_gap(void **state)
{
    (void)state;
    const double w = 5.59, z = 0.02, a = -0.3 * G * 0.364;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, w, z);
    sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, NULL);
    sw_engine_push(e, 0.0, a, 0.0);
    sw_engine_push(e, 1e-3, a, 0.0);
    sw_engine_push(e, 3600.0 + 1e-3, a, 0.0);
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_true(s.steps < 10);
    sw_output_t o;
    sw_engine_get_output(e, 0, &o);
    double u, ud;
    closed_form(a, 0.0, w, z, 3600.0 + 1e-3, &u, &ud);
    tu_near(o.state.u, u, 1e-12 * fabs(u));
    tu_near(o.state.u_dot, ud, 1e-12);
    /* undamped, swinging close to the threshold: still exact, still cheap
     * compared with stepping (w / 0.5 pieces per second at most) */
    const sw_scene_t sc0 = tu_frame(2.0, 0.728, 250.0, w, 0.0);
    sw_engine_t *e0 = tu_engine(&sc0, "rk4", 1e-3, NULL);
    const double a0 = -0.49 * G * 0.364; /* overshoot to 0.98 of the threshold */
    sw_engine_push(e0, 0.0, a0, 0.0);
    sw_engine_push(e0, 600.0, a0, 0.0);
    sw_engine_summary(e0, 0, &s);
    assert_int_equal(s.uplifts, 0);
    sw_engine_get_output(e0, 0, &o);
    closed_form(a0, 0.0, w, 0.0, 600.0, &u, &ud);
    tu_near(o.state.u, u, 1e-9 * fabs(u));
    sw_engine_destroy(e0);
    sw_engine_destroy(e);
}

/* Vibration, then a braking shock that lifts the package on the frame, then
 * vibration again: the exact stuck phases and the RK4-stepped ones give the
 * same run to RK4's accuracy (both are checked against rk8pd). */
typedef struct {
    double t_up, th_max, t_over;
    long uplifts, impacts;
} run_t;

static double shock_input(double t)
{
    const double v = 0.6 * sin(2.0 * M_PI * 3.1 * t) + 0.4 * sin(2.0 * M_PI * 11.3 * t + 1.0);
    const double b = (t > 2.0 && t < 2.6) ? -1.05 * G * 0.364 * sin(M_PI * (t - 2.0) / 0.6) : 0.0;
    return v + b;
}

static run_t run_shock(const char *scheme, int stepped, const sw_scene_t *sc)
{
    sw_engine_opts_t o = {0};
    o.scheme = scheme;
    o.stuck_stepped = stepped;
    sw_engine_t *e = sw_engine_create(sc, 1, &o, NULL, NULL, 0);
    assert_non_null(e);
    for (int i = 0; i <= 12000; i++) sw_engine_push(e, i * 1e-3, shock_input(i * 1e-3), 0.0);
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    sw_engine_destroy(e);
    return (run_t){s.uplift_time, s.max_abs_theta, s.overturn_time, s.uplifts, s.impacts};
}

static void test_matches_stepped(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    const run_t ex = run_shock("rk4", 0, &sc), st = run_shock("rk4", 1, &sc);
    const run_t ref = run_shock("rk8pd", 0, &sc);
    print_message(
        "uplift %.12f / %.12f / ref %.12f; max theta %.10f / %.10f / %.10f; "
        "impacts %ld %ld %ld\n",
        ex.t_up, st.t_up, ref.t_up, ex.th_max, st.th_max, ref.th_max, ex.impacts, st.impacts,
        ref.impacts);
    assert_true(ref.uplifts >= 1 && ref.impacts >= 1);
    assert_int_equal(ex.uplifts, ref.uplifts);
    assert_int_equal(st.uplifts, ref.uplifts);
    /* the exact path is at least as close to the reference as the stepped one */
    assert_true(fabs(ex.t_up - ref.t_up) <= fabs(st.t_up - ref.t_up) + 1e-12);
    tu_near(ex.t_up, st.t_up, 1e-8);
    tu_near(ex.th_max, st.th_max, 1e-7);
    tu_near(ex.th_max, ref.th_max, 1e-7);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_step_and_ramp),
        cmocka_unit_test(test_uplift_on_ramp),
        cmocka_unit_test(test_long_gap),
        cmocka_unit_test(test_matches_stepped),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
