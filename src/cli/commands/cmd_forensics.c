/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cmd_forensics.c - "swaywatch forensics": after an incident, what a
 * recorded log did to each package, how close it came, and what would
 * have saved it.
 *
 * The log is read exactly as replay reads it (source.h: CSV or an
 * lcm-logger file told by its first bytes, the input gate, the
 * plausibility check, the settling), through one engine for every
 * --scene; what the gate handed the engine is kept in memory as it goes
 * (a take callback), because the searches replay it many times and
 * reading and parsing the file for each trial would cost more than the
 * physics.  Then, for every package:
 *   - the safety factor: the scales of the recorded longitudinal
 *     acceleration that still leave it upright and that overturn it, a
 *     bracket (sweep.h; overturning is not monotonic, so a survived log is
 *     also searched below 1 for a weaker shock of the same shape that
 *     would have overturned it);
 *   - a what-if table: the same log with the package alone on the bed, on
 *     the typical supports of a catalogue (or the user's), in other sizes,
 *     each with its outcome and safety factor (whatif.c).
 * Every search of every package runs at once on --threads threads, in
 * rounds whose results do not depend on the number of threads.
 *
 * The answer comes first, the method after (the replay summary and how
 * the factor was searched); -q keeps the answer alone.  --json says the
 * same for machines, --report writes it as one self-contained HTML page
 * (report.c), --plot the figure replay draws (figure.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "clobber.h"
#include "cost.h"
#include "figure.h"
#include "forensics.h"
#include "interrupt.h"
#include "plot.h"
#include "source.h"

static int check_size(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    double h, w, d;
    if (sw_cli_parse_size(arg, &h, &w, &d) == 0)
        return SW_EXIT_OK;
    sw_cli_error(
        "--%s: expected HEIGHTxWIDTH or HEIGHTxWIDTHxDEPTH in m, e.g. 2.4x0.8 or 2.4x0.8x0.6, "
        "got '%s'",
        o->long_name, arg);
    return SW_EXIT_USAGE;
}

static int check_report(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    const char *dot = strrchr(arg, '.');
    if (dot && (!strcmp(dot, ".html") || !strcmp(dot, ".htm")))
        return SW_EXIT_OK;
    sw_cli_error("--%s: '%s': the file name must end in .html", o->long_name, arg);
    return SW_EXIT_USAGE;
}

#define FO(f) SW_CLI_AT(sw_cli_forensics_opts_t, f)

static const sw_cli_option_t forensics_options[] = {
    {SW_CLI_SECTION, .help = "Run:"},
    {SW_CLI_DOUBLE, 0, "settle", "SECONDS", FO(settle), .rule = SW_NUM_NONNEGATIVE, .def = 30,
     .hi = 1e5, .what = "a number of seconds >= 0",
     .help = "after the log, zero acceleration for up to this long or until the outcome is "
             "certain (default %g; 0: none); at most a day: an undamped frame never rests"},
    {SW_CLI_FLAG, 0, "fail-on-overturn", FO(fail_on_overturn), .value = 1,
     .help = "exit 1 if a package as given overturned, or if the verdict is incomplete (a gap "
             "or restart over motion may hide an overturn)"},
    {SW_CLI_LONG, 0, "max-samples", "N", FO(max_samples), .min = 1, .max = 1L << 28,
     .def = SW_CLI_LOG_MAX_SAMPLES, .what = "a whole number of samples >= 1",
     .help =
         "hold at most N samples of the log in memory (24 bytes each, 32 with a lateral "
         "column; default " SW_CLI_STR(
             SW_CLI_LOG_MAX_SAMPLES_N) ", 9.3 h at 1 kHz; at most 268435456); a longer log, or an "
                                       "endless pipe, is refused with exit 2 instead of filling "
                                       "the "
                                       "memory"},
    {SW_CLI_SECTION,
     .help = "Safety factor (scale of the whole longitudinal acceleration, and of the lateral "
             "one with it for a package with a depth):"},
    {SW_CLI_DOUBLE, 0, "step", "X", FO(so.step), .rule = SW_NUM_POSITIVE, .lo = 1e-4, .hi = 1,
     .what = "a positive relative step",
     .help = "relative scan step (default 0.02); smaller steps take tens of thousands of "
             "replays of the log"},
    {SW_CLI_DOUBLE, 0, "tol", "X", FO(so.tol), .rule = SW_NUM_POSITIVE, .lo = 1e-9, .hi = 0.5,
     .what = "a positive relative tolerance",
     .help = "relative width of the final bracket (default 0.001); finer than 1e-9 is below "
             "what the model resolves"},
    {SW_CLI_DOUBLE, 0, "max-factor", "X", FO(so.x_max), .rule = SW_NUM_POSITIVE, .lo = 1, .hi = 1e4,
     .what = "a positive scale factor",
     .help = "largest scale tried (default: 20 times the scale at which the log's peak lifts a "
             "package on the bed)"},
    {SW_CLI_SECTION,
     .help = "What if (without these, typical supports from a catalogue; frequencies as 2Hz, "
             "or rad/s):"},
    {SW_CLI_STRING, 0, "frame-mass", "KG", FO(w.frame_mass),
     .help = "frame mass m_b (default: the scene's, else m/4)"},
    {SW_CLI_CALL, 0, "frame-omega", "F", FO(w.frame_omega), .fn = sw_cli_opt_frequency,
     .help = "a frame on bearings of this natural frequency (2Hz, or 12.6 rad/s) instead of "
             "the catalogue's frames"},
    {SW_CLI_STRING, 0, "frame-zeta", "Z", FO(w.frame_zeta),
     .help = "bearing damping ratio (default: the scene's, else " SW_CLI_STR(SW_WHATIF_ZETA) ")"},
    {SW_CLI_CALL, 0, "cushion-omega", "F", FO(w.cushion_omega), .fn = sw_cli_opt_frequency,
     .help = "a cushion of this natural frequency (8Hz, or 50 rad/s), on the frame if the "
             "scene has one, instead of the catalogue's cushions"},
    {SW_CLI_STRING, 0, "cushion-zeta", "Z", FO(w.cushion_zeta),
     .help = "cushion damping ratio (default: the scene's, else " SW_CLI_STR(SW_WHATIF_ZETA) ")"},
    {SW_CLI_LIST, 0, "size", "HxW[xD]", FO(w.sizes), .fn = check_size,
     .help = "the package with height H, width W along the truck and depth D across it (m; "
             "without D, the scene's depth), on the scene's support; repeatable"},
    {SW_CLI_FLAG, 0, "no-what-if", FO(w.no_what_if), .value = 1,
     .help = "only the replay and the safety factor"},
    {SW_CLI_LONG, 0, "reserve-evals", "N", FO(w.reserve_evals), .min = 0, .max = 1L << 30,
     .def = SW_WHATIF_RESERVE_EVALS, .what = "a whole number >= 0",
     .help = "a what-if case's smallest reserve: at most N evaluations, the most threatened "
             "moments first (default %g; 0: no limit); a case that needs more shows a bracket"},
    {.kind = SW_CLI_END},
};

/* The searches' threads: not in a batch, which runs its logs on its own
 * threads (each log's searches then run on the thread of its job). */
static const sw_cli_option_t forensics_thread_options[] = {
    {SW_CLI_SECTION, .help = "Run:"},
    {SW_CLI_LONG, 0, "threads", "N", FO(threads), .flags = SW_CLI_CAP, .min = 1, .max = 256,
     .def = 2, .what = "a whole number of threads >= 1",
     .help = "searches run on N threads (default %g); the results are the same for any N"},
    {.kind = SW_CLI_END},
};

/* forensics' files, in the Output section with the shared rows. */
static const sw_cli_option_t forensics_output_options[] = {
    {SW_CLI_SECTION, .help = "Output:"},
    {SW_CLI_STRING, 0, "report", "FILE.html", FO(report), .fn = check_report,
     .help = "the whole report as one self-contained HTML page to hand over: the log's facts "
             "and times in UTC, what of it was not used, the figure and a close-up of each "
             "decisive moment, events, safety factors, what-if tables, the model's limits, "
             "and the fingerprint (SHA-256 of the log and scenes, version and commit, "
             "command)"},
    {SW_CLI_STRING, 0, "plot", "FILE.png|.svg", FO(plot), .fn = sw_cli_plot_check,
     .help = "a_g(t), theta(t)/alpha and margin(t) with the events"},
    {SW_CLI_TEXT,
     .help = "\nWith --json the whole report is one JSON object on stdout (docs/forensics.md):\n"
             "'build' (version and commit), 'command_line', 'log' (its facts, SHA-256, UTC\n"
             "start and end, what was not used), 'scenes' (their SHA-256), 'replay' (replay's\n"
             "JSON summary) and 'packages', each with its 'utc' times, 'safety_factor' and\n"
             "'what_if'.  With --out - or --events - (which need -q) the answer goes to\n"
             "standard error.  A progress line goes to standard error when it is a terminal\n"
             "(not with -q)."},
    {.kind = SW_CLI_END},
};

static const sw_cli_command_t forensics_cmd = {
    .name = "forensics",
    .usage = "forensics LOG --scene S.ini [--scene T.ini ...] [options]",
    .about =
        "After an incident: replays the log LOG (a CSV file, '-' for standard input, or an\n"
        "lcm-logger file, read exactly as replay reads it) through every package and says,\n"
        "for each:\n"
        "  - whether it overturned and how close it came;\n"
        "  - its safety factor: the scales of the recorded longitudinal acceleration that\n"
        "    still leave it upright and that overturn it, as a bracket [upright, overturns]\n"
        "    (with a lateral column and a package with a depth, both axes scaled together,\n"
        "    and the plane that gives out first named);\n"
        "  - what would have saved it: the same log with the package on the bed, on typical\n"
        "    frames and cushions (a catalogue; or --frame-omega, --cushion-omega) and in other\n"
        "    sizes (--size), each with its outcome, peak and safety factor.\n"
        "The log is held in memory (24 bytes a sample, at most --max-samples): the searches\n"
        "replay it many times for every case.\n",
    .exits = SW_CLI_EXIT_OVERTURN | SW_CLI_EXIT_STRICT | SW_CLI_EXIT_INCOMPLETE,
};

/* ---- the replay -------------------------------------------------------------------- */

static void on_state(void *user, const sw_output_t *out)
{
    sw_cli_forensics_t *F = user;
    sw_cli_states_write(&F->states, out); /* the stream evaluated the reserve first */
    sw_cli_figure_state(F->fig, out);
}

static void on_event(void *user, const sw_event_t *ev)
{
    sw_cli_forensics_t *F = user;
    if (sw_cli_events_feed(&F->events, F->R.risk, ev) & SW_SETTLE_REPORT) {
        sw_cli_figure_event(F->fig, ev);
        sw_cli_forensics_event(F, ev);
    }
}

static void on_take(void *user, double t, double a_g, double a_z, int restart)
{
    sw_cli_forensics_t *F = user;
    if (sw_forensics_push(F->fx, t, a_g, a_z, restart) != SW_OK)
        F->halt = 1; /* the log is held whole or not at all: the reading may stop */
}

/* The same with the lateral acceleration: the lateral planes are searched
 * on it too (the log read with a lateral plane). */
static void on_take_lat(void *user, double t, double a_g, double a_y, double a_z, int restart)
{
    sw_cli_forensics_t *F = user;
    if (sw_forensics_push_lat(F->fx, t, a_g, a_y, a_z, restart) != SW_OK)
        F->halt = 1;
}

/* Open LOG as replay does; refuse what its source does not take and
 * outputs that would overwrite an input. */
static int open_log(sw_cli_forensics_t *F)
{
    int rc;
    const sw_cli_file_t outputs[] = {{"--out", F->o.out_path},
                                     {"--events", F->o.events_path},
                                     {"--plot", F->fo.plot},
                                     {"--report", F->fo.report}};
    const char *const names[] = {"--out", "--events"};
    const char *const paths[] = {F->o.out_path, F->o.events_path};
    if ((rc = sw_cli_reader_open(&F->R, F->log, &F->in, F->o.quiet, F->given)) != SW_EXIT_OK ||
        (rc = sw_cli_check_run_files(F->log, &F->o.scenes, outputs, 4)) != SW_EXIT_OK ||
        (rc = sw_cli_check_outputs(F->o.out_path, F->o.events_path, NULL, F->o.json, F->o.quiet)) !=
            SW_EXIT_OK ||
        (rc = sw_cli_check_stdout(names, paths, 2, F->o.json, F->o.quiet)) != SW_EXIT_OK)
        return rc;
    return sw_cli_reader_prepare(&F->R);
}

/* The scenes (unless a batch's options hold them already) and the engine
 * options they and --accuracy give. */
static int load(sw_cli_forensics_t *F)
{
    int rc;
    if (F->scenes)
        return SW_EXIT_OK;
    if ((rc = sw_cli_load_scenes(&F->o, &F->scenes, &F->n)) != SW_EXIT_OK)
        return rc;
    sw_cli_engine_opts(&F->o, &F->eo);
    F->eo.check_default = 1; /* a chosen scheme or dt: its verdict checked (summary.c) */
    return sw_cli_resolve_accuracy(&F->o, F->scenes, F->n, &F->eo);
}

/* ---- the library's forensics: its progress line, the object ------------------------ */

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The progress line: on a terminal only, at most five times a second. */
static void progress(void *user, const sw_safety_progress_t *p)
{
    sw_cli_forensics_t *F = user;
    const double t = now_s();
    if (t - F->progress_at < 0.2 && p->cases_done < p->cases)
        return;
    F->progress_at = t;
    fprintf(stderr, "\rswaywatch: forensics: searching: %zu of %zu cases done, %ld runs, %.0f s ",
            p->cases_done, p->cases, p->trials, t - F->started);
    F->progress_shown = 1;
}

/* The library's forensics for the scenes: their what-if cases, and the
 * log held as the engine gets it, for the searches. */
static int make_forensics(sw_cli_forensics_t *F)
{
    sw_forensics_opts_t fo;
    double *sizes = sw_cli_whatif_opts(&F->fo.w, &fo.whatif);
    if (!sizes) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    memset(&fo.run, 0, sizeof fo.run);
    fo.run.engine = F->eo; /* the replay's integration options, --accuracy included */
    fo.run.settle = F->fo.settle > 0.0 ? F->fo.settle : -1.0; /* negative: no free motion */
    fo.search = F->fo.so;
    fo.threads = (int)F->fo.threads;
    fo.max_samples = (size_t)F->fo.max_samples;
    fo.reserve_rate = F->o.reserve_rate;
    fo.reserve_evals = F->fo.w.reserve_evals;
    fo.progress = !F->o.quiet && isatty(STDERR_FILENO) ? progress : NULL;
    fo.user = F;
    F->fx = sw_forensics_create(F->scenes, F->n, &fo, NULL);
    free(sizes);
    if (!F->fx) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    return SW_EXIT_OK;
}

/* 1. The replay, exactly as replay runs it, keeping what the engine got. */
static int replay_log(sw_cli_forensics_t *F)
{
    int rc;
    if ((rc = load(F)) != SW_EXIT_OK)
        return rc;
    sw_engine_opts_t eo = F->eo;
    eo.on_event = on_event;
    eo.on_state = on_state;
    eo.user = F;
    if ((rc = make_forensics(F)) != SW_EXIT_OK)
        return rc;
    F->R.take = on_take;
    F->R.take_lat = on_take_lat;
    F->R.lateral = 1; /* a CSV log's lateral column drives the scenes with a depth */
    F->R.halt = &F->halt;
    F->R.reserve_rate = F->o.reserve_rate;
    /* the reserve of each state only where the figures or --out show it;
     * the minimum is the same either way (risk.h) */
    F->R.reserve_min_only = !F->o.out_path && !F->fo.plot && !F->fo.report;
    if ((rc = sw_cli_reader_engine(&F->R, F->scenes, F->n, &eo, F->scenes_shared)) != SW_EXIT_OK)
        return rc;
    sw_engine_t *e = F->R.e;
    if (F->o.verbose)
        sw_cli_print_derived(stderr, e, F->scenes, F->n);
    if ((rc = sw_cli_states_open(&F->states, F->o.out_path, F->o.every, NULL, F->scenes, F->n)) !=
            SW_EXIT_OK ||
        (rc = sw_cli_events_open(&F->events, F->o.events_path, NULL, F->scenes, F->n)) !=
            SW_EXIT_OK)
        return rc;
    if ((F->fo.plot || F->fo.report) && !(F->fig = sw_cli_figure_create(e, F->scenes, F->n)))
        return SW_EXIT_IO;
    if ((rc = sw_cli_reader_risk(&F->R, &F->o, F->scenes, F->n)) != SW_EXIT_OK)
        return rc;
    if (F->o.reserve_rate > 0.0) {
        sw_cli_figure_risk(F->fig, F->R.risk);
        sw_cli_figure_stream(F->fig, F->R.st); /* the lateral planes' */
    }
    F->states.risk = F->R.risk; /* after open, which clears the writer */
    F->events.all_impacts = F->o.all_impacts;
    if ((rc = sw_cli_forensics_begin(F)) != SW_EXIT_OK)
        return rc;
    if ((rc = sw_cli_reader_feed(&F->R)) != SW_EXIT_OK)
        return rc;
    const int held = sw_forensics_status(F->fx);
    if (held == SW_ENOMEM) {
        sw_cli_error("%s: out of memory holding the log (%zu samples)", F->R.lf.name,
                     sw_forensics_log(F->fx)->n);
        return SW_EXIT_IO;
    }
    if (held == SW_ETOOBIG) {
        sw_cli_error(
            "%s: more than %ld samples: %ld is the cap (--max-samples) of the log held "
            "in memory; give a larger --max-samples, or cut the log to the incident",
            F->R.lf.name, F->fo.max_samples, F->fo.max_samples);
        return SW_EXIT_USAGE;
    }
    sw_cli_reader_settle(&F->R, F->fo.settle);
    sw_cli_risk_resolve(F->R.risk, F->scenes, F->n);
    for (size_t k = 0; F->R.st && k < F->n; k++) { /* the lateral planes' reserves too */
        const int rl = sw_stream_risk_resolve(F->R.st, k, SW_PLANE_LAT);
        if (rl < 0)
            sw_cli_error("%s: the smallest reserve across the truck could not be found: %s",
                         F->scenes[k].name, sw_strerror(rl));
    }
    sw_cli_events_finish(&F->events, F->R.risk, F->n);
    sw_cli_forensics_end(F);
    rc = sw_cli_states_close(&F->states);
    int rc2 = sw_cli_events_close(&F->events);
    if (rc == SW_EXIT_OK)
        rc = rc2;
    if ((rc2 = sw_cli_reader_report(&F->R)) != SW_EXIT_OK)
        return rc2;
    sw_cli_run_t *run = &F->R.run;
    run->log = F->log;
    run->settle = F->fo.settle;
    run->interrupted = sw_cli_signal;
    /* the spans without samples, shaded in the figure */
    for (size_t i = 0; F->fig && i < run->unused.ngap; i++) {
        const sw_cli_unused_gap_t *g = &run->unused.gap[i];
        if (g->kind == SW_GATE_EV_GAP)
            sw_cli_figure_gap(F->fig, g->t_engine - g->span, g->t_engine);
    }
    return rc;
}

/* ---- 2. the searches --------------------------------------------------------------- */

/* The searches on the held log. */
static int run_cases(sw_cli_forensics_t *F)
{
    const int show = !F->o.quiet && isatty(STDERR_FILENO);
    F->started = now_s();
    /* The search cannot stop between trials and writes nothing: a signal
     * ends the process at once. */
    if (!F->scenes_shared) /* a batch's jobs run on many threads: the batch handles signals */
        sw_cli_interrupt_now(
            "forensics: interrupted during the safety-factor search; --out and "
            "--events are complete, no report");
    int rc = sw_forensics_safety(F->fx);
    if (rc == SW_OK && F->R.risk && F->o.reserve_rate > 0.0) {
        if (show)
            fprintf(stderr,
                    "\rswaywatch: forensics: the smallest reserve of each what-if case, "
                    "%.0f s \033[K",
                    now_s() - F->started);
        F->progress_shown |= show;
        rc = sw_forensics_reserve(F->fx, F->R.risk);
    }
    if (!F->scenes_shared)
        sw_cli_interrupt_now(NULL);
    F->search_s = now_s() - F->started;
    if (F->progress_shown)
        fprintf(stderr, "\r\033[K");
    if (rc == SW_ENOMEM) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    F->cases = sw_forensics_cases(F->fx, &F->ncases);
    sw_cli_whatif_name_options(F->cases, F->ncases);
    for (size_t i = 0; i < F->ncases; i++)
        if (F->cases[i].is_scene && !F->cases[i].available) {
            sw_cli_error("forensics: %s: safety factor: %s", F->scenes[F->cases[i].pkg].name,
                         F->cases[i].note);
            return SW_EXIT_USAGE;
        }
    return SW_EXIT_OK;
}

/* ---- the command ------------------------------------------------------------------- */

/* Interrupted during the replay: its summary alone, marked so. */
static int report_interrupted(const sw_cli_forensics_t *F)
{
    const sw_cli_run_t *run = &F->R.run;
    if (F->o.json)
        sw_cli_print_json(stdout, F->R.e, run);
    else if (!F->o.quiet)
        sw_cli_print_summary(stdout, F->R.e, run);
    sw_cli_error(
        "forensics: interrupted by %s after %ld samples of the replay; the output "
        "files end with the last whole row; no safety factor or what-if",
        sw_cli_signal_name(sw_cli_signal), run->samples_read);
    return sw_cli_interrupt_code();
}

/* The replay and the run at scale 1 of the search agree on every outcome;
 * if not, say so (the shock is at the edge of what the model resolves). */
static void check_agree(const sw_cli_forensics_t *F)
{
    for (size_t i = 0; i < F->ncases; i++) {
        const sw_whatif_case_t *C = &F->cases[i];
        sw_summary_t sum;
        if (!C->is_scene || sw_engine_summary(F->R.e, C->pkg, &sum) != SW_OK)
            continue;
        if (sum.overturned != C->sf.overturned)
            sw_cli_error(
                "forensics: %s: the replay and the safety-factor run disagree on the "
                "outcome (overturned %s / %s): the shock is at the edge of the model's "
                "resolution",
                F->scenes[C->pkg].name, sum.overturned ? "yes" : "no",
                C->sf.overturned ? "yes" : "no");
    }
}

/* Everything a run opened and made; the options stay (the scenes, unless
 * a batch's options hold them). */
static void cleanup(sw_cli_forensics_t *F)
{
    sw_cli_states_close(&F->states);
    sw_cli_events_close(&F->events);
    sw_cli_forensics_free(F);
    sw_cli_reader_close(&F->R);
    sw_forensics_destroy(F->fx);
    F->fx = NULL;
    F->cases = NULL;
    F->ncases = 0;
    sw_cli_figure_destroy(F->fig);
    F->fig = NULL;
    if (!F->scenes_shared) {
        free(F->scenes);
        F->scenes = NULL;
    }
    F->halt = 0;
}

static int check_options(const sw_cli_forensics_t *F)
{
    if (F->fo.so.x_max > 0.0 && F->fo.so.x_max <= 1.0) {
        sw_cli_error("--max-factor: expected a factor above 1, got %g", F->fo.so.x_max);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

static size_t groups(sw_cli_forensics_t *F, sw_cli_group_t *g, int batch)
{
    size_t n = 0;
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_csv_options, &F->in.copts);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_sample_options, &F->in.copts);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(forensics_options, &F->fo);
    n += sw_cli_source_groups(&F->in, g + n, 0); /* lcm-logger files' */
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_gate_options, &F->in.gate);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_scene_options, &F->o);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_integration_options, &F->o);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_accuracy_options, &F->o);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_reserve_options, &F->o);
    if (batch)
        return n;
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(forensics_thread_options, &F->fo);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_output_options, &F->o);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(forensics_output_options, &F->fo);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP_IN(sw_cli_common_options, &F->o, "Output:");
    return n;
}

