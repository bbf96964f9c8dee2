/* SPDX-License-Identifier: GPL-3.0-or-later */
/* risk.h - what a run means to the people watching it, beside the engine:
 * each package's reserve in g (reserve.h) evaluated at a rate on the
 * engine's clock, its minimum and when; the impacts that matter
 * (alarm.h's significance) apart from the micro-impacts of settling, which
 * are folded into settling spans.  replay, forensics, batch and the
 * monitor all read a run through it, so they say the same.
 *
 * Push-style, fed by the caller's engine callbacks: every output
 * (sw_risk_output) and every event (sw_risk_event) of every package, then
 * sw_risk_finish at the end of the stream.  The reserve is evaluated at
 * the first output of a package and then at the first output at or after
 * each multiple of 1/rate s of engine time after it, so a replay's values
 * depend on the log, never on the machine.  A state at rest costs no run
 * (the reserve's cached value).
 *
 * An offline run that needs the minimum alone (min_only) keeps the states
 * due at the rate instead, and evaluates them most threatened first
 * (reserve_log.c, as sw_reserve_log_min) when its buffer is full and at
 * sw_risk_resolve(): the same minimum, at the same state, as evaluating
 * every one, for a fraction of the runs where the minimum stands out.
 *
 * Memory: everything is allocated by sw_risk_create() and
 * sw_risk_replace(); feeding allocates nothing, except in min_only mode a
 * capped reserve each time the smallest value found so far changes (at a
 * full buffer or the resolution).  No I/O, no global state; one thread at
 * a time per object. */
#ifndef SWAYWATCH_RISK_H
#define SWAYWATCH_RISK_H

#include <stddef.h>

#include "alarm.h"
#include "engine.h"
#include "export.h"
#include "reserve.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SW_RISK_RATE 10.0 /* Hz of engine time: the default reserve rate */

#define SW_RISK_MIN_STATES 16384 /* states a min_only package holds before it evaluates them */

typedef struct {
    double reserve_rate;       /* Hz of engine time; 0 = SW_RISK_RATE; < 0 = no reserve */
    sw_reserve_opts_t reserve; /* the reserve's options (reserve.h); zeros: its defaults */
    int min_only;              /* non-zero: no value per state (reserve_g stays NAN), only the
                                  minimum, found by sw_risk_resolve() (offline runs) */
} sw_risk_opts_t;

/* What is known of one package so far. */
typedef struct {
    double reserve_g;        /* g, the latest evaluation; NAN before the first (or off) */
    int direction;           /* sw_reserve_dir of it (0: none needed or none yet) */
    double pulse;            /* s, its design pulse (0: none) */
    double reserve_t;        /* s, time of the state it was evaluated on; NAN: none */
    double min_reserve_g;    /* g, the smallest evaluated; NAN: none */
    double min_reserve_time; /* s, the time of that state; NAN: none */
    int min_direction;       /* sw_reserve_dir of the smallest (0: none) */
    double min_pulse;        /* s, its design pulse (0: none) */
    double rest_reserve_g;   /* g, the reserve at rest (NAN without a reserve) */
    long evaluations;        /* states the reserve was taken at: evaluated (cached ones
                                included) or, min_only, shown no smaller than the minimum */
    long reserve_faults;     /* evaluations in which a run faulted */
    long reserve_runs;       /* reserve searches run (not cached; min_only: full or capped) */
    long impacts;            /* significant impacts (alarm.h) */
    long micro_impacts;      /* impacts below the significance, in settling spans */
    long settling_spans;
    double impact_min;      /* rad/s, the significance used; 0: every impact counts (a
                               cushion has none) */
    const char *no_reserve; /* why the package has no reserve although one was asked
                               for (a scene too stiff, reserve.h's SW_ETOOBIG); NULL when
                               it has one or the rate is off */
} sw_risk_pkg_t;

typedef struct sw_risk sw_risk_t;

/* For n validated scenes (the engine's, in its order).  o may be NULL.
 * NULL on failure with the code in *err (may be NULL) and the reason in
 * msg: SW_EINVAL (a scene that does not validate, bad options), SW_ENOMEM,
 * or a reserve's error.  A scene too stiff for its reserve is no failure:
 * that package has none, and sw_risk_pkg()->no_reserve says why. */
SW_API sw_risk_t *sw_risk_create(const sw_scene_t *scenes, size_t n, const sw_risk_opts_t *o,
                                 int *err, char *msg, size_t msglen);
SW_API void sw_risk_destroy(sw_risk_t *r); /* NULL accepted */

/* One engine output of package out->pkg.  Returns 1 when the reserve was
 * evaluated on it (sw_risk_pkg() has the new value), 0 when not (min_only:
 * never), or a negative status (SW_EINVAL: no such package; min_only: an
 * evaluation's error while the held states were evaluated).  A run that
 * faulted during the evaluation is counted in reserve_faults; the value is
 * then what the other runs found. */
SW_API int sw_risk_output(sw_risk_t *r, const sw_output_t *out);

/* min_only: evaluate package k's states still held, so that its figures
 * hold the minimum (a no-op otherwise, and when nothing is held).  Call it
 * at the end of the stream, before reading the minimum.  SW_OK, or an
 * evaluation's error (SW_ENOMEM, ...). */
SW_API int sw_risk_resolve(sw_risk_t *r, size_t k);

/* One engine event.  Returns SW_SETTLE_REPORT and/or SW_SETTLE_CLOSED as
 * sw_settle_feed() does (alarm.h): a micro-impact is folded into a span
 * (0: not to be reported by itself); a closed span is in *closed. */
SW_API int sw_risk_event(sw_risk_t *r, const sw_event_t *ev, sw_settle_span_t *closed);

/* End of stream for package k: a span still open is closed into *closed
 * (returns 1), else 0. */
SW_API int sw_risk_finish(sw_risk_t *r, size_t k, sw_settle_span_t *closed);

/* Package k's figures (NULL if there is no such package). */
SW_API const sw_risk_pkg_t *sw_risk_pkg(const sw_risk_t *r, size_t k);

/* Package k's scene replaced (a reload): its reserve rebuilt, its figures
 * started again.  Allocates.  SW_OK, or an error with the reason in msg
 * and package k unchanged. */
SW_API int sw_risk_replace(sw_risk_t *r, size_t k, const sw_scene_t *scene, char *msg,
                           size_t msglen);

/* Every package from the start again (the figures; the reserves stay). */
SW_API void sw_risk_reset(sw_risk_t *r);

#ifdef __cplusplus
}
#endif
#endif
