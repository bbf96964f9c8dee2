/* SPDX-License-Identifier: GPL-3.0-or-later */
/* monitor.h - the core of the LCM monitor (libswaywatch_lcm), shared by
 * `swaywatch monitor` (live), the replay of lcm-logger files (eventlog.h)
 * and the tests.
 *
 * It takes raw accel_t messages (bytes, as LCM delivers them), checks and
 * decodes each one into a sample of one input stream (stream.h: the gate,
 * the engine, the reserve, the alarm logic, the same stream a CSV log
 * goes through), rate-limits the alarms, and publishes state_t and
 * alarm_t messages on an lcm_t (if one is given).  It owns no thread, no
 * socket and no timer: the caller delivers messages and calls
 * sw_mon_tick() when sw_mon_deadline() says so.  Nothing here blocks
 * (LCM publishing over udpm does not), prints or touches files.
 *
 * Every message received is accounted for exactly once:
 *   received = accepted + sum of rejected[reason] + held.
 * Samples pass the input gate (gate.h) as every source's do: integrated
 * by their own utime (the sensor's clock), the time that really passed
 * known from the arrival time; a sample that leaps ahead of the stream, or
 * goes back, waits until the stream confirms it (a gap, a clock step, a
 * sensor restart: each an alarm and a counter) or refutes it (refused), so
 * one forged or corrupt utime costs that sample only, and no stretch of
 * input blinds the monitor for more than a few samples.  Gaps follow the
 * gap policy at a cost independent of their length.
 *
 * Contested input (docs/timing.md): when refused samples form a second
 * timeline, or a second sender's seq numbers interleave, INPUT_CONTESTED
 * is raised at once (critical), the timeline the arrival times support is
 * kept, and the other is evaluated by the stream's second set of engines,
 * made at create time, whose alarms from WARN up are raised too ("second
 * timeline: ..."): no pattern of forged samples silences an overturn.
 *
 * Authenticated sensors (auth.h, docs/security.md): with keys, every
 * message must carry a MAC under one of them and a fresh freshness value;
 * the others are refused before the gate sees them (unauthenticated,
 * unknown_key, bad_mac, replayed), counted, and raise INPUT_CONTESTED
 * (critical) when they begin to arrive: the authenticated stream alone is
 * integrated, and keeps its verdict. */
#ifndef SWAYWATCH_LCM_MONITOR_H
#define SWAYWATCH_LCM_MONITOR_H

#include <lcm/lcm.h>
#include <stddef.h>
#include <stdint.h>

#include "auth.h"
#include "eventlog.h"
#include "monitor_opts.h"
#include "swaywatch/alarm.h"
#include "swaywatch/engine.h"
#include "swaywatch/gate.h"
#include "swaywatch/risk.h"
#include "swaywatch/scene.h"
#include "swaywatch/stream.h"
#include "swaywatch/units.h"

/* us: a utime is a time since 1970 (or since a sensor's boot) before
 * 2^52 us, September 2112.  Anything else is refused as "time": so any two
 * utimes the monitor works with are less than 2^52 us (143 years) apart,
 * every sum and difference of them is exact in int64 and in double, and
 * no first sample can set the clock so far off that the genuine ones
 * after it cannot be told apart from it. */
#define SW_MON_UTIME_MAX (INT64_C(1) << 52)

