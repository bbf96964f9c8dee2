/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_flight.c - a package in free flight when the bed falls away faster
 * than gravity (physics.md, "Free flight"), against closed forms: the
 * landing map reduces to physics.md's impact maps (eta on the bed,
 * r_frame and the frame's momentum on a frame) and to the identity for a
 * landing on the corner it left; in the air theta turns at the rate it
 * left with; a level package lands when its centre of mass, a projectile
 * under -g_eff, is back at its height (by quadrature of the input, not
 * by the engine's polynomials); a short jolt keeps the rocking package's
 * overturn, a long flight leaves the verdict incomplete. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

static sw_derived_t derived(const sw_scene_t *sc)
{
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(sc, &d, NULL, NULL, NULL), SW_OK);
    return d;
}

/* Landing at theta = 0 on the front corner with the velocities of rocking
 * about the rear one (theta' > 0: top forward): physics.md's impact maps. */
static void test_landing_is_the_impact_map(void **state)
{
    (void)state;
    const sw_scene_t bare = tu_bare(2.0, 0.728), fr = tu_frame(2.0, 0.728, 250.0, 5.59, 0.1);
    const sw_derived_t db = derived(&bare), df = derived(&fr);
    const double w = 0.7, du = 0.13; /* rad/s, m/s */
    /* rocking about the rear corner (s = -1) at theta = 0: v_C = du + w (h, -b) */
    const double h = db.h, b = db.b;
    double du_after = NAN;
    tu_near(sw_landing_map(&db, 1, 0.0, w, w * h, -w * b, 0.0, NULL), db.eta * w, 1e-14);
    const double wp = sw_landing_map(&df, 1, 0.0, w, du + w * h, -w * b, du, &du_after);
    tu_near(wp, df.r_frame * w, 1e-14);
    tu_near(du_after, du + df.gamma * h * (w - wp), 1e-14);
    /* and physics.md's closed form of r_frame */
    const double s = sin(df.alpha), c = cos(df.alpha);
    tu_near(df.r_frame, 1.0 - 6.0 * s * s / (4.0 - 3.0 * df.gamma * c * c), 1e-15);
}

/* Landing on the corner it left, with the velocities of rocking about it
 * (a flight too short to change them): nothing changes. */
static void test_landing_on_its_corner(void **state)
{
    (void)state;
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 5.59, 0.1)};
    for (int m = 0; m < 2; m++) {
        const sw_derived_t d = derived(&sc[m]);
        const double du = m ? -0.21 : 0.0;
        for (int s = -1; s <= 1; s += 2)
            for (double th = 0.05; th < 1.5; th += 0.3)
                for (double w = -1.0; w <= 1.0; w += 0.5) {
                    const double A = d.alpha - th; /* s theta = th */
                    const double rx = -s * d.R * sin(A), ry = d.R * cos(A);
                    double da = NAN;
                    const double wp =
                        sw_landing_map(&d, s, s * th, w, du + w * ry, -w * rx, du, &da);
                    tu_near(wp, w, 1e-13);
                    tu_near(da, du, 1e-13);
                }
    }
}

/* An engine on the block, with the samples pushed through it. */
static sw_engine_t *engine(const sw_scene_t *sc, tu_events_t *rec)
{
    sw_engine_opts_t o = {0};
    o.on_event = rec ? tu_on_event : NULL;
    o.user = rec;
    sw_engine_t *e = sw_engine_create(sc, 1, &o, NULL, NULL, 0);
    assert_non_null(e);
    return e;
}

/* a_z (m/s^2, up) of the test's jolt: 0, a linear ramp over 1 ms to
 * depth, held to t_end, back over 1 ms. */
static double jolt(double t, double t_start, double t_end, double depth)
{
    if (t <= t_start || t >= t_end + 1e-3)
        return 0.0;
    if (t < t_start + 1e-3)
        return depth * (t - t_start) / 1e-3;
    if (t <= t_end)
        return depth;
    return depth * (t_end + 1e-3 - t) / 1e-3;
}

/* A rocking block in the air turns at the rate it left with: theta is
 * linear in time and theta' constant from the instant g_eff falls to 0
 * (where the input's ramp crosses -g: a closed form) to the landing. */
