/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cmd_monitor.c - "swaywatch monitor": the live monitor on the vehicle's
 * LCM bus.  Subscribes to acceleration samples, advances every package's
 * model as they arrive, publishes states and alarms (the work is done by
 * the monitor core, src/lcm/monitor.c).
 *
 * This file holds the options and the command: the scenes and the LCM URL
 * checked, the monitor core started and subscribed; the loop is in
 * monitor_loop.c, the reload on SIGHUP in monitor_reload.c
 * (monitor_cli.h). */
#include <errno.h>
#include <lcm/lcm.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clobber.h"
#include "cost.h"
#include "input.h"
#include "keyfile.h"
#include "lcmlog.h"
#include "lcmopts.h"
#include "monitor_cli.h"
#include "notify.h"
#include "opts.h"
#include "output.h"

/* LCM's per-subscription queue drops what does not fit (default 30) and
 * counts nothing.  Unlimited (0), nothing is lost there; the backlog is
 * bounded by time instead: a message that waited longer than --max-backlog
 * is refused unread and counted (overload).  What the kernel drops before
 * LCM sees it is read from /proc/net/udp (socket_drops, monitor_loop.c). */
#define ACCEL_QUEUE 0

/* monitor's own options, and the monitor core's. */
typedef struct {
    sw_mon_opts_t mo;
    sw_cli_gate_t gate;        /* the input gate's options, as every source has them */
    const char *url;           /* --lcm-url; NULL: LCM's default */
    const char *accel_channel; /* subscribed to */
    const char *key_file;      /* --key: authenticated sensors */
    double status_every;       /* s, --status; 0: no status line */
    double max_backlog;        /* s, --max-backlog */
} monitor_opts_t;

