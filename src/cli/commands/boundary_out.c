/* SPDX-License-Identifier: GPL-3.0-or-later */
/* boundary_out.c - what "swaywatch boundary" writes: the curves, the
 * detail and the safe islands as CSV, in g tan alpha or in physical units
 * (g, m/s^2, the pulse's duration in ms), the figure drawn by gnuplot,
 * and the notes on the points that need a word. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "boundary.h"
#include "output.h"
#include "plot.h"

/* ---- the quantities of the columns --------------------------------------------- */

/* ms, the pulse duration of curve c at point i. */
static double duration_ms(const boundary_t *B, size_t c, size_t i)
{
    if (B->b.durations)
        return B->b.durations[i] * 1e3;
    return sw_bnd_shape_angle(B) / (B->b.ratios[i] * B->cv[c].p) * 1e3;
}

/* The value of a row's first column: the duration (ms) with
 * --pulse-duration, else omega_e/p (the same for every curve). */
static double key_at(const boundary_t *B, size_t i)
{
    return B->b.durations ? B->b.durations[i] * 1e3 : B->b.ratios[i];
}

/* The other quantity of row i (omega_e/p or the duration), of curve c. */
static double other_at(const boundary_t *B, size_t c, size_t i)
{
    return B->b.durations ? sw_bnd_ratio_at(B, c, i) : duration_ms(B, c, i);
}

static const char *key_name(const boundary_t *B)
{
    return B->b.durations ? "duration_ms" : "omega_ratio";
}

static const char *other_name(const boundary_t *B)
{
    return B->b.durations ? "omega_ratio" : "duration_ms";
}

/* Amplitudes in the units written, per unit of g tan alpha of curve c. */
static double unit_scale(const boundary_t *B, size_t c)
{
    switch (B->units) {
        case UNITS_G: return B->cv[c].gtan / SW_G0;
        case UNITS_MPS2: return B->cv[c].gtan;
        default: return 1.0;
    }
}

/* The unit after a curve's name in a CSV header: " (g)", " (m/s^2)". */
static const char *unit_suffix(const boundary_t *B)
{
    return B->units == UNITS_G ? " (g)" : B->units == UNITS_MPS2 ? " (m/s^2)" : "";
}

/* ---- output -------------------------------------------------------------------- */

static void csv_num(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.6g", v);
}

/* A header field "<label><text>". */
static void csv_label(FILE *f, const char *label, const char *text)
{
    char h[320];
    snprintf(h, sizeof h, "%s%s", label, text);
    sw_cli_csv_text(f, h);
}

static long write_curves(FILE *f, const boundary_t *B)
{
    const size_t nc = B->nc, nr = B->b.nr;
    const int per_curve = B->physical && !B->shared_p; /* the other quantity per curve */
    char other[32];
    snprintf(other, sizeof other, " %s", other_name(B));
    fputs(key_name(B), f);
    if (B->physical && B->shared_p)
        fprintf(f, ",%s", other_name(B));
    for (size_t c = 0; c < nc; c++) {
        if (per_curve) {
            fputc(',', f);
            csv_label(f, B->cv[c].label, other);
        }
        fputc(',', f);
        csv_label(f, B->cv[c].label, unit_suffix(B));
    }
    fputc('\n', f);
    for (size_t i = 0; i < nr; i++) {
        fprintf(f, "%.6g", key_at(B, i));
        if (B->physical && B->shared_p)
            fprintf(f, ",%.6g", other_at(B, 0, i));
        for (size_t c = 0; c < nc; c++) {
            const sw_boundary_point_t *P = &B->pts[c * nr + i];
            if (per_curve)
                fprintf(f, ",%.6g", other_at(B, c, i));
            fputc(',', f);
            if (P->th.found)
                csv_num(f, P->th.x * unit_scale(B, c));
        }
        fputc('\n', f);
    }
    return (long)nr;
}

static const char *end_name(sw_run_end e)
{
    switch (e) {
        case SW_END_OVERTURN: return "overturn";
        case SW_END_FALLING: return "falling";
        case SW_END_REST: return "rest";
        case SW_END_BOUND: return "bound";
        case SW_END_TIMEOUT: return "timeout";
    }
    return "unknown";
}

