/* SPDX-License-Identifier: GPL-3.0-or-later */
/* engine.c - the streaming integrator's API and its sample loop: advances
 * every package to each pushed sample, one step at a time with the
 * package's stepper (step.h), asks the event layer for the events inside
 * each step (event.h), hands the timed ones and the cut to the phase
 * machine (pkg.h), and reports the state once per sample.  A package at
 * rest takes its exact solution instead of steps where its model has one
 * (stuck.h), and a rigid one flies in closed form (flight.h).  Every error
 * of the layers below comes back here and faults the package in one
 * place.
 *
 * The layers below are reached through two tables, the scheme's row
 * (scheme_ops.h) and the package's model ops (model_ops.h): nothing here
 * depends on which scheme or which model runs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "event.h"
#include "flight.h"
#include "input.h"
#include "model_ops.h"
#include "numeric.h"
#include "pkg.h"
#include "step.h"
#include "stuck.h"
#include "swaywatch/model.h"
#include "swaywatch/status.h"

#define NO_LAT ((size_t)-1)

/* Both planes of a package lifted at once (sw_planes_t), absolute times. */
typedef struct {
    double from, to;                /* s, NAN: never */
    double time;                    /* s */
    double lift;                    /* s, while both are lifted: the later plane's lift */
    const sw_pkg_t *along, *across; /* the package's two planes */
} sw_both_t;

struct sw_engine {
    size_t n;
    sw_pkg_t *pk;
    sw_engine_opts_t o;
    sw_step_ctx_t sc; /* what the step and event layers share: the scheme, its options */
    sw_pkg_ctx_t pc;  /* what the packages share: where their events go */
    int stuck_exact;  /* a stuck frame takes its exact solution (the scheme allows it) */
    int started;
    int restart;        /* the next sample starts afresh: packages at rest, no bridge */
    int origin_set;     /* sw_engine_set_origin(): pc.origin is not the first sample's time */
    double t;           /* s, time of the last sample, relative to pc.origin */
    double t_abs;       /* s, the same as the caller gave it */
    double ag, az;      /* m/s^2, last sample */
    sw_input_t in;      /* input over the interval being integrated */
    double dt_req;      /* s, the step asked for (sw_engine_dt_requested) */
    sw_engine_t *check; /* the default scheme and step beside it (opts.check_default) */
    const volatile sig_atomic_t *stop; /* the caller's: ends sw_engine_finish() early */
    /* the lateral planes (opts.lateral, the scenes with a depth): an engine
     * of their own, whose package j is package lat_pkg[j] here */
    sw_engine_t *lat;
    size_t *lat_of;   /* n: a package's index in lat, or NO_LAT */
    size_t *lat_pkg;  /* lat->n */
    sw_both_t *both;  /* lat->n: both planes lifted at once */
    double t_both;    /* s, absolute: the last sample the planes were compared at */
    sw_both_t **open; /* lat->n: the packages lifted in both at t_both, n_open of them */
    size_t n_open;
    int both_stale; /* a phase may have changed with no event: compare every package */
    int apart;      /* the two engines' clocks may differ (finish, a refused advance) */
};

/* No span of both planes lifted yet. */
static void both_clear(sw_both_t *b)
{
    b->from = b->to = NAN;
    b->time = 0.0;
}

/* ---- the sample loop ----------------------------------------------------- */

/* Every v[i] finite?  0 v is 0 for a finite v and NaN for an infinite or
 * NaN one, so the sum of them is 0 exactly when all are finite: two
 * multiply-adds a number and no branch, in two chains that overlap (the
 * state and the report are checked on every step and sample): the
 * engine's last line of defence, its own. */
static inline int all_finite(const double v[], size_t n)
{
    double s0 = 0.0, s1 = 0.0;
    size_t i = 0;
    for (; i + 1 < n; i += 2) {
        s0 += 0.0 * v[i];
        s1 += 0.0 * v[i + 1];
    }
    if (i < n)
        s0 += 0.0 * v[i];
    return s0 + s1 == 0.0;
}

/* The state is still inside the model: finite, and a rocking package not
 * turned beyond half a turn (a step may overshoot pi/2 slightly before the
 * overturn event cuts it; one that lands beyond pi computed garbage, and its
 * numbers must not reach the summary). */
static int finite_state(const sw_pkg_t *P, const double y[])
{
    return all_finite(y, (size_t)P->m.n) &&
           !(P->m.phase == SW_PHASE_ROCKING && fabs(y[P->m.ith]) > M_PI);
}

/* An error ends the interval: the package is left at t1, and faults at
 * t (the engine's one fault exit, advance_pkg). */
static int failed(sw_pkg_t *P, double t1, double t, int code, double *tf)
{
    P->t = t1;
    *tf = t;
    return code;
}

/* The input at t for package P: the engine's value at an end of the
 * interval (X) when t is one, else evaluated there. */
static inline sw_input_at_t input_at(const sw_pkg_t *P, const sw_input_ends_t *X, double t)
{
    if (t == X->t[0])
        return X->u[0];
    if (t == X->t[1])
        return X->u[1];
    return sw_input_at(P->m.in, P->m.g, t);
}

/* Advance one package on its support from P->t to t1 under the input
 * e->in (X: its values at the interval's ends).  The loop guards against
 * a map that keeps re-triggering without progress and against a step
 * count no finite number of events explains; either is a fault, never a
 * hang.  SW_OK, or the error at *tf that ends
 * the interval (the package is then at t1, to fault).  (Longer than 80
 * lines: the loop is the engine's one control flow, and splitting it
 * would hide the order of its cases.) */
