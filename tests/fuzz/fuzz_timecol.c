/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_timecol.c - libFuzzer target for the time-column inference of the
 * CSV reader: a log's header and first rows read with infer on (the
 * columns and units from the names, epochs by magnitude, date-times with
 * the day and the month in either order; docs/input.md), and the stages
 * that decide it on their own (csv_time.c, csv_infer.c).
 *
 * Input: 2 bytes of options (date order, delimiter, header, decimal comma,
 * preamble; which columns the caller gives), then the text (at most
 * MAX_TEXT bytes: the look-ahead the layout is decided on, and a few rows).
 *
 * Checks, through the reader (csv.h): only the documented results; a
 * refusal says why; a layout has distinct columns, each one the header chose
 * among the header's fields (its name is that field's), units of the
 * role's table (time: s, ms, us, ns, date-time; acceleration: m/s^2, g,
 * mg) at their own scale, the date order given when one was given, and a
 * unit the header names never silently replaced by a default; every row
 * delivered is finite and later than the one before.
 *
 * Checks of the stages, on every field of the text: a date-time that is
 * read has fields in range, and its time since 1970 is the one glibc's
 * timegm() gives for them (an independent calendar), in either order of
 * day and month exactly when the date exists in it; a number's epoch unit
 * puts it between 2000 and 2100, and no unit does when none is given; the
 * header's fields guessed into columns give distinct columns in range or
 * a reason. */
#define _GNU_SOURCE /* timegm */
#include <time.h>

#include "csv_int.h"
#include "fuzz.h"
#include "swaywatch/status.h"

#define MAX_TEXT 4096  /* bytes of text read */
#define MAX_FIELDS 256 /* fields of the text checked by the stages */

/* 2000-01-01 and 2100-01-01 in s since 1970 (date -u -d 2000-01-01 +%s) */
#define EPOCH_LO 946684800.0
#define EPOCH_HI 4102444800.0

typedef struct {
    long rows;
    int have_t;
    double last_t;
} rows_t;

static int on_row(void *user, long line, double t, double a, double z)
{
    rows_t *r = user;
    FZ_CHECK(line >= 1);
    FZ_CHECK(isfinite(t) && isfinite(a) && isfinite(z));
    FZ_CHECK(!r->have_t || t > r->last_t);
    r->have_t = 1;
    r->last_t = t;
    r->rows++;
    return 0;
}

static void on_reject(void *user, long line, const char *reason)
{
    (void)user;
    FZ_CHECK(line >= 1 && reason && reason[0]);
}

static int is_time_unit(int u)
{
    return u == SW_CSV_UNIT_S || u == SW_CSV_UNIT_MS || u == SW_CSV_UNIT_US ||
           u == SW_CSV_UNIT_NS || u == SW_CSV_UNIT_DATETIME;
}

static int is_accel_unit(int u)
{
    return u == SW_CSV_UNIT_MPS2 || u == SW_CSV_UNIT_G || u == SW_CSV_UNIT_MG;
}

static int is_from(int f)
{
    return f == SW_CSV_FROM_DEFAULT || f == SW_CSV_FROM_OPTION || f == SW_CSV_FROM_HEADER ||
           f == SW_CSV_FROM_VALUES;
}

/* The layout of a reader that fixed one. */
static void check_layout(const sw_csv_t *c, const sw_csv_layout_t *L, const sw_csv_opts_t *o)
{
    FZ_CHECK(L->col[0] >= 0 && L->col[1] >= 0 && L->col[0] != L->col[1]);
    FZ_CHECK(L->col[2] < 0 || (L->col[2] != L->col[0] && L->col[2] != L->col[1]));
    const long nh = sw_csv_header_count(c);
    for (int r = 0; r < 2; r++) {
        FZ_CHECK(is_from(L->col_from[r]) && is_from(L->unit_from[r]));
        if (L->col_from[r] == SW_CSV_FROM_HEADER) {
            /* a column the header chose is one of its fields, by name */
            FZ_CHECK(L->has_header && o->infer);
            FZ_CHECK(L->col[r] < nh);
            FZ_CHECK(strcmp(L->name[r], sw_csv_header_field(c, L->col[r])) == 0);
        }
        FZ_CHECK(memchr(L->name[r], '\0', sizeof L->name[r]) != NULL);
        /* every scale is a unit's of the role's table (no scale is given) */
        FZ_CHECK(r == 0 ? is_time_unit(L->unit[r]) : is_accel_unit(L->unit[r]));
        FZ_CHECK(isfinite(L->scale[r]) && L->scale[r] > 0.0);
        FZ_CHECK(L->scale[r] == sw_csv_unit_scale(L->unit[r]));
        FZ_CHECK(sw_csv_unit_name(L->unit[r])[0] != '\0');
        /* a unit the header names is never replaced by a default */
        const int hu = L->header_unit[r];
        FZ_CHECK(hu == SW_CSV_UNIT_NONE || (r == 0 ? is_time_unit(hu) : is_accel_unit(hu)));
        if (o->infer && L->has_header && hu != SW_CSV_UNIT_NONE && hu != L->unit[r])
            FZ_CHECK(L->unit_from[r] == SW_CSV_FROM_OPTION ||
                     L->unit_from[r] == SW_CSV_FROM_VALUES);
    }
    FZ_CHECK(L->date_order == SW_CSV_DATE_AUTO || L->date_order == SW_CSV_DATE_DMY ||
             L->date_order == SW_CSV_DATE_MDY);
    /* an order given is the order used */
    if (o->date_order != SW_CSV_DATE_AUTO && L->date_order != SW_CSV_DATE_AUTO)
        FZ_CHECK(L->date_order == o->date_order);
    FZ_CHECK(L->preamble >= 0 && L->first_line >= 1);
    FZ_CHECK(L->delim == ',' || L->delim == ';' || L->delim == '\t' || L->delim == 0);
}

