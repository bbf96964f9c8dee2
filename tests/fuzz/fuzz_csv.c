/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_csv.c - libFuzzer target for the CSV reader (csv.h).
 *
 * Input: 3 bytes of options (delimiter, header mode, column choice, units,
 * flip), 1 byte seeding the chunking, then the CSV text.  The text is read
 * twice: in one sw_csv_feed() call, and in chunks of random sizes (1 byte
 * to 4 KiB).  Both runs must deliver the same rows and rejections with the
 * same line numbers, and each must keep the reader's promises: counts add
 * up, delivered values are finite, time strictly increases, reasons are
 * printable ASCII. */
#include "fuzz.h"

#define MAX_TEXT (256 * 1024) /* bytes; longer inputs are cut */

typedef struct {
    uint64_t digest; /* FNV-1a over everything delivered, in order */
    long rows, rejects, last_line;
    int have_t;
    double last_t;
} run_t;

static void mix(uint64_t *h, const void *p, size_t n)
{
    const unsigned char *s = p;
    for (size_t i = 0; i < n; i++) *h = (*h ^ s[i]) * 0x100000001b3ULL;
}

static int on_row(void *user, long line, double t, double a, double z)
{
    run_t *r = user;
    FZ_CHECK(isfinite(t) && isfinite(a) && isfinite(z));
    FZ_CHECK(line >= 1 && line >= r->last_line);
    FZ_CHECK(!r->have_t || t > r->last_t);
    r->have_t = 1;
    r->last_t = t;
    r->last_line = line;
    r->rows++;
    mix(&r->digest, &line, sizeof line);
    mix(&r->digest, &t, sizeof t);
    mix(&r->digest, &a, sizeof a);
    mix(&r->digest, &z, sizeof z);
    return 0;
}

static void on_reject(void *user, long line, const char *reason)
{
    run_t *r = user;
    FZ_CHECK(line >= 1 && line >= r->last_line);
    FZ_CHECK(reason && reason[0]);
    for (const char *p = reason; *p; p++) FZ_CHECK(*p >= 0x20 && *p < 0x7f);
    r->last_line = line;
    r->rejects++;
    mix(&r->digest, &line, sizeof line);
    mix(&r->digest, reason, strlen(reason));
}

static const char *const columns[] = {NULL, "1", "2", "3", "t", "a", "time", "acc", "z", "4"};
#define NCOL (sizeof columns / sizeof columns[0])

/* One run; chunk_seed 0 feeds everything at once. */
static void run(const sw_csv_opts_t *o, const uint8_t *text, size_t len, uint32_t chunk_seed,
                run_t *r, sw_csv_counts_t *counts, int *status)
{
    memset(r, 0, sizeof *r);
    r->digest = 0xcbf29ce484222325ULL;
    int err = 0;
    char msg[256];
    sw_csv_t *c = sw_csv_create(o, on_row, on_reject, r, &err, msg, sizeof msg);
    if (!c) {
        FZ_CHECK(err < 0);
        *status = err;
        memset(counts, 0, sizeof *counts);
        return;
    }
    int rc = SW_OK;
    uint32_t x = chunk_seed | 1u;
    size_t off = 0;
    while (off < len && rc == SW_OK) {
        size_t n = len - off;
        if (chunk_seed) {
            x ^= x << 13, x ^= x >> 17, x ^= x << 5; /* xorshift32 */
            size_t k = (x & 3) == 0 ? 1 + (x >> 8) % 4096 : 1 + (x >> 8) % 16;
            if (k < n)
                n = k;
        }
        rc = sw_csv_feed(c, (const char *)text + off, n);
        off += n;
    }
    if (rc == SW_OK)
        rc = sw_csv_finish(c);
    /* the results csv.h documents for feed and finish */
    FZ_CHECK(rc == SW_OK || rc == SW_ENOTFOUND || rc == SW_EINVAL || rc == SW_EAMBIGUOUS);
    if (rc != SW_OK) {
        const char *m = sw_csv_error_message(c);
        FZ_CHECK(m && m[0]);
        FZ_CHECK(sw_csv_feed(c, "1,2\n", 4) == rc); /* the error is sticky */
    }
    sw_csv_counts(c, counts);
    FZ_CHECK(counts->rows == counts->accepted + counts->rejected);
    FZ_CHECK(counts->lines ==
             counts->rows + counts->comments + counts->blanks + counts->headers + counts->preamble);
    FZ_CHECK(counts->headers <= 1);
    FZ_CHECK(counts->accepted == r->rows && counts->rejected == r->rejects);
    FZ_CHECK(r->last_line <= counts->lines);
    *status = rc;
    sw_csv_destroy(c);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes_t b = {data, size};
    const uint8_t o0 = fz_byte(&b), o1 = fz_byte(&b), o2 = fz_byte(&b), seed = fz_byte(&b);
    static const char delims[] = {0, ',', ';', '\t'};
    sw_csv_opts_t o;
    memset(&o, 0, sizeof o);
    o.delim = delims[o0 & 3];
    o.header = (int)((o0 >> 2) % 3) - 1;
    o.flip = (o0 >> 4) & 1;
    o.time_col = columns[o1 % NCOL];
    o.accel_col = columns[(o1 / NCOL) % NCOL];
    o.vert_col = (o0 >> 5) & 1 ? columns[o2 % NCOL] : NULL;
    static const double tscale[] = {0, 1, 1e-3, 1e-6};
    static const double ascale[] = {0, 1, 9.80665, 1e300};
    o.time_scale = tscale[(o2 >> 4) & 3];
    o.accel_scale = ascale[(o2 >> 6) & 3];
    /* header inference and the decimal comma: seed bits 6 and 7 */
    o.infer = (seed >> 6) & 1;
    o.decimal_comma = (seed >> 7) & 1 ? -1 : (o1 & 1);
    if (o.infer && (o2 & 1))
        o.time_col = o.accel_col = NULL; /* let the header choose */

    size_t len = b.n > MAX_TEXT ? MAX_TEXT : b.n;
    run_t whole, chunked;
    sw_csv_counts_t cw, cc;
    int sw, sc;
    run(&o, b.p, len, 0, &whole, &cw, &sw);
    run(&o, b.p, len, 0x9e3779b9u * (uint32_t)(seed + 1), &chunked, &cc, &sc);
    FZ_CHECK(sw == sc);
    FZ_CHECK(whole.digest == chunked.digest);
    FZ_CHECK(memcmp(&cw, &cc, sizeof cw) == 0);
    return 0;
}
