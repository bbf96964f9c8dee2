/* SPDX-License-Identifier: GPL-3.0-or-later */
/* clobber.c - no output overwrites an input or another output
 * (clobber.h). */
#include "clobber.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lcmurl.h"

/* Symbolic links followed at most (as the kernel's ELOOP limit). */
#define MAX_LINKS 40

typedef struct {
    int exists;
    dev_t dev;
    ino_t ino;
    char path[PATH_MAX]; /* resolved, for a file that does not exist yet */
} ident_t;

/* dir part of p ("." if none) and its last component. */
static void split(const char *p, char *dir, size_t dlen, const char **base)
{
    const char *slash = strrchr(p, '/');
    if (!slash) {
        snprintf(dir, dlen, ".");
        *base = p;
    } else if (slash == p) {
        snprintf(dir, dlen, "/");
        *base = slash + 1;
    } else {
        snprintf(dir, dlen, "%.*s", (int)(slash - p), p);
        *base = slash + 1;
    }
}

/* Where opening p for writing would create a file: dangling symbolic
 * links followed, the directory resolved. */
static void resolve_new(const char *path, char *out, size_t len)
{
    char cur[PATH_MAX], dir[PATH_MAX], link[PATH_MAX];
    const char *base;
    snprintf(cur, sizeof cur, "%s", path);
    struct stat st;
    for (int i = 0; i < MAX_LINKS && lstat(cur, &st) == 0 && S_ISLNK(st.st_mode); i++) {
        ssize_t n = readlink(cur, link, sizeof link - 1);
        if (n < 0)
            break;
        link[n] = '\0';
        if (link[0] == '/') {
            snprintf(cur, sizeof cur, "%s", link);
        } else {
            split(cur, dir, sizeof dir, &base);
            char next[PATH_MAX];
            if (snprintf(next, sizeof next, "%s/%s", dir, link) >= (int)sizeof next)
                break;
            memcpy(cur, next, sizeof cur);
        }
    }
    split(cur, dir, sizeof dir, &base);
    char real[PATH_MAX];
    if (!realpath(dir, real) ||
        snprintf(out, len, "%s/%s", strcmp(real, "/") ? real : "", base) >= (int)len)
        snprintf(out, len, "%s", cur);
}

static void identify(const sw_cli_file_t *f, int is_input, ident_t *id)
{
    memset(id, 0, sizeof *id);
    struct stat st;
    int ok;
    if (!strcmp(f->path, "-")) /* standard input: what it was redirected from */
        ok = is_input && fstat(STDIN_FILENO, &st) == 0 && S_ISREG(st.st_mode);
    else
        ok = stat(f->path, &st) == 0;
    if (ok) {
        id->exists = 1;
        id->dev = st.st_dev;
        id->ino = st.st_ino;
    } else if (strcmp(f->path, "-")) {
        resolve_new(f->path, id->path, sizeof id->path);
    }
}

static int same(const ident_t *a, const ident_t *b)
{
    if (a->exists && b->exists)
        return a->dev == b->dev && a->ino == b->ino;
    return !a->exists && !b->exists && a->path[0] && !strcmp(a->path, b->path);
}

static const char *kind(const sw_cli_file_t *in)
{
    if (!strcmp(in->what, "LOG"))
        return "the log being read";
    if (!strcmp(in->what, "--scene"))
        return "a scene file being read";
    if (!strcmp(in->what, "--manifest"))
        return "the manifest being read";
    return "an input being read";
}

static int given(const sw_cli_file_t *f)
{
    return f->path && f->path[0];
}

int sw_cli_check_files(const sw_cli_file_t *in, size_t nin, const sw_cli_file_t *out, size_t nout)
{
    ident_t a, b;
    for (size_t i = 0; i < nout; i++) {
        if (!given(&out[i]) || !strcmp(out[i].path, "-"))
            continue;
        identify(&out[i], 0, &a);
        for (size_t k = 0; a.exists && k < nin; k++) {
            if (!given(&in[k]))
                continue;
            identify(&in[k], 1, &b);
            if (same(&a, &b)) {
                sw_cli_error("%s %s: that is %s (%s %s): writing it would destroy it", out[i].what,
                             out[i].path, kind(&in[k]), in[k].what,
                             strcmp(in[k].path, "-") ? in[k].path : "- (standard input)");
                return SW_EXIT_USAGE;
            }
        }
        for (size_t k = i + 1; k < nout; k++) {
            if (!given(&out[k]) || !strcmp(out[k].path, "-"))
                continue;
            identify(&out[k], 0, &b);
            if (same(&a, &b)) {
                sw_cli_error("%s %s and %s %s name the same file: one would overwrite the other",
                             out[i].what, out[i].path, out[k].what, out[k].path);
                return SW_EXIT_USAGE;
            }
        }
    }
    return SW_EXIT_OK;
}

int sw_cli_check_run_files(const char *log, const sw_cli_list_t *scenes, const sw_cli_file_t *out,
                           size_t nout)
{
    const size_t nin = 1 + (scenes ? scenes->n : 0);
    sw_cli_file_t *in = calloc(nin, sizeof *in);
    if (!in) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    in[0] = (sw_cli_file_t){"LOG", log};
    for (size_t i = 1; i < nin; i++) in[i] = (sw_cli_file_t){"--scene", scenes->v[i - 1]};
    int rc = sw_cli_check_files(in, nin, out, nout);
    free(in);
    return rc;
}

const char *sw_cli_lcm_url_output(const char *url, char *buf, size_t len)
{
    url = sw_cli_lcm_url_effective(url);
    if (sw_cli_lcm_url_file(url, buf, len) != SW_CLI_URL_WRITES || !buf[0])
        return NULL;
    return buf;
}
