/* cmd_forensics.c - "swaywatch forensics": after an incident, what a
 * recorded log did to a package, how much margin was left, and what would
 * have saved it.
 *
 * The report is what replay prints, plus
 *   - the safety factor: the smallest factor by which the recorded
 *     longitudinal acceleration would have to be scaled to overturn the
 *     package (sweep.h: scan the scale upward, then bisect; overturning is
 *     not monotonic, so a survived log is also searched below 1 for a
 *     weaker shock of the same shape that would have overturned it);
 *   - a what-if table: the same log with the package on the bed, on a
 *     frame, on a cushion, and in other sizes, each with its outcome and
 *     safety factor;
 *   - optionally a figure of a_g(t), theta(t)/alpha and margin(t) with the
 *     events, and the whole report as JSON.
 *
 * Unlike replay, forensics holds the whole log in memory (input.c): the
 * safety-factor search replays it tens of times per case, and re-reading
 * and re-parsing the file for each trial would cost more than the physics.
 * The figure is figure.c's, as replay draws it.  The what-if cases are
 * built, run and reported by whatif.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clobber.h"
#include "figure.h"
#include "input.h"
#include "interrupt.h"
#include "opts.h"
#include "output.h"
#include "plot.h"
#include "whatif.h"

/* forensics' own options. */
typedef struct {
    double settle; /* s of zero input after the end of the log, as replay */
    int fail_on_overturn;
    long threads;
    long max_samples; /* the log held in memory, at most */
    sw_search_opts_t so;
    sw_cli_whatif_t w;
    const char *plot;
} forensics_opts_t;

static int check_size(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    double h, w;
    if (sw_cli_parse_size(arg, &h, &w) == 0) return SW_EXIT_OK;
    sw_cli_error("--%s: expected HEIGHTxWIDTH in m, e.g. 2.4x0.8, got '%s'", o->long_name, arg);
    return SW_EXIT_USAGE;
}

#define FO(f) SW_CLI_AT(forensics_opts_t, f)

