/* SPDX-License-Identifier: GPL-3.0-or-later */
/* forensics.h - after an incident, what a recorded log did to each
 * package and what would have saved it (docs/forensics.md).
 *
 * A forensics object holds the log as the input gate handed it to the
 * engine (push each sample from the gate's take callback, gate.h:
 * SI units, bridged gaps and restarts included), because its searches
 * run the recording many times and reading and parsing it for each trial
 * would cost more than the physics.  From the held log it computes, for
 * every package, the what-if cases (whatif.h: the scene as given, on the
 * bed, on the typical supports of a catalogue or the caller's, in other
 * sizes), the safety factor of each (safety.h) and their smallest
 * reserves (reserve.h), all searches at once on the caller's number of
 * threads, with results that do not depend on it.  It does no I/O.
 *
 * Allocation: the cases in sw_forensics_create(); the held log grows
 * geometrically (doubling) up to max_samples as samples are pushed, so
 * a log of n samples costs about log2(n) allocations, never one per
 * sample; the searches allocate while they run (sw_whatif_safety). */
#ifndef SWAYWATCH_FORENSICS_H
#define SWAYWATCH_FORENSICS_H

#include <stddef.h>

#include "engine.h"
#include "export.h"
#include "risk.h"
#include "run.h"
#include "safety.h"
#include "scene.h"
#include "search.h"
#include "whatif.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sw_forensics sw_forensics_t;

typedef struct {
    sw_run_opts_t run;       /* every trial's run: the replay's engine options, and settle
                                (s; < 0: no free motion after the log) */
    sw_search_opts_t search; /* the safety factor's scan and bisection */
    sw_whatif_opts_t whatif; /* which cases (read in create only) */
    int threads;             /* worker threads; 0 or 1 = the calling thread alone */
    size_t max_samples;      /* samples held at most; 0 = no limit */
    double reserve_rate;     /* Hz of log time: the cases' smallest reserves' states */
    long reserve_evals;      /* a case's smallest reserve: evaluations at most (0: no limit) */
    void (*progress)(void *user, const sw_safety_progress_t *p); /* may be NULL: as
                                sw_safety_opts_t's, during sw_forensics_safety() */
    void *user;
} sw_forensics_opts_t;

/* A forensics object for the n scenes (validated) with options o: the
 * cases built, no sample held.  NULL on failure, with *err (may be NULL):
 * SW_EINVAL or SW_ENOMEM. */
SW_API sw_forensics_t *sw_forensics_create(const sw_scene_t *scenes, size_t n,
                                           const sw_forensics_opts_t *o, int *err);
/* Free everything; NULL is accepted. */
SW_API void sw_forensics_destroy(sw_forensics_t *F);

/* One sample as the gate handed it to the engine (restart: the packages
 * restarted from rest before it).  SW_OK; SW_ETOOBIG once one more than
 * max_samples is offered, SW_ENOMEM when the log could not grow: the
 * sample is not kept, nor any after it (the same status again). */
SW_API int sw_forensics_push(sw_forensics_t *F, double t, double a_g, double a_z, int restart);
/* The same with the lateral acceleration a_y (m/s^2, across the truck, as
 * sw_engine_push_lat takes it): each package with a depth is then searched
 * in its lateral plane too (sw_forensics_factor).  A log is held with a_y
 * from its first sample or not at all: mixing the two calls is refused
 * (SW_EINVAL, the sample not kept). */
SW_API int sw_forensics_push_lat(sw_forensics_t *F, double t, double a_g, double a_y, double a_z,
                                 int restart);
/* SW_OK, or what stopped the holding (SW_ETOOBIG, SW_ENOMEM). */
SW_API int sw_forensics_status(const sw_forensics_t *F);
/* The log held so far (a_z NULL when every sample's was 0); valid until
 * the next push or destroy. */
SW_API const sw_log_t *sw_forensics_log(const sw_forensics_t *F);
/* The held log with the lateral acceleration in a_g (the same t, a_z and
 * restarts), or NULL when it has none. */
SW_API const sw_log_t *sw_forensics_log_lat(const sw_forensics_t *F);

/* The held log into engine e (made for the same scenes, with opts.lateral
 * when the log has a lateral acceleration), exactly as the
 * replay's engine had it (its restarts from rest before the same
 * samples), up to the first sample after t_end (s); when that is the end
 * of the log, the settling after it (sw_engine_finish(e, settle), when
 * settle > 0). */
SW_API void sw_forensics_rerun(const sw_forensics_t *F, sw_engine_t *e, double t_end,
                               double settle);

/* The safety factor of every available case on the held log
 * (sw_whatif_safety()), and with a lateral acceleration held, that of the
 * lateral plane of every package with a depth on it.  SW_OK, or
 * SW_ENOMEM. */
SW_API int sw_forensics_safety(sw_forensics_t *F);
/* The smallest reserve of every case: the scenes as given from the
 * replay's risk (made with reserve_rate; NULL: not theirs), the other
 * cases by sw_whatif_reserve() on the held log.  SW_OK, or SW_ENOMEM. */
