/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_risk.c - risk.h against what it does not compute itself: the
 * evaluation times from the rate alone, the reserve values from separate
 * sw_reserve_eval() calls on the same states, the impact split from the
 * engine's own impact events and the significance's closed form
 * 0.1 * 2 p sin(alpha/2), and the settling spans from the events' order. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "testutil.h"

#define RATE_HZ 1000.0 /* samples */
#define NSAMP 4000     /* 4 s */
#define MAXEV 20000

typedef struct {
    sw_risk_t *risk;
    sw_reserve_t *ref; /* a second reserve of the same scene: the reference values */
    sw_output_t last;
    int evals;
    double eval_t[200];
    double worst_diff; /* between risk's values and the reference's */
    double ref_min, ref_min_t;
    sw_event_t ev[MAXEV];
    int nev;
    int reported_impacts, closed_spans;
    long closed_micro;
} rig_t;

static void on_state(void *user, const sw_output_t *out)
{
    rig_t *R = user;
    const int rc = sw_risk_output(R->risk, out);
    assert_true(rc == 0 || rc == 1);
    if (rc != 1)
        return;
    assert_true(R->evals < 200);
    R->eval_t[R->evals++] = out->t;
    sw_reserve_result_t res;
    assert_int_equal(sw_reserve_eval(R->ref, &out->state, &res), SW_OK);
    const sw_risk_pkg_t *p = sw_risk_pkg(R->risk, 0);
    const double d = fabs(p->reserve_g - res.reserve_g);
    if (d > R->worst_diff)
        R->worst_diff = d;
    if (!(res.reserve_g >= R->ref_min)) {
        R->ref_min = res.reserve_g;
        R->ref_min_t = out->t;
    }
}

static void on_event(void *user, const sw_event_t *ev)
{
    rig_t *R = user;
    assert_true(R->nev < MAXEV);
    R->ev[R->nev++] = *ev;
    sw_settle_span_t span;
    const int f = sw_risk_event(R->risk, ev, &span);
    if (f & SW_SETTLE_CLOSED) {
        R->closed_spans++;
        R->closed_micro += span.impacts;
    }
    if ((f & SW_SETTLE_REPORT) && ev->kind == SW_EV_IMPACT)
        R->reported_impacts++;
}

/* A braking half-sine of amp m/s^2 lasting 0.3 s from 0.5 s. */
static double pulse(double t, double amp)
{
    return t >= 0.5 && t < 0.8 ? -amp * sin(M_PI * (t - 0.5) / 0.3) : 0.0;
}

static rig_t *run(const sw_scene_t *sc, double amp, double rate)
{
    rig_t *R = calloc(1, sizeof *R);
    assert_non_null(R);
    R->ref_min = R->ref_min_t = NAN;
    const sw_risk_opts_t ro = {.reserve_rate = rate};
    int err = 0;
    char msg[256];
    R->risk = sw_risk_create(sc, 1, &ro, &err, msg, sizeof msg);
    if (!R->risk)
        fail_msg("sw_risk_create: %s", msg);
    R->ref = sw_reserve_create(sc, NULL, &err, msg, sizeof msg);
    assert_non_null(R->ref);
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    eo.on_state = on_state;
    eo.on_event = on_event;
    eo.user = R;
    sw_engine_t *e = sw_engine_create(sc, 1, &eo, &err, msg, sizeof msg);
    assert_non_null(e);
    for (long k = 0; k < NSAMP; k++) {
        const double t = (double)k / RATE_HZ;
        assert_true(sw_engine_push(e, t, pulse(t, amp), 0.0) >= 0);
    }
    sw_settle_span_t span;
    if (sw_risk_finish(R->risk, 0, &span)) {
        R->closed_spans++;
        R->closed_micro += span.impacts;
    }
    sw_engine_destroy(e);
    return R;
}

static void rig_free(rig_t *R)
{
    sw_risk_destroy(R->risk);
    sw_reserve_destroy(R->ref);
    free(R);
}

/* At 10 Hz over 4 s of samples: 40 evaluations, the k-th at the first
 * sample at or after 0.1 k s; each value the reserve's own for that state;
 * the minimum that of those values. */
static void test_rate_and_values(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rig_t *R = run(&sc, 6.0, 0.0 /* the default: 10 Hz */);
    assert_int_equal(R->evals, 40);
    for (int k = 0; k < R->evals; k++)
        assert_true(R->eval_t[k] >= 0.1 * k - 1e-9 &&
                    R->eval_t[k] <= 0.1 * k + 1.0 / RATE_HZ + 1e-9);
    assert_true(R->worst_diff == 0.0); /* deterministic: the same state, the same value */
    const sw_risk_pkg_t *p = sw_risk_pkg(R->risk, 0);
    assert_int_equal(p->evaluations, 40);
    assert_true(p->min_reserve_g == R->ref_min && p->min_reserve_time == R->ref_min_t);
    /* the crate rocked: its reserve fell below the one at rest */
    sw_reserve_result_t rest;
    sw_reserve_rest(R->ref, &rest);
    assert_true(p->min_reserve_g < rest.reserve_g);
    rig_free(R);
}

/* Every impact is significant or a micro-impact; significant exactly when
 * the speed before it reaches 0.1 * 2 p sin(alpha/2); the micro-impacts
 * are all in the closed spans. */
