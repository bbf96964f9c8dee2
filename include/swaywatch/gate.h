/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gate.h - one input gate for every source.  CSV replay, lcm-logger replay
 * and the live monitor hand their samples to a gate; it decides, the same
 * way for all of them, which samples the engine gets and what happened to
 * the stream, and it keeps the facts that expose a misread log.
 * docs/timing.md tells the whole story; in short:
 *
 * Values: a value that is not finite, or beyond max_accel (a spike), is
 * refused at once.
 *
 * The logger's timing is learned from the whole stream, not from the last
 * few samples: a histogram of every interval, weighted by the time each
 * covers (so that 1 kHz bursts in a 10 Hz log, FIFO reads stamped in
 * batches or merged CAN frames do not make the logger look faster than it
 * is), forgetting slowly so that a rate change is followed, beside the
 * median of the last few intervals.  Its spacing S is the larger of the
 * interval below which the logger writes 90 % of the time and that median.
 * A gap is an interval longer than 10 S and than 10 ms (gap overrides
 * both), or longer than max_bridge whatever the spacing: every
 * long interval, wherever it comes from, is bridged linearly up to
 * max_bridge or restarts the packages from rest (sw_engine_restart), so the
 * work per sample is bounded whatever the times.
 *
 * A log (no receive time) is read with a look-ahead of SW_GATE_LOOKAHEAD
 * samples: a time is refused only on evidence that it is the outlier, a row
 * off the timeline that its neighbours share (not in any longest increasing
 * run of the look-ahead), never because a step is longer than the steps
 * before it; a run of confirm rows back in time that the old timeline does
 * not outnumber is a restart.  The spacing after an interval counts as
 * well: a rate that drops is no gap.  Times that repeat because the logger
 * stamps whole milliseconds (or any coarse unit) at a higher rate are
 * reconstructed: each run of equal stamps is spread evenly over its unit
 * (an event, and a count in the facts).
 *
 * With receive times (live, lcm-logger files) time follows the stream, not
 * a sample that leaps.  No genuine sample arrives sooner after it was
 * stamped than the fastest of the last 64 (the envelope; it may arrive
 * later: a stall, then a burst).  A sample stamped further ahead of that
 * than 1.5 S (jump), or a little ahead of it and leading the last sample by
 * more than the time that passed allows, or behind the last sample, waits
 * in a chain of mutually consistent samples; the stream confirms the chain
 * (confirm samples in a row, spanning real time) or refutes it (a sample
 * on the old timeline; held samples stamped before that one were only
 * early and are taken), so one forged or corrupt time costs that sample,
 * never the rest.  A confirmed chain is
 *   - a gap (the stream resumed later), handled by the gap policy;
 *   - a clock step (the source's clock moved while little real time
 *     passed): re-timed, the motion goes on;
 *   - a restart (time went back): re-timed, and with no receive time the
 *     packages restart from rest.
 * The engine's clock moves by the source's own time, except where the
 * source's clock stepped: a receive time that leaps never moves it.
 *
 * Contested input (receive times known): samples refused for their time
 * that form a timeline of their own (three in a row, each within 16
 * intervals of the last), eight refused for their time within 64
 * received, the timeline switching twice (clock steps, restarts) within
 * 256, or two seq outliers within 256 from a sender that counts: two
 * timelines compete on the channel (a forged or duplicated sender).  The
 * gate says so at once
 * (SW_GATE_EV_CONTESTED), keeps the timeline the receive times support,
 * hands every sample of the other one to on_rival (for a second set of
 * engines to evaluate), and says when the other one has gone quiet
 * (SW_GATE_EV_UNCONTESTED).  The sender's seq counts a loss only on
 * evidence: a jump that the next sample confirms.
 *
 * Every refused sample is counted by reason and reported with where it
 * came from; every gap, step and restart is an event.  A gap that overlaps
 * rocking, or with the bed at a quarter of a package's uplift threshold or
 * more at either end (what it hid may have lifted the package), leaves the
 * verdict incomplete (counted, and the first such time kept).
 *
 * Times handed to the engine are the source's (relative to the first
 * sample when relative is set, or when the source's times look like an
 * epoch), shifted past every step and restart so that they always
 * increase.  Memory is fixed at create; arithmetic on any int64 seq and any
 * time is overflow-free.  No I/O, no global state. */
#ifndef SWAYWATCH_GATE_H
#define SWAYWATCH_GATE_H

#include <stddef.h>
#include <stdint.h>

#include "engine.h"
#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SW_GATE_NO_SEQ INT64_MIN /* sw_sample_t.seq: the source has none */
#define SW_GATE_CONFIRM_MAX 8    /* largest confirm */
#define SW_GATE_CHAINS 3         /* chains waiting at once (the oldest makes room) */
#define SW_GATE_LOOKAHEAD 64     /* samples a log without receive times is read ahead */
/* most samples held: the look-ahead, or the chains */
#define SW_GATE_HELD_MAX (SW_GATE_LOOKAHEAD + SW_GATE_CHAINS * SW_GATE_CONFIRM_MAX)

