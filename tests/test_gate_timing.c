/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_gate_timing.c - properties of the gate's timing model (gate.h,
 * docs/timing.md), on timings drawn at random from a seeded generator,
 * many seeds each:
 *   - honest timings (jitter up to +-50 %, Poisson, 1 kHz bursts in a
 *     10 Hz log, merged frames of several CAN IDs, rate changes, FIFO
 *     reads stamped in batches, whole-ms stamps at 1600 Hz), read as a
 *     log (look-ahead) and as a live stream (receive times): no sample
 *     refused, no gap event, every repeated stamp spread and said;
 *   - hostile timings: rows far ahead in runs of 1 to 8, intervals that
 *     grow geometrically, chains far apart: the work per sample (engine
 *     steps of a cushion, whose cost grows with the time it integrates)
 *     stays below that of max_bridge, and every genuine row is kept;
 *   - forged samples interleaved with a genuine stream at 1:1 to 1:8
 *     (ahead, behind, on the genuine times, a year ahead; seq copied,
 *     next, random): either every genuine sample is taken and no forged
 *     one, or the gate declares the input contested.
 * Truth is known by construction; nothing here is the program's output. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "swaywatch/gate.h"
#include "testutil.h"

#define NMAX 40000
#define SEEDS 40

/* ---- a seeded generator (splitmix64) ---------------------------------------- */

static uint64_t rng_state;

static uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static double uni(void) /* [0, 1) */
{
    return (double)(rng_next() >> 11) * 0x1.0p-53;
}

static double uni_in(double a, double b)
{
    return a + (b - a) * uni();
}

static double expo(double mean)
{
    return -mean * log1p(-uni());
}

/* ---- timings ---------------------------------------------------------------------- */

typedef struct {
    double t[NMAX];  /* s, the stamps in the order written */
    double rx[NMAX]; /* s, when each arrived (live) */
    int n;
    double unit; /* s: stamps are whole units (reconstruction expected), 0 none */
} timing_t;

static void add(timing_t *T, double t)
{
    if (T->n < NMAX)
        T->t[T->n++] = t;
}

/* jitter up to +-50 % around a rate of 5 Hz .. 2 kHz */
static void gen_jitter(timing_t *T)
{
    const double p = 1.0 / uni_in(5.0, 2000.0), jit = uni_in(0.0, 0.5);
    double t = 0.0;
    while (T->n < NMAX && t < 120.0) {
        add(T, t);
        t += p * (1.0 + uni_in(-jit, jit));
    }
}

static void gen_poisson(timing_t *T)
{
    const double rate = uni_in(20.0, 2000.0);
    double t = 0.0;
    while (T->n < NMAX && t < 120.0) {
        add(T, t);
        t += 1e-6 + expo(1.0 / rate);
    }
}

/* a 10 Hz log with 1 kHz bursts of 20 ms to 0.6 s (triggered recording) */
static void gen_bursts(timing_t *T)
{
    double t = 0.0;
    const double base = uni_in(0.08, 0.12), busy = uni_in(0.05, 0.6);
    while (T->n < NMAX && t < 300.0) {
        if (uni() < busy) {
            const double end = t + uni_in(0.02, 0.6);
            for (; t < end && T->n < NMAX; t += 1e-3 * (1.0 + uni_in(-0.05, 0.05))) add(T, t);
        }
        add(T, t);
        t += base * (1.0 + uni_in(-0.1, 0.1));
    }
}

/* CAN frames of 2 to 5 IDs merged (the 10 Hz acceleration frame among
 * them), each periodic with its own jitter and phase; two frames at the
 * same microsecond are one row after the other, a microsecond apart */
static void gen_can(timing_t *T)
{
    static const double periods[] = {0.005, 0.01, 0.02, 0.025, 0.05, 0.1};
    const int ids = 2 + (int)(uni() * 4.0);
    double next[6], per[6];
    per[0] = 0.1;
    next[0] = uni_in(0.0, 0.1);
    for (int i = 1; i < ids; i++) {
        per[i] = periods[(int)(uni() * 6.0)];
        next[i] = uni_in(0.0, per[i]);
    }
    double last = -1.0;
    while (T->n < NMAX && last < 200.0) {
        int k = 0;
        for (int i = 1; i < ids; i++)
            if (next[i] < next[k])
                k = i;
        double t = round(next[k] * 1e6) / 1e6;
        if (t <= last)
            t = last + 1e-6;
        add(T, t);
        last = t;
        next[k] += per[k] * (1.0 + uni_in(-0.1, 0.1));
    }
}

/* stretches of 2 to 20 s at rates of 5 Hz to 2 kHz, each +-20 % jitter */
static void gen_rate_changes(timing_t *T, double max_ratio)
{
    double t = 0.0, rate = uni_in(5.0, 2000.0);
    while (T->n < NMAX && t < 300.0) {
        const double end = t + uni_in(2.0, 20.0);
        for (; t < end && T->n < NMAX; t += (1.0 + uni_in(-0.2, 0.2)) / rate) add(T, t);
        double r;
        do r = uni_in(5.0, 2000.0);
        while (r / rate > max_ratio || rate / r > max_ratio);
        rate = r;
    }
}

