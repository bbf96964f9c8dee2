/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_extremes.c - the engine at the edges of its range, each case either
 * within a stated error of the rk8pd reference (rtol 1e-12) or of a closed
 * form, or refused clearly: slenderness alpha 1..45 deg, size R 0.05..10 m,
 * pulses up to 50 g and omega_e/p up to 100, internal steps from 1e-6 s to
 * the sample interval, bearings from nearly free to nearly rigid, gamma
 * towards 0 and 1, a free-rocking cascade of thousands of impacts, and an
 * hour without samples. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
/* cmocka needs the four above first */
#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define G 9.81
#define DEG (M_PI / 180.0)

/* A block of half-diagonal R (m) and slenderness alpha (rad). */
static sw_scene_t block(double R, double alpha)
{
    return tu_bare(2.0 * R * cos(alpha), 2.0 * R * sin(alpha));
}

static sw_scene_t on_frame(sw_scene_t sc, double frame_mass, double omega, double zeta)
{
    sc.has_frame = 1;
    sc.frame_mass = frame_mass;
    sc.frame_omega = omega;
    sc.frame_zeta = zeta;
    sc.frame_k_given = sc.frame_c_given = SW_GIVEN_RATIO;
    return sc;
}

/* Half-sine braking pulse of ratio * g tan(alpha) at omega_e = wp * p,
 * sampled at `rate` Hz for t_end s (or until overturn). */
static sw_summary_t run(const sw_scene_t *sc, const char *scheme, double dt, double ratio,
                        double wp, double rate, double t_end)
{
    sw_engine_opts_t o = {0};
    o.scheme = scheme;
    o.dt = dt;
    o.rtol = strcmp(scheme, "rk8pd") ? 0.0 : 1e-12;
    o.atol = o.rtol * 1e-2;
    sw_summary_t s;
    memset(&s, 0, sizeof s);
    sw_engine_t *e = sw_engine_create(sc, 1, &o, NULL, NULL, 0);
    assert_non_null(e);
    const sw_derived_t *d = sw_engine_derived(e, 0);
    sw_pulse_t pu = {SW_PULSE_HALF_SINE, -ratio * G * tan(d->alpha), wp * d->p};
    const long n = (long)(t_end * rate);
    for (long i = 0; i <= n; i++) {
        sw_engine_push(e, i / rate, sw_pulse_eval(&pu, i / rate), 0.0);
        sw_engine_summary(e, 0, &s);
        if (s.overturned)
            break;
    }
    sw_engine_destroy(e);
    return s;
}

/* The default against the reference: same decision, max|theta| within
 * tol_theta (rad), overturn time within tol_t (s). */
static void check_vs_ref(const sw_scene_t *sc, double ratio, double wp, double t_end,
                         double tol_theta, double tol_t, const char *what)
{
    const sw_summary_t a = run(sc, "rk4", 0.0, ratio, wp, 1000.0, t_end);
    const sw_summary_t r = run(sc, "rk8pd", 0.0, ratio, wp, 1000.0, t_end);
    print_message("%-28s over %d/%d  theta_max %.6g (err %.1e)  t_over err %.1e  impacts %ld\n",
                  what, a.overturned, r.overturned, r.max_abs_theta,
                  fabs(a.max_abs_theta - r.max_abs_theta),
                  r.overturned ? fabs(a.overturn_time - r.overturn_time) : 0.0, r.impacts);
    assert_int_equal(a.faults, 0);
    assert_int_equal(r.faults, 0);
    assert_int_equal(a.overturned, r.overturned);
    if (r.overturned)
        tu_near(a.overturn_time, r.overturn_time, tol_t);
    else
        tu_near(a.max_abs_theta, r.max_abs_theta, tol_theta);
}

static void test_alpha_range(void **state)
{
    (void)state;
    const double alphas[] = {1.0, 5.0, 20.0, 45.0};
    for (int k = 0; k < 4; k++) {
        const sw_scene_t sc = block(1.0, alphas[k] * DEG);
        char what[64];
        snprintf(what, sizeof what, "alpha %g deg", alphas[k]);
        check_vs_ref(&sc, 1.5, 3.0, 8.0, 1e-8, 1e-8, what);
        snprintf(what, sizeof what, "alpha %g deg, strong", alphas[k]);
        check_vs_ref(&sc, 6.0, 3.0, 8.0, 1e-8, 1e-8, what);
    }
}

