/* SPDX-License-Identifier: GPL-3.0-or-later */
/* reserve_bench.c - what the reserve (reserve.h) costs along real drives,
 * and how much warning its alarms give compared with the margin's
 * (docs/accuracy-speed.md, "The reserve"; docs/alarms.md).
 *
 *   reserve_bench cost [--runs N] [--minutes M] [--model NAME] [--step S]
 *       each model along the road (M minutes of bench_road.c, default
 *       60) and the rocking drives (sample_logs, El Centro scaled): the
 *       engine replays the drive at its own rate, the state is taken
 *       every 0.1 s (10 Hz) and the reserve evaluated on it; CPU time of
 *       the evaluations alone, median of N runs (default 5);
 *   reserve_bench leadtime [--minutes M] [--workload drives|road]
 *       drives that end in overturn (the sample logs, synthetic braking
 *       and pothole sequences, El Centro scaled just past the scale that
 *       overturns), and the road (no overturn) for false alarms: when the
 *       margin-based and the reserve-based WARN first fire, for a range of
 *       reserve levels;
 *   reserve_bench accuracy
 *       the default reserve against an rk8pd reference on every state away
 *       from rest along the rocking drives;
 *   reserve_bench eval --model NAME --workload NAME [--minutes M]
 *       one pass of the evaluations, nothing printed per evaluation (for
 *       valgrind --tool=callgrind --toggle-collect=sw_reserve_eval).
 *
 * Models: the crate of sw_bench (2 m x 0.728 m, 1000 kg) on the bed, on
 * its frame, on a soft and on a stiff cushion.  Data files are found
 * under the source tree (SW_SOURCE_DIR) and the shared data directory
 * (SW_SHARED_DIR), both compiled in; a missing El Centro record skips its
 * rows. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>

#include "bench.h"

#define SNAP_DT 0.1 /* s, reserve evaluations: 10 Hz */
#define SETTLE 10.0 /* s of quiet input after a drive */
#define MAX_RUNS 25

/* ---- models -------------------------------------------------------------- */

static sw_scene_t crate(void)
{
    sw_scene_t sc;
    sw_scene_init(&sc);
    snprintf(sc.name, sizeof sc.name, "crate-A");
    sc.height = 2.0; /* m */
    sc.width = 0.728;
    sc.mass = 1000.0;
    return sc;
}

static sw_scene_t with_frame(sw_scene_t sc)
{
    sc.has_frame = 1;
    sc.frame_mass = 250.0;
    sc.frame_omega = 5.59;
    sc.frame_zeta = 0.1;
    sc.frame_k_given = sc.frame_c_given = SW_GIVEN_RATIO;
    return sc;
}

static sw_scene_t with_cushion(sw_scene_t sc, double omega_c, double zeta_c)
{
    sc.has_cushion = 1;
    sc.cushion_omega = omega_c;
    sc.cushion_zeta = zeta_c;
    sc.cushion_k_given = sc.cushion_c_given = SW_GIVEN_RATIO;
    return sc;
}

typedef struct {
    const char *name;
    sw_scene_t sc;
} model_t;

/* The soft cushion (that of sw_bench, omega_c = 44.7 rad/s) overturns the
 * crate on the road within minutes (the road's speeding up tips it
 * back), so the road is driven with a firmer one as well. */
#define NMODELS 5
static int make_models(model_t *m)
{
    m[0] = (model_t){"bare", crate()};
    m[1] = (model_t){"frame", with_frame(crate())};
    m[2] = (model_t){"cushion-soft", with_cushion(crate(), 44.7, 0.045)};
    m[3] = (model_t){"cushion-300", with_cushion(crate(), 300.0, 0.1)};
    m[4] = (model_t){"cushion-stiff", with_cushion(crate(), 1e4, 0.05)};
    return NMODELS;
}

/* ---- drives ---------------------------------------------------------------- */

typedef struct {
    char name[64];
    double *t, *a; /* s, m/s^2 */
    size_t n, cap;
} drive_t;

static int push(drive_t *d, double t, double a)
{
    if (d->n == d->cap) {
        const size_t cap = d->cap ? 2 * d->cap : 4096;
        double *nt = realloc(d->t, cap * sizeof *nt);
        if (!nt)
            return -1;
        d->t = nt;
        double *na = realloc(d->a, cap * sizeof *na);
        if (!na)
            return -1;
        d->a = na;
        d->cap = cap;
    }
    d->t[d->n] = t;
    d->a[d->n] = a;
    d->n++;
    return 0;
}

static void drive_free(drive_t *d)
{
    free(d->t);
    free(d->a);
    memset(d, 0, sizeof *d);
}

