/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_stability.c - the fixed-step schemes' stability regions against the
 * scenes' modes (scheme.h: sw_scheme_amplification, sw_scheme_stable_dt;
 * model.h: sw_model_modes), checked against closed forms: forward Euler's
 * region |1 + z| <= 1, Heun's |1 + z + z^2/2| <= 1, RK4's quartic; the edge
 * of each on a damped mode (Euler 2 zeta / omega; Heun the root of a
 * cubic; RK4 2 sqrt(2) on the imaginary axis and 2.7853 on the negative
 * real one); the modes of the frame and the cushion from their omega and
 * zeta.  Then the engine: a forced dt outside the region is refused with a
 * stable dt named, an unforced one is shortened inside it, and a chosen
 * scheme or dt runs the default beside it (sw_engine_checker). */
#include <complex.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>

#include "testutil.h"

static const sw_scheme_t *scheme(const char *name)
{
    const sw_scheme_t *s = sw_scheme_lookup(name);
    assert_non_null(s);
    return s;
}

/* The stability polynomials written out, complex arithmetic. */
static double ref_amp(int order, double complex z)
{
    switch (order) {
        case 1: return cabs(1.0 + z);
        case 2: return cabs(1.0 + z + z * z / 2.0);
        default: return cabs(1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0);
    }
}

static void test_amplification_closed_forms(void **state)
{
    (void)state;
    const char *names[3] = {"euler", "heun", "rk4"};
    const int order[3] = {1, 2, 4};
    for (int k = 0; k < 3; k++) {
        const sw_scheme_t *s = scheme(names[k]);
        for (double re = -3.5; re <= 1.0; re += 0.125)
            for (double im = -3.5; im <= 3.5; im += 0.125) {
                const double want = ref_amp(order[k], re + I * im);
                tu_near(sw_scheme_amplification(s, re, im), want, 1e-13 * fmax(1.0, want));
            }
    }
    /* the adaptive schemes have no region: their error control keeps them */
    assert_true(isnan(sw_scheme_amplification(scheme("rkck"), -1.0, 0.0)));
    assert_true(isnan(sw_scheme_amplification(NULL, -1.0, 0.0)));
}

/* One damped mode of natural frequency w (rad/s) and damping ratio z < 1. */
static sw_mode_t mode(double w, double z)
{
    return (sw_mode_t){.re = -z * w, .im = w * sqrt(1.0 - z * z), .omega = w, .zeta = z};
}

/* The smallest positive root of r^3 - 4 z r^2 + 8 z^2 r - 8 z = 0: where
 * |1 + z + z^2/2|^2 - 1 = 2 r c + 2 r^2 c^2 + r^3 c + r^4 / 4 (c = -zeta)
 * vanishes, i.e. Heun's edge on the mode's ray in units of omega. */
static double heun_edge(double z)
{
    double x[3];
    const int n = gsl_poly_solve_cubic(-4.0 * z, 8.0 * z * z, -8.0 * z, &x[0], &x[1], &x[2]);
    double r = INFINITY;
    for (int i = 0; i < n; i++)
        if (x[i] > 0.0)
            r = fmin(r, x[i]);
    return r;
}

