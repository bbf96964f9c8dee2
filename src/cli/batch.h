/* SPDX-License-Identifier: GPL-3.0-or-later */
/* batch.h - the jobs of "swaywatch batch": what is done to each log.
 *
 * A job is a table: its options (the same rows as the command of its name,
 * less that command's own outputs), parsed once per distinct set of
 * options (the command line's, and each manifest line's on top of them),
 * and a function that runs one log with them and writes the log's part of
 * the records: for each package, the members of its JSON Lines record and
 * the fields of its CSV row.  The batch adds what every record has (the
 * log, its place in the batch, its status, its messages), writes the
 * error records of logs that failed, and keeps the order.  A job's run
 * may be called on any thread of any rank at once with the same options:
 * it only reads them. */
#ifndef SWAYWATCH_CLI_BATCH_H
#define SWAYWATCH_CLI_BATCH_H

#include <stdio.h>

#include "opts.h"
#include "output.h"

/* Where a job writes one log's records: for each package, one call of
 * package() with its status (a word: "ok", "incomplete"), the JSON members
 * (no braces; the batch puts its own before them) and the CSV fields (as
 * many as the job's header names). */
typedef struct sw_cli_records sw_cli_records_t;
void sw_cli_records_package(sw_cli_records_t *rec, const char *status, const char *json,
                            size_t jlen, const char *csv, size_t clen);

/* One package's record while a job writes it: the JSON members to j and
 * the CSV fields to c, two memory streams; its status (NULL: "ok"). */
typedef struct {
    FILE *j, *c;
    char *json, *csv;
    size_t jlen, clen;
    const char *status;
} sw_cli_record_t;

/* A package's record status: "incomplete" when its verdict is (a gap may
 * have hidden an overturn: a script reading "ok" must not take it as
 * one), else "ok"; a log that fails has "error" records (batch_out.c). */
const char *sw_cli_record_status(const sw_summary_t *s, const sw_cli_run_t *run);
/* Open both streams: 0, or -1 when memory ran out (then write nothing,
 * but still call sw_cli_record_end). */
int sw_cli_record_begin(sw_cli_record_t *r);
/* Close the streams and, if nothing failed, hand the record to rec with
 * its JSON on one line (its own line breaks become spaces); free it.  0,
 * or -1 when memory ran out (nothing handed over). */
int sw_cli_record_end(sw_cli_records_t *rec, sw_cli_record_t *r);

typedef struct {
    const char *name;  /* --job NAME */
    const char *about; /* one line for --help */
    /* options at their defaults (NULL: out of memory, reported); freed by
     * destroy (NULL ok), lists the parser made included */
    void *(*create)(void);
    void (*destroy)(void *opts);
    /* its groups bound to opts (at most SW_CLI_JOB_GROUPS) */
    size_t (*groups)(void *opts, sw_cli_group_t *g);
    /* the shared options in opts (the scenes: a manifest line's replace
     * the command line's) */
    sw_cli_opts_t *(*common)(void *opts);
    /* after parsing: the scenes read and checked, once; SW_EXIT_* (reported) */
    int (*ready)(void *opts, const sw_cli_group_t *g, size_t ng);
    /* one log: its records; returns the exit code the log's own command
     * would give (0 ok, 1 overturned with --fail-on-overturn, else a
     * failure, reported: the batch then writes an error record and drops
     * what was written) */
    int (*run)(const void *opts, const char *log, sw_cli_records_t *rec);
    const char *csv_header; /* the CSV fields of run, names joined by commas */
} sw_cli_job_t;

#define SW_CLI_JOB_GROUPS 20

extern const sw_cli_job_t sw_cli_job_replay;
extern const sw_cli_job_t sw_cli_job_forensics;

#endif