static void test_size_range(void **state)
{
    (void)state;
    const double Rs[] = {0.05, 1.0, 10.0};
    for (int k = 0; k < 3; k++) {
        const sw_scene_t sc = block(Rs[k], 20.0 * DEG);
        char what[64];
        snprintf(what, sizeof what, "R %g m", Rs[k]);
        /* small blocks rock fast: p = 12 rad/s at R = 0.05 m, (p dt)^4 ~ 2e-8 */
        check_vs_ref(&sc, 2.0, 3.0, Rs[k] < 0.1 ? 3.0 : 12.0, 1e-7, 1e-7, what);
    }
}

/* 50 g at omega_e / p = 100 (a 12 ms knock on the crate); 5 g at 30. */
static void test_violent_pulses(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const double thr = tan(atan(0.364)); /* a_e / (g tan alpha) = 50 g / (g tan alpha) */
    check_vs_ref(&sc, 50.0 / thr, 100.0, 8.0, 1e-7, 1e-7, "50 g, omega_e/p 100");
    check_vs_ref(&sc, 5.0 / thr, 30.0, 8.0, 1e-7, 1e-7, "5 g, omega_e/p 30");
    check_vs_ref(&sc, 30.0, 100.0, 8.0, 1e-7, 1e-7, "30 x uplift, omega_e/p 100");
    const sw_scene_t fr = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    check_vs_ref(&fr, 50.0 / thr, 100.0, 8.0, 1e-7, 1e-7, "frame, 50 g, omega_e/p 100");
}

/* From 1e-6 s to the sample interval the default scheme stays within its
 * own error of the reference (round-off grows with the step count, slowly). */
static void test_dt_range(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const sw_summary_t r = run(&sc, "rk8pd", 0.0, 2.0, 3.0, 1000.0, 2.5);
    const double dts[] = {1e-6, 1e-5, 1e-4, 1e-3, 1e-2};
    for (int k = 0; k < 5; k++) {
        const sw_summary_t a = run(&sc, "rk4", dts[k], 2.0, 3.0, 1000.0, 2.5);
        print_message("dt %g: theta_max err %.2e, steps %ld\n", dts[k],
                      fabs(a.max_abs_theta - r.max_abs_theta), a.steps);
        assert_int_equal(a.faults, 0);
        tu_near(a.max_abs_theta, r.max_abs_theta, 1e-9);
    }
    /* a dt above the sample interval is cut to it: 1e-2 s and 1e-3 s agree */
    const sw_summary_t a2 = run(&sc, "rk4", 1e-2, 2.0, 3.0, 1000.0, 2.5);
    const sw_summary_t a3 = run(&sc, "rk4", 1e-3, 2.0, 3.0, 1000.0, 2.5);
    assert_true(a2.max_abs_theta == a3.max_abs_theta);
}

/* Bearings from nearly free (omega_b = 0.01 rad/s) to nearly rigid
 * (1e5 rad/s, sub-stepped to omega h <= 0.5; rigid bearings give the bare
 * block); a forced step above the stability bound is refused. */
