/* SPDX-License-Identifier: GPL-3.0-or-later */
/* source_lcmlog.c - the lcm-logger source (source.h; LCM builds): a log
 * read in-process, never through the network (eventlog.h), its accel_t
 * messages into the monitor core (monitor.h), which decodes and checks
 * each one into its input stream as the live monitor does, and with
 * --publish also publishes states and alarms over LCM, paced in real
 * time (or faster) by the samples' utime. */
#include <errno.h>
#include <lcm/lcm.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "interrupt.h"
#include "keyfile.h"
#include "lcmlog.h"
#include "lcmopts.h"
#include "lcmurl.h"
#include "source.h"

/* ---- options ------------------------------------------------------------------------ */

#define RD(f) SW_CLI_AT(sw_cli_read_opts_t, f)

/* The section of the options of lcm-logger files. */
#define SECTION                                                                        \
    "lcm-logger files (swaywatch.accel_t; of the CSV options, --accel-unit, --flip,\n" \
    "--flip-lat and --strict apply):"

/* --accel-channel, as monitor calls it; --channel, its name before, still
 * works. */
static const sw_cli_option_t channel_options[] = {
    {SW_CLI_STRING, 0, "accel-channel", "REGEX", RD(channel),
     .help = "accel channel: a name or an anchored regex, as LCM subscribes "
             "(default " SW_MON_ACCEL_CHANNEL ")"},
    {SW_CLI_STRING, 0, "channel", "REGEX", RD(channel), .flags = SW_CLI_HIDDEN},
    {SW_CLI_STRING, 0, "key", "FILE", RD(key_file),
     .help = "authenticated samples only: refuse and count every accel_t that is not signed by "
             "a key of the key file FILE, or is a copy of an earlier one, as monitor --key does "
             "(without --key, MACs are not checked)"},
    {.kind = SW_CLI_END},
};

static const sw_cli_option_t publish_options[] = {
    {SW_CLI_STRING, 0, "publish", "URL", RD(publish_url),
     .help = "also publish states and alarms over LCM ('' = LCM's default URL; "
             "file:///path?mode=w writes a log)"},
    {SW_CLI_DOUBLE, 0, "speed", "X", RD(speed), .rule = SW_NUM_NONNEGATIVE, .def = 1, .lo = 1e-3,
     .hi = 1e6, .what = "a factor >= 0 (0: as fast as possible)",
     .help = "with --publish: X times real time by the samples' utime (default %g; 0 = as fast "
             "as possible); below 1e-3 one second of log would take over a quarter of an hour"},
    {SW_CLI_TEXT,
     .help = "Samples are integrated by their own utime, not the log's timestamps.  Messages\n"
             "on other channels are counted and skipped; corrupted regions of the log (a bad\n"
             "header, a length field past the end of the file or beyond LCM's limits, junk)\n"
             "are skipped, counted and reported with their byte offset (--strict: exit 2);\n"
             "bad, duplicate and late samples are refused as by the monitor.  With --publish,\n"
             "only accepted samples are paced on."},
    {.kind = SW_CLI_END},
};

static const sw_cli_option_t *const lcmlog_own[] = {
    channel_options, sw_cli_lcm_input_options, publish_options, sw_cli_lcm_publish_options, NULL};

static void lcmlog_init(sw_cli_read_opts_t *o)
{
    sw_cli_mon_opts_init(&o->mo);
    o->channel = SW_MON_ACCEL_CHANNEL;
}

static size_t lcmlog_groups(sw_cli_read_opts_t *o, sw_cli_group_t *g, int publish)
{
    size_t n = 0;
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP_IN(channel_options, o, SECTION);
    g[n++] = (sw_cli_group_t)SW_CLI_GROUP_IN(sw_cli_lcm_input_options, &o->mo, SECTION);
    if (publish) {
        g[n++] = (sw_cli_group_t)SW_CLI_GROUP_IN(publish_options, o, SECTION);
        g[n++] = (sw_cli_group_t)SW_CLI_GROUP_IN(sw_cli_lcm_publish_options, &o->mo, SECTION);
    }
    return n;
}

