/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_csv_stages.c - the CSV reader's stages one by one (csv_int.h): the
 * unit reader, the inference of columns from a header's names, the
 * preamble finder, the time readers and the columns' profiles.  Every
 * expected value is what the header text itself says (its unit, its
 * words), not what the reader happened to return. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "csv_int.h"
#include "swaywatch/csv.h"
#include "swaywatch/status.h"

/* ---- the unit reader ----------------------------------------------------------- */

static void expect_class(const char *text, int cls, int unit)
{
    int u = -1;
    const int c = sw_csv_unit_class(text, &u);
    if (c != cls || u != unit)
        fail_msg("\"%s\": class %d unit %d, expected %d %d", text, c, u, cls, unit);
}

static void test_unit_class(void **state)
{
    (void)state;
    /* time */
    expect_class("s", SW_CSV_UC_TIME, SW_CSV_UNIT_S);
    expect_class("Sec", SW_CSV_UC_TIME, SW_CSV_UNIT_S);
    expect_class("ms", SW_CSV_UC_TIME, SW_CSV_UNIT_MS);
    expect_class("\xc2\xb5s", SW_CSV_UC_TIME, SW_CSV_UNIT_US);
    expect_class("ns", SW_CSV_UC_TIME, SW_CSV_UNIT_NS);
    expect_class("Nanos", SW_CSV_UC_TIME, SW_CSV_UNIT_NS);
    /* accelerations, and a logger's range written as the unit */
    expect_class("g", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G);
    expect_class("Gs", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G);
    expect_class("G's", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G);
    expect_class("mg", SW_CSV_UC_ACCEL, SW_CSV_UNIT_MG);
    expect_class("m/s\xc2\xb2", SW_CSV_UC_ACCEL, SW_CSV_UNIT_MPS2);
    expect_class("m / s ^ 2", SW_CSV_UC_ACCEL, SW_CSV_UNIT_MPS2);
    expect_class("100g", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G);
    expect_class(
        "\xc2\xb1"
        "16 g",
        SW_CSV_UC_ACCEL, SW_CSV_UNIT_G);
    expect_class("+-2g", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G);
    /* the units the issue lists, and more: never an acceleration */
    const char *const other[] = {"deg",
                                 "Degrees",
                                 "m",
                                 "mi",
                                 "km/h",
                                 "mph",
                                 "rpm",
                                 "%",
                                 "\xc2\xb5T",
                                 "rad/s",
                                 "\xc2\xb0"
                                 "C",
                                 "Hz",
                                 "hPa",
                                 "m/s",
                                 "\xc2\xb0/s",
                                 NULL};
    for (int i = 0; other[i]; i++) expect_class(other[i], SW_CSV_UC_OTHER, SW_CSV_UNIT_NONE);
    /* written, but no unit known: not an acceleration either */
    expect_class("raw", SW_CSV_UC_UNKNOWN, SW_CSV_UNIT_NONE);
    expect_class("16 deg", SW_CSV_UC_UNKNOWN, SW_CSV_UNIT_NONE); /* a range only of g */
    expect_class("", SW_CSV_UC_NONE, SW_CSV_UNIT_NONE);
    /* the options' reading: one role at a time */
    assert_int_equal(sw_csv_unit_parse("ns", 1), SW_CSV_UNIT_NS);
    assert_int_equal(sw_csv_unit_parse("ns", 0), SW_CSV_UNIT_NONE);
    assert_int_equal(sw_csv_unit_parse("g", 1), SW_CSV_UNIT_NONE);
    assert_int_equal(sw_csv_unit_parse("100g", 0), SW_CSV_UNIT_NONE); /* a range is a header's */
    assert_true(sw_csv_unit_scale(SW_CSV_UNIT_NS) == 1e-9);
    assert_true(sw_csv_unit_scale(SW_CSV_UNIT_MG) == 9.80665e-3);
}

/* name -> its unit's class and unit, and its words joined by '|' */
static void expect_words(const char *name, int cls, int unit, const char *words)
{
    sw_csv_words_t w;
    sw_csv_words(name, &w);
    char got[256] = "";
    for (int i = 0; i < w.nw; i++) {
        strcat(got, i ? "|" : "");
        strcat(got, w.w[i]);
    }
    if (w.uclass != cls || w.unit_id != unit || strcmp(got, words))
        fail_msg("\"%s\": class %d unit %d words \"%s\", expected %d %d \"%s\"", name, w.uclass,
                 w.unit_id, got, cls, unit, words);
}

