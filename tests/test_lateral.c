/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_lateral.c - the lateral plane (physics.md, "The lateral plane"): a
 * package with a depth, in an engine told to expect a lateral
 * acceleration, rocks across the truck as the planar model of the package
 * over its depth.
 *
 * References: the planar run of the same scene with width = depth (the
 * lateral plane must equal it to the last bit), the static uplift
 * threshold a = g b/h of each plane's half-size over the centre's height,
 * and outcomes the static threshold decides (an input below it never
 * lifts a bare block; one well above it overturns it). */
/* cmocka.h needs these first */
/* clang-format off */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
/* clang-format on */
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define G 9.81        /* m/s^2, the scenes' gravity */
#define RATE 1000.0   /* Hz, the samples pushed */
#define MAX_OUT 40000 /* states recorded per plane */

/* The states of one plane of package 0, as reported. */
typedef struct {
    sw_plane plane;
    int n;
    sw_output_t o[MAX_OUT];
} states_t;

typedef struct {
    states_t *st;
    tu_events_t *ev;
} rec_t;

static void on_state(void *user, const sw_output_t *o)
{
    rec_t *r = user;
    if (o->plane == r->st->plane && o->pkg == 0 && r->st->n < MAX_OUT)
        r->st->o[r->st->n++] = *o;
}

static void on_event(void *user, const sw_event_t *ev)
{
    rec_t *r = user;
    if (r->ev)
        tu_on_event(r->ev, ev);
}

static sw_engine_t *make(const sw_scene_t *sc, size_t n, int lateral, rec_t *r)
{
    sw_engine_opts_t o = {0};
    o.lateral = lateral;
    o.on_state = r && r->st ? on_state : NULL;
    o.on_event = r ? on_event : NULL;
    o.user = r;
    int err;
    char msg[256];
    sw_engine_t *e = sw_engine_create(sc, n, &o, &err, msg, sizeof msg);
    if (!e)
        fail_msg("engine: %s (%s)", msg, sw_strerror(err));
    return e;
}

/* A half-sine of amplitude a (m/s^2) and duration T (s) from t0 (s). */
static double half_sine(double t, double t0, double T, double a)
{
    return t >= t0 && t <= t0 + T ? a * sin(M_PI * (t - t0) / T) : 0.0;
}

/* A drive that lifts, rocks and, at its end, overturns a crate over
 * 0.5 m: a braking half-sine, road noise (a fixed sum of sines) and a
 * vertical shake, sampled at RATE. */
static double drive(double t)
{
    return half_sine(t, 1.0, 1.2, -0.45 * G) + half_sine(t, 4.0, 0.4, 1.5 * G) +
           0.3 * sin(2 * M_PI * 7.3 * t) + 0.2 * sin(2 * M_PI * 13.1 * t + 0.4);
}

static double vert(double t)
{
    return 0.4 * sin(2 * M_PI * 3.1 * t);
}

/* The summary's numbers and counts, the name aside (the same here). */
static void assert_same_summary(const sw_summary_t *a, const sw_summary_t *b)
{
    assert_int_equal(a->overturned, b->overturned);
    assert_memory_equal(&a->overturn_time, &b->overturn_time, sizeof(double));
    assert_memory_equal(&a->tip_time, &b->tip_time, sizeof(double));
    assert_memory_equal(&a->uplift_time, &b->uplift_time, sizeof(double));
    assert_memory_equal(&a->max_abs_theta, &b->max_abs_theta, sizeof(double));
    assert_memory_equal(&a->min_margin, &b->min_margin, sizeof(double));
    assert_memory_equal(&a->min_margin_bound, &b->min_margin_bound, sizeof(double));
    assert_memory_equal(&a->max_uplift_ratio, &b->max_uplift_ratio, sizeof(double));
    assert_int_equal(a->impacts, b->impacts);
    assert_int_equal(a->uplifts, b->uplifts);
    assert_int_equal(a->rests, b->rests);
    assert_int_equal(a->steps, b->steps);
}

/* (a) A lateral-only input on a package of depth w equals, to the last
 * bit, the planar run of the package of width w on that input; the plane
 * along the truck, with no input, never lifts.  For each model. */
