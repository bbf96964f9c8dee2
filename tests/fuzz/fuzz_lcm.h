/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_lcm.h - what the targets that run a publishing monitor share
 * (fuzz_accel.c, fuzz_feed.c): one memq:// instance for the whole process,
 * and the checks of every state_t and alarm_t published on it.
 *
 * The instance is made at the first input and never destroyed.  Made per
 * input, it cost more than the rest of a short one, and liblcm 1.3.1 leaks
 * the mutex its first lcm_handle() creates (56 bytes per lcm_t): every
 * input then ended with more allocations than frees, which makes libFuzzer
 * run LeakSanitizer's whole-heap scan after it (half the time of those
 * targets went there).  GLib's slice allocator is told to use malloc, so
 * that what an input allocates through LCM it frees, counted as such.  An
 * input leaves nothing queued: each drains the queue before it ends. */
#ifndef SW_FUZZ_LCM_H
#define SW_FUZZ_LCM_H

#include <lcm/lcm.h>

#include "fuzz.h"
#include "monitor.h"
#include "swaywatch_alarm_t.h"
#include "swaywatch_state_t.h"

typedef struct {
    long states, alarms;
} fz_seen_t;

static fz_seen_t fz_seen; /* this input's messages */

static void fz_on_state_msg(const lcm_recv_buf_t *rb, const char *ch, void *user)
{
    (void)ch, (void)user;
    swaywatch_state_t m;
    FZ_CHECK(swaywatch_state_t_decode(rb->data, 0, (int)rb->data_size, &m) == (int)rb->data_size);
    const double v[] = {m.theta,        m.theta_dot,    m.u,  m.z_b, m.margin,
                        m.margin_bound, m.uplift_ratio, m.a_g};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) FZ_CHECK(isfinite(v[i]));
    FZ_CHECK(fabs(m.theta) <= M_PI_2 + 1e-6);
    FZ_CHECK(memchr(m.name, 0, sizeof m.name) != NULL);
    fz_seen.states++;
}

static void fz_on_alarm_msg(const lcm_recv_buf_t *rb, const char *ch, void *user)
{
    (void)ch, (void)user;
    swaywatch_alarm_t m;
    FZ_CHECK(swaywatch_alarm_t_decode(rb->data, 0, (int)rb->data_size, &m) == (int)rb->data_size);
    FZ_CHECK(isfinite(m.theta) && isfinite(m.margin));
    FZ_CHECK(memchr(m.text, 0, sizeof m.text) != NULL);
    fz_seen.alarms++;
}

/* Hands every queued message to its handler. */
static inline void fz_lcm_drain(lcm_t *lcm)
{
    while (lcm_handle_timeout(lcm, 0) > 0) {
    }
}

/* The process's instance, subscribed to the monitor's state and alarm
 * channels, with this input's counts set to zero. */
static inline lcm_t *fz_lcm(void)
{
    static lcm_t *lcm;
    if (!lcm) {
        setenv("G_SLICE", "always-malloc", 0);
        lcm = lcm_create("memq://");
        FZ_CHECK(lcm != NULL);
        FZ_CHECK(lcm_subscribe(lcm, SW_MON_STATE_CHANNEL, fz_on_state_msg, NULL) != NULL);
        FZ_CHECK(lcm_subscribe(lcm, SW_MON_ALARM_CHANNEL, fz_on_alarm_msg, NULL) != NULL);
        /* the mutex liblcm makes at the first message handled, made now */
        FZ_CHECK(lcm_publish(lcm, "FUZZ_WARM_UP", "", 0) == 0);
        fz_lcm_drain(lcm);
    }
    memset(&fz_seen, 0, sizeof fz_seen);
    return lcm;
}

#endif
