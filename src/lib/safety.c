/* SPDX-License-Identifier: GPL-3.0-or-later */
/* safety.c - the safety factors of a recorded log (sweep.h): for each
 * scene, the smallest scale of the log's longitudinal acceleration that
 * overturns the package, found by running the log many times ("trials").
 *
 * Two things make an hour-long log affordable.
 *
 * Trials start as late as their outcome allows ("checkpoints").  Nothing
 * can overturn a package before it leaves its rest contact, and until then
 * its motion is known without running the model:
 *   - on the bed it stands still while |x a_g| < g_eff tan(alpha) at the
 *     samples (the input is linear between them), so a trial at scale x
 *     starts at the sample before the first one that can lift it, and
 *     whenever the package is at rest again it jumps to the sample before
 *     the next one.  The engine integrates on the log's own time origin
 *     (sw_engine_set_origin), so this is the very arithmetic of a run from
 *     the start: the same result to the last bit;
 *   - on a frame the package rides the frame, a linear oscillator: its
 *     state at scale x is x times the state at scale 1, taken from one run
 *     at a scale far too small to lift anything (the probe), stored every
 *     CHECK samples.  A trial starts from the stored state before the first
 *     sample at which the scaled support acceleration can reach the uplift
 *     threshold (the same as a run from the start but for rounding);
 *   - on a cushion (on the bed, no cubic term, no vertical input) the
 *     rocking about rest is, to first order, a damped oscillator in closed
 *     form; the trial starts from its scaled state a lead-in before the
 *     first possible edge lift, long enough for what the linear state got
 *     wrong (second order in the tilt) to decay below FORGET of itself;
 *     and since the same holds after each stretch in which an edge lifted,
 *     a trial in which no edge has lifted for a lead-in jumps, as on the
 *     bed, to the linear state a lead-in before the next sample that can
 *     lift an edge at its scale (a soft cushion rocks under a calm road
 *     now and then all through a long log).
 * Elsewhere (a cushion on a frame, vertical input, adaptive schemes on a
 * frame, sample intervals long against the support's period) trials run
 * from the start.
 *
 * The searches of all scenes run at once on a pool of threads, in rounds
 * of SECTIONS trials: the scan takes SECTIONS points of its grid at a
 * time, and a bracket is cut into SECTIONS + 1 pieces, keeping the lowest
 * change from safe to overturning.  A round's points do not depend on the
 * number of threads, so neither does any result. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "run.h"
#include "swaywatch/model.h"
#include "swaywatch/status.h"
#include "swaywatch/sweep.h"

#define DEFAULT_STEP 0.02
#define DEFAULT_TOL 1e-3
#define DEFAULT_X_MAX 20.0
#define LIFT_MARGIN_LOG 0.9    /* probes are sampled only at the log's samples */
#define SECTIONS 4             /* trials per round of a search */
#define BLOCK 256              /* samples per block of the bed's lift index */
#define SUPER 256              /* blocks per superblock */
#define CHECK 256              /* samples between stored linear states */
#define BARE_EDGE (1.0 - 1e-9) /* rounding of the interpolated input, with room */
#define LONG_STEP 0.25         /* omega dt beyond which a sample interval may hide a peak */
#define FORGET 1e-6            /* cushion: share of the start state's error left after the lead */
#define NEAR_PEAK 0.25         /* peak |theta| / alpha from which the scan takes its finest step */
#define FAR_STEPS 5.0          /* the scan's step far from that, in --step */
#define MAX_THREADS 256

/* ---- checkpoints ----------------------------------------------------------- */

typedef enum { CK_NONE, CK_BARE, CK_FRAME, CK_CUSHION } ck_kind;

typedef struct {
    size_t i; /* sample */
    double s; /* the lowest scale at which a sample up to i can lift the package */
} rec_t;

/* What every trial of one scene uses, made once before its search. */
typedef struct {
    const sw_scene_t *sc;
    sw_derived_t d;
    const sw_log_t *log;
    const sw_run_opts_t *ro;
    ck_kind kind;
    double tan_alpha;
    double *blk, *sup; /* bed, cushion: minima of the lifting scale per block and
                          superblock */
    rec_t *rec;        /* frame, cushion: prefix minima of the lifting scale */
    size_t nrec, caprec;
    double *st;           /* unit-scale states every CHECK samples: (u, u') of the frame, or of
                             the cushion's rocking oscillator (theta = gain u) */
    double w, zeta, gain; /* cushion's rocking oscillator: rad/s, 1, theta per u (rad/m) */
    double lead;          /* s, cushion: lead-in before the first possible lift */
    size_t i_peak;        /* sample of the largest drive (frame, cushion) */
    double a_peak, bare_lift, lift_scale;
} prep_t;

/* The scale at which sample i lifts a package standing on the bed: 0 if
 * the bed falls away (g_eff <= 0), INFINITY without acceleration. */
static double bare_scale(const prep_t *P, size_t i)
{
    const sw_log_t *L = P->log;
    const double geff = P->sc->g + (L->a_z ? L->a_z[i] : 0.0); /* m/s^2 */
    if (!(geff > 0.0))
        return 0.0;
    const double a = fabs(L->a_g[i]);
    return a > 0.0 ? geff * P->tan_alpha / a : INFINITY;
}

/* The minima of the lifting scale per block and superblock, all
 * INFINITY. */
