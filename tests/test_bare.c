/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_bare.c - the bare rocking block (scene 1) against closed forms:
 * uplift threshold, free rocking (quadrature of the energy integral),
 * Housner's impact ratio, rest, grid independence of located events. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "testutil.h"

#define G 9.81

/* height 2.0 m, width 0.728 m: the DESIGN.md crate */
static sw_scene_t crate(void)
{
    return tu_bare(2.0, 0.728);
}

static double alpha_of(double height, double width)
{
    return atan(width / height);
}

/* Constant acceleration 1% below g tan(alpha) never lifts; 1% above lifts
 * in the direction physics.md gives (braking tips the top forward). */
static void test_uplift_threshold(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    const double thr = G * tan(alpha_of(2.0, 0.728));
    const double factors[] = {-0.99, 0.99, -1.01, 1.01};
    for (int k = 0; k < 4; k++) {
        tu_events_t rec = {0};
        sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, &rec);
        assert_non_null(e);
        for (int i = 0; i <= 2000; i++) sw_engine_push(e, i * 1e-3, factors[k] * thr, 0.0);
        sw_summary_t s;
        sw_engine_summary(e, 0, &s);
        if (fabs(factors[k]) < 1.0) {
            assert_int_equal(s.uplifts, 0);
            assert_true(s.max_abs_theta == 0.0);
        } else {
            assert_int_equal(s.uplifts, 1);
            const sw_event_t *up = tu_first(&rec, SW_EV_UPLIFT);
            assert_non_null(up);
            assert_true(up->t == 0.0); /* beyond the threshold from the first sample */
            const int fwd = factors[k] < 0.0;
            assert_int_equal((int)up->info, fwd ? 1 : -1);
            sw_output_t o;
            sw_engine_get_output(e, 0, &o);
            assert_true(fwd ? o.state.theta > 0.0 : o.state.theta < 0.0);
        }
        sw_engine_destroy(e);
    }
}

/* A ramp crosses the threshold between samples: uplift is placed at the
 * exact crossing of the linearly interpolated input, not at a sample. */
static void test_uplift_between_samples(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    const double thr = G * tan(alpha_of(2.0, 0.728));
    tu_events_t rec = {0};
    sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, &rec);
    /* a = -thr * t / 0.1234 reaches -thr at t = 0.1234 s */
    for (int i = 0; i <= 200; i++) sw_engine_push(e, i * 1e-3, -thr * (i * 1e-3) / 0.1234, 0.0);
    const sw_event_t *up = tu_first(&rec, SW_EV_UPLIFT);
    assert_non_null(up);
    tu_near(up->t, 0.1234, 1e-12);
    assert_int_equal((int)up->info, 1);
    sw_engine_destroy(e);
}

/* Free rocking from rest at theta0: with no input, energy gives
 *   theta'^2 = 2 p^2 (cos(alpha - theta0) - cos(alpha - theta)),
 * so the time to reach theta = 0 is
 *   t1 = int_0^theta0 dtheta / (p sqrt(2 (cos(alpha - theta0) - cos(alpha - theta)))).
 * With theta = theta0 (1 - v^2) the endpoint singularity disappears:
 *   t1 = int_0^1 2 theta0 v dv / (p sqrt(2 (cos(alpha - theta0) - cos(alpha - theta0 (1 - v^2))))).
 * After the impact theta' is multiplied by eta = 1 - 1.5 sin^2 alpha, the
 * block rises on the other corner to theta1 with
 *   cos(alpha - theta1) = cos(alpha) + theta'^2 / (2 p^2)
 * and returns after 2 t(theta1). */
typedef struct {
    double alpha, p, theta0;
} quarter_t;

static double quarter_integrand(double v, void *u)
{
    const quarter_t *q = u;
    const double th = q->theta0 * (1.0 - v * v);
    const double den = q->p * sqrt(2.0 * (cos(q->alpha - q->theta0) - cos(q->alpha - th)));
    return 2.0 * q->theta0 * v / den;
}

