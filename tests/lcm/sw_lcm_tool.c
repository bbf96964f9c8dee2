/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sw_lcm_tool.c - test helper for the LCM integration tests.
 *
 *   sw_lcm_tool mklog OUT.lcmlog PULSE...       accel_t log written with the event-log API
 *   sw_lcm_tool publish URL PULSE... [--bad N]  the same samples published live, paced
 *   sw_lcm_tool dump LOG                        what a log holds, one fact per line
 *   sw_lcm_tool feed [--all-alarms] [--publish URL] LOG SCENE...
 *                                               the log's accel_t messages pushed into the
 *                                               monitor core, as the live loop does
 *
 * PULSE: --rate HZ --amplitude A --omega W --duration T [--lead S]: a
 * half-sine pulse of A m/s^2 (negative brakes) and W rad/s on the x axis,
 * starting S seconds into a recording of T seconds sampled at HZ; y gets a
 * small wobble that the monitor must ignore.  --bad N puts a wrong-type and
 * a truncated message on the channel after every N samples.  --key FILE
 * signs every sample with the last key of the key file (accel_t, freshness
 * from --fresh N, default the wall clock in us, +1 per sample); without
 * it the samples are in the layout of senders without a key
 * (accel_v1_t).
 *
 * dump prints, for the swaywatch channels:
 *   accel COUNT
 *   state NAME count N seq_gaps G max_abs_theta X min_margin M
 *                                         (NAME:lateral for a lateral plane)
 *   alarm UTIME NAME KIND LEVEL          (in order)
 *   nonfinite N                           (doubles that were not finite)
 * so that shell tests can compare two logs with grep and diff.
 *
 * feed reads LOG with LCM's own event-log reader and hands each message on
 * the ACCEL channel to sw_mon_feed() (the monitor core's push API, no
 * lcm_t: nothing published), with lcm-logger's timestamp as the wall
 * clock and its time after the first as the arrival, the command's
 * default options (reserve at 10 Hz), then flushes and settles 30 s as
 * replay does.  It prints every state as a row of replay's --out
 * ("state " then the row) and publishes what the monitor publishes on URL
 * (--publish); with --all-alarms there is no rate limit and each alarm is
 * printed, "alarm T NAME KIND", T the engine's time (%.9g, as the events
 * file).
 * A monitor that drives the same stream as replay writes the same rows. */
#include <gsl/gsl_errno.h>
#include <lcm/eventlog.h>
#include <lcm/lcm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "auth.h"
#include "monitor.h"
#include "swaywatch/swaywatch.h"
#include "swaywatch_accel_t.h"
#include "swaywatch_accel_v1_t.h"
#include "swaywatch_alarm_t.h"
#include "swaywatch_state_t.h"

#define MAXPKG 16

typedef struct {
    double rate, amplitude, omega, duration, lead;
    long bad;
    const char *channel;
    sw_keyring_t *keys; /* --key: sign with its last key */
    int64_t fresh;      /* --fresh: the first sample's freshness; 0 = the wall clock in us */
} pulse_opts_t;

static int64_t wall_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* The key file at path, as the command reads it (without its permission
 * check: the tests make their files). */
static sw_keyring_t *load_keys(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        perror(path);
        return NULL;
    }
    static char text[SW_AUTH_FILE_MAX + 1];
    const size_t n = fread(text, 1, sizeof text, f);
    fclose(f);
    char msg[256];
    sw_keyring_t *k = sw_keyring_parse(text, n, path, msg, sizeof msg);
    if (!k)
        fprintf(stderr, "sw_lcm_tool: %s\n", msg);
    return k;
}

static int parse_pulse(int argc, char **argv, int i, pulse_opts_t *p)
{
    p->rate = 500;
    p->amplitude = -9;
    p->omega = 10;
    p->duration = 2;
    p->lead = 0.2;
    p->bad = 0;
    p->channel = "ACCEL";
    p->keys = NULL;
    p->fresh = 0;
    for (; i + 1 < argc; i += 2) {
        const char *k = argv[i], *v = argv[i + 1];
        if (!strcmp(k, "--rate"))
            p->rate = atof(v);
        else if (!strcmp(k, "--amplitude"))
            p->amplitude = atof(v);
        else if (!strcmp(k, "--omega"))
            p->omega = atof(v);
        else if (!strcmp(k, "--duration"))
            p->duration = atof(v);
        else if (!strcmp(k, "--lead"))
            p->lead = atof(v);
        else if (!strcmp(k, "--bad"))
            p->bad = atol(v);
        else if (!strcmp(k, "--channel"))
            p->channel = v;
        else if (!strcmp(k, "--key")) {
            sw_keyring_destroy(p->keys);
            if (!(p->keys = load_keys(v)))
                return -1;
        } else if (!strcmp(k, "--fresh"))
            p->fresh = atoll(v);
        else {
            fprintf(stderr, "sw_lcm_tool: unknown option %s\n", k);
            return -1;
        }
    }
    if (i != argc || !(p->rate > 0) || !(p->duration > 0)) {
        fprintf(stderr, "sw_lcm_tool: bad pulse options\n");
        return -1;
    }
    return 0;
}

