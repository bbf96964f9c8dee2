/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_infer.c - a logger export's header read as a person reads it: which
 * column is time and which is the longitudinal acceleration, and in what
 * units ("Time (ms)", "X (g)", "time_ms;accel_g", "Acceleration Gs",
 * "ax [m/s²]").  It decides only what the names say without doubt; when
 * two columns fit equally, or none does, it says so and the caller asks the
 * user, because a wrong guess gives a confident wrong verdict.
 *
 * A name is split into words (letters and digits; a bracketed part is its
 * unit); a unit may also be the last word ("time_ms", "accel_g").  Time is
 * a word such as time, t, timestamp or elapsed (not sample, index, count);
 * acceleration a word such as accel, acc, acceleration, ax, or any name
 * whose unit is an acceleration ("X (g)").  Among several acceleration
 * columns the longitudinal one is the x axis (the vehicle frame: x points
 * forward) or one named longitudinal or forward, else the only one that
 * names no axis beside lateral and vertical ones; among several time
 * columns the one with a unit (elapsed seconds) is preferred to one without
 * (a date-time).  The columns the caller names or numbers instead are
 * read here too (sw_csv_colspec_parse).  Everything here is a function of
 * its arguments: the reader (csv.c) hands in what it read and applies the
 * layout, or ends the parse with the code and message returned. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csv_int.h"
#include "swaywatch/status.h"

typedef struct {
    int time, index, accel; /* the name reads as time, a sample index, an acceleration */
    int axis;               /* 'x' (longitudinal), 'y', 'z', or 0 */
    int tunit, aunit;       /* units read for the time role and as an acceleration */
} kind_t;