static void check_equal_planar(sw_scene_t alone)
{
    static states_t s_lat, s_one;
    tu_events_t *ev_lat = calloc(1, sizeof *ev_lat), *ev_one = calloc(1, sizeof *ev_one);
    assert_non_null(ev_lat);
    assert_non_null(ev_one);
    sw_scene_t two = alone;
    two.depth = alone.width;
    two.width = 1.3; /* along the truck: any other size */
    s_lat = (states_t){.plane = SW_PLANE_LAT};
    s_one = (states_t){.plane = SW_PLANE_LONG};
    rec_t r_lat = {&s_lat, ev_lat}, r_one = {&s_one, ev_one};
    sw_engine_t *a = make(&two, 1, 1, &r_lat), *b = make(&alone, 1, 0, &r_one);
    assert_int_equal(sw_engine_planes(a, 0), 2);
    assert_int_equal(sw_engine_planes(b, 0), 1);
    for (int i = 0; i <= 8 * (int)RATE; i++) {
        const double t = i / RATE;
        assert_true(sw_engine_push_lat(a, t, 0.0, drive(t), vert(t)) >= 0);
        assert_true(sw_engine_push(b, t, drive(t), vert(t)) >= 0);
    }
    sw_engine_finish(a, 5.0);
    sw_engine_finish(b, 5.0);
    assert_int_equal(s_lat.n, s_one.n);
    for (int i = 0; i < s_one.n; i++) {
        sw_output_t x = s_lat.o[i];
        x.plane = SW_PLANE_LONG;
        assert_memory_equal(&x, &s_one.o[i], sizeof x);
    }
    int n_lat = 0;
    for (int i = 0; i < ev_lat->n; i++) {
        if (ev_lat->ev[i].plane != SW_PLANE_LAT)
            continue;
        const sw_event_t *x = &ev_lat->ev[i], *y = &ev_one->ev[n_lat];
        assert_true(n_lat < ev_one->n);
        assert_int_equal(x->pkg, y->pkg);
        assert_int_equal(x->kind, y->kind);
        const double vx[] = {x->t, x->theta, x->theta_dot, x->margin, x->info};
        const double vy[] = {y->t, y->theta, y->theta_dot, y->margin, y->info};
        assert_memory_equal(vx, vy, sizeof vx);
        n_lat++;
    }
    assert_int_equal(n_lat, ev_one->n);
    assert_true(tu_count(ev_one, SW_EV_UPLIFT) > 0);
    sw_summary_t sl, so, sa;
    assert_int_equal(sw_engine_summary_plane(a, 0, SW_PLANE_LAT, &sl), SW_OK);
    assert_int_equal(sw_engine_summary(b, 0, &so), SW_OK);
    assert_same_summary(&sl, &so);
    assert_int_equal(sw_engine_summary_plane(a, 0, SW_PLANE_LONG, &sa), SW_OK);
    assert_int_equal(sa.uplifts, 0);
    sw_planes_t p;
    assert_int_equal(sw_engine_planes_summary(a, 0, &p), SW_OK);
    assert_int_equal(p.planes, 2);
    assert_int_equal(p.worse, SW_PLANE_LAT);
    assert_false(p.both_rocking);
    sw_engine_destroy(a);
    sw_engine_destroy(b);
    free(ev_lat);
    free(ev_one);
}

static void test_lateral_equals_planar(void **state)
{
    (void)state;
    check_equal_planar(tu_bare(2.0, 0.5));
    check_equal_planar(tu_frame(2.0, 0.5, 250.0, 5.59, 0.1));
    check_equal_planar(tu_cushion(tu_bare(2.0, 0.5), 60.0, 0.05));
}

/* (b) Each plane lifts where the static threshold says, a = g b/h with b
 * its own half-size: a slow ramp k t on both axes lifts the crate of
 * depth 0.5 m across the truck at t = g (0.25/1)/k, and along the truck
 * (width 0.728 m) at g (0.364/1)/k.  For a bare block the uplift time is
 * exact; on a frame the frame's absolute acceleration follows a ramp
 * once the bearings' transient has decayed (as e^(-zeta omega t), here
 * e^(-0.56 * 10) = 4e-3 of k/omega_b in acceleration). */
