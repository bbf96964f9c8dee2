/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_stream.c - stream.h against what it does not compute itself: the
 * same samples through a gate and an engine composed by hand (every
 * state, event, refusal and stream event the same, bit for bit); the
 * bare block's uplift threshold g tan(alpha) (an UPLIFT alarm just above
 * it, none just below), with the alarm's source time the sample's own;
 * the reserve evaluated on a state before the state is reported, at the
 * times the rate alone gives; a forged timeline that brakes hard beside
 * a quiet genuine one raising its alarms through the second engines; a
 * package replaced; NULL and bad options refused; nothing allocated per
 * sample (glibc's allocator counts). */
#include <malloc.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define MAXREC 20000

typedef struct {
    sw_output_t st[MAXREC];
    int nst;
    sw_event_t ev[512];
    int nev;
    long rej_where[512];
    sw_gate_reject rej[512];
    int nrej;
    sw_gate_event_t in[64];
    int nin;
    sw_alarm_t al[512];
    double al_src[512];
    int nal;
    int took;
    /* the reserve seen from the state callback */
    const sw_stream_t *stream;
    int reserve_checked, reserve_fresh;
} rec_t;

static void r_state(void *u, const sw_output_t *o)
{
    rec_t *r = u;
    if (r->stream) {
        /* the reserve was evaluated on this state already, or before it */
        const sw_risk_pkg_t *p = sw_risk_pkg(sw_stream_risk(r->stream), o->pkg);
        assert_non_null(p);
        assert_true(p->reserve_t <= o->t);
        r->reserve_checked++;
        r->reserve_fresh += p->reserve_t == o->t;
    }
    if (r->nst < MAXREC)
        r->st[r->nst++] = *o;
}
static void r_event(void *u, const sw_event_t *e)
{
    rec_t *r = u;
    if (r->nev < 512)
        r->ev[r->nev++] = *e;
}
static void r_reject(void *u, const sw_sample_t *s, sw_gate_reject why, const char *text)
{
    rec_t *r = u;
    assert_non_null(text);
    if (r->nrej < 512) {
        r->rej_where[r->nrej] = s->where;
        r->rej[r->nrej++] = why;
    }
}
static void r_input(void *u, const sw_gate_event_t *ev)
{
    rec_t *r = u;
    if (r->nin < 64)
        r->in[r->nin++] = *ev;
}
static void r_alarm(void *u, const sw_alarm_t *a, double t_source)
{
    rec_t *r = u;
    if (r->nal < 512) {
        r->al_src[r->nal] = t_source;
        r->al[r->nal++] = *a;
    }
}
static void r_take(void *u, double t, double a_g, double a_z, int restart)
{
    (void)t;
    (void)a_g;
    (void)a_z;
    (void)restart;
    ((rec_t *)u)->took++;
}

/* Two events the same, field by field (their padding is anyone's). */
static void same_event(const sw_event_t *x, const sw_event_t *y)
{
    assert_int_equal(x->pkg, y->pkg);
    assert_int_equal(x->kind, y->kind);
    assert_memory_equal(&x->t, &y->t, sizeof x->t);
    assert_memory_equal(&x->theta, &y->theta, sizeof x->theta);
    assert_memory_equal(&x->theta_dot, &y->theta_dot, sizeof x->theta_dot);
    assert_memory_equal(&x->margin, &y->margin, sizeof x->margin);
    assert_memory_equal(&x->info, &y->info, sizeof x->info);
}

static void same_input(const sw_gate_event_t *x, const sw_gate_event_t *y)
{
    assert_int_equal(x->kind, y->kind);
    assert_memory_equal(&x->t, &y->t, sizeof x->t);
    assert_memory_equal(&x->t_engine, &y->t_engine, sizeof x->t_engine);
    assert_memory_equal(&x->span, &y->span, sizeof x->span);
    assert_int_equal(x->restarted, y->restarted);
    assert_int_equal(x->incomplete, y->incomplete);
    assert_int_equal(x->bridged, y->bridged);
    assert_int_equal(x->where, y->where);
}

/* A log's samples (no receive times): a braking half-sine of 7 m/s^2 at
 * 8 rad/s from 0.5 s at 1 kHz, a spike of 900 m/s^2 at 1.0 s, a hole of
 * 0.3 s from 2.0 s; 4 s in all. */
static int log_sample(long k, sw_sample_t *s)
{
    const double t = (double)k / 1000.0;
    if (t > 2.0 && t < 2.3)
        return 0;
    double a = t >= 0.5 && t <= 0.5 + M_PI / 8.0 ? -7.0 * sin(8.0 * (t - 0.5)) : 0.0;
    if (k == 1000)
        a = -900.0;
    *s = (sw_sample_t){.t = t,
                       .a_g = a,
                       .a_max = NAN,
                       .seq = SW_GATE_NO_SEQ,
                       .rx = NAN,
                       .wall = NAN,
                       .where = k + 2};
    return 1;
}

static sw_gate_opts_t log_gate(void)
{
    return (sw_gate_opts_t){.relative = -1, .max_accel = 50 * 9.80665};
}

/* The stream's states, events, refusals and stream events are those of a
 * gate composed by hand in front of an engine. */
static void test_same_as_composed(void **state)
{
    (void)state;
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 5.59, 0.1)};
    rec_t *a = calloc(1, sizeof *a), *b = calloc(1, sizeof *b);
    assert_non_null(a);
    assert_non_null(b);

    sw_stream_opts_t so = {.gate = log_gate(),
                           .risk = {.reserve_rate = -1.0},
                           .hysteresis = -1.0,
                           .on_state = r_state,
                           .on_event = r_event,
                           .on_input = r_input,
                           .on_reject = r_reject,
                           .on_take = r_take,
                           .user = a};
    int err = 0;
    char msg[256] = "";
    sw_stream_t *st = sw_stream_create(sc, 2, &so, &err, msg, sizeof msg);
    assert_non_null(st);
    assert_int_equal(sw_stream_count(st), 2);

    sw_engine_opts_t eo = {.on_state = r_state, .on_event = r_event, .user = b};
    sw_engine_t *e = sw_engine_create(sc, 2, &eo, &err, msg, sizeof msg);
    assert_non_null(e);
    sw_gate_opts_t go = log_gate();
    go.on_event = r_input;
    go.on_reject = r_reject;
    go.on_take = r_take;
    go.user = b;
    sw_gate_t *g = sw_gate_create(e, &go, msg, sizeof msg);
    assert_non_null(g);

    for (long k = 0; k <= 4000; k++) {
        sw_sample_t s;
        if (!log_sample(k, &s))
            continue;
        assert_int_equal(sw_stream_push(st, &s), sw_gate_push(g, &s));
    }
    assert_int_equal(sw_stream_finish(st), sw_gate_flush(g));
    assert_int_equal(sw_stream_settle(st, 5.0), sw_engine_finish(e, 5.0));

    assert_true(a->nst > 2 * 3000);
    assert_int_equal(a->nst, b->nst);
    assert_memory_equal(a->st, b->st, (size_t)a->nst * sizeof a->st[0]);
    assert_true(a->nev > 0);
    assert_int_equal(a->nev, b->nev);
    for (int i = 0; i < a->nev; i++) same_event(&a->ev[i], &b->ev[i]);
    /* the spike refused, with its line */
    assert_int_equal(a->nrej, 1);
    assert_int_equal(b->nrej, 1);
    assert_int_equal(a->rej[0], SW_GATE_REJ_IMPLAUSIBLE);
    assert_int_equal(a->rej_where[0], 1002);
    /* the hole: one gap, at the same place */
    assert_true(a->nin >= 1);
    assert_int_equal(a->nin, b->nin);
    assert_int_equal(a->in[0].kind, SW_GATE_EV_GAP);
    for (int i = 0; i < a->nin; i++) same_input(&a->in[i], &b->in[i]);
    assert_int_equal(a->took, b->took);
    sw_gate_facts_t fa, fb;
    sw_gate_facts(sw_stream_gate(st), &fa);
    sw_gate_facts(g, &fb);
    assert_int_equal(fa.accepted, fb.accepted);
    assert_int_equal(a->took, fa.accepted);
    for (size_t k = 0; k < 2; k++) {
        sw_summary_t x, y;
        assert_int_equal(sw_engine_summary(sw_stream_engine(st), k, &x), SW_OK);
        assert_int_equal(sw_engine_summary(e, k, &y), SW_OK);
        assert_int_equal(x.impacts, y.impacts);
        assert_int_equal(x.overturned, y.overturned);
        assert_memory_equal(&x.max_abs_theta, &y.max_abs_theta, sizeof x.max_abs_theta);
        assert_memory_equal(&x.min_margin, &y.min_margin, sizeof x.min_margin);
        assert_int_equal(x.steps, y.steps);
    }
    sw_gate_destroy(g);
    sw_engine_destroy(e);
    sw_stream_destroy(st);
    free(a);
    free(b);
}

