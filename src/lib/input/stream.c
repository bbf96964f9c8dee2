/* SPDX-License-Identifier: GPL-3.0-or-later */
/* stream.c - one input path (stream.h): the gate in front of the engine,
 * each output into the reserve and the alarm watches; while two
 * timelines compete, a second gate and set of engines for the other one,
 * whose alarms from WARN up are raised too.  Every part is made at
 * create; a sample allocates nothing. */
#include "swaywatch/stream.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/status.h"

struct sw_stream {
    size_t n;
    sw_engine_t *engine;
    sw_gate_t *gate;
    sw_risk_t *risk;
    sw_alarm_watch_t *watch; /* one per package */
    char (*names)[SW_NAME_MAX];
    int alarms; /* on_alarm given: the watches run */
    /* the second timeline (opts.rival): its gate, engines and watches, no
     * reserve; fresh: the watches as set up, for each new contest */
    sw_gate_t *gate_b;
    sw_engine_t *engine_b;
    sw_alarm_watch_t *watch_b, *watch_fresh;
    double hysteresis;
    sw_stream_opts_t o;
    /* the lateral planes (o.engine.lateral): the reserve of each, on the
     * packages with a depth, whose index there lat_of says */
    sw_risk_t *risk_lat;
    size_t *lat_of;
    /* their alarm watches (on_alarm given), per package (used for those
     * with a lateral plane), set up from the lateral scenes: the lateral
     * plane's alarms are raised apart and named so (alarm.h); the second
     * timeline's and its fresh copies too */
    sw_alarm_watch_t *watch_lat, *watch_lat_b, *watch_lat_fresh;
};

#define NO_LAT ((size_t)-1)

/* ---- the kept timeline ------------------------------------------------------------ */

static void on_alarm(void *user, const sw_alarm_t *a)
{
    const sw_stream_t *st = user;
    st->o.on_alarm(st->o.user, a, sw_gate_source_time(st->gate, a->t));
}

/* The watch of a package's plane: each plane has its own (a lateral
 * plane's alarms are never the other's, nor silenced by it); NULL when
 * alarms are off. */
static sw_alarm_watch_t *watch_of(sw_alarm_watch_t *lon, sw_alarm_watch_t *lat, size_t k,
                                  sw_plane plane)
{
    if (plane == SW_PLANE_LONG)
        return lon ? &lon[k] : NULL;
    return plane == SW_PLANE_LAT && lat ? &lat[k] : NULL;
}

static void on_event(void *user, const sw_event_t *ev)
{
    sw_stream_t *st = user;
    if (st->o.on_event)
        st->o.on_event(st->o.user, ev);
    sw_alarm_watch_t *w = st->alarms && ev->pkg < st->n
                              ? watch_of(st->watch, st->watch_lat, ev->pkg, ev->plane)
                              : NULL;
    if (w)
        sw_alarm_on_event(w, ev, on_alarm, st);
}

/* The reserve of a package's plane, and the package's index in it (the
 * lateral planes' reserve holds only the packages with a depth); NULL
 * where the plane has none. */
static sw_risk_t *risk_of(const sw_stream_t *st, size_t k, sw_plane plane, size_t *j)
{
    *j = k;
    if (plane == SW_PLANE_LONG)
        return st->risk;
    *j = st->lat_of ? st->lat_of[k] : NO_LAT;
    return plane == SW_PLANE_LAT && *j != NO_LAT ? st->risk_lat : NULL;
}

/* The reserve first, then the alarms: the caller's state carries both.
 * Each plane has its own reserve and its own watch. */
static void on_state(void *user, const sw_output_t *out)
{
    sw_stream_t *st = user;
    const size_t k = out->pkg;
    if (k >= st->n)
        return;
    size_t j = k;
    sw_risk_t *risk = risk_of(st, k, out->plane, &j);
    sw_alarm_watch_t *w = st->alarms ? watch_of(st->watch, st->watch_lat, k, out->plane) : NULL;
    if (risk && sw_output_finite(out)) {
        sw_output_t in_risk;
        const sw_output_t *q = out;
        if (j != k) { /* the package as the reserve numbers it */
            in_risk = *out;
            in_risk.pkg = j;
            q = &in_risk;
        }
        if (sw_risk_output(risk, q) == 1 && w)
            sw_alarm_on_reserve(w, out->t, out->state.theta, out->margin,
                                sw_risk_pkg(risk, j)->reserve_g, on_alarm, st);
    }
    if (w)
        sw_alarm_on_output(w, out, on_alarm, st);
    if (st->o.on_state)
        st->o.on_state(st->o.user, out);
}

