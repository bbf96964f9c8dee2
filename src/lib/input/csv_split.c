/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_split.c - one line of a CSV log split into the fields a caller wants
 * (csv_int.h: bytes, a length and a small options struct in; fields, or
 * why the line cannot be split, out).  Directly on the delimiter when the
 * line holds no quote (the fast path, most rows of a numeric log), through
 * libcsv in strict mode when it does.  The fast path reproduces libcsv's
 * treatment of unquoted fields exactly (spaces and tabs around a field are
 * dropped); the tests compare the two.  A line that may be the header has
 * every field kept (its names choose the columns, and messages list them).
 * Nothing here knows the reader's state: the splitter holds only libcsv's
 * parser and the copies of quoted fields. */
#include <stdio.h>
#include <stdlib.h>
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

/* One field of the line: remember it if a slot wants this column, keep its
 * name while capturing, and look it up among the names asked for.  copy:
 * the text lives in libcsv's buffer, which the next field reuses. */
static void take_field(sw_csv_splitter_t *sp, char *s, size_t n, int copy)
{
    const sw_csv_split_opts_t *o = sp->o;
    sw_csv_fields_t *f = sp->f;
    long k = f->nf++;
    if (o->capture && k < SW_CSV_MAX_FIELDS) {
        const char *a = s;
        size_t an = n;
        while (an && sw_csv_is_blank(*a)) a++, an--;
        while (an && sw_csv_is_blank(a[an - 1])) an--;
        if (an >= SW_CSV_NAME_MAX)
            an = SW_CSV_NAME_MAX - 1;
        memcpy(o->capture[k], a, an);
        o->capture[k][an] = '\0';
        f->ncap = k + 1;
    }
    if (o->names) {
        for (int r = 0; r < N_ROLES; r++)
            if (o->names[r] && f->match[r] < 0 && sw_csv_name_equal(s, n, o->names[r]))
                f->match[r] = k;
    }
    if (k > sp->maxwant)
        return;
    const char *kept = NULL;
    for (int r = 0; r < N_SLOTS; r++) {
        if (o->want[r] != k)
            continue;
        if (!kept) {
            if (copy) {
                if (sp->scratch_used + n + 1 > SCRATCH_CAP)
                    return; /* cannot happen */
                char *d = sp->scratch + sp->scratch_used;
                memcpy(d, s, n);
                d[n] = '\0';
                sp->scratch_used += n + 1;
                kept = d;
            } else {
                s[n] = '\0'; /* within the field or on its delimiter: already scanned */
                kept = s;
            }
        }
        f->fs[r] = kept;
        f->fl[r] = n;
    }
}

/* Split a line that holds no quote character: exactly what libcsv does with
 * unquoted fields, without its per-byte state machine and field copies. */
static void split_plain(sw_csv_splitter_t *sp, char *s, size_t n)
{
    const sw_csv_split_opts_t *o = sp->o;
    char *p = s, *end = s + n;
    for (;;) {
        char *d = memchr(p, o->delim, (size_t)(end - p));
        char *e = d ? d : end;
        while (p < e && sw_csv_is_blank(*p)) p++;
        while (e > p && sw_csv_is_blank(e[-1])) e--;
        take_field(sp, p, (size_t)(e - p), 0);
        if (!d)
            return;
        /* Thousands of columns: stop once every wanted field is in hand. */
        if (!o->names && !o->capture && sp->f->nf > sp->maxwant)
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
static void lcsv_reset(sw_csv_splitter_t *sp)
{
    csv_set_opts(&sp->lp, LIBCSV_OPTS & ~CSV_STRICT_FINI);
    csv_fini(&sp->lp, NULL, NULL, NULL);
    csv_set_opts(&sp->lp, LIBCSV_OPTS);
}

/* Split a line holding a quote through libcsv. */
static int split_quoted(sw_csv_splitter_t *sp, char *s, size_t n)
{
    sw_csv_fields_t *f = sp->f;
    csv_set_delim(&sp->lp, (unsigned char)sp->o->delim);
    size_t used = csv_parse(&sp->lp, s, n, lcsv_field, NULL, sp);
    if (used < n) {
        int err = csv_error(&sp->lp);
        lcsv_reset(sp);
        if (err == CSV_EPARSE) {
            char ex[EXCERPT_MAX + 8];
            sw_csv_excerpt(ex, sizeof ex, s + used, n - used);
            snprintf(f->reason, sizeof f->reason, "malformed quoting in field %ld at %s", f->nf + 1,
                     ex);
        } else {
            snprintf(f->reason, sizeof f->reason, "CSV parser: %s", csv_strerror(err));
        }
        return SW_CSV_SPLIT_BAD;
    }
    if (csv_fini(&sp->lp, lcsv_field, NULL, sp) != 0) {
        lcsv_reset(sp);
        snprintf(f->reason, sizeof f->reason, "unterminated quote in field %ld", f->nf + 1);
        return SW_CSV_SPLIT_BAD;
    }
    return SW_CSV_SPLIT_OK;
}

int sw_csv_split(sw_csv_splitter_t *sp, char *s, size_t n, const sw_csv_split_opts_t *o,
                 sw_csv_fields_t *f)
{
    /* every row of a log comes here: only what a reader of f may look at
     * is reset (fl and reason are read only with fs set, or on an error) */
    sp->o = o;
    sp->f = f;
    sp->maxwant = -1;
    for (int r = 0; r < N_SLOTS; r++) {
        f->fs[r] = NULL;
        if (o->want[r] > sp->maxwant)
            sp->maxwant = o->want[r];
    }
    if (o->names)
        for (int r = 0; r < N_ROLES; r++) f->match[r] = -1;
    f->nf = 0;
    f->ncap = 0;
    if (!memchr(s, '"', n)) {
        split_plain(sp, s, n);
        return SW_CSV_SPLIT_OK;
    }
    sp->scratch_used = 0;
    return split_quoted(sp, s, n);
}

int sw_csv_splitter_init(sw_csv_splitter_t *sp)
{
    memset(sp, 0, sizeof *sp);
    sp->scratch = malloc(SCRATCH_CAP);
    if (!sp->scratch)
        return -1;
    csv_init(&sp->lp, LIBCSV_OPTS);
    csv_set_term_func(&sp->lp, lcsv_term);
    /* libcsv grows its field buffer linearly by this much: the default (128)
     * would mean thousands of reallocations for one long quoted field. */
    csv_set_blk_size(&sp->lp, 64 * 1024);
    sp->ready = 1;
    return 0;
}

void sw_csv_splitter_free(sw_csv_splitter_t *sp)
{
    if (sp->ready)
        csv_free(&sp->lp);
    free(sp->scratch);
    memset(sp, 0, sizeof *sp);
}