/* Constant braking a from t0 for 1 s at 1 kHz, relative times. */
static rec_t *brake(const sw_scene_t *sc, double a, double t0)
{
    rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    const sw_stream_opts_t so = {.gate = {.relative = 1},
                                 .risk = {.reserve_rate = -1.0},
                                 .hysteresis = -1.0,
                                 .on_alarm = r_alarm,
                                 .user = r};
    char msg[256];
    sw_stream_t *st = sw_stream_create(sc, 1, &so, NULL, msg, sizeof msg);
    assert_non_null(st);
    for (long k = 0; k <= 1000; k++) {
        const sw_sample_t s = {.t = t0 + (double)k / 1000.0,
                               .a_g = a,
                               .a_max = NAN,
                               .seq = SW_GATE_NO_SEQ,
                               .rx = NAN,
                               .wall = NAN};
        sw_stream_push(st, &s);
    }
    sw_stream_finish(st);
    sw_stream_destroy(st);
    return r;
}

static int count_kind(const rec_t *r, sw_alarm_kind k)
{
    int n = 0;
    for (int i = 0; i < r->nal; i++) n += r->al[i].kind == k;
    return n;
}

/* A bare block lifts off under a constant acceleration beyond g tan(alpha)
 * and never below it: an UPLIFT alarm 2 % above, none 2 % below; the
 * alarm's source time is the sample's (the log starts at 1000 s). */
