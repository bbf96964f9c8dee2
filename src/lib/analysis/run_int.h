/* SPDX-License-Identifier: GPL-3.0-or-later */
/* run_int.h - what the library's run-many-times modules share (run.c: one
 * run; search.c, boundary.c: searches, boundaries; safety.c: the safety factors of a log;
 * reserve.c: the reserve): an engine made for runs, the one loop that runs
 * until the outcome is certain (with the caller's certificate), and the
 * probe of how far a package is from leaving its rest contact.
 * Internal: not part of the public API. */
#ifndef SWAYWATCH_RUN_INT_H
#define SWAYWATCH_RUN_INT_H

#include <stddef.h>

#include "swaywatch/run.h"

#define SW_RUN_CHECKS_PER_PERIOD 16.0 /* stop checks per rocking period of free motion */

/* An engine and what its event callback records of the current run: the
 * direction of the first uplift and of the overturn (+1 the top forward),
 * which tell a direct overturn from one after a reverse sway.  The engine
 * holds a pointer to the record: a runner must not move once made. */
typedef struct {
    sw_engine_t *e;
    int uplift_side, overturn_side;
    void *state_user; /* the on_state callback's user (sw_runner_make_watched) */
} sw_runner_t;

/* An engine for one scene.  dt: the option, or the scheme's default capped
 * at 1/400 of the shorter of the pulse period (omega_e > 0) and the
 * rocking period.  Returns SW_OK, or the error with msg set. */
int sw_runner_make(sw_runner_t *R, const sw_scene_t *sc, const sw_run_opts_t *o, double omega_e,
                   int *err, char *msg, size_t msglen);
/* The same, with the engine's on_state callback (may be NULL).  The
 * engine's user is the runner (its events need it): the callback gets R
 * and finds its own user in R->state_user. */
int sw_runner_make_watched(sw_runner_t *R, const sw_scene_t *sc, const sw_run_opts_t *o,
                           double omega_e, sw_state_fn on_state, void *user, int *err, char *msg,
                           size_t msglen);
void sw_runner_reset(sw_runner_t *R);

/* Free motion allowed after the input (s), for a package of rocking
 * frequency p (rad/s). */
double sw_run_free_time(const sw_run_opts_t *o, double p);

/* The certificate a caller may add to a run (sw_run_until()): at a check
 * during the input, at t (s) in state s, 1 if the package is certainly
 * safe whatever the rest of the input does (the reserve's energy check),
 * else 0. */
typedef int (*sw_run_cert_fn)(void *user, double t, const sw_state_t *s);

/* How a run goes until its outcome is certain. */
typedef struct {
    sw_input_fn input; /* the input up to t_input, NULL = none (it was pushed before) */
    void *input_user;
    double t_input;         /* s, the end of the input */
    double check;           /* s, between certificate checks during the input */
    sw_run_cert_fn certify; /* may be NULL: no checks during the input */
    void *cert_user;
    double t0;          /* s, the run's time when the engine has not started yet */
    double free_time;   /* s, free motion allowed after the input ends */
    int limit_set;      /* non-zero: the free motion ends at t_limit instead */
    double t_limit;     /* s */
    double chunk;       /* s, between checks of the free motion */
    int decide_at_once; /* a model whose margin decides free rocking exactly
                           (ops->free_exact): decided by the margin at the end of the input,
                           instead of by rest or falling seen as it rocks on */
    int stop_on_fault;  /* a model fault ends the run (SW_END_TIMEOUT, counted) */
} sw_run_until_t;

/* The one run-until-certain loop: the input (if any) in steps of check
 * with the certificate between them, then free motion until the outcome
 * is certain or free_time passes.  Sets *end and *t_end (s); returns
 * SW_OK, or the engine's error. */
int sw_run_until(sw_engine_t *e, const sw_run_until_t *u, sw_run_end *end, double *t_end);

/* Free motion from the end of the input until the outcome is certain or
 * t_limit (s) passes; checks every chunk seconds.  Fills r. */
int sw_run_free_motion(sw_runner_t *R, double t_limit, double chunk, sw_run_result_t *r);

/* Push sample i of the log, its longitudinal acceleration times scale,
 * restarting the engine first where the input gate restarted it
 * (*next_restart: the next entry of log->restart to look at, 0 at the
 * start).  Returns sw_engine_push()'s status. */
int sw_run_push(sw_engine_t *e, const sw_log_t *log, size_t i, double scale, size_t *next_restart);

/* The pulse from rest, then free motion (sw_pulse_run()). */
int sw_run_pulse_on(sw_runner_t *R, const sw_pulse_t *pulse, const sw_run_opts_t *o,
                    sw_run_result_t *r);

/* The log scaled, from the start, then free motion (sw_log_run()). */
int sw_run_log_on(sw_runner_t *R, const sw_log_t *log, double scale, const sw_run_opts_t *o,
                  sw_run_result_t *r);

/* A probe's peak drive (ops->lift_drive), at scale probe, turned into the
 * scale at which the package first lifts, at a drive of level
 * (ops->lift_level): INFINITY if the peak is 0. */
double sw_run_probe_lift(double probe, double peak, double level);

void sw_set_msg(char *msg, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

#endif
