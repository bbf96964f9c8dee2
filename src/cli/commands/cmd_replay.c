/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cmd_replay.c - "swaywatch replay": run a recorded acceleration log (CSV
 * file, standard input, or an lcm-logger file) through the model of every
 * package and report whether, when and how close each came to overturning.
 *
 * The options are parsed once; the log is then read as source.h reads
 * it for every command: its first bytes choose its source, whose samples
 * go into one input stream (a CSV log streamed in fixed chunks through
 * the CSV reader, so memory does not grow with the length of the log; an
 * lcm-logger file read in-process into the monitor core, which with
 * --publish also publishes states and alarms over LCM).  --wide and --plot
 * take the same states as --out (output.c, figure.c): the figure from a
 * fixed number of buckets per package, so a replay of any length draws
 * from fixed memory.
 *
 * The replay of one log is also a job of "swaywatch batch" (replay.h):
 * the options parsed once, then each log run with a copy of them on any
 * thread, its summary handed to the caller instead of printed. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clobber.h"
#include "cost.h"
#include "figure.h"
#include "interrupt.h"
#include "lcmurl.h"
#include "replay.h"
#include "source.h"

/* replay's own options. */
typedef struct {
    double settle; /* s of zero input after the end of the log */
    int fail_on_overturn;
} replay_opts_t;

#define RO(f) SW_CLI_AT(replay_opts_t, f)

static const sw_cli_option_t replay_options[] = {
    {SW_CLI_SECTION, .help = "Run:"},
    {SW_CLI_DOUBLE, 0, "settle", "SECONDS", RO(settle), .rule = SW_NUM_NONNEGATIVE, .def = 30,
     .hi = 1e5, .what = "a number of seconds >= 0",
     .help = "after the log ends, go on with zero acceleration for up to this long, or until "
             "every package is at rest or has overturned (default %g; 0: stop at the end of the "
             "log); at most 1e5 s (a day), since an undamped frame never comes to rest"},
    {SW_CLI_FLAG, 0, "fail-on-overturn", RO(fail_on_overturn), .value = 1,
     .help = "exit 1 if any package overturned, or if the verdict is incomplete (a gap or "
             "restart over motion may hide an overturn)"},
    {.kind = SW_CLI_END},
};

static const sw_cli_command_t replay_cmd = {
    .name = "replay",
    .usage = "replay LOG --scene S.ini [--scene T.ini ...] [options]",
    .about =
        "Replays a recorded acceleration log of the truck bed through the rocking model of\n"
        "each package and reports whether, when and how close it came to overturning.\n"
        "LOG is a CSV file, '-' for standard input, or an lcm-logger file (recognised by\n"
        "its first bytes; needs a build with LCM).  An lcm-logger log that cannot seek (a\n"
        "pipe, '-') is copied to a temporary file first (at most 4 GiB), in one pass.\n",
    .exits = SW_CLI_EXIT_OVERTURN | SW_CLI_EXIT_STRICT | SW_CLI_EXIT_INCOMPLETE,
};

/* Everything a replay uses, whatever the source: the options (parsed
 * once; a batch copies them for each log), then the run's state. */
struct sw_cli_replay {
    sw_cli_opts_t o;
    sw_cli_read_opts_t in;
    replay_opts_t ro;
    /* the first option given that only CSV logs take, and the first that
     * only lcm-logger files take */
    sw_cli_given_t given;
    /* scenes belong to the options a batch copied: read, and their cost
     * measured, once for every log */
    int scenes_shared;
    int concluded;     /* the run got to its summary */
    const char *log;   /* LOG as given */
    sw_cli_reader_t R; /* the log's reading, and the engine it feeds */
    sw_scene_t *scenes;
    size_t n;
    sw_engine_opts_t eo;
    sw_cli_states_t states;
    sw_cli_events_t events;
    sw_cli_wide_t wide;
    sw_cli_figure_t *fig;
};
typedef struct sw_cli_replay replay_t;

/* A state, its reserve evaluated by the stream (the rows carry it). */
static void on_state(void *user, const sw_output_t *out)
{
    replay_t *r = user;
    sw_cli_states_write(&r->states, out);
    sw_cli_wide_write(&r->wide, out);
    sw_cli_figure_state(r->fig, out); /* both planes */
}

