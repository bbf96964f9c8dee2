/* SPDX-License-Identifier: GPL-3.0-or-later */
/* batch_replay.c - the replay job of "swaywatch batch" (batch.h): each log
 * replayed as "swaywatch replay" does it (replay.h), and for each package
 * the members of replay's JSON summary (the package's, then the log's:
 * settle, the input's facts) and a CSV row of the same. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "batch.h"
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

#define CSV_HEADER                                                                              \
    "package,model,overturned,overturn_time,tip_time,uplift_time,max_abs_theta,"                \
    "max_theta_ratio,alpha,min_margin,min_margin_bound,max_uplift_ratio,impacts,uplifts,rests," \
    "faults,samples_read,samples_rejected,scheme,dt,steps,settle,rejected_share,start,end,"     \
    "start_absolute,duration,dt_median,rate,peak_accel_g,gaps,gap_max,restarts,clock_steps,"    \
    "incomplete,forced,check,verdict,min_reserve_g,min_reserve_time,rest_reserve_g"

/* The CSV row of package i: the fields of CSV_HEADER. */
static void csv_row(FILE *f, const sw_engine_t *e, size_t i, const sw_cli_run_t *run,
                    const sw_summary_t *s)
{
    const sw_derived_t *d = sw_engine_derived(e, i);
    sw_cli_csv_text(f, s->name);
    fprintf(f, ",%s,%d", sw_model_name(s->model), s->overturned);
    sw_cli_csv_num(f, s->overturn_time);
    sw_cli_csv_num(f, s->tip_time);
    sw_cli_csv_num(f, s->uplift_time);
    sw_cli_csv_num(f, s->max_abs_theta);
    sw_cli_csv_num(f, s->max_theta_ratio);
    sw_cli_csv_num(f, d ? d->alpha : NAN);
    sw_cli_csv_num(f, s->min_margin);
    sw_cli_csv_num(f, s->min_margin_bound);
    sw_cli_csv_num(f, s->max_uplift_ratio);
    fprintf(f, ",%ld,%ld,%ld,%ld,%ld,%ld,", s->impacts, s->uplifts, s->rests, s->faults,
            run->samples_read, run->samples_rejected);
    sw_cli_csv_text(f, sw_engine_scheme(e));
    sw_cli_csv_num(f, sw_engine_dt_used(e, i)); /* the step taken, as the JSON's dt */
    fprintf(f, ",%ld", s->steps);
    sw_cli_csv_num(f, run->settle);
    const sw_gate_facts_t *F = &run->facts;
    const int h = run->have_facts;
    sw_cli_csv_num(
        f, run->samples_read ? (double)run->samples_rejected / (double)run->samples_read : 0.0);
    sw_cli_csv_num(f, h ? F->t_first - F->t_origin : NAN);
    sw_cli_csv_num(f, h ? F->t_last - F->t_origin : NAN);
    fputc(',', f);
    char iso[64];
    if (h && sw_cli_run_utc(run, 0.0, iso, sizeof iso))
        fputs(iso, f);
    sw_cli_csv_num(f, h ? F->duration : NAN);
    sw_cli_csv_num(f, h ? F->dt_median : NAN);
    sw_cli_csv_num(f, h ? F->rate : NAN);
    sw_cli_csv_num(f, h ? F->peak_a / SW_G0 : NAN);
    if (h)
        fprintf(f, ",%ld", F->gaps);
    else
        fputc(',', f);
    sw_cli_csv_num(f, h ? F->gap_max : NAN);
    if (h)
        fprintf(f, ",%ld,%ld,%d", F->restarts, F->clock_steps, F->incomplete ? 1 : 0);
    else
        fputs(",,,", f);
    fprintf(f, ",%d,", run->forced);
    sw_cli_csv_text(f, run->check);
    /* the verdict, and the reserve as the JSON record has it (empty where
     * it has null: risk.h keeps NAN until there is a value) */
    fputc(',', f);
    sw_cli_csv_text(f, sw_cli_verdict(s, run));
    const sw_risk_pkg_t *p = run->risk ? sw_risk_pkg(run->risk, i) : NULL;
    sw_cli_csv_num(f, p ? p->min_reserve_g : NAN);
    sw_cli_csv_num(f, p ? p->min_reserve_time : NAN);
    sw_cli_csv_num(f, p ? p->rest_reserve_g : NAN);
}

typedef struct {
    sw_cli_records_t *rec;
    int oom;
} report_t;

/* What sw_cli_replay_log() hands over: the records of every package. */
static void report(void *user, const sw_engine_t *e, const sw_cli_run_t *run)
{
    report_t *R = user;
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) != SW_OK)
            continue;
        sw_cli_record_t r;
        if (sw_cli_record_begin(&r) == 0) {
            r.status = sw_cli_record_status(&s, run);
            json_t *o = sw_cli_rec_new();
            sw_cli_json_package(o, e, i, run);
            sw_cli_rec_num(o, "settle", run->settle);
            if (run->have_facts)
                sw_cli_json_facts(o, "input", run);
            if (sw_cli_rec_members(r.j, o) != 0)
                R->oom = 1;
            csv_row(r.c, e, i, run, &s);
        }
        if (sw_cli_record_end(R->rec, &r) != 0)
            R->oom = 1;
    }
}

static int run(const void *opts, const char *log, sw_cli_records_t *rec)
{
    report_t R = {.rec = rec};
    const int rc = sw_cli_replay_log(opts, log, report, &R);
    if (R.oom) {
        sw_cli_error("%s: out of memory", log);
        return SW_EXIT_IO;
    }
    return rc;
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
    .csv_header = CSV_HEADER,
};
