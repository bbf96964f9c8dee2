/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sweep.h - overturning questions answered by many runs of the engine:
 * "does this pulse (or this log, scaled) overturn the package", the lowest
 * overturning pulse amplitude as a function of the pulse frequency (the
 * overturning boundary curves of physics.md), and the safety factor of a
 * recorded log (the smallest scale of its acceleration that overturns).
 *
 * Overturning is not monotonic in the amplitude (a full-sine pulse that is
 * larger can be survived: the package is thrown back before it falls), so
 * every search scans upward in small relative steps before it bisects, and
 * reports the lowest overturning value it found and, on request, the safe
 * islands above it.  A window of overturning narrower than one scan step
 * can be missed; the step is an option.
 *
 * Units: amplitudes are given as x = a_e / (g tan alpha) (1 = the bed
 * acceleration that just lifts a package standing on the bed), pulse
 * frequencies as omega_e / p, log scales as plain factors.
 *
 * No I/O, no global state: every call works on its own engines.  The
 * threaded sweeps give results identical to a single-threaded run, because
 * every point is computed alone, deterministically, into its own slot. */
#ifndef SWAYWATCH_SWEEP_H
#define SWAYWATCH_SWEEP_H

#include <stddef.h>

#include "engine.h"
#include "export.h"
#include "pulse.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- one run ------------------------------------------------------------ */

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

/* ---- threshold search --------------------------------------------------- */

/* One trial: does x overturn?  Fill r; return SW_OK or a negative code,
 * which ends the search. */
typedef int (*sw_trial_fn)(void *user, double x, sw_run_result_t *r);

typedef struct {
    double x_min, x_max; /* scan range; both > 0, x_min < x_max */
    double step;         /* relative scan step, x_{k+1} = x_k (1 + step); 0 = 0.02 */
    double tol;          /* relative width of the final brackets; 0 = 1e-3 */
    int islands;         /* non-zero: go on scanning above the lowest overturn and map the
                            safe islands up to x_max */
} sw_search_opts_t;

#define SW_MAX_ISLANDS 16

/* Amplitudes x with lo < x < hi were found safe (the ends are bracketed to
 * tol: lo overturns just below, hi just above); open: safe up to x_max. */
typedef struct {
    double lo, hi;
    int open;
} sw_island_t;

typedef struct {
    int found;            /* some x in [x_min, x_max] overturned */
    int at_min;           /* x_min itself overturned: the threshold may be lower */
    double x;             /* lowest overturning x found: the upper end of the final
                             bracket, a value that was run and overturned */
    double x_safe;        /* the lower end of that bracket: run and safe (0 if at_min) */
    sw_run_result_t at_x; /* the run at x */
    int n_islands;
    int islands_truncated; /* more than SW_MAX_ISLANDS islands */
    sw_island_t islands[SW_MAX_ISLANDS];
    long trials; /* runs made */
} sw_threshold_t;

/* Scan x_min, x_min (1 + step), ... up to x_max (the last point clipped to
 * x_max) until a trial overturns, then bisect the last safe / first
 * overturning pair to tol.  Returns SW_OK (found or not), SW_EINVAL for bad
 * options, or the first error of a trial. */
SW_API int sw_threshold_search(sw_trial_fn f, void *user, const sw_search_opts_t *o,
                               sw_threshold_t *out);

/* ---- overturning boundary curves ---------------------------------------- */

/* One curve: a scene, and optionally a frame that follows the pulse. */
typedef struct {
    sw_scene_t scene;
    double bearing_ratio; /* > 0: at every point the frame's omega_b is set to
                             bearing_ratio * omega_e (the paper's omega_b/omega_e); the scene
                             must have a frame.  0: the scene as it is */
} sw_curve_t;

/* The scene of curve c under a pulse of omega_e (rad/s): the curve's scene,
 * with omega_b = bearing_ratio * omega_e when it has a ratio (omega_e <= 0:
 * any pulse; omega_b is then 1 rad/s, for checking and describing the rest
 * of the scene).  Returns SW_OK, or SW_EINVAL (out holds the scene as it
 * is) for a ratio on a scene without a frame. */
SW_API int sw_curve_scene(const sw_curve_t *c, double omega_e, sw_scene_t *out);

typedef void (*sw_progress_fn)(void *user, size_t done, size_t total);

typedef struct {
    sw_pulse_shape shape;
    sw_run_opts_t run;
    sw_search_opts_t search; /* x = a_e/(g tan alpha).  x_min 0 = automatic: the lowest
                                amplitude at which the package can lift at all (1 on the bed;
                                on a frame, 0.99 times the value found from the linear
                                response of the stuck frame, sampled 400 times a period).
                                x_max 0 = 20 */
    int threads;             /* worker threads; 0 or 1 = run in the calling thread */
    sw_progress_fn progress; /* may be NULL; called after each point, from any thread,
                                one call at a time */
    void *user;
} sw_boundary_opts_t;

typedef struct {
    double omega_ratio; /* omega_e / p */
    int status;         /* SW_OK or this point's error */
    double x_lift;      /* lowest amplitude at which the package can lift (search start
                           before the 0.9 factor) */
    sw_threshold_t th;  /* th.found, th.x: the boundary a_e/(g tan alpha) */
} sw_boundary_point_t;

