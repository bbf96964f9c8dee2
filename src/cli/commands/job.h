/* SPDX-License-Identifier: GPL-3.0-or-later */
/* job.h - what a command offers "swaywatch batch": a job, done to each
 * log.  A command that has one defines it in a file of its own
 * (replay_job.c, forensics_job.c), the batch lists the jobs by name
 * (cmd_batch.c) and sees nothing else of the command: the commands do
 * not include each other, only this contract.
 *
 * A job is a table: its options (the same rows as the command of its name,
 * less that command's own outputs), parsed once per distinct set of
 * options (the command line's, and each manifest line's on top of them),
 * and a function that runs one log with them and writes the log's part of
 * the records: for each package, the members of its JSON Lines record;
 * its CSV row is read off that record by the job's columns (record.h), so
 * the two cannot disagree.  The batch adds what every record has (the
 * log, its place in the batch, its status, its messages), writes the
 * error records of logs that failed, and keeps the order.  A job's run
 * may be called on any thread of any rank at once with the same options:
 * it only reads them. */
#ifndef SWAYWATCH_CLI_JOB_H
#define SWAYWATCH_CLI_JOB_H

#include <stdio.h>

#include "opts.h"
#include "output.h"

/* Where a job writes one log's records: for each package, one call with
 * its summary s, the log's run and its members in o, made by
 * sw_cli_rec_new() (the batch puts its own before them, the input's
 * facts after them as "input"; o is released).  Its status is
 * "incomplete" when its verdict is (a gap may have hidden an overturn: a
 * script reading "ok" must not take it as one), else "ok"; a log that
 * fails has "error" records (batch_out.c), as one whose record ran out of
 * memory. */
typedef struct sw_cli_records sw_cli_records_t;
void sw_cli_records_package(sw_cli_records_t *rec, const sw_summary_t *s, const sw_cli_run_t *run,
                            json_t *o);

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
    /* the job's columns of the CSV table, read off each record */
    const sw_cli_column_t *columns;
    size_t ncolumns;
} sw_cli_job_t;

#define SW_CLI_JOB_GROUPS 20

extern const sw_cli_job_t sw_cli_job_replay;
extern const sw_cli_job_t sw_cli_job_forensics;

#endif