/* Why a message on the accel channel was refused. */
typedef enum {
    SW_MON_REJ_DECODE = 0,   /* not an accel_t: wrong fingerprint, or truncated */
    SW_MON_REJ_TRAILING,     /* an accel_t followed by extra bytes */
    SW_MON_REJ_NONFINITE,    /* ax, ay or az is NaN or infinite */
    SW_MON_REJ_IMPLAUSIBLE,  /* |ax|, |ay| or |az| above the plausibility limit */
    SW_MON_REJ_SKEW,         /* utime too far from the wall clock */
    SW_MON_REJ_DUPLICATE,    /* same utime as the last accepted sample */
    SW_MON_REJ_OUT_OF_ORDER, /* utime before the last accepted sample (late) */
    SW_MON_REJ_JUMP,         /* utime far ahead, and the next sample did not follow it */
    SW_MON_REJ_ENGINE,       /* refused by the engine (should not happen) */
    SW_MON_REJ_TIME,         /* utime outside 0 .. SW_MON_UTIME_MAX (1970 to 2112) */
    SW_MON_REJ_OVERLOAD,     /* refused unread: it waited too long in the receive queue
                                (the caller sheds load with sw_mon_refuse) */
    SW_MON_REJ_CONTESTED,    /* from a second sender whose seq numbers interleave with
                                the kept one's (evaluated apart: docs/timing.md) */
    /* with keys (auth.h): */
    SW_MON_REJ_UNAUTHENTICATED, /* no MAC: the old layout (accel_v1_t), or key id 0 */
    SW_MON_REJ_UNKNOWN_KEY,     /* a key id that is not among the keys */
    SW_MON_REJ_BAD_MAC,         /* a MAC that does not match (another key, altered bytes,
                                   another channel) */
    SW_MON_REJ_REPLAYED,        /* authentic but not fresh: a copy of an earlier message */
    SW_MON_NREJ
} sw_mon_reject;

typedef struct {
    long received;              /* messages handed to sw_mon_feed() */
    long accepted;              /* pushed into the engine */
    long held;                  /* samples waiting to be confirmed */
    long rejected[SW_MON_NREJ]; /* received = accepted + sum(rejected) */
    long lost;                  /* samples missing by the sender's seq (dropped on the way) */
    long seq_restarts;          /* seq went back while utime went on: sender restarted */
    long gaps;                  /* sensor gaps (between samples or seen by the timer) */
    long clock_steps;           /* the sensor's clock stepped (utime leapt, time did not) */
    long restarts;              /* utime went back: the sensor restarted */
    long states;                /* state_t messages published */
    long states_withheld;       /* states not published because a value was not finite */
    long alarms;                /* alarm_t messages raised (published if there is an lcm) */
    long alarms_folded;         /* alarms the rate limit held back: each is counted in a
                                   summary that went out ("N more in 1 s, the last: ...");
                                   alarms raised = alarms + alarms_folded */
    long publish_errors;        /* lcm_publish failures */
    long contests;              /* times two timelines competed (INPUT_CONTESTED) */
    long contested;             /* samples of the second timeline, evaluated apart (they
                                   are among the rejected) */
    long auth_contests;         /* with keys: times samples failing authentication began to
                                   arrive (INPUT_CONTESTED) */
    long macs_unchecked;        /* without keys: samples that carried a MAC, not checked */
} sw_mon_counts_t;

typedef struct sw_mon sw_mon_t;

/* Create a monitor for n validated scenes.  eo gives scheme, dt, ... (its
 * callbacks are ignored: the monitor uses its own); out (may be NULL: no
 * publishing) is borrowed, not owned.  NULL on failure with the reason in
 * msg. */
sw_mon_t *sw_mon_create(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo,
                        const sw_mon_opts_t *mo, lcm_t *out, char *msg, size_t msglen);
void sw_mon_destroy(sw_mon_t *m); /* NULL ok */

/* One message from the accel channel.  wall_us: wall clock now (us since
 * 1970, for the skew check; ignored when max_skew is 0); mono: a monotonic
 * clock in s (arrival time: sensor gaps and alarm rate limits).  Returns
 * SW_OK or SW_EVENT when accepted, SW_MON_HELD when held (see above), or a
 * negative status when refused (*why, if not NULL, gets the reason). */
#define SW_MON_HELD 100
int sw_mon_feed(sw_mon_t *m, const void *data, size_t len, int64_t wall_us, double mono,
                sw_mon_reject *why);
/* The same, for a message that came on channel (NULL: opts.accel_channel):
 * with keys, its MAC must cover that channel. */
int sw_mon_feed_on(sw_mon_t *m, const char *channel, const void *data, size_t len, int64_t wall_us,
                   double mono, sw_mon_reject *why);

/* s: samples failing authentication are over (INPUT_CONTESTED, info) when
 * none came for this long. */
#define SW_MON_AUTH_QUIET 2.0

/* New keys (a key file read again; borrowed): the freshness seen under each
 * key id goes on.  SW_OK, or SW_EINVAL for a monitor made without keys or
 * keys NULL (authentication is not turned on or off while it runs). */
