/* internal.h - what the library's modules share and the public API hides:
 * a package's parameters, its integration state, the model's right-hand
 * sides and maps (model.c), the fixed-step schemes (scheme.c). */
#ifndef SWAYWATCH_INTERNAL_H
#define SWAYWATCH_INTERNAL_H

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "swaywatch/engine.h"
#include "swaywatch/scene.h"

#define SW_NMAX 6 /* longest state vector: cushion on a frame (u, theta, z and rates) */

/* The input seen by a package inside one step: linear in time between two
 * samples (a_g = ag0 + ag_slope (t - t0)), or a function (pulses). */
typedef struct {
    double t0;                /* s */
    double ag0, ag_slope;     /* m/s^2, m/s^3 */
    double az0, az_slope;     /* m/s^2, m/s^3 (vertical, up) */
    sw_input_fn fn;           /* if not NULL: a_g = fn(fn_user, t), a_z = 0 */
    void *fn_user;
} sw_input_t;

/* One package: parameters, state, summary, work space.  Everything is
 * allocated once, in sw_engine_create(). */
typedef struct sw_pkg {
    sw_scene_t scene;
    sw_derived_t d;
    double g;          /* m/s^2, nominal gravity */
    double kR;         /* 1/m, 3/(4R) = p^2/g */
    double tan_alpha;
    int n;             /* length of the state vector */
    int ith, idth;     /* indices of theta and theta_dot in y */
    int iu, idu;       /* u, u_dot (-1 without a frame) */
    int iz, idz;       /* z, z_dot (-1 without a cushion) */
    double yscale[SW_NMAX]; /* typical size of each component (finite-difference Jacobian) */
    double e_lift;     /* J/kg, cushion: least energy above rest that lifts an edge */
    int track_rate;    /* cushion: the right-hand side records rate_seen */
    double rate_seen;  /* rad/s, fastest contact rate met by the stages of a step */
    double rate_rest;  /* 1/s, the contact's rate bound at rest (model_cushion.c) */

    /* integration state */
    double t;          /* s */
    double y[SW_NMAX];
    sw_phase phase;
    int side;          /* s = +1 / -1 while rocking */
    const sw_input_t *in;

    /* stepping */
    double h;          /* s, largest internal step for this package */
    gsl_odeiv2_system sys;
    gsl_odeiv2_step *gstep;   /* adaptive schemes only */
    gsl_odeiv2_control *gctl;
    gsl_odeiv2_evolve *gevo;
    double h_adapt;    /* s, GSL's proposed next step */
    gsl_odeiv2_driver gdrv; /* not allocated: hands gctl to GSL's implicit steppers */

    double nj_cache[5]; /* engine.c: exact stuck-frame step of length [0]: g, g', I1, I2 */
    double trig[3];     /* model.c: an angle (NAN: none yet), its sin and cos */
    int beyond_alpha;  /* |theta| >= alpha at the last check */
    double t_lift;     /* s, time of the last uplift */
    int hold;          /* keep the package stuck for one step (see after_impact) */
    sw_summary_t sum;
} sw_pkg_t;

/* --- model.c --- */
void sw_model_setup(sw_pkg_t *P);                  /* layout of y from the scene */
int sw_model_rhs(double t, const double y[], double f[], void *pkg); /* GSL signature */
/* The input at time t (s): a_g, and g_eff = g + a_z (m/s^2).  Inline: a
 * right-hand side evaluates them at every stage. */
static inline double sw_input_ag(const sw_input_t *in, double t)
{
    if (in->fn) return in->fn(in->fn_user, t);
    return in->ag0 + in->ag_slope * (t - in->t0);
}
static inline double sw_input_geff(const sw_pkg_t *P, double t)
{
    const sw_input_t *in = P->in;
    if (in->fn) return P->g;
    return P->g + in->az0 + in->az_slope * (t - in->t0);
}
/* Absolute acceleration of the package's support (m/s^2): a_g for bare,
 * a_g + u'' for frame, given f = y'. */
double sw_model_support_accel(const sw_pkg_t *P, double t, const double f[]);
void sw_model_impact(sw_pkg_t *P);                  /* at theta = 0: velocity map, side flips */
void sw_model_to_state(const sw_pkg_t *P, sw_state_t *s);
void sw_model_from_state(sw_pkg_t *P, const sw_state_t *s);
void sw_model_output(const sw_pkg_t *P, double t, sw_output_t *o);
int sw_model_uplift_side(const sw_pkg_t *P, double t); /* +1/-1 if above uplift, 0 else */

/* --- model_cushion.c --- */
/* With P->track_rate set, also raises P->rate_seen to the contact's
 * fastest rate at y (rad/s; omega_max at rest, more where the contact is
 * stiffer, 0 without contact). */
int sw_cushion_rhs(sw_pkg_t *P, double t, const double y[], double f[]);
void sw_cushion_setup(sw_pkg_t *P); /* e_lift, rate_rest; after the layout */
void sw_cushion_rest(sw_pkg_t *P);  /* upright at the static deflection, nominal g */
/* b^2 sin^2(theta) - z |z| (m^2): > 0 while an edge of the base is off the
 * cushion; *der (may be NULL) gets its time derivative. */
double sw_cushion_lift(const sw_pkg_t *P, const double y[], double *der);
/* Energy of motion about rest at nominal g (J/kg): kinetic + gravity +
 * cushion strain + bearing strain. */
double sw_cushion_motion_energy(const sw_pkg_t *P, const double y[]);

/* --- scheme.c --- */
/* Finite-difference Jacobian in GSL's signature, for the implicit schemes. */
int sw_model_jacobian(double t, const double y[], double *dfdy, double dfdt[], void *pkg);
typedef void (*sw_fixed_step_fn)(sw_pkg_t *P, double t, double h, const double y[], double yout[]);
struct sw_scheme {
    const char *name;
    int order;
    int adaptive;
    double stab;       /* |lambda h| bound on the imaginary / negative real axis */
    double default_dt; /* s */
    sw_fixed_step_fn step; /* fixed-step schemes */
    const gsl_odeiv2_step_type *const *gsl_type; /* adaptive schemes */
    int implicit;      /* 0 explicit; 1 implicit one-step (needs the Jacobian and a
                          driver); 2 implicit multistep (msbdf: also cannot
                          re-step from a step's start) */
};

#endif
