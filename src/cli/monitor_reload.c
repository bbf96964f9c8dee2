/* SPDX-License-Identifier: GPL-3.0-or-later */
/* monitor_reload.c - the scene files of "swaywatch monitor" read again on
 * SIGHUP (systemctl reload; monitor_cli.h), without losing the state of
 * the packages whose scene did not change.
 *
 * Every --scene file is read again, with the --set overrides, exactly as at
 * start.  A package whose scene values are the same as before (comments,
 * layout and the order of keys do not count) is left alone: its state, its
 * alarm state and its place in the message streams go on.  A package whose
 * scene changed is rebuilt and starts from rest at the current sample time
 * (sw_mon_replace).  All or nothing: if a file cannot be read or is not a
 * valid scene, or a changed scene cannot be built, nothing is changed and
 * the monitor goes on with the scenes it had.  The file list itself is the
 * one given at start. */
#include <stdio.h>
#include <stdlib.h>

#include "cost.h"
#include "monitor_cli.h"

int sw_cli_mon_reload(sw_mon_t *mon, const sw_cli_opts_t *o, sw_scene_t *scenes, size_t n)
{
    sw_scene_t *fresh = NULL, *changed = NULL;
    size_t nf = 0, nchanged = 0;
    sw_engine_t *trial = NULL;
    char msg[512] = "";

    int rc = sw_cli_load_scenes(o, &fresh, &nf);
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
        goto done;
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
        if (sw_mon_replace(mon, k, &fresh[k], msg, sizeof msg) != SW_OK) {
            sw_cli_error("monitor: reload: %s: %s", fresh[k].name, msg);
            rc = SW_EXIT_IO;
            continue; /* only memory: the package keeps its old scene */
        }
        fprintf(stderr, "swaywatch: monitor: reload: %s rebuilt from %s (scene changed)\n",
                fresh[k].name, o->scenes.v[k]);
        scenes[k] = fresh[k];
        sw_cli_warn_no_reserve(sw_mon_risk(mon), k, k + 1, scenes);
    }
    fprintf(stderr, "swaywatch: monitor: reload: %zu of %zu packages rebuilt, the others kept\n",
            nchanged, n);
    sw_cli_warn_scene_cost(changed, nchanged, &eo);
    goto done;

keep:
    sw_cli_error("monitor: reload: scene files not applied; going on with the scenes of before");
done:
    sw_engine_destroy(trial);
    free(changed);
    free(fresh);
    return rc;
}
