/* SPDX-License-Identifier: GPL-3.0-or-later */
/* csv_int.h - the stages of the CSV reader (csv.h is the API), each a
 * function of its arguments that returns its result: a line split into
 * fields (csv_split.c), numbers and date-times (csv_num.c), a header's
 * names read into columns and units (csv_infer.c).  csv.c alone holds the
 * reader's state and calls them. */
#ifndef SWAYWATCH_CSV_INT_H
#define SWAYWATCH_CSV_INT_H

#include <locale.h>
#include <stddef.h>

#include <csv.h>

#include "swaywatch/csv.h"

/* ---- what the stages share -------------------------------------------------------- */

/* Field slots filled while splitting a line.  PROBE is the field looked at to
 * decide whether the first line is a header. */
enum { R_TIME, R_ACCEL, R_VERT, R_LAT, R_PROBE, N_SLOTS };
#define N_ROLES 4 /* time, accel, vertical, lateral: the columns chosen by the caller */

static const char *const role_name[N_ROLES] = {"time", "accel", "vertical", "lateral"};

/* The line buffer holds SW_CSV_MAX_LINE bytes of content plus a '\r' (CRLF
 * ends are stripped only once the line is complete) plus a NUL. */
#define LINE_CAP ((size_t)SW_CSV_MAX_LINE + 1)
/* Copies of the wanted fields on the libcsv path: at most the line itself
 * plus one NUL per slot. */
#define SCRATCH_CAP ((size_t)SW_CSV_MAX_LINE + 2 + N_SLOTS)
#define EXCERPT_MAX 40                           /* bytes of offending text quoted in a reason */
#define MAX_COLUMN_INDEX ((long)SW_CSV_MAX_LINE) /* a line cannot hold more fields */

#define LIBCSV_OPTS (CSV_STRICT | CSV_STRICT_FINI | CSV_APPEND_NULL)

/* ---- csv_split.c: a line into fields --------------------------------------------- */

int sw_csv_is_blank(char ch);
/* Case-insensitive ASCII comparison of a header field with a column name,
 * both trimmed of spaces and tabs. */
int sw_csv_name_equal(const char *a, size_t an, const char *b);
/* s[0..n) quoted for a message, at most EXCERPT_MAX bytes, non-ASCII as '?'. */
void sw_csv_excerpt(char *dst, size_t cap, const char *s, size_t n);

/* What to take from a line. */
typedef struct {
    char delim;         /* ',', ';' or tab */
    long want[N_SLOTS]; /* 0-based column per slot, -1 none */
    /* names to look up among the fields (the columns named by the caller;
       NULL entries: none), or NULL: no look-up */
    const char *const *names;
    /* where to keep the first SW_CSV_MAX_FIELDS fields, trimmed and cut to
       SW_CSV_NAME_MAX - 1 bytes (a header), or NULL */
    char (*capture)[SW_CSV_NAME_MAX];
} sw_csv_split_opts_t;

/* What a line held. */
typedef struct {
    const char *fs[N_SLOTS]; /* NUL-terminated field text per slot, NULL = absent */
    size_t fl[N_SLOTS];      /* their lengths (only where fs is set) */
    long nf;                 /* fields seen (all of them unless the line was cut short
                                after the last wanted one, with neither names nor capture) */
    long match[N_ROLES];     /* field of each name looked up, -1 not found (set only with
                                names to look up) */
    long ncap;               /* fields captured */
    char reason[256];        /* why the line could not be split */
} sw_csv_fields_t;

/* libcsv's parser and the copies of quoted fields: the state splitting
 * needs, allocated once. */
typedef struct {
    struct csv_parser lp;
    char *scratch;
    size_t scratch_used;
    int ready;
    long maxwant;                 /* during a split */
    const sw_csv_split_opts_t *o; /* during a split */
    sw_csv_fields_t *f;           /* during a split */
} sw_csv_splitter_t;

enum { SW_CSV_SPLIT_OK = 0, SW_CSV_SPLIT_BAD = -1 };

/* 0 or -1 (out of memory). */
int sw_csv_splitter_init(sw_csv_splitter_t *sp);
void sw_csv_splitter_free(sw_csv_splitter_t *sp); /* zeroed or initialised */
/* Split s[0..n) (s[n] writable; field ends are overwritten with NULs) as o
 * says into f: SW_CSV_SPLIT_OK, or SW_CSV_SPLIT_BAD with f->reason when
 * its quoting is malformed (f holds the fields before the fault). */
int sw_csv_split(sw_csv_splitter_t *sp, char *s, size_t n, const sw_csv_split_opts_t *o,
                 sw_csv_fields_t *f);

/* ---- csv_num.c ------------------------------------------------------------- */

enum { SW_NUM_OK, SW_NUM_EMPTY, SW_NUM_BAD, SW_NUM_COMMA, SW_NUM_RANGE };

