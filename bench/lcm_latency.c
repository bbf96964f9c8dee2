/* lcm_latency.c - end-to-end latency of a running `swaywatch monitor`:
 * publishes accel_t samples at a fixed rate and times each state_t the
 * monitor publishes back, from just before the publish of the sample to the
 * handler that receives the state it caused (matched by utime).
 *
 *   lcm_latency URL RATE_HZ SECONDS PACKAGES [MONITOR_PID]
 *
 * Two threads: one publishes, paced by clock_nanosleep() on absolute times,
 * the other handles the states as they come (LCM calls are thread-safe), so
 * neither waits for the other and nothing spins.  Prints one
 * line: rate, samples sent, states expected and received, latency median,
 * p99 and max (us), and, given the monitor's pid, its CPU use over the run
 * from /proc (user + system time / wall time). */
#include <gsl/gsl_errno.h>
#include <lcm/lcm.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "swaywatch_accel_t.h"
#include "swaywatch_state_t.h"

#define UTIME0 1700000000000000LL

typedef struct {
    lcm_t *lcm;
    double rate;           /* Hz */
    long n;                /* samples to send */
    _Atomic int64_t *sent; /* ns (monotonic) at publish, per sample; 0 = not yet */
    atomic_int done;       /* the publisher has finished */
    double send_secs;      /* s the publisher took: the rate achieved is n / send_secs */
    double *lat;           /* s, per state received */
    long nlat, cap;
    int64_t period_us;
    long late_or_foreign;
} bench_t;

static int64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static double mono_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void on_state(const lcm_recv_buf_t *rb, const char *ch, const swaywatch_state_t *m,
                     void *user)
{
    (void)rb;
    (void)ch;
    bench_t *b = user;
    const int64_t now = mono_ns();
    const int64_t k = (m->utime - UTIME0) / b->period_us;
    const int64_t sent = k >= 0 && k < b->n ? atomic_load(&b->sent[k]) : 0;
    if (sent == 0 || b->nlat >= b->cap) {
        b->late_or_foreign++;
        return;
    }
    b->lat[b->nlat++] = 1e-9 * (double)(now - sent);
}

/* The publisher: sample k at t0 + k / rate. */
static void *publisher(void *arg)
{
    bench_t *b = arg;
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    const double start = mono_now();
    for (long k = 0; k < b->n; k++) {
        const int64_t due = (int64_t)t0.tv_sec * 1000000000 + t0.tv_nsec +
                            (int64_t)llround(1e9 * (double)k / b->rate);
        struct timespec ts = {(time_t)(due / 1000000000), (long)(due % 1000000000)};
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) != 0) {
        }
        /* a braking sine that keeps the crate rocking: 5 m/s^2, 0.5 Hz */
        const double t = (double)k / b->rate;
        swaywatch_accel_t s = {.utime = UTIME0 + k * b->period_us,
                               .seq = k,
                               .ax = -5.0 * sin(M_PI * t),
                               .ay = 0.0,
                               .az = 0.0};
        atomic_store(&b->sent[k], mono_ns());
        swaywatch_accel_t_publish(b->lcm, "ACCEL", &s);
    }
    b->send_secs = mono_now() - start;
    atomic_store(&b->done, 1); /* also hands send_secs to the main thread */
    return NULL;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* user + system CPU seconds of a process, from /proc/PID/stat. */
static double cpu_seconds(long pid)
{
    char path[64], buf[1024];
    snprintf(path, sizeof path, "/proc/%ld/stat", pid);
    FILE *f = fopen(path, "r");
    if (!f)
        return NAN;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    char *p = strrchr(buf, ')'); /* the command name may hold spaces */
    if (!p)
        return NAN;
    unsigned long ut = 0, st = 0;
    /* fields 3.. after the name; utime and stime are fields 14 and 15 */
    if (sscanf(p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %lu %lu", &ut, &st) != 2)
        return NAN;
    return (double)(ut + st) / (double)sysconf(_SC_CLK_TCK);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc < 5) {
        fprintf(stderr, "usage: lcm_latency URL RATE_HZ SECONDS PACKAGES [MONITOR_PID]\n");
        return 2;
    }
    const char *url = argv[1];
    const double rate = atof(argv[2]), secs = atof(argv[3]);
    const long npkg = atol(argv[4]), pid = argc > 5 ? atol(argv[5]) : 0;
    if (!(rate > 0) || !(secs > 0) || npkg < 1)
        return 2;

    bench_t b;
    memset(&b, 0, sizeof b);
    const long n = (long)(rate * secs);
    b.rate = rate;
    b.n = n;
    b.period_us = (int64_t)llround(1e6 / rate);
    b.sent = calloc((size_t)n, sizeof *b.sent);
    b.cap = n * npkg;
    b.lat = calloc((size_t)b.cap, sizeof *b.lat);
    b.lcm = lcm_create(url);
    if (!b.sent || !b.lat || !b.lcm) {
        fprintf(stderr, "lcm_latency: cannot start (LCM URL %s)\n", url);
        return 1;
    }
    for (long k = 0; k < n; k++) atomic_init(&b.sent[k], 0);
    atomic_init(&b.done, 0);
    swaywatch_state_t_subscription_t *sub =
        swaywatch_state_t_subscribe(b.lcm, "SWAY_STATE", on_state, &b);
    swaywatch_state_t_subscription_set_queue_capacity(sub, 0);
    /* subscribed before the first sample: LCM has no handshake */
    nanosleep(&(struct timespec){0, 200000000L}, NULL);

    const double cpu0 = pid ? cpu_seconds(pid) : NAN;
    const double t0 = mono_now();
    pthread_t th;
    if (pthread_create(&th, NULL, publisher, &b) != 0)
        return 1;
    /* handle until the publisher is done and the stragglers are in */
    double end = INFINITY;
    while (mono_now() < end) {
        lcm_handle_timeout(b.lcm, 50);
        if (end == INFINITY && atomic_load(&b.done))
            end = mono_now() + 0.5;
    }
    pthread_join(th, NULL);
    const double wall = mono_now() - t0;
    const double cpu1 = pid ? cpu_seconds(pid) : NAN;

    qsort(b.lat, (size_t)b.nlat, sizeof *b.lat, cmp);
    const long expect = n * npkg;
    double med = b.nlat ? b.lat[b.nlat / 2] : NAN;
    double p99 = b.nlat ? b.lat[(long)(0.99 * (double)(b.nlat - 1))] : NAN;
    double mx = b.nlat ? b.lat[b.nlat - 1] : NAN;
    printf(
        "rate %.0f Hz (achieved %.0f), packages %ld: sent %ld, states %ld of %ld (lost %ld), "
        "latency median %.0f us, p99 %.0f us, max %.0f us",
        rate, (double)n / b.send_secs, npkg, n, b.nlat, expect, expect - b.nlat, med * 1e6,
        p99 * 1e6, mx * 1e6);
    if (pid)
        printf(", monitor CPU %.1f%%", 100.0 * (cpu1 - cpu0) / wall);
    printf("\n");

    swaywatch_state_t_unsubscribe(b.lcm, sub);
    lcm_destroy(b.lcm);
    free(b.sent);
    free(b.lat);
    return expect == b.nlat ? 0 : 3;
}
