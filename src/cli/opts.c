/* SPDX-License-Identifier: GPL-3.0-or-later */
/* opts.c - options from one table (opts.h): the parser over getopt_long,
 * the --help generated from the rows, the number and list parsers.
 *
 * Everything here prints its own messages ("swaywatch: ..." on stderr) and
 * returns an exit code, so a command is a short sequence of calls with one
 * cleanup path. */
#include "opts.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* --help: lines of at most HELP_WIDTH columns; the help of the options
 * starts in one column per command, past the longest option (at most
 * HELP_COLUMN: a longer option has its help on the next line). */
#define HELP_WIDTH 80
#define HELP_COLUMN 30

/* getopt_long codes of the rows: ROW_CODE + the row's index over all the
 * groups, beyond the characters of the short options. */
#define ROW_CODE 256

/* ---- numbers ---------------------------------------------------------- */

static int bad_value(const sw_cli_option_t *o, const char *arg)
{
    sw_cli_error("--%s: expected %s, got '%s'", o->long_name, o->what, arg ? arg : "");
    return SW_EXIT_USAGE;
}

int sw_cli_opt_double(const sw_cli_option_t *o, const char *arg, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = arg ? strtod(arg, &end) : NAN;
    int ok = arg && end != arg && *end == '\0' && errno != ERANGE && isfinite(v);
    if (ok && o->rule == SW_NUM_POSITIVE)
        ok = v > 0.0;
    if (ok && o->rule == SW_NUM_NONNEGATIVE)
        ok = v >= 0.0;
    if (ok && o->rule == SW_NUM_NONZERO)
        ok = v != 0.0;
    if (!ok)
        return bad_value(o, arg);
    if (sw_cli_opt_range(o, arg, v) != SW_EXIT_OK)
        return SW_EXIT_USAGE;
    *out = v;
    return SW_EXIT_OK;
}

static int has_range(const sw_cli_option_t *o)
{
    return o->hi > o->lo;
}

/* "1e-07 to 1", "0, or 0.001 to 1e+06": the bounds as --help and the
 * refusals say them. */
static void range_text(char *buf, size_t len, const sw_cli_option_t *o)
{
    const int off = o->rule == SW_NUM_NONNEGATIVE && o->lo > 0.0;
    snprintf(buf, len, "%s%g to %g%s", off ? "0, or " : "", o->lo, o->hi,
             o->rule == SW_NUM_NONZERO ? " in magnitude" : "");
}

int sw_cli_opt_range(const sw_cli_option_t *o, const char *arg, double v)
{
    if (!has_range(o) || (v == 0.0 && o->rule == SW_NUM_NONNEGATIVE))
        return SW_EXIT_OK;
    const double m = o->rule == SW_NUM_NONZERO ? fabs(v) : v;
    if (m >= o->lo && m <= o->hi)
        return SW_EXIT_OK;
    char r[96];
    range_text(r, sizeof r, o);
    sw_cli_error("--%s: out of range: expected %s, got '%s'", o->long_name, r, arg ? arg : "");
    return SW_EXIT_USAGE;
}

int sw_cli_opt_long(const sw_cli_option_t *o, const char *arg, long *out)
{
    char *end = NULL;
    errno = 0;
    long v = arg ? strtol(arg, &end, 10) : 0;
    if (!arg || end == arg || *end != '\0' || errno == ERANGE || v < o->min)
        return bad_value(o, arg);
    if (o->max > 0 && v > o->max) {
        /* A thread count is capped: the results do not depend on it.
         * Anything else above its bound is refused, never quietly cut. */
        if (!(o->flags & SW_CLI_CAP)) {
            sw_cli_error("--%s: out of range: expected %ld to %ld, got '%s'", o->long_name, o->min,
                         o->max, arg);
            return SW_EXIT_USAGE;
        }
        v = o->max;
    }
    *out = v;
    return SW_EXIT_OK;
}

