/* output.c - what the commands write: the state and event CSVs, the human
 * and JSON summaries, and the derived quantities of --verbose.
 *
 * Everything here prints its own messages ("swaywatch: ..." on stderr) and
 * returns an exit code. */
#include "output.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <signal.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>

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
        if (!d) continue;
        fprintf(f, "swaywatch: %s: %s model\n", sc->name, sw_model_name(d->model));
        derived_line(f, "R", d->R, "m", "half-diagonal sqrt(h^2 + b^2)");
        derived_line(f, "alpha", d->alpha * 180.0 / M_PI, "deg", "atan(b/h), slenderness");
        derived_line(f, "g tan a", sc->g * tan(d->alpha), "m/s^2", "uplift threshold (rigid support)");
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
        sw_cli_error("--%s -: standard output carries the %s", is_stdout(out_path) ? "out" : "events",
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

void sw_cli_csv_text(FILE *f, const char *s)
{
    if (!strpbrk(s, ",;\t\"\r\n")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"') fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

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
    if (is_stdout(path)) return stdout;
    FILE *f = fopen(path, "w");
    if (!f) sw_cli_error("%s: cannot create: %s", path, strerror(errno));
    return f;
}

int sw_cli_out_close(FILE *f, const char *path)
{
    if (!f) return SW_EXIT_OK;
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

int sw_cli_states_open(sw_cli_states_t *w, const char *path, long every, const sw_scene_t *scenes,
                       size_t n)
{
    memset(w, 0, sizeof *w);
    w->path = path;
    w->scenes = scenes;
    w->n = n;
    w->every = every > 0 ? every : 1;
    if (!path) return SW_EXIT_OK;
    w->seen = calloc(n ? n : 1, sizeof *w->seen);
    if (!w->seen) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    w->f = sw_cli_out_open(path);
    if (!w->f) {
        free(w->seen);
        w->seen = NULL;
        return SW_EXIT_IO;
    }
    fputs("t,package,phase,theta,theta_dot,u,u_dot,z,z_dot,margin,margin_bound,uplift_ratio,a_g,"
          "reserve_g\n",
          w->f);
    return SW_EXIT_OK;
}

void sw_cli_states_write(sw_cli_states_t *w, const sw_output_t *o)
{
    if (!w->f) return;
    if (o->pkg < w->n && w->seen[o->pkg]++ % w->every != 0) return;
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
    w->seen = NULL;
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
    if (!path) return SW_EXIT_OK;
    w->alpha = calloc(n ? n : 1, sizeof *w->alpha);
    w->row = calloc(n ? n : 1, sizeof *w->row);
    w->have = calloc(n ? n : 1, 1);
    if (!w->alpha || !w->row || !w->have) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    for (size_t i = 0; i < n; i++) {
        const sw_derived_t *d = sw_engine_derived(e, i);
        w->alpha[i] = d ? d->alpha : NAN;
    }
    if (!(w->f = sw_cli_out_open(path))) return SW_EXIT_IO;
    static const char *const cols[] = {"phase",        "theta",        "theta_dot",
                                       "ratio",        "margin",       "margin_bound",
                                       "uplift_ratio", "reserve_g"};
    fputs("t,a_g", w->f);
    for (size_t i = 0; i < n; i++) {
        long same = 0; /* earlier packages of the same name */
        for (size_t j = 0; j < i; j++) same += !strcmp(scenes[j].name, scenes[i].name);
        char name[96];
        if (same)
            snprintf(name, sizeof name, "%s#%ld", scenes[i].name, same + 1);
        else
            snprintf(name, sizeof name, "%s", scenes[i].name);
        for (size_t c = 0; c < sizeof cols / sizeof cols[0]; c++) {
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
    if (!w->open) return;
    w->open = 0;
    int first = -1, missing = 0;
    for (size_t i = 0; i < w->n; i++) {
        if (w->have[i] && first < 0) first = (int)i;
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
                fputs(",,,,,,,,", w->f);
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
        }
        fputc('\n', w->f);
        w->rows++;
        w->incomplete += missing > 0;
    }
    memset(w->have, 0, w->n);
}

void sw_cli_wide_write(sw_cli_wide_t *w, const sw_output_t *o)
{
    if (!w->f || o->pkg >= w->n) return;
    /* a new instant, or this package again: the row so far is complete */
    if (w->open) {
        size_t k = 0;
        while (k < w->n && !w->have[k]) k++;
        if (w->have[o->pkg] || (k < w->n && w->row[k].t != o->t)) wide_flush(w);
    }
    w->row[o->pkg] = *o;
    w->have[o->pkg] = 1;
    w->open = 1;
    if (o->pkg == w->n - 1) wide_flush(w);
}

int sw_cli_wide_close(sw_cli_wide_t *w)
{
    if (w->f) wide_flush(w);
    int rc = sw_cli_out_close(w->f, w->path);
    if (w->f && w->nonfinite)
        sw_cli_error("%s: %ld non-finite values written as empty fields", sw_cli_out_name(w->path),
                     w->nonfinite);
    if (w->f && w->incomplete)
        sw_cli_error("%s: %ld rows lack a package's state (empty fields)",
                     sw_cli_out_name(w->path), w->incomplete);
    free(w->alpha);
    free(w->row);
    free(w->have);
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
        if (!is_stdout(paths[i])) continue;
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

int sw_cli_events_open(sw_cli_events_t *w, const char *path, const sw_scene_t *scenes, size_t n)
{
    memset(w, 0, sizeof *w);
    w->path = path;
    w->scenes = scenes;
    w->n = n;
    if (!path) return SW_EXIT_OK;
    w->f = sw_cli_out_open(path);
    if (!w->f) return SW_EXIT_IO;
    fputs("t,package,event,theta,theta_dot,margin,info\n", w->f);
    return SW_EXIT_OK;
}

void sw_cli_events_span(sw_cli_events_t *w, size_t pkg, const sw_settle_span_t *span)
{
    if (!w->f || w->all_impacts) return; /* its impacts are rows of their own */
    fprintf(w->f, "%.9g,", span->t_start);
    sw_cli_csv_text(w->f, pkg_name(w->scenes, w->n, pkg));
    fprintf(w->f, ",settling,,%.9g,,%ld\n", span->max_speed, span->impacts);
    w->rows++;
}

int sw_cli_events_feed(sw_cli_events_t *w, sw_risk_t *risk, const sw_event_t *ev)
{
    sw_settle_span_t span;
    const int f = risk ? sw_risk_event(risk, ev, &span) : SW_SETTLE_REPORT;
    if (f < 0) return SW_SETTLE_REPORT; /* a package risk does not know: as it is */
    if (f & SW_SETTLE_CLOSED) sw_cli_events_span(w, ev->pkg, &span);
    if ((f & SW_SETTLE_REPORT) || w->all_impacts) sw_cli_events_write(w, ev);
    return w->all_impacts ? f | SW_SETTLE_REPORT : f;
}

void sw_cli_events_finish(sw_cli_events_t *w, sw_risk_t *risk, size_t n)
{
    sw_settle_span_t span;
    for (size_t k = 0; risk && k < n; k++)
        if (sw_risk_finish(risk, k, &span)) sw_cli_events_span(w, k, &span);
}

void sw_cli_events_write(sw_cli_events_t *w, const sw_event_t *ev)
{
    if (!w->f) return;
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

/* ---- summaries --------------------------------------------------------------- */

int sw_cli_any_overturned(const sw_engine_t *e)
{
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) == SW_OK && s.overturned) return 1;
    }
    return 0;
}

const char *sw_cli_verdict(const sw_summary_t *s)
{
    if (s->overturned) return "overturned";
    return s->faults ? "unreliable" : "upright";
}

int sw_cli_verdict_exit(const sw_engine_t *e, int fail_on_overturn)
{
    if (!fail_on_overturn) return SW_EXIT_OK;
    if (sw_cli_any_overturned(e)) return SW_EXIT_OVERTURNED;
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) == SW_OK && s.faults) {
            sw_cli_error("%s: the model faulted %ld times: no verdict, and --fail-on-overturn "
                         "needs one (exit 2)",
                         s.name, s.faults);
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

/* The facts of the log: what would expose a misread (duration, rate, peak,
 * gaps), and whether the verdict is incomplete or forced. */
static void print_facts(FILE *f, const sw_cli_run_t *run)
{
    const sw_gate_facts_t *F = &run->facts;
    const double t0 = F->t_first - F->t_origin, t1 = F->t_last - F->t_origin;
    const double share = run->samples_read
                             ? 100.0 * (double)run->samples_rejected / (double)run->samples_read
                             : 0.0;
    fprintf(f, "  rejected        %ld of %ld (%.2f %%)\n", run->samples_rejected,
            run->samples_read, share);
    if (F->t_origin != 0.0) {
        char iso[64];
        sw_cli_iso_seconds(iso, sizeof iso, F->t_origin);
        fprintf(f, "  starts          %s (the times below are from there)\n", iso);
    }
    fprintf(f, "  times           %.4f s to %.4f s (%.4f s of samples)\n", t0, t1, F->duration);
    if (isfinite(F->dt_median))
        fprintf(f, "  sample interval %.6g ms median (%.6g to %.6g ms): %.6g Hz\n",
                F->dt_median * 1e3, F->dt_min * 1e3, F->dt_max * 1e3, F->rate);
    fprintf(f, "  peak |a|        %.4g m/s^2 = %.4g g\n", F->peak_a, F->peak_a / 9.80665);
    if (F->gaps || F->restarts || F->clock_steps)
        fprintf(f,
                "  gaps            %ld (%.4g s in all, the longest %.4g s); restarts %ld, "
                "clock steps %ld\n",
                F->gaps, F->gap_total, F->gap_max, F->restarts, F->clock_steps);
    else
        fputs("  gaps            none\n", f);
    if (F->incomplete)
        fprintf(f,
                "  VERDICT INCOMPLETE: %ld gap%s or restart%s overlap rocking or an "
                "acceleration past the uplift threshold (first at %.4f s)\n",
                F->incomplete, F->incomplete == 1 ? "" : "s", F->incomplete == 1 ? "" : "s",
                F->first_incomplete - F->t_origin);
    if (run->forced)
        fprintf(f, "  VERDICT FORCED (--force): %s\n", run->check);
    else if (run->check[0])
        fprintf(f, "  warning         %s\n", run->check);
}

/* The outcome line's words: a faulted run never reads as a plain verdict. */
static void print_outcome(FILE *f, const sw_summary_t *s)
{
    if (s->overturned) {
        fputs("OVERTURNED at ", f);
        print_time(f, s->overturn_time, "an unknown time");
        if (s->faults) fprintf(f, " (the model faulted %ld times before: see --events)", s->faults);
    } else if (s->faults) {
        fprintf(f, "stayed upright (model faulted %ld times: not a verdict; see --events)",
                s->faults);
    } else {
        fputs("stayed upright", f);
    }
}

/* Impacts: the ones that matter, the settling apart. */
static void print_impacts(FILE *f, const sw_summary_t *s, const sw_risk_pkg_t *p)
{
    if (!p || !(p->impact_min > 0.0)) {
        fprintf(f, "\n  impacts         %ld\n", s->impacts);
        return;
    }
    fprintf(f, "\n  impacts         %ld that matter (before each, at least %.3g rad/s: a swing of 1 %% "
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

/* The reserve: the smallest evaluated, in g, and what it means. */
void sw_cli_print_reserve(FILE *f, const sw_risk_pkg_t *p)
{
    if (p && p->no_reserve) {
        fprintf(f, "  reserve         none: the scene is too stiff for it to be computed\n");
        return;
    }
    if (!p || !p->evaluations) return;
    if (!(p->min_reserve_g > 0.0))
        fprintf(f, "  minimum reserve 0 g at %.4f s: from then on it overturns with no further "
                   "input (at rest %.3g g)\n",
                p->min_reserve_time, p->rest_reserve_g);
    else
        fprintf(f, "  minimum reserve %.3g g at %.4f s: a %s half-sine of %.3g s that strong "
                   "would have overturned it then (at rest %.3g g)\n",
                p->min_reserve_g, p->min_reserve_time,
                p->min_direction == SW_RESERVE_ACCELERATING ? "speeding-up" : "braking",
                p->min_pulse, p->rest_reserve_g);
    if (p->reserve_faults)
        fprintf(f, "                  (%ld evaluations had a run fault: the value may be high)\n",
                p->reserve_faults);
}

/* The words a summary of an interrupted run starts with. */
static void print_interrupted(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run)
{
    if (!run->interrupted) return;
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
        fprintf(f, "log %s: %ld samples read, %ld accepted, %ld rejected", strcmp(run->log, "-") ? run->log : "(stdin)",
                run->samples_read, run->samples_read - run->samples_rejected,
                run->samples_rejected);
        if (run->settle > 0.0) fprintf(f, "; settle up to %g s after the end", run->settle);
        fputc('\n', f);
        if (run->have_facts) print_facts(f, run);
    }
    if (run->pulse) {
        const sw_pulse_t *p = run->pulse;
        fprintf(f, "pulse %s: amplitude %g m/s^2 (%.4g g), omega %g rad/s, %.6g s long; %.6g s "
                   "simulated\n",
                sw_pulse_shape_name(p->shape), p->amplitude, p->amplitude / 9.80665, p->omega,
                sw_pulse_duration(p), run->duration);
    }
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) != SW_OK) continue;
        double alpha = alpha_of(e, i);
        double dt = sw_engine_dt(e, i);
        fprintf(f, "\npackage %s: %s model, scheme %s, dt %.6g ms\n", s.name,
                sw_model_name(s.model), sw_engine_scheme(e), dt * 1e3);
        if (run->log)
            fprintf(f, "  samples         %ld read, %ld accepted, %ld rejected\n", run->samples_read,
                    run->samples_read - run->samples_rejected, run->samples_rejected);
        fputs("  first uplift    ", f);
        print_time(f, s.uplift_time, "none (never left the upright position)");
        if (s.uplifts > 1) fprintf(f, " (%ld uplifts in all)", s.uplifts);
        print_impacts(f, &s, sw_risk_pkg(run->risk, i));
        fprintf(f, "  peak |theta|    %.3f deg = %.3f alpha (alpha = %.2f deg)\n",
                s.max_abs_theta * 180.0 / M_PI, s.max_theta_ratio, alpha * 180.0 / M_PI);
        fputs("  tipped (alpha)  ", f);
        print_time(f, s.tip_time, "no (|theta| stayed below alpha)");
        print_margin(f, &s);
        sw_cli_print_reserve(f, sw_risk_pkg(run->risk, i));
        fputs("  outcome         ", f);
        print_outcome(f, &s);
        fputc('\n', f);
    }
}

void sw_cli_json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        switch (*p) {
        case '"': fputs("\\\"", f); break;
        case '\\': fputs("\\\\", f); break;
        case '\n': fputs("\\n", f); break;
        case '\r': fputs("\\r", f); break;
        case '\t': fputs("\\t", f); break;
        default:
            /* Other control characters escaped; bytes >= 0x80 pass as UTF-8. */
            if (*p < 0x20)
                fprintf(f, "\\u%04x", *p);
            else
                fputc(*p, f);
        }
    }
    fputc('"', f);
}

