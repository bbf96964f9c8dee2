/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sw_accel_feed.c - test tool: a stream of swaywatch.accel_t samples with a
 * known share of bad messages, published live over LCM or written to an
 * lcm-logger file, and an exact tally of what was sent.
 *
 *   sw_accel_feed publish URL [options]    paced, over LCM (udpm, ...)
 *   sw_accel_feed log FILE [options]       an lcm-logger event log
 *   sw_accel_feed check FILE               what a recording of the monitor's
 *                                          output holds (see check())
 *
 * Options:
 *   --channel CH       channel (default ACCEL)
 *   --count N          good samples (default 1000)
 *   --rate HZ          sample rate: utime step 1e6/HZ us (default 1000)
 *   --pace HZ          publish: messages paced at this rate of good samples
 *                      (default --rate; 0 = as fast as possible)
 *   --garbage PERMILLE bad messages per 1000 good ones (default 0), one after
 *                      a good sample, the kinds taken in turn
 *   --kinds LIST       comma-separated kinds to use (default all of them):
 *                      fingerprint (a flipped fingerprint bit), other_type
 *                      (a state_t on the channel), truncated, empty, trailing
 *                      (extra bytes), oversized (64 KiB after the sample),
 *                      nonfinite (NaN or infinity), implausible (1e4 m/s^2),
 *                      duplicate (the last good utime again), out_of_order
 *                      (1 ms before the last good sample); and, only when
 *                      named here, past and future (a day before or after:
 *                      refused as skew when the monitor checks --max-skew)
 *   --utime0 US        utime of the first sample (default 1700000000000000)
 *   --seq0 N           seq of the first good sample (default 0)
 *   --seed S           placement of the bad messages (default 1)
 *   --empty N          first N empty messages (counted as decode): probes
 *                      that tell when a subscriber is listening
 *   --pulse A          every 5 s of sample time a 0.3 s braking half-sine of
 *                      A m/s^2 on top of a gentle sway (default 7: it rocks
 *                      the sample crates hard, short of overturning them)
 *   --event K:KIND[:ARG]  a field fault before good sample K (repeatable):
 *                      restart:S  the sensor restarts: seq from 0, utime S s
 *                                 back (default 30)
 *                      step:S     its clock steps S s forward (default 3600)
 *                      future:S   one forged sample S s ahead (default a
 *                                 year): refused as jump
 *                      utime:max|min  one sample stamped INT64_MAX or
 *                                 INT64_MIN: refused as time
 *                      seq:max|min  sample K carries seq INT64_MAX or
 *                                 INT64_MIN (a good sample all the same)
 *                      flood:N    N copies of the last sample at once:
 *                                 refused as duplicate
 *                      fall:S     S s of vertical acceleration -15 m/s^2
 *                                 (below -1 g: every sample a model fault)
 *                      pause:S    the sensor stops for S s (its samples
 *                                 are not sent: lost by seq)
 *                      forge:S    for S s a forger: after every second
 *                                 good sample one quiet sample stamped
 *                                 2.5 ms ahead of it, with its seq
 *                                 (refused as jump; the input contested)
 *                      fifo:S     for S s the samples go out as an IMU's
 *                                 FIFO is read: 32 at a time, when the
 *                                 last of them is due, each stamped when
 *                                 read (a few us apart)
 *                      Each prints "event K KIND ARG WALL_US UTIME_AFTER":
 *                      when it was applied (CLOCK_REALTIME, us) and the
 *                      utime of the first good sample after it.
 *
 * Output on stdout, one "key value" per line: published (all messages),
 * good, then the bad messages by the monitor's reason names: decode
 * (fingerprint, other_type, truncated, empty), trailing (trailing,
 * oversized), nonfinite, implausible, duplicate, out_of_order, skew (past,
 * future), jump (future events), time (utime events); skipped (good samples
 * a pause did not send); and last_utime (us).  In a log, each event is stamped with its
 * sample's utime plus 0.2 ms, as lcm-logger would receive it from a sensor
 * whose clock is synchronised.  The seq of good samples increases by one per good
 * sample: bad messages take none, so a seq gap in what the monitor
 * accepted is a message lost on the way. */