static void test_bearing_stiffness(void **state)
{
    (void)state;
    /* nearly free: the frame takes the pulse and the crate does not lift;
     * the frame's drift u after the pulse is exact (stuck phase) */
    for (int z = 0; z < 2; z++) {
        const sw_scene_t soft = tu_frame(2.0, 0.728, 250.0, 0.01, z ? 0.1 : 0.0);
        double u[2];
        for (int k = 0; k < 2; k++) {
            sw_engine_t *e = tu_engine(&soft, k ? "rk8pd" : "rk4", 0.0, NULL);
            sw_pulse_t pu = {SW_PULSE_HALF_SINE, -1.5 * G * 0.364, 3.0 * 2.6294};
            for (int i = 0; i <= 4000; i++)
                sw_engine_push(e, i * 1e-3, sw_pulse_eval(&pu, i * 1e-3), 0.0);
            sw_output_t o;
            sw_engine_get_output(e, 0, &o);
            sw_summary_t s;
            sw_engine_summary(e, 0, &s);
            assert_int_equal(s.uplifts, 0);
            u[k] = o.state.u;
            sw_engine_destroy(e);
        }
        print_message("omega_b 0.01, zeta %g: u %.12g m, reference %.12g m\n", z ? 0.1 : 0.0, u[0],
                      u[1]);
        tu_near(u[0], u[1], 1e-9 * fabs(u[1]));
    }
    const sw_scene_t stiff = tu_frame(2.0, 0.728, 250.0, 1e5, 0.05);
    const sw_scene_t bare = tu_bare(2.0, 0.728);
    const sw_summary_t a = run(&stiff, "rk4", 0.0, 1.5, 3.0, 1000.0, 3.0);
    const sw_summary_t b = run(&bare, "rk4", 0.0, 1.5, 3.0, 1000.0, 3.0);
    print_message("omega_b 1e5: theta_max %.8g, bare %.8g\n", a.max_abs_theta, b.max_abs_theta);
    assert_int_equal(a.faults, 0);
    tu_near(a.max_abs_theta, b.max_abs_theta, 1e-4 * b.max_abs_theta);
    sw_engine_opts_t o = {0};
    o.dt = 1e-3;
    o.dt_forced = 1;
    int err = 0;
    char msg[512];
    assert_null(sw_engine_create(&stiff, 1, &o, &err, msg, sizeof msg));
    assert_int_equal(err, SW_EUNSTABLE);
}

/* gamma -> 0 (a frame 1e4 times heavier than the crate, stiff bearings)
 * is the bare block; gamma -> 1 (a 1 g frame) is still integrated to the
 * reference's accuracy. */
static void test_gamma_limits(void **state)
{
    (void)state;
    const sw_scene_t heavy = tu_frame(2.0, 0.728, 1e7, 5000.0, 0.7);
    const sw_scene_t bare = tu_bare(2.0, 0.728);
    const sw_summary_t a = run(&heavy, "rk4", 0.0, 1.5, 3.0, 1000.0, 3.0);
    const sw_summary_t b = run(&bare, "rk4", 0.0, 1.5, 3.0, 1000.0, 3.0);
    print_message("gamma 1e-4: theta_max %.8g, bare %.8g\n", a.max_abs_theta, b.max_abs_theta);
    tu_near(a.max_abs_theta, b.max_abs_theta, 1e-3 * b.max_abs_theta);
    const sw_scene_t light = tu_frame(2.0, 0.728, 1e-3, 5.59, 0.1);
    check_vs_ref(&light, 1.5, 3.0, 8.0, 1e-8, 1e-8, "gamma 1 - 1e-6");
    const sw_scene_t light2 = on_frame(block(1.0, 45.0 * DEG), 1e-3, 20.0, 0.02);
    check_vs_ref(&light2, 3.0, 3.0, 8.0, 1e-8, 1e-8, "gamma 1 - 1e-6, alpha 45 deg");
}

/* Free rocking from 0.999 alpha of a slender block (alpha = 4 deg, eta =
 * 0.9927) with rest at 1e-14 of the barrier: about two thousand impacts.
 * With no input the speed before each impact is eta times the one before
 * (energy is conserved between impacts); the cascade ends in rest. */
