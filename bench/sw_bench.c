/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sw_bench.c - speed against accuracy of every model and scheme, written
 * as markdown tables and gnuplot data for docs/accuracy-speed.md (run it
 * through scripts/run-bench.sh, which also records the machine).
 *
 *   sw_bench run [--quick] [--runs N] [--data DIR]   all measurements
 *   sw_bench gen-csv [--hours H] [--seed S] [--incident]  the road log as CSV;
 *                                                    --incident: calm, ending in a hard stop
 *   sw_bench replay-csv FILE|- [--model bare|frame]  CSV parse + engine
 *   sw_bench rock|road|baseline|gen [--model M] [--scheme S] [--dt DT]
 *            [--rtol R] [--stepped] [--seconds N]   one workload (profiling)
 *   sw_bench planes [--runs N] [--seconds N]        one plane against two
 *   sw_bench shocks [--model M] [--planes 0|1|2] [--seconds N]  its workload
 *                                                   (0: the input alone)
 *
 * What "run" measures, per model (table below) and scheme setting:
 * - cost while rocking: the package is kept rocking (free rocking from
 *   0.9 alpha, restarted when it comes to rest) under 1 kHz samples; CPU ns
 *   per input sample and per internal step, median of --runs runs;
 * - accuracy on pulses: half-sine braking pulses at 0.9 and 1.1 times the
 *   overturning boundary for four omega_e/p, sampled at 1 kHz; error of
 *   max|theta| (survivors) and of the overturn time (overturners) against
 *   rk8pd at rtol 1e-12 on the same samples;
 * - decisions: 200 pulses within +-5 % of the boundary (found by the
 *   reference); how many overturn decisions agree with the reference;
 * - an hour of road at 1 kHz (bench_road.c) for the defaults and a few
 *   other settings: real-time factor, and the straightforward GSL baseline
 *   (bench_baseline.c) on the same log. */
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>

#include "bench.h"

#define G0 9.81
#define RATE 1000.0 /* Hz, sample rate of every workload */

/* ---- models: adding one is one row ------------------------------------ */

static sw_scene_t scene_crate(void)
{
    sw_scene_t sc;
    sw_scene_init(&sc);
    snprintf(sc.name, sizeof sc.name, "crate-A");
    sc.height = 2.0; /* m */
    sc.width = 0.728;
    sc.mass = 1000.0;
    return sc;
}

static sw_scene_t scene_bare(void)
{
    return scene_crate();
}

static sw_scene_t scene_frame(void)
{
    sw_scene_t sc = scene_crate();
    sc.has_frame = 1;
    sc.frame_mass = 250.0;
    sc.frame_omega = 5.59;
    sc.frame_zeta = 0.1;
    sc.frame_k_given = sc.frame_c_given = SW_GIVEN_RATIO;
    return sc;
}

/* The crate on a cushion on the bed: soft (that of crate-a.ini, omega_c =
 * 44.7 rad/s) and stiff (omega_c = 1e4 rad/s, where docs/cushion.md makes
 * rkck the default). */
static sw_scene_t scene_cushion(double omega_c, double zeta_c)
{
    sw_scene_t sc = scene_crate();
    sc.has_cushion = 1;
    sc.cushion_omega = omega_c;
    sc.cushion_zeta = zeta_c;
    sc.cushion_k_given = sc.cushion_c_given = SW_GIVEN_RATIO;
    return sc;
}

static sw_scene_t scene_cushion_soft(void)
{
    return scene_cushion(44.7, 0.045);
}

static sw_scene_t scene_cushion_stiff(void)
{
    return scene_cushion(1e4, 0.05);
}

typedef struct {
    const char *name;
    sw_scene_t (*scene)(void);
    int baseline; /* bench_baseline.c implements it */
    int cushion;  /* never stuck: kept moving by pulses, settings without Euler/Heun */
} bmodel_t;

/* The crate of tests/scenes/crate-a*.ini; a model is one row. */
static const bmodel_t models[] = {
    {"bare", scene_bare, 1, 0},
    {"frame", scene_frame, 1, 0},
    {"cushion-soft", scene_cushion_soft, 0, 1},
    {"cushion-stiff", scene_cushion_stiff, 0, 1},
};
#define NMODELS (sizeof models / sizeof models[0])
static const bmodel_t *find_model(const char *name);

/* ---- scheme settings -------------------------------------------------- */

typedef struct {
    const char *scheme;
    double dt;   /* s, fixed-step schemes */
    double rtol; /* adaptive schemes (atol = rtol / 100) */
    int road;    /* also run on the hour of road */
} bcfg_t;

