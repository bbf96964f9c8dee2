/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_auth.c - authenticated sensors (src/lcm/auth.h, docs/security.md):
 * key files parsed or refused with the line, the MAC as the message format
 * states it (computed here again with libsodium's one-shot HMAC over bytes
 * put together by this test), and a monitor with keys over memq://.
 *
 * The drive is test_forgery.c's: a genuine sensor sends 1 kHz of two
 * brakings that overturn the crate together (either alone does not).  The
 * attack is issue 24's: one forged quiet sample per two genuine ones,
 * stamped 2.5 ms ahead of each.  A monitor with the sensor's key must
 * ignore the forgeries entirely: its engine sees exactly what it sees
 * without them (the same summary, to the bit), TIP and OVERTURNED are
 * raised, and INPUT_CONTESTED (critical) says something else publishes. */
#include <gsl/gsl_errno.h>
#include <lcm/lcm.h>
#include <math.h>
#include <sodium.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* cmocka.h needs these before it. */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
// clang-format on

#include "auth.h"
#include "monitor.h"
#include "swaywatch/swaywatch.h"
#include "swaywatch_accel_t.h"
#include "swaywatch_accel_v1_t.h"
#include "swaywatch_alarm_t.h"

#define NSAMP 4001 /* 4 s at 1 kHz */
#define UTIME0 1700000000000000LL
#define FRESH0 1700000000500000LL /* the sender's freshness: its clock when it started */
#define MAXAL 4096

/* Two keys of id 1 and 2, and a stranger's key of id 1. */
#define KEY1 "000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f"
#define KEY2 "f0e1d2c3b4a5968778695a4b3c2d1e0fffeeddccbbaa99887766554433221100"
#define KEYX "5555555555555555555555555555555555555555555555555555555555555555"
static const char keys_1[] = "1 HMAC-SHA256 HEX:" KEY1 "\n";
static const char keys_12[] =
    "# both, during a change-over\n1 HMAC-SHA256 HEX:" KEY1 "\n2 HMAC-SHA256 HEX:" KEY2 "\n";
static const char keys_2[] = "2 HMAC-SHA256 HEX:" KEY2 "\n";
static const char keys_x[] = "1 HMAC-SHA256 HEX:" KEYX "\n";

static const char *scene_a =
    "[package]\nname = crate-A\nheight = 2.0\nwidth = 0.728\nmass = 1000\n"
    "[alarm]\nwarn_margin = 0.5\ncritical_margin = 0.2\n";

/* m/s^2: two brakings, 8 m/s^2 at 10 rad/s, from 0.2 s and 1.7 s */
static double drive(long k)
{
    const double t = (double)k / 1000.0;
    double a = 0.0;
    for (int i = 0; i < 2; i++) {
        const double t0 = 0.2 + 1.5 * i;
        if (t >= t0 && t <= t0 + M_PI / 10.0)
            a -= 8.0 * sin(10.0 * (t - t0));
    }
    return a;
}

static sw_keyring_t *ring(const char *text)
{
    char msg[256] = "";
    sw_keyring_t *k = sw_keyring_parse(text, strlen(text), "test", msg, sizeof msg);
    if (!k)
        fail_msg("%s", msg);
    return k;
}

/* ---- messages ---------------------------------------------------------------------- */

typedef struct {
    unsigned char b[128];
    size_t len;
} msg_t;

/* A sample signed with key id of keys (keys NULL: accel_t with no MAC). */
static msg_t signed_msg(const sw_keyring_t *keys, int id, const char *channel, int64_t utime,
                        int64_t seq, double ax, int64_t fresh)
{
    swaywatch_accel_t s = {.utime = utime, .seq = seq, .ax = ax, .freshness = fresh};
    if (keys)
        assert_int_equal(sw_auth_sign(keys, id, channel, &s), SW_OK);
    msg_t m;
    const int len = swaywatch_accel_t_encode(m.b, 0, sizeof m.b, &s);
    assert_int_equal(len, SW_AUTH_ACCEL_LEN);
    m.len = (size_t)len;
    return m;
}

