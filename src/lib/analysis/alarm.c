/* SPDX-License-Identifier: GPL-3.0-or-later */
/* alarm.c - alarms from engine events, margins and the reserve, with
 * hysteresis, and the helpers that make margins and impacts read right
 * (alarm.h).  Pure: no I/O, no allocation, no globals. */
#include "swaywatch/alarm.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_traits.h"
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
    w->reserve_warn_armed = w->reserve_critical_armed = 1;
    return SW_OK;
}

int sw_alarm_set_reserve(sw_alarm_watch_t *w, double warn_g, double critical_g, double hysteresis_g)
{
    if (!w || !isfinite(warn_g) || !isfinite(critical_g) || !isfinite(hysteresis_g))
        return SW_EINVAL;
    if (warn_g != 0.0 && !(warn_g > 0.0 && critical_g > 0.0 && critical_g < warn_g))
        return SW_EINVAL;
    w->warn_reserve_g = warn_g;
    w->critical_reserve_g = warn_g != 0.0 ? critical_g : 0.0;
    w->reserve_hysteresis_g = hysteresis_g < 0.0 ? SW_ALARM_RESERVE_HYSTERESIS_G : hysteresis_g;
    w->reserve_warn_armed = w->reserve_critical_armed = 1;
    return SW_OK;
}

int sw_alarm_set_impact_min(sw_alarm_watch_t *w, double min_speed)
{
    if (!w || !isfinite(min_speed) || min_speed < 0.0)
        return SW_EINVAL;
    w->impact_min = min_speed;
    return SW_OK;
}

int sw_alarm_set_plane(sw_alarm_watch_t *w, sw_plane plane)
{
    if (!w || (plane != SW_PLANE_LONG && plane != SW_PLANE_LAT))
        return SW_EINVAL;
    w->plane = plane;
    return SW_OK;
}

