/* SPDX-License-Identifier: GPL-3.0-or-later */
/* safety_prep.c - one trial of a safety-factor search (safety.c): the log
 * with its longitudinal acceleration scaled, run until the outcome is
 * known, and what is prepared once per scene so that an hour-long log is
 * affordable.
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
 *     threshold (the same as a run from the start but for rounding).  A
 *     search trial also jumps over every later stretch in which the
 *     package stands on the frame and nothing can lift it (frame_jump);
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
 * What a trial must get right (sw_trial_need) decides how much of that it
 * may skip.  The run at scale 1 reports everything and is made as above.
 * A search trial on a cushion needs only whether it overturns (and, for
 * the scan's next step, its peak below SW_SAFETY_NEAR_PEAK): it starts
 * each stretch that can lift an edge from reference states instead of a
 * lead-in, and leaves each as soon as its ringing cannot lift an edge
 * again (rock_trial, "the cushion: reference states" below).  Where its
 * peak sets the scan's step, the trial is made as above but without the
 * samples that cannot change its outcome or its peak (exact_jump): the
 * peak of the run at scale 1 and of every trial the step depends on is
 * the very number the lead-ins give. */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "model_traits.h"
#include "run_int.h"
#include "safety_prep.h"
#include "stuck.h"
#include "swaywatch/status.h"

#define BLOCK 256              /* samples per block of the bed's lift index */
#define SUPER 256              /* blocks per superblock */
#define CHECK 256              /* samples between stored linear states */
#define BARE_EDGE (1.0 - 1e-9) /* rounding of the interpolated input, with room */
#define LONG_STEP 0.25         /* omega dt beyond which a sample interval may hide a peak */
#define FORGET 1e-6            /* cushion: share of the start state's error left after the lead */
_Static_assert(BLOCK == CHECK, "a block starts at a checkpoint");

/* The run options of a trial that needs need: the search's, and but for
 * the run at scale 1 (which reports everything) no margins after each
 * sample, which no search trial reads (its outcome and peak come from the
 * events; the margins a trial's end needs are computed on demand). */
static sw_run_opts_t trial_opts(const prep_t *P, sw_trial_need need)
{
    sw_run_opts_t ro;
    if (P->ro)
        ro = *P->ro;
    else
        memset(&ro, 0, sizeof ro);
    ro.engine.margins_off = need != SW_TRIAL_FULL;
    return ro;
}

/* ---- checkpoints ----------------------------------------------------------- */

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

/* A package the input itself lifts (the bed): every sample's scale. */
static int prep_direct(prep_t *P)
{
    if (blocks_alloc(P) != SW_OK)
        return SW_ENOMEM;
    for (size_t i = 0; i < P->log->n; i++) block_min(P, i, bare_scale(P, i));
    P->kind = CK_DIRECT;
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

/* A package standing on a linear support (the frame): one run at a scale
 * far too small to lift anything, which the stuck package follows exactly.  CK_NONE (no
 * checkpoints) if the scheme steps the stuck frame adaptively or the probe ever left the stuck
 * phase. */
static int prep_stuck(prep_t *P, sw_runner_t *R)
{
    const sw_log_t *L = P->log;
    const sw_scheme_t *S = sw_scheme_lookup(sw_engine_scheme(R->e));
    if (!S || sw_scheme_adaptive(S) || (P->ro && P->ro->engine.stuck_stepped))
        return SW_OK;
    const double probe = 1e-4 * P->bare_lift;
    size_t next_restart = 0;
    double peak = 0.0;
    if (blocks_alloc(P) != SW_OK)
        return SW_ENOMEM;
    sw_runner_reset(R);
    for (size_t i = 0; i < L->n; i++) {
        if (sw_run_push(R->e, L, i, probe, &next_restart) < 0)
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
        block_min(P, i, s);
        store_state(P, i, o.state.u / probe, o.state.u_dot / probe);
    }
    P->lift_scale = peak > 0.0 ? 1.0 / peak : INFINITY;
    P->kind = CK_STUCK;
    return SW_OK;
}

/* A package whose rocking about rest is, to first order, one damped
 * oscillator (ops->rock_linear: a linear cushion on the bed), stepped in
 * closed form between samples (sw_nj_step); an edge lifts when the drive
 * reaches its level. */
static int refs_alloc(prep_t *P);
static int prep_rock(prep_t *P, sw_runner_t *R, const sw_rock_linear_t *rl)
{
    const sw_log_t *L = P->log;
    P->rock = *rl;
    sw_runner_reset(R);
    if (sw_engine_push(R->e, L->t[0], 0.0, 0.0) < 0)
        return SW_OK; /* no checkpoints */
    sw_output_t o;
    sw_engine_get_output(R->e, 0, &o);
    P->rest = o.state;
    if (refs_alloc(P) != SW_OK)
        return SW_ENOMEM;
    P->lead = log(1.0 / FORGET) / rl->lam;
    const double per = rl->per; /* lift drive over its level per unit u, 1/m */
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
            sw_nj_step(P->rock.w, P->rock.zeta, H, L->a_g[i - 1], s, u, u1);
            u[0] = u1[0];
            u[1] = u1[1];
        }
        const double v = per * fabs(u[0]); /* drive / z_s at scale 1 */
        if (v > peak) {
            peak = v;
            P->i_peak = i;
        }
        const double s = long_interval(P, i, P->rock.w) ? 0.0 : v > 0.0 ? 1.0 / v : INFINITY;
        if (add_record(P, i, s) != SW_OK)
            return SW_ENOMEM;
        block_min(P, i, s);
        store_state(P, i, u[0], u[1]);
    }
    P->st_end[0] = u[0];
    P->st_end[1] = u[1];
    P->lift_scale = peak > 0.0 ? 1.0 / peak : INFINITY;
    P->kind = CK_ROCK;
    return SW_OK;
}