/* A sample of a sender without a key: the old layout. */
static msg_t v1_msg(int64_t utime, int64_t seq, double ax)
{
    const swaywatch_accel_v1_t s = {.utime = utime, .seq = seq, .ax = ax};
    msg_t m;
    const int len = swaywatch_accel_v1_t_encode(m.b, 0, sizeof m.b, &s);
    assert_int_equal(len, SW_AUTH_ACCEL_V1_LEN);
    m.len = (size_t)len;
    return m;
}

/* ---- the monitor ------------------------------------------------------------------- */

typedef struct {
    swaywatch_alarm_t al[MAXAL];
    int nal;
} bus_t;

static void on_alarm_msg(const lcm_recv_buf_t *rb, const char *ch, const swaywatch_alarm_t *m,
                         void *user)
{
    (void)rb;
    (void)ch;
    bus_t *b = user;
    if (b->nal < MAXAL)
        b->al[b->nal++] = *m;
}

typedef struct {
    lcm_t *lcm;
    sw_mon_t *mon;
    swaywatch_alarm_t_subscription_t *as;
    sw_scene_t scene;
    bus_t bus;
} rig_t;

static rig_t *rig_new(const sw_keyring_t *keys)
{
    rig_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    sw_scene_init(&r->scene);
    assert_int_equal(sw_scene_parse(&r->scene, scene_a, "test", NULL, NULL), SW_OK);
    assert_int_equal(sw_scene_validate(&r->scene, NULL, "test", NULL, NULL), SW_OK);
    r->lcm = lcm_create("memq://");
    assert_non_null(r->lcm);
    sw_mon_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.vertical = -1;
    mo.hysteresis = -1.0;
    mo.reserve_rate = -1.0; /* the reserve is not what this is about; faster */
    mo.keys = keys;
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    char msg[256] = "";
    r->mon = sw_mon_create(&r->scene, 1, &eo, &mo, r->lcm, msg, sizeof msg);
    assert_non_null(r->mon);
    r->as = swaywatch_alarm_t_subscribe(r->lcm, "SWAY_ALARM", on_alarm_msg, &r->bus);
    swaywatch_alarm_t_subscription_set_queue_capacity(r->as, 0);
    return r;
}

static void rig_free(rig_t *r)
{
    swaywatch_alarm_t_unsubscribe(r->lcm, r->as);
    sw_mon_destroy(r->mon);
    lcm_destroy(r->lcm);
    free(r);
}

static int feed(rig_t *r, const msg_t *m, double mono)
{
    return sw_mon_feed(r->mon, m->b, m->len, 0, mono, NULL);
}

static void finish(rig_t *r)
{
    sw_mon_flush(r->mon);
    while (lcm_handle_timeout(r->lcm, 0) > 0) {
    }
}

static int has(const bus_t *b, int kind, int level)
{
    for (int i = 0; i < b->nal; i++)
        if (b->al[i].kind == kind && b->al[i].level >= level)
            return 1;
    return 0;
}

static int count(const bus_t *b, int kind, int level)
{
    int n = 0;
    for (int i = 0; i < b->nal; i++) n += b->al[i].kind == kind && b->al[i].level == level;
    return n;
}

static int overturn_seen(const bus_t *b)
{
    return has(b, SWAYWATCH_ALARM_T_KIND_TIP, 0) && has(b, SWAYWATCH_ALARM_T_KIND_OVERTURNED, 0);
}

static sw_summary_t summary(rig_t *r)
{
    sw_summary_t s;
    assert_int_equal(sw_engine_summary(sw_mon_engine(r->mon), 0, &s), SW_OK);
    return s;
}

/* The genuine drive, signed with keys' id, sample k. */
static msg_t genuine(const sw_keyring_t *keys, int id, long k)
{
    return signed_msg(keys, id, "ACCEL", UTIME0 + k * 1000, k, drive(k), FRESH0 + k);
}

