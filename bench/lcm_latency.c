/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lcm_latency.c - end-to-end latency of a running `swaywatch monitor`,
 * against an LCM echo in the same run: publishes accel_t samples at a fixed
 * rate and times each state_t the monitor publishes back (SWAY_STATE) and
 * each one an echo process publishes back (ECHO_STATE), from just before
 * the publish of the sample to the handler that receives the state it
 * caused (matched by utime).  Both receive the same multicast samples at
 * the same time; the echo decodes each sample and publishes one state_t per
 * package with no model, the way the monitor does (raw subscription,
 * poll() and lcm_handle(), the same queue), so the ratio of the two is
 * what the model and the monitor's checks add to LCM's own round trip on
 * this machine at this moment.
 *
 *   lcm_latency URL RATE_HZ SECONDS PACKAGES [MONITOR_PID [ECHO_PID]]
 *   lcm_latency echo URL PACKAGES          the echo, until SIGINT or SIGTERM
 *
 * Two threads: one publishes, paced by clock_nanosleep() on absolute times,
 * the other handles the states as they come (LCM calls are thread-safe), so
 * neither waits for the other and nothing spins.  Prints two lines, the
 * monitor's and the echo's: rate, samples sent, states expected and
 * received, latency median, p99 and max (us), and, given their pids, CPU
 * use over the run from /proc (user + system time / wall time); then the
 * ratios monitor / echo of the median and of the p99. */
#include <gsl/gsl_errno.h>
#include <lcm/lcm.h>
#include <math.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "swaywatch_accel_t.h"
#include "swaywatch_state_t.h"

#define UTIME0 1700000000000000LL

#define ECHO_CHANNEL "ECHO_STATE"
#define ACCEL_QUEUE 2000 /* as the monitor's accel subscription */
#define BATCH 256        /* as the monitor: messages per wake-up */

/* States received from one responder (the monitor or the echo). */
typedef struct {
    double *lat; /* s, per state received */
    long nlat, cap;
    long late_or_foreign;
} series_t;