static void test_words(void **state)
{
    (void)state;
    expect_words("Longitude / X Position (Degrees)", SW_CSV_UC_OTHER, SW_CSV_UNIT_NONE,
                 "longitude|x|position");
    expect_words("Acceleration Gs", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G, "acceleration");
    expect_words("Accel X (g)", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G, "accel|x");
    expect_words("Beschl. [m/s\xc2\xb2]", SW_CSV_UC_ACCEL, SW_CSV_UNIT_MPS2, "beschl");
    expect_words("Zeit [s]", SW_CSV_UC_TIME, SW_CSV_UNIT_S, "zeit");
    expect_words("Temps (s)", SW_CSV_UC_TIME, SW_CSV_UNIT_S, "temps");
    expect_words("Acc\xc3\xa9l\xc3\xa9ration (g)", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G,
                 "acc\xc3\xa9l\xc3\xa9ration");
    /* camel case, unit words first or last */
    expect_words("uptimeNanos", SW_CSV_UC_TIME, SW_CSV_UNIT_NS, "uptime");
    expect_words("seconds_elapsed", SW_CSV_UC_TIME, SW_CSV_UNIT_S, "elapsed");
    expect_words("time_ns", SW_CSV_UC_TIME, SW_CSV_UNIT_NS, "time");
    expect_words("Time (ns)", SW_CSV_UC_TIME, SW_CSV_UNIT_NS, "time");
    expect_words("accelerometerAccelerationX(G)", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G,
                 "accelerometer|acceleration|x");
    expect_words("accelerometerTimestamp_sinceReboot(s)", SW_CSV_UC_TIME, SW_CSV_UNIT_S,
                 "accelerometer|timestamp|since|reboot");
    expect_words("GPSTime", SW_CSV_UC_NONE, SW_CSV_UNIT_NONE, "gps|time");
    expect_words("AccX", SW_CSV_UC_NONE, SW_CSV_UNIT_NONE, "acc|x");
    expect_words("aT", SW_CSV_UC_NONE, SW_CSV_UNIT_NONE, "at");
    /* Physics Toolbox's g-force names its unit */
    expect_words("gFx", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G, "gfx");
    expect_words("G-Force X", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G, "g|force|x");
    /* ranges, several brackets, units that are not accelerations */
    expect_words("X (100g)", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G, "x");
    expect_words("Acc [g] (filtered)", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G, "acc");
    expect_words("heading_deg", SW_CSV_UC_OTHER, SW_CSV_UNIT_NONE, "heading");
    expect_words("X (raw)", SW_CSV_UC_UNKNOWN, SW_CSV_UNIT_NONE, "x");
    expect_words("acc_v", SW_CSV_UC_NONE, SW_CSV_UNIT_NONE, "acc|v"); /* an axis, not volts */
    expect_words("g", SW_CSV_UC_NONE, SW_CSV_UNIT_NONE, "g");         /* a name alone is a name */
    expect_words("accel_g", SW_CSV_UC_ACCEL, SW_CSV_UNIT_G, "accel");
    expect_words("time_ms", SW_CSV_UC_TIME, SW_CSV_UNIT_MS, "time");
}

/* ---- the inference ----------------------------------------------------------- */

/* The header in one string, fields split on '|'. */
static long header(const char *text, char names[][SW_CSV_NAME_MAX])
{
    long n = 0;
    const char *p = text;
    for (;;) {
        const char *e = strchr(p, '|');
        const size_t k = e ? (size_t)(e - p) : strlen(p);
        snprintf(names[n], SW_CSV_NAME_MAX, "%.*s", (int)k, p);
        n++;
        if (!e)
            return n;
        p = e + 1;
    }
}

/* Guess time and accel: their 1-based columns (0: refused, with the
 * reason in why). */
static void guess(const char *text, long *t, long *a, char *why, size_t cap)
{
    char names[SW_CSV_MAX_FIELDS][SW_CSV_NAME_MAX];
    const long n = header(text, names);
    const int want[SW_CSV_NROLES] = {1, 1, 0};
    sw_csv_guess_t g;
    *t = *a = 0;
    if (sw_csv_guess((const char(*)[SW_CSV_NAME_MAX])names, n, want, -1, NULL, 0, &g) != 0) {
        snprintf(why, cap, "%s", g.why);
        return;
    }
    why[0] = '\0';
    *t = g.col[SW_CSV_ROLE_TIME] + 1;
    *a = g.col[SW_CSV_ROLE_ACCEL] + 1;
}

