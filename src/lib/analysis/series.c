/* SPDX-License-Identifier: GPL-3.0-or-later */
/* series.c - a long series as the extremes of its stretches (series.h):
 * buckets of each quantity's smallest and largest value and when, merged
 * in pairs when full. */
#include "swaywatch/series.h"

#include <math.h>
#include <stdlib.h>

#include "swaywatch/status.h"

struct sw_series {
    size_t nq, nbuckets;
    sw_extreme_t *b;   /* 2 nbuckets buckets of nq quantities, bucket by bucket */
    size_t nb;         /* full buckets */
    sw_extreme_t *cur; /* the bucket being filled (nq) */
    long in_cur;       /* samples in cur */
    long width;        /* samples per bucket */
};

sw_series_t *sw_series_create(size_t nq, size_t nbuckets)
{
    sw_series_t *s = nq && nbuckets ? calloc(1, sizeof *s) : NULL;
    if (!s)
        return NULL;
    s->nq = nq;
    s->nbuckets = nbuckets;
    s->width = 1;
    s->b = calloc((2 * nbuckets + 1) * nq, sizeof *s->b);
    if (!s->b) {
        free(s);
        return NULL;
    }
    s->cur = s->b + 2 * nbuckets * nq;
    return s;
}

void sw_series_destroy(sw_series_t *s)
{
    if (!s)
        return;
    free(s->b);
    free(s);
}

/* a takes in b's extremes, nq quantities (b is later: a tie keeps a's
 * time); a value that is none yet (NaN) takes b's. */
static void merge(sw_extreme_t *a, const sw_extreme_t *b, size_t nq)
{
    for (size_t q = 0; q < nq; q++) {
        if (b[q].vmin < a[q].vmin || (isnan(a[q].vmin) && !isnan(b[q].vmin))) {
            a[q].vmin = b[q].vmin;
            a[q].tmin = b[q].tmin;
        }
        if (b[q].vmax > a[q].vmax || (isnan(a[q].vmax) && !isnan(b[q].vmax))) {
            a[q].vmax = b[q].vmax;
            a[q].tmax = b[q].tmax;
        }
    }
}

void sw_series_add(sw_series_t *s, double t, const double *v)
{
    const size_t nq = s->nq;
    for (size_t q = 0; q < nq; q++) {
        const sw_extreme_t one = {.tmin = t, .vmin = v[q], .tmax = t, .vmax = v[q]};
        if (s->in_cur == 0)
            s->cur[q] = one;
        else
            merge(&s->cur[q], &one, 1);
    }
    if (++s->in_cur < s->width)
        return;
    for (size_t q = 0; q < nq; q++) s->b[s->nb * nq + q] = s->cur[q];
    s->nb++;
    s->in_cur = 0;
    if (s->nb < 2 * s->nbuckets)
        return;
    /* full: pairs merge, and each bucket covers twice as many samples */
    for (size_t i = 0; i < s->nbuckets; i++) {
        for (size_t q = 0; q < nq; q++) s->b[i * nq + q] = s->b[2 * i * nq + q];
        merge(&s->b[i * nq], &s->b[(2 * i + 1) * nq], nq);
    }
    s->nb = s->nbuckets;
    s->width *= 2;
}

size_t sw_series_count(const sw_series_t *s)
{
    return s->nb + (s->in_cur > 0);
}

int sw_series_get(const sw_series_t *s, size_t i, size_t q, sw_extreme_t *out)
{
    if (q >= s->nq || i >= sw_series_count(s))
        return SW_EINVAL;
    *out = i < s->nb ? s->b[i * s->nq + q] : s->cur[q];
    return SW_OK;
}