typedef struct {
    lcm_t *lcm;
    double rate;           /* Hz */
    long n;                /* samples to send */
    _Atomic int64_t *sent; /* ns (monotonic) at publish, per sample; 0 = not yet */
    atomic_int done;       /* the publisher has finished */
    double send_secs;      /* s the publisher took: the rate achieved is n / send_secs */
    int64_t period_us;
    series_t mon, echo;
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
    bench_t *b = user;
    series_t *s = strcmp(ch, ECHO_CHANNEL) ? &b->mon : &b->echo;
    const int64_t now = mono_ns();
    const int64_t k = (m->utime - UTIME0) / b->period_us;
    const int64_t sent = k >= 0 && k < b->n ? atomic_load(&b->sent[k]) : 0;
    if (sent == 0 || s->nlat >= s->cap) {
        s->late_or_foreign++;
        return;
    }
    s->lat[s->nlat++] = 1e-9 * (double)(now - sent);
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

/* ---- the echo ---------------------------------------------------------- */

static volatile sig_atomic_t echo_stop;

static void on_echo_signal(int sig)
{
    (void)sig;
    echo_stop = 1;
}

typedef struct {
    lcm_t *lcm;
    long npkg;
    int64_t seq;
    unsigned char buf[512];
} echo_t;

/* A sample in, one state per package out, as the monitor publishes them
 * (decode, checks for a well-formed message, encode into a buffer made
 * once, lcm_publish) but with no model. */
static void on_accel(const lcm_recv_buf_t *rb, const char *ch, void *user)
{
    (void)ch;
    echo_t *e = user;
    swaywatch_accel_t a;
    if (rb->data_size > INT32_MAX ||
        swaywatch_accel_t_decode(rb->data, 0, (int)rb->data_size, &a) != (int)rb->data_size ||
        !isfinite(a.ax))
        return;
    for (long k = 0; k < e->npkg; k++) {
        swaywatch_state_t s;
        memset(&s, 0, sizeof s);
        s.utime = a.utime;
        s.seq = e->seq++;
        snprintf((char *)s.name, sizeof s.name, "echo-%ld", k);
        s.margin = 1.0;
        s.a_g = a.ax;
        int len = swaywatch_state_t_encode(e->buf, 0, (int)sizeof e->buf, &s);
        if (len > 0)
            lcm_publish(e->lcm, ECHO_CHANNEL, e->buf, (unsigned)len);
    }
}

static int run_echo(const char *url, long npkg)
{
    echo_t e = {.lcm = lcm_create(url), .npkg = npkg};
    if (!e.lcm || npkg < 1) {
        fprintf(stderr, "lcm_latency echo: cannot start (LCM URL %s)\n", url);
        return 1;
    }
    struct sigaction sa = {.sa_handler = on_echo_signal};
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    lcm_subscription_t *sub = lcm_subscribe(e.lcm, "ACCEL", on_accel, &e);
    lcm_subscription_set_queue_capacity(sub, ACCEL_QUEUE);
    const int fd = lcm_get_fileno(e.lcm);
    while (!echo_stop) {
        struct pollfd p = {.fd = fd, .events = POLLIN};
        if (poll(&p, 1, 200) > 0 && (p.revents & POLLIN)) {
            lcm_handle(e.lcm);
            for (int i = 1; i < BATCH && lcm_handle_timeout(e.lcm, 0) > 0; i++) {
            }
        }
    }
    lcm_unsubscribe(e.lcm, sub);
    lcm_destroy(e.lcm);
    return 0;
}

/* ---- the bench --------------------------------------------------------- */

typedef struct {
    double med, p99, max; /* s; NaN: none */
} stats_t;

static stats_t stats_of(series_t *s)
{
    stats_t r = {NAN, NAN, NAN};
    if (!s->nlat)
        return r;
    qsort(s->lat, (size_t)s->nlat, sizeof *s->lat, cmp);
    r.med = s->lat[s->nlat / 2];
    r.p99 = s->lat[(long)(0.99 * (double)(s->nlat - 1))];
    r.max = s->lat[s->nlat - 1];
    return r;
}

static void print_series(const char *who, const bench_t *b, long npkg, const series_t *s,
                         const stats_t *st, double cpu)
{
    const long expect = b->n * npkg;
    printf(
        "%s: rate %.0f Hz (achieved %.0f), packages %ld: sent %ld, states %ld of %ld "
        "(lost %ld), latency median %.0f us, p99 %.0f us, max %.0f us",
        who, b->rate, (double)b->n / b->send_secs, npkg, b->n, s->nlat, expect, expect - s->nlat,
        st->med * 1e6, st->p99 * 1e6, st->max * 1e6);
    if (isfinite(cpu))
        printf(", CPU %.1f%%", cpu);
    printf("\n");
}

static int series_alloc(series_t *s, long cap)
{
    s->cap = cap;
    s->lat = calloc((size_t)cap, sizeof *s->lat);
    return s->lat ? 0 : -1;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc == 4 && !strcmp(argv[1], "echo"))
        return run_echo(argv[2], atol(argv[3]));
    if (argc < 5) {
        fprintf(stderr,
                "usage: lcm_latency URL RATE_HZ SECONDS PACKAGES [MONITOR_PID [ECHO_PID]]\n"
                "       lcm_latency echo URL PACKAGES\n");
        return 2;
    }
    const char *url = argv[1];
    const double rate = atof(argv[2]), secs = atof(argv[3]);
    const long npkg = atol(argv[4]), pid = argc > 5 ? atol(argv[5]) : 0;
    const long echo_pid = argc > 6 ? atol(argv[6]) : 0;
    if (!(rate > 0) || !(secs > 0) || npkg < 1)
        return 2;

    bench_t b;
    memset(&b, 0, sizeof b);
    const long n = (long)(rate * secs);
    b.rate = rate;
    b.n = n;
    b.period_us = (int64_t)llround(1e6 / rate);
    b.sent = calloc((size_t)n, sizeof *b.sent);
    b.lcm = lcm_create(url);
    if (!b.sent || series_alloc(&b.mon, n * npkg) || series_alloc(&b.echo, n * npkg) || !b.lcm) {
        fprintf(stderr, "lcm_latency: cannot start (LCM URL %s)\n", url);
        return 1;
    }
    for (long k = 0; k < n; k++) atomic_init(&b.sent[k], 0);
    atomic_init(&b.done, 0);
    swaywatch_state_t_subscription_t *sub =
        swaywatch_state_t_subscribe(b.lcm, "SWAY_STATE|" ECHO_CHANNEL, on_state, &b);
    swaywatch_state_t_subscription_set_queue_capacity(sub, 0);
    /* subscribed before the first sample: LCM has no handshake */
    nanosleep(&(struct timespec){0, 200000000L}, NULL);

    const double cpu0 = pid ? cpu_seconds(pid) : NAN;
    const double ecpu0 = echo_pid ? cpu_seconds(echo_pid) : NAN;
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
    const double cpu = pid ? 100.0 * (cpu_seconds(pid) - cpu0) / wall : NAN;
    const double ecpu = echo_pid ? 100.0 * (cpu_seconds(echo_pid) - ecpu0) / wall : NAN;

    const stats_t ms = stats_of(&b.mon), es = stats_of(&b.echo);
    print_series("monitor", &b, npkg, &b.mon, &ms, cpu);
    print_series("echo   ", &b, npkg, &b.echo, &es, ecpu);
    printf("ratio monitor/echo: median %.2f, p99 %.2f\n", ms.med / es.med, ms.p99 / es.p99);

    swaywatch_state_t_unsubscribe(b.lcm, sub);
    lcm_destroy(b.lcm);
    const long expect = n * npkg;
    const int ok = b.mon.nlat == expect && b.echo.nlat == expect;
    free(b.sent);
    free(b.mon.lat);
    free(b.echo.lat);
    return ok ? 0 : 3;
}
