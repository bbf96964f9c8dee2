/* SPDX-License-Identifier: GPL-3.0-or-later */
/* batch_out.c - the run of "swaywatch batch" (batch_int.h) and its
 * records: the outputs checked and opened, each log run by its job on the
 * farm, and one JSON Lines record per log and package (and a CSV row of
 * the same) written on rank 0.
 *
 * The logs run on the farm (farm.h): on every core, and under mpirun or
 * srun on every rank, the longest (biggest) first; the records are written
 * in the order of the logs, the same bytes whatever the number of threads
 * or ranks.  A log that fails (unreadable, refused by the input gate) gives
 * an error record with the reason, and the batch goes on. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "batch_int.h"
#include "clobber.h"
#include "interrupt.h"
#include "output.h"

/* ---- records -------------------------------------------------------------------- */

/* What a job's run writes for a log: each package's status and JSON
 * record on a line, as text, for rank 0 (farm.h). */
struct sw_cli_records {
    FILE *f;
    long n;
    int oom; /* a record could not be made: the log fails */
};

void sw_cli_records_package(sw_cli_records_t *rec, const sw_summary_t *s, const sw_cli_run_t *run,
                            json_t *o)
{
    if (run->have_facts)
        sw_cli_json_facts(o, "input", run);
    char *line = sw_cli_rec_line(o); /* one line: JSON escapes every line break */
    if (!line) {
        rec->oom = 1;
        return;
    }
    /* a status is one word of letters: nothing else can end it */
    fprintf(rec->f, "%s %s\n", strcmp(sw_cli_verdict(s, run), "incomplete") ? "ok" : "incomplete",
            line);
    free(line);
    rec->n++;
}

/* ---- outputs ---------------------------------------------------------------------- */

static int is_stdout(const char *path)
{
    return !path || !strcmp(path, "-");
}

/* The rules of every command (clobber.h): no output is a log, the
 * manifest or a scene of any line, and --out and --csv are two files
 * (also when one is named ./x and the other x). */
static int check_outputs(const batch_t *B)
{
    if (B->b.csv && is_stdout(B->b.out) && is_stdout(B->b.csv)) {
        sw_cli_error("--csv -: standard output already carries the records (give --out a file)");
        return SW_EXIT_USAGE;
    }
    const sw_cli_file_t out[] = {{"--out", is_stdout(B->b.out) ? NULL : B->b.out},
                                 {"--csv", B->b.csv}};
    size_t nin = 1 + B->n;
    for (size_t k = 0; k < B->nsets; k++) nin += B->job->common(B->sets[k].opts)->scenes.n;
    sw_cli_file_t *in = calloc(nin, sizeof *in);
    if (!in) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    size_t m = 0;
    in[m++] = (sw_cli_file_t){"--manifest", B->b.manifest};
    for (size_t i = 0; i < B->n; i++) in[m++] = (sw_cli_file_t){"LOG", B->items[i].log};
    for (size_t k = 0; k < B->nsets; k++) {
        const sw_cli_list_t *sc = &B->job->common(B->sets[k].opts)->scenes;
        for (size_t i = 0; i < sc->n; i++) in[m++] = (sw_cli_file_t){"--scene", sc->v[i]};
    }
    const int rc = sw_cli_check_files(in, m, out, sizeof out / sizeof out[0]);
    free(in);
    return rc;
}

static int open_outputs(batch_t *B)
{
    B->out = sw_cli_out_open(B->b.out ? B->b.out : "-");
    if (!B->out)
        return SW_EXIT_IO;
    if (!B->b.csv)
        return SW_EXIT_OK;
    B->csv = sw_cli_out_open(B->b.csv);
    if (!B->csv)
        return SW_EXIT_IO;
    fputs("index,line,log,job,status", B->csv);
    sw_cli_csv_header(B->csv, B->job->columns, B->job->ncolumns);
    fputs(",messages\n", B->csv);
    return SW_EXIT_OK;
}

/* ---- one log, on any thread of any rank --------------------------------------------- */

static void run_item(void *user, size_t i, FILE *out)
{
    const batch_t *B = user;
    const item_t *it = &B->items[i];
    char *buf = NULL;
    size_t len = 0;
    sw_cli_records_t rec = {.f = open_memstream(&buf, &len)};
    int rc = SW_EXIT_IO;
    if (!rec.f)
        sw_cli_error("%s: out of memory", it->log);
    else
        rc = B->job->run(B->sets[it->set].opts, it->log, &rec);
    if (rec.f && (fclose(rec.f) != 0 || rec.oom) &&
        (rc == SW_EXIT_OK || rc == SW_EXIT_OVERTURNED)) {
        sw_cli_error("%s: out of memory", it->log);
        rc = SW_EXIT_IO;
    }
    if (sw_cli_signal) { /* the run may have been cut short: no record from it */
        sw_cli_error("%s: interrupted by %s", it->log, sw_cli_signal_name(sw_cli_signal));
        rc = 128 + sw_cli_signal;
    }
    const int good = rc == SW_EXIT_OK || rc == SW_EXIT_OVERTURNED;
    fprintf(out, "%d %ld\n", rc, good ? rec.n : 0L);
    if (good)
        fwrite(buf, 1, len, out);
    free(buf);
}

