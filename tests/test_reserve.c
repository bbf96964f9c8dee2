/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_reserve.c - the reserve in g (reserve.h) against values it does
 * not compute itself: the published boundary table of the bare block
 * (rocking-anchors.md section 2.2), sw_boundary_point with its fine steps,
 * brute-force scans of sw_pulse_run_from (run.c's machinery, GSL
 * rk8pd where cheap enough) from rocking states, closed forms of the
 * energy bound, and the physics of a state that overturns with no input.
 * Also: safe islands above the lowest overturning amplitude, the merged
 * scan over directions and pulses, determinism, the rest cache and bad
 * arguments. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

static const double A20 = 20.0 * M_PI / 180.0; /* rad */
/* The reserve's runs (rk4 at 1/24 of the shortest period, rkck at rtol
 * 3e-4) against rk8pd at rtol 1e-10: an amplitude within this factor of
 * a threshold may be judged either way (docs/reserve.md, "Steps fit the
 * question"). */
#define RUN_SLACK 1.001

static sw_scene_t crate(void)
{
    return tu_bare(2.0, 2.0 * tan(A20));
}

static sw_scene_t crate_frame(void)
{
    return tu_frame(2.0, 2.0 * tan(A20), 250.0, 5.59, 0.1);
}

static sw_scene_t with_pulse(sw_scene_t sc, double T)
{
    sc.design_pulse[0] = T;
    sc.n_design_pulse = 1;
    return sc;
}

static sw_reserve_t *make(const sw_scene_t *sc, const sw_reserve_opts_t *o)
{
    int err = 0;
    char msg[256];
    sw_reserve_t *r = sw_reserve_create(sc, o, &err, msg, sizeof msg);
    if (!r)
        fail_msg("sw_reserve_create: %s (%s)", msg, sw_strerror(err));
    return r;
}

static sw_derived_t derived(const sw_scene_t *sc)
{
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(sc, &d, NULL, NULL, NULL), SW_OK);
    return d;
}

static sw_state_t rocking(double theta, double theta_dot)
{
    sw_state_t s;
    memset(&s, 0, sizeof s);
    s.phase = SW_PHASE_ROCKING;
    s.theta = theta;
    s.theta_dot = theta_dot;
    s.side = theta > 0.0 ? 1 : theta < 0.0 ? -1 : theta_dot >= 0.0 ? 1 : -1;
    return s;
}

/* Does a half-sine of amplitude x g in direction dir, duration T, overturn
 * the package from s?  run.c's runs, full free motion, rk8pd unless
 * scheme is given. */
static int overturns(const sw_scene_t *sc, const sw_state_t *s, int dir, double x, double T,
                     const char *scheme)
{
    sw_pulse_t pl = {SW_PULSE_HALF_SINE, dir * x * SW_G0, M_PI / T};
    sw_run_opts_t ro;
    memset(&ro, 0, sizeof ro);
    ro.engine.scheme = scheme ? scheme : "rk8pd";
    ro.engine.rtol = 1e-10;
    ro.engine.atol = 1e-12;
    sw_run_result_t r;
    char msg[256];
    const int rc = sw_pulse_run_from(sc, s, &pl, &ro, &r, msg, sizeof msg);
    if (rc != SW_OK)
        fail_msg("sw_pulse_run_from: %s", msg);
    return r.overturned;
}

/* The lowest overturning amplitude (g) on a geometric grid of relative
 * step 0.5 % from x0 up to x1, by brute force: 0 if none. */
static double brute_force(const sw_scene_t *sc, const sw_state_t *s, int dir, double T, double x0,
                          double x1, const char *scheme)
{
    for (double x = x0; x <= x1; x *= 1.005)
        if (overturns(sc, s, dir, x, T, scheme))
            return x;
    return 0.0;
}

/* ---- at rest: the boundary ---------------------------------------------------- */

/* rocking-anchors.md section 2.2: alpha = 0.25 rad, half-sine, the lowest
 * overturning a/(g tan alpha) by an independent RK4 code (1 % scan, then
 * bisection; 3 decimals).  The reserve at rest with T = pi/(k p) is that
 * boundary in g: its bracket [reserve_g, over_g] (1 % wide) must hold the
 * table's value, widened by the table's rounding. */
static void test_rest_published_table(void **state)
{
    (void)state;
    const sw_scene_t base = tu_bare(2.0, 2.0 * tan(0.25));
    const sw_derived_t d = derived(&base);
    const double unit = base.g * tan(d.alpha) / SW_G0; /* g per g tan(alpha) */
    static const struct {
        double ratio, x;
    } ref[] = {{1.0, 1.321}, {2.0, 1.801}, {3.0, 2.297}, {4.0, 2.798}, {6.0, 3.802}};
    for (size_t i = 0; i < sizeof ref / sizeof ref[0]; i++) {
        const sw_scene_t sc = with_pulse(base, M_PI / (ref[i].ratio * d.p));
        sw_reserve_t *r = make(&sc, NULL);
        sw_reserve_result_t res;
        sw_reserve_rest(r, &res);
        assert_true(res.found && res.cached);
        const double lo = res.reserve_g / unit, hi = res.over_g / unit;
        assert_true(res.safe_g == res.reserve_g);
        if (!(ref[i].x >= lo - 0.0006 && ref[i].x <= hi + 0.0006))
            fail_msg("omega/p = %g: table %.3f outside [%.5f, %.5f]", ref[i].ratio, ref[i].x, lo,
                     hi);
        assert_true(hi / lo - 1.0 <= 0.0101);
        /* mirror symmetric at rest: both directions alike */
        assert_true(res.dir_g[0] == res.dir_g[1]);
        sw_reserve_destroy(r);
    }
}

