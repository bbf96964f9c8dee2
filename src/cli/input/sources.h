/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sources.h - what a source of samples is (sw_cli_source_t: a row of
 * functions, as LCM's providers are, with the options a log is read
 * with) and the table of those this build has (sources.c).  The reader
 * (source.h, source.c) goes through the table, which knows the reader
 * only by name (sw_cli_reader_t) and calls nothing above it; the rows
 * (source_csv.c, source_lcmlog.c) are the reader's calls for their
 * source. */
#ifndef SWAYWATCH_CLI_SOURCES_H
#define SWAYWATCH_CLI_SOURCES_H

#include <stddef.h>

#include "input.h"
#include "monitor_opts.h"
#include "opts.h"

/* How a log is read: CSV options, the gate's, and those of lcm-logger
 * files; bound to option rows by the command (input.h, and the sources'
 * own groups: sw_cli_source_groups). */
typedef struct {
    sw_cli_csv_opts_t copts;
    sw_cli_gate_t gate;
    /* lcm-logger files */
    const char *channel;     /* the accel channel regex */
    const char *key_file;    /* --key: authenticated samples only */
    sw_mon_opts_t mo;        /* axes, --max-skew; publishing channels and rate */
    const char *publish_url; /* --publish; NULL: no publishing */
    double speed;            /* --publish: X times real time; 0 as fast as possible */
} sw_cli_read_opts_t;

typedef struct sw_cli_reader sw_cli_reader_t;

/* One source of samples. */
typedef struct sw_cli_source {
    const char *name;  /* what such a log is, in messages and reports: "a CSV log" */
    const char *takes; /* what its own options are for: "CSV logs" */
    const char *picks; /* the options that choose its channels and units, for a refusal */
    int (*sniff)(const void *buf, size_t len); /* its first bytes; NULL: anything (the last row) */
    const sw_cli_option_t *const *own;         /* option tables only it takes (NULL-ended) */
    void (*init)(sw_cli_read_opts_t *o);       /* its options' defaults */
    /* its option groups bound to o, those of publishing too with publish,
     * into g; returns how many (at most SW_CLI_SOURCE_GROUPS); may be NULL */
    size_t (*groups)(sw_cli_read_opts_t *o, sw_cli_group_t *g, int publish);
    /* the reader's calls below, for this source; NULL: nothing to do */
    int (*prepare)(sw_cli_reader_t *R);
    int (*start)(sw_cli_reader_t *R, const sw_scene_t *scenes, size_t n,
                 const sw_engine_opts_t *eo);
    /* every sample into R->st; fills R->run's counts and dates, R->accepted,
     * R->interrupted or R->halted, and f (the gate's facts, those refused
     * upstream counted) and *vert (a vertical channel) for the check */
    int (*feed)(sw_cli_reader_t *R, sw_gate_facts_t *f, int *vert);
    /* after the verdict's check: rc its result, SW_EXIT_USAGE when there
     * was none (no sample taken, a signal) */
    void (*checked)(sw_cli_reader_t *R, int rc);
    int (*report)(sw_cli_reader_t *R);
    void (*close)(sw_cli_reader_t *R);
} sw_cli_source_t;

#define SW_CLI_SOURCE_GROUPS 4 /* groups a source offers at most */
#define SW_CLI_SOURCES_MAX 4   /* rows of the table at most */

/* The source of a log whose first len bytes are buf: the first row of the
 * build's table whose sniff matches.  NULL when they say it is a kind of
 * log this build does not read; *needs then says what it would take
 * ("lcm-logger files need the LCM build"). */
const sw_cli_source_t *sw_cli_source_of(const void *buf, size_t len, const char **needs);
/* The rows of the table, NULL after the last. */
const sw_cli_source_t *sw_cli_source_at(size_t i);

extern const sw_cli_source_t sw_cli_source_csv;
extern const sw_cli_source_t sw_cli_source_lcmlog; /* LCM builds */

#endif