static int blocks_alloc(prep_t *P)
{
    const size_t n = P->log->n, nb = (n + BLOCK - 1) / BLOCK, ns = (nb + SUPER - 1) / SUPER;
    P->blk = malloc(nb * sizeof *P->blk);
    P->sup = malloc(ns * sizeof *P->sup);
    if (!P->blk || !P->sup)
        return SW_ENOMEM;
    for (size_t b = 0; b < nb; b++) P->blk[b] = INFINITY;
    for (size_t b = 0; b < ns; b++) P->sup[b] = INFINITY;
    return SW_OK;
}

/* Sample i lifts at scale s. */
static void block_min(prep_t *P, size_t i, double s)
{
    if (s < P->blk[i / BLOCK])
        P->blk[i / BLOCK] = s;
    if (s < P->sup[i / BLOCK / SUPER])
        P->sup[i / BLOCK / SUPER] = s;
}

static int prep_bare(prep_t *P)
{
    if (blocks_alloc(P) != SW_OK)
        return SW_ENOMEM;
    for (size_t i = 0; i < P->log->n; i++) block_min(P, i, bare_scale(P, i));
    P->kind = CK_BARE;
    return SW_OK;
}

/* The first sample of the first block after sample i's with a sample
 * that can lift at a scale up to X (blocks); n if none. */
static size_t next_block(const prep_t *P, size_t i, double X)
{
    const size_t n = P->log->n, nb = (n + BLOCK - 1) / BLOCK;
    size_t b = i / BLOCK + 1;
    while (b < nb) {
        if (b % SUPER == 0 && P->sup[b / SUPER] > X) {
            b = (b / SUPER + 1) * SUPER;
            continue;
        }
        if (P->blk[b] <= X)
            return b * BLOCK;
        b++;
    }
    return n;
}

/* The first sample at or after i that can lift a package on the bed at a
 * scale up to X; n if none. */
static size_t next_lift(const prep_t *P, size_t i, double X)
{
    const size_t n = P->log->n;
    while (i < n) {
        if (i % BLOCK == 0) {
            const size_t b = i / BLOCK;
            if (b % SUPER == 0 && P->sup[b / SUPER] > X) {
                i = (b / SUPER + 1) * SUPER * BLOCK;
                continue;
            }
            if (P->blk[b] > X) {
                i = (b + 1) * BLOCK;
                continue;
            }
        }
        if (bare_scale(P, i) <= X)
            return i;
        i++;
    }
    return n;
}

/* A new lowest lifting scale s at sample i. */
static int add_record(prep_t *P, size_t i, double s)
{
    if (P->nrec && !(s < P->rec[P->nrec - 1].s))
        return SW_OK;
    if (P->nrec == P->caprec) {
        const size_t cap = P->caprec ? 2 * P->caprec : 64;
        rec_t *r = realloc(P->rec, cap * sizeof *r);
        if (!r)
            return SW_ENOMEM;
        P->rec = r;
        P->caprec = cap;
    }
    P->rec[P->nrec++] = (rec_t){i, s};
    return SW_OK;
}

/* The first sample that can lift the package at scale X (records); n if
 * none. */
static size_t first_lift(const prep_t *P, double X)
{
    size_t lo = 0, hi = P->nrec; /* records: i increasing, s decreasing */
    while (lo < hi) {
        const size_t m = lo + (hi - lo) / 2;
        if (P->rec[m].s <= X)
            hi = m;
        else
            lo = m + 1;
    }
    return lo < P->nrec ? P->rec[lo].i : P->log->n;
}

static int store_state(prep_t *P, size_t i, double a, double b)
{
    if (i % CHECK)
        return SW_OK;
    P->st[2 * (i / CHECK)] = a;
    P->st[2 * (i / CHECK) + 1] = b;
    return SW_OK;
}

/* A sample interval too long for its samples to bound the support's
 * motion between them (a bridged gap): it may lift at any scale. */
static int long_interval(const prep_t *P, size_t i, double w)
{
    return i > 0 && w * (P->log->t[i] - P->log->t[i - 1]) > LONG_STEP;
}

/* The frame: one run at a scale far too small to lift anything, which
 * the stuck frame follows exactly (linear).  CK_NONE (no checkpoints) if
 * the scheme steps the stuck frame adaptively or the probe ever left the
 * stuck phase. */
static int prep_frame(prep_t *P, sw_runner_t *R)
{
    const sw_log_t *L = P->log;
    const sw_scheme_t *S = sw_scheme_lookup(sw_engine_scheme(R->e));
    if (!S || sw_scheme_adaptive(S) || (P->ro && P->ro->engine.stuck_stepped))
        return SW_OK;
    const double probe = 1e-4 * P->bare_lift;
    size_t next_restart = 0;
    double peak = 0.0;
    sw_runner_reset(R);
    for (size_t i = 0; i < L->n; i++) {
        while (next_restart < L->nrestart && L->restart[next_restart] <= i)
            if (L->restart[next_restart++] == i)
                sw_engine_restart(R->e);
        if (sw_engine_push(R->e, L->t[i], probe * L->a_g[i], L->a_z ? L->a_z[i] : 0.0) < 0)
            return SW_OK;
        sw_output_t o;
        sw_engine_get_output(R->e, 0, &o);
        if (o.state.phase != SW_PHASE_STUCK)
            return SW_OK;
        const double v = o.uplift_ratio / probe; /* at scale 1 */
        if (v > peak) {
            peak = v;
            P->i_peak = i;
        }
        const double s = long_interval(P, i, P->d.omega_b) ? 0.0 : v > 0.0 ? 1.0 / v : INFINITY;
        if (add_record(P, i, s) != SW_OK)
            return SW_ENOMEM;
        store_state(P, i, o.state.u / probe, o.state.u_dot / probe);
    }
    P->lift_scale = peak > 0.0 ? 1.0 / peak : INFINITY;
    P->kind = CK_FRAME;
    return SW_OK;
}

