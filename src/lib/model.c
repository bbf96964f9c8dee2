/* SPDX-License-Identifier: GPL-3.0-or-later */
/* model.c - what every model shares: the table of models, the common
 * set-up of a package (constants, typical sizes), the right-hand side in
 * GSL's signature, the state as the API gives it, and the common part of
 * the report.  Each model's physics is in its own file (model_rigid.c,
 * model_cushion.c) behind its ops table (internal.h). */
#include <math.h>
#include <string.h>

#include "internal.h"
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

void sw_model_setup(sw_pkg_t *P)
{
    P->ops = sw_model_ops_of(P->d.model);
    P->iu = P->idu = P->iz = P->idz = -1;
    P->trig[0] = NAN;
    P->g = P->scene.g;
    P->kR = 0.75 / P->d.R;
    P->tan_alpha = tan(P->d.alpha);
    P->ops->setup(P);
}

void sw_model_scale(sw_pkg_t *P, int i, int di, double size)
{
    P->yscale[i] = size;
    P->yscale[di] = fmax(P->d.omega_max, P->d.p) * size;
}

int sw_model_rhs(double t, const double y[], double f[], void *pkg)
{
    sw_pkg_t *P = pkg; /* not const: the sin/cos cache, the cushion's rate tracking */
    return P->ops->rhs(P, t, y, f);
}

void sw_model_to_state(const sw_pkg_t *P, sw_state_t *s)
{
    memset(s, 0, sizeof *s);
    s->theta = P->y[P->ith];
    s->theta_dot = P->y[P->idth];
    if (P->iu >= 0) {
        s->u = P->y[P->iu];
        s->u_dot = P->y[P->idu];
    }
    if (P->iz >= 0) {
        s->z = P->y[P->iz];
        s->z_dot = P->y[P->idz];
    }
    s->phase = P->phase;
    s->side = P->phase == SW_PHASE_STUCK ? 0 : P->side;
}

void sw_model_from_state(sw_pkg_t *P, const sw_state_t *s)
{
    memset(P->y, 0, sizeof P->y);
    P->y[P->ith] = s->theta;
    P->y[P->idth] = s->theta_dot;
    if (P->iu >= 0) {
        P->y[P->iu] = s->u;
        P->y[P->idu] = s->u_dot;
    }
    if (P->iz >= 0) {
        P->y[P->iz] = s->z;
        P->y[P->idz] = s->z_dot;
    }
    P->phase = s->phase;
    P->side = s->side ? (s->side > 0 ? 1 : -1) : (s->theta < 0 ? -1 : 1);
    if (!P->ops->stuck_advance) {
        /* a model that is never stuck (a cushion): side follows theta */
        if (P->phase == SW_PHASE_STUCK)
            P->phase = SW_PHASE_ROCKING;
        P->side = s->theta < 0.0 ? -1 : 1;
        return;
    }
    if (P->phase == SW_PHASE_STUCK) {
        P->y[P->ith] = P->y[P->idth] = 0.0;
    }
}

void sw_model_output(const sw_pkg_t *P, double t, sw_output_t *o)
{
    memset(o, 0, sizeof *o);
    o->t = t;
    sw_model_to_state(P, &o->state);
    o->a_g = sw_input_ag(P->in, t);
    P->ops->output(P, t, o);
}
