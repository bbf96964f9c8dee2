/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_fault.c - numerical faults: a package whose state leaves the model
 * gets an SW_EV_FAULT event, is reset to rest, and the engine goes on; no
 * state, event or summary ever carries NaN or infinity.
 *
 * Faults are forced by an input so large that the fixed step exceeds the
 * scheme's stability bound for it.  The bed falling faster than gravity
 * (g + a_z <= 0) and exactly zero gravity (the energy bound's barrier
 * vanishes) are no longer faults: the packages fly (physics.md, "Free
 * flight"), and their reports stay finite.  Absurd samples (1e300) are
 * refused at the door. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define G 9.81

typedef struct {
    tu_events_t ev;
    long states, nonfinite;
    sw_output_t last[4]; /* per package */
} rec_t;

static void count_nonfinite(rec_t *r, const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++) r->nonfinite += !isfinite(v[i]);
}

static void on_state(void *user, const sw_output_t *o)
{
    rec_t *r = user;
    const double v[] = {
        o->t,       o->state.u,     o->state.u_dot, o->state.theta,  o->state.theta_dot,
        o->state.z, o->state.z_dot, o->margin,      o->margin_bound, o->uplift_ratio,
        o->a_g,     o->a_support};
    count_nonfinite(r, v, sizeof v / sizeof v[0]);
    r->states++;
    if (o->pkg < 4)
        r->last[o->pkg] = *o;
}

static void on_event(void *user, const sw_event_t *ev)
{
    rec_t *r = user;
    const double v[] = {ev->t, ev->theta, ev->theta_dot, ev->margin, ev->info};
    count_nonfinite(r, v, sizeof v / sizeof v[0]);
    tu_on_event(&r->ev, ev);
}

static sw_engine_t *engine(const sw_scene_t *sc, size_t n, double dt, rec_t *r)
{
    sw_engine_opts_t o = {0};
    o.dt = dt;
    o.on_state = on_state;
    o.on_event = on_event;
    o.user = r;
    int err = 0;
    char msg[256];
    sw_engine_t *e = sw_engine_create(sc, n, &o, &err, msg, sizeof msg);
    if (!e)
        fprintf(stderr, "engine: %s\n", msg);
    assert_non_null(e);
    return e;
}

/* A braking half-sine of amplitude a (m/s^2, > 0) and length 0.4 s from
 * t0, sampled at 1 kHz, with vertical acceleration az. */
static double brake(sw_engine_t *e, double t0, double a, double az)
{
    double t = t0;
    for (int i = 1; i <= 400; i++) {
        t = t0 + i * 1e-3;
        sw_engine_push(e, t, -a * sin(M_PI * i / 400.0), az);
    }
    return t;
}

static long count_after(const tu_events_t *r, sw_event_kind k, double t)
{
    long c = 0;
    for (int i = 0; i < r->n; i++) c += r->ev[i].kind == k && r->ev[i].t >= t;
    return c;
}

/* Rocking, then the bed drops faster than g for 50 ms: each package
 * (bare and frame) flies (physics.md, "Free flight"), no fault, every
 * report finite; once gravity is back it lands, and the next shock rocks
 * them again. */
