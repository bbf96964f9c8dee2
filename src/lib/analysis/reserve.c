/* SPDX-License-Identifier: GPL-3.0-or-later */
/* reserve.c - the reserve in g (reserve.h): the smallest design pulse that
 * would overturn a package from its current state, found by runs of
 * private engines through the public engine API only.
 *
 * One evaluation is a scan-then-bisect search over every design pulse
 * and direction at once: a resumable search (search_int.h) of one
 * amplitude a round per pulse and direction, merged here.  What keeps it
 * cheap without hiding a lower overturning amplitude (docs/reserve.md
 * gives the arguments in full):
 *   - every scan starts at a proven lower bound, not at a guess:
 *     the lift bound (a package that never leaves its support cannot
 *     overturn: on the bed a pulse below g tan(alpha) lifts nothing; a
 *     stuck frame is linear until uplift, so the lowest lifting amplitude
 *     is read off its linear response, sampled finely, with a rigorous
 *     energy bound on the ringing after the samples end), and the energy
 *     bound (the work of a pulse is at most its velocity change times the
 *     largest velocity the package's energy allows, and overturning needs
 *     the barrier's energy);
 *   - a run stops as soon as its outcome is certain: the bare block's
 *     free-rocking margin is exact, so a bare run ends with the pulse; a
 *     frame or cushion run ends when the total-energy certificate
 *     (margin_bound > 0) holds after the pulse, or at overturn;
 *   - the scans of all pulses and directions are merged: the lowest next
 *     scan point of them all is tried first, so the first overturn found
 *     is the lowest on every grid and no scan runs past it (values that
 *     could not be the minimum are never computed); the other scans are
 *     then run once at that bracket's top, since their grids differ and
 *     one may overturn below it, and bisected where they do;
 *   - what is published is the bracket's safe end (an amplitude run and
 *     survived, or a proven bound), never above the true reserve;
 *   - the engines compute no report (outcome_only): no peaks, tips or
 *     margins inside their runs, only the state the certificate reads;
 *   - a state that is its own mirror image (upright and still) needs one
 *     direction: the models are symmetric under theta -> -theta,
 *     u -> -u, a_g -> -a_g;
 *   - the value at rest is computed once, by create, with the same
 *     search, and returned for states at exact rest;
 *   - steps are a fixed fraction of the shortest period of the run
 *     (SW_RESERVE_STEPS per period), not the 1 ms of a 1 kHz log: the
 *     pulse is a smooth function, and the 1 % answer does not need
 *     1e-11 rad (docs/accuracy-speed.md measures what this costs in
 *     accuracy).
 * Not done: starting the scan from the previous evaluation's value.
 * Nothing bounds how much the reserve can drop in 0.1 s of rocking (an
 * impact or a turning point changes it abruptly), so such a start could
 * step over a lower overturning amplitude.
 *
 * Everything is allocated in create; eval allocates nothing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/engine.h"
#include "swaywatch/model.h"
#include "swaywatch/pulse.h"
#include "swaywatch/reserve.h"
#include "swaywatch/run.h"
#include "swaywatch/status.h"

#include "model_traits.h"
#include "reserve_lift.h"
#include "run_int.h" /* sw_set_msg */
#include "search_int.h"

#define DEFAULT_STEP 0.02
#define DEFAULT_TOL 0.01
#define DEFAULT_X_MAX 20.0 /* in units of g tan(alpha), as the boundary search */
/* adaptive schemes: the answer is wanted to 1 %; docs/accuracy-speed.md
 * measures that no answer moves by more than that against rk8pd */
#define DEFAULT_RTOL 3e-4
#define DEFAULT_ATOL 1e-7
#define DEFAULT_REST_EPS 1e-6  /* rest below 1e-6 of the barrier: ends impact cascades */
#define CHECKS_PER_PERIOD 32.0 /* certificate checks per rocking period of free motion */
#define ENERGY_SLACK 0.98      /* the energy bound is exact; the runs are not */
#define CERT_SLACK 0.99        /* the same for the certificate during a pulse */
#define CHECKS_PER_PULSE 8.0   /* certificate checks during a pulse (fewer cut adaptive steps) */

