/* SPDX-License-Identifier: GPL-3.0-or-later */
/* near.h - a double-precision closeness assertion for the cmocka tests.
 * cmocka's assert_float_equal() converts its arguments to float, so a
 * tolerance finer than about 1e-7 relative asserts nothing; tu_near()
 * compares in double and prints both values on failure.  Include after
 * cmocka.h. */
#ifndef SW_NEAR_H
#define SW_NEAR_H

#include <math.h>

#ifdef cmocka_unit_test /* only where cmocka is */
static inline void tu_near_(double a, double b, double tol, const char *sa, const char *sb,
                            const char *file, int line)
{
    if (fabs(a - b) <= tol)
        return;
    print_error("%s = %.17g, %s = %.17g: |difference| %.3g > %.3g\n", sa, a, sb, b, fabs(a - b),
                tol);
    _fail(file, line);
}

/* |a - b| <= tol, in double precision (NaN never passes). */
#define tu_near(a, b, tol) tu_near_((a), (b), (tol), #a, #b, __FILE__, __LINE__)
#endif

#endif