static void test_stable_dt_closed_forms(void **state)
{
    (void)state;
    const sw_scheme_t *eu = scheme("euler"), *he = scheme("heun"), *rk = scheme("rk4");
    const double zetas[] = {0.01, 0.05, 0.1, 0.3, 0.7};
    for (size_t k = 0; k < sizeof zetas / sizeof zetas[0]; k++) {
        const double w = 44.72, z = zetas[k];
        const sw_mode_t m = mode(w, z);
        /* forward Euler: |1 + z|^2 = 1 - 2 zeta r + r^2, stable to r = 2 zeta */
        /* (to what the region allows for a growth of 1e-6 per period) */
        tu_near(sw_scheme_stable_dt(eu, &m, 1, NULL), 2.0 * z / w, 1e-6 / w);
        tu_near(sw_scheme_stable_dt(he, &m, 1, NULL), heun_edge(z) / w, 1e-5 * heun_edge(z) / w);
    }
    /* RK4: the imaginary axis to 2 sqrt(2) (|R(iy)|^2 = 1 - y^6/72 + y^8/576),
     * the negative real axis to the root of x^3 - 4 x^2 + 12 x - 24 = 0 */
    const sw_mode_t undamped = {.re = 0.0, .im = 10.0, .omega = 10.0, .zeta = 0.0};
    tu_near(sw_scheme_stable_dt(rk, &undamped, 1, NULL), 2.0 * sqrt(2.0) / 10.0, 1e-6);
    double x[3];
    assert_int_equal(gsl_poly_solve_cubic(-4.0, 12.0, -24.0, &x[0], &x[1], &x[2]), 1);
    const sw_mode_t real = {.re = -3.0, .im = 0.0, .omega = 3.0, .zeta = 1.0};
    tu_near(sw_scheme_stable_dt(rk, &real, 1, NULL), x[0] / 3.0, 1e-6);
    tu_near(sw_scheme_stable_dt(eu, &real, 1, NULL), 2.0 / 3.0, 1e-6);
    tu_near(sw_scheme_stable_dt(he, &real, 1, NULL), 2.0 / 3.0, 1e-6);
    /* an undamped mode: |R(iy)|^2 is 1 + y^2 for Euler, 1 + y^4/4 for Heun,
     * a growth of y^2/2 and y^4/8 a step, 2 pi / y steps a period; a growth
     * below 1e-6 a period counts as stable: for Euler y = 3e-7, below any
     * practical step (none), for Heun y = (8e-6 / (2 pi))^(1/3) = 0.0108 */
    assert_true(sw_scheme_stable_dt(eu, &undamped, 1, NULL) == 0.0);
    const double y = cbrt(8e-6 / (2.0 * M_PI)); /* rad per step */
    tu_near(sw_scheme_stable_dt(he, &undamped, 1, NULL), y / 10.0, 1e-3 * y / 10.0);
    /* several modes: the smallest, and which */
    const sw_mode_t two[2] = {mode(5.0, 0.1), mode(40.0, 0.05)};
    int worst = -1;
    tu_near(sw_scheme_stable_dt(eu, two, 2, &worst), 2.0 * 0.05 / 40.0, 1e-6 / 40.0);
    assert_int_equal(worst, 1);
    /* every step below the edge is stable, one 1 % beyond it is not */
    const double h = sw_scheme_stable_dt(he, &two[1], 1, NULL);
    for (double f = 0.01; f <= 1.0; f += 0.01)
        assert_true(ref_amp(2, f * h * (two[1].re + I * two[1].im)) <= 1.0 + 1e-9);
    assert_true(ref_amp(2, 1.01 * h * (two[1].re + I * two[1].im)) > 1.0);
    /* adaptive: no bound */
    assert_true(isinf(sw_scheme_stable_dt(scheme("rk8pd"), two, 2, NULL)));
}

/* The edge the way stability.c found it before it tried the 1 % grid in
 * blocks: every grid point r_k = r_{k-1} * 1.01 from 1e-4 in turn until
 * the first unstable one, then 60 bisections.  Its answer in units of
 * omega. */
static int grid_unstable(const sw_scheme_t *s, double r, double ure, double uim)
{
    return sw_scheme_amplification(s, r * ure, r * uim) > exp(1e-6 * r / (2.0 * M_PI));
}

static double every_point_edge(const sw_scheme_t *s, double ure, double uim)
{
    double lo = 0.0, hi = 0.0;
    for (double r = 1e-4; r < 8.0; r *= 1.01) {
        if (grid_unstable(s, r, ure, uim)) {
            hi = r;
            break;
        }
        lo = r;
    }
    if (!(hi > 0.0))
        return INFINITY;
    if (!(lo > 0.0))
        return 0.0;
    for (int k = 0; k < 60; k++) {
        const double mid = 0.5 * (lo + hi);
        if (grid_unstable(s, mid, ure, uim))
            hi = mid;
        else
            lo = mid;
    }
    return lo;
}

