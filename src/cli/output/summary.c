/* SPDX-License-Identifier: GPL-3.0-or-later */
/* summary.c - what a run says at its end: the human summary, the JSON
 * summary, the verdict's exit code, and the derived quantities of
 * --verbose (the writers of the output files are in output.c).
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

/* ---- derived quantities -------------------------------------------------- */

/* One aligned line of --verbose: name, value with unit, what it is. */
static void derived_line(FILE *f, const char *name, double v, const char *unit, const char *what)
{
    char val[48];
    snprintf(val, sizeof val, "%.6g %s", v, unit);
    fprintf(f, "  %-8s %-18s %s\n", name, val, what);
}

void sw_cli_print_derived(FILE *f, const sw_engine_t *e, const sw_scene_t *scenes, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        const sw_derived_t *d = sw_engine_derived(e, i);
        const sw_scene_t *sc = &scenes[i];
        if (!d)
            continue;
        fprintf(f, "swaywatch: %s: %s model\n", sc->name, sw_model_name(d->model));
        derived_line(f, "R", d->R, "m", "half-diagonal sqrt(h^2 + b^2)");
        derived_line(f, "alpha", d->alpha * 180.0 / M_PI, "deg", "atan(b/h), slenderness");
        derived_line(f, "g tan a", sc->g * tan(d->alpha), "m/s^2",
                     "uplift threshold (rigid support)");
        derived_line(f, "p", d->p, "rad/s", "rocking frequency sqrt(3 g / 4 R)");
        derived_line(f, "eta", d->eta, "", "impact ratio on a rigid support");
        if (sc->has_frame) {
            derived_line(f, "gamma", d->gamma, "", "m / (m + m_b)");
            derived_line(f, "omega_b", d->omega_b, "rad/s", "bearing frequency");
            derived_line(f, "zeta_b", d->zeta_b, "", "bearing damping ratio");
            derived_line(f, "r_frame", d->r_frame, "", "impact ratio on the frame");
        }
        if (sc->has_cushion) {
            derived_line(f, "omega_c", d->omega_c, "rad/s", "cushion frequency sqrt(K/m)");
            derived_line(f, "zeta_c", d->zeta_c, "", "cushion damping ratio");
            if (d->K > 0.0) {
                double wz, wr;
                sw_cushion_frequencies(d, sc->g, &wz, &wr);
                derived_line(f, "z_static", sw_cushion_static_deflection(d, sc->g), "m",
                             "static cushion deflection, root of K z + B3 z^3 = m g");
                derived_line(f, "omega_z", wz, "rad/s", "vertical natural frequency (undamped)");
                derived_line(f, "omega_r", wr, "rad/s", "rocking natural frequency on the cushion");
            }
        }
        char what[64];
        snprintf(what, sizeof what, "internal step of scheme %s", sw_engine_scheme(e));
        derived_line(f, "dt", sw_engine_dt(e, i), "s", what);
    }
}

/* ---- summaries --------------------------------------------------------------- */

/* The summaries of package i's planes into s[0] (along the truck) and
 * s[1] (across it, with a lateral plane): how many (0: no package i). */
static int plane_summaries(const sw_engine_t *e, size_t i, sw_summary_t s[SW_PLANES])
{
    if (sw_engine_summary(e, i, &s[0]) != SW_OK)
        return 0;
    return sw_engine_summary_plane(e, i, SW_PLANE_LAT, &s[1]) == SW_OK ? 2 : 1;
}

/* Package i's verdict: its plane's summary, or its worse plane's (which
 * in *plane). */
static int verdict_summary(const sw_engine_t *e, size_t i, sw_summary_t *v, sw_plane *plane)
{
    sw_summary_t s[SW_PLANES];
    const int n = plane_summaries(e, i, s);
    if (!n)
        return -1;
    const int worse = n == 2 && sw_summary_worse(&s[0], &s[1]);
    *v = s[worse];
    if (plane)
        *plane = worse ? SW_PLANE_LAT : SW_PLANE_LONG;
    return 0;
}

int sw_cli_any_overturned(const sw_engine_t *e)
{
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s[SW_PLANES];
        const int n = plane_summaries(e, i, s);
        for (int p = 0; p < n; p++)
            if (s[p].overturned)
                return 1;
    }
    return 0;
}

/* A free flight longer than SW_FLIGHT_LONG (physics.md "Free flight"): its
 * landing is outside the model, so what followed it is not a verdict,
 * unless the package had overturned before it. */
static int flight_open(const sw_summary_t *s)
{
    return !isnan(s->flight_long_time) &&
           !(s->overturned && s->overturn_time < s->flight_long_time);
}

const char *sw_cli_verdict_seen(const sw_summary_t *s)
{
    if (s->overturned)
        return "overturned";
    return s->faults ? "unreliable" : "upright";
}

