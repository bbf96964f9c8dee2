/* SPDX-License-Identifier: GPL-3.0-or-later */
/* output.c - the files the commands write: the state CSV (--out), the
 * wide state CSV (--wide) and the events CSV (--events), and the checks
 * that keep an output off an input or another output.  The summaries are
 * in summary.c.
 *
 * Everything here prints its own messages ("swaywatch: ..." on stderr) and
 * returns an exit code. */
#include "output.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

/* ---- output files ---------------------------------------------------------- */

static int is_stdout(const char *path)
{
    return path && !strcmp(path, "-");
}

/* Non-zero if path exists and is the file st describes. */
static int is_file(const char *path, const struct stat *st)
{
    struct stat ps;
    return path && !is_stdout(path) && stat(path, &ps) == 0 && ps.st_dev == st->st_dev &&
           ps.st_ino == st->st_ino;
}

int sw_cli_check_outputs(const char *out_path, const char *events_path, FILE *in, int json,
                         int quiet)
{
    struct stat st;
    /* "-" is standard output: for one of them, and only if no summary goes
     * there too. */
    if (is_stdout(out_path) && is_stdout(events_path)) {
        sw_cli_error("--out and --events cannot both be standard output");
        return SW_EXIT_USAGE;
    }
    if ((is_stdout(out_path) || is_stdout(events_path)) && (json || !quiet)) {
        sw_cli_error("--%s -: standard output carries the %s",
                     is_stdout(out_path) ? "out" : "events",
                     json ? "JSON summary (--json)" : "summary; add -q to leave it out");
        return SW_EXIT_USAGE;
    }
    /* Opening an output truncates it: it must be neither the log being
     * read nor the other output. */
    if (in && in != stdin && fstat(fileno(in), &st) == 0) {
        if (is_file(out_path, &st)) {
            sw_cli_error("--out %s: that is the log being read", out_path);
            return SW_EXIT_USAGE;
        }
        if (is_file(events_path, &st)) {
            sw_cli_error("--events %s: that is the log being read", events_path);
            return SW_EXIT_USAGE;
        }
    }
    if (out_path && events_path && !is_stdout(out_path) &&
        (!strcmp(out_path, events_path) ||
         (stat(out_path, &st) == 0 && is_file(events_path, &st)))) {
        sw_cli_error("--out and --events name the same file '%s'", out_path);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* ---- CSV writers ------------------------------------------------------------ */

/* A number field preceded by a comma; non-finite values stay empty. */
static void csv_num(FILE *f, double v, long *nonfinite)
{
    if (isfinite(v))
        fprintf(f, ",%.9g", v);
    else {
        fputc(',', f);
        (*nonfinite)++;
    }
}

/* Package pkg's latest reserve (g), an empty field when there is none yet
 * (no reserve, or not evaluated yet): not a non-finite value. */
static void csv_reserve(FILE *f, const sw_risk_t *risk, size_t pkg)
{
    const sw_risk_pkg_t *p = sw_risk_pkg(risk, pkg);
    if (p && isfinite(p->reserve_g))
        fprintf(f, ",%.9g", p->reserve_g);
    else
        fputc(',', f);
}

/* Package pkg's lateral plane's latest reserve, as csv_reserve. */
static void csv_reserve_lat(FILE *f, const sw_stream_t *st, size_t pkg)
{
    const sw_risk_pkg_t *p = sw_stream_risk_plane(st, pkg, SW_PLANE_LAT);
    if (p && isfinite(p->reserve_g))
        fprintf(f, ",%.9g", p->reserve_g);
    else
        fputc(',', f);
}

/* Some package of e rocks in a lateral plane too. */
static int any_lateral(const sw_engine_t *e, size_t n)
{
    for (size_t i = 0; e && i < n; i++)
        if (sw_engine_planes(e, i) == 2)
            return 1;
    return 0;
}

static const char *pkg_name(const sw_scene_t *scenes, size_t n, size_t pkg)
{
    return pkg < n ? scenes[pkg].name : "?";
}

const char *sw_cli_out_name(const char *path)
{
    return is_stdout(path) ? "standard output" : path;
}

FILE *sw_cli_out_open(const char *path)
{
    if (is_stdout(path))
        return stdout;
    FILE *f = fopen(path, "w");
    if (!f)
        sw_cli_error("%s: cannot create: %s", path, strerror(errno));
    return f;
}

int sw_cli_out_close(FILE *f, const char *path)
{
    if (!f)
        return SW_EXIT_OK;
    int bad = ferror(f);
    int saved = errno;
    /* Standard output stays open: main() checks it once more at the end. */
    if (f == stdout ? fflush(f) != 0 : fclose(f) != 0) {
        bad = 1;
        saved = errno;
    }
    if (bad) {
        sw_cli_error("%s: write failed: %s", sw_cli_out_name(path), strerror(saved));
        return SW_EXIT_IO;
    }
    return SW_EXIT_OK;
}

int sw_cli_states_open(sw_cli_states_t *w, const char *path, long every, const sw_engine_t *e,
                       const sw_scene_t *scenes, size_t n)
{
    memset(w, 0, sizeof *w);
    w->path = path;
    w->scenes = scenes;
    w->n = n;
    w->every = every > 0 ? every : 1;
    if (!path)
        return SW_EXIT_OK;
    w->seen = calloc(n ? n : 1, sizeof *w->seen);
    w->lat = any_lateral(e, n);
    if (w->lat) {
        w->lat_out = calloc(n, sizeof *w->lat_out);
        w->lat_have = calloc(n, 1);
    }
    if (!w->seen || (w->lat && (!w->lat_out || !w->lat_have))) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    w->f = sw_cli_out_open(path);
    if (!w->f) {
        free(w->seen);
        w->seen = NULL;
        return SW_EXIT_IO;
    }
    fputs(
        "t,package,phase,theta,theta_dot,u,u_dot,z,z_dot,margin,margin_bound,uplift_ratio,a_g,"
        "reserve_g",
        w->f);
    fputs(w->lat ? ",theta_lat,margin_lat,reserve_g_lat\n" : "\n", w->f);
    return SW_EXIT_OK;
}

void sw_cli_states_write(sw_cli_states_t *w, const sw_output_t *o)
{
    if (!w->f)
        return;
    if (o->plane == SW_PLANE_LAT) { /* written with the longitudinal one, which follows */
        if (w->lat && o->pkg < w->n) {
            w->lat_out[o->pkg] = *o;
            w->lat_have[o->pkg] = 1;
        }
        return;
    }
    if (o->pkg < w->n && w->seen[o->pkg]++ % w->every != 0)
        return;
    const sw_state_t *s = &o->state;
    long *nf = &w->nonfinite;
    if (isfinite(o->t))
        fprintf(w->f, "%.9g,", o->t);
    else {
        fputc(',', w->f);
        (*nf)++;
    }
    sw_cli_csv_text(w->f, pkg_name(w->scenes, w->n, o->pkg));
    fprintf(w->f, ",%s", sw_phase_name(s->phase));
    csv_num(w->f, s->theta, nf);
    csv_num(w->f, s->theta_dot, nf);
    csv_num(w->f, s->u, nf);
    csv_num(w->f, s->u_dot, nf);
    csv_num(w->f, s->z, nf);
    csv_num(w->f, s->z_dot, nf);
    csv_num(w->f, o->margin, nf);
    csv_num(w->f, o->margin_bound, nf);
    csv_num(w->f, o->uplift_ratio, nf);
    csv_num(w->f, o->a_g, nf);
    csv_reserve(w->f, w->risk, o->pkg);
    if (w->lat) {
        const sw_output_t *l = o->pkg < w->n ? &w->lat_out[o->pkg] : NULL;
        if (l && w->lat_have[o->pkg] && l->t == o->t) {
            csv_num(w->f, l->state.theta, nf);
            csv_num(w->f, l->margin, nf);
            csv_reserve_lat(w->f, w->stream, o->pkg);
        } else {
            fputs(",,,", w->f);
        }
    }
    fputc('\n', w->f);
    w->rows++;
}

int sw_cli_states_close(sw_cli_states_t *w)
{
    int rc = sw_cli_out_close(w->f, w->path);
    if (w->f && w->nonfinite)
        sw_cli_error("%s: %ld non-finite values written as empty fields", sw_cli_out_name(w->path),
                     w->nonfinite);
    free(w->seen);
    free(w->lat_out);
    free(w->lat_have);
    w->seen = NULL;
    w->lat_out = NULL;
    w->lat_have = NULL;
    w->f = NULL;
    return rc;
}

int sw_cli_wide_open(sw_cli_wide_t *w, const char *path, long every, const sw_engine_t *e,
                     const sw_scene_t *scenes, size_t n)
{
    memset(w, 0, sizeof *w);
    w->path = path;
    w->n = n;
    w->every = every > 0 ? every : 1;
    if (!path)
        return SW_EXIT_OK;
    w->alpha = calloc(n ? n : 1, sizeof *w->alpha);
    w->row = calloc(n ? n : 1, sizeof *w->row);
    w->have = calloc(n ? n : 1, 1);
    w->planes = calloc(n ? n : 1, 1);
    w->lat_row = calloc(n ? n : 1, sizeof *w->lat_row);
    if (!w->alpha || !w->row || !w->have || !w->planes || !w->lat_row) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    for (size_t i = 0; i < n; i++) {
        const sw_derived_t *d = sw_engine_derived(e, i);
        w->alpha[i] = d ? d->alpha : NAN;
        w->planes[i] = (unsigned char)(sw_engine_planes(e, i) == 2 ? 2 : 1);
    }
    if (!(w->f = sw_cli_out_open(path)))
        return SW_EXIT_IO;
    static const char *const cols[] = {"phase",     "theta",        "theta_dot",    "ratio",
                                       "margin",    "margin_bound", "uplift_ratio", "reserve_g",
                                       "theta_lat", "margin_lat",   "reserve_g_lat"};
    fputs("t,a_g", w->f);
    for (size_t i = 0; i < n; i++) {
        long same = 0; /* earlier packages of the same name */
        for (size_t j = 0; j < i; j++) same += !strcmp(scenes[j].name, scenes[i].name);
        char name[96];
        if (same)
            snprintf(name, sizeof name, "%s#%ld", scenes[i].name, same + 1);
        else
            snprintf(name, sizeof name, "%s", scenes[i].name);
        const size_t ncols = w->planes[i] == 2 ? 11 : 8; /* the _lat ones with a lateral plane */
        for (size_t c = 0; c < ncols; c++) {
            char col[128];
            snprintf(col, sizeof col, "%s.%s", name, cols[c]);
            fputc(',', w->f);
            sw_cli_csv_text(w->f, col);
        }
    }
    fputc('\n', w->f);
    return SW_EXIT_OK;
}

/* Write the gathered row (unless --every skips it) and start afresh. */
static void wide_flush(sw_cli_wide_t *w)
{
    if (!w->open)
        return;
    w->open = 0;
    int first = -1, missing = 0;
    for (size_t i = 0; i < w->n; i++) {
        if (w->have[i] && first < 0)
            first = (int)i;
        missing += !w->have[i];
    }
    if (w->seen++ % w->every == 0 && first >= 0) {
        long *nf = &w->nonfinite;
        const sw_output_t *o0 = &w->row[first];
        if (isfinite(o0->t))
            fprintf(w->f, "%.9g", o0->t);
        else
            (*nf)++;
        csv_num(w->f, o0->a_g, nf);
        for (size_t i = 0; i < w->n; i++) {
            const sw_output_t *o = &w->row[i];
            if (!w->have[i]) {
                fputs(w->planes[i] == 2 ? ",,,,,,,,,,," : ",,,,,,,,", w->f);
                continue;
            }
            fprintf(w->f, ",%s", sw_phase_name(o->state.phase));
            csv_num(w->f, o->state.theta, nf);
            csv_num(w->f, o->state.theta_dot, nf);
            csv_num(w->f, o->state.theta / w->alpha[i], nf);
            csv_num(w->f, o->margin, nf);
            csv_num(w->f, o->margin_bound, nf);
            csv_num(w->f, o->uplift_ratio, nf);
            csv_reserve(w->f, w->risk, i);
            if (w->planes[i] != 2)
                continue;
            const sw_output_t *l = &w->lat_row[i];
            if (l->t == o->t && l->plane == SW_PLANE_LAT) {
                csv_num(w->f, l->state.theta, nf);
                csv_num(w->f, l->margin, nf);
                csv_reserve_lat(w->f, w->stream, i);
            } else {
                fputs(",,,", w->f);
            }
        }
        fputc('\n', w->f);
        w->rows++;
        w->incomplete += missing > 0;
    }
    memset(w->have, 0, w->n);
}

void sw_cli_wide_write(sw_cli_wide_t *w, const sw_output_t *o)
{
    if (!w->f || o->pkg >= w->n)
        return;
    if (o->plane == SW_PLANE_LAT) { /* written with the longitudinal one, which follows */
        w->lat_row[o->pkg] = *o;
        return;
    }
    /* a new instant, or this package again: the row so far is complete */
    if (w->open) {
        size_t k = 0;
        while (k < w->n && !w->have[k]) k++;
        if (w->have[o->pkg] || (k < w->n && w->row[k].t != o->t))
            wide_flush(w);
    }
    w->row[o->pkg] = *o;
    w->have[o->pkg] = 1;
    w->open = 1;
    if (o->pkg == w->n - 1)
        wide_flush(w);
}

int sw_cli_wide_close(sw_cli_wide_t *w)
{
    if (w->f)
        wide_flush(w);
    int rc = sw_cli_out_close(w->f, w->path);
    if (w->f && w->nonfinite)
        sw_cli_error("%s: %ld non-finite values written as empty fields", sw_cli_out_name(w->path),
                     w->nonfinite);
    if (w->f && w->incomplete)
        sw_cli_error("%s: %ld rows lack a package's state (empty fields)", sw_cli_out_name(w->path),
                     w->incomplete);
    free(w->alpha);
    free(w->row);
    free(w->have);
    free(w->planes);
    free(w->lat_row);
    w->planes = NULL;
    w->lat_row = NULL;
    w->alpha = NULL;
    w->row = NULL;
    w->have = NULL;
    w->f = NULL;
    return rc;
}

int sw_cli_check_stdout(const char *const names[], const char *const paths[], size_t n, int json,
                        int quiet)
{
    const char *on_stdout = NULL;
    for (size_t i = 0; i < n; i++) {
        if (!is_stdout(paths[i]))
            continue;
        if (on_stdout) {
            sw_cli_error("%s and %s cannot both be standard output", on_stdout, names[i]);
            return SW_EXIT_USAGE;
        }
        if (json || !quiet) {
            sw_cli_error("%s -: standard output carries the %s", names[i],
                         json ? "JSON summary (--json)" : "summary; add -q to leave it out");
            return SW_EXIT_USAGE;
        }
        on_stdout = names[i];
    }
    return SW_EXIT_OK;
}

int sw_cli_events_open(sw_cli_events_t *w, const char *path, const sw_engine_t *e,
                       const sw_scene_t *scenes, size_t n)
{
    memset(w, 0, sizeof *w);
    w->path = path;
    w->scenes = scenes;
    w->n = n;
    if (!path)
        return SW_EXIT_OK;
    w->f = sw_cli_out_open(path);
    if (!w->f)
        return SW_EXIT_IO;
    w->lat = any_lateral(e, n);
    fputs(w->lat ? "t,package,event,theta,theta_dot,margin,info,plane\n"
                 : "t,package,event,theta,theta_dot,margin,info\n",
          w->f);
    return SW_EXIT_OK;
}

void sw_cli_events_span(sw_cli_events_t *w, size_t pkg, const sw_settle_span_t *span)
{
    if (!w->f || w->all_impacts)
        return; /* its impacts are rows of their own */
    fprintf(w->f, "%.9g,", span->t_start);
    sw_cli_csv_text(w->f, pkg_name(w->scenes, w->n, pkg));
    fprintf(w->f, ",settling,,%.9g,,%ld%s\n", span->max_speed, span->impacts,
            w->lat ? ",longitudinal" : "");
    w->rows++;
}

int sw_cli_events_feed(sw_cli_events_t *w, sw_risk_t *risk, const sw_event_t *ev)
{
    sw_settle_span_t span;
    if (ev->plane == SW_PLANE_LAT) { /* the settling spans are the longitudinal plane's */
        sw_cli_events_write(w, ev);
        return SW_SETTLE_REPORT;
    }
    const int f = risk ? sw_risk_event(risk, ev, &span) : SW_SETTLE_REPORT;
    if (f < 0)
        return SW_SETTLE_REPORT; /* a package risk does not know: as it is */
    if (f & SW_SETTLE_CLOSED)
        sw_cli_events_span(w, ev->pkg, &span);
    if ((f & SW_SETTLE_REPORT) || w->all_impacts)
        sw_cli_events_write(w, ev);
    return w->all_impacts ? f | SW_SETTLE_REPORT : f;
}

void sw_cli_events_finish(sw_cli_events_t *w, sw_risk_t *risk, size_t n)
{
    sw_settle_span_t span;
    for (size_t k = 0; risk && k < n; k++)
        if (sw_risk_finish(risk, k, &span))
            sw_cli_events_span(w, k, &span);
}

void sw_cli_events_write(sw_cli_events_t *w, const sw_event_t *ev)
{
    if (!w->f)
        return;
    long *nf = &w->nonfinite;
    if (isfinite(ev->t))
        fprintf(w->f, "%.9g,", ev->t);
    else {
        fputc(',', w->f);
        (*nf)++;
    }
    sw_cli_csv_text(w->f, pkg_name(w->scenes, w->n, ev->pkg));
    fprintf(w->f, ",%s", sw_event_name(ev->kind));
    csv_num(w->f, ev->theta, nf);
    csv_num(w->f, ev->theta_dot, nf);
    csv_num(w->f, ev->margin, nf);
    csv_num(w->f, ev->info, nf);
    if (w->lat)
        fprintf(w->f, ",%s", sw_plane_name(ev->plane));
    fputc('\n', w->f);
    w->rows++;
}

int sw_cli_events_close(sw_cli_events_t *w)
{
    int rc = sw_cli_out_close(w->f, w->path);
    if (w->f && w->nonfinite)
        sw_cli_error("%s: %ld non-finite values written as empty fields", sw_cli_out_name(w->path),
                     w->nonfinite);
    w->f = NULL;
    return rc;
}
