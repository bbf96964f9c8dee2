/* SPDX-License-Identifier: GPL-3.0-or-later */
/* boundary.c - the overturning boundary curves of pulses (boundary.h):
 * at each point a threshold search (search.c) over pulse runs (run.c),
 * the points on the library's pool (pool.c).  The safety factors of a log, which use the same runs
 * and search, are in safety.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_traits.h"
#include "pool_int.h"
#include "run_int.h"
#include "swaywatch/boundary.h"
#include "swaywatch/model.h"
#include "swaywatch/search.h"
#include "swaywatch/status.h"

#define DEFAULT_X_MAX 20.0
#define PROBE_SAMPLES 400.0     /* samples per period when probing the stuck frame */
#define PROBE_MAX_SAMPLES 20000 /* cap on the samples of one probe run */

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
    return sw_run_pulse_on(T->R, &T->pulse, T->ro, r);
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
    const sw_model_traits_t *ops = sw_model_traits_of(d->model);
    double wfast, wslow; /* rad/s */
    ops->probe_rates(d, g, &wfast, &wslow);
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
        const double v = ops->lift_drive(d, level, &o);
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
    const sw_model_traits_t *ops = sw_model_traits_of(d.model);
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

/* The sweep as the pool's job: each point a task, its index. */
typedef struct {
    const sw_curve_t *curves;
    const double *ratios;
    size_t nratios, total;
    const sw_boundary_opts_t *o;
    sw_boundary_point_t *out;
    char (*msgs)[256];
    size_t next, done;
} sweep_t;

static int sweep_take(void *user, void *task)
{
    sweep_t *S = user;
    if (S->next >= S->total)
        return 0;
    const size_t i = S->next++;
    memcpy(task, &i, sizeof i);
    return 1;
}

static int sweep_ended(void *user)
{
    (void)user;
    return 1; /* every point is handed out at once */
}

static void sweep_run(void *user, void *task)
{
    sweep_t *S = user;
    size_t i;
    memcpy(&i, task, sizeof i);
    const size_t c = i / S->nratios, k = i % S->nratios;
    sw_boundary_point(&S->curves[c], S->ratios[k], S->o, &S->out[i], S->msgs[i], sizeof S->msgs[i]);
}

static void sweep_done(void *user, void *task)
{
    sweep_t *S = user;
    (void)task;
    S->done++;
    if (S->o->progress) /* under the pool's lock: one call at a time */
        S->o->progress(S->o->user, S->done, S->total);
}

int sw_boundary_sweep(const sw_curve_t *curves, size_t ncurves, const double *ratios,
                      size_t nratios, const sw_boundary_opts_t *o, sw_boundary_point_t *out,
                      char *msg, size_t msglen)
{
    sw_set_msg(msg, msglen, "%s", "");
    if (!curves || !ratios || !o || !out || ncurves == 0 || nratios == 0)
        return SW_EINVAL;
    sweep_t S = {curves, ratios, nratios, ncurves * nratios, o, out, NULL, 0, 0};
    S.msgs = calloc(S.total, sizeof *S.msgs);
    if (!S.msgs) {
        sw_set_msg(msg, msglen, "out of memory");
        return SW_ENOMEM;
    }
    const sw_pool_job_t J = {sizeof(size_t), sweep_take, sweep_ended, sweep_run, sweep_done, &S};
    sw_pool_run(&J, o->threads);
    int rc = SW_OK;
    for (size_t i = 0; i < S.total; i++)
        if (out[i].status < 0) {
            rc = out[i].status;
            sw_set_msg(msg, msglen, "curve %zu, omega_e/p = %g: %s", i / nratios + 1,
                       out[i].omega_ratio, S.msgs[i][0] ? S.msgs[i] : sw_strerror(rc));
            break;
        }
    free(S.msgs);
    return rc;
}