static void classify(const char *name, kind_t *k)
{
    static const char *const time_w[] = {"time",     "t",   "timestamp", "ts",    "elapsed", "date",
                                         "datetime", "utc", "epoch",     "clock", NULL};
    static const char *const index_w[] = {"sample", "samples", "index", "idx",   "n",
                                          "no",     "nr",      "num",   "count", "seq",
                                          "id",     "record",  "row",   NULL};
    static const char *const accel_w[] = {"accel",         "acc", "acceleration",
                                          "accelerometer", "a",   NULL};
    static const char *const x_w[] = {"x",    "ax",           "accx", "accelx",  "xaccel", "xacc",
                                      "long", "longitudinal", "lon",  "forward", "fwd",    "surge",
                                      NULL};
    static const char *const y_w[] = {"y",    "ay",  "accy",    "accely", "yaccel",
                                      "yacc", "lat", "lateral", "sway",   NULL};
    static const char *const z_w[] = {"z",    "az",       "accz",  "accelz", "zaccel", "zacc",
                                      "vert", "vertical", "heave", "up",     NULL};
    sw_csv_words_t w;
    int tlast, alast;
    sw_csv_words(name, &w);
    memset(k, 0, sizeof *k);
    k->tunit = sw_csv_words_unit(&w, 1, &tlast);
    k->aunit = sw_csv_words_unit(&w, 0, &alast);
    for (int i = 0; i < w.nw; i++) {
        /* a numbered name reads as its word: "acc1", "time2" */
        char x[SW_CSV_WORD_MAX];
        snprintf(x, sizeof x, "%s", w.w[i]);
        size_t xl = strlen(x);
        while (xl > 1 && x[xl - 1] >= '0' && x[xl - 1] <= '9') x[--xl] = '\0';
        if (sw_csv_word_in(x, index_w))
            k->index = 1;
        if (sw_csv_word_in(x, time_w) && !(tlast && i == w.nw - 1))
            k->time = 1;
        if (alast && i == w.nw - 1)
            continue; /* the unit word */
        if (sw_csv_word_in(x, accel_w))
            k->accel = 1;
        if (sw_csv_word_in(x, x_w))
            k->axis = 'x';
        if (sw_csv_word_in(x, y_w))
            k->axis = 'y';
        if (sw_csv_word_in(x, z_w))
            k->axis = 'z';
    }
    if (k->aunit != SW_CSV_UNIT_NONE || (k->axis && !k->time))
        k->accel = 1;
    if (k->index || k->accel)
        k->time = 0;
    if (k->time)
        k->accel = 0;
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

int sw_csv_guess(const char names[][SW_CSV_NAME_MAX], long n, const int want[SW_CSV_NROLES],
                 long skip, sw_csv_guess_t *g)
{
    enum { CAP = 16 };
    long tc[CAP] = {0}, tu[CAP] = {0}, ac[CAP] = {0}, ax[CAP] = {0}, an[CAP] = {0};
    int ntc = 0, ntu = 0, nac = 0, nax = 0, nan_ = 0;
    char list[200];
    memset(g, 0, sizeof *g);
    for (int r = 0; r < SW_CSV_NROLES; r++) g->col[r] = -1;
    for (long i = 0; i < n; i++) {
        kind_t k;
        if (i == skip)
            continue;
        classify(names[i], &k);
        if (k.time && ntc < CAP) {
            tc[ntc++] = i;
            if (k.tunit != SW_CSV_UNIT_NONE && ntu < CAP)
                tu[ntu++] = i;
        }
        if (k.accel && nac < CAP) {
            ac[nac++] = i;
            if (k.axis == 'x' && nax < CAP)
                ax[nax++] = i;
            if (!k.axis && nan_ < CAP)
                an[nan_++] = i; /* no axis: not lateral, not vertical */
        }
    }
    if (want[SW_CSV_ROLE_TIME]) {
        /* elapsed time with a unit beats a date-time or a bare name */
        const long *set = ntu ? tu : tc;
        const int ns = ntu ? ntu : ntc;
        if (ns != 1) {
            list_names(names, set, ns, list, sizeof list);
            if (ns == 0)
                snprintf(g->why, sizeof g->why, "no column is named as time");
            else
                snprintf(g->why, sizeof g->why, "several columns could be time: %s", list);
            return -1;
        }
        g->col[SW_CSV_ROLE_TIME] = set[0];
        g->unit[SW_CSV_ROLE_TIME] = sw_csv_name_unit(names[set[0]], 1);
    }
    if (want[SW_CSV_ROLE_ACCEL]) {
        /* one acceleration column; or among several the one along x; or,
         * with no x, the one that names no axis beside lateral and
         * vertical ones ("accel, z") */
        const long *set = nac == 1 ? ac : nax ? ax : an;
        const int ns = nac == 1 ? 1 : nax ? nax : nan_;
        if (ns != 1) {
            list_names(names, nac ? ac : ax, nac ? nac : nax, list, sizeof list);
            if (nac == 0)
                snprintf(g->why, sizeof g->why, "no column is named as an acceleration");
            else
                snprintf(g->why, sizeof g->why,
                         "several columns could be the longitudinal acceleration: %s", list);
            return -1;
        }
        g->col[SW_CSV_ROLE_ACCEL] = set[0];
        g->unit[SW_CSV_ROLE_ACCEL] = sw_csv_name_unit(names[set[0]], 0);
    }
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
    cs->col[R_VERT] = -1;
    const char *spec[N_ROLES] = {o->time_col ? o->time_col : "1", o->accel_col ? o->accel_col : "2",
                                 o->vert_col};
    for (int r = 0; r < N_ROLES; r++) {
        cs->given[r] = (r == R_TIME    ? o->time_col
                        : r == R_ACCEL ? o->accel_col
                                       : o->vert_col) != NULL;
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
                               : SW_CSV_UNIT_NONE;
    return scale == 1.0 ? SW_CSV_UNIT_MPS2 : scale == SW_G0 ? SW_CSV_UNIT_G : SW_CSV_UNIT_NONE;
}

int sw_csv_infer(const sw_csv_infer_in_t *in, sw_csv_layout_t *L, char *msg, size_t msglen)
{
    long col[N_ROLES];
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
            if ((want[0] || want[1]) &&
                sw_csv_guess(in->names, in->nnames, want, col[R_VERT], &g) != 0) {
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
    if (in->has_header) {
        const int tu = L->header_unit[R_TIME], au = L->header_unit[R_ACCEL];
        if (in->scale_given[0] && tu != SW_CSV_UNIT_NONE && tu != L->unit[R_TIME])
            L->unit_from[R_TIME] = SW_CSV_FROM_OPTION; /* overrides the header */
        if (!in->scale_given[0] && tu != SW_CSV_UNIT_NONE)
            L->unit_from[R_TIME] = SW_CSV_FROM_HEADER;
        if (!in->scale_given[1] && au != SW_CSV_UNIT_NONE)
            L->unit_from[R_ACCEL] = L->unit_from[R_VERT] = SW_CSV_FROM_HEADER;
    }
    return SW_OK;
}
