/* SPDX-License-Identifier: GPL-3.0-or-later */
/* source_csv.c - the CSV source (source.h): a log streamed in fixed
 * chunks through the CSV reader (csv.h, choosing the columns and units
 * and saying which) into the input stream, every refused row and every
 * gap or restart reported with its line.  The stream judges time: a lone
 * row off in time is that row's fault, not the log's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "interrupt.h"
#include "source.h"

/* The source's own, from prepare to close. */
typedef struct {
    sw_cli_reader_t *R;
    const char *name;
    sw_csv_t *csv;
    sw_cli_rejects_t rej;
    int quiet;
    int layout_said;
    /* the command's engine callbacks: the stream's user is this */
    sw_state_fn on_state;
    sw_event_fn on_event;
    void *user;
    int halted; /* R->halt was set: the caller has all it can take */
    /* SIGINT or SIGTERM: the rows after it (in the chunk being fed) are not
     * read; the pump stops after the chunk */
    int stopped;
    long unread, unread_rejected;
    sw_cli_unused_t *unused; /* the run's record of what was not used */
    int any_depth;           /* a scene gives package.depth */
    int lateral;             /* the log's lateral column drives their lateral planes */
    int lat_col_unused;      /* --lat-col was given, and said not to be used */
} feed_t;

/* ---- what the reader chose ------------------------------------------------------- */

static const char *from_name(int from)
{
    return from == SW_CSV_FROM_HEADER   ? "from the header"
           : from == SW_CSV_FROM_OPTION ? "as given"
           : from == SW_CSV_FROM_VALUES ? "from the values"
                                        : "default";
}

