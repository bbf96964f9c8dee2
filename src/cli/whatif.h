/* SPDX-License-Identifier: GPL-3.0-or-later */
/* whatif.h - the what-if cases of forensics: for every package, the same
 * log with the package as given, alone on the bed, on the typical
 * supports of a catalogue (or the user's), and in other sizes; each
 * case's safety factor (sweep.h), all cases of all packages searched at
 * once, and the table and JSON that report them. */
#ifndef SWAYWATCH_CLI_WHATIF_H
#define SWAYWATCH_CLI_WHATIF_H

#include <stdio.h>

#include "opts.h"
#include "record.h"

/* Damping ratios of a frame or a cushion the scene does not have (the
 * paper's Table I). */
#define SW_CLI_FRAME_ZETA "0.1"
#define SW_CLI_CUSHION_ZETA "0.1"

/* A typical support of the catalogue (docs/forensics.md): a frame on
 * bearings or a cushion, by its natural frequency with the package on it,
 * and what real products it stands for. */
typedef struct {
    const char *name;       /* "frame, soft bearings" */
    int cushion;            /* 0 a frame (on the bed), 1 a cushion (on the bed) */
    double hz;              /* natural frequency with the package on it, Hz */
    double zeta;            /* damping ratio */
    const char *stands_for; /* what real supports it stands for */
} sw_cli_support_t;

extern const sw_cli_support_t sw_cli_supports[];
extern const size_t sw_cli_nsupports;

/* The what-if options.  Frequencies in rad/s (0: not given); the other
 * scene values as text, set as scene keys. */
typedef struct {
    const char *frame_mass, *frame_zeta, *cushion_zeta;
    double frame_omega, cushion_omega;
    sw_cli_list_t sizes; /* --size HxW */
    int no_what_if;      /* only the scenes as given */
    long reserve_evals;  /* --reserve-evals: per case, at most (0: no limit) */
} sw_cli_whatif_t;

/* An option's check for a frequency (dest: a double, rad/s): "2Hz",
 * "2 Hz", "12.6rad/s", or a bare number in rad/s. */
int sw_cli_opt_frequency(const sw_cli_option_t *o, const char *arg, void *dest);

typedef struct {
    char name[64];          /* "as given", "bed", "frame, soft bearings", "size 2.4x0.8 m" */
    char desc[224];         /* the package and its support, in numbers */
    const char *stands_for; /* catalogue rows: what real supports they stand for; else NULL */
    size_t pkg;             /* the --scene it belongs to (0-based) */
    int is_scene;
    int available; /* 0: not computed, note says why */
    char note[256];
    sw_scene_t scene;
    sw_model_kind model;
    int status;
    sw_safety_t sf;
    /* the smallest reserve along the log (sw_reserve_log_min; the scene as
     * given: the replay's): has_reserve 0 when not computed, reserve_note
     * says why when it could not be */
    int has_reserve, reserve_status;
    sw_reserve_log_t rl;
    char reserve_note[160];
} sw_cli_case_t;

/* Reserve evaluations at most per what-if case by default
 * (--reserve-evals, sw_reserve_log_min's max_evals): the most threatened
 * states first; a case that needs more shows its minimum as a bracket
 * (docs/forensics.md). */
#define SW_CLI_WHATIF_RESERVE_EVALS 400

/* "HEIGHTxWIDTH" (m, both > 0) into *h, *w: 0, or -1 if it is not one. */
int sw_cli_parse_size(const char *arg, double *h, double *w);

/* The cases of the n scenes (free()), scene by scene, each scene's first
 * the scene as given.  A case that cannot be built is not available, its
 * note says why.  NULL: out of memory. */
sw_cli_case_t *sw_cli_whatif_build(const sw_scene_t *scenes, size_t nsc, const sw_cli_whatif_t *w,
                                   size_t *n);

/* The safety factor of every available case, all at once on threads
 * threads (the results do not depend on their number); progress as for
 * sw_safety_factors() (may be NULL).  SW_OK, or SW_ENOMEM. */
int sw_cli_whatif_run(sw_cli_case_t *cases, size_t n, const sw_log_t *log, const sw_run_opts_t *ro,
                      const sw_search_opts_t *so, int threads,
                      void (*progress)(void *user, const sw_safety_progress_t *p), void *user);

/* The smallest reserve along the log of every available case that is not
 * a scene as given, at rate Hz, on threads threads (the results do not
 * depend on their number).  SW_OK or SW_ENOMEM. */
int sw_cli_whatif_reserve(sw_cli_case_t *cases, size_t n, const sw_log_t *log,
                          const sw_run_opts_t *ro, double rate, long max_evals, int threads);
/* The case's smallest reserve as text: "0.236 g", "<= 0.236 g (>= 0.150)",
 * "n/a: ..." or "-" (not computed). */
void sw_cli_whatif_reserve_text(char *buf, size_t len, const sw_cli_case_t *C);

/* The bracket of a found factor, with as many digits as its two ends need
 * to differ: "[0.459, 0.4593]". */
void sw_cli_safety_bracket(char *buf, size_t len, const sw_safety_t *s);
/* What the safety factor means for this package, in one sentence. */
void sw_cli_safety_sentence(char *buf, size_t len, const sw_safety_t *s);

/* The what-if table of package pkg's cases (a row each), on f. */
void sw_cli_whatif_print_table(FILE *f, const sw_cli_case_t *cs, size_t n, size_t pkg);
/* The cases of package pkg that stayed upright where the scene did not,
 * in words ("frame, soft bearings; cushion, firm"), or "" if none. */
void sw_cli_whatif_savers(char *buf, size_t len, const sw_cli_case_t *cs, size_t n, size_t pkg);
/* As JSON (record.h): the case's member "safety_factor" of o; the case's
 * members into o. */
void sw_cli_whatif_json_safety(json_t *o, const sw_cli_case_t *C);
void sw_cli_whatif_json_case(json_t *o, const sw_cli_case_t *C);

#endif
