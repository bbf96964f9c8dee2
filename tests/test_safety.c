/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_safety.c - the safety factors of a log (sweep.h, safety.c): runs
 * that start part-way through the log against runs from its start (a
 * different path: sw_log_run, or an engine fed by hand), the search's
 * trials that jump over what cannot change their answer (safety_prep.c)
 * against the same, the log's restarts, several scenes at once against
 * one at a time, and results that do not depend on the number of
 * threads. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "safety_prep.h"
#include "testutil.h"

#define N 90000 /* 90 s at 1 kHz */

static double t_[N], a_[N], s_[N];

/* A long drive: mild vibration, then every 20 s a braking pulse of the
 * given peak (m/s^2) with a rebound; quiet between.  The crate rocks in
 * each and comes to rest before the next. */
static sw_log_t drive(double peak)
{
    for (size_t i = 0; i < N; i++) {
        const double t = i * 1e-3, u = fmod(t, 20.0) - 15.0;
        t_[i] = t;
        a_[i] = 0.15 * sin(2.0 * M_PI * 1.6 * t) + 0.1 * sin(2.0 * M_PI * 11.0 * t + 1.0);
        if (u >= 0.0 && u < 0.6)
            a_[i] += -peak * sin(M_PI * u / 0.6) * (1.0 + 0.1 * (t / 20.0));
        if (u >= 0.6 && u < 0.9)
            a_[i] += 0.3 * peak * sin(M_PI * (u - 0.6) / 0.3);
    }
    return (sw_log_t){.t = t_, .a_g = a_, .n = N};
}

static sw_log_t scaled(const sw_log_t *L, double x)
{
    for (size_t i = 0; i < L->n; i++) s_[i] = x * L->a_g[i];
    sw_log_t s = *L;
    s.a_g = s_;
    return s;
}

/* The run at scale 1 of the safety factor (at_one) of the log scaled by
 * x: it starts where the crate can first lift and jumps over the
 * stretches it stands at rest. */
static sw_run_result_t at_one(const sw_scene_t *sc, const sw_log_t *L, double x,
                              const sw_run_opts_t *ro)
{
    const sw_log_t s = scaled(L, x);
    const sw_search_opts_t so = {.x_max = 1.5, .step = 0.2, .tol = 0.05};
    sw_safety_t sf;
    char msg[256];
    assert_int_equal(sw_safety_factor(sc, &s, ro, &so, &sf, msg, sizeof msg), SW_OK);
    return sf.at_one;
}

static void same_bits(double a, double b)
{
    assert_memory_equal(&a, &b, sizeof a);
}

/* On the bed: the same run to the last bit as sw_log_run from the start,
 * rocking and at rest by turns, surviving and overturning. */
static void test_bed_exact(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const sw_log_t L = drive(4.0);
    const sw_run_opts_t ro = {.settle = 10.0};
    const double xs[] = {0.95, 1.1, 1.25, 1.6, 2.2};
    int over = 0, rocked = 0;
    for (size_t k = 0; k < sizeof xs / sizeof xs[0]; k++) {
        const sw_run_result_t a = at_one(&sc, &L, xs[k], &ro);
        sw_run_result_t b;
        char msg[256];
        assert_int_equal(sw_log_run(&sc, &L, xs[k], &ro, &b, msg, sizeof msg), SW_OK);
        assert_int_equal(a.overturned, b.overturned);
        assert_int_equal(a.end, b.end);
        assert_int_equal(a.impacts, b.impacts);
        assert_int_equal(a.uplifts, b.uplifts);
        same_bits(a.max_theta_ratio, b.max_theta_ratio);
        same_bits(a.min_margin, b.min_margin);
        same_bits(a.uplift_time, b.uplift_time);
        same_bits(a.tip_time, b.tip_time);
        same_bits(a.overturn_time, b.overturn_time);
        same_bits(a.t_end, b.t_end);
        over += b.overturned;
        rocked += b.uplifts > 2 && !b.overturned;
    }
    assert_true(over >= 1);   /* both outcomes are covered */
    assert_true(rocked >= 1); /* and runs that rest between episodes */
}

