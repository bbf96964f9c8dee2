/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_reserve_log.c - the smallest reserve along a log
 * (sw_reserve_log_min) against the exhaustive answer: the same log run
 * through an engine of the same settings, every due state evaluated by
 * sw_risk, as replay does it.  On the bed, on a frame and on a cushion, a
 * log that rocks the package and one that overturns it; a budget too small
 * to finish gives a bracket that holds the exhaustive minimum.  And the
 * minimum-only reserve of sw_risk (risk.h, min_only), which an offline
 * replay uses, against the same exhaustive answer on drives of a few
 * minutes, with more states than it holds at once. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "testutil.h"

static const double A20 = 20.0 * M_PI / 180.0; /* rad */
#define RATE 200.0                             /* Hz, the synthetic logs */
#define SECONDS 16.0
#define N 3200 /* RATE * SECONDS */

/* A braking of peak amp g at 2 s (half-sine, 1 s), a pothole-like jolt of
 * 3 amp g at 6 s (50 ms), another braking at 9 s, then quiet. */
typedef struct {
    double t[N];
    double a[N];
    sw_log_t log;
} log_t;

static double bump(double t, double t0, double T, double amp)
{
    return t >= t0 && t <= t0 + T ? amp * sin(M_PI * (t - t0) / T) : 0.0;
}

static log_t *make_log(double amp)
{
    log_t *L = calloc(1, sizeof *L);
    assert_non_null(L);
    const size_t n = N;
    for (size_t i = 0; i < n; i++) {
        const double t = (double)i / RATE;
        L->t[i] = t;
        L->a[i] = -SW_G0 * (bump(t, 2.0, 1.0, amp) + bump(t, 6.0, 0.05, 3.0 * amp) +
                            bump(t, 9.0, 0.8, 0.8 * amp));
    }
    L->log = (sw_log_t){.t = L->t, .a_g = L->a, .n = n};
    return L;
}

/* The exhaustive answer: an engine with the default settings (those of the
 * log runs for these scenes: rk4 at 1 ms), every due state evaluated. */
typedef struct {
    sw_risk_t *risk;
} ref_t;

static void ref_state(void *user, const sw_output_t *o)
{
    sw_risk_output(((ref_t *)user)->risk, o);
}

static sw_risk_pkg_t exhaustive(const sw_scene_t *sc, const log_t *L)
{
    int err;
    char msg[256];
    sw_risk_opts_t ro = {.reserve_rate = SW_RESERVE_LOG_RATE};
    ref_t R = {sw_risk_create(sc, 1, &ro, &err, msg, sizeof msg)};
    assert_non_null(R.risk);
    sw_engine_opts_t eo = {0};
    eo.on_state = ref_state;
    eo.user = &R;
    sw_engine_t *e = sw_engine_create(sc, 1, &eo, &err, msg, sizeof msg);
    assert_non_null(e);
    for (size_t i = 0; i < L->log.n; i++) {
        sw_engine_push(e, L->t[i], L->a[i], 0.0);
        sw_summary_t s;
        sw_engine_summary(e, 0, &s);
        if (s.overturned)
            break;
    }
    const sw_risk_pkg_t out = *sw_risk_pkg(R.risk, 0);
    sw_engine_destroy(e);
    sw_risk_destroy(R.risk);
    return out;
}

