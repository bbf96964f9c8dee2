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

#include <stddef.h>

#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    SW_PHASE_STUCK = 0,     /* package moves with its support (theta = 0) */
    SW_PHASE_ROCKING = 1,   /* rocking about a base corner (bare/frame), or
                               moving on the cushion (cushion) */
    SW_PHASE_OVERTURNED = 2 /* |theta| reached pi/2: frozen */
} sw_phase;

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
    SW_EV_FAULT = 6     /* model fault (info = status code); package reset to rest */
} sw_event_kind;

/* State of one package.  Unused coordinates of simpler models stay 0. */
typedef struct {
    double u, u_dot;         /* m, m/s: frame displacement relative to the bed */
    double theta, theta_dot; /* rad, rad/s: tilt, > 0 top forward */
    double z, z_dot;         /* m, m/s: cushion compression at the base midpoint */
    sw_phase phase;
    int side; /* +1 rocking about the front corner, -1 the rear, 0 stuck;
                 on a cushion the sign of theta */
} sw_state_t;

typedef struct {
    size_t pkg;   /* index of the package (scene) */
    sw_event_kind kind;
    double t;     /* s */
    double theta; /* rad, at the event */
    double theta_dot; /* rad/s, after the event's map */
    double margin;    /* 1, after the event */
    double info;      /* see sw_event_kind */
} sw_event_t;

typedef struct {
    size_t pkg;
    double t;             /* s */
    sw_state_t state;
    double margin;        /* 1 at rest, 0 at the edge of overturning, < 0 beyond */
    double margin_bound;  /* guaranteed margin (frame, cushion); = margin for bare */
    double uplift_ratio;  /* |A| / (g tan alpha), A = acceleration of the support */
    double a_g;           /* m/s^2, bed acceleration used at t */
    double a_support;     /* m/s^2, absolute acceleration of the package's support */
} sw_output_t;

typedef void (*sw_event_fn)(void *user, const sw_event_t *ev);
typedef void (*sw_state_fn)(void *user, const sw_output_t *out);

typedef struct {
    const char *scheme; /* name from the scheme table (sw_scheme_lookup); NULL = default:
                           SW_DEFAULT_SCHEME, or SW_STIFF_SCHEME for a stiff cushion */
    double dt;          /* s, largest internal step; 0 = the scheme's default */
    int dt_forced;      /* non-zero: refuse (SW_EUNSTABLE) a dt above the stability
                           bound instead of sub-stepping */
    double rtol, atol;  /* adaptive schemes; 0 = defaults (1e-10, 1e-12) */
    double rest_eps;    /* rest threshold as a fraction of the energy barrier; 0 = 1e-9 */
    int stuck_stepped;  /* non-zero: step a stuck frame with the fixed-step scheme instead of
                           its exact solution (comparisons; the default is exact and cheaper) */
    sw_event_fn on_event;
    sw_state_fn on_state; /* called once per pushed sample and package; may be NULL */
    void *user;
} sw_engine_opts_t;

typedef struct {
    char name[SW_NAME_MAX];
    sw_model_kind model;
    int overturned;
    double overturn_time;  /* s, NAN if none */
    double tip_time;       /* s, NAN if none */
    double uplift_time;    /* s, NAN if none */
    double max_abs_theta;  /* rad */
    double max_theta_ratio;/* max|theta| / alpha */
    double min_margin;     /* 1 */
    double min_margin_bound;
    double max_uplift_ratio;
    long impacts, uplifts, rests, faults;
    long steps;            /* internal steps taken */
} sw_summary_t;

typedef struct sw_engine sw_engine_t;

/* Create an engine for n validated scenes.  On failure returns NULL and, if
 * err is not NULL, stores the code; msg (may be NULL) gets the reason, e.g.
 * the stability numbers for a forced dt. */
sw_engine_t *sw_engine_create(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *opts,
                              int *err, char *msg, size_t msglen);

/* Free everything; NULL is accepted. */
void sw_engine_destroy(sw_engine_t *e);

/* Back to the state after create: all packages at rest, no time yet. */
void sw_engine_reset(sw_engine_t *e);

/* Replace package pkg by a new scene (a scene file edited while the stream
 * runs): the package is rebuilt as sw_engine_create() would build it, with
 * the engine's options, and starts at rest at the current time with a fresh
 * summary; every other package keeps its state and summary untouched.
 * Allocates (the new package's work space).  Returns SW_OK, or an error
 * (SW_EINVAL, SW_EUNSTABLE, SW_ENOMEM, ...; msg says why) with the engine
 * unchanged. */