/* On a frame the stuck state is scaled from the probe: the same to
 * rounding; on a cushion on the bed it starts a lead-in early from the
 * linear state: the same far below what a sensor resolves. */
static void test_linear_starts(void **state)
{
    (void)state;
    sw_scene_t cu = tu_bare(2.0, 0.728);
    cu.has_cushion = 1;
    cu.cushion_omega = 60.0;
    cu.cushion_zeta = 0.3;
    cu.cushion_k_given = cu.cushion_c_given = SW_GIVEN_RATIO;
    const sw_scene_t fr = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    const sw_scene_t *scenes[2] = {&fr, &cu};
    const sw_run_opts_t ro = {.settle = 10.0};
    for (int m = 0; m < 2; m++) {
        /* quiet, then one braking at the end (a drive's last episode) */
        sw_log_t L = drive(0.0);
        for (size_t i = 0; i < N; i++) {
            const double u = t_[i] - 80.0;
            if (u >= 0.0 && u < 0.6)
                a_[i] += -3.0 * sin(M_PI * u / 0.6);
        }
        const double xs[] = {0.6, 1.0, 1.4};
        for (size_t k = 0; k < 3; k++) {
            const sw_run_result_t a = at_one(scenes[m], &L, xs[k], &ro);
            sw_run_result_t b;
            char msg[256];
            assert_int_equal(sw_log_run(scenes[m], &L, xs[k], &ro, &b, msg, sizeof msg), SW_OK);
            assert_int_equal(a.overturned, b.overturned);
            assert_int_equal(a.impacts, b.impacts);
            tu_near(a.max_theta_ratio, b.max_theta_ratio, m == 0 ? 1e-9 : 1e-6);
            tu_near(a.min_margin, b.min_margin, m == 0 ? 1e-9 : 1e-6);
            if (!isnan(b.uplift_time))
                tu_near(a.uplift_time, b.uplift_time, 1e-9);
        }
    }
}

/* On a cushion a trial whose package has been back in full contact for a
 * lead-in after a lift jumps to the linear state a lead-in before the next
 * sample that can lift it: an early braking that lifts an edge, a long
 * quiet stretch, then the braking at the end.  The runs equal runs from the
 * start far below what a sensor resolves. */
static void test_cushion_jumps(void **state)
{
    (void)state;
    sw_scene_t cu = tu_bare(2.0, 0.728);
    cu.has_cushion = 1;
    cu.cushion_omega = 60.0;
    cu.cushion_zeta = 0.3;
    cu.cushion_k_given = cu.cushion_c_given = SW_GIVEN_RATIO;
    const sw_run_opts_t ro = {.settle = 10.0};
    sw_log_t L = drive(0.0);
    for (size_t i = 0; i < N; i++) {
        for (int k = 0; k < 2; k++) {
            const double u = t_[i] - (k ? 80.0 : 5.0);
            if (u >= 0.0 && u < 0.6)
                a_[i] += -3.0 * sin(M_PI * u / 0.6);
        }
    }
    const double xs[] = {0.6, 1.0, 1.4};
    int lifted_twice = 0;
    for (size_t k = 0; k < 3; k++) {
        const sw_run_result_t a = at_one(&cu, &L, xs[k], &ro);
        sw_run_result_t b;
        char msg[256];
        assert_int_equal(sw_log_run(&cu, &L, xs[k], &ro, &b, msg, sizeof msg), SW_OK);
        assert_int_equal(a.overturned, b.overturned);
        assert_int_equal(a.uplifts, b.uplifts);
        tu_near(a.max_theta_ratio, b.max_theta_ratio, 1e-6);
        tu_near(a.min_margin, b.min_margin, 1e-6);
        tu_near(a.uplift_time, b.uplift_time, 1e-9);
        if (b.overturned)
            tu_near(a.overturn_time, b.overturn_time, 1e-6);
        lifted_twice += b.uplifts >= 2 && b.uplift_time < 10.0;
    }
    assert_true(lifted_twice >= 1); /* the early braking lifts an edge, and so does the last */
}

/* Quiet driving (vibration well below any lift), brakings of 3 m/s^2
 * at the given times (s), and a restart of the log at 60 s. */