static swaywatch_accel_t sample(const pulse_opts_t *p, long k, int64_t utime0)
{
    sw_pulse_t pulse = {SW_PULSE_HALF_SINE, p->amplitude, p->omega};
    double t = (double)k / p->rate;
    swaywatch_accel_t s;
    s.utime = utime0 + (int64_t)llround(t * 1e6);
    s.seq = k;
    s.ax = sw_pulse_eval(&pulse, t - p->lead);
    s.ay = 0.3 * sin(40.0 * t);
    s.az = 0.0;
    return s;
}

static long n_samples(const pulse_opts_t *p)
{
    return (long)floor(p->duration * p->rate) + 1;
}

/* Sample s encoded as the sender sends it: signed (accel_t) with --key,
 * else in the layout of senders without a key (accel_v1_t).  The
 * encoded length, or -1. */
static int encode(pulse_opts_t *p, swaywatch_accel_t *s, unsigned char *buf, int cap)
{
    if (!p->keys) {
        const swaywatch_accel_v1_t v = {s->utime, s->seq, s->ax, s->ay, s->az};
        return swaywatch_accel_v1_t_encode(buf, 0, cap, &v);
    }
    if (p->fresh == 0)
        p->fresh = wall_us();
    s->freshness = p->fresh++;
    if (sw_auth_sign(p->keys, sw_keyring_signer(p->keys), p->channel, s) != SW_OK)
        return -1;
    return swaywatch_accel_t_encode(buf, 0, cap, s);
}

static int write_event(lcm_eventlog_t *log, const char *channel, int64_t ts, void *data, int len)
{
    lcm_eventlog_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.timestamp = ts;
    ev.channellen = (int32_t)strlen(channel);
    ev.channel = (char *)channel;
    ev.datalen = len;
    ev.data = data;
    return lcm_eventlog_write_event(log, &ev);
}

static int cmd_mklog(const char *path, pulse_opts_t *p)
{
    lcm_eventlog_t *log = lcm_eventlog_create(path, "w");
    if (!log) {
        perror(path);
        return 1;
    }
    unsigned char buf[256];
    const int64_t utime0 = 1700000000000000LL; /* a fixed, realistic epoch time */
    for (long k = 0; k < n_samples(p); k++) {
        swaywatch_accel_t s = sample(p, k, utime0);
        int len = encode(p, &s, buf, sizeof buf);
        if (len < 0 || write_event(log, p->channel, s.utime, buf, len) != 0) {
            fprintf(stderr, "sw_lcm_tool: cannot write %s\n", path);
            lcm_eventlog_destroy(log);
            return 1;
        }
    }
    lcm_eventlog_destroy(log);
    return 0;
}

static int cmd_publish(const char *url, pulse_opts_t *p)
{
    lcm_t *lcm = lcm_create(url);
    if (!lcm) {
        fprintf(stderr, "sw_lcm_tool: cannot create LCM %s\n", url);
        return 1;
    }
    struct timespec t0, wall;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    clock_gettime(CLOCK_REALTIME, &wall);
    int64_t utime0 = (int64_t)wall.tv_sec * 1000000 + wall.tv_nsec / 1000;
    unsigned char buf[256];
    int rc = 0;
    for (long k = 0; k < n_samples(p) && rc == 0; k++) {
        double due = (double)k / p->rate;
        struct timespec ts = t0;
        ts.tv_sec += (time_t)due;
        ts.tv_nsec += (long)((due - floor(due)) * 1e9);
        if (ts.tv_nsec >= 1000000000L) {
            ts.tv_sec++;
            ts.tv_nsec -= 1000000000L;
        }
        clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL);
        swaywatch_accel_t s = sample(p, k, utime0);
        const int slen = encode(p, &s, buf, sizeof buf);
        if (slen < 0 || lcm_publish(lcm, p->channel, buf, (unsigned)slen) != 0)
            rc = 1;
        if (p->bad > 0 && k % p->bad == p->bad - 1) {
            /* a state_t on the accel channel, then a truncated accel_t */
            swaywatch_state_t st;
            memset(&st, 0, sizeof st);
            int len = swaywatch_state_t_encode(buf, 0, sizeof buf, &st);
            if (len < 0 || lcm_publish(lcm, p->channel, buf, (unsigned)len) != 0)
                rc = 1;
            len = encode(p, &s, buf, sizeof buf);
            if (len < 0 || lcm_publish(lcm, p->channel, buf, (unsigned)len - 5) != 0)
                rc = 1;
        }
    }
    lcm_destroy(lcm);
    return rc;
}