static int check_accel_channel(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    /* LCM's limit on channel names */
    if (!arg[0] || strlen(arg) > 63) {
        sw_cli_error("--%s: expected a channel regex of 1 to 63 characters, got '%s'", o->long_name,
                     arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

#define MO(f) SW_CLI_AT(monitor_opts_t, f)

/* --reserve-rate 0 turns the reserve off (monitor.h: reserve_rate < 0). */
static int check_reserve_rate(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)o;
    (void)arg;
    double *v = dest;
    if (*v == 0.0)
        *v = -1.0;
    return SW_EXIT_OK;
}

static const sw_cli_option_t monitor_lcm_options[] = {
    {SW_CLI_SECTION, .help = "LCM:"},
    {SW_CLI_STRING, 'l', "lcm-url", "URL", MO(url),
     .help = "LCM URL (default: $LCM_DEFAULT_URL, else LCM's default, "
             "udpm://239.255.76.67:7667?ttl=0); a file://LOG is checked first and refused if "
             "damaged (LCM's reader trusts its length fields)"},
    {SW_CLI_STRING, 0, "accel-channel", "REGEX", MO(accel_channel), .fn = check_accel_channel,
     .help = "accel channel: a name or an anchored regex, as LCM subscribes "
             "(default " SW_MON_ACCEL_CHANNEL ")"},
    {SW_CLI_STRING, 0, "key", "FILE", MO(key_file),
     .help = "authenticated sensors: refuse every sample that is not signed by a key of the key "
             "file FILE (swaywatch keygen; re-read on SIGHUP); see below"},
    {SW_CLI_TEXT,
     .help = "\nAuthenticated sensors (--key): every accel_t must carry a MAC under one of the\n"
             "keys of FILE and a freshness above the last one accepted under its key.  Samples\n"
             "without a MAC (a sender without a key, the old layout), under an unknown key,\n"
             "with a wrong MAC or replayed are refused and counted (unauthenticated,\n"
             "unknown_key, bad_mac, replayed), and raise INPUT_CONTESTED (critical) when they\n"
             "begin to arrive: only the authenticated stream is integrated.  FILE holds lines\n"
             "'ID HMAC-SHA256 HEX:KEY'; it is refused if every user can read it or its group\n"
             "can write it.  Without --key, samples in both layouts are taken and MACs are\n"
             "not checked."},
    {.kind = SW_CLI_END},
};

static const sw_cli_option_t monitor_input_options[] = {
    {SW_CLI_SECTION, .help = "Input:"},
    {SW_CLI_FLAG, 0, "flip", MO(mo.flip), .value = 1,
     .help = "negate the longitudinal axis (sensor mounted backwards)"},
    {SW_CLI_FLAG, 0, "flip-lat", MO(mo.flip_lat), .value = 1,
     .help = "negate the lateral axis (a sensor whose y axis points to the right)"},
    {SW_CLI_CALL, 0, "accel-unit", "m/s2|g", MO(mo.accel_scale), .fn = sw_cli_accel_unit,
     .help = "unit of the message's values (default m/s2)"},
    {SW_CLI_DOUBLE, 0, "reserve-rate", "HZ", MO(mo.reserve_rate), .rule = SW_NUM_NONNEGATIVE,
     .def = SW_RISK_RATE, .lo = 0.01, .hi = 1000, .fn = check_reserve_rate,
     .what = "a rate in Hz >= 0 (0: none)",
     .help = "reserve evaluations per second of sample time for each package: the smallest "
             "design braking pulse in g that would overturn it now, in state_t.reserve_g and "
             "behind the RESERVE_WARN and RESERVE_CRITICAL alarms (default %g; 0: none; "
             "docs/reserve.md gives the cost per model)"},
    {SW_CLI_DOUBLE, 0, "max-backlog", "SECONDS", MO(max_backlog), .rule = SW_NUM_POSITIVE, .def = 1,
     .lo = 1e-3, .hi = 3600, .what = "a positive number of seconds",
     .help = "a message that waited longer than this in the receive queue (the monitor fell "
             "behind: a flood, a stalled machine) is refused unread as overload and counted, so "
             "the monitor catches up instead of working on stale samples (default %g; "
             "udpm and tcpq only)"},
    {SW_CLI_DOUBLE, 0, "status", "SECONDS", MO(status_every), .rule = SW_NUM_NONNEGATIVE, .lo = 0.1,
     .hi = 86400, .what = "a number of seconds >= 0 (0: no status)",
     .help = "one status line on stderr every SECONDS: sample rate, lag behind the sensor clock, "
             "CPU share, counts (default 0: none; under systemd it is also the service's "
             "status, updated every " SW_CLI_STR(NOTIFY_STATUS_EVERY_S) " s without --status)"},
    {SW_CLI_TEXT,
     .help = "\nA sensor with a synchronised clock can use --max-skew (e.g. 10); leave it off\n"
             "when lcm-logplayer replays an old log.\n"
             "\n"
             "Sensor gaps: when no sample has arrived for --gap seconds (if --gap is not given:\n"
             "ten times the sensor's pace as the input gate learns it, at least 0.1 s), a\n"
             "SENSOR_GAP alarm (warn) is published and the model waits: it is not\n"
             "advanced and publishes no state.  When samples resume, the gap follows\n"
             "--gap-policy (bridged linearly up to --max-bridge, else the packages restart\n"
             "from rest) and a SENSOR_GAP alarm says so; critical when the gap overlaps\n"
             "rocking or an acceleration past an uplift threshold (the verdict is incomplete).\n"
             "\n"
             "Time: samples are integrated by their own utime, the time that really passed\n"
             "taken from their arrival.  A sample stamped further ahead of its arrival than\n"
             "any before (beyond --max-jump; default 1.5 sample intervals) or that goes back\n"
             "waits until --confirm samples in a row follow it: then the sensor's clock\n"
             "stepped (re-timed, the motion goes on), it restarted (utime went back), or it\n"
             "was silent (a gap), each a SENSOR_GAP alarm and a counter; else the stream\n"
             "refutes it and it alone is refused.  One forged or corrupt utime cannot make the\n"
             "later samples late, nor blind the monitor.\n"
             "\n"
             "Contested input: when refused samples form a second timeline, or a second\n"
             "sender's seq numbers interleave, INPUT_CONTESTED (critical) is raised at once;\n"
             "the timeline the arrival times support is kept and the other is evaluated by a\n"
             "second set of engines, whose alarms go out too (\"second timeline: ...\").  No\n"
             "pattern of forged samples silences an overturn (docs/timing.md).\n"
             "\n"
             "Bad input: messages that are not accel_t (wrong type, truncated, trailing bytes),\n"
             "samples with a non-finite value or beyond --max-accel or --max-skew, duplicates\n"
             "(same utime as the last accepted sample) and late samples (utime before it) are\n"
             "refused and counted by reason: the model never integrates backwards.  The first\n"
             "refusal of each reason raises INPUT_REJECTED at once, later ones at most once a\n"
             "second with their count.  Samples lost on the way are counted from the sender's\n"
             "seq.  A state whose numbers are not all finite is never published: a MODEL_FAULT\n"
             "alarm is, instead."},
    {.kind = SW_CLI_END},
};

/* What the monitor publishes: the states and alarms (sw_cli_lcm_publish_options). */
static const sw_cli_option_t monitor_output_notes[] = {
    {SW_CLI_SECTION, .help = "Output:"},
    {SW_CLI_TEXT,
     .help = "\nThe monitor writes no files: record its output with lcm-logger.\n"
             "\n"
             "Every alarm it raises also goes to stderr, as one line:\n"
             "  swaywatch: alarm TIME level=LEVEL package=NAME kind=KIND theta=RAD\n"
             "  margin=M text=\"...\"\n"
             "TIME is the wall clock, ISO 8601 UTC with ms; input alarms have package=-\n"
             "theta=- margin=-.  When stderr is the journal (systemd's JOURNAL_STREAM), the\n"
             "line starts with the syslog priority of its level, <2> critical, <4> warn,\n"
             "<6> info, and errors with <3>: 'journalctl -p warning -u swaywatch-monitor'\n"
             "lists the warn and critical alarms and the errors.\n"
             "\n"
             "Under systemd (Type=notify) the monitor sends READY=1 once it is subscribed,\n"
             "WATCHDOG=1 from its main loop at half of WatchdogSec= (a stalled loop is\n"
             "killed and restarted), its status line as STATUS= and STOPPING=1 at the end."},
    {.kind = SW_CLI_END},
};

static const sw_cli_command_t monitor_cmd = {
    .name = "monitor",
    .usage = "monitor --scene S.ini [--scene T.ini ...] [options]",
    .about =
        "Live monitor: subscribes to acceleration samples (swaywatch.accel_t) over LCM,\n"
        "advances the model of every package as they arrive, and publishes each package's\n"
        "state (swaywatch.state_t) and alarms (swaywatch.alarm_t).  Runs until SIGINT or\n"
        "SIGTERM, then prints a summary on stderr.  Samples are integrated by their own\n"
        "utime, never by arrival time.\n"
        "\n"
        "SIGHUP (systemctl reload) re-reads the scene files and the --key file once none\n"
        "has changed for 1 s: a package whose scene values changed is rebuilt and starts\n"
        "from rest; the others keep their state, alarms and message sequence; the keys\n"
        "are replaced (the freshness seen under each key id is kept).  If a file is\n"
        "unreadable, invalid, changes while it is read or is still changing 10 s after\n"
        "the SIGHUP, nothing changes.  Write a new scene to another file and rename it\n"
        "over the old one.\n",
    .exit_text =
        "Exit codes: 0 stopped by SIGINT or SIGTERM, 2 bad usage, bad scene or key file,\n"
        "3 LCM could not be set up (URL, network) or a scene or key file could not be\n"
        "read.\n",
};

/* ---- the command --------------------------------------------------------------- */

/* Non-zero if LCM at url receives from the network (udpm, tcpq): its
 * receive times are when a message arrived, and a backlog can build up.
 * A file:// log's are the recording's; memq's are the publishing's. */
static int network_url(const char *url)
{
    const char *u = url ? url : getenv("LCM_DEFAULT_URL");
    return !u || !u[0] || !strncmp(u, "udpm://", 7) || !strncmp(u, "tcpq://", 7);
}

/* LCM at url, or why not. */
static lcm_t *open_lcm(const char *url)
{
    lcm_t *lcm = lcm_create(url);
    if (lcm)
        return lcm;
    /* The usual cause with udpm: no route for multicast (a host or network
     * namespace with only loopback). */
    int udpm = !url || !url[0] || !strncmp(url, "udpm://", 7);
    sw_cli_error("monitor: cannot set up LCM with %s%s", url && url[0] ? url : "the default URL",
                 udpm ? " (udpm needs a route for 224.0.0.0/4, e.g. 'ip route add "
                        "224.0.0.0/4 dev lo')"
                      : "");
    return NULL;
}

/* The monitor core on c's scenes, publishing on lcm. */
static int start(mon_ctx_t *c, const sw_mon_opts_t *mo, lcm_t *lcm)
{
    sw_engine_opts_t eo;
    sw_cli_engine_opts(c->opts, &eo);
    int rc = sw_cli_resolve_accuracy(c->opts, c->scenes, c->n, &eo);
    if (rc != SW_EXIT_OK)
        return rc;
    char msg[512] = "";
    sw_mon_opts_t o = *mo;
    o.on_alarm = sw_cli_mon_print_alarm;
    o.user = c;
    c->mon = sw_mon_create(c->scenes, c->n, &eo, &o, lcm, msg, sizeof msg);
    if (!c->mon) {
        sw_cli_error("monitor: %s", msg[0] ? msg : "cannot start");
        return SW_EXIT_USAGE;
    }
    if (c->opts->verbose)
        sw_cli_print_derived(stderr, sw_mon_engine(c->mon), c->scenes, c->n);
    sw_cli_warn_scene_cost(c->scenes, c->n, &eo);
    sw_cli_warn_no_reserve(sw_mon_risk(c->mon), 0, c->n, c->scenes);
    c->reserve_rate = mo->reserve_rate;
    c->lat_axis = mo->lat_axis;
    sw_cli_warn_reserve_cost(sw_mon_risk(c->mon), 0, c->n, c->scenes, c->reserve_rate);
    return SW_EXIT_OK;
}

/* What the options name: no replay outputs, the gate's settings, the
 * scenes loaded, an LCM log URL checked; the files apart from each other. */
static int check_args(const sw_cli_opts_t *o, monitor_opts_t *m, sw_scene_t **scenes, size_t *n)
{
    int rc;
    if (o->out_path || o->events_path || o->json || o->every != 1) {
        sw_cli_error(
            "monitor: --out, --events, --every and --json are for replay and "
            "simulate; record the monitor's output with lcm-logger");
        return SW_EXIT_USAGE;
    }
    if ((rc = sw_cli_mon_gate(&m->mo, &m->gate)) != SW_EXIT_OK)
        return rc;
    char url_path[4096];
    const sw_cli_file_t url_out = {"--lcm-url",
                                   sw_cli_lcm_url_output(m->url, url_path, sizeof url_path)};
    if ((rc = sw_cli_check_run_files(NULL, &o->scenes, &url_out, 1)) != SW_EXIT_OK ||
        (rc = sw_cli_load_scenes(o, scenes, n)) != SW_EXIT_OK ||
        (rc = sw_cli_mon_lateral(&m->mo, *scenes, *n)) != SW_EXIT_OK)
        return rc;
    /* A file:// URL: LCM's reader trusts the log, ours checks it first. */
    return sw_cli_check_lcm_url("monitor", m->url);
}

int cmd_monitor(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    sw_cli_opts_t o = {0};
    monitor_opts_t m = {.accel_channel = SW_MON_ACCEL_CHANNEL};
    sw_scene_t *scenes = NULL;
    size_t n = 0;
    lcm_t *lcm = NULL;
    lcm_subscription_t *sub = NULL;
    mon_ctx_t ctx;
    memset(&ctx, 0, sizeof ctx);
    sw_cli_mon_opts_init(&m.mo);
    sw_cli_gate_init(&m.gate);
    sw_cli_group_t g[] = {
        SW_CLI_GROUP(monitor_lcm_options, &m),
        SW_CLI_GROUP_IN(sw_cli_lcm_input_options, &m.mo, "Input:"),
        SW_CLI_GROUP(monitor_input_options, &m),
        SW_CLI_GROUP(sw_cli_gate_options, &m.gate),
        SW_CLI_GROUP(sw_cli_scene_options, &o),
        SW_CLI_GROUP(sw_cli_integration_options, &o),
        SW_CLI_GROUP(sw_cli_accuracy_options, &o),
        SW_CLI_GROUP_IN(sw_cli_lcm_publish_options, &m.mo, "Output:"),
        SW_CLI_GROUP(monitor_output_notes, NULL),
        SW_CLI_GROUP_IN(sw_cli_common_options, &o, "Output:"),
        /* taken, to be refused below with the reason */
        {.rows = sw_cli_output_options, .base = &o, .flags = SW_CLI_HIDDEN},
    };
    const size_t ng = sizeof g / sizeof g[0];

    int first;
    if ((rc = sw_cli_parse(&monitor_cmd, g, ng, argc, argv, &first)) != SW_CLI_CONTINUE)
        goto out;
    rc = SW_EXIT_USAGE;
    if (sw_cli_no_operand("monitor", argc, argv, first) != SW_EXIT_OK)
        goto out;
    if ((rc = check_args(&o, &m, &scenes, &n)) != SW_EXIT_OK)
        goto out;
    if (m.key_file && !(ctx.keys = sw_cli_key_load("--key", m.key_file, &rc)))
        goto out;
    m.mo.keys = ctx.keys;
    ctx.key_file = m.key_file;
    rc = SW_EXIT_IO;
    if (sw_cli_mon_signals_install() != 0) {
        sw_cli_error("monitor: cannot install signal handlers: %s", strerror(errno));
        goto out;
    }
    if (!(lcm = open_lcm(m.url)))
        goto out;

    ctx.opts = &o;
    ctx.scenes = scenes;
    ctx.n = n;
    ctx.max_backlog = network_url(m.url) ? m.max_backlog : 0.0;
    if (sw_cli_mon_reload_init(&ctx) != 0)
        goto out;
    if ((rc = start(&ctx, &m.mo, lcm)) != SW_EXIT_OK)
        goto out;

    /* Raw subscription: the generated one drops bad messages with a line
     * on stderr and no count. */
    sub = lcm_subscribe(lcm, m.accel_channel, sw_cli_mon_on_accel, &ctx);
    if (!sub) {
        sw_cli_error("monitor: cannot subscribe to %s", m.accel_channel);
        rc = SW_EXIT_IO;
        goto out;
    }
    lcm_subscription_set_queue_capacity(sub, ACCEL_QUEUE);
    char ready[128];
    snprintf(ready, sizeof ready, "READY=1\nSTATUS=waiting for samples on %s", m.accel_channel);
    sw_cli_notify(ready);
    rc = sw_cli_mon_run(lcm, &ctx, m.status_every);

out:
    if (sub)
        lcm_unsubscribe(lcm, sub);
    sw_mon_destroy(ctx.mon);
    sw_keyring_destroy(ctx.keys);
    sw_cli_mon_reload_free(&ctx);
    if (lcm)
        lcm_destroy(lcm);
    sw_cli_mon_signals_remove();
    free(scenes);
    sw_cli_parse_free(g, ng);
    return rc;
}