/* One design pulse: its engine and, for a frame, the stuck frame's linear
 * response (reserve_lift.h). */
typedef struct {
    double T;     /* s */
    double check; /* s, between certificate checks during the pulse: whole steps */
    sw_engine_t *e;
    sw_lift_table_t lift;
} pulse_ctx_t;

struct sw_reserve {
    sw_scene_t sc;
    sw_derived_t d;
    sw_reserve_opts_t o;
    double step, tol; /* relative */
    double max_g, floor_g;
    double lift_g;                /* g: g tan(alpha) / SW_G0 */
    const sw_model_traits_t *ops; /* the model's traits: they choose the bounds and the ends */
    sw_state_t rest_state;        /* the engine's state of rest (side aside) */
    double t_free;                /* s, free motion after a pulse */
    double chunk;                 /* s, between certificate checks after the pulse */
    double sqrt_eb;               /* sqrt(J/kg): square root of the barrier energy */
    double c_energy;              /* 1: sw_model_work_rate() */
    size_t np;
    pulse_ctx_t p[SW_DESIGN_PULSES_MAX];
    sw_reserve_result_t rest;
};

/* ---- bounds ------------------------------------------------------------- */

/* The energy argument (docs/reserve.md).  In the bed's frame the input
 * acts on the centre of mass of everything that moves, the rest of the
 * forces are conservative or dissipate, so d sqrt(E)/dt <= c |a| while
 * |theta| < alpha (the potential energy from rest is >= 0 there), with c
 * the model's work rate (sw_model_work_rate) and E per unit package mass.
 * Reaching |theta| = alpha needs E >= E_b. */
static double energy_bound(const sw_derived_t *d, double g, double sqrt_eb, double c,
                           const sw_state_t *s, double T)
{
    if (fabs(s->theta) >= d->alpha || s->phase == SW_PHASE_OVERTURNED || !isfinite(c))
        return 0.0;
    /* int |a| dt over the half-sine = 2 a_e T / pi; quiet input after the
     * pulse only loses energy */
    const double gap = sqrt_eb - sqrt(fmax(sw_model_energy(d, g, s), 0.0));
    if (!(gap > 0.0))
        return 0.0;
    return M_PI * gap / (2.0 * T * c) / SW_G0;
}

double sw_reserve_energy_bound(const sw_derived_t *d, double g, const sw_state_t *s, double T)
{
    if (!d || !s || !(T > 0.0) || !(g > 0.0))
        return 0.0;
    return energy_bound(d, g, sqrt(sw_model_barrier(d, g)), sw_model_work_rate(d), s, T);
}

/* The proven lower bound of the amplitude (g) that can overturn the
 * package from s with pulse P in direction dir, or 0 if none is known. */
static double lower_bound_g(const sw_reserve_t *R, const pulse_ctx_t *P, const sw_state_t *s,
                            int dir)
{
    /* the barrier and the work rate as create computed them (a cushion's
     * barrier is a Newton solve) */
    double x = ENERGY_SLACK * energy_bound(&R->d, R->sc.g, R->sqrt_eb, R->c_energy, s, P->T);
    if (s->phase == SW_PHASE_STUCK) {
        if (R->ops->lift_direct)
            x = fmax(x, R->lift_g); /* the half-sine's peak must reach g tan(alpha) */
        else if (R->ops->stuck_linear)
            x = fmax(x, sw_lift_table_bound(&P->lift, &R->d, R->sc.g, s, dir));
    }
    return x;
}

double sw_reserve_lower_bound(const sw_reserve_t *r, const sw_state_t *s, int dir, size_t pulse)
{
    if (!r || !s || pulse >= r->np || (dir != SW_RESERVE_BRAKING && dir != SW_RESERVE_ACCELERATING))
        return 0.0;
    return lower_bound_g(r, &r->p[pulse], s, dir);
}

/* ---- one run ------------------------------------------------------------- */

