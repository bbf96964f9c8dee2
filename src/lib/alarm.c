/* alarm.c - alarms from engine events and margins, with hysteresis
 * (alarm.h).  Pure: no I/O, no allocation, no globals. */
#include "swaywatch/alarm.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "swaywatch/status.h"

int sw_alarm_init(sw_alarm_watch_t *w, size_t pkg, double warn_margin, double critical_margin,
                  double hysteresis)
{
    if (!w || !isfinite(warn_margin) || !isfinite(critical_margin) || !isfinite(hysteresis))
        return SW_EINVAL;
    memset(w, 0, sizeof *w);
    w->pkg = pkg;
    w->warn_margin = warn_margin;
    w->critical_margin = critical_margin;
    w->hysteresis = hysteresis < 0.0 ? SW_ALARM_HYSTERESIS : hysteresis;
    w->warn_armed = w->critical_armed = w->fault_armed = 1;
    return SW_OK;
}

/* Alarms are published as they are: a NaN must never leave the process. */
static double finite_or_zero(double x)
{
    return isfinite(x) ? x : 0.0;
}

static int emit_alarm(sw_alarm_watch_t *w, sw_alarm_kind kind, sw_alarm_level level, double t,
                      double theta, double margin, const char *text, sw_alarm_fn emit, void *user)
{
    sw_alarm_t a;
    a.pkg = w->pkg;
    a.kind = kind;
    a.level = level;
    a.t = finite_or_zero(t);
    a.theta = finite_or_zero(theta);
    a.margin = finite_or_zero(margin);
    snprintf(a.text, sizeof a.text, "%s", text);
    w->raised++;
    if (emit)
        emit(user, &a);
    return 1;
}

int sw_alarm_on_event(sw_alarm_watch_t *w, const sw_event_t *ev, sw_alarm_fn emit, void *user)
{
    char text[SW_ALARM_TEXT_MAX];
    sw_alarm_kind kind;
    sw_alarm_level level = SW_ALARM_LEVEL_INFO;

    switch (ev->kind) {
        case SW_EV_UPLIFT:
            kind = SW_ALARM_UPLIFT;
            snprintf(text, sizeof text, "corner lifted: rocking %s",
                     ev->info >= 0.0 ? "forward" : "backward");
            break;
        case SW_EV_IMPACT:
            kind = SW_ALARM_IMPACT;
            snprintf(text, sizeof text, "impact at %.4g rad/s", finite_or_zero(ev->info));
            break;
        case SW_EV_REST:
            kind = SW_ALARM_REST;
            snprintf(text, sizeof text, "back to rest");
            break;
        case SW_EV_TIP:
            kind = SW_ALARM_TIP;
            level = SW_ALARM_LEVEL_CRITICAL;
            snprintf(text, sizeof text, "centre of mass over the corner (|theta| = alpha)");
            break;
        case SW_EV_OVERTURN:
            kind = SW_ALARM_OVERTURNED;
            level = SW_ALARM_LEVEL_CRITICAL;
            snprintf(text, sizeof text, "overturned (|theta| = pi/2)");
            break;
        case SW_EV_FAULT:
            kind = SW_ALARM_MODEL_FAULT;
            level = SW_ALARM_LEVEL_CRITICAL;
            snprintf(text, sizeof text, "model fault: %s; package reset to rest",
                     sw_strerror(isfinite(ev->info) ? (int)ev->info : SW_EFAULT));
            break;
        default: return 0;
    }
    return emit_alarm(w, kind, level, ev->t, ev->theta, ev->margin, text, emit, user);
}

int sw_alarm_output_finite(const sw_output_t *o)
{
    return sw_output_finite(o);
}

/* One threshold with hysteresis: fires on the way down while armed, re-arms
 * above threshold + hysteresis.  A NaN margin neither fires nor re-arms. */
static int crossed(int *armed, double margin, double threshold, double hysteresis)
{
    if (*armed && margin < threshold) {
        *armed = 0;
        return 1;
    }
    if (!*armed && margin > threshold + hysteresis)
        *armed = 1;
    return 0;
}

int sw_alarm_on_output(sw_alarm_watch_t *w, const sw_output_t *o, sw_alarm_fn emit, void *user)
{
    char text[SW_ALARM_TEXT_MAX];
    int n = 0;

    if (!sw_output_finite(o)) {
        if (!w->fault_armed)
            return 0;
        w->fault_armed = 0;
        return emit_alarm(w, SW_ALARM_MODEL_FAULT, SW_ALARM_LEVEL_CRITICAL, o->t, o->state.theta,
                          o->margin, "model output not finite; state withheld", emit, user);
    }
    w->fault_armed = 1;

    if (crossed(&w->warn_armed, o->margin, w->warn_margin, w->hysteresis)) {
        snprintf(text, sizeof text, "margin %.3f < warn %.3f", o->margin, w->warn_margin);
        n += emit_alarm(w, SW_ALARM_WARN, SW_ALARM_LEVEL_WARN, o->t, o->state.theta, o->margin,
                        text, emit, user);
    }
    if (crossed(&w->critical_armed, o->margin, w->critical_margin, w->hysteresis)) {
        snprintf(text, sizeof text, "margin %.3f < critical %.3f", o->margin, w->critical_margin);
        n += emit_alarm(w, SW_ALARM_CRITICAL, SW_ALARM_LEVEL_CRITICAL, o->t, o->state.theta,
                        o->margin, text, emit, user);
    }
    return n;
}

void sw_alarm_input(sw_alarm_t *a, sw_alarm_kind kind, sw_alarm_level level, double t,
                    const char *text)
{
    a->pkg = SW_ALARM_ALL;
    a->kind = kind;
    a->level = level;
    a->t = finite_or_zero(t);
    a->theta = 0.0;
    a->margin = 0.0;
    snprintf(a->text, sizeof a->text, "%s", text ? text : "");
}

const char *sw_alarm_kind_name(sw_alarm_kind k)
{
    switch (k) {
        case SW_ALARM_UPLIFT: return "uplift";
        case SW_ALARM_IMPACT: return "impact";
        case SW_ALARM_WARN: return "warn";
        case SW_ALARM_CRITICAL: return "critical";
        case SW_ALARM_TIP: return "tip";
        case SW_ALARM_OVERTURNED: return "overturned";
        case SW_ALARM_REST: return "rest";
        case SW_ALARM_MODEL_FAULT: return "model_fault";
        case SW_ALARM_SENSOR_GAP: return "sensor_gap";
        case SW_ALARM_INPUT_REJECTED: return "input_rejected";
    }
    return "unknown";
}

const char *sw_alarm_level_name(sw_alarm_level l)
{
    switch (l) {
        case SW_ALARM_LEVEL_INFO: return "info";
        case SW_ALARM_LEVEL_WARN: return "warn";
        case SW_ALARM_LEVEL_CRITICAL: return "critical";
    }
    return "unknown";
}
