/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv.c - streaming CSV ingestion of acceleration logs (csv.h).
 *
 * Bytes arrive in chunks of any size.  They are gathered into one physical
 * line at a time, in a buffer allocated once at create; each complete line is
 * classified (blank, comment, header, data row) and split into fields, and
 * only the fields the caller asked for are converted to numbers.
 *
 * Why one physical line = one record (rather than streaming everything
 * through libcsv): libcsv reports no line numbers (its terminator hook has no
 * user pointer, so counting would need global state), and a stray quote
 * would swallow the rest of the stream into one field.  Parsing line by line
 * makes line numbers exact and confines any damage to its own line.  A
 * quoted field can therefore not span lines; logger exports never need that.
 *
 * Lines without a quote character are split on the delimiter directly (the
 * fast path, most rows of a numeric log); lines with a quote go through
 * libcsv in strict mode.  The fast path reproduces libcsv's treatment of
 * unquoted fields exactly (spaces and tabs around a field are dropped), so
 * both give identical results; the tests compare them.  Numbers and
 * date-times are read by csv_num.c, a header's names by csv_infer.c. */
#include <float.h>
#include <locale.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <csv.h>

#include "csv_int.h"
#include "swaywatch/csv.h"
#include "swaywatch/status.h"

/* A line held in the look-ahead. */
typedef struct {
    int kind;        /* L_* */
    long lineno;     /* 1-based physical line */
    size_t off, len; /* its text in abuf (data-like lines only) */
} ahead_t;

/* Any line fits while less than SW_CSV_AHEAD_BYTES are held. */
#define AHEAD_CAP ((size_t)SW_CSV_AHEAD_BYTES + SW_CSV_MAX_LINE + 1)

/* The reader's state: the only place it lives. */
struct sw_csv {
    /* options, fixed at create */
    char delim; /* 0 until detected */
    int header; /* -1 detect, 0 none, 1 present */
    double tscale, ascale;
    int flip;
    char *name[N_ROLES]; /* column name as given, looked up in the header; NULL: by index */
    long col[N_ROLES];   /* 0-based column index; -1 unknown (named) or unused */
    long probe;          /* column tested by header detection */
    int have_vert;
    int lateral;  /* the options': read a lateral column (given or inferred) */
    int have_lat; /* the layout has one */
    int flip_lat;
    double lat_scale;       /* m/s^2 per unit of the lateral column */
    double row_lat;         /* m/s^2, the lateral value of the row being delivered (NAN: none) */
    int col_given[N_ROLES]; /* the caller named or numbered the column */
    sw_csv_row_fn on_row;
    sw_csv_reject_fn on_reject;
    void *user;
    locale_t cloc; /* "C" numeric locale: '.' is the decimal point whatever
                      the program's locale says */
    int infer;     /* read unnamed columns and units from the header */
    int tscale_given, ascale_given;
    int dcomma; /* decimal comma: -1 not decided yet, 0, 1 */
    int tkind;  /* time column: 0 not seen yet, 1 numbers, 2 date-times */
    sw_csv_layout_t lay;
    char hdr[SW_CSV_MAX_FIELDS][SW_CSV_NAME_MAX]; /* the header's fields, trimmed */
    long nhdr;

    /* the physical line being gathered */
    char *line;
    size_t len;
    int overlong; /* the line outgrew the buffer: the rest is dropped */
    int finished;

    /* one line's split */
    sw_csv_splitter_t sp;
    sw_csv_split_opts_t so;
    sw_csv_fields_t f;

    /* the look-ahead: the first lines, held until the layout is fixed */
    int deciding;          /* still holding lines */
    char *abuf;            /* their text, AHEAD_CAP bytes */
    size_t aused;          /* bytes of abuf in use */
    ahead_t *ahead;        /* SW_CSV_AHEAD_LINES lines */
    int nahead, adata;     /* lines held, of which data-like */
    sw_csv_line_t *alines; /* the data-like ones, for the preamble's finder */
    long skip_lines;       /* the options': 0 find the preamble, N > 0 the first N lines,
                              < 0 none */
    long pre_data;         /* data-like lines of the preamble found, still to come */
    sw_csv_profile_t prof[SW_CSV_MAX_FIELDS]; /* the columns as the look-ahead's rows show them */
    long nprof;
    char pcap[SW_CSV_MAX_FIELDS][SW_CSV_NAME_MAX]; /* a row's fields, for the profiles */
    int date_order;                                /* the options' */
    int dorder; /* day and month first: the order in use, or AUTO: not known */

