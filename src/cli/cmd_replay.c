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
 * utime.  --wide and --plot take the same states as --out (output.c,
 * figure.c): the figure from a fixed number of buckets per package, so a
 * replay of any length draws from fixed memory.
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
#include "feed.h"
#include "figure.h"
#include "input.h"
#include "interrupt.h"
#include "opts.h"
#include "output.h"
#include "replay.h"
#ifdef SW_HAVE_LCM
#include <lcm/lcm.h>

#include "eventlog.h"
#include "lcmlog.h"
#include "lcmopts.h"
#include "monitor.h"
#endif

/* replay's own options. */
typedef struct {
    double settle; /* s of zero input after the end of the log */
    int fail_on_overturn;
    const char *channel;     /* lcm-logger files: the accel channel regex */
    const char *publish_url; /* --publish; NULL: no publishing */
    double speed;
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
     .help = "exit 1 if any package overturned"},
    {SW_CLI_END},
};

#ifdef SW_HAVE_LCM
#define LCM_SECTION                                                                                \
    "lcm-logger files (swaywatch.accel_t; of the CSV options, --accel-unit, --flip\n"             \
    "and --strict apply):"

/* --accel-channel, as monitor calls it; --channel, its name before, still
 * works. */
static const sw_cli_option_t replay_channel_options[] = {
    {SW_CLI_STRING, 0, "accel-channel", "REGEX", RO(channel),
     .help = "accel channel: a name or an anchored regex, as LCM subscribes (default "
             SW_MON_ACCEL_CHANNEL ")"},
    {SW_CLI_STRING, 0, "channel", "REGEX", RO(channel), .flags = SW_CLI_HIDDEN},
    {SW_CLI_END},
};

static const sw_cli_option_t replay_publish_options[] = {
    {SW_CLI_STRING, 0, "publish", "URL", RO(publish_url),
     .help = "also publish states and alarms over LCM ('' = LCM's default URL; "
             "file:///path?mode=w writes a log)"},
    {SW_CLI_DOUBLE, 0, "speed", "X", RO(speed), .rule = SW_NUM_NONNEGATIVE, .def = 1,
     .lo = 1e-3, .hi = 1e6, .what = "a factor >= 0 (0: as fast as possible)",
     .help = "with --publish: X times real time by the samples' utime (default %g; 0 = as fast "
             "as possible); below 1e-3 one second of log would take over a quarter of an hour"},
    {SW_CLI_TEXT,
     .help = "Samples are integrated by their own utime, not the log's timestamps.  Messages\n"
             "on other channels are counted and skipped; corrupted regions of the log (a bad\n"
             "header, a length field past the end of the file or beyond LCM's limits, junk)\n"
             "are skipped, counted and reported with their byte offset (--strict: exit 2);\n"
             "bad, duplicate and late samples are refused as by the monitor.  With --publish,\n"
             "only accepted samples are paced on."},
    {SW_CLI_END},
};
#endif

static const sw_cli_command_t replay_cmd = {
    .name = "replay",
    .usage = "replay LOG --scene S.ini [--scene T.ini ...] [options]",
    .about = "Replays a recorded acceleration log of the truck bed through the rocking model of\n"
             "each package and reports whether, when and how close it came to overturning.\n"
             "LOG is a CSV file, '-' for standard input, or an lcm-logger file (recognised by\n"
             "its first bytes; needs a build with LCM).  An lcm-logger log that cannot seek (a\n"
             "pipe, '-') is copied to a temporary file first (at most 4 GiB), in one pass.\n",
    .exits = SW_CLI_EXIT_OVERTURN | SW_CLI_EXIT_STRICT,
};

/* Everything a replay uses, whatever the source: the options (parsed
 * once; a batch copies them for each log), then the run's state. */
