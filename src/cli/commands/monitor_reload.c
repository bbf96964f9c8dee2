/* SPDX-License-Identifier: GPL-3.0-or-later */
/* monitor_reload.c - the scene files of "swaywatch monitor" read again on
 * SIGHUP (systemctl reload; monitor_cli.h), without losing the state of
 * the packages whose scene did not change.
 *
 * A file being written is never read half-way.  The SIGHUP only asks for
 * a reload; the loop goes on with the samples, and the files are read once
 * none has changed (stat(): size, modification and change times, inode)
 * for SW_CLI_RELOAD_QUIET seconds, and refused if one changed while it was
 * read.  A file still changing SW_CLI_RELOAD_GIVE_UP seconds after the
 * SIGHUP is not applied.  The safe way to change a scene is the rename(2)
 * convention of editors and configuration tools: write the new file beside
 * the old one and rename it over it; a scene rewritten in place is said so
 * when it is applied.
 *
 * Every --scene file is read again, with the --set overrides, exactly as at
 * start.  A package whose scene values are the same as before (comments,
 * layout and the order of keys do not count) is left alone: its state, its
 * alarm state and its place in the message streams go on.  A package whose
 * scene changed is rebuilt and starts from rest at the current sample time
 * (sw_mon_replace).  All or nothing: if a file cannot be read or is not a
 * valid scene, or a changed scene cannot be built, nothing is changed and
 * the monitor goes on with the scenes it had.  The file list itself is the
 * one given at start.
 *
 * The --key file is one more file of the list: waited on and read with
 * the scenes, all or nothing; its keys replace the monitor's (the
 * freshness seen under each key id goes on), so a key is changed without
 * a restart (docs/security.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cost.h"
#include "keyfile.h"
#include "monitor_cli.h"

/* ---- what the files look like --------------------------------------------------- */

static void file_id(const char *path, sw_cli_file_id_t *id)
{
    struct stat st;
    memset(id, 0, sizeof *id);
    if (stat(path, &st) != 0)
        return; /* reading it will say why */
    id->exists = 1;
    id->dev = st.st_dev;
    id->ino = st.st_ino;
    id->size = st.st_size;
    id->mtime = st.st_mtim;
    id->ctime = st.st_ctim;
}

static int same_time(struct timespec a, struct timespec b)
{
    return a.tv_sec == b.tv_sec && a.tv_nsec == b.tv_nsec;
}

static int same_id(const sw_cli_file_id_t *a, const sw_cli_file_id_t *b)
{
    return a->exists == b->exists && a->dev == b->dev && a->ino == b->ino && a->size == b->size &&
           same_time(a->mtime, b->mtime) && same_time(a->ctime, b->ctime);
}

/* The files a reload reads: the scene files, then the key file. */
static size_t files(const mon_ctx_t *c)
{
    return c->n + (c->key_file != NULL);
}

static const char *file_path(const mon_ctx_t *c, size_t k)
{
    return k < c->n ? c->opts->scenes.v[k] : c->key_file;
}

/* The first file whose id differs from ids[], or files(c); ids[]
 * updated. */
static size_t look(const mon_ctx_t *c, sw_cli_file_id_t *ids)
{
    const size_t n = files(c);
    size_t first = n;
    for (size_t k = 0; k < n; k++) {
        sw_cli_file_id_t now;
        file_id(file_path(c, k), &now);
        if (!same_id(&now, &ids[k]) && first == n)
            first = k;
        ids[k] = now;
    }
    return first;
}

int sw_cli_mon_reload_init(mon_ctx_t *c)
{
    sw_cli_reload_t *r = &c->reload;
    memset(r, 0, sizeof *r);
    r->seen = calloc(files(c) ? files(c) : 1, sizeof *r->seen);
    r->loaded = calloc(files(c) ? files(c) : 1, sizeof *r->loaded);
    if (!r->seen || !r->loaded) {
        sw_cli_error("monitor: out of memory");
        return -1;
    }
    look(c, r->loaded);
    return 0;
}

void sw_cli_mon_reload_free(mon_ctx_t *c)
{
    free(c->reload.seen);
    free(c->reload.loaded);
    memset(&c->reload, 0, sizeof c->reload);
}