static SW_ALWAYS_INLINE int advance_ground(sw_engine_t *e, sw_pkg_t *P, double t1,
                                           const sw_input_ends_t *X, double *tf)
{
    sw_step_ctx_t *C = &e->sc;
    sw_pkg_ctx_t *E = &e->pc;
    sw_stepper_t *W = &P->st;
    double y1[SW_NMAX];
    int guard = 0, same_t = 0, checked = 0;
    while (P->t < t1) {
        if (++guard > 100000000) /* cannot happen with a finite event count */
            return failed(P, t1, P->t, SW_EFAULT, tf);
        if (P->m.phase == SW_PHASE_OVERTURNED)
            break;
        if (P->m.phase == SW_PHASE_STUCK && P->m.ops->stands) {
            int side = 0;
            const int r = sw_stuck_advance[P->m.ops->stands](P, X, t1, e->stuck_exact, &side);
            if (r == SW_STUCK_STILL)
                break;
            if (r == SW_STUCK_MOVED)
                continue;
            if (r == SW_STUCK_FAULT)
                return failed(P, t1, P->t, SW_EFAULT, tf);
            if (r == SW_STUCK_LIFT) {
                sw_pkg_start_rocking(E, P, P->t, NULL, side);
                continue;
            }
        }
        const double t0 = P->t, rem = t1 - t0;
        double h;
        if (!checked) {
            const sw_input_at_t u0 = input_at(P, X, t0), u1 = input_at(P, X, t1);
            if (sw_step_input_unstable(C, W, &u0, &u1))
                return failed(P, t1, t0, SW_EUNSTABLE, tf);
            checked = 1;
        }
        const int st = W->advance(C, W, t0, P->y, t1, y1, &h);
        if (st != SW_OK)
            return failed(P, t1, t0, st, tf);
        P->sum.steps++;
        P->h_used = sw_max2(P->h_used, h);
        if (!finite_state(P, y1))
            return failed(P, t1, t0, SW_EFAULT, tf);
        W->step_y1 = y1;
        W->step_h = h;
        sw_timed_t cut; /* a cut's time, the state and the input there */
        sw_timed_t timed[SW_MAX_CANDS];
        int nt;
        const int ev = sw_event_find(C, W, X, t0, h, P->y, y1, &cut, timed, &nt);
        P->m.held = 0;
        if (ev == SW_EVF_NONE) {
            memcpy(P->y, y1, sizeof(double) * (size_t)P->m.n);
            P->t = (h == rem) ? t1 : t0 + h;
            sw_pkg_stepped(E, P, timed, nt, SW_EVF_NONE, NULL);
            continue;
        }
        same_t = cut.t - t0 <= 1e-12 * fmax(1.0, fabs(t0)) ? same_t + 1 : 0;
        if (same_t > 64) { /* a map that keeps re-triggering without progress */
            sw_pkg_timed(E, P, timed, nt);
            return failed(P, t1, t0, SW_EFAULT, tf);
        }
        memcpy(P->y, cut.y, sizeof(double) * (size_t)P->m.n);
        P->t = cut.t;
        sw_pkg_stepped(E, P, timed, nt, ev, &cut.u);
        sw_step_restart(W); /* the map changed the state: the scheme's history is gone */
    }
    P->t = t1;
    return SW_OK;
}

/* The first time in [t0, t1] at which g_eff = g + a_z falls to 0 (the bed
 * falls away faster than gravity; linear between samples), or INFINITY. */
static double take_off_time(const sw_pkg_t *P, const sw_input_ends_t *X, double t0, double t1)
{
    const double g0 = input_at(P, X, t0).ge, g1 = input_at(P, X, t1).ge; /* m/s^2 */
    if (!(g0 > 0.0))
        return t0;
    if (g1 > 0.0)
        return INFINITY;
    const double t = t0 + (t1 - t0) * (g0 / (g0 - g1));
    return t < t1 ? t : t1;
}

/* A model whose equations hold in the air (a cushion's): its flights
 * timed as the spans of g_eff <= 0 in [t0, t1] (the bed falling away
 * faster than gravity), for the summary; P->m.flying and P->fl_t0 say one
 * is going on.  Its support holds it horizontally in the air too
 * (physics.md): a long flight is where that is doubtful. */
static void time_in_air(sw_pkg_ctx_t *C, sw_pkg_t *P, const sw_input_ends_t *X, double t0,
                        double t1)
{
    const double g0 = input_at(P, X, t0).ge, g1 = input_at(P, X, t1).ge;       /* m/s^2 */
    const double tz = g0 != g1 ? t0 + (t1 - t0) * (g0 / (g0 - g1)) : INFINITY; /* g_eff = 0 */
    if (!P->m.flying && (!(g0 > 0.0) || !(g1 > 0.0))) {
        P->m.flying = 1;
        P->fl_long = 0;
        P->fl_t0 = g0 > 0.0 ? tz : t0;
        P->sum.flights++;
    }
    if (P->m.flying && g1 > 0.0) {
        const double end = g0 > 0.0 ? t0 : tz, dur = end - P->fl_t0; /* s */
        sw_flight_note(C, P, dur);
        P->m.flying = 0;
        P->sum.flight_max = sw_max2(P->sum.flight_max, dur);
    } else if (P->m.flying) {
        sw_flight_note(C, P, t1 - P->fl_t0);
    }
}

/* Advance one package from P->t toward t1 through take-offs and flights
 * (flight.c), for a model that flies, or with its flights timed, for one
 * whose equations hold in the air; for one that does neither, g_eff <= 0
 * is outside the model: an error.  SW_OK with P at t1, or the error at
 * *tf that stopped it: P is then at t1, or where the support segment
 * before a take-off ended (it takes off from there once it has faulted).
 * The input at the interval's ends is evaluated here, once. */
static int advance_flying(sw_engine_t *e, sw_pkg_t *P, double t1, double *tf)
{
    sw_pkg_ctx_t *C = &e->pc;
    const sw_input_ends_t E = {
        .t = {P->t, t1},
        .u = {sw_input_at(P->m.in, P->m.g, P->t), sw_input_at(P->m.in, P->m.g, t1)}};
    const sw_input_ends_t *X = &E;
    for (int guard = 0; P->t < t1 && P->m.phase != SW_PHASE_OVERTURNED; guard++) {
        if (guard > 1000000) /* take-offs and landings without progress */
            return failed(P, t1, P->t, SW_EFAULT, tf);
        if (P->m.ops->flies == SW_FLIES_INTEGRATED) {
            time_in_air(C, P, X, P->t, t1);
            return advance_ground(e, P, t1, X, tf);
        }
        if (P->m.flying) {
            const int still = sw_flight_advance(C, P, t1) == SW_STUCK_STILL;
            if (P->m.flying)
                sw_flight_note(C, P, P->t - P->fl_t0);
            if (still)
                break;
            continue;
        }
        const double toff = take_off_time(P, X, P->t, t1); /* s */
        if (toff <= P->t) {
            if (!P->m.ops->flies)
                return failed(P, t1, P->t, SW_EFAULT, tf);
            sw_flight_take_off(C, P, P->t);
            continue;
        }
        const double tg = sw_min2(toff, t1); /* s */
        const int rc = advance_ground(e, P, tg, X, tf);
        if (rc != SW_OK || !(toff < t1))
            return rc;
        P->t = toff; /* g_eff is 0 here: it takes off next */
    }
    P->t = t1;
    return SW_OK;
}

/* The one way a package faults: the phase machine puts it at rest and
 * says so (SW_EV_FAULT), and its scheme's error control starts afresh. */
static void fault(sw_engine_t *e, sw_pkg_t *P, double t, int code)
{
    sw_pkg_fault(&e->pc, P, t, code);
    sw_step_forget(&P->st);
}

/* Advance one package from P->t to t1: on its support, and in free flight
 * while the bed falls away from it.  The input is evaluated at the
 * interval's two ends here (or, for a package that flies or may, in
 * advance_flying), once, and handed to the tests there (the take-off,
 * the step layer's input check).  Every error of the layers below comes
 * back here and faults the package; the interval goes on from where the
 * error left it (a segment on the support before a take-off). */
