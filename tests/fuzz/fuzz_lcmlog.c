/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_lcmlog.c - libFuzzer target for the lcm-logger reader behind
 * `swaywatch replay LOG.lcmlog` (eventlog.h): any bytes as a log file,
 * read through its public API into a monitor core watching a bare crate (no
 * publishing; the models are the other targets' matter, the file's bytes
 * this one's).
 *
 * Input: 1 byte of options (strict; the accel channel: ACCEL, a regex
 * matching it and others, or a channel no event has; the monitor's skew
 * check), then the file's bytes.  The seeds are lcm-logger logs (written
 * with LCM's event-log API) and damaged copies of them.
 *
 * The work per input is bounded where it grows with the samples, not
 * where the bytes are read.  The reader and the accel_t decoders see the
 * whole file (at most MAX_FILE bytes, some 200 events); the monitor's
 * input gate and engine, half of an input's time when they took every
 * event, see the events up to the MAX_TAKES-th sample the engine takes,
 * or the first beyond MAX_SPAN of sample time after the first sample, or
 * the one that brings the engine to FZ_STEP_BUDGET steps.  Whichever
 * comes first sets the reader's stop flag (as a signal does), so that
 * sw_mon_feed_log() returns as a stopped replay does; the target then
 * clears the flag and reads the rest of the file itself, decoding every
 * event on the channel.  96 samples are past the gate's warm-up (its
 * first 64 intervals teach it the pace; its gap, pace and ring code runs
 * after them); the seeds' pulse has 120.  A refused sample does not count
 * (it costs the gate less than a take, and the file holds at most some
 * 200 events).  The engine steps STEP at most, one step per sample of
 * the seeds' 200 Hz where the default 1 ms made five (the crate's motion
 * is fuzz_scene's matter, not this target's).  Gaps are bridged up to
 * FZ_MAX_BRIDGE, and no reserve is kept (fuzz.h).
 *
 * Checks: the log opens (it is a readable file); the monitor's read ends
 * with SW_OK, or with strict SW_EPARSE / SW_EINVAL; a read stopped early
 * says so, and only once the flag was set; every event on the channel
 * reached the monitor (received = on_channel); received = accepted +
 * rejected + held, and after sw_mon_flush() nothing is held; corrupted
 * regions are counted when reading did not end cleanly; the read resumed
 * after the stop goes on to the end of the file (SW_EPARSE at each
 * corrupted region with strict), and every event it yields decodes as an
 * accel_t in one of its layouts using no more bytes than it has, or does
 * not; at the end, events = on_channel + other_channels. */
#define _GNU_SOURCE /* memfd_create */
#include <signal.h>
#include <stdint.h>
#include <sys/mman.h>
#include <unistd.h>

#include "../testutil.h"
#include "eventlog.h"
#include "fuzz.h"
#include "monitor.h"

#define MAX_FILE (16 * 1024) /* bytes of the log; the rest of an input is not read */
#define MAX_TAKES 96         /* samples the engine takes before the read is stopped */
#define MAX_SPAN 1.0         /* s of sample time after the first sample taken */
#define STEP 0.005           /* s, the engine's largest step: one per sample at 200 Hz */

/* The file the reader opens: one per process, rewritten for each input,
 * opened again through /proc/self/fd.  In memory (memfd_create): a file
 * on disk truncated and rewritten for every input made the filesystem
 * write it out at every close, and the target wait for it (it used a
 * quarter of a core where the others used two thirds); an unlinked
 * temporary file where there is no memfd. */
static int file_fd = -1;
static char file_path[64];

static int write_file(const uint8_t *data, size_t size)
{
    if (file_fd < 0) {
        file_fd = memfd_create("fuzz_lcmlog", 0);
        if (file_fd < 0) {
            char tmpl[] = "/tmp/fuzz_lcmlog.XXXXXX";
            file_fd = mkstemp(tmpl);
            if (file_fd < 0)
                return -1;
            unlink(tmpl);
        }
        snprintf(file_path, sizeof file_path, "/proc/self/fd/%d", file_fd);
    }
    if (ftruncate(file_fd, 0) != 0)
        return -1;
    size_t done = 0;
    while (done < size) {
        ssize_t w = pwrite(file_fd, data + done, size - done, (off_t)done);
        if (w <= 0)
            return -1;
        done += (size_t)w;
    }
    return 0;
}

/* Stops the read once a cap is reached (the top of this file). */
typedef struct {
    sw_mon_t *m;
    long takes;
    volatile sig_atomic_t stop;
} budget_t;

