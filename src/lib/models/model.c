/* SPDX-License-Identifier: GPL-3.0-or-later */
/* model.c - what every model shares: the table of models and their
 * traits, the common set-up of a package's model (constants, typical
 * sizes), the right-hand side and Jacobian in GSL's signature, the state
 * set from the API's, and the public functions of model.h that read the
 * traits.  Each model's physics is in its own file (model_rigid.c,
 * model_cushion.c) behind its ops table (model_ops.h) and its traits
 * (model_traits.h). */
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "model_ops.h"
#include "model_traits.h"
#include "swaywatch/model.h"

const char *sw_phase_name(sw_phase p)
{
    switch (p) {
        case SW_PHASE_STUCK: return "stuck";
        case SW_PHASE_ROCKING: return "rocking";
        case SW_PHASE_OVERTURNED: return "overturned";
    }
    return "unknown";
}

/* The scene decides the model; a model is a row here. */
const sw_model_ops_t *sw_model_ops_of(sw_model_kind kind)
{
    static const sw_model_ops_t *const table[SW_MODEL_KINDS] = {
        [SW_MODEL_BARE] = &sw_model_bare,
        [SW_MODEL_FRAME] = &sw_model_frame,
        [SW_MODEL_CUSHION] = &sw_model_cushion,
    };
    _Static_assert(SW_MODEL_CUSHION + 1 == SW_MODEL_KINDS,
                   "a new sw_model_kind needs SW_MODEL_KINDS and a row here");
    return (unsigned)kind < sizeof table / sizeof table[0] ? table[kind] : NULL;
}

const sw_model_traits_t *sw_model_traits_of(sw_model_kind kind)
{
    const sw_model_ops_t *m = sw_model_ops_of(kind);
    return m ? m->traits : NULL;
}

const char *sw_model_name(sw_model_kind k)
{
    const sw_model_ops_t *m = sw_model_ops_of(k);
    return m ? m->name : "unknown";
}

/* A contact faster than the fixed steps of dt can follow (omega_max dt >
 * SW_STIFF_OMEGA_DT): only a model whose right-hand side tracks its
 * contact rate has one. */
int sw_model_stiff(const sw_derived_t *d, double dt)
{
    const sw_model_ops_t *m = sw_model_ops_of(d->model);
    return m && m->tracks_rate && d->omega_max * dt > SW_STIFF_OMEGA_DT;
}

int sw_modes_add(sw_mode_t m[SW_MODES_MAX], int n, double re, double im, const char *name)
{
    /* decaying, or oscillating undamped; not growing, not at rest */
    if (n >= SW_MODES_MAX || !(re < 0.0 || (re == 0.0 && im != 0.0)))
        return n;
    const double w = hypot(re, im);
    m[n] = (sw_mode_t){.re = re, .im = fabs(im), .omega = w, .zeta = -re / w, .name = name};
    return n + 1;
}

int sw_modes_quadratic(sw_mode_t m[SW_MODES_MAX], int n, double a, double b, double c,
                       const char *name)
{
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0)
        return sw_modes_add(m, n, -b / (2.0 * a), sqrt(-disc) / (2.0 * a), name);
    /* real roots: the larger in size without cancellation, the other from
     * their product c / a */
    const double big = -(b + sqrt(disc)) / (2.0 * a);
    n = sw_modes_add(m, n, big, 0.0, name);
    return big != 0.0 ? sw_modes_add(m, n, c / (a * big), 0.0, name) : n;
}

int sw_model_modes(const sw_derived_t *d, double g, sw_mode_t m[SW_MODES_MAX])
{
    const sw_model_traits_t *tr = d && m ? sw_model_traits_of(d->model) : NULL;
    return tr && tr->modes ? tr->modes(d, g, m) : 0;
}

int sw_model_settled(const sw_derived_t *d, double g, const sw_state_t *s)
{
    const sw_model_traits_t *tr = d && s ? sw_model_traits_of(d->model) : NULL;
    if (!tr)
        return 0;
    if (s->phase == SW_PHASE_OVERTURNED)
        return 1;
    return s->phase != SW_PHASE_ROCKING && tr->settled && tr->settled(d, g, s);
}

