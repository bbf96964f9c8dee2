/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_keyset.c - batch's manifest lines grouped by their options
 * (src/cli/commands/keyset.c) in n log n comparisons, counted: a million lines
 * with 50,000 distinct sets (what did not start in two minutes when each
 * line searched the sets found so far) take at most 2 n log2 n, where
 * that search took about n x sets / 2 = 2.5e10.  The groups are checked
 * against a table built in one pass by the test itself. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "keyset.h"

#define N 1000000
#define SETS 50000

/* The options of line i: one of SETS sets, scrambled so that the first
 * line of a set is not its number; every 97th line has none (NULL). */
static long set_of(size_t i)
{
    return i % 97 == 0 ? -1 : (long)((i * 7919u) % SETS);
}

static void test_million_lines(void **state)
{
    (void)state;
    char **keys = calloc(N, sizeof *keys);
    size_t *first = calloc(N, sizeof *first);
    size_t *want = calloc(SETS + 1, sizeof *want);
    assert_non_null(keys);
    assert_non_null(first);
    assert_non_null(want);
    for (size_t k = 0; k <= SETS; k++) want[k] = SIZE_MAX;
    for (size_t i = 0; i < N; i++) {
        const long s = set_of(i);
        if (s >= 0) {
            char buf[96];
            snprintf(buf, sizeof buf,
                     "--scene\x1fscenes/s%05ld.ini\x1f--set\x1fpackage.mass=%ld\x1f", s, 100 + s);
            keys[i] = strdup(buf);
            assert_non_null(keys[i]);
        }
        const size_t slot = s >= 0 ? (size_t)s : SETS; /* SETS: the NULL key */
        if (want[slot] == SIZE_MAX)
            want[slot] = i;
    }
    long compares = 0;
    assert_int_equal(sw_cli_keyset_first((const char *const *)keys, N, first, &compares), 0);
    for (size_t i = 0; i < N; i++) {
        const long s = set_of(i);
        if (first[i] != want[s >= 0 ? (size_t)s : SETS])
            fail_msg("line %zu: first %zu, expected %zu", i, first[i], want[s >= 0 ? s : SETS]);
    }
    const double bound = 2.0 * N * log2((double)N);
    print_message("%d lines, %d sets: %ld comparisons (at most %.3g; a search per line: %.3g)\n", N,
                  SETS, compares, bound, (double)N * SETS / 2.0);
    assert_true(compares > 0 && (double)compares <= bound);
    for (size_t i = 0; i < N; i++) free(keys[i]);
    free(keys);
    free(first);
    free(want);
}

static void test_small_cases(void **state)
{
    (void)state;
    size_t first[6];
    long c = -1;
    assert_int_equal(sw_cli_keyset_first(NULL, 0, first, &c), 0);
    assert_int_equal(c, 0);
    const char *none[3] = {NULL, NULL, NULL};
    assert_int_equal(sw_cli_keyset_first(none, 3, first, NULL), 0);
    for (size_t i = 0; i < 3; i++) assert_int_equal(first[i], 0);
    const char *mixed[6] = {"b", NULL, "a", "b", "", NULL};
    assert_int_equal(sw_cli_keyset_first(mixed, 6, first, NULL), 0);
    const size_t want[6] = {0, 1, 2, 0, 4, 1};
    for (size_t i = 0; i < 6; i++) assert_int_equal(first[i], want[i]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_small_cases),
        cmocka_unit_test(test_million_lines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