const char *sw_cli_units_accepted(int time_role)
{
    return time_role ? "ms, s or us, e.g. 11ms or 0.011s"
                     : "g or m/s2 (m/s^2, m/s\xc2\xb2, mps2), e.g. 10g or 98.1m/s2";
}

int sw_cli_opt_quantity(const sw_cli_option_t *o, const char *arg, int time_role, int bare_ok,
                        double *si, int *unit)
{
    char *end = NULL;
    errno = 0;
    const double v = arg ? strtod(arg, &end) : NAN;
    if (!arg || end == arg || errno == ERANGE || !isfinite(v))
        return bad_value(o, arg);
    while (*end == ' ') end++;
    int u = SW_CSV_UNIT_NONE;
    if (*end) {
        u = sw_csv_unit_parse(end, time_role);
        if (u == SW_CSV_UNIT_NONE) {
            sw_cli_error("--%s: unknown unit '%s' in '%s': expected %s", o->long_name, end, arg,
                         sw_cli_units_accepted(time_role));
            return SW_EXIT_USAGE;
        }
    } else if (!bare_ok) {
        sw_cli_error("--%s: '%s' has no unit: expected %s", o->long_name, arg,
                     sw_cli_units_accepted(time_role));
        return SW_EXIT_USAGE;
    }
    int ok = 1;
    if (o->rule == SW_NUM_POSITIVE)
        ok = v > 0.0;
    if (o->rule == SW_NUM_NONNEGATIVE)
        ok = v >= 0.0;
    if (o->rule == SW_NUM_NONZERO)
        ok = v != 0.0;
    if (!ok)
        return bad_value(o, arg);
    if (sw_cli_opt_range(o, arg, v * sw_csv_unit_scale(u)) != SW_EXIT_OK)
        return SW_EXIT_USAGE;
    *si = v * sw_csv_unit_scale(u);
    if (unit)
        *unit = u;
    return SW_EXIT_OK;
}

/* "1/3" or a decimal number. */
static int parse_fraction(const char *s, double *out)
{
    char *end = NULL;
    double a = strtod(s, &end);
    if (end == s)
        return -1;
    if (*end == '/') {
        const char *q = end + 1;
        double b = strtod(q, &end);
        if (end == q || b == 0.0)
            return -1;
        a /= b;
    }
    if (*end != '\0' || !isfinite(a))
        return -1;
    *out = a;
    return 0;
}

int sw_cli_parse_list(const char *opt, const char *arg, int positive, double **vals, size_t *n)
{
    size_t cap = 1;
    for (const char *p = arg; *p; p++) cap += *p == ',';
    double *v = calloc(cap, sizeof *v);
    char *copy = strdup(arg);
    if (!v || !copy) {
        free(v);
        free(copy);
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    size_t k = 0;
    for (char *tok = copy, *next; tok; tok = next) {
        next = strchr(tok, ',');
        if (next)
            *next++ = '\0'; /* an empty item ("1,,2") is an error, not skipped */
        double x;
        if (parse_fraction(tok, &x) != 0 || (positive && !(x > 0.0))) {
            sw_cli_error("%s: expected %snumbers separated by commas, got '%s'", opt,
                         positive ? "positive " : "", tok);
            free(v);
            free(copy);
            return SW_EXIT_USAGE;
        }
        v[k++] = x;
    }
    free(copy);
    if (k == 0) {
        sw_cli_error("%s: expected at least one value, got '%s'", opt, arg);
        free(v);
        return SW_EXIT_USAGE;
    }
    *vals = v;
    *n = k;
    return SW_EXIT_OK;
}

int sw_cli_parse_range(const char *opt, const char *arg, size_t max, double **vals, size_t *n)
{
    if (!strchr(arg, ':'))
        return sw_cli_parse_list(opt, arg, 1, vals, n);
    double a, b, s;
    char tail;
    if (sscanf(arg, "%lf:%lf:%lf%c", &a, &b, &s, &tail) != 3 || !isfinite(a) || !isfinite(b) ||
        !isfinite(s) || !(a > 0.0) || !(b >= a) || !(s > 0.0)) {
        sw_cli_error("%s: expected FROM:TO:STEP with 0 < FROM <= TO and STEP > 0, got '%s'", opt,
                     arg);
        return SW_EXIT_USAGE;
    }
    const double count = floor((b - a) / s * (1.0 + 1e-12) + 1e-9) + 1.0;
    if (count > (double)max) {
        sw_cli_error("%s: '%s' gives %.0f points, more than %zu", opt, arg, count, max);
        return SW_EXIT_USAGE;
    }
    double *v = calloc((size_t)count, sizeof *v);
    if (!v) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    for (size_t i = 0; i < (size_t)count; i++) v[i] = a + (double)i * s;
    *vals = v;
    *n = (size_t)count;
    return SW_EXIT_OK;
}

/* ---- parsing ------------------------------------------------------------ */

/* Every option row of the groups, flattened: its getopt_long code is
 * ROW_CODE + its index here. */
typedef struct {
    const sw_cli_option_t *o;
    sw_cli_group_t *g;
} row_t;

static int is_option(const sw_cli_option_t *o)
{
    return o->kind != SW_CLI_SECTION && o->kind != SW_CLI_TEXT;
}

static void *dest_of(const row_t *r)
{
    return (char *)r->g->base + r->o->offset;
}

static int list_append(sw_cli_list_t *l, const char *arg)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 8;
        const char **v = realloc(l->v, cap * sizeof *v);
        if (!v) {
            sw_cli_error("out of memory");
            return SW_EXIT_IO;
        }
        l->v = v;
        l->cap = cap;
    }
    l->v[l->n++] = arg;
    return SW_EXIT_OK;
}

