/* SPDX-License-Identifier: GPL-3.0-or-later */
/* figure.c - the state figure of replay, simulate and forensics (figure.h):
 * the series kept in merging min/max buckets, the events, and the gnuplot
 * script that draws them in panels sharing the time axis (a table: what
 * is drawn and the caption that says it come from the same rows). */
#include "figure.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"
#include "swaywatch/series.h"

/* buckets per package after a merge; at most twice as many (the gnuplot
 * fuzz target, whose figures hold a few samples, lowers it with -D: the
 * buckets of three packages are 1.5 MiB to allocate and clear) */
#ifndef SW_FIG_BUCKETS
#define SW_FIG_BUCKETS 2000
#endif
#define NBUCKETS ((size_t)SW_FIG_BUCKETS)
#define MAX_EVENTS 100000   /* events kept */
#define MAX_LINES 200       /* vertical event lines drawn (gnuplot arrows) */
#define MAX_UPLIFT_LINES 50 /* of them uplifts: a long drive can have thousands */
#define MARGIN_FLOOR (-1.0) /* the margin panel shows margins down to this */

/* The quantities kept per package (the reserve only with a risk). */
enum { Q_AG, Q_RATIO, Q_MARGIN, Q_RESERVE, NQ };

/* The panels, top to bottom (the lateral tilt only with a lateral plane). */
enum { P_ACCEL, P_TILT, P_TILT_LAT, P_MARGIN, P_RESERVE, NPANELS };

#define MAX_GAPS 50 /* gaps shaded */
#define MAX_MARKS 8 /* decisive moments marked */

/* One plane of one package: a package with a lateral plane has two
 * traces, the lateral one after every longitudinal one. */
typedef struct {
    char name[64];
    size_t pkg;         /* the package */
    int lat;            /* the lateral plane (across the truck, over the depth) */
    double alpha;       /* rad, of this plane */
    double g_tan_alpha; /* m/s^2, the uplift threshold on a rigid support */
    sw_series_t *s;     /* the NQ quantities, as the extremes of NBUCKETS stretches */
} trace_t;

struct sw_cli_figure {
    trace_t *tr;
    size_t n;              /* traces: the packages', then their lateral planes' */
    size_t npkg;           /* packages */
    size_t *lat_of;        /* package -> its lateral trace, or NO_LAT */
    size_t nlat;           /* lateral traces */
    const sw_stream_t *st; /* the lateral planes' reserve; NULL: none drawn */
    sw_event_t *ev;
    size_t nev, cap;
    long dropped;            /* events beyond MAX_EVENTS, or lost to a failed allocation */
    const sw_risk_t *risk;   /* NULL: no reserve panel */
    int windowed;            /* only states and events in [w0, w1] are kept */
    double w0, w1;           /* s */
    int no_margin;           /* the margin panel left out */
    double gap[MAX_GAPS][2]; /* s, spans without samples, shaded */
    size_t ngap;
    double mark[MAX_MARKS]; /* s, decisive moments: a solid line */
    size_t nmark;
};

/* Line colours of the packages, in order (then again). */
static const char *const colours[] = {"#1d3557", "#e76f51", "#2a9d8f", "#8338ec",
                                      "#f4a261", "#6a994e", "#b5179e", "#457b9d"};
#define NCOLOURS (sizeof colours / sizeof colours[0])
#define NO_LAT ((size_t)-1)

/* A trace's colour: its package's, in both planes. */
static const char *colour(const trace_t *T)
{
    return colours[T->pkg % NCOLOURS];
}