long sw_cli_run_incomplete(const sw_cli_run_t *run)
{
    /* the one place that says which doubts about the input leave a
     * verdict open: today the gate's gaps and restarts over motion (a
     * long free flight, a doubt about the model, is flight_open()'s) */
    return run && run->have_facts ? run->facts.incomplete : 0;
}

const char *sw_cli_verdict(const sw_summary_t *s, const sw_cli_run_t *run)
{
    if (flight_open(s) || (!s->overturned && sw_cli_run_incomplete(run) > 0))
        return "incomplete";
    return sw_cli_verdict_seen(s);
}

void sw_cli_incomplete_why(const sw_cli_run_t *run, char *buf, size_t len)
{
    const long n = sw_cli_run_incomplete(run);
    if (len)
        buf[0] = '\0';
    if (n <= 0)
        return;
    const sw_gate_facts_t *F = &run->facts;
    const sw_cli_unused_t *u = &run->unused;
    int k;
    if (u->have_incomplete) {
        const sw_cli_unused_gap_t *g = &u->first_incomplete;
        const double at = g->t - F->t_origin;
        if (g->kind == SW_GATE_EV_GAP)
            k = snprintf(buf, len, "a gap of %.4g s at %.3f s", g->span, at);
        else if (g->kind == SW_GATE_EV_RESTART)
            k = snprintf(buf, len, "a restart of the log's clock at %.3f s (back by %.4g s)", at,
                         -g->span);
        else
            k = snprintf(buf, len, "a step of the log's clock at %.3f s", at);
    } else { /* an lcm-logger file: the monitor core keeps the first time alone */
        k = snprintf(buf, len, "a gap or restart at %.3f s", F->first_incomplete - F->t_origin);
    }
    if (k < 0 || (size_t)k >= len)
        return;
    snprintf(buf + k, len - (size_t)k,
             " overlapped rocking or an acceleration near the uplift threshold");
    if (n > 1) {
        const size_t m = strlen(buf);
        snprintf(buf + m, len - m, " (%ld such in all)", n);
    }
}

/* The step taken and the one asked for differ (beyond rounding: a 1 kHz
 * log's intervals are 1 ms to the last bits). */
static int dt_differs(const sw_engine_t *e, size_t i)
{
    const double dt = sw_engine_dt_used(e, i), req = sw_engine_dt_requested(e);
    return !(fabs(dt - req) <= 1e-9 * req);
}

/* What the default scheme and step said of package i, where a chosen
 * scheme or dt ran beside it (sw_engine_checker): its verdict word into
 * *word, and 1 if it agrees with this run's; -1 where there is no check. */
static int check_agrees(const sw_engine_t *e, size_t i, const sw_summary_t *s, const char **word)
{
    const sw_engine_t *c = sw_engine_checker(e);
    sw_summary_t cs;
    if (!c || sw_engine_summary(c, i, &cs) != SW_OK)
        return -1;
    *word = sw_cli_verdict_seen(&cs);
    return !strcmp(*word, sw_cli_verdict_seen(s));
}

/* A verdict the default scheme and step contradict: said on stderr, so
 * that no chosen --scheme or --dt changes a verdict quietly. */
static void warn_checks(const sw_engine_t *e)
{
    const sw_engine_t *c = sw_engine_checker(e);
    for (size_t i = 0; c && i < sw_engine_count(e); i++) {
        sw_summary_t s;
        const char *dw = NULL;
        if (sw_engine_summary(e, i, &s) != SW_OK || check_agrees(e, i, &s, &dw) != 0)
            continue;
        sw_cli_error(
            "warning: %s: %s at dt %.3g ms says %s, the default (%s at dt %.3g ms) says %s: "
            "the verdict depends on the scheme or the step; trust the default, or check with "
            "--accuracy",
            s.name, sw_engine_scheme(e), sw_engine_dt_used(e, i) * 1e3, sw_cli_verdict_seen(&s),
            sw_engine_scheme(c), sw_engine_dt_used(c, i) * 1e3, dw);
    }
}

