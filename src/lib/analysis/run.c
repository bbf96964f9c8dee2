/* SPDX-License-Identifier: GPL-3.0-or-later */
/* run.c - one run of a package, as the run-many-times modules make it
 * (run.h): an engine made for runs, a pulse or a log, then the free
 * motion until the outcome is certain.
 *
 * A run stops as soon as its outcome is certain, which is what makes a
 * sweep of thousands of runs affordable:
 *   - |theta| reached pi/2 (the engine's overturn event);
 *   - a model whose free rocking the margin decides exactly (the bare
 *     block, ops->free_exact): beyond alpha with no input left and moving
 *     outward, gravity only pulls it further (physics.md), so it
 *     overturns; at rest after the input, nothing moves it again;
 *   - any other: margin_bound > 0 after the input: the total energy cannot
 *     grow and is below the barrier, so it cannot overturn;
 *   - otherwise the free-motion time limit (20 rocking periods by default).
 * The checks are made on a fixed grid of the free motion (16 per rocking
 * period), so a run is the same computation whichever thread makes it. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "model_traits.h"
#include "run_int.h"
#include "swaywatch/model.h"
#include "swaywatch/run.h"
#include "swaywatch/status.h"

#define DEFAULT_FREE_PERIODS 20.0
#define STEPS_PER_PERIOD 400.0 /* automatic dt: steps per shortest period */

void sw_set_msg(char *msg, size_t len, const char *fmt, ...)
{
    if (!msg || !len)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, len, fmt, ap);
    va_end(ap);
}

/* ---- one run --------------------------------------------------------------- */

/* The runner's event callback (run.h): the direction of the first uplift
 * and of the overturn. */
static void on_run_event(void *user, const sw_event_t *ev)
{
    sw_runner_t *R = user;
    /* a level base leaving a cushion (info 0) has no direction yet */
    if (ev->kind == SW_EV_UPLIFT && !R->uplift_side && ev->info != 0.0)
        R->uplift_side = ev->info > 0.0 ? 1 : -1;
    if (ev->kind == SW_EV_OVERTURN)
        R->overturn_side = ev->theta > 0.0 ? 1 : -1;
}

void sw_runner_reset(sw_runner_t *R)
{
    sw_engine_reset(R->e);
    R->uplift_side = R->overturn_side = 0;
}

/* An engine for one scene.  dt: the option, or the scheme's default capped
 * at 1/STEPS_PER_PERIOD of the shorter of the pulse period (omega_e > 0)
 * and the rocking period.  No scheme given stays NULL, so that the engine
 * can choose its scheme for a stiff cushion. */
int sw_runner_make(sw_runner_t *R, const sw_scene_t *sc, const sw_run_opts_t *o, double omega_e,
                   int *err, char *msg, size_t msglen)
{
    return sw_runner_make_watched(R, sc, o, omega_e, NULL, NULL, err, msg, msglen);
}

int sw_runner_make_watched(sw_runner_t *R, const sw_scene_t *sc, const sw_run_opts_t *o,
                           double omega_e, sw_state_fn on_state, void *user, int *err, char *msg,
                           size_t msglen)
{
    memset(R, 0, sizeof *R);
    sw_derived_t d;
    char why[256];
    if (sw_scene_validate(sc, &d, NULL, NULL, NULL) != SW_OK) {
        *err = SW_EINVAL;
        sw_set_msg(msg, msglen, "scene '%s' is not valid", sc->name);
        return *err;
    }
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    if (o)
        eo = o->engine;
    eo.dt_forced = 0;
    eo.check_default = 0; /* a run is one of many: the caller checks what it concludes */
    eo.on_event = NULL;
    eo.on_state = NULL;
    const sw_scheme_t *s = sw_scheme_lookup(eo.scheme ? eo.scheme : SW_DEFAULT_SCHEME);
    if (!s) {
        *err = SW_ENOTFOUND;
        sw_set_msg(msg, msglen, "unknown scheme '%s'", eo.scheme);
        return *err;
    }
    if (eo.dt > 0.0 || eo.accuracy > 0.0) {
        /* as given, or chosen by the engine for the accuracy */
    } else {
        double period = 2.0 * M_PI / d.p; /* s */
        if (omega_e > 0.0)
            period = fmin(period, 2.0 * M_PI / omega_e);
        eo.dt = fmin(sw_scheme_default_dt(s), period / STEPS_PER_PERIOD);
    }
    eo.on_event = on_run_event;
    eo.user = R;
    eo.on_state = on_state;
    R->state_user = user;
    why[0] = '\0';
    R->e = sw_engine_create(sc, 1, &eo, err, why, sizeof why);
    if (!R->e)
        sw_set_msg(msg, msglen, "%s", why[0] ? why : sw_strerror(*err));
    return R->e ? SW_OK : *err;
}

