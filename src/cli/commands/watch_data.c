/* SPDX-License-Identifier: GPL-3.0-or-later */
/* watch_data.c - what "swaywatch watch" has seen on the bus: the state
 * and alarm subscriptions (raw, decoded here), per package the last state
 * and its rate, alpha from its scene or its states, and the input's
 * health: states and alarms lost (their seq), the monitor's refusals and
 * sensor gaps, the rate and lag of the states. */
#include <lcm/lcm.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "monitor.h"
#include "opts.h"
#include "text.h"
#include "watch.h"

double sw_watch_mono_now(void)
{
    return sw_mon_clock();
}

int64_t sw_watch_wall_now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* An int8_t[cap] text of a message as a C string: NUL-terminated, control
 * characters as '?'. */
void sw_watch_msg_text(char *dst, const int8_t *src, size_t cap)
{
    sw_cli_term_text(dst, cap, (const char *)src, cap);
}

/* Messages lost between last and seq (the publisher's counter); a seq at or
 * before last is a publisher that started again. */
static void count_seq(int64_t seq, int64_t *last, int *have, long *lost, long *restarts)
{
    if (*have) {
        if (seq <= *last) {
            (*restarts)++;
        } else {
            unsigned long long d = (unsigned long long)seq - (unsigned long long)*last - 1;
            *lost += d > (unsigned long long)(LONG_MAX / 2) ? LONG_MAX / 2 : (long)d;
            if (*lost > LONG_MAX / 2)
                *lost = LONG_MAX / 2;
        }
    }
    *last = seq;
    *have = 1;
}

/* The row of a package's plane (a plane that is neither is shown as the
 * lateral one's: it is not the plane along the truck). */
static pkg_view_t *find_pkg(watch_t *w, const char *name, int plane)
{
    plane = plane == SWAYWATCH_STATE_T_PLANE_LONGITUDINAL ? plane : SWAYWATCH_STATE_T_PLANE_LATERAL;
    for (size_t i = 0; i < w->npkg; i++)
        if (w->pkg[i].plane == plane && !strcmp(w->pkg[i].name, name))
            return &w->pkg[i];
    if (w->npkg == MAX_PKG)
        return NULL;
    pkg_view_t *p = &w->pkg[w->npkg++];
    memset(p, 0, sizeof *p);
    snprintf(p->name, sizeof p->name, "%s", name);
    p->plane = plane;
    p->alpha = NAN;
    p->rate = NAN;
    for (size_t k = 0; k < w->nscenes; k++)
        if (!strcmp(w->scenes[k].name, name)) {
            p->alpha = plane == SWAYWATCH_STATE_T_PLANE_LATERAL && w->scene_alpha_lat
                           ? w->scene_alpha_lat[k]
                           : w->scene_alpha[k];
            p->alpha_from = isfinite(p->alpha) ? 1 : 0;
        }
    return p;
}

/* alpha of a bare package from one of its states: uplift_ratio =
 * |a_g| / (g tan alpha).  Only from a state that says enough. */
static void infer_alpha(pkg_view_t *p, const swaywatch_state_t *s)
{
    if (p->alpha_from == 1 || s->model != SWAYWATCH_STATE_T_MODEL_BARE)
        return;
    if (!(s->uplift_ratio > 1e-3) || !(fabs(s->a_g) > 1e-2) || !isfinite(s->a_g))
        return;
    double a = atan(fabs(s->a_g) / (SW_G0 * s->uplift_ratio));
    if (isfinite(a) && a > 0.0 && a < M_PI_2) {
        p->alpha = a;
        p->alpha_from = 2;
    }
}

static void on_state(const lcm_recv_buf_t *rb, const char *channel, void *user)
{
    (void)channel;
    watch_t *w = user;
    swaywatch_state_t s;
    if (rb->data_size > INT32_MAX ||
        swaywatch_state_t_decode(rb->data, 0, (int)rb->data_size, &s) != (int)rb->data_size) {
        w->undecodable++;
        return;
    }
    const double now = sw_watch_mono_now();
    w->states++;
    count_seq(s.seq, &w->state_seq, &w->have_state_seq, &w->lost_states, &w->seq_restarts);
    char name[SW_NAME_MAX];
    sw_watch_msg_text(name, s.name, sizeof s.name);
    pkg_view_t *p = find_pkg(w, name, s.plane);
    if (!p) {
        w->pkg_overflow++;
        return;
    }
    p->last = s;
    p->rx = now;
    p->win++;
    infer_alpha(p, &s);
    if (p->alpha_from && isfinite(s.theta)) {
        double r = fabs(s.theta) / p->alpha;
        if (r > p->peak)
            p->peak = r;
    }
    w->last_rx = now;
    w->gap_open = 0;
    w->win_states++;
    /* in double: a hostile utime (INT64_MIN) must not overflow */
    w->win_lag_sum += ((double)sw_watch_wall_now_us() - (double)s.utime) / 1e6;
}

