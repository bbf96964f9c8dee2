/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gate_int.h - what the files of the input gate share (gate.h is the
 * contract): the gate's state, its constants, and the calls between
 *   gate.c          the API: create, push, flush, facts, the plausibility check;
 *   gate_pace.c     the logger's pace and the thresholds it gives (a leaf);
 *   gate_timing.c   taking a sample, across gaps, steps and restarts;
 *   gate_ahead.c    a log without receive times, read through the look-ahead;
 *   gate_live.c     a stream with receive times: chains, confirmed or refuted;
 *   gate_contest.c  events, refusals, the sender's seq, a second timeline.
 * docs/timing.md tells why each does what it does. */
#ifndef SW_GATE_INT_H
#define SW_GATE_INT_H

#include <math.h>
#include <stdint.h>

#include "swaywatch/gate.h"
#include "swaywatch/status.h"
#include "swaywatch/units.h"

#define CHAINS SW_GATE_CHAINS
#define HIST_PER_DECADE 96 /* the facts' interval histogram: 2.4 % wide bins */
#define HIST_DECADES 12    /* 1e-7 s .. 1e5 s */
#define HIST_BINS (HIST_PER_DECADE * HIST_DECADES)
#define HIST_LO 1e-7
#define EPOCH_LIKE 1e6        /* s: a first time this large is a clock, not elapsed time */
#define TIME_MAX 8589934592.0 /* 2^33 s: the engine's limit (SW_ERESOLUTION) */

/* The timing model (docs/timing.md). */
#define TM_PER_DECADE 8                        /* spacing histogram: 33 % wide bins */
#define TM_BINS (TM_PER_DECADE * HIST_DECADES) /* 1e-7 s .. 1e5 s */
#define TM_WINDOW 120.0 /* s of covered time remembered; halved beyond (rate changes) */
#define TM_REFRESH 32   /* intervals between two readings of the histogram */
#define RECENT 8        /* the last intervals, whose median is the short-term spacing */
#define RING 64         /* ... and of which 90 % of the time says a batched pace at once */
#define ENV_N 64        /* samples whose arrival makes the envelope */
#define GAP_FACTOR 10.0 /* a gap is longer than this many spacings ... */
#define GAP_FLOOR 0.01  /* s, ... and than this */
#define TM_QUANTILE                                                                           \
    0.9                       /* of the time covered: the spacing is the interval below which \
                                 the logger writes 90 % of the time */
#define JUMP_FACTOR 1.5       /* s per spacing: how far a sample may run ahead of real time */
#define JUMP_FLOOR 1e-4       /* s */
#define PACED_RATIO 1.5       /* live: two intervals within this ratio are a pace (gate_timing.c) */
#define WARM_N 64             /* live: the first intervals teach the pace; none is a gap */
#define WARM_TIME 10.0        /* s of a log: gaps before are judged again once the pace is known */
#define WARM_LIVE 2.0         /* s of a live stream: the same */
#define DEFER 16              /* gap events that wait for that */
#define RECON_MIN 4           /* repeated stamps in the look-ahead that reveal a coarse clock */
#define RIVAL_MIN 3           /* refused samples in a row on one timeline: contested */
#define RIVAL_DENSE 8         /* or this many refused for their time ... */
#define RIVAL_SPAN 64         /* ... within this many samples received */
#define RIVAL_KEEP 8          /* the last of them, handed over when the contest is declared */
#define SEQ_WINDOW 256        /* accepted samples: two seq outliers within are a second sender */
#define SEQ_LIVE 3            /* +1 steps before seq numbers count as evidence */
#define SEQ_FAR 1000000000ULL /* seq steps beyond: corrupt, never a loss */
#define SEQ_REFUSED 16        /* seqs ahead of the last kept, of samples refused */

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
    /* refused samples ahead of last: they arrived, so a leap over them
     * is no loss of theirs (distinct seqs, a ring) */
    int64_t refused[SEQ_REFUSED];
    int nrefused, refused_head;
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
    double env; /* s, the largest stamp minus receive time of the last ENV_N samples taken
                   on this stretch: no genuine sample arrives sooner after it was stamped
                   (it may later); the recent ones, so that it follows a latency that
                   drifts up */
    double env_ring[ENV_N];
    long nenv, env_at; /* samples in the ring; the index of the largest */
    int flushing;      /* the end: refused chains are no evidence of a rival */
    timing_t tm;
    seqs_t seq;
    rival_t rv;
    /* receive times known: chains */
    chain_t chain[CHAINS];
    int nchain;
    double rx_prev; /* s, arrival of the last sample that reached the live path; NAN */
    /* A backlog read after a silence (docs/timing.md, "A drained backlog"):
     * no sample at all arrived for longer than a gap (the monitor or the
     * stream stopped), and what comes since was stamped before it was
     * read, later than the stream's own delivery by more than a gap */
    double burst_from;  /* s, arrival of the first sample after the silence; NAN: none goes
                           on (a sample taken on time ends it) */
    double burst_until; /* s, arrival by which it is over whatever comes: twice the silence */
    double burst_env;   /* s, the envelope before the silence (the stream's delivery on time;
                           NAN unknown) */
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
    /* its count and the bins in use, [hist_lo, hist_hi] (none while
     * hist_n is 0): the facts' median looks at those alone, as a monitor
     * reads the facts often */
    long hist_n;
    int hist_lo, hist_hi;
    double sum_z, sum_abs_a;
    double sum_abs_y; /* m/s^2, of the lateral axis (opts.lateral) */
};

