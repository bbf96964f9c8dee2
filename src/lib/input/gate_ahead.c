/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gate_ahead.c - a log without receive times, read through a look-ahead
 * of SW_GATE_LOOKAHEAD samples: a row is refused only when it is off the
 * timeline that the rows around it share, a run back in time is a
 * restart when the old timeline does not outnumber it, and repeated
 * stamps of a coarse clock are spread over their unit. */
#include <math.h>
#include <stdio.h>

#include "gate_int.h"

#define AT(g, i) (&(g)->ahead[((g)->head + (i)) % (g)->window])

/* The order of the look-ahead, counted again (after times were spread). */
static void recount(sw_gate_t *g)
{
    g->desc = g->ndup = 0;
    for (int i = 0; i + 1 < g->nahead; i++) {
        const double a = AT(g, i)->t, b = AT(g, i + 1)->t;
        g->desc += b < a;
        g->ndup += b == a;
    }
}

/* Length of the longest strictly increasing run of look-ahead times in
 * (lo, hi), from index `from` on (patience sorting: n log n, n <= 64). */
static int lis(const sw_gate_t *g, int from, double lo, double hi)
{
    double tails[SW_GATE_LOOKAHEAD];
    int len = 0;
    for (int i = from; i < g->nahead; i++) {
        const double x = AT(g, i)->t;
        if (!(x > lo && x < hi))
            continue;
        int a = 0, b = len;
        while (a < b) {
            const int m = (a + b) / 2;
            if (tails[m] < x)
                a = m + 1;
            else
                b = m;
        }
        tails[a] = x;
        if (a == len)
            len++;
    }
    return len;
}

/* s: the pace of the look-ahead after the front sample (how fast the
 * logger writes from here), as the timing model reads it: the interval
 * below which 90 % of its time is covered; NAN if none. */
static double spacing_after(const sw_gate_t *g)
{
    double v[SW_GATE_LOOKAHEAD], tot = 0.0;
    int n = 0;
    for (int i = 0; i + 1 < g->nahead; i++) {
        const double d = AT(g, i + 1)->t - AT(g, i)->t;
        if (d > 0.0) {
            v[n++] = d;
            tot += d;
        }
    }
    if (n == 0)
        return NAN;
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
            const double x = v[j];
            v[j] = v[j - 1];
            v[j - 1] = x;
        }
    double acc = 0.0;
    for (int i = 0; i < n; i++) {
        acc += v[i];
        if (acc >= TM_QUANTILE * tot)
            return v[i];
    }
    return v[n - 1];
}

/* s: the coarsest decimal unit all times of the look-ahead are whole
 * multiples of, when the distinct times step by about one unit (a logger
 * that stamps whole milliseconds); 0 when there is none. */
static double stamp_unit(const sw_gate_t *g)
{
    static const double units[] = {1.0, 0.1, 0.01, 1e-3, 1e-4, 1e-5, 1e-6};
    for (size_t u = 0; u < sizeof units / sizeof units[0]; u++) {
        const double q = units[u];
        int ok = 1;
        for (int i = 0; i < g->nahead && ok; i++) {
            const double x = AT(g, i)->t / q;
            ok = fabs(x - nearbyint(x)) <= 1e-3 * fmax(1.0, fabs(x) * 1e-12);
        }
        if (!ok)
            continue;
        /* the distinct times: do they step by about one unit? */
        double steps[SW_GATE_LOOKAHEAD];
        int n = 0;
        for (int i = 0; i + 1 < g->nahead; i++) {
            const double d = AT(g, i + 1)->t - AT(g, i)->t;
            if (d > 0.0)
                steps[n++] = d;
        }
        if (n == 0)
            return q;
        for (int i = 1; i < n; i++)
            for (int j = i; j > 0 && steps[j - 1] > steps[j]; j--) {
                const double x = steps[j];
                steps[j] = steps[j - 1];
                steps[j - 1] = x;
            }
        return steps[n / 2] <= 1.5 * q ? q : 0.0;
    }
    return 0.0;
}

/* Repeated times in the look-ahead, enough of them to show a logger that
 * stamps coarser than it samples: spread from here on (said once). */
static void maybe_reconstruct(sw_gate_t *g)
{
    if (g->recon || g->ndup < RECON_MIN)
        return;
    g->recon = 1;
    g->unit = stamp_unit(g);
    g->f.stamp_unit = g->unit;
    const sw_sample_t *p0 = AT(g, 0);
    sw_gate_event_t ev = {.kind = SW_GATE_EV_RECONSTRUCT,
                          .t = p0->t,
                          .t_engine = g->last_engine,
                          .span = g->unit,
                          .where = p0->where};
    gate_emit(g, &ev);
}