/* Trying the grid in blocks finds what trying every point finds, to the
 * bit: on modes of every damping ratio from 0 to 1 in steps of 0.001, at
 * frequencies from 0.37 to 3.3e5 rad/s (whose rounding moves the mode's
 * direction), made the way sw_model_modes makes them and with omega
 * given, under each scheme with a region.  A ray that left a region and
 * came back, or a block walked wrong at either end of the grid, would
 * differ. */
static void test_stable_dt_every_point(void **state)
{
    (void)state;
    const char *names[3] = {"euler", "heun", "rk4"};
    const double ws[] = {0.37, 5.59, 44.72, 3.3e5}; /* rad/s */
    long n = 0, zero = 0;
    for (int k = 0; k < 3; k++) {
        const sw_scheme_t *s = scheme(names[k]);
        for (int j = 0; j <= 1000; j++) {
            const double z = j / 1000.0;
            for (size_t i = 0; i < sizeof ws / sizeof ws[0]; i++) {
                const double w = ws[i], re = -z * w, im = w * sqrt(1.0 - z * z);
                const sw_mode_t m[2] = {
                    {.re = re, .im = im, .omega = hypot(re, im), .zeta = z},
                    mode(w, z),
                };
                for (int v = 0; v < 2; v++) {
                    const double want =
                        every_point_edge(s, m[v].re / m[v].omega, m[v].im / m[v].omega) /
                        m[v].omega;
                    const double got = sw_scheme_stable_dt(s, &m[v], 1, NULL);
                    if (got != want)
                        fail_msg("%s, zeta %g, omega %g: %.17g s, every point %.17g s", names[k], z,
                                 m[v].omega, got, want);
                    n++;
                    zero += want == 0.0;
                }
            }
        }
    }
    assert_int_equal(n, 3 * 1001 * 4 * 2);
    assert_int_equal(zero, 4 * 2); /* Euler undamped: the first grid point is unstable */
}

static sw_derived_t derived(const sw_scene_t *sc)
{
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(sc, &d, NULL, NULL, NULL), SW_OK);
    return d;
}

/* Is there a mode with this eigenvalue? */
static int has_mode(const sw_mode_t *m, int n, double re, double im, double tol)
{
    for (int i = 0; i < n; i++)
        if (fabs(m[i].re - re) <= tol && fabs(m[i].im - im) <= tol)
            return 1;
    return 0;
}

/* The modes from the scenes' derived groups: the rocking saddle's decaying
 * root -p (bare), the bearing mode -zeta_b w_b + i w_b sqrt(1 - zeta_b^2)
 * and, while rocking, the roots of D l^2 + 2 zeta_b w_b l + w_b^2 with
 * D = 1 - 3 gamma / 4 (frame), the cushion's vertical mode (no cubic term:
 * omega_c, zeta_c) and its rocking mode J l^2 + c_r l + k_r (bed). */
