/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_csv.c - CSV ingestion (csv.h): formats, units, column choice, row
 * rejection with exact line numbers, limits, garbage input.
 *
 * Every input is fed three ways (one chunk, 7-byte chunks, 1-byte chunks)
 * and the three runs must agree exactly; every run checks the counting
 * invariants. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_errno.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/csv.h"
#include "swaywatch/status.h"

/* ---------------------------------------------------------------- harness */

typedef struct {
    long line;
    double t, a, z;
} row_rec;

typedef struct {
    long line;
    char reason[256];
} rej_rec;

typedef struct {
    row_rec *rows;
    size_t nrows, caprows;
    rej_rec *rejs;
    size_t nrejs, caprejs;
    sw_csv_counts_t counts;
    int feed_rc, finish_rc;
    char msg[256];
    long refuse_line; /* on_row refuses the row on this line */
} result_t;

static int on_row(void *user, long line, double t, double a, double z)
{
    result_t *r = user;
    if (line == r->refuse_line)
        return 1;
    if (r->nrows == r->caprows) {
        r->caprows = r->caprows ? 2 * r->caprows : 64;
        r->rows = realloc(r->rows, r->caprows * sizeof *r->rows);
        assert_non_null(r->rows);
    }
    r->rows[r->nrows++] = (row_rec){line, t, a, z};
    return 0;
}

static void on_reject(void *user, long line, const char *reason)
{
    result_t *r = user;
    if (r->nrejs == r->caprejs) {
        r->caprejs = r->caprejs ? 2 * r->caprejs : 64;
        r->rejs = realloc(r->rejs, r->caprejs * sizeof *r->rejs);
        assert_non_null(r->rejs);
    }
    r->rejs[r->nrejs].line = line;
    snprintf(r->rejs[r->nrejs].reason, sizeof r->rejs[r->nrejs].reason, "%s", reason);
    r->nrejs++;
}

static void result_free(result_t *r)
{
    free(r->rows);
    free(r->rejs);
    memset(r, 0, sizeof *r);
}

static long physical_lines(const char *in, size_t len)
{
    long n = 0;
    for (size_t i = 0; i < len; i++) n += in[i] == '\n';
    return n + (len && in[len - 1] != '\n');
}

/* One run with the given chunk size (0: all at once). */
static void run(const char *in, size_t len, const sw_csv_opts_t *o, size_t chunk, long refuse,
                result_t *r)
{
    int err = 12345;
    char msg[256];
    memset(r, 0, sizeof *r);
    r->refuse_line = refuse;
    sw_csv_t *c = sw_csv_create(o, on_row, on_reject, r, &err, msg, sizeof msg);
    if (!c)
        fail_msg("create failed (%d): %s", err, msg);
    assert_int_equal(err, SW_OK);
    if (!chunk)
        chunk = len ? len : 1;
    r->feed_rc = SW_OK;
    for (size_t off = 0; off < len && r->feed_rc == SW_OK; off += chunk)
        r->feed_rc = sw_csv_feed(c, in + off, len - off < chunk ? len - off : chunk);
    r->finish_rc = sw_csv_finish(c);
    if (r->feed_rc == SW_OK)
        r->feed_rc = r->finish_rc; /* an error found when the look-ahead ends at finish */
    sw_csv_counts(c, &r->counts);
    snprintf(r->msg, sizeof r->msg, "%s", sw_csv_error_message(c));
    sw_csv_destroy(c);

    const sw_csv_counts_t *n = &r->counts;
    assert_int_equal(n->rows, n->accepted + n->rejected);
    assert_int_equal(n->lines, n->rows + n->comments + n->blanks + n->headers + n->preamble);
    assert_int_equal((long)r->nrows, n->accepted);
    assert_int_equal((long)r->nrejs, n->rejected);
    if (r->feed_rc == SW_OK) {
        assert_int_equal(r->finish_rc, SW_OK);
        assert_int_equal(n->lines, physical_lines(in, len));
        assert_string_equal(r->msg, "");
    } else {
        assert_true(r->feed_rc < 0);
        assert_int_equal(r->finish_rc, r->feed_rc); /* the error is sticky */
        assert_true(r->msg[0] != '\0');
    }
    for (size_t i = 1; i < r->nrows; i++) {
        assert_true(r->rows[i].line > r->rows[i - 1].line);
        if (!o->any_order)
            assert_true(r->rows[i].t > r->rows[i - 1].t);
    }
}

static void assert_same(const result_t *x, const result_t *y)
{
    assert_memory_equal(&x->counts, &y->counts, sizeof x->counts);
    assert_int_equal(x->feed_rc, y->feed_rc);
    assert_int_equal(x->finish_rc, y->finish_rc);
    assert_string_equal(x->msg, y->msg);
    assert_int_equal(x->nrows, y->nrows);
    for (size_t i = 0; i < x->nrows; i++) {
        assert_int_equal(x->rows[i].line, y->rows[i].line);
        /* bit-identical: same text, same conversion */
        assert_memory_equal(&x->rows[i].t, &y->rows[i].t, sizeof(double));
        assert_memory_equal(&x->rows[i].a, &y->rows[i].a, sizeof(double));
        assert_memory_equal(&x->rows[i].z, &y->rows[i].z, sizeof(double));
    }
    assert_int_equal(x->nrejs, y->nrejs);
    for (size_t i = 0; i < x->nrejs; i++) {
        assert_int_equal(x->rejs[i].line, y->rejs[i].line);
        assert_string_equal(x->rejs[i].reason, y->rejs[i].reason);
    }
}

/* Run with one chunk, 7-byte and 1-byte chunks; all must agree.  The
 * one-chunk result is left in r. */
static void run3r(const char *in, size_t len, const sw_csv_opts_t *o, long refuse, result_t *r)
{
    static const size_t chunks[] = {7, 1};
    run(in, len, o, 0, refuse, r);
    for (size_t k = 0; k < sizeof chunks / sizeof chunks[0]; k++) {
        result_t other;
        run(in, len, o, chunks[k], refuse, &other);
        assert_same(r, &other);
        result_free(&other);
    }
}

static void run3(const char *in, size_t len, const sw_csv_opts_t *o, result_t *r)
{
    run3r(in, len, o, -1, r);
}

#define RUN_STR(s, o, r) run3((s), strlen(s), (o), (r))

static sw_csv_opts_t defaults(void)
{
    sw_csv_opts_t o;
    memset(&o, 0, sizeof o);
    o.header = -1;
    return o;
}

static void check_counts(int at, const result_t *r, long lines, long rows, long accepted,
                         long comments, long blanks, long headers)
{
    const sw_csv_counts_t *n = &r->counts;
    if (n->lines != lines || n->rows != rows || n->accepted != accepted ||
        n->rejected != rows - accepted || n->comments != comments || n->blanks != blanks ||
        n->headers != headers)
        fail_msg(
            "test line %d: counts lines %ld rows %ld accepted %ld rejected %ld comments %ld "
            "blanks %ld headers %ld, expected %ld %ld %ld %ld %ld %ld %ld",
            at, n->lines, n->rows, n->accepted, n->rejected, n->comments, n->blanks, n->headers,
            lines, rows, accepted, rows - accepted, comments, blanks, headers);
}

