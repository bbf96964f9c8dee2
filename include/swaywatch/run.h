/* SPDX-License-Identifier: GPL-3.0-or-later */
/* run.h - one run of a package, started from rest or from a given state:
 * a pulse or a recorded log (scaled), then free motion until the outcome
 * is certain (overturn, rest, a guarantee of safety, or the time limit).
 * Every analysis of many runs (search.h, boundary.h, safety.h,
 * reserve.h) is made of these.
 *
 * No I/O, no global state: every call works on its own engine. */
#ifndef SWAYWATCH_RUN_H
#define SWAYWATCH_RUN_H

#include <stddef.h>

#include "engine.h"
#include "export.h"
#include "pulse.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    sw_engine_opts_t engine; /* scheme, dt, rtol, atol, accuracy, rest_eps, stuck_stepped as
                                for sw_engine_create(), except: dt 0 = automatic, the
                                scheme's default at most 1/400 of the shorter of the pulse
                                period 2 pi/omega_e and the rocking period 2 pi/p, and never
                                forced (dt_forced is ignored); the callbacks are the run's
                                own (on_event, on_state and user are ignored) */
    double free_periods;     /* free motion allowed after the input ends, in rocking periods
                                2 pi/p; 0 = 20 */
    double settle;           /* s; if > 0, replaces free_periods (logs, as replay --settle);
                                if < 0, no free motion: the run ends with the input */
} sw_run_opts_t;

/* Why a run stopped. */
typedef enum {
    SW_END_OVERTURN = 0, /* |theta| reached pi/2 */
    SW_END_FALLING = 1,  /* bare package beyond alpha, moving outward, no input left: it
                            overturns (physics.md); counted as overturned */
    SW_END_REST = 2,     /* bare package at rest after the input: safe */
    SW_END_BOUND = 3,    /* frame: margin_bound > 0 after the input, i.e. the energy left
                            cannot reach the barrier: safe */
    SW_END_TIMEOUT = 4   /* the free-motion time limit passed: counted as safe */
} sw_run_end;

typedef struct {
    int overturned; /* SW_END_OVERTURN or SW_END_FALLING */
    sw_run_end end;
    long impacts; /* impacts before the overturn (or in the whole run) */
    long uplifts;
    long faults;            /* model faults (the run is then not trustworthy) */
    double uplift_time;     /* s, NAN if none */
    double tip_time;        /* s, first |theta| = alpha, NAN if none */
    double overturn_time;   /* s, NAN unless SW_END_OVERTURN */
    double max_theta_ratio; /* max |theta| / alpha (1.0 at least when it fell) */
    double min_margin;      /* 1 */
    double t_end;           /* s, when the run stopped */
    int uplift_side;        /* direction of the first uplift: +1 the top forward, -1 back,
                               0 none (on a cushion: of the first edge lift) */
    int overturn_side;      /* direction of the overturn (0 if none): the same as
                               uplift_side for a direct overturn, opposite after a reverse
                               sway */
} sw_run_result_t;

/* Run the pulse through a package standing still at t = 0: exactly (the
 * pulse is a function of time, the step grid meets its end), then free
 * motion until overturn, rest, a guarantee of safety, or the time limit.
 * Returns SW_OK, SW_EINVAL (bad scene or pulse; msg says why), SW_ENOMEM,
 * or SW_EFAULT if the model faulted (r is still filled). */
SW_API int sw_pulse_run(const sw_scene_t *sc, const sw_pulse_t *pulse, const sw_run_opts_t *o,
                        sw_run_result_t *r, char *msg, size_t msglen);

/* The same from state s (sw_state_t of this scene, any phase; the pulse
 * starts at t = 0 from it) instead of rest: "what would this pulse do
 * now".  An overturned state ends at once (SW_END_OVERTURN).  Returns as
 * sw_pulse_run(), SW_EINVAL also for a state the engine refuses. */
SW_API int sw_pulse_run_from(const sw_scene_t *sc, const sw_state_t *s, const sw_pulse_t *pulse,
                             const sw_run_opts_t *o, sw_run_result_t *r, char *msg, size_t msglen);

/* A recorded log held in memory: n samples, time increasing (s), bed
 * acceleration (m/s^2, x forward) and optionally vertical acceleration
 * (m/s^2, up; a_z NULL = none).  restart (may be NULL when nrestart is 0):
 * increasing indices of the samples before which every package restarts
 * from rest (sw_engine_restart), where the input gate restarted them (a
 * sensor restart, a gap too long to bridge): the log as the gate fed the
 * engine (gate.h, on_take). */
typedef struct {
    const double *t;
    const double *a_g;
    const double *a_z;
    size_t n;
    const size_t *restart;
    size_t nrestart;
} sw_log_t;

/* Run the log with its longitudinal acceleration multiplied by scale
 * (vertical acceleration unchanged), then free motion as for pulses (time
 * limit: o->settle if > 0, else free_periods).  Samples the engine refuses
 * (non-finite, not increasing) are skipped.  Returns as sw_pulse_run(). */
SW_API int sw_log_run(const sw_scene_t *sc, const sw_log_t *log, double scale,
                      const sw_run_opts_t *o, sw_run_result_t *r, char *msg, size_t msglen);

#ifdef __cplusplus
}
#endif
#endif