static void check_threshold(sw_scene_t sc, double tol)
{
    tu_events_t *ev = calloc(1, sizeof *ev);
    assert_non_null(ev);
    sc.depth = 0.5;
    rec_t r = {NULL, ev};
    sw_engine_t *e = make(&sc, 1, 1, &r);
    const double k = 0.02 * G; /* m/s^3 */
    for (int i = 0; i <= 20 * (int)RATE; i++) {
        const double t = i / RATE;
        sw_engine_push_lat(e, t, k * t, k * t, 0.0);
    }
    const double t_lat = G * 0.25 / k, t_long = G * 0.364 / k; /* s: 12.5, 18.2 */
    int seen[SW_PLANES] = {0, 0};
    for (int i = 0; i < ev->n; i++) {
        const sw_event_t *x = &ev->ev[i];
        if (x->kind != SW_EV_UPLIFT || seen[x->plane]++)
            continue;
        tu_near(x->t, x->plane == SW_PLANE_LAT ? t_lat : t_long, tol);
    }
    assert_int_equal(seen[SW_PLANE_LAT] > 0, 1);
    assert_int_equal(seen[SW_PLANE_LONG] > 0, 1);
    sw_engine_destroy(e);
    free(ev);
}

static void test_static_uplift_per_plane(void **state)
{
    (void)state;
    check_threshold(tu_bare(2.0, 0.728), 1e-9);
    check_threshold(tu_frame(2.0, 0.728, 250.0, 5.59, 0.1), 1e-3);
}

/* Pushes half-sines along (ax: amplitude, g) and across (ay) the truck,
 * both from t0_x and t0_y over Tx and Ty seconds, for t_end seconds. */
typedef struct {
    double ax, t0_x, Tx, ay, t0_y, Ty, t_end;
} pulses_t;

static sw_engine_t *run_pulses(const sw_scene_t *sc, const pulses_t *p, tu_events_t *ev)
{
    rec_t r = {NULL, ev};
    sw_engine_t *e = make(sc, 1, 1, &r);
    for (int i = 0; i <= (int)(p->t_end * RATE); i++) {
        const double t = i / RATE;
        sw_engine_push_lat(e, t, half_sine(t, p->t0_x, p->Tx, p->ax * G),
                           half_sine(t, p->t0_y, p->Ty, p->ay * G), 0.0);
    }
    sw_engine_finish(e, 10.0);
    return e;
}

/* (c) The crate 2 m high, 0.728 m long, 0.5 m deep: thresholds 0.364 g
 * along, 0.25 g across.  A 2 g pulse of 1 s overturns it in its plane; a
 * pulse below a plane's threshold never lifts it there. */
static void test_which_plane_overturns(void **state)
{
    (void)state;
    tu_events_t *ev = calloc(1, sizeof *ev);
    assert_non_null(ev);
    sw_scene_t sc = tu_bare(2.0, 0.728);
    sc.depth = 0.5;
    sw_summary_t lo, la;
    sw_planes_t p;

    /* only the lateral plane overturns */
    const pulses_t side = {0.2, 1.0, 1.0, 2.0, 1.0, 1.0, 6.0};
    sw_engine_t *e = run_pulses(&sc, &side, ev);
    sw_engine_summary_plane(e, 0, SW_PLANE_LONG, &lo);
    sw_engine_summary_plane(e, 0, SW_PLANE_LAT, &la);
    assert_false(lo.overturned);
    assert_int_equal(lo.uplifts, 0);
    assert_true(la.overturned);
    sw_engine_planes_summary(e, 0, &p);
    assert_int_equal(p.worse, SW_PLANE_LAT);
    assert_false(p.both_rocking);
    const sw_event_t *ov = tu_first(ev, SW_EV_OVERTURN);
    assert_non_null(ov);
    assert_int_equal(ov->plane, SW_PLANE_LAT);
    sw_engine_destroy(e);

    /* only the longitudinal plane overturns */
    ev->n = 0;
    const pulses_t ahead = {2.0, 1.0, 1.0, 0.1, 1.0, 1.0, 6.0};
    e = run_pulses(&sc, &ahead, ev);
    sw_engine_summary_plane(e, 0, SW_PLANE_LONG, &lo);
    sw_engine_summary_plane(e, 0, SW_PLANE_LAT, &la);
    assert_true(lo.overturned);
    assert_false(la.overturned);
    assert_int_equal(la.uplifts, 0);
    sw_engine_planes_summary(e, 0, &p);
    assert_int_equal(p.worse, SW_PLANE_LONG);
    assert_false(p.both_rocking);
    ov = tu_first(ev, SW_EV_OVERTURN);
    assert_non_null(ov);
    assert_int_equal(ov->plane, SW_PLANE_LONG);
    sw_engine_destroy(e);
    free(ev);
}