/* Frame and cushion at rest against sw_boundary_point (its own search, 400
 * steps per period, bracket 0.1 %): the two brackets overlap. */
static void check_rest_boundary(const sw_scene_t *sc, double T)
{
    const sw_derived_t d = derived(sc);
    const double unit = sc->g * tan(d.alpha) / SW_G0;
    sw_curve_t c;
    memset(&c, 0, sizeof c);
    c.scene = *sc;
    sw_boundary_opts_t bo;
    memset(&bo, 0, sizeof bo);
    bo.shape = SW_PULSE_HALF_SINE;
    sw_boundary_point_t bp;
    assert_int_equal(sw_boundary_point(&c, M_PI / T / d.p, &bo, &bp, NULL, 0), SW_OK);
    assert_true(bp.th.found);
    const sw_scene_t s2 = with_pulse(*sc, T);
    sw_reserve_t *r = make(&s2, NULL);
    sw_reserve_result_t res;
    sw_reserve_rest(r, &res);
    if (!(res.reserve_g <= bp.th.x * unit * 1.0005 && bp.th.x_safe * unit <= res.over_g * 1.0005))
        fail_msg("T = %g s: reserve [%.5f, %.5f] g, boundary [%.5f, %.5f] g", T, res.reserve_g,
                 res.over_g, bp.th.x_safe * unit, bp.th.x * unit);
    sw_reserve_destroy(r);
}

static void test_rest_boundary_models(void **state)
{
    (void)state;
    const sw_scene_t fr = crate_frame();
    check_rest_boundary(&fr, 1.0);
    check_rest_boundary(&fr, 0.3);
    const sw_scene_t cu = tu_cushion(crate(), 44.7, 0.045);
    check_rest_boundary(&cu, 1.0);
    const sw_scene_t cf = tu_cushion(crate_frame(), 100.0, 0.1);
    check_rest_boundary(&cf, 0.5);
}

/* ---- away from rest ---------------------------------------------------------- */

/* Away from rest the reserve is the lowest overturning amplitude a
 * brute-force scan finds (rk8pd, 0.5 % steps from the energy bound, below
 * which nothing overturns: test_energy_bound_holds), in each direction:
 * at most that (it is the safe end of its bracket; RUN_SLACK allows for
 * the integration error of the reserve's runs), and within the bracket's
 * width and the brute force's step of it; while it rocks it is smaller
 * than at rest. */
static void check_brute(const sw_scene_t *sc, const sw_state_t *s, double T, const char *scheme,
                        int smaller)
{
    sw_reserve_opts_t o;
    memset(&o, 0, sizeof o);
    o.each_direction = 1;
    const sw_scene_t sT = with_pulse(*sc, T);
    sw_reserve_t *r = make(&sT, &o);
    sw_reserve_result_t res, rest;
    assert_int_equal(sw_reserve_eval(r, s, &res), SW_OK);
    sw_reserve_rest(r, &rest);
    assert_false(res.cached);
    assert_true(res.found);
    if (smaller)
        assert_true(res.reserve_g < rest.reserve_g);
    const sw_derived_t d = derived(sc);
    const double bound = 0.99 * sw_reserve_energy_bound(&d, sc->g, s, T);
    for (int i = 0; i < 2; i++) {
        const int dir = i == 0 ? SW_RESERVE_BRAKING : SW_RESERVE_ACCELERATING;
        assert_true(res.dir_exact[i]);
        const double ref =
            brute_force(sc, s, dir, T, fmax(bound, 0.01), 1.02 * res.dir_g[i], scheme);
        if (!(ref > 0.0 && ref * RUN_SLACK >= res.dir_g[i] &&
              ref <= res.dir_g[i] * 1.0101 * 1.005 * RUN_SLACK))
            fail_msg("direction %d: reserve %.4f g (safe %.4f), brute force %.4f g", dir,
                     res.dir_g[i], res.safe_g, ref);
    }
    /* the smaller of the two, and its direction */
    const int di = res.direction == SW_RESERVE_BRAKING ? 0 : 1;
    assert_true(res.reserve_g == res.dir_g[di]);
    assert_true(res.reserve_g <= res.dir_g[1 - di]);
    sw_reserve_destroy(r);
}