/* Read one option's value into its destination. */
static int take(const row_t *r, const char *arg)
{
    const sw_cli_option_t *o = r->o;
    void *dest = dest_of(r);
    int rc = SW_EXIT_OK;
    switch (o->kind) {
        case SW_CLI_FLAG: *(int *)dest = o->value; break;
        case SW_CLI_STRING:
            if (o->fn)
                rc = o->fn(o, arg, dest);
            if (rc == SW_EXIT_OK)
                *(const char **)dest = arg;
            break;
        case SW_CLI_LIST:
            if (o->fn)
                rc = o->fn(o, arg, dest);
            if (rc == SW_EXIT_OK)
                rc = list_append(dest, arg);
            break;
        case SW_CLI_DOUBLE:
            rc = sw_cli_opt_double(o, arg, dest);
            if (rc == SW_EXIT_OK && o->fn)
                rc = o->fn(o, arg, dest);
            break;
        case SW_CLI_LONG:
            rc = sw_cli_opt_long(o, arg, dest);
            if (rc == SW_EXIT_OK && o->fn)
                rc = o->fn(o, arg, dest);
            break;
        case SW_CLI_CALL: rc = o->fn(o, arg, dest); break;
        default: break;
    }
    return rc;
}

/* getopt_long's complaints, worded as ours; argv[optind - 1] is the option
 * it was reading. */
static int misuse(int c, char **argv)
{
    if (c == ':') {
        sw_cli_error("%s: option '%s' needs a value", argv[0], argv[optind - 1]);
    } else if (optopt > 0 && optopt < ROW_CODE) {
        sw_cli_error("%s: unknown option '-%c'; see 'swaywatch %s --help'", argv[0], optopt,
                     argv[0]);
    } else if (optopt >= ROW_CODE) { /* a known long option given a value it does not take */
        const char *opt = argv[optind - 1];
        const char *eq = strchr(opt, '=');
        sw_cli_error("%s: option '%.*s' takes no value", argv[0],
                     (int)(eq ? eq - opt : (long)strlen(opt)), opt);
    } else {
        sw_cli_error("%s: unknown option '%s'; see 'swaywatch %s --help'", argv[0],
                     argv[optind - 1], argv[0]);
    }
    return SW_EXIT_USAGE;
}