static void advance_pkg(sw_engine_t *e, sw_pkg_t *P, double t1)
{
    double tf; /* s, where an error happened */
    int rc;
    if (!P->m.flying && P->m.ops->flies != SW_FLIES_INTEGRATED) {
        const sw_input_ends_t X = {
            .t = {P->t, t1},
            .u = {sw_input_at(P->m.in, P->m.g, P->t), sw_input_at(P->m.in, P->m.g, t1)}};
        /* the bed does not fall away in [t, t1] (g_eff is linear between
         * samples): on the support throughout, the common case */
        rc = X.u[0].ge > 0.0 && X.u[1].ge > 0.0 ? advance_ground(e, P, t1, &X, &tf)
                                                : advance_flying(e, P, t1, &tf);
    } else {
        rc = advance_flying(e, P, t1, &tf);
    }
    while (rc != SW_OK) {
        fault(e, P, tf, rc);
        if (!(P->t < t1))
            break;
        rc = advance_flying(e, P, t1, &tf); /* from the end of a segment before a take-off */
    }
    P->t = t1;
}

/* Every number of an output, finite?  Inline: checked on every report. */
static inline int output_finite(const sw_output_t *o)
{
    const double v[] = {
        o->t,       o->state.u,     o->state.u_dot, o->state.theta,  o->state.theta_dot,
        o->state.z, o->state.z_dot, o->margin,      o->margin_bound, o->uplift_ratio,
        o->a_g,     o->a_support};
    return all_finite(v, sizeof v / sizeof v[0]);
}

int sw_output_finite(const sw_output_t *o)
{
    return output_finite(o);
}

/* A report with a non-finite number at t: the package faults and is
 * reported at rest instead, under the input at t.  Out of line: the
 * report of every sample stays lean. */
static SW_NOINLINE void report_fault(sw_engine_t *e, sw_pkg_t *P, double t, sw_output_t *o)
{
    fault(e, P, t, SW_EFAULT);
    const sw_input_at_t u = sw_input_at(P->m.in, P->m.g, t);
    sw_model_output(&P->m, &P->scr, &u, t, P->y, o);
}

static void report_states(sw_engine_t *e, double t)
{
    for (size_t i = 0; i < e->n; i++) {
        sw_pkg_t *P = &e->pk[i];
        sw_output_t o;
        if ((e->o.outcome_only || e->o.margins_off) && !e->o.on_state) {
            /* no one reads the report (its margins cost about a step):
             * only the last line of defence, on y itself (each component
             * of y is a number of the state, and the state's others are 0) */
            if (!all_finite(P->y, (size_t)P->m.n))
                fault(e, P, t, SW_EFAULT);
            continue;
        }
        /* the input at the sample, evaluated here (the engine owns its
         * time) and handed to the report */
        const sw_input_at_t u = sw_input_at(P->m.in, P->m.g, t);
        sw_model_output(&P->m, &P->scr, &u, t, P->y, &o);
        /* Last line of defence: a non-finite number is never reported; the
         * package faults and is reported at rest instead. */
        if (!output_finite(&o))
            report_fault(e, P, t, &o);
        o.pkg = i;
        o.t = e->pc.origin + t;
        if (o.margin < P->sum.min_margin)
            P->sum.min_margin = o.margin;
        if (o.margin_bound < P->sum.min_margin_bound)
            P->sum.min_margin_bound = o.margin_bound;
        if (o.uplift_ratio > P->sum.max_uplift_ratio)
            P->sum.max_uplift_ratio = o.uplift_ratio;
        if (e->o.on_state)
            e->o.on_state(e->o.user, &o);
    }
}

/* ---- building packages ----------------------------------------------------- */

static void pkg_reset(sw_pkg_t *P)
{
    sw_pkg_rest(P);
    P->t = 0.0;
    P->st.h_adapt = P->st.h;
    P->h_used = 0.0;
    memset(&P->sum, 0, sizeof P->sum);
    snprintf(P->sum.name, sizeof P->sum.name, "%s", P->scene.name);
    P->sum.model = P->m.d.model;
    P->sum.overturn_time = P->sum.tip_time = P->sum.uplift_time = NAN;
    P->sum.flight_long_time = NAN;
    P->sum.min_margin = P->sum.min_margin_bound = 1.0;
    /* A reset engine runs as a new one: nothing of an earlier run (the
     * stuck frame's coefficients of its last interval) changes a bit of
     * the next. */
    memset(P->nj_cache, 0, sizeof P->nj_cache);
    sw_step_reset(&P->st);
}

/* Build package number index of e from scene into P (zeroed), for the
 * engine's scheme and options.  On failure msg says why; P may hold work
 * space to free with sw_step_free(). */
static int pkg_init(sw_engine_t *e, sw_pkg_t *P, const sw_scene_t *scene, size_t index, char *msg,
                    size_t msglen)
{
    P->scene = *scene;
    if (sw_scene_validate(&P->scene, &P->m.d, NULL, NULL, NULL) != SW_OK) {
        if (msg && msglen)
            snprintf(msg, msglen, "scene '%s' is not valid", scene->name);
        return SW_EINVAL;
    }
    sw_model_setup(&P->m, &P->scr, &P->scene);
    P->index = index;
    P->m.in = &e->in;
    const double dt = e->o.dt > 0.0 ? e->o.dt : e->sc.scheme->default_dt; /* s */
    return sw_step_init(&e->sc, &P->st, &P->m, &P->scr, P->scene.name, dt, e->o.rtol, e->o.atol,
                        msg, msglen);
}

/* ---- public API ------------------------------------------------------- */

void sw_engine_reset(sw_engine_t *e)
{
    if (!e)
        return;
    e->started = 0;
    e->restart = 0;
    e->origin_set = 0;
    e->t = e->t_abs = NAN;
    e->pc.origin = 0.0;
    e->ag = e->az = 0.0;
    memset(&e->in, 0, sizeof e->in);
    for (size_t i = 0; i < e->n; i++) pkg_reset(&e->pk[i]);
    sw_engine_reset(e->check);
    sw_engine_reset(e->lat);
    e->t_both = NAN;
    e->n_open = 0;
    e->both_stale = 1;
    e->apart = 0;
    if (e->lat)
        for (size_t j = 0; j < e->lat->n; j++) both_clear(&e->both[j]);
}

void sw_engine_destroy(sw_engine_t *e)
{
    if (!e)
        return;
    for (size_t i = 0; i < e->n; i++) sw_step_free(&e->pk[i].st);
    sw_engine_destroy(e->check);
    sw_engine_destroy(e->lat);
    free(e->lat_of);
    free(e->lat_pkg);
    free(e->both);
    free(e->open);
    free(e->pk);
    free(e);
}

static int fail(int *err, int code, char *msg, size_t msglen, const char *text)
{
    if (err)
        *err = code;
    if (msg && msglen)
        snprintf(msg, msglen, "%s", text);
    return code;
}

/* The scheme when none is asked for: rk4 at its default step, unless a
 * cushion is stiff, omega_max dt > 0.05 (a landing on the cushion then
 * lasts fewer than about 20 fixed steps and rk4's error there grows to
 * 1e-5..1e-3 rad); then GSL's adaptive rkck, which was the fastest for a
 * given accuracy on every stiff cushion measured, ahead of the implicit
 * schemes and far ahead of sub-stepped rk4 (docs/cushion.md).  A forced dt
 * keeps rk4, so that the dt is honoured or refused. */
