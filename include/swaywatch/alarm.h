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
 * Input-level alarms (SENSOR_GAP, INPUT_REJECTED) concern the input stream,
 * not a package; the monitor raises them with sw_alarm_input().
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
    SW_ALARM_UPLIFT = 1,         /* a base corner lifted: rocking started (info) */
    SW_ALARM_IMPACT = 2,         /* the other corner landed (info) */
    SW_ALARM_WARN = 3,           /* margin < warn_margin (warn) */
    SW_ALARM_CRITICAL = 4,       /* margin < critical_margin (critical) */
    SW_ALARM_TIP = 5,            /* |theta| reached alpha (critical) */
    SW_ALARM_OVERTURNED = 6,     /* |theta| reached pi/2 (critical) */
    SW_ALARM_REST = 7,           /* back to rest after rocking (info) */
    SW_ALARM_MODEL_FAULT = 8,    /* model fault or non-finite output (critical) */
    SW_ALARM_SENSOR_GAP = 9,     /* input: no samples for too long (warn; info when it ends) */
    SW_ALARM_INPUT_REJECTED = 10 /* input: samples refused (warn) */
} sw_alarm_kind;

typedef enum {
    SW_ALARM_LEVEL_INFO = 0,
    SW_ALARM_LEVEL_WARN = 1,
    SW_ALARM_LEVEL_CRITICAL = 2
} sw_alarm_level;

#define SW_ALARM_TEXT_MAX 128     /* bytes including the NUL, as alarm_t.text */
#define SW_ALARM_HYSTERESIS 0.05  /* 1, default re-arm distance above a threshold */
#define SW_ALARM_ALL ((size_t)-1) /* sw_alarm_t.pkg of input alarms: every package */

typedef struct {
    size_t pkg; /* package index, or SW_ALARM_ALL */
    sw_alarm_kind kind;
    sw_alarm_level level;
    double t;                     /* s, time of the sample (or event) it refers to */
    double theta;                 /* rad; always finite (0 when unknown) */
    double margin;                /* 1; always finite (0 when unknown) */
    char text[SW_ALARM_TEXT_MAX]; /* one line, NUL-terminated */
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
} sw_alarm_watch_t;

/* Set up w for package pkg with the scene's thresholds (1) and a hysteresis
 * (1; < 0 means SW_ALARM_HYSTERESIS).  Returns SW_OK, or SW_EINVAL when a
 * value is not finite. */
SW_API int sw_alarm_init(sw_alarm_watch_t *w, size_t pkg, double warn_margin, double critical_margin,
                  double hysteresis);

/* Feed one engine event of w's package.  Calls emit (may be NULL) with the
 * alarm it maps to; returns the number of alarms raised (0 or 1). */
SW_API int sw_alarm_on_event(sw_alarm_watch_t *w, const sw_event_t *ev, sw_alarm_fn emit, void *user);

/* Feed one engine output (state) of w's package.  Raises WARN / CRITICAL
 * (both, WARN first, when the margin falls below both at once) and
 * MODEL_FAULT when an output value is not finite (once, until the output is
 * finite again).  Returns the number of alarms raised (0..2). */
SW_API int sw_alarm_on_output(sw_alarm_watch_t *w, const sw_output_t *out, sw_alarm_fn emit, void *user);

/* Non-zero when every number of out is finite, i.e. it may be published:
 * sw_output_finite() (engine.h), under the name earlier releases had. */
SW_API int sw_alarm_output_finite(const sw_output_t *out);

/* Fill a with an input-level alarm (pkg = SW_ALARM_ALL, theta = margin =
 * 0) at time t (s); text is copied and truncated to fit. */
SW_API void sw_alarm_input(sw_alarm_t *a, sw_alarm_kind kind, sw_alarm_level level, double t,
                    const char *text);

/* "uplift", "impact", "warn", "critical", "tip", "overturned", "rest",
 * "model_fault", "sensor_gap", "input_rejected"; "unknown" otherwise. */
SW_API const char *sw_alarm_kind_name(sw_alarm_kind k);
/* "info", "warn", "critical"; "unknown" otherwise. */
SW_API const char *sw_alarm_level_name(sw_alarm_level l);

#ifdef __cplusplus
}
#endif
#endif
