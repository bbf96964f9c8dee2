/* SPDX-License-Identifier: GPL-3.0-or-later */
/* boundary.h - what the files of "swaywatch boundary" share: its options,
 * its curves and the state of a run.  cmd_boundary.c parses the options
 * and runs the command, boundary_curves.c makes the curves (scenes x
 * --vary values x bearing ratios) and their units, boundary_sweep.c sweeps
 * them over the threads and MPI ranks, boundary_out.c writes the CSVs and
 * the figure.  sw_bnd_ names the command's own, apart from the library's
 * sw_boundary_ (sweep.h). */
#ifndef SWAYWATCH_CLI_BOUNDARY_H
#define SWAYWATCH_CLI_BOUNDARY_H

#include <stddef.h>

#include "farm.h"
#include "opts.h"

#define DEFAULT_X_MAX 20.0 /* g tan alpha: the end of the scan without --max-amplitude */

/* Units of the amplitudes written and drawn (--units). */
enum { UNITS_GTAN = 0, UNITS_G, UNITS_MPS2 };

/* --vary SEC.KEY=V1,V2,...: the key and its values (pointers into a copy). */
typedef struct {
    char *key;     /* "frame.zeta" (owned copy of the whole argument) */
    char **values; /* "0.05", "0.1", ... */
    size_t n;
} vary_t;

/* boundary's own options. */
typedef struct {
    sw_boundary_opts_t bo;
    int have_shape, progress;
    long threads;
    double *ratios; /* --omega-ratio */
    size_t nr;
    double *durations;     /* s, --pulse-duration (instead of --omega-ratio; nr of them) */
    int units;             /* UNITS_*, -1: not given */
    double min_si, max_si; /* m/s^2: --min-amplitude, --max-amplitude given with a unit; 0: as
                              bo.search.x_min, x_max (g tan alpha) */
    const char *min_arg, *max_arg; /* as given, for messages */
    double *bearing;               /* --bearing-ratio, and as written ("1/3") */
    size_t nbear;
    const char *bear_arg;
    vary_t *vary;
    size_t nvary;
    const char *out; /* the curves; NULL: standard output */
    const char *plot, *islands, *detail, *title;
    int quiet;
    int lateral; /* --plane lateral: the curves of the scenes' lateral planes */
} boundary_opts_t;

/* One curve: a scene (a copy, --vary applied) and its bearing ratio. */
typedef struct {
    sw_curve_t c;
    char label[256];
    double p;            /* rad/s, the package's rocking frequency */
    double gtan;         /* m/s^2, g tan alpha of the package: the amplitudes' unit */
    double x_min, x_max; /* the scan, in g tan alpha (x_min 0: automatic) */
} curve_t;

/* Everything a boundary run uses. */
typedef struct {
    sw_cli_world_t world;
    sw_cli_opts_t o;
    boundary_opts_t b;
    char *bear_copy;        /* --bearing-ratio, split at the commas: */
    const char **bear_text; /* the ratios as written, for the labels ("1/3") */
    sw_scene_t *scenes;
    size_t nsc;
    curve_t *cv;
    size_t nc;
    sw_boundary_point_t *pts;       /* curve-major: pts[c * nr + i] */
    int units;                      /* UNITS_*: --units, or its default */
    int physical;                   /* the other of omega_e/p and the duration goes along */
    int shared_p;                   /* every curve's package has the same p: one duration per row */
    const sw_cli_option_t *options; /* boundary's own rows, for their bounds */
} boundary_t;

/* Every scene x every combination of the --vary values that apply to it x
 * every bearing ratio (scenes without a frame: as they are), into *out
 * (*nout of them, to free); SW_EXIT_* (reported). */
int sw_bnd_build_curves(const sw_scene_t *scenes, size_t nsc, const vary_t *vary, size_t nvary,
                        const double *bearing, size_t nbear, const char *bear_text[], curve_t **out,
                        size_t *nout);
/* Each curve's scan range, checked against the options' bounds;
 * SW_EXIT_* (reported). */
int sw_bnd_curve_units(boundary_t *B);
/* --verbose: what each curve's scene is, on stderr. */
void sw_bnd_print_curves(const boundary_t *B);
/* rad, omega_e times the pulse's duration: pi (half-sine), 2 pi (full-sine). */
double sw_bnd_shape_angle(const boundary_t *B);
/* omega_e/p of curve c at point i. */
double sw_bnd_ratio_at(const boundary_t *B, size_t c, size_t i);

/* Every curve at every point into B->pts (allocated); SW_EXIT_*
 * (reported on rank 0). */
int sw_bnd_sweep(boundary_t *B);

/* The files, each said on stderr with what it holds, then the points that
 * need a word (unless --quiet); SW_EXIT_*. */
int sw_bnd_write_outputs(const boundary_t *B);

#endif
