/* SPDX-License-Identifier: GPL-3.0-or-later */
/* report.c - "swaywatch forensics --report FILE.html": the incident report
 * as one self-contained HTML page an investigator can attach to a claim.
 * It needs no network and no script to be read: the style is inline, the
 * figures are the one replay draws (figure.c) and a close-up of each
 * decisive moment (report_zoom.c), drawn by gnuplot as SVG and written
 * into the page, each with the caption its panels give.  It says what
 * --json says (forensics_out.c), in the same order: the answer first (and
 * above it, in words, why a verdict is incomplete), the recording with its
 * times in UTC and what of it was not used, the method and the model's
 * limits, and last the fingerprint that ties the page to the log, the
 * scenes and the program. */
#define _DEFAULT_SOURCE /* mkstemps */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "forensics.h"

/* s with the characters HTML gives a meaning escaped. */
static void html(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
            case '<': fputs("&lt;", f); break;
            case '>': fputs("&gt;", f); break;
            case '&': fputs("&amp;", f); break;
            case '"': fputs("&quot;", f); break;
            default: fputc(*s, f);
        }
    }
}

/* A number, or a dash where there is none. */
static void num(FILE *f, const char *fmt, double v)
{
    if (isfinite(v))
        fprintf(f, fmt, v);
    else
        fputs("&ndash;", f);
}

static const char style[] =
    "body{font-family:sans-serif;max-width:62em;margin:1.5em auto;padding:0 1em;color:#1d1d1d;"
    "line-height:1.4}\n"
    "h1{font-size:1.5em;margin-bottom:0.2em}h2{font-size:1.2em;margin-top:1.6em;"
    "border-bottom:1px solid #ccc}\n"
    "table{border-collapse:collapse;margin:0.5em 0;font-size:0.92em}"
    "td,th{border:1px solid #ccc;padding:0.2em 0.5em;text-align:left;vertical-align:top}"
    "th{background:#f0f0f0}td.n{text-align:right;font-variant-numeric:tabular-nums}\n"
    ".over{color:#b00020;font-weight:bold}.up{color:#1b6e20;font-weight:bold}\n"
    ".answer{border:2px solid #444;padding:0.5em 1em;margin:0.8em 0;background:#fafafa}\n"
    ".fig svg{width:100%;height:auto}code{background:#f3f3f3;padding:0 0.2em;"
    "word-break:break-all}\n"
    ".note{color:#555;font-size:0.9em}\n"
    ".alert{border:2px solid #b00020;background:#fff3f3;padding:0.5em 1em;margin:0.8em 0}\n"
    "figure{margin:1em 0}figcaption{color:#333;font-size:0.9em}\n";

/* The smallest reserve of a package, in words. */
static void reserve(FILE *f, const sw_risk_pkg_t *p)
{
    if (!p || !p->evaluations || !isfinite(p->min_reserve_g))
        return;
    fprintf(f, "<p><b>Smallest reserve %.3g g</b> at %.3f s (standing at rest: %.3g g): ",
            p->min_reserve_g, p->min_reserve_time, p->rest_reserve_g);
    if (p->min_reserve_g > 0.0)
        fprintf(f,
                "from its state then, a %s half-sine pulse of %.3g s and %.3g g would have "
                "overturned it.</p>",
                p->min_direction == SW_RESERVE_ACCELERATING ? "speeding-up" : "braking",
                p->min_pulse, p->min_reserve_g);
    else
        fprintf(f, "from then on it overturns with no further input.</p>");
}

/* ---- the answer -------------------------------------------------------------------- */

