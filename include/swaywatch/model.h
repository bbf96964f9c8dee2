/* SPDX-License-Identifier: GPL-3.0-or-later */
/* model.h - the state of a package and pure functions of the rocking
 * models (physics.md): margins to overturn, energies, impact ratios, and
 * the cushion's static deflection and natural frequencies.  No allocation,
 * no I/O, no state. */
#ifndef SWAYWATCH_MODEL_H
#define SWAYWATCH_MODEL_H

#include "export.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    SW_PHASE_STUCK = 0,     /* package moves with its support (theta = 0) */
    SW_PHASE_ROCKING = 1,   /* rocking about a base corner (bare/frame), or
                               moving on the cushion (cushion) */
    SW_PHASE_OVERTURNED = 2 /* |theta| reached pi/2: frozen */
} sw_phase;

/* State of one package.  Unused coordinates of simpler models stay 0. */
typedef struct {
    double u, u_dot;         /* m, m/s: frame displacement relative to the bed */
    double theta, theta_dot; /* rad, rad/s: tilt, > 0 top forward */
    double z, z_dot;         /* m, m/s: cushion compression at the base midpoint */
    sw_phase phase;
    int side; /* +1 rocking about the front corner, -1 the rear, 0 stuck;
                 on a cushion the sign of theta */
} sw_state_t;

/* "stuck", "rocking", "overturned" (the state CSV's phase column);
 * "unknown" for a value outside the enum. */
SW_API const char *sw_phase_name(sw_phase p);

/* Margin to overturn of a rigidly rocking package (bare, or frame with the
 * package's energy relative to the frame): 1 at rest, 0 at the edge, < 0
 * beyond.  r is the impact ratio (eta for bare, r_frame for the frame). */
SW_API double sw_margin_rocking(const sw_derived_t *d, double r, double theta, double theta_dot);

/* margin_bound of physics.md for the frame: 1 - E_tot / (m g R (1 - cos a)),
 * a guarantee once the excitation stops.  g_eff in m/s^2. */
SW_API double sw_margin_bound_frame(const sw_derived_t *d, double g_eff, const sw_state_t *s);

/* Total mechanical energy per unit package mass (J/kg) of the frame model
 * while rocking or stuck: kinetic + gravity + bearing strain, gravity
 * measured from the upright package. */
SW_API double sw_energy_frame(const sw_derived_t *d, double g_eff, const sw_state_t *s);

/* Energy of the bare block per unit mass (J/kg), from upright. */
SW_API double sw_energy_bare(const sw_derived_t *d, double g_eff, const sw_state_t *s);

/* --- any model, by d->model ---------------------------------------------
 * Energies per unit package mass (J/kg) from rest, as the margins use
 * them; NAN for a model outside the enum. */

/* The total mechanical energy of state s (package, frame and supports). */
SW_API double sw_model_energy(const sw_derived_t *d, double g, const sw_state_t *s);
/* The energy barrier: the least energy with which |theta| reaches alpha. */
SW_API double sw_model_barrier(const sw_derived_t *d, double g);
/* c (1) with d sqrt(E)/dt <= c |a| for a bed acceleration a (m/s^2), E
 * per unit package mass, while |theta| < alpha: the input's work rate
 * over the centre of mass's largest horizontal speed that the kinetic
 * energy allows (docs/reserve.md, the energy bound). */
SW_API double sw_model_work_rate(const sw_derived_t *d);
/* 1 if state s can no longer change once the input stops: overturned, or
 * standing where nothing left in it can lift the package again (on a
 * frame, the bearings' remaining energy cannot drive the support's
 * acceleration up to g tan(alpha)); 0 if it may still move, or if the
 * model cannot prove it. */
SW_API int sw_model_settled(const sw_derived_t *d, double g, const sw_state_t *s);

/* One mode of a scene linearised about rest, damping included: the
 * eigenvalue lambda = re + i im (1/s) with re <= 0 and im >= 0 (its
 * conjugate is implied), omega = |lambda| (rad/s), zeta = -re / |lambda|
 * (1 for a real root, whatever the mode's own damping ratio), and what it
 * is ("the bearing mode", ...). */
typedef struct {
    double re, im;    /* 1/s */
    double omega;     /* rad/s */
    double zeta;      /* 1 */
    const char *name; /* static text */
} sw_mode_t;

#define SW_MODES_MAX 8

