/* SPDX-License-Identifier: GPL-3.0-or-later */
/* input.c - CSV input options, log files read in chunks (the pump that
 * feeds the CSV reader; the first chunk tells the source), and reading a
 * whole CSV log into memory, for the commands that run one log many times
 * (forensics: one replay per trial of the safety-factor search).  replay
 * itself streams the log and never holds it.
 *
 * Memory: 16 bytes per accepted row (24 with a vertical column); a 1 kHz
 * log of one hour is about 58 MB. */
#include "input.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CHUNK (64 * 1024) /* bytes read and fed at a time */

void sw_cli_csv_opts_init(sw_cli_csv_opts_t *o)
{
    memset(o, 0, sizeof *o);
    o->csv.header = -1;
    o->csv.infer = 1;          /* columns and units nobody gave: from the header */
    o->csv.decimal_comma = -1; /* detected in ';' and tab files */
}

/* ---- the input gate ------------------------------------------------------------- */

void sw_cli_gate_init(sw_cli_gate_t *g)
{
    memset(g, 0, sizeof *g);
    g->vert_gravity = -1;
}

void sw_cli_gate_opts(const sw_cli_gate_t *g, sw_gate_opts_t *o)
{
    memset(o, 0, sizeof *o);
    o->gap = g->gap;
    o->gap_policy = g->gap_policy ? SW_GAP_RESTART : SW_GAP_BRIDGE;
    o->max_bridge = g->max_bridge;
    o->max_accel = g->max_accel;
    o->jump = g->max_jump == 0.0 ? -1.0 : g->max_jump < 0.0 ? 0.0 : g->max_jump;
    o->confirm = (int)g->confirm;
    o->vert_gravity = g->vert_gravity == 1;
}

void sw_cli_gate_limits(const sw_cli_gate_t *g, sw_gate_limits_t *lim)
{
    memset(lim, 0, sizeof *lim);
    /* 0 %: any rejected sample refuses the verdict */
    lim->max_rejected = g->max_rejected > 0.0 ? g->max_rejected / 100.0 : 1e-300;
}

/* "--max-accel 30g" or "--max-accel 294.2" (m/s^2); at most the engine's
 * limit, beyond which it refuses every sample itself. */
int sw_cli_accel_limit(const sw_cli_option_t *o, const char *arg, void *dest)
{
    double *out = dest;
    const char *given = arg;
    char buf[64];
    size_t len = strlen(arg);
    double scale = 1.0;
    if (len > 0 && len < sizeof buf && (arg[len - 1] == 'g' || arg[len - 1] == 'G')) {
        memcpy(buf, arg, len - 1);
        buf[len - 1] = '\0';
        arg = buf;
        scale = SW_G0;
    }
    /* the bounds (m/s^2) apply once the value is in m/s^2 */
    sw_cli_option_t unbounded = *o;
    unbounded.lo = unbounded.hi = 0.0;
    if (sw_cli_opt_double(&unbounded, arg, out) != SW_EXIT_OK)
        return SW_EXIT_USAGE;
    *out *= scale;
    return sw_cli_opt_range(o, given, *out);
}