static void assert_close(int at, double got, double want, const char *what, long line)
{
    if (!(fabs(got - want) <= 1e-12 * (1.0 + fabs(want))))
        fail_msg("test line %d: input line %ld: %s = %.17g, expected %.17g", at, line, what, got,
                 want);
}

static void check_row(int at, const result_t *r, size_t i, long line, double t, double a, double z)
{
    if (i >= r->nrows)
        fail_msg("test line %d: row %zu missing (%zu rows)", at, i, r->nrows);
    if (r->rows[i].line != line)
        fail_msg("test line %d: row %zu is on line %ld, expected %ld", at, i, r->rows[i].line,
                 line);
    assert_close(at, r->rows[i].t, t, "t", line);
    assert_close(at, r->rows[i].a, a, "a_g", line);
    assert_close(at, r->rows[i].z, z, "a_z", line);
}

static void check_rej(int at, const result_t *r, size_t i, long line, const char *reason)
{
    if (i >= r->nrejs)
        fail_msg("test line %d: rejection %zu missing (%zu rejections)", at, i, r->nrejs);
    if (r->rejs[i].line != line || strcmp(r->rejs[i].reason, reason))
        fail_msg("test line %d: rejection %zu: line %ld \"%s\", expected line %ld \"%s\"", at, i,
                 r->rejs[i].line, r->rejs[i].reason, line, reason);
}

#define assert_counts(...) check_counts(__LINE__, __VA_ARGS__)
#define assert_row(...) check_row(__LINE__, __VA_ARGS__)
#define assert_rej(...) check_rej(__LINE__, __VA_ARGS__)

static char *read_fixture(const char *name, size_t *len)
{
    char path[512];
    snprintf(path, sizeof path, "%s/tests/csv/%s", SW_SOURCE_DIR, name);
    FILE *f = fopen(path, "rb");
    if (!f)
        fail_msg("cannot open %s", path);
    char *buf = malloc(1 << 16);
    assert_non_null(buf);
    *len = fread(buf, 1, 1 << 16, f);
    fclose(f);
    return buf;
}

/* Deterministic random bytes (xorshift64*). */
static uint64_t rnd(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * 2685821657736338717ULL;
}

/* ------------------------------------------------------------------ tests */

static void test_no_header(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("0,1\n0.5,2.5\n1,-3\n", &o, &r);
    assert_counts(&r, 3, 3, 3, 0, 0, 0);
    assert_row(&r, 0, 1, 0.0, 1.0, 0.0);
    assert_row(&r, 1, 2, 0.5, 2.5, 0.0);
    assert_row(&r, 2, 3, 1.0, -3.0, 0.0);
    result_free(&r);

    /* header = 0: a text first line is a bad row, not a header */
    o.header = 0;
    RUN_STR("time,accel\n0,1\n", &o, &r);
    assert_counts(&r, 2, 2, 1, 0, 0, 0);
    assert_rej(&r, 0, 1, "time (column 1) is not a number: \"time\"");
    result_free(&r);
}

static void test_header(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("time,accel\n0,1\n1,2\n", &o, &r);
    assert_counts(&r, 3, 2, 2, 0, 0, 1);
    assert_row(&r, 0, 2, 0.0, 1.0, 0.0);
    assert_row(&r, 1, 3, 1.0, 2.0, 0.0);
    result_free(&r);

    /* only the first line can be the header */
    RUN_STR("t,a\n0,1\nt,a\n1,2\n", &o, &r);
    assert_counts(&r, 4, 3, 2, 0, 0, 1);
    assert_rej(&r, 0, 3, "time (column 1) is not a number: \"t\"");
    result_free(&r);

    /* nor after a data row */
    RUN_STR("0,1\nt,a\n", &o, &r);
    assert_counts(&r, 2, 2, 1, 0, 0, 0);
    result_free(&r);

    /* header = 1: the first line is the header even if numeric */
    o.header = 1;
    RUN_STR("1,2\n3,4\n", &o, &r);
    assert_counts(&r, 2, 1, 1, 0, 0, 1);
    assert_row(&r, 0, 2, 3.0, 4.0, 0.0);
    result_free(&r);
}

static void test_header_only_and_empty(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("time,accel\n", &o, &r);
    assert_counts(&r, 1, 0, 0, 0, 0, 1);
    result_free(&r);
    RUN_STR("time,accel", &o, &r);
    assert_counts(&r, 1, 0, 0, 0, 0, 1);
    result_free(&r);
    run3("", 0, &o, &r);
    assert_counts(&r, 0, 0, 0, 0, 0, 0);
    result_free(&r);
    RUN_STR("\n\n# nothing here\n", &o, &r);
    assert_counts(&r, 3, 0, 0, 1, 2, 0);
    result_free(&r);
    /* named columns and no data at all: not an error */
    o.time_col = "time";
    o.accel_col = "accel";
    RUN_STR("# empty log\n", &o, &r);
    assert_counts(&r, 1, 0, 0, 1, 0, 0);
    result_free(&r);
}

static void test_delimiters(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("t;a\n0;1.5\n1;-2\n", &o, &r);
    assert_counts(&r, 3, 2, 2, 0, 0, 1);
    assert_row(&r, 1, 3, 1.0, -2.0, 0.0);
    result_free(&r);

    RUN_STR("t\ta\n0\t1.5\n1\t-2\n", &o, &r);
    assert_counts(&r, 3, 2, 2, 0, 0, 1);
    assert_row(&r, 0, 2, 0.0, 1.5, 0.0);
    result_free(&r);

    /* blanks around fields are dropped, as libcsv does */
    RUN_STR("0 , 1.5 \n 1 ,  -2\n", &o, &r);
    assert_counts(&r, 2, 2, 2, 0, 0, 0);
    assert_row(&r, 1, 2, 1.0, -2.0, 0.0);
    result_free(&r);
    /* a tab anywhere wins detection; tabs around fields need the delimiter given */
    o.header = 0;
    RUN_STR("0 ,\t1.5 \n", &o, &r);
    assert_rej(&r, 0, 1, "time (column 1) is not a number: \"0 ,\"");
    result_free(&r);
    o.delim = ',';
    o.header = -1;
    RUN_STR("0 ,\t1.5 \n 1\t, -2\t\n", &o, &r);
    assert_counts(&r, 2, 2, 2, 0, 0, 0);
    assert_row(&r, 1, 2, 1.0, -2.0, 0.0);
    result_free(&r);

    /* a given delimiter is used as given */
    o.delim = ';';
    RUN_STR("0;1\n1,2\n2;3\n", &o, &r);
    assert_counts(&r, 3, 3, 2, 0, 0, 0);
    assert_rej(&r, 0, 2, "time (column 1) is not a number (decimal comma?): \"1,2\"");
    result_free(&r);
    o.delim = ',';
    RUN_STR("0,1\n1\t2\n", &o, &r);
    assert_rej(&r, 0, 2, "time (column 1) is not a number: \"1?2\"");
    result_free(&r);

    /* no delimiter yet: a single column */
    o.delim = 0;
    RUN_STR("12345\n0,1\n", &o, &r);
    assert_counts(&r, 2, 2, 1, 0, 0, 0);
    assert_rej(&r, 0, 1, "expected at least 2 columns, found 1 (no ',' ';' or tab delimiter)");
    assert_row(&r, 0, 2, 0.0, 1.0, 0.0);
    result_free(&r);
}