static void test_modes(void **state)
{
    (void)state;
    sw_mode_t m[SW_MODES_MAX];
    const sw_scene_t bare = tu_bare(2.0, 0.728);
    const sw_derived_t db = derived(&bare);
    assert_int_equal(sw_model_modes(&db, bare.g, m), 1);
    tu_near(m[0].re, -db.p, 1e-12);
    tu_near(m[0].im, 0.0, 0.0);

    const sw_scene_t fr = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    const sw_derived_t df = derived(&fr);
    const int nf = sw_model_modes(&df, fr.g, m);
    assert_int_equal(nf, 3);
    const double w = 5.59, z = 0.1, D = 1.0 - 0.75 * df.gamma;
    assert_true(has_mode(m, nf, -z * w, w * sqrt(1.0 - z * z), 1e-12));
    assert_true(has_mode(m, nf, -z * w / D, w * sqrt(D - z * z) / D, 1e-12));
    assert_true(has_mode(m, nf, -df.p / sqrt(D), 0.0, 1e-12));
    for (int i = 0; i < nf; i++) {
        tu_near(m[i].omega, hypot(m[i].re, m[i].im), 1e-12);
        tu_near(m[i].zeta, -m[i].re / m[i].omega, 1e-15);
        assert_non_null(m[i].name);
    }

    const sw_scene_t cu = tu_cushion(tu_bare(2.0, 0.728), 44.72, 0.05);
    const sw_derived_t dc = derived(&cu);
    const int nc = sw_model_modes(&dc, cu.g, m);
    assert_int_equal(nc, 2);
    assert_true(has_mode(m, nc, -0.05 * 44.72, 44.72 * sqrt(1.0 - 0.05 * 0.05), 1e-9));
    const double J = dc.R * dc.R / 3.0 + dc.h * dc.h, b2 = dc.b * dc.b / 3.0;
    const double kr = 44.72 * 44.72 * b2 - cu.g * dc.h, cr = 2.0 * 0.05 * 44.72 * b2;
    assert_true(has_mode(m, nc, -cr / (2.0 * J), sqrt(4.0 * J * kr - cr * cr) / (2.0 * J), 1e-9));
    /* on a frame: the quartic's roots, the fastest of which is omega_max */
    const sw_scene_t cf = tu_cushion(tu_frame(2.0, 0.728, 250.0, 5.59, 0.1), 100.0, 0.1);
    const sw_derived_t dcf = derived(&cf);
    const int ncf = sw_model_modes(&dcf, cf.g, m);
    assert_true(ncf >= 3);
    double fastest = 0.0;
    for (int i = 0; i < ncf; i++) fastest = fmax(fastest, m[i].omega);
    tu_near(fastest, dcf.omega_max, 1e-9 * dcf.omega_max);
    /* an overdamped vertical mode: two real roots, -w (z -+ sqrt(z^2 - 1)) */
    const sw_scene_t od = tu_cushion(tu_bare(2.0, 0.728), 100.0, 2.0);
    const sw_derived_t dod = derived(&od);
    const int nod = sw_model_modes(&dod, od.g, m);
    assert_true(has_mode(m, nod, -100.0 * (2.0 + sqrt(3.0)), 0.0, 1e-9));
    assert_true(has_mode(m, nod, -100.0 * (2.0 - sqrt(3.0)), 0.0, 1e-9));
}

static sw_engine_t *make(const sw_scene_t *sc, const char *scheme_name, double dt, int forced,
                         int check, int *err, char *msg, size_t msglen)
{
    sw_engine_opts_t o = {0};
    o.scheme = scheme_name;
    o.dt = dt;
    o.dt_forced = forced;
    o.check_default = check;
    return sw_engine_create(sc, 1, &o, err, msg, msglen);
}

/* A forced dt is refused just beyond the region's edge (Euler: 2 zeta /
 * omega of the cushion's vertical mode; the crate-on-cushion of the
 * sample logs: 2.24 ms), with the stable dt and the default scheme named,
 * and accepted just inside it; the refusal of the case (euler at
 * 5 ms, omega_c dt = 0.22) and of Heun at 40 ms.  Unforced, the step is
 * shortened to 0.9 of the edge and the engine says what was asked.  An
 * undamped bearing mode has no stable Euler step at all: refused, the
 * default scheme named. */
static void test_engine_refuses_or_shortens(void **state)
{
    (void)state;
    int err = 0;
    char msg[512];
    const sw_scene_t cu = tu_cushion(tu_bare(2.0, 0.728), 44.72, 0.05);
    const double edge = 2.0 * 0.05 / 44.72; /* s */
    sw_engine_t *e = make(&cu, "euler", 1.02 * edge, 1, 0, &err, msg, sizeof msg);
    assert_null(e);
    assert_int_equal(err, SW_EUNSTABLE);
    assert_non_null(strstr(msg, "vertical mode"));
    assert_non_null(strstr(msg, "use dt <= 0.00224 s"));
    assert_non_null(strstr(msg, "default scheme rk4"));
    e = make(&cu, "euler", 0.98 * edge, 1, 0, &err, msg, sizeof msg);
    assert_non_null(e);
    tu_near(sw_engine_dt(e, 0), 0.98 * edge, 1e-15);
    sw_engine_destroy(e);
    assert_null(make(&cu, "euler", 0.005, 1, 0, &err, msg, sizeof msg));
    assert_null(make(&cu, "heun", 0.04, 1, 0, &err, msg, sizeof msg));
    assert_int_equal(err, SW_EUNSTABLE);

    e = make(&cu, "euler", 0.005, 0, 0, &err, msg, sizeof msg);
    assert_non_null(e);
    assert_true(sw_engine_dt(e, 0) <= 0.9 * edge * (1.0 + 1e-4));
    tu_near(sw_engine_dt_requested(e), 0.005, 0.0);
    sw_engine_destroy(e);

    const sw_scene_t und = tu_frame(2.0, 0.728, 250.0, 5.59, 0.0);
    for (int forced = 0; forced < 2; forced++) {
        assert_null(make(&und, "euler", 1e-5, forced, 0, &err, msg, sizeof msg));
        assert_int_equal(err, SW_EUNSTABLE);
        assert_non_null(strstr(msg, "euler is unstable for its bearing mode"));
        assert_non_null(strstr(msg, "at every step: use the default scheme rk4"));
    }
    e = make(&und, "rk4", 1e-3, 1, 0, &err, msg, sizeof msg);
    assert_non_null(e);
    sw_engine_destroy(e);
}

