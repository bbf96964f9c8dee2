/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_unit.c - the units of a CSV log: a header name read as words and a
 * unit, a unit's text read as what it measures, and the scales of the
 * units.  The options' units (--time-unit, --accel-unit) are read the same
 * way.
 *
 * A unit is written in brackets in any language ("Zeit [s]", "Temps (s)",
 * "Accélération (g)", "X [m/s²]"), or as the last word of a name
 * ("accel_g", "Acceleration Gs", "uptimeNanos"), or, for time, as its
 * first ("seconds_elapsed").  What a unit measures matters as much as its
 * scale: a column in degrees, metres, km/h, rpm, %, µT, rad/s or °C is not
 * an acceleration whatever its name says ("Longitude / X Position
 * (Degrees)"), and a column whose bracketed unit is none of the units read
 * here ("X (raw)", "(counts)") is not one either, because its scale is
 * unknown.  A range written as a unit ("X (100g)", "(±16 g)": a logger's
 * channel and its full scale) is read as the unit of the values. */
#include <stdio.h>
#include <string.h>

#include "csv_int.h"

char sw_csv_lower(char c)
{
    return c >= 'A' && c <= 'Z' ? (char)(c - 'A' + 'a') : c;
}

static int is_upper(char c)
{
    return c >= 'A' && c <= 'Z';
}

static int is_lower(char c)
{
    return c >= 'a' && c <= 'z';
}

static int is_alnum(unsigned char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c >= 0x80; /* UTF-8 (µ, ², é, ...) stays inside words and units */
}

int sw_csv_word_in(const char *w, const char *const *set)
{
    for (; *set; set++)
        if (!strcmp(w, *set))
            return 1;
    return 0;
}

/* ---- units --------------------------------------------------------------------- */

static const char *const u_s[] = {"s", "sec", "secs", "second", "seconds", NULL};
static const char *const u_ms[] = {"ms",          "msec",         "msecs", "millis",
                                   "millisecond", "milliseconds", NULL};
static const char *const u_us[] = {"us",     "\xc2\xb5s",   "\xce\xbcs",    "usec", "usecs",
                                   "micros", "microsecond", "microseconds", NULL};
static const char *const u_ns[] = {"ns",         "nsec",        "nsecs", "nanos",
                                   "nanosecond", "nanoseconds", NULL};
static const char *const u_g[] = {"g", "gs", "g's", "g0", "gn", "gee", "gees", NULL};
static const char *const u_mg[] = {"mg", "millig", NULL};
static const char *const u_mps2[] = {"m/s2",
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
/* Units of other quantities, as loggers write them: angles, rates of turn,
 * lengths, speeds, engine speed, shares, magnetic field, temperature,
 * pressure, electricity, light, sound, force, mass, position. */
static const char *const u_other[] = {"deg",
                                      "degs",
                                      "degree",
                                      "degrees",
                                      "\xc2\xb0",
                                      "rad",
                                      "rads",
                                      "radian",
                                      "radians",
                                      "rad/s",
                                      "deg/s",
                                      "\xc2\xb0/s",
                                      "dps",
                                      "rpm",
                                      "hz",
                                      "khz",
                                      "%",
                                      "pct",
                                      "percent",
                                      "m",
                                      "mm",
                                      "cm",
                                      "km",
                                      "mi",
                                      "ft",
                                      "nmi",
                                      "m/s",
                                      "km/h",
                                      "kmh",
                                      "kph",
                                      "mph",
                                      "kn",
                                      "kt",
                                      "kts",
                                      "knots",
                                      "ft/s",
                                      "\xc2\xb5t",
                                      "\xce\xbct",
                                      "ut",
                                      "mt",
                                      "nt",
                                      "gauss",
                                      "\xc2\xb0\x63",
                                      "\xc2\xb0\x66",
                                      "degc",
                                      "degf",
                                      "c",
                                      "f",
                                      "k",
                                      "pa",
                                      "hpa",
                                      "kpa",
                                      "mbar",
                                      "bar",
                                      "psi",
                                      "v",
                                      "mv",
                                      "ma",
                                      "w",
                                      "kw",
                                      "lux",
                                      "lx",
                                      "db",
                                      "dbm",
                                      "n",
                                      "nm",
                                      "kg",
                                      "wgs84",
                                      NULL};

/* The unit of a unit's text (lowercase, no spaces): SW_CSV_UNIT_* with its
 * class. */
static int unit_read(const char *u, int *cls)
{
    static const struct {
        const char *const *names;
        int unit, cls;
    } table[] = {
        {u_s, SW_CSV_UNIT_S, SW_CSV_UC_TIME},        {u_ms, SW_CSV_UNIT_MS, SW_CSV_UC_TIME},
        {u_us, SW_CSV_UNIT_US, SW_CSV_UC_TIME},      {u_ns, SW_CSV_UNIT_NS, SW_CSV_UC_TIME},
        {u_g, SW_CSV_UNIT_G, SW_CSV_UC_ACCEL},       {u_mg, SW_CSV_UNIT_MG, SW_CSV_UC_ACCEL},
        {u_mps2, SW_CSV_UNIT_MPS2, SW_CSV_UC_ACCEL}, {u_other, SW_CSV_UNIT_NONE, SW_CSV_UC_OTHER},
    };
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (sw_csv_word_in(u, table[i].names)) {
            *cls = table[i].cls;
            return table[i].unit;
        }
    *cls = u[0] ? SW_CSV_UC_UNKNOWN : SW_CSV_UC_NONE;
    return SW_CSV_UNIT_NONE;
}

/* A unit, or a range written as one: "100g", "±16g", "+-2g", "16 g" (the
 * spaces removed already) is the logger's full scale, its values in g. */
static int unit_or_range(const char *u, int *cls)
{
    const int unit = unit_read(u, cls);
    if (*cls != SW_CSV_UC_UNKNOWN)
        return unit;
    const char *p = u;
    if (!strncmp(p, "\xc2\xb1", 2))
        p += 2;
    else if (!strncmp(p, "+-", 2))
        p += 2;
    else if (*p == '+')
        p++;
    const char *d = p;
    while ((*p >= '0' && *p <= '9') || *p == '.') p++;
    if (p == d)
        return unit;
    int c;
    const int r = unit_read(p, &c);
    if (c == SW_CSV_UC_ACCEL) {
        *cls = c;
        return r;
    }
    return unit;
}

/* Lowercase text without spaces, at most cap - 1 bytes. */
static void squeeze(const char *s, size_t n, char *dst, size_t cap)
{
    size_t k = 0;
    for (size_t i = 0; i < n && k + 1 < cap; i++)
        if (s[i] != ' ' && s[i] != '\t')
            dst[k++] = sw_csv_lower(s[i]);
    dst[k] = '\0';
}

int sw_csv_unit_class(const char *text, int *unit)
{
    char u[SW_CSV_WORD_MAX * 2];
    int cls;
    squeeze(text, text ? strlen(text) : 0, u, sizeof u);
    const int r = unit_or_range(u, &cls);
    if (unit)
        *unit = r;
    return cls;
}

int sw_csv_unit_parse(const char *text, int time_role)
{
    /* a unit alone: a range ("100g") is a header's way of writing one */
    char u[SW_CSV_WORD_MAX * 2];
    int cls;
    squeeze(text, text ? strlen(text) : 0, u, sizeof u);
    const int unit = unit_read(u, &cls);
    return cls == (time_role ? SW_CSV_UC_TIME : SW_CSV_UC_ACCEL) ? unit : SW_CSV_UNIT_NONE;
}

double sw_csv_unit_scale(int unit)
{
    switch (unit) {
        case SW_CSV_UNIT_MS: return 1e-3;
        case SW_CSV_UNIT_US: return 1e-6;
        case SW_CSV_UNIT_NS: return 1e-9;
        case SW_CSV_UNIT_G: return SW_G0;
        case SW_CSV_UNIT_MG: return SW_G0 * 1e-3;
        default: return 1.0;
    }
}

/* ---- names --------------------------------------------------------------------- */

/* A word of a name, split further where its case says a new word starts
 * ("accelerometerAccelerationX", "uptimeNanos", "GPSTime"), except in words
 * of three letters or fewer ("gFx", "aT", "AccX" is four): those are the
 * short names of one thing. */
static void add_words(sw_csv_words_t *o, const char *s, size_t n)
{
    size_t start = 0;
    for (size_t i = 1; i <= n; i++) {
        const int cut =
            i == n ||
            (n > 3 && ((is_lower(s[i - 1]) && is_upper(s[i])) ||
                       (i + 1 < n && is_upper(s[i - 1]) && is_upper(s[i]) && is_lower(s[i + 1]))));
        if (!cut)
            continue;
        if (o->nw < SW_CSV_MAX_WORDS) {
            char *w = o->w[o->nw++];
            size_t k = 0;
            for (size_t j = start; j < i && k + 1 < SW_CSV_WORD_MAX; j++)
                w[k++] = sw_csv_lower(s[j]);
            w[k] = '\0';
        }
        start = i;
    }
}

/* Drop word i (it was the unit). */
static void drop_word(sw_csv_words_t *o, int i)
{
    for (int j = i; j + 1 < o->nw; j++) memcpy(o->w[j], o->w[j + 1], SW_CSV_WORD_MAX);
    o->nw--;
}

/* A g-force names its unit: "gFx", "TgF" (Physics Toolbox), "G-Force X",
 * "gforce". */
static int g_force(const sw_csv_words_t *o)
{
    static const char *const gf[] = {"gfx", "gfy", "gfz", "tgf", "gforce", NULL};
    for (int i = 0; i < o->nw; i++)
        if (sw_csv_word_in(o->w[i], gf) ||
            (i + 1 < o->nw && !strcmp(o->w[i], "g") && !strcmp(o->w[i + 1], "force")))
            return 1;
    return 0;
}

void sw_csv_words(const char *name, sw_csv_words_t *o)
{
    memset(o, 0, sizeof *o);
    int best = SW_CSV_UC_NONE; /* of the bracketed parts: the last one read as a unit */
    const char *p = name;
    while (*p) {
        if (*p == '(' || *p == '[' || *p == '{') {
            const char close = *p == '(' ? ')' : *p == '[' ? ']' : '}';
            const char *q = ++p;
            while (*p && *p != close) p++;
            char u[sizeof o->unit];
            squeeze(q, (size_t)(p - q), u, sizeof u);
            if (*p)
                p++;
            int cls;
            const int unit = unit_or_range(u, &cls);
            /* a unit known beats one that is not ("[g] (filtered)") */
            if (cls == SW_CSV_UC_NONE ||
                (best > SW_CSV_UC_NONE && best < SW_CSV_UC_UNKNOWN && cls == SW_CSV_UC_UNKNOWN))
                continue;
            best = cls;
            o->uclass = cls;
            o->unit_id = unit;
            snprintf(o->unit, sizeof o->unit, "%s", u);
            continue;
        }
        if (!is_alnum((unsigned char)*p)) {
            p++;
            continue;
        }
        const char *q = p;
        while (*p && is_alnum((unsigned char)*p)) p++;
        add_words(o, q, (size_t)(p - q));
    }
    if (o->uclass == SW_CSV_UC_NONE && g_force(o)) {
        o->uclass = SW_CSV_UC_ACCEL;
        o->unit_id = SW_CSV_UNIT_G;
        snprintf(o->unit, sizeof o->unit, "g");
        return;
    }
    if (o->uclass != SW_CSV_UC_NONE || o->nw < 2)
        return;
    /* no bracket: the last word when it is a unit ("accel_g", "Acceleration
     * Gs"), or the first when it is a unit of time ("seconds_elapsed") */
    int cls;
    int unit = unit_read(o->w[o->nw - 1], &cls);
    int at = o->nw - 1;
    /* one letter is a unit of another quantity only as metres: "acc_v" is
     * the vertical axis, not volts */
    if (cls == SW_CSV_UC_OTHER && o->w[at][1] == '\0' && o->w[at][0] != 'm')
        cls = SW_CSV_UC_UNKNOWN;
    if (cls == SW_CSV_UC_UNKNOWN) {
        unit = unit_read(o->w[0], &cls);
        at = 0;
        if (cls != SW_CSV_UC_TIME)
            return;
    }
    o->uclass = cls;
    o->unit_id = unit;
    snprintf(o->unit, sizeof o->unit, "%s", o->w[at]);
    drop_word(o, at);
}

/* Units of time no option reads (--time-unit is s, ms, us or ns), as a
 * name writes them: "Time (min)", "Zeit [h]", "elapsed_minutes".  Read as
 * a unit they would make the name's unit one of time, and "(min)" is as
 * often a minimum ("Accel X [g] (min)"); so they are only looked for in
 * the name of the column already chosen as time.  Days are left out:
 * "time_of_day" holds seconds of the day as often as not. */
static const char *const u_time_unread[] = {"min",    "mins",   "minute",  "minutes", "minuten",
                                            "h",      "hr",     "hrs",     "hour",    "hours",
                                            "heures", "stunde", "stunden", NULL};

const char *sw_csv_time_unit_unread(const char *name, char *dst, size_t cap)
{
    sw_csv_words_t w;
    sw_csv_words(name, &w);
    const char *u = w.uclass == SW_CSV_UC_UNKNOWN             ? w.unit
                    : w.uclass == SW_CSV_UC_NONE && w.nw >= 2 ? w.w[w.nw - 1]
                                                              : NULL;
    if (!u || !sw_csv_word_in(u, u_time_unread))
        return NULL;
    snprintf(dst, cap, "%s", u);
    return dst;
}

int sw_csv_name_unit(const char *name, int time_role)
{
    sw_csv_words_t w;
    sw_csv_words(name, &w);
    return w.uclass == (time_role ? SW_CSV_UC_TIME : SW_CSV_UC_ACCEL) ? w.unit_id
                                                                      : SW_CSV_UNIT_NONE;
}