/* Decay rate (1/s) of the slower mode of a damped oscillator. */
static double decay_rate(double w, double zeta)
{
    return zeta < 1.0 ? zeta * w : w * (zeta - sqrt((zeta - 1.0) * (zeta + 1.0)));
}

/* A cushion on the bed: the rocking about rest to first order,
 *   (I_C + m h^2) theta'' + C b^2/3 theta' + (K b^2/3 - m g h) theta = -m h a_g,
 * in closed form between samples (sw_nj_step); an edge lifts when
 * b |theta| reaches the static deflection z_s. */
static int prep_cushion(prep_t *P)
{
    const sw_log_t *L = P->log;
    const sw_derived_t *d = &P->d;
    const double m = P->sc->mass, g = P->sc->g;
    const double I = d->I_C + m * d->h * d->h;                /* kg m^2 */
    const double k = d->K * d->b * d->b / 3.0 - m * g * d->h; /* N m/rad */
    const double c = d->C * d->b * d->b / 3.0;                /* N m s/rad */
    if (!(k > 0.0) || !(c > 0.0))
        return SW_OK;
    P->w = sqrt(k / I);
    P->zeta = c / (2.0 * I * P->w);
    P->gain = m * d->h / I;
    const double lam = fmin(decay_rate(P->w, P->zeta), decay_rate(d->omega_c, d->zeta_c));
    P->lead = log(1.0 / FORGET) / lam;
    const double z_s = sw_cushion_static_deflection(d, g); /* m */
    const double per = d->b * P->gain / z_s;               /* lift drive per unit u, 1/m */
    if (blocks_alloc(P) != SW_OK)
        return SW_ENOMEM;
    double u[2] = {0.0, 0.0}, peak = 0.0;
    size_t next_restart = 0;
    for (size_t i = 0; i < L->n; i++) {
        int fresh = i == 0;
        while (next_restart < L->nrestart && L->restart[next_restart] <= i)
            if (L->restart[next_restart++] == i)
                fresh = 1;
        if (fresh) {
            u[0] = u[1] = 0.0;
        } else {
            const double H = L->t[i] - L->t[i - 1];
            const double s = (L->a_g[i] - L->a_g[i - 1]) / H;
            double u1[2];
            sw_nj_step(P->w, P->zeta, H, L->a_g[i - 1], s, u, u1);
            u[0] = u1[0];
            u[1] = u1[1];
        }
        const double v = per * fabs(u[0]); /* drive / z_s at scale 1 */
        if (v > peak) {
            peak = v;
            P->i_peak = i;
        }
        const double s = long_interval(P, i, P->w) ? 0.0 : v > 0.0 ? 1.0 / v : INFINITY;
        if (add_record(P, i, s) != SW_OK)
            return SW_ENOMEM;
        block_min(P, i, s);
        store_state(P, i, u[0], u[1]);
    }
    P->lift_scale = peak > 0.0 ? 1.0 / peak : INFINITY;
    P->kind = CK_CUSHION;
    return SW_OK;
}

/* Without checkpoints: the lifting scale from a run far too small to lift
 * anything (linear to first order), as sweep.c's pulses do. */
static void prep_probe(prep_t *P, sw_runner_t *R)
{
    const sw_log_t *L = P->log;
    const double probe = 1e-4 * P->bare_lift;
    const double z_s =
        P->d.model == SW_MODEL_CUSHION ? sw_cushion_static_deflection(&P->d, P->sc->g) : 0.0;
    double peak = 0.0;
    size_t next_restart = 0;
    sw_runner_reset(R);
    for (size_t i = 0; i < L->n; i++) {
        while (next_restart < L->nrestart && L->restart[next_restart] <= i)
            if (L->restart[next_restart++] == i)
                sw_engine_restart(R->e);
        if (sw_engine_push(R->e, L->t[i], probe * L->a_g[i], L->a_z ? L->a_z[i] : 0.0) < 0)
            continue;
        sw_output_t o;
        sw_engine_get_output(R->e, 0, &o);
        const double v = sw_run_probe_value(&P->d, &o, z_s);
        if (v > peak)
            peak = v;
    }
    P->lift_scale = sw_run_probe_lift(&P->d, probe, peak, z_s);
}

/* Times strictly increasing and every value finite: what checkpoints rely
 * on (the engine would refuse the others, and a run from the start skips
 * them). */
static int clean_log(const sw_log_t *L)
{
    for (size_t i = 0; i < L->n; i++) {
        if (!isfinite(L->t[i]) || !isfinite(L->a_g[i]) || (L->a_z && !isfinite(L->a_z[i])))
            return 0;
        if (i > 0 && !(L->t[i] > L->t[i - 1]))
            return 0;
    }
    return L->n > 0;
}

static void prep_free(prep_t *P)
{
    free(P->blk);
    free(P->sup);
    free(P->rec);
    free(P->st);
    P->blk = P->sup = P->st = NULL;
    P->rec = NULL;
}

