/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_engine_replace.c - sw_engine_replace(), what a monitor uses when a
 * scene file changes under it: the other packages go on exactly as if
 * nothing happened (same numbers, bit for bit), the replaced one starts from
 * rest and then moves exactly like a fresh engine started at that instant,
 * and a scene that does not validate changes nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define N_SAMPLES 3001 /* 3 s at 1 kHz */
#define T_REPLACE 1000 /* sample index of the replacement (t = 1 s) */

/* Two braking half-sines (10 rad/s): -5 m/s^2 at t = 0, -6 m/s^2 at
 * t = 1 s, still bed in between and after. */
static double input(int i)
{
    const double t = i * 1e-3, w = 10.0;
    if (t < M_PI / w)
        return -5.0 * sin(w * t);
    if (t >= 1.0 && t < 1.0 + M_PI / w)
        return -6.0 * sin(w * (t - 1.0));
    return 0.0;
}

typedef struct {
    double theta[2][N_SAMPLES], theta_dot[2][N_SAMPLES];
    int phase[2][N_SAMPLES];
    int i; /* sample being pushed */
    size_t pkg_offset;
} trace_t;

static void on_state(void *user, const sw_output_t *o)
{
    trace_t *tr = user;
    const size_t k = o->pkg + tr->pkg_offset;
    if (tr->i < N_SAMPLES && k < 2) {
        tr->theta[k][tr->i] = o->state.theta;
        tr->theta_dot[k][tr->i] = o->state.theta_dot;
        tr->phase[k][tr->i] = o->state.phase;
    }
}

static sw_scene_t named(sw_scene_t sc, const char *name)
{
    snprintf(sc.name, sizeof sc.name, "%s", name);
    return sc;
}

/* B's new scene: on a frame (by default), or on a cushion. */
static sw_scene_t new_b(int cushion)
{
    if (!cushion)
        return named(tu_frame(2.0, 0.728, 250.0, 5.59, 0.1), "B2");
    sw_scene_t sc = named(tu_bare(2.0, 0.728), "B2");
    sc.has_cushion = 1;
    sc.cushion_stiffness = 2.0e6;
    sc.cushion_damping = 4.0e3;
    sc.cushion_cubic = 0.0;
    sc.cushion_k_given = sc.cushion_c_given = SW_GIVEN_DIMENSIONAL;
    return sc;
}

static void run_scheme(const char *scheme, int cushion)
{
    static trace_t ref, rep, fresh;
    const sw_scene_t scenes[2] = {named(tu_bare(2.0, 0.728), "A"), named(tu_bare(2.0, 0.728), "B")};
    /* B's new scene: the model (and the state's length) changes. */
    const sw_scene_t b2 = new_b(cushion);
    const sw_model_kind b2_model = cushion ? SW_MODEL_CUSHION : SW_MODEL_FRAME;
    sw_scene_t bad = named(tu_bare(2.0, 0.728), "bad");
    bad.height = -1.0;
    char msg[256];
    int err;

    memset(&ref, 0, sizeof ref);
    memset(&rep, 0, sizeof rep);
    memset(&fresh, 0, sizeof fresh);
    sw_engine_opts_t o = {.scheme = scheme, .on_state = on_state};

    o.user = &ref;
    sw_engine_t *R = sw_engine_create(scenes, 2, &o, &err, msg, sizeof msg);
    o.user = &rep;
    sw_engine_t *E = sw_engine_create(scenes, 2, &o, &err, msg, sizeof msg);
    o.user = &fresh;
    fresh.pkg_offset = 1; /* F's package 0 is B2: compare with E's package 1 */
    sw_engine_t *F = sw_engine_create(&b2, 1, &o, &err, msg, sizeof msg);
    assert_non_null(R);
    assert_non_null(E);
    assert_non_null(F);

    sw_summary_t before, after;
    for (int i = 0; i < N_SAMPLES; i++) {
        const double t = i * 1e-3;
        ref.i = rep.i = fresh.i = i;
        assert_true(sw_engine_push(R, t, input(i), 0.0) >= 0);
        assert_true(sw_engine_push(E, t, input(i), 0.0) >= 0);
        if (i >= T_REPLACE)
            assert_true(sw_engine_push(F, t, input(i), 0.0) >= 0);
        if (i == T_REPLACE) {
            /* A is still rocking from the first pulse, B too. */
            assert_int_equal(rep.phase[0][i], SW_PHASE_ROCKING);
            assert_int_equal(rep.phase[1][i], SW_PHASE_ROCKING);
            assert_int_equal(sw_engine_summary(E, 1, &before), SW_OK);

            /* A scene that does not validate: refused, nothing changes. */
            assert_int_equal(sw_engine_replace(E, 1, &bad, msg, sizeof msg), SW_EINVAL);
            assert_true(msg[0] != '\0');
            assert_int_equal(sw_engine_summary(E, 1, &after), SW_OK);
            assert_memory_equal(&before, &after, sizeof before);
            assert_int_equal(sw_engine_replace(E, 2, &b2, msg, sizeof msg), SW_EINVAL);

            assert_int_equal(sw_engine_replace(E, 1, &b2, msg, sizeof msg), SW_OK);
            sw_output_t out;
            assert_int_equal(sw_engine_get_output(E, 1, &out), SW_OK);
            if (!cushion)
                assert_int_equal(out.state.phase, SW_PHASE_STUCK);
            assert_true(out.state.theta == 0.0 && out.state.theta_dot == 0.0);
            assert_true(out.t == t);
            assert_int_equal(sw_engine_summary(E, 1, &after), SW_OK);
            assert_string_equal(after.name, "B2");
            assert_int_equal(after.model, b2_model);
            assert_int_equal(after.uplifts, 0);
            assert_int_equal(sw_engine_derived(E, 1)->model, b2_model);
        }
    }
    ref.i = N_SAMPLES; /* settling states are not traced */
    assert_int_equal(sw_engine_finish(R, 5.0) >= 0, 1);

    /* A: identical to the run without a replacement, every sample. */
    for (int i = 0; i < N_SAMPLES; i++) {
        assert_true(rep.theta[0][i] == ref.theta[0][i]);
        assert_true(rep.theta_dot[0][i] == ref.theta_dot[0][i]);
    }
    sw_summary_t sa_ref, sa_rep;
    assert_int_equal(sw_engine_summary(R, 0, &sa_ref), SW_OK);
    assert_int_equal(sw_engine_summary(E, 0, &sa_rep), SW_OK);
    assert_true(sa_rep.max_abs_theta == sa_ref.max_abs_theta);
    assert_int_equal(sa_rep.impacts <= sa_ref.impacts, 1); /* R settled longer */

    /* B2: as a fresh engine started at the replacement (E reported the old
     * B at that sample, before the replacement); it rocks again in the
     * second pulse. */
    int rocked = 0;
    for (int i = T_REPLACE + 1; i < N_SAMPLES; i++) {
        assert_true(fabs(rep.theta[1][i] - fresh.theta[1][i]) <= 1e-12);
        assert_int_equal(rep.phase[1][i], fresh.phase[1][i]);
        rocked |= rep.phase[1][i] == SW_PHASE_ROCKING;
    }
    assert_true(rocked);
    assert_int_equal(sw_engine_summary(E, 1, &after), SW_OK);
    assert_true(after.uplifts > 0);
    assert_true(isfinite(after.uplift_time) && after.uplift_time >= 1.0);

    sw_engine_destroy(R);
    sw_engine_destroy(E);
    sw_engine_destroy(F);
}

