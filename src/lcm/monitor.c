/* monitor.c - the monitor core (monitor.h): checks accel_t messages, drives
 * the engine and the alarm logic, publishes state_t and alarm_t.
 *
 * Nothing in here allocates after sw_mon_create(): messages are encoded
 * into a buffer made at create time and handed to lcm_publish(). */
#include "monitor.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

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
                   SWAYWATCH_ALARM_T_KIND_INPUT_REJECTED == SW_ALARM_INPUT_REJECTED,
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
_Static_assert(sizeof(((swaywatch_state_t *)0)->name) == SW_NAME_MAX,
               "state_t.name holds a scene name");
_Static_assert(sizeof(((swaywatch_alarm_t *)0)->text) == SW_ALARM_TEXT_MAX,
               "alarm_t.text holds an alarm text");

/* Messages are fixed-size; this holds the largest encoded one. */
#define SW_MON_BUF 512

struct sw_mon {
    sw_engine_t *engine;
    size_t n;
    sw_alarm_watch_t *watch; /* one per package */
    char (*names)[SW_NAME_MAX];
    int64_t *next_state_us;  /* per package: sample utime of the next state due */
    int64_t state_period_us; /* 0: every sample */

    sw_mon_opts_t o;
    const char *state_channel, *alarm_channel;
    lcm_t *out;
    unsigned char *buf;

    /* input stream */
    int have_last;
    int64_t origin_us; /* utime of engine t = 0 */
    int64_t last_us;   /* utime of the last accepted sample */
    int64_t last_seq;
    double last_rx; /* mono s, arrival of the last accepted sample */
    int64_t gap_us;
    int gap_open; /* the timer saw the input stop; it has not resumed */
    int64_t jump_us; /* 0: no sample is held */
    swaywatch_accel_t held[SW_MON_HELD_MAX]; /* samples far ahead, oldest first */
    double held_rx[SW_MON_HELD_MAX];         /* mono s, their arrival */
    int nheld;

    /* INPUT_REJECTED rate limit, per reason */
    double rej_last_alarm[SW_MON_NREJ]; /* mono s; -INFINITY: never */
    long rej_pending[SW_MON_NREJ];      /* refused since the last alarm for that reason */
    double rej_interval;

    int64_t state_seq, alarm_seq;
    sw_mon_counts_t c;
};

static const char *const reject_names[SW_MON_NREJ] = {
    "decode", "trailing", "nonfinite", "implausible", "skew",
    "duplicate", "out_of_order", "jump", "engine"};

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

/* utime of a time t (s) on the engine's clock. */
static int64_t utime_of(const sw_mon_t *m, double t)
{
    return m->origin_us + (int64_t)llround(t * 1e6);
}

static void send_alarm(sw_mon_t *m, const sw_alarm_t *a, int64_t utime)
{
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
        set_name(msg.name, sizeof msg.name, m->names[a->pkg]);
    msg.kind = (int8_t)a->kind;
    msg.level = (int8_t)a->level;
    set_name(msg.text, sizeof msg.text, a->text);
    /* sw_alarm_t guarantees finite numbers; checked again because a NaN
     * must never be published. */
    msg.theta = isfinite(a->theta) ? a->theta : 0.0;
    msg.margin = isfinite(a->margin) ? a->margin : 0.0;
    publish(m, m->alarm_channel, swaywatch_alarm_t_encode(m->buf, 0, SW_MON_BUF, &msg));
}

static void on_alarm(void *user, const sw_alarm_t *a)
{
    sw_mon_t *m = user;
    send_alarm(m, a, utime_of(m, a->t));
}

static void on_event(void *user, const sw_event_t *ev)
{
    sw_mon_t *m = user;
    if (m->o.on_event)
        m->o.on_event(m->o.user, ev);
    if (ev->pkg < m->n)
        sw_alarm_on_event(&m->watch[ev->pkg], ev, on_alarm, m);
}

