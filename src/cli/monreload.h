/* monreload.h - the monitor re-reads its scene files on SIGHUP
 * (monreload.c; LCM builds only). */
#ifndef SWAYWATCH_MONRELOAD_H
#define SWAYWATCH_MONRELOAD_H

#include "cli.h"
#include "monitor.h"

/* Re-read the scene files of o (with its --set overrides) and rebuild the
 * packages of mon whose scene changed; scenes[0..n) are the monitor's
 * current scenes, updated in place.  Says what it did on stderr.  Returns
 * SW_EXIT_OK, or SW_EXIT_USAGE / SW_EXIT_IO with nothing changed. */
int sw_cli_monitor_reload(sw_mon_t *mon, const sw_cli_opts_t *o, sw_scene_t *scenes, size_t n);

#endif