static double time_to_upright(double alpha, double p, double theta0)
{
    quarter_t q = {alpha, p, theta0};
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
    gsl_function F = {quarter_integrand, &q};
    double r, err;
    gsl_integration_qags(&F, 0.0, 1.0, 1e-13, 1e-12, 200, w, &r, &err);
    gsl_integration_workspace_free(w);
    return r;
}

static void test_free_rocking(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    const double alpha = alpha_of(2.0, 0.728);
    const double R = sqrt(1.0 + 0.364 * 0.364);
    const double p = sqrt(3.0 * G / (4.0 * R));
    const double eta = 1.0 - 1.5 * sin(alpha) * sin(alpha);
    const double theta0 = 0.5 * alpha;
    const char *schemes[] = {"rk4", "rk8pd"};
    for (int k = 0; k < 2; k++) {
        tu_events_t rec = {0};
        sw_engine_t *e = tu_engine(&sc, schemes[k], 1e-3, &rec);
        sw_engine_push(e, 0.0, 0.0, 0.0);
        sw_state_t st = {0};
        st.theta = theta0;
        st.phase = SW_PHASE_ROCKING;
        st.side = 1;
        sw_engine_set_state(e, 0, &st);
        for (int i = 1; i <= 20000; i++) sw_engine_push(e, i * 1e-3, 0.0, 0.0);

        const double t1 = time_to_upright(alpha, p, theta0);
        const double w1 = -p * sqrt(2.0 * (cos(alpha - theta0) - cos(alpha)));
        const sw_event_t *imp = tu_first(&rec, SW_EV_IMPACT);
        assert_non_null(imp);
        tu_near(imp->t, t1, 1e-9 * t1);
        tu_near(imp->info, w1, 1e-9 * fabs(w1));
        /* second impact: rise on the rear corner and back */
        const double wp = eta * w1;
        const double theta1 = alpha - acos(cos(alpha) + wp * wp / (2.0 * p * p));
        const double t2 = t1 + 2.0 * time_to_upright(alpha, p, theta1);
        int seen = 0, last_rest = 0;
        for (int i = 0; i < rec.n; i++) {
            const sw_event_t *ev = &rec.ev[i];
            if (ev->kind == SW_EV_IMPACT) {
                /* every impact: theta'+ = eta theta'-, kinetic energy ratio eta^2 */
                const double ratio = (ev->theta_dot * ev->theta_dot) / (ev->info * ev->info);
                if (ev->theta_dot != 0.0)
                    tu_near(ratio, eta * eta, 1e-12);
                if (++seen == 2)
                    tu_near(ev->t, t2, 1e-8 * t2);
            }
            if (ev->kind == SW_EV_REST)
                last_rest = i;
        }
        assert_true(seen > 10);
        assert_true(last_rest > 0); /* the cascade ends */
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        assert_int_equal(o.state.phase, SW_PHASE_STUCK);
        assert_true(o.margin == 1.0);
        sw_engine_destroy(e);
    }
}