    /* stream state */
    long lineno;
    int header_open; /* the next data-like line may still be the header */
    int have_last;
    double last_t;
    int any_order; /* the options' any_order: no time-order check here */
    sw_csv_counts_t n;
    int status;    /* sticky error ending the parse, or SW_OK */
    char msg[400]; /* "line N: " + a reason */
    char reason[256];
};

/* ---------------------------------------------------------------- numbers */

enum {
    NUM_OK = SW_NUM_OK,
    NUM_EMPTY = SW_NUM_EMPTY,
    NUM_BAD = SW_NUM_BAD,
    NUM_COMMA = SW_NUM_COMMA,
    NUM_RANGE = SW_NUM_RANGE,
    NUM_ORDER /* a date-time with day and month first, the order not known */
};

static int parse_number(const sw_csv_t *c, const char *s, size_t n, double *out)
{
    return sw_csv_number(c->cloc, s, n, c->dcomma == 1, out);
}

/* ------------------------------------------------------------------ lines */

static void reject(sw_csv_t *c)
{
    c->n.rejected++;
    if (c->on_reject)
        c->on_reject(c->user, c->lineno, c->reason);
}

/* "accel (column 2)" or "accel (column 5, \"acc_x\")" */
static void column_label(const sw_csv_t *c, int r, char *dst, size_t cap)
{
    if (c->name[r])
        snprintf(dst, cap, "%s (column %ld, \"%s\")", role_name[r], c->col[r] + 1, c->name[r]);
    else
        snprintf(dst, cap, "%s (column %ld)", role_name[r], c->col[r] + 1);
}

/* End the parse with code and "line N: text". */
static void fail(sw_csv_t *c, int code, const char *text)
{
    c->status = code;
    snprintf(c->msg, sizeof c->msg, "line %ld: %s", c->lineno, text);
}

static int names_pending(const sw_csv_t *c)
{
    for (int r = 0; r < N_ROLES; r++)
        if (c->name[r] && c->col[r] < 0)
            return 1;
    return 0;
}

static int fix_layout(sw_csv_t *c, int has_header);

/* The first data-like line is a row that cannot be used (c->reason says
 * why): the file has no header, so a named column cannot be found; else
 * the defaults apply.  The row is refused after the layout is fixed, so
 * that a caller can say how rows are read before why this one was not. */
static void no_header(sw_csv_t *c)
{
    for (int r = 0; r < N_ROLES; r++)
        if (c->name[r] && c->col[r] < 0) {
            char t[200];
            snprintf(t, sizeof t, "column \"%s\" (%s) is named but the input has no header",
                     c->name[r], role_name[r]);
            reject(c);
            fail(c, SW_ENOTFOUND, t);
            return;
        }
    if (fix_layout(c, 0) == SW_OK)
        reject(c);
}

/* The layout once the columns are known (from the options, the header's
 * names or the defaults), or the parse ended. */
static int fix_layout(sw_csv_t *c, int has_header)
{
    const sw_csv_infer_in_t in = {
        .col = {c->col[R_TIME], c->col[R_ACCEL], c->col[R_VERT], c->col[R_LAT]},
        .name = (const char *const *)c->name,
        .match = c->f.match,
        .col_given = {c->col_given[R_TIME], c->col_given[R_ACCEL], c->col_given[R_VERT],
                      c->col_given[R_LAT]},
        .scale = {c->tscale, c->ascale},
        .scale_given = {c->tscale_given, c->ascale_given},
        .infer = c->infer,
        .lateral = c->lateral,
        .has_header = has_header,
        .names = (const char(*)[SW_CSV_NAME_MAX])c->hdr,
        .nnames = c->nhdr,
        .delim = c->delim,
        .decimal_comma = c->dcomma,
        .tkind = c->tkind,
        .date_order = c->date_order,
        .prof = c->prof,
        .nprof = c->nprof,
    };
    char t[320];
    const int rc = sw_csv_infer(&in, &c->lay, t, sizeof t);
    if (rc != SW_OK) {
        fail(c, rc, t);
        return rc;
    }
    for (int r = 0; r < N_ROLES; r++) c->col[r] = c->lay.col[r];
    c->lay.preamble = c->n.preamble; /* the preamble comes before the table */
    c->lay.first_line = c->lineno;
    c->lay.preamble_from = c->skip_lines > 0 ? SW_CSV_FROM_OPTION
                           : c->n.preamble   ? SW_CSV_FROM_VALUES
                                             : SW_CSV_FROM_DEFAULT;
    c->tscale = c->lay.scale[R_TIME];
    if (c->lay.date_order != SW_CSV_DATE_AUTO)
        c->dorder = c->lay.date_order;
    c->ascale = c->lay.scale[R_ACCEL];
    c->have_lat = c->lay.col[R_LAT] >= 0;
    c->lat_scale = c->lay.scale[R_LAT];
    return SW_OK;
}

