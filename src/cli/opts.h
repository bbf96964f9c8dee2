/* opts.h - the options every command shares (scene, integration, output),
 * number parsing, scene loading and the engine built from the options. */
#ifndef SWAYWATCH_CLI_OPTS_H
#define SWAYWATCH_CLI_OPTS_H

#include <getopt.h>
#include <stdio.h>

#include "cli.h"

/* replay and simulate (and later monitor, forensics) take the same scene,
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

#endif
