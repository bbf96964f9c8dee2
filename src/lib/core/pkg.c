/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pkg.c - one package's phase machine: standing (stuck), rocking, at rest
 * again, overturned, faulted; the maps of the events that change the
 * dynamics (uplift, impact, overturn), the summary, and the events it
 * reports through the engine's callback.  The physics of each map is the
 * model's (its ops); what follows from it is here. */
#include <math.h>
#include <string.h>

#include "input.h"
#include "model_ops.h"
#include "numeric.h"
#include "pkg.h"
#include "swaywatch/status.h"

/* Report an event at time t with the package's current state, or with the
 * state vector y_at when the event lies inside a step (tipping), under
 * the input at t: the event layer's where it found the time (it
 * evaluated it there), else evaluated here. */
void sw_pkg_emit_at(sw_pkg_ctx_t *C, sw_pkg_t *P, sw_event_kind kind, double t,
                    const sw_input_at_t *u, double info, const double *y_at)
{
    sw_event_t ev;
    sw_output_t o;
    sw_input_at_t here;
    if (!u) {
        here = sw_input_at(P->m.in, P->m.g, t);
        u = &here;
    }
    sw_model_output(&P->m, &P->scr, u, t, y_at ? y_at : P->y, &o);
    ev.pkg = P->index;
    ev.kind = kind;
    ev.t = C->origin + t;
    ev.theta = o.state.theta;
    ev.theta_dot = o.state.theta_dot;
    ev.margin = o.margin;
    ev.info = info;
    ev.plane = SW_PLANE_LONG;
    if (o.margin < P->sum.min_margin)
        P->sum.min_margin = o.margin;
    C->events++;
    if (C->on_event)
        C->on_event(C->user, &ev);
}

static void emit(sw_pkg_ctx_t *C, sw_pkg_t *P, sw_event_kind kind, double t, const sw_input_at_t *u,
                 double info)
{
    sw_pkg_emit_at(C, P, kind, t, u, info, NULL);
}

void sw_pkg_track_theta(sw_pkg_t *P, double th)
{
    const double a = fabs(th);
    if (a > P->sum.max_abs_theta) {
        P->sum.max_abs_theta = a;
        P->sum.max_theta_ratio = a / P->m.d.alpha;
    }
}

void sw_pkg_rest(sw_pkg_t *P)
{
    memset(P->y, 0, sizeof P->y);
    P->m.held = 0;
    P->m.flying = 0;
    P->m.t_lift = NAN;
    P->m.phase = SW_PHASE_STUCK;
    P->m.side = 1;
    P->beyond_alpha = 0;
    if (P->m.ops->rest)
        P->m.ops->rest(&P->m, P->y);
}

void sw_pkg_fault(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, int code)
{
    P->sum.faults++;
    sw_pkg_rest(P);
    emit(C, P, SW_EV_FAULT, t, NULL, code);
}

void sw_pkg_start_rocking(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, const sw_input_at_t *u, int side)
{
    P->m.phase = SW_PHASE_ROCKING;
    P->m.side = side;
    P->m.t_lift = t;
    P->y[P->m.ith] = P->y[P->m.idth] = 0.0;
    P->sum.uplifts++;
    if (isnan(P->sum.uplift_time))
        P->sum.uplift_time = t;
    emit(C, P, SW_EV_UPLIFT, t, u, side);
}

/* |theta| reached alpha at t (the state there: y_at). */
void sw_pkg_tip(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, const sw_input_at_t *u, const double y_at[])
{
    if (isnan(P->sum.tip_time))
        P->sum.tip_time = t;
    P->beyond_alpha = 1;
    sw_pkg_emit_at(C, P, SW_EV_TIP, t, u, (y_at[P->m.ith] < 0.0 ? -1.0 : 1.0) * P->m.d.alpha, y_at);
}

/* The first edge of a package that never impacts (a cushion's) left its
 * support at t: uplift; info +1 when the rear edge lifts (the top tips
 * forward), -1 the front, 0 when the level base leaves at once. */
static void lift(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, const sw_input_at_t *u,
                 const double y_at[])
{
    const double th = y_at[P->m.ith];
    const double side = th == 0.0 ? 0.0 : th < 0.0 ? -1.0 : 1.0;
    P->m.t_lift = t;
    P->sum.uplifts++;
    if (isnan(P->sum.uplift_time))
        P->sum.uplift_time = t;
    sw_pkg_emit_at(C, P, SW_EV_UPLIFT, t, u, side, y_at);
}

void sw_pkg_timed(sw_pkg_ctx_t *C, sw_pkg_t *P, const sw_timed_t ev[], int n)
{
    for (int i = 0; i < n; i++) {
        if (ev[i].role == SW_ROLE_PEAK)
            sw_pkg_track_theta(P, ev[i].y[P->m.ith]);
        else if (ev[i].role == SW_ROLE_TIP)
            sw_pkg_tip(C, P, ev[i].t, &ev[i].u, ev[i].y);
        else
            lift(C, P, ev[i].t, &ev[i].u, ev[i].y);
    }
}

/* After an accepted step with no cut, for a model that follows its side
 * or tests for rest: one call into the model says both. */