/* an IMU sampling at 200 Hz .. 1 kHz, its FIFO read every 8 to 32 samples:
 * each sample stamped when read, a few microseconds apart */
static void gen_fifo(timing_t *T)
{
    const double p = 1.0 / uni_in(200.0, 1000.0);
    const int batch = 8 + (int)(uni() * 25.0);
    double t = 0.0;
    while (T->n < NMAX && t < 120.0) {
        const double read = t + batch * p * (1.0 + uni_in(-0.2, 0.2));
        double x = read;
        for (int i = 0; i < batch; i++, x += uni_in(2e-6, 8e-6)) add(T, x);
        t = read;
    }
}

/* 1600 Hz with +-5 % jitter, the times written in whole milliseconds */
static void gen_whole_ms(timing_t *T)
{
    double t = uni_in(0.0, 1.0);
    while (T->n < NMAX && t < 20.0) {
        add(T, floor(t * 1000.0) / 1000.0);
        t += (1.0 + uni_in(-0.05, 0.05)) / 1600.0;
    }
    T->unit = 1e-3;
}

/* Arrival times: the stamp plus a latency of 0.1 ms to a few ms (rarely a
 * stall of 20 ms), never before the one sent before (one link, in order);
 * FIFO batches arrive together when read. */
static void arrivals(timing_t *T, int batched)
{
    double last = -INFINITY;
    for (int i = 0; i < T->n; i++) {
        double rx = T->t[i] + 1e-4 + expo(3e-4) + (uni() < 0.002 ? 0.02 : 0.0);
        if (batched)
            rx = T->t[i] + 2e-4;
        if (rx < last)
            rx = last;
        last = rx;
        T->rx[i] = 100.0 + rx;
    }
}

/* ---- a gate on a quiet bed ------------------------------------------------------- */

typedef struct {
    long refused, refused_genuine, refused_forged;
    long gaps, reconstruct, contested, other_events;
    long first_refused_where;
    sw_gate_reject first_reason;
} seen_t;

static void on_event(void *user, const sw_gate_event_t *ev)
{
    seen_t *s = user;
    switch (ev->kind) {
        case SW_GATE_EV_GAP: s->gaps++; break;
        case SW_GATE_EV_RECONSTRUCT: s->reconstruct++; break;
        case SW_GATE_EV_CONTESTED: s->contested++; break;
        default: s->other_events++; break;
    }
}

static void on_reject(void *user, const sw_sample_t *smp, sw_gate_reject r, const char *text)
{
    seen_t *s = user;
    (void)text;
    if (s->refused == 0) {
        s->first_refused_where = smp->where;
        s->first_reason = r;
    }
    s->refused++;
    if (smp->where < 0)
        s->refused_forged++;
    else
        s->refused_genuine++;
}

static sw_sample_t sample_at(double t, double rx, long i)
{
    return (sw_sample_t){.t = t,
                         .a_g = 0.05 * sin(3.0 * t),
                         .a_max = NAN,
                         .seq = i,
                         .rx = rx,
                         .wall = NAN,
                         .where = i};
}

/* Runs timing T through a gate (live: with receive times) and returns what
 * it saw; the accounting must hold. */
static seen_t run(const timing_t *T, int live, sw_gate_facts_t *facts)
{
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    sw_engine_t *e = tu_engine(&sc, NULL, 0.0, NULL);
    assert_non_null(e);
    seen_t s;
    memset(&s, 0, sizeof s);
    sw_gate_opts_t o = {.on_event = on_event, .on_reject = on_reject, .user = &s};
    sw_gate_t *g = sw_gate_create(e, &o, NULL, 0);
    assert_non_null(g);
    for (int i = 0; i < T->n; i++) {
        sw_sample_t x = sample_at(T->t[i], live ? T->rx[i] : NAN, i);
        if (!live)
            x.seq = SW_GATE_NO_SEQ;
        sw_gate_push(g, &x);
    }
    sw_gate_flush(g);
    sw_gate_facts(g, facts);
    assert_int_equal(facts->received, T->n);
    assert_int_equal(facts->received, facts->accepted + sw_gate_rejected(facts));
    assert_int_equal(facts->held, 0);
    sw_gate_destroy(g);
    sw_engine_destroy(e);
    return s;
}

static void expect_honest(const timing_t *T, int live, const char *what, uint64_t seed)
{
    sw_gate_facts_t f;
    const seen_t s = run(T, live, &f);
    const char *only = getenv("SW_TIMING_DUMP_WHAT");
    if ((s.refused || s.gaps || s.contested) && getenv("SW_TIMING_DUMP") &&
        (!only || strstr(what, only))) {
        FILE *d = fopen(getenv("SW_TIMING_DUMP"), "w");
        for (int i = 0; d && i < T->n; i++) fprintf(d, "%.9f %.9f\n", T->t[i], T->rx[i]);
        if (d)
            fclose(d);
    }
    if (s.refused || s.gaps || s.contested)
        fail_msg("%s (%s, seed %llu): %ld refused (first: line %ld, %s), %ld gaps, %ld contested",
                 what, live ? "live" : "log", (unsigned long long)seed, s.refused,
                 s.first_refused_where, sw_gate_reject_name(s.first_reason), s.gaps, s.contested);
    if (T->unit > 0.0 && !live) {
        assert_int_equal(s.reconstruct, 1);
        assert_true(f.reconstructed > 0);
        tu_near(f.stamp_unit, T->unit, 1e-12);
    } else {
        assert_int_equal(s.reconstruct, 0);
    }
}

