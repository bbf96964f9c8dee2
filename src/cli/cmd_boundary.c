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
 * depend on the number of threads or ranks. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "clobber.h"
#include "cost.h"
#include "farm.h"
#include "interrupt.h"
#include "opts.h"
#include "output.h"
#include "plot.h"

#define MAX_POINTS 100000 /* omega_e/p values; a typo such as 1:12:0.0001 is refused */
#define MAX_CURVES 1000
#define G0 9.80665        /* m/s^2 per g (standard gravity, as accelerometers read) */
#define DEFAULT_X_MAX 20.0 /* g tan alpha: the end of the scan without --max-amplitude */

/* Units of the amplitudes written and drawn (--units). */
enum { UNITS_GTAN = 0, UNITS_G, UNITS_MPS2 };

/* --vary SEC.KEY=V1,V2,...: the key and its values (pointers into a copy). */
typedef struct {
    char *key;     /* "frame.zeta" (owned copy of the whole argument) */
    char **values; /* "0.05", "0.1", ... */
    size_t n;
} vary_t;

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

/* boundary's own options. */
typedef struct {
    sw_boundary_opts_t bo;
    int have_shape, progress;
    long threads;
    double *ratios; /* --omega-ratio */
    size_t nr;
    double *durations; /* s, --pulse-duration (instead of --omega-ratio; nr of them) */
    int units;         /* UNITS_*, -1: not given */
    double min_si, max_si; /* m/s^2: --min-amplitude, --max-amplitude given with a unit; 0: as
                              bo.search.x_min, x_max (g tan alpha) */
    const char *min_arg, *max_arg; /* as given, for messages */
    double *bearing; /* --bearing-ratio, and as written ("1/3") */
    size_t nbear;
    const char *bear_arg;
    vary_t *vary;
    size_t nvary;
    const char *out; /* the curves; NULL: standard output */
    const char *plot, *islands, *detail, *title;
    int quiet;
} boundary_opts_t;

static int parse_shape(const sw_cli_option_t *o, const char *arg, void *dest)
{
    boundary_opts_t *b = dest;
    b->have_shape = 1;
    if (sw_pulse_shape_parse(arg, &b->bo.shape) == SW_OK) return SW_EXIT_OK;
    sw_cli_error("--%s: expected half-sine or full-sine, got '%s'", o->long_name, arg);
    return SW_EXIT_USAGE;
}