/* ---- the second timeline ----------------------------------------------------------- */

/* An alarm of the second engines: from WARN up it is raised as the first's
 * are, saying where it comes from, timed by the second gate. */
static void on_alarm_b(void *user, const sw_alarm_t *a)
{
    const sw_stream_t *st = user;
    if (a->level < SW_ALARM_LEVEL_WARN)
        return;
    sw_alarm_t b = *a;
    static const char head[] = "second timeline: ";
    size_t tl = strlen(a->text);
    if (tl > sizeof b.text - sizeof head)
        tl = sizeof b.text - sizeof head; /* cut to fit */
    memcpy(b.text, head, sizeof head - 1);
    memcpy(b.text + sizeof head - 1, a->text, tl);
    b.text[sizeof head - 1 + tl] = '\0';
    st->o.on_alarm(st->o.user, &b, sw_gate_source_time(st->gate_b, a->t));
}

static void on_event_b(void *user, const sw_event_t *ev)
{
    sw_stream_t *st = user;
    sw_alarm_watch_t *w = st->alarms && ev->pkg < st->n
                              ? watch_of(st->watch_b, st->watch_lat_b, ev->pkg, ev->plane)
                              : NULL;
    if (w)
        sw_alarm_on_event(w, ev, on_alarm_b, st);
}

static void on_state_b(void *user, const sw_output_t *out)
{
    sw_stream_t *st = user;
    sw_alarm_watch_t *w = st->alarms && out->pkg < st->n
                              ? watch_of(st->watch_b, st->watch_lat_b, out->pkg, out->plane)
                              : NULL;
    if (w && sw_output_finite(out))
        sw_alarm_on_output(w, out, on_alarm_b, st);
}

/* A sample of the second timeline (the first gate counted it as refused). */
static void on_rival(void *user, const sw_sample_t *s)
{
    const sw_stream_t *st = user;
    sw_gate_push(st->gate_b, s);
}

/* ---- the gate's reports -------------------------------------------------------------- */

static void on_gate_event(void *user, const sw_gate_event_t *ev)
{
    sw_stream_t *st = user;
    if (ev->kind == SW_GATE_EV_CONTESTED && st->engine_b) {
        /* a contest begins: the second engines start afresh, at rest */
        sw_engine_reset(st->engine_b);
        sw_gate_reset(st->gate_b);
        memcpy(st->watch_b, st->watch_fresh, st->n * sizeof *st->watch_b);
        if (st->watch_lat_b)
            memcpy(st->watch_lat_b, st->watch_lat_fresh, st->n * sizeof *st->watch_lat_b);
    }
    if (st->o.on_input)
        st->o.on_input(st->o.user, ev);
}

static void on_gate_reject(void *user, const sw_sample_t *s, sw_gate_reject r, const char *text)
{
    const sw_stream_t *st = user;
    if (st->o.on_reject)
        st->o.on_reject(st->o.user, s, r, text);
}

static void on_gate_take(void *user, double t, double a_g, double a_z, int restart)
{
    const sw_stream_t *st = user;
    st->o.on_take(st->o.user, t, a_g, a_z, restart);
}

static void on_gate_take_lat(void *user, double t, double a_g, double a_y, double a_z, int restart)
{
    const sw_stream_t *st = user;
    st->o.on_take_lat(st->o.user, t, a_g, a_y, a_z, restart);
}

/* ---- create, destroy ------------------------------------------------------------- */

static void fail(int code, int *err, char *msg, size_t msglen, const char *why)
{
    if (err)
        *err = code;
    if (msg && msglen && why)
        snprintf(msg, msglen, "%s", why);
}

/* The alarm watch of package k's lateral plane, from its lateral scene
 * (its own alpha, impact significance; the scene's levels), into w.
 * SW_OK (nothing for a package without a depth) or SW_EINVAL. */
