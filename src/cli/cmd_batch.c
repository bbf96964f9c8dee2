/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cmd_batch.c - "swaywatch batch": one job (replay, batch.h) over many
 * logs, given as operands and in a manifest (manifest.h) whose lines add
 * their own options; one JSON Lines record per log and package, and
 * optionally a CSV table of the same.
 *
 * The command line's options are parsed once; each distinct set of a
 * manifest line's options is parsed once more, on top of them (a line's
 * --scene replaces the command line's scenes), and its scenes read then,
 * so that a bad option or scene stops the batch before any log is run.  A
 * log that fails (unreadable, refused by the input gate) gives an error
 * record with the reason, and the batch goes on.
 *
 * The logs run on the farm (farm.h): on every core, and under mpirun or
 * srun on every rank, the longest (biggest) first; the records are written
 * in the order of the logs, the same bytes whatever the number of threads
 * or ranks. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "batch.h"
#include "farm.h"
#include "manifest.h"
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

/* ---- records -------------------------------------------------------------------- */

/* What a job's run writes for a log: each package's JSON members and CSV
 * fields, with their lengths. */
struct sw_cli_records {
    FILE *f;
    long n;
};

void sw_cli_records_package(sw_cli_records_t *rec, const char *json, size_t jlen, const char *csv,
                            size_t clen)
{
    fprintf(rec->f, "%zu %zu\n", jlen, clen);
    fwrite(json, 1, jlen, rec->f);
    fwrite(csv, 1, clen, rec->f);
    rec->n++;
}

int sw_cli_record_begin(sw_cli_record_t *r)
{
    memset(r, 0, sizeof *r);
    r->j = open_memstream(&r->json, &r->jlen);
    r->c = open_memstream(&r->csv, &r->clen);
    return r->j && r->c ? 0 : -1;
}

int sw_cli_record_end(sw_cli_records_t *rec, sw_cli_record_t *r)
{
    int bad = !r->j || !r->c;
    if (r->j && fclose(r->j) != 0)
        bad = 1;
    if (r->c && fclose(r->c) != 0)
        bad = 1;
    if (!bad) {
        for (size_t i = 0; i < r->jlen; i++)
            if (r->json[i] == '\n')
                r->json[i] = ' ';
        sw_cli_records_package(rec, r->json, r->jlen, r->csv, r->clen);
    }
    free(r->json);
    free(r->csv);
    memset(r, 0, sizeof *r);
    return bad ? -1 : 0;
}

/* ---- options ---------------------------------------------------------------------- */

typedef struct {
    const sw_cli_job_t *job;
    const char *manifest; /* --manifest */
    const char *out;      /* --out; NULL: standard output */
    const char *csv;      /* --csv */
    long threads;
    int progress, quiet;
} batch_opts_t;

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

static const sw_cli_option_t batch_options[] = {
    {SW_CLI_SECTION, .help = "Batch:"},
    {SW_CLI_CALL, 0, "job", "NAME", BO(job), .fn = parse_job,
     .help = "what is done to each log: replay (the default), as 'swaywatch replay' does"},
    {SW_CLI_STRING, 'm', "manifest", "FILE", BO(manifest),
     .help = "the logs, one a line, each followed by its own options ('-': standard input); "
             "after the LOG operands"},
    {SW_CLI_LONG, 0, "threads", "N", BO(threads), .min = 0, .max = 1024, .def = 0,
     .what = "a whole number of threads >= 0",
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
             "the manifest), the log, the job, status ok or error, the fields of the job's\n"
             "--json summary for one package (replay: the package's, settle, input: the\n"
             "log's facts) and the log's messages.  A log that fails (exit code in exit) has\n"
             "one record, with status error and the reason in messages; the batch goes on.\n"
             "Under mpirun or srun (a build with MPI) the logs are shared among the ranks;\n"
             "rank 0 writes the same bytes as a single process."},
    {SW_CLI_END},
};

static const sw_cli_command_t batch_cmd = {
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
        "Exit codes: 0 every log gave its records, 1 a package overturned and\n"
        "--fail-on-overturn was given, 2 bad usage or input (options, manifest, scene\n"
        "files), 3 an output or the manifest could not be written or read, 4 some logs\n"
        "failed: their records say why, the others are done.\n",
};