double sw_model_energy(const sw_derived_t *d, double g, const sw_state_t *s)
{
    const sw_model_traits_t *tr = d && s ? sw_model_traits_of(d->model) : NULL;
    return tr ? tr->energy(d, g, s) : NAN;
}

double sw_model_barrier(const sw_derived_t *d, double g)
{
    const sw_model_traits_t *tr = d ? sw_model_traits_of(d->model) : NULL;
    return tr ? tr->barrier(d, g) : NAN;
}

double sw_model_work_rate(const sw_derived_t *d)
{
    const sw_model_traits_t *tr = d ? sw_model_traits_of(d->model) : NULL;
    return tr ? tr->work_rate(d) : NAN;
}

void sw_model_setup(sw_model_t *M, sw_model_scratch_t *S, const sw_scene_t *sc)
{
    M->ops = sw_model_ops_of(M->d.model);
    M->iu = M->idu = M->iz = M->idz = -1;
    M->g = sc->g;
    M->kR = 0.75 / M->d.R;
    M->tan_alpha = tan(M->d.alpha);
    M->frame_mass = sc->has_frame ? sc->frame_mass : 0.0;
    S->trig[0] = NAN;
    S->memo_n = S->memo_next = 0; /* nothing remembered of another model */
    M->rate_cap = INFINITY;       /* a model that tracks a rate and can bound it says so */
    M->ops->setup(M, sc);
}

void sw_model_scale(sw_model_t *M, int i, int di, double size)
{
    M->yscale[i] = size;
    M->yscale[di] = fmax(M->d.omega_max, M->d.p) * size;
}

int sw_model_rhs(double t, const double y[], double f[], void *params)
{
    const sw_model_sys_t *sys = params;
    const sw_input_at_t u = sw_input_at(sys->m->in, sys->m->g, t);
    return sys->m->ops->rhs(sys->m, sys->s, &u, y, f);
}

int sw_model_jacobian(double t, const double y[], double *dfdy, double dfdt[], void *params)
{
    /* Forward differences, step sqrt(eps) times the component's size or
     * its typical size (the model's right-hand sides are only piecewise
     * smooth: a contact end or a clamp may lie inside a step, which Newton
     * iterations tolerate). */
    const sw_model_t *M = ((const sw_model_sys_t *)params)->m;
    const int n = M->n;
    const double rt_eps = 1.4901161193847656e-08; /* sqrt(DBL_EPSILON) */
    double f0[SW_NMAX], f1[SW_NMAX], yp[SW_NMAX];
    sw_model_rhs(t, y, f0, params);
    memcpy(yp, y, sizeof(double) * (size_t)n);
    for (int j = 0; j < n; j++) {
        yp[j] = y[j] + rt_eps * (fabs(y[j]) + M->yscale[j]);
        const double dj = yp[j] - y[j]; /* the step as represented */
        sw_model_rhs(t, yp, f1, params);
        for (int i = 0; i < n; i++) dfdy[i * n + j] = (f1[i] - f0[i]) / dj;
        yp[j] = y[j];
    }
    const double tp = t + rt_eps * fmax(fabs(t), 1e-3), dt = tp - t;
    sw_model_rhs(tp, y, f1, params);
    for (int i = 0; i < n; i++) dfdt[i] = (f1[i] - f0[i]) / dt;
    return GSL_SUCCESS;
}

void sw_model_from_state(sw_model_t *M, double y[SW_NMAX], const sw_state_t *s)
{
    memset(y, 0, sizeof(double) * SW_NMAX);
    y[M->ith] = s->theta;
    y[M->idth] = s->theta_dot;
    if (M->iu >= 0) {
        y[M->iu] = s->u;
        y[M->idu] = s->u_dot;
    }
    if (M->iz >= 0) {
        y[M->iz] = s->z;
        y[M->idz] = s->z_dot;
    }
    M->phase = s->phase;
    M->side = s->side ? (s->side > 0 ? 1 : -1) : (s->theta < 0 ? -1 : 1);
    if (!M->ops->stands) {
        /* a model that never stands still (a cushion): side follows theta */
        if (M->phase == SW_PHASE_STUCK)
            M->phase = SW_PHASE_ROCKING;
        M->side = s->theta < 0.0 ? -1 : 1;
        return;
    }
    if (M->phase == SW_PHASE_STUCK) {
        y[M->ith] = y[M->idth] = 0.0;
    }
}
