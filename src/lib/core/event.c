/* SPDX-License-Identifier: GPL-3.0-or-later */
/* event.c - the event layer (GSL has none; CVODE's root check and root
 * find): events inside a step, for every model alike.
 *
 * After a step the model names the events that may have happened in it
 * (ops->candidates, from the endpoint values).  A candidate crossing is
 * confirmed on the cubic Hermite interpolant of its event function over
 * the step (values and time derivatives at both ends, hermite.h), split
 * into monotone pieces so that a double crossing inside one step is not
 * missed, and bracketed by bisection.  The root is then polished by
 * re-stepping from the step's start with the same scheme and Newton
 * iterations on the event function, so the event lies on the scheme's own
 * solution and the result does not depend on where the sample grid falls.
 * Events that change the dynamics (uplift, impact, overturn, a kink to cut
 * at) end the step; tipping, peaks of |theta| and a cushion's first lift
 * are only timed.  Like CVODE's rootsfound, both are handed back: the cut
 * with its time and state, polished, and the timed events before it with
 * their times and states;
 * what follows from them (the maps, the reports) is the package's (pkg.c),
 * which the engine hands them to. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "event.h"
#include "hermite.h"
#include "model_ops.h"
#include "step.h"
#include "swaywatch/status.h"

/* The ends of the step being examined: the states, the input there, the
 * derivatives under it and each candidate's event function (value v,
 * time derivative d), from one model call per end. */
typedef struct {
    const double *y0, *y1;
    double f0[SW_NMAX], f1[SW_NMAX];
    double v0[SW_MAX_CANDS], d0[SW_MAX_CANDS], v1[SW_MAX_CANDS], d1[SW_MAX_CANDS];
} sw_ends_t;

/* Where candidate i's function rises through 0 over the step, in [0, 1]
 * by its rule (SW_RULE_*), or -1. */
static double root_of(const sw_evcand_t *c, int i, double h, const sw_ends_t *E)
{
    const double v0 = E->v0[i], d0 = E->d0[i], v1 = E->v1[i], d1 = E->d1[i];
    if (c->rule == SW_RULE_KINK && v0 > 0.0)
        return -1.0; /* crossed already: we are past this kink */
    /* Clearly below the threshold all step: the interpolant exceeds
     * max(v0, v1) by at most 4/27 h (|d0| + |d1|) (its two derivative
     * terms), so it has no rise, and the search would find none.  (Both
     * below 0: their larger one compared in place, no libm call.) */
    if (c->clear && v1 < 0.0 && v0 < 0.0 && (v0 > v1 ? v0 : v1) < -0.5 * h * (fabs(d0) + fabs(d1)))
        return -1.0;
    /* on the event function's interpolant over the step */
    if (c->rule == SW_RULE_PLAIN)
        return sw_herm_rise(v0, d0, v1, d1, h, NULL);
    if (c->rule != SW_RULE_KINK && (v0 > 0.0 || (v0 == 0.0 && d0 > 0.0)))
        return 0.0; /* already through at the start of the step */
    double tol;
    double tau = sw_herm_rise(v0, d0, v1, d1, h, &tol);
    if (tau < 0.0 && v0 < 0.0 && v1 > tol)
        tau = 1.0; /* round-off in the pieces */
    return tau;
}

/* The peak of |theta| inside a step: where the turn function rises before
 * tau = lim, polished by re-stepping so that max |theta| is as accurate as
 * the scheme, even for long adaptive steps.  1 with the peak in *out. */
static int find_peak(sw_stepper_t *W, const sw_evcand_t *c, double t0, int i, double h,
                     const sw_ends_t *E, double lim, sw_timed_t *out)
{
    const double tau = root_of(c, i, h, E);
    if (!(tau > 0.0 && tau <= lim))
        return 0;
    sw_event_polish(W, c->ev, t0, h, E->y0, tau, out);
    return 1;
}

int sw_event_keep_outcome(sw_evcand_t c[], int nc)
{
    int n = 0;
    for (int i = 0; i < nc; i++)
        if (c[i].role == SW_ROLE_CUT)
            c[n++] = c[i];
    return n;
}

