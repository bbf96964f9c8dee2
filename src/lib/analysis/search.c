/* SPDX-License-Identifier: GPL-3.0-or-later */
/* search.c - the lowest value that overturns a package (search.h): the
 * resumable scan-then-bisect search in rounds (search_int.h) whose trials
 * the caller runs where it likes, and the blocking search over a trial
 * function that drives it, with the safe islands above it. */
#include <math.h>
#include <string.h>

#include "search_int.h"
#include "swaywatch/search.h"
#include "swaywatch/status.h"

#define DEFAULT_STEP 0.02
#define DEFAULT_TOL 1e-3
#define FAR_STEPS 5.0 /* the scan's step far from SW_SEARCH_NEAR_PEAK, in --step */

/* ---- threshold search ----------------------------------------------------- */

typedef struct {
    sw_trial_fn f;
    void *user;
    double tol;
    long *trials;
} search_t;

static int trial(const search_t *S, double x, sw_run_result_t *r)
{
    memset(r, 0, sizeof *r);
    (*S->trials)++;
    return S->f(S->user, x, r);
}

/* Bisect between xs (safe) and xo (overturning), in either order, to the
 * relative tolerance; *safe gets the final safe end.  Geometric
 * midpoints, as the search's. */
static int bisect(const search_t *S, double xs, double xo, double *safe)
{
    sw_run_result_t r;
    for (;;) {
        const double lo = fmin(xs, xo), hi = fmax(xs, xo);
        if (hi / lo - 1.0 <= S->tol)
            break;
        const double m = sqrt(lo * hi);
        if (!(m > lo && m < hi))
            break;
        const int rc = trial(S, m, &r);
        if (rc < 0)
            return rc;
        if (r.overturned)
            xo = m;
        else
            xs = m;
    }
    *safe = xs;
    return SW_OK;
}

int sw_threshold_search(sw_trial_fn f, void *user, const sw_search_opts_t *o, sw_threshold_t *out)
{
    if (!f || !o || !out)
        return SW_EINVAL;
    /* the lowest overturn: the resumable search, one point a round on the
     * grid x_min (1 + step)^k */
    const sw_search_how_t how = {.per_round = 1, .fixed_step = 1};
    sw_search_t T;
    int rc = sw_search_init_how(&T, o, &how, out);
    if (rc != SW_OK)
        return rc;
    const double tol = T.o.tol; /* resolved (the search widens its own at its end) */
    while (sw_search_points(&T)) {
        memset(&T.r[0], 0, sizeof T.r[0]);
        if ((rc = f(user, T.x[0], &T.r[0])) < 0) {
            out->trials++; /* a run made, as any */
            return rc;
        }
        sw_search_feed(&T);
    }
    if (!out->found || !o->islands)
        return SW_OK;

    /* map the safe islands above: walk the same scan grid to x_max from
     * its first overturning point */
    search_t S = {f, user, tol, &out->trials};
    sw_run_result_t r;
    long k = T.k;
    double x, prev = fmin(o->x_min * pow(1.0 + T.o.step, (double)k), o->x_max);
    int over = 1;
    sw_island_t cur = {0.0, 0.0, 0};
    while (prev < o->x_max) {
        k++;
        x = fmin(o->x_min * pow(1.0 + T.o.step, (double)k), o->x_max);
        if ((rc = trial(&S, x, &r)) < 0)
            return rc;
        if (over && !r.overturned) {
            if ((rc = bisect(&S, x, prev, &cur.lo)) < 0)
                return rc;
            over = 0;
        } else if (!over && r.overturned) {
            if ((rc = bisect(&S, prev, x, &cur.hi)) < 0)
                return rc;
            cur.open = 0;
            if (out->n_islands < SW_MAX_ISLANDS)
                out->islands[out->n_islands++] = cur;
            else
                out->islands_truncated = 1;
            over = 1;
        }
        prev = x;
    }
    if (!over) {
        cur.hi = o->x_max;
        cur.open = 1;
        if (out->n_islands < SW_MAX_ISLANDS)
            out->islands[out->n_islands++] = cur;
        else
            out->islands_truncated = 1;
    }
    return SW_OK;
}

/* ---- the resumable search, in rounds ----------------------------------------- */

int sw_search_init(sw_search_t *S, const sw_search_opts_t *o, sw_threshold_t *out)
{
    return sw_search_init_how(S, o, NULL, out);
}

