/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_eventlog.c - the lcm-logger reader (eventlog.h) on crafted logs:
 * the events it yields are the accel channel's, at the offsets and with
 * the times and bytes written, the other channel's and a damaged one's
 * counted and skipped, strict stopping at the damage and going on after
 * it; the work of resynchronising is linear in the size of the log
 * however many length fields are wrong, counted as the bytes the process
 * reads (/proc/self/io: what the reader really asked of the kernel, not
 * what it says it did); every good event is found.  Speed itself is
 * measured in bench/, not here. */
#include <lcm/lcm.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* cmocka.h needs these before it. */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
// clang-format on

#include "eventlog.h"
#include "monitor.h"
#include "swaywatch/swaywatch.h"
#include "swaywatch_accel_v1_t.h"

#define UTIME0 1700000000000000LL

static const char *scene_text =
    "[package]\nname = crate-A\nheight = 2.0\nwidth = 0.728\nmass = 1000\n";

static void put32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static void put64(unsigned char *p, uint64_t v)
{
    put32(p, (uint32_t)(v >> 32));
    put32(p + 4, (uint32_t)v);
}

/* One event: header, "ACCEL", an accel_t of a sender without a key; datalen as given (the real
 * length if < 0).  Returns its size. */
static size_t event(unsigned char *p, long k, int64_t datalen)
{
    swaywatch_accel_v1_t s = {.utime = UTIME0 + k * 1000, .seq = k, .ax = 0.0};
    unsigned char data[64];
    int len = swaywatch_accel_v1_t_encode(data, 0, sizeof data, &s);
    assert_true(len == 48);
    put32(p, SW_LCMLOG_SYNC);
    put64(p + 4, (uint64_t)k);
    put64(p + 12, (uint64_t)s.utime);
    put32(p + 20, 5);
    put32(p + 24, (uint32_t)(datalen < 0 ? len : datalen));
    memcpy(p + 28, "ACCEL", 5);
    memcpy(p + 33, data, (size_t)len);
    return 33 + (size_t)len;
}

/* A log of n events in which every other one has a wrong data length:
 * alternately past the end of the file (which a reader that trusts it
 * reads to the end) and inside the file but not on an event's end.
 * *good gets the number of intact events. */
static void write_log(const char *path, long n, long *good)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    unsigned char ev[128];
    *good = 0;
    for (long k = 0; k < n; k++) {
        int64_t dl = -1;
        if (k % 4 == 1)
            dl = 0x0ffffff0; /* past the end, under LCM's 256 MB */
        else if (k % 4 == 3)
            dl = 48 + 81 * 3 + 7; /* lands in the middle of an event */
        else
            (*good)++;
        size_t len = event(ev, k, dl);
        assert_true(fwrite(ev, 1, len, f) == len);
    }
    assert_int_equal(fclose(f), 0);
}

/* ACCEL, OTHER, a damaged ACCEL, ACCEL: what sw_lcmlog_next() yields. */
static void check_next(int strict)
{
    char path[] = "/tmp/sw-eventlog-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    unsigned char buf[4][128];
    size_t len[4];
    len[0] = event(buf[0], 0, -1);
    len[1] = event(buf[1], 1, -1);
    memcpy(buf[1] + 28, "OTHER", 5);
    len[2] = event(buf[2], 2, 48 + 7); /* ends inside the next event */
    len[3] = event(buf[3], 3, -1);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    for (int i = 0; i < 4; i++) assert_true(fwrite(buf[i], 1, len[i], f) == len[i]);
    assert_int_equal(fclose(f), 0);

    const sw_lcmlog_opts_t o = {.strict = strict};
    int err = 0;
    sw_lcmlog_t *log = sw_lcmlog_open(path, &o, &err);
    assert_non_null(log);
    sw_lcmlog_event_t ev;
    assert_int_equal(sw_lcmlog_next(log, &ev), 1);
    assert_int_equal(ev.offset, 0);
    assert_int_equal(ev.timestamp, UTIME0);
    assert_true(ev.rx == 0.0);
    assert_string_equal(ev.channel, "ACCEL");
    assert_int_equal(ev.len, 48);
    assert_memory_equal(ev.data, buf[0] + 33, 48);
    if (strict)
        assert_int_equal(sw_lcmlog_next(log, &ev), SW_EPARSE);
    assert_int_equal(sw_lcmlog_next(log, &ev), 1);
    assert_int_equal(ev.offset, (long long)(len[0] + len[1] + len[2]));
    assert_int_equal(ev.timestamp, UTIME0 + 3000);
    assert_true(ev.rx == 0.003); /* 3000 us / 1e6, correctly rounded */
    assert_memory_equal(ev.data, buf[3] + 33, 48);
    assert_int_equal(sw_lcmlog_next(log, &ev), 0);
    assert_int_equal(sw_lcmlog_next(log, &ev), 0); /* and stays at the end */
    sw_lcmlog_counts_t c;
    sw_lcmlog_counts(log, &c);
    assert_int_equal(c.events, 3);
    assert_int_equal(c.on_channel, 2);
    assert_int_equal(c.other_channels, 1);
    assert_int_equal(c.corrupt, 1);
    assert_int_equal(c.first_corrupt, (long long)(len[0] + len[1]));
    assert_int_equal(c.corrupt_bytes, (long long)len[2]);
    assert_int_equal(c.first_utime, UTIME0);
    assert_int_equal(c.last_utime, UTIME0 + 3000);
    sw_lcmlog_close(log);
    remove(path);
}

