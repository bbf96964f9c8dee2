/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_infer.c - a logger export's header read as a person reads it: which
 * column is time and which is the longitudinal acceleration, and in what
 * units ("Time (ms)", "X (g)", "time_ms;accel_g", "Acceleration Gs",
 * "ax [m/s²]").  It decides only what the names say without doubt; when
 * two columns fit equally, or none does, it says so and the caller asks the
 * user, because a wrong guess gives a confident wrong verdict.
 *
 * A name is read as words and a unit (csv_unit.c).  Time is a name whose
 * unit is one of time ("Zeit [s]", "uptimeNanos") or a word such as time,
 * t, timestamp, elapsed, uptime (not sample, index, count); acceleration a
 * name whose unit is one ("X (g)", "Beschl. [m/s²]") or a word such as
 * accel, acc, acceleration, or only an axis ("ax", "X").  A name whose
 * unit is anything else is never an acceleration ("Longitude / X Position
 * (Degrees)"), and a magnitude ("Absolute acceleration", "TgF") is never
 * the longitudinal one.  A name that says acceleration, in a word or by
 * its unit, beats a bare axis; then, among several, the longitudinal one
 * is the x axis (the vehicle frame: x points forward) or one named
 * longitudinal or forward, else the only one that names no axis beside
 * lateral and vertical ones.  Among several time columns one with a unit
 * (elapsed seconds) is preferred to one without (a date-time), and of
 * those with units, the ones that say time in words ("Duration (ms)" does
 * not).  Two still equal: refused, both named.  The columns the caller
 * names or numbers instead are read here too (sw_csv_colspec_parse).
 * Everything here is a function of its arguments: the reader (csv.c) hands
 * in what it read and applies the layout, or ends the parse with the code
 * and message returned. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csv_int.h"
#include "swaywatch/status.h"

typedef struct {
    int time;   /* the name reads as time */
    int twords; /* ... and says so in words, not only by its unit */
    int accel;  /* as an acceleration that may be the longitudinal one */
    int named;  /* ... and says it is an acceleration (a word or its unit), not only
                   an axis */
    int axis;   /* 'x' (longitudinal), 'y', 'z', or 0 */
    int nonacc; /* it names an axis or an acceleration, but its unit is not one */
    int tunit;  /* SW_CSV_UNIT_* of a time unit */
} kind_t;

static const char *const time_w[] = {
    "time",  "t",     "timestamp", "ts",     "elapsed",    "date",        "datetime",
    "utc",   "epoch", "clock",     "uptime", "zeit",       "temps",       "tiempo",
    "tempo", "czas",  "tid",       "aika",   "horodatage", "zeitstempel", "uhrzeit",
    "datum", "heure", "hora",      "fecha",  NULL};
static const char *const index_w[] = {"sample", "samples", "index", "idx", "n",      "no",  "nr",
                                      "num",    "count",   "seq",   "id",  "record", "row", NULL};
static const char *const accel_w[] = {"accel",
                                      "acc",
                                      "accl",
                                      "acceleration",
                                      "accelerometer",
                                      "a",
                                      "gforce",
                                      "beschleunigung",
                                      "beschl",
                                      "acc\xc3\xa9l\xc3\xa9ration",
                                      "aceleraci\xc3\xb3n",
                                      "accelerazione",
                                      "versnelling",
                                      "przyspieszenie",
                                      NULL};
/* the magnitude of the acceleration: never the longitudinal axis */
static const char *const mag_w[] = {"absolute", "abs",       "total", "magnitude", "mag",
                                    "norm",     "resultant", "tgf",   "at",        NULL};
static const char *const x_w[] = {"x",    "ax",    "accx",         "accelx", "xaccel",
                                  "xacc", "long",  "longitudinal", "lon",    "forward",
                                  "fwd",  "surge", "gfx",          NULL};
static const char *const y_w[] = {"y",   "ay",      "accy", "accely", "yaccel", "yacc",
                                  "lat", "lateral", "sway", "gfy",    NULL};
static const char *const z_w[] = {"z",    "az",       "accz",  "accelz", "zaccel", "zacc",
                                  "vert", "vertical", "heave", "up",     "gfz",    NULL};

static void classify(const char *name, kind_t *k)
{
    sw_csv_words_t w;
    sw_csv_words(name, &w);
    memset(k, 0, sizeof *k);
    int index = 0, mag = 0, tw = -1, aw = -1; /* the last time and acceleration words */
    for (int i = 0; i < w.nw; i++) {
        /* a numbered name reads as its word: "acc1", "time2" */
        char x[SW_CSV_WORD_MAX];
        snprintf(x, sizeof x, "%s", w.w[i]);
        size_t xl = strlen(x);
        while (xl > 1 && x[xl - 1] >= '0' && x[xl - 1] <= '9') x[--xl] = '\0';
        if (sw_csv_word_in(x, index_w))
            index = 1;
        if (sw_csv_word_in(x, time_w))
            tw = i;
        if (sw_csv_word_in(x, accel_w))
            aw = i;
        if (sw_csv_word_in(x, mag_w))
            mag = 1;
        if (sw_csv_word_in(x, x_w))
            k->axis = 'x';
        if (sw_csv_word_in(x, y_w))
            k->axis = 'y';
        if (sw_csv_word_in(x, z_w))
            k->axis = 'z';
    }
    if (index)
        return;
    switch (w.uclass) {
        case SW_CSV_UC_TIME: /* "Zeit [s]", "seconds_elapsed", "uptimeNanos" */
            k->time = 1;
            k->twords = tw >= 0;
            k->tunit = w.unit_id;
            return;
        case SW_CSV_UC_ACCEL: /* "X (g)", "Beschl. [m/s²]" */
            k->accel = !mag;
            k->named = 1;
            return;
        case SW_CSV_UC_OTHER:
        case SW_CSV_UC_UNKNOWN:
            /* a time word beside a unit that is not a known one is still
             * time ("loggingTime(txt)"); nothing with a unit that is not an
             * acceleration is one ("Longitude / X Position (Degrees)") */
            k->time = tw >= 0 && w.uclass == SW_CSV_UC_UNKNOWN;
            k->twords = k->time;
            k->nonacc = aw >= 0 || k->axis;
            return;
        default: break;
    }
    /* no unit: the words say it; of a time word and an acceleration word the
     * last one names the thing ("accelerometerTimestamp") */
    if (aw >= 0 && aw > tw) {
        k->accel = !mag;
        k->named = 1;
    } else if (tw >= 0) {
        k->time = k->twords = 1;
    } else if (k->axis) {
        k->accel = !mag;
    }
}

/* "\"a\", \"b\"" of the columns in set, into dst. */
static void list_names(const char names[][SW_CSV_NAME_MAX], const long *set, int n, char *dst,
                       size_t cap)
{
    size_t k = 0;
    dst[0] = '\0';
    for (int i = 0; i < n && k + 8 < cap; i++)
        k += (size_t)snprintf(dst + k, cap - k, "%s\"%s\" (column %ld)", i ? ", " : "",
                              names[set[i]], set[i] + 1);
}

enum { CAP = 16 };

/* A set of columns. */
typedef struct {
    long c[CAP];
    int n;
} set_t;

static void put(set_t *s, long i)
{
    if (s->n < CAP)
        s->c[s->n++] = i;
}

/* The resolution of a time column in the look-ahead's rows: how often a
 * stamp repeats (share of the steps) and the smallest positive step in s.
 * 0 when its rows do not show it. */
typedef struct {
    int known;
    double repeats; /* share of the steps that are zero */
    double q;       /* s, the smallest positive step (infinite: every step is zero) */
} res_t;

static res_t resolution(const char *name, const sw_csv_profile_t *p)
{
    res_t r = {0, 0.0, 0.0};
    if (!p || p->steps < 2)
        return r;
    double scale = 1.0; /* date-times: s */
    const int u = sw_csv_name_unit(name, 1);
    if (u != SW_CSV_UNIT_NONE)
        scale = sw_csv_unit_scale(u);
    else if (p->nnum > p->niso + p->ndm && sw_csv_epoch_unit(p->first) != SW_CSV_UNIT_NONE)
        scale = sw_csv_unit_scale(sw_csv_epoch_unit(p->first));
    r.known = 1;
    r.repeats = (double)p->zero / (double)p->steps;
    r.q = p->minstep > 0.0 ? p->minstep * scale : HUGE_VAL;
    return r;
}

/* a repeats its stamps clearly more often than b, or as often with a step
 * more than twice as long */
static int coarser(const res_t *a, const res_t *b)
{
    if (!a->known || !b->known)
        return 0;
    if (a->repeats > b->repeats + 0.25)
        return 1;
    return fabs(a->repeats - b->repeats) <= 0.25 && a->q > 2.0 * b->q;
}

int sw_csv_guess(const char names[][SW_CSV_NAME_MAX], long n, const int want[SW_CSV_NROLES],
                 long skip, const sw_csv_profile_t *prof, long nprof, sw_csv_guess_t *g)
{
    set_t tu = {0}, tw = {0}, tc = {0}; /* time: with a unit, with a time word, any */
    set_t named = {0}, bare = {0};      /* accelerations: named as such, an axis only */
    set_t nonacc = {0};                 /* axes whose unit is not an acceleration */
    kind_t kinds[SW_CSV_MAX_FIELDS];
    char list[200];
    memset(g, 0, sizeof *g);
    for (int r = 0; r < SW_CSV_NROLES; r++) g->col[r] = -1;
    for (long i = 0; i < n && i < SW_CSV_MAX_FIELDS; i++) {
        kind_t k;
        if (i == skip)
            continue;
        classify(names[i], &k);
        /* a column of date-times is time, whatever its name ("Datum/Uhrzeit") */
        const sw_csv_profile_t *p = i < nprof ? &prof[i] : NULL;
        if (!k.time && !k.accel && p && p->niso + p->ndm > p->nnum &&
            2 * (p->niso + p->ndm) >= p->n)
            k.time = 1;
        if (i < SW_CSV_MAX_FIELDS)
            kinds[i] = k;
        if (k.time) {
            put(&tc, i);
            if (k.tunit != SW_CSV_UNIT_NONE)
                put(&tu, i);
            if (k.twords)
                put(&tw, i);
        }
        if (k.accel)
            put(k.named ? &named : &bare, i);
        if (k.nonacc)
            put(&nonacc, i);
    }
    if (want[SW_CSV_ROLE_TIME]) {
        /* the finer time (a date to the second beside a clock in ns) */
        res_t res[CAP];
        for (int i = 0; i < tc.n; i++)
            res[i] = resolution(names[tc.c[i]], tc.c[i] < nprof ? &prof[tc.c[i]] : NULL);
        set_t fine = {0};
        for (int i = 0; i < tc.n; i++) {
            int worse = 0;
            for (int j = 0; j < tc.n && !worse; j++) worse = j != i && coarser(&res[i], &res[j]);
            if (!worse)
                put(&fine, tc.c[i]);
        }
        if (fine.n < tc.n) {
            set_t keep = {0};
            for (int i = 0; i < tu.n; i++)
                for (int j = 0; j < fine.n; j++)
                    if (tu.c[i] == fine.c[j])
                        put(&keep, tu.c[i]);
            tu = keep;
            tc = fine;
        }
        /* then elapsed time with a unit beats a date-time or a bare name;
         * of several with units, those that say time in words ("Duration
         * (s)" does not) */
        set_t set = tu.n ? tu : tc;
        if (set.n > 1 && tw.n) {
            set_t kept = {0};
            for (int i = 0; i < set.n; i++)
                if (kinds[set.c[i]].twords)
                    put(&kept, set.c[i]);
            if (kept.n)
                set = kept;
        }
        if (set.n != 1) {
            list_names(names, set.c, set.n, list, sizeof list);
            if (set.n == 0)
                snprintf(g->why, sizeof g->why, "no column is named as time");
            else
                snprintf(g->why, sizeof g->why, "several columns could be time: %s", list);
            return -1;
        }
        g->col[SW_CSV_ROLE_TIME] = set.c[0];
        g->unit[SW_CSV_ROLE_TIME] = sw_csv_name_unit(names[set.c[0]], 1);
    }
    if (want[SW_CSV_ROLE_ACCEL]) {
        /* a name that says acceleration ("Acceleration Gs", "Accel X (g)")
         * beats a bare axis ("X"); then one column; or among several the
         * one along x; or, with no x, the one that names no axis beside
         * lateral and vertical ones ("accel, z") */
        const set_t *tier = named.n ? &named : &bare;
        set_t ax = {0}, an = {0};
        for (int i = 0; i < tier->n; i++) {
            const int a = kinds[tier->c[i]].axis;
            if (a == 'x')
                put(&ax, tier->c[i]);
            if (!a)
                put(&an, tier->c[i]); /* no axis: not lateral, not vertical */
        }
        const set_t *pick = tier->n == 1 ? tier : ax.n ? &ax : &an;
        if (pick->n != 1) {
            list_names(names, tier->c, tier->n, list, sizeof list);
            if (tier->n == 0)
                snprintf(g->why, sizeof g->why, "no column is named as an acceleration");
            else
                snprintf(g->why, sizeof g->why,
                         "several columns could be the longitudinal acceleration: %s", list);
            if (tier->n == 0 && nonacc.n) {
                list_names(names, nonacc.c, nonacc.n, list, sizeof list);
                const size_t k = strlen(g->why);
                snprintf(g->why + k, sizeof g->why - k, " (%s: %s)",
                         nonacc.n == 1 ? "its unit is not an acceleration"
                                       : "their units are not accelerations",
                         list);
            }
            return -1;
        }
        /* a lone lateral or vertical acceleration named as such is not
         * taken over a bare x ("X", "Accel Y (g)"): ask */
        const long c = pick->c[0];
        if (tier == &named && kinds[c].axis && kinds[c].axis != 'x') {
            set_t both = {0};
            put(&both, c);
            for (int i = 0; i < bare.n; i++)
                if (kinds[bare.c[i]].axis == 'x')
                    put(&both, bare.c[i]);
            if (both.n > 1) {
                list_names(names, both.c, both.n, list, sizeof list);
                snprintf(g->why, sizeof g->why,
                         "several columns could be the longitudinal acceleration: %s", list);
                return -1;
            }
        }
        g->col[SW_CSV_ROLE_ACCEL] = c;
        g->unit[SW_CSV_ROLE_ACCEL] = sw_csv_name_unit(names[c], 0);
    }
    return 0;
}

int sw_csv_guess_lat(const char names[][SW_CSV_NAME_MAX], long n, const long *taken, int ntaken,
                     long *col, char *why, size_t whylen)
{
    set_t named = {0}, bare = {0};
    char list[200];
    *col = -1;
    for (long i = 0; i < n && i < SW_CSV_MAX_FIELDS; i++) {
        int skip = 0;
        for (int k = 0; k < ntaken; k++) skip |= taken[k] == i;
        kind_t k;
        if (skip)
            continue;
        classify(names[i], &k);
        if (k.accel && k.axis == 'y')
            put(k.named ? &named : &bare, i);
    }
    const set_t *tier = named.n ? &named : &bare;
    if (tier->n > 1) {
        list_names(names, tier->c, tier->n, list, sizeof list);
        snprintf(why, whylen, "several columns could be the lateral acceleration: %s", list);
        return -1;
    }
    if (tier->n == 1)
        *col = tier->c[0];
    return 0;
}

/* ---- the columns the caller names ------------------------------------------ */

/* Column spec: 1-based index ("3") or a name.  Sets *col (0-based), or
 * *name and *len (trimmed, pointing into spec) with *col = -1. */
static int parse_column(const char *spec, const char *role, long *col, const char **name,
                        size_t *len, char *t, size_t tlen)
{
    while (sw_csv_is_blank(*spec)) spec++;
    size_t n = strlen(spec);
    while (n && sw_csv_is_blank(spec[n - 1])) n--;
    if (!n) {
        snprintf(t, tlen, "%s column: empty name", role);
        return SW_EINVAL;
    }
    size_t digits = 0;
    while (digits < n && spec[digits] >= '0' && spec[digits] <= '9') digits++;
    if (digits == n) {
        long v = 0;
        for (size_t i = 0; i < n; i++) {
            v = v * 10 + (spec[i] - '0');
            if (v > MAX_COLUMN_INDEX)
                break;
        }
        if (v < 1 || v > MAX_COLUMN_INDEX) {
            snprintf(t, tlen, "%s column %.*s: index out of range (1..%ld)", role, (int)n, spec,
                     MAX_COLUMN_INDEX);
            return SW_EINVAL;
        }
        *col = v - 1;
        return SW_OK;
    }
    *name = spec;
    *len = n;
    *col = -1;
    return SW_OK;
}

/* Two trimmed names, case-insensitively (ASCII). */
static int same_name(const char *a, size_t an, const char *b, size_t bn)
{
    if (an != bn)
        return 0;
    for (size_t i = 0; i < an; i++)
        if (sw_csv_lower(a[i]) != sw_csv_lower(b[i]))
            return 0;
    return 1;
}

int sw_csv_colspec_parse(const sw_csv_opts_t *o, sw_csv_colspec_t *cs, char *t, size_t tlen)
{
    memset(cs, 0, sizeof *cs);
    cs->col[R_VERT] = cs->col[R_LAT] = -1;
    const char *spec[N_ROLES] = {o->time_col ? o->time_col : "1", o->accel_col ? o->accel_col : "2",
                                 o->vert_col, o->lat_col};
    for (int r = 0; r < N_ROLES; r++) {
        cs->given[r] = (r == R_TIME    ? o->time_col
                        : r == R_ACCEL ? o->accel_col
                        : r == R_VERT  ? o->vert_col
                                       : o->lat_col) != NULL;
        if (!spec[r])
            continue;
        int rc =
            parse_column(spec[r], role_name[r], &cs->col[r], &cs->name[r], &cs->len[r], t, tlen);
        if (rc != SW_OK)
            return rc;
    }
    for (int r = 0; r < N_ROLES; r++) {
        for (int q = r + 1; q < N_ROLES; q++) {
            int same = (cs->col[r] >= 0 && cs->col[r] == cs->col[q]) ||
                       (cs->name[r] && cs->name[q] &&
                        same_name(cs->name[r], cs->len[r], cs->name[q], cs->len[q]));
            if (same) {
                snprintf(t, tlen, "%s and %s columns are the same", role_name[r], role_name[q]);
                return SW_EINVAL;
            }
        }
        if (cs->name[r] && o->header == 0) {
            snprintf(t, tlen,
                     "%s column \"%.*s\" is named but the input has no header (header = 0); "
                     "give a 1-based index",
                     role_name[r], (int)cs->len[r], cs->name[r]);
            return SW_ENOTFOUND;
        }
    }
    return SW_OK;
}

/* ---- the header read: columns and units -------------------------------- */

/* The unit a scale stands for: s, ms, us for time; m/s^2 or g. */
static int unit_of_scale(int r, double scale)
{
    if (r == R_TIME)
        return scale == 1.0    ? SW_CSV_UNIT_S
               : scale == 1e-3 ? SW_CSV_UNIT_MS
               : scale == 1e-6 ? SW_CSV_UNIT_US
               : scale == 1e-9 ? SW_CSV_UNIT_NS
                               : SW_CSV_UNIT_NONE;
    return scale == 1.0            ? SW_CSV_UNIT_MPS2
           : scale == SW_G0        ? SW_CSV_UNIT_G
           : scale == SW_G0 * 1e-3 ? SW_CSV_UNIT_MG
                                   : SW_CSV_UNIT_NONE;
}

/* "column 2 \"Date\"" or "column 2", into dst. */
static void column_name(const sw_csv_layout_t *L, char *dst, size_t cap)
{
    if (L->name[R_TIME][0])
        snprintf(dst, cap, "column %ld \"%s\"", L->col[R_TIME] + 1, L->name[R_TIME]);
    else
        snprintf(dst, cap, "column %ld", L->col[R_TIME] + 1);
}

/* What the time column's values say, once it is chosen: date-times (with
 * day and month in which order), or numbers whose magnitude is an epoch's
 * (its unit, when neither the caller nor the name gave one). */
static int time_values(const sw_csv_infer_in_t *in, sw_csv_layout_t *L, char *msg, size_t msglen)
{
    const long tc = L->col[R_TIME];
    const sw_csv_profile_t *p = tc >= 0 && tc < in->nprof ? &in->prof[tc] : NULL;
    char what[SW_CSV_NAME_MAX + 32];
    if (!p)
        return SW_OK;
    column_name(L, what, sizeof what);
    if (p->ndm > 0 && p->ndm >= p->nnum + p->niso) {
        int order = in->date_order, from = SW_CSV_FROM_OPTION;
        if (order == SW_CSV_DATE_AUTO) {
            from = SW_CSV_FROM_VALUES;
            order = p->a13 && !p->b13   ? SW_CSV_DATE_DMY
                    : p->b13 && !p->a13 ? SW_CSV_DATE_MDY
                                        : SW_CSV_DATE_AUTO;
        }
        if (order == SW_CSV_DATE_AUTO) {
            if (p->a13 && p->b13)
                snprintf(msg, msglen,
                         "time %s: its dates have a day above 12 first in %ld rows and second "
                         "in %ld: say which order is right with --date-order dmy or "
                         "--date-order mdy",
                         what, p->a13, p->b13);
            else
                snprintf(msg, msglen,
                         "time %s: its dates write day and month before the year, and none of "
                         "the first %ld has a number above 12 to tell which is the day: say "
                         "--date-order dmy (day first) or --date-order mdy (month first)",
                         what, p->ndm);
            return SW_EAMBIGUOUS;
        }
        L->date_order = order;
        L->unit[R_TIME] = SW_CSV_UNIT_DATETIME;
        L->unit_from[R_TIME] = from;
        L->scale[R_TIME] = 1.0;
        return SW_OK;
    }
    if (p->niso > 0 && p->niso >= p->nnum) {
        L->unit[R_TIME] = SW_CSV_UNIT_DATETIME;
        L->unit_from[R_TIME] = SW_CSV_FROM_VALUES;
        L->scale[R_TIME] = 1.0;
        return SW_OK;
    }
    if (p->nnum == 0)
        return SW_OK;
    /* numbers in a unit no option reads: in s by default they would be 60
     * or 3600 times too fast, a confident wrong verdict */
    char unread[SW_CSV_WORD_MAX * 2];
    if (in->infer && !in->scale_given[0] && L->header_unit[R_TIME] == SW_CSV_UNIT_NONE &&
        sw_csv_time_unit_unread(L->name[R_TIME], unread, sizeof unread)) {
        snprintf(msg, msglen,
                 "time %s: its name gives the unit \"%s\", which is not read (s, ms, us or "
                 "ns): write the times in one of those and say which with --time-unit",
                 what, unread);
        return SW_EAMBIGUOUS;
    }
    const int eu = sw_csv_epoch_unit(p->first);
    if (in->infer && !in->scale_given[0] && L->header_unit[R_TIME] == SW_CSV_UNIT_NONE &&
        eu != SW_CSV_UNIT_NONE) {
        L->scale[R_TIME] = sw_csv_unit_scale(eu);
        L->unit[R_TIME] = eu;
        L->unit_from[R_TIME] = SW_CSV_FROM_VALUES;
        L->epoch = 1;
        return SW_OK;
    }
    L->epoch = sw_csv_epoch_unit(p->first * L->scale[R_TIME]) == SW_CSV_UNIT_S;
    return SW_OK;
}

static int infer(const sw_csv_infer_in_t *in, sw_csv_layout_t *L, char *msg, size_t msglen);

/* The header's lateral column, when the caller gave none: read
 * (in->lateral: col[R_LAT], or the parse refused when several fit), or
 * only said (*unread). */
static int lateral_of(const sw_csv_infer_in_t *in, long col[N_ROLES], long *unread, char *msg,
                      size_t msglen)
{
    const long taken[] = {col[R_TIME], col[R_ACCEL], col[R_VERT]};
    char why[200];
    long c = -1;
    if (sw_csv_guess_lat(in->names, in->nnames, taken, 3, &c, why, sizeof why) != 0) {
        if (!in->lateral)
            return SW_OK; /* not read: nothing to decide */
        snprintf(msg, msglen,
                 "cannot tell the columns from the header: %s; say which with "
                 "--lat-col",
                 why);
        return SW_EAMBIGUOUS;
    }
    if (in->lateral)
        col[R_LAT] = c;
    else
        *unread = c;
    return SW_OK;
}

/* The lateral column's unit: the acceleration unit given, else its own
 * name's, else the longitudinal column's (a log writes its axes in one
 * unit); and the name of a lateral column not read. */
static void lateral_unit(const sw_csv_infer_in_t *in, sw_csv_layout_t *L, long unread)
{
    L->lat_unread = unread;
    if (unread >= 0 && unread < in->nnames)
        snprintf(L->name[R_LAT], sizeof L->name[R_LAT], "%s", in->names[unread]);
    if (L->col[R_LAT] < 0)
        return;
    const int hu = L->header_unit[R_LAT];
    L->unit_from[R_LAT] = L->unit_from[R_ACCEL];
    if (!in->scale_given[1] && in->infer && hu != SW_CSV_UNIT_NONE) {
        L->scale[R_LAT] = sw_csv_unit_scale(hu);
        L->unit[R_LAT] = hu;
        L->unit_from[R_LAT] = SW_CSV_FROM_HEADER;
    }
    if (L->col_from[R_LAT] == SW_CSV_FROM_DEFAULT)
        L->col_from[R_LAT] = SW_CSV_FROM_HEADER; /* inferred */
}

int sw_csv_infer(const sw_csv_infer_in_t *in, sw_csv_layout_t *out, char *msg, size_t msglen)
{
    sw_csv_layout_t L;
    const int rc = infer(in, &L, msg, msglen);
    if (rc == SW_OK)
        *out = L; /* a layout is given whole, or not at all */
    return rc;
}

static int infer(const sw_csv_infer_in_t *in, sw_csv_layout_t *L, char *msg, size_t msglen)
{
    long col[N_ROLES], lat_unread = -1;
    double tscale = in->scale[0], ascale = in->scale[1];
    memset(L, 0, sizeof *L);
    msg[0] = '\0';
    for (int r = 0; r < N_ROLES; r++) col[r] = in->col[r];
    if (in->has_header) {
        /* the named columns */
        for (int r = 0; r < N_ROLES; r++) {
            if (!in->name[r])
                continue;
            if (in->match[r] < 0) {
                snprintf(msg, msglen, "no column named \"%s\" (%s) in the header", in->name[r],
                         role_name[r]);
                return SW_ENOTFOUND;
            }
            col[r] = in->match[r];
        }
        /* the columns and units nobody gave, from the names */
        const int want[SW_CSV_NROLES] = {!in->col_given[R_TIME], !in->col_given[R_ACCEL], 0};
        if (in->infer) {
            sw_csv_guess_t g;
            if ((want[0] || want[1]) && sw_csv_guess(in->names, in->nnames, want, col[R_VERT],
                                                     in->prof, in->nprof, &g) != 0) {
                snprintf(msg, msglen, "cannot tell the columns from the header: %s", g.why);
                return SW_EAMBIGUOUS;
            }
            for (int r = 0; r < 2; r++)
                if (want[r]) {
                    col[r] = g.col[r];
                    L->col_from[r] = SW_CSV_FROM_HEADER;
                }
            const int tu = col[R_TIME] < in->nnames ? sw_csv_name_unit(in->names[col[R_TIME]], 1)
                                                    : SW_CSV_UNIT_NONE;
            const int au = col[R_ACCEL] < in->nnames ? sw_csv_name_unit(in->names[col[R_ACCEL]], 0)
                                                     : SW_CSV_UNIT_NONE;
            if (!in->scale_given[0] && tu != SW_CSV_UNIT_NONE)
                tscale = sw_csv_unit_scale(tu);
            if (!in->scale_given[1] && au != SW_CSV_UNIT_NONE)
                ascale = sw_csv_unit_scale(au);
            if (col[R_LAT] < 0 && !in->col_given[R_LAT]) {
                const int rc = lateral_of(in, col, &lat_unread, msg, msglen);
                if (rc != SW_OK)
                    return rc;
            }
        }
        for (int r = 0; r < N_ROLES; r++)
            for (int q = r + 1; q < N_ROLES; q++)
                if (col[r] >= 0 && col[r] == col[q]) {
                    snprintf(msg, msglen, "%s and %s are the same column (%ld)", role_name[r],
                             role_name[q], col[r] + 1);
                    return SW_EINVAL;
                }
    }

    /* the layout: which columns, in which units, and where each came from */
    L->ready = 1;
    L->delim = in->delim;
    L->has_header = in->has_header;
    L->decimal_comma = in->decimal_comma;
    for (int r = 0; r < N_ROLES; r++) {
        L->col[r] = col[r];
        L->name[r][0] = '\0';
        if (in->has_header && col[r] >= 0 && col[r] < in->nnames)
            snprintf(L->name[r], sizeof L->name[r], "%s", in->names[col[r]]);
        L->scale[r] = r == R_TIME ? tscale : ascale;
        L->unit[r] = unit_of_scale(r, L->scale[r]);
        L->header_unit[r] =
            L->name[r][0] ? sw_csv_name_unit(L->name[r], r == R_TIME) : SW_CSV_UNIT_NONE;
        if (L->col_from[r] != SW_CSV_FROM_HEADER)
            L->col_from[r] = in->col_given[r] ? SW_CSV_FROM_OPTION : SW_CSV_FROM_DEFAULT;
        const int given = in->scale_given[r == R_TIME ? 0 : 1];
        L->unit_from[r] = given ? SW_CSV_FROM_OPTION : SW_CSV_FROM_DEFAULT;
    }
    if (in->tkind == 2)
        L->unit[R_TIME] = SW_CSV_UNIT_DATETIME;
    if (in->has_header && in->infer) {
        /* without infer the names are not read: the units are the defaults */
        const int tu = L->header_unit[R_TIME], au = L->header_unit[R_ACCEL];
        if (in->scale_given[0] && tu != SW_CSV_UNIT_NONE && tu != L->unit[R_TIME])
            L->unit_from[R_TIME] = SW_CSV_FROM_OPTION; /* overrides the header */
        if (!in->scale_given[0] && tu != SW_CSV_UNIT_NONE)
            L->unit_from[R_TIME] = SW_CSV_FROM_HEADER;
        if (!in->scale_given[1] && au != SW_CSV_UNIT_NONE)
            L->unit_from[R_ACCEL] = L->unit_from[R_VERT] = SW_CSV_FROM_HEADER;
    }
    lateral_unit(in, L, lat_unread);
    return time_values(in, L, msg, msglen);
}
