/* SPDX-License-Identifier: GPL-3.0-or-later */
/* internal.h - what the library's modules share and the public API hides.
 *
 * The engine is built in layers, as GSL's ode-initval2 (step -> evolve ->
 * driver) and CVODE's root finding are:
 *
 *   engine.c   the API and the sample loop: create, push, finish, reports
 *   pkg.c      one package's phase machine: uplift, impact, rest, overturn,
 *              fault, and the summary; emits events
 *   event.c    events inside a step: candidates from the model, roots on
 *              the cubic Hermite interpolant (hermite.h), polished by
 *              re-stepping
 *   step.c     one step with the engine's scheme (a row of scheme.c)
 *   stuck.c    exact solutions while a package stands on its support
 *   model*.c   the physics, one ops table per model (right-hand side,
 *              events, impact map, margins, rest test)
 *
 * Calls go down only: engine -> pkg/event -> step -> model.  The engine
 * never branches on the scheme or the model: it reads the scheme's row and
 * the package's model ops. */
#ifndef SWAYWATCH_INTERNAL_H
#define SWAYWATCH_INTERNAL_H

#include <math.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "swaywatch/engine.h"
#include "swaywatch/model.h"
#include "swaywatch/scene.h"

#define SW_NMAX 6 /* longest state vector: cushion on a frame (u, theta, z and rates) */

/* The input seen by a package inside one step: linear in time between two
 * samples (a_g = ag0 + ag_slope (t - t0)), or a function (pulses). */
typedef struct {
    double t0;            /* s */
    double ag0, ag_slope; /* m/s^2, m/s^3 */
    double az0, az_slope; /* m/s^2, m/s^3 (vertical, up) */
    sw_input_fn fn;       /* if not NULL: a_g = fn(fn_user, fn_t0 + t), a_z = 0 */
    void *fn_user;
    double fn_t0; /* s: the engine's origin (fn takes absolute time) */
} sw_input_t;

typedef struct sw_pkg sw_pkg_t;
typedef struct sw_model_ops sw_model_ops_t;

/* The values of sw_model_kind: the rows of every table indexed by it (the
 * models in model.c, the schemes' specialised bodies in scheme.c). */
#define SW_MODEL_KINDS 3

/* A package as its model sees it (GSL's params, CVODE's user data): the
 * parameters, set once when the package is built, the input, and the mode
 * the phase machine (pkg.c, flight.c) sets at its maps, which selects the
 * equations (the hybrid system's discrete state). */
typedef struct {
    const sw_model_ops_t *ops; /* the model's behaviour table */
    sw_derived_t d;
    double g;               /* m/s^2, nominal gravity */
    double kR;              /* 1/m, 3/(4R) = p^2/g */
    double tan_alpha;       /* 1 */
    double frame_mass;      /* kg, m_b (0 without a frame) */
    int n;                  /* length of the state vector */
    int ith, idth;          /* indices of theta and theta_dot in y */
    int iu, idu;            /* u, u_dot (-1 without a frame) */
    int iz, idz;            /* z, z_dot (-1 without a cushion) */
    double yscale[SW_NMAX]; /* typical size of each component (finite-difference Jacobian) */
    double e_lift;          /* J/kg, cushion: least energy above rest that lifts an edge */
    double rate_rest;       /* 1/s, the contact's rate bound at rest (model_cushion.c) */
    double e_barrier;       /* J/kg, cushion: sw_cushion_barrier() under nominal gravity */
    double v_rest;          /* J/kg, cushion: potential at rest under nominal gravity */
    const sw_input_t *in;   /* the engine's input over the interval being integrated */
    /* the mode */
    sw_phase phase;
    int side;   /* s = +1 / -1 while rocking */
    int flying; /* in the air (flight.c): no contact with the support */
} sw_model_t;

/* What a model's right-hand side writes as it goes: its scratch, one per
 * package, passed beside the model. */
typedef struct {
    double trig[3];   /* model_rigid.h: an angle (NAN: none yet), its sin and cos */
    int track_rate;   /* cushion: the right-hand side records rate_seen */
    double rate_seen; /* rad/s, fastest contact rate met by the stages of a step */
} sw_model_scratch_t;

