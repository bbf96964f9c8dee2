/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_time.c - the engine's clock: it runs on time relative to its first
 * sample, so a drive stamped with epoch times gives the answer of the same
 * drive stamped from zero; a time too large for its own resolution is
 * refused, never integrated (a microsecond clock read as seconds once made
 * the loops spin forever); a restart puts the packages back at rest
 * without bridging; every loop that must make progress does. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

/* A braking half-sine of -6 m/s^2 at 8 rad/s sampled at 1 kHz from t0. */
static double pulse(int i)
{
    const double t = i * 1e-3, w = 8.0;
    return t < M_PI / w ? -6.0 * sin(w * t) : 0.0;
}

static sw_summary_t drive(const sw_scene_t *sc, double t0, int n, int *rc_bad)
{
    sw_engine_t *e = tu_engine(sc, NULL, 0.0, NULL);
    assert_non_null(e);
    *rc_bad = 0;
    for (int i = 0; i < n; i++)
        if (sw_engine_push(e, t0 + i * 1e-3, pulse(i), 0.0) < 0)
            (*rc_bad)++;
    sw_engine_finish(e, 10.0);
    sw_summary_t s;
    assert_int_equal(sw_engine_summary(e, 0, &s), SW_OK);
    sw_engine_destroy(e);
    return s;
}

/* The same drive at t0 = 0 and at an epoch time: the same motion; the
 * summary's times are the caller's (shifted by t0). */
static void test_epoch_times(void **state)
{
    (void)state;
    const sw_scene_t scenes[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 5.59, 0.1)};
    for (int k = 0; k < 2; k++) {
        int bad0, bad1;
        const sw_summary_t a = drive(&scenes[k], 0.0, 3000, &bad0);
        const double t0 = 1716206400.0; /* 2024-05-20T12:00:00Z */
        const sw_summary_t b = drive(&scenes[k], t0, 3000, &bad1);
        assert_int_equal(bad0, 0);
        assert_int_equal(bad1, 0);
        assert_int_equal(a.uplifts, b.uplifts);
        assert_int_equal(a.impacts, b.impacts);
        assert_true(a.uplifts > 0);
        /* epoch sample times carry 2.4e-7 s of rounding: the motion agrees
         * to far better than a step */
        assert_true(fabs(a.max_abs_theta - b.max_abs_theta) <= 1e-6 * a.max_abs_theta);
        assert_true(fabs((b.uplift_time - t0) - a.uplift_time) < 1e-6);
    }
}

/* 1.7e15 s (microseconds read as seconds) has steps of 0.25 s: refused,
 * as are 1e300 and a jump to it; the engine stays usable. */
static void test_coarse_times_refused(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    sw_engine_t *e = tu_engine(&sc, NULL, 0.0, NULL);
    assert_non_null(e);
    assert_int_equal(sw_engine_push(e, 1700000000000000.0, 0.0, 0.0), SW_ERESOLUTION);
    assert_int_equal(sw_engine_push(e, 1e300, 0.0, 0.0), SW_ERESOLUTION);
    assert_true(isnan(sw_engine_time(e))); /* nothing started */
    assert_int_equal(sw_engine_push(e, 0.0, 0.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_push(e, 1e-3, -1.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_push(e, 1e300, -1.0, 0.0), SW_ERESOLUTION);
    assert_int_equal(sw_engine_push(e, 2e-3, -1.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_advance_fn(e, 1e300, NULL, NULL), SW_EINVAL);
    sw_engine_destroy(e);
}

/* Two absolute times that differ by less than the resolution of the time
 * relative to the first sample (here 1e-300 s after a sample 16.5 ms in)
 * are the same time to the engine: the later is refused as not after the
 * earlier, and the next distinct sample goes on. */
static void test_same_relative_time(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    sw_engine_t *e = tu_engine(&sc, NULL, 0.0, NULL);
    assert_non_null(e);
    assert_int_equal(sw_engine_push(e, -0.0165, 0.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_push(e, 0.0, 0.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_push(e, 1e-300, 0.0, 3.6), SW_EORDER);
    assert_int_equal(sw_engine_push(e, 1e-3, 0.0, 0.0), SW_OK);
    assert_true(fabs(sw_engine_time(e) - 1e-3) < 1e-15);
    sw_engine_destroy(e);
}

/* After a restart the packages stand at rest and the next sample is not
 * bridged from the last: a braking that would have lifted the crate when
 * interpolated over the pause does not. */
static void test_restart(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    tu_events_t rec;
    memset(&rec, 0, sizeof rec);
    sw_engine_t *e = tu_engine(&sc, NULL, 0.0, &rec);
    assert_non_null(e);
    for (int i = 0; i < 300; i++) assert_true(sw_engine_push(e, i * 1e-3, pulse(i), 0.0) >= 0);
    sw_output_t o;
    assert_int_equal(sw_engine_get_output(e, 0, &o), SW_OK);
    assert_int_equal(o.state.phase, SW_PHASE_ROCKING);
    const long uplifts = tu_count(&rec, SW_EV_UPLIFT);
    assert_int_equal(sw_engine_restart(e), SW_OK);
    assert_int_equal(sw_engine_get_output(e, 0, &o), SW_OK);
    assert_int_equal(o.state.phase, SW_PHASE_STUCK);
    assert_true(o.state.theta == 0.0 && o.state.theta_dot == 0.0);
    /* the pause: 5 s later the bed is still; the last sample braked hard */
    assert_true(sw_engine_push(e, 5.3, 0.0, 0.0) >= 0);
    assert_true(sw_engine_push(e, 5.301, 0.0, 0.0) >= 0);
    assert_int_equal(tu_count(&rec, SW_EV_UPLIFT), uplifts);
    sw_summary_t s;
    assert_int_equal(sw_engine_summary(e, 0, &s), SW_OK);
    assert_int_equal(s.uplifts, uplifts); /* kept */
    assert_true(sw_engine_time(e) == 5.301);
    sw_engine_destroy(e);
}

/* Settling ends even when the clock cannot move (no settle time is spun
 * forever), and a stuck frame crosses a long gap in bounded work. */
static void test_progress(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    sw_engine_t *e = tu_engine(&sc, NULL, 0.0, NULL);
    assert_non_null(e);
    assert_int_equal(sw_engine_push(e, 0.0, 0.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_push(e, 1e-3, -1.0, 0.0), SW_OK);
    /* a day without samples, bridged: the exact stuck solution */
    assert_true(sw_engine_push(e, 86400.0, -1.0, 0.0) >= 0);
    sw_summary_t s;
    assert_int_equal(sw_engine_summary(e, 0, &s), SW_OK);
    assert_int_equal(s.faults, 0);
    assert_int_equal(sw_engine_finish(e, 5.0) >= 0, 1);
    sw_engine_destroy(e);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_epoch_times),        cmocka_unit_test(test_coarse_times_refused),
        cmocka_unit_test(test_same_relative_time), cmocka_unit_test(test_restart),
        cmocka_unit_test(test_progress),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
