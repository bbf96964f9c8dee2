/* SPDX-License-Identifier: GPL-3.0-or-later */
/* report_zoom.c - the report's close-ups (forensics.h): on a drive of
 * minutes the overturn is one pixel column of the full figure, so each
 * decisive moment (a package's overturn, else its smallest reserve) gets
 * a figure of its own, a few seconds either side, with every sample.
 *
 * The full figure keeps a long log as the extremes of stretches, so the
 * close-ups cannot come from it: the log as the gate handed it to the
 * engine (held in memory for the searches, sw_forensics_t) is run again
 * (sw_forensics_rerun), from its start, through a fresh engine of the
 * same scenes and options, which repeats the replay exactly (gate.h), up
 * to the end of the last window.  Each window
 * has its own reserve, evaluated at the reserve rate from the window's
 * start: only there does it cost. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "forensics.h"

/* ---- the moments ----------------------------------------------------------------------- */

static int by_time(const void *a, const void *b)
{
    const double x = ((const sw_cli_zoom_t *)a)->t, y = ((const sw_cli_zoom_t *)b)->t;
    return (x > y) - (x < y);
}

size_t sw_cli_report_moments(const sw_cli_forensics_t *F, sw_cli_zoom_t *z, size_t max)
{
    sw_cli_zoom_t *m = calloc(F->n ? F->n : 1, sizeof *m);
    if (!m)
        return 0;
    size_t nm = 0;
    for (size_t k = 0; k < F->n; k++) {
        sw_summary_t s; /* the plane that decides the verdict, named with two */
        if (!sw_cli_forensics_summary(F, k, &s))
            continue;
        int planes;
        const sw_plane plane = sw_cli_forensics_plane(F, k, &planes);
        const char *where = sw_cli_forensics_where(planes, plane);
        const sw_risk_pkg_t *rp = F->R.risk ? sw_cli_forensics_reserve(F, k, plane) : NULL;
        sw_cli_zoom_t *o = &m[nm];
        if (s.overturned && isfinite(s.overturn_time)) {
            o->t = s.overturn_time;
            snprintf(o->what, sizeof o->what, "the overturn of %s%s at %.3f s", F->scenes[k].name,
                     where, o->t);
        } else if (rp && rp->evaluations > 0 && isfinite(rp->min_reserve_time)) {
            o->t = rp->min_reserve_time;
            snprintf(o->what, sizeof o->what, "the smallest reserve of %s%s (%.3g g) at %.3f s",
                     F->scenes[k].name, where, rp->min_reserve_g, o->t);
        } else if (isfinite(s.uplift_time)) {
            o->t = s.uplift_time;
            snprintf(o->what, sizeof o->what, "the first uplift of %s%s at %.3f s",
                     F->scenes[k].name, where, o->t);
        } else {
            continue; /* it never moved: nothing to look at closer */
        }
        o->t0 = o->t - SW_CLI_ZOOM_HALF;
        o->t1 = o->t + SW_CLI_ZOOM_HALF;
        o->marks[0] = o->t;
        o->nmarks = 1;
        nm++;
    }
    qsort(m, nm, sizeof *m, by_time);
    /* moments closer than a window's half share one window */
    size_t n = 0;
    for (size_t i = 0; i < nm; i++) {
        sw_cli_zoom_t *last = n ? &z[n - 1] : NULL;
        if (last && m[i].t0 <= last->t1 && last->nmarks < SW_CLI_ZOOM_MARKS) {
            last->t1 = m[i].t1;
            last->marks[last->nmarks++] = m[i].t;
            const size_t len = strlen(last->what);
            snprintf(last->what + len, sizeof last->what - len, "; %s", m[i].what);
            continue;
        }
        if (n == max)
            break;
        z[n++] = m[i];
    }
    free(m);
    return n;
}

/* ---- the run --------------------------------------------------------------------------- */

typedef struct {
    const sw_cli_zoom_t *z;
    size_t nz;
    sw_cli_figure_t **fig;
    sw_risk_t **risk;
} zrun_t;

static int inside(const sw_cli_zoom_t *z, double t)
{
    return t >= z->t0 && t <= z->t1;
}