static int watch_lat_init(sw_alarm_watch_t *w, size_t k, const sw_scene_t *sc, double hysteresis)
{
    sw_scene_t lat;
    memset(w, 0, sizeof *w);
    if (!sw_scene_has_depth(sc))
        return SW_OK;
    if (sw_scene_lateral(sc, &lat) != SW_OK || sw_alarm_init_scene(w, k, &lat, hysteresis) != SW_OK)
        return SW_EINVAL;
    return sw_alarm_set_plane(w, SW_PLANE_LAT);
}

/* The lateral planes' watches (alarms on and lateral planes made). */
static int make_watch_lat(sw_stream_t *st, const sw_scene_t *scenes, size_t n)
{
    const size_t m = n ? n : 1;
    if (!(st->watch_lat = calloc(m, sizeof *st->watch_lat)))
        return SW_ENOMEM;
    for (size_t k = 0; k < n; k++)
        if (watch_lat_init(&st->watch_lat[k], k, &scenes[k], st->hysteresis) != SW_OK)
            return SW_EINVAL;
    if (!st->o.rival)
        return SW_OK;
    st->watch_lat_b = calloc(m, sizeof *st->watch_lat_b);
    st->watch_lat_fresh = calloc(m, sizeof *st->watch_lat_fresh);
    if (!st->watch_lat_b || !st->watch_lat_fresh)
        return SW_ENOMEM;
    memcpy(st->watch_lat_b, st->watch_lat, n * sizeof *st->watch_lat);
    memcpy(st->watch_lat_fresh, st->watch_lat, n * sizeof *st->watch_lat);
    return SW_OK;
}

/* The reserve of the lateral planes: a risk over the lateral scenes
 * (sw_scene_lateral) of the packages with a depth, the design pulses
 * applied across the truck.  Nothing without a depth or a reserve. */
static int make_risk_lat(sw_stream_t *st, const sw_scene_t *scenes, size_t n,
                         const sw_risk_opts_t *ro, char *msg, size_t msglen)
{
    size_t m = 0;
    for (size_t k = 0; k < n; k++) m += sw_scene_has_depth(&scenes[k]) != 0;
    if (m == 0 || ro->reserve_rate < 0.0)
        return SW_OK;
    sw_scene_t *lat = calloc(m, sizeof *lat);
    st->lat_of = calloc(n, sizeof *st->lat_of);
    if (!lat || !st->lat_of) {
        free(lat);
        if (msg && msglen)
            snprintf(msg, msglen, "%s", sw_strerror(SW_ENOMEM));
        return SW_ENOMEM;
    }
    for (size_t k = 0, j = 0; k < n; k++) {
        st->lat_of[k] = NO_LAT;
        if (sw_scene_lateral(&scenes[k], &lat[j]) == SW_OK)
            st->lat_of[k] = j++;
    }
    int e = SW_OK;
    st->risk_lat = sw_risk_create(lat, m, ro, &e, msg, msglen);
    free(lat);
    return st->risk_lat ? SW_OK : e != SW_OK ? e : SW_ENOMEM;
}