/* The first data-like line was a header. */
static void take_header(sw_csv_t *c)
{
    c->n.headers++;
    fix_layout(c, 1);
}

/* The delimiter of the first data-like line, if not given.  0 when the line
 * has none: a one-column header, or a row reported as such. */
static int choose_delim(sw_csv_t *c, const char *s, size_t n, int header_here)
{
    const char d = sw_csv_detect_delim(s, n);
    if (d) {
        c->delim = d;
        return 1;
    }
    if (header_here && c->header == 1) {
        for (int r = 0; r < N_ROLES; r++) c->f.match[r] = -1;
        take_header(c); /* a one-column header: named columns fail */
        return 0;
    }
    c->n.rows++;
    snprintf(c->reason, sizeof c->reason,
             "expected at least 2 columns, found 1 (no ',' ';' or tab delimiter)");
    if (header_here)
        no_header(c);
    else
        reject(c);
    return 0;
}

/* Split the line into the slots wanted; 0 with c->reason when its quoting
 * is malformed. */
static int split_line(sw_csv_t *c, char *s, size_t n, int header_here)
{
    sw_csv_split_opts_t *o = &c->so;
    o->delim = c->delim;
    for (int r = 0; r < N_ROLES; r++) o->want[r] = c->col[r];
    o->want[R_PROBE] = header_here && c->header < 0 ? c->probe : -1;
    o->names = header_here && names_pending(c) ? (const char *const *)c->name : NULL;
    o->capture = header_here ? c->hdr : NULL;
    const int rc = sw_csv_split(&c->sp, s, n, o, &c->f);
    if (header_here)
        c->nhdr = c->f.ncap;
    if (rc != SW_CSV_SPLIT_OK) {
        snprintf(c->reason, sizeof c->reason, "%s", c->f.reason);
        return 0;
    }
    return 1;
}

/* A first line whose time field is not a number may still be a data row
 * with a corrupt time ("0.00O,-9"): its time field holds digits and
 * another field is a number.  A header's names have no field that is a
 * number, or no digit in the time field's ("t,1,2").  Taking such a row
 * for the header would make it vanish from the counts. */
static int corrupt_row(sw_csv_t *c, const char *t, size_t tn)
{
    int digits = 0;
    for (size_t i = 0; i < tn; i++) digits |= t[i] >= '0' && t[i] <= '9';
    if (!digits)
        return 0;
    for (long k = 0; k < c->nhdr; k++) {
        double v;
        if (parse_number(c, c->hdr[k], strlen(c->hdr[k]), &v) == NUM_OK)
            return 1;
    }
    return 0;
}

/* The first data-like line: a header (taken; returns 1), or the first data
 * row (0; also when the parse ended, with c->status set). */
static int first_line(sw_csv_t *c, int ok)
{
    int is_header = c->header == 1;
    if (c->header < 0 && ok && c->f.fs[R_PROBE]) {
        /* "0,001", "1e400" and date-times are data as far as this is
         * concerned: such a first row is reported, not taken for a header. */
        double v;
        const int res = parse_number(c, c->f.fs[R_PROBE], c->f.fl[R_PROBE], &v);
        is_header = (res == NUM_EMPTY || res == NUM_BAD) &&
                    !sw_csv_is_datetime(c->f.fs[R_PROBE], c->f.fl[R_PROBE]) &&
                    !corrupt_row(c, c->f.fs[R_PROBE], c->f.fl[R_PROBE]);
    }
    if (is_header) {
        take_header(c);
        return 1;
    }
    c->nhdr = 0;
    if (c->so.names) {
        /* Reported like any unusable row, then the parse ends. */
        int r = 0;
        while (!(c->name[r] && c->col[r] < 0)) r++;
        snprintf(c->reason, sizeof c->reason,
                 "column \"%s\" (%s) is named but the input has no header", c->name[r],
                 role_name[r]);
        c->n.rows++;
        reject(c);
        fail(c, SW_ENOTFOUND, c->reason);
        return 0;
    }
    if (fix_layout(c, 0) != SW_OK) {
        /* A first row the layout cannot be fixed from is counted and
         * reported like any unusable row (rows == accepted + rejected),
         * then the parse ends with the layout's message. */
        c->n.rows++;
        const char *m = strstr(c->msg, ": "); /* after "line N: " */
        snprintf(c->reason, sizeof c->reason, "%.200s", m ? m + 2 : c->msg);
        reject(c);
    }
    return 0;
}