int sw_cli_verdict_exit(const sw_engine_t *e, const sw_cli_run_t *run, int fail_on_overturn)
{
    warn_checks(e);
    if (!fail_on_overturn)
        return SW_EXIT_OK;
    if (sw_cli_any_overturned(e))
        return SW_EXIT_OVERTURNED;
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s[SW_PLANES];
        const int n = plane_summaries(e, i, s);
        for (int p = 0; p < n; p++)
            if (flight_open(&s[p])) {
                sw_cli_error(
                    "%s: the verdict is incomplete: in the air over %g s from %.4f s, the "
                    "landing is outside the model; --fail-on-overturn exits 1",
                    s[p].name, SW_FLIGHT_LONG, s[p].flight_long_time);
                return SW_EXIT_OVERTURNED;
            }
    }
    if (sw_cli_run_incomplete(run) > 0) {
        char why[256];
        sw_cli_incomplete_why(run, why, sizeof why);
        sw_cli_error(
            "%s: the verdict is incomplete: %s; an overturn may be hidden there, so "
            "--fail-on-overturn exits 1",
            run->log && strcmp(run->log, "-") ? run->log : "(stdin)", why);
        return SW_EXIT_OVERTURNED;
    }
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s[SW_PLANES];
        const int n = plane_summaries(e, i, s);
        for (int p = 0; p < n; p++)
            if (s[p].faults) {
                sw_cli_error(
                    "%s: the model faulted %ld times%s: no verdict, and --fail-on-overturn "
                    "needs one (exit 2)",
                    s[p].name, s[p].faults, p ? " in the lateral plane" : "");
                return SW_EXIT_USAGE;
            }
    }
    return SW_EXIT_OK;
}

static double alpha_of(const sw_engine_t *e, size_t i)
{
    const sw_derived_t *d = sw_engine_derived(e, i);
    return d ? d->alpha : NAN;
}

/* "at 7.5123 s" or a fallback phrase when the time is absent. */
static void print_time(FILE *f, double t, const char *none)
{
    if (isfinite(t))
        fprintf(f, "%.4f s", t);
    else
        fputs(none, f);
}

/* An absolute time (s since 1970) as ISO-8601 UTC with milliseconds. */
void sw_cli_iso_seconds(char *buf, size_t len, double t)
{
    const double whole = floor(t);
    long ms = lround((t - whole) * 1000.0);
    time_t secs = (time_t)whole;
    if (ms >= 1000) {
        ms -= 1000;
        secs++;
    }
    struct tm tm;
    if (!gmtime_r(&secs, &tm) || !strftime(buf, len, "%Y-%m-%dT%H:%M:%S", &tm)) {
        snprintf(buf, len, "%.3f s since 1970", t);
        return;
    }
    const size_t n = strlen(buf);
    snprintf(buf + n, len - n, ".%03ldZ", ms);
}

int sw_cli_epoch_plausible(double t)
{
    return t >= SW_CLI_EPOCH_MIN && t < SW_CLI_EPOCH_MAX;
}

int sw_cli_run_utc(const sw_cli_run_t *run, double t, char *buf, size_t len)
{
    if (len)
        buf[0] = '\0';
    if (!run->absolute || !run->have_facts || !isfinite(t))
        return 0;
    /* after a step or a restart, engine times are no longer the source's
     * shifted by the origin; an lcm-logger file's events are not listed,
     * so none is known after its first */
    const sw_gate_facts_t *F = &run->facts;
    if (run->unused.listed ? !(t < run->unused.first_shift) : (F->restarts || F->clock_steps))
        return 0;
    sw_cli_iso_seconds(buf, len, t + F->t_origin + run->abs_base);
    return 1;
}

/* The facts of the log: what would expose a misread (duration, rate, peak,
 * gaps), and whether the verdict is incomplete or forced. */
static void print_facts(FILE *f, const sw_cli_run_t *run)
{
    const sw_gate_facts_t *F = &run->facts;
    const double t0 = F->t_first - F->t_origin, t1 = F->t_last - F->t_origin;
    const double share =
        run->samples_read ? 100.0 * (double)run->samples_rejected / (double)run->samples_read : 0.0;
    fprintf(f, "  rejected        %ld of %ld (%.2f %%)\n", run->samples_rejected, run->samples_read,
            share);
    if (run->absolute) {
        char iso[64], end[64];
        sw_cli_iso_seconds(iso, sizeof iso, run->abs_start);
        sw_cli_iso_seconds(end, sizeof end, run->abs_end);
        fprintf(
            f, "  starts          %s, ends %s (UTC, from %s; the times below are from the start)\n",
            iso, end, run->abs_from);
    }
    fprintf(f, "  times           %.4f s to %.4f s (%.4f s of samples)\n", t0, t1, F->duration);
    if (isfinite(F->dt_median))
        fprintf(f, "  sample interval %.6g ms median (%.6g to %.6g ms): %.6g Hz\n",
                F->dt_median * 1e3, F->dt_min * 1e3, F->dt_max * 1e3, F->rate);
    fprintf(f, "  peak |a|        %.4g m/s^2 = %.4g g\n", F->peak_a, F->peak_a / SW_G0);
    if (F->gaps || F->restarts || F->clock_steps)
        fprintf(f,
                "  gaps            %ld (%.4g s in all, the longest %.4g s); restarts %ld, "
                "clock steps %ld\n",
                F->gaps, F->gap_total, F->gap_max, F->restarts, F->clock_steps);
    else
        fputs("  gaps            none\n", f);
    if (F->incomplete)
        fprintf(f,
                "  VERDICT INCOMPLETE: %ld gap%s or restart%s overlap%s rocking or an "
                "acceleration near the uplift threshold (first at %.4f s)\n",
                F->incomplete, F->incomplete == 1 ? "" : "s", F->incomplete == 1 ? "" : "s",
                F->incomplete == 1 ? "s" : "", F->first_incomplete - F->t_origin);
    if (run->forced)
        fprintf(f, "  VERDICT FORCED (--force): %s\n", run->check);
    else if (run->check[0])
        fprintf(f, "  warning         %s\n", run->check);
}

