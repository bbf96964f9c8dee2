/* lcmlog.c - the pacing of a replay that publishes (lcmlog.h). */
#include "lcmlog.h"

#include <math.h>
#include <time.h>

#include "monitor.h"

void sw_cli_pace(sw_cli_pacer_t *p, double t)
{
    if (!(p->speed > 0.0))
        return;
    const double now = sw_mon_clock();
    if (!p->started || (t - p->t0) / p->speed - (now - p->start) > SW_CLI_MAX_PAUSE) {
        p->started = 1;
        p->start = now;
        p->t0 = t;
        return;
    }
    const double due = p->start + (t - p->t0) / p->speed;
    while (!(p->stop && *p->stop)) {
        const double d = due - sw_mon_clock();
        if (d <= 0.0)
            break;
        struct timespec ts = {(time_t)d, (long)((d - floor(d)) * 1e9)};
        nanosleep(&ts, NULL); /* a signal ends it early: the loop looks at *stop */
    }
}