/* (c) Both planes lifted at once is flagged, with its span; both planes
 * rocking one after the other is not.  A bare block lifted by an input
 * above its threshold rocks on at least while the input stays above it,
 * so 0.5 g along and 0.4 g across at once lift both together. */
static void test_both_planes_rocking(void **state)
{
    (void)state;
    tu_events_t *ev = calloc(1, sizeof *ev);
    assert_non_null(ev);
    sw_scene_t sc = tu_bare(2.0, 0.728);
    sc.depth = 0.5;
    sw_planes_t p;

    const pulses_t at_once = {0.5, 1.0, 0.5, 0.4, 1.0, 0.5, 12.0};
    sw_engine_t *e = run_pulses(&sc, &at_once, ev);
    sw_engine_planes_summary(e, 0, &p);
    assert_true(p.both_rocking);
    /* the span starts at the later of the two planes' first lifts */
    double lift[SW_PLANES] = {NAN, NAN};
    for (int i = 0; i < ev->n; i++)
        if (ev->ev[i].kind == SW_EV_UPLIFT && isnan(lift[ev->ev[i].plane]))
            lift[ev->ev[i].plane] = ev->ev[i].t;
    assert_false(isnan(lift[SW_PLANE_LONG]) || isnan(lift[SW_PLANE_LAT]));
    assert_true(lift[SW_PLANE_LAT] < lift[SW_PLANE_LONG]); /* the lower threshold first */
    tu_near(p.both_from, lift[SW_PLANE_LONG], 0.0);
    /* it lasts at least while both inputs are above their thresholds:
     * 0.5 sin(pi s/0.5) >= 0.364 until s = 0.5 (1 - asin(0.728)/pi) */
    const double above = 1.0 + 0.5 * (1 - asin(0.364 / 0.5) / M_PI); /* s */
    assert_true(p.both_to >= above - 1.0 / RATE);
    assert_true(p.both_time > 0.0 && p.both_time <= p.both_to - p.both_from + 1e-12);
    sw_engine_destroy(e);

    /* across first, at rest again long before the pulse along */
    ev->n = 0;
    const pulses_t apart = {0.5, 12.0, 0.5, 0.4, 1.0, 0.5, 16.0};
    e = run_pulses(&sc, &apart, ev);
    sw_summary_t la, lo;
    sw_engine_summary_plane(e, 0, SW_PLANE_LAT, &la);
    sw_engine_summary_plane(e, 0, SW_PLANE_LONG, &lo);
    assert_true(la.uplifts > 0 && la.rests > 0);
    assert_true(lo.uplifts > 0);
    sw_engine_planes_summary(e, 0, &p);
    assert_false(p.both_rocking);
    assert_true(isnan(p.both_from) && isnan(p.both_to));
    sw_engine_destroy(e);
    free(ev);
}

/* Both planes' states of package 0, and the uplift events, as reported. */
typedef struct {
    states_t st[SW_PLANES];
    tu_events_t ev;
} both_rec_t;

static void on_both_state(void *user, const sw_output_t *o)
{
    both_rec_t *r = user;
    states_t *s = &r->st[o->plane];
    if (o->pkg == 0 && s->n < MAX_OUT)
        s->o[s->n++] = *o;
}

static void on_both_event(void *user, const sw_event_t *ev)
{
    tu_on_event(&((both_rec_t *)user)->ev, ev);
}

/* Shocks along every 2.3 s and across every 1.7 s (half-sines above each
 * plane's threshold, alternating in sign), so that the planes lift, land
 * and rest over and over, sometimes together and sometimes apart. */
static double shocks(double t, double every, double T, double a)
{
    const double s = fmod(t, every);
    return (fmod(t, 2.0 * every) < every ? 1.0 : -1.0) * half_sine(s, 0.0, T, a);
}