/* Everything a trial needs: the lifting scale and the checkpoints. */
static int prep_make(prep_t *P, char *msg, size_t msglen)
{
    int err = SW_OK;
    const sw_log_t *L = P->log;
    if (sw_scene_validate(P->sc, &P->d, NULL, NULL, NULL) != SW_OK) {
        sw_set_msg(msg, msglen, "scene '%s' is not valid", P->sc->name);
        return SW_EINVAL;
    }
    P->tan_alpha = tan(P->d.alpha);
    for (size_t i = 0; i < L->n; i++)
        if (isfinite(L->a_g[i]) && fabs(L->a_g[i]) > P->a_peak)
            P->a_peak = fabs(L->a_g[i]);
    if (P->a_peak == 0.0)
        return SW_OK;
    P->bare_lift = P->sc->g * P->tan_alpha / P->a_peak; /* scale lifting a package on the bed */
    const int clean = clean_log(L);
    if (P->d.model == SW_MODEL_BARE && clean) { /* the lowest of every sample's */
        if ((err = prep_bare(P)) != SW_OK)
            return err;
        P->lift_scale = INFINITY;
        for (size_t b = 0; b < (L->n + BLOCK * SUPER - 1) / (BLOCK * SUPER); b++)
            P->lift_scale = fmin(P->lift_scale, P->sup[b]);
        return SW_OK;
    }
    if (P->d.model == SW_MODEL_BARE && !L->a_z) {
        P->lift_scale = P->bare_lift;
        return SW_OK;
    }
    if (clean && !(P->st = calloc(2 * (L->n / CHECK + 1), sizeof *P->st)))
        return SW_ENOMEM;
    sw_runner_t R;
    if (sw_runner_make(&R, P->sc, P->ro, 0.0, &err, msg, msglen) != SW_OK)
        return err;
    if (clean && P->d.model == SW_MODEL_FRAME)
        err = prep_frame(P, &R);
    else if (clean && !P->sc->has_frame && P->d.B3 == 0.0 && !L->a_z)
        err = prep_cushion(P);
    if (err == SW_OK && P->kind == CK_NONE)
        prep_probe(P, &R);
    sw_engine_destroy(R.e);
    return err;
}

/* ---- one trial ---------------------------------------------------------------- */

/* The last sample from lo up to i at least a lead-in before sample i
 * (lo if none). */
static size_t lead_in(const prep_t *P, size_t lo, size_t i)
{
    const sw_log_t *L = P->log;
    const double t0 = L->t[i] - P->lead;
    const size_t first = lo;
    size_t hi = i;
    while (lo < hi) {
        const size_t m = lo + (hi - lo + 1) / 2;
        if (L->t[m] <= t0)
            lo = m;
        else
            hi = m - 1;
    }
    return L->t[lo] <= t0 ? lo : first;
}

/* Where a trial at scale x starts: the sample, and whether a lift is
 * possible at all. */
static size_t trial_start(const prep_t *P, double x, int *none)
{
    const sw_log_t *L = P->log;
    size_t k = 0;
    *none = 0;
    if (P->kind == CK_BARE)
        k = next_lift(P, 0, x / BARE_EDGE);
    else if (P->kind != CK_NONE)
        k = first_lift(P, x / LIFT_MARGIN_LOG);
    if (k >= L->n) {
        *none = 1;
        k = P->kind == CK_BARE ? L->n - 1 : P->i_peak;
    }
    size_t i = k > 0 ? k - 1 : 0;
    if (P->kind == CK_CUSHION) /* the lead-in */
        i = lead_in(P, 0, i);
    if (P->kind == CK_FRAME || P->kind == CK_CUSHION)
        i -= i % CHECK;
    return i;
}

/* The package at sample i (just pushed, at rest) in the scaled stored
 * state. */
static int linear_state(const prep_t *P, sw_engine_t *e, double x, size_t i)
{
    sw_output_t o;
    sw_engine_get_output(e, 0, &o); /* at rest */
    sw_state_t s = o.state;
    const double *q = &P->st[2 * (i / CHECK)];
    if (P->kind == CK_FRAME) {
        s.u = x * q[0];
        s.u_dot = x * q[1];
    } else {
        s.theta = x * P->gain * q[0];
        s.theta_dot = x * P->gain * q[1];
    }
    return sw_engine_set_state(e, 0, &s);
}

/* After sample i on a cushion, no edge lifted since last_lift (s;
 * INFINITY: one may be lifted now): the sample to jump to (a checkpoint a
 * lead-in before the next that can lift an edge at X), or 0 for none
 * worth it. */
static size_t cushion_jump(const prep_t *P, size_t i, double last_lift, double X)
{
    const sw_log_t *L = P->log;
    if (i % CHECK || L->t[i] - last_lift < P->lead)
        return 0;
    const size_t k = next_block(P, i, X);
    size_t to = lead_in(P, i, k >= L->n ? L->n - 1 : k);
    to -= to % CHECK;
    return to >= i + 2 * CHECK && to + 2 < L->n ? to : 0;
}

/* The engine at sample i with the scaled stored state. */
static int trial_begin(const prep_t *P, sw_runner_t *R, double x, size_t i)
{
    const sw_log_t *L = P->log;
    sw_engine_t *e = R->e;
    sw_runner_reset(R);
    if (P->kind == CK_NONE) { /* from the start, skipping what the engine refuses */
        sw_engine_push(e, L->t[0], x * L->a_g[0], L->a_z ? L->a_z[0] : 0.0);
        return SW_OK;
    }
    if (sw_engine_set_origin(e, L->t[0]) != SW_OK)
        return SW_EINVAL;
    const int rc = sw_engine_push(e, L->t[i], x * L->a_g[i], L->a_z ? L->a_z[i] : 0.0);
    if (rc < 0 || P->kind == CK_BARE || i == 0)
        return rc < 0 ? rc : SW_OK;
    return linear_state(P, e, x, i);
}