/* Piecewise linear braking: 0 at 0 s, -1.5 g tan(alpha) at 0.2 s, 0 at 0.4 s. */
static double braking(double t, double thr)
{
    if (t <= 0.0 || t >= 0.4)
        return 0.0;
    return t < 0.2 ? -1.5 * thr * t / 0.2 : -1.5 * thr * (0.4 - t) / 0.2;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The same continuous input sampled on two grids offset by 0.37 ms (both
 * containing the input's corners): the located events agree to the
 * scheme's accuracy, not to the grid. */
static void test_grid_independence(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    const double thr = G * tan(alpha_of(2.0, 0.728));
    static double ts[9000];
    double t_imp[2] = {0}, t_up[2] = {0}, th_max[2] = {0};
    for (int k = 0; k < 2; k++) {
        const double off = k ? 0.37e-3 : 0.0;
        int n = 0;
        ts[n++] = 0.0;
        ts[n++] = 0.2;
        ts[n++] = 0.4;
        for (int j = 1; j * 1e-3 + off <= 8.0; j++) ts[n++] = j * 1e-3 + off;
        qsort(ts, (size_t)n, sizeof ts[0], cmp_double);
        tu_events_t rec = {0};
        sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, &rec);
        for (int i = 0; i < n; i++)
            if (i == 0 || ts[i] - ts[i - 1] > 1e-9)
                sw_engine_push(e, ts[i], braking(ts[i], thr), 0.0);
        t_up[k] = tu_first(&rec, SW_EV_UPLIFT)->t;
        t_imp[k] = tu_first(&rec, SW_EV_IMPACT)->t;
        sw_summary_t s;
        sw_engine_summary(e, 0, &s);
        th_max[k] = s.max_abs_theta;
        assert_true(s.impacts > 2);
        sw_engine_destroy(e);
    }
    /* uplift: -1.5 thr t / 0.2 = -thr at t = 0.2 / 1.5 exactly */
    tu_near(t_up[0], 0.2 / 1.5, 1e-12);
    tu_near(t_up[1], 0.2 / 1.5, 1e-12);
    tu_near(t_imp[0], t_imp[1], 1e-8);
    tu_near(th_max[0], th_max[1], 1e-9);
}

/* Overturn at |theta| = pi/2: bare block with a long strong braking. */
static void test_overturn_and_tip(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    const double alpha = alpha_of(2.0, 0.728);
    const double thr = G * tan(alpha);
    tu_events_t rec = {0};
    sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, &rec);
    for (int i = 0; i <= 5000; i++) sw_engine_push(e, i * 1e-3, -2.0 * thr, 0.0);
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_true(s.overturned);
    assert_true(s.tip_time < s.overturn_time);
    tu_near(s.max_abs_theta, M_PI_2, 1e-12);
    const sw_event_t *tip = tu_first(&rec, SW_EV_TIP);
    assert_non_null(tip);
    /* at the tip the interpolated theta is alpha to the step's accuracy */
    tu_near(tip->theta, alpha, 1e-6);
    sw_output_t o;
    sw_engine_get_output(e, 0, &o);
    assert_int_equal(o.state.phase, SW_PHASE_OVERTURNED);
    assert_true(o.margin < 0.0);
    sw_engine_destroy(e);
}

/* Bad samples are refused without touching the state. */
static void test_bad_samples(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, NULL);
    assert_int_equal(sw_engine_push(e, 0.0, 0.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_push(e, 0.001, NAN, 0.0), SW_ENONFINITE);
    assert_int_equal(sw_engine_push(e, 0.0, 1.0, 0.0), SW_EORDER);
    assert_int_equal(sw_engine_push(e, -1.0, 1.0, 0.0), SW_EORDER);
    tu_near(sw_engine_time(e), 0.0, 0.0);
    assert_int_equal(sw_engine_push(e, 0.001, 0.0, 0.0), SW_OK);
    sw_engine_destroy(e);
    sw_engine_destroy(NULL);
}

/* A vertical acceleration a_z changes gravity to g + a_z in every gravity
 * term: with the bed dropping at 0.5 g the uplift threshold halves; below
 * -g the package leaves the bed level, in free flight (test_flight.c): no
 * fault, no uplift to a side. */
