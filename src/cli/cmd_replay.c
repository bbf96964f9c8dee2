/* cmd_replay.c - "swaywatch replay": run a recorded acceleration log (CSV
 * file, standard input, or an lcm-logger file) through the model of every
 * package and report whether, when and how close each came to overturning.
 *
 * The options are parsed once; the log's first bytes then choose its
 * source (input.h).  A CSV log is streamed in fixed chunks through the CSV
 * reader into the engine, so memory does not grow with the length of the
 * log.  An lcm-logger file is read in-process (eventlog.h, never through
 * the network) into the monitor core, which refuses bad, duplicate and
 * late samples as the live monitor does; with --publish, states and alarms
 * also go out over LCM, paced in real time (or faster) by the samples'
 * utime. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "source.h"

/* replay's own options. */
typedef struct {
    double settle; /* s of zero input after the end of the log */
    int fail_on_overturn;
    const char *publish_url; /* --publish; NULL: no publishing */
    double speed;
} replay_opts_t;

#define RO(f) SW_CLI_AT(replay_opts_t, f)

static const sw_cli_option_t replay_options[] = {
    {SW_CLI_SECTION, .help = "Run:"},
    {SW_CLI_DOUBLE, 0, "settle", "SECONDS", RO(settle), .rule = SW_NUM_NONNEGATIVE, .def = 30,
     .what = "a number of seconds >= 0",
     .help = "after the log ends, go on with zero acceleration for up to this long, or until "
             "every package is at rest or has overturned (default %g; 0: stop at the end of the "
             "log)"},
    {SW_CLI_FLAG, 0, "fail-on-overturn", RO(fail_on_overturn), .value = 1,
     .help = "exit 1 if any package overturned"},
    {SW_CLI_END},
};

#ifdef SW_HAVE_LCM
static const sw_cli_option_t replay_publish_options[] = {
    {SW_CLI_STRING, 0, "publish", "URL", RO(publish_url),
     .help = "also publish states and alarms over LCM ('' = LCM's default URL; "
             "file:///path?mode=w writes a log)"},
    {SW_CLI_DOUBLE, 0, "speed", "X", RO(speed), .rule = SW_NUM_NONNEGATIVE, .def = 1,
     .what = "a factor >= 0 (0: as fast as possible)",
     .help = "with --publish: X times real time by the samples' utime (default %g; 0 = as fast "
             "as possible)"},
    {SW_CLI_TEXT,
     .help = "Samples are integrated by their own utime, not the log's timestamps.  Messages\n"
             "on other channels are counted and skipped; corrupted regions of the log are\n"
             "skipped and counted (--strict: exit 2); bad, duplicate and late samples are\n"
             "refused as by the monitor."},
    {SW_CLI_END},
};
#endif

static const sw_cli_command_t replay_cmd = {
    .name = "replay",
    .usage = "replay LOG --scene S.ini [--scene T.ini ...] [options]",
    .about = "Replays a recorded acceleration log of the truck bed through the rocking model of\n"
             "each package and reports whether, when and how close it came to overturning.\n"
             "LOG is a CSV file, '-' for standard input, or an lcm-logger file (recognised by\n"
             "its first bytes; needs a build with LCM).\n",
    .exits = SW_CLI_EXIT_OVERTURN | SW_CLI_EXIT_STRICT,
};

/* Everything a replay uses, whatever the source. */
typedef struct {
    sw_cli_opts_t o;
    sw_cli_read_opts_t in;
    replay_opts_t ro;
    sw_cli_reader_t R;
    sw_scene_t *scenes;
    size_t n;
    sw_engine_opts_t eo;
    sw_cli_states_t states;
    sw_cli_events_t events;
#ifdef SW_HAVE_LCM
    lcm_t *lcm; /* --publish */
#endif
} replay_t;

static void on_state(void *user, const sw_output_t *out)
{
    replay_t *r = user;
    sw_cli_states_write(&r->states, out);
}

static void on_event(void *user, const sw_event_t *ev)
{
    replay_t *r = user;
    sw_cli_events_write(&r->events, ev);
}

/* ---- the command ------------------------------------------------------------------ */

/* --publish: LCM for the monitor core to publish on. */
static int publish(replay_t *r)
{
#ifdef SW_HAVE_LCM
    if (!r->ro.publish_url || r->R.src->kind != SW_CLI_SRC_LCMLOG) return SW_EXIT_OK;
    r->lcm = lcm_create(r->ro.publish_url);
    if (!r->lcm) {
        sw_cli_error("--publish: cannot set up LCM with '%s'", r->ro.publish_url);
        return SW_EXIT_IO;
    }
    r->R.publish = r->lcm;
#else
    (void)r;
#endif
    return SW_EXIT_OK;
}

/* The engine: replay's own, or the monitor core's. */
static int start(replay_t *r)
{
    int rc;
    if ((rc = sw_cli_load_scenes(&r->o, &r->scenes, &r->n)) != SW_EXIT_OK) return rc;
    sw_cli_engine_opts(&r->o, &r->eo);
    if ((rc = sw_cli_resolve_accuracy(&r->o, r->scenes, r->n, &r->eo)) != SW_EXIT_OK) return rc;
    if ((rc = publish(r)) != SW_EXIT_OK) return rc;
    r->eo.on_event = on_event;
    r->eo.on_state = r->o.out_path ? on_state : NULL;
    r->eo.user = r;
    return sw_cli_reader_engine(&r->R, r->scenes, r->n, &r->eo);
}

