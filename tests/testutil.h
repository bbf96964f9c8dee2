/* SPDX-License-Identifier: GPL-3.0-or-later */
/* testutil.h - small helpers shared by the physics tests: scenes built in
 * code, event recording, pulse runs, tu_near() (near.h).  Include after
 * cmocka.h. */
#ifndef SW_TESTUTIL_H
#define SW_TESTUTIL_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "near.h"
#include "swaywatch/swaywatch.h"

/* A bare block of height 2h and width 2b (m), mass 1000 kg. */
static inline sw_scene_t tu_bare(double height, double width)
{
    sw_scene_t sc;
    sw_scene_init(&sc);
    snprintf(sc.name, sizeof sc.name, "block");
    sc.height = height;
    sc.width = width;
    sc.mass = 1000.0;
    return sc;
}

/* The same block on a frame given by mass (kg), omega_b (rad/s), zeta_b. */
static inline sw_scene_t tu_frame(double height, double width, double frame_mass, double omega,
                                  double zeta)
{
    sw_scene_t sc = tu_bare(height, width);
    sc.has_frame = 1;
    sc.frame_mass = frame_mass;
    sc.frame_omega = omega;
    sc.frame_zeta = zeta;
    sc.frame_k_given = SW_GIVEN_RATIO;
    sc.frame_c_given = SW_GIVEN_RATIO;
    return sc;
}

/* The scene sc on a cushion of natural frequency omega_c (rad/s) and
 * damping ratio zeta_c, both given as ratios. */
static inline sw_scene_t tu_cushion(sw_scene_t sc, double omega_c, double zeta_c)
{
    sc.has_cushion = 1;
    sc.cushion_omega = omega_c;
    sc.cushion_zeta = zeta_c;
    sc.cushion_k_given = sc.cushion_c_given = SW_GIVEN_RATIO;
    return sc;
}

#define TU_MAX_EV 4096
typedef struct {
    int n;
    sw_event_t ev[TU_MAX_EV];
} tu_events_t;

static inline void tu_on_event(void *user, const sw_event_t *ev)
{
    tu_events_t *r = user;
    if (r->n < TU_MAX_EV)
        r->ev[r->n++] = *ev;
}

static inline int tu_count(const tu_events_t *r, sw_event_kind k)
{
    int c = 0;
    for (int i = 0; i < r->n; i++) c += r->ev[i].kind == k;
    return c;
}

static inline const sw_event_t *tu_first(const tu_events_t *r, sw_event_kind k)
{
    for (int i = 0; i < r->n; i++)
        if (r->ev[i].kind == k)
            return &r->ev[i];
    return NULL;
}

static inline sw_engine_t *tu_engine(const sw_scene_t *sc, const char *scheme, double dt,
                                     tu_events_t *rec)
{
    sw_engine_opts_t o = {0};
    o.scheme = scheme;
    o.dt = dt;
    o.on_event = rec ? tu_on_event : NULL;
    o.user = rec;
    int err;
    char msg[256];
    sw_engine_t *e = sw_engine_create(sc, 1, &o, &err, msg, sizeof msg);
    if (!e)
        fprintf(stderr, "engine: %s (%s)\n", msg, sw_strerror(err));
    return e;
}

/* Run a pulse exactly (advance to the end of the pulse, then free motion
 * until t_end); returns the summary. */
static inline sw_summary_t tu_pulse(const sw_scene_t *sc, const char *scheme, double dt,
                                    sw_pulse_t pulse, double t_end, tu_events_t *rec)
{
    sw_summary_t s;
    memset(&s, 0, sizeof s);
    sw_engine_t *e = tu_engine(sc, scheme, dt, rec);
    if (!e)
        return s;
    sw_engine_advance_fn(e, sw_pulse_duration(&pulse), sw_pulse_eval, &pulse);
    sw_engine_advance_fn(e, t_end, sw_pulse_eval, &pulse);
    sw_engine_summary(e, 0, &s);
    sw_engine_destroy(e);
    return s;
}

#endif
