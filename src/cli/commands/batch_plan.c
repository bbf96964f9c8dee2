/* SPDX-License-Identifier: GPL-3.0-or-later */
/* batch_plan.c - the work list of "swaywatch batch" (batch_int.h): the
 * logs of the operands and of the manifest, in that order, each with its
 * set of the job's options, and what each log costs.
 *
 * The command line's options are parsed once; each distinct set of a
 * manifest line's options is parsed once more, on top of them (a line's
 * --scene replaces the command line's scenes), and its scenes read then,
 * so that a bad option or scene stops the batch before any log is run. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "batch_int.h"
#include "interrupt.h"
#include "keyset.h"

/* The messages printed while f ran, each line again as
 * "swaywatch: WHERE: message". */
static void reprint(const char *where, const char *msgs, size_t len)
{
    const char *p = msgs, *end = msgs + len;
    while (p < end) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        if (le - p >= 11 && !strncmp(p, "swaywatch: ", 11))
            p += 11;
        sw_cli_error("%s: %.*s", where, (int)(le - p), p);
        p = nl ? nl + 1 : end;
    }
}

/* A new set of the job's options: the command line's options, then args
 * (a manifest line's; NULL for none), parsed and made ready.  Messages of
 * a line's set name the manifest's line. */
static int new_set(batch_t *B, char **args, size_t nargs, long line, optset_t *set)
{
    const sw_cli_job_t *J = B->job;
    int rc = SW_EXIT_IO;
    set->opts = J->create();
    if (!set->opts)
        return SW_EXIT_IO;
    sw_cli_group_t g[SW_CLI_JOB_GROUPS + 1];
    size_t ng = 0;
    char **argv = NULL;
    void *alone = NULL;
    char *msgs = NULL;
    size_t mlen = 0;
    FILE *mf = NULL, *before = NULL;
    char where[512];
    snprintf(where, sizeof where, "%s:%ld", B->b.manifest ? B->b.manifest : "", line);
    if (args) { /* the line's messages, to say where they come from */
        mf = open_memstream(&msgs, &mlen);
        if (!mf)
            goto oom;
        before = sw_cli_msg_to(mf);
    }
    size_t nline_scenes = 0;
    int first;
    if (args) {
        /* the line alone: only the job's options, and how many scenes */
        alone = J->create();
        if (!alone)
            goto oom;
        sw_cli_group_t ga[SW_CLI_JOB_GROUPS];
        const size_t na = J->groups(alone, ga);
        char **av = calloc(nargs + 2, sizeof *av);
        if (!av)
            goto oom;
        av[0] = "batch";
        memcpy(av + 1, args, nargs * sizeof *av);
        rc = sw_cli_parse(&sw_batch_cmd, ga, na, (int)nargs + 1, av, &first);
        if (rc == SW_CLI_CONTINUE && first < (int)nargs + 1) {
            sw_cli_error("unexpected '%s': one log a line, first", av[first]);
            rc = SW_EXIT_USAGE;
        }
        free(av);
        if (rc != SW_CLI_CONTINUE)
            goto out;
        nline_scenes = J->common(alone)->scenes.n;
    }
    /* the command line's options (the batch's own too, into a copy), then
     * the line's */
    batch_opts_t scratch = B->b;
    g[ng++] = (sw_cli_group_t)SW_CLI_GROUP(sw_batch_options, &scratch);
    ng += J->groups(set->opts, g + ng);
    argv = calloc((size_t)B->first + nargs + 1, sizeof *argv);
    if (!argv)
        goto oom;
    int argc = 0;
    argv[argc++] = "batch";
    for (int i = 1; i < B->first; i++)
        if (strcmp(B->argv[i], "--"))
            argv[argc++] = B->argv[i];
    for (size_t i = 0; i < nargs; i++) argv[argc++] = args[i];
    rc = sw_cli_parse(&sw_batch_cmd, g, ng, argc, argv, &first);
    if (rc != SW_CLI_CONTINUE)
        goto out;
    sw_cli_list_t *sc = &J->common(set->opts)->scenes;
    if (nline_scenes > 0 && sc->n > nline_scenes) { /* the line's scenes replace the others */
        memmove(sc->v, sc->v + (sc->n - nline_scenes), nline_scenes * sizeof *sc->v);
        sc->n = nline_scenes;
    }
    rc = J->ready(set->opts, g + 1, ng - 1);
    goto out;
oom:
    sw_cli_error("out of memory");
    rc = SW_EXIT_IO;
out:
    if (mf) {
        sw_cli_msg_to(before == stderr ? NULL : before);
        fclose(mf);
        reprint(where, msgs, mlen);
        free(msgs);
    }
    J->destroy(alone);
    free(argv);
    /* the lists of set->opts are freed with it (destroy); the batch's own
     * options have none */
    return rc;
}

/* The key of a manifest line's options: its words joined by a unit
 * separator (no option has one); NULL when it has none (the command
 * line's set), or when memory ran out (*oom). */
static char *line_key(const sw_cli_manifest_line_t *L, int *oom)
{
    *oom = 0;
    if (!L->nargs)
        return NULL;
    size_t len = 1;
    for (size_t i = 0; i < L->nargs; i++) len += strlen(L->args[i]) + 1;
    char *key = malloc(len);
    if (!key) {
        *oom = 1;
        return NULL;
    }
    char *p = key;
    for (size_t i = 0; i < L->nargs; i++) {
        const size_t l = strlen(L->args[i]);
        memcpy(p, L->args[i], l);
        p[l] = '\x1f';
        p += l + 1;
    }
    *p = '\0';
    return key;
}

