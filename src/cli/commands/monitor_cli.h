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
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>

#include "monitor.h"
#include "opts.h"

/* s between STATUS= updates for the service manager without --status. */
#define NOTIFY_STATUS_EVERY_S 10

/* A reload reads the scene files only once none has changed (size,
 * modification and change times, inode) for SW_CLI_RELOAD_QUIET seconds,
 * so that a file being rewritten in place is not read half-written; one
 * still changing SW_CLI_RELOAD_GIVE_UP seconds after the SIGHUP is not
 * applied. */
#define SW_CLI_RELOAD_QUIET 1.0    /* s */
#define SW_CLI_RELOAD_GIVE_UP 10.0 /* s */

/* What stat() says of a scene file, to tell a change. */
typedef struct {
    int exists;
    dev_t dev;
    ino_t ino;
    off_t size;
    struct timespec mtime, ctime;
} sw_cli_file_id_t;

/* A reload asked for by SIGHUP and not done yet. */
typedef struct {
    int pending;
    double asked;             /* monotonic s: the SIGHUP */
    double since;             /* the files have looked like seen[] since then */
    size_t changing;          /* the scene file seen changing last */
    sw_cli_file_id_t *seen;   /* per scene file, as last looked at */
    sw_cli_file_id_t *loaded; /* as when its scene was last read */
} sw_cli_reload_t;

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
    double reserve_rate;     /* Hz of sample time; < 0: no reserve */
    int lat_axis;            /* --lat-axis: 0..2, -1 none (a depth then rocks no plane) */
    const char *key_file;    /* --key, or NULL */
    sw_keyring_t *keys;      /* its keys, the monitor core's (a reload replaces them) */
    sw_cli_reload_t reload;
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

/* The reload's state for c's scene files as they are now (just read):
 * 0, or -1 when memory ran out (reported).  Freed by
 * sw_cli_mon_reload_free. */
int sw_cli_mon_reload_init(mon_ctx_t *c);
void sw_cli_mon_reload_free(mon_ctx_t *c);

/* SIGHUP at monotonic time now: a reload, done by sw_cli_mon_reload_poll()
 * once the files are quiet. */
void sw_cli_mon_reload_ask(mon_ctx_t *c, double now);

/* When the pending reload wants a look (monotonic s); INFINITY if none. */
double sw_cli_mon_reload_due(const mon_ctx_t *c);

/* At monotonic time now: if a reload is pending and every scene file has
 * stayed the same for SW_CLI_RELOAD_QUIET s, re-read the scene files of
 * c->opts (with its --set overrides) and rebuild the packages whose scene
 * changed (c->scenes updated in place), all or nothing; a file that
 * changed while it was read, or still changes SW_CLI_RELOAD_GIVE_UP s
 * after the SIGHUP, keeps every scene as it was.  Says what it did on
 * stderr.  Returns 1 when the reload is over (done or refused), 0 while
 * it waits. */
int sw_cli_mon_reload_poll(mon_ctx_t *c, double now);

#endif