sw_cli_figure_t *sw_cli_figure_create(const sw_engine_t *e, const sw_scene_t *scenes, size_t n)
{
    sw_cli_figure_t *f = calloc(1, sizeof *f);
    size_t nlat = 0;
    for (size_t i = 0; i < n; i++) nlat += sw_engine_planes(e, i) == 2;
    if (f) {
        f->tr = calloc(n + nlat ? n + nlat : 1, sizeof *f->tr);
        f->lat_of = calloc(n ? n : 1, sizeof *f->lat_of);
    }
    if (!f || !f->tr || !f->lat_of)
        goto oom;
    f->npkg = n;
    f->nlat = nlat;
    f->n = n + nlat;
    for (size_t i = 0, j = n; i < n; i++) {
        f->lat_of[i] = NO_LAT;
        for (int plane = 0; plane < 2; plane++) {
            size_t k = i;
            const sw_engine_t *pe =
                plane ? sw_engine_plane(e, i, SW_PLANE_LAT, &k) : e; /* its plane's engine */
            if (!pe)
                continue;
            if (plane)
                f->lat_of[i] = j;
            trace_t *T = &f->tr[plane ? j++ : i];
            const sw_derived_t *d = sw_engine_derived(pe, k);
            snprintf(T->name, sizeof T->name, "%s", scenes[i].name);
            T->pkg = i;
            T->lat = plane;
            T->alpha = d ? d->alpha : NAN;
            T->g_tan_alpha = d ? scenes[i].g * tan(d->alpha) : NAN;
            if (!(T->s = sw_series_create(NQ, NBUCKETS)))
                goto oom;
        }
    }
    return f;
oom:
    sw_cli_figure_destroy(f);
    sw_cli_error("out of memory for the figure");
    return NULL;
}

void sw_cli_figure_destroy(sw_cli_figure_t *f)
{
    if (!f)
        return;
    for (size_t i = 0; f->tr && i < f->n; i++) sw_series_destroy(f->tr[i].s);
    free(f->tr);
    free(f->lat_of);
    free(f->ev);
    free(f);
}

/* ---- keeping ----------------------------------------------------------------- */

/* Outside the window of a zoom? */
static int outside(const sw_cli_figure_t *f, double t)
{
    return f->windowed && !(t >= f->w0 && t <= f->w1);
}

/* The trace of plane p of package k, or NULL. */
static trace_t *trace_of(const sw_cli_figure_t *f, size_t k, sw_plane p)
{
    if (k >= f->npkg)
        return NULL;
    if (p == SW_PLANE_LONG)
        return &f->tr[k];
    return f->lat_of[k] == NO_LAT ? NULL : &f->tr[f->lat_of[k]];
}

/* The reserve of trace T's plane, or NULL. */
static const sw_risk_pkg_t *reserve_of(const sw_cli_figure_t *f, const trace_t *T)
{
    if (!f->risk)
        return NULL;
    if (!T->lat)
        return sw_risk_pkg(f->risk, T->pkg);
    return f->st ? sw_stream_risk_plane(f->st, T->pkg, SW_PLANE_LAT) : NULL;
}

void sw_cli_figure_state(sw_cli_figure_t *f, const sw_output_t *out)
{
    trace_t *T = f ? trace_of(f, out->pkg, out->plane) : NULL;
    if (!T || outside(f, out->t))
        return;
    /* the margin as presented (alarm.h): in [-1, 1], -1 at overturn, so a
     * falling package does not read as a recovery */
    const sw_risk_pkg_t *rp = reserve_of(f, T);
    const double v[NQ] = {out->a_g, out->state.theta / T->alpha,
                          sw_margin_presented(out->margin, out->state.phase),
                          rp ? rp->reserve_g : NAN};
    for (int q = 0; q < Q_RESERVE; q++)
        if (!isfinite(v[q]))
            return; /* the engine reports none; a gap in the line if it did */
    sw_series_add(T->s, out->t, v);
}

void sw_cli_figure_risk(sw_cli_figure_t *f, const sw_risk_t *risk)
{
    if (f)
        f->risk = risk;
}

void sw_cli_figure_stream(sw_cli_figure_t *f, const sw_stream_t *st)
{
    if (f)
        f->st = st;
}

void sw_cli_figure_window(sw_cli_figure_t *f, double t0, double t1)
{
    if (!f)
        return;
    f->windowed = 1;
    f->w0 = t0;
    f->w1 = t1;
}

void sw_cli_figure_no_margin(sw_cli_figure_t *f)
{
    if (f)
        f->no_margin = 1;
}

void sw_cli_figure_gap(sw_cli_figure_t *f, double t0, double t1)
{
    if (!f || f->ngap == MAX_GAPS || !(t1 > t0) || outside(f, t0) + outside(f, t1) == 2)
        return;
    f->gap[f->ngap][0] = t0;
    f->gap[f->ngap][1] = t1;
    f->ngap++;
}

void sw_cli_figure_mark(sw_cli_figure_t *f, double t)
{
    if (f && f->nmark < MAX_MARKS && isfinite(t))
        f->mark[f->nmark++] = t;
}