sw_stream_t *sw_stream_create(const sw_scene_t *scenes, size_t n, const sw_stream_opts_t *o,
                              int *err, char *msg, size_t msglen)
{
    static const sw_stream_opts_t defaults = {.hysteresis = -1.0};
    int e = SW_OK;
    if (err)
        *err = SW_OK;
    if (msg && msglen)
        msg[0] = '\0';
    if (!o)
        o = &defaults;
    if (!scenes && n > 0) {
        fail(SW_EINVAL, err, msg, msglen, "no scenes");
        return NULL;
    }
    sw_stream_t *st = calloc(1, sizeof *st);
    if (!st) {
        fail(SW_ENOMEM, err, msg, msglen, sw_strerror(SW_ENOMEM));
        return NULL;
    }
    st->o = *o;
    st->n = n;
    st->alarms = o->on_alarm != NULL;
    st->hysteresis = o->hysteresis;
    const size_t m = n ? n : 1;
    st->watch = calloc(m, sizeof *st->watch);
    st->names = calloc(m, sizeof *st->names);
    if (!st->watch || !st->names)
        goto nomem;
    for (size_t k = 0; k < n; k++) {
        if (sw_alarm_init_scene(&st->watch[k], k, &scenes[k], o->hysteresis) != SW_OK) {
            char why[SW_NAME_MAX + 40];
            snprintf(why, sizeof why, "%s: alarm thresholds not finite", scenes[k].name);
            fail(SW_EINVAL, err, msg, msglen, why);
            sw_stream_destroy(st);
            return NULL;
        }
        snprintf(st->names[k], sizeof st->names[k], "%s", scenes[k].name);
    }

    /* The engine reports to the stream; outputs only when someone reads
     * them (a caller's state, the reserve, the alarms): an engine without
     * a state callback need not compute them after every sample. */
    sw_engine_opts_t eo = o->engine;
    eo.on_event = on_event;
    eo.on_state = o->on_state || st->alarms || !(o->risk.reserve_rate < 0.0) ? on_state : NULL;
    eo.user = st;
    if (!(st->engine = sw_engine_create(scenes, n, &eo, &e, msg, msglen)))
        goto failed;
    sw_gate_opts_t go = o->gate;
    go.lateral = eo.lateral; /* an engine with lateral planes takes samples with a_y */
    go.on_event = on_gate_event;
    go.on_reject = on_gate_reject;
    go.on_take = o->on_take ? on_gate_take : NULL;
    go.on_take_lat = o->on_take_lat ? on_gate_take_lat : NULL;
    go.on_rival = o->rival ? on_rival : NULL;
    go.user = st;
    if (!(st->gate = sw_gate_create(st->engine, &go, msg, msglen))) {
        e = SW_EINVAL;
        goto failed;
    }
    if (o->rival) {
        /* the second timeline: the same scenes and checks (not the wall
         * clock's: its samples were checked by the first gate), nothing
         * reported but its alarms */
        st->watch_b = calloc(m, sizeof *st->watch_b);
        st->watch_fresh = calloc(m, sizeof *st->watch_fresh);
        if (!st->watch_b || !st->watch_fresh)
            goto nomem;
        memcpy(st->watch_fresh, st->watch, n * sizeof *st->watch);
        memcpy(st->watch_b, st->watch, n * sizeof *st->watch);
        sw_engine_opts_t eb = o->engine;
        eb.on_event = on_event_b;
        eb.on_state = on_state_b;
        eb.user = st;
        sw_gate_opts_t gb = o->gate;
        gb.max_skew = 0.0;
        gb.on_event = NULL;
        gb.on_reject = NULL;
        gb.on_take = NULL;
        gb.on_take_lat = NULL;
        gb.on_rival = NULL;
        gb.user = NULL;
        gb.lateral = eb.lateral;
        if (!(st->engine_b = sw_engine_create(scenes, n, &eb, &e, msg, msglen)))
            goto failed;
        if (!(st->gate_b = sw_gate_create(st->engine_b, &gb, msg, msglen))) {
            e = SW_EINVAL;
            goto failed;
        }
    }
    if (!(st->risk = sw_risk_create(scenes, n, &o->risk, &e, msg, msglen)))
        goto failed;
    if (eo.lateral && (e = make_risk_lat(st, scenes, n, &o->risk, msg, msglen)) != SW_OK)
        goto failed;
    if (eo.lateral && st->alarms && (e = make_watch_lat(st, scenes, n)) != SW_OK) {
        if (e == SW_ENOMEM)
            goto nomem;
        fail(e, err, msg, msglen, "a lateral plane's alarm thresholds are not valid");
        sw_stream_destroy(st);
        return NULL;
    }
    return st;

nomem:
    e = SW_ENOMEM;
    if (msg && msglen)
        snprintf(msg, msglen, "%s", sw_strerror(SW_ENOMEM));
failed:
    if (err)
        *err = e != SW_OK ? e : SW_ENOMEM;
    sw_stream_destroy(st);
    return NULL;
}

void sw_stream_destroy(sw_stream_t *st)
{
    if (!st)
        return;
    sw_gate_destroy(st->gate);
    sw_gate_destroy(st->gate_b);
    sw_risk_destroy(st->risk);
    sw_risk_destroy(st->risk_lat);
    free(st->lat_of);
    sw_engine_destroy(st->engine);
    sw_engine_destroy(st->engine_b);
    free(st->watch);
    free(st->watch_b);
    free(st->watch_fresh);
    free(st->watch_lat);
    free(st->watch_lat_b);
    free(st->watch_lat_fresh);
    free(st->names);
    free(st);
}

