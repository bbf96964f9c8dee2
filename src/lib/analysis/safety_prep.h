/* SPDX-License-Identifier: GPL-3.0-or-later */
/* safety_prep.h - the checkpoints of the safety-factor trials (safety_prep.c)
 * and one trial, for the search of safety.c.  Internal. */
#ifndef SWAYWATCH_SAFETY_PREP_H
#define SWAYWATCH_SAFETY_PREP_H

#include <stddef.h>

#include "model_traits.h"
#include "search_int.h"
#include "swaywatch/model.h"
#include "swaywatch/run.h"

#define LIFT_MARGIN_LOG 0.9 /* probes are sampled only at the log's samples */

/* How trials start late, chosen by the model's traits (model_traits.h): none;
 * the input itself lifts the package (lift_direct: the bed); it stands on
 * a linear support (stuck_linear: the frame); its rocking about rest is
 * one linear oscillator (rock_linear: a linear cushion on the bed). */
typedef enum { CK_NONE, CK_DIRECT, CK_STUCK, CK_ROCK } ck_kind;

typedef struct {
    size_t i; /* sample */
    double s; /* the lowest scale at which a sample up to i can lift the package */
} rec_t;

/* What every trial of one scene uses, made once before its search. */
typedef struct {
    const sw_scene_t *sc;
    sw_derived_t d;
    const sw_log_t *log;
    const sw_run_opts_t *ro;
    ck_kind kind;
    double tan_alpha;
    double *blk, *sup; /* bed, cushion: minima of the lifting scale per block and
                          superblock */
    rec_t *rec;        /* frame, cushion: prefix minima of the lifting scale */
    size_t nrec, caprec;
    double *st;            /* unit-scale states every CHECK samples: (u, u') of the frame, or of
                              the cushion's rocking oscillator (theta = gain u) */
    sw_rock_linear_t rock; /* CK_ROCK: the rocking oscillator (ops->rock_linear) */
    double lead;           /* s, cushion: lead-in before the first possible lift */
    sw_state_t rest;       /* CK_ROCK: the engine's state of rest */
    double st_end[2];      /* CK_ROCK: the unit-scale state at the last sample */
    struct sw_refs *refs;  /* CK_ROCK: the reference states at checkpoints (safety_prep.c) */
    size_t i_peak;         /* sample of the largest drive (frame, cushion) */
    double a_peak, bare_lift, lift_scale;
} prep_t;

/* What every trial of scene *P->sc on *P->log uses, made once before its
 * search (P->sc, P->log and P->ro set by the caller).  SW_OK, or an error
 * with msg set. */
int sw_safety_prep_make(prep_t *P, char *msg, size_t msglen);
void sw_safety_prep_free(prep_t *P);

/* What a trial must get right, as a run of the log from its start would:
 * everything it reports (the run at scale 1), or whether it overturns and
 * its peak |theta| / alpha where that is below SW_SAFETY_NEAR_PEAK (the
 * scan's step depends on it; EXACT: the same, made the exact way without
 * trying the fast one first), or whether it overturns alone. */
typedef enum { SW_TRIAL_FULL, SW_TRIAL_PEAK, SW_TRIAL_EXACT, SW_TRIAL_OUTCOME } sw_trial_need;

/* peak |theta| / alpha from which the scan takes its finest step */
#define SW_SAFETY_NEAR_PEAK SW_SEARCH_NEAR_PEAK

/* One trial at scale x into r.  A search trial (not SW_TRIAL_FULL) at
 * which nothing can lift the package is safe without a run; a full one
 * runs anyway, over its largest response. */
int sw_safety_trial(const prep_t *P, double x, sw_trial_need need, sw_run_result_t *r, char *msg,
                    size_t msglen);

#endif