void sw_cli_json_num(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.9g", v);
    else
        fputs("null", f);
}

/* ", " and a line break (br) between the members of an object. */
static void json_sep(FILE *f, const char *br)
{
    fputc(',', f);
    fputs(br, f);
}

void sw_cli_json_facts(FILE *f, const sw_cli_run_t *run, const char *br)
{
    const sw_gate_facts_t *F = &run->facts;
    fprintf(f, "{\"rejected_share\": ");
    sw_cli_json_num(f, run->samples_read ? (double)run->samples_rejected /
                                               (double)run->samples_read
                                         : 0.0);
    fprintf(f, ", \"start\": ");
    sw_cli_json_num(f, F->t_first - F->t_origin);
    fprintf(f, ", \"end\": ");
    sw_cli_json_num(f, F->t_last - F->t_origin);
    fprintf(f, ", \"start_absolute\": ");
    if (F->t_origin != 0.0) {
        char iso[64];
        sw_cli_iso_seconds(iso, sizeof iso, F->t_origin);
        sw_cli_json_string(f, iso);
    } else {
        fputs("null", f);
    }
    json_sep(f, br);
    fprintf(f, "\"duration\": ");
    sw_cli_json_num(f, F->duration);
    fprintf(f, ", \"dt_median\": ");
    sw_cli_json_num(f, F->dt_median);
    fprintf(f, ", \"dt_min\": ");
    sw_cli_json_num(f, F->dt_min);
    fprintf(f, ", \"dt_max\": ");
    sw_cli_json_num(f, F->dt_max);
    fprintf(f, ", \"rate\": ");
    sw_cli_json_num(f, F->rate);
    json_sep(f, br);
    fprintf(f, "\"peak_accel\": ");
    sw_cli_json_num(f, F->peak_a);
    fprintf(f, ", \"peak_accel_g\": ");
    sw_cli_json_num(f, F->peak_a / 9.80665);
    fprintf(f, ", \"gaps\": %ld, \"gap_total\": ", F->gaps);
    sw_cli_json_num(f, F->gap_total);
    fprintf(f, ", \"gap_max\": ");
    sw_cli_json_num(f, F->gap_max);
    fprintf(f, ", \"restarts\": %ld, \"clock_steps\": %ld,", F->restarts, F->clock_steps);
    fputs(br, f);
    fprintf(f, "\"incomplete\": %s", F->incomplete ? "true" : "false");
    fprintf(f, ", \"forced\": %s, \"check\": ", run->forced ? "true" : "false");
    if (run->check[0])
        sw_cli_json_string(f, run->check);
    else
        fputs("null", f);
    fputc('}', f);
}

