/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cost.h - what a scene and its reserve cost to run, estimated from the
 * scene and the schemes, never timed.
 *
 * A scene inside every documented limit can still be stiff enough that
 * the engine runs slower than real time (a frame of 1e7 kg on bearings of
 * 1e6 rad/s): a live monitor would fall further behind the sensor at every
 * sample, and a replay would take longer than the drive.  Nothing here
 * times anything (a timer said the stock crate was too stiff on a loaded
 * machine): the cost is the steps the engine must take per second of
 * input, from the scene's fastest mode against the step, times a cost
 * per step measured in docs/accuracy-speed.md and rounded up.  A scene
 * estimated below SW_COST_MIN_RT_FACTOR times real time deserves a
 * warning, with the numbers the estimate came from.
 *
 * The reserve (reserve.h) costs per evaluation: every design pulse of the
 * scene searched in both directions, each trial a run of the pulse and up
 * to SW_RESERVE_FREE_PERIODS rocking periods at 1/SW_RESERVE_STEPS of the
 * shortest period.  Its estimate for one pulse of T seconds is that run's
 * nominal steps times a cost per nominal step of the model (the trials,
 * most of them ended early, included) times T^1.5 (longer pulses cost
 * more: measured on rocking packages, T = 1, 2, 4, 8 s cost 0.43, 0.86,
 * 3.0, 12.3 ms on the bed, 1.1, 2.3, 4.2, 7.0 on the frame, 1.4, 4.3,
 * 13.8, 35.7 on the soft cushion: the estimate is within a factor of
 * about two of these); the pulses are summed, times the reserve rate, and
 * the reserves of all packages together above 1 / SW_COST_MIN_RT_FACTOR
 * seconds of CPU per second of input deserve a warning. */
#ifndef SWAYWATCH_COST_H
#define SWAYWATCH_COST_H

#include <stddef.h>

#include "engine.h"
#include "export.h"
#include "risk.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Seconds of input per second of CPU below which a run falls behind. */
#define SW_COST_MIN_RT_FACTOR 10.0
/* s of CPU per engine step, upper estimates (docs/accuracy-speed.md:
 * explicit steps of every model 40-300 ns, a cushion's contact tracking
 * more; the implicit schemes 1.3-14 us) */
#define SW_COST_STEP_S 1e-6
#define SW_COST_IMPLICIT_STEP_S 20e-6
/* The reserve: s of CPU per nominal step of a 1 s pulse's run, its whole
 * search counted (the bed 1.44 us and the frame 1.3 us measured, with
 * fixed steps; the soft cushion 0.26 us, adaptive), and the growth with
 * the pulse's duration */
#define SW_COST_RESERVE_STEP_S 1.5e-6
#define SW_COST_RESERVE_CUSHION_STEP_S 0.3e-6
#define SW_COST_RESERVE_T_POWER 1.5

/* The estimate of one scene's engine. */
typedef struct {
    double steps;       /* engine steps per s of rocking input */
    const char *scheme; /* the scheme the engine chose (a static name) */
    double h;           /* s, its step (a fixed step is already cut for omega_max) */
    double omega_max;   /* rad/s, the scene's fastest mode */
    double rt_factor;   /* s of input per s of CPU */
} sw_scene_cost_t;

/* The estimate for scene sc with engine options eo (their callbacks are
 * not used) into out.  SW_OK, SW_EINVAL for a scene that does not
 * validate, or the engine's error when it cannot be built (a run of the
 * scene says why). */
SW_API int sw_scene_cost(const sw_scene_t *sc, const sw_engine_opts_t *eo, sw_scene_cost_t *out);

/* s of CPU one evaluation of scene sc's reserve may take while the
 * package rocks (every design pulse); 0 for a scene that does not
 * validate. */
SW_API double sw_reserve_eval_cost(const sw_scene_t *sc);

/* The reserves of packages k0 <= k < k1 of risk (scenes[k] their scenes),
 * evaluated rate times per second of input, together. */
typedef struct {
    double total;     /* s of CPU per s of input, every package with a reserve */
    double worst;     /* the same, of the costliest package alone */
    size_t worst_pkg; /* its index (k0 when none has a reserve) */
    size_t with;      /* packages that have a reserve */
} sw_reserve_cost_t;
SW_API void sw_reserve_cost(const sw_risk_t *risk, size_t k0, size_t k1, const sw_scene_t *scenes,
                            double rate, sw_reserve_cost_t *out);

#ifdef __cplusplus
}
#endif
#endif