static long write_detail(FILE *f, const boundary_t *B)
{
    const size_t nc = B->nc, nr = B->b.nr;
    fputs(
        "curve,omega_ratio,found,boundary,safe_below,lift,impacts,uplift_side,overturn_side,"
        "uplift_time,tip_time,overturn_time,end,trials,duration_ms,boundary_g\n",
        f);
    for (size_t c = 0; c < nc; c++)
        for (size_t i = 0; i < nr; i++) {
            const sw_boundary_point_t *P = &B->pts[c * nr + i];
            const sw_run_result_t *r = &P->th.at_x;
            sw_cli_csv_text(f, B->cv[c].label);
            fprintf(f, ",%.6g,%d,", sw_bnd_ratio_at(B, c, i), P->th.found);
            if (P->th.found) {
                csv_num(f, P->th.x);
                fputc(',', f);
                if (!P->th.at_min)
                    csv_num(f, P->th.x_safe);
                fputc(',', f);
                csv_num(f, P->x_lift);
                fprintf(f, ",%ld,%d,%d,", r->impacts, r->uplift_side, r->overturn_side);
                csv_num(f, r->uplift_time);
                fputc(',', f);
                csv_num(f, r->tip_time);
                fputc(',', f);
                csv_num(f, r->overturn_time);
                fprintf(f, ",%s", end_name(r->end));
            } else {
                fputs(",,", f);
                csv_num(f, P->x_lift);
                fputs(",,,,,,,", f);
            }
            fprintf(f, ",%ld,%.6g,", P->th.trials, duration_ms(B, c, i));
            if (P->th.found)
                csv_num(f, P->th.x * B->cv[c].gtan / SW_G0);
            fputc('\n', f);
        }
    return (long)(nc * nr);
}

static long write_islands(FILE *f, const boundary_t *B)
{
    const size_t nc = B->nc, nr = B->b.nr;
    if (B->physical)
        fprintf(f, "curve,omega_ratio,duration_ms,from%s,to%s,open\n", unit_suffix(B),
                unit_suffix(B));
    else
        fputs("curve,omega_ratio,from,to,open\n", f);
    long rows = 0;
    for (size_t c = 0; c < nc; c++)
        for (size_t i = 0; i < nr; i++) {
            const sw_threshold_t *T = &B->pts[c * nr + i].th;
            const double k = unit_scale(B, c);
            for (int j = 0; j < T->n_islands; j++, rows++) {
                sw_cli_csv_text(f, B->cv[c].label);
                fprintf(f, ",%.6g", sw_bnd_ratio_at(B, c, i));
                if (B->physical)
                    fprintf(f, ",%.6g", duration_ms(B, c, i));
                fprintf(f, ",%.6g,%.6g,%d\n", T->islands[j].lo * k, T->islands[j].hi * k,
                        T->islands[j].open);
            }
        }
    return rows;
}

/* Write path with fn; *rows gets the data rows written. */
static int write_file(const char *path, const boundary_t *B, long (*fn)(FILE *, const boundary_t *),
                      long *rows)
{
    FILE *f = sw_cli_out_open(path);
    if (!f)
        return SW_EXIT_IO;
    *rows = fn(f, B);
    return sw_cli_out_close(f, path);
}

/* ---- figure -------------------------------------------------------------------- */

static const char *const colours[] = {"#1d3557", "#e76f51", "#2a9d8f", "#8338ec",
                                      "#f4a261", "#6a994e", "#b5179e", "#457b9d"};
#define NCOLOURS (sizeof colours / sizeof colours[0])

/* The curve's points as datablocks: $c<c> the boundary (NaN where none),
 * $b<c> / $f<c> the points overturning back / forward, $n<c> the points
 * with no overturn up to the scan's end (drawn there), $i<c> the safe
 * islands (x, from, to). */
