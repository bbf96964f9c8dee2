/* SPDX-License-Identifier: GPL-3.0-or-later */
/* alarm_listener.c - a downstream consumer of `swaywatch monitor`: it
 * subscribes to the alarm channel and prints every alarm, one line each,
 * stamped with the time of the sample it refers to (ISO 8601, UTC, to the
 * millisecond) and marked "sideways" for the lateral plane of a package
 * with a depth, and tells when alarms were lost on the way (by the
 * publisher's seq).
 *
 * Build with the generated C types, installed beside the LCM definitions
 * (share/swaywatch/lcmtypes/c; or made with 'lcm-gen -c alarm_t.lcm'),
 * from any folder (tests/package checks this line as it is installed):
 *     T=/usr/share/swaywatch/lcmtypes/c
 *     cc -o alarm_listener /usr/share/doc/swaywatch/examples/alarm_listener.c \
 *         $T/swaywatch_alarm_t.c -I$T -llcm
 * (/usr/local for a build installed with 'cmake --install').
 *
 * usage: alarm_listener [-l URL] [-c CHANNEL] [-n COUNT] [-t SECONDS]
 *   -l URL      LCM URL (default: $LCM_DEFAULT_URL, else LCM's default)
 *   -c CHANNEL  alarm channel (default SWAY_ALARM)
 *   -n COUNT    exit after COUNT alarms (default: run until SIGINT/SIGTERM)
 *   -t SECONDS  exit when no alarm came for SECONDS (default: never)
 * Exit status: 0, or 1 if LCM could not be set up, 2 on bad usage. */
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700 /* getopt, sigaction */
#endif
#include <inttypes.h>
#include <lcm/lcm.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "swaywatch_alarm_t.h"

static volatile sig_atomic_t stop;

static void on_signal(int sig)
{
    (void)sig;
    stop = 1;
}

typedef struct {
    long received, lost;
    int64_t last_seq;
} listener_t;

/* The kind's name, from the generated constants; a kind this program was
 * built before (alarm_t only ever gains kinds) by its number. */
static const char *kind_name(int k, char *buf, size_t size)
{
    switch (k) {
        case SWAYWATCH_ALARM_T_KIND_UPLIFT: return "UPLIFT";
        case SWAYWATCH_ALARM_T_KIND_IMPACT: return "IMPACT";
        case SWAYWATCH_ALARM_T_KIND_WARN: return "WARN";
        case SWAYWATCH_ALARM_T_KIND_CRITICAL: return "CRITICAL";
        case SWAYWATCH_ALARM_T_KIND_TIP: return "TIP";
        case SWAYWATCH_ALARM_T_KIND_OVERTURNED: return "OVERTURNED";
        case SWAYWATCH_ALARM_T_KIND_REST: return "REST";
        case SWAYWATCH_ALARM_T_KIND_MODEL_FAULT: return "MODEL_FAULT";
        case SWAYWATCH_ALARM_T_KIND_SENSOR_GAP: return "SENSOR_GAP";
        case SWAYWATCH_ALARM_T_KIND_INPUT_REJECTED: return "INPUT_REJECTED";
        case SWAYWATCH_ALARM_T_KIND_RESERVE_WARN: return "RESERVE_WARN";
        case SWAYWATCH_ALARM_T_KIND_RESERVE_CRITICAL: return "RESERVE_CRITICAL";
        case SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED: return "INPUT_CONTESTED";
        default: snprintf(buf, size, "KIND_%d", k); return buf;
    }
}

/* A NUL-padded text of the message as a C string for the terminal: a
 * control byte (an escape sequence a hostile sender put there) as '?'. */
static void clean(char *dst, const int8_t *src, size_t cap)
{
    size_t i = 0;
    for (; i < cap && src[i]; i++) {
        const unsigned char c = (unsigned char)src[i];
        dst[i] = c < 0x20 || c == 0x7f ? '?' : (char)c;
    }
    dst[i] = '\0';
}