#include <errno.h>
#include <lcm/eventlog.h>
#include <lcm/lcm.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "swaywatch_accel_t.h"
#include "swaywatch_alarm_t.h"
#include "swaywatch_state_t.h"

enum {
    K_FINGERPRINT,
    K_OTHER_TYPE,
    K_TRUNCATED,
    K_EMPTY,
    K_TRAILING,
    K_OVERSIZED,
    K_NONFINITE,
    K_IMPLAUSIBLE,
    K_DUPLICATE,
    K_OUT_OF_ORDER,
    K_PAST,
    K_FUTURE,
    NKIND
};
static const char *const kind_name[NKIND] = {
    "fingerprint", "other_type",  "truncated", "empty",        "trailing", "oversized",
    "nonfinite",   "implausible", "duplicate", "out_of_order", "past",     "future"};
/* The monitor's reason for each kind (sw_mon_reject_name). */
static const char *const reason_of[NKIND] = {
    "decode",    "decode",      "decode",    "decode",       "trailing", "trailing",
    "nonfinite", "implausible", "duplicate", "out_of_order", "skew",     "skew"};
static const char *const reasons[] = {"decode",    "trailing",     "nonfinite", "implausible",
                                      "duplicate", "out_of_order", "skew"};
#define NREASON (sizeof reasons / sizeof reasons[0])

#define OVERSIZE (64 * 1024)
#define FIFO 32 /* samples a FIFO read takes */
#define MAX_EVENTS 64

enum {
    E_RESTART,
    E_STEP,
    E_FUTURE,
    E_UTIME,
    E_SEQ,
    E_FLOOD,
    E_FALL,
    E_PAUSE,
    E_FORGE,
    E_FIFO,
    NEVKIND
};
static const char *const event_name[NEVKIND] = {"restart", "step", "future", "utime", "seq",
                                                "flood",   "fall", "pause",  "forge", "fifo"};

typedef struct {
    long k; /* before good sample k */
    int kind;
    double arg;  /* s, or a count */
    int extreme; /* utime, seq: +1 max, -1 min */
} event_t;

typedef struct {
    const char *channel;
    long count;
    double rate, pace, pulse;
    long garbage; /* per 1000 */
    long empty;   /* probes sent first */
    int use[NKIND];
    int64_t utime0, seq0;
    uint64_t seed;
    event_t ev[MAX_EVENTS];
    int nev;
} opts_t;

typedef struct {
    lcm_t *lcm;          /* publish */
    lcm_eventlog_t *log; /* log */
    const char *channel;
    long published, good, by_kind[NKIND];
    long jump, time, skipped; /* forged samples sent (future, utime), pause's unsent */
    int64_t stamp;            /* us, the log's receive time for the next event */
    unsigned char *buf;       /* OVERSIZE + room for a message */
    int failed;
} sink_t;

static void die_usage(const char *why)
{
    fprintf(stderr, "sw_accel_feed: %s\n", why);
    fprintf(stderr, "usage: sw_accel_feed publish URL | log FILE [options]; see the source\n");
    exit(2);
}

static int parse_kinds(const char *list, int use[NKIND])
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    memset(use, 0, sizeof(int) * NKIND);
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int k = 0;
        while (k < NKIND && strcmp(tok, kind_name[k])) k++;
        if (k == NKIND)
            return -1;
        use[k] = 1;
    }
    return 0;
}

/* "K:KIND[:ARG]" into o->ev. */
static int parse_event(const char *v, opts_t *o)
{
    char kind[16] = "", arg[32] = "";
    long k;
    if (o->nev == MAX_EVENTS || sscanf(v, "%ld:%15[a-z]:%31s", &k, kind, arg) < 2 || k < 0)
        return -1;
    event_t *e = &o->ev[o->nev];
    e->k = k;
    e->kind = 0;
    while (e->kind < NEVKIND && strcmp(kind, event_name[e->kind])) e->kind++;
    if (e->kind == NEVKIND)
        return -1;
    static const double def[NEVKIND] = {30, 3600, 365 * 86400.0, 0, 0, 1000, 1, 1, 1, 1};
    e->arg = def[e->kind];
    e->extreme = 0;
    if (e->kind == E_UTIME || e->kind == E_SEQ) {
        if (strcmp(arg, "max") && strcmp(arg, "min"))
            return -1;
        e->extreme = strcmp(arg, "max") ? -1 : 1;
    } else if (arg[0]) {
        char *end;
        e->arg = strtod(arg, &end);
        if (*end || !(e->arg > 0) || !isfinite(e->arg))
            return -1;
    }
    o->nev++;
    return 0;
}

