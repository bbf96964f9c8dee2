/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_physics_claims.c - claims the documents make about the models,
 * each checked here by runs or closed forms instead of being taken on
 * trust (docs/physics.md, docs/cushion.md):
 *   - the bare block's margin predicts the free-motion outcome exactly:
 *     its sign decides overturn on 150 random states (rk8pd runs);
 *   - "past alpha after the pulse means overturned" holds for the bare
 *     block only: a framed package past alpha moving outward can be
 *     brought back by its bearing;
 *   - an edge of a cushioned package lifts at about one third of the
 *     uplift ratio, 1/3 - g h/(omega_c^2 b^2) (the kern rule), not just
 *     below 1;
 *   - on a cushion the package cannot stand still beyond a tilt below
 *     alpha (the pressure acts inside the corner), while the centre of mass
 *     passes over the loaded corner at exactly alpha, and the potential
 *     stays >= 0 up to alpha (which the reserve's energy bound uses);
 *   - with a cubic term the cushion's contact set can be two intervals. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

static const double A20 = 20.0 * M_PI / 180.0; /* rad */

/* A deterministic uniform number in [0, 1). */
static double uniform(uint64_t *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 9007199254740992.0;
}

/* Free motion from s, no input, up to t_end (s): overturned?  rk8pd at a
 * tight tolerance, the rest threshold far below anything that matters. */
static int free_overturns(const sw_scene_t *sc, const sw_state_t *s, double t_end)
{
    sw_engine_opts_t o;
    memset(&o, 0, sizeof o);
    o.scheme = "rk8pd";
    o.rtol = 1e-12;
    o.atol = 1e-14;
    int err;
    sw_engine_t *e = sw_engine_create(sc, 1, &o, &err, NULL, 0);
    assert_non_null(e);
    assert_int_equal(sw_engine_set_state(e, 0, s), SW_OK);
    sw_summary_t sum;
    for (double t = 0.5; t <= t_end; t += 0.5) {
        sw_engine_advance_fn(e, t, sw_pulse_eval, &(sw_pulse_t){SW_PULSE_HALF_SINE, 0.0, 1.0});
        sw_engine_summary(e, 0, &sum);
        sw_output_t out;
        sw_engine_get_output(e, 0, &out);
        if (sum.overturned || out.state.phase == SW_PHASE_STUCK)
            break;
    }
    sw_engine_summary(e, 0, &sum);
    sw_engine_destroy(e);
    return sum.overturned;
}

/* physics.md, "Margin to overturn": for free rocking the bare margin is
 * exact, its sign predicts the outcome.  150 states spread over both
 * sides, inside and beyond alpha, moving in and out, with energies from
 * 0.1 to 2 barriers; states within 1e-3 of the edge are left out (there a
 * run's own error could decide). */
static void test_margin_sign_150_states(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 2.0 * tan(A20));
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(&sc, &d, NULL, NULL, NULL), SW_OK);
    uint64_t seed = 150;
    int checked = 0, over = 0;
    while (checked < 150) {
        const double th = (2.0 * uniform(&seed) - 1.0) * 1.3 * d.alpha;
        /* kinetic energy for a total of E barriers, where the potential
         * allows it */
        const double PE = (cos(d.alpha - fabs(th)) - cos(d.alpha)) / (1.0 - cos(d.alpha));
        const double E = 0.1 + 1.9 * uniform(&seed);
        if (E <= PE)
            continue;
        const double w = sqrt((E - PE) * 2.0 * d.p * d.p * (1.0 - cos(d.alpha))); /* rad/s */
        const double thd = uniform(&seed) < 0.5 ? w : -w;
        const double m = sw_margin_rocking(&d, d.eta, th, thd);
        if (fabs(m) < 1e-3)
            continue;
        sw_state_t s;
        memset(&s, 0, sizeof s);
        s.phase = SW_PHASE_ROCKING;
        s.theta = th;
        s.theta_dot = thd;
        s.side = th > 0.0 ? 1 : -1;
        const int o = free_overturns(&sc, &s, 30.0);
        if (o != (m <= 0.0))
            fail_msg("theta %.5f rad, theta' %.5f rad/s: margin %.4f but %s", th, thd, m,
                     o ? "overturned" : "survived");
        checked++;
        over += o;
    }
    /* both outcomes well represented */
    assert_true(over > 30 && over < 120);
}

/* physics.md, pulses: "past alpha after the pulse means overturned" is
 * right for the bare block, where gravity alone acts; a package on a frame
 * past alpha, moving outward, is brought back by the bearing pushing the
 * frame forward. */
