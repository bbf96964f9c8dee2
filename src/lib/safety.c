/* SPDX-License-Identifier: GPL-3.0-or-later */
/* safety.c - the safety factors of a recorded log (sweep.h): for each
 * scene, the smallest scale of the log's longitudinal acceleration that
 * overturns the package, found by running the log many times ("trials",
 * each starting as late as its outcome allows: safety_prep.c).
 *
 * The searches of all scenes run at once on the library's pool of threads
 * (pool.c), in rounds
 * of SECTIONS trials: the scan takes SECTIONS points of its grid at a
 * time, and a bracket is cut into SECTIONS + 1 pieces, keeping the lowest
 * change from safe to overturning.  A round's points do not depend on the
 * number of threads, so neither does any result. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "pool_int.h"
#include "run_int.h"
#include "safety_prep.h"
#include "swaywatch/model.h"
#include "swaywatch/safety.h"
#include "swaywatch/search.h"
#include "swaywatch/status.h"

#define DEFAULT_STEP 0.02
#define DEFAULT_TOL 1e-3
#define DEFAULT_X_MAX 20.0
#define SECTIONS 4     /* trials per round of a search */
#define NEAR_PEAK 0.25 /* peak |theta| / alpha from which the scan takes its finest step */
#define FAR_STEPS 5.0  /* the scan's step far from that, in --step */

/* ---- the search, in rounds --------------------------------------------------- */

enum { SR_SCAN, SR_SECT, SR_DONE };

/* One threshold search (sw_threshold_search()'s scan and bracket) as a
 * machine: points() gives a round's scales, feed() takes their results. */
typedef struct {
    sw_search_opts_t o; /* resolved: step, tol set */
    int phase;
    long k;           /* scan: points run so far */
    double x_last;    /* scan: the last point run (safe) */
    double peak_last; /* its largest |theta| / alpha */
    double lo, hi;    /* bracket: lo safe, hi overturns */
    sw_run_result_t r_hi;
    double x[SECTIONS];
    sw_run_result_t r[SECTIONS];
    int n; /* points of the current round */
    sw_threshold_t *out;
} search_t;

static int search_init(search_t *S, const sw_search_opts_t *o, sw_threshold_t *out)
{
    memset(S, 0, sizeof *S);
    memset(out, 0, sizeof *out);
    S->o = *o;
    S->out = out;
    if (!(S->o.step > 0.0))
        S->o.step = DEFAULT_STEP;
    if (!(S->o.tol > 0.0))
        S->o.tol = DEFAULT_TOL;
    if (!(o->x_min > 0.0) || !(o->x_max > o->x_min) || !isfinite(o->x_max) ||
        !isfinite(S->o.step) || !isfinite(S->o.tol)) {
        S->phase = SR_DONE;
        return SW_EINVAL;
    }
    return SW_OK;
}

/* The bracket [lo, hi] is found: done if it is narrow enough. */
static void search_bracket(search_t *S)
{
    S->phase = SR_SECT;
    if (S->hi / S->lo - 1.0 > S->o.tol)
        return;
    S->phase = SR_DONE;
    S->out->found = 1;
    S->out->x = S->hi;
    S->out->x_safe = S->lo;
    S->out->at_x = S->r_hi;
}

/* The relative step of the scan's next round: --step wherever the
 * package came within a quarter of alpha of its corner (peak |theta| of
 * the last point run at least alpha / 4), growing to FAR_STEPS times it
 * as that peak falls to 0 (no lift at all): a package that stays far from
 * tipping at x does not overturn at a few per cent more, while near
 * tipping, where overturning is not monotonic in the scale, the scan is as
 * fine as asked. */
static double scan_step(const search_t *S)
{
    const double near = fmin(1.0, fmax(0.0, S->peak_last / NEAR_PEAK));
    return S->o.step * (FAR_STEPS - (FAR_STEPS - 1.0) * near);
}

