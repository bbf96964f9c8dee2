/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gate.c - the input gate (gate.h): every source's samples pass here on
 * their way to the engine.  Three parts:
 *   - the timing model: the logger's spacing from a time-weighted histogram
 *     of every interval, what a gap is, the engine's time across one;
 *   - a log without receive times, read through a look-ahead window: a
 *     time is refused only when the rows around it share a timeline it is
 *     off; repeated coarse stamps are spread over their unit;
 *   - a stream with receive times: chains of samples that do not continue
 *     the timeline wait until the stream confirms or refutes them; refused
 *     samples that agree with each other, or seq numbers that interleave,
 *     are a second timeline competing with the first (contested input).
 * Memory is fixed at create: the look-ahead window, CHAINS chains of
 * confirm samples each, a few rival samples. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/gate.h"
#include "swaywatch/status.h"

#define CHAINS SW_GATE_CHAINS
#define HIST_PER_DECADE 96 /* the facts' interval histogram: 2.4 % wide bins */
#define HIST_DECADES 12    /* 1e-7 s .. 1e5 s */
#define HIST_BINS (HIST_PER_DECADE * HIST_DECADES)
#define HIST_LO 1e-7
#define G0 9.80665            /* m/s^2 per g */
#define EPOCH_LIKE 1e6        /* s: a first time this large is a clock, not elapsed time */
#define TIME_MAX 8589934592.0 /* 2^33 s: the engine's limit (SW_ERESOLUTION) */

/* The timing model (docs/timing.md). */
#define TM_PER_DECADE 8                        /* spacing histogram: 33 % wide bins */
#define TM_BINS (TM_PER_DECADE * HIST_DECADES) /* 1e-7 s .. 1e5 s */
#define TM_WINDOW 120.0 /* s of covered time remembered; halved beyond (rate changes) */
#define TM_REFRESH 32   /* intervals between two readings of the histogram */
#define RECENT 8        /* the last intervals, whose median is the short-term spacing */
#define RING 64         /* ... and of which 90 % of the time says a batched pace at once */
#define GAP_FACTOR 10.0 /* a gap is longer than this many spacings ... */
#define GAP_FLOOR 0.01  /* s, ... and than this */
#define TM_QUANTILE                                                                           \
    0.9                       /* of the time covered: the spacing is the interval below which \
                                 the logger writes 90 % of the time */
#define JUMP_FACTOR 1.5       /* s per spacing: how far a sample may run ahead of real time */
#define JUMP_FLOOR 1e-4       /* s */
#define WARM_N 64             /* live: the first intervals teach the pace; none is a gap */
#define WARM_TIME 10.0        /* s of a log: gaps before are judged again once the pace is known */
#define DEFER 16              /* gap events that wait for that */
#define RECON_MIN 4           /* repeated stamps in the look-ahead that reveal a coarse clock */
#define RIVAL_MIN 3           /* refused samples in a row on one timeline: contested */
#define RIVAL_DENSE 4         /* or this many refused for their time ... */
#define RIVAL_SPAN 64         /* ... within this many samples received */
#define RIVAL_KEEP 8          /* the last of them, handed over when the contest is declared */
#define SEQ_WINDOW 256        /* accepted samples: two seq outliers within are a second sender */
#define SEQ_LIVE 3            /* +1 steps before seq numbers count as evidence */
#define SEQ_FAR 1000000000ULL /* seq steps beyond: corrupt, never a loss */

typedef struct {
    sw_sample_t s[SW_GATE_CONFIRM_MAX];
    int n;
} chain_t;

/* The logger's timing: time covered by the intervals of each bin (so that
 * the spacing is the one that covers most of the log, whatever the count
 * of short intervals in bursts), and the last few intervals. */
typedef struct {
    double w[TM_BINS];  /* s, decayed */
    double c[TM_BINS];  /* intervals, decayed */
    double total;       /* s */
    double n;           /* intervals */
    double spacing;     /* s, the time-weighted median read at the last refresh; NAN */
    int since;          /* intervals added since */
    double ring[RING];  /* s, the last intervals, gaps included */
    char ring_ok[RING]; /* learnable: no gap, nor normal only beside a gap */
    long nring;
    double rx_recent[RECENT]; /* s, receive-time intervals of accepted samples */
    long nrx;
    long seen;      /* intervals ever added */
    double covered; /* s, time covered by them */
} timing_t;

