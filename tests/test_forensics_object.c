/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_forensics_object.c - the library's forensics object (forensics.h),
 * its family of boundary curves (boundary.h) and its cost estimates
 * (cost.h): the held log against the samples pushed (its cap, its
 * restarts, its vertical channel), the log run again against the same
 * samples pushed by hand, the cases against sw_whatif_cases(); the
 * family's size as the product the header promises and its labels; the
 * estimate of a fixed step from the documented cost per step. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

static sw_forensics_opts_t opts(size_t max)
{
    sw_forensics_opts_t o;
    memset(&o, 0, sizeof o);
    o.max_samples = max;
    o.whatif.scenes_only = 1;
    return o;
}

/* Three samples held, the fourth refused, and every one after it. */
static void test_cap(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const sw_forensics_opts_t o = opts(3);
    sw_forensics_t *F = sw_forensics_create(&sc, 1, &o, NULL);
    assert_non_null(F);
    for (int i = 0; i < 3; i++)
        assert_int_equal(sw_forensics_push(F, 0.01 * i, 1.0, 0.0, 0), SW_OK);
    assert_int_equal(sw_forensics_push(F, 0.03, 1.0, 0.0, 0), SW_ETOOBIG);
    assert_int_equal(sw_forensics_push(F, 0.04, 1.0, 0.0, 0), SW_ETOOBIG);
    assert_int_equal(sw_forensics_status(F), SW_ETOOBIG);
    const sw_log_t *L = sw_forensics_log(F);
    assert_int_equal(L->n, 3);
    assert_null(L->a_z); /* no vertical channel */
    assert_true(L->t[2] == 0.02);
    sw_forensics_destroy(F);
}

/* A restart before the first sample is none; one later is the index of
 * the sample it comes before; a vertical value makes the channel. */
static void test_restarts(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const sw_forensics_opts_t o = opts(0);
    sw_forensics_t *F = sw_forensics_create(&sc, 1, &o, NULL);
    assert_non_null(F);
    for (int i = 0; i < 10000; i++) /* past the first growth */
        assert_int_equal(sw_forensics_push(F, 0.001 * i, 0.0, i == 7 ? 0.5 : 0.0, i == 0 || i == 5),
                         SW_OK);
    const sw_log_t *L = sw_forensics_log(F);
    assert_int_equal(L->n, 10000);
    assert_int_equal(L->nrestart, 1);
    assert_int_equal(L->restart[0], 5);
    assert_non_null(L->a_z);
    assert_true(L->a_z[7] == 0.5 && L->a_z[8] == 0.0);
    assert_true(L->t[9999] == 0.001 * 9999);
    sw_forensics_destroy(F);
}

/* The held log run again ends where the same samples pushed by hand end,
 * the restart at the same sample. */
static void test_rerun(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const sw_forensics_opts_t o = opts(0);
    sw_forensics_t *F = sw_forensics_create(&sc, 1, &o, NULL);
    sw_engine_t *a = tu_engine(&sc, "rk4", 1e-3, NULL), *b = tu_engine(&sc, "rk4", 1e-3, NULL);
    assert_true(F && a && b);
    for (int i = 0; i < 2000; i++) {
        const double t = 0.002 * i, ag = 6.0 * sin(6.0 * t); /* lifts the block */
        assert_int_equal(sw_forensics_push(F, t, ag, 0.0, i == 900), SW_OK);
        if (i == 900)
            sw_engine_restart(b);
        sw_engine_push(b, t, ag, 0.0);
    }
    sw_forensics_rerun(F, a, INFINITY, 0.0);
    sw_output_t oa, ob;
    assert_int_equal(sw_engine_get_output(a, 0, &oa), SW_OK);
    assert_int_equal(sw_engine_get_output(b, 0, &ob), SW_OK);
    assert_true(oa.t == ob.t);
    assert_memory_equal(&oa.state, &ob.state, sizeof oa.state);
    /* up to a time: the first sample after it is the last pushed */
    sw_engine_t *c = tu_engine(&sc, "rk4", 1e-3, NULL);
    sw_forensics_rerun(F, c, 1.0, 0.0);
    assert_int_equal(sw_engine_get_output(c, 0, &oa), SW_OK);
    tu_near(oa.t, 1.002, 1e-12);
    sw_engine_destroy(a);
    sw_engine_destroy(b);
    sw_engine_destroy(c);
    sw_forensics_destroy(F);
}

