/* SPDX-License-Identifier: GPL-3.0-or-later */
/* replay_job.c - replay's job for "swaywatch batch" (job.h): each log
 * replayed as "swaywatch replay" does it (replay.h), and for each package
 * the members of replay's JSON summary (the package's, then the log's:
 * settle, the input's facts), with the columns of its CSV row. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "job.h"
#include "output.h"
#include "replay.h"

static void *create(void)
{
    return sw_cli_replay_new();
}

static void destroy(void *opts)
{
    sw_cli_replay_free(opts);
}

static size_t groups(void *opts, sw_cli_group_t *g)
{
    return sw_cli_replay_groups(opts, g);
}

static sw_cli_opts_t *common(void *opts)
{
    return sw_cli_replay_opts(opts);
}

static int ready(void *opts, const sw_cli_group_t *g, size_t ng)
{
    return sw_cli_replay_ready(opts, g, ng);
}

/* The CSV table: columns of the record (the package's members of the
 * summary, settle, the input's facts). */
static const sw_cli_column_t columns[] = {
    {.name = "package", .path = "name"},
    {.name = "model"},
    {.name = "overturned"},
    {.name = "overturn_time"},
    {.name = "tip_time"},
    {.name = "uplift_time"},
    {.name = "max_abs_theta"},
    {.name = "max_theta_ratio"},
    {.name = "alpha"},
    {.name = "min_margin"},
    {.name = "min_margin_bound"},
    {.name = "max_uplift_ratio"},
    {.name = "impacts"},
    {.name = "uplifts"},
    {.name = "rests"},
    {.name = "faults"},
    {.name = "samples_read"},
    {.name = "samples_rejected"},
    {.name = "scheme"},
    {.name = "dt"}, /* the step taken */
    {.name = "steps"},
    {.name = "settle"},
    {.name = "rejected_share", .path = "input.rejected_share"},
    {.name = "start", .path = "input.start"},
    {.name = "end", .path = "input.end"},
    {.name = "start_absolute", .path = "input.start_absolute"},
    {.name = "duration", .path = "input.duration"},
    {.name = "dt_median", .path = "input.dt_median"},
    {.name = "rate", .path = "input.rate"},
    {.name = "peak_accel_g", .path = "input.peak_accel_g"},
    {.name = "gaps", .path = "input.gaps"},
    {.name = "gap_max", .path = "input.gap_max"},
    {.name = "restarts", .path = "input.restarts"},
    {.name = "clock_steps", .path = "input.clock_steps"},
    {.name = "incomplete", .path = "input.incomplete"},
    {.name = "forced", .path = "input.forced", .missing = "0"},
    {.name = "check", .path = "input.check"},
    {.name = "verdict"},
    {.name = "min_reserve_g"},
    {.name = "min_reserve_time"},
    {.name = "rest_reserve_g"},
    /* a package with a lateral plane (empty for one without): the plane of
     * the verdict (overturned and verdict above are the package's, the
     * rest the plane along the truck's), both planes lifted at once, and
     * the lateral plane's main fields */
    {.name = "plane"},
    {.name = "both_planes_rocking"},
    {.name = "lateral_overturned", .path = "lateral.overturned"},
    {.name = "lateral_verdict", .path = "lateral.verdict"},
    {.name = "lateral_overturn_time", .path = "lateral.overturn_time"},
    {.name = "lateral_tip_time", .path = "lateral.tip_time"},
    {.name = "lateral_uplift_time", .path = "lateral.uplift_time"},
    {.name = "lateral_max_abs_theta", .path = "lateral.max_abs_theta"},
    {.name = "lateral_max_theta_ratio", .path = "lateral.max_theta_ratio"},
    {.name = "lateral_alpha", .path = "lateral.alpha"},
    {.name = "lateral_min_margin", .path = "lateral.min_margin"},
    {.name = "lateral_impacts", .path = "lateral.impacts"},
    {.name = "lateral_uplifts", .path = "lateral.uplifts"},
    {.name = "lateral_min_reserve_g", .path = "lateral.min_reserve_g"},
    {.name = "lateral_min_reserve_time", .path = "lateral.min_reserve_time"},
};

/* What sw_cli_replay_log() hands over: the records of every package. */
static void report(void *user, const sw_engine_t *e, const sw_cli_run_t *run)
{
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) != SW_OK)
            continue;
        json_t *o = sw_cli_rec_new();
        sw_cli_json_package(o, e, i, run);
        sw_cli_rec_num(o, "settle", run->settle);
        sw_cli_records_package(user, &s, run, o);
    }
}

static int run(const void *opts, const char *log, sw_cli_records_t *rec)
{
    return sw_cli_replay_log(opts, log, report, rec);
}

const sw_cli_job_t sw_cli_job_replay = {
    .name = "replay",
    .about = "replay each log (swaywatch replay): the outcome of every package",
    .create = create,
    .destroy = destroy,
    .groups = groups,
    .common = common,
    .ready = ready,
    .run = run,
    .columns = columns,
    .ncolumns = sizeof columns / sizeof columns[0],
};
