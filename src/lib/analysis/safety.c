/* SPDX-License-Identifier: GPL-3.0-or-later */
/* safety.c - the safety factors of a recorded log (safety.h): for each
 * scene, the smallest scale of the log's longitudinal acceleration that
 * overturns the package, found by running the log many times ("trials",
 * each starting as late as its outcome allows: safety_prep.c).
 *
 * The searches of all scenes run at once on the library's pool of
 * threads (pool.c), each a resumable search (search.c) in rounds of
 * SW_SEARCH_SECTIONS trials.  A round's points do not depend on the
 * number of threads, so neither does any result. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_traits.h"
#include "pool_int.h"
#include "run_int.h"
#include "safety_prep.h"
#include "search_int.h"
#include "swaywatch/model.h"
#include "swaywatch/safety.h"
#include "swaywatch/search.h"
#include "swaywatch/status.h"

#define DEFAULT_X_MAX 20.0

/* ---- the scenes' searches on a pool of threads -------------------------------- */

/* A scene's work goes on three tracks: the run at scale 1 (ONE), the
 * search below it (BELOW: from the lifting scale up to 1, whatever the
 * outcome at 1) and, once ONE says it survived, the search above it
 * (ABOVE).  Each track is a sequence of rounds; a round's tasks run in any
 * order on any thread, and the track moves on when the last one is done.
 * A failing track stops; the scene reports the first failing track's
 * first error, so that the error too is the same for any threads. */
enum { TR_ONE, TR_BELOW, TR_ABOVE, TR_N };
enum { T_PREP = -1, T_SIDE = -2 };

typedef struct {
    sw_safety_case_t *out;
    int weight; /* the cost of its trials, roughly: its tasks go first (case_weight) */
    prep_t P;
    int prepared;
    int pending[TR_N]; /* tasks of each track's current round not finished */
    int err[TR_N], err_at[TR_N];
    char msg[TR_N][256];
    sw_search_t below, above;
    int done;
} case_t;

typedef struct {
    case_t *c;       /* NULL for the caller's side work */
    int track, slot; /* track T_PREP: the preparation */
    size_t side;     /* track T_SIDE: which of the caller's side tasks */
    int err;         /* the task's outcome, and why */
    char msg[256];
} task_t;

typedef struct {
    task_t *q; /* in the order pushed: at most 2 SW_SEARCH_SECTIONS + 1 tasks of each case wait
                  at a time */
    size_t cap, len;
    size_t active;
    size_t side_next; /* the caller's side tasks handed out so far */
    const sw_safety_opts_t *o;
    sw_safety_progress_t prog;
} pool_t;

static void push_task(pool_t *W, case_t *c, int track, int slot)
{
    W->q[W->len++] = (task_t){.c = c, .track = track, .slot = slot};
    if (track != T_PREP)
        c->pending[track]++;
}

/* What trial slot of the current round must get right: the scan's next
 * step depends on the peak of the round's last trial (search.c), the
 * rest only on whether each overturns.  Where that peak is likely to be
 * below SW_SAFETY_NEAR_PEAK again, the trial is made the exact way at
 * once (SW_TRIAL_EXACT: the answer is the same, one fast run less). */
static sw_trial_need search_need(const sw_search_t *S, int slot)
{
    if (S->phase != SW_SEARCH_SCAN || slot != S->n - 1)
        return SW_TRIAL_OUTCOME;
    return S->peak_last < 0.8 * SW_SAFETY_NEAR_PEAK ? SW_TRIAL_EXACT : SW_TRIAL_PEAK;
}

static int task_run(const task_t *t, char *msg, size_t msglen)
{
    case_t *c = t->c;
    switch (t->track) {
        case T_PREP: return sw_safety_prep_make(&c->P, msg, msglen);
        case TR_ONE:
            return sw_safety_trial(&c->P, 1.0, SW_TRIAL_FULL, &c->out->sf.at_one, msg, msglen);
        case TR_BELOW:
            return sw_safety_trial(&c->P, c->below.x[t->slot], search_need(&c->below, t->slot),
                                   &c->below.r[t->slot], msg, msglen);
        default:
            return sw_safety_trial(&c->P, c->above.x[t->slot], search_need(&c->above, t->slot),
                                   &c->above.r[t->slot], msg, msglen);
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
        if (!sw_model_traits_of(P->d.model)->lift_direct || P->log->a_z)
            so.x_min *= LIFT_MARGIN_LOG;
        if (P->log->a_z)
            so.x_min = fmin(so.x_min, LIFT_MARGIN_LOG * P->bare_lift);
    }
    return so;
}