/* A plain decimal number in s[0..n) (blanks around it allowed; s[n] is
 * NUL): SW_NUM_OK with *out, or why not.  decimal_comma: ',' is the decimal
 * mark (a field holding both ',' and '.' is refused: a thousands separator
 * cannot be told from a decimal mark); otherwise a ',' gives SW_NUM_COMMA.
 * Read in the "C" locale cloc whatever the program's locale is. */
int sw_csv_number(locale_t cloc, const char *s, size_t n, int decimal_comma, double *out);

/* ---- csv_time.c: date-times, epochs ------------------------------------------------ */

/* A date-time's fields as written. */
typedef struct {
    int dm;   /* 0: year first ("2024-05-20", "2016/05/14"); 1: day and month
                 first, in an order the text does not say ("14/05/2016") */
    long y;   /* year */
    int a, b; /* year first: month, day; dm: the first and second numbers */
    int h, mi, sec;
    double frac; /* s */
    long offset; /* s east of UTC */
} sw_csv_dt_t;

/* s[0..n) read as a date-time of a form csv_time.c lists: 1, else 0 (the
 * date may still be impossible). */
int sw_csv_dt_read(const char *s, size_t n, sw_csv_dt_t *dt);
/* Its time in s since 1970-01-01 UTC, with order (SW_CSV_DATE_DMY or
 * SW_CSV_DATE_MDY) for the day-and-month form: 1, 0 for an impossible date,
 * -1 for that form without an order. */
int sw_csv_dt_seconds(const sw_csv_dt_t *dt, int order, double *out);
/* Both at once: 1 with *out, 0 not a date-time (or an impossible one), -1
 * day and month first without an order. */
int sw_csv_datetime(const char *s, size_t n, int order, double *out);
/* A date-time in some order. */
int sw_csv_is_datetime(const char *s, size_t n);
/* The unit in which v is a time since 1970 between 2000 and 2100
 * (SW_CSV_UNIT_S, _MS, _US, _NS), or SW_CSV_UNIT_NONE. */
int sw_csv_epoch_unit(double v);

/* ---- csv_profile.c: a column as the look-ahead's rows show it ------------------------ */

typedef struct {
    long n;               /* fields holding something */
    long nnum, niso, ndm; /* numbers, year-first date-times, day-and-month date-times */
    long a13, b13;        /* day-and-month: the first / second number above 12 (the day) */
    double first;         /* the first number */
    long steps, zero;     /* steps between consecutive values of one kind, of which zero */
    double minstep;       /* the smallest positive step (the column's unit; s for date-times) */
    double prev;          /* the previous value, */
    int kind_prev;        /* ... and its kind */
} sw_csv_profile_t;

/* One field of a row in the column (zeroed profile to start). */
void sw_csv_profile_add(sw_csv_profile_t *p, const char *s, size_t n, char delim, locale_t cloc);

/* ---- csv_preamble.c: where the table starts ------------------------------------- */

/* A data-like line of the look-ahead (not blank, not a comment); s NULL
 * for a line too long to hold. */
typedef struct {
    const char *s;
    size_t n;
} sw_csv_line_t;

typedef struct {
    char delim;    /* given, or 0 */
    int header;    /* the options' header: -1 detect, 0 none, 1 present */
    locale_t cloc; /* "C" numeric locale */
} sw_csv_preamble_opts_t;

/* A delimiter among tab, ';', ',' outside quotes (in that order), or 0. */
char sw_csv_detect_delim(const char *s, size_t n);
/* How many of the n data-like lines come before the table (its header, or
 * its first row without one): 0 unless the lines show it without doubt. */
long sw_csv_preamble_find(const sw_csv_line_t *lines, long n, const sw_csv_preamble_opts_t *o);

/* ---- csv_unit.c: names into words and units ---------------------------------- */

#define SW_CSV_MAX_WORDS 8
#define SW_CSV_WORD_MAX 24

/* What a unit measures. */
enum {
    SW_CSV_UC_NONE = 0, /* no unit written */
    SW_CSV_UC_TIME,     /* s, ms, us, ns */
    SW_CSV_UC_ACCEL,    /* g, mg, m/s^2 (or a range in one: "100g") */
    SW_CSV_UC_OTHER,    /* a known unit of another quantity: deg, m, km/h, rpm, %, uT, ... */
    SW_CSV_UC_UNKNOWN   /* written, but none of these ("raw", "txt", "WGS84") */
};

/* A header name as words and a unit. */
typedef struct {
    char w[SW_CSV_MAX_WORDS][SW_CSV_WORD_MAX]; /* lowercase words, the unit left out */
    int nw;
    char unit[SW_CSV_WORD_MAX * 2]; /* the unit's text, spaces removed, lowercase */
    int uclass;                     /* SW_CSV_UC_* */
    int unit_id;                    /* SW_CSV_UNIT_* of a time or acceleration unit, else NONE */
} sw_csv_words_t;

char sw_csv_lower(char c); /* ASCII */
/* Split a header name into words and its unit (csv_unit.c says where a
 * unit is written). */
