/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_profile.c - what the rows of the look-ahead show of a column, for
 * the decisions a header's names cannot make: whether its times are
 * numbers, year-first date-times or day-and-month date-times (and which of
 * day and month comes first: a number above 12 is the day), their
 * magnitude (an epoch in s, ms, us or ns), and their resolution (the
 * smallest step, and how often a time repeats: a date column to the second
 * beside a clock in ns repeats its stamps). */
#include <math.h>
#include <string.h>

#include "csv_int.h"

enum { K_NONE, K_NUM, K_DT };

/* A step from the previous value of the same kind. */
static void step(sw_csv_profile_t *p, int kind, double v)
{
    if (p->kind_prev == kind) {
        const double d = v - p->prev;
        p->steps++;
        if (d == 0.0)
            p->zero++;
        else if (d > 0.0 && (p->minstep == 0.0 || d < p->minstep))
            p->minstep = d;
    }
    p->kind_prev = kind;
    p->prev = v;
}

void sw_csv_profile_add(sw_csv_profile_t *p, const char *s, size_t n, char delim, locale_t cloc)
{
    while (n && (*s == ' ' || *s == '\t')) s++, n--;
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t')) n--;
    if (!n)
        return;
    p->n++;
    double v;
    if (sw_csv_number(cloc, s, n, 0, &v) == SW_NUM_OK ||
        (delim != ',' && sw_csv_number(cloc, s, n, 1, &v) == SW_NUM_OK)) {
        if (!p->nnum)
            p->first = v;
        p->nnum++;
        step(p, K_NUM, v);
        return;
    }
    sw_csv_dt_t dt;
    if (!sw_csv_dt_read(s, n, &dt))
        return;
    if (!dt.dm) {
        if (sw_csv_dt_seconds(&dt, SW_CSV_DATE_DMY, &v) != 1) /* year first: the order unused */
            return;
        p->niso++;
        step(p, K_DT, v);
        return;
    }
    /* day and month first: a field above 12 (and at most 31) is the day,
     * the other one the month */
    if (dt.a < 1 || dt.b < 1 || dt.a > 31 || dt.b > 31 || (dt.a > 12 && dt.b > 12))
        return;
    p->ndm++;
    p->a13 += dt.a > 12;
    p->b13 += dt.b > 12;
    /* steps within a day are exact whatever the order; a new day is a
     * larger step */
    const double tod = dt.h * 3600.0 + dt.mi * 60.0 + dt.sec + dt.frac;
    step(p, K_DT, 86400.0 * ((double)dt.y * 1024.0 + dt.a * 32.0 + dt.b) + tod);
}