/* The reserve and the impacts that matter (null without them). */
static void json_risk(FILE *f, const sw_risk_pkg_t *p, const char *br)
{
    const int rv = p && p->evaluations > 0;
    json_sep(f, br);
    fprintf(f, "\"min_reserve_g\": ");
    sw_cli_json_num(f, rv ? p->min_reserve_g : NAN);
    fprintf(f, ", \"min_reserve_time\": ");
    sw_cli_json_num(f, rv ? p->min_reserve_time : NAN);
    fprintf(f, ", \"min_reserve_direction\": %s, \"min_reserve_pulse\": ",
            !rv || !p->min_direction            ? "null"
            : p->min_direction == SW_RESERVE_BRAKING ? "\"braking\""
                                                     : "\"accelerating\"");
    sw_cli_json_num(f, rv && p->min_pulse > 0.0 ? p->min_pulse : NAN);
    fprintf(f, ", \"rest_reserve_g\": ");
    sw_cli_json_num(f, p ? p->rest_reserve_g : NAN);
    fprintf(f, ", \"reserve_evaluations\": %ld", p ? p->evaluations : 0L);
    fprintf(f, ", \"no_reserve\": ");
    if (p && p->no_reserve)
        sw_cli_json_string(f, p->no_reserve);
    else
        fputs("null", f);
    json_sep(f, br);
    if (p && p->impact_min > 0.0)
        fprintf(f, "\"significant_impacts\": %ld, \"micro_impacts\": %ld, \"settling_spans\": %ld",
                p->impacts, p->micro_impacts, p->settling_spans);
    else
        fputs("\"significant_impacts\": null, \"micro_impacts\": null, \"settling_spans\": null",
              f);
}

