/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_csv_lateral.c - the lateral acceleration column of a CSV log:
 * found by its header's name as real exports write it ("Lateral Gs",
 * "Y (g)", "ay", "accelerometerAccelerationY(G)"), or given by name or
 * index; in its own unit, else the longitudinal column's; flipped on
 * request; refused when several columns fit and it is asked for; said
 * but not read when it is not asked for.  Expected values are the text's
 * numbers times the unit (1 g = 9.80665 m/s^2). */
/* cmocka.h needs these first */
/* clang-format off */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
/* clang-format on */

#include "near.h"
#include "swaywatch/csv.h"
#include "swaywatch/status.h"
#include "swaywatch/units.h"

#define MAXROWS 8

typedef struct {
    sw_csv_t *c;
    int n, rejected;
    double a[MAXROWS], y[MAXROWS];
    char reason[256];
    int rc;
    char msg[400];
    sw_csv_layout_t lay;
} res_t;

static int on_row(void *user, long line, double t, double a, double z)
{
    (void)line;
    (void)t;
    (void)z;
    res_t *r = user;
    if (r->n < MAXROWS) {
        r->a[r->n] = a;
        r->y[r->n] = sw_csv_lateral(r->c);
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

static void run(const char *text, const sw_csv_opts_t *o, res_t *r)
{
    memset(r, 0, sizeof *r);
    int err = 0;
    char msg[256];
    r->c = sw_csv_create(o, on_row, on_reject, r, &err, msg, sizeof msg);
    assert_non_null(r->c);
    r->rc = sw_csv_feed(r->c, text, strlen(text));
    if (r->rc == SW_OK)
        r->rc = sw_csv_finish(r->c);
    snprintf(r->msg, sizeof r->msg, "%s", sw_csv_error_message(r->c));
    assert_int_equal(sw_csv_layout(r->c, &r->lay), SW_OK);
    sw_csv_destroy(r->c);
}

static sw_csv_opts_t opts(int lateral)
{
    sw_csv_opts_t o;
    memset(&o, 0, sizeof o);
    o.header = -1;
    o.infer = 1;
    o.decimal_comma = -1;
    o.lateral = lateral;
    return o;
}

/* The names real exports give the lateral axis, beside a longitudinal one. */
static void test_names_of_exports(void **state)
{
    (void)state;
    static const struct {
        const char *text;
        long col;     /* 0-based */
        double scale; /* m/s^2 per unit */
    } cases[] = {
        {"Time (s),Longitudinal Gs,Lateral Gs,Vertical Gs\n0,0.1,0.25,1\n0.01,0.1,0.5,1\n", 2,
         SW_G0},
        {"Time (ms),X (g),Y (g),Z (g)\n0,0.1,0.25,1\n10,0.1,0.5,1\n", 2, SW_G0},
        {"t,ax,ay,az\n0,0.1,0.25,9.8\n0.01,0.1,0.5,9.8\n", 2, 1.0},
        {"loggingTime(txt),accelerometerAccelerationX(G),accelerometerAccelerationY(G),"
         "accelerometerAccelerationZ(G)\n"
         "0,0.1,0.25,1\n0.01,0.1,0.5,1\n",
         2, SW_G0},
        /* the lateral one before the longitudinal one */
        {"time,Y (g),X (g)\n0,0.25,0.1\n0.01,0.5,0.1\n", 1, SW_G0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        res_t r;
        sw_csv_opts_t o = opts(1);
        run(cases[i].text, &o, &r);
        if (r.rc != SW_OK)
            fail_msg("case %zu: %s", i, r.msg);
        assert_int_equal(r.lay.col[3], cases[i].col);
        assert_int_equal(r.lay.col_from[3], SW_CSV_FROM_HEADER);
        assert_int_equal(r.n, 2);
        tu_near(r.y[0], 0.25 * cases[i].scale, 1e-12);
        tu_near(r.y[1], 0.5 * cases[i].scale, 1e-12);
        tu_near(r.a[0], 0.1 * cases[i].scale, 1e-12); /* the longitudinal one unchanged */
    }
}

/* The lateral column's unit: its own name's, else the longitudinal
 * column's, else the unit given for both. */
static void test_units(void **state)
{
    (void)state;
    res_t r;
    sw_csv_opts_t o = opts(1);
    run("t,X (m/s^2),Lateral Gs\n0,1,0.5\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    tu_near(r.a[0], 1.0, 0);
    tu_near(r.y[0], 0.5 * SW_G0, 1e-12);
    run("t,ax (g),ay\n0,0.1,0.5\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    tu_near(r.y[0], 0.5 * SW_G0, 1e-12);
    assert_int_equal(r.lay.unit[3], SW_CSV_UNIT_G);
    o.accel_scale = 1.0; /* --accel-unit m/s2 over both names */
    run("t,ax (g),ay (g)\n0,0.1,0.5\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    tu_near(r.y[0], 0.5, 0);
    assert_int_equal(r.lay.unit_from[3], SW_CSV_FROM_OPTION);
}

/* Given by name or index, flipped; a bad lateral value refuses its row
 * with the column named; --lat-col without lateral is a misuse. */
static void test_given_and_flipped(void **state)
{
    (void)state;
    res_t r;
    sw_csv_opts_t o = opts(1);
    o.lat_col = "sway";
    o.flip_lat = 1;
    run("t,a,sway\n0,1,2\n0.01,1,x\n0.02,1,3\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[3], 2);
    assert_int_equal(r.lay.col_from[3], SW_CSV_FROM_OPTION);
    assert_int_equal(r.n, 2);
    tu_near(r.y[0], -2.0, 0);
    tu_near(r.y[1], -3.0, 0);
    assert_int_equal(r.rejected, 1);
    assert_non_null(strstr(r.reason, "lateral (column 3"));
    o.lat_col = "3";
    o.flip_lat = 0;
    run("0,1,2\n0.01,1,4\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    tu_near(r.y[1], 4.0, 0);
    o.lat_col = "2"; /* the longitudinal column's */
    int err = 0;
    char msg[256];
    sw_csv_t *c = sw_csv_create(&o, on_row, on_reject, &r, &err, msg, sizeof msg);
    assert_null(c);
    assert_int_equal(err, SW_EINVAL);
    o = opts(0);
    o.lat_col = "3";
    c = sw_csv_create(&o, on_row, on_reject, &r, &err, msg, sizeof msg);
    assert_null(c);
    assert_int_equal(err, SW_EINVAL);
}

/* Several candidates: refused when asked for, naming them; not asked
 * for, the log reads as before.  One not asked for is said, not read. */
static void test_ambiguous_and_unread(void **state)
{
    (void)state;
    res_t r;
    sw_csv_opts_t o = opts(1);
    const char *two = "t,X (g),Y (g),Lateral Gs\n0,0.1,0.2,0.3\n";
    run(two, &o, &r);
    assert_int_equal(r.rc, SW_EAMBIGUOUS);
    assert_non_null(strstr(r.msg, "lateral acceleration"));
    assert_non_null(strstr(r.msg, "--lat-col"));
    o = opts(0);
    run(two, &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[3], -1);
    assert_int_equal(r.lay.lat_unread, -1);
    run("t,X (g),Y (g)\n0,0.1,0.2\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[3], -1);
    assert_int_equal(r.lay.lat_unread, 2);
    assert_string_equal(r.lay.name[3], "Y (g)");
    assert_true(isnan(r.y[0]));
    /* none: no lateral column, the log is read as before */
    o = opts(1);
    run("t,X (g),Z (g),Lateral (deg)\n0,0.1,1,3\n", &o, &r);
    assert_int_equal(r.rc, SW_OK);
    assert_int_equal(r.lay.col[3], -1);
    assert_true(isnan(r.y[0]));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_names_of_exports),
        cmocka_unit_test(test_units),
        cmocka_unit_test(test_given_and_flipped),
        cmocka_unit_test(test_ambiguous_and_unread),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
