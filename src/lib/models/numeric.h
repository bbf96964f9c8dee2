/* SPDX-License-Identifier: GPL-3.0-or-later */
/* numeric.h - small numerical helpers of the engine's hot paths: inline
 * where libm's are calls or branch (checked on every step and sample).  A
 * leaf: it knows nothing of packages or engines.  Internal. */
#ifndef SWAYWATCH_NUMERIC_H
#define SWAYWATCH_NUMERIC_H

#include <stddef.h>

/* GCC and clang: inline even where the size heuristics would not (each
 * scheme's stages are where the time goes). */
#if defined(__GNUC__)
#define SW_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define SW_ALWAYS_INLINE inline
#endif

/* ... and out of line where the rare path, inlined, would make the common
 * one save registers on every call (a step's hand-over to the phase
 * machine). */
#if defined(__GNUC__)
#define SW_NOINLINE __attribute__((noinline))
#else
#define SW_NOINLINE
#endif

/* Every v[i] finite?  0 v is 0 for a finite v and NaN for an infinite or
 * NaN one, so the sum of them is 0 exactly when all are finite: two
 * multiply-adds a number and no branch, in two chains that overlap (the
 * state and the report are checked on every step and sample). */
static inline int sw_all_finite(const double v[], size_t n)
{
    double s0 = 0.0, s1 = 0.0;
    size_t i = 0;
    for (; i + 1 < n; i += 2) {
        s0 += 0.0 * v[i];
        s1 += 0.0 * v[i + 1];
    }
    if (i < n)
        s0 += 0.0 * v[i];
    return s0 + s1 == 0.0;
}

/* max and min of numbers known to be finite: inline where libm's fmax and
 * fmin are calls (they must handle NaN), for the per-step checks. */
static inline double sw_max2(double a, double b)
{
    return a > b ? a : b;
}

static inline double sw_min2(double a, double b)
{
    return a < b ? a : b;
}

#endif