/* Both axes scaled together, closed form: a bare block of width w, depth
 * d and height H under a constant acceleration (a_x, a_y) from t = 0
 * overturns exactly when the scaled acceleration of one plane reaches
 * g tan(alpha) of that plane (beyond it the block only ever rocks further:
 * physics.md, scene 1), so the package's factor is the smaller of
 * (g w/H)/|a_x| and (g d/H)/|a_y|, and the plane that gives out first is
 * the one with the smaller.  The bracket must hold that value, within the
 * search's tolerance. */
static void factor_case(double ax, double ay, double want, sw_plane plane, int overturned)
{
    sw_scene_t sc = tu_bare(2.0, 1.0);
    sc.depth = 0.6;
    sw_forensics_opts_t o = opts(0);
    o.run.engine.scheme = "rk4";
    o.run.engine.dt = 1e-3;
    o.run.settle = 10.0;
    sw_forensics_t *F = sw_forensics_create(&sc, 1, &o, NULL);
    assert_non_null(F);
    for (int i = 0; i <= 500; i++) /* 5 s at 100 Hz */
        assert_int_equal(sw_forensics_push_lat(F, 0.01 * i, ax, ay, 0.0, 0), SW_OK);
    assert_non_null(sw_forensics_log_lat(F));
    assert_int_equal(sw_forensics_safety(F), SW_OK);
    sw_forensics_factor_t fx;
    assert_int_equal(sw_forensics_factor(F, 0, &fx), SW_OK);
    assert_int_equal(fx.planes, 2);
    assert_non_null(fx.lateral);
    assert_int_equal(fx.first, plane);
    assert_int_equal(fx.sf.overturned, overturned);
    assert_true(fx.sf.found);
    /* the bracket holds the closed form and is no wider than the tolerance */
    assert_true(fx.sf.factor_safe <= want * (1.0 + 1e-9));
    assert_true(fx.sf.factor >= want * (1.0 - 1e-9));
    assert_true(fx.sf.factor <= fx.sf.factor_safe * (1.0 + 2.5e-3));
    /* each plane's own search found its own closed form */
    const double g = sc.g;
    const double lx = g * (1.0 / 2.0) / fabs(ax), ly = g * (0.6 / 2.0) / fabs(ay);
    const sw_safety_t *L = &sw_forensics_scene_case(F, 0)->sf, *T = &fx.lateral->sf;
    assert_true(L->factor_safe <= lx * (1.0 + 1e-9) && L->factor >= lx * (1.0 - 1e-9));
    assert_true(T->factor_safe <= ly * (1.0 + 1e-9) && T->factor >= ly * (1.0 - 1e-9));
    assert_int_equal(fx.sf.trials, L->trials + T->trials);
    if (ax == 0.0) /* an axis that never moves it does not bound the search */
        assert_true(fx.sf.max_scale == T->max_scale && fx.sf.max_scale > 1.0);
    sw_forensics_destroy(F);
}