/* time (s), acceleration (m/s^2); a header line and '#' lines skipped */
static int load_csv(drive_t *d, const char *path, const char *name)
{
    memset(d, 0, sizeof *d);
    snprintf(d->name, sizeof d->name, "%s", name);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char line[256];
    while (fgets(line, sizeof line, f)) {
        char *end;
        const double t = strtod(line, &end);
        if (end == line || (*end != ',' && *end != ';'))
            continue;
        const double a = strtod(end + 1, NULL);
        if (push(d, t, a))
            break;
    }
    fclose(f);
    return d->n ? 0 : -1;
}

/* PEER AT2: 4 header lines, then 8F10.5 in g at 0.02 s */
static int load_at2(drive_t *d, const char *path, double scale)
{
    memset(d, 0, sizeof *d);
    snprintf(d->name, sizeof d->name, "elcentro x%.3g", scale);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char line[256];
    int ln = 0;
    size_t k = 0;
    while (fgets(line, sizeof line, f)) {
        if (++ln <= 4)
            continue;
        for (int i = 0; i < 8; i++) {
            char field[11];
            if (strlen(line) < (size_t)(10 * i + 10))
                break;
            memcpy(field, line + 10 * i, 10);
            field[10] = '\0';
            char *end;
            const double v = strtod(field, &end);
            if (end == field)
                continue;
            push(d, 0.02 * (double)k++, scale * v * SW_G0);
        }
    }
    fclose(f);
    return d->n ? 0 : -1;
}

static void road(drive_t *d, double minutes, unsigned long long seed)
{
    memset(d, 0, sizeof *d);
    snprintf(d->name, sizeof d->name, "road %g min", minutes);
    bench_road_t *r = bench_road_create(1000.0, seed);
    const size_t n = (size_t)(minutes * 60.0 * 1000.0);
    for (size_t i = 0; i < n && r; i++) push(d, (double)i / 1000.0, bench_road_next(r));
    bench_road_destroy(r);
}

/* Synthetic sequences at 1 kHz on a quiet road (vibration of the road
 * model with its events, seed 7, scaled down to 0.02 g rms): events of
 * growing level, in units of g tan(alpha) of the crate (L), the whole
 * drive later scaled until it just overturns the package. */
typedef enum { SYN_STOPS, SYN_BRAKE_POTHOLE, SYN_POTHOLES } syn_t;

static void synthetic(drive_t *d, syn_t kind)
{
    memset(d, 0, sizeof *d);
    static const char *names[] = {"stop-and-go", "braking+pothole", "pothole series"};
    snprintf(d->name, sizeof d->name, "%s", names[kind]);
    const double L = 9.81 * 0.364; /* m/s^2 */
    bench_road_t *r = bench_road_create(1000.0, 7);
    const double dur = 40.0;
    for (size_t i = 0; i < (size_t)(dur * 1000.0); i++) {
        const double t = (double)i / 1000.0;
        double a = 0.3 * (r ? bench_road_next(r) : 0.0); /* background */
        if (kind == SYN_STOPS) {
            /* braking every 6 s from 3 s: 0.5 s sin^2 onset, 1 s plateau,
             * 0.5 s release; levels 0.5, 0.6, ... L */
            const double tc = t - 3.0;
            const int k = (int)floor(tc / 6.0);
            const double u = tc - 6.0 * k;
            if (tc >= 0.0 && u < 2.0) {
                const double lev = (0.5 + 0.1 * k) * L;
                const double f = u < 0.5   ? sin(M_PI * u) * sin(M_PI * u)
                                 : u < 1.5 ? 1.0
                                           : sin(M_PI * (2.0 - u)) * sin(M_PI * (2.0 - u));
                a -= lev * f;
            }
        } else if (kind == SYN_BRAKE_POTHOLE) {
            /* braking at 0.6 L from 5 s (1 s onset) for 4 s, a pothole
             * (80 ms half-sine, 2 L, then 2 L the other way) every 1 s
             * during it, growing by 10 % each */
            if (t >= 5.0 && t < 11.0) {
                const double u = t - 5.0;
                const double f = u < 1.0   ? 0.5 - 0.5 * cos(M_PI * u)
                                 : u < 5.0 ? 1.0
                                           : 0.5 + 0.5 * cos(M_PI * (u - 5.0));
                a -= 0.6 * L * f;
                const int k = (int)floor(u - 1.5);
                const double v = u - 1.5 - k;
                if (u >= 1.5 && k < 4 && v < 0.16) {
                    const double amp = 2.0 * L * (1.0 + 0.1 * k);
                    a += (v < 0.08 ? -amp : amp) * sin(M_PI * fmod(v, 0.08) / 0.08);
                }
            }
        } else {
            /* potholes (60 ms half-sine pairs) every 1.5 s from 2 s,
             * growing from 1 L by 8 % each */
            const double tc = t - 2.0;
            const int k = (int)floor(tc / 1.5);
            const double v = tc - 1.5 * k;
            if (tc >= 0.0 && v < 0.12) {
                const double amp = L * pow(1.08, k);
                a += (v < 0.06 ? -amp : amp) * sin(M_PI * fmod(v, 0.06) / 0.06);
            }
        }
        push(d, t, a);
    }
    bench_road_destroy(r);
}

