/* SPDX-License-Identifier: GPL-3.0-or-later */
/* input.h - the input over the interval being integrated: the bed's
 * acceleration linear between two samples, or a function of time
 * (pulses).  The engine owns it.  The layers that own a time (the engine,
 * the step layer and its schemes, the event layer) evaluate it there and
 * hand the value down: a model is autonomous given the input's value
 * (sw_input_at_t) and never reads the input itself.  A leaf.  Internal. */
#ifndef SWAYWATCH_INPUT_H
#define SWAYWATCH_INPUT_H

#include "swaywatch/engine.h"

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

/* The input at one time, as a model's right-hand side, event functions
 * and report read it: evaluated once by the layer that owns the time and
 * handed down. */
typedef struct {
    double ag;      /* m/s^2, the bed's acceleration a_g */
    double ge;      /* m/s^2, g_eff = g + a_z */
    double ge_rate; /* m/s^3, d g_eff / dt (0 for a function input) */
} sw_input_at_t;

static inline sw_input_at_t sw_input_at(const sw_input_t *in, double g, double t)
{
    sw_input_at_t u;
    u.ag = sw_input_ag(in, t);
    u.ge = sw_input_geff(in, g, t);
    u.ge_rate = in->fn ? 0.0 : in->az_slope;
    return u;
}

/* The input at the two ends t[0], t[1] (s) of the interval the engine
 * advances a package over, evaluated once there by the engine, which
 * owns the interval: the layers below take these values where their
 * time is one of these. */
typedef struct {
    double t[2];
    sw_input_at_t u[2];
} sw_input_ends_t;

#endif