static void check_scene(const sw_scene_t *sc, double amp, int expect_overturn)
{
    log_t *L = make_log(amp);
    const sw_risk_pkg_t ref = exhaustive(sc, L);
    sw_reserve_log_t got;
    char msg[256];
    assert_int_equal(sw_reserve_log_min(sc, &L->log, NULL, &got, msg, sizeof msg), SW_OK);
    print_message(
        "%s, %.2f g: exhaustive %.4f g at %.2f s (%ld evaluations); pruned %.4f g at "
        "%.2f s (%ld of %zu states)\n",
        sc->name, amp, ref.min_reserve_g, ref.min_reserve_time, ref.evaluations, got.min_g,
        got.min_time, got.evaluated, got.states);
    assert_true(got.exact);
    assert_true(got.min_g == got.lower_g);
    if (expect_overturn) {
        assert_true(got.min_g == 0.0);
        assert_true(ref.min_reserve_g == 0.0);
        /* the overturned state is kept at its time, possibly before the
         * next due state that replay evaluates */
        assert_true(got.min_time <= ref.min_reserve_time);
    } else {
        assert_true(got.min_g > 0.0);
        assert_true(got.min_g == ref.min_reserve_g);
        assert_true(got.min_time == ref.min_reserve_time);
        assert_int_equal(got.direction, ref.min_direction);
        assert_true(got.evaluated <= (long)got.states);
        /* on the bed, where most states are at rest or nearly so, far
         * fewer evaluations than states */
        if (sc->has_frame == 0 && sc->has_cushion == 0)
            assert_true(got.evaluated < (long)got.states / 4);
    }
    /* a budget of one evaluation: a bracket around the true minimum */
    sw_reserve_log_opts_t o = {.max_evals = 1};
    sw_reserve_log_t b;
    assert_int_equal(sw_reserve_log_min(sc, &L->log, &o, &b, msg, sizeof msg), SW_OK);
    assert_true(b.evaluated <= 1);
    assert_true(b.lower_g <= got.min_g && got.min_g <= b.min_g);
    if (!b.exact)
        assert_true(b.lower_g < b.min_g);
    free(L);
}

static void test_bare(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 2.0 * tan(A20));
    check_scene(&sc, 0.40, 0);
    check_scene(&sc, 0.75, 1);
}

static void test_frame(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_frame(2.0, 2.0 * tan(A20), 250.0, 5.59, 0.1);
    check_scene(&sc, 0.25, 0);
    check_scene(&sc, 0.60, 1);
}

static void test_cushion(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_cushion(tu_bare(2.0, 2.0 * tan(A20)), 50.0, 0.1);
    check_scene(&sc, 0.10, 0);
    check_scene(&sc, 0.50, 1);
}

/* A drive of `seconds` at 200 Hz: vibration near the crate's rocking
 * and a frame's frequencies, and every 40 s a braking half-sine of 1 s
 * whose peak is amp g, then grows by step g each time (step > 0: the last
 * stands out; < 0: the first). */
static sw_log_t drive_log(double *t, double *a, double seconds, double amp, double step)
{
    const size_t n = (size_t)(seconds * RATE);
    for (size_t i = 0; i < n; i++) {
        t[i] = (double)i / RATE;
        a[i] = 0.4 * sin(2.0 * M_PI * 1.3 * t[i]) + 0.3 * sin(2.0 * M_PI * 0.9 * t[i] + 1.0) +
               0.2 * sin(2.0 * M_PI * 7.0 * t[i]);
        for (int k = 0; 40.0 * k + 10.0 < seconds; k++)
            a[i] -= SW_G0 * bump(t[i], 40.0 * k + 10.0, 1.0, amp + step * k);
    }
    return (sw_log_t){.t = t, .a_g = a, .n = n};
}

/* The log through an engine of default settings, its outputs into a risk
 * at rate Hz, every due state evaluated or (min_only) held and resolved
 * at the end. */
static sw_risk_pkg_t risk_of(const sw_scene_t *sc, const sw_log_t *L, double rate, int min_only)
{
    int err;
    char msg[256];
    sw_risk_opts_t ro = {.reserve_rate = rate, .min_only = min_only};
    ref_t R = {sw_risk_create(sc, 1, &ro, &err, msg, sizeof msg)};
    assert_non_null(R.risk);
    sw_engine_opts_t eo = {0};
    eo.on_state = ref_state;
    eo.user = &R;
    sw_engine_t *e = sw_engine_create(sc, 1, &eo, &err, msg, sizeof msg);
    assert_non_null(e);
    for (size_t i = 0; i < L->n; i++) sw_engine_push(e, L->t[i], L->a_g[i], 0.0);
    assert_int_equal(sw_risk_resolve(R.risk, 0), SW_OK);
    const sw_risk_pkg_t out = *sw_risk_pkg(R.risk, 0);
    sw_engine_destroy(e);
    sw_risk_destroy(R.risk);
    return out;
}