/* ---- the batch -------------------------------------------------------------------- */

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

typedef struct {
    sw_cli_world_t world;
    batch_opts_t b;
    const sw_cli_job_t *job;
    size_t csv_fields; /* of the job's CSV header */
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
    size_t nsets;
    double *cost;
    /* outputs (rank 0) */
    FILE *out, *csv;
    long ok, failed, records;
    int overturned; /* a log's job gave 1 (--fail-on-overturn) */
    int write_failed;
    long *by_rank; /* logs each rank ran */
    int threads;   /* per rank */
} batch_t;

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

/* The messages printed while f ran, each line again as
 * "swaywatch: WHERE: message". */
static void reprint(const char *where, const char *msgs, size_t len)
{
    const char *p = msgs, *end = msgs + len;
    while (p < end) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        if (le - p >= 11 && !strncmp(p, "swaywatch: ", 11))
            p += 11;
        sw_cli_error("%s: %.*s", where, (int)(le - p), p);
        p = nl ? nl + 1 : end;
    }
}

/* A new set of the job's options: the command line's options, then args
 * (a manifest line's; NULL for none), parsed and made ready.  Messages of
 * a line's set name the manifest's line. */
static int new_set(batch_t *B, char **args, size_t nargs, long line, optset_t *set)
{
    const sw_cli_job_t *J = B->job;
    int rc = SW_EXIT_IO;
    set->opts = J->create();
    if (!set->opts)
        return SW_EXIT_IO;
    sw_cli_group_t g[SW_CLI_JOB_GROUPS + 1];
    size_t ng = 0;
    char **argv = NULL;
    void *alone = NULL;
    char *msgs = NULL;
    size_t mlen = 0;
    FILE *mf = NULL, *before = NULL;
    char where[512];
    snprintf(where, sizeof where, "%s:%ld", B->b.manifest ? B->b.manifest : "", line);
    if (args) { /* the line's messages, to say where they come from */
        mf = open_memstream(&msgs, &mlen);
        if (!mf)
            goto oom;
        before = sw_cli_msg_to(mf);
    }
    size_t nline_scenes = 0;
    int first;
    if (args) {
        /* the line alone: only the job's options, and how many scenes */
        alone = J->create();
        if (!alone)
            goto oom;
        sw_cli_group_t ga[SW_CLI_JOB_GROUPS];
        const size_t na = J->groups(alone, ga);
        char **av = calloc(nargs + 2, sizeof *av);
        if (!av)
            goto oom;
        av[0] = "batch";
        memcpy(av + 1, args, nargs * sizeof *av);
        rc = sw_cli_parse(&batch_cmd, ga, na, (int)nargs + 1, av, &first);
        if (rc == SW_CLI_CONTINUE && first < (int)nargs + 1) {
            sw_cli_error("unexpected '%s': one log a line, first", av[first]);
            rc = SW_EXIT_USAGE;
        }
        free(av);
        if (rc != SW_CLI_CONTINUE)
            goto out;
        nline_scenes = J->common(alone)->scenes.n;
    }
    /* the command line's options (the batch's own too, into a copy), then
     * the line's */
    batch_opts_t scratch = B->b;
    g[ng++] = (sw_cli_group_t)SW_CLI_GROUP(batch_options, &scratch);
    ng += J->groups(set->opts, g + ng);
    argv = calloc((size_t)B->first + nargs + 1, sizeof *argv);
    if (!argv)
        goto oom;
    int argc = 0;
    argv[argc++] = "batch";
    for (int i = 1; i < B->first; i++)
        if (strcmp(B->argv[i], "--"))
            argv[argc++] = B->argv[i];
    for (size_t i = 0; i < nargs; i++) argv[argc++] = args[i];
    rc = sw_cli_parse(&batch_cmd, g, ng, argc, argv, &first);
    if (rc != SW_CLI_CONTINUE)
        goto out;
    sw_cli_list_t *sc = &J->common(set->opts)->scenes;
    if (nline_scenes > 0 && sc->n > nline_scenes) { /* the line's scenes replace the others */
        memmove(sc->v, sc->v + (sc->n - nline_scenes), nline_scenes * sizeof *sc->v);
        sc->n = nline_scenes;
    }
    rc = J->ready(set->opts, g + 1, ng - 1);
    goto out;
oom:
    sw_cli_error("out of memory");
    rc = SW_EXIT_IO;
out:
    if (mf) {
        sw_cli_msg_to(before == stderr ? NULL : before);
        fclose(mf);
        reprint(where, msgs, mlen);
        free(msgs);
    }
    J->destroy(alone);
    free(argv);
    /* the lists of set->opts are freed with it (destroy); the batch's own
     * options have none */
    return rc;
}

