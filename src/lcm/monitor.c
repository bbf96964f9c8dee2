/* SPDX-License-Identifier: GPL-3.0-or-later */
/* monitor.c - the monitor core (monitor.h) around one input stream
 * (stream.h): accel_t messages decoded and checked into it, its states
 * and alarms encoded as state_t and alarm_t and published, the alarms
 * through the rate limit (alarm_fold.h), the input alarms (gaps, refused
 * and contested samples) on the monotonic clock the caller hands in.  The
 * gate, the engines of both timelines, the reserve and the alarm watches
 * are the stream's: a CSV log and an lcm-logger file go through the same.
 *
 * With keys, each message is authenticated (auth.c) where it is decoded,
 * before anything else looks at it.
 *
 * Nothing in here allocates after sw_mon_create(): messages are encoded
 * into a buffer made at create time and handed to lcm_publish(). */
#include "monitor.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "alarm_fold.h"
#include "swaywatch/status.h"
#include "swaywatch_accel_t.h"
#include "swaywatch_alarm_t.h"
#include "swaywatch_state_t.h"

/* The library's enums are copied into the messages as they are. */
_Static_assert(SWAYWATCH_ALARM_T_KIND_UPLIFT == SW_ALARM_UPLIFT &&
                   SWAYWATCH_ALARM_T_KIND_IMPACT == SW_ALARM_IMPACT &&
                   SWAYWATCH_ALARM_T_KIND_WARN == SW_ALARM_WARN &&
                   SWAYWATCH_ALARM_T_KIND_CRITICAL == SW_ALARM_CRITICAL &&
                   SWAYWATCH_ALARM_T_KIND_TIP == SW_ALARM_TIP &&
                   SWAYWATCH_ALARM_T_KIND_OVERTURNED == SW_ALARM_OVERTURNED &&
                   SWAYWATCH_ALARM_T_KIND_REST == SW_ALARM_REST &&
                   SWAYWATCH_ALARM_T_KIND_MODEL_FAULT == SW_ALARM_MODEL_FAULT &&
                   SWAYWATCH_ALARM_T_KIND_SENSOR_GAP == SW_ALARM_SENSOR_GAP &&
                   SWAYWATCH_ALARM_T_KIND_INPUT_REJECTED == SW_ALARM_INPUT_REJECTED &&
                   SWAYWATCH_ALARM_T_KIND_RESERVE_WARN == SW_ALARM_RESERVE_WARN &&
                   SWAYWATCH_ALARM_T_KIND_RESERVE_CRITICAL == SW_ALARM_RESERVE_CRITICAL &&
                   SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED == SW_ALARM_INPUT_CONTESTED,
               "alarm_t.KIND_* == sw_alarm_kind");
_Static_assert(SWAYWATCH_ALARM_T_LEVEL_INFO == SW_ALARM_LEVEL_INFO &&
                   SWAYWATCH_ALARM_T_LEVEL_WARN == SW_ALARM_LEVEL_WARN &&
                   SWAYWATCH_ALARM_T_LEVEL_CRITICAL == SW_ALARM_LEVEL_CRITICAL,
               "alarm_t.LEVEL_* == sw_alarm_level");
_Static_assert(SWAYWATCH_STATE_T_PHASE_STUCK == SW_PHASE_STUCK &&
                   SWAYWATCH_STATE_T_PHASE_ROCKING == SW_PHASE_ROCKING &&
                   SWAYWATCH_STATE_T_PHASE_OVERTURNED == SW_PHASE_OVERTURNED,
               "state_t.PHASE_* == sw_phase");
_Static_assert(SWAYWATCH_STATE_T_MODEL_BARE == SW_MODEL_BARE &&
                   SWAYWATCH_STATE_T_MODEL_FRAME == SW_MODEL_FRAME &&
                   SWAYWATCH_STATE_T_MODEL_CUSHION == SW_MODEL_CUSHION,
               "state_t.MODEL_* == sw_model_kind");
_Static_assert(SWAYWATCH_STATE_T_PLANE_LONGITUDINAL == SW_PLANE_LONG &&
                   SWAYWATCH_STATE_T_PLANE_LATERAL == SW_PLANE_LAT &&
                   SWAYWATCH_ALARM_T_PLANE_LONGITUDINAL == SW_PLANE_LONG &&
                   SWAYWATCH_ALARM_T_PLANE_LATERAL == SW_PLANE_LAT,
               "state_t.PLANE_* == alarm_t.PLANE_* == sw_plane");
_Static_assert(sizeof(((swaywatch_state_t *)0)->name) == SW_NAME_MAX,
               "state_t.name holds a scene name");
_Static_assert(sizeof(((swaywatch_alarm_t *)0)->text) == SW_ALARM_TEXT_MAX,
               "alarm_t.text holds an alarm text");