/* The scales of the next round (S->n of them; 0 when done). */
static int search_points(search_t *S)
{
    S->n = 0;
    if (S->phase == SR_SCAN) {
        const double f = 1.0 + scan_step(S);
        for (int j = 0; j < SECTIONS; j++) {
            const double x = S->k == 0 ? fmin(S->o.x_min * pow(f, j), S->o.x_max)
                                       : fmin(S->x_last * pow(f, j + 1.0), S->o.x_max);
            S->x[S->n++] = x;
            if (x >= S->o.x_max)
                break; /* the scan's last point is x_max itself */
        }
    } else if (S->phase == SR_SECT) {
        const double ratio = S->hi / S->lo;
        double prev = S->lo;
        for (int j = 1; j <= SECTIONS; j++) {
            const double x = S->lo * pow(ratio, (double)j / (SECTIONS + 1));
            if (x > prev && x < S->hi)
                S->x[S->n++] = prev = x;
        }
        if (!S->n) { /* no scale left between them: as narrow as it gets */
            S->o.tol = INFINITY;
            search_bracket(S);
        }
    }
    return S->n;
}

/* The round's results: the lowest overturning scale wins, with the safe
 * one just below it. */
static void search_feed(search_t *S)
{
    S->out->trials += S->n;
    int j = 0;
    while (j < S->n && !S->r[j].overturned) j++;
    if (S->phase == SR_SCAN) {
        if (j == S->n) { /* all safe */
            S->lo = S->x_last = S->x[S->n - 1];
            S->peak_last = S->r[S->n - 1].max_theta_ratio;
            S->k += S->n;
            if (S->x[S->n - 1] >= S->o.x_max)
                S->phase = SR_DONE; /* nothing overturns */
            return;
        }
        if (S->k + j == 0) { /* x_min itself overturns: the threshold may be lower */
            S->phase = SR_DONE;
            S->out->found = S->out->at_min = 1;
            S->out->x = S->x[0];
            S->out->x_safe = 0.0;
            S->out->at_x = S->r[0];
            return;
        }
        S->lo = j > 0 ? S->x[j - 1] : S->lo;
        S->hi = S->x[j];
        S->r_hi = S->r[j];
        search_bracket(S);
        return;
    }
    if (j < S->n) {
        S->lo = j > 0 ? S->x[j - 1] : S->lo;
        S->hi = S->x[j];
        S->r_hi = S->r[j];
    } else {
        S->lo = S->x[S->n - 1];
    }
    search_bracket(S);
}

/* ---- the scenes' searches on a pool of threads -------------------------------- */

/* A scene's work goes on three tracks: the run at scale 1 (ONE), the
 * search below it (BELOW: from the lifting scale up to 1, whatever the
 * outcome at 1) and, once ONE says it survived, the search above it
 * (ABOVE).  Each track is a sequence of rounds; a round's tasks run in any
 * order on any thread, and the track moves on when the last one is done.
 * A failing track stops; the scene reports the first failing track's
 * first error, so that the error too is the same for any threads. */
enum { TR_ONE, TR_BELOW, TR_ABOVE, TR_N };
enum { T_PREP = -1 };

typedef struct {
    sw_safety_case_t *out;
    prep_t P;
    int prepared;
    int pending[TR_N]; /* tasks of each track's current round not finished */
    int err[TR_N], err_at[TR_N];
    char msg[TR_N][256];
    search_t below, above;
    int done;
} case_t;

typedef struct {
    case_t *c;
    int track, slot; /* track T_PREP: the preparation */
    int err;         /* the task's outcome, and why */
    char msg[256];
} task_t;

typedef struct {
    task_t *q; /* a ring: at most 2 SECTIONS + 1 tasks of each case wait at a time */
    size_t cap, head, len;
    size_t active;
    const sw_safety_opts_t *o;
    sw_safety_progress_t prog;
} pool_t;

static void push_task(pool_t *W, case_t *c, int track, int slot)
{
    W->q[(W->head + W->len++) % W->cap] = (task_t){.c = c, .track = track, .slot = slot};
    if (track != T_PREP)
        c->pending[track]++;
}

static int task_run(const task_t *t, char *msg, size_t msglen)
{
    case_t *c = t->c;
    switch (t->track) {
        case T_PREP: return sw_safety_prep_make(&c->P, msg, msglen);
        case TR_ONE: return sw_safety_trial(&c->P, 1.0, 1, &c->out->sf.at_one, msg, msglen);
        case TR_BELOW:
            return sw_safety_trial(&c->P, c->below.x[t->slot], 0, &c->below.r[t->slot], msg,
                                   msglen);
        default:
            return sw_safety_trial(&c->P, c->above.x[t->slot], 0, &c->above.r[t->slot], msg,
                                   msglen);
    }
}

/* The search options of the scene: the caller's, with the automatic
 * range (sw_safety_factor()). */
