/* SPDX-License-Identifier: GPL-3.0-or-later */
/* reserve_log.c - the smallest reserve along a log (reserve.h,
 * sw_reserve_log_min): the states of one run of the log, taken at a rate,
 * and the reserve evaluated on the few that can hold the minimum.
 *
 * Every state has a proven lower bound of its reserve, cheap to compute
 * (sw_reserve_lower_bound: the energy bound, and the lift bound of a
 * package standing on the bed or stuck on its frame), and a state at rest
 * has the value computed once.  Sorted by that bound, smallest first, the
 * states are evaluated until the next one's bound is not below the
 * smallest reserve found: no state after it can hold a smaller one.  The
 * order also finds the minimum early, since the bound is lowest where the
 * package holds the most energy.  Ties keep the earliest state, as a
 * replay's minimum does. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run_int.h"
#include "sched.h"
#include "swaywatch/reserve.h"
#include "swaywatch/status.h"

typedef struct {
    double t;  /* s, log time */
    double lb; /* g, the proven lower bound of its reserve; the value at rest */
    int rest;  /* at rest: lb is its reserve */
    sw_state_t s;
} taken_t;

typedef struct {
    sw_sched_t due;
    double period; /* s */
    taken_t *v;
    size_t n, cap;
    int oom;
} sink_t;

static void keep(sink_t *K, double t, const sw_state_t *s)
{
    if (K->n == K->cap) {
        const size_t cap = K->cap ? 2 * K->cap : 1024;
        taken_t *v = realloc(K->v, cap * sizeof *v);
        if (!v) {
            K->oom = 1;
            return;
        }
        K->v = v;
        K->cap = cap;
    }
    taken_t *x = &K->v[K->n++];
    memset(x, 0, sizeof *x);
    x->t = t;
    x->s = *s;
}

static void take(void *user, const sw_output_t *o)
{
    sink_t *K = ((sw_runner_t *)user)->state_user;
    if (!K->oom && sw_sched_due(&K->due, o->t, K->period))
        keep(K, o->t, &o->state);
}

static int by_bound(const void *a, const void *b)
{
    const taken_t *x = a, *y = b;
    if (x->lb != y->lb)
        return x->lb < y->lb ? -1 : 1;
    return (x->t > y->t) - (x->t < y->t);
}

/* The smallest lower bound over the design pulses and both directions. */
static double bound_of(const sw_reserve_t *r, const sw_state_t *s)
{
    const size_t np = sw_reserve_pulses(r, NULL);
    double lb = INFINITY;
    for (size_t j = 0; j < np; j++)
        for (int dir = -1; dir <= 1; dir += 2) lb = fmin(lb, sw_reserve_lower_bound(r, s, dir, j));
    return isfinite(lb) ? lb : 0.0;
}

/* Evaluate the taken states smallest bound first into out. */
static int search(sw_reserve_t *r, taken_t *v, size_t n, long max_evals, sw_reserve_log_t *out)
{
    sw_reserve_result_t rest;
    sw_reserve_rest(r, &rest);
    for (size_t i = 0; i < n; i++) {
        v[i].rest = sw_reserve_is_rest(r, &v[i].s);
        v[i].lb = v[i].rest ? rest.reserve_g : bound_of(r, &v[i].s);
    }
    qsort(v, n, sizeof *v, by_bound);
    out->exact = 1;
    for (size_t i = 0; i < n; i++) {
        const taken_t *x = &v[i];
        /* sorted: no state from here on can be smaller, nor as small and
         * earlier */
        if (x->lb > out->min_g || (x->lb == out->min_g && x->t >= out->min_time))
            break;
        sw_reserve_result_t res;
        if (x->rest) {
            res = rest;
        } else if (max_evals > 0 && out->evaluated >= max_evals) {
            out->exact = 0;
            out->lower_g = x->lb;
            break;
        } else {
            out->evaluated++;
            const int rc = sw_reserve_eval(r, &x->s, &res);
            if (rc == SW_EFAULT)
                out->faults++;
            else if (rc < 0)
                return rc;
        }
        if (res.reserve_g < out->min_g || (res.reserve_g == out->min_g && x->t < out->min_time)) {
            out->min_g = res.reserve_g;
            out->min_time = x->t;
            out->direction = res.direction;
            out->pulse = res.pulse;
        }
    }
    if (out->exact)
        out->lower_g = out->min_g;
    else
        out->lower_g = fmin(out->lower_g, out->min_g);
    return SW_OK;
}

int sw_reserve_log_min(const sw_scene_t *sc, const sw_log_t *log, const sw_reserve_log_opts_t *o,
                       sw_reserve_log_t *out, char *msg, size_t msglen)
{
    sw_set_msg(msg, msglen, "%s", "");
    if (!sc || !log || !log->t || !log->a_g || !out)
        return SW_EINVAL;
    memset(out, 0, sizeof *out);
    out->min_g = out->min_time = out->lower_g = NAN;
    sw_reserve_log_opts_t opt;
    memset(&opt, 0, sizeof opt);
    if (o)
        opt = *o;
    const double rate = opt.rate > 0.0 ? opt.rate : SW_RESERVE_LOG_RATE; /* Hz */
    if (!(rate < 1e9) || opt.max_evals < 0) {
        sw_set_msg(msg, msglen, "bad options (rate %g Hz, max_evals %ld)", rate, opt.max_evals);
        return SW_EINVAL;
    }
    int err = SW_OK;
    sw_reserve_t *r = sw_reserve_create(sc, &opt.reserve, &err, msg, msglen);
    if (!r)
        return err;
    sink_t K = {.period = 1.0 / rate};
    sw_sched_reset(&K.due);
    sw_runner_t R;
    if (sw_runner_make_watched(&R, sc, &opt.run, 0.0, take, &K, &err, msg, msglen) != SW_OK) {
        sw_reserve_destroy(r);
        return err;
    }
    sw_run_result_t rr;
    memset(&rr, 0, sizeof rr);
    err = sw_run_log_on(&R, log, 1.0, &opt.run, &rr);
    if (err == SW_OK && rr.overturned && !K.oom) {
        /* the run stops at the overturn, perhaps before the next state is
         * due: the overturned state, reserve 0, at its time */
        sw_state_t s;
        sw_engine_get_state(R.e, 0, &s);
        keep(&K, rr.overturn_time, &s);
    }
    sw_engine_destroy(R.e);
    if (err == SW_EFAULT)
        sw_set_msg(msg, msglen, "the model faulted during the run of the log");
    if (err == SW_OK && K.oom)
        err = SW_ENOMEM;
    if (err == SW_OK) {
        out->states = K.n;
        out->min_g = out->lower_g = INFINITY;
        err = search(r, K.v, K.n, opt.max_evals, out);
        if (!K.n)
            out->min_g = out->lower_g = NAN;
    }
    if (err == SW_EINVAL)
        sw_set_msg(msg, msglen, "the log has no usable sample");
    else if (err < 0 && !(msg && msg[0]))
        sw_set_msg(msg, msglen, "%s", sw_strerror(err));
    free(K.v);
    sw_reserve_destroy(r);
    return err;
}
