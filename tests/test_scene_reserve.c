/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_scene_reserve.c - the [alarm] keys of the reserve: design_pulse (a
 * list of durations), warn_reserve_g and critical_reserve_g; their
 * defaults, parsing, --set overrides, validation messages, and
 * sw_scene_equal() telling every one of them apart. */
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
#include <gsl/gsl_errno.h>

#include "swaywatch/scene.h"
#include "swaywatch/status.h"

typedef struct {
    int n;
    int line[16];
    char msg[16][512];
} diags_t;

static void collect(void *user, const char *origin, int line, const char *msg)
{
    (void)origin;
    diags_t *d = user;
    if (d->n >= 16)
        return;
    d->line[d->n] = line;
    snprintf(d->msg[d->n], sizeof d->msg[0], "%s", msg);
    d->n++;
}

/* A diagnostic at line (-1: any) holding both texts. */
static int has_diag(const diags_t *d, int line, const char *a, const char *b)
{
    for (int i = 0; i < d->n; i++)
        if ((line < 0 || d->line[i] == line) && strstr(d->msg[i], a) &&
            (!b || strstr(d->msg[i], b)))
            return 1;
    return 0;
}

#define PKG "[package]\nheight = 2\nwidth = 0.728\nmass = 1000\n"

static int load(const char *text, sw_scene_t *sc, diags_t *dg)
{
    sw_scene_init(sc);
    memset(dg, 0, sizeof *dg);
    int rc = sw_scene_parse(sc, text, "crate.ini", collect, dg);
    if (rc == SW_OK)
        rc = sw_scene_validate(sc, NULL, "crate.ini", collect, dg);
    return rc;
}

static void test_defaults(void **state)
{
    (void)state;
    sw_scene_t sc;
    diags_t dg;
    assert_int_equal(load(PKG, &sc, &dg), SW_OK);
    assert_int_equal(sc.n_design_pulse, 1);
    assert_true(sc.design_pulse[0] == SW_DESIGN_PULSE_DEFAULT);
    assert_true(sc.warn_reserve_g == SW_WARN_RESERVE_G_DEFAULT);
    assert_true(sc.critical_reserve_g == SW_CRITICAL_RESERVE_G_DEFAULT);
    assert_true(SW_CRITICAL_RESERVE_G_DEFAULT < SW_WARN_RESERVE_G_DEFAULT);
}

static void test_parse_list(void **state)
{
    (void)state;
    sw_scene_t sc;
    diags_t dg;
    assert_int_equal(load(PKG "[alarm]\ndesign_pulse = 1.0, 0.08 ,2.5   # s\n"
                              "warn_reserve_g = 0.2\ncritical_reserve_g = 0.1\n",
                          &sc, &dg),
                     SW_OK);
    assert_int_equal(sc.n_design_pulse, 3);
    assert_true(sc.design_pulse[0] == 1.0 && sc.design_pulse[1] == 0.08 &&
                sc.design_pulse[2] == 2.5);
    assert_true(sc.warn_reserve_g == 0.2 && sc.critical_reserve_g == 0.1);
    /* an override replaces the whole list */
    assert_int_equal(sw_scene_set_arg(&sc, "alarm.design_pulse=0.5", collect, &dg), SW_OK);
    assert_int_equal(sc.n_design_pulse, 1);
    assert_true(sc.design_pulse[0] == 0.5 && sc.design_pulse[1] == 0.0);
    /* eight is the most */
    assert_int_equal(load(PKG "[alarm]\ndesign_pulse = 1,2,3,4,5,6,7,8\n", &sc, &dg), SW_OK);
    assert_int_equal(sc.n_design_pulse, SW_DESIGN_PULSES_MAX);
}

