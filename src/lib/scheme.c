/* scheme.c - the table of time-stepping schemes, looked up by name like
 * GSL's step types.  Fixed-step explicit Runge-Kutta schemes are written out
 * here (GSL's rk4 does step doubling, 11 evaluations a step); the adaptive
 * schemes are GSL odeiv2 steppers driven by the engine with error control.
 *
 * stab is the scheme's stability bound |lambda h| for the fastest mode of a
 * scene (negative real axis: Euler and Heun 2, RK4 2.785; RK4 also covers
 * the imaginary axis up to 2.83, Euler and Heun do not, so on an undamped
 * oscillation they are weakly unstable at any h: their error stays bounded
 * over a run only for omega h << 1). */
#include <math.h>
#include <string.h>

#include "internal.h"

static void euler_step(sw_pkg_t *P, double t, double h, const double y[], double yout[])
{
    double k1[SW_NMAX];
    sw_model_rhs(t, y, k1, P);
    for (int i = 0; i < P->n; i++) yout[i] = y[i] + h * k1[i];
}

static void heun_step(sw_pkg_t *P, double t, double h, const double y[], double yout[])
{
    double k1[SW_NMAX], k2[SW_NMAX], yt[SW_NMAX];
    const int n = P->n;
    sw_model_rhs(t, y, k1, P);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h * k1[i];
    sw_model_rhs(t + h, yt, k2, P);
    for (int i = 0; i < n; i++) yout[i] = y[i] + 0.5 * h * (k1[i] + k2[i]);
}

static void rk4_step(sw_pkg_t *P, double t, double h, const double y[], double yout[])
{
    double k1[SW_NMAX], k2[SW_NMAX], k3[SW_NMAX], k4[SW_NMAX], yt[SW_NMAX];
    const int n = P->n;
    const double h2 = 0.5 * h;
    sw_model_rhs(t, y, k1, P);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h2 * k1[i];
    sw_model_rhs(t + h2, yt, k2, P);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h2 * k2[i];
    sw_model_rhs(t + h2, yt, k3, P);
    for (int i = 0; i < n; i++) yt[i] = y[i] + h * k3[i];
    sw_model_rhs(t + h, yt, k4, P);
    for (int i = 0; i < n; i++)
        yout[i] = y[i] + (h / 6.0) * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

/* gsl_odeiv2_step_* are variables, not constants: store their addresses. */
static const sw_scheme_t schemes[] = {
    {"rk4", 4, 0, 2.785, 1e-3, rk4_step, NULL},
    {"heun", 2, 0, 2.0, 2.5e-4, heun_step, NULL},
    {"euler", 1, 0, 2.0, 1e-5, euler_step, NULL},
    {"rkf45", 5, 1, 0.0, 1e-3, NULL, &gsl_odeiv2_step_rkf45},
    {"rkck", 5, 1, 0.0, 1e-3, NULL, &gsl_odeiv2_step_rkck},
    {"rk8pd", 8, 1, 0.0, 1e-3, NULL, &gsl_odeiv2_step_rk8pd},
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
