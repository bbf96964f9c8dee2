/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cli.h - the swaywatch command: exit codes, the error printer and the
 * subcommands.  What they share lives in opts.h (options, scenes),
 * input.h (logs), output.h (files and summaries) and plot.h (figures). */
#ifndef SWAYWATCH_CLI_H
#define SWAYWATCH_CLI_H

#include <stdio.h>

#include "swaywatch/swaywatch.h"

/* Exit codes (documented in README.md and every --help). */
enum {
    SW_EXIT_OK = 0,         /* success */
    SW_EXIT_OVERTURNED = 1, /* a package overturned and --fail-on-overturn was given */
    SW_EXIT_USAGE = 2,      /* bad usage or bad input (scene, options, --strict rows) */
    SW_EXIT_IO = 3,         /* a file could not be read or written */
    SW_EXIT_PARTIAL = 4     /* batch: some logs failed (their records say why); the rest done */
};

/* One subcommand: argv[0] is the subcommand's name. */
typedef int (*sw_cmd_fn)(int argc, char **argv);

int cmd_replay(int argc, char **argv);
int cmd_simulate(int argc, char **argv);
int cmd_monitor(int argc, char **argv); /* LCM builds only (SW_HAVE_LCM) */
int cmd_watch(int argc, char **argv);   /* LCM and curses builds only (SW_HAVE_WATCH) */
int cmd_boundary(int argc, char **argv);
int cmd_forensics(int argc, char **argv);
int cmd_batch(int argc, char **argv);
int cmd_keygen(int argc, char **argv); /* LCM builds only */

/* "swaywatch: " + printf-style message + newline, on the calling thread's
 * message stream (sw_cli_msg()). */
void sw_cli_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Where the calling thread's messages go: standard error, unless
 * sw_cli_msg_to() gave it another stream (a batch job collects the
 * messages of its log, to put them in the log's record and print them in
 * the order of the logs, whatever thread ran it).  Lines that go with a
 * message (a header listed, counts) are printed on sw_cli_msg() too. */
FILE *sw_cli_msg(void);
/* Send this thread's messages to f (NULL: standard error); returns the
 * stream they went to before. */
FILE *sw_cli_msg_to(FILE *f);

#endif