static void test_frame_past_alpha(void **state)
{
    (void)state;
    const sw_scene_t bare = tu_bare(2.0, 2.0 * tan(A20));
    const sw_scene_t fr = tu_frame(2.0, 2.0 * tan(A20), 250.0, 5.59, 0.1);
    sw_state_t s;
    memset(&s, 0, sizeof s);
    s.phase = SW_PHASE_ROCKING;
    s.side = 1;
    s.theta = 1.01 * A20;
    s.theta_dot = 0.05; /* rad/s, outward */
    assert_true(free_overturns(&bare, &s, 10.0));
    s.u = -0.05; /* m: the bearing compressed behind the frame */
    assert_false(free_overturns(&fr, &s, 30.0));
}

static sw_scene_t cushion(double omega_c, double zeta_c)
{
    return tu_cushion(tu_bare(2.0, 2.0 * tan(A20)), omega_c, zeta_c);
}

typedef struct {
    int lifted;
    double t;
} lift_t;

static void on_lift(void *user, const sw_event_t *ev)
{
    lift_t *l = user;
    if (ev->kind == SW_EV_UPLIFT && !l->lifted) {
        l->lifted = 1;
        l->t = ev->t;
    }
}

static double ramp(void *user, double t)
{
    return -*(const double *)user * t;
}

/* Quasi-static braking, 1 % of g tan(alpha) per second, light damping: an
 * edge leaves the cushion when b theta = z_s, theta = m h a/(K b^2/3 - m g h),
 * i.e. at a/(g tan alpha) = 1/3 - g h/(omega_c^2 b^2). */
static void test_cushion_kern_rule(void **state)
{
    (void)state;
    const double wcs[] = {30.0, 44.7, 100.0, 300.0};
    for (size_t i = 0; i < 4; i++) {
        const sw_scene_t sc = cushion(wcs[i], 0.02);
        const double h = 1.0, b = tan(A20), L = sc.g * tan(A20);
        const double kern = 1.0 / 3.0 - sc.g * h / (wcs[i] * wcs[i] * b * b);
        lift_t l = {0, 0.0};
        sw_engine_opts_t o;
        memset(&o, 0, sizeof o);
        o.scheme = "rkck";
        o.on_event = on_lift;
        o.user = &l;
        int err;
        sw_engine_t *e = sw_engine_create(&sc, 1, &o, &err, NULL, 0);
        assert_non_null(e);
        double rate = 0.01 * L; /* m/s^3 */
        sw_engine_advance_fn(e, 60.0, ramp, &rate);
        assert_true(l.lifted);
        const double ratio = rate * l.t / L;
        if (!(fabs(ratio / kern - 1.0) < 0.01))
            fail_msg("omega_c %g: edge lifts at %.4f, kern rule %.4f", wcs[i], ratio, kern);
        assert_true(ratio < 0.34); /* a third, not "just below 1" */
        sw_engine_destroy(e);
    }
}

/* The least potential (gravity + cushion strain, from rest; J/kg) at tilt
 * theta over the sinking z, by golden-section search. */
static double least_potential(const sw_derived_t *d, double g, double theta)
{
    sw_state_t s;
    memset(&s, 0, sizeof s);
    s.phase = SW_PHASE_ROCKING;
    s.side = 1;
    s.theta = theta;
    double lo = -1.0, hi = 1.0; /* m */
    for (int it = 0; it < 200; it++) {
        const double m1 = lo + 0.381966 * (hi - lo), m2 = lo + 0.618034 * (hi - lo);
        s.z = m1;
        const double f1 = sw_energy_cushion(d, g, &s);
        s.z = m2;
        const double f2 = sw_energy_cushion(d, g, &s);
        if (f1 < f2)
            hi = m2;
        else
            lo = m1;
    }
    s.z = 0.5 * (lo + hi);
    return sw_energy_cushion(d, g, &s);
}

/* On a cushion the pressure acts inside the loaded corner: the least
 * potential along the tilt peaks before alpha (the package cannot stand
 * still beyond that tilt), above its value at alpha (the barrier the
 * margins use, which is therefore on the safe side).  Released at rest a
 * little beyond the peak, below alpha, the package falls; a little before
 * it, it comes back.  The potential is >= 0 all the way to alpha.  And the
 * centre of mass passes over the loaded corner at exactly alpha: with B
 * held, the corner is at b (cos th, -sin th) from B and the centre of mass
 * at h (sin th, cos th), whatever z. */