typedef void (*gen_fn)(timing_t *T);

static void honest(gen_fn gen, const char *what, int live, int batched)
{
    static timing_t T;
    for (uint64_t seed = 1; seed <= SEEDS; seed++) {
        rng_state = seed * 7919;
        memset(&T, 0, sizeof T);
        gen(&T);
        if (live)
            arrivals(&T, batched);
        expect_honest(&T, live, what, seed);
    }
}

static void test_honest_jitter(void **state)
{
    (void)state;
    honest(gen_jitter, "jitter", 0, 0);
    honest(gen_jitter, "jitter", 1, 0);
}

static void test_honest_poisson(void **state)
{
    (void)state;
    honest(gen_poisson, "poisson", 0, 0);
    honest(gen_poisson, "poisson", 1, 0);
}

static void test_honest_bursts(void **state)
{
    (void)state;
    honest(gen_bursts, "bursts", 0, 0);
    honest(gen_bursts, "bursts", 1, 0);
}

/* A storm of outages live: a 1 kHz sensor whose link drops 0.3 s after
 * every 20 samples, 60 times, from 0.5 s into the stream.  The outages
 * recur, but each lies among fast samples: no stretch of the stream runs
 * at their pace, so none becomes the pace, and every one is a gap (the
 * first ones said two seconds in, when a live stream's pace is known). */
static void test_outage_storm_live(void **state)
{
    (void)state;
    static timing_t T;
    memset(&T, 0, sizeof T);
    rng_state = 4242;
    double t = 0.0;
    for (int i = 0; i < 500; i++, t += 1e-3) add(&T, t);
    for (int k = 0; k < 60; k++) {
        t += 0.3 - 1e-3;
        for (int i = 0; i < 100; i++, t += 1e-3) add(&T, t);
    }
    arrivals(&T, 0);
    sw_gate_facts_t f;
    const seen_t s = run(&T, 1, &f);
    assert_int_equal(s.refused, 0);
    assert_int_equal(s.gaps, 60);
    assert_int_equal(f.gaps, 60);
}

static void test_honest_can(void **state)
{
    (void)state;
    honest(gen_can, "merged CAN frames", 0, 0);
    honest(gen_can, "merged CAN frames", 1, 0);
}

static void gen_rate_any(timing_t *T)
{
    gen_rate_changes(T, INFINITY);
}

static void gen_rate_5(timing_t *T)
{
    gen_rate_changes(T, 5.0);
}

static void test_honest_rate_changes(void **state)
{
    (void)state;
    honest(gen_rate_any, "rate changes", 0, 0);
    /* live, no look-ahead: a rate that drops more than tenfold is a gap
     * until the recent intervals show the new pace (docs/timing.md) */
    honest(gen_rate_5, "rate changes by up to 5x", 1, 0);
}

static void test_honest_fifo(void **state)
{
    (void)state;
    honest(gen_fifo, "FIFO batches", 0, 0);
    honest(gen_fifo, "FIFO batches", 1, 1);
}

static void test_honest_whole_ms(void **state)
{
    (void)state;
    honest(gen_whole_ms, "whole ms at 1600 Hz", 0, 0);
}

/* Whole-ms stamps at 1600 Hz: the spread times are those of a 1600 Hz
 * logger to within a millisecond, and increase. */
static void on_take_t(void *user, double t, double a_g, double a_z, int restart)
{
    (void)a_g;
    (void)a_z;
    (void)restart;
    double *last = user;
    assert_true(t > last[0]);
    last[0] = t;
    last[1] += 1.0;
}

static void test_whole_ms_spread(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    sw_engine_t *e = tu_engine(&sc, NULL, 0.0, NULL);
    double last[2] = {-INFINITY, 0.0};
    sw_gate_opts_t o = {.on_take = on_take_t, .user = last};
    sw_gate_t *g = sw_gate_create(e, &o, NULL, 0);
    for (int i = 0; i < 16000; i++) {
        const double t = floor(i / 1.6) / 1000.0; /* whole ms of sample i at 1600 Hz */
        sw_sample_t x = sample_at(t, NAN, i);
        x.seq = SW_GATE_NO_SEQ;
        sw_gate_push(g, &x);
    }
    sw_gate_flush(g);
    sw_gate_facts_t f;
    sw_gate_facts(g, &f);
    assert_int_equal(f.accepted, 16000);
    assert_int_equal((long)last[1], 16000);
    assert_int_equal(f.reconstructed, 16000 - 10000); /* 10 s: 10000 distinct stamps */
    /* 1600 Hz: the end within a millisecond of 9.999375 s, and the mean
     * rate that of the logger */
    assert_true(fabs(f.t_last - 9.999375) < 1e-3);
    tu_near((double)(f.accepted - 1) / (f.t_last - f.t_first), 1600.0, 0.01 * 1600.0);
    sw_gate_destroy(g);
    sw_engine_destroy(e);
}

/* ---- hostile timings: the work per sample is bounded ------------------------------ */