static void on_state(void *user, const sw_output_t *out)
{
    const zrun_t *Z = user;
    for (size_t i = 0; i < Z->nz; i++) {
        if (!inside(&Z->z[i], out->t))
            continue;
        if (Z->risk[i] && out->plane == SW_PLANE_LONG) /* the reserve is along the truck */
            sw_risk_output(Z->risk[i], out);           /* first: the figure reads it */
        sw_cli_figure_state(Z->fig[i], out);
    }
}

static void on_event(void *user, const sw_event_t *ev)
{
    const zrun_t *Z = user;
    for (size_t i = 0; i < Z->nz; i++) {
        if (!inside(&Z->z[i], ev->t))
            continue;
        sw_settle_span_t closed;
        /* the micro-impacts of settling folded as in the full figure */
        if (!Z->risk[i] || ev->plane == SW_PLANE_LAT ||
            (sw_risk_event(Z->risk[i], ev, &closed) & SW_SETTLE_REPORT))
            sw_cli_figure_event(Z->fig[i], ev);
    }
}

int sw_cli_report_zooms(const sw_cli_forensics_t *F, const sw_cli_zoom_t *z, size_t nz,
                        sw_cli_figure_t **fig, sw_risk_t **risk)
{
    int rc = SW_EXIT_IO;
    zrun_t Z = {.z = z, .nz = nz, .fig = fig, .risk = risk};
    sw_engine_t *e = NULL;
    memset(fig, 0, nz * sizeof *fig);
    memset(risk, 0, nz * sizeof *risk);
    const int reserve = F->o.reserve_rate > 0.0;
    for (size_t i = 0; i < nz; i++) {
        if (!(fig[i] = sw_cli_figure_create(F->R.e, F->scenes, F->n)))
            goto out;
        sw_cli_figure_window(fig[i], z[i].t0, z[i].t1);
        sw_cli_figure_no_margin(fig[i]);
        for (int k = 0; k < z[i].nmarks; k++) sw_cli_figure_mark(fig[i], z[i].marks[k]);
        const sw_cli_unused_t *u = &F->R.run.unused;
        for (size_t g = 0; g < u->ngap; g++)
            if (u->gap[g].kind == SW_GATE_EV_GAP)
                sw_cli_figure_gap(fig[i], u->gap[g].t_engine - u->gap[g].span, u->gap[g].t_engine);
        if (reserve) {
            const sw_risk_opts_t ro = {.reserve_rate = F->o.reserve_rate};
            int err = SW_OK;
            char msg[256] = "";
            if (!(risk[i] = sw_risk_create(F->scenes, F->n, &ro, &err, msg, sizeof msg))) {
                sw_cli_error("--report: the close-up's reserve: %s",
                             msg[0] ? msg : sw_strerror(err));
                goto out;
            }
            sw_cli_figure_risk(fig[i], risk[i]);
        }
    }
    sw_engine_opts_t eo = F->eo;
    eo.lateral = sw_forensics_log_lat(F->fx) != NULL; /* the lateral planes as replayed */
    eo.on_state = on_state;
    eo.on_event = on_event;
    eo.user = &Z;
    int err = SW_OK;
    char msg[256] = "";
    if (!(e = sw_engine_create(F->scenes, F->n, &eo, &err, msg, sizeof msg))) {
        sw_cli_error("--report: the close-ups' engine: %s", msg[0] ? msg : sw_strerror(err));
        goto out;
    }
    double end = -INFINITY;
    for (size_t i = 0; i < nz; i++) end = fmax(end, z[i].t1);
    /* the samples exactly as the replay's engine had them, then the
     * settling if a moment is in it */
    sw_forensics_rerun(F->fx, e, end, F->fo.settle);
    rc = SW_EXIT_OK;
out:
    sw_engine_destroy(e);
    if (rc != SW_EXIT_OK)
        for (size_t k = 0; k < nz; k++) {
            sw_cli_figure_destroy(fig[k]);
            sw_risk_destroy(risk[k]);
            fig[k] = NULL;
            risk[k] = NULL;
        }
    return rc;
}
