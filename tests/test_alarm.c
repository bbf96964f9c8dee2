/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_alarm.c - the alarm module: event mapping, margin thresholds with
 * hysteresis, non-finite outputs.  Pure logic, no engine needed: outputs
 * and events are made up here. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* cmocka.h needs these before it. */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
// clang-format on

#include "swaywatch/alarm.h"
#include "swaywatch/status.h"

#define MAXA 64

typedef struct {
    sw_alarm_t a[MAXA];
    int n;
} sink_t;

static void collect(void *user, const sw_alarm_t *a)
{
    sink_t *s = user;
    assert_true(s->n < MAXA);
    /* Whatever is raised must be publishable as is. */
    assert_true(isfinite(a->t) && isfinite(a->theta) && isfinite(a->margin));
    assert_non_null(memchr(a->text, '\0', sizeof a->text));
    s->a[s->n++] = *a;
}

static sw_output_t out_at(double t, double margin)
{
    sw_output_t o;
    memset(&o, 0, sizeof o);
    o.t = t;
    o.margin = margin;
    o.margin_bound = margin;
    o.state.theta = 0.01;
    o.state.phase = SW_PHASE_ROCKING;
    return o;
}

static int feed(sw_alarm_watch_t *w, sink_t *s, double t, double margin)
{
    sw_output_t o = out_at(t, margin);
    return sw_alarm_on_output(w, &o, collect, s);
}

/* A margin oscillating around warn_margin, within the hysteresis band,
 * raises exactly one WARN; rising above warn + hysteresis re-arms it. */
static void test_warn_hysteresis(void **st)
{
    (void)st;
    sw_alarm_watch_t w;
    sink_t s = {.n = 0};
    assert_int_equal(sw_alarm_init(&w, 3, 0.5, 0.2, 0.05), SW_OK);
    assert_int_equal(feed(&w, &s, 0.0, 1.0), 0);
    for (int i = 0; i < 200; i++) {
        double m = 0.5 + 0.04 * sin(0.7 * i); /* crosses 0.5 about 45 times */
        feed(&w, &s, 0.001 * i, m);
    }
    assert_int_equal(s.n, 1);
    assert_int_equal(s.a[0].kind, SW_ALARM_WARN);
    assert_int_equal(s.a[0].level, SW_ALARM_LEVEL_WARN);
    assert_int_equal(s.a[0].pkg, 3);
    assert_true(s.a[0].margin < 0.5);
    assert_non_null(strstr(s.a[0].text, "warn"));

    /* Exactly at threshold + hysteresis is not above it: still disarmed. */
    feed(&w, &s, 1.0, 0.55);
    feed(&w, &s, 1.1, 0.45);
    assert_int_equal(s.n, 1);
    /* Above it: re-armed, and the next fall raises a second WARN. */
    feed(&w, &s, 1.2, 0.5501);
    feed(&w, &s, 1.3, 0.499);
    assert_int_equal(s.n, 2);
    assert_int_equal(s.a[1].kind, SW_ALARM_WARN);
    assert_true(fabs(s.a[1].t - 1.3) < 1e-15);
}

/* Falling below both thresholds in one step raises WARN then CRITICAL;
 * each threshold has its own hysteresis. */
static void test_warn_and_critical(void **st)
{
    (void)st;
    sw_alarm_watch_t w;
    sink_t s = {.n = 0};
    assert_int_equal(sw_alarm_init(&w, 0, 0.5, 0.2, -1.0), SW_OK);
    assert_true(fabs(w.hysteresis - SW_ALARM_HYSTERESIS) < 1e-15);
    assert_int_equal(feed(&w, &s, 0.0, 0.1), 2);
    assert_int_equal(s.a[0].kind, SW_ALARM_WARN);
    assert_int_equal(s.a[1].kind, SW_ALARM_CRITICAL);
    assert_int_equal(s.a[1].level, SW_ALARM_LEVEL_CRITICAL);
    /* Back to 0.3: critical re-arms (0.3 > 0.25), warn does not. */
    assert_int_equal(feed(&w, &s, 0.1, 0.3), 0);
    assert_int_equal(feed(&w, &s, 0.2, 0.19), 1);
    assert_int_equal(s.a[2].kind, SW_ALARM_CRITICAL);
    /* Overturned: margin stays negative, nothing more is raised. */
    for (int i = 0; i < 10; i++) assert_int_equal(feed(&w, &s, 0.3 + i, -0.5), 0);
    assert_int_equal(s.n, 3);
}