/* (c) The span of both planes lifted, over many overlaps: the same as
 * the definition applied to what the engine reports, sample by sample
 * (both planes' phase rocking at a sample: the time since the later of
 * the previous sample and the two planes' last uplifts counts; the span
 * runs from the first such time to the last such sample).  The engine
 * skips the comparison where no plane had an event; this checks that it
 * loses nothing by it. */
static void test_both_span_over_many_overlaps(void **state)
{
    (void)state;
    both_rec_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    r->st[SW_PLANE_LONG].plane = SW_PLANE_LONG;
    r->st[SW_PLANE_LAT].plane = SW_PLANE_LAT;
    sw_scene_t sc = tu_bare(2.0, 0.728);
    sc.depth = 0.5; /* thresholds 0.364 g along, 0.25 g across */
    sw_engine_opts_t o = {0};
    o.lateral = 1;
    o.on_state = on_both_state;
    o.on_event = on_both_event;
    o.user = r;
    int err;
    char msg[256];
    sw_engine_t *e = sw_engine_create(&sc, 1, &o, &err, msg, sizeof msg);
    assert_non_null(e);
    const states_t *A = &r->st[SW_PLANE_LONG], *B = &r->st[SW_PLANE_LAT];
    double lift[SW_PLANES] = {NAN, NAN}, from = NAN, to = NAN, time = 0.0, t_prev = NAN;
    int k = 0, samples_both = 0, entered = 0, was_both = 0;
    const int n = 30 * (int)RATE;
    for (int i = 0; i <= n; i++) {
        assert_true(sw_engine_push_lat(e, i / RATE, shocks(i / RATE, 2.3, 0.3, 0.42 * G),
                                       shocks(i / RATE, 1.7, 0.2, 0.30 * G), 0.0) >= 0);
        assert_int_equal(A->n, i + 1);
        assert_int_equal(B->n, i + 1);
        const double t = A->o[i].t; /* s */
        assert_memory_equal(&t, &B->o[i].t, sizeof t);
        for (; k < r->ev.n; k++)
            if (r->ev.ev[k].kind == SW_EV_UPLIFT)
                lift[r->ev.ev[k].plane] = r->ev.ev[k].t;
        const int both =
            A->o[i].state.phase == SW_PHASE_ROCKING && B->o[i].state.phase == SW_PHASE_ROCKING;
        if (both) {
            double f = fmax(lift[SW_PLANE_LONG], lift[SW_PLANE_LAT]); /* s */
            if (!isnan(t_prev))
                f = fmax(f, t_prev);
            if (isnan(from))
                from = f;
            to = t;
            time += t > f ? t - f : 0.0;
            samples_both++;
            entered += !was_both;
        }
        was_both = both;
        t_prev = t;
        /* the span as it stands after every sample */
        sw_planes_t p;
        assert_int_equal(sw_engine_planes_summary(e, 0, &p), SW_OK);
        assert_int_equal(p.both_rocking, !isnan(from));
        const double got[] = {p.both_from, p.both_to, p.both_time}, want[] = {from, to, time};
        assert_memory_equal(got, want, sizeof got);
    }
    assert_true(r->ev.n < TU_MAX_EV);
    assert_true(entered >= 10);                         /* many overlaps, */
    assert_true(samples_both < (to - from) * RATE / 2); /* with long gaps between them */
    sw_engine_destroy(e);
    free(r);
}

/* After sw_engine_finish() the two planes' clocks may differ: each
 * settles only while it moves.  A sample one plane's clock refuses is
 * refused whole; neither plane takes it. */
