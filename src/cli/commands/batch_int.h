/* SPDX-License-Identifier: GPL-3.0-or-later */
/* batch_int.h - what the files of "swaywatch batch" share: its options,
 * the state of a batch, and the two halves of its work.  cmd_batch.c
 * parses the options and runs the command, batch_plan.c builds the work
 * list (the logs of the operands and of the manifest, each with its set of
 * the job's options), batch_out.c runs it on the farm and writes the
 * records.  The jobs see only job.h.  sw_batch_ names the command's
 * own. */
#ifndef SWAYWATCH_CLI_BATCH_INT_H
#define SWAYWATCH_CLI_BATCH_INT_H

#include <stdio.h>

#include "farm.h"
#include "job.h"
#include "manifest.h"

/* batch's own options. */
typedef struct {
    const sw_cli_job_t *job;
    const char *manifest; /* --manifest */
    const char *out;      /* --out; NULL: standard output */
    const char *csv;      /* --csv */
    long threads;
    int progress, quiet;
} batch_opts_t;

/* One log of the batch. */
typedef struct {
    const char *log;
    long line;  /* in the manifest; 0: an operand */
    size_t set; /* its options */
} item_t;

/* One set of a job's options. */
typedef struct {
    void *opts;
    char *key; /* the line's options, joined; NULL: the command line's alone */
} optset_t;

/* Everything a batch uses. */
typedef struct {
    sw_cli_world_t world;
    batch_opts_t b;
    const sw_cli_job_t *job;
    /* the command line */
    int argc;
    char **argv;
    int first; /* its first operand */
    sw_cli_group_t g[SW_CLI_JOB_GROUPS + 1];
    size_t ng;
    /* the logs */
    char *mtext;
    size_t mlen;
    sw_cli_manifest_t man;
    item_t *items;
    size_t n;
    optset_t *sets;
    size_t nsets, sets_cap;
    double *cost;
    /* outputs (rank 0) */
    FILE *out, *csv;
    long ok, failed, records;
    long cut;       /* logs a signal stopped: no record */
    int overturned; /* a log's job gave 1 (--fail-on-overturn) */
    int write_failed;
    long *by_rank; /* logs each rank ran */
    int threads;   /* per rank */
} batch_t;

/* batch's own rows and the command: a manifest line's options are parsed
 * with them, as the command line's are. */
extern const sw_cli_option_t sw_batch_options[];
extern const sw_cli_command_t sw_batch_cmd;

/* The logs: the operands, then the manifest's lines, each with its set of
 * options (made ready: scenes read), and what each costs; SW_EXIT_*
 * (reported). */
int sw_batch_plan(batch_t *B);

/* Every log run on the farm, the records written on rank 0 in the order
 * of the logs, the outputs closed and the summary said; SW_EXIT_*
 * (reported). */
int sw_batch_run(batch_t *B);

#endif