static void test_events(void **st)
{
    (void)st;
    static const struct {
        sw_event_kind ev;
        double info;
        sw_alarm_kind kind;
        sw_alarm_level level;
        const char *word;
    } cases[] = {
        {SW_EV_UPLIFT, +1, SW_ALARM_UPLIFT, SW_ALARM_LEVEL_INFO, "forward"},
        {SW_EV_UPLIFT, -1, SW_ALARM_UPLIFT, SW_ALARM_LEVEL_INFO, "backward"},
        {SW_EV_IMPACT, -0.25, SW_ALARM_IMPACT, SW_ALARM_LEVEL_INFO, "impact"},
        {SW_EV_REST, 0, SW_ALARM_REST, SW_ALARM_LEVEL_INFO, "rest"},
        {SW_EV_TIP, 0, SW_ALARM_TIP, SW_ALARM_LEVEL_CRITICAL, "corner"},
        {SW_EV_OVERTURN, 0, SW_ALARM_OVERTURNED, SW_ALARM_LEVEL_CRITICAL, "overturned"},
        {SW_EV_FAULT, SW_EFAULT, SW_ALARM_MODEL_FAULT, SW_ALARM_LEVEL_CRITICAL, "model fault"},
        {SW_EV_FLIGHT, 1.0, SW_ALARM_MODEL_FAULT, SW_ALARM_LEVEL_CRITICAL, "free flight"},
    };
    sw_alarm_watch_t w;
    sink_t s = {.n = 0};
    assert_int_equal(sw_alarm_init(&w, 1, 0.5, 0.2, 0.05), SW_OK);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sw_event_t ev = {.pkg = 1,
                         .kind = cases[i].ev,
                         .t = 2.5,
                         .theta = 0.1 * (double)i,
                         .theta_dot = 0.0,
                         .margin = 0.7,
                         .info = cases[i].info};
        assert_int_equal(sw_alarm_on_event(&w, &ev, collect, &s), 1);
        assert_int_equal(s.a[i].kind, cases[i].kind);
        assert_int_equal(s.a[i].level, cases[i].level);
        assert_non_null(strstr(s.a[i].text, cases[i].word));
        assert_true(fabs(s.a[i].theta - 0.1 * (double)i) < 1e-15);
        assert_true(fabs(s.a[i].t - 2.5) < 1e-15);
    }
    /* An unknown event kind raises nothing; a NaN in an event never reaches
     * the alarm. */
    sw_event_t odd = {.kind = (sw_event_kind)99};
    assert_int_equal(sw_alarm_on_event(&w, &odd, collect, &s), 0);
    sw_event_t nan_ev = {.kind = SW_EV_IMPACT, .t = 1, .theta = NAN, .margin = NAN, .info = NAN};
    assert_int_equal(sw_alarm_on_event(&w, &nan_ev, collect, &s), 1);
    assert_true(s.a[s.n - 1].theta == 0.0 && s.a[s.n - 1].margin == 0.0);
    assert_int_equal(w.raised, s.n);
}

/* A non-finite output raises one MODEL_FAULT (not one per sample), does not
 * touch the margin alarms, and re-arms once outputs are finite again. */
static void test_nonfinite_output(void **st)
{
    (void)st;
    sw_alarm_watch_t w;
    sink_t s = {.n = 0};
    assert_int_equal(sw_alarm_init(&w, 0, 0.5, 0.2, 0.05), SW_OK);
    sw_output_t o = out_at(0.0, 1.0);
    assert_true(sw_alarm_output_finite(&o));
    o.state.theta_dot = NAN;
    assert_false(sw_alarm_output_finite(&o));
    assert_int_equal(sw_alarm_on_output(&w, &o, collect, &s), 1);
    o.margin = NAN; /* a NaN margin must not look like "below warn" */
    assert_int_equal(sw_alarm_on_output(&w, &o, collect, &s), 0);
    o.a_g = INFINITY;
    assert_int_equal(sw_alarm_on_output(&w, &o, collect, &s), 0);
    assert_int_equal(s.n, 1);
    assert_int_equal(s.a[0].kind, SW_ALARM_MODEL_FAULT);
    assert_int_equal(s.a[0].level, SW_ALARM_LEVEL_CRITICAL);
    assert_true(s.a[0].margin == 1.0); /* finite values are kept */

    assert_int_equal(feed(&w, &s, 1.0, 0.9), 0);
    o = out_at(2.0, NAN);
    o.state.theta = -INFINITY;
    assert_int_equal(sw_alarm_on_output(&w, &o, collect, &s), 1);
    assert_int_equal(s.n, 2);
    assert_true(s.a[1].theta == 0.0 && s.a[1].margin == 0.0); /* stand-ins for non-finite */
}