static void test_ballistic_rotation(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    tu_events_t *rec = calloc(1, sizeof *rec);
    sw_engine_t *e = engine(&sc, rec);
    const double G = sc.g, depth = -1.5 * G; /* m/s^2 */
    sw_engine_push(e, 0.0, 0.0, 0.0);
    sw_state_t st = {.theta = 0.1, .theta_dot = 0.4, .phase = SW_PHASE_ROCKING, .side = 1};
    assert_int_equal(sw_engine_set_state(e, 0, &st), SW_OK);
    /* the take-off: the ramp from 0 to depth over [0.010, 0.011] crosses
     * -g at 0.010 + 1e-3 g / |depth| */
    const double t_off = 0.010 + 1e-3 * G / -depth;
    double th_off = NAN, w_off = NAN;
    int in_air = 0;
    for (int i = 1; i <= 400; i++) {
        const double t = i * 1e-3;
        sw_engine_push(e, t, 0.0, jolt(t, 0.010, 0.015, depth));
        sw_output_t o;
        sw_engine_get_output(e, 0, &o);
        if (t < t_off)
            continue;
        if (!in_air) {
            /* the first sample in the air: from here theta' is frozen */
            in_air = 1;
            w_off = o.state.theta_dot;
            th_off = o.state.theta - w_off * (t - t_off);
            assert_int_equal(tu_count(rec, SW_EV_IMPACT), 0);
        }
        if (tu_count(rec, SW_EV_IMPACT) > 0)
            break; /* landed */
        tu_near(o.state.theta_dot, w_off, 0.0);
        tu_near(o.state.theta, th_off + w_off * (t - t_off), 1e-12);
    }
    assert_true(in_air);
    const sw_event_t *land = tu_first(rec, SW_EV_IMPACT);
    assert_non_null(land);
    assert_true(land->t > 0.015);    /* g_eff stays <= 0 until then */
    tu_near(land->info, w_off, 0.0); /* the rate it landed with */
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_int_equal(s.flights, 1);
    assert_int_equal(s.faults, 0);
    tu_near(s.flight_max, land->t - t_off, 1e-9);
    assert_true(isnan(s.flight_long_time));
    sw_engine_destroy(e);
    free(rec);
}

/* A level block standing on the bed, no a_g: it rises straight up and
 * lands level (a rest) when its centre of mass, y'' = -g_eff relative to
 * the bed, is back at height h.  The landing time by quadrature of the
 * input (trapezoids of 1e-7 s), against the engine's REST event. */
static void test_level_landing_time(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    tu_events_t *rec = calloc(1, sizeof *rec);
    sw_engine_t *e = engine(&sc, rec);
    const double G = sc.g, depth = -1.5 * G, t0 = 0.100, t1 = 0.130; /* m/s^2, s */
    for (int i = 0; i <= 400; i++) {
        const double t = i * 1e-3;
        sw_engine_push(e, t, 0.0, jolt(t, t0, t1, depth));
    }
    /* quadrature: from the take-off (g_eff = 0 on the ramp) */
    const double t_off = t0 + 1e-3 * G / -depth, dt = 1e-7;
    double v = 0.0, y = 0.0, t = t_off, t_land = NAN; /* m/s, m, s */
    for (int k = 0; k < 10000000; k++) {
        const double ga = G + jolt(t, t0, t1, depth), gb = G + jolt(t + dt, t0, t1, depth);
        const double v1 = v - 0.5 * (ga + gb) * dt;
        const double y1 = y + 0.5 * (v + v1) * dt;
        if (k > 10 && y1 <= 0.0) {
            t_land = t + dt * y / (y - y1);
            break;
        }
        v = v1;
        y = y1;
        t += dt;
    }
    assert_false(isnan(t_land));
    const sw_event_t *rest = tu_first(rec, SW_EV_REST);
    assert_non_null(rest);
    print_message("level flight: take-off %.6f s, landing %.9f s, quadrature %.9f s\n", t_off,
                  rest->t, t_land);
    tu_near(rest->t, t_land, 1e-7);
    const sw_event_t *up = tu_first(rec, SW_EV_UPLIFT);
    assert_non_null(up);
    tu_near(up->t, t_off, 1e-12);
    assert_true(up->info == 0.0); /* a level base leaves with no direction */
    sw_summary_t s;
    sw_engine_summary(e, 0, &s);
    assert_int_equal(s.flights, 1);
    assert_int_equal(s.faults, 0);
    assert_int_equal(s.impacts, 0);
    sw_output_t o;
    sw_engine_get_output(e, 0, &o);
    assert_int_equal(o.state.phase, SW_PHASE_STUCK);
    sw_engine_destroy(e);
    free(rec);
}