/* A model and its scratch: GSL's params for sw_model_rhs and
 * sw_model_jacobian. */
typedef struct {
    const sw_model_t *m;
    sw_model_scratch_t *s;
} sw_model_sys_t;

typedef struct sw_stepper sw_stepper_t;

/* What the step and event layers of one engine share: its scheme and the
 * options they read, and the step being examined (for a multistep
 * re-step).  Owned by the engine, embedded in it. */
typedef struct {
    const sw_scheme_t *scheme;
    int dt_forced;         /* a forced dt is refused, never sub-stepped */
    int outcome_only;      /* peaks and tips are not timed (sw_engine_opts_t) */
    double hmax;           /* s, longest step (SW_ACCURACY_HMAX under the accuracy option,
                              else INFINITY) */
    const double *step_y1; /* end of the step being examined */
    double step_h;         /* s, its length */
} sw_step_ctx_t;

/* One fixed step of length h (s) from (t, y) into yout. */
typedef void (*sw_fixed_step_fn)(const sw_model_t *M, sw_model_scratch_t *S, double t, double h,
                                 const double y[], double yout[]);

/* One step from (t0, y0) toward t1 into y1; *h gets its length. */
typedef int (*sw_advance_fn)(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, const double y0[],
                             double t1, double y1[], double *h);

/* The scheme's work space for one package (step.c), as GSL's step,
 * control and evolve objects are theirs: bound to the package's model. */
struct sw_stepper {
    sw_model_sys_t ms;     /* the model it steps and its scratch (GSL's params) */
    double h;              /* s, largest internal step for this package */
    double stab_rate;      /* omega_max h at the edge of the scheme's stability region
                              for the modes at rest (INFINITY: adaptive, or no mode) */
    sw_advance_fn advance; /* the scheme's advance for this model */
    sw_fixed_step_fn step; /* fixed-step schemes: the body for this model */
    gsl_odeiv2_system sys;
    gsl_odeiv2_step *gstep; /* adaptive schemes only */
    gsl_odeiv2_control *gctl;
    gsl_odeiv2_evolve *gevo;
    double h_adapt;         /* s, GSL's proposed next step */
    gsl_odeiv2_driver gdrv; /* not allocated: hands gctl to GSL's implicit steppers */
};

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
    double t_lift;    /* s, time of the last uplift */
    int hold;         /* keep the package stuck for one step (pkg.c's after_impact) */
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

/* ---- small numerical helpers ---------------------------------------------- */

/* GCC and clang: inline even where the size heuristics would not (each
 * scheme's stages are where the time goes). */
#if defined(__GNUC__)
#define SW_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define SW_ALWAYS_INLINE inline
#endif

/* Every v[i] finite?  0 v is 0 for a finite v and NaN for an infinite or
 * NaN one, so the sum of them is 0 exactly when all are finite: two
 * multiply-adds a number and no branch, in two chains that overlap (the
 * state and the report are checked on every step and sample). */
static inline int sw_all_finite(const double v[], size_t n)
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

/* max and min of numbers known to be finite: inline where libm's fmax and
 * fmin are calls (they must handle NaN), for the per-step checks. */
static inline double sw_max2(double a, double b)
{
    return a > b ? a : b;
}

static inline double sw_min2(double a, double b)
{
    return a < b ? a : b;
}

/* The input at time t (s): a_g, and g_eff = g + a_z (m/s^2) for nominal
 * gravity g.  Inline: a right-hand side evaluates them at every stage. */
static inline double sw_input_ag(const sw_input_t *in, double t)
{
    if (in->fn)
        return in->fn(in->fn_user, in->fn_t0 + t);
    return in->ag0 + in->ag_slope * (t - in->t0);
}
static inline double sw_input_geff(const sw_input_t *in, double g, double t)
{
    if (in->fn)
        return g;
    return g + in->az0 + in->az_slope * (t - in->t0);
}

/* ---- models (model.c, model_rigid.c, model_cushion.c) ---------------------- */