/* ---- the stream ------------------------------------------------------------------------ */

int sw_stream_push(sw_stream_t *st, const sw_sample_t *s)
{
    return st ? sw_gate_push(st->gate, s) : SW_EINVAL;
}

int sw_stream_finish(sw_stream_t *st)
{
    return st ? sw_gate_flush(st->gate) : SW_EINVAL;
}

int sw_stream_settle(sw_stream_t *st, double settle)
{
    if (!st)
        return SW_EINVAL;
    return settle > 0.0 ? sw_engine_finish(st->engine, settle) : SW_OK;
}

int sw_stream_replace(sw_stream_t *st, size_t k, const sw_scene_t *scene, char *msg, size_t msglen)
{
    sw_alarm_watch_t w, wl;
    if (!st || !scene || k >= st->n) {
        if (msg && msglen)
            snprintf(msg, msglen, "no such package");
        return SW_EINVAL;
    }
    if (sw_alarm_init_scene(&w, k, scene, st->hysteresis) != SW_OK) {
        if (msg && msglen)
            snprintf(msg, msglen, "%s: alarm thresholds not finite", scene->name);
        return SW_EINVAL;
    }
    if (st->watch_lat && watch_lat_init(&wl, k, scene, st->hysteresis) != SW_OK) {
        if (msg && msglen)
            snprintf(msg, msglen, "%s: the lateral plane's alarm thresholds are not valid",
                     scene->name);
        return SW_EINVAL;
    }
    const int rc = sw_engine_replace(st->engine, k, scene, msg, msglen);
    if (rc != SW_OK)
        return rc;
    /* the second timeline's package too; if it cannot be rebuilt (it was
     * in the first engine), it goes on with the old scene until the next
     * contest starts it afresh */
    if (st->engine_b)
        sw_engine_replace(st->engine_b, k, scene, NULL, 0);
    st->watch[k] = w;
    if (st->watch_b)
        st->watch_b[k] = st->watch_fresh[k] = w;
    if (st->watch_lat)
        st->watch_lat[k] = wl;
    if (st->watch_lat_b)
        st->watch_lat_b[k] = st->watch_lat_fresh[k] = wl;
    snprintf(st->names[k], sizeof st->names[k], "%s", scene->name);
    /* the reserve of the new scene; if it cannot be built the package goes
     * on with the old one, and the caller hears why */
    const size_t j = st->lat_of ? st->lat_of[k] : NO_LAT;
    sw_scene_t lat;
    if (j != NO_LAT && sw_scene_lateral(scene, &lat) == SW_OK) {
        const int rl = sw_risk_replace(st->risk_lat, j, &lat, msg, msglen);
        if (rl != SW_OK)
            return rl;
    }
    return sw_risk_replace(st->risk, k, scene, msg, msglen);
}

int sw_stream_risk_resolve(sw_stream_t *st, size_t k, sw_plane plane)
{
    if (!st || k >= st->n)
        return SW_EINVAL;
    size_t j = k;
    sw_risk_t *r = risk_of(st, k, plane, &j);
    return r ? sw_risk_resolve(r, j) : SW_OK;
}

const sw_risk_pkg_t *sw_stream_risk_plane(const sw_stream_t *st, size_t k, sw_plane plane)
{
    if (!st || k >= st->n)
        return NULL;
    size_t j = k;
    return sw_risk_pkg(risk_of(st, k, plane, &j), j);
}

sw_engine_t *sw_stream_engine(const sw_stream_t *st)
{
    return st ? st->engine : NULL;
}

sw_risk_t *sw_stream_risk(const sw_stream_t *st)
{
    return st ? st->risk : NULL;
}

const sw_gate_t *sw_stream_gate(const sw_stream_t *st)
{
    return st ? st->gate : NULL;
}

size_t sw_stream_count(const sw_stream_t *st)
{
    return st ? st->n : 0;
}

const char *sw_stream_name(const sw_stream_t *st, size_t k)
{
    return st && k < st->n ? st->names[k] : "";
}
