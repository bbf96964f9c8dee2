/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv.h - streaming CSV ingestion of acceleration logs (built on libcsv).
 *
 * Push-style like libcsv itself: feed any number of byte chunks, then
 * finish.  Each usable row is delivered as (t, a_g, a_z) in SI units; each
 * row that cannot be used is delivered with its physical line number and the
 * reason, and counted.  The library does no I/O: the caller reads the file.
 *
 * Format (DESIGN.md): first column time, second longitudinal acceleration;
 * optional header row; '#' comment lines (leading blanks allowed) and blank
 * lines are skipped and counted; ',' ';' or tab delimited (detected from the
 * first non-comment, non-blank line: tab, else ';', else ',').  A UTF-8 BOM
 * and CRLF line ends are accepted.  Fields may be quoted ("1.5"), but one
 * physical line is one record: a quote cannot span lines.
 *
 * Rows are rejected when a field is missing, empty, not a plain decimal
 * number ("nan", "inf", "1.0x", hex, and decimal commas such as "0,001"
 * unless the decimal comma is on), out of range ("1e400"), when time does
 * not increase (duplicates included; unless any_order), when the quoting is malformed, or
 * when the line is longer than SW_CSV_MAX_LINE bytes.  A gap in time is not
 * an error.  Numbers are read with '.' as the decimal point whatever the
 * locale (',' with decimal_comma).  The time column may hold ISO-8601
 * date-times instead of numbers ("2024-05-20T12:00:00.000Z", "2018-04-08
 * 10:31:37.005628"; no zone: UTC), delivered as seconds since 1970 UTC; all
 * its rows then must.
 *
 * With infer, a header's names choose the columns and units nobody gave
 * ("Time (ms)", "X (g)", "time_ms;accel_g"): sw_csv_layout() says what was
 * chosen and from where; when the names do not say it without doubt the
 * parse ends with SW_EAMBIGUOUS, because a wrong guess gives a confident
 * wrong answer.
 *
 * Lines before the table that are not part of it (a logger's title,
 * instrument, serial number, trigger, units...) are its preamble: found in
 * the look-ahead when the lines show it without doubt (the first row is the
 * first line of two or more numbers whose field count the lines under it
 * keep; the header is the line above it when that holds names), or the
 * first skip_lines lines; skipped and counted.
 *
 * Counts always satisfy rows == accepted + rejected and
 * lines == rows + comments + blanks + headers + preamble. */
#ifndef SWAYWATCH_CSV_H
#define SWAYWATCH_CSV_H

#include <stddef.h>

#include "export.h"
#include "units.h"

#ifdef __cplusplus
extern "C" {
#endif

/* SW_CSV_MAX_LINE and SW_CSV_AHEAD_BYTES may be lowered with -D for a
 * whole build: the fuzz build does, so that its inputs reach them
 * (CMakeLists.txt, SW_FUZZ). */
#ifndef SW_CSV_MAX_LINE
#define SW_CSV_MAX_LINE (1 << 20) /* bytes; longer lines are rejected, not buffered */
#endif
#define SW_CSV_NAME_MAX 64   /* bytes kept of a header field's name */
#define SW_CSV_MAX_FIELDS 64 /* header fields kept (inference, messages) */
/* The look-ahead: the first lines of a log are held until its layout is
 * fixed (the preamble, the columns and the time format are decided on
 * them), at most this many data-like lines, lines, or bytes of text. */
#define SW_CSV_AHEAD_ROWS 256
#define SW_CSV_AHEAD_LINES 1024
#ifndef SW_CSV_AHEAD_BYTES
#define SW_CSV_AHEAD_BYTES (256 * 1024)
#endif

/* Units of the time and acceleration columns. */
enum {
    SW_CSV_UNIT_NONE = 0, /* not known (a name without a unit; a custom scale) */
    SW_CSV_UNIT_S,
    SW_CSV_UNIT_MS,
    SW_CSV_UNIT_US,
    SW_CSV_UNIT_DATETIME, /* ISO-8601 date-times, in s since 1970 UTC */
    SW_CSV_UNIT_MPS2,
    SW_CSV_UNIT_G,
    SW_CSV_UNIT_NS, /* time in nanoseconds */
    SW_CSV_UNIT_MG  /* acceleration in thousandths of g */
};

/* The order of day and month in date-times that write them before the
 * year ("14/05/2016", "05/14/2016"). */
enum { SW_CSV_DATE_AUTO = 0, SW_CSV_DATE_DMY, SW_CSV_DATE_MDY };

/* Where a column or a unit came from. */
enum {
    SW_CSV_FROM_DEFAULT = 0,
    SW_CSV_FROM_OPTION,
    SW_CSV_FROM_HEADER,
    SW_CSV_FROM_VALUES /* the lines or values of the look-ahead showed it */
};

typedef struct {
    char delim;            /* ',', ';', '\t', or 0 to detect */
    const char *time_col;  /* column name or 1-based index; NULL = "1" */
    const char *accel_col; /* NULL = "2" */
    const char *vert_col;  /* optional vertical acceleration column; NULL = none */
    double time_scale;     /* s per unit of the time column: 1, 1e-3, 1e-6; 0 = 1 */
    double accel_scale;    /* m/s^2 per unit (SW_G0 for g); 0 = 1 */
    int flip;              /* non-zero: negate the longitudinal axis */
    int header;            /* -1 detect: the first non-comment, non-blank line is the header
                              when its time field (column 1 if time is named) is empty or not
                              numeric ("0,5" and "1e400" count as numeric: such a row is
                              reported, not skipped); 0 none (the first line is a row: no
                              preamble is looked for); 1 that line is the header.  Named
                              columns match the trimmed header fields case-insensitively. */
    int infer;             /* non-zero: the columns and units not given above are read from
                              the header's names (see the top of this file); without a
                              header the defaults apply (column 1 in s, column 2 in m/s^2) */
    int decimal_comma;     /* 1: ',' is the decimal mark; -1: detect it in a ';' or tab
                              delimited file from the first number holding ',' or '.'; 0: a
                              ',' in a number is refused */
    int any_order;         /* non-zero: rows go to on_row in any time order, duplicates
                              included, for a consumer that judges time itself (the input
                              gate, gate.h: a lone row whose time is off is that row's fault,
                              not the fault of the rows after it); 0: a time not after the
                              previous row's is refused here */
    long skip_lines;       /* 0: find a preamble (lines before the table that are not part
                              of it: titles, "key: value" and "key,value" lines; see the top
                              of this file); N > 0: the first N physical lines are the
                              preamble, whatever they hold; < 0: there is none */
    int date_order;        /* SW_CSV_DATE_AUTO: day and month before the year are told apart
                              by the look-ahead's rows (a number above 12 is the day), and
                              refused (SW_EAMBIGUOUS) when they cannot be; SW_CSV_DATE_DMY,
                              SW_CSV_DATE_MDY: as given */
    /* added with the lateral plane */
    int lateral;         /* non-zero: read a lateral acceleration (sw_csv_lateral() in
                            on_row): lat_col, else with infer the header's lateral column
                            ("Lateral Gs", "Y (g)", "ay"; several: SW_EAMBIGUOUS), else none
                            (layout col[3] = -1); 0: none is read, and lat_col must be NULL
                            (one the header names is said in the layout's lat_unread) */
    const char *lat_col; /* lateral acceleration column, name or 1-based index; NULL: as
                            lateral says.  In the unit of accel_scale where given, else its
                            header's, else the longitudinal column's */
    int flip_lat;        /* non-zero: negate the lateral axis */
} sw_csv_opts_t;

/* The layout in use, once the header (or the first data row) has fixed it.
 * Roles: 0 time, 1 longitudinal acceleration, 2 vertical acceleration, 3
 * lateral acceleration. */
typedef struct {
    int ready;  /* 0 until the layout is fixed */
    char delim; /* 0 while not detected */
    int has_header;
    int decimal_comma;             /* -1 not decided yet, 0, 1 */
    long col[4];                   /* 0-based; -1: the role is not read */
    char name[4][SW_CSV_NAME_MAX]; /* the header's name of the column ("" without one) */
    int unit[4];                   /* SW_CSV_UNIT_* in use */
    double scale[4];               /* s or m/s^2 per unit of the column */
    int col_from[4], unit_from[4]; /* SW_CSV_FROM_* */
    int header_unit[4];            /* the unit the column's name says (NONE: none); when it
                                      differs from unit, the option given overrode it */
    long preamble;                 /* lines skipped before the table */
    long first_line;               /* the table's first line (its header, or its first row) */
    int date_order;                /* date-times with day and month first: SW_CSV_DATE_DMY or
                                      SW_CSV_DATE_MDY (unit_from[0] says whence); else AUTO */
    int epoch;                     /* the time column's values are a time since 1970 */
    int preamble_from;             /* SW_CSV_FROM_OPTION (skip_lines), SW_CSV_FROM_VALUES
                                      (found), SW_CSV_FROM_DEFAULT (none) */
    long lat_unread;               /* without opts.lateral: the header's lateral column (its
                                      name in name[3]), which is not read; -1: none */
} sw_csv_layout_t;

typedef struct {
    long lines;    /* physical lines seen */
    long rows;     /* data rows (not header, comment or blank) */
    long accepted; /* rows delivered */
    long rejected; /* rows refused; rows == accepted + rejected */
    long comments, blanks, headers;
    long preamble; /* lines before the table (sw_csv_opts_t.skip_lines) */
} sw_csv_counts_t;

/* line is the 1-based physical line number. */
typedef int (*sw_csv_row_fn)(void *user, long line, double t, double a_g, double a_z);
typedef void (*sw_csv_reject_fn)(void *user, long line, const char *reason);

typedef struct sw_csv sw_csv_t;

/* NULL on failure (bad options: *err holds the code and msg says why; a
 * named column with header = 0 is SW_ENOTFOUND).  on_row and on_reject may
 * be NULL.  A non-zero return from on_row rejects that row: it is counted
 * and reported to on_reject with reason "refused by consumer". */
SW_API sw_csv_t *sw_csv_create(const sw_csv_opts_t *opts, sw_csv_row_fn on_row,
                               sw_csv_reject_fn on_reject, void *user, int *err, char *msg,
                               size_t msglen);
SW_API void sw_csv_destroy(sw_csv_t *c);

/* Inside on_row: the row's lateral acceleration (m/s^2, after its unit and
 * flip_lat), read when the layout has a lateral column (col[3] >= 0);
 * NAN when it has none. */
SW_API double sw_csv_lateral(const sw_csv_t *c);

/* Feed bytes; returns SW_OK or a negative code that ends the parse and is
 * returned again by every later call: SW_ENOTFOUND when a named column is
 * not in the header or the input has no header (that first data row is also
 * reported as rejected), SW_EINVAL when two roles resolve to the same header
 * field, SW_EAMBIGUOUS when infer cannot tell the columns from the header.
 * sw_csv_error_message() says which column and line.  Bad rows are not
 * errors: they are counted and reported.
 *
 * The first lines are held (the look-ahead, SW_CSV_AHEAD_*) until the
 * layout is fixed on them; then they are read in order, counted and
 * delivered with their own line numbers, and every later line as it comes.
 * So rows, and an error of the header, come from the feed that fills the
 * look-ahead, or from sw_csv_finish() for a shorter input. */
SW_API int sw_csv_feed(sw_csv_t *c, const char *buf, size_t len);

/* Flush the last line (with or without a final newline) and the
 * look-ahead; returns SW_OK or the code that ended the parse.  Feeding
 * after finish is an error (SW_EINVAL). */
SW_API int sw_csv_finish(sw_csv_t *c);

SW_API void sw_csv_counts(const sw_csv_t *c, sw_csv_counts_t *out);

/* The layout in use: SW_OK once it is fixed (out->ready), SW_EINVAL for
 * NULL arguments; before that out->ready is 0. */
SW_API int sw_csv_layout(const sw_csv_t *c, sw_csv_layout_t *out);

/* The header's fields, as read (trimmed, at most SW_CSV_NAME_MAX - 1
 * bytes, the first SW_CSV_MAX_FIELDS): for messages that list them.  NULL
 * past the last or without a header. */
SW_API long sw_csv_header_count(const sw_csv_t *c);
SW_API const char *sw_csv_header_field(const sw_csv_t *c, long i);

/* A unit as written ("s", "ms", "us", "µs", "ns", "nanos"; "g", "G", "Gs",
 * "mg", "m/s2", "m/s^2", "m/s²", "mps2", ...; spaces and case ignored):
 * SW_CSV_UNIT_*, or SW_CSV_UNIT_NONE if it is none of the time units
 * (time_role) or the acceleration units.  The same reading a header's
 * names get. */
SW_API int sw_csv_unit_parse(const char *text, int time_role);

/* s or m/s^2 per unit: 1e-3 for ms, 1e-9 for ns, SW_G0 for g; 1 for the
 * SI units, date-times and SW_CSV_UNIT_NONE. */
SW_API double sw_csv_unit_scale(int unit);

/* "s", "ms", "us", "ns", "date-time", "m/s^2", "g", "mg", or "" for
 * SW_CSV_UNIT_NONE. */
SW_API const char *sw_csv_unit_name(int unit);

/* Details of the error that ended the parse ("line 1: no column named
 * \"acc\" (accel) in the header"); "" when there was none. */
SW_API const char *sw_csv_error_message(const sw_csv_t *c);

#ifdef __cplusplus
}
#endif
#endif
