/* SPDX-License-Identifier: GPL-3.0-or-later */
/* engine.h - the streaming integrator.
 *
 * Push-style: the caller owns the loop and pushes samples (t, a_g[, a_z]) in
 * increasing time order; the engine advances every package of every scene to
 * t at fixed internal steps (no longer than the requested dt, aligned to the
 * samples), interpolating the input linearly between samples.  Uplift,
 * impact, tipping and overturn are located inside a step, the step is cut
 * there, the impact map applied, and integration continues.  State is
 * reported once per pushed sample and events as they happen, through
 * callbacks.  Memory is fixed at create time: nothing grows with the log.
 *
 * Ownership: sw_engine_create() copies the scenes.  Not thread-safe; use one
 * engine per thread. */
#ifndef SWAYWATCH_ENGINE_H
#define SWAYWATCH_ENGINE_H

#include <signal.h>
#include <stddef.h>

#include "export.h"
#include "model.h"
#include "scene.h"
#include "scheme.h"

#ifdef __cplusplus
extern "C" {
#endif

/* On a cushion nothing impacts: UPLIFT is the first time an edge of the
 * base leaves the cushion (info +1 the rear edge, the top tipping forward;
 * -1 the front; 0 the whole base), REST the first end of a step after that
 * with the base in full contact again and too little energy of motion to
 * lift an edge with no input (docs/cushion.md). */
typedef enum {
    SW_EV_UPLIFT = 1,   /* rocking started; info = direction s (+1 forward) */
    SW_EV_IMPACT = 2,   /* the other corner landed; info = theta_dot before (rad/s) */
    SW_EV_REST = 3,     /* the cascade of impacts ended: stuck again */
    SW_EV_TIP = 4,      /* |theta| reached alpha (centre of mass over the corner) */
    SW_EV_OVERTURN = 5, /* |theta| reached pi/2 */
    SW_EV_FAULT = 6,    /* model fault (info = status code); package reset to rest */
    SW_EV_FLIGHT = 7    /* in free flight for SW_FLIGHT_LONG already (at t): its landing is
                           outside the model, the verdict incomplete; info = when the
                           flight began (s) */
} sw_event_kind;

/* "uplift", "impact", "rest", "tip", "overturn", "fault" (the events CSV's
 * event column); "unknown" for a value outside the enum. */
SW_API const char *sw_event_name(sw_event_kind k);

/* The vertical plane a package rocks in: along the truck (its width, the
 * longitudinal acceleration), or across it (its depth, the lateral
 * acceleration), for a scene with a depth in an engine made with
 * opts.lateral (physics.md, "The lateral plane"). */
typedef enum { SW_PLANE_LONG = 0, SW_PLANE_LAT = 1 } sw_plane;
#define SW_PLANES 2

/* "longitudinal", "lateral" ("unknown" for a value outside the enum). */
SW_API const char *sw_plane_name(sw_plane p);

typedef struct {
    size_t pkg; /* index of the package (scene) */
    sw_event_kind kind;
    double t;         /* s */
    double theta;     /* rad, at the event */
    double theta_dot; /* rad/s, after the event's map */
    double margin;    /* 1, after the event */
    double info;      /* see sw_event_kind */
    sw_plane plane;   /* where it happened: SW_PLANE_LONG, unless opts.lateral */
} sw_event_t;

typedef struct {
    size_t pkg;
    double t; /* s */
    sw_state_t state;
    double margin;       /* 1 at rest, 0 at the edge of overturning, < 0 beyond */
    double margin_bound; /* guaranteed margin (frame, cushion); = margin for bare */
    double uplift_ratio; /* |A| / (g tan alpha), A = acceleration of the support */
    double a_g;          /* m/s^2, bed acceleration used at t */
    double a_support;    /* m/s^2, absolute acceleration of the package's support */
    sw_plane plane;      /* the plane reported: SW_PLANE_LONG, unless opts.lateral (a_g is
                            then the lateral acceleration, a_support across the truck) */
} sw_output_t;

/* Non-zero if every number of o is finite (the engine never reports one
 * that is not; a consumer that copies or alters outputs can check its own). */
SW_API int sw_output_finite(const sw_output_t *o);

typedef void (*sw_event_fn)(void *user, const sw_event_t *ev);
typedef void (*sw_state_fn)(void *user, const sw_output_t *out);

typedef struct {
    const char *scheme; /* name from the scheme table (sw_scheme_lookup); NULL = default:
                           SW_DEFAULT_SCHEME, or SW_STIFF_SCHEME for a stiff cushion */
    double dt;          /* s, largest internal step; 0 = the scheme's default */
    int dt_forced;      /* non-zero: refuse (SW_EUNSTABLE) a dt above the stability
                           bound instead of sub-stepping */
    double rtol, atol;  /* adaptive schemes; 0 = defaults (1e-10, 1e-12) */
    double accuracy;    /* rad; > 0: choose the scheme and dt by sw_scheme_for_accuracy_n()
                           for the engine's scenes (scheme must be NULL and dt 0, else
                           SW_EINVAL); 0 = off */
    double rest_eps;    /* rest threshold as a fraction of the energy barrier; 0 = 1e-9 */
    int stuck_stepped;  /* non-zero: step a stuck frame with the fixed-step scheme instead of
                           its exact solution (comparisons; the default is exact and cheaper) */
    int outcome_only;   /* non-zero: do not time what only the report needs inside steps:
                           peaks of |theta|, tips past alpha, a cushion's lifts (the
                           summary's max |theta| then comes from step ends; no TIP, no
                           cushion UPLIFT or REST events), and, without on_state, no
                           margins after each call (the summary's minimum margins see
                           only the events; sw_engine_get_output computes them on
                           demand); for runs that need only whether and when a package
                           overturns, such as the reserve's */
    int check_default;  /* non-zero: where scheme or dt (given, not chosen by accuracy) make
                           the engine integrate otherwise than it would by itself (no
                           scheme, no dt), run that default beside it on the same input,
                           outcome only, so that a verdict can be checked against it
                           (sw_engine_checker); it costs that second engine */
    sw_event_fn on_event;
    sw_state_fn on_state; /* called once per pushed sample and package; may be NULL */
    void *user;
    int lateral;     /* non-zero: the caller pushes a lateral acceleration too
                        (sw_engine_push_lat), and each package whose scene has a depth
                        rocks in a lateral plane as well (sw_scene_lateral: its own
                        scheme and step, as an engine of that scene alone would take
                        them); its events and states come through the same callbacks
                        with plane SW_PLANE_LAT, each sample's lateral states before
                        the longitudinal ones.  0: one plane, a depth is not read, and
                        nothing of a second plane is allocated or computed */
    int margins_off; /* non-zero, without on_state: no margins after each call, as with
                        outcome_only, while peaks, tips and lifts are still timed (the
                        summary's minimum margins and largest uplift ratio then see
                        only the events; sw_engine_get_output computes them on
                        demand); for
                        runs that need whether a package overturns and its peak, such
                        as the safety factor's search trials */
} sw_engine_opts_t;

typedef struct {
    char name[SW_NAME_MAX];
    sw_model_kind model;
    int overturned;
    double overturn_time;   /* s, NAN if none */
    double tip_time;        /* s, NAN if none */
    double uplift_time;     /* s, NAN if none */
    double max_abs_theta;   /* rad */
    double max_theta_ratio; /* max|theta| / alpha */
    double min_margin;      /* 1 */
    double min_margin_bound;
    double max_uplift_ratio;
    long impacts, uplifts, rests, faults;
    long steps;              /* internal steps taken */
    long flights;            /* times the package left its support in free flight (the bed
                                falling faster than gravity: physics.md, "Free flight") */
    double flight_max;       /* s, the longest of them (0: none) */
    double flight_long_time; /* s, when the first flight longer than SW_FLIGHT_LONG began
                                (NAN: none): what followed it is not a verdict */
} sw_summary_t;

/* s: a flight longer than this leaves the verdict incomplete: its landing
 * from centimetres up is where the no-bounce, no-slide impact of the
 * model is doubtful (physics.md, "Free flight"). */
#define SW_FLIGHT_LONG 0.1

typedef struct sw_engine sw_engine_t;

/* Create an engine for n validated scenes.  On failure returns NULL and, if
 * err is not NULL, stores the code; msg (may be NULL) gets the reason, e.g.
 * the stability numbers for a forced dt. */
SW_API sw_engine_t *sw_engine_create(const sw_scene_t *scenes, size_t n,
                                     const sw_engine_opts_t *opts, int *err, char *msg,
                                     size_t msglen);

/* Free everything; NULL is accepted. */
SW_API void sw_engine_destroy(sw_engine_t *e);

/* Back to the state after create: all packages at rest, no time yet. */
SW_API void sw_engine_reset(sw_engine_t *e);

/* Replace package pkg by a new scene (a scene file edited while the stream
 * runs): the package is rebuilt as sw_engine_create() would build it, with
 * the engine's options, and starts at rest at the current time with a fresh
 * summary; every other package keeps its state and summary untouched.
 * Allocates (the new package's work space).  Returns SW_OK, or an error
 * (SW_EINVAL, SW_EUNSTABLE, SW_ENOMEM, ...; msg says why) with the engine
 * unchanged. */
SW_API int sw_engine_replace(sw_engine_t *e, size_t pkg, const sw_scene_t *scene, char *msg,
                             size_t msglen);

/* Push one sample: bed acceleration a_g (m/s^2, x forward) and vertical
 * acceleration a_z (m/s^2, up; 0 if not measured) at time t (s).  The first
 * sample sets the start time; the engine integrates on time relative to it
 * (outputs, events and summaries give the caller's times), so epoch times
 * cost no accuracy.  Returns SW_OK, SW_EVENT if an event was reported, or
 * SW_EORDER / SW_ENONFINITE / SW_ETOOBIG (|a_g| or |a_z| above
 * SW_MAX_ACCEL) / SW_ERESOLUTION (|t| >= 2^33 s, whose steps are coarser
 * than 2e-6 s: a time unit mistake) with the sample ignored and the state
 * untouched.
 *
 * A package whose state leaves the model (not finite, g + a_z <= 0, or an
 * input so large that the fixed step exceeds the scheme's stability bound
 * for it) gets an SW_EV_FAULT event and is reset to rest; the others go on.
 * Outputs and events never carry a non-finite number. */
SW_API int sw_engine_push(sw_engine_t *e, double t, double a_g, double a_z);

/* Push one sample with its lateral acceleration a_y (m/s^2, across the
 * truck; which side is positive is the caller's choice, the planes being
 * symmetric: the states' theta then tips toward +y): as sw_engine_push,
 * the lateral planes driven by a_y and a_z, the longitudinal ones by a_g
 * and a_z.  A sample one plane would refuse is refused whole (a_y is
 * checked as a_g is), the state untouched.  On an engine without lateral
 * planes a_y is checked and then not used.  An engine with lateral planes
 * takes its samples here only: sw_engine_push() on it returns SW_EINVAL
 * (a sample without its lateral value cannot drive the lateral planes,
 * and is not guessed). */
SW_API int sw_engine_push_lat(sw_engine_t *e, double t, double a_g, double a_y, double a_z);

/* Before the first sample: integrate on time relative to t0 (s) instead
 * of the first sample's time, which may then be any time >= t0.  A run
 * that starts part-way through a log with the log's first time as t0
 * does the very arithmetic of a run from the log's start: for a package
 * standing still up to there, the same result to the last bit.  Returns
 * SW_OK, SW_EINVAL (started already, t0 not finite) or SW_ERESOLUTION. */
SW_API int sw_engine_set_origin(sw_engine_t *e, double t0);

/* The stream goes on after an interruption that is not to be bridged (a
 * sensor restart, an outage too long to interpolate over): every package
 * not overturned is put back at rest, and the next pushed sample starts the
 * input afresh, with nothing interpolated from the last one.  Summaries
 * are kept.  Time must still increase.  Returns SW_OK (SW_EINVAL for NULL). */
SW_API int sw_engine_restart(sw_engine_t *e);

/* Input given as a function of time instead of samples (pulses, tests):
 * advance from the current time to t1 with a_g = f(t), a_z = 0.  The start
 * time is 0 if nothing was pushed.  Lateral planes move freely (a_y = 0). */
typedef double (*sw_input_fn)(void *user, double t);
SW_API int sw_engine_advance_fn(sw_engine_t *e, double t1, sw_input_fn f, void *user);
/* The quiet input, 0 m/s^2 at every t (user ignored): free motion. */
SW_API double sw_input_zero(void *user, double t);

/* End of stream: with settle > 0, continue with zero input for up to settle
 * seconds or until every package is at rest or overturned, or until the
 * stop flag (sw_engine_set_stop) is set.  Returns SW_OK or SW_EVENT. */
SW_API int sw_engine_finish(sw_engine_t *e, double settle);

/* A flag of the caller's that ends sw_engine_finish() early: once *stop
 * is non-zero, the free motion ends after the millisecond of it being
 * computed (its states reported whole), so a long settle cannot outlast
 * a signal.  The engine only reads it (a signal handler may set it).
 * NULL, the default: nothing ends it early. */
SW_API void sw_engine_set_stop(sw_engine_t *e, const volatile sig_atomic_t *stop);

/* Replace a package's state at the current time (tests, what-if runs). */
SW_API int sw_engine_set_state(sw_engine_t *e, size_t pkg, const sw_state_t *s);
SW_API int sw_engine_get_output(const sw_engine_t *e, size_t pkg, sw_output_t *out);
/* The state alone: what get_output reports first, without its margins. */
SW_API int sw_engine_get_state(const sw_engine_t *e, size_t pkg, sw_state_t *s);

SW_API size_t sw_engine_count(const sw_engine_t *e);
SW_API double sw_engine_time(const sw_engine_t *e); /* s, NAN before the first sample */
SW_API const sw_derived_t *sw_engine_derived(const sw_engine_t *e, size_t pkg);
SW_API int sw_engine_summary(const sw_engine_t *e, size_t pkg, sw_summary_t *s);
SW_API const char *sw_engine_scheme(const sw_engine_t *e);

/* The planes of package pkg: 2 when it rocks in a lateral plane too
 * (opts.lateral and a depth), 1 when not, 0 for no such package. */
SW_API int sw_engine_planes(const sw_engine_t *e, size_t pkg);
/* One plane's summary (sw_engine_summary is the longitudinal one) and
 * its current output; SW_ENOTFOUND for a plane the package does not
 * have. */
SW_API int sw_engine_summary_plane(const sw_engine_t *e, size_t pkg, sw_plane plane,
                                   sw_summary_t *s);
SW_API int sw_engine_get_output_plane(const sw_engine_t *e, size_t pkg, sw_plane plane,
                                      sw_output_t *out);

/* The engine that holds plane p of package pkg (e itself for
 * SW_PLANE_LONG; the lateral planes' engine, owned by e, for
 * SW_PLANE_LAT), with the package's index there in *k: read it with
 * sw_engine_summary, sw_engine_derived, sw_engine_scheme, sw_engine_dt_used
 * (as sw_engine_checker's).  NULL when the package has no such plane. */
SW_API const sw_engine_t *sw_engine_plane(const sw_engine_t *e, size_t pkg, sw_plane p, size_t *k);

/* What the planes of a package say together. */
typedef struct {
    int planes;       /* 1 or 2 */
    sw_plane worse;   /* the plane of the verdict (sw_summary_worse): SW_PLANE_LONG with one */
    int both_rocking; /* both planes were lifted at once (at a sample): the package may
                         have rocked on a corner, which the planar models do not describe,
                         and the verdict after it is their decoupled approximation
                         (physics.md, "The lateral plane") */
    double both_from; /* s, the first sample time at which both were lifted (NAN: never) */
    double both_to;   /* s, the last one (NAN: never) */
    double both_time; /* s, how long both were lifted, summed over sample intervals */
} sw_planes_t;
SW_API int sw_engine_planes_summary(const sw_engine_t *e, size_t pkg, sw_planes_t *p);

/* Which of two planes' summaries is the worse: 1 for b, 0 for a.  An
 * overturned plane is worse than one that is not, of two overturned
 * the earlier; else the smaller min_margin, then the larger
 * max_theta_ratio; a tie goes to a. */
SW_API int sw_summary_worse(const sw_summary_t *a, const sw_summary_t *b);
SW_API double sw_engine_dt(const sw_engine_t *e, size_t pkg); /* s, internal step in use */
/* The step a package's fixed-step scheme actually took: the longest so
 * far (s; a sample interval shorter than sw_engine_dt cuts the steps to
 * it, an event cuts one short).  sw_engine_dt before the first step, and
 * for an adaptive scheme (whose steps its error control chooses). */
SW_API double sw_engine_dt_used(const sw_engine_t *e, size_t pkg);
/* The step asked for (s): opts.dt, or the scheme's default; where the
 * engine shortened it (an unforced dt above a mode's stability bound)
 * sw_engine_dt is less. */
SW_API double sw_engine_dt_requested(const sw_engine_t *e);
/* The engine running the default scheme and step beside e (opts
 * check_default), outcome only, on the same input; NULL when there is
 * none (not asked for, or e's own setting is the default).  Read with
 * sw_engine_summary, sw_engine_scheme, sw_engine_dt; owned by e. */
SW_API const sw_engine_t *sw_engine_checker(const sw_engine_t *e);

/* m/s^2 (about 10,000 g): no accelerometer on a vehicle reads more; a
 * larger value is a corrupt sample, refused by sw_engine_push(). */
#define SW_MAX_ACCEL 1e5

#ifdef __cplusplus
}
#endif
#endif