static const char *default_scheme(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *o)
{
    if (o->dt_forced)
        return SW_DEFAULT_SCHEME;
    const double dt = o->dt > 0.0 ? o->dt : SW_DEFAULT_DT; /* s */
    for (size_t i = 0; i < n; i++) {
        sw_derived_t d;
        if (sw_scene_validate(&scenes[i], &d, NULL, NULL, NULL) != SW_OK)
            continue;
        if (sw_model_stiff(&d, dt))
            return SW_STIFF_SCHEME;
    }
    return SW_DEFAULT_SCHEME;
}

/* --accuracy: the scheme and step of the measured table, for every scene. */
static int resolve_accuracy(sw_engine_t *e, const sw_scene_t *scenes, size_t n, int *err, char *msg,
                            size_t msglen)
{
    char buf[512];
    if (e->o.scheme || e->o.dt != 0.0 || !(e->o.accuracy > 0.0))
        return fail(err, SW_EINVAL, msg, msglen,
                    "accuracy must be > 0 and chooses the scheme and the step: give it "
                    "without scheme and dt");
    size_t bad = 0;
    const int r = sw_scheme_for_accuracy_n(scenes, n, e->o.accuracy, &e->o.scheme, &e->o.dt, &bad);
    if (r != SW_OK) {
        snprintf(buf, sizeof buf, "accuracy %g rad, scene '%s': %s", e->o.accuracy,
                 scenes[bad].name,
                 r == SW_ENOTFOUND ? "tighter than any measured setting reaches (about "
                                     "1e-14 rad); choose the scheme rk8pd and rtol instead"
                                   : "no measured table for this model; choose the scheme "
                                     "and dt or rtol instead");
        return fail(err, r, msg, msglen, buf);
    }
    e->o.dt_forced = 0;
    e->o.accuracy = 0.0; /* resolved: e->o now names the scheme */
    e->sc.hmax = SW_ACCURACY_HMAX;
    return SW_OK;
}

/* The engine the same scenes get with no scheme and no dt (the default
 * scheme, or the stiff one; its step), beside e when e integrates
 * otherwise, outcome only and without callbacks; left out when e's
 * scheme, steps and tolerances are the default's, or if it cannot be made
 * (e then runs unchecked: sw_engine_checker is NULL). */
static void make_check(sw_engine_t *e, const sw_scene_t *scenes, size_t n)
{
    const sw_engine_opts_t d = {
        .rest_eps = e->o.rest_eps, .stuck_stepped = e->o.stuck_stepped, .outcome_only = 1};
    sw_engine_t *c = sw_engine_create(scenes, n, &d, NULL, NULL, 0);
    if (!c)
        return;
    int same = c->sc.scheme == e->sc.scheme &&
               (!e->sc.scheme->adaptive || (!(e->o.rtol > 0.0) && !(e->o.atol > 0.0)));
    for (size_t i = 0; same && i < n; i++) same = c->pk[i].st.h == e->pk[i].st.h;
    if (same)
        sw_engine_destroy(c);
    else
        e->check = c;
}

/* ---- the lateral planes --------------------------------------------------- */

/* The lateral engine's callbacks: its package and plane said as the
 * engine it serves knows them, to the caller's callbacks. */
static void lat_event(void *user, const sw_event_t *ev)
{
    const sw_engine_t *e = user;
    sw_event_t v = *ev;
    v.pkg = e->lat_pkg[ev->pkg];
    v.plane = SW_PLANE_LAT;
    if (e->o.on_event)
        e->o.on_event(e->o.user, &v);
}

static void lat_state(void *user, const sw_output_t *out)
{
    const sw_engine_t *e = user;
    sw_output_t o = *out;
    o.pkg = e->lat_pkg[out->pkg];
    o.plane = SW_PLANE_LAT;
    e->o.on_state(e->o.user, &o);
}

/* The lateral planes of the scenes with a depth: an engine of the
 * lateral scenes (sw_scene_lateral) with the caller's options, so that
 * each plane integrates exactly as an engine of its scene alone would.
 * Allocates here, once; nothing when no scene has a depth. */
static int make_lateral(sw_engine_t *e, const sw_scene_t *scenes, size_t n,
                        const sw_engine_opts_t *opts, int *err, char *msg, size_t msglen)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++) m += sw_scene_has_depth(&scenes[i]) != 0;
    if (m == 0)
        return SW_OK;
    sw_scene_t *lat = calloc(m, sizeof *lat);
    e->lat_of = calloc(n, sizeof *e->lat_of);
    e->lat_pkg = calloc(m, sizeof *e->lat_pkg);
    e->both = calloc(m, sizeof *e->both);
    e->open = calloc(m, sizeof *e->open);
    if (!lat || !e->lat_of || !e->lat_pkg || !e->both || !e->open) {
        free(lat);
        return fail(err, SW_ENOMEM, msg, msglen, "out of memory");
    }
    for (size_t i = 0, j = 0; i < n; i++) {
        e->lat_of[i] = NO_LAT;
        if (sw_scene_lateral(&scenes[i], &lat[j]) != SW_OK)
            continue;
        e->lat_of[i] = j;
        e->lat_pkg[j++] = i;
    }
    sw_engine_opts_t o = *opts;
    o.lateral = 0;
    o.user = e;
    o.on_event = lat_event;
    o.on_state = opts->on_state ? lat_state : NULL;
    int r = SW_OK;
    char buf[512];
    e->lat = sw_engine_create(lat, m, &o, &r, buf, sizeof buf);
    free(lat);
    if (!e->lat) {
        char text[600];
        snprintf(text, sizeof text, "across the truck: %s", buf);
        return fail(err, r, msg, msglen, text);
    }
    for (size_t j = 0; j < m; j++) {
        e->both[j].along = &e->pk[e->lat_pkg[j]];
        e->both[j].across = &e->lat->pk[j];
    }
    return SW_OK;
}

/* Off its support since a lift: rocking (a rigid package's phase), and
 * not back at rest since its last lift (a cushion's t_lift, which a
 * rigid package keeps after its rest). */
static inline int lifted(const sw_pkg_t *P)
{
    return P->m.phase == SW_PHASE_ROCKING && !isnan(P->m.t_lift);
}

/* Compare the planes at the sample just taken (absolute time t): a
 * package lifted in both (lifted(): not at rest, not overturned)
 * extends its span.  Each plane's lift time is exact; the end of an
 * overlap is seen at the samples.  Every package compared; those lifted
 * in both kept in e->open for track_sample(). */
static void track_both(sw_engine_t *e, double t)
{
    const sw_engine_t *L = e->lat;
    e->n_open = 0;
    for (size_t j = 0; j < L->n; j++) {
        sw_both_t *b = &e->both[j];
        if (!lifted(b->along) || !lifted(b->across))
            continue;
        b->lift = fmax(e->pc.origin + b->along->m.t_lift, L->pc.origin + b->across->m.t_lift);
        const double from = isnan(e->t_both) ? b->lift : fmax(b->lift, e->t_both); /* s */
        if (isnan(b->from))
            b->from = from;
        b->to = t;
        b->time += t > from ? t - from : 0.0;
        e->open[e->n_open++] = b;
    }
    e->t_both = t;
    e->both_stale = 0;
}