/* The reader, with infer on, over the whole text. */
static void run_reader(const sw_csv_opts_t *o, const uint8_t *text, size_t len)
{
    rows_t rows = {0, 0, 0.0};
    int err = 0;
    char msg[256];
    sw_csv_t *c = sw_csv_create(o, on_row, on_reject, &rows, &err, msg, sizeof msg);
    if (!c) { /* a column given that is the other's default */
        FZ_CHECK((err == SW_EINVAL || err == SW_ENOTFOUND) && msg[0]);
        return;
    }
    int rc = sw_csv_feed(c, (const char *)text, len);
    if (rc == SW_OK)
        rc = sw_csv_finish(c);
    FZ_CHECK(rc == SW_OK || rc == SW_ENOTFOUND || rc == SW_EINVAL || rc == SW_EAMBIGUOUS);
    sw_csv_layout_t L;
    FZ_CHECK(sw_csv_layout(c, &L) == SW_OK);
    if (rc != SW_OK) {
        const char *m = sw_csv_error_message(c);
        FZ_CHECK(m && m[0]);
    } else {
        /* a log with a row has a layout */
        FZ_CHECK(L.ready || rows.rows == 0);
    }
    if (L.ready)
        check_layout(c, &L, o);
    sw_csv_counts_t n;
    sw_csv_counts(c, &n);
    FZ_CHECK(n.accepted == rows.rows && n.rows == n.accepted + n.rejected);
    sw_csv_destroy(c);
}

static int days_in(long y, int m)
{
    /* day 0 of the month after m (tm_mon counts from 0): m's last */
    struct tm tm = {.tm_year = (int)(y - 1900), .tm_mon = m, .tm_mday = 0};
    const time_t t = timegm(&tm);
    struct tm back;
    gmtime_r(&t, &back);
    return back.tm_mday;
}

/* One field read as a date-time, each way, against timegm(). */
static void check_datetime(const char *s, size_t n)
{
    sw_csv_dt_t dt;
    if (!sw_csv_dt_read(s, n, &dt))
        return;
    FZ_CHECK(dt.y >= 0 && dt.y <= 9999);
    FZ_CHECK(dt.h >= 0 && dt.h <= 23 && dt.mi >= 0 && dt.mi <= 59 && dt.sec >= 0 && dt.sec <= 60);
    FZ_CHECK(dt.frac >= 0.0 && dt.frac < 1.0);
    FZ_CHECK(dt.offset > -86400 && dt.offset < 86400);
    for (int order = SW_CSV_DATE_DMY; order <= SW_CSV_DATE_MDY; order++) {
        const int mo = dt.dm && order == SW_CSV_DATE_DMY ? dt.b : dt.a;
        const int d = dt.dm && order == SW_CSV_DATE_DMY ? dt.a : dt.b;
        const int exists = mo >= 1 && mo <= 12 && d >= 1 && d <= days_in(dt.y, mo);
        double v = NAN;
        const int got = sw_csv_dt_seconds(&dt, order, &v);
        FZ_CHECK(got == exists);
        if (!got)
            continue;
        struct tm tm = {.tm_year = (int)(dt.y - 1900),
                        .tm_mon = mo - 1,
                        .tm_mday = d,
                        .tm_hour = dt.h,
                        .tm_min = dt.mi,
                        .tm_sec = dt.sec};
        const double want = (double)(timegm(&tm) - dt.offset) + dt.frac;
        FZ_CHECK(isfinite(v) && v == want);
        double w = NAN;
        FZ_CHECK(sw_csv_datetime(s, n, order, &w) == 1 && w == v);
    }
    /* without an order only the year-first form is read */
    double v;
    FZ_CHECK((sw_csv_dt_seconds(&dt, SW_CSV_DATE_AUTO, &v) == -1) == dt.dm);
}