/* Event functions: each "rises through 0" at its event.  The cutting ones
 * end the step there and apply their map (pkg.c); the others are timed
 * inside the step. */
enum {
    SW_EVF_NONE = 0,
    SW_EVF_IMPACT,      /* the rocking corner's other side lands */
    SW_EVF_OVERTURN,    /* |theta| reaches pi/2 */
    SW_EVF_UPLIFT_FWD,  /* a stuck frame's support reaches the threshold, top forward */
    SW_EVF_UPLIFT_BACK, /* ... backward */
    SW_EVF_TIP,         /* |theta| reaches alpha */
    SW_EVF_TURN,        /* |theta| stops growing: a peak */
    /* cushion: an edge leaves / regains the cushion (B below the surface:
     * full <-> partial contact), the last edge does (B above: partial <->
     * free flight); the _IN variants are the reverse crossings */
    SW_EVF_LIFT,
    SW_EVF_LIFT_IN,
    SW_EVF_FLY,
    SW_EVF_FLY_IN
};

/* What the event layer does with a candidate. */
enum {
    SW_ROLE_CUT,  /* the earliest of these ends the step (its map follows) */
    SW_ROLE_PEAK, /* a peak of |theta| inside the step: max |theta| */
    SW_ROLE_TIP,  /* |theta| = alpha: timed and reported */
    SW_ROLE_LIFT  /* the first lift since rest of a package that never impacts */
};

/* How its root is searched on the interpolant over [0, 1]. */
enum {
    SW_RULE_RISE,  /* through at the start (value > 0, or 0 and rising): 0; else the first
                      rise above round-off, or the end if only round-off hid it */
    SW_RULE_PLAIN, /* the first rise from below 0 to >= 0; none at the start */
    SW_RULE_KINK   /* a kink of the right-hand side to cut at: only from below, strictly
                      inside the step */
};

typedef struct {
    unsigned char ev;    /* SW_EVF_* */
    unsigned char role;  /* SW_ROLE_* */
    unsigned char rule;  /* SW_RULE_* */
    unsigned char clear; /* skip when clearly below 0 over the whole step (uplift) */
} sw_evcand_t;

#define SW_MAX_CANDS 8

/* What the caller knows of the step that ops->candidates must honour. */
enum {
    SW_CAND_KINKS = 1, /* the scheme's steps must be cut at kinks of the right-hand side */
    SW_CAND_HELD = 2,  /* the package is held on its support for this step: no uplift */
    SW_CAND_LIFTED = 4 /* it lifted since its last rest: its first lift is timed already */
};

/* What a stuck package's exact advance did (stuck.c). */
enum {
    SW_STUCK_STEP = -1, /* not handled: step the package with the scheme */
    SW_STUCK_STILL = 0, /* stuck up to the end of the interval */
    SW_STUCK_MOVED = 1, /* P->t moved on: look again */
    SW_STUCK_LIFT = 2,  /* lifted at P->t, direction *side */
    SW_STUCK_FAULT = 3  /* the exact advance made no progress: a fault, never a hang */
};

/* The rocking about rest to first order as one damped oscillator
 * u'' + 2 zeta w u' + w^2 u = -a (the input, m/s^2), theta = gain u: what
 * checkpoints step in closed form between samples (safety_prep.c). */
typedef struct {
    double w, zeta;   /* rad/s, 1 */
    double gain;      /* theta per u, rad/m */
    double per;       /* the lift drive over its level per unit u, 1/m */
    double lam;       /* 1/s: the decay rate of the slowest mode about rest */
    double wz, zetaz; /* rad/s, 1: the vertical mode about rest (z, the state's z) */
    double per_z;     /* the lift drive over its level per unit of z - z_s, 1/m */
} sw_rock_linear_t;

typedef struct sw_model_traits sw_model_traits_t;

/* A model's behaviour: what the engine's layers do with a package of it.
 * Adding a model is one model_X.c with one of these (and its traits) and
 * a row in sw_model_ops_of() (model.c). */
