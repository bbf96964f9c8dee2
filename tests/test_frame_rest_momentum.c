/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_frame_rest_momentum.c - momentum at a frame's rest transition.
 *
 * physics.md, scene 2: the rest transition is an impact whose theta_dot+
 * is 0, so the frame still takes the package's last rocking momentum:
 * u'+ = u'- + gamma h (theta'- - theta'+) with theta'+ = 0 (an engine
 * whose rest branch skipped the frame's jump failed it).  The ordinary
 * impact is checked the same way: it shows that the measurement works.
 *
 * Measurement: a package a hair before its corner lands (theta = -1e-12
 * rad, moving in), run for 1 us: the impact happens at once, and the
 * continuous motion in that microsecond changes u' by less than 1e-5 m/s
 * (the bearing is at rest, the frame's acceleration is a few m/s^2). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

static const double A20 = 20.0 * M_PI / 180.0; /* rad */

typedef struct {
    int rests, impacts;
} count_t;

static void on_event(void *user, const sw_event_t *ev)
{
    count_t *c = user;
    c->rests += ev->kind == SW_EV_REST;
    c->impacts += ev->kind == SW_EV_IMPACT;
}

/* u' (m/s) right after the landing of a package coming in at theta_dot
 * (rad/s) with u' = 0, with rest threshold rest_eps. */
static double u_dot_after(double theta_dot, double rest_eps, count_t *c)
{
    const sw_scene_t sc = tu_frame(2.0, 2.0 * tan(A20), 250.0, 5.59, 0.1);
    sw_engine_opts_t o;
    memset(&o, 0, sizeof o);
    o.scheme = "rk8pd";
    o.rest_eps = rest_eps;
    o.on_event = on_event;
    o.user = c;
    int err;
    sw_engine_t *e = sw_engine_create(&sc, 1, &o, &err, NULL, 0);
    assert_non_null(e);
    sw_state_t s;
    memset(&s, 0, sizeof s);
    s.phase = SW_PHASE_ROCKING;
    s.side = -1;
    s.theta = -1e-12;
    s.theta_dot = theta_dot;
    assert_int_equal(sw_engine_set_state(e, 0, &s), SW_OK);
    sw_engine_advance_fn(e, 1e-6, sw_pulse_eval, &(sw_pulse_t){SW_PULSE_HALF_SINE, 0.0, 1.0});
    sw_output_t out;
    sw_engine_get_output(e, 0, &out);
    sw_engine_destroy(e);
    return out.state.u_dot;
}

/* theta'+ of the frame's impact map, physics.md: gamma = 0.8. */
static double r_frame(void)
{
    const double g = 1000.0 / 1250.0, s = sin(A20), c = cos(A20);
    return 1.0 - 6.0 * s * s / (4.0 - 3.0 * g * c * c);
}

/* A landing that goes on rocking: u'+ = gamma h (theta'- - theta'+). */
static void test_impact_momentum(void **state)
{
    (void)state;
    count_t c = {0, 0};
    const double thd = 0.5; /* rad/s */
    const double got = u_dot_after(thd, 0.0, &c);
    assert_int_equal(c.impacts, 1);
    assert_int_equal(c.rests, 0);
    const double want = 0.8 * 1.0 * (thd - r_frame() * thd); /* m/s, h = 1 m */
    if (!(fabs(got - want) < 1e-5))
        fail_msg("u'+ = %.8f m/s, expected %.8f", got, want);
}

/* A landing that ends the sway (a high rest threshold makes this one the
 * last): theta'+ = 0, u'+ = gamma h theta'-. */
static void test_rest_momentum(void **state)
{
    (void)state;
    count_t c = {0, 0};
    const double thd = 0.05; /* rad/s: after the impact 1e-3 of the barrier */
    const double got = u_dot_after(thd, 0.5, &c);
    assert_int_equal(c.rests, 1);
    const double want = 0.8 * 1.0 * thd; /* m/s */
    if (!(fabs(got - want) < 1e-5))
        fail_msg("u'+ = %.8f m/s after the rest transition, expected %.8f", got, want);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_impact_momentum),
        cmocka_unit_test(test_rest_momentum),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
