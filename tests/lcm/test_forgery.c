/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_forgery.c - forged samples on the accel channel never silence an
 * overturn (docs/timing.md, "Contested input").  A genuine sensor sends
 * 1 kHz of two brakings that overturn the crate (8 m/s^2 half-sines at
 * 10 rad/s, 1.5 s apart: either alone leaves it at a third of its tipping
 * angle, a run of the engine shows); a forger on the same channel sends
 * quiet samples among them, every 1 to 8 genuine ones, stamped ahead,
 * behind, on the genuine times, a year ahead, in bursts; its seq copies,
 * follows, or ignores the genuine one.  The monitor core, over memq://,
 * must end with a TIP or OVERTURNED alarm for the crate or a critical
 * INPUT_CONTESTED alarm: never only WARN-level input alarms.  And the
 * work stays bounded: the engine's steps are those of a clean run, within
 * a factor. */
#include <gsl/gsl_errno.h>
#include <lcm/lcm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* cmocka.h needs these before it. */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
// clang-format on

#include "monitor.h"
#include "swaywatch/swaywatch.h"
#include "swaywatch_accel_t.h"
#include "swaywatch_alarm_t.h"

#define NSAMP 4001 /* 4 s at 1 kHz */
#define UTIME0 1700000000000000LL
#define MAXAL 4096

static const char *scene_a =
    "[package]\nname = crate-A\nheight = 2.0\nwidth = 0.728\nmass = 1000\n"
    "[alarm]\nwarn_margin = 0.5\ncritical_margin = 0.2\n";

/* m/s^2: two brakings, 8 m/s^2 at 10 rad/s, from 0.2 s and 1.7 s */
static double drive(long k)
{
    const double t = (double)k / 1000.0;
    double a = 0.0;
    for (int i = 0; i < 2; i++) {
        const double t0 = 0.2 + 1.5 * i;
        if (t >= t0 && t <= t0 + M_PI / 10.0)
            a -= 8.0 * sin(10.0 * (t - t0));
    }
    return a;
}

static uint64_t rng_state;
static uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

typedef struct {
    swaywatch_alarm_t al[MAXAL];
    int nal;
} bus_t;

static void on_alarm_msg(const lcm_recv_buf_t *rb, const char *ch, const swaywatch_alarm_t *m,
                         void *user)
{
    (void)rb;
    (void)ch;
    bus_t *b = user;
    if (b->nal < MAXAL)
        b->al[b->nal++] = *m;
}

typedef struct {
    lcm_t *lcm;
    sw_mon_t *mon;
    swaywatch_alarm_t_subscription_t *as;
    sw_scene_t scene;
    bus_t bus;
} rig_t;

static rig_t *rig_new(int confirm)
{
    rig_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    sw_scene_init(&r->scene);
    assert_int_equal(sw_scene_parse(&r->scene, scene_a, "test", NULL, NULL), SW_OK);
    assert_int_equal(sw_scene_validate(&r->scene, NULL, "test", NULL, NULL), SW_OK);
    r->lcm = lcm_create("memq://");
    assert_non_null(r->lcm);
    sw_mon_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.vertical = -1;
    mo.hysteresis = -1.0;
    mo.reserve_rate = -1.0; /* the reserve is not what this is about; faster */
    mo.confirm = confirm;
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    char msg[256] = "";
    r->mon = sw_mon_create(&r->scene, 1, &eo, &mo, r->lcm, msg, sizeof msg);
    assert_non_null(r->mon);
    r->as = swaywatch_alarm_t_subscribe(r->lcm, "SWAY_ALARM", on_alarm_msg, &r->bus);
    swaywatch_alarm_t_subscription_set_queue_capacity(r->as, 0);
    return r;
}

static void rig_free(rig_t *r)
{
    swaywatch_alarm_t_unsubscribe(r->lcm, r->as);
    sw_mon_destroy(r->mon);
    lcm_destroy(r->lcm);
    free(r);
}