struct sw_model_ops {
    const char *name;
    const sw_model_traits_t *traits; /* what can be said from the scene alone */
    /* layout of y, typical sizes, constants (after the common set-up) */
    void (*setup)(sw_model_t *M, const sw_scene_t *sc);
    /* f = y' at (t, y); GSL_SUCCESS, or a GSL error that makes an adaptive
     * step retry shorter.  May write the scratch S. */
    int (*rhs)(const sw_model_t *M, sw_model_scratch_t *S, double t, const double y[], double f[]);
    /* the state at rest into y (zeroed before), and its mode; NULL: the
     * zeroed state, standing */
    void (*rest)(sw_model_t *M, double y[]);
    /* the events to look for over the step (t0, y0) -> (t0 + h, y1), in the
     * order they are handled, given what the caller knows (SW_CAND_*).
     * Returns how many (<= SW_MAX_CANDS). */
    int (*candidates)(const sw_model_t *M, int flags, double h, const double y0[],
                      const double y1[], sw_evcand_t c[]);
    /* value and time derivative of event function ev at (t, y), f = y' */
    void (*event_fn)(const sw_model_t *M, int ev, double t, const double y[], const double f[],
                     double *val, double *der);
    /* at theta = 0: the velocity map on y, the side flips; NULL: never
     * impacts */
    void (*impact)(sw_model_t *M, double y[]);
    /* at theta = 0: theta' to 0 (a landing, the end of a cascade), whatever
     * the support takes of the package's momentum; NULL with impact */
    void (*land)(const sw_model_t *M, double y[]);
    /* +1 / -1 if the support is beyond the uplift threshold at t, else 0 */
    int (*uplift_side)(const sw_model_t *M, double t, const double y[]);
    /* how the package stands on its support, which stuck.c solves exactly
     * (SW_STANDS_*); 0: it never stands still (a cushion) */
    int stands;
    /* the rest of the report after the common part (sw_model_output) */
    void (*output)(const sw_model_t *M, const sw_model_scratch_t *S, double t, const double y[],
                   sw_output_t *o);
    /* the side as the state decides it, after an accepted step and at a
     * cut before its map (a cushion's is the sign of theta); NULL: the
     * maps set it */
    void (*follow)(sw_model_t *M, const double y[]);
    /* a package that lifted since its last rest is back at rest (it can
     * no longer lift without input): checked after every accepted step
     * with no cut, and said by the phase machine (sw_pkg_after_step);
     * NULL: rest only through the maps */
    int (*at_rest)(const sw_model_t *M, const double y[]);
    /* still moving, for sw_engine_finish (settled packages end it early) */
    int (*moving)(const sw_model_t *M, const double y[], double rest_eps);
    /* the right-hand side reports the fastest contact rate of its stages,
     * and a fixed step is retaken shorter where that rate is too fast; a
     * model with such a contact can be stiff (sw_model_stiff) */
    int tracks_rate;
    /* g_eff <= 0, the bed falling away faster than gravity: SW_FLIES_CLOSED,
     * a rigid package flies in closed form (flight.c); SW_FLIES_INTEGRATED,
     * the model's equations hold with no contact (a cushion's free
     * flight); 0: outside the model, a fault */
    int flies;
};

enum { SW_FLIES_CLOSED = 1, SW_FLIES_INTEGRATED = 2 };

/* ops->stands: SW_STANDS_RIGID, on a rigid support that the input itself
 * must accelerate beyond g_eff tan(alpha) to lift the package (the bare
 * block); SW_STANDS_OSCILLATOR, on a linear oscillator (u, u') whose
 * acceleration must (the frame). */
enum { SW_STANDS_RIGID = 1, SW_STANDS_OSCILLATOR = 2 };

extern const sw_model_ops_t sw_model_bare, sw_model_frame, sw_model_cushion;
const sw_model_ops_t *sw_model_ops_of(sw_model_kind kind);

/* What can be said of a model from its scene alone, with no package run:
 * pure functions of the derived quantities, and the claims the analyses
 * that run a package many times (run.c, sweep.c, safety*.c, reserve*.c)
 * and the alarms rely on, so that they never ask which model it is. */