int sw_event_locate(sw_stepper_t *W, const sw_input_ends_t *X, double t0, double h,
                    const double y0[], const double y1[], const sw_evcand_t c[], int nc,
                    sw_timed_t *cut, sw_timed_t timed[], int *ntimed)
{
    const sw_model_t *M = W->ms.m;
    const double t1 = t0 + h;
    /* the input at the step's ends: the engine's where they are the
     * interval's (a step per sample), else evaluated here */
    const sw_input_at_t u0 = t0 == X->t[0] ? X->u[0] : sw_input_at(M->in, M->g, t0),
                        u1 = t1 == X->t[1] ? X->u[1] : sw_input_at(M->in, M->g, t1);
    sw_ends_t E; /* not zeroed: the two calls below write what is read */
    E.y0 = y0;
    E.y1 = y1;
    M->ops->events(M, W->ms.s, &u0, y0, c, nc, E.f0, E.v0, E.d0);
    M->ops->events(M, W->ms.s, &u1, y1, c, nc, E.f1, E.v1, E.d1);
    /* the earliest cutting event ends the step */
    int best = SW_EVF_NONE;
    double best_tau = 2.0;
    for (int i = 0; i < nc; i++) {
        if (c[i].role != SW_ROLE_CUT)
            continue;
        const double tau = root_of(&c[i], i, h, &E);
        const int inside = c[i].rule == SW_RULE_KINK ? tau > 0.0 && tau < 1.0 : tau >= 0.0;
        if (inside && tau < best_tau) {
            best_tau = tau;
            best = c[i].ev;
        }
    }
    /* what happens before it is timed, in the candidates' order */
    const double lim = best == SW_EVF_NONE ? 1.0 : best_tau;
    int n = 0;
    for (int i = 0; i < nc; i++) {
        if (c[i].role == SW_ROLE_CUT)
            continue;
        sw_timed_t *T = &timed[n];
        T->role = c[i].role;
        if (c[i].role == SW_ROLE_PEAK) {
            n += find_peak(W, &c[i], t0, i, h, &E, lim, T);
            continue;
        }
        const double tau = root_of(&c[i], i, h, &E);
        if (!(tau >= 0.0 && tau <= lim))
            continue;
        sw_herm_state(M->n, h, y0, E.f0, y1, E.f1, tau, T->y);
        T->t = t0 + tau * h;
        T->u = sw_input_at(M->in, M->g, T->t);
        n++;
    }
    *ntimed = n;
    if (best != SW_EVF_NONE) { /* the cut itself, on the scheme's own solution */
        cut->role = SW_ROLE_CUT;
        sw_event_polish(W, best, t0, h, y0, lim, cut);
    }
    return best;
}

/* Polish the event time: re-step from (t0, y0) with Newton iterations on
 * the event function (the model's one call per iterate, its value and
 * derivative there), then make sure the returned instant is at or just
 * past the crossing (value >= 0): an uplift placed a hair early would leave
 * the package pushed the wrong way and chatter.  Leaves the event's time,
 * the state and the input there in *at: the input is the last iterate's
 * when that is the returned time, as it is unless the iterations ran
 * out. */
void sw_event_polish(sw_stepper_t *W, int ev, double t0, double h, const double y0[], double tau,
                     sw_timed_t *at)
{
    const sw_model_t *M = W->ms.m;
    const sw_evcand_t c = {.ev = (unsigned char)ev};
    double ts = t0 + tau * h, v = 0.0, d = 0.0, f[SW_NMAX];
    double tu = NAN; /* s, where at->u was evaluated */
    double *y = at->y;
    if (tau == 0.0) {
        memcpy(y, y0, sizeof(double) * (size_t)M->n);
        ts = t0;
        goto done;
    }
    const double t1 = t0 + h;
    for (int it = 0; it < 8; it++) {
        if (W->restep(&W->ms, t0, ts - t0, y0, y) != SW_OK)
            goto done;
        at->u = sw_input_at(M->in, M->g, ts);
        tu = ts;
        M->ops->events(M, W->ms.s, &at->u, y, &c, 1, f, &v, &d);
        if (v == 0.0 || d == 0.0)
            break;
        double tn = ts - v / d;
        if (tn <= t0)
            tn = 0.5 * (t0 + ts);
        if (tn > t1)
            tn = t1;
        const double dt = fabs(tn - ts);
        if (dt <= 4.0 * DBL_EPSILON * fmax(1.0, fabs(ts)))
            break;
        ts = tn;
    }
    for (int it = 0; it < 8 && v < 0.0 && ts < t1; it++) {
        double dt = d > 0.0 ? -2.0 * v / d : 0.0;
        dt = fmax(dt, 8.0 * DBL_EPSILON * fmax(1.0, fabs(ts)) * (1 << it));
        ts = fmin(t1, ts + dt);
        if (W->restep(&W->ms, t0, ts - t0, y0, y) != SW_OK)
            break;
        at->u = sw_input_at(M->in, M->g, ts);
        tu = ts;
        M->ops->events(M, W->ms.s, &at->u, y, &c, 1, f, &v, &d);
    }
done:
    if (tu != ts)
        at->u = sw_input_at(M->in, M->g, ts);
    at->t = ts;
}
