/* SPDX-License-Identifier: GPL-3.0-or-later */
/* reserve.h - the reserve in g: how hard a design braking (or speeding-up)
 * pulse, applied from now on, would have to be to overturn a package.
 *
 * For a package's scene and one state of it (sw_state_t, any phase), the
 * reserve is the smallest amplitude a_e, in g (SW_G0 = 9.80665 m/s^2), of a
 * half-sine pulse a_g(t) = -/+ a_e sin(pi t / T) for 0 <= t <= T, quiet
 * input after it, that overturns the package started from that state.  A
 * braking pulse (negative a_g) tips the top forward, a speeding-up pulse
 * backward; the reserve is the smaller of the two directions, over every
 * design pulse duration T of the scene ([alarm] design_pulse, default
 * SW_DESIGN_PULSE_DEFAULT s; docs/reserve.md says why).  At rest it equals
 * the overturning boundary at omega_e = pi/T (sw_boundary_point); while the
 * package rocks it is smaller.  0 means the package overturns with no
 * further input at all.
 *
 * Overturning is not monotonic in the amplitude (safe islands), so every
 * search scans upward from a proven lower bound in small relative steps
 * and bisects the first overturning step (as sw_threshold_search does);
 * every other pulse and direction is then run at that bracket's top and
 * bisected where it overturns.  The answer is the safe end of a bracket
 * of relative width opts.tol: an amplitude shown not to overturn the
 * package (run and survived, or a proven bound), so the reserve is never
 * above the true one.  A window of overturning amplitudes narrower than
 * one scan step can be missed.
 *
 * Cost: everything is allocated by sw_reserve_create() (one private engine
 * per design pulse); sw_reserve_eval() allocates nothing.  The value at
 * rest is computed once, in create, and returned for every state at exact
 * rest.  Runs stop as soon as their outcome is certain (docs/reserve.md).
 *
 * Determinism: the result of sw_reserve_eval() depends only on the scene,
 * the options and the state, never on earlier calls.
 *
 * Threads: an sw_reserve_t is used by one thread at a time (eval changes
 * its engines); separate objects, even of the same scene, are independent.
 * No I/O, no global state. */
#ifndef SWAYWATCH_RESERVE_H
#define SWAYWATCH_RESERVE_H

#include <stddef.h>

#include "export.h"
#include "model.h"
#include "run.h"
#include "scene.h"
#include "units.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Direction of a design pulse: braking (a_g < 0, tips the top forward) or
 * speeding up (a_g > 0, tips it backward). */
typedef enum { SW_RESERVE_BRAKING = -1, SW_RESERVE_ACCELERATING = 1 } sw_reserve_dir;

typedef struct {
    sw_run_opts_t run;    /* engine.scheme, rtol, atol, rest_eps as for sw_engine_create()
                             (callbacks ignored; outcome_only always), except the defaults:
                             rtol 3e-4, atol 1e-7, rest_eps 1e-6 (docs/reserve.md);
                             engine.dt 0 = automatic: 1/SW_RESERVE_STEPS
                             of the shortest of the pulse's period 2T, the rocking period
                             2 pi/p and the scene's fastest period 2 pi/omega_max, at most
                             the scheme's default; free_periods 0 = SW_RESERVE_FREE_PERIODS
                             rocking periods of free motion after the pulse before a run
                             that is still undecided is counted safe; settle ignored */
    double step;          /* relative scan step; 0 = 0.02 */
    double tol;           /* relative width of the final bracket; 0 = 0.01 */
    double max_g;         /* largest amplitude searched, g; 0 = 20 g tan(alpha) / SW_G0 */
    double floor_g;       /* smallest amplitude searched, g, where no lower bound is known;
                             0 = SW_RESERVE_FLOOR_G */
    int each_direction;   /* non-zero: search each direction to its own value (dir_g
                             exact, up to about twice the runs); 0: only the smaller */
    int no_cache;         /* non-zero: compute the rest value like any other state */
    double max_run_steps; /* steps one pulse run (pulse and free motion) may take at a fixed
                             dt; 0 = SW_RESERVE_MAX_RUN_STEPS.  A scene that needs more (a
                             stiff cushion or frame forces a tiny dt) is refused with
                             SW_ETOOBIG: its reserve would take minutes per value */
} sw_reserve_opts_t;

