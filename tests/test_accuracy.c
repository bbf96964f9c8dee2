/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_accuracy.c - the accuracy option: for several tolerances on theta
 * the scheme and step that sw_scheme_for_accuracy() picks do achieve the
 * tolerance against rk8pd at rtol 1e-12 on a test pulse, for both models,
 * sampled and as a function (simulate's input); and tolerances it cannot
 * promise are refused. */
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

/* A pulse given as a function, as simulate drives it: sw_pulse_advance
 * in chunks of the output interval (1 ms, simulate's default, and 0.1 s),
 * then free motion to 20 rocking periods after the pulse; max|theta|.
 * accuracy > 0: the accuracy option; else scheme at rtol (the reference,
 * advanced to the pulse's end and then to the end in one call each). */
static double function_theta_max(const sw_scene_t *sc, double accuracy, const char *scheme,
                                 double rtol, double ratio, double wp, double chunk)
{
    sw_engine_opts_t o = {0};
    o.accuracy = accuracy;
    o.scheme = scheme;
    o.rtol = rtol;
    o.atol = rtol * 1e-2;
    sw_engine_t *e = sw_engine_create(sc, 1, &o, NULL, NULL, 0);
    assert_non_null(e);
    const sw_derived_t *d = sw_engine_derived(e, 0);
    sw_pulse_t pu = {SW_PULSE_HALF_SINE, -ratio * G * tan(d->alpha), wp * d->p};
    const double tp = sw_pulse_duration(&pu), T = tp + 20.0 * 2.0 * M_PI / d->p; /* s */
    if (chunk > 0.0) {
        double t = 0.0;
        for (long k = 1; t < T; k++) {
            t = fmin((double)k * chunk, T);
            assert_true(sw_pulse_advance(e, t, &pu) >= 0);
        }
    } else {
        assert_true(sw_engine_advance_fn(e, tp, sw_pulse_eval, &pu) >= 0);
        assert_true(sw_engine_advance_fn(e, T, sw_pulse_eval, &pu) >= 0);
    }
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_int_equal(s.faults, 0);
    assert_false(s.overturned);
    sw_engine_destroy(e);
    return s.max_abs_theta;
}

/* simulate meets its --accuracy: the setting chosen for a tolerance,
 * driven by a pulse function as simulate drives it, stays within it
 * against rk8pd at rtol 1e-14 (advanced to the pulse's end exactly): the
 * pulse's end is a kink no step may straddle (it cost 1e-7 rad), and an
 * adaptive row's step stays within the 1 ms of its measurement however
 * far apart the rows of the output are (rkf45 in 0.1 s steps: 2.4e-11
 * rad). */
static void test_function_input(void **state)
{
    (void)state;
    const sw_scene_t scenes[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 5.59, 0.1)};
    /* about 0.88 of the boundary (docs/accuracy-speed.md's reference) at
     * omega_e/p = 3, and below it at 6 */
    const double ratio[2][2] = {{2.0, 2.0}, {1.7, 3.1}};
    const double wps[2] = {3.0, 6.0};
    const double tols[] = {1e-10, 1e-11, 1e-12, 1e-13};
    const double chunks[] = {1e-3, 0.1};
    for (int m = 0; m < 2; m++)
        for (int w = 0; w < 2; w++) {
            const double ref =
                function_theta_max(&scenes[m], 0.0, "rk8pd", 1e-14, ratio[m][w], wps[w], 0.0);
            assert_true(ref > 0.01);
            for (size_t k = 0; k < sizeof tols / sizeof tols[0]; k++)
                for (int c = 0; c < 2; c++) {
                    const double th = function_theta_max(&scenes[m], tols[k], NULL, 0.0,
                                                         ratio[m][w], wps[w], chunks[c]);
                    print_message("%s omega_e/p %g tol %.0e, rows of %g s: error %.2e\n",
                                  m ? "frame" : "bare", wps[w], tols[k], chunks[c], fabs(th - ref));
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
        cmocka_unit_test(test_function_input),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