/* "... rejected: REASON (N so far)": the monitor's count of that reason. */
static void count_rejected(watch_t *w, const char *text)
{
    const char *p = strstr(text, "rejected: ");
    char reason[24];
    long n;
    if (!p || sscanf(p + 10, "%23[a-z_] (%ld so far)", reason, &n) != 2)
        snprintf(reason, sizeof reason, "other"), n = -1;
    size_t i = 0;
    while (i < w->nreasons && strcmp(w->reason[i].name, reason)) i++;
    if (i == w->nreasons) {
        if (w->nreasons == MAX_REASONS)
            i = MAX_REASONS - 1; /* the rest are told together */
        else
            snprintf(w->reason[w->nreasons++].name, sizeof w->reason[0].name, "%s", reason);
    }
    /* The count the alarm states, or one more for an alarm that states none. */
    w->reason[i].so_far =
        n >= 0 ? (n > w->reason[i].so_far ? n : w->reason[i].so_far) : w->reason[i].so_far + 1;
}

static void on_alarm(const lcm_recv_buf_t *rb, const char *channel, void *user)
{
    (void)channel;
    watch_t *w = user;
    swaywatch_alarm_t a;
    if (rb->data_size > INT32_MAX ||
        swaywatch_alarm_t_decode(rb->data, 0, (int)rb->data_size, &a) != (int)rb->data_size) {
        w->undecodable++;
        return;
    }
    w->alarms++;
    long restarts = 0;
    count_seq(a.seq, &w->alarm_seq, &w->have_alarm_seq, &w->lost_alarms, &restarts);
    w->ring[w->ring_next] = (alarm_view_t){.wall_us = sw_watch_wall_now_us(), .a = a};
    w->ring_next = (w->ring_next + 1) % (size_t)w->o->alarms;
    if (w->ring_n < (size_t)w->o->alarms)
        w->ring_n++;
    char text[sizeof a.text];
    sw_watch_msg_text(text, a.text, sizeof a.text);
    if (a.kind == SWAYWATCH_ALARM_T_KIND_INPUT_REJECTED)
        count_rejected(w, text);
    if (a.kind == SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED) {
        if (a.level >= SWAYWATCH_ALARM_T_LEVEL_CRITICAL)
            w->contests++;
        w->contest_open = a.level >= SWAYWATCH_ALARM_T_LEVEL_CRITICAL;
    }
    if (a.kind == SWAYWATCH_ALARM_T_KIND_SENSOR_GAP) {
        if (a.level >= SWAYWATCH_ALARM_T_LEVEL_WARN) {
            w->gaps++;
            w->gap_open = !strncmp(text, "no accel sample", 15);
        } else {
            w->gap_open = 0;
        }
    }
}

/* Close the rate and lag window once a second. */
void sw_watch_window(watch_t *w, double now)
{
    double span = now - w->win_start;
    if (span < 1.0)
        return;
    w->rate = (double)w->win_states / span;
    w->lag = w->win_states ? w->win_lag_sum / (double)w->win_states : NAN;
    for (size_t i = 0; i < w->npkg; i++) {
        w->pkg[i].rate = (double)w->pkg[i].win / span;
        w->pkg[i].win = 0;
    }
    w->win_states = 0;
    w->win_lag_sum = 0.0;
    w->win_start = now;
}

int sw_watch_subscribe(lcm_t *lcm, watch_t *w, lcm_subscription_t **s1, lcm_subscription_t **s2)
{
    *s1 = lcm_subscribe(lcm, w->o->state_channel, on_state, w);
    *s2 = lcm_subscribe(lcm, w->o->alarm_channel, on_alarm, w);
    if (!*s1 || !*s2) {
        sw_cli_error("watch: cannot subscribe to %s and %s", w->o->state_channel,
                     w->o->alarm_channel);
        return SW_EXIT_IO;
    }
    lcm_subscription_set_queue_capacity(*s1, STATE_QUEUE);
    lcm_subscription_set_queue_capacity(*s2, 1000);
    return SW_EXIT_OK;
}