static const bcfg_t cfgs[] = {
    {"euler", 1e-3, 0, 0},  {"euler", 1e-4, 0, 1},  {"euler", 3e-5, 0, 0}, {"heun", 1e-3, 0, 1},
    {"heun", 5e-4, 0, 0},   {"heun", 2.5e-4, 0, 0}, {"heun", 1e-4, 0, 0},  {"heun", 5e-5, 0, 0},
    {"rk4", 1e-3, 0, 1},    {"rk4", 5e-4, 0, 0},    {"rk4", 2.5e-4, 0, 1}, {"rk4", 1e-4, 0, 0},
    {"rk4", 5e-5, 0, 0},    {"rkf45", 0, 1e-4, 0},  {"rkf45", 0, 1e-6, 0}, {"rkf45", 0, 1e-8, 1},
    {"rkf45", 0, 1e-10, 0}, {"rkck", 0, 1e-4, 0},   {"rkck", 0, 1e-6, 0},  {"rkck", 0, 1e-8, 1},
    {"rkck", 0, 1e-10, 0},  {"rk8pd", 0, 1e-4, 0},  {"rk8pd", 0, 1e-6, 0}, {"rk8pd", 0, 1e-8, 0},
    {"rk8pd", 0, 1e-10, 1}, {"rk4imp", 0, 1e-8, 0}, {"bsimp", 0, 1e-8, 0}, {"msbdf", 0, 1e-8, 0},
};
#define NCFGS (sizeof cfgs / sizeof cfgs[0])
static const bcfg_t ref_cfg = {"rk8pd", 0, 1e-12, 0};

/* The settings run on the cushion models: RK4 at the default step, the
 * adaptive and implicit schemes at rtol 1e-8 (and rkck and rk8pd at the
 * default 1e-10); Euler and Heun add nothing there but hours. */
static int cushion_cfg(const bcfg_t *c)
{
    if (!strcmp(c->scheme, "rk4"))
        return c->dt == 1e-3;
    if (!strcmp(c->scheme, "euler") || !strcmp(c->scheme, "heun"))
        return 0;
    return c->rtol == 1e-8 || (c->rtol == 1e-10 && strcmp(c->scheme, "rkf45"));
}

static const char *cfg_label(const bcfg_t *c, char *buf, size_t n)
{
    if (c->rtol > 0)
        snprintf(buf, n, "%s rtol %.0e", c->scheme, c->rtol);
    else
        snprintf(buf, n, "%s dt %.2g", c->scheme, c->dt);
    return buf;
}

/* ---- engine runs ------------------------------------------------------ */

typedef struct {
    int moving, over, faults;
    long uplifts;
} watch_t;

static void on_event(void *user, const sw_event_t *ev)
{
    watch_t *w = user;
    switch (ev->kind) {
        case SW_EV_UPLIFT:
            w->moving = 1;
            w->uplifts++;
            break;
        case SW_EV_REST: w->moving = 0; break;
        case SW_EV_OVERTURN:
            w->over = 1;
            w->moving = 0;
            break;
        case SW_EV_FAULT:
            w->faults++;
            w->moving = 0;
            break;
        default: break;
    }
}

