/* SPDX-License-Identifier: GPL-3.0-or-later */
/* input.h - acceleration logs: CSV input options, rejected rows, log files
 * read in chunks (their first bytes tell their source: source.h); a
 * whole log held in memory is the library's (swaywatch/forensics.h). */
#ifndef SWAYWATCH_CLI_INPUT_H
#define SWAYWATCH_CLI_INPUT_H

#include <signal.h>
#include <stdio.h>

#include "cli.h"
#include "opts.h"

/* ---- the input gate's options (every source) ------------------------------------ */

/* What the gate (gate.h) checks, and how a doubtful log's verdict is
 * given: the same options and defaults for CSV logs, lcm-logger files and
 * the live monitor. */
typedef struct {
    double gap;          /* s; 0 = 10 times the logger's spacing, at least 10 ms (gate.h) */
    int gap_policy;      /* SW_GAP_BRIDGE, SW_GAP_RESTART */
    double max_bridge;   /* s */
    double max_accel;    /* m/s^2 */
    double max_jump;     /* s; 0 = never wait (the gate's jump < 0); default the gap */
    long confirm;        /* samples */
    int vert_gravity;    /* -1 not said, 0 removed, 1 included */
    double max_rejected; /* %, of samples refused before a log is */
    int force;           /* a verdict even where the plausibility check refuses it */
} sw_cli_gate_t;

void sw_cli_gate_init(sw_cli_gate_t *g);
extern const sw_cli_option_t sw_cli_gate_options[];
/* The gate's options from the CLI's (callbacks left NULL). */
void sw_cli_gate_opts(const sw_cli_gate_t *g, sw_gate_opts_t *o);
/* The plausibility limits from the CLI's options. */
void sw_cli_gate_limits(const sw_cli_gate_t *g, sw_gate_limits_t *lim);

/* ---- CSV input options ------------------------------------------------------- */

typedef struct {
    sw_csv_opts_t csv;
    int strict; /* stop at the first rejected row */
} sw_cli_csv_opts_t;

void sw_cli_csv_opts_init(sw_cli_csv_opts_t *o);

/* Rows into a sw_cli_csv_opts_t, in the CSV input section: the options of
 * CSV logs alone (columns, delimiter, header, time unit), and those that
 * also apply to lcm-logger files (--accel-unit, --flip, --strict). */
extern const sw_cli_option_t sw_cli_csv_options[];
extern const sw_cli_option_t sw_cli_sample_options[];

/* fn of an --accel-unit row: m/s2 or g into dest, a double of m/s^2 per
 * unit (1 g = SW_G0).  Shared by CSV and LCM input. */
int sw_cli_accel_unit(const sw_cli_option_t *o, const char *arg, void *dest);
/* fn of a --max-accel row: "30g" or m/s^2, at most SW_MAX_ACCEL. */
int sw_cli_accel_limit(const sw_cli_option_t *o, const char *arg, void *dest);

/* Rejected rows of a CSV log: each one counted, the first
 * SW_CLI_MAX_PRINTED_REJECTS printed as "NAME:LINE: reason" (none with
 * quiet); with strict the first one stops the run and later ones are not
 * counted. */
#define SW_CLI_MAX_PRINTED_REJECTS 20
typedef struct {
    const char *name; /* the log, as quoted in messages */
    int strict, quiet;
    int stop;      /* strict saw a rejected row */
    long reported; /* rejected rows seen (printed or not) */
    long printed;  /* printed one by one */
} sw_cli_rejects_t;
void sw_cli_rejects_add(sw_cli_rejects_t *r, long line, const char *reason);
/* The line for the rows not printed one by one ("... N more rejected rows",
 * or "N rejected rows" with quiet); nothing if there are none. */
void sw_cli_rejects_summary(const sw_cli_rejects_t *r);

/* A log read in chunks: path, or "-" for standard input.  Open reads the
 * first chunk, whose first bytes tell its source (sw_cli_source_of(),
 * source.h).
 * Both return SW_EXIT_OK or SW_EXIT_IO (reported). */
typedef struct {
    FILE *in;
    char *buf;
    size_t len;       /* bytes in buf */
    const char *name; /* path, or "(stdin)" */
} sw_cli_logfile_t;
int sw_cli_logfile_open(sw_cli_logfile_t *f, const char *path);
/* Feed the chunks to csv, from the one read, until the end of the file,
 * then finish it; stops early when the reader fails or *stop is set (after
 * any chunk; after(user), if not NULL, runs after each feed and the
 * finish).  *fr gets the reader's last status (< 0: it failed). */
int sw_cli_logfile_pump(sw_cli_logfile_t *f, sw_csv_t *csv, const int *stop, void (*after)(void *),
                        void *user, int *fr);
void sw_cli_logfile_close(sw_cli_logfile_t *f); /* zeroed or open; closes stdin never */

/* The cap of forensics' --max-samples: 2^25 samples, 9.3 h at 1 kHz. */
#define SW_CLI_LOG_MAX_SAMPLES_N 33554432
#define SW_CLI_LOG_MAX_SAMPLES ((long)SW_CLI_LOG_MAX_SAMPLES_N)

#endif
