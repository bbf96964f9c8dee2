/* SPDX-License-Identifier: GPL-3.0-or-later */
/* notify.h - what a long-running command tells its service manager
 * (sd_notify(3)): READY=1 once it serves, WATCHDOG=1 while its main loop
 * turns, STATUS= a line for 'systemctl status', STOPPING=1.
 *
 * Built with libsystemd (SW_HAVE_SYSTEMD) this is sd_notify() and
 * sd_watchdog_enabled(); without it every call does nothing and there is
 * no watchdog.  Outside systemd (no NOTIFY_SOCKET) nothing is sent either,
 * so the commands call these unconditionally. */
#ifndef SWAYWATCH_CLI_NOTIFY_H
#define SWAYWATCH_CLI_NOTIFY_H

/* Send state (newline-separated "KEY=VALUE" assignments, as sd_notify()).
 * Returns > 0 when sent, 0 when there is nobody to tell (no NOTIFY_SOCKET,
 * or a build without libsystemd), < 0 on an error (-errno). */
int sw_cli_notify(const char *state);

/* The same with "STATUS=" and text (a line; a newline in it ends it). */
int sw_cli_notify_status(const char *text);

/* Seconds between two WATCHDOG=1 of the main loop: half the watchdog
 * timeout systemd set for this process (WATCHDOG_USEC, WATCHDOG_PID), as
 * sd_watchdog_enabled(3) recommends; 0 when there is no watchdog. */
double sw_cli_watchdog_interval(void);

#endif