/* A gap in the first seconds of a log, waiting to be judged again. */
typedef struct {
    sw_gate_event_t ev;
    double dt; /* s, the interval */
} deferred_t;

/* The sender's seq numbers, with a discontinuity pending until the next
 * sample says whether it was real (a loss, a restart) or an outlier. */
typedef struct {
    int have;
    int64_t last;
    long normal; /* +1 steps seen */
    int pend;
    int64_t pend_seq;
    long outlier_at; /* accepted count at the last outlier; < 0 none */
} seqs_t;

/* The second timeline: refused samples consistent with each other. */
typedef struct {
    sw_sample_t last;
    int n; /* in a row on one timeline */
    sw_sample_t keep[RIVAL_KEEP];
    int nkeep, head;
    long at[RIVAL_DENSE]; /* received count at the last refusals for their time */
    int nat;
    long switched; /* received count at the last clock step or restart; < 0 none */
    double active; /* rx of its last sample */
    double since;  /* rx when the contest began */
    int contested, by_seq;
} rival_t;

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
    int have_env;
    double env;   /* s, the largest stamp minus receive time taken on this stretch: no
                     genuine sample arrives sooner after it was stamped (it may later) */
    int flushing; /* the end: refused chains are no evidence of a rival */
    timing_t tm;
    seqs_t seq;
    rival_t rv;
    /* receive times known: chains */
    chain_t chain[CHAINS];
    int nchain;
    /* no receive times: the look-ahead (a ring of window samples) */
    sw_sample_t *ahead;
    int window, head, nahead;
    int desc, ndup; /* adjacent pairs in it that go back, and that repeat */
    int recon;      /* repeated stamps are spread */
    double unit;    /* s, their unit (0: spread to the next stamp) */
    deferred_t deferred[DEFER];
    int ndeferred;
    /* facts */
    sw_gate_facts_t f;
    long hist[HIST_BINS];
    double hist_sum[HIST_BINS];
    double sum_z, sum_abs_a;
};

static const char *const reject_names[SW_GATE_NREJ] = {
    "nonfinite", "implausible", "time", "skew", "duplicate", "late", "jump", "engine", "contested"};

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
        case SW_GATE_EV_RECONSTRUCT: return "reconstructed";
        case SW_GATE_EV_CONTESTED: return "contested";
        case SW_GATE_EV_UNCONTESTED: return "uncontested";
    }
    return "unknown";
}

long sw_gate_rejected(const sw_gate_facts_t *f)
{
    long n = 0;
    for (int r = 0; r < SW_GATE_NREJ; r++) n += f->rejected[r];
    return n;
}

