/* SPDX-License-Identifier: GPL-3.0-or-later */
/* manifest.h - the manifest of a batch: one log a line, with its own
 * options after it, written as on a command line:
 *
 *     # fleet 2024-05-20
 *     logs/truck-017.csv --scene crate.ini --scene pallet.ini
 *     "logs/truck 018.csv" --scene crate.ini --accel-unit g --time-unit ms
 *     logs/truck-019.lcmlog
 *
 * Words are separated by blanks; '...' keeps everything as it is, "..."
 * everything but \" and \\; a backslash outside quotes keeps the next
 * character; a word that begins with # begins a comment.  Paths are taken
 * as they are written, relative to the current folder, as on the command
 * line.  Nothing is expanded (no variables, no globs). */
#ifndef SWAYWATCH_CLI_MANIFEST_H
#define SWAYWATCH_CLI_MANIFEST_H

#include <stddef.h>

typedef struct {
    char *log;   /* the first word */
    char **args; /* the words after it (NULL-terminated), nargs of them */
    size_t nargs;
    long line; /* 1-based */
} sw_cli_manifest_line_t;

typedef struct {
    sw_cli_manifest_line_t *v; /* the lines that name a log, in order */
    size_t n;
    char **words; /* every word, owned */
    size_t nwords;
} sw_cli_manifest_t;

/* The whole of path ('-': standard input) into *text (free()), *len bytes.
 * SW_EXIT_OK, or SW_EXIT_IO (reported). */
int sw_cli_manifest_read(const char *path, char **text, size_t *len);

/* Split text (len bytes) of the manifest called name into lines.  Each
 * problem is reported as "swaywatch: NAME:LINE: why".  SW_EXIT_OK, or
 * SW_EXIT_USAGE (a quote not closed, a line that begins with an option, a
 * NUL byte) or SW_EXIT_IO (memory).  Free with sw_cli_manifest_free()
 * (zeroed ok). */
int sw_cli_manifest_parse(const char *name, const char *text, size_t len, sw_cli_manifest_t *m);
void sw_cli_manifest_free(sw_cli_manifest_t *m);

#endif
