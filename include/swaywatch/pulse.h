/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pulse.h - the excitation pulses of physics.md, for simulate, boundary
 * curves and tests.  half-sine: a_e sin(w t) for 0 <= t <= pi/w; full-sine:
 * a_e sin(w t) for 0 <= t <= 2 pi/w; zero outside. */
#ifndef SWAYWATCH_PULSE_H
#define SWAYWATCH_PULSE_H

#include "engine.h"
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

/* Advance engine e to t1 (s, as sw_engine_advance_fn) under pulse p, the
 * pulse's time being the engine's: first to each kink of the input that
 * lies strictly between the engine's time and t1 (the pulse's start 0
 * and its end), so that no step of a scheme straddles one (a step across
 * a kink loses the scheme's order: 1e-7 rad where RK4 at 1 ms is good to
 * 1e-12).  sw_engine_advance_fn's status (the worst of the pieces). */
SW_API int sw_pulse_advance(sw_engine_t *e, double t1, sw_pulse_t *p);

#ifdef __cplusplus
}
#endif
#endif
