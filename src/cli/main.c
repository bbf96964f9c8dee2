/* SPDX-License-Identifier: GPL-3.0-or-later */
/* main.c - the swaywatch command: dispatch to subcommands (git style). */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "cli.h"
#include "journal.h"
#include "swaywatch/swaywatch.h"

/* The lines after the version, as GNU tools print them (help2man turns
 * them into the manual's COPYRIGHT section). */
static const char licence[] =
    "Copyright (C) 2026 swaywatch developers\n"
    "License GPLv3+: GNU GPL version 3 or later <https://gnu.org/licenses/gpl.html>\n"
    "This is free software: you are free to change and redistribute it.\n"
    "There is NO WARRANTY, to the extent permitted by law.\n";

static const struct {
    const char *name;
    sw_cmd_fn fn;
    const char *summary;
} commands[] = {
    {"replay", cmd_replay, "replay a recorded log (CSV or lcm-logger) through the model"},
    {"simulate", cmd_simulate, "run a half-sine or full-sine pulse through the model"},
#ifdef SW_HAVE_LCM
    {"monitor", cmd_monitor, "live: subscribe to acceleration over LCM, publish state and alarms"},
#endif
#ifdef SW_HAVE_WATCH
    {"watch", cmd_watch, "live view of the monitor's states and alarms in the terminal"},
#endif
    {"boundary", cmd_boundary, "overturning boundary curves: lowest overturning pulse vs omega/p"},
    {"forensics", cmd_forensics,
     "a log's outcome, safety factor, and what support would have saved it"},
    {"batch", cmd_batch, "many logs on every core (and MPI rank): JSON Lines records, a CSV table"},
#ifdef SW_HAVE_LCM
    {"keygen", cmd_keygen, "a key for authenticated sensors (monitor --key, the senders' --key)"},
#endif
};

/* Per thread: the jobs of a batch run on several threads at once, each
 * collecting the messages of its own log. */
static _Thread_local FILE *msg_stream;

FILE *sw_cli_msg(void)
{
    return msg_stream ? msg_stream : stderr;
}

FILE *sw_cli_msg_to(FILE *f)
{
    FILE *before = sw_cli_msg();
    msg_stream = f;
    return before;
}

void sw_cli_error(const char *fmt, ...)
{
    FILE *f = sw_cli_msg();
    va_list ap;
    va_start(ap, fmt);
    /* Under systemd an error is logged at priority err (journal.h); a
     * batch job's messages are kept, not logged. */
    if (f == stderr)
        fputs(sw_cli_journal_prefix(SW_PRIO_ERR), f);
    fputs("swaywatch: ", f);
    vfprintf(f, fmt, ap);
    fputc('\n', f);
    va_end(ap);
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: swaywatch <command> [options]\n"
            "\n"
            "Tells whether floating cargo on a truck will tip over.\n"
            "\n"
            "Commands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(f,
            "\n"
            "Options:\n"
            "  -h, --help     this help\n"
            "  -V, --version  the version (also after a command: swaywatch replay --version)\n"
            "\n"
            "Run 'swaywatch help <command>' or 'swaywatch <command> --help' for a command's\n"
            "options.\n"
            "Exit codes: 0 ok, 1 a package overturned (with --fail-on-overturn),\n"
            "2 bad usage or input, 3 I/O error, 4 batch: some logs failed.\n");
}

/* "swaywatch CMD --version", for every command alike (and for help2man,
 * which makes a manual page per command from its --help and --version).
 * Options after "--" are operands, not options. */
static int wants_version(int argc, char **argv)
{
    for (int i = 2; i < argc && strcmp(argv[i], "--"); i++)
        if (!strcmp(argv[i], "--version"))
            return 1;
    return 0;
}

static int is_help(const char *arg)
{
    return !strcmp(arg, "--help") || !strcmp(arg, "-h") || !strcmp(arg, "help");
}

/* The command named name, or NULL. */
static sw_cmd_fn command(const char *name)
{
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(name, commands[i].name))
            return commands[i].fn;
    return NULL;
}

/* "swaywatch help [CMD]", as git does: the command's help, or ours. */
static int help(int argc, char **argv)
{
    if (argc < 3 || is_help(argv[2])) {
        usage(stdout);
        return SW_EXIT_OK;
    }
    if (argc > 3) {
        sw_cli_error("help: one command at a time; unexpected '%s'", argv[3]);
        return SW_EXIT_USAGE;
    }
    sw_cmd_fn fn = command(argv[2]);
    if (!fn) {
        sw_cli_error("'%s' is not a command; see 'swaywatch --help'", argv[2]);
        return SW_EXIT_USAGE;
    }
    char *args[] = {argv[2], "--help", NULL};
    return fn(2, args);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc < 2) {
        usage(stderr);
        return SW_EXIT_USAGE;
    }
    int rc;
    if (!strcmp(argv[1], "help")) {
        rc = help(argc, argv);
    } else if (is_help(argv[1])) {
        usage(stdout);
        return SW_EXIT_OK;
    } else if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "-V")) {
        printf("swaywatch %s\n%s", sw_version(), licence);
        rc = SW_EXIT_OK;
    } else {
        sw_cmd_fn fn = command(argv[1]);
        if (!fn) {
            sw_cli_error("'%s' is not a command; see 'swaywatch --help'", argv[1]);
            return SW_EXIT_USAGE;
        }
        if (wants_version(argc, argv)) {
            printf("swaywatch %s %s\n%s", argv[1], sw_version(), licence);
            rc = SW_EXIT_OK;
        } else {
            rc = fn(argc - 1, argv + 1);
        }
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        sw_cli_error("error writing standard output");
        return SW_EXIT_IO;
    }
    return rc;
}
