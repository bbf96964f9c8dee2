/* SPDX-License-Identifier: GPL-3.0-or-later */
/* bench.h - what the parts of sw_bench share: the synthetic road log and
 * the straightforward GSL baseline it is compared with. */
#ifndef SW_BENCH_H
#define SW_BENCH_H

#include <stddef.h>

#include "swaywatch/swaywatch.h"

/* A log of n samples at rate Hz: t[i] = i / rate (s), a[i] longitudinal bed
 * acceleration (m/s^2). */
typedef struct {
    size_t n;
    double rate; /* Hz */
    double *t, *a;
} bench_log_t;

/* Road vibration (band-limited noise, ~0.06 g rms) with braking manoeuvres
 * (up to 0.17 g, seconds long) and pothole/bump shocks (tens of ms, up to
 * ~0.7 g) at random times; deterministic for a seed.  Returns 0, or -1 when
 * out of memory. */
int bench_log_make(bench_log_t *log, double seconds, double rate, unsigned long long seed);
void bench_log_free(bench_log_t *log);
/* The same samples one at a time, without storing them (for long CSVs). */
typedef struct bench_road bench_road_t;
bench_road_t *bench_road_create(double rate, unsigned long long seed);
double bench_road_next(bench_road_t *r); /* next sample, m/s^2 */
void bench_road_destroy(bench_road_t *r);
/* The hard stop of sample_logs/hard-stop-overturn.csv, vibration left out,
 * u s after its start (8 s long; m/s^2). */
double bench_hard_stop(double u);
#define BENCH_HARD_STOP_S 8.0

/* Straightforward implementation: gsl_odeiv2_driver_apply (rkf45, reset
 * every sample) from one sample to the next, events found by a sign change
 * at the sample's end and bisection (re-integrating from the sample start).
 * Bare and frame only.  Fills the summary fields it knows. */
int bench_baseline_run(const sw_scene_t *sc, const bench_log_t *log, double eps, sw_summary_t *s);

#endif
