/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gate_live.c - a stream with receive times (live, lcm-logger files): a
 * sample continues the timeline unless it is stamped ahead of the
 * envelope of its arrival or goes back; then it waits in a chain of
 * consistent samples until the stream confirms (across real time) or
 * refutes it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gate_int.h"

/* Does s continue the timeline: later than the last sample taken, and not
 * stamped further ahead of its arrival than any sample taken on this
 * stretch (the envelope), by more than the jump tolerance?  Samples that
 * arrive late (a stall, then a burst) are never ahead of it; forged ones
 * stamped ahead of the genuine stream are. */
static int continues(const sw_gate_t *g, const sw_sample_t *s)
{
    if (!(s->t > g->last.t))
        return 0;
    if (isnan(s->rx) || !g->have_env)
        return s->t - g->last.t - fmax(s->rx - g->last.rx, 0.0) <= gate_jump_tol(g) ||
               isnan(s->rx - g->last.rx);
    const double ahead = (s->t - s->rx) - g->env;
    if (ahead <= 0.0) /* most are not ahead at all (a burst after a stall: late) */
        return 1;
    if (ahead > gate_jump_tol(g))
        return 0;
    /* a little ahead: then also beside the last sample, which may have been
     * late itself (the envelope alone lets a forged sample through when the
     * genuine one before it was): stamped after it by no more than the
     * time that passed and an interval the stream has shown lately */
    const double lead = s->t - g->last.t - fmax(s->rx - g->last.rx, 0.0);
    /* or it is read in a backlog drained after a silence: no genuine
     * sample came meanwhile that a forged one could be stamped beside, and
     * the last one may have been read late, at the end of the stall */
    return lead <= gate_jump_tol(g) || lead <= gate_recent_max(g) || s->rx >= g->burst_from;
}

/* Does b continue a (later, and not ahead of the time that really passed
 * by more than tol)?  For chains and rival samples. */
static int follows(const sw_gate_t *g, const sw_sample_t *a, const sw_sample_t *b)
{
    const double dt = b->t - a->t;
    if (!(dt > 0.0))
        return 0;
    const double real = !isnan(a->rx) && !isnan(b->rx) ? b->rx - a->rx : 0.0;
    return dt - fmax(real, 0.0) <= gate_jump_tol(g);
}

void gate_refuse_held(sw_gate_t *g, const sw_sample_t *s)
{
    const int late = g->have_last && s->t < g->last.t;
    char text[160];
    snprintf(text, sizeof text,
             late ? "time %.15g s is before the timeline (%.15g s) and the stream did "
                    "not follow it"
                  : "time %.15g s leaps from the timeline (%.15g s) and the stream did "
                    "not follow it",
             s->t, g->have_last ? g->last.t : NAN);
    gate_refuse(g, s, late ? SW_GATE_REJ_LATE : SW_GATE_REJ_JUMP, text);
}

static void drop_chain(sw_gate_t *g, int k)
{
    chain_t c = g->chain[k];
    g->chain[k] = g->chain[g->nchain - 1];
    g->nchain--;
    for (int i = 0; i < c.n; i++) gate_refuse_held(g, &c.s[i]);
}

void gate_drop_chains(sw_gate_t *g)
{
    while (g->nchain) drop_chain(g, g->nchain - 1);
}

/* A chain confirmed: it is the timeline now; each of its intervals gets
 * the treatment of any interval.  The other chains are refuted after it
 * is taken, so that each of their samples is refused as behind or ahead
 * of the timeline as it now is (an out-of-order copy of a sample of the
 * confirmed chain is late, not a leap). */
int gate_confirm(sw_gate_t *g, int k)
{
    chain_t c = g->chain[k];
    g->chain[k] = g->chain[g->nchain - 1];
    g->nchain--;
    int rc = SW_OK;
    for (int i = 0; i < c.n; i++) {
        int r;
        if (!g->have_last) {
            r = gate_take_first(g, &c.s[i]);
        } else if (i == 0) {
            int iv;
            const double te = gate_resume(g, &c.s[0], gate_gap_threshold(g, NAN), &iv);
            r = gate_take(g, &c.s[0], te, iv);
        } else {
            r = gate_advance(g, &c.s[i], NAN);
        }
        if (r != SW_OK && (rc == SW_OK || r < 0))
            rc = r;
    }
    gate_drop_chains(g); /* the others are refuted */
    return rc;
}