static void on_event(void *user, const sw_event_t *ev)
{
    replay_t *r = user;
    if (sw_cli_events_feed(&r->events, r->R.risk, ev) & SW_SETTLE_REPORT)
        sw_cli_figure_event(r->fig, ev);
}

/* Something takes the states: --out, --wide or --plot. */
static int wants_states(const replay_t *r)
{
    return r->o.out_path || r->o.wide_path || r->o.plot_path || r->o.reserve_rate > 0.0;
}

/* ---- the command ------------------------------------------------------------------ */

/* The scenes (unless a batch's options hold them already) and the engine
 * options they and --accuracy give. */
static int load(replay_t *r)
{
    int rc;
    if (r->scenes)
        return SW_EXIT_OK;
    if ((rc = sw_cli_load_scenes(&r->o, &r->scenes, &r->n)) != SW_EXIT_OK)
        return rc;
    sw_cli_engine_opts(&r->o, &r->eo);
    r->eo.check_default = 1; /* a chosen scheme or dt: its verdict checked (summary.c) */
    return sw_cli_resolve_accuracy(&r->o, r->scenes, r->n, &r->eo);
}

/* The stream of the log's source. */
static int start(replay_t *r)
{
    int rc;
    if ((rc = load(r)) != SW_EXIT_OK)
        return rc;
    r->eo.on_event = on_event;
    r->eo.on_state = wants_states(r) ? on_state : NULL;
    r->eo.user = r;
    r->R.reserve_rate = r->o.reserve_rate;
    /* the reserve of each state only where a row shows it; the summary's
     * minimum is the same either way (risk.h) */
    r->R.reserve_min_only = !r->o.out_path && !r->o.wide_path;
    r->R.lateral = 1; /* a CSV log's lateral column drives the scenes with a depth */
    return sw_cli_reader_engine(&r->R, r->scenes, r->n, &r->eo, r->scenes_shared);
}

/* No output may be the log, a scene or another output (--publish
 * file://PATH?mode=w writes a log too). */
static int check_files(const replay_t *r)
{
    char url_path[4096];
    const sw_cli_file_t out[] = {
        {"--out", r->o.out_path},
        {"--events", r->o.events_path},
        {"--wide", r->o.wide_path},
        {"--plot", r->o.plot_path},
        {"--publish", sw_cli_lcm_url_output(r->in.publish_url, url_path, sizeof url_path)},
    };
    return sw_cli_check_run_files(r->log, &r->o.scenes, out, sizeof out / sizeof out[0]);
}

/* Open LOG: a missing file is an I/O error (3) whatever else is wrong,
 * and its first bytes choose the source; then what the source does not
 * take is refused, and outputs that would overwrite the log. */
static int open_log(replay_t *r)
{
    int rc;
    const char *const names[] = {"--out", "--events", "--wide"};
    const char *const paths[] = {r->o.out_path, r->o.events_path, r->o.wide_path};
    if ((rc = sw_cli_reader_open(&r->R, r->log, &r->in, r->o.quiet, r->given)) != SW_EXIT_OK ||
        (rc = check_files(r)) != SW_EXIT_OK ||
        (rc = sw_cli_check_outputs(r->o.out_path, r->o.events_path, NULL, r->o.json, r->o.quiet)) !=
            SW_EXIT_OK ||
        (rc = sw_cli_check_stdout(names, paths, 3, r->o.json, r->o.quiet)) != SW_EXIT_OK)
        return rc;
    return sw_cli_reader_prepare(&r->R);
}

/* After the run: the files closed, the counts of an lcm-logger file, what
 * the summaries say of the run. */
static int conclude(replay_t *r)
{
    sw_cli_events_finish(&r->events, r->R.risk, r->n);
    int rc = sw_cli_states_close(&r->states);
    int rc2 = sw_cli_events_close(&r->events);
    if (rc == SW_EXIT_OK)
        rc = rc2;
    rc2 = sw_cli_wide_close(&r->wide);
    if (rc == SW_EXIT_OK)
        rc = rc2;
    if ((rc2 = sw_cli_reader_report(&r->R)) != SW_EXIT_OK)
        return rc2;
    sw_cli_run_t *run = &r->R.run;
    run->log = r->log;
    run->settle = r->ro.settle;
    run->interrupted = sw_cli_signal;
    r->concluded = 1;
    return rc;
}

