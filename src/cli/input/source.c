/* SPDX-License-Identifier: GPL-3.0-or-later */
/* source.c - a log read the way replay reads it (source.h), whatever its
 * source: the file opened and its source chosen by its first bytes, the
 * options of other sources refused, the source's stream made and fed,
 * the verdict's plausibility check, the settling.  What differs between
 * sources is in their rows (source_csv.c, source_lcmlog.c). */
#include "source.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cost.h"
#include "interrupt.h"

void sw_cli_read_opts_init(sw_cli_read_opts_t *o)
{
    memset(o, 0, sizeof *o);
    sw_cli_gate_init(&o->gate);
    for (size_t i = 0; sw_cli_source_at(i); i++)
        if (sw_cli_source_at(i)->init)
            sw_cli_source_at(i)->init(o);
}

size_t sw_cli_source_groups(sw_cli_read_opts_t *o, sw_cli_group_t *g, int publish)
{
    size_t n = 0;
    for (size_t i = 0; sw_cli_source_at(i); i++)
        if (sw_cli_source_at(i)->groups)
            n += sw_cli_source_at(i)->groups(o, g + n, publish);
    return n;
}

/* The source whose own option table rows are, or NULL. */
static const sw_cli_source_t *owner(const sw_cli_option_t *rows)
{
    for (size_t i = 0; sw_cli_source_at(i); i++) {
        const sw_cli_source_t *s = sw_cli_source_at(i);
        for (size_t k = 0; s->own && s->own[k]; k++)
            if (s->own[k] == rows)
                return s;
    }
    return NULL;
}

sw_cli_given_t sw_cli_source_given(const sw_cli_group_t *g, size_t ng)
{
    sw_cli_given_t out;
    memset(&out, 0, sizeof out);
    int at[SW_CLI_SOURCES_MAX] = {0};
    for (size_t i = 0; i < ng; i++) {
        const sw_cli_source_t *s = g[i].given ? owner(g[i].rows) : NULL;
        if (!s)
            continue;
        size_t k = 0;
        while (k < out.n && out.src[k] != s) k++;
        if (k == out.n) {
            if (out.n == SW_CLI_SOURCES_MAX)
                continue;
            out.n++;
        } else if (at[k] <= g[i].given_at) {
            continue; /* an option of this source was given before */
        }
        out.src[k] = s;
        out.opt[k] = g[i].given->long_name;
        at[k] = g[i].given_at;
    }
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
    const char *needs = "";
    if (!(R->src = sw_cli_source_of(R->lf.buf, R->lf.len, &needs))) {
        sw_cli_error("%s: %s", log, needs);
        return SW_EXIT_USAGE;
    }
    for (size_t i = 0; i < given.n; i++)
        if (given.src[i] != R->src) {
            sw_cli_error("%s: option '--%s' is for %s, and this is %s", R->lf.name, given.opt[i],
                         given.src[i]->takes, R->src->name);
            return SW_EXIT_USAGE;
        }
    return SW_EXIT_OK;
}

int sw_cli_reader_prepare(sw_cli_reader_t *R)
{
    return R->src->prepare ? R->src->prepare(R) : SW_EXIT_OK;
}

/* ---- the stream ------------------------------------------------------------------- */

int sw_cli_reader_engine(sw_cli_reader_t *R, const sw_scene_t *scenes, size_t n,
                         const sw_engine_opts_t *eo, int shared)
{
    R->user = eo->user;
    const int rc = R->src->start(R, scenes, n, eo);
    if (rc != SW_EXIT_OK)
        return rc;
    R->e = sw_stream_engine(R->st);
    R->risk = sw_stream_risk(R->st);
    if (!shared) /* a batch measured the scenes' cost once */
        sw_cli_warn_scene_cost(scenes, n, eo);
    return SW_EXIT_OK;
}

int sw_cli_reader_risk(sw_cli_reader_t *R, const sw_cli_opts_t *o, const sw_scene_t *scenes,
                       size_t n)
{
    R->run.risk = R->risk;
    R->run.stream = R->st;
    sw_cli_warn_no_reserve(R->risk, 0, n, scenes);
    sw_cli_warn_reserve_cost(R->risk, 0, n, scenes, o->reserve_rate);
    return SW_EXIT_OK;
}

