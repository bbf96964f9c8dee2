/* SPDX-License-Identifier: GPL-3.0-or-later */
/* monitor_opts.h - the options of the monitor core (monitor.h) and its
 * defaults, apart: they need nothing from LCM (keys are only pointed to),
 * so the command's options of lcm-logger files are read in every build,
 * the LCM parts of it present or not. */
#ifndef SWAYWATCH_LCM_MONITOR_OPTS_H
#define SWAYWATCH_LCM_MONITOR_OPTS_H

#include "eventlog.h"
#include "swaywatch/alarm.h"
#include "swaywatch/engine.h"
#include "swaywatch/gate.h"
#include "swaywatch/units.h"

typedef struct sw_keyring sw_keyring_t; /* auth.h */

#define SW_MON_STATE_CHANNEL "SWAY_STATE"
#define SW_MON_ALARM_CHANNEL "SWAY_ALARM"
#define SW_MON_ACCEL_CHANNEL SW_LCMLOG_CHANNEL
#define SW_MON_GAP 0.1                /* s, default sensor gap threshold */
#define SW_MON_MAX_ACCEL (50 * SW_G0) /* m/s^2, default plausibility limit */

typedef struct {
    const char *state_channel; /* NULL = SW_MON_STATE_CHANNEL */
    const char *alarm_channel; /* NULL = SW_MON_ALARM_CHANNEL */
    int axis;                  /* 0 x, 1 y, 2 z: message axis along the truck's travel */
    int vertical;              /* message axis giving the vertical input a_z, or -1: none */
    int flip;                  /* non-zero: negate the longitudinal axis */
    double accel_scale;        /* m/s^2 per message unit: 1, or SW_G0; 0 = 1 */
    double state_rate;         /* Hz, states per package per second of sample time; 0 = all */
    double gap;                /* s, sensor gap threshold: between samples (the gate's gap;
                                  0 = the sensor's pace as the gate learns it) and with
                                  none arriving (the timer; 0 = the gate's threshold, at
                                  least SW_MON_GAP) */
    sw_gap_policy gap_policy;  /* bridge (up to max_bridge) or restart from rest */
    double max_bridge;         /* s, longest gap bridged; 0 = 10 s */
    int confirm;               /* samples that confirm a jump or a restart; 0 = 3 */
    int vert_gravity;          /* the vertical axis includes gravity (subtracted) */
    double max_accel;          /* m/s^2, plausibility limit (in m/s^2 after scaling);
                                  0 = SW_MON_MAX_ACCEL */
    double max_skew;           /* s, largest |utime - wall clock|; 0 = not checked */
    double max_jump;           /* s, how far utime may run ahead of its arrival (beyond any
                                  sample before) before the stream must confirm it; 0 = 1.5
                                  sample intervals (gate.h), < 0 = any (no sample held) */
    double hysteresis;         /* 1, margin alarms; < 0 = SW_ALARM_HYSTERESIS */
    double reserve_rate;       /* Hz of sample time: reserve evaluations per package (risk.h;
                                  state_t.reserve_g, RESERVE_WARN/CRITICAL alarms); 0 = 10,
                                  < 0 = none */
    double reject_interval;    /* s, at most one INPUT_REJECTED alarm per reason per
                                  interval (later ones are summed up); 0 = 1 s */
    double alarm_interval;     /* s, at most one alarm per package and kind per interval:
                                  the rest go out as one summary with their count when it
                                  has passed; 0 = 1 s, < 0 = no limit */
    sw_state_fn on_state;      /* optional: every engine output (t relative to the first
                                  sample), published or not */
    sw_event_fn on_event;      /* optional: every engine event */
    sw_alarm_fn on_alarm;      /* optional: every alarm raised (t relative, as on_state) */
    sw_gate_take_fn on_take;   /* optional: every sample pushed into the engine, as the
                                  gate reports it (gate.h): a log read once, replayed */
    const sw_keyring_t *keys;  /* NULL: no authentication (either layout taken, MACs not
                                  checked); else every message must be authentic under one
                                  of these keys (auth.h); borrowed (sw_mon_set_keys) */
    const char *accel_channel; /* the channel of messages fed by sw_mon_feed() (a MAC
                                  covers it); NULL = SW_MON_ACCEL_CHANNEL */
    void *user;
    /* the lateral plane (docs/lcm.md): with lateral, the packages whose
     * scene gives a depth rock across the truck too, driven by the
     * message's lat_axis (0 x, 1 y, 2 z; y left positive), negated with
     * flip_lat; their states and alarms carry plane LATERAL.  No depth in
     * any scene: nothing of it is made (one plane, as without).  0: one
     * plane, whatever the scenes say. */
    int lateral;
    int lat_axis;
    int flip_lat;
    /* optional: with lateral planes, called instead of on_take, with the
     * lateral value the engine got too (a caller that runs them again) */
    sw_gate_take_lat_fn on_take_lat;
} sw_mon_opts_t;

#endif