/* Has a chain waited long enough?  confirm samples, spanning at least half
 * the real time in which the timeline's own samples arrive: a burst of
 * forged samples cannot confirm itself while the genuine stream goes on.
 * Or confirm samples all read in one drained backlog: after a silence
 * longer than a gap (the monitor or the stream stopped), read together,
 * each within half a spacing of the one before, and stamped at the
 * stream's pace (the chain's samples follow each other by no more than
 * the jump tolerance).  There the receive times say nothing of the time
 * that passed between them, and no genuine sample of the old timeline
 * came meanwhile; waiting for real time to pass would refuse the
 * backlog as leaps, sample after sample. */
static int confirmable(const sw_gate_t *g, const chain_t *c)
{
    if (c->n < g->o.confirm)
        return 0;
    const double rx_span = c->s[c->n - 1].rx - c->s[0].rx;
    if (!g->have_last) /* the first: it must arrive at least half as fast as it is stamped */
        return c->n == SW_GATE_CONFIRM_MAX || g->o.jump < 0.0 ||
               rx_span >= 0.5 * (c->s[c->n - 1].t - c->s[0].t);
    if (g->tm.nrx == 0)
        return 1;
    if (c->s[0].rx >= g->burst_from) /* false while none goes on (NAN) */
        return 1;
    /* full, and arriving at least half as fast as it is stamped: no sample
     * of the timeline came to refute it while it did (the real time in
     * which the timeline's samples arrive, below, is frozen while nothing
     * is taken: one late arrival before must not hold it for good) */
    if (c->n == SW_GATE_CONFIRM_MAX && rx_span >= 0.5 * (c->s[c->n - 1].t - c->s[0].t))
        return 1;
    double v[RECENT];
    const int n = g->tm.nrx < RECENT ? (int)g->tm.nrx : RECENT;
    memcpy(v, g->tm.rx_recent, sizeof v[0] * (size_t)n);
    const double rx_sp = gate_time_quantile(v, n, TM_QUANTILE); /* bursts do not shrink it */
    return rx_span >= 0.5 * (g->o.confirm - 1) * rx_sp;
}

/* The drained backlog, if one goes on: s arrived after a silence longer
 * than a gap (the monitor was stopped, or the stream).  It goes on however
 * the reader reads it (in one burst, in chunks, slowly as it wakes, with a
 * busy core now and then: no receive interval ends it) until a sample is
 * taken on time (backlog_done) or twice the silence has passed. */
static void note_arrival(sw_gate_t *g, const sw_sample_t *s)
{
    const double drx = s->rx - g->rx_prev, sp = gate_spacing(g);
    g->rx_prev = s->rx;
    if (isnan(sp) || !(drx >= 0.0)) {
        g->burst_from = NAN;
    } else if (drx > gate_threshold_of(g, sp) && !gate_warming(g) &&
               drx > gate_threshold_of(g, gate_spacing_full(g, 1))) {
        /* a silence: what comes now may be a backlog (beyond the pace of
         * the recent intervals too: a FIFO's reads are none).  A second
         * one while a backlog is read keeps what was known before the
         * first (the envelope then is the backlog's, late) */
        if (isnan(g->burst_from))
            g->burst_env = g->have_env ? g->env : NAN;
        g->burst_until =
            gate_fmax_nan(isnan(g->burst_from) ? NAN : g->burst_until, s->rx + 2.0 * drx);
        g->burst_from = s->rx;
    } else if (!isnan(g->burst_from) && s->rx > g->burst_until) {
        g->burst_from = NAN; /* a reader this slow is no backlog's */
    }
}

/* A sample taken after the silence on time (read no later after it was
 * stamped than the stream delivered before the silence, within the jump
 * tolerance): the reader has caught up and the backlog is read.  A stream
 * that merely paused on time ends it with its first sample.  Once a
 * sample was taken across a gap, a clock step or a restart since the
 * silence (a sender restarted on a later clock, a clock that leapt while
 * the monitor was stopped and passes for a pause), the envelope before it
 * says nothing of the stamps now: the backlog is then over when twice the
 * silence has passed (note_arrival). */
static void backlog_done(sw_gate_t *g)
{
    if (isnan(g->burst_from) || !g->have_last || !(g->last.rx >= g->burst_from))
        return;
    const double late = g->burst_env - (g->last.t - g->last.rx); /* s; NAN unknown */
    if (late <= gate_jump_tol(g))
        g->burst_from = NAN;
}

