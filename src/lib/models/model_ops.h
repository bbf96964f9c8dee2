/* SPDX-License-Identifier: GPL-3.0-or-later */
/* model_ops.h - a model as the engine's layers see it: the package's
 * model (sw_model_t: parameters, input, mode) and its scratch, the event
 * functions and candidates a model names, and its operations table
 * (struct sw_model_ops: right-hand side, events, maps, report, rest).
 * The engine reaches a model only through these; adding a model is one
 * model_X.c with its ops and traits (model_traits.h) and a row in
 * sw_model_ops_of() (model.c).  The models include nothing above this
 * header.  Internal. */
#ifndef SWAYWATCH_MODEL_OPS_H
#define SWAYWATCH_MODEL_OPS_H

#include <string.h>

#include "input.h"
#include "numeric.h"
#include "swaywatch/engine.h"
#include "swaywatch/model.h"
#include "swaywatch/scene.h"

#define SW_NMAX 6 /* longest state vector: cushion on a frame (u, theta, z and rates) */

typedef struct sw_model_ops sw_model_ops_t;
typedef struct sw_model_traits sw_model_traits_t;

/* The values of sw_model_kind: the rows of the table indexed by it (the
 * models in model.c). */
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
    double rate_cap;        /* 1/s, a proven bound of the tracked contact rate over every
                               state (INFINITY: none known; model_cushion.c) */
    double e_barrier;       /* J/kg, cushion: sw_cushion_barrier() under nominal gravity */
    double v_rest;          /* J/kg, cushion: potential at rest under nominal gravity */
    const sw_input_t *in;   /* the engine's input over the interval being integrated: the
                               layers that evaluate the model read it, the ops get its value */
    /* the mode, and which events it arms */
    sw_phase phase;
    int side;      /* s = +1 / -1 while rocking */
    int flying;    /* in the air (flight.c): no contact with the support */
    int held;      /* kept standing for one step (pkg.c's after_impact): no uplift */
    double t_lift; /* s, the last uplift, NAN since the last rest: a first lift is timed */
} sw_model_t;

/* What a model's right-hand side writes as it goes: its scratch, one per
 * package, passed beside the model. */
#define SW_RHS_MEMO 2 /* right-hand sides remembered: the ends of the last two steps */
typedef struct {
    double trig[3];   /* model_rigid.c: an angle (NAN: none yet), its sin and cos */
    int track_rate;   /* cushion: the right-hand side records rate_seen */
    double rate_seen; /* rad/s, fastest contact rate met by the stages of a step */
    /* cushion: the right-hand sides at the last ends the event layer
     * examined, with the (a_g, g_eff, y) they are for */
    struct {
        double ag, ge, y[SW_NMAX], f[SW_NMAX];
        double sin_cos[2]; /* sin and cos of y's theta */
        int rc;
    } memo[SW_RHS_MEMO];
    int memo_on;           /* remember (the step layer says: fixed steps) */
    int memo_n, memo_next; /* entries in use, the one written next */
} sw_model_scratch_t;

/* A model and its scratch: GSL's params for sw_model_rhs and
 * sw_model_jacobian. */
typedef struct {
    const sw_model_t *m;
    sw_model_scratch_t *s;
} sw_model_sys_t;

/* One fixed step of length h (s) from (t, y) into yout of the system ms
 * (a model and its scratch): a fixed-step scheme's body for one model
 * (fixed_rk.h), which is also the scheme's re-step; SW_OK (an int, so
 * that the scheme's advance reaches it by a jump).  The other schemes'
 * re-steps take the same form (step.h: ms is the first member of their
 * stepper), as GSL's step types' apply functions take their own state. */
typedef int (*sw_fixed_step_fn)(sw_model_sys_t *ms, double t, double h, const double y[],
                                double yout[]);

/* The fixed-step schemes' bodies (fixed_rk.h): a scheme's row names its
 * body (struct sw_scheme's rk), a model may instantiate each with its
 * right-hand side inlined (ops->fixed). */
enum { SW_RK_NONE = 0, SW_RK_EULER, SW_RK_HEUN, SW_RK_RK4, SW_RK_KINDS };

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
    unsigned char clear; /* skip when clearly below 0 over the whole step (uplift, kinks) */
} sw_evcand_t;

#define SW_MAX_CANDS 8

/* A model's behaviour: what the engine's layers do with a package of it.
 * Adding a model is one model_X.c with one of these (and its traits) and
 * a row in sw_model_ops_of() (model.c). */
