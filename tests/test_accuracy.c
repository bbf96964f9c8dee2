/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_accuracy.c - the accuracy option: for several tolerances on theta
 * the scheme and step that sw_scheme_for_accuracy() picks do achieve the
 * tolerance against rk8pd at rtol 1e-12 on a test pulse, for both models;
 * and tolerances it cannot promise are refused. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
/* cmocka needs the four above first */
#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define G 9.81

/* A half-sine braking pulse of ratio * g tan(alpha) at omega_e = wp * p,
 * sampled at 1 kHz, 10 s in all; returns max|theta|. */
static double pulse_theta_max(const sw_scene_t *sc, const char *scheme, double dt, double rtol,
                              double ratio, double wp)
{
    sw_engine_opts_t o = {0};
    o.scheme = scheme;
    o.dt = dt;
    o.rtol = rtol;
    o.atol = rtol * 1e-2;
    sw_engine_t *e = sw_engine_create(sc, 1, &o, NULL, NULL, 0);
    assert_non_null(e);
    const sw_derived_t *d = sw_engine_derived(e, 0);
    sw_pulse_t pu = {SW_PULSE_HALF_SINE, -ratio * G * tan(d->alpha), wp * d->p};
    for (int i = 0; i <= 10000; i++) sw_engine_push(e, i * 1e-3, sw_pulse_eval(&pu, i * 1e-3), 0.0);
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_int_equal(s.faults, 0);
    assert_false(s.overturned);
    sw_engine_destroy(e);
    return s.max_abs_theta;
}

static void test_achieves_tolerance(void **state)
{
    (void)state;
    const sw_scene_t scenes[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 5.59, 0.1)};
    const double ratio[2] = {2.0, 1.7}; /* about 0.88 of the boundary at omega_e/p = 3 */
    const double tols[] = {1e-3, 1e-6, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14};
    for (int m = 0; m < 2; m++) {
        const double ref = pulse_theta_max(&scenes[m], "rk8pd", 0.0, 1e-12, ratio[m], 3.0);
        assert_true(ref > 0.3 * atan(0.364));
        for (size_t k = 0; k < sizeof tols / sizeof tols[0]; k++) {
            const char *scheme = NULL;
            double dt = -1.0;
            assert_int_equal(
                sw_scheme_for_accuracy(m ? SW_MODEL_FRAME : SW_MODEL_BARE, tols[k], &scheme, &dt),
                SW_OK);
            assert_non_null(scheme);
            assert_non_null(sw_scheme_lookup(scheme));
            const double th = pulse_theta_max(&scenes[m], scheme, dt, 0.0, ratio[m], 3.0);
            print_message("%s tol %.0e: %s dt %g, error %.2e\n", m ? "frame" : "bare", tols[k],
                          scheme, dt, fabs(th - ref));
            assert_true(fabs(th - ref) <= tols[k]);
        }
    }
}

static void test_refusals(void **state)
{
    (void)state;
    const char *scheme = NULL;
    double dt = 0.0;
    assert_int_equal(sw_scheme_for_accuracy(SW_MODEL_BARE, 1e-18, &scheme, &dt), SW_ENOTFOUND);
    assert_int_equal(sw_scheme_for_accuracy(SW_MODEL_FRAME, 1e-15, &scheme, &dt), SW_ENOTFOUND);
    assert_int_equal(sw_scheme_for_accuracy(SW_MODEL_BARE, 0.0, &scheme, &dt), SW_EINVAL);
    assert_int_equal(sw_scheme_for_accuracy(SW_MODEL_BARE, -1e-3, &scheme, &dt), SW_EINVAL);
    assert_int_equal(sw_scheme_for_accuracy(SW_MODEL_BARE, NAN, &scheme, &dt), SW_EINVAL);
    assert_int_equal(sw_scheme_for_accuracy(SW_MODEL_BARE, 1e-3, NULL, &dt), SW_EINVAL);
    assert_int_equal(sw_scheme_for_accuracy((sw_model_kind)99, 1e-3, &scheme, &dt), SW_EINVAL);
    /* a tolerance looser than any row gets the loosest row, a fixed step
     * no longer than the default (1e-3, checked above, passes through the
     * same row) */
    const char *loose = NULL;
    double loose_dt = 0.0;
    assert_int_equal(sw_scheme_for_accuracy(SW_MODEL_FRAME, 1.0, &loose, &loose_dt), SW_OK);
    assert_int_equal(sw_scheme_for_accuracy(SW_MODEL_FRAME, 1e-3, &scheme, &dt), SW_OK);
    assert_string_equal(loose, scheme);
    assert_true(loose_dt == dt && dt > 0.0 && dt <= SW_DEFAULT_DT);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_achieves_tolerance),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