static void test_factor_both_axes(void **state)
{
    (void)state;
    const double g = tu_bare(2.0, 1.0).g;
    /* w/H = 0.5, d/H = 0.3 */
    factor_case(-3.0, -4.0, g * 0.3 / 4.0, SW_PLANE_LAT, 1); /* overturned, sideways */
    factor_case(-1.0, -1.2, g * 0.3 / 1.2, SW_PLANE_LAT, 0); /* survived; sideways first */
    factor_case(-2.0, 0.5, g * 0.5 / 2.0, SW_PLANE_LONG, 0); /* survived; forward first */
    factor_case(-6.0, 1.0, g * 0.5 / 6.0, SW_PLANE_LONG, 1); /* overturned forward */
    factor_case(0.0, -1.2, g * 0.3 / 1.2, SW_PLANE_LAT, 0);  /* nothing along the truck */
}

/* Without a lateral acceleration the factor is the scene case's, one
 * plane; a log cannot mix samples with and without a lateral value. */
static void test_factor_one_plane(void **state)
{
    (void)state;
    sw_scene_t sc = tu_bare(2.0, 1.0);
    sc.depth = 0.6;
    const sw_forensics_opts_t o = opts(0);
    sw_forensics_t *F = sw_forensics_create(&sc, 1, &o, NULL);
    assert_int_equal(sw_forensics_push(F, 0.0, -1.0, 0.0, 0), SW_OK);
    assert_int_equal(sw_forensics_push_lat(F, 0.01, -1.0, -1.0, 0.0, 0), SW_EINVAL);
    assert_int_equal(sw_forensics_log(F)->n, 1);
    assert_null(sw_forensics_log_lat(F));
    assert_null(sw_forensics_lateral_case(F, 0));
    sw_forensics_destroy(F);
    F = sw_forensics_create(&sc, 1, &o, NULL);
    assert_int_equal(sw_forensics_push_lat(F, 0.0, -1.0, -1.0, 0.0, 0), SW_OK);
    assert_int_equal(sw_forensics_push(F, 0.01, -1.0, 0.0, 0), SW_EINVAL);
    assert_non_null(sw_forensics_lateral_case(F, 0));
    sw_forensics_destroy(F);
}

/* The crate of the tests across: 2 m high, 1 m long, 0.3 m deep, with
 * the sizes 2 x 1 x 0.8 m and 2 x 0.5 m (the scene's depth) as what-ifs,
 * and 5 s of a steady a_y = -0.25 g at 100 Hz pushed. */
static const double across_sizes[] = {2.0, 1.0, 2.0, 0.5}, across_depths[] = {0.8, 0.0};

static sw_forensics_t *across_pushed(sw_scene_t *sc)
{
    *sc = tu_bare(2.0, 1.0);
    sc->depth = 0.3;
    sw_forensics_opts_t o = opts(0);
    o.whatif.scenes_only = 0;
    o.whatif.sizes = across_sizes;
    o.whatif.depths = across_depths;
    o.whatif.nsizes = 2;
    o.run.engine.scheme = "rk4";
    o.run.engine.dt = 1e-3;
    o.run.settle = 10.0;
    o.reserve_rate = 10.0;
    sw_forensics_t *F = sw_forensics_create(sc, 1, &o, NULL);
    assert_non_null(F);
    for (int i = 0; i <= 500; i++) /* 5 s at 100 Hz */
        assert_int_equal(sw_forensics_push_lat(F, 0.01 * i, 0.0, -0.25 * sc->g, 0.0, 0), SW_OK);
    return F;
}

/* What-if cases across the truck, closed form: a bare block of height H
 * and depth d under a constant lateral acceleration a_y overturns exactly
 * when a scale of it reaches g d / H (as above).  The scene (d = 0.3 m,
 * H = 2 m) overturns across the truck; a size of depth 0.8 m does not,
 * and its factor is (g 0.4)/|a_y|; a size that gives no depth keeps the
 * scene's.  Each case's lateral plane has its reserve computed. */
