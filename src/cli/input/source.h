/* SPDX-License-Identifier: GPL-3.0-or-later */
/* source.h - a log read the way replay reads it, for every command that
 * reads one (replay and its batch jobs, forensics): the file opened, its
 * first bytes choosing its source, the options the source does not take
 * refused, then the samples into one input stream (stream.h: the gate,
 * the engine, the reserve), the plausibility check of the verdict, the
 * settling after the end.  What the gate handed the engine can be
 * recorded as it goes (a take callback, gate.h), so that a command that
 * runs the log many times reads it exactly once, exactly as replay does.
 *
 * A source is a row of functions (sw_cli_source_t), as LCM's providers
 * are: a CSV log through the CSV reader (source_csv.c), an lcm-logger
 * file through the monitor core, which decodes its accel_t messages into
 * the same kind of stream (source_lcmlog.c, LCM builds).  sources.h says
 * what a source is; sources.c holds the table of the sources the build
 * has, and nothing else knows which there are.
 *
 * The calls, in order: open, prepare, engine, risk, feed, settle,
 * report, close.  Each prints its own messages (sw_cli_msg()) and returns
 * an exit code. */
#ifndef SWAYWATCH_CLI_SOURCE_H
#define SWAYWATCH_CLI_SOURCE_H

#include <signal.h>

#include "input.h"
#include "opts.h"
#include "output.h"
#include "sources.h"

/* The options' defaults, every source's. */
void sw_cli_read_opts_init(sw_cli_read_opts_t *o);

/* Every source's option groups bound to o (publish: those of publishing
 * too; CSV's own rows, sw_cli_csv_options, the command places itself),
 * into g; returns how many (at most SW_CLI_SOURCE_GROUPS per source). */
size_t sw_cli_source_groups(sw_cli_read_opts_t *o, sw_cli_group_t *g, int publish);

/* After sw_cli_parse() of the ng groups g: for each source of which an
 * option only it takes was given, that source and the first such option
 * given. */
typedef struct {
    size_t n;
    const sw_cli_source_t *src[SW_CLI_SOURCES_MAX];
    const char *opt[SW_CLI_SOURCES_MAX];
} sw_cli_given_t;
sw_cli_given_t sw_cli_source_given(const sw_cli_group_t *g, size_t ng);

struct sw_cli_reader {
    const char *log; /* LOG as given */
    const sw_cli_read_opts_t *o;
    sw_cli_logfile_t lf;
    const sw_cli_source_t *src;
    sw_stream_t *st;  /* the input stream the source feeds (the monitor core's for an
                         lcm-logger file) */
    sw_engine_t *e;   /* its engine */
    sw_risk_t *risk;  /* its reserve, impacts that matter */
    sw_cli_run_t run; /* what was read: counts, the log's facts, the check */
    int quiet;
    int interrupted;                   /* a signal stopped the reading (interrupt.h) */
    long accepted;                     /* samples the engine got */
    sw_gate_take_fn take;              /* may be NULL: each sample the engine got, with user */
    void *user;                        /* eo.user of the engine */
    double reserve_rate;               /* Hz of the log's time, --reserve-rate (0: no reserve) */
    int reserve_min_only;              /* nothing shows the reserve of each state (no --out,
                                          --wide or figure): a CSV log's stream seeks its
                                          minimum alone (risk.h min_only); an lcm-logger
                                          file's monitor core keeps its rate */
    const volatile sig_atomic_t *halt; /* may be NULL: once non-zero (take has all it can
                                          hold) a CSV log is read no further */
    int halted;                        /* halt stopped the reading */
    void *priv;                        /* the source's own (made by prepare, freed by close) */
    int lateral; /* the command reports a lateral plane: a CSV log's lateral column drives
                    the packages whose scene gives a depth (engine opts.lateral) */
    sw_gate_take_lat_fn take_lat; /* may be NULL: with a lateral plane read, called instead
                                     of take, with the lateral value too */
};

/* Open LOG ("-" for standard input): a missing file is an I/O error (3)
 * whatever else is wrong, and its first bytes choose the source; then the
 * options it does not take are refused (given).  SW_EXIT_OK,
 * SW_EXIT_USAGE or SW_EXIT_IO. */
int sw_cli_reader_open(sw_cli_reader_t *R, const char *log, const sw_cli_read_opts_t *o, int quiet,
                       sw_cli_given_t given);

/* What the source needs before the engine (an lcm-logger file: its
 * reader, the channel regex checked first, a pipe spooled).  SW_EXIT_OK,
 * SW_EXIT_USAGE or SW_EXIT_IO. */
int sw_cli_reader_prepare(sw_cli_reader_t *R);

/* The stream for the n scenes with eo (its callbacks and user are the
 * command's, R->take, R->reserve_rate and R->reserve_min_only set
 * before): R->st, R->e and
 * R->risk; shared: the scenes' cost was measured and warned about already
 * (a batch), else it is now.  SW_EXIT_OK, SW_EXIT_USAGE or SW_EXIT_IO
 * (reported). */
int sw_cli_reader_engine(sw_cli_reader_t *R, const sw_scene_t *scenes, size_t n,
                         const sw_engine_opts_t *eo, int shared);

/* What the run means (risk.h, the stream's): into R->run, and what the
 * reserve cannot do or costs, said.  SW_EXIT_OK. */
int sw_cli_reader_risk(sw_cli_reader_t *R, const sw_cli_opts_t *o, const sw_scene_t *scenes,
                       size_t n);

/* Every sample into the stream, then the verdict's check (not after a
 * signal, nor when no sample was taken).  SW_EXIT_OK, SW_EXIT_USAGE
 * (refused: reported) or SW_EXIT_IO. */
int sw_cli_reader_feed(sw_cli_reader_t *R);

/* Up to settle s of zero input after the log (not after a signal, nor
 * after a log with no usable sample). */
void sw_cli_reader_settle(sw_cli_reader_t *R, double settle);

/* After the command's files are closed: what the source has to say of
 * the log (an lcm-logger file's corrupted regions and counts; with quiet
 * only when no sample was usable).  SW_EXIT_OK, or SW_EXIT_USAGE when no
 * sample was usable. */
int sw_cli_reader_report(sw_cli_reader_t *R);

void sw_cli_reader_close(sw_cli_reader_t *R); /* zeroed or open */

#endif