/* The outcome line's words: a faulted run never reads as a plain verdict,
 * nor one that a gap may have changed. */
static void print_outcome(FILE *f, const sw_summary_t *s, const sw_cli_run_t *run)
{
    if (!s->overturned && sw_cli_run_incomplete(run) > 0) {
        char why[256];
        sw_cli_incomplete_why(run, why, sizeof why);
        if (s->faults)
            fprintf(f, "INCOMPLETE: no verdict as far as the samples go (model faulted %ld times)",
                    s->faults);
        else
            fputs("INCOMPLETE: upright as far as the samples go", f);
        fprintf(f, ", but %s", why);
    } else if (s->overturned) {
        fputs("OVERTURNED at ", f);
        print_time(f, s->overturn_time, "an unknown time");
        if (s->faults)
            fprintf(f, " (the model faulted %ld times before: see --events)", s->faults);
    } else if (s->faults) {
        fprintf(f, "stayed upright (model faulted %ld times: not a verdict; see --events)",
                s->faults);
    } else {
        fputs("stayed upright", f);
    }
    if (s->flights)
        fprintf(f, "; %ld free flight%s, the longest %.3g s", s->flights,
                s->flights == 1 ? "" : "s", s->flight_max);
    if (flight_open(s))
        fprintf(f,
                " -- INCOMPLETE: in the air over %g s from %.4f s, the landing is outside "
                "the model",
                SW_FLIGHT_LONG, s->flight_long_time);
}

/* Impacts: the ones that matter, the settling apart. */
static void print_impacts(FILE *f, const sw_summary_t *s, const sw_risk_pkg_t *p)
{
    if (!p || !(p->impact_min > 0.0)) {
        fprintf(f, "\n  impacts         %ld\n", s->impacts);
        return;
    }
    fprintf(
        f,
        "\n  impacts         %ld that matter (before each, at least %.3g rad/s: a swing of 1 %% "
        "of the energy that tips it)",
        p->impacts, p->impact_min);
    if (p->micro_impacts)
        fprintf(f, "; %ld micro-impacts in %ld settling span%s", p->micro_impacts,
                p->settling_spans, p->settling_spans == 1 ? "" : "s");
    fputc('\n', f);
}

/* The margin, and what its number means. */
static void print_margin(FILE *f, const sw_summary_t *s)
{
    fprintf(f, "\n  minimum margin  %.4f (energy to spare: 1 at rest, 0 at the edge of overturning",
            s->min_margin);
    if (s->min_margin < 0.0)
        fprintf(f, "; below 0 it was falling, shown as %.3f in [-1, 0] in figures",
                sw_margin_presented(s->min_margin, SW_PHASE_ROCKING));
    fputs(")\n", f);
}

/* The reserve: the smallest evaluated, in g, and what it means; across
 * the truck (lateral) its pulse is sideways. */
static void print_reserve(FILE *f, const sw_risk_pkg_t *p, int lateral)
{
    if (p && p->no_reserve) {
        fprintf(f, "  reserve         none: the scene is too stiff for it to be computed\n");
        return;
    }
    if (!p || !p->evaluations)
        return;
    if (!(p->min_reserve_g > 0.0))
        fprintf(f,
                "  minimum reserve 0 g at %.4f s: from then on it overturns with no further "
                "input (at rest %.3g g)\n",
                p->min_reserve_time, p->rest_reserve_g);
    else
        fprintf(f,
                "  minimum reserve %.3g g at %.4f s: a %s half-sine of %.3g s that strong "
                "would have overturned it then (at rest %.3g g)\n",
                p->min_reserve_g, p->min_reserve_time,
                lateral                                       ? "sideways"
                : p->min_direction == SW_RESERVE_ACCELERATING ? "speeding-up"
                                                              : "braking",
                p->min_pulse, p->rest_reserve_g);
    if (p->reserve_faults)
        fprintf(f, "                  (%ld evaluations had a run fault: the value may be high)\n",
                p->reserve_faults);
}

