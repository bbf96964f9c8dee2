/* cli.h - what the subcommands of the swaywatch command share. */
#ifndef SWAYWATCH_CLI_H
#define SWAYWATCH_CLI_H

#include <getopt.h>
#include <stdio.h>

#include "swaywatch/swaywatch.h"

/* Exit codes (documented in README.md and every --help). */
enum {
    SW_EXIT_OK = 0,         /* success */
    SW_EXIT_OVERTURNED = 1, /* a package overturned and --fail-on-overturn was given */
    SW_EXIT_USAGE = 2,      /* bad usage or bad input (scene, options, --strict rows) */
    SW_EXIT_IO = 3          /* a file could not be read or written */
};

/* One subcommand: argv[0] is the subcommand's name. */
typedef int (*sw_cmd_fn)(int argc, char **argv);

int cmd_replay(int argc, char **argv);
int cmd_simulate(int argc, char **argv);
int cmd_monitor(int argc, char **argv); /* LCM builds only (SW_HAVE_LCM) */
int cmd_boundary(int argc, char **argv);
int cmd_forensics(int argc, char **argv);

/* "swaywatch: " + printf-style message + newline, on stderr. */
void sw_cli_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* ---- shared plumbing (common.c) ----------------------------------------
 * replay and simulate (and later monitor, forensics) take the same scene,
 * engine and output options; each command's getopt_long loop hands the
 * options it does not know itself to sw_cli_common_option(). */

/* getopt_long codes of the shared options (outside the char range). */
enum {
    SW_OPT_SCENE = 1000,
    SW_OPT_SET,
    SW_OPT_SCHEME,
    SW_OPT_DT,
    SW_OPT_RTOL,
    SW_OPT_ATOL,
    SW_OPT_ACCURACY,
    SW_OPT_OUT,
    SW_OPT_EVERY,
    SW_OPT_EVENTS,
    SW_OPT_JSON,
    SW_OPT_QUIET,
    SW_OPT_VERBOSE,
    SW_OPT_HELP,
    SW_OPT_FIRST_OWN /* a command's own options start here */
};

/* Entries for a command's struct option table. */
#define SW_CLI_COMMON_LONGOPTS                                                                     \
    {"scene", required_argument, NULL, SW_OPT_SCENE},                                              \
        {"set", required_argument, NULL, SW_OPT_SET},                                              \
        {"scheme", required_argument, NULL, SW_OPT_SCHEME},                                        \
        {"dt", required_argument, NULL, SW_OPT_DT},                                                \
        {"rtol", required_argument, NULL, SW_OPT_RTOL},                                            \
        {"accuracy", required_argument, NULL, SW_OPT_ACCURACY},                                    \
        {"atol", required_argument, NULL, SW_OPT_ATOL},                                            \
        {"out", required_argument, NULL, SW_OPT_OUT},                                              \
        {"every", required_argument, NULL, SW_OPT_EVERY},                                          \
        {"events", required_argument, NULL, SW_OPT_EVENTS},                                        \
        {"json", no_argument, NULL, SW_OPT_JSON}, {"quiet", no_argument, NULL, SW_OPT_QUIET},     \
        {"verbose", no_argument, NULL, SW_OPT_VERBOSE}, {"help", no_argument, NULL, SW_OPT_HELP}

/* Short forms of the shared options, for the optstring (leading ':' so a
 * missing value is reported by us, with our prefix). */
#define SW_CLI_COMMON_SHORTOPTS ":hs:o:e:qv"

/* The help of the shared options (scene and integration, then output;
 * the first part alone for a command that writes no files), and the
 * exit-code paragraph every --help ends with (overturn, strict: the
 * command has --fail-on-overturn, --strict). */
void sw_cli_print_common_help(FILE *f);
void sw_cli_print_scene_help(FILE *f);
void sw_cli_print_exit_help(FILE *f, int overturn, int strict);