static void expect_cols(const char *text, long t, long a)
{
    long gt, ga;
    char why[256];
    guess(text, &gt, &ga, why, sizeof why);
    if (gt != t || ga != a)
        fail_msg("%s: time %ld accel %ld (%s), expected %ld %ld", text, gt, ga, why, t, a);
}

static void expect_refused(const char *text, const char *says)
{
    long gt, ga;
    char why[256];
    guess(text, &gt, &ga, why, sizeof why);
    if (gt || ga || !strstr(why, says))
        fail_msg("%s: time %ld accel %ld (%s), expected a refusal saying \"%s\"", text, gt, ga, why,
                 says);
}

static void test_inference(void **state)
{
    (void)state;
    /* units beat axis letters; a unit that is not an acceleration is never
     * one (the CAN export with GPS columns of the issue) */
    expect_cols(
        "Time (s)|Latitude / Y Position (Degrees)|Longitude / X Position (Degrees)|"
        "Speed (km/h)|Heading (Degrees)|Acceleration Gs|Lateral Gs|Engine (rpm)",
        1, 6);
    expect_cols("t|X|Acceleration Gs", 1, 3);
    expect_cols("Zeit [s]|Beschl. [m/s\xc2\xb2]", 1, 2);
    expect_cols("Temps (s)|Acc\xc3\xa9l\xc3\xa9ration (g)", 1, 2);
    expect_cols("time|gFx|gFy|gFz|TgF", 1, 2);
    expect_cols("time|ax|ay|az|aT", 1, 2);
    expect_cols(
        "Time (s)|Acceleration x (m/s^2)|Acceleration y (m/s^2)|Acceleration z "
        "(m/s^2)|Absolute acceleration (m/s^2)",
        1, 2);
    expect_cols(
        "Time (s)|X (100g)|Y (100g)|Z (100g)|Temperature (\xc2\xb0"
        "C)",
        1, 2);
    /* the phone apps: a unit-suffixed iPhone export, Sensor Logger */
    expect_cols(
        "loggingTime(txt)|loggingSample(N)|accelerometerTimestamp_sinceReboot(s)|"
        "accelerometerAccelerationX(G)|accelerometerAccelerationY(G)|"
        "accelerometerAccelerationZ(G)",
        3, 4);
    expect_cols("time|seconds_elapsed|z|y|x", 2, 5);
    expect_cols("uptimeNanos|x|y|z", 1, 2);
    /* a time named in words beats a duration with only a unit */
    expect_cols("Duration (ms)|Time (s)|ax", 2, 3);
    /* refusals: nothing left, or two still equal */
    expect_refused("t|X (deg)|Y (deg)", "their units are not accelerations: \"X (deg)\"");
    expect_refused("t|Magnetic field x (\xc2\xb5T)|Gyroscope x (rad/s)", "not accelerations");
    expect_refused("time|acc1 (g)|acc2 (g)", "\"acc2 (g)\" (column 3)");
    expect_refused("t|X|Accel Y (g)", "\"Accel Y (g)\" (column 3), \"X\" (column 2)");
    expect_refused("Time (s)|Absolute acceleration (m/s^2)", "no column is named as an acc");
    expect_refused("t1 (s)|t2 (s)|ax", "several columns could be time");
}

/* ---- the preamble finder ------------------------------------------------------- */

/* The lines of text (one string, '\n' between lines; all data-like). */
static long find(const char *text, char delim, int header)
{
    static char buf[4096];
    sw_csv_line_t lines[64];
    long n = 0;
    snprintf(buf, sizeof buf, "%s", text);
    for (char *p = buf; *p && n < 64;) {
        char *e = strchr(p, '\n');
        lines[n].s = p;
        lines[n].n = e ? (size_t)(e - p) : strlen(p);
        n++;
        if (!e)
            break;
        p = e + 1;
    }
    const sw_csv_preamble_opts_t o = {delim, header, newlocale(LC_NUMERIC_MASK, "C", (locale_t)0)};
    const long k = sw_csv_preamble_find(lines, n, &o);
    freelocale(o.cloc);
    return k;
}

