/* lcmopts.h - what the LCM commands (monitor, and replay of lcm-logger
 * files) share on top of the monitor core: their common options.  LCM
 * builds only. */
#ifndef SWAYWATCH_CLI_LCMOPTS_H
#define SWAYWATCH_CLI_LCMOPTS_H

#include "monitor.h"

/* Handle c (an SW_OPT_LCM_* code of cli.h) for opts, a sw_mon_opts_t (the
 * form of a sw_cli_group_t), if it is one of the options both commands
 * take: --state-channel, --alarm-channel, --state-rate, --axis,
 * --vertical, --gap, --max-accel.  Returns -1 if it is not, else
 * SW_EXIT_OK or SW_EXIT_USAGE (reported). */
int sw_cli_mon_option(void *opts, int c, const char *arg);

#endif
