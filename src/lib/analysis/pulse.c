/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pulse.c - half-sine and full-sine excitation pulses (physics.md). */
#include <math.h>
#include <string.h>

#include "swaywatch/engine.h"
#include "swaywatch/pulse.h"
#include "swaywatch/status.h"

int sw_pulse_shape_parse(const char *name, sw_pulse_shape *out)
{
    if (name && !strcmp(name, "half-sine")) {
        *out = SW_PULSE_HALF_SINE;
        return SW_OK;
    }
    if (name && !strcmp(name, "full-sine")) {
        *out = SW_PULSE_FULL_SINE;
        return SW_OK;
    }
    return SW_ENOTFOUND;
}

const char *sw_pulse_shape_name(sw_pulse_shape s)
{
    return s == SW_PULSE_FULL_SINE ? "full-sine" : "half-sine";
}

double sw_pulse_duration(const sw_pulse_t *p)
{
    return (p->shape == SW_PULSE_FULL_SINE ? 2.0 * M_PI : M_PI) / p->omega;
}

double sw_pulse_eval(void *pulse, double t)
{
    const sw_pulse_t *p = pulse;
    if (t < 0.0 || t > sw_pulse_duration(p))
        return 0.0;
    return p->amplitude * sin(p->omega * t);
}

int sw_pulse_advance(sw_engine_t *e, double t1, sw_pulse_t *p)
{
    if (!e || !p)
        return SW_EINVAL;
    const double kinks[2] = {0.0, sw_pulse_duration(p)}; /* s */
    const double t0 = sw_engine_time(e);                 /* NAN before the start: from 0 */
    int any = 0;
    for (int k = 0; k < 2; k++) {
        if (!(kinks[k] < t1) || (!isnan(t0) && !(kinks[k] > t0)) || (isnan(t0) && k == 0))
            continue;
        const int rc = sw_engine_advance_fn(e, kinks[k], sw_pulse_eval, p);
        if (rc < 0)
            return rc;
        any |= rc == SW_EVENT;
    }
    const int rc = sw_engine_advance_fn(e, t1, sw_pulse_eval, p);
    return rc < 0 ? rc : any ? SW_EVENT : rc;
}