/* ---- recording a drive ------------------------------------------------------ */

typedef struct {
    double t, theta, margin;
    sw_state_t s;
} snap_t;

typedef struct {
    snap_t *v;
    size_t n, cap;
    double next; /* s, next snapshot */
    int over;
    double t_over, t_tip;                       /* s */
    sw_alarm_watch_t w;                         /* margin alarms at every sample */
    double mwarn_first, mwarn_last, mcrit_last; /* s, NAN if none (before the overturn) */
    long mwarns;
} rec_t;

static void rec_alarm(void *user, const sw_alarm_t *a)
{
    rec_t *R = user;
    if (R->over)
        return;
    if (a->kind == SW_ALARM_WARN) {
        if (isnan(R->mwarn_first))
            R->mwarn_first = a->t;
        R->mwarn_last = a->t;
        R->mwarns++;
    }
    if (a->kind == SW_ALARM_CRITICAL)
        R->mcrit_last = a->t;
}

static void rec_event(void *user, const sw_event_t *ev)
{
    rec_t *R = user;
    sw_alarm_on_event(&R->w, ev, rec_alarm, R);
    if (ev->kind == SW_EV_OVERTURN && !R->over) {
        R->over = 1;
        R->t_over = ev->t;
    }
    if (ev->kind == SW_EV_TIP && isnan(R->t_tip))
        R->t_tip = ev->t;
}

static void rec_state(void *user, const sw_output_t *o)
{
    rec_t *R = user;
    sw_alarm_on_output(&R->w, o, rec_alarm, R);
    if (o->t + 1e-9 < R->next)
        return;
    R->next += SNAP_DT;
    if (R->n == R->cap) {
        const size_t cap = R->cap ? 2 * R->cap : 1024;
        snap_t *nv = realloc(R->v, cap * sizeof *nv);
        if (!nv)
            return;
        R->v = nv;
        R->cap = cap;
    }
    R->v[R->n++] = (snap_t){o->t, o->state.theta, o->margin, o->state};
}

/* Replay d (acceleration times scale) through the default engine, then
 * SETTLE s of quiet input; states at 10 Hz, margin alarms, overturn. */
static int record(const sw_scene_t *sc, const drive_t *d, double scale, rec_t *R)
{
    memset(R, 0, sizeof *R);
    R->t_over = R->t_tip = R->mwarn_first = R->mwarn_last = R->mcrit_last = NAN;
    R->next = d->t[0];
    sw_alarm_init(&R->w, 0, sc->warn_margin, sc->critical_margin, -1.0);
    sw_engine_opts_t o = {0};
    o.on_event = rec_event;
    o.on_state = rec_state;
    o.user = R;
    int err;
    char msg[256];
    sw_engine_t *e = sw_engine_create(sc, 1, &o, &err, msg, sizeof msg);
    if (!e) {
        fprintf(stderr, "reserve_bench: engine: %s\n", msg);
        return -1;
    }
    for (size_t i = 0; i < d->n; i++) sw_engine_push(e, d->t[i], scale * d->a[i], 0.0);
    sw_engine_finish(e, SETTLE);
    sw_engine_destroy(e);
    return 0;
}

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double mono_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
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

/* ---- cost -------------------------------------------------------------------- */

typedef struct {
    double cpu_s;  /* median CPU time of all evaluations */
    double max_ms; /* slowest single evaluation (wall, first run) */
    long evals, cached, trials;
    long live;          /* evaluations of states not overturned (an overturned one is free) */
    double min_reserve; /* g */
} cost_t;

static int eval_all(sw_reserve_t *r, const rec_t *R, double *res, cost_t *c, int timed_each)
{
    sw_reserve_result_t out;
    for (size_t i = 0; i < R->n; i++) {
        const double w0 = timed_each ? mono_now() : 0.0;
        if (sw_reserve_eval(r, &R->v[i].s, &out) < 0)
            return -1;
        if (timed_each) {
            const double ms = 1e3 * (mono_now() - w0);
            if (ms > c->max_ms)
                c->max_ms = ms;
            c->cached += out.cached;
            c->trials += out.trials;
            c->live += R->v[i].s.phase != SW_PHASE_OVERTURNED;
            if (out.reserve_g < c->min_reserve)
                c->min_reserve = out.reserve_g;
        }
        if (res)
            res[i] = out.reserve_g;
    }
    return 0;
}

