/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gate_contest.c - what the gate says and refuses: events, refused samples
 * counted by reason, the sender's seq (a loss or a restart counted on
 * evidence), and a second timeline competing with the one kept (forged
 * or duplicated senders: docs/timing.md, "Contested input"). */
#include <math.h>
#include <stdio.h>

#include "gate_int.h"

void gate_emit(sw_gate_t *g, sw_gate_event_t *ev)
{
    if (ev->incomplete) {
        g->f.incomplete++;
        if (isnan(g->f.first_incomplete))
            g->f.first_incomplete = ev->t;
    }
    if (g->o.on_event)
        g->o.on_event(g->o.user, ev);
}

void gate_to_rival(sw_gate_t *g, const sw_sample_t *s)
{
    g->f.contested++;
    if (g->o.on_rival)
        g->o.on_rival(g->o.user, s);
}

/* Two timelines compete from s on: said at once, and the rival samples
 * kept so far go to on_rival, in the order they came. */
static void contest_begin(sw_gate_t *g, const sw_sample_t *s, int by_seq)
{
    rival_t *r = &g->rv;
    r->contested = 1;
    r->by_seq = by_seq;
    r->since = r->active = s->rx;
    g->f.contests++;
    sw_gate_event_t ev = {.kind = SW_GATE_EV_CONTESTED,
                          .t = g->have_last ? g->last.t : s->t,
                          .t_engine = g->last_engine,
                          .where = s->where};
    gate_emit(g, &ev);
    for (int i = 0; i < r->nkeep; i++)
        gate_to_rival(g, &r->keep[(r->head + RIVAL_KEEP - r->nkeep + i) % RIVAL_KEEP]);
    r->nkeep = 0;
}

/* s: the second timeline is over when nothing of it came for this long. */
static double contest_quiet(const sw_gate_t *g)
{
    const double s = gate_spacing(g);
    return isnan(s) ? 2.0 : fmax(2.0, 50.0 * s);
}

void gate_contest_check_end(sw_gate_t *g, double rx)
{
    rival_t *r = &g->rv;
    if (!r->contested || !(rx - r->active > contest_quiet(g)))
        return;
    sw_gate_event_t ev = {.kind = SW_GATE_EV_UNCONTESTED,
                          .t = g->have_last ? g->last.t : NAN,
                          .t_engine = g->last_engine,
                          .span = r->active - r->since,
                          .where = g->have_last ? g->last.where : 0};
    r->contested = r->by_seq = 0;
    r->n = r->nkeep = r->nat = 0;
    gate_emit(g, &ev);
}

/* A sample refused for its time, with a receive time: is it on a second
 * timeline (after the last one refused, as far ahead of it as real time
 * allows, not long after it)? */
void gate_rival_note(sw_gate_t *g, const sw_sample_t *s)
{
    rival_t *r = &g->rv;
    if (isnan(s->rx) || g->flushing)
        return;
    /* a timeline of its own has a pace: the next of its samples comes within
     * 16 of the kept stream's intervals (a forger at 1:8 does; samples
     * refused here and there, on the kept clock, do not) */
    const double sp = gate_spacing(g), expire = isnan(sp) ? 0.1 : 16.0 * sp;
    const double real = s->rx - r->last.rx, dt = s->t - r->last.t;
    if (r->n > 0 && dt > 0.0 && real <= expire && dt - fmax(real, 0.0) <= gate_jump_tol(g))
        r->n++;
    else
        r->n = 1;
    r->last = *s;
    r->active = s->rx;
    /* however the refused samples are mixed (a forger may interleave
     * garbage with its timeline), many refusals for time are two senders */
    r->at[r->nat++ % RIVAL_DENSE] = g->f.received;
    const int dense =
        r->nat >= RIVAL_DENSE && g->f.received - r->at[r->nat % RIVAL_DENSE] < RIVAL_SPAN;
    if (r->contested) {
        gate_to_rival(g, s);
        return;
    }
    r->keep[r->head] = *s;
    r->head = (r->head + 1) % RIVAL_KEEP;
    if (r->nkeep < RIVAL_KEEP)
        r->nkeep++;
    if (r->n >= RIVAL_MIN || dense)
        contest_begin(g, s, 0);
}

/* The timeline moved to another (a clock step, a restart), with receive
 * times: once is a sensor's doing; twice within RIVAL_SPAN * 4 samples is
 * two timelines taking turns. */
void gate_note_switch(sw_gate_t *g, const sw_sample_t *s)
{
    rival_t *r = &g->rv;
    if (isnan(s->rx) || g->flushing)
        return;
    const int again = r->switched >= 0 && g->f.received - r->switched < 4 * RIVAL_SPAN;
    r->switched = g->f.received;
    r->active = s->rx;
    if (again && !r->contested)
        contest_begin(g, s, 0);
}

/* A refused sample ahead of the kept seq numbers arrived: remember its
 * seq (once) so that a leap over it does not count it lost. */
static void seq_note_refused(seqs_t *q, int64_t v)
{
    for (int i = 0; i < q->nrefused; i++)
        if (q->refused[i] == v)
            return;
    q->refused[q->refused_head] = v;
    q->refused_head = (q->refused_head + 1) % SEQ_REFUSED;
    if (q->nrefused < SEQ_REFUSED)
        q->nrefused++;
}