/* The reserve's certificate during a pulse (sw_run_until()): if even all
 * the work the rest of the pulse could do (c |a| int_t^T sin, c the work
 * rate) cannot lift sqrt(E) to the barrier's, the run is safe now. */
typedef struct {
    const sw_reserve_t *R;
    double w;  /* rad/s, the pulse's omega */
    double ca; /* sqrt(J/kg), c |a| / w */
} cert_t;

static int certify(void *user, double t, const sw_state_t *s)
{
    const cert_t *C = user;
    const sw_reserve_t *R = C->R;
    if (fabs(s->theta) >= R->d.alpha)
        return 0;
    const double E = fmax(sw_model_energy(&R->d, R->sc.g, s), 0.0); /* J/kg */
    return sqrt(E) + C->ca * (1.0 + cos(C->w * t)) < CERT_SLACK * R->sqrt_eb;
}

/* Run state s under a pulse of amplitude a (m/s^2, signed; 0 = quiet) and
 * decide: fills r->overturned, r->end, r->t_end, r->faults.  The pulse
 * goes in whole steps between checks of the certificate; a model whose
 * margin decides free rocking is decided at the pulse's end. */
static int run(const sw_reserve_t *R, const pulse_ctx_t *P, const sw_state_t *s, double a,
               sw_run_result_t *r)
{
    sw_engine_t *e = P->e;
    sw_engine_reset(e);
    int rc = sw_engine_set_state(e, 0, s);
    if (rc < 0)
        return rc;
    sw_pulse_t pl = {SW_PULSE_HALF_SINE, a, M_PI / P->T};
    const double w = M_PI / P->T;
    cert_t C = {R, w, R->c_energy * fabs(a) / w};
    const sw_run_until_t u = {.input = a != 0.0 ? sw_pulse_eval : NULL,
                              .input_user = &pl,
                              .t_input = P->T,
                              .check = P->check,
                              .certify = certify,
                              .cert_user = &C,
                              .t0 = 0.0,
                              .free_time = R->t_free,
                              .chunk = R->chunk,
                              .decide_at_once = 1,
                              .stop_on_fault = 1};
    if ((rc = sw_run_until(e, &u, &r->end, &r->t_end)) < 0)
        return rc;
    sw_summary_t sum;
    sw_engine_summary(e, 0, &sum);
    r->faults = r->end == SW_END_TIMEOUT ? sum.faults : 0;
    r->overturned = r->end == SW_END_OVERTURN || r->end == SW_END_FALLING;
    return r->faults ? SW_EFAULT : SW_OK;
}

/* ---- evaluation ---------------------------------------------------------- */

/* The state of rest as the engine makes it (a reset engine's), whatever
 * the model: on the bed stuck, on a frame stuck and centred, on a cushion
 * upright and still at its static deflection. */
static int is_rest(const sw_reserve_t *R, const sw_state_t *s)
{
    const sw_state_t *r = &R->rest_state;
    return s->phase == r->phase && s->theta == r->theta && s->theta_dot == r->theta_dot &&
           s->u == r->u && s->u_dot == r->u_dot && s->z == r->z && s->z_dot == r->z_dot;
}

int sw_reserve_is_rest(const sw_reserve_t *r, const sw_state_t *s)
{
    return r && s && is_rest(r, s);
}

static int state_ok(const sw_state_t *s)
{
    return isfinite(s->u) && isfinite(s->u_dot) && isfinite(s->theta) && isfinite(s->theta_dot) &&
           isfinite(s->z) && isfinite(s->z_dot) &&
           (s->phase == SW_PHASE_STUCK || s->phase == SW_PHASE_ROCKING ||
            s->phase == SW_PHASE_OVERTURNED);
}

/* Upright, still and centred: its own mirror image. */
static int symmetric(const sw_state_t *s)
{
    return s->theta == 0.0 && s->theta_dot == 0.0 && s->u == 0.0 && s->u_dot == 0.0;
}

static void result_zero(sw_reserve_result_t *out)
{
    out->reserve_g = out->safe_g = out->over_g = 0.0;
    out->found = 1;
    out->direction = 0;
    out->pulse = 0.0;
    out->dir_g[0] = out->dir_g[1] = 0.0;
    out->dir_exact[0] = out->dir_exact[1] = 1;
}

