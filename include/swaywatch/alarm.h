/* SPDX-License-Identifier: GPL-3.0-or-later */
/* alarm.h - turns one package's engine outputs and events into alarms.
 *
 * Pure logic, no I/O: the caller feeds every event (sw_event_fn) and every
 * state (sw_state_fn) of a package to that package's sw_alarm_watch_t, and
 * gets alarms back through a callback, in the order they happen.
 *
 * Margin alarms (WARN, CRITICAL) use hysteresis: an alarm is raised when the
 * margin falls below the threshold, and the threshold re-arms only once the
 * margin has risen above threshold + hysteresis.  A margin hovering at the
 * threshold therefore raises one alarm, not one per crossing.  The margin is
 * sw_output_t.margin (physics.md), the one published in every state.
 *
 * Reserve alarms (RESERVE_WARN, RESERVE_CRITICAL) do the same on the
 * reserve in g (reserve.h), fed by sw_alarm_on_reserve() whenever the
 * reserve is evaluated: raised when it falls below a level, re-armed above
 * level + hysteresis.  docs/alarms.md gives the lead times they buy.
 *
 * Impacts: with an impact significance set (sw_alarm_set_impact_min), an
 * impact slower than it raises no IMPACT alarm; sw_settle_t folds such
 * micro-impacts into one "settling" span for reports.
 *
 * Input-level alarms (SENSOR_GAP, INPUT_REJECTED, INPUT_CONTESTED) concern
 * the input stream, not a package; the monitor raises them with
 * sw_alarm_input().
 *
 * The kind and level values are those of the LCM type swaywatch.alarm_t
 * (lcmtypes/alarm_t.lcm), so they can be copied across unchanged. */
#ifndef SWAYWATCH_ALARM_H
#define SWAYWATCH_ALARM_H

#include <stddef.h>

#include "engine.h"
#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    SW_ALARM_UPLIFT = 1,            /* a base corner lifted: rocking started (info) */
    SW_ALARM_IMPACT = 2,            /* the other corner landed (info) */
    SW_ALARM_WARN = 3,              /* margin < warn_margin (warn) */
    SW_ALARM_CRITICAL = 4,          /* margin < critical_margin (critical) */
    SW_ALARM_TIP = 5,               /* |theta| reached alpha (critical) */
    SW_ALARM_OVERTURNED = 6,        /* |theta| reached pi/2 (critical) */
    SW_ALARM_REST = 7,              /* back to rest after rocking (info) */
    SW_ALARM_MODEL_FAULT = 8,       /* model fault or non-finite output (critical) */
    SW_ALARM_SENSOR_GAP = 9,        /* input: no samples for too long (warn; info when it ends) */
    SW_ALARM_INPUT_REJECTED = 10,   /* input: samples refused (warn) */
    SW_ALARM_RESERVE_WARN = 11,     /* reserve < warn_reserve_g (warn) */
    SW_ALARM_RESERVE_CRITICAL = 12, /* reserve < critical_reserve_g (critical) */
    SW_ALARM_INPUT_CONTESTED = 13   /* input: two timelines compete (critical; info when
                                       it ends): a forged or duplicated sender */
} sw_alarm_kind;

typedef enum {
    SW_ALARM_LEVEL_INFO = 0,
    SW_ALARM_LEVEL_WARN = 1,
    SW_ALARM_LEVEL_CRITICAL = 2
} sw_alarm_level;

#define SW_ALARM_TEXT_MAX 128              /* bytes including the NUL, as alarm_t.text */
#define SW_ALARM_HYSTERESIS 0.05           /* 1, default re-arm distance above a threshold */
#define SW_ALARM_RESERVE_HYSTERESIS_G 0.02 /* g, the same for reserve levels (docs/alarms.md) */
#define SW_IMPACT_SIGNIFICANCE 0.1         /* 1, default fraction of the tipping speed (below) */
#define SW_ALARM_ALL ((size_t)-1)          /* sw_alarm_t.pkg of input alarms: every package */

typedef struct {
    size_t pkg; /* package index, or SW_ALARM_ALL */
    sw_alarm_kind kind;
    sw_alarm_level level;
    double t;                     /* s, time of the sample (or event) it refers to */
    double theta;                 /* rad; always finite (0 when unknown) */
    double margin;                /* 1; always finite (0 when unknown) */
    char text[SW_ALARM_TEXT_MAX]; /* one line, NUL-terminated */
    sw_plane plane;               /* the package's plane it concerns (its watch's,
                                     sw_alarm_set_plane); SW_PLANE_LONG for input alarms */
} sw_alarm_t;