/* What the interval before an accepted sample teaches the timing model:
 * the pace (learned, and learnable in the ring); nothing beyond the ring,
 * being normal only beside a gap or a gap itself (tainted); the ring only,
 * learnable (the first intervals of a live stream); nothing at all (a
 * clock step, a restart). */
enum { IV_NORMAL, IV_TAINT, IV_GAP, IV_WARM, IV_BREAK };

/* The larger of a and b, either of which may be NAN (unknown). */
static inline double gate_fmax_nan(double a, double b)
{
    return isnan(a) ? b : isnan(b) ? a : fmax(a, b);
}

/* gate_pace.c: the logger's pace, and the thresholds it gives */
void gate_tm_add(timing_t *tm, double dt, double x, int long_run, int ok);
double gate_time_quantile(double *v, int n, double q);
double gate_spacing(const sw_gate_t *g);
double gate_spacing_full(const sw_gate_t *g, int ok_only);
double gate_threshold_of(const sw_gate_t *g, double s);
int gate_looks_long(const sw_gate_t *g, double dt);
double gate_recent_max(const sw_gate_t *g);
int gate_warming(const sw_gate_t *g);
double gate_gap_threshold_of(const sw_gate_t *g, double after);
double gate_gap_threshold(const sw_gate_t *g, double after);
double gate_jump_tol(const sw_gate_t *g);

/* gate_timing.c: taking a sample, across gaps */
int gate_take(sw_gate_t *g, const sw_sample_t *s, double te, int iv);
int gate_take_first(sw_gate_t *g, const sw_sample_t *s);
double gate_resume(sw_gate_t *g, const sw_sample_t *s, double thr, int *iv);
void gate_judge_deferred(sw_gate_t *g);
int gate_advance(sw_gate_t *g, const sw_sample_t *s, double after);

/* gate_contest.c: events, refusals, seq, a second timeline */
void gate_emit(sw_gate_t *g, sw_gate_event_t *ev);
void gate_to_rival(sw_gate_t *g, const sw_sample_t *s);
void gate_contest_check_end(sw_gate_t *g, double rx);
void gate_rival_note(sw_gate_t *g, const sw_sample_t *s);
void gate_note_switch(sw_gate_t *g, const sw_sample_t *s);
int gate_refuse(sw_gate_t *g, const sw_sample_t *s, sw_gate_reject r, const char *text);
void gate_note_seq(sw_gate_t *g, const sw_sample_t *s);
int gate_seq_kept(const sw_gate_t *g, const sw_sample_t *s);

/* gate_live.c: with receive times */
void gate_refuse_held(sw_gate_t *g, const sw_sample_t *s);
void gate_drop_chains(sw_gate_t *g);
int gate_confirm(sw_gate_t *g, int k);
int gate_live_push(sw_gate_t *g, const sw_sample_t *s);

/* gate_ahead.c: without receive times */
int gate_ahead_push(sw_gate_t *g, const sw_sample_t *s);
void gate_ahead_drain(sw_gate_t *g);

#endif