/* Above the answers, in words: a verdict the log may not support. */
static void banner(FILE *f, const sw_cli_forensics_t *F)
{
    const sw_cli_run_t *run = &F->R.run;
    if (sw_cli_run_incomplete(run) > 0) {
        char why[256];
        sw_cli_incomplete_why(run, why, sizeof why);
        fprintf(f,
                "<div class=\"alert\" id=\"incomplete\"><p><b>The verdict is INCOMPLETE.</b> "
                "The recording has a hole where it matters: ");
        html(f, why);
        fprintf(f,
                ". What the samples do not show may have overturned a package, so no package "
                "that stayed upright in the samples can be said to have stayed upright. The "
                "gaps are listed under <a href=\"#unused\">What was not used</a>.</p></div>\n");
    }
    if (run->forced) {
        fprintf(f,
                "<div class=\"alert\" id=\"forced\"><p><b>The verdict was forced</b> "
                "(<code>--force</code>) although the recording fails the plausibility check: ");
        html(f, run->check);
        fprintf(f, ".</p></div>\n");
    }
}

static void answers(FILE *f, const sw_cli_forensics_t *F)
{
    for (size_t k = 0; k < F->n; k++) {
        sw_summary_t s;
        const sw_whatif_case_t *C = sw_cli_forensics_scene_case(F, k);
        if (!C || !sw_cli_forensics_summary(F, k, &s))
            continue;
        fprintf(f, "<div class=\"answer\" id=\"answer-%zu\"><p><b>", k);
        html(f, F->scenes[k].name);
        fprintf(f, "</b> (");
        char desc[224];
        html(f, sw_cli_whatif_desc(desc, sizeof desc, C));
        fprintf(f, "): ");
        const char *verdict = sw_cli_verdict(&s, &F->R.run);
        int planes;
        const sw_plane plane = sw_cli_forensics_plane(F, k, &planes);
        const char *where = sw_cli_forensics_where(planes, plane);
        char utc[64];
        if (s.overturned) {
            fprintf(f, "<span class=\"over\">OVERTURNED%s</span> at %.3f s", where,
                    s.overturn_time);
            if (sw_cli_forensics_utc(F, s.overturn_time, utc, sizeof utc))
                fprintf(f, " (%s)", utc);
            fputc('.', f);
        } else if (!strcmp(verdict, "incomplete")) {
            char why[256];
            sw_cli_incomplete_why(&F->R.run, why, sizeof why);
            fprintf(f,
                    "<span class=\"over\">INCOMPLETE</span>: %s as far as the samples go "
                    "(its tilt reached %.3f of the tipping angle), but ",
                    s.faults ? "no verdict (the model faulted)" : "upright", s.max_theta_ratio);
            html(f, why);
            fprintf(f,
                    ": an overturn may be hidden there. (The reserve and the safety factor "
                    "below are those of the samples, across the gap as the replay handled "
                    "it.)");
        } else if (!strcmp(verdict, "upright")) {
            fprintf(f,
                    "<span class=\"up\">stayed upright</span>; its tilt%s reached %.3f of the "
                    "tipping angle, its smallest margin to overturn was %.3f.",
                    where, s.max_theta_ratio, s.min_margin);
        } else {
            fprintf(f, "<span class=\"over\">no verdict</span>: the model faulted.");
        }
        fprintf(f, "</p>");
        if (planes == 2)
            fprintf(f, "<p class=\"plane\">The verdict is the %s plane's: it gave out%s.</p>",
                    sw_plane_name(plane), where);
        reserve(f, F->R.risk ? sw_cli_forensics_reserve(F, k, plane) : NULL);
        char b[64], sentence[640];
        sw_forensics_factor_t fx;
        const sw_safety_t *sf = sw_cli_forensics_factor(F, k, &fx) ? &fx.sf : &C->sf;
        sw_cli_safety_bracket(b, sizeof b, sf);
        sw_cli_safety_sentence(sentence, sizeof sentence, sf);
        fprintf(f, "<p><b>Safety factor %s.</b> ", b);
        html(f, sentence);
        if (fx.planes == 2) {
            char both[256];
            sw_cli_forensics_planes(both, sizeof both, &fx, &C->sf);
            fprintf(f, " Both horizontal axes scaled together: it ");
            html(f, both);
            fprintf(f, ".");
        }
        fprintf(f, "</p>");
        if (s.overturned && !F->fo.w.no_what_if) {
            char save[512];
            sw_cli_forensics_savers(F, k, save, sizeof save);
            fprintf(f, "<p><b>Would have stayed upright:</b> ");
            html(f, save[0] ? save : "none of the supports and sizes tried (see below)");
            fprintf(f, ".</p>");
        }
        fprintf(f, "</div>\n");
    }
}

