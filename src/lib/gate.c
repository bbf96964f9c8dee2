/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gate.c - the input gate (gate.h): every source's samples pass here on
 * their way to the engine.  The timeline is the last accepted sample's
 * time; a sample that does not continue it waits in a chain until the
 * stream confirms or refutes it (see gate.h).  Memory is fixed: at most
 * CHAINS chains of confirm samples each. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/gate.h"
#include "swaywatch/status.h"

#define CHAINS SW_GATE_CHAINS
#define DT_WINDOW 5        /* intervals in the typical-interval median */
#define HIST_PER_DECADE 96 /* interval histogram: 2.4 % wide bins */
#define HIST_DECADES 12    /* 1e-7 s .. 1e5 s */
#define HIST_BINS (HIST_PER_DECADE * HIST_DECADES)
#define HIST_LO 1e-7
#define G0 9.80665            /* m/s^2 per g */
#define EPOCH_LIKE 1e6        /* s: a first time this large is a clock, not elapsed time */
#define TIME_MAX 8589934592.0 /* 2^33 s: the engine's limit (SW_ERESOLUTION) */

typedef struct {
    sw_sample_t s[SW_GATE_CONFIRM_MAX];
    int n;
} chain_t;

struct sw_gate {
    sw_engine_t *e;
    sw_gate_opts_t o;
    int relative; /* resolved at the first sample */
    /* the timeline */
    int have_last;
    sw_sample_t last;   /* the last accepted sample (source time) */
    double last_engine; /* s, the engine time it was pushed at */
    double offset;      /* s, engine time = source time + offset */
    int restarted;      /* the engine was restarted: the next sample taken says so */
    int64_t last_seq;
    int have_seq;
    double dts[DT_WINDOW];
    int ndt;
    chain_t chain[CHAINS];
    int nchain;
    /* facts */
    sw_gate_facts_t f;
    long hist[HIST_BINS];
    double hist_sum[HIST_BINS];
    double sum_z;
};

static const char *const reject_names[SW_GATE_NREJ] = {
    "nonfinite", "implausible", "time", "skew", "duplicate", "late", "jump", "engine"};

const char *sw_gate_reject_name(sw_gate_reject r)
{
    return (unsigned)r < SW_GATE_NREJ ? reject_names[r] : "unknown";
}

const char *sw_gate_event_name(sw_gate_event_kind k)
{
    switch (k) {
        case SW_GATE_EV_GAP: return "gap";
        case SW_GATE_EV_CLOCK_STEP: return "clock step";
        case SW_GATE_EV_RESTART: return "restart";
        case SW_GATE_EV_SEQ_RESTART: return "seq restart";
    }
    return "unknown";
}

long sw_gate_rejected(const sw_gate_facts_t *f)
{
    long n = 0;
    for (int r = 0; r < SW_GATE_NREJ; r++) n += f->rejected[r];
    return n;
}

sw_gate_t *sw_gate_create(sw_engine_t *e, const sw_gate_opts_t *o, char *msg, size_t msglen)
{
    static const sw_gate_opts_t defaults;
    if (msg && msglen)
        msg[0] = '\0';
    if (!o)
        o = &defaults;
    const char *bad = NULL;
    if (!e)
        bad = "no engine";
    else if (!(o->gap >= 0.0) || !isfinite(o->gap))
        bad = "gap must be >= 0";
    else if (!(o->max_bridge >= 0.0) || !isfinite(o->max_bridge))
        bad = "max_bridge must be >= 0";
    else if (!(o->max_accel >= 0.0) || !isfinite(o->max_accel))
        bad = "max_accel must be >= 0";
    else if (isnan(o->jump) || isinf(o->jump))
        bad = "jump must be finite";
    else if (!(o->max_skew >= 0.0) || !isfinite(o->max_skew))
        bad = "max_skew must be >= 0";
    else if (o->confirm < 0 || o->confirm > SW_GATE_CONFIRM_MAX)
        bad = "confirm must be 0..8";
    else if (o->gap_policy != SW_GAP_BRIDGE && o->gap_policy != SW_GAP_RESTART)
        bad = "unknown gap policy";
    if (bad) {
        if (msg && msglen)
            snprintf(msg, msglen, "%s", bad);
        return NULL;
    }
    sw_gate_t *g = calloc(1, sizeof *g);
    if (!g) {
        if (msg && msglen)
            snprintf(msg, msglen, "out of memory");
        return NULL;
    }
    g->e = e;
    g->o = *o;
    if (g->o.max_bridge == 0.0)
        g->o.max_bridge = 10.0;
    if (g->o.max_accel == 0.0)
        g->o.max_accel = 50.0 * G0;
    if (g->o.confirm == 0)
        g->o.confirm = 3;
    g->f.t_first = g->f.t_last = g->f.first_incomplete = NAN;
    g->f.dt_min = g->f.dt_median = g->f.dt_max = g->f.rate = NAN;
    return g;
}

