/* SPDX-License-Identifier: GPL-3.0-or-later */
/* stream.h - one input path: every source's samples go through one
 * stream object, the input gate (gate.h) into the engine (engine.h), each
 * output into the reserve (risk.h) and the alarm logic (alarm.h).  A CSV
 * log, an lcm-logger file and the live monitor each build one and push
 * their samples into it, so what they decide and report is the same by
 * construction; the source keeps only what is its own (reading text or
 * decoding messages, its clock, where it publishes).
 *
 * Push-style, as the engine: the caller owns the loop, pushes samples
 * (sw_sample_t, gate.h) and says when the input ends (sw_stream_finish);
 * the settling after it is asked for apart (sw_stream_settle), since a
 * caller may decide first whether the log deserves a verdict.  What
 * happens comes back through callbacks, in the order it happens:
 *   on_reject  a sample the gate refused, with its reason;
 *   on_input   what happened to the stream: a gap, a clock step, a
 *              restart, stamps reconstructed, a contest begun or ended;
 *   on_take    a sample as the engine got it (a log read once, replayed);
 *   on_event   an engine event (uplift, impact, tip, overturn, ...);
 *   on_alarm   an alarm of a package, with the source's time of it;
 *   on_state   an engine output, once per sample and package, after the
 *              reserve was evaluated on it (sw_risk_pkg() has it) and
 *              after the alarms it raised.
 * Engine events are not fed to the reserve's settling spans: those are
 * a report's matter (sw_risk_event() on sw_stream_risk()).
 *
 * Contested input (receive times only, gate.h): with opts.rival, a
 * second gate and a second set of engines, made at create time, evaluate
 * the second timeline while two compete (from rest at the start of each
 * contest); their alarms from WARN up come through on_alarm, their text
 * beginning "second timeline: ", so that no pattern of forged samples
 * silences an overturn.
 *
 * Memory is fixed at create: pushing allocates nothing.  No I/O, no
 * global state; one thread at a time per stream. */
#ifndef SWAYWATCH_STREAM_H
#define SWAYWATCH_STREAM_H

#include <stddef.h>

#include "alarm.h"
#include "engine.h"
#include "export.h"
#include "gate.h"
#include "risk.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One alarm: a as the alarm module raised it (a->t on the engine's clock),
 * t_source the same instant on the source's clock (sw_gate_source_time()
 * of the gate that timed it), for a caller that stamps alarms with the
 * source's times. */
typedef void (*sw_stream_alarm_fn)(void *user, const sw_alarm_t *a, double t_source);

typedef struct {
    sw_engine_opts_t engine; /* scheme, dt, tolerances, accuracy, check_default; its
                                callbacks and user are not used (the stream's are).  With
                                lateral, the samples carry a_y (the gate is made lateral),
                                the packages with a depth rock across the truck too: their
                                states and events come with plane SW_PLANE_LAT, their
                                reserve is sw_stream_risk_plane's; with on_alarm, each
                                plane has its alarm watch, the lateral one's alarms with
                                plane SW_PLANE_LAT and named so (alarm.h) */
    sw_gate_opts_t gate;     /* the gate's checks and policies; its callbacks and user
                                are not used (the stream's are) */
    sw_risk_opts_t risk;     /* the reserve's rate (< 0: none) and options */
    double hysteresis;       /* 1, margin alarms (alarm.h); < 0 = SW_ALARM_HYSTERESIS */
    int rival;               /* non-zero: evaluate a second timeline while two compete
                                (above); it costs a second gate and set of engines */
    sw_state_fn on_state;    /* each may be NULL */
    sw_event_fn on_event;
    sw_stream_alarm_fn on_alarm; /* NULL: no alarm logic runs */
    sw_gate_event_fn on_input;
    sw_gate_reject_fn on_reject;
    sw_gate_take_fn on_take;
    void *user; /* of every callback */
    /* may be NULL: with lateral, called instead of on_take, with the
     * lateral value too */
    sw_gate_take_lat_fn on_take_lat;
} sw_stream_opts_t;

typedef struct sw_stream sw_stream_t;

/* A stream for n validated scenes.  NULL on failure, with the code in
 * *err (may be NULL) and the reason in msg (may be NULL): SW_EINVAL (bad
 * options, a scene whose alarm levels are not finite), SW_ENOMEM, or the
 * engine's, the gate's or the reserve's error. */
SW_API sw_stream_t *sw_stream_create(const sw_scene_t *scenes, size_t n, const sw_stream_opts_t *o,
                                     int *err, char *msg, size_t msglen);
SW_API void sw_stream_destroy(sw_stream_t *st); /* NULL ok */

/* One sample.  Returns what sw_gate_push() does: SW_OK or SW_EVENT (taken),
 * SW_GATE_HELD (waiting for the stream to confirm it), or a negative
 * status (refused: on_reject said why); SW_EINVAL for NULL. */
SW_API int sw_stream_push(sw_stream_t *st, const sw_sample_t *s);

/* End of the input: the look-ahead is decided, samples nobody confirmed
 * are refused (sw_gate_flush()).  Returns SW_OK (SW_EINVAL for NULL). */
SW_API int sw_stream_finish(sw_stream_t *st);

/* After the end, up to settle s of zero input, until every package is at
 * rest or overturned (sw_engine_finish(); its stop flag ends it early).
 * Nothing after a stream with no sample taken, or settle <= 0.  Returns
 * SW_OK or SW_EVENT. */
SW_API int sw_stream_settle(sw_stream_t *st, double settle);

/* Replace package k by a new, validated scene (a scene file edited while
 * the stream runs): it restarts from rest at the current time with a
 * fresh alarm state, in the second set of engines too; the other
 * packages, the input and its facts go on untouched.  Allocates.  Returns
 * SW_OK; an error with the reason in msg and nothing changed (SW_EINVAL:
 * no such package, alarm levels not finite; the engine's error); or, when
 * the package was replaced but its reserve could not be rebuilt (no
 * memory), the reserve's error, the package going on with the old
 * reserve. */
SW_API int sw_stream_replace(sw_stream_t *st, size_t k, const sw_scene_t *scene, char *msg,
                             size_t msglen);

/* The parts, for reading (summaries, facts, reserves) and for what only
 * the engine offers (sw_engine_set_stop).  Samples go in through
 * sw_stream_push() alone. */
SW_API sw_engine_t *sw_stream_engine(const sw_stream_t *st);
SW_API sw_risk_t *sw_stream_risk(const sw_stream_t *st);
/* The reserve of one plane of package k (sw_risk_pkg of the stream's
 * risk for SW_PLANE_LONG; for SW_PLANE_LAT that of the package's lateral
 * plane, the design pulses applied across the truck); NULL when the
 * package has no such plane, or the lateral plane no reserve. */
SW_API const sw_risk_pkg_t *sw_stream_risk_plane(const sw_stream_t *st, size_t k, sw_plane plane);
/* sw_risk_resolve() of that plane's reserve (risk.h min_only: at the end
 * of the stream, before its minimum is read).  SW_OK also when the
 * package has no such plane or it no reserve. */
SW_API int sw_stream_risk_resolve(sw_stream_t *st, size_t k, sw_plane plane);
SW_API const sw_gate_t *sw_stream_gate(const sw_stream_t *st);
SW_API size_t sw_stream_count(const sw_stream_t *st); /* packages */
/* Package k's name, as its scene says (the replaced one's after
 * sw_stream_replace()); "" for no such package. */
SW_API const char *sw_stream_name(const sw_stream_t *st, size_t k);

#ifdef __cplusplus
}
#endif
#endif