struct sw_cli_replay {
    sw_cli_opts_t o;
    sw_cli_csv_opts_t copts;
    sw_cli_gate_t gate;
    replay_opts_t ro;
    /* the first option given that only CSV logs take, and the first that
     * only lcm-logger files take (NULL: none) */
    const char *csv_given, *lcm_given;
    /* scenes belong to the options a batch copied: read, and their cost
     * measured, once for every log */
    int scenes_shared;
    int concluded; /* the run got to its summary */
    const char *log; /* LOG as given */
    sw_cli_logfile_t lf;
    sw_scene_t *scenes;
    size_t n;
    sw_engine_opts_t eo;
    sw_engine_t *e; /* the engine (the monitor core's, for an lcm-logger file) */
    sw_cli_states_t states;
    sw_cli_events_t events;
    sw_cli_wide_t wide;
    sw_cli_figure_t *fig;
    sw_risk_t *risk; /* the reserve, impacts that matter, settling spans */
    int risk_owned;  /* made here (a CSV log), not the monitor core's */
    sw_cli_run_t run;
#ifdef SW_HAVE_LCM
    sw_mon_opts_t mo;
    sw_mon_t *mon;
    lcm_t *lcm;
    sw_lcmlog_t *lcmlog;
    sw_cli_regions_t regions;
    sw_cli_pacer_t pacer; /* --publish: states go out paced by their sample time */
#endif
};
typedef struct sw_cli_replay replay_t;

static void on_state(void *user, const sw_output_t *out)
{
    replay_t *r = user;
#ifdef SW_HAVE_LCM
    /* Before the monitor publishes them: only accepted samples make
     * states, so a refused sample never stalls the replay. */
    sw_cli_pace(&r->pacer, out->t);
#endif
    /* first: the rows carry its reserve (the monitor core feeds its own) */
    if (r->risk_owned) sw_risk_output(r->risk, out);
    sw_cli_states_write(&r->states, out);
    sw_cli_wide_write(&r->wide, out);
    sw_cli_figure_state(r->fig, out);
}

static void on_event(void *user, const sw_event_t *ev)
{
    replay_t *r = user;
    if (sw_cli_events_feed(&r->events, r->risk, ev) & SW_SETTLE_REPORT)
        sw_cli_figure_event(r->fig, ev);
}

/* Something takes the states: --out, --wide or --plot. */
static int wants_states(const replay_t *r)
{
    return r->o.out_path || r->o.wide_path || r->o.plot_path || r->o.reserve_rate > 0.0;
}

/* ---- CSV logs ------------------------------------------------------------------ */

/* Stream the CSV log through the reader and the input gate into the
 * engine; the engine and the writers are ready.  Then the verdict's
 * check, before the settling that the verdict includes. */
static int replay_csv(replay_t *r)
{
    sw_cli_fed_t fed;
    int rc = sw_cli_feed_csv(&r->lf, &r->copts, &r->gate, r->e, r->o.quiet, &fed);
    if (rc != SW_EXIT_OK) return rc;
    r->run.samples_read = fed.rows;
    r->run.samples_rejected = fed.rejected;
    if (fed.interrupted) return SW_EXIT_OK; /* no check, no settling: finish() says why */
    rc = sw_cli_feed_verdict(r->lf.name, &fed.facts, &r->gate, r->copts.csv.vert_col != NULL,
                             r->o.quiet, &r->run);
    if (rc != SW_EXIT_OK) return rc;
    sw_engine_finish(r->e, r->ro.settle);
    return SW_EXIT_OK;
}

/* ---- lcm-logger files ---------------------------------------------------------- */

#ifdef SW_HAVE_LCM
/* Open the log (the channel regex checked first) and the --publish URL. */
static int lcmlog_open(replay_t *r)
{
    int err = 0;
    r->regions = (sw_cli_regions_t){.name = r->lf.name, .quiet = r->o.quiet};
    const sw_lcmlog_opts_t lo = {
        .channel = r->ro.channel,
        .strict = r->copts.strict,
        .on_region = sw_cli_print_region,
        .user = &r->regions,
        .stop = &sw_cli_signal,
    };
    r->pacer.speed = r->ro.publish_url ? r->ro.speed : 0.0;
    r->pacer.stop = &sw_cli_signal;
    /* The log as opened, its first chunk included: a pipe is read once. */
    r->lcmlog = sw_lcmlog_open_stream(r->lf.in, r->lf.buf, r->lf.len, &lo, &err);
    if (!r->lcmlog) {
        if (err == SW_EINVAL)
            sw_cli_error("--accel-channel: not a valid regular expression: '%s'", r->ro.channel);
        else if (err == SW_ENOMEM)
            sw_cli_error("out of memory");
        else if (err == SW_ETOOBIG)
            sw_cli_error("%s: a log read from a pipe is copied to a temporary file first, and "
                         "this one is longer than %lld bytes; give its file name",
                         r->lf.name, (long long)SW_LCMLOG_SPOOL_MAX);
        else
            sw_cli_error("%s: cannot read: %s", r->lf.name, strerror(errno));
        return err == SW_EINVAL || err == SW_ETOOBIG ? SW_EXIT_USAGE : SW_EXIT_IO;
    }
    return SW_EXIT_OK;
}