static tu_events_t cascade_rec;
static void test_rocking_cascade(void **state)
{
    (void)state;
    const double alpha = 4.0 * DEG;
    const sw_scene_t sc = block(1.0, alpha);
    sw_engine_opts_t o = {0};
    o.rest_eps = 1e-14;
    o.on_event = tu_on_event;
    o.user = &cascade_rec;
    sw_engine_t *e = sw_engine_create(&sc, 1, &o, NULL, NULL, 0);
    assert_non_null(e);
    const double eta = sw_engine_derived(e, 0)->eta;
    sw_engine_push(e, 0.0, 0.0, 0.0);
    sw_state_t st = {0};
    st.theta = 0.999 * alpha;
    st.phase = SW_PHASE_ROCKING;
    st.side = 1;
    sw_engine_set_state(e, 0, &st);
    for (int i = 1; i <= 100000 && tu_count(&cascade_rec, SW_EV_REST) == 0; i++)
        sw_engine_push(e, i * 1e-2, 0.0, 0.0); /* 10 ms samples, 1 ms steps */
    const int n = tu_count(&cascade_rec, SW_EV_IMPACT);
    /* |v_k+1| = eta |v_k| to 1e-9, plus 1e-12 rad/s: late in the cascade
     * the speeds are tiny and the impact times, near t = 100 s, resolve to
     * about 1e-14 s, so each speed is known to about 1e-14 s x theta'' */
    double worst = 0.0, worst_abs = 0.0, prev = 0.0;
    int k = 0;
    for (int i = 0; i < cascade_rec.n; i++) {
        const sw_event_t *ev = &cascade_rec.ev[i];
        if (ev->kind != SW_EV_IMPACT)
            continue;
        if (k > 0 && ev->theta_dot != 0.0) {
            const double dev = fabs(fabs(ev->info) - eta * fabs(prev));
            if (fabs(prev) > 1e-3)
                worst = fmax(worst, dev / fabs(prev));
            worst_abs = fmax(worst_abs, dev - 1e-9 * fabs(prev));
        }
        prev = ev->info;
        k++;
    }
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    print_message(
        "eta %.10f: %d impacts, worst |ratio - eta| %.2e (speeds > 1e-3 rad/s), "
        "worst excess %.2e rad/s, rest at %.6f s, %ld steps\n",
        eta, n, worst, worst_abs, cascade_rec.ev[cascade_rec.n - 1].t, s.steps);
    assert_true(n > 1000);
    assert_true(worst < 1e-9);
    assert_true(worst_abs < 1e-12);
    assert_int_equal(tu_count(&cascade_rec, SW_EV_REST), 1);
    assert_int_equal(s.faults, 0);
    assert_int_equal(s.overturned, 0);
    sw_engine_destroy(e);
}

/* An hour without samples (the logger stopped): the input is interpolated
 * linearly across the gap, as between any two samples.  A block at rest
 * costs nothing, a frame at rest or still swinging a few exact pieces, and a
 * package still rocking when the gap starts rocks to rest and then stands. */
static void test_hour_gap(void **state)
{
    (void)state;
    const sw_scene_t bare = tu_bare(2.0, 0.728);
    const sw_scene_t fr = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    for (int m = 0; m < 2; m++) {
        sw_engine_t *e = tu_engine(m ? &fr : &bare, "rk4", 0.0, NULL);
        const double a = -0.5 * G * 0.364;
        sw_engine_push(e, 0.0, a, 0.0);
        sw_engine_push(e, 1e-3, a, 0.0);
        sw_engine_push(e, 3600.0, a, 0.0);
        sw_summary_t s;
        sw_engine_summary(e, 0, &s);
        print_message("%s at rest across 1 h: %ld steps\n", m ? "frame" : "bare", s.steps);
        assert_true(s.steps <= (m ? 10 : 0));
        assert_int_equal(s.uplifts, 0);
        sw_engine_destroy(e);
    }
    /* rocking when the gap starts */
    sw_engine_t *e = tu_engine(&fr, "rk4", 0.0, NULL);
    sw_engine_push(e, 0.0, 0.0, 0.0);
    sw_state_t st = {0};
    st.theta = 0.5 * atan(0.364);
    st.phase = SW_PHASE_ROCKING;
    st.side = 1;
    sw_engine_set_state(e, 0, &st);
    sw_engine_push(e, 3600.0, 0.0, 0.0);
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    sw_output_t o;
    sw_engine_get_output(e, 0, &o);
    print_message("frame rocking into a 1 h gap: %ld steps, %ld impacts, phase %d\n", s.steps,
                  s.impacts, o.state.phase);
    assert_int_equal(o.state.phase, SW_PHASE_STUCK);
    assert_int_equal(s.rests, 1);
    assert_true(s.steps < 200000);
    sw_engine_destroy(e);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_alpha_range),       cmocka_unit_test(test_size_range),
        cmocka_unit_test(test_violent_pulses),    cmocka_unit_test(test_dt_range),
        cmocka_unit_test(test_bearing_stiffness), cmocka_unit_test(test_gamma_limits),
        cmocka_unit_test(test_rocking_cascade),   cmocka_unit_test(test_hour_gap),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
