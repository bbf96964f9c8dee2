/* SPDX-License-Identifier: GPL-3.0-or-later */
/* boundary.h - the overturning boundary curves of physics.md: the lowest
 * overturning pulse amplitude as a function of the pulse frequency, for
 * a scene and optionally a frame that follows the pulse.
 *
 * Units: amplitudes are given as x = a_e / (g tan alpha) (1 = the bed
 * acceleration that just lifts a package standing on the bed), pulse
 * frequencies as omega_e / p.
 *
 * The threaded sweep gives results identical to a single-threaded run,
 * because every point is computed alone, deterministically, into its own
 * slot. */
#ifndef SWAYWATCH_BOUNDARY_H
#define SWAYWATCH_BOUNDARY_H

#include <stddef.h>

#include "export.h"
#include "pulse.h"
#include "run.h"
#include "scene.h"
#include "search.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One curve: a scene, and optionally a frame that follows the pulse. */
typedef struct {
    sw_scene_t scene;
    double bearing_ratio; /* > 0: at every point the frame's omega_b is set to
                             bearing_ratio * omega_e (the paper's omega_b/omega_e); the scene
                             must have a frame.  0: the scene as it is */
} sw_curve_t;

/* The scene of curve c under a pulse of omega_e (rad/s): the curve's scene,
 * with omega_b = bearing_ratio * omega_e when it has a ratio (omega_e <= 0:
 * any pulse; omega_b is then 1 rad/s, for checking and describing the rest
 * of the scene).  Returns SW_OK, or SW_EINVAL (out holds the scene as it
 * is) for a ratio on a scene without a frame. */
SW_API int sw_curve_scene(const sw_curve_t *c, double omega_e, sw_scene_t *out);

typedef void (*sw_progress_fn)(void *user, size_t done, size_t total);

typedef struct {
    sw_pulse_shape shape;
    sw_run_opts_t run;
    sw_search_opts_t search; /* x = a_e/(g tan alpha).  x_min 0 = automatic: the lowest
                                amplitude at which the package can lift at all (1 on the bed;
                                on a frame, 0.99 times the value found from the linear
                                response of the stuck frame, sampled 400 times a period).
                                x_max 0 = 20 */
    int threads;             /* worker threads; 0 or 1 = run in the calling thread */
    sw_progress_fn progress; /* may be NULL; called after each point, from any thread,
                                one call at a time */
    void *user;
} sw_boundary_opts_t;

typedef struct {
    double omega_ratio; /* omega_e / p */
    int status;         /* SW_OK or this point's error */
    double x_lift;      /* lowest amplitude at which the package can lift (search start
                           before the 0.9 factor) */
    sw_threshold_t th;  /* th.found, th.x: the boundary a_e/(g tan alpha) */
} sw_boundary_point_t;

/* The boundary of one curve at one omega_e/p.  Returns the point's status
 * (also stored in out->status); msg (may be NULL) says why on error. */
SW_API int sw_boundary_point(const sw_curve_t *c, double omega_ratio, const sw_boundary_opts_t *o,
                             sw_boundary_point_t *out, char *msg, size_t msglen);

/* Every curve at every ratio; out has ncurves * nratios slots, curve-major
 * (out[c * nratios + i]).  Points run in parallel on o->threads threads.
 * Returns SW_OK if every point succeeded, else the first failing point's
 * status in (curve, ratio) order, with its message in msg. */
SW_API int sw_boundary_sweep(const sw_curve_t *curves, size_t ncurves, const double *ratios,
                             size_t nratios, const sw_boundary_opts_t *o, sw_boundary_point_t *out,
                             char *msg, size_t msglen);

/* ---- a family of curves: scenes x values of scene keys x bearing ratios ---- */

/* One scene key and the values it takes, one curve each ("frame.zeta",
 * "0.05", "0.1": keys and values as sw_scene_set_arg() reads them). */
typedef struct {
    const char *key;
    const char *const *values;
    size_t n;
} sw_vary_t;

/* Does v apply to scene s?  A [frame] or [cushion] key leaves a scene
 * without that section as it is (a bare reference curve stays one curve). */
SW_API int sw_vary_applies(const sw_vary_t *v, const sw_scene_t *s);

#define SW_FAMILY_MAX 1000 /* curves of one family, at most */
#define SW_FAMILY_LABEL 256

/* One curve of a family and its units. */
typedef struct {
    sw_curve_t c;
    char label[SW_FAMILY_LABEL]; /* the scene's name, then " KEY=VALUE" for each value applied
                                    and " wb/we=RATIO" (the ratio as written) */
    double p;                    /* rad/s, the package's rocking frequency */
    double gtan;                 /* m/s^2, g tan alpha of the package: the amplitudes' unit */
} sw_family_curve_t;

/* How many curves the family has: every scene times every combination of
 * the values of the keys that apply to it times every bearing ratio (nbear
 * of them; a scene without a frame: as it is).  *framed (may be NULL): how
 * many scenes have a frame.  The count stops once above SW_FAMILY_MAX. */
SW_API size_t sw_family_count(const sw_scene_t *scenes, size_t nsc, const sw_vary_t *vary,
                              size_t nvary, size_t nbear, size_t *framed);

/* Where a family could not be built: the curve, and the key and the
 * index of its value that was refused (vary SIZE_MAX: the curve's scene
 * did not validate). */
typedef struct {
    size_t curve;
    size_t vary, value;
} sw_family_fail_t;

/* The family's curves into out (sw_family_count() slots), scene-major,
 * then the combinations (the first key's values fastest), then the
 * ratios; each curve's scene checked (at omega_e <= 0, sw_curve_scene())
 * and its units.  bearing_text[i] is ratio i as written, for the labels.
 * Errors go to diag (may be NULL; a scene's origin is the curve's label).
 * Returns SW_OK, or the status of the first value sw_scene_set_arg()
 * refused or SW_EINVAL for a scene that does not validate, with *fail
 * (may be NULL) saying where. */
SW_API int sw_family_build(const sw_scene_t *scenes, size_t nsc, const sw_vary_t *vary,
                           size_t nvary, const double *bearing, const char *const *bearing_text,
                           size_t nbear, sw_family_curve_t *out, sw_diag_fn diag, void *user,
                           sw_family_fail_t *fail);

#ifdef __cplusplus
}
#endif
#endif
