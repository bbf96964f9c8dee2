/* SPDX-License-Identifier: GPL-3.0-or-later */
/* opts.h - options from one table, in the manner of git's parse-options.
 *
 * One row describes one option: its long and short name, its kind, where
 * its value goes (an offset in the struct its group points at), the rule
 * its value must follow and its help.  A command binds tables of rows to
 * its structs (sw_cli_group_t) and parses argv once with sw_cli_parse(),
 * which also prints --help, generated from the same rows.  Tables shared by
 * several commands: scene and integration, output (here), CSV input
 * (input.h), LCM input and publishing (lcmopts.h).
 *
 * Everything here prints its own messages ("swaywatch: ..." on stderr) and
 * returns an exit code, so a command is a short sequence of calls with one
 * cleanup path.  opts.c holds the parser and the help, scenes.c the shared
 * rows and the scenes and engine they make. */
#ifndef SWAYWATCH_CLI_OPTS_H
#define SWAYWATCH_CLI_OPTS_H

#include <stddef.h>
#include <stdio.h>

#include "cli.h"

/* ---- the table --------------------------------------------------------- */

typedef enum {
    SW_CLI_END = 0, /* ends a table */
    SW_CLI_SECTION, /* a --help section: help is its title; the rows after it belong to it */
    SW_CLI_TEXT,    /* a paragraph printed after the options of its section */
    SW_CLI_FLAG,    /* no value: stores the row's value (an int) */
    SW_CLI_STRING,  /* stores the argument (a const char *, pointing into argv) */
    SW_CLI_DOUBLE,  /* a number (double) that follows the row's rule */
    SW_CLI_LONG,    /* a whole number (long), min to max (if max > 0); see SW_CLI_CAP */
    SW_CLI_LIST,    /* repeatable: appends the argument to a sw_cli_list_t */
    SW_CLI_CALL,    /* fn reads the argument (or none, if the row has no arg) */
    SW_CLI_HELP     /* -h, --help: the help on stdout, exit 0 */
} sw_cli_kind;

/* Rules of SW_CLI_DOUBLE rows. */
enum { SW_NUM_ANY = 0, SW_NUM_POSITIVE, SW_NUM_NONNEGATIVE, SW_NUM_NONZERO };

#define SW_CLI_HIDDEN 1u /* a row or a group left out of --help (aliases, refused options) */
#define SW_CLI_CAP 2u    /* SW_CLI_LONG: above max taken as max (a thread count), not refused */

typedef struct sw_cli_option sw_cli_option_t;

/* Reads arg (NULL for an option without a value) for option o into dest
 * (the row's destination).  Returns SW_EXIT_OK, or SW_EXIT_USAGE /
 * SW_EXIT_IO after printing why. */
typedef int (*sw_cli_option_fn)(const sw_cli_option_t *o, const char *arg, void *dest);

struct sw_cli_option {
    sw_cli_kind kind;
    int short_name;        /* 0: none */
    const char *long_name; /* without the dashes */
    const char *arg;       /* the value's name in --help ("FILE"); NULL: takes no value */
    size_t offset;         /* where the value goes, in the struct the group points at */
    int rule;              /* SW_CLI_DOUBLE: SW_NUM_* */
    long min, max;         /* SW_CLI_LONG */
    double def;            /* SW_CLI_DOUBLE, SW_CLI_LONG: stored before parsing; and the
                              value of "%g" in help, for every kind */
    int value;             /* SW_CLI_FLAG: what it stores */
    const char *what;      /* the expected value in words: "expected WHAT, got 'ARG'" */
    const char *help;      /* one line, wrapped when printed; SECTION and TEXT: as printed */
    sw_cli_option_fn fn;   /* SW_CLI_CALL: reads the value; STRING, LIST: checks it before it
                              is stored; DOUBLE, LONG: checks (or adjusts) it after the rule */
    void (*help_fn)(char *buf, size_t len); /* help made at run time, instead of help */
    unsigned flags;                         /* SW_CLI_HIDDEN, SW_CLI_CAP */
    /* SW_CLI_DOUBLE (and CALL rows that read with sw_cli_opt_double()):
     * the bounds, inclusive, when hi > lo: a value (its magnitude under
     * SW_NUM_NONZERO) outside [lo, hi] is refused, but for 0 under
     * SW_NUM_NONNEGATIVE (0: off).  --help appends them to the row's help:
     * "(range LO to HI)", or "(0, or LO to HI)". */
    double lo, hi;
};

/* A macro's value as a string, for help texts ("20"). */
#define SW_CLI_STR_(x) #x
#define SW_CLI_STR(x) SW_CLI_STR_(x)

