/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_uplift_sampled.c - a bare package lifted by sampled input (linear
 * between samples) starts to rock exactly once per uplift.  Regression: on
 * the threshold crossing theta'' is 0 up to round-off, and the engine used
 * to find an impact at the very start of the first rocking step, rest, and
 * uplift again at the same instant without end. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <string.h>

/* cmocka.h needs these before it. */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
// clang-format on

#include "swaywatch/swaywatch.h"

static long n_events;

static void count(void *user, const sw_event_t *ev)
{
    (void)user;
    (void)ev;
    /* Far more than any of these pulses can cause: fail instead of hanging. */
    if (++n_events > 10000)
        fail_msg("event storm at t = %.17g s", ev->t);
}

static void test_sampled_half_sine(void **st)
{
    (void)st;
    sw_scene_t sc;
    sw_scene_init(&sc);
    assert_int_equal(sw_scene_parse(&sc,
                                    "[package]\nname = tall\nheight = 2.0\nwidth = 0.728\n"
                                    "mass = 1000\n",
                                    "test", NULL, NULL),
                     SW_OK);
    assert_int_equal(sw_scene_validate(&sc, NULL, "test", NULL, NULL), SW_OK);
    const double amps[] = {-4.0, -6.0, -9.0, 6.0, -14.0}; /* m/s^2; uplift at 3.57 */
    const double rates[] = {1000.0, 200.0};               /* Hz */
    for (size_t i = 0; i < sizeof amps / sizeof amps[0]; i++)
        for (size_t j = 0; j < sizeof rates / sizeof rates[0]; j++) {
            sw_engine_opts_t eo;
            memset(&eo, 0, sizeof eo);
            eo.on_event = count;
            n_events = 0;
            sw_engine_t *e = sw_engine_create(&sc, 1, &eo, NULL, NULL, 0);
            assert_non_null(e);
            for (long k = 0; k <= (long)(2.0 * rates[j]); k++) {
                const double t = (double)k / rates[j], tp = t - 0.2;
                const double a = (tp >= 0.0 && tp <= M_PI / 10.0) ? amps[i] * sin(10.0 * tp) : 0.0;
                assert_true(sw_engine_push(e, t, a, 0.0) >= 0);
            }
            sw_summary_t s;
            assert_int_equal(sw_engine_summary(e, 0, &s), SW_OK);
            assert_int_equal(s.uplifts, 1);
            assert_true(s.max_abs_theta > 0.0);
            assert_true(s.impacts < 200);
            sw_engine_destroy(e);
        }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_sampled_half_sine)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