static sw_log_t episodes(const double *at, size_t n, size_t *restart)
{
    sw_log_t L = drive(0.0);
    for (size_t i = 0; i < N; i++)
        for (size_t k = 0; k < n; k++) {
            const double u = t_[i] - at[k];
            if (u >= 0.0 && u < 0.6)
                a_[i] += -3.0 * sin(M_PI * u / 0.6);
        }
    *restart = 60000;
    L.restart = restart;
    L.nrestart = 1;
    return L;
}

/* The trials of a search at scale x against the log scaled by x run from
 * its start (sw_log_run): the same outcome; a trial whose peak sets the
 * scan's step (SW_TRIAL_PEAK) has the peak of the trial that reports
 * everything (SW_TRIAL_FULL, made as the run at scale 1 is) to peak_tol
 * (0: to the last bit); one that needs its outcome alone the run's peak to
 * tol (it is reached while the package rocks, which such a trial runs;
 * what it jumps over cannot lift the package). */
static int check_trials(const sw_scene_t *sc, const sw_log_t *L, const double *xs, size_t nx,
                        double tol, double peak_tol)
{
    const sw_run_opts_t ro = {.settle = 10.0};
    prep_t P = {.sc = sc, .log = L, .ro = &ro};
    char msg[256];
    assert_int_equal(sw_safety_prep_make(&P, msg, sizeof msg), SW_OK);
    int rocked_twice = 0;
    for (size_t k = 0; k < nx; k++) {
        sw_run_result_t ref, full, peak, outcome;
        assert_int_equal(sw_log_run(sc, L, xs[k], &ro, &ref, msg, sizeof msg), SW_OK);
        assert_int_equal(sw_safety_trial(&P, xs[k], SW_TRIAL_FULL, &full, msg, sizeof msg), SW_OK);
        assert_int_equal(sw_safety_trial(&P, xs[k], SW_TRIAL_PEAK, &peak, msg, sizeof msg), SW_OK);
        assert_int_equal(sw_safety_trial(&P, xs[k], SW_TRIAL_OUTCOME, &outcome, msg, sizeof msg),
                         SW_OK);
        assert_int_equal(full.overturned, ref.overturned);
        assert_int_equal(peak.overturned, ref.overturned);
        assert_int_equal(outcome.overturned, ref.overturned);
        tu_near(full.max_theta_ratio, ref.max_theta_ratio, tol);
        if (!ref.overturned) {
            if (peak_tol > 0.0)
                tu_near(peak.max_theta_ratio, full.max_theta_ratio, peak_tol);
            else
                same_bits(peak.max_theta_ratio, full.max_theta_ratio);
            tu_near(outcome.max_theta_ratio, ref.max_theta_ratio, tol);
        }
        rocked_twice += ref.uplifts >= 2 && !ref.overturned;
    }
    sw_safety_prep_free(&P);
    return rocked_twice;
}

/* On a frame: episodes 8 s and 40 s apart (and a restart between), the
 * package standing on the frame in between, which the trials jump over in
 * closed form (the same motion but for rounding); 8 s after an episode
 * the frame still rings with a few per cent of what it took, which the
 * next episode feels. */
static void test_trials_frame(void **state)
{
    (void)state;
    const sw_scene_t fr = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    const double at[] = {5.0, 13.0, 45.0, 85.0};
    size_t restart;
    const sw_log_t L = episodes(at, 4, &restart);
    const double xs[] = {0.8, 1.0, 1.3, 1.6, 2.0};
    assert_true(check_trials(&fr, &L, xs, 5, 1e-9, 1e-13) >= 1);
}

/* On a cushion on the bed (lead-in 24 s): episodes 55 s apart, a restart
 * between them, a last one near the end; the trials start each episode
 * from reference states and leave it when the ringing can no longer lift
 * an edge. */
static void test_trials_cushion(void **state)
{
    (void)state;
    sw_scene_t cu = tu_bare(2.0, 0.728);
    cu.has_cushion = 1;
    cu.cushion_omega = 60.0;
    cu.cushion_zeta = 0.3;
    cu.cushion_k_given = cu.cushion_c_given = SW_GIVEN_RATIO;
    const double at[] = {30.0, 85.0};
    size_t restart;
    const sw_log_t L = episodes(at, 2, &restart);
    const double xs[] = {0.6, 0.9, 1.2, 1.5, 2.5};
    assert_true(check_trials(&cu, &L, xs, 5, 1e-6, 0.0) >= 1);
}