static void test_replace_rk4(void **state)
{
    (void)state;
    run_scheme("rk4", 0);
}

/* An adaptive scheme: the GSL work space moves with the package. */
static void test_replace_rkck(void **state)
{
    (void)state;
    run_scheme("rkck", 0);
}

/* An implicit one: its driver points back into the package. */
static void test_replace_cushion_implicit(void **state)
{
    (void)state;
    run_scheme("rk4imp", 1);
}

/* The engine's scheme is the engine's: beside a stiff cushion the default
 * is the adaptive rkck for every package, and a package rebuilt by a
 * reload gets rkck's work space too (it once got the rk4 that its scene
 * alone would get, and the first step after the reload crashed).  The new
 * package then moves as in a fresh engine of the same scenes. */
static void test_replace_beside_stiff_cushion(void **state)
{
    (void)state;
    static trace_t rep, fresh;
    sw_scene_t stiff = named(tu_bare(2.0, 0.728), "S");
    stiff.has_cushion = 1;
    stiff.cushion_omega = 300.0; /* rad/s: omega_max dt >> 0.05 at 1 ms */
    stiff.cushion_zeta = 0.05;
    stiff.cushion_cubic = 0.0;
    stiff.cushion_k_given = stiff.cushion_c_given = SW_GIVEN_RATIO;
    const sw_scene_t scenes[2] = {stiff, named(tu_bare(2.0, 0.728), "B")};
    const sw_scene_t changed[2] = {stiff, named(tu_bare(2.0, 0.6), "B2")};
    char msg[256];
    int err;
    memset(&rep, 0, sizeof rep);
    memset(&fresh, 0, sizeof fresh);
    sw_engine_opts_t o = {.on_state = on_state}; /* no scheme: the engine chooses */
    o.user = &rep;
    sw_engine_t *E = sw_engine_create(scenes, 2, &o, &err, msg, sizeof msg);
    o.user = &fresh;
    sw_engine_t *F = sw_engine_create(changed, 2, &o, &err, msg, sizeof msg);
    assert_non_null(E);
    assert_non_null(F);
    assert_string_equal(sw_engine_scheme(E), SW_STIFF_SCHEME);
    for (int i = 0; i < N_SAMPLES; i++) {
        const double t = i * 1e-3;
        rep.i = fresh.i = i;
        if (i == T_REPLACE)
            assert_int_equal(sw_engine_replace(E, 1, &changed[1], msg, sizeof msg), SW_OK);
        assert_true(sw_engine_push(E, t, input(i), 0.0) >= 0);
        if (i >= T_REPLACE)
            assert_true(sw_engine_push(F, t, input(i), 0.0) >= 0);
    }
    int rocked = 0;
    for (int i = T_REPLACE + 1; i < N_SAMPLES; i++) {
        assert_true(fabs(rep.theta[1][i] - fresh.theta[1][i]) <= 1e-12);
        assert_int_equal(rep.phase[1][i], fresh.phase[1][i]);
        rocked |= rep.phase[1][i] == SW_PHASE_ROCKING;
    }
    assert_true(rocked);
    sw_summary_t s;
    assert_int_equal(sw_engine_summary(E, 1, &s), SW_OK);
    assert_int_equal(s.faults, 0);
    assert_string_equal(s.name, "B2");
    sw_engine_destroy(E);
    sw_engine_destroy(F);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_replace_rk4),
        cmocka_unit_test(test_replace_rkck),
        cmocka_unit_test(test_replace_cushion_implicit),
        cmocka_unit_test(test_replace_beside_stiff_cushion),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
