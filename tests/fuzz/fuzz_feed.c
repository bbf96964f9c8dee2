/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_feed.c - libFuzzer target for the monitor core's input timeline:
 * sw_mon_feed() with well-formed accel_t messages whose utime and seq are
 * anything an int64 can hold (far future, far past, backwards, repeated,
 * INT64_MIN and INT64_MAX, a sender restarting at 0) and whose values are
 * anything a double can hold (NaN, infinities, huge, denormal), with the
 * clocks of arrival moving on between them.  fuzz_accel covers the bytes of
 * a message; this one covers what a broken or hostile sender's clock and
 * counter do to the monitor.  A bare crate is watched, and a framed one or
 * a second bare one (an option: the frame's engine costs a fifth of an
 * input to make, twice, as the monitor keeps a rival timeline's engine
 * too): the models whose cost does not grow with a gap's length.  The
 * work per input
 * is bounded (fuzz.h): at most MAX_RECORDS records and FZ_STEP_BUDGET
 * engine steps, gaps bridged up to FZ_MAX_BRIDGE (longer ones restart the
 * packages, as the gap policy does), and no reserve (risk.h: building it
 * costs several times the rest of an input, and the timeline is the matter).
 *
 * Input: 1 byte of monitor options (vertical axis, skew check, max_jump:
 * default, any, 0.5 s; state rate; the second crate framed), then records of a kind byte and its
 * bytes: 0: utime and seq as raw int64 (8 + 8 bytes, big-endian), values; 1: utime += int16 us, seq
 * += int8, values; 2: utime += int32 us (up to 35 min either way), seq + 1, values; 3: utime and
 * seq each from a table of extremes (1 byte each), values; 4: time passes for the timers (1 byte:
 * 10 ms units) and they run; 5: the last message again; 6: utime -= uint16 ms (a clock going back),
 * seq = 0 (a restart), values; 7: utime += 1 ms, seq + 1, values. values: 1 byte: 0-3 small numbers
 * (3 bytes follow), 4-5 a special value on every axis (1 byte: which), 6-7 three raw doubles (24
 * bytes).
 *
 * Checks, after every message: received = accepted + rejected (by reason)
 * + held, with 0 <= held <= SW_GATE_HELD_MAX; an accepted sample had finite
 * values within the plausibility limit and is the last accepted utime;
 * every state_t and alarm_t published decodes and holds only finite
 * numbers.  At the end (after sw_mon_flush) nothing is held. */
#include <stdint.h>

#include "../testutil.h"
#include "fuzz.h"
#include "fuzz_lcm.h"
#include "monitor.h"
#include "swaywatch_accel_t.h"

#define MAX_RECORDS 48

static uint64_t be(fz_bytes_t *b, int n)
{
    uint64_t u = 0;
    for (int i = 0; i < n; i++) u = (u << 8) | fz_byte(b);
    return u;
}

/* int64 from n big-endian bytes, sign-extended from n * 8 bits. */
static int64_t sbe(fz_bytes_t *b, int n)
{
    uint64_t u = be(b, n);
    if (n < 8 && (u >> (8 * n - 1)))
        u |= ~UINT64_C(0) << (8 * n);
    int64_t s;
    memcpy(&s, &u, sizeof s);
    return s;
}

/* a + d, wrapping like the machine (no undefined behaviour here: the
 * monitor is what is under test). */
static int64_t wrap_add(int64_t a, int64_t d)
{
    uint64_t u = (uint64_t)a + (uint64_t)d;
    int64_t s;
    memcpy(&s, &u, sizeof s);
    return s;
}

static const int64_t WALL0 = 1700000000000000LL;

static int64_t extreme(uint8_t k)
{
    static const int64_t t[] = {INT64_MIN,
                                INT64_MIN + 1,
                                -1000000,
                                -1,
                                0,
                                1,
                                1700000000000000LL,                    /* 2023 */
                                1700000000000000LL + 9500000,          /* + 9.5 s */
                                1700000000000000LL + 31536000000000LL, /* + 1 year */
                                1700000000000000LL - 31536000000000LL, /* - 1 year */
                                1700000000000000LL + 86400000000LL,    /* + 1 day */
                                INT64_MAX / 2,
                                INT64_MAX - 1000000,
                                INT64_MAX - 1,
                                INT64_MAX};
    return t[k % (sizeof t / sizeof t[0])];
}

static double special(uint8_t k)
{
    static const double t[] = {NAN,     INFINITY, -INFINITY, 1e300,   -1e300, DBL_MAX,
                               DBL_MIN, 4.9e-324, -0.0,      0.0,     490.0,  490.4,
                               -490.4,  -20.0,    -9.81,     -9.8067, 1e-300, 3.5};
    return t[k % (sizeof t / sizeof t[0])];
}

static void values(fz_bytes_t *b, swaywatch_accel_t *a)
{
    const uint8_t k = fz_byte(b);
    if (k % 8 < 4) {
        a->ax = (int8_t)fz_byte(b) * 0.25;
        a->ay = (int8_t)fz_byte(b) * 0.25;
        a->az = (int8_t)fz_byte(b) * 0.1;
    } else if (k % 8 < 6) {
        const uint8_t s = fz_byte(b);
        a->ax = special(s);
        a->ay = special((uint8_t)(s >> 3));
        a->az = special((uint8_t)(s * 7));
    } else {
        a->ax = fz_double(b);
        a->ay = fz_double(b);
        a->az = fz_double(b);
    }
}

