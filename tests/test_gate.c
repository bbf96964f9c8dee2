/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_gate.c - the input gate (gate.h), on streams whose truth is known
 * by construction: a clean drive, one corrupt time, a hole, a restart, a
 * log played twice, forged and stepped times with receive times, spikes,
 * int64 extremes, gravity in the vertical column, and the plausibility
 * verdicts.  Every run checks received = accepted + held + rejected. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "swaywatch/gate.h"
#include "testutil.h"

#define MAXEV 64

typedef struct {
    sw_gate_event_t ev[MAXEV];
    int nev;
    long rej_where[MAXEV];
    sw_gate_reject rej_why[MAXEV];
    int nrej;
} log_t;

static void on_event(void *user, const sw_gate_event_t *ev)
{
    log_t *L = user;
    if (L->nev < MAXEV)
        L->ev[L->nev] = *ev;
    L->nev++;
}

static void on_reject(void *user, const sw_sample_t *s, sw_gate_reject r, const char *text)
{
    log_t *L = user;
    assert_non_null(text);
    if (L->nrej < MAXEV) {
        L->rej_where[L->nrej] = s->where;
        L->rej_why[L->nrej] = r;
    }
    L->nrej++;
}

typedef struct {
    sw_engine_t *e;
    sw_gate_t *g;
    log_t L;
} rig_t;

static void rig_open(rig_t *r, const sw_scene_t *sc, sw_gate_opts_t o)
{
    memset(r, 0, sizeof *r);
    r->e = tu_engine(sc, NULL, 0.0, NULL);
    assert_non_null(r->e);
    o.on_event = on_event;
    o.on_reject = on_reject;
    o.user = &r->L;
    char msg[128];
    r->g = sw_gate_create(r->e, &o, msg, sizeof msg);
    assert_non_null(r->g);
}

static sw_gate_facts_t rig_close(rig_t *r)
{
    sw_gate_facts_t f;
    sw_gate_flush(r->g);
    sw_gate_facts(r->g, &f);
    assert_int_equal(f.received, f.accepted + f.held + sw_gate_rejected(&f));
    assert_int_equal(f.held, 0);
    sw_gate_destroy(r->g);
    sw_engine_destroy(r->e);
    return f;
}

static sw_sample_t sample(double t, double a, long where)
{
    sw_sample_t s = {.t = t,
                     .a_g = a,
                     .a_max = NAN,
                     .seq = SW_GATE_NO_SEQ,
                     .rx = NAN,
                     .wall = NAN,
                     .where = where};
    return s;
}

static const sw_gate_opts_t defaults = {0};

static void test_clean(void **state)
{
    (void)state;
    rig_t r;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rig_open(&r, &sc, defaults);
    for (int i = 0; i <= 3000; i++)
        assert_true(sw_gate_push(r.g, &(sw_sample_t){.t = i * 1e-3,
                                                     .a_g = 0.1 * sin(i * 1e-2),
                                                     .a_max = NAN,
                                                     .seq = SW_GATE_NO_SEQ,
                                                     .rx = NAN,
                                                     .wall = NAN,
                                                     .where = i}) >= 0 ||
                    i < 2);
    const sw_gate_facts_t f = rig_close(&r);
    assert_int_equal(f.accepted, 3001);
    assert_int_equal(r.L.nev, 0);
    assert_int_equal(r.L.nrej, 0);
    tu_near(f.dt_median, 1e-3, 1e-12);
    tu_near(f.rate, 1000.0, 1e-6);
    tu_near(f.duration, 3.0, 1e-9);
    tu_near(f.peak_a, 0.1, 1e-4);
    assert_true(f.t_first == 0.0 && f.t_last == 3.0);
    assert_int_equal(sw_gate_check(&f, NULL, NULL, 0), SW_OK);
}