static void test_crlf_bom_comments(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("time,accel\r\n0,1\r\n1,2\r\n", &o, &r);
    assert_counts(&r, 3, 2, 2, 0, 0, 1);
    assert_row(&r, 1, 3, 1.0, 2.0, 0.0);
    result_free(&r);

    /* the BOM must not stick to the first header name */
    o.time_col = "time";
    o.accel_col = "ACCEL";
    RUN_STR("\xEF\xBB\xBFtime,accel\r\n0,1\r\n", &o, &r);
    assert_counts(&r, 2, 1, 1, 0, 0, 1);
    result_free(&r);
    o = defaults();
    RUN_STR(
        "\xEF\xBB\xBF"
        "0,1\n",
        &o, &r);
    assert_counts(&r, 1, 1, 1, 0, 0, 0);
    result_free(&r);
    RUN_STR("\xEF\xBB\xBF# exported\n0,1\n", &o, &r);
    assert_counts(&r, 2, 1, 1, 1, 0, 0);
    result_free(&r);
    /* a BOM anywhere else is data */
    RUN_STR(
        "0,1\n\xEF\xBB\xBF"
        "1,2\n",
        &o, &r);
    assert_counts(&r, 2, 2, 1, 0, 0, 0);
    result_free(&r);

    const char *in =
        "# logger v2\n"  /* 1 */
        "  # indented\n" /* 2 */
        "\n"             /* 3 */
        "   \n"          /* 4 */
        "\t\r\n"         /* 5 */
        "time,accel\n"   /* 6 */
        "# mid-file\n"   /* 7 */
        "0,1\n"          /* 8 */
        "\n"             /* 9 */
        "1,2\n"          /* 10 */
        "#";             /* 11 */
    RUN_STR(in, &o, &r);
    assert_counts(&r, 11, 2, 2, 4, 4, 1);
    assert_row(&r, 0, 8, 0.0, 1.0, 0.0);
    assert_row(&r, 1, 10, 1.0, 2.0, 0.0);
    result_free(&r);
}

static void test_units_and_flip(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    o.accel_scale = 9.80665;
    o.vert_col = "3";
    RUN_STR("0,1,-1\n0.01,-0.5,0.25\n", &o, &r);
    assert_row(&r, 0, 1, 0.0, 9.80665, -9.80665);
    assert_row(&r, 1, 2, 0.01, -4.903325, 2.4516625);
    result_free(&r);

    o.flip = 1; /* longitudinal only */
    RUN_STR("0,1,-1\n", &o, &r);
    assert_row(&r, 0, 1, 0.0, -9.80665, -9.80665);
    result_free(&r);

    o = defaults();
    o.time_scale = 1e-3;
    RUN_STR("0,0\n1,0\n2500,0", &o, &r);
    assert_row(&r, 1, 2, 0.001, 0.0, 0.0);
    assert_row(&r, 2, 3, 2.5, 0.0, 0.0);
    result_free(&r);
    o.time_scale = 1e-6;
    RUN_STR("0,0\n1,0\n2500000,0", &o, &r);
    assert_row(&r, 1, 2, 1e-6, 0.0, 0.0);
    assert_row(&r, 2, 3, 2.5, 0.0, 0.0);
    result_free(&r);

    /* the time check is made in seconds: 1000 ms then 1 s */
    o.time_scale = 1e-3;
    RUN_STR("999,0\n1000,0\n1000.0,0\n", &o, &r);
    assert_counts(&r, 3, 3, 2, 0, 0, 0);
    assert_rej(&r, 0, 3, "duplicate time 1 s (same as the previous row)");
    result_free(&r);

    /* finite text that overflows once scaled */
    o = defaults();
    o.accel_scale = 9.80665;
    RUN_STR("0,1e308\n", &o, &r);
    assert_rej(&r, 0, 1, "accel (column 2) is out of range after unit conversion: \"1e308\"");
    result_free(&r);
}

static void test_columns(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    const char *in = "Accel X , t_s ,az\n1,0,9.8\n2,0.5,9.7\n";
    o.time_col = "T_S";      /* case-insensitive */
    o.accel_col = "accel x"; /* header field is trimmed */
    RUN_STR(in, &o, &r);
    assert_counts(&r, 3, 2, 2, 0, 0, 1);
    assert_row(&r, 0, 2, 0.0, 1.0, 0.0);
    assert_row(&r, 1, 3, 0.5, 2.0, 0.0);
    result_free(&r);

    o.vert_col = " AZ ";
    RUN_STR(in, &o, &r);
    assert_row(&r, 1, 3, 0.5, 2.0, 9.7);
    result_free(&r);

    /* by index, with and without the header */
    o = defaults();
    o.time_col = "2";
    o.accel_col = "1";
    o.vert_col = "3";
    RUN_STR(in, &o, &r);
    assert_counts(&r, 3, 2, 2, 0, 0, 1);
    assert_row(&r, 1, 3, 0.5, 2.0, 9.7);
    result_free(&r);
    RUN_STR("1,0,9.8\n2,0.5\n", &o, &r);
    assert_counts(&r, 2, 2, 1, 0, 0, 0);
    assert_rej(&r, 0, 2, "missing field: vertical (column 3); the line has 2 fields");
    result_free(&r);

    /* named vertical column with the other two by index */
    o.vert_col = "az";
    RUN_STR(in, &o, &r);
    assert_row(&r, 0, 2, 0.0, 1.0, 9.8);
    result_free(&r);

    /* reasons name the column by header name too */
    o = defaults();
    o.accel_col = "Accel X";
    o.time_col = "t_s";
    RUN_STR("Accel X,t_s\n1,0\nx,1\n", &o, &r);
    assert_rej(&r, 0, 3, "accel (column 1, \"Accel X\") is not a number: \"x\"");
    result_free(&r);
}

static void test_named_column_errors(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    o.accel_col = "acc";
    RUN_STR("t,a\n0,1\n", &o, &r);
    assert_int_equal(r.feed_rc, SW_ENOTFOUND);
    assert_string_equal(r.msg, "line 1: no column named \"acc\" (accel) in the header");
    assert_counts(&r, 1, 0, 0, 0, 0, 1);
    result_free(&r);

    /* a named column, but the first line is data */
    RUN_STR("# c\n0,1\n1,2\n", &o, &r);
    assert_int_equal(r.feed_rc, SW_ENOTFOUND);
    assert_string_equal(r.msg,
                        "line 2: column \"acc\" (accel) is named but the input has no header");
    assert_counts(&r, 2, 1, 0, 1, 0, 0);
    assert_rej(&r, 0, 2, "column \"acc\" (accel) is named but the input has no header");
    result_free(&r);

    /* header = 1 with a single-column header */
    o.header = 1;
    RUN_STR("acc\n0,1\n", &o, &r);
    assert_int_equal(r.feed_rc, SW_ENOTFOUND);
    result_free(&r);

    /* two roles on the same header field */
    o = defaults();
    o.time_col = "1";
    o.accel_col = "T";
    RUN_STR("t,a\n0,1\n", &o, &r);
    assert_int_equal(r.feed_rc, SW_EINVAL);
    assert_string_equal(r.msg, "line 1: time and accel are the same column (1)");
    result_free(&r);

    /* the error is sticky: later feeds do nothing.  The header is read
     * when the look-ahead ends (here at finish), and the error with it. */
    o.accel_col = "nope";
    result_t u = {0};
    sw_csv_t *c = sw_csv_create(&o, on_row, on_reject, &u, NULL, NULL, 0);
    assert_non_null(c);
    assert_int_equal(sw_csv_feed(c, "t,a\n", 4), SW_OK);
    assert_int_equal(sw_csv_feed(c, "0,1\n", 4), SW_OK);
    assert_int_equal(sw_csv_finish(c), SW_ENOTFOUND);
    assert_int_equal(sw_csv_feed(c, "0,1\n", 4), SW_ENOTFOUND);
    assert_int_equal(sw_csv_finish(c), SW_ENOTFOUND);
    assert_int_equal(u.nrows, 0);
    sw_csv_destroy(c);
}

