/* logread.c - CSV input options (the ones replay documents) and reading a
 * whole CSV log into memory, for the commands that run one log many times
 * (forensics: one replay per trial of the safety-factor search).  replay
 * itself streams the log and never holds it.
 *
 * Memory: 16 bytes per accepted row (24 with a vertical column); a 1 kHz
 * log of one hour is about 58 MB. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#define CHUNK (64 * 1024)      /* bytes read and fed at a time */
#define MAX_PRINTED_REJECTS 20 /* rejected rows listed one by one; the rest only counted */

void sw_cli_csv_opts_init(sw_cli_csv_opts_t *o)
{
    memset(o, 0, sizeof *o);
    o->csv.header = -1;
}

void sw_cli_print_csv_help(FILE *f)
{
    fprintf(f,
            "CSV input (default: column 1 time in s, column 2 longitudinal acceleration in\n"
            "m/s^2, x forward: braking is negative; optional header row; '#' comments):\n"
            "      --time-col NAME|N    time column, by header name or 1-based index (default 1)\n"
            "      --accel-col NAME|N   longitudinal acceleration column (default 2)\n"
            "      --vert-col NAME|N    vertical acceleration column, up positive, same unit as\n"
            "                           --accel-unit (default: none, gravity only)\n"
            "      --delimiter D        ',', ';' or tab (default: detected from the first line)\n"
            "      --header             the first row is a header (default: detected)\n"
            "      --no-header          the first row is data\n"
            "      --accel-unit U       m/s2 or g, 1 g = 9.80665 m/s^2 (default m/s2)\n"
            "      --time-unit U        s, ms or us (default s)\n"
            "      --flip               negate the longitudinal axis (logger mounted backwards)\n"
            "      --strict             stop at the first rejected row, exit 2\n"
            "Rows that cannot be used (missing field, not a number, not finite, time not\n"
            "increasing) are counted and reported on stderr with their line number (the first\n"
            "%d one by one); the run goes on without them unless --strict.\n",
            MAX_PRINTED_REJECTS);
}

