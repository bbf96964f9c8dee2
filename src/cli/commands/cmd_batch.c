/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cmd_batch.c - "swaywatch batch": one job (replay, job.h) over many
 * logs, given as operands and in a manifest (manifest.h) whose lines add
 * their own options; one JSON Lines record per log and package, and
 * optionally a CSV table of the same.
 *
 * This file holds the jobs, the options and the command; the work list is
 * built in batch_plan.c, run and written in batch_out.c (batch_int.h).  A
 * bad option, manifest line or scene stops the batch before any log runs;
 * a log that fails gives an error record, and the batch goes on. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "batch_int.h"
#include "interrupt.h"
#include "output.h"

/* ---- the jobs ------------------------------------------------------------------- */

static const sw_cli_job_t *const jobs[] = {&sw_cli_job_replay, &sw_cli_job_forensics};

static const sw_cli_job_t *job_named(const char *name)
{
    for (size_t i = 0; i < sizeof jobs / sizeof jobs[0]; i++)
        if (!strcmp(jobs[i]->name, name))
            return jobs[i];
    return NULL;
}

/* ---- options ---------------------------------------------------------------------- */

static int parse_job(const sw_cli_option_t *o, const char *arg, void *dest)
{
    const sw_cli_job_t **j = dest;
    if ((*j = job_named(arg)))
        return SW_EXIT_OK;
    char names[128] = "";
    for (size_t i = 0; i < sizeof jobs / sizeof jobs[0]; i++) {
        const size_t k = strlen(names);
        snprintf(names + k, sizeof names - k, "%s%s",
                 i ? (i + 1 < sizeof jobs / sizeof jobs[0] ? ", " : " or ") : "", jobs[i]->name);
    }
    sw_cli_error("--%s: expected %s, got '%s'", o->long_name, names, arg);
    return SW_EXIT_USAGE;
}

#define BO(f) SW_CLI_AT(batch_opts_t, f)

const sw_cli_option_t sw_batch_options[] = {
    {SW_CLI_SECTION, .help = "Batch:"},
    {SW_CLI_CALL, 0, "job", "NAME", BO(job), .fn = parse_job,
     .help = "what is done to each log: replay (the default), as 'swaywatch replay' does"},
    {SW_CLI_STRING, 'm', "manifest", "FILE", BO(manifest),
     .help = "the logs, one a line, each followed by its own options ('-': standard input); "
             "after the LOG operands"},
    {SW_CLI_LONG, 0, "threads", "N", BO(threads), .flags = SW_CLI_CAP, .min = 0, .max = 1024,
     .def = 0, .what = "a whole number of threads >= 0",
     .help = "worker threads (per MPI rank); 0, the default: the CPUs this process may run on; "
             "results do not depend on it"},
    {SW_CLI_SECTION, .help = "Output:"},
    {SW_CLI_STRING, 'o', "out", "FILE.jsonl", BO(out),
     .help = "the JSON Lines records, one per log and package (default, or '-': standard "
             "output)"},
    {SW_CLI_STRING, 0, "csv", "FILE.csv", BO(csv),
     .help = "the same as a CSV table, one row per log and package ('-': standard output, if "
             "--out names a file)"},
    {SW_CLI_FLAG, 0, "progress", BO(progress), .value = 1,
     .help = "logs done on stderr (default: only when stderr is a terminal)"},
    {SW_CLI_FLAG, 0, "no-progress", BO(progress), .value = 0, .help = "no progress"},
    {SW_CLI_FLAG, 'q', "quiet", BO(quiet), .value = 1,
     .help = "no messages of the logs and no summary on stderr (the records keep the messages)"},
    {SW_CLI_HELP, 'h', "help", .help = "this help"},
    {SW_CLI_TEXT,
     .help = "A record has the place of the log in the batch (index, from 1; line: its line in\n"
             "the manifest), the log, the job, status (ok, incomplete or error), the fields\n"
             "of the job's --json summary for one package (replay: the package's, settle,\n"
             "input: the log's facts) and the log's messages.  Status incomplete: the\n"
             "package's verdict is, because a gap or restart of its log overlapped motion\n"
             "and may hide an overturn.  A log that fails (exit code in exit) has one\n"
             "record, with status error and the reason in messages; the batch goes on.\n"
             "Under mpirun or srun (a build with MPI) the logs are shared among the ranks;\n"
             "rank 0 writes the same bytes as a single process."},
    {.kind = SW_CLI_END},
};