typedef struct {
    char name[64];
    long count;
    double max_abs_theta, min_margin;
} pkg_t;

/* A package's plane: its name, and ":lateral" after it across the truck. */
static pkg_t *find_pkg(pkg_t *pk, int *n, const int8_t *name, int plane)
{
    char s[64];
    memcpy(s, name, 63);
    s[63] = '\0';
    if (plane == SWAYWATCH_STATE_T_PLANE_LATERAL && strlen(s) < sizeof s - 9)
        strcat(s, ":lateral");
    for (int i = 0; i < *n; i++)
        if (!strcmp(pk[i].name, s))
            return &pk[i];
    if (*n == MAXPKG)
        return NULL;
    pkg_t *p = &pk[(*n)++];
    memset(p, 0, sizeof *p);
    snprintf(p->name, sizeof p->name, "%s", s);
    p->min_margin = INFINITY;
    return p;
}

static int cmd_dump(const char *path)
{
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    if (!log) {
        perror(path);
        return 1;
    }
    pkg_t pk[MAXPKG];
    int npk = 0;
    long accel = 0, nonfinite = 0, state_gaps = 0, alarm_gaps = 0;
    int64_t state_seq = -1, alarm_seq = -1;
    for (lcm_eventlog_event_t *ev; (ev = lcm_eventlog_read_next_event(log));
         lcm_eventlog_free_event(ev)) {
        if (!strcmp(ev->channel, "ACCEL")) {
            accel++;
        } else if (!strcmp(ev->channel, "SWAY_STATE")) {
            swaywatch_state_t s;
            if (swaywatch_state_t_decode(ev->data, 0, ev->datalen, &s) != ev->datalen) {
                printf("undecodable state\n");
                continue;
            }
            if (state_seq >= 0 && s.seq != state_seq + 1)
                state_gaps++;
            state_seq = s.seq;
            const double v[] = {s.theta,        s.theta_dot,    s.u,  s.z_b, s.margin,
                                s.margin_bound, s.uplift_ratio, s.a_g};
            for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) nonfinite += !isfinite(v[i]);
            pkg_t *p = find_pkg(pk, &npk, s.name, s.plane);
            if (!p)
                continue;
            p->count++;
            if (fabs(s.theta) > p->max_abs_theta)
                p->max_abs_theta = fabs(s.theta);
            if (s.margin < p->min_margin)
                p->min_margin = s.margin;
        } else if (!strcmp(ev->channel, "SWAY_ALARM")) {
            swaywatch_alarm_t a;
            if (swaywatch_alarm_t_decode(ev->data, 0, ev->datalen, &a) != ev->datalen) {
                printf("undecodable alarm\n");
                continue;
            }
            if (alarm_seq >= 0 && a.seq != alarm_seq + 1)
                alarm_gaps++;
            alarm_seq = a.seq;
            nonfinite += !isfinite(a.theta) + !isfinite(a.margin);
            char name[64], text[128];
            memcpy(name, a.name, 63);
            name[63] = '\0';
            memcpy(text, a.text, 127);
            text[127] = '\0';
            printf("alarm %lld %s %d %d %s\n", (long long)a.utime, name[0] ? name : "-", a.kind,
                   a.level, text);
        }
    }
    lcm_eventlog_destroy(log);
    printf("accel %ld\n", accel);
    for (int i = 0; i < npk; i++)
        printf("state %s count %ld max_abs_theta %.17g min_margin %.17g\n", pk[i].name, pk[i].count,
               pk[i].max_abs_theta, pk[i].min_margin);
    printf("state_seq_gaps %ld\nalarm_seq_gaps %ld\nnonfinite %ld\n", state_gaps, alarm_gaps,
           nonfinite);
    return 0;
}

typedef struct {
    const sw_scene_t *scenes;
    sw_mon_t *mon;
    int all_alarms;
} feed_t;

static void num(double v)
{
    if (isfinite(v))
        printf(",%.9g", v);
    else
        putchar(',');
}

static void feed_state(void *user, const sw_output_t *o)
{
    const feed_t *F = user;
    const sw_state_t *s = &o->state;
    printf("state %.9g,%s,%s", o->t, F->scenes[o->pkg].name, sw_phase_name(s->phase));
    num(s->theta);
    num(s->theta_dot);
    num(s->u);
    num(s->u_dot);
    num(s->z);
    num(s->z_dot);
    num(o->margin);
    num(o->margin_bound);
    num(o->uplift_ratio);
    num(o->a_g);
    const sw_risk_pkg_t *p = sw_risk_pkg(sw_mon_risk(F->mon), o->pkg);
    num(p ? p->reserve_g : NAN);
    putchar('\n');
}