struct sw_model_traits {
    /* model.h's sw_model_energy, sw_model_barrier, sw_model_work_rate */
    double (*energy)(const sw_derived_t *d, double g, const sw_state_t *s);
    double (*barrier)(const sw_derived_t *d, double g);
    double (*work_rate)(const sw_derived_t *d);
    /* a package not rocking can no longer lift without input
     * (sw_model_settled); NULL: never proven */
    int (*settled)(const sw_derived_t *d, double g, const sw_state_t *s);
    /* the modes about rest a fixed step must keep stable (model.h's
     * sw_model_modes): how many into m */
    int (*modes)(const sw_derived_t *d, double g, sw_mode_t m[SW_MODES_MAX]);
    /* a rocking package lands on its corners with an impact (the alarms'
     * impact speed); 0: it lands without one (a cushion) */
    int impacts;
    /* the package leaves its rest contact exactly when the input itself
     * reaches g tan(alpha) (the bare block): there is nothing to probe */
    int lift_direct;
    /* free rocking is decided by the margin exactly (physics.md's closed
     * form for the bare block): stuck it rests, past alpha moving out it
     * falls */
    int free_exact;
    /* standing, the package rides a linear oscillator (u, u') driven by
     * the input (the frame: stuck.c, reserve_lift.c's table) */
    int stuck_linear;
    /* leaving the rest contact: the drive of a report, and the drive at
     * which the package leaves (the level); about rest the drive is linear
     * in the input, to first order, so a probe far too small to lift
     * scales to the lifting input */
    double (*lift_level)(const sw_derived_t *d, double g);
    double (*lift_drive)(const sw_derived_t *d, double level, const sw_output_t *o);
    /* the fastest and the slowest rate (rad/s) of the response about rest,
     * which a probe must sample and wait for; NULL with lift_direct */
    void (*probe_rates)(const sw_derived_t *d, double g, double *fast, double *slow);
    /* a pulse's probe finds at least this fraction of the lifting
     * amplitude (the search starts there) */
    double probe_margin;
    /* the rocking about rest, to first order, as one damped oscillator
     * (sw_rock_linear_t) for a package of mass m (kg): 1 and *r filled, or
     * 0 when the model has none; NULL: never */
    int (*rock_linear)(const sw_derived_t *d, double m, double g, sw_rock_linear_t *r);
};

/* The traits of a model kind, NULL for a kind outside the enum. */
const sw_model_traits_t *sw_model_traits_of(sw_model_kind kind);

/* The decaying roots of a lambda^2 + b lambda + c = 0 (a > 0, b >= 0) as
 * modes named name, appended to m[0..n) up to SW_MODES_MAX: one (with its
 * conjugate implied) when they are complex, two when real; the new count.
 * A root at 0 or growing is not a mode to keep stable; an undamped
 * oscillation is. */
int sw_modes_quadratic(sw_mode_t m[SW_MODES_MAX], int n, double a, double b, double c,
                       const char *name);
/* The complex root re + i im appended as a mode (if it decays, or
 * oscillates undamped): the new count. */
int sw_modes_add(sw_mode_t m[SW_MODES_MAX], int n, double re, double im, const char *name);

/* The model's contact is too fast for fixed steps of dt (s): the default
 * scheme is then SW_STIFF_SCHEME (engine.c). */
int sw_model_stiff(const sw_derived_t *d, double dt);
/* The model of a package of scene sc (M->d filled, the rest zeroed):
 * common constants, then ops->setup; S ready for the first step. */
void sw_model_setup(sw_model_t *M, sw_model_scratch_t *S, const sw_scene_t *sc);
/* Typical size of component i of the state (m or rad), for finite-
 * difference Jacobians, and of its rate di at the scene's fastest
 * frequency (ops->setup: every component). */
void sw_model_scale(sw_model_t *M, int i, int di, double size);
/* The right-hand side and a finite-difference Jacobian (for the implicit
 * schemes) in GSL's signature; params: a sw_model_sys_t. */