/* A restart in the log: the run equals one fed by hand to an engine that
 * restarts there (sw_engine_restart), and differs from the run without. */
static void test_restarts(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    sw_log_t L = drive(2.5);
    const size_t at[] = {35200, 75100}; /* during the second and fourth braking */
    L.restart = at;
    L.nrestart = 2;
    const sw_run_opts_t ro = {.settle = -1.0};
    sw_run_result_t a, b;
    char msg[256];
    assert_int_equal(sw_log_run(&sc, &L, 1.0, &ro, &a, msg, sizeof msg), SW_OK);
    /* by hand: an engine (1 ms, the run's own step for this crate) that
     * restarts where the log says */
    sw_engine_t *e = tu_engine(&sc, NULL, 1e-3, NULL);
    for (size_t i = 0, r = 0; i < L.n; i++) {
        if (r < L.nrestart && L.restart[r] == i) {
            sw_engine_restart(e);
            r++;
        }
        sw_engine_push(e, L.t[i], L.a_g[i], 0.0);
    }
    sw_summary_t h;
    sw_engine_summary(e, 0, &h);
    sw_engine_destroy(e);
    assert_false(h.overturned);
    assert_true(h.uplifts > 1);
    assert_int_equal(h.impacts, a.impacts);
    same_bits(h.max_theta_ratio, a.max_theta_ratio);
    sw_log_t L0 = L;
    L0.nrestart = 0;
    assert_int_equal(sw_log_run(&sc, &L0, 1.0, &ro, &b, msg, sizeof msg), SW_OK);
    assert_true(a.max_theta_ratio != b.max_theta_ratio || a.impacts != b.impacts);
    /* the safety factor's run at 1 takes the same restarts */
    sw_safety_t sf;
    const sw_search_opts_t so = {.x_max = 1.2, .step = 0.2, .tol = 0.05};
    assert_int_equal(sw_safety_factor(&sc, &L, &ro, &so, &sf, msg, sizeof msg), SW_OK);
    assert_int_equal(sf.at_one.impacts, a.impacts);
    tu_near(sf.at_one.max_theta_ratio, a.max_theta_ratio, 1e-9);
}

/* The bracket: the log scaled by factor_safe survives, by factor
 * overturns, run from the start; several scenes at once give what each
 * gives alone; 1, 2 and 3 threads give the same to the last bit. */
static void test_many_threads(void **state)
{
    (void)state;
    sw_safety_case_t *c = calloc(3 * 3, sizeof *c);
    assert_non_null(c);
    const sw_log_t L = drive(3.0);
    sw_scene_t cu = tu_bare(2.0, 0.728);
    cu.has_cushion = 1;
    cu.cushion_omega = 80.0;
    cu.cushion_zeta = 0.3;
    cu.cushion_k_given = cu.cushion_c_given = SW_GIVEN_RATIO;
    const sw_scene_t sc[3] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 8.0, 0.1), cu};
    const int threads[3] = {1, 2, 3};
    for (int k = 0; k < 3; k++) {
        sw_safety_opts_t o = {.threads = threads[k], .run = {.settle = 5.0}};
        for (int i = 0; i < 3; i++) c[3 * k + i].scene = sc[i];
        assert_int_equal(sw_safety_factors(&c[3 * k], 3, &L, &o), SW_OK);
    }
    for (int i = 0; i < 3; i++) {
        const sw_safety_t *s = &c[i].sf;
        assert_true(s->found);
        for (int k = 1; k < 3; k++) {
            const sw_safety_t *u = &c[3 * k + i].sf;
            same_bits(s->factor, u->factor);
            same_bits(s->factor_safe, u->factor_safe);
            assert_int_equal(s->trials, u->trials);
            same_bits(s->at_one.max_theta_ratio, u->at_one.max_theta_ratio);
        }
        sw_safety_t one;
        char msg[256];
        const sw_run_opts_t ro = {.settle = 5.0};
        assert_int_equal(sw_safety_factor(&sc[i], &L, &ro, NULL, &one, msg, sizeof msg), SW_OK);
        same_bits(one.factor, s->factor);
        sw_run_result_t r;
        assert_int_equal(sw_log_run(&sc[i], &L, s->factor_safe, &ro, &r, msg, sizeof msg), SW_OK);
        assert_false(r.overturned);
        assert_int_equal(sw_log_run(&sc[i], &L, s->factor, &ro, &r, msg, sizeof msg), SW_OK);
        assert_true(r.overturned);
        assert_true(s->factor / s->factor_safe - 1.0 <= 1e-3);
    }
    free(c);
}

