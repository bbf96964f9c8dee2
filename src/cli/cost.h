/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cost.h - what a scene costs to run, measured when it is loaded.
 *
 * A scene inside every documented limit can still be stiff enough that
 * the engine runs slower than real time (a frame of 1e7 kg on bearings of
 * 1e6 rad/s, a cushion of 1e6 rad/s with a cubic term of 1e30): a live
 * monitor would fall further behind the sensor at every sample, and a
 * replay would take longer than the drive.  Each scene is run alone, on a
 * copy, through SW_CLI_CALIBRATION_S of rocking input (a braking step of
 * three times its uplift threshold, sampled at 1 kHz) with the command's
 * engine options, timed on the process's CPU clock; a scene below
 * SW_CLI_MIN_RT_FACTOR times real time is warned about, with the factor
 * measured.  The calibration stops early after SW_CLI_CALIBRATION_CPU_S
 * of CPU, so a very slow scene costs no more than that to find out. */
#ifndef SWAYWATCH_CLI_COST_H
#define SWAYWATCH_CLI_COST_H

#include <stddef.h>

#include "cli.h"

#define SW_CLI_CALIBRATION_S 0.05     /* s of input */
#define SW_CLI_CALIBRATION_CPU_S 0.25 /* s of CPU at most */
#define SW_CLI_MIN_RT_FACTOR 10.0

/* The real-time factor of scene sc with engine options eo (callbacks
 * ignored): seconds of input per second of CPU.  < 0 if the engine cannot
 * be built or refuses the input (the run itself will say why). */
double sw_cli_scene_rt_factor(const sw_scene_t *sc, const sw_engine_opts_t *eo);

/* Measure every scene and warn on stderr about those below
 * SW_CLI_MIN_RT_FACTOR: "swaywatch: warning: scene NAME runs at only 2.1
 * times real time ...".  Returns how many were warned about. */
int sw_cli_warn_scene_cost(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo);

/* Warn about packages k0 <= k < k1 of risk that have no reserve although
 * one was asked for (a scene too stiff for it, risk.h's no_reserve):
 * "swaywatch: warning: no reserve for NAME: WHY".  Returns how many. */
int sw_cli_warn_no_reserve(const sw_risk_t *risk, size_t k0, size_t k1, const sw_scene_t *scenes);

#endif