int sw_model_rhs(double t, const double y[], double f[], void *params);
int sw_model_jacobian(double t, const double y[], double *dfdy, double dfdt[], void *params);
void sw_model_to_state(const sw_model_t *M, const double y[], sw_state_t *s);
void sw_model_from_state(sw_model_t *M, double y[SW_NMAX], const sw_state_t *s);
void sw_model_output(const sw_model_t *M, const sw_model_scratch_t *S, double t, const double y[],
                     sw_output_t *o);

/* ---- stuck.c: exact solutions of a package standing on its support ---------- */

/* Advance a stuck package toward t1 exactly, as its model stands
 * (ops->stands): the bare block's uplift time solved for on the linear
 * input, or the pulse scanned at the package's step and the crossing
 * bisected; the frame's linear oscillator in closed form under sampled
 * input where exact is set (the scheme allows it), else SW_STUCK_STEP.
 * On SW_STUCK_LIFT, *side is the direction. */
int sw_stuck_advance(sw_pkg_t *P, double t1, int exact, int *side);
/* The exact step of the damped oscillator u'' + 2 zeta w u' + w^2 u = -a(t),
 * a = a0 + s t, over H (s) from (u, u') = u0 into u1 (Nigam & Jennings, as
 * a stuck frame takes it): for the linear response of other models. */
void sw_nj_step(double w, double zeta, double H, double a0, double s, const double u0[2],
                double u1[2]);

/* ---- scheme.c ------------------------------------------------------------------ */

/* A scheme's behaviour.  The engine reads its row, never its name. */
struct sw_scheme {
    const char *name;
    int order;
    int adaptive;      /* GSL's error control chooses the steps */
    double stab;       /* |lambda h| bound on the negative real axis (fixed steps; 0:
                          none to check, the error control keeps it) */
    int region;        /* fixed steps: the stability function R(z) is the Taylor
                          polynomial of e^z of this degree (an explicit Runge-Kutta
                          scheme with as many stages as its order, up to 4); its
                          stability region is |R(z)| <= 1.  0: adaptive */
    double default_dt; /* s */
    /* one step toward t1 (step.c: fixed sub-steps, or GSL's evolve); for
     * the fixed schemes also one per model with its body inlined (NULL:
     * the generic one serves) */
    sw_advance_fn advance;
    sw_advance_fn advance_for[SW_MODEL_KINDS];
    /* the solution at t0 + h inside the step being examined (step.c:
     * re-step from its start, or the Hermite interpolant of a multistep
     * scheme, which cannot restart without losing its history) */
    int (*restep)(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, double h, const double y0[],
                  double y1[]);
    /* fixed steps: the body specialised for a model (the right-hand side
     * inlined per stage), or NULL for the generic body below */
    sw_fixed_step_fn step_for[SW_MODEL_KINDS];
    sw_fixed_step_fn step;                       /* the generic body (the model's rhs per stage) */
    const gsl_odeiv2_step_type *const *gsl_type; /* adaptive schemes */
    int implicit;    /* needs the Jacobian, and a driver for its Newton tolerances */
    int cut_kinks;   /* fixed steps lose their order across a kink of the
                        right-hand side: cut them there */
    int exact_stuck; /* a stuck frame may take its exact solution (the adaptive
                        schemes step it, under their own error control) */
};

/* One fixed step from (P->t, P->y) into y1, no longer than the package's
 * step h nor than what is left of the interval, splitting that into equal
 * steps; body is the scheme's step for the model.  A model that tracks its
 * contact rate (track: it may) can pass through states far stiffer than
 * rest (a cushion landing on a corner or flat, a cubic cushion compressed
 * hard) where a step that is stable at rest blows up or skips the
 * landing: its right-hand side reports the fastest contact rate its
 * stages met, and the step is retaken shorter until that rate times h is
 * within the bound the package's h keeps at rest (0.5, or the scheme's
 * stability bound for a forced dt).  A template: scheme.c instantiates it
 * per scheme and model with the body known, so that a step is one call. */