/* ---- the log ----------------------------------------------------------------------- */

static void row_text(FILE *f, const char *k, const char *v)
{
    fprintf(f, "<tr><th>%s</th><td>", k);
    html(f, v);
    fprintf(f, "</td></tr>\n");
}

static void log_facts(FILE *f, const sw_cli_forensics_t *F)
{
    const sw_cli_run_t *run = &F->R.run;
    const sw_gate_facts_t *x = &run->facts;
    fprintf(f, "<h2>The recording</h2>\n<table id=\"log\">\n");
    row_text(f, "log", strcmp(F->log, "-") ? F->log : "(standard input)");
    row_text(f, "kind", F->R.src ? F->R.src->name : "");
    if (run->absolute) {
        char iso[64];
        sw_cli_iso_seconds(iso, sizeof iso, run->abs_start);
        row_text(f, "starts at (UTC)", iso);
        sw_cli_iso_seconds(iso, sizeof iso, run->abs_end);
        row_text(f, "ends at (UTC)", iso);
        row_text(f, "dates from", run->abs_from);
    } else {
        row_text(f, "dates", "none: the log's times count from an unknown start");
    }
    fprintf(f, "<tr><th>duration</th><td>");
    num(f, "%.3f s", run->have_facts ? x->duration : NAN);
    fprintf(f, "</td></tr>\n<tr><th>sample rate</th><td>");
    num(f, "%.6g Hz", run->have_facts ? x->rate : NAN);
    fprintf(f, "</td></tr>\n<tr><th>samples</th><td>%ld read, %zu used, %ld rejected</td></tr>\n",
            run->samples_read, sw_forensics_log(F->fx)->n, run->samples_rejected);
    fprintf(f, "<tr><th>peak |bed acceleration|</th><td>");
    num(f, "%.3f m/s&sup2;", run->have_facts ? x->peak_a : NAN);
    num(f, " (%.3f g)", run->have_facts ? x->peak_a / SW_G0 : NAN);
    fprintf(f, "</td></tr>\n<tr><th>gaps</th><td>%ld", run->have_facts ? x->gaps : 0L);
    if (run->have_facts && x->gaps > 0)
        fprintf(f, " (%.3f s in all, the longest %.3f s)", x->gap_total, x->gap_max);
    fprintf(f, "; %ld restarts, %ld clock steps", run->have_facts ? x->restarts : 0L,
            run->have_facts ? x->clock_steps : 0L);
    if (run->have_facts && x->incomplete > 0)
        fprintf(f, "; <b>%ld of them leave%s the verdict incomplete</b>", x->incomplete,
                x->incomplete == 1 ? "s" : "");
    fprintf(f, "</td></tr>\n");
    if (run->check[0])
        row_text(f, run->forced ? "verdict forced although" : "warning", run->check);
    fprintf(f,
            "</table>\n<p class=\"note\">Times are seconds from the first sample%s. What of "
            "the recording was not used is listed <a href=\"#unused\">below</a>.</p>\n",
            run->absolute ? "; beside them, where the log has dates, the time in UTC" : "");
}

/* A time in seconds and, where the log has dates, in UTC: two cells. */
static void time_cells(FILE *f, const sw_cli_forensics_t *F, double t)
{
    char utc[64];
    fprintf(f, "<td class=\"n\">");
    num(f, "%.4f", t);
    fprintf(f, "</td>");
    if (F->R.run.absolute) {
        fprintf(f, "<td>");
        if (sw_cli_forensics_utc(F, t, utc, sizeof utc))
            fputs(utc, f);
        else
            fputs(isfinite(t) ? "unknown (after a clock step or restart)" : "&ndash;", f);
        fprintf(f, "</td>");
    }
}