static sw_engine_t *engine(const sw_scene_t *sc, const bcfg_t *c, int stepped, watch_t *w)
{
    sw_engine_opts_t o = {0};
    o.scheme = c->scheme;
    o.dt = c->dt;
    o.rtol = c->rtol;
    o.atol = c->rtol * 1e-2;
    o.stuck_stepped = stepped;
    o.on_event = w ? on_event : NULL;
    o.user = w;
    int err = 0;
    char msg[256];
    sw_engine_t *e = sw_engine_create(sc, 1, &o, &err, msg, sizeof msg);
    if (!e)
        fprintf(stderr, "sw_bench: engine: %s\n", msg);
    return e;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* CPU time of this process: leaves out the time it waited while other
 * work ran on a shared machine (wall time is reported beside it). */
static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int cmp_dbl(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_dbl);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* A half-sine braking pulse of ratio * g tan(alpha) at omega_e = wp * p,
 * sampled at RATE, then no input until the package rests or overturns (or
 * 20 rocking periods pass). */
typedef struct {
    double theta_max, t_over;
    int over, faults;
    long steps, samples;
} prun_t;

static prun_t run_pulse(const sw_scene_t *sc, const bcfg_t *c, double ratio, double wp)
{
    prun_t r = {0};
    watch_t w = {0};
    sw_engine_t *e = engine(sc, c, 0, &w);
    if (!e) {
        r.faults = 1;
        return r;
    }
    const sw_derived_t *d = sw_engine_derived(e, 0);
    sw_pulse_t pu = {SW_PULSE_HALF_SINE, -ratio * sc->g * tan(d->alpha), wp * d->p};
    /* then free motion: overturns come within 2-3 s, the cascade's end
     * (rest) does not change max|theta|; a package on a cushion never
     * comes to rest, 3 s of it are enough */
    const double free_s = d->model == SW_MODEL_CUSHION ? 3.0 : 8.0;
    const double T = sw_pulse_duration(&pu), t_end = T + fmin(free_s, 20.0 * 2.0 * M_PI / d->p);
    for (long i = 0;; i++) {
        const double t = i / RATE;
        sw_engine_push(e, t, sw_pulse_eval(&pu, t), 0.0);
        r.samples++;
        if (w.over || t > t_end || (t > T && !w.moving && w.uplifts > 0))
            break;
    }
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    r.theta_max = s.max_abs_theta;
    r.over = s.overturned;
    r.t_over = s.overturn_time;
    r.faults = (int)s.faults;
    r.steps = s.steps;
    sw_engine_destroy(e);
    return r;
}

/* Keep the package rocking for `seconds` of 1 kHz zero input: free rocking
 * from 0.9 alpha, alternately forward and back, restarted at rest.  A
 * package on a cushion has no rigid rocking to start from: it gets a
 * braking or speeding-up half-sine of 0.8 g tan(alpha) at omega_e = 3 p
 * every 4 s instead (below every boundary measured).  Returns the CPU time; steps and samples
 * through the pointers. */
static double run_rocking(const sw_scene_t *sc, const bcfg_t *c, double seconds, long *steps,
                          long *samples)
{
    watch_t w = {0};
    sw_engine_t *e = engine(sc, c, 0, &w);
    if (!e)
        return NAN;
    const sw_derived_t *d = sw_engine_derived(e, 0);
    const long n = (long)(seconds * RATE);
    const int cushion = d->model == SW_MODEL_CUSHION;
    sw_pulse_t pu = {SW_PULSE_HALF_SINE, 0.8 * sc->g * tan(d->alpha), 3.0 * d->p};
    int side = 1;
    const double t0 = cpu_now();
    sw_engine_push(e, 0.0, 0.0, 0.0);
    for (long i = 1; i <= n; i++) {
        if (cushion) {
            const double t = i / RATE, tp = fmod(t, 4.0);
            const double sg = fmod(t, 8.0) < 4.0 ? -1.0 : 1.0;
            sw_engine_push(e, t, sg * sw_pulse_eval(&pu, tp), 0.0);
            continue;
        }
        if (!w.moving) {
            sw_state_t st = {0};
            st.theta = side * 0.9 * d->alpha;
            st.phase = SW_PHASE_ROCKING;
            st.side = side;
            side = -side;
            sw_engine_set_state(e, 0, &st);
            w.moving = 1;
        }
        sw_engine_push(e, i / RATE, 0.0, 0.0);
    }
    const double el = cpu_now() - t0;
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    *steps = s.steps;
    *samples = n;
    sw_engine_destroy(e);
    return el;
}

/* The hour of road through one engine; CPU time (wall time in *wall),
 * summary. */
static double run_road(const sw_scene_t *sc, const bcfg_t *c, int stepped, const bench_log_t *log,
                       sw_summary_t *s, double *wall)
{
    sw_engine_t *e = engine(sc, c, stepped, NULL);
    if (!e)
        return NAN;
    const double w0 = now(), t0 = cpu_now();
    for (size_t i = 0; i < log->n; i++) sw_engine_push(e, log->t[i], log->a[i], 0.0);
    const double el = cpu_now() - t0;
    if (wall)
        *wall = now() - w0;
    sw_engine_summary(e, 0, s);
    sw_engine_destroy(e);
    return el;
}

/* ---- one plane against two (issue 29: two cost at most twice one) ----- */

/* The shocks workload: a half-sine of amp * g tan(alpha) at omega_e = 3 p
 * every 4 s, braking and speeding up in turn, so that the package rocks
 * (lifts, impacts, comes to rest) for much of the time: amp = 1.6 on the
 * bed and the frame (0.70 and 0.83 of their boundaries at omega_e/p = 3).
 * On a cushion one shock of 0.8 (0.65 of the soft one's boundary) and
 * the free motion after it, which never rests (one step per sample):
 * repeated every 4 s, even shocks of 0.3 overturned the soft cushion's
 * package within 200 s.  With planes = 2 the scene gets a depth equal to
 * its width and the engine the same input across the truck
 * (sw_engine_push_lat): the second plane is the first's twin, so the
 * ratio is the second plane's cost, not a different motion's.  planes =
 * 0 makes the input alone (its cost, to subtract).  Returns the CPU time;
 * the longitudinal plane's summary and the samples through the pointers. */
static double run_shocks(const sw_scene_t *sc0, int planes, double seconds, sw_summary_t *s,
                         long *samples)
{
    sw_scene_t sc = *sc0;
    if (planes == 2)
        sc.depth = sc.width; /* m */
    sw_engine_opts_t o = {0};
    o.lateral = planes == 2;
    int err = 0;
    char msg[256];
    sw_engine_t *e = sw_engine_create(&sc, 1, &o, &err, msg, sizeof msg);
    if (!e) {
        fprintf(stderr, "sw_bench: engine: %s\n", msg);
        return NAN;
    }
    const sw_derived_t *d = sw_engine_derived(e, 0);
    const double amp = d->model == SW_MODEL_CUSHION ? 0.8 : 1.6;
    sw_pulse_t pu = {SW_PULSE_HALF_SINE, amp * sc.g * tan(d->alpha), 3.0 * d->p};
    const double every = d->model == SW_MODEL_CUSHION ? INFINITY : 4.0; /* s */
    const long n = (long)(seconds * RATE);
    volatile double sink = 0.0; /* planes = 0: the input alone, its cost to subtract */
    const double t0 = cpu_now();
    for (long i = 0; i <= n; i++) {
        const double t = i / RATE, tp = isinf(every) ? t : fmod(t, every);
        const double a = (fmod(t, 8.0) < 4.0 ? -1.0 : 1.0) * sw_pulse_eval(&pu, tp); /* m/s^2 */
        if (planes == 2)
            sw_engine_push_lat(e, t, a, a, 0.0);
        else if (planes == 1)
            sw_engine_push(e, t, a, 0.0);
        else
            sink += a;
    }
    const double el = cpu_now() - t0;
    (void)sink;
    sw_engine_summary(e, 0, s);
    *samples = n + 1;
    sw_engine_destroy(e);
    return el;
}

/* The models of the planes table: the bed, the frame and the soft cushion. */
static const char *const plane_models[] = {"bare", "frame", "cushion-soft"};
#define NPLANE_MODELS (sizeof plane_models / sizeof plane_models[0])

/* One plane against two on the shocks workload, per model: CPU ns per
 * sample of the engine (the input's own cost, measured alone in the same
 * run, subtracted), median of runs, the three interleaved run by run so
 * that they see the same load, and the ratio of the medians and its range
 * over the runs, as a markdown table. */
static int cmd_planes(int runs, double seconds)
{
    printf(
        "| model | uplifts (per plane) | steps per sample (per plane) | input alone (ns per "
        "sample) | one plane (ns per sample) | two planes (ns per sample) | ratio two / one "
        "(medians) | ratio, range over the runs |\n|---|---|---|---|---|---|---|---|\n");
    for (size_t m = 0; m < NPLANE_MODELS; m++) {
        const sw_scene_t sc = find_model(plane_models[m])->scene();
        double t0[64], t1[64], t2[64], r[64];
        sw_summary_t s0, s1 = {0}, s2 = {0};
        long n = 1;
        for (int k = 0; k < runs; k++) {
            t0[k] = run_shocks(&sc, 0, seconds, &s0, &n);
            t1[k] = run_shocks(&sc, 1, seconds, &s1, &n) - t0[k];
            t2[k] = run_shocks(&sc, 2, seconds, &s2, &n) - t0[k];
            r[k] = t2[k] / t1[k];
        }
        if (s1.uplifts != s2.uplifts || s1.steps != s2.steps || s1.overturned || s2.overturned)
            fprintf(stderr, "sw_bench: %s: the planes' runs differ or overturned\n",
                    plane_models[m]);
        const double m0 = median(t0, runs), m1 = median(t1, runs), m2 = median(t2, runs);
        qsort(r, (size_t)runs, sizeof *r, cmp_dbl);
        printf("| %s | %ld | %.2f | %.0f | %.0f | %.0f | %.2f | %.2f to %.2f |\n", plane_models[m],
               s1.uplifts, (double)s1.steps / n, 1e9 * m0 / n, 1e9 * m1 / n, 1e9 * m2 / n, m2 / m1,
               r[0], r[runs - 1]);
        fflush(stdout);
    }
    return 0;
}

/* ---- the boundary and the pulse sets ---------------------------------- */

#define NW 4
static const double wps[NW] = {1.5, 3.0, 6.0, 12.0}; /* omega_e / p */
#define NDEC 50                                      /* pulses per frequency */

/* Smallest overturning amplitude ratio by the reference: scan up by 10 %
 * from the rigid uplift threshold (down, for a soft cushion that overturns
 * below it), then bisect to 1e-6. */
static double boundary(const sw_scene_t *sc, double wp)
{
    double lo = 1.0, hi = 1.0;
    if (run_pulse(sc, &ref_cfg, 1.0, wp).over) {
        while (lo > 0.01 && run_pulse(sc, &ref_cfg, lo, wp).over) {
            hi = lo;
            lo /= 1.1;
        }
    } else {
        while (hi < 100.0) {
            if (run_pulse(sc, &ref_cfg, hi, wp).over)
                break;
            lo = hi;
            hi *= 1.1;
        }
    }
    while (hi - lo > 1e-6 * hi) {
        const double m = 0.5 * (lo + hi);
        if (run_pulse(sc, &ref_cfg, m, wp).over)
            hi = m;
        else
            lo = m;
    }
    return hi;
}

static double dec_ratio(double b, int k)
{
    return b * (1.0 + 0.05 * (2.0 * k / (NDEC - 1) - 1.0));
}

typedef struct {
    double err_theta, err_tover;                 /* rad, s: worst over the accuracy pulses */
    int acc_flips;                               /* accuracy pulses whose decision differs */
    int agree, total, faults;                    /* decisions */
    double ns_sample, ns_step, steps_per_sample; /* while rocking */
} cres_t;

/* ---- output helpers --------------------------------------------------- */

static void fmt_err(char *buf, size_t n, double v, int flips)
{
    if (flips)
        snprintf(buf, n, "decision differs (%d)", flips);
    else if (v == 0.0)
        snprintf(buf, n, "0");
    else
        snprintf(buf, n, "%.1e", v);
}

static long max_rss_kib(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

/* ---- run -------------------------------------------------------------- */

static int cmd_run(int quick, int runs, const char *data)
{
    const double rock_s = quick ? 20.0 : 200.0;   /* s of rocking per timing run */
    const double road_s = quick ? 360.0 : 3600.0; /* s of road */
    const int ndec = quick ? 10 : NDEC;
    printf("<!-- generated by sw_bench run%s --runs %d -->\n\n", quick ? " --quick" : "", runs);
    for (size_t m = 0; m < NMODELS; m++) {
        const sw_scene_t sc = models[m].scene();
        sw_derived_t d;
        sw_scene_validate(&sc, &d, NULL, NULL, NULL);
        fprintf(stderr, "sw_bench: %s: boundary by the reference\n", models[m].name);
        double bnd[NW];
        for (int k = 0; k < NW; k++) bnd[k] = boundary(&sc, wps[k]);
        /* reference answers */
        prun_t ref_acc[NW][2], ref_dec[NW][NDEC];
        for (int k = 0; k < NW; k++) {
            ref_acc[k][0] = run_pulse(&sc, &ref_cfg, 0.9 * bnd[k], wps[k]);
            ref_acc[k][1] = run_pulse(&sc, &ref_cfg, 1.1 * bnd[k], wps[k]);
            for (int j = 0; j < ndec; j++)
                ref_dec[k][j] = run_pulse(
                    &sc, &ref_cfg, dec_ratio(bnd[k], j * (NDEC - 1) / (ndec > 1 ? ndec - 1 : 1)),
                    wps[k]);
        }
        printf("### Model `%s`\n\n", models[m].name);
        printf("alpha = %.4f rad, p = %.4f rad/s", d.alpha, d.p);
        if (d.model == SW_MODEL_FRAME)
            printf(", gamma = %.3f, omega_b = %.3f rad/s, zeta_b = %.3f", d.gamma, d.omega_b,
                   d.zeta_b);
        printf(
            ".  Overturning boundary of a half-sine braking pulse by the reference, "
            "a_e / (g tan alpha):\n\n| omega_e/p |");
        for (int k = 0; k < NW; k++) printf(" %g |", wps[k]);
        printf("\n|---|");
        for (int k = 0; k < NW; k++) printf("---|");
        printf("\n| boundary |");
        for (int k = 0; k < NW; k++) printf(" %.5f |", bnd[k]);
        printf("\n\nReference at 0.9 x boundary: max|theta| / alpha =");
        for (int k = 0; k < NW; k++) printf(" %.4f", ref_acc[k][0].theta_max / d.alpha);
        printf("; at 1.1 x boundary: overturn time (s) =");
        for (int k = 0; k < NW; k++) printf(" %.4f", ref_acc[k][1].t_over);
        printf(".\n\n");
        printf(
            "| scheme | dt (s) / rtol | ns per sample (rocking) | ns per step | M steps/s | "
            "steps per sample | max-theta error (rad) | overturn-time error (s) | decisions "
            "agreeing | faults |\n|---|---|---|---|---|---|---|---|---|---|\n");
        FILE *dat = NULL;
        if (data) {
            char path[512];
            snprintf(path, sizeof path, "%s/pareto-%s.dat", data, models[m].name);
            dat = fopen(path, "w");
            if (dat)
                fprintf(dat, "# scheme dt rtol ns_per_sample err_theta err_tover agree total\n");
        }
        cres_t all[NCFGS];
        for (size_t c = 0; c < NCFGS; c++) {
            const bcfg_t *C = &cfgs[c];
            char lab[64];
            all[c] = (cres_t){.faults = 1};
            if (models[m].cushion && !cushion_cfg(C))
                continue;
            fprintf(stderr, "sw_bench: %s: %s\n", models[m].name, cfg_label(C, lab, sizeof lab));
            cres_t R = {0};
            for (int k = 0; k < NW; k++) {
                for (int j = 0; j < 2; j++) {
                    const prun_t p = run_pulse(&sc, C, (j ? 1.1 : 0.9) * bnd[k], wps[k]);
                    const prun_t *q = &ref_acc[k][j];
                    R.faults += p.faults;
                    if (p.over != q->over)
                        R.acc_flips++;
                    else if (q->over)
                        R.err_tover = fmax(R.err_tover, fabs(p.t_over - q->t_over));
                    else
                        R.err_theta = fmax(R.err_theta, fabs(p.theta_max - q->theta_max));
                }
                for (int j = 0; j < ndec; j++) {
                    const prun_t p = run_pulse(
                        &sc, C, dec_ratio(bnd[k], j * (NDEC - 1) / (ndec > 1 ? ndec - 1 : 1)),
                        wps[k]);
                    R.faults += p.faults;
                    R.agree += p.over == ref_dec[k][j].over;
                    R.total++;
                }
            }
            double tw[64], steps_ps = 0.0, ns_step = 0.0;
            /* about the same number of steps for every setting */
            const double per = C->dt > 0.0 && C->dt < 1e-3 ? 1e-3 / C->dt : 1.0;
            const double secs = fmax(rock_s / per, fmin(rock_s, 10.0));
            for (int r = 0; r < runs; r++) {
                long st = 0, sa = 1;
                tw[r] = run_rocking(&sc, C, secs, &st, &sa);
                tw[r] /= (double)sa;
                steps_ps = (double)st / sa;
            }
            R.ns_sample = 1e9 * median(tw, runs);
            ns_step = R.ns_sample / steps_ps;
            char e1[64], e2[64];
            fmt_err(e1, sizeof e1, R.err_theta, R.acc_flips);
            fmt_err(e2, sizeof e2, R.err_tover, R.acc_flips);
            char dts[32];
            if (C->rtol > 0)
                snprintf(dts, sizeof dts, "rtol %.0e", C->rtol);
            else
                snprintf(dts, sizeof dts, "%.2g", C->dt);
            all[c] = R;
            printf("| %s | %s | %.0f | %.0f | %.2f | %.2f | %s | %s | %d / %d | %d |\n", C->scheme,
                   dts, R.ns_sample, ns_step, 1e3 / ns_step, steps_ps, e1, e2, R.agree, R.total,
                   R.faults);
            fflush(stdout);
            if (dat)
                fprintf(dat, "%s %g %g %.1f %.3e %.3e %d %d\n", C->scheme, C->dt, C->rtol,
                        R.ns_sample, R.acc_flips ? 1.0 : fmax(R.err_theta, 1e-16),
                        R.acc_flips ? 1.0 : fmax(R.err_tover, 1e-16), R.agree, R.total);
        }
        if (dat)
            fclose(dat);
        /* the accuracy option's table: per decade of tolerance the cheapest
         * setting whose max-theta error was at most half of it (adaptive
         * schemes only at the engine's default rtol 1e-10).  Euler and Heun
         * only for the bare block: they are not stable on the imaginary
         * axis, and a frame or a cushion is an oscillator whose damping a
         * scene may set near zero (their errors on this crate's damped
         * bearings do not show it). */
        printf(
            "\nRows this run measured for `%s` (the cheapest setting per decade of "
            "tolerance; the rows in use are under \"Accuracy option\"):\n\n```\n",
            models[m].name);
        int prev = -1;
        double prev_tol = 0.0;
        for (int e10 = -2; e10 >= -15; e10--) {
            const double tol = e10 >= -14 ? pow(10.0, e10) : 0.0; /* 0: flush the last row */
            int best = -1;
            for (size_t c = 0; c < NCFGS && tol > 0.0; c++) {
                const cres_t *R = &all[c];
                if (R->acc_flips || R->faults || R->agree < R->total)
                    continue;
                if (cfgs[c].rtol > 0 && cfgs[c].rtol != 1e-10)
                    continue;
                if (d.model != SW_MODEL_BARE &&
                    (!strcmp(cfgs[c].scheme, "euler") || !strcmp(cfgs[c].scheme, "heun")))
                    continue;
                if (!(R->err_theta <= 0.5 * tol))
                    continue;
                if (best < 0 || R->ns_sample < all[best].ns_sample)
                    best = (int)c;
            }
            /* timings on a shared machine are noisy: keep the default when it
             * meets the tolerance and is within 25 % of the cheapest */
            for (size_t c = 0; c < NCFGS && best >= 0; c++)
                if (!strcmp(cfgs[c].scheme, SW_DEFAULT_SCHEME) && cfgs[c].dt == SW_DEFAULT_DT &&
                    !all[c].acc_flips && !all[c].faults && all[c].agree == all[c].total &&
                    all[c].err_theta <= 0.5 * tol && all[c].ns_sample <= 1.25 * all[best].ns_sample)
                    best = (int)c;
            if (prev >= 0 && best != prev)
                printf("    {SW_MODEL_%s, %.0e, \"%s\", %g},\n",
                       d.model == SW_MODEL_FRAME     ? "FRAME"
                       : d.model == SW_MODEL_CUSHION ? "CUSHION"
                                                     : "BARE",
                       prev_tol, cfgs[prev].scheme, cfgs[prev].rtol > 0 ? 0.0 : cfgs[prev].dt);
            if (best < 0)
                break;
            prev = best;
            prev_tol = tol;
        }
        printf("```\n\n");
    }

    /* ---- an hour of road ---- */
    fprintf(stderr, "sw_bench: road log\n");
    bench_log_t log;
    if (bench_log_make(&log, road_s, RATE, 20240611ULL) != 0)
        return 1;
    printf("### %.0f s of road at 1 kHz (%zu samples, in memory)\n\n", road_s, log.n);
    printf(
        "Median of %d runs.  CPU time of the process; ns per sample and the "
        "real-time factor (log duration / time) from it.\n\n",
        runs);
    printf(
        "| model | setting | CPU (s) | wall (s) | ns per sample | real-time factor | steps | "
        "uplifts | impacts | max theta / alpha | overturned |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (size_t m = 0; m < NMODELS; m++) {
        const sw_scene_t sc = models[m].scene();
        sw_derived_t d;
        sw_scene_validate(&sc, &d, NULL, NULL, NULL);
        double base_wall = NAN, def_wall = NAN;
        for (size_t c = 0; c <= NCFGS + 1; c++) {
            /* the road settings, then the frame with its stuck phase stepped,
             * then the baseline */
            const int stepped = c == NCFGS;
            const int base = c == NCFGS + 1;
            bcfg_t C = {"rk4", 1e-3, 0, 1};
            if (c < NCFGS) {
                if (!cfgs[c].road)
                    continue;
                C = cfgs[c];
                if (models[m].cushion)
                    continue; /* replay targets: bare and frame */
            }
            if (stepped && d.model != SW_MODEL_FRAME)
                continue;
            if (base && !models[m].baseline)
                continue;
            double tw[64], tc[64];
            sw_summary_t s;
            for (int r = 0; r < runs; r++) {
                if (base) {
                    const double w0 = now(), t0 = cpu_now();
                    bench_baseline_run(&sc, &log, 1e-8, &s);
                    tc[r] = cpu_now() - t0;
                    tw[r] = now() - w0;
                } else {
                    tc[r] = run_road(&sc, &C, stepped, &log, &s, &tw[r]);
                }
            }
            const double wall = median(tw, runs), cpu = median(tc, runs);
            char lab[96];
            if (base)
                snprintf(lab, sizeof lab, "GSL driver baseline (rkf45, eps 1e-8)");
            else if (stepped)
                snprintf(lab, sizeof lab, "rk4 dt 0.001, stuck frame stepped");
            else
                cfg_label(&C, lab, sizeof lab);
            if (base)
                base_wall = cpu;
            if (!base && !stepped && !strcmp(C.scheme, "rk4") && C.dt == 1e-3)
                def_wall = cpu;
            printf("| %s | %s | %.3f | %.3f | %.1f | %.0f | %ld | %ld | %ld | %.4f | %s |\n",
                   models[m].name, lab, cpu, wall, 1e9 * cpu / log.n, road_s / cpu, s.steps,
                   s.uplifts, s.impacts, s.max_theta_ratio, s.overturned ? "yes" : "no");
            fflush(stdout);
        }
        if (isfinite(base_wall) && isfinite(def_wall))
            printf("| %s | **baseline / default** | | | **%.2f x** | | | | | | |\n", models[m].name,
                   base_wall / def_wall);
    }
    printf("\nPeak memory of this benchmark process (max RSS): %ld KiB.\n\n", max_rss_kib());
    bench_log_free(&log);
    return 0;
}

/* ---- CSV -------------------------------------------------------------- */

/* The road log; incident: the road at 0.3 of its level (a calm motorway:
 * 0.02 g rms, braking up to 0.05 g, bumps up to 0.2 g), ending in the hard
 * stop of the sample log (the incident an investigator gets the hour
 * before). */
static int cmd_gen_csv(double hours, unsigned long long seed, int incident)
{
    bench_road_t *r = bench_road_create(RATE, seed);
    if (!r)
        return 1;
    const long n = (long)(hours * 3600.0 * RATE) + 1;
    const double level = incident ? 0.3 : 1.0, t_stop = (n - 1) / RATE - BENCH_HARD_STOP_S;
    static char buf[1 << 16];
    size_t k = 0;
    k += (size_t)snprintf(buf, sizeof buf, "time_s,accel_ms2\n");
    for (long i = 0; i < n; i++) {
        if (k > sizeof buf - 64) {
            if (fwrite(buf, 1, k, stdout) != k)
                break;
            k = 0;
        }
        double a = level * bench_road_next(r);
        if (incident && i / RATE >= t_stop)
            a += bench_hard_stop(i / RATE - t_stop);
        k += (size_t)snprintf(buf + k, sizeof buf - k, "%.3f,%.5f\n", i / RATE, a);
    }
    fwrite(buf, 1, k, stdout);
    bench_road_destroy(r);
    return fflush(stdout) == 0 && !ferror(stdout) ? 0 : 1;
}

typedef struct {
    sw_engine_t *e;
    long bad;
} feed_t;

static int on_row(void *user, long line, double t, double a_g, double a_z)
{
    (void)line;
    feed_t *f = user;
    const int rc = sw_engine_push(f->e, t, a_g, a_z);
    return rc < 0;
}

static int cmd_replay_csv(const char *path, const char *model)
{
    const bmodel_t *bm = find_model(model);
    if (!bm)
        return 2;
    const int fd = strcmp(path, "-") ? open(path, O_RDONLY) : 0;
    if (fd < 0) {
        fprintf(stderr, "sw_bench: %s: %s\n", path, strerror(errno));
        return 3;
    }
    const sw_scene_t sc = bm->scene();
    const bcfg_t C = {SW_DEFAULT_SCHEME, 0, 0, 0};
    feed_t f = {engine(&sc, &C, 0, NULL), 0};
    sw_csv_opts_t co = {0};
    co.header = -1;
    int err = 0;
    char msg[256];
    sw_csv_t *csv = sw_csv_create(&co, on_row, NULL, &f, &err, msg, sizeof msg);
    if (!f.e || !csv)
        return 2;
    const double w0 = now(), t0 = cpu_now();
    static char buf[1 << 18];
    ssize_t got;
    while ((got = read(fd, buf, sizeof buf)) > 0) sw_csv_feed(csv, buf, (size_t)got);
    sw_csv_finish(csv);
    const double el = cpu_now() - t0, wall = now() - w0;
    sw_csv_counts_t cnt;
    sw_csv_counts(csv, &cnt);
    sw_summary_t s;
    sw_engine_summary(f.e, 0, &s);
    printf(
        "model %s rows %ld rejected %ld cpu %.3f s wall %.3f s (%.0f ns/row) uplifts %ld "
        "impacts %ld max_rss_kib %ld\n",
        bm->name, cnt.accepted, cnt.rejected, el, wall, 1e9 * el / (double)cnt.rows, s.uplifts,
        s.impacts, max_rss_kib());
    sw_csv_destroy(csv);
    sw_engine_destroy(f.e);
    if (fd)
        close(fd);
    return 0;
}

static const bmodel_t *find_model(const char *name)
{
    for (size_t m = 0; m < NMODELS; m++)
        if (!strcmp(models[m].name, name))
            return &models[m];
    fprintf(stderr, "sw_bench: no model '%s'\n", name);
    return NULL;
}

/* One workload, one setting: for profiling and quick checks. */
static int cmd_one(const char *what, const char *model, const bcfg_t *C, int stepped,
                   double seconds, int planes)
{
    const bmodel_t *bm = find_model(model);
    if (!bm)
        return 2;
    const sw_scene_t sc = bm->scene();
    if (!strcmp(what, "shocks")) {
        sw_summary_t s;
        long n = 1;
        const double el = run_shocks(&sc, planes, seconds, &s, &n);
        printf("shocks %s, %d plane%s: %.1f ns/sample, uplifts %ld steps/sample %.2f%s\n", model,
               planes, planes == 1 ? "" : "s", 1e9 * el / n, s.uplifts, (double)s.steps / n,
               s.overturned ? " OVERTURNED" : "");
        return 0;
    }
    if (!strcmp(what, "rock")) {
        long st = 0, sa = 1;
        const double el = run_rocking(&sc, C, seconds, &st, &sa);
        printf(
            "rock %s %s dt %g rtol %g: %.1f ns/sample %.1f ns/step (%.2f Msteps/s) steps/sample "
            "%.2f\n",
            model, C->scheme, C->dt, C->rtol, 1e9 * el / sa, 1e9 * el / st, 1e-6 * st / el,
            (double)st / sa);
        return 0;
    }
    bench_log_t log;
    if (bench_log_make(&log, seconds, RATE, 20240611ULL) != 0)
        return 1;
    if (!strcmp(what, "gen")) { /* the log alone, to subtract its cost */
        bench_log_free(&log);
        return 0;
    }
    sw_summary_t s;
    const double el = !strcmp(what, "baseline") ? (bench_baseline_run(&sc, &log, 1e-8, &s), 0.0)
                                                : run_road(&sc, C, stepped, &log, &s, NULL);
    printf(
        "road %s %s: %.3f s, %.1f ns/sample, steps %ld uplifts %ld impacts %ld max "
        "theta/alpha %.4f%s\n",
        model, C->scheme, el, 1e9 * el / log.n, s.steps, s.uplifts, s.impacts, s.max_theta_ratio,
        s.overturned ? " OVERTURNED" : "");
    bench_log_free(&log);
    return 0;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: sw_bench run [--quick] [--runs N] [--data DIR]\n"
            "       sw_bench gen-csv [--hours H] [--seed S] [--incident]\n"
            "       sw_bench replay-csv FILE|- [--model bare|frame]\n"
            "       sw_bench rock|road|baseline|gen [--model M] [--scheme S] [--dt DT] "
            "[--rtol R] [--stepped] [--seconds N]\n"
            "       sw_bench planes [--runs N] [--seconds N]\n"
            "       sw_bench shocks [--model M] [--planes 0|1|2] [--seconds N]\n");
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *cmd = argv[1];
    int quick = 0, runs = 5;
    double hours = 1.0;
    unsigned long long seed = 20240611ULL;
    const char *data = NULL, *model = "bare";
    bcfg_t one = {SW_DEFAULT_SCHEME, 0, 0, 0};
    int stepped = 0, incident = 0, planes = 1;
    double seconds = 200.0;
    static const struct option lo[] = {
        {"quick", no_argument, NULL, 'q'},
        {"runs", required_argument, NULL, 'r'},
        {"data", required_argument, NULL, 'd'},
        {"hours", required_argument, NULL, 'H'},
        {"seed", required_argument, NULL, 's'},
        {"model", required_argument, NULL, 'm'},
        {"scheme", required_argument, NULL, 'S'},
        {"dt", required_argument, NULL, 't'},
        {"rtol", required_argument, NULL, 'T'},
        {"stepped", no_argument, NULL, 'x'},
        {"seconds", required_argument, NULL, 'n'},
        {"incident", no_argument, NULL, 'i'},
        {"planes", required_argument, NULL, 'p'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    optind = 2;
    int ch;
    while ((ch = getopt_long(argc, argv, "", lo, NULL)) != -1) {
        switch (ch) {
            case 'q': quick = 1; break;
            case 'r': runs = atoi(optarg); break;
            case 'd': data = optarg; break;
            case 'H': hours = atof(optarg); break;
            case 's': seed = strtoull(optarg, NULL, 10); break;
            case 'm': model = optarg; break;
            case 'S': one.scheme = optarg; break;
            case 't': one.dt = atof(optarg); break;
            case 'T': one.rtol = atof(optarg); break;
            case 'x': stepped = 1; break;
            case 'n': seconds = atof(optarg); break;
            case 'i': incident = 1; break;
            case 'p': planes = atoi(optarg) == 2 ? 2 : atoi(optarg) == 0 ? 0 : 1; break;
            case 'h': usage(stdout); return 0;
            default: usage(stderr); return 2;
        }
    }
    if (runs < 1 || runs > 64)
        runs = 5;
    if (!strcmp(cmd, "run"))
        return cmd_run(quick, runs, data);
    if (!strcmp(cmd, "gen-csv"))
        return cmd_gen_csv(hours, seed, incident);
    if (!strcmp(cmd, "rock") || !strcmp(cmd, "road") || !strcmp(cmd, "baseline") ||
        !strcmp(cmd, "gen") || !strcmp(cmd, "shocks"))
        return cmd_one(cmd, model, &one, stepped, seconds, planes);
    if (!strcmp(cmd, "planes"))
        return cmd_planes(runs, seconds);
    if (!strcmp(cmd, "replay-csv") && optind < argc)
        return cmd_replay_csv(argv[optind], model);
    usage(stderr);
    return 2;
}
