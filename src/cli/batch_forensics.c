/* SPDX-License-Identifier: GPL-3.0-or-later */
/* batch_forensics.c - the forensics job of "swaywatch batch" (batch.h):
 * each log through "swaywatch forensics" (forensics.h), and for each
 * package the members of forensics' JSON for it (its verdict, smallest
 * reserve, safety factor, what would have saved it, the what-if rows) and
 * the log's facts, and a CSV row of the answer. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "batch.h"
#include "forensics.h"
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

#define CSV_HEADER                                                                             \
    "package,model,verdict,overturned,overturn_time,max_theta_ratio,min_margin,min_reserve_g," \
    "factor_safe,factor,weaker_overturning_factor,trials,saved_by,samples_read,"               \
    "samples_rejected,samples_used,duration,rate,peak_accel_g,gaps"

/* The CSV row of package k: the fields of CSV_HEADER. */
static void csv_row(FILE *f, const sw_cli_forensics_t *F, size_t k, const sw_summary_t *s,
                    const sw_cli_case_t *C)
{
    sw_cli_csv_text(f, s->name);
    fprintf(f, ",%s,%s,%d", sw_model_name(s->model), sw_cli_verdict(s, &F->R.run), s->overturned);
    sw_cli_csv_num(f, s->overturn_time);
    sw_cli_csv_num(f, s->max_theta_ratio);
    sw_cli_csv_num(f, s->min_margin);
    const sw_risk_pkg_t *rp = F->R.risk ? sw_risk_pkg(F->R.risk, k) : NULL;
    sw_cli_csv_num(f, rp && rp->evaluations > 0 ? rp->min_reserve_g : NAN);
    const sw_safety_t *sf = &C->sf;
    const int ok = C->available && sf->found;
    sw_cli_csv_num(f, ok && sf->factor_safe > 0.0 ? sf->factor_safe : NAN);
    sw_cli_csv_num(f, ok ? sf->factor : NAN);
    sw_cli_csv_num(f, C->available && !sf->overturned && sf->below.found ? sf->below.x : NAN);
    fprintf(f, ",%ld,", C->available ? sf->trials : 0L);
    char save[512];
    sw_cli_whatif_savers(save, sizeof save, F->cases, F->ncases, k);
    sw_cli_csv_text(f, s->overturned ? save : "");
    const sw_cli_run_t *run = &F->R.run;
    fprintf(f, ",%ld,%ld,%zu", run->samples_read, run->samples_rejected, F->L.n);
    const int h = run->have_facts;
    sw_cli_csv_num(f, h ? run->facts.duration : NAN);
    sw_cli_csv_num(f, h ? run->facts.rate : NAN);
    sw_cli_csv_num(f, h ? run->facts.peak_a / SW_G0 : NAN);
    if (h)
        fprintf(f, ",%ld", run->facts.gaps);
    else
        fputc(',', f);
}

typedef struct {
    sw_cli_records_t *rec;
    int oom;
} report_t;

static void report(void *user, const sw_cli_forensics_t *F)
{
    report_t *R = user;
    for (size_t k = 0; k < F->n; k++) {
        sw_summary_t s;
        const sw_cli_case_t *C = sw_cli_forensics_scene_case(F, k);
        if (!C || !sw_cli_forensics_summary(F, k, &s))
            continue;
        sw_cli_record_t r;
        if (sw_cli_record_begin(&r) == 0) {
            r.status = sw_cli_record_status(&s, &F->R.run);
            json_t *o = sw_cli_rec_new();
            sw_cli_forensics_json_package(o, F, k);
            sw_cli_rec_int(o, "samples_read", F->R.run.samples_read);
            sw_cli_rec_int(o, "samples_rejected", F->R.run.samples_rejected);
            sw_cli_rec_int(o, "samples_used", (long long)F->L.n);
            if (F->R.run.have_facts)
                sw_cli_json_facts(o, "input", &F->R.run);
            if (sw_cli_rec_members(r.j, o) != 0)
                R->oom = 1;
            csv_row(r.c, F, k, &s, C);
        }
        if (sw_cli_record_end(R->rec, &r) != 0)
            R->oom = 1;
    }
}

static int run(const void *opts, const char *log, sw_cli_records_t *rec)
{
    report_t R = {.rec = rec};
    const int rc = sw_cli_forensics_log(opts, log, report, &R);
    if (R.oom) {
        sw_cli_error("%s: out of memory", log);
        return SW_EXIT_IO;
    }
    return rc;
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
    .csv_header = CSV_HEADER,
};