/* The decimal mark of a ';' or tab export, from the first number that shows
 * one (a ',' file cannot use ',' as its decimal mark). */
static void decide_comma(sw_csv_t *c)
{
    if (c->dcomma != -1)
        return;
    if (c->delim == ',') {
        c->dcomma = c->lay.decimal_comma = 0;
        return;
    }
    for (int r = 0; r < N_ROLES; r++) {
        if (!c->f.fs[r])
            continue;
        /* a date-time's marks are its own ("20.05.2024 12:00:00.000") */
        if (r == R_TIME && sw_csv_is_datetime(c->f.fs[r], c->f.fl[r]))
            continue;
        if (memchr(c->f.fs[r], ',', c->f.fl[r])) {
            c->dcomma = c->lay.decimal_comma = 1;
            return;
        }
        if (memchr(c->f.fs[r], '.', c->f.fl[r])) {
            c->dcomma = c->lay.decimal_comma = 0;
            return;
        }
    }
}

/* The time field: a number, or a date-time (all rows as the first). */
static int parse_time(sw_csv_t *c, double *out)
{
    const char *s = c->f.fs[R_TIME];
    const size_t n = c->f.fl[R_TIME];
    if (c->tkind != 2) {
        const int res = parse_number(c, s, n, out);
        if (res == NUM_OK)
            c->tkind = 1;
        if (res != NUM_BAD || c->tkind == 1)
            return res;
    }
    const int dt = sw_csv_datetime(s, n, c->dorder, out);
    if (dt < 0)
        return NUM_ORDER;
    if (dt > 0) {
        if (c->tkind == 0) {
            c->tkind = 2;
            c->tscale = 1.0;
            /* the layout says what is read: a date-time, not the epoch
             * numbers of the look-ahead rows after it */
            if (c->lay.unit[R_TIME] != SW_CSV_UNIT_DATETIME)
                c->lay.unit_from[R_TIME] = SW_CSV_FROM_VALUES; /* over a "(s)" header */
            c->lay.unit[R_TIME] = SW_CSV_UNIT_DATETIME;
            c->lay.scale[R_TIME] = 1.0;
            c->lay.epoch = 0;
        }
        return NUM_OK;
    }
    return NUM_BAD;
}

/* Why field r of a row could not be used, into c->reason. */
static void field_reason(sw_csv_t *c, int r, int res)
{
    char label[120], ex[EXCERPT_MAX + 8];
    column_label(c, r, label, sizeof label);
    sw_csv_excerpt(ex, sizeof ex, c->f.fs[r], c->f.fl[r]);
    switch (res) {
        case NUM_EMPTY: snprintf(c->reason, sizeof c->reason, "%s is empty", label); break;
        case NUM_COMMA:
            snprintf(c->reason, sizeof c->reason, "%s is not a number (decimal comma?): %s", label,
                     ex);
            break;
        case NUM_RANGE:
            snprintf(c->reason, sizeof c->reason, "%s is out of range: %s", label, ex);
            break;
        case NUM_ORDER:
            snprintf(c->reason, sizeof c->reason,
                     "%s: day and month in an order not known: %s (say --date-order dmy or mdy)",
                     label, ex);
            break;
        default:
            if (r == R_TIME && c->tkind == 2)
                snprintf(c->reason, sizeof c->reason,
                         "%s is not a date-time like the rows before it: %s", label, ex);
            else
                snprintf(c->reason, sizeof c->reason, "%s is not a number: %s", label, ex);
            break;
    }
}