/* Messages are fixed-size; this holds the largest encoded one. */
#define SW_MON_BUF 512

struct sw_mon {
    sw_stream_t *st; /* the gate, the engines, the reserve, the alarm watches */
    /* the stream's parts, read after every message */
    const sw_gate_t *gate;
    sw_engine_t *engine;
    sw_risk_t *risk;
    size_t n;
    int lateral;             /* the stream has lateral planes (o.lateral and a depth) */
    int64_t *next_state_us;  /* per package and plane (2 k + plane): sample utime of the
                                next state due */
    int64_t state_period_us; /* 0: every sample */

    sw_mon_opts_t o;
    const char *state_channel, *alarm_channel;
    lcm_t *out;
    unsigned char *buf;

    /* what the monitor keeps of the input stream (the gate decides) */
    int have_last;    /* a sample was accepted */
    int64_t last_us;  /* utime of the last accepted sample */
    double last_rx;   /* mono s, arrival of the last feed that took a sample */
    int gap_open;     /* the timer saw the input stop; it has not resumed */
    double timer_gap; /* s, no sample arriving for longer is a gap; 0: the gate's threshold */
    double feed_mono; /* mono s of the message being fed */
    long timer_gaps;
    sw_mon_reject feed_why; /* the reason of the last refusal during a feed */
    int have_base;
    int64_t base_us; /* utime of the first sample received: the gate is fed
                        (utime - base) / 1e6 s, exact for any utime near it */

    /* Every other alarm kind: a burst per package and kind per interval;
     * the ones after it are folded into one summary (alarm_fold.h). */
    sw_fold_t *fold;
    double now; /* mono s of the feed or tick in progress */

    /* INPUT_REJECTED rate limit, per reason */
    double rej_last_alarm[SW_MON_NREJ]; /* mono s; -INFINITY: never */
    long rej_pending[SW_MON_NREJ];      /* refused since the last alarm for that reason */
    double rej_interval;

    /* with keys: the verifier, and samples failing it (INPUT_CONTESTED) */
    sw_auth_t *auth;
    const char *accel_channel;
    int auth_open;     /* samples failing authentication arrive */
    double auth_last;  /* mono s of the last of them */
    long auth_refused; /* refused since they began */

    int64_t state_seq, alarm_seq;
    sw_mon_counts_t c;
};

static const char *const reject_names[SW_MON_NREJ] = {
    "decode",          "trailing",    "nonfinite", "implausible", "skew",     "duplicate",
    "out_of_order",    "jump",        "engine",    "time",        "overload", "contested",
    "unauthenticated", "unknown_key", "bad_mac",   "replayed"};

const char *sw_mon_reject_name(sw_mon_reject r)
{
    return (unsigned)r < SW_MON_NREJ ? reject_names[r] : "unknown";
}

int sw_mon_axis_parse(const char *s)
{
    if (!s || !s[0] || s[1])
        return -1;
    if (s[0] >= 'x' && s[0] <= 'z')
        return s[0] - 'x';
    return -1;
}

