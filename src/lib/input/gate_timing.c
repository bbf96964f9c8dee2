/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gate_timing.c - a sample taken into the engine (docs/timing.md): at its
 * time, or across a gap, a clock step or a restart at a cost independent
 * of its length, with what it teaches the logger's pace (gate_pace.c) and
 * the log's facts. */
#include <math.h>
#include <string.h>

#include "gate_int.h"

/* The facts' interval histogram (count-based, the whole log). */
static void note_interval(sw_gate_t *g, double dt, double x)
{
    if (!(dt > 0.0))
        return;
    if (isnan(g->f.dt_min) || dt < g->f.dt_min)
        g->f.dt_min = dt;
    if (isnan(g->f.dt_max) || dt > g->f.dt_max)
        g->f.dt_max = dt;
    int b = (int)floor(x * HIST_PER_DECADE);
    if (b < 0)
        b = 0;
    if (b >= HIST_BINS)
        b = HIST_BINS - 1;
    g->hist[b]++;
    g->hist_sum[b] += dt;
    if (g->hist_n++ == 0)
        g->hist_lo = g->hist_hi = b;
    else if (b < g->hist_lo)
        g->hist_lo = b;
    else if (b > g->hist_hi)
        g->hist_hi = b;
}

/* Could the motion across a gap have mattered?  A package rocking, or the
 * bed at either end of the gap at a quarter of a package's uplift
 * threshold or more: what the gap hid (a braking's peak, a shock) can have
 * lifted or overturned it, and no interpolation knows.  A quiet bed and
 * standing packages at both ends leave the verdict complete. */
static int motion_near(const sw_gate_t *g, double a_next)
{
    for (size_t k = 0; k < sw_engine_count(g->e); k++) {
        sw_output_t o;
        if (sw_engine_get_output(g->e, k, &o) != SW_OK)
            continue;
        if (o.state.phase == SW_PHASE_ROCKING || o.uplift_ratio >= 0.25)
            return 1;
        const sw_derived_t *d = sw_engine_derived(g->e, k);
        /* g from p^2 = 3 g / (4 R): the scene's own gravity */
        const double grav = d->p * d->p * 4.0 * d->R / 3.0;
        if (fabs(a_next) >= 0.25 * grav * tan(d->alpha))
            return 1;
    }
    return 0;
}

static void count_gap(sw_gate_t *g, double span)
{
    g->f.gaps++;
    g->f.gap_total += span;
    if (span > g->f.gap_max)
        g->f.gap_max = span;
}

/* The envelope: the largest stamp minus arrival of the last ENV_N samples
 * (a sliding maximum, scanned again only when the largest leaves). */
static void env_add(sw_gate_t *g, double off)
{
    if (!g->have_env) {
        g->nenv = 0;
        g->have_env = 1;
    }
    const long i = g->nenv++;
    g->env_ring[i % ENV_N] = off;
    if (i == 0 || off >= g->env) {
        g->env = off;
        g->env_at = i;
    } else if (i - g->env_at >= ENV_N) { /* the largest is gone: the next one */
        const long lo = g->nenv > ENV_N ? g->nenv - ENV_N : 0;
        g->env_at = lo;
        for (long k = lo; k < g->nenv; k++)
            if (g->env_ring[k % ENV_N] >= g->env_ring[g->env_at % ENV_N])
                g->env_at = k;
        g->env = g->env_ring[g->env_at % ENV_N];
    }
}

/* One horizontal axis's facts (the longitudinal's, the lateral's) with
 * an accepted value a (m/s^2): the plausibility check reads them. */
static inline void axis_add(double a, double *peak, long *above_half_g, double *min, double *max,
                            double *sum_abs)
{
    const double aa = fabs(a);
    if (aa > *peak)
        *peak = aa;
    if (aa > 0.5 * SW_G0)
        ++*above_half_g;
    if (isnan(*min) || a < *min)
        *min = a;
    if (isnan(*max) || a > *max)
        *max = a;
    *sum_abs += aa;
}

/* Live, is an interval dt (s) that was not normal (a gap, normal only
 * beside one, the warm-up's) the logger's pace all the same?  It is when
 * the interval before it was as long (within PACED_RATIO: the logger wrote
 * at that pace for a stretch, as a 10 Hz logger does between its 1 kHz
 * bursts) and the receive times say that the time passed (at least half
 * of it: samples read at once in a backlog, or forged, teach nothing).  A
 * lone outage among fast samples, however often it recurs, stays out of
 * the long run, so a storm of outages is never learned as the pace; one
 * at most max_bridge, so a chain of samples far apart is neither. */
static int paced(const sw_gate_t *g, const sw_sample_t *s, double dt)
{
    const timing_t *tm = &g->tm;
    if (isnan(s->rx) || tm->nring == 0 || dt > g->o.max_bridge)
        return 0;
    const double prev = tm->ring[(tm->nring - 1) % RING];
    const double drx = s->rx - g->last.rx;
    return prev * PACED_RATIO >= dt && dt * PACED_RATIO >= prev && drx >= 0.5 * dt;
}