static void test_finish_then_sample(void **state)
{
    (void)state;
    static states_t s_lat;
    s_lat = (states_t){.plane = SW_PLANE_LAT};
    rec_t r = {&s_lat, NULL};
    sw_scene_t sc = tu_bare(2.0, 0.728);
    sc.depth = 0.5;
    sw_engine_t *e = make(&sc, 1, 1, &r);
    /* the plane along rocks at the end (0.5 g against 0.364 g), the
     * plane across stands */
    for (int i = 0; i <= (int)RATE; i++) {
        const double t = i / RATE;
        assert_true(sw_engine_push_lat(e, t, half_sine(t, 0.5, 0.6, 0.5 * G), 0.0, 0.0) >= 0);
    }
    sw_output_t o;
    assert_int_equal(sw_engine_get_output_plane(e, 0, SW_PLANE_LONG, &o), SW_OK);
    assert_int_equal(o.state.phase, SW_PHASE_ROCKING);
    sw_engine_finish(e, 0.5); /* the plane along alone settles, to 1.5 s */
    assert_int_equal(sw_engine_get_output_plane(e, 0, SW_PLANE_LAT, &o), SW_OK);
    tu_near(o.t, 1.0, 0.0);
    const int n = s_lat.n;
    assert_int_equal(sw_engine_push_lat(e, 1.2, 0.0, 0.0, 0.0), SW_EORDER);
    assert_int_equal(s_lat.n, n);
    assert_int_equal(sw_engine_get_output_plane(e, 0, SW_PLANE_LAT, &o), SW_OK);
    tu_near(o.t, 1.0, 0.0);
    /* after both clocks, both take it */
    assert_true(sw_engine_push_lat(e, 1.6, 0.0, 0.0, 0.0) >= 0);
    assert_int_equal(s_lat.n, n + 1);
    assert_int_equal(sw_engine_get_output_plane(e, 0, SW_PLANE_LAT, &o), SW_OK);
    tu_near(o.t, 1.6, 0.0);
    sw_engine_destroy(e);
}

/* The API's edges: no lateral plane without the option or without a
 * depth; a sample without its lateral value is refused by an engine with
 * lateral planes; a bad lateral value refuses the sample whole; the
 * packages keep their indices. */
