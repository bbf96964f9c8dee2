/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lcmlog.h - what the commands do around lcm-logger logs (eventlog.h):
 * corrupted regions reported one by one, a log checked before LCM's own
 * reader gets it (monitor --lcm-url file://...), and real-time pacing of a
 * replay that publishes.  LCM builds only. */
#ifndef SWAYWATCH_CLI_LCMLOG_H
#define SWAYWATCH_CLI_LCMLOG_H

#include "cli.h"
#include "eventlog.h"

/* Corrupted regions: each counted, the first SW_CLI_MAX_PRINTED_REGIONS
 * printed as "NAME: byte OFFSET: corrupted region of N bytes skipped:
 * WHY" (none with quiet).  on_region of sw_lcmlog_opts_t, user a
 * sw_cli_regions_t. */
#define SW_CLI_MAX_PRINTED_REGIONS 20
typedef struct {
    const char *name; /* the log, as quoted in messages */
    int quiet;
    long seen, printed;
} sw_cli_regions_t;
void sw_cli_print_region(void *user, const sw_lcmlog_region_t *r);
/* "NAME: ... N more corrupted regions" if some were not printed ("NAME: N
 * corrupted regions skipped" with quiet). */
void sw_cli_regions_summary(const sw_cli_regions_t *r);

/* An LCM URL that makes LCM read a log file itself (file://PATH, mode r):
 * LCM's reader trusts the file's length fields, so the file is checked
 * with ours first.  SW_EXIT_OK if url is no such URL or the log is whole;
 * else the reason is printed ("CMD: PATH: N corrupted regions ...") and
 * SW_EXIT_USAGE (damaged, or not a regular file) or SW_EXIT_IO (cannot be
 * read) is returned.  url NULL or "": $LCM_DEFAULT_URL, as LCM does. */
int sw_cli_check_lcm_url(const char *cmd, const char *url);

/* Real-time pacing by sample time: sw_cli_pace(p, t) sleeps until t / speed
 * seconds after the first call (t in s on the samples' clock).  A step of
 * more than SW_CLI_MAX_PAUSE s of wall time restarts the clock there
 * instead of waiting.  A signal that sets *stop (if not NULL) ends a
 * sleep. */
#define SW_CLI_MAX_PAUSE 3600.0
typedef struct {
    double speed; /* > 0; 0: no pacing */
    const volatile sig_atomic_t *stop;
    int started;
    double start, t0; /* monotonic s at sample time t0 */
} sw_cli_pacer_t;
void sw_cli_pace(sw_cli_pacer_t *p, double t);

#endif
