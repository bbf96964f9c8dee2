/* SPDX-License-Identifier: GPL-3.0-or-later */
/* whatif.h - would another support, or another size, have saved it?
 *
 * For each package of a log (a scene), the what-if cases are the same log
 * run with the package as given, alone on the bed, on the typical supports
 * of a catalogue (a frame on bearings, a cushion; or, instead of those of
 * its kind, the caller's frame and cushion) and in other sizes.  Each
 * case's safety factor (sweep.h: the smallest scale of the recorded
 * acceleration that overturns it) and its smallest reserve along the log
 * (reserve.h) answer the question for it.
 *
 * A case that puts the package on a support of the catalogue or the
 * caller's has that support in both planes (the scene's lateral_* values
 * of that support are dropped); the bed and the sizes keep the scene's
 * supports as they are, across the truck too.
 *
 * The catalogue stands for real products by the natural frequency they
 * have with the package on them, as their makers state it for a support
 * loaded as intended (docs/forensics.md says where each number comes
 * from); damping ratios the scene does not give are the paper's Table I
 * values.  The cases are the caller's array: build them, then search and
 * evaluate them; no I/O, no global state. */
#ifndef SWAYWATCH_WHATIF_H
#define SWAYWATCH_WHATIF_H

#include <stddef.h>

#include "export.h"
#include "reserve.h"
#include "run.h"
#include "safety.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A typical support of the catalogue. */
typedef struct {
    const char *name;       /* "frame, soft bearings" */
    int cushion;            /* 0 a frame on bearings, 1 a cushion; on the bed */
    double hz;              /* Hz: natural frequency with the package on it */
    double zeta;            /* damping ratio */
    const char *stands_for; /* what real supports it stands for */
} sw_support_t;

/* The catalogue's rows, *n of them. */
SW_API const sw_support_t *sw_whatif_supports(size_t *n);

/* Damping ratio of a frame or a cushion the scene does not give (the
 * paper's Table I), and the mass of a frame it does not give, per kg of
 * the package (m_b = m/4: gamma = 0.8, Table I). */
#define SW_WHATIF_ZETA 0.1
#define SW_WHATIF_FRAME_MASS_RATIO 0.25

/* Reserve evaluations at most per case by default (sw_reserve_log_min's
 * max_evals; the most threatened states first): a case that needs more
 * has its minimum as a bracket. */
#define SW_WHATIF_RESERVE_EVALS 400

/* Which cases: values of the caller's supports are text, as a scene file
 * or sw_scene_set() takes them (NULL or 0: not given).  A frame or a
 * cushion of the caller replaces the catalogue's of its kind; a case
 * that cannot be built says why in its note, naming the member here. */
typedef struct {
    const char *frame_mass; /* kg; NULL: the scene's, else SW_WHATIF_FRAME_MASS_RATIO m */
    double frame_omega;     /* rad/s, the bearings' natural frequency; 0: the scene's */
    const char *frame_zeta; /* NULL: the scene's, else SW_WHATIF_ZETA */
    double cushion_omega;   /* rad/s; 0: the scene's */
    const char *cushion_zeta;
    const double *sizes; /* m: height, width of each other size (2 nsizes values, > 0) */
    size_t nsizes;
    const double *depths; /* m: the depth of each size (nsizes values; 0, or NULL for
                             all: the scene's) */
    int scenes_only;      /* only the scenes as given */
} sw_whatif_opts_t;

typedef struct {
    char name[64]; /* "as given", "bed", "frame, soft bearings", "size 2.4x0.8 m", "size 2.4x0.8x0.6
                      m" */
    const char *stands_for; /* a catalogue row: what real supports it stands for; else NULL */
    size_t pkg;             /* the scene it belongs to (0-based) */
    int is_scene;           /* the scene as given */
    int built;              /* the scene was built and validated: model, derived hold */
    int available;          /* its safety factor is (to be) computed; else note says why */
    char note[256];
    sw_scene_t scene;
    sw_model_kind model;
    sw_derived_t derived;
    int status; /* of the safety factor's search: SW_OK or its error */
    sw_safety_t sf;
    /* the smallest reserve along the log (sw_whatif_reserve, or set by the
     * caller): has_reserve 0 when not computed, reserve_note says why when
     * it could not be */
    int has_reserve, reserve_status;
    sw_reserve_log_t rl;
    char reserve_note[160];
} sw_whatif_case_t;

/* How many cases sw_whatif_cases() makes for n scenes, at most. */
SW_API size_t sw_whatif_max(size_t n, const sw_whatif_opts_t *o);

/* The cases of the n scenes into cs (room for sw_whatif_max()), zeroed
 * first, scene by scene, each scene's first the scene as given; returns
 * how many.  A case that cannot be built is not available. */
SW_API size_t sw_whatif_cases(const sw_scene_t *scenes, size_t n, const sw_whatif_opts_t *o,
                              sw_whatif_case_t *cs);

/* The safety factor of every available case, all searched at once as
 * sw_safety_factors() does (the results do not depend on o->threads).  A
 * case whose search fails is no longer available (note: why).  Allocates
 * while it runs.  SW_OK, or SW_ENOMEM. */
SW_API int sw_whatif_safety(sw_whatif_case_t *cs, size_t n, const sw_log_t *log,
                            const sw_safety_opts_t *o);

/* The smallest reserve along the log (sw_reserve_log_min with o) of every
 * available case that is not a scene as given (a replay has those), on
 * threads threads (the results do not depend on their number).  SW_OK, or
 * SW_ENOMEM. */
SW_API int sw_whatif_reserve(sw_whatif_case_t *cs, size_t n, const sw_log_t *log,
                             const sw_reserve_log_opts_t *o, int threads);
/* The same for case C alone, whatever its availability: has_reserve,
 * reserve_status, rl and reserve_note filled (reserve_status SW_ENOMEM:
 * out of memory). */
SW_API void sw_whatif_reserve_case(sw_whatif_case_t *C, const sw_log_t *log,
                                   const sw_reserve_log_opts_t *o);

#ifdef __cplusplus
}
#endif
#endif