static void test_api_edges(void **state)
{
    (void)state;
    sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_bare(2.0, 0.728)};
    sc[1].depth = 0.5;
    sw_summary_t s;
    /* without opts.lateral a depth is not read */
    sw_engine_t *e = make(sc, 2, 0, NULL);
    assert_int_equal(sw_engine_planes(e, 1), 1);
    assert_int_equal(sw_engine_summary_plane(e, 1, SW_PLANE_LAT, &s), SW_ENOTFOUND);
    assert_int_equal(sw_engine_push(e, 0.0, 0.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_push_lat(e, 0.001, 0.0, 1.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_push_lat(e, 0.002, 0.0, NAN, 0.0), SW_ENONFINITE);
    sw_engine_destroy(e);

    tu_events_t *ev = calloc(1, sizeof *ev);
    assert_non_null(ev);
    rec_t r = {NULL, ev};
    e = make(sc, 2, 1, &r);
    assert_int_equal(sw_engine_planes(e, 0), 1);
    assert_int_equal(sw_engine_planes(e, 1), 2);
    assert_int_equal(sw_engine_planes(e, 2), 0);
    assert_int_equal(sw_engine_push(e, 0.0, 0.0, 0.0), SW_EINVAL);
    assert_int_equal(sw_engine_push_lat(e, 0.0, 0.0, 0.0, 0.0), SW_OK);
    assert_int_equal(sw_engine_push_lat(e, 0.001, 0.0, INFINITY, 0.0), SW_ENONFINITE);
    assert_int_equal(sw_engine_push_lat(e, 0.001, NAN, 0.0, 0.0), SW_ENONFINITE);
    assert_int_equal(sw_engine_push_lat(e, 0.001, 0.0, 2 * SW_MAX_ACCEL, 0.0), SW_ETOOBIG);
    assert_int_equal(sw_engine_push_lat(e, 0.001, 2 * SW_MAX_ACCEL, 0.0, 0.0), SW_ETOOBIG);
    assert_int_equal(sw_engine_push_lat(e, 0.0, 0.0, 0.0, 0.0), SW_EORDER);
    /* a lateral step above 0.25 g lifts package 1 across, and only it */
    assert_int_equal(sw_engine_push_lat(e, 0.001, 0.0, 0.3 * G, 0.0), SW_EVENT);
    assert_int_equal(ev->n, 1);
    assert_int_equal(ev->ev[0].pkg, 1);
    assert_int_equal(ev->ev[0].plane, SW_PLANE_LAT);
    assert_int_equal(ev->ev[0].kind, SW_EV_UPLIFT);
    sw_output_t o;
    assert_int_equal(sw_engine_get_output_plane(e, 1, SW_PLANE_LAT, &o), SW_OK);
    assert_int_equal(o.pkg, 1);
    assert_int_equal(o.plane, SW_PLANE_LAT);
    assert_true(o.uplift_ratio > 1.0);
    assert_int_equal(sw_engine_get_output_plane(e, 0, SW_PLANE_LAT, &o), SW_ENOTFOUND);
    /* a reload may not add or remove the plane, and may change it */
    char msg[256];
    assert_int_equal(sw_engine_replace(e, 1, &sc[0], msg, sizeof msg), SW_EINVAL);
    assert_non_null(strstr(msg, "package.depth removed"));
    sw_scene_t deeper = sc[1];
    deeper.depth = 0.6;
    assert_int_equal(sw_engine_replace(e, 1, &deeper, msg, sizeof msg), SW_OK);
    assert_int_equal(sw_engine_summary_plane(e, 1, SW_PLANE_LAT, &s), SW_OK);
    assert_int_equal(s.uplifts, 0); /* a fresh summary */
    sw_engine_destroy(e);
    free(ev);
}

/* The gate checks the lateral axis as the longitudinal one: a value not
 * finite or a spike refuses the sample, and a lateral channel that reads
 * gravity for minutes (a vertical axis taken for it) refuses the log,
 * naming --lat-col.  A gate without lateral never reads a_y. */
typedef struct {
    long refused[SW_GATE_NREJ];
} gate_rec_t;

static void on_gate_reject(void *user, const sw_sample_t *s, sw_gate_reject r, const char *text)
{
    (void)s;
    (void)text;
    ((gate_rec_t *)user)->refused[r]++;
}

static void test_gate_lateral_axis(void **state)
{
    (void)state;
    sw_scene_t sc = tu_bare(2.0, 0.728);
    sc.depth = 0.5;
    for (int lateral = 0; lateral <= 1; lateral++) {
        sw_engine_t *e = make(&sc, 1, lateral, NULL);
        gate_rec_t rec = {{0}};
        sw_gate_opts_t go = {.on_reject = on_gate_reject, .user = &rec, .lateral = lateral};
        char msg[200];
        sw_gate_t *g = sw_gate_create(e, &go, msg, sizeof msg);
        assert_non_null(g);
        for (int i = 0; i < 100 * 70; i++) { /* 70 s at 100 Hz */
            sw_sample_t s = {.t = i / 100.0,
                             .a_g = 0.3 * sin(i / 10.0),
                             .a_y = G, /* gravity on the axis read as lateral */
                             .a_max = NAN,
                             .seq = SW_GATE_NO_SEQ,
                             .rx = NAN,
                             .wall = NAN,
                             .where = i};
            if (i == 500)
                s.a_y = NAN;
            if (i == 600)
                s.a_y = 60 * G; /* beyond the default 50 g */
            sw_gate_push(g, &s);
        }
        sw_gate_flush(g);
        sw_gate_facts_t f;
        sw_gate_facts(g, &f);
        char why[320];
        const int r = sw_gate_check(&f, NULL, why, sizeof why);
        if (lateral) {
            assert_int_equal(rec.refused[SW_GATE_REJ_NONFINITE], 1);
            assert_int_equal(rec.refused[SW_GATE_REJ_IMPLAUSIBLE], 1);
            assert_true(f.lateral);
            assert_int_equal(f.lat.above_half_g, f.accepted);
            tu_near(f.lat.peak, G, 0);
            assert_int_equal(r, SW_GATE_REFUSE);
            assert_non_null(strstr(why, "the lateral channel looks like gravity"));
            assert_non_null(strstr(why, "the column or axis of the lateral acceleration"));
        } else {
            assert_int_equal(rec.refused[SW_GATE_REJ_NONFINITE], 0);
            assert_int_equal(rec.refused[SW_GATE_REJ_IMPLAUSIBLE], 0);
            assert_false(f.lateral);
            assert_true(r != SW_GATE_REFUSE);
        }
        sw_gate_destroy(g);
        sw_engine_destroy(e);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lateral_equals_planar),
        cmocka_unit_test(test_static_uplift_per_plane),
        cmocka_unit_test(test_which_plane_overturns),
        cmocka_unit_test(test_both_planes_rocking),
        cmocka_unit_test(test_both_span_over_many_overlaps),
        cmocka_unit_test(test_finish_then_sample),
        cmocka_unit_test(test_api_edges),
        cmocka_unit_test(test_gate_lateral_axis),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