int sw_search_init_how(sw_search_t *S, const sw_search_opts_t *o, const sw_search_how_t *how,
                       sw_threshold_t *out)
{
    memset(S, 0, sizeof *S);
    memset(out, 0, sizeof *out);
    S->o = *o;
    if (how)
        S->how = *how;
    if (!(S->how.per_round >= 1 && S->how.per_round <= SW_SEARCH_SECTIONS))
        S->how.per_round = SW_SEARCH_SECTIONS;
    S->lo = S->how.safe;
    S->out = out;
    if (!(S->o.step > 0.0))
        S->o.step = DEFAULT_STEP;
    if (!(S->o.tol > 0.0))
        S->o.tol = DEFAULT_TOL;
    if (!(o->x_min > 0.0) || !(o->x_max > o->x_min) || !isfinite(o->x_max) ||
        !isfinite(S->o.step) || !isfinite(S->o.tol)) {
        S->phase = SW_SEARCH_DONE;
        return SW_EINVAL;
    }
    return SW_OK;
}

/* The bracket [lo, hi] is found: done if it is narrow enough. */
static void bracket(sw_search_t *S)
{
    S->phase = SW_SEARCH_SECT;
    if (S->hi / S->lo - 1.0 > S->o.tol)
        return;
    S->phase = SW_SEARCH_DONE;
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
 * fine as asked.  A fixed step does not grow. */
static double scan_step(const sw_search_t *S)
{
    if (S->how.fixed_step)
        return S->o.step;
    const double near = fmin(1.0, fmax(0.0, S->peak_last / SW_SEARCH_NEAR_PEAK));
    return S->o.step * (FAR_STEPS - (FAR_STEPS - 1.0) * near);
}

/* The scales of the next round (S->n of them; 0 when done). */
int sw_search_points(sw_search_t *S)
{
    const int per = S->how.per_round;
    S->n = 0;
    if (S->phase == SW_SEARCH_PROBE) {
        S->x[S->n++] = S->hi;
    } else if (S->phase == SW_SEARCH_SCAN) {
        const double f = 1.0 + scan_step(S);
        for (int j = 0; j < per; j++) {
            const double x = S->how.fixed_step
                                 ? fmin(S->o.x_min * pow(f, (double)(S->k + j)), S->o.x_max)
                             : S->k == 0 ? fmin(S->o.x_min * pow(f, j), S->o.x_max)
                                         : fmin(S->x_last * pow(f, j + 1.0), S->o.x_max);
            S->x[S->n++] = x;
            if (x >= S->o.x_max)
                break; /* the scan's last point is x_max itself */
        }
    } else if (S->phase == SW_SEARCH_SECT) {
        const double ratio = S->hi / S->lo;
        double prev = S->lo;
        for (int j = 1; j <= per; j++) {
            /* one point: the geometric midpoint, rounded once */
            const double x =
                per == 1 ? sqrt(S->lo * S->hi) : S->lo * pow(ratio, (double)j / (per + 1));
            if (x > prev && x < S->hi)
                S->x[S->n++] = prev = x;
        }
        if (!S->n) { /* no scale left between them: as narrow as it gets */
            S->o.tol = INFINITY;
            bracket(S);
        }
    }
    return S->n;
}

void sw_search_probe(sw_search_t *S, double x)
{
    S->phase = SW_SEARCH_PROBE;
    S->hi = x;
}

/* The round's results: the lowest overturning scale wins, with the safe
 * one just below it. */
void sw_search_feed(sw_search_t *S)
{
    S->out->trials += S->n;
    int j = 0;
    while (j < S->n && !S->r[j].overturned) j++;
    if (j == S->n) { /* all safe */
        S->lo = S->x[S->n - 1];
        if (S->phase == SW_SEARCH_SECT) {
            bracket(S);
        } else if (S->phase == SW_SEARCH_PROBE) {
            S->phase = SW_SEARCH_DONE;
        } else {
            S->x_last = S->lo;
            S->peak_last = S->r[S->n - 1].max_theta_ratio;
            S->k += S->n;
            if (S->x[S->n - 1] >= S->o.x_max)
                S->phase = SW_SEARCH_DONE; /* nothing overturns */
        }
        return;
    }
    if (S->phase != SW_SEARCH_SECT && S->k + j == 0) {
        /* the first point run overturns: the threshold may be lower, down
         * to how.safe */
        S->phase = SW_SEARCH_DONE;
        S->out->found = S->out->at_min = 1;
        S->out->x = S->x[0];
        S->out->x_safe = S->lo;
        S->out->at_x = S->r[0];
        return;
    }
    S->lo = j > 0 ? S->x[j - 1] : S->lo;
    S->hi = S->x[j];
    S->r_hi = S->r[j];
    bracket(S);
}