/* One row's time 0.100 -> 900.100: that row is refused, the rest kept. */
static void test_lone_outlier(void **state)
{
    (void)state;
    rig_t r;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rig_open(&r, &sc, defaults);
    for (int i = 0; i < 3000; i++) {
        const double t = i == 100 ? 900.100 : i * 1e-3;
        sw_gate_push(r.g, &(sw_sample_t){.t = t,
                                         .a_max = NAN,
                                         .seq = SW_GATE_NO_SEQ,
                                         .rx = NAN,
                                         .wall = NAN,
                                         .where = i + 2});
    }
    const sw_gate_facts_t f = rig_close(&r);
    assert_int_equal(f.accepted, 2999);
    assert_int_equal(r.L.nrej, 1);
    assert_int_equal(r.L.rej_where[0], 102);
    assert_int_equal(r.L.rej_why[0], SW_GATE_REJ_JUMP);
    assert_int_equal(f.gaps, 0);
    assert_int_equal(r.L.nev, 0);
}

/* A 2 s hole: one gap event, bridged (under max_bridge), every sample
 * kept; a 60 s hole restarts the packages; policy restart always does. */
static void test_gaps(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const double holes[3] = {2.0, 60.0, 2.0};
    for (int k = 0; k < 3; k++) {
        rig_t r;
        sw_gate_opts_t o = defaults;
        if (k == 2)
            o.gap_policy = SW_GAP_RESTART;
        rig_open(&r, &sc, o);
        for (int i = 0; i < 2000; i++) {
            const double t = i * 1e-3 + (i >= 1000 ? holes[k] : 0.0);
            sw_gate_push(r.g, &(sw_sample_t){.t = t,
                                             .a_max = NAN,
                                             .seq = SW_GATE_NO_SEQ,
                                             .rx = NAN,
                                             .wall = NAN,
                                             .where = i});
        }
        const sw_gate_facts_t f = rig_close(&r);
        assert_int_equal(f.accepted, 2000);
        assert_int_equal(f.gaps, 1);
        assert_int_equal(r.L.nev, 1);
        assert_int_equal(r.L.ev[0].kind, SW_GATE_EV_GAP);
        tu_near(r.L.ev[0].span, holes[k] + 1e-3, 1e-9);
        assert_int_equal(r.L.ev[0].where, 1000);
        assert_int_equal(r.L.ev[0].bridged, k == 0);
        assert_int_equal(r.L.ev[0].restarted, k != 0);
        assert_int_equal(r.L.ev[0].incomplete, 0); /* a still bed, a standing crate */
        tu_near(f.gap_total, holes[k] + 1e-3, 1e-9);
    }
}

/* A hole while the crate rocks: the verdict is incomplete. */
static void test_gap_while_rocking(void **state)
{
    (void)state;
    rig_t r;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rig_open(&r, &sc, defaults);
    for (int i = 0; i < 3000; i++) {
        const double t = i * 1e-3 + (i >= 300 ? 2.0 : 0.0);
        const double a = t < M_PI / 8.0 ? -6.0 * sin(8.0 * t) : 0.0;
        sw_gate_push(r.g, &(sw_sample_t){.t = t,
                                         .a_g = a,
                                         .a_max = NAN,
                                         .seq = SW_GATE_NO_SEQ,
                                         .rx = NAN,
                                         .wall = NAN,
                                         .where = i});
    }
    const sw_gate_facts_t f = rig_close(&r);
    assert_int_equal(f.incomplete, 1);
    tu_near(f.first_incomplete, 0.299, 1e-9);
}

/* A log appended to itself: time goes back; after the stream confirms it,
 * a restart, and every sample is kept. */
static void test_log_twice(void **state)
{
    (void)state;
    rig_t r;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    rig_open(&r, &sc, defaults);
    for (int i = 0; i < 2000; i++)
        sw_gate_push(r.g, &(sw_sample_t){.t = (i % 1000) * 1e-3,
                                         .a_max = NAN,
                                         .seq = SW_GATE_NO_SEQ,
                                         .rx = NAN,
                                         .wall = NAN,
                                         .where = i});
    const double t_end = sw_engine_time(r.e);
    const sw_gate_facts_t f = rig_close(&r);
    assert_int_equal(f.accepted, 2000);
    assert_int_equal(f.restarts, 1);
    assert_int_equal(r.L.nev, 1);
    assert_int_equal(r.L.ev[0].kind, SW_GATE_EV_RESTART);
    assert_true(r.L.ev[0].restarted);
    assert_int_equal(r.L.ev[0].where, 1000);
    assert_true(t_end > 1.9); /* the engine's clock went on */
}