/* ---- reading ----------------------------------------------------------------------- */

/* The plausibility check of a fed log (gate.h) and the vertical channel's
 * gravity: SW_EXIT_OK with run's check and forced set (a warning or a
 * forced verdict, printed), or SW_EXIT_USAGE with the reason and what to
 * do printed (no verdict).  vert: the source has a vertical channel. */
static int verdict(const char *name, const char *picks, const sw_gate_facts_t *f,
                   const sw_cli_gate_t *go, int vert, int quiet, sw_cli_run_t *run)
{
    sw_gate_limits_t lim;
    sw_cli_gate_limits(go, &lim);
    char why[320] = "";
    int r = sw_gate_check(f, &lim, why, sizeof why);
    /* gravity counted twice: a vertical channel reading +1 g on average
     * that nobody said includes it */
    if (r != SW_GATE_REFUSE && vert && go->vert_gravity < 0 &&
        fabs(f->mean_z - SW_G0) < 0.15 * SW_G0) {
        snprintf(why, sizeof why,
                 "the vertical channel reads %.3g g on average: it includes gravity (an "
                 "accelerometer), which the model would count twice; say "
                 "--vert-includes-gravity (or --vert-excludes-gravity if it does not)",
                 f->mean_z / SW_G0);
        r = SW_GATE_REFUSE;
    }
    run->facts = *f;
    run->have_facts = 1;
    if (r == SW_GATE_WARN) {
        snprintf(run->check, sizeof run->check, "%s", why);
        if (!quiet)
            sw_cli_error("%s: warning: %s", name, why);
        return SW_EXIT_OK;
    }
    if (r != SW_GATE_REFUSE)
        return SW_EXIT_OK;
    if (!go->force) {
        sw_cli_error("%s: no verdict: %s", name, why);
        sw_cli_error(
            "%s: check the channels and units (see the lines above; %s), or give "
            "--force for a verdict marked as forced",
            name, picks);
        return SW_EXIT_USAGE;
    }
    run->forced = 1;
    snprintf(run->check, sizeof run->check, "%s", why);
    sw_cli_error("%s: verdict forced (--force) although %s", name, why);
    return SW_EXIT_OK;
}

int sw_cli_reader_feed(sw_cli_reader_t *R)
{
    sw_gate_facts_t f;
    int vert = 0;
    memset(&f, 0, sizeof f);
    int rc = R->src->feed(R, &f, &vert);
    if (rc != SW_EXIT_OK || R->halted)
        return rc;
    /* a stopped or empty log: no check; the command, or the report, says why */
    const int checked = !R->interrupted && R->accepted > 0;
    if (checked)
        rc = verdict(R->lf.name, R->src->picks, &f, &R->o->gate, vert, R->quiet, &R->run);
    if (R->src->checked)
        R->src->checked(R, checked ? rc : SW_EXIT_USAGE);
    return rc;
}

void sw_cli_reader_settle(sw_cli_reader_t *R, double settle)
{
    if (R->interrupted || R->halted || sw_cli_signal || R->accepted <= 0 || !(settle > 0.0))
        return;
    /* a signal ends the free motion too: --settle may be long */
    sw_engine_set_stop(R->e, &sw_cli_signal);
    sw_stream_settle(R->st, settle);
    sw_engine_set_stop(R->e, NULL);
}

/* ---- after the run ------------------------------------------------------------------- */

int sw_cli_reader_report(sw_cli_reader_t *R)
{
    return R->src->report ? R->src->report(R) : SW_EXIT_OK;
}

void sw_cli_reader_close(sw_cli_reader_t *R)
{
    if (R->src && R->src->close)
        R->src->close(R); /* the stream, and what the source made */
    R->st = NULL;
    R->e = NULL;
    R->risk = NULL;
    R->run.risk = NULL;
    R->run.stream = NULL;
    R->priv = NULL;
    sw_cli_logfile_close(&R->lf);
}