static void test_rocking_bare(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    /* tipping forward, moving out; and moving in after a large swing */
    check_brute(
        &sc,
        &(sw_state_t){.theta = 0.4 * A20, .theta_dot = 0.1, .phase = SW_PHASE_ROCKING, .side = 1},
        1.0, NULL, 1);
    sw_state_t s = rocking(-0.5 * A20, 0.2);
    check_brute(&sc, &s, 1.0, NULL, 1);
}

static void test_rocking_frame(void **state)
{
    (void)state;
    const sw_scene_t sc = crate_frame();
    sw_state_t s = rocking(0.3 * A20, -0.05);
    s.u = -0.02;   /* m */
    s.u_dot = 0.1; /* m/s */
    check_brute(&sc, &s, 1.0, NULL, 1);
}

/* A stuck frame whose bearing rings: not symmetric, and the scan starts at
 * the lift bound read off the linear response.  Nothing below the true
 * lowest overturning amplitude may be skipped: brute force from the energy
 * bound (far below lifting) agrees in both directions. */
static void test_frame_lift_bound(void **state)
{
    (void)state;
    const sw_scene_t sc = crate_frame();
    sw_state_t st;
    memset(&st, 0, sizeof st);
    st.phase = SW_PHASE_STUCK;
    st.u = 0.015;    /* m */
    st.u_dot = 0.04; /* m/s */
    check_brute(&sc, &st, 1.0, NULL, 0);
    st.u = -0.01;
    st.u_dot = 0.08;
    check_brute(&sc, &st, 0.4, NULL, 0);
}

static void test_rocking_cushion(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_cushion(crate(), 44.7, 0.045);
    const sw_derived_t d = derived(&sc);
    sw_state_t s = rocking(0.15 * A20, 0.05);
    s.z = sw_cushion_static_deflection(&d, sc.g);
    /* rkck at its default tolerance: rk8pd on a cushion takes minutes */
    check_brute(&sc, &s, 1.0, "rkck", 1);
}

/* A bare block beyond alpha moving outward falls with no input at all
 * (physics.md): reserve 0, no pulse.  An overturned package: 0. */
static void test_already_falling(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    sw_reserve_t *r = make(&sc, NULL);
    sw_reserve_result_t res;
    sw_state_t s = rocking(1.05 * A20, 0.01);
    assert_int_equal(sw_reserve_eval(r, &s, &res), SW_OK);
    assert_true(res.found);
    assert_true(res.reserve_g == 0.0 && res.direction == 0 && res.pulse == 0.0);
    /* inside alpha, moving outward with more than the barrier's energy */
    const sw_derived_t d = derived(&sc);
    const double w_tip = 2.0 * d.p * sin(0.5 * d.alpha); /* rad/s, reaches alpha from 0 */
    s = rocking(0.0, 1.01 * w_tip);
    assert_int_equal(sw_reserve_eval(r, &s, &res), SW_OK);
    assert_true(res.reserve_g == 0.0);
    s = rocking(0.0, 0.97 * w_tip); /* just short: a pulse is needed */
    assert_int_equal(sw_reserve_eval(r, &s, &res), SW_OK);
    assert_true(res.reserve_g > 0.0);
    memset(&s, 0, sizeof s);
    s.phase = SW_PHASE_OVERTURNED;
    s.theta = M_PI / 2;
    assert_int_equal(sw_reserve_eval(r, &s, &res), SW_OK);
    assert_true(res.reserve_g == 0.0);
    sw_reserve_destroy(r);
}

/* ---- safe islands ---------------------------------------------------------- */

/* From this state (rocking back, moving in) a speeding-up pulse of 1 s
 * overturns it in a window of amplitudes, then a safe island, then again
 * (found by a scan of run.c's runs; checked here).  The reserve must be
 * the window's lower end, not the island's upper one. */
static void test_island(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    const sw_state_t s = rocking(-0.20761, 0.48816);
    const double T = 1.0;
    /* the reference pattern, by brute force (rk4 at 1/400 of the periods) */
    const double first = brute_force(&sc, &s, SW_RESERVE_ACCELERATING, T, 0.2, 1.0, "rk4");
    assert_true(first > 0.0);
    double island = 0.0;
    for (double x = first; x < 1.0; x *= 1.005)
        if (!overturns(&sc, &s, SW_RESERVE_ACCELERATING, x, T, "rk4")) {
            island = x;
            break;
        }
    assert_true(island > first * 1.05); /* a window wider than the scan step */
    int over_again = 0;
    for (double x = island; x < 1.0; x *= 1.005)
        if (overturns(&sc, &s, SW_RESERVE_ACCELERATING, x, T, "rk4")) {
            over_again = 1;
            break;
        }
    assert_true(over_again);

    sw_reserve_opts_t o;
    memset(&o, 0, sizeof o);
    o.each_direction = 1;
    sw_reserve_t *r = make(&sc, &o);
    sw_reserve_result_t res;
    assert_int_equal(sw_reserve_eval(r, &s, &res), SW_OK);
    if (!(first * RUN_SLACK >= res.dir_g[1] && first <= res.dir_g[1] * 1.0101 * 1.005 * RUN_SLACK))
        fail_msg("speeding up: reserve %.4f g, first overturn %.4f g, island from %.4f g",
                 res.dir_g[1], first, island);
    sw_reserve_destroy(r);
}