/* One scan: a design pulse in one direction, from its lower bound up, a
 * search in rounds of one amplitude (search_int.h) on the fixed grid
 * lo (1 + step)^k.  Its S.lo is the safe end: the proven bound (0 if
 * none), then each amplitude run and found safe, in increasing order; no
 * amplitude of this scan below it overturns (up to a window narrower
 * than a scan step). */
typedef struct {
    const pulse_ctx_t *P;
    int dir;
    int bounded; /* the scan starts at the proven bound (else at the floor, above it) */
    sw_search_t S;
    sw_threshold_t th; /* found: (S.lo, th.x] holds the scan's threshold */
} scan_t;

/* Run scan c's round (one amplitude) from s and feed it to its search.  A
 * faulted run counts as safe (and is reported by the caller); a failed
 * one is counted too. */
static int scan_run(const sw_reserve_t *R, const sw_state_t *s, scan_t *c, long *trials,
                    int *faulted)
{
    sw_run_result_t *r = &c->S.r[0];
    memset(r, 0, sizeof *r);
    (*trials)++;
    const int rc = run(R, c->P, s, c->dir * c->S.x[0] * SW_G0, r);
    if (rc == SW_EFAULT) {
        *faulted = 1;
        r->overturned = 0;
    } else if (rc < 0) {
        return rc;
    }
    sw_search_feed(&c->S);
    return SW_OK;
}

/* Run scan c's search to its end: its bracket bisected to tol. */
static int scan_finish(const sw_reserve_t *R, const sw_state_t *s, scan_t *c, long *trials,
                       int *faulted)
{
    int rc = SW_OK;
    while (rc == SW_OK && sw_search_points(&c->S)) rc = scan_run(R, s, c, trials, faulted);
    return rc;
}

/* The merged scan over the n scans (pulses x directions): always try the
 * lowest next scan point of them all, so that the first overturn found is
 * the lowest on every scan's grid, and no scan goes past it; bisect that
 * scan.  Another scan's threshold may still lie between its last safe
 * grid point and the bracket's top (the grids differ): every other scan
 * is run at the top, lowered as it goes, and bisected where it
 * overturns.  Then no scan overturns below the smallest of their safe
 * ends, and one overturned within tol above it.  Returns SW_OK or the
 * first error. */
static int merged_scan(const sw_reserve_t *R, const sw_state_t *s, scan_t *c, int n, long *trials,
                       int *faulted)
{
    scan_t *b;
    int rc;
    do {
        b = NULL;
        double x = INFINITY;
        for (int i = 0; i < n; i++)
            if (c[i].S.phase == SW_SEARCH_SCAN && sw_search_points(&c[i].S) && c[i].S.x[0] < x) {
                x = c[i].S.x[0];
                b = &c[i];
            }
        if (!b)
            return SW_OK; /* nothing overturns up to max_g */
        if ((rc = scan_run(R, s, b, trials, faulted)) < 0)
            return rc;
    } while (!b->S.r[0].overturned);
    if ((rc = scan_finish(R, s, b, trials, faulted)) < 0)
        return rc;
    double top = b->th.x;
    for (int i = 0; i < n; i++) {
        scan_t *ci = &c[i];
        /* every grid point of ci below b's overturn was run and survived;
         * its next is at or above it */
        if (ci == b || ci->S.phase != SW_SEARCH_SCAN || !(ci->S.lo < top))
            continue;
        sw_search_probe(&ci->S, top);
        if ((rc = scan_finish(R, s, ci, trials, faulted)) < 0)
            return rc;
        if (ci->th.found)
            top = ci->th.x;
    }
    return SW_OK;
}

/* The scans of one pass into c, each from its lower bound: every design
 * pulse in the first ndir directions (braking first), or in direction
 * number only (>= 0) alone.  Returns how many. */
