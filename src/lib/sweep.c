/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sweep.c - overturning boundaries and safety factors: many independent
 * runs of the engine, a scan-then-bisect threshold search, and a small
 * pthread work queue.
 *
 * A run stops as soon as its outcome is certain, which is what makes a
 * sweep of thousands of runs affordable:
 *   - |theta| reached pi/2 (the engine's overturn event);
 *   - bare package, no input left, beyond alpha and moving outward: gravity
 *     only pulls it further (physics.md), so it overturns;
 *   - bare package at rest after the input: nothing moves it again;
 *   - frame: margin_bound > 0 after the input: the total energy cannot
 *     grow and is below the barrier, so it cannot overturn;
 *   - otherwise the free-motion time limit (20 rocking periods by default).
 * The checks are made on a fixed grid of the free motion (16 per rocking
 * period), so a run is the same computation whichever thread makes it.
 * The safety factors of a log, which use these runs, are in safety.c. */
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "run.h"
#include "swaywatch/model.h"
#include "swaywatch/status.h"
#include "swaywatch/sweep.h"

#define DEFAULT_FREE_PERIODS 20.0
#define DEFAULT_STEP 0.02
#define DEFAULT_TOL 1e-3
#define DEFAULT_X_MAX 20.0
#define STEPS_PER_PERIOD 400.0  /* automatic dt: steps per shortest period */
#define PROBE_SAMPLES 400.0     /* samples per period when probing the stuck frame */
#define PROBE_MAX_SAMPLES 20000 /* cap on the samples of one probe run */
#define MAX_THREADS 256

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

/* Free motion from the end of the input until the outcome is certain or
 * t_limit (s) passes; checks every chunk seconds. */
int sw_run_free_motion(sw_runner_t *R, double t_limit, double chunk, sw_run_result_t *r)
{
    sw_engine_t *e = R->e;
    const sw_derived_t *d = sw_engine_derived(e, 0);
    const int free_exact = sw_model_ops_of(d->model)->free_exact;
    sw_run_end end;
    sw_output_t o;
    for (;;) {
        sw_summary_t s;
        sw_engine_summary(e, 0, &s);
        sw_engine_get_output(e, 0, &o);
        const double t = sw_engine_time(e);
        if (s.overturned) {
            end = SW_END_OVERTURN;
            break;
        }
        if (free_exact) {
            if (o.state.phase == SW_PHASE_STUCK) {
                end = SW_END_REST;
                break;
            }
            if (fabs(o.state.theta) >= d->alpha && o.state.theta * o.state.theta_dot > 0.0) {
                end = SW_END_FALLING;
                break;
            }
        } else if (o.margin_bound > 0.0) {
            end = SW_END_BOUND;
            break;
        }
        if (!(t < t_limit)) {
            end = SW_END_TIMEOUT;
            break;
        }
        const int rc = sw_engine_advance_fn(e, fmin(t_limit, t + chunk), sw_input_zero, NULL);
        if (rc < 0)
            return rc;
    }
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

static int run_pulse_on(sw_runner_t *R, const sw_pulse_t *pulse, const sw_run_opts_t *o,
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
    err = run_pulse_on(&R, pulse, o, r);
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

/* ---- threshold search ----------------------------------------------------- */

typedef struct {
    sw_trial_fn f;
    void *user;
    double tol;
    long *trials;
} search_t;

static int trial(const search_t *S, double x, sw_run_result_t *r)
{
    memset(r, 0, sizeof *r);
    (*S->trials)++;
    return S->f(S->user, x, r);
}

/* Bisect between xs (safe) and xo (overturning, run result *ro), in
 * either order, to the relative tolerance; *safe and *over get the final
 * ends and *r_over (may be NULL) the run at *over.  Geometric midpoints:
 * the scan is geometric too. */
static int bisect(const search_t *S, double xs, double xo, const sw_run_result_t *ro, double *safe,
                  double *over, sw_run_result_t *r_over)
{
    sw_run_result_t r, r_o = *ro;
    for (;;) {
        const double lo = fmin(xs, xo), hi = fmax(xs, xo);
        if (hi / lo - 1.0 <= S->tol)
            break;
        const double m = sqrt(lo * hi);
        if (!(m > lo && m < hi))
            break;
        const int rc = trial(S, m, &r);
        if (rc < 0)
            return rc;
        if (r.overturned) {
            xo = m;
            r_o = r;
        } else {
            xs = m;
        }
    }
    *safe = xs;
    *over = xo;
    if (r_over)
        *r_over = r_o;
    return SW_OK;
}

int sw_threshold_search(sw_trial_fn f, void *user, const sw_search_opts_t *o, sw_threshold_t *out)
{
    if (!f || !o || !out)
        return SW_EINVAL;
    memset(out, 0, sizeof *out);
    const double step = o->step > 0.0 ? o->step : DEFAULT_STEP;
    const double tol = o->tol > 0.0 ? o->tol : DEFAULT_TOL;
    if (!(o->x_min > 0.0) || !(o->x_max > o->x_min) || !isfinite(o->x_max) || !isfinite(step) ||
        !isfinite(tol))
        return SW_EINVAL;
    search_t S = {f, user, tol, &out->trials};
    sw_run_result_t r;
    double x = o->x_min, last = 0.0;
    int k = 0, rc;

    /* scan for the first overturn */
    for (;; k++) {
        x = fmin(o->x_min * pow(1.0 + step, k), o->x_max);
        if ((rc = trial(&S, x, &r)) < 0)
            return rc;
        if (r.overturned)
            break;
        last = x;
        if (x >= o->x_max)
            return SW_OK; /* nothing overturns up to x_max */
    }
    out->found = 1;
    if (k == 0) {
        out->at_min = 1;
        out->x = x;
        out->x_safe = 0.0;
        out->at_x = r;
    } else {
        rc = bisect(&S, last, x, &r, &out->x_safe, &out->x, &out->at_x);
        if (rc < 0)
            return rc;
    }
    if (!o->islands)
        return SW_OK;

    /* map the safe islands above: walk the same scan grid to x_max */
    int over = 1;
    double prev = x;
    sw_run_result_t r_prev = r;
    sw_island_t cur = {0.0, 0.0, 0};
    while (prev < o->x_max) {
        k++;
        x = fmin(o->x_min * pow(1.0 + step, k), o->x_max);
        if ((rc = trial(&S, x, &r)) < 0)
            return rc;
        if (over && !r.overturned) {
            double safe, ov;
            rc = bisect(&S, x, prev, &r_prev, &safe, &ov, NULL);
            if (rc < 0)
                return rc;
            cur.lo = safe;
            over = 0;
        } else if (!over && r.overturned) {
            double safe, ov;
            rc = bisect(&S, prev, x, &r, &safe, &ov, NULL);
            if (rc < 0)
                return rc;
            cur.hi = safe;
            cur.open = 0;
            if (out->n_islands < SW_MAX_ISLANDS)
                out->islands[out->n_islands++] = cur;
            else
                out->islands_truncated = 1;
            over = 1;
        }
        prev = x;
        r_prev = r;
    }
    if (!over) {
        cur.hi = o->x_max;
        cur.open = 1;
        if (out->n_islands < SW_MAX_ISLANDS)
            out->islands[out->n_islands++] = cur;
        else
            out->islands_truncated = 1;
    }
    return SW_OK;
}

/* ---- parallel jobs ---------------------------------------------------------- */

typedef struct {
    pthread_mutex_t mu;
    size_t next, n;
    void (*job)(void *user, size_t i);
    void *user;
} pool_t;

static void *pool_worker(void *arg)
{
    pool_t *p = arg;
    for (;;) {
        pthread_mutex_lock(&p->mu);
        const size_t i = p->next++;
        pthread_mutex_unlock(&p->mu);
        if (i >= p->n)
            break;
        p->job(p->user, i);
    }
    return NULL;
}

void sw_parallel_for(size_t n, int threads, void (*job)(void *user, size_t i), void *user)
{
    if (!job || n == 0)
        return;
    if (threads <= 1 || n == 1) {
        for (size_t i = 0; i < n; i++) job(user, i);
        return;
    }
    pool_t p = {.next = 0, .n = n, .job = job, .user = user};
    if (pthread_mutex_init(&p.mu, NULL) != 0) {
        for (size_t i = 0; i < n; i++) job(user, i);
        return;
    }
    pthread_t tid[MAX_THREADS];
    size_t want = (size_t)threads;
    if (want > MAX_THREADS)
        want = MAX_THREADS;
    if (want > n)
        want = n;
    size_t started = 0;
    for (; started < want; started++)
        if (pthread_create(&tid[started], NULL, pool_worker, &p) != 0)
            break;
    if (started == 0)
        pool_worker(&p); /* no thread at all: do it here */
    for (size_t i = 0; i < started; i++) pthread_join(tid[i], NULL);
    pthread_mutex_destroy(&p.mu);
}

/* ---- boundary curves -------------------------------------------------------- */

typedef struct {
    sw_runner_t *R;
    const sw_run_opts_t *ro;
    sw_pulse_t pulse;
    double unit; /* m/s^2, g tan(alpha): x = 1 */
} pulse_trial_t;

static int pulse_trial(void *user, double x, sw_run_result_t *r)
{
    pulse_trial_t *T = user;
    T->pulse.amplitude = x * T->unit;
    return run_pulse_on(T->R, &T->pulse, T->ro, r);
}

/* The probe's peak drive turned into the x (or scale) at which the
 * package first lifts, at a drive of level (ops->lift_level). */
double sw_run_probe_lift(double probe, double peak, double level)
{
    if (!(peak > 0.0))
        return INFINITY;
    return probe * level / peak;
}

/* The lowest x at which the package can leave its rest contact at all
 * (bare: 1).  On a frame the package moves with it until the support's
 * acceleration reaches g tan(alpha); on a cushion it cannot overturn
 * without an edge leaving the cushion.  Until then the system is linear
 * (frame), or linear to O(theta^2) with theta below z_s/b (cushion), so the
 * response is proportional to the pulse: run a pulse far too small to lift
 * anything, sample the drive finely over the pulse and the ringing after
 * it, and scale.  The peak of a decaying free oscillation comes within its
 * first period after the pulse. */
static double pulse_lift(sw_engine_t *e, const sw_derived_t *d, double g, sw_pulse_t pulse,
                         double unit, double level)
{
    const double probe = 1e-4;
    pulse.amplitude = probe * unit;
    sw_engine_reset(e);
    double wfast, wslow; /* rad/s */
    sw_model_ops_of(d->model)->probe_rates(d, g, &wfast, &wslow);
    const double wmax = fmax(pulse.omega, wfast);
    const double t_end = sw_pulse_duration(&pulse) + 1.5 * 2.0 * M_PI / wslow; /* s */
    double dt = 2.0 * M_PI / wmax / PROBE_SAMPLES;                             /* s */
    if (t_end / dt > PROBE_MAX_SAMPLES)
        dt = t_end / PROBE_MAX_SAMPLES;
    double peak = 0.0;
    for (double t = 0.0; t < t_end;) {
        t = fmin(t_end, t + dt);
        sw_engine_advance_fn(e, t, sw_pulse_eval, &pulse);
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        const double v = sw_model_lift_drive(d, level, &o);
        if (v > peak)
            peak = v;
    }
    return sw_run_probe_lift(probe, peak, level);
}

int sw_curve_scene(const sw_curve_t *c, double omega_e, sw_scene_t *out)
{
    *out = c->scene;
    if (!(c->bearing_ratio > 0.0))
        return SW_OK;
    if (!c->scene.has_frame)
        return SW_EINVAL;
    out->frame_omega = omega_e > 0.0 ? c->bearing_ratio * omega_e : 1.0;
    out->frame_stiffness = NAN;
    out->frame_k_given = SW_GIVEN_RATIO;
    return SW_OK;
}

int sw_boundary_point(const sw_curve_t *c, double omega_ratio, const sw_boundary_opts_t *o,
                      sw_boundary_point_t *out, char *msg, size_t msglen)
{
    int err = SW_OK;
    sw_set_msg(msg, msglen, "%s", "");
    if (!c || !o || !out)
        return SW_EINVAL;
    memset(out, 0, sizeof *out);
    out->omega_ratio = omega_ratio;
    sw_scene_t sc = c->scene;
    sw_derived_t d;
    sw_runner_t R;
    R.e = NULL;
    if (!(omega_ratio > 0.0) || !isfinite(omega_ratio)) {
        sw_set_msg(msg, msglen, "omega_e/p must be > 0");
        err = SW_EINVAL;
        goto out;
    }
    if (sw_scene_validate(&sc, &d, NULL, NULL, NULL) != SW_OK) {
        sw_set_msg(msg, msglen, "scene '%s' is not valid", sc.name);
        err = SW_EINVAL;
        goto out;
    }
    const double omega_e = omega_ratio * d.p; /* rad/s */
    if (c->bearing_ratio > 0.0) {
        if (sw_curve_scene(c, omega_e, &sc) != SW_OK) {
            sw_set_msg(msg, msglen, "scene '%s' has no frame to set omega_b/omega_e on", sc.name);
            err = SW_EINVAL;
            goto out;
        }
        if (sw_scene_validate(&sc, &d, NULL, NULL, NULL) != SW_OK) {
            sw_set_msg(msg, msglen, "scene '%s' with omega_b = %g rad/s is not valid", sc.name,
                       sc.frame_omega);
            err = SW_EINVAL;
            goto out;
        }
    }
    if (sw_runner_make(&R, &sc, &o->run, omega_e, &err, msg, msglen) != SW_OK)
        goto out;

    pulse_trial_t T = {&R, &o->run, {o->shape, 0.0, omega_e}, sc.g * tan(d.alpha)};
    sw_search_opts_t so = o->search;
    const sw_model_ops_t *ops = sw_model_ops_of(d.model);
    if (ops->lift_direct)
        out->x_lift = 1.0; /* the bed acceleration itself must reach g tan(alpha) */
    else
        out->x_lift = pulse_lift(R.e, &d, sc.g, T.pulse, T.unit, ops->lift_level(&d, sc.g));
    if (!(so.x_max > 0.0))
        so.x_max = DEFAULT_X_MAX;
    if (!(so.x_min > 0.0)) {
        so.x_min = ops->lift_direct ? 1.0 : ops->probe_margin * out->x_lift;
        if (!(so.x_min < so.x_max)) { /* cannot even lift below x_max */
            out->th.found = 0;
            goto out;
        }
    }
    err = sw_threshold_search(pulse_trial, &T, &so, &out->th);
    if (err == SW_EINVAL)
        sw_set_msg(msg, msglen, "bad search range or steps (x_min %g, x_max %g)", so.x_min,
                   so.x_max);
    else if (err == SW_EFAULT)
        sw_set_msg(msg, msglen, "the model faulted at omega_e/p = %g", omega_ratio);
    else if (err < 0)
        sw_set_msg(msg, msglen, "%s", sw_strerror(err));
out:
    sw_engine_destroy(R.e);
    out->status = err;
    return err;
}

typedef struct {
    const sw_curve_t *curves;
    const double *ratios;
    size_t nratios, total;
    const sw_boundary_opts_t *o;
    sw_boundary_point_t *out;
    char (*msgs)[256];
    pthread_mutex_t mu;
    size_t done;
} sweep_t;

static void sweep_job(void *user, size_t i)
{
    sweep_t *S = user;
    const size_t c = i / S->nratios, k = i % S->nratios;
    sw_boundary_point(&S->curves[c], S->ratios[k], S->o, &S->out[i], S->msgs[i], sizeof S->msgs[i]);
    if (S->o->progress) {
        pthread_mutex_lock(&S->mu);
        S->done++;
        S->o->progress(S->o->user, S->done, S->total);
        pthread_mutex_unlock(&S->mu);
    }
}

int sw_boundary_sweep(const sw_curve_t *curves, size_t ncurves, const double *ratios,
                      size_t nratios, const sw_boundary_opts_t *o, sw_boundary_point_t *out,
                      char *msg, size_t msglen)
{
    sw_set_msg(msg, msglen, "%s", "");
    if (!curves || !ratios || !o || !out || ncurves == 0 || nratios == 0)
        return SW_EINVAL;
    sweep_t S = {
        curves, ratios, nratios, ncurves * nratios, o, out, NULL, PTHREAD_MUTEX_INITIALIZER, 0};
    S.msgs = calloc(S.total, sizeof *S.msgs);
    if (!S.msgs) {
        sw_set_msg(msg, msglen, "out of memory");
        return SW_ENOMEM;
    }
    sw_parallel_for(S.total, o->threads, sweep_job, &S);
    int rc = SW_OK;
    for (size_t i = 0; i < S.total; i++)
        if (out[i].status < 0) {
            rc = out[i].status;
            sw_set_msg(msg, msglen, "curve %zu, omega_e/p = %g: %s", i / nratios + 1,
                       out[i].omega_ratio, S.msgs[i][0] ? S.msgs[i] : sw_strerror(rc));
            break;
        }
    free(S.msgs);
    pthread_mutex_destroy(&S.mu);
    return rc;
}