/* The rows, getopt_long's table and its short options (leading ':' so a
 * missing value is reported by us, with our prefix). */
typedef struct {
    row_t *rows;
    struct option *longopts;
    char *shortopts;
    size_t n;
} table_t;

static int build_table(table_t *t, sw_cli_group_t *g, size_t n)
{
    size_t count = 0;
    for (size_t i = 0; i < n; i++)
        for (const sw_cli_option_t *o = g[i].rows; o->kind != SW_CLI_END; o++)
            count += is_option(o);
    t->rows = calloc(count + 1, sizeof *t->rows);
    t->longopts = calloc(count + 1, sizeof *t->longopts);
    t->shortopts = calloc(3 * count + 2, 1);
    if (!t->rows || !t->longopts || !t->shortopts) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    char *s = t->shortopts;
    *s++ = ':';
    for (size_t i = 0; i < n; i++)
        for (const sw_cli_option_t *o = g[i].rows; o->kind != SW_CLI_END; o++) {
            if (!is_option(o))
                continue;
            const int has_arg = o->arg ? required_argument : no_argument;
            t->rows[t->n] = (row_t){o, &g[i]};
            t->longopts[t->n] = (struct option){o->long_name, has_arg, NULL, ROW_CODE + (int)t->n};
            if (o->short_name) {
                *s++ = (char)o->short_name;
                if (o->arg)
                    *s++ = ':';
            }
            t->n++;
        }
    return SW_EXIT_OK;
}

static void free_table(table_t *t)
{
    free(t->rows);
    free(t->longopts);
    free(t->shortopts);
}

/* Defaults stored before parsing: a DOUBLE or LONG row's def is its
 * value when the option is not given. */
static void store_defaults(const table_t *t)
{
    for (size_t k = 0; k < t->n; k++) {
        const row_t *r = &t->rows[k];
        if (r->o->kind == SW_CLI_DOUBLE)
            *(double *)dest_of(r) = r->o->def;
        if (r->o->kind == SW_CLI_LONG)
            *(long *)dest_of(r) = (long)r->o->def;
    }
}

const sw_cli_option_t *sw_cli_option_named(const sw_cli_option_t *rows, const char *long_name)
{
    const sw_cli_option_t *o = rows;
    while (o->kind != SW_CLI_END && !(o->long_name && !strcmp(o->long_name, long_name))) o++;
    return o->kind == SW_CLI_END ? NULL : o;
}

int sw_cli_parse(const sw_cli_command_t *cmd, sw_cli_group_t *g, size_t n, int argc, char **argv,
                 int *operand)
{
    table_t t = {0};
    int rc = build_table(&t, g, n);
    if (rc != SW_EXIT_OK)
        goto out;
    store_defaults(&t);
    for (size_t i = 0; i < n; i++) {
        g[i].given = NULL;
        g[i].given_at = 0;
    }
    opterr = 0; /* misuse() words the errors */
    optind = 0; /* a fresh scan */
    int given = 0;
    for (int c; (c = getopt_long(argc, argv, t.shortopts, t.longopts, NULL)) != -1;) {
        const row_t *r = NULL;
        if (c >= ROW_CODE && (size_t)(c - ROW_CODE) < t.n)
            r = &t.rows[c - ROW_CODE];
        for (size_t k = 0; !r && c != '?' && c != ':' && k < t.n; k++)
            if (t.rows[k].o->short_name == c)
                r = &t.rows[k];
        if (!r) {
            rc = misuse(c, argv);
            goto out;
        }
        given++;
        if (!r->g->given) {
            r->g->given = r->o;
            r->g->given_at = given;
        }
        if (r->o->kind == SW_CLI_HELP) {
            sw_cli_print_help(stdout, cmd, g, n);
            rc = SW_EXIT_OK;
            goto out;
        }
        rc = take(r, optarg);
        if (rc != SW_EXIT_OK)
            goto out;
    }
    *operand = optind;
    rc = SW_CLI_CONTINUE;
out:
    free_table(&t);
    return rc;
}

