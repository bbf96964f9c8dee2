/* SPDX-License-Identifier: GPL-3.0-or-later */
/* manifest.c - reading a batch's manifest and splitting its lines into
 * words (manifest.h), the way a shell splits a command line, without any
 * expansion. */
#include "manifest.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#define MANIFEST_MAX (1L << 30) /* bytes: a million logs have far fewer */

int sw_cli_manifest_read(const char *path, char **text, size_t *len)
{
    *text = NULL;
    *len = 0;
    const int in = !strcmp(path, "-");
    FILE *f = in ? stdin : fopen(path, "rb");
    if (!f) {
        sw_cli_error("%s: cannot open: %s", path, strerror(errno));
        return SW_EXIT_IO;
    }
    size_t cap = 0;
    char *buf = NULL;
    int rc = SW_EXIT_OK;
    for (;;) {
        if (*len + 4096 > cap) {
            cap = cap ? 2 * cap : 65536;
            char *nb = cap <= (size_t)MANIFEST_MAX ? realloc(buf, cap + 1) : NULL;
            if (!nb) {
                sw_cli_error("%s: %s", path,
                             cap > (size_t)MANIFEST_MAX ? "longer than 1 GiB: not a manifest"
                                                        : "out of memory");
                rc = SW_EXIT_IO;
                break;
            }
            buf = nb;
        }
        const size_t got = fread(buf + *len, 1, cap - *len, f);
        *len += got;
        if (got == 0)
            break;
    }
    if (rc == SW_EXIT_OK && ferror(f)) {
        sw_cli_error("%s: cannot read: %s", path, strerror(errno));
        rc = SW_EXIT_IO;
    }
    if (!in)
        fclose(f);
    if (rc != SW_EXIT_OK) {
        free(buf);
        *len = 0;
        return rc;
    }
    if (!buf)
        buf = calloc(1, 1);
    if (!buf) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    buf[*len] = '\0';
    *text = buf;
    return SW_EXIT_OK;
}

/* ---- splitting ------------------------------------------------------------------ */

typedef struct {
    const char *name;
    long line;
    sw_cli_manifest_t *m;
    char *word; /* being built */
    size_t wlen, wcap;
} split_t;

static int put(split_t *S, char c)
{
    if (S->wlen + 2 > S->wcap) {
        size_t cap = S->wcap ? 2 * S->wcap : 64;
        char *w = realloc(S->word, cap);
        if (!w)
            return -1;
        S->word = w;
        S->wcap = cap;
    }
    S->word[S->wlen++] = c;
    S->word[S->wlen] = '\0';
    return 0;
}

/* The word built so far joins the manifest's words. */
static int end_word(split_t *S)
{
    sw_cli_manifest_t *m = S->m;
    char **w = realloc(m->words, (m->nwords + 1) * sizeof *w);
    if (!w)
        return -1;
    m->words = w;
    m->words[m->nwords++] = S->word ? S->word : strdup("");
    if (!m->words[m->nwords - 1])
        return -1;
    S->word = NULL;
    S->wlen = S->wcap = 0;
    return 0;
}

/* One line (without its newline) into words; the index of its first word
 * in *first, the count in *count. */
static int split_line(split_t *S, const char *p, const char *end, size_t *first, size_t *count)
{
    *first = S->m->nwords;
    *count = 0;
    for (;;) {
        while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) p++;
        if (p == end || *p == '#')
            return SW_EXIT_OK;
        int in_word = 0;
        while (p < end && *p != ' ' && *p != '\t' && *p != '\r') {
            char c = *p++;
            int bad = 0;
            if (c == '\'' || c == '"') {
                const char q = c;
                in_word = 1;
                while (p < end && *p != q) {
                    c = *p++;
                    if (q == '"' && c == '\\' && p < end && (*p == '"' || *p == '\\'))
                        c = *p++;
                    bad |= put(S, c);
                }
                if (p == end) {
                    sw_cli_error("%s:%ld: a %s quote is not closed", S->name, S->line,
                                 q == '"' ? "double" : "single");
                    return SW_EXIT_USAGE;
                }
                p++;
            } else {
                if (c == '\\' && p < end)
                    c = *p++;
                bad |= put(S, c);
                in_word = 1;
            }
            if (bad)
                goto oom;
        }
        if (in_word) {
            if (end_word(S) != 0)
                goto oom;
            (*count)++;
        }
    }
oom:
    sw_cli_error("out of memory");
    return SW_EXIT_IO;
}

int sw_cli_manifest_parse(const char *name, const char *text, size_t len, sw_cli_manifest_t *m)
{
    memset(m, 0, sizeof *m);
    if (memchr(text, '\0', len)) {
        const char *z = memchr(text, '\0', len);
        long line = 1;
        for (const char *p = text; p < z; p++) line += *p == '\n';
        sw_cli_error("%s:%ld: a NUL byte: this is not a text file of logs", name, line);
        return SW_EXIT_USAGE;
    }
    split_t S = {.name = name, .m = m};
    /* first the words of every line, then the lines point into them (the
     * array of words moves while it grows) */
    size_t nlines = 0, cap = 0;
    size_t(*span)[3] = NULL; /* per line with words: first word, count, line number */
    int rc = SW_EXIT_OK;
    const char *p = text, *end = text + len;
    while (p < end && rc == SW_EXIT_OK) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        S.line++;
        size_t first, count;
        rc = split_line(&S, p, le, &first, &count);
        if (rc == SW_EXIT_OK && count > 0) {
            const char *w = m->words[first];
            if (w[0] == '-' && w[1] != '\0') {
                sw_cli_error(
                    "%s:%ld: a line begins with the log, then its options; not with "
                    "'%s'",
                    name, S.line, w);
                rc = SW_EXIT_USAGE;
            } else {
                if (nlines == cap) {
                    cap = cap ? 2 * cap : 256;
                    void *ns = realloc(span, cap * sizeof *span);
                    if (!ns) {
                        sw_cli_error("out of memory");
                        rc = SW_EXIT_IO;
                        break;
                    }
                    span = ns;
                }
                span[nlines][0] = first;
                span[nlines][1] = count;
                span[nlines][2] = (size_t)S.line;
                nlines++;
            }
        }
        p = nl ? nl + 1 : end;
    }
    free(S.word);
    if (rc == SW_EXIT_OK && nlines) {
        /* each line's args: the words after the log, and a NULL */
        m->v = calloc(nlines, sizeof *m->v);
        if (!m->v) {
            sw_cli_error("out of memory");
            rc = SW_EXIT_IO;
        } else {
            for (size_t i = 0; i < nlines && rc == SW_EXIT_OK; i++) {
                sw_cli_manifest_line_t *L = &m->v[i];
                L->log = m->words[span[i][0]];
                L->nargs = span[i][1] - 1;
                L->line = (long)span[i][2];
                L->args = calloc(L->nargs + 1, sizeof *L->args);
                if (!L->args) {
                    sw_cli_error("out of memory");
                    rc = SW_EXIT_IO;
                    break;
                }
                for (size_t k = 0; k < L->nargs; k++) L->args[k] = m->words[span[i][0] + 1 + k];
                m->n = i + 1;
            }
        }
    }
    free(span);
    if (rc != SW_EXIT_OK)
        sw_cli_manifest_free(m);
    return rc;
}

void sw_cli_manifest_free(sw_cli_manifest_t *m)
{
    for (size_t i = 0; i < m->n; i++) free(m->v[i].args);
    free(m->v);
    for (size_t i = 0; i < m->nwords; i++) free(m->words[i]);
    free(m->words);
    memset(m, 0, sizeof *m);
}
