/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cost.h - what a scene costs to run, estimated from the scene.
 *
 * A scene inside every documented limit can still be stiff enough that
 * the engine runs slower than real time (a frame of 1e7 kg on bearings of
 * 1e6 rad/s): a live monitor would fall further behind the sensor at every
 * sample, and a replay would take longer than the drive.  Nothing here
 * times anything (a timer said the stock crate was too stiff on a loaded
 * machine): the cost is the steps the engine must take per second of
 * input, from the scene's fastest mode against the step, times a cost
 * per step measured in docs/accuracy-speed.md and rounded up.  A scene
 * estimated below SW_CLI_MIN_RT_FACTOR times real time is warned about,
 * with the numbers the estimate came from.
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
 * the reserves of all packages together above 1 / SW_CLI_MIN_RT_FACTOR
 * seconds of CPU per second of input are warned about. */
#ifndef SWAYWATCH_CLI_COST_H
#define SWAYWATCH_CLI_COST_H

#include <stddef.h>

#include "cli.h"

#define SW_CLI_MIN_RT_FACTOR 10.0
/* s of CPU per engine step, upper estimates (docs/accuracy-speed.md:
 * explicit steps of every model 40-300 ns, a cushion's contact tracking
 * more; the implicit schemes 1.3-14 us) */
#define SW_CLI_STEP_S 1e-6
#define SW_CLI_IMPLICIT_STEP_S 20e-6
/* The reserve: s of CPU per nominal step of a 1 s pulse's run, its whole
 * search counted (the bed 1.44 us and the frame 1.3 us measured, with
 * fixed steps; the soft cushion 0.26 us, adaptive), and the growth with
 * the pulse's duration */
#define SW_CLI_RESERVE_STEP_S 1.5e-6
#define SW_CLI_RESERVE_CUSHION_STEP_S 0.3e-6
#define SW_CLI_RESERVE_T_POWER 1.5

/* The estimate for scene sc with engine options eo: steps per second of
 * rocking input (*steps), the scheme and the step the engine chose
 * (*scheme, *h in s; may be NULL), and the real-time factor, seconds of
 * input per second of CPU.  < 0 if the engine cannot be built (the run
 * itself will say why). */
double sw_cli_scene_rt_factor(const sw_scene_t *sc, const sw_engine_opts_t *eo, double *steps,
                              const char **scheme, double *h);

/* Estimate every scene and warn on stderr about those below
 * SW_CLI_MIN_RT_FACTOR: "swaywatch: warning: scene NAME needs about N
 * steps per second of input ...".  Returns how many were warned about. */
int sw_cli_warn_scene_cost(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo);

/* s of CPU one evaluation of scene sc's reserve may take while the
 * package rocks (every design pulse). */
double sw_cli_reserve_eval_cost(const sw_scene_t *sc);

/* Warn when the reserves of packages k0 <= k < k1 of risk (those that
 * have one), evaluated rate times per second of input, may take more
 * than 1 / SW_CLI_MIN_RT_FACTOR s of CPU per second of input together:
 * "swaywatch: warning: the reserve of ... may take ...".  Returns 1 if it
 * warned. */
int sw_cli_warn_reserve_cost(const sw_risk_t *risk, size_t k0, size_t k1, const sw_scene_t *scenes,
                             double rate);

/* Warn about packages k0 <= k < k1 of risk that have no reserve although
 * one was asked for (a scene too stiff for it, risk.h's no_reserve):
 * "swaywatch: warning: no reserve for NAME: WHY".  Returns how many. */
int sw_cli_warn_no_reserve(const sw_risk_t *risk, size_t k0, size_t k1, const sw_scene_t *scenes);

#endif