SW_API int sw_forensics_reserve(sw_forensics_t *F, const sw_risk_t *replay);

/* The safety factor of package k with both horizontal axes scaled
 * together.  The planes are driven each by its own axis (physics.md, "The
 * lateral plane"), so the package overturns at a scale when either plane
 * does: its factor is the smaller plane's, the plane that gives out first
 * (for a log it survived, a weaker overturning shock of either plane
 * counts, the smaller; the search range is the smaller of the two).
 * With one plane (no depth, no lateral acceleration, or the lateral
 * search not available), sf is the scene case's and planes 1. */
typedef struct {
    int planes;                      /* 1 or 2 */
    sw_plane first;                  /* the plane that gives out first (SW_PLANE_LONG with
                                        one; on a tie, along the truck) */
    sw_safety_t sf;                  /* the package's: factor, its safe end, overturned... */
    const sw_whatif_case_t *lateral; /* the lateral plane's own case (its scene over the
                                        depth, its search), or NULL */
    sw_plane worse; /* the plane of the verdict at scale 1 (sw_summary_worse's order on
                       sf.at_one of each plane); SW_PLANE_LONG with one */
} sw_forensics_factor_t;
/* SW_OK, or SW_EINVAL for no such package.  After sw_forensics_safety(). */
SW_API int sw_forensics_factor(const sw_forensics_t *F, size_t k, sw_forensics_factor_t *out);
/* The same for what-if case i (sw_forensics_cases()): the case in both
 * planes, its lateral plane over the case's depth with the case's
 * support.  SW_OK, or SW_EINVAL for no such case. */
SW_API int sw_forensics_case_factor(const sw_forensics_t *F, size_t i, sw_forensics_factor_t *out);
/* What-if case i's verdict on the held log, one for every form that says
 * it (after sw_forensics_safety(); its reserve after
 * sw_forensics_reserve()).  A case is judged when its search ran in each
 * plane it has: a package with a depth on a log with a lateral
 * acceleration has two, and a case whose plane across was not searched
 * has no verdict (it may have tipped sideways), not the verdict along.
 * Judged in two planes, its run at scale 1 is the worse plane's
 * (factor.worse) and its smallest reserve the smaller of the two planes';
 * where a plane has none, the case has none known: the plane along the
 * truck when it says why it has none (reserve_note), else the one
 * across. */
typedef struct {
    int planes;        /* the planes it has: 2 with a depth and a lateral acceleration held */
    int judged;        /* searched in each plane it has; 0: note says why not */
    sw_plane unjudged; /* not judged: the plane that was not (SW_PLANE_LAT: the
                          plane across, the one along being searched or not) */
    const char *note;  /* not judged: why (that plane's case's note); else "" */
    int upright;       /* judged, and upright at scale 1 in each plane */
    int saves;         /* upright, and not the scene as given: a support or a size that
                          would have saved its package where the scene did not */
    sw_forensics_factor_t factor;    /* sw_forensics_case_factor()'s: one plane or both */
    const sw_whatif_case_t *run;     /* judged: the case (or its lateral plane) whose
                                        sf.at_one is its run at scale 1; else NULL */
    const sw_whatif_case_t *reserve; /* judged: the one whose smallest reserve is the
                                        case's (has_reserve 0: none known, reserve_note
                                        says why); else NULL */
} sw_forensics_verdict_t;
/* SW_OK, or SW_EINVAL for no such case. */
SW_API int sw_forensics_case_verdict(const sw_forensics_t *F, size_t i,
                                     sw_forensics_verdict_t *out);
/* The runs every search took (the trials of the safety factors of each
 * available case and of each lateral plane searched). */
SW_API long sw_forensics_trials(const sw_forensics_t *F);

/* Every case's lateral plane, parallel to sw_forensics_cases() (*n of
 * them; available says whether it was searched, note why not), or NULL
 * (*n 0) when the log has no lateral acceleration.  Their smallest
 * reserves are computed by sw_forensics_reserve() on the lateral
 * acceleration, the scenes as given's included. */
SW_API const sw_whatif_case_t *sw_forensics_lateral_cases(const sw_forensics_t *F, size_t *n);
/* Package k's lateral plane as a case (its scene, its search once
 * sw_forensics_safety() ran; available says whether it was searched), or
 * NULL when the scene has no depth or the log no lateral acceleration. */
SW_API const sw_whatif_case_t *sw_forensics_lateral_case(const sw_forensics_t *F, size_t k);

/* Every package's cases, package by package, each package's first the
 * scene as given (*n of them); owned by F.  A caller may rewrite a
 * case's notes for its users (naming its own options). */
SW_API sw_whatif_case_t *sw_forensics_cases(sw_forensics_t *F, size_t *n);
/* The case of package k as given, or NULL. */
SW_API const sw_whatif_case_t *sw_forensics_scene_case(const sw_forensics_t *F, size_t k);

#ifdef __cplusplus
}
#endif
#endif
