/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_alarm_reserve.c - alarms on the reserve (hysteresis, levels from
 * the scene), significant impacts and settling spans, and the presented
 * margin (alarm.h).  The tipping speed is checked against the physics it
 * stands for (a block launched just above it overturns, just below it does
 * not), the presented margin against a real overturn run. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define MAXA 32

typedef struct {
    sw_alarm_t a[MAXA];
    int n;
} sink_t;

static void collect(void *user, const sw_alarm_t *a)
{
    sink_t *s = user;
    assert_true(s->n < MAXA);
    assert_true(isfinite(a->t) && isfinite(a->theta) && isfinite(a->margin));
    assert_non_null(memchr(a->text, '\0', sizeof a->text));
    s->a[s->n++] = *a;
}

static int feed(sw_alarm_watch_t *w, sink_t *s, double t, double reserve)
{
    return sw_alarm_on_reserve(w, t, 0.01, 0.8, reserve, collect, s);
}

/* A reserve hovering at a level raises one alarm; it re-arms only above
 * level + hysteresis; falling below both levels at once raises WARN then
 * CRITICAL; NaN neither raises nor re-arms. */
static void test_reserve_hysteresis(void **state)
{
    (void)state;
    sw_alarm_watch_t w;
    sink_t s = {.n = 0};
    assert_int_equal(sw_alarm_init(&w, 3, 0.5, 0.2, -1.0), SW_OK);
    /* off until levels are set */
    assert_int_equal(feed(&w, &s, 0.0, 0.01), 0);
    assert_int_equal(sw_alarm_set_reserve(&w, 0.2, 0.1, 0.02), SW_OK);
    assert_int_equal(feed(&w, &s, 0.1, 0.30), 0);
    assert_int_equal(feed(&w, &s, 0.2, 0.19), 1);
    assert_int_equal(s.a[0].kind, SW_ALARM_RESERVE_WARN);
    assert_int_equal(s.a[0].level, SW_ALARM_LEVEL_WARN);
    assert_int_equal((int)s.a[0].pkg, 3);
    assert_true(s.a[0].t == 0.2 && s.a[0].margin == 0.8 && s.a[0].theta == 0.01);
    assert_non_null(strstr(s.a[0].text, "reserve 0.190 g < warn 0.200 g"));
    assert_int_equal(feed(&w, &s, 0.3, 0.215), 0); /* within the band: not re-armed */
    assert_int_equal(feed(&w, &s, 0.4, 0.19), 0);
    assert_int_equal(feed(&w, &s, 0.5, NAN), 0);
    assert_int_equal(feed(&w, &s, 0.6, 0.23), 0); /* re-armed */
    assert_int_equal(feed(&w, &s, 0.7, 0.05), 2);
    assert_int_equal(s.a[1].kind, SW_ALARM_RESERVE_WARN);
    assert_int_equal(s.a[2].kind, SW_ALARM_RESERVE_CRITICAL);
    assert_int_equal(s.a[2].level, SW_ALARM_LEVEL_CRITICAL);
    assert_int_equal(feed(&w, &s, 0.8, 0.0), 0);
    assert_int_equal((int)w.raised, 3);
    assert_string_equal(sw_alarm_kind_name(SW_ALARM_RESERVE_WARN), "reserve_warn");
    assert_string_equal(sw_alarm_kind_name(SW_ALARM_RESERVE_CRITICAL), "reserve_critical");
}

static void test_reserve_levels(void **state)
{
    (void)state;
    sw_alarm_watch_t w;
    assert_int_equal(sw_alarm_init(&w, 0, 0.5, 0.2, -1.0), SW_OK);
    assert_int_equal(sw_alarm_set_reserve(&w, 0.1, 0.1, 0.0), SW_EINVAL);
    assert_int_equal(sw_alarm_set_reserve(&w, 0.1, 0.0, 0.0), SW_EINVAL);
    assert_int_equal(sw_alarm_set_reserve(&w, NAN, 0.05, 0.0), SW_EINVAL);
    assert_int_equal(sw_alarm_set_reserve(&w, 0.1, 0.05, -1.0), SW_OK);
    assert_true(w.reserve_hysteresis_g == SW_ALARM_RESERVE_HYSTERESIS_G);
    assert_int_equal(sw_alarm_set_reserve(&w, 0.0, 0.0, 0.0), SW_OK); /* off */
    assert_int_equal(sw_alarm_on_reserve(&w, 0.0, 0.0, 0.0, 0.0, NULL, NULL), 0);

    /* from a scene: its levels, and impacts judged by significance */
    sw_scene_t sc = tu_bare(2.0, 0.728);
    sc.warn_reserve_g = 0.3;
    sc.critical_reserve_g = 0.12;
    assert_int_equal(sw_alarm_init_scene(&w, 1, &sc, -1.0), SW_OK);
    assert_true(w.warn_reserve_g == 0.3 && w.critical_reserve_g == 0.12);
    assert_true(w.warn_margin == sc.warn_margin && w.critical_margin == sc.critical_margin);
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(&sc, &d, NULL, NULL, NULL), SW_OK);
    assert_float_equal(w.impact_min, SW_IMPACT_SIGNIFICANCE * sw_impact_tip_speed(&d, sc.g), 0.0);
    sc.mass = -1.0;
    assert_int_equal(sw_alarm_init_scene(&w, 1, &sc, -1.0), SW_EINVAL);
}