/* ---- the records, on rank 0, in order ----------------------------------------------- */

/* The messages as member "messages" of rec and as one CSV field
 * (joined by " | "), each without the "swaywatch: " prefix. */
static void messages(json_t *rec, FILE *cf, const char *msgs, size_t mlen)
{
    char *joined = NULL;
    size_t jlen = 0;
    FILE *j = cf ? open_memstream(&joined, &jlen) : NULL;
    json_t *arr = sw_cli_rec_arr(rec, "messages");
    const char *p = msgs, *end = msgs + mlen;
    for (int k = 0; p < end; k++) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        if (le - p >= 11 && !strncmp(p, "swaywatch: ", 11))
            p += 11;
        char *line = strndup(p, (size_t)(le - p));
        if (line)
            sw_cli_rec_text(arr, NULL, line);
        else
            sw_cli_rec_put(arr, NULL, NULL); /* no memory: the record fails */
        if (line && j)
            fprintf(j, "%s%s", k ? " | " : "", line);
        free(line);
        p = nl ? nl + 1 : end;
    }
    if (j && fclose(j) == 0) {
        fputc(',', cf);
        sw_cli_csv_text(cf, joined);
    } else if (cf) {
        fputc(',', cf);
    }
    free(joined);
}

/* What every record of log i begins with: a new record (NULL: out of
 * memory) and the CSV row's first fields. */
static json_t *head(const batch_t *B, size_t i, const char *status)
{
    const item_t *it = &B->items[i];
    json_t *rec = sw_cli_rec_new();
    sw_cli_rec_int(rec, "index", (long long)i + 1);
    sw_cli_rec_put(rec, "line", it->line ? json_integer(it->line) : json_null());
    sw_cli_rec_text(rec, "log", it->log);
    sw_cli_rec_text(rec, "job", B->job->name);
    sw_cli_rec_text(rec, "status", status);
    if (B->csv) {
        fprintf(B->csv, "%zu,", i + 1);
        if (it->line)
            fprintf(B->csv, "%ld", it->line);
        fputc(',', B->csv);
        sw_cli_csv_text(B->csv, it->log);
        fprintf(B->csv, ",%s,%s", B->job->name, status);
    }
    return rec;
}

/* The record on its line; -1 when memory ran out (reported). */
static int put_record(batch_t *B, size_t i, json_t *rec)
{
    if (sw_cli_rec_write(B->out, rec, SW_CLI_REC_LINE) != 0) {
        sw_cli_error("%s: its record: out of memory", B->items[i].log);
        return -1;
    }
    if (B->csv)
        fputc('\n', B->csv);
    B->records++;
    return 0;
}

static int take_item(void *user, size_t i, const char *data, size_t len, const char *msgs,
                     size_t mlen)
{
    batch_t *B = user;
    int rc = SW_EXIT_IO;
    long npkg = 0;
    const char *p = data, *end = data + len;
    if (sscanf(p, "%d %ld", &rc, &npkg) != 2)
        rc = SW_EXIT_IO, npkg = 0;
    p = memchr(p, '\n', len);
    p = p ? p + 1 : end;
    const int good = rc == SW_EXIT_OK || rc == SW_EXIT_OVERTURNED;
    if (rc > 128 && sw_cli_signal) {
        B->cut++; /* this process is stopping: a log not done has no record */
        return 0;
    }
    if (!B->b.quiet && mlen)
        fwrite(msgs, 1, mlen, stderr);
    int bad = 0;
    if (good) {
        B->ok++;
        B->overturned |= rc == SW_EXIT_OVERTURNED;
        for (long k = 0; k < npkg && p < end; k++) {
            char status[16];
            int at = 0;
            const char *nl = memchr(p, '\n', (size_t)(end - p));
            if (!nl || sscanf(p, "%15[a-z] %n", status, &at) != 1 || at <= 0)
                break;
            json_error_t jerr;
            json_t *members = json_loadb(p + at, (size_t)(nl - p) - (size_t)at, 0, &jerr);
            p = nl + 1;
            json_t *rec = head(B, i, status);
            if (!members || json_object_update(rec, members) != 0)
                sw_cli_rec_put(rec, "members", NULL); /* the record fails */
            if (B->csv)
                sw_cli_csv_row(B->csv, members, B->job->columns, B->job->ncolumns);
            json_decref(members);
            messages(rec, B->csv, msgs, mlen);
            bad |= put_record(B, i, rec);
        }
    } else {
        B->failed++;
        json_t *rec = head(B, i, "error");
        sw_cli_rec_int(rec, "exit", rc);
        if (B->csv)
            for (size_t k = 0; k < B->job->ncolumns; k++) fputc(',', B->csv);
        messages(rec, B->csv, msgs, mlen);
        bad |= put_record(B, i, rec);
    }
    if (bad || ferror(B->out) || (B->csv && ferror(B->csv))) {
        if (!bad)
            sw_cli_error("%s: write failed: %s",
                         ferror(B->out) ? sw_cli_out_name(B->b.out ? B->b.out : "-")
                                        : sw_cli_out_name(B->b.csv),
                         strerror(errno));
        B->write_failed = 1;
        return -1;
    }
    return 0;
}