static void clear(sw_gate_t *g)
{
    sw_engine_t *e = g->e;
    sw_gate_opts_t o = g->o;
    sw_sample_t *ahead = g->ahead;
    const int window = g->window;
    memset(g, 0, sizeof *g);
    g->e = e;
    g->o = o;
    g->ahead = ahead;
    g->window = window;
    g->tm.spacing = NAN;
    g->seq.outlier_at = -1;
    g->rv.switched = -1;
    g->f.t_first = g->f.t_last = g->f.first_incomplete = NAN;
    g->f.dt_min = g->f.dt_median = g->f.dt_max = g->f.rate = NAN;
    g->f.spacing = NAN;
    g->f.gap_threshold = INFINITY;
    g->f.min_a = g->f.max_a = NAN;
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
    else if (o->lookahead != 0 && (o->lookahead < 2 || o->lookahead > SW_GATE_LOOKAHEAD))
        bad = "lookahead must be 2..64";
    if (bad) {
        if (msg && msglen)
            snprintf(msg, msglen, "%s", bad);
        return NULL;
    }
    sw_gate_t *g = calloc(1, sizeof *g);
    const int window = o->lookahead ? o->lookahead : SW_GATE_LOOKAHEAD;
    sw_sample_t *ahead = calloc((size_t)window, sizeof *ahead);
    if (!g || !ahead) {
        free(g);
        free(ahead);
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
    g->ahead = ahead;
    g->window = window;
    clear(g);
    return g;
}

void sw_gate_destroy(sw_gate_t *g)
{
    if (!g)
        return;
    free(g->ahead);
    free(g);
}

void sw_gate_reset(sw_gate_t *g)
{
    if (g)
        clear(g);
}

/* ---- the timing model ------------------------------------------------------------ */

static int tm_bin(double dt)
{
    int b = (int)floor(log10(dt / HIST_LO) * TM_PER_DECADE);
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
static double time_quantile(double *v, int n, double q)
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
static void tm_add(timing_t *tm, double dt, int long_run, int ok)
{
    tm->ring_ok[tm->nring % RING] = (char)ok;
    tm->ring[tm->nring++ % RING] = dt;
    tm->seen++;
    tm->covered += dt;
    if (!long_run)
        return;
    const int b = tm_bin(dt);
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

static double fmax_nan(double a, double b)
{
    return isnan(a) ? b : isnan(b) ? a : fmax(a, b);
}

/* s: the logger's spacing now, the larger of the long-run one and the
 * median of the last eight intervals (a rate that dropped is followed
 * within a few samples); NAN before any interval.  Cheap: for every
 * sample. */
static double spacing(const sw_gate_t *g)
{
    double v[RECENT];
    const int n = ring_last(&g->tm, v, RECENT, 0);
    return fmax_nan(g->tm.spacing, median8(v, n));
}

/* The same, and the pace of the last 64 intervals weighted by the time
 * each covers (all of them, or the learnable ones): a FIFO read every 30
 * samples, or the pause between two bursts, is the logger's pace from
 * its second time on; an outage is forgotten 64 samples later.  For
 * intervals that look long. */
static double spacing_full(const sw_gate_t *g, int ok_only)
{
    double v[RING];
    const int n = ring_last(&g->tm, v, RING, ok_only);
    return fmax_nan(spacing(g), time_quantile(v, n, TM_QUANTILE));
}

static double threshold_of(const sw_gate_t *g, double s)
{
    if (g->o.gap > 0.0)
        return g->o.gap;
    return isnan(s) ? INFINITY : fmax(GAP_FLOOR, GAP_FACTOR * s);
}

/* s: longer intervals are gaps, whatever the stream has seen; after: the
 * spacing of the intervals that follow (the look-ahead), NAN if unknown. */
static double gap_threshold_of(const sw_gate_t *g, double after)
{
    return threshold_of(g, fmax_nan(spacing_full(g, 0), after));
}

/* Live, the first WARM_N intervals teach the pace (the first read of a
 * FIFO, the first of two CAN frames): none of them is a gap, unless it is
 * longer than max_bridge (the timer of a monitor still sees a silence). */
static int warming(const sw_gate_t *g)
{
    return g->o.gap == 0.0 && !isnan(g->last.rx) && g->tm.seen < WARM_N;
}

static double gap_threshold(const sw_gate_t *g, double after)
{
    return warming(g) ? INFINITY : gap_threshold_of(g, after);
}

/* s: how far a sample may run ahead of the time that really passed. */
static double jump_tol(const sw_gate_t *g)
{
    if (g->o.jump < 0.0)
        return INFINITY;
    if (g->o.jump > 0.0)
        return g->o.jump;
    const double s = spacing(g);
    return isnan(s) ? 1.0 : fmax(JUMP_FLOOR, JUMP_FACTOR * s); /* none yet: 1 s */
}

double sw_gate_gap_threshold(const sw_gate_t *g)
{
    return g ? gap_threshold(g, NAN) : INFINITY;
}

int sw_gate_contested(const sw_gate_t *g)
{
    return g ? g->rv.contested : 0;
}

/* The facts' interval histogram (count-based, the whole log). */
static void note_interval(sw_gate_t *g, double dt)
{
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

/* ---- events, refusals, the second timeline --------------------------------------- */

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

static void to_rival(sw_gate_t *g, const sw_sample_t *s)
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
    emit(g, &ev);
    for (int i = 0; i < r->nkeep; i++)
        to_rival(g, &r->keep[(r->head + RIVAL_KEEP - r->nkeep + i) % RIVAL_KEEP]);
    r->nkeep = 0;
}

/* s: the second timeline is over when nothing of it came for this long. */
static double contest_quiet(const sw_gate_t *g)
{
    const double s = spacing(g);
    return isnan(s) ? 2.0 : fmax(2.0, 50.0 * s);
}

static void contest_check_end(sw_gate_t *g, double rx)
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
    emit(g, &ev);
}

/* A sample refused for its time, with a receive time: is it on a second
 * timeline (after the last one refused, as far ahead of it as real time
 * allows, not long after it)? */
static void rival_note(sw_gate_t *g, const sw_sample_t *s)
{
    rival_t *r = &g->rv;
    if (isnan(s->rx) || g->flushing)
        return;
    const double sp = spacing(g), expire = isnan(sp) ? 1.0 : fmax(1.0, 20.0 * sp);
    const double real = s->rx - r->last.rx, dt = s->t - r->last.t;
    if (r->n > 0 && dt > 0.0 && real <= expire && dt - fmax(real, 0.0) <= jump_tol(g))
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
        to_rival(g, s);
        return;
    }
    r->keep[r->head] = *s;
    r->head = (r->head + 1) % RIVAL_KEEP;
    if (r->nkeep < RIVAL_KEEP)
        r->nkeep++;
    if (r->n >= RIVAL_MIN || dense)
        contest_begin(g, s, 0);
}

static void note_seq(sw_gate_t *g, const sw_sample_t *s);

/* The timeline moved to another (a clock step, a restart), with receive
 * times: once is a sensor's doing; twice within RIVAL_SPAN * 4 samples is
 * two timelines taking turns. */
static void note_switch(sw_gate_t *g, const sw_sample_t *s)
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

static int refuse(sw_gate_t *g, const sw_sample_t *s, sw_gate_reject r, const char *text)
{
    /* a sample refused for its values did arrive: its seq is no loss */
    if ((r == SW_GATE_REJ_NONFINITE || r == SW_GATE_REJ_IMPLAUSIBLE) && g->seq.have &&
        s->seq != SW_GATE_NO_SEQ && s->seq > g->seq.last &&
        (uint64_t)s->seq - (uint64_t)g->seq.last < SEQ_FAR)
        note_seq(g, s);
    static const int code[SW_GATE_NREJ] = {SW_ENONFINITE, SW_ETOOBIG, SW_ERESOLUTION,
                                           SW_ETOOBIG,    SW_EORDER,  SW_EORDER,
                                           SW_EORDER,     SW_EINVAL,  SW_EORDER};
    g->f.rejected[r]++;
    if (g->o.on_reject)
        g->o.on_reject(g->o.user, s, r, text);
    if (r == SW_GATE_REJ_LATE || r == SW_GATE_REJ_JUMP)
        rival_note(g, s);
    return code[r];
}

/* ---- the sender's seq -------------------------------------------------------------- */

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
static void note_seq(sw_gate_t *g, const sw_sample_t *s)
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
    if (q->pend) {
        const int64_t p = q->pend_seq;
        q->pend = 0;
        if (p > q->last) { /* a leap forward */
            if (v >= p) {
                const uint64_t d = (uint64_t)p - (uint64_t)q->last;
                /* while two timelines compete, the numbers between may
                 * have come on the other one: no evidence of a loss */
                if (d <= SEQ_FAR && !g->rv.contested)
                    g->f.lost += (long)(d - 1);
                q->last = p;
                if (v == p)
                    return; /* the same seq again: confirmed, nothing more */
            } else {
                seq_outlier(g, s);
            }
        } else { /* back, or the same again */
            const int old =
                v > q->last && (uint64_t)v - (uint64_t)q->last <= (uint64_t)v - (uint64_t)p;
            if (old) {
                seq_outlier(g, s);
            } else if (v > p) {
                g->f.seq_restarts++;
                sw_gate_event_t ev = {
                    .kind = SW_GATE_EV_SEQ_RESTART, .t = g->last.t, .where = s->where};
                emit(g, &ev);
                q->last = p;
            } else {
                seq_outlier(g, s);
            }
        }
    }
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
static int seq_kept(const sw_gate_t *g, const sw_sample_t *s)
{
    const seqs_t *q = &g->seq;
    if (s->seq == SW_GATE_NO_SEQ || !q->have)
        return 1;
    const int64_t last = q->pend && q->pend_seq > q->last ? q->pend_seq : q->last;
    if (!(s->seq > last))
        return 0;
    const double sp = spacing(g), dt = g->have_last ? s->t - g->last.t : 0.0;
    const double near = 64.0 + (sp > 0.0 && dt > 0.0 ? 2.0 * dt / sp : 0.0);
    return (double)((uint64_t)s->seq - (uint64_t)last) <= near;
}

/* ---- accepting ------------------------------------------------------------------- */

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

static void judge_deferred(sw_gate_t *g);

static void count_gap(sw_gate_t *g, double span)
{
    g->f.gaps++;
    g->f.gap_total += span;
    if (span > g->f.gap_max)
        g->f.gap_max = span;
}

/* What the interval before an accepted sample teaches the timing model:
 * the pace (learned, and learnable in the ring); nothing beyond the ring,
 * being normal only beside a gap or a gap itself (tainted); the ring only,
 * learnable (the first intervals of a live stream); nothing at all (a
 * clock step, a restart). */
enum { IV_NORMAL, IV_TAINT, IV_GAP, IV_WARM, IV_BREAK };

/* Push an accepted sample at engine time te. */
static int take(sw_gate_t *g, const sw_sample_t *s, double te, int iv)
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
            if (iv != IV_BREAK)
                tm_add(&g->tm, dt, iv == IV_NORMAL, iv == IV_NORMAL || iv == IV_WARM);
        }
        const double drx = s->rx - g->last.rx;
        if (drx >= 0.0)
            g->tm.rx_recent[g->tm.nrx++ % RECENT] = drx;
    } else {
        g->f.t_first = s->t;
    }
    note_seq(g, s);
    if (g->ndeferred && g->tm.covered >= WARM_TIME)
        judge_deferred(g);
    g->f.t_last = s->t;
    g->f.accepted++;
    const double aa = fabs(s->a_g);
    if (aa > g->f.peak_a)
        g->f.peak_a = aa;
    if (fabs(s->a_z) > g->f.peak_z)
        g->f.peak_z = fabs(s->a_z);
    if (aa > 0.5 * G0)
        g->f.above_half_g++;
    if (isnan(g->f.min_a) || s->a_g < g->f.min_a)
        g->f.min_a = s->a_g;
    if (isnan(g->f.max_a) || s->a_g > g->f.max_a)
        g->f.max_a = s->a_g;
    g->sum_abs_a += aa;
    g->sum_z += s->a_z;
    if (!isnan(s->rx)) {
        const double off = s->t - s->rx;
        g->env = g->have_env ? fmax(g->env, off) : off;
        g->have_env = 1;
    }
    g->have_last = 1;
    g->last = *s;
    g->last_engine = te;
    return rc;
}