/* ---- the source's own --------------------------------------------------------------- */

typedef struct {
    sw_cli_reader_t *R;
    sw_lcmlog_t *lcmlog;
    sw_mon_t *mon;
    sw_keyring_t *keys; /* --key's */
    lcm_t *lcm;         /* --publish */
    sw_cli_regions_t regions;
    sw_cli_pacer_t pacer; /* --publish: states go out paced by their sample time */
    /* the command's engine callbacks: the monitor's user is this */
    sw_state_fn on_state;
    sw_event_fn on_event;
    void *user;
} lcmlog_t;

/* Before the monitor publishes a state: only accepted samples make
 * states, so a refused sample never stalls the replay. */
static void on_state(void *user, const sw_output_t *out)
{
    lcmlog_t *P = user;
    sw_cli_pace(&P->pacer, out->t);
    if (P->on_state)
        P->on_state(P->user, out);
}

static void on_event(void *user, const sw_event_t *ev)
{
    const lcmlog_t *P = user;
    P->on_event(P->user, ev);
}

static void on_take(void *user, double t, double a_g, double a_z, int restart)
{
    const lcmlog_t *P = user;
    P->R->take(P->R->user, t, a_g, a_z, restart);
}

static void on_take_lat(void *user, double t, double a_g, double a_y, double a_z, int restart)
{
    const lcmlog_t *P = user;
    P->R->take_lat(P->R->user, t, a_g, a_y, a_z, restart);
}

/* ---- the source's calls ------------------------------------------------------------- */

/* The log's reader (the channel regex checked first; a pipe spooled). */
static int lcmlog_prepare(sw_cli_reader_t *R)
{
    lcmlog_t *P = calloc(1, sizeof *P);
    if (!P) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    P->R = R;
    R->priv = P;
    int err = 0;
    if (R->o->key_file && !(P->keys = sw_cli_key_load("--key", R->o->key_file, &err)))
        return err;
    P->regions = (sw_cli_regions_t){.name = R->lf.name, .quiet = R->quiet};
    const sw_lcmlog_opts_t lo = {
        .channel = R->o->channel,
        .strict = R->o->copts.strict,
        .on_region = sw_cli_print_region,
        .user = &P->regions,
        .stop = &sw_cli_signal,
    };
    /* The log as opened, its first chunk included: a pipe is read once. */
    P->lcmlog = sw_lcmlog_open_stream(R->lf.in, R->lf.buf, R->lf.len, &lo, &err);
    if (P->lcmlog)
        return SW_EXIT_OK;
    if (err == SW_EINVAL)
        sw_cli_error("--accel-channel: not a valid regular expression: '%s'", R->o->channel);
    else if (err == SW_ENOMEM)
        sw_cli_error("out of memory");
    else if (err == SW_ETOOBIG)
        sw_cli_error(
            "%s: a log read from a pipe is copied to a temporary file first, and "
            "this one is longer than %lld bytes; give its file name",
            R->lf.name, (long long)SW_LCMLOG_SPOOL_MAX);
    else
        sw_cli_error("%s: cannot read: %s", R->lf.name, strerror(errno));
    return err == SW_EINVAL || err == SW_ETOOBIG ? SW_EXIT_USAGE : SW_EXIT_IO;
}