/* track_both() after a sample, cheaply where it can be: a package starts
 * to rock, or rocks again after a landing, only with an event (its
 * uplift), so after a sample with no event in either plane only the
 * packages lifted in both at the last sample can be, with the same lift
 * times.  They are looked at (a landing held for a step stops rocking
 * with no event) and their spans extended as track_both() would (b->lift
 * and t_both are not NAN there, so fmax() is a comparison). */
static SW_ALWAYS_INLINE void track_sample(sw_engine_t *e, double t)
{
    if (e->pc.events | e->lat->pc.events | e->both_stale) {
        track_both(e, t);
        return;
    }
    for (size_t k = 0; k < e->n_open; k++)
        if (!lifted(e->open[k]->along) || !lifted(e->open[k]->across)) {
            track_both(e, t);
            return;
        }
    const double t_last = e->t_both; /* s */
    for (size_t k = 0; k < e->n_open; k++) {
        sw_both_t *b = e->open[k];
        const double from = b->lift > t_last ? b->lift : t_last; /* s */
        b->to = t;
        b->time += t > from ? t - from : 0.0;
    }
    e->t_both = t;
}

sw_engine_t *sw_engine_create(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *opts,
                              int *err, char *msg, size_t msglen)
{
    char buf[512];
    if (err)
        *err = SW_OK;
    if (msg && msglen)
        msg[0] = '\0';
    if (!scenes || n == 0) {
        fail(err, SW_EINVAL, msg, msglen, "no scene");
        return NULL;
    }
    sw_engine_t *e = calloc(1, sizeof *e);
    if (!e || !(e->pk = calloc(n, sizeof *e->pk))) {
        free(e);
        fail(err, SW_ENOMEM, msg, msglen, "out of memory");
        return NULL;
    }
    e->n = n;
    if (opts)
        e->o = *opts;
    /* a scheme or a dt chosen by the caller (not by the accuracy table) */
    const int check = e->o.check_default && (e->o.scheme || e->o.dt > 0.0);
    if (e->o.accuracy != 0.0 && resolve_accuracy(e, scenes, n, err, msg, msglen) != SW_OK)
        goto out_fail;
    const sw_scheme_t *S =
        sw_scheme_lookup(e->o.scheme ? e->o.scheme : default_scheme(scenes, n, &e->o));
    if (!S) {
        snprintf(buf, sizeof buf, "unknown scheme '%s'", e->o.scheme);
        fail(err, SW_ENOTFOUND, msg, msglen, buf);
        goto out_fail;
    }
    if (e->o.dt < 0.0 || !isfinite(e->o.dt) || e->o.rtol < 0.0 || e->o.atol < 0.0 ||
        e->o.rest_eps < 0.0) {
        fail(err, SW_EINVAL, msg, msglen, "dt, rtol, atol and rest_eps must be >= 0");
        goto out_fail;
    }
    const double hmax = e->sc.hmax > 0.0 ? e->sc.hmax : INFINITY; /* s */
    e->sc = (sw_step_ctx_t){
        .scheme = S, .hmax = hmax, .dt_forced = e->o.dt_forced, .outcome_only = e->o.outcome_only};
    e->pc = (sw_pkg_ctx_t){.rest_eps = e->o.rest_eps > 0.0 ? e->o.rest_eps : 1e-9,
                           .on_event = e->o.on_event,
                           .user = e->o.user};
    e->stuck_exact = S->exact_stuck && !e->o.stuck_stepped;
    e->dt_req = e->o.dt > 0.0 ? e->o.dt : S->default_dt;
    for (size_t i = 0; i < n; i++) {
        buf[0] = '\0';
        const int r = pkg_init(e, &e->pk[i], &scenes[i], i, buf, sizeof buf);
        if (r != SW_OK) {
            fail(err, r, msg, msglen, buf);
            goto out_fail;
        }
    }
    if (check)
        make_check(e, scenes, n);
    if (e->o.lateral && make_lateral(e, scenes, n, opts, err, msg, msglen) != SW_OK)
        goto out_fail;
    sw_engine_reset(e);
    return e;
out_fail:
    sw_engine_destroy(e);
    return NULL;
}

/* A first sample already beyond the threshold lifts a standing package at
 * once. */
static void initial_uplift(sw_engine_t *e, sw_pkg_t *P, double t)
{
    P->t = t;
    if (!(sw_input_geff(P->m.in, P->m.g, t) > 0.0) && P->m.ops->flies != SW_FLIES_INTEGRATED) {
        if (P->m.phase == SW_PHASE_OVERTURNED || P->m.flying)
            return;
        if (P->m.ops->flies)
            sw_flight_take_off(&e->pc, P, t);
        else
            fault(e, P, t, SW_EFAULT);
        return;
    }
    if (P->m.phase != SW_PHASE_STUCK)
        return;
    const sw_input_at_t u = sw_input_at(P->m.in, P->m.g, t);
    const int side = P->m.ops->uplift_side(&P->m, &u, P->y);
    if (side)
        sw_pkg_start_rocking(&e->pc, P, t, &u, side);
}

/* The stream starts (or starts again, after sw_engine_restart()) at t
 * (relative): every package from its state at t, with no input before. */
static void start_at(sw_engine_t *e, double t, double ag, double az)
{
    e->started = 1;
    e->t = t;
    e->ag = ag;
    e->az = az;
    e->in = (sw_input_t){.t0 = t, .ag0 = ag, .az0 = az};
    for (size_t i = 0; i < e->n; i++) initial_uplift(e, &e->pk[i], t);
}

/* A time whose own resolution is coarse (an absolute time of 1.7e15 s, a
 * microsecond clock read as seconds, has steps of 0.25 s) cannot be
 * integrated on: refused, never a hang.  Below 2^33 s (272 years) the steps
 * of a double are at most 2e-6 s, and the engine, which runs on time
 * relative to its first sample, sees every sample after the last. */
static inline int coarse_time(double t_abs)
{
    return !(fabs(t_abs) < 8589934592.0);
}

/* The numbers of a sample: finite, and accelerations (m/s^2) within what
 * a sample may hold.  Not finite comes first, whichever value it is. */
static SW_ALWAYS_INLINE int sample_ok(double t_abs, double a_g, double a_z)
{
    if (!isfinite(t_abs) || !isfinite(a_g) || !isfinite(a_z))
        return SW_ENONFINITE;
    if (fabs(a_g) > SW_MAX_ACCEL || fabs(a_z) > SW_MAX_ACCEL)
        return SW_ETOOBIG;
    return SW_OK;
}

/* May e take a sample at t_abs (s, finite)?  The first one, any time the
 * clock resolves (after the origin, if one was set); a later one, after
 * the last, also once made relative. */