static void test_cases_across(void **state)
{
    (void)state;
    sw_scene_t sc;
    sw_forensics_t *F = across_pushed(&sc);
    const double ay = -0.25 * sc.g;
    assert_int_equal(sw_forensics_safety(F), SW_OK);
    assert_int_equal(sw_forensics_reserve(F, NULL), SW_OK);
    size_t n, nl;
    const sw_whatif_case_t *cs = sw_forensics_cases(F, &n);
    const sw_whatif_case_t *lat = sw_forensics_lateral_cases(F, &nl);
    assert_int_equal(nl, n);
    assert_true(n >= 3);
    const size_t at[] = {0, n - 2, n - 1}; /* as given first, the sizes last */
    assert_true(cs[0].is_scene);
    assert_string_equal(cs[n - 2].name, "size 2x1x0.8 m");
    assert_string_equal(cs[n - 1].name, "size 2x0.5 m");
    const double dd[] = {0.3, 0.8, 0.3};
    for (size_t j = 0; j < 3; j++) {
        const size_t i = at[j];
        const double depth = dd[j]; /* m, the case's */
        sw_forensics_factor_t x;
        assert_int_equal(sw_forensics_case_factor(F, i, &x), SW_OK);
        assert_int_equal(x.planes, 2);
        assert_ptr_equal(x.lateral, &lat[i]);
        assert_true(lat[i].scene.width == depth);         /* the plane over the case's depth */
        const double f = (depth / 2.0) * sc.g / fabs(ay); /* the closed form */
        assert_int_equal(x.first, SW_PLANE_LAT);
        assert_int_equal(x.sf.overturned, f < 1.0);
        assert_int_equal(x.worse, f < 1.0 ? SW_PLANE_LAT : SW_PLANE_LONG);
        assert_true(x.sf.found);
        assert_true(x.sf.factor_safe <= f * (1.0 + 1e-9) && x.sf.factor >= f * (1.0 - 1e-9));
        assert_false(cs[i].sf.overturned); /* nothing along the truck */
        assert_true(lat[i].has_reserve);
    }
    assert_int_equal(sw_forensics_case_factor(F, n, &(sw_forensics_factor_t){0}), SW_EINVAL);
    sw_forensics_destroy(F);
}

/* The what-if cases' smallest reserves, made while the searches run, are
 * what sw_reserve_log_min() gives each case's scene on the held log after
 * them; the scene as given is left to the replay (none here), on one
 * thread and on three. */
static void test_reserves_alongside(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    for (int threads = 1; threads <= 3; threads += 2) {
        sw_forensics_opts_t o = opts(0);
        o.whatif.scenes_only = 0;
        o.threads = threads;
        o.run.settle = 5.0;
        o.reserve_rate = 2.0;
        o.reserve_evals = 0; /* exact: every state */
        sw_forensics_t *F = sw_forensics_create(&sc, 1, &o, NULL);
        assert_non_null(F);
        for (int i = 0; i <= 800; i++) { /* 8 s at 100 Hz: a sway and a braking shock */
            const double t = 0.01 * i;
            const double a = 0.8 * sin(2.0 * M_PI * 1.3 * t) - (t >= 4.0 && t < 4.2 ? 5.0 : 0.0);
            assert_int_equal(sw_forensics_push(F, t, a, 0.0, 0), SW_OK);
        }
        assert_int_equal(sw_forensics_safety(F), SW_OK);
        assert_int_equal(sw_forensics_reserve(F, NULL), SW_OK);
        size_t n;
        const sw_whatif_case_t *cs = sw_forensics_cases(F, &n);
        assert_true(n >= 3);
        const sw_reserve_log_opts_t rlo = {.rate = 2.0, .max_evals = 0, .run = o.run};
        int seen = 0;
        for (size_t i = 0; i < n; i++) {
            if (cs[i].is_scene || !cs[i].available) {
                assert_false(cs[i].has_reserve);
                continue;
            }
            sw_reserve_log_t rl;
            char note[160] = "";
            assert_int_equal(
                sw_reserve_log_min(&cs[i].scene, sw_forensics_log(F), &rlo, &rl, note, sizeof note),
                SW_OK);
            assert_true(cs[i].has_reserve);
            assert_int_equal(cs[i].reserve_status, SW_OK);
            assert_memory_equal(&cs[i].rl.min_g, &rl.min_g, sizeof rl.min_g);
            assert_memory_equal(&cs[i].rl.min_time, &rl.min_time, sizeof rl.min_time);
            assert_int_equal(cs[i].rl.evaluated, rl.evaluated);
            seen++;
        }
        assert_true(seen >= 2);
        sw_forensics_destroy(F);
    }
}