/* Without checkpoints: the lifting scale from a run far too small to lift
 * anything (linear to first order), as boundary.c's pulses do. */
static void prep_probe(prep_t *P, sw_runner_t *R)
{
    const sw_log_t *L = P->log;
    const double probe = 1e-4 * P->bare_lift;
    const sw_model_traits_t *ops = sw_model_traits_of(P->d.model);
    const double level = ops->lift_level(&P->d, P->sc->g);
    double peak = 0.0;
    size_t next_restart = 0;
    sw_runner_reset(R);
    for (size_t i = 0; i < L->n; i++) {
        if (sw_run_push(R->e, L, i, probe, &next_restart) < 0)
            continue;
        sw_output_t o;
        sw_engine_get_output(R->e, 0, &o);
        const double v = ops->lift_drive(&P->d, level, &o);
        if (v > peak)
            peak = v;
    }
    P->lift_scale = sw_run_probe_lift(probe, peak, level);
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

static void refs_free(prep_t *P);
void sw_safety_prep_free(prep_t *P)
{
    refs_free(P);
    free(P->blk);
    free(P->sup);
    free(P->rec);
    free(P->st);
    P->blk = P->sup = P->st = NULL;
    P->rec = NULL;
}

/* Everything a trial needs: the lifting scale and the checkpoints. */
int sw_safety_prep_make(prep_t *P, char *msg, size_t msglen)
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
    const sw_model_traits_t *ops = sw_model_traits_of(P->d.model);
    if (ops->lift_direct && clean) { /* the lowest of every sample's */
        if ((err = prep_direct(P)) != SW_OK)
            return err;
        P->lift_scale = INFINITY;
        for (size_t b = 0; b < (L->n + BLOCK * SUPER - 1) / (BLOCK * SUPER); b++)
            P->lift_scale = fmin(P->lift_scale, P->sup[b]);
        return SW_OK;
    }
    if (ops->lift_direct && !L->a_z) {
        P->lift_scale = P->bare_lift;
        return SW_OK;
    }
    if (clean && !(P->st = calloc(2 * (L->n / CHECK + 1), sizeof *P->st)))
        return SW_ENOMEM;
    sw_runner_t R;
    if (sw_runner_make(&R, P->sc, P->ro, 0.0, &err, msg, msglen) != SW_OK)
        return err;
    sw_rock_linear_t rl;
    if (clean && ops->stuck_linear)
        err = prep_stuck(P, &R);
    else if (clean && !L->a_z && ops->rock_linear &&
             ops->rock_linear(&P->d, P->sc->mass, P->sc->g, &rl))
        err = prep_rock(P, &R, &rl);
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
    if (P->kind == CK_DIRECT)
        k = next_lift(P, 0, x / BARE_EDGE);
    else if (P->kind != CK_NONE)
        k = first_lift(P, x / LIFT_MARGIN_LOG);
    if (k >= L->n) {
        *none = 1;
        k = P->kind == CK_DIRECT ? L->n - 1 : P->i_peak;
    }
    size_t i = k > 0 ? k - 1 : 0;
    if (P->kind == CK_ROCK) /* the lead-in */
        i = lead_in(P, 0, i);
    if (P->kind == CK_STUCK || P->kind == CK_ROCK)
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
    if (P->kind == CK_STUCK) {
        s.u = x * q[0];
        s.u_dot = x * q[1];
    } else {
        s.theta = x * P->rock.gain * q[0];
        s.theta_dot = x * P->rock.gain * q[1];
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
    if (rc < 0 || P->kind == CK_DIRECT || i == 0)
        return rc < 0 ? rc : SW_OK;
    return linear_state(P, e, x, i);
}

/* ---- the cushion: reference states ------------------------------------------------ */

/* A trial on a linear cushion on the bed starts each stretch that can lift
 * an edge from the package's state a little before it, instead of from the
 * linear state a lead-in before it.  That state is taken from reference
 * runs: while no edge lifts the cushion is a smooth system symmetric under
 * theta -> -theta, a_g -> -a_g, so at a checkpoint the state of the run at
 * scale x is an odd function of x in theta and theta' and an even one in
 * z - z_s and z', a power series whose terms fall as theta^2.  Three runs
 * at scales 0.3, 0.6 and 0.9 of the highest that cannot lift an edge over
 * the lead-in before the checkpoint give the series to x^5 (x^6): its
 * remainder, and the engine's own round-off as a function of x, are a few
 * 1e-12 rad where theta is 3e-3 rad (the 1 kHz drive of bench/drive_log.py,
 * a 30 rad/s cushion), below the error the lead-in leaves (FORGET of the
 * linear state's error, 1e-5 rad there).  A reference run is a lead-in
 * itself, from the linear state; it is made once per checkpoint, by
 * whichever trial needs it first, the same for any thread. */
#define REF_N 3
#define REF_ANCHOR 16   /* checkpoints between the places where references are made */
#define ROCK_D_MAX 0.8  /* a larger ringing: no early jump */
#define PEAK_TOL 1e-6   /* the fast trial's peak is right to far better than this */
#define PEAK_SLACK 1.05 /* |theta| where no edge lifts, over its linear bound: O(theta^2) */
enum { REF_NONE, REF_BUSY, REF_DONE, REF_FAIL };

typedef struct {
    int state;
    size_t c0;          /* where the runs start (a lead-in before the checkpoint) */
    int run[REF_N];     /* each run: REF_NONE, REF_BUSY, REF_DONE, REF_FAIL */
    double x[REF_N];    /* scales */
    double y[REF_N][4]; /* theta, theta', z - z_s, z' at the checkpoint */
} ref_t;

struct sw_refs {
    pthread_mutex_t mu;
    pthread_cond_t cv;
    size_t n; /* checkpoints */
    ref_t *v; /* per checkpoint */
};

static int refs_alloc(prep_t *P)
{
    struct sw_refs *R = calloc(1, sizeof *R);
    if (!R)
        return SW_ENOMEM;
    R->n = P->log->n / CHECK + 1;
    R->v = calloc(R->n, sizeof *R->v); /* REF_NONE */
    if (!R->v || pthread_mutex_init(&R->mu, NULL) != 0) {
        free(R->v);
        free(R);
        return SW_ENOMEM;
    }
    pthread_cond_init(&R->cv, NULL);
    P->refs = R;
    return SW_OK;
}

static void refs_free(prep_t *P)
{
    struct sw_refs *R = P->refs;
    if (!R)
        return;
    pthread_cond_destroy(&R->cv);
    pthread_mutex_destroy(&R->mu);
    free(R->v);
    free(R);
    P->refs = NULL;
}

/* The reference runs of checkpoint c: from the linear state a lead-in
 * before c (or from rest at the log's start), at scales below the lowest
 * that can lift an edge over that stretch.  REF_FAIL if there is no such
 * stretch. */
static int ref_plan(const prep_t *P, size_t c, ref_t *f)
{
    size_t c0 = lead_in(P, 0, c);
    c0 -= c0 % CHECK;
    double S = INFINITY; /* the lowest lifting scale before c */
    for (size_t b = c0 / BLOCK; b < c / BLOCK; b++) S = fmin(S, P->blk[b]);
    if (!(S > 0.0) || !isfinite(S) || c0 == c)
        return REF_FAIL;
    f->c0 = c0;
    for (int j = 0; j < REF_N; j++) f->x[j] = LIFT_MARGIN_LOG * S * (j + 1) / REF_N;
    return REF_BUSY;
}

/* Reference run j of checkpoint c into y: REF_DONE, or REF_FAIL if an
 * edge lifted or the run faulted. */
static int ref_run(const prep_t *P, size_t c, const ref_t *f, int j, double y[4])
{
    const sw_log_t *L = P->log;
    sw_runner_t R;
    int err = SW_OK;
    const sw_run_opts_t ro = trial_opts(P, SW_TRIAL_OUTCOME);
    if (sw_runner_make(&R, P->sc, &ro, 0.0, &err, NULL, 0) != SW_OK)
        return REF_FAIL;
    const double x = f->x[j];
    size_t next_restart = 0;
    while (next_restart < L->nrestart && L->restart[next_restart] <= f->c0) next_restart++;
    int st = trial_begin(P, &R, x, f->c0) == SW_OK ? REF_DONE : REF_FAIL;
    for (size_t i = f->c0 + 1; i <= c && st == REF_DONE; i++)
        if (sw_run_push(R.e, L, i, x, &next_restart) < 0)
            st = REF_FAIL;
    sw_summary_t sum;
    sw_engine_summary(R.e, 0, &sum);
    if (sum.uplifts || sum.faults || sum.overturned)
        st = REF_FAIL;
    sw_state_t q;
    sw_engine_get_state(R.e, 0, &q);
    y[0] = q.theta;
    y[1] = q.theta_dot;
    y[2] = q.z - P->rest.z;
    y[3] = q.z_dot;
    sw_engine_destroy(R.e);
    return st;
}

/* The reference runs of checkpoint c, made now if no trial made them yet:
 * a trial that needs them while others are making them makes the runs
 * not yet begun, then waits for the rest.  NULL if they cannot be had.
 * Every run depends on c alone, so they are the same whoever makes them. */
static const ref_t *ref_get(const prep_t *P, size_t c)
{
    struct sw_refs *R = P->refs;
    if (!R || c % CHECK || c / CHECK >= R->n)
        return NULL;
    ref_t *f = &R->v[c / CHECK];
    pthread_mutex_lock(&R->mu);
    if (f->state == REF_NONE)
        f->state = ref_plan(P, c, f);
    while (f->state == REF_BUSY) {
        int j = 0;
        while (j < REF_N && f->run[j] != REF_NONE) j++;
        if (j == REF_N) { /* all begun: wait for them */
            pthread_cond_wait(&R->cv, &R->mu);
            continue;
        }
        f->run[j] = REF_BUSY;
        pthread_mutex_unlock(&R->mu);
        double y[4];
        const int st = ref_run(P, c, f, j, y);
        pthread_mutex_lock(&R->mu);
        memcpy(f->y[j], y, sizeof y);
        f->run[j] = st;
        int done = 1, fail = 0;
        for (int k = 0; k < REF_N; k++) {
            done &= f->run[k] == REF_DONE || f->run[k] == REF_FAIL;
            fail |= f->run[k] == REF_FAIL;
        }
        if (done) {
            f->state = fail ? REF_FAIL : REF_DONE;
            pthread_cond_broadcast(&R->cv);
        }
    }
    const int ok = f->state == REF_DONE;
    pthread_mutex_unlock(&R->mu);
    return ok ? f : NULL;
}

/* y(x) = x^p (a + b x^2 + c x^4) through the three references (Lagrange
 * in x^2). */
static double ref_fit(const ref_t *f, int k, int p, double x)
{
    const double X = x * x;
    double r = 0.0;
    for (int i = 0; i < REF_N; i++) {
        double l = 1.0;
        for (int j = 0; j < REF_N; j++)
            if (j != i)
                l *= (X - f->x[j] * f->x[j]) / (f->x[i] * f->x[i] - f->x[j] * f->x[j]);
        r += l * f->y[i][k] / (p == 1 ? f->x[i] : f->x[i] * f->x[i]);
    }
    return r * (p == 1 ? x : X);
}

/* The engine at checkpoint c in the state of scale x the references give
 * (sample c pushed). */
static int ref_begin(const prep_t *P, sw_runner_t *R, const ref_t *f, double x, size_t c)
{
    const sw_log_t *L = P->log;
    sw_state_t q = P->rest;
    q.theta = ref_fit(f, 0, 1, x);
    q.theta_dot = ref_fit(f, 1, 1, x);
    q.z = P->rest.z + ref_fit(f, 2, 2, x);
    q.z_dot = ref_fit(f, 3, 2, x);
    const int rc = sw_engine_push(R->e, L->t[c], x * L->a_g[c], 0.0);
    return rc < 0 ? rc : sw_engine_set_state(R->e, 0, &q);
}

/* The bound D, over the lift level, of the lift drive of the difference
 * between the package's state at checkpoint i and the linear state at
 * scale x: while no edge lifts, that difference rings freely in the
 * rocking and the vertical modes, each a damped oscillator whose energy
 * (q'^2 + w^2 q^2) / 2 can only fall, so |q| <= sqrt(q^2 + q'^2 / w^2)
 * for ever; the drive b sin(theta) - (z - z_s) grows by at most per/gain
 * times the first and per_z times the second. */
static double rock_ringing(const prep_t *P, const sw_state_t *s, double x, size_t i)
{
    const sw_rock_linear_t *k = &P->rock;
    const double *q = &P->st[2 * (i / CHECK)];
    const double dt = s->theta - x * k->gain * q[0], dv = s->theta_dot - x * k->gain * q[1];
    const double dz = s->z - P->rest.z, dzv = s->z_dot;
    const double A = sqrt(dt * dt + dv * dv / (k->w * k->w));
    const double Az = sqrt(dz * dz + dzv * dzv / (k->wz * k->wz));
    return k->per / k->gain * A + k->per_z * Az;
}

/* The place where references are made for a trial that needs a state at
 * checkpoint c: the last anchor at or before it, so that trials whose
 * stretches begin a little apart share them.  Every anchor costs REF_N
 * lead-ins, and every trial runs from its anchor to its stretch: on the
 * hour-long drive of bench/drive_log.py anchors 4 s apart (4096 samples)
 * make 13 sets of references instead of the 15 of anchors 2 s apart (two
 * pairs of stretches 2 s apart share theirs), 3 % fewer samples stepped
 * in all (17.64 million against 18.23: 0.86 million fewer in references,
 * 0.27 million more in the trials' run-ups).  8 s apart would merge one
 * pair more (0.43 million) for run-ups about three times as long again
 * (an estimate, not measured). */
static size_t ref_anchor(size_t c)
{
    return c - c % (REF_ANCHOR * CHECK);
}

enum { ROCK_STAY, ROCK_JUMP, ROCK_OVER };

/* The stretch after checkpoint i of a trial at scale x in which no edge
 * can lift, whatever the ringing left in the state: *b, the first block
 * after it that can lift one (n: none up to the end), and *theta_max, a
 * bound of |theta| over it (rad).  ROCK_STAY when the ringing is too large
 * to say anything; ROCK_OVER when nothing can lift an edge up to the end
 * of the log nor in the free motion after it. */
static int rock_calm(const prep_t *P, const sw_runner_t *R, double x, size_t i, size_t *b,
                     double *theta_max)
{
    const sw_log_t *L = P->log;
    const sw_rock_linear_t *k = &P->rock;
    if (i % CHECK || i + 2 * CHECK >= L->n)
        return ROCK_STAY;
    sw_state_t s;
    sw_engine_get_state(R->e, 0, &s);
    const double D = rock_ringing(P, &s, x, i);
    if (!(D < ROCK_D_MAX))
        return ROCK_STAY;
    const double X = x / (LIFT_MARGIN_LOG * (1.0 - D));
    if (P->blk[i / BLOCK] <= X) /* the rest of sample i's block may lift */
        return ROCK_STAY;
    *b = next_block(P, i, X);
    const size_t nb = (L->n + BLOCK - 1) / BLOCK, end = *b < L->n ? *b / BLOCK : nb;
    double S = P->blk[i / BLOCK]; /* the lowest lifting scale over the stretch */
    for (size_t j = i / BLOCK + 1; j < end; j++) S = fmin(S, P->blk[j]);
    /* b |theta| / z_s <= x v + D there, v the unit-scale drive over the level */
    *theta_max = PEAK_SLACK * k->gain / k->per * (x / S + D);
    if (*b < L->n)
        return ROCK_JUMP;
    const double *q = P->st_end; /* the linear state at the last sample, scale 1 */
    const double A = x * sqrt(q[0] * q[0] + q[1] * q[1] / (k->w * k->w));
    *theta_max = fmax(*theta_max, PEAK_SLACK * k->gain / k->per * (k->per * A + D));
    return k->per * A + D < LIFT_MARGIN_LOG ? ROCK_OVER : ROCK_STAY;
}

/* After sample i (a checkpoint) of a fast trial on a cushion, with no edge
 * lifted since `calm` (s; -INFINITY: the state holds nothing to forget):
 * may the run jump to the next stretch that can lift an edge?  It may when
 * the ringing left by what came before, bounded by rock_ringing, cannot
 * lift an edge before it (the linear drive at scale x stays below
 * LIFT_MARGIN_LOG (1 - D) of the level at every sample in between, so the
 * drive stays below the level), and when that ringing will have decayed
 * there to FORGET^2 of itself (two lead-ins after calm), which the
 * reference state leaves out as the jumps after a lead-in leave out what
 * is left of it then.  Nothing in between can overturn the package; its
 * peak there is not known, so a fast trial's peak is a lower bound of the
 * peak of a run from the start (to the references' error).  Returns
 * ROCK_JUMP with *to (the reference anchor before that stretch), ROCK_OVER
 * when no edge can lift again, up to the end of the log nor in the free
 * motion after it (the linear motion at the last sample rings freely then,
 * bounded as the difference is), ROCK_STAY otherwise. */
static int rock_jump(const prep_t *P, const sw_runner_t *R, double x, size_t i, double calm,
                     size_t *to)
{
    const sw_log_t *L = P->log;
    size_t b;
    double theta_max;
    const int rc = rock_calm(P, R, x, i, &b, &theta_max);
    if (rc != ROCK_JUMP)
        return rc;
    const size_t c = ref_anchor(b - CHECK); /* b starts a block */
    if (c < i + 2 * CHECK || L->t[c] - calm < 2.0 * P->lead)
        return ROCK_STAY;
    *to = c;
    return ROCK_JUMP;
}

/* After checkpoint i of a trial whose peak must be the one of a run from
 * the start, made as before (the linear state a lead-in before each
 * stretch that can lift an edge, cushion_jump), with no edge lifted since
 * last_lift: the same run without the samples it computes for nothing.
 * While no edge can lift (rock_calm), that run's state holds no lift to
 * wait for, so where it would next jump (the first checkpoint at which
 * cushion_jump moves it, before any edge can lift) can be known now, and
 * the run jumps there at once, to the very state it would have had; and
 * when no edge can lift any more up to the end, the run is over.  Both
 * only when the package has already been further from upright than
 * anything skipped can take it, so that the peak stands. */
static int exact_jump(const prep_t *P, const sw_runner_t *R, double x, size_t i, double last_lift,
                      size_t *to)
{
    const sw_log_t *L = P->log;
    size_t b;
    double theta_max;
    const int rc = rock_calm(P, R, x, i, &b, &theta_max);
    if (rc == ROCK_STAY)
        return rc;
    sw_summary_t sum;
    sw_engine_summary(R->e, 0, &sum);
    if (!(sum.max_abs_theta >= theta_max))
        return ROCK_STAY;
    if (rc == ROCK_OVER)
        return rc;
    /* cushion_jump at the checkpoints from i on: it first moves the run at
     * the first one a lead-in after last_lift, j, if ever; the next block
     * that can lift at x is the same from all of them (none before b) */
    size_t j = i;
    while (j < b && L->t[j] - last_lift < P->lead) j += CHECK;
    if (j >= b)
        return ROCK_STAY;
    const size_t t = cushion_jump(P, j, last_lift, x / LIFT_MARGIN_LOG);
    if (!t || t >= b) /* none, or past a block that can lift: keep running */
        return ROCK_STAY;
    *to = t;
    return ROCK_JUMP;
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

/* After sample i (a checkpoint) of a search trial on a frame: the sample
 * to jump to, or 0 for none, with the state there in *to_state.
 *
 * While the package stands on its frame the frame is a linear oscillator
 * (physics.md), so the state at scale x is x times the stored unit-scale
 * state plus the free ringing of the difference d = (u, u') - x q, which
 * the oscillator carries in closed form (sw_nj_step without input).  The
 * support acceleration of that ringing never exceeds
 * w sqrt(1 + 4 zeta^2) sqrt(2 e), e = (d'^2 + w^2 d^2) / 2 the ringing's
 * energy, which can only fall (the bound of reserve_lift.c); over the lift
 * threshold g tan(alpha) it is D.  So no sample lifts the package before
 * the first at which x |A_1| / (g tan(alpha)) reaches LIFT_MARGIN_LOG (1 -
 * D), A_1 the stored unit-scale support acceleration: the run jumps to the
 * checkpoint before it, in the state the stuck run would have had there
 * (to rounding), and skips nothing that could lift the package. */
#define FRAME_D_MAX 0.5 /* a larger ringing: no jump (the bound would allow little) */
static size_t frame_jump(const prep_t *P, const sw_runner_t *R, double x, size_t i,
                         sw_state_t *to_state)
{
    const sw_log_t *L = P->log;
    if (i % CHECK || L->a_z || i + 2 * CHECK >= L->n)
        return 0;
    sw_output_t o;
    sw_engine_get_output(R->e, 0, &o);
    if (o.state.phase != SW_PHASE_STUCK)
        return 0;
    const double w = P->d.omega_b, zeta = P->d.zeta_b;
    const double *q = &P->st[2 * (i / CHECK)];
    double d[2] = {o.state.u - x * q[0], o.state.u_dot - x * q[1]};
    const double e = 0.5 * (d[1] * d[1] + w * w * d[0] * d[0]);
    const double D = w * sqrt(1.0 + 4.0 * zeta * zeta) * sqrt(2.0 * e) / (P->sc->g * P->tan_alpha);
    if (!(D < FRAME_D_MAX))
        return 0;
    const double X = x / (LIFT_MARGIN_LOG * (1.0 - D));
    if (P->blk[i / BLOCK] <= X) /* the rest of sample i's block may lift */
        return 0;
    const size_t k = next_block(P, i, X);
    size_t to = k >= L->n ? L->n - 1 : k - 1;
    to -= to % CHECK;
    if (to < i + 2 * CHECK)
        return 0;
    /* a restart in between puts the run and the stored states at rest
     * alike: nothing of the ringing is left */
    for (size_t r = 0; r < L->nrestart; r++)
        if (L->restart[r] > i && L->restart[r] <= to)
            d[0] = d[1] = 0.0;
    double d1[2];
    sw_nj_step(w, zeta, L->t[to] - L->t[i], 0.0, 0.0, d, d1);
    const double *q1 = &P->st[2 * (to / CHECK)];
    *to_state = o.state;
    to_state->u = x * q1[0] + d1[0];
    to_state->u_dot = x * q1[1] + d1[1];
    return to;
}

/* How a trial runs: as a run of the log from its start reports it (the
 * run at scale 1); with the jumps that keep whether it overturns and its
 * peak exactly (a search trial whose peak sets the scan's step); or with
 * every jump (fast: the cushion's references, a peak that is a lower
 * bound). */
enum { RUN_FULL, RUN_PEAK, RUN_FAST };

/* The trial's samples from i0 on, then the free motion (sw_run_log_on's
 * loop, with the jumps of its mode).  calm: s, when the cushion's state
 * last held something to forget (-INFINITY: nothing). */
static int trial_run(const prep_t *P, sw_runner_t *R, double x, size_t i0, int mode, double calm,
                     sw_run_result_t *r)
{
    const sw_log_t *L = P->log;
    sw_engine_t *e = R->e;
    const double X = x / BARE_EDGE;
    size_t next_restart = 0;
    while (next_restart < L->nrestart && L->restart[next_restart] <= i0) next_restart++;
    int look = P->kind == CK_DIRECT; /* look for a jump: from the start, and after events */
    double last_lift = calm;         /* cushion: the start's error decays as a lift's does */
    int over = 0;                    /* the outcome and the peak are known: the run ends */
    for (size_t i = i0 + 1; i < L->n; i++) {
        size_t to = 0;
        const int calm_now = P->kind == CK_ROCK && !(last_lift > L->t[i - 1]);
        const int rj = calm_now && mode == RUN_FAST   ? rock_jump(P, R, x, i - 1, calm, &to)
                       : calm_now && mode == RUN_PEAK ? exact_jump(P, R, x, i - 1, last_lift, &to)
                                                      : ROCK_STAY;
        if (rj == ROCK_OVER) {
            over = 1;
            break;
        }
        const ref_t *f = rj == ROCK_JUMP && mode == RUN_FAST ? ref_get(P, to) : NULL;
        if (f) {
            while (next_restart < L->nrestart && L->restart[next_restart] <= to) next_restart++;
            sw_engine_restart(e);
            const int rc = ref_begin(P, R, f, x, to);
            if (rc < 0)
                return rc;
            last_lift = calm = -INFINITY;
            i = to;
            continue;
        }
        /* a fast trial falls back on the lead-in only where it has no
         * references, and only after a lift or from a linear state */
        const int lead_in_ok = mode != RUN_FAST || (rj == ROCK_JUMP && isfinite(last_lift));
        if (P->kind == CK_ROCK &&
            ((rj == ROCK_JUMP && mode == RUN_PEAK) ||
             (lead_in_ok && (to = cushion_jump(P, i - 1, last_lift, x / LIFT_MARGIN_LOG))))) {
            while (next_restart < L->nrestart && L->restart[next_restart] <= to) next_restart++;
            sw_engine_restart(e);
            const int rc = sw_engine_push(e, L->t[to], x * L->a_g[to], 0.0);
            if (rc < 0)
                return rc;
            const int sr = linear_state(P, e, x, to);
            if (sr != SW_OK)
                return sr;
            last_lift = calm = L->t[to];
            i = to;
            continue; /* the loop goes on at sample to + 1 */
        }
        sw_state_t st;
        if (P->kind == CK_STUCK && mode != RUN_FULL && (to = frame_jump(P, R, x, i - 1, &st))) {
            while (next_restart < L->nrestart && L->restart[next_restart] <= to) next_restart++;
            sw_engine_restart(e);
            int rc = sw_engine_push(e, L->t[to], x * L->a_g[to], 0.0);
            if (rc >= 0)
                rc = sw_engine_set_state(e, 0, &st);
            if (rc < 0)
                return rc;
            i = to;
            continue;
        }
        const int j = look ? bare_jump(P, R, i - 1, X, &to) : JUMP_STOP;
        if (j == JUMP_STOP)
            look = 0;
        if (j == JUMP_GO) {
            while (next_restart < L->nrestart && L->restart[next_restart] <= to) next_restart++;
            sw_engine_restart(e); /* at rest already: the run goes on afresh from sample to */
            i = to;
        }
        const int rc = sw_run_push(e, L, i, x, &next_restart);
        if (rc == SW_EVENT) {
            sw_summary_t s;
            sw_engine_summary(e, 0, &s);
            if (s.overturned)
                break;
            /* an edge lifts only between an uplift and the rest after it */
            last_lift = s.uplifts > s.rests ? INFINITY : L->t[i];
            calm = fmax(calm, L->t[i]);
            look = P->kind == CK_DIRECT;
        }
    }
    const double p = sw_engine_derived(e, 0)->p;
    const double t = sw_engine_time(e);
    if (isnan(t))
        return SW_EINVAL;
    return sw_run_free_motion(R, over ? t : t + sw_run_free_time(P->ro, p),
                              2.0 * M_PI / p / SW_RUN_CHECKS_PER_PERIOD, r);
}

/* A fast trial on a cushion: from the reference state at the anchor
 * before its first stretch that can lift an edge, instead of the linear
 * state a lead-in before it (i0; from rest when i0 is the log's start),
 * then with the early jumps.  Returns the trial's status. */
static int rock_trial(const prep_t *P, sw_runner_t *R, double x, size_t i0, sw_run_result_t *r)
{
    const size_t k = first_lift(P, x / LIFT_MARGIN_LOG);
    size_t c = k ? k - 1 : 0;
    c = ref_anchor(c - c % CHECK);
    const ref_t *f = i0 > 0 && c > i0 ? ref_get(P, c) : NULL;
    int err;
    if (!f) {
        if ((err = trial_begin(P, R, x, i0)) == SW_OK)
            err = trial_run(P, R, x, i0, RUN_FAST, i0 > 0 ? P->log->t[i0] : -INFINITY, r);
        return err;
    }
    sw_runner_reset(R);
    if ((err = sw_engine_set_origin(R->e, P->log->t[0])) != SW_OK ||
        (err = ref_begin(P, R, f, x, c)) < 0)
        return err;
    return trial_run(P, R, x, c, RUN_FAST, -INFINITY, r);
}

/* One trial at scale x into r.  A search trial (full 0) at which nothing
 * can lift the package is safe without a run; a full one runs anyway, over
 * its largest response. */
int sw_safety_trial(const prep_t *P, double x, sw_trial_need need, sw_run_result_t *r, char *msg,
                    size_t msglen)
{
    memset(r, 0, sizeof *r);
    int none, err = SW_OK;
    const size_t i0 = trial_start(P, x, &none);
    if (none && need != SW_TRIAL_FULL) {
        r->end = SW_END_REST;
        r->uplift_time = r->tip_time = r->overturn_time = NAN;
        r->min_margin = 1.0;
        r->t_end = P->log->t[P->log->n - 1];
        return SW_OK;
    }
    sw_runner_t R;
    const sw_run_opts_t ro = trial_opts(P, need);
    if (sw_runner_make(&R, P->sc, &ro, 0.0, &err, msg, msglen) != SW_OK)
        return err;
    /* A cushion's fast trial gets a peak right to about 1e-9 of itself
     * (the reference states), not as a run from the start would to the
     * last digits: where the scan's step depends on it, the trial is made
     * again as before, from the linear state a lead-in before each stretch
     * (below SW_SAFETY_NEAR_PEAK, with room for that error). */
    int done = 0;
    if (P->kind == CK_ROCK && (need == SW_TRIAL_PEAK || need == SW_TRIAL_OUTCOME) && !none) {
        err = rock_trial(P, &R, x, i0, r);
        done = err < 0 || r->overturned || need == SW_TRIAL_OUTCOME ||
               r->max_theta_ratio >= SW_SAFETY_NEAR_PEAK * (1.0 + PEAK_TOL);
    }
    if (!done) {
        memset(r, 0, sizeof *r);
        if ((err = trial_begin(P, &R, x, i0)) == SW_OK)
            err = trial_run(P, &R, x, i0, need == SW_TRIAL_FULL ? RUN_FULL : RUN_PEAK,
                            P->log->t[i0], r);
    }
    sw_engine_destroy(R.e);
    if (err == SW_EFAULT)
        sw_set_msg(msg, msglen, "the model faulted during a trial");
    else if (err < 0)
        sw_set_msg(msg, msglen, "%s", sw_strerror(err));
    return err;
}
