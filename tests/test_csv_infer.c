/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_csv_infer.c - reading a logger export as it was meant (csv.h): the
 * columns and units a header's names give (infer), date-time time columns,
 * decimal commas, and the refusals where the header does not say which
 * column is which.  The expected columns and units are what the header
 * texts say; date-times are checked against their epoch seconds computed
 * independently (Python's datetime, UTC). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/csv.h"
#include "swaywatch/status.h"

#define MAXROWS 16

typedef struct {
    double t[MAXROWS], a[MAXROWS];
    int n, rejected;
    char reason[256];
    int rc;
    char msg[512];
    sw_csv_layout_t lay;
    char h0[SW_CSV_NAME_MAX];
    long nh;
} res_t;

static int on_row(void *user, long line, double t, double a, double z)
{
    (void)line;
    (void)z;
    res_t *r = user;
    if (r->n < MAXROWS) {
        r->t[r->n] = t;
        r->a[r->n] = a;
    }
    r->n++;
    return 0;
}

static void on_reject(void *user, long line, const char *reason)
{
    (void)line;
    res_t *r = user;
    if (!r->rejected++)
        snprintf(r->reason, sizeof r->reason, "%s", reason);
}

/* Feed text in 5-byte chunks (the layout must not depend on the chunks). */
static void run(const char *text, const sw_csv_opts_t *o, res_t *r)
{
    memset(r, 0, sizeof *r);
    int err = 0;
    char msg[256];
    sw_csv_t *c = sw_csv_create(o, on_row, on_reject, r, &err, msg, sizeof msg);
    assert_non_null(c);
    const size_t n = strlen(text);
    r->rc = SW_OK;
    for (size_t i = 0; i < n && r->rc == SW_OK; i += 5)
        r->rc = sw_csv_feed(c, text + i, n - i < 5 ? n - i : 5);
    if (r->rc == SW_OK)
        r->rc = sw_csv_finish(c);
    snprintf(r->msg, sizeof r->msg, "%s", sw_csv_error_message(c));
    assert_int_equal(sw_csv_layout(c, &r->lay), SW_OK);
    r->nh = sw_csv_header_count(c);
    if (r->nh)
        snprintf(r->h0, sizeof r->h0, "%s", sw_csv_header_field(c, 0));
    sw_csv_destroy(c);
}

static sw_csv_opts_t infer_opts(void)
{
    sw_csv_opts_t o;
    memset(&o, 0, sizeof o);
    o.header = -1;
    o.infer = 1;
    o.decimal_comma = -1;
    return o;
}

/* A 3-axis shock logger's export: BOM, CRLF, quoted header, a sample index
 * before the time. */
static void test_three_axis_export(void **state)
{
    (void)state;
    res_t r;
    const sw_csv_opts_t o = infer_opts();
    run("\xEF\xBB\xBF\"Sample\",\"Time (ms)\",\"X (g)\",\"Y (g)\",\"Z (g)\",\"Temp (C)\"\r\n"
        "1,0,0.5,0.01,1.0,21.5\r\n2,1,-0.25,0.0,1.0,21.5\r\n",
        &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.n, 2);
    assert_true(r.lay.ready && r.lay.has_header);
    assert_int_equal(r.lay.col[0], 1);
    assert_int_equal(r.lay.col[1], 2);
    assert_string_equal(r.lay.name[0], "Time (ms)");
    assert_string_equal(r.lay.name[1], "X (g)");
    assert_int_equal(r.lay.unit[0], SW_CSV_UNIT_MS);
    assert_int_equal(r.lay.unit[1], SW_CSV_UNIT_G);
    assert_int_equal(r.lay.col_from[0], SW_CSV_FROM_HEADER);
    assert_int_equal(r.lay.unit_from[1], SW_CSV_FROM_HEADER);
    assert_true(r.t[1] == 1e-3);
    assert_true(r.a[0] == 0.5 * 9.80665 && r.a[1] == -0.25 * 9.80665);
    assert_string_equal(r.h0, "Sample");
    assert_int_equal(r.nh, 6);
}

static void test_units_in_suffixes(void **state)
{
    (void)state;
    res_t r;
    const sw_csv_opts_t o = infer_opts();
    run("time_ms;accel_g\n0;0\n1000;-0.5\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_true(r.t[1] == 1.0 && r.a[1] == -0.5 * 9.80665);
    /* a phone export: time in s, three axes in m/s^2, x is longitudinal */
    run("time_s,ax_mps2,ay_mps2,az_mps2\n0,1,2,9.8\n0.01,-3,2,9.8\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[1], 1);
    assert_int_equal(r.lay.unit[1], SW_CSV_UNIT_MPS2);
    assert_true(r.a[1] == -3.0);
    /* bracketed units with spaces and UTF-8 */
    run("Time [s]\tAcceleration x [m/s\xc2\xb2]\tAcceleration y [m/s\xc2\xb2]\n0\t1\t0\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.unit[0], SW_CSV_UNIT_S);
    assert_int_equal(r.lay.unit[1], SW_CSV_UNIT_MPS2);
    assert_int_equal(r.lay.col[1], 1);
    /* an axis-less acceleration beside a vertical one: the axis-less one;
     * the vertical column named as such is never a candidate */
    run("t_s,accel_mps2,z_mps2\n0,1,9.8\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[1], 1);
    sw_csv_opts_t ov = o;
    ov.vert_col = "a_vert";
    run("t_s,a_vert,accel\n0,9.8,1\n", &ov, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[1], 2);
    /* names without units: the defaults, said to be defaults */
    run("time,accel\n0,1\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.unit_from[0], SW_CSV_FROM_DEFAULT);
    assert_int_equal(r.lay.unit[1], SW_CSV_UNIT_MPS2);
}

/* A CAN-bus export: a date-time, elapsed seconds, one acceleration in G. */
static void test_can_export(void **state)
{
    (void)state;
    res_t r;
    const sw_csv_opts_t o = infer_opts();
    run("Timestamp,Time (s),Acceleration Gs\n"
        "2024-05-20T12:00:00.000Z,0.000,0.01\n2024-05-20T12:00:00.083Z,0.083,-0.2\n",
        &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[0], 1);
    assert_int_equal(r.lay.col[1], 2);
    assert_int_equal(r.lay.unit[1], SW_CSV_UNIT_G);
    assert_true(r.t[1] == 0.083);
    /* the date-time column itself, chosen by the user */
    sw_csv_opts_t o2 = o;
    o2.time_col = "Timestamp";
    run("Timestamp,Time (s),Acceleration Gs\n"
        "2024-05-20T12:00:00.000Z,0.000,0.01\n2024-05-20T12:00:00.083Z,0.083,-0.2\n",
        &o2, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.unit[0], SW_CSV_UNIT_DATETIME);
    assert_true(r.t[0] == 1716206400.0);
    assert_true(fabs(r.t[1] - 1716206400.083) < 1e-6);
}

static void test_datetimes(void **state)
{
    (void)state;
    res_t r;
    sw_csv_opts_t o;
    memset(&o, 0, sizeof o);
    o.header = -1;
    /* without a header: a date-time first field is data, not a header */
    run("2018-04-08 10:31:37.005628,0.5\n2024-05-20T14:00:00+02:00,1\n"
        "2000-02-29T23:59:59Z,2\n",
        &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.has_header, 0);
    assert_int_equal(r.n, 2); /* 2000 is before 2024: refused, time goes backwards */
    assert_true(fabs(r.t[0] - 1523183497.005628) < 1e-6);
    assert_true(r.t[1] == 1716206400.0);
    assert_non_null(strstr(r.reason, "not after previous"));
    /* date-times and numbers do not mix in one column */
    run("t,a\n2024-05-20T12:00:00Z,0\n5,1\n", &o, &r);
    assert_int_equal(r.n, 1);
    assert_non_null(strstr(r.reason, "not a date-time like the rows before it"));
    /* impossible dates are refused */
    run("t,a\n2023-02-29T00:00:00Z,0\n2024-13-01 00:00:00,0\n2024-01-01T24:00:00,0\n", &o, &r);
    assert_int_equal(r.n, 0);
    assert_int_equal(r.rejected, 3);
}

static void test_decimal_comma(void **state)
{
    (void)state;
    res_t r;
    const sw_csv_opts_t o = infer_opts();
    run("time_s;accel_mps2\n0,000;-0,00646\n0,001;0,5\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.n, 2);
    assert_int_equal(r.lay.decimal_comma, 1);
    assert_true(r.t[1] == 0.001 && r.a[0] == -0.00646 && r.a[1] == 0.5);
    /* a thousands separator is not a decimal mark */
    run("time_s;accel_mps2\n0,5;1\n1,5;1.000,5\n", &o, &r);
    assert_int_equal(r.n, 1);
    assert_int_equal(r.rejected, 1);
    /* '.' seen first: commas are refused as before */
    run("time_s;accel_mps2\n0.5;1\n1,5;2\n", &o, &r);
    assert_int_equal(r.lay.decimal_comma, 0);
    assert_int_equal(r.n, 1);
    assert_non_null(strstr(r.reason, "decimal comma?"));
    /* off (the default of zeroed options): refused */
    sw_csv_opts_t off = o;
    off.decimal_comma = 0;
    run("time_s;accel_mps2\n0,000;-0,00646\n", &off, &r);
    assert_int_equal(r.n, 0);
    /* on: '.' numbers are refused */
    sw_csv_opts_t on = o;
    on.decimal_comma = 1;
    run("t;a\n0.5;1\n", &on, &r);
    assert_int_equal(r.n, 0);
}

/* The header does not say which column is which: no guess. */
static void test_ambiguous(void **state)
{
    (void)state;
    res_t r;
    const sw_csv_opts_t o = infer_opts();
    run("a,b\n0,1\n", &o, &r);
    assert_int_equal(r.rc, SW_EAMBIGUOUS);
    assert_non_null(strstr(r.msg, "no column is named as time"));
    assert_int_equal(r.n, 0);
    run("time,acc1,acc2\n0,1,2\n", &o, &r);
    assert_int_equal(r.rc, SW_EAMBIGUOUS);
    assert_non_null(strstr(r.msg, "several columns could be the longitudinal acceleration"));
    assert_non_null(strstr(r.msg, "\"acc2\" (column 3)"));
    run("Sample,Value\n1,0.5\n", &o, &r);
    assert_int_equal(r.rc, SW_EAMBIGUOUS);
    run("t1 (s),t2 (s),ax\n0,0,1\n", &o, &r);
    assert_int_equal(r.rc, SW_EAMBIGUOUS);
    assert_non_null(strstr(r.msg, "several columns could be time"));
    /* the columns given: no question left */
    sw_csv_opts_t o2 = o;
    o2.time_col = "1";
    o2.accel_col = "acc2";
    run("time,acc1,acc2\n0,1,2\n", &o2, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_true(r.a[0] == 2.0);
    /* without infer, the defaults as always */
    sw_csv_opts_t o3 = o;
    o3.infer = 0;
    run("a,b\n0,1\n", &o3, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.n, 1);
}

/* An option wins over the header, and the layout shows what the header
 * said so that the contradiction can be reported. */
static void test_option_against_header(void **state)
{
    (void)state;
    res_t r;
    sw_csv_opts_t o = infer_opts();
    o.accel_scale = 1.0; /* m/s^2 */
    run("t_s,accel_g\n0,1\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_true(r.a[0] == 1.0);
    assert_int_equal(r.lay.unit[1], SW_CSV_UNIT_MPS2);
    assert_int_equal(r.lay.unit_from[1], SW_CSV_FROM_OPTION);
    assert_int_equal(r.lay.header_unit[1], SW_CSV_UNIT_G);
    /* no header: the defaults, from nowhere but the defaults */
    o = infer_opts();
    run("0,1\n1,2\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.has_header, 0);
    assert_int_equal(r.lay.col_from[0], SW_CSV_FROM_DEFAULT);
    assert_int_equal(r.lay.unit_from[1], SW_CSV_FROM_DEFAULT);
}

/* Issue 24: a CAN export with GPS columns.  "Longitude / X Position
 * (Degrees)" names the x axis, but its unit is an angle: the acceleration
 * is "Acceleration Gs", in g. */
static void test_units_not_accelerations(void **state)
{
    (void)state;
    res_t r;
    const sw_csv_opts_t o = infer_opts();
    run("Time (s),Latitude / Y Position (Degrees),Longitude / X Position (Degrees),"
        "Speed (km/h),Acceleration Gs,Lateral Gs\n"
        "0.00,48.137154,11.576124,50.2,0.01,0.00\n"
        "0.10,48.137160,11.576180,50.1,-0.35,0.02\n",
        &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[1], 4);
    assert_string_equal(r.lay.name[1], "Acceleration Gs");
    assert_int_equal(r.lay.unit[1], SW_CSV_UNIT_G);
    assert_true(r.a[1] == -0.35 * 9.80665);
    /* German units in brackets say everything */
    run("Zeit [s];Beschl. [m/s\xc2\xb2]\n0,00;0,1\n0,01;-2,5\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[0], 0);
    assert_int_equal(r.lay.col[1], 1);
    assert_int_equal(r.lay.unit_from[0], SW_CSV_FROM_HEADER);
    assert_int_equal(r.lay.unit[1], SW_CSV_UNIT_MPS2);
    assert_true(r.t[1] == 0.01 && r.a[1] == -2.5);
    /* only angles: no acceleration, and the reason names them */
    run("t,X (deg),Y (deg)\n0,1,2\n", &o, &r);
    assert_int_equal(r.rc, SW_EAMBIGUOUS);
    assert_non_null(strstr(r.msg, "their units are not accelerations"));
}

/* Issue 24's times: ns, epochs told by their magnitude, day-first dates,
 * and of two time columns the finer.  The expected times are the texts'
 * (1716206400 s is 2024-05-20T12:00:00Z: date -u -d 2024-05-20T12:00:00Z
 * +%s). */
static void test_times(void **state)
{
    (void)state;
    res_t r;
    sw_csv_opts_t o = infer_opts();
    /* Android's uptime in ns, named so */
    run("uptimeNanos,x,y,z\n36000000000000,0.1,0,9.8\n36000010000000,-0.2,0,9.8\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.unit[0], SW_CSV_UNIT_NS);
    assert_int_equal(r.lay.unit_from[0], SW_CSV_FROM_HEADER);
    assert_true(fabs(r.t[1] - r.t[0] - 0.01) < 1e-9);
    run("Time (ns);Acceleration (g)\n0;0\n2500000;1\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_true(r.t[1] == 0.0025);
    /* an epoch in ms named "timestamp": its unit from its magnitude */
    run("timestamp,accel_x\n1716206400000,0.1\n1716206400010,0.2\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.unit[0], SW_CSV_UNIT_MS);
    assert_int_equal(r.lay.unit_from[0], SW_CSV_FROM_VALUES);
    assert_int_equal(r.lay.epoch, 1);
    assert_true(r.t[0] == 1716206400.0);
    assert_true(fabs(r.t[1] - 1716206400.01) < 1e-6);
    /* in ns, from Sensor Logger's "time" beside its "seconds_elapsed" */
    run("time,seconds_elapsed,z,y,x\n1716206400000000000,0,9.8,0,0.1\n"
        "1716206400010000000,0.01,9.8,0,0.2\n",
        &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[0], 1); /* the same resolution: the one with a unit */
    assert_int_equal(r.lay.col[1], 4);
    /* day-first date-times, decided by a day above 12 */
    run("Date/Time,Acceleration X (g)\n14/05/2016 11:17:09.000,0.1\n14/05/2016 11:17:09.010,0.2\n",
        &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.unit[0], SW_CSV_UNIT_DATETIME);
    assert_int_equal(r.lay.date_order, SW_CSV_DATE_DMY);
    assert_int_equal(r.lay.unit_from[0], SW_CSV_FROM_VALUES);
    assert_true(r.t[0] == 1463224629.0); /* date -u -d "2016-05-14 11:17:09" +%s */
    assert_true(fabs(r.t[1] - 1463224629.01) < 1e-6);
    run("Zeit;Beschl. [g]\n20.05.2024 12:00:00,000;0,1\n20.05.2024 12:00:00,010;0,2\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_true(r.t[0] == 1716206400.0);
    /* the date's '.' is not the decimal mark of the numbers beside it */
    run("Zeit;Beschl. [g]\n20.05.2024 12:00:00.000;0,1\n20.05.2024 12:00:00.010;-0,2\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.n, 2);
    assert_int_equal(r.lay.decimal_comma, 1);
    assert_true(r.a[1] == -0.2 * 9.80665);
    /* month first, decided the same way */
    run("Time,Accel (g)\n5/14/2016 1:17:09.000 PM,0.1\n5/14/2016 1:17:09.010 PM,0.2\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.date_order, SW_CSV_DATE_MDY);
    assert_true(r.t[0] == 1463231829.0); /* date -u -d "2016-05-14 13:17:09" +%s */
    /* undecidable: refused, the option named; given, read */
    const char *undecided =
        "Date,Accel (g)\n05/06/2024 12:00:00.000,0.1\n05/06/2024 12:00:00.010,0.2\n";
    run(undecided, &o, &r);
    assert_int_equal(r.rc, SW_EAMBIGUOUS);
    assert_non_null(strstr(r.msg, "--date-order dmy"));
    assert_int_equal(r.n, 0);
    assert_int_equal(r.lay.ready, 0); /* no layout is half given */
    /* a column of date-times is time, whatever its name */
    run("Aufgezeichnet;Beschl. [g]\n20.05.2024 12:00:00.000;0,1\n20.05.2024 12:00:00.010;0,2\n", &o,
        &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col_from[0], SW_CSV_FROM_HEADER);
    assert_true(r.t[0] == 1716206400.0);
    o.date_order = SW_CSV_DATE_DMY;
    run(undecided, &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.unit_from[0], SW_CSV_FROM_OPTION);
    assert_true(r.t[0] == 1717588800.0); /* 5 June: date -u -d "2024-06-05 12:00" +%s */
    o.date_order = SW_CSV_DATE_MDY;
    run(undecided, &o, &r);
    assert_true(r.t[0] == 1714996800.0); /* 6 May: date -u -d "2024-05-06 12:00" +%s */
    o = infer_opts();
    /* a date to the second beside an uptime in ns: the uptime */
    run("date,uptimeNanos,x\n"
        "2024-05-20 12:00:01,36000000000000,0.1\n"
        "2024-05-20 12:00:01,36000010000000,0.1\n"
        "2024-05-20 12:00:01,36000020000000,0.1\n",
        &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[0], 1);
    assert_int_equal(r.n, 3);
}

/* A time column whose name writes a unit of time not read here (minutes,
 * hours) was read in seconds by default, 60 or 3600 times too fast: a
 * confident wrong verdict.  Refused, --time-unit named; read as the
 * option says once it is given.  A bracket that is no unit of time
 * ("Time (UTC)") leaves the time read as before (an epoch by its
 * magnitude). */
static void test_time_unit_not_read(void **state)
{
    (void)state;
    res_t r;
    sw_csv_opts_t o = infer_opts();
    static const char *const minutes[] = {
        "Time (min),Accel (g)\n0.00,0.1\n0.01,0.2\n",
        "Zeit [h];Beschl. [g]\n0,000;0,1\n0,001;0,2\n",
        "elapsed_minutes,ax\n0.00,0.1\n0.01,0.2\n",
        "Temps (heures),Acceleration X (g)\n0.00,0.1\n0.01,0.2\n",
    };
    for (size_t i = 0; i < sizeof minutes / sizeof minutes[0]; i++) {
        run(minutes[i], &o, &r);
        if (r.rc == SW_OK)
            fail_msg("%s: read, its time in %s", minutes[i],
                     r.lay.unit_from[0] == SW_CSV_FROM_DEFAULT ? "s by default" : "some unit");
        assert_non_null(strstr(r.msg, "--time-unit"));
        assert_int_equal(r.n, 0);
        assert_int_equal(r.lay.ready, 0);
    }
    /* seconds of the day: "day" is no unit here */
    run("time_of_day,ax\n43200.00,0.1\n43200.01,0.2\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.n, 2);
    /* the option says what the values are */
    o.time_scale = 1.0;
    run(minutes[0], &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.n, 2);
    assert_int_equal(r.lay.unit_from[0], SW_CSV_FROM_OPTION);
    o = infer_opts();
    /* "(UTC)" is no unit of time: an epoch in s by its magnitude */
    run("Time (UTC),ax\n1716206400.00,0.1\n1716206400.01,0.2\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.epoch, 1);
    assert_true(r.t[0] == 1716206400.0);
    /* nor is a minimum among the acceleration's columns a time: it is an
     * acceleration in g beside another (refused as such, as before) */
    run("Time (s),Accel X (g),Accel X [g] (min)\n0.00,0.1,0.0\n0.01,0.2,0.1\n", &o, &r);
    assert_int_equal(r.rc, SW_EAMBIGUOUS);
    assert_non_null(strstr(r.msg, "several columns could be the longitudinal acceleration"));
    o.accel_col = "2";
    run("Time (s),Accel X (g),Accel X [g] (min)\n0.00,0.1,0.0\n0.01,0.2,0.1\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[0], 0);
    assert_int_equal(r.lay.unit[0], SW_CSV_UNIT_S);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_three_axis_export),
        cmocka_unit_test(test_units_in_suffixes),
        cmocka_unit_test(test_can_export),
        cmocka_unit_test(test_datetimes),
        cmocka_unit_test(test_decimal_comma),
        cmocka_unit_test(test_ambiguous),
        cmocka_unit_test(test_option_against_header),
        cmocka_unit_test(test_units_not_accelerations),
        cmocka_unit_test(test_times),
        cmocka_unit_test(test_time_unit_not_read),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