static void test_uplift_alarm_at_threshold(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const double thr = sc.g * 0.728 / 2.0; /* m/s^2, g tan(alpha), tan(alpha) = b/h */
    rec_t *below = brake(&sc, -0.98 * thr, 1000.0);
    assert_int_equal(count_kind(below, SW_ALARM_UPLIFT), 0);
    rec_t *above = brake(&sc, -1.02 * thr, 1000.0);
    assert_int_equal(count_kind(above, SW_ALARM_UPLIFT), 1);
    for (int i = 0; i < above->nal; i++) {
        /* engine time from the first sample, source time from 1000 s */
        tu_near(above->al_src[i] - above->al[i].t, 1000.0, 1e-9);
        assert_true(above->al[i].pkg == 0);
    }
    free(below);
    free(above);
}

/* The reserve at 10 Hz: evaluated on a state before that state is
 * reported, at the first one and then once per 0.1 s of engine time. */
static void test_reserve_before_state(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    const sw_stream_opts_t so = {.gate = log_gate(),
                                 .risk = {.reserve_rate = 10.0},
                                 .hysteresis = -1.0,
                                 .on_state = r_state,
                                 .user = r};
    sw_stream_t *st = sw_stream_create(&sc, 1, &so, NULL, NULL, 0);
    assert_non_null(st);
    r->stream = st;
    for (long k = 0; k <= 2000; k++) { /* 2 s at 1 kHz, no hole */
        const sw_sample_t s = {.t = (double)k / 1000.0,
                               .a_g = k >= 500 && k < 700 ? -2.0 : 0.0,
                               .a_max = NAN,
                               .seq = SW_GATE_NO_SEQ,
                               .rx = NAN,
                               .wall = NAN};
        sw_stream_push(st, &s);
    }
    sw_stream_finish(st);
    assert_int_equal(r->reserve_checked, r->nst);
    /* t = 0, 0.1, ..., 2.0 s: 21 evaluations, each seen by its own state */
    assert_int_equal(r->reserve_fresh, 21);
    assert_int_equal(sw_risk_pkg(sw_stream_risk(st), 0)->evaluations, 21);
    sw_stream_destroy(st);
    free(r);
}

/* Live: a genuine quiet sensor at 1 kHz and a forger on the same channel,
 * one sample per genuine one, stamped 100 s ahead of its arrival, braking
 * hard enough to overturn the crate.  The gate keeps the genuine timeline
 * (its stamps agree with the arrival times) and says the input is
 * contested; with rival the second engines raise the forged timeline's
 * overturn, marked; without, nothing but the contest is heard. */