void sw_cli_parse_free(const sw_cli_group_t *g, size_t n)
{
    for (size_t i = 0; i < n; i++)
        for (const sw_cli_option_t *o = g[i].rows; o->kind != SW_CLI_END; o++)
            if (o->kind == SW_CLI_LIST) {
                sw_cli_list_t *l = (sw_cli_list_t *)((char *)g[i].base + o->offset);
                free(l->v);
                memset(l, 0, sizeof *l);
            }
}

const char *sw_cli_log_operand(const char *cmd, int argc, char **argv, int first)
{
    if (first >= argc) {
        sw_cli_error(
            "%s: missing LOG (a CSV file, or - for standard input); see 'swaywatch %s "
            "--help'",
            cmd, cmd);
        return NULL;
    }
    if (first + 1 < argc) {
        sw_cli_error("%s: one LOG at a time; unexpected '%s'", cmd, argv[first + 1]);
        return NULL;
    }
    return argv[first];
}

int sw_cli_no_operand(const char *cmd, int argc, char **argv, int first)
{
    if (first >= argc)
        return SW_EXIT_OK;
    sw_cli_error("%s: unexpected argument '%s'; see 'swaywatch %s --help'", cmd, argv[first], cmd);
    return SW_EXIT_USAGE;
}

/* ---- --help ------------------------------------------------------------- */

static int visible(const sw_cli_group_t *g, const sw_cli_option_t *o)
{
    return !(g->flags & SW_CLI_HIDDEN) && !(o->flags & SW_CLI_HIDDEN);
}

/* "  -s, --scene FILE" or "      --set SEC.KEY=VALUE". */
static int label(char *buf, size_t len, const sw_cli_option_t *o)
{
    char sh[8] = "    ";
    if (o->short_name)
        snprintf(sh, sizeof sh, "-%c, ", o->short_name);
    return snprintf(buf, len, "  %s--%s%s%s", sh, o->long_name, o->arg ? " " : "",
                    o->arg ? o->arg : "");
}

/* The help of o, with "%g" replaced by its default. */
static void help_text(char *buf, size_t len, const sw_cli_option_t *o)
{
    if (o->help_fn) {
        o->help_fn(buf, len);
        return;
    }
    const char *h = o->help ? o->help : "";
    const char *at = strstr(h, "%g");
    if (!at)
        snprintf(buf, len, "%s", h);
    else
        snprintf(buf, len, "%.*s%g%s", (int)(at - h), h, o->def, at + 2);
    size_t used = strlen(buf);
    if (has_range(o) && used < len) {
        char r[96];
        range_text(r, sizeof r, o);
        snprintf(buf + used, len - used, " (%s%s)",
                 o->rule == SW_NUM_NONNEGATIVE && o->lo > 0.0 ? "" : "range ", r);
    }
}

/* text from column col, wrapped at HELP_WIDTH at spaces, continuation
 * lines indented to col.  A word longer than a line (a CSV header) is cut
 * after a comma, beginning on the line before when a fair piece fits. */
static void wrap(FILE *f, const char *text, int col)
{
    const int width = HELP_WIDTH - col;
    int first = 1;
    while (*text) {
        int cut = (int)strlen(text);
        if (cut > width) {
            cut = width;
            while (cut > 0 && text[cut] != ' ') cut--;
            const int next = cut ? cut + 1 : 0;
            /* a piece of it on this line, if the piece is not a scrap */
            if ((int)strcspn(text + next, " ") > width)
                for (int i = width; i > next + 12 || (next == 0 && i > 0); i--)
                    if (text[i - 1] == ',') {
                        cut = i;
                        break;
                    }
            if (cut == 0)
                cut = (int)strcspn(text, " "); /* no place to cut: the word whole */
        }
        if (!first)
            fprintf(f, "%*s", col, "");
        fprintf(f, "%.*s\n", cut, text);
        text += cut;
        while (*text == ' ') text++;
        first = 0;
    }
}

