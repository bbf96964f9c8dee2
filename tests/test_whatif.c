/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_whatif.c - the what-if cases (whatif.h): which cases a scene gets,
 * the catalogue's supports as the paper's Table I and the makers'
 * frequencies give them (gamma = m / (m + m_b) = 0.8 for m_b = m/4,
 * omega = 2 pi f), the caller's supports and sizes, the notes of cases
 * that cannot be built, and the safety factors and reserves of the cases
 * against the same analyses run on each case's scene alone. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define MAX 32

static size_t cases(const sw_scene_t *sc, size_t n, const sw_whatif_opts_t *o, sw_whatif_case_t *cs)
{
    assert_true(sw_whatif_max(n, o) <= MAX);
    const size_t m = sw_whatif_cases(sc, n, o, cs);
    assert_true(m <= sw_whatif_max(n, o));
    return m;
}

/* A package on the bed: itself and the four supports of the catalogue. */
static void test_catalogue(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const sw_whatif_opts_t o = {0};
    static sw_whatif_case_t cs[MAX];
    size_t ns;
    const sw_support_t *S = sw_whatif_supports(&ns);
    assert_int_equal(ns, 4);
    assert_int_equal(cases(&sc, 1, &o, cs), 1 + ns);
    assert_string_equal(cs[0].name, "as given");
    assert_true(cs[0].is_scene && cs[0].built && cs[0].available);
    assert_int_equal(cs[0].model, SW_MODEL_BARE);
    for (size_t k = 0; k < ns; k++) {
        const sw_whatif_case_t *C = &cs[1 + k];
        assert_string_equal(C->name, S[k].name);
        assert_ptr_equal(C->stands_for, S[k].stands_for);
        assert_true(!C->is_scene && C->built && C->available);
        assert_int_equal(C->pkg, 0);
        assert_true(S[k].zeta == 0.1); /* Table I */
        if (S[k].cushion) {
            assert_int_equal(C->model, SW_MODEL_CUSHION);
            assert_false(C->scene.has_frame);
            tu_near(C->derived.omega_c, 2.0 * M_PI * S[k].hz, 1e-12);
            tu_near(C->derived.zeta_c, 0.1, 1e-12);
        } else {
            assert_int_equal(C->model, SW_MODEL_FRAME);
            tu_near(C->scene.frame_mass, 250.0, 1e-12);
            tu_near(C->derived.gamma, 0.8, 1e-12);
            tu_near(C->derived.omega_b, 2.0 * M_PI * S[k].hz, 1e-12);
            tu_near(C->derived.zeta_b, 0.1, 1e-12);
        }
    }
}

/* A package on a frame: the bed too, and its own frame's mass kept. */
static void test_on_frame(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 400.0, 6.0, 0.2);
    const sw_whatif_opts_t o = {0};
    static sw_whatif_case_t cs[MAX];
    assert_int_equal(cases(&sc, 1, &o, cs), 6);
    assert_string_equal(cs[1].name, "bed");
    assert_int_equal(cs[1].model, SW_MODEL_BARE);
    assert_string_equal(cs[2].name, "frame, soft bearings");
    tu_near(cs[2].scene.frame_mass, 400.0, 1e-12);
    tu_near(cs[2].derived.gamma, 1000.0 / 1400.0, 1e-12);
    tu_near(cs[2].derived.omega_b, 2.0 * M_PI, 1e-12);
    assert_string_equal(cs[4].name, "cushion, soft");
    assert_false(cs[4].scene.has_frame); /* a catalogue cushion stands on the bed */
}

/* The caller's frame and cushion replace the catalogue's; a cushion of
 * the caller stands on the scene's frame. */
static void test_own_supports(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_frame(2.0, 0.728, 400.0, 6.0, 0.2);
    const sw_whatif_opts_t o = {
        .frame_omega = 2.0 * M_PI * 3.0, .cushion_omega = 2.0 * M_PI * 30.0, .cushion_zeta = "0.3"};
    static sw_whatif_case_t cs[MAX];
    assert_int_equal(cases(&sc, 1, &o, cs), 4);
    assert_string_equal(cs[2].name, "frame");
    tu_near(cs[2].derived.omega_b, 2.0 * M_PI * 3.0, 1e-12);
    tu_near(cs[2].derived.zeta_b, 0.2, 1e-12); /* the scene's */
    assert_string_equal(cs[3].name, "cushion");
    assert_true(cs[3].scene.has_frame);
    tu_near(cs[3].derived.omega_c, 2.0 * M_PI * 30.0, 1e-12);
    tu_near(cs[3].derived.zeta_c, 0.3, 1e-12);
}

/* Cases that cannot be built are not available, and say which member of
 * the options would make them. */