/* A data row split into its fields: check, convert, deliver. */
static void data_row(sw_csv_t *c, int ok)
{
    c->n.rows++;
    if (!ok) {
        reject(c);
        return;
    }
    decide_comma(c);
    double v[N_ROLES] = {0.0, 0.0, 0.0, 0.0};
    for (int r = 0; r < N_ROLES; r++) {
        if ((r == R_VERT && !c->have_vert) || (r == R_LAT && !c->have_lat))
            continue;
        if (!c->f.fs[r]) {
            char label[120];
            column_label(c, r, label, sizeof label);
            snprintf(c->reason, sizeof c->reason, "missing field: %s; the line has %ld field%s",
                     label, c->f.nf, c->f.nf == 1 ? "" : "s");
            reject(c);
            return;
        }
        const int res =
            r == R_TIME ? parse_time(c, &v[r]) : parse_number(c, c->f.fs[r], c->f.fl[r], &v[r]);
        if (res != NUM_OK) {
            field_reason(c, r, res);
            reject(c);
            return;
        }
    }

    double t = v[R_TIME] * c->tscale;
    double a = v[R_ACCEL] * c->ascale;
    double z = v[R_VERT] * c->ascale;
    double y = v[R_LAT] * c->lat_scale;
    if (!isfinite(t) || !isfinite(a) || !isfinite(z) || !isfinite(y)) {
        int r = !isfinite(t) ? R_TIME : !isfinite(a) ? R_ACCEL : !isfinite(z) ? R_VERT : R_LAT;
        char label[120], ex[EXCERPT_MAX + 8];
        column_label(c, r, label, sizeof label);
        sw_csv_excerpt(ex, sizeof ex, c->f.fs[r], c->f.fl[r]);
        snprintf(c->reason, sizeof c->reason, "%s is out of range after unit conversion: %s", label,
                 ex);
        reject(c);
        return;
    }
    if (c->flip)
        a = -a;
    if (c->flip_lat)
        y = -y;
    c->row_lat = c->have_lat ? y : NAN;
    if (!c->any_order && c->have_last && t <= c->last_t) {
        if (t == c->last_t)
            snprintf(c->reason, sizeof c->reason,
                     "duplicate time %.15g s (same as the previous row)", t);
        else
            snprintf(c->reason, sizeof c->reason, "time %.15g s not after previous %.15g s", t,
                     c->last_t);
        reject(c);
        return;
    }
    if (c->on_row && c->on_row(c->user, c->lineno, t, a, z) != 0) {
        snprintf(c->reason, sizeof c->reason, "refused by consumer");
        reject(c);
        return;
    }
    c->n.accepted++;
    c->have_last = 1;
    c->last_t = t;
}

/* A line that is neither blank nor a comment. */
static void data_line(sw_csv_t *c, char *s, size_t n)
{
    const int header_here = c->header_open;
    c->header_open = 0; /* whatever this line is, no later line is a header */
    if (!c->delim && !choose_delim(c, s, n, header_here))
        return;
    const int ok = split_line(c, s, n, header_here);
    if (header_here && (first_line(c, ok) || c->status < 0))
        return;
    data_row(c, ok);
}

/* What a physical line is, judged before anything else is known. */
enum { L_BLANK, L_COMMENT, L_DATA, L_OVERLONG };

static int classify(const char *s, size_t n, int overlong)
{
    size_t i = 0;
    while (i < n && sw_csv_is_blank(s[i])) i++;
    if (i < n && s[i] == '#') /* judged on the kept prefix, however long */
        return L_COMMENT;
    if (i == n && !overlong)
        return L_BLANK;
    return overlong ? L_OVERLONG : L_DATA;
}

/* One physical line (s[n] writable) at c->lineno, once the look-ahead is
 * over: counted, and read as what it is. */
static void process(sw_csv_t *c, int kind, char *s, size_t n)
{
    c->n.lines++;
    if (c->lineno <= c->skip_lines || (kind >= L_DATA && c->pre_data > 0)) {
        c->n.preamble++; /* --skip-lines, or the preamble found */
        c->pre_data -= kind >= L_DATA && c->lineno > c->skip_lines;
        return;
    }
    switch (kind) {
        case L_COMMENT: c->n.comments++; return;
        case L_BLANK: c->n.blanks++; return;
        case L_OVERLONG:
            if (c->header_open && c->header == 1) {
                c->header_open = 0;
                for (int r = 0; r < N_ROLES; r++) c->f.match[r] = -1;
                take_header(c);
                return;
            }
            c->n.rows++;
            snprintf(c->reason, sizeof c->reason, "line longer than %d bytes", SW_CSV_MAX_LINE);
            if (c->header_open) {
                c->header_open = 0;
                no_header(c);
            } else {
                reject(c);
            }
            return;
        default:
            s[n] = '\0';
            data_line(c, s, n);
            return;
    }
}