double sw_mon_clock(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void set_name(int8_t *dst, size_t cap, const char *src)
{
    size_t len = strlen(src);
    if (len > cap - 1)
        len = cap - 1;
    memset(dst, 0, cap);
    memcpy(dst, src, len);
}

static void publish(sw_mon_t *m, const char *channel, int len)
{
    if (len < 0 || lcm_publish(m->out, channel, m->buf, (unsigned)len) != 0)
        m->c.publish_errors++;
}

/* The source time (s) the gate sees for a utime: relative to the first
 * sample received, exact in double for any utime within 2^53 us of it;
 * NAN (refused by the gate as not finite... as a time) beyond. */
static double source_time(sw_mon_t *m, int64_t utime)
{
    if (!m->have_base) {
        m->have_base = 1;
        m->base_us = utime;
    }
    int64_t d;
    if (__builtin_sub_overflow(utime, m->base_us, &d))
        return utime < m->base_us ? -1e300 : 1e300;
    return (double)d / 1e6;
}

/* The utime of a source time (s). */
static int64_t utime_at(const sw_mon_t *m, double t)
{
    const double us = t * 1e6;
    if (!(fabs(us) < 9.2e18))
        return m->base_us;
    int64_t u;
    return __builtin_add_overflow(m->base_us, (int64_t)llround(us), &u) ? m->base_us : u;
}

/* utime of a time t (s) on the engine's clock: the source's clock of the
 * current stretch (samples were fed as utime / 1e6 s: llround recovers the
 * integer). */
static int64_t utime_of(const sw_mon_t *m, double t)
{
    return utime_at(m, sw_gate_source_time(m->gate, t));
}

/* The latest reserve of package pkg's plane for a message: -1 when there
 * is none. */
static double reserve_of(const sw_mon_t *m, size_t pkg, sw_plane plane)
{
    const sw_risk_pkg_t *p = plane == SW_PLANE_LONG ? sw_risk_pkg(m->risk, pkg)
                                                    : sw_stream_risk_plane(m->st, pkg, plane);
    return p && isfinite(p->reserve_g) ? p->reserve_g : -1.0;
}

/* Publish one alarm (no rate limit: the fold decides). */
static void emit_alarm(void *user, const sw_alarm_t *a, int64_t utime)
{
    sw_mon_t *m = user;
    m->c.alarms++;
    if (m->o.on_alarm)
        m->o.on_alarm(m->o.user, a);
    if (!m->out)
        return;
    swaywatch_alarm_t msg;
    memset(&msg, 0, sizeof msg);
    msg.utime = utime;
    msg.seq = m->alarm_seq++;
    if (a->pkg < m->n)
        set_name(msg.name, sizeof msg.name, sw_stream_name(m->st, a->pkg));
    msg.kind = (int8_t)a->kind;
    msg.level = (int8_t)a->level;
    set_name(msg.text, sizeof msg.text, a->text);
    /* sw_alarm_t guarantees finite numbers; checked again because a NaN
     * must never be published. */
    msg.theta = isfinite(a->theta) ? a->theta : 0.0;
    msg.margin = isfinite(a->margin) ? a->margin : 0.0;
    msg.reserve_g = reserve_of(m, a->pkg, a->plane);
    msg.plane = a->pkg < m->n && a->plane == SW_PLANE_LAT ? SWAYWATCH_ALARM_T_PLANE_LATERAL
                                                          : SWAYWATCH_ALARM_T_PLANE_LONGITUDINAL;
    publish(m, m->alarm_channel, swaywatch_alarm_t_encode(m->buf, 0, SW_MON_BUF, &msg));
}

/* Every alarm goes through the rate limit. */
static void send_alarm(sw_mon_t *m, const sw_alarm_t *a, int64_t utime)
{
    sw_fold_send(m->fold, a, utime, m->now);
}

/* A package's alarm (either timeline's), at its sample's utime. */
static void on_alarm(void *user, const sw_alarm_t *a, double t_source)
{
    sw_mon_t *m = user;
    send_alarm(m, a, utime_at(m, t_source));
}

static void on_event(void *user, const sw_event_t *ev)
{
    const sw_mon_t *m = user;
    if (m->o.on_event)
        m->o.on_event(m->o.user, ev);
}

/* A state, its reserve evaluated and its alarms raised by the stream. */
static void on_state(void *user, const sw_output_t *out)
{
    sw_mon_t *m = user;
    const size_t k = out->pkg;
    const int lat = out->plane == SW_PLANE_LAT;
    int64_t *const next = &m->next_state_us[2 * k + (lat ? 1 : 0)]; /* each plane its grid */
    if (m->o.on_state)
        m->o.on_state(m->o.user, out);
    /* Outputs come at sample times (and at the settling steps after the
     * end of a log): t = (utime - origin) / 1e6 maps back exactly. */
    int finite = sw_output_finite(out);
    int64_t utime = finite ? utime_of(m, out->t) : m->last_us;
    if (m->state_period_us > 0) {
        /* The sensor's clock went back (a restart, a log played twice):
         * the grid follows it, or no state would go out until the new
         * clock caught up with the old grid. */
        if (utime < *next - m->state_period_us)
            *next = utime;
        if (utime < *next)
            return;
        *next += m->state_period_us;
        /* After a gap, restart the grid instead of publishing a burst. */
        if (*next <= utime)
            *next = utime + m->state_period_us;
    }
    if (!finite) {
        m->c.states_withheld++; /* the alarm module raised MODEL_FAULT */
        return;
    }
    m->c.states++;
    if (!m->out)
        return;
    swaywatch_state_t msg;
    memset(&msg, 0, sizeof msg);
    msg.utime = utime;
    msg.seq = m->state_seq++;
    set_name(msg.name, sizeof msg.name, sw_stream_name(m->st, k));
    msg.model = (int8_t)sw_engine_derived(m->engine, k)->model;
    msg.phase = (int8_t)out->state.phase;
    msg.side = (int8_t)out->state.side;
    msg.theta = out->state.theta;
    msg.theta_dot = out->state.theta_dot;
    msg.u = out->state.u;
    msg.z_b = out->state.z;
    msg.margin = out->margin;
    msg.margin_bound = out->margin_bound;
    msg.uplift_ratio = out->uplift_ratio;
    msg.a_g = out->a_g;
    msg.reserve_g = reserve_of(m, k, out->plane);
    msg.plane = lat ? SWAYWATCH_STATE_T_PLANE_LATERAL : SWAYWATCH_STATE_T_PLANE_LONGITUDINAL;
    publish(m, m->state_channel, swaywatch_state_t_encode(m->buf, 0, SW_MON_BUF, &msg));
}

static void on_gate_reject(void *user, const sw_sample_t *s, sw_gate_reject r, const char *text);
static void on_gate_event(void *user, const sw_gate_event_t *ev);

/* The stream's user is the monitor; the caller's recorder gets its own. */
static void on_gate_take(void *user, double t, double a_g, double a_z, int restart)
{
    const sw_mon_t *m = user;
    m->o.on_take(m->o.user, t, a_g, a_z, restart);
}

static void on_gate_take_lat(void *user, double t, double a_g, double a_y, double a_z, int restart)
{
    const sw_mon_t *m = user;
    m->o.on_take_lat(m->o.user, t, a_g, a_y, a_z, restart);
}

/* The options, their defaults filled in, are in range. */
static int opts_valid(const sw_mon_opts_t *o)
{
    return o->axis >= 0 && o->axis <= 2 && o->vertical >= -1 && o->vertical <= 2 &&
           o->accel_scale > 0.0 && o->gap >= 0.0 && o->max_accel > 0.0 && o->state_rate >= 0.0 &&
           o->max_skew >= 0.0 && o->reject_interval >= 0.0 && o->alarm_interval < 1e9 &&
           isfinite(o->gap) && isfinite(o->state_rate) && o->max_jump < 1e9 &&
           /* in microseconds of int64: a gap beyond 1e9 s or a rate below
            * 1e-9 Hz would overflow */
           o->gap <= 1e9 && !(o->state_rate > 0.0 && !(o->state_rate >= 1e-9)) &&
           (!o->lateral || (o->lat_axis >= 0 && o->lat_axis <= 2));
}

/* The stream of the monitor: its gate with the monitor's checks, both
 * timelines evaluated, every alarm to the monitor (its user). */
static sw_stream_t *make_stream(sw_mon_t *m, const sw_scene_t *scenes, size_t n,
                                const sw_engine_opts_t *eo, char *msg, size_t msglen)
{
    sw_stream_opts_t so = {
        .engine = *eo,
        .gate = {.gap = m->o.gap,
                 .gap_policy = m->o.gap_policy,
                 .max_bridge = m->o.max_bridge,
                 .max_accel = m->o.max_accel,
                 .jump = m->o.max_jump,
                 .max_skew = m->o.max_skew,
                 .confirm = m->o.confirm,
                 .relative = 1,
                 .vert_gravity = m->o.vert_gravity},
        .risk = {.reserve_rate = m->o.reserve_rate},
        .hysteresis = m->o.hysteresis,
        .rival = 1,
        .on_state = on_state,
        .on_event = on_event,
        .on_alarm = on_alarm,
        .on_input = on_gate_event,
        .on_reject = on_gate_reject,
        .on_take = m->o.on_take ? on_gate_take : NULL,
        .user = m,
        .on_take_lat = m->o.on_take_lat ? on_gate_take_lat : NULL,
    };
    so.engine.lateral = m->lateral;
    return sw_stream_create(scenes, n, &so, NULL, msg, msglen);
}

sw_mon_t *sw_mon_create(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo,
                        const sw_mon_opts_t *mo, lcm_t *out, char *msg, size_t msglen)
{
    sw_mon_t *m = calloc(1, sizeof *m);
    if (!m)
        goto nomem;
    m->o = *mo;
    if (m->o.accel_scale == 0.0)
        m->o.accel_scale = 1.0;
    if (m->o.max_accel == 0.0)
        m->o.max_accel = SW_MON_MAX_ACCEL;
    m->timer_gap = m->o.gap;
    if (!opts_valid(&m->o)) {
        if (msg)
            snprintf(msg, msglen, "invalid monitor options");
        free(m);
        return NULL;
    }
    m->state_channel = mo->state_channel ? mo->state_channel : SW_MON_STATE_CHANNEL;
    m->accel_channel = mo->accel_channel ? mo->accel_channel : SW_MON_ACCEL_CHANNEL;
    m->alarm_channel = mo->alarm_channel ? mo->alarm_channel : SW_MON_ALARM_CHANNEL;
    m->out = out;
    m->n = n;
    m->state_period_us = m->o.state_rate > 0.0 ? (int64_t)llround(1e6 / m->o.state_rate) : 0;
    if (m->o.state_rate > 0.0 && m->state_period_us < 1)
        m->state_period_us = 1;
    m->rej_interval = m->o.reject_interval > 0.0 ? m->o.reject_interval : 1.0;
    for (int r = 0; r < SW_MON_NREJ; r++) m->rej_last_alarm[r] = -INFINITY;
    const double interval = m->o.alarm_interval == 0.0 ? 1.0 : fmax(m->o.alarm_interval, 0.0);

    /* a lateral plane only where a scene asks for it: without a depth,
     * nothing of it is made or computed */
    for (size_t k = 0; k < n && m->o.lateral; k++) m->lateral |= sw_scene_has_depth(&scenes[k]);
    m->next_state_us = calloc(n ? 2 * n : 1, sizeof *m->next_state_us);
    m->buf = malloc(SW_MON_BUF);
    m->fold = sw_fold_create(n, interval, emit_alarm, m);
    if (!m->next_state_us || !m->buf || !m->fold)
        goto nomem;
    if (mo->keys && !(m->auth = sw_auth_create(mo->keys)))
        goto nomem;
    if (!(m->st = make_stream(m, scenes, n, eo, msg, msglen))) {
        sw_mon_destroy(m);
        return NULL;
    }
    m->gate = sw_stream_gate(m->st);
    m->engine = sw_stream_engine(m->st);
    m->risk = sw_stream_risk(m->st);
    return m;

nomem:
    if (msg)
        snprintf(msg, msglen, "%s", sw_strerror(SW_ENOMEM));
    sw_mon_destroy(m);
    return NULL;
}

void sw_mon_destroy(sw_mon_t *m)
{
    if (!m)
        return;
    sw_auth_destroy(m->auth);
    sw_stream_destroy(m->st);
    free(m->next_state_us);
    free(m->buf);
    sw_fold_destroy(m->fold);
    free(m);
}

/* s: no sample arriving for longer is a gap: the option, or the gate's
 * threshold for the sensor's pace (a 10 Hz sensor is not silent after
 * 0.1 s), at least SW_MON_GAP. */
static double timer_gap(const sw_mon_t *m)
{
    if (m->timer_gap > 0.0)
        return m->timer_gap;
    const double thr = sw_gate_gap_threshold(m->gate);
    return isfinite(thr) && thr > SW_MON_GAP ? thr : SW_MON_GAP;
}

/* utime for an input alarm: on the sensor's clock once it is known. */
static int64_t input_utime(const sw_mon_t *m, int64_t fallback)
{
    return m->have_last ? m->last_us : fallback;
}

static void input_alarm(sw_mon_t *m, sw_alarm_kind kind, sw_alarm_level level, int64_t utime,
                        const char *text)
{
    sw_alarm_t a;
    sw_gate_facts_t f;
    sw_gate_facts(m->gate, &f);
    double d = 0.0;
    if (m->have_last) {
        int64_t du;
        d = __builtin_sub_overflow(utime, m->base_us, &du) ? 0.0 : (double)du / 1e6 - f.t_origin;
    }
    sw_alarm_input(&a, kind, level, d, text);
    send_alarm(m, &a, utime);
}

/* Raise INPUT_REJECTED for reason r now, or hold it back (counted) when
 * one was raised less than rej_interval ago. */
static void reject_alarm(sw_mon_t *m, sw_mon_reject r, double mono, int64_t utime)
{
    char text[SW_ALARM_TEXT_MAX];
    if (m->rej_pending[r] == 0 || mono - m->rej_last_alarm[r] < m->rej_interval)
        return;
    if (m->rej_pending[r] == 1)
        snprintf(text, sizeof text, "accel sample rejected: %s (%ld so far)", reject_names[r],
                 m->c.rejected[r]);
    else
        snprintf(text, sizeof text, "%ld accel samples rejected: %s (%ld so far)",
                 m->rej_pending[r], reject_names[r], m->c.rejected[r]);
    m->rej_pending[r] = 0;
    m->rej_last_alarm[r] = mono;
    input_alarm(m, SW_ALARM_INPUT_REJECTED, SW_ALARM_LEVEL_WARN, utime, text);
}

static int refuse(sw_mon_t *m, sw_mon_reject r, double mono, int64_t utime, sw_mon_reject *why)
{
    static const int code[SW_MON_NREJ] = {SW_EPARSE,  SW_EPARSE,      SW_ENONFINITE, SW_ETOOBIG,
                                          SW_ETOOBIG, SW_EORDER,      SW_EORDER,     SW_EORDER,
                                          SW_EINVAL,  SW_ERESOLUTION, SW_ETOOBIG,    SW_EORDER,
                                          SW_EAUTH,   SW_EAUTH,       SW_EAUTH,      SW_EAUTH};
    m->c.rejected[r]++;
    m->rej_pending[r]++;
    reject_alarm(m, r, mono, input_utime(m, utime));
    if (why)
        *why = r;
    return code[r];
}

/* The gate refused a sample (now, or one it held): counted by reason. */
static void on_gate_reject(void *user, const sw_sample_t *s, sw_gate_reject r, const char *text)
{
    static const sw_mon_reject map[SW_GATE_NREJ] = {
        SW_MON_REJ_NONFINITE, SW_MON_REJ_IMPLAUSIBLE, SW_MON_REJ_TIME,
        SW_MON_REJ_SKEW,      SW_MON_REJ_DUPLICATE,   SW_MON_REJ_OUT_OF_ORDER,
        SW_MON_REJ_JUMP,      SW_MON_REJ_ENGINE,      SW_MON_REJ_CONTESTED};
    sw_mon_t *m = user;
    (void)text;
    m->feed_why = map[r];
    refuse(m, map[r], m->feed_mono, utime_at(m, s->t), NULL);
}

/* A gap, a clock step or a restart of the stream: an alarm (the gap's
 * before the states of the sample that ends it). */
static void on_gate_event(void *user, const sw_gate_event_t *ev)
{
    sw_mon_t *m = user;
    char text[SW_ALARM_TEXT_MAX];
    char how[72];
    snprintf(how, sizeof how, "%s%s",
             ev->restarted ? "; packages restarted from rest"
             : ev->bridged ? "; bridged by linear interpolation"
                           : "",
             ev->incomplete ? "; it overlaps rocking: incomplete" : "");
    sw_alarm_level level = ev->incomplete ? SW_ALARM_LEVEL_CRITICAL : SW_ALARM_LEVEL_WARN;
    switch (ev->kind) {
        case SW_GATE_EV_GAP:
            if (m->gap_open) {
                m->timer_gaps--; /* the gap the timer saw: counted once, by the gate now */
                snprintf(text, sizeof text, "accel back after %.3f s%s", ev->span, how);
                level = ev->incomplete ? SW_ALARM_LEVEL_CRITICAL : SW_ALARM_LEVEL_INFO;
            } else {
                snprintf(text, sizeof text, "%.3f s between accel samples%s", ev->span, how);
            }
            break;
        case SW_GATE_EV_CLOCK_STEP:
            snprintf(text, sizeof text, "sensor clock stepped by %+.6g s (re-timed)%s", ev->span,
                     how);
            break;
        case SW_GATE_EV_RESTART:
            snprintf(text, sizeof text, "sensor time went back by %.6g s: a restart%s", -ev->span,
                     how);
            break;
        case SW_GATE_EV_SEQ_RESTART:
            snprintf(text, sizeof text, "accel seq went back: the sender restarted");
            level = SW_ALARM_LEVEL_INFO;
            break;
        case SW_GATE_EV_CONTESTED:
            snprintf(text, sizeof text,
                     "two timelines on the accel channel (a forged or duplicated sender): "
                     "the one the arrival times support kept, both evaluated");
            input_alarm(m, SW_ALARM_INPUT_CONTESTED, SW_ALARM_LEVEL_CRITICAL, m->last_us, text);
            return;
        case SW_GATE_EV_UNCONTESTED:
            snprintf(text, sizeof text,
                     "accel channel no longer contested: the second timeline stopped after "
                     "%.3f s",
                     ev->span);
            input_alarm(m, SW_ALARM_INPUT_CONTESTED, SW_ALARM_LEVEL_INFO, m->last_us, text);
            return;
        case SW_GATE_EV_RECONSTRUCT: return; /* a log's, never live */
    }
    m->gap_open = 0;
    input_alarm(m, SW_ALARM_SENSOR_GAP, level, utime_at(m, ev->t), text);
}

/* A message that failed authentication (r): refused, and INPUT_CONTESTED
 * (critical) raised when such messages begin to arrive: something else
 * than the keyed sensor publishes on the channel (or the sensor has
 * another key), and what it sends is never integrated. */
static int auth_refuse(sw_mon_t *m, sw_auth_result r, const char *channel, double mono,
                       int64_t wall_us, sw_mon_reject *why)
{
    static const sw_mon_reject map[SW_AUTH_NRESULTS] = {
        SW_MON_REJ_ENGINE, SW_MON_REJ_UNAUTHENTICATED, SW_MON_REJ_UNKNOWN_KEY, SW_MON_REJ_BAD_MAC,
        SW_MON_REJ_REPLAYED};
    m->auth_last = mono;
    m->auth_refused++;
    if (!m->auth_open) {
        char text[SW_ALARM_TEXT_MAX];
        m->auth_open = 1;
        m->auth_refused = 1;
        m->c.auth_contests++;
        snprintf(text, sizeof text,
                 "unauthentic accel samples on %.40s (%s): refused, the authenticated stream kept",
                 channel, sw_auth_result_name(r));
        input_alarm(m, SW_ALARM_INPUT_CONTESTED, SW_ALARM_LEVEL_CRITICAL, input_utime(m, wall_us),
                    text);
    }
    return refuse(m, map[r], mono, wall_us, why);
}

/* The unauthentic samples stopped: said once (info). */
static void auth_check_end(sw_mon_t *m, double mono)
{
    if (!m->auth_open || !(mono - m->auth_last > SW_MON_AUTH_QUIET))
        return;
    char text[SW_ALARM_TEXT_MAX];
    m->auth_open = 0;
    snprintf(text, sizeof text,
             "accel channel no longer contested: no unauthentic sample for %.0f s (%ld refused)",
             SW_MON_AUTH_QUIET, m->auth_refused);
    input_alarm(m, SW_ALARM_INPUT_CONTESTED, SW_ALARM_LEVEL_INFO, m->last_us, text);
}

int sw_mon_feed(sw_mon_t *m, const void *data, size_t len, int64_t wall_us, double mono,
                sw_mon_reject *why)
{
    return sw_mon_feed_on(m, NULL, data, len, wall_us, mono, why);
}

int sw_mon_feed_on(sw_mon_t *m, const char *channel, const void *data, size_t len, int64_t wall_us,
                   double mono, sw_mon_reject *why)
{
    swaywatch_accel_t s;
    int layout = 0;
    m->c.received++;
    m->feed_mono = mono;
    m->now = mono;
    const int used = sw_accel_decode(data, len, &s, &layout);
    if (used < 0)
        return refuse(m, SW_MON_REJ_DECODE, mono, wall_us, why);
    /* The generated decoder accepts trailing bytes; a well-formed sender
     * never sends them. */
    if ((size_t)used != len)
        return refuse(m, SW_MON_REJ_TRAILING, mono, wall_us, why);
    if (!channel)
        channel = m->accel_channel;
    if (m->auth) {
        const sw_auth_result ar = sw_auth_check(m->auth, channel, data, &s, layout, m->c.received);
        if (ar != SW_AUTH_OK)
            return auth_refuse(m, ar, channel, mono, wall_us, why);
    } else if (layout == 2 && s.key_id != 0) {
        m->c.macs_unchecked++;
    }
    /* every axis must be finite, the ones not used too: a NaN anywhere is
     * a broken sender */
    if (!isfinite(s.ax) || !isfinite(s.ay) || !isfinite(s.az))
        return refuse(m, SW_MON_REJ_NONFINITE, mono, m->have_last ? m->last_us : wall_us, why);
    if (s.utime < 0 || s.utime >= SW_MON_UTIME_MAX)
        return refuse(m, SW_MON_REJ_TIME, mono, m->have_last ? m->last_us : wall_us, why);
    const double v[3] = {s.ax * m->o.accel_scale, s.ay * m->o.accel_scale, s.az * m->o.accel_scale};
    const double t = source_time(m, s.utime); /* first: the first sample sets the base */
    const sw_sample_t smp = {
        .t = t,
        .a_g = m->o.flip ? -v[m->o.axis] : v[m->o.axis],
        .a_z = m->o.vertical >= 0 ? v[m->o.vertical] : 0.0,
        .a_max = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2]))),
        .a_y = !m->lateral     ? 0.0
               : m->o.flip_lat ? -v[m->o.lat_axis]
                               : v[m->o.lat_axis],
        /* INT64_MIN is a seq like any other, never "none" */
        .seq = s.seq == SW_GATE_NO_SEQ ? s.seq + 1 : s.seq,
        .rx = mono,
        .wall = m->o.max_skew > 0.0 ? source_time(m, wall_us) : NAN,
        .where = m->c.received,
    };
    const long before = m->c.accepted;
    m->feed_why = SW_MON_NREJ;
    int rc = sw_stream_push(m->st, &smp);
    m->c.accepted = sw_gate_accepted(m->gate);
    if (m->c.accepted > before) {
        /* this sample, or held ones it confirmed, went in */
        m->have_last = 1;
        m->last_us = s.utime; /* the last one pushed: held ones go in before it */
        m->last_rx = mono;
        m->gap_open = 0;
    }
    if (rc == SW_GATE_HELD)
        return SW_MON_HELD;
    if (rc < 0 && why)
        *why = m->feed_why; /* the sample itself is refused last */
    return rc;
}

