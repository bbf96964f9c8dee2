/* input.c - CSV input options, log files read in chunks (the pump that
 * feeds the CSV reader, the source told by the first bytes), and reading a
 * whole CSV log into memory, for the commands that run one log many times
 * (forensics: one replay per trial of the safety-factor search).  replay
 * itself streams the log and never holds it.
 *
 * Memory: 16 bytes per accepted row (24 with a vertical column); a 1 kHz
 * log of one hour is about 58 MB. */
#include "input.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eventlog.h"

#define CHUNK (64 * 1024)      /* bytes read and fed at a time */

void sw_cli_csv_opts_init(sw_cli_csv_opts_t *o)
{
    memset(o, 0, sizeof *o);
    o->csv.header = -1;
}

/* The value of a text option, one of a few names: dest gets the value of
 * the name, or the message names the choices. */
static int parse_delim(const sw_cli_option_t *o, const char *arg, void *dest)
{
    char *out = dest;
    if (!strcmp(arg, ",") || !strcmp(arg, "comma"))
        *out = ',';
    else if (!strcmp(arg, ";") || !strcmp(arg, "semicolon"))
        *out = ';';
    else if (!strcmp(arg, "tab") || !strcmp(arg, "\t") || !strcmp(arg, "\\t"))
        *out = '\t';
    else {
        sw_cli_error("--%s: expected ',', ';' or tab, got '%s'", o->long_name, arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

int sw_cli_accel_unit(const sw_cli_option_t *o, const char *arg, void *dest)
{
    double *scale = dest;
    if (!strcmp(arg, "m/s2") || !strcmp(arg, "m/s^2") || !strcmp(arg, "mps2"))
        *scale = 1.0;
    else if (!strcmp(arg, "g"))
        *scale = 9.80665;
    else {
        sw_cli_error("--%s: expected m/s2 or g, got '%s'", o->long_name, arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

static int parse_time_unit(const sw_cli_option_t *o, const char *arg, void *dest)
{
    double *scale = dest;
    if (!strcmp(arg, "s"))
        *scale = 1.0;
    else if (!strcmp(arg, "ms"))
        *scale = 1e-3;
    else if (!strcmp(arg, "us"))
        *scale = 1e-6;
    else {
        sw_cli_error("--%s: expected s, ms or us, got '%s'", o->long_name, arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* Column choice: a header name or a 1-based index; "0" is neither. */
static int check_col(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    char *end = NULL;
    long v = strtol(arg, &end, 10);
    if (*arg == '\0' || (end != arg && *end == '\0' && v < 1)) {
        sw_cli_error("--%s: expected a column name or a 1-based index, got '%s'", o->long_name,
                     arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

#define CSV(f) SW_CLI_AT(sw_cli_csv_opts_t, f)
#define CSV_SECTION                                                                                \
    "CSV input (default: column 1 time in s, column 2 longitudinal acceleration in\n"             \
    "m/s^2, x forward: braking is negative; optional header row; '#' comments):"

const sw_cli_option_t sw_cli_csv_options[] = {
    {SW_CLI_SECTION, .help = CSV_SECTION},
    {SW_CLI_STRING, 0, "time-col", "NAME|N", CSV(csv.time_col), .fn = check_col,
     .help = "time column, by header name or 1-based index (default 1)"},
    {SW_CLI_STRING, 0, "accel-col", "NAME|N", CSV(csv.accel_col), .fn = check_col,
     .help = "longitudinal acceleration column (default 2)"},
    {SW_CLI_STRING, 0, "vert-col", "NAME|N", CSV(csv.vert_col), .fn = check_col,
     .help = "vertical acceleration column, up positive, same unit as --accel-unit (default: "
             "none, gravity only)"},
    {SW_CLI_CALL, 0, "delimiter", "D", CSV(csv.delim), .fn = parse_delim,
     .help = "',', ';' or tab (default: detected from the first line)"},
    {SW_CLI_FLAG, 0, "header", CSV(csv.header), .value = 1,
     .help = "the first row is a header (default: detected)"},
    {SW_CLI_FLAG, 0, "no-header", CSV(csv.header), .value = 0, .help = "the first row is data"},
    {SW_CLI_CALL, 0, "time-unit", "U", CSV(csv.time_scale), .fn = parse_time_unit,
     .help = "s, ms or us (default s)"},
    {SW_CLI_END},
};

const sw_cli_option_t sw_cli_sample_options[] = {
    {SW_CLI_SECTION, .help = CSV_SECTION},
    {SW_CLI_CALL, 0, "accel-unit", "U", CSV(csv.accel_scale), .fn = sw_cli_accel_unit,
     .help = "m/s2 or g, 1 g = 9.80665 m/s^2 (default m/s2)"},
    {SW_CLI_FLAG, 0, "flip", CSV(csv.flip), .value = 1,
     .help = "negate the longitudinal axis (logger mounted backwards)"},
    {SW_CLI_FLAG, 0, "strict", CSV(strict), .value = 1,
     .help = "stop at the first rejected row, exit 2"},
    {SW_CLI_TEXT,
     .help = "Rows that cannot be used (missing field, not a number, not finite, time not\n"
             "increasing) are counted and reported on stderr with their line number (the first\n"
             SW_CLI_STR(SW_CLI_MAX_PRINTED_REJECTS) " one by one); the run goes on without them "
             "unless --strict.\n"
             "With --quiet, they are only counted (one line on stderr)."},
    {SW_CLI_END},
};

/* ---- rejected rows, log files ------------------------------------------------- */

void sw_cli_rejects_add(sw_cli_rejects_t *r, long line, const char *reason)
{
    if (r->stop) return; /* strict: the run already ended at an earlier row */
    r->reported++;
    if (r->strict) r->stop = 1;
    if (r->quiet || r->printed >= SW_CLI_MAX_PRINTED_REJECTS) return;
    r->printed++;
    sw_cli_error("%s:%ld: %s", r->name, line, reason);
}

void sw_cli_rejects_summary(const sw_cli_rejects_t *r)
{
    if (r->reported <= r->printed) return;
    if (r->quiet)
        sw_cli_error("%s: %ld rejected rows", r->name, r->reported);
    else
        sw_cli_error("%s: ... %ld more rejected rows", r->name, r->reported - r->printed);
}

int sw_cli_logfile_open(sw_cli_logfile_t *f, const char *path)
{
    memset(f, 0, sizeof *f);
    f->name = strcmp(path, "-") ? path : "(stdin)";
    f->in = strcmp(path, "-") ? fopen(path, "rb") : stdin;
    if (!f->in) {
        sw_cli_error("%s: cannot open: %s", path, strerror(errno));
        return SW_EXIT_IO;
    }
    f->buf = malloc(CHUNK);
    if (!f->buf) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    f->len = fread(f->buf, 1, CHUNK, f->in);
    if (ferror(f->in)) {
        sw_cli_error("%s: cannot read: %s", f->name, strerror(errno));
        return SW_EXIT_IO;
    }
    return SW_EXIT_OK;
}

int sw_cli_logfile_pump(sw_cli_logfile_t *f, sw_csv_t *csv, const int *stop,
                        void (*after)(void *), void *user, int *fr)
{
    *fr = SW_OK;
    while (f->len > 0 && !*stop) {
        *fr = sw_csv_feed(csv, f->buf, f->len);
        if (after) after(user);
        if (*fr < 0) return SW_EXIT_OK;
        f->len = fread(f->buf, 1, CHUNK, f->in);
        if (ferror(f->in)) {
            sw_cli_error("%s: cannot read: %s", f->name, strerror(errno));
            return SW_EXIT_IO;
        }
    }
    if (!*stop) {
        *fr = sw_csv_finish(csv);
        if (after) after(user);
    }
    return SW_EXIT_OK;
}

void sw_cli_logfile_close(sw_cli_logfile_t *f)
{
    free(f->buf);
    if (f->in && f->in != stdin) fclose(f->in);
    memset(f, 0, sizeof *f);
}

static const sw_cli_source_t sources[] = {
#ifdef SW_HAVE_LCM
    {SW_CLI_SRC_LCMLOG, "an lcm-logger file", sw_lcmlog_sniff, 1},
#else
    {SW_CLI_SRC_LCMLOG, "an lcm-logger file", sw_lcmlog_sniff, 0},
#endif
    {SW_CLI_SRC_CSV, "a CSV log", NULL, 1},
};

const sw_cli_source_t *sw_cli_logfile_source(const sw_cli_logfile_t *f)
{
    const size_t n = sizeof sources / sizeof sources[0];
    size_t i = 0;
    while (i + 1 < n && !sources[i].sniff(f->buf, f->len)) i++;
    return &sources[i];
}

/* ---- reading ------------------------------------------------------------------ */

typedef struct {
    sw_cli_log_t *log;
    sw_cli_rejects_t rej;
    int halt; /* rej.stop, out of memory, or the cap reached */
    int oom;
    size_t max; /* samples kept at most */
    int capped; /* one more was offered */
} read_ctx_t;

static int grow(sw_cli_log_t *L, size_t max)
{
    size_t cap = L->cap ? 2 * L->cap : 4096;
    if (cap > max) cap = max;
    double *t = realloc(L->t, cap * sizeof *t);
    if (!t) return -1;
    L->t = t;
    double *a = realloc(L->a_g, cap * sizeof *a);
    if (!a) return -1;
    L->a_g = a;
    if (L->has_z) {
        double *z = realloc(L->a_z, cap * sizeof *z);
        if (!z) return -1;
        L->a_z = z;
    }
    L->cap = cap;
    return 0;
}

static int on_row(void *user, long line, double t, double a_g, double a_z)
{
    read_ctx_t *c = user;
    sw_cli_log_t *L = c->log;
    (void)line;
    if (c->halt) return 1;
    if (L->n == c->max) {
        c->capped = c->halt = 1;
        return 1;
    }
    if (L->n == L->cap && grow(L, c->max) != 0) {
        c->oom = c->halt = 1;
        return 1;
    }
    L->t[L->n] = t;
    L->a_g[L->n] = a_g;
    if (L->has_z) L->a_z[L->n] = a_z;
    L->n++;
    return 0;
}

static void on_reject(void *user, long line, const char *reason)
{
    read_ctx_t *c = user;
    if (c->oom || c->capped) return;
    sw_cli_rejects_add(&c->rej, line, reason);
    c->halt = c->rej.stop;
}

int sw_cli_log_read(const char *path, const sw_cli_csv_opts_t *o, int quiet, long max,
                    sw_cli_log_t *L)
{
    int rc = SW_EXIT_USAGE;
    memset(L, 0, sizeof *L);
    L->has_z = o->csv.vert_col != NULL;
    sw_csv_t *csv = NULL;
    sw_cli_logfile_t f;
    if (sw_cli_logfile_open(&f, path) != SW_EXIT_OK) {
        rc = SW_EXIT_IO;
        goto out;
    }
    read_ctx_t ctx = {L, {f.name, o->strict, quiet, 0, 0, 0}, 0, 0, max > 0 ? (size_t)max : 1, 0};
    if (sw_cli_logfile_source(&f)->kind != SW_CLI_SRC_CSV) {
        sw_cli_error("%s: an lcm-logger file; this command reads CSV logs (replay reads both)",
                     f.name);
        goto out;
    }
    int err = 0;
    char msg[256] = "";
    csv = sw_csv_create(&o->csv, on_row, on_reject, &ctx, &err, msg, sizeof msg);
    if (!csv) {
        sw_cli_error("%s: %s", f.name, msg[0] ? msg : sw_strerror(err));
        goto out;
    }
    int fr;
    if (sw_cli_logfile_pump(&f, csv, &ctx.halt, NULL, NULL, &fr) != SW_EXIT_OK) {
        rc = SW_EXIT_IO;
        goto out;
    }
    if (ctx.oom) {
        sw_cli_error("%s: out of memory after %zu samples", f.name, L->n);
        rc = SW_EXIT_IO;
        goto out;
    }
    if (ctx.capped) {
        sw_cli_error("%s: more than %ld samples: the whole log is held in memory (%zu bytes a "
                     "sample) and %ld is the cap (--max-samples); cut the log, or replay it "
                     "(replay streams)",
                     f.name, max, L->has_z ? 3 * sizeof(double) : 2 * sizeof(double), max);
        goto out;
    }
    if (fr < 0) {
        const char *why = sw_csv_error_message(csv);
        sw_cli_error("%s: %s", f.name, why && why[0] ? why : sw_strerror(fr));
        rc = fr == SW_ENOMEM ? SW_EXIT_IO : SW_EXIT_USAGE;
        goto out;
    }
    if (ctx.rej.stop) {
        sw_cli_error("%s: stopped at the first rejected row (--strict)", f.name);
        goto out;
    }
    sw_csv_counts_t counts;
    sw_csv_counts(csv, &counts);
    L->rows = counts.rows;
    L->rejected = counts.rejected;
    sw_cli_rejects_summary(&ctx.rej);
    if (L->n == 0) {
        sw_cli_error("%s: no usable samples (%ld data rows, %ld rejected)", f.name, counts.rows,
                     counts.rejected);
        goto out;
    }
    rc = SW_EXIT_OK;
out:
    sw_csv_destroy(csv);
    sw_cli_logfile_close(&f);
    if (rc != SW_EXIT_OK) sw_cli_log_free(L);
    return rc;
}

void sw_cli_log_free(sw_cli_log_t *L)
{
    free(L->t);
    free(L->a_g);
    free(L->a_z);
    memset(L, 0, sizeof *L);
}