void sw_cli_figure_event(sw_cli_figure_t *f, const sw_event_t *ev)
{
    if (!f || !trace_of(f, ev->pkg, ev->plane) || outside(f, ev->t))
        return;
    if (f->nev == f->cap) {
        size_t cap = f->cap ? 2 * f->cap : 256;
        if (cap > MAX_EVENTS)
            cap = MAX_EVENTS;
        sw_event_t *e = cap > f->cap ? realloc(f->ev, cap * sizeof *e) : NULL;
        if (!e) {
            f->dropped++;
            return;
        }
        f->ev = e;
        f->cap = cap;
    }
    f->ev[f->nev++] = *ev;
}

/* ---- drawing ----------------------------------------------------------------- */

static void emit_bucket(FILE *g, const sw_extreme_t *B)
{
    const int min_first = B->tmin <= B->tmax;
    const double t1 = min_first ? B->tmin : B->tmax, v1 = min_first ? B->vmin : B->vmax;
    const double t2 = min_first ? B->tmax : B->tmin, v2 = min_first ? B->vmax : B->vmin;
    if (isnan(v1)) /* the reserve before its first evaluation */
        return;
    fprintf(g, "%.9g %.9g\n", t1, v1);
    if (t2 != t1 || v2 != v1)
        fprintf(g, "%.9g %.9g\n", t2, v2);
}

/* Package k's quantity q as the datablock $s<k>_<q>. */
static void series_block(FILE *g, const trace_t *T, size_t k, int q)
{
    const size_t nb = sw_series_count(T->s);
    fprintf(g, "$s%zu_%d << EOD\n", k, q);
    for (size_t i = 0; i < nb; i++) {
        sw_extreme_t B;
        sw_series_get(T->s, i, (size_t)q, &B);
        emit_bucket(g, &B);
    }
    if (!nb)
        fputs("NaN NaN\n", g);
    fputs("EOD\n", g);
}

/* The time span and the lowest margin of every package's series. */
static int extent(const sw_cli_figure_t *f, double *t0, double *t1, double *min_margin)
{
    int any = 0;
    *t0 = INFINITY;
    *t1 = -INFINITY;
    *min_margin = INFINITY;
    for (size_t k = 0; k < f->n; k++)
        for (size_t i = 0; i < sw_series_count(f->tr[k].s); i++) {
            sw_extreme_t B;
            any = 1;
            for (int q = 0; q < Q_RESERVE; q++) {
                sw_series_get(f->tr[k].s, i, (size_t)q, &B);
                *t0 = fmin(*t0, fmin(B.tmin, B.tmax));
                *t1 = fmax(*t1, fmax(B.tmin, B.tmax));
                if (q == Q_MARGIN)
                    *min_margin = fmin(*min_margin, B.vmin);
            }
        }
    return any;
}

/* The events of package k of one kind (impacts with rests) at
 * (t, theta/alpha), as the datablock $e<k>_<kind>. */
static void event_block(FILE *g, const sw_cli_figure_t *f, size_t k, sw_event_kind kind)
{
    int n = 0;
    fprintf(g, "$e%zu_%d << EOD\n", k, (int)kind);
    for (size_t i = 0; i < f->nev; i++) {
        const sw_event_t *ev = &f->ev[i];
        const int same = ev->kind == kind || (kind == SW_EV_IMPACT && ev->kind == SW_EV_REST);
        const trace_t *T = &f->tr[k];
        const double r = ev->theta / T->alpha;
        if (ev->pkg != T->pkg || (ev->plane == SW_PLANE_LAT) != T->lat || !same ||
            !isfinite(ev->t) || !isfinite(r))
            continue;
        fprintf(g, "%.9g %.9g\n", ev->t, r);
        n++;
    }
    if (!n)
        fputs("NaN NaN\n", g);
    fputs("EOD\n", g);
}

/* Colour and style of an event kind's vertical line, or NULL: none. */
static const char *line_colour(sw_event_kind k)
{
    switch (k) {
        case SW_EV_UPLIFT: return "#2a9d8f";
        case SW_EV_TIP: return "#e9c46a";
        case SW_EV_OVERTURN: return "#d62828";
        case SW_EV_FAULT: return "#000000";
        default: return NULL;
    }
}

/* Vertical lines through every panel at the uplifts (the first ones),
 * tips, overturns and faults; solid black ones at the decisive moments;
 * the gaps shaded. */