/* One plane's lines, from its first uplift to its outcome. */
static void print_plane(FILE *f, const sw_summary_t *s, double alpha, const sw_risk_pkg_t *p,
                        int lateral, const sw_cli_run_t *run)
{
    fputs("  first uplift    ", f);
    print_time(f, s->uplift_time, "none (never left the upright position)");
    if (s->uplifts > 1)
        fprintf(f, " (%ld uplifts in all)", s->uplifts);
    print_impacts(f, s, lateral ? NULL : p); /* the lateral impacts are not sorted */
    fprintf(f, "  peak |theta|    %.3f deg = %.3f alpha (alpha = %.2f deg)\n",
            s->max_abs_theta * 180.0 / M_PI, s->max_theta_ratio, alpha * 180.0 / M_PI);
    fputs("  tipped (alpha)  ", f);
    print_time(f, s->tip_time, "no (|theta| stayed below alpha)");
    print_margin(f, s);
    print_reserve(f, p, lateral);
    fputs("  outcome         ", f);
    print_outcome(f, s, run);
    fputc('\n', f);
}

/* Package i's lateral plane: its engine (k its package there), the
 * planes' summary and the lateral one's; NULL for a package in one plane. */
static const sw_engine_t *lateral_of(const sw_engine_t *e, size_t i, sw_planes_t *P, size_t *k,
                                     sw_summary_t *s)
{
    const sw_engine_t *L = sw_engine_plane(e, i, SW_PLANE_LAT, k);
    if (sw_engine_planes_summary(e, i, P) != SW_OK || P->planes < 2 || !L ||
        sw_engine_summary(L, *k, s) != SW_OK)
        return NULL;
    return L;
}

/* A package with a lateral plane: its lines, which plane the verdict is,
 * and both planes lifted at once. */
static void print_lateral(FILE *f, const sw_engine_t *e, size_t i, const sw_cli_run_t *run)
{
    sw_planes_t P;
    size_t k;
    sw_summary_t s;
    const sw_engine_t *L = lateral_of(e, i, &P, &k, &s);
    if (!L)
        return;
    const sw_derived_t *d = sw_engine_derived(L, k);
    fprintf(f, "  lateral plane   across the truck, depth %.4g m: scheme %s, dt %.6g ms\n",
            d ? 2.0 * d->b : NAN, sw_engine_scheme(L), sw_engine_dt_used(L, k) * 1e3);
    print_plane(f, &s, d ? d->alpha : NAN, sw_stream_risk_plane(run->stream, i, SW_PLANE_LAT), 1,
                run);
    sw_summary_t v;
    verdict_summary(e, i, &v, NULL);
    fprintf(f, "  verdict         %s, decided by the %s plane%s\n", sw_cli_verdict(&v, run),
            sw_plane_name(P.worse),
            P.worse == SW_PLANE_LAT && v.overturned ? " (tipped sideways)" : "");
    if (P.both_rocking)
        fprintf(f,
                "  both planes     lifted at once from %.4f s to %.4f s (%.4g s in all): the "
                "package may have rocked on a corner, which the planar models approximate "
                "(docs/physics.md, \"The lateral plane\")\n",
                P.both_from, P.both_to, P.both_time);
}

void sw_cli_print_reserve(FILE *f, const sw_risk_pkg_t *p)
{
    print_reserve(f, p, 0);
}

/* The words a summary of an interrupted run starts with. */
static void print_interrupted(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run)
{
    if (!run->interrupted)
        return;
    const double t = sw_engine_time(e);
    fprintf(f, "INTERRUPTED by %s", run->interrupted == SIGINT ? "SIGINT" : "SIGTERM");
    if (isfinite(t))
        fprintf(f, " at t = %.4f s: everything below covers the input up to there only\n", t);
    else
        fputs(" before the first sample\n", f);
}