/* Each of n values within the row's bounds. */
static int check_values(const sw_cli_option_t *o, const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        char arg[32];
        snprintf(arg, sizeof arg, "%g", v[i]);
        if (sw_cli_opt_range(o, arg, v[i]) != SW_EXIT_OK) return SW_EXIT_USAGE;
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
    if (!copy) goto oom;
    if (strchr(copy, ':')) {
        char *from = copy, *to = strchr(from, ':'), *step;
        *to++ = '\0';
        step = strchr(to, ':');
        if (!step || strchr(step + 1, ':')) {
            sw_cli_error("--%s: expected FROM:TO:STEP, each with its unit (e.g. 5ms:50ms:5ms), "
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
        if (!(v = calloc(n, sizeof *v))) goto oom;
        for (size_t i = 0; i < n; i++) v[i] = a + (double)i * d;
    } else {
        size_t cap = 1;
        for (const char *p = copy; *p; p++) cap += *p == ',';
        if (!(v = calloc(cap, sizeof *v))) goto oom;
        for (char *tok = copy, *next; tok; tok = next) {
            next = strchr(tok, ',');
            if (next) *next++ = '\0';
            if ((rc = duration_item(o, tok, &v[n])) != SW_EXIT_OK) goto out;
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
        sw_cli_error("--%s: unknown unit '%s': expected gtan (g tan alpha), g or m/s2 (m/s^2, "
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
    if (rc == SW_EXIT_OK && unit == SW_CSV_UNIT_NONE) rc = sw_cli_opt_range(o, arg, v);
    if (rc != SW_EXIT_OK) return rc;
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
     .lo = 1e-3, .hi = 1e4, .what = "a positive amplitude in g tan alpha, or with its unit (e.g. 2g)",
     .help = "start of the scan, in g tan alpha, or with a unit: g or m/s2, e.g. 0.5g (default: "
             "the lowest amplitude that can lift the package at all)"},
    {SW_CLI_CALL, 0, "max-amplitude", "X", .fn = parse_amplitude, .rule = SW_NUM_POSITIVE,
     .lo = 1e-3, .hi = 1e4, .what = "a positive amplitude in g tan alpha, or with its unit (e.g. 10g)",
     .help = "end of the scan, in g tan alpha, or with a unit, e.g. 10g (default 20 g tan "
             "alpha); a curve with no overturn up to it has an empty field at that point, "
             "marked in the figure; 1e4 g tan alpha is beyond any accelerometer"},
    {SW_CLI_DOUBLE, 0, "free-periods", "N", BO(bo.run.free_periods), .rule = SW_NUM_POSITIVE,
     .lo = 1e-2, .hi = 1e4, .what = "a positive number of rocking periods",
     .help = "free motion after the pulse, in rocking periods 2 pi/p (default 20); more than "
             "1e4 would make every trial hours of motion"},
    {SW_CLI_LONG, 0, "threads", "N", BO(threads), .min = 0, .max = 256, .def = 0,
     .what = "a whole number of threads >= 0",
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
     .help = "the curves (default, or '-': standard output): omega_ratio,<curve 1>,<curve 2>,... in "
             "units of g tan alpha; in physical units duration_ms too (first with "
             "--pulse-duration; one per curve, '<curve> duration_ms', when the packages' sizes "
             "differ) and the curves' columns '<curve> (g)'"},
    {SW_CLI_STRING, 0, "detail", "FILE.csv", BO(detail),
     .help = "one row per curve and point ('-': standard output, if --out names a file): the bracket, impacts before the overturn at the "
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
    {SW_CLI_END},
};

static const sw_cli_command_t boundary_cmd = {
    .name = "boundary",
    .usage = "boundary --scene S.ini --pulse half-sine|full-sine\n"
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

/* ---- curves -------------------------------------------------------------------- */

typedef struct {
    sw_curve_t c;
    char label[256];
    double p;            /* rad/s, the package's rocking frequency */
    double gtan;         /* m/s^2, g tan alpha of the package: the amplitudes' unit */
    double x_min, x_max; /* the scan, in g tan alpha (x_min 0: automatic) */
} curve_t;

static void append(char *buf, size_t len, const char *fmt, const char *a, const char *b)
{
    size_t used = strlen(buf);
    if (used < len) snprintf(buf + used, len - used, fmt, a, b);
}

/* Does --vary v apply to scene s?  A [frame] or [cushion] key leaves a
 * scene without that section as it is (a bare reference curve stays one
 * curve). */
static int vary_applies(const vary_t *v, const sw_scene_t *s)
{
    if (!strncmp(v->key, "frame.", 6)) return s->has_frame;
    if (!strncmp(v->key, "cushion.", 8)) return s->has_cushion;
    return 1;
}

/* Every scene x every combination of the --vary values that apply to it x
 * every bearing ratio (scenes without a frame: as they are). */
static int build_curves(const sw_scene_t *scenes, size_t nsc, const vary_t *vary, size_t nvary,
                        const double *bearing, size_t nbear, const char *bear_text[],
                        curve_t **out, size_t *nout)
{
    size_t total = 0, framed = 0;
    for (size_t s = 0; s < nsc; s++) {
        size_t combos = 1;
        for (size_t k = 0; k < nvary; k++)
            if (vary_applies(&vary[k], &scenes[s])) combos *= vary[k].n;
        total += combos * (scenes[s].has_frame && nbear ? nbear : 1);
        framed += scenes[s].has_frame != 0;
        if (total > MAX_CURVES) break;
    }
    if (nbear && !framed) {
        sw_cli_error("--bearing-ratio: no scene has a [frame]");
        return SW_EXIT_USAGE;
    }
    if (total > MAX_CURVES) {
        sw_cli_error("boundary: more than %d curves", MAX_CURVES);
        return SW_EXIT_USAGE;
    }
    curve_t *cv = calloc(total, sizeof *cv);
    if (!cv) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    size_t m = 0;
    sw_cli_diag_t diag = {0};
    for (size_t s = 0; s < nsc; s++) {
        size_t combos = 1;
        for (size_t k = 0; k < nvary; k++)
            if (vary_applies(&vary[k], &scenes[s])) combos *= vary[k].n;
        const size_t nb = scenes[s].has_frame && nbear ? nbear : 1;
        for (size_t c = 0; c < combos; c++)
            for (size_t b = 0; b < nb; b++) {
                curve_t *C = &cv[m++];
                C->c.scene = scenes[s]; /* a copy: --vary edits only this curve */
                snprintf(C->label, sizeof C->label, "%s", scenes[s].name);
                size_t idx = c;
                for (size_t k = 0; k < nvary; k++) {
                    if (!vary_applies(&vary[k], &scenes[s])) continue;
                    const char *val = vary[k].values[idx % vary[k].n];
                    idx /= vary[k].n;
                    char assign[512];
                    snprintf(assign, sizeof assign, "%s=%s", vary[k].key, val);
                    const long before = diag.errors;
                    if (sw_scene_set_arg(&C->c.scene, assign, sw_cli_print_diag, &diag) != SW_OK) {
                        if (diag.errors == before) sw_cli_error("--vary %s: rejected", assign);
                        free(cv);
                        return SW_EXIT_USAGE;
                    }
                    append(C->label, sizeof C->label, " %s=%s", vary[k].key, val);
                }
                if (scenes[s].has_frame && nbear) {
                    C->c.bearing_ratio = bearing[b];
                    append(C->label, sizeof C->label, " wb/we=%s%s", bear_text[b], "");
                }
                sw_scene_t check; /* omega_b is set at each point */
                sw_curve_scene(&C->c, 0.0, &check);
                const long before = diag.errors;
                if (sw_scene_validate(&check, NULL, C->label, sw_cli_print_diag, &diag) != SW_OK) {
                    if (diag.errors == before) sw_cli_error("%s: invalid scene", C->label);
                    free(cv);
                    return SW_EXIT_USAGE;
                }
            }
    }
    *out = cv;
    *nout = total;
    return SW_EXIT_OK;
}

/* ---- the run ----------------------------------------------------------------- */

/* Everything a boundary run uses. */
typedef struct {
    sw_cli_world_t world;
    sw_cli_opts_t o;
    boundary_opts_t b;
    char *bear_copy;         /* --bearing-ratio, split at the commas: */
    const char **bear_text;  /* the ratios as written, for the labels ("1/3") */
    sw_scene_t *scenes;
    size_t nsc;
    curve_t *cv;
    size_t nc;
    sw_boundary_point_t *pts; /* curve-major: pts[c * nr + i] */
    int units;                /* UNITS_*: --units, or its default */
    int physical;             /* the other of omega_e/p and the duration goes along */
    int shared_p;             /* every curve's package has the same p: one duration per row */
} boundary_t;

/* pulse.h: a half-sine of omega_e lasts pi/omega_e, a full-sine 2 pi/omega_e. */
static double shape_angle(const boundary_t *B)
{
    return B->b.bo.shape == SW_PULSE_FULL_SINE ? 2.0 * M_PI : M_PI;
}

/* omega_e/p of curve c at point i. */
static double ratio_at(const boundary_t *B, size_t c, size_t i)
{
    if (B->b.durations) return shape_angle(B) / (B->b.durations[i] * B->cv[c].p);
    return B->b.ratios[i];
}

/* ms, the pulse duration of curve c at point i. */
static double duration_ms(const boundary_t *B, size_t c, size_t i)
{
    if (B->b.durations) return B->b.durations[i] * 1e3;
    return shape_angle(B) / (B->b.ratios[i] * B->cv[c].p) * 1e3;
}

/* The value of a row's first column: the duration (ms) with
 * --pulse-duration, else omega_e/p (the same for every curve). */
static double key_at(const boundary_t *B, size_t i)
{
    return B->b.durations ? B->b.durations[i] * 1e3 : B->b.ratios[i];
}

/* The other quantity of row i (omega_e/p or the duration), of curve c. */
static double other_at(const boundary_t *B, size_t c, size_t i)
{
    return B->b.durations ? ratio_at(B, c, i) : duration_ms(B, c, i);
}

static const char *key_name(const boundary_t *B)
{
    return B->b.durations ? "duration_ms" : "omega_ratio";
}

static const char *other_name(const boundary_t *B)
{
    return B->b.durations ? "omega_ratio" : "duration_ms";
}

/* Amplitudes in the units written, per unit of g tan alpha of curve c. */
static double unit_scale(const boundary_t *B, size_t c)
{
    switch (B->units) {
    case UNITS_G: return B->cv[c].gtan / G0;
    case UNITS_MPS2: return B->cv[c].gtan;
    default: return 1.0;
    }
}

/* The unit after a curve's name in a CSV header: " (g)", " (m/s^2)". */
static const char *unit_suffix(const boundary_t *B)
{
    return B->units == UNITS_G ? " (g)" : B->units == UNITS_MPS2 ? " (m/s^2)" : "";
}

/* ---- progress ------------------------------------------------------------------ */

/* The curves are swept in groups: the points before this group, and all. */
typedef struct {
    size_t offset, total;
} progress_t;

static void on_progress(void *user, size_t done, size_t total)
{
    const progress_t *P = user;
    (void)total;
    done += P->offset;
    fprintf(stderr, "\rswaywatch: boundary %3.0f%% (%zu/%zu points)", 100.0 * done / P->total,
            done, P->total);
    if (done == P->total) fputc('\n', stderr);
    fflush(stderr);
}

/* ---- output -------------------------------------------------------------------- */

static void csv_num(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, "%.6g", v);
}

/* A header field "<label><text>". */
static void csv_label(FILE *f, const char *label, const char *text)
{
    char h[320];
    snprintf(h, sizeof h, "%s%s", label, text);
    sw_cli_csv_text(f, h);
}

static long write_curves(FILE *f, const boundary_t *B)
{
    const size_t nc = B->nc, nr = B->b.nr;
    const int per_curve = B->physical && !B->shared_p; /* the other quantity per curve */
    char other[32];
    snprintf(other, sizeof other, " %s", other_name(B));
    fputs(key_name(B), f);
    if (B->physical && B->shared_p) fprintf(f, ",%s", other_name(B));
    for (size_t c = 0; c < nc; c++) {
        if (per_curve) {
            fputc(',', f);
            csv_label(f, B->cv[c].label, other);
        }
        fputc(',', f);
        csv_label(f, B->cv[c].label, unit_suffix(B));
    }
    fputc('\n', f);
    for (size_t i = 0; i < nr; i++) {
        fprintf(f, "%.6g", key_at(B, i));
        if (B->physical && B->shared_p) fprintf(f, ",%.6g", other_at(B, 0, i));
        for (size_t c = 0; c < nc; c++) {
            const sw_boundary_point_t *P = &B->pts[c * nr + i];
            if (per_curve) fprintf(f, ",%.6g", other_at(B, c, i));
            fputc(',', f);
            if (P->th.found) csv_num(f, P->th.x * unit_scale(B, c));
        }
        fputc('\n', f);
    }
    return (long)nr;
}

static const char *end_name(sw_run_end e)
{
    switch (e) {
    case SW_END_OVERTURN: return "overturn";
    case SW_END_FALLING: return "falling";
    case SW_END_REST: return "rest";
    case SW_END_BOUND: return "bound";
    case SW_END_TIMEOUT: return "timeout";
    }
    return "unknown";
}

static long write_detail(FILE *f, const boundary_t *B)
{
    const size_t nc = B->nc, nr = B->b.nr;
    fputs("curve,omega_ratio,found,boundary,safe_below,lift,impacts,uplift_side,overturn_side,"
          "uplift_time,tip_time,overturn_time,end,trials,duration_ms,boundary_g\n",
          f);
    for (size_t c = 0; c < nc; c++)
        for (size_t i = 0; i < nr; i++) {
            const sw_boundary_point_t *P = &B->pts[c * nr + i];
            const sw_run_result_t *r = &P->th.at_x;
            sw_cli_csv_text(f, B->cv[c].label);
            fprintf(f, ",%.6g,%d,", ratio_at(B, c, i), P->th.found);
            if (P->th.found) {
                csv_num(f, P->th.x);
                fputc(',', f);
                if (!P->th.at_min) csv_num(f, P->th.x_safe);
                fputc(',', f);
                csv_num(f, P->x_lift);
                fprintf(f, ",%ld,%d,%d,", r->impacts, r->uplift_side, r->overturn_side);
                csv_num(f, r->uplift_time);
                fputc(',', f);
                csv_num(f, r->tip_time);
                fputc(',', f);
                csv_num(f, r->overturn_time);
                fprintf(f, ",%s", end_name(r->end));
            } else {
                fputs(",,", f);
                csv_num(f, P->x_lift);
                fputs(",,,,,,,", f);
            }
            fprintf(f, ",%ld,%.6g,", P->th.trials, duration_ms(B, c, i));
            if (P->th.found) csv_num(f, P->th.x * B->cv[c].gtan / G0);
            fputc('\n', f);
        }
    return (long)(nc * nr);
}

static long write_islands(FILE *f, const boundary_t *B)
{
    const size_t nc = B->nc, nr = B->b.nr;
    if (B->physical)
        fprintf(f, "curve,omega_ratio,duration_ms,from%s,to%s,open\n", unit_suffix(B),
                unit_suffix(B));
    else
        fputs("curve,omega_ratio,from,to,open\n", f);
    long rows = 0;
    for (size_t c = 0; c < nc; c++)
        for (size_t i = 0; i < nr; i++) {
            const sw_threshold_t *T = &B->pts[c * nr + i].th;
            const double k = unit_scale(B, c);
            for (int j = 0; j < T->n_islands; j++, rows++) {
                sw_cli_csv_text(f, B->cv[c].label);
                fprintf(f, ",%.6g", ratio_at(B, c, i));
                if (B->physical) fprintf(f, ",%.6g", duration_ms(B, c, i));
                fprintf(f, ",%.6g,%.6g,%d\n", T->islands[j].lo * k, T->islands[j].hi * k,
                        T->islands[j].open);
            }
        }
    return rows;
}

/* Write path with fn; *rows gets the data rows written. */
static int write_file(const char *path, const boundary_t *B,
                      long (*fn)(FILE *, const boundary_t *), long *rows)
{
    FILE *f = sw_cli_out_open(path);
    if (!f) return SW_EXIT_IO;
    *rows = fn(f, B);
    return sw_cli_out_close(f, path);
}

/* ---- figure -------------------------------------------------------------------- */

static const char *const colours[] = {"#1d3557", "#e76f51", "#2a9d8f", "#8338ec",
                                      "#f4a261", "#6a994e", "#b5179e", "#457b9d"};
#define NCOLOURS (sizeof colours / sizeof colours[0])

/* The curve's points as datablocks: $c<c> the boundary (NaN where none),
 * $b<c> / $f<c> the points overturning back / forward, $n<c> the points
 * with no overturn up to the scan's end (drawn there), $i<c> the safe
 * islands (x, from, to). */
static void curve_blocks(FILE *g, const boundary_t *B, size_t c)
{
    const size_t nr = B->b.nr;
    const double k = unit_scale(B, c);
    const char *names = "cbfni";
    for (const char *n = names; *n; n++) {
        int any = 0;
        fprintf(g, "$%c%zu << EOD\n", *n, c);
        for (size_t i = 0; i < nr; i++) {
            const sw_threshold_t *T = &B->pts[c * nr + i].th;
            const double x = key_at(B, i);
            const int side = T->at_x.overturn_side;
            switch (*n) {
            case 'c':
                fprintf(g, "%.9g %.9g\n", x, T->found ? T->x * k : NAN);
                any = 1;
                break;
            case 'b':
            case 'f':
                if (T->found && (*n == 'b' ? side < 0 : side > 0)) {
                    fprintf(g, "%.9g %.9g\n", x, T->x * k);
                    any = 1;
                }
                break;
            case 'n':
                if (!T->found) {
                    fprintf(g, "%.9g %.9g\n", x, B->cv[c].x_max * k);
                    any = 1;
                }
                break;
            default:
                for (int j = 0; j < T->n_islands; j++, any = 1)
                    fprintf(g, "%.9g %.9g %.9g\n", x, T->islands[j].lo * k,
                            T->islands[j].hi * k);
            }
        }
        if (!any) fputs(*n == 'i' ? "NaN NaN NaN\n" : "NaN NaN\n", g);
        fputs("EOD\n", g);
    }
}

/* Half the width of an island's box: a third of the closest spacing of
 * the points, so neighbours never touch. */
static double island_half_width(const boundary_t *B, double lo, double hi)
{
    double gap = INFINITY;
    for (size_t i = 0; i < B->b.nr; i++)
        for (size_t j = i + 1; j < B->b.nr; j++) {
            const double d = fabs(key_at(B, i) - key_at(B, j));
            if (d > 0.0 && d < gap) gap = d;
        }
    return isfinite(gap) ? gap / 3.0 : fmax(hi - lo, fabs(lo)) * 0.02 + 1e-9;
}

/* Tics of the top axis, whose value is K/x: round values (1, 1.5, 2, 3,
 * 4, 5, 6, 8 times a power of ten) at least 7 % of the width apart, as
 * gnuplot would place them on a linear axis of their own. */
static void x2_tics(FILE *g, double K, double x0, double x1)
{
    static const double mant[] = {1, 1.5, 2, 3, 4, 5, 6, 8};
    const double v0 = K / x1, v1 = K / x0; /* the top axis's range, increasing */
    const double min_gap = 0.07 * (x1 - x0);
    double last_x = NAN;
    int n = 0;
    fputs("set x2tics (", g);
    for (double dec = pow(10.0, floor(log10(v0))); dec <= v1 && n < 40; dec *= 10.0)
        for (size_t m = 0; m < sizeof mant / sizeof mant[0]; m++) {
            const double v = mant[m] * dec;
            if (v < v0 || v > v1) continue;
            const double x = K / v;
            if (isfinite(last_x) && fabs(last_x - x) < min_gap) continue;
            fprintf(g, "%s%.6g", n++ ? ", " : "", v);
            last_x = x;
        }
    fputs(")\n", g);
}

static int plot(const char *path, const boundary_t *B)
{
    const size_t nc = B->nc, nr = B->b.nr;
    double lo = INFINITY, hi = -INFINITY, top = 0.0;
    for (size_t i = 0; i < nr; i++) {
        lo = fmin(lo, key_at(B, i));
        hi = fmax(hi, key_at(B, i));
    }
    /* What there is to draw; the maximum searched is in the picture when a
     * point reached it without an overturn, or an island is open to it. */
    int same_max = 1, islands = 0, back = 0, fwd = 0, none = 0, open = 0;
    double top_max = 0.0;
    for (size_t c = 0; c < nc; c++) {
        const double k = unit_scale(B, c), m = B->cv[c].x_max * k;
        same_max = same_max && fabs(m - B->cv[0].x_max * unit_scale(B, 0)) <= 1e-9 * m;
        top_max = fmax(top_max, m);
        for (size_t i = 0; i < nr; i++) {
            const sw_threshold_t *T = &B->pts[c * nr + i].th;
            if (T->found) top = fmax(top, T->x * k);
            back += T->found && T->at_x.overturn_side < 0;
            fwd += T->found && T->at_x.overturn_side > 0;
            none += !T->found;
            islands += T->n_islands;
            for (int j = 0; j < T->n_islands; j++) {
                top = fmax(top, T->islands[j].hi * k);
                open += T->islands[j].open;
            }
        }
    }
    const int show_max = none || open || top_max <= 1.3 * top;
    if (show_max || !(top > 0.0)) top = fmax(top, top_max);
    const double pad = hi > lo ? 0.015 * (hi - lo) : 0.05 * fmax(fabs(lo), 1e-6);
    sw_plot_t *p = sw_cli_plot_open(path, 1200, 650);
    if (!p) return SW_EXIT_IO;
    FILE *g = sw_cli_plot_file(p);
    char deftitle[128];
    snprintf(deftitle, sizeof deftitle, "Overturning boundary, %s pulse",
             sw_pulse_shape_name(B->b.bo.shape));
    fputs("set title ", g);
    sw_cli_plot_text(g, B->b.title ? B->b.title : deftitle);
    fprintf(g, "\nset xlabel '%s'\nset ylabel '%s'\n",
            B->b.durations ? "pulse duration (ms)" : "ω_e / p",
            B->units == UNITS_G      ? "peak acceleration a_e (g)"
            : B->units == UNITS_MPS2 ? "peak acceleration a_e (m/s^2)"
                                     : "a_e / (g tan α)");
    fprintf(g,
            "set grid\nset key at screen 0.675, graph 1 left top Left reverse box opaque\n"
            "set lmargin at screen 0.07\nset rmargin at screen 0.66\n"
            "set xrange [%.9g:%.9g]\nset yrange [0:%.9g]\nset datafile missing 'NaN'\n",
            lo - pad, hi + pad, 1.08 * top);
    if (B->physical && B->shared_p) {
        /* the other quantity along the top: duration = angle / (ratio p), both ways */
        const double K = shape_angle(B) * 1e3 / B->cv[0].p;
        fprintf(g, "set link x2 via %.12g/x inverse %.12g/x\nset xtics nomirror\n"
                   "set x2label '%s'\n",
                K, K, B->b.durations ? "ω_e / p" : "pulse duration (ms)");
        x2_tics(g, K, lo - pad, hi + pad);
    }
    fputs("set label 1 'a_e > 0 speeds the truck up: the package sways back first;' "
          "at screen 0.675, screen 0.16 left font ',9'\n"
          "set label 2 'under braking, forward and back swap.' "
          "at screen 0.675, screen 0.125 left font ',9'\n",
          g);
    const double w = island_half_width(B, lo, hi);
    for (size_t c = 0; c < nc; c++) curve_blocks(g, B, c);
    fputs("plot ", g);
    for (size_t c = 0; c < nc; c++) {
        const char *col = colours[c % NCOLOURS];
        if (islands)
            fprintf(g,
                    "$i%zu using 1:(($2+$3)/2):($1-%.9g):($1+%.9g):2:3 with boxxyerror "
                    "fs transparent solid 0.25 noborder lc rgb '%s' notitle, \\\n     ",
                    c, w, w, col);
        fprintf(g, "$c%zu using 1:2 with lines lw 2 lc rgb '%s' title ", c, col);
        sw_cli_plot_text(g, B->cv[c].label);
        fprintf(g,
                ", $b%zu using 1:2 with points pt 7 ps 0.9 lc rgb '%s' notitle"
                ", $f%zu using 1:2 with points pt 11 ps 1.3 lc rgb '%s' notitle"
                ", $n%zu using 1:2 with points pt 8 ps 1.4 lc rgb '%s' notitle",
                c, col, c, col, c, col);
        if (show_max && !same_max)
            fprintf(g, ", %.9g with lines lc rgb '%s' dt 2 notitle",
                    B->cv[c].x_max * unit_scale(B, c), col);
        fputs(", \\\n     ", g);
    }
    if (show_max && same_max)
        fprintf(g, "%.9g with lines lc rgb '#888888' dt 2 title 'the maximum searched'",
                B->cv[0].x_max * unit_scale(B, 0));
    else if (show_max)
        fputs("NaN with lines lc rgb '#888888' dt 2 title 'the maximum searched (each curve)'", g);
    else
        fputs("NaN notitle", g);
    if (back)
        fputs(", NaN with points pt 7 ps 0.9 lc rgb 'black' title 'overturns back (top to the "
              "rear)'",
              g);
    if (fwd)
        fputs(", NaN with points pt 11 ps 1.3 lc rgb 'black' title 'overturns forward (top to "
              "the front)'",
              g);
    if (none)
        fputs(", NaN with points pt 8 ps 1.4 lc rgb 'black' title 'no overturn up to the "
              "maximum'",
              g);
    if (islands)
        fputs(", NaN with boxes fs transparent solid 0.25 noborder lc rgb '#555555' "
              "title 'safe islands above the boundary'",
              g);
    fputc('\n', g);
    return sw_cli_plot_close(p);
}

/* ---- the command --------------------------------------------------------------- */

/* What the options leave to check together; the search's defaults. */
static int check_options(boundary_t *B, int argc, char **argv, int first)
{
    sw_boundary_opts_t *bo = &B->b.bo;
    if (sw_cli_no_operand("boundary", argc, argv, first) != SW_EXIT_OK) return SW_EXIT_USAGE;
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
    if (!(bo->search.x_max > 0.0) && !(B->b.max_si > 0.0)) bo->search.x_max = DEFAULT_X_MAX;
    if (bo->search.x_max > 0.0 && bo->search.x_min >= bo->search.x_max) {
        sw_cli_error("--min-amplitude %g is not below the default --max-amplitude %g",
                     bo->search.x_min, bo->search.x_max);
        return SW_EXIT_USAGE;
    }
    B->units = B->b.units >= 0 ? B->b.units : B->b.durations ? UNITS_G : UNITS_GTAN;
    B->physical = B->units != UNITS_GTAN || B->b.durations != NULL;
    /* The curves go to standard output unless --out names a file; "-"
     * gives it to one of the CSV files. */
    const char *taken = !B->b.out || !strcmp(B->b.out, "-") ? "the curves (give --out a file)"
                                                             : NULL;
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
    if (!B->b.nbear) return SW_EXIT_OK;
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

/* Non-zero (reported) if v, what arg (given in physical units) is for
 * curve C, is outside the bounds of the option named opt. */
static int in_range(const char *opt, const char *arg, const curve_t *C, double v)
{
    const sw_cli_option_t *o = boundary_options;
    while (o->kind != SW_CLI_END && !(o->long_name && !strcmp(o->long_name, opt))) o++;
    if (o->kind == SW_CLI_END || !(o->hi > o->lo) || (v >= o->lo && v <= o->hi)) return 0;
    sw_cli_error("curve '%s': %s is %g %s, out of range: expected %g to %g", C->label,
                 arg ? arg : "", v, strcmp(opt, "omega-ratio") ? "g tan alpha" : "omega_e/p",
                 o->lo, o->hi);
    return 1;
}

/* Each curve's p, g tan alpha and scan range (amplitudes given in g or
 * m/s^2 are a different g tan alpha for each package). */
static int curve_units(boundary_t *B)
{
    const sw_boundary_opts_t *bo = &B->b.bo;
    for (size_t c = 0; c < B->nc; c++) {
        curve_t *C = &B->cv[c];
        sw_scene_t s;
        sw_derived_t d;
        sw_curve_scene(&C->c, 0.0, &s);
        if (sw_scene_validate(&s, &d, NULL, NULL, NULL) != SW_OK) {
            sw_cli_error("%s: invalid scene", C->label);
            return SW_EXIT_USAGE;
        }
        C->p = d.p;
        C->gtan = s.g * tan(d.alpha);
        C->x_min = B->b.min_si > 0.0 ? B->b.min_si / C->gtan : bo->search.x_min;
        C->x_max = B->b.max_si > 0.0 ? B->b.max_si / C->gtan : bo->search.x_max;
        /* what the options' bounds say in g tan alpha and omega_e/p, for
         * the values given in g, m/s^2 or ms */
        if ((B->b.min_si > 0.0 && in_range("min-amplitude", B->b.min_arg, C, C->x_min)) ||
            (B->b.max_si > 0.0 && in_range("max-amplitude", B->b.max_arg, C, C->x_max)))
            return SW_EXIT_USAGE;
        for (size_t i = 0; B->b.durations && i < B->b.nr; i++) {
            char dur[64];
            snprintf(dur, sizeof dur, "%gms", B->b.durations[i] * 1e3);
            if (in_range("omega-ratio", dur, C, ratio_at(B, c, i))) return SW_EXIT_USAGE;
        }
        if (C->x_min > 0.0 && C->x_min >= C->x_max) {
            sw_cli_error("curve '%s': --min-amplitude %s (%g g tan alpha) is not below "
                         "--max-amplitude %s (%g g tan alpha)",
                         C->label, B->b.min_arg ? B->b.min_arg : "", C->x_min,
                         B->b.max_arg ? B->b.max_arg : "20", C->x_max);
            return SW_EXIT_USAGE;
        }
    }
    B->shared_p = 1;
    for (size_t c = 1; c < B->nc; c++)
        B->shared_p = B->shared_p && fabs(B->cv[c].p - B->cv[0].p) <= 1e-12 * B->cv[0].p;
    return SW_EXIT_OK;
}

/* --verbose: what each curve's scene is. */
static void print_curves(const boundary_t *B)
{
    for (size_t c = 0; c < B->nc; c++) {
        const curve_t *C = &B->cv[c];
        sw_derived_t d;
        sw_scene_t s; /* omega_b is set per point */
        sw_curve_scene(&C->c, 0.0, &s);
        if (sw_scene_validate(&s, &d, NULL, NULL, NULL) != SW_OK) continue;
        fprintf(stderr,
                "swaywatch: curve %zu '%s': %s model, alpha %.4g deg, p %.6g rad/s, "
                "g tan alpha %.6g m/s^2",
                c + 1, C->label, sw_model_name(d.model), d.alpha * 180.0 / M_PI, d.p,
                s.g * tan(d.alpha));
        if (d.model == SW_MODEL_FRAME)
            fprintf(stderr, ", gamma %.4g, zeta_b %.4g, omega_b %s", d.gamma, d.zeta_b,
                    C->c.bearing_ratio > 0.0 ? "per point" : "");
        if (d.model == SW_MODEL_FRAME && !(C->c.bearing_ratio > 0.0))
            fprintf(stderr, "%.6g rad/s", d.omega_b);
        fputc('\n', stderr);
    }
}

/* Curves a and b take the same points and the same scan: one sweep. */
static int same_sweep(const boundary_t *B, size_t a, size_t b)
{
    const curve_t *A = &B->cv[a], *C = &B->cv[b];
    return A->x_min == C->x_min && A->x_max == C->x_max && (!B->b.durations || A->p == C->p);
}

/* ---- the points over the ranks of an MPI job -------------------------------------- */

/* One group's sweep: its curves at its ratios, into gp (curve-major). */
typedef struct {
    const sw_cli_world_t *world;
    const sw_curve_t *curves;
    size_t k;
    const double *ratios;
    size_t nr;
    const sw_boundary_opts_t *bo;
    sw_boundary_point_t *gp;
    char (*msgs)[256];
    int progress;
} group_t;

/* One point, on any thread of any rank: the point, then its message. */
static void point_run(void *user, size_t i, FILE *out)
{
    const group_t *G = user;
    sw_boundary_point_t pt;
    memset(&pt, 0, sizeof pt);
    char msg[256] = "";
    sw_boundary_point(&G->curves[i / G->nr], G->ratios[i % G->nr], G->bo, &pt, msg,
                      sizeof msg);
    fwrite(&pt, sizeof pt, 1, out);
    fputs(msg, out);
}

static int point_take(void *user, size_t i, const char *data, size_t len, const char *msgs,
                      size_t mlen)
{
    group_t *G = user;
    if (mlen) fwrite(msgs, 1, mlen, stderr);
    if (len < sizeof *G->gp) {
        sw_cli_error("boundary: point %zu came back short", i + 1);
        return -1;
    }
    memcpy(&G->gp[i], data, sizeof *G->gp);
    size_t m = len - sizeof *G->gp;
    if (m >= sizeof G->msgs[i]) m = sizeof G->msgs[i] - 1;
    memcpy(G->msgs[i], data + sizeof *G->gp, m);
    G->msgs[i][m] = '\0';
    return 0;
}

/* What sw_boundary_sweep() does, with the points spread over the ranks:
 * the same points, the same first failure in (curve, ratio) order.
 * *exit_code: the exit code if it failed. */
static int sweep_ranks(group_t *G, char *msg, size_t msglen, int *exit_code)
{
    const size_t np = G->k * G->nr;
    G->msgs = calloc(np, sizeof *G->msgs);
    if (!G->msgs) {
        snprintf(msg, msglen, "out of memory");
        *exit_code = SW_EXIT_IO;
        return SW_ENOMEM;
    }
    const sw_cli_farm_t farm = {
        .world = G->world,
        .n = np,
        .threads = G->bo->threads,
        .run = point_run,
        .take = point_take,
        .user = G,
        .what = G->progress ? "points" : NULL,
    };
    *exit_code = sw_cli_farm_run(&farm);
    int rc = *exit_code == SW_EXIT_OK ? SW_OK : SW_ENOMEM;
    if (rc != SW_OK) snprintf(msg, msglen, "the points could not be gathered");
    else *exit_code = SW_EXIT_USAGE; /* if a point failed */
    for (size_t i = 0; rc == SW_OK && G->world->rank == 0 && i < np; i++)
        if (G->gp[i].status < 0) {
            rc = G->gp[i].status;
            snprintf(msg, msglen, "curve %zu, omega_e/p = %g: %s", i / G->nr + 1,
                     G->gp[i].omega_ratio, G->msgs[i][0] ? G->msgs[i] : sw_strerror(rc));
        }
    free(G->msgs);
    G->msgs = NULL;
    return rc;
}

/* Every curve at every point, in groups of curves that share the points
 * and the scan (one group, all the curves, in dimensionless units). */
static int sweep(boundary_t *B)
{
    const size_t nc = B->nc, nr = B->b.nr;
    int rc = SW_EXIT_IO;
    B->pts = calloc(nc * nr, sizeof *B->pts);
    sw_curve_t *curves = calloc(nc, sizeof *curves);
    size_t *member = calloc(nc, sizeof *member);
    unsigned char *done = calloc(nc, 1);
    double *ratios = calloc(nr, sizeof *ratios);
    sw_boundary_point_t *gp = calloc(nc * nr, sizeof *gp);
    if (!B->pts || !curves || !member || !done || !ratios || !gp) {
        sw_cli_error("out of memory");
        goto out;
    }
    progress_t P = {0, nc * nr};
    /* The sweep cannot stop between points and writes nothing: a signal
     * ends the process at once. */
    sw_cli_interrupt_now("boundary: interrupted during the sweep; nothing written");
    for (size_t c0 = 0; c0 < nc; c0++) {
        if (done[c0]) continue;
        size_t k = 0;
        for (size_t c = c0; c < nc; c++)
            if (!done[c] && same_sweep(B, c0, c)) {
                done[c] = 1;
                member[k] = c;
                curves[k++] = B->cv[c].c;
            }
        for (size_t i = 0; i < nr; i++) ratios[i] = ratio_at(B, c0, i);
        sw_boundary_opts_t bo = B->b.bo;
        bo.search.x_min = B->cv[c0].x_min;
        bo.search.x_max = B->cv[c0].x_max;
        bo.progress = B->b.progress && B->world.size == 1 ? on_progress : NULL;
        bo.user = &P;
        char msg[512] = "";
        int sr, code = SW_EXIT_USAGE;
        if (B->world.size > 1) {
            group_t G = {&B->world, curves, k, ratios, nr, &bo, gp, NULL, B->b.progress};
            sr = sweep_ranks(&G, msg, sizeof msg, &code);
        } else {
            sr = sw_boundary_sweep(curves, k, ratios, nr, &bo, gp, msg, sizeof msg);
        }
        for (size_t j = 0; j < k; j++)
            memcpy(&B->pts[member[j] * nr], &gp[j * nr], nr * sizeof *gp);
        P.offset += k * nr;
        if (sr != SW_OK && B->world.rank != 0) { /* rank 0 says why */
            rc = code;
            goto out;
        }
        if (sr != SW_OK) {
            /* the library numbers the curves of the group: name the curve instead */
            size_t bad = 0;
            while (bad + 1 < k * nr && gp[bad].status >= 0) bad++;
            const char *why = msg;
            if (!strncmp(why, "curve ", 6) && strstr(why, ", ")) why = strstr(why, ", ") + 2;
            sw_cli_error("boundary: curve '%s', %s", B->cv[member[bad / nr]].label,
                         why[0] ? why : sw_strerror(sr));
            rc = code;
            goto out;
        }
    }
    rc = SW_EXIT_OK;
out:
    sw_cli_interrupt_now(NULL);
    free(curves);
    free(member);
    free(done);
    free(ratios);
    free(gp);
    return rc;
}

/* The points that need a word: not overturned, an upper bound, more
 * islands than listed. */
static void notes(const boundary_t *B)
{
    long at_min = 0, missing = 0, truncated = 0;
    const size_t np = B->nc * B->b.nr;
    for (size_t i = 0; i < np; i++) {
        at_min += B->pts[i].th.found && B->pts[i].th.at_min;
        missing += !B->pts[i].th.found;
        truncated += B->pts[i].th.islands_truncated;
    }
    if (missing) {
        char max[64];
        if (B->b.max_arg)
            snprintf(max, sizeof max, "%s", B->b.max_arg);
        else
            snprintf(max, sizeof max, "%g", DEFAULT_X_MAX);
        sw_cli_error("boundary: %ld of %zu points did not overturn up to --max-amplitude %s "
                     "(empty fields)",
                     missing, np, max);
    }
    if (at_min)
        sw_cli_error("boundary: %ld points overturned at --min-amplitude already: their "
                     "value is an upper bound",
                     at_min);
    if (truncated)
        sw_cli_error("boundary: %ld points have more than %d safe islands; the rest are "
                     "not listed",
                     truncated, SW_MAX_ISLANDS);
}

/* The files, each said on stderr with what it holds, then the points that
 * need a word (unless --quiet). */
static int write_outputs(const boundary_t *B)
{
    const size_t nc = B->nc;
    const int say = !B->b.quiet;
    const char *out = B->b.out ? B->b.out : "-";
    long rows = 0;
    int rc = write_file(out, B, write_curves, &rows);
    if (rc == SW_EXIT_OK && say)
        sw_cli_error("boundary: wrote %s: %zu curve%s at %ld point%s", sw_cli_out_name(out), nc,
                     nc == 1 ? "" : "s", rows, rows == 1 ? "" : "s");
    if (rc == SW_EXIT_OK && B->b.detail) {
        rc = write_file(B->b.detail, B, write_detail, &rows);
        if (rc == SW_EXIT_OK && say)
            sw_cli_error("boundary: wrote %s: %ld row%s, one per curve and point",
                         sw_cli_out_name(B->b.detail), rows, rows == 1 ? "" : "s");
    }
    if (rc == SW_EXIT_OK && B->b.islands) {
        rc = write_file(B->b.islands, B, write_islands, &rows);
        if (rc == SW_EXIT_OK && say)
            sw_cli_error("boundary: wrote %s: %ld safe island%s", sw_cli_out_name(B->b.islands),
                         rows, rows == 1 ? "" : "s");
    }
    if (rc == SW_EXIT_OK && B->b.plot) {
        rc = plot(B->b.plot, B);
        if (rc == SW_EXIT_OK && say)
            sw_cli_error("boundary: wrote %s: a figure of %zu curve%s", B->b.plot, nc,
                         nc == 1 ? "" : "s");
    }
    if (!say) return rc;
    notes(B);
    return rc;
}

int cmd_boundary(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    boundary_t B;
    memset(&B, 0, sizeof B);
    if ((rc = sw_cli_world_start(&B.world)) != SW_EXIT_OK) return rc;
    /* Every rank sets up as rank 0 does; the others keep their messages
     * to themselves unless they alone fail. */
    char *msgs = NULL;
    size_t mlen = 0;
    FILE *mf = B.world.rank != 0 ? open_memstream(&msgs, &mlen) : NULL;
    if (mf) sw_cli_msg_to(mf);
    B.b.progress = B.world.rank == 0 && isatty(fileno(stderr)) ? 1 : 0;
    B.b.units = -1;
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
            (rc = build_curves(B.scenes, B.nsc, B.b.vary, B.b.nvary, B.b.bearing, B.b.nbear,
                               B.bear_text, &B.cv, &B.nc)) == SW_EXIT_OK)
            rc = curve_units(&B);
    }
    if (mf) {
        sw_cli_msg_to(NULL);
        fclose(mf);
    }
    rc = sw_cli_world_agree(&B.world, rc, msgs, mlen);
    free(msgs);
    if (rc != SW_EXIT_OK || help) goto out;
    if (B.world.rank == 0) {
        if (B.o.verbose) print_curves(&B);
        sw_cli_warn_scene_cost(B.scenes, B.nsc, &B.b.bo.run.engine);
    }
    if ((rc = sweep(&B)) != SW_EXIT_OK || B.world.rank != 0) goto out;
    rc = write_outputs(&B);
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