struct sw_model_ops {
    const char *name;
    const sw_model_traits_t *traits; /* what can be said from the scene alone */
    /* layout of y, typical sizes, constants (after the common set-up) */
    void (*setup)(sw_model_t *M, const sw_scene_t *sc);
    /* f = y' at y under the input's value u there (the caller evaluates
     * it at the stage's time: the model is autonomous given it);
     * GSL_SUCCESS, or a GSL error that makes an adaptive step retry
     * shorter.  May write the scratch S. */
    int (*rhs)(const sw_model_t *M, sw_model_scratch_t *S, const sw_input_at_t *u, const double y[],
               double f[]);
    /* the fixed-step schemes' bodies with the right-hand side inlined per
     * stage, instantiated by the model (SW_FIXED_RK_ROW); NULL: the
     * generic body (scheme.c: rhs per stage) */
    sw_fixed_step_fn fixed[SW_RK_KINDS];
    /* the state at rest into y (zeroed before), and its mode; NULL: the
     * zeroed state, standing */
    void (*rest)(sw_model_t *M, double y[]);
    /* the events to look for over the step (t0, y0) -> (t0 + h, y1), in the
     * order they are handled, as the mode arms them; cut_kinks: the
     * scheme's steps must be cut at kinks of the right-hand side.  Returns
     * how many (<= SW_MAX_CANDS). */
    int (*candidates)(const sw_model_t *M, int cut_kinks, double h, const double y0[],
                      const double y1[], sw_evcand_t c[]);
    /* f = y' at y under the input's value u there (as rhs), and the value
     * v[i] and time derivative d[i] of the event function of each c[i],
     * i < n, at y: the event layer's one call per end of a step (every
     * candidate) and per polish iterate (one), so a model computes what
     * its functions share (an angle's sine) once.  May write the scratch
     * S, as rhs. */
    void (*events)(const sw_model_t *M, sw_model_scratch_t *S, const sw_input_at_t *u,
                   const double y[], const sw_evcand_t c[], int n, double f[], double v[],
                   double d[]);
    /* at theta = 0: the velocity map on y, the side flips; NULL: never
     * impacts */
    void (*impact)(sw_model_t *M, double y[]);
    /* at theta = 0: theta' to 0 (a landing, the end of a cascade), whatever
     * the support takes of the package's momentum; NULL with impact */
    void (*land)(const sw_model_t *M, double y[]);
    /* +1 / -1 if the support is beyond the uplift threshold under the
     * input's value u, else 0 */
    int (*uplift_side)(const sw_model_t *M, const sw_input_at_t *u, const double y[]);
    /* how the package stands on its support, which stuck.c solves exactly
     * (SW_STANDS_*); 0: it never stands still (a cushion) */
    int stands;
    /* the rest of the report after the common part (sw_model_output),
     * under the input's value u at the report's time */
    void (*output)(const sw_model_t *M, const sw_model_scratch_t *S, const sw_input_at_t *u,
                   const double y[], sw_output_t *o);
    /* the side as the state decides it, at a cut before its map (a
     * cushion's is the sign of theta); NULL: the maps set it */
    void (*follow)(sw_model_t *M, const double y[]);
    /* after every accepted step with no cut, one call: the side as the
     * state decides it (as follow), and for a package rocking since a
     * lift that has not come back to rest (lifted), whether it now is (it
     * can no longer lift without input), which the phase machine says
     * (sw_pkg_stepped); 0 when not lifted.  NULL: the side as follow
     * says, rest only through the maps */
    int (*stepped)(sw_model_t *M, const double y[], int lifted);
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
enum { SW_STANDS_RIGID = 1, SW_STANDS_OSCILLATOR = 2, SW_STANDS_KINDS };

extern const sw_model_ops_t sw_model_bare, sw_model_frame, sw_model_cushion;
const sw_model_ops_t *sw_model_ops_of(sw_model_kind kind);

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

void sw_model_from_state(sw_model_t *M, double y[SW_NMAX], const sw_state_t *s);

/* The state as the API gives it, and the report at t (s) of state y
 * under the input's value u there (the caller, which owns the time,
 * evaluated it): the common part, then the model's (ops->output).
 * Inline: every sample reports every package. */
static inline void sw_model_to_state(const sw_model_t *M, const double y[], sw_state_t *s)
{
    memset(s, 0, sizeof *s);
    s->theta = y[M->ith];
    s->theta_dot = y[M->idth];
    if (M->iu >= 0) {
        s->u = y[M->iu];
        s->u_dot = y[M->idu];
    }
    if (M->iz >= 0) {
        s->z = y[M->iz];
        s->z_dot = y[M->idz];
    }
    s->phase = M->phase;
    s->side = M->phase == SW_PHASE_STUCK ? 0 : M->side;
}

static SW_ALWAYS_INLINE void sw_model_output(const sw_model_t *M, const sw_model_scratch_t *S,
                                             const sw_input_at_t *u, double t, const double y[],
                                             sw_output_t *o)
{
    memset(o, 0, sizeof *o);
    o->t = t;
    sw_model_to_state(M, y, &o->state);
    o->a_g = u->ag;
    M->ops->output(M, S, u, y, o);
}

#endif