static sw_search_opts_t case_search(const pool_t *W, const case_t *c)
{
    const prep_t *P = &c->P;
    sw_search_opts_t so = W->o->search;
    if (!(so.x_max > 0.0))
        so.x_max = DEFAULT_X_MAX * P->bare_lift;
    if (!(so.x_min > 0.0)) {
        so.x_min = P->lift_scale;
        if (!sw_model_ops_of(P->d.model)->lift_direct || P->log->a_z)
            so.x_min *= LIFT_MARGIN_LOG;
        if (P->log->a_z)
            so.x_min = fmin(so.x_min, LIFT_MARGIN_LOG * P->bare_lift);
    }
    return so;
}

/* The next round of a search track, or none (done). */
static void track_next(pool_t *W, case_t *c, int track)
{
    search_t *S = track == TR_BELOW ? &c->below : &c->above;
    if (c->err[track] || S->phase == SR_DONE) {
        S->n = 0;
        return;
    }
    const int n = search_points(S);
    for (int j = 0; j < n; j++) push_task(W, c, track, j);
}

/* Prepared: the run at 1 and the search below it start together. */
static void case_start(pool_t *W, case_t *c)
{
    sw_safety_t *sf = &c->out->sf;
    c->prepared = 1;
    c->below.phase = c->above.phase = SR_DONE;
    push_task(W, c, TR_ONE, 0);
    if (c->P.a_peak == 0.0)
        return; /* no longitudinal acceleration: no scale changes anything */
    const sw_search_opts_t so = case_search(W, c);
    sf->max_scale = so.x_max;
    sf->lift_scale = c->P.lift_scale;
    sw_search_opts_t sb = so;
    sb.x_max = 1.0;
    if (sb.x_min < 1.0 && search_init(&c->below, &sb, &sf->below) != SW_OK) {
        c->err[TR_BELOW] = SW_EINVAL;
        snprintf(c->msg[TR_BELOW], sizeof c->msg[0],
                 "the log has no usable sample, or the search range is empty");
    }
    track_next(W, c, TR_BELOW);
}

/* The run at 1 is done: the search above it, if it survived. */
static void case_one_done(pool_t *W, case_t *c)
{
    sw_safety_t *sf = &c->out->sf;
    sf->overturned = sf->at_one.overturned;
    if (c->err[TR_ONE] || c->P.a_peak == 0.0)
        return;
    const sw_search_opts_t so = case_search(W, c);
    sw_search_opts_t sa = so;
    sa.x_min = fmax(1.0, so.x_min);
    if (!sf->overturned && sa.x_min < sa.x_max) {
        if (search_init(&c->above, &sa, &sf->above) != SW_OK) {
            c->err[TR_ABOVE] = SW_EINVAL;
            snprintf(c->msg[TR_ABOVE], sizeof c->msg[0],
                     "the log has no usable sample, or the search range is empty");
        }
        track_next(W, c, TR_ABOVE);
    }
}

static void case_finish(pool_t *W, case_t *c)
{
    sw_safety_t *sf = &c->out->sf;
    for (int k = 0; k < TR_N; k++)
        if (c->err[k]) {
            c->out->status = c->err[k];
            snprintf(c->out->msg, sizeof c->out->msg, "%s",
                     c->msg[k][0] ? c->msg[k] : sw_strerror(c->err[k]));
            break;
        }
    if (c->P.a_peak == 0.0)
        sf->lift_scale = INFINITY;
    if (sf->overturned && c->P.a_peak > 0.0 && !(case_search(W, c).x_min < 1.0)) {
        /* lifting estimated above 1, yet 1 overturned: 1 itself */
        sf->below.found = sf->below.at_min = 1;
        sf->below.x = 1.0;
        sf->below.at_x = sf->at_one;
    }
    sf->trials = 1 + sf->below.trials + sf->above.trials;
    if (sf->overturned && sf->below.found) {
        sf->found = 1;
        sf->factor = sf->below.x;
        sf->factor_safe = sf->below.x_safe;
    } else if (!sf->overturned && sf->above.found) {
        sf->found = 1;
        sf->factor = sf->above.x;
        sf->factor_safe = sf->above.at_min ? 1.0 : sf->above.x_safe;
    }
    c->done = 1;
    sw_safety_prep_free(&c->P);
    W->active--;
    W->prog.cases_done++;
}

/* A task is done (under the lock): its track may move on, the scene may
 * be finished. */
