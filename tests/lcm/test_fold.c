/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_fold.c - the monitor's alarm rate limit (alarm_fold.h) keeps each
 * plane of a package apart: a burst of one plane's alarms of a kind
 * never holds back the other plane's alarm of that kind, which goes out
 * at once; the held-back ones of a plane are counted and summarised in
 * that plane's own summary. */
#include <math.h>
#include <stdint.h>
#include <string.h>

/* cmocka.h needs these before it. */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
// clang-format on

#include "alarm_fold.h"

#define MAXA 32

typedef struct {
    sw_alarm_t a[MAXA];
    int n;
} sink_t;

static void emit(void *user, const sw_alarm_t *a, int64_t utime)
{
    sink_t *s = user;
    (void)utime;
    assert_true(s->n < MAXA);
    s->a[s->n++] = *a;
}

static sw_alarm_t alarm_of(size_t pkg, sw_plane plane, sw_alarm_kind kind)
{
    sw_alarm_t a;
    memset(&a, 0, sizeof a);
    a.pkg = pkg;
    a.plane = plane;
    a.kind = kind;
    a.level = SW_ALARM_LEVEL_CRITICAL;
    strcpy(a.text, plane == SW_PLANE_LAT ? "tipping sideways" : "tip");
    return a;
}

static void test_planes_apart(void **st)
{
    (void)st;
    sink_t s = {.n = 0};
    sw_fold_t *f = sw_fold_create(2, 1.0, emit, &s);
    assert_non_null(f);
    /* a storm across the truck on package 1: a burst, the rest held */
    const sw_alarm_t lat = alarm_of(1, SW_PLANE_LAT, SW_ALARM_TIP);
    for (int i = 0; i < 10; i++) sw_fold_send(f, &lat, i, 0.01 * i);
    assert_int_equal(s.n, SW_FOLD_BURST);
    /* the same kind along the truck, in the same window: out at once, as
     * are package 0's */
    const sw_alarm_t lon = alarm_of(1, SW_PLANE_LONG, SW_ALARM_TIP);
    sw_fold_send(f, &lon, 100, 0.2);
    assert_int_equal(s.n, SW_FOLD_BURST + 1);
    assert_int_equal(s.a[s.n - 1].plane, SW_PLANE_LONG);
    const sw_alarm_t other = alarm_of(0, SW_PLANE_LAT, SW_ALARM_TIP);
    sw_fold_send(f, &other, 101, 0.3);
    assert_int_equal(s.n, SW_FOLD_BURST + 2);
    assert_int_equal(s.a[s.n - 1].pkg, 0);
    /* the window ends: the lateral plane's summary, its plane kept */
    sw_fold_tick(f, 2.0);
    assert_int_equal(s.n, SW_FOLD_BURST + 3);
    const sw_alarm_t *sum = &s.a[s.n - 1];
    assert_int_equal(sum->plane, SW_PLANE_LAT);
    assert_int_equal(sum->pkg, 1);
    assert_non_null(strstr(sum->text, "7 more in 1 s, the last: tipping sideways"));
    assert_int_equal(sw_fold_folded(f), 6);
    /* input alarms keep their own row */
    sw_alarm_t in;
    sw_alarm_input(&in, SW_ALARM_SENSOR_GAP, SW_ALARM_LEVEL_WARN, 0.0, "gap");
    sw_fold_send(f, &in, 200, 3.0);
    assert_int_equal(s.n, SW_FOLD_BURST + 4);
    sw_fold_destroy(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_planes_apart),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
