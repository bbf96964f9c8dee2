/* SPDX-License-Identifier: GPL-3.0-or-later */
/* bench_road.c - a synthetic hour of truck-bed acceleration at 1 kHz for
 * the benchmarks: what a shock logger on a lorry records on an ordinary
 * road, with events now and then that make a tall crate rock.
 *
 * - vibration: two resonances driven by white noise (body pitch near
 *   1.6 Hz, axle hop near 12 Hz), about 0.06 g rms together;
 * - braking (and speeding up): ramps of 1 s to a plateau of 1-4 s, up to
 *   0.17 g braking and 0.15 g speeding up, on average once a minute each;
 * - potholes and bumps: half-sine shocks of 20-80 ms, up to about 0.7 g,
 *   on average every 15 s.
 * Everything is drawn from one seeded generator (splitmix64), so the log is
 * the same on every machine and no file needs to be kept. */
#include <math.h>
#include <stdlib.h>

#include "bench.h"

#define G0 9.81

struct bench_road {
    double rate; /* Hz */
    unsigned long long s;
    double y1[2], y2[2]; /* AR(2) states of the two resonances */
    double c1[3], c2[3]; /* AR(2) coefficients: a1, a2, input gain */
    long i;              /* sample index */
    /* current manoeuvre: plateau level (m/s^2), times in samples */
    double man_level;
    long man_start, man_len, man_ramp;
    long next_man;
    /* current shock */
    double sh_amp;
    long sh_start, sh_len;
    long next_sh;
};

static double uni(bench_road_t *r) /* (0, 1) */
{
    unsigned long long z = (r->s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) / 9007199254740992.0;
}

static double gauss(bench_road_t *r)
{
    return sqrt(-2.0 * log(uni(r))) * cos(2.0 * M_PI * uni(r));
}

/* exponential waiting time with the given mean, in samples */
static long wait(bench_road_t *r, double mean_s)
{
    return 1 + (long)(-log(uni(r)) * mean_s * r->rate);
}

/* AR(2) resonance at f Hz with pole radius from damping ratio z; the gain
 * makes its stationary standard deviation sd (m/s^2). */
static void resonance(double c[3], double f, double z, double sd, double rate)
{
    const double w = 2.0 * M_PI * f / rate, rad = exp(-z * w);
    c[0] = 2.0 * rad * cos(w * sqrt(1.0 - z * z));
    c[1] = -rad * rad;
    /* variance of y_n = a1 y_{n-1} + a2 y_{n-2} + e_n for unit e */
    const double a1 = c[0], a2 = c[1];
    const double var = (1.0 - a2) / ((1.0 + a2) * ((1.0 - a2) * (1.0 - a2) - a1 * a1));
    c[2] = sd / sqrt(var);
}

bench_road_t *bench_road_create(double rate, unsigned long long seed)
{
    bench_road_t *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->rate = rate;
    r->s = seed;
    resonance(r->c1, 1.6, 0.15, 0.045 * G0, rate);
    resonance(r->c2, 12.0, 0.10, 0.040 * G0, rate);
    r->next_man = wait(r, 30.0);
    r->next_sh = wait(r, 15.0);
    r->man_len = r->sh_len = 0;
    return r;
}

double bench_road_next(bench_road_t *r)
{
    const long i = r->i++;
    double a = 0.0;
    for (int k = 0; k < 2; k++) {
        double *y = k ? r->y2 : r->y1;
        const double *c = k ? r->c2 : r->c1;
        const double yn = c[0] * y[0] + c[1] * y[1] + c[2] * gauss(r);
        y[1] = y[0];
        y[0] = yn;
        a += yn;
    }
    if (i == r->next_man) {
        const int brake = uni(r) < 0.5;
        r->man_level = brake ? -(0.05 + 0.12 * uni(r)) * G0 : (0.03 + 0.12 * uni(r)) * G0;
        r->man_start = i;
        r->man_ramp = (long)(1.0 * r->rate);
        r->man_len = (long)((1.0 + 3.0 * uni(r)) * r->rate) + 2 * r->man_ramp;
        r->next_man = i + r->man_len + wait(r, 30.0);
    }
    if (r->man_len > 0 && i < r->man_start + r->man_len) {
        const long k = i - r->man_start, e = r->man_start + r->man_len - i;
        const double f = k < r->man_ramp   ? (double)k / r->man_ramp
                         : e < r->man_ramp ? (double)e / r->man_ramp
                                           : 1.0;
        a += r->man_level * (0.5 - 0.5 * cos(M_PI * f));
    }
    if (i == r->next_sh) {
        r->sh_amp = (uni(r) < 0.5 ? -1.0 : 1.0) * (0.1 + 0.6 * pow(uni(r), 2.0)) * G0;
        r->sh_len = (long)((0.02 + 0.06 * uni(r)) * r->rate) + 1;
        r->sh_start = i;
        r->next_sh = i + r->sh_len + wait(r, 15.0);
    }
    if (r->sh_len > 0 && i < r->sh_start + r->sh_len)
        a += r->sh_amp * sin(M_PI * (double)(i - r->sh_start) / r->sh_len);
    return a;
}

void bench_road_destroy(bench_road_t *r)
{
    free(r);
}

int bench_log_make(bench_log_t *log, double seconds, double rate, unsigned long long seed)
{
    log->n = (size_t)(seconds * rate) + 1;
    log->rate = rate;
    log->t = malloc(log->n * sizeof *log->t);
    log->a = malloc(log->n * sizeof *log->a);
    bench_road_t *r = bench_road_create(rate, seed);
    if (!log->t || !log->a || !r) {
        bench_road_destroy(r);
        bench_log_free(log);
        return -1;
    }
    for (size_t i = 0; i < log->n; i++) {
        log->t[i] = (double)i / rate;
        log->a[i] = bench_road_next(r);
    }
    bench_road_destroy(r);
    return 0;
}

void bench_log_free(bench_log_t *log)
{
    free(log->t);
    free(log->a);
    log->t = log->a = NULL;
    log->n = 0;
}

/* The hard stop of sample_logs/hard-stop-overturn.csv without its
 * vibration (scripts/make_sample_logs.py): an emergency stop just below
 * the uplift threshold of the sample crate, then a collision-like shock
 * with structural ringing.  u: s from 2 s before the stop; m/s^2. */
double bench_hard_stop(double u)
{
    double a = 0.0;
    if (u >= 2.0 && u < 4.0) { /* plateau(t, 2.0, 0.4, 0.8, -3.0) */
        const double v = u - 2.0;
        a += v < 0.4   ? -3.0 * 0.5 * (1 - cos(M_PI * v / 0.4))
             : v < 1.2 ? -3.0
             : v < 1.6 ? -3.0 * 0.5 * (1 + cos(M_PI * (v - 1.2) / 0.4))
                       : 0.0;
    }
    if (u >= 3.0 && u <= 3.35)
        a += -18.0 * pow(sin(M_PI * (u - 3.0) / 0.35), 2.0);
    if (u >= 3.0 && u <= 3.3) { /* shock(t, 3.0, 0.3, 6.0, 12.0) */
        const double v = u - 3.0, decay = 3.0 / 0.3, first = exp(-decay * 0.25 / 12.0);
        const double taper = sin(M_PI * fmin(v / (0.25 / 12.0), 1.0) / 2.0);
        a += 6.0 / first * taper * exp(-decay * v) * sin(2.0 * M_PI * 12.0 * v);
    }
    return a;
}