/* The boundary of one curve at one omega_e/p.  Returns the point's status
 * (also stored in out->status); msg (may be NULL) says why on error. */
SW_API int sw_boundary_point(const sw_curve_t *c, double omega_ratio, const sw_boundary_opts_t *o,
                             sw_boundary_point_t *out, char *msg, size_t msglen);

/* Every curve at every ratio; out has ncurves * nratios slots, curve-major
 * (out[c * nratios + i]).  Points run in parallel on o->threads threads.
 * Returns SW_OK if every point succeeded, else the first failing point's
 * status in (curve, ratio) order, with its message in msg. */
SW_API int sw_boundary_sweep(const sw_curve_t *curves, size_t ncurves, const double *ratios,
                             size_t nratios, const sw_boundary_opts_t *o, sw_boundary_point_t *out,
                             char *msg, size_t msglen);

/* ---- safety factor of a log --------------------------------------------- */

typedef struct {
    int overturned;         /* the log as recorded (scale 1) overturned the package */
    sw_run_result_t at_one; /* that run */
    int found;              /* a factor was found below the search's x_max */
    double factor;          /* the safety factor: the smallest scale that overturns the
                               package (<= 1 if the log overturned it); if it survived,
                               the smallest scale above 1 that overturns it (every scale
                               from 1 up to it was found safe).  INFINITY if not found */
    double factor_safe;     /* the safe end of the final bracket (just below factor) */
    sw_threshold_t below;   /* scales from the lifting scale up to 1: for a log that
                               survived, below.found means a weaker shock of the same shape
                               would have overturned it (below.x) - it survived by luck */
    sw_threshold_t above;   /* survived only: the search from 1 up (factor = above.x) */
    double lift_scale;      /* the scale at which the package can first lift (estimated on
                               a frame or with vertical acceleration); INFINITY if the log
                               has no longitudinal acceleration */
    double max_scale;       /* the largest scale the search would try (its x_max) */
    long trials;            /* runs of the log, all searches and the recorded one */
} sw_safety_t;

/* The safety factor of a log: the factor by which its longitudinal
 * acceleration would have to be scaled to overturn the package.  so may be
 * NULL; its x_min 0 = automatic (the lifting scale, times 0.9 on a frame,
 * a cushion or with vertical acceleration: below it nothing can lift),
 * x_max 0 = 20 times the scale that lifts a package standing on the bed;
 * step and tol as in sw_threshold_search() (islands are not mapped).
 *
 * The scan takes its grid points four at a time and a bracket is cut in
 * five, keeping the lowest change from safe to overturning, so that the
 * four runs of a round can run in parallel (sw_safety_factors()); the
 * final bracket is tol wide as with bisection, its ends other scales.
 * Every run starts as late as its outcome allows: at the sample before the
 * first that can lift the package at that scale, with the state the
 * package has there (exact on the bed, and across the stretches it stands
 * at rest; to rounding on a frame; to FORGET = 1e-9 of the second-order
 * error of the linear motion on a cushion on the bed): an hour-long log
 * costs what the stretches that can move the package cost.  at_one, the
 * run of the log as recorded, is made the same way (on a cushion that
 * never lifts, over its largest response).  Returns SW_OK (found or not),
 * or the first error of a trial with a reason in msg. */
SW_API int sw_safety_factor(const sw_scene_t *sc, const sw_log_t *log, const sw_run_opts_t *ro,
                            const sw_search_opts_t *so, sw_safety_t *out, char *msg, size_t msglen);

/* One scene of sw_safety_factors(): the caller sets scene; the rest is
 * filled. */
typedef struct {
    sw_scene_t scene;
    int status;    /* SW_OK, or the first error of its trials */
    char msg[256]; /* why, on error */
    sw_safety_t sf;
} sw_safety_case_t;

typedef struct {
    size_t cases, cases_done;
    long trials; /* runs of the log made so far, all scenes together */
} sw_safety_progress_t;

typedef struct {
    sw_run_opts_t run;       /* as for sw_safety_factor() */
    sw_search_opts_t search; /* as for sw_safety_factor() */
    int threads;             /* worker threads; 0 or 1 = the calling thread alone */
    void (*progress)(void *user, const sw_safety_progress_t *p); /* may be NULL; after
                                each trial, from any thread, one call at a time */
    void *user;
} sw_safety_opts_t;

/* The safety factors of n scenes for one log, all searches at once on
 * o->threads threads: each scene's result is what sw_safety_factor() gives
 * it, whatever the number of threads.  Allocates (a few bytes per sample
 * and scene while it runs).  Returns SW_OK if every scene succeeded, else
 * the first failing scene's status (cases[i].msg says why), or SW_EINVAL /
 * SW_ENOMEM. */
SW_API int sw_safety_factors(sw_safety_case_t *cases, size_t n, const sw_log_t *log,
                             const sw_safety_opts_t *o);

/* ---- parallel jobs ------------------------------------------------------- */

/* Call job(user, i) for i = 0 .. n-1 on up to threads threads (0 or 1:
 * in the calling thread, in order), each thread taking the next index when
 * it is free.  Jobs must be independent: each writes only its own results.
 * If a thread cannot be started its share runs on the others (or in the
 * calling thread); every job runs exactly once. */
SW_API void sw_parallel_for(size_t n, int threads, void (*job)(void *user, size_t i), void *user);

#ifdef __cplusplus
}
#endif
#endif