/* The first lines are held until the layout is fixed: no row reaches the
 * caller before SW_CSV_AHEAD_ROWS data-like lines are in (or the input
 * ends), then they come in order with their own line numbers, and the
 * header's errors surface then. */
static void test_lookahead(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t u = {0};
    sw_csv_t *c = sw_csv_create(&o, on_row, on_reject, &u, NULL, NULL, 0);
    assert_non_null(c);
    char line[64];
    assert_int_equal(sw_csv_feed(c, "t,a\n# note\n", 11), SW_OK);
    /* the header and 254 rows: 255 data-like lines, all held */
    for (int i = 0; i < SW_CSV_AHEAD_ROWS - 2; i++) {
        const int k = snprintf(line, sizeof line, "%d,%d\n", i, -i);
        assert_int_equal(sw_csv_feed(c, line, (size_t)k), SW_OK);
    }
    sw_csv_layout_t L;
    assert_int_equal(sw_csv_layout(c, &L), SW_OK);
    assert_int_equal(L.ready, 0);
    assert_int_equal(u.nrows, 0);
    /* the 256th: the look-ahead is full, everything held is read */
    assert_int_equal(sw_csv_feed(c, "1000,5\n", 7), SW_OK);
    assert_int_equal(u.nrejs, 0);
    assert_int_equal(u.nrows, SW_CSV_AHEAD_ROWS - 1);
    assert_int_equal(sw_csv_layout(c, &L), SW_OK);
    assert_int_equal(L.ready, 1);
    assert_int_equal(L.has_header, 1);
    assert_int_equal(u.rows[0].line, 3); /* after the header and the comment */
    assert_true(u.rows[0].t == 0.0);
    assert_int_equal(u.rows[SW_CSV_AHEAD_ROWS - 3].line, SW_CSV_AHEAD_ROWS);
    assert_true(u.rows[SW_CSV_AHEAD_ROWS - 3].a == -(SW_CSV_AHEAD_ROWS - 3));
    assert_true(u.rows[SW_CSV_AHEAD_ROWS - 2].t == 1000.0);
    /* later rows go through at once */
    assert_int_equal(sw_csv_feed(c, "1001,6\n", 7), SW_OK);
    assert_int_equal(u.nrows, SW_CSV_AHEAD_ROWS);
    assert_int_equal(u.rows[SW_CSV_AHEAD_ROWS - 1].line, SW_CSV_AHEAD_ROWS + 2);
    assert_int_equal(sw_csv_finish(c), SW_OK);
    sw_csv_counts_t n;
    sw_csv_counts(c, &n);
    assert_int_equal(n.lines, SW_CSV_AHEAD_ROWS + 2);
    assert_int_equal(n.comments, 1);
    assert_int_equal(n.headers, 1);
    sw_csv_destroy(c);
    result_free(&u);

    /* a named column missing from the header: the error comes with the
     * look-ahead's end, and nothing after the header is counted */
    o.accel_col = "nope";
    c = sw_csv_create(&o, on_row, on_reject, &u, NULL, NULL, 0);
    assert_non_null(c);
    int rc = SW_OK;
    for (int i = 0; i <= SW_CSV_AHEAD_ROWS && rc == SW_OK; i++)
        rc = sw_csv_feed(c, i ? "1,2\n" : "t,a\n", 4);
    assert_int_equal(rc, SW_ENOTFOUND);
    assert_string_equal(sw_csv_error_message(c),
                        "line 1: no column named \"nope\" (accel) in the header");
    sw_csv_counts(c, &n);
    assert_int_equal(n.lines, 1);
    assert_int_equal(n.headers, 1);
    assert_int_equal(u.nrows, 0);
    sw_csv_destroy(c);
    result_free(&u);

    /* many comment lines end the look-ahead too */
    o = defaults();
    c = sw_csv_create(&o, on_row, on_reject, &u, NULL, NULL, 0);
    assert_non_null(c);
    assert_int_equal(sw_csv_feed(c, "t,a\n0,1\n", 8), SW_OK);
    for (int i = 0; i < SW_CSV_AHEAD_LINES - 2; i++)
        assert_int_equal(sw_csv_feed(c, "#\n", 2), SW_OK);
    assert_int_equal(u.nrows, 1);
    sw_csv_destroy(c);
    result_free(&u);
}

/* Options: delimiter, columns, scales, header; the rest zero. */
static sw_csv_opts_t mk(char delim, const char *tc, const char *ac, const char *vc, double ts,
                        double as, int header)
{
    sw_csv_opts_t o;
    memset(&o, 0, sizeof o);
    o.delim = delim;
    o.time_col = tc;
    o.accel_col = ac;
    o.vert_col = vc;
    o.time_scale = ts;
    o.accel_scale = as;
    o.header = header;
    return o;
}

static void test_bad_options(void **state)
{
    (void)state;
    struct {
        sw_csv_opts_t o;
        int err;
    } cases[] = {
        {mk('|', NULL, NULL, NULL, 0, 0, -1), SW_EINVAL},
        {mk(0, NULL, NULL, NULL, 0, 0, 2), SW_EINVAL},
        {mk(0, NULL, NULL, NULL, -1.0, 0, -1), SW_EINVAL},
        {mk(0, NULL, NULL, NULL, 0, NAN, -1), SW_EINVAL},
        {mk(0, NULL, NULL, NULL, 0, -9.80665, -1), SW_EINVAL},
        {mk(0, "0", NULL, NULL, 0, 0, -1), SW_EINVAL},
        {mk(0, "  ", NULL, NULL, 0, 0, -1), SW_EINVAL},
        {mk(0, "99999999999999999999", NULL, NULL, 0, 0, -1), SW_EINVAL},
        {mk(0, "2", NULL, NULL, 0, 0, -1), SW_EINVAL},      /* same as accel */
        {mk(0, "t", "T", NULL, 0, 0, -1), SW_EINVAL},       /* same name */
        {mk(0, NULL, NULL, "1", 0, 0, -1), SW_EINVAL},      /* vertical = time */
        {mk(0, "time", NULL, NULL, 0, 0, 0), SW_ENOTFOUND}, /* named, no header */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int err = 0;
        char msg[200] = "";
        sw_csv_t *c = sw_csv_create(&cases[i].o, NULL, NULL, NULL, &err, msg, sizeof msg);
        if (c)
            fail_msg("case %zu accepted", i);
        assert_int_equal(err, cases[i].err);
        assert_true(msg[0] != '\0');
        /* and without err/msg */
        assert_null(sw_csv_create(&cases[i].o, NULL, NULL, NULL, NULL, NULL, 0));
    }
    /* NULL options are the defaults; NULL callbacks are fine */
    sw_csv_t *c = sw_csv_create(NULL, NULL, NULL, NULL, NULL, NULL, 0);
    assert_non_null(c);
    assert_int_equal(sw_csv_feed(c, "t,a\n0,1\n1", 9), SW_OK);
    assert_int_equal(sw_csv_finish(c), SW_OK);
    assert_int_equal(sw_csv_finish(c), SW_OK);
    assert_int_equal(sw_csv_feed(c, "2,3\n", 4), SW_EINVAL); /* after finish */
    sw_csv_counts_t n;
    sw_csv_counts(c, &n);
    assert_int_equal(n.accepted, 1);
    assert_int_equal(n.lines, 3);
    sw_csv_destroy(c);
    sw_csv_destroy(NULL);
    assert_int_equal(sw_csv_feed(NULL, "x", 1), SW_EINVAL);
}

