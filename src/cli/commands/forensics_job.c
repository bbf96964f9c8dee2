/* SPDX-License-Identifier: GPL-3.0-or-later */
/* forensics_job.c - forensics' job for "swaywatch batch" (job.h): each
 * log through "swaywatch forensics" (forensics.h), and for each package
 * the members of forensics' JSON for it (its verdict, smallest reserve,
 * safety factor, what would have saved it, the what-if rows) and the
 * log's facts, with the columns of a CSV row of the answer. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "forensics.h"
#include "job.h"
#include "output.h"

static void *create(void)
{
    return sw_cli_forensics_new();
}

static void destroy(void *opts)
{
    sw_cli_forensics_destroy(opts);
}

static size_t groups(void *opts, sw_cli_group_t *g)
{
    return sw_cli_forensics_groups(opts, g);
}

static sw_cli_opts_t *common(void *opts)
{
    return &((sw_cli_forensics_t *)opts)->o;
}

static int ready(void *opts, const sw_cli_group_t *g, size_t ng)
{
    return sw_cli_forensics_ready(opts, g, ng);
}

/* The CSV table: columns of the record (forensics' package, the counts,
 * the input's facts). */
static const sw_cli_column_t columns[] = {
    {.name = "package", .path = "name"},
    {.name = "model"},
    {.name = "verdict"},
    {.name = "overturned"},
    {.name = "overturn_time"},
    {.name = "max_theta_ratio"},
    {.name = "min_margin"},
    {.name = "min_reserve_g"},
    {.name = "factor_safe", .path = "safety_factor.factor_safe"},
    {.name = "factor", .path = "safety_factor.factor"},
    {.name = "weaker_overturning_factor", .path = "safety_factor.weaker_overturning_factor"},
    {.name = "trials",
     .path = "safety_factor.trials",
     .missing = "0"}, /* none where it was not searched */
    {.name = "saved_by"},
    {.name = "samples_read"},
    {.name = "samples_rejected"},
    {.name = "samples_used"},
    {.name = "duration", .path = "input.duration"},
    {.name = "rate", .path = "input.rate"},
    {.name = "peak_accel_g", .path = "input.peak_accel_g"},
    {.name = "gaps", .path = "input.gaps"},
    /* a package with a lateral plane (empty for one without): the plane of
     * the verdict (whose are the peak, margin and reserve above), the plane
     * that gives out first with both axes scaled (the factor above), and
     * each plane's own bracket */
    {.name = "plane"},
    {.name = "factor_plane", .path = "safety_factor.plane"},
    {.name = "longitudinal_factor_safe", .path = "safety_factor.planes.longitudinal.factor_safe"},
    {.name = "longitudinal_factor", .path = "safety_factor.planes.longitudinal.factor"},
    {.name = "lateral_factor_safe", .path = "safety_factor.planes.lateral.factor_safe"},
    {.name = "lateral_factor", .path = "safety_factor.planes.lateral.factor"},
};

static void report(void *user, const sw_cli_forensics_t *F)
{
    for (size_t k = 0; k < F->n; k++) {
        sw_summary_t s;
        const sw_whatif_case_t *C = sw_cli_forensics_scene_case(F, k);
        if (!C || !sw_cli_forensics_summary(F, k, &s))
            continue;
        json_t *o = sw_cli_rec_new();
        sw_cli_forensics_json_package(o, F, k);
        sw_cli_rec_int(o, "samples_read", F->R.run.samples_read);
        sw_cli_rec_int(o, "samples_rejected", F->R.run.samples_rejected);
        sw_cli_rec_int(o, "samples_used", (long long)sw_forensics_log(F->fx)->n);
        sw_cli_records_package(user, &s, &F->R.run, o);
    }
}

static int run(const void *opts, const char *log, sw_cli_records_t *rec)
{
    return sw_cli_forensics_log(opts, log, report, rec);
}

const sw_cli_job_t sw_cli_job_forensics = {
    .name = "forensics",
    .about =
        "the forensics of each log (swaywatch forensics): verdict, safety factor and "
        "what-if of every package",
    .create = create,
    .destroy = destroy,
    .groups = groups,
    .common = common,
    .ready = ready,
    .run = run,
    .columns = columns,
    .ncolumns = sizeof columns / sizeof columns[0],
};