/* Live, with receive times: samples stamped a year ahead, two in a row,
 * then one every 9.5 s, are refused; every genuine sample is kept. */
static void test_forged_times(void **state)
{
    (void)state;
    rig_t r;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    sw_gate_opts_t o = defaults;
    o.gap = 0.1;
    rig_open(&r, &sc, o);
    long genuine = 0, forged = 0;
    for (int i = 0; i < 30000; i++) {
        const double t = 1.7e9 + i * 1e-3, rx = 100.0 + i * 1e-3;
        sw_sample_t s = {.t = t, .a_max = NAN, .seq = i, .rx = rx, .wall = NAN, .where = i};
        sw_gate_push(r.g, &s);
        genuine++;
        if (i == 5000 || i == 5001 || (i > 6000 && i % 9500 == 0)) {
            s.t = i == 5000 || i == 5001 ? t + 3.15e7 + i * 1e-3 : t + 9.5;
            s.where = -i;
            sw_gate_push(r.g, &s);
            forged++;
        }
    }
    const sw_gate_facts_t f = rig_close(&r);
    assert_int_equal(f.accepted, genuine);
    assert_int_equal(sw_gate_rejected(&f), forged);
    for (int k = 0; k < r.L.nrej && k < MAXEV; k++) assert_true(r.L.rej_where[k] < 0);
    assert_int_equal(f.gaps, 0);
}

/* Live: the sensor's clock steps an hour ahead (little real time passes),
 * later its time goes back to 0 (a restart with an unsynchronised clock):
 * each is reported, the motion goes on, every sample is kept. */
static void test_clock_steps(void **state)
{
    (void)state;
    rig_t r;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    sw_gate_opts_t o = defaults;
    o.gap = 0.1;
    rig_open(&r, &sc, o);
    for (int i = 0; i < 6000; i++) {
        double t = 1000.0 + i * 1e-3;
        if (i >= 2000)
            t += 3600.0;
        if (i >= 4000)
            t = (i - 4000) * 1e-3;
        sw_gate_push(r.g, &(sw_sample_t){.t = t,
                                         .a_max = NAN,
                                         .seq = i >= 4000 ? i - 4000 : i,
                                         .rx = 50.0 + i * 1e-3,
                                         .wall = NAN,
                                         .where = i});
    }
    const double t_end = sw_engine_time(r.e);
    const sw_gate_facts_t f = rig_close(&r);
    assert_int_equal(f.accepted, 6000);
    assert_int_equal(f.clock_steps, 1);
    assert_int_equal(f.restarts, 1);
    assert_int_equal(f.seq_restarts, 1);
    assert_int_equal(f.gaps, 0);
    int steps = 0, restarts = 0;
    for (int k = 0; k < r.L.nev; k++) {
        if (r.L.ev[k].kind == SW_GATE_EV_CLOCK_STEP) {
            steps++;
            tu_near(r.L.ev[k].span, 3600.0, 1e-6);
            assert_false(r.L.ev[k].restarted);
        }
        if (r.L.ev[k].kind == SW_GATE_EV_RESTART) {
            restarts++;
            assert_false(r.L.ev[k].restarted); /* no real time passed: the motion goes on */
        }
    }
    assert_int_equal(steps, 1);
    assert_int_equal(restarts, 1);
    /* the engine's clock moved by the time that really passed: 6 s */
    tu_near(t_end - f.t_first, 5.999, 1e-6);
}