/* The decisive moments of each package, in seconds and in UTC. */
static void moments(FILE *f, const sw_cli_forensics_t *F)
{
    const int utc = F->R.run.absolute;
    fprintf(f,
            "<h2>When</h2>\n<table id=\"times\"><tr><th>package</th><th>moment</th>"
            "<th>t (s)</th>%s</tr>\n",
            utc ? "<th>UTC</th>" : "");
    for (size_t k = 0; k < F->n; k++)
        for (int p = 0; p < 2; p++) { /* each plane's moments, named by plane with two */
            sw_summary_t s;
            int planes;
            sw_cli_forensics_plane(F, k, &planes);
            if (p >= planes || !F->R.e ||
                sw_engine_summary_plane(F->R.e, k, (sw_plane)p, &s) != SW_OK)
                continue;
            const char *where = sw_cli_forensics_where(planes, (sw_plane)p);
            const sw_risk_pkg_t *rp =
                F->R.risk ? sw_cli_forensics_reserve(F, k, (sw_plane)p) : NULL;
            const struct {
                const char *what;
                double t;
            } when[] = {
                {"first uplift", s.uplift_time},
                {"tipped (|θ| = α)", s.tip_time},
                {"overturned", s.overturn_time},
                {"smallest reserve", rp && rp->evaluations > 0 ? rp->min_reserve_time : NAN},
            };
            for (size_t i = 0; i < sizeof when / sizeof when[0]; i++) {
                if (!isfinite(when[i].t))
                    continue;
                fprintf(f, "<tr><td>");
                html(f, F->scenes[k].name);
                fprintf(f, "</td><td>%s%s</td>", when[i].what, where);
                time_cells(f, F, when[i].t);
                fprintf(f, "</tr>\n");
            }
        }
    fprintf(f, "</table>\n");
    if (!utc)
        fprintf(f,
                "<p class=\"note\">The log has no dates (its times count from an unknown "
                "start), so no time of day can be given.</p>\n");
}

/* What of the recording the replay did not use: refusals by reason, gaps. */
static void unused(FILE *f, const sw_cli_forensics_t *F)
{
    const sw_cli_run_t *run = &F->R.run;
    const sw_cli_unused_t *u = &run->unused;
    const double t0 = run->have_facts ? run->facts.t_origin : 0.0;
    fprintf(f, "<h2 id=\"unused\">What was not used</h2>\n");
    if (u->rejected == 0) {
        fprintf(f, "<p>No sample was refused: %ld read, all used.</p>\n", run->samples_read);
    } else {
        fprintf(f,
                "<p>%ld of %ld %s refused, by reason (the first %s of each):</p>\n"
                "<table id=\"rejected\"><tr><th>reason</th><th>count</th>%s</tr>\n",
                u->rejected, run->samples_read, u->places ? "rows were" : "samples were",
                u->places ? "lines" : "count",
                u->places ? "<th>first lines</th><th>the first "
                            "one</th>"
                          : "");
        for (size_t i = 0; i < u->nreason; i++) {
            const sw_cli_unused_reason_t *r = &u->reason[i];
            fprintf(f, "<tr><td>");
            html(f, r->reason);
            fprintf(f, "</td><td class=\"n\">%ld</td>", r->count);
            if (u->places) {
                fprintf(f, "<td>");
                for (int k = 0; k < r->nwhere; k++) fprintf(f, "%s%ld", k ? ", " : "", r->where[k]);
                if (r->count > r->nwhere)
                    fprintf(f, ", &hellip;");
                fprintf(f, "</td><td><code>");
                html(f, r->first);
                fprintf(f, "</code></td>");
            }
            fprintf(f, "</tr>\n");
        }
        if (u->other)
            fprintf(f, "<tr><td>other reasons</td><td class=\"n\">%ld</td></tr>\n", u->other);
        fprintf(f, "</table>\n");
    }
    const long events =
        u->listed ? u->events : run->facts.gaps + run->facts.restarts + run->facts.clock_steps;
    if (events == 0) {
        fprintf(f, "<p>No gap, restart or clock step: the samples cover the recording.</p>\n");
        return;
    }
    if (!u->listed) { /* an lcm-logger file: the monitor core counts them */
        fprintf(f,
                "<p>%ld gaps (%.3f s in all, the longest %.3f s), %ld restarts and %ld clock "
                "steps; the monitor core that reads lcm-logger files counts them without "
                "listing them (its SENSOR_GAP alarms name each one).</p>\n",
                run->facts.gaps, run->facts.gap_total, run->facts.gap_max, run->facts.restarts,
                run->facts.clock_steps);
        return;
    }
    fprintf(f,
            "<p>%ld span%s without samples or with a clock that stepped%s:</p>\n"
            "<table id=\"gaps\"><tr><th>what</th><th>from (s)</th>%s<th>for (s)</th>"
            "<th>line after</th><th>handled</th><th>verdict</th></tr>\n",
            u->events, u->events == 1 ? "" : "s",
            u->events > (long)u->ngap ? " (the first are listed)" : "",
            run->absolute ? "<th>from (UTC)</th>" : "");
    for (size_t i = 0; i < u->ngap; i++) {
        const sw_cli_unused_gap_t *g = &u->gap[i];
        fprintf(f, "<tr><td>%s</td>", sw_gate_event_name(g->kind));
        const double at = g->t - t0;
        fprintf(f, "<td class=\"n\">%.4f</td>", at);
        if (run->absolute) {
            char utc[64];
            sw_cli_iso_seconds(utc, sizeof utc, g->t + run->abs_base);
            fprintf(f, "<td>%s</td>", utc);
        }
        fprintf(f, "<td class=\"n\">%.4g</td><td class=\"n\">%ld</td><td>%s</td><td>%s</td></tr>\n",
                fabs(g->span), g->where,
                g->restarted ? "the packages restarted from rest"
                : g->bridged ? "bridged by a straight line"
                             : "re-timed",
                g->incomplete ? "<span class=\"over\">left incomplete: it overlapped motion</span>"
                              : "not affected");
    }
    fprintf(f, "</table>\n");
}

