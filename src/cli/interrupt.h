/* SPDX-License-Identifier: GPL-3.0-or-later */
/* interrupt.h - SIGINT and SIGTERM in the commands that run to an end
 * (replay, simulate, forensics, boundary, batch).
 *
 * The handler (installed with sigaction, SA_RESTART) only records the
 * signal in sw_cli_signal; the loops look at it between rows or samples
 * and stop there, so every output file ends with a whole row, and the
 * command closes its files, prints its summary marked as interrupted and
 * exits with 128 + the signal (130 for SIGINT, 143 for SIGTERM, as shells
 * report them).  A second signal ends the process at once.
 *
 * A computation inside the library that cannot stop between steps and
 * writes nothing (a boundary sweep, a safety-factor search) runs in
 * "immediate" mode: a signal then prints a line naming what was stopped
 * and exits at once, from the handler, with the same code. */
#ifndef SWAYWATCH_CLI_INTERRUPT_H
#define SWAYWATCH_CLI_INTERRUPT_H

#include <signal.h>

#include "cli.h"

/* The first SIGINT or SIGTERM received; 0 if none. */
extern volatile sig_atomic_t sw_cli_signal;

/* Install the handlers: SW_EXIT_OK, or SW_EXIT_IO (reported). */
int sw_cli_interrupt_install(void);

/* Immediate mode while msg is not NULL: a signal prints "swaywatch: MSG
 * (SIGINT)" and exits.  msg must stay valid until the next call. */
void sw_cli_interrupt_now(const char *msg);

/* Immediate mode off for the rest of the process: batch runs searches on
 * worker threads, and its main thread writes the records of the logs that
 * are done before it ends the process (a search's _exit would lose
 * them). */
void sw_cli_interrupt_deferred(void);

/* 128 + the signal received (SW_EXIT_OK if none). */
int sw_cli_interrupt_code(void);

/* "SIGINT", "SIGTERM". */
const char *sw_cli_signal_name(int sig);

#endif