static SW_ALWAYS_INLINE int sw_step_fixed_with(const sw_step_ctx_t *C, sw_stepper_t *W, double t0,
                                               const double y0[], double t1, double y1[],
                                               double *hout, sw_fixed_step_fn body, int track)
{
    const sw_model_t *M = W->ms.m;
    sw_model_scratch_t *S = W->ms.s;
    const double rem = t1 - t0;
    double hmax = W->h, h = rem; /* s */
    for (int tries = 0;; tries++) {
        if (rem <= hmax) {
            h = rem; /* the common case: a step per sample */
        } else {
            const double nst = ceil(rem / hmax - 1e-9);
            h = nst <= 1.0 ? rem : rem / nst;
        }
        if (!track || !M->ops->tracks_rate) {
            body(M, S, t0, h, y0, y1);
            break;
        }
        const double bound = sw_min2(C->dt_forced ? C->scheme->stab : 0.5, W->stab_rate);
        S->rate_seen = 0.0;
        S->track_rate = 1;
        body(M, S, t0, h, y0, y1);
        S->track_rate = 0;
        if (S->rate_seen * h <= bound * (1.0 + 1e-9) || tries >= 60)
            break;
        hmax = fmin(0.5 * h, bound / S->rate_seen);
    }
    *hout = h;
    return 0; /* SW_OK */
}

/* step.c: the rows' behaviours (the generic fixed advance: the package's
 * body, its rate tracked if its model asks) */
int sw_step_fixed(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, const double y0[], double t1,
                  double y1[], double *h);
int sw_step_evolve(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, const double y0[], double t1,
                   double y1[], double *h);
int sw_restep_fixed(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, double h, const double y0[],
                    double y1[]);
int sw_restep_gsl(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, double h, const double y0[],
                  double y1[]);
int sw_restep_hermite(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, double h,
                      const double y0[], double y1[]);

/* ---- step.c: one step with the engine's scheme -------------------------------- */

/* Set up the scheme's work space for P (after the model's set-up).
 * Returns SW_OK, SW_EUNSTABLE (forced dt above the stability bound; msg
 * says why) or SW_ENOMEM. */
int sw_step_init(const sw_step_ctx_t *C, sw_stepper_t *W, const sw_model_t *M,
                 sw_model_scratch_t *S, const char *name, double dt, double rtol, double atol,
                 char *msg, size_t msglen);
/* Point the package's GSL system (and an implicit stepper's driver) at P:
 * after sw_step_init, and again after the package is moved in memory. */
void sw_step_bind(sw_stepper_t *W, const sw_model_t *M, sw_model_scratch_t *S);
void sw_step_free(sw_stepper_t *W);
void sw_step_reset(sw_stepper_t *W);  /* forget the scheme's history (after a map) */
void sw_step_forget(sw_stepper_t *W); /* restart the error control's count (after a fault) */
/* The input over [t0, t1] makes a fixed step unstable for P? */
int sw_step_input_unstable(const sw_step_ctx_t *C, const sw_stepper_t *W, double t0, double t1);
/* One step from (P->t, P->y) toward t1 (at most t1 - P->t) into y1; *h
 * gets its length.  SW_OK or an error (the package must fault). */
static inline int sw_step_advance(const sw_step_ctx_t *C, sw_stepper_t *W, double t0,
                                  const double y0[], double t1, double y1[], double *h)
{
    return W->advance(C, W, t0, y0, t1, y1, h);
}
/* The scheme's solution at t0 + h from (t0, y0), h inside the step being
 * examined: events lie on the scheme's own solution. */
static inline int sw_step_restep(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, double h,
                                 const double y0[], double y1[])
{
    return C->scheme->restep(C, W, t0, h, y0, y1);
}

/* ---- event.c: events inside a step ------------------------------------------- */

/* An event timed inside a step, handed back as CVODE's rootsfound are:
 * the package's phase machine reports it (sw_pkg_timed). */
typedef struct {
    int role;          /* SW_ROLE_PEAK, SW_ROLE_TIP or SW_ROLE_LIFT */
    double t;          /* s */
    double y[SW_NMAX]; /* the state at t */
} sw_timed_t;