static int scans_of(const sw_reserve_t *R, const sw_state_t *s, int ndir, int only, scan_t c[])
{
    int n = 0;
    for (int k = 0; k < ndir; k++) {
        const int dir = k == 0 ? SW_RESERVE_BRAKING : SW_RESERVE_ACCELERATING;
        if (only >= 0 && k != only)
            continue;
        for (size_t j = 0; j < R->np; j++) {
            scan_t *ci = &c[n++];
            ci->P = &R->p[j];
            ci->dir = dir;
            const sw_search_how_t how = {
                .per_round = 1, .fixed_step = 1, .safe = lower_bound_g(R, ci->P, s, dir)};
            ci->bounded = how.safe >= R->floor_g;
            const sw_search_opts_t so = {.x_min = ci->bounded ? how.safe : R->floor_g,
                                         .x_max = R->max_g,
                                         .step = R->step,
                                         .tol = R->tol};
            /* a bound at or above max_g: safe up to max_g, nothing to scan */
            if (sw_search_init_how(&ci->S, &so, &how, &ci->th) != SW_OK)
                ci->S.lo = R->max_g;
        }
    }
    return n;
}

/* The result of the scans c[0..n): the reserve is the smallest safe end
 * (no scan overturns below it), each direction's the smallest of its
 * scans; a direction is exact when one of its scans overturned within tol
 * above that, or none overturned up to max_g.  The direction and pulse
 * are those of the scan whose safe end is the reserve. */
static void conclude(const sw_reserve_t *R, const scan_t *c, int n, int mirror,
                     sw_reserve_result_t *out)
{
    double lo[2] = {R->max_g, R->max_g}, top[2] = {INFINITY, INFINITY}; /* g */
    int best = -1;
    for (int i = 0; i < n; i++) {
        const int di = c[i].dir == SW_RESERVE_BRAKING ? 0 : 1;
        lo[di] = fmin(lo[di], c[i].S.lo);
        if (!c[i].th.found)
            continue;
        top[di] = fmin(top[di], c[i].th.x);
        if (best < 0 || c[i].S.lo < c[best].S.lo ||
            (c[i].S.lo == c[best].S.lo && c[i].th.x < c[best].th.x))
            best = i;
    }
    if (mirror) {
        lo[1] = lo[0];
        top[1] = top[0];
    }
    for (int di = 0; di < 2; di++) {
        out->dir_g[di] = lo[di];
        out->dir_exact[di] = isfinite(top[di]) ? top[di] / lo[di] - 1.0 <= R->tol * (1.0 + 1e-9)
                                               : !(lo[di] < R->max_g);
    }
    out->found = best >= 0;
    if (!out->found) {
        out->reserve_g = out->safe_g = R->max_g;
        out->over_g = INFINITY;
        out->direction = SW_RESERVE_BRAKING;
        out->pulse = R->p[0].T;
        return;
    }
    out->reserve_g = out->safe_g = fmin(lo[0], lo[1]);
    out->over_g = fmin(top[0], top[1]);
    out->direction = c[best].dir;
    out->pulse = c[best].P->T;
    /* overturned at the floor, the first amplitude tried: nothing below it
     * was searched */
    out->at_floor = c[best].th.at_min && !c[best].bounded;
}

static int compute(sw_reserve_t *R, const sw_state_t *s, sw_reserve_result_t *out)
{
    memset(out, 0, sizeof *out);
    int faulted = 0;
    if (s->phase == SW_PHASE_OVERTURNED) {
        result_zero(out);
        return SW_OK;
    }
    /* quiet input: the same for every pulse */
    sw_run_result_t rq;
    memset(&rq, 0, sizeof rq);
    out->trials++;
    int rc = run(R, &R->p[0], s, 0.0, &rq);
    if (rc == SW_EFAULT)
        faulted = 1;
    else if (rc < 0)
        return rc;
    if (rq.overturned) {
        result_zero(out);
        return SW_OK;
    }

    /* A state that is its own mirror image needs the braking pulses only;
     * with each_direction the two directions are scanned apart, so that
     * each gets its own value. */
    const int mirror = symmetric(s);
    const int ndir = mirror ? 1 : 2;
    const int passes = R->o.each_direction && !mirror ? 2 : 1;
    scan_t c[2 * SW_DESIGN_PULSES_MAX];
    int n = 0;
    for (int pass = 0; pass < passes; pass++) {
        const int m = scans_of(R, s, ndir, passes == 2 ? pass : -1, c + n);
        rc = merged_scan(R, s, c + n, m, &out->trials, &faulted);
        if (rc < 0)
            return rc;
        n += m;
    }
    conclude(R, c, n, mirror, out);
    return faulted ? SW_EFAULT : SW_OK;
}

