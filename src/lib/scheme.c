/* scheme.c - the table of time-stepping schemes, looked up by name like
 * GSL's step types.  Fixed-step explicit Runge-Kutta schemes are written out
 * here (GSL's rk4 does step doubling, 11 evaluations a step); the adaptive
 * schemes are GSL odeiv2 steppers driven by the engine with error control.
 * The implicit ones (rk4imp, bsimp, msbdf) are offered for stiff cushions
 * (docs/cushion.md measures them against rkck, the default there); they
 * need the Jacobian (GSL does not check: without one they crash), which is
 * taken here by forward differences.
 *
 * stab is the scheme's stability bound |lambda h| for the fastest mode of a
 * scene (negative real axis: Euler and Heun 2, RK4 2.785; RK4 also covers
 * the imaginary axis up to 2.83, Euler and Heun do not, so on an undamped
 * oscillation they are weakly unstable at any h: their error stays bounded
 * over a run only for omega h << 1). */
#include <math.h>
#include <string.h>

#include "internal.h"
#include "model_rigid.h"

/* The fixed-step schemes are written once, as inline bodies taking the
 * model and the state's length; the step functions in the table call them
 * with constants, so that the bare and frame models each get a body with
 * their right-hand side inlined into every stage (the cushion's is a
 * call).  The input is evaluated once per distinct stage time. */

/* One stage: f = y'(t, y), with the input (ag, ge) already at t for a bare
 * or framed package (the cushion evaluates its own). */
static SW_ALWAYS_INLINE void stage(sw_pkg_t *P, sw_model_kind model, double t, double ag,
                                   double ge, const double y[], double f[])
{
    if (model == SW_MODEL_CUSHION) sw_cushion_rhs(P, t, y, f);
    else sw_rigid_rhs_of(P, model, ag, ge, y, f);
}

static SW_ALWAYS_INLINE void stage_input(const sw_pkg_t *P, sw_model_kind model, double t,
                                         double *ag, double *ge)
{
    if (model == SW_MODEL_CUSHION) return;
    *ag = sw_input_ag(P->in, t);
    *ge = sw_input_geff(P, t);
}

static SW_ALWAYS_INLINE void euler_of(sw_pkg_t *P, sw_model_kind model, int n, double t,
                                      double h, const double y[], double yout[])
{
    double k1[SW_NMAX], ag = 0.0, ge = 0.0;
    stage_input(P, model, t, &ag, &ge);
    stage(P, model, t, ag, ge, y, k1);
    for (int i = 0; i < n; i++) yout[i] = y[i] + h * k1[i];
}

static SW_ALWAYS_INLINE void heun_of(sw_pkg_t *P, sw_model_kind model, int n, double t, double h,
                                     const double y[], double yout[])
{
    double k1[SW_NMAX], k2[SW_NMAX], yt[SW_NMAX], ag = 0.0, ge = 0.0;
    stage_input(P, model, t, &ag, &ge);
    stage(P, model, t, ag, ge, y, k1);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h * k1[i];
    stage_input(P, model, t + h, &ag, &ge);
    stage(P, model, t + h, ag, ge, yt, k2);
    for (int i = 0; i < n; i++) yout[i] = y[i] + 0.5 * h * (k1[i] + k2[i]);
}