/* The log named in r->log through the engine, with r's options: opened,
 * its source checked, the engine started, the outputs opened, the log
 * run, the outputs closed. */
static int replay_one(replay_t *r)
{
    int rc;
    if ((rc = open_log(r)) != SW_EXIT_OK || (rc = start(r)) != SW_EXIT_OK)
        return rc;
    sw_engine_t *e = r->R.e;
    if (r->o.verbose)
        sw_cli_print_derived(stderr, e, r->scenes, r->n);
    if ((rc = sw_cli_states_open(&r->states, r->o.out_path, r->o.every, e, r->scenes, r->n)) !=
            SW_EXIT_OK ||
        (rc = sw_cli_events_open(&r->events, r->o.events_path, e, r->scenes, r->n)) != SW_EXIT_OK ||
        (rc = sw_cli_wide_open(&r->wide, r->o.wide_path, r->o.every, e, r->scenes, r->n)) !=
            SW_EXIT_OK)
        return rc;
    if (r->o.plot_path && !(r->fig = sw_cli_figure_create(e, r->scenes, r->n)))
        return SW_EXIT_IO;
    if ((rc = sw_cli_reader_risk(&r->R, &r->o, r->scenes, r->n)) != SW_EXIT_OK)
        return rc;
    r->states.risk = r->wide.risk = r->R.risk; /* after open, which clears the writers */
    r->states.stream = r->wide.stream = r->R.st;
    r->events.all_impacts = r->o.all_impacts;
    if ((rc = sw_cli_reader_feed(&r->R)) != SW_EXIT_OK)
        return rc;
    sw_cli_reader_settle(&r->R, r->ro.settle);
    sw_cli_risk_resolve(r->R.risk, r->scenes, r->n);
    for (size_t k = 0; k < r->n; k++) { /* the lateral planes' reserves too */
        const int rl = sw_stream_risk_resolve(r->R.st, k, SW_PLANE_LAT);
        if (rl < 0)
            sw_cli_error("%s: the smallest reserve across the truck could not be found: %s",
                         r->scenes[k].name, sw_strerror(rl));
    }
    return conclude(r);
}

/* Everything a run opened and made; the options stay. */
static void cleanup(replay_t *r)
{
    sw_cli_states_close(&r->states);
    sw_cli_events_close(&r->events);
    sw_cli_wide_close(&r->wide);
    sw_cli_figure_destroy(r->fig);
    r->fig = NULL;
    sw_cli_reader_close(&r->R);
    if (!r->scenes_shared) {
        free(r->scenes);
        r->scenes = NULL;
    }
}

/* The summary of a concluded run, the figure, and the exit code: rc (the
 * outputs' closing), or the verdict's. */
static int finish(replay_t *r, int rc)
{
    const sw_cli_run_t *run = &r->R.run;
    if (r->o.json && sw_cli_print_json(stdout, r->R.e, run) != SW_EXIT_OK)
        rc = SW_EXIT_IO;
    else if (!r->o.json && !r->o.quiet)
        sw_cli_print_summary(stdout, r->R.e, run);
    if (rc == SW_EXIT_OK && r->fig) {
        char title[512];
        snprintf(title, sizeof title, "swaywatch replay %s%s",
                 strcmp(r->log, "-") ? r->log : "(standard input)",
                 run->interrupted ? " (interrupted)" : "");
        rc = sw_cli_figure_draw(r->fig, r->o.plot_path, title);
    }
    if (rc == SW_EXIT_OK)
        rc = sw_cli_verdict_exit(r->R.e, &r->R.run, r->ro.fail_on_overturn);
    if (run->interrupted) {
        sw_cli_error(
            "replay: interrupted by %s after %ld samples; the output files end with "
            "the last whole row",
            sw_cli_signal_name(run->interrupted), run->samples_read);
        if (rc != SW_EXIT_IO)
            rc = sw_cli_interrupt_code();
    }
    return rc;
}