/* The keyed monitor on the genuine drive alone: what it sees. */
static sw_summary_t clean;

static void test_genuine_signed(void **st)
{
    (void)st;
    sw_keyring_t *keys = ring(keys_1);
    rig_t *r = rig_new(keys);
    for (long k = 0; k < NSAMP; k++) {
        const msg_t m = genuine(keys, 1, k);
        assert_true(feed(r, &m, k * 1e-3) >= 0);
    }
    finish(r);
    assert_true(overturn_seen(&r->bus));
    assert_false(has(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED, 0));
    assert_false(has(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_REJECTED, 0));
    sw_mon_counts_t c;
    sw_mon_counts(r->mon, &c);
    assert_int_equal(c.accepted, NSAMP);
    assert_int_equal(sw_mon_rejected(&c), 0);
    const sw_auth_facts_t *f = sw_mon_auth_facts(r->mon);
    assert_non_null(f);
    assert_int_equal(f->checked, NSAMP);
    assert_int_equal(f->refused[SW_AUTH_OK], NSAMP);
    clean = summary(r);
    assert_true(clean.overturned);
    rig_free(r);
    sw_keyring_destroy(keys);
}

/* The keyed engine's summary is the clean one, to the bit. */
static void assert_clean(rig_t *r)
{
    const sw_summary_t s = summary(r);
    assert_int_equal(s.overturned, clean.overturned);
    assert_true(s.overturn_time == clean.overturn_time);
    assert_true(s.tip_time == clean.tip_time);
    assert_true(s.uplift_time == clean.uplift_time);
    assert_true(s.max_abs_theta == clean.max_abs_theta);
    assert_true(s.min_margin == clean.min_margin);
    assert_int_equal(s.impacts, clean.impacts);
    assert_int_equal(s.steps, clean.steps);
}

/* Issue 24's attack, forged three ways: an accel_t without a MAC, the old
 * layout, and a MAC under a stranger's key of the same id.  The forger's
 * seq copies the genuine one and its freshness runs far ahead (it cannot
 * move the genuine sender's on). */
enum { FORGE_NO_MAC, FORGE_V1, FORGE_OTHER_KEY, FORGE_KINDS };

static void test_interleave_attack_ignored(void **st)
{
    (void)st;
    static const sw_mon_reject why[FORGE_KINDS] = {SW_MON_REJ_UNAUTHENTICATED,
                                                   SW_MON_REJ_UNAUTHENTICATED, SW_MON_REJ_BAD_MAC};
    sw_keyring_t *keys = ring(keys_1), *stranger = ring(keys_x);
    for (int kind = 0; kind < FORGE_KINDS; kind++) {
        rig_t *r = rig_new(keys);
        long forged = 0;
        for (long k = 0; k < NSAMP; k++) {
            const double mono = k * 1e-3;
            const msg_t g = genuine(keys, 1, k);
            assert_true(feed(r, &g, mono) >= 0);
            if (k % 2 == 1) {
                const int64_t u = UTIME0 + k * 1000 + 2500;
                const msg_t f = kind == FORGE_V1 ? v1_msg(u, k, 0.0)
                                : kind == FORGE_NO_MAC
                                    ? signed_msg(NULL, 0, "ACCEL", u, k, 0.0, INT64_MAX - k)
                                    : signed_msg(stranger, 1, "ACCEL", u, k, 0.0, INT64_MAX - k);
                sw_mon_reject w = SW_MON_NREJ;
                assert_int_equal(sw_mon_feed(r->mon, f.b, f.len, 0, mono + 1e-6, &w), SW_EAUTH);
                assert_int_equal(w, why[kind]);
                forged++;
            }
        }
        finish(r);
        assert_true(overturn_seen(&r->bus));
        assert_true(
            has(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED, SWAYWATCH_ALARM_T_LEVEL_CRITICAL));
        sw_mon_counts_t c;
        sw_mon_counts(r->mon, &c);
        assert_int_equal(c.accepted, NSAMP);
        assert_int_equal(c.rejected[why[kind]], forged);
        assert_int_equal(sw_mon_rejected(&c), forged);
        assert_int_equal(c.contests, 0); /* the gate never saw a second timeline */
        assert_int_equal(c.lost, 0);
        assert_int_equal(c.auth_contests, 1);
        const sw_auth_facts_t *f = sw_mon_auth_facts(r->mon);
        assert_int_equal(f->first.where, 3); /* the first forged message was the 3rd fed */
        assert_int_equal(f->first.why, kind == FORGE_OTHER_KEY ? SW_AUTH_BAD_MAC : SW_AUTH_NONE);
        assert_string_equal(f->first.channel, "ACCEL");
        assert_clean(r);
        rig_free(r);
    }
    sw_keyring_destroy(keys);
    sw_keyring_destroy(stranger);
}