static void event_lines(FILE *g, const sw_cli_figure_t *f)
{
    int arrows = 0, uplifts = 0;
    for (size_t i = 0; i < f->nmark; i++)
        fprintf(g,
                "set arrow %d from first %.9g, graph 0 to first %.9g, graph 1 nohead lc rgb "
                "'#000000' lw 2 back\n",
                ++arrows, f->mark[i], f->mark[i]);
    for (size_t i = 0; i < f->ngap; i++)
        fprintf(g,
                "set object %zu rect from first %.9g, graph 0 to first %.9g, graph 1 back "
                "fc rgb '#bbbbbb' fs transparent solid 0.35 noborder\n",
                i + 1, f->gap[i][0], f->gap[i][1]);
    for (size_t i = 0; i < f->nev && arrows < MAX_LINES; i++) {
        const sw_event_t *ev = &f->ev[i];
        const char *col = line_colour(ev->kind);
        if (!col || !isfinite(ev->t))
            continue;
        if (ev->kind == SW_EV_UPLIFT && uplifts++ >= MAX_UPLIFT_LINES)
            continue;
        fprintf(g,
                "set arrow %d from first %.9g, graph 0 to first %.9g, graph 1 nohead lc rgb '%s' "
                "lw 1.5 dt %d back\n",
                ++arrows, ev->t, ev->t, col, ev->plane == SW_PLANE_LAT ? 4 : 2);
    }
}

/* The tips, overturns and faults of one plane named beside their line in
 * that plane's tilt panel ("overturn across the truck, crate-A"), so that
 * a figure of two planes says which one gave out; set before the panel,
 * unset after it.  Tips and overturns of a one-plane figure are named by
 * the legend alone, as before. */
static void event_labels(FILE *g, const sw_cli_figure_t *f, int lat)
{
    int n = 0;
    for (size_t i = 0; f->nlat && i < f->nev && n < MAX_MARKS * 4; i++) {
        const sw_event_t *ev = &f->ev[i];
        const char *what = ev->kind == SW_EV_OVERTURN ? "overturn"
                           : ev->kind == SW_EV_TIP    ? "tip"
                           : ev->kind == SW_EV_FAULT  ? "model fault"
                                                      : NULL;
        if (!what || (ev->plane == SW_PLANE_LAT) != lat || !isfinite(ev->t) || ev->pkg >= f->npkg)
            continue;
        char text[160];
        snprintf(text, sizeof text, "%s %s, %s", what, lat ? "across the truck" : "along the truck",
                 f->tr[ev->pkg].name);
        fputs("set label ", g);
        sw_cli_plot_text(g, text);
        fprintf(g, " at first %.9g, graph 0.97 right rotate by 90 offset -0.6,0 font ',9' front\n",
                ev->t);
        n++;
    }
}

/* Legend entries of the kinds of events there are, drawn once in black
 * (the points carry the package's colour). */
static void event_legend(FILE *g, const sw_cli_figure_t *f)
{
    static const struct {
        sw_event_kind kind;
        const char *entry;
    } legend[] = {
        {SW_EV_UPLIFT, "NaN with points pt 9 ps 1.2 lc rgb 'black' title 'uplift'"},
        {SW_EV_TIP, "NaN with points pt 13 ps 1.2 lc rgb 'black' title 'tip (|θ| = α)'"},
        {SW_EV_OVERTURN, "NaN with points pt 7 ps 1.6 lc rgb '#d62828' title 'overturn'"},
        {SW_EV_IMPACT, "NaN with points pt 6 ps 0.5 lc rgb 'black' title 'impact / rest'"},
        {SW_EV_FAULT, "NaN with points pt 4 ps 1.2 lc rgb 'black' title 'model fault'"},
    };
    for (size_t j = 0; j < sizeof legend / sizeof legend[0]; j++)
        for (size_t i = 0; i < f->nev; i++) {
            const sw_event_kind k = f->ev[i].kind == SW_EV_REST ? SW_EV_IMPACT : f->ev[i].kind;
            if (k == legend[j].kind) {
                fprintf(g, ", %s", legend[j].entry);
                break;
            }
        }
}

/* The thresholds line(s) of the acceleration panel: one pair if every
 * package has the same g tan(alpha). */