static void test_preamble(void **state)
{
    (void)state;
    /* a shock logger's export: 8 lines about the recording, then the table */
    const char *saver =
        "Shock recorder export\n"
        "Instrument:,SR-3X\n"
        "Serial Number:,10427\n"
        "Event:,17\n"
        "Trigger:,X axis 0.50 G\n"
        "Sample Rate:,1000 Hz\n"
        "Pre-trigger:,10 %\n"
        "Units:,G\n"
        "Time (s),X (G),Y (G),Z (G)\n"
        "0.000,0.01,0.00,1.00\n"
        "0.001,-0.02,0.01,1.01\n"
        "0.002,-0.05,0.00,0.99\n";
    assert_int_equal(find(saver, 0, -1), 8);
    assert_int_equal(find(saver, ',', 1), 8);
    assert_int_equal(find(saver, 0, 0), 0); /* no header: the first line is a row */
    /* "key,value" lines over a table of two columns */
    assert_int_equal(
        find("Device,Phone\nRate,100 Hz\nSerial,12345\ntime,accel\n0,1\n0.01,2\n0.02,3\n", 0, -1),
        3);
    /* no header: the lines of words before the first row */
    assert_int_equal(find("Logger X\nStarted 2024-05-20\n0,1\n0.1,2\n0.2,3\n", 0, -1), 2);
    /* ';' with decimal commas, tab, quotes, a trailing delimiter in the rows */
    assert_int_equal(find("Ger\xc3\xa4t;SR-3X\nZeit [s];Beschl. [m/s\xc2\xb2]\n0,00;0,1\n0,01;0,2\n"
                          "0,02;0,3\n",
                          0, -1),
                     1);
    assert_int_equal(find("title\t\nt\ta\n0\t1\n1\t2\n2\t3\n", 0, -1), 1);
    assert_int_equal(find("\"Instrument\",\"X\"\n\"t\",\"a\"\n\"0\",\"1\"\n\"1\",\"2\"\n", 0, -1),
                     1);
    assert_int_equal(find("Title\na,b\n0,1,\n1,2,\n2,3,\n", 0, -1), 1);
    /* no preamble: the table starts at the first line */
    assert_int_equal(find("t,a\n0,1\n1,2\n", 0, -1), 0);
    assert_int_equal(find("0,1\n1,2\n", 0, -1), 0);
    /* doubt: the table starts at the first line, as without a preamble */
    assert_int_equal(find("0,nan\n1,inf\n2,1\n3,1\n4,1\n", 0, -1), 0); /* rows spoilt */
    assert_int_equal(find("0,nan\n2,1e400\nt,a\n3,1\n4,1\n", 0, -1), 0);
    assert_int_equal(find("0.00O,-9\n0.001,-9\n0.002,-9\n", 0, -1), 0); /* a corrupt time */
    assert_int_equal(find("12345\n0,1\n1,2\n", 0, -1), 0);              /* no words */
    assert_int_equal(find("time,accel\n0.000,0.1\n0.001;0.2\n0.002\t0.3\n0.003,0.4\n0.004;0.5\n"
                          "0.005,0.6\n",
                          0, -1),
                     0); /* the rows do not keep a field count */
    assert_int_equal(find("Title\nCal,1.0,2.0,3.0\nt,a\n0,1\n1,2\n2,3\n", 0, -1), 0);
    assert_int_equal(find("Title\nt,a\n0,1\n1,2,3\n2,3,4\n3\n", 0, -1), 0);
    assert_int_equal(find("Title only\n", 0, -1), 0);
}

/* ---- the time readers ---------------------------------------------------------- */

/* Seconds since 1970 of the dates below, from GNU date (date -u -d
 * "2024-05-20 12:00:00" +%s, and so on): an independent calendar. */
#define T_2024_05_20_1200 1716206400.0
#define T_2016_05_14_111709 1463224629.0
#define T_2016_05_14_131709 1463231829.0
#define T_2000_02_29_235959 951868799.0
#define T_2024_06_05_1200 1717588800.0
#define T_2024_05_06_1200 1714996800.0
#define T_2024_01_01_0030 1704069000.0

static void expect_time(const char *s, int order, int rc, double t)
{
    double v = -1.0;
    const int got = sw_csv_datetime(s, strlen(s), order, &v);
    if (got != rc || (rc == 1 && fabs(v - t) > 1e-6))
        fail_msg("\"%s\" order %d: %d %.6f, expected %d %.6f", s, order, got, v, rc, t);
}