/* .offset of a row: the member f of the group's struct T. */
#define SW_CLI_AT(T, f) .offset = offsetof(T, f)

/* The destination of a SW_CLI_LIST row. */
typedef struct {
    const char **v; /* the arguments in order (pointing into argv) */
    size_t n, cap;
} sw_cli_list_t;

/* A table bound to the struct its offsets point into. */
typedef struct {
    const sw_cli_option_t *rows; /* ended by a SW_CLI_END row */
    void *base;
    const char *section; /* --help section of the rows before the table's first SECTION */
    unsigned flags;      /* SW_CLI_HIDDEN: parsed, left out of --help */
    /* set by sw_cli_parse(): the group's first option given and its place
     * among all the options given (1, 2, ...); NULL and 0 if none */
    const sw_cli_option_t *given;
    int given_at;
} sw_cli_group_t;

/* A group of rows into base; in section sec (the rows before the table's
 * first SECTION row). */
#define SW_CLI_GROUP(rows_, base_)       \
    {                                    \
        .rows = (rows_), .base = (base_) \
    }
#define SW_CLI_GROUP_IN(rows_, base_, sec)                 \
    {                                                      \
        .rows = (rows_), .base = (base_), .section = (sec) \
    }

/* What --help says besides the options. */
enum { SW_CLI_EXIT_OVERTURN = 1, SW_CLI_EXIT_STRICT = 2, SW_CLI_EXIT_INCOMPLETE = 4 };
typedef struct {
    const char *name;      /* "replay", as in messages */
    const char *usage;     /* after "usage: swaywatch " (may go on over indented lines) */
    const char *about;     /* the paragraphs after the usage line, as printed */
    unsigned exits;        /* SW_CLI_EXIT_*: the codes 1 and the --strict case */
    const char *exit_text; /* the exit-code paragraph, instead of the usual one */
} sw_cli_command_t;

/* sw_cli_parse(): the options are read, go on with the operands. */
#define SW_CLI_CONTINUE (-1)

/* Parse argv (argv[0] is the command's name) once, against the rows of the
 * n groups: the defaults of DOUBLE and LONG rows are stored, then each
 * option read and checked, in order.  Returns SW_CLI_CONTINUE with the
 * first operand's index in *operand (getopt_long has moved the operands
 * behind the options), or the command's exit code: SW_EXIT_OK after
 * --help (printed on stdout), SW_EXIT_USAGE or SW_EXIT_IO after the first
 * bad option (reported).  Free the lists with sw_cli_parse_free(). */
int sw_cli_parse(const sw_cli_command_t *cmd, sw_cli_group_t *g, size_t n, int argc, char **argv,
                 int *operand);
void sw_cli_parse_free(const sw_cli_group_t *g, size_t n);

/* The row of rows (a table ending with SW_CLI_END) named long_name, or
 * NULL: for a value checked against its bounds after parsing. */
const sw_cli_option_t *sw_cli_option_named(const sw_cli_option_t *rows, const char *long_name);

/* The command's --help: usage, about, every visible section with its
 * options and paragraphs, the exit codes.  A section gathers every row
 * under its title, in the order of the groups, where the title first
 * appears. */
void sw_cli_print_help(FILE *f, const sw_cli_command_t *cmd, const sw_cli_group_t *g, size_t n);

/* Number values, checked as rows check them (an end pointer, finite, the
 * rule or the minimum): on a bad value "swaywatch: --NAME: expected WHAT,
 * got 'ARG'" and SW_EXIT_USAGE.  For fn of SW_CLI_CALL rows that parse a
 * number with their row's rule. */
int sw_cli_opt_double(const sw_cli_option_t *o, const char *arg, double *out);
/* The bounds of o alone, on a value v read from arg (a row that scales
 * what it read, such as a value in g, checks after scaling): SW_EXIT_OK,
 * or SW_EXIT_USAGE after "swaywatch: --NAME: out of range: expected LO to
 * HI, got 'ARG'". */
int sw_cli_opt_range(const sw_cli_option_t *o, const char *arg, double v);
int sw_cli_opt_long(const sw_cli_option_t *o, const char *arg, long *out);

/* A number and its unit, as shock standards state pulses: "10g",
 * "-98.1m/s2", "11ms", "0.011 s" (the units a CSV header may carry,
 * csv.h: g or m/s2 and its spellings for an acceleration, s, ms or us for
 * a time, time_role).  *si gets the value in m/s^2 or s, *unit the unit
 * read (SW_CSV_UNIT_*; SW_CSV_UNIT_NONE for a bare number, taken as SI only
 * if bare_ok).  The row's rule applies to the number.  On a bad number
 * "expected WHAT", on a unit not in the list or a missing one a message
 * naming the units accepted, and SW_EXIT_USAGE. */