/* ---- directions close to each other ----------------------------------------- */

/* The reference: the lowest amplitude (g) of a half-sine of duration T in
 * direction dir that overturns the package from s, by its own search
 * through sw_pulse_run_from (GSL's rk8pd at rtol 1e-10, full free motion):
 * a scan in 0.5 % steps from x0, then a bisection to 1e-5.  *safe gets the
 * bracket's lower end. */
static double reference(const sw_scene_t *sc, const sw_state_t *s, int dir, double T, double x0,
                        double *safe)
{
    double last = 0.0;
    for (double x = x0; x < 3.0; x *= 1.005) {
        if (overturns(sc, s, dir, x, T, NULL)) {
            double lo = last > 0.0 ? last : 0.99 * x0, hi = x;
            while (hi / lo - 1.0 > 1e-5) {
                const double m = sqrt(lo * hi);
                if (overturns(sc, s, dir, m, T, NULL))
                    hi = m;
                else
                    lo = m;
            }
            *safe = lo;
            return hi;
        }
        last = x;
    }
    fail_msg("no overturn up to 3 g");
    return 0.0;
}

/* States whose braking and speeding-up thresholds lie within 2 % of each
 * other (found by sweeping theta' at small tilts), where a search that
 * bisects only the first scan to overturn can miss the other direction's
 * threshold between its last safe grid point and that amplitude.  The
 * published reserve must never exceed the reference's threshold and be
 * at most tol (1 %) below it (RUN_SLACK on top), by default (the merged
 * search) and with each_direction; so must each direction's dir_g where
 * it is exact, and it is never above its direction's threshold. */
static void check_close(const sw_scene_t *sc, double theta, double theta_dot)
{
    sw_state_t s = rocking(theta, theta_dot);
    const sw_derived_t d = derived(sc);
    if (sc->has_cushion)
        s.z = sw_cushion_static_deflection(&d, sc->g);
    const double x0 = fmax(0.99 * sw_reserve_energy_bound(&d, sc->g, &s, 1.0), 0.05);
    double ref[2], ref_safe[2];
    for (int i = 0; i < 2; i++)
        ref[i] = reference(sc, &s, i == 0 ? SW_RESERVE_BRAKING : SW_RESERVE_ACCELERATING, 1.0, x0,
                           &ref_safe[i]);
    /* the states are what they claim to be */
    if (!(fmax(ref[0], ref[1]) / fmin(ref[0], ref[1]) < 1.02))
        fail_msg("theta %g, theta' %g: thresholds %.5f / %.5f g are not within 2 %%", theta,
                 theta_dot, ref[0], ref[1]);
    const double r = fmin(ref[0], ref[1]), r_safe = fmin(ref_safe[0], ref_safe[1]);
    for (int each = 0; each < 2; each++) {
        sw_reserve_opts_t o;
        memset(&o, 0, sizeof o);
        o.each_direction = each;
        sw_reserve_t *R = make(sc, &o);
        sw_reserve_result_t res;
        assert_int_equal(sw_reserve_eval(R, &s, &res), SW_OK);
        assert_true(res.found && !res.at_floor);
        if (!(res.reserve_g <= r && res.reserve_g * 1.01 * RUN_SLACK >= r_safe))
            fail_msg(
                "%s, theta %g, theta' %g, each_direction %d: reserve %.5f g (direction %d), "
                "reference %.5f g braking, %.5f g speeding up",
                sw_model_name(d.model), theta, theta_dot, each, res.reserve_g, res.direction,
                ref[0], ref[1]);
        assert_true(res.safe_g == res.reserve_g);
        assert_true(res.over_g / res.reserve_g - 1.0 <= 0.01 * (1.0 + 1e-9));
        for (int i = 0; i < 2; i++) {
            if (!(res.dir_g[i] <= ref[i]))
                fail_msg("%s, direction %d: dir_g %.5f g above the reference %.5f g",
                         sw_model_name(d.model), i, res.dir_g[i], ref[i]);
            if (each)
                assert_true(res.dir_exact[i]);
            if (res.dir_exact[i] && !(res.dir_g[i] * 1.01 * RUN_SLACK >= ref_safe[i]))
                fail_msg("%s, direction %d: dir_g %.5f g, reference %.5f g", sw_model_name(d.model),
                         i, res.dir_g[i], ref[i]);
        }
        sw_reserve_destroy(R);
    }
}