static double g_step; /* --step: the reserve's scan step (0 = its default) */

static int cost_of(const sw_scene_t *sc, const rec_t *R, int runs, cost_t *c)
{
    int err;
    char msg[256];
    sw_reserve_opts_t o;
    memset(&o, 0, sizeof o);
    o.step = g_step;
    o.max_run_steps = 1e9; /* measure the stiff cushion too, which the default refuses */
    sw_reserve_t *r = sw_reserve_create(sc, &o, &err, msg, sizeof msg);
    if (!r) {
        fprintf(stderr, "reserve_bench: reserve: %s\n", msg);
        return -1;
    }
    memset(c, 0, sizeof *c);
    c->evals = (long)R->n;
    c->min_reserve = INFINITY;
    eval_all(r, R, NULL, c, 1); /* warm-up run, also per-evaluation figures */
    double t[MAX_RUNS];
    for (int k = 0; k < runs; k++) {
        const double t0 = cpu_now();
        eval_all(r, R, NULL, c, 0);
        t[k] = cpu_now() - t0;
    }
    c->cpu_s = median(t, runs);
    sw_reserve_destroy(r);
    return 0;
}

static int data_path(char *buf, size_t n, const char *dir, const char *file)
{
    return snprintf(buf, n, "%s/%s", dir, file) < (int)n ? 0 : -1;
}

/* The rocking drives: the two sample logs, El Centro x1.5 (peak 0.48 g). */
static int rocking_drives(drive_t *d)
{
    char p[1024];
    int n = 0;
    data_path(p, sizeof p, SW_SOURCE_DIR, "sample_logs/braking-pothole.csv");
    if (!load_csv(&d[n], p, "braking-pothole.csv"))
        n++;
    data_path(p, sizeof p, SW_SOURCE_DIR, "sample_logs/hard-stop-overturn.csv");
    if (!load_csv(&d[n], p, "hard-stop-overturn.csv"))
        n++;
    data_path(p, sizeof p, SW_SHARED_DIR, "data/elcentro-1940-ns.AT2");
    if (!load_at2(&d[n], p, 1.5))
        n++;
    return n;
}

/* Per evaluation over the states not overturned: evaluating an overturned
 * package costs nothing, and a drive that ends in overturn would
 * otherwise look cheaper the earlier it ends. */
static void cost_row(const char *model, const char *drive, const rec_t *R, const cost_t *c)
{
    const double per = c->cpu_s / (double)(c->live ? c->live : 1); /* s per evaluation */
    printf("| %s | %s | %ld | %.0f%% | %.0f | %.3f | %.1f | %.2f%% | %.3f |\n", model, drive,
           c->live, 100.0 * (double)c->cached / (double)(c->live ? c->live : 1),
           (double)c->trials / (double)(c->live ? c->live : 1), 1e3 * per, c->max_ms,
           100.0 * per * 10.0 * 10.0, c->min_reserve);
    (void)R;
    fflush(stdout);
}

static int cmd_cost(int runs, double minutes, const char *only)
{
    model_t m[NMODELS];
    const int nm = make_models(m);
    drive_t dr[4];
    const int nd = rocking_drives(dr);
    printf("<!-- reserve_bench cost --runs %d --minutes %g%s%s -->\n\n", runs, minutes,
           only ? " --model " : "", only ? only : "");
    if (g_step > 0.0)
        printf("Scan step %g (the default is 0.02).\n\n", g_step);
    printf(
        "Over the evaluations (10 Hz) of states not overturned; CPU time of the "
        "evaluations alone, median of %d runs (3 for cushion-300, 1 for cushion-stiff); "
        "\"one core\": ten such packages evaluated at 10 Hz.\n\n"
        "| model | drive | evaluations | at rest (cached) | runs per evaluation | "
        "CPU ms per evaluation | slowest (ms, wall) | one core, 10 packages at 10 Hz | "
        "min reserve (g) |\n|---|---|---|---|---|---|---|---|---|\n",
        runs);
    for (int i = 0; i < nm; i++) {
        if (only && strcmp(only, m[i].name))
            continue;
        const int stiff = !strcmp(m[i].name, "cushion-stiff");
        const int soft = !strcmp(m[i].name, "cushion-soft");
        const int firm = !strcmp(m[i].name, "cushion-300");
        drive_t rd;
        /* the stiffer cushions cost too much for an hour of road per run */
        road(&rd, stiff ? fmin(minutes, 1.0) : firm ? fmin(minutes, 10.0) : minutes, 1);
        for (int k = soft ? 0 : -1; k < nd; k++) {
            const drive_t *d = k < 0 ? &rd : &dr[k];
            rec_t R;
            if (record(&m[i].sc, d, 1.0, &R))
                return 1;
            cost_t c;
            const int nr = stiff ? 1 : firm ? (runs < 3 ? runs : 3) : runs;
            if (cost_of(&m[i].sc, &R, nr, &c) == 0)
                cost_row(m[i].name, d->name, &R, &c);
            free(R.v);
        }
        drive_free(&rd);
    }
    for (int k = 0; k < nd; k++) drive_free(&dr[k]);
    return 0;
}