int cmd_forensics(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    sw_cli_forensics_t *F = calloc(1, sizeof *F);
    if (!F) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    sw_cli_read_opts_init(&F->in);
    /* the command as given, for the report: the parser reorders argv */
    F->argc = argc;
    F->argv = malloc(((size_t)argc + 1) * sizeof *F->argv);
    if (!F->argv) {
        free(F);
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    memcpy(F->argv, argv, ((size_t)argc + 1) * sizeof *argv);
    sw_cli_group_t g[16];
    const size_t ng = groups(F, g, 0);

    int first;
    if ((rc = sw_cli_parse(&forensics_cmd, g, ng, argc, argv, &first)) != SW_CLI_CONTINUE)
        goto out;
    if ((rc = sw_cli_interrupt_install()) != SW_EXIT_OK)
        goto out;
    rc = SW_EXIT_USAGE;
    if (!(F->log = sw_cli_log_operand("forensics", argc, argv, first)))
        goto out;
    if (check_options(F) != SW_EXIT_OK)
        goto out;
    F->given = sw_cli_source_given(g, ng);
    if ((rc = open_log(F)) != SW_EXIT_OK)
        goto out;
    sw_cli_forensics_digest_start(F);
    if ((rc = replay_log(F)) != SW_EXIT_OK)
        goto out;
    if (sw_cli_signal) {
        rc = report_interrupted(F);
        goto out;
    }
    if ((rc = run_cases(F)) != SW_EXIT_OK || (rc = sw_cli_forensics_fingerprint(F)) != SW_EXIT_OK)
        goto out;
    check_agree(F);
    /* --out - / --events -: standard output carries that file. */
    FILE *ans = F->o.out_path && !strcmp(F->o.out_path, "-")         ? stderr
                : F->o.events_path && !strcmp(F->o.events_path, "-") ? stderr
                                                                     : stdout;
    if (F->o.json && (rc = sw_cli_forensics_json(ans, F)) != SW_EXIT_OK)
        goto out;
    if (!F->o.json)
        sw_cli_forensics_text(ans, F);
    if (fflush(ans) != 0 || ferror(ans)) {
        sw_cli_error("standard output: write error");
        rc = SW_EXIT_IO;
        goto out;
    }
    if (F->fo.plot) {
        char title[512]; /* LOG: the packages */
        int k =
            snprintf(title, sizeof title, "%s:", strcmp(F->log, "-") ? F->log : "(standard input)");
        for (size_t i = 0; i < F->n && k > 0 && (size_t)k < sizeof title; i++)
            k += snprintf(title + k, sizeof title - (size_t)k, "%s %s", i ? "," : "",
                          F->scenes[i].name);
        if ((rc = sw_cli_figure_draw(F->fig, F->fo.plot, title)) != SW_EXIT_OK)
            goto out;
    }
    if (F->fo.report && (rc = sw_cli_forensics_report(F, F->fo.report)) != SW_EXIT_OK)
        goto out;
    rc = sw_cli_verdict_exit(F->R.e, &F->R.run, F->fo.fail_on_overturn);
    if (sw_cli_signal) { /* while the report or the figure was written: both are whole */
        sw_cli_error("forensics: interrupted by %s after the report",
                     sw_cli_signal_name(sw_cli_signal));
        rc = sw_cli_interrupt_code();
    }
out:
    cleanup(F);
    sw_cli_parse_free(g, ng);
    free(F->argv);
    free(F);
    return rc;
}

/* ---- the forensics of one log, for batch (forensics.h) ----------------------------- */

sw_cli_forensics_t *sw_cli_forensics_new(void)
{
    sw_cli_forensics_t *F = calloc(1, sizeof *F);
    if (!F) {
        sw_cli_error("out of memory");
        return NULL;
    }
    sw_cli_read_opts_init(&F->in);
    return F;
}

void sw_cli_forensics_destroy(sw_cli_forensics_t *F)
{
    if (!F)
        return;
    sw_cli_group_t g[16];
    sw_cli_parse_free(g, groups(F, g, 1));
    cleanup(F);
    free(F->scenes);
    free(F);
}

size_t sw_cli_forensics_groups(sw_cli_forensics_t *F, sw_cli_group_t *g)
{
    return groups(F, g, 1);
}

int sw_cli_forensics_ready(sw_cli_forensics_t *F, const sw_cli_group_t *g, size_t ng)
{
    int rc;
    F->given = sw_cli_source_given(g, ng);
    if ((rc = check_options(F)) != SW_EXIT_OK || (rc = load(F)) != SW_EXIT_OK)
        return rc;
    sw_cli_warn_scene_cost(F->scenes, F->n, &F->eo);
    F->scenes_shared = 1; /* the copies made for each log share them */
    return SW_EXIT_OK;
}

int sw_cli_forensics_log(const sw_cli_forensics_t *opts, const char *log,
                         sw_cli_forensics_report_fn report, void *user)
{
    sw_cli_forensics_t *F = malloc(sizeof *F);
    if (!F) {
        sw_cli_error("%s: out of memory", log);
        return SW_EXIT_IO;
    }
    *F = *opts; /* the options; a ready one has run nothing, so no state is copied */
    F->log = log;
    F->o.quiet = 1;
    F->o.json = 0;
    int rc;
    if ((rc = open_log(F)) == SW_EXIT_OK && (rc = replay_log(F)) == SW_EXIT_OK &&
        (rc = run_cases(F)) == SW_EXIT_OK) {
        check_agree(F);
        report(user, F);
        rc = sw_cli_verdict_exit(F->R.e, &F->R.run, F->fo.fail_on_overturn);
    }
    cleanup(F);
    free(F);
    return rc;
}