/* The first sample of the stream sets the origin. */
static int take_first(sw_gate_t *g, const sw_sample_t *s)
{
    g->relative = g->o.relative == 1 || (g->o.relative != 0 && fabs(s->t) >= EPOCH_LIKE);
    g->f.t_origin = g->relative ? s->t : 0.0;
    g->offset = -g->f.t_origin;
    return take(g, s, s->t + g->offset, IV_BREAK);
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
static double resume(sw_gate_t *g, const sw_sample_t *s, double thr, int *iv)
{
    const double dt = s->t - g->last.t; /* s, > 0 ahead, < 0 back */
    const double real = s->rx - g->last.rx, sp = spacing(g), one = isnan(sp) ? 1e-3 : sp;
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
        if (ahead > fmin(fmin(thr, gap_threshold_of(g, NAN)), g->o.max_bridge)) {
            ev.kind = SW_GATE_EV_CLOCK_STEP;
            ev.span = ahead;
            elapsed = dt - ahead > 0.0 ? dt - ahead : one;
            g->f.clock_steps++;
            note_switch(g, s);
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
        note_switch(g, s);
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
    ev.t_engine = te;
    /* A bridged gap in the first seconds of a log may be the logger's pace
     * (the first pause between 1 kHz bursts): judged again once the pace
     * is known.  Bridging is what the engine does between any samples, so
     * nothing but the word waits. */
    if (gap && ev.bridged && ev.kind == SW_GATE_EV_GAP && isnan(s->rx) && g->o.gap == 0.0 &&
        g->tm.covered < WARM_TIME && g->ndeferred < DEFER) {
        g->deferred[g->ndeferred++] = (deferred_t){.ev = ev, .dt = elapsed};
        return te;
    }
    if (gap)
        count_gap(g, elapsed);
    if (ev.kind != SW_GATE_EV_GAP || gap)
        emit(g, &ev);
    return te;
}

/* The deferred gaps of a log's first seconds, judged by the pace learned
 * since: the ones still far beyond it are said (late, with where they
 * were); the others were the logger's pace, and are learned as such. */
static void judge_deferred(sw_gate_t *g)
{
    const int n = g->ndeferred;
    if (n == 0)
        return;
    g->ndeferred = 0;
    const double thr = gap_threshold(g, NAN);
    for (int i = 0; i < n; i++) {
        deferred_t *d = &g->deferred[i];
        if (d->dt > thr) {
            count_gap(g, d->dt);
            emit(g, &d->ev);
        } else {
            tm_add(&g->tm, d->dt, 1, 1);
        }
    }
}

/* A sample that continues the timeline forward: at its own time, or
 * across a gap (after: the look-ahead's spacing, NAN if none). */
static int advance(sw_gate_t *g, const sw_sample_t *s, double after)
{
    const double dt = s->t - g->last.t;
    if (dt <= 0.0 || dt > g->o.max_bridge) {
        int iv;
        const double te = resume(g, s, gap_threshold(g, after), &iv);
        return take(g, s, te, iv);
    }
    const double te = s->t + g->offset;
    if (!(dt > threshold_of(g, spacing(g)))) /* the common case, cheap */
        return take(g, s, te, IV_NORMAL);
    /* a closer look: the pace of the recent intervals, and of the ones
     * that follow where a log shows them */
    if (!(dt > threshold_of(g, fmax_nan(spacing_full(g, 1), after))))
        return take(g, s, te, IV_NORMAL);
    const double thr = gap_threshold_of(g, after);
    if (!(dt > thr))
        return take(g, s, te, IV_TAINT); /* normal only beside a recent gap */
    if (warming(g))
        return take(g, s, te, IV_WARM); /* no gap yet: the pace is being learned */
    int iv;
    const double te_gap = resume(g, s, thr, &iv);
    return take(g, s, te_gap, iv);
}

/* ---- with receive times: chains --------------------------------------------------- */

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
        return s->t - g->last.t - fmax(s->rx - g->last.rx, 0.0) <= jump_tol(g) ||
               isnan(s->rx - g->last.rx);
    return (s->t - s->rx) - g->env <= jump_tol(g);
}

/* Does b continue a (later, and not ahead of the time that really passed
 * by more than tol)?  For chains and rival samples. */
static int follows(const sw_gate_t *g, const sw_sample_t *a, const sw_sample_t *b)
{
    const double dt = b->t - a->t;
    if (!(dt > 0.0))
        return 0;
    const double real = !isnan(a->rx) && !isnan(b->rx) ? b->rx - a->rx : 0.0;
    return dt - fmax(real, 0.0) <= jump_tol(g);
}

static void refuse_held(sw_gate_t *g, const sw_sample_t *s)
{
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

static void drop_chain(sw_gate_t *g, int k)
{
    chain_t c = g->chain[k];
    g->chain[k] = g->chain[g->nchain - 1];
    g->nchain--;
    for (int i = 0; i < c.n; i++) refuse_held(g, &c.s[i]);
}

static void drop_chains(sw_gate_t *g)
{
    while (g->nchain) drop_chain(g, g->nchain - 1);
}

/* A chain confirmed: it is the timeline now; each of its intervals gets
 * the treatment of any interval. */
static int confirm(sw_gate_t *g, int k)
{
    chain_t c = g->chain[k];
    g->chain[k] = g->chain[g->nchain - 1];
    g->nchain--;
    drop_chains(g); /* the others are refuted */
    int rc = SW_OK;
    for (int i = 0; i < c.n; i++) {
        int r;
        if (!g->have_last) {
            r = take_first(g, &c.s[i]);
        } else if (i == 0) {
            int iv;
            const double te = resume(g, &c.s[0], gap_threshold(g, NAN), &iv);
            r = take(g, &c.s[0], te, iv);
        } else {
            r = advance(g, &c.s[i], NAN);
        }
        if (r != SW_OK && (rc == SW_OK || r < 0))
            rc = r;
    }
    return rc;
}

/* Has a chain waited long enough?  confirm samples, spanning at least half
 * the real time in which the timeline's own samples arrive: a burst of
 * forged samples cannot confirm itself while the genuine stream goes on. */
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
    double v[RECENT];
    const int n = g->tm.nrx < RECENT ? (int)g->tm.nrx : RECENT;
    memcpy(v, g->tm.rx_recent, sizeof v[0] * (size_t)n);
    const double rx_sp = time_quantile(v, n, TM_QUANTILE); /* bursts do not shrink it */
    return rx_span >= 0.5 * (g->o.confirm - 1) * rx_sp;
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
        if (c->n == SW_GATE_CONFIRM_MAX) { /* full, and not confirmed yet: the oldest goes */
            const sw_sample_t old = c->s[0];
            memmove(c->s, c->s + 1, sizeof c->s[0] * (size_t)(c->n - 1));
            c->n--;
            refuse_held(g, &old);
            c = &g->chain[k];
        }
        c->s[c->n++] = *s;
        if (confirmable(g, c))
            return confirm(g, k);
        return SW_GATE_HELD;
    }
    if (g->nchain == CHAINS)
        drop_chain(g, 0); /* the oldest makes room */
    chain_t *c = &g->chain[g->nchain++];
    c->s[0] = *s;
    c->n = 1;
    if (confirmable(g, c))
        return confirm(g, g->nchain - 1);
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
            advance(g, &early[i], NAN);
        else
            refuse_held(g, &early[i]); /* the same time as one before it */
    }
}