typedef struct {
    double t;     /* s, the source's time */
    double a_g;   /* m/s^2, longitudinal (x forward), in SI after units and flip */
    double a_z;   /* m/s^2, vertical up, as read (see vert_gravity); 0 if none */
    double a_max; /* m/s^2, largest |value| of all the sample's axes for the spike
                     check; NAN: max(|a_g|, |a_z|), and |a_y| in a lateral gate */
    int64_t seq;  /* the sender's sequence number, or SW_GATE_NO_SEQ */
    double rx;    /* s, receive time on a monotonic clock; NAN if none (a CSV log) */
    double wall;  /* s since 1970 at receipt, for the skew check; NAN if none */
    long where;   /* the source's place of it (line, event number), for messages */
    double a_y;   /* m/s^2, lateral, in SI after units and flip: read only by a gate
                     made with lateral (sw_gate_opts_t), checked there as a_g is */
} sw_sample_t;

typedef enum {
    SW_GATE_REJ_NONFINITE = 0, /* a value not finite */
    SW_GATE_REJ_IMPLAUSIBLE,   /* an axis beyond max_accel: a spike */
    SW_GATE_REJ_TIME,          /* a time too large for its resolution (2^33 s) */
    SW_GATE_REJ_SKEW,          /* too far from the wall clock at receipt */
    SW_GATE_REJ_DUPLICATE,     /* the same time as the last accepted sample */
    SW_GATE_REJ_LATE,          /* before the last accepted sample, and not confirmed */
    SW_GATE_REJ_JUMP,          /* far ahead, and the stream did not follow it */
    SW_GATE_REJ_ENGINE,        /* refused by the engine (should not happen) */
    SW_GATE_REJ_CONTESTED,     /* on a second sender's seq stream while two compete
                                  (evaluated apart: on_rival) */
    SW_GATE_NREJ
} sw_gate_reject;

typedef enum {
    SW_GATE_EV_GAP = 1,         /* span s, from t (source time of the last sample before) */
    SW_GATE_EV_CLOCK_STEP = 2,  /* the source clock stepped by span s (+ ahead, - back) */
    SW_GATE_EV_RESTART = 3,     /* time went back by span s with no receive time: restart */
    SW_GATE_EV_SEQ_RESTART = 4, /* seq went back while time went on: the sender restarted */
    SW_GATE_EV_RECONSTRUCT = 5, /* times repeat: the logger stamps in units of span s at a
                                   higher rate; repeated stamps are spread over their unit
                                   from here on (span 0: over the interval to the next) */
    SW_GATE_EV_CONTESTED = 6,   /* a second timeline competes with the one kept (forged or
                                   duplicated sender): its samples go to on_rival */
    SW_GATE_EV_UNCONTESTED = 7  /* the second timeline went quiet; span: s it lasted */
} sw_gate_event_kind;

typedef struct {
    sw_gate_event_kind kind;
    double t;        /* s, the source's time where it happened (the last sample before) */
    double t_engine; /* s, the engine's time of the first sample after */
    double span;     /* s, see the kind */
    int restarted;   /* the packages were restarted from rest (gap policy, restart) */
    int incomplete;  /* it overlapped rocking or an acceleration past the uplift threshold */
    int bridged;     /* the gap was bridged by linear interpolation */
    long where;      /* the source's place of the first sample after */
} sw_gate_event_t;

typedef void (*sw_gate_event_fn)(void *user, const sw_gate_event_t *ev);
/* One refused sample: its reason, and a sentence saying why. */
typedef void (*sw_gate_reject_fn)(void *user, const sw_sample_t *s, sw_gate_reject r,
                                  const char *text);
/* One sample as the engine got it: engine time t (s), a_g and a_z (m/s^2, a_z
 * with gravity removed when vert_gravity says so); restart is non-zero when
 * the packages were restarted from rest just before it (sw_engine_restart).
 * Pushing the same calls into a fresh engine of the same scenes, with
 * sw_engine_restart() where restart is set, repeats the run: a log read
 * once can be replayed many times exactly as the gate fed it. */
typedef void (*sw_gate_take_fn)(void *user, double t, double a_g, double a_z, int restart);
/* The same with the lateral acceleration a_y (m/s^2, as the engine got it:
 * sw_engine_push_lat) of a lateral gate, for a caller that runs the
 * lateral planes again. */
typedef void (*sw_gate_take_lat_fn)(void *user, double t, double a_g, double a_y, double a_z,
                                    int restart);