static void test_input_and_names(void **st)
{
    (void)st;
    sw_alarm_t a;
    char longtext[400];
    memset(longtext, 'x', sizeof longtext - 1);
    longtext[sizeof longtext - 1] = '\0';
    sw_alarm_input(&a, SW_ALARM_SENSOR_GAP, SW_ALARM_LEVEL_WARN, NAN, longtext);
    assert_int_equal(a.pkg, SW_ALARM_ALL);
    assert_true(a.t == 0.0 && a.theta == 0.0 && a.margin == 0.0);
    assert_int_equal(strlen(a.text), SW_ALARM_TEXT_MAX - 1);
    assert_string_equal(sw_alarm_kind_name(SW_ALARM_SENSOR_GAP), "sensor_gap");
    assert_string_equal(sw_alarm_kind_name(SW_ALARM_INPUT_REJECTED), "input_rejected");
    assert_string_equal(sw_alarm_kind_name((sw_alarm_kind)0), "unknown");
    assert_string_equal(sw_alarm_level_name(SW_ALARM_LEVEL_CRITICAL), "critical");
    sw_alarm_watch_t w;
    assert_int_equal(sw_alarm_init(&w, 0, NAN, 0.2, 0.05), SW_EINVAL);
    assert_int_equal(sw_alarm_init(NULL, 0, 0.5, 0.2, 0.05), SW_EINVAL);
}

/* A lateral plane's watch: every alarm it raises carries SW_PLANE_LAT and
 * says "sideways" (the uplift also to which side: theta > 0 is the top to
 * the left); the same events on a watch along the truck say neither. */
static void test_lateral_plane(void **st)
{
    (void)st;
    static const struct {
        sw_event_kind ev;
        double info;
        const char *lat, *lon;
    } cases[] = {
        {SW_EV_UPLIFT, +1, "corner lifted: rocking sideways, to the left", "rocking forward"},
        {SW_EV_UPLIFT, -1, "corner lifted: rocking sideways, to the right", "rocking backward"},
        {SW_EV_IMPACT, -0.25, "impact sideways at", "impact at"},
        {SW_EV_REST, 0, "back to rest after rocking sideways", "back to rest"},
        {SW_EV_TIP, 0, "tipping sideways: centre of mass over the corner", "centre of mass"},
        {SW_EV_OVERTURN, 0, "overturned sideways (|theta| = pi/2)", "overturned (|theta|"},
        {SW_EV_FAULT, SW_EFAULT, "model fault sideways: ", "model fault: "},
        {SW_EV_FLIGHT, 1.0, "s sideways: the landing", "s: the landing"},
    };
    sw_alarm_watch_t lat, lon;
    assert_int_equal(sw_alarm_init(&lat, 3, 0.5, 0.2, 0.05), SW_OK);
    assert_int_equal(sw_alarm_init(&lon, 3, 0.5, 0.2, 0.05), SW_OK);
    assert_int_equal(lon.plane, SW_PLANE_LONG);
    assert_int_equal(sw_alarm_set_plane(&lat, SW_PLANE_LAT), SW_OK);
    assert_int_equal(sw_alarm_set_plane(&lat, (sw_plane)7), SW_EINVAL);
    assert_int_equal(sw_alarm_set_plane(NULL, SW_PLANE_LAT), SW_EINVAL);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sink_t a = {.n = 0}, b = {.n = 0};
        const sw_event_t ev = {.kind = cases[i].ev, .pkg = 3, .t = 1.0, .info = cases[i].info};
        assert_int_equal(sw_alarm_on_event(&lat, &ev, collect, &a), 1);
        assert_int_equal(sw_alarm_on_event(&lon, &ev, collect, &b), 1);
        assert_int_equal(a.a[0].plane, SW_PLANE_LAT);
        assert_int_equal(b.a[0].plane, SW_PLANE_LONG);
        assert_int_equal(a.a[0].kind, b.a[0].kind); /* the same kind, level and package */
        assert_int_equal(a.a[0].level, b.a[0].level);
        assert_int_equal(a.a[0].pkg, 3);
        assert_non_null(strstr(a.a[0].text, cases[i].lat));
        assert_non_null(strstr(b.a[0].text, cases[i].lon));
        assert_null(strstr(b.a[0].text, "sideways"));
    }
    /* margins and reserves: the plane and the word, the numbers as along */
    sink_t a = {.n = 0};
    assert_int_equal(feed(&lat, &a, 1.0, 0.1), 2);
    assert_int_equal(sw_alarm_set_reserve(&lat, 0.3, 0.1, -1.0), SW_OK);
    assert_int_equal(sw_alarm_on_reserve(&lat, 1.0, 0.0, 0.1, 0.05, collect, &a), 2);
    assert_int_equal(a.n, 4);
    assert_string_equal(a.a[0].text, "margin sideways 0.100 < warn 0.500");
    assert_string_equal(a.a[1].text, "margin sideways 0.100 < critical 0.200");
    assert_string_equal(a.a[2].text, "reserve sideways 0.050 g < warn 0.300 g");
    assert_string_equal(a.a[3].text, "reserve sideways 0.050 g < critical 0.100 g");
    for (int i = 0; i < a.n; i++) assert_int_equal(a.a[i].plane, SW_PLANE_LAT);
    /* input alarms belong to no package's plane */
    sw_alarm_t in;
    in.plane = SW_PLANE_LAT;
    sw_alarm_input(&in, SW_ALARM_SENSOR_GAP, SW_ALARM_LEVEL_WARN, 1.0, "gap");
    assert_int_equal(in.plane, SW_PLANE_LONG);
}

