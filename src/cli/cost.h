/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cost.h - the warnings about what a scene and its reserve cost to run,
 * from the library's estimates (swaywatch/cost.h, where the estimate is
 * explained): a scene estimated below SW_COST_MIN_RT_FACTOR times real
 * time, and reserves above 1 / SW_COST_MIN_RT_FACTOR s of CPU per second
 * of input together, are warned about with the numbers the estimate came
 * from. */
#ifndef SWAYWATCH_CLI_COST_H
#define SWAYWATCH_CLI_COST_H

#include <stddef.h>

#include "cli.h"

/* Estimate every scene and warn on stderr about those below
 * SW_COST_MIN_RT_FACTOR: "swaywatch: warning: scene NAME needs about N
 * steps per second of input ...".  Returns how many were warned about. */
int sw_cli_warn_scene_cost(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo);

/* Warn when the reserves of packages k0 <= k < k1 of risk (those that
 * have one), evaluated rate times per second of input, may take more
 * than 1 / SW_COST_MIN_RT_FACTOR s of CPU per second of input together:
 * "swaywatch: warning: the reserve of ... may take ...".  Returns 1 if it
 * warned. */
int sw_cli_warn_reserve_cost(const sw_risk_t *risk, size_t k0, size_t k1, const sw_scene_t *scenes,
                             double rate);

/* Warn about packages k0 <= k < k1 of risk that have no reserve although
 * one was asked for (a scene too stiff for it, risk.h's no_reserve):
 * "swaywatch: warning: no reserve for NAME: WHY".  Returns how many. */
int sw_cli_warn_no_reserve(const sw_risk_t *risk, size_t k0, size_t k1, const sw_scene_t *scenes);

#endif
