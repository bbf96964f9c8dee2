/* lcmlog.h - what the commands do around lcm-logger logs (eventlog.h):
 * real-time pacing of a replay that publishes.  LCM builds only. */
#ifndef SWAYWATCH_CLI_LCMLOG_H
#define SWAYWATCH_CLI_LCMLOG_H

#include <signal.h>

#include "cli.h"
#include "eventlog.h"

/* Real-time pacing by sample time: sw_cli_pace(p, t) sleeps until t / speed
 * seconds after the first call (t in s on the samples' clock).  A step of
 * more than SW_CLI_MAX_PAUSE s of wall time restarts the clock there
 * instead of waiting.  A signal that sets *stop (if not NULL) ends a
 * sleep. */
#define SW_CLI_MAX_PAUSE 3600.0
typedef struct {
    double speed; /* > 0; 0: no pacing */
    const volatile sig_atomic_t *stop;
    int started;
    double start, t0; /* monotonic s at sample time t0 */
} sw_cli_pacer_t;
void sw_cli_pace(sw_cli_pacer_t *p, double t);

#endif
