/* SPDX-License-Identifier: GPL-3.0-or-later */
/* numeric.h - what the hot paths ask of the compiler (inline, out of
 * line), and the engine's max and min of finite numbers, inline where
 * libm's are calls.  A leaf: it knows nothing of packages or engines.
 * The step layer, the schemes and the models write their few comparisons
 * in place: on a sample's path only the engine's files call into this
 * header (scripts/arch/sample-path.sh).  Internal. */
#ifndef SWAYWATCH_NUMERIC_H
#define SWAYWATCH_NUMERIC_H

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

/* max and min of numbers known to be finite: inline where libm's fmax and
 * fmin are calls (they must handle NaN), for the engine's per-step
 * checks (engine.c, flight.c). */
static inline double sw_max2(double a, double b)
{
    return a > b ? a : b;
}

static inline double sw_min2(double a, double b)
{
    return a < b ? a : b;
}

#endif