/* ---- lead time ------------------------------------------------------------- */

#define NLEV 5
static const double warn_levels[NLEV] = {0.1, 0.15, 0.2, 0.25, 0.3}; /* g */

typedef struct {
    double first, last; /* s, first WARN and the last one raised before the end */
    long raised;
} warn_t;

static void lev_alarm(void *user, const sw_alarm_t *a)
{
    warn_t *w = user;
    if (a->kind != SW_ALARM_RESERVE_WARN)
        return;
    if (isnan(w->first))
        w->first = a->t;
    w->last = a->t;
    w->raised++;
}

/* Reserve WARN at warn_g (critical at half of it, hysteresis hyst_g g, < 0
 * the default) on the 10 Hz series, before t_end (s). */
static warn_t reserve_warns_h(const rec_t *R, const double *res, double warn_g, double t_end,
                              double hyst_g)
{
    warn_t w = {NAN, NAN, 0};
    sw_alarm_watch_t aw;
    sw_alarm_init(&aw, 0, 0.5, 0.2, -1.0);
    sw_alarm_set_reserve(&aw, warn_g, 0.5 * warn_g, hyst_g);
    for (size_t i = 0; i < R->n && R->v[i].t < t_end; i++)
        sw_alarm_on_reserve(&aw, R->v[i].t, R->v[i].theta, R->v[i].margin, res[i], lev_alarm, &w);
    return w;
}

static warn_t reserve_warns(const rec_t *R, const double *res, double warn_g, double t_end)
{
    return reserve_warns_h(R, res, warn_g, t_end, -1.0);
}

/* "first / last" lead times (s) before t_over, "-" if no alarm */
static void lead_cell(double t_over, double first, double last)
{
    if (isnan(first))
        printf(" - |");
    else if (first == last)
        printf(" %.2f |", t_over - first);
    else
        printf(" %.2f / %.2f |", t_over - first, t_over - last);
}

/* The smallest scale of d that overturns the package (sw_safety_factor). */
static double overturn_scale(const sw_scene_t *sc, const drive_t *d)
{
    sw_log_t log = {.t = d->t, .a_g = d->a, .n = d->n};
    sw_run_opts_t ro = {0};
    ro.settle = SETTLE;
    sw_search_opts_t so = {0};
    so.step = 0.02;
    so.tol = 1e-3;
    sw_safety_t s;
    char msg[256];
    if (sw_safety_factor(sc, &log, &ro, &so, &s, msg, sizeof msg) < 0 || !s.found)
        return NAN;
    return s.factor;
}

/* One drive for the lead-time tables: the overturn row, or a near-miss
 * row (into *miss, printed later) when it survives. */
static int lead_drive(const model_t *m, const drive_t *d, double scale, sw_reserve_t *r, char *miss,
                      size_t misslen)
{
    rec_t R;
    if (record(&m->sc, d, scale, &R))
        return -1;
    double *res = malloc(R.n * sizeof *res);
    cost_t c = {0};
    c.min_reserve = INFINITY;
    eval_all(r, &R, res, &c, 1);
    double min_margin = INFINITY;
    for (size_t i = 0; i < R.n; i++) min_margin = fmin(min_margin, R.v[i].margin);
    if (!R.over) {
        size_t n = strlen(miss);
        n += (size_t)snprintf(miss + n, misslen - n, "| %s | %s x%.3g | %.3f | %s |", m->name,
                              d->name, scale, min_margin, isnan(R.mwarn_first) ? "no" : "yes");
        for (int k = 0; k < NLEV && n < misslen; k++)
            n += (size_t)snprintf(
                miss + n, misslen - n, " %s |",
                reserve_warns(&R, res, warn_levels[k], INFINITY).raised ? "yes" : "no");
        if (n < misslen)
            snprintf(miss + n, misslen - n, " %.3f |\n", c.min_reserve);
    } else {
        printf("| %s | %s x%.3g | %.2f |", m->name, d->name, scale, R.t_over);
        lead_cell(R.t_over, R.t_tip, R.t_tip);
        lead_cell(R.t_over, R.mwarn_first, R.mwarn_last);
        lead_cell(R.t_over, R.mcrit_last, R.mcrit_last);
        for (int k = 0; k < NLEV; k++) {
            const warn_t w = reserve_warns(&R, res, warn_levels[k], R.t_over);
            lead_cell(R.t_over, w.first, w.last);
        }
        /* the reserve 2 s and 1 s before the overturn */
        double r2 = NAN, r1 = NAN;
        for (size_t i = 0; i < R.n; i++) {
            if (R.v[i].t <= R.t_over - 2.0)
                r2 = res[i];
            if (R.v[i].t <= R.t_over - 1.0)
                r1 = res[i];
        }
        printf(" %.3f | %.3f |\n", r2, r1);
        fflush(stdout);
    }
    free(res);
    free(R.v);
    return 0;
}