/* Issue 24: a logger export with lines about the recording before its
 * header was read with the header as a bad row and default units on a g
 * column.  The preamble is skipped and counted, the header read. */
static void test_preamble(void **state)
{
    (void)state;
    const char *in =
        "Shock recorder export\r\n"      /* 1 */
        "Instrument:,SR-3X\r\n"          /* 2 */
        "Serial Number:,10427\r\n"       /* 3 */
        "\r\n"                           /* 4: a blank line stays a blank line */
        "Trigger:,X axis 0.50 G\r\n"     /* 5 */
        "# exported with defaults\r\n"   /* 6: and a comment a comment */
        "Sample Rate:,1000 Hz\r\n"       /* 7 */
        "Time (s),X (G),Y (G),Z (G)\r\n" /* 8 */
        "0.000,0.01,0.00,1.00\r\n"
        "0.001,-0.50,0.01,1.01\r\n"
        "0.002,-0.25,0.00,0.99\r\n";
    sw_csv_opts_t o = defaults();
    o.infer = 1;
    result_t r;
    RUN_STR(in, &o, &r);
    assert_int_equal(r.feed_rc, SW_OK);
    assert_counts(&r, 11, 3, 3, 1, 1, 1);
    assert_int_equal(r.counts.preamble, 5);
    assert_row(&r, 1, 10, 0.001, -0.50 * 9.80665, 0.0);
    result_free(&r);
    /* the layout says where the table starts, and why */
    int err;
    sw_csv_t *c = sw_csv_create(&o, NULL, NULL, NULL, &err, NULL, 0);
    assert_non_null(c);
    assert_int_equal(sw_csv_feed(c, in, strlen(in)), SW_OK);
    assert_int_equal(sw_csv_finish(c), SW_OK);
    sw_csv_layout_t L;
    assert_int_equal(sw_csv_layout(c, &L), SW_OK);
    assert_int_equal(L.preamble, 5);
    assert_int_equal(L.preamble_from, SW_CSV_FROM_VALUES);
    assert_int_equal(L.first_line, 8);
    assert_string_equal(L.name[1], "X (G)");
    assert_int_equal(L.unit[1], SW_CSV_UNIT_G);
    sw_csv_destroy(c);

    /* skip_lines: the first N physical lines, whatever they are */
    o.skip_lines = 7;
    RUN_STR(in, &o, &r);
    assert_int_equal(r.feed_rc, SW_OK);
    assert_counts(&r, 11, 3, 3, 0, 0, 1);
    assert_int_equal(r.counts.preamble, 7);
    result_free(&r);
    /* too few: the last metadata line is taken for the header */
    o.skip_lines = 6;
    RUN_STR(in, &o, &r);
    assert_int_equal(r.feed_rc, SW_EAMBIGUOUS);
    result_free(&r);
    /* none: as before the preamble was known, every line of it and the
     * table's header are rows refused */
    o.skip_lines = -1;
    o.infer = 0;
    RUN_STR(in, &o, &r);
    assert_int_equal(r.feed_rc, SW_OK);
    assert_int_equal(r.counts.preamble, 0);
    assert_counts(&r, 11, 9, 3, 1, 1, 0);
    assert_rej(&r, 0, 1, "expected at least 2 columns, found 1 (no ',' ';' or tab delimiter)");
    assert_rej(&r, 5, 8, "time (column 1) is not a number: \"Time (s)\"");
    result_free(&r);
}

static void test_bad_row_in_the_middle(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("time,accel\n0,1\n0.1,abc\n0.2,3\n0.3\n0.4,4,extra\n", &o, &r);
    assert_counts(&r, 6, 5, 3, 0, 0, 1);
    assert_rej(&r, 0, 3, "accel (column 2) is not a number: \"abc\"");
    assert_rej(&r, 1, 5, "missing field: accel (column 2); the line has 1 field");
    assert_row(&r, 0, 2, 0.0, 1.0, 0.0);
    assert_row(&r, 1, 4, 0.2, 3.0, 0.0);
    assert_row(&r, 2, 6, 0.4, 4.0, 0.0);
    result_free(&r);

    /* long offending text is cut in the reason; control bytes are masked */
    RUN_STR("0,0123456789012345678901234567890123456789TAIL\n1,\x01\x7f\xc3\xa9\n", &o, &r);
    assert_rej(&r, 0, 1,
               "accel (column 2) is not a number: "
               "\"0123456789012345678901234567890123456789...\"");
    assert_rej(&r, 1, 2, "accel (column 2) is not a number: \"????\"");
    result_free(&r);
}

static void test_time_order(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("1.235,0\n1.234,0\n1.235,0\n1.236,0\n3601.236,0\n", &o, &r);
    assert_counts(&r, 5, 5, 3, 0, 0, 0);
    assert_rej(&r, 0, 2, "time 1.234 s not after previous 1.235 s");
    assert_rej(&r, 1, 3, "duplicate time 1.235 s (same as the previous row)");
    assert_row(&r, 1, 4, 1.236, 0.0, 0.0);
    assert_row(&r, 2, 5, 3601.236, 0.0, 0.0); /* an hour's gap is not an error */
    result_free(&r);

    /* a rejected row does not become the reference */
    RUN_STR("0,0\n5,abc\n1,0\n", &o, &r);
    assert_counts(&r, 3, 3, 2, 0, 0, 0);
    result_free(&r);

    /* any_order: every row goes on, in the order read, for a consumer that
     * judges time itself (the input gate) */
    o.any_order = 1;
    RUN_STR("1.235,0\n1.234,0\n1.235,0\n900.1,0\n1.236,0\n", &o, &r);
    assert_counts(&r, 5, 5, 5, 0, 0, 0);
    assert_row(&r, 1, 2, 1.234, 0.0, 0.0);
    assert_row(&r, 3, 4, 900.1, 0.0, 0.0);
    assert_row(&r, 4, 5, 1.236, 0.0, 0.0);
    result_free(&r);
}

/* A first line with a corrupt time but a number beside it is a data row,
 * reported with its line; it must not vanish as a "header".  A header's
 * names hold no number, or no digit in the time field's. */
static void test_corrupt_first_row(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("0.00O,-9\n0.001,-9\n", &o, &r);
    assert_counts(&r, 2, 2, 1, 0, 0, 0);
    assert_rej(&r, 0, 1, "time (column 1) is not a number: \"0.00O\"");
    result_free(&r);

    RUN_STR("t,1\n0,2\n", &o, &r); /* a header whose second name is a number */
    assert_counts(&r, 2, 1, 1, 0, 0, 1);
    result_free(&r);

    RUN_STR("time1,accel2\n0,2\n", &o, &r); /* digits in names, no number: a header */
    assert_counts(&r, 2, 1, 1, 0, 0, 1);
    result_free(&r);
}