int sw_reserve_eval(sw_reserve_t *r, const sw_state_t *s, sw_reserve_result_t *out)
{
    if (!r || !s || !out)
        return SW_EINVAL;
    if (!state_ok(s))
        return SW_EINVAL;
    if (!r->o.no_cache && is_rest(r, s)) {
        *out = r->rest;
        return SW_OK;
    }
    return compute(r, s, out);
}

void sw_reserve_rest(const sw_reserve_t *r, sw_reserve_result_t *out)
{
    if (r && out)
        *out = r->rest;
}

size_t sw_reserve_pulses(const sw_reserve_t *r, const double **T)
{
    static const double none[1] = {0.0};
    if (!r) {
        if (T)
            *T = none;
        return 0;
    }
    if (T)
        *T = r->sc.design_pulse;
    return r->np;
}

/* ---- create / destroy ---------------------------------------------------- */

void sw_reserve_destroy(sw_reserve_t *r)
{
    if (!r)
        return;
    for (size_t j = 0; j < r->np; j++) {
        sw_engine_destroy(r->p[j].e);
        sw_lift_table_free(&r->p[j].lift);
    }
    free(r);
}

/* dt for pulse T: the shortest of the pulse's period 2T, the rocking
 * period and the scene's fastest period, over SW_RESERVE_STEPS. */
static double auto_dt(const sw_derived_t *d, double T)
{
    double period = fmin(2.0 * T, 2.0 * M_PI / d->p); /* s */
    if (d->omega_max > 0.0)
        period = fmin(period, 2.0 * M_PI / d->omega_max);
    return period / SW_RESERVE_STEPS;
}

/* The private engine of design pulse P (duration P->T set) and what its
 * runs need: SW_OK, or an error with msg set. */
static int pulse_make(const sw_reserve_t *R, pulse_ctx_t *P, char *msg, size_t msglen)
{
    const sw_derived_t *d = &R->d;
    sw_engine_opts_t eo = R->o.run.engine;
    eo.on_event = NULL;
    eo.outcome_only = 1; /* the outcome alone: no report to time or compute */
    eo.check_default = 0;
    eo.on_state = NULL;
    eo.user = NULL;
    eo.dt_forced = 0;
    if (!(eo.dt > 0.0) && !(eo.accuracy > 0.0))
        eo.dt = auto_dt(d, P->T);
    /* checks at whole steps, so that they do not cut the step grid */
    const double dt = eo.dt > 0.0 ? eo.dt : auto_dt(d, P->T);
    /* a fixed step that a stiff support forces down to microseconds
     * makes every run millions of steps: refuse, and say why */
    const double max_steps =
        R->o.max_run_steps > 0.0 ? R->o.max_run_steps : SW_RESERVE_MAX_RUN_STEPS;
    const double steps = (P->T + R->t_free) / dt;
    if (!(eo.accuracy > 0.0) && !(steps <= max_steps)) {
        sw_set_msg(msg, msglen,
                   "a design-pulse run would take %.3g steps of %.3g s (%.3g s of "
                   "pulse and free motion), more than %.3g; the scene is too stiff for the "
                   "reserve to keep up",
                   steps, dt, P->T + R->t_free, max_steps);
        return SW_ETOOBIG;
    }
    P->check = dt * ceil(P->T / CHECKS_PER_PULSE / dt);
    if (!(eo.rtol > 0.0))
        eo.rtol = DEFAULT_RTOL;
    if (!(eo.atol > 0.0))
        eo.atol = DEFAULT_ATOL;
    if (!(eo.rest_eps > 0.0))
        eo.rest_eps = DEFAULT_REST_EPS;
    char why[256] = "";
    int err = SW_OK;
    P->e = sw_engine_create(&R->sc, 1, &eo, &err, why, sizeof why);
    if (!P->e) {
        if (err == SW_OK)
            err = SW_ENOMEM;
        sw_set_msg(msg, msglen, "%s", why[0] ? why : sw_strerror(err));
        return err;
    }
    if (R->ops->stuck_linear && (err = sw_lift_table_make(&P->lift, d, P->T)) != SW_OK) {
        sw_set_msg(msg, msglen, "out of memory");
        return err;
    }
    return SW_OK;
}

