/* SPDX-License-Identifier: GPL-3.0-or-later */
/* forensics.c - the forensics of a recorded log (forensics.h): the log
 * held as the gate handed it to the engine, and from it every package's
 * what-if cases with their safety factors and smallest reserves
 * (whatif.c does each case's work). */
#include "swaywatch/forensics.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/status.h"

struct sw_forensics {
    sw_forensics_opts_t o;
    size_t npkg;
    sw_whatif_case_t *cases;
    size_t ncases;
    /* the held log */
    double *t, *a_g, *a_z; /* a_z: 0 where there is no vertical channel */
    size_t n, cap;
    int has_z; /* some a_z is not 0 */
    size_t *restart;
    size_t nrestart, restart_cap;
    int status; /* SW_OK, or what stopped the holding */
    sw_log_t log;
};

sw_forensics_t *sw_forensics_create(const sw_scene_t *scenes, size_t n,
                                    const sw_forensics_opts_t *o, int *err)
{
    int rc = SW_ENOMEM;
    sw_forensics_t *F = NULL;
    if (!scenes || !n || !o) {
        rc = SW_EINVAL;
        goto fail;
    }
    if (!(F = calloc(1, sizeof *F)))
        goto fail;
    F->o = *o;
    F->o.whatif.sizes = NULL; /* read here only */
    F->npkg = n;
    F->cases = calloc(sw_whatif_max(n, &o->whatif), sizeof *F->cases);
    if (!F->cases)
        goto fail;
    F->ncases = sw_whatif_cases(scenes, n, &o->whatif, F->cases);
    return F;
fail:
    sw_forensics_destroy(F);
    if (err)
        *err = rc;
    return NULL;
}

void sw_forensics_destroy(sw_forensics_t *F)
{
    if (!F)
        return;
    free(F->cases);
    free(F->t);
    free(F->a_g);
    free(F->a_z);
    free(F->restart);
    free(F);
}

/* ---- the held log -------------------------------------------------------------- */

static int grow(sw_forensics_t *F)
{
    size_t cap = F->cap ? 2 * F->cap : 4096;
    if (F->o.max_samples && cap > F->o.max_samples)
        cap = F->o.max_samples;
    double *t = realloc(F->t, cap * sizeof *t);
    if (!t)
        return -1;
    F->t = t;
    double *a = realloc(F->a_g, cap * sizeof *a);
    if (!a)
        return -1;
    F->a_g = a;
    double *z = realloc(F->a_z, cap * sizeof *z);
    if (!z)
        return -1;
    F->a_z = z;
    F->cap = cap;
    return 0;
}

static int add_restart(sw_forensics_t *F)
{
    if (F->nrestart == F->restart_cap) {
        size_t cap = F->restart_cap ? 2 * F->restart_cap : 16;
        size_t *r = realloc(F->restart, cap * sizeof *r);
        if (!r)
            return -1;
        F->restart = r;
        F->restart_cap = cap;
    }
    F->restart[F->nrestart++] = F->n;
    return 0;
}

int sw_forensics_push(sw_forensics_t *F, double t, double a_g, double a_z, int restart)
{
    if (F->status != SW_OK)
        return F->status;
    if (F->o.max_samples && F->n == F->o.max_samples)
        return F->status = SW_ETOOBIG;
    if ((F->n == F->cap && grow(F) != 0) || (restart && F->n > 0 && add_restart(F) != 0))
        return F->status = SW_ENOMEM;
    F->t[F->n] = t;
    F->a_g[F->n] = a_g;
    F->a_z[F->n] = a_z;
    F->has_z |= a_z != 0.0;
    F->n++;
    F->log = (sw_log_t){.t = F->t,
                        .a_g = F->a_g,
                        .a_z = F->has_z ? F->a_z : NULL,
                        .n = F->n,
                        .restart = F->restart,
                        .nrestart = F->nrestart};
    return SW_OK;
}

int sw_forensics_status(const sw_forensics_t *F)
{
    return F->status;
}

const sw_log_t *sw_forensics_log(const sw_forensics_t *F)
{
    return &F->log;
}

void sw_forensics_rerun(const sw_forensics_t *F, sw_engine_t *e, double t_end, double settle)
{
    size_t i = 0, r = 0;
    for (; i < F->n; i++) {
        while (r < F->nrestart && F->restart[r] <= i)
            if (F->restart[r++] == i)
                sw_engine_restart(e);
        sw_engine_push(e, F->t[i], F->a_g[i], F->has_z ? F->a_z[i] : 0.0);
        if (F->t[i] > t_end)
            break;
    }
    if (i == F->n && F->n > 0 && settle > 0.0) /* a moment in the settling after the log */
        sw_engine_finish(e, settle);
}

/* ---- the searches -------------------------------------------------------------- */

int sw_forensics_safety(sw_forensics_t *F)
{
    const sw_safety_opts_t so = {.run = F->o.run,
                                 .search = F->o.search,
                                 .threads = F->o.threads,
                                 .progress = F->o.progress,
                                 .user = F->o.user};
    return sw_whatif_safety(F->cases, F->ncases, sw_forensics_log(F), &so);
}

int sw_forensics_reserve(sw_forensics_t *F, const sw_risk_t *replay)
{
    for (size_t i = 0; replay && i < F->ncases; i++) {
        sw_whatif_case_t *C = &F->cases[i];
        const sw_risk_pkg_t *p = C->is_scene ? sw_risk_pkg(replay, C->pkg) : NULL;
        if (!p)
            continue;
        if (p->no_reserve) {
            snprintf(C->reserve_note, sizeof C->reserve_note, "%s", p->no_reserve);
            continue;
        }
        C->has_reserve = 1;
        C->rl.min_g = C->rl.lower_g = p->min_reserve_g;
        C->rl.min_time = p->min_reserve_time;
        C->rl.direction = p->min_direction;
        C->rl.pulse = p->min_pulse;
        C->rl.exact = 1;
        C->rl.states = C->rl.evaluated = p->evaluations;
        C->rl.faults = p->reserve_faults;
    }
    const sw_reserve_log_opts_t rlo = {
        .rate = F->o.reserve_rate, .max_evals = F->o.reserve_evals, .run = F->o.run};
    return sw_whatif_reserve(F->cases, F->ncases, sw_forensics_log(F), &rlo, F->o.threads);
}

sw_whatif_case_t *sw_forensics_cases(sw_forensics_t *F, size_t *n)
{
    *n = F->ncases;
    return F->cases;
}

const sw_whatif_case_t *sw_forensics_scene_case(const sw_forensics_t *F, size_t k)
{
    for (size_t i = 0; i < F->ncases; i++)
        if (F->cases[i].pkg == k && F->cases[i].is_scene)
            return &F->cases[i];
    return NULL;
}
