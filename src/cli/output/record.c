/* SPDX-License-Identifier: GPL-3.0-or-later */
/* record.c - JSON through jansson, CSV cells through libcsv's writer, and
 * CSV rows read off JSON records (record.h). */
#include "record.h"

#include <csv.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "text.h"

/* Whether the record this thread is building lost something (a value or
 * a member that could not be allocated): sw_cli_rec_write() refuses it.
 * Per thread: batch builds records on every core at once. */
static _Thread_local int failed;

json_t *sw_cli_rec_new(void)
{
    json_t *o = json_object();
    failed = !o;
    return o;
}

void sw_cli_rec_put(json_t *o, const char *key, json_t *v)
{
    if (!o || !v) {
        json_decref(v);
        failed = 1;
        return;
    }
    if ((json_is_array(o) ? json_array_append_new(o, v) : json_object_set_new(o, key, v)) != 0)
        failed = 1; /* jansson released v */
}

json_t *sw_cli_rec_obj(json_t *o, const char *key)
{
    json_t *v = json_object();
    sw_cli_rec_put(o, key, v);
    return o ? v : NULL;
}

json_t *sw_cli_rec_arr(json_t *o, const char *key)
{
    json_t *v = json_array();
    sw_cli_rec_put(o, key, v);
    return o ? v : NULL;
}

void sw_cli_rec_num(json_t *o, const char *key, double v)
{
    sw_cli_rec_put(o, key, isfinite(v) ? json_real(v) : json_null());
}

void sw_cli_rec_int(json_t *o, const char *key, long long v)
{
    sw_cli_rec_put(o, key, json_integer(v));
}

void sw_cli_rec_bool(json_t *o, const char *key, int v)
{
    sw_cli_rec_put(o, key, json_boolean(v));
}

void sw_cli_rec_null(json_t *o, const char *key)
{
    sw_cli_rec_put(o, key, json_null());
}

/* s as a JSON string: well-formed UTF-8 as it is, each ill-formed subpart
 * as U+FFFD (EF BF BD), so that jansson takes it and it decodes as
 * Python's errors="replace" reads the bytes. */
static json_t *text_value(const char *s)
{
    const unsigned char *p = (const unsigned char *)s;
    const size_t n = strlen(s);
    size_t out = 0, bad = 0;
    for (size_t k = 0; k < n;) {
        size_t len;
        uint32_t cp;
        if (!sw_cli_utf8_next(p + k, n - k, &len, &cp))
            bad++, out += 3;
        else
            out += len;
        k += len;
    }
    if (!bad)
        return json_stringn_nocheck(s, n);
    char *buf = malloc(out);
    if (!buf)
        return NULL;
    size_t m = 0;
    for (size_t k = 0; k < n;) {
        size_t len;
        uint32_t cp;
        if (sw_cli_utf8_next(p + k, n - k, &len, &cp))
            memcpy(buf + m, p + k, len), m += len;
        else
            memcpy(buf + m, "\xef\xbf\xbd", 3), m += 3;
        k += len;
    }
    json_t *v = json_stringn_nocheck(buf, m);
    free(buf);
    return v;
}

void sw_cli_rec_text(json_t *o, const char *key, const char *s)
{
    sw_cli_rec_put(o, key, s ? text_value(s) : json_null());
}

/* %.9g, as the hand-written JSON had it; jansson adds ".0" to a whole
 * number, which parses to the same value. */
#define FLAGS JSON_REAL_PRECISION(9)

int sw_cli_rec_write(FILE *f, json_t *o, int layout)
{
    int rc = -1;
    if (o && !failed)
        rc = json_dumpf(o, f, FLAGS | (layout == SW_CLI_REC_DOC ? JSON_INDENT(2) : 0));
    json_decref(o);
    if (rc == 0)
        fputc('\n', f);
    return rc == 0 || ferror(f) ? 0 : -1; /* a write error is the stream's: its close says it */
}

char *sw_cli_rec_line(json_t *o)
{
    char *s = o && !failed ? json_dumps(o, FLAGS) : NULL;
    json_decref(o);
    return s;
}

/* ---- CSV ------------------------------------------------------------------------ */

void sw_cli_csv_text(FILE *f, const char *s)
{
    /* a cell that a spreadsheet would read as a formula gets a leading
     * "'" (OWASP, "CSV injection"); quoted only when it has to be, by
     * libcsv's writer (RFC 4180: quotes doubled) */
    const char *lead = s[0] && strchr("=+-@\t\r", s[0]) ? "'" : "";
    if (!strpbrk(s, ",;\t\"\r\n")) {
        fputs(lead, f);
        fputs(s, f);
        return;
    }
    if (!*lead) {
        csv_fwrite(f, s, strlen(s));
        return;
    }
    const size_t n = strlen(s) + 2; /* the "'", s and its NUL */
    char small[256], *c = n <= sizeof small ? small : malloc(n);
    if (c) {
        snprintf(c, n, "'%s", s);
        csv_fwrite(f, c, n - 1);
    } else { /* no memory for the copy: the same cell, quoted here */
        fputs("\"'", f);
        for (; *s; s++) {
            if (*s == '"')
                fputc('"', f);
            fputc(*s, f);
        }
        fputc('"', f);
    }
    if (c != small)
        free(c);
}

void sw_cli_csv_num(FILE *f, double v)
{
    fputc(',', f);
    if (isfinite(v))
        fprintf(f, "%.9g", v);
}

void sw_cli_csv_header(FILE *f, const sw_cli_column_t *c, size_t n)
{
    for (size_t i = 0; i < n; i++) fprintf(f, ",%s", c[i].name);
}

/* The member of rec at path ("a.b.c"), or NULL. */
static const json_t *member(const json_t *rec, const char *path)
{
    char key[64];
    while (rec && *path) {
        const size_t n = strcspn(path, ".");
        if (n >= sizeof key)
            return NULL;
        memcpy(key, path, n);
        key[n] = '\0';
        rec = json_object_get(rec, key);
        path += n + (path[n] == '.');
    }
    return rec;
}

/* v as CSV text (no comma). */
static void cell(FILE *f, const json_t *v)
{
    switch (json_typeof(v)) {
        case JSON_REAL: fprintf(f, "%.9g", json_real_value(v)); break;
        case JSON_INTEGER: fprintf(f, "%" JSON_INTEGER_FORMAT, json_integer_value(v)); break;
        case JSON_TRUE: fputc('1', f); break;
        case JSON_FALSE: fputc('0', f); break;
        case JSON_STRING: sw_cli_csv_text(f, json_string_value(v)); break;
        case JSON_ARRAY: {
            /* the items as one text: "frame, soft bearings; cushion, firm" */
            char *joined = NULL;
            size_t len = 0;
            FILE *m = open_memstream(&joined, &len);
            size_t i;
            const json_t *it;
            json_array_foreach(v, i, it)
            {
                if (m && json_is_string(it))
                    fprintf(m, "%s%s", i ? "; " : "", json_string_value(it));
            }
            if (m && fclose(m) == 0)
                sw_cli_csv_text(f, joined);
            free(joined);
            break;
        }
        default: break; /* null, an object: an empty cell */
    }
}

void sw_cli_csv_row(FILE *f, const json_t *rec, const sw_cli_column_t *c, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        const json_t *v = member(rec, c[i].path ? c[i].path : c[i].name);
        fputc(',', f);
        if (v)
            cell(f, v);
        else if (c[i].missing)
            fputs(c[i].missing, f);
    }
}