/* The default beside a chosen scheme or dt: none when the choice is the
 * default (rk4 named without a dt, or the default dt forced), none unless
 * asked for, one otherwise, running the default scheme at its step.  Its
 * verdict on 1 s braking half-sines around the frame crate's boundary
 * (0.36 to 0.42 g) is that of a separate engine made with no scheme and
 * no dt on the same input, while the chosen Euler at 20 ms (inside the
 * bearings' region, 2 zeta_b / omega_b = 36 ms) runs beside it. */
static void test_checker(void **state)
{
    (void)state;
    int err = 0;
    char msg[512];
    const sw_scene_t fr = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    sw_engine_t *e = make(&fr, "rk4", 0.0, 0, 1, &err, msg, sizeof msg);
    assert_non_null(e);
    assert_null(sw_engine_checker(e));
    sw_engine_destroy(e);
    e = make(&fr, NULL, 1e-3, 1, 1, &err, msg, sizeof msg);
    assert_non_null(e);
    assert_null(sw_engine_checker(e));
    sw_engine_destroy(e);
    e = make(&fr, "euler", 0.0, 0, 0, &err, msg, sizeof msg);
    assert_null(sw_engine_checker(e)); /* not asked for */
    sw_engine_destroy(e);

    for (double x = 0.36; x <= 0.42; x += 0.01) {
        sw_pulse_t pl = {SW_PULSE_HALF_SINE, -x * SW_G0, M_PI};
        e = make(&fr, "euler", 0.02, 1, 1, &err, msg, sizeof msg);
        assert_non_null(e);
        const sw_engine_t *c = sw_engine_checker(e);
        assert_non_null(c);
        assert_string_equal(sw_engine_scheme(c), SW_DEFAULT_SCHEME);
        tu_near(sw_engine_dt(c, 0), SW_DEFAULT_DT, 0.0);
        sw_engine_t *d = make(&fr, NULL, 0.0, 0, 0, &err, msg, sizeof msg);
        for (int k = 1; k <= 100; k++) {
            assert_true(sw_engine_advance_fn(e, 0.1 * k, sw_pulse_eval, &pl) >= 0);
            assert_true(sw_engine_advance_fn(d, 0.1 * k, sw_pulse_eval, &pl) >= 0);
        }
        sw_summary_t sc, sd;
        assert_int_equal(sw_engine_summary(c, 0, &sc), SW_OK);
        assert_int_equal(sw_engine_summary(d, 0, &sd), SW_OK);
        assert_int_equal(sc.overturned, sd.overturned);
        assert_int_equal(sc.faults, sd.faults);
        if (sc.overturned)
            tu_near(sc.overturn_time, sd.overturn_time, 0.0);
        sw_engine_destroy(d);
        sw_engine_destroy(e);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_amplification_closed_forms),
        cmocka_unit_test(test_stable_dt_closed_forms),
        cmocka_unit_test(test_stable_dt_every_point),
        cmocka_unit_test(test_modes),
        cmocka_unit_test(test_engine_refuses_or_shortens),
        cmocka_unit_test(test_checker),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
