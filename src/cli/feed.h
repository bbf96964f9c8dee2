/* SPDX-License-Identifier: GPL-3.0-or-later */
/* feed.h - a log into an engine through the input gate, as every command
 * that reads a log does it: the CSV reader choosing columns and units
 * (and saying which), the gate deciding what the engine gets, every
 * refused row and every gap or restart reported with its line, and the
 * plausibility check that decides whether the log's verdict is given. */
#ifndef SWAYWATCH_CLI_FEED_H
#define SWAYWATCH_CLI_FEED_H

#include <signal.h>

#include "input.h"
#include "output.h"

/* What a fed log was. */
typedef struct {
    long rows;              /* data rows the CSV reader saw */
    long rejected;          /* rows refused, by the reader or the gate */
    sw_gate_facts_t facts;  /* the gate's */
    int interrupted;        /* SIGINT or SIGTERM stopped the reading: the counts cover the
                               rows fed before it (interrupt.h) */
    int halted;             /* the caller's halt stopped it (nothing else is filled) */
    int time_unit;          /* SW_CSV_UNIT_* of the time column (DATETIME: dates) */
    sw_cli_unused_t unused; /* the rows refused and the stream's events, kept */
} sw_cli_fed_t;

/* Stream the CSV log lf (opened) through the reader and the gate into e,
 * then flush the gate.  A SIGINT or SIGTERM stops it between rows
 * (out->interrupted; the gate is not flushed, the rest of the chunk read
 * is not counted).  Refused rows and stream events go to stderr with
 * their line (rows: the first SW_CLI_MAX_PRINTED_REJECTS; none with
 * quiet).  take (may be NULL) gets each sample the engine got, with
 * take_user (gate.h); once *halt (may be NULL) is non-zero the reading
 * stops before the next row (out->halted).  Returns SW_EXIT_OK, SW_EXIT_USAGE (bad options or
 * columns the header does not tell, --strict at a refused row: reported) or SW_EXIT_IO. */
int sw_cli_feed_csv(sw_cli_logfile_t *lf, const sw_cli_csv_opts_t *co, const sw_cli_gate_t *go,
                    sw_engine_t *e, int quiet, sw_gate_take_fn take, void *take_user,
                    const volatile sig_atomic_t *halt, sw_cli_fed_t *out);

/* The plausibility check of a fed log (gate.h) and the vertical channel's
 * gravity: SW_EXIT_OK with run's check and forced set (a warning or a
 * forced verdict, printed), or SW_EXIT_USAGE with the reason and what to
 * do printed (no verdict).  vert: the source has a vertical channel. */
int sw_cli_feed_verdict(const char *name, const sw_gate_facts_t *f, const sw_cli_gate_t *go,
                        int vert, int quiet, sw_cli_run_t *run);

#endif