static SW_ALWAYS_INLINE int time_ok(const sw_engine_t *e, double t_abs)
{
    if (!e->started) {
        if (coarse_time(t_abs))
            return SW_ERESOLUTION;
        return e->origin_set && !(t_abs - e->pc.origin >= 0.0) ? SW_EORDER : SW_OK;
    }
    if (!(t_abs > e->t_abs))
        return SW_EORDER;
    if (coarse_time(t_abs))
        return SW_ERESOLUTION;
    /* Rounding keeps the order but not the difference: two absolute times
     * closer than the relative time's resolution are one time here. */
    return t_abs - e->pc.origin > e->t ? SW_OK : SW_EORDER;
}

/* Take an accepted sample that follows the last one: every package
 * advanced over the interval (relative time t, span since the last
 * sample, both s) with the input linear between the two samples (the
 * vertical one's slope az_slope, m/s^3, given: two planes share it),
 * the states reported. */
static SW_ALWAYS_INLINE int take_next(sw_engine_t *e, double t_abs, double t, double span,
                                      double a_g, double a_z, double az_slope)
{
    e->pc.events = 0;
    e->t_abs = t_abs;
    e->in = (sw_input_t){.t0 = e->t,
                         .ag0 = e->ag,
                         .ag_slope = (a_g - e->ag) / span,
                         .az0 = e->az,
                         .az_slope = az_slope};
    for (size_t i = 0; i < e->n; i++) advance_pkg(e, &e->pk[i], t);
    e->t = t;
    e->ag = a_g;
    e->az = a_z;
    e->in = (sw_input_t){.t0 = t, .ag0 = a_g, .az0 = a_z};
    report_states(e, t);
    return e->pc.events ? SW_EVENT : SW_OK;
}

/* Take a sample sample_ok() and time_ok() accepted: the stream starts
 * (or starts again) there, or goes on to it. */
static SW_ALWAYS_INLINE int take(sw_engine_t *e, double t_abs, double a_g, double a_z)
{
    if (!e->started) {
        e->pc.events = 0;
        if (!e->origin_set)
            e->pc.origin = t_abs;
        const double t = e->origin_set ? t_abs - e->pc.origin : 0.0; /* s, relative */
        e->t_abs = t_abs;
        start_at(e, t, a_g, a_z);
        report_states(e, t);
        return e->pc.events ? SW_EVENT : SW_OK;
    }
    const double t = t_abs - e->pc.origin; /* s, relative */
    if (e->restart) {
        e->pc.events = 0;
        e->t_abs = t_abs;
        e->restart = 0;
        start_at(e, t, a_g, a_z);
        report_states(e, t);
        return e->pc.events ? SW_EVENT : SW_OK;
    }
    const double span = t - e->t; /* s */
    return take_next(e, t_abs, t, span, a_g, a_z, (a_z - e->az) / span);
}

static SW_ALWAYS_INLINE int push(sw_engine_t *e, double t_abs, double a_g, double a_z)
{
    int rc = sample_ok(t_abs, a_g, a_z);
    if (rc == SW_OK)
        rc = time_ok(e, t_abs);
    return rc == SW_OK ? take(e, t_abs, a_g, a_z) : rc;
}

int sw_engine_push(sw_engine_t *e, double t_abs, double a_g, double a_z)
{
    if (!e || e->lat) /* the lateral planes need their input: sw_engine_push_lat */
        return SW_EINVAL;
    const int rc = push(e, t_abs, a_g, a_z);
    if (rc >= 0 && e->check) /* through the API: push() stays inlined here */
        sw_engine_push(e->check, t_abs, a_g, a_z);
    return rc;
}

/* The sample is checked once for both planes (its numbers, and its time
 * against the longitudinal engine's clock, which the lateral one keeps
 * in step with), so that neither plane takes a sample the other would
 * refuse; then each plane takes it unchecked.  Only after
 * sw_engine_finish() or a refused sw_engine_advance_fn(), which may
 * leave the two clocks apart, is the time checked against both. */
int sw_engine_push_lat(sw_engine_t *e, double t_abs, double a_g, double a_y, double a_z)
{
    if (!e)
        return SW_EINVAL;
    int rc = sample_ok(t_abs, a_g, a_z);
    if (!isfinite(a_y))
        return SW_ENONFINITE;
    if (rc == SW_OK && fabs(a_y) > SW_MAX_ACCEL)
        rc = SW_ETOOBIG;
    if (rc != SW_OK)
        return rc;
    sw_engine_t *L = e->lat;
    if (!L)
        return sw_engine_push(e, t_abs, a_g, a_z);
    rc = time_ok(e, t_abs);
    if (rc == SW_OK && e->apart)
        rc = time_ok(L, t_abs);
    if (rc != SW_OK)
        return rc;
    /* the lateral planes first: the caller's on_state sees them before the
     * longitudinal ones of the same sample */
    int rl;
    if (e->started && !e->restart && !e->apart) {
        /* the common case: the clocks in step, so the interval and the
         * vertical input over it are the same in both planes */
        const double t = t_abs - e->pc.origin, span = t - e->t; /* s */
        const double az_slope = (a_z - e->az) / span;           /* m/s^3 */
        rl = take_next(L, t_abs, t, span, a_y, a_z, az_slope);
        if (L->check)
            sw_engine_push(L->check, t_abs, a_y, a_z);
        rc = take_next(e, t_abs, t, span, a_g, a_z, az_slope);
    } else {
        rl = take(L, t_abs, a_y, a_z);
        if (L->check)
            sw_engine_push(L->check, t_abs, a_y, a_z);
        rc = take(e, t_abs, a_g, a_z);
    }
    if (e->check)
        sw_engine_push(e->check, t_abs, a_g, a_z);
    track_sample(e, t_abs);
    return rc == SW_EVENT || rl == SW_EVENT ? SW_EVENT : rc;
}

/* Advance to t1 (relative) with a_g = f(user, absolute time). */
static int advance_to(sw_engine_t *e, double t1, sw_input_fn f, void *user)
{
    e->pc.events = 0;
    e->in = (sw_input_t){.fn = f, .fn_user = user, .fn_t0 = e->pc.origin};
    if (!e->started) {
        e->started = 1;
        e->t = 0.0;
        e->t_abs = e->pc.origin;
        for (size_t i = 0; i < e->n; i++) initial_uplift(e, &e->pk[i], 0.0);
    }
    if (!(t1 > e->t))
        return t1 == e->t ? SW_OK : SW_EORDER;
    e->restart = 0; /* a function input is defined everywhere: nothing to bridge */
    for (size_t i = 0; i < e->n; i++) advance_pkg(e, &e->pk[i], t1);
    e->t = t1;
    e->t_abs = e->pc.origin + t1;
    e->ag = f(user, e->t_abs);
    e->az = 0.0;
    report_states(e, t1);
    e->in = (sw_input_t){.t0 = t1, .ag0 = e->ag};
    return e->pc.events ? SW_EVENT : SW_OK;
}