static void on_state(void *user, const sw_output_t *out)
{
    sw_mon_t *m = user;
    size_t k = out->pkg;
    if (k >= m->n)
        return;
    if (m->o.on_state)
        m->o.on_state(m->o.user, out);
    sw_alarm_on_output(&m->watch[k], out, on_alarm, m);
    /* Outputs come at sample times (and at the settling steps after the
     * end of a log): t = (utime - origin) / 1e6 maps back exactly. */
    int finite = sw_output_finite(out);
    int64_t utime = finite ? utime_of(m, out->t) : m->last_us;
    if (m->state_period_us > 0) {
        if (utime < m->next_state_us[k])
            return;
        m->next_state_us[k] += m->state_period_us;
        /* After a gap, restart the grid instead of publishing a burst. */
        if (m->next_state_us[k] <= utime)
            m->next_state_us[k] = utime + m->state_period_us;
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
    set_name(msg.name, sizeof msg.name, m->names[k]);
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
    publish(m, m->state_channel, swaywatch_state_t_encode(m->buf, 0, SW_MON_BUF, &msg));
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
    if (m->o.gap == 0.0)
        m->o.gap = SW_MON_GAP;
    if (m->o.max_accel == 0.0)
        m->o.max_accel = SW_MON_MAX_ACCEL;
    if (m->o.max_jump == 0.0)
        m->o.max_jump = SW_MON_MAX_JUMP;
    if (m->o.axis < 0 || m->o.axis > 2 || m->o.vertical < -1 || m->o.vertical > 2 ||
        !(m->o.accel_scale > 0.0) || !(m->o.gap > 0.0) || !(m->o.max_accel > 0.0) ||
        !(m->o.state_rate >= 0.0) || !(m->o.max_skew >= 0.0) || !(m->o.reject_interval >= 0.0) ||
        !isfinite(m->o.gap) || !isfinite(m->o.state_rate) || !(m->o.max_jump < 1e9) ||
        /* in microseconds of int64: a gap beyond 1e9 s or a rate below
         * 1e-9 Hz would overflow */
        !(m->o.gap <= 1e9) || (m->o.state_rate > 0.0 && !(m->o.state_rate >= 1e-9))) {
        if (msg)
            snprintf(msg, msglen, "invalid monitor options");
        free(m);
        return NULL;
    }
    m->state_channel = mo->state_channel ? mo->state_channel : SW_MON_STATE_CHANNEL;
    m->alarm_channel = mo->alarm_channel ? mo->alarm_channel : SW_MON_ALARM_CHANNEL;
    m->out = out;
    m->n = n;
    m->gap_us = (int64_t)llround(m->o.gap * 1e6);
    m->jump_us = m->o.max_jump < 0.0 ? 0 : (int64_t)llround(m->o.max_jump * 1e6);
    m->state_period_us = m->o.state_rate > 0.0 ? (int64_t)llround(1e6 / m->o.state_rate) : 0;
    if (m->o.state_rate > 0.0 && m->state_period_us < 1)
        m->state_period_us = 1;
    m->rej_interval = m->o.reject_interval > 0.0 ? m->o.reject_interval : 1.0;
    for (int r = 0; r < SW_MON_NREJ; r++) m->rej_last_alarm[r] = -INFINITY;

    m->watch = calloc(n ? n : 1, sizeof *m->watch);
    m->names = calloc(n ? n : 1, sizeof *m->names);
    m->next_state_us = calloc(n ? n : 1, sizeof *m->next_state_us);
    m->buf = malloc(SW_MON_BUF);
    if (!m->watch || !m->names || !m->next_state_us || !m->buf)
        goto nomem;

    sw_engine_opts_t e = *eo;
    e.on_event = on_event;
    e.on_state = on_state;
    e.user = m;
    int err = 0;
    m->engine = sw_engine_create(scenes, n, &e, &err, msg, msglen);
    if (!m->engine) {
        sw_mon_destroy(m);
        return NULL;
    }
    for (size_t k = 0; k < n; k++) {
        if (sw_alarm_init(&m->watch[k], k, scenes[k].warn_margin, scenes[k].critical_margin,
                          m->o.hysteresis) != SW_OK) {
            if (msg)
                snprintf(msg, msglen, "%s: alarm thresholds not finite", scenes[k].name);
            sw_mon_destroy(m);
            return NULL;
        }
        snprintf(m->names[k], sizeof m->names[k], "%s", scenes[k].name);
    }
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
    sw_engine_destroy(m->engine);
    free(m->watch);
    free(m->names);
    free(m->next_state_us);
    free(m->buf);
    free(m);
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
    sw_alarm_input(&a, kind, level, m->have_last ? (double)(utime - m->origin_us) / 1e6 : 0.0,
                   text);
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
    static const int code[SW_MON_NREJ] = {SW_EPARSE, SW_EPARSE, SW_ENONFINITE,
                                          SW_ETOOBIG, SW_ETOOBIG, SW_EORDER,
                                          SW_EORDER, SW_EORDER, SW_EINVAL};
    m->c.rejected[r]++;
    m->rej_pending[r]++;
    reject_alarm(m, r, mono, input_utime(m, utime));
    if (why)
        *why = r;
    return code[r];
}

static int accept(sw_mon_t *m, const swaywatch_accel_t *s, double mono, sw_mon_reject *why);
static void drop_held(sw_mon_t *m, int keep, double mono);

int sw_mon_feed(sw_mon_t *m, const void *data, size_t len, int64_t wall_us, double mono,
                sw_mon_reject *why)
{
    swaywatch_accel_t s;
    m->c.received++;
    int used = len <= INT32_MAX ? swaywatch_accel_t_decode(data, 0, (int)len, &s) : -1;
    if (used < 0)
        return refuse(m, SW_MON_REJ_DECODE, mono, wall_us, why);
    /* The generated decoder accepts trailing bytes; a well-formed sender
     * never sends them. */
    if ((size_t)used != len)
        return refuse(m, SW_MON_REJ_TRAILING, mono, wall_us, why);
    if (!isfinite(s.ax) || !isfinite(s.ay) || !isfinite(s.az))
        return refuse(m, SW_MON_REJ_NONFINITE, mono, s.utime, why);
    const double v[3] = {s.ax * m->o.accel_scale, s.ay * m->o.accel_scale, s.az * m->o.accel_scale};
    if (fabs(v[0]) > m->o.max_accel || fabs(v[1]) > m->o.max_accel || fabs(v[2]) > m->o.max_accel)
        return refuse(m, SW_MON_REJ_IMPLAUSIBLE, mono, s.utime, why);
    if (m->o.max_skew > 0.0 && fabs((double)(s.utime - wall_us)) > m->o.max_skew * 1e6)
        return refuse(m, SW_MON_REJ_SKEW, mono, s.utime, why);
    if (m->have_last && s.utime == m->last_us)
        return refuse(m, SW_MON_REJ_DUPLICATE, mono, s.utime, why);
    if (m->have_last && s.utime < m->last_us)
        return refuse(m, SW_MON_REJ_OUT_OF_ORDER, mono, s.utime, why);

    /* Held samples (far from the last accepted one) and the next one s:
     * s on the old timeline refutes them all; s within max_jump of a held
     * one confirms it (the clock did jump), which is taken, then s (or s is
     * refused as late if it is before it), and the other held one is
     * refused; s far from all of them is held as well, the oldest of two
     * refused to make room.  Two places, not one: a glitch that
     * alternates with good samples, or a bad first sample, does not refute
     * the good ones. */
    const int on_old = m->have_last && s.utime - m->last_us <= m->jump_us;
    if (m->jump_us <= 0 || on_old) {
        drop_held(m, -1, mono);
        return accept(m, &s, mono, why);
    }
    for (int i = 0; i < m->nheld; i++) {
        const swaywatch_accel_t h = m->held[i];
        if (s.utime == h.utime)
            return refuse(m, SW_MON_REJ_DUPLICATE, mono, s.utime, why);
        if (llabs(s.utime - h.utime) <= m->jump_us) {
            const double rx = m->held_rx[i];
            drop_held(m, i, mono);
            accept(m, &h, rx, NULL);
            if (s.utime < h.utime)
                return refuse(m, SW_MON_REJ_OUT_OF_ORDER, mono, s.utime, why);
            return accept(m, &s, mono, why);
        }
    }
    if (m->nheld == SW_MON_HELD_MAX) {
        refuse(m, SW_MON_REJ_JUMP, mono, m->held[0].utime, NULL);
        m->held[0] = m->held[1];
        m->held_rx[0] = m->held_rx[1];
        m->nheld--;
    }
    m->held[m->nheld] = s;
    m->held_rx[m->nheld++] = mono;
    return SW_MON_HELD;
}

/* Refuse every held sample as a jump but the one at index keep (-1: all). */
static void drop_held(sw_mon_t *m, int keep, double mono)
{
    for (int i = 0; i < m->nheld; i++)
        if (i != keep) refuse(m, SW_MON_REJ_JUMP, mono, m->held[i].utime, NULL);
    m->nheld = 0;
}

/* Push a checked sample into the engine; its gap and seq bookkeeping. */
static int accept(sw_mon_t *m, const swaywatch_accel_t *sp, double mono, sw_mon_reject *why)
{
    const swaywatch_accel_t s = *sp;
    const double v[3] = {s.ax * m->o.accel_scale, s.ay * m->o.accel_scale, s.az * m->o.accel_scale};
    double a_g = m->o.flip ? -v[m->o.axis] : v[m->o.axis];
    double a_z = m->o.vertical >= 0 ? v[m->o.vertical] : 0.0;
    if (!m->have_last)
        m->origin_us = s.utime;

    /* Gaps: announced before the states of the sample that ends them. */
    char text[SW_ALARM_TEXT_MAX];
    if (m->have_last) {
        double dt = (double)(s.utime - m->last_us) / 1e6;
        if (m->gap_open) {
            snprintf(text, sizeof text,
                     "accel back after %.3f s; %.3f s of input bridged by linear interpolation",
                     mono - m->last_rx, dt);
            input_alarm(m, SW_ALARM_SENSOR_GAP, SW_ALARM_LEVEL_INFO, s.utime, text);
        } else if (s.utime - m->last_us > m->gap_us) {
            m->c.gaps++;
            snprintf(text, sizeof text,
                     "%.3f s between accel samples; bridged by linear interpolation", dt);
            input_alarm(m, SW_ALARM_SENSOR_GAP, SW_ALARM_LEVEL_WARN, s.utime, text);
        }
    }
    m->gap_open = 0;

    if (!m->have_last)
        for (size_t k = 0; k < m->n; k++) m->next_state_us[k] = s.utime;
    int rc = sw_engine_push(m->engine, (double)(s.utime - m->origin_us) / 1e6, a_g, a_z);
    if (rc < 0)
        return refuse(m, SW_MON_REJ_ENGINE, mono, s.utime, why);

    if (m->have_last) {
        if (s.seq > m->last_seq + 1)
            m->c.lost += (long)(s.seq - m->last_seq - 1);
        else if (s.seq <= m->last_seq)
            m->c.seq_restarts++;
    }
    m->have_last = 1;
    m->last_us = s.utime;
    m->last_seq = s.seq;
    m->last_rx = mono;
    m->c.accepted++;
    return rc;
}

double sw_mon_deadline(const sw_mon_t *m)
{
    double d = INFINITY;
    if (m->have_last && !m->gap_open)
        d = m->last_rx + m->o.gap;
    for (int r = 0; r < SW_MON_NREJ; r++)
        if (m->rej_pending[r] > 0 && m->rej_last_alarm[r] + m->rej_interval < d)
            d = m->rej_last_alarm[r] + m->rej_interval;
    return d;
}

void sw_mon_tick(sw_mon_t *m, double mono)
{
    if (m->have_last && !m->gap_open && mono - m->last_rx > m->o.gap) {
        char text[SW_ALARM_TEXT_MAX];
        double waited = mono - m->last_rx;
        m->gap_open = 1;
        m->c.gaps++;
        snprintf(text, sizeof text, "no accel sample for %.3f s", waited);
        input_alarm(m, SW_ALARM_SENSOR_GAP, SW_ALARM_LEVEL_WARN,
                    m->last_us + (int64_t)llround(waited * 1e6), text);
    }
    for (int r = 0; r < SW_MON_NREJ; r++) reject_alarm(m, (sw_mon_reject)r, mono, m->last_us);
}

void sw_mon_flush(sw_mon_t *m)
{
    drop_held(m, -1, INFINITY);
    for (int r = 0; r < SW_MON_NREJ; r++) reject_alarm(m, (sw_mon_reject)r, INFINITY, m->last_us);
}

void sw_mon_counts(const sw_mon_t *m, sw_mon_counts_t *c)
{
    *c = m->c;
    c->held = m->nheld;
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
    return m->have_last ? m->origin_us : 0;
}

int64_t sw_mon_last_utime(const sw_mon_t *m)
{
    return m->have_last ? m->last_us : 0;
}

int sw_mon_replace(sw_mon_t *m, size_t k, const sw_scene_t *scene, char *msg, size_t msglen)
{
    sw_alarm_watch_t w;
    if (!m || !scene || k >= m->n) {
        if (msg)
            snprintf(msg, msglen, "no such package");
        return SW_EINVAL;
    }
    if (sw_alarm_init(&w, k, scene->warn_margin, scene->critical_margin, m->o.hysteresis) !=
        SW_OK) {
        if (msg)
            snprintf(msg, msglen, "%s: alarm thresholds not finite", scene->name);
        return SW_EINVAL;
    }
    int rc = sw_engine_replace(m->engine, k, scene, msg, msglen);
    if (rc != SW_OK)
        return rc;
    m->watch[k] = w;
    snprintf(m->names[k], sizeof m->names[k], "%s", scene->name);
    return SW_OK;
}
