/* SPDX-License-Identifier: GPL-3.0-or-later */
/* reserve_log.c - the smallest reserve along a log (reserve.h,
 * sw_reserve_log_min): the states of one run of the log, taken at a rate,
 * and the reserve evaluated on the few that can hold the minimum; the
 * search itself (reserve_min.h) is also risk.c's minimum-only reserve.
 *
 * Every state has a proven lower bound of its reserve, cheap to compute
 * (sw_reserve_lower_bound: the energy bound, and the lift bound of a
 * package standing on the bed or stuck on its frame), and a state at rest
 * has the value computed once.  Sorted by that bound, smallest first, the
 * states are evaluated until the next one's bound is not below the
 * smallest reserve found: no state after it can hold a smaller one.  The
 * order also finds the minimum early, since the bound is lowest where the
 * package holds the most energy.  Ties keep the earliest state, as a
 * replay's minimum does.
 *
 * Once a smallest value m is known, a state need not be evaluated in
 * full to show that its reserve is not smaller: an evaluation capped at
 * M = m (1 + step) (1 + 1e-9) (max_g, reserve.h) scans the same grid from
 * the same lower bound, lo (1 + step)^k, up to M.  If nothing up to M
 * overturns, the full evaluation's first overturning point on every scan
 * lies above M, the last safe point below it is at least M / (1 + step),
 * and the value it reports, within that bracket, is above m.  Where the
 * smallest reserve stands out (a shock in a long drive) most states are
 * shown so in a few runs; where it does not, the capped scan costs about
 * what the full one would. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "reserve_min.h"
#include "run_int.h"
#include "sched.h"
#include "swaywatch/status.h"

#define DEFAULT_STEP 0.02 /* reserve.h: the scan's relative step when opts.step is 0 */
#define CAP_ROOM 1e-9     /* M is strictly above m (1 + step) */
#define CAP_REUSE 1.1     /* a capped object up to this much above M is used as it is */

void sw_rmin_init(sw_rmin_t *m, const sw_scene_t *sc, const sw_reserve_opts_t *o, sw_reserve_t *r)
{
    memset(m, 0, sizeof *m);
    m->sc = *sc;
    if (o)
        m->opts = *o;
    m->r = r;
}

void sw_rmin_free(sw_rmin_t *m)
{
    sw_reserve_destroy(m->cap);
    m->cap = NULL;
}

/* The capped evaluation for a smallest value min_g (g), made if the one
 * at hand is not right for it; NULL if none can be had (a cap at or
 * below the floor, or create failing: the states are then evaluated in
 * full). */
static sw_reserve_t *capped(sw_rmin_t *m, double min_g)
{
    const double step = m->opts.step > 0.0 ? m->opts.step : DEFAULT_STEP;
    const double M = min_g * (1.0 + step) * (1.0 + CAP_ROOM);
    if (m->cap && m->cap_g >= M && m->cap_g <= CAP_REUSE * M)
        return m->cap;
    sw_reserve_destroy(m->cap);
    m->cap = NULL;
    const double floor_g = m->opts.floor_g > 0.0 ? m->opts.floor_g : SW_RESERVE_FLOOR_G;
    if (!isfinite(M) || !(M > floor_g))
        return NULL;
    sw_reserve_opts_t o = m->opts;
    o.max_g = M;
    int err = SW_OK;
    m->cap = sw_reserve_create(&m->sc, &o, &err, NULL, 0);
    m->cap_g = M;
    return m->cap;
}

static int by_bound(const void *a, const void *b)
{
    const sw_rmin_state_t *x = a, *y = b;
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

int sw_rmin_search(sw_rmin_t *m, sw_rmin_state_t *v, size_t n, long max_evals,
                   sw_reserve_log_t *out)
{
    sw_reserve_t *r = m->r;
    sw_reserve_result_t rest;
    sw_reserve_rest(r, &rest);
    for (size_t i = 0; i < n; i++) {
        v[i].rest = sw_reserve_is_rest(r, &v[i].s);
        v[i].lb = v[i].rest ? rest.reserve_g : bound_of(r, &v[i].s);
    }
    qsort(v, n, sizeof *v, by_bound);
    for (size_t i = 0; i < n; i++) {
        const sw_rmin_state_t *x = &v[i];
        /* sorted: no state from here on can be smaller, nor as small and
         * earlier */
        if (x->lb > out->min_g || (x->lb == out->min_g && x->t >= out->min_time))
            break;
        sw_reserve_result_t res;
        if (x->rest) {
            res = rest;
        } else if (max_evals > 0 && out->evaluated >= max_evals) {
            out->exact = 0;
            out->lower_g = fmin(out->lower_g, x->lb);
            break;
        } else {
            out->evaluated++;
            sw_reserve_t *c = isfinite(out->min_g) ? capped(m, out->min_g) : NULL;
            if (c) {
                const int rc = sw_reserve_eval(c, &x->s, &res);
                if (rc < 0 && rc != SW_EFAULT)
                    return rc;
                if (rc == SW_OK && !res.found)
                    continue; /* its reserve is above the smallest found */
            }
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
    return SW_OK;
}

/* ---- the smallest reserve along a log ------------------------------------------- */

typedef struct {
    sw_sched_t due;
    double period; /* s */
    sw_rmin_state_t *v;
    size_t n, cap;
    int oom;
} sink_t;

static void keep(sink_t *K, double t, const sw_state_t *s)
{
    if (K->n == K->cap) {
        const size_t cap = K->cap ? 2 * K->cap : 1024;
        sw_rmin_state_t *v = realloc(K->v, cap * sizeof *v);
        if (!v) {
            K->oom = 1;
            return;
        }
        K->v = v;
        K->cap = cap;
    }
    sw_rmin_state_t *x = &K->v[K->n++];
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
        out->exact = 1;
        sw_rmin_t M;
        sw_rmin_init(&M, sc, &opt.reserve, r);
        err = sw_rmin_search(&M, K.v, K.n, opt.max_evals, out);
        sw_rmin_free(&M);
        if (out->exact)
            out->lower_g = out->min_g;
        else
            out->lower_g = fmin(out->lower_g, out->min_g);
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