void sw_cli_mon_reload_ask(mon_ctx_t *c, double now)
{
    sw_cli_reload_t *r = &c->reload;
    if (!r->seen)
        return;
    r->pending = 1;
    r->asked = r->since = now;
    look(c, r->seen);
    fprintf(stderr,
            "swaywatch: monitor: reload: SIGHUP; the scene files%s are read once none has "
            "changed for %g s\n",
            c->key_file ? " and the key file" : "", SW_CLI_RELOAD_QUIET);
}

double sw_cli_mon_reload_due(const mon_ctx_t *c)
{
    return c->reload.pending ? c->reload.since + SW_CLI_RELOAD_QUIET : INFINITY;
}

/* ---- the reload ----------------------------------------------------------------- */

/* How scene file k came to change since it was read: "" (it did not),
 * or a note for the message. */
static const char *how_changed(const sw_cli_reload_t *r, size_t k)
{
    const sw_cli_file_id_t *a = &r->loaded[k], *b = &r->seen[k];
    if (same_id(a, b))
        return "";
    if (a->exists && b->exists && a->dev == b->dev && a->ino == b->ino)
        return "; it was rewritten in place: renaming a new file over it is safer";
    return "";
}

/* The keys of a key file read again into the monitor; said when the file
 * changed. */
static void apply_keys(mon_ctx_t *c, sw_keyring_t *keys)
{
    sw_mon_set_keys(c->mon, keys);
    sw_keyring_destroy(c->keys);
    c->keys = keys;
    const size_t k = c->n; /* the key file's place */
    if (same_id(&c->reload.loaded[k], &c->reload.seen[k]))
        return;
    char ids[4 * SW_AUTH_ID_MAX + 1] = "";
    size_t used = 0;
    for (int i = 0; i < sw_keyring_size(keys) && used < sizeof ids; i++)
        used += (size_t)snprintf(ids + used, sizeof ids - used, "%s%d", i ? ", " : "",
                                 sw_keyring_id(keys, i));
    fprintf(stderr,
            "swaywatch: monitor: reload: %d key%s from %s (id %s); the freshness seen under "
            "each id kept\n",
            sw_keyring_size(keys), sw_keyring_size(keys) == 1 ? "" : "s", c->key_file, ids);
}

/* Read the files, now quiet, and apply what changed: SW_EXIT_OK (or the
 * code of the refusal, nothing changed); *again set when a file changed
 * while it was read (nothing changed, the wait starts over). */
