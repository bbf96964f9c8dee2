/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lcmlog.c - corrupted regions of lcm-logger logs reported, file:// URLs
 * checked before LCM reads them, and the pacing of a replay that
 * publishes (lcmlog.h). */
#include "lcmlog.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "lcmurl.h"
#include "monitor.h"

void sw_cli_print_region(void *user, const sw_lcmlog_region_t *r)
{
    sw_cli_regions_t *g = user;
    g->seen++;
    if (g->quiet || g->printed >= SW_CLI_MAX_PRINTED_REGIONS)
        return;
    g->printed++;
    sw_cli_error("%s: byte %lld: corrupted region of %lld bytes skipped: %s", g->name, r->offset,
                 r->length, r->why);
}

void sw_cli_regions_summary(const sw_cli_regions_t *r)
{
    if (r->seen <= r->printed)
        return;
    if (r->quiet)
        sw_cli_error("%s: %ld corrupted regions skipped", r->name, r->seen);
    else
        sw_cli_error("%s: ... %ld more corrupted regions", r->name, r->seen - r->printed);
}

int sw_cli_check_lcm_url(const char *cmd, const char *url)
{
    url = sw_cli_lcm_url_effective(url);
    if (!url)
        return SW_EXIT_OK;
    /* The path as liblcm takes it: the same options, the last of each. */
    char *path = malloc(strlen(url) + 1);
    if (!path) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    if (sw_cli_lcm_url_file(url, path, strlen(url) + 1) != SW_CLI_URL_READS) {
        free(path);
        return SW_EXIT_OK;
    }
    int rc = SW_EXIT_IO;
    sw_lcmlog_t *log = NULL;
    struct stat st;
    if (stat(path, &st) != 0) {
        sw_cli_error("%s: %s: cannot open: %s", cmd, path, strerror(errno));
        goto out;
    }
    /* LCM reads the file again after this check: a pipe would be empty. */
    if (!S_ISREG(st.st_mode)) {
        sw_cli_error(
            "%s: %s: not a regular file; LCM's file:// provider reads logs from files "
            "(replay reads pipes)",
            cmd, path);
        rc = SW_EXIT_USAGE;
        goto out;
    }
    int err = 0;
    log = sw_lcmlog_open(path, NULL, &err);
    if (log) { /* every event read, none used: the counts say what the log holds */
        sw_lcmlog_event_t ev;
        while ((err = sw_lcmlog_next(log, &ev)) > 0) continue;
    }
    if (!log || err != SW_OK) {
        sw_cli_error("%s: %s: cannot read: %s", cmd, path,
                     err == SW_ENOMEM ? "out of memory" : strerror(errno));
        goto out;
    }
    sw_lcmlog_counts_t c;
    sw_lcmlog_counts(log, &c);
    rc = SW_EXIT_OK;
    if (c.corrupt > 0) {
        sw_cli_error(
            "%s: %s: %ld corrupted region%s (the first at byte %lld: %lld bytes in "
            "all); LCM's file:// provider trusts the length fields of a log, so a "
            "damaged one is refused: 'swaywatch replay %s' reads it, skipping the "
            "damage",
            cmd, path, c.corrupt, c.corrupt == 1 ? "" : "s", c.first_corrupt, c.corrupt_bytes,
            path);
        rc = SW_EXIT_USAGE;
    }
out:
    sw_lcmlog_close(log);
    free(path);
    return rc;
}

void sw_cli_pace(sw_cli_pacer_t *p, double t)
{
    if (!(p->speed > 0.0))
        return;
    const double now = sw_mon_clock();
    if (!p->started || (t - p->t0) / p->speed - (now - p->start) > SW_CLI_MAX_PAUSE) {
        p->started = 1;
        p->start = now;
        p->t0 = t;
        return;
    }
    const double due = p->start + (t - p->t0) / p->speed;
    while (!(p->stop && *p->stop)) {
        const double d = due - sw_mon_clock();
        if (d <= 0.0)
            break;
        struct timespec ts = {(time_t)d, (long)((d - floor(d)) * 1e9)};
        nanosleep(&ts, NULL); /* a signal ends it early: the loop looks at *stop */
    }
}