/* ---- the figure -------------------------------------------------------------------- */

/* fig drawn by gnuplot into a temporary SVG file, copied in from its
 * <svg> element on, in a <figure> with the caption its panels give.  0,
 * or -1 (a note is written instead). */
static int embed(FILE *f, const sw_cli_figure_t *fig, const char *title, const char *id,
                 const char *before)
{
    const char *dir = getenv("TMPDIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/swaywatch-report-XXXXXX.svg", dir && *dir ? dir : "/tmp");
    int fd = mkstemps(path, 4);
    int ok = 0;
    if (fd >= 0) {
        close(fd);
        if (fig && sw_cli_figure_draw(fig, path, title) == SW_EXIT_OK) {
            FILE *in = fopen(path, "r");
            if (in) {
                int started = 0;
                fprintf(f, "<figure class=\"fig\" id=\"%s\">\n", id);
                char line[8192];
                while (fgets(line, sizeof line, in)) { /* the prolog up to <svg dropped */
                    if (!started) {
                        char *s = strstr(line, "<svg");
                        if (!s)
                            continue;
                        started = 1;
                        fputs(s, f);
                        continue;
                    }
                    fputs(line, f); /* a line longer than the buffer comes in pieces */
                }
                ok = started && !ferror(in);
                fclose(in);
                char caption[2048];
                fprintf(f, "<figcaption>");
                html(f, before);
                if (sw_cli_figure_caption(fig, caption, sizeof caption))
                    html(f, caption);
                fprintf(f, "</figcaption></figure>\n");
            }
        }
        unlink(path);
    }
    if (!ok) {
        sw_cli_error(
            "--report: a figure could not be drawn (gnuplot is needed); the report "
            "says so in its place");
        fprintf(f,
                "<p class=\"over\">The figure could not be drawn: gnuplot was not found or "
                "failed.</p>\n");
        return -1;
    }
    return 0;
}