static SW_NOINLINE void after_step(sw_pkg_ctx_t *C, sw_pkg_t *P)
{
    const sw_model_ops_t *ops = P->m.ops;
    if (!ops->stepped) {
        ops->follow(&P->m, P->y);
        return;
    }
    if (!ops->stepped(&P->m, P->y, P->m.phase == SW_PHASE_ROCKING && !isnan(P->m.t_lift)))
        return;
    P->m.t_lift = NAN;
    P->beyond_alpha = 0;
    P->sum.rests++;
    emit(C, P, SW_EV_REST, P->t, NULL, 0.0);
}

/* Kinetic energy of theta' below rest_eps of the energy barrier? */
static int below_rest(const sw_pkg_ctx_t *C, const sw_pkg_t *P, double theta_dot)
{
    const double p = P->m.d.p;
    return 0.5 * theta_dot * theta_dot / (p * p) < C->rest_eps * (1.0 - cos(P->m.d.alpha));
}

/* After an impact at t (u: the input there): the cascade ends (rest) when
 * the rebound energy is below rest_eps of the barrier; the package then
 * stands, or starts to rock again at once if its support is still beyond
 * the uplift threshold. */
static void after_impact(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, const sw_input_at_t *u)
{
    if (!below_rest(C, P, P->y[P->m.idth]))
        return;
    P->m.ops->land(&P->m, P->y);
    const int side = P->m.ops->uplift_side(&P->m, u, P->y);
    if (side != 0 && t == P->m.t_lift) {
        /* Lifted and landed at the same instant: the support is at the
         * threshold and the step's own error pushed the package the wrong
         * way.  Hold it for one step (the support keeps moving), then look
         * again, so that time always advances. */
        P->m.phase = SW_PHASE_STUCK;
        P->m.held = 1;
        return;
    }
    if (side == 0) {
        P->m.phase = SW_PHASE_STUCK;
        P->sum.rests++;
        emit(C, P, SW_EV_REST, t, u, 0.0);
    } else {
        P->m.side = side;
    }
}

/* The cut ev at t, u the input there. */
static SW_NOINLINE void on_cut(sw_pkg_ctx_t *C, sw_pkg_t *P, int ev, double t,
                               const sw_input_at_t *u)
{
    /* At an overturn the polished state lies just past pi/2 (by up to a
     * step's worth of theta'); the overturn map records pi/2. */
    if (P->m.phase == SW_PHASE_ROCKING && ev != SW_EVF_OVERTURN)
        sw_pkg_track_theta(P, P->y[P->m.ith]);
    if (P->m.ops->follow)
        P->m.ops->follow(&P->m, P->y);
    switch (ev) {
        case SW_EVF_IMPACT: {
            const double before = P->y[P->m.idth];
            if (below_rest(C, P, before)) {
                /* arriving with less than the rest energy: a landing, not an
                 * impact (the step's round-off after a lift, or the end of a
                 * cascade) */
                P->y[P->m.ith] = 0.0;
                P->m.ops->land(&P->m, P->y);
                after_impact(C, P, t, u);
                break;
            }
            P->y[P->m.ith] = 0.0;
            P->m.ops->impact(&P->m, P->y);
            P->beyond_alpha = 0;
            P->sum.impacts++;
            emit(C, P, SW_EV_IMPACT, t, u, before);
            after_impact(C, P, t, u);
            break;
        }
        case SW_EVF_OVERTURN: {
            const double rate = P->y[P->m.idth];
            P->y[P->m.ith] = P->m.side * M_PI_2;
            sw_pkg_track_theta(P, M_PI_2);
            P->m.phase = SW_PHASE_OVERTURNED;
            P->sum.overturned = 1;
            P->sum.overturn_time = t;
            emit(C, P, SW_EV_OVERTURN, t, u, rate);
            for (int i = 0; i < P->m.n; i++)
                if (i != P->m.ith)
                    P->y[i] = 0.0;
            break;
        }
        case SW_EVF_UPLIFT_FWD:
        case SW_EVF_UPLIFT_BACK:
            sw_pkg_start_rocking(C, P, t, u, ev == SW_EVF_UPLIFT_FWD ? +1 : -1);
            break;
        default: break; /* a kink: the step was cut there, nothing changes */
    }
}

/* Called after every step: what most steps need (|theta| kept) inline,
 * the rest out of line, so that a step costs what it did when the engine
 * kept |theta| itself. */
void sw_pkg_stepped(sw_pkg_ctx_t *C, sw_pkg_t *P, const sw_timed_t timed[], int nt, int ev,
                    const sw_input_at_t *u)
{
    if (nt)
        sw_pkg_timed(C, P, timed, nt);
    if (ev != SW_EVF_NONE) {
        on_cut(C, P, ev, P->t, u);
        return;
    }
    if (P->m.phase == SW_PHASE_ROCKING)
        sw_pkg_track_theta(P, P->y[P->m.ith]);
    if (P->m.ops->follow || P->m.ops->stepped)
        after_step(C, P);
}

void sw_pkg_on_cut(sw_pkg_ctx_t *C, sw_pkg_t *P, int ev, double t)
{
    const sw_input_at_t u = sw_input_at(P->m.in, P->m.g, t);
    on_cut(C, P, ev, t, &u);
}