static int cmd_leadtime(double minutes, const char *part)
{
    const int drives = !part || strcmp(part, "road"), roads = !part || strcmp(part, "drives");
    model_t m[NMODELS];
    make_models(m);
    drive_t dr[8];
    int nd = rocking_drives(dr);
    const int elc = nd == 3; /* El Centro found: scaled per model below, from x1 */
    if (elc) {
        char p[1024];
        drive_free(&dr[2]);
        data_path(p, sizeof p, SW_SHARED_DIR, "data/elcentro-1940-ns.AT2");
        load_at2(&dr[2], p, 1.0);
        snprintf(dr[2].name, sizeof dr[2].name, "elcentro");
    }
    synthetic(&dr[nd++], SYN_STOPS);
    synthetic(&dr[nd++], SYN_BRAKE_POTHOLE);
    synthetic(&dr[nd++], SYN_POTHOLES);
    static char miss[16384];
    miss[0] = '\0';
    printf("<!-- reserve_bench leadtime --minutes %g -->\n\n", minutes);
    printf(
        "Drives that end in overturn: seconds from the first / the last WARN before "
        "the overturn to the overturn (one number when they coincide; \"-\": none).  "
        "Reserve levels: WARN at the level, CRITICAL at half of it, hysteresis "
        "%.2f g; the reserve is evaluated at 10 Hz, the margin at every sample.\n\n"
        "| model | drive | overturn (s) | tip (theta = alpha) | margin WARN (0.5) | "
        "margin CRITICAL (0.2) |",
        SW_ALARM_RESERVE_HYSTERESIS_G);
    for (int k = 0; k < NLEV; k++) printf(" reserve WARN %.2f g |", warn_levels[k]);
    printf(" reserve 2 s before (g) | 1 s before (g) |\n|---|---|---|---|---|---|");
    for (int k = 0; k < NLEV; k++) printf("---|");
    printf("---|---|\n");
    for (int i = 0; i < 3 && drives; i++) { /* bare, frame, soft cushion: stiff ones take hours */
        int err;
        char msg[256];
        sw_reserve_t *r = sw_reserve_create(&m[i].sc, NULL, &err, msg, sizeof msg);
        if (!r)
            return 1;
        for (int k = 0; k < nd; k++) {
            const int scaled = (elc && k == 2) || k >= (elc ? 3 : 2);
            if (!scaled) {
                lead_drive(&m[i], &dr[k], 1.0, r, miss, sizeof miss);
                continue;
            }
            /* just past the smallest overturning scale (the hardest case
             * to warn of), 1.2 times it (a clear overturn), and 0.95 times
             * it (a near miss) */
            const double f = overturn_scale(&m[i].sc, &dr[k]);
            if (!isfinite(f)) {
                fprintf(stderr, "reserve_bench: %s, %s: no overturning scale up to 20x\n",
                        m[i].name, dr[k].name);
                continue;
            }
            lead_drive(&m[i], &dr[k], f * 1.001, r, miss, sizeof miss);
            lead_drive(&m[i], &dr[k], f * 1.2, r, miss, sizeof miss);
            lead_drive(&m[i], &dr[k], f * 0.95, r, miss, sizeof miss);
        }
        sw_reserve_destroy(r);
    }

    if (drives)
        printf(
            "\nDrives that come close and survive: do the alarms fire?\n\n"
            "| model | drive | min margin | margin WARN (0.5) |");
    for (int k = 0; k < NLEV && drives; k++) printf(" reserve WARN %.2f g |", warn_levels[k]);
    if (drives) {
        printf(" min reserve (g) |\n|---|---|---|---|");
        for (int k = 0; k < NLEV; k++) printf("---|");
        printf("---|\n%s", miss);
    }
    if (!roads)
        goto done;

    /* false alarms on the road */
    printf(
        "\nAlarms per hour on the road (%g minutes of bench_road.c; none of these "
        "overturns); reserve WARN counts with hysteresis %.2f g, and 0.05 g after the "
        "slash:\n\n| model | margin WARN (0.5) |",
        minutes, SW_ALARM_RESERVE_HYSTERESIS_G);
    for (int k = 0; k < NLEV; k++) printf(" reserve WARN %.2f g |", warn_levels[k]);
    printf(" min margin | min reserve (g) | reserve at rest (g) |\n|---|---|");
    for (int k = 0; k < NLEV; k++) printf("---|");
    printf("---|---|---|\n");
    fflush(stdout);
    drive_t rd;
    road(&rd, minutes, 1);
    static const int road_models[] = {0, 1, 3}; /* the soft cushion overturns there */
    for (int ii = 0; ii < 3; ii++) {
        const int i = road_models[ii];
        rec_t R;
        if (record(&m[i].sc, &rd, 1.0, &R))
            return 1;
        int err;
        char msg[256];
        sw_reserve_t *r = sw_reserve_create(&m[i].sc, NULL, &err, msg, sizeof msg);
        double *res = malloc(R.n * sizeof *res);
        cost_t c = {0};
        c.min_reserve = INFINITY;
        eval_all(r, &R, res, &c, 1);
        const double hours = minutes / 60.0;
        printf("| %s | %.1f |", m[i].name, (double)R.mwarns / hours);
        for (int k = 0; k < NLEV; k++)
            printf(" %.1f / %.1f |",
                   (double)reserve_warns(&R, res, warn_levels[k], INFINITY).raised / hours,
                   (double)reserve_warns_h(&R, res, warn_levels[k], INFINITY, 0.05).raised / hours);
        sw_reserve_result_t rest;
        sw_reserve_rest(r, &rest);
        double min_margin = INFINITY;
        for (size_t j = 0; j < R.n; j++) min_margin = fmin(min_margin, R.v[j].margin);
        printf(" %.3f | %.3f | %.3f |\n", min_margin, c.min_reserve, rest.reserve_g);
        fflush(stdout);
        free(res);
        free(R.v);
        sw_reserve_destroy(r);
    }
    drive_free(&rd);
done:
    for (int k = 0; k < nd; k++) drive_free(&dr[k]);
    return 0;
}