double sw_run_free_time(const sw_run_opts_t *o, double p)
{
    if (o && o->settle > 0.0)
        return o->settle;
    if (o && o->settle < 0.0)
        return 0.0;
    const double n = o && o->free_periods > 0.0 ? o->free_periods : DEFAULT_FREE_PERIODS;
    return n * 2.0 * M_PI / p;
}

static void fill_result(const sw_runner_t *R, sw_run_end end, const sw_output_t *o,
                        sw_run_result_t *r)
{
    const sw_engine_t *e = R->e;
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    r->end = end;
    r->overturned = end == SW_END_OVERTURN || end == SW_END_FALLING;
    r->impacts = s.impacts;
    r->uplifts = s.uplifts;
    r->faults = s.faults;
    r->uplift_time = s.uplift_time;
    r->tip_time = s.tip_time;
    r->overturn_time = s.overturn_time;
    r->max_theta_ratio = s.max_theta_ratio;
    r->min_margin = s.min_margin;
    r->t_end = sw_engine_time(e);
    r->uplift_side = R->uplift_side;
    r->overturn_side = end == SW_END_FALLING ? (o->state.theta > 0.0 ? 1 : -1) : R->overturn_side;
}

/* The input in steps of u->check, the certificate between them: the run
 * ends safe as soon as it holds.  Overturned or faulted, the free motion's
 * checks decide at once.  Returns 1 if certified (*end set), 0 to go on,
 * or the engine's error. */
static int run_input(sw_engine_t *e, const sw_run_until_t *u, double *t, sw_run_end *end)
{
    const int exact = sw_model_traits_of(sw_engine_derived(e, 0)->model)->free_exact;
    while (*t < u->t_input) {
        *t = u->certify ? fmin(u->t_input, *t + u->check) : u->t_input;
        const int rc = sw_engine_advance_fn(e, *t, u->input, u->input_user);
        if (rc < 0)
            return rc;
        if (!(*t < u->t_input) || !u->certify)
            break;
        sw_summary_t sum;
        sw_engine_summary(e, 0, &sum);
        if (sum.overturned || sum.faults)
            break;
        sw_state_t st;
        sw_engine_get_state(e, 0, &st); /* the margins are not needed here */
        if (u->certify(u->cert_user, *t, &st)) {
            *end = exact ? SW_END_REST : SW_END_BOUND;
            return 1;
        }
    }
    return 0;
}

