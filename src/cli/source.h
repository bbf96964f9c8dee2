/* SPDX-License-Identifier: GPL-3.0-or-later */
/* source.h - a log read the way replay reads it, for every command that
 * reads one (replay and its batch jobs, forensics): the file opened, its
 * first bytes telling a CSV log from an lcm-logger file, the options the
 * source does not take refused, then the samples through the input gate
 * into an engine: a CSV log by the CSV reader (feed.h), an lcm-logger
 * file in-process into the monitor core (eventlog.h, monitor.h; a pipe is
 * spooled once); the plausibility check of the verdict; the settling after
 * the end.  What the gate handed the engine can be recorded as it goes (a
 * take callback, gate.h), so that a command that runs the log many times
 * reads it exactly once, exactly as replay does.
 *
 * The calls, in order: open, prepare, engine, feed, settle, report, close.
 * Each prints its own messages (sw_cli_msg()) and returns an exit code. */
#ifndef SWAYWATCH_CLI_SOURCE_H
#define SWAYWATCH_CLI_SOURCE_H

#include "feed.h"
#include "input.h"
#include "opts.h"
#include "output.h"
#ifdef SW_HAVE_LCM
#include <lcm/lcm.h>

#include "eventlog.h"
#include "keyfile.h"
#include "lcmlog.h"
#include "lcmopts.h"
#include "monitor.h"
#endif

/* How a log is read: CSV options, the gate's, and those of lcm-logger
 * files; bound to option rows by the command (input.h, lcmopts.h and
 * sw_cli_channel_options below). */
typedef struct {
    sw_cli_csv_opts_t copts;
    sw_cli_gate_t gate;
    const char *channel;  /* lcm-logger files: the accel channel regex */
    const char *key_file; /* lcm-logger files: --key, authenticated samples only */
#ifdef SW_HAVE_LCM
    sw_mon_opts_t mo; /* lcm-logger files: axes, --max-skew; publishing channels */
#endif
} sw_cli_read_opts_t;

void sw_cli_read_opts_init(sw_cli_read_opts_t *o);

#ifdef SW_HAVE_LCM
/* --accel-channel (and --channel, its old name) into a sw_cli_read_opts_t. */
extern const sw_cli_option_t sw_cli_channel_options[];
/* The section of the options of lcm-logger files. */
#define SW_CLI_LCM_SECTION                                                            \
    "lcm-logger files (swaywatch.accel_t; of the CSV options, --accel-unit, --flip\n" \
    "and --strict apply):"
#endif

/* After sw_cli_parse(): which options only one source takes were given,
 * the first of each (NULL: none): the rows of sw_cli_csv_options for CSV,
 * and for lcm-logger files those of the ng groups g whose rows are
 * sw_cli_channel_options, sw_cli_lcm_input_options or one of the extra
 * tables (a command's own lcm-only rows, NULL-ended; may be NULL). */
typedef struct {
    const char *csv, *lcm;
} sw_cli_given_t;
sw_cli_given_t sw_cli_source_given(const sw_cli_group_t *g, size_t ng,
                                   const sw_cli_option_t *const *extra);

typedef struct {
    const char *log; /* LOG as given */
    const sw_cli_read_opts_t *o;
    sw_cli_logfile_t lf;
    const sw_cli_source_t *src;
    sw_engine_t *e;   /* the engine fed (the monitor core's for lcm-logger files) */
    sw_cli_run_t run; /* what was read: counts, the log's facts, the check */
    int quiet;
    int interrupted;                   /* a signal stopped the reading (interrupt.h) */
    long accepted;                     /* samples the engine got */
    sw_gate_take_fn take;              /* may be NULL: each sample the engine got, with user */
    void *user;                        /* eo.user of the engine */
    double reserve_rate;               /* Hz of the log's time, --reserve-rate (0: no reserve) */
    sw_risk_t *risk;                   /* the reserve, impacts that matter (sw_cli_reader_risk) */
    int risk_owned;                    /* made for a CSV log; else the monitor core's */
    const volatile sig_atomic_t *halt; /* may be NULL: once non-zero (take has all it can
                                          hold) a CSV log is read no further */
    int halted;                        /* halt stopped the reading */
#ifdef SW_HAVE_LCM
    lcm_t *publish; /* may be NULL: where the monitor core publishes */
    sw_mon_t *mon;
    sw_lcmlog_t *lcmlog;
    sw_cli_regions_t regions;
    sw_keyring_t *keys; /* --key's */
#endif
} sw_cli_reader_t;

/* Open LOG ("-" for standard input): a missing file is an I/O error (3)
 * whatever else is wrong, and its first bytes choose the source; then the
 * options it does not take are refused (given).  SW_EXIT_OK,
 * SW_EXIT_USAGE or SW_EXIT_IO. */
int sw_cli_reader_open(sw_cli_reader_t *R, const char *log, const sw_cli_read_opts_t *o, int quiet,
                       sw_cli_given_t given);

/* An lcm-logger file: its reader (the channel regex checked first; a pipe
 * spooled).  A CSV log: nothing.  SW_EXIT_OK, SW_EXIT_USAGE or
 * SW_EXIT_IO. */
int sw_cli_reader_prepare(sw_cli_reader_t *R);

/* The engine for the n scenes with eo (its callbacks and user are the
 * command's; the monitor core takes them over for an lcm-logger file);
 * shared: the scenes' cost was measured and warned about already (a
 * batch), else it is now.  SW_EXIT_OK or SW_EXIT_USAGE (reported). */
int sw_cli_reader_engine(sw_cli_reader_t *R, const sw_scene_t *scenes, size_t n,
                         const sw_engine_opts_t *eo, int shared);

/* After the engine: what the run means (risk.h) at R->reserve_rate, the
 * monitor core's for an lcm-logger file (it publishes it), else made for
 * the n scenes.  The command feeds a risk it owns (risk_owned) from its
 * state callback.  SW_EXIT_OK or SW_EXIT_USAGE (reported). */
int sw_cli_reader_risk(sw_cli_reader_t *R, const sw_cli_opts_t *o, const sw_scene_t *scenes,
                       size_t n);

/* Every sample into the engine, then the verdict's check (not after a
 * signal).  SW_EXIT_OK, SW_EXIT_USAGE (refused: reported) or
 * SW_EXIT_IO. */
int sw_cli_reader_feed(sw_cli_reader_t *R);

/* Up to settle s of zero input after the log (not after a signal, nor
 * after a log with no usable sample). */
void sw_cli_reader_settle(sw_cli_reader_t *R, double settle);

/* After the command's files are closed: what an lcm-logger file held (its
 * corrupted regions, its counts; with quiet only when no sample was
 * usable).  SW_EXIT_OK, or SW_EXIT_USAGE when no sample was usable. */
int sw_cli_reader_report(sw_cli_reader_t *R);

void sw_cli_reader_close(sw_cli_reader_t *R); /* zeroed or open */

#endif