/* A case's verdict in both planes, against the same closed form: a bare
 * block of height H = 2 m and depth d under a constant lateral
 * acceleration of 0.25 g overturns across the truck when d / H < 0.25,
 * and nothing happens along it.  The scene (d = 0.3 m) and the size that
 * keeps its depth overturn across, which decides their verdict; the size
 * of depth 0.8 m stays upright and would have saved it.  Its smallest
 * reserve is the lateral plane's: both planes stand at rest, and a block
 * standing on a narrower base (0.8 m across, 1 m along) tips at a smaller
 * pulse.  Before the search across, no case has a verdict. */
static void test_case_verdict(void **state)
{
    (void)state;
    sw_scene_t sc;
    sw_forensics_t *F = across_pushed(&sc);
    size_t n, nl;
    sw_whatif_case_t *cs = sw_forensics_cases(F, &n);
    const sw_whatif_case_t *lat = sw_forensics_lateral_cases(F, &nl);
    assert_true(n >= 3);
    const size_t at[] = {0, n - 2, n - 1}; /* as given first, the sizes last */
    assert_string_equal(cs[n - 2].name, "size 2x1x0.8 m");
    sw_forensics_verdict_t v;
    for (size_t j = 0; j < 3; j++) { /* searched along, not yet across: no verdict */
        const size_t i = at[j];
        assert_int_equal(sw_forensics_case_verdict(F, i, &v), SW_OK);
        assert_int_equal(v.planes, 2);
        assert_false(v.judged || v.upright || v.saves);
        assert_int_equal(v.unjudged, SW_PLANE_LAT);
        assert_string_equal(v.note, lat[i].note);
        assert_null(v.run);
    }
    assert_int_equal(sw_forensics_safety(F), SW_OK);
    assert_int_equal(sw_forensics_reserve(F, NULL), SW_OK);
    const int upright[] = {0, 1, 0}; /* as given, 2x1x0.8, 2x0.5 (d = 0.3) */
    for (size_t j = 0; j < 3; j++) {
        const size_t i = at[j];
        assert_int_equal(sw_forensics_case_verdict(F, i, &v), SW_OK);
        assert_true(v.judged);
        assert_int_equal(v.factor.planes, 2);
        assert_int_equal(v.upright, upright[j]);
        assert_int_equal(v.saves, upright[j] && j > 0);
        assert_ptr_equal(v.run, upright[j] ? &cs[i] : &lat[i]);
        assert_int_equal(v.run->sf.at_one.overturned, !upright[j]);
    }
    long trials = 0; /* every search's, as each case's factor counts its planes' */
    for (size_t i = 0; i < n; i++) {
        assert_int_equal(sw_forensics_case_verdict(F, i, &v), SW_OK);
        trials += cs[i].available ? v.factor.sf.trials : 0;
        trials += v.factor.planes < 2 && lat[i].available ? lat[i].sf.trials : 0;
    }
    assert_true(trials > 0);
    assert_int_equal(sw_forensics_trials(F), trials);
    /* the reserve: the narrower base's; a plane without one leaves none */
    const size_t k = n - 2;
    assert_true(cs[k].has_reserve && lat[k].has_reserve);
    assert_true(lat[k].rl.min_g < cs[k].rl.min_g);
    sw_forensics_case_verdict(F, k, &v);
    assert_ptr_equal(v.reserve, &lat[k]);
    cs[k].has_reserve = 0; /* none, without a reason: the other plane's */
    sw_forensics_case_verdict(F, k, &v);
    assert_ptr_equal(v.reserve, &lat[k]);
    snprintf(cs[k].reserve_note, sizeof cs[k].reserve_note, "too stiff");
    sw_forensics_case_verdict(F, k, &v);
    assert_ptr_equal(v.reserve, &cs[k]);
    assert_int_equal(sw_forensics_case_verdict(F, n, &v), SW_EINVAL);
    sw_forensics_destroy(F);
}