static void test_close_directions(void **state)
{
    (void)state;
    /* the crate of sample_logs/crate.ini on braking-pothole.csv at 8.5 s:
     * 0.4871 g braking, 0.4798 g speeding up; then two more */
    const sw_scene_t bare = crate();
    check_close(&bare, 0.00082, -0.149);
    check_close(&bare, 0.001, 0.06);
    check_close(&bare, 0.02, -0.12);
    const sw_scene_t fr = crate_frame();
    check_close(&fr, 0.001, 0.01);
    check_close(&fr, 0.02, -0.23);
    check_close(&fr, 0.001, -0.01);
    /* the cushion of sample_logs/crate-on-cushion.ini */
    const sw_scene_t cu = tu_cushion(crate(), 44.72, 0.05);
    check_close(&cu, -0.02, 0.21);
    check_close(&cu, 0.001, -0.01);
    check_close(&cu, 0.02, -0.22);
}

/* ---- the energy bound -------------------------------------------------------- */

/* Closed form at rest: pi sqrt(g R (1 - cos a)) / (2 T c) with c =
 * sqrt(3/8) on the bed; 0 at and beyond the barrier. */
static void test_energy_bound_closed_form(void **state)
{
    (void)state;
    const sw_scene_t sc = crate();
    const sw_derived_t d = derived(&sc);
    sw_state_t s;
    memset(&s, 0, sizeof s);
    s.phase = SW_PHASE_STUCK;
    const double T = 0.7;
    const double want =
        M_PI * sqrt(sc.g * d.R * (1.0 - cos(d.alpha))) / (2.0 * T * sqrt(3.0 / 8.0));
    assert_float_equal(sw_reserve_energy_bound(&d, sc.g, &s, T) * SW_G0, want, 1e-9 * want);
    s = rocking(1.01 * d.alpha, 0.0);
    assert_true(sw_reserve_energy_bound(&d, sc.g, &s, T) == 0.0);
    s = rocking(0.0, 1.2 * 2.0 * d.p * sin(0.5 * d.alpha));
    assert_true(sw_reserve_energy_bound(&d, sc.g, &s, T) == 0.0);
}

/* The energies behind the bound, per model, against closed forms: the
 * rigid barrier g R (1 - cos alpha), the work rates sqrt(3/8) on the bed
 * and 1/sqrt(2 gamma) on a frame, a block held still at theta holding
 * g R (cos(alpha - theta) - cos(alpha)) above rest; a cushion's barrier
 * is sw_cushion_barrier's; a model outside the enum gives NAN. */
static void test_model_energies(void **state)
{
    (void)state;
    const sw_scene_t bare = crate(), frame = crate_frame();
    const sw_scene_t cush = tu_cushion(crate(), 44.7, 0.045);
    const sw_derived_t db = derived(&bare), df = derived(&frame), dc = derived(&cush);
    const double g = bare.g;
    assert_float_equal(sw_model_barrier(&db, g), g * db.R * (1.0 - cos(db.alpha)), 1e-12);
    assert_float_equal(sw_model_barrier(&df, g), g * df.R * (1.0 - cos(df.alpha)), 1e-12);
    assert_true(sw_model_barrier(&dc, g) == sw_cushion_barrier(&dc, g));
    assert_float_equal(sw_model_work_rate(&db), sqrt(3.0 / 8.0), 1e-15);
    assert_float_equal(sw_model_work_rate(&df), 1.0 / sqrt(2.0 * df.gamma), 1e-15);
    const sw_state_t s = rocking(0.5 * db.alpha, 0.0);
    const double want = g * db.R * (cos(db.alpha - s.theta) - cos(db.alpha));
    assert_float_equal(sw_model_energy(&db, g, &s), want, 1e-12);
    sw_derived_t bad = db;
    bad.model = (sw_model_kind)7;
    assert_true(isnan(sw_model_energy(&bad, g, &s)));
    assert_true(isnan(sw_model_barrier(&bad, g)));
    assert_true(isnan(sw_model_work_rate(&bad)));
}

/* The bound is a bound: just below it nothing overturns, from rest and
 * from rocking states, on the bed, the frame and a cushion, for short and
 * long pulses (rk8pd runs; rkck on the cushion). */
static void check_bound(const sw_scene_t *sc, const sw_state_t *s, const char *scheme)
{
    const sw_derived_t d = derived(sc);
    const double Ts[] = {0.05, 0.3, 1.0};
    for (size_t k = 0; k < 3; k++) {
        const double x = sw_reserve_energy_bound(&d, sc->g, s, Ts[k]);
        assert_true(x > 0.0);
        for (int dir = -1; dir <= 1; dir += 2)
            if (overturns(sc, s, dir, 0.999 * x, Ts[k], scheme))
                fail_msg("T = %g s, direction %d: %.4f g overturns below the bound", Ts[k], dir,
                         0.999 * x);
    }
}

static void test_energy_bound_holds(void **state)
{
    (void)state;
    sw_state_t rest;
    memset(&rest, 0, sizeof rest);
    rest.phase = SW_PHASE_STUCK;
    const sw_scene_t bare = crate(), fr = crate_frame();
    check_bound(&bare, &rest, NULL);
    check_bound(
        &bare,
        &(sw_state_t){.theta = 0.3 * A20, .theta_dot = 0.15, .phase = SW_PHASE_ROCKING, .side = 1},
        NULL);
    check_bound(&fr, &rest, NULL);
    sw_state_t s = rocking(-0.2 * A20, 0.1);
    s.u = 0.01;
    check_bound(&fr, &s, NULL);
    const sw_scene_t cu = tu_cushion(crate(), 44.7, 0.045);
    const sw_derived_t dc = derived(&cu);
    sw_state_t sc0;
    memset(&sc0, 0, sizeof sc0);
    sc0.phase = SW_PHASE_ROCKING;
    sc0.z = sw_cushion_static_deflection(&dc, cu.g);
    check_bound(&cu, &sc0, "rkck");
}