/* The columns as the rows of the look-ahead show them: every data-like
 * line after the table's first (its header, or a row: one row less does
 * not matter), split on the delimiter the first line will be given. */
static void profile(sw_csv_t *c)
{
    long skipped = 0;
    int i = 0;
    for (; i < c->nahead; i++) {
        const ahead_t *e = &c->ahead[i];
        if (e->kind < L_DATA || e->lineno <= c->skip_lines)
            continue;
        if (skipped++ < c->pre_data)
            continue;
        break;
    }
    if (i == c->nahead || c->ahead[i].kind != L_DATA)
        return;
    const char d =
        c->delim ? c->delim : sw_csv_detect_delim(c->abuf + c->ahead[i].off, c->ahead[i].len);
    if (!d)
        return;
    sw_csv_split_opts_t so = {.delim = d, .capture = c->pcap};
    for (int r = 0; r < N_SLOTS; r++) so.want[r] = -1; /* no field is taken, all captured */
    sw_csv_fields_t f;
    for (i++; i < c->nahead; i++) {
        const ahead_t *e = &c->ahead[i];
        if (e->kind != L_DATA)
            continue;
        /* nothing is written into the line: no field is wanted */
        sw_csv_split(&c->sp, c->abuf + e->off, e->len, &so, &f);
        for (long k = 0; k < f.ncap; k++)
            sw_csv_profile_add(&c->prof[k], c->pcap[k], strlen(c->pcap[k]), d, c->cloc);
        if (f.ncap > c->nprof)
            c->nprof = f.ncap;
    }
}

/* The look-ahead is over: the lines held are read in order, as any later
 * line is, up to an error that ends the parse. */
static void decide(sw_csv_t *c)
{
    const long read = c->lineno;
    c->deciding = 0;
    if (c->skip_lines == 0) { /* find the preamble */
        long n = 0;
        for (int i = 0; i < c->nahead; i++)
            if (c->ahead[i].kind >= L_DATA)
                c->alines[n++] = (sw_csv_line_t){
                    c->ahead[i].kind == L_DATA ? c->abuf + c->ahead[i].off : "", c->ahead[i].len};
        const sw_csv_preamble_opts_t po = {c->delim, c->header, c->cloc};
        c->pre_data = sw_csv_preamble_find(c->alines, n, &po);
    }
    profile(c);
    for (int i = 0; i < c->nahead && c->status >= 0; i++) {
        const ahead_t *e = &c->ahead[i];
        c->lineno = e->lineno;
        process(c, e->kind, c->abuf + e->off, e->len);
    }
    c->lineno = read;
    c->nahead = 0;
    c->aused = 0;
}

/* Hold a line while the layout is not fixed; decide once the look-ahead
 * is full. */
static void hold(sw_csv_t *c, int kind, const char *s, size_t n)
{
    ahead_t *e = &c->ahead[c->nahead++];
    e->kind = kind;
    e->lineno = c->lineno;
    e->off = c->aused;
    e->len = kind == L_DATA ? n : 0;
    if (kind == L_DATA) {
        memcpy(c->abuf + c->aused, s, n);
        c->abuf[c->aused + n] = '\0';
        c->aused += n + 1;
        c->adata++;
    }
    if (c->nahead == SW_CSV_AHEAD_LINES || c->adata == SW_CSV_AHEAD_ROWS ||
        c->aused >= SW_CSV_AHEAD_BYTES)
        decide(c);
}

/* A complete physical line is in c->line (without its '\n'). */
static void end_line(sw_csv_t *c)
{
    char *s = c->line;
    size_t n = c->len;
    int overlong = c->overlong;
    c->len = 0;
    c->overlong = 0;
    c->lineno++;

    if (c->lineno == 1 && n >= 3 && !memcmp(s, "\xEF\xBB\xBF", 3))
        s += 3, n -= 3;
    if (!overlong && n && s[n - 1] == '\r')
        n--;
    if (n > (size_t)SW_CSV_MAX_LINE)
        overlong = 1;
    const int kind = classify(s, n, overlong);
    if (c->deciding)
        hold(c, kind, s, n);
    else
        process(c, kind, s, n);
}