/* Open LOG, refuse what its source does not take and outputs that would
 * overwrite it, then its reader. */
static int open_log(replay_t *r, const char *log, const sw_cli_group_t *g, size_t nlcm)
{
    int rc;
    if ((rc = sw_cli_reader_open(&r->R, log, &r->in, r->o.quiet, &g[0], &g[3], nlcm)) !=
            SW_EXIT_OK ||
        (rc = sw_cli_check_outputs(r->o.out_path, r->o.events_path, r->R.lf.in, r->o.json,
                                   r->o.quiet)) != SW_EXIT_OK)
        return rc;
#ifdef SW_HAVE_LCM
    r->R.speed = r->ro.publish_url ? r->ro.speed : 0.0;
#endif
    return sw_cli_reader_prepare(&r->R);
}

/* After the run: the files closed, the summary; the exit code. */
static int finish(replay_t *r)
{
    int rc = sw_cli_states_close(&r->states);
    int rc2 = sw_cli_events_close(&r->events);
    if (rc == SW_EXIT_OK) rc = rc2;
    if ((rc2 = sw_cli_reader_report(&r->R)) != SW_EXIT_OK) return rc2;
    sw_cli_run_t *run = &r->R.run;
    run->log = r->R.log;
    run->settle = r->ro.settle;
    if (r->o.json)
        sw_cli_print_json(stdout, r->R.e, run);
    else if (!r->o.quiet)
        sw_cli_print_summary(stdout, r->R.e, run);
    if (rc == SW_EXIT_OK && r->ro.fail_on_overturn && sw_cli_any_overturned(r->R.e))
        rc = SW_EXIT_OVERTURNED;
    return rc;
}

int cmd_replay(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    replay_t r;
    memset(&r, 0, sizeof r);
    sw_cli_read_opts_init(&r.in);
    sw_cli_group_t g[] = {
        SW_CLI_GROUP(sw_cli_csv_options, &r.in.copts),
        SW_CLI_GROUP(sw_cli_sample_options, &r.in.copts),
        SW_CLI_GROUP(replay_options, &r.ro),
#ifdef SW_HAVE_LCM
        /* the options of lcm-logger files: g[3] to g[6] */
        SW_CLI_GROUP_IN(sw_cli_channel_options, &r.in, SW_CLI_LCM_SECTION),
        SW_CLI_GROUP_IN(sw_cli_lcm_input_options, &r.in.mo, SW_CLI_LCM_SECTION),
        SW_CLI_GROUP_IN(replay_publish_options, &r.ro, SW_CLI_LCM_SECTION),
        SW_CLI_GROUP_IN(sw_cli_lcm_publish_options, &r.in.mo, SW_CLI_LCM_SECTION),
#endif
        SW_CLI_GROUP(sw_cli_gate_options, &r.in.gate),
        SW_CLI_GROUP(sw_cli_scene_options, &r.o),
        SW_CLI_GROUP(sw_cli_integration_options, &r.o),
        SW_CLI_GROUP(sw_cli_accuracy_options, &r.o),
        SW_CLI_GROUP(sw_cli_output_options, &r.o),
        SW_CLI_GROUP_IN(sw_cli_common_options, &r.o, "Output:"),
    };
    const size_t ng = sizeof g / sizeof g[0];
#ifdef SW_HAVE_LCM
    const size_t nlcm = 4;
#else
    const size_t nlcm = 0;
#endif

    int first;
    const char *log;
    if ((rc = sw_cli_parse(&replay_cmd, g, ng, argc, argv, &first)) != SW_CLI_CONTINUE) goto out;
    rc = SW_EXIT_USAGE;
    if (!(log = sw_cli_log_operand("replay", argc, argv, first))) goto out;
    if ((rc = open_log(&r, log, g, nlcm)) != SW_EXIT_OK || (rc = start(&r)) != SW_EXIT_OK)
        goto out;
    if (r.o.verbose) sw_cli_print_derived(stderr, r.R.e, r.scenes, r.n);
    if ((rc = sw_cli_states_open(&r.states, r.o.out_path, r.o.every, r.scenes, r.n)) !=
            SW_EXIT_OK ||
        (rc = sw_cli_events_open(&r.events, r.o.events_path, r.scenes, r.n)) != SW_EXIT_OK)
        goto out;
    rc = sw_cli_reader_read(&r.R, r.ro.settle);
    if (rc == SW_EXIT_OK) rc = finish(&r);
out:
    sw_cli_states_close(&r.states);
    sw_cli_events_close(&r.events);
    sw_cli_reader_close(&r.R);
#ifdef SW_HAVE_LCM
    if (r.lcm) lcm_destroy(r.lcm);
#endif
    free(r.scenes);
    sw_cli_parse_free(g, ng);
    return rc;
}
