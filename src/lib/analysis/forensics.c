/* SPDX-License-Identifier: GPL-3.0-or-later */
/* forensics.c - the forensics of a recorded log (forensics.h): the log
 * held as the gate handed it to the engine, and from it every package's
 * what-if cases with their safety factors and smallest reserves
 * (whatif.c does each case's work); with a lateral acceleration held,
 * each package's lateral plane searched as a case of its own and the two
 * planes' factors joined into the package's.  The what-if cases' smallest
 * reserves are made on the searches' threads while they run (side work),
 * since they need only the held log. */
#include "swaywatch/forensics.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/status.h"

struct sw_forensics {
    sw_forensics_opts_t o;
    size_t npkg;
    sw_whatif_case_t *cases;
    size_t ncases;
    sw_whatif_case_t *lat; /* per case (ncases): its lateral plane (available: a depth,
                              and a lateral acceleration held) */
    /* the held log */
    double *t, *a_g, *a_z; /* a_z: 0 where there is no vertical channel */
    double *a_y;           /* lateral, once a sample came with one (push_lat) */
    int has_y;             /* every sample came with a lateral value */
    size_t n, cap;
    int has_z; /* some a_z is not 0 */
    size_t *restart;
    size_t nrestart, restart_cap;
    int status; /* SW_OK, or what stopped the holding */
    sw_log_t log;
    sw_log_t log_lat; /* the same log driven by a_y */
    /* per plane (0 along the truck, 1 across it): copies of the cases
     * taken before its search, in which the side work made the smallest
     * reserves, and which of them it made */
    sw_whatif_case_t *staged[2];
    unsigned char *side_done[2];
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
    F->o.whatif.sizes = F->o.whatif.depths = NULL; /* read here only */
    F->npkg = n;
    F->cases = calloc(sw_whatif_max(n, &o->whatif), sizeof *F->cases);
    if (!F->cases)
        goto fail;
    F->ncases = sw_whatif_cases(scenes, n, &o->whatif, F->cases);
    if (!(F->lat = calloc(F->ncases ? F->ncases : 1, sizeof *F->lat)))
        goto fail;
    for (int p = 0; p < 2; p++)
        if (!(F->staged[p] = calloc(F->ncases ? F->ncases : 1, sizeof *F->staged[p])) ||
            !(F->side_done[p] = calloc(F->ncases ? F->ncases : 1, 1)))
            goto fail;
    for (size_t i = 0; i < F->ncases; i++) { /* available once a lateral log is held */
        const sw_whatif_case_t *L = &F->cases[i];
        sw_whatif_case_t *C = &F->lat[i];
        C->pkg = L->pkg;
        C->is_scene = 0; /* its reserve computed here: the replay holds the longitudinal one */
        C->stands_for = L->stands_for;
        snprintf(C->name, sizeof C->name, "%s", L->name);
        C->built =
            L->built && sw_scene_lateral(&L->scene, &C->scene) == SW_OK &&
            sw_scene_validate(&C->scene, &C->derived, "across the truck", NULL, NULL) == SW_OK;
        C->model = C->derived.model;
        snprintf(C->note, sizeof C->note, "%s",
                 C->built ? "the log has no lateral acceleration"
                 : L->built && !sw_scene_has_depth(&L->scene) ? "the scene gives no depth"
                 : L->built ? "its lateral plane is not a valid scene"
                            : "not built");
    }
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
    free(F->lat);
    for (int p = 0; p < 2; p++) {
        free(F->staged[p]);
        free(F->side_done[p]);
    }
    free(F->a_y);
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
    if (F->has_y) {
        double *y = realloc(F->a_y, cap * sizeof *y);
        if (!y)
            return -1;
        F->a_y = y;
    }
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

/* One sample; lat: it carries a_y.  A log is lateral from its first
 * sample or not at all: a lateral value after samples without one, or a
 * sample without one in a lateral log, is refused (SW_EINVAL), since the
 * lateral plane would be driven by values that were never read. */
static int push(sw_forensics_t *F, double t, double a_g, double a_y, int lat, double a_z,
                int restart)
{
    if (F->status != SW_OK)
        return F->status;
    if (F->n == 0 && lat && !F->a_y) { /* the first sample decides */
        F->has_y = 1;
        if (F->cap && !(F->a_y = malloc(F->cap * sizeof *F->a_y)))
            return F->status = SW_ENOMEM;
    }
    if (lat != F->has_y)
        return SW_EINVAL;
    if (F->o.max_samples && F->n == F->o.max_samples)
        return F->status = SW_ETOOBIG;
    if ((F->n == F->cap && grow(F) != 0) || (restart && F->n > 0 && add_restart(F) != 0))
        return F->status = SW_ENOMEM;
    F->t[F->n] = t;
    F->a_g[F->n] = a_g;
    F->a_z[F->n] = a_z;
    if (F->has_y)
        F->a_y[F->n] = a_y;
    F->has_z |= a_z != 0.0;
    F->n++;
    F->log = (sw_log_t){.t = F->t,
                        .a_g = F->a_g,
                        .a_z = F->has_z ? F->a_z : NULL,
                        .n = F->n,
                        .restart = F->restart,
                        .nrestart = F->nrestart};
    F->log_lat = F->log;
    F->log_lat.a_g = F->a_y;
    return SW_OK;
}

int sw_forensics_push(sw_forensics_t *F, double t, double a_g, double a_z, int restart)
{
    return push(F, t, a_g, 0.0, 0, a_z, restart);
}

int sw_forensics_push_lat(sw_forensics_t *F, double t, double a_g, double a_y, double a_z,
                          int restart)
{
    return push(F, t, a_g, a_y, 1, a_z, restart);
}

int sw_forensics_status(const sw_forensics_t *F)
{
    return F->status;
}

const sw_log_t *sw_forensics_log(const sw_forensics_t *F)
{
    return &F->log;
}

const sw_log_t *sw_forensics_log_lat(const sw_forensics_t *F)
{
    return F->has_y ? &F->log_lat : NULL;
}

void sw_forensics_rerun(const sw_forensics_t *F, sw_engine_t *e, double t_end, double settle)
{
    size_t i = 0, r = 0;
    for (; i < F->n; i++) {
        while (r < F->nrestart && F->restart[r] <= i)
            if (F->restart[r++] == i)
                sw_engine_restart(e);
        const double az = F->has_z ? F->a_z[i] : 0.0;
        if (F->has_y)
            sw_engine_push_lat(e, F->t[i], F->a_g[i], F->a_y[i], az);
        else
            sw_engine_push(e, F->t[i], F->a_g[i], az);
        if (F->t[i] > t_end)
            break;
    }
    if (i == F->n && F->n > 0 && settle > 0.0) /* a moment in the settling after the log */
        sw_engine_finish(e, settle);
}

/* ---- the searches -------------------------------------------------------------- */

static sw_reserve_log_opts_t reserve_opts(const sw_forensics_t *F)
{
    return (sw_reserve_log_opts_t){
        .rate = F->o.reserve_rate, .max_evals = F->o.reserve_evals, .run = F->o.run};
}

/* The side work of one plane's search: case i's smallest reserve, if
 * sw_whatif_reserve() would make it (an available case, not a scene as
 * given), into its copy. */
typedef struct {
    sw_forensics_t *F;
    int plane;
    const sw_log_t *log;
    sw_reserve_log_opts_t o;
} side_t;

static void reserve_side(void *user, size_t i)
{
    const side_t *S = user;
    sw_whatif_case_t *C = &S->F->staged[S->plane][i];
    if (!C->available || C->is_scene)
        return;
    sw_whatif_reserve_case(C, S->log, &S->o);
    S->F->side_done[S->plane][i] = 1; /* each i is one task: no other thread writes it */
}

/* The searches of plane's cases on log, the cases' smallest reserves
 * made alongside when they are asked for (reserve_rate > 0): on a long
 * log they are a serial second or more after the searches otherwise (the
 * hour-long drive of docs/forensics.md), now done while a thread would
 * wait for a round's last trial. */
static int plane_safety(sw_forensics_t *F, int plane, sw_whatif_case_t *cs, const sw_log_t *log)
{
    side_t S = {F, plane, log, reserve_opts(F)};
    sw_safety_opts_t so = {.run = F->o.run,
                           .search = F->o.search,
                           .threads = F->o.threads,
                           .progress = F->o.progress,
                           .user = F->o.user};
    memset(F->side_done[plane], 0, F->ncases ? F->ncases : 1);
    if (F->o.reserve_rate > 0.0 && F->ncases) {
        memcpy(F->staged[plane], cs, F->ncases * sizeof *cs);
        so.sides = F->ncases;
        so.side = reserve_side;
        so.side_user = &S;
    }
    return sw_whatif_safety(cs, F->ncases, log, &so);
}

int sw_forensics_safety(sw_forensics_t *F)
{
    int rc = plane_safety(F, 0, F->cases, sw_forensics_log(F));
    if (rc != SW_OK || !F->has_y)
        return rc;
    /* the lateral planes of every case: the same searches on the lateral
     * acceleration (the planes are driven each by its own axis, so scaling
     * both axes together overturns the package at the smaller of the two
     * factors) */
    for (size_t i = 0; i < F->ncases; i++) {
        sw_whatif_case_t *C = &F->lat[i];
        C->available = C->built && F->cases[i].available;
        if (C->available)
            C->note[0] = '\0';
        else if (C->built)
            snprintf(C->note, sizeof C->note, "%s", F->cases[i].note);
    }
    return plane_safety(F, 1, F->lat, &F->log_lat);
}

/* The scale at which plane sf first overturns the package: for a log it
 * survived, a weaker overturning scale found below 1 comes first. */
static double first_over(const sw_safety_t *sf)
{
    if (sf->overturned)
        return sf->found ? sf->factor : INFINITY;
    if (sf->below.found)
        return sf->below.x;
    return INFINITY;
}

/* How far plane sf was searched: no limit for a plane whose axis never
 * lifts the package (no acceleration on it: no scale can move it). */
static double searched(const sw_safety_t *sf)
{
    return isinf(sf->lift_scale) ? INFINITY : sf->max_scale;
}

/* Which of two planes' runs at scale 1 is the worse (sw_summary_worse's
 * order): 1 for b.  An overturn without a time (it fell after the log)
 * comes after one with a time. */
static int run_worse(const sw_run_result_t *a, const sw_run_result_t *b)
{
    if (a->overturned != b->overturned)
        return b->overturned;
    if (a->overturned) {
        const double ta = isnan(a->overturn_time) ? INFINITY : a->overturn_time;
        const double tb = isnan(b->overturn_time) ? INFINITY : b->overturn_time;
        return tb < ta;
    }
    if (a->min_margin != b->min_margin)
        return b->min_margin < a->min_margin;
    return b->max_theta_ratio > a->max_theta_ratio;
}

int sw_forensics_factor(const sw_forensics_t *F, size_t k, sw_forensics_factor_t *out)
{
    for (size_t i = 0; k < F->npkg && i < F->ncases; i++)
        if (F->cases[i].pkg == k && F->cases[i].is_scene)
            return sw_forensics_case_factor(F, i, out);
    return SW_EINVAL;
}

int sw_forensics_case_factor(const sw_forensics_t *F, size_t i, sw_forensics_factor_t *out)
{
    const sw_whatif_case_t *L = i < F->ncases ? &F->cases[i] : NULL;
    if (!L || !out)
        return SW_EINVAL;
    memset(out, 0, sizeof *out);
    out->first = out->worse = SW_PLANE_LONG;
    out->sf = L->sf;
    out->planes = 1;
    const sw_whatif_case_t *T = &F->lat[i];
    if (!L->available || !F->has_y || !T->available)
        return SW_OK;
    out->planes = 2;
    out->lateral = T;
    out->worse = run_worse(&L->sf.at_one, &T->sf.at_one) ? SW_PLANE_LAT : SW_PLANE_LONG;
    const sw_safety_t *a = &L->sf, *b = &T->sf;
    sw_safety_t *s = &out->sf;
    s->overturned = a->overturned || b->overturned;
    int lat; /* the plane that gives out first */
    if (s->overturned) {
        /* the smallest scale that overturns either plane, no larger than 1 */
        const double xa = first_over(a), xb = first_over(b);
        lat = xb < xa || (xb == xa && b->overturned && !a->overturned);
    } else {
        const double fa = a->found ? a->factor : INFINITY, fb = b->found ? b->factor : INFINITY;
        lat = fb < fa || (fb == fa && searched(b) < searched(a));
    }
    const sw_safety_t *w = lat ? b : a, *o = lat ? a : b;
    out->first = lat ? SW_PLANE_LAT : SW_PLANE_LONG;
    s->at_one = w->overturned || !o->overturned ? w->at_one : o->at_one;
    if (s->overturned && !w->overturned) {
        /* the plane that gives out first survived the log: it overturns
         * below 1, on the scale its own search found */
        s->found = 1;
        s->factor = w->below.x;
        s->factor_safe = w->below.x_safe;
    } else {
        s->found = w->found;
        s->factor = w->factor;
        s->factor_safe = w->factor_safe;
    }
    /* survived: the weaker overturning shock is the smaller of the planes' */
    s->below = a->below;
    if (b->below.found && (!a->below.found || b->below.x < a->below.x))
        s->below = b->below;
    if (s->overturned)
        s->below.found = 0;
    s->above = w->above;
    s->lift_scale = fmin(a->lift_scale, b->lift_scale);
    s->max_scale = fmin(searched(a), searched(b)); /* searched this far in both */
    if (isinf(s->max_scale))
        s->max_scale = a->max_scale; /* neither axis moves it */
    s->trials = a->trials + b->trials;
    if (!s->overturned && s->found && s->factor > s->max_scale) {
        s->found = 0; /* the other plane's search did not reach it */
        s->factor = INFINITY;
    }
    return SW_OK;
}

/* Whose smallest reserve is the case's, of case L and its lateral plane
 * T (NULL: one plane): the smaller; a plane without one leaves the case
 * none known, L's when it says why, else T's. */
static const sw_whatif_case_t *reserve_plane(const sw_whatif_case_t *L, const sw_whatif_case_t *T)
{
    if (!T)
        return L;
    if (!L->has_reserve)
        return L->reserve_note[0] ? L : T;
    return T->has_reserve && !(T->rl.min_g < L->rl.min_g) ? L : T;
}

int sw_forensics_case_verdict(const sw_forensics_t *F, size_t i, sw_forensics_verdict_t *out)
{
    if (!F || !out || i >= F->ncases)
        return SW_EINVAL;
    const sw_whatif_case_t *L = &F->cases[i], *T = &F->lat[i];
    memset(out, 0, sizeof *out);
    sw_forensics_case_factor(F, i, &out->factor);
    out->planes = F->has_y && T->built ? 2 : 1;
    out->unjudged = SW_PLANE_LONG;
    out->note = "";
    if (!L->available) {
        out->note = L->note;
        return SW_OK;
    }
    if (out->planes == 2 && !T->available) { /* a depth, but no verdict across */
        out->unjudged = SW_PLANE_LAT;
        out->note = T->note;
        return SW_OK;
    }
    const int two = out->factor.planes == 2;
    out->judged = 1;
    out->run = two && out->factor.worse == SW_PLANE_LAT ? T : L;
    out->reserve = reserve_plane(L, two ? T : NULL);
    out->upright = !L->sf.overturned && !(two && T->sf.overturned);
    out->saves = out->upright && !L->is_scene;
    return SW_OK;
}

long sw_forensics_trials(const sw_forensics_t *F)
{
    long n = 0;
    for (size_t i = 0; i < F->ncases; i++) {
        n += F->cases[i].available ? F->cases[i].sf.trials : 0;
        n += F->has_y && F->lat[i].available ? F->lat[i].sf.trials : 0;
    }
    return n;
}

const sw_whatif_case_t *sw_forensics_lateral_case(const sw_forensics_t *F, size_t k)
{
    for (size_t i = 0; k < F->npkg && F->has_y && i < F->ncases; i++)
        if (F->cases[i].pkg == k && F->cases[i].is_scene)
            return F->lat[i].built ? &F->lat[i] : NULL;
    return NULL;
}

const sw_whatif_case_t *sw_forensics_lateral_cases(const sw_forensics_t *F, size_t *n)
{
    *n = F->has_y ? F->ncases : 0;
    return F->has_y ? F->lat : NULL;
}

/* The smallest reserve of plane's cases as sw_whatif_reserve() makes it:
 * the side work's, for the cases still available after their search,
 * when it made every one of them (the same rate and budget: the options
 * do not change); otherwise sw_whatif_reserve() now. */
static int plane_reserve(sw_forensics_t *F, int plane, sw_whatif_case_t *cs, const sw_log_t *log)
{
    int all = 1;
    for (size_t i = 0; i < F->ncases; i++)
        if (cs[i].available && !cs[i].is_scene)
            all &= F->side_done[plane][i];
    if (!all) {
        const sw_reserve_log_opts_t rlo = reserve_opts(F);
        return sw_whatif_reserve(cs, F->ncases, log, &rlo, F->o.threads);
    }
    int rc = SW_OK;
    for (size_t i = 0; i < F->ncases; i++) {
        if (!cs[i].available || cs[i].is_scene)
            continue;
        const sw_whatif_case_t *S = &F->staged[plane][i];
        cs[i].has_reserve = S->has_reserve;
        cs[i].reserve_status = S->reserve_status;
        cs[i].rl = S->rl;
        memcpy(cs[i].reserve_note, S->reserve_note, sizeof cs[i].reserve_note);
        if (S->reserve_status == SW_ENOMEM)
            rc = SW_ENOMEM;
    }
    return rc;
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
    int rc = plane_reserve(F, 0, F->cases, sw_forensics_log(F));
    if (rc == SW_OK && F->has_y) /* the lateral planes' (the scenes': the replay's) */
        rc = plane_reserve(F, 1, F->lat, &F->log_lat);
    return rc;
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
