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
 * number ("nan", "inf", "1.0x", hex, and decimal commas such as "0,001" in a
 * ';' file are refused), out of range ("1e400"), when time does not increase
 * (duplicates included), when the quoting is malformed, or when the line is
 * longer than SW_CSV_MAX_LINE bytes.  A gap in time is not an error.
 * Numbers are read with '.' as the decimal point whatever the locale.
 *
 * Counts always satisfy rows == accepted + rejected and
 * lines == rows + comments + blanks + headers. */
#ifndef SWAYWATCH_CSV_H
#define SWAYWATCH_CSV_H

#include <stddef.h>

#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SW_CSV_MAX_LINE (1 << 20) /* bytes; longer lines are rejected, not buffered */

typedef struct {
    char delim;            /* ',', ';', '\t', or 0 to detect */
    const char *time_col;  /* column name or 1-based index; NULL = "1" */
    const char *accel_col; /* NULL = "2" */
    const char *vert_col;  /* optional vertical acceleration column; NULL = none */
    double time_scale;     /* s per unit of the time column: 1, 1e-3, 1e-6; 0 = 1 */
    double accel_scale;    /* m/s^2 per unit (9.80665 for g); 0 = 1 */
    int flip;              /* non-zero: negate the longitudinal axis */
    int header;            /* -1 detect: the first non-comment, non-blank line is the header
                              when its time field (column 1 if time is named) is empty or not
                              numeric ("0,5" and "1e400" count as numeric: such a row is
                              reported, not skipped); 0 none; 1 that line is the header.  Named
                              columns match the trimmed header fields case-insensitively. */
} sw_csv_opts_t;

typedef struct {
    long lines;    /* physical lines seen */
    long rows;     /* data rows (not header, comment or blank) */
    long accepted; /* rows delivered */
    long rejected; /* rows refused; rows == accepted + rejected */
    long comments, blanks, headers;
} sw_csv_counts_t;

/* line is the 1-based physical line number. */
typedef int (*sw_csv_row_fn)(void *user, long line, double t, double a_g, double a_z);
typedef void (*sw_csv_reject_fn)(void *user, long line, const char *reason);

typedef struct sw_csv sw_csv_t;

/* NULL on failure (bad options: *err holds the code and msg says why; a
 * named column with header = 0 is SW_ENOTFOUND).  on_row and on_reject may
 * be NULL.  A non-zero return from on_row rejects that row: it is counted
 * and reported to on_reject with reason "refused by consumer". */
SW_API sw_csv_t *sw_csv_create(const sw_csv_opts_t *opts, sw_csv_row_fn on_row, sw_csv_reject_fn on_reject,
                        void *user, int *err, char *msg, size_t msglen);
SW_API void sw_csv_destroy(sw_csv_t *c);

/* Feed bytes; returns SW_OK or a negative code that ends the parse and is
 * returned again by every later call: SW_ENOTFOUND when a named column is
 * not in the header or the input has no header (that first data row is also
 * reported as rejected), SW_EINVAL when two roles resolve to the same header
 * field.  sw_csv_error_message() says which column and line.  Bad rows are
 * not errors: they are counted and reported. */
SW_API int sw_csv_feed(sw_csv_t *c, const char *buf, size_t len);

/* Flush the last line (with or without a final newline).  Feeding after
 * finish is an error (SW_EINVAL). */
SW_API int sw_csv_finish(sw_csv_t *c);

SW_API void sw_csv_counts(const sw_csv_t *c, sw_csv_counts_t *out);

/* Details of the error that ended the parse ("line 1: no column named
 * \"acc\" (accel) in the header"); "" when there was none. */
SW_API const char *sw_csv_error_message(const sw_csv_t *c);

#ifdef __cplusplus
}
#endif
#endif
