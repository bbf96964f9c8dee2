/* SPDX-License-Identifier: GPL-3.0-or-later */
/* monitor_cli.h - what the files of "swaywatch monitor" share (monitor.h
 * is the monitor core's, in src/lcm): cmd_monitor.c holds the options and
 * the command, monitor_loop.c the loop (signals, samples in, alarm and
 * status lines, the service manager's timers), monitor_reload.c the
 * re-reading of the scene files on SIGHUP.  LCM builds only. */
#ifndef SWAYWATCH_CLI_MONITOR_CLI_H
#define SWAYWATCH_CLI_MONITOR_CLI_H

#include <lcm/lcm.h>
#include <stddef.h>

#include "monitor.h"
#include "opts.h"

/* s between STATUS= updates for the service manager without --status. */
#define NOTIFY_STATUS_EVERY_S 10

/* The running monitor, as the loop and the LCM handler see it. */
typedef struct {
    sw_mon_t *mon;
    const sw_cli_opts_t *opts; /* for a reload: the scene files and --set */
    sw_scene_t *scenes;
    size_t n;
    /* since the last status line */
    long accepted;
    double lag_sum, lag_max; /* s, wall clock at handling minus sample utime */
    double busy;             /* s spent handling samples */
    double max_backlog;      /* s; 0: no shedding (a log, memq: the receive time is not now) */
} mon_ctx_t;

/* The handlers of SIGINT and SIGTERM (stop) and SIGHUP (reload), which
 * wake the loop through a pipe: 0, or -1 (errno says why). */
int sw_cli_mon_signals_install(void);
/* The default actions again and the pipe closed (also after a failed
 * install). */
void sw_cli_mon_signals_remove(void);

/* The handler of the accel subscription (user: the mon_ctx_t): a message
 * into the monitor core, or refused unread when it waited too long. */
void sw_cli_mon_on_accel(const lcm_recv_buf_t *rb, const char *channel, void *user);
/* The monitor core's alarm callback (user: the mon_ctx_t): every alarm on
 * stderr, one line each (journal.h). */
void sw_cli_mon_print_alarm(void *user, const sw_alarm_t *a);

/* The loop until SIGINT or SIGTERM, then the summary on stderr;
 * SW_EXIT_OK, or SW_EXIT_IO (reported). */
int sw_cli_mon_run(lcm_t *lcm, mon_ctx_t *c, double status_every);

/* Re-read the scene files of o (with its --set overrides) and rebuild the
 * packages of mon whose scene changed; scenes[0..n) are the monitor's
 * current scenes, updated in place.  Says what it did on stderr.  Returns
 * SW_EXIT_OK, or SW_EXIT_USAGE / SW_EXIT_IO with nothing changed. */
int sw_cli_mon_reload(sw_mon_t *mon, const sw_cli_opts_t *o, sw_scene_t *scenes, size_t n);

#endif
