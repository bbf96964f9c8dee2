/* SPDX-License-Identifier: GPL-3.0-or-later */
/* watch.h - what the files of "swaywatch watch" share: what has been seen
 * on the bus (watch_data.c: the subscriptions, the states and alarms
 * decoded and counted), and its view (watch_view.c: lines of text, on the
 * screen or as plain snapshots); cmd_watch.c holds the options, the loop
 * and the command. */
#ifndef SWAYWATCH_CLI_WATCH_H
#define SWAYWATCH_CLI_WATCH_H

#include <lcm/lcm.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "opts.h"
#include "swaywatch_alarm_t.h"
#include "swaywatch_state_t.h"

#define REDRAW_HZ 4
#define MAX_PKG 64        /* packages shown; more are counted */
#define MAX_REASONS 16    /* refusal reasons told apart */
#define STATE_QUEUE 20000 /* LCM queue of the state subscription: 2 s of 10 packages at 1 kHz */
#define STALE 2.0         /* s without a state: said so */
#define PLAIN_WIDTH 100   /* columns of a plain snapshot */
#define MAX_COLS 512
#define MAX_ROWS 256

/* state_t has a reserve column when the build's state_t.lcm has reserve_g
 * (CMake defines SW_STATE_HAS_RESERVE). */
#ifdef SW_STATE_HAS_RESERVE
#define RESERVE_OF(s) ((s)->reserve_g)
#define HAVE_RESERVE 1
#else
#define RESERVE_OF(s) ((void)(s), NAN)
#define HAVE_RESERVE 0
#endif

typedef struct {
    const char *url;
    const char *state_channel, *alarm_channel;
    int once;
    double wait;  /* s, --once listens this long */
    double every; /* s between plain snapshots */
    long alarms;  /* last alarms shown */
} watch_opts_t;

/* One plane of a package (state_t.name and plane): a package that rocks
 * across the truck too has two rows. */
typedef struct {
    char name[SW_NAME_MAX];
    int plane; /* state_t.PLANE_* */
    swaywatch_state_t last;
    double rx;      /* monotonic s at the arrival of the last state */
    double alpha;   /* rad; NaN: not known */
    int alpha_from; /* 0 unknown, 1 the scene, 2 inferred from the states */
    double peak;    /* largest |theta| / alpha so far */
    long win;       /* states in the current window */
    double rate;    /* states/s over the last window */
} pkg_view_t;

typedef struct {
    int64_t wall_us; /* when it arrived */
    swaywatch_alarm_t a;
} alarm_view_t;

typedef struct {
    char name[24];
    long so_far; /* the monitor's count, from its latest alarm of this reason */
} reason_t;

typedef struct {
    const watch_opts_t *o;
    const sw_scene_t *scenes; /* --scene, for alpha */
    const double *scene_alpha;
    const double *scene_alpha_lat; /* across the truck; NaN: no depth */
    size_t nscenes;

    pkg_view_t pkg[MAX_PKG];
    size_t npkg;
    long pkg_overflow; /* states of packages beyond MAX_PKG */

    alarm_view_t *ring; /* the last o->alarms alarms */
    size_t ring_n, ring_next;

    long states, alarms, undecodable;
    int64_t state_seq, alarm_seq; /* last seen */
    int have_state_seq, have_alarm_seq;
    long lost_states, lost_alarms, seq_restarts;
    reason_t reason[MAX_REASONS];
    size_t nreasons;
    long gaps;
    int gap_open;     /* the monitor said no sample arrives, and nothing has come since */
    long contests;    /* INPUT_CONTESTED alarms at critical level */
    int contest_open; /* the last of them has not been followed by its end (info) */

    double start, last_rx; /* monotonic s: start, last state */
    double win_start;      /* the rate and lag window */
    long win_states;
    double win_lag_sum;
    double rate, lag; /* the last window's: states/s, mean lag (s); NaN: none yet */
} watch_t;

/* s, the monitor's clock (monotonic). */
double sw_watch_mono_now(void);
/* us since the epoch, this computer's clock. */
int64_t sw_watch_wall_now_us(void);
/* An int8_t[cap] text of a message as a C string for a terminal (at most
 * cap bytes with the NUL): control characters (C0, DEL and C1, which a
 * terminal reads as escape sequences) and bytes that are not UTF-8 as
 * '?' (text.h). */
void sw_watch_msg_text(char *dst, const int8_t *src, size_t cap);

/* Subscribe w to the state and alarm channels of its options; SW_EXIT_*
 * (reported). */
int sw_watch_subscribe(lcm_t *lcm, watch_t *w, lcm_subscription_t **s1, lcm_subscription_t **s2);
/* Close the rate and lag window once a second. */
void sw_watch_window(watch_t *w, double now);

/* The view as plain text on standard output. */
void sw_watch_plain_snapshot(const watch_t *w);
/* The view on the curses screen, at its size. */
void sw_watch_screen_draw(const watch_t *w);

#endif
