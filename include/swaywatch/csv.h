/* csv.h - streaming CSV ingestion of acceleration logs (built on libcsv).
 *
 * Push-style like libcsv itself: feed any number of byte chunks, then
 * finish.  Each usable row is delivered as (t, a_g, a_z) in SI units; each
 * row that cannot be used is delivered with its physical line number and the
 * reason, and counted.  The library does no I/O: the caller reads the file.
 *
 * Format (DESIGN.md): first column time, second longitudinal acceleration;
 * optional header row; '#' comment lines; ',' ';' or tab delimited (detected
 * from the first non-comment line unless given).  A UTF-8 BOM and CRLF line
 * ends are accepted.  Rows are rejected when a field is missing, not a
 * number, not finite, or when time does not increase. */
#ifndef SWAYWATCH_CSV_H
#define SWAYWATCH_CSV_H

#include <stddef.h>

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
    int header;            /* -1 detect (first row with a non-numeric time), 0 none, 1 yes */
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

/* NULL on failure (bad options: msg says why).  A non-zero return from
 * on_row rejects that row with reason "refused by consumer" unless the
 * consumer already reported it. */
sw_csv_t *sw_csv_create(const sw_csv_opts_t *opts, sw_csv_row_fn on_row, sw_csv_reject_fn on_reject,
                        void *user, int *err, char *msg, size_t msglen);
void sw_csv_destroy(sw_csv_t *c);

/* Feed bytes; returns SW_OK or a negative code (SW_ENOTFOUND: a named
 * column is not in the header, which ends the parse). */
int sw_csv_feed(sw_csv_t *c, const char *buf, size_t len);

/* Flush the last line (with or without a final newline). */
int sw_csv_finish(sw_csv_t *c);

void sw_csv_counts(const sw_csv_t *c, sw_csv_counts_t *out);

#ifdef __cplusplus
}
#endif
#endif