void sw_csv_words(const char *name, sw_csv_words_t *w);
/* The unit of time that the name of a time column writes and that no
 * option reads (minutes, hours, days), into dst; NULL if none. */
const char *sw_csv_time_unit_unread(const char *name, char *dst, size_t cap);
/* w is one of the NULL-terminated set. */
int sw_csv_word_in(const char *w, const char *const *set);
/* The class (SW_CSV_UC_*) of a unit's text, with its SW_CSV_UNIT_* in
 * *unit (may be NULL). */
int sw_csv_unit_class(const char *text, int *unit);
/* The unit a header name carries ("Time (ms)", "accel_g", "X [m/s²]"),
 * SW_CSV_UNIT_NONE if none; time units for the time role, acceleration
 * units otherwise. */
int sw_csv_name_unit(const char *name, int time_role);

/* ---- csv_infer.c ------------------------------------------------------------ */

enum { SW_CSV_ROLE_TIME, SW_CSV_ROLE_ACCEL, SW_CSV_ROLE_VERT, SW_CSV_NROLES };

/* What a header says: per role, the column it names (-1 none), the unit
 * (SW_CSV_UNIT_*, or SW_CSV_UNIT_NONE) and its scale (s or m/s^2 per unit). */
typedef struct {
    long col[SW_CSV_NROLES];
    int unit[SW_CSV_NROLES];
    char why[256]; /* when a role cannot be told: the reason, naming the candidates */
} sw_csv_guess_t;

/* Which of the n header fields are time and longitudinal acceleration.
 * want[r]: look for role r; skip: a column taken already (the vertical
 * one), or -1; prof: the first nprof columns as the look-ahead's rows show
 * them (may be NULL), so that of several time columns the finer is chosen.
 * Returns 0, or -1 with g->why set when a wanted role has no candidate or
 * several equally good ones. */
int sw_csv_guess(const char names[][SW_CSV_NAME_MAX], long n, const int want[SW_CSV_NROLES],
                 long skip, const sw_csv_profile_t *prof, long nprof, sw_csv_guess_t *g);

/* The lateral acceleration among the n header fields, other than the
 * columns taken (ntaken of them, -1 entries ignored): a name that says
 * acceleration along y ("Lateral Gs", "Y (g)", "accelerometerAccelerationY")
 * beats a bare y axis ("ay", "Y").  0 with *col (-1: none), or -1 with why
 * set when several fit equally. */
int sw_csv_guess_lat(const char names[][SW_CSV_NAME_MAX], long n, const long *taken, int ntaken,
                     long *col, char *why, size_t whylen);

/* The columns the caller gave (sw_csv_opts_t's time_col, accel_col,
 * vert_col, lat_col): a 0-based index, or a name (trimmed; it points into the
 * option's text and is not NUL-terminated). */
typedef struct {
    long col[N_ROLES];         /* -1: named, or the vertical or lateral column not given */
    const char *name[N_ROLES]; /* NULL: by index */
    size_t len[N_ROLES];
    int given[N_ROLES]; /* the caller named or numbered it (else time is 1, accel 2) */
} sw_csv_colspec_t;

/* Parse and check the options' columns: SW_OK, or the code with the reason
 * in t (two the same, a bad index, a name with header = 0). */
int sw_csv_colspec_parse(const sw_csv_opts_t *o, sw_csv_colspec_t *cs, char *t, size_t tlen);

/* What the reader knows once the table's first line is read: what the
 * caller gave, and the header's fields if it has one. */
typedef struct {
    long col[N_ROLES];       /* columns given by index, -1: named or none */
    const char *const *name; /* names given (NUL-terminated), NULL entries: by index */
    const long *match;       /* the header field holding each name, -1 not found */
    int col_given[N_ROLES];  /* the caller named or numbered the column */
    double scale[2];         /* s per unit of time, m/s^2 per unit of acceleration */
    int scale_given[2];      /* ... given by the caller (else 1, the default) */
    int infer;               /* read the columns and units nobody gave from the names */
    int lateral;             /* read a lateral column: the one given, or the header's; 0:
                                one the header names is only said (lat_unread) */
    int has_header;
    const char (*names)[SW_CSV_NAME_MAX]; /* the header's fields, trimmed */
    long nnames;
    char delim;
    int decimal_comma;            /* -1 not decided yet, 0, 1 */
    int tkind;                    /* time column: 0 not seen yet, 1 numbers, 2 date-times */
    int date_order;               /* the options': SW_CSV_DATE_* */
    const sw_csv_profile_t *prof; /* the columns as the look-ahead's rows show them */
    long nprof;
} sw_csv_infer_in_t;

/* The layout (csv.h) the header and the options give: SW_OK, or
 * SW_ENOTFOUND (a named column is not in the header), SW_EAMBIGUOUS (infer
 * cannot tell the columns from the names), SW_EINVAL (two roles on one
 * column), with the reason in msg. */
int sw_csv_infer(const sw_csv_infer_in_t *in, sw_csv_layout_t *L, char *msg, size_t msglen);

#endif