/* The same attack on a monitor without keys still ends in an overturn
 * or a critical contest (test_forgery.c): authentication is what makes it
 * ignored.  Here: an unkeyed monitor takes both layouts, and counts the
 * MACs it could not check. */
static void test_unkeyed_takes_both_layouts(void **st)
{
    (void)st;
    sw_keyring_t *keys = ring(keys_1);
    for (int layout = 1; layout <= 2; layout++) {
        rig_t *r = rig_new(NULL);
        for (long k = 0; k < NSAMP; k++) {
            const msg_t m =
                layout == 1 ? v1_msg(UTIME0 + k * 1000, k, drive(k)) : genuine(keys, 1, k);
            assert_true(feed(r, &m, k * 1e-3) >= 0);
        }
        finish(r);
        assert_true(overturn_seen(&r->bus));
        sw_mon_counts_t c;
        sw_mon_counts(r->mon, &c);
        assert_int_equal(c.accepted, NSAMP);
        assert_int_equal(c.macs_unchecked, layout == 2 ? NSAMP : 0);
        assert_null(sw_mon_auth_facts(r->mon));
        rig_free(r);
    }
    sw_keyring_destroy(keys);
}

/* A sender without a key (the old layout) on a keyed monitor: every
 * sample refused, the contest raised; nothing integrated. */
static void test_old_sender_refused_by_keyed(void **st)
{
    (void)st;
    sw_keyring_t *keys = ring(keys_1);
    rig_t *r = rig_new(keys);
    for (long k = 0; k < NSAMP; k++) {
        const msg_t m = v1_msg(UTIME0 + k * 1000, k, drive(k));
        assert_int_equal(feed(r, &m, k * 1e-3), SW_EAUTH);
    }
    finish(r);
    assert_false(has(&r->bus, SWAYWATCH_ALARM_T_KIND_TIP, 0));
    assert_true(
        has(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED, SWAYWATCH_ALARM_T_LEVEL_CRITICAL));
    assert_true(has(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_REJECTED, 0));
    sw_mon_counts_t c;
    sw_mon_counts(r->mon, &c);
    assert_int_equal(c.accepted, 0);
    assert_int_equal(c.rejected[SW_MON_REJ_UNAUTHENTICATED], NSAMP);
    rig_free(r);
    sw_keyring_destroy(keys);
}

/* Genuine messages recorded and played again (the bytes as they were, MAC
 * and all): each copy refused as replayed, whether it comes 50 ms after
 * its original or seconds later; the drive's verdict is the clean one. */