static int help_column(const sw_cli_group_t *g, size_t n)
{
    int col = 0;
    char buf[128];
    for (size_t i = 0; i < n; i++)
        for (const sw_cli_option_t *o = g[i].rows; o->kind != SW_CLI_END; o++) {
            if (!is_option(o) || !visible(&g[i], o))
                continue;
            int w = label(buf, sizeof buf, o) + 2;
            if (w > col)
                col = w;
        }
    return col < HELP_COLUMN ? col : HELP_COLUMN;
}

/* Print the rows of section title (options first, then paragraphs). */
static void print_section(FILE *f, const char *title, const sw_cli_group_t *g, size_t n, int col)
{
    fprintf(f, "\n%s\n", title);
    for (int texts = 0; texts < 2; texts++)
        for (size_t i = 0; i < n; i++) {
            if (g[i].flags & SW_CLI_HIDDEN)
                continue;
            const char *sec = g[i].section;
            for (const sw_cli_option_t *o = g[i].rows; o->kind != SW_CLI_END; o++) {
                if (o->kind == SW_CLI_SECTION)
                    sec = o->help;
                if (!sec || strcmp(sec, title) != 0 || !visible(&g[i], o))
                    continue;
                if (texts && o->kind == SW_CLI_TEXT)
                    fprintf(f, "%s\n", o->help);
                if (texts || !is_option(o))
                    continue;
                char lab[128], help[1024];
                int w = label(lab, sizeof lab, o);
                if (w + 2 > col)
                    fprintf(f, "%s\n%*s", lab, col, "");
                else
                    fprintf(f, "%-*s", col, lab);
                help_text(help, sizeof help, o);
                wrap(f, help, col);
            }
        }
}

/* Titles in the order they first appear; a section once. */
#define MAX_SECTIONS 32

void sw_cli_print_help(FILE *f, const sw_cli_command_t *cmd, const sw_cli_group_t *g, size_t n)
{
    const char *titles[MAX_SECTIONS];
    size_t nt = 0;
    for (size_t i = 0; i < n; i++) {
        if (g[i].flags & SW_CLI_HIDDEN)
            continue;
        const char *sec = g[i].section;
        for (const sw_cli_option_t *o = g[i].rows; o->kind != SW_CLI_END; o++) {
            if (o->kind == SW_CLI_SECTION)
                sec = o->help;
            if (o->kind == SW_CLI_SECTION || !sec || !visible(&g[i], o))
                continue;
            size_t k = 0;
            while (k < nt && strcmp(titles[k], sec) != 0) k++;
            if (k == nt && nt < MAX_SECTIONS)
                titles[nt++] = sec;
        }
    }
    fprintf(f, "usage: swaywatch %s\n", cmd->usage);
    if (cmd->about)
        fprintf(f, "\n%s", cmd->about);
    const int col = help_column(g, n);
    for (size_t k = 0; k < nt; k++) print_section(f, titles[k], g, n, col);
    if (cmd->exit_text) {
        fprintf(f, "\n%s", cmd->exit_text);
        return;
    }
    fprintf(f, "\nExit codes: 0 ok");
    if (cmd->exits & SW_CLI_EXIT_OVERTURN)
        fprintf(f, ", 1 a package overturned and --fail-on-overturn was given%s",
                cmd->exits & SW_CLI_EXIT_INCOMPLETE
                    ? "\n(with it also a verdict left incomplete by a gap or restart over motion)"
                    : "");
    fprintf(f,
            ",\n2 bad usage or bad input (options, scene files%s%s),\n"
            "3 a file could not be read or written,\n"
            "130 or 143 stopped by SIGINT or SIGTERM, within a second (the output files end\n"
            "with a whole row; the summary, marked INTERRUPTED, covers the input up to there).\n",
            cmd->exits & SW_CLI_EXIT_STRICT ? ", rows under --strict" : "",
            cmd->exits & SW_CLI_EXIT_OVERTURN
                ? ";\nwith --fail-on-overturn also a package whose model faulted: no verdict"
                : "");
}