int sw_mon_feed_log(sw_mon_t *m, sw_lcmlog_t *log, int strict)
{
    sw_lcmlog_event_t ev;
    int r;
    while ((r = sw_lcmlog_next(log, &ev)) > 0) {
        /* a MAC covers the channel */
        sw_mon_feed_on(m, ev.channel, ev.data, ev.len, ev.timestamp, ev.rx, NULL);
        /* a refusal, of this sample or of one held before it */
        if (strict && sw_mon_rejected(&m->c) > 0)
            return SW_EINVAL;
    }
    return r;
}

int sw_mon_refuse(sw_mon_t *m, sw_mon_reject r, double mono)
{
    if ((unsigned)r >= SW_MON_NREJ)
        r = SW_MON_REJ_ENGINE;
    m->c.received++;
    m->feed_mono = m->now = mono;
    return refuse(m, r, mono, m->have_last ? m->last_us : 0, NULL);
}

double sw_mon_deadline(const sw_mon_t *m)
{
    double d = INFINITY;
    if (m->have_last && !m->gap_open)
        d = m->last_rx + timer_gap(m);
    for (int r = 0; r < SW_MON_NREJ; r++)
        if (m->rej_pending[r] > 0 && m->rej_last_alarm[r] + m->rej_interval < d)
            d = m->rej_last_alarm[r] + m->rej_interval;
    if (m->auth_open && m->auth_last + SW_MON_AUTH_QUIET < d)
        d = m->auth_last + SW_MON_AUTH_QUIET;
    const double f = sw_fold_deadline(m->fold);
    return f < d ? f : d;
}

