/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cost.c - what a scene and its reserve cost to run, estimated from the
 * scene and the schemes, never timed (cost.h). */
#include "swaywatch/cost.h"

#include <math.h>
#include <string.h>

#include "swaywatch/reserve.h"
#include "swaywatch/scheme.h"
#include "swaywatch/status.h"

int sw_scene_cost(const sw_scene_t *sc, const sw_engine_opts_t *eo, sw_scene_cost_t *out)
{
    memset(out, 0, sizeof *out);
    sw_derived_t d;
    if (sw_scene_validate(sc, &d, NULL, NULL, NULL) != SW_OK)
        return SW_EINVAL;
    sw_engine_opts_t o = *eo;
    o.on_event = NULL;
    o.on_state = NULL;
    o.user = NULL;
    int err = 0;
    sw_engine_t *e = sw_engine_create(sc, 1, &o, &err, NULL, 0);
    if (!e)
        return err < 0 ? err : SW_EINVAL;
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
    out->steps = n;
    out->scheme = name;
    out->h = step;
    out->omega_max = d.omega_max;
    out->rt_factor = 1.0 / (n * (implicit ? SW_COST_IMPLICIT_STEP_S : SW_COST_STEP_S));
    return SW_OK;
}

double sw_reserve_eval_cost(const sw_scene_t *sc)
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
        weighted += nominal * pow(fmax(1.0, T), SW_COST_RESERVE_T_POWER);
    }
    const double per_step =
        d.model == SW_MODEL_CUSHION ? SW_COST_RESERVE_CUSHION_STEP_S : SW_COST_RESERVE_STEP_S;
    return weighted * per_step;
}

void sw_reserve_cost(const sw_risk_t *risk, size_t k0, size_t k1, const sw_scene_t *scenes,
                     double rate, sw_reserve_cost_t *out)
{
    memset(out, 0, sizeof *out);
    out->worst_pkg = k0;
    for (size_t k = k0; k < k1; k++) {
        const sw_risk_pkg_t *p = sw_risk_pkg(risk, k);
        if (!p || p->no_reserve)
            continue;
        const double c = rate * sw_reserve_eval_cost(&scenes[k]);
        out->with++;
        out->total += c;
        if (c > out->worst) {
            out->worst = c;
            out->worst_pkg = k;
        }
    }
}
