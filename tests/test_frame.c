/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_frame.c - the package on a support frame (scene 2): the stuck frame
 * against the closed-form step response of a damped oscillator, uplift
 * located on it, the corrected impact ratio, energy conservation between
 * impacts, and the stiff-bearing/heavy-frame limit that is scene 1. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define G 9.81

/* Step load a (m/s^2) from rest: u'' + 2 z w u' + w^2 u = -a gives
 *   u  = U (1 - e^{-z w t} (cos wd t + z w / wd sin wd t)),  U = -a / w^2
 *   u' = U e^{-z w t} (w^2 / wd) sin wd t
 * and the support's absolute acceleration A = -(2 z w u' + w^2 u). */
static double step_A(double a, double w, double z, double t)
{
    const double wd = w * sqrt(1.0 - z * z), U = -a / (w * w), ex = exp(-z * w * t);
    const double u = U * (1.0 - ex * (cos(wd * t) + z * w / wd * sin(wd * t)));
    const double ud = U * ex * (w * w / wd) * sin(wd * t);
    return -(2.0 * z * w * ud + w * w * u);
}

/* A constant braking of 0.6 g tan(alpha) never lifts a bare block, but the
 * frame overshoots to about 1.85 times it: uplift when A = -g tan(alpha),
 * found here by bisection on the closed form. */
static void test_stuck_frame_uplift(void **state)
{
    (void)state;
    const double w = 6.0, z = 0.05;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, w, z);
    const double thr = G * 0.364;
    const double a = -0.6 * thr;
    double lo = 0.0, hi = M_PI / (w * sqrt(1.0 - z * z)); /* A peaks at half a period */
    assert_true(step_A(a, w, z, hi) < -thr);
    for (int i = 0; i < 200; i++) {
        const double m = 0.5 * (lo + hi);
        if (step_A(a, w, z, m) <= -thr)
            hi = m;
        else
            lo = m;
    }
    const char *schemes[] = {"rk4", "rk8pd"};
    const double tol[] = {1e-8, 1e-10};
    for (int k = 0; k < 2; k++) {
        tu_events_t rec = {0};
        sw_engine_t *e = tu_engine(&sc, schemes[k], 1e-3, &rec);
        for (int i = 0; i <= 1000; i++) sw_engine_push(e, i * 1e-3, a, 0.0);
        const sw_event_t *up = tu_first(&rec, SW_EV_UPLIFT);
        assert_non_null(up);
        tu_near(up->t, hi, tol[k]);
        assert_int_equal((int)up->info, 1); /* braking: the top tips forward */
        sw_engine_destroy(e);
    }
}

/* Every impact multiplies theta' by r = 1 - 6 sin^2 a / (4 - 3 gamma cos^2 a)
 * (physics.md, corrected eq. 10); alpha = 20 deg, gamma = 0.8 gives 0.627. */
static void test_impact_ratio(void **state)
{
    (void)state;
    const double alpha = 20.0 * M_PI / 180.0;
    const double height = 2.0, width = height * tan(alpha);
    const sw_scene_t sc = tu_frame(height, width, 250.0, 5.0, 0.1); /* gamma = 0.8 */
    const double r = 1.0 - 6.0 * pow(sin(alpha), 2) / (4.0 - 3.0 * 0.8 * pow(cos(alpha), 2));
    tu_near(r, 0.627, 5e-4);
    tu_events_t rec = {0};
    sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, &rec);
    sw_engine_push(e, 0.0, 0.0, 0.0);
    sw_state_t st = {0};
    st.theta = 0.6 * alpha;
    st.phase = SW_PHASE_ROCKING;
    st.side = 1;
    sw_engine_set_state(e, 0, &st);
    for (int i = 1; i <= 5000; i++) sw_engine_push(e, i * 1e-3, 0.0, 0.0);
    int n = 0;
    for (int i = 0; i < rec.n; i++)
        if (rec.ev[i].kind == SW_EV_IMPACT && rec.ev[i].theta_dot != 0.0) {
            tu_near(rec.ev[i].theta_dot / rec.ev[i].info, r, 1e-12);
            n++;
        }
    assert_true(n >= 3);
    sw_engine_destroy(e);
}

/* With c_b = 0 and no input, total energy (package + frame + bearing) is
 * conserved between impacts; a scheme of order q loses it as dt^q. */