sw_reserve_t *sw_reserve_create(const sw_scene_t *sc, const sw_reserve_opts_t *opts, int *err,
                                char *msg, size_t msglen)
{
    int e_ = SW_OK;
    if (!err)
        err = &e_;
    *err = SW_OK;
    sw_set_msg(msg, msglen, "%s", "");
    if (!sc) {
        *err = SW_EINVAL;
        sw_set_msg(msg, msglen, "no scene");
        return NULL;
    }
    sw_reserve_t *R = calloc(1, sizeof *R);
    if (!R) {
        *err = SW_ENOMEM;
        sw_set_msg(msg, msglen, "out of memory");
        return NULL;
    }
    R->sc = *sc;
    if (opts)
        R->o = *opts;
    if (sw_scene_validate(&R->sc, &R->d, NULL, NULL, NULL) != SW_OK) {
        *err = SW_EINVAL;
        sw_set_msg(msg, msglen, "scene '%s' is not valid", sc->name);
        goto fail;
    }
    const sw_derived_t *d = &R->d;
    R->step = R->o.step > 0.0 ? R->o.step : DEFAULT_STEP;
    R->tol = R->o.tol > 0.0 ? R->o.tol : DEFAULT_TOL;
    R->lift_g = R->sc.g * tan(d->alpha) / SW_G0;
    R->ops = sw_model_traits_of(d->model);
    R->max_g = R->o.max_g > 0.0 ? R->o.max_g : DEFAULT_X_MAX * R->lift_g;
    R->floor_g = R->o.floor_g > 0.0 ? R->o.floor_g : SW_RESERVE_FLOOR_G;
    if (!isfinite(R->step) || !isfinite(R->tol) || !isfinite(R->max_g) || !isfinite(R->floor_g) ||
        !(R->floor_g < R->max_g)) {
        *err = SW_EINVAL;
        sw_set_msg(msg, msglen, "bad reserve options (step %g, tol %g, floor %g g, max %g g)",
                   R->step, R->tol, R->floor_g, R->max_g);
        goto fail;
    }
    const double fp = R->o.run.free_periods > 0.0 ? R->o.run.free_periods : SW_RESERVE_FREE_PERIODS;
    R->t_free = fp * 2.0 * M_PI / d->p;
    R->chunk = 2.0 * M_PI / d->p / CHECKS_PER_PERIOD;
    R->sqrt_eb = sqrt(sw_model_barrier(d, R->sc.g));
    R->c_energy = sw_model_work_rate(d);

    R->np = (size_t)R->sc.n_design_pulse;
    for (size_t j = 0; j < R->np; j++) {
        R->p[j].T = R->sc.design_pulse[j];
        if ((*err = pulse_make(R, &R->p[j], msg, msglen)) != SW_OK)
            goto fail;
    }

    /* the value at rest, by the same search as any state */
    sw_engine_reset(R->p[0].e);
    sw_engine_get_state(R->p[0].e, 0, &R->rest_state);
    const int rc = compute(R, &R->rest_state, &R->rest);
    if (rc < 0) {
        *err = rc;
        sw_set_msg(msg, msglen, "the reserve at rest: %s", sw_strerror(rc));
        goto fail;
    }
    R->rest.cached = 1;
    R->rest.trials = 0;
    return R;
fail:
    sw_reserve_destroy(R);
    return NULL;
}