static void test_parse_errors(void **state)
{
    (void)state;
    sw_scene_t sc;
    diags_t dg;
    static const struct {
        const char *text, *a, *b;
        int line;
    } cases[] = {
        {PKG "[alarm]\ndesign_pulse = 1, two\n", "alarm.design_pulse", "item 2", 6},
        {PKG "[alarm]\ndesign_pulse = 1,\n", "alarm.design_pulse", "item 2", 6},
        {PKG "[alarm]\ndesign_pulse = 1,2,3,4,5,6,7,8,9\n", "alarm.design_pulse", "at most 8", 6},
        {PKG "[alarm]\ndesign_pulse = nan\n", "alarm.design_pulse", "not a finite number", 6},
        {PKG "[alarm]\ndesign_pulse = 1\ndesign_pulse = 2\n", "design_pulse given twice", NULL, 7},
        {PKG "[alarm]\nwarn_reserve_g = x\n", "alarm.warn_reserve_g", "in g", 6},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        assert_int_not_equal(load(cases[i].text, &sc, &dg), SW_OK);
        if (!has_diag(&dg, cases[i].line, cases[i].a, cases[i].b))
            fail_msg("case %zu: no diagnostic at line %d with \"%s\"", i, cases[i].line,
                     cases[i].a);
    }
}

/* Ranges: durations 1 ms to 60 s, levels from 0.001 to 10 g, critical below
 * warn; every problem is reported, at the [alarm] line. */
static void test_validation(void **state)
{
    (void)state;
    sw_scene_t sc;
    diags_t dg;
    static const struct {
        const char *text, *a, *b;
    } cases[] = {
        {PKG "[alarm]\ndesign_pulse = 0.0005\n", "design_pulse item 1", "between 0.001 and 60"},
        {PKG "[alarm]\ndesign_pulse = 1, 100\n", "design_pulse item 2", "between"},
        {PKG "[alarm]\ndesign_pulse = -1\n", "design_pulse item 1", NULL},
        {PKG "[alarm]\nwarn_reserve_g = 0\n", "alarm.warn_reserve_g = 0", "from 0.001 to 10"},
        {PKG "[alarm]\nwarn_reserve_g = 1e-320\n", "alarm.warn_reserve_g", "from 0.001 to 10"},
        {PKG "[alarm]\nwarn_reserve_g = 11\n", "alarm.warn_reserve_g = 11", NULL},
        {PKG "[alarm]\ncritical_reserve_g = -0.1\n", "alarm.critical_reserve_g", NULL},
        {PKG "[alarm]\nwarn_reserve_g = 0.1\ncritical_reserve_g = 0.1\n",
         "critical_reserve_g = 0.1 is not below", "warn_reserve_g = 0.1"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        assert_int_equal(load(cases[i].text, &sc, &dg), SW_EINVAL);
        if (!has_diag(&dg, 5, cases[i].a, cases[i].b))
            fail_msg("case %zu: no diagnostic at line 5 with \"%s\"", i, cases[i].a);
    }
    /* a list count out of range set from code */
    sw_scene_init(&sc);
    sc.height = 2;
    sc.width = 0.7;
    sc.mass = 100;
    sc.n_design_pulse = 0;
    memset(&dg, 0, sizeof dg);
    assert_int_equal(sw_scene_validate(&sc, NULL, "code", collect, &dg), SW_EINVAL);
    assert_true(has_diag(&dg, -1, "alarm.design_pulse has 0 durations", NULL));
}

/* sw_scene_equal() tells every new field apart, and ignores list entries
 * past the count. */
static void test_equal(void **state)
{
    (void)state;
    sw_scene_t a, b;
    diags_t dg;
    assert_int_equal(load(PKG "[alarm]\ndesign_pulse = 1, 0.5\n", &a, &dg), SW_OK);
    b = a;
    assert_true(sw_scene_equal(&a, &b));
    b.design_pulse[1] = 0.6;
    assert_false(sw_scene_equal(&a, &b));
    b = a;
    b.n_design_pulse = 1;
    assert_false(sw_scene_equal(&a, &b));
    b = a;
    b.design_pulse[5] = 3.0; /* past the count */
    assert_true(sw_scene_equal(&a, &b));
    b = a;
    b.warn_reserve_g = 0.3;
    assert_false(sw_scene_equal(&a, &b));
    b = a;
    b.critical_reserve_g = 0.01;
    assert_false(sw_scene_equal(&a, &b));
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),     cmocka_unit_test(test_parse_list),
        cmocka_unit_test(test_parse_errors), cmocka_unit_test(test_validation),
        cmocka_unit_test(test_equal),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