/* The earliest cutting event among the model's candidates c[0..nc) inside
 * the step (t0, y0) -> (t0 + h, y1) (SW_EVF_NONE if none; *tau its place
 * in [0, 1]); the timed events before it in timed[0..*ntimed), in the
 * order of the candidates (timed has room for nc). */
int sw_event_locate(const sw_step_ctx_t *C, sw_stepper_t *W, double t0, double h, const double y0[],
                    const double y1[], const sw_evcand_t c[], int nc, double *tau,
                    sw_timed_t timed[], int *ntimed);
/* Keep the candidates that end a step (the dynamics), drop those that only
 * time a peak, a tip or a cushion's lift (the report); the count left. */
int sw_event_keep_outcome(sw_evcand_t c[], int nc);
/* The same, asking the model for its candidates first: inline, because
 * most steps have none and the question is then all the work. */
static inline int sw_event_find(const sw_step_ctx_t *C, sw_stepper_t *W, int flags, double t0,
                                double h, const double y0[], const double y1[], double *tau,
                                sw_timed_t timed[SW_MAX_CANDS], int *ntimed)
{
    sw_evcand_t c[SW_MAX_CANDS];
    const sw_model_t *M = W->ms.m;
    int nc =
        M->ops->candidates(M, flags | (C->scheme->cut_kinks ? SW_CAND_KINKS : 0), h, y0, y1, c);
    if (nc && C->outcome_only)
        nc = sw_event_keep_outcome(c, nc);
    *ntimed = 0;
    return nc ? sw_event_locate(C, W, t0, h, y0, y1, c, nc, tau, timed, ntimed) : SW_EVF_NONE;
}
/* Polish the event time by re-stepping; the state there in y; its time. */
double sw_event_polish(const sw_step_ctx_t *C, sw_stepper_t *W, int ev, double t0, double h,
                       const double y0[], double tau, double y[]);

/* ---- flight.c: a rigid package in free flight ----------------------------------- */

/* P leaves its support at t (g_eff reached 0), with its momentum. */
void sw_flight_take_off(sw_pkg_ctx_t *C, sw_pkg_t *P, double t);
/* A flight of P (flying since P->fl_t0, or landed after dur s) that has
 * lasted SW_FLIGHT_LONG: said once, as SW_EV_FLIGHT at fl_t0 +
 * SW_FLIGHT_LONG, and kept in the summary.  dur: s in the air so far. */
void sw_flight_note(sw_pkg_ctx_t *C, sw_pkg_t *P, double dur);
/* Advance a flying P toward t1 in closed form: SW_STUCK_STILL (in the
 * air at t1), SW_STUCK_MOVED (landed, or on its side, at P->t). */
int sw_flight_advance(sw_pkg_ctx_t *C, sw_pkg_t *P, double t1);

/* ---- pkg.c: one package's phase machine ---------------------------------------- */

void sw_pkg_emit_at(sw_pkg_ctx_t *C, sw_pkg_t *P, sw_event_kind kind, double t, double info,
                    const double *y_at);
void sw_pkg_track_theta(sw_pkg_t *P, double theta);
void sw_pkg_rest(sw_pkg_t *P);
/* A fault at t (code: the error): at rest, counted and said. */
void sw_pkg_fault(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, int code);
void sw_pkg_start_rocking(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, int side);
void sw_pkg_tip(sw_pkg_ctx_t *C, sw_pkg_t *P, double t, const double y_at[]);
/* The events timed inside a step (sw_event_locate), in their order: a
 * peak of |theta| kept in the summary, a tip or a first lift reported. */
void sw_pkg_timed(sw_pkg_ctx_t *C, sw_pkg_t *P, const sw_timed_t ev[], int n);
/* After an accepted step with no cut, for a model with a rest test: a
 * package lifted since its last rest that is back at rest says so. */
void sw_pkg_after_step(sw_pkg_ctx_t *C, sw_pkg_t *P);
/* The map of a cutting event at t (the state is there); the caller resets
 * the scheme's history after it (sw_step_reset). */
void sw_pkg_on_cut(sw_pkg_ctx_t *C, sw_pkg_t *P, int ev, double t);

#endif