int sw_cli_json_package(FILE *f, const sw_engine_t *e, size_t i, const sw_cli_run_t *run,
                        const char *br)
{
    sw_summary_t s;
    if (sw_engine_summary(e, i, &s) != SW_OK) return -1;
    fprintf(f, "\"name\": ");
    sw_cli_json_string(f, s.name);
    fprintf(f, ", \"model\": ");
    sw_cli_json_string(f, sw_model_name(s.model));
    fprintf(f, ", \"overturned\": %s, \"verdict\": \"%s\"", s.overturned ? "true" : "false",
            sw_cli_verdict(&s));
    json_sep(f, br);
    fprintf(f, "\"overturn_time\": ");
    sw_cli_json_num(f, s.overturn_time);
    fprintf(f, ", \"tip_time\": ");
    sw_cli_json_num(f, s.tip_time);
    fprintf(f, ", \"uplift_time\": ");
    sw_cli_json_num(f, s.uplift_time);
    json_sep(f, br);
    fprintf(f, "\"max_abs_theta\": ");
    sw_cli_json_num(f, s.max_abs_theta);
    fprintf(f, ", \"max_theta_ratio\": ");
    sw_cli_json_num(f, s.max_theta_ratio);
    fprintf(f, ", \"alpha\": ");
    sw_cli_json_num(f, alpha_of(e, i));
    json_sep(f, br);
    fprintf(f, "\"min_margin\": ");
    sw_cli_json_num(f, s.min_margin);
    fprintf(f, ", \"min_margin_bound\": ");
    sw_cli_json_num(f, s.min_margin_bound);
    fprintf(f, ", \"max_uplift_ratio\": ");
    sw_cli_json_num(f, s.max_uplift_ratio);
    json_sep(f, br);
    fprintf(f, "\"impacts\": %ld, \"uplifts\": %ld, \"rests\": %ld, \"faults\": %ld", s.impacts,
            s.uplifts, s.rests, s.faults);
    json_risk(f, sw_risk_pkg(run->risk, i), br);
    json_sep(f, br);
    fprintf(f, "\"samples_read\": %ld, \"samples_rejected\": %ld", run->samples_read,
            run->samples_rejected);
    json_sep(f, br);
    fprintf(f, "\"scheme\": ");
    sw_cli_json_string(f, sw_engine_scheme(e));
    fprintf(f, ", \"dt\": ");
    sw_cli_json_num(f, sw_engine_dt(e, i));
    fprintf(f, ", \"steps\": %ld", s.steps);
    return 0;
}