/* replay's groups bound to r: all of them, or a batch's (the log's
 * reading, scenes and integration: no outputs, no --publish, no --help). */
static size_t groups(replay_t *r, sw_cli_group_t *g, int batch)
{
    size_t n = 0;
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_csv_options, &r->in.copts);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_sample_options, &r->in.copts);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(replay_options, &r->ro);
    n += sw_cli_source_groups(&r->in, g + n, !batch); /* lcm-logger files' */
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_gate_options, &r->in.gate);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_scene_options, &r->o);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_integration_options, &r->o);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_accuracy_options, &r->o);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_reserve_options, &r->o);
    if (!batch) {
        g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_output_options, &r->o);
        g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_picture_options, &r->o);
        g[n++] = (sw_cli_group_t)SW_CLI_GROUP_IN(sw_cli_common_options, &r->o, "Output:");
    }
    return n;
}

/* After parsing: which options only one source takes were given (the
 * first of each). */
static void parsed(replay_t *r, const sw_cli_group_t *g, size_t ng)
{
    r->given = sw_cli_source_given(g, ng);
}

static void init(replay_t *r)
{
    memset(r, 0, sizeof *r);
    sw_cli_read_opts_init(&r->in);
}

int cmd_replay(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    replay_t r;
    init(&r);
    sw_cli_group_t g[SW_CLI_REPLAY_GROUPS];
    const size_t ng = groups(&r, g, 0);

    int first;
    if ((rc = sw_cli_parse(&replay_cmd, g, ng, argc, argv, &first)) != SW_CLI_CONTINUE)
        goto out;
    if ((rc = sw_cli_interrupt_install()) != SW_EXIT_OK)
        goto out;
    rc = SW_EXIT_USAGE;
    if (!(r.log = sw_cli_log_operand("replay", argc, argv, first)))
        goto out;
    parsed(&r, g, ng);
    rc = replay_one(&r);
    if (r.concluded)
        rc = finish(&r, rc);
out:
    cleanup(&r);
    sw_cli_parse_free(g, ng);
    return rc;
}

/* ---- the replay of one log, for batch (replay.h) ---------------------------------- */

sw_cli_replay_t *sw_cli_replay_new(void)
{
    replay_t *r = malloc(sizeof *r);
    if (!r) {
        sw_cli_error("out of memory");
        return NULL;
    }
    init(r);
    return r;
}

void sw_cli_replay_free(sw_cli_replay_t *r)
{
    if (!r)
        return;
    sw_cli_group_t g[SW_CLI_REPLAY_GROUPS];
    sw_cli_parse_free(g, groups(r, g, 0));
    cleanup(r);
    if (r->scenes_shared)
        free(r->scenes);
    free(r);
}

size_t sw_cli_replay_groups(sw_cli_replay_t *r, sw_cli_group_t *g)
{
    return groups(r, g, 1);
}

int sw_cli_replay_ready(sw_cli_replay_t *r, const sw_cli_group_t *g, size_t ng)
{
    parsed(r, g, ng);
    r->scenes_shared = 0;
    int rc = load(r);
    r->scenes_shared = 1; /* the copies made for each log share them */
    if (rc == SW_EXIT_OK)
        sw_cli_warn_scene_cost(r->scenes, r->n, &r->eo);
    return rc;
}

sw_cli_opts_t *sw_cli_replay_opts(sw_cli_replay_t *r)
{
    return &r->o;
}

int sw_cli_replay_log(const sw_cli_replay_t *opts, const char *log, sw_cli_replay_report_fn report,
                      void *user)
{
    replay_t *r = malloc(sizeof *r);
    if (!r) {
        sw_cli_error("%s: out of memory", log);
        return SW_EXIT_IO;
    }
    *r = *opts; /* the options; a ready one has run nothing, so no state is copied */
    r->log = log;
    r->o.quiet = 1;
    r->o.json = 0;
    int rc = replay_one(r);
    if (rc == SW_EXIT_OK && r->concluded) {
        report(user, r->R.e, &r->R.run);
        rc = sw_cli_verdict_exit(r->R.e, &r->R.run, r->ro.fail_on_overturn);
    }
    cleanup(r);
    free(r);
    return rc;
}
