/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cmd_boundary.c - "swaywatch boundary": overturning boundary curves, the
 * lowest pulse amplitude a_e/(g tan alpha) that overturns the package as a
 * function of omega_e/p, for one or more curves (scenes, --vary values of
 * a scene key, --bearing-ratio values), as CSV and optionally a figure.
 *
 * In physical units (--units g or m/s2, --pulse-duration) the same curves
 * are given as a pulse's peak in g or m/s^2 against its duration in ms,
 * as shock standards state pulses.  A duration is a different omega_e/p
 * for packages of different sizes, and an amplitude in g a different
 * a_e/(g tan alpha) for different slendernesses, so the curves are swept
 * in groups that share the points and the search range.
 *
 * The points are independent runs of the library's boundary search
 * (sweep.h) spread over --threads worker threads, and under mpirun or srun
 * (a build with MPI) over the ranks too (farm.h); the output does not
 * depend on the number of threads or ranks.
 *
 * This file holds the options and the command; the curves, the sweep and
 * the output have files of their own (boundary.h). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "boundary.h"
#include "clobber.h"
#include "cost.h"
#include "farm.h"
#include "interrupt.h"
#include "opts.h"
#include "output.h"
#include "plot.h"

#define MAX_POINTS 100000 /* omega_e/p values; a typo such as 1:12:0.0001 is refused */