/* Engine steps of a cushion (stepped at every instant, its cost grows with
 * the time integrated) for the times t[] of a log (rx NAN) or a stream. */
static long steps_of(const double *t, const double *rx, const char *forged, int n,
                     double max_bridge, seen_t *s)
{
    const sw_scene_t sc = tu_cushion(tu_bare(2.0, 0.728), 44.7, 0.05);
    sw_engine_t *e = tu_engine(&sc, NULL, 0.0, NULL);
    assert_non_null(e);
    memset(s, 0, sizeof *s);
    sw_gate_opts_t o = {
        .on_event = on_event, .on_reject = on_reject, .user = s, .max_bridge = max_bridge};
    sw_gate_t *g = sw_gate_create(e, &o, NULL, 0);
    for (int i = 0; i < n; i++) {
        sw_sample_t x = sample_at(t[i], rx ? rx[i] : NAN, forged && forged[i] ? -i : i);
        sw_gate_push(g, &x);
    }
    sw_gate_flush(g);
    sw_summary_t sum;
    sw_engine_summary(e, 0, &sum);
    sw_gate_destroy(g);
    sw_engine_destroy(e);
    return sum.steps;
}

/* the cost of integrating one second of input */
static long steps_per_second(void)
{
    static double t[1001];
    for (int i = 0; i <= 1000; i++) t[i] = i * 1e-3;
    seen_t s;
    return steps_of(t, NULL, NULL, 1001, 10.0, &s);
}

static void test_hostile_geometric(void **state)
{
    (void)state;
    static double t[400], rx[400];
    const long per_s = steps_per_second();
    assert_true(per_s > 100); /* the measure measures something */
    for (uint64_t seed = 1; seed <= 10; seed++) {
        rng_state = seed;
        const double growth = uni_in(1.05, 2.0);
        int n = 0;
        double dt = 1e-3, x = 0.0;
        while (n < 400 && x < 4e9) {
            t[n] = x;
            rx[n] = 50.0 + x; /* live: as if the stream really took that long */
            n++;
            x += dt;
            dt *= growth;
        }
        seen_t s;
        /* a log: each interval costs at most max_bridge (1 s) of integration */
        const long log_steps = steps_of(t, NULL, NULL, n, 1.0, &s);
        assert_true(log_steps <= (long)n * (per_s + 50));
        /* live, every sample arriving at once: nothing leaps ahead of real
         * time by more than a spacing before it is confirmed */
        for (int i = 0; i < n; i++) rx[i] = 50.0 + 1e-6 * i;
        const long live_steps = steps_of(t, rx, NULL, n, 1.0, &s);
        assert_true(live_steps <= (long)n * (per_s + 50));
    }
}

/* Runs of 1 to 8 rows far ahead (50 ms to 1e8 s) in a 1 kHz log: refused,
 * every genuine row kept, and the cost that of the genuine rows. */
static void test_hostile_far_rows(void **state)
{
    (void)state;
    static double t[12000];
    static char mark[12000];
    const long per_s = steps_per_second();
    static const double leaps[] = {0.05, 10.0, 1e3, 1e6, 1e8};
    for (uint64_t seed = 1; seed <= 20; seed++) {
        rng_state = seed;
        int n = 0;
        long forged = 0;
        for (int i = 0; i < 10000 && n < 11990; i++) {
            mark[n] = 0;
            t[n++] = i * 1e-3;
            if (uni() < 0.003) {
                const int run = 1 + (int)(uni() * 8.0);
                const double leap = leaps[(int)(uni() * 5.0)];
                for (int k = 0; k < run; k++) {
                    mark[n] = 1;
                    t[n++] = i * 1e-3 + leap + k * 1e-3;
                }
                forged += run;
            }
        }
        seen_t s;
        const long steps = steps_of(t, NULL, mark, n, 10.0, &s);
        assert_int_equal(s.refused_genuine, 0);
        assert_int_equal(s.refused_forged + 0, forged);
        assert_int_equal(s.gaps, 0);
        assert_true(steps <= 11 * per_s); /* 10 s of log, and a margin */
    }
}

/* ---- a monitor the OS stalls (live) ---------------------------------------------- */

/* A 1 kHz sensor (stamps with jitter) received by a monitor that the OS
 * stops now and then: for 50 ms, 200 ms, 1 s or 3 s, at random points,
 * some again soon after (while it drains the last backlog, or just
 * after).  What arrived meanwhile waits in the socket and is read in one
 * burst when the monitor runs again: each sample a few microseconds after
 * the one before, their stamps still 1 ms apart.  With the soak's garbage
 * after some good samples: an out-of-order copy (1 ms before the last
 * good sample) or a duplicate (the same sample again). */
enum { G_NONE, G_LATE, G_DUP };

typedef struct {
    double t[NMAX], rx[NMAX];
    int garbage[NMAX]; /* G_*: the message is garbage of that kind */
    long good[NMAX];   /* its good sample's index (garbage: the one it copies) */
    int n;
    int events; /* the sensor pauses and its clock leaps, while the monitor is stopped */
    long pauses, leaps;
    /* how the monitor reads its backlog when it runs again (D_*), and
     * whether a pause of the sensor skips its seq numbers (its samples
     * unsent: lost) */
    int drain, skip_seq;
    long skipped; /* seq numbers a pause skipped */
} stalled_t;