static void test_notes(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    static sw_whatif_case_t cs[MAX];
    const sw_whatif_opts_t no_omega = {.frame_mass = "300"};
    size_t n = cases(&sc, 1, &no_omega, cs);
    assert_string_equal(cs[n - 1].name, "frame");
    assert_false(cs[n - 1].available || cs[n - 1].built);
    assert_non_null(strstr(cs[n - 1].note, "frame_omega"));
    const sw_whatif_opts_t bad = {.frame_omega = 10.0, .frame_zeta = "abc"};
    n = cases(&sc, 1, &bad, cs);
    assert_false(cs[n - 1].available);
    assert_memory_equal(cs[n - 1].note, "frame_zeta: ", 12);
    /* a cushion too soft to hold the package: refused by validation */
    const sw_whatif_opts_t soft = {.cushion_omega = 1.0};
    n = cases(&sc, 1, &soft, cs);
    assert_string_equal(cs[n - 1].name, "cushion");
    assert_false(cs[n - 1].available);
    assert_true(cs[n - 1].note[0] != '\0');
}

/* Other sizes on the scene's support; only the scenes when asked. */
static void test_sizes_and_scenes(void **state)
{
    (void)state;
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(1.2, 0.8, 300.0, 5.0, 0.1)};
    const double sizes[] = {1.5, 0.7, 3.0, 1.0};
    const sw_whatif_opts_t o = {.sizes = sizes, .nsizes = 2};
    static sw_whatif_case_t cs[MAX];
    const size_t n = cases(sc, 2, &o, cs);
    assert_int_equal(n, (1 + 4 + 2) + (2 + 4 + 2));
    assert_string_equal(cs[5].name, "size 1.5x0.7 m");
    tu_near(cs[5].scene.height, 1.5, 0.0);
    tu_near(cs[5].scene.width, 0.7, 0.0);
    assert_int_equal(cs[7].pkg, 1);
    assert_true(cs[7].is_scene);
    assert_true(cs[n - 1].scene.has_frame && cs[n - 1].pkg == 1);
    const sw_whatif_opts_t only = {.sizes = sizes, .nsizes = 2, .scenes_only = 1};
    assert_int_equal(cases(sc, 2, &only, cs), 2);
    assert_true(cs[0].is_scene && cs[1].is_scene && cs[1].pkg == 1);
}

#define N 4000 /* 4 s at 1 kHz */
static double t_[N], a_[N];

/* A braking half-sine of peak (m/s^2), 0.5 s long, at 1 s. */
static sw_log_t braking(double peak)
{
    for (size_t i = 0; i < N; i++) {
        const double t = i * 1e-3, u = t - 1.0;
        t_[i] = t;
        a_[i] = u >= 0.0 && u < 0.5 ? -peak * sin(M_PI * u / 0.5) : 0.0;
    }
    return (sw_log_t){.t = t_, .a_g = a_, .n = N};
}

/* Each case's safety factor is the one its scene has alone, on any
 * number of threads. */
static void test_safety(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const sw_whatif_opts_t o = {0};
    static sw_whatif_case_t cs[MAX];
    const size_t n = cases(&sc, 1, &o, cs);
    const sw_log_t L = braking(3.0);
    const sw_safety_opts_t so = {
        .run = {.settle = 3.0}, .search = {.x_max = 8.0, .step = 0.1, .tol = 0.01}, .threads = 2};
    assert_int_equal(sw_whatif_safety(cs, n, &L, &so), SW_OK);
    int found = 0;
    for (size_t i = 0; i < n; i++) {
        sw_safety_t one;
        char msg[256];
        assert_true(cs[i].available);
        assert_int_equal(
            sw_safety_factor(&cs[i].scene, &L, &so.run, &so.search, &one, msg, sizeof msg), SW_OK);
        assert_int_equal(cs[i].sf.found, one.found);
        assert_int_equal(cs[i].sf.trials, one.trials);
        if (one.found)
            assert_memory_equal(&cs[i].sf.factor, &one.factor, sizeof one.factor);
        found += one.found;
    }
    assert_true(found > 0);
}

/* Each case's smallest reserve is the one its scene has alone; the scene
 * as given is left to the caller (a replay has it). */
static void test_reserve(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    const sw_whatif_opts_t o = {0};
    static sw_whatif_case_t cs[MAX];
    const size_t n = cases(&sc, 1, &o, cs);
    const sw_log_t L = braking(2.0);
    const sw_reserve_log_opts_t ro = {.rate = 2.0, .max_evals = 3, .run = {.settle = 1.0}};
    assert_int_equal(sw_whatif_reserve(cs, n, &L, &ro, 2), SW_OK);
    assert_false(cs[0].has_reserve);
    for (size_t i = 1; i < n; i++) {
        sw_reserve_log_t one;
        char msg[160];
        const int rc = sw_reserve_log_min(&cs[i].scene, &L, &ro, &one, msg, sizeof msg);
        assert_int_equal(cs[i].reserve_status, rc);
        assert_int_equal(cs[i].has_reserve, rc == SW_OK);
        if (rc == SW_OK)
            assert_memory_equal(&cs[i].rl.min_g, &one.min_g, sizeof one.min_g);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_catalogue),        cmocka_unit_test(test_on_frame),
        cmocka_unit_test(test_own_supports),     cmocka_unit_test(test_notes),
        cmocka_unit_test(test_sizes_and_scenes), cmocka_unit_test(test_safety),
        cmocka_unit_test(test_reserve),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