/* The whole recording, then a close-up of each decisive moment. */
static int figures(FILE *f, const sw_cli_forensics_t *F)
{
    fprintf(f, "<h2>What the packages went through</h2>\n");
    const char *name = strcmp(F->log, "-") ? F->log : "(standard input)";
    int rc = embed(f, F->fig, name, "figure", "The whole recording. ");
    sw_cli_zoom_t z[SW_CLI_ZOOMS];
    const size_t nz = sw_cli_report_moments(F, z, SW_CLI_ZOOMS);
    if (nz == 0)
        return rc;
    sw_cli_figure_t *fig[SW_CLI_ZOOMS];
    sw_risk_t *risk[SW_CLI_ZOOMS];
    fprintf(f,
            "<h2>The moments that mattered</h2>\n<p>Each package's decisive moment (its "
            "overturn, else its smallest reserve), %.0f s either side, with every sample. The "
            "recording was run again for these, exactly as the replay ran it.</p>\n",
            SW_CLI_ZOOM_HALF);
    if (sw_cli_report_zooms(F, z, nz, fig, risk) != SW_EXIT_OK) {
        fprintf(f, "<p class=\"over\">The close-ups could not be made.</p>\n");
        return -1;
    }
    for (size_t i = 0; i < nz; i++) {
        char title[640], id[32], before[1024];
        snprintf(title, sizeof title, "%s: %.3f s to %.3f s", name, z[i].t0, z[i].t1);
        snprintf(id, sizeof id, "zoom-%zu", i);
        char u0[64], u1[64], utc[160] = "";
        if (sw_cli_forensics_utc(F, z[i].t0, u0, sizeof u0) &&
            sw_cli_forensics_utc(F, z[i].t1, u1, sizeof u1))
            snprintf(utc, sizeof utc, " (%s to %s)", u0, u1);
        snprintf(before, sizeof before, "Close-up: %.3f s to %.3f s%s, around %s. ", z[i].t0,
                 z[i].t1, utc, z[i].what);
        if (embed(f, fig[i], title, id, before) != 0)
            rc = -1;
        sw_cli_figure_destroy(fig[i]);
        sw_risk_destroy(risk[i]);
    }
    return rc;
}

/* ---- tables ------------------------------------------------------------------------ */

static void events(FILE *f, const sw_cli_forensics_t *F)
{
    fprintf(f,
            "<h2>Events</h2>\n<table id=\"events\"><tr><th>t (s)</th>%s<th>package</th>"
            "<th>event</th><th>&theta;/&alpha;</th><th>margin</th></tr>\n",
            F->R.run.absolute ? "<th>UTC</th>" : "");
    for (size_t i = 0; i < F->nev; i++) {
        const sw_event_t *e = &F->ev[i];
        const double alpha = atan2(F->scenes[e->pkg].width, F->scenes[e->pkg].height);
        fprintf(f, "<tr>");
        time_cells(f, F, e->t);
        fprintf(f, "<td>");
        html(f, F->scenes[e->pkg].name);
        fprintf(f, "</td><td>%s</td><td class=\"n\">", sw_event_name(e->kind));
        num(f, "%.3f", e->theta / alpha);
        fprintf(f, "</td><td class=\"n\">");
        num(f, "%.3f", e->margin);
        fprintf(f, "</td></tr>\n");
    }
    fprintf(f, "</table>\n");
    if (F->nev == 0)
        fprintf(f, "<p>No events: no package left its rest.</p>\n");
    if (F->ev_dropped > 0)
        fprintf(f,
                "<p class=\"note\">%ld more events (impacts after the first 20 of a package, "
                "or beyond %d in all) are not listed; <code>--events FILE</code> writes every "
                "one.</p>\n",
                F->ev_dropped, SW_CLI_FORENSICS_EVENTS);
}

