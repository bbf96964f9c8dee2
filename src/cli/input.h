/* input.h - acceleration logs: CSV input options, rejected rows, log files
 * read in chunks, and whole CSV logs held in memory. */
#ifndef SWAYWATCH_CLI_INPUT_H
#define SWAYWATCH_CLI_INPUT_H

#include <getopt.h>
#include <stdio.h>

#include "cli.h"

/* ---- CSV logs held in memory ---------------------------------------------------
 * The CSV input options replay documents, for commands that run one log
 * many times and so read it into memory first (forensics).  replay streams
 * its log and parses the same options itself. */
enum {
    SW_OPT_CSV_TIME_COL = 1200, /* getopt_long codes, apart from the shared, own and LCM ones */
    SW_OPT_CSV_ACCEL_COL,
    SW_OPT_CSV_VERT_COL,
    SW_OPT_CSV_DELIM,
    SW_OPT_CSV_HEADER,
    SW_OPT_CSV_NO_HEADER,
    SW_OPT_CSV_ACCEL_UNIT,
    SW_OPT_CSV_TIME_UNIT,
    SW_OPT_CSV_FLIP,
    SW_OPT_CSV_STRICT
};

#define SW_CLI_CSV_LONGOPTS                                                                        \
    {"time-col", required_argument, NULL, SW_OPT_CSV_TIME_COL},                                    \
        {"accel-col", required_argument, NULL, SW_OPT_CSV_ACCEL_COL},                              \
        {"vert-col", required_argument, NULL, SW_OPT_CSV_VERT_COL},                                \
        {"delimiter", required_argument, NULL, SW_OPT_CSV_DELIM},                                  \
        {"header", no_argument, NULL, SW_OPT_CSV_HEADER},                                          \
        {"no-header", no_argument, NULL, SW_OPT_CSV_NO_HEADER},                                    \
        {"accel-unit", required_argument, NULL, SW_OPT_CSV_ACCEL_UNIT},                            \
        {"time-unit", required_argument, NULL, SW_OPT_CSV_TIME_UNIT},                              \
        {"flip", no_argument, NULL, SW_OPT_CSV_FLIP}, {"strict", no_argument, NULL, SW_OPT_CSV_STRICT}

typedef struct {
    sw_csv_opts_t csv;
    int strict; /* stop at the first rejected row */
} sw_cli_csv_opts_t;

void sw_cli_csv_opts_init(sw_cli_csv_opts_t *o);
void sw_cli_print_csv_help(FILE *f);
/* Handle a CSV option code for opts, a sw_cli_csv_opts_t (the form of a
 * sw_cli_group_t); -1 if c is not one, else SW_EXIT_OK or SW_EXIT_USAGE
 * (reported). */
int sw_cli_csv_option(void *opts, int c, const char *arg);
/* --accel-unit m/s2|g: m/s^2 per unit in *scale (1 g = 9.80665 m/s^2);
 * SW_EXIT_OK or SW_EXIT_USAGE (reported).  Shared by CSV and LCM input. */
int sw_cli_parse_accel_unit(const char *arg, double *scale);

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
 * first chunk, whose first bytes tell CSV (sw_lcmlog_sniff() false) from
 * an lcm-logger file.  Both return SW_EXIT_OK or SW_EXIT_IO (reported). */
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
int sw_cli_logfile_pump(sw_cli_logfile_t *f, sw_csv_t *csv, const int *stop,
                        void (*after)(void *), void *user, int *fr);
void sw_cli_logfile_close(sw_cli_logfile_t *f); /* zeroed or open; closes stdin never */

/* A whole log: accepted rows in file order, SI units. */
typedef struct {
    double *t, *a_g, *a_z; /* a_z only with --vert-col (has_z), else NULL */
    size_t n, cap;
    int has_z;
    long rows, rejected; /* data rows seen, and refused (reported on stderr) */
} sw_cli_log_t;

/* Read path ("-" = stdin) into L; rejected rows reported like replay does
 * (counted only with quiet).  Returns SW_EXIT_OK, SW_EXIT_USAGE (bad rows
 * under --strict, no usable row, an lcm-logger file) or SW_EXIT_IO.  Free
 * with sw_cli_log_free(). */
int sw_cli_log_read(const char *path, const sw_cli_csv_opts_t *o, int quiet, sw_cli_log_t *L);
void sw_cli_log_free(sw_cli_log_t *L);

#endif