/* --publish: LCM for the monitor core to publish on, and the pacing. */
static int publish(lcmlog_t *P)
{
    const sw_cli_read_opts_t *o = P->R->o;
    P->pacer.speed = o->publish_url ? o->speed : 0.0;
    P->pacer.stop = &sw_cli_signal;
    if (!o->publish_url)
        return SW_EXIT_OK;
    /* LCM's file provider reads a log unless told to write one: nothing
     * could be published, and a damaged log would crash its reader. */
    if (sw_cli_lcm_url_file(sw_cli_lcm_url_effective(o->publish_url), NULL, 0) ==
        SW_CLI_URL_READS) {
        sw_cli_error(
            "--publish %s: LCM reads that file instead of writing it (as liblcm reads the "
            "URL: its last mode= decides); add ?mode=w to write a log",
            o->publish_url);
        return SW_EXIT_USAGE;
    }
    if (!(P->lcm = lcm_create(o->publish_url))) {
        sw_cli_error("--publish: cannot set up LCM with '%s'", o->publish_url);
        return SW_EXIT_IO;
    }
    return SW_EXIT_OK;
}

/* The monitor core, whose stream the log feeds. */
static int lcmlog_start(sw_cli_reader_t *R, const sw_scene_t *scenes, size_t n,
                        const sw_engine_opts_t *eo)
{
    lcmlog_t *P = R->priv;
    int rc = publish(P);
    if (rc != SW_EXIT_OK)
        return rc;
    sw_mon_opts_t mo = R->o->mo;
    if (sw_cli_mon_gate(&mo, &R->o->gate) != SW_EXIT_OK)
        return SW_EXIT_USAGE;
    P->on_state = eo->on_state;
    P->on_event = eo->on_event;
    P->user = eo->user;
    mo.reserve_rate = R->reserve_rate > 0.0 ? R->reserve_rate : -1.0;
    mo.accel_scale = R->o->copts.csv.accel_scale;
    mo.flip = R->o->copts.csv.flip;
    mo.flip_lat = R->o->copts.csv.flip_lat;
    if (sw_cli_mon_lateral(&mo, scenes, R->lateral ? n : 0) != SW_EXIT_OK)
        return SW_EXIT_USAGE;
    int depth = 0;
    for (size_t k = 0; k < n; k++) depth |= sw_scene_has_depth(&scenes[k]);
    if (!R->lateral && depth && mo.lat_axis >= 0 && !R->quiet)
        sw_cli_error(
            "%s: note: the lateral acceleration (--lat-axis) is not used: this command judges "
            "the plane along the truck only",
            R->lf.name);
    mo.on_state = eo->on_state || P->pacer.speed > 0.0 ? on_state : NULL;
    mo.on_event = eo->on_event ? on_event : NULL;
    mo.on_take = R->take ? on_take : NULL;
    mo.on_take_lat = R->take_lat ? on_take_lat : NULL;
    mo.keys = P->keys;
    mo.user = P;
    char msg[512] = "";
    if (!(P->mon = sw_mon_create(scenes, n, eo, &mo, P->lcm, msg, sizeof msg))) {
        sw_cli_error("cannot start the engine: %s", msg[0] ? msg : "unknown reason");
        return SW_EXIT_USAGE;
    }
    R->st = sw_mon_stream(P->mon);
    return SW_EXIT_OK;
}

/* The samples the monitor core refused, by reason (it keeps no places). */
static void unused(sw_cli_reader_t *R, const sw_mon_counts_t *k)
{
    sw_cli_unused_init(&R->run.unused, 0);
    for (int r = 0; r < SW_MON_NREJ; r++)
        sw_cli_unused_count(&R->run.unused, sw_mon_reject_name((sw_mon_reject)r), k->rejected[r]);
}

/* The dates of an lcm-logger file: the samples' utime when it is one (µs
 * since 1970, as accel_t says), else the times lcm-logger received them
 * (its own clock: a sensor that counts from its boot still has a date
 * there, to the logger's latency).  The monitor core times the gate from
 * the first sample it received, the base, at source time 0. */