static int reload(mon_ctx_t *c, int *again)
{
    sw_cli_reload_t *r = &c->reload;
    const sw_cli_opts_t *o = c->opts;
    sw_scene_t *scenes = c->scenes, *fresh = NULL, *changed = NULL;
    const size_t n = c->n;
    size_t nf = 0, nchanged = 0;
    sw_engine_t *trial = NULL;
    sw_keyring_t *keys = NULL;
    char msg[512] = "";
    *again = 0;

    int rc = sw_cli_load_scenes(o, &fresh, &nf);
    int krc = SW_EXIT_OK;
    if (c->key_file)
        keys = sw_cli_key_load("--key", c->key_file, &krc);
    /* The files must still be what was waited on: else one was written
     * while it was read. */
    const size_t moved = look(c, r->seen);
    if (moved < files(c)) {
        fprintf(stderr,
                "swaywatch: monitor: reload: %s changed while it was read; waiting until it "
                "stays unchanged for %g s\n",
                file_path(c, moved), SW_CLI_RELOAD_QUIET);
        r->changing = moved;
        *again = 1;
        goto done;
    }
    if (rc == SW_EXIT_OK)
        rc = krc;
    if (rc != SW_EXIT_OK)
        goto keep;
    if (nf != n) { /* the same files as at start: cannot happen */
        sw_cli_error("monitor: reload: %zu scenes instead of %zu", nf, n);
        rc = SW_EXIT_USAGE;
        goto keep;
    }
    changed = calloc(n, sizeof *changed);
    if (!changed) {
        sw_cli_error("monitor: reload: out of memory");
        rc = SW_EXIT_IO;
        goto keep;
    }
    for (size_t k = 0; k < n; k++)
        if (!sw_scene_equal(&scenes[k], &fresh[k]))
            changed[nchanged++] = fresh[k];
    if (nchanged == 0) {
        fprintf(stderr, "swaywatch: monitor: reload: no scene changed; %zu packages kept\n", n);
        goto applied;
    }
    /* A package cannot gain or lose its lateral plane while the monitor
     * runs (its input and engines are made with or without one): refused
     * whole, with the reason, never a depth judged along the truck only. */
    for (size_t k = 0; k < n && c->lat_axis >= 0; k++) {
        const int had = sw_engine_planes(sw_mon_engine(c->mon), k) == 2;
        if (!sw_scene_equal(&scenes[k], &fresh[k]) && had != (sw_scene_has_depth(&fresh[k]) != 0)) {
            sw_cli_error(
                "monitor: reload: %s: package.depth %s: a package cannot gain or lose its "
                "lateral plane while the monitor runs; restart the monitor",
                fresh[k].name, had ? "removed" : "added");
            rc = SW_EXIT_USAGE;
            goto keep;
        }
    }
    /* Build the changed packages once on the side with the monitor's
     * options: what passes here cannot fail in sw_mon_replace() but for
     * memory, so a reload does not stop half-way. */
    sw_engine_opts_t eo;
    sw_cli_engine_opts(o, &eo);
    int err = 0;
    trial = sw_engine_create(changed, nchanged, &eo, &err, msg, sizeof msg);
    if (!trial) {
        sw_cli_error("monitor: reload: %s", msg[0] ? msg : sw_strerror(err));
        rc = SW_EXIT_USAGE;
        goto keep;
    }
    for (size_t k = 0; k < n; k++) {
        if (sw_scene_equal(&scenes[k], &fresh[k]))
            continue;
        if (sw_mon_replace(c->mon, k, &fresh[k], msg, sizeof msg) != SW_OK) {
            sw_cli_error("monitor: reload: %s: %s", fresh[k].name, msg);
            rc = SW_EXIT_IO;
            continue; /* only memory: the package keeps its old scene */
        }
        fprintf(stderr, "swaywatch: monitor: reload: %s rebuilt from %s (scene changed%s)\n",
                fresh[k].name, o->scenes.v[k], how_changed(r, k));
        scenes[k] = fresh[k];
        sw_cli_warn_no_reserve(sw_mon_risk(c->mon), k, k + 1, scenes);
    }
    fprintf(stderr, "swaywatch: monitor: reload: %zu of %zu packages rebuilt, the others kept\n",
            nchanged, n);
    sw_cli_warn_scene_cost(changed, nchanged, &eo);
    sw_cli_warn_reserve_cost(sw_mon_risk(c->mon), 0, n, scenes, c->reserve_rate);
applied:
    if (keys)
        apply_keys(c, keys);
    keys = NULL;
    memcpy(r->loaded, r->seen, files(c) * sizeof *r->loaded);
    goto done;

keep:
    sw_cli_error("monitor: reload: %s not applied; going on with the scenes%s of before",
                 c->key_file ? "scene and key files" : "scene files",
                 c->key_file ? " and keys" : "");
done:
    sw_keyring_destroy(keys);
    sw_engine_destroy(trial);
    free(changed);
    free(fresh);
    return rc;
}

int sw_cli_mon_reload_poll(mon_ctx_t *c, double now)
{
    sw_cli_reload_t *r = &c->reload;
    if (!r->pending || now < r->since + SW_CLI_RELOAD_QUIET)
        return 0;
    const size_t moved = look(c, r->seen);
    int again = moved < files(c);
    if (again)
        r->changing = moved;
    else
        reload(c, &again);
    if (!again) {
        r->pending = 0;
        return 1;
    }
    if (now - r->asked < SW_CLI_RELOAD_GIVE_UP) {
        r->since = now; /* changed: wait for it to stay the same */
        return 0;
    }
    sw_cli_error(
        "monitor: reload: %s is still changing %g s after the SIGHUP: %s not applied; going "
        "on with the scenes%s of before (write the new file beside the old one and rename it "
        "over it)",
        file_path(c, r->changing), now - r->asked,
        c->key_file ? "scene and key files" : "scene files", c->key_file ? " and keys" : "");
    r->pending = 0;
    return 1;
}