/* The lift bound of a stuck frame: no pulse below it lifts the package
 * (brute force on the runs' uplift, rk8pd, 0.1 % steps), and it is tight:
 * one a little above it does (it is read off the linear response, not
 * guessed).  On the bed it is g tan(alpha) exactly. */
static void test_lift_bound_tight(void **state)
{
    (void)state;
    const sw_scene_t sc = crate_frame();
    sw_reserve_t *r = make(&sc, NULL);
    sw_state_t st;
    memset(&st, 0, sizeof st);
    st.phase = SW_PHASE_STUCK;
    const double us[3][2] = {{0.0, 0.0}, {0.015, 0.04}, {-0.01, 0.08}}; /* m, m/s */
    for (int k = 0; k < 3; k++) {
        st.u = us[k][0];
        st.u_dot = us[k][1];
        for (int dir = -1; dir <= 1; dir += 2) {
            const double lb = sw_reserve_lower_bound(r, &st, dir, 0);
            assert_true(lb > 0.0);
            double lift = 0.0;
            for (double x = 0.97 * lb; x < 1.05 * lb; x *= 1.001) {
                sw_pulse_t pl = {SW_PULSE_HALF_SINE, dir * x * SW_G0, M_PI / 1.0};
                sw_run_opts_t ro;
                memset(&ro, 0, sizeof ro);
                ro.engine.scheme = "rk8pd";
                ro.engine.rtol = 1e-10;
                ro.engine.atol = 1e-12;
                ro.settle = 5.0;
                sw_run_result_t rr;
                assert_int_equal(sw_pulse_run_from(&sc, &st, &pl, &ro, &rr, NULL, 0), SW_OK);
                if (!isnan(rr.uplift_time)) {
                    lift = x;
                    break;
                }
            }
            if (!(lift >= lb && lift <= lb * 1.01))
                fail_msg("u = %g m, u' = %g m/s, direction %d: bound %.5f g, lifts at %.5f g", st.u,
                         st.u_dot, dir, lb, lift);
        }
    }
    sw_reserve_destroy(r);
    const sw_scene_t bare = crate();
    const sw_derived_t d = derived(&bare);
    r = make(&bare, NULL);
    memset(&st, 0, sizeof st);
    st.phase = SW_PHASE_STUCK;
    assert_float_equal(sw_reserve_lower_bound(r, &st, SW_RESERVE_BRAKING, 0) * SW_G0,
                       bare.g * tan(d.alpha), 1e-12);
    assert_true(sw_reserve_lower_bound(r, &st, 0, 0) == 0.0);
    assert_true(sw_reserve_lower_bound(r, &st, 1, 1) == 0.0);
    sw_reserve_destroy(r);
}

/* ---- several pulses, determinism, the cache ------------------------------------ */

static void test_several_pulses(void **state)
{
    (void)state;
    const sw_scene_t base = crate_frame();
    sw_scene_t two = base;
    two.n_design_pulse = 2;
    two.design_pulse[0] = 1.0;
    two.design_pulse[1] = 2.0;
    sw_state_t s = rocking(0.2 * A20, 0.05);
    s.u = 0.01;
    sw_reserve_result_t a, b, both;
    sw_scene_t s1 = with_pulse(base, 1.0), s2 = with_pulse(base, 2.0);
    sw_reserve_t *r1 = make(&s1, NULL), *r2 = make(&s2, NULL), *rb = make(&two, NULL);
    assert_int_equal(sw_reserve_eval(r1, &s, &a), SW_OK);
    assert_int_equal(sw_reserve_eval(r2, &s, &b), SW_OK);
    assert_int_equal(sw_reserve_eval(rb, &s, &both), SW_OK);
    /* the smaller of the two, to the bracket's width: never above an
     * amplitude either search saw overturn, not below their safe ends by
     * more than tol, and the same pulse and direction where the two differ
     * by more than that */
    const sw_reserve_result_t *lo = a.reserve_g <= b.reserve_g ? &a : &b;
    const sw_reserve_result_t *hi = lo == &a ? &b : &a;
    assert_true(both.reserve_g <= fmin(a.over_g, b.over_g));
    assert_true(both.reserve_g * 1.0101 >= lo->reserve_g);
    if (hi->reserve_g > lo->over_g * 1.0101) {
        assert_true(both.pulse == lo->pulse);
        assert_true(both.direction == lo->direction);
    }
    const double *T;
    assert_int_equal(sw_reserve_pulses(rb, &T), 2);
    assert_true(T[0] == 1.0 && T[1] == 2.0);
    /* at rest: the smaller of the two rest values */
    sw_reserve_result_t ra, rb_, rr;
    sw_reserve_rest(r1, &ra);
    sw_reserve_rest(r2, &rb_);
    sw_reserve_rest(rb, &rr);
    assert_true(rr.reserve_g == fmin(ra.reserve_g, rb_.reserve_g));
    sw_reserve_destroy(r1);
    sw_reserve_destroy(r2);
    sw_reserve_destroy(rb);
}