int sw_engine_advance_fn(sw_engine_t *e, double t1, sw_input_fn f, void *user)
{
    if (!e || !f || !isfinite(t1))
        return SW_EINVAL;
    if (coarse_time(t1))
        return SW_ERESOLUTION;
    const int rc = advance_to(e, t1 - e->pc.origin, f, user);
    if (rc >= 0 && e->check)
        advance_to(e->check, t1 - e->check->pc.origin, f, user);
    if (rc < 0 && e->lat)
        e->apart = 1; /* the first call starts the longitudinal clock alone */
    if (rc < 0 || !e->lat)
        return rc;
    const int rl = sw_engine_advance_fn(e->lat, t1, sw_input_zero, NULL);
    if (rl < 0)
        e->apart = 1;
    track_both(e, t1);
    return rl == SW_EVENT ? SW_EVENT : rc;
}

int sw_engine_set_origin(sw_engine_t *e, double t0)
{
    if (!e || e->started || !isfinite(t0))
        return SW_EINVAL;
    if (coarse_time(t0))
        return SW_ERESOLUTION;
    e->pc.origin = t0;
    e->origin_set = 1;
    if (e->check)
        sw_engine_set_origin(e->check, t0);
    if (e->lat)
        sw_engine_set_origin(e->lat, t0);
    return SW_OK;
}

int sw_engine_restart(sw_engine_t *e)
{
    if (!e)
        return SW_EINVAL;
    if (!e->started)
        return SW_OK;
    for (size_t i = 0; i < e->n; i++) {
        sw_pkg_t *P = &e->pk[i];
        if (P->m.phase != SW_PHASE_OVERTURNED) {
            sw_pkg_rest(P);
            sw_step_reset(&P->st);
        }
    }
    e->restart = 1;
    e->both_stale = 1; /* the packages put at rest with no event */
    if (e->check)
        sw_engine_restart(e->check);
    if (e->lat)
        sw_engine_restart(e->lat);
    return SW_OK;
}

double sw_input_zero(void *user, double t)
{
    (void)user;
    (void)t;
    return 0.0;
}

/* Any package of e still moving (finish goes on while one is). */
static int any_moving(const sw_engine_t *e)
{
    for (size_t i = 0; i < e->n; i++)
        if (e->pk[i].m.ops->moving(&e->pk[i].m, e->pk[i].y, e->pc.rest_eps))
            return 1;
    return 0;
}

/* The lateral planes settle beside the longitudinal ones on the same
 * clock, each engine only while one of its packages moves: the chunks
 * each takes are those it would take alone. */
int sw_engine_finish(sw_engine_t *e, double settle)
{
    if (!e)
        return SW_EINVAL;
    if (e->check)
        sw_engine_finish(e->check, settle);
    if (e->lat && e->lat->check)
        sw_engine_finish(e->lat->check, settle);
    int any = 0;
    if (!(settle > 0.0) || !e->started)
        return SW_OK;
    sw_engine_t *L = e->lat;
    const double t_end = e->t + settle;
    const double chunk = 1e-3; /* s, state reports while settling */
    for (double t = e->t; t < t_end && !(e->stop && *e->stop);) {
        const int moving = any_moving(e), lat_moving = L && any_moving(L);
        if (!moving && !lat_moving)
            break;
        const double tn = fmin(t_end, t + chunk);
        if (!(tn > t))
            break; /* beyond the clock's resolution: no progress */
        if (moving && advance_to(e, tn, sw_input_zero, NULL) == SW_EVENT)
            any = 1;
        if (lat_moving &&
            advance_to(L, tn + (e->pc.origin - L->pc.origin), sw_input_zero, NULL) == SW_EVENT)
            any = 1;
        if (L)
            track_both(e, e->pc.origin + tn);
        t = tn;
    }
    if (L)
        e->apart = 1; /* each engine advanced only while one of its packages moved */
    return any ? SW_EVENT : SW_OK;
}

void sw_engine_set_stop(sw_engine_t *e, const volatile sig_atomic_t *stop)
{
    if (!e)
        return;
    e->stop = stop;
    sw_engine_set_stop(e->check, stop); /* the default beside it settles too */
    sw_engine_set_stop(e->lat, stop);
}

int sw_engine_set_state(sw_engine_t *e, size_t pkg, const sw_state_t *s)
{
    if (!e || pkg >= e->n || !s)
        return SW_EINVAL;
    sw_pkg_t *P = &e->pk[pkg];
    P->m.flying = 0; /* a state given is on its support */
    sw_model_from_state(&P->m, P->y, s);
    P->beyond_alpha = fabs(P->y[P->m.ith]) >= P->m.d.alpha;
    sw_step_reset(&P->st);
    e->both_stale = 1; /* a phase given, with no event */
    if (e->check)
        sw_engine_set_state(e->check, pkg, s);
    return SW_OK;
}

int sw_engine_get_state(const sw_engine_t *e, size_t pkg, sw_state_t *s)
{
    if (!e || pkg >= e->n || !s)
        return SW_EINVAL;
    sw_model_to_state(&e->pk[pkg].m, e->pk[pkg].y, s);
    return SW_OK;
}

int sw_engine_get_output(const sw_engine_t *e, size_t pkg, sw_output_t *out)
{
    if (!e || pkg >= e->n || !out)
        return SW_EINVAL;
    const sw_pkg_t *P = &e->pk[pkg];
    const double t = e->started ? e->t : 0.0;
    const sw_input_at_t u = sw_input_at(P->m.in, P->m.g, t);
    sw_model_output(&P->m, &P->scr, &u, t, P->y, out);
    out->t = e->pc.origin + t;
    out->pkg = pkg;
    return SW_OK;
}

size_t sw_engine_count(const sw_engine_t *e)
{
    return e ? e->n : 0;
}

double sw_engine_time(const sw_engine_t *e)
{
    return e && e->started ? e->t_abs : NAN;
}

const sw_derived_t *sw_engine_derived(const sw_engine_t *e, size_t pkg)
{
    return e && pkg < e->n ? &e->pk[pkg].m.d : NULL;
}

int sw_engine_summary(const sw_engine_t *e, size_t pkg, sw_summary_t *s)
{
    if (!e || pkg >= e->n || !s)
        return SW_EINVAL;
    const sw_pkg_t *P = &e->pk[pkg];
    *s = P->sum;
    if (P->m.flying) { /* a flight not yet over counts as long as it has lasted */
        s->flight_max = sw_max2(s->flight_max, P->t - P->fl_t0);
        if (P->t - P->fl_t0 > SW_FLIGHT_LONG && isnan(s->flight_long_time))
            s->flight_long_time = P->fl_t0;
    }
    /* kept relative, reported as the caller's times (NAN stays NAN) */
    s->overturn_time += e->pc.origin;
    s->tip_time += e->pc.origin;
    s->uplift_time += e->pc.origin;
    s->flight_long_time += e->pc.origin;
    return SW_OK;
}

const char *sw_engine_scheme(const sw_engine_t *e)
{
    return e ? e->sc.scheme->name : NULL;
}

