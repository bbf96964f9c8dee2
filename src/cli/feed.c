/* SPDX-License-Identifier: GPL-3.0-or-later */
/* feed.c - a CSV log into an engine through the reader and the input gate
 * (feed.h), and the verdict's plausibility check: what replay does with a
 * CSV log, in one place, so that every command reads a log the same way. */
#include "feed.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "interrupt.h"

typedef struct {
    const char *name;
    sw_csv_t *csv;
    sw_gate_t *gate;
    sw_cli_rejects_t rej;
    int quiet;
    int layout_said;
    sw_gate_take_fn take;
    void *take_user;
    const volatile sig_atomic_t *halt; /* may be NULL: the caller's stop (a cap reached) */
    int halted;
    /* SIGINT or SIGTERM: the rows after it (in the chunk being fed) are not
     * read; the pump stops after the chunk */
    int stopped;
    long unread, unread_rejected;
    sw_cli_unused_t *unused; /* the caller's record of what was not used */
} feed_t;

/* ---- what the reader chose ------------------------------------------------------- */

static const char *from_name(int from)
{
    return from == SW_CSV_FROM_HEADER   ? "from the header"
           : from == SW_CSV_FROM_OPTION ? "as given"
           : from == SW_CSV_FROM_VALUES ? "from the values"
                                        : "default";
}

/* "time: column 2 "Time (ms)", ms (from the header); accel: ..." once the
 * layout is fixed, and a unit given against the header's. */
static void say_layout(feed_t *F)
{
    sw_csv_layout_t L;
    if (F->layout_said || sw_csv_layout(F->csv, &L) != SW_OK || !L.ready)
        return;
    F->layout_said = 1;
    if (F->quiet)
        return;
    static const char *const role[2] = {"time", "accel"};
    FILE *m = sw_cli_msg();
    if (L.preamble > 0 && L.preamble_from == SW_CSV_FROM_OPTION)
        fprintf(m,
                "swaywatch: %s: skipped %ld line%s of preamble (--skip-lines); the table starts "
                "on line %ld\n",
                F->name, L.preamble, L.preamble == 1 ? "" : "s", L.first_line);
    else if (L.preamble > 0)
        fprintf(m,
                "swaywatch: %s: skipped %ld line%s of preamble; the table starts on line %ld "
                "(--skip-lines N says otherwise)\n",
                F->name, L.preamble, L.preamble == 1 ? "" : "s", L.first_line);
    fprintf(m, "swaywatch: %s: ", F->name);
    for (int r = 0; r < 2; r++) {
        fprintf(m, "%s%s: column %ld", r ? "; " : "", role[r], L.col[r] + 1);
        if (L.name[r][0])
            fprintf(m, " \"%s\"", L.name[r]);
        const char *u = sw_csv_unit_name(L.unit[r]);
        const char *how = "";
        if (r == 0 && L.date_order == SW_CSV_DATE_DMY)
            how = ", day first";
        else if (r == 0 && L.date_order == SW_CSV_DATE_MDY)
            how = ", month first";
        if (u[0])
            fprintf(m, ", %s%s%s", r == 0 && L.epoch ? "epoch " : "", u, how);
        else
            fprintf(m, ", x %g", L.scale[r]);
        fprintf(m, " (%s)", from_name(L.unit_from[r]));
    }
    fputc('\n', m);
    for (int r = 0; r < 2; r++)
        if (L.unit_from[r] == SW_CSV_FROM_OPTION && L.header_unit[r] != SW_CSV_UNIT_NONE &&
            L.header_unit[r] != L.unit[r])
            sw_cli_error("%s: --%s %s contradicts the header's \"%s\" (%s); using %s as given",
                         F->name, r ? "accel-unit" : "time-unit", sw_csv_unit_name(L.unit[r]),
                         L.name[r], sw_csv_unit_name(L.header_unit[r]),
                         sw_csv_unit_name(L.unit[r]));
}

static void after_chunk(void *user)
{
    say_layout(user);
}

/* The header did not say which column is which: it, and how to say it. */
static void explain_columns(const feed_t *F)
{
    const char *why = sw_csv_error_message(F->csv);
    sw_cli_error("%s: %s", F->name, why);
    if (strstr(why, "--date-order"))
        return; /* the reason names the option: the columns are not in question */
    const long n = sw_csv_header_count(F->csv);
    if (n > 0) {
        FILE *m = sw_cli_msg();
        fprintf(m, "swaywatch: %s: the header:", F->name);
        for (long i = 0; i < n; i++)
            fprintf(m, "%s %ld \"%s\"", i ? "," : "", i + 1, sw_csv_header_field(F->csv, i));
        fputc('\n', m);
    }
    sw_cli_error(
        "%s: say which with --time-col and --accel-col (a name or a 1-based index), "
        "and the units with --time-unit and --accel-unit where the names do not say "
        "them; --skip-lines N if the header is not the table's first line",
        F->name);
}

