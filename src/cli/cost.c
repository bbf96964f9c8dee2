/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cost.c - what a scene and its reserve cost to run, estimated from the
 * scene, never timed (cost.h). */
#include "cost.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

double sw_cli_scene_rt_factor(const sw_scene_t *sc, const sw_engine_opts_t *eo, double *steps,
                              const char **scheme, double *h)
{
    sw_derived_t d;
    if (sw_scene_validate(sc, &d, NULL, NULL, NULL) != SW_OK)
        return -1.0;
    sw_engine_opts_t o = *eo;
    o.on_event = NULL;
    o.on_state = NULL;
    o.user = NULL;
    int err = 0;
    sw_engine_t *e = sw_engine_create(sc, 1, &o, &err, NULL, 0);
    if (!e)
        return -1.0;
    const char *name = sw_engine_scheme(e);
    double step = sw_engine_dt(e, 0); /* s: a fixed step is already cut for omega_max */
    sw_engine_destroy(e);
    const sw_scheme_t *S = sw_scheme_lookup(name);
    const int implicit = S && sw_scheme_implicit(S);
    /* An explicit adaptive scheme's error control cannot take steps
     * beyond its stability bound on the fastest mode: about 2 / omega. */
    if (S && sw_scheme_adaptive(S) && !implicit && d.omega_max > 0.0)
        step = fmin(step, 2.0 / d.omega_max);
    const double n = step > 0.0 ? 1.0 / step : INFINITY; /* steps per s of input */
    if (steps)
        *steps = n;
    if (scheme)
        *scheme = name;
    if (h)
        *h = step;
    return 1.0 / (n * (implicit ? SW_CLI_IMPLICIT_STEP_S : SW_CLI_STEP_S));
}

int sw_cli_warn_scene_cost(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo)
{
    int warned = 0;
    for (size_t i = 0; i < n; i++) {
        double steps = 0.0, h = 0.0;
        const char *scheme = "";
        const double f = sw_cli_scene_rt_factor(&scenes[i], eo, &steps, &scheme, &h);
        if (!(f >= 0.0) || f >= SW_CLI_MIN_RT_FACTOR)
            continue;
        sw_derived_t d;
        sw_scene_validate(&scenes[i], &d, NULL, NULL, NULL);
        warned++;
        sw_cli_error(
            "warning: scene %s needs about %.3g steps per second of input (%s, step %.3g s; its "
            "fastest mode omega_max = %.4g rad/s), estimated at only %.2g times real time; "
            "below %g a live monitor falls behind the sensor, and a replay takes up to %.2g s "
            "per second of log: the model is too stiff for its step (--verbose shows its "
            "frequencies)",
            scenes[i].name, steps, scheme, h, d.omega_max, f, SW_CLI_MIN_RT_FACTOR, 1.0 / f);
    }
    return warned;
}

double sw_cli_reserve_eval_cost(const sw_scene_t *sc)
{
    sw_derived_t d;
    if (sw_scene_validate(sc, &d, NULL, NULL, NULL) != SW_OK)
        return 0.0;
    const double rock = 2.0 * M_PI / d.p; /* s, the rocking period */
    double weighted = 0.0;                /* nominal steps of one run of each pulse, weighted */
    for (int j = 0; j < sc->n_design_pulse; j++) {
        const double T = sc->design_pulse[j]; /* s */
        /* reserve.c: the run's step and length */
        double period = fmin(2.0 * T, rock);
        if (d.omega_max > 0.0)
            period = fmin(period, 2.0 * M_PI / d.omega_max);
        const double nominal = (T + SW_RESERVE_FREE_PERIODS * rock) / (period / SW_RESERVE_STEPS);
        weighted += nominal * pow(fmax(1.0, T), SW_CLI_RESERVE_T_POWER);
    }
    const double per_step =
        d.model == SW_MODEL_CUSHION ? SW_CLI_RESERVE_CUSHION_STEP_S : SW_CLI_RESERVE_STEP_S;
    return weighted * per_step;
}

int sw_cli_warn_reserve_cost(const sw_risk_t *risk, size_t k0, size_t k1, const sw_scene_t *scenes,
                             double rate)
{
    if (!(rate > 0.0))
        return 0;
    double total = 0.0, worst = 0.0; /* s of CPU per s of input */
    size_t with = 0, at = k0;
    for (size_t k = k0; k < k1; k++) {
        const sw_risk_pkg_t *p = sw_risk_pkg(risk, k);
        if (!p || p->no_reserve)
            continue;
        const double c = rate * sw_cli_reserve_eval_cost(&scenes[k]);
        with++;
        total += c;
        if (c > worst) {
            worst = c;
            at = k;
        }
    }
    if (!(total > 1.0 / SW_CLI_MIN_RT_FACTOR))
        return 0;
    sw_cli_error(
        "warning: the reserve of %zu package%s, evaluated %g times per second of input, may "
        "take up to %.2g s of CPU per second of input (%s: %d design pulse%s, up to %.3g ms an "
        "evaluation); above %g a live monitor can fall behind its sensor and a replay takes "
        "that long per second of log: lower --reserve-rate, or give [alarm] design_pulse "
        "fewer durations",
        with, with == 1 ? "" : "s", rate, total, scenes[at].name, scenes[at].n_design_pulse,
        scenes[at].n_design_pulse == 1 ? "" : "s", 1e3 * worst / rate, 1.0 / SW_CLI_MIN_RT_FACTOR);
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