static void check_epoch(double v)
{
    static const double per_s[] = {1.0, 1e3, 1e6, 1e9};
    static const int unit[] = {SW_CSV_UNIT_S, SW_CSV_UNIT_MS, SW_CSV_UNIT_US, SW_CSV_UNIT_NS};
    const int u = sw_csv_epoch_unit(v);
    int in = 0;
    for (int i = 0; i < 4; i++) {
        const int here = v >= EPOCH_LO * per_s[i] && v < EPOCH_HI * per_s[i];
        in += here;
        if (here)
            FZ_CHECK(u == unit[i]);
    }
    FZ_CHECK(in <= 1); /* the ranges do not meet */
    if (!in)
        FZ_CHECK(u == SW_CSV_UNIT_NONE);
}

/* The first line's fields into columns, as the reader's header. */
static void check_guess(char names[][SW_CSV_NAME_MAX], long n, uint8_t o)
{
    const int want[SW_CSV_NROLES] = {1, (o & 1) == 0, 0};
    const long skip = (o >> 1) & 1 ? (long)((o >> 2) % (n + 1)) - 1 : -1;
    sw_csv_guess_t g;
    memset(&g, 0xa5, sizeof g);
    const int rc = sw_csv_guess((const char(*)[SW_CSV_NAME_MAX])names, n, want, skip, NULL, 0, &g);
    FZ_CHECK(rc == 0 || rc == -1);
    if (rc == -1) {
        FZ_CHECK(memchr(g.why, '\0', sizeof g.why) != NULL && g.why[0]);
        return;
    }
    for (int r = 0; r < 2; r++) {
        if (!want[r])
            continue;
        FZ_CHECK(g.col[r] >= 0 && g.col[r] < n && g.col[r] != skip);
        FZ_CHECK(g.unit[r] == SW_CSV_UNIT_NONE ||
                 (r == 0 ? is_time_unit(g.unit[r]) : is_accel_unit(g.unit[r])));
    }
    if (want[0] && want[1])
        FZ_CHECK(g.col[0] != g.col[1]);
}

/* Every field of the text (split at delimiters and line ends) through the
 * stages; the first line's fields also guessed into columns. */
static void run_stages(const uint8_t *text, size_t len, uint8_t o)
{
    static char names[SW_CSV_MAX_FIELDS][SW_CSV_NAME_MAX];
    long nnames = 0;
    int first_line = 1;
    locale_t cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    FZ_CHECK(cloc != (locale_t)0);
    char field[128];
    size_t start = 0;
    for (size_t i = 0, nf = 0; i <= len && nf < MAX_FIELDS; i++) {
        const int end = i == len || text[i] == '\n';
        if (!end && text[i] != ',' && text[i] != ';' && text[i] != '\t')
            continue;
        size_t n = i - start;
        if (n >= sizeof field)
            n = sizeof field - 1;
        memcpy(field, text + start, n);
        field[n] = '\0';
        if (n && field[n - 1] == '\r')
            field[--n] = '\0';
        start = i + 1;
        nf++;
        check_datetime(field, n);
        double v;
        if (sw_csv_number(cloc, field, n, 0, &v) == SW_NUM_OK) {
            FZ_CHECK(isfinite(v));
            check_epoch(v);
        }
        if (first_line && nnames < SW_CSV_MAX_FIELDS) {
            const size_t k = n < SW_CSV_NAME_MAX - 1 ? n : SW_CSV_NAME_MAX - 1;
            memcpy(names[nnames], field, k);
            names[nnames++][k] = '\0';
        }
        if (end && first_line) {
            first_line = 0;
            check_guess(names, nnames, o);
        }
    }
    freelocale(cloc);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes_t b = {data, size};
    const uint8_t o0 = fz_byte(&b), o1 = fz_byte(&b);
    static const char delims[] = {0, ',', ';', '\t'};
    static const int dc[] = {-1, 0, 1, -1};
    sw_csv_opts_t o;
    memset(&o, 0, sizeof o);
    o.infer = 1;
    o.date_order = (o0 & 3) == 3 ? SW_CSV_DATE_AUTO : (int)(o0 & 3);
    o.delim = delims[(o0 >> 2) & 3];
    o.header = (o0 >> 4) & 1 ? 1 : -1;
    o.decimal_comma = dc[(o0 >> 5) & 3];
    o.skip_lines = (o0 >> 7) ? -1 : 0;
    /* mostly nothing given: the header decides; else one column by number
     * or by a name the header may hold */
    static const char *const given[] = {NULL, NULL, NULL, NULL, "1", "2", "3", "time"};
    if ((o1 & 7) >= 4) {
        if (o1 & 8)
            o.accel_col = given[o1 & 7];
        else
            o.time_col = given[o1 & 7];
    }
    const size_t len = b.n > MAX_TEXT ? MAX_TEXT : b.n;
    run_reader(&o, b.p, len);
    run_stages(b.p, len, o1 >> 4);
    return 0;
}