static void threshold_plots(FILE *g, const sw_cli_figure_t *f)
{
    int same = 1;
    for (size_t k = 1; k < f->n; k++)
        same = same && fabs(f->tr[k].g_tan_alpha - f->tr[0].g_tan_alpha) <=
                           1e-9 * fabs(f->tr[0].g_tan_alpha);
    for (size_t k = 0; k < (same ? 1 : f->n); k++) {
        const trace_t *T = &f->tr[k];
        char title[160];
        snprintf(title, sizeof title, "± g tan α = %.3g m/s² (%.3g g): uplift%s%s%s",
                 T->g_tan_alpha, T->g_tan_alpha / SW_G0, same ? "" : ", ", same ? "" : T->name,
                 same || !T->lat ? "" : " (lateral)");
        fprintf(g, ", %.9g with lines lc rgb '%s' dt %d lw 1.2 title ", T->g_tan_alpha,
                same ? "#777777" : colour(T), T->lat ? 5 : 3);
        sw_cli_plot_text(g, title);
        fprintf(g, ", %.9g with lines lc rgb '%s' dt %d lw 1.2 notitle", -T->g_tan_alpha,
                same ? "#777777" : colour(T), T->lat ? 5 : 3);
    }
}

/* "<what>, <package>" as an enhanced-text title; "<what> across, <package>"
 * for a lateral plane. */
static void series_title(FILE *g, const char *what, const trace_t *T)
{
    char t[160];
    snprintf(t, sizeof t, "%s%s, %s", what, T->lat ? " across" : "", T->name);
    sw_cli_plot_text(g, t);
}

/* Panel 2: theta / alpha along the truck (lat 0) or across it (lat 1),
 * the events of that plane on it. */
static void panel_tilt(FILE *g, const sw_cli_figure_t *f, int lat)
{
    event_labels(g, f, lat);
    fprintf(g,
            "set ylabel '%s'\nplot 1 with lines lc rgb '#d62828' dt 3 "
            "title 'tipping: |θ| = α (±1)', -1 with lines lc rgb '#d62828' dt 3 notitle",
            lat       ? "tilt across the truck θ / α"
            : f->nlat ? "tilt along the truck θ / α"
                      : "tilt θ / α");
    for (size_t k = 0; k < f->n; k++) {
        if (f->tr[k].lat != lat)
            continue;
        const char *c = colour(&f->tr[k]);
        fprintf(g, ", $s%zu_%d using 1:2 with lines lc rgb '%s' lw 1.5 title ", k, Q_RATIO, c);
        series_title(g, "θ/α", &f->tr[k]);
        fprintf(g,
                ", $e%zu_%d using 1:2 with points pt 6 ps 0.5 lc rgb '%s' notitle"
                ", $e%zu_%d using 1:2 with points pt 9 ps 1.2 lc rgb '%s' notitle"
                ", $e%zu_%d using 1:2 with points pt 13 ps 1.2 lc rgb '%s' notitle"
                ", $e%zu_%d using 1:2 with points pt 7 ps 1.6 lc rgb '#d62828' notitle"
                ", $e%zu_%d using 1:2 with points pt 4 ps 1.2 lc rgb '%s' notitle",
                k, SW_EV_IMPACT, c, k, SW_EV_UPLIFT, c, k, SW_EV_TIP, c, k, SW_EV_OVERTURN, k,
                SW_EV_FAULT, c);
    }
    event_legend(g, f);
    fputc('\n', g);
    if (f->nlat)
        fputs("unset label\n", g);
}

/* Panel 3: the margin to overturn, as presented: below 0 the package is
 * past the edge, and -1 is overturned (mmin: the lowest drawn). */
static void panel_margin(FILE *g, const sw_cli_figure_t *f, double mmin)
{
    const double lo = fmax(MARGIN_FLOOR, fmin(0.0, mmin)) - 0.05;
    fprintf(g,
            "set ylabel 'margin to overturn%s'\n"
            "set yrange [%.6g:1.05]\n"
            "plot 0 with lines lc rgb '#d62828' dt 3 title 'overturns with no more input "
            "below 0'",
            mmin < 0.0 ? " (-1: overturned)" : "", lo);
    for (size_t k = 0; k < f->n; k++) {
        fprintf(g, ", $s%zu_%d using 1:2 with lines lc rgb '%s' lw 1.5%s title ", k, Q_MARGIN,
                colour(&f->tr[k]), f->tr[k].lat ? " dt 2" : "");
        series_title(g, "margin", &f->tr[k]);
    }
    fputc('\n', g);
}

