/* SPDX-License-Identifier: GPL-3.0-or-later */
/* input.h - the input over the interval being integrated, as every layer
 * that evaluates it sees it: the bed's acceleration linear between two
 * samples, or a function of time (pulses).  The engine owns it; the
 * models read it through their sw_model_t.  Internal. */
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

#endif