static void test_vertical_acceleration(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    const double thr = G * tan(alpha_of(2.0, 0.728));
    for (int k = 0; k < 3; k++) {
        const double az = k == 0 ? 0.0 : (k == 1 ? -0.5 * G : -1.2 * G);
        tu_events_t rec = {0};
        sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, &rec);
        for (int i = 0; i <= 100; i++) sw_engine_push(e, i * 1e-3, -0.6 * thr, az);
        sw_summary_t s;
        sw_engine_summary(e, 0, &s);
        if (k == 0)
            assert_int_equal(s.uplifts, 0); /* 0.6 of the threshold */
        if (k == 1)
            assert_int_equal(s.uplifts, 1); /* 1.2 of the halved threshold */
        if (k == 2) {
            assert_int_equal(s.faults, 0);
            assert_int_equal(s.flights, 1);
            const sw_event_t *f = tu_first(&rec, SW_EV_UPLIFT);
            assert_non_null(f);
            assert_true(f->info == 0.0 && f->t == 0.0); /* level, at once */
            assert_true(isfinite(f->theta) && isfinite(f->margin));
        }
        sw_engine_destroy(e);
    }
}

/* margins_off (sw_engine_opts_t): the same motion, events, peak and
 * outcome as a run with its margins, no per-sample margins (the summary's
 * minimum sees the events only), and the margins computed on demand the
 * same.  On the
 * bare block and on a cushion, rocking under a half-sine that lifts
 * them, one that does not overturn them and one that does. */
static void test_margins_off(void **state)
{
    (void)state;
    const sw_scene_t bare = tu_bare(2.0, 0.728);
    const sw_scene_t cush = tu_cushion(tu_bare(2.0, 0.728), 30.0, 0.1);
    const sw_scene_t *scenes[] = {&bare, &cush};
    const double amps[] = {-0.5 * 9.81, -1.2 * 9.81}; /* m/s^2 */
    for (int k = 0; k < 2; k++)
        for (int a = 0; a < 2; a++) {
            sw_pulse_t p = {SW_PULSE_HALF_SINE, amps[a], 2.0 * M_PI};
            sw_summary_t s[2];
            sw_output_t o[2];
            tu_events_t rec[2];
            for (int off = 0; off < 2; off++) {
                memset(&rec[off], 0, sizeof rec[off]);
                sw_engine_opts_t eo = {0};
                eo.on_event = tu_on_event;
                eo.user = &rec[off];
                eo.margins_off = off;
                int err;
                sw_engine_t *e = sw_engine_create(scenes[k], 1, &eo, &err, NULL, 0);
                assert_non_null(e);
                for (int i = 1; i <= 3000; i++) { /* 1 kHz, 3 s */
                    const double t = 1e-3 * i;
                    assert_true(sw_engine_push(e, t, sw_pulse_eval(&p, t), 0.0) >= 0);
                }
                sw_engine_summary(e, 0, &s[off]);
                sw_engine_get_output(e, 0, &o[off]);
                sw_engine_destroy(e);
            }
            assert_true(s[0].uplifts > 0);
            assert_int_equal(s[0].overturned, s[1].overturned);
            assert_memory_equal(&s[0].max_abs_theta, &s[1].max_abs_theta, sizeof(double));
            assert_int_equal(rec[0].n, rec[1].n);
            for (int i = 0; i < rec[0].n; i++) {
                assert_int_equal(rec[0].ev[i].kind, rec[1].ev[i].kind);
                assert_memory_equal(&rec[0].ev[i].t, &rec[1].ev[i].t, sizeof(double));
            }
            assert_memory_equal(&o[0].state, &o[1].state, sizeof o[0].state);
            assert_memory_equal(&o[0].margin, &o[1].margin, sizeof(double));
            /* the margins of the events alone: a minimum over fewer */
            assert_true(s[0].min_margin < 1.0);
            assert_true(s[1].min_margin >= s[0].min_margin);
            assert_true(s[1].max_uplift_ratio <= s[0].max_uplift_ratio);
        }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_uplift_threshold),      cmocka_unit_test(test_uplift_between_samples),
        cmocka_unit_test(test_free_rocking),          cmocka_unit_test(test_grid_independence),
        cmocka_unit_test(test_overturn_and_tip),      cmocka_unit_test(test_bad_samples),
        cmocka_unit_test(test_vertical_acceleration), cmocka_unit_test(test_margins_off),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