static int parse_policy(const sw_cli_option_t *o, const char *arg, void *dest)
{
    int *out = dest;
    if (!strcmp(arg, "bridge"))
        *out = 0;
    else if (!strcmp(arg, "restart"))
        *out = 1;
    else {
        sw_cli_error("--%s: expected bridge or restart, got '%s'", o->long_name, arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

#define GATE(f) SW_CLI_AT(sw_cli_gate_t, f)

const sw_cli_option_t sw_cli_gate_options[] = {
    {SW_CLI_SECTION, .help = "Input checks (every source: CSV, lcm-logger, live):"},
    {SW_CLI_CALL, 0, "max-accel", "A", GATE(max_accel), .fn = sw_cli_accel_limit,
     .rule = SW_NUM_POSITIVE, .lo = 0.1, .hi = SW_MAX_ACCEL,
     .what = "a positive acceleration in m/s^2, or in g with a g suffix",
     .help = "refuse samples with any axis beyond A (a spike), in m/s^2 or with a g suffix, "
             "e.g. 30g (default 50g); at most the engine's own limit on samples, in m/s^2"},
    {SW_CLI_DOUBLE, 0, "gap", "SECONDS", GATE(gap), .rule = SW_NUM_NONNEGATIVE, .lo = 1e-4,
     .hi = 86400, .what = "a number of seconds >= 0 (0: ten times the logger's spacing)",
     .help = "samples further apart are a gap, an event counted in the summary (default: ten "
             "times the spacing the logger keeps over the whole log, and at least 10 ms; "
             "docs/timing.md); at most a day"},
    {SW_CLI_CALL, 0, "gap-policy", "bridge|restart", GATE(gap_policy), .fn = parse_policy,
     .help = "across a gap: interpolate linearly (bridge, the default), or treat it as "
             "missing and restart every package from rest"},
    {SW_CLI_DOUBLE, 0, "max-bridge", "SECONDS", GATE(max_bridge), .rule = SW_NUM_POSITIVE,
     .def = 10, .lo = 1e-3, .hi = 86400, .what = "a positive number of seconds",
     .help = "longest gap bridged; longer ones restart the packages from rest (default %g)"},
    {SW_CLI_DOUBLE, 0, "max-jump", "SECONDS", GATE(max_jump), .rule = SW_NUM_NONNEGATIVE, .def = -1,
     .lo = 1e-6, .hi = 86400, .what = "a number of seconds >= 0 (0: take any time at once)",
     .help = "a sample whose time leaps further than this beyond the time that passed (or goes "
             "back) waits until the stream confirms it (default: 1.5 of the logger's sample "
             "intervals; 0: never wait)"},
    {SW_CLI_LONG, 0, "confirm", "N", GATE(confirm), .min = 2, .max = SW_GATE_CONFIRM_MAX, .def = 3,
     .what = "a number of samples from 2 to " SW_CLI_STR(SW_GATE_CONFIRM_MAX),
     .help = "samples in a row that confirm a leap or a restart of the time (default %g)"},
    {SW_CLI_FLAG, 0, "vert-includes-gravity", GATE(vert_gravity), .value = 1,
     .help = "the vertical channel reads +1 g at rest (an accelerometer): gravity is "
             "subtracted once"},
    {SW_CLI_FLAG, 0, "vert-excludes-gravity", GATE(vert_gravity), .value = 0,
     .help = "the vertical channel has gravity removed already (0 at rest)"},
    {SW_CLI_DOUBLE, 0, "max-rejected", "PERCENT", GATE(max_rejected), .rule = SW_NUM_NONNEGATIVE,
     .def = 1, .lo = 0, .hi = 100, .what = "a percentage >= 0",
     .help = "refuse a verdict when more than this share of the samples was rejected (default "
             "%g percent)"},
    {SW_CLI_FLAG, 0, "force", GATE(force), .value = 1,
     .help = "give a verdict even for a log the plausibility check refuses (a rate or span no "
             "vehicle log has, an impossible peak, too many rejected rows); marked as forced"},
    {.kind = SW_CLI_END},
};

/* The value of a text option, one of a few names: dest gets the value of
 * the name, or the message names the choices. */
static int parse_delim(const sw_cli_option_t *o, const char *arg, void *dest)
{
    char *out = dest;
    if (!strcmp(arg, ",") || !strcmp(arg, "comma"))
        *out = ',';
    else if (!strcmp(arg, ";") || !strcmp(arg, "semicolon"))
        *out = ';';
    else if (!strcmp(arg, "tab") || !strcmp(arg, "\t") || !strcmp(arg, "\\t"))
        *out = '\t';
    else {
        sw_cli_error("--%s: expected ',', ';' or tab, got '%s'", o->long_name, arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* A unit option, read as a header's unit is (csv.h): "g", "G", "Gs",
 * "m/s2", "m/s^2", "m/s²", "mps2"; "s", "ms", "us". */
static int parse_unit(const sw_cli_option_t *o, const char *arg, double *scale, int time_role)
{
    const int u = sw_csv_unit_parse(arg, time_role);
    if (u == SW_CSV_UNIT_NONE) {
        sw_cli_error(
            "--%s: expected %s, got '%s'", o->long_name,
            time_role ? "s, ms, us or ns" : "m/s2 (or m/s^2, m/s\xc2\xb2, mps2), g (G, Gs) or mg",
            arg);
        return SW_EXIT_USAGE;
    }
    *scale = sw_csv_unit_scale(u);
    return SW_EXIT_OK;
}

int sw_cli_accel_unit(const sw_cli_option_t *o, const char *arg, void *dest)
{
    return parse_unit(o, arg, dest, 0);
}

static int parse_time_unit(const sw_cli_option_t *o, const char *arg, void *dest)
{
    return parse_unit(o, arg, dest, 1);
}

static int parse_date_order(const sw_cli_option_t *o, const char *arg, void *dest)
{
    int *out = dest;
    if (!strcmp(arg, "dmy"))
        *out = SW_CSV_DATE_DMY;
    else if (!strcmp(arg, "mdy"))
        *out = SW_CSV_DATE_MDY;
    else {
        sw_cli_error("--%s: expected dmy (day first) or mdy (month first), got '%s'", o->long_name,
                     arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* Column choice: a header name or a 1-based index; "0" is neither. */
static int check_col(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    char *end = NULL;
    long v = strtol(arg, &end, 10);
    if (*arg == '\0' || (end != arg && *end == '\0' && v < 1)) {
        sw_cli_error("--%s: expected a column name or a 1-based index, got '%s'", o->long_name,
                     arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* --skip-lines 0 says there is no preamble: the reader's -1 (its 0 is
 * "find it"). */
static int skip_lines(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)o;
    (void)arg;
    long *n = dest;
    if (*n == 0)
        *n = -1;
    return SW_EXIT_OK;
}

#define CSV(f) SW_CLI_AT(sw_cli_csv_opts_t, f)
#define CSV_SECTION                                                                   \
    "CSV input (default: column 1 time in s, column 2 longitudinal acceleration in\n" \
    "m/s^2, x forward: braking is negative; optional header row; '#' comments):"

const sw_cli_option_t sw_cli_csv_options[] = {
    {SW_CLI_SECTION, .help = CSV_SECTION},
    {SW_CLI_STRING, 0, "time-col", "NAME|N", CSV(csv.time_col), .fn = check_col,
     .help = "time column, by header name or 1-based index (default: the header's time "
             "column, else 1)"},
    {SW_CLI_STRING, 0, "accel-col", "NAME|N", CSV(csv.accel_col), .fn = check_col,
     .help = "longitudinal acceleration column (default: the header's, x among several "
             "axes, else 2)"},
    {SW_CLI_STRING, 0, "vert-col", "NAME|N", CSV(csv.vert_col), .fn = check_col,
     .help = "vertical acceleration column, up positive, same unit as --accel-unit; say "
             "whether it includes gravity (--vert-includes-gravity: an accelerometer reads +1 g "
             "at rest) (default: none, gravity only)"},
    {SW_CLI_STRING, 0, "lat-col", "NAME|N", CSV(csv.lat_col), .fn = check_col,
     .help = "lateral acceleration column, across the truck (y to the left), same unit "
             "handling as --accel-col; it drives the lateral plane of the scenes that give "
             "package.depth (default: the header's lateral column: Lateral Gs, Y (g), ay; none: "
             "one plane, along the truck)"},
    {SW_CLI_CALL, 0, "delimiter", "D", CSV(csv.delim), .fn = parse_delim,
     .help = "',', ';' or tab (default: detected from the first line)"},
    {SW_CLI_FLAG, 0, "header", CSV(csv.header), .value = 1,
     .help = "the first row is a header (default: detected)"},
    {SW_CLI_FLAG, 0, "no-header", CSV(csv.header), .value = 0,
     .help = "the first row is data (and no preamble is looked for)"},
    {SW_CLI_LONG, 0, "skip-lines", "N", CSV(csv.skip_lines), .min = 0, .max = 1000000,
     .fn = skip_lines, .what = "a number of lines from 0 to 1000000",
     .help = "the first N lines are a preamble before the table (its header, or its first row), "
             "skipped and counted; 0: there is none (default: found, see below)"},
    {SW_CLI_CALL, 0, "time-unit", "U", CSV(csv.time_scale), .fn = parse_time_unit,
     .help = "s, ms, us or ns (default: from the header's name, else from the values when they "
             "are an epoch, else s)"},
    {SW_CLI_CALL, 0, "date-order", "dmy|mdy", CSV(csv.date_order), .fn = parse_date_order,
     .help = "date-times that write day and month before the year (14/05/2016, 20.05.2024): "
             "day first (dmy) or month first (mdy) (default: told from the values, where a "
             "number above 12 is the day)"},
    {SW_CLI_FLAG, 0, "decimal-comma", CSV(csv.decimal_comma), .value = 1,
     .help = "',' is the decimal mark (default: detected in ';' and tab files from the first "
             "number with a mark)"},
    {SW_CLI_FLAG, 0, "no-decimal-comma", CSV(csv.decimal_comma), .value = 0,
     .help = "refuse numbers with a ','"},
    {SW_CLI_TEXT,
     .help = "How a CSV log is read (docs/input.md has the table): the first 256 rows are\n"
             "looked at before anything is decided; stderr says what was chosen and from\n"
             "where; what the file does not say is refused, naming the option that says it.\n"
             "  preamble  lines above the table (a title, key: value lines) are skipped when\n"
             "            the first row of two or more numbers, whose field count the rows\n"
             "            under it keep, shows where the table starts; in doubt, none.\n"
             "  header    the table's first line, if its time field is not a number.\n"
             "  time      a column with a time unit (Zeit [s], uptimeNanos), named as time\n"
             "            (time, timestamp, elapsed, uptime, Datum...) or holding date-times;\n"
             "            of several the finer (fewer repeated stamps, shorter steps), then\n"
             "            one with a unit; still several or none: refused, --time-col.\n"
             "  accel     a column whose unit is an acceleration (X (g), Beschl. [m/s^2],\n"
             "            Acceleration Gs, X (100g)) or named one (accel, acc, ax); a name\n"
             "            that says acceleration beats a bare axis (X); never a column whose\n"
             "            unit is anything else (deg, m, km/h, rpm, %, uT, rad/s, degC, raw)\n"
             "            nor a magnitude; of several the x axis, else the one with no axis;\n"
             "            still several or none: refused, --accel-col.\n"
             "  lateral   for scenes with package.depth: an acceleration along y (Lateral Gs,\n"
             "            Y (g), ay, accelerometerAccelerationY); several: refused,\n"
             "            --lat-col; none: the packages are judged along the truck only.\n"
             "  units     as given, else the name's (in brackets in any language, or a last\n"
             "            word: _ms, Gs, Nanos), else for time an epoch's told by its size\n"
             "            (s, ms, us or ns since 1970: \"from the values\"), else s and m/s^2;\n"
             "            a time named in minutes or hours (Time (min), Zeit [h]): refused,\n"
             "            --time-unit once the times are in s, ms, us or ns.\n"
             "  dates     ISO-8601 and year first; day and month first (14/05/2016 11:17:09,\n"
             "            20.05.2024 12:00:00.000, 5/14/2016 1:17:09 PM) in the order a day\n"
             "            above 12 shows; none above 12: refused, --date-order dmy|mdy.\n"
             "Epoch and date-time logs are timed from their start."},
    {.kind = SW_CLI_END},
};

const sw_cli_option_t sw_cli_sample_options[] = {
    {SW_CLI_SECTION, .help = CSV_SECTION},
    {SW_CLI_CALL, 0, "accel-unit", "U", CSV(csv.accel_scale), .fn = sw_cli_accel_unit,
     .help = "m/s2 (m/s^2, mps2), g (G, Gs) or mg, "
             "1 g = " SW_CLI_STR(SW_G0) " m/s^2 (default: from the header's name, else m/s2)"},
    {SW_CLI_FLAG, 0, "flip", CSV(csv.flip), .value = 1,
     .help = "negate the longitudinal axis (logger mounted backwards)"},
    {SW_CLI_FLAG, 0, "flip-lat", CSV(csv.flip_lat), .value = 1,
     .help = "negate the lateral axis (a logger whose y axis points to the right)"},
    {SW_CLI_FLAG, 0, "strict", CSV(strict), .value = 1,
     .help = "stop at the first rejected row, exit 2"},
    {SW_CLI_TEXT,
     .help = "Rows that cannot be used (missing field, not a number, not finite, time not\n"
             "increasing) are counted and reported on stderr with their line number (the "
             "first\n" SW_CLI_STR(
                 SW_CLI_MAX_PRINTED_REJECTS) " one by one); the run goes on without them "
                                             "unless --strict.\n"
                                             "With --quiet, they are only counted (one line on "
                                             "stderr)."},
    {.kind = SW_CLI_END},
};

/* ---- rejected rows, log files ------------------------------------------------- */

void sw_cli_rejects_add(sw_cli_rejects_t *r, long line, const char *reason)
{
    if (r->stop)
        return; /* strict: the run already ended at an earlier row */
    r->reported++;
    if (r->strict)
        r->stop = 1;
    if (r->quiet || r->printed >= SW_CLI_MAX_PRINTED_REJECTS)
        return;
    r->printed++;
    sw_cli_error("%s:%ld: %s", r->name, line, reason);
}

void sw_cli_rejects_summary(const sw_cli_rejects_t *r)
{
    if (r->reported <= r->printed)
        return;
    if (r->quiet)
        sw_cli_error("%s: %ld rejected rows", r->name, r->reported);
    else
        sw_cli_error("%s: ... %ld more rejected rows", r->name, r->reported - r->printed);
}

int sw_cli_logfile_open(sw_cli_logfile_t *f, const char *path)
{
    memset(f, 0, sizeof *f);
    f->name = strcmp(path, "-") ? path : "(stdin)";
    f->in = strcmp(path, "-") ? fopen(path, "rb") : stdin;
    if (!f->in) {
        sw_cli_error("%s: cannot open: %s", path, strerror(errno));
        return SW_EXIT_IO;
    }
    f->buf = malloc(CHUNK);
    if (!f->buf) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    f->len = fread(f->buf, 1, CHUNK, f->in);
    if (ferror(f->in)) {
        sw_cli_error("%s: cannot read: %s", f->name, strerror(errno));
        return SW_EXIT_IO;
    }
    return SW_EXIT_OK;
}

int sw_cli_logfile_pump(sw_cli_logfile_t *f, sw_csv_t *csv, const int *stop, void (*after)(void *),
                        void *user, int *fr)
{
    *fr = SW_OK;
    while (f->len > 0 && !*stop) {
        *fr = sw_csv_feed(csv, f->buf, f->len);
        if (after)
            after(user);
        if (*fr < 0)
            return SW_EXIT_OK;
        f->len = fread(f->buf, 1, CHUNK, f->in);
        if (ferror(f->in)) {
            sw_cli_error("%s: cannot read: %s", f->name, strerror(errno));
            return SW_EXIT_IO;
        }
    }
    if (!*stop) {
        *fr = sw_csv_finish(csv);
        if (after)
            after(user);
    }
    return SW_EXIT_OK;
}

void sw_cli_logfile_close(sw_cli_logfile_t *f)
{
    free(f->buf);
    if (f->in && f->in != stdin)
        fclose(f->in);
    memset(f, 0, sizeof *f);
}