/* ------------------------------------------------------------- public API */

static int bad_opts(int *err, char *msg, size_t msglen, int code, const char *text)
{
    if (err)
        *err = code;
    if (msg && msglen)
        snprintf(msg, msglen, "%s", text);
    return code;
}

sw_csv_t *sw_csv_create(const sw_csv_opts_t *opts, sw_csv_row_fn on_row, sw_csv_reject_fn on_reject,
                        void *user, int *err, char *msg, size_t msglen)
{
    static const sw_csv_opts_t defaults = {.header = -1};
    const sw_csv_opts_t *o = opts ? opts : &defaults;
    char t[200];

    if (o->delim != 0 && o->delim != ',' && o->delim != ';' && o->delim != '\t') {
        bad_opts(err, msg, msglen, SW_EINVAL, "delimiter must be ',', ';' or tab");
        return NULL;
    }
    if (o->header < -1 || o->header > 1) {
        bad_opts(err, msg, msglen, SW_EINVAL, "header must be -1 (detect), 0 or 1");
        return NULL;
    }
    double ts = o->time_scale == 0.0 ? 1.0 : o->time_scale;
    double as = o->accel_scale == 0.0 ? 1.0 : o->accel_scale;
    if (!(isfinite(ts) && ts > 0.0)) {
        bad_opts(err, msg, msglen, SW_EINVAL, "time scale must be finite and positive");
        return NULL;
    }
    if (!(isfinite(as) && as > 0.0)) {
        bad_opts(err, msg, msglen, SW_EINVAL,
                 "acceleration scale must be finite and positive (flip reverses the axis)");
        return NULL;
    }

    sw_csv_t *c = calloc(1, sizeof *c);
    if (!c) {
        bad_opts(err, msg, msglen, SW_ENOMEM, "out of memory");
        return NULL;
    }
    sw_csv_colspec_t cs;
    const int rc = sw_csv_colspec_parse(o, &cs, t, sizeof t);
    if (rc != SW_OK) {
        bad_opts(err, msg, msglen, rc, t);
        sw_csv_destroy(c);
        return NULL;
    }
    for (int r = 0; r < N_ROLES; r++) {
        c->col[r] = cs.col[r];
        c->col_given[r] = cs.given[r];
        if (!cs.name[r])
            continue;
        c->name[r] = malloc(cs.len[r] + 1);
        if (!c->name[r]) {
            bad_opts(err, msg, msglen, SW_ENOMEM, "out of memory");
            sw_csv_destroy(c);
            return NULL;
        }
        memcpy(c->name[r], cs.name[r], cs.len[r]);
        c->name[r][cs.len[r]] = '\0';
    }
    c->have_vert = o->vert_col != NULL;
    c->lateral = o->lateral != 0;
    c->flip_lat = o->flip_lat != 0;
    c->lat_scale = as;
    c->row_lat = NAN;
    if (o->lat_col && !o->lateral) {
        bad_opts(err, msg, msglen, SW_EINVAL, "lat_col is given, but lateral is 0");
        sw_csv_destroy(c);
        return NULL;
    }
    if (o->date_order < SW_CSV_DATE_AUTO || o->date_order > SW_CSV_DATE_MDY) {
        bad_opts(err, msg, msglen, SW_EINVAL, "date_order must be SW_CSV_DATE_AUTO, _DMY or _MDY");
        sw_csv_destroy(c);
        return NULL;
    }
    if (o->decimal_comma < -1 || o->decimal_comma > 1) {
        bad_opts(err, msg, msglen, SW_EINVAL, "decimal_comma must be -1 (detect), 0 or 1");
        sw_csv_destroy(c);
        return NULL;
    }
    c->infer = o->infer != 0;
    c->tscale_given = o->time_scale != 0.0;
    c->ascale_given = o->accel_scale != 0.0;
    c->dcomma = o->decimal_comma;
    c->delim = o->delim;
    c->header = o->header;
    c->header_open = o->header != 0;
    c->tscale = ts;
    c->ascale = as;
    c->flip = o->flip != 0;
    c->any_order = o->any_order != 0;
    /* With a named time column its position is unknown until the header is
     * read, so detection looks at the first column. */
    c->probe = c->col[R_TIME] >= 0 ? c->col[R_TIME] : 0;
    c->on_row = on_row;
    c->on_reject = on_reject;
    c->user = user;

    c->line = malloc(LINE_CAP + 1);
    c->abuf = malloc(AHEAD_CAP);
    c->ahead = malloc(SW_CSV_AHEAD_LINES * sizeof *c->ahead);
    c->alines = malloc(SW_CSV_AHEAD_LINES * sizeof *c->alines);
    c->skip_lines = o->skip_lines;
    c->date_order = o->date_order;
    c->dorder = o->date_order;
    c->deciding = 1;
    c->cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (!c->line || !c->abuf || !c->ahead || !c->alines || c->cloc == (locale_t)0 ||
        sw_csv_splitter_init(&c->sp) != 0) {
        bad_opts(err, msg, msglen, SW_ENOMEM, "out of memory");
        sw_csv_destroy(c);
        return NULL;
    }
    if (err)
        *err = SW_OK;
    if (msg && msglen)
        msg[0] = '\0';
    return c;
}