int sw_alarm_init_scene(sw_alarm_watch_t *w, size_t pkg, const sw_scene_t *sc, double hysteresis)
{
    sw_derived_t d;
    if (!w || !sc || sw_scene_validate(sc, &d, NULL, NULL, NULL) != SW_OK)
        return SW_EINVAL;
    int rc = sw_alarm_init(w, pkg, sc->warn_margin, sc->critical_margin, hysteresis);
    if (rc == SW_OK)
        rc = sw_alarm_set_reserve(w, sc->warn_reserve_g, sc->critical_reserve_g, -1.0);
    if (rc == SW_OK)
        rc = sw_alarm_set_impact_min(w, SW_IMPACT_SIGNIFICANCE * sw_impact_tip_speed(&d, sc->g));
    return rc;
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
    a.plane = w->plane;
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
    /* across the truck, every text says so: theta > 0 is the top to the
     * left (physics.md, "The lateral plane") */
    const int lat = w->plane == SW_PLANE_LAT;
    const char *const side = lat ? " sideways" : "";

    switch (ev->kind) {
        case SW_EV_UPLIFT:
            kind = SW_ALARM_UPLIFT;
            snprintf(text, sizeof text, "corner lifted: rocking %s",
                     lat ? (ev->info >= 0.0 ? "sideways, to the left" : "sideways, to the right")
                         : (ev->info >= 0.0 ? "forward" : "backward"));
            break;
        case SW_EV_IMPACT:
            if (w->impact_min > 0.0 && !(fabs(ev->info) >= w->impact_min))
                return 0; /* a micro-impact: below the significance */
            kind = SW_ALARM_IMPACT;
            snprintf(text, sizeof text, "impact%s at %.4g rad/s", side, finite_or_zero(ev->info));
            break;
        case SW_EV_REST:
            kind = SW_ALARM_REST;
            snprintf(text, sizeof text, "back to rest%s", lat ? " after rocking sideways" : "");
            break;
        case SW_EV_TIP:
            kind = SW_ALARM_TIP;
            level = SW_ALARM_LEVEL_CRITICAL;
            snprintf(text, sizeof text, "%scentre of mass over the corner (|theta| = alpha)",
                     lat ? "tipping sideways: " : "");
            break;
        case SW_EV_OVERTURN:
            kind = SW_ALARM_OVERTURNED;
            level = SW_ALARM_LEVEL_CRITICAL;
            snprintf(text, sizeof text, "overturned%s (|theta| = pi/2)", side);
            break;
        case SW_EV_FAULT:
            kind = SW_ALARM_MODEL_FAULT;
            level = SW_ALARM_LEVEL_CRITICAL;
            snprintf(text, sizeof text, "model fault%s: %s; package reset to rest", side,
                     sw_strerror(isfinite(ev->info) ? (int)ev->info : SW_EFAULT));
            break;
        case SW_EV_FLIGHT:
            /* the model cannot say where it lands: fail safe */
            kind = SW_ALARM_MODEL_FAULT;
            level = SW_ALARM_LEVEL_CRITICAL;
            snprintf(text, sizeof text,
                     "in free flight for over %g s%s: the landing is outside the model",
                     SW_FLIGHT_LONG, side);
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

/* "WHAT X UNIT< LEVEL Y UNIT" for x below y, into text: both with three
 * decimals, as many more as it takes (up to nine) for the numbers printed
 * to compare as x and y do; "margin 0.200 < critical 0.200" was printed
 * for a margin of 0.19996.  The alarm itself compares x and y exactly: no
 * rounding delays it. */
static void below_text(char *text, size_t len, const char *what, double x, const char *level,
                       double y, const char *unit)
{
    char a[64], b[64];
    int d = 3;
    for (; d < 9; d++) {
        snprintf(a, sizeof a, "%.*f", d, x);
        snprintf(b, sizeof b, "%.*f", d, y);
        if (strtod(a, NULL) < strtod(b, NULL))
            break;
    }
    snprintf(text, len, "%s %.*f%s < %s %.*f%s", what, d, x, unit, level, d, y, unit);
}

/* What a margin or reserve alarm measures, in the watch's plane. */
static const char *margin_word(const sw_alarm_watch_t *w)
{
    return w->plane == SW_PLANE_LAT ? "margin sideways" : "margin";
}

static const char *reserve_word(const sw_alarm_watch_t *w)
{
    return w->plane == SW_PLANE_LAT ? "reserve sideways" : "reserve";
}

int sw_alarm_on_output(sw_alarm_watch_t *w, const sw_output_t *o, sw_alarm_fn emit, void *user)
{
    char text[SW_ALARM_TEXT_MAX];
    int n = 0;

    if (!sw_output_finite(o)) {
        if (!w->fault_armed)
            return 0;
        w->fault_armed = 0;
        return emit_alarm(
            w, SW_ALARM_MODEL_FAULT, SW_ALARM_LEVEL_CRITICAL, o->t, o->state.theta, o->margin,
            w->plane == SW_PLANE_LAT ? "model output not finite sideways; state withheld"
                                     : "model output not finite; state withheld",
            emit, user);
    }
    w->fault_armed = 1;

    if (crossed(&w->warn_armed, o->margin, w->warn_margin, w->hysteresis)) {
        below_text(text, sizeof text, margin_word(w), o->margin, "warn", w->warn_margin, "");
        n += emit_alarm(w, SW_ALARM_WARN, SW_ALARM_LEVEL_WARN, o->t, o->state.theta, o->margin,
                        text, emit, user);
    }
    if (crossed(&w->critical_armed, o->margin, w->critical_margin, w->hysteresis)) {
        below_text(text, sizeof text, margin_word(w), o->margin, "critical", w->critical_margin,
                   "");
        n += emit_alarm(w, SW_ALARM_CRITICAL, SW_ALARM_LEVEL_CRITICAL, o->t, o->state.theta,
                        o->margin, text, emit, user);
    }
    return n;
}

int sw_alarm_on_reserve(sw_alarm_watch_t *w, double t, double theta, double margin,
                        double reserve_g, sw_alarm_fn emit, void *user)
{
    char text[SW_ALARM_TEXT_MAX];
    int n = 0;
    if (!w || !(w->warn_reserve_g > 0.0))
        return 0;
    if (crossed(&w->reserve_warn_armed, reserve_g, w->warn_reserve_g, w->reserve_hysteresis_g)) {
        below_text(text, sizeof text, reserve_word(w), reserve_g, "warn", w->warn_reserve_g, " g");
        n += emit_alarm(w, SW_ALARM_RESERVE_WARN, SW_ALARM_LEVEL_WARN, t, theta, margin, text, emit,
                        user);
    }
    if (crossed(&w->reserve_critical_armed, reserve_g, w->critical_reserve_g,
                w->reserve_hysteresis_g)) {
        below_text(text, sizeof text, reserve_word(w), reserve_g, "critical", w->critical_reserve_g,
                   " g");
        n += emit_alarm(w, SW_ALARM_RESERVE_CRITICAL, SW_ALARM_LEVEL_CRITICAL, t, theta, margin,
                        text, emit, user);
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
    a->plane = SW_PLANE_LONG;
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
        case SW_ALARM_RESERVE_WARN: return "reserve_warn";
        case SW_ALARM_RESERVE_CRITICAL: return "reserve_critical";
        case SW_ALARM_INPUT_CONTESTED: return "input_contested";
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

/* ---- margins and impacts that read right ---------------------------------- */

double sw_impact_tip_speed(const sw_derived_t *d, double g)
{
    /* a model without an impact map (the cushion) lands without impacts */
    const sw_model_traits_t *m = d ? sw_model_traits_of(d->model) : NULL;
    if (!m || !m->impacts || !(g > 0.0))
        return 0.0;
    /* 1/2 I_O w^2 = m g R (1 - cos a) with p^2 = m g R / I_O:
     * w = p sqrt(2 (1 - cos a)) = 2 p sin(a/2); p at this g */
    const double p = sqrt(3.0 * g / (4.0 * d->R)); /* rad/s */
    return 2.0 * p * sin(0.5 * d->alpha);
}

int sw_impact_significant(const sw_derived_t *d, double g, double theta_dot_before, double fraction)
{
    return fabs(theta_dot_before) >= fraction * sw_impact_tip_speed(d, g);
}

double sw_margin_presented(double margin, sw_phase phase)
{
    if (phase == SW_PHASE_OVERTURNED)
        return -1.0;
    if (isnan(margin))
        return margin;
    if (margin >= 0.0)
        return margin > 1.0 ? 1.0 : margin;
    /* expm1: exact near 0 (the sign change stays where it is), -1 only in
     * the limit, so the overturn itself is the first -1 */
    return expm1(margin);
}

void sw_settle_init(sw_settle_t *s, double min_speed)
{
    memset(s, 0, sizeof *s);
    s->min_speed = min_speed;
}

static int settle_close(sw_settle_t *s, sw_settle_span_t *closed)
{
    if (!s->open)
        return 0;
    if (closed)
        *closed = s->span;
    s->open = 0;
    return SW_SETTLE_CLOSED;
}

int sw_settle_feed(sw_settle_t *s, const sw_event_t *ev, sw_settle_span_t *closed)
{
    if (ev->kind == SW_EV_IMPACT && fabs(ev->info) < s->min_speed) {
        const double v = fabs(ev->info); /* rad/s */
        if (!s->open) {
            s->open = 1;
            s->span.t_start = ev->t;
            s->span.impacts = 0;
            s->span.max_speed = 0.0;
        }
        s->span.t_end = ev->t;
        s->span.impacts++;
        if (v > s->span.max_speed)
            s->span.max_speed = v;
        return 0;
    }
    return settle_close(s, closed) | SW_SETTLE_REPORT;
}

int sw_settle_finish(sw_settle_t *s, sw_settle_span_t *closed)
{
    return settle_close(s, closed) ? 1 : 0;
}