/* After sample i, on the bed: may the run jump ahead?  JUMP_GO with *to,
 * the sample before the next that can lift the package, when it stands at
 * rest and the input at samples i - 1 and i cannot lift it (nor, then,
 * hold it: pkg.c); JUMP_KEEP: not now, look again after the next sample;
 * JUMP_STOP: it moves (look again after its next event). */
enum { JUMP_KEEP, JUMP_STOP, JUMP_GO };
static int bare_jump(const prep_t *P, const sw_runner_t *R, size_t i, double X, size_t *to)
{
    const size_t n = P->log->n;
    if (i == 0 || i + 2 >= n)
        return JUMP_STOP;
    if (bare_scale(P, i) <= X || bare_scale(P, i - 1) <= X)
        return JUMP_KEEP;
    sw_output_t o;
    sw_engine_get_output(R->e, 0, &o);
    if (o.state.phase != SW_PHASE_STUCK)
        return JUMP_STOP;
    const size_t k = next_lift(P, i + 1, X);
    *to = k >= n ? n - 1 : k - 1;
    return *to >= i + 2 ? JUMP_GO : JUMP_KEEP;
}

/* The trial's samples from i0 on, then the free motion (sw_run_log_on's
 * loop, with the bed's jumps). */
static int trial_run(const prep_t *P, sw_runner_t *R, double x, size_t i0, sw_run_result_t *r)
{
    const sw_log_t *L = P->log;
    sw_engine_t *e = R->e;
    const double X = x / BARE_EDGE;
    size_t next_restart = 0;
    while (next_restart < L->nrestart && L->restart[next_restart] <= i0) next_restart++;
    int look = P->kind == CK_BARE; /* look for a jump: from the start, and after events */
    double last_lift = L->t[i0];   /* cushion: the start's error decays as a lift's does */
    for (size_t i = i0 + 1; i < L->n; i++) {
        size_t to;
        if (P->kind == CK_CUSHION &&
            (to = cushion_jump(P, i - 1, last_lift, x / LIFT_MARGIN_LOG))) {
            while (next_restart < L->nrestart && L->restart[next_restart] <= to) next_restart++;
            sw_engine_restart(e);
            const int rc = sw_engine_push(e, L->t[to], x * L->a_g[to], 0.0);
            if (rc < 0)
                return rc;
            const int sr = linear_state(P, e, x, to);
            if (sr != SW_OK)
                return sr;
            last_lift = L->t[to];
            i = to;
            continue; /* the loop goes on at sample to + 1 */
        }
        const int j = look ? bare_jump(P, R, i - 1, X, &to) : JUMP_STOP;
        if (j == JUMP_STOP)
            look = 0;
        if (j == JUMP_GO) {
            while (next_restart < L->nrestart && L->restart[next_restart] <= to) next_restart++;
            sw_engine_restart(e); /* at rest already: the run goes on afresh from sample to */
            i = to;
        }
        while (next_restart < L->nrestart && L->restart[next_restart] <= i)
            if (L->restart[next_restart++] == i)
                sw_engine_restart(e);
        const int rc = sw_engine_push(e, L->t[i], x * L->a_g[i], L->a_z ? L->a_z[i] : 0.0);
        if (rc == SW_EVENT) {
            sw_summary_t s;
            sw_engine_summary(e, 0, &s);
            if (s.overturned)
                break;
            /* an edge lifts only between an uplift and the rest after it */
            last_lift = s.uplifts > s.rests ? INFINITY : L->t[i];
            look = P->kind == CK_BARE;
        }
    }
    const double p = sw_engine_derived(e, 0)->p;
    const double t = sw_engine_time(e);
    if (isnan(t))
        return SW_EINVAL;
    return sw_run_free_motion(R, t + sw_run_free_time(P->ro, p),
                              2.0 * M_PI / p / SW_RUN_CHECKS_PER_PERIOD, r);
}

/* One trial at scale x into r.  A search trial (full 0) at which nothing
 * can lift the package is safe without a run; a full one runs anyway, over
 * its largest response. */
static int trial(const prep_t *P, double x, int full, sw_run_result_t *r, char *msg, size_t msglen)
{
    memset(r, 0, sizeof *r);
    int none, err = SW_OK;
    const size_t i0 = trial_start(P, x, &none);
    if (none && !full) {
        r->end = SW_END_REST;
        r->uplift_time = r->tip_time = r->overturn_time = NAN;
        r->min_margin = 1.0;
        r->t_end = P->log->t[P->log->n - 1];
        return SW_OK;
    }
    sw_runner_t R;
    if (sw_runner_make(&R, P->sc, P->ro, 0.0, &err, msg, msglen) != SW_OK)
        return err;
    if ((err = trial_begin(P, &R, x, i0)) == SW_OK)
        err = trial_run(P, &R, x, i0, r);
    sw_engine_destroy(R.e);
    if (err == SW_EFAULT)
        sw_set_msg(msg, msglen, "the model faulted during a trial");
    else if (err < 0)
        sw_set_msg(msg, msglen, "%s", sw_strerror(err));
    return err;
}

/* ---- the search, in rounds --------------------------------------------------- */

enum { SR_SCAN, SR_SECT, SR_DONE };

/* One threshold search (sw_threshold_search()'s scan and bracket) as a
 * machine: points() gives a round's scales, feed() takes their results. */