/* The modes an explicit fixed step must keep inside its stability region
 * (sw_scheme_stable_dt), at most SW_MODES_MAX of them into m; returns how
 * many.  A rocking block on the bed is a saddle, lambda = +-p sqrt(cos(alpha
 * - |theta|)): its decaying root at its fastest (|theta| = alpha), -p
 * (-p / sqrt(1 - 3 gamma / 4) on a frame, where the package's inertia
 * seen by the frame is least); the growing root is the motion itself, not
 * an instability of a scheme.  A frame adds its bearing mode standing
 * (lambda^2 + 2 zeta_b w_b lambda + w_b^2 = 0) and while the package rocks
 * (the inertia factor D = 1 - 3 gamma / 4 on lambda^2).  A cushion has its
 * vertical mode (tangent stiffness, zeta_c) and its rocking mode about
 * rest (coupled to the frame's, if any: the roots of sw_cushion_omega_max).
 * g in m/s^2 (the scene's).  0 for a model outside the enum. */
SW_API int sw_model_modes(const sw_derived_t *d, double g, sw_mode_t m[SW_MODES_MAX]);

/* The landing of a rigid package from free flight (physics.md, "Free
 * flight") on the corner on side s (+1 the front) at tilt theta (rad):
 * theta' after it (rad/s), from theta' = theta_dot in the air, the centre
 * of mass's velocity (vx, vy) and the support's u_dot (m/s, all relative
 * to the bed; u_dot 0 and gamma 0 on the bed).  It keeps the package's
 * angular momentum about that corner and the horizontal momentum of
 * package and frame, with no bounce and no slide:
 *   (4R^2/3 - gamma r_y^2) theta'+ = R^2/3 theta' - r_x vy + (1 - gamma)
 *   r_y (vx - u_dot), r = (-s R sin(alpha - s theta), R cos(alpha - s theta))
 * the vector from the corner to the centre of mass.  *u_dot_after (may be
 * NULL) gets the support's velocity after it.  With the velocities of
 * rocking about the other corner at theta = 0 it is the impact map: eta
 * on the bed, r_frame on a frame. */
SW_API double sw_landing_map(const sw_derived_t *d, int s, double theta, double theta_dot,
                             double vx, double vy, double u_dot, double *u_dot_after);

/* --- cushion (scene 3) ---------------------------------------------------
 * d comes from sw_scene_validate() of a cushion scene; g is the gravity to
 * use (m/s^2, the scene's g, or g_eff = g + a_z). */

/* Static deflection z_B at rest (m): the root of K z + B3 z^3 = m g. */
SW_API double sw_cushion_static_deflection(const sw_derived_t *d, double g);

/* Undamped natural frequencies (rad/s) about rest, with the tangent
 * stiffness K_t = K + 3 B3 z_s^2: vertical sqrt(K_t/m) and rocking
 * sqrt((K_t b^2/3 - m g h) / (I_C + m h^2)) (rocking about B with the frame,
 * if any, held fixed).  Either pointer may be NULL. */
SW_API void sw_cushion_frequencies(const sw_derived_t *d, double g, double *omega_z,
                                   double *omega_theta);

/* The fastest rate of the model linearised about rest (rad/s): the
 * largest |lambda| of the vertical mode and of the rocking mode (coupled
 * to the frame, if any), damping included -- an overdamped mode's fast
 * real root exceeds its natural frequency: 3.7 omega_c at zeta_c = 2.
 * This is the scene's omega_max, the bound for an explicit step; the
 * engine shortens the step further in states stiffer than rest. */
SW_API double sw_cushion_omega_max(const sw_derived_t *d, double g);

/* The energy barrier (J/kg): the least potential energy (gravity + cushion
 * strain, from rest) at |theta| = alpha. */
SW_API double sw_cushion_barrier(const sw_derived_t *d, double g);

/* Total mechanical energy per unit package mass (J/kg) from rest: kinetic
 * (package and frame) + gravity + cushion strain + bearing strain. */
SW_API double sw_energy_cushion(const sw_derived_t *d, double g_eff, const sw_state_t *s);

/* margin and margin_bound of physics.md for the cushion (either pointer
 * may be NULL).  margin: 1 - (package energy relative to its support) /
 * barrier inside |theta| < alpha, <= 0 beyond; margin_bound: the same with
 * the total energy (frame and bearing included), a guarantee once the
 * excitation stops.  No impact factor: nothing on a cushion impacts.
 * docs/cushion.md gives their limits. */
SW_API void sw_margin_cushion(const sw_derived_t *d, double g_eff, const sw_state_t *s,
                              double *margin, double *margin_bound);

#ifdef __cplusplus
}
#endif
#endif