static SW_ALWAYS_INLINE void rk4_of(sw_pkg_t *P, sw_model_kind model, int n, double t, double h,
                                    const double y[], double yout[])
{
    double k1[SW_NMAX], k2[SW_NMAX], k3[SW_NMAX], k4[SW_NMAX], yt[SW_NMAX];
    double ag = 0.0, ge = 0.0;
    const double h2 = 0.5 * h;
    stage_input(P, model, t, &ag, &ge);
    stage(P, model, t, ag, ge, y, k1);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h2 * k1[i];
    stage_input(P, model, t + h2, &ag, &ge);
    stage(P, model, t + h2, ag, ge, yt, k2);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h2 * k2[i];
    stage(P, model, t + h2, ag, ge, yt, k3);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h * k3[i];
    stage_input(P, model, t + h, &ag, &ge);
    stage(P, model, t + h, ag, ge, yt, k4);
    for (int i = 0; i < n; i++)
        yout[i] = y[i] + (h / 6.0) * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

/* A table entry per scheme; the model picks the body. */
#define SW_FIXED_STEP(name, body)                                                          \
    static void name(sw_pkg_t *P, double t, double h, const double y[], double yout[])     \
    {                                                                                      \
        switch (P->d.model) {                                                              \
        case SW_MODEL_BARE: body(P, SW_MODEL_BARE, 2, t, h, y, yout); return;              \
        case SW_MODEL_FRAME: body(P, SW_MODEL_FRAME, 4, t, h, y, yout); return;            \
        default: body(P, SW_MODEL_CUSHION, P->n, t, h, y, yout); return;                   \
        }                                                                                  \
    }
SW_FIXED_STEP(euler_step, euler_of)
SW_FIXED_STEP(heun_step, heun_of)
SW_FIXED_STEP(rk4_step, rk4_of)

int sw_model_jacobian(double t, const double y[], double *dfdy, double dfdt[], void *pkg)
{
    /* Forward differences, step sqrt(eps) times the component's size or
     * its typical size (the model's right-hand sides are only piecewise
     * smooth: a contact end or a clamp may lie inside a step, which Newton
     * iterations tolerate). */
    sw_pkg_t *P = pkg;
    const int n = P->n;
    const double rt_eps = 1.4901161193847656e-08; /* sqrt(DBL_EPSILON) */
    double f0[SW_NMAX], f1[SW_NMAX], yp[SW_NMAX];
    sw_model_rhs(t, y, f0, P);
    memcpy(yp, y, sizeof(double) * (size_t)n);
    for (int j = 0; j < n; j++) {
        yp[j] = y[j] + rt_eps * (fabs(y[j]) + P->yscale[j]);
        const double dj = yp[j] - y[j]; /* the step as represented */
        sw_model_rhs(t, yp, f1, P);
        for (int i = 0; i < n; i++) dfdy[i * n + j] = (f1[i] - f0[i]) / dj;
        yp[j] = y[j];
    }
    const double tp = t + rt_eps * fmax(fabs(t), 1e-3), dt = tp - t;
    sw_model_rhs(tp, y, f1, P);
    for (int i = 0; i < n; i++) dfdt[i] = (f1[i] - f0[i]) / dt;
    return GSL_SUCCESS;
}

/* gsl_odeiv2_step_* are variables, not constants: store their addresses. */
static const sw_scheme_t schemes[] = {
    {"rk4", 4, 0, 2.785, 1e-3, rk4_step, NULL, 0},
    {"heun", 2, 0, 2.0, 2.5e-4, heun_step, NULL, 0},
    {"euler", 1, 0, 2.0, 1e-5, euler_step, NULL, 0},
    {"rkf45", 5, 1, 0.0, 1e-3, NULL, &gsl_odeiv2_step_rkf45, 0},
    {"rkck", 5, 1, 0.0, 1e-3, NULL, &gsl_odeiv2_step_rkck, 0},
    {"rk8pd", 8, 1, 0.0, 1e-3, NULL, &gsl_odeiv2_step_rk8pd, 0},
    /* implicit Gauss RK (step doubling for the error), Bader-Deuflhard
     * semi-implicit extrapolation, variable-order BDF; order as GSL reports
     * it (the highest for bsimp and msbdf, which vary it) */
    {"rk4imp", 4, 1, 0.0, 1e-3, NULL, &gsl_odeiv2_step_rk4imp, 1},
    {"bsimp", 12, 1, 0.0, 1e-3, NULL, &gsl_odeiv2_step_bsimp, 1},
    {"msbdf", 5, 1, 0.0, 1e-3, NULL, &gsl_odeiv2_step_msbdf, 2},
};

const sw_scheme_t *sw_scheme_at(size_t i)
{
    return i < sizeof schemes / sizeof schemes[0] ? &schemes[i] : NULL;
}

const sw_scheme_t *sw_scheme_lookup(const char *name)
{
    for (size_t i = 0; i < sizeof schemes / sizeof schemes[0]; i++)
        if (name && !strcmp(name, schemes[i].name)) return &schemes[i];
    return NULL;
}

const char *sw_scheme_name(const sw_scheme_t *s)
{
    return s->name;
}

int sw_scheme_order(const sw_scheme_t *s)
{
    return s->order;
}

int sw_scheme_adaptive(const sw_scheme_t *s)
{
    return s->adaptive;
}

double sw_scheme_default_dt(const sw_scheme_t *s)
{
    return s->default_dt;
}