/* The same state gives the same bits whatever came before, in the same
 * object and in a fresh one; the mirror image gives the mirror answer. */
static void test_deterministic(void **state)
{
    (void)state;
    const sw_scene_t sc = crate_frame();
    sw_reserve_t *r = make(&sc, NULL), *fresh = make(&sc, NULL);
    sw_state_t a = rocking(0.25 * A20, 0.08), b = rocking(-0.1 * A20, -0.2);
    a.u = 0.005;
    a.u_dot = -0.03;
    sw_reserve_result_t x1, x2, x3, y;
    assert_int_equal(sw_reserve_eval(r, &a, &x1), SW_OK);
    assert_int_equal(sw_reserve_eval(r, &b, &y), SW_OK);
    assert_int_equal(sw_reserve_eval(r, &a, &x2), SW_OK);
    assert_int_equal(sw_reserve_eval(fresh, &a, &x3), SW_OK);
    assert_memory_equal(&x1, &x2, sizeof x1);
    assert_memory_equal(&x1, &x3, sizeof x1);
    /* mirror: theta, theta_dot, u, u_dot negated */
    sw_state_t m = a;
    m.theta = -a.theta;
    m.theta_dot = -a.theta_dot;
    m.u = -a.u;
    m.u_dot = -a.u_dot;
    m.side = -a.side;
    sw_reserve_result_t xm;
    assert_int_equal(sw_reserve_eval(r, &m, &xm), SW_OK);
    assert_true(fabs(xm.reserve_g / x1.reserve_g - 1.0) < 1e-9);
    assert_int_equal(xm.direction, -x1.direction);
    sw_reserve_destroy(r);
    sw_reserve_destroy(fresh);
}

/* One half-sine run from s through the engine, with or without
 * outcome_only; the final state, summary and TIP events. */
typedef struct {
    sw_state_t end;
    sw_output_t out;
    sw_summary_t sum;
    int tips;
} oo_run_t;

static oo_run_t outcome_run(const sw_scene_t *sc, const char *scheme, double dt, int outcome_only,
                            const sw_state_t *s, double a_g)
{
    tu_events_t *rec = calloc(1, sizeof *rec);
    assert_non_null(rec);
    sw_engine_opts_t o = {0};
    o.scheme = scheme;
    o.dt = dt;
    o.rtol = 1e-6;
    o.outcome_only = outcome_only;
    o.on_event = tu_on_event;
    o.user = rec;
    int err;
    char msg[256];
    sw_engine_t *e = sw_engine_create(sc, 1, &o, &err, msg, sizeof msg);
    assert_non_null(e);
    assert_int_equal(sw_engine_set_state(e, 0, s), SW_OK);
    sw_pulse_t pl = {SW_PULSE_HALF_SINE, a_g, M_PI / 1.0};
    assert_true(sw_engine_advance_fn(e, 1.0, sw_pulse_eval, &pl) >= 0);
    oo_run_t r;
    memset(&r, 0, sizeof r);
    for (int k = 1; k <= 40; k++) /* free motion, in chunks as the reserve's runs */
        assert_true(sw_engine_advance_fn(e, 1.0 + 0.1 * k, sw_pulse_eval, &pl) >= 0);
    assert_int_equal(sw_engine_get_state(e, 0, &r.end), SW_OK);
    assert_int_equal(sw_engine_get_output(e, 0, &r.out), SW_OK);
    assert_int_equal(sw_engine_summary(e, 0, &r.sum), SW_OK);
    r.tips = tu_count(rec, SW_EV_TIP);
    sw_engine_destroy(e);
    free(rec);
    return r;
}

/* outcome_only leaves the motion alone: the same final state bit for bit,
 * the same verdict and overturn time, on every model and for a run that
 * overturns and one that does not; what it drops is only the report (TIP
 * events here).  The reserve runs this way. */