int sw_run_until(sw_engine_t *e, const sw_run_until_t *u, sw_run_end *end, double *t_end)
{
    const sw_derived_t *d = sw_engine_derived(e, 0);
    const int exact = sw_model_traits_of(d->model)->free_exact;
    const double t_started = sw_engine_time(e);
    double t = isnan(t_started) ? u->t0 : t_started; /* s */
    if (u->input) {
        const int rc = run_input(e, u, &t, end);
        if (rc != 0) {
            *t_end = t;
            return rc < 0 ? rc : SW_OK;
        }
    }
    const double t_limit = u->limit_set ? u->t_limit : t + u->free_time; /* s */
    for (;;) {
        sw_summary_t s;
        sw_engine_summary(e, 0, &s);
        if (u->stop_on_fault && s.faults) {
            *end = SW_END_TIMEOUT;
            break;
        }
        if (s.overturned) {
            *end = SW_END_OVERTURN;
            break;
        }
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        if (exact && u->decide_at_once) {
            /* exact for free rocking (physics.md): decided now */
            if (o.state.phase == SW_PHASE_STUCK)
                *end = SW_END_REST;
            else
                *end = o.margin > 0.0 ? SW_END_REST : SW_END_FALLING;
            break;
        }
        if (exact) {
            if (o.state.phase == SW_PHASE_STUCK) {
                *end = SW_END_REST;
                break;
            }
            if (fabs(o.state.theta) >= d->alpha && o.state.theta * o.state.theta_dot > 0.0) {
                *end = SW_END_FALLING;
                break;
            }
        } else if (o.margin_bound > 0.0) {
            *end = SW_END_BOUND;
            break;
        }
        if (!(t < t_limit)) {
            *end = SW_END_TIMEOUT;
            break;
        }
        const int rc = sw_engine_advance_fn(e, fmin(t_limit, t + u->chunk), sw_input_zero, NULL);
        if (rc < 0)
            return rc;
        const double te = sw_engine_time(e);
        t = isnan(te) ? fmin(t_limit, t + u->chunk) : te;
    }
    *t_end = t;
    return SW_OK;
}

/* Free motion from the end of the input until the outcome is certain or
 * t_limit (s) passes; checks every chunk seconds. */
int sw_run_free_motion(sw_runner_t *R, double t_limit, double chunk, sw_run_result_t *r)
{
    sw_engine_t *e = R->e;
    const sw_run_until_t u = {.limit_set = 1, .t_limit = t_limit, .chunk = chunk};
    sw_run_end end;
    double t_end;
    const int rc = sw_run_until(e, &u, &end, &t_end);
    if (rc < 0)
        return rc;
    sw_output_t o;
    sw_engine_get_output(e, 0, &o);
    fill_result(R, end, &o, r);
    return r->faults ? SW_EFAULT : SW_OK;
}

/* The pulse from state s (NULL: at rest), then free motion. */
static int run_pulse_from(sw_runner_t *R, const sw_state_t *s, const sw_pulse_t *pulse,
                          const sw_run_opts_t *o, sw_run_result_t *r)
{
    sw_pulse_t pl = *pulse;
    const double p = sw_engine_derived(R->e, 0)->p;
    const double T = sw_pulse_duration(&pl);
    sw_runner_reset(R);
    if (s) {
        const int rc = sw_engine_set_state(R->e, 0, s);
        if (rc < 0)
            return rc;
    }
    /* Up to the end of the pulse first, so that a step ends on its kink. */
    const int rc = sw_engine_advance_fn(R->e, T, sw_pulse_eval, &pl);
    if (rc < 0)
        return rc;
    return sw_run_free_motion(R, T + sw_run_free_time(o, p),
                              2.0 * M_PI / p / SW_RUN_CHECKS_PER_PERIOD, r);
}

int sw_run_pulse_on(sw_runner_t *R, const sw_pulse_t *pulse, const sw_run_opts_t *o,
                    sw_run_result_t *r)
{
    return run_pulse_from(R, NULL, pulse, o, r);
}

static int check_pulse(const sw_pulse_t *pulse, char *msg, size_t msglen)
{
    if (!pulse || !(pulse->omega > 0.0) || !isfinite(pulse->omega) || !isfinite(pulse->amplitude)) {
        sw_set_msg(msg, msglen, "the pulse needs a finite amplitude and omega > 0");
        return SW_EINVAL;
    }
    return SW_OK;
}

int sw_pulse_run(const sw_scene_t *sc, const sw_pulse_t *pulse, const sw_run_opts_t *o,
                 sw_run_result_t *r, char *msg, size_t msglen)
{
    int err = SW_OK;
    sw_set_msg(msg, msglen, "%s", "");
    if (!sc || !r)
        return SW_EINVAL;
    memset(r, 0, sizeof *r);
    if ((err = check_pulse(pulse, msg, msglen)) != SW_OK)
        return err;
    sw_runner_t R;
    if (sw_runner_make(&R, sc, o, pulse->omega, &err, msg, msglen) != SW_OK)
        return err;
    err = sw_run_pulse_on(&R, pulse, o, r);
    if (err == SW_EFAULT)
        sw_set_msg(msg, msglen, "the model faulted during the run");
    sw_engine_destroy(R.e);
    return err;
}