static void dates(sw_cli_reader_t *R, const lcmlog_t *P, const sw_gate_facts_t *f)
{
    const double origin = (double)sw_mon_origin(P->mon) / 1e6; /* s, engine t = 0 */
    sw_lcmlog_counts_t lc;
    sw_lcmlog_counts(P->lcmlog, &lc);
    sw_cli_run_t *run = &R->run;
    int logger = 0;
    if (sw_cli_epoch_plausible(origin)) {
        run->abs_base = origin - f->t_origin;
        run->abs_from = "the samples' utime";
    } else if (lc.first_utime > 0 && sw_cli_epoch_plausible((double)lc.first_utime / 1e6)) {
        run->abs_base = (double)lc.first_utime / 1e6;
        run->abs_from = "lcm-logger's receive times (the samples' utime is no date)";
        logger = 1;
    } else {
        return;
    }
    run->absolute = 1;
    run->abs_start = f->t_first + run->abs_base;
    run->abs_end = f->t_last + run->abs_base;
    if (logger && (f->restarts || f->clock_steps))
        run->abs_end = (double)lc.last_utime / 1e6; /* the sensor's clock went back or leapt */
}

static int lcmlog_feed(sw_cli_reader_t *R, sw_gate_facts_t *f, int *vert)
{
    lcmlog_t *P = R->priv;
    const int strict = R->o->copts.strict;
    const int lr = sw_mon_feed_log(P->mon, P->lcmlog, strict);
    P->pacer.speed = 0.0; /* the settling after the log is not paced */
    if (lr == SW_ENOTFOUND) {
        sw_cli_error("%s: cannot read: %s", R->lf.name, strerror(errno));
        return SW_EXIT_IO;
    }
    if (lr != SW_OK) {
        sw_cli_error("%s: stopped at the first bad event or sample (--strict)", R->log);
        return SW_EXIT_USAGE;
    }
    sw_mon_flush(P->mon);
    sw_mon_counts_t k;
    sw_mon_counts(P->mon, &k);
    if (strict && sw_mon_rejected(&k) > 0) { /* the last sample, held */
        sw_cli_error("%s: stopped at the first bad event or sample (--strict)", R->log);
        return SW_EXIT_USAGE;
    }
    R->run.samples_read = k.received;
    R->run.samples_rejected = k.received - k.accepted;
    R->accepted = k.accepted;
    R->interrupted = sw_cli_signal != 0;
    if (k.accepted == 0 || R->interrupted)
        return SW_EXIT_OK;
    sw_mon_facts(P->mon, f);
    /* not accel_t, NaN on an axis; not what failed authentication: those
     * samples are known not to be the sensor's, not a sign of a misread log */
    const sw_auth_facts_t *au = sw_mon_auth_facts(P->mon);
    f->upstream_rejected =
        k.received - f->received - (au ? au->checked - au->refused[SW_AUTH_OK] : 0);
    *vert = R->o->mo.vertical >= 0;
    /* A sender without a lateral axis writes one value (0) throughout: an
     * honest log, read along the truck, its lateral plane held still.  Said
     * so, not refused as a channel that never varies (the CSV path's
     * reason: a wrong column; an accel_t's ay is no column chosen). */
    if (f->lateral && f->accepted > 1 && f->lat.min == f->lat.max) {
        if (!R->quiet)
            sw_cli_error(
                "%s: note: the lateral acceleration (--lat-axis) reads %.6g m/s^2 throughout: "
                "the sender has no lateral axis, or the truck never turned; the lateral "
                "planes saw no more than that",
                R->log, f->lat.min);
        f->lateral = 0;
    }
    unused(R, &k);
    dates(R, P, f);
    return SW_EXIT_OK;
}

/* Signed samples read without --key: said (always when the log is
 * refused, rc not SW_EXIT_OK: forged samples among them may be why). */
static void lcmlog_checked(sw_cli_reader_t *R, int rc)
{
    const lcmlog_t *P = R->priv;
    sw_mon_counts_t k;
    sw_mon_counts(P->mon, &k);
    if (k.macs_unchecked > 0 && (!R->quiet || rc != SW_EXIT_OK))
        fprintf(sw_cli_msg(),
                "swaywatch: %s: %ld samples carry a MAC that was not checked: give the sender's "
                "key file (--key FILE) to refuse forged and replayed samples\n",
                R->log, k.macs_unchecked);
}