/* The same sample again (a network duplicate) is no rival; the same time
 * with other values or another seq is. */
static int same_sample(const sw_sample_t *a, const sw_sample_t *b)
{
    return a->t == b->t && a->seq == b->seq && a->a_g == b->a_g && a->a_z == b->a_z;
}

static int live_push(sw_gate_t *g, const sw_sample_t *s)
{
    contest_check_end(g, s->rx);
    char text[160];
    if (g->rv.contested && g->rv.by_seq && !seq_kept(g, s)) {
        g->rv.active = s->rx;
        snprintf(text, sizeof text,
                 "seq %lld is not the kept sender's (two senders' seq numbers interleave)",
                 (long long)s->seq);
        g->f.rejected[SW_GATE_REJ_CONTESTED]++;
        if (g->o.on_reject)
            g->o.on_reject(g->o.user, s, SW_GATE_REJ_CONTESTED, text);
        to_rival(g, s);
        return SW_EORDER;
    }
    if (g->have_last && s->t == g->last.t) {
        snprintf(text, sizeof text, "time %.15g s is a duplicate (the same as the sample before)",
                 s->t);
        const int rc = refuse(g, s, SW_GATE_REJ_DUPLICATE, text);
        if (!same_sample(s, &g->last))
            rival_note(g, s);
        return rc;
    }
    if (g->have_last && continues(g, s)) {
        take_early(g, s);
        drop_chains(g); /* the stream went on: waiting samples are refuted */
        return advance(g, s, NAN);
    }
    return hold(g, s);
}