/* The drive of sample_logs/hard-stop-overturn.csv's kind: a braking
 * step that overturns the crate; with and without a jolt of one sample
 * (a_z = -12 m/s^2 at 1 ms, the bed falling faster than gravity for a
 * third of a millisecond) while it rocks.  It used to fault and reset
 * the crate to rest (no verdict); a short flight keeps its momentum: it
 * overturns as without the jolt. */
static void test_short_jolt_keeps_the_overturn(void **state)
{
    (void)state;
    const sw_scene_t sc[2] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 5.59, 0.1)};
    for (int m = 0; m < 2; m++) {
        sw_summary_t s[2];
        for (int k = 0; k < 2; k++) {
            sw_engine_t *e = engine(&sc[m], NULL);
            for (int i = 0; i <= 6000; i++) {
                const double t = i * 1e-3;
                const double ag = t >= 1.0 && t < 1.8 ? -0.9 * 9.81 : 0.0; /* m/s^2 */
                sw_engine_push(e, t, ag, k && i == 1500 ? -12.0 : 0.0);
            }
            sw_engine_finish(e, 10.0);
            sw_engine_summary(e, 0, &s[k]);
            sw_engine_destroy(e);
        }
        print_message("%s: overturn %.6f s, with the jolt %.6f s (%ld flights, %.3g s)\n",
                      m ? "frame" : "bare", s[0].overturn_time, s[1].overturn_time, s[1].flights,
                      s[1].flight_max);
        assert_true(s[0].overturned && s[1].overturned);
        assert_int_equal(s[1].faults, 0);
        assert_int_equal(s[1].flights, 1);
        assert_true(s[0].uplift_time < 1.5 && s[0].overturn_time > 1.5); /* rocking then */
        assert_true(s[1].flight_max < SW_FLIGHT_LONG);
        assert_true(isnan(s[1].flight_long_time));
        /* on the bed it lands 3.7 ms later, hardly changed; on the frame the
         * crate turns so fast then (theta'^2 R cos(alpha - |theta|) = 9.7
         * m/s^2, about g) that its corner, once free, rises away from the
         * frame for 75 ms, and it overturns 13 ms later than without */
        tu_near(s[1].overturn_time, s[0].overturn_time, m ? 0.05 : 1e-3);
    }
}

/* A flight longer than SW_FLIGHT_LONG leaves the verdict incomplete (its
 * start recorded) and is said once, as SW_EV_FLIGHT when it has lasted
 * SW_FLIGHT_LONG (a monitor raises its alarm then, in the air); on a
 * cushion, whose equations run on in the air, the same. */
static void test_long_flight(void **state)
{
    (void)state;
    const sw_scene_t sc[3] = {tu_bare(2.0, 0.728), tu_frame(2.0, 0.728, 250.0, 5.59, 0.1),
                              tu_cushion(tu_bare(2.0, 0.728), 44.72, 0.05)};
    for (int m = 0; m < 3; m++) {
        tu_events_t *rec = calloc(1, sizeof *rec);
        assert_non_null(rec);
        sw_engine_t *e = engine(&sc[m], rec);
        for (int i = 0; i <= 3000; i++) {
            const double t = i * 1e-3;
            sw_engine_push(e, t, 0.0, jolt(t, 1.0, 1.2, -2.0 * 9.81));
        }
        assert_int_equal(tu_count(rec, SW_EV_FLIGHT), 1);
        const sw_event_t *fl = tu_first(rec, SW_EV_FLIGHT);
        tu_near(fl->info, 1.0 + 1e-3 / 2.0, 1e-9);               /* began */
        tu_near(fl->t, 1.0 + 1e-3 / 2.0 + SW_FLIGHT_LONG, 1e-9); /* said */
        free(rec);
        sw_summary_t s;
        sw_engine_summary(e, 0, &s);
        print_message("%s: %ld flights, longest %.4f s, from %.4f s\n", sw_model_name(s.model),
                      s.flights, s.flight_max, s.flight_long_time);
        assert_int_equal(s.faults, 0);
        assert_true(s.flights >= 1);
        assert_true(s.flight_max > SW_FLIGHT_LONG);
        tu_near(s.flight_long_time, 1.0 + 1e-3 / 2.0, 1e-9); /* g_eff = 0 mid-ramp */
        sw_engine_destroy(e);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_landing_is_the_impact_map),
        cmocka_unit_test(test_landing_on_its_corner),
        cmocka_unit_test(test_ballistic_rotation),
        cmocka_unit_test(test_level_landing_time),
        cmocka_unit_test(test_short_jolt_keeps_the_overturn),
        cmocka_unit_test(test_long_flight),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