/* The set of options for a manifest line (NULL args: the command line's). */
static int set_for(batch_t *B, const sw_cli_manifest_line_t *L, size_t *idx)
{
    char *key = NULL;
    if (L && L->nargs) {
        size_t len = 1;
        for (size_t i = 0; i < L->nargs; i++) len += strlen(L->args[i]) + 1;
        key = malloc(len);
        if (!key) {
            sw_cli_error("out of memory");
            return SW_EXIT_IO;
        }
        char *p = key;
        for (size_t i = 0; i < L->nargs; i++) {
            const size_t l = strlen(L->args[i]);
            memcpy(p, L->args[i], l);
            p[l] = '\x1f'; /* a unit separator: no option has one */
            p += l + 1;
        }
        *p = '\0';
    }
    for (size_t i = 0; i < B->nsets; i++)
        if ((!key && !B->sets[i].key) || (key && B->sets[i].key && !strcmp(key, B->sets[i].key))) {
            free(key);
            *idx = i;
            return SW_EXIT_OK;
        }
    optset_t *s = realloc(B->sets, (B->nsets + 1) * sizeof *s);
    if (!s) {
        free(key);
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    B->sets = s;
    optset_t *set = &B->sets[B->nsets++];
    memset(set, 0, sizeof *set);
    set->key = key;
    *idx = B->nsets - 1;
    return new_set(B, key ? L->args : NULL, key ? L->nargs : 0, L ? L->line : 0, set);
}

static int add_item(batch_t *B, const char *log, long line, size_t set, size_t cap)
{
    if (!strcmp(log, "-")) {
        if (line)
            sw_cli_error("%s:%ld: standard input cannot be a log of a batch", B->b.manifest, line);
        else
            sw_cli_error("batch: standard input cannot be a log of a batch");
        return SW_EXIT_USAGE;
    }
    if (B->n == cap)
        return SW_EXIT_IO;
    B->items[B->n++] = (item_t){log, line, set};
    return SW_EXIT_OK;
}

/* The logs: the operands, then the manifest's lines, each with its set of
 * options (made ready: scenes read). */
static int collect(batch_t *B)
{
    int rc;
    if (B->b.manifest) {
        if (B->world.rank == 0)
            rc = sw_cli_manifest_read(B->b.manifest, &B->mtext, &B->mlen);
        else
            rc = SW_EXIT_OK;
        /* standard input reaches rank 0 alone */
        if ((rc = sw_cli_world_share(&B->world, rc, &B->mtext, &B->mlen)) != SW_EXIT_OK)
            return rc;
        if ((rc = sw_cli_manifest_parse(B->b.manifest, B->mtext, B->mlen, &B->man)) != SW_EXIT_OK)
            return rc;
    }
    const size_t cap = (size_t)(B->argc - B->first) + B->man.n;
    if (cap == 0) {
        sw_cli_error("batch: no logs: give them as operands or in a --manifest");
        return SW_EXIT_USAGE;
    }
    B->items = calloc(cap, sizeof *B->items);
    if (!B->items) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    size_t set;
    for (int i = B->first; i < B->argc; i++)
        if ((rc = set_for(B, NULL, &set)) != SW_EXIT_OK ||
            (rc = add_item(B, B->argv[i], 0, set, cap)) != SW_EXIT_OK)
            return rc;
    for (size_t i = 0; i < B->man.n; i++) {
        const sw_cli_manifest_line_t *L = &B->man.v[i];
        if ((rc = set_for(B, L, &set)) != SW_EXIT_OK ||
            (rc = add_item(B, L->log, L->line, set, cap)) != SW_EXIT_OK)
            return rc;
    }
    return SW_EXIT_OK;
}

/* The logs' sizes: the longest go first.  A log that cannot be read costs
 * nothing; its job says why. */
static int costs(batch_t *B)
{
    B->cost = calloc(B->n, sizeof *B->cost);
    if (!B->cost) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    if (B->world.rank != 0)
        return SW_EXIT_OK; /* rank 0 hands out the work */
    for (size_t i = 0; i < B->n; i++) {
        struct stat st;
        if (stat(B->items[i].log, &st) == 0)
            B->cost[i] = (double)st.st_size;
    }
    return SW_EXIT_OK;
}

/* ---- outputs ---------------------------------------------------------------------- */

static int is_stdout(const char *path)
{
    return !path || !strcmp(path, "-");
}

static int check_outputs(const batch_t *B)
{
    if (B->b.csv && is_stdout(B->b.out) && is_stdout(B->b.csv)) {
        sw_cli_error("--csv -: standard output already carries the records (give --out a file)");
        return SW_EXIT_USAGE;
    }
    struct stat a, b;
    if (B->b.csv && !is_stdout(B->b.out) && !is_stdout(B->b.csv) &&
        (!strcmp(B->b.out, B->b.csv) || (stat(B->b.out, &a) == 0 && stat(B->b.csv, &b) == 0 &&
                                         a.st_dev == b.st_dev && a.st_ino == b.st_ino))) {
        sw_cli_error("--out and --csv name the same file '%s'", B->b.out);
        return SW_EXIT_USAGE;
    }
    /* an output that is an input would be truncated before it is read */
    const char *outs[2] = {is_stdout(B->b.out) ? NULL : B->b.out,
                           B->b.csv && !is_stdout(B->b.csv) ? B->b.csv : NULL};
    for (int k = 0; k < 2; k++) {
        if (!outs[k] || stat(outs[k], &a) != 0)
            continue;
        if (B->b.manifest && strcmp(B->b.manifest, "-") && stat(B->b.manifest, &b) == 0 &&
            a.st_dev == b.st_dev && a.st_ino == b.st_ino) {
            sw_cli_error("--%s %s: that is the manifest", k ? "csv" : "out", outs[k]);
            return SW_EXIT_USAGE;
        }
        for (size_t i = 0; i < B->n; i++)
            if (stat(B->items[i].log, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino) {
                sw_cli_error("--%s %s: that is a log of the batch", k ? "csv" : "out", outs[k]);
                return SW_EXIT_USAGE;
            }
    }
    return SW_EXIT_OK;
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
    fprintf(B->csv, "index,line,log,job,status,%s,messages\n", B->job->csv_header);
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
    if (rec.f && fclose(rec.f) != 0 && (rc == SW_EXIT_OK || rc == SW_EXIT_OVERTURNED)) {
        sw_cli_error("%s: out of memory", it->log);
        rc = SW_EXIT_IO;
    }
    const int good = rc == SW_EXIT_OK || rc == SW_EXIT_OVERTURNED;
    fprintf(out, "%d %ld\n", rc, good ? rec.n : 0L);
    if (good)
        fwrite(buf, 1, len, out);
    free(buf);
}

/* ---- the records, on rank 0, in order ----------------------------------------------- */

/* The messages as a JSON array and as one CSV field (joined by " | "),
 * each without the "swaywatch: " prefix. */
static void messages(FILE *jf, FILE *cf, const char *msgs, size_t mlen)
{
    char *joined = NULL;
    size_t jlen = 0;
    FILE *j = cf ? open_memstream(&joined, &jlen) : NULL;
    fputc('[', jf);
    const char *p = msgs, *end = msgs + mlen;
    for (int k = 0; p < end; k++) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        if (le - p >= 11 && !strncmp(p, "swaywatch: ", 11))
            p += 11;
        char *line = strndup(p, (size_t)(le - p));
        if (line) {
            if (k)
                fputs(", ", jf);
            sw_cli_json_string(jf, line);
            if (j)
                fprintf(j, "%s%s", k ? " | " : "", line);
            free(line);
        }
        p = nl ? nl + 1 : end;
    }
    fputc(']', jf);
    if (j && fclose(j) == 0) {
        fputc(',', cf);
        sw_cli_csv_text(cf, joined);
    } else if (cf) {
        fputc(',', cf);
    }
    free(joined);
}

/* What every record of log i begins with. */
static void head(const batch_t *B, size_t i, const char *status)
{
    const item_t *it = &B->items[i];
    fprintf(B->out, "{\"index\": %zu, \"line\": ", i + 1);
    if (it->line)
        fprintf(B->out, "%ld", it->line);
    else
        fputs("null", B->out);
    fputs(", \"log\": ", B->out);
    sw_cli_json_string(B->out, it->log);
    fputs(", \"job\": ", B->out);
    sw_cli_json_string(B->out, B->job->name);
    fprintf(B->out, ", \"status\": \"%s\"", status);
    if (!B->csv)
        return;
    fprintf(B->csv, "%zu,", i + 1);
    if (it->line)
        fprintf(B->csv, "%ld", it->line);
    fputc(',', B->csv);
    sw_cli_csv_text(B->csv, it->log);
    fprintf(B->csv, ",%s,%s", B->job->name, status);
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
    if (!B->b.quiet && mlen)
        fwrite(msgs, 1, mlen, stderr);
    if (good) {
        B->ok++;
        B->overturned |= rc == SW_EXIT_OVERTURNED;
        for (long k = 0; k < npkg && p < end; k++) {
            size_t jl = 0, cl = 0;
            if (sscanf(p, "%zu %zu", &jl, &cl) != 2)
                break;
            const char *nl = memchr(p, '\n', (size_t)(end - p));
            if (!nl || (size_t)(end - nl - 1) < jl + cl)
                break;
            p = nl + 1;
            head(B, i, "ok");
            fputs(", ", B->out);
            fwrite(p, 1, jl, B->out);
            fputs(", \"messages\": ", B->out);
            if (B->csv) {
                fputc(',', B->csv);
                fwrite(p + jl, 1, cl, B->csv);
            }
            messages(B->out, B->csv, msgs, mlen);
            fputs("}\n", B->out);
            if (B->csv)
                fputc('\n', B->csv);
            p += jl + cl;
            B->records++;
        }
    } else {
        B->failed++;
        head(B, i, "error");
        fprintf(B->out, ", \"exit\": %d, \"messages\": ", rc);
        if (B->csv)
            for (size_t k = 0; k < B->csv_fields; k++) fputc(',', B->csv);
        messages(B->out, B->csv, msgs, mlen);
        fputs("}\n", B->out);
        if (B->csv)
            fputc('\n', B->csv);
        B->records++;
    }
    if (ferror(B->out) || (B->csv && ferror(B->csv))) {
        sw_cli_error(
            "%s: write failed: %s",
            ferror(B->out) ? sw_cli_out_name(B->b.out ? B->b.out : "-") : sw_cli_out_name(B->b.csv),
            strerror(errno));
        B->write_failed = 1;
        return -1;
    }
    return 0;
}

/* ---- the command -------------------------------------------------------------------- */

static int run_batch(batch_t *B)
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
    };
    rc = sw_cli_farm_run(&farm);
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
    B.g[B.ng++] = (sw_cli_group_t)SW_CLI_GROUP(batch_options, &B.b);
    B.ng += B.job->groups(opts, B.g + B.ng);
    rc = sw_cli_parse(&batch_cmd, B.g, B.ng, argc, argv, &B.first);
    B.job->destroy(opts); /* a check of the options; each set parses them again */
    opts = NULL;
    sw_cli_parse_free(B.g, 1);
    B.ng = 0;
    if (rc != SW_CLI_CONTINUE)
        goto setup_done;
    B.job = B.b.job;
    B.csv_fields = 1;
    for (const char *c = B.job->csv_header; *c; c++) B.csv_fields += *c == ',';
    if ((rc = collect(&B)) == SW_EXIT_OK)
        rc = costs(&B);

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
        rc = run_batch(&B);
    free_batch(&B);
    return sw_cli_world_end(&B.world, rc);
}
