/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_mon_replace.c - sw_mon_replace(), the monitor side of a reload, over
 * memq://: two monitors get the same samples, M has its second package
 * replaced half-way, the reference R does not.  The kept package's states
 * are the same in both, sample for sample; the replaced one restarts from
 * rest under its new name and model; M's state messages keep one seq
 * without a gap; a scene that cannot be built changes nothing. */
#include <gsl/gsl_errno.h>
#include <lcm/lcm.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* cmocka needs these first */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "monitor.h"
#include "swaywatch/swaywatch.h"
#include "swaywatch_accel_t.h"
#include "swaywatch_state_t.h"

#define RATE 500       /* Hz */
#define N (3 * RATE)   /* samples */
#define K_REPLACE RATE /* the replacement comes after the sample at t = 1 s */
#define T0 1700000000000000LL

/* Braking half-sines of 10 rad/s: -5 m/s^2 at 0.1 s, -6 m/s^2 at 1.2 s. */
static double accel(long k)
{
    const double t = (double)k / RATE, w = 10.0;
    if (t >= 0.1 && t < 0.1 + M_PI / w)
        return -5.0 * sin(w * (t - 0.1));
    if (t >= 1.2 && t < 1.2 + M_PI / w)
        return -6.0 * sin(w * (t - 1.2));
    return 0.0;
}

typedef struct {
    double theta[2][N + 1];
    int phase[2][N + 1];
    long k; /* sample being fed */
} trace_t;

static void on_state(void *user, const sw_output_t *o)
{
    trace_t *tr = user;
    if (o->pkg < 2 && tr->k <= N) {
        tr->theta[o->pkg][tr->k] = o->state.theta;
        tr->phase[o->pkg][tr->k] = o->state.phase;
    }
}

typedef struct {
    long count, gaps;
    int64_t last_seq;
    char last_name[2][64]; /* by the order of the scenes (first letter A/B) */
    int8_t last_model_b;
} bus_t;

static void on_state_msg(const lcm_recv_buf_t *rb, const char *ch, const swaywatch_state_t *m,
                         void *user)
{
    (void)rb;
    (void)ch;
    bus_t *b = user;
    if (b->count > 0 && m->seq != b->last_seq + 1)
        b->gaps++;
    b->last_seq = m->seq;
    b->count++;
    const int which = strncmp((const char *)m->name, "crate-A", 7) ? 1 : 0;
    memcpy(b->last_name[which], m->name, 64);
    if (which == 1)
        b->last_model_b = m->model;
}

static sw_scene_t crate(const char *name, double width)
{
    sw_scene_t sc;
    sw_scene_init(&sc);
    snprintf(sc.name, sizeof sc.name, "%s", name);
    sc.height = 2.0;
    sc.width = width;
    sc.mass = 1000.0;
    assert_int_equal(sw_scene_validate(&sc, NULL, NULL, NULL, NULL), SW_OK);
    return sc;
}

static void feed(sw_mon_t *m, long k)
{
    unsigned char buf[128];
    swaywatch_accel_t s = {.utime = T0 + k * (1000000 / RATE), .seq = k, .ax = accel(k)};
    int len = swaywatch_accel_t_encode(buf, 0, sizeof buf, &s);
    assert_true(len > 0);
    assert_true(sw_mon_feed(m, buf, (size_t)len, 0, (double)k / RATE, NULL) >= 0);
}

static void test_replace_keeps_the_others(void **state)
{
    (void)state;
    static trace_t tm, tr;
    static bus_t bus;
    memset(&tm, 0, sizeof tm);
    memset(&tr, 0, sizeof tr);
    memset(&bus, 0, sizeof bus);
    const sw_scene_t scenes[2] = {crate("crate-A", 0.728), crate("crate-B", 0.728)};
    sw_scene_t b2 = crate("crate-B2", 0.728);
    b2.has_frame = 1;
    b2.frame_mass = 250.0;
    b2.frame_omega = 5.59;
    b2.frame_zeta = 0.1;
    b2.frame_k_given = b2.frame_c_given = SW_GIVEN_RATIO;
    assert_int_equal(sw_scene_validate(&b2, NULL, NULL, NULL, NULL), SW_OK);
    sw_scene_t bad = crate("crate-B3", 0.728);
    bad.warn_margin = NAN; /* alarm thresholds must be finite */

    lcm_t *lcm = lcm_create("memq://");
    assert_non_null(lcm);
    swaywatch_state_t_subscription_t *sub =
        swaywatch_state_t_subscribe(lcm, "SWAY_STATE", on_state_msg, &bus);
    swaywatch_state_t_subscription_set_queue_capacity(sub, 0);

    sw_engine_opts_t eo = {0};
    char msg[256];
    sw_mon_opts_t mo = {.vertical = -1, .hysteresis = -1.0, .on_state = on_state, .user = &tm};
    sw_mon_t *M = sw_mon_create(scenes, 2, &eo, &mo, lcm, msg, sizeof msg);
    mo.user = &tr;
    sw_mon_t *R = sw_mon_create(scenes, 2, &eo, &mo, NULL, msg, sizeof msg);
    assert_non_null(M);
    assert_non_null(R);

    for (long k = 0; k <= N; k++) {
        tm.k = tr.k = k;
        feed(M, k);
        feed(R, k);
        while (lcm_handle_timeout(lcm, 0) > 0) {
        }
        if (k == K_REPLACE) {
            assert_int_equal(tm.phase[0][k], SW_PHASE_ROCKING);
            assert_int_equal(tm.phase[1][k], SW_PHASE_ROCKING);
            assert_int_not_equal(sw_mon_replace(M, 1, &bad, msg, sizeof msg), SW_OK);
            assert_int_equal(sw_mon_replace(M, 2, &b2, msg, sizeof msg), SW_EINVAL);
            assert_int_equal(sw_mon_replace(M, 1, &b2, msg, sizeof msg), SW_OK);
        }
    }

    /* crate-A: the same in both monitors, bit for bit. */
    for (long k = 0; k <= N; k++) assert_true(tm.theta[0][k] == tr.theta[0][k]);
    /* crate-B: at rest from the replacement until the second pulse lifts it. */
    assert_true(tm.theta[1][K_REPLACE + 1] == 0.0);
    assert_int_equal(tm.phase[1][K_REPLACE + 1], SW_PHASE_STUCK);
    assert_true(tr.theta[1][K_REPLACE + 1] != 0.0);
    int rocked = 0;
    for (long k = K_REPLACE + 1; k <= N; k++) rocked |= tm.phase[1][k] == SW_PHASE_ROCKING;
    assert_true(rocked);

    /* The messages: one seq without a gap, the new name and model. */
    sw_mon_counts_t c;
    sw_mon_counts(M, &c);
    assert_int_equal(bus.count, c.states);
    assert_int_equal(bus.count, 2 * (N + 1));
    assert_int_equal(bus.gaps, 0);
    assert_string_equal(bus.last_name[1], "crate-B2");
    assert_int_equal(bus.last_model_b, SWAYWATCH_STATE_T_MODEL_FRAME);
    sw_summary_t s;
    assert_int_equal(sw_engine_summary(sw_mon_engine(M), 1, &s), SW_OK);
    assert_string_equal(s.name, "crate-B2");

    swaywatch_state_t_unsubscribe(lcm, sub);
    sw_mon_destroy(M);
    sw_mon_destroy(R);
    lcm_destroy(lcm);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_replace_keeps_the_others)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