typedef struct {
    const char **scene_files; /* --scene, in order (points into argv) */
    size_t n_scene_files;
    const char **sets; /* --set section.key=value, in order */
    size_t n_sets;
    const char *scheme; /* --scheme, NULL = engine default */
    double dt;          /* s, --dt; 0 = scheme default */
    double rtol, atol;  /* 0 = engine defaults */
    double accuracy;    /* rad, --accuracy: pick scheme and dt for this error in theta; 0 = off */
    const char *out_path;    /* --out: state time series CSV */
    long every;              /* --every: write every Nth state row of each package */
    const char *events_path; /* --events: event list CSV */
    int json, quiet, verbose, help;
} sw_cli_opts_t;

/* Prepare o for at most argc repeated options.  Returns SW_EXIT_OK or
 * SW_EXIT_IO (out of memory, reported).  Free with sw_cli_opts_fini(). */
int sw_cli_opts_init(sw_cli_opts_t *o, int argc);
void sw_cli_opts_fini(sw_cli_opts_t *o);

/* Handle getopt_long's result c (with optarg arg) if it is a shared option.
 * Returns -1 if c is not a shared option, otherwise SW_EXIT_OK or
 * SW_EXIT_USAGE (reported).  Also turns '?' and ':' into the usual
 * messages, using argv[optind - 1] to name the option. */
int sw_cli_common_option(sw_cli_opts_t *o, int c, const char *arg, char **argv);

/* A group of options that several commands share (the CSV reader's, the
 * monitor's): like sw_cli_common_option, returns -1 if c is not one of its
 * options, otherwise SW_EXIT_OK or SW_EXIT_USAGE (reported). */
typedef struct {
    int (*fn)(void *ctx, int c, const char *arg);
    void *ctx;
} sw_cli_group_t;

/* The option loop of every command: getopt_long over argv (opterr off),
 * each option offered first to sw_cli_common_option, then to the n groups
 * in turn; returns the first that none of them takes, for the command's
 * own switch (> 0), SW_CLI_OPT_END after the last option (optind is then
 * the first operand), SW_CLI_OPT_HELP at --help (usage, if not NULL, has
 * printed the help on stdout), or SW_CLI_OPT_BAD after a misuse was
 * reported.  longindex as getopt_long's. */
enum { SW_CLI_OPT_END = -1, SW_CLI_OPT_HELP = -2, SW_CLI_OPT_BAD = -3 };
int sw_cli_getopt(sw_cli_opts_t *o, int argc, char **argv, const char *shortopts,
                  const struct option *longopts, int *longindex, const sw_cli_group_t *groups,
                  size_t n, void (*usage)(FILE *));

/* The one LOG operand left after the options (argv[optind]); NULL, with
 * the message, if there is none or more than one.  cmd names the command. */
const char *sw_cli_log_operand(const char *cmd, int argc, char **argv);

/* Number options: strtod with an end pointer and isfinite().  what is the
 * expectation in words ("a positive number of seconds").  On a bad value
 * prints "swaywatch: OPT: expected WHAT, got 'ARG'" and returns
 * SW_EXIT_USAGE. */
enum { SW_NUM_ANY = 0, SW_NUM_POSITIVE = 1, SW_NUM_NONNEGATIVE = 2, SW_NUM_NONZERO = 3 };
int sw_cli_parse_double(const char *opt, const char *arg, int rule, const char *what, double *out);
int sw_cli_parse_long(const char *opt, const char *arg, long min, const char *what, long *out);

/* Read every --scene file, apply every --set to every scene, validate.
 * Each problem is printed as "swaywatch: FILE:LINE: message".  Returns
 * SW_EXIT_OK with *scenes (free()) and *n set, SW_EXIT_USAGE for bad
 * scenes or no --scene, SW_EXIT_IO if a file cannot be read. */
int sw_cli_load_scenes(const sw_cli_opts_t *o, sw_scene_t **scenes, size_t *n);