static void test_cushion_tips_before_alpha(void **state)
{
    (void)state;
    const sw_scene_t sc = cushion(44.7, 0.045);
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(&sc, &d, NULL, NULL, NULL), SW_OK);
    double vmax = -1.0, th_max = 0.0, vmin = 1.0;
    for (int k = 1; k <= 400; k++) {
        const double th = d.alpha * k / 400.0;
        const double v = least_potential(&d, sc.g, th);
        if (v > vmax) {
            vmax = v;
            th_max = th;
        }
        vmin = fmin(vmin, v);
    }
    const double barrier = sw_cushion_barrier(&d, sc.g);
    assert_true(vmin >= -1e-9);
    assert_true(th_max < 0.95 * d.alpha);
    assert_true(vmax > 1.01 * barrier);
    assert_float_equal(least_potential(&d, sc.g, d.alpha), barrier, 1e-6 * barrier);
    for (int k = -1; k <= 1; k += 2) {
        const double th = th_max + k * 0.03 * d.alpha;
        sw_state_t s;
        memset(&s, 0, sizeof s);
        s.phase = SW_PHASE_ROCKING;
        s.side = 1;
        s.theta = th;
        /* at the z of least potential: vertically balanced */
        double lo = -1.0, hi = 1.0;
        for (int it = 0; it < 200; it++) {
            const double m1 = lo + 0.381966 * (hi - lo), m2 = lo + 0.618034 * (hi - lo);
            s.z = m1;
            const double f1 = sw_energy_cushion(&d, sc.g, &s);
            s.z = m2;
            const double f2 = sw_energy_cushion(&d, sc.g, &s);
            if (f1 < f2)
                hi = m2;
            else
                lo = m1;
        }
        s.z = 0.5 * (lo + hi);
        sw_engine_opts_t o;
        memset(&o, 0, sizeof o);
        o.scheme = "rkck";
        int err;
        sw_engine_t *e = sw_engine_create(&sc, 1, &o, &err, NULL, 0);
        assert_non_null(e);
        assert_int_equal(sw_engine_set_state(e, 0, &s), SW_OK);
        sw_engine_advance_fn(e, 10.0, sw_pulse_eval, &(sw_pulse_t){SW_PULSE_HALF_SINE, 0.0, 1.0});
        sw_summary_t sum;
        sw_engine_summary(e, 0, &sum);
        assert_int_equal(sum.overturned, k > 0);
        sw_engine_destroy(e);
    }
    /* the geometry of the corner */
    const double h = d.h, b = d.b;
    assert_float_equal(h * sin(d.alpha), b * cos(d.alpha), 1e-15);
}

/* physics.md, scene 3: the force density f(s) = k'z + b'z^3 + c'z' where
 * z(s) > 0, clamped at f >= 0.  With z and z' both linear in s, f is a
 * cubic in z, convex on z > 0, so f < 0 (the dampers of a fast-rising part
 * would pull) can fill a middle sub-interval: the contact is then two
 * intervals, pushing at the shallow end (still compressing) and at the
 * deep end (the cubic term).  An example, worked by hand: per unit
 * length k' = 1e6 N/m^2, c' = 1e4 N s/m^2, b' = 1e12 N/m^4, a base tilted
 * 0.005 rad and turning at -5 rad/s so that z' = 0.1 - 1000 z (m/s):
 * f = 1e12 z^3 - 9e6 z + 1e3 N/m is +1e3 at z = 0, -7e3 at 1 mm and +1e3
 * at 3 mm. */
static void test_cubic_two_intervals(void **state)
{
    (void)state;
    const double k = 1e6, c = 1e4, beta = 1e12;                /* N/m^2, N s/m^2, N/m^4 */
    const double b = 0.4, th = 0.005, thd = -1000.0 * tan(th); /* m, rad, rad/s */
    const double zB = 0.0015, zBd = 0.1 - 1000.0 * zB;         /* m, m/s */
    int pieces = 0, in = 0;
    for (int i = 0; i <= 100000; i++) {
        const double sg = -b + 2.0 * b * i / 100000.0;
        const double z = zB + sg * sin(th), zd = zBd + sg * thd * cos(th);
        const double f = z > 0.0 ? k * z + beta * z * z * z + c * zd : 0.0;
        const int push = f > 0.0;
        if (push && !in)
            pieces++;
        in = push;
    }
    assert_int_equal(pieces, 2);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_margin_sign_150_states),
        cmocka_unit_test(test_frame_past_alpha),
        cmocka_unit_test(test_cushion_kern_rule),
        cmocka_unit_test(test_cushion_tips_before_alpha),
        cmocka_unit_test(test_cubic_two_intervals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