static const sw_cli_option_t forensics_options[] = {
    {SW_CLI_SECTION, .help = "Run:"},
    {SW_CLI_DOUBLE, 0, "settle", "SECONDS", FO(settle), .rule = SW_NUM_NONNEGATIVE, .def = 30,
     .hi = 1e5, .what = "a number of seconds >= 0",
     .help = "after the log, zero acceleration for up to this long or until the outcome is "
             "certain (default %g; 0: none); at most a day: an undamped frame never rests"},
    {SW_CLI_FLAG, 0, "fail-on-overturn", FO(fail_on_overturn), .value = 1,
     .help = "exit 1 if the package as given overturned"},
    {SW_CLI_LONG, 0, "max-samples", "N", FO(max_samples), .min = 1, .max = 1L << 28,
     .def = SW_CLI_LOG_MAX_SAMPLES, .what = "a whole number of samples >= 1",
     .help = "hold at most N samples of the log in memory (16 bytes each, 24 with --vert-col; "
             "default " SW_CLI_STR(SW_CLI_LOG_MAX_SAMPLES_N) ", 9.3 h at 1 kHz; at most 268435456); a longer log, or an endless pipe, "
             "is refused with exit 2 instead of filling the memory"},
    {SW_CLI_SECTION, .help = "Safety factor (scale of the whole longitudinal acceleration):"},
    {SW_CLI_DOUBLE, 0, "step", "X", FO(so.step), .rule = SW_NUM_POSITIVE, .lo = 1e-4, .hi = 1,
     .what = "a positive relative step",
     .help = "relative scan step (default 0.02); smaller steps take tens of thousands of "
             "replays of the log"},
    {SW_CLI_DOUBLE, 0, "tol", "X", FO(so.tol), .rule = SW_NUM_POSITIVE, .lo = 1e-9, .hi = 0.5,
     .what = "a positive relative tolerance",
     .help = "relative width of the final bracket (default 0.001); finer than 1e-9 is below "
             "what the model resolves"},
    {SW_CLI_DOUBLE, 0, "max-factor", "X", FO(so.x_max), .rule = SW_NUM_POSITIVE, .lo = 1,
     .hi = 1e4, .what = "a positive scale factor",
     .help = "largest scale tried (default: 20 times the scale at which the log's peak lifts a "
             "package on the bed)"},
    {SW_CLI_LONG, 0, "threads", "N", FO(threads), .min = 1, .max = 256, .def = 2,
     .what = "a whole number of threads >= 1",
     .help = "what-if cases computed in parallel (default %g)"},
    {SW_CLI_SECTION,
     .help = "What if (each case replaces part of the scene; scene values are the defaults):"},
    {SW_CLI_STRING, 0, "frame-mass", "KG", FO(w.frame_mass),
     .help = "frame mass m_b (default: the scene's, else m/4)"},
    {SW_CLI_STRING, 0, "frame-omega", "W", FO(w.frame_omega),
     .help = "bearing frequency omega_b, rad/s (needed if the scene has no [frame])"},
    {SW_CLI_STRING, 0, "frame-zeta", "Z", FO(w.frame_zeta),
     .help = "bearing damping ratio (default: the scene's, else " SW_CLI_FRAME_ZETA ")"},
    {SW_CLI_STRING, 0, "cushion-omega", "W", FO(w.cushion_omega),
     .help = "cushion frequency omega_c, rad/s (needed if the scene has no [cushion]); on the "
             "frame if the scene has one"},
    {SW_CLI_STRING, 0, "cushion-zeta", "Z", FO(w.cushion_zeta),
     .help = "cushion damping ratio (default: the scene's, else " SW_CLI_CUSHION_ZETA ")"},
    {SW_CLI_LIST, 0, "size", "HxW", FO(w.sizes), .fn = check_size,
     .help = "the package with height H and width W (m), on the scene's support; repeatable"},
    {SW_CLI_FLAG, 0, "no-what-if", FO(w.no_what_if), .value = 1,
     .help = "only the replay and the safety factor"},
    {SW_CLI_END},
};

/* forensics' figure, in the Output section with the shared rows. */
static const sw_cli_option_t forensics_output_options[] = {
    {SW_CLI_SECTION, .help = "Output:"},
    {SW_CLI_STRING, 0, "plot", "FILE.png|.svg", FO(plot), .fn = sw_cli_plot_check,
     .help = "a_g(t), theta(t)/alpha and margin(t) with the events"},
    {SW_CLI_TEXT,
     .help = "\nWith --json the whole report is one JSON object on stdout: 'replay' (replay's\n"
             "JSON summary), 'safety_factor' and 'what_if'."},
    {SW_CLI_END},
};

static const sw_cli_command_t forensics_cmd = {
    .name = "forensics",
    .usage = "forensics LOG --scene S.ini [options]",
    .about =
        "After an incident: replays the CSV log LOG ('-' for standard input) through the\n"
        "package of S.ini and prints what replay prints, then\n"
        "  - the safety factor: the smallest factor by which the recorded longitudinal\n"
        "    acceleration would have to be scaled to overturn the package (at most 1 if it\n"
        "    overturned; for a log it survived, also any weaker scale of the same shock\n"
        "    that would have overturned it: overturning is not monotonic in the amplitude);\n"
        "  - a what-if table: the same log with the package on the bed, on a frame, on a\n"
        "    cushion and in other sizes, each with its outcome and safety factor.\n"
        "The log is held in memory (about 16 bytes a sample, at most --max-samples): the\n"
        "search replays it tens of times for every case.\n",
    .exits = SW_CLI_EXIT_OVERTURN | SW_CLI_EXIT_STRICT,
};

/* ---- the replay, with what the figure needs ----------------------------------- */

typedef struct {
    sw_cli_states_t *states;
    sw_cli_events_t *events;
    sw_risk_t *risk;      /* the reserve, impacts that matter, settling spans */
    sw_cli_figure_t *fig; /* NULL: no figure */
} replay_t;