/* Panel 4: the reserve, the smallest design pulse that would overturn
 * the package. */
static void panel_reserve(FILE *g, const sw_cli_figure_t *f)
{
    fputs(
        "set ylabel 'reserve (g)'\n"
        "set yrange [0:*]\nplot 0 with lines lc rgb '#d62828' dt 3 "
        "title 'no reserve: overturns with no more input'",
        g);
    for (size_t k = 0; k < f->n; k++) {
        if (!reserve_of(f, &f->tr[k]))
            continue;
        fprintf(g, ", $s%zu_%d using 1:2 with lines lc rgb '%s' lw 1.5%s title ", k, Q_RESERVE,
                colour(&f->tr[k]), f->tr[k].lat ? " dt 2" : "");
        series_title(g, "reserve", &f->tr[k]);
    }
    fputc('\n', g);
}

/* Panel 1: the bed's acceleration and the uplift thresholds; with a
 * lateral plane, the lateral acceleration too (the first lateral trace's:
 * every plane is driven by the same log). */
static void panel_accel(FILE *g, const sw_cli_figure_t *f)
{
    if (!f->nlat)
        fputs(
            "set ylabel 'bed acceleration a_g (m/s^2)'\n"
            "plot $s0_0 using 1:2 with lines lc rgb '#264653' lw 1.2 title 'bed acceleration a_g'",
            g);
    else
        fprintf(g,
                "set ylabel 'bed acceleration a_g, a_y (m/s^2)'\n"
                "plot $s0_0 using 1:2 with lines lc rgb '#264653' lw 1.2 title 'along the truck "
                "a_g (forward +)', $s%zu_0 using 1:2 with lines lc rgb '#9d4edd' lw 1.2 title "
                "'across the truck a_y (lateral)'",
                f->npkg);
    threshold_plots(g, f);
    fputc('\n', g);
}

/* The panels drawn, top to bottom, into p; how many. */
static int panel_list(const sw_cli_figure_t *f, int p[NPANELS])
{
    int n = 0;
    p[n++] = P_ACCEL;
    p[n++] = P_TILT;
    if (f->nlat)
        p[n++] = P_TILT_LAT;
    if (!f->no_margin)
        p[n++] = P_MARGIN;
    if (f->risk)
        p[n++] = P_RESERVE;
    return n;
}

/* What each panel shows, in words, for a caption. */
static const char *const panel_words[NPANELS] = {
    [P_ACCEL] =
        "the bed acceleration a_g (m/s², negative is braking) with the thresholds "
        "±g tan α at which a package standing on the bed starts to rock",
    [P_TILT] =
        "the tilt θ of each package as a fraction of its tipping angle α (at 1 its "
        "centre of mass is over the edge: past it, it falls unless the truck pushes it "
        "back), with the events marked",
    [P_TILT_LAT] =
        "the tilt across the truck of each package with a depth, its lateral plane (rocking "
        "over its depth, driven by the lateral acceleration), as a fraction of its tipping "
        "angle across, with that plane's events marked and its tips and overturns named",
    [P_MARGIN] =
        "the margin to overturn of each package (1 at rest, 0: it overturns with no "
        "more input, -1: overturned)",
    [P_RESERVE] =
        "the reserve of each package in g: the smallest design pulse, braking or "
        "speeding up, that would have overturned it from its state then (0: it "
        "overturns with no more input)",
};