void sw_cli_print_summary(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run)
{
    print_interrupted(f, e, run);
    if (run->log) {
        fprintf(f, "log %s: %ld samples read, %ld accepted, %ld rejected",
                strcmp(run->log, "-") ? run->log : "(stdin)", run->samples_read,
                run->samples_read - run->samples_rejected, run->samples_rejected);
        if (run->settle > 0.0)
            fprintf(f, "; settle up to %g s after the end", run->settle);
        fputc('\n', f);
        if (run->have_facts)
            print_facts(f, run);
    }
    if (run->pulse) {
        const sw_pulse_t *p = run->pulse;
        fprintf(f,
                "pulse %s: amplitude %g m/s^2 (%.4g g), omega %g rad/s, %.6g s long; %.6g s "
                "simulated\n",
                sw_pulse_shape_name(p->shape), p->amplitude, p->amplitude / SW_G0, p->omega,
                sw_pulse_duration(p), run->duration);
    }
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) != SW_OK)
            continue;
        double alpha = alpha_of(e, i);
        double dt = sw_engine_dt_used(e, i);
        fprintf(f, "\npackage %s: %s model, scheme %s, dt %.6g ms", s.name, sw_model_name(s.model),
                sw_engine_scheme(e), dt * 1e3);
        if (dt_differs(e, i))
            fprintf(f, " (requested %.6g ms)", sw_engine_dt_requested(e) * 1e3);
        fputc('\n', f);
        if (run->log)
            fprintf(f, "  samples         %ld read, %ld accepted, %ld rejected\n",
                    run->samples_read, run->samples_read - run->samples_rejected,
                    run->samples_rejected);
        print_plane(f, &s, alpha, sw_risk_pkg(run->risk, i), 0, run);
        const char *dw = NULL;
        const int agrees = check_agrees(e, i, &s, &dw);
        if (agrees >= 0)
            fprintf(
                f, "  default scheme  %s at dt %.6g ms: %s%s\n",
                sw_engine_scheme(sw_engine_checker(e)),
                sw_engine_dt_used(sw_engine_checker(e), i) * 1e3, dw,
                agrees ? " (agrees)" : " -- DIFFERS: this verdict depends on the scheme or step");
        print_lateral(f, e, i, run);
    }
}

/* ---- JSON ---------------------------------------------------------------------------- */

/* An ISO-8601 UTC time, or null. */
static void json_utc(json_t *o, const char *key, int have, const char *iso)
{
    sw_cli_rec_text(o, key, have ? iso : NULL);
}

void sw_cli_json_facts(json_t *o, const char *key, const sw_cli_run_t *run)
{
    const sw_gate_facts_t *F = &run->facts;
    json_t *in = sw_cli_rec_obj(o, key);
    sw_cli_rec_num(
        in, "rejected_share",
        run->samples_read ? (double)run->samples_rejected / (double)run->samples_read : 0.0);
    sw_cli_rec_num(in, "start", F->t_first - F->t_origin);
    sw_cli_rec_num(in, "end", F->t_last - F->t_origin);
    char iso[64];
    json_utc(in, "start_absolute", sw_cli_run_utc(run, 0.0, iso, sizeof iso), iso);
    if (run->absolute)
        sw_cli_iso_seconds(iso, sizeof iso, run->abs_end);
    json_utc(in, "end_absolute", run->absolute, iso);
    sw_cli_rec_num(in, "duration", F->duration);
    sw_cli_rec_num(in, "dt_median", F->dt_median);
    sw_cli_rec_num(in, "dt_min", F->dt_min);
    sw_cli_rec_num(in, "dt_max", F->dt_max);
    sw_cli_rec_num(in, "rate", F->rate);
    sw_cli_rec_num(in, "peak_accel", F->peak_a);
    sw_cli_rec_num(in, "peak_accel_g", F->peak_a / SW_G0);
    sw_cli_rec_int(in, "gaps", F->gaps);
    sw_cli_rec_num(in, "gap_total", F->gap_total);
    sw_cli_rec_num(in, "gap_max", F->gap_max);
    sw_cli_rec_int(in, "restarts", F->restarts);
    sw_cli_rec_int(in, "clock_steps", F->clock_steps);
    sw_cli_rec_bool(in, "incomplete", F->incomplete != 0);
    sw_cli_rec_bool(in, "forced", run->forced);
    sw_cli_rec_text(in, "check", run->check[0] ? run->check : NULL);
}

void sw_cli_json_incomplete(json_t *o, const sw_summary_t *s, const sw_cli_run_t *run)
{
    const long n = s->overturned ? 0 : sw_cli_run_incomplete(run);
    if (n <= 0 && !flight_open(s)) {
        sw_cli_rec_null(o, "incomplete_because");
        return;
    }
    json_t *w = sw_cli_rec_obj(o, "incomplete_because");
    char why[256];
    if (n <= 0) { /* a free flight too long for the model */
        snprintf(why, sizeof why,
                 "in the air over %g s from %.4f s: the landing is outside the model",
                 SW_FLIGHT_LONG, s->flight_long_time);
        sw_cli_rec_int(w, "count", 1);
        sw_cli_rec_num(w, "first_time", s->flight_long_time);
        sw_cli_rec_text(w, "first_kind", "flight");
        sw_cli_rec_null(w, "first_span");
        sw_cli_rec_text(w, "text", why);
        return;
    }
    const sw_gate_facts_t *F = &run->facts;
    const sw_cli_unused_t *u = &run->unused;
    const sw_cli_unused_gap_t *g = u->have_incomplete ? &u->first_incomplete : NULL;
    sw_cli_rec_int(w, "count", n);
    sw_cli_rec_num(w, "first_time", (g ? g->t : F->first_incomplete) - F->t_origin);
    sw_cli_rec_text(w, "first_kind", g ? sw_gate_event_name(g->kind) : NULL);
    sw_cli_rec_num(w, "first_span", g ? g->span : NAN);
    sw_cli_incomplete_why(run, why, sizeof why);
    sw_cli_rec_text(w, "text", why);
}