static void test_refused_by_consumer(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    const char *in = "0,0\n2,0\n1,0\n";
    run3r(in, strlen(in), &o, 2, &r);
    assert_counts(&r, 3, 3, 2, 0, 0, 0);
    assert_rej(&r, 0, 2, "refused by consumer");
    assert_row(&r, 1, 3, 1.0, 0.0, 0.0); /* compared with the last accepted time */
    result_free(&r);
}

static void test_quoting(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    const char *in =
        "\"time\",\"accel\"\n" /* 1 */
        "\"0\",\"1.5\"\n"      /* 2 */
        "\" 0.5 \", 2\n"       /* 3: blanks inside quotes are allowed */
        "1,\"2\"\"\"\n"        /* 4: 2" */
        "2,3,\"a,b\"\"c\"\n"   /* 5: quoted unused field */
        "3,1\"2\n"             /* 6: quote inside unquoted field */
        "4,\"1\"x\n"           /* 7: text after closing quote */
        "5,\"1\n"              /* 8: unterminated */
        "6,\"7\"\n"            /* 9: the parser recovered */
        "\"7\",8\r\n"          /* 10 */
        "8,\"9\r\n"            /* 11: unterminated, CRLF */
        "9,\"10\"";            /* 12 */
    RUN_STR(in, &o, &r);
    assert_counts(&r, 12, 11, 6, 0, 0, 1);
    assert_row(&r, 0, 2, 0.0, 1.5, 0.0);
    assert_row(&r, 1, 3, 0.5, 2.0, 0.0);
    assert_row(&r, 2, 5, 2.0, 3.0, 0.0);
    assert_row(&r, 3, 9, 6.0, 7.0, 0.0);
    assert_row(&r, 4, 10, 7.0, 8.0, 0.0);
    assert_row(&r, 5, 12, 9.0, 10.0, 0.0);
    assert_rej(&r, 0, 4, "accel (column 2) is not a number: \"2\"\"");
    assert_rej(&r, 1, 6, "malformed quoting in field 2 at \"\"2\"");
    assert_rej(&r, 2, 7, "malformed quoting in field 2 at \"x\"");
    assert_rej(&r, 3, 8, "unterminated quote in field 2");
    assert_rej(&r, 4, 11, "unterminated quote in field 2");
    result_free(&r);

    /* quoted header names in a ';' file with a named column */
    o.time_col = "Time [ms]";
    o.accel_col = "acc x [g]";
    RUN_STR("\"Time [ms]\";\"Acc X [g]\"\n\"0\";\"1,5\"\n1;\"2\"\n", &o, &r);
    assert_counts(&r, 3, 2, 1, 0, 0, 1);
    assert_rej(&r, 0, 2,
               "accel (column 2, \"acc x [g]\") is not a number (decimal comma?): \"1,5\"");
    result_free(&r);

    /* a quoted ',' does not make ',' the delimiter */
    o = defaults();
    RUN_STR("\"time, s\";\"accel\"\n0;1\n", &o, &r);
    assert_counts(&r, 2, 1, 1, 0, 0, 1);
    result_free(&r);
}

static void test_decimal_comma(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("t;a\n0,001;-3,5\n0.002;-3.5\n0.003;-3,5\n", &o, &r);
    assert_counts(&r, 4, 3, 1, 0, 0, 1);
    assert_rej(&r, 0, 2, "time (column 1) is not a number (decimal comma?): \"0,001\"");
    assert_rej(&r, 1, 4, "accel (column 2) is not a number (decimal comma?): \"-3,5\"");
    assert_row(&r, 0, 3, 0.002, -3.5, 0.0);
    result_free(&r);

    /* without a header: ';' wins over ',' */
    RUN_STR("0,001;-3,5\n", &o, &r);
    assert_counts(&r, 1, 1, 0, 0, 0, 0);
    result_free(&r);
    o.header = 0;
    RUN_STR("0,001\t-3,5\n", &o, &r);
    assert_rej(&r, 0, 1, "time (column 1) is not a number (decimal comma?): \"0,001\"");
    result_free(&r);
}

static void test_not_numbers(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    const char *in =
        "0,nan\n"       /* 1 */
        "1,inf\n"       /* 2 */
        "2,-Infinity\n" /* 3 */
        "3,1e400\n"     /* 4 */
        "4,1.0x\n"      /* 5 */
        "5,\n"          /* 6 */
        "6,  \n"        /* 7 */
        "7,0x10\n"      /* 8 */
        "8,1e\n"        /* 9 */
        "9,--1\n"       /* 10 */
        "10,1e-400\n"   /* 11: underflow is zero, accepted */
        "11,+.5e1\n"    /* 12 */
        "NaN,1\n"       /* 13 */
        "1e999,1\n"     /* 14 */
        "12,\"\"\n";    /* 15 */
    o.header = 0;
    RUN_STR(in, &o, &r);
    assert_counts(&r, 15, 15, 2, 0, 0, 0);
    assert_rej(&r, 0, 1, "accel (column 2) is not a number: \"nan\"");
    assert_rej(&r, 1, 2, "accel (column 2) is not a number: \"inf\"");
    assert_rej(&r, 2, 3, "accel (column 2) is not a number: \"-Infinity\"");
    assert_rej(&r, 3, 4, "accel (column 2) is out of range: \"1e400\"");
    assert_rej(&r, 4, 5, "accel (column 2) is not a number: \"1.0x\"");
    assert_rej(&r, 5, 6, "accel (column 2) is empty");
    assert_rej(&r, 6, 7, "accel (column 2) is empty");
    assert_rej(&r, 7, 8, "accel (column 2) is not a number: \"0x10\"");
    assert_rej(&r, 8, 9, "accel (column 2) is not a number: \"1e\"");
    assert_rej(&r, 9, 10, "accel (column 2) is not a number: \"--1\"");
    assert_rej(&r, 10, 13, "time (column 1) is not a number: \"NaN\"");
    assert_rej(&r, 11, 14, "time (column 1) is out of range: \"1e999\"");
    assert_rej(&r, 12, 15, "accel (column 2) is empty");
    assert_row(&r, 0, 11, 10.0, 0.0, 0.0);
    assert_row(&r, 1, 12, 11.0, 5.0, 0.0);
    result_free(&r);
}