size_t sw_cli_figure_caption(const sw_cli_figure_t *f, char *buf, size_t len)
{
    static const char *const places[][NPANELS] = {
        {"", "", "", "", ""},
        {"", "", "", "", ""},
        {"Top", "bottom", "", "", ""},
        {"Top", "middle", "bottom", "", ""},
        {"Top", "second", "third", "bottom", ""},
        {"Top", "second", "third", "fourth", "bottom"},
    };
    int p[NPANELS];
    const int n = panel_list(f, p);
    FILE *m = fmemopen(buf, len, "w");
    if (!m || !len)
        return 0;
    for (int i = 0; i < n; i++) {
        fprintf(m, "%s%s: %s", i ? "; " : "", places[n][i], panel_words[p[i]]);
        if (f->nlat && p[i] == P_ACCEL)
            fputs(
                ", and the acceleration across the truck a_y (left positive) with the "
                "thresholds of the lateral planes",
                m);
        if (f->nlat && p[i] == P_TILT)
            fputs(" (along the truck)", m);
        if (f->nlat && (p[i] == P_MARGIN || p[i] == P_RESERVE)) {
            int lat_drawn = p[i] == P_MARGIN;
            for (size_t k = f->npkg; k < f->n && !lat_drawn; k++)
                lat_drawn = reserve_of(f, &f->tr[k]) != NULL;
            fputs(lat_drawn ? " (dashed: across the truck)" : " (along the truck only)", m);
        }
    }
    fputs(". ", m);
    static const struct {
        sw_event_kind kind;
        const char *words;
    } lines[] = {{SW_EV_UPLIFT, "uplifts (green)"},
                 {SW_EV_TIP, "tips (yellow)"},
                 {SW_EV_OVERTURN, "overturns (red)"},
                 {SW_EV_FAULT, "model faults (black)"}};
    int said = 0;
    for (size_t j = 0; j < sizeof lines / sizeof lines[0]; j++)
        for (size_t i = 0; i < f->nev; i++)
            if (f->ev[i].kind == lines[j].kind) {
                fprintf(m, "%s%s", said++ ? ", " : "Dashed vertical lines: ", lines[j].words);
                break;
            }
    if (said)
        fputs(f->nlat ? " (dash-dot: an event of a lateral plane). " : ". ", m);
    if (f->nmark)
        fputs("The solid black line is the moment this view is centred on. ", m);
    if (f->ngap)
        fputs("Grey bands: spans the log has no samples for (gaps), bridged or restarted. ", m);
    if (f->windowed)
        fputs("Every sample of this span is drawn.", m);
    else
        fputs("Long logs are drawn from the extremes of each stretch, so no peak is lost.", m);
    const int bad = ferror(m);
    fclose(m);
    return bad ? 0 : strlen(buf);
}

int sw_cli_figure_draw(const sw_cli_figure_t *f, const char *path, const char *title)
{
    double t0, t1, mmin;
    if (!extent(f, &t0, &t1, &mmin)) {
        sw_cli_error("%s: no state to draw", path);
        return SW_EXIT_USAGE;
    }
    if (!(t1 > t0))
        t1 = t0 + 1.0;
    int list[NPANELS];
    const int panels = panel_list(f, list);
    sw_plot_t *p = sw_cli_plot_open(path, 1200, 320 * panels);
    if (!p)
        return SW_EXIT_IO;
    FILE *g = sw_cli_plot_file(p);

    /* the data, as inline datablocks */
    static const sw_event_kind kinds[] = {SW_EV_UPLIFT, SW_EV_IMPACT, SW_EV_TIP, SW_EV_OVERTURN,
                                          SW_EV_FAULT};
    for (size_t k = 0; k < f->n; k++) {
        for (int q = 0; q < (f->risk ? NQ : Q_RESERVE); q++) series_block(g, &f->tr[k], k, q);
        for (size_t j = 0; j < sizeof kinds / sizeof kinds[0]; j++) event_block(g, f, k, kinds[j]);
    }
    event_lines(g, f);

    fprintf(g, "set multiplot layout %d,1 title ", panels);
    sw_cli_plot_text(g, title);
    fprintf(g,
            " font ',13'\n"
            "set grid\nset key at screen 0.635, graph 1 left top Left reverse box opaque\n"
            "set lmargin at screen 0.08\nset rmargin at screen 0.62\n"
            "set xrange [%.9g:%.9g]\nset xlabel ''\nset format x ''\n",
            t0, t1);

    for (int i = 0; i < panels; i++) {
        if (i == panels - 1) /* the time axis under the last panel */
            fputs("set format x '%g'\nset xlabel 'time t (s)'\n", g);
        switch (list[i]) {
            case P_ACCEL: panel_accel(g, f); break;
            case P_TILT: panel_tilt(g, f, 0); break;
            case P_TILT_LAT: panel_tilt(g, f, 1); break;
            case P_MARGIN: panel_margin(g, f, mmin); break;
            case P_RESERVE: panel_reserve(g, f); break;
        }
    }
    fputs("unset multiplot\n", g);
    if (f->dropped)
        sw_cli_error("%s: %ld events beyond the %d kept are not marked", path, f->dropped,
                     MAX_EVENTS);
    return sw_cli_plot_close(p);
}