static void curve_blocks(FILE *g, const boundary_t *B, size_t c)
{
    const size_t nr = B->b.nr;
    const double k = unit_scale(B, c);
    const char *names = "cbfni";
    for (const char *n = names; *n; n++) {
        int any = 0;
        fprintf(g, "$%c%zu << EOD\n", *n, c);
        for (size_t i = 0; i < nr; i++) {
            const sw_threshold_t *T = &B->pts[c * nr + i].th;
            const double x = key_at(B, i);
            const int side = T->at_x.overturn_side;
            switch (*n) {
                case 'c':
                    fprintf(g, "%.9g %.9g\n", x, T->found ? T->x * k : NAN);
                    any = 1;
                    break;
                case 'b':
                case 'f':
                    if (T->found && (*n == 'b' ? side < 0 : side > 0)) {
                        fprintf(g, "%.9g %.9g\n", x, T->x * k);
                        any = 1;
                    }
                    break;
                case 'n':
                    if (!T->found) {
                        fprintf(g, "%.9g %.9g\n", x, B->cv[c].x_max * k);
                        any = 1;
                    }
                    break;
                default:
                    for (int j = 0; j < T->n_islands; j++, any = 1)
                        fprintf(g, "%.9g %.9g %.9g\n", x, T->islands[j].lo * k,
                                T->islands[j].hi * k);
            }
        }
        if (!any)
            fputs(*n == 'i' ? "NaN NaN NaN\n" : "NaN NaN\n", g);
        fputs("EOD\n", g);
    }
}

/* Half the width of an island's box: a third of the closest spacing of
 * the points, so neighbours never touch. */
static double island_half_width(const boundary_t *B, double lo, double hi)
{
    double gap = INFINITY;
    for (size_t i = 0; i < B->b.nr; i++)
        for (size_t j = i + 1; j < B->b.nr; j++) {
            const double d = fabs(key_at(B, i) - key_at(B, j));
            if (d > 0.0 && d < gap)
                gap = d;
        }
    return isfinite(gap) ? gap / 3.0 : fmax(hi - lo, fabs(lo)) * 0.02 + 1e-9;
}

/* Tics of the top axis, whose value is K/x: round values (1, 1.5, 2, 3,
 * 4, 5, 6, 8 times a power of ten) at least 7 % of the width apart, as
 * gnuplot would place them on a linear axis of their own. */
static void x2_tics(FILE *g, double K, double x0, double x1)
{
    static const double mant[] = {1, 1.5, 2, 3, 4, 5, 6, 8};
    const double v0 = K / x1, v1 = K / x0; /* the top axis's range, increasing */
    const double min_gap = 0.07 * (x1 - x0);
    double last_x = NAN;
    int n = 0;
    fputs("set x2tics (", g);
    for (double dec = pow(10.0, floor(log10(v0))); dec <= v1 && n < 40; dec *= 10.0)
        for (size_t m = 0; m < sizeof mant / sizeof mant[0]; m++) {
            const double v = mant[m] * dec;
            if (v < v0 || v > v1)
                continue;
            const double x = K / v;
            if (isfinite(last_x) && fabs(last_x - x) < min_gap)
                continue;
            fprintf(g, "%s%.6g", n++ ? ", " : "", v);
            last_x = x;
        }
    fputs(")\n", g);
}

/* What a figure has to draw, and its ranges. */
typedef struct {
    double lo, hi, pad;           /* the x axis: the points' first column, and a margin */
    double top;                   /* the top of the y axis, in the units drawn */
    int same_max;                 /* every curve searched up to the same amplitude */
    int show_max;                 /* the maximum searched is drawn */
    int islands, back, fwd, none; /* islands; points overturning back, forward; none */
} extent_t;

static extent_t plot_extent(const boundary_t *B)
{
    const size_t nc = B->nc, nr = B->b.nr;
    extent_t E = {.lo = INFINITY, .hi = -INFINITY, .same_max = 1};
    double top = 0.0;
    for (size_t i = 0; i < nr; i++) {
        E.lo = fmin(E.lo, key_at(B, i));
        E.hi = fmax(E.hi, key_at(B, i));
    }
    /* What there is to draw; the maximum searched is in the picture when a
     * point reached it without an overturn, or an island is open to it. */
    int open = 0;
    double top_max = 0.0;
    for (size_t c = 0; c < nc; c++) {
        const double k = unit_scale(B, c), m = B->cv[c].x_max * k;
        E.same_max = E.same_max && fabs(m - B->cv[0].x_max * unit_scale(B, 0)) <= 1e-9 * m;
        top_max = fmax(top_max, m);
        for (size_t i = 0; i < nr; i++) {
            const sw_threshold_t *T = &B->pts[c * nr + i].th;
            if (T->found)
                top = fmax(top, T->x * k);
            E.back += T->found && T->at_x.overturn_side < 0;
            E.fwd += T->found && T->at_x.overturn_side > 0;
            E.none += !T->found;
            E.islands += T->n_islands;
            for (int j = 0; j < T->n_islands; j++) {
                top = fmax(top, T->islands[j].hi * k);
                open += T->islands[j].open;
            }
        }
    }
    E.show_max = E.none || open || top_max <= 1.3 * top;
    if (E.show_max || !(top > 0.0))
        top = fmax(top, top_max);
    E.top = top;
    E.pad = E.hi > E.lo ? 0.015 * (E.hi - E.lo) : 0.05 * fmax(fabs(E.lo), 1e-6);
    return E;
}

