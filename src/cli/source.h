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
 * the same kind of stream (source_lcmlog.c, LCM builds).  sources.c holds
 * the table of the sources the build has; nothing else knows which there
 * are.
 *
 * The calls, in order: open, prepare, engine, risk, feed, settle,
 * report, close.  Each prints its own messages (sw_cli_msg()) and returns
 * an exit code. */
#ifndef SWAYWATCH_CLI_SOURCE_H
#define SWAYWATCH_CLI_SOURCE_H

#include <signal.h>

#include "input.h"
#include "monitor_opts.h"
#include "opts.h"
#include "output.h"

/* How a log is read: CSV options, the gate's, and those of lcm-logger
 * files; bound to option rows by the command (input.h, and the sources'
 * own groups: sw_cli_source_groups). */
typedef struct {
    sw_cli_csv_opts_t copts;
    sw_cli_gate_t gate;
    /* lcm-logger files */
    const char *channel;     /* the accel channel regex */
    const char *key_file;    /* --key: authenticated samples only */
    sw_mon_opts_t mo;        /* axes, --max-skew; publishing channels and rate */
    const char *publish_url; /* --publish; NULL: no publishing */
    double speed;            /* --publish: X times real time; 0 as fast as possible */
} sw_cli_read_opts_t;

typedef struct sw_cli_reader sw_cli_reader_t;

/* One source of samples. */
typedef struct sw_cli_source {
    const char *name;  /* what such a log is, in messages and reports: "a CSV log" */
    const char *takes; /* what its own options are for: "CSV logs" */
    int (*sniff)(const void *buf, size_t len); /* its first bytes; NULL: anything (the last row) */
    const sw_cli_option_t *const *own;         /* option tables only it takes (NULL-ended) */
    void (*init)(sw_cli_read_opts_t *o);       /* its options' defaults */
    /* its option groups bound to o, those of publishing too with publish,
     * into g; returns how many (at most SW_CLI_SOURCE_GROUPS); may be NULL */
    size_t (*groups)(sw_cli_read_opts_t *o, sw_cli_group_t *g, int publish);
    /* the reader's calls below, for this source; NULL: nothing to do */
    int (*prepare)(sw_cli_reader_t *R);
    int (*start)(sw_cli_reader_t *R, const sw_scene_t *scenes, size_t n,
                 const sw_engine_opts_t *eo);
    /* every sample into R->st; fills R->run's counts and dates, R->accepted,
     * R->interrupted or R->halted, and f (the gate's facts, those refused
     * upstream counted) and *vert (a vertical channel) for the check */
    int (*feed)(sw_cli_reader_t *R, sw_gate_facts_t *f, int *vert);
    /* after the verdict's check: rc its result, SW_EXIT_USAGE when there
     * was none (no sample taken, a signal) */
    void (*checked)(sw_cli_reader_t *R, int rc);
    int (*report)(sw_cli_reader_t *R);
    void (*close)(sw_cli_reader_t *R);
} sw_cli_source_t;

#define SW_CLI_SOURCE_GROUPS 4 /* groups a source offers at most */
#define SW_CLI_SOURCES_MAX 4   /* rows of the table at most */

/* The source of a log whose first len bytes are buf: the first row of the
 * build's table whose sniff matches.  NULL when they say it is a kind of
 * log this build does not read; *needs then says what it would take
 * ("lcm-logger files need the LCM build"). */
const sw_cli_source_t *sw_cli_source_of(const void *buf, size_t len, const char **needs);
/* The rows of the table, NULL after the last. */
const sw_cli_source_t *sw_cli_source_at(size_t i);

extern const sw_cli_source_t sw_cli_source_csv;
extern const sw_cli_source_t sw_cli_source_lcmlog; /* LCM builds */

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