/* A sw_diag_fn printing "swaywatch: ORIGIN:LINE: message" and counting the
 * diagnostics in user, a sw_cli_diag_t. */
typedef struct {
    long errors;
} sw_cli_diag_t;
void sw_cli_print_diag(void *user, const char *origin, int line, const char *msg);

/* With --accuracy, set eo's scheme and dt to the cheapest measured setting
 * (sw_scheme_for_accuracy) that reaches it for every scene's model.
 * Returns SW_EXIT_OK, or SW_EXIT_USAGE (reported) when no measured setting
 * reaches it or a scene's model has no table. */
int sw_cli_resolve_accuracy(const sw_cli_opts_t *o, const sw_scene_t *scenes, size_t n,
                            sw_engine_opts_t *eo);

/* Engine options from the shared options (callbacks left NULL). */
void sw_cli_engine_opts(const sw_cli_opts_t *o, sw_engine_opts_t *eo);

/* Create the engine; on failure print the reason, return NULL. */
sw_engine_t *sw_cli_engine_create(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo);

/* Derived quantities of every package (--verbose), on f. */
void sw_cli_print_derived(FILE *f, const sw_engine_t *e, const sw_scene_t *scenes, size_t n);

/* Refuse (message, SW_EXIT_USAGE) an --out or --events that names the input
 * being read (in, may be NULL) or each other: opening them truncates. */
int sw_cli_check_outputs(const sw_cli_opts_t *o, FILE *in);

/* --out: the state time series, one row per package and output instant:
 * t,package,phase,theta,theta_dot,u,u_dot,z,z_dot,margin,margin_bound,
 * uplift_ratio,a_g.  Numbers as %.9g; a non-finite value is written as an
 * empty field and counted. */
typedef struct {
    FILE *f;
    const char *path;
    const sw_scene_t *scenes; /* for package names */
    size_t n;
    long every;
    long *seen;      /* per package: rows offered, for --every */
    long rows;       /* rows written */
    long nonfinite;  /* fields left empty because the value was not finite */
} sw_cli_states_t;

/* Open (path NULL: a disabled writer whose write does nothing). */
int sw_cli_states_open(sw_cli_states_t *w, const char *path, long every, const sw_scene_t *scenes,
                       size_t n);
void sw_cli_states_write(sw_cli_states_t *w, const sw_output_t *out);
/* A CSV text field, quoted only when it has to be (RFC 4180). */
void sw_cli_csv_text(FILE *f, const char *s);
/* Flush and close; returns SW_EXIT_OK or SW_EXIT_IO (reported). */
int sw_cli_states_close(sw_cli_states_t *w);

/* --events: t,package,event,theta,theta_dot,margin,info. */
typedef struct {
    FILE *f;
    const char *path;
    const sw_scene_t *scenes;
    size_t n;
    long rows, nonfinite;
} sw_cli_events_t;

int sw_cli_events_open(sw_cli_events_t *w, const char *path, const sw_scene_t *scenes, size_t n);
void sw_cli_events_write(sw_cli_events_t *w, const sw_event_t *ev);
int sw_cli_events_close(sw_cli_events_t *w);


/* What fed the engine, for the summaries. */
typedef struct {
    const char *log;         /* LOG as given ("-" for stdin), or NULL */
    const sw_pulse_t *pulse; /* simulate: the pulse, or NULL */
    double duration;         /* s, simulate: time simulated */
    long samples_read;       /* data rows seen */
    long samples_rejected;   /* data rows refused (CSV layer or engine) */
    double settle;           /* s, replay: --settle */
} sw_cli_run_t;

/* The one-screen human summary / the JSON summary (DESIGN.md contract). */
void sw_cli_print_summary(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run);
void sw_cli_print_json(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run);

/* s as a JSON string literal (quotes included). */
void sw_cli_json_string(FILE *f, const char *s);

/* Non-zero if any package overturned. */
int sw_cli_any_overturned(const sw_engine_t *e);