/* The reserve and the impacts that matter (null without them); across
 * the truck (lateral) the pulse's direction is a side: a negative pulse
 * (the one that brakes along the truck) points to the right, y being to
 * the left. */
static void json_risk(json_t *o, const sw_risk_pkg_t *p, int lateral)
{
    const int rv = p && p->evaluations > 0;
    sw_cli_rec_num(o, "min_reserve_g", rv ? p->min_reserve_g : NAN);
    sw_cli_rec_num(o, "min_reserve_time", rv ? p->min_reserve_time : NAN);
    sw_cli_rec_text(o, "min_reserve_direction",
                    !rv || !p->min_direction                 ? NULL
                    : p->min_direction == SW_RESERVE_BRAKING ? (lateral ? "right" : "braking")
                                                             : (lateral ? "left" : "accelerating"));
    sw_cli_rec_num(o, "min_reserve_pulse", rv && p->min_pulse > 0.0 ? p->min_pulse : NAN);
    sw_cli_rec_num(o, "rest_reserve_g", p ? p->rest_reserve_g : NAN);
    sw_cli_rec_int(o, "reserve_evaluations", p ? p->evaluations : 0L);
    sw_cli_rec_text(o, "no_reserve", p && p->no_reserve ? p->no_reserve : NULL);
    const int sig = p && p->impact_min > 0.0 && !lateral; /* lateral impacts: not sorted */
    sw_cli_rec_put(o, "significant_impacts", sig ? json_integer(p->impacts) : json_null());
    sw_cli_rec_put(o, "micro_impacts", sig ? json_integer(p->micro_impacts) : json_null());
    sw_cli_rec_put(o, "settling_spans", sig ? json_integer(p->settling_spans) : json_null());
}

/* One plane's fields (the longitudinal ones at the package's level, the
 * lateral ones in its "lateral" object): e holds it as package i. */
static void json_plane(json_t *o, const sw_engine_t *e, size_t i, const sw_summary_t *s,
                       const sw_risk_pkg_t *risk, int lateral)
{
    sw_cli_rec_num(o, "overturn_time", s->overturn_time);
    sw_cli_rec_num(o, "tip_time", s->tip_time);
    sw_cli_rec_num(o, "uplift_time", s->uplift_time);
    sw_cli_rec_num(o, "max_abs_theta", s->max_abs_theta);
    sw_cli_rec_num(o, "max_theta_ratio", s->max_theta_ratio);
    sw_cli_rec_num(o, "alpha", alpha_of(e, i));
    sw_cli_rec_num(o, "min_margin", s->min_margin);
    sw_cli_rec_num(o, "min_margin_bound", s->min_margin_bound);
    sw_cli_rec_num(o, "max_uplift_ratio", s->max_uplift_ratio);
    sw_cli_rec_int(o, "impacts", s->impacts);
    sw_cli_rec_int(o, "uplifts", s->uplifts);
    sw_cli_rec_int(o, "rests", s->rests);
    sw_cli_rec_int(o, "faults", s->faults);
    if (s->flights) { /* free flights (physics.md): only where there were some */
        sw_cli_rec_int(o, "flights", s->flights);
        sw_cli_rec_num(o, "flight_max", s->flight_max);
        sw_cli_rec_num(o, "flight_long_time", s->flight_long_time);
    }
    json_risk(o, risk, lateral);
}

/* A scheme or step chosen, checked by the default beside it. */
static void json_check(json_t *o, const sw_engine_t *e, size_t i, const sw_summary_t *s)
{
    const char *dw = NULL;
    const int agrees = check_agrees(e, i, s, &dw);
    if (agrees < 0)
        return;
    const sw_engine_t *c = sw_engine_checker(e);
    json_t *k = sw_cli_rec_obj(o, "scheme_check");
    sw_cli_rec_text(k, "scheme", sw_engine_scheme(c));
    sw_cli_rec_num(k, "dt", sw_engine_dt_used(c, i));
    sw_cli_rec_text(k, "verdict", dw);
    sw_cli_rec_bool(k, "agrees", agrees);
}

/* A package with a lateral plane: which plane the verdict is, both
 * planes lifted at once, and the lateral plane's fields. */