static void test_datetimes(void **state)
{
    (void)state;
    const int D = SW_CSV_DATE_DMY, M = SW_CSV_DATE_MDY, A = SW_CSV_DATE_AUTO;
    /* year first: ISO-8601 and its kin, whatever the order option */
    expect_time("2024-05-20T12:00:00.000Z", A, 1, T_2024_05_20_1200);
    expect_time("2024-05-20 14:00:00+02:00", A, 1, T_2024_05_20_1200);
    expect_time("2016/05/14 11:17:09", M, 1, T_2016_05_14_111709);
    /* day and month first: the two shapes, and a spreadsheet's */
    expect_time("14/05/2016 11:17:09", D, 1, T_2016_05_14_111709);
    expect_time("20.05.2024 12:00:00.000", D, 1, T_2024_05_20_1200);
    expect_time("20-05-2024 12:00:00.250", D, 1, T_2024_05_20_1200 + 0.25);
    expect_time("05/14/2016 11:17:09", M, 1, T_2016_05_14_111709);
    expect_time("5/14/2016 1:17:09 PM", M, 1, T_2016_05_14_131709);
    expect_time("1/1/2024 12:30 AM", D, 1, T_2024_01_01_0030);
    expect_time("29.02.2000 23:59:59", D, 1, T_2000_02_29_235959);
    /* one text, two dates: the order decides */
    expect_time("05/06/2024 12:00:00", D, 1, T_2024_06_05_1200);
    expect_time("05/06/2024 12:00:00", M, 1, T_2024_05_06_1200);
    expect_time("05/06/2024 12:00:00", A, -1, 0.0); /* not known: neither */
    /* impossible dates, and texts that are not date-times */
    expect_time("31/02/2024 00:00:00", D, 0, 0.0);
    expect_time("14/05/2016 11:17:09", M, 0, 0.0); /* month 14 */
    expect_time("29.02.2023 12:00:00", D, 0, 0.0);
    expect_time("13:00 PM", D, 0, 0.0);
    expect_time("14/05/2016", D, 0, 0.0);        /* a date without a time */
    expect_time("14/05/16 11:17:09", D, 0, 0.0); /* a year of two digits */
    expect_time("14/05-2016 11:17:09", D, 0, 0.0);
    expect_time("1.5", D, 0, 0.0);
    expect_time("1/1/2024 13:30 PM", D, 0, 0.0);
    assert_true(sw_csv_is_datetime("05/06/2024 12:00:00", 19));
    assert_false(sw_csv_is_datetime("45/06/2024 12:00:00", 19));
}

static void test_epoch(void **state)
{
    (void)state;
    /* 2000-01-01 and 2100-01-01 bound an epoch (date -u -d 2000-01-01 +%s:
     * 946684800; 2100-01-01: 4102444800) */
    assert_int_equal(sw_csv_epoch_unit(946684800.0), SW_CSV_UNIT_S);
    assert_int_equal(sw_csv_epoch_unit(946684799.0), SW_CSV_UNIT_NONE);
    assert_int_equal(sw_csv_epoch_unit(4102444799.0), SW_CSV_UNIT_S);
    assert_int_equal(sw_csv_epoch_unit(T_2024_05_20_1200), SW_CSV_UNIT_S);
    assert_int_equal(sw_csv_epoch_unit(T_2024_05_20_1200 * 1e3 + 123), SW_CSV_UNIT_MS);
    assert_int_equal(sw_csv_epoch_unit(T_2024_05_20_1200 * 1e6), SW_CSV_UNIT_US);
    assert_int_equal(sw_csv_epoch_unit(T_2024_05_20_1200 * 1e9), SW_CSV_UNIT_NS);
    /* an uptime of ten hours in ns, a plain elapsed time: no epoch */
    assert_int_equal(sw_csv_epoch_unit(3.6e13), SW_CSV_UNIT_NONE);
    assert_int_equal(sw_csv_epoch_unit(0.5), SW_CSV_UNIT_NONE);
}

/* Profiles of the columns of rows given as one string ('|' between fields,
 * '\n' between rows). */
static long profiles(const char *rows, sw_csv_profile_t *p)
{
    locale_t cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    long nc = 0;
    memset(p, 0, SW_CSV_MAX_FIELDS * sizeof *p);
    for (const char *r = rows; *r;) {
        const char *e = strchr(r, '\n');
        const size_t len = e ? (size_t)(e - r) : strlen(r);
        long k = 0;
        for (size_t a = 0; a <= len; k++) {
            size_t b = a;
            while (b < len && r[b] != '|') b++;
            sw_csv_profile_add(&p[k], r + a, b - a, ',', cloc);
            a = b + 1;
        }
        if (k > nc)
            nc = k;
        r += len + (e != NULL);
    }
    freelocale(cloc);
    return nc;
}