/* ---- accuracy ------------------------------------------------------------------ */

/* The default reserve against a reference (rk8pd at rtol 1e-10, 400
 * steps per shortest period at most, the engine's rest threshold 1e-9) on
 * every state away from rest along the rocking drives. */
static int cmd_accuracy(void)
{
    model_t m[NMODELS];
    make_models(m);
    drive_t dr[4];
    const int nd = rocking_drives(dr);
    printf(
        "<!-- reserve_bench accuracy -->\n\n| model | states (away from rest) | identical | "
        "within 1 %% | worst difference | CPU ms per evaluation, default / reference |\n"
        "|---|---|---|---|---|---|\n");
    for (int i = 0; i < 4; i++) { /* bare, frame, the soft and the 300 rad/s cushion */
        int err;
        char msg[256];
        sw_reserve_opts_t ro;
        memset(&ro, 0, sizeof ro);
        ro.no_cache = 1;
        sw_reserve_t *def = sw_reserve_create(&m[i].sc, &ro, &err, msg, sizeof msg);
        sw_derived_t d;
        sw_scene_validate(&m[i].sc, &d, NULL, NULL, NULL);
        double per = fmin(2.0 * m[i].sc.design_pulse[0], 2.0 * M_PI / d.p); /* s */
        if (d.omega_max > 0.0)
            per = fmin(per, 2.0 * M_PI / d.omega_max);
        ro.run.engine.scheme = "rk8pd";
        ro.run.engine.rtol = 1e-10;
        ro.run.engine.atol = 1e-12;
        ro.run.engine.dt = per / 400.0;
        ro.run.engine.rest_eps = 1e-9;
        ro.max_run_steps = 1e8; /* the reference may take its time */
        sw_reserve_t *ref = sw_reserve_create(&m[i].sc, &ro, &err, msg, sizeof msg);
        if (!def || !ref)
            return 1;
        long n = 0, same = 0, close = 0;
        double worst = 0.0, t_def = 0.0, t_ref = 0.0;
        for (int k = 0; k < nd; k++) {
            rec_t R;
            if (record(&m[i].sc, &dr[k], 1.0, &R))
                return 1;
            for (size_t j = 0; j < R.n; j++) {
                if (sw_reserve_is_rest(def, &R.v[j].s) || R.v[j].s.phase == SW_PHASE_OVERTURNED)
                    continue;
                sw_reserve_result_t a, b;
                double t0 = cpu_now();
                sw_reserve_eval(def, &R.v[j].s, &a);
                const double t1 = cpu_now();
                sw_reserve_eval(ref, &R.v[j].s, &b);
                t_ref += cpu_now() - t1;
                t_def += t1 - t0;
                n++;
                const double diff =
                    b.reserve_g > 0.0 ? fabs(a.reserve_g / b.reserve_g - 1.0) : fabs(a.reserve_g);
                same += a.reserve_g == b.reserve_g;
                close += diff <= 0.01;
                worst = fmax(worst, diff);
            }
            free(R.v);
        }
        printf("| %s | %ld | %ld | %ld | %.2f %% | %.2f / %.2f |\n", m[i].name, n, same, close,
               100.0 * worst, n ? 1e3 * t_def / (double)n : 0.0, n ? 1e3 * t_ref / (double)n : 0.0);
        fflush(stdout);
        sw_reserve_destroy(def);
        sw_reserve_destroy(ref);
    }
    for (int k = 0; k < nd; k++) drive_free(&dr[k]);
    return 0;
}