/* One sample of the second timeline while two compete (already counted as
 * refused): its time is the source's, as pushed.  A caller that evaluates
 * both timelines pushes it into a gate of its own in front of a second set
 * of engines. */
typedef void (*sw_gate_rival_fn)(void *user, const sw_sample_t *s);

typedef enum {
    SW_GAP_BRIDGE = 0, /* interpolate linearly across (up to max_bridge) */
    SW_GAP_RESTART = 1 /* treat as missing: the packages restart from rest after it */
} sw_gap_policy;

typedef struct {
    double gap; /* s: samples further apart are a gap; 0 = 10 times the logger's
                   spacing and at least 10 ms (docs/timing.md) */
    sw_gap_policy gap_policy;
    double max_bridge; /* s: longest gap bridged under SW_GAP_BRIDGE; 0 = 10 s */
    double max_accel;  /* m/s^2: any axis beyond is a spike; 0 = 50 g */
    double jump;       /* s, with receive times: a sample further ahead of the last one
                          than the time that really passed waits for confirmation; 0 =
                          1.5 times the spacing; < 0 = never (every sample taken at once;
                          in a log, a row ahead is then never refused) */
    double max_skew;   /* s: |t - wall| beyond is refused; 0 = not checked */
    int confirm;       /* consistent samples that confirm a chain; 0 = 3, at most
                          SW_GATE_CONFIRM_MAX */
    int relative;      /* 1: engine times from the first sample; 0: the source's times;
                          -1 (default 0 means -1): relative when the first |t| >= 1e6 s */
    int vert_gravity;  /* a_z includes gravity (an accelerometer reads +1 g at rest):
                          1 yes, subtracted (SW_G0); 0 no; the facts say what a_z read */
    sw_gate_event_fn on_event;
    sw_gate_reject_fn on_reject;
    sw_gate_take_fn on_take; /* may be NULL */
    void *user;
    sw_gate_rival_fn on_rival; /* may be NULL: the second timeline is only counted */
    int lookahead;             /* samples a log without receive times is read ahead, 2 ..
                                  SW_GATE_LOOKAHEAD; 0 = SW_GATE_LOOKAHEAD */
    int lateral;               /* the samples carry a_y: checked as a_g is (finite, the
                                  spike limit, the facts' lat and the plausibility check)
                                  and pushed with sw_engine_push_lat (the engine made with
                                  opts.lateral); on_take still gets the longitudinal value */
    /* may be NULL: in a lateral gate, called instead of on_take, with the
     * lateral value too */
    sw_gate_take_lat_fn on_take_lat;
} sw_gate_opts_t;

/* One acceleration axis as the accepted samples showed it. */
typedef struct {
    double peak;       /* m/s^2, largest |a| */
    long above_half_g; /* samples with |a| > 0.5 g */
    double mean_abs;   /* m/s^2, mean |a| */
    double min, max;   /* m/s^2, smallest and largest a (NAN: none) */
} sw_gate_axis_t;

/* What the stream was: for the summaries, and for the plausibility check. */
typedef struct {
    long received;               /* samples handed to the gate */
    long upstream_rejected;      /* the caller's to fill: samples its reader refused before
                                    the gate (unreadable rows); sw_gate_check counts them */
    long accepted;               /* pushed into the engine */
    long held;                   /* waiting in chains or the look-ahead now */
    long rejected[SW_GATE_NREJ]; /* received = accepted + held + sum(rejected) */
    long lost;                   /* missing by the sender's seq: a jump the next sample
                                    confirmed (a seq that leaps alone is no loss) */
    long gaps, clock_steps, restarts, seq_restarts;
    long incomplete;                  /* gaps and restarts that leave the verdict incomplete */
    double first_incomplete;          /* s, source time of the first (NAN: none) */
    double gap_total, gap_max;        /* s, spans of the gaps */
    double t_first, t_last;           /* s, source times of the first and last accepted (NAN) */
    double t_origin;                  /* s, the source time of engine t = 0 */
    double duration;                  /* s, covered by accepted samples (steps excluded) */
    double dt_min, dt_median, dt_max; /* s, intervals between accepted samples (NAN) */
    double rate;                      /* Hz, 1 / dt_median (NAN) */
    double peak_a, peak_z;            /* m/s^2, largest |a_g| and |a_z| accepted */
    double mean_z;                    /* m/s^2, mean a_z as read (before gravity removal) */
    /* added with the whole-stream timing model (docs/timing.md) */
    double spacing;       /* s, the logger's pace now: its long-run pace and the median of
                             the last eight intervals (NAN: none) */
    double gap_threshold; /* s, intervals longer were gaps at the end (INFINITY: none yet) */
    long reconstructed;   /* samples whose repeated time was spread over its unit */
    double stamp_unit;    /* s, the unit of the stamps that were spread (0: none found) */
    long seq_outliers;    /* seqs that leapt or went back alone (another sender's) */
    long contests;        /* times a second timeline competed */
    long contested;       /* samples of the second timeline (refused here; on_rival) */
    long above_half_g;    /* accepted samples with |a_g| > 0.5 g */
    double mean_abs_a;    /* m/s^2, mean |a_g| accepted */
    double min_a, max_a;  /* m/s^2, smallest and largest a_g accepted (NAN: none) */
    /* added with the lateral plane */
    int lateral;        /* the samples carried a lateral acceleration (opts.lateral) */
    sw_gate_axis_t lat; /* its axis (zeros and NAN without) */
} sw_gate_facts_t;

