/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_num.c - the numbers of a CSV log: plain decimals (with '.' or, in a
 * ';' export, ',' as the decimal mark).  Strict: strtod alone would also
 * take "nan", "inf", hex floats and leading junk like "\v".  Date-times
 * are csv_time.c's. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "csv_int.h"

static int is_blank(char ch)
{
    return ch == ' ' || ch == '\t';
}

#if FLT_EVAL_METHOD == 0
/* Powers of ten that are exact doubles. */
static const double pow10_exact[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                     1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* Logger output ("12.345", "-0.00731", "1.5e-3") without strtod, which
 * costs most of the parse time otherwise.  When the digits form an integer
 * m <= 2^53 and the decimal exponent k is within +-22, m and 10^|k| are both
 * exact doubles and one IEEE multiplication or division rounds correctly
 * (Clinger's fast path): the result is the one strtod gives, bit for bit.
 * Anything else returns 0 and is left to strtod.  mark is the decimal mark. */
static int fast_decimal(const char *p, const char *end, char mark, double *out)
{
    int neg = 0, any = 0, k = 0;
    uint64_t m = 0;
    if (p < end && (*p == '+' || *p == '-'))
        neg = *p++ == '-';
    for (; p < end && *p >= '0' && *p <= '9'; p++, any = 1) {
        if (m > UINT64_C(1) << 53)
            return 0;
        m = m * 10 + (uint64_t)(*p - '0');
    }
    if (p < end && *p == mark) {
        for (p++; p < end && *p >= '0' && *p <= '9'; p++, any = 1, k--) {
            if (m > UINT64_C(1) << 53)
                return 0;
            m = m * 10 + (uint64_t)(*p - '0');
        }
    }
    if (!any)
        return 0;
    if (p < end && (*p == 'e' || *p == 'E')) {
        int eneg = 0, e = 0, edigits = 0;
        p++;
        if (p < end && (*p == '+' || *p == '-'))
            eneg = *p++ == '-';
        for (; p < end && *p >= '0' && *p <= '9'; p++, edigits++) {
            if (e > 1000)
                return 0;
            e = e * 10 + (*p - '0');
        }
        if (!edigits)
            return 0;
        k += eneg ? -e : e;
    }
    if (p != end || m > UINT64_C(1) << 53)
        return 0;
    double v = (double)m;
    if (m != 0) {
        if (k < -22 || k > 22)
            return 0;
        v = k < 0 ? v / pow10_exact[-k] : v * pow10_exact[k];
    }
    *out = neg ? -v : v;
    return 1;
}
#endif

int sw_csv_number(locale_t cloc, const char *s, size_t n, int decimal_comma, double *out)
{
    while (n && is_blank(*s)) s++, n--;
    while (n && is_blank(s[n - 1])) n--;
    if (!n)
        return SW_NUM_EMPTY;
#if FLT_EVAL_METHOD == 0
    if (fast_decimal(s, s + n, decimal_comma ? ',' : '.', out))
        return SW_NUM_OK;
#endif
    int comma = 0, dot = 0, bad = 0;
    for (size_t i = 0; i < n; i++) {
        const char ch = s[i];
        if ((ch >= '0' && ch <= '9') || ch == '-' || ch == '+' || ch == 'e' || ch == 'E')
            continue;
        if (ch == ',')
            comma++;
        else if (ch == '.')
            dot++;
        else
            bad = 1;
    }
    if (bad)
        return SW_NUM_BAD;
    char buf[64];
    const char *p = s;
    if (decimal_comma) {
        /* "1.000,5": a thousands separator or a second mark, not a number */
        if (dot || comma > 1 || n >= sizeof buf)
            return SW_NUM_BAD;
        memcpy(buf, s, n);
        buf[n] = '\0';
        char *c = memchr(buf, ',', n);
        if (c)
            *c = '.';
        p = buf;
    } else if (comma) {
        return SW_NUM_COMMA; /* "0,001": a number, but not in this format */
    }
    char *end;
    const locale_t prev = uselocale(cloc);
    const double v = strtod(p, &end);
    uselocale(prev);
    if (end != p + n)
        return SW_NUM_BAD;
    /* Overflow gives HUGE_VAL; underflow (1e-400) gives a tiny finite
     * value with ERANGE, which is as good as zero here and accepted. */
    if (!isfinite(v))
        return SW_NUM_RANGE;
    *out = v;
    return SW_NUM_OK;
}
