/* SPDX-License-Identifier: GPL-3.0-or-later */
/* series.h - a long series kept in bounded memory as the extremes of its
 * stretches, so that a figure of a drive of hours draws every peak.
 *
 * Each sample gives nq quantities at a time t (s).  A bucket keeps, for
 * each quantity, its smallest and largest value over the samples it
 * covers and when each was first reached.  A bucket covers one sample at
 * first; when 2 nbuckets buckets are full, neighbours merge in pairs and
 * each covers twice as many samples from then on, so the buckets hold
 * between nbuckets and 2 nbuckets stretches of equal length whatever the
 * series' length.  A NaN is "none yet" (a quantity not evaluated at
 * every sample): a bucket takes the first value that is not.
 *
 * Memory: everything in sw_series_create(); adding allocates nothing.
 * No I/O, no global state; one thread at a time per object. */
#ifndef SWAYWATCH_SERIES_H
#define SWAYWATCH_SERIES_H

#include <stddef.h>

#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sw_series sw_series_t;

/* The extremes of one quantity over one bucket. */
typedef struct {
    double tmin, vmin; /* s, and the smallest value (NaN: none) */
    double tmax, vmax; /* s, and the largest */
} sw_extreme_t;

/* A series of nq quantities (nq >= 1) in nbuckets to 2 nbuckets buckets
 * (nbuckets >= 1); NULL when out of memory or nq or nbuckets is 0. */
SW_API sw_series_t *sw_series_create(size_t nq, size_t nbuckets);
/* Free it; NULL is accepted. */
SW_API void sw_series_destroy(sw_series_t *s);
/* One sample: v[0..nq-1] at t (s), t not before the last sample's. */
SW_API void sw_series_add(sw_series_t *s, double t, const double *v);
/* The buckets so far, in time order, the one being filled last. */
SW_API size_t sw_series_count(const sw_series_t *s);
/* Quantity q of bucket i (< sw_series_count) into *out: SW_OK, or
 * SW_EINVAL for no such bucket or quantity. */
SW_API int sw_series_get(const sw_series_t *s, size_t i, size_t q, sw_extreme_t *out);

#ifdef __cplusplus
}
#endif
#endif