/* The minimum, its time, direction and pulse, the states taken: the same
 * as the exhaustive evaluation's, for fewer reserve searches. */
static void check_min_only(const sw_scene_t *sc, double seconds, double rate, double amp,
                           double step)
{
    const size_t n = (size_t)(seconds * RATE);
    double *t = malloc(n * sizeof *t), *a = malloc(n * sizeof *a);
    assert_non_null(t);
    assert_non_null(a);
    const sw_log_t L = drive_log(t, a, seconds, amp, step);
    const sw_risk_pkg_t all = risk_of(sc, &L, rate, 0), min = risk_of(sc, &L, rate, 1);
    print_message("%s, %.0f s at %.0f Hz: %.4f g at %.2f s; %ld states, %ld searches of %ld\n",
                  sc->name, seconds, rate, min.min_reserve_g, min.min_reserve_time, min.evaluations,
                  min.reserve_runs, all.reserve_runs);
    assert_true(all.min_reserve_g > 0.0);
    assert_true(min.min_reserve_g == all.min_reserve_g);
    assert_true(min.min_reserve_time == all.min_reserve_time);
    assert_int_equal(min.min_direction, all.min_direction);
    assert_true(min.min_pulse == all.min_pulse);
    assert_int_equal(min.evaluations, all.evaluations);
    assert_true(isnan(min.reserve_g)); /* no value per state */
    assert_true(min.reserve_runs < all.reserve_runs);
    free(t);
    free(a);
}

static void test_min_only(void **state)
{
    (void)state;
    const double w = 2.0 * tan(A20);
    /* 100 Hz for 3 min: more states than SW_RISK_MIN_STATES, in two
     * searches; the minimum in the second (the last shock the strongest),
     * then in the first (the first strongest), which the second search
     * must keep */
    const sw_scene_t bare = tu_bare(2.0, w);
    assert_true(180.0 * 100.0 > SW_RISK_MIN_STATES);
    check_min_only(&bare, 180.0, 100.0, 0.33, 0.03);  /* lifted by the last three */
    check_min_only(&bare, 180.0, 100.0, 0.45, -0.03); /* by the first three */
    const sw_scene_t frame = tu_frame(2.0, w, 250.0, 5.59, 0.1);
    check_min_only(&frame, 180.0, SW_RISK_RATE, 0.12, 0.03);
    const sw_scene_t cushion = tu_cushion(tu_bare(2.0, w), 50.0, 0.1);
    check_min_only(&cushion, 130.0, SW_RISK_RATE, 0.12, 0.03);
}

static void test_bad_arguments(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 2.0 * tan(A20));
    log_t *L = make_log(0.1);
    sw_reserve_log_t out;
    char msg[256];
    assert_int_equal(sw_reserve_log_min(NULL, &L->log, NULL, &out, msg, sizeof msg), SW_EINVAL);
    assert_int_equal(sw_reserve_log_min(&sc, NULL, NULL, &out, msg, sizeof msg), SW_EINVAL);
    assert_int_equal(sw_reserve_log_min(&sc, &L->log, NULL, NULL, msg, sizeof msg), SW_EINVAL);
    sw_reserve_log_opts_t o = {.max_evals = -1};
    assert_int_equal(sw_reserve_log_min(&sc, &L->log, &o, &out, msg, sizeof msg), SW_EINVAL);
    assert_true(msg[0] != '\0');
    free(L);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bare),          cmocka_unit_test(test_frame),
        cmocka_unit_test(test_cushion),       cmocka_unit_test(test_min_only),
        cmocka_unit_test(test_bad_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