/* The title, the axes (in physical units the other quantity along the
 * top) and the note on directions. */
static void plot_axes(FILE *g, const boundary_t *B, const extent_t *E)
{
    const double lo = E->lo, hi = E->hi, pad = E->pad;
    char deftitle[128];
    snprintf(deftitle, sizeof deftitle, "Overturning boundary, %s pulse%s",
             sw_pulse_shape_name(B->b.bo.shape), B->b.lateral ? ", across the truck" : "");
    fputs("set title ", g);
    sw_cli_plot_text(g, B->b.title ? B->b.title : deftitle);
    fprintf(g, "\nset xlabel '%s'\nset ylabel '%s'\n",
            B->b.durations ? "pulse duration (ms)" : "ω_e / p",
            B->units == UNITS_G      ? "peak acceleration a_e (g)"
            : B->units == UNITS_MPS2 ? "peak acceleration a_e (m/s^2)"
                                     : "a_e / (g tan α)");
    fprintf(g,
            "set grid\nset key at screen 0.675, graph 1 left top Left reverse box opaque\n"
            "set lmargin at screen 0.07\nset rmargin at screen 0.66\n"
            "set xrange [%.9g:%.9g]\nset yrange [0:%.9g]\nset datafile missing 'NaN'\n",
            lo - pad, hi + pad, 1.08 * E->top);
    if (B->physical && B->shared_p) {
        /* the other quantity along the top: duration = angle / (ratio p), both ways */
        const double K = sw_bnd_shape_angle(B) * 1e3 / B->cv[0].p;
        fprintf(g,
                "set link x2 via %.12g/x inverse %.12g/x\nset xtics nomirror\n"
                "set x2label '%s'\n",
                K, K, B->b.durations ? "ω_e / p" : "pulse duration (ms)");
        x2_tics(g, K, lo - pad, hi + pad);
    }
    fputs(
        "set label 1 'a_e > 0 speeds the truck up: the package sways back first;' "
        "at screen 0.675, screen 0.16 left font ',9'\n"
        "set label 2 'under braking, forward and back swap.' "
        "at screen 0.675, screen 0.125 left font ',9'\n",
        g);
}

/* The plot command: each curve's islands, line and points, then the
 * legend's entries for what the colours share. */
static void plot_series(FILE *g, const boundary_t *B, const extent_t *E)
{
    const size_t nc = B->nc;
    const int show_max = E->show_max, same_max = E->same_max;
    const double w = island_half_width(B, E->lo, E->hi);
    fputs("plot ", g);
    for (size_t c = 0; c < nc; c++) {
        const char *col = colours[c % NCOLOURS];
        if (E->islands)
            fprintf(g,
                    "$i%zu using 1:(($2+$3)/2):($1-%.9g):($1+%.9g):2:3 with boxxyerror "
                    "fs transparent solid 0.25 noborder lc rgb '%s' notitle, \\\n     ",
                    c, w, w, col);
        fprintf(g, "$c%zu using 1:2 with lines lw 2 lc rgb '%s' title ", c, col);
        sw_cli_plot_text(g, B->cv[c].label);
        fprintf(g,
                ", $b%zu using 1:2 with points pt 7 ps 0.9 lc rgb '%s' notitle"
                ", $f%zu using 1:2 with points pt 11 ps 1.3 lc rgb '%s' notitle"
                ", $n%zu using 1:2 with points pt 8 ps 1.4 lc rgb '%s' notitle",
                c, col, c, col, c, col);
        if (show_max && !same_max)
            fprintf(g, ", %.9g with lines lc rgb '%s' dt 2 notitle",
                    B->cv[c].x_max * unit_scale(B, c), col);
        fputs(", \\\n     ", g);
    }
    if (show_max && same_max)
        fprintf(g, "%.9g with lines lc rgb '#888888' dt 2 title 'the maximum searched'",
                B->cv[0].x_max * unit_scale(B, 0));
    else if (show_max)
        fputs("NaN with lines lc rgb '#888888' dt 2 title 'the maximum searched (each curve)'", g);
    else
        fputs("NaN notitle", g);
    if (E->back)
        fputs(
            ", NaN with points pt 7 ps 0.9 lc rgb 'black' title 'overturns back (top to the "
            "rear)'",
            g);
    if (E->fwd)
        fputs(
            ", NaN with points pt 11 ps 1.3 lc rgb 'black' title 'overturns forward (top to "
            "the front)'",
            g);
    if (E->none)
        fputs(
            ", NaN with points pt 8 ps 1.4 lc rgb 'black' title 'no overturn up to the "
            "maximum'",
            g);
    if (E->islands)
        fputs(
            ", NaN with boxes fs transparent solid 0.25 noborder lc rgb '#555555' "
            "title 'safe islands above the boundary'",
            g);
    fputc('\n', g);
}

