/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_convergence.c - halving dt divides the error by about 2^order for
 * every fixed-step scheme, in runs with several impacts (what event
 * location buys: without it the impact times are quantised to the grid and
 * every scheme is first order).  Reference: GSL rk8pd at rtol 1e-12. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define G 9.81

typedef struct {
    double theta_max; /* rad */
    double theta_T;   /* rad, theta at the end time */
    double t_imp3;    /* s, time of the third impact */
    long impacts;
} run_t;

static run_t run(const sw_scene_t *sc, const char *scheme, double dt, const sw_pulse_t *pulse,
                 double T)
{
    run_t r = {0};
    sw_engine_opts_t o = {0};
    tu_events_t *rec = calloc(1, sizeof *rec);
    o.scheme = scheme;
    o.dt = dt;
    o.rtol = 1e-12;
    o.atol = 1e-14;
    o.on_event = tu_on_event;
    o.user = rec;
    sw_engine_t *e = sw_engine_create(sc, 1, &o, NULL, NULL, 0);
    assert_non_null(e);
    sw_pulse_t p = *pulse;
    sw_engine_advance_fn(e, sw_pulse_duration(&p), sw_pulse_eval, &p);
    sw_engine_advance_fn(e, T, sw_pulse_eval, &p);
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    sw_output_t out;
    sw_engine_get_output(e, 0, &out);
    r.theta_max = s.max_abs_theta;
    r.theta_T = out.state.theta;
    r.impacts = s.impacts;
    int k = 0;
    for (int i = 0; i < rec->n; i++)
        if (rec->ev[i].kind == SW_EV_IMPACT && ++k == 3)
            r.t_imp3 = rec->ev[i].t;
    sw_engine_destroy(e);
    free(rec);
    return r;
}

static void check_order(const sw_scene_t *sc, const sw_pulse_t *pulse, double T)
{
    const run_t ref = run(sc, "rk8pd", 1e-3, pulse, T);
    assert_true(ref.impacts >= 3);
    const struct {
        const char *scheme;
        int order;
        double dt;
    } cases[] = {{"rk4", 4, 4e-3}, {"heun", 2, 1e-3}, {"euler", 1, 1e-4}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double emax[3], eT[3], eimp[3];
        for (int j = 0; j < 3; j++) {
            const run_t r = run(sc, cases[k].scheme, cases[k].dt / (1 << j), pulse, T);
            assert_int_equal(r.impacts >= 3, 1);
            emax[j] = fabs(r.theta_max - ref.theta_max);
            eT[j] = fabs(r.theta_T - ref.theta_T);
            eimp[j] = fabs(r.t_imp3 - ref.t_imp3);
        }
        const double q_max = log2(emax[1] / emax[2]), q_T = log2(eT[1] / eT[2]),
                     q_imp = log2(eimp[1] / eimp[2]);
        print_message(
            "%-5s errors theta_max %.2e %.2e %.2e (order %.2f), theta(T) %.2e %.2e "
            "%.2e (order %.2f), 3rd impact %.2e (order %.2f)\n",
            cases[k].scheme, emax[0], emax[1], emax[2], q_max, eT[0], eT[1], eT[2], q_T, eimp[2],
            q_imp);
        const double q = cases[k].order;
        assert_true(q_max > q - 0.4 && q_max < q + 0.6);
        assert_true(q_T > q - 0.4 && q_T < q + 0.6);
        assert_true(q_imp > q - 0.4 && q_imp < q + 0.6);
    }
}

/* Bare block: a half-sine braking pulse at w_e = 2p of 1.5 g tan(alpha)
 * rocks it with a cascade of impacts; theta at 2.5 s lies after several. */
static void test_bare_order(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const double R = sqrt(1.0 + 0.364 * 0.364), p = sqrt(3.0 * G / (4.0 * R));
    const sw_pulse_t pulse = {SW_PULSE_HALF_SINE, -1.5 * G * 0.364, 2.0 * p};
    check_order(&sc, &pulse, 2.5);
}

/* Frame (gamma = 0.8, w_b = 5 rad/s, zeta_b = 0.1): a full-sine braking
 * pulse of 0.8 g tan(alpha) at 6 rad/s rocks it through a long cascade. */
static void test_frame_order(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, 5.0, 0.1);
    const sw_pulse_t pulse = {SW_PULSE_FULL_SINE, -0.8 * G * 0.364, 6.0};
    check_order(&sc, &pulse, 2.2);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bare_order),
        cmocka_unit_test(test_frame_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
