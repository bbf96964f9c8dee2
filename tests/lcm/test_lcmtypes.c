/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_lcmtypes.c - the generated C code of the swaywatch LCM types:
 * encode/decode round trips, fixed sizes, and what the decoders do with
 * bad bytes (the monitor relies on each of these). */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <string.h>

/* cmocka.h needs these before it. */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
// clang-format on

#include "swaywatch_accel_t.h"
#include "swaywatch_accel_v1_t.h"
#include "swaywatch_alarm_t.h"
#include "swaywatch_state_t.h"

static void test_accel_round_trip(void **st)
{
    (void)st;
    swaywatch_accel_t a = {.utime = 1700000000123456LL,
                           .seq = 42,
                           .ax = -3.25,
                           .ay = 1e-300,
                           .az = -0.0,
                           .freshness = 0x0102030405060708LL,
                           .key_id = 200,
                           .mac = {-1, 2, -3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, -128}};
    unsigned char buf[256];
    int len = swaywatch_accel_t_encode(buf, 0, sizeof buf, &a);
    /* 8-byte fingerprint + 2 int64 + 3 double + freshness, key id and a
     * 16-byte MAC, whatever the values. */
    assert_int_equal(len, 8 + 16 + 24 + 8 + 1 + 16);
    assert_int_equal(swaywatch_accel_t_encoded_size(&a), len);
    swaywatch_accel_t b;
    memset(&b, 0xff, sizeof b);
    assert_int_equal(swaywatch_accel_t_decode(buf, 0, len, &b), len);
    assert_true(b.utime == a.utime && b.seq == a.seq);
    assert_true(b.ax == a.ax && b.ay == a.ay && b.az == a.az && signbit(b.az));
    assert_true(b.freshness == a.freshness && b.key_id == 200);
    assert_memory_equal(b.mac, a.mac, sizeof a.mac);
    /* Big-endian on the wire: utime follows the fingerprint; the fields
     * the MAC covers are the first 57 bytes, the MAC the last 16. */
    assert_int_equal(buf[8], 0x00);
    assert_int_equal(buf[15], (unsigned char)(a.utime & 0xff));
    assert_int_equal(buf[48], 0x01);
    assert_int_equal(buf[55], 0x08);
    assert_int_equal(buf[56], 200);
    assert_int_equal(buf[57], 0xff);
    assert_int_equal(buf[72], 0x80);
    swaywatch_accel_t_decode_cleanup(&b);
}

/* The layout of senders without a key: accel_t of 0.1.0, field for field;
 * the two fingerprints differ, so neither decoder misreads the other's
 * messages. */
static void test_accel_v1(void **st)
{
    (void)st;
    const swaywatch_accel_v1_t a = {.utime = 7, .seq = -1, .ax = 1.5, .ay = -2.5, .az = 0.25};
    const swaywatch_accel_t b = {.utime = 7, .seq = -1, .ax = 1.5, .ay = -2.5, .az = 0.25};
    unsigned char va[128], vb[128];
    const int la = swaywatch_accel_v1_t_encode(va, 0, sizeof va, &a);
    const int lb = swaywatch_accel_t_encode(vb, 0, sizeof vb, &b);
    assert_int_equal(la, 48);
    assert_int_equal(lb, 73);
    assert_memory_not_equal(va, vb, 8);
    assert_memory_equal(va + 8, vb + 8, 40); /* the same fields, in the same place */
    swaywatch_accel_t d;
    swaywatch_accel_v1_t e;
    assert_true(swaywatch_accel_t_decode(va, 0, la, &d) < 0);
    assert_true(swaywatch_accel_v1_t_decode(vb, 0, lb, &e) < 0);
    assert_true(__swaywatch_accel_t_get_hash() != __swaywatch_accel_v1_t_get_hash());
}

