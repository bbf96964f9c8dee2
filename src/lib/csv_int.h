/* csv_int.h - what the CSV reader's files share (csv.h is the API): the
 * number and date-time readers (csv_num.c) and the reading of a header's
 * names into columns and units (csv_infer.c). */
#ifndef SWAYWATCH_CSV_INT_H
#define SWAYWATCH_CSV_INT_H

#include <locale.h>
#include <stddef.h>

#include "swaywatch/csv.h"

/* ---- csv_num.c ------------------------------------------------------------- */

enum { SW_NUM_OK, SW_NUM_EMPTY, SW_NUM_BAD, SW_NUM_COMMA, SW_NUM_RANGE };

/* A plain decimal number in s[0..n) (blanks around it allowed; s[n] is
 * NUL): SW_NUM_OK with *out, or why not.  decimal_comma: ',' is the decimal
 * mark (a field holding both ',' and '.' is refused: a thousands separator
 * cannot be told from a decimal mark); otherwise a ',' gives SW_NUM_COMMA.
 * Read in the "C" locale cloc whatever the program's locale is. */
int sw_csv_number(locale_t cloc, const char *s, size_t n, int decimal_comma, double *out);

/* An ISO-8601 date-time ("2024-05-20T12:00:00.000Z", "2018-04-08
 * 10:31:37.005628", "2024-05-20T14:00:00+02:00"; without a zone it is read
 * as UTC) in s[0..n): 1 with *out in seconds since 1970-01-01 UTC, else 0. */
int sw_csv_datetime(const char *s, size_t n, double *out);

/* ---- csv_infer.c ------------------------------------------------------------ */

enum { SW_CSV_ROLE_TIME, SW_CSV_ROLE_ACCEL, SW_CSV_ROLE_VERT, SW_CSV_NROLES };

/* What a header says: per role, the column it names (-1 none), the unit
 * (SW_CSV_UNIT_*, or SW_CSV_UNIT_NONE) and its scale (s or m/s^2 per unit). */
typedef struct {
    long col[SW_CSV_NROLES];
    int unit[SW_CSV_NROLES];
    char why[256]; /* when a role cannot be told: the reason, naming the candidates */
} sw_csv_guess_t;

/* The unit a header name carries ("Time (ms)", "accel_g", "X [m/s²]"),
 * SW_CSV_UNIT_NONE if none; time units for the time role, acceleration
 * units otherwise. */
int sw_csv_name_unit(const char *name, int time_role);

/* Which of the n header fields are time and longitudinal acceleration.
 * want[r]: look for role r.  Returns 0, or -1 with g->why set when a
 * wanted role has no candidate or several equally good ones. */
int sw_csv_guess(const char names[][SW_CSV_NAME_MAX], long n, const int want[SW_CSV_NROLES],
                 sw_csv_guess_t *g);

/* m/s^2 or s per unit. */
double sw_csv_unit_scale(int unit);

#endif