static void parse(int argc, char **argv, opts_t *o)
{
    o->channel = "ACCEL";
    o->count = 1000;
    o->rate = 1000;
    o->pace = -1;
    o->pulse = 7;
    o->garbage = 0;
    o->empty = 0;
    o->utime0 = 1700000000000000LL;
    o->seq0 = 0;
    o->seed = 1;
    o->nev = 0;
    for (int k = 0; k < NKIND; k++) o->use[k] = k != K_PAST && k != K_FUTURE;
    for (int i = 3; i < argc; i += 2) {
        if (i + 1 >= argc)
            die_usage("option without a value");
        const char *k = argv[i], *v = argv[i + 1];
        char *end;
        errno = 0;
        if (!strcmp(k, "--channel")) {
            o->channel = v;
            continue;
        }
        if (!strcmp(k, "--event")) {
            if (parse_event(v, o) != 0)
                die_usage("bad --event");
            continue;
        }
        if (!strcmp(k, "--kinds")) {
            if (parse_kinds(v, o->use))
                die_usage("unknown kind in --kinds");
            continue;
        }
        double x = strtod(v, &end);
        if (end == v || *end || errno || !isfinite(x))
            die_usage("bad number");
        if (!strcmp(k, "--count"))
            o->count = (long)x;
        else if (!strcmp(k, "--rate"))
            o->rate = x;
        else if (!strcmp(k, "--pace"))
            o->pace = x;
        else if (!strcmp(k, "--garbage"))
            o->garbage = (long)x;
        else if (!strcmp(k, "--utime0"))
            o->utime0 = strtoll(v, NULL, 10);
        else if (!strcmp(k, "--seq0"))
            o->seq0 = strtoll(v, NULL, 10);
        else if (!strcmp(k, "--seed"))
            o->seed = (uint64_t)strtoull(v, NULL, 10);
        else if (!strcmp(k, "--pulse"))
            o->pulse = x;
        else if (!strcmp(k, "--empty"))
            o->empty = (long)x;
        else
            die_usage("unknown option");
    }
    if (o->pace < 0)
        o->pace = o->rate;
    if (o->count < 0 || o->empty < 0 || !(o->rate > 0) || o->garbage < 0 || o->garbage > 1000)
        die_usage("bad --count, --rate or --garbage");
}

static uint64_t next_rand(uint64_t *s)
{
    /* xorshift64* */
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * 2685821657736338717ULL;
}

static void emit(sink_t *s, const void *data, int len)
{
    int rc;
    if (s->lcm) {
        rc = lcm_publish(s->lcm, s->channel, data, (unsigned)len);
    } else {
        lcm_eventlog_event_t ev;
        memset(&ev, 0, sizeof ev);
        ev.timestamp = s->stamp;
        ev.channellen = (int32_t)strlen(s->channel);
        ev.channel = (char *)s->channel;
        ev.datalen = len;
        ev.data = (void *)data;
        rc = lcm_eventlog_write_event(s->log, &ev);
    }
    if (rc != 0)
        s->failed = 1;
    s->published++;
}

static int encode(sink_t *s, const swaywatch_accel_t *m)
{
    return swaywatch_accel_t_encode(s->buf, 0, OVERSIZE, m);
}