/* The backlog read in one burst, microseconds apart; with a busy core now
 * and then (the reader waits 0.3 to 3 ms, a sample in 20); slowly as it
 * wakes (its first 5 to 40 samples half a spacing or more apart, then in
 * a burst); in chunks of 30 (a subscription's queue) 0.5 to 2 ms apart. */
enum { D_BURST, D_HICCUPS, D_SLOW_WAKE, D_CHUNKS, D_KINDS };

/* s: the time the reader takes to read the next message of a backlog, the
 * k-th of it (the first: k = 0) */
static double drain_step(const stalled_t *S, long k, long slow)
{
    switch (S->drain) {
        case D_HICCUPS: return uni() < 0.05 ? uni_in(3e-4, 3e-3) : uni_in(1e-6, 5e-6);
        case D_SLOW_WAKE: return k < slow ? uni_in(5e-4, 1e-3) : uni_in(1e-6, 5e-6);
        case D_CHUNKS: return k % 30 == 29 ? uni_in(5e-4, 2e-3) : uni_in(1e-6, 5e-6);
    }
    return uni_in(1e-6, 5e-6);
}

static double stall_end(const double *from, const double *to, int n, double x)
{
    for (int k = 0; k < n; k++)
        if (x >= from[k] && x < to[k])
            return to[k];
    return x;
}

static void gen_stalled(stalled_t *S, int garbage)
{
    static const double lens[] = {0.05, 0.2, 1.0, 3.0};
    double from[24], to[24];
    int ns = 0;
    const double jit = uni_in(0.0, 0.5), dur = 30.0;
    for (double at = uni_in(1.5, 3.0); at < dur - 4.0 && ns < 22; at += uni_in(0.5, 4.0)) {
        from[ns] = 100.0 + at;
        to[ns] = from[ns] + lens[(int)(uni() * 4.0)];
        ns++;
        if (uni() < 0.4) { /* again soon: during the drain or just after it */
            from[ns] = to[ns - 1] + uni_in(1e-4, 0.05);
            to[ns] = from[ns] + lens[(int)(uni() * 4.0)];
            at = to[ns] - 100.0;
            ns++;
        }
    }
    /* the sensor's own events, while the monitor is stopped (their
     * samples after come in the burst): a pause (an honest gap: stamps
     * and real time both leap), or its clock leaping 0.2 s ahead of real
     * time (a clock step, as a sender restarted on a later time does) */
    S->n = S->pauses = S->leaps = S->skipped = 0;
    double t = 0.0, last_rx = -INFINITY, shift = 0.0;
    int next_stall = 0;
    long backlog = 0; /* messages read since the reader woke, while it catches up */
    double last_event = -INFINITY;
    const long slow = S->drain == D_BURST ? 0 : 5 + (long)(uni() * 36.0);
    for (long i = 0; S->n < NMAX - 2 && t < dur; i++) {
        const double lat = 1e-4 + expo(2e-4), live = 100.0 + t + lat + shift;
        const double woke = stall_end(from, to, ns, live);
        double rx;
        if (S->drain == D_BURST) {
            rx = fmax(woke, last_rx + uni_in(1e-6, 5e-6));
        } else {
            /* in a backlog (stopped now, or still catching up): read after
             * the one before, at the reader's pace, never while stopped */
            const int behind = woke > live || last_rx > live;
            backlog = behind ? backlog + 1 : 0;
            rx = behind ? stall_end(from, to, ns,
                                    fmax(woke, last_rx + drain_step(S, backlog - 1, slow)))
                        : fmax(live, last_rx + uni_in(1e-6, 5e-6));
        }
        S->t[S->n] = t;
        S->rx[S->n] = last_rx = rx;
        S->garbage[S->n] = G_NONE;
        S->good[S->n++] = i;
        if (garbage && i > 100 && uni() < 0.03) {
            const int kind = uni() < 0.5 ? G_LATE : G_DUP;
            S->t[S->n] = kind == G_LATE ? t - 1e-3 : t;
            S->rx[S->n] = last_rx = fmax(stall_end(from, to, ns, rx + uni_in(1e-6, 3e-5)),
                                         last_rx + uni_in(1e-6, 5e-6));
            S->garbage[S->n] = kind;
            S->good[S->n++] = i;
        }
        t += 1e-3 * (1.0 + uni_in(-jit, jit));
        if (S->events && next_stall < ns && 100.0 + t + shift >= from[next_stall]) {
            double u = uni();
            /* (with skip_seq, the sensor's events a second apart at least:
             * a clock that steps twice within 256 samples is two timelines
             * taking turns, contested, and a pause hidden in a stall may
             * be said as a step) */
            if (S->skip_seq && t - last_event < 1.0)
                u = 1.0;
            if (u < 0.25) {
                const double p = uni_in(0.2, 1.0);
                t += p;            /* real time passes as much */
                if (S->skip_seq) { /* its samples unsent: their seq numbers skipped */
                    const long k = (long)floor(p / 1e-3);
                    i += k;
                    S->skipped += k;
                }
                S->pauses++;
            } else if (u < 0.5) {
                t += 0.2;
                shift -= 0.2; /* the stamps leap, real time does not */
                S->leaps++;
            }
            if (u < 0.5)
                last_event = t;
            next_stall++;
        }
        while (next_stall < ns && 100.0 + t + shift >= from[next_stall]) next_stall++;
    }
}