/* Why a lateral column is not read. */
static const char *unused_why(const feed_t *F)
{
    return !F->any_depth ? "no scene gives package.depth, the size across the truck the "
                           "lateral plane rocks over"
                         : "this command judges the plane along the truck only";
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
    if (L.col[3] >= 0) {
        fprintf(m, "; lateral: column %ld", L.col[3] + 1);
        if (L.name[3][0])
            fprintf(m, " \"%s\"", L.name[3]);
        const char *u = sw_csv_unit_name(L.unit[3]);
        if (u[0])
            fprintf(m, ", %s", u);
        else
            fprintf(m, ", x %g", L.scale[3]);
        fprintf(m, " (%s)", from_name(L.unit_from[3]));
    }
    fputc('\n', m);
    if (L.lat_unread >= 0 && !F->lat_col_unused)
        sw_cli_error("%s: the lateral column %ld \"%s\" is not used: %s", F->name, L.lat_unread + 1,
                     L.name[3], unused_why(F));
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

/* ---- rows into the stream ---------------------------------------------------------- */

static int on_row(void *user, long line, double t, double a_g, double a_z)
{
    feed_t *F = user;
    if (F->halted || (F->R->halt && *F->R->halt)) { /* the caller has all it can take */
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
                           .where = line,
                           .a_y = sw_csv_lateral(F->csv)};
    sw_stream_push(F->R->st, &s); /* refused samples come back through on_gate_reject */
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
    F->R->take(F->R->user, t, a_g, a_z, restart);
}

static void on_gate_take_lat(void *user, double t, double a_g, double a_y, double a_z, int restart)
{
    const feed_t *F = user;
    F->R->take_lat(F->R->user, t, a_g, a_y, a_z, restart);
}

static void on_state(void *user, const sw_output_t *out)
{
    const feed_t *F = user;
    F->on_state(F->user, out);
}

static void on_event(void *user, const sw_event_t *ev)
{
    const feed_t *F = user;
    F->on_event(F->user, ev);
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

/* ---- the source's calls ------------------------------------------------------------- */

/* Dates: a date-time column (time_unit), or epoch times (the gate timed
 * the log from its first sample) that fall in the years of recordings. */
static void dates(sw_cli_reader_t *R, const sw_gate_facts_t *f, int time_unit)
{
    if (f->accepted <= 0 || !(time_unit == SW_CSV_UNIT_DATETIME ||
                              (f->t_origin != 0.0 && sw_cli_epoch_plausible(f->t_origin))))
        return;
    R->run.absolute = 1;
    R->run.abs_base = 0.0; /* the source's times are dates */
    R->run.abs_start = f->t_first;
    R->run.abs_end = f->t_last;
    R->run.abs_from =
        time_unit == SW_CSV_UNIT_DATETIME ? "the log's date-times" : "the log's epoch times";
}

static int csv_prepare(sw_cli_reader_t *R)
{
    feed_t *F = calloc(1, sizeof *F);
    if (!F) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    F->R = R;
    F->name = R->lf.name;
    F->quiet = R->quiet;
    R->priv = F;
    return SW_EXIT_OK;
}

/* Whether the log has a lateral column to read, decided before the
 * stream is made (its engine has lateral planes or not): --lat-col, or
 * the header's, read by a reader of its own from the first chunk of the
 * file (the header is in it); a header that does not say it without
 * doubt leaves it to the reader of the run, which refuses the log. */
static int peek_lateral(const sw_cli_reader_t *R)
{
    const sw_csv_opts_t *o = &R->o->copts.csv;
    if (o->lat_col)
        return 1;
    if (!o->infer || !R->lf.buf || R->lf.len == 0)
        return 0;
    sw_csv_opts_t po = *o;
    po.lateral = 1;
    po.any_order = 1;
    sw_csv_t *c = sw_csv_create(&po, NULL, NULL, NULL, NULL, NULL, 0);
    if (!c)
        return 0;
    int rc = sw_csv_feed(c, R->lf.buf, R->lf.len);
    sw_csv_layout_t L;
    if (rc >= 0 && (sw_csv_layout(c, &L) != SW_OK || !L.ready))
        rc = sw_csv_finish(c);
    const int lat = rc >= 0 && sw_csv_layout(c, &L) == SW_OK && L.ready && L.col[3] >= 0;
    sw_csv_destroy(c);
    return lat || rc == SW_EAMBIGUOUS; /* several: the run's reader refuses, naming them */
}

/* The stream: the gate's options as given, times relative when they look
 * like an epoch; the command's callbacks through F.  The engine has
 * lateral planes when the command reports them, a scene gives a depth and
 * the log has a lateral column. */
static int csv_start(sw_cli_reader_t *R, const sw_scene_t *scenes, size_t n,
                     const sw_engine_opts_t *eo)
{
    feed_t *F = R->priv;
    F->on_state = eo->on_state;
    F->on_event = eo->on_event;
    F->user = eo->user;
    for (size_t k = 0; k < n; k++) F->any_depth |= sw_scene_has_depth(&scenes[k]);
    F->lateral = R->lateral && F->any_depth && peek_lateral(R);
    if (R->lateral && F->any_depth && !F->lateral && !F->quiet)
        sw_cli_error(
            "%s: note: no lateral column (--lat-col NAME|N names one): the packages "
            "with a depth are judged along the truck only",
            F->name);
    sw_stream_opts_t so = {
        .engine = *eo,
        .risk = {.reserve_rate = R->reserve_rate > 0.0 ? R->reserve_rate : -1.0,
                 .min_only = R->reserve_min_only},
        .hysteresis = -1.0,
        .on_state = eo->on_state ? on_state : NULL,
        .on_event = eo->on_event ? on_event : NULL,
        .on_input = on_gate_event,
        .on_reject = on_gate_reject,
        .on_take = R->take ? on_gate_take : NULL,
        .user = F,
        .on_take_lat = R->take_lat ? on_gate_take_lat : NULL,
    };
    so.engine.lateral = F->lateral;
    sw_cli_gate_opts(&R->o->gate, &so.gate);
    so.gate.relative = -1;
    int err = 0;
    char msg[512] = "";
    if (!(R->st = sw_stream_create(scenes, n, &so, &err, msg, sizeof msg))) {
        sw_cli_error("cannot start the engine: %s", msg[0] ? msg : sw_strerror(err));
        return err == SW_ENOMEM ? SW_EXIT_IO : SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* The log through the reader into the stream, then its end.  A SIGINT or
 * SIGTERM stops it between rows (R->interrupted; the stream is not
 * finished, the rest of the chunk read is not counted); so does R->halt
 * (R->halted). */
static int csv_feed(sw_cli_reader_t *R, sw_gate_facts_t *f, int *vert)
{
    feed_t *F = R->priv;
    const sw_cli_csv_opts_t *co = &R->o->copts;
    int rc = SW_EXIT_USAGE, err = 0;
    char msg[256] = "";
    F->rej = (sw_cli_rejects_t){.name = F->name, .quiet = F->quiet, .strict = co->strict};
    sw_cli_unused_init(&R->run.unused, 1);
    R->run.unused.listed = 1;
    F->unused = &R->run.unused;
    *vert = co->csv.vert_col != NULL;
    sw_csv_opts_t copts = co->csv;
    copts.any_order = 1; /* the gate judges time: a lone row off in time is that row's fault */
    copts.lateral = F->lateral;
    if (!F->lateral && copts.lat_col) {
        if (!F->quiet)
            sw_cli_error("%s: --lat-col %s is not used: %s", F->name, copts.lat_col, unused_why(F));
        copts.lat_col = NULL;
        F->lat_col_unused = 1;
    }
    F->csv = sw_csv_create(&copts, on_row, on_reject, F, &err, msg, sizeof msg);
    if (!F->csv) {
        sw_cli_error("%s: %s", F->name, msg[0] ? msg : sw_strerror(err));
        return SW_EXIT_USAGE;
    }
    int fr;
    if ((rc = sw_cli_logfile_pump(&R->lf, F->csv, &F->rej.stop, after_chunk, F, &fr)) != SW_EXIT_OK)
        return rc;
    sw_csv_counts_t counts;
    sw_csv_counts(F->csv, &counts);
    if (F->stopped) { /* what was read, without the rest */
        sw_gate_facts(sw_stream_gate(R->st), f);
        R->interrupted = 1;
        R->run.samples_read = counts.rows - F->unread - F->unread_rejected;
        R->run.samples_rejected = counts.rejected - F->unread_rejected + sw_gate_rejected(f);
        R->accepted = f->accepted;
        sw_cli_rejects_summary(&F->rej);
        dates(R, f, SW_CSV_UNIT_NONE); /* the layout is not asked after a signal */
        return SW_EXIT_OK;
    }
    if (F->halted) { /* the caller says why */
        R->halted = 1;
        return SW_EXIT_OK;
    }
    if (fr == SW_EAMBIGUOUS || fr == SW_ENOTFOUND) {
        explain_columns(F); /* the reader's reason names the column, then the header */
        return SW_EXIT_USAGE;
    }
    if (fr < 0) {
        sw_cli_error("%s: %s", F->name, sw_strerror(fr));
        return fr == SW_ENOMEM ? SW_EXIT_IO : SW_EXIT_USAGE;
    }
    if (!F->rej.stop)
        sw_stream_finish(R->st);
    if (F->rej.stop) {
        sw_cli_error("%s: stopped at the first rejected row (--strict)", F->name);
        return SW_EXIT_USAGE;
    }
    sw_csv_counts(F->csv, &counts);
    sw_gate_facts(sw_stream_gate(R->st), f);
    f->upstream_rejected = counts.rejected; /* rows the reader could not use */
    R->run.samples_read = counts.rows;
    R->run.samples_rejected = counts.rejected + sw_gate_rejected(f);
    R->accepted = f->accepted;
    sw_cli_rejects_summary(&F->rej);
    if (f->reconstructed > 0 && !F->quiet)
        sw_cli_error("%s: %ld of %ld times reconstructed (repeated stamps spread over their unit)",
                     F->name, f->reconstructed, R->run.samples_read);
    if (f->accepted <= 0) {
        sw_cli_error("%s: no usable samples (%ld data rows, %ld rejected)%s", F->name,
                     R->run.samples_read, R->run.samples_rejected,
                     R->run.samples_read > 0
                         ? ": the lines above say why; check the columns and units "
                           "(--time-col, --time-unit, --accel-col, --accel-unit)"
                         : "");
        return SW_EXIT_USAGE;
    }
    sw_csv_layout_t layout;
    dates(R, f,
          sw_csv_layout(F->csv, &layout) == SW_OK && layout.ready ? layout.unit[0]
                                                                  : SW_CSV_UNIT_NONE);
    return SW_EXIT_OK;
}

static void csv_close(sw_cli_reader_t *R)
{
    feed_t *F = R->priv;
    if (F)
        sw_csv_destroy(F->csv);
    sw_stream_destroy(R->st);
    free(F);
}

static void csv_init(sw_cli_read_opts_t *o)
{
    sw_cli_csv_opts_init(&o->copts);
}

static const sw_cli_option_t *const csv_own[] = {sw_cli_csv_options, NULL};

const sw_cli_source_t sw_cli_source_csv = {
    .name = "a CSV log",
    .picks = "--time-col, --time-unit, --accel-col, --accel-unit, --lat-col",
    .takes = "CSV logs",
    .own = csv_own,
    .init = csv_init,
    .prepare = csv_prepare,
    .start = csv_start,
    .feed = csv_feed,
    .close = csv_close,
};
