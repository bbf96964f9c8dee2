/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lcmopts.h - the options of the LCM commands (monitor, and replay of
 * lcm-logger files) that set up the monitor core: rows into a
 * sw_mon_opts_t.  LCM builds only. */
#ifndef SWAYWATCH_CLI_LCMOPTS_H
#define SWAYWATCH_CLI_LCMOPTS_H

#include <stdio.h>

#include "input.h"
#include "monitor.h"
#include "opts.h"

/* --state-channel, --alarm-channel, --state-rate: what is published. */
extern const sw_cli_option_t sw_cli_lcm_publish_options[];
/* --axis, --lat-axis, --vertical, --max-skew: which of a message's values are taken
 * (the input gate's options, sw_cli_gate_options, decide the rest). */
extern const sw_cli_option_t sw_cli_lcm_input_options[];

/* "rejected N (reason n, ...)": the refusals by reason, as monitor and
 * replay print them. */
void sw_cli_print_rejected(FILE *f, const sw_mon_counts_t *k);

/* "authentication: N checked, A authentic, R refused (the first: message
 * W on CHANNEL, REASON (key K); the last: ...)": what a monitor with keys
 * checked and where the refused messages came from (a: its facts). */
void sw_cli_print_auth(FILE *f, const sw_auth_facts_t *a);

/* Set mo to the defaults these rows assume (vertical none, the library's
 * hysteresis) before sw_cli_parse(). */
void sw_cli_mon_opts_init(sw_mon_opts_t *mo);

/* The lateral plane: mo->lateral set when a scene gives a depth and
 * --lat-axis is not none; SW_EXIT_USAGE (reported) when that axis is the
 * longitudinal or the vertical one. */
int sw_cli_mon_lateral(sw_mon_opts_t *mo, const sw_scene_t *scenes, size_t n);

/* The input gate's options into mo; SW_EXIT_USAGE (reported) when a
 * vertical axis is given without saying whether it includes gravity. */
int sw_cli_mon_gate(sw_mon_opts_t *mo, const sw_cli_gate_t *g);

#endif