static void feed(rig_t *r, int64_t utime, int64_t seq, double ax, double mono)
{
    const swaywatch_accel_t s = {.utime = utime, .seq = seq, .ax = ax};
    unsigned char buf[128];
    const int len = swaywatch_accel_t_encode(buf, 0, sizeof buf, &s);
    assert_true(len > 0);
    sw_mon_feed(r->mon, buf, (size_t)len, 0, mono, NULL);
}

static void finish(rig_t *r)
{
    sw_mon_flush(r->mon);
    while (lcm_handle_timeout(r->lcm, 0) > 0) {
    }
}

static int has(const bus_t *b, int kind, int level)
{
    for (int i = 0; i < b->nal; i++)
        if (b->al[i].kind == kind && b->al[i].level >= level)
            return 1;
    return 0;
}

static int overturn_seen(const bus_t *b)
{
    return has(b, SWAYWATCH_ALARM_T_KIND_TIP, 0) || has(b, SWAYWATCH_ALARM_T_KIND_OVERTURNED, 0);
}

static long steps(rig_t *r)
{
    sw_summary_t s;
    assert_int_equal(sw_engine_summary(sw_mon_engine(r->mon), 0, &s), SW_OK);
    return s.steps;
}

/* The drive alone: the crate overturns, and what that costs. */
static long clean_steps;

static void test_genuine_overturns(void **st)
{
    (void)st;
    rig_t *r = rig_new(0);
    for (long k = 0; k < NSAMP; k++) feed(r, UTIME0 + k * 1000, k, drive(k), k * 1e-3);
    finish(r);
    assert_true(has(&r->bus, SWAYWATCH_ALARM_T_KIND_OVERTURNED, SWAYWATCH_ALARM_T_LEVEL_CRITICAL));
    assert_false(has(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED, 0));
    clean_steps = steps(r);
    assert_true(clean_steps > 100);
    rig_free(r);
    /* either braking alone does not overturn it */
    for (int which = 0; which < 2; which++) {
        rig_t *q = rig_new(0);
        for (long k = 0; k < NSAMP; k++) {
            const double a = (k < 1600) == (which == 0) ? drive(k) : 0.0;
            feed(q, UTIME0 + k * 1000, k, a, k * 1e-3);
        }
        finish(q);
        assert_false(overturn_seen(&q->bus));
        rig_free(q);
    }
}

/* The attack as reported: one forged sample per two genuine ones, each
 * stamped 2.5 ms ahead of the genuine one it follows and arriving with
 * it, quiet, with the genuine seq; also with --confirm 8.  Before, every
 * genuine sample was refused as out of order and the crate was reported
 * upright with WARN-level input alarms only.  From 0.5 s on (the monitor
 * knows the sensor's pace): the genuine timeline is kept; from the first
 * sample (nothing known yet, either may be taken): the overturn is still
 * raised, by whichever timeline carries the genuine samples. */
static void test_interleave_attack(void **st)
{
    (void)st;
    for (int from = 0; from <= 500; from += 500)
        for (int confirm = 3; confirm <= 8; confirm += 5) {
            rig_t *r = rig_new(confirm);
            for (long k = 0; k < NSAMP; k++) {
                const double mono = k * 1e-3;
                feed(r, UTIME0 + k * 1000, k, drive(k), mono);
                if (k >= from && k % 2 == 1)
                    feed(r, UTIME0 + k * 1000 + 2500, k, 0.0, mono + 1e-6);
            }
            finish(r);
            assert_true(overturn_seen(&r->bus));
            assert_true(has(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED,
                            SWAYWATCH_ALARM_T_LEVEL_CRITICAL));
            sw_mon_counts_t c;
            sw_mon_counts(r->mon, &c);
            if (from > 0)
                assert_int_equal(c.accepted, NSAMP); /* the genuine timeline was kept */
            assert_true(c.contests >= 1);
            assert_true(c.lost <= 8); /* forged seqs are no loss (a few before the contest) */
            assert_true(steps(r) <= 3 * clean_steps);
            rig_free(r);
        }
}