/* The tipping speed is 2 p sin(alpha/2) (closed form, from h, b, g), and
 * it means what it says: a block launched upright at 1.01 times it with no
 * input overturns, at 0.99 times it does not (rk8pd). */
static void test_tip_speed(void **state)
{
    (void)state;
    const double h = 1.0, b = 0.364, g = 9.81;
    const sw_scene_t sc = tu_bare(2.0 * h, 2.0 * b);
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(&sc, &d, NULL, NULL, NULL), SW_OK);
    const double p = sqrt(3.0 * g / (4.0 * sqrt(h * h + b * b)));
    const double w = 2.0 * p * sin(0.5 * atan(b / h));
    assert_float_equal(sw_impact_tip_speed(&d, g), w, 1e-12);
    for (int k = 0; k < 2; k++) {
        const double f = k ? 1.01 : 0.99;
        sw_state_t s;
        memset(&s, 0, sizeof s);
        s.phase = SW_PHASE_ROCKING;
        s.side = 1;
        s.theta_dot = f * w;
        sw_pulse_t none = {SW_PULSE_HALF_SINE, 0.0, 1.0};
        sw_run_opts_t ro;
        memset(&ro, 0, sizeof ro);
        ro.engine.scheme = "rk8pd";
        ro.engine.rtol = 1e-12;
        ro.engine.atol = 1e-14;
        sw_run_result_t r;
        assert_int_equal(sw_pulse_run_from(&sc, &s, &none, &ro, &r, NULL, 0), SW_OK);
        assert_int_equal(r.overturned, k);
    }
    assert_true(sw_impact_significant(&d, g, -0.2 * w, 0.1));
    assert_false(sw_impact_significant(&d, g, 0.05 * w, 0.1));
    /* nothing impacts on a cushion */
    d.model = SW_MODEL_CUSHION;
    assert_true(sw_impact_tip_speed(&d, g) == 0.0);
}

static sw_event_t ev(sw_event_kind k, double t, double info)
{
    sw_event_t e;
    memset(&e, 0, sizeof e);
    e.kind = k;
    e.t = t;
    e.info = info;
    return e;
}

static void test_impact_alarms(void **state)
{
    (void)state;
    sw_alarm_watch_t w;
    sink_t s = {.n = 0};
    assert_int_equal(sw_alarm_init(&w, 0, 0.5, 0.2, -1.0), SW_OK);
    sw_event_t e = ev(SW_EV_IMPACT, 1.0, 0.003);
    assert_int_equal(sw_alarm_on_event(&w, &e, collect, &s), 1); /* every impact by default */
    assert_int_equal(sw_alarm_set_impact_min(&w, 0.09), SW_OK);
    assert_int_equal(sw_alarm_on_event(&w, &e, collect, &s), 0);
    e.info = -0.2;
    assert_int_equal(sw_alarm_on_event(&w, &e, collect, &s), 1);
    assert_int_equal(s.a[1].kind, SW_ALARM_IMPACT);
    e = ev(SW_EV_REST, 2.0, 0.0); /* other events unaffected */
    assert_int_equal(sw_alarm_on_event(&w, &e, collect, &s), 1);
    assert_int_equal(sw_alarm_set_impact_min(&w, -1.0), SW_EINVAL);
}

/* Micro-impacts fold into one span, closed by the next other event (or
 * at the end), reported before it. */