/* One bad message of kind k; last is the last good sample sent. */
static void send_bad(sink_t *s, int k, const swaywatch_accel_t *last, uint64_t *rnd)
{
    swaywatch_accel_t m = *last;
    int len;
    switch (k) {
        case K_FINGERPRINT:
            len = encode(s, &m);
            s->buf[(int)(next_rand(rnd) % 8)] ^= (unsigned char)(1u << (next_rand(rnd) % 8));
            emit(s, s->buf, len);
            break;
        case K_OTHER_TYPE: {
            swaywatch_state_t st;
            memset(&st, 0, sizeof st);
            st.utime = m.utime;
            snprintf((char *)st.name, sizeof st.name, "not-an-accel");
            len = swaywatch_state_t_encode(s->buf, 0, OVERSIZE, &st);
            emit(s, s->buf, len);
            break;
        }
        case K_TRUNCATED:
            len = encode(s, &m);
            emit(s, s->buf, 1 + (int)(next_rand(rnd) % (uint64_t)(len - 1)));
            break;
        case K_EMPTY: emit(s, s->buf, 0); break;
        case K_TRAILING:
            len = encode(s, &m);
            memset(s->buf + len, 0xA5, 4);
            emit(s, s->buf, len + 4);
            break;
        case K_OVERSIZED:
            len = encode(s, &m);
            memset(s->buf + len, 0x5A, OVERSIZE - (size_t)len);
            emit(s, s->buf, OVERSIZE);
            break;
        case K_NONFINITE:
            if (next_rand(rnd) & 1)
                m.ax = NAN;
            else
                m.az = -INFINITY;
            emit(s, s->buf, encode(s, &m));
            break;
        case K_IMPLAUSIBLE:
            m.ax = (next_rand(rnd) & 1) ? 1e4 : -1e4;
            emit(s, s->buf, encode(s, &m));
            break;
        case K_DUPLICATE: emit(s, s->buf, encode(s, &m)); break;
        case K_OUT_OF_ORDER:
            m.utime -= 1000;
            emit(s, s->buf, encode(s, &m));
            break;
        case K_PAST:
        case K_FUTURE:
            m.utime += (k == K_PAST ? -1 : 1) * 86400LL * 1000000;
            emit(s, s->buf, encode(s, &m));
            break;
    }
    s->by_kind[k]++;
}

/* Sample k: a gentle sway, and every 5 s a braking half-sine of 0.3 s. */
static swaywatch_accel_t sample(const opts_t *o, long k)
{
    const double t = (double)k / o->rate;
    const double ph = fmod(t, 5.0) - 2.0;
    swaywatch_accel_t m;
    m.utime = o->utime0 + (int64_t)llround(t * 1e6);
    m.seq = o->seq0 + k;
    m.ax = 0.8 * sin(2 * M_PI * 0.2 * t);
    if (ph >= 0 && ph < 0.3)
        m.ax -= o->pulse * sin(M_PI * ph / 0.3);
    m.ay = 0.2 * sin(2 * M_PI * 3.1 * t);
    m.az = 0.3 * sin(2 * M_PI * 11.0 * t);
    return m;
}

/* The faults in force: what the events changed. */
typedef struct {
    int64_t ushift;             /* us added to every utime from now on */
    int64_t seqshift;           /* added to every seq from now on */
    long fall_end;              /* samples before it fall (az -15 m/s^2) */
    long forge_from, forge_end; /* a forger sends among these samples */
    long fifo_from, fifo_end;   /* these go out in FIFO batches */
    int have_seq_once;
    int64_t seq_once; /* the seq of the next sample, once */
} fault_t;

/* Apply event e before good sample k (last: the last good sample sent).
 * Returns the number of samples a pause skips, else 0. */
