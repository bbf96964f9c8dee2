/* SPDX-License-Identifier: GPL-3.0-or-later */
/* model_traits.h - what can be said of a model from its scene alone: the
 * pure functions behind model.h's energies, barrier, work rate, settling
 * and modes, and the claims that the analyses running a package many
 * times (run.c, sweep.c, safety*.c, reserve*.c) and the alarms rely on.
 * They see a model only through these, never through its operations on
 * a package (model_ops.h).  Defined by each model beside its ops; looked
 * up in model.c.  Internal. */
#ifndef SWAYWATCH_MODEL_TRAITS_H
#define SWAYWATCH_MODEL_TRAITS_H

#include "swaywatch/engine.h"
#include "swaywatch/model.h"
#include "swaywatch/scene.h"

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

#endif
