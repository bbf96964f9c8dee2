/* SPDX-License-Identifier: GPL-3.0-or-later */
/* risk.c - the reserve at a rate, its minimum, significant impacts and
 * settling spans of every package beside an engine (risk.h); in min_only
 * mode the states due are held and their minimum found most threatened
 * first (reserve_min.h). */
#include "swaywatch/risk.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reserve_min.h"
#include "sched.h"
#include "swaywatch/status.h"

typedef struct {
    sw_reserve_t *reserve; /* NULL: no reserve (rate < 0) */
    sw_settle_t settle;
    int settles;    /* impacts can be told apart (not a cushion) */
    sw_sched_t due; /* when the next evaluation is due */
    sw_risk_pkg_t f;
    char no_reserve[256]; /* why this package has no reserve; "" when it has one */
    /* min_only */
    sw_rmin_t rm;          /* the search (its capped reserve) */
    sw_rmin_state_t *held; /* states due, not evaluated yet (SW_RISK_MIN_STATES) */
    size_t nheld;
    sw_reserve_log_t best; /* the smallest found among those evaluated */
} pkg_t;

struct sw_risk {
    size_t n;
    double period; /* s between evaluations; 0: no reserve */
    sw_risk_opts_t o;
    pkg_t *p;
};

static void figures_init(pkg_t *p)
{
    const double impact_min = p->f.impact_min;
    memset(&p->f, 0, sizeof p->f);
    p->f.reserve_g = p->f.reserve_t = p->f.min_reserve_g = p->f.min_reserve_time = NAN;
    p->f.impact_min = impact_min;
    p->f.rest_reserve_g = NAN;
    p->f.no_reserve = p->no_reserve[0] ? p->no_reserve : NULL;
    if (p->reserve) {
        sw_reserve_result_t rest;
        sw_reserve_rest(p->reserve, &rest);
        p->f.rest_reserve_g = rest.reserve_g;
    }
    sw_sched_reset(&p->due);
    if (p->settles)
        sw_settle_init(&p->settle, impact_min);
    p->nheld = 0;
    memset(&p->best, 0, sizeof p->best);
    p->best.min_g = p->best.lower_g = INFINITY;
    p->best.min_time = NAN;
    p->best.exact = 1;
}

/* Package p for scene sc: its reserve and its significance. */
static int pkg_build(const sw_risk_t *r, const sw_scene_t *sc, pkg_t *p, char *msg, size_t msglen)
{
    sw_derived_t d;
    memset(p, 0, sizeof *p);
    if (sw_scene_validate(sc, &d, sc->name, NULL, NULL) != SW_OK) {
        if (msg)
            snprintf(msg, msglen, "%s: the scene does not validate", sc->name);
        return SW_EINVAL;
    }
    p->f.impact_min = SW_IMPACT_SIGNIFICANCE * sw_impact_tip_speed(&d, sc->g);
    p->settles = p->f.impact_min > 0.0;
    if (r->period > 0.0) {
        int err = SW_OK;
        p->reserve =
            sw_reserve_create(sc, &r->o.reserve, &err, p->no_reserve, sizeof p->no_reserve);
        /* too stiff to evaluate: the package goes on without a reserve,
         * and says so (f.no_reserve) */
        if (!p->reserve && err != SW_ETOOBIG) {
            if (msg)
                snprintf(msg, msglen, "%s", p->no_reserve);
            return err != SW_OK ? err : SW_ENOMEM;
        }
        if (p->reserve)
            p->no_reserve[0] = '\0';
        if (p->reserve && r->o.min_only) {
            sw_rmin_init(&p->rm, sc, &r->o.reserve, p->reserve);
            if (!(p->held = malloc(SW_RISK_MIN_STATES * sizeof *p->held))) {
                if (msg)
                    snprintf(msg, msglen, "%s", sw_strerror(SW_ENOMEM));
                return SW_ENOMEM;
            }
        }
    }
    figures_init(p);
    return SW_OK;
}

static void pkg_free(pkg_t *p)
{
    sw_rmin_free(&p->rm);
    free(p->held);
    p->held = NULL;
    sw_reserve_destroy(p->reserve);
    p->reserve = NULL;
}

sw_risk_t *sw_risk_create(const sw_scene_t *scenes, size_t n, const sw_risk_opts_t *o, int *err,
                          char *msg, size_t msglen)
{
    int e = SW_ENOMEM;
    sw_risk_t *r = calloc(1, sizeof *r);
    if (r) {
        if (o)
            r->o = *o;
        const double rate = r->o.reserve_rate == 0.0 ? SW_RISK_RATE : r->o.reserve_rate;
        r->n = n;
        r->p = calloc(n ? n : 1, sizeof *r->p);
        e = !r->p ? SW_ENOMEM : !(rate < 1e9) || (!scenes && n) ? SW_EINVAL : SW_OK;
        if (e == SW_EINVAL && msg)
            snprintf(msg, msglen, "reserve rate not a rate");
        r->period = rate > 0.0 ? 1.0 / rate : 0.0;
        for (size_t k = 0; e == SW_OK && k < n; k++)
            e = pkg_build(r, &scenes[k], &r->p[k], msg, msglen);
    }
    if (err)
        *err = e;
    if (e == SW_OK)
        return r;
    if (e == SW_ENOMEM && msg)
        snprintf(msg, msglen, "%s", sw_strerror(SW_ENOMEM));
    sw_risk_destroy(r);
    return NULL;
}

