/* SPDX-License-Identifier: GPL-3.0-or-later */
/* safety.h - the safety factor of a recorded log: the smallest scale of
 * its longitudinal acceleration (a plain factor) that overturns the
 * package, and whether a weaker shock of the same shape would have.
 *
 * The searches of several scenes run together on worker threads; every
 * result is the same whatever the number of threads. */
#ifndef SWAYWATCH_SAFETY_H
#define SWAYWATCH_SAFETY_H

#include <stddef.h>

#include "export.h"
#include "run.h"
#include "scene.h"
#include "search.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int overturned;         /* the log as recorded (scale 1) overturned the package */
    sw_run_result_t at_one; /* that run */
    int found;              /* a factor was found below the search's x_max */
    double factor;          /* the safety factor: the smallest scale that overturns the
                               package (<= 1 if the log overturned it); if it survived,
                               the smallest scale above 1 that overturns it (every scale
                               from 1 up to it was found safe).  INFINITY if not found */
    double factor_safe;     /* the safe end of the final bracket (just below factor) */
    sw_threshold_t below;   /* scales from the lifting scale up to 1: for a log that
                               survived, below.found means a weaker shock of the same shape
                               would have overturned it (below.x) - it survived by luck */
    sw_threshold_t above;   /* survived only: the search from 1 up (factor = above.x) */
    double lift_scale;      /* the scale at which the package can first lift (estimated on
                               a frame or with vertical acceleration); INFINITY if the log
                               has no longitudinal acceleration */
    double max_scale;       /* the largest scale the search would try (its x_max) */
    long trials;            /* runs of the log, all searches and the recorded one */
} sw_safety_t;

/* The safety factor of a log: the factor by which its longitudinal
 * acceleration would have to be scaled to overturn the package.  so may be
 * NULL; its x_min 0 = automatic (the lifting scale, times 0.9 on a frame,
 * a cushion or with vertical acceleration: below it nothing can lift),
 * x_max 0 = 20 times the scale that lifts a package standing on the bed;
 * step and tol as in sw_threshold_search() (islands are not mapped).
 *
 * The scan takes its grid points four at a time and a bracket is cut in
 * five, keeping the lowest change from safe to overturning, so that the
 * four runs of a round can run in parallel (sw_safety_factors()); the
 * final bracket is tol wide as with bisection, its ends other scales.
 * Every run starts as late as its outcome allows: at the sample before the
 * first that can lift the package at that scale, with the state the
 * package has there (exact on the bed, and across the stretches it stands
 * at rest; to rounding on a frame; to 1e-6 of the second-order error of
 * the linear motion on a cushion on the bed): an hour-long log costs what
 * the stretches that can move the package cost.  at_one, the run of the
 * log as recorded, is made the same way (on a cushion that never lifts,
 * over its largest response).  The search's runs also jump over the
 * stretches in which a frame stands and a cushion cannot lift an edge,
 * keeping each run's outcome, and its peak where the scan's step depends
 * on it (docs/forensics.md).  Returns SW_OK (found or not), or the first
 * error of a trial with a reason in msg. */
SW_API int sw_safety_factor(const sw_scene_t *sc, const sw_log_t *log, const sw_run_opts_t *ro,
                            const sw_search_opts_t *so, sw_safety_t *out, char *msg, size_t msglen);

/* One scene of sw_safety_factors(): the caller sets scene; the rest is
 * filled. */
typedef struct {
    sw_scene_t scene;
    int status;    /* SW_OK, or the first error of its trials */
    char msg[256]; /* why, on error */
    sw_safety_t sf;
} sw_safety_case_t;

typedef struct {
    size_t cases, cases_done;
    long trials; /* runs of the log made so far, all scenes together */
} sw_safety_progress_t;

typedef struct {
    sw_run_opts_t run;       /* as for sw_safety_factor() */
    sw_search_opts_t search; /* as for sw_safety_factor() */
    int threads;             /* worker threads; 0 or 1 = the calling thread alone */
    void (*progress)(void *user, const sw_safety_progress_t *p); /* may be NULL; after
                                each trial, from any thread, one call at a time */
    void *user;
    /* Work of the caller's own that needs none of the searches' results
     * (may be none): side(side_user, k) for every k below sides, once
     * each, on any of the threads, whenever no trial is waiting for one
     * (a round's last long trial leaves the others idle), so that it
     * costs no time of its own on free cores.  Done when the call
     * returns. */
    size_t sides;
    void (*side)(void *side_user, size_t k);
    void *side_user;
} sw_safety_opts_t;

/* The safety factors of n scenes for one log, all searches at once on
 * o->threads threads: each scene's result is what sw_safety_factor() gives
 * it, whatever the number of threads.  Allocates (a few bytes per sample
 * and scene while it runs).  Returns SW_OK if every scene succeeded, else
 * the first failing scene's status (cases[i].msg says why), or SW_EINVAL /
 * SW_ENOMEM. */
SW_API int sw_safety_factors(sw_safety_case_t *cases, size_t n, const sw_log_t *log,
                             const sw_safety_opts_t *o);

#ifdef __cplusplus
}
#endif
#endif