typedef struct sw_gate sw_gate_t;

/* A gate in front of engine e (borrowed; it must outlive the gate).  NULL
 * on failure (bad options; msg says why). */
SW_API sw_gate_t *sw_gate_create(sw_engine_t *e, const sw_gate_opts_t *o, char *msg, size_t msglen);
SW_API void sw_gate_destroy(sw_gate_t *g); /* NULL ok */

/* One sample.  Returns SW_OK or SW_EVENT (taken: the engine's status), 1000
 * (SW_GATE_HELD) when it waits in a chain, or a negative status when it was
 * refused (on_reject said why). */
#define SW_GATE_HELD 1000
SW_API int sw_gate_push(sw_gate_t *g, const sw_sample_t *s);

/* End of the stream: the look-ahead is decided, chains nobody confirmed
 * are refused (as late or jumps).  Returns SW_OK. */
SW_API int sw_gate_flush(sw_gate_t *g);

/* Back to the state after create (no timeline, no facts), keeping the
 * options; nothing is allocated.  For a second timeline evaluated afresh. */
SW_API void sw_gate_reset(sw_gate_t *g);

/* s: an interval longer than this is a gap now (the gap option, or ten
 * times the long-run pace and the median of the last eight intervals, at
 * least 10 ms; INFINITY before the first interval and while a live stream
 * warms up).  Cheap, for a monitor's timer, which waits at least this
 * long before it calls the input silent; a sample's own interval is also
 * judged against the recent and the look-ahead pace, which can only say
 * more. */
SW_API double sw_gate_gap_threshold(const sw_gate_t *g);

/* Non-zero while a second timeline competes (SW_GATE_EV_CONTESTED). */
SW_API int sw_gate_contested(const sw_gate_t *g);

SW_API void sw_gate_facts(const sw_gate_t *g, sw_gate_facts_t *f);
/* Samples pushed into the engine so far (sw_gate_facts_t.accepted), cheap:
 * for a caller that asks after every sample. */
SW_API long sw_gate_accepted(const sw_gate_t *g);

/* The source's time (s) of an engine time on the current stretch of the
 * timeline (since the last gap, step or restart): for publishing times on
 * the source's clock. */
SW_API double sw_gate_source_time(const sw_gate_t *g, double t_engine);
SW_API long sw_gate_rejected(const sw_gate_facts_t *f); /* sum of rejected[] */

/* "nonfinite", "implausible", "time", "skew", "duplicate", "late", "jump",
 * "engine", "contested"; "gap", "clock step", "restart", "seq restart",
 * "reconstructed", "contested", "uncontested". */
SW_API const char *sw_gate_reject_name(sw_gate_reject r);
SW_API const char *sw_gate_event_name(sw_gate_event_kind k);

/* ---- plausibility: is this a log a vehicle can have written? ---------------- */

typedef struct {
    double max_rejected; /* share of received samples refused; 0 = 0.01 */
    double min_rate;     /* Hz, below: refused (no shock of interest resolved; most often a
                            time column in ms read as s, which gives 1 Hz); 0 = 2 */
    double warn_rate;    /* Hz, below: a warning (short shocks not resolved); 0 = 20 */
    double max_duration; /* s; 0 = 366 days */
    double max_peak;     /* m/s^2, largest |a_g| a truck bed sees; 0 = 25 g */
    double min_still;    /* s: a log at least this long whose longitudinal channel sits
                            beyond 0.5 g for most of it, or never varies, is refused
                            (gravity, a GPS or speed column); 0 = 60 s */
} sw_gate_limits_t;

/* SW_OK, SW_GATE_WARN (a verdict, with the warning in why) or SW_GATE_REFUSE
 * (no verdict: why says what is implausible, what it most often means and
 * the option that reads it right). */
#define SW_GATE_WARN 1
#define SW_GATE_REFUSE (-1)
SW_API int sw_gate_check(const sw_gate_facts_t *f, const sw_gate_limits_t *lim, char *why,
                         size_t whylen);

#ifdef __cplusplus
}
#endif
#endif
