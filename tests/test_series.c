/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_series.c - a long series kept as the extremes of its stretches
 * (series.h), against what the samples themselves say: the smallest and
 * largest value of the whole series and when they came, a lone spike in
 * a long calm, stretches of equal length in time order, their number
 * between nbuckets and 2 nbuckets, a quantity that is none at first, and
 * the calls refused. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "swaywatch/series.h"
#include "swaywatch/status.h"

/* A sine of 7 Hz and a ramp, 100,003 samples at 1 kHz into 50 to 100
 * buckets: the extremes over every bucket are those of the samples, each
 * at the time of its first sample; the buckets cover equal runs of
 * samples (a power of two) in time order, the last one partly. */
static void test_extremes_kept(void **state)
{
    (void)state;
    const size_t N = 100003, nb = 50;
    sw_series_t *s = sw_series_create(2, nb);
    assert_non_null(s);
    double lo = INFINITY, hi = -INFINITY, tlo = NAN, thi = NAN;
    for (size_t i = 0; i < N; i++) {
        const double t = 1e-3 * (double)i;
        const double v[2] = {sin(2.0 * M_PI * 7.0 * t + 0.3), t};
        if (v[0] < lo) {
            lo = v[0];
            tlo = t;
        }
        if (v[0] > hi) {
            hi = v[0];
            thi = t;
        }
        sw_series_add(s, t, v);
    }
    const size_t n = sw_series_count(s);
    assert_true(n >= nb && n <= 2 * nb + 1);
    double got_lo = INFINITY, got_hi = -INFINITY, got_tlo = NAN, got_thi = NAN;
    /* samples per full bucket: the smallest power of two that puts N
     * samples in fewer than 2 nb full buckets */
    size_t w = 1;
    while (N / w >= 2 * nb) w *= 2;
    for (size_t i = 0; i < n; i++) {
        sw_extreme_t e, r;
        assert_int_equal(sw_series_get(s, i, 0, &e), SW_OK);
        assert_int_equal(sw_series_get(s, i, 1, &r), SW_OK);
        if (e.vmin < got_lo) {
            got_lo = e.vmin;
            got_tlo = e.tmin;
        }
        if (e.vmax > got_hi) {
            got_hi = e.vmax;
            got_thi = e.tmax;
        }
        /* the ramp: its stretch's first and last samples */
        const double t0 = 1e-3 * (double)(i * w);
        const double t1 = i + 1 < n ? 1e-3 * (double)((i + 1) * w - 1) : 1e-3 * (double)(N - 1);
        assert_true(fabs(r.vmin - t0) < 1e-12 && fabs(r.tmin - t0) < 1e-12);
        assert_true(fabs(r.vmax - t1) < 1e-12 && fabs(r.tmax - t1) < 1e-12);
    }
    assert_true(got_lo == lo && got_tlo == tlo);
    assert_true(got_hi == hi && got_thi == thi);
    sw_series_destroy(s);
}

/* One sample of 5 in a million of zeros survives every merge, at its
 * time; equal values keep the first time of their stretch. */
static void test_spike(void **state)
{
    (void)state;
    sw_series_t *s = sw_series_create(1, 8);
    assert_non_null(s);
    const size_t N = 1000000, at = 654321;
    for (size_t i = 0; i < N; i++) {
        const double v = i == at ? 5.0 : 0.0;
        sw_series_add(s, (double)i, &v);
    }
    int seen = 0;
    for (size_t i = 0; i < sw_series_count(s); i++) {
        sw_extreme_t e;
        sw_series_get(s, i, 0, &e);
        assert_true(e.vmin == 0.0);
        if (e.vmax == 5.0) {
            seen++;
            assert_true(e.tmax == (double)at);
        }
        assert_true(e.tmin <= e.tmax || e.vmax == 0.0);
    }
    assert_int_equal(seen, 1);
    sw_series_destroy(s);
}

/* A quantity that is none (NaN) for the first samples takes the first
 * value that is not; the other quantities are not held back. */
static void test_none_yet(void **state)
{
    (void)state;
    sw_series_t *s = sw_series_create(2, 1); /* a bucket, then 2 merged */
    assert_non_null(s);
    const double a[2] = {1.0, NAN}, b[2] = {3.0, 2.0}, c[2] = {-1.0, 4.0};
    sw_series_add(s, 0.0, a);
    sw_series_add(s, 1.0, b); /* two full buckets: merged into one of 2 samples */
    assert_int_equal(sw_series_count(s), 1);
    sw_extreme_t e;
    sw_series_get(s, 0, 1, &e);
    assert_true(e.vmin == 2.0 && e.tmin == 1.0 && e.vmax == 2.0 && e.tmax == 1.0);
    sw_series_get(s, 0, 0, &e);
    assert_true(e.vmin == 1.0 && e.tmin == 0.0 && e.vmax == 3.0 && e.tmax == 1.0);
    sw_series_add(s, 2.0, c); /* the bucket being filled: last */
    assert_int_equal(sw_series_count(s), 2);
    sw_series_get(s, 1, 0, &e);
    assert_true(e.vmin == -1.0 && e.tmin == 2.0);
    assert_int_equal(sw_series_get(s, 2, 0, &e), SW_EINVAL);
    assert_int_equal(sw_series_get(s, 0, 2, &e), SW_EINVAL);
    sw_series_destroy(s);
}

static void test_refused(void **state)
{
    (void)state;
    assert_null(sw_series_create(0, 10));
    assert_null(sw_series_create(3, 0));
    sw_series_t *s = sw_series_create(1, 4);
    assert_int_equal(sw_series_count(s), 0);
    sw_extreme_t e;
    assert_int_equal(sw_series_get(s, 0, 0, &e), SW_EINVAL);
    sw_series_destroy(s);
    sw_series_destroy(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_extremes_kept),
        cmocka_unit_test(test_spike),
        cmocka_unit_test(test_none_yet),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