static int lcmlog_publish(replay_t *r)
{
    if (!r->ro.publish_url) return SW_EXIT_OK;
    r->lcm = lcm_create(r->ro.publish_url);
    if (r->lcm) return SW_EXIT_OK;
    sw_cli_error("--publish: cannot set up LCM with '%s'", r->ro.publish_url);
    return SW_EXIT_IO;
}

static sw_engine_t *lcmlog_engine(replay_t *r)
{
    if (sw_cli_mon_gate(&r->mo, &r->gate) != SW_EXIT_OK) return NULL;
    r->mo.reserve_rate = r->o.reserve_rate > 0.0 ? r->o.reserve_rate : -1.0;
    r->mo.accel_scale = r->copts.csv.accel_scale;
    r->mo.flip = r->copts.csv.flip;
    r->mo.on_state = wants_states(r) || r->pacer.speed > 0.0 ? on_state : NULL;
    r->mo.on_event = on_event;
    r->mo.user = r;
    char msg[512] = "";
    r->mon = sw_mon_create(r->scenes, r->n, &r->eo, &r->mo, r->lcm, msg, sizeof msg);
    if (!r->mon) {
        sw_cli_error("cannot start the engine: %s", msg[0] ? msg : "unknown reason");
        return NULL;
    }
    if (!r->scenes_shared) sw_cli_warn_scene_cost(r->scenes, r->n, &r->eo);
    return sw_mon_engine(r->mon);
}

static int replay_lcmlog(replay_t *r)
{
    const int lr = sw_lcmlog_read(r->lcmlog, r->mon);
    if (lr == SW_ENOTFOUND) {
        sw_cli_error("%s: cannot read: %s", r->lf.name, strerror(errno));
        return SW_EXIT_IO;
    }
    if (lr != SW_OK) {
        sw_cli_error("%s: stopped at the first bad event or sample (--strict)", r->log);
        return SW_EXIT_USAGE;
    }
    r->pacer.speed = 0.0; /* the settling after the log is not paced */
    sw_mon_flush(r->mon);
    sw_mon_counts_t k;
    sw_mon_counts(r->mon, &k);
    if (r->copts.strict && sw_mon_rejected(&k) > 0) { /* the last sample, held, not confirmed */
        sw_cli_error("%s: stopped at the first bad event or sample (--strict)", r->log);
        return SW_EXIT_USAGE;
    }
    r->run.samples_read = k.received;
    r->run.samples_rejected = k.received - k.accepted;
    if (k.accepted > 0 && !sw_cli_signal) {
        sw_gate_facts_t f;
        sw_mon_facts(r->mon, &f);
        f.upstream_rejected = k.received - f.received; /* not accel_t, NaN on an axis */
        const int rc = sw_cli_feed_verdict(r->log, &f, &r->gate, r->mo.vertical >= 0,
                                           r->o.quiet, &r->run);
        if (rc != SW_EXIT_OK) return rc;
    }
    if (k.accepted > 0 && r->ro.settle > 0.0 && !sw_cli_signal)
        sw_engine_finish(r->e, r->ro.settle);
    return SW_EXIT_OK;
}

/* What was read; SW_EXIT_USAGE (reported) if no sample was taken.
 * --quiet keeps the counts when they explain a failure. */
static int lcmlog_report(replay_t *r)
{
    sw_mon_counts_t k;
    sw_mon_counts(r->mon, &k);
    sw_lcmlog_counts_t lc;
    sw_lcmlog_counts(r->lcmlog, &lc);
    sw_cli_regions_summary(&r->regions);
    if (!r->o.quiet || k.accepted == 0) {
        FILE *m = sw_cli_msg();
        fprintf(m,
                "swaywatch: %s: %ld events, %ld on the accel channel, %ld on other channels, "
                "%ld corrupted regions skipped\n",
                r->log, lc.events, lc.on_channel, lc.other_channels, lc.corrupt);
        fprintf(m, "swaywatch: %s: accel samples: %ld = accepted %ld + ", r->log, k.received,
                k.accepted);
        sw_cli_print_rejected(m, &k);
        fprintf(m, "; lost %ld (by seq), gaps %ld, restarts %ld, clock steps %ld; %ld states, "
                        "%ld alarms\n",
                k.lost, k.gaps, k.restarts, k.clock_steps,
                k.states, k.alarms);
    }
    if (k.accepted > 0) return SW_EXIT_OK;
    sw_cli_error("%s: no usable accel_t sample on a channel matching '%s'", r->log,
                 r->ro.channel);
    return SW_EXIT_USAGE;
}