static double energy_drift(const char *scheme, double dt)
{
    const double alpha = atan(0.364);
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, 4.0, 0.0);
    tu_events_t rec = {0};
    sw_engine_t *e = tu_engine(&sc, scheme, dt, &rec);
    sw_engine_push(e, 0.0, 0.0, 0.0);
    sw_state_t st = {0};
    st.theta = 0.7 * alpha;
    st.theta_dot = 0.05;
    st.u = 0.02;
    st.phase = SW_PHASE_ROCKING;
    st.side = 1;
    sw_engine_set_state(e, 0, &st);
    const sw_derived_t *d = sw_engine_derived(e, 0);
    const double E0 = sw_energy_frame(d, G, &st);
    const double Eb = G * d->R * (1.0 - cos(d->alpha));
    double worst = 0.0;
    /* sample at 8 ms (a multiple of every dt used) until the first impact */
    for (int i = 1; i <= 2000; i++) {
        sw_engine_push(e, i * 8e-3, 0.0, 0.0);
        if (tu_count(&rec, SW_EV_IMPACT) > 0)
            break;
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        worst = fmax(worst, fabs(sw_energy_frame(d, G, &o.state) - E0) / Eb);
    }
    assert_true(tu_count(&rec, SW_EV_IMPACT) > 0); /* the window ended at an impact */
    sw_engine_destroy(e);
    return worst;
}

static void test_energy_conservation(void **state)
{
    (void)state;
    const struct {
        const char *scheme;
        double dt, lo, hi, abs_max;
    } cases[] = {
        /* (Euler is refused on these undamped bearings: no step is inside
         * its stability region, test_stability.c) */
        {"rk4", 2e-3, 12.0, 20.0, 1e-9},
        {"heun", 1e-3, 3.0, 9.0, 1e-4},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const double e1 = energy_drift(cases[k].scheme, cases[k].dt);
        const double e2 = energy_drift(cases[k].scheme, cases[k].dt / 2);
        print_message("%s: drift %.3g -> %.3g, ratio %.2f\n", cases[k].scheme, e1, e2, e1 / e2);
        assert_true(e1 < cases[k].abs_max);
        assert_true(e1 / e2 > cases[k].lo && e1 / e2 < cases[k].hi);
    }
    /* the adaptive reference conserves it to its tolerance */
    assert_true(energy_drift("rk8pd", 1e-3) < 1e-9);
}

/* Heavy frame on very stiff bearings: the frame follows the bed and the
 * package rocks as the bare block does (physics.md: k_b -> inf, gamma -> 0
 * is scene 1). */
static void test_stiff_limit_is_bare(void **state)
{
    (void)state;
    const sw_scene_t bare = tu_bare(2.0, 0.728);
    const sw_scene_t fr = tu_frame(2.0, 0.728, 1e7, 3000.0, 0.7);
    const double R = sqrt(1.0 + 0.364 * 0.364), p = sqrt(3.0 * G / (4.0 * R));
    sw_pulse_t pulse = {SW_PULSE_HALF_SINE, -1.5 * G * 0.364, 2.0 * p};
    sw_engine_t *eb = tu_engine(&bare, "rk4", 1e-3, NULL);
    sw_engine_t *ef = tu_engine(&fr, "rk4", 1e-3, NULL);
    const double T = sw_pulse_duration(&pulse);
    double worst = 0.0, peak = 0.0;
    for (int i = 1; i <= 600; i++) {
        const double t = fmin(T, i * 5e-3);
        sw_engine_advance_fn(eb, t, sw_pulse_eval, &pulse);
        sw_engine_advance_fn(ef, t, sw_pulse_eval, &pulse);
        if (t == T && i * 5e-3 > T) {
            sw_engine_advance_fn(eb, i * 5e-3, sw_pulse_eval, &pulse);
            sw_engine_advance_fn(ef, i * 5e-3, sw_pulse_eval, &pulse);
        }
        sw_output_t ob, of;
        sw_engine_get_output(eb, 0, &ob);
        sw_engine_get_output(ef, 0, &of);
        worst = fmax(worst, fabs(ob.state.theta - of.state.theta));
        peak = fmax(peak, fabs(ob.state.theta));
    }
    sw_summary_t sb, sf;
    sw_engine_summary(eb, 0, &sb);
    sw_engine_summary(ef, 0, &sf);
    print_message("peak %.4g rad, worst |dtheta| %.3g rad, impacts %ld / %ld\n", peak, worst,
                  sb.impacts, sf.impacts);
    assert_true(sb.impacts >= 3);
    /* the frame follows the bed to O(2 zeta_b da/dt / omega_b), about 0.3 % of a_g here */
    assert_true(worst < 2e-3 * peak);
    tu_near(sb.max_abs_theta, sf.max_abs_theta, 0.005 * sb.max_abs_theta);
    sw_engine_destroy(eb);
    sw_engine_destroy(ef);
}