/* How many refused seqs lie strictly between lo and hi. */
static long seq_refused_between(const seqs_t *q, int64_t lo, int64_t hi)
{
    long n = 0;
    for (int i = 0; i < q->nrefused; i++) n += q->refused[i] > lo && q->refused[i] < hi;
    return n;
}

int gate_refuse(sw_gate_t *g, const sw_sample_t *s, sw_gate_reject r, const char *text)
{
    /* a refused sample did arrive: its seq is no loss (one refused for
     * its values continues the numbers as an accepted one would) */
    if (g->seq.have && s->seq != SW_GATE_NO_SEQ && s->seq > g->seq.last &&
        (uint64_t)s->seq - (uint64_t)g->seq.last < SEQ_FAR) {
        if (r == SW_GATE_REJ_NONFINITE || r == SW_GATE_REJ_IMPLAUSIBLE)
            gate_note_seq(g, s);
        else
            seq_note_refused(&g->seq, s->seq);
    }
    static const int code[SW_GATE_NREJ] = {SW_ENONFINITE, SW_ETOOBIG, SW_ERESOLUTION,
                                           SW_ETOOBIG,    SW_EORDER,  SW_EORDER,
                                           SW_EORDER,     SW_EINVAL,  SW_EORDER};
    g->f.rejected[r]++;
    if (g->o.on_reject)
        g->o.on_reject(g->o.user, s, r, text);
    if (r == SW_GATE_REJ_LATE || r == SW_GATE_REJ_JUMP)
        gate_rival_note(g, s);
    return code[r];
}

static void seq_outlier(sw_gate_t *g, const sw_sample_t *s)
{
    seqs_t *q = &g->seq;
    g->f.seq_outliers++;
    const long at = g->f.accepted;
    const int again = q->outlier_at >= 0 && at - q->outlier_at <= SEQ_WINDOW;
    q->outlier_at = at;
    if (isnan(s->rx) || g->flushing)
        return;
    g->rv.active = s->rx;
    if (!again || q->normal < SEQ_LIVE)
        return;
    if (g->rv.contested)
        g->rv.by_seq = 1; /* from now on told apart by seq as well */
    else
        contest_begin(g, s, 1);
}

/* A seq that leaps or goes back waits for the next one: a loss is counted
 * and a sender restart reported only when the next continues it; when
 * the next continues the old numbers instead, it was an outlier (another
 * sender's, or corrupt).  Overflow-free for any int64. */
void gate_note_seq(sw_gate_t *g, const sw_sample_t *s)
{
    seqs_t *q = &g->seq;
    const int64_t v = s->seq;
    if (v == SW_GATE_NO_SEQ)
        return;
    if (!q->have) {
        q->have = 1;
        q->last = v;
        return;
    }
    int refuted = 0; /* the pending one was an outlier */
    if (q->pend) {
        const int64_t p = q->pend_seq;
        q->pend = 0;
        if (p > q->last) { /* a leap forward */
            if (v >= p) {
                const uint64_t d = (uint64_t)p - (uint64_t)q->last;
                /* while two timelines compete, the numbers between may
                 * have come on the other one: no evidence of a loss */
                if (d <= SEQ_FAR && !g->rv.contested) {
                    const long gone = (long)(d - 1) - seq_refused_between(q, q->last, p);
                    g->f.lost += gone > 0 ? gone : 0;
                }
                q->last = p;
                if (v == p)
                    return; /* the same seq again: confirmed, nothing more */
            } else {
                seq_outlier(g, s);
                refuted = 1;
            }
        } else { /* back, or the same again */
            const int old =
                v > q->last && (uint64_t)v - (uint64_t)q->last <= (uint64_t)v - (uint64_t)p;
            if (old) {
                seq_outlier(g, s);
                refuted = 1;
            } else if (v > p) {
                g->f.seq_restarts++;
                q->nrefused = 0; /* numbers of the old run */
                sw_gate_event_t ev = {
                    .kind = SW_GATE_EV_SEQ_RESTART, .t = g->last.t, .where = s->where};
                gate_emit(g, &ev);
                q->last = p;
            } else {
                seq_outlier(g, s);
                refuted = 1;
            }
        }
    }
    if (refuted && v > q->last && (uint64_t)v - (uint64_t)q->last == 2)
        q->last++; /* the outlier's own slot: a sample with a corrupt seq came */
    if (v > q->last && (uint64_t)v - (uint64_t)q->last == 1) {
        q->last = v;
        q->normal++;
    } else {
        q->pend = 1;
        q->pend_seq = v;
    }
}

/* While two senders' seq streams interleave: is s on the kept one?  It
 * must follow its last number, by no more than the samples its time
 * allows. */
int gate_seq_kept(const sw_gate_t *g, const sw_sample_t *s)
{
    const seqs_t *q = &g->seq;
    if (s->seq == SW_GATE_NO_SEQ || !q->have)
        return 1;
    const int64_t last = q->pend && q->pend_seq > q->last ? q->pend_seq : q->last;
    if (!(s->seq > last))
        return 0;
    const double sp = gate_spacing(g), dt = g->have_last ? s->t - g->last.t : 0.0;
    const double near = 64.0 + (sp > 0.0 && dt > 0.0 ? 2.0 * dt / sp : 0.0);
    return (double)((uint64_t)s->seq - (uint64_t)last) <= near;
}