static int parse_delim(const char *arg, char *out)
{
    if (!strcmp(arg, ",") || !strcmp(arg, "comma"))
        *out = ',';
    else if (!strcmp(arg, ";") || !strcmp(arg, "semicolon"))
        *out = ';';
    else if (!strcmp(arg, "tab") || !strcmp(arg, "\t") || !strcmp(arg, "\\t"))
        *out = '\t';
    else {
        sw_cli_error("--delimiter: expected ',', ';' or tab, got '%s'", arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

int sw_cli_parse_accel_unit(const char *arg, double *scale)
{
    if (!strcmp(arg, "m/s2") || !strcmp(arg, "m/s^2") || !strcmp(arg, "mps2"))
        *scale = 1.0;
    else if (!strcmp(arg, "g"))
        *scale = 9.80665;
    else {
        sw_cli_error("--accel-unit: expected m/s2 or g, got '%s'", arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

static int parse_time_unit(const char *arg, double *scale)
{
    if (!strcmp(arg, "s"))
        *scale = 1.0;
    else if (!strcmp(arg, "ms"))
        *scale = 1e-3;
    else if (!strcmp(arg, "us"))
        *scale = 1e-6;
    else {
        sw_cli_error("--time-unit: expected s, ms or us, got '%s'", arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* Column choice: a header name or a 1-based index; "0" is neither. */
static int check_col(const char *opt, const char *arg)
{
    char *end = NULL;
    long v = strtol(arg, &end, 10);
    if (*arg == '\0' || (end != arg && *end == '\0' && v < 1)) {
        sw_cli_error("%s: expected a column name or a 1-based index, got '%s'", opt, arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

int sw_cli_csv_option(sw_cli_csv_opts_t *o, int c, const char *arg)
{
    switch (c) {
    case SW_OPT_CSV_TIME_COL: o->csv.time_col = arg; return check_col("--time-col", arg);
    case SW_OPT_CSV_ACCEL_COL: o->csv.accel_col = arg; return check_col("--accel-col", arg);
    case SW_OPT_CSV_VERT_COL: o->csv.vert_col = arg; return check_col("--vert-col", arg);
    case SW_OPT_CSV_DELIM: return parse_delim(arg, &o->csv.delim);
    case SW_OPT_CSV_HEADER: o->csv.header = 1; return SW_EXIT_OK;
    case SW_OPT_CSV_NO_HEADER: o->csv.header = 0; return SW_EXIT_OK;
    case SW_OPT_CSV_ACCEL_UNIT: return sw_cli_parse_accel_unit(arg, &o->csv.accel_scale);
    case SW_OPT_CSV_TIME_UNIT: return parse_time_unit(arg, &o->csv.time_scale);
    case SW_OPT_CSV_FLIP: o->csv.flip = 1; return SW_EXIT_OK;
    case SW_OPT_CSV_STRICT: o->strict = 1; return SW_EXIT_OK;
    default: return -1;
    }
}

/* ---- reading ------------------------------------------------------------------ */

typedef struct {
    sw_cli_log_t *log;
    const char *name;
    int strict, quiet, stop, oom;
    long reported, printed;
} read_ctx_t;

static int grow(sw_cli_log_t *L)
{
    size_t cap = L->cap ? 2 * L->cap : 4096;
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

static void report_reject(read_ctx_t *c, long line, const char *reason)
{
    c->reported++;
    if (c->strict) c->stop = 1;
    if (c->quiet || c->printed >= MAX_PRINTED_REJECTS) return;
    c->printed++;
    sw_cli_error("%s:%ld: %s", c->name, line, reason);
}

static int on_row(void *user, long line, double t, double a_g, double a_z)
{
    read_ctx_t *c = user;
    sw_cli_log_t *L = c->log;
    (void)line;
    if (c->stop || c->oom) return 1;
    if (L->n == L->cap && grow(L) != 0) {
        c->oom = 1;
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
    if (c->oom) return;
    report_reject(c, line, reason);
}

int sw_cli_log_read(const char *path, const sw_cli_csv_opts_t *o, int quiet, sw_cli_log_t *L)
{
    int rc = SW_EXIT_USAGE;
    memset(L, 0, sizeof *L);
    L->has_z = o->csv.vert_col != NULL;
    read_ctx_t ctx = {L, strcmp(path, "-") ? path : "(stdin)", o->strict, quiet, 0, 0, 0, 0};
    FILE *in = strcmp(path, "-") ? fopen(path, "rb") : stdin;
    char *buf = NULL;
    sw_csv_t *csv = NULL;
    if (!in) {
        sw_cli_error("%s: cannot open: %s", path, strerror(errno));
        return SW_EXIT_IO;
    }
    buf = malloc(CHUNK);
    if (!buf) {
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
        goto out;
    }
    size_t len = fread(buf, 1, CHUNK, in);
    if (ferror(in)) {
        sw_cli_error("%s: cannot read: %s", ctx.name, strerror(errno));
        rc = SW_EXIT_IO;
        goto out;
    }
    if (sw_cli_is_lcmlog(buf, len)) {
        sw_cli_error("%s: an lcm-logger file; this command reads CSV logs (replay reads both)",
                     ctx.name);
        goto out;
    }
    int err = 0;
    char msg[256] = "";
    csv = sw_csv_create(&o->csv, on_row, on_reject, &ctx, &err, msg, sizeof msg);
    if (!csv) {
        sw_cli_error("%s: %s", ctx.name, msg[0] ? msg : sw_strerror(err));
        goto out;
    }
    int fr = SW_OK;
    while (len > 0 && !ctx.stop && !ctx.oom) {
        fr = sw_csv_feed(csv, buf, len);
        if (fr < 0) break;
        len = fread(buf, 1, CHUNK, in);
        if (ferror(in)) {
            sw_cli_error("%s: cannot read: %s", ctx.name, strerror(errno));
            rc = SW_EXIT_IO;
            goto out;
        }
    }
    if (fr >= 0 && !ctx.stop && !ctx.oom) fr = sw_csv_finish(csv);
    if (ctx.oom) {
        sw_cli_error("%s: out of memory after %zu samples", ctx.name, L->n);
        rc = SW_EXIT_IO;
        goto out;
    }
    if (fr < 0) {
        const char *why = sw_csv_error_message(csv);
        sw_cli_error("%s: %s", ctx.name, why && why[0] ? why : sw_strerror(fr));
        rc = fr == SW_ENOMEM ? SW_EXIT_IO : SW_EXIT_USAGE;
        goto out;
    }
    if (ctx.stop) {
        sw_cli_error("%s: stopped at the first rejected row (--strict)", ctx.name);
        goto out;
    }
    sw_csv_counts_t counts;
    sw_csv_counts(csv, &counts);
    L->rows = counts.rows;
    L->rejected = counts.rejected;
    if (ctx.reported > ctx.printed) {
        if (quiet)
            sw_cli_error("%s: %ld rejected rows", ctx.name, ctx.reported);
        else
            sw_cli_error("%s: ... %ld more rejected rows", ctx.name, ctx.reported - ctx.printed);
    }
    if (L->n == 0) {
        sw_cli_error("%s: no usable samples (%ld data rows, %ld rejected)", ctx.name, counts.rows,
                     counts.rejected);
        goto out;
    }
    rc = SW_EXIT_OK;
out:
    sw_csv_destroy(csv);
    free(buf);
    if (in && in != stdin) fclose(in);
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