static const char *level_name(int l)
{
    switch (l) {
        case SWAYWATCH_ALARM_T_LEVEL_INFO: return "info";
        case SWAYWATCH_ALARM_T_LEVEL_WARN: return "warn";
        case SWAYWATCH_ALARM_T_LEVEL_CRITICAL: return "CRITICAL";
        default: return "?";
    }
}

/* utime (microseconds since the epoch, UTC) as "2026-11-24T15:40:12.345Z";
 * the raw number if the system cannot convert it. */
static const char *iso_time(int64_t utime, char *buf, size_t size)
{
    int64_t sec = utime / 1000000, us = utime % 1000000;
    if (us < 0) { /* before 1970: round the seconds down */
        us += 1000000;
        sec -= 1;
    }
    time_t t = (time_t)sec;
    struct tm tm;
    size_t n = gmtime_r(&t, &tm) ? strftime(buf, size, "%Y-%m-%dT%H:%M:%S", &tm) : 0;
    if (n == 0)
        snprintf(buf, size, "utime %" PRId64, utime);
    else
        snprintf(buf + n, size - n, ".%03dZ", (int)(us / 1000));
    return buf;
}

static void on_alarm(const lcm_recv_buf_t *rbuf, const char *channel, const swaywatch_alarm_t *a,
                     void *user)
{
    (void)rbuf;
    (void)channel;
    listener_t *L = user;
    /* The texts are fixed arrays, NUL-padded; copied to be sure of the
     * terminating NUL whatever the sender put there. */
    char name[sizeof a->name + 1], text[sizeof a->text + 1], kind[24];
    clean(name, a->name, sizeof a->name);
    clean(text, a->text, sizeof a->text);

    if (L->received > 0 && a->seq > L->last_seq + 1)
        L->lost += (long)(a->seq - L->last_seq - 1);
    L->last_seq = a->seq;
    L->received++;
    char when[48];
    printf("%s seq %" PRId64 " %-8s %-16s %-12s%s theta %+.4f margin %+.3f  %s\n",
           iso_time(a->utime, when, sizeof when), a->seq, level_name(a->level),
           kind_name(a->kind, kind, sizeof kind), name[0] ? name : "(input)",
           a->plane == SWAYWATCH_ALARM_T_PLANE_LATERAL ? " sideways" : "", a->theta, a->margin,
           text);
    fflush(stdout);
}

int main(int argc, char **argv)
{
    const char *url = NULL, *channel = "SWAY_ALARM";
    long count = 0;
    double idle = 0.0;
    for (int c; (c = getopt(argc, argv, "l:c:n:t:h")) != -1;) {
        switch (c) {
            case 'l': url = optarg; break;
            case 'c': channel = optarg; break;
            case 'n': count = strtol(optarg, NULL, 10); break;
            case 't': idle = strtod(optarg, NULL); break;
            case 'h':
                printf("usage: alarm_listener [-l URL] [-c CHANNEL] [-n COUNT] [-t SECONDS]\n");
                return 0;
            default: return 2;
        }
    }
    lcm_t *lcm = lcm_create(url);
    if (!lcm) {
        fprintf(stderr, "alarm_listener: cannot set up LCM (%s)\n", url ? url : "default URL");
        return 1;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    listener_t L = {0};
    swaywatch_alarm_t_subscription_t *sub = swaywatch_alarm_t_subscribe(lcm, channel, on_alarm, &L);
    /* Alarms come in bursts (an impact cascade): keep them all. */
    swaywatch_alarm_t_subscription_set_queue_capacity(sub, 0);
    fprintf(stderr, "alarm_listener: listening on %s\n", channel);

    /* Wait in slices of 100 ms so that signals and the idle limit are seen. */
    double waited = 0.0;
    while (!stop && (count <= 0 || L.received < count) && (idle <= 0.0 || waited < idle)) {
        int r = lcm_handle_timeout(lcm, 100);
        if (r < 0)
            break;
        waited = r > 0 ? 0.0 : waited + 0.1;
    }
    fprintf(stderr, "alarm_listener: %ld alarms, %ld lost\n", L.received, L.lost);
    swaywatch_alarm_t_unsubscribe(lcm, sub);
    lcm_destroy(lcm);
    return 0;
}