enum { F_AHEAD, F_AHEAD_SMALL, F_BEHIND, F_ON_GENUINE, F_YEAR, F_BURST, F_KINDS };
enum { S_COPY, S_NEXT, S_RANDOM, S_HUGE, S_MIN, S_KINDS };

static int64_t forged_seq(int sk, long k, long j)
{
    switch (sk) {
        case S_COPY: return k;
        case S_NEXT: return k + 1;
        case S_RANDOM: return (int64_t)(rng_next() >> 1);
        case S_HUGE: return INT64_MAX - 1000 + j % 1000;
        default: return INT64_MIN;
    }
}

/* Every pattern: the genuine verdict, or a critical contest. */
static void test_forgery_patterns(void **st)
{
    (void)st;
    static const char *const kinds[F_KINDS] = {
        "ahead", "a little ahead", "behind", "on the genuine times", "a year ahead", "in bursts"};
    int genuine_kept = 0, cases = 0;
    for (int kind = 0; kind < F_KINDS; kind++)
        for (int sk = 0; sk < S_KINDS; sk++)
            for (int ratio = 1; ratio <= 8; ratio += (ratio < 3 ? 1 : 5))
                for (int confirm = 3; confirm <= 8; confirm += 5) {
                    rng_state = (uint64_t)(1 + kind * 1000 + sk * 100 + ratio * 10 + confirm);
                    const double value = (rng_next() & 1) ? 0.0 : 8.0; /* quiet, or the other way */
                    rig_t *r = rig_new(confirm);
                    long j = 0;
                    for (long k = 0; k < NSAMP; k++) {
                        const double mono = k * 1e-3;
                        const int64_t u = UTIME0 + k * 1000;
                        const int forge = k % ratio == ratio - 1;
                        if (forge && kind == F_ON_GENUINE)
                            feed(r, u, forged_seq(sk, k, j++), value, mono - 1e-6);
                        feed(r, u, k, drive(k), mono);
                        if (!forge || kind == F_ON_GENUINE)
                            continue;
                        switch (kind) {
                            case F_AHEAD:
                                feed(r, u + 2500, forged_seq(sk, k, j++), value, mono);
                                break;
                            case F_AHEAD_SMALL:
                                feed(r, u + 500, forged_seq(sk, k, j++), value, mono + 5e-4);
                                break;
                            case F_BEHIND:
                                feed(r, u - 2500, forged_seq(sk, k, j++), value, mono);
                                break;
                            case F_YEAR:
                                feed(r, u + 31536000000000LL, forged_seq(sk, k, j++), value, mono);
                                break;
                            case F_BURST:
                                for (int b = 0; b < confirm + 1; b++)
                                    feed(r, u + 2500 + 1000 * b, forged_seq(sk, k, j++), value,
                                         mono);
                                break;
                        }
                    }
                    finish(r);
                    const int kept = overturn_seen(&r->bus);
                    const int contested = has(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED,
                                              SWAYWATCH_ALARM_T_LEVEL_CRITICAL);
                    if (!kept && !contested)
                        fail_msg("forged %s, seq kind %d, 1:%d, confirm %d: silence", kinds[kind],
                                 sk, ratio, confirm);
                    /* a second sender is always said, at critical level */
                    if (!contested)
                        fail_msg("forged %s, seq kind %d, 1:%d, confirm %d: not contested",
                                 kinds[kind], sk, ratio, confirm);
                    if (steps(r) > 3 * clean_steps)
                        fail_msg("forged %s, seq kind %d, 1:%d, confirm %d: %ld steps, clean %ld",
                                 kinds[kind], sk, ratio, confirm, steps(r), clean_steps);
                    genuine_kept += kept;
                    cases++;
                    rig_free(r);
                }
    /* with arrival times the genuine timeline is the one kept, mostly */
    printf("genuine overturn seen in %d of %d forged patterns\n", genuine_kept, cases);
    assert_true(2 * genuine_kept > cases);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_genuine_overturns),
        cmocka_unit_test(test_interleave_attack),
        cmocka_unit_test(test_forgery_patterns),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
