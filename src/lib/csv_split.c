/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_split.c - one line of a CSV log split into the fields its reader
 * wants: directly on the delimiter when the line holds no quote (the fast
 * path, most rows of a numeric log), through libcsv in strict mode when it
 * does.  The fast path reproduces libcsv's treatment of unquoted fields
 * exactly (spaces and tabs around a field are dropped); the tests compare
 * the two.  While a line may be the header every field is kept (its names
 * choose the columns, and messages list them). */
#include <stdio.h>
#include <string.h>

#include <csv.h>

#include "csv_int.h"

/* ------------------------------------------------------------------ text */

int sw_csv_is_blank(char ch)
{
    return ch == ' ' || ch == '\t';
}

/* Case-insensitive ASCII comparison of a header field with a column name,
 * both trimmed of spaces and tabs (quoted header fields keep them). */
int sw_csv_name_equal(const char *a, size_t an, const char *b)
{
    while (an && sw_csv_is_blank(*a)) a++, an--;
    while (an && sw_csv_is_blank(a[an - 1])) an--;
    size_t bn = strlen(b);
    if (an != bn)
        return 0;
    for (size_t i = 0; i < an; i++) {
        unsigned char x = (unsigned char)a[i], y = (unsigned char)b[i];
        if (x >= 'A' && x <= 'Z')
            x = (unsigned char)(x - 'A' + 'a');
        if (y >= 'A' && y <= 'Z')
            y = (unsigned char)(y - 'A' + 'a');
        if (x != y)
            return 0;
    }
    return 1;
}

/* Up to EXCERPT_MAX bytes of s, quoted, with anything but printable ASCII
 * shown as '?': reasons end up on terminals and in logs, and garbage input
 * must not put control bytes (or a cut UTF-8 sequence) there. */
void sw_csv_excerpt(char *dst, size_t cap, const char *s, size_t n)
{
    size_t k = 0, lim = n > EXCERPT_MAX ? EXCERPT_MAX : n;
    if (cap < EXCERPT_MAX + 6) {
        if (cap)
            dst[0] = '\0';
        return;
    }
    dst[k++] = '"';
    for (size_t i = 0; i < lim; i++) {
        unsigned char ch = (unsigned char)s[i];
        dst[k++] = (ch >= 0x20 && ch < 0x7f) ? (char)ch : '?';
    }
    if (n > lim) {
        memcpy(dst + k, "...", 3);
        k += 3;
    }
    dst[k++] = '"';
    dst[k] = '\0';
}

/* ----------------------------------------------------------------- fields */

/* One field of the current line: remember it if a slot wants this column,
 * and look its text up among the column names while reading a header.
 * copy: the text lives in libcsv's buffer, which the next field reuses. */
static void take_field(sw_csv_t *c, char *s, size_t n, int copy)
{
    long k = c->nf++;
    if (c->capturing && k < SW_CSV_MAX_FIELDS) {
        const char *a = s;
        size_t an = n;
        while (an && sw_csv_is_blank(*a)) a++, an--;
        while (an && sw_csv_is_blank(a[an - 1])) an--;
        if (an >= SW_CSV_NAME_MAX)
            an = SW_CSV_NAME_MAX - 1;
        memcpy(c->hdr[k], a, an);
        c->hdr[k][an] = '\0';
        c->nhdr = k + 1;
    }
    if (c->matching) {
        for (int r = 0; r < N_ROLES; r++)
            if (c->name[r] && c->match[r] < 0 && sw_csv_name_equal(s, n, c->name[r]))
                c->match[r] = k;
    }
    if (k > c->maxwant)
        return;
    const char *kept = NULL;
    for (int r = 0; r < N_SLOTS; r++) {
        if (c->want[r] != k)
            continue;
        if (!kept) {
            if (copy) {
                if (c->scratch_used + n + 1 > SCRATCH_CAP)
                    return; /* cannot happen */
                char *d = c->scratch + c->scratch_used;
                memcpy(d, s, n);
                d[n] = '\0';
                c->scratch_used += n + 1;
                kept = d;
            } else {
                s[n] = '\0'; /* within the field or on its delimiter: already scanned */
                kept = s;
            }
        }
        c->fs[r] = kept;
        c->fl[r] = n;
    }
}

/* Split a line that holds no quote character: exactly what libcsv does with
 * unquoted fields, without its per-byte state machine and field copies. */
void sw_csv_split_plain(sw_csv_t *c, char *s, size_t n)
{
    char *p = s, *end = s + n;
    for (;;) {
        char *d = memchr(p, c->delim, (size_t)(end - p));
        char *e = d ? d : end;
        while (p < e && sw_csv_is_blank(*p)) p++;
        while (e > p && sw_csv_is_blank(e[-1])) e--;
        take_field(c, p, (size_t)(e - p), 0);
        if (!d)
            return;
        /* Thousands of columns: stop once every wanted field is in hand. */
        if (!c->matching && !c->capturing && c->nf > c->maxwant)
            return;
        p = d + 1;
    }
}

static void lcsv_field(void *s, size_t n, void *user)
{
    take_field(user, s, n, 1);
}

/* Lines are handed over without their '\n' and with a final '\r' already
 * stripped; any other '\r' is data, not the end of a record. */
static int lcsv_term(unsigned char ch)
{
    return ch == '\n';
}

/* Back to a clean state after an error.  csv_fini does not reset the parser
 * after a CSV_STRICT_FINI error, so that check is switched off for the
 * discarding call; no callbacks, so the partial row is dropped. */
void sw_csv_lcsv_reset(sw_csv_t *c)
{
    csv_set_opts(&c->lp, LIBCSV_OPTS & ~CSV_STRICT_FINI);
    csv_fini(&c->lp, NULL, NULL, NULL);
    csv_set_opts(&c->lp, LIBCSV_OPTS);
}

/* Split a line holding a quote through libcsv.  0 with c->reason set when
 * the quoting is malformed. */
int sw_csv_split_quoted(sw_csv_t *c, char *s, size_t n)
{
    size_t used = csv_parse(&c->lp, s, n, lcsv_field, NULL, c);
    if (used < n) {
        int err = csv_error(&c->lp);
        sw_csv_lcsv_reset(c);
        if (err == CSV_EPARSE) {
            char ex[EXCERPT_MAX + 8];
            sw_csv_excerpt(ex, sizeof ex, s + used, n - used);
            snprintf(c->reason, sizeof c->reason, "malformed quoting in field %ld at %s", c->nf + 1,
                     ex);
        } else {
            snprintf(c->reason, sizeof c->reason, "CSV parser: %s", csv_strerror(err));
        }
        return 0;
    }
    if (csv_fini(&c->lp, lcsv_field, NULL, c) != 0) {
        sw_csv_lcsv_reset(c);
        snprintf(c->reason, sizeof c->reason, "unterminated quote in field %ld", c->nf + 1);
        return 0;
    }
    return 1;
}

void sw_csv_lcsv_init(sw_csv_t *c)
{
    csv_init(&c->lp, LIBCSV_OPTS);
    csv_set_term_func(&c->lp, lcsv_term);
    /* libcsv grows its field buffer linearly by this much: the default (128)
     * would mean thousands of reallocations for one long quoted field. */
    csv_set_blk_size(&c->lp, 64 * 1024);
    if (c->delim)
        csv_set_delim(&c->lp, (unsigned char)c->delim);
}
