/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_preamble.c - where the table of a logger export starts.  Loggers
 * write lines before it: a title, the instrument, its serial number, the
 * trigger, the units, as "key: value" or "key,value" lines.  The table is
 * the header and the rows under it: the first data row is the first line
 * of numbers whose field count the lines after it keep, and the header is
 * the line just above it, if that line holds names.
 *
 * A row is a line of two or more values (numbers, date-times) making at
 * least half of its fields; no line of the preamble is one, each holds
 * words (a line of numbers alone may be a damaged row), and none has the
 * table's field count, a value and no field of words alone ("0,nan" is a
 * row spoilt; "Serial,12345" is not).  It decides
 * only what the lines show without doubt, because a line taken for
 * preamble by mistake is a row lost: the lines under the first row must
 * keep its field count (three in four of the next sixteen, for a damaged
 * row or two).  Otherwise the table starts at the first line, as in a file
 * without a preamble, and the header and rows are read as always.  With no
 * header (the caller says the first line is a row) there is no preamble
 * either, unless the caller says how long it is. */
#include <string.h>

#include "csv_int.h"

#define RUN 16 /* lines after the first row that must keep its field count (3 in 4) */

/* A delimiter among tab, ';', ',' occurring outside quotes, in that order of
 * preference: ';' files use ',' as the decimal mark, so a line holding both
 * is ';'-delimited; tab-delimited headers may well contain commas. */
char sw_csv_detect_delim(const char *s, size_t n)
{
    int tab = 0, semi = 0, comma = 0, q = 0;
    for (size_t i = 0; i < n; i++) {
        char ch = s[i];
        if (ch == '"')
            q = !q;
        else if (!q) {
            tab |= ch == '\t';
            semi |= ch == ';';
            comma |= ch == ',';
        }
    }
    return tab ? '\t' : semi ? ';' : comma ? ',' : 0;
}

/* A field as a value: a number (with ',' as the decimal mark too, unless
 * ',' is the delimiter) or a date-time. */
static int is_value(const char *s, size_t n, char d, const sw_csv_preamble_opts_t *o)
{
    double v;
    if (sw_csv_number(o->cloc, s, n, 0, &v) == SW_NUM_OK)
        return 1;
    if (d != ',' && sw_csv_number(o->cloc, s, n, 1, &v) == SW_NUM_OK)
        return 1;
    return sw_csv_is_datetime(s, n);
}

/* The shape of a line split on d: its fields, how many are not empty, and
 * how many of those are values.  Quotes around a field are dropped. */
typedef struct {
    long nf, full, values;
    long text; /* fields of words alone: letters, no digit, not "nan" or "inf" */
} shape_t;

/* Words alone, not a number spoilt ("nan", "inf", "1e400", "0x10"). */
static int is_text(const char *s, size_t n)
{
    static const char *const notnum[] = {"nan", "inf", "infinity", "na", "null", "none", NULL};
    char w[16];
    size_t k = 0;
    int letter = 0;
    for (size_t i = 0; i < n; i++) {
        const unsigned char c = (unsigned char)s[i];
        if (c >= '0' && c <= '9')
            return 0;
        letter |= (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c >= 0x80;
        if (c != '+' && c != '-' && k + 1 < sizeof w)
            w[k++] = sw_csv_lower((char)c);
    }
    w[k] = '\0';
    return letter && !sw_csv_word_in(w, notnum);
}

static shape_t shape(const char *s, size_t n, char d, const sw_csv_preamble_opts_t *o)
{
    shape_t sh = {0, 0, 0, 0};
    size_t i = 0;
    for (;;) {
        size_t a = i;
        int q = 0;
        while (i < n && (q || s[i] != d)) {
            if (s[i] == '"')
                q = !q;
            i++;
        }
        size_t b = i;
        while (a < b && sw_csv_is_blank(s[a])) a++;
        while (b > a && sw_csv_is_blank(s[b - 1])) b--;
        if (b - a >= 2 && s[a] == '"' && s[b - 1] == '"')
            a++, b--;
        sh.nf++;
        if (b > a) {
            sh.full++;
            sh.values += is_value(s + a, b - a, d, o);
            sh.text += is_text(s + a, b - a);
        }
        if (i >= n)
            return sh;
        i++;
    }
}

/* Two or more values, making at least half of the fields that hold
 * anything: a row of a table, not a line of metadata. */
static int row_like(const shape_t *sh)
{
    return sh->nf >= 2 && sh->values >= 2 && 2 * sh->values >= sh->full;
}

/* Words: a letter (or UTF-8 text).  A line without any is numbers and
 * punctuation: a damaged row as likely as metadata. */
static int has_words(const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        const unsigned char c = (unsigned char)s[i];
        if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c >= 0x80)
            return 1;
    }
    return 0;
}

long sw_csv_preamble_find(const sw_csv_line_t *lines, long n, const sw_csv_preamble_opts_t *o)
{
    if (o->header == 0)
        return 0; /* the caller says the first line is a row */
    /* the delimiter: given, or the one under which most lines are rows */
    char d = o->delim;
    if (!d) {
        static const char cand[] = {'\t', ';', ','};
        long best = 0;
        for (int k = 0; k < 3; k++) {
            long rows = 0;
            for (long i = 0; i < n; i++) {
                const shape_t sh = shape(lines[i].s, lines[i].n, cand[k], o);
                rows += row_like(&sh);
            }
            if (rows > best) {
                best = rows;
                d = cand[k];
            }
        }
        if (!d)
            return 0;
    }
    /* the first row, and the rows after it keep its field count */
    long t = 0;
    shape_t first = {0, 0, 0, 0};
    for (; t < n; t++) {
        first = shape(lines[t].s, lines[t].n, d, o);
        if (row_like(&first))
            break;
    }
    if (t == 0 || t == n)
        return 0;
    long after = 0, kept = 0;
    for (long i = t + 1; i < n && after < RUN; i++, after++) {
        const shape_t sh = shape(lines[i].s, lines[i].n, d, o);
        kept += sh.nf == first.nf;
    }
    if (4 * kept < 3 * after)
        return 0;
    /* the header: the line above, when it holds names (no line above looks
     * like a row: the first that does is the first row, or there is no
     * preamble) */
    long start = t;
    const shape_t h = shape(lines[t - 1].s, lines[t - 1].n, d, o);
    if (o->header == 1 || h.nf >= 2)
        start = t - 1;
    /* every line above holds words, and none is a row spoilt: the table's
     * field count, a value, and no field of words ("0,nan", "2,1e400") */
    for (long i = 0; i < start; i++) {
        const shape_t sh = shape(lines[i].s, lines[i].n, d, o);
        if (!has_words(lines[i].s, lines[i].n) ||
            (sh.nf == first.nf && sh.values > 0 && sh.text == 0))
            return 0;
    }
    return start;
}