typedef struct {
    sw_search_opts_t o; /* resolved: step, tol set */
    int phase;
    long k;           /* scan: points run so far */
    double x_last;    /* scan: the last point run (safe) */
    double peak_last; /* its largest |theta| / alpha */
    double lo, hi;    /* bracket: lo safe, hi overturns */
    sw_run_result_t r_hi;
    double x[SECTIONS];
    sw_run_result_t r[SECTIONS];
    int n; /* points of the current round */
    sw_threshold_t *out;
} search_t;

static int search_init(search_t *S, const sw_search_opts_t *o, sw_threshold_t *out)
{
    memset(S, 0, sizeof *S);
    memset(out, 0, sizeof *out);
    S->o = *o;
    S->out = out;
    if (!(S->o.step > 0.0))
        S->o.step = DEFAULT_STEP;
    if (!(S->o.tol > 0.0))
        S->o.tol = DEFAULT_TOL;
    if (!(o->x_min > 0.0) || !(o->x_max > o->x_min) || !isfinite(o->x_max) ||
        !isfinite(S->o.step) || !isfinite(S->o.tol)) {
        S->phase = SR_DONE;
        return SW_EINVAL;
    }
    return SW_OK;
}

/* The bracket [lo, hi] is found: done if it is narrow enough. */
static void search_bracket(search_t *S)
{
    S->phase = SR_SECT;
    if (S->hi / S->lo - 1.0 > S->o.tol)
        return;
    S->phase = SR_DONE;
    S->out->found = 1;
    S->out->x = S->hi;
    S->out->x_safe = S->lo;
    S->out->at_x = S->r_hi;
}

/* The relative step of the scan's next round: --step wherever the
 * package came within a quarter of alpha of its corner (peak |theta| of
 * the last point run at least alpha / 4), growing to FAR_STEPS times it
 * as that peak falls to 0 (no lift at all): a package that stays far from
 * tipping at x does not overturn at a few per cent more, while near
 * tipping, where overturning is not monotonic in the scale, the scan is as
 * fine as asked. */
static double scan_step(const search_t *S)
{
    const double near = fmin(1.0, fmax(0.0, S->peak_last / NEAR_PEAK));
    return S->o.step * (FAR_STEPS - (FAR_STEPS - 1.0) * near);
}

/* The scales of the next round (S->n of them; 0 when done). */
static int search_points(search_t *S)
{
    S->n = 0;
    if (S->phase == SR_SCAN) {
        const double f = 1.0 + scan_step(S);
        for (int j = 0; j < SECTIONS; j++) {
            const double x = S->k == 0 ? fmin(S->o.x_min * pow(f, j), S->o.x_max)
                                       : fmin(S->x_last * pow(f, j + 1.0), S->o.x_max);
            S->x[S->n++] = x;
            if (x >= S->o.x_max)
                break; /* the scan's last point is x_max itself */
        }
    } else if (S->phase == SR_SECT) {
        const double ratio = S->hi / S->lo;
        double prev = S->lo;
        for (int j = 1; j <= SECTIONS; j++) {
            const double x = S->lo * pow(ratio, (double)j / (SECTIONS + 1));
            if (x > prev && x < S->hi)
                S->x[S->n++] = prev = x;
        }
        if (!S->n) { /* no scale left between them: as narrow as it gets */
            S->o.tol = INFINITY;
            search_bracket(S);
        }
    }
    return S->n;
}

/* The round's results: the lowest overturning scale wins, with the safe
 * one just below it. */
static void search_feed(search_t *S)
{
    S->out->trials += S->n;
    int j = 0;
    while (j < S->n && !S->r[j].overturned) j++;
    if (S->phase == SR_SCAN) {
        if (j == S->n) { /* all safe */
            S->lo = S->x_last = S->x[S->n - 1];
            S->peak_last = S->r[S->n - 1].max_theta_ratio;
            S->k += S->n;
            if (S->x[S->n - 1] >= S->o.x_max)
                S->phase = SR_DONE; /* nothing overturns */
            return;
        }
        if (S->k + j == 0) { /* x_min itself overturns: the threshold may be lower */
            S->phase = SR_DONE;
            S->out->found = S->out->at_min = 1;
            S->out->x = S->x[0];
            S->out->x_safe = 0.0;
            S->out->at_x = S->r[0];
            return;
        }
        S->lo = j > 0 ? S->x[j - 1] : S->lo;
        S->hi = S->x[j];
        S->r_hi = S->r[j];
        search_bracket(S);
        return;
    }
    if (j < S->n) {
        S->lo = j > 0 ? S->x[j - 1] : S->lo;
        S->hi = S->x[j];
        S->r_hi = S->r[j];
    } else {
        S->lo = S->x[S->n - 1];
    }
    search_bracket(S);
}

/* ---- the scenes' searches on a pool of threads -------------------------------- */

/* A scene's work goes on three tracks: the run at scale 1 (ONE), the
 * search below it (BELOW: from the lifting scale up to 1, whatever the
 * outcome at 1) and, once ONE says it survived, the search above it
 * (ABOVE).  Each track is a sequence of rounds; a round's tasks run in any
 * order on any thread, and the track moves on when the last one is done.
 * A failing track stops; the scene reports the first failing track's
 * first error, so that the error too is the same for any threads. */
enum { TR_ONE, TR_BELOW, TR_ABOVE, TR_N };
enum { T_PREP = -1 };

typedef struct {
    sw_safety_case_t *out;
    prep_t P;
    int prepared;
    int pending[TR_N]; /* tasks of each track's current round not finished */
    int err[TR_N], err_at[TR_N];
    char msg[TR_N][256];
    search_t below, above;
    int done;
} case_t;