/* A forced dt above the stability bound is refused with the numbers. */
static void test_forced_dt_refused(void **state)
{
    (void)state;
    const sw_scene_t fr = tu_frame(2.0, 0.728, 250.0, 3000.0, 0.1);
    sw_engine_opts_t o = {0};
    o.scheme = "rk4";
    o.dt = 1e-3;
    o.dt_forced = 1;
    int err = 0;
    char msg[512];
    sw_engine_t *e = sw_engine_create(&fr, 1, &o, &err, msg, sizeof msg);
    assert_null(e);
    assert_int_equal(err, SW_EUNSTABLE);
    assert_non_null(strstr(msg, "stability bound"));
    o.dt = 1e-4;
    e = sw_engine_create(&fr, 1, &o, &err, msg, sizeof msg);
    assert_non_null(e);
    sw_engine_destroy(e);
}

static double zero(void *user, double t)
{
    (void)user;
    (void)t;
    return 0.0;
}

/* The rest transition is an impact whose theta'^+ is 0 (physics.md): the
 * frame takes the package's last momentum, u'^+ = u'^- + gamma h theta'^-.
 * A package landing at theta = 0 with too little energy to rebound comes
 * to rest, and the frame then swings freely from u = 0 at that velocity: a
 * damped oscillator whose velocity after 1 ms is known in closed form. */
static void test_rest_takes_momentum(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    tu_events_t rec;
    memset(&rec, 0, sizeof rec);
    sw_engine_t *e = tu_engine(&sc, NULL, 0.0, &rec);
    assert_non_null(e);
    const sw_derived_t *d = sw_engine_derived(e, 0);
    const double w0 = -1e-6; /* rad/s: landing, below the rest energy */
    const sw_state_t s0 = {.theta = 0.0, .theta_dot = w0, .phase = SW_PHASE_ROCKING, .side = 1};
    assert_int_equal(sw_engine_set_state(e, 0, &s0), SW_OK);
    assert_true(sw_engine_advance_fn(e, 1e-3, zero, NULL) >= 0);
    assert_non_null(tu_first(&rec, SW_EV_REST));
    sw_output_t o;
    assert_int_equal(sw_engine_get_output(e, 0, &o), SW_OK);
    assert_int_equal(o.state.phase, SW_PHASE_STUCK);
    const double v0 = d->gamma * d->h * w0; /* m/s, the frame's share */
    const double w = d->omega_b, z = d->zeta_b, wd = w * sqrt(1.0 - z * z), t = 1e-3;
    const double v = v0 * exp(-z * w * t) * (cos(wd * t) - z * w / wd * sin(wd * t));
    tu_near(o.state.u_dot, v, 1e-9 * fabs(v));
    sw_engine_destroy(e);
}

/* sw_model_settled on a frame is the closed form of the undamped
 * oscillator: standing still at u, the support's acceleration peaks at
 * w^2 |u|.  Just below g tan(alpha)/w^2 the package stays put for good;
 * just above it lifts, and the test says so. */