static void test_next(void **state)
{
    (void)state;
    check_next(0);
    check_next(1);
}

/* Bytes this process has read through read(2) and its kin. */
static long long rchar(void)
{
    FILE *f = fopen("/proc/self/io", "r");
    if (!f)
        return -1;
    char line[128];
    long long v = -1;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "rchar: %lld", &v) == 1)
            break;
    fclose(f);
    return v;
}

static sw_mon_t *monitor(sw_scene_t *sc)
{
    sw_scene_init(sc);
    assert_int_equal(sw_scene_parse(sc, scene_text, "test", NULL, NULL), SW_OK);
    assert_int_equal(sw_scene_validate(sc, NULL, "test", NULL, NULL), SW_OK);
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    sw_mon_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.vertical = -1;
    mo.max_jump = -1.0;
    char msg[256] = "";
    sw_mon_t *m = sw_mon_create(sc, 1, &eo, &mo, NULL, msg, sizeof msg);
    assert_non_null(m);
    return m;
}

/* Bytes read per byte of log, for a log of n events. */
static double read_ratio(long n)
{
    char path[] = "/tmp/sw-eventlog-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    long good;
    write_log(path, n, &good);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    assert_int_equal(fseek(f, 0, SEEK_END), 0);
    const double size = (double)ftell(f);
    fclose(f);

    sw_scene_t sc;
    sw_mon_t *m = monitor(&sc);
    int err = 0;
    sw_lcmlog_t *log = sw_lcmlog_open(path, NULL, &err);
    assert_non_null(log);
    const long long before = rchar();
    assert_true(before >= 0);
    assert_int_equal(sw_mon_feed_log(m, log, 0), SW_OK);
    const long long after = rchar();
    sw_lcmlog_counts_t c;
    sw_lcmlog_counts(log, &c);
    sw_lcmlog_close(log);
    sw_mon_destroy(m);
    remove(path);

    const double ratio = (double)(after - before) / size;
    print_message("%ld events, %.0f bytes: %.2f bytes read per byte of log\n", n, size, ratio);
    /* Each byte read about once (a few times at most), at every size: a
     * reader that reads to the end at each bad length reads the log
     * hundreds of times over, more the longer it is. */
    assert_true(ratio < 4.0);
    /* Every intact event is found; each damaged one is a region of its
     * own. */
    assert_int_equal(c.events, good);
    assert_int_equal(c.on_channel, good);
    assert_int_equal(c.corrupt, n - good);
    return ratio;
}

static void test_resync_is_linear(void **state)
{
    (void)state;
    double first = 0.0;
    for (long n = 2000; n <= 16000; n *= 2) {
        const double r = read_ratio(n);
        if (n == 2000)
            first = r;
        else
            assert_true(r < 1.5 * first + 0.1);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_next),
        cmocka_unit_test(test_resync_is_linear),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