/* A support of the catalogue applies across the truck too (the scene's
 * lateral bearings dropped); the scene as given keeps its own. */
static void test_cases_support_across(void **state)
{
    (void)state;
    sw_scene_t sc = tu_frame(2.0, 1.0, 250.0, 6.0, 0.1);
    sc.depth = 0.6;
    sc.frame_lat_omega = 3.0; /* rad/s */
    sc.frame_lat_k_given = SW_GIVEN_RATIO;
    sw_forensics_opts_t o = opts(0);
    o.whatif.scenes_only = 0;
    sw_forensics_t *F = sw_forensics_create(&sc, 1, &o, NULL);
    assert_non_null(F);
    assert_int_equal(sw_forensics_push_lat(F, 0.0, 0.0, 0.0, 0.0, 0), SW_OK);
    size_t n, nl;
    const sw_whatif_case_t *cs = sw_forensics_cases(F, &n);
    const sw_whatif_case_t *lat = sw_forensics_lateral_cases(F, &nl);
    int seen = 0;
    for (size_t i = 0; i < n; i++) {
        if (cs[i].is_scene) {
            assert_true(fabs(lat[i].derived.omega_b - 3.0) < 1e-12);
            seen |= 1;
        } else if (!strcmp(cs[i].name, "frame, soft bearings")) {
            assert_true(fabs(lat[i].derived.omega_b - 2.0 * M_PI * 1.0) < 1e-12);
            assert_true(fabs(cs[i].derived.omega_b - lat[i].derived.omega_b) < 1e-12);
            seen |= 2;
        }
    }
    assert_int_equal(seen, 3);
    sw_forensics_destroy(F);
}

/* The cases are sw_whatif_cases()'s; each package's as given is found. */
static void test_cases(void **state)
{
    (void)state;
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 6.0, 0.1)};
    sw_forensics_opts_t o = opts(0);
    o.whatif.scenes_only = 0;
    sw_forensics_t *F = sw_forensics_create(sc, 2, &o, NULL);
    assert_non_null(F);
    static sw_whatif_case_t ref[64];
    assert_true(sw_whatif_max(2, &o.whatif) <= 64);
    const size_t m = sw_whatif_cases(sc, 2, &o.whatif, ref);
    size_t n;
    const sw_whatif_case_t *cs = sw_forensics_cases(F, &n);
    assert_int_equal(n, m);
    for (size_t i = 0; i < n; i++) {
        assert_string_equal(cs[i].name, ref[i].name);
        assert_int_equal(cs[i].pkg, ref[i].pkg);
    }
    for (size_t k = 0; k < 2; k++) {
        const sw_whatif_case_t *C = sw_forensics_scene_case(F, k);
        assert_non_null(C);
        assert_true(C->is_scene && C->pkg == k);
    }
    assert_null(sw_forensics_scene_case(F, 2));
    sw_forensics_destroy(F);
}

/* A framed scene x 3 x 2 values x 2 ratios, and a bare one the frame's
 * key and the ratios do not apply to (x 2): 12 + 2 curves, labelled in
 * that order, the first key fastest. */