#define SW_RESERVE_STEPS 24.0        /* automatic dt: steps per shortest period */
#define SW_RESERVE_FREE_PERIODS 10.0 /* free motion allowed after a pulse, rocking periods */
#define SW_RESERVE_FLOOR_G 0.01      /* g: below road vibration (about 0.06 g rms) */
#define SW_RESERVE_MAX_RUN_STEPS 2e5 /* steps a pulse run may need at most (docs/reserve.md) */

typedef struct {
    double reserve_g; /* g: the reserve, the safe end of the final bracket: no scanned
                         pulse overturns the package below it (up to a window narrower
                         than a scan step), an amplitude that was run and survived or a
                         proven bound, never above the true reserve and within tol of
                         it; 0 if the package overturns with no further input; max_g if
                         nothing up to max_g overturns (found = 0) */
    double safe_g;    /* g: the same number as reserve_g (the bracket's safe end; kept
                         for callers that read it by this name) */
    double over_g;    /* g: the bracket's top, the lowest amplitude that was run and
                         overturned (over_g / reserve_g - 1 <= tol unless at_floor);
                         0 when reserve_g is 0, INFINITY when found is 0 */
    int found;        /* some amplitude up to max_g overturns (or none is needed) */
    int at_floor;     /* the first amplitude tried, the floor, overturned: the true value
                         is in (reserve_g, floor_g], reserve_g the proven bound (0 if
                         none) */
    int direction;    /* sw_reserve_dir of reserve_g (0 when reserve_g is 0: no pulse) */
    double pulse;     /* s, the design pulse duration T of reserve_g (0 when reserve_g
                         is 0) */
    double dir_g[2];  /* g, [0] braking, [1] speeding up: each direction's reserve over
                         the design pulses, its safe end as reserve_g's; when
                         dir_exact[i] is 0 that direction was searched only as far as the
                         smaller one needed, and its reserve is at least dir_g[i] */
    int dir_exact[2];
    int cached;  /* the state was at rest: the value computed in create */
    long trials; /* pulse runs made by this call (0 when cached) */
} sw_reserve_result_t;

typedef struct sw_reserve sw_reserve_t;

/* Build the reserve of one validated scene: one engine per design pulse,
 * and the value at rest (several tens of pulse runs per design pulse).
 * opts may be NULL (defaults).  On failure returns NULL and, if err is not
 * NULL, stores the code (SW_EINVAL for a scene that does not validate or
 * bad options, SW_ETOOBIG for a run longer than max_run_steps, SW_ENOMEM,
 * or an engine's error); msg (may be NULL) gets the reason. */
SW_API sw_reserve_t *sw_reserve_create(const sw_scene_t *sc, const sw_reserve_opts_t *opts,
                                       int *err, char *msg, size_t msglen);

/* Free everything; NULL is accepted. */
SW_API void sw_reserve_destroy(sw_reserve_t *r);

/* The reserve of the package in state s (as reported by the engine for
 * this scene, sw_output_t.state).  An overturned package has reserve 0.
 * Returns SW_OK, SW_EINVAL (NULL argument, a number not finite, a phase
 * outside the enum), or SW_EFAULT if a run faulted (out is then the
 * result of the runs that did not; out->found may be 0).  Allocates
 * nothing; no I/O. */
SW_API int sw_reserve_eval(sw_reserve_t *r, const sw_state_t *s, sw_reserve_result_t *out);

/* The value at rest, computed by create (no run). */
SW_API void sw_reserve_rest(const sw_reserve_t *r, sw_reserve_result_t *out);