/* The front sample starts a run of k equal times: spread them evenly over
 * their unit, or over the time to the next distinct stamp when it is
 * sooner (or when the unit is unknown). */
static void spread_run(sw_gate_t *g)
{
    const double t0 = AT(g, 0)->t;
    int k = 1;
    while (k < g->nahead && AT(g, k)->t == t0) k++;
    if (k == 1)
        return;
    double span = g->unit > 0.0 ? g->unit : INFINITY;
    if (k < g->nahead && AT(g, k)->t > t0)
        span = fmin(span, AT(g, k)->t - t0);
    if (isinf(span)) {
        span = gate_spacing(g) * k; /* the log's end: at the logger's pace */
        if (!(span > 0.0))
            return;
    }
    for (int i = 1; i < k; i++) AT(g, i)->t = t0 + span * i / k;
    g->f.reconstructed += k - 1;
    recount(g);
}

/* Is the front sample, ahead of the timeline, on a longest increasing run
 * of the look-ahead above it?  If not, the rows around it share a timeline
 * it is off. */
static int forward_ok(const sw_gate_t *g, double T)
{
    if (g->desc == 0 || g->o.jump < 0.0)
        return 1;
    const double t0 = AT(g, 0)->t;
    return 1 + lis(g, 1, t0, INFINITY) >= lis(g, 0, T, INFINITY);
}

/* The front sample is behind the timeline: a restart when it starts a run
 * of at least confirm rows back in time that the rows continuing the old
 * timeline do not outnumber. */
static int backward_restart(const sw_gate_t *g, double T)
{
    const double t0 = AT(g, 0)->t;
    const int back = 1 + lis(g, 1, t0, T);
    return back >= g->o.confirm && back > lis(g, 0, T, INFINITY);
}

/* Decide the front sample of the look-ahead, and drop it from there. */
static void decide_front(sw_gate_t *g)
{
    sw_sample_t *p0 = AT(g, 0);
    const double T = g->have_last ? g->last.t : -INFINITY;
    if (g->nahead > 1 && AT(g, 1)->t == p0->t) {
        maybe_reconstruct(g);
        if (g->recon && p0->t > T)
            spread_run(g);
    }
    const sw_sample_t s = *p0;
    const int fwd = s.t > T && forward_ok(g, T);
    const int restart = s.t < T && backward_restart(g, T);
    /* the pace ahead matters only for an interval that looks long (or
     * where a restart begins): read only then */
    double after = NAN;
    if (g->nahead > 1 && g->have_last && (restart || (fwd && gate_looks_long(g, s.t - T))))
        after = spacing_after(g);
    /* leave the window before the callbacks: they may look at the facts */
    if (g->nahead > 1) {
        const double t1 = AT(g, 1)->t;
        g->desc -= t1 < s.t;
        g->ndup -= t1 == s.t;
    }
    g->head = (g->head + 1) % g->window;
    g->nahead--;
    char text[160];
    if (!g->have_last) {
        if (fwd)
            gate_take_first(g, &s);
        else
            gate_refuse_held(g, &s);
        return;
    }
    if (s.t == T) {
        snprintf(text, sizeof text, "time %.15g s is a duplicate (the same as the row before)",
                 s.t);
        gate_refuse(g, &s, SW_GATE_REJ_DUPLICATE, text);
        return;
    }
    if (s.t > T) {
        if (fwd)
            gate_advance(g, &s, after);
        else
            gate_refuse_held(g, &s);
        return;
    }
    if (restart) {
        int iv;
        const double te = gate_resume(g, &s, gate_gap_threshold(g, after), &iv);
        gate_take(g, &s, te, iv);
    } else {
        gate_refuse_held(g, &s);
    }
}

int gate_ahead_push(sw_gate_t *g, const sw_sample_t *s)
{
    if (g->nahead > 0) {
        const double tl = AT(g, g->nahead - 1)->t;
        g->desc += s->t < tl;
        g->ndup += s->t == tl;
    }
    *AT(g, g->nahead) = *s;
    g->nahead++;
    while (g->nahead >= g->window) decide_front(g);
    return SW_GATE_HELD;
}

void gate_ahead_drain(sw_gate_t *g)
{
    while (g->nahead > 0) decide_front(g);
}
