/* SPDX-License-Identifier: GPL-3.0-or-later */
/* record.h - the one writer of what the commands emit for programs: JSON
 * documents and records built as jansson values, CSV cells through
 * libcsv's writer, and CSV rows that are columns of a JSON record.
 *
 * JSON: a record is a jansson object filled member by member in the order
 * it is written (jansson keeps insertion order); numbers are written with
 * 9 significant digits (JSON_REAL_PRECISION(9): what %.9g wrote), a value
 * that is not finite as null (JSON has no NaN), and every string as valid
 * UTF-8 whatever bytes it held (text.h: each ill-formed subpart becomes
 * U+FFFD; jansson refuses invalid UTF-8).  The setters take an object (a
 * member named key) or an array (an item appended; key unused), and a
 * NULL container (its own creation failed): nothing is lost silently, as
 * every failure, memory running out included, marks the thread's record
 * as failed and sw_cli_rec_write() refuses it.
 *
 * CSV: a row of a batch is the projection of its JSON record: a column is
 * a name and where its value is in the record, so the two cannot
 * disagree. */
#ifndef SWAYWATCH_CLI_RECORD_H
#define SWAYWATCH_CLI_RECORD_H

#include <jansson.h>
#include <stddef.h>
#include <stdio.h>

/* A new empty object; the thread's record is no longer failed.  NULL when
 * memory ran out (then the record is). */
json_t *sw_cli_rec_new(void);

/* Members of an object o (key), or items of an array o (key NULL). */
json_t *sw_cli_rec_obj(json_t *o, const char *key);        /* a new object in o */
json_t *sw_cli_rec_arr(json_t *o, const char *key);        /* a new array in o */
void sw_cli_rec_num(json_t *o, const char *key, double v); /* null if not finite */
void sw_cli_rec_int(json_t *o, const char *key, long long v);
void sw_cli_rec_bool(json_t *o, const char *key, int v);
void sw_cli_rec_text(json_t *o, const char *key, const char *s); /* NULL: null */
void sw_cli_rec_null(json_t *o, const char *key);
/* v (a new reference, may be NULL: out of memory) into o. */
void sw_cli_rec_put(json_t *o, const char *key, json_t *v);

/* How a record is written: a document indented by two spaces per level
 * (--json), or one line (a JSON Lines record); both end with a newline. */
enum { SW_CLI_REC_DOC, SW_CLI_REC_LINE };

/* Write o on f and release it: 0, or -1 when memory ran out while it was
 * built or written (nothing of it written, or a part).  A write error is
 * left to the stream (its close reports it). */
int sw_cli_rec_write(FILE *f, json_t *o, int layout);
/* o as one line (no newline) in a string to free(), or NULL (failed);
 * o is released. */
char *sw_cli_rec_line(json_t *o);

/* CSV cells, each after a comma (the first of a line is the caller's). */
/* s as a CSV text cell (RFC 4180), no comma: quoted only when it has to
 * be.  A cell that begins with '=', '+', '-', '@', a tab or a carriage
 * return gets a leading "'", so that no spreadsheet reads it as a formula
 * (OWASP, "CSV injection").  For text only: numbers are written as
 * numbers. */
void sw_cli_csv_text(FILE *f, const char *s);
void sw_cli_csv_num(FILE *f, double v); /* ",%.9g", or "," when not finite */

/* A CSV column of a JSON record: its name and the member it shows
 * ("input.duration": members of members; NULL: the member name).  An
 * absent member or null is an empty cell, or missing; a number as
 * printed in JSON (%.9g), an integer as it is, true and false as 1 and 0,
 * text as a text cell, an array as its items joined by "; ". */
typedef struct {
    const char *name;
    const char *path;
    const char *missing; /* the cell of an absent member (NULL: empty) */
} sw_cli_column_t;

/* The names joined by commas, after a comma (no newline). */
void sw_cli_csv_header(FILE *f, const sw_cli_column_t *c, size_t n);
/* The cells of record rec, each after a comma (no newline). */
void sw_cli_csv_row(FILE *f, const json_t *rec, const sw_cli_column_t *c, size_t n);

#endif