void sw_gate_destroy(sw_gate_t *g)
{
    free(g);
}

/* ---- the typical interval, and the facts ----------------------------------- */

/* Median of the last DT_WINDOW intervals (fewer at the start); NAN: none. */
static double typical_dt(const sw_gate_t *g)
{
    double v[DT_WINDOW];
    const int n = g->ndt < DT_WINDOW ? g->ndt : DT_WINDOW;
    if (n == 0)
        return NAN;
    memcpy(v, g->dts, sizeof(double) * (size_t)n);
    for (int i = 1; i < n; i++) /* insertion sort: five numbers */
        for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
            const double x = v[j];
            v[j] = v[j - 1];
            v[j - 1] = x;
        }
    return v[n / 2];
}

static double gap_of(const sw_gate_t *g)
{
    if (g->o.gap > 0.0)
        return g->o.gap;
    const double d = typical_dt(g);
    return isnan(d) ? INFINITY : fmax(5.0 * d, 1e-3);
}

static double jump_of(const sw_gate_t *g)
{
    if (g->o.jump < 0.0)
        return INFINITY;
    if (g->o.jump > 0.0)
        return g->o.jump;
    const double gap = gap_of(g);
    return isinf(gap) ? 1.0 : gap; /* no typical interval yet: 1 s */
}

static void note_interval(sw_gate_t *g, double dt)
{
    g->dts[g->ndt % DT_WINDOW] = dt;
    g->ndt++;
    if (!(dt > 0.0))
        return;
    if (isnan(g->f.dt_min) || dt < g->f.dt_min)
        g->f.dt_min = dt;
    if (isnan(g->f.dt_max) || dt > g->f.dt_max)
        g->f.dt_max = dt;
    int b = (int)floor(log10(dt / HIST_LO) * HIST_PER_DECADE);
    if (b < 0)
        b = 0;
    if (b >= HIST_BINS)
        b = HIST_BINS - 1;
    g->hist[b]++;
    g->hist_sum[b] += dt;
}

/* ---- refusing and accepting -------------------------------------------------- */