typedef struct {
    long genuine, late_ok, dup_ok, wrong;
    long first_wrong;
    sw_gate_reject first_reason;
    const stalled_t *S;
} stall_seen_t;

static void on_reject_stall(void *user, const sw_sample_t *smp, sw_gate_reject r, const char *text)
{
    stall_seen_t *s = user;
    (void)text;
    const int g = smp->where < 0 ? s->S->garbage[-smp->where - 1] : G_NONE;
    if (g == G_LATE && r == SW_GATE_REJ_LATE)
        s->late_ok++;
    else if (g == G_DUP && r == SW_GATE_REJ_DUPLICATE)
        s->dup_ok++;
    else {
        if (s->wrong++ == 0) {
            s->first_wrong = smp->where;
            s->first_reason = r;
        }
        if (g == G_NONE)
            s->genuine++;
    }
}

/* One stalled stream through a gate: every honest sample taken, every
 * garbage message refused under its own reason, every pause said; with
 * skip_seq, the seq numbers a pause skipped counted lost, and none more. */
static void stalls_case(stalled_t *S, int with_seq, int garbage, uint64_t seed)
{
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    gen_stalled(S, garbage);
    sw_engine_t *e = tu_engine(&sc, NULL, 0.0, NULL);
    stall_seen_t s = {.S = S};
    sw_gate_opts_t o = {.on_reject = on_reject_stall, .user = &s};
    sw_gate_t *g = sw_gate_create(e, &o, NULL, 0);
    long nlate = 0, ndup = 0;
    for (int i = 0; i < S->n; i++) {
        sw_sample_t x = sample_at(S->t[i], S->rx[i], S->good[i]);
        x.seq = with_seq ? S->good[i] : SW_GATE_NO_SEQ;
        if (S->garbage[i] != G_NONE) {
            x = sample_at(S->t[i - 1], S->rx[i], S->good[i]); /* the same values */
            x.t = S->t[i];
            x.seq = with_seq ? S->good[i] : SW_GATE_NO_SEQ;
            x.where = -(i + 1);
            nlate += S->garbage[i] == G_LATE;
            ndup += S->garbage[i] == G_DUP;
        }
        sw_gate_push(g, &x);
    }
    sw_gate_flush(g);
    sw_gate_facts_t f;
    sw_gate_facts(g, &f);
    if (s.wrong || s.late_ok != nlate || s.dup_ok != ndup)
        fail_msg(
            "stalls (drain %d, seq %d, garbage %d, events %d, seed %llu): %ld honest "
            "samples refused, %ld refusals under a wrong reason (first: %ld, "
            "%s); late %ld of %ld, duplicate %ld of %ld",
            S->drain, with_seq, garbage, S->events, (unsigned long long)seed, s.genuine, s.wrong,
            s.first_wrong, sw_gate_reject_name(s.first_reason), s.late_ok, nlate, s.dup_ok, ndup);
    assert_int_equal(f.accepted, S->n - nlate - ndup);
    /* no stall alone is a gap or a step; every pause is said.
     * A leap hidden in a stall longer than itself cannot be
     * told from a backlog by receive times (docs/timing.md):
     * said as a gap, a step, or not at all */
    if (S->events ? f.gaps + f.clock_steps < S->pauses ||
                        f.gaps + f.clock_steps > 2 * (S->pauses + S->leaps)
                  : f.gaps + f.clock_steps > 0)
        fail_msg(
            "stalls (drain %d, seq %d, garbage %d, events %d, seed %llu): %ld gaps of "
            "%ld pauses, %ld clock steps of %ld leaps",
            S->drain, with_seq, garbage, S->events, (unsigned long long)seed, f.gaps, S->pauses,
            f.clock_steps, S->leaps);
    assert_int_equal(f.restarts, 0);
    /* one sender, read late: no second timeline, and what its pauses
     * skipped is lost, no more, no less (the garbage's late copies, at
     * 1.5 %, five times the soak's, may pass for a second timeline:
     * docs/timing.md) */
    if (S->skip_seq && !garbage && (f.contests != 0 || (with_seq && f.lost != S->skipped)))
        fail_msg(
            "stalls (drain %d, seq %d, garbage %d, seed %llu): %ld contests, lost %ld "
            "of the %ld seq numbers the pauses skipped",
            S->drain, with_seq, garbage, (unsigned long long)seed, f.contests, f.lost, S->skipped);
    sw_gate_destroy(g);
    sw_engine_destroy(e);
}

static void test_honest_stalls(void **state)
{
    (void)state;
    static stalled_t S;
    for (int variant = 0; variant < 8; variant++)
        for (uint64_t seed = 1; seed <= SEEDS; seed++) {
            rng_state = seed * 104729 + (uint64_t)variant;
            S.events = variant >> 2;
            S.drain = D_BURST;
            S.skip_seq = 0;
            stalls_case(&S, variant & 1, (variant >> 1) & 1, seed);
        }
}