/* s of covered time in which a bridged gap waits to be judged once the
 * pace is known: a log's first seconds; a live stream's first two, so
 * that its word comes soon (the monitor's timer says a silence at once) */
static double warm_time(const sw_sample_t *s)
{
    return isnan(s->rx) ? WARM_TIME : WARM_LIVE;
}

/* Push an accepted sample at engine time te. */
int gate_take(sw_gate_t *g, const sw_sample_t *s, double te, int iv)
{
    const double az = g->o.vert_gravity ? s->a_z - SW_G0 : s->a_z;
    const int rc = g->o.lateral ? sw_engine_push_lat(g->e, te, s->a_g, s->a_y, az)
                                : sw_engine_push(g->e, te, s->a_g, az);
    if (rc < 0)
        return gate_refuse(g, s, SW_GATE_REJ_ENGINE, sw_strerror(rc));
    if (g->o.lateral && g->o.on_take_lat)
        g->o.on_take_lat(g->o.user, te, s->a_g, s->a_y, az, g->restarted);
    else if (g->o.on_take)
        g->o.on_take(g->o.user, te, s->a_g, az, g->restarted);
    g->restarted = 0;
    if (g->have_last) {
        const double dt = s->t - g->last.t;
        if (dt > 0.0) {
            const double x = log10(dt / HIST_LO); /* once for both histograms */
            note_interval(g, dt, x);
            g->f.duration += te - g->last_engine;
            if (iv != IV_BREAK)
                gate_tm_add(&g->tm, dt, x, iv == IV_NORMAL || paced(g, s, dt),
                            iv == IV_NORMAL || iv == IV_WARM);
        }
        const double drx = s->rx - g->last.rx;
        if (drx >= 0.0)
            g->tm.rx_recent[g->tm.nrx++ % RECENT] = drx;
    } else {
        g->f.t_first = s->t;
    }
    gate_note_seq(g, s);
    if (g->ndeferred && g->tm.covered >= warm_time(s))
        gate_judge_deferred(g);
    g->f.t_last = s->t;
    g->f.accepted++;
    axis_add(s->a_g, &g->f.peak_a, &g->f.above_half_g, &g->f.min_a, &g->f.max_a, &g->sum_abs_a);
    if (g->o.lateral)
        axis_add(s->a_y, &g->f.lat.peak, &g->f.lat.above_half_g, &g->f.lat.min, &g->f.lat.max,
                 &g->sum_abs_y);
    if (fabs(s->a_z) > g->f.peak_z)
        g->f.peak_z = fabs(s->a_z);
    g->sum_z += s->a_z;
    if (!isnan(s->rx)) {
        const double off = s->t - s->rx;
        env_add(g, off);
    }
    g->have_last = 1;
    g->last = *s;
    g->last_engine = te;
    return rc;
}

/* The first sample of the stream sets the origin. */
int gate_take_first(sw_gate_t *g, const sw_sample_t *s)
{
    g->relative = g->o.relative == 1 || (g->o.relative != 0 && fabs(s->t) >= EPOCH_LIKE);
    g->f.t_origin = g->relative ? s->t : 0.0;
    g->offset = -g->f.t_origin;
    return gate_take(g, s, s->t + g->offset, IV_BREAK);
}

/* The first sample of a stretch that does not continue the timeline at
 * its pace (a gap, a clock step, a restart): what happened, the gap
 * policy, and its engine time.  The engine's clock moves by the source's
 * own time, so that what is reported is on the source's clock; where the
 * source's clock leapt ahead of the time that really passed (known from
 * the receive times) it moves by that time instead, and when the source's
 * time went back, by the time that passed (one spacing when unknown or
 * beyond max_bridge).  Every such interval, however long, costs the engine
 * no more than max_bridge of bridging or a restart from rest. */
