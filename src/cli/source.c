/* SPDX-License-Identifier: GPL-3.0-or-later */
/* source.c - a log read the way replay reads it (source.h): CSV logs
 * streamed in fixed chunks through the CSV reader and the input gate
 * (feed.c), lcm-logger files read in-process (eventlog.h, never through
 * the network) into the monitor core, which refuses bad, duplicate and
 * late samples as the live monitor does. */
#include "source.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "cost.h"
#include "interrupt.h"

void sw_cli_read_opts_init(sw_cli_read_opts_t *o)
{
    memset(o, 0, sizeof *o);
    sw_cli_csv_opts_init(&o->copts);
    sw_cli_gate_init(&o->gate);
#ifdef SW_HAVE_LCM
    sw_cli_mon_opts_init(&o->mo);
    o->channel = SW_MON_ACCEL_CHANNEL;
#endif
}

#ifdef SW_HAVE_LCM
#define RD(f) SW_CLI_AT(sw_cli_read_opts_t, f)

/* --accel-channel, as monitor calls it; --channel, its name before, still
 * works. */
const sw_cli_option_t sw_cli_channel_options[] = {
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
#endif

sw_cli_given_t sw_cli_source_given(const sw_cli_group_t *g, size_t ng,
                                   const sw_cli_option_t *const *extra)
{
    sw_cli_given_t out = {NULL, NULL};
    const sw_cli_group_t *lcm = NULL;
    for (size_t i = 0; i < ng; i++) {
        if (!g[i].given)
            continue;
        if (g[i].rows == sw_cli_csv_options)
            out.csv = g[i].given->long_name;
#ifdef SW_HAVE_LCM
        int only = g[i].rows == sw_cli_channel_options || g[i].rows == sw_cli_lcm_input_options;
        for (size_t k = 0; extra && extra[k]; k++) only |= g[i].rows == extra[k];
        if (only && (!lcm || g[i].given_at < lcm->given_at))
            lcm = &g[i];
#else
        (void)extra;
#endif
    }
    out.lcm = lcm ? lcm->given->long_name : NULL;
    return out;
}

/* ---- opening --------------------------------------------------------------------- */

int sw_cli_reader_open(sw_cli_reader_t *R, const char *log, const sw_cli_read_opts_t *o, int quiet,
                       sw_cli_given_t given)
{
    int rc;
    R->log = log;
    R->o = o;
    R->quiet = quiet;
    if ((rc = sw_cli_logfile_open(&R->lf, log)) != SW_EXIT_OK)
        return rc;
    R->src = sw_cli_logfile_source(&R->lf);
    if (!R->src->available) {
        sw_cli_error("%s: lcm-logger files need the LCM build", log);
        return SW_EXIT_USAGE;
    }
    if (R->src->kind == SW_CLI_SRC_LCMLOG && given.csv) {
        sw_cli_error("%s: --%s is for CSV logs; this is an lcm-logger file", log, given.csv);
        return SW_EXIT_USAGE;
    }
    if (R->src->kind == SW_CLI_SRC_CSV && given.lcm) {
        sw_cli_error("%s: option '--%s' is for lcm-logger files, and this is a CSV log", R->lf.name,
                     given.lcm);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

int sw_cli_reader_prepare(sw_cli_reader_t *R)
{
#ifdef SW_HAVE_LCM
    if (R->src->kind != SW_CLI_SRC_LCMLOG)
        return SW_EXIT_OK;
    int err = 0;
    if (R->o->key_file && !(R->keys = sw_cli_key_load("--key", R->o->key_file, &err)))
        return err;
    R->regions = (sw_cli_regions_t){.name = R->lf.name, .quiet = R->quiet};
    const sw_lcmlog_opts_t lo = {
        .channel = R->o->channel,
        .strict = R->o->copts.strict,
        .on_region = sw_cli_print_region,
        .user = &R->regions,
        .stop = &sw_cli_signal,
    };
    /* The log as opened, its first chunk included: a pipe is read once. */
    R->lcmlog = sw_lcmlog_open_stream(R->lf.in, R->lf.buf, R->lf.len, &lo, &err);
    if (R->lcmlog)
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
#else
    (void)R;
    return SW_EXIT_OK;
#endif
}

/* ---- the engine ------------------------------------------------------------------- */

#ifdef SW_HAVE_LCM
static int lcmlog_engine(sw_cli_reader_t *R, const sw_scene_t *scenes, size_t n,
                         const sw_engine_opts_t *eo, int shared)
{
    sw_mon_opts_t mo = R->o->mo;
    if (sw_cli_mon_gate(&mo, &R->o->gate) != SW_EXIT_OK)
        return SW_EXIT_USAGE;
    mo.reserve_rate = R->reserve_rate > 0.0 ? R->reserve_rate : -1.0;
    mo.accel_scale = R->o->copts.csv.accel_scale;
    mo.flip = R->o->copts.csv.flip;
    mo.on_state = eo->on_state;
    mo.on_event = eo->on_event;
    mo.on_take = R->take;
    mo.user = eo->user;
    mo.keys = R->keys;
    char msg[512] = "";
    R->mon = sw_mon_create(scenes, n, eo, &mo, R->publish, msg, sizeof msg);
    if (!R->mon) {
        sw_cli_error("cannot start the engine: %s", msg[0] ? msg : "unknown reason");
        return SW_EXIT_USAGE;
    }
    if (!shared)
        sw_cli_warn_scene_cost(scenes, n, eo);
    R->e = sw_mon_engine(R->mon);
    return SW_EXIT_OK;
}
#endif

int sw_cli_reader_engine(sw_cli_reader_t *R, const sw_scene_t *scenes, size_t n,
                         const sw_engine_opts_t *eo, int shared)
{
    R->user = eo->user;
#ifdef SW_HAVE_LCM
    if (R->src->kind == SW_CLI_SRC_LCMLOG)
        return lcmlog_engine(R, scenes, n, eo, shared);
#endif
    if (!shared) {
        R->e = sw_cli_engine_create(scenes, n, eo);
    } else { /* a batch measured the scenes' cost once */
        int err = 0;
        char msg[512] = "";
        R->e = sw_engine_create(scenes, n, eo, &err, msg, sizeof msg);
        if (!R->e)
            sw_cli_error("cannot start the engine: %s", msg[0] ? msg : sw_strerror(err));
    }
    return R->e ? SW_EXIT_OK : SW_EXIT_USAGE;
}

int sw_cli_reader_risk(sw_cli_reader_t *R, const sw_cli_opts_t *o, const sw_scene_t *scenes,
                       size_t n)
{
#ifdef SW_HAVE_LCM
    if (R->src->kind == SW_CLI_SRC_LCMLOG) {
        R->risk = sw_mon_risk(R->mon);
        R->risk_owned = 0;
    }
#endif
    if (!R->risk) {
        if (!(R->risk = sw_cli_risk_create(o, scenes, n)))
            return SW_EXIT_USAGE;
        R->risk_owned = 1;
    }
    R->run.risk = R->risk;
    return SW_EXIT_OK;
}

/* ---- reading ----------------------------------------------------------------------- */

/* Stream the CSV log through the reader and the input gate into the
 * engine; then the verdict's check. */
static int feed_csv(sw_cli_reader_t *R)
{
    sw_cli_fed_t fed;
    int rc = sw_cli_feed_csv(&R->lf, &R->o->copts, &R->o->gate, R->e, R->quiet, R->take, R->user,
                             R->halt, &fed);
    if (rc != SW_EXIT_OK)
        return rc;
    if ((R->halted = fed.halted))
        return SW_EXIT_OK; /* the command says why */
    R->run.samples_read = fed.rows;
    R->run.samples_rejected = fed.rejected;
    R->run.unused = fed.unused;
    R->accepted = fed.facts.accepted;
    R->interrupted = fed.interrupted;
    /* dates: a date-time column, or epoch times (the gate timed the log
     * from its first sample) that fall in the years of recordings */
    const sw_gate_facts_t *f = &fed.facts;
    if (fed.facts.accepted > 0 && (fed.time_unit == SW_CSV_UNIT_DATETIME ||
                                   (f->t_origin != 0.0 && sw_cli_epoch_plausible(f->t_origin)))) {
        R->run.absolute = 1;
        R->run.abs_base = 0.0; /* the source's times are dates */
        R->run.abs_start = f->t_first;
        R->run.abs_end = f->t_last;
        R->run.abs_from = fed.time_unit == SW_CSV_UNIT_DATETIME ? "the log's date-times"
                                                                : "the log's epoch times";
    }
    if (fed.interrupted)
        return SW_EXIT_OK; /* no check, no settling: the command says why */
    return sw_cli_feed_verdict(R->lf.name, &fed.facts, &R->o->gate,
                               R->o->copts.csv.vert_col != NULL, R->quiet, &R->run);
}

#ifdef SW_HAVE_LCM
/* The samples the monitor core refused, by reason (it keeps no places). */
static void lcmlog_unused(sw_cli_reader_t *R, const sw_mon_counts_t *k)
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
static void lcmlog_dates(sw_cli_reader_t *R, const sw_gate_facts_t *f)
{
    const double origin = (double)sw_mon_origin(R->mon) / 1e6; /* s, engine t = 0 */
    sw_lcmlog_counts_t lc;
    sw_lcmlog_counts(R->lcmlog, &lc);
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

/* Signed samples read without --key: said (always when the log is
 * refused, rc not SW_EXIT_OK: forged samples among them may be why). */
static void unchecked_note(const sw_cli_reader_t *R, const sw_mon_counts_t *k, int rc)
{
    if (k->macs_unchecked > 0 && (!R->quiet || rc != SW_EXIT_OK))
        fprintf(sw_cli_msg(),
                "swaywatch: %s: %ld samples carry a MAC that was not checked: give the sender's "
                "key file (--key FILE) to refuse forged and replayed samples\n",
                R->log, k->macs_unchecked);
}

static int feed_lcmlog(sw_cli_reader_t *R)
{
    const int lr = sw_mon_feed_log(R->mon, R->lcmlog, R->o->copts.strict);
    if (lr == SW_ENOTFOUND) {
        sw_cli_error("%s: cannot read: %s", R->lf.name, strerror(errno));
        return SW_EXIT_IO;
    }
    if (lr != SW_OK) {
        sw_cli_error("%s: stopped at the first bad event or sample (--strict)", R->log);
        return SW_EXIT_USAGE;
    }
    sw_mon_flush(R->mon);
    sw_mon_counts_t k;
    sw_mon_counts(R->mon, &k);
    if (R->o->copts.strict && sw_mon_rejected(&k) > 0) { /* the last sample, held */
        sw_cli_error("%s: stopped at the first bad event or sample (--strict)", R->log);
        return SW_EXIT_USAGE;
    }
    R->run.samples_read = k.received;
    R->run.samples_rejected = k.received - k.accepted;
    R->accepted = k.accepted;
    R->interrupted = sw_cli_signal != 0;
    if (k.accepted == 0 || R->interrupted) {
        unchecked_note(R, &k, SW_EXIT_USAGE);
        return SW_EXIT_OK;
    }
    sw_gate_facts_t f;
    sw_mon_facts(R->mon, &f);
    /* not accel_t, NaN on an axis; not what failed authentication: those
     * samples are known not to be the sensor's, not a sign of a misread log */
    const sw_auth_facts_t *au = sw_mon_auth_facts(R->mon);
    f.upstream_rejected =
        k.received - f.received - (au ? au->checked - au->refused[SW_AUTH_OK] : 0);
    lcmlog_unused(R, &k);
    lcmlog_dates(R, &f);
    const int rc =
        sw_cli_feed_verdict(R->log, &f, &R->o->gate, R->o->mo.vertical >= 0, R->quiet, &R->run);
    unchecked_note(R, &k, rc);
    return rc;
}
#endif

int sw_cli_reader_feed(sw_cli_reader_t *R)
{
#ifdef SW_HAVE_LCM
    if (R->src->kind == SW_CLI_SRC_LCMLOG)
        return feed_lcmlog(R);
#endif
    return feed_csv(R);
}

void sw_cli_reader_settle(sw_cli_reader_t *R, double settle)
{
    if (R->interrupted || R->halted || sw_cli_signal || R->accepted <= 0)
        return;
#ifdef SW_HAVE_LCM
    if (R->src->kind == SW_CLI_SRC_LCMLOG && !(settle > 0.0))
        return;
#endif
    /* a signal ends the free motion too: --settle may be long */
    sw_engine_set_stop(R->e, &sw_cli_signal);
    sw_engine_finish(R->e, settle);
    sw_engine_set_stop(R->e, NULL);
}

/* ---- after the run ------------------------------------------------------------------- */

#ifdef SW_HAVE_LCM
/* Why no sample was usable, when authentication refused them all: what
 * the refusals say of the log, and the option that reads it. */
static const char *unusable_why(const sw_cli_reader_t *R)
{
    const sw_auth_facts_t *au = sw_mon_auth_facts(R->mon);
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
#endif

int sw_cli_reader_report(sw_cli_reader_t *R)
{
#ifdef SW_HAVE_LCM
    if (R->src->kind != SW_CLI_SRC_LCMLOG)
        return SW_EXIT_OK;
    sw_mon_counts_t k;
    sw_mon_counts(R->mon, &k);
    sw_lcmlog_counts_t lc;
    sw_lcmlog_counts(R->lcmlog, &lc);
    sw_cli_regions_summary(&R->regions);
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
        const sw_auth_facts_t *au = sw_mon_auth_facts(R->mon);
        if (au) {
            fprintf(m, "swaywatch: %s: ", R->log);
            sw_cli_print_auth(m, au);
            fputc('\n', m);
        }
    }
    if (k.accepted > 0)
        return SW_EXIT_OK;
    sw_cli_error("%s: no usable accel_t sample on a channel matching '%s'%s", R->log, R->o->channel,
                 unusable_why(R));
    return SW_EXIT_USAGE;
#else
    (void)R;
    return SW_EXIT_OK;
#endif
}

void sw_cli_reader_close(sw_cli_reader_t *R)
{
    if (R->risk_owned)
        sw_risk_destroy(R->risk);
    R->risk = NULL;
    R->risk_owned = 0;
    R->run.risk = NULL;
#ifdef SW_HAVE_LCM
    if (R->mon)
        R->e = NULL; /* the monitor's */
    sw_mon_destroy(R->mon);
    sw_lcmlog_close(R->lcmlog);
    sw_keyring_destroy(R->keys);
    R->mon = NULL;
    R->lcmlog = NULL;
    R->keys = NULL;
#endif
    sw_engine_destroy(R->e);
    R->e = NULL;
    sw_cli_logfile_close(&R->lf);
}