static void on_take(void *user, double t, double a_g, double a_z, int restart)
{
    (void)a_g, (void)a_z, (void)restart;
    budget_t *bu = user;
    if (++bu->takes >= MAX_TAKES || !(t <= MAX_SPAN) ||
        fz_steps(sw_mon_engine(bu->m)) >= FZ_STEP_BUDGET)
        bu->stop = 1;
}

static sw_mon_t *make(uint8_t o, budget_t *bu)
{
    sw_mon_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.vertical = -1;
    mo.max_skew = (o >> 3) & 1 ? 10.0 : 0.0;
    mo.hysteresis = -1.0;
    mo.reserve_rate = -1.0;
    mo.max_bridge = FZ_MAX_BRIDGE;
    mo.on_take = on_take;
    mo.user = bu;
    sw_scene_t sc = tu_bare(2.0, 0.728);
    snprintf(sc.name, sizeof sc.name, "crate");
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    eo.dt = STEP;
    char msg[256];
    sw_mon_t *m = sw_mon_create(&sc, 1, &eo, &mo, NULL, msg, sizeof msg);
    FZ_CHECK(m != NULL);
    bu->m = m;
    return m;
}

/* The rest of a log whose read was stopped: every event on the channel
 * decoded, none fed.  Returns their count. */
static long read_rest(sw_lcmlog_t *log, int strict)
{
    long n = 0;
    sw_lcmlog_event_t ev;
    int r;
    while ((r = sw_lcmlog_next(log, &ev)) != 0) {
        if (r < 0) {
            /* a corrupted region, reported with strict; the read goes on */
            FZ_CHECK(strict && r == SW_EPARSE);
            continue;
        }
        FZ_CHECK(r == 1 && ev.len <= SW_LCMLOG_MAX_FEED && ev.offset >= 0);
        n++;
        swaywatch_accel_t a;
        int layout = 0;
        const int used = sw_accel_decode(ev.data, ev.len, &a, &layout);
        FZ_CHECK(used == -1 ||
                 (used > 0 && (size_t)used <= ev.len && (layout == 1 || layout == 2)));
    }
    return n;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    const uint8_t o = data[0];
    if (write_file(data + 1, size - 1 > MAX_FILE ? MAX_FILE : size - 1) != 0)
        return 0;
    static const char *const channels[] = {"ACCEL", "ACC.*|SWAY_.*", "NOT_THERE", NULL};
    budget_t bu = {NULL, 0, 0};
    sw_lcmlog_opts_t lo = {.channel = channels[(o >> 1) % 4], .strict = o & 1, .stop = &bu.stop};
    int err = 0;
    sw_lcmlog_t *log = sw_lcmlog_open(file_path, &lo, &err);
    FZ_CHECK(log != NULL);
    sw_mon_t *m = make(o, &bu);

    const int rc = sw_mon_feed_log(m, log, lo.strict);
    FZ_CHECK(rc == SW_OK || (lo.strict && (rc == SW_EPARSE || rc == SW_EINVAL)));
    sw_lcmlog_counts_t lc;
    sw_lcmlog_counts(log, &lc);
    FZ_CHECK(lc.events >= 0 && lc.on_channel >= 0 && lc.other_channels >= 0 && lc.corrupt >= 0);
    FZ_CHECK(lc.events == lc.on_channel + lc.other_channels);
    if (rc == SW_EPARSE)
        FZ_CHECK(lc.corrupt > 0);
    /* stopped by the flag alone, which a cap alone sets */
    FZ_CHECK(!lc.stopped || bu.stop);

    sw_mon_counts_t c;
    sw_mon_counts(m, &c);
    FZ_CHECK(c.received == lc.on_channel);
    FZ_CHECK(c.held >= 0 && c.held <= SW_GATE_HELD_MAX);
    FZ_CHECK(c.received == c.accepted + sw_mon_rejected(&c) + c.held);
    sw_mon_flush(m);
    sw_mon_counts(m, &c);
    FZ_CHECK(c.held == 0 && c.received == c.accepted + sw_mon_rejected(&c));
    sw_summary_t s;
    FZ_CHECK(sw_engine_summary(sw_mon_engine(m), 0, &s) == SW_OK);
    fz_check_summary(&s);
    sw_mon_destroy(m);

    /* The rest of the file, for the reader and the decoders. */
    bu.stop = 0;
    const long rest = read_rest(log, lo.strict);
    sw_lcmlog_counts_t end;
    sw_lcmlog_counts(log, &end);
    FZ_CHECK(end.on_channel == lc.on_channel + rest);
    FZ_CHECK(end.events == end.on_channel + end.other_channels && end.corrupt >= lc.corrupt);
    sw_lcmlog_close(log);
    return 0;
}