/* ---- rows into the gate ------------------------------------------------------------ */

static int on_row(void *user, long line, double t, double a_g, double a_z)
{
    feed_t *F = user;
    if (F->halted || (F->halt && *F->halt)) { /* the caller has all it can take */
        F->halted = F->rej.stop = 1;
        return 0;
    }
    if (F->stopped || sw_cli_signal) {
        F->stopped = F->rej.stop = 1;
        F->unread++;
        return 0;
    }
    if (F->rej.stop)
        return 1; /* --strict: nothing after the first bad row counts */
    say_layout(F);
    const sw_sample_t s = {.t = t,
                           .a_g = a_g,
                           .a_z = a_z,
                           .a_max = NAN,
                           .seq = SW_GATE_NO_SEQ,
                           .rx = NAN,
                           .wall = NAN,
                           .where = line};
    sw_gate_push(F->gate, &s); /* refused samples come back through on_gate_reject */
    return 0;
}

static void on_reject(void *user, long line, const char *reason)
{
    feed_t *F = user;
    say_layout(F); /* what the row was read as, before why it was refused */
    if (F->stopped) {
        F->unread_rejected++;
        return;
    }
    if (!F->rej.stop) /* --strict counts none after the first */
        sw_cli_unused_reject(F->unused, line, NULL, reason);
    sw_cli_rejects_add(&F->rej, line, reason);
}

static void on_gate_reject(void *user, const sw_sample_t *s, sw_gate_reject r, const char *text)
{
    feed_t *F = user;
    char buf[240];
    snprintf(buf, sizeof buf, "%s (%s)", text, sw_gate_reject_name(r));
    if (!F->rej.stop)
        sw_cli_unused_reject(F->unused, s->where, sw_cli_unused_gate_reason(r), buf);
    sw_cli_rejects_add(&F->rej, s->where, buf);
}

static void on_gate_take(void *user, double t, double a_g, double a_z, int restart)
{
    const feed_t *F = user;
    F->take(F->take_user, t, a_g, a_z, restart);
}

static void on_gate_event(void *user, const sw_gate_event_t *ev)
{
    feed_t *F = user;
    sw_cli_unused_event(F->unused, ev);
    if (F->quiet)
        return;
    const char *how = ev->restarted ? "the packages restart from rest"
                      : ev->bridged ? "bridged by linear interpolation"
                                    : "no time without samples";
    switch (ev->kind) {
        case SW_GATE_EV_GAP:
            sw_cli_error("%s:%ld: note: a gap of %.6g s without samples: %s%s", F->name, ev->where,
                         ev->span, how,
                         ev->incomplete
                             ? "; it overlaps rocking or an acceleration past the uplift "
                               "threshold: the verdict is incomplete"
                             : "");
            break;
        case SW_GATE_EV_RESTART:
            sw_cli_error(
                "%s:%ld: note: time goes back by %.6g s and the log goes on from there (a "
                "sensor restart, or a log played twice): %s%s",
                F->name, ev->where, -ev->span, how,
                ev->incomplete ? "; the verdict is incomplete" : "");
            break;
        case SW_GATE_EV_CLOCK_STEP:
            sw_cli_error("%s:%ld: note: the clock steps by %+.6g s: re-timed", F->name, ev->where,
                         ev->span);
            break;
        case SW_GATE_EV_RECONSTRUCT:
            if (ev->span > 0.0)
                sw_cli_error(
                    "%s:%ld: note: times repeat: the logger stamps whole units of %g s at a "
                    "higher rate; each run of equal times is spread evenly over its unit "
                    "(reconstructed)",
                    F->name, ev->where, ev->span);
            else
                sw_cli_error(
                    "%s:%ld: note: times repeat in runs (samples stamped in batches); each run "
                    "of equal times is spread evenly up to the next time (reconstructed)",
                    F->name, ev->where);
            break;
        case SW_GATE_EV_SEQ_RESTART:
        case SW_GATE_EV_CONTESTED:
        case SW_GATE_EV_UNCONTESTED: break;
    }
}