/* The caller's side work shares the searches' threads: every task runs
 * exactly once, on 1, 2 and 3 threads, and the searches answer to the
 * last bit what they answer without it. */
typedef struct {
    int runs[8];
} side_count_t;

static void count_side(void *user, size_t k)
{
    side_count_t *S = user;
    S->runs[k]++; /* each k is one task: no other thread writes it */
}

static void test_side_work(void **state)
{
    (void)state;
    const sw_log_t L = drive(3.0);
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 8.0, 0.1)};
    sw_safety_case_t plain[2], side[2];
    sw_safety_opts_t o = {.threads = 2, .run = {.settle = 5.0}};
    for (int i = 0; i < 2; i++) plain[i].scene = sc[i];
    assert_int_equal(sw_safety_factors(plain, 2, &L, &o), SW_OK);
    for (int threads = 1; threads <= 3; threads++) {
        side_count_t S = {{0}};
        o.threads = threads;
        o.sides = 7; /* more than the threads, fewer than the slots */
        o.side = count_side;
        o.side_user = &S;
        for (int i = 0; i < 2; i++) side[i].scene = sc[i];
        assert_int_equal(sw_safety_factors(side, 2, &L, &o), SW_OK);
        for (int k = 0; k < 8; k++) assert_int_equal(S.runs[k], k < 7);
        for (int i = 0; i < 2; i++) {
            same_bits(side[i].sf.factor, plain[i].sf.factor);
            same_bits(side[i].sf.factor_safe, plain[i].sf.factor_safe);
            assert_int_equal(side[i].sf.trials, plain[i].sf.trials);
        }
    }
}

/* An engine told the log's origin and started at sample k gives, for a
 * package that stood still until then, the run from the start to the
 * last bit; a first sample before the origin is refused. */
static void test_origin(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const sw_log_t L = drive(5.0);
    sw_engine_t *a = tu_engine(&sc, NULL, 0.0, NULL), *b = tu_engine(&sc, NULL, 0.0, NULL);
    const double t0 = 1234.5678; /* a time origin that rounds */
    assert_int_equal(sw_engine_set_origin(b, t0), SW_OK);
    assert_int_equal(sw_engine_push(b, t0 - 1.0, 0.0, 0.0), SW_EORDER);
    for (size_t i = 0; i < 20000; i++) {
        sw_engine_push(a, t0 + L.t[i], L.a_g[i], 0.0);
        if (i >= 14000)
            sw_engine_push(b, t0 + L.t[i], L.a_g[i], 0.0);
    }
    sw_summary_t sa, sb;
    sw_engine_summary(a, 0, &sa);
    sw_engine_summary(b, 0, &sb);
    assert_true(sa.uplifts > 0);
    assert_int_equal(sa.impacts, sb.impacts);
    same_bits(sa.max_abs_theta, sb.max_abs_theta);
    same_bits(sa.uplift_time, sb.uplift_time);
    assert_int_equal(sw_engine_set_origin(b, 0.0), SW_EINVAL); /* started */
    sw_engine_destroy(a);
    sw_engine_destroy(b);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bed_exact),      cmocka_unit_test(test_linear_starts),
        cmocka_unit_test(test_cushion_jumps),  cmocka_unit_test(test_restarts),
        cmocka_unit_test(test_many_threads),   cmocka_unit_test(test_side_work),
        cmocka_unit_test(test_origin),         cmocka_unit_test(test_trials_frame),
        cmocka_unit_test(test_trials_cushion),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