void sw_mon_tick(sw_mon_t *m, double mono)
{
    m->now = mono;
    if (m->have_last && !m->gap_open && mono - m->last_rx > timer_gap(m)) {
        char text[SW_ALARM_TEXT_MAX];
        double waited = mono - m->last_rx;
        m->gap_open = 1;
        m->timer_gaps++;
        snprintf(text, sizeof text, "no accel sample for %.3f s", waited);
        input_alarm(m, SW_ALARM_SENSOR_GAP, SW_ALARM_LEVEL_WARN,
                    m->last_us + (int64_t)llround(waited * 1e6), text);
    }
    for (int r = 0; r < SW_MON_NREJ; r++) reject_alarm(m, (sw_mon_reject)r, mono, m->last_us);
    auth_check_end(m, mono);
    sw_fold_tick(m->fold, mono);
}

void sw_mon_flush(sw_mon_t *m)
{
    m->feed_mono = INFINITY;
    m->now = INFINITY;
    sw_stream_finish(m->st);
    sw_gate_facts_t f;
    sw_gate_facts(m->gate, &f);
    m->c.accepted = f.accepted;
    for (int r = 0; r < SW_MON_NREJ; r++) reject_alarm(m, (sw_mon_reject)r, INFINITY, m->last_us);
    sw_fold_tick(m->fold, INFINITY);
}