/* Lines at, just over and far over the limit. */
static void test_long_lines(void **state)
{
    (void)state;
    const size_t max = SW_CSV_MAX_LINE;
    size_t cap = 8 * max;
    char *in = malloc(cap);
    assert_non_null(in);
    size_t n = 0;
    n += (size_t)sprintf(in + n, "time,accel\n0,1\n"); /* 1, 2 */
    n += (size_t)sprintf(in + n, "1,");                /* 3: 2 MB */
    memset(in + n, '7', 2 * max);
    n += 2 * max;
    in[n++] = '\n';
    n += (size_t)sprintf(in + n, "2,2\n# "); /* 4, 5: 2 MB comment */
    memset(in + n, 'c', 2 * max);
    n += 2 * max;
    in[n++] = '\n';
    size_t start = n; /* 6: exactly max */
    n += (size_t)sprintf(in + n, "3,3");
    memset(in + n, ' ', max - (n - start));
    n = start + max;
    in[n++] = '\r'; /* CRLF does not count */
    in[n++] = '\n';
    start = n; /* 7: max + 1 */
    n += (size_t)sprintf(in + n, "4,4");
    memset(in + n, ' ', max + 1 - (n - start));
    n = start + max + 1;
    in[n++] = '\n';
    n += (size_t)sprintf(in + n, "5,5\n"); /* 8 */
    start = n;                             /* 9: long, no newline */
    memset(in + n, '1', max + 10);
    n += max + 10;
    assert_true(n <= cap);

    sw_csv_opts_t o = defaults();
    result_t r;
    run3(in, n, &o, &r);
    assert_counts(&r, 9, 7, 4, 1, 0, 1);
    assert_rej(&r, 0, 3, "line longer than 1048576 bytes");
    assert_rej(&r, 1, 7, "line longer than 1048576 bytes");
    assert_rej(&r, 2, 9, "line longer than 1048576 bytes");
    assert_row(&r, 0, 2, 0.0, 1.0, 0.0);
    assert_row(&r, 1, 4, 2.0, 2.0, 0.0);
    assert_row(&r, 2, 6, 3.0, 3.0, 0.0);
    assert_row(&r, 3, 8, 5.0, 5.0, 0.0);
    result_free(&r);

    /* a long quoted field within the limit goes through libcsv */
    n = 0;
    n += (size_t)sprintf(in + n, "0,1,\"");
    memset(in + n, 'q', max - 100);
    n += max - 100;
    n += (size_t)sprintf(in + n, "\"\n1,2\n");
    run(in, n, &o, 0, -1, &r);
    assert_counts(&r, 2, 2, 2, 0, 0, 0);
    result_free(&r);
    free(in);
}

static void test_many_columns(void **state)
{
    (void)state;
    const int ncol = 5000;
    size_t cap = 200000;
    char *in = malloc(cap);
    assert_non_null(in);
    size_t n = 0;
    for (int k = 1; k <= ncol; k++) n += (size_t)sprintf(in + n, "%sc%d", k > 1 ? "," : "", k);
    in[n++] = '\n';
    for (int row = 0; row < 3; row++) {
        for (int k = 1; k <= ncol; k++)
            n += (size_t)sprintf(in + n, "%s%d.%d", k > 1 ? "," : "", row, k);
        in[n++] = '\n';
    }
    assert_true(n < cap);

    sw_csv_opts_t o = defaults();
    o.time_col = "C4999";
    o.accel_col = "5000";
    o.vert_col = "c1";
    result_t r;
    run3(in, n, &o, &r);
    assert_counts(&r, 4, 3, 3, 0, 0, 1);
    assert_row(&r, 0, 2, 0.4999, 0.5, 0.1);
    assert_row(&r, 2, 4, 2.4999, 2.5, 2.1);
    result_free(&r);

    o = defaults();
    o.time_col = "4999";
    o.accel_col = "3";
    run3(in, n, &o, &r);
    assert_counts(&r, 4, 3, 3, 0, 0, 1);
    assert_row(&r, 1, 3, 1.4999, 1.3, 0.0);
    result_free(&r);

    o.accel_col = "5001";
    run3(in, n, &o, &r);
    assert_counts(&r, 4, 3, 0, 0, 0, 1);
    assert_rej(&r, 0, 2, "missing field: accel (column 5001); the line has 5000 fields");
    result_free(&r);
    free(in);
}

static void test_truncated_last_line(void **state)
{
    (void)state;
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("0,1\n1,2", &o, &r);
    assert_counts(&r, 2, 2, 2, 0, 0, 0);
    assert_row(&r, 1, 2, 1.0, 2.0, 0.0);
    result_free(&r);
    RUN_STR("0,1\n1,2\r", &o, &r);
    assert_row(&r, 1, 2, 1.0, 2.0, 0.0);
    result_free(&r);
    RUN_STR("0,1\n1,", &o, &r);
    assert_rej(&r, 0, 2, "accel (column 2) is empty");
    result_free(&r);
    /* '\r' in mid-line is data (old Mac line ends are not supported) */
    RUN_STR("0,1\r1,2\n", &o, &r);
    assert_rej(&r, 0, 1, "accel (column 2) is not a number: \"1?1\"");
    result_free(&r);
}

static void test_fixtures(void **state)
{
    (void)state;
    size_t len;
    char *in = read_fixture("logger-export.csv", &len);
    sw_csv_opts_t o = defaults();
    o.time_col = "time [ms]";
    o.accel_col = "Acc X [g]";
    o.vert_col = "Acc Z [g]";
    o.time_scale = 1e-3;
    o.accel_scale = 9.80665;
    result_t r;
    run3(in, len, &o, &r);
    assert_counts(&r, 11, 7, 5, 2, 1, 1);
    assert_rej(&r, 0, 8,
               "accel (column 2, \"Acc X [g]\") is not a number (decimal comma?): \"0,750\"");
    assert_rej(&r, 1, 10, "duplicate time 0.04 s (same as the previous row)");
    assert_row(&r, 0, 5, 0.0, 0.010 * 9.80665, 1.001 * 9.80665);
    assert_row(&r, 2, 7, 0.020, 0.5 * 9.80665, 1.012 * 9.80665);
    assert_row(&r, 4, 11, 0.050, 0.1 * 9.80665, 1.003 * 9.80665);
    result_free(&r);
    free(in);

    in = read_fixture("tab-no-final-newline.tsv", &len);
    o = defaults();
    o.vert_col = "vert";
    o.flip = 1;
    run3(in, len, &o, &r);
    assert_counts(&r, 6, 5, 4, 0, 0, 1);
    assert_rej(&r, 0, 4, "accel (column 2) is not a number: \"nan\"");
    assert_row(&r, 1, 3, 0.001, -0.15, -0.02);
    assert_row(&r, 3, 6, 0.004, -0.30, 0.02);
    result_free(&r);
    free(in);
}

/* Random bytes, uniform and biased towards CSV syntax: no crash, the three
 * chunkings agree, the invariants hold (checked in run). */
static void test_garbage(void **state)
{
    (void)state;
    static const char syntax[] = ",;\t\"\r\n #0123456789.-eE \0\xEF\xBB\xBF";
    uint64_t seed = 0x9E3779B97F4A7C15ULL;
    size_t cap = 1 << 16;
    char *in = malloc(cap);
    assert_non_null(in);
    for (int iter = 0; iter < 60; iter++) {
        size_t n = (size_t)(rnd(&seed) % (iter < 30 ? 2000 : cap));
        for (size_t i = 0; i < n; i++) {
            uint64_t x = rnd(&seed);
            in[i] = (iter & 1) ? (char)(x >> 24) : syntax[(x >> 24) % (sizeof syntax - 1)];
        }
        sw_csv_opts_t o = defaults();
        o.delim = (iter % 3 == 0) ? 0 : (iter % 3 == 1) ? ',' : '\t';
        o.header = (int)(iter % 3) - 1;
        o.vert_col = (iter & 2) ? "3" : NULL;
        result_t r;
        run3(in, n, &o, &r);
        result_free(&r);
    }
    free(in);
}

/* Lines without a quote are split directly, lines with one go through
 * libcsv: for the same fields both must give the same rows and reasons.
 * The two inputs differ only in an unused third field, bare or quoted. */
