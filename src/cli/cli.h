/* cli.h - what the subcommands of the swaywatch command share. */
#ifndef SWAYWATCH_CLI_H
#define SWAYWATCH_CLI_H

#include <stdio.h>

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

/* "swaywatch: " + printf-style message + newline, on stderr. */
void sw_cli_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* lcm-logger files given to replay (lcmlog.c, LCM builds only): argc/argv
 * are replay's own, as the user typed them (argv[0] = "replay"). */
int sw_cli_replay_lcmlog(const char *path, int argc, char **argv);
/* The paragraph of replay's --help about lcm-logger files. */
void sw_cli_print_lcmlog_help(FILE *f);

#endif