double gate_resume(sw_gate_t *g, const sw_sample_t *s, double thr, int *iv)
{
    const double dt = s->t - g->last.t; /* s, > 0 ahead, < 0 back */
    const double real = s->rx - g->last.rx, sp = gate_spacing(g), one = isnan(sp) ? 1e-3 : sp;
    /* s: how far the source's clock ran ahead of the time that passed */
    const double ahead = isnan(real)   ? NAN
                         : g->have_env ? (s->t - s->rx) - g->env
                                       : dt - fmax(real, 0.0);
    sw_gate_event_t ev = {.t = g->last.t, .where = s->where};
    double elapsed;
    *iv = IV_BREAK;
    if (dt > 0.0) {
        /* ahead of the time that passed by more than a gap: the clock
         * stepped (whether the sample waited for it or not) */
        if (ahead > fmin(fmin(thr, gate_gap_threshold_of(g, NAN)), g->o.max_bridge)) {
            ev.kind = SW_GATE_EV_CLOCK_STEP;
            ev.span = ahead;
            elapsed = dt - ahead > 0.0 ? dt - ahead : one;
            g->f.clock_steps++;
            gate_note_switch(g, s);
        } else {
            ev.kind = SW_GATE_EV_GAP;
            ev.span = elapsed = dt;
            *iv = IV_GAP;
        }
    } else {
        ev.kind = SW_GATE_EV_RESTART;
        ev.span = dt;
        elapsed = real > 0.0 && real <= g->o.max_bridge ? real : one;
        g->f.restarts++;
        gate_note_switch(g, s);
    }
    const int gap = elapsed > thr || elapsed > g->o.max_bridge; /* a time with no samples */
    if (ev.kind == SW_GATE_EV_GAP && !gap)
        *iv = IV_NORMAL; /* ahead of real time a little (a latency that changed) */
    const int unknown = ev.kind == SW_GATE_EV_RESTART && isnan(s->rx);
    ev.restarted =
        unknown || (gap && (g->o.gap_policy == SW_GAP_RESTART || elapsed > g->o.max_bridge));
    ev.bridged = gap && !ev.restarted;
    ev.incomplete = (gap || unknown) && motion_near(g, s->a_g);
    if (ev.restarted) {
        sw_engine_restart(g->e);
        g->restarted = 1;
    }
    const double te = g->last_engine + elapsed;
    g->offset = te - s->t;
    g->have_env = 0; /* a new stretch: its own relation to real time */
    /* a backlog read now (gate_live.c) ends with its time: across a gap, a
     * step or a restart the stamps no longer say how late it is read (a
     * clock that leapt while the monitor was stopped passes for a pause) */
    g->burst_env = NAN;
    ev.t_engine = te;
    /* A bridged gap in the first seconds of a stream may be the logger's
     * pace (the first pause between 1 kHz bursts): judged again once the
     * pace is known.  Bridging is what the engine does between any
     * samples, so nothing but the word waits; live, only the word of a gap
     * that left the verdict complete: one that may have changed it is said
     * at once (under doubt, alarm). */
    if (gap && ev.bridged && ev.kind == SW_GATE_EV_GAP && g->o.gap == 0.0 &&
        g->tm.covered < warm_time(s) && g->ndeferred < DEFER && (isnan(s->rx) || !ev.incomplete)) {
        g->deferred[g->ndeferred++] = (deferred_t){.ev = ev, .dt = elapsed};
        return te;
    }
    if (gap)
        count_gap(g, elapsed);
    if (ev.kind != SW_GATE_EV_GAP || gap)
        gate_emit(g, &ev);
    return te;
}

/* The deferred gaps of a stream's first seconds, judged by the pace
 * learned since: the ones still far beyond it are said (late, with where
 * they were); the others were the logger's pace, and are learned as such.
 * Live, they are judged two seconds in, when the recent intervals may
 * still hold them: those intervals count only where learnable, so that a
 * gap is not its own pace. */
void gate_judge_deferred(sw_gate_t *g)
{
    const int n = g->ndeferred;
    if (n == 0)
        return;
    g->ndeferred = 0;
    const double thr = isnan(g->last.rx) ? gate_gap_threshold(g, NAN)
                                         : gate_threshold_of(g, gate_spacing_full(g, 1));
    for (int i = 0; i < n; i++) {
        deferred_t *d = &g->deferred[i];
        if (d->dt > thr) {
            count_gap(g, d->dt);
            gate_emit(g, &d->ev);
        } else {
            gate_tm_add(&g->tm, d->dt, log10(d->dt / HIST_LO), 1, 1);
        }
    }
}

/* A sample that continues the timeline forward: at its own time, or
 * across a gap (after: the look-ahead's spacing, NAN if none). */
int gate_advance(sw_gate_t *g, const sw_sample_t *s, double after)
{
    const double dt = s->t - g->last.t;
    if (dt <= 0.0 || dt > g->o.max_bridge) {
        int iv;
        const double te = gate_resume(g, s, gate_gap_threshold(g, after), &iv);
        return gate_take(g, s, te, iv);
    }
    const double te = s->t + g->offset;
    if (!gate_looks_long(g, dt)) /* the common case */
        return gate_take(g, s, te, IV_NORMAL);
    /* a closer look: the pace of the recent intervals, and of the ones
     * that follow where a log shows them */
    if (!(dt > gate_threshold_of(g, gate_fmax_nan(gate_spacing_full(g, 1), after))))
        return gate_take(g, s, te, IV_NORMAL);
    const double thr = gate_gap_threshold_of(g, after);
    if (!(dt > thr))
        return gate_take(g, s, te, IV_TAINT); /* normal only beside a recent gap */
    if (gate_warming(g))
        return gate_take(g, s, te, IV_WARM); /* no gap yet: the pace is being learned */
    int iv;
    const double te_gap = gate_resume(g, s, thr, &iv);
    return gate_take(g, s, te_gap, iv);
}