static int plot(const char *path, const boundary_t *B)
{
    const extent_t E = plot_extent(B);
    sw_plot_t *p = sw_cli_plot_open(path, 1200, 650);
    if (!p)
        return SW_EXIT_IO;
    FILE *g = sw_cli_plot_file(p);
    plot_axes(g, B, &E);
    for (size_t c = 0; c < B->nc; c++) curve_blocks(g, B, c);
    plot_series(g, B, &E);
    return sw_cli_plot_close(p);
}

/* The points that need a word: not overturned, an upper bound, more
 * islands than listed. */
static void notes(const boundary_t *B)
{
    long at_min = 0, missing = 0, truncated = 0;
    const size_t np = B->nc * B->b.nr;
    for (size_t i = 0; i < np; i++) {
        at_min += B->pts[i].th.found && B->pts[i].th.at_min;
        missing += !B->pts[i].th.found;
        truncated += B->pts[i].th.islands_truncated;
    }
    if (missing) {
        char max[64];
        if (B->b.max_arg)
            snprintf(max, sizeof max, "%s", B->b.max_arg);
        else
            snprintf(max, sizeof max, "%g", DEFAULT_X_MAX);
        sw_cli_error(
            "boundary: %ld of %zu points did not overturn up to --max-amplitude %s "
            "(empty fields)",
            missing, np, max);
    }
    if (at_min)
        sw_cli_error(
            "boundary: %ld points overturned at --min-amplitude already: their "
            "value is an upper bound",
            at_min);
    if (truncated)
        sw_cli_error(
            "boundary: %ld points have more than %d safe islands; the rest are "
            "not listed",
            truncated, SW_MAX_ISLANDS);
}

/* The files, each said on stderr with what it holds, then the points that
 * need a word (unless --quiet). */
int sw_bnd_write_outputs(const boundary_t *B)
{
    const size_t nc = B->nc;
    const int say = !B->b.quiet;
    const char *out = B->b.out ? B->b.out : "-";
    long rows = 0;
    int rc = write_file(out, B, write_curves, &rows);
    if (rc == SW_EXIT_OK && say)
        sw_cli_error("boundary: wrote %s: %zu curve%s at %ld point%s", sw_cli_out_name(out), nc,
                     nc == 1 ? "" : "s", rows, rows == 1 ? "" : "s");
    if (rc == SW_EXIT_OK && B->b.detail) {
        rc = write_file(B->b.detail, B, write_detail, &rows);
        if (rc == SW_EXIT_OK && say)
            sw_cli_error("boundary: wrote %s: %ld row%s, one per curve and point",
                         sw_cli_out_name(B->b.detail), rows, rows == 1 ? "" : "s");
    }
    if (rc == SW_EXIT_OK && B->b.islands) {
        rc = write_file(B->b.islands, B, write_islands, &rows);
        if (rc == SW_EXIT_OK && say)
            sw_cli_error("boundary: wrote %s: %ld safe island%s", sw_cli_out_name(B->b.islands),
                         rows, rows == 1 ? "" : "s");
    }
    if (rc == SW_EXIT_OK && B->b.plot) {
        rc = plot(B->b.plot, B);
        if (rc == SW_EXIT_OK && say)
            sw_cli_error("boundary: wrote %s: a figure of %zu curve%s", B->b.plot, nc,
                         nc == 1 ? "" : "s");
    }
    if (!say)
        return rc;
    notes(B);
    return rc;
}