/* The monitor stopped while the sensor pauses or its clock leaps, waking
 * to a backlog it cannot read in one burst (a busy core as it wakes, a
 * queue read in chunks): the samples after the pause are no leap, the
 * pause's seq numbers are lost, and no second timeline is seen. */
static void test_honest_stalls_slow_drain(void **state)
{
    (void)state;
    static stalled_t S;
    for (int drain = D_HICCUPS; drain < D_KINDS; drain++)
        for (int variant = 0; variant < 4; variant++)
            for (uint64_t seed = 1; seed <= SEEDS; seed++) {
                rng_state = seed * 7727 + (uint64_t)(10 * drain + variant);
                S.events = 1;
                S.drain = drain;
                S.skip_seq = 1;
                stalls_case(&S, variant & 1, (variant >> 1) & 1, seed);
            }
}

/* ---- a sender restarted (live) ------------------------------------------------------ */

/* A sender stopped and started again RUNS times, as the soak's publisher
 * is: a pause of 0.3 to 0.35 s of real time, its first sample stamped
 * 0.5 s after its last (a clock that steps ahead of real time by 0.15 to
 * 0.2 s), its seq from 0 again.  Stamped exactly at its rate, each sample
 * sent when due (a few microseconds per send) and received 5 to 20 us
 * later, in order.  What varies (pattern, a bit each): the new sender
 * starts 0.5 to 2 ms late (its first samples overdue, sent back to back);
 * one of its first three sends takes 70 to 400 us (the first send on a
 * new socket, a page fault); the reader waits 0.5 to 6 ms (a busy core)
 * among the last eight samples before the pause, so that the real time in
 * which the stream's samples arrive looks long. */
#define RUNS 5

typedef struct {
    double t[NMAX], rx[NMAX];
    long seq[NMAX];
    int n;
} restarts_t;

static void gen_restarts(restarts_t *R, double rate, int pattern)
{
    const double sp = 1.0 / rate;
    const int per = 1500;
    double t0 = 0.0, w0 = 100.0, last_rx = -INFINITY;
    R->n = 0;
    for (int run = 0; run < RUNS; run++) {
        const double late = run > 0 && (pattern & 1) ? uni_in(5e-4, 2e-3) : 0.0;
        const int slow_at = run > 0 && (pattern & 2) ? 1 + (int)(uni() * 2.0) : -1;
        const int wait_at = run < RUNS - 1 && (pattern & 4) ? per - 1 - (int)(uni() * 8.0) : -1;
        double sent = -INFINITY;
        for (int k = 0; k < per && R->n < NMAX; k++) {
            const double cost = k == slow_at ? uni_in(7e-5, 4e-4) : uni_in(2e-6, 6e-6);
            sent = k == 0 ? w0 : fmax(w0 - late + k * sp, sent + cost);
            double rx = fmax(sent + uni_in(5e-6, 2e-5), last_rx + uni_in(2e-6, 6e-6));
            if (k == wait_at)
                rx += uni_in(5e-4, 6e-3);
            R->t[R->n] = t0 + k * sp;
            R->rx[R->n] = last_rx = rx;
            R->seq[R->n++] = k;
        }
        t0 += (per - 1) * sp + 0.5;
        w0 = last_rx + uni_in(0.3, 0.35);
    }
}

static void test_honest_sender_restarts(void **state)
{
    (void)state;
    static restarts_t R;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    static const double rates[] = {1000.0, 8000.0};
    for (int r = 0; r < 2; r++)
        for (int pattern = 0; pattern < 8; pattern++)
            for (uint64_t seed = 1; seed <= SEEDS; seed++) {
                rng_state = seed * 6151 + (uint64_t)(10 * r + pattern);
                gen_restarts(&R, rates[r], pattern);
                sw_engine_t *e = tu_engine(&sc, NULL, 0.0, NULL);
                seen_t s;
                memset(&s, 0, sizeof s);
                sw_gate_opts_t o = {.on_event = on_event, .on_reject = on_reject, .user = &s};
                sw_gate_t *g = sw_gate_create(e, &o, NULL, 0);
                for (int i = 0; i < R.n; i++) {
                    sw_sample_t x = sample_at(R.t[i], R.rx[i], i);
                    x.seq = R.seq[i];
                    sw_gate_push(g, &x);
                }
                sw_gate_flush(g);
                sw_gate_facts_t f;
                sw_gate_facts(g, &f);
                /* every sample taken; each restart a seq restart and a
                 * step of the clock, said once; one sender, no contest */
                if (s.refused || f.seq_restarts != RUNS - 1 || f.lost != 0 || f.contests != 0 ||
                    f.clock_steps != RUNS - 1)
                    fail_msg(
                        "restarts at %.0f Hz (pattern %d, seed %llu): %ld refused (first: "
                        "%ld, %s), %ld seq restarts, %ld lost, %ld contests, %ld clock "
                        "steps, %ld gaps",
                        rates[r], pattern, (unsigned long long)seed, s.refused,
                        s.first_refused_where, sw_gate_reject_name(s.first_reason), f.seq_restarts,
                        f.lost, f.contests, f.clock_steps, f.gaps);
                sw_gate_destroy(g);
                sw_engine_destroy(e);
            }
}

/* ---- forged samples among genuine ones (live) ------------------------------------- */