static long apply_event(const opts_t *o, sink_t *s, const event_t *e, long k, fault_t *f,
                        const swaywatch_accel_t *last)
{
    swaywatch_accel_t m = *last;
    switch (e->kind) {
        case E_RESTART:
            f->ushift -= (int64_t)llround(e->arg * 1e6);
            f->seqshift = -(o->seq0 + k);
            return 0;
        case E_STEP: f->ushift += (int64_t)llround(e->arg * 1e6); return 0;
        case E_FUTURE:
            m.utime += (int64_t)llround(e->arg * 1e6);
            emit(s, s->buf, encode(s, &m));
            s->jump++;
            return 0;
        case E_UTIME:
            m.utime = e->extreme > 0 ? INT64_MAX : INT64_MIN;
            emit(s, s->buf, encode(s, &m));
            s->time++;
            return 0;
        case E_SEQ:
            f->have_seq_once = 1;
            f->seq_once = e->extreme > 0 ? INT64_MAX : INT64_MIN;
            return 0;
        case E_FLOOD:
            for (long i = 0; i < (long)e->arg; i++) emit(s, s->buf, encode(s, &m));
            s->by_kind[K_DUPLICATE] += (long)e->arg;
            return 0;
        case E_FALL: f->fall_end = k + (long)llround(e->arg * o->rate); return 0;
        case E_FORGE:
            f->forge_from = k;
            f->forge_end = k + (long)llround(e->arg * o->rate);
            return 0;
        case E_FIFO:
            f->fifo_from = k;
            f->fifo_end = k + (long)llround(e->arg * o->rate);
            return 0;
        case E_PAUSE: {
            const long n = (long)llround(e->arg * o->rate);
            s->skipped += n;
            return n;
        }
    }
    return 0;
}

static int64_t wall_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static void sleep_until(const struct timespec *t0, double at)
{
    struct timespec ts = *t0;
    double whole = floor(at);
    ts.tv_sec += (time_t)whole;
    ts.tv_nsec += (long)((at - whole) * 1e9);
    if (ts.tv_nsec >= 1000000000L) {
        ts.tv_sec++;
        ts.tv_nsec -= 1000000000L;
    }
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR) {
    }
}

/* A recording (lcm-logger) of the monitor's output: counts the state_t and
 * alarm_t messages, those that do not decode exactly, and the numbers in
 * them that are not finite; prints "states N", "alarms N", "undecodable N",
 * "nonfinite N", "alarm_kind_K N" per alarm kind.  Exit 1 if the log
 * cannot be read. */