/* The next round of a search track, or none (done). */
static void track_next(pool_t *W, case_t *c, int track)
{
    sw_search_t *S = track == TR_BELOW ? &c->below : &c->above;
    if (c->err[track] || S->phase == SW_SEARCH_DONE) {
        S->n = 0;
        return;
    }
    const int n = sw_search_points(S);
    /* the trial that must get its peak right may take longest: first */
    for (int j = 0; j < n; j++)
        push_task(W, c, track, search_need(S, n - 1) != SW_TRIAL_OUTCOME ? (j + n - 1) % n : j);
}

/* Prepared: the run at 1 and the search below it start together. */
static void case_start(pool_t *W, case_t *c)
{
    sw_safety_t *sf = &c->out->sf;
    c->prepared = 1;
    c->below.phase = c->above.phase = SW_SEARCH_DONE;
    push_task(W, c, TR_ONE, 0);
    if (c->P.a_peak == 0.0)
        return; /* no longitudinal acceleration: no scale changes anything */
    const sw_search_opts_t so = case_search(W, c);
    sf->max_scale = so.x_max;
    sf->lift_scale = c->P.lift_scale;
    sw_search_opts_t sb = so;
    sb.x_max = 1.0;
    if (sb.x_min < 1.0 && sw_search_init(&c->below, &sb, &sf->below) != SW_OK) {
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
        if (sw_search_init(&c->above, &sa, &sf->above) != SW_OK) {
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
                sw_search_feed(&c->below);
            if (k == TR_ABOVE && !c->err[k])
                sw_search_feed(&c->above);
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

/* How long a scene's searches take, roughly, as a rank: a cushion's trials
 * step a stiff model and its rounds form the longest chain of work that
 * must wait for each other (on the hour-long drive of bench/drive_log.py
 * three quarters of all the CPU time, in 14 rounds); a frame's and the
 * bed's are far cheaper per sample (and jump further).  The pool takes the
 * tasks of the heaviest scene first, so that its chain starts at once and
 * never waits behind a lighter scene's trial; the others fill the threads
 * it leaves idle.  Only the order of the work depends on it, never a
 * result. */
static int case_weight(const sw_scene_t *sc)
{
    return sc->has_cushion ? 2 : sc->has_frame ? 1 : 0;
}

static int job_take(void *user, void *task)
{
    pool_t *W = user;
    if (!W->len) { /* no trial waits: the caller's side work, if any is left */
        if (!W->o->side || W->side_next >= W->o->sides)
            return 0;
        const task_t t = {.track = T_SIDE, .side = W->side_next++};
        memcpy(task, &t, sizeof t);
        return 1;
    }
    size_t best = 0; /* the first task of the heaviest scene waiting */
    for (size_t k = 1; k < W->len; k++)
        if (W->q[k].c->weight > W->q[best].c->weight)
            best = k;
    memcpy(task, &W->q[best], sizeof(task_t));
    memmove(&W->q[best], &W->q[best + 1], (W->len - best - 1) * sizeof *W->q);
    W->len--;
    return 1;
}

static int job_ended(void *user)
{
    const pool_t *W = user;
    return !W->active && (!W->o->side || W->side_next >= W->o->sides);
}

static void job_run(void *user, void *task)
{
    const pool_t *W = user;
    task_t *t = task;
    if (t->track == T_SIDE) {
        W->o->side(W->o->side_user, t->side);
        return;
    }
    t->msg[0] = '\0';
    t->err = task_run(t, t->msg, sizeof t->msg);
}

static void job_done(void *user, void *task)
{
    const task_t *t = task;
    if (t->track != T_SIDE)
        task_done(user, t, t->err, t->msg);
}

int sw_safety_factors(sw_safety_case_t *cases, size_t n, const sw_log_t *log,
                      const sw_safety_opts_t *o)
{
    if (!cases || !log || !log->t || !log->a_g || !o || n == 0)
        return SW_EINVAL;
    case_t *cs = calloc(n, sizeof *cs);
    pool_t W = {.cap = n * (2 * SW_SEARCH_SECTIONS + 1) + 1, .o = o, .active = n};
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
        cs[i] = (case_t){.out = out, .weight = case_weight(&out->scene)};
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
