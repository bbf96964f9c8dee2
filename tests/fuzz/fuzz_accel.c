/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_accel.c - libFuzzer target for what the live monitor does with a
 * message on its acceleration channel: the generated swaywatch_accel_t
 * decoder, the monitor core's checks (sw_mon_feed) and the engine behind
 * them, for two bare crates (the frame's engine costs a fifth of an input
 * to make, twice, as the monitor keeps a rival timeline's engine too; the
 * models are fuzz_scene's and fuzz_feed's matter).  The monitor publishes over
 * memq://, and every state_t and alarm_t it publishes is decoded and
 * checked.
 *
 * Input: 1 byte of monitor options (axis, vertical axis, flip, unit, skew
 * check), then records:
 *   0: a raw message: length byte, then that many bytes, as received;
 *   1: an accel_t from small numbers: utime step (2 bytes, us), seq step,
 *      ax, ay, az (1 byte each, scaled);
 *   2: an accel_t from raw bytes: utime step (4 bytes, us), ax, az (8 bytes
 *      each, any double);
 *   3: time passes for the timers (sensor gap, rejection summaries).
 * Samples more than half a second apart are not generated: the engine's
 * work grows with the length of a gap (see docs/security.md: --max-skew
 * bounds it for a live monitor).  The work per input is bounded (fuzz.h):
 * MAX_RECORDS records, FZ_STEP_BUDGET engine steps, gaps bridged up to
 * FZ_MAX_BRIDGE, and no reserve (building it costs several times the rest
 * of an input; a message's bytes are the matter here).
 *
 * Checks: every message is counted once (received = accepted + rejected
 * by reason); what is published decodes exactly and holds only finite
 * numbers; a non-finite or implausible sample is never accepted. */

#include "../testutil.h"
#include "fuzz.h"
#include "fuzz_lcm.h"
#include "monitor.h"
#include "swaywatch_accel_t.h"

#define MAX_RECORDS 48

static sw_scene_t crate(int tall)
{
    sw_scene_t sc = tall ? tu_bare(2.0, 0.728) : tu_bare(1.2, 0.8);
    snprintf(sc.name, sizeof sc.name, tall ? "crate" : "box");
    return sc;
}

static int8_t sbyte(fz_bytes_t *b)
{
    return (int8_t)fz_byte(b);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes_t b = {data, size};
    const uint8_t o = fz_byte(&b);
    sw_mon_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.axis = o % 3;
    mo.vertical = (int)((o >> 2) % 4) - 1;
    mo.flip = (o >> 4) & 1;
    mo.accel_scale = (o >> 5) & 1 ? SW_G0 : 1.0;
    mo.max_skew = (o >> 6) & 1 ? 5.0 : 0.0;
    mo.state_rate = (o >> 7) ? 100.0 : 0.0;
    mo.hysteresis = -1.0;
    mo.reserve_rate = -1.0;
    mo.max_bridge = FZ_MAX_BRIDGE;

    lcm_t *lcm = fz_lcm();
    const sw_scene_t sc[2] = {crate(1), crate(0)};
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    char msg[256];
    sw_mon_t *m = sw_mon_create(sc, 2, &eo, &mo, lcm, msg, sizeof msg);
    FZ_CHECK(m != NULL);

    const int64_t wall0 = 1700000000000000LL;
    int64_t utime = wall0, wall = wall0;
    int64_t seq = 0;
    double mono = 100.0;
    unsigned char buf[256];
    long fed = 0;
    for (int r = 0; r < MAX_RECORDS && b.n > 0 && fz_steps(sw_mon_engine(m)) < FZ_STEP_BUDGET;
         r++) {
        const uint8_t kind = fz_byte(&b);
        int len = -1;
        sw_mon_reject why = SW_MON_NREJ;
        swaywatch_accel_t a;
        memset(&a, 0, sizeof a);
        double ax = 0.0, ay = 0.0, az = 0.0;
        switch (kind & 3) {
            case 0:
                len = fz_byte(&b);
                if ((size_t)len > b.n)
                    len = (int)b.n;
                memcpy(buf, b.p, (size_t)len);
                b.p += len;
                b.n -= (size_t)len;
                break;
            case 1: {
                const int step = (int16_t)((fz_byte(&b) << 8) | fz_byte(&b));
                utime += step;
                seq += sbyte(&b);
                ax = sbyte(&b) * 0.5;
                ay = sbyte(&b) * 0.5;
                az = sbyte(&b) * 0.2;
                break;
            }
            case 2: {
                uint32_t step = 0;
                for (int i = 0; i < 4; i++) step = (step << 8) | fz_byte(&b);
                utime += (int32_t)step % 500000; /* within +-0.5 s */
                seq++;
                ax = fz_double(&b);
                az = fz_double(&b);
                break;
            }
            default: {
                const double dt = fz_byte(&b) * 0.01; /* up to 2.55 s */
                mono += dt;
                wall += (int64_t)(dt * 1e6);
                if (mono >= sw_mon_deadline(m))
                    sw_mon_tick(m, mono);
                continue;
            }
        }
        if (len < 0) {
            a.utime = utime;
            a.seq = seq;
            a.ax = ax;
            a.ay = ay;
            a.az = az;
            len = swaywatch_accel_t_encode(buf, 0, (int)sizeof buf, &a);
            FZ_CHECK(len > 0);
        }
        mono += 1e-3;
        wall += 1000;
        const int rc = sw_mon_feed(m, buf, (size_t)len, wall, mono, &why);
        fed++;
        if (rc == SW_MON_HELD) {
            sw_mon_counts_t c;
            sw_mon_counts(m, &c);
            FZ_CHECK(c.held >= 1 && c.held <= 3 * SW_GATE_CONFIRM_MAX);
        } else if (rc >= 0) {
            /* Accepted: it decoded exactly (in either layout: auth.h), and
             * its values are sane. */
            swaywatch_accel_t d;
            int layout = 0;
            FZ_CHECK(sw_accel_decode(buf, (size_t)len, &d, &layout) == len);
            FZ_CHECK(isfinite(d.ax) && isfinite(d.ay) && isfinite(d.az));
            const double lim = SW_MON_MAX_ACCEL / mo.accel_scale;
            FZ_CHECK(fabs(d.ax) <= lim && fabs(d.ay) <= lim && fabs(d.az) <= lim);
            FZ_CHECK(sw_mon_last_utime(m) == d.utime);
        } else {
            FZ_CHECK(why < SW_MON_NREJ);
            FZ_CHECK(why != SW_MON_REJ_ENGINE); /* the core's checks come first */
        }
        fz_lcm_drain(lcm);
        if (mono >= sw_mon_deadline(m))
            sw_mon_tick(m, mono);
    }
    sw_mon_flush(m);
    fz_lcm_drain(lcm);
    sw_mon_counts_t c;
    sw_mon_counts(m, &c);
    long rejected = 0;
    for (int r = 0; r < SW_MON_NREJ; r++) rejected += c.rejected[r];
    FZ_CHECK(c.received == fed);
    FZ_CHECK(c.held == 0); /* the flush refused what was held */
    FZ_CHECK(c.received == c.accepted + rejected);
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