/* Why no sample was usable, when authentication refused them all: what
 * the refusals say of the log, and the option that reads it. */
static const char *unusable_why(const lcmlog_t *P)
{
    const sw_auth_facts_t *au = sw_mon_auth_facts(P->mon);
    if (!au || au->checked == 0 || au->refused[SW_AUTH_OK] > 0)
        return "";
    if (au->refused[SW_AUTH_NONE] == au->checked)
        return ": every sample is unauthenticated (no MAC: written by a sender without a key); "
               "without --key they are read, unchecked";
    if (au->refused[SW_AUTH_REPLAYED] == 0 && au->refused[SW_AUTH_NONE] == 0)
        return ": every sample is signed by another key (unknown_key, bad_mac); give --key the "
               "key file of the sender that wrote the log";
    return ": every sample failed authentication (see the counts above)";
}

/* What the log held: its corrupted regions, its counts. */
static int lcmlog_report(sw_cli_reader_t *R)
{
    lcmlog_t *P = R->priv;
    sw_mon_counts_t k;
    sw_mon_counts(P->mon, &k);
    sw_lcmlog_counts_t lc;
    sw_lcmlog_counts(P->lcmlog, &lc);
    sw_cli_regions_summary(&P->regions);
    if (!R->quiet || k.accepted == 0) {
        FILE *m = sw_cli_msg();
        fprintf(m,
                "swaywatch: %s: %ld events, %ld on the accel channel, %ld on other channels, "
                "%ld corrupted regions skipped\n",
                R->log, lc.events, lc.on_channel, lc.other_channels, lc.corrupt);
        fprintf(m, "swaywatch: %s: accel samples: %ld = accepted %ld + ", R->log, k.received,
                k.accepted);
        sw_cli_print_rejected(m, &k);
        fprintf(m,
                "; lost %ld (by seq), gaps %ld, restarts %ld, clock steps %ld; %ld states, "
                "%ld alarms\n",
                k.lost, k.gaps, k.restarts, k.clock_steps, k.states, k.alarms);
        if (k.contests > 0)
            fprintf(m,
                    "swaywatch: %s: contested %ld time%s: two timelines on the accel channel (a "
                    "forged or duplicated sender); the one the arrival times support was "
                    "replayed, the other's %ld samples evaluated beside it (INPUT_CONTESTED "
                    "alarms)\n",
                    R->log, k.contests, k.contests == 1 ? "" : "s", k.contested);
        const sw_auth_facts_t *au = sw_mon_auth_facts(P->mon);
        if (au) {
            fprintf(m, "swaywatch: %s: ", R->log);
            sw_cli_print_auth(m, au);
            fputc('\n', m);
        }
    }
    if (k.accepted > 0)
        return SW_EXIT_OK;
    sw_cli_error("%s: no usable accel_t sample on a channel matching '%s'%s", R->log, R->o->channel,
                 unusable_why(P));
    return SW_EXIT_USAGE;
}

static void lcmlog_close(sw_cli_reader_t *R)
{
    lcmlog_t *P = R->priv;
    if (!P)
        return;
    sw_mon_destroy(P->mon); /* and its stream */
    sw_lcmlog_close(P->lcmlog);
    sw_keyring_destroy(P->keys);
    if (P->lcm)
        lcm_destroy(P->lcm);
    free(P);
}

const sw_cli_source_t sw_cli_source_lcmlog = {
    .name = "an lcm-logger file",
    .picks = "--axis, --lat-axis, --vertical, --flip, --flip-lat",
    .takes = "lcm-logger files",
    .sniff = sw_lcmlog_sniff,
    .own = lcmlog_own,
    .init = lcmlog_init,
    .groups = lcmlog_groups,
    .prepare = lcmlog_prepare,
    .start = lcmlog_start,
    .feed = lcmlog_feed,
    .checked = lcmlog_checked,
    .report = lcmlog_report,
    .close = lcmlog_close,
};