const sw_cli_command_t sw_batch_cmd = {
    .name = "batch",
    .usage = "batch [LOG ...] [--manifest FILE] --scene S.ini [options]",
    .about =
        "Runs a job over many logs: replays each, as 'swaywatch replay LOG' would with the\n"
        "same options, on every core (and under mpirun or srun on every rank), longest\n"
        "log first, and writes one JSON Lines record per log and package, in the order\n"
        "of the logs.  The options of the job (scenes, CSV input, input checks,\n"
        "integration) apply to every log; a manifest line adds its own after its log\n"
        "(its --scene replacing the command line's).  Options and scenes are checked\n"
        "before any log runs.\n",
    .exit_text =
        "Exit codes: 0 every log gave its records, 1 a package overturned, or a log's\n"
        "verdict is incomplete (its records' status: a gap or restart over motion), and\n"
        "--fail-on-overturn was given, 2 bad usage or input (options, manifest, scene\n"
        "files), 3 an output or the manifest could not be written or read, 4 some logs\n"
        "failed: their records say why, the others are done, 130 or 143 stopped by SIGINT\n"
        "or SIGTERM: the logs done have their records, whole; the others have none.\n",
};

/* ---- the command -------------------------------------------------------------------- */

/* The job named by --job NAME or --job=NAME, before the options are parsed
 * (its options are part of the table); the last one given wins, as when
 * parsing. */
static const sw_cli_job_t *find_job(int argc, char **argv)
{
    const sw_cli_job_t *j = &sw_cli_job_replay;
    for (int i = 1; i < argc && strcmp(argv[i], "--"); i++) {
        const char *name = NULL;
        if (!strcmp(argv[i], "--job") && i + 1 < argc)
            name = argv[i + 1];
        else if (!strncmp(argv[i], "--job=", 6))
            name = argv[i] + 6;
        if (name && job_named(name))
            j = job_named(name);
    }
    return j;
}

static void free_batch(batch_t *B)
{
    if (B->out)
        sw_cli_out_close(B->out, B->b.out ? B->b.out : "-");
    if (B->csv)
        sw_cli_out_close(B->csv, B->b.csv);
    for (size_t i = 0; i < B->nsets; i++) {
        B->job->destroy(B->sets[i].opts);
        free(B->sets[i].key);
    }
    free(B->sets);
    free(B->items);
    free(B->cost);
    free(B->by_rank);
    sw_cli_manifest_free(&B->man);
    free(B->mtext);
    sw_cli_parse_free(B->g, B->ng);
}

int cmd_batch(int argc, char **argv)
{
    batch_t B;
    memset(&B, 0, sizeof B);
    int rc = sw_cli_world_start(&B.world);
    if (rc != SW_EXIT_OK)
        return rc;
    /* SIGINT, SIGTERM: the logs done get their records, whole, and the
     * batch ends within a second (batch_out.c); never from inside a
     * job's search. */
    if ((rc = sw_cli_interrupt_install()) != SW_EXIT_OK)
        return sw_cli_world_end(&B.world, rc);
    sw_cli_interrupt_deferred();
    /* The other ranks set up as rank 0 does, and keep their messages to
     * themselves unless they alone fail. */
    char *msgs = NULL;
    size_t mlen = 0;
    FILE *mf = B.world.rank != 0 ? open_memstream(&msgs, &mlen) : NULL;
    if (mf)
        sw_cli_msg_to(mf);

    B.argc = argc;
    B.argv = argv;
    B.job = find_job(argc, argv);
    B.b.job = B.job;
    B.b.progress = B.world.rank == 0 && isatty(fileno(stderr));
    void *opts = B.job->create();
    if (!opts) {
        rc = SW_EXIT_IO;
        goto setup_done;
    }
    B.g[B.ng++] = (sw_cli_group_t)SW_CLI_GROUP(sw_batch_options, &B.b);
    B.ng += B.job->groups(opts, B.g + B.ng);
    rc = sw_cli_parse(&sw_batch_cmd, B.g, B.ng, argc, argv, &B.first);
    B.job->destroy(opts); /* a check of the options; each set parses them again */
    opts = NULL;
    sw_cli_parse_free(B.g, 1);
    B.ng = 0;
    if (rc != SW_CLI_CONTINUE)
        goto setup_done;
    B.job = B.b.job;
    rc = sw_batch_plan(&B);

setup_done:
    if (mf) {
        sw_cli_msg_to(NULL);
        fclose(mf);
    }
    if (rc == SW_CLI_CONTINUE)
        rc = SW_EXIT_OK;
    /* --help: every rank stops after it (rank 0 printed it) */
    const int help = rc == SW_EXIT_OK && B.n == 0;
    rc = sw_cli_world_agree(&B.world, rc, msgs, mlen);
    free(msgs);
    if (rc == SW_EXIT_OK && !help)
        rc = sw_batch_run(&B);
    free_batch(&B);
    return sw_cli_world_end(&B.world, rc);
}