/* ---- without receive times: the look-ahead ----------------------------------------- */

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
    emit(g, &ev);
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
        span = spacing(g) * k; /* the log's end: at the logger's pace */
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
    const double after = g->nahead > 1 ? spacing_after(g) : NAN;
    const int fwd = s.t > T && forward_ok(g, T);
    const int restart = s.t < T && backward_restart(g, T);
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
            take_first(g, &s);
        else
            refuse_held(g, &s);
        return;
    }
    if (s.t == T) {
        snprintf(text, sizeof text, "time %.15g s is a duplicate (the same as the row before)",
                 s.t);
        refuse(g, &s, SW_GATE_REJ_DUPLICATE, text);
        return;
    }
    if (s.t > T) {
        if (fwd)
            advance(g, &s, after);
        else
            refuse_held(g, &s);
        return;
    }
    if (restart) {
        int iv;
        const double te = resume(g, &s, gap_threshold(g, after), &iv);
        take(g, &s, te, iv);
    } else {
        refuse_held(g, &s);
    }
}

static int ahead_push(sw_gate_t *g, const sw_sample_t *s)
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

static void ahead_drain(sw_gate_t *g)
{
    while (g->nahead > 0) decide_front(g);
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
    if (isnan(s->rx))
        return ahead_push(g, s);
    ahead_drain(g); /* a source that gains receive times: what waits is decided */
    return live_push(g, s);
}