double sw_engine_dt(const sw_engine_t *e, size_t pkg)
{
    return e && pkg < e->n ? e->pk[pkg].st.h : NAN;
}

double sw_engine_dt_used(const sw_engine_t *e, size_t pkg)
{
    if (!e || pkg >= e->n)
        return NAN;
    const sw_pkg_t *P = &e->pk[pkg];
    return !e->sc.scheme->adaptive && P->h_used > 0.0 ? P->h_used : P->st.h;
}

double sw_engine_dt_requested(const sw_engine_t *e)
{
    return e ? e->dt_req : NAN;
}

const sw_engine_t *sw_engine_checker(const sw_engine_t *e)
{
    return e ? e->check : NULL;
}

const char *sw_plane_name(sw_plane p)
{
    switch (p) {
        case SW_PLANE_LONG: return "longitudinal";
        case SW_PLANE_LAT: return "lateral";
    }
    return "unknown";
}

const sw_engine_t *sw_engine_plane(const sw_engine_t *e, size_t pkg, sw_plane p, size_t *k)
{
    if (!e || pkg >= e->n)
        return NULL;
    if (p == SW_PLANE_LONG) {
        *k = pkg;
        return e;
    }
    if (p != SW_PLANE_LAT || !e->lat || e->lat_of[pkg] == NO_LAT)
        return NULL;
    *k = e->lat_of[pkg];
    return e->lat;
}

int sw_engine_planes(const sw_engine_t *e, size_t pkg)
{
    size_t k;
    if (!e || pkg >= e->n)
        return 0;
    return sw_engine_plane(e, pkg, SW_PLANE_LAT, &k) ? 2 : 1;
}

int sw_engine_summary_plane(const sw_engine_t *e, size_t pkg, sw_plane plane, sw_summary_t *s)
{
    size_t k;
    const sw_engine_t *E = sw_engine_plane(e, pkg, plane, &k);
    if (!s || !e || pkg >= e->n)
        return SW_EINVAL;
    return E ? sw_engine_summary(E, k, s) : SW_ENOTFOUND;
}

int sw_engine_get_output_plane(const sw_engine_t *e, size_t pkg, sw_plane plane, sw_output_t *out)
{
    size_t k;
    const sw_engine_t *E = sw_engine_plane(e, pkg, plane, &k);
    if (!out || !e || pkg >= e->n)
        return SW_EINVAL;
    if (!E)
        return SW_ENOTFOUND;
    const int r = sw_engine_get_output(E, k, out);
    out->pkg = pkg;
    out->plane = plane;
    return r;
}

int sw_summary_worse(const sw_summary_t *a, const sw_summary_t *b)
{
    if (a->overturned != b->overturned)
        return b->overturned;
    if (a->overturned)
        return b->overturn_time < a->overturn_time;
    if (a->min_margin != b->min_margin)
        return b->min_margin < a->min_margin;
    return b->max_theta_ratio > a->max_theta_ratio;
}

int sw_engine_planes_summary(const sw_engine_t *e, size_t pkg, sw_planes_t *p)
{
    if (!e || pkg >= e->n || !p)
        return SW_EINVAL;
    *p = (sw_planes_t){.planes = sw_engine_planes(e, pkg),
                       .worse = SW_PLANE_LONG,
                       .both_from = NAN,
                       .both_to = NAN};
    if (p->planes < 2)
        return SW_OK;
    sw_summary_t a, b;
    sw_engine_summary_plane(e, pkg, SW_PLANE_LONG, &a);
    sw_engine_summary_plane(e, pkg, SW_PLANE_LAT, &b);
    p->worse = sw_summary_worse(&a, &b) ? SW_PLANE_LAT : SW_PLANE_LONG;
    const sw_both_t *w = &e->both[e->lat_of[pkg]];
    p->both_rocking = !isnan(w->from);
    p->both_from = w->from;
    p->both_to = w->to;
    p->both_time = w->time;
    return SW_OK;
}

const char *sw_event_name(sw_event_kind k)
{
    switch (k) {
        case SW_EV_UPLIFT: return "uplift";
        case SW_EV_IMPACT: return "impact";
        case SW_EV_REST: return "rest";
        case SW_EV_TIP: return "tip";
        case SW_EV_OVERTURN: return "overturn";
        case SW_EV_FAULT: return "fault";
        case SW_EV_FLIGHT: return "flight";
    }
    return "unknown";
}

/* ---- replacing one package ---------------------------------------------- */

/* The new package is built for this engine, with its scheme and options
 * (not the scheme the new scene alone would get: a stiff cushion elsewhere
 * in the engine may have chosen an adaptive one, whose work space the new
 * package must have), into a zeroed package off to the side, so that a
 * failure leaves the engine unchanged; then moved into place, and the
 * pointers that lead back into it (the ODE system's parameters, an implicit
 * stepper's driver) are set again. */
int sw_engine_replace(sw_engine_t *e, size_t pkg, const sw_scene_t *scene, char *msg, size_t msglen)
{
    if (msg && msglen)
        msg[0] = '\0';
    if (!e || !scene || pkg >= e->n) {
        if (msg && msglen)
            snprintf(msg, msglen, "no such package");
        return SW_EINVAL;
    }
    /* a new scene that cannot have the planes the package has leaves the
     * engine unchanged */
    const size_t j = e->lat ? e->lat_of[pkg] : NO_LAT;
    if (e->o.lateral && (j != NO_LAT) != (sw_scene_has_depth(scene) != 0)) {
        if (msg && msglen)
            snprintf(msg, msglen,
                     "package.depth %s: a package cannot gain or lose its lateral plane while "
                     "the stream runs",
                     j != NO_LAT ? "removed" : "added");
        return SW_EINVAL;
    }
    sw_pkg_t fresh;
    memset(&fresh, 0, sizeof fresh);
    int r = pkg_init(e, &fresh, scene, pkg, msg, msglen);
    if (r == SW_OK && j != NO_LAT) {
        sw_scene_t lat;
        sw_scene_lateral(scene, &lat);
        char buf[400];
        r = sw_engine_replace(e->lat, j, &lat, buf, sizeof buf);
        if (r != SW_OK && msg && msglen)
            snprintf(msg, msglen, "across the truck: %s", buf);
    }
    if (r != SW_OK) {
        sw_step_free(&fresh.st);
        return r;
    }
    sw_pkg_t *P = &e->pk[pkg];
    sw_step_free(&P->st);
    *P = fresh;
    sw_step_bind(&P->st, &P->m, &P->scr);
    pkg_reset(P);
    P->t = e->started ? e->t : 0.0;
    if (j != NO_LAT) {
        both_clear(&e->both[j]);
        e->both_stale = 1;
    }
    if (e->check && sw_engine_replace(e->check, pkg, scene, NULL, 0) != SW_OK) {
        /* the check can no longer follow: drop it rather than check wrongly */
        sw_engine_destroy(e->check);
        e->check = NULL;
    }
    return SW_OK;
}