static void test_replayed_refused(void **st)
{
    (void)st;
    sw_keyring_t *keys = ring(keys_1);
    rig_t *r = rig_new(keys);
    long copies = 0;
    for (long k = 0; k < NSAMP; k++) {
        const double mono = k * 1e-3;
        const msg_t g = genuine(keys, 1, k);
        assert_true(feed(r, &g, mono) >= 0);
        if (k >= 50 && k % 3 == 0) {
            const msg_t old = genuine(keys, 1, k - 50);
            sw_mon_reject w = SW_MON_NREJ;
            assert_int_equal(sw_mon_feed(r->mon, old.b, old.len, 0, mono + 1e-6, &w), SW_EAUTH);
            assert_int_equal(w, SW_MON_REJ_REPLAYED);
            copies++;
        }
        if (k == 3000) { /* and the first brake again, a burst of it */
            for (long j = 200; j < 520; j++) {
                const msg_t old = genuine(keys, 1, j);
                assert_int_equal(feed(r, &old, mono + 2e-6), SW_EAUTH);
                copies++;
            }
        }
    }
    /* the last message itself, again */
    const msg_t last = genuine(keys, 1, NSAMP - 1);
    assert_int_equal(feed(r, &last, NSAMP * 1e-3), SW_EAUTH);
    copies++;
    finish(r);
    sw_mon_counts_t c;
    sw_mon_counts(r->mon, &c);
    assert_int_equal(c.accepted, NSAMP);
    assert_int_equal(c.rejected[SW_MON_REJ_REPLAYED], copies);
    assert_int_equal(sw_mon_rejected(&c), copies);
    assert_true(overturn_seen(&r->bus));
    assert_true(
        has(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED, SWAYWATCH_ALARM_T_LEVEL_CRITICAL));
    assert_clean(r);
    rig_free(r);
    sw_keyring_destroy(keys);
}

/* A wrong key: the same id, another secret (bad_mac); an id the monitor
 * does not have (unknown_key).  Altered bytes and another channel: bad_mac. */
static void test_wrong_key_and_altered(void **st)
{
    (void)st;
    sw_keyring_t *k1 = ring(keys_1), *k2 = ring(keys_2), *kx = ring(keys_x);
    rig_t *r = rig_new(k1);
    msg_t m = signed_msg(kx, 1, "ACCEL", UTIME0, 0, 0.0, FRESH0);
    sw_mon_reject w = SW_MON_NREJ;
    assert_int_equal(sw_mon_feed(r->mon, m.b, m.len, 0, 0.0, &w), SW_EAUTH);
    assert_int_equal(w, SW_MON_REJ_BAD_MAC);
    m = signed_msg(k2, 2, "ACCEL", UTIME0, 0, 0.0, FRESH0);
    assert_int_equal(sw_mon_feed(r->mon, m.b, m.len, 0, 0.0, &w), SW_EAUTH);
    assert_int_equal(w, SW_MON_REJ_UNKNOWN_KEY);
    /* one bit of any byte the MAC covers, or of the MAC */
    const msg_t good = signed_msg(k1, 1, "ACCEL", UTIME0, 0, -3.0, FRESH0);
    for (size_t i = 8; i < good.len; i++) {
        if (i == 56)
            continue; /* key_id: another key, unknown_key (below) */
        m = good;
        m.b[i] ^= 0x04;
        assert_int_equal(sw_mon_feed(r->mon, m.b, m.len, 0, 0.0, &w), SW_EAUTH);
        if (w != SW_MON_REJ_BAD_MAC)
            fail_msg("byte %zu altered: refused as %s", i, sw_mon_reject_name(w));
    }
    m = good;
    m.b[56] = 9;
    assert_int_equal(sw_mon_feed(r->mon, m.b, m.len, 0, 0.0, &w), SW_EAUTH);
    assert_int_equal(w, SW_MON_REJ_UNKNOWN_KEY);
    /* signed for ACCEL, received on ACCEL_B (a regex subscription) */
    assert_int_equal(sw_mon_feed_on(r->mon, "ACCEL_B", good.b, good.len, 0, 0.0, &w), SW_EAUTH);
    assert_int_equal(w, SW_MON_REJ_BAD_MAC);
    /* and the right channel at last: every refusal left its freshness alone */
    assert_true(sw_mon_feed_on(r->mon, "ACCEL", good.b, good.len, 0, 0.0, &w) >= 0);
    const sw_auth_facts_t *f = sw_mon_auth_facts(r->mon);
    assert_int_equal(f->refused[SW_AUTH_OK], 1);
    assert_int_equal(f->last.why, SW_AUTH_BAD_MAC);
    assert_string_equal(f->last.channel, "ACCEL_B");
    assert_int_equal(f->first.key_id, 1);
    rig_free(r);
    sw_keyring_destroy(k1);
    sw_keyring_destroy(k2);
    sw_keyring_destroy(kx);
}