static void lcmlog_close(replay_t *r)
{
    sw_mon_destroy(r->mon);
    if (r->lcm) lcm_destroy(r->lcm);
    sw_lcmlog_close(r->lcmlog);
}
#endif

/* ---- the command ------------------------------------------------------------------ */

/* The options the log's source does not take; SW_EXIT_OK or SW_EXIT_USAGE
 * (reported, naming the first one given). */
static int check_source(const sw_cli_source_t *src, const replay_t *r)
{
    if (!src->available) {
        sw_cli_error("%s: lcm-logger files need the LCM build", r->log);
        return SW_EXIT_USAGE;
    }
    if (src->kind == SW_CLI_SRC_LCMLOG && r->csv_given) {
        sw_cli_error("%s: --%s is for CSV logs; this is an lcm-logger file", r->log,
                     r->csv_given);
        return SW_EXIT_USAGE;
    }
    if (src->kind == SW_CLI_SRC_CSV && r->lcm_given) {
        sw_cli_error("%s: option '--%s' is for lcm-logger files, and this is a CSV log",
                     r->lf.name, r->lcm_given);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* The scenes (unless a batch's options hold them already) and the engine
 * options they and --accuracy give. */
static int load(replay_t *r)
{
    int rc;
    if (r->scenes) return SW_EXIT_OK;
    if ((rc = sw_cli_load_scenes(&r->o, &r->scenes, &r->n)) != SW_EXIT_OK) return rc;
    sw_cli_engine_opts(&r->o, &r->eo);
    return sw_cli_resolve_accuracy(&r->o, r->scenes, r->n, &r->eo);
}

/* The engine: replay's own, or the monitor core's. */
static int start(replay_t *r, const sw_cli_source_t *src)
{
    int rc;
    if ((rc = load(r)) != SW_EXIT_OK) return rc;
#ifdef SW_HAVE_LCM
    if (src->kind == SW_CLI_SRC_LCMLOG) {
        if ((rc = lcmlog_publish(r)) != SW_EXIT_OK) return rc;
        r->e = lcmlog_engine(r);
        return r->e ? SW_EXIT_OK : SW_EXIT_USAGE;
    }
#endif
    (void)src;
    r->eo.on_event = on_event;
    r->eo.on_state = wants_states(r) ? on_state : NULL;
    r->eo.user = r;
    if (!r->scenes_shared) {
        r->e = sw_cli_engine_create(r->scenes, r->n, &r->eo);
    } else { /* a batch measured the scenes' cost once */
        int err = 0;
        char msg[512] = "";
        r->e = sw_engine_create(r->scenes, r->n, &r->eo, &err, msg, sizeof msg);
        if (!r->e) sw_cli_error("cannot start the engine: %s", msg[0] ? msg : sw_strerror(err));
    }
    return r->e ? SW_EXIT_OK : SW_EXIT_USAGE;
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
        {"--publish", sw_cli_lcm_url_output(r->ro.publish_url, url_path, sizeof url_path)},
    };
    return sw_cli_check_run_files(r->log, &r->o.scenes, out, sizeof out / sizeof out[0]);
}

/* Open LOG: a missing file is an I/O error (3) whatever else is wrong,
 * and its first bytes choose the source; then what the source does not
 * take is refused, and outputs that would overwrite the log. */
static const sw_cli_source_t *open_log(replay_t *r, int *rc)
{
    if ((*rc = sw_cli_logfile_open(&r->lf, r->log)) != SW_EXIT_OK) return NULL;
    const sw_cli_source_t *src = sw_cli_logfile_source(&r->lf);
    const char *const names[] = {"--out", "--events", "--wide"};
    const char *const paths[] = {r->o.out_path, r->o.events_path, r->o.wide_path};
    if ((*rc = check_source(src, r)) != SW_EXIT_OK ||
        (*rc = check_files(r)) != SW_EXIT_OK ||
        (*rc = sw_cli_check_outputs(r->o.out_path, r->o.events_path, NULL, r->o.json,
                                     r->o.quiet)) != SW_EXIT_OK ||
        (*rc = sw_cli_check_stdout(names, paths, 3, r->o.json, r->o.quiet)) != SW_EXIT_OK)
        return NULL;
#ifdef SW_HAVE_LCM
    if (src->kind == SW_CLI_SRC_LCMLOG && (*rc = lcmlog_open(r)) != SW_EXIT_OK) return NULL;
#endif
    return src;
}

/* After the run: the files closed, the counts of an lcm-logger file, what
 * the summaries say of the run. */
static int conclude(replay_t *r, const sw_cli_source_t *src)
{
    sw_cli_events_finish(&r->events, r->risk, r->n);
    int rc = sw_cli_states_close(&r->states);
    int rc2 = sw_cli_events_close(&r->events);
    if (rc == SW_EXIT_OK) rc = rc2;
    rc2 = sw_cli_wide_close(&r->wide);
    if (rc == SW_EXIT_OK) rc = rc2;
#ifdef SW_HAVE_LCM
    if (src->kind == SW_CLI_SRC_LCMLOG && (rc2 = lcmlog_report(r)) != SW_EXIT_OK) return rc2;
#endif
    (void)src;
    r->run.log = r->log;
    r->run.settle = r->ro.settle;
    r->run.interrupted = sw_cli_signal;
    r->concluded = 1;
    return rc;
}

/* The reserve and the impacts that matter: the monitor core's for an
 * lcm-logger file (it publishes them), else made here. */
static int risk_start(replay_t *r, const sw_cli_source_t *src)
{
#ifdef SW_HAVE_LCM
    if (src->kind == SW_CLI_SRC_LCMLOG) {
        r->risk = sw_mon_risk(r->mon);
        r->risk_owned = 0;
    }
#endif
    if (!r->risk) {
        if (!(r->risk = sw_cli_risk_create(&r->o, r->scenes, r->n))) return SW_EXIT_USAGE;
        r->risk_owned = 1;
    }
    (void)src;
    r->states.risk = r->wide.risk = r->run.risk = r->risk;
    r->events.all_impacts = r->o.all_impacts;
    return SW_EXIT_OK;
}

/* The log named in r->log through the engine, with r's options: opened,
 * its source checked, the engine started, the outputs opened, the log
 * run, the outputs closed. */
static int replay_one(replay_t *r)
{
    int rc;
    const sw_cli_source_t *src = open_log(r, &rc);
    if (!src || (rc = start(r, src)) != SW_EXIT_OK) return rc;
    if (r->o.verbose) sw_cli_print_derived(stderr, r->e, r->scenes, r->n);
    if ((rc = sw_cli_states_open(&r->states, r->o.out_path, r->o.every, r->scenes, r->n)) !=
            SW_EXIT_OK ||
        (rc = sw_cli_events_open(&r->events, r->o.events_path, r->scenes, r->n)) != SW_EXIT_OK ||
        (rc = sw_cli_wide_open(&r->wide, r->o.wide_path, r->o.every, r->e, r->scenes, r->n)) !=
            SW_EXIT_OK)
        return rc;
    if (r->o.plot_path && !(r->fig = sw_cli_figure_create(r->e, r->scenes, r->n)))
        return SW_EXIT_IO;
    if ((rc = risk_start(r, src)) != SW_EXIT_OK) return rc;
#ifdef SW_HAVE_LCM
    if (src->kind == SW_CLI_SRC_LCMLOG)
        rc = replay_lcmlog(r);
    else
#endif
        rc = replay_csv(r);
    if (rc == SW_EXIT_OK) rc = conclude(r, src);
    return rc;
}

/* Everything a run opened and made; the options stay. */
static void cleanup(replay_t *r)
{
    sw_cli_states_close(&r->states);
    sw_cli_events_close(&r->events);
    sw_cli_wide_close(&r->wide);
    sw_cli_figure_destroy(r->fig);
    r->fig = NULL;
    if (r->risk_owned) sw_risk_destroy(r->risk);
    r->risk = NULL;
    r->run.risk = NULL;
#ifdef SW_HAVE_LCM
    if (r->mon) r->e = NULL; /* the monitor's */
    lcmlog_close(r);
    r->mon = NULL;
    r->lcm = NULL;
    r->lcmlog = NULL;
#endif
    sw_engine_destroy(r->e);
    r->e = NULL;
    if (!r->scenes_shared) {
        free(r->scenes);
        r->scenes = NULL;
    }
    sw_cli_logfile_close(&r->lf);
}

/* The summary of a concluded run, the figure, and the exit code: rc (the
 * outputs' closing), or the verdict's. */
static int finish(replay_t *r, int rc)
{
    if (r->o.json)
        sw_cli_print_json(stdout, r->e, &r->run);
    else if (!r->o.quiet)
        sw_cli_print_summary(stdout, r->e, &r->run);
    if (rc == SW_EXIT_OK && r->fig) {
        char title[512];
        snprintf(title, sizeof title, "swaywatch replay %s%s",
                 strcmp(r->log, "-") ? r->log : "(standard input)",
                 r->run.interrupted ? " (interrupted)" : "");
        rc = sw_cli_figure_draw(r->fig, r->o.plot_path, title);
    }
    if (rc == SW_EXIT_OK) rc = sw_cli_verdict_exit(r->e, r->ro.fail_on_overturn);
    if (r->run.interrupted) {
        sw_cli_error("replay: interrupted by %s after %ld samples; the output files end with "
                     "the last whole row",
                     sw_cli_signal_name(r->run.interrupted), r->run.samples_read);
        if (rc != SW_EXIT_IO) rc = sw_cli_interrupt_code();
    }
    return rc;
}

/* replay's groups bound to r: all of them, or a batch's (the log's
 * reading, scenes and integration: no outputs, no --publish, no --help). */
static size_t groups(replay_t *r, sw_cli_group_t *g, int batch)
{
    size_t n = 0;
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_csv_options, &r->copts);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_sample_options, &r->copts);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(replay_options, &r->ro);
#ifdef SW_HAVE_LCM
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP_IN(replay_channel_options, &r->ro, LCM_SECTION);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP_IN(sw_cli_lcm_input_options, &r->mo, LCM_SECTION);
    if (!batch) {
        g[n++] = (sw_cli_group_t)SW_CLI_GROUP_IN(replay_publish_options, &r->ro, LCM_SECTION);
        g[n++] =
            (sw_cli_group_t)SW_CLI_GROUP_IN(sw_cli_lcm_publish_options, &r->mo, LCM_SECTION);
    }
#endif
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP(sw_cli_gate_options, &r->gate);
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

/* After parsing: the defaults that depend on the source, and which
 * options only one source takes were given (the first of each). */
static void parsed(replay_t *r, const sw_cli_group_t *g, size_t ng)
{
#ifdef SW_HAVE_LCM
    if (!r->ro.channel) r->ro.channel = SW_MON_ACCEL_CHANNEL;
#endif
    const sw_cli_group_t *lcm = NULL;
    for (size_t i = 0; i < ng; i++) {
        if (!g[i].given) continue;
        if (g[i].rows == sw_cli_csv_options) r->csv_given = g[i].given->long_name;
#ifdef SW_HAVE_LCM
        if ((g[i].rows == replay_channel_options || g[i].rows == sw_cli_lcm_input_options ||
             g[i].rows == replay_publish_options || g[i].rows == sw_cli_lcm_publish_options) &&
            (!lcm || g[i].given_at < lcm->given_at))
            lcm = &g[i];
#endif
    }
    r->lcm_given = lcm ? lcm->given->long_name : NULL;
}

static void init(replay_t *r)
{
    memset(r, 0, sizeof *r);
    sw_cli_csv_opts_init(&r->copts);
    sw_cli_gate_init(&r->gate);
#ifdef SW_HAVE_LCM
    sw_cli_mon_opts_init(&r->mo);
#endif
}

int cmd_replay(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    replay_t r;
    init(&r);
    sw_cli_group_t g[SW_CLI_REPLAY_GROUPS];
    const size_t ng = groups(&r, g, 0);

    int first;
    if ((rc = sw_cli_parse(&replay_cmd, g, ng, argc, argv, &first)) != SW_CLI_CONTINUE) goto out;
    if ((rc = sw_cli_interrupt_install()) != SW_EXIT_OK) goto out;
    rc = SW_EXIT_USAGE;
    if (!(r.log = sw_cli_log_operand("replay", argc, argv, first))) goto out;
    parsed(&r, g, ng);
    rc = replay_one(&r);
    if (r.concluded) rc = finish(&r, rc);
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
    if (!r) return;
    sw_cli_group_t g[SW_CLI_REPLAY_GROUPS];
    sw_cli_parse_free(g, groups(r, g, 0));
    cleanup(r);
    if (r->scenes_shared) free(r->scenes);
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
    if (rc == SW_EXIT_OK) sw_cli_warn_scene_cost(r->scenes, r->n, &r->eo);
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
        report(user, r->e, &r->run);
        rc = sw_cli_verdict_exit(r->e, r->ro.fail_on_overturn);
    }
    cleanup(r);
    free(r);
    return rc;
}