static void on_state(void *user, const sw_output_t *out)
{
    replay_t *R = user;
    sw_risk_output(R->risk, out);
    sw_cli_states_write(R->states, out);
    sw_cli_figure_state(R->fig, out);
}

static void on_event(void *user, const sw_event_t *ev)
{
    replay_t *R = user;
    if (sw_cli_events_feed(R->events, R->risk, ev) & SW_SETTLE_REPORT)
        sw_cli_figure_event(R->fig, ev);
}

/* ---- figure ------------------------------------------------------------------------ */

static int draw(const char *path, const char *log, const sw_scene_t *sc, const replay_t *R)
{
    char title[512];
    snprintf(title, sizeof title, "%s: %s", log, sc->name);
    return sw_cli_figure_draw(R->fig, path, title);
}

/* ---- the command --------------------------------------------------------------------- */

/* Everything a forensics run uses. */
typedef struct {
    sw_cli_opts_t o;
    sw_cli_csv_opts_t copts;
    forensics_opts_t fo;
    const char *log_path;
    sw_cli_log_t L;
    sw_scene_t *scenes;
    size_t nsc;
    sw_engine_opts_t eo;
    sw_engine_t *e;
    long refused; /* samples the engine refused */
    size_t pushed; /* samples handed to the engine (fewer if interrupted) */
    sw_cli_states_t states;
    sw_cli_events_t events;
    replay_t R;
    sw_cli_case_t *cases;
    size_t ncases;
} forensics_t;

/* 0. The log into memory; nothing is written yet, so a signal ends the
 * process at once. */
static int read_log(forensics_t *F)
{
    sw_cli_interrupt_now("forensics: interrupted while reading the log; nothing written");
    int rc = sw_cli_log_read(F->log_path, &F->copts, F->o.quiet, F->fo.max_samples, &F->L);
    sw_cli_interrupt_now(NULL);
    return rc;
}

/* 1. The replay, exactly as replay runs it. */
static int replay_log(forensics_t *F)
{
    int rc;
    replay_t *R = &F->R;
    sw_cli_engine_opts(&F->o, &F->eo);
    if ((rc = sw_cli_resolve_accuracy(&F->o, F->scenes, F->nsc, &F->eo)) != SW_EXIT_OK) return rc;
    sw_engine_opts_t eo = F->eo;
    eo.on_event = on_event;
    eo.on_state = F->o.out_path || F->fo.plot || F->o.reserve_rate > 0.0 ? on_state : NULL;
    eo.user = R;
    if (!(F->e = sw_cli_engine_create(F->scenes, 1, &eo))) return SW_EXIT_USAGE;
    if (!(R->risk = sw_cli_risk_create(&F->o, F->scenes, 1))) return SW_EXIT_USAGE;
    if (F->fo.plot && !(R->fig = sw_cli_figure_create(F->e, F->scenes, 1))) return SW_EXIT_IO;
    if (F->o.verbose) sw_cli_print_derived(stderr, F->e, F->scenes, 1);
    if ((rc = sw_cli_states_open(&F->states, F->o.out_path, F->o.every, F->scenes, 1)) !=
            SW_EXIT_OK ||
        (rc = sw_cli_events_open(&F->events, F->o.events_path, F->scenes, 1)) != SW_EXIT_OK)
        return rc;
    F->states.risk = R->risk; /* after open, which clears the writer */
    R->states = &F->states;
    R->events = &F->events;
    const sw_cli_log_t *L = &F->L;
    for (size_t i = 0; i < L->n && !sw_cli_signal; i++, F->pushed++)
        if (sw_engine_push(F->e, L->t[i], L->a_g[i], L->has_z ? L->a_z[i] : 0.0) < 0)
            F->refused++;
    if (!sw_cli_signal) {
        sw_engine_finish(F->e, F->fo.settle);
        sw_cli_events_finish(&F->events, R->risk, 1);
    }
    rc = sw_cli_states_close(&F->states);
    int rc2 = sw_cli_events_close(&F->events);
    if (rc == SW_EXIT_OK) rc = rc2;
    return rc;
}