/* A change of key: the monitor holds ids 1 and 2; the sender goes from 1
 * to 2 mid-drive.  Every sample is taken; a copy of a key-1 message after
 * the change is still refused.  Then the monitor's file loses key 1
 * (sw_mon_set_keys, as a reload does): key-1 samples are unknown_key,
 * key-2 ones go on, their freshness remembered. */
static void test_rotation(void **st)
{
    (void)st;
    sw_keyring_t *k12 = ring(keys_12), *k2 = ring(keys_2);
    assert_int_equal(sw_keyring_size(k12), 2);
    assert_int_equal(sw_keyring_signer(k12), 2);
    rig_t *r = rig_new(k12);
    for (long k = 0; k < NSAMP; k++) {
        const msg_t m = genuine(k12, k < 1000 ? 1 : 2, k);
        assert_true(feed(r, &m, k * 1e-3) >= 0);
        if (k == 1500) {
            const msg_t old = genuine(k12, 1, 999);
            assert_int_equal(feed(r, &old, k * 1e-3), SW_EAUTH);
        }
        if (k == 2000)
            assert_int_equal(sw_mon_set_keys(r->mon, k2), SW_OK);
        if (k == 2500) {
            sw_mon_reject w = SW_MON_NREJ;
            const msg_t m1 =
                signed_msg(k12, 1, "ACCEL", UTIME0 + k * 1000 + 500, k, 0.0, FRESH0 + 10 * NSAMP);
            assert_int_equal(sw_mon_feed(r->mon, m1.b, m1.len, 0, k * 1e-3, &w), SW_EAUTH);
            assert_int_equal(w, SW_MON_REJ_UNKNOWN_KEY);
            const msg_t old2 = genuine(k12, 2, 2400);
            assert_int_equal(sw_mon_feed(r->mon, old2.b, old2.len, 0, k * 1e-3, &w), SW_EAUTH);
            assert_int_equal(w, SW_MON_REJ_REPLAYED);
        }
    }
    finish(r);
    sw_mon_counts_t c;
    sw_mon_counts(r->mon, &c);
    assert_int_equal(c.accepted, NSAMP);
    assert_int_equal(c.rejected[SW_MON_REJ_REPLAYED], 2);
    assert_int_equal(c.rejected[SW_MON_REJ_UNKNOWN_KEY], 1);
    assert_clean(r);
    rig_free(r);
    /* the keys cannot be turned off, nor on, while a monitor runs */
    rig_t *u = rig_new(NULL);
    assert_int_equal(sw_mon_set_keys(u->mon, k2), SW_EINVAL);
    rig_free(u);
    sw_keyring_destroy(k12);
    sw_keyring_destroy(k2);
}

/* Forged samples in two bursts, 4.5 s apart: INPUT_CONTESTED critical when
 * each begins, info once none came for SW_MON_AUTH_QUIET s after it. */
