/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sched.h - a rate on an engine's clock, as the reserve is taken (risk.c,
 * reserve_log.c): due at the first output, then at the first output at or
 * after each multiple of the period after it, so that what is taken
 * depends on the log, never on the machine.  Internal. */
#ifndef SWAYWATCH_SCHED_H
#define SWAYWATCH_SCHED_H

#include <math.h>

typedef struct {
    double next;   /* s of engine time: due at or after it; NAN: at the next output */
    double origin; /* s, time of the first output of the schedule */
    double m;      /* periods since origin: next = origin + m period (a product, not a
                      sum: no drift over hours) */
} sw_sched_t;

static inline void sw_sched_reset(sw_sched_t *s)
{
    s->next = NAN;
}

/* Is an output at t (s) due, for period (s)?  If so the schedule moves on
 * to the next multiple of the period after t (after a gap, the first one
 * past it).  A clock that went back (an engine restarted) starts afresh. */
static inline int sw_sched_due(sw_sched_t *s, double t, double period)
{
    if (!isnan(s->next) && t < s->next - period)
        s->next = NAN;
    if (!isnan(s->next) && t < s->next)
        return 0;
    if (isnan(s->next)) {
        s->origin = t;
        s->m = 0.0;
    }
    s->m = fmax(s->m + 1.0, floor((t - s->origin) / period) + 1.0);
    s->next = s->origin + s->m * period;
    return 1;
}

#endif
