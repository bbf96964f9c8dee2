/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_unit.c - the units of a CSV log: a header name split into words and
 * a unit ("Time (ms)", "accel_g", "X [m/s²]"), a unit's text read as a time
 * or an acceleration unit, and the scales of the units.  The options'
 * units (--time-unit, --accel-unit) are read the same way. */
#include <stdio.h>
#include <string.h>

#include "csv_int.h"

char sw_csv_lower(char c)
{
    return c >= 'A' && c <= 'Z' ? (char)(c - 'A' + 'a') : c;
}

static int is_alnum(unsigned char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c >= 0x80; /* UTF-8 (µ, ², ...) stays inside words and units */
}

/* Split a header name into words and a bracketed unit. */
void sw_csv_words(const char *name, sw_csv_words_t *o)
{
    memset(o, 0, sizeof *o);
    const char *p = name;
    while (*p) {
        if (*p == '(' || *p == '[' || *p == '{') {
            const char close = *p == '(' ? ')' : *p == '[' ? ']' : '}';
            size_t k = 0;
            for (p++; *p && *p != close; p++)
                if (*p != ' ' && k + 1 < sizeof o->unit)
                    o->unit[k++] = sw_csv_lower(*p);
            o->unit[k] = '\0';
            if (*p)
                p++;
            continue;
        }
        if (!is_alnum((unsigned char)*p)) {
            p++;
            continue;
        }
        size_t k = 0;
        char *w = o->nw < SW_CSV_MAX_WORDS ? o->w[o->nw] : NULL;
        for (; *p && is_alnum((unsigned char)*p); p++)
            if (w && k + 1 < SW_CSV_WORD_MAX)
                w[k++] = sw_csv_lower(*p);
        if (w) {
            w[k] = '\0';
            o->nw++;
        }
    }
}

int sw_csv_word_in(const char *w, const char *const *set)
{
    for (; *set; set++)
        if (!strcmp(w, *set))
            return 1;
    return 0;
}

/* The unit of a unit text, for the time role or an acceleration. */
static int unit_of(const char *u, int time_role)
{
    static const char *const s[] = {"s", "sec", "secs", "second", "seconds", NULL};
    static const char *const ms[] = {"ms",          "msec",         "msecs", "millis",
                                     "millisecond", "milliseconds", NULL};
    static const char *const us[] = {"us",     "\xc2\xb5s",   "\xce\xbcs",    "usec", "usecs",
                                     "micros", "microsecond", "microseconds", NULL};
    static const char *const g[] = {"g", "gs", "g0", "gee", "gees", NULL};
    static const char *const mps2[] = {"m/s2",
                                       "m/s^2",
                                       "m/s\xc2\xb2",
                                       "ms2",
                                       "ms^-2",
                                       "ms-2",
                                       "mps2",
                                       "m/s/s",
                                       "mss",
                                       "m*s^-2",
                                       "m.s-2",
                                       "m.s^-2",
                                       "ms\xe2\x81\xbb\xc2\xb2",
                                       "m\xc2\xb7s\xe2\x81\xbb\xc2\xb2",
                                       "m/sec2",
                                       "m/sec^2",
                                       NULL};
    if (!u[0])
        return SW_CSV_UNIT_NONE;
    if (time_role) {
        if (sw_csv_word_in(u, s))
            return SW_CSV_UNIT_S;
        if (sw_csv_word_in(u, ms))
            return SW_CSV_UNIT_MS;
        if (sw_csv_word_in(u, us))
            return SW_CSV_UNIT_US;
        return SW_CSV_UNIT_NONE;
    }
    if (sw_csv_word_in(u, g))
        return SW_CSV_UNIT_G;
    if (sw_csv_word_in(u, mps2))
        return SW_CSV_UNIT_MPS2;
    return SW_CSV_UNIT_NONE;
}

/* The unit of a name: its bracketed part, else its last word when it is a
 * unit and not the only word ("accel_g", "time_ms"; "g" alone is a name). */
int sw_csv_words_unit(const sw_csv_words_t *w, int time_role, int *last_is_unit)
{
    *last_is_unit = 0;
    if (w->unit[0])
        return unit_of(w->unit, time_role);
    if (w->nw >= 2) {
        const int u = unit_of(w->w[w->nw - 1], time_role);
        if (u != SW_CSV_UNIT_NONE)
            *last_is_unit = 1;
        return u;
    }
    return SW_CSV_UNIT_NONE;
}

int sw_csv_unit_parse(const char *text, int time_role)
{
    char u[SW_CSV_WORD_MAX * 2];
    size_t k = 0;
    for (const char *p = text; p && *p && k + 1 < sizeof u; p++)
        if (*p != ' ')
            u[k++] = sw_csv_lower(*p);
    u[k] = '\0';
    return unit_of(u, time_role);
}

int sw_csv_name_unit(const char *name, int time_role)
{
    sw_csv_words_t w;
    int last;
    sw_csv_words(name, &w);
    return sw_csv_words_unit(&w, time_role, &last);
}

double sw_csv_unit_scale(int unit)
{
    switch (unit) {
        case SW_CSV_UNIT_MS: return 1e-3;
        case SW_CSV_UNIT_US: return 1e-6;
        case SW_CSV_UNIT_G: return SW_G0;
        default: return 1.0;
    }
}