/* Spikes, non-finite values, int64 extremes of seq and coarse times. */
static void test_hostile_values(void **state)
{
    (void)state;
    rig_t r;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rig_open(&r, &sc, defaults);
    for (int i = 0; i < 1000; i++) {
        sw_sample_t s = sample(i * 1e-3, 0.0, i);
        if (i >= 500 && i < 510)
            s.a_g = -900.0; /* a 10 ms glitch */
        if (i == 600)
            s.a_z = NAN;
        s.seq = i == 700 ? INT64_MAX : i == 701 ? INT64_MIN : i;
        sw_gate_push(r.g, &s);
    }
    sw_gate_push(r.g, &(sw_sample_t){.t = (double)INT64_MIN / 1e6,
                                     .a_max = NAN,
                                     .seq = SW_GATE_NO_SEQ,
                                     .rx = NAN,
                                     .wall = NAN,
                                     .where = 2000});
    sw_gate_push(r.g, &(sw_sample_t){.t = 1e300,
                                     .a_max = NAN,
                                     .seq = SW_GATE_NO_SEQ,
                                     .rx = NAN,
                                     .wall = NAN,
                                     .where = 2001});
    const sw_gate_facts_t f = rig_close(&r);
    assert_int_equal(f.rejected[SW_GATE_REJ_IMPLAUSIBLE], 10);
    assert_int_equal(f.rejected[SW_GATE_REJ_NONFINITE], 1);
    assert_int_equal(f.rejected[SW_GATE_REJ_TIME], 2);
    assert_true(f.lost >= 0 && f.lost < 1000);
    assert_true(f.peak_a == 0.0);
}

/* A vertical accelerometer reads +1 g at rest: counted once, not twice. */
static void test_vertical_gravity(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    sw_derived_t d;
    sw_scene_validate(&sc, &d, NULL, NULL, NULL);
    const double brake = -1.5 * sc.g * tan(d.alpha); /* lifts on a bed under 1 g only */
    for (int with = 0; with < 2; with++) {
        rig_t r;
        sw_gate_opts_t o = defaults;
        o.vert_gravity = with;
        rig_open(&r, &sc, o);
        for (int i = 0; i < 500; i++) {
            sw_sample_t s = sample(i * 1e-3, i > 100 ? brake : 0.0, i);
            s.a_z = 9.80665;
            sw_gate_push(r.g, &s);
        }
        sw_summary_t sum;
        sw_engine_summary(r.e, 0, &sum);
        const sw_gate_facts_t f = rig_close(&r);
        tu_near(f.mean_z, 9.80665, 1e-9);
        assert_int_equal(sum.uplifts > 0, with);
    }
}

static void test_plausibility(void **state)
{
    (void)state;
    char why[256];
    sw_gate_facts_t f;
    memset(&f, 0, sizeof f);
    f.received = 1000;
    f.accepted = 1000;
    f.dt_median = 1e-3;
    f.rate = 1000.0;
    f.duration = 1.0;
    f.peak_a = 5.0;
    assert_int_equal(sw_gate_check(&f, NULL, why, sizeof why), SW_OK);
    f.rejected[SW_GATE_REJ_LATE] = 11; /* 1.1 % */
    assert_int_equal(sw_gate_check(&f, NULL, why, sizeof why), SW_GATE_REFUSE);
    assert_non_null(strstr(why, "refused"));
    sw_gate_limits_t lim = {.max_rejected = 0.05};
    assert_int_equal(sw_gate_check(&f, &lim, why, sizeof why), SW_OK);
    f.rejected[SW_GATE_REJ_LATE] = 0;
    f.dt_median = 1.0; /* a 1 kHz log with its ms read as seconds */
    f.rate = 1.0 / 1.0 - 1e-9;
    assert_int_equal(sw_gate_check(&f, NULL, why, sizeof why), SW_GATE_REFUSE);
    assert_non_null(strstr(why, "ms or us"));
    f.dt_median = 1.0 / 12.0; /* a 12 Hz CAN log: read, with a warning */
    f.rate = 12.0;
    assert_int_equal(sw_gate_check(&f, NULL, why, sizeof why), SW_GATE_WARN);
    f.rate = 1000.0;
    f.peak_a = 2000.0 * 9.80665; /* "Time (ms)" read as acceleration */
    assert_int_equal(sw_gate_check(&f, NULL, why, sizeof why), SW_GATE_REFUSE);
    f.peak_a = 5.0;
    f.duration = 3.0 * 365 * 86400;
    assert_int_equal(sw_gate_check(&f, NULL, why, sizeof why), SW_GATE_REFUSE);
}