void sw_mon_counts(const sw_mon_t *m, sw_mon_counts_t *c)
{
    sw_gate_facts_t f;
    sw_gate_facts(m->gate, &f);
    *c = m->c;
    c->alarms_folded = sw_fold_folded(m->fold);
    c->accepted = f.accepted;
    c->held = f.held;
    c->lost = f.lost;
    c->seq_restarts = f.seq_restarts;
    c->gaps = f.gaps + m->timer_gaps;
    c->clock_steps = f.clock_steps;
    c->restarts = f.restarts;
    c->contests = f.contests;
    c->contested = f.contested;
}

void sw_mon_facts(const sw_mon_t *m, sw_gate_facts_t *f)
{
    sw_gate_facts(m->gate, f);
}

long sw_mon_rejected(const sw_mon_counts_t *c)
{
    long n = 0;
    for (int r = 0; r < SW_MON_NREJ; r++) n += c->rejected[r];
    return n;
}

sw_engine_t *sw_mon_engine(sw_mon_t *m)
{
    return m->engine;
}

int64_t sw_mon_origin(const sw_mon_t *m)
{
    sw_gate_facts_t f;
    sw_gate_facts(m->gate, &f);
    return m->have_last ? utime_at(m, f.t_origin) : 0;
}

int64_t sw_mon_last_utime(const sw_mon_t *m)
{
    return m->have_last ? m->last_us : 0;
}

int sw_mon_replace(sw_mon_t *m, size_t k, const sw_scene_t *scene, char *msg, size_t msglen)
{
    if (!m) {
        if (msg)
            snprintf(msg, msglen, "no such package");
        return SW_EINVAL;
    }
    return sw_stream_replace(m->st, k, scene, msg, msglen);
}

sw_risk_t *sw_mon_risk(sw_mon_t *m)
{
    return m ? m->risk : NULL;
}

sw_stream_t *sw_mon_stream(sw_mon_t *m)
{
    return m ? m->st : NULL;
}

int sw_mon_set_keys(sw_mon_t *m, const sw_keyring_t *keys)
{
    if (!m || !m->auth || !keys)
        return SW_EINVAL;
    sw_auth_set_keys(m->auth, keys);
    m->o.keys = keys;
    return SW_OK;
}

const sw_auth_facts_t *sw_mon_auth_facts(const sw_mon_t *m)
{
    return m && m->auth ? sw_auth_facts(m->auth) : NULL;
}