typedef struct {
    case_t *c;
    int track, slot; /* track T_PREP: the preparation */
} task_t;

typedef struct {
    pthread_mutex_t mu;
    pthread_cond_t cv;
    task_t *q; /* a ring: at most 2 SECTIONS + 1 tasks of each case wait at a time */
    size_t cap, head, len;
    size_t active;
    const sw_safety_opts_t *o;
    sw_safety_progress_t prog;
} pool_t;

static void push_task(pool_t *W, case_t *c, int track, int slot)
{
    W->q[(W->head + W->len++) % W->cap] = (task_t){c, track, slot};
    if (track != T_PREP)
        c->pending[track]++;
}

static int task_run(const task_t *t, char *msg, size_t msglen)
{
    case_t *c = t->c;
    switch (t->track) {
        case T_PREP: return prep_make(&c->P, msg, msglen);
        case TR_ONE: return trial(&c->P, 1.0, 1, &c->out->sf.at_one, msg, msglen);
        case TR_BELOW:
            return trial(&c->P, c->below.x[t->slot], 0, &c->below.r[t->slot], msg, msglen);
        default: return trial(&c->P, c->above.x[t->slot], 0, &c->above.r[t->slot], msg, msglen);
    }
}

/* The search options of the scene: the caller's, with the automatic
 * range (sw_safety_factor()). */
static sw_search_opts_t case_search(const pool_t *W, const case_t *c)
{
    const prep_t *P = &c->P;
    sw_search_opts_t so = W->o->search;
    if (!(so.x_max > 0.0))
        so.x_max = DEFAULT_X_MAX * P->bare_lift;
    if (!(so.x_min > 0.0)) {
        so.x_min = P->lift_scale;
        if (P->d.model != SW_MODEL_BARE || P->log->a_z)
            so.x_min *= LIFT_MARGIN_LOG;
        if (P->log->a_z)
            so.x_min = fmin(so.x_min, LIFT_MARGIN_LOG * P->bare_lift);
    }
    return so;
}

/* The next round of a search track, or none (done). */
static void track_next(pool_t *W, case_t *c, int track)
{
    search_t *S = track == TR_BELOW ? &c->below : &c->above;
    if (c->err[track] || S->phase == SR_DONE) {
        S->n = 0;
        return;
    }
    const int n = search_points(S);
    for (int j = 0; j < n; j++) push_task(W, c, track, j);
}

/* Prepared: the run at 1 and the search below it start together. */
static void case_start(pool_t *W, case_t *c)
{
    sw_safety_t *sf = &c->out->sf;
    c->prepared = 1;
    c->below.phase = c->above.phase = SR_DONE;
    push_task(W, c, TR_ONE, 0);
    if (c->P.a_peak == 0.0)
        return; /* no longitudinal acceleration: no scale changes anything */
    const sw_search_opts_t so = case_search(W, c);
    sf->max_scale = so.x_max;
    sf->lift_scale = c->P.lift_scale;
    sw_search_opts_t sb = so;
    sb.x_max = 1.0;
    if (sb.x_min < 1.0 && search_init(&c->below, &sb, &sf->below) != SW_OK) {
        c->err[TR_BELOW] = SW_EINVAL;
        snprintf(c->msg[TR_BELOW], sizeof c->msg[0],
                 "the log has no usable sample, or the search range is empty");
    }
    track_next(W, c, TR_BELOW);
}

/* The run at 1 is done: the search above it, if it survived. */
static void case_one_done(pool_t *W, case_t *c)
{
    sw_safety_t *sf = &c->out->sf;
    sf->overturned = sf->at_one.overturned;
    if (c->err[TR_ONE] || c->P.a_peak == 0.0)
        return;
    const sw_search_opts_t so = case_search(W, c);
    sw_search_opts_t sa = so;
    sa.x_min = fmax(1.0, so.x_min);
    if (!sf->overturned && sa.x_min < sa.x_max) {
        if (search_init(&c->above, &sa, &sf->above) != SW_OK) {
            c->err[TR_ABOVE] = SW_EINVAL;
            snprintf(c->msg[TR_ABOVE], sizeof c->msg[0],
                     "the log has no usable sample, or the search range is empty");
        }
        track_next(W, c, TR_ABOVE);
    }
}

static void case_finish(pool_t *W, case_t *c)
{
    sw_safety_t *sf = &c->out->sf;
    for (int k = 0; k < TR_N; k++)
        if (c->err[k]) {
            c->out->status = c->err[k];
            snprintf(c->out->msg, sizeof c->out->msg, "%s",
                     c->msg[k][0] ? c->msg[k] : sw_strerror(c->err[k]));
            break;
        }
    if (c->P.a_peak == 0.0)
        sf->lift_scale = INFINITY;
    if (sf->overturned && c->P.a_peak > 0.0 && !(case_search(W, c).x_min < 1.0)) {
        /* lifting estimated above 1, yet 1 overturned: 1 itself */
        sf->below.found = sf->below.at_min = 1;
        sf->below.x = 1.0;
        sf->below.at_x = sf->at_one;
    }
    sf->trials = 1 + sf->below.trials + sf->above.trials;
    if (sf->overturned && sf->below.found) {
        sf->found = 1;
        sf->factor = sf->below.x;
        sf->factor_safe = sf->below.x_safe;
    } else if (!sf->overturned && sf->above.found) {
        sf->found = 1;
        sf->factor = sf->above.x;
        sf->factor_safe = sf->above.at_min ? 1.0 : sf->above.x_safe;
    }
    c->done = 1;
    prep_free(&c->P);
    W->active--;
    W->prog.cases_done++;
}

