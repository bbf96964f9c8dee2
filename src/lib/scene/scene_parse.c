/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scene_parse.c - reading a scene file: INI through inih, with our own
 * line reader for line numbers, comments and the lines inih would take
 * silently, and each key set as sw_scene_set() does, reported with its
 * line.  No I/O: the caller hands in the text of the file. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

/* The packaged libinih is built with INI_HANDLER_LINENO = 0, so the handler
 * cannot be told the line number (defining the macro here would only make
 * our handler's type disagree with how the library calls it).  Line numbers
 * come from our own reader instead, see scene_reader(). */
#include <ini.h>

#include "scene_int.h"
#include "swaywatch/scene.h"
#include "swaywatch/status.h"

/* ---- parsing a file ------------------------------------------------------ */

typedef struct {
    sw_scene_t *sc;
    const char *origin;
    sw_diag_fn diag;
    void *user;
    const char *pos; /* next unread character of the text */
    int lineno;      /* 1-based number of the line last handed to inih */
    int section;     /* SEC_*, SEC_NONE or SEC_SKIP */
    int section_line[SEC_COUNT];
    int key_line[K_COUNT];
    int rc; /* first error, SW_OK if none */
} parse_ctx;

static void fail(parse_ctx *c, int code)
{
    if (c->rc == SW_OK)
        c->rc = code;
}

/* A section header, already stripped to "[...]".  Returns the text to hand
 * to inih. */
static const char *section_header(parse_ctx *c, const char *a, size_t n)
{
    const char *in = a + 1, *end = a + n - 1; /* between the brackets */
    while (in < end && isspace((unsigned char)*in)) in++;
    while (end > in && isspace((unsigned char)end[-1])) end--;
    char name[32];
    size_t len = (size_t)(end - in);
    if (len >= sizeof name)
        len = sizeof name - 1; /* unknown anyway */
    memcpy(name, in, len);
    name[len] = '\0';

    int s = sw_scene_find_section(name);
    c->section = SEC_SKIP;
    if (s < 0) {
        sw_scene_report(c->diag, c->user, c->origin, c->lineno,
                        "unknown section [%s]: expected [package], [frame], [cushion] or [alarm]",
                        name);
        fail(c, SW_ENOTFOUND);
        return "";
    }
    if (c->section_line[s]) {
        sw_scene_report(c->diag, c->user, c->origin, c->lineno,
                        "section [%s] given twice (first at line %d): expected each section once, "
                        "one package per file",
                        name, c->section_line[s]);
        fail(c, SW_EINVAL);
        return "";
    }
    c->section = s;
    c->section_line[s] = c->lineno;
    switch (s) {
        case SEC_PACKAGE: c->sc->line_package = c->lineno; break;
        case SEC_FRAME:
            c->sc->line_frame = c->lineno;
            c->sc->has_frame = 1;
            break;
        case SEC_CUSHION:
            c->sc->line_cushion = c->lineno;
            c->sc->has_cushion = 1;
            break;
        default: c->sc->line_alarm = c->lineno; break;
    }
    return sw_scene_section_names[s];
}

/* inih's line reader, fed from the text.  It does three things inih cannot
 * do for us as packaged:
 *  - it counts lines, so the handler knows which line it is called for
 *    (inih calls the handler for a line before it reads the next one);
 *  - it strips comments: the packaged inih strips inline comments only
 *    after ';' (INI_INLINE_COMMENT_PREFIXES is ";"), while scene files use
 *    "height = 2.0   # m".  Changing ini_inline_comment_prefixes would
 *    change a global of a shared library for every user of it, so a '#' or
 *    ';' at the start of a line or after white space starts a comment here;
 *  - it rejects what inih would accept silently or report only as "the
 *    first bad line": lines without '=', broken section headers, lines too
 *    long for inih's buffer (it would truncate them), and leading white
 *    space, which inih would take as the continuation of the previous
 *    value (INI_ALLOW_MULTILINE) - here it is just indentation.
 * Bad lines are reported and handed to inih as empty lines. */