static int refuse(sw_gate_t *g, const sw_sample_t *s, sw_gate_reject r, const char *text)
{
    /* a sample refused for its values did arrive: its seq is no loss */
    if ((r == SW_GATE_REJ_NONFINITE || r == SW_GATE_REJ_IMPLAUSIBLE) && g->have_seq &&
        s->seq != SW_GATE_NO_SEQ && s->seq > g->last_seq &&
        (uint64_t)s->seq - (uint64_t)g->last_seq < 1000000000ULL)
        g->last_seq = s->seq;
    static const int code[SW_GATE_NREJ] = {SW_ENONFINITE, SW_ETOOBIG, SW_ERESOLUTION, SW_ETOOBIG,
                                           SW_EORDER,     SW_EORDER,  SW_EORDER,      SW_EINVAL};
    g->f.rejected[r]++;
    if (g->o.on_reject)
        g->o.on_reject(g->o.user, s, r, text);
    return code[r];
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

static void emit(sw_gate_t *g, sw_gate_event_t *ev)
{
    if (ev->incomplete) {
        g->f.incomplete++;
        if (isnan(g->f.first_incomplete))
            g->f.first_incomplete = ev->t;
    }
    if (g->o.on_event)
        g->o.on_event(g->o.user, ev);
}

/* The sender's seq: missing ones counted, a seq that goes back while time
 * goes on is a sender restart.  Overflow-free for any int64. */
static void note_seq(sw_gate_t *g, const sw_sample_t *s)
{
    if (s->seq == SW_GATE_NO_SEQ)
        return;
    if (g->have_seq) {
        if (s->seq > g->last_seq) {
            const uint64_t d = (uint64_t)s->seq - (uint64_t)g->last_seq; /* >= 1, no overflow */
            if (d > 1 && d <= 1000000000ULL)
                g->f.lost += (long)(d - 1);
        } else if (s->seq < g->last_seq) {
            g->f.seq_restarts++;
            sw_gate_event_t ev = {
                .kind = SW_GATE_EV_SEQ_RESTART, .t = g->last.t, .where = s->where};
            emit(g, &ev);
        }
    }
    g->have_seq = 1;
    g->last_seq = s->seq;
}

/* Push an accepted sample at engine time te. */
static int take(sw_gate_t *g, const sw_sample_t *s, double te)
{
    const double az = g->o.vert_gravity ? s->a_z - G0 : s->a_z;
    const int rc = sw_engine_push(g->e, te, s->a_g, az);
    if (rc < 0)
        return refuse(g, s, SW_GATE_REJ_ENGINE, sw_strerror(rc));
    if (g->o.on_take)
        g->o.on_take(g->o.user, te, s->a_g, az, g->restarted);
    g->restarted = 0;
    if (g->have_last) {
        const double dt = s->t - g->last.t;
        if (dt > 0.0) {
            note_interval(g, dt);
            g->f.duration += te - g->last_engine;
        }
    } else {
        g->f.t_first = s->t;
    }
    note_seq(g, s);
    g->f.t_last = s->t;
    g->f.accepted++;
    if (fabs(s->a_g) > g->f.peak_a)
        g->f.peak_a = fabs(s->a_g);
    if (fabs(s->a_z) > g->f.peak_z)
        g->f.peak_z = fabs(s->a_z);
    g->sum_z += s->a_z;
    g->have_last = 1;
    g->last = *s;
    g->last_engine = te;
    return rc;
}

/* The first sample of a stretch that does not continue the timeline (a
 * gap; or a confirmed chain, ahead or behind): what happened, the gap
 * policy, and its engine time.  The engine's clock moves by the time that
 * really passed: the receive times' difference where the source has them,
 * else the source's own; a restart in a log with no receive time moves it
 * by one typical interval, the packages starting again from rest. */
static double resume(sw_gate_t *g, const sw_sample_t *s)
{
    const double dt = s->t - g->last.t; /* s, > 0 ahead, < 0 back */
    const double typ = typical_dt(g), one = isnan(typ) ? 1e-3 : typ;
    sw_gate_event_t ev = {.t = g->last.t, .where = s->where};
    double elapsed;
    if (!isnan(s->rx) && !isnan(g->last.rx)) {
        const double real = s->rx - g->last.rx;
        elapsed = real > 0.0 ? real : one;
        if (!(dt > 0.0)) {
            ev.kind = SW_GATE_EV_RESTART;
            ev.span = dt;
            g->f.restarts++;
        } else if (fabs(dt - elapsed) > jump_of(g)) {
            ev.kind = SW_GATE_EV_CLOCK_STEP;
            ev.span = dt - elapsed;
            g->f.clock_steps++;
        } else {
            ev.kind = SW_GATE_EV_GAP;
            ev.span = elapsed;
        }
    } else if (dt > 0.0) {
        ev.kind = SW_GATE_EV_GAP;
        ev.span = elapsed = dt;
    } else {
        ev.kind = SW_GATE_EV_RESTART;
        ev.span = dt;
        elapsed = one;
        g->f.restarts++;
    }
    const int gap = elapsed > gap_of(g); /* a time with no samples */
    if (gap) {
        g->f.gaps++;
        g->f.gap_total += elapsed;
        if (elapsed > g->f.gap_max)
            g->f.gap_max = elapsed;
    }
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
    ev.t_engine = te;
    if (ev.kind != SW_GATE_EV_GAP || gap)
        emit(g, &ev);
    return te;
}

/* ---- chains ------------------------------------------------------------------- */

/* Does b continue a (consistent: later, and not ahead of the time that
 * really passed by more than the jump tolerance)? */
static int follows(const sw_gate_t *g, const sw_sample_t *a, const sw_sample_t *b)
{
    const double dt = b->t - a->t;
    if (!(dt > 0.0))
        return 0;
    const double real = !isnan(a->rx) && !isnan(b->rx) ? b->rx - a->rx : 0.0;
    return dt - fmax(real, 0.0) <= jump_of(g);
}

static void drop_chain(sw_gate_t *g, int k)
{
    chain_t *c = &g->chain[k];
    for (int i = 0; i < c->n; i++) {
        const sw_sample_t *s = &c->s[i];
        const int late = g->have_last && s->t < g->last.t;
        char text[160];
        snprintf(text, sizeof text,
                 late ? "time %.15g s is before the timeline (%.15g s) and the stream did "
                        "not follow it"
                      : "time %.15g s leaps from the timeline (%.15g s) and the stream did "
                        "not follow it",
                 s->t, g->have_last ? g->last.t : NAN);
        refuse(g, s, late ? SW_GATE_REJ_LATE : SW_GATE_REJ_JUMP, text);
    }
    g->chain[k] = g->chain[g->nchain - 1];
    g->nchain--;
}

static void drop_chains(sw_gate_t *g)
{
    while (g->nchain) drop_chain(g, g->nchain - 1);
}

/* A chain confirmed: it is the timeline now. */
static int confirm(sw_gate_t *g, int k)
{
    chain_t c = g->chain[k];
    g->chain[k] = g->chain[g->nchain - 1];
    g->nchain--;
    drop_chains(g); /* the others are refuted */
    int rc = SW_OK;
    for (int i = 0; i < c.n; i++) {
        double te;
        if (!g->have_last) {
            g->relative =
                g->o.relative == 1 || (g->o.relative != 0 && fabs(c.s[0].t) >= EPOCH_LIKE);
            g->f.t_origin = g->relative ? c.s[0].t : 0.0;
            g->offset = -g->f.t_origin;
            te = c.s[i].t + g->offset;
        } else if (i == 0) {
            te = resume(g, &c.s[0]);
        } else {
            te = c.s[i].t + g->offset;
        }
        const int r = take(g, &c.s[i], te);
        if (r != SW_OK && (rc == SW_OK || r < 0))
            rc = r;
    }
    return rc;
}

/* A sample that does not continue the timeline: into a chain. */
static int hold(sw_gate_t *g, const sw_sample_t *s)
{
    for (int k = 0; k < g->nchain; k++) {
        chain_t *c = &g->chain[k];
        if (s->t == c->s[c->n - 1].t) {
            char text[120];
            snprintf(text, sizeof text, "time %.15g s is a duplicate of a waiting sample", s->t);
            return refuse(g, s, SW_GATE_REJ_DUPLICATE, text);
        }
        if (!follows(g, &c->s[c->n - 1], s))
            continue;
        c->s[c->n++] = *s;
        if (c->n >= g->o.confirm)
            return confirm(g, k);
        return SW_GATE_HELD;
    }
    if (g->nchain == CHAINS)
        drop_chain(g, 0); /* the oldest makes room */
    chain_t *c = &g->chain[g->nchain++];
    c->s[0] = *s;
    c->n = 1;
    if (c->n >= g->o.confirm)
        return confirm(g, g->nchain - 1);
    return SW_GATE_HELD;
}

/* ---- the sample --------------------------------------------------------------- */

int sw_gate_push(sw_gate_t *g, const sw_sample_t *s)
{
    if (!g || !s)
        return SW_EINVAL;
    g->f.received++;
    char text[160];
    if (!isfinite(s->t) || !isfinite(s->a_g) || !isfinite(s->a_z))
        return refuse(g, s, SW_GATE_REJ_NONFINITE, "a value is not finite");
    const double amax = isnan(s->a_max) ? fmax(fabs(s->a_g), fabs(s->a_z)) : s->a_max;
    if (!(amax <= g->o.max_accel)) {
        snprintf(text, sizeof text, "|a| = %.6g m/s^2 (%.4g g) beyond the limit %.6g m/s^2", amax,
                 amax / G0, g->o.max_accel);
        return refuse(g, s, SW_GATE_REJ_IMPLAUSIBLE, text);
    }
    if (!(fabs(s->t) < TIME_MAX)) {
        snprintf(text, sizeof text,
                 "time %.15g s: its steps are coarser than 2e-6 s (a time unit mistake?)", s->t);
        return refuse(g, s, SW_GATE_REJ_TIME, text);
    }
    if (g->o.max_skew > 0.0 && !isnan(s->wall) && !(fabs(s->t - s->wall) <= g->o.max_skew)) {
        snprintf(text, sizeof text, "time %.15g s is %.6g s from the wall clock", s->t,
                 s->t - s->wall);
        return refuse(g, s, SW_GATE_REJ_SKEW, text);
    }
    if (g->have_last && s->t == g->last.t) {
        snprintf(text, sizeof text, "duplicate time %.15g s (same as the previous sample)", s->t);
        return refuse(g, s, SW_GATE_REJ_DUPLICATE, text);
    }
    if (g->have_last && follows(g, &g->last, s)) {
        drop_chains(g); /* the stream went on: waiting samples are refuted */
        const double dt = s->t - g->last.t;
        if (dt > gap_of(g))
            return take(g, s, resume(g, s));
        return take(g, s, s->t + g->offset);
    }
    return hold(g, s);
}

int sw_gate_flush(sw_gate_t *g)
{
    if (!g)
        return SW_EINVAL;
    if (!g->have_last && g->nchain) {
        /* a stream too short to confirm anything: its longest stretch,
         * which nothing contradicts, is the timeline */
        int best = 0;
        for (int k = 1; k < g->nchain; k++)
            if (g->chain[k].n > g->chain[best].n)
                best = k;
        confirm(g, best);
    }
    drop_chains(g);
    return SW_OK;
}

void sw_gate_facts(const sw_gate_t *g, sw_gate_facts_t *f)
{
    *f = g->f;
    f->held = 0;
    for (int k = 0; k < g->nchain; k++) f->held += g->chain[k].n;
    f->mean_z = f->accepted ? g->sum_z / (double)f->accepted : 0.0;
    long n = 0, half = 0;
    for (int b = 0; b < HIST_BINS; b++) n += g->hist[b];
    for (int b = 0; b < HIST_BINS && n; b++) {
        half += g->hist[b];
        if (2 * half >= n) {
            f->dt_median = g->hist_sum[b] / (double)g->hist[b]; /* the bin's mean */
            break;
        }
    }
    f->rate = f->dt_median > 0.0 ? 1.0 / f->dt_median : NAN;
}

double sw_gate_source_time(const sw_gate_t *g, double t_engine)
{
    return t_engine - g->offset;
}

/* ---- plausibility --------------------------------------------------------------- */

int sw_gate_check(const sw_gate_facts_t *f, const sw_gate_limits_t *lim, char *why, size_t whylen)
{
    static const sw_gate_limits_t defaults;
    if (!lim)
        lim = &defaults;
    const double max_rej = lim->max_rejected > 0.0 ? lim->max_rejected : 0.01;
    const double min_rate = lim->min_rate > 0.0 ? lim->min_rate : 2.0;
    const double warn_rate = lim->warn_rate > 0.0 ? lim->warn_rate : 20.0;
    const double max_dur = lim->max_duration > 0.0 ? lim->max_duration : 366.0 * 86400.0;
    const double max_peak = lim->max_peak > 0.0 ? lim->max_peak : 25.0 * G0;
    const long rej = sw_gate_rejected(f) + f->upstream_rejected;
    const long seen = f->received + f->upstream_rejected;
    if (why && whylen)
        why[0] = '\0';
    if (seen > 0 && (double)rej > max_rej * (double)seen) {
        snprintf(why, whylen,
                 "%ld of %ld samples (%.1f %%) were refused, more than %.3g %%: a wrong "
                 "column, unit or delimiter is the usual cause",
                 rej, seen, 100.0 * (double)rej / (double)seen, 100.0 * max_rej);
        return SW_GATE_REFUSE;
    }
    if (f->accepted < 2) {
        snprintf(why, whylen, "%ld usable samples: nothing to judge", f->accepted);
        return SW_GATE_REFUSE;
    }
    if (f->rate < min_rate) {
        snprintf(why, whylen,
                 "the samples are %.4g s apart (%.3g Hz): no vehicle log is that slow; a "
                 "time column in ms or us read as seconds?",
                 f->dt_median, f->rate);
        return SW_GATE_REFUSE;
    }
    if (f->duration > max_dur) {
        snprintf(why, whylen, "the log spans %.3g days: a time unit mistake?",
                 f->duration / 86400.0);
        return SW_GATE_REFUSE;
    }
    if (f->peak_a > max_peak) {
        snprintf(why, whylen,
                 "the largest acceleration is %.4g m/s^2 (%.3g g), beyond what a truck bed "
                 "sees (%.3g g): an acceleration in g read as m/s^2 the other way round, or "
                 "a wrong column?",
                 f->peak_a, f->peak_a / G0, max_peak / G0);
        return SW_GATE_REFUSE;
    }
    if (f->rate < warn_rate) {
        snprintf(why, whylen,
                 "%.3g Hz: shocks shorter than a few sample intervals (about %.2g s) are not "
                 "resolved",
                 f->rate, 3.0 / f->rate);
        return SW_GATE_WARN;
    }
    return SW_OK;
}
