/* SPDX-License-Identifier: GPL-3.0-or-later */
/* journal.h - messages for people who read them in the journal or on a
 * terminal: one line per alarm, and the sd-daemon priority prefixes
 * ("<2>", "<4>", ...) that make journald file a line under its level when
 * standard error is the journal.
 *
 * systemd tells a service that its standard error is the journal by the
 * environment variable JOURNAL_STREAM ("DEVICE:INODE" of the stream it
 * connected, sd-daemon(3), systemd.exec(5)); a line written there that
 * starts with "<N>" is logged at priority N (journalctl -p).  Anywhere else
 * (a terminal, a file, a pipe, or a child that inherited the variable but
 * writes elsewhere) the lines go out without the prefix. */
#ifndef SWAYWATCH_CLI_JOURNAL_H
#define SWAYWATCH_CLI_JOURNAL_H

#include <stddef.h>
#include <stdint.h>

#include "swaywatch/alarm.h"

/* syslog priorities, as sd-daemon(3)'s SD_CRIT, SD_WARNING, ... */
enum { SW_PRIO_CRIT = 2, SW_PRIO_ERR = 3, SW_PRIO_WARNING = 4, SW_PRIO_INFO = 6 };

/* Non-zero if standard error is the stream JOURNAL_STREAM names (its
 * device and inode match).  Decided at the first call and remembered. */
int sw_cli_stderr_is_journal(void);

/* "<N>" for priority prio when standard error is the journal, else "". */
const char *sw_cli_journal_prefix(int prio);

/* The priority of an alarm level: critical 2, warn 4, info 6. */
int sw_cli_alarm_priority(sw_alarm_level level);

/* A wall-clock time (us since 1970) as ISO 8601 UTC with milliseconds,
 * "2026-11-22T10:15:30.123Z"; len >= 32.  Rounds down to the ms. */
void sw_cli_iso_time(char *buf, size_t len, int64_t us);

/* One alarm, as the monitor writes it on standard error. */
typedef struct {
    int64_t wall_us; /* wall clock when it was raised, us since 1970 */
    sw_alarm_level level;
    sw_alarm_kind kind;
    const char *package; /* NULL: an input alarm, which concerns every package */
    double theta;        /* rad */
    double margin;       /* 1 */
    double reserve_g;    /* g, the package's latest reserve at the alarm; NaN (or < 0,
                            alarm_t's "none"): not known, left out */
    const char *text;    /* the alarm's sentence */
} sw_cli_alarm_line_t;

/* Format a as one line, without the newline and without a priority prefix:
 *   swaywatch: alarm TIME level=LEVEL package=NAME kind=KIND theta=RAD
 *     margin=M [reserve_g=G] text="TEXT"
 * (one line; wrapped here only).  TIME is ISO 8601 UTC with ms; an input
 * alarm has package=- theta=- margin=-; a name with a space or a '"' is
 * quoted, a '"' in it or in the text becomes '\''.  Truncated to len - 1
 * bytes; returns the length it needed (as snprintf). */
size_t sw_cli_alarm_format(char *buf, size_t len, const sw_cli_alarm_line_t *a);

/* Write a's line to standard error in one write, with the priority prefix
 * of its level when standard error is the journal. */
void sw_cli_alarm_print(const sw_cli_alarm_line_t *a);

#endif