typedef void (*sw_alarm_fn)(void *user, const sw_alarm_t *a);

/* Per-package alarm state; caller-allocated, set up by sw_alarm_init(). */
typedef struct {
    size_t pkg;
    double warn_margin;     /* 1 */
    double critical_margin; /* 1 */
    double hysteresis;      /* 1 */
    int warn_armed;         /* non-zero: the next fall below warn_margin raises WARN */
    int critical_armed;
    int fault_armed; /* non-zero: the next non-finite output raises MODEL_FAULT */
    long raised;     /* alarms raised so far */
    /* reserve levels, g (SW_G0); 0 = reserve alarms off (sw_alarm_init) */
    double warn_reserve_g, critical_reserve_g, reserve_hysteresis_g;
    int reserve_warn_armed, reserve_critical_armed;
    double impact_min; /* rad/s: slower impacts raise no IMPACT alarm; 0 = every impact */
    sw_plane plane;    /* the plane watched: SW_PLANE_LONG, unless sw_alarm_set_plane */
} sw_alarm_watch_t;

/* Set up w for package pkg with the scene's thresholds (1) and a hysteresis
 * (1; < 0 means SW_ALARM_HYSTERESIS).  Returns SW_OK, or SW_EINVAL when a
 * value is not finite. */
SW_API int sw_alarm_init(sw_alarm_watch_t *w, size_t pkg, double warn_margin,
                         double critical_margin, double hysteresis);

/* Set up w from a validated scene: its margin and reserve levels, and
 * impact significance SW_IMPACT_SIGNIFICANCE of the package's tipping
 * speed (sw_impact_tip_speed; none on a cushion, where nothing impacts).
 * hysteresis < 0: SW_ALARM_HYSTERESIS; the reserve's is
 * SW_ALARM_RESERVE_HYSTERESIS_G.  Returns SW_OK, or SW_EINVAL for a scene
 * that does not validate. */
SW_API int sw_alarm_init_scene(sw_alarm_watch_t *w, size_t pkg, const sw_scene_t *sc,
                               double hysteresis);

/* Reserve levels (g): warn_g 0 turns reserve alarms off; otherwise
 * 0 < critical_g < warn_g, hysteresis_g >= 0 (< 0: the default).  Re-arms
 * both.  Returns SW_OK or SW_EINVAL. */
SW_API int sw_alarm_set_reserve(sw_alarm_watch_t *w, double warn_g, double critical_g,
                                double hysteresis_g);

/* The plane w watches (sw_alarm_init: SW_PLANE_LONG).  A lateral plane's
 * alarms carry it and say so in their text ("overturned sideways",
 * "margin sideways 0.430 < warn 0.500"), so that no reader takes them for
 * the plane along the truck.  Set it up from the lateral scene
 * (sw_scene_lateral) with sw_alarm_init_scene first.  SW_OK or SW_EINVAL. */
SW_API int sw_alarm_set_plane(sw_alarm_watch_t *w, sw_plane plane);

/* Impacts slower than min_speed (rad/s, |theta_dot| before the impact)
 * raise no IMPACT alarm; 0 restores one per impact.  SW_OK or SW_EINVAL. */
SW_API int sw_alarm_set_impact_min(sw_alarm_watch_t *w, double min_speed);

/* Feed one engine event of w's package.  Calls emit (may be NULL) with the
 * alarm it maps to; returns the number of alarms raised (0 or 1: 0 for an
 * impact below the significance). */
SW_API int sw_alarm_on_event(sw_alarm_watch_t *w, const sw_event_t *ev, sw_alarm_fn emit,
                             void *user);

/* Feed one engine output (state) of w's package.  Raises WARN / CRITICAL
 * (both, WARN first, when the margin falls below both at once) and
 * MODEL_FAULT when an output value is not finite (once, until the output is
 * finite again).  Returns the number of alarms raised (0..2). */
SW_API int sw_alarm_on_output(sw_alarm_watch_t *w, const sw_output_t *out, sw_alarm_fn emit,
                              void *user);

/* Feed one evaluation of the reserve (g) at time t (s), with the theta
 * (rad) and margin (1) of the state it was evaluated on, for the alarm's
 * record.  Raises RESERVE_WARN / RESERVE_CRITICAL (both, WARN first, when
 * it falls below both at once) with hysteresis.  A NaN reserve neither
 * raises nor re-arms.  Returns the number of alarms raised (0..2). */