/* A longitudinal channel that is no acceleration: gravity (a vertical axis
 * chosen as longitudinal, 1 g for two minutes), a GPS column read as g
 * (a constant 10), a channel that never moves; refused with the reason and
 * the options, the counts exact.  A real drive of two minutes with a hard
 * braking (0.7 g for 3 s), and a one-minute log that is never off, are
 * not; nor is 1 g for ten seconds (a minute is the rule's span). */
static int still_verdict(double seconds, double (*a)(double t), char *why, size_t whylen)
{
    rig_t r;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rig_open(&r, &sc, defaults);
    const long n = (long)(seconds * 100.0);
    for (long i = 0; i <= n; i++)
        sw_gate_push(r.g, &(sw_sample_t){.t = i * 0.01,
                                         .a_g = a(i * 0.01),
                                         .a_max = NAN,
                                         .seq = SW_GATE_NO_SEQ,
                                         .rx = NAN,
                                         .wall = NAN,
                                         .where = i});
    const sw_gate_facts_t f = rig_close(&r);
    assert_int_equal(f.received, n + 1);
    assert_int_equal(f.accepted, n + 1);
    return sw_gate_check(&f, NULL, why, whylen);
}

static double gravity(double t)
{
    return 9.80665 + 0.2 * sin(37.0 * t) + 0.05 * sin(211.0 * t);
}

static double gps_as_g(double t)
{
    (void)t;
    return 10.0 * 9.80665; /* "Longitude (Degrees)" read as g */
}

static double stuck(double t)
{
    (void)t;
    return 0.0490333; /* 0.005 g, never a change */
}

static double drive(double t)
{
    const double brake = t > 60.0 && t < 63.0 ? -0.7 * 9.80665 : 0.0;
    return brake + 0.5 * sin(13.0 * t) + 0.2 * sin(71.0 * t);
}

static void test_plausibility_still(void **state)
{
    (void)state;
    char why[400];
    assert_int_equal(still_verdict(120.0, gravity, why, sizeof why), SW_GATE_REFUSE);
    assert_non_null(strstr(why, "looks like gravity or not an acceleration"));
    assert_non_null(strstr(why, "the column or axis of the longitudinal acceleration"));
    /* the library names no command-line option: the caller says --force once */
    assert_null(strstr(why, "--"));
    assert_int_equal(still_verdict(120.0, gps_as_g, why, sizeof why), SW_GATE_REFUSE);
    assert_non_null(strstr(why, "looks like gravity or not an acceleration"));
    assert_int_equal(still_verdict(120.0, stuck, why, sizeof why), SW_GATE_REFUSE);
    assert_non_null(strstr(why, "never varies"));
    assert_int_equal(still_verdict(120.0, drive, why, sizeof why), SW_OK);
    assert_int_equal(still_verdict(60.0, drive, why, sizeof why), SW_OK);
    assert_int_equal(still_verdict(10.0, gravity, why, sizeof why), SW_OK);
}

/* ---- what the engine got, recorded (on_take) ---------------------------- */

#define TAKE_MAX 8000
typedef struct {
    double t[TAKE_MAX], ag[TAKE_MAX], az[TAKE_MAX];
    int restart[TAKE_MAX];
    int n;
} takes_t;

static void on_take(void *user, double t, double a_g, double a_z, int restart)
{
    takes_t *k = user;
    assert_true(k->n < TAKE_MAX);
    k->t[k->n] = t;
    k->ag[k->n] = a_g;
    k->az[k->n] = a_z;
    k->restart[k->n++] = restart;
}