/* A task is done (under the lock): its track may move on, the scene may
 * be finished. */
static void task_done(pool_t *W, const task_t *t, int err, const char *msg)
{
    case_t *c = t->c;
    const int k = t->track;
    if (k == T_PREP) {
        if (err < 0) {
            c->err[TR_ONE] = err;
            snprintf(c->msg[TR_ONE], sizeof c->msg[0], "%s", msg);
        } else {
            case_start(W, c);
        }
    } else {
        W->prog.trials++;
        if (err < 0 && (!c->err[k] || t->slot < c->err_at[k])) {
            c->err[k] = err;
            c->err_at[k] = t->slot;
            snprintf(c->msg[k], sizeof c->msg[0], "%s", msg);
        }
        if (--c->pending[k] == 0) {
            if (k == TR_ONE)
                case_one_done(W, c);
            if (k == TR_BELOW && !c->err[k])
                search_feed(&c->below);
            if (k == TR_ABOVE && !c->err[k])
                search_feed(&c->above);
            if (k != TR_ONE)
                track_next(W, c, k);
        }
    }
    if (!c->pending[TR_ONE] && !c->pending[TR_BELOW] && !c->pending[TR_ABOVE])
        case_finish(W, c);
    if (W->o->progress)
        W->o->progress(W->o->user, &W->prog);
    pthread_cond_broadcast(&W->cv);
}

static void *worker(void *arg)
{
    pool_t *W = arg;
    char msg[256];
    pthread_mutex_lock(&W->mu);
    for (;;) {
        if (W->len) {
            const task_t t = W->q[W->head];
            W->head = (W->head + 1) % W->cap;
            W->len--;
            pthread_mutex_unlock(&W->mu);
            msg[0] = '\0';
            const int err = task_run(&t, msg, sizeof msg);
            pthread_mutex_lock(&W->mu);
            task_done(W, &t, err, msg);
            continue;
        }
        if (!W->active)
            break;
        pthread_cond_wait(&W->cv, &W->mu);
    }
    pthread_mutex_unlock(&W->mu);
    return NULL;
}

/* Run the pool's tasks on up to threads threads (the calling thread
 * works too). */
static void pool_run(pool_t *W, int threads)
{
    pthread_t tid[MAX_THREADS];
    size_t started = 0;
    const size_t want = threads > MAX_THREADS ? MAX_THREADS : threads > 1 ? (size_t)threads : 1;
    for (; started + 1 < want; started++)
        if (pthread_create(&tid[started], NULL, worker, W) != 0)
            break;
    worker(W);
    for (size_t i = 0; i < started; i++) pthread_join(tid[i], NULL);
}

int sw_safety_factors(sw_safety_case_t *cases, size_t n, const sw_log_t *log,
                      const sw_safety_opts_t *o)
{
    if (!cases || !log || !log->t || !log->a_g || !o || n == 0)
        return SW_EINVAL;
    case_t *cs = calloc(n, sizeof *cs);
    pool_t W = {.cap = n * (2 * SECTIONS + 1) + 1, .o = o, .active = n};
    W.q = malloc(W.cap * sizeof *W.q);
    if (!cs || !W.q || pthread_mutex_init(&W.mu, NULL) != 0) {
        free(cs);
        free(W.q);
        return SW_ENOMEM;
    }
    pthread_cond_init(&W.cv, NULL);
    W.prog.cases = n;
    for (size_t i = 0; i < n; i++) {
        sw_safety_case_t *out = &cases[i];
        out->status = SW_OK;
        out->msg[0] = '\0';
        memset(&out->sf, 0, sizeof out->sf);
        out->sf.factor = out->sf.factor_safe = INFINITY;
        cs[i] = (case_t){.out = out};
        cs[i].P = (prep_t){.sc = &out->scene, .log = log, .ro = &o->run};
        if (log->n == 0) { /* nothing to run: refused at once */
            cs[i].err[TR_ONE] = SW_EINVAL;
            snprintf(cs[i].msg[TR_ONE], sizeof cs[i].msg[0], "the log has no usable sample");
            case_finish(&W, &cs[i]);
            continue;
        }
        push_task(&W, &cs[i], T_PREP, 0);
    }
    pool_run(&W, o->threads);
    int rc = SW_OK;
    for (size_t i = 0; i < n && rc == SW_OK; i++) rc = cases[i].status;
    pthread_cond_destroy(&W.cv);
    pthread_mutex_destroy(&W.mu);
    free(W.q);
    free(cs);
    return rc;
}

int sw_safety_factor(const sw_scene_t *sc, const sw_log_t *log, const sw_run_opts_t *ro,
                     const sw_search_opts_t *so, sw_safety_t *out, char *msg, size_t msglen)
{
    sw_set_msg(msg, msglen, "%s", "");
    if (!sc || !log || !out)
        return SW_EINVAL;
    sw_safety_case_t *c = calloc(1, sizeof *c);
    if (!c)
        return SW_ENOMEM;
    c->scene = *sc;
    sw_safety_opts_t o = {.threads = 1};
    if (ro)
        o.run = *ro;
    if (so)
        o.search = *so;
    const int rc = sw_safety_factors(c, 1, log, &o);
    *out = c->sf;
    if (rc < 0)
        sw_set_msg(msg, msglen, "%s", c->msg);
    free(c);
    return rc;
}