/* Non-zero if s is the package's state of rest, for which sw_reserve_eval()
 * returns the value of sw_reserve_rest(): a package on the bed stuck; on a
 * frame stuck with u = u' = 0; on a cushion upright at its static
 * deflection and still. */
SW_API int sw_reserve_is_rest(const sw_reserve_t *r, const sw_state_t *s);

/* The amplitudes (g) below which no pulse of duration T (s) can overturn
 * the package from state s: the energy bound of docs/reserve.md (the work
 * of a pulse cannot exceed its velocity change times the largest velocity
 * the package's energy allows).  0 when the state already holds the
 * barrier's energy.  A pure function of the scene's derived quantities. */
SW_API double sw_reserve_energy_bound(const sw_derived_t *d, double g, const sw_state_t *s,
                                      double T);

/* Where the search for design pulse number pulse in direction dir starts:
 * the proven lower bound (g) below which no such pulse can overturn the
 * package from s, the larger of the energy bound and, for a package
 * standing on the bed or stuck on its frame, the lift bound (it cannot
 * overturn without leaving its support; on a frame read off the stuck
 * frame's linear response, sampled 400 times a period, less 0.5 %).  0 if
 * none is known (or bad arguments). */
SW_API double sw_reserve_lower_bound(const sw_reserve_t *r, const sw_state_t *s, int dir,
                                     size_t pulse);

/* The scene's design pulses, s (n of them; at most SW_DESIGN_PULSES_MAX). */
SW_API size_t sw_reserve_pulses(const sw_reserve_t *r, const double **T);

/* ---- the smallest reserve along a log ---------------------------------- */

#define SW_RESERVE_LOG_RATE 10.0 /* Hz of log time: states taken, as sw_risk's default */

typedef struct {
    double rate;               /* Hz of log time; 0 = SW_RESERVE_LOG_RATE */
    long max_evals;            /* reserve evaluations at most; 0 = no limit */
    sw_run_opts_t run;         /* the log's run, as sw_log_run() (callbacks ignored) */
    sw_reserve_opts_t reserve; /* the reserve's options; zeros: its defaults */
} sw_reserve_log_opts_t;

typedef struct {
    double min_g;    /* g: the smallest reserve found, the earliest if several (NAN: no
                        state taken) */
    double min_time; /* s, log time of that state (NAN: none) */
    int direction;   /* sw_reserve_dir of min_g (0: none needed) */
    double pulse;    /* s, its design pulse (0: none) */
    double lower_g;  /* g: proven, no state taken has a smaller reserve (= min_g when
                        exact) */
    int exact;       /* every state taken was evaluated or proven not smaller */
    size_t states;   /* states taken */
    long evaluated;  /* reserve evaluations run (states at rest cost none) */
    long faults;     /* evaluations in which a pulse run faulted */
} sw_reserve_log_t;

/* The smallest reserve along a log at scale 1, for what-if questions: the
 * log is run as sw_log_run() runs it (then free motion), its states taken
 * as sw_risk takes them (the first, then the first at or after each
 * multiple of 1/rate s), and the reserve evaluated on them in the order of
 * their proven lower bounds, smallest first (the most threatened states
 * first), until no state left can have a smaller reserve than the
 * smallest found: the same minimum as evaluating every state, at a
 * fraction of the cost.  With max_evals the search may stop before that:
 * exact is then 0 and the minimum lies in [lower_g, min_g].  Allocates
 * (a state per evaluation time); no I/O.  Returns SW_OK, SW_EINVAL (bad
 * arguments, no usable sample), SW_ENOMEM, the reserve's SW_ETOOBIG (a
 * scene too stiff for it) or a run's error, with the reason in msg. */
SW_API int sw_reserve_log_min(const sw_scene_t *sc, const sw_log_t *log,
                              const sw_reserve_log_opts_t *o, sw_reserve_log_t *out, char *msg,
                              size_t msglen);

#ifdef __cplusplus
}
#endif
#endif
