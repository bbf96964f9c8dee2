/* lcmlog.c - "swaywatch replay" of lcm-logger files: the event log is read
 * in-process (eventlog.h, never through the network) into the monitor core,
 * and the same summaries as for a CSV replay are printed.  With --publish,
 * states and alarms also go out over LCM, paced in real time (or faster)
 * by the samples' utime. */
#include <errno.h>
#include <lcm/lcm.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eventlog.h"
#include "input.h"
#include "lcmopts.h"
#include "monitor.h"
#include "opts.h"
#include "output.h"

#define DEFAULT_SETTLE 30.0 /* s, as for CSV logs */

enum {
    OPT_TIME_COL = SW_OPT_FIRST_OWN,
    OPT_ACCEL_COL,
    OPT_VERT_COL,
    OPT_DELIM,
    OPT_HEADER,
    OPT_NO_HEADER,
    OPT_ACCEL_UNIT,
    OPT_TIME_UNIT,
    OPT_FLIP,
    OPT_STRICT,
    OPT_SETTLE,
    OPT_FAIL_ON_OVERTURN
};

/* replay's options (cmd_replay.c), those that only lcm-logger files take
 * included. */
static const struct option long_opts[] = {
    SW_CLI_COMMON_LONGOPTS,
    {"time-col", required_argument, NULL, OPT_TIME_COL},
    {"accel-col", required_argument, NULL, OPT_ACCEL_COL},
    {"vert-col", required_argument, NULL, OPT_VERT_COL},
    {"delimiter", required_argument, NULL, OPT_DELIM},
    {"header", no_argument, NULL, OPT_HEADER},
    {"no-header", no_argument, NULL, OPT_NO_HEADER},
    {"accel-unit", required_argument, NULL, OPT_ACCEL_UNIT},
    {"time-unit", required_argument, NULL, OPT_TIME_UNIT},
    {"flip", no_argument, NULL, OPT_FLIP},
    {"strict", no_argument, NULL, OPT_STRICT},
    {"settle", required_argument, NULL, OPT_SETTLE},
    {"fail-on-overturn", no_argument, NULL, OPT_FAIL_ON_OVERTURN},
    SW_CLI_LCMLOG_LONGOPTS,
    {NULL, 0, NULL, 0},
};

void sw_cli_print_lcmlog_help(FILE *f)
{
    fprintf(f,
            "lcm-logger files (swaywatch.accel_t; of the CSV options, --accel-unit and --flip apply):\n"
            "      --channel REGEX        accel channel, an anchored regex as in LCM (default "
            "%s)\n"
            "      --axis x|y|z           message axis along the truck's travel (default x)\n"
            "      --vertical x|y|z|none  message axis used as vertical acceleration (default "
            "none)\n"
            "      --gap SECONDS          samples further apart raise SENSOR_GAP (default %g)\n"
            "      --max-accel A          refuse samples beyond A, m/s^2 or e.g. 30g (default "
            "50g)\n"
            "      --max-skew SECONDS     refuse samples whose utime is further than this from\n"
            "                             the time lcm-logger received them (default: not\n"
            "                             checked)\n"
            "      --max-jump SECONDS     hold a sample further than this after the last one\n"
            "                             until the next confirms it (default %g; 0: off)\n"
            "      --publish URL          also publish states and alarms over LCM ('' = LCM's\n"
            "                             default URL; file:///path?mode=w writes a log)\n"
            "      --speed X              with --publish: X times real time by the samples'\n"
            "                             utime (default 1; 0 = as fast as possible)\n"
            "      --state-channel CHAN, --alarm-channel CHAN, --state-rate HZ  as for monitor\n"
            "Samples are integrated by their own utime, not the log's timestamps.  Messages\n"
            "on other channels are counted and skipped; corrupted regions of the log are\n"
            "skipped and counted (--strict: exit 2); bad, duplicate and late samples are\n"
            "refused as by the monitor.\n",
            SW_MON_ACCEL_CHANNEL, SW_MON_GAP, SW_MON_MAX_JUMP);
}

typedef struct {
    sw_cli_states_t *states;
    sw_cli_events_t *events;
} sinks_t;

static void on_state(void *user, const sw_output_t *out)
{
    sinks_t *s = user;
    sw_cli_states_write(s->states, out);
}

static void on_event(void *user, const sw_event_t *ev)
{
    sinks_t *s = user;
    sw_cli_events_write(s->events, ev);
}

