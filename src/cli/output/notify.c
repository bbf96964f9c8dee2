/* SPDX-License-Identifier: GPL-3.0-or-later */
/* notify.c - sd_notify() when built with libsystemd (notify.h). */
#include "notify.h"

#include <stdint.h>
#include <stdio.h>

#ifdef SW_HAVE_SYSTEMD
#include <systemd/sd-daemon.h>
#endif

int sw_cli_notify(const char *state)
{
#ifdef SW_HAVE_SYSTEMD
    return sd_notify(0, state);
#else
    (void)state;
    return 0;
#endif
}

int sw_cli_notify_status(const char *text)
{
    char buf[512];
    int n = snprintf(buf, sizeof buf, "STATUS=%s", text);
    if (n < 0)
        return -1;
    for (char *p = buf; *p; p++)
        if (*p == '\n') {
            *p = '\0';
            break;
        }
    return sw_cli_notify(buf);
}

double sw_cli_watchdog_interval(void)
{
#ifdef SW_HAVE_SYSTEMD
    uint64_t usec = 0;
    if (sd_watchdog_enabled(0, &usec) > 0 && usec > 0)
        return (double)usec / 2e6;
#endif
    return 0.0;
}