/* ---- one pass (profiling) ----------------------------------------------------- */

static int cmd_eval(const char *model, const char *workload, double minutes)
{
    model_t m[NMODELS];
    const int nm = make_models(m);
    const model_t *mm = NULL;
    for (int i = 0; i < nm; i++)
        if (model && !strcmp(model, m[i].name))
            mm = &m[i];
    if (!mm) {
        fprintf(stderr,
                "reserve_bench: --model bare|frame|cushion-soft|cushion-300|cushion-stiff\n");
        return 2;
    }
    drive_t d;
    char p[1024];
    if (!workload || !strcmp(workload, "road")) {
        road(&d, minutes, 1);
    } else {
        data_path(p, sizeof p, SW_SOURCE_DIR, "sample_logs/");
        strncat(p, workload, sizeof p - strlen(p) - 1);
        if (load_csv(&d, p, workload)) {
            fprintf(stderr, "reserve_bench: cannot read %s\n", p);
            return 2;
        }
    }
    rec_t R;
    if (record(&mm->sc, &d, 1.0, &R))
        return 1;
    int err;
    char msg[256];
    sw_reserve_t *r = sw_reserve_create(&mm->sc, NULL, &err, msg, sizeof msg);
    if (!r)
        return 1;
    cost_t c = {0};
    c.min_reserve = INFINITY;
    eval_all(r, &R, NULL, &c, 1);
    printf("%s %s: %zu evaluations, %ld of states not overturned, %ld cached, %ld runs\n", mm->name,
           d.name, R.n, c.live, c.cached, c.trials);
    sw_reserve_destroy(r);
    free(R.v);
    drive_free(&d);
    return 0;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    int runs = 5;
    double minutes = 60.0;
    const char *model = NULL, *workload = NULL;
    static const struct option lo[] = {
        {"runs", required_argument, NULL, 'r'},  {"minutes", required_argument, NULL, 'm'},
        {"model", required_argument, NULL, 'M'}, {"workload", required_argument, NULL, 'w'},
        {"step", required_argument, NULL, 's'},  {NULL, 0, NULL, 0}};
    if (argc < 2) {
        fprintf(stderr, "usage: reserve_bench cost|leadtime|accuracy|eval [options]\n");
        return 2;
    }
    const char *cmd = argv[1];
    optind = 2;
    int ch;
    while ((ch = getopt_long(argc, argv, "", lo, NULL)) != -1) {
        switch (ch) {
            case 'r': runs = atoi(optarg); break;
            case 'm': minutes = atof(optarg); break;
            case 'M': model = optarg; break;
            case 'w': workload = optarg; break;
            case 's': g_step = atof(optarg); break;
            default: return 2;
        }
    }
    if (runs < 1 || runs > MAX_RUNS || !(minutes > 0.0)) {
        fprintf(stderr, "reserve_bench: --runs 1..%d, --minutes > 0\n", MAX_RUNS);
        return 2;
    }
    if (!strcmp(cmd, "cost"))
        return cmd_cost(runs, minutes, model);
    if (!strcmp(cmd, "leadtime"))
        return cmd_leadtime(minutes, workload);
    if (!strcmp(cmd, "eval"))
        return cmd_eval(model, workload, minutes);
    if (!strcmp(cmd, "accuracy"))
        return cmd_accuracy();
    fprintf(stderr, "reserve_bench: unknown command %s\n", cmd);
    return 2;
}