static void json_lateral(json_t *o, const sw_engine_t *e, size_t i, const sw_cli_run_t *run)
{
    sw_planes_t P;
    size_t k;
    sw_summary_t s;
    const sw_engine_t *L = lateral_of(e, i, &P, &k, &s);
    if (!L)
        return;
    sw_cli_rec_text(o, "plane", sw_plane_name(P.worse));
    sw_cli_rec_bool(o, "both_planes_rocking", P.both_rocking);
    sw_cli_rec_num(o, "both_planes_from", P.both_from);
    sw_cli_rec_num(o, "both_planes_to", P.both_to);
    sw_cli_rec_num(o, "both_planes_time", P.both_rocking ? P.both_time : NAN);
    json_t *l = sw_cli_rec_obj(o, "lateral");
    sw_cli_rec_bool(l, "overturned", s.overturned);
    sw_cli_rec_text(l, "verdict", sw_cli_verdict(&s, run));
    sw_cli_rec_text(l, "seen", sw_cli_verdict_seen(&s));
    json_plane(l, L, k, &s, sw_stream_risk_plane(run->stream, i, SW_PLANE_LAT), 1);
    sw_cli_rec_text(l, "scheme", sw_engine_scheme(L));
    sw_cli_rec_num(l, "dt", sw_engine_dt_used(L, k));
    sw_cli_rec_int(l, "steps", s.steps);
    json_check(l, L, k, &s);
}

int sw_cli_json_package(json_t *o, const sw_engine_t *e, size_t i, const sw_cli_run_t *run)
{
    sw_summary_t s, v;
    if (sw_engine_summary(e, i, &s) != SW_OK || verdict_summary(e, i, &v, NULL) != 0)
        return -1;
    sw_cli_rec_text(o, "name", s.name);
    sw_cli_rec_text(o, "model", sw_model_name(s.model));
    /* the package's verdict: with a lateral plane, the worse plane's ("plane") */
    sw_cli_rec_bool(o, "overturned", v.overturned);
    sw_cli_rec_text(o, "verdict", sw_cli_verdict(&v, run));
    sw_cli_rec_text(o, "seen", sw_cli_verdict_seen(&v));
    sw_cli_json_incomplete(o, &v, run);
    json_plane(o, e, i, &s, sw_risk_pkg(run->risk, i), 0);
    sw_cli_rec_int(o, "samples_read", run->samples_read);
    sw_cli_rec_int(o, "samples_rejected", run->samples_rejected);
    sw_cli_rec_text(o, "scheme", sw_engine_scheme(e));
    sw_cli_rec_num(o, "dt", sw_engine_dt_used(e, i));
    if (dt_differs(e, i))
        sw_cli_rec_num(o, "dt_requested", sw_engine_dt_requested(e));
    sw_cli_rec_int(o, "steps", s.steps);
    json_check(o, e, i, &s);
    json_lateral(o, e, i, run);
    return 0;
}

void sw_cli_json_summary(json_t *o, const sw_engine_t *e, const sw_cli_run_t *run)
{
    sw_cli_rec_text(o, "swaywatch", sw_version());
    sw_cli_rec_text(o, "log", run->log);
    if (run->pulse) {
        json_t *p = sw_cli_rec_obj(o, "pulse");
        sw_cli_rec_text(p, "shape", sw_pulse_shape_name(run->pulse->shape));
        sw_cli_rec_num(p, "amplitude", run->pulse->amplitude);
        sw_cli_rec_num(p, "omega", run->pulse->omega);
        sw_cli_rec_num(p, "duration", sw_pulse_duration(run->pulse));
        sw_cli_rec_num(o, "simulated", run->duration);
    }
    if (run->log)
        sw_cli_rec_num(o, "settle", run->settle);
    if (run->interrupted) {
        json_t *k = sw_cli_rec_obj(o, "interrupted");
        sw_cli_rec_text(k, "signal", run->interrupted == SIGINT ? "SIGINT" : "SIGTERM");
        sw_cli_rec_num(k, "t", sw_engine_time(e));
    } else {
        sw_cli_rec_null(o, "interrupted");
    }
    sw_cli_rec_int(o, "samples_read", run->samples_read);
    sw_cli_rec_int(o, "samples_rejected", run->samples_rejected);
    if (run->have_facts)
        sw_cli_json_facts(o, "input", run);
    json_t *pk = sw_cli_rec_arr(o, "packages");
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) == SW_OK)
            sw_cli_json_package(sw_cli_rec_obj(pk, NULL), e, i, run);
    }
}

int sw_cli_print_json(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run)
{
    json_t *o = sw_cli_rec_new();
    sw_cli_json_summary(o, e, run);
    if (sw_cli_rec_write(f, o, SW_CLI_REC_DOC) == 0)
        return SW_EXIT_OK;
    sw_cli_error("the JSON summary: out of memory");
    return SW_EXIT_IO;
}
