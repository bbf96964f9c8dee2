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

#ifdef __cplusplus
}
#endif
#endif