static void test_settle_spans(void **state)
{
    (void)state;
    sw_settle_t st;
    sw_settle_init(&st, 0.09);
    sw_settle_span_t sp;
    sw_event_t e = ev(SW_EV_UPLIFT, 1.0, 1.0);
    assert_int_equal(sw_settle_feed(&st, &e, &sp), SW_SETTLE_REPORT);
    e = ev(SW_EV_IMPACT, 1.5, 0.5);
    assert_int_equal(sw_settle_feed(&st, &e, &sp), SW_SETTLE_REPORT);
    const double micro[3][2] = {{1.6, -0.05}, {1.65, 0.02}, {1.67, -0.004}};
    for (int i = 0; i < 3; i++) {
        e = ev(SW_EV_IMPACT, micro[i][0], micro[i][1]);
        assert_int_equal(sw_settle_feed(&st, &e, &sp), 0);
    }
    e = ev(SW_EV_REST, 1.7, 0.0);
    memset(&sp, 0, sizeof sp);
    assert_int_equal(sw_settle_feed(&st, &e, &sp), SW_SETTLE_REPORT | SW_SETTLE_CLOSED);
    assert_true(sp.t_start == 1.6 && sp.t_end == 1.67);
    assert_int_equal(sp.impacts, 3);
    assert_true(sp.max_speed == 0.05);
    assert_int_equal(sw_settle_finish(&st, &sp), 0);
    /* a span still open at the end of the stream */
    e = ev(SW_EV_IMPACT, 3.0, 0.01);
    assert_int_equal(sw_settle_feed(&st, &e, NULL), 0);
    assert_int_equal(sw_settle_finish(&st, &sp), 1);
    assert_true(sp.t_start == 3.0 && sp.t_end == 3.0 && sp.impacts == 1);
    /* a significant impact closes it too */
    e = ev(SW_EV_IMPACT, 4.0, 0.01);
    sw_settle_feed(&st, &e, NULL);
    e = ev(SW_EV_IMPACT, 4.1, 0.3);
    assert_int_equal(sw_settle_feed(&st, &e, NULL), SW_SETTLE_REPORT | SW_SETTLE_CLOSED);
}

/* The presented margin: within [-1, 1], the margin itself on [0, 1],
 * monotone, -1 only when overturned. */
static void test_presented_margin(void **state)
{
    (void)state;
    assert_true(sw_margin_presented(1.0, SW_PHASE_STUCK) == 1.0);
    assert_true(sw_margin_presented(0.37, SW_PHASE_ROCKING) == 0.37);
    assert_true(sw_margin_presented(0.0, SW_PHASE_ROCKING) == 0.0);
    assert_true(sw_margin_presented(-21.19, SW_PHASE_ROCKING) > -1.0);
    assert_true(sw_margin_presented(-21.19, SW_PHASE_OVERTURNED) == -1.0);
    assert_true(isnan(sw_margin_presented(NAN, SW_PHASE_ROCKING)));
    double prev = -1.0;
    for (double m = -40.0; m <= 1.0; m += 0.01) {
        const double v = sw_margin_presented(m, SW_PHASE_ROCKING);
        assert_true(v >= -1.0 && v <= 1.0);
        assert_true(v >= prev);
        assert_true((v < 0.0) == (m < 0.0)); /* the edge stays where it is */
        prev = v;
    }
}

/* On a real overturn the raw margin runs far below -1 and steps back up to
 * -1 when the package lands on its side (what a plot reads as a
 * recovery); the presented margin falls monotonically to -1 instead. */
typedef struct {
    double last_raw, min_raw, last_shown;
    int rises, n;
} track_t;

static void on_state(void *user, const sw_output_t *o)
{
    track_t *t = user;
    const double v = sw_margin_presented(o->margin, o->state.phase);
    if (t->n && o->margin < 0.0 && v > t->last_shown)
        t->rises++;
    t->last_shown = v;
    if (o->state.phase != SW_PHASE_OVERTURNED)
        t->last_raw = o->margin;
    t->min_raw = fmin(t->min_raw, o->margin);
    t->n++;
}

static void test_presented_margin_overturn(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    sw_engine_opts_t o;
    memset(&o, 0, sizeof o);
    track_t t = {.last_raw = 1.0, .min_raw = 1.0, .last_shown = 1.0, .rises = 0, .n = 0};
    o.on_state = on_state;
    o.user = &t;
    int err;
    sw_engine_t *e = sw_engine_create(&sc, 1, &o, &err, NULL, 0);
    assert_non_null(e);
    /* a hard braking half-sine, 1 s, 1 g: far past the boundary */
    sw_pulse_t pl = {SW_PULSE_HALF_SINE, -SW_G0, M_PI};
    for (int i = 1; i <= 4000; i++) sw_engine_push(e, i * 1e-3, sw_pulse_eval(&pl, i * 1e-3), 0.0);
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_true(s.overturned);
    assert_true(t.min_raw < -5.0);     /* the raw margin runs far below -1 ... */
    assert_true(t.last_raw < -1.0);    /* ... right up to the overturn */
    assert_true(t.last_shown == -1.0); /* shown: -1 at the end */
    assert_int_equal(t.rises, 0);      /* and never back up while negative */
    sw_engine_destroy(e);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reserve_hysteresis),
        cmocka_unit_test(test_reserve_levels),
        cmocka_unit_test(test_tip_speed),
        cmocka_unit_test(test_impact_alarms),
        cmocka_unit_test(test_settle_spans),
        cmocka_unit_test(test_presented_margin),
        cmocka_unit_test(test_presented_margin_overturn),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