static void test_free_fall(void **state)
{
    (void)state;
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250, 5.59, 0.1)};
    rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    sw_engine_t *e = engine(sc, 2, 0.0, r);
    sw_engine_push(e, 0.0, 0.0, 0.0);
    double t = brake(e, 0.0, 1.2 * G * 0.364, 0.0);
    assert_int_equal(r->last[0].state.phase, SW_PHASE_ROCKING);

    for (int i = 1; i <= 50; i++) sw_engine_push(e, t + i * 1e-3, 0.0, -1.5 * G);
    t += 50e-3;
    for (size_t k = 0; k < 2; k++) {
        sw_summary_t s;
        sw_engine_summary(e, k, &s);
        assert_int_equal(s.faults, 0);
        assert_int_equal(s.flights, 1);
        assert_true(s.flight_max >= 49e-3);
    }
    assert_null(tu_first(&r->ev, SW_EV_FAULT));

    /* Gravity back: it lands; a second shock: both rock again, no fault. */
    for (int i = 1; i <= 2000; i++) sw_engine_push(e, t + i * 1e-3, 0.0, 0.0);
    t += 2.0;
    const double t_back = t;
    long faults_before = 0;
    for (int i = 0; i < r->ev.n; i++) faults_before += r->ev.ev[i].kind == SW_EV_FAULT;
    t = brake(e, t + 1e-3, 1.2 * G * 0.364, 0.0);
    assert_true(count_after(&r->ev, SW_EV_UPLIFT, t_back) >= 2);
    assert_int_equal(count_after(&r->ev, SW_EV_FAULT, t_back), 0);
    long faults_after = 0;
    for (int i = 0; i < r->ev.n; i++) faults_after += r->ev.ev[i].kind == SW_EV_FAULT;
    assert_int_equal(faults_after, faults_before);
    assert_int_equal(r->nonfinite, 0);
    sw_engine_destroy(e);
    free(r);
}

/* g + a_z exactly 0: the frame's energy bound divides by the barrier
 * g_eff R (1 - cos alpha); it must not come out as NaN.  The packages
 * float, level and still, and are back on the bed with gravity. */
static void test_zero_gravity(void **state)
{
    (void)state;
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250, 5.59, 0.1)};
    rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    sw_engine_t *e = engine(sc, 2, 0.0, r);
    sw_engine_push(e, 0.0, 0.0, -G);
    for (int i = 1; i <= 10; i++) sw_engine_push(e, i * 1e-3, 0.0, -G);
    for (int i = 11; i <= 20; i++) sw_engine_push(e, i * 1e-3, 0.0, 0.0);
    assert_true(r->states == 2 * 21);
    assert_int_equal(r->nonfinite, 0);
    assert_int_equal(tu_count(&r->ev, SW_EV_FAULT), 0);
    for (size_t k = 0; k < 2; k++) {
        sw_output_t o;
        sw_engine_get_output(e, k, &o);
        assert_true(isfinite(o.margin_bound) && o.margin_bound == 1.0);
        assert_int_equal(o.state.phase, SW_PHASE_STUCK);
        sw_summary_t s;
        sw_engine_summary(e, k, &s);
        assert_int_equal(s.flights, 1);
    }
    sw_engine_destroy(e);
    free(r);
}

/* A large (but accepted) input with a long fixed step: sqrt(kR a) h above
 * RK4's bound.  The bare package faults with SW_EUNSTABLE, while a frame
 * package whose stiff bearings already force short steps rides it out;
 * the faulted package works normally once the input is sane again. */
static void test_step_beyond_stability(void **state)
{
    (void)state;
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250, 2000.0, 0.1)};
    rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    const double dt = 0.02; /* s; sqrt(kR 5e4) dt = 3.8 > 2.785 */
    sw_engine_t *e = engine(sc, 2, dt, r);
    assert_true(sw_engine_dt(e, 1) < 1e-3);
    sw_engine_push(e, 0.0, 0.0, 0.0);
    assert_int_equal(sw_engine_push(e, dt, -5e4, 0.0), SW_EVENT);
    sw_engine_push(e, 2 * dt, -5e4, 0.0);
    const sw_event_t *f = tu_first(&r->ev, SW_EV_FAULT);
    assert_non_null(f);
    assert_int_equal(f->pkg, 0);
    assert_int_equal((int)f->info, SW_EUNSTABLE);
    sw_summary_t s0, s1;
    sw_engine_summary(e, 0, &s0);
    sw_engine_summary(e, 1, &s1);
    assert_true(s0.faults >= 1);
    assert_int_equal(s1.faults, 0);
    assert_int_equal(r->last[0].state.phase, SW_PHASE_STUCK);

    /* Sane input again (the ramp down from the last large sample may
     * still fault): quiet for the bare block, no further faults. */
    sw_engine_push(e, 3 * dt, 0.0, 0.0);
    sw_engine_summary(e, 0, &s0);
    const long faults = s0.faults;
    for (int i = 4; i < 100; i++) sw_engine_push(e, i * dt, 0.0, 0.0);
    sw_engine_summary(e, 0, &s0);
    assert_int_equal(s0.faults, faults);
    assert_int_equal(r->nonfinite, 0);
    sw_engine_destroy(e);
    free(r);
}