/* ---- the run -------------------------------------------------------------------- */

/* A signal stopped the farm (rank 0): the records of the logs done are
 * written, whole, the outputs closed, and the process ends at once (jobs
 * still running on other threads and ranks are not waited for) with 128 +
 * the signal. */
static void interrupted(batch_t *B)
{
    const int code = sw_cli_interrupt_code();
    int rc = B->out ? sw_cli_out_close(B->out, B->b.out ? B->b.out : "-") : SW_EXIT_OK;
    const int rc2 = B->csv ? sw_cli_out_close(B->csv, B->b.csv) : SW_EXIT_OK;
    B->out = B->csv = NULL;
    const long done = B->ok + B->failed;
    sw_cli_error(
        "batch: interrupted by %s: %ld of %zu logs done, their %ld record%s written whole to "
        "%s%s%s; the other %zu logs have no record",
        sw_cli_signal_name(sw_cli_signal), done, B->n, B->records, B->records == 1 ? "" : "s",
        sw_cli_out_name(B->b.out ? B->b.out : "-"), B->b.csv ? " and " : "",
        B->b.csv ? sw_cli_out_name(B->b.csv) : "", B->n - (size_t)done);
    sw_cli_world_exit(&B->world, rc != SW_EXIT_OK || rc2 != SW_EXIT_OK ? SW_EXIT_IO : code);
}

int sw_batch_run(batch_t *B)
{
    int rc = SW_EXIT_OK;
    if (B->world.rank == 0 &&
        ((rc = check_outputs(B)) != SW_EXIT_OK || (rc = open_outputs(B)) != SW_EXIT_OK)) {
        /* fall through to agree: the other ranks wait for the verdict */
    }
    if ((rc = sw_cli_world_agree(&B->world, rc, NULL, 0)) != SW_EXIT_OK)
        return rc;
    B->threads = sw_cli_threads(&B->world, B->b.threads);
    B->by_rank = calloc((size_t)B->world.size, sizeof *B->by_rank);
    const sw_cli_farm_t farm = {
        .world = &B->world,
        .n = B->n,
        .cost = B->cost,
        .threads = B->threads,
        .by_rank = B->by_rank,
        .run = run_item,
        .take = take_item,
        .user = B,
        .what = B->b.progress ? "logs" : NULL,
        .stop = &sw_cli_signal,
    };
    rc = sw_cli_farm_run(&farm);
    if (rc == SW_CLI_FARM_INTERRUPTED)
        interrupted(B); /* does not return */
    if (B->world.rank != 0)
        return rc;
    int rc2 = B->out ? sw_cli_out_close(B->out, B->b.out ? B->b.out : "-") : SW_EXIT_OK;
    int rc3 = B->csv ? sw_cli_out_close(B->csv, B->b.csv) : SW_EXIT_OK;
    B->out = B->csv = NULL;
    if (rc == SW_EXIT_OK)
        rc = rc2 != SW_EXIT_OK ? rc2 : rc3;
    if (rc != SW_EXIT_OK)
        return rc;
    if (!B->b.quiet) {
        sw_cli_error("batch: %zu log%s: %ld done, %ld failed; %ld record%s to %s%s%s", B->n,
                     B->n == 1 ? "" : "s", B->ok, B->failed, B->records, B->records == 1 ? "" : "s",
                     sw_cli_out_name(B->b.out ? B->b.out : "-"), B->b.csv ? ", the table to " : "",
                     B->b.csv ? sw_cli_out_name(B->b.csv) : "");
        if (B->world.size > 1 && B->by_rank) { /* how the work was shared */
            FILE *m = sw_cli_msg();
            fprintf(m, "swaywatch: batch: %d ranks (rank 0 with %d thread%s); logs run by each:",
                    B->world.size, B->threads, B->threads == 1 ? "" : "s");
            for (int r = 0; r < B->world.size; r++) fprintf(m, " %ld", B->by_rank[r]);
            fputc('\n', m);
        }
    }
    if (B->failed)
        return SW_EXIT_PARTIAL;
    return B->overturned ? SW_EXIT_OVERTURNED : SW_EXIT_OK;
}
