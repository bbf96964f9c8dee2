/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_time.c - the times of a CSV log that are not plain seconds:
 * date-times and epoch times.
 *
 * Date-times are read as loggers and spreadsheets write them: ISO-8601 and
 * year first ("2024-05-20T12:00:00.000Z", "2018-04-08 10:31:37.005628",
 * "2016/05/14 11:17:09"), or with the day and the month before the year
 * ("14/05/2016 11:17:09", "20.05.2024 12:00:00.000", "5/14/2016 1:17:09
 * PM"), '/', '.' or '-' between them.  In the second form the order of day
 * and month is not in the text: the caller decides it from the data (a
 * field above 12 is the day) or is told (--date-order), and until then such
 * a time is read as neither.  No zone: UTC.  A parser from libc would
 * depend on the locale and the time zone of the machine; this one on
 * neither.
 *
 * Epoch times are recognised by their magnitude: a time since 1970 between
 * the years 2000 and 2100 is 9.5e8 to 4.1e9 in s, a thousand times more in
 * ms, a million in us, a billion in ns, and the four ranges do not meet. */
#include <string.h>

#include "csv_int.h"

static int is_blank(char ch)
{
    return ch == ' ' || ch == '\t';
}

/* 1 to max decimal digits at *p into *v (and their count in *k); advances
 * *p.  0 if none. */
static int digits(const char **p, const char *end, int max, long *v, int *k)
{
    long x = 0;
    int i = 0;
    for (; i < max && *p < end && **p >= '0' && **p <= '9'; i++, (*p)++) x = x * 10 + (**p - '0');
    *v = x;
    if (k)
        *k = i;
    return i > 0;
}

/* Exactly two digits. */
static int two(const char **p, const char *end, long *v)
{
    int k;
    return digits(p, end, 2, v, &k) && k == 2;
}

int sw_csv_dt_read(const char *s, size_t n, sw_csv_dt_t *dt)
{
    while (n && is_blank(*s)) s++, n--;
    while (n && is_blank(s[n - 1])) n--;
    const char *p = s, *end = s + n;
    long g1, g2, g3;
    int k1, k2, k3;
    memset(dt, 0, sizeof *dt);
    /* the date: three groups, one separator */
    if (!digits(&p, end, 4, &g1, &k1) || p >= end)
        return 0;
    const char sep = *p;
    if (sep != '-' && sep != '/' && sep != '.')
        return 0;
    p++;
    if (!digits(&p, end, 2, &g2, &k2) || p >= end || *p++ != sep || !digits(&p, end, 4, &g3, &k3))
        return 0;
    if (k1 == 4 && k3 <= 2) { /* year first */
        dt->y = g1;
        dt->a = (int)g2;
        dt->b = (int)g3;
    } else if (k1 <= 2 && k3 == 4) { /* day and month first, in some order */
        dt->dm = 1;
        dt->a = (int)g1;
        dt->b = (int)g2;
        dt->y = g3;
    } else {
        return 0;
    }
    /* the time of day */
    if (p >= end || (*p != 'T' && *p != 't' && *p != ' '))
        return 0;
    p++;
    while (p < end && *p == ' ') p++;
    long h, mi, sec = 0;
    if (!digits(&p, end, 2, &h, NULL) || p >= end || *p++ != ':' || !two(&p, end, &mi))
        return 0;
    if (p < end && *p == ':') {
        p++;
        if (!two(&p, end, &sec))
            return 0;
    }
    double frac = 0.0, scale = 1.0;
    if (p < end && (*p == '.' || *p == ',')) {
        p++;
        int nd = 0;
        for (; p < end && *p >= '0' && *p <= '9'; p++, nd++)
            if (nd < 15) {
                frac = frac * 10.0 + (*p - '0');
                scale *= 10.0;
            }
        if (!nd)
            return 0;
    }
    /* a 12-hour clock */
    const char *q = p;
    while (q < end && *q == ' ') q++;
    if (end - q >= 2 && (q[1] == 'M' || q[1] == 'm') &&
        (q[0] == 'A' || q[0] == 'a' || q[0] == 'P' || q[0] == 'p')) {
        if (h < 1 || h > 12)
            return 0;
        h = h % 12 + ((q[0] == 'P' || q[0] == 'p') ? 12 : 0);
        p = q + 2;
    }
    /* the zone */
    long offset = 0; /* s east of UTC */
    if (p < end && (*p == 'Z' || *p == 'z')) {
        p++;
    } else if (p < end && (*p == '+' || *p == '-')) {
        const int sign = *p++ == '-' ? -1 : 1;
        long oh, om = 0;
        if (!two(&p, end, &oh))
            return 0;
        if (p < end && *p == ':')
            p++;
        if (p < end && !two(&p, end, &om))
            return 0;
        if (oh > 23 || om > 59)
            return 0;
        offset = sign * (oh * 3600L + om * 60L);
    }
    if (p != end || h > 23 || mi > 59 || sec > 60)
        return 0;
    dt->h = (int)h;
    dt->mi = (int)mi;
    dt->sec = (int)sec;
    dt->frac = frac / scale;
    dt->offset = offset;
    return 1;
}

/* Days from 1970-01-01 to y-m-d in the proleptic Gregorian calendar
 * (H. Hinnant's days_from_civil: exact for every date, no libc, no zone). */
static long days_from_civil(long y, int m, int d)
{
    y -= m <= 2;
    const long era = (y >= 0 ? y : y - 399) / 400;
    const long yoe = y - era * 400;
    const long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

static int days_in_month(long y, int m)
{
    static const int dm[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const int leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
    return m == 2 ? 28 + leap : dm[m - 1];
}

int sw_csv_dt_seconds(const sw_csv_dt_t *dt, int order, double *out)
{
    int mo = dt->a, d = dt->b;
    if (dt->dm) {
        if (order != SW_CSV_DATE_DMY && order != SW_CSV_DATE_MDY)
            return -1;
        mo = order == SW_CSV_DATE_DMY ? dt->b : dt->a;
        d = order == SW_CSV_DATE_DMY ? dt->a : dt->b;
    }
    if (mo < 1 || mo > 12 || d < 1 || d > days_in_month(dt->y, mo))
        return 0;
    const long whole = days_from_civil(dt->y, mo, d) * 86400L + dt->h * 3600L + dt->mi * 60L +
                       dt->sec - dt->offset;
    *out = (double)whole + dt->frac;
    return 1;
}

int sw_csv_datetime(const char *s, size_t n, int order, double *out)
{
    sw_csv_dt_t dt;
    if (!sw_csv_dt_read(s, n, &dt))
        return 0;
    return sw_csv_dt_seconds(&dt, order, out);
}

int sw_csv_is_datetime(const char *s, size_t n)
{
    sw_csv_dt_t dt;
    double v;
    return sw_csv_dt_read(s, n, &dt) && (sw_csv_dt_seconds(&dt, SW_CSV_DATE_DMY, &v) == 1 ||
                                         sw_csv_dt_seconds(&dt, SW_CSV_DATE_MDY, &v) == 1);
}

/* 2000-01-01T00:00:00Z and 2100-01-01T00:00:00Z in s since 1970 (date -u
 * -d 2000-01-01 +%s; date -u -d 2100-01-01 +%s). */
#define EPOCH_LO 946684800.0
#define EPOCH_HI 4102444800.0

int sw_csv_epoch_unit(double v)
{
    static const struct {
        double per_s;
        int unit;
    } u[] = {
        {1.0, SW_CSV_UNIT_S}, {1e3, SW_CSV_UNIT_MS}, {1e6, SW_CSV_UNIT_US}, {1e9, SW_CSV_UNIT_NS}};
    for (size_t i = 0; i < sizeof u / sizeof u[0]; i++)
        if (v >= EPOCH_LO * u[i].per_s && v < EPOCH_HI * u[i].per_s)
            return u[i].unit;
    return SW_CSV_UNIT_NONE;
}