void sw_risk_destroy(sw_risk_t *r)
{
    if (!r)
        return;
    for (size_t k = 0; r->p && k < r->n; k++) pkg_free(&r->p[k]);
    free(r->p);
    free(r);
}

/* Evaluate package p's reserve on out's state. */
static void evaluate(pkg_t *p, const sw_output_t *out)
{
    sw_reserve_result_t res;
    const int rc = sw_reserve_eval(p->reserve, &out->state, &res);
    if (rc == SW_EINVAL)
        return; /* a state not finite: no value, none kept */
    if (rc != SW_OK)
        p->f.reserve_faults++;
    p->f.evaluations++;
    p->f.reserve_runs += !res.cached;
    p->f.reserve_g = res.reserve_g;
    p->f.direction = res.direction;
    p->f.pulse = res.pulse;
    p->f.reserve_t = out->t;
    if (!(res.reserve_g >= p->f.min_reserve_g)) { /* NAN min: the first */
        p->f.min_reserve_g = res.reserve_g;
        p->f.min_reserve_time = out->t;
        p->f.min_direction = res.direction;
        p->f.min_pulse = res.pulse;
    }
}

/* min_only: the held states evaluated, most threatened first; the
 * figures take the smallest found so far. */
static int resolve_held(pkg_t *p)
{
    const int rc = sw_rmin_search(&p->rm, p->held, p->nheld, 0, &p->best);
    p->nheld = 0;
    if (isfinite(p->best.min_g)) {
        p->f.min_reserve_g = p->best.min_g;
        p->f.min_reserve_time = p->best.min_time;
        p->f.min_direction = p->best.direction;
        p->f.min_pulse = p->best.pulse;
    }
    p->f.reserve_faults = p->best.faults;
    p->f.reserve_runs = p->best.evaluated;
    return rc;
}

/* A state the reserve would evaluate (reserve.h: finite, a phase of the
 * enum); the others get no value and are not kept, in either mode. */
static int state_usable(const sw_state_t *s)
{
    return isfinite(s->u) && isfinite(s->u_dot) && isfinite(s->theta) && isfinite(s->theta_dot) &&
           isfinite(s->z) && isfinite(s->z_dot) &&
           (s->phase == SW_PHASE_STUCK || s->phase == SW_PHASE_ROCKING ||
            s->phase == SW_PHASE_OVERTURNED);
}

int sw_risk_output(sw_risk_t *r, const sw_output_t *out)
{
    if (!r || !out || out->pkg >= r->n)
        return SW_EINVAL;
    pkg_t *p = &r->p[out->pkg];
    if (!p->reserve || !isfinite(out->t))
        return 0;
    if (!sw_sched_due(&p->due, out->t, r->period))
        return 0;
    if (!p->held) {
        evaluate(p, out);
        return 1;
    }
    if (!state_usable(&out->state))
        return 0;
    sw_rmin_state_t *x = &p->held[p->nheld++];
    memset(x, 0, sizeof *x);
    x->t = out->t;
    x->s = out->state;
    p->f.evaluations++;
    if (p->nheld == SW_RISK_MIN_STATES) {
        const int rc = resolve_held(p);
        if (rc < 0)
            return rc;
    }
    return 0;
}

int sw_risk_resolve(sw_risk_t *r, size_t k)
{
    if (!r || k >= r->n)
        return SW_EINVAL;
    pkg_t *p = &r->p[k];
    return p->held && p->nheld ? resolve_held(p) : SW_OK;
}

int sw_risk_event(sw_risk_t *r, const sw_event_t *ev, sw_settle_span_t *closed)
{
    if (!r || !ev || ev->pkg >= r->n)
        return SW_EINVAL;
    pkg_t *p = &r->p[ev->pkg];
    const int f = p->settles ? sw_settle_feed(&p->settle, ev, closed) : SW_SETTLE_REPORT;
    if (f & SW_SETTLE_CLOSED)
        p->f.settling_spans++;
    if (ev->kind == SW_EV_IMPACT) {
        if (f & SW_SETTLE_REPORT)
            p->f.impacts++;
        else
            p->f.micro_impacts++;
    }
    return f;
}

int sw_risk_finish(sw_risk_t *r, size_t k, sw_settle_span_t *closed)
{
    if (!r || k >= r->n || !r->p[k].settles)
        return 0;
    const int closed_one = sw_settle_finish(&r->p[k].settle, closed);
    r->p[k].f.settling_spans += closed_one;
    return closed_one;
}

const sw_risk_pkg_t *sw_risk_pkg(const sw_risk_t *r, size_t k)
{
    return r && k < r->n ? &r->p[k].f : NULL;
}

int sw_risk_replace(sw_risk_t *r, size_t k, const sw_scene_t *scene, char *msg, size_t msglen)
{
    if (!r || !scene || k >= r->n) {
        if (msg)
            snprintf(msg, msglen, "no such package");
        return SW_EINVAL;
    }
    pkg_t fresh;
    const int rc = pkg_build(r, scene, &fresh, msg, msglen);
    if (rc != SW_OK) {
        pkg_free(&fresh);
        return rc;
    }
    pkg_free(&r->p[k]);
    r->p[k] = fresh;
    r->p[k].f.no_reserve = r->p[k].no_reserve[0] ? r->p[k].no_reserve : NULL; /* not fresh's */
    return SW_OK;
}

void sw_risk_reset(sw_risk_t *r)
{
    for (size_t k = 0; r && k < r->n; k++) figures_init(&r->p[k]);
}
