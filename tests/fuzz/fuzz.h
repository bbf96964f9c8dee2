/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz.h - what the fuzz targets share: a check that aborts (libFuzzer and
 * the sanitizers report an abort as a crash, and the regression replay
 * fails on it), and a cursor over the fuzzer's bytes.
 *
 * Each target is a plain LLVMFuzzerTestOneInput(): built with clang and
 * -fsanitize=fuzzer under SW_FUZZ, and with replay_main.c in every build, so
 * the corpus and the kept crash inputs run as ordinary tests. */
#ifndef SW_FUZZ_H
#define SW_FUZZ_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/swaywatch.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* An invariant of the code under test does not hold: say which, then
 * abort so that the input is kept as a crash. */
#define FZ_CHECK(cond)                                                                   \
    do {                                                                                 \
        if (!(cond)) {                                                                   \
            fprintf(stderr, "%s:%d: invariant failed: %s\n", __FILE__, __LINE__, #cond); \
            abort();                                                                     \
        }                                                                                \
    } while (0)

typedef struct {
    const uint8_t *p;
    size_t n;
} fz_bytes_t;

/* Next byte, 0 once the input is used up (inputs shorter than a record
 * still exercise something). */
static inline uint8_t fz_byte(fz_bytes_t *b)
{
    if (!b->n)
        return 0;
    b->n--;
    return *b->p++;
}

static inline double fz_double(fz_bytes_t *b)
{
    uint64_t u = 0;
    for (int i = 0; i < 8; i++) u = (u << 8) | fz_byte(b);
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

/* The work an engine has done so far: the internal steps of all its
 * packages (their summaries' steps; a stuck package's exact advance counts
 * one).  The targets that stream samples stop taking records once it
 * passes FZ_STEP_BUDGET (half a second of motion at the default 1 ms step
 * for each of two packages: a 10 g braking pulse overturns the bare crate
 * of the seeds in 0.42 s), and keep each record's span short (a bridged gap no longer than
 * FZ_MAX_BRIDGE), so that no input costs more than a few milliseconds
 * under the sanitizers.  The long stretches cut off repeat what the short
 * ones do; the lines the targets reach grew with the rate (HACKING.md,
 * "Fuzzing"). */
#define FZ_STEP_BUDGET 1000
#define FZ_MAX_BRIDGE 0.25 /* s, sw_mon_opts_t.max_bridge (the default is 10 s) */

static inline long fz_steps(const sw_engine_t *e)
{
    long n = 0;
    sw_summary_t s;
    for (size_t k = 0; k < sw_engine_count(e); k++)
        if (sw_engine_summary(e, k, &s) == SW_OK)
            n += s.steps;
    return n;
}

/* Every number an engine output carries must be finite: the engine never
 * hands out NaN or infinity (a package whose state leaves the model is
 * faulted and reset instead). */
static inline void fz_check_output(const sw_output_t *o)
{
    FZ_CHECK(isfinite(o->t));
    FZ_CHECK(isfinite(o->state.u) && isfinite(o->state.u_dot));
    FZ_CHECK(isfinite(o->state.theta) && isfinite(o->state.theta_dot));
    FZ_CHECK(isfinite(o->state.z) && isfinite(o->state.z_dot));
    FZ_CHECK(isfinite(o->margin) && isfinite(o->margin_bound));
    FZ_CHECK(isfinite(o->uplift_ratio));
    FZ_CHECK(isfinite(o->a_g) && isfinite(o->a_support));
    FZ_CHECK(o->state.phase == SW_PHASE_STUCK || o->state.phase == SW_PHASE_ROCKING ||
             o->state.phase == SW_PHASE_OVERTURNED);
    FZ_CHECK(fabs(o->state.theta) <= M_PI_2 + 1e-6);
}

static inline void fz_check_event(const sw_event_t *ev)
{
    FZ_CHECK(ev->kind >= SW_EV_UPLIFT && ev->kind <= SW_EV_FLIGHT);
    FZ_CHECK(isfinite(ev->t) && isfinite(ev->theta) && isfinite(ev->theta_dot));
    FZ_CHECK(isfinite(ev->margin) && isfinite(ev->info));
    FZ_CHECK(fabs(ev->theta) <= M_PI_2 + 1e-6);
}

/* The summary: times are a number or NAN ("none"), never infinite; the
 * rest is finite; counts are not negative. */
static inline void fz_check_summary(const sw_summary_t *s)
{
    FZ_CHECK(!isinf(s->overturn_time) && !isinf(s->tip_time) && !isinf(s->uplift_time));
    FZ_CHECK(s->overturned == !isnan(s->overturn_time));
    FZ_CHECK(isfinite(s->max_abs_theta) && isfinite(s->max_theta_ratio));
    FZ_CHECK(isfinite(s->min_margin) && isfinite(s->min_margin_bound));
    FZ_CHECK(isfinite(s->max_uplift_ratio));
    FZ_CHECK(s->impacts >= 0 && s->uplifts >= 0 && s->rests >= 0 && s->faults >= 0);
    FZ_CHECK(s->max_abs_theta <= M_PI_2 + 1e-6);
}

#endif