static void test_contest_bursts(void **st)
{
    (void)st;
    sw_keyring_t *keys = ring(keys_1);
    rig_t *r = rig_new(keys);
    for (long k = 0; k < 10000; k++) {
        const double mono = k * 1e-3;
        const msg_t g = signed_msg(keys, 1, "ACCEL", UTIME0 + k * 1000, k, 0.0, FRESH0 + k);
        feed(r, &g, mono);
        if ((k >= 1000 && k < 1500) || (k >= 6000 && k < 6100)) {
            const msg_t f = v1_msg(UTIME0 + k * 1000 + 300, k, 9.0);
            feed(r, &f, mono);
        }
        if (mono >= sw_mon_deadline(r->mon))
            sw_mon_tick(r->mon, mono);
    }
    sw_mon_tick(r->mon, 10.0);
    finish(r);
    assert_int_equal(
        count(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED, SWAYWATCH_ALARM_T_LEVEL_CRITICAL),
        2);
    assert_int_equal(
        count(&r->bus, SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED, SWAYWATCH_ALARM_T_LEVEL_INFO), 2);
    sw_mon_counts_t c;
    sw_mon_counts(r->mon, &c);
    assert_int_equal(c.auth_contests, 2);
    assert_int_equal(c.accepted, 10000);
    assert_int_equal(c.rejected[SW_MON_REJ_UNAUTHENTICATED], 600);
    /* the critical alarm names the channel and the reason */
    for (int i = 0; i < r->bus.nal; i++)
        if (r->bus.al[i].kind == SWAYWATCH_ALARM_T_KIND_INPUT_CONTESTED &&
            r->bus.al[i].level == SWAYWATCH_ALARM_T_LEVEL_CRITICAL)
            assert_non_null(strstr((const char *)r->bus.al[i].text, "on ACCEL (unauthenticated)"));
    rig_free(r);
    sw_keyring_destroy(keys);
}

/* ---- keys and MACs ---------------------------------------------------------------- */

/* The MAC is what docs/lcm.md states: the first 16 bytes of
 * HMAC-SHA-256(key, channel || 0 || the 57 bytes before the MAC), here
 * computed with libsodium's one-shot call over bytes this test puts
 * together (the key from its hex, not through the key file parser). */
static void test_mac_as_stated(void **st)
{
    (void)st;
    assert_true(sodium_init() >= 0);
    sw_keyring_t *keys = ring(keys_12);
    static const char *const hex[2] = {KEY1, KEY2};
    static const char *const channels[] = {"ACCEL", "A", "SENSOR_REAR_LEFT_ACCEL_0123456789"};
    for (int id = 1; id <= 2; id++)
        for (size_t c = 0; c < sizeof channels / sizeof channels[0]; c++) {
            const msg_t m =
                signed_msg(keys, id, channels[c], UTIME0 + 12345, 77, -4.25, FRESH0 + 99 * id);
            unsigned char key[32];
            assert_int_equal(sodium_hex2bin(key, sizeof key, hex[id - 1], 64, NULL, NULL, NULL), 0);
            unsigned char in[128], out[crypto_auth_hmacsha256_BYTES];
            const size_t cl = strlen(channels[c]);
            memcpy(in, channels[c], cl);
            in[cl] = 0;
            memcpy(in + cl + 1, m.b, 57);
            crypto_auth_hmacsha256(out, in, cl + 1 + 57, key);
            assert_memory_equal(m.b + 57, out, 16);
            assert_int_equal(m.b[56], id); /* key_id, just before the MAC */
        }
    sw_keyring_destroy(keys);
}

/* Key files: comments, blank lines, CRLF, tabs and case are fine; every
 * other line is refused with its number, and the key never quoted. */