static void test_family(void **state)
{
    (void)state;
    sw_scene_t sc[2] = {tu_frame(2.0, 0.728, 250.0, 6.0, 0.1), tu_bare(2.0, 0.728)};
    snprintf(sc[0].name, sizeof sc[0].name, "framed");
    const char *const zeta[] = {"0.05", "0.1", "0.2"}, *const height[] = {"2", "3"};
    const sw_vary_t v[2] = {{"frame.zeta", zeta, 3}, {"package.height", height, 2}};
    const double bear[2] = {0.5, 2.0};
    const char *const bear_text[2] = {"1/2", "2"};
    size_t framed = 0;
    assert_int_equal(sw_family_count(sc, 2, v, 2, 2, &framed), 14);
    assert_int_equal(framed, 1);
    sw_family_curve_t fc[14];
    sw_family_fail_t fail;
    assert_int_equal(sw_family_build(sc, 2, v, 2, bear, bear_text, 2, fc, NULL, NULL, &fail),
                     SW_OK);
    assert_string_equal(fc[0].label, "framed frame.zeta=0.05 package.height=2 wb/we=1/2");
    assert_string_equal(fc[1].label, "framed frame.zeta=0.05 package.height=2 wb/we=2");
    assert_string_equal(fc[2].label, "framed frame.zeta=0.1 package.height=2 wb/we=1/2");
    assert_string_equal(fc[11].label, "framed frame.zeta=0.2 package.height=3 wb/we=2");
    assert_string_equal(fc[13].label, "block package.height=3");
    tu_near(fc[11].c.scene.frame_zeta, 0.2, 0);
    tu_near(fc[11].c.scene.height, 3.0, 0);
    tu_near(fc[1].c.bearing_ratio, 2.0, 0);
    assert_true(fc[13].c.bearing_ratio == 0.0);
    /* the units: p = sqrt(3 g / (4 R)) of a block of half-diagonal R on the bed */
    const double R = 0.5 * sqrt(3.0 * 3.0 + 0.728 * 0.728);
    tu_near(fc[13].p, sqrt(3.0 * sc[1].g / (4.0 * R)), 1e-12);
    tu_near(fc[13].gtan, sc[1].g * 0.728 / 3.0, 1e-12);
    /* a refused value: where */
    const char *const bad[] = {"0.1", "x"};
    const sw_vary_t w = {"frame.zeta", bad, 2};
    assert_int_not_equal(sw_family_build(sc, 1, &w, 1, NULL, NULL, 0, fc, NULL, NULL, &fail),
                         SW_OK);
    assert_int_equal(fail.curve, 1);
    assert_int_equal(fail.vary, 0);
    assert_int_equal(fail.value, 1);
}

/* A fixed explicit step: 1/dt steps a second at SW_COST_STEP_S each. */
static void test_cost(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    sw_engine_opts_t eo = {0};
    eo.scheme = "rk4";
    eo.dt = 1e-3;
    sw_scene_cost_t c;
    assert_int_equal(sw_scene_cost(&sc, &eo, &c), SW_OK);
    assert_string_equal(c.scheme, "rk4");
    tu_near(c.h, 1e-3, 1e-15);
    tu_near(c.steps, 1e3, 1e-9);
    tu_near(c.rt_factor, 1.0 / (1e3 * SW_COST_STEP_S), 1e-9);
    sw_scene_t bad = sc;
    bad.height = -1.0;
    assert_int_equal(sw_scene_cost(&bad, &eo, &c), SW_EINVAL);
    assert_true(sw_reserve_eval_cost(&bad) == 0.0);
    assert_true(sw_reserve_eval_cost(&sc) > 0.0);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cap),
        cmocka_unit_test(test_restarts),
        cmocka_unit_test(test_rerun),
        cmocka_unit_test(test_cases),
        cmocka_unit_test(test_family),
        cmocka_unit_test(test_cost),
        cmocka_unit_test(test_factor_both_axes),
        cmocka_unit_test(test_factor_one_plane),
        cmocka_unit_test(test_cases_across),
        cmocka_unit_test(test_reserves_alongside),
        cmocka_unit_test(test_cases_support_across),
        cmocka_unit_test(test_case_verdict),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