int sw_mon_set_keys(sw_mon_t *m, const sw_keyring_t *keys);
/* With keys: what was checked and where refused messages came from (the
 * message's count, its channel and key id); NULL without keys. */
const sw_auth_facts_t *sw_mon_auth_facts(const sw_mon_t *m);

/* Every accel event of an lcm-logger log (eventlog.h) to the end, fed as
 * its messages: lcm-logger's receive time of each is the wall clock (what
 * max_skew compares a sample's utime with: a sample stamped far from
 * when it arrived would otherwise be accepted and make every later one
 * late) and its arrival time.  Returns SW_OK at the end of the log (or
 * when its stop flag ended it); SW_EPARSE (the log's strict: a corrupted
 * region) or SW_ENOTFOUND (the file cannot be read) from
 * sw_lcmlog_next(); with strict, SW_EINVAL at the first sample refused
 * (held ones included).  The caller calls sw_mon_flush() after. */
int sw_mon_feed_log(sw_mon_t *m, sw_lcmlog_t *log, int strict);

/* A message the caller refuses without reading it, for reason r (e.g.
 * SW_MON_REJ_OVERLOAD: it waited in the receive queue for longer than a
 * monitor that must keep up can afford): counted, and raised as
 * INPUT_REJECTED, as any refusal.  mono as for sw_mon_feed().  Returns the
 * negative status of that refusal. */
int sw_mon_refuse(sw_mon_t *m, sw_mon_reject r, double mono);

/* Timers: detects a sensor gap (no sample for longer than the gap
 * threshold since the last one arrived) and publishes rejection summaries
 * that were held back.  Call it when mono reaches sw_mon_deadline(). */
void sw_mon_tick(sw_mon_t *m, double mono);

/* Monotonic time (s) at which sw_mon_tick() next has work; INFINITY if
 * none. */
double sw_mon_deadline(const sw_mon_t *m);

/* End of input: refuse samples still held (nothing confirmed them) and
 * publish rejection summaries still held back. */
void sw_mon_flush(sw_mon_t *m);

/* Replace package k by a new, validated scene (a scene file edited while
 * the monitor runs): its model restarts from rest at the current sample
 * time, with a fresh alarm state; the other packages, the input stream, the
 * counters and the seq numbers of the channels go on untouched.  Allocates.
 * Returns SW_OK, or an error with the reason in msg and the monitor
 * unchanged. */
int sw_mon_replace(sw_mon_t *m, size_t k, const sw_scene_t *scene, char *msg, size_t msglen);

void sw_mon_counts(const sw_mon_t *m, sw_mon_counts_t *c);
long sw_mon_rejected(const sw_mon_counts_t *c); /* sum of rejected[] */
sw_engine_t *sw_mon_engine(sw_mon_t *m);
/* The input stream the monitor drives (its gate, engines, reserve). */
sw_stream_t *sw_mon_stream(sw_mon_t *m);
/* The packages' reserves (risk.h), fed every finite output by the monitor;
 * their events are the caller's to feed (settling spans are a report's
 * matter; the alarms count only significant impacts by themselves). */
sw_risk_t *sw_mon_risk(sw_mon_t *m);
/* The input gate's facts about the stream: duration, intervals, peaks. */
void sw_mon_facts(const sw_mon_t *m, sw_gate_facts_t *f);
int64_t sw_mon_origin(const sw_mon_t *m); /* utime of t = 0 (us), 0 before the first sample */
int64_t sw_mon_last_utime(
    const sw_mon_t *m); /* utime of the last accepted sample (us), 0 if none */

/* "decode", "trailing", "nonfinite", "implausible", "skew", "duplicate",
 * "out_of_order", "jump", "engine", "time", "overload", "contested",
 * "unauthenticated", "unknown_key", "bad_mac", "replayed". */
const char *sw_mon_reject_name(sw_mon_reject r);

/* Axis name "x" | "y" | "z" to 0..2; -1 if none of them. */
int sw_mon_axis_parse(const char *s);

/* CLOCK_MONOTONIC in s: the clock a live caller reads the mono arguments
 * of sw_mon_feed() and sw_mon_tick() from (and sw_mon_deadline() is on). */
double sw_mon_clock(void);

#endif