static char *scene_reader(char *str, int num, void *stream)
{
    parse_ctx *c = stream;
    if (*c->pos == '\0')
        return NULL;
    const char *a = c->pos;
    size_t n = strcspn(a, "\n");
    c->pos = a + n + (a[n] == '\n');
    c->lineno++;

    /* A UTF-8 byte order mark, as some editors write. */
    if (c->lineno == 1 && n >= 3 && !memcmp(a, "\xEF\xBB\xBF", 3)) {
        a += 3;
        n -= 3;
    }
    while (n > 0 && isspace((unsigned char)*a)) a++, n--;
    for (size_t i = 0; i < n; i++) {
        if ((a[i] == '#' || a[i] == ';') && (i == 0 || isspace((unsigned char)a[i - 1]))) {
            n = i;
            break;
        }
    }
    while (n > 0 && isspace((unsigned char)a[n - 1])) n--;

    str[0] = '\0';
    if (n == 0)
        return str;

    if (a[0] == '[') {
        if (a[n - 1] != ']') {
            sw_scene_report(c->diag, c->user, c->origin, c->lineno,
                            memchr(a, ']', n)
                                ? "unexpected text after the section header: expected "
                                  "[section] alone on its line"
                                : "section header without its closing ']'");
            fail(c, SW_EPARSE);
            c->section = SEC_SKIP;
            return str;
        }
        const char *name = section_header(c, a, n);
        if (*name)
            snprintf(str, (size_t)num, "[%s]\n", name);
        return str;
    }

    size_t sep = strcspn(a, "=:");
    if (sep >= n) {
        /* Quote this line only: a runs on into the rest of the text. */
        sw_scene_report(c->diag, c->user, c->origin, c->lineno,
                        "\"%.*s\": expected key = value, a [section] header or a comment",
                        (int)(n < 40 ? n : 40), a);
        fail(c, SW_EPARSE);
        return str;
    }
    size_t keylen = sep;
    while (keylen > 0 && isspace((unsigned char)a[keylen - 1])) keylen--;
    if (keylen == 0) {
        sw_scene_report(c->diag, c->user, c->origin, c->lineno, "missing key before '%c'", a[sep]);
        fail(c, SW_EPARSE);
        return str;
    }
    /* inih needs room for the text, a newline and the terminator. */
    if (num < 2 || n > (size_t)num - 2) {
        sw_scene_report(c->diag, c->user, c->origin, c->lineno,
                        "line too long: expected at most %d characters before any comment",
                        num - 2);
        fail(c, SW_EPARSE);
        return str;
    }
    memcpy(str, a, n);
    str[n] = '\n';
    str[n + 1] = '\0';
    return str;
}

static int scene_handler(void *user, const char *section, const char *name, const char *value)
{
    parse_ctx *c = user;
    (void)section; /* c->section is the same, already checked */
    int line = c->lineno;
    if (c->section == SEC_SKIP)
        return 1; /* its header was reported */
    if (c->section == SEC_NONE) {
        sw_scene_report(
            c->diag, c->user, c->origin, line,
            "key \"%.40s\" outside any section: expected a [package], [frame], [cushion] "
            "or [alarm] header before it",
            name);
        fail(c, SW_EPARSE);
        return 1;
    }
    const char *sec = sw_scene_section_names[c->section];
    int k = sw_scene_find_key(c->section, name);
    if (k >= 0 && c->key_line[k]) {
        sw_scene_report(c->diag, c->user, c->origin, line,
                        "%s.%s given twice (first at line %d): expected each key once", sec, name,
                        c->key_line[k]);
        fail(c, SW_EINVAL);
        return 1;
    }
    if (k >= 0 && sw_scene_keys[k].partner >= 0 && c->key_line[sw_scene_keys[k].partner]) {
        int other = sw_scene_keys[k].partner;
        sw_scene_report(
            c->diag, c->user, c->origin, line,
            "%s.%s (line %d) and %s.%s (line %d) both given: expected one of the two, not "
            "both",
            sec, sw_scene_keys[other].name, c->key_line[other], sec, name, line);
        c->key_line[k] = line;
        fail(c, SW_EINVAL);
        return 1;
    }
    if (k >= 0)
        c->key_line[k] = line;
    /* Unknown keys are reported by sw_scene_set, as for --set. */
    int rc = sw_scene_set(c->sc, sec, name, value, 0, c->origin, line, c->diag, c->user);
    if (rc != SW_OK)
        fail(c, rc);
    return 1;
}

int sw_scene_parse(sw_scene_t *sc, const char *text, const char *origin, sw_diag_fn diag,
                   void *user)
{
    if (!sc || !text) {
        sw_scene_report(diag, user, origin, 0, "internal: sw_scene_parse called without %s",
                        !sc ? "a scene" : "text");
        return SW_EINVAL;
    }
    parse_ctx c;
    memset(&c, 0, sizeof c);
    c.sc = sc;
    c.origin = origin ? origin : "";
    c.diag = diag;
    c.user = user;
    c.pos = text;
    c.section = SEC_NONE;
    c.rc = SW_OK;

    int r = ini_parse_stream(scene_reader, &c, scene_handler, &c);
    if (r == -2) {
        sw_scene_report(diag, user, c.origin, 0, "out of memory while parsing");
        return SW_ENOMEM;
    }
    /* The reader hands inih only well-formed lines and the handler never
     * fails, so inih should have nothing to add; if it does, say where. */
    if (r > 0 && c.rc == SW_OK) {
        sw_scene_report(diag, user, c.origin, r, "malformed line");
        c.rc = SW_EPARSE;
    }
    return c.rc;
}