/* 2. The safety factor and the what-if cases. */
static int run_cases(forensics_t *F)
{
    F->cases = sw_cli_whatif_build(&F->scenes[0], &F->fo.w, &F->ncases);
    if (!F->cases) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    sw_run_opts_t ro;
    memset(&ro, 0, sizeof ro);
    ro.engine = F->eo; /* the replay's integration options, --accuracy included */
    ro.settle = F->fo.settle > 0.0 ? F->fo.settle : -1.0; /* negative: no free motion at all */
    const sw_cli_log_t *L = &F->L;
    sw_log_t lg = {L->t, L->a_g, L->has_z ? L->a_z : NULL, L->n};
    /* The search cannot stop between trials and writes nothing: a signal
     * ends the process at once. */
    sw_cli_interrupt_now("forensics: interrupted during the safety-factor search; --out and "
                         "--events are complete, no report");
    sw_cli_whatif_run(F->cases, F->ncases, &lg, &ro, &F->fo.so, (int)F->fo.threads);
    sw_cli_interrupt_now(NULL);
    if (!F->cases[0].available) {
        sw_cli_error("forensics: safety factor: %s", F->cases[0].note);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* 3'. Interrupted during the replay: its summary alone, marked so. */
static int report_interrupted(const forensics_t *F)
{
    const long read = (long)F->pushed < F->L.rows ? (long)F->pushed : F->L.rows;
    const sw_cli_run_t run = {
        .log = F->log_path,
        .samples_read = read,
        .samples_rejected = F->refused,
        .settle = F->fo.settle,
        .risk = F->R.risk,
        .interrupted = sw_cli_signal,
    };
    if (F->o.json) {
        fprintf(stdout, "{\n\"replay\": ");
        sw_cli_print_json(stdout, F->e, &run);
        fprintf(stdout, ",\n\"safety_factor\": null,\n\"what_if\": []\n}\n");
    } else if (!F->o.quiet) {
        sw_cli_print_summary(stdout, F->e, &run);
    }
    sw_cli_error("forensics: interrupted by %s after %ld samples of the replay; the output "
                 "files end with the last whole row; no safety factor or what-if",
                 sw_cli_signal_name(sw_cli_signal), read);
    return sw_cli_interrupt_code();
}

/* 3. The report: replay's summary, the safety factor and the table. */
static void report(const forensics_t *F)
{
    const sw_cli_run_t run = {
        .log = F->log_path,
        .samples_read = F->L.rows,
        .samples_rejected = F->L.rejected + F->refused,
        .settle = F->fo.settle,
        .risk = F->R.risk,
    };
    if (F->o.json) {
        fprintf(stdout, "{\n\"replay\": ");
        sw_cli_print_json(stdout, F->e, &run);
        fprintf(stdout, ",\n\"safety_factor\": ");
        sw_cli_whatif_json_safety(stdout, &F->cases[0]);
        fprintf(stdout, ",\n\"what_if\": [");
        for (size_t i = 0; i < F->ncases; i++) {
            fprintf(stdout, "%s\n  ", i ? "," : "");
            sw_cli_whatif_json_case(stdout, &F->cases[i]);
        }
        fprintf(stdout, "\n]\n}\n");
    } else if (!F->o.quiet) {
        sw_cli_print_summary(stdout, F->e, &run);
        sw_cli_whatif_print_safety(stdout, &F->cases[0]);
        if (!F->fo.w.no_what_if) sw_cli_whatif_print_table(stdout, F->cases, F->ncases);
    }
}

int cmd_forensics(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    forensics_t F;
    memset(&F, 0, sizeof F);
    sw_cli_csv_opts_init(&F.copts);
    sw_cli_group_t g[] = {
        SW_CLI_GROUP(sw_cli_csv_options, &F.copts),
        SW_CLI_GROUP(sw_cli_sample_options, &F.copts),
        SW_CLI_GROUP(forensics_options, &F.fo),
        SW_CLI_GROUP(sw_cli_scene_options, &F.o),
        SW_CLI_GROUP(sw_cli_integration_options, &F.o),
        SW_CLI_GROUP(sw_cli_accuracy_options, &F.o),
        SW_CLI_GROUP(sw_cli_output_options, &F.o),
        SW_CLI_GROUP(sw_cli_reserve_options, &F.o),
        SW_CLI_GROUP(forensics_output_options, &F.fo),
        SW_CLI_GROUP_IN(sw_cli_common_options, &F.o, "Output:"),
    };
    const size_t ng = sizeof g / sizeof g[0];

    int first;
    if ((rc = sw_cli_parse(&forensics_cmd, g, ng, argc, argv, &first)) != SW_CLI_CONTINUE)
        goto out;
    rc = SW_EXIT_USAGE;
    if (!(F.log_path = sw_cli_log_operand("forensics", argc, argv, first))) goto out;
    if ((rc = sw_cli_interrupt_install()) != SW_EXIT_OK) goto out;
    rc = SW_EXIT_USAGE;
    if (F.o.scenes.n > 1) {
        sw_cli_error("forensics: one --scene (one package) at a time");
        goto out;
    }
    if (F.fo.so.x_max > 0.0 && F.fo.so.x_max <= 1.0) {
        sw_cli_error("--max-factor: expected a factor above 1, got %g", F.fo.so.x_max);
        goto out;
    }
    const sw_cli_file_t outputs[] = {
        {"--out", F.o.out_path}, {"--events", F.o.events_path}, {"--plot", F.fo.plot}};
    if ((rc = sw_cli_check_run_files(F.log_path, &F.o.scenes, outputs, 3)) != SW_EXIT_OK ||
        (rc = sw_cli_check_outputs(F.o.out_path, F.o.events_path, NULL, F.o.json, F.o.quiet)) !=
            SW_EXIT_OK ||
        (rc = read_log(&F)) != SW_EXIT_OK ||
        (rc = sw_cli_load_scenes(&F.o, &F.scenes, &F.nsc)) != SW_EXIT_OK ||
        (rc = replay_log(&F)) != SW_EXIT_OK)
        goto out;
    if (sw_cli_signal) {
        rc = report_interrupted(&F);
        goto out;
    }
    if ((rc = run_cases(&F)) != SW_EXIT_OK) goto out;
    sw_summary_t sum;
    sw_engine_summary(F.e, 0, &sum);
    if (sum.overturned != F.cases[0].sf.overturned)
        sw_cli_error("forensics: the replay and the safety-factor run disagree on the outcome "
                     "(overturned %s / %s): the shock is at the edge of the model's resolution",
                     sum.overturned ? "yes" : "no", F.cases[0].sf.overturned ? "yes" : "no");
    report(&F);
    if (F.fo.plot && (rc = draw(F.fo.plot, F.log_path, &F.scenes[0], &F.R)) != SW_EXIT_OK)
        goto out;
    rc = sw_cli_verdict_exit(F.e, F.fo.fail_on_overturn);
    if (sw_cli_signal) { /* while the report or the figure was written: both are whole */
        sw_cli_error("forensics: interrupted by %s after the report",
                     sw_cli_signal_name(sw_cli_signal));
        rc = sw_cli_interrupt_code();
    }
out:
    sw_cli_states_close(&F.states);
    sw_cli_events_close(&F.events);
    sw_engine_destroy(F.e);
    sw_risk_destroy(F.R.risk);
    free(F.cases);
    sw_cli_figure_destroy(F.R.fig);
    free(F.scenes);
    sw_cli_log_free(&F.L);
    sw_cli_parse_free(g, ng);
    return rc;
}
