/* SPDX-License-Identifier: GPL-3.0-or-later */
/* replay.h - the replay of one log as "swaywatch replay" does it (the
 * source told by the log's first bytes, the input gate, the plausibility
 * check, the settling), for commands that replay many logs: replay's
 * options are parsed once, then each log runs with a copy of them, on any
 * thread, and its summary goes to a function instead of standard output.
 * cmd_replay.c holds it. */
#ifndef SWAYWATCH_CLI_REPLAY_H
#define SWAYWATCH_CLI_REPLAY_H

#include "opts.h"
#include "output.h"

typedef struct sw_cli_replay sw_cli_replay_t;

/* The most groups sw_cli_replay_groups() binds. */
#define SW_CLI_REPLAY_GROUPS 16

/* replay's options at their defaults; NULL if out of memory (reported).
 * Free with sw_cli_replay_free() (NULL ok), which frees the lists the
 * parser made and the scenes. */
sw_cli_replay_t *sw_cli_replay_new(void);
void sw_cli_replay_free(sw_cli_replay_t *r);

/* replay's groups bound to r, as a batch takes them: the log's reading
 * (CSV, lcm-logger files, the input gate), --settle, --fail-on-overturn,
 * scenes and integration; not the outputs of one replay (--out, --events,
 * --json, --publish) nor --help.  Returns how many were written to g (at
 * most SW_CLI_REPLAY_GROUPS). */
size_t sw_cli_replay_groups(sw_cli_replay_t *r, sw_cli_group_t *g);

/* After sw_cli_parse() of r's groups g: the scenes read and checked and
 * --accuracy resolved, once for every log run with r.  SW_EXIT_OK, or the
 * exit code (reported). */
int sw_cli_replay_ready(sw_cli_replay_t *r, const sw_cli_group_t *g, size_t ng);

/* The options r shares with the other commands (scenes, integration). */
sw_cli_opts_t *sw_cli_replay_opts(sw_cli_replay_t *r);

/* What one log gave: the engine (its packages' summaries) and the run. */
typedef void (*sw_cli_replay_report_fn)(void *user, const sw_engine_t *e, const sw_cli_run_t *run);

/* Replay log with the options of r (ready; only read, so any number of
 * threads may share it), as "swaywatch replay -q" would: messages go to
 * the thread's message stream (sw_cli_msg()).  On success report(user,
 * ...) is called before the engine goes, and SW_EXIT_OK returned;
 * otherwise the exit code replay would give (reported), and report is not
 * called. */
int sw_cli_replay_log(const sw_cli_replay_t *r, const char *log, sw_cli_replay_report_fn report,
                      void *user);

#endif