/* A new set of options for key (taken; NULL: the command line's alone)
 * and manifest line L (NULL for the command line's), parsed and made
 * ready; its index in *idx. */
static int add_set(batch_t *B, char *key, const sw_cli_manifest_line_t *L, size_t *idx)
{
    if (B->nsets == B->sets_cap) {
        const size_t cap = B->sets_cap ? 2 * B->sets_cap : 16;
        optset_t *s = realloc(B->sets, cap * sizeof *s);
        if (!s) {
            free(key);
            sw_cli_error("out of memory");
            return SW_EXIT_IO;
        }
        B->sets = s;
        B->sets_cap = cap;
    }
    optset_t *set = &B->sets[B->nsets++];
    memset(set, 0, sizeof *set);
    set->key = key;
    *idx = B->nsets - 1;
    return new_set(B, key ? L->args : NULL, key ? L->nargs : 0, L ? L->line : 0, set);
}

static int add_item(batch_t *B, const char *log, long line, size_t set, size_t cap)
{
    if (!strcmp(log, "-")) {
        if (line)
            sw_cli_error("%s:%ld: standard input cannot be a log of a batch", B->b.manifest, line);
        else
            sw_cli_error("batch: standard input cannot be a log of a batch");
        return SW_EXIT_USAGE;
    }
    if (B->n == cap)
        return SW_EXIT_IO;
    B->items[B->n++] = (item_t){log, line, set};
    return SW_EXIT_OK;
}

/* The logs: the operands, then the manifest's lines, each with its set of
 * options (made ready: scenes read). */
static int collect(batch_t *B)
{
    int rc;
    if (B->b.manifest) {
        if (B->world.rank == 0)
            rc = sw_cli_manifest_read(B->b.manifest, &B->mtext, &B->mlen);
        else
            rc = SW_EXIT_OK;
        /* standard input reaches rank 0 alone */
        if ((rc = sw_cli_world_share(&B->world, rc, &B->mtext, &B->mlen)) != SW_EXIT_OK)
            return rc;
        if ((rc = sw_cli_manifest_parse(B->b.manifest, B->mtext, B->mlen, &B->man)) != SW_EXIT_OK)
            return rc;
    }
    const size_t cap = (size_t)(B->argc - B->first) + B->man.n;
    if (cap == 0) {
        sw_cli_error("batch: no logs: give them as operands or in a --manifest");
        return SW_EXIT_USAGE;
    }
    B->items = calloc(cap, sizeof *B->items);
    if (!B->items) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    size_t cmd_set = SIZE_MAX; /* the command line's options alone, once needed */
    for (int i = B->first; i < B->argc; i++)
        if ((cmd_set == SIZE_MAX && (rc = add_set(B, NULL, NULL, &cmd_set)) != SW_EXIT_OK) ||
            (rc = add_item(B, B->argv[i], 0, cmd_set, cap)) != SW_EXIT_OK)
            return rc;
    /* The lines grouped by their options in n log n (keyset.h); each
     * distinct set is parsed at its first line, as the lines come. */
    const size_t n = B->man.n;
    char **keys = calloc(n ? n : 1, sizeof *keys);
    size_t *first = calloc(n ? n : 1, sizeof *first);
    size_t *set_of = calloc(n ? n : 1, sizeof *set_of);
    rc = keys && first && set_of ? SW_EXIT_OK : SW_EXIT_IO;
    for (size_t i = 0; i < n && rc == SW_EXIT_OK; i++) {
        int oom;
        keys[i] = line_key(&B->man.v[i], &oom);
        if (oom)
            rc = SW_EXIT_IO;
    }
    if (rc == SW_EXIT_OK && sw_cli_keyset_first((const char *const *)keys, n, first, NULL) != 0)
        rc = SW_EXIT_IO;
    if (rc != SW_EXIT_OK)
        sw_cli_error("out of memory");
    for (size_t i = 0; i < n && rc == SW_EXIT_OK; i++) {
        const sw_cli_manifest_line_t *L = &B->man.v[i];
        if (sw_cli_signal) { /* a long manifest: nothing is written yet */
            sw_cli_error("batch: interrupted by %s while reading the manifest; nothing written",
                         sw_cli_signal_name(sw_cli_signal));
            rc = sw_cli_interrupt_code();
            break;
        }
        if (first[i] != i) {
            set_of[i] = set_of[first[i]];
        } else if (!keys[i]) {
            if (cmd_set == SIZE_MAX)
                rc = add_set(B, NULL, NULL, &cmd_set);
            set_of[i] = cmd_set;
        } else {
            rc = add_set(B, keys[i], L, &set_of[i]);
            keys[i] = NULL; /* the set's now */
        }
        if (rc == SW_EXIT_OK)
            rc = add_item(B, L->log, L->line, set_of[i], cap);
    }
    for (size_t i = 0; keys && i < n; i++) free(keys[i]);
    free(keys);
    free(first);
    free(set_of);
    return rc;
}

/* The logs' sizes: the longest go first.  A log that cannot be read costs
 * nothing; its job says why. */
static int costs(batch_t *B)
{
    B->cost = calloc(B->n, sizeof *B->cost);
    if (!B->cost) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    if (B->world.rank != 0)
        return SW_EXIT_OK; /* rank 0 hands out the work */
    for (size_t i = 0; i < B->n; i++) {
        struct stat st;
        if (stat(B->items[i].log, &st) == 0)
            B->cost[i] = (double)st.st_size;
    }
    return SW_EXIT_OK;
}

int sw_batch_plan(batch_t *B)
{
    const int rc = collect(B);
    return rc == SW_EXIT_OK ? costs(B) : rc;
}
