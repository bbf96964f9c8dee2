/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cost.c - the warnings about what a scene and its reserve cost to run,
 * from the library's estimates (cost.h). */
#include "cost.h"

#include <stdio.h>

int sw_cli_warn_scene_cost(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo)
{
    int warned = 0;
    for (size_t i = 0; i < n; i++) {
        sw_scene_cost_t c;
        if (sw_scene_cost(&scenes[i], eo, &c) != SW_OK || c.rt_factor >= SW_COST_MIN_RT_FACTOR)
            continue;
        warned++;
        sw_cli_error(
            "warning: scene %s needs about %.3g steps per second of input (%s, step %.3g s; its "
            "fastest mode omega_max = %.4g rad/s), estimated at only %.2g times real time; "
            "below %g a live monitor falls behind the sensor, and a replay takes up to %.2g s "
            "per second of log: the model is too stiff for its step (--verbose shows its "
            "frequencies)",
            scenes[i].name, c.steps, c.scheme, c.h, c.omega_max, c.rt_factor, SW_COST_MIN_RT_FACTOR,
            1.0 / c.rt_factor);
    }
    return warned;
}

int sw_cli_warn_reserve_cost(const sw_risk_t *risk, size_t k0, size_t k1, const sw_scene_t *scenes,
                             double rate)
{
    if (!(rate > 0.0))
        return 0;
    sw_reserve_cost_t c;
    sw_reserve_cost(risk, k0, k1, scenes, rate, &c);
    if (!(c.total > 1.0 / SW_COST_MIN_RT_FACTOR))
        return 0;
    const sw_scene_t *at = &scenes[c.worst_pkg];
    sw_cli_error(
        "warning: the reserve of %zu package%s, evaluated %g times per second of input, may "
        "take up to %.2g s of CPU per second of input (%s: %d design pulse%s, up to %.3g ms an "
        "evaluation); above %g a live monitor can fall behind its sensor and a replay takes "
        "that long per second of log: lower --reserve-rate, or give [alarm] design_pulse "
        "fewer durations",
        c.with, c.with == 1 ? "" : "s", rate, c.total, at->name, at->n_design_pulse,
        at->n_design_pulse == 1 ? "" : "s", 1e3 * c.worst / rate, 1.0 / SW_COST_MIN_RT_FACTOR);
    return 1;
}

int sw_cli_warn_no_reserve(const sw_risk_t *risk, size_t k0, size_t k1, const sw_scene_t *scenes)
{
    int warned = 0;
    for (size_t k = k0; k < k1; k++) {
        const sw_risk_pkg_t *p = sw_risk_pkg(risk, k);
        if (!p || !p->no_reserve)
            continue;
        warned++;
        sw_cli_error(
            "warning: no reserve for %s: %s (--reserve-rate 0 silences this; the "
            "margins and the verdict are not affected)",
            scenes[k].name, p->no_reserve);
    }
    return warned;
}