static void test_fast_path_matches_libcsv(void **state)
{
    (void)state;
    static const char *const vocab[] = {
        "1.5", " 2 ", "\t3\t", "",     "  ",      "abc",    "1.0x",  "nan", "-0",   "1e5",
        "1,5", "7",   "8.25",  " -9 ", "1e400",   "+4",     "0.001", "x y", "\x01", "3\r4",
        "5.",  ".5",  "12",    "100",  "-2.5e-3", "  42  ", "1 2",   "e",   "\xff", "99"};
    static const char delims[] = {',', ';', '\t'};
    const size_t nv = sizeof vocab / sizeof vocab[0];
    uint64_t seed = 12345;
    size_t cap = 1 << 16;
    char *plain = malloc(cap), *quoted = malloc(cap);
    assert_non_null(plain);
    assert_non_null(quoted);
    for (int iter = 0; iter < 30; iter++) {
        char d = delims[iter % 3];
        size_t a = 0, b = 0;
        if (iter % 2) {
            a += (size_t)sprintf(plain + a, " Time %c accel%cx\n", d, d);
            b += (size_t)sprintf(quoted + b, " Time %c accel%c\"x\"\n", d, d);
        }
        for (int line = 0; line < 200; line++) {
            const char *f1 = vocab[rnd(&seed) % nv], *f2 = vocab[rnd(&seed) % nv];
            /* CRLF, a trailing empty field, or LF */
            char end[3] = {'\n', 0, 0};
            uint64_t kind = rnd(&seed) % 4;
            if (kind == 0)
                end[0] = '\r', end[1] = '\n';
            if (kind == 1)
                end[0] = d, end[1] = '\n';
            a += (size_t)sprintf(plain + a, "%s%c%s%cu%s", f1, d, f2, d, end);
            b += (size_t)sprintf(quoted + b, "%s%c%s%c\"u\"%s", f1, d, f2, d, end);
        }
        assert_true(a < cap && b < cap);
        sw_csv_opts_t o = defaults();
        o.delim = d; /* the vocabulary holds tabs and commas: detection is tested elsewhere */
        if (iter % 2 && iter % 4 == 1) {
            o.time_col = "time";
            o.accel_col = "ACCEL";
        }
        result_t ra, rb;
        run3(plain, a, &o, &ra);
        run3(quoted, b, &o, &rb);
        if (ra.counts.accepted == 0 || ra.counts.rejected == 0)
            fail_msg("iter %d: %ld accepted, %ld rejected", iter, ra.counts.accepted,
                     ra.counts.rejected);
        assert_same(&ra, &rb);
        result_free(&ra);
        result_free(&rb);
    }
    free(plain);
    free(quoted);
}

/* Plain decimals are converted without strtod when that is exact: the
 * values must still be strtod's, bit for bit, for every form of number. */
static void test_numbers_match_strtod(void **state)
{
    (void)state;
    const int nlines = 20000;
    size_t cap = (size_t)nlines * 80;
    char *in = malloc(cap);
    char(*text)[64] = malloc((size_t)nlines * sizeof *text);
    assert_non_null(in);
    assert_non_null(text);
    uint64_t seed = 777;
    size_t n = 0;
    for (int i = 0; i < nlines; i++) {
        char *t = text[i];
        int k = 0;
        uint64_t x = rnd(&seed);
        static const char signs[] = {0, '+', '-', 0};
        if (signs[x % 4])
            t[k++] = signs[x % 4];
        int idig = (int)(rnd(&seed) % 21), fdig = (int)(rnd(&seed) % 21);
        if (rnd(&seed) % 4 == 0)
            idig = fdig = (int)(rnd(&seed) % 4); /* short ones too */
        for (int j = 0; j < idig; j++) t[k++] = (char)('0' + rnd(&seed) % 10);
        if (fdig || rnd(&seed) % 2) {
            t[k++] = '.';
            for (int j = 0; j < fdig; j++) t[k++] = (char)('0' + rnd(&seed) % 10);
        }
        if (!idig && !fdig)
            t[k++] = '7';
        if (rnd(&seed) % 3 == 0) {
            t[k++] = rnd(&seed) % 2 ? 'e' : 'E';
            if (rnd(&seed) % 2)
                t[k++] = rnd(&seed) % 2 ? '-' : '+';
            k += sprintf(t + k, "%d", (int)(rnd(&seed) % (rnd(&seed) % 4 ? 30 : 400)));
        }
        t[k] = '\0';
        n += (size_t)sprintf(in + n, "%d,%s\n", i, t);
    }
    assert_true(n < cap);
    sw_csv_opts_t o = defaults();
    o.header = 0;
    result_t r;
    run(in, n, &o, 0, -1, &r);
    size_t next = 0;
    for (int i = 0; i < nlines; i++) {
        double want = strtod(text[i], NULL);
        if (!isfinite(want))
            continue; /* rejected: out of range */
        if (next >= r.nrows || r.rows[next].line != i + 1)
            fail_msg("\"%s\" (line %d) was not accepted", text[i], i + 1);
        if (memcmp(&r.rows[next].a, &want, sizeof want))
            fail_msg("\"%s\": %.17g, strtod gives %.17g", text[i], r.rows[next].a, want);
        next++;
    }
    assert_int_equal(next, r.nrows);
    result_free(&r);
    free(in);
    free(text);
}

/* Numbers use '.' whatever LC_NUMERIC says (only checked where a
 * decimal-comma locale is installed). */
static void test_locale(void **state)
{
    (void)state;
    static const char *const names[] = {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "de_DE"};
    const char *got = NULL;
    for (size_t i = 0; i < sizeof names / sizeof names[0] && !got; i++)
        got = setlocale(LC_NUMERIC, names[i]);
    if (!got)
        skip();
    sw_csv_opts_t o = defaults();
    result_t r;
    RUN_STR("0.5,1.25\n", &o, &r);
    setlocale(LC_NUMERIC, "C");
    assert_row(&r, 0, 1, 0.5, 1.25, 0.0);
    result_free(&r);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_header),
        cmocka_unit_test(test_header),
        cmocka_unit_test(test_header_only_and_empty),
        cmocka_unit_test(test_delimiters),
        cmocka_unit_test(test_crlf_bom_comments),
        cmocka_unit_test(test_units_and_flip),
        cmocka_unit_test(test_columns),
        cmocka_unit_test(test_named_column_errors),
        cmocka_unit_test(test_lookahead),
        cmocka_unit_test(test_preamble),
        cmocka_unit_test(test_bad_options),
        cmocka_unit_test(test_bad_row_in_the_middle),
        cmocka_unit_test(test_time_order),
        cmocka_unit_test(test_corrupt_first_row),
        cmocka_unit_test(test_refused_by_consumer),
        cmocka_unit_test(test_quoting),
        cmocka_unit_test(test_decimal_comma),
        cmocka_unit_test(test_not_numbers),
        cmocka_unit_test(test_numbers_match_strtod),
        cmocka_unit_test(test_long_lines),
        cmocka_unit_test(test_many_columns),
        cmocka_unit_test(test_truncated_last_line),
        cmocka_unit_test(test_fixtures),
        cmocka_unit_test(test_garbage),
        cmocka_unit_test(test_fast_path_matches_libcsv),
        cmocka_unit_test(test_locale),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