static void whatif(FILE *f, const sw_cli_forensics_t *F)
{
    fprintf(f,
            "<h2>What would have saved it</h2>\n<p>The same recording, with each package "
            "as given, alone on the bed, on typical supports and in other sizes. Smallest "
            "reserve: the design braking pulse, in g, that would have overturned it at its "
            "most threatened moment (&le; x (&ge; y): between y and x, the search stopped at "
            "its budget). Safety factor: the recording scaled by the first number leaves it "
            "upright, by the second it overturns.</p>\n");
    int planes = 1;
    for (size_t k = 0; k < F->n; k++) {
        int p;
        sw_cli_forensics_plane(F, k, &p);
        planes = p > planes ? p : planes;
    }
    if (planes == 2)
        fprintf(f,
                "<p class=\"note\">A package with a depth is judged in both planes in every "
                "case (across the truck over the case's depth, on the case's support): the "
                "outcome, peak and margin are the worse plane's, named; the reserve the "
                "smaller; the safety factor both axes scaled together.</p>\n");
    for (size_t k = 0; k < F->n; k++) {
        fprintf(f, "<h3>");
        html(f, F->scenes[k].name);
        fprintf(f,
                "</h3>\n<table class=\"whatif\"><tr><th>case</th><th>outcome</th>"
                "<th>peak &theta;/&alpha;</th><th>smallest margin</th><th>smallest "
                "reserve</th><th>safety factor</th><th>package and support</th></tr>\n");
        for (size_t i = 0; i < F->ncases; i++) {
            const sw_whatif_case_t *C = &F->cases[i];
            if (C->pkg != k)
                continue;
            fprintf(f, "<tr><td>");
            html(f, C->name);
            sw_forensics_verdict_t v;
            sw_forensics_case_verdict(F->fx, i, &v);
            if (!v.judged) {
                fprintf(f, "</td><td colspan=\"6\">not computed%s: ",
                        v.unjudged == SW_PLANE_LAT ? " across the truck" : "");
                html(f, v.note);
                fprintf(f, "</td></tr>\n");
                continue;
            }
            const sw_safety_t *sf = &v.factor.sf;
            const sw_run_result_t *r = &v.run->sf.at_one;
            char b[64];
            sw_cli_safety_bracket(b, sizeof b, sf);
            fprintf(f, "</td><td class=\"%s\">%s%s</td><td class=\"n\">",
                    r->overturned ? "over" : "up", r->overturned ? "overturned" : "upright",
                    v.factor.planes < 2 ? ""
                    : v.run == C        ? " along"
                                        : " across");
            num(f, "%.3f", r->max_theta_ratio);
            fprintf(f, "</td><td class=\"n\">");
            num(f, "%.3f", r->min_margin);
            char rsv[192];
            sw_cli_whatif_reserve_text(rsv, sizeof rsv, v.reserve);
            fprintf(f, "</td><td class=\"n\">");
            html(f, rsv);
            fprintf(f, "</td><td class=\"n\">");
            html(f, b);
            if (!sf->overturned && sf->below.found)
                fprintf(f, " (but %.4g overturns: luck of timing)", sf->below.x);
            fprintf(f, "</td><td>");
            char desc[224];
            html(f, sw_cli_whatif_desc(desc, sizeof desc, C));
            if (C->stands_for) {
                fprintf(f, "<br><span class=\"note\">");
                html(f, C->stands_for);
                fprintf(f, "</span>");
            }
            fprintf(f, "</td></tr>\n");
        }
        fprintf(f, "</table>\n");
    }
}

static void limits(FILE *f, const sw_cli_forensics_t *F)
{
    const long runs = sw_forensics_trials(F->fx);
    fprintf(f,
            "<h2>How this was found</h2>\n"
            "<p>The recording was read as <code>swaywatch replay</code> reads it (the same "
            "columns, units, plausibility checks and gap handling) and each package was run "
            "through its rocking model: a rigid block that stays on the bed until the "
            "acceleration lifts one edge, then rocks about that edge, with the frame and "
            "cushion, where there is one, as springs and dampers. The safety factor was found "
            "by scaling the whole longitudinal acceleration of the recording and running it "
            "again, scanning upward and then narrowing the change from upright to overturned "
            "(%ld runs in all).</p>\n"
            "<h2>Assumptions and limits</h2>\n<ul>\n"
            "<li>Only the acceleration along the direction of travel moves the package (and the "
            "vertical one where the log has it); sideways motion, the road's slope and the "
            "truck's pitch are not part of the model.</li>\n"
            "<li>The package is a rigid box with its mass at its centre; it does not slide, and "
            "its edges do not bounce (each impact with the bed loses the energy the model "
            "says). A package that can slide, or that is lashed, is not described by it.</li>\n"
            "<li>Frames and cushions are linear springs with viscous damping of the stated "
            "natural frequency; a real foam is stiffer as it compresses and its damping "
            "depends on the speed.</li>\n"
            "<li>The catalogue's frequencies are typical values for supports loaded as "
            "intended; the numbers of the actual product under the actual load should "
            "replace them (<code>--frame-omega</code>, <code>--cushion-omega</code>).</li>\n"
            "<li>The recording is taken as the motion of the bed under the package. A sensor "
            "elsewhere on the truck, or one that clips, changes the answer.</li>\n"
            "<li>The safety factor scales the whole recording: a different shock of the same "
            "strength can do more or less. Overturning is not monotonic in the strength, which "
            "is why the search also looks below the recorded strength.</li>\n"
            "</ul>\n",
            runs);
}

