/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scheme.h - the time-stepping schemes, a const table looked up by name as
 * GSL's step types are, and the accuracy policy that picks one.
 *
 * Fixed-step: "euler", "heun", "rk4" (explicit Runge-Kutta written out
 * with the model's right-hand side inlined per stage); adaptive through
 * GSL odeiv2: "rkf45", "rkck", "rk8pd", and the implicit "rk4imp",
 * "bsimp", "msbdf" (Jacobian by finite differences). */
#ifndef SWAYWATCH_SCHEME_H
#define SWAYWATCH_SCHEME_H

#include <stddef.h>

#include "export.h"
#include "model.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sw_scheme sw_scheme_t;
SW_API const sw_scheme_t *sw_scheme_lookup(const char *name); /* NULL: no such scheme */
SW_API const sw_scheme_t *sw_scheme_at(size_t i);             /* NULL past the end */
SW_API const char *sw_scheme_name(const sw_scheme_t *s);
SW_API int sw_scheme_order(const sw_scheme_t *s);
SW_API int sw_scheme_adaptive(const sw_scheme_t *s);
/* Non-zero for an implicit scheme (rk4imp, bsimp, msbdf): its step is not
 * bounded by the fastest mode, and costs a Jacobian and a linear solve. */
SW_API int sw_scheme_implicit(const sw_scheme_t *s);
SW_API double sw_scheme_default_dt(const sw_scheme_t *s); /* s */

/* The amplification |R(z)| of one step of a fixed-step scheme at z =
 * lambda h = re + i im: R(z) = 1 + z (euler), 1 + z + z^2/2 (heun),
 * 1 + z + z^2/2 + z^3/6 + z^4/24 (rk4).  The scheme is stable on a mode
 * lambda with step h where |R(lambda h)| <= 1.  NAN for an adaptive scheme
 * (its error control chooses the steps). */
SW_API double sw_scheme_amplification(const sw_scheme_t *s, double re, double im);

/* The largest fixed step (s) that keeps lambda dt of each of the n modes
 * (sw_model_modes) inside the scheme's stability region, every shorter
 * step too; *worst (may be NULL) the index of the mode that sets it (-1:
 * none).  A step that lets a mode grow by less than 1e-6 per period of it
 * counts as stable (rounding; Heun on an undamped mode up to omega dt =
 * 0.011).  0 when no step of at least 1e-4 / omega is stable for some mode
 * (an undamped mode under euler); INFINITY for an adaptive scheme or no
 * mode. */
SW_API double sw_scheme_stable_dt(const sw_scheme_t *s, const sw_mode_t *m, int n, int *worst);

/* Accuracy option: the cheapest scheme and internal step dt (s; 0 = the
 * scheme's default, for the adaptive ones) that kept the error of max|theta|
 * within theta_tol (rad) in the benchmark of docs/accuracy-speed.md, for the
 * model's reference scene (errors of fixed steps grow as (p dt)^order: a
 * package rocking faster than that scene needs a tighter tolerance).
 * *scheme is a static string for sw_engine_opts_t.scheme.  Returns SW_OK,
 * SW_ENOTFOUND when theta_tol is tighter than any setting measured, or
 * SW_EINVAL (theta_tol not > 0, NULL pointers, a model without a table). */
SW_API int sw_scheme_for_accuracy(sw_model_kind model, double theta_tol, const char **scheme,
                                  double *dt);

/* s: the rows were measured on pulses sampled at 1 kHz, where no step is
 * longer than a sample interval.  An engine whose setting the accuracy
 * option chose keeps every step within this, whatever its input (a pulse
 * given as a function, samples further apart), so that an adaptive row
 * holds as measured (rkf45 at rtol 1e-10 in steps of 0.1 s errs by
 * 2.4e-11 rad where its row promises 1e-13). */
#define SW_ACCURACY_HMAX 1e-3

/* The same for n scenes run by one engine: the setting of the scene that
 * needs the most accurate one (adaptive before fixed, then the higher
 * order, then the smaller step).  Invalid scenes give SW_EINVAL; the
 * first scene whose model has no table or no setting fine enough gives
 * that scene's code, with its index in *bad (may be NULL). */
SW_API int sw_scheme_for_accuracy_n(const sw_scene_t *scenes, size_t n, double theta_tol,
                                    const char **scheme, double *dt, size_t *bad);

#define SW_DEFAULT_SCHEME "rk4"
#define SW_DEFAULT_DT 1e-3
/* Used instead when no scheme is given, no dt is forced and a cushion
 * scene is stiff: omega_max * dt > SW_STIFF_OMEGA_DT (docs/cushion.md). */
#define SW_STIFF_SCHEME "rkck"
#define SW_STIFF_OMEGA_DT 0.05

#ifdef __cplusplus
}
#endif
#endif
