/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pulse.h - the excitation pulses of physics.md, for simulate, boundary
 * curves and tests.  half-sine: a_e sin(w t) for 0 <= t <= pi/w; full-sine:
 * a_e sin(w t) for 0 <= t <= 2 pi/w; zero outside. */
#ifndef SWAYWATCH_PULSE_H
#define SWAYWATCH_PULSE_H

#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { SW_PULSE_HALF_SINE = 0, SW_PULSE_FULL_SINE = 1 } sw_pulse_shape;

typedef struct {
    sw_pulse_shape shape;
    double amplitude; /* m/s^2, a_e (sign included: negative brakes) */
    double omega;     /* rad/s, w_e */
} sw_pulse_t;

/* Parse "half-sine" or "full-sine"; SW_OK or SW_ENOTFOUND. */
SW_API int sw_pulse_shape_parse(const char *name, sw_pulse_shape *out);
SW_API const char *sw_pulse_shape_name(sw_pulse_shape s);

SW_API double sw_pulse_duration(const sw_pulse_t *p); /* s */

/* a_g(t), m/s^2.  The signature fits sw_input_fn (user = the pulse). */
SW_API double sw_pulse_eval(void *pulse, double t);

#ifdef __cplusplus
}
#endif
#endif