/* A file's row of the fingerprint. */
static void digest_row(FILE *f, const char *what, const char *path, const sw_cli_digest_t *d)
{
    fprintf(f, "<tr><th>%s</th><td><code>", what);
    html(f, path);
    fprintf(f, "</code></td>");
    if (d && d->ok)
        fprintf(f, "<td class=\"n\">%lld</td><td><code class=\"sha256\">%s</code></td></tr>\n",
                d->size, d->sha256);
    else {
        fprintf(f, "<td colspan=\"2\">no digest: ");
        html(f, d ? d->why : "not computed");
        fprintf(f, "</td></tr>\n");
    }
}

static void fingerprint(FILE *f, const sw_cli_forensics_t *F)
{
    char v[160];
    sw_cli_version_text(v, sizeof v);
    fprintf(f,
            "<h2 id=\"fingerprint\">Fingerprint</h2>\n<p>What this report was made from: "
            "<code>sha256sum FILE</code> gives the same digits for the same file.</p>\n"
            "<table id=\"digests\"><tr><th></th><th>file</th><th>bytes</th><th>SHA-256</th>"
            "</tr>\n");
    digest_row(f, "log", strcmp(F->log, "-") ? F->log : "(standard input)",
               F->fingerprinted ? &F->log_digest : NULL);
    for (size_t i = 0; i < F->o.scenes.n; i++)
        digest_row(f, "scene", F->o.scenes.v[i], F->scene_digest ? &F->scene_digest[i] : NULL);
    fprintf(f, "</table>\n<p>Made by swaywatch <span id=\"version\">");
    html(f, v);
    fprintf(f,
            "</span>, with the command (as a POSIX shell reads it back)</p>\n<p><code "
            "id=\"command\">");
    html(f, F->command_line ? F->command_line : "(not known)");
    char when[64] = "";
    const time_t now = time(NULL);
    struct tm tm;
    if (gmtime_r(&now, &tm))
        strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", &tm);
    fprintf(f,
            "</code></p>\n<p class=\"note\">Written %s. The same content as JSON: add "
            "<code>--json</code>.</p>\n",
            when);
}

int sw_cli_forensics_report(const sw_cli_forensics_t *F, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        sw_cli_error("--report %s: cannot write: %s", path, strerror(errno));
        return SW_EXIT_IO;
    }
    fprintf(f,
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<title>Incident report: ");
    html(f, strcmp(F->log, "-") ? F->log : "(standard input)");
    fprintf(f,
            "</title>\n<style>\n%s</style>\n</head>\n<body>\n<h1>Incident report</h1>\n"
            "<p class=\"note\">Whether the recorded motion of the truck bed overturned the "
            "cargo, how close it came, and what would have saved it.</p>\n",
            style);
    banner(f, F);
    answers(f, F);
    log_facts(f, F);
    moments(f, F);
    unused(f, F);
    figures(f, F);
    events(f, F);
    if (!F->fo.w.no_what_if)
        whatif(f, F);
    limits(f, F);
    fingerprint(f, F);
    fprintf(f, "</body>\n</html>\n");
    if (ferror(f) | (fclose(f) != 0)) {
        sw_cli_error("--report %s: write error", path);
        return SW_EXIT_IO;
    }
    return SW_EXIT_OK;
}