/* A fault does not end the sample interval: the package stands from
 * there, and the bed falling away later in the same interval still lifts
 * it off.  Rocking under a huge braking (RK4 unstable at dt = 20 ms, as
 * above), the bed then drops at 3 g: g_eff = g - 3 g t / dt reaches 0 at
 * dt / 3, where the faulted package, standing, takes off level. */
static void test_fault_then_take_off(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    const double dt = 0.02; /* s */
    sw_engine_t *e = engine(&sc, 1, dt, r);
    sw_engine_push(e, 0.0, -5e4, 0.0); /* lifts at once */
    assert_int_equal(r->last[0].state.phase, SW_PHASE_ROCKING);
    sw_engine_push(e, dt, -5e4, -3.0 * sc.g);
    assert_int_equal(r->ev.n, 3);
    assert_int_equal(r->ev.ev[0].kind, SW_EV_UPLIFT);
    assert_int_equal(r->ev.ev[1].kind, SW_EV_FAULT);
    assert_int_equal((int)r->ev.ev[1].info, SW_EUNSTABLE);
    tu_near(r->ev.ev[1].t, 0.0, 0.0);
    assert_int_equal(r->ev.ev[2].kind, SW_EV_UPLIFT);
    assert_true(r->ev.ev[2].info == 0.0); /* level: a take-off */
    tu_near(r->ev.ev[2].t, dt / 3.0, 1e-15);
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_int_equal(s.faults, 1);
    assert_int_equal(s.flights, 1);
    assert_int_equal(r->nonfinite, 0);
    sw_engine_destroy(e);
    free(r);
}

/* 1e300, NaN and infinity are refused; the sample is ignored and the state
 * untouched, and the next good sample continues from the last good one. */
static void test_absurd_samples_refused(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    sw_engine_t *e = engine(&sc, 1, 0.0, r);
    assert_int_equal(sw_engine_push(e, 0.0, 0.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_push(e, 1e-3, 1e300, 0.0), SW_ETOOBIG);
    assert_int_equal(sw_engine_push(e, 1e-3, 0.0, -1e300), SW_ETOOBIG);
    assert_int_equal(sw_engine_push(e, 1e-3, -SW_MAX_ACCEL * 1.0001, 0.0), SW_ETOOBIG);
    assert_int_equal(sw_engine_push(e, 1e-3, NAN, 0.0), SW_ENONFINITE);
    assert_int_equal(sw_engine_push(e, 1e-3, 0.0, INFINITY), SW_ENONFINITE);
    assert_true(sw_engine_time(e) == 0.0);
    assert_int_equal(r->states, 1);
    assert_int_equal(r->ev.n, 0);
    assert_int_equal(sw_engine_push(e, 1e-3, 0.0, 0.0), SW_OK);
    /* The largest accepted input overturns the block (the physics, not a
     * fault) and every number stays finite. */
    assert_int_equal(sw_engine_push(e, 2e-3, -SW_MAX_ACCEL, 0.0), SW_EVENT);
    for (int i = 3; i <= 20; i++) sw_engine_push(e, i * 1e-3, -SW_MAX_ACCEL, 0.0);
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_true(s.overturned || s.faults > 0);
    assert_true(isfinite(s.min_margin) && isfinite(s.max_abs_theta));
    assert_int_equal(r->nonfinite, 0);
    sw_engine_destroy(e);
    free(r);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_fall),
        cmocka_unit_test(test_zero_gravity),
        cmocka_unit_test(test_step_beyond_stability),
        cmocka_unit_test(test_fault_then_take_off),
        cmocka_unit_test(test_absurd_samples_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