static void test_settled_frame(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, 5.0, 0.0);
    for (int k = 0; k < 2; k++) {
        const double f = k == 0 ? 0.99 : 1.01;
        tu_events_t rec = {0};
        sw_engine_t *e = tu_engine(&sc, "rk4", 1e-3, &rec);
        assert_non_null(e);
        const sw_derived_t *d = sw_engine_derived(e, 0);
        const double w = d->omega_b, u0 = f * sc.g * tan(d->alpha) / (w * w); /* m */
        const sw_state_t s0 = {.phase = SW_PHASE_STUCK, .u = u0};
        assert_int_equal(sw_model_settled(d, sc.g, &s0), k == 0);
        assert_int_equal(sw_engine_set_state(e, 0, &s0), SW_OK);
        assert_true(sw_engine_advance_fn(e, 5.0 * 2.0 * M_PI / w, zero, NULL) >= 0);
        assert_int_equal(tu_count(&rec, SW_EV_UPLIFT) > 0, k == 1);
        sw_engine_destroy(e);
    }
    /* overturned is final; rocking is not settled; the bed holds still */
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(&sc, &d, NULL, NULL, NULL), SW_OK);
    const sw_state_t over = {.phase = SW_PHASE_OVERTURNED}, rock = {.phase = SW_PHASE_ROCKING};
    assert_true(sw_model_settled(&d, sc.g, &over));
    assert_false(sw_model_settled(&d, sc.g, &rock));
    const sw_scene_t bare = tu_bare(2.0, 0.728);
    assert_int_equal(sw_scene_validate(&bare, &d, NULL, NULL, NULL), SW_OK);
    const sw_state_t still = {.phase = SW_PHASE_STUCK};
    assert_true(sw_model_settled(&d, bare.g, &still));
    /* a cushion cannot prove it (its phase is always rocking) */
    const sw_scene_t cu = tu_cushion(tu_bare(2.0, 0.728), 40.0, 0.1);
    assert_int_equal(sw_scene_validate(&cu, &d, NULL, NULL, NULL), SW_OK);
    assert_false(sw_model_settled(&d, cu.g, &rock));
}

/* margin_bound (physics.md) is 1 - E_tot / (m g R (1 - cos alpha)): here
 * E_tot is written from the motion of the package and the frame, not from
 * the model's energy: the frame's and the package's shared translation
 * (m + m_b) u'^2 / 2, the bearings' strain k_b u^2 / 2, the centre of mass
 * raised to R cos(alpha - |theta|) over the corner, and the rotation about
 * the corner (I_O = 4/3 m R^2), whose horizontal velocity theta' h at
 * theta = 0 the frame's velocity adds to. */
static void test_margin_bound_frame(void **state)
{
    (void)state;
    const double m = 1000.0, mb = 250.0; /* kg */
    const sw_scene_t sc = tu_frame(2.0, 0.728, mb, 5.0, 0.1);
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(&sc, &d, NULL, NULL, NULL), SW_OK);
    const double R = d.R, h = d.h, alpha = d.alpha;
    const double kb = 25.0 * (m + mb); /* N/m: omega_b^2 (m + m_b) */
    const double Eb = m * G * (R - h); /* J: the centre of mass over the corner */
    sw_state_t s = {0};
    s.phase = SW_PHASE_ROCKING;
    s.side = 1;
    tu_near(sw_margin_bound_frame(&d, G, &s), 1.0, 1e-15); /* at rest */

    s.u_dot = 0.3; /* m/s: the frame and the package slide together */
    tu_near(sw_margin_bound_frame(&d, G, &s), 1.0 - 0.5 * (m + mb) * 0.09 / Eb, 1e-12);

    s.u_dot = 0.0;
    s.u = 0.01; /* m: the bearings strained */
    tu_near(sw_margin_bound_frame(&d, G, &s), 1.0 - 0.5 * kb * 1e-4 / Eb, 1e-12);

    s.u = 0.0;
    s.theta = 0.5 * alpha; /* tilted, at rest: only the centre of mass raised */
    tu_near(sw_margin_bound_frame(&d, G, &s), 1.0 - m * G * (R * cos(0.5 * alpha) - h) / Eb, 1e-12);

    s.theta = 0.0;
    s.theta_dot = 0.2; /* rad/s, about the front corner, the frame moving forward */
    s.u_dot = 0.1;
    const double E =
        0.5 * (m + mb) * 0.01 + 0.5 * (4.0 / 3.0) * m * R * R * 0.04 + m * 0.1 * 0.2 * h; /* J */
    tu_near(sw_margin_bound_frame(&d, G, &s), 1.0 - E / Eb, 1e-12);

    /* beyond alpha it guarantees nothing: never above 0, even at rest */
    s = (sw_state_t){.theta = alpha + 0.01, .phase = SW_PHASE_ROCKING, .side = 1};
    assert_true(sw_margin_bound_frame(&d, G, &s) <= 0.0);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stuck_frame_uplift),  cmocka_unit_test(test_impact_ratio),
        cmocka_unit_test(test_energy_conservation), cmocka_unit_test(test_stiff_limit_is_bare),
        cmocka_unit_test(test_forced_dt_refused),   cmocka_unit_test(test_rest_takes_momentum),
        cmocka_unit_test(test_settled_frame),       cmocka_unit_test(test_margin_bound_frame),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