/* Returns the samples held. */
static long check_counts(sw_mon_t *m, long fed)
{
    sw_mon_counts_t c;
    sw_mon_counts(m, &c);
    FZ_CHECK(c.received == fed);
    FZ_CHECK(c.held >= 0 && c.held <= SW_GATE_HELD_MAX);
    FZ_CHECK(c.accepted >= 0);
    for (int r = 0; r < SW_MON_NREJ; r++) FZ_CHECK(c.rejected[r] >= 0);
    FZ_CHECK(c.received == c.accepted + sw_mon_rejected(&c) + c.held);
    return c.held;
}

static sw_mon_t *make(uint8_t o, lcm_t *lcm)
{
    sw_mon_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.axis = 0;
    mo.vertical = (o & 1) ? 2 : -1;
    mo.max_skew = (o >> 1) & 1 ? 10.0 : 0.0;
    mo.max_jump = (o >> 2) % 3 == 0 ? 0.0 : (o >> 2) % 3 == 1 ? -1.0 : 0.5;
    mo.state_rate = (o >> 4) & 1 ? 100.0 : 0.0;
    mo.hysteresis = -1.0;
    mo.reserve_rate = -1.0;
    mo.max_bridge = FZ_MAX_BRIDGE;
    const int frame = (o >> 5) & 1;
    sw_scene_t sc[2] = {tu_bare(2.0, 0.728),
                        frame ? tu_frame(2.0, 0.728, 250.0, 5.59, 0.1) : tu_bare(1.2, 0.8)};
    snprintf(sc[0].name, sizeof sc[0].name, "crate");
    snprintf(sc[1].name, sizeof sc[1].name, frame ? "crate-frame" : "box");
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    char msg[256];
    sw_mon_t *m = sw_mon_create(sc, 2, &eo, &mo, lcm, msg, sizeof msg);
    FZ_CHECK(m != NULL);
    return m;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes_t b = {data, size};
    lcm_t *lcm = fz_lcm();
    sw_mon_t *m = make(fz_byte(&b), lcm);

    swaywatch_accel_t a = {.utime = WALL0, .seq = 0};
    int64_t wall = WALL0;
    double mono = 100.0;
    unsigned char buf[128]; /* an accel_t is 73 bytes */
    int len = -1;
    long fed = 0, held = 0;
    for (int r = 0; r < MAX_RECORDS && b.n > 0 && fz_steps(sw_mon_engine(m)) < FZ_STEP_BUDGET;
         r++) {
        const uint8_t kind = fz_byte(&b);
        switch (kind % 8) {
            case 0:
                a.utime = sbe(&b, 8);
                a.seq = sbe(&b, 8);
                values(&b, &a);
                break;
            case 1:
                a.utime = wrap_add(a.utime, sbe(&b, 2));
                a.seq = wrap_add(a.seq, sbe(&b, 1));
                values(&b, &a);
                break;
            case 2:
                a.utime = wrap_add(a.utime, sbe(&b, 4));
                a.seq = wrap_add(a.seq, 1);
                values(&b, &a);
                break;
            case 3:
                a.utime = extreme(fz_byte(&b));
                a.seq = extreme(fz_byte(&b));
                values(&b, &a);
                break;
            case 4: {
                const double dt = fz_byte(&b) * 0.01;
                mono += dt;
                wall += (int64_t)(dt * 1e6);
                if (mono >= sw_mon_deadline(m))
                    sw_mon_tick(m, mono);
                continue;
            }
            case 5:
                if (len < 0)
                    continue;
                break;
            case 6:
                a.utime = wrap_add(a.utime, -1000 * (int64_t)be(&b, 2));
                a.seq = 0;
                values(&b, &a);
                break;
            default:
                a.utime = wrap_add(a.utime, 1000);
                a.seq = wrap_add(a.seq, 1);
                values(&b, &a);
                break;
        }
        if (kind % 8 != 5) {
            len = swaywatch_accel_t_encode(buf, 0, (int)sizeof buf, &a);
            FZ_CHECK(len > 0);
        }
        mono += 1e-3;
        wall += 1000;
        sw_mon_reject why = SW_MON_NREJ;
        const int rc = sw_mon_feed(m, buf, (size_t)len, wall, mono, &why);
        fed++;
        if (rc >= 0 && rc != SW_MON_HELD) {
            swaywatch_accel_t d;
            FZ_CHECK(swaywatch_accel_t_decode(buf, 0, len, &d) == len);
            FZ_CHECK(isfinite(d.ax) && isfinite(d.ay) && isfinite(d.az));
            FZ_CHECK(fabs(d.ax) <= SW_MON_MAX_ACCEL && fabs(d.ay) <= SW_MON_MAX_ACCEL &&
                     fabs(d.az) <= SW_MON_MAX_ACCEL);
            FZ_CHECK(sw_mon_last_utime(m) == d.utime);
        } else if (rc < 0) {
            FZ_CHECK(why < SW_MON_NREJ);
        }
        /* the counts after every message that was held or that found
         * samples held (confirmed or refuted them), and every 8th: they
         * cost as much as the message (the gate's facts) */
        if (rc == SW_MON_HELD || held > 0 || fed % 8 == 0)
            held = check_counts(m, fed);
        fz_lcm_drain(lcm);
        if (mono >= sw_mon_deadline(m))
            sw_mon_tick(m, mono);
    }
    sw_mon_flush(m);
    fz_lcm_drain(lcm);
    check_counts(m, fed);
    sw_mon_counts_t c;
    sw_mon_counts(m, &c);
    FZ_CHECK(c.held == 0); /* the flush refused what was held */
    FZ_CHECK(c.publish_errors == 0);
    FZ_CHECK(c.states == fz_seen.states && c.alarms == fz_seen.alarms);
    for (size_t k = 0; k < 2; k++) {
        sw_summary_t s;
        FZ_CHECK(sw_engine_summary(sw_mon_engine(m), k, &s) == SW_OK);
        fz_check_summary(&s);
    }
    sw_mon_destroy(m);
    return 0;
}