/* lcm-logger files given to replay (lcmlog.c, LCM builds only): argc/argv
 * are replay's own, as the user typed them (argv[0] = "replay"). */
int sw_cli_replay_lcmlog(const char *path, int argc, char **argv);
/* The paragraph of replay's --help about lcm-logger files. */
void sw_cli_print_lcmlog_help(FILE *f);

/* Options of replay that only lcm-logger files take.  replay accepts them
 * in its option table (a CSV log given one is an error) and hands the file
 * and its arguments to sw_cli_replay_lcmlog(), which reads them. */
enum {
    SW_OPT_LCM_CHANNEL = 1100,
    SW_OPT_LCM_PUBLISH,
    SW_OPT_LCM_SPEED,
    SW_OPT_LCM_STATE_CHANNEL,
    SW_OPT_LCM_ALARM_CHANNEL,
    SW_OPT_LCM_STATE_RATE,
    SW_OPT_LCM_AXIS,
    SW_OPT_LCM_VERTICAL,
    SW_OPT_LCM_GAP,
    SW_OPT_LCM_MAX_ACCEL,
    SW_OPT_LCM_MAX_SKEW,
    SW_OPT_LCM_MAX_JUMP,
    SW_OPT_LCM_END /* one past the last */
};
#define SW_CLI_LCMLOG_LONGOPTS                                                                     \
    {"channel", required_argument, NULL, SW_OPT_LCM_CHANNEL},                                      \
        {"publish", required_argument, NULL, SW_OPT_LCM_PUBLISH},                                  \
        {"speed", required_argument, NULL, SW_OPT_LCM_SPEED},                                      \
        {"state-channel", required_argument, NULL, SW_OPT_LCM_STATE_CHANNEL},                      \
        {"alarm-channel", required_argument, NULL, SW_OPT_LCM_ALARM_CHANNEL},                      \
        {"state-rate", required_argument, NULL, SW_OPT_LCM_STATE_RATE},                            \
        {"axis", required_argument, NULL, SW_OPT_LCM_AXIS},                                        \
        {"vertical", required_argument, NULL, SW_OPT_LCM_VERTICAL},                                \
        {"gap", required_argument, NULL, SW_OPT_LCM_GAP},                                          \
        {"max-accel", required_argument, NULL, SW_OPT_LCM_MAX_ACCEL},                              \
        {"max-skew", required_argument, NULL, SW_OPT_LCM_MAX_SKEW},                                \
        {"max-jump", required_argument, NULL, SW_OPT_LCM_MAX_JUMP}

/* ---- CSV logs held in memory (logread.c) -------------------------------------
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

/* ---- figures (plot.c): gnuplot as a subprocess ------------------------------
 * sw_cli_plot_open() starts gnuplot with the terminal chosen by the file's
 * extension (.png: pngcairo, or png without cairo; .svg) and its output set;
 * the caller writes the rest of the script (data as inline datablocks) to
 * sw_cli_plot_file() and sw_cli_plot_close() waits for gnuplot and reports
 * its failure with gnuplot's own messages. */
typedef struct sw_plot sw_plot_t;

/* SW_EXIT_OK if path ends in .png or .svg, else SW_EXIT_USAGE (reported,
 * naming opt). */
int sw_cli_plot_check(const char *opt, const char *path);
sw_plot_t *sw_cli_plot_open(const char *path, int width, int height);
FILE *sw_cli_plot_file(sw_plot_t *p);
int sw_cli_plot_close(sw_plot_t *p); /* SW_EXIT_OK or SW_EXIT_IO */
/* s as a gnuplot string literal (single quotes), as it is (file names). */
void sw_cli_plot_string(FILE *f, const char *s);
/* s as a gnuplot string literal to be shown as text: the enhanced-text
 * markup characters (_ ^ { } @ & ~) escaped. */
void sw_cli_plot_text(FILE *f, const char *s);

#endif
