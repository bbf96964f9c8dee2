/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pkg.h - one package and its phase machine (pkg.c): its model, state,
 * stepper, summary and flight (struct sw_pkg), and what happens to it:
 * uplift, impact, rest, overturn, fault, the events it reports through
 * the engine's callback.  The engine, stuck.c and flight.c move packages;
 * the layers below (step, event, model) never see one.  Internal. */
#ifndef SWAYWATCH_PKG_H
#define SWAYWATCH_PKG_H

#include "event.h"
#include "model_ops.h"
#include "step.h"
#include "swaywatch/engine.h"

typedef struct sw_pkg sw_pkg_t;

/* What the packages of one engine share: where their events go and the
 * rest threshold.  Owned by the engine, embedded in it. */
typedef struct {
    double rest_eps;      /* rest threshold, a fraction of the energy barrier */
    sw_event_fn on_event; /* may be NULL */
    void *user;
    double origin; /* s: the absolute time of the engine's t = 0 (the first
                      sample's); the layers run on time relative to it */
    int events;    /* events reported during the current call */
} sw_pkg_ctx_t;

/* One package: its model, state, summary, work space.  Everything is
 * allocated once, when the package is built (pkg_init in engine.c). */
struct sw_pkg {
    sw_model_t m;           /* the model: parameters, input, mode */
    sw_model_scratch_t scr; /* its right-hand side's scratch */
    sw_stepper_t st;        /* the scheme's work space */
    sw_scene_t scene;
    size_t index; /* its place in the engine (events and states say it) */

    /* integration state: the phase machine (pkg.c) and the loop (engine.c) */
    double t; /* s */
    double y[SW_NMAX];
    int beyond_alpha; /* |theta| >= alpha at the last check */
    /* free flight (flight.c): the centre of mass relative to the bed */
    int fl_long;         /* this flight has lasted SW_FLIGHT_LONG: said (SW_EV_FLIGHT) */
    int fl_up;           /* it has risen clear of its support */
    double fl_t0;        /* s, in the air since */
    double fl_yc;        /* m, height of the centre of mass over the support */
    double fl_vx, fl_vy; /* m/s, its velocity */
    sw_summary_t sum;
    double h_used;      /* s, the longest step taken (sw_engine_dt_used) */
    double nj_cache[5]; /* stuck.c: exact stuck-frame step of length [0]: g, g', I1, I2 */
};

/* Report an event at t with the package's state, or with y_at (an event
 * inside a step); u: the input at t where the caller has it (the event
 * layer's), NULL to evaluate it here. */
void sw_pkg_emit_at(sw_pkg_ctx_t *C, sw_pkg_t *P, sw_event_kind kind, double t,
                    const sw_input_at_t *u, double info, const double *y_at);
void sw_pkg_track_theta(sw_pkg_t *P, double theta);
void sw_pkg_rest(sw_pkg_t *P);
/* A fault at t (code: the error): at rest, counted and said. */
void sw_pkg_fault(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, int code);
/* Uplift and tipping at t (u: the input there, or NULL, as
 * sw_pkg_emit_at). */
void sw_pkg_start_rocking(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, const sw_input_at_t *u, int side);
void sw_pkg_tip(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, const sw_input_at_t *u,
                const double y_at[]);
/* The events timed inside a step (sw_event_locate), in their order: a
 * peak of |theta| kept in the summary, a tip or a first lift reported. */
void sw_pkg_timed(sw_pkg_ctx_t *C, sw_pkg_t *P, const sw_timed_t ev[], int n);
/* A step taken, in one call: the events it timed (timed[0..nt), as
 * sw_pkg_timed), then where it ended, P->t and P->y (the engine moved
 * them there: the step's end, or its cut, polished): with no cut (ev
 * SW_EVF_NONE), |theta| kept while rocking, the side as the model
 * follows it, and a package lifted since its last rest that its model
 * finds back at rest says so; at a cut ev, its map (sw_pkg_on_cut) under
 * the input there, u (the event layer's).  The caller restarts the
 * scheme after a cut (sw_step_restart). */
void sw_pkg_stepped(sw_pkg_ctx_t *C, sw_pkg_t *P, const sw_timed_t timed[], int nt, int ev,
                    const sw_input_at_t *u);
/* A cutting event ev at t (P->t, P->y there): |theta| kept, the side as
 * the model says, then the event's map (a step's cut, and a flight's
 * overturn, flight.c). */
void sw_pkg_on_cut(sw_pkg_ctx_t *C, sw_pkg_t *P, int ev, double t);

#endif