static int check(const char *path)
{
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    if (!log) {
        fprintf(stderr, "sw_accel_feed: cannot read %s\n", path);
        return 1;
    }
    long states = 0, alarms = 0, bad = 0, nonfinite = 0, kinds[16] = {0};
    for (lcm_eventlog_event_t *ev; (ev = lcm_eventlog_read_next_event(log));
         lcm_eventlog_free_event(ev)) {
        swaywatch_state_t st;
        swaywatch_alarm_t al;
        if (swaywatch_state_t_decode(ev->data, 0, ev->datalen, &st) == ev->datalen) {
            const double v[] = {st.theta,        st.theta_dot,    st.u,  st.z_b, st.margin,
                                st.margin_bound, st.uplift_ratio, st.a_g};
            for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) nonfinite += !isfinite(v[i]);
            states++;
        } else if (swaywatch_alarm_t_decode(ev->data, 0, ev->datalen, &al) == ev->datalen) {
            nonfinite += !isfinite(al.theta) + !isfinite(al.margin);
            kinds[al.kind & 15]++;
            alarms++;
        } else {
            bad++;
        }
    }
    lcm_eventlog_destroy(log);
    printf("states %ld\nalarms %ld\nundecodable %ld\nnonfinite %ld\n", states, alarms, bad,
           nonfinite);
    for (int k = 0; k < 16; k++)
        if (kinds[k])
            printf("alarm_kind_%d %ld\n", k, kinds[k]);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "check"))
        return check(argv[2]);
    if (argc < 3)
        die_usage("missing mode and target");
    opts_t o;
    parse(argc, argv, &o);
    sink_t s;
    memset(&s, 0, sizeof s);
    s.channel = o.channel;
    s.buf = calloc(1, OVERSIZE + 256);
    if (!s.buf)
        return 1;
    int live = !strcmp(argv[1], "publish");
    if (live) {
        s.lcm = lcm_create(argv[2]);
        if (!s.lcm) {
            fprintf(stderr, "sw_accel_feed: cannot create LCM %s\n", argv[2]);
            return 1;
        }
    } else if (!strcmp(argv[1], "log")) {
        s.log = lcm_eventlog_create(argv[2], "w");
        if (!s.log) {
            fprintf(stderr, "sw_accel_feed: cannot write %s\n", argv[2]);
            return 1;
        }
    } else {
        die_usage("mode is publish or log");
    }

    int kinds[NKIND], nk = 0;
    for (int k = 0; k < NKIND; k++)
        if (o.use[k])
            kinds[nk++] = k;
    uint64_t rnd = o.seed * 0x9E3779B97F4A7C15ULL + 1;
    long turn = 0;
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    swaywatch_accel_t last;
    memset(&last, 0, sizeof last);
    s.stamp = o.utime0;
    for (long k = 0; k < o.empty && !s.failed; k++) {
        emit(&s, s.buf, 0);
        s.by_kind[K_EMPTY]++;
    }
    fault_t f = {.fall_end = -1, .forge_end = -1, .fifo_end = -1};
    for (long k = 0; k < o.count && !s.failed; k++) {
        /* a FIFO batch of 32 goes out when its last sample is due */
        const int fifo = k >= f.fifo_from && k < f.fifo_end;
        long due = fifo ? f.fifo_from + ((k - f.fifo_from) / FIFO + 1) * FIFO - 1 : k;
        if (due >= f.fifo_end && fifo)
            due = f.fifo_end - 1; /* the last read takes what is left */
        if (live && o.pace > 0)
            sleep_until(&t0, (double)due / o.pace);
        int applied[MAX_EVENTS], na = 0;
        int64_t when[MAX_EVENTS];
        long skip = 0;
        for (int i = 0; i < o.nev; i++)
            if (o.ev[i].k == k && k > 0) {
                when[na] = wall_us();
                applied[na++] = i;
                skip += apply_event(&o, &s, &o.ev[i], k, &f, &last);
            }
        if (skip > 0) { /* the sensor is silent, its samples unsent */
            k += skip;
            if (k >= o.count)
                break;
            if (live && o.pace > 0)
                sleep_until(&t0, (double)k / o.pace);
        }
        last = sample(&o, k);
        last.utime += f.ushift;
        last.seq += f.seqshift;
        if (f.have_seq_once) {
            last.seq = f.seq_once;
            f.have_seq_once = 0;
        }
        if (k < f.fall_end)
            last.az = -15.0;
        if (fifo) /* stamped when read, the first of the batch at the read */
            last.utime = sample(&o, due).utime + f.ushift + 4 * (k - due + FIFO - 1);
        for (int i = 0; i < na; i++)
            printf("event %ld %s %g %lld %lld\n", o.ev[applied[i]].k,
                   event_name[o.ev[applied[i]].kind], o.ev[applied[i]].arg, (long long)when[i],
                   (long long)last.utime);
        s.stamp = last.utime + 200;
        emit(&s, s.buf, encode(&s, &last));
        s.good++;
        if (k >= f.forge_from && k < f.forge_end && (k - f.forge_from) % 2 == 1) {
            swaywatch_accel_t forged = last;
            forged.utime += 2500;
            forged.ax = forged.ay = forged.az = 0.0;
            s.stamp = forged.utime; /* a log receives it ahead too */
            emit(&s, s.buf, encode(&s, &forged));
            s.jump++;
        }
        if (nk && o.garbage && (long)(next_rand(&rnd) % 1000) < o.garbage)
            send_bad(&s, kinds[turn++ % nk], &last, &rnd);
    }
    if (s.lcm)
        lcm_destroy(s.lcm);
    if (s.log)
        lcm_eventlog_destroy(s.log);
    free(s.buf);
    if (s.failed) {
        fprintf(stderr, "sw_accel_feed: publishing or writing failed\n");
        return 1;
    }
    printf("published %ld\ngood %ld\n", s.published, s.good);
    for (size_t r = 0; r < NREASON; r++) {
        long n = 0;
        for (int k = 0; k < NKIND; k++)
            if (!strcmp(reason_of[k], reasons[r]))
                n += s.by_kind[k];
        printf("%s %ld\n", reasons[r], n);
    }
    printf("jump %ld\ntime %ld\nskipped %ld\n", s.jump, s.time, s.skipped);
    printf("last_utime %lld\n", (long long)last.utime);
    return 0;
}