int sw_engine_replace(sw_engine_t *e, size_t pkg, const sw_scene_t *scene, char *msg,
                      size_t msglen);

/* Push one sample: bed acceleration a_g (m/s^2, x forward) and vertical
 * acceleration a_z (m/s^2, up; 0 if not measured) at time t (s).  The first
 * sample sets the start time.  Returns SW_OK, SW_EVENT if an event was
 * reported, or SW_EORDER / SW_ENONFINITE / SW_ETOOBIG (|a_g| or |a_z| above
 * SW_MAX_ACCEL) with the sample ignored and the state untouched.
 *
 * A package whose state leaves the model (not finite, g + a_z <= 0, or an
 * input so large that the fixed step exceeds the scheme's stability bound
 * for it) gets an SW_EV_FAULT event and is reset to rest; the others go on.
 * Outputs and events never carry a non-finite number. */
int sw_engine_push(sw_engine_t *e, double t, double a_g, double a_z);

/* Input given as a function of time instead of samples (pulses, tests):
 * advance from the current time to t1 with a_g = f(t), a_z = 0.  The start
 * time is 0 if nothing was pushed. */
typedef double (*sw_input_fn)(void *user, double t);
int sw_engine_advance_fn(sw_engine_t *e, double t1, sw_input_fn f, void *user);

/* End of stream: with settle > 0, continue with zero input for up to settle
 * seconds or until every package is at rest or overturned.  Returns SW_OK or
 * SW_EVENT. */
int sw_engine_finish(sw_engine_t *e, double settle);

/* Replace a package's state at the current time (tests, what-if runs). */
int sw_engine_set_state(sw_engine_t *e, size_t pkg, const sw_state_t *s);
int sw_engine_get_output(const sw_engine_t *e, size_t pkg, sw_output_t *out);

size_t sw_engine_count(const sw_engine_t *e);
double sw_engine_time(const sw_engine_t *e); /* s, NAN before the first sample */
const sw_derived_t *sw_engine_derived(const sw_engine_t *e, size_t pkg);
int sw_engine_summary(const sw_engine_t *e, size_t pkg, sw_summary_t *s);
const char *sw_engine_scheme(const sw_engine_t *e);
double sw_engine_dt(const sw_engine_t *e, size_t pkg); /* s, internal step in use */

/* Steppers, looked up by name.  Fixed-step: "euler", "heun", "rk4";
 * adaptive through GSL odeiv2: "rkf45", "rkck", "rk8pd", and the implicit
 * "rk4imp", "bsimp", "msbdf" (Jacobian by finite differences). */
typedef struct sw_scheme sw_scheme_t;
const sw_scheme_t *sw_scheme_lookup(const char *name);
const sw_scheme_t *sw_scheme_at(size_t i); /* NULL past the end */
const char *sw_scheme_name(const sw_scheme_t *s);
int sw_scheme_order(const sw_scheme_t *s);
int sw_scheme_adaptive(const sw_scheme_t *s);
double sw_scheme_default_dt(const sw_scheme_t *s); /* s */

/* Accuracy option: the cheapest scheme and internal step dt (s; 0 = the
 * scheme's default, for the adaptive ones) that kept the error of max|theta|
 * within theta_tol (rad) in the benchmark of docs/accuracy-speed.md, for the
 * model's reference scene (errors of fixed steps grow as (p dt)^order: a
 * package rocking faster than that scene needs a tighter tolerance).
 * *scheme is a static string for sw_engine_opts_t.scheme.  Returns SW_OK,
 * SW_ENOTFOUND when theta_tol is tighter than any setting measured, or
 * SW_EINVAL (theta_tol not > 0, NULL pointers, a model without a table). */
int sw_scheme_for_accuracy(sw_model_kind model, double theta_tol, const char **scheme, double *dt);

/* m/s^2 (about 10,000 g): no accelerometer on a vehicle reads more; a
 * larger value is a corrupt sample, refused by sw_engine_push(). */
#define SW_MAX_ACCEL 1e5

#define SW_DEFAULT_SCHEME "rk4"
#define SW_DEFAULT_DT 1e-3
/* Used instead when no scheme is given, no dt is forced and a cushion
 * scene is stiff: omega_max * dt > SW_STIFF_OMEGA_DT (docs/cushion.md). */
#define SW_STIFF_SCHEME "rkck"
#define SW_STIFF_OMEGA_DT 0.05

#ifdef __cplusplus
}
#endif
#endif