static void print_lcm_counts(FILE *f, const char *path, const sw_lcmlog_counts_t *lc,
                             const sw_mon_counts_t *k)
{
    fprintf(f,
            "swaywatch: %s: %ld events, %ld on the accel channel, %ld on other channels, "
            "%ld corrupted regions skipped\n",
            path, lc->events, lc->on_channel, lc->other_channels, lc->corrupt);
    const long rej = sw_mon_rejected(k);
    fprintf(f, "swaywatch: %s: accel samples: %ld = accepted %ld + rejected %ld", path, k->received,
            k->accepted, rej);
    const char *sep = " (";
    for (int r = 0; r < SW_MON_NREJ; r++)
        if (k->rejected[r]) {
            fprintf(f, "%s%s %ld", sep, sw_mon_reject_name((sw_mon_reject)r), k->rejected[r]);
            sep = ", ";
        }
    fprintf(f, "%s; lost %ld (by seq), gaps %ld; %ld states, %ld alarms\n", rej ? ")" : "", k->lost,
            k->gaps, k->states, k->alarms);
}

int sw_cli_replay_lcmlog(const char *path, int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    sw_cli_opts_t o;
    sw_mon_opts_t mo;
    const char *channel = SW_MON_ACCEL_CHANNEL;
    const char *publish_url = NULL;
    int publish = 0, strict = 0, fail_on_overturn = 0;
    double speed = 1.0, settle = DEFAULT_SETTLE;
    sw_scene_t *scenes = NULL;
    size_t n = 0;
    lcm_t *lcm = NULL;
    sw_mon_t *mon = NULL;
    sw_lcmlog_t *log = NULL;
    sw_cli_states_t states = {0};
    sw_cli_events_t events = {0};
    sinks_t sinks = {&states, &events};
    sw_lcmlog_counts_t lc = {0};

    memset(&mo, 0, sizeof mo);
    mo.vertical = -1;
    mo.hysteresis = -1.0;
    if (sw_cli_opts_init(&o, argc) != SW_EXIT_OK)
        return SW_EXIT_IO;
    optind = 0; /* a fresh scan: replay has parsed these arguments once already */
    int li = -1; /* index in long_opts of the option just read */
    const sw_cli_group_t groups[] = {{sw_cli_mon_option, &mo}};
    int c;
    while ((c = sw_cli_getopt(&o, argc, argv,
                              SW_CLI_COMMON_SHORTOPTS, long_opts, &li, groups, 1, NULL)) > 0) {
        int r = SW_EXIT_OK;
        switch (c) {
            case OPT_TIME_COL:
            case OPT_ACCEL_COL:
            case OPT_VERT_COL:
            case OPT_DELIM:
            case OPT_HEADER:
            case OPT_NO_HEADER:
            case OPT_TIME_UNIT:
                /* argv[optind - 1] would be the value of --time-unit ms */
                sw_cli_error("%s: --%s is for CSV logs; this is an lcm-logger file", path,
                             li >= 0 ? long_opts[li].name : "that option");
                r = SW_EXIT_USAGE;
                break;
            case OPT_ACCEL_UNIT: r = sw_cli_parse_accel_unit(optarg, &mo.accel_scale); break;
            case OPT_FLIP: mo.flip = 1; break;
            case OPT_STRICT: strict = 1; break;
            case OPT_SETTLE:
                r = sw_cli_parse_double("--settle", optarg, SW_NUM_NONNEGATIVE,
                                        "a number of seconds >= 0", &settle);
                break;
            case OPT_FAIL_ON_OVERTURN: fail_on_overturn = 1; break;
            case SW_OPT_LCM_CHANNEL: channel = optarg; break;
            case SW_OPT_LCM_PUBLISH:
                publish = 1;
                publish_url = optarg;
                break;
            case SW_OPT_LCM_SPEED:
                r = sw_cli_parse_double("--speed", optarg, SW_NUM_NONNEGATIVE,
                                        "a factor >= 0 (0: as fast as possible)", &speed);
                break;
            default: sw_cli_error("replay: unhandled option"); r = SW_EXIT_USAGE;
        }
        if (r != SW_EXIT_OK)
            goto out;
    }
    if (c != SW_CLI_OPT_END) {
        if (c == SW_CLI_OPT_HELP) rc = SW_EXIT_OK;
        goto out;
    }
    int err = 0;
    sw_lcmlog_opts_t lo = {.channel = channel, .speed = publish ? speed : 0.0, .strict = strict};
    log = sw_lcmlog_open(path, &lo, &err);
    if (!log) {
        if (err == SW_EINVAL)
            sw_cli_error("--channel: not a valid regular expression: '%s'", channel);
        else if (err == SW_ENOMEM)
            sw_cli_error("out of memory");
        else
            sw_cli_error("%s: cannot open: %s", path, strerror(errno));
        rc = err == SW_EINVAL ? SW_EXIT_USAGE : SW_EXIT_IO;
        goto out;
    }
    rc = sw_cli_load_scenes(&o, &scenes, &n);
    if (rc != SW_EXIT_OK)
        goto out;

    if (publish) {
        lcm = lcm_create(publish_url);
        if (!lcm) {
            sw_cli_error("--publish: cannot set up LCM with '%s'", publish_url);
            rc = SW_EXIT_IO;
            goto out;
        }
    }
    if ((rc = sw_cli_states_open(&states, o.out_path, o.every, scenes, n)) != SW_EXIT_OK ||
        (rc = sw_cli_events_open(&events, o.events_path, scenes, n)) != SW_EXIT_OK)
        goto out;

    sw_engine_opts_t eo;
    sw_cli_engine_opts(&o, &eo);
    if ((rc = sw_cli_resolve_accuracy(&o, scenes, n, &eo)) != SW_EXIT_OK) goto out;
    mo.on_state = o.out_path ? on_state : NULL;
    mo.on_event = on_event;
    mo.user = &sinks;
    char msg[512] = "";
    mon = sw_mon_create(scenes, n, &eo, &mo, lcm, msg, sizeof msg);
    if (!mon) {
        sw_cli_error("cannot start the engine: %s", msg[0] ? msg : "unknown reason");
        rc = SW_EXIT_USAGE;
        goto out;
    }
    if (o.verbose)
        sw_cli_print_derived(stderr, sw_mon_engine(mon), scenes, n);

    rc = sw_lcmlog_read(log, mon) == SW_OK ? SW_EXIT_OK : SW_EXIT_USAGE;
    sw_lcmlog_counts(log, &lc);
    if (rc != SW_EXIT_OK) {
        sw_cli_error("%s: stopped at the first bad event or sample (--strict)", path);
        goto out;
    }
    sw_mon_flush(mon);
    sw_mon_counts_t k;
    sw_mon_counts(mon, &k);
    if (strict && sw_mon_rejected(&k) > 0) { /* the last sample, held and never confirmed */
        sw_cli_error("%s: stopped at the first bad event or sample (--strict)", path);
        rc = SW_EXIT_USAGE;
        goto out;
    }
    if (k.accepted > 0 && settle > 0.0)
        sw_engine_finish(sw_mon_engine(mon), settle);

    if ((rc = sw_cli_states_close(&states)) != SW_EXIT_OK ||
        (rc = sw_cli_events_close(&events)) != SW_EXIT_OK)
        goto out;
    sw_mon_counts(mon, &k);
    sw_cli_run_t run;
    memset(&run, 0, sizeof run);
    run.log = path;
    run.samples_read = k.received;
    run.samples_rejected = k.received - k.accepted;
    run.settle = settle;
    /* --quiet keeps the counts when they explain a failure. */
    if (!o.quiet || k.accepted == 0)
        print_lcm_counts(stderr, path, &lc, &k);
    if (k.accepted == 0) {
        sw_cli_error("%s: no usable accel_t sample on a channel matching '%s'", path, channel);
        rc = SW_EXIT_USAGE;
        goto out;
    }
    if (o.json)
        sw_cli_print_json(stdout, sw_mon_engine(mon), &run);
    else if (!o.quiet)
        sw_cli_print_summary(stdout, sw_mon_engine(mon), &run);
    rc = fail_on_overturn && sw_cli_any_overturned(sw_mon_engine(mon)) ? SW_EXIT_OVERTURNED
                                                                       : SW_EXIT_OK;

out:
    sw_cli_states_close(&states);
    sw_cli_events_close(&events);
    sw_mon_destroy(mon);
    if (lcm)
        lcm_destroy(lcm);
    sw_lcmlog_close(log);
    free(scenes);
    sw_cli_opts_fini(&o);
    return rc;
}