void sw_cli_print_json(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run)
{
    fprintf(f, "{\n  \"swaywatch\": ");
    sw_cli_json_string(f, sw_version());
    fprintf(f, ",\n  \"log\": ");
    if (run->log)
        sw_cli_json_string(f, run->log);
    else
        fputs("null", f);
    if (run->pulse) {
        fprintf(f, ",\n  \"pulse\": {\"shape\": ");
        sw_cli_json_string(f, sw_pulse_shape_name(run->pulse->shape));
        fprintf(f, ", \"amplitude\": ");
        sw_cli_json_num(f, run->pulse->amplitude);
        fprintf(f, ", \"omega\": ");
        sw_cli_json_num(f, run->pulse->omega);
        fprintf(f, ", \"duration\": ");
        sw_cli_json_num(f, sw_pulse_duration(run->pulse));
        fprintf(f, "},\n  \"simulated\": ");
        sw_cli_json_num(f, run->duration);
    }
    if (run->log) {
        fprintf(f, ",\n  \"settle\": ");
        sw_cli_json_num(f, run->settle);
    }
    fprintf(f, ",\n  \"interrupted\": ");
    if (run->interrupted)
        fprintf(f, "{\"signal\": \"%s\", \"t\": ",
                run->interrupted == SIGINT ? "SIGINT" : "SIGTERM");
    if (run->interrupted) {
        sw_cli_json_num(f, sw_engine_time(e));
        fputc('}', f);
    } else {
        fputs("null", f);
    }
    fprintf(f, ",\n  \"samples_read\": %ld,\n  \"samples_rejected\": %ld", run->samples_read,
            run->samples_rejected);
    if (run->have_facts) {
        fprintf(f, ",\n  \"input\": ");
        sw_cli_json_facts(f, run, "\n    ");
    }
    fprintf(f, ",\n  \"packages\": [");
    const char *sep = "\n    {";
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) != SW_OK) continue;
        fputs(sep, f);
        sw_cli_json_package(f, e, i, run, "\n     ");
        fputc('}', f);
        sep = ",\n    {";
    }
    fprintf(f, "\n  ]\n}\n");
}