static void test_state_round_trip(void **st)
{
    (void)st;
    swaywatch_state_t s;
    memset(&s, 0, sizeof s);
    s.utime = 5;
    s.seq = 7;
    strcpy((char *)s.name, "crate-A");
    s.model = SWAYWATCH_STATE_T_MODEL_CUSHION;
    s.phase = SWAYWATCH_STATE_T_PHASE_ROCKING;
    s.side = -1;
    s.theta = -0.125;
    s.theta_dot = 2.5;
    s.u = 0.01;
    s.z_b = 0.002;
    s.margin = 0.4;
    s.margin_bound = 0.3;
    s.uplift_ratio = 1.2;
    s.a_g = -4.0;
    s.reserve_g = 0.35;
    s.plane = SWAYWATCH_STATE_T_PLANE_LATERAL;
    unsigned char buf[512];
    int len = swaywatch_state_t_encode(buf, 0, sizeof buf, &s);
    /* fingerprint, utime + seq, name, model + phase + side, nine doubles, plane */
    assert_int_equal(len, 8 + 16 + 64 + 3 + 9 * 8 + 1);
    swaywatch_state_t t;
    assert_int_equal(swaywatch_state_t_decode(buf, 0, len, &t), len);
    assert_memory_equal(&s.name, &t.name, sizeof s.name);
    assert_true(t.utime == 5 && t.seq == 7 && t.model == 2 && t.phase == 1 && t.side == -1);
    assert_true(t.theta == s.theta && t.theta_dot == s.theta_dot && t.u == s.u);
    assert_true(t.z_b == s.z_b && t.margin == s.margin && t.margin_bound == s.margin_bound);
    assert_true(t.uplift_ratio == s.uplift_ratio && t.a_g == s.a_g);
    assert_true(t.reserve_g == s.reserve_g);
    assert_int_equal(t.plane, 1);
}

static void test_alarm_round_trip(void **st)
{
    (void)st;
    swaywatch_alarm_t a;
    memset(&a, 0, sizeof a);
    a.utime = -1;
    a.seq = 1LL << 40;
    strcpy((char *)a.name, "crate-B");
    a.kind = SWAYWATCH_ALARM_T_KIND_CRITICAL;
    a.level = SWAYWATCH_ALARM_T_LEVEL_CRITICAL;
    strcpy((char *)a.text, "margin 0.150 < critical 0.200");
    a.theta = 0.3;
    a.margin = 0.15;
    a.reserve_g = 0.2;
    a.plane = SWAYWATCH_ALARM_T_PLANE_LATERAL;
    unsigned char buf[512];
    int len = swaywatch_alarm_t_encode(buf, 0, sizeof buf, &a);
    /* fingerprint, utime + seq, name, kind + level, text, three doubles, plane */
    assert_int_equal(len, 8 + 16 + 64 + 2 + 128 + 24 + 1);
    swaywatch_alarm_t b;
    memset(&b, 0, sizeof b); /* padding compares too */
    assert_int_equal(swaywatch_alarm_t_decode(buf, 0, len, &b), len);
    assert_memory_equal(&a, &b, sizeof a);
}

/* What the monitor's raw subscription has to catch itself. */
static void test_bad_bytes(void **st)
{
    (void)st;
    swaywatch_accel_t a = {.utime = 1, .seq = 2, .ax = 3, .ay = 4, .az = 5}, b;
    swaywatch_state_t s;
    memset(&s, 0, sizeof s);
    unsigned char buf[512];
    int len = swaywatch_accel_t_encode(buf, 0, sizeof buf, &a);
    for (int cut = 0; cut < len; cut++) assert_true(swaywatch_accel_t_decode(buf, 0, cut, &b) < 0);
    buf[3] ^= 0x10; /* fingerprint */
    assert_true(swaywatch_accel_t_decode(buf, 0, len, &b) < 0);
    buf[3] ^= 0x10;
    /* Trailing bytes are accepted by the decoder: the caller compares the
     * length consumed with the length received. */
    assert_int_equal(swaywatch_accel_t_decode(buf, 0, len + 8, &b), len);
    /* Another type's message is refused by its fingerprint. */
    int slen = swaywatch_state_t_encode(buf, 0, sizeof buf, &s);
    assert_true(swaywatch_accel_t_decode(buf, 0, slen, &b) < 0);
    assert_true(__swaywatch_accel_t_get_hash() != __swaywatch_state_t_get_hash());
    assert_true(__swaywatch_alarm_t_get_hash() != __swaywatch_state_t_get_hash());
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_accel_round_trip), cmocka_unit_test(test_accel_v1),
        cmocka_unit_test(test_state_round_trip), cmocka_unit_test(test_alarm_round_trip),
        cmocka_unit_test(test_bad_bytes)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