static rec_t *contest(int rival)
{
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    const sw_stream_opts_t so = {.gate = {.relative = 1},
                                 .risk = {.reserve_rate = -1.0},
                                 .hysteresis = -1.0,
                                 .rival = rival,
                                 .on_alarm = r_alarm,
                                 .on_input = r_input,
                                 .user = r};
    char msg[256];
    sw_stream_t *st = sw_stream_create(&sc, 1, &so, NULL, msg, sizeof msg);
    assert_non_null(st);
    for (long k = 0; k < 3000; k++) {
        const double t = (double)k / 1000.0;
        const sw_sample_t g = {.t = t,
                               .a_g = 0.0,
                               .a_max = NAN,
                               .seq = SW_GATE_NO_SEQ,
                               .rx = t,
                               .wall = NAN,
                               .where = 2 * k};
        const sw_sample_t f = {.t = t + 100.0,
                               .a_g = t > 0.2 ? -9.0 : 0.0,
                               .a_max = NAN,
                               .seq = SW_GATE_NO_SEQ,
                               .rx = t + 0.0002,
                               .wall = NAN,
                               .where = 2 * k + 1};
        sw_stream_push(st, &g);
        sw_stream_push(st, &f);
    }
    sw_stream_finish(st);
    sw_summary_t s;
    assert_int_equal(sw_engine_summary(sw_stream_engine(st), 0, &s), SW_OK);
    assert_false(s.overturned); /* the kept timeline is the quiet one */
    assert_true(sw_gate_contested(sw_stream_gate(st)) || r->nin > 0);
    sw_stream_destroy(st);
    return r;
}

static void test_rival_alarms(void **state)
{
    (void)state;
    rec_t *with = contest(1), *without = contest(0);
    int contested = 0;
    for (int i = 0; i < with->nin; i++) contested += with->in[i].kind == SW_GATE_EV_CONTESTED;
    assert_true(contested >= 1);
    int marked = 0;
    for (int i = 0; i < with->nal; i++) {
        const sw_alarm_t *a = &with->al[i];
        assert_true(a->level >= SW_ALARM_LEVEL_WARN); /* the second's: WARN up only */
        assert_memory_equal(a->text, "second timeline: ", 17);
        if (a->kind == SW_ALARM_OVERTURNED || a->kind == SW_ALARM_TIP)
            marked++;
        /* timed by the forger's clock: 100 s ahead of the genuine one */
        assert_true(with->al_src[i] > 100.0);
    }
    assert_true(marked >= 1);
    assert_int_equal(count_kind(without, SW_ALARM_OVERTURNED), 0);
    assert_int_equal(count_kind(without, SW_ALARM_TIP), 0);
    free(with);
    free(without);
}

/* A package replaced: its name and scene are the new ones, it stands at
 * rest; no such package, or alarm levels not finite: nothing changes. */
static void test_replace(void **state)
{
    (void)state;
    sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_bare(1.0, 0.5)};
    snprintf(sc[1].name, sizeof sc[1].name, "second");
    rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    const sw_stream_opts_t so = {.gate = log_gate(),
                                 .risk = {.reserve_rate = -1.0},
                                 .hysteresis = -1.0,
                                 .on_alarm = r_alarm,
                                 .user = r};
    sw_stream_t *st = sw_stream_create(sc, 2, &so, NULL, NULL, 0);
    assert_non_null(st);
    assert_string_equal(sw_stream_name(st, 0), "block");
    assert_string_equal(sw_stream_name(st, 1), "second");
    assert_string_equal(sw_stream_name(st, 2), "");
    for (long k = 0; k <= 300; k++) { /* rocking: the squat block lifts (g tan alpha 4.9) */
        const sw_sample_t s = {.t = (double)k / 1000.0,
                               .a_g = -6.0,
                               .a_max = NAN,
                               .seq = SW_GATE_NO_SEQ,
                               .rx = NAN,
                               .wall = NAN};
        sw_stream_push(st, &s);
    }
    sw_state_t x;
    assert_int_equal(sw_engine_get_state(sw_stream_engine(st), 1, &x), SW_OK);
    assert_int_not_equal(x.phase, SW_PHASE_STUCK);

    char msg[128] = "";
    sw_scene_t bad = tu_bare(1.5, 0.6);
    snprintf(bad.name, sizeof bad.name, "bad");
    bad.warn_margin = NAN;
    assert_int_equal(sw_stream_replace(st, 1, &bad, msg, sizeof msg), SW_EINVAL);
    assert_non_null(strstr(msg, "not finite"));
    assert_int_equal(sw_stream_replace(st, 2, &sc[0], msg, sizeof msg), SW_EINVAL);
    assert_string_equal(sw_stream_name(st, 1), "second");

    sw_scene_t fresh = tu_bare(1.5, 0.6);
    snprintf(fresh.name, sizeof fresh.name, "fresh");
    assert_int_equal(sw_stream_replace(st, 1, &fresh, msg, sizeof msg), SW_OK);
    assert_string_equal(sw_stream_name(st, 1), "fresh");
    assert_int_equal(sw_engine_get_state(sw_stream_engine(st), 1, &x), SW_OK);
    assert_int_equal(x.phase, SW_PHASE_STUCK);
    tu_near(x.theta, 0.0, 0.0);
    sw_stream_destroy(st);
    free(r);
}

