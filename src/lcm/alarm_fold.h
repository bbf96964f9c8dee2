/* SPDX-License-Identifier: GPL-3.0-or-later */
/* alarm_fold.h - the monitor's alarm rate limit (journald's
 * RateLimitIntervalSec/RateLimitBurst, per package, plane and kind): within a
 * window of the interval from its first alarm, SW_FOLD_BURST alarms go out
 * and the rest are held back, counted, and go out as one summary when the
 * window ends; an alarm of a higher level than any sent in the window
 * always goes out at once.  A storm of 2,000 MODEL_FAULTs a second is
 * SW_FOLD_BURST alarms and one summary a second.  Internal to
 * libswaywatch_lcm; no I/O: what goes out goes to the emit callback. */
#ifndef SWAYWATCH_ALARM_FOLD_H
#define SWAYWATCH_ALARM_FOLD_H

#include <stddef.h>
#include <stdint.h>

#include "swaywatch/alarm.h"

#define SW_FOLD_BURST 3 /* alarms of a package's plane and kind let through per window */

/* Send alarm a, stamped utime, now. */
typedef void (*sw_fold_emit_fn)(void *user, const sw_alarm_t *a, int64_t utime);

typedef struct sw_fold sw_fold_t;

/* A limit for n packages (and one row for the input's alarms, a->pkg >=
 * n), one window of interval seconds (0: no limit, every alarm goes out);
 * NULL if out of memory. */
sw_fold_t *sw_fold_create(size_t n, double interval, sw_fold_emit_fn emit, void *user);
void sw_fold_destroy(sw_fold_t *f);

/* Alarm a at monotonic time mono (s; not finite during a flush: a fresh
 * start):
 * sent now, or held back.  INPUT_REJECTED is never held here: the monitor
 * folds it per reason before. */
void sw_fold_send(sw_fold_t *f, const sw_alarm_t *a, int64_t utime, double mono);
/* Send the summaries of the windows that ended by mono (all: INFINITY). */
void sw_fold_tick(sw_fold_t *f, double mono);
/* Monotonic time (s) of the earliest pending summary; INFINITY: none. */
double sw_fold_deadline(const sw_fold_t *f);
/* Alarms held back and sent inside a summary so far. */
long sw_fold_folded(const sw_fold_t *f);

#endif