void sw_csv_destroy(sw_csv_t *c)
{
    if (!c)
        return;
    sw_csv_splitter_free(&c->sp);
    if (c->cloc != (locale_t)0)
        freelocale(c->cloc);
    for (int r = 0; r < N_ROLES; r++) free(c->name[r]);
    free(c->line);
    free(c->abuf);
    free(c->ahead);
    free(c->alines);
    free(c);
}

/* Add bytes of the current line; past the limit keep only the prefix (enough
 * to recognise a comment) and drop the rest up to the newline. */
static void append(sw_csv_t *c, const char *s, size_t n)
{
    if (c->overlong)
        return;
    if (n > LINE_CAP - c->len) {
        memcpy(c->line + c->len, s, LINE_CAP - c->len);
        c->len = LINE_CAP;
        c->overlong = 1;
        return;
    }
    memcpy(c->line + c->len, s, n);
    c->len += n;
}

int sw_csv_feed(sw_csv_t *c, const char *buf, size_t len)
{
    if (!c || (!buf && len))
        return SW_EINVAL;
    if (c->status < 0)
        return c->status;
    if (c->finished) {
        c->status = SW_EINVAL;
        snprintf(c->msg, sizeof c->msg, "sw_csv_feed called after sw_csv_finish");
        return c->status;
    }
    while (len) {
        const char *nl = memchr(buf, '\n', len);
        size_t seg = nl ? (size_t)(nl - buf) : len;
        append(c, buf, seg);
        if (!nl)
            break;
        end_line(c);
        if (c->status < 0)
            return c->status;
        buf += seg + 1;
        len -= seg + 1;
    }
    return SW_OK;
}

int sw_csv_finish(sw_csv_t *c)
{
    if (!c)
        return SW_EINVAL;
    if (c->status < 0)
        return c->status;
    if (c->finished)
        return SW_OK;
    c->finished = 1;
    if (c->len || c->overlong)
        end_line(c);
    if (c->deciding && c->status >= 0)
        decide(c); /* a log shorter than the look-ahead */
    return c->status;
}

void sw_csv_counts(const sw_csv_t *c, sw_csv_counts_t *out)
{
    if (!out)
        return;
    if (!c) {
        memset(out, 0, sizeof *out);
        return;
    }
    *out = c->n;
}

const char *sw_csv_error_message(const sw_csv_t *c)
{
    return c ? c->msg : "";
}

double sw_csv_lateral(const sw_csv_t *c)
{
    return c ? c->row_lat : NAN;
}

int sw_csv_layout(const sw_csv_t *c, sw_csv_layout_t *out)
{
    if (!c || !out)
        return SW_EINVAL;
    *out = c->lay;
    return SW_OK;
}

long sw_csv_header_count(const sw_csv_t *c)
{
    return c ? c->nhdr : 0;
}

const char *sw_csv_header_field(const sw_csv_t *c, long i)
{
    return c && i >= 0 && i < c->nhdr ? c->hdr[i] : NULL;
}

const char *sw_csv_unit_name(int unit)
{
    switch (unit) {
        case SW_CSV_UNIT_S: return "s";
        case SW_CSV_UNIT_MS: return "ms";
        case SW_CSV_UNIT_US: return "us";
        case SW_CSV_UNIT_DATETIME: return "date-time";
        case SW_CSV_UNIT_MPS2: return "m/s^2";
        case SW_CSV_UNIT_G: return "g";
        case SW_CSV_UNIT_NS: return "ns";
        case SW_CSV_UNIT_MG: return "mg";
        default: return "";
    }
}