static void task_done(pool_t *W, const task_t *t, int err, const char *msg)
{
    case_t *c = t->c;
    const int k = t->track;
    if (k == T_PREP) {
        if (err < 0) {
            c->err[TR_ONE] = err;
            snprintf(c->msg[TR_ONE], sizeof c->msg[0], "%s", msg);
        } else {
            case_start(W, c);
        }
    } else {
        W->prog.trials++;
        if (err < 0 && (!c->err[k] || t->slot < c->err_at[k])) {
            c->err[k] = err;
            c->err_at[k] = t->slot;
            snprintf(c->msg[k], sizeof c->msg[0], "%s", msg);
        }
        if (--c->pending[k] == 0) {
            if (k == TR_ONE)
                case_one_done(W, c);
            if (k == TR_BELOW && !c->err[k])
                search_feed(&c->below);
            if (k == TR_ABOVE && !c->err[k])
                search_feed(&c->above);
            if (k != TR_ONE)
                track_next(W, c, k);
        }
    }
    if (!c->pending[TR_ONE] && !c->pending[TR_BELOW] && !c->pending[TR_ABOVE])
        case_finish(W, c);
    if (W->o->progress)
        W->o->progress(W->o->user, &W->prog);
}

/* ---- the pool's job: the queue's tasks ---------------------------------------- */

static int job_take(void *user, void *task)
{
    pool_t *W = user;
    if (!W->len)
        return 0;
    memcpy(task, &W->q[W->head], sizeof(task_t));
    W->head = (W->head + 1) % W->cap;
    W->len--;
    return 1;
}

static int job_ended(void *user)
{
    const pool_t *W = user;
    return !W->active;
}

static void job_run(void *user, void *task)
{
    (void)user;
    task_t *t = task;
    t->msg[0] = '\0';
    t->err = task_run(t, t->msg, sizeof t->msg);
}

static void job_done(void *user, void *task)
{
    const task_t *t = task;
    task_done(user, t, t->err, t->msg);
}

int sw_safety_factors(sw_safety_case_t *cases, size_t n, const sw_log_t *log,
                      const sw_safety_opts_t *o)
{
    if (!cases || !log || !log->t || !log->a_g || !o || n == 0)
        return SW_EINVAL;
    case_t *cs = calloc(n, sizeof *cs);
    pool_t W = {.cap = n * (2 * SECTIONS + 1) + 1, .o = o, .active = n};
    W.q = malloc(W.cap * sizeof *W.q);
    if (!cs || !W.q) {
        free(cs);
        free(W.q);
        return SW_ENOMEM;
    }
    W.prog.cases = n;
    for (size_t i = 0; i < n; i++) {
        sw_safety_case_t *out = &cases[i];
        out->status = SW_OK;
        out->msg[0] = '\0';
        memset(&out->sf, 0, sizeof out->sf);
        out->sf.factor = out->sf.factor_safe = INFINITY;
        cs[i] = (case_t){.out = out};
        cs[i].P = (prep_t){.sc = &out->scene, .log = log, .ro = &o->run};
        if (log->n == 0) { /* nothing to run: refused at once */
            cs[i].err[TR_ONE] = SW_EINVAL;
            snprintf(cs[i].msg[TR_ONE], sizeof cs[i].msg[0], "the log has no usable sample");
            case_finish(&W, &cs[i]);
            continue;
        }
        push_task(&W, &cs[i], T_PREP, 0);
    }
    const sw_pool_job_t J = {sizeof(task_t), job_take, job_ended, job_run, job_done, &W};
    sw_pool_run(&J, o->threads);
    int rc = SW_OK;
    for (size_t i = 0; i < n && rc == SW_OK; i++) rc = cases[i].status;
    free(W.q);
    free(cs);
    return rc;
}

int sw_safety_factor(const sw_scene_t *sc, const sw_log_t *log, const sw_run_opts_t *ro,
                     const sw_search_opts_t *so, sw_safety_t *out, char *msg, size_t msglen)
{
    sw_set_msg(msg, msglen, "%s", "");
    if (!sc || !log || !out)
        return SW_EINVAL;
    sw_safety_case_t *c = calloc(1, sizeof *c);
    if (!c)
        return SW_ENOMEM;
    c->scene = *sc;
    sw_safety_opts_t o = {.threads = 1};
    if (ro)
        o.run = *ro;
    if (so)
        o.search = *so;
    const int rc = sw_safety_factors(c, 1, log, &o);
    *out = c->sf;
    if (rc < 0)
        sw_set_msg(msg, msglen, "%s", c->msg);
    free(c);
    return rc;
}