int sw_pulse_run_from(const sw_scene_t *sc, const sw_state_t *s, const sw_pulse_t *pulse,
                      const sw_run_opts_t *o, sw_run_result_t *r, char *msg, size_t msglen)
{
    int err = SW_OK;
    sw_set_msg(msg, msglen, "%s", "");
    if (!sc || !s || !r)
        return SW_EINVAL;
    memset(r, 0, sizeof *r);
    if ((err = check_pulse(pulse, msg, msglen)) != SW_OK)
        return err;
    if (s->phase == SW_PHASE_OVERTURNED) { /* frozen: the engine would not say so */
        r->overturned = 1;
        r->end = SW_END_OVERTURN;
        r->overturn_time = r->tip_time = r->t_end = 0.0;
        r->uplift_time = NAN;
        r->overturn_side = s->theta > 0.0 ? 1 : -1;
        return SW_OK;
    }
    sw_runner_t R;
    if (sw_runner_make(&R, sc, o, pulse->omega, &err, msg, msglen) != SW_OK)
        return err;
    err = run_pulse_from(&R, s, pulse, o, r);
    if (err == SW_EINVAL)
        sw_set_msg(msg, msglen, "the state was refused");
    if (err == SW_EFAULT)
        sw_set_msg(msg, msglen, "the model faulted during the run");
    sw_engine_destroy(R.e);
    return err;
}

int sw_run_push(sw_engine_t *e, const sw_log_t *log, size_t i, double scale, size_t *next_restart)
{
    while (*next_restart < log->nrestart && log->restart[*next_restart] <= i)
        if (log->restart[(*next_restart)++] == i)
            sw_engine_restart(e);
    return sw_engine_push(e, log->t[i], scale * log->a_g[i], log->a_z ? log->a_z[i] : 0.0);
}

int sw_run_log_on(sw_runner_t *R, const sw_log_t *log, double scale, const sw_run_opts_t *o,
                  sw_run_result_t *r)
{
    sw_engine_t *e = R->e;
    const double p = sw_engine_derived(e, 0)->p;
    sw_runner_reset(R);
    size_t next_restart = 0;
    for (size_t i = 0; i < log->n; i++) {
        const int rc = sw_run_push(e, log, i, scale, &next_restart);
        if (rc == SW_EVENT) {
            sw_summary_t s;
            sw_engine_summary(e, 0, &s);
            if (s.overturned)
                break; /* frozen from here on */
        }
    }
    const double t = sw_engine_time(e);
    if (isnan(t))
        return SW_EINVAL; /* no usable sample */
    return sw_run_free_motion(R, t + sw_run_free_time(o, p),
                              2.0 * M_PI / p / SW_RUN_CHECKS_PER_PERIOD, r);
}

int sw_log_run(const sw_scene_t *sc, const sw_log_t *log, double scale, const sw_run_opts_t *o,
               sw_run_result_t *r, char *msg, size_t msglen)
{
    int err = SW_OK;
    sw_set_msg(msg, msglen, "%s", "");
    if (!sc || !r || !log || !log->t || !log->a_g || !isfinite(scale))
        return SW_EINVAL;
    memset(r, 0, sizeof *r);
    sw_runner_t R;
    if (sw_runner_make(&R, sc, o, 0.0, &err, msg, msglen) != SW_OK)
        return err;
    err = sw_run_log_on(&R, log, scale, o, r);
    if (err == SW_EINVAL)
        sw_set_msg(msg, msglen, "the log has no usable sample");
    if (err == SW_EFAULT)
        sw_set_msg(msg, msglen, "the model faulted during the run");
    sw_engine_destroy(R.e);
    return err;
}

/* The probe's peak drive turned into the x (or scale) at which the
 * package first lifts, at a drive of level (ops->lift_level). */
double sw_run_probe_lift(double probe, double peak, double level)
{
    if (!(peak > 0.0))
        return INFINITY;
    return probe * level / peak;
}