/* A stream with a corrupt time, a spike, a bridged hole, a long hole
 * (restart) and the log played twice (restart), rocking a frame and
 * lifting a crate: the samples the gate reports, pushed into a fresh
 * engine with a restart where it says so, give the same summary to the
 * last bit as the engine the gate fed. */
static void test_takes_replay(void **state)
{
    (void)state;
    static takes_t k;
    k.n = 0;
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 5.59, 0.1)};
    sw_engine_t *e = sw_engine_create(sc, 2, &(sw_engine_opts_t){0}, NULL, NULL, 0);
    assert_non_null(e);
    sw_gate_opts_t o = {.on_take = on_take, .user = &k, .vert_gravity = 1};
    char msg[128];
    sw_gate_t *g = sw_gate_create(e, &o, msg, sizeof msg);
    assert_non_null(g);
    for (int i = 0; i < 6000; i++) {
        const int j = i % 3000; /* played twice */
        double t = j * 1e-3 + (j >= 1000 ? 0.5 : 0.0) + (j >= 2000 ? 30.0 : 0.0);
        if (j == 1500)
            t += 700.0; /* a corrupt time */
        const double a = -5.0 * sin(6.0 * j * 1e-3) + (j == 800 ? 900.0 : 0.0);
        const sw_sample_t s = {.t = t,
                               .a_g = a,
                               .a_z = 9.80665 + 0.5 * cos(j * 1e-2),
                               .a_max = NAN,
                               .seq = SW_GATE_NO_SEQ,
                               .rx = NAN,
                               .wall = NAN,
                               .where = i};
        sw_gate_push(g, &s);
    }
    sw_gate_flush(g);
    sw_gate_facts_t f;
    sw_gate_facts(g, &f);
    assert_int_equal(k.n, f.accepted);
    assert_int_equal(f.accepted + sw_gate_rejected(&f), 6000);
    assert_true(f.restarts + f.gaps >= 3);
    int restarts = 0;
    for (int i = 0; i < k.n; i++) restarts += k.restart[i];
    assert_true(restarts >= 2); /* the long hole and the second playing */
    assert_int_equal(k.restart[0], 0);

    sw_engine_t *e2 = sw_engine_create(sc, 2, &(sw_engine_opts_t){0}, NULL, NULL, 0);
    for (int i = 0; i < k.n; i++) {
        if (k.restart[i])
            sw_engine_restart(e2);
        assert_true(sw_engine_push(e2, k.t[i], k.ag[i], k.az[i]) >= 0);
    }
    for (size_t p = 0; p < 2; p++) {
        sw_summary_t a, b;
        sw_engine_summary(e, p, &a);
        sw_engine_summary(e2, p, &b);
        assert_true(a.uplifts > 0);
        assert_int_equal(a.uplifts, b.uplifts);
        assert_int_equal(a.impacts, b.impacts);
        assert_int_equal(a.steps, b.steps);
        assert_memory_equal(&a.max_abs_theta, &b.max_abs_theta, sizeof(double));
        assert_memory_equal(&a.min_margin, &b.min_margin, sizeof(double));
        sw_output_t oa, ob;
        sw_engine_get_output(e, p, &oa);
        sw_engine_get_output(e2, p, &ob);
        assert_memory_equal(&oa.state, &ob.state, sizeof oa.state);
    }
    sw_engine_destroy(e2);
    sw_gate_destroy(g);
    sw_engine_destroy(e);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clean),
        cmocka_unit_test(test_lone_outlier),
        cmocka_unit_test(test_gaps),
        cmocka_unit_test(test_gap_while_rocking),
        cmocka_unit_test(test_log_twice),
        cmocka_unit_test(test_forged_times),
        cmocka_unit_test(test_clock_steps),
        cmocka_unit_test(test_hostile_values),
        cmocka_unit_test(test_vertical_gravity),
        cmocka_unit_test(test_plausibility),
        cmocka_unit_test(test_plausibility_still),
        cmocka_unit_test(test_takes_replay),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