int sw_gate_flush(sw_gate_t *g)
{
    if (!g)
        return SW_EINVAL;
    g->flushing = 1;
    ahead_drain(g);
    judge_deferred(g);
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
    g->flushing = 0;
    return SW_OK;
}

void sw_gate_facts(const sw_gate_t *g, sw_gate_facts_t *f)
{
    *f = g->f;
    f->held = g->nahead;
    for (int k = 0; k < g->nchain; k++) f->held += g->chain[k].n;
    f->mean_z = f->accepted ? g->sum_z / (double)f->accepted : 0.0;
    f->mean_abs_a = f->accepted ? g->sum_abs_a / (double)f->accepted : 0.0;
    long n = 0, half = 0;
    for (int b = 0; b < HIST_BINS; b++) n += g->hist[b];
    for (int b = 0; b < HIST_BINS && n; b++) {
        half += g->hist[b];
        if (2 * half >= n) {
            f->dt_median = g->hist_sum[b] / (double)g->hist[b]; /* the bin's mean */
            break;
        }
    }
    /* spread stamps alternate (half a unit, a unit): their median says
     * nothing of the logger's pace, their mean does */
    if (f->reconstructed > 0 && f->accepted > 1 && f->duration > 0.0)
        f->dt_median = f->duration / (double)(f->accepted - 1);
    f->rate = f->dt_median > 0.0 ? 1.0 / f->dt_median : NAN;
    f->spacing = spacing_full(g, 0);
    f->gap_threshold = gap_threshold(g, NAN);
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
    const double min_still = lim->min_still > 0.0 ? lim->min_still : 60.0;
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
    /* A truck brakes at 0.5 g for seconds, never for a minute: a channel
     * beyond it most of a long log, or one that never moves, is no
     * longitudinal acceleration (gravity on a vertical axis, a GPS, speed or
     * angle column). */
    if (f->duration >= min_still && f->accepted >= 100) {
        const int high = 2 * f->above_half_g > f->accepted;
        const int still = f->min_a == f->max_a;
        if (high || still) {
            if (high)
                snprintf(why, whylen,
                         "the longitudinal channel looks like gravity or not an acceleration: "
                         "%.0f %% of %.3g min beyond 0.5 g (mean |a| %.3g g), which no truck "
                         "brakes or speeds up for that long; choose the acceleration column "
                         "with --accel-col NAME|N, or give --force",
                         100.0 * (double)f->above_half_g / (double)f->accepted, f->duration / 60.0,
                         f->mean_abs_a / G0);
            else
                snprintf(why, whylen,
                         "the longitudinal channel looks like gravity or not an acceleration: "
                         "it reads %.6g m/s^2 for all %.3g min and never varies; choose the "
                         "acceleration column with --accel-col NAME|N, or give --force",
                         f->min_a, f->duration / 60.0);
            return SW_GATE_REFUSE;
        }
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
