/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_mon_limits.c - the monitor core refuses options whose values in
 * microseconds do not fit its int64 clock (a gap of 1e300 s, a state rate
 * of 1e-300 Hz) instead of overflowing. */
#include <stdio.h>
#include <string.h>

/* cmocka.h needs these before it. */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
// clang-format on

#include "monitor.h"
#include "swaywatch/swaywatch.h"

static const char *scene_text =
    "[package]\nname = crate-A\nheight = 2.0\nwidth = 0.728\nmass = 1000\n";

static sw_mon_t *create(double gap, double state_rate)
{
    static sw_scene_t sc;
    sw_scene_init(&sc);
    assert_int_equal(sw_scene_parse(&sc, scene_text, "test", NULL, NULL), SW_OK);
    assert_int_equal(sw_scene_validate(&sc, NULL, "test", NULL, NULL), SW_OK);
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    sw_mon_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.vertical = -1;
    mo.gap = gap;
    mo.state_rate = state_rate;
    char msg[256] = "";
    return sw_mon_create(&sc, 1, &eo, &mo, NULL, msg, sizeof msg);
}

static void test_limits(void **state)
{
    (void)state;
    sw_mon_t *m = create(0.1, 100.0);
    assert_non_null(m);
    sw_mon_destroy(m);
    assert_null(create(1e300, 0.0));
    assert_null(create(0.1, 1e-300));
    m = create(1e9, 1e-9); /* the largest that fit */
    assert_non_null(m);
    sw_mon_destroy(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_limits)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