static void test_null_and_bad_options(void **state)
{
    (void)state;
    sw_stream_destroy(NULL);
    assert_int_equal(sw_stream_push(NULL, NULL), SW_EINVAL);
    assert_int_equal(sw_stream_finish(NULL), SW_EINVAL);
    assert_int_equal(sw_stream_settle(NULL, 1.0), SW_EINVAL);
    assert_null(sw_stream_engine(NULL));
    assert_null(sw_stream_risk(NULL));
    assert_null(sw_stream_gate(NULL));
    assert_int_equal(sw_stream_count(NULL), 0);
    assert_string_equal(sw_stream_name(NULL, 0), "");
    char msg[128];
    assert_int_equal(sw_stream_replace(NULL, 0, NULL, msg, sizeof msg), SW_EINVAL);

    const sw_scene_t sc = tu_bare(2.0, 0.728);
    int err = 0;
    sw_stream_opts_t so = {.gate = {.confirm = 99}, .hysteresis = -1.0};
    assert_null(sw_stream_create(&sc, 1, &so, &err, msg, sizeof msg));
    assert_int_equal(err, SW_EINVAL);
    assert_non_null(strstr(msg, "confirm"));

    sw_scene_t nan_levels = sc;
    nan_levels.critical_margin = NAN;
    so.gate.confirm = 0;
    assert_null(sw_stream_create(&nan_levels, 1, &so, &err, msg, sizeof msg));
    assert_int_equal(err, SW_EINVAL);
    assert_non_null(strstr(msg, "alarm thresholds not finite"));

    so.engine.scheme = "no-such-scheme";
    assert_null(sw_stream_create(&sc, 1, &so, &err, msg, sizeof msg));
    assert_true(err < 0);

    /* defaults: a stream with no options at all takes samples */
    sw_stream_t *st = sw_stream_create(&sc, 1, NULL, &err, NULL, 0);
    assert_non_null(st);
    assert_int_equal(err, SW_OK);
    const sw_sample_t s = {.t = 0.0, .a_max = NAN, .seq = SW_GATE_NO_SEQ, .rx = NAN, .wall = NAN};
    assert_true(sw_stream_push(st, &s) >= 0);
    sw_stream_destroy(st);
}

/* Pushing allocates nothing: the allocator's bytes in use are the same
 * after 20 s of 1 kHz samples with everything on (alarms, the reserve,
 * the second timeline, a refusal, a gap) as after create. */
static void test_no_allocation_per_sample(void **state)
{
    (void)state;
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 5.59, 0.1)};
    rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    const sw_stream_opts_t so = {.gate = {.relative = 1},
                                 .risk = {.reserve_rate = 10.0},
                                 .hysteresis = -1.0,
                                 .rival = 1,
                                 .on_alarm = r_alarm,
                                 .on_input = r_input,
                                 .on_reject = r_reject,
                                 .user = r};
    sw_stream_t *st = sw_stream_create(sc, 2, &so, NULL, NULL, 0);
    assert_non_null(st);
    sw_sample_t s = {.a_max = NAN, .seq = SW_GATE_NO_SEQ, .wall = NAN};
    /* one sample first: anything made lazily on the first is made now */
    s.t = s.rx = 0.0;
    sw_stream_push(st, &s);
    const size_t before = mallinfo2().uordblks;
    for (long k = 1; k <= 20000; k++) {
        s.t = s.rx = (double)k / 1000.0;
        if (k > 9000 && k < 9500)
            continue; /* a gap */
        s.a_g = k % 2000 < 300 ? -3.0 * sin((double)(k % 2000) * M_PI / 300.0) : 0.0;
        s.a_g = k == 5000 ? 1e4 : s.a_g; /* refused */
        sw_stream_push(st, &s);
    }
    sw_stream_finish(st);
    assert_int_equal(mallinfo2().uordblks, before);
    assert_true(r->nrej >= 1);
    sw_stream_destroy(st);
    free(r);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_as_composed),
        cmocka_unit_test(test_uplift_alarm_at_threshold),
        cmocka_unit_test(test_reserve_before_state),
        cmocka_unit_test(test_rival_alarms),
        cmocka_unit_test(test_replace),
        cmocka_unit_test(test_null_and_bad_options),
        cmocka_unit_test(test_no_allocation_per_sample),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
