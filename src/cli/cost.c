/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cost.c - the real-time factor of a scene, measured when it is loaded
 * (cost.h). */
#include "cost.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

static double cpu_now(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double sw_cli_scene_rt_factor(const sw_scene_t *sc, const sw_engine_opts_t *eo)
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
    /* Braking at three times the uplift threshold of the package on the
     * bed: it rocks within milliseconds, on any support. */
    const double a = -3.0 * sc->g * tan(d.alpha);
    const double rate = 1000.0;
    const long n = (long)(SW_CLI_CALIBRATION_S * rate);
    double t = 0.0;
    const double start = cpu_now();
    double cpu = 0.0;
    long k;
    for (k = 0; k <= n; k++) {
        t = (double)k / rate;
        if (sw_engine_push(e, t, k == 0 ? 0.0 : a, 0.0) < 0) {
            sw_engine_destroy(e);
            return -1.0;
        }
        cpu = cpu_now() - start;
        if (cpu > SW_CLI_CALIBRATION_CPU_S)
            break;
    }
    sw_engine_destroy(e);
    /* below the clock's resolution: far faster than any threshold */
    return cpu > 0.0 ? t / cpu : INFINITY;
}

int sw_cli_warn_scene_cost(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo)
{
    int warned = 0;
    for (size_t i = 0; i < n; i++) {
        const double f = sw_cli_scene_rt_factor(&scenes[i], eo);
        if (!(f >= 0.0) || f >= SW_CLI_MIN_RT_FACTOR)
            continue;
        warned++;
        sw_cli_error(
            "warning: scene %s runs at only %.2g times real time (measured on %g s of "
            "rocking input); below %g a live monitor falls behind the sensor, and a "
            "replay takes %.2g s per second of log: the model is too stiff for its step "
            "(--verbose shows its frequencies)",
            scenes[i].name, f, SW_CLI_CALIBRATION_S, SW_CLI_MIN_RT_FACTOR, 1.0 / f);
    }
    return warned;
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