static void test_key_files(void **st)
{
    (void)st;
    static const char good[] = "# swaywatch keys\r\n\r\n  3\thmac-sha256   hex:" KEY1
                               "  \r\n   # the new one\n200 HMAC-SHA256 HEX:" KEY2;
    char msg[256];
    sw_keyring_t *k = sw_keyring_parse(good, strlen(good), "keys", msg, sizeof msg);
    assert_non_null(k);
    assert_int_equal(sw_keyring_size(k), 2);
    assert_int_equal(sw_keyring_id(k, 0), 3);
    assert_int_equal(sw_keyring_id(k, 1), 200);
    assert_int_equal(sw_keyring_signer(k), 200);
    assert_true(sw_keyring_has(k, 3) && sw_keyring_has(k, 200) && !sw_keyring_has(k, 1));
    sw_keyring_destroy(k);

    static const struct {
        const char *text;
        const char *says;
    } bad[] = {
        {"", "no key in it"},
        {"# only a comment\n\n", "no key in it"},
        {"1 HMAC-SHA256\n", "keys:1: expected 'ID HMAC-SHA256 HEX:KEY'"},
        {"1 HMAC-SHA256 HEX:" KEY1 " extra\n", "keys:1: expected"},
        {"\n0 HMAC-SHA256 HEX:" KEY1 "\n",
         "keys:2: key id '0' is not a whole number from 1 to 255"},
        {"256 HMAC-SHA256 HEX:" KEY1 "\n", "keys:1: key id '256'"},
        {"-1 HMAC-SHA256 HEX:" KEY1 "\n", "keys:1: key id '-1'"},
        {"1x HMAC-SHA256 HEX:" KEY1 "\n", "keys:1: key id '1x'"},
        {"1 HMAC-SHA256 HEX:" KEY1 "\n1 HMAC-SHA256 HEX:" KEY2 "\n",
         "keys:2: key id 1 is given twice (line 1 and here)"},
        {"1 SHA1 HEX:" KEY1 "\n", "keys:1: key type 'SHA1': only HMAC-SHA256"},
        {"1 HMAC-SHA256 " KEY1 "\n", "keys:1: the key is not HEX: and 64 hexadecimal digits"},
        {"1 HMAC-SHA256 HEX:" KEY1 "00\n", "keys:1: the key is not HEX:"},
        {"1 HMAC-SHA256 HEX:00112233\n", "keys:1: the key is not HEX:"},
        {"1 HMAC-SHA256 HEX:g00102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1\n",
         "keys:1: the key is not HEX:"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        msg[0] = '\0';
        k = sw_keyring_parse(bad[i].text, strlen(bad[i].text), "keys", msg, sizeof msg);
        if (k || !strstr(msg, bad[i].says))
            fail_msg("case %zu: '%s', expected '%s'", i, msg, bad[i].says);
        if (strstr(msg, "0102030405") || strstr(msg, "e1d2c3b4"))
            fail_msg("case %zu: the key is quoted: %s", i, msg);
    }
    /* a NUL byte, a line too long, a file too long */
    static const char nul[] = "1 HMAC-SHA256 HEX:" KEY1 "\n\0\n";
    assert_null(sw_keyring_parse(nul, sizeof nul - 1, "keys", msg, sizeof msg));
    assert_non_null(strstr(msg, "keys:2: a NUL byte"));
    char *big = malloc(SW_AUTH_FILE_MAX + 2);
    assert_non_null(big);
    memset(big, '#', SW_AUTH_FILE_MAX + 1);
    big[SW_AUTH_FILE_MAX + 1] = '\0';
    assert_null(sw_keyring_parse(big, 1000, "keys", msg, sizeof msg));
    assert_non_null(strstr(msg, "keys:1: line too long"));
    assert_null(sw_keyring_parse(big, SW_AUTH_FILE_MAX + 1, "keys", msg, sizeof msg));
    assert_non_null(strstr(msg, "not a key file"));
    free(big);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_key_files),
        cmocka_unit_test(test_mac_as_stated),
        cmocka_unit_test(test_genuine_signed),
        cmocka_unit_test(test_interleave_attack_ignored),
        cmocka_unit_test(test_unkeyed_takes_both_layouts),
        cmocka_unit_test(test_old_sender_refused_by_keyed),
        cmocka_unit_test(test_replayed_refused),
        cmocka_unit_test(test_wrong_key_and_altered),
        cmocka_unit_test(test_rotation),
        cmocka_unit_test(test_contest_bursts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