/* The two numbers of "margin X < critical Y" (or "reserve X g < warn
 * Y g"), read back. */
static void numbers(const char *text, double *x, double *y)
{
    const char *lt = strstr(text, " < ");
    assert_non_null(lt);
    const char *a = strchr(text, ' ');
    *x = strtod(a, NULL);
    const char *b = strchr(lt + 3, ' ');
    *y = strtod(b, NULL);
}

/* What an alarm says is true as printed: a margin or reserve just below
 * its level ("margin 0.200 < critical 0.200" was printed for 0.19996)
 * comes with the digits that show it below; an ordinary one keeps three
 * decimals.  The alarm is raised at the exact crossing, never later. */
static void test_text_compares_as_printed(void **st)
{
    (void)st;
    const double below[] = {1e-2, 1e-3, 4e-4, 5e-5, 1e-6, 1e-7, 1e-8};
    for (size_t k = 0; k < sizeof below / sizeof below[0]; k++) {
        sw_alarm_watch_t w;
        sink_t s = {.n = 0};
        assert_int_equal(sw_alarm_init(&w, 0, 0.5, 0.2, 0.05), SW_OK);
        assert_int_equal(sw_alarm_set_reserve(&w, 0.2, 0.1, 0.02), SW_OK);
        feed(&w, &s, 0.0, 1.0);
        assert_int_equal(feed(&w, &s, 0.1, 0.2 - below[k]), 2); /* warn and critical */
        sw_alarm_on_reserve(&w, 0.2, 0.0, 1.0, 0.1 - below[k], collect, &s);
        assert_int_equal(s.n, 2 + 2);
        for (int i = 0; i < s.n; i++) {
            double x, y;
            numbers(s.a[i].text, &x, &y);
            if (!(x < y))
                fail_msg("'%s' does not read as below (%g under the level)", s.a[i].text, below[k]);
        }
        if (below[k] >= 1e-3)
            assert_non_null(strstr(s.a[1].text, "< critical 0.200"));
    }
    sw_alarm_watch_t w;
    sink_t s = {.n = 0};
    assert_int_equal(sw_alarm_init(&w, 0, 0.5, 0.2, 0.05), SW_OK);
    feed(&w, &s, 0.0, 0.15);
    assert_string_equal(s.a[0].text, "margin 0.150 < warn 0.500");
    assert_string_equal(s.a[1].text, "margin 0.150 < critical 0.200");
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_warn_hysteresis), cmocka_unit_test(test_warn_and_critical),
        cmocka_unit_test(test_events),          cmocka_unit_test(test_nonfinite_output),
        cmocka_unit_test(test_input_and_names), cmocka_unit_test(test_text_compares_as_printed),
        cmocka_unit_test(test_lateral_plane),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