static void test_profiles(void **state)
{
    (void)state;
    sw_csv_profile_t p[SW_CSV_MAX_FIELDS];
    /* a date to the second beside an uptime in ns, at 4 Hz */
    const char *rows =
        "2024-05-20 12:00:01|3600000000000|0.01\n"
        "2024-05-20 12:00:01|3600250000000|0.02\n"
        "2024-05-20 12:00:01|3600500000000|0.03\n"
        "2024-05-20 12:00:01|3600750000000|0.04\n"
        "2024-05-20 12:00:02|3601000000000|0.05\n"
        "2024-05-20 12:00:02|3601250000000|0.06\n";
    assert_int_equal(profiles(rows, p), 3);
    assert_int_equal(p[0].niso, 6);
    assert_int_equal(p[0].steps, 5);
    assert_int_equal(p[0].zero, 4); /* the stamp repeats */
    assert_true(p[0].minstep == 1.0);
    assert_int_equal(p[1].nnum, 6);
    assert_int_equal(p[1].zero, 0);
    assert_true(p[1].minstep == 250000000.0);
    assert_true(p[1].first == 3600000000000.0);
    /* the finer one is time; the coarse one first in the header */
    char names[SW_CSV_MAX_FIELDS][SW_CSV_NAME_MAX] = {"date", "uptimeNanos", "x"};
    const int want[SW_CSV_NROLES] = {1, 1, 0};
    sw_csv_guess_t g;
    assert_int_equal(sw_csv_guess((const char(*)[SW_CSV_NAME_MAX])names, 3, want, -1, p, 3, &g), 0);
    assert_int_equal(g.col[SW_CSV_ROLE_TIME], 1);
    /* the same resolution: the one with a unit, as without profiles */
    rows =
        "2024-05-20 12:00:00.000|0.00|0.1\n"
        "2024-05-20 12:00:00.100|0.10|0.1\n"
        "2024-05-20 12:00:00.200|0.20|0.1\n";
    profiles(rows, p);
    char names2[SW_CSV_MAX_FIELDS][SW_CSV_NAME_MAX] = {"Timestamp", "Time (s)", "Acceleration Gs"};
    assert_int_equal(sw_csv_guess((const char(*)[SW_CSV_NAME_MAX])names2, 3, want, -1, p, 3, &g),
                     0);
    assert_int_equal(g.col[SW_CSV_ROLE_TIME], 1);
    /* two clocks in ns, one coarse: the fine one even without a unit; both
     * fine: both named in the refusal */
    rows =
        "1716206400000000000|1716206400000000000|0.1\n"
        "1716206400000000000|1716206400010000000|0.1\n"
        "1716206401000000000|1716206400020000000|0.1\n";
    profiles(rows, p);
    char names3[SW_CSV_MAX_FIELDS][SW_CSV_NAME_MAX] = {"time_ns", "timestamp", "ax"};
    assert_int_equal(sw_csv_guess((const char(*)[SW_CSV_NAME_MAX])names3, 3, want, -1, p, 3, &g),
                     0);
    assert_int_equal(g.col[SW_CSV_ROLE_TIME], 1);
    rows =
        "1716206400000000000|1716206400000000000|0.1\n"
        "1716206400010000000|1716206400010000000|0.1\n"
        "1716206400020000000|1716206400020000000|0.1\n";
    profiles(rows, p);
    char names4[SW_CSV_MAX_FIELDS][SW_CSV_NAME_MAX] = {"time_ns", "timestamp_ns", "ax"};
    assert_int_not_equal(
        sw_csv_guess((const char(*)[SW_CSV_NAME_MAX])names4, 3, want, -1, p, 3, &g), 0);
    assert_non_null(strstr(g.why, "\"time_ns\" (column 1), \"timestamp_ns\" (column 2)"));
    /* day and month first: a number above 12 says which is the day */
    profiles("14/05/2016 11:17:09|1\n14/05/2016 11:17:10|2\n", p);
    assert_int_equal(p[0].ndm, 2);
    assert_int_equal(p[0].a13, 2);
    assert_int_equal(p[0].b13, 0);
    assert_true(p[0].minstep == 1.0);
    profiles("05/06/2024 12:00:00|1\n05/06/2024 12:00:01|2\n", p);
    assert_int_equal(p[0].ndm, 2);
    assert_int_equal(p[0].a13 + p[0].b13, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_unit_class), cmocka_unit_test(test_words),
        cmocka_unit_test(test_inference),  cmocka_unit_test(test_preamble),
        cmocka_unit_test(test_datetimes),  cmocka_unit_test(test_epoch),
        cmocka_unit_test(test_profiles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