static void feed_alarm(void *user, const sw_alarm_t *a)
{
    const feed_t *F = user;
    const char *name = a->pkg == SW_ALARM_ALL ? "-" : F->scenes[a->pkg].name;
    if (F->all_alarms)
        printf("alarm %.9g %s %s\n", a->t, name, sw_alarm_kind_name(a->kind));
}

static int cmd_feed(int argc, char **argv)
{
    feed_t F = {0};
    int i = 2;
    const char *url = NULL;
    for (; i < argc && argv[i][0] == '-'; i++)
        if (!strcmp(argv[i], "--all-alarms"))
            F.all_alarms = 1;
        else if (!strcmp(argv[i], "--publish") && i + 1 < argc)
            url = argv[++i];
        else
            break;
    if (argc - i < 2) {
        fprintf(stderr, "usage: sw_lcm_tool feed [--all-alarms] [--publish URL] LOG SCENE...\n");
        return 2;
    }
    const char *path = argv[i++];
    const size_t n = (size_t)(argc - i);
    sw_scene_t *sc = calloc(n, sizeof *sc);
    if (!sc)
        return 1;
    for (size_t k = 0; k < n; k++) {
        FILE *f = fopen(argv[i + (int)k], "rb");
        char text[8192];
        size_t len = f ? fread(text, 1, sizeof text - 1, f) : 0;
        if (f)
            fclose(f);
        text[len] = '\0';
        sw_scene_init(&sc[k]);
        if (!f || sw_scene_parse(&sc[k], text, argv[i + (int)k], NULL, NULL) != SW_OK ||
            sw_scene_validate(&sc[k], NULL, argv[i + (int)k], NULL, NULL) != SW_OK) {
            fprintf(stderr, "sw_lcm_tool: %s: not a scene\n", argv[i + (int)k]);
            free(sc);
            return 2;
        }
    }
    F.scenes = sc;
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    sw_mon_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.vertical = -1;
    mo.hysteresis = -1.0;
    mo.reserve_rate = SW_RISK_RATE;
    mo.alarm_interval = F.all_alarms ? -1.0 : 0.0;
    mo.on_state = feed_state;
    mo.on_alarm = feed_alarm;
    mo.user = &F;
    char msg[256] = "";
    lcm_t *lcm = url ? lcm_create(url) : NULL;
    F.mon = !url || lcm ? sw_mon_create(sc, n, &eo, &mo, lcm, msg, sizeof msg) : NULL;
    lcm_eventlog_t *log = F.mon ? lcm_eventlog_create(path, "r") : NULL;
    if (!log) {
        fprintf(stderr, "sw_lcm_tool: %s\n", F.mon ? path : msg[0] ? msg : url);
        sw_mon_destroy(F.mon);
        if (lcm)
            lcm_destroy(lcm);
        free(sc);
        return 1;
    }
    int have0 = 0;
    int64_t ts0 = 0;
    for (lcm_eventlog_event_t *ev; (ev = lcm_eventlog_read_next_event(log));
         lcm_eventlog_free_event(ev)) {
        if (strcmp(ev->channel, "ACCEL") != 0)
            continue;
        if (!have0) {
            have0 = 1;
            ts0 = ev->timestamp;
        }
        sw_mon_feed(F.mon, ev->data, (size_t)ev->datalen, ev->timestamp,
                    (double)(ev->timestamp - ts0) / 1e6, NULL);
    }
    lcm_eventlog_destroy(log);
    sw_mon_flush(F.mon);
    sw_stream_settle(sw_mon_stream(F.mon), 30.0);
    sw_mon_destroy(F.mon);
    if (lcm)
        lcm_destroy(lcm);
    free(sc);
    return 0;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    pulse_opts_t p;
    int rc;
    if (argc >= 3 && !strcmp(argv[1], "mklog")) {
        rc = parse_pulse(argc, argv, 3, &p) ? 2 : cmd_mklog(argv[2], &p);
        sw_keyring_destroy(p.keys);
        return rc;
    }
    if (argc >= 3 && !strcmp(argv[1], "publish")) {
        rc = parse_pulse(argc, argv, 3, &p) ? 2 : cmd_publish(argv[2], &p);
        sw_keyring_destroy(p.keys);
        return rc;
    }
    if (argc == 3 && !strcmp(argv[1], "dump"))
        return cmd_dump(argv[2]);
    if (argc >= 2 && !strcmp(argv[1], "feed"))
        return cmd_feed(argc, argv);
    fprintf(stderr,
            "usage: sw_lcm_tool mklog OUT [pulse] | publish URL [pulse] | dump LOG | feed "
            "[--all-alarms] LOG SCENE...\n");
    return 2;
}