/* A sample that does not continue the timeline: into a chain. */
static int hold(sw_gate_t *g, const sw_sample_t *s)
{
    for (int k = 0; k < g->nchain; k++) {
        chain_t *c = &g->chain[k];
        if (s->t == c->s[c->n - 1].t) {
            char text[120];
            snprintf(text, sizeof text, "time %.15g s is a duplicate of a waiting sample", s->t);
            return gate_refuse(g, s, SW_GATE_REJ_DUPLICATE, text);
        }
        if (!follows(g, &c->s[c->n - 1], s))
            continue;
        if (c->n == SW_GATE_CONFIRM_MAX) { /* full, and not confirmed yet: the oldest goes */
            const sw_sample_t old = c->s[0];
            memmove(c->s, c->s + 1, sizeof c->s[0] * (size_t)(c->n - 1));
            c->n--;
            gate_refuse_held(g, &old);
            c = &g->chain[k];
        }
        c->s[c->n++] = *s;
        if (confirmable(g, c))
            return gate_confirm(g, k);
        return SW_GATE_HELD;
    }
    if (g->nchain == CHAINS)
        drop_chain(g, 0); /* the oldest makes room */
    chain_t *c = &g->chain[g->nchain++];
    c->s[0] = *s;
    c->n = 1;
    if (confirmable(g, c))
        return gate_confirm(g, g->nchain - 1);
    return SW_GATE_HELD;
}

/* s continues the timeline: held samples stamped between the timeline and
 * s were on it all along, only quicker to arrive than any before (the
 * envelope was not yet its own): taken first, in order of their time. */
static void take_early(sw_gate_t *g, const sw_sample_t *s)
{
    sw_sample_t early[SW_GATE_HELD_MAX];
    int n = 0;
    for (int k = 0; k < g->nchain; k++) {
        chain_t *c = &g->chain[k];
        int kept = 0;
        for (int i = 0; i < c->n; i++) {
            if (c->s[i].t > g->last.t && c->s[i].t < s->t)
                early[n++] = c->s[i];
            else
                c->s[kept++] = c->s[i];
        }
        c->n = kept;
    }
    for (int k = 0; k < g->nchain;) { /* chains left empty go */
        if (g->chain[k].n == 0)
            g->chain[k] = g->chain[--g->nchain];
        else
            k++;
    }
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && early[j - 1].t > early[j].t; j--) {
            const sw_sample_t x = early[j];
            early[j] = early[j - 1];
            early[j - 1] = x;
        }
    for (int i = 0; i < n; i++) {
        if (early[i].t > g->last.t)
            gate_advance(g, &early[i], NAN);
        else
            gate_refuse_held(g, &early[i]); /* the same time as one before it */
    }
}

/* The same sample again (a network duplicate) is no rival; the same time
 * with other values or another seq is. */
static int same_sample(const sw_sample_t *a, const sw_sample_t *b)
{
    return a->t == b->t && a->seq == b->seq && a->a_g == b->a_g && a->a_z == b->a_z &&
           a->a_y == b->a_y;
}

static int live_push(sw_gate_t *g, const sw_sample_t *s)
{
    char text[160];
    if (g->rv.contested && g->rv.by_seq && !gate_seq_kept(g, s)) {
        g->rv.active = s->rx;
        snprintf(text, sizeof text,
                 "seq %lld is not the kept sender's (two senders' seq numbers interleave)",
                 (long long)s->seq);
        g->f.rejected[SW_GATE_REJ_CONTESTED]++;
        if (g->o.on_reject)
            g->o.on_reject(g->o.user, s, SW_GATE_REJ_CONTESTED, text);
        gate_to_rival(g, s);
        return SW_EORDER;
    }
    if (g->have_last && s->t == g->last.t) {
        snprintf(text, sizeof text, "time %.15g s is a duplicate (the same as the sample before)",
                 s->t);
        const int rc = gate_refuse(g, s, SW_GATE_REJ_DUPLICATE, text);
        if (!same_sample(s, &g->last))
            gate_rival_note(g, s);
        return rc;
    }
    if (g->have_last && continues(g, s)) {
        take_early(g, s);
        gate_drop_chains(g); /* the stream went on: waiting samples are refuted */
        return gate_advance(g, s, NAN);
    }
    return hold(g, s);
}

int gate_live_push(sw_gate_t *g, const sw_sample_t *s)
{
    gate_contest_check_end(g, s->rx);
    note_arrival(g, s);
    const int rc = live_push(g, s);
    backlog_done(g);
    return rc;
}