int sw_cli_opt_quantity(const sw_cli_option_t *o, const char *arg, int time_role, int bare_ok,
                        double *si, int *unit);
/* The units sw_cli_opt_quantity() accepts, in words, with an example. */
const char *sw_cli_units_accepted(int time_role);

/* Comma-separated numbers, fractions such as 1/3 allowed, into a new
 * array (free()); positive: each must be > 0.  FROM:TO:STEP (inclusive;
 * the values FROM + i STEP, computed from i) or such a list, at most max
 * values.  SW_EXIT_OK, or SW_EXIT_USAGE / SW_EXIT_IO (reported, naming
 * opt). */
int sw_cli_parse_list(const char *opt, const char *arg, int positive, double **vals, size_t *n);
int sw_cli_parse_range(const char *opt, const char *arg, size_t max, double **vals, size_t *n);

/* The operands: exactly one LOG (NULL, reported, otherwise), or none
 * (SW_EXIT_OK, or SW_EXIT_USAGE reported). */
const char *sw_cli_log_operand(const char *cmd, int argc, char **argv, int first);
int sw_cli_no_operand(const char *cmd, int argc, char **argv, int first);

/* ---- scene, integration and output options -------------------------------- */

typedef struct {
    sw_cli_list_t scenes; /* --scene, in order */
    sw_cli_list_t sets;   /* --set section.key=value, in order */
    const char *scheme;   /* --scheme, NULL = engine default */
    double dt;            /* s, --dt; 0 = scheme default */
    double rtol, atol;    /* 0 = engine defaults */
    double accuracy;      /* rad, --accuracy: pick scheme and dt for this error in theta; 0 = off */
    const char *out_path; /* --out: state time series CSV */
    long every;           /* --every: write every Nth state row of each package */
    const char *events_path; /* --events: event list CSV */
    const char *wide_path;   /* --wide: the state series, a column group per package */
    const char *plot_path;   /* --plot: the state figure (.png or .svg) */
    double reserve_rate;     /* Hz of the log's time, --reserve-rate; 0: no reserve */
    int all_impacts;         /* --all-impacts: every impact in --events, micro ones too */
    int json, quiet, verbose;
} sw_cli_opts_t;

/* Rows into a sw_cli_opts_t. */
extern const sw_cli_option_t sw_cli_scene_options[];       /* Scene: --scene, --set */
extern const sw_cli_option_t sw_cli_integration_options[]; /* Integration: --scheme, --dt,
                                                              --rtol, --atol */
extern const sw_cli_option_t sw_cli_accuracy_options[];    /* Integration: --accuracy */
extern const sw_cli_option_t sw_cli_output_options[];      /* Output: --out, --every, --events,
                                                              --json, --quiet */
extern const sw_cli_option_t sw_cli_picture_options[];     /* Output: --wide, --plot (replay,
                                                              simulate) */
extern const sw_cli_option_t sw_cli_reserve_options[];     /* Reserve and impacts:
                                                              --reserve-rate, --all-impacts */
/* --verbose and --help, with no section of their own. */
extern const sw_cli_option_t sw_cli_common_options[];

/* ---- scenes and the engine -------------------------------------------------- */

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

/* What the run means (risk.h) for the n scenes, with --reserve-rate: NULL
 * on failure, reported. */
sw_risk_t *sw_cli_risk_create(const sw_cli_opts_t *o, const sw_scene_t *scenes, size_t n);
/* At the end of the stream: the minimum of a risk made min_only (risk.h,
 * sw_risk_resolve) for each of the n packages; a failure is said on
 * stderr, and that package has no minimum. */
void sw_cli_risk_resolve(sw_risk_t *r, const sw_scene_t *scenes, size_t n);

/* With --accuracy, set eo's scheme and dt to the cheapest measured setting
 * (sw_scheme_for_accuracy) that reaches it for every scene's model.
 * Returns SW_EXIT_OK, or SW_EXIT_USAGE (reported) when no measured setting
 * reaches it or a scene's model has no table. */
int sw_cli_resolve_accuracy(const sw_cli_opts_t *o, const sw_scene_t *scenes, size_t n,
                            sw_engine_opts_t *eo);

/* Engine options from the shared options (callbacks left NULL). */
void sw_cli_engine_opts(const sw_cli_opts_t *o, sw_engine_opts_t *eo);

/* Create the engine; on failure print the reason, return NULL.  Warns
 * about scenes estimated to run slower than SW_COST_MIN_RT_FACTOR times
 * real time (cost.h). */
sw_engine_t *sw_cli_engine_create(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo);

#endif