int sw_cli_feed_csv(sw_cli_logfile_t *lf, const sw_cli_csv_opts_t *co, const sw_cli_gate_t *go,
                    sw_engine_t *e, int quiet, sw_gate_take_fn take, void *take_user,
                    const volatile sig_atomic_t *halt, sw_cli_fed_t *out)
{
    int rc = SW_EXIT_USAGE, err = 0;
    char msg[256] = "";
    feed_t F = {
        .name = lf->name, .quiet = quiet, .take = take, .take_user = take_user, .halt = halt};
    F.rej = (sw_cli_rejects_t){.name = lf->name, .quiet = quiet, .strict = co->strict};
    memset(out, 0, sizeof *out);
    sw_cli_unused_init(&out->unused, 1);
    out->unused.listed = 1;
    F.unused = &out->unused;
    sw_gate_opts_t gopts;
    sw_cli_gate_opts(go, &gopts);
    gopts.on_event = on_gate_event;
    gopts.on_reject = on_gate_reject;
    gopts.on_take = take ? on_gate_take : NULL;
    gopts.user = &F;
    gopts.relative = -1;
    F.gate = sw_gate_create(e, &gopts, msg, sizeof msg);
    if (!F.gate) {
        sw_cli_error("%s: %s", lf->name, msg);
        return SW_EXIT_USAGE;
    }
    sw_csv_opts_t copts = co->csv;
    copts.any_order = 1; /* the gate judges time: a lone row off in time is that row's fault */
    F.csv = sw_csv_create(&copts, on_row, on_reject, &F, &err, msg, sizeof msg);
    if (!F.csv) {
        sw_cli_error("%s: %s", lf->name, msg[0] ? msg : sw_strerror(err));
        goto out;
    }
    int fr;
    rc = sw_cli_logfile_pump(lf, F.csv, &F.rej.stop, after_chunk, &F, &fr);
    if (rc != SW_EXIT_OK)
        goto out;
    if (F.stopped) { /* what was read, without the rest */
        sw_csv_counts_t k;
        sw_csv_counts(F.csv, &k);
        sw_gate_facts(F.gate, &out->facts);
        out->interrupted = 1;
        out->rows = k.rows - F.unread - F.unread_rejected;
        out->rejected = k.rejected - F.unread_rejected + sw_gate_rejected(&out->facts);
        sw_cli_rejects_summary(&F.rej);
        goto out;
    }
    if (F.halted) { /* the caller says why */
        out->halted = 1;
        rc = SW_EXIT_OK;
        goto out;
    }
    rc = SW_EXIT_USAGE;
    if (fr == SW_EAMBIGUOUS || fr == SW_ENOTFOUND) {
        explain_columns(&F); /* the reader's reason names the column, then the header */
        goto out;
    }
    if (fr < 0) {
        sw_cli_error("%s: %s", lf->name, sw_strerror(fr));
        rc = fr == SW_ENOMEM ? SW_EXIT_IO : SW_EXIT_USAGE;
        goto out;
    }
    if (!F.rej.stop)
        sw_gate_flush(F.gate);
    if (F.rej.stop) {
        sw_cli_error("%s: stopped at the first rejected row (--strict)", lf->name);
        goto out;
    }
    sw_csv_layout_t layout;
    if (sw_csv_layout(F.csv, &layout) == SW_OK && layout.ready)
        out->time_unit = layout.unit[0];
    sw_csv_counts_t counts;
    sw_csv_counts(F.csv, &counts);
    sw_gate_facts(F.gate, &out->facts);
    out->facts.upstream_rejected = counts.rejected; /* rows the reader could not use */
    out->rows = counts.rows;
    out->rejected = counts.rejected + sw_gate_rejected(&out->facts);
    sw_cli_rejects_summary(&F.rej);
    if (out->facts.reconstructed > 0 && !quiet)
        sw_cli_error("%s: %ld of %ld times reconstructed (repeated stamps spread over their unit)",
                     lf->name, out->facts.reconstructed, out->rows);
    if (out->facts.accepted <= 0) {
        sw_cli_error("%s: no usable samples (%ld data rows, %ld rejected)%s", lf->name, out->rows,
                     out->rejected,
                     out->rows > 0 ? ": the lines above say why; check the columns and units "
                                     "(--time-col, --time-unit, --accel-col, --accel-unit)"
                                   : "");
        goto out;
    }
    rc = SW_EXIT_OK;
out:
    sw_csv_destroy(F.csv);
    sw_gate_destroy(F.gate);
    return rc;
}

/* ---- the verdict's check ----------------------------------------------------------- */

int sw_cli_feed_verdict(const char *name, const sw_gate_facts_t *f, const sw_cli_gate_t *go,
                        int vert, int quiet, sw_cli_run_t *run)
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
            "%s: check the columns and units (see the lines above; --time-col, "
            "--time-unit, --accel-col, --accel-unit), or give --force for a verdict "
            "marked as forced",
            name);
        return SW_EXIT_USAGE;
    }
    run->forced = 1;
    snprintf(run->check, sizeof run->check, "%s", why);
    sw_cli_error("%s: verdict forced (--force) although %s", name, why);
    return SW_EXIT_OK;
}
