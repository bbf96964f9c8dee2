/* whatif.h - the what-if cases of forensics: the same log with the
 * package as given, on the bed, on a frame, on a cushion and in other
 * sizes; each case's safety factor (sweep.h) and the report of them. */
#ifndef SWAYWATCH_CLI_WHATIF_H
#define SWAYWATCH_CLI_WHATIF_H

#include <stdio.h>

#include "opts.h"

/* Damping ratios of a frame or a cushion the scene does not have (the
 * paper's Table I). */
#define SW_CLI_FRAME_ZETA "0.1"
#define SW_CLI_CUSHION_ZETA "0.1"

/* The what-if options: scene values as text, set as scene keys. */
typedef struct {
    const char *frame_mass, *frame_omega, *frame_zeta;
    const char *cushion_omega, *cushion_zeta;
    sw_cli_list_t sizes; /* --size HxW */
    int no_what_if;      /* only the scene as given */
} sw_cli_whatif_t;

typedef struct {
    char name[64];  /* "as given", "bed", "frame", "cushion", "size 2.4x0.8 m" */
    char desc[192]; /* the support, in words and numbers */
    int is_scene;
    int available;  /* 0: not computed, note says why */
    char note[256];
    sw_scene_t scene;
    sw_model_kind model;
    int status;
    sw_safety_t sf;
} sw_cli_case_t;

/* "HEIGHTxWIDTH" (m, both > 0) into *h, *w: 0, or -1 if it is not one. */
int sw_cli_parse_size(const char *arg, double *h, double *w);

/* The cases (free()); the first is the scene as given.  A case that cannot
 * be built is not available, its note says why.  NULL: out of memory. */
sw_cli_case_t *sw_cli_whatif_build(const sw_scene_t *sc, const sw_cli_whatif_t *w, size_t *n);

/* The safety factor of every available case, on threads threads. */
void sw_cli_whatif_run(sw_cli_case_t *cases, size_t n, const sw_log_t *log,
                       const sw_run_opts_t *ro, const sw_search_opts_t *so, int threads);

/* The safety factor of the scene as given, and the table of the cases. */
void sw_cli_whatif_print_safety(FILE *f, const sw_cli_case_t *C);
void sw_cli_whatif_print_table(FILE *f, const sw_cli_case_t *cs, size_t n);
/* The same as JSON values. */
void sw_cli_whatif_json_safety(FILE *f, const sw_cli_case_t *C);
void sw_cli_whatif_json_case(FILE *f, const sw_cli_case_t *C);

#endif