static void test_impacts_split(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rig_t *R = run(&sc, 6.0, -1.0 /* no reserve: impacts only */);
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(&sc, &d, "t", NULL, NULL), SW_OK);
    const double min = 0.1 * 2.0 * d.p * sin(d.alpha / 2.0); /* rad/s, alarm.h */
    long sig = 0, micro = 0;
    for (int i = 0; i < R->nev; i++)
        if (R->ev[i].kind == SW_EV_IMPACT) {
            if (fabs(R->ev[i].info) >= min)
                sig++;
            else
                micro++;
        }
    assert_true(sig > 0 && micro > 0); /* a sway that settles */
    const sw_risk_pkg_t *p = sw_risk_pkg(R->risk, 0);
    tu_near(p->impact_min, min, 1e-12);
    assert_int_equal(p->impacts, sig);
    assert_int_equal(p->micro_impacts, micro);
    assert_int_equal(R->reported_impacts, sig);
    assert_int_equal(R->closed_micro, micro);
    assert_int_equal(p->settling_spans, R->closed_spans);
    assert_int_equal(p->evaluations, 0);
    assert_true(isnan(p->reserve_g) && isnan(p->min_reserve_g));
    rig_free(R);
}

/* Replace and reset start the figures again; bad arguments are refused. */
static void test_replace_reset(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    rig_t *R = run(&sc, 6.0, 0.0);
    const sw_scene_t wider = tu_bare(2.0, 1.0);
    char msg[128];
    assert_int_equal(sw_risk_replace(R->risk, 0, &wider, msg, sizeof msg), SW_OK);
    const sw_risk_pkg_t *p = sw_risk_pkg(R->risk, 0);
    assert_int_equal(p->evaluations, 0);
    assert_true(isnan(p->min_reserve_g));
    assert_int_equal(sw_risk_replace(R->risk, 1, &wider, msg, sizeof msg), SW_EINVAL);
    sw_scene_t bad = wider;
    bad.height = -1.0;
    assert_int_not_equal(sw_risk_replace(R->risk, 0, &bad, msg, sizeof msg), SW_OK);
    assert_true(sw_risk_pkg(R->risk, 0)->impact_min > 0.0); /* unchanged */
    sw_output_t out;
    memset(&out, 0, sizeof out);
    out.pkg = 3;
    assert_int_equal(sw_risk_output(R->risk, &out), SW_EINVAL);
    assert_null(sw_risk_pkg(R->risk, 1));
    sw_risk_reset(R->risk);
    assert_int_equal(sw_risk_pkg(R->risk, 0)->impacts, 0);
    rig_free(R);
}

/* A scene whose pulse runs would need more steps than allowed: the
 * reserve refuses it (SW_ETOOBIG) exactly above the count (pulse T plus 10
 * rocking periods of free motion) / (the shorter of 2T and the rocking
 * period, over 24); risk goes on without it and says why. */
static void test_too_stiff(void **state)
{
    (void)state;
    const sw_scene_t sc = tu_bare(2.0, 0.728);
    sw_derived_t d;
    assert_int_equal(sw_scene_validate(&sc, &d, "t", NULL, NULL), SW_OK);
    const double T = sc.design_pulse[0];    /* s */
    const double period = 2.0 * M_PI / d.p; /* s */
    const double steps = (T + 10.0 * period) / (fmin(2.0 * T, period) / 24.0);
    sw_reserve_opts_t o;
    memset(&o, 0, sizeof o);
    int err = 0;
    char msg[256] = "";
    o.max_run_steps = steps * (1.0 - 1e-9);
    assert_null(sw_reserve_create(&sc, &o, &err, msg, sizeof msg));
    assert_int_equal(err, SW_ETOOBIG);
    assert_non_null(strstr(msg, "too stiff"));
    o.max_run_steps = steps * (1.0 + 1e-9);
    sw_reserve_t *ok = sw_reserve_create(&sc, &o, &err, msg, sizeof msg);
    assert_non_null(ok);
    sw_reserve_destroy(ok);

    sw_risk_opts_t ro;
    memset(&ro, 0, sizeof ro);
    ro.reserve.max_run_steps = steps / 2.0;
    sw_risk_t *r = sw_risk_create(&sc, 1, &ro, &err, msg, sizeof msg);
    assert_non_null(r);
    const sw_risk_pkg_t *p = sw_risk_pkg(r, 0);
    assert_non_null(p->no_reserve);
    assert_non_null(strstr(p->no_reserve, "too stiff"));
    sw_output_t out;
    memset(&out, 0, sizeof out);
    out.state.phase = SW_PHASE_STUCK;
    assert_int_equal(sw_risk_output(r, &out), 0); /* nothing to evaluate */
    assert_int_equal(p->evaluations, 0);
    assert_true(isnan(p->reserve_g) && isnan(p->rest_reserve_g));
    assert_true(p->impact_min > 0.0); /* the impacts still count */
    /* a reload keeps saying why (the reason is the object's, not a copy's) */
    assert_int_equal(sw_risk_replace(r, 0, &sc, msg, sizeof msg), SW_OK);
    p = sw_risk_pkg(r, 0);
    assert_non_null(p->no_reserve);
    assert_non_null(strstr(p->no_reserve, "too stiff"));
    sw_risk_destroy(r);

    /* with the default limit the crate has its reserve */
    r = sw_risk_create(&sc, 1, NULL, &err, msg, sizeof msg);
    assert_non_null(r);
    assert_null(sw_risk_pkg(r, 0)->no_reserve);
    sw_risk_destroy(r);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rate_and_values),
        cmocka_unit_test(test_impacts_split),
        cmocka_unit_test(test_replace_reset),
        cmocka_unit_test(test_too_stiff),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
