/* SPDX-License-Identifier: GPL-3.0-or-later */
/* report.c - "swaywatch forensics --report FILE.html": the incident report
 * as one self-contained HTML page an investigator can attach to a claim.
 * It needs no network and no script to be read: the style is inline, the
 * figure is the one replay draws (figure.c), drawn by gnuplot as SVG and
 * written into the page.  It says what --json says (forensics_out.c), in
 * the same order: the answer first, the method and the model's limits
 * after. */
#define _DEFAULT_SOURCE /* mkstemps */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "forensics.h"

#define G0 9.80665 /* m/s^2 per g */

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
    ".note{color:#555;font-size:0.9em}\n";

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

static void answers(FILE *f, const sw_cli_forensics_t *F)
{
    for (size_t k = 0; k < F->n; k++) {
        sw_summary_t s;
        const sw_cli_case_t *C = sw_cli_forensics_scene_case(F, k);
        if (!C || !sw_cli_forensics_summary(F, k, &s))
            continue;
        fprintf(f, "<div class=\"answer\" id=\"answer-%zu\"><p><b>", k);
        html(f, F->scenes[k].name);
        fprintf(f, "</b> (");
        html(f, C->desc);
        fprintf(f, "): ");
        const char *verdict = sw_cli_verdict(&s, &F->R.run);
        if (s.overturned) {
            fprintf(f, "<span class=\"over\">OVERTURNED</span> at %.3f s.", s.overturn_time);
        } else if (!strcmp(verdict, "incomplete")) {
            char why[256];
            sw_cli_incomplete_why(&F->R.run, why, sizeof why);
            fprintf(f,
                    "<span class=\"over\">INCOMPLETE</span>: %s as far as the samples go "
                    "(its tilt reached %.3f of the tipping angle), but ",
                    s.faults ? "no verdict (the model faulted)" : "upright", s.max_theta_ratio);
            html(f, why);
            fprintf(f, ": an overturn may be hidden there.");
        } else if (!strcmp(verdict, "upright")) {
            fprintf(f,
                    "<span class=\"up\">stayed upright</span>; its tilt reached %.3f of the "
                    "tipping angle, its smallest margin to overturn was %.3f.",
                    s.max_theta_ratio, s.min_margin);
        } else {
            fprintf(f, "<span class=\"over\">no verdict</span>: the model faulted.");
        }
        fprintf(f, "</p>");
        reserve(f, F->R.risk ? sw_risk_pkg(F->R.risk, k) : NULL);
        char b[64], sentence[640];
        sw_cli_safety_bracket(b, sizeof b, &C->sf);
        sw_cli_safety_sentence(sentence, sizeof sentence, &C->sf);
        fprintf(f, "<p><b>Safety factor %s.</b> ", b);
        html(f, sentence);
        fprintf(f, "</p>");
        if (s.overturned && !F->fo.w.no_what_if) {
            char save[512];
            sw_cli_whatif_savers(save, sizeof save, F->cases, F->ncases, k);
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
    if (run->have_facts && x->t_origin != 0.0) {
        char iso[64];
        sw_cli_iso_seconds(iso, sizeof iso, x->t_origin);
        row_text(f, "starts at (UTC)", iso);
    }
    fprintf(f, "<tr><th>duration</th><td>");
    num(f, "%.3f s", run->have_facts ? x->duration : NAN);
    fprintf(f, "</td></tr>\n<tr><th>sample rate</th><td>");
    num(f, "%.6g Hz", run->have_facts ? x->rate : NAN);
    fprintf(f, "</td></tr>\n<tr><th>samples</th><td>%ld read, %zu used, %ld rejected</td></tr>\n",
            run->samples_read, F->L.n, run->samples_rejected);
    fprintf(f, "<tr><th>peak |bed acceleration|</th><td>");
    num(f, "%.3f m/s&sup2;", run->have_facts ? x->peak_a : NAN);
    num(f, " (%.3f g)", run->have_facts ? x->peak_a / G0 : NAN);
    fprintf(f, "</td></tr>\n<tr><th>gaps</th><td>%ld", run->have_facts ? x->gaps : 0L);
    if (run->have_facts && x->gaps > 0)
        fprintf(f, " (%.3f s in all, the longest %.3f s)", x->gap_total, x->gap_max);
    fprintf(f, "; %ld restarts, %ld clock steps", run->have_facts ? x->restarts : 0L,
            run->have_facts ? x->clock_steps : 0L);
    if (run->have_facts && x->incomplete > 0)
        fprintf(f, "; <b>%ld of them leave the verdict incomplete</b>", x->incomplete);
    fprintf(f, "</td></tr>\n");
    if (run->check[0])
        row_text(f, run->forced ? "verdict forced although" : "warning", run->check);
    fprintf(f,
            "</table>\n<p class=\"note\">Times are seconds from the first sample. Rejected "
            "samples (unreadable rows, spikes, times out of order) are listed with their line "
            "on the standard error of the command that made this report.</p>\n");
}

/* ---- the figure -------------------------------------------------------------------- */

/* The figure drawn by gnuplot into a temporary SVG file, copied in from
 * its <svg> element on.  0, or -1 (a note is written instead). */
static int figure(FILE *f, const sw_cli_forensics_t *F)
{
    fprintf(f, "<h2>What the packages went through</h2>\n");
    const char *dir = getenv("TMPDIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/swaywatch-report-XXXXXX.svg", dir && *dir ? dir : "/tmp");
    int fd = mkstemps(path, 4);
    int ok = 0;
    if (fd >= 0) {
        close(fd);
        char title[512];
        snprintf(title, sizeof title, "%s", strcmp(F->log, "-") ? F->log : "(standard input)");
        if (F->fig && sw_cli_figure_draw(F->fig, path, title) == SW_EXIT_OK) {
            FILE *in = fopen(path, "r");
            if (in) {
                int started = 0;
                fprintf(f, "<div class=\"fig\" id=\"figure\">\n");
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
                fprintf(f, "</div>\n");
            }
        }
        unlink(path);
    }
    if (!ok) {
        sw_cli_error(
            "--report: the figure could not be drawn (gnuplot is needed); the report "
            "says so in its place");
        fprintf(f,
                "<p class=\"over\">The figure could not be drawn: gnuplot was not found or "
                "failed.</p>\n");
        return -1;
    }
    fprintf(f,
            "<p class=\"note\">Top: the bed acceleration a<sub>g</sub> (m/s&sup2;; negative is "
            "braking) with the thresholds &plusmn;g&nbsp;tan&nbsp;&alpha; at which a package "
            "standing on the bed starts to rock. Middle: the tilt &theta; of each package as a "
            "fraction of its tipping angle &alpha; (1: it tips over the edge; past it, it falls "
            "unless the truck pushes it back), with the events marked. Bottom: the margin to "
            "overturn (1 at rest, 0: it overturns with no more input). Long logs are drawn from "
            "the extremes of each stretch, so no peak is lost.</p>\n");
    return 0;
}

/* ---- tables ------------------------------------------------------------------------ */

static void events(FILE *f, const sw_cli_forensics_t *F)
{
    fprintf(f,
            "<h2>Events</h2>\n<table id=\"events\"><tr><th>t (s)</th><th>package</th>"
            "<th>event</th><th>&theta;/&alpha;</th><th>margin</th></tr>\n");
    for (size_t i = 0; i < F->nev; i++) {
        const sw_event_t *e = &F->ev[i];
        const double alpha = atan2(F->scenes[e->pkg].width, F->scenes[e->pkg].height);
        fprintf(f, "<tr><td class=\"n\">%.4f</td><td>", e->t);
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
    for (size_t k = 0; k < F->n; k++) {
        fprintf(f, "<h3>");
        html(f, F->scenes[k].name);
        fprintf(f,
                "</h3>\n<table class=\"whatif\"><tr><th>case</th><th>outcome</th>"
                "<th>peak &theta;/&alpha;</th><th>smallest margin</th><th>smallest "
                "reserve</th><th>safety factor</th><th>package and support</th></tr>\n");
        for (size_t i = 0; i < F->ncases; i++) {
            const sw_cli_case_t *C = &F->cases[i];
            if (C->pkg != k)
                continue;
            fprintf(f, "<tr><td>");
            html(f, C->name);
            if (!C->available) {
                fprintf(f, "</td><td colspan=\"6\">not computed: ");
                html(f, C->note);
                fprintf(f, "</td></tr>\n");
                continue;
            }
            const sw_run_result_t *r = &C->sf.at_one;
            char b[64];
            sw_cli_safety_bracket(b, sizeof b, &C->sf);
            fprintf(f, "</td><td class=\"%s\">%s</td><td class=\"n\">",
                    r->overturned ? "over" : "up", r->overturned ? "overturned" : "upright");
            num(f, "%.3f", r->max_theta_ratio);
            fprintf(f, "</td><td class=\"n\">");
            num(f, "%.3f", r->min_margin);
            char rsv[192];
            sw_cli_whatif_reserve_text(rsv, sizeof rsv, C);
            fprintf(f, "</td><td class=\"n\">");
            html(f, rsv);
            fprintf(f, "</td><td class=\"n\">");
            html(f, b);
            if (!C->sf.overturned && C->sf.below.found)
                fprintf(f, " (but %.4g overturns: luck of timing)", C->sf.below.x);
            fprintf(f, "</td><td>");
            html(f, C->desc);
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
    long runs = 0;
    for (size_t i = 0; i < F->ncases; i++)
        runs += F->cases[i].available ? F->cases[i].sf.trials : 0;
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

static void provenance(FILE *f, const sw_cli_forensics_t *F)
{
    fprintf(f, "<h2>Made by</h2>\n<p>swaywatch %s, with the command</p>\n<p><code>swaywatch",
            SW_VERSION);
    for (int i = 0; i < F->argc; i++) {
        fputc(' ', f);
        const char *a = F->argv[i];
        const int quote = strpbrk(a, " \t'\"\\$`!*?;&|<>()") != NULL || !*a;
        if (quote)
            fputc('\'', f);
        for (const char *p = a; *p; p++) {
            if (*p == '\'')
                fputs("'\\''", f);
            else {
                char c[2] = {*p, 0};
                html(f, c);
            }
        }
        if (quote)
            fputc('\'', f);
    }
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
    answers(f, F);
    log_facts(f, F);
    figure(f, F);
    events(f, F);
    if (!F->fo.w.no_what_if)
        whatif(f, F);
    limits(f, F);
    provenance(f, F);
    fprintf(f, "</body>\n</html>\n");
    if (ferror(f) | (fclose(f) != 0)) {
        sw_cli_error("--report %s: write error", path);
        return SW_EXIT_IO;
    }
    return SW_EXIT_OK;
}