enum { F_AHEAD, F_AHEAD_SMALL, F_BEHIND, F_ON_GENUINE, F_YEAR, F_KINDS };
enum { S_COPY, S_NEXT, S_RANDOM, S_NONE, S_KINDS };

static void test_forged_interleaved(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    for (int ratio = 1; ratio <= 8; ratio++)
        for (int kind = 0; kind < F_KINDS; kind++)
            for (int sk = 0; sk < S_KINDS; sk++)
                for (int confirm = 3; confirm <= 8; confirm += 5) {
                    rng_state = (uint64_t)(ratio * 100 + kind * 10 + sk);
                    sw_engine_t *e = tu_engine(&sc, NULL, 0.0, NULL);
                    seen_t s;
                    memset(&s, 0, sizeof s);
                    sw_gate_opts_t o = {.on_event = on_event,
                                        .on_reject = on_reject,
                                        .user = &s,
                                        .confirm = confirm};
                    sw_gate_t *g = sw_gate_create(e, &o, NULL, 0);
                    long nforged = 0;
                    const int start = 500 + (int)(uni() * 200.0);
                    for (int i = 0; i < 4000; i++) {
                        const double t = 1.0 + i * 1e-3, rx = 10.0 + i * 1e-3;
                        sw_sample_t x = sample_at(t, rx, i);
                        x.a_g = -3.0;
                        if (kind == F_ON_GENUINE && i >= start && (i - start) % ratio == 0) {
                            /* sent just before the genuine one, with its time */
                            sw_sample_t f = x;
                            f.a_g = 0.0;
                            f.where = -i;
                            f.rx -= 1e-6;
                            f.seq = sk == S_COPY     ? i
                                    : sk == S_NEXT   ? i + 1
                                    : sk == S_RANDOM ? (int64_t)(rng_next() >> 2)
                                                     : 0;
                            sw_gate_push(g, &f);
                            nforged++;
                        }
                        sw_gate_push(g, &x);
                        if (kind != F_ON_GENUINE && i >= start && (i - start) % ratio == 0) {
                            static const double off[] = {2.5e-3, 0.5e-3, -2.5e-3, 0.0, 3.15e7};
                            sw_sample_t f = x;
                            f.a_g = 0.0;
                            f.where = -i;
                            f.t = t + off[kind];
                            f.seq = sk == S_COPY     ? i
                                    : sk == S_NEXT   ? i + 1
                                    : sk == S_RANDOM ? (int64_t)(rng_next() >> 2)
                                                     : 0;
                            sw_gate_push(g, &f);
                            nforged++;
                        }
                    }
                    sw_gate_flush(g);
                    sw_gate_facts_t f;
                    sw_gate_facts(g, &f);
                    const long forged_taken = nforged - s.refused_forged;
                    const int clean = s.refused_genuine == 0 && forged_taken == 0;
                    /* a second sender at 1:8 or more often is a contest,
                     * said at once, whichever timeline was kept */
                    if (s.contested == 0)
                        fail_msg(
                            "forged %s, seq %d, 1:%d, confirm %d: %ld genuine refused, "
                            "%ld forged taken (clean %d), and not contested",
                            (const char *[]){"ahead", "a little ahead", "behind",
                                             "on the genuine times", "a year ahead"}[kind],
                            sk, ratio, confirm, s.refused_genuine, forged_taken, clean);
                    /* with receive times the genuine timeline is the one
                     * kept when the forger stamps ahead of it or a year on */
                    if ((kind == F_AHEAD || kind == F_YEAR) && !clean)
                        fail_msg("forged %s, seq %d, 1:%d, confirm %d: %ld genuine refused",
                                 kind == F_AHEAD ? "ahead" : "a year ahead", sk, ratio, confirm,
                                 s.refused_genuine);
                    /* seq numbers that do not count are no evidence: with
                     * them a forger that keeps to the genuine order is
                     * taken (docs/timing.md says so) */
                    /* every sample arrived, refused or not: none is
                     * lost by seq */
                    if (f.lost != 0)
                        fail_msg(
                            "forged %s, seq %d, 1:%d, confirm %d: %ld lost by seq, "
                            "%ld genuine refused",
                            (const char *[]){"ahead", "a little ahead", "behind",
                                             "on the genuine times", "a year ahead"}[kind],
                            sk, ratio, confirm, f.lost, s.refused_genuine);
                    sw_gate_destroy(g);
                    sw_engine_destroy(e);
                }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_honest_jitter),
        cmocka_unit_test(test_honest_poisson),
        cmocka_unit_test(test_honest_bursts),
        cmocka_unit_test(test_honest_can),
        cmocka_unit_test(test_honest_rate_changes),
        cmocka_unit_test(test_honest_fifo),
        cmocka_unit_test(test_honest_whole_ms),
        cmocka_unit_test(test_whole_ms_spread),
        cmocka_unit_test(test_hostile_geometric),
        cmocka_unit_test(test_hostile_far_rows),
        cmocka_unit_test(test_forged_interleaved),
        cmocka_unit_test(test_honest_stalls),
        cmocka_unit_test(test_honest_stalls_slow_drain),
        cmocka_unit_test(test_honest_sender_restarts),
        cmocka_unit_test(test_outage_storm_live),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
