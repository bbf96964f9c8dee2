/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gate_pace.c - the logger's pace as the gate learns it (docs/timing.md):
 * a time-weighted histogram of every interval and a ring of the recent
 * ones, their quantiles, the spacing they give, and the thresholds that
 * follow from it: what interval looks long, what a gap is, how far a
 * sample may run ahead of real time.  A leaf of the gate: what takes a
 * sample (gate_timing.c), what refuses one and judges a second timeline
 * (gate_contest.c) and the live and look-ahead paths ask it; it asks
 * none of them. */
#include <math.h>

#include "gate_int.h"

/* The bin of an interval whose position in decades above HIST_LO is x. */
static int tm_bin(double x)
{
    const int b = (int)floor(x * TM_PER_DECADE);
    return b < 0 ? 0 : b >= TM_BINS ? TM_BINS - 1 : b;
}

static void sort_doubles(double *v, int n)
{
    for (int i = 1; i < n; i++) /* insertion sort: at most 64 numbers, most in order */
        for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
            const double x = v[j];
            v[j] = v[j - 1];
            v[j - 1] = x;
        }
}

static double median8(const double *ring, long n)
{
    double v[RECENT];
    const int k = n <= 0 ? 0 : n < RECENT ? (int)n : RECENT;
    if (k == 0)
        return NAN;
    for (int i = 0; i < k; i++) v[i] = ring[i];
    sort_doubles(v, k);
    return v[k / 2];
}

/* The interval below which q of the time of v[0..n) is covered (sorts v). */
double gate_time_quantile(double *v, int n, double q)
{
    if (n == 0)
        return NAN;
    double tot = 0.0;
    for (int i = 0; i < n; i++) tot += v[i];
    sort_doubles(v, n);
    double acc = 0.0;
    for (int i = 0; i < n; i++) {
        acc += v[i];
        if (acc >= q * tot)
            return v[i];
    }
    return v[n - 1];
}

/* The last k intervals of the ring (only the learnable ones if ok_only),
 * newest first, into v; their count. */
static int ring_last(const timing_t *tm, double *v, int k, int ok_only)
{
    const int n = tm->nring < k ? (int)tm->nring : k;
    int m = 0;
    for (int i = 0; i < n; i++) {
        const long j = (tm->nring - 1 - i) % RING;
        if (!ok_only || tm->ring_ok[j])
            v[m++] = tm->ring[j];
    }
    return m;
}

/* The time-weighted 90th percentile interval: the interval length below
 * which 90 % of the time the histogram remembers is covered (the mean
 * interval of its bin).  Weighted by time, so that bursts of short
 * intervals, however many, do not hide the pace of the rest; a high
 * quantile, so that a pace the logger keeps a tenth of the time is its
 * own, not a gap. */
static void tm_refresh(timing_t *tm)
{
    tm->since = 0;
    if (!(tm->total > 0.0)) {
        tm->spacing = NAN;
        return;
    }
    double acc = 0.0;
    for (int b = 0; b < TM_BINS; b++) {
        acc += tm->w[b];
        if (acc >= TM_QUANTILE * tm->total) {
            tm->spacing = tm->c[b] > 0.0 ? tm->w[b] / tm->c[b] : NAN;
            return;
        }
    }
    tm->spacing = NAN;
}

/* An interval between two accepted samples: every one into the recent
 * ring (ok: learnable); the ones that teach the pace (long_run) into the
 * long-run histogram. */
void gate_tm_add(timing_t *tm, double dt, double x, int long_run, int ok)
{
    tm->ring_ok[tm->nring % RING] = (char)ok;
    tm->ring[tm->nring++ % RING] = dt;
    tm->seen++;
    tm->covered += dt;
    if (!long_run)
        return;
    const int b = tm_bin(x);
    tm->w[b] += dt;
    tm->c[b] += 1.0;
    tm->total += dt;
    tm->n += 1.0;
    if (tm->total > TM_WINDOW) { /* forget slowly: a new rate takes over */
        for (int i = 0; i < TM_BINS; i++) {
            tm->w[i] *= 0.5;
            tm->c[i] *= 0.5;
        }
        tm->total *= 0.5;
        tm->n *= 0.5;
    }
    if (++tm->since >= TM_REFRESH || tm->n < 2.0 * TM_REFRESH || isnan(tm->spacing))
        tm_refresh(tm);
}

/* s: the logger's spacing now, the larger of the long-run one and the
 * median of the last eight intervals (a rate that dropped is followed
 * within a few samples); NAN before any interval.  Cheap: for every
 * sample. */
double gate_spacing(const sw_gate_t *g)
{
    double v[RECENT];
    const int n = ring_last(&g->tm, v, RECENT, 0);
    return gate_fmax_nan(g->tm.spacing, median8(v, n));
}

/* The same, and the pace of the last 64 intervals weighted by the time
 * each covers (all of them, or the learnable ones): a FIFO read every 30
 * samples, or the pause between two bursts, is the logger's pace from
 * its second time on; an outage is forgotten 64 samples later.  For
 * intervals that look long. */
double gate_spacing_full(const sw_gate_t *g, int ok_only)
{
    double v[RING];
    const int n = ring_last(&g->tm, v, RING, ok_only);
    return gate_fmax_nan(gate_spacing(g), gate_time_quantile(v, n, TM_QUANTILE));
}

/* s: the longest of the last 64 intervals taken (NAN: none). */
double gate_recent_max(const sw_gate_t *g)
{
    double v[RING];
    const int n = ring_last(&g->tm, v, RING, 0);
    double m = NAN;
    for (int i = 0; i < n; i++)
        if (isnan(m) || v[i] > m)
            m = v[i];
    return m;
}

/* Is an interval dt beyond the cheap threshold (the long-run pace alone,
 * then with the median of the last eight: the threshold only grows)?  If
 * not, it is no gap whatever a closer look says; for every sample. */
int gate_looks_long(const sw_gate_t *g, double dt)
{
    if (!isnan(g->tm.spacing) && !(dt > gate_threshold_of(g, g->tm.spacing)))
        return 0;
    return dt > gate_threshold_of(g, gate_spacing(g));
}

double gate_threshold_of(const sw_gate_t *g, double s)
{
    if (g->o.gap > 0.0)
        return g->o.gap;
    return isnan(s) ? INFINITY : fmax(GAP_FLOOR, GAP_FACTOR * s);
}

/* s: longer intervals are gaps, whatever the stream has seen; after: the
 * spacing of the intervals that follow (the look-ahead), NAN if unknown. */
double gate_gap_threshold_of(const sw_gate_t *g, double after)
{
    return gate_threshold_of(g, gate_fmax_nan(gate_spacing_full(g, 0), after));
}

/* Live, the first WARM_N intervals teach the pace (the first read of a
 * FIFO, the first of two CAN frames): none of them is a gap, unless it is
 * longer than max_bridge (the timer of a monitor still sees a silence). */
int gate_warming(const sw_gate_t *g)
{
    return g->o.gap == 0.0 && !isnan(g->last.rx) && g->tm.seen < WARM_N;
}

double gate_gap_threshold(const sw_gate_t *g, double after)
{
    return gate_warming(g) ? INFINITY : gate_gap_threshold_of(g, after);
}

/* s: how far a sample may run ahead of the time that really passed. */
double gate_jump_tol(const sw_gate_t *g)
{
    if (g->o.jump < 0.0)
        return INFINITY;
    if (g->o.jump > 0.0)
        return g->o.jump;
    const double s = gate_spacing(g);
    return isnan(s) ? 1.0 : fmax(JUMP_FLOOR, JUMP_FACTOR * s); /* none yet: 1 s */
}