static int parse_vary(const char *arg, vary_t *v)
{
    memset(v, 0, sizeof *v);
    const char *eq = strchr(arg, '=');
    const char *dot = strchr(arg, '.');
    if (!eq || !dot || dot > eq || eq == arg || eq[1] == '\0') {
        sw_cli_error("--vary: expected SECTION.KEY=V1,V2,..., got '%s'", arg);
        return SW_EXIT_USAGE;
    }
    v->key = strdup(arg);
    size_t cap = 1;
    for (const char *p = eq; *p; p++) cap += *p == ',';
    v->values = calloc(cap, sizeof *v->values);
    if (!v->key || !v->values) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    char *vals = v->key + (eq - arg);
    *vals++ = '\0';
    char *save = NULL;
    for (char *tok = strtok_r(vals, ",", &save); tok; tok = strtok_r(NULL, ",", &save))
        v->values[v->n++] = tok;
    if (v->n == 0) {
        sw_cli_error("--vary: no values in '%s'", arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

static void vary_free(vary_t *v)
{
    free(v->key);
    free(v->values);
}

static int parse_shape(const sw_cli_option_t *o, const char *arg, void *dest)
{
    boundary_opts_t *b = dest;
    b->have_shape = 1;
    if (sw_pulse_shape_parse(arg, &b->bo.shape) == SW_OK)
        return SW_EXIT_OK;
    sw_cli_error("--%s: expected half-sine or full-sine, got '%s'", o->long_name, arg);
    return SW_EXIT_USAGE;
}

/* Each of n values within the row's bounds. */
static int check_values(const sw_cli_option_t *o, const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        char arg[32];
        snprintf(arg, sizeof arg, "%g", v[i]);
        if (sw_cli_opt_range(o, arg, v[i]) != SW_EXIT_OK)
            return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

static int parse_ratios(const sw_cli_option_t *o, const char *arg, void *dest)
{
    boundary_opts_t *b = dest;
    free(b->ratios);
    free(b->durations);
    b->ratios = b->durations = NULL;
    b->nr = 0;
    char opt[64];
    snprintf(opt, sizeof opt, "--%s", o->long_name);
    int rc = sw_cli_parse_range(opt, arg, MAX_POINTS, &b->ratios, &b->nr);
    return rc == SW_EXIT_OK ? check_values(o, b->ratios, b->nr) : rc;
}

/* One duration of --pulse-duration, with its unit, in s. */
static int duration_item(const sw_cli_option_t *o, const char *text, double *s)
{
    return sw_cli_opt_quantity(o, text, 1, 0, s, NULL);
}

/* --pulse-duration FROM:TO:STEP or D1,D2,..., each with its unit (5ms:50ms:5ms,
 * 10ms,0.02s): the values FROM + i STEP, inclusive, as --omega-ratio's. */
static int parse_durations(const sw_cli_option_t *o, const char *arg, void *dest)
{
    boundary_opts_t *b = dest;
    free(b->ratios);
    free(b->durations);
    b->ratios = b->durations = NULL;
    b->nr = 0;
    char *copy = strdup(arg);
    double *v = NULL;
    size_t n = 0;
    int rc = SW_EXIT_IO;
    if (!copy)
        goto oom;
    if (strchr(copy, ':')) {
        char *from = copy, *to = strchr(from, ':'), *step;
        *to++ = '\0';
        step = strchr(to, ':');
        if (!step || strchr(step + 1, ':')) {
            sw_cli_error(
                "--%s: expected FROM:TO:STEP, each with its unit (e.g. 5ms:50ms:5ms), "
                "got '%s'",
                o->long_name, arg);
            rc = SW_EXIT_USAGE;
            goto out;
        }
        *step++ = '\0';
        double a, z, d;
        if ((rc = duration_item(o, from, &a)) != SW_EXIT_OK ||
            (rc = duration_item(o, to, &z)) != SW_EXIT_OK ||
            (rc = duration_item(o, step, &d)) != SW_EXIT_OK)
            goto out;
        rc = SW_EXIT_USAGE;
        if (z < a) {
            sw_cli_error("--%s: FROM %g s is after TO %g s in '%s'", o->long_name, a, z, arg);
            goto out;
        }
        const double count = floor((z - a) / d * (1.0 + 1e-12) + 1e-9) + 1.0;
        if (count > MAX_POINTS) {
            sw_cli_error("--%s: '%s' gives %.0f points, more than %d", o->long_name, arg, count,
                         MAX_POINTS);
            goto out;
        }
        n = (size_t)count;
        if (!(v = calloc(n, sizeof *v)))
            goto oom;
        for (size_t i = 0; i < n; i++) v[i] = a + (double)i * d;
    } else {
        size_t cap = 1;
        for (const char *p = copy; *p; p++) cap += *p == ',';
        if (!(v = calloc(cap, sizeof *v)))
            goto oom;
        for (char *tok = copy, *next; tok; tok = next) {
            next = strchr(tok, ',');
            if (next)
                *next++ = '\0';
            if ((rc = duration_item(o, tok, &v[n])) != SW_EXIT_OK)
                goto out;
            n++;
        }
    }
    b->durations = v;
    b->nr = n;
    v = NULL;
    rc = SW_EXIT_OK;
    goto out;
oom:
    sw_cli_error("out of memory");
    rc = SW_EXIT_IO;
out:
    free(v);
    free(copy);
    return rc;
}

/* --units: g tan alpha (gtan), g or m/s2 (and the spellings a CSV
 * header may use). */
static int parse_units(const sw_cli_option_t *o, const char *arg, void *dest)
{
    boundary_opts_t *b = dest;
    const int u = sw_csv_unit_parse(arg, 0);
    if (u == SW_CSV_UNIT_G)
        b->units = UNITS_G;
    else if (u == SW_CSV_UNIT_MPS2)
        b->units = UNITS_MPS2;
    else if (!strcmp(arg, "gtan") || !strcmp(arg, "g-tan-alpha"))
        b->units = UNITS_GTAN;
    else {
        sw_cli_error(
            "--%s: unknown unit '%s': expected gtan (g tan alpha), g or m/s2 (m/s^2, "
            "mps2)",
            o->long_name, arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* --min-amplitude, --max-amplitude: a bare number in g tan alpha (as
 * before), or an acceleration with its unit (5g, 49m/s2).  The row's
 * bounds are in g tan alpha: a value with a unit is checked for each
 * package, once its g tan alpha is known (curve_units). */
static int parse_amplitude(const sw_cli_option_t *o, const char *arg, void *dest)
{
    boundary_opts_t *b = dest;
    const int is_max = !strcmp(o->long_name, "max-amplitude");
    double v;
    int unit;
    sw_cli_option_t unbounded = *o;
    unbounded.lo = unbounded.hi = 0.0;
    int rc = sw_cli_opt_quantity(&unbounded, arg, 0, 1, &v, &unit);
    if (rc == SW_EXIT_OK && unit == SW_CSV_UNIT_NONE)
        rc = sw_cli_opt_range(o, arg, v);
    if (rc != SW_EXIT_OK)
        return rc;
    double *x = is_max ? &b->bo.search.x_max : &b->bo.search.x_min;
    double *si = is_max ? &b->max_si : &b->min_si;
    *x = unit == SW_CSV_UNIT_NONE ? v : 0.0;
    *si = unit == SW_CSV_UNIT_NONE ? 0.0 : v;
    *(is_max ? &b->max_arg : &b->min_arg) = arg;
    return SW_EXIT_OK;
}

static int parse_bearing(const sw_cli_option_t *o, const char *arg, void *dest)
{
    boundary_opts_t *b = dest;
    free(b->bearing);
    b->bearing = NULL;
    b->nbear = 0;
    b->bear_arg = arg;
    char opt[64];
    snprintf(opt, sizeof opt, "--%s", o->long_name);
    int rc = sw_cli_parse_list(opt, arg, 1, &b->bearing, &b->nbear);
    return rc == SW_EXIT_OK ? check_values(o, b->bearing, b->nbear) : rc;
}

/* --plane longitudinal|lateral. */
static int parse_plane(const sw_cli_option_t *o, const char *arg, void *dest)
{
    boundary_opts_t *b = dest;
    if (!strcmp(arg, "longitudinal") || !strcmp(arg, "lateral")) {
        b->lateral = !strcmp(arg, "lateral");
        return SW_EXIT_OK;
    }
    sw_cli_error("--%s: expected longitudinal or lateral, got '%s'", o->long_name, arg);
    return SW_EXIT_USAGE;
}

static int add_vary(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)o;
    boundary_opts_t *b = dest;
    vary_t *v = realloc(b->vary, (b->nvary + 1) * sizeof *v);
    if (!v) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    b->vary = v;
    return parse_vary(arg, &b->vary[b->nvary++]);
}

#define BO(f) SW_CLI_AT(boundary_opts_t, f)

static const sw_cli_option_t boundary_options[] = {
    {SW_CLI_SECTION,
     .help = "Curves (one CSV column each): every --scene, times every --vary value, times\n"
             "every --bearing-ratio value for scenes with a frame."},
    {SW_CLI_CALL, 0, "pulse", "SHAPE", .fn = parse_shape,
     .help = "half-sine or full-sine (required)"},
    {SW_CLI_CALL, 0, "omega-ratio", "R", .fn = parse_ratios, .lo = 1e-3, .hi = 1e4,
     .help = "omega_e/p values: FROM:TO:STEP (inclusive) or a list R1,R2,... (required, or "
             "--pulse-duration); below 1e-3 a pulse lasts thousands of rocking periods, above "
             "1e4 it is far shorter than a step"},
    {SW_CLI_CALL, 0, "pulse-duration", "D", .fn = parse_durations, .rule = SW_NUM_POSITIVE,
     .what = "a positive time with its unit, e.g. 11ms or 0.011s",
     .help = "the pulse's duration instead of omega_e/p, each value with its unit (ms, s or us): "
             "FROM:TO:STEP, e.g. 5ms:50ms:5ms, or a list D1,D2,...; a half-sine lasts pi/omega_e, "
             "a full-sine 2 pi/omega_e (omega_e/p within --omega-ratio's range); implies --units "
             "g unless --units says otherwise"},
    {SW_CLI_CALL, 0, "vary", "SEC.KEY=V1,V2", .fn = add_vary,
     .help = "one curve per value of a scene key, e.g. --vary frame.zeta=0.05,0.1,0.2; "
             "repeatable (all combinations); a frame or cushion key leaves scenes without that "
             "section as they are"},
    {SW_CLI_CALL, 0, "plane", "PLANE", .fn = parse_plane,
     .help = "longitudinal (default): the package rocking along the truck, over its width; "
             "lateral: across it, over its [package] depth (every scene must give one), on the "
             "frame's and cushion's lateral_ values where given; --vary package.depth then "
             "varies the size it rocks over"},
    {SW_CLI_CALL, 0, "bearing-ratio", "B1,B2", .fn = parse_bearing, .lo = 1e-3, .hi = 1e3,
     .help = "omega_b = B * omega_e at every point (the paper's omega_b/omega_e); values may be "
             "fractions such as 1/3; scenes without a [frame] are drawn once, as they are"},
    {SW_CLI_SECTION, .help = "Search:"},
    {SW_CLI_DOUBLE, 0, "step", "X", BO(bo.search.step), .rule = SW_NUM_POSITIVE, .lo = 1e-4,
     .hi = 1, .what = "a positive relative step",
     .help = "relative scan step (default 0.02); smaller steps take tens of thousands of runs "
             "per point"},
    {SW_CLI_DOUBLE, 0, "tol", "X", BO(bo.search.tol), .rule = SW_NUM_POSITIVE, .lo = 1e-9,
     .hi = 0.5, .what = "a positive relative tolerance",
     .help = "relative width of the final bracket (default 0.001); finer than 1e-9 is below "
             "what the model resolves"},
    {SW_CLI_CALL, 0, "min-amplitude", "X", .fn = parse_amplitude, .rule = SW_NUM_POSITIVE,
     .lo = 1e-3, .hi = 1e4,
     .what = "a positive amplitude in g tan alpha, or with its unit (e.g. 2g)",
     .help = "start of the scan, in g tan alpha, or with a unit: g or m/s2, e.g. 0.5g (default: "
             "the lowest amplitude that can lift the package at all)"},
    {SW_CLI_CALL, 0, "max-amplitude", "X", .fn = parse_amplitude, .rule = SW_NUM_POSITIVE,
     .lo = 1e-3, .hi = 1e4,
     .what = "a positive amplitude in g tan alpha, or with its unit (e.g. 10g)",
     .help = "end of the scan, in g tan alpha, or with a unit, e.g. 10g (default 20 g tan "
             "alpha); a curve with no overturn up to it has an empty field at that point, "
             "marked in the figure; 1e4 g tan alpha is beyond any accelerometer"},
    {SW_CLI_DOUBLE, 0, "free-periods", "N", BO(bo.run.free_periods), .rule = SW_NUM_POSITIVE,
     .lo = 1e-2, .hi = 1e4, .what = "a positive number of rocking periods",
     .help = "free motion after the pulse, in rocking periods 2 pi/p (default 20); more than "
             "1e4 would make every trial hours of motion"},
    {SW_CLI_LONG, 0, "threads", "N", BO(threads), .flags = SW_CLI_CAP, .min = 0, .max = 256,
     .def = 0, .what = "a whole number of threads >= 0",
     .help = "worker threads (per MPI rank); 0, the default: the CPUs this process may run on; "
             "results do not depend on it"},
    {SW_CLI_SECTION, .help = "Integration:"},
    {SW_CLI_TEXT,
     .help = "Without --dt, each run's step is the scheme's, at most 1/400 of the pulse period\n"
             "and of the rocking period; a --dt above the scheme's stability bound is\n"
             "sub-stepped, not refused."},
    {SW_CLI_SECTION, .help = "Output:"},
    {SW_CLI_CALL, 0, "units", "UNIT", .fn = parse_units,
     .help = "amplitudes of --out, --islands and the figure in gtan (g tan alpha, the default), "
             "g or m/s2; in g or m/s2 the pulse duration (ms) goes with omega_e/p"},
    {SW_CLI_STRING, 'o', "out", "FILE.csv", BO(out),
     .help =
         "the curves (default, or '-': standard output): omega_ratio,<curve 1>,<curve 2>,... in "
         "units of g tan alpha; in physical units duration_ms too (first with "
         "--pulse-duration; one per curve, '<curve> duration_ms', when the packages' sizes "
         "differ) and the curves' columns '<curve> (g)'"},
    {SW_CLI_STRING, 0, "detail", "FILE.csv", BO(detail),
     .help = "one row per curve and point ('-': standard output, if --out names a file): the "
             "bracket, impacts before the overturn at the "
             "boundary (0: overturned directly; >= 1: after an impact), the directions of the "
             "first uplift and of the overturn (+1 the top forward, -1 back; opposite: it "
             "overturned after a reverse sway), times, trials"},
    {SW_CLI_STRING, 0, "islands", "FILE.csv", BO(islands),
     .help = "scan on up to --max-amplitude and list the safe islands above the boundary "
             "('-' as for --detail): curve,omega_ratio,from,to,open"},
    {SW_CLI_STRING, 0, "plot", "FILE.png|.svg", BO(plot), .fn = sw_cli_plot_check,
     .help = "draw the curves (and islands) with gnuplot"},
    {SW_CLI_STRING, 0, "title", "TEXT", BO(title), .help = "title of the figure"},
    {SW_CLI_FLAG, 0, "progress", BO(progress), .value = 1,
     .help = "percentage on stderr (default: only when stderr is a terminal)"},
    {SW_CLI_FLAG, 0, "no-progress", BO(progress), .value = 0, .help = "no percentage"},
    {SW_CLI_FLAG, 'q', "quiet", BO(quiet), .value = 1, .help = "no summary on stderr"},
    {.kind = SW_CLI_END},
};

static const sw_cli_command_t boundary_cmd = {
    .name = "boundary",
    .usage =
        "boundary --scene S.ini --pulse half-sine|full-sine\n"
        "                          --omega-ratio R|--pulse-duration D [options]",
    .about =
        "Overturning boundary curves: for each omega_e/p, the lowest amplitude\n"
        "a_e/(g tan alpha) of a pulse a(t) = a_e sin(omega_e t) (half-sine: one half wave;\n"
        "full-sine: one whole wave) that overturns the package standing still, with p the\n"
        "package's rocking frequency sqrt(3 g / 4 R) and g tan alpha the bed acceleration\n"
        "that lifts it.  Each amplitude is run exactly (the pulse is a function of time),\n"
        "then free motion until the outcome is certain or --free-periods pass.  Amplitudes\n"
        "are scanned upward in --step relative steps from the lowest one that can lift the\n"
        "package, then bisected to --tol: overturning is not monotonic for full-sine\n"
        "pulses (a bigger pulse can be survived), so the lowest overturning amplitude is\n"
        "reported, and with --islands the safe islands above it.\n"
        "In a shock engineer's terms, --pulse-duration 5ms:50ms:1ms and --units g give\n"
        "the boundary as the pulse's peak in g against its duration in ms.\n",
};

/* ---- the command --------------------------------------------------------------- */

/* What the options leave to check together; the search's defaults. */
static int check_options(boundary_t *B, int argc, char **argv, int first)
{
    sw_boundary_opts_t *bo = &B->b.bo;
    if (sw_cli_no_operand("boundary", argc, argv, first) != SW_EXIT_OK)
        return SW_EXIT_USAGE;
    if (!B->b.have_shape || !B->b.nr) {
        sw_cli_error("boundary: missing %s; see 'swaywatch boundary --help'",
                     !B->b.have_shape ? "--pulse half-sine|full-sine"
                                      : "--omega-ratio FROM:TO:STEP or --pulse-duration "
                                        "FROM:TO:STEP (e.g. 5ms:50ms:5ms)");
        return SW_EXIT_USAGE;
    }
    if (bo->search.x_min > 0.0 && bo->search.x_max > 0.0 && bo->search.x_min >= bo->search.x_max) {
        sw_cli_error("--min-amplitude %g is not below --max-amplitude %g", bo->search.x_min,
                     bo->search.x_max);
        return SW_EXIT_USAGE;
    }
    if (B->b.min_si > 0.0 && B->b.max_si > 0.0 && B->b.min_si >= B->b.max_si) {
        sw_cli_error("--min-amplitude %s is not below --max-amplitude %s", B->b.min_arg,
                     B->b.max_arg);
        return SW_EXIT_USAGE;
    }
    if (!(bo->search.x_max > 0.0) && !(B->b.max_si > 0.0))
        bo->search.x_max = DEFAULT_X_MAX;
    if (bo->search.x_max > 0.0 && bo->search.x_min >= bo->search.x_max) {
        sw_cli_error("--min-amplitude %g is not below the default --max-amplitude %g",
                     bo->search.x_min, bo->search.x_max);
        return SW_EXIT_USAGE;
    }
    B->units = B->b.units >= 0 ? B->b.units : B->b.durations ? UNITS_G : UNITS_GTAN;
    B->physical = B->units != UNITS_GTAN || B->b.durations != NULL;
    /* The curves go to standard output unless --out names a file; "-"
     * gives it to one of the CSV files. */
    const char *taken =
        !B->b.out || !strcmp(B->b.out, "-") ? "the curves (give --out a file)" : NULL;
    if (B->b.detail && !strcmp(B->b.detail, "-")) {
        if (taken) {
            sw_cli_error("--detail -: standard output already carries %s", taken);
            return SW_EXIT_USAGE;
        }
        taken = "--detail";
    }
    if (taken && B->b.islands && !strcmp(B->b.islands, "-")) {
        sw_cli_error("--islands -: standard output already carries %s", taken);
        return SW_EXIT_USAGE;
    }
    bo->search.islands = B->b.islands != NULL;
    bo->threads = sw_cli_threads(&B->world, B->b.threads);
    sw_cli_engine_opts(&B->o, &bo->run.engine);
    if (!B->b.nbear)
        return SW_EXIT_OK;
    /* labels of the bearing ratios as the user wrote them ("1/3") */
    B->bear_copy = strdup(B->b.bear_arg);
    B->bear_text = calloc(B->b.nbear, sizeof *B->bear_text);
    if (!B->bear_copy || !B->bear_text) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    size_t k = 0;
    char *save = NULL;
    for (char *t = strtok_r(B->bear_copy, ",", &save); t && k < B->b.nbear;
         t = strtok_r(NULL, ",", &save))
        B->bear_text[k++] = t;
    return SW_EXIT_OK;
}

/* --plane lateral: each scene replaced by the scene of its lateral plane
 * (sw_scene_lateral: the package over its depth, the lateral support
 * values), and --vary package.depth turned into the width of that scene;
 * a scene without a depth, or a --vary of the width (not the size this
 * plane rocks over), is refused. */
static int to_plane(boundary_t *B)
{
    if (!B->b.lateral)
        return SW_EXIT_OK;
    for (size_t k = 0; k < B->nsc; k++) {
        sw_scene_t lat;
        if (sw_scene_lateral(&B->scenes[k], &lat) != SW_OK) {
            sw_cli_error(
                "--plane lateral: %s gives no [package] depth (m, the size across the truck "
                "the lateral plane rocks over): add one to the scene or --set package.depth=D",
                k < B->o.scenes.n ? B->o.scenes.v[k] : B->scenes[k].name);
            return SW_EXIT_USAGE;
        }
        B->scenes[k] = lat;
    }
    for (size_t i = 0; i < B->b.nvary; i++) {
        char *key = B->b.vary[i].key;
        if (!strcmp(key, "package.width")) {
            sw_cli_error(
                "--vary package.width: with --plane lateral the package rocks over its "
                "depth; vary package.depth");
            return SW_EXIT_USAGE;
        }
        if (!strcmp(key, "package.depth")) /* the same length: rewritten in place */
            memcpy(key, "package.width", sizeof "package.width");
    }
    return SW_EXIT_OK;
}

int cmd_boundary(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    boundary_t B;
    memset(&B, 0, sizeof B);
    if ((rc = sw_cli_world_start(&B.world)) != SW_EXIT_OK)
        return rc;
    /* Every rank sets up as rank 0 does; the others keep their messages
     * to themselves unless they alone fail. */
    char *msgs = NULL;
    size_t mlen = 0;
    FILE *mf = B.world.rank != 0 ? open_memstream(&msgs, &mlen) : NULL;
    if (mf)
        sw_cli_msg_to(mf);
    B.b.progress = B.world.rank == 0 && isatty(fileno(stderr)) ? 1 : 0;
    B.b.units = -1;
    B.options = boundary_options;
    sw_cli_group_t g[] = {
        SW_CLI_GROUP(sw_cli_scene_options, &B.o),
        SW_CLI_GROUP(boundary_options, &B.b),
        SW_CLI_GROUP(sw_cli_integration_options, &B.o),
        SW_CLI_GROUP_IN(sw_cli_common_options, &B.o, "Output:"),
    };
    const size_t ng = sizeof g / sizeof g[0];

    int first, help = 0;
    if ((rc = sw_cli_parse(&boundary_cmd, g, ng, argc, argv, &first)) != SW_CLI_CONTINUE) {
        help = rc == SW_EXIT_OK;
    } else {
        const sw_cli_file_t outputs[] = {{"--out", B.b.out},
                                         {"--detail", B.b.detail},
                                         {"--islands", B.b.islands},
                                         {"--plot", B.b.plot}};
        if ((rc = sw_cli_interrupt_install()) == SW_EXIT_OK &&
            (rc = check_options(&B, argc, argv, first)) == SW_EXIT_OK &&
            (rc = sw_cli_check_run_files(NULL, &B.o.scenes, outputs, 4)) == SW_EXIT_OK &&
            (rc = sw_cli_load_scenes(&B.o, &B.scenes, &B.nsc)) == SW_EXIT_OK &&
            (rc = to_plane(&B)) == SW_EXIT_OK &&
            (rc = sw_bnd_build_curves(B.scenes, B.nsc, B.b.vary, B.b.nvary, B.b.bearing, B.b.nbear,
                                      B.bear_text, &B.cv, &B.nc)) == SW_EXIT_OK)
            rc = sw_bnd_curve_units(&B);
    }
    if (mf) {
        sw_cli_msg_to(NULL);
        fclose(mf);
    }
    rc = sw_cli_world_agree(&B.world, rc, msgs, mlen);
    free(msgs);
    if (rc != SW_EXIT_OK || help)
        goto out;
    if (B.world.rank == 0) {
        if (B.o.verbose)
            sw_bnd_print_curves(&B);
        sw_cli_warn_scene_cost(B.scenes, B.nsc, &B.b.bo.run.engine);
    }
    if ((rc = sw_bnd_sweep(&B)) != SW_EXIT_OK || B.world.rank != 0)
        goto out;
    rc = sw_bnd_write_outputs(&B);
    if (sw_cli_signal && rc != SW_EXIT_IO) { /* while writing: the files are whole */
        sw_cli_error("boundary: interrupted by %s after the files were written",
                     sw_cli_signal_name(sw_cli_signal));
        rc = sw_cli_interrupt_code();
    }
out:
    free(B.pts);
    free(B.cv);
    free(B.scenes);
    for (size_t k = 0; k < B.b.nvary; k++) vary_free(&B.b.vary[k]);
    free(B.b.vary);
    free(B.b.ratios);
    free(B.b.durations);
    free(B.b.bearing);
    free(B.bear_copy);
    free(B.bear_text);
    sw_cli_parse_free(g, ng);
    return sw_cli_world_end(&B.world, rc);
}