static void test_outcome_only_same_motion(void **state)
{
    (void)state;
    const sw_scene_t sc[3] = {crate(), crate_frame(), tu_cushion(crate(), 44.7, 0.045)};
    const char *scheme[3] = {"rk4", "rk4", "rkck"};
    const double dt[3] = {1e-3, 1e-3, 5e-3};
    for (int m = 0; m < 3; m++) {
        const sw_state_t s = m == 2 ? rocking(0.02, 0.05) : rocking(0.3 * A20, 0.1);
        sw_state_t s0 = s;
        if (m == 2)
            s0.z = 9.81 / (44.7 * 44.7); /* near the static deflection */
        int overturned = 0, survived = 0;
        for (double x = 0.2; x <= 1.6; x += 0.35) {
            const oo_run_t full = outcome_run(&sc[m], scheme[m], dt[m], 0, &s0, -x * SW_G0);
            const oo_run_t oo = outcome_run(&sc[m], scheme[m], dt[m], 1, &s0, -x * SW_G0);
            assert_memory_equal(&full.end, &oo.end, sizeof full.end);
            assert_memory_equal(&full.out.state, &oo.end, sizeof oo.end);
            assert_int_equal(full.sum.overturned, oo.sum.overturned);
            assert_int_equal(full.sum.impacts, oo.sum.impacts);
            if (full.sum.overturned)
                assert_true(full.sum.overturn_time == oo.sum.overturn_time);
            assert_int_equal(oo.tips, 0);
            if (full.sum.overturned)
                assert_true(full.tips > 0);
            overturned += full.sum.overturned;
            survived += !full.sum.overturned;
        }
        /* both outcomes were exercised */
        assert_true(overturned > 0);
        assert_true(survived > 0);
    }
}

static void test_rest_cache(void **state)
{
    (void)state;
    const sw_scene_t scenes[3] = {crate(), crate_frame(), tu_cushion(crate(), 44.7, 0.045)};
    for (int i = 0; i < 3; i++) {
        sw_reserve_opts_t o;
        memset(&o, 0, sizeof o);
        sw_reserve_t *r = make(&scenes[i], &o);
        o.no_cache = 1;
        sw_reserve_t *nc = make(&scenes[i], &o);
        const sw_derived_t d = derived(&scenes[i]);
        sw_state_t s;
        memset(&s, 0, sizeof s);
        s.phase = i == 2 ? SW_PHASE_ROCKING : SW_PHASE_STUCK;
        s.z = i == 2 ? sw_cushion_static_deflection(&d, scenes[i].g) : 0.0;
        assert_true(sw_reserve_is_rest(r, &s));
        sw_reserve_result_t c, n;
        assert_int_equal(sw_reserve_eval(r, &s, &c), SW_OK);
        assert_int_equal(sw_reserve_eval(nc, &s, &n), SW_OK);
        assert_true(c.cached && !n.cached);
        assert_true(c.trials == 0 && n.trials > 0);
        /* the cache holds exactly what a computation gives */
        assert_true(c.reserve_g == n.reserve_g && c.safe_g == n.safe_g);
        /* a stuck frame whose bearing moves is not at rest */
        if (i == 1) {
            s.u_dot = 1e-6;
            assert_false(sw_reserve_is_rest(r, &s));
        }
        sw_reserve_destroy(r);
        sw_reserve_destroy(nc);
    }
}

static void test_bad_arguments(void **state)
{
    (void)state;
    int err = 0;
    char msg[256];
    sw_scene_t bad = crate();
    bad.height = -1.0;
    assert_null(sw_reserve_create(&bad, NULL, &err, msg, sizeof msg));
    assert_int_equal(err, SW_EINVAL);
    assert_null(sw_reserve_create(NULL, NULL, &err, NULL, 0));
    assert_int_equal(err, SW_EINVAL);
    const sw_scene_t sc = crate();
    sw_reserve_opts_t o;
    memset(&o, 0, sizeof o);
    o.floor_g = 5.0;
    o.max_g = 1.0;
    assert_null(sw_reserve_create(&sc, &o, &err, msg, sizeof msg));
    assert_int_equal(err, SW_EINVAL);
    sw_reserve_t *r = make(&sc, NULL);
    sw_state_t s = rocking(NAN, 0.0);
    sw_reserve_result_t res;
    assert_int_equal(sw_reserve_eval(r, &s, &res), SW_EINVAL);
    s = rocking(0.1, 0.0);
    s.phase = (sw_phase)7;
    assert_int_equal(sw_reserve_eval(r, &s, &res), SW_EINVAL);
    assert_int_equal(sw_reserve_eval(NULL, &s, &res), SW_EINVAL);
    assert_int_equal(sw_reserve_eval(r, NULL, &res), SW_EINVAL);
    sw_reserve_destroy(r);
    sw_reserve_destroy(NULL);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rest_published_table),
        cmocka_unit_test(test_rest_boundary_models),
        cmocka_unit_test(test_rocking_bare),
        cmocka_unit_test(test_rocking_frame),
        cmocka_unit_test(test_rocking_cushion),
        cmocka_unit_test(test_already_falling),
        cmocka_unit_test(test_island),
        cmocka_unit_test(test_close_directions),
        cmocka_unit_test(test_energy_bound_closed_form),
        cmocka_unit_test(test_model_energies),
        cmocka_unit_test(test_energy_bound_holds),
        cmocka_unit_test(test_frame_lift_bound),
        cmocka_unit_test(test_lift_bound_tight),
        cmocka_unit_test(test_several_pulses),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_outcome_only_same_motion),
        cmocka_unit_test(test_rest_cache),
        cmocka_unit_test(test_bad_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