SW_API int sw_alarm_on_reserve(sw_alarm_watch_t *w, double t, double theta, double margin,
                               double reserve_g, sw_alarm_fn emit, void *user);

/* Non-zero when every number of out is finite, i.e. it may be published:
 * sw_output_finite() (engine.h), under the name earlier releases had. */
SW_API int sw_alarm_output_finite(const sw_output_t *out);

/* Fill a with an input-level alarm (pkg = SW_ALARM_ALL, theta = margin =
 * 0) at time t (s); text is copied and truncated to fit. */
SW_API void sw_alarm_input(sw_alarm_t *a, sw_alarm_kind kind, sw_alarm_level level, double t,
                           const char *text);

/* "uplift", "impact", "warn", "critical", "tip", "overturned", "rest",
 * "model_fault", "sensor_gap", "input_rejected", "reserve_warn",
 * "reserve_critical", "input_contested"; "unknown" otherwise. */
SW_API const char *sw_alarm_kind_name(sw_alarm_kind k);
/* "info", "warn", "critical"; "unknown" otherwise. */
SW_API const char *sw_alarm_level_name(sw_alarm_level l);

/* ---- margins and impacts that read right ---------------------------------- */

/* The tipping speed (rad/s): the angular velocity that carries a package
 * standing upright just to |theta| = alpha, 2 p sin(alpha/2) (its kinetic
 * energy is the barrier m g R (1 - cos alpha)).  An impact at f times it
 * ends a swing that held f^2 of the barrier energy; with the default
 * f = SW_IMPACT_SIGNIFICANCE, 1 %, i.e. a swing to about 0.5 % of alpha.
 * g in m/s^2 (the scene's).  0 on a cushion (no impacts). */
SW_API double sw_impact_tip_speed(const sw_derived_t *d, double g);

/* Non-zero if an impact at theta_dot_before (rad/s, the event's info) is
 * significant: |theta_dot_before| >= fraction * sw_impact_tip_speed(). */
SW_API int sw_impact_significant(const sw_derived_t *d, double g, double theta_dot_before,
                                 double fraction);

/* The margin as presented (plots, summaries, dashboards): within [-1, 1]
 * and monotone in the margin.  margin >= 0 is shown as it is (1 at rest,
 * 0 at the edge beyond which free motion overturns the package); a
 * negative margin, which runs to large negative values while the package
 * falls (the bare block's PE - KE - 1 is about -11 at pi/2 with no speed),
 * is shown as expm1(margin) in (-1, 0); an overturned package is -1.  So a
 * falling package approaches -1 and the overturn reads -1: no step back
 * up.  NaN stays NaN. */
SW_API double sw_margin_presented(double margin, sw_phase phase);

/* Settling spans: the cascade of micro-impacts at the end of a sway,
 * reported as one span instead of one line (and one alarm) per impact. */
typedef struct {
    double t_start, t_end; /* s: the first and last micro-impact */
    long impacts;          /* micro-impacts in the span */
    double max_speed;      /* rad/s, the fastest of them (|theta_dot| before) */
} sw_settle_span_t;

typedef struct {
    double min_speed; /* rad/s, significance: slower impacts are micro-impacts */
    int open;         /* a span is open */
    sw_settle_span_t span;
} sw_settle_t;

/* min_speed > 0 (rad/s), e.g. SW_IMPACT_SIGNIFICANCE * sw_impact_tip_speed(). */
SW_API void sw_settle_init(sw_settle_t *s, double min_speed);

#define SW_SETTLE_REPORT 1 /* report ev as usual */
#define SW_SETTLE_CLOSED 2 /* a span ended before ev: *closed holds it; report it first */

/* Feed every event of one package in order.  A micro-impact opens a span
 * or joins the open one and is not to be reported (returns 0); any other
 * event closes an open span first (SW_SETTLE_CLOSED, with *closed filled)
 * and is to be reported (SW_SETTLE_REPORT).  closed may be NULL. */
SW_API int sw_settle_feed(sw_settle_t *s, const sw_event_t *ev, sw_settle_span_t *closed);

/* End of stream: close an open span into *closed; returns 1 if there was
 * one, else 0. */
SW_API int sw_settle_finish(sw_settle_t *s, sw_settle_span_t *closed);

#ifdef __cplusplus
}
#endif
#endif
