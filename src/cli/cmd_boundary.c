/* cmd_boundary.c - "swaywatch boundary": overturning boundary curves, the
 * lowest pulse amplitude a_e/(g tan alpha) that overturns the package as a
 * function of omega_e/p, for one or more curves (scenes, --vary values of
 * a scene key, --bearing-ratio values), as CSV and optionally a figure.
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
    b->ratios = NULL;
    b->nr = 0;
    char opt[64];
    snprintf(opt, sizeof opt, "--%s", o->long_name);
    int rc = sw_cli_parse_range(opt, arg, MAX_POINTS, &b->ratios, &b->nr);
    return rc == SW_EXIT_OK ? check_values(o, b->ratios, b->nr) : rc;
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
     .help = "omega_e/p values: FROM:TO:STEP (inclusive) or a list R1,R2,... (required); below "
             "1e-3 a pulse lasts thousands of rocking periods, above 1e4 it is far shorter "
             "than a step"},
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
    {SW_CLI_DOUBLE, 0, "min-amplitude", "X", BO(bo.search.x_min), .rule = SW_NUM_POSITIVE,
     .lo = 1e-3, .hi = 1e4,
     .what = "a positive amplitude in g tan alpha",
     .help = "start of the scan, in g tan alpha (default: the lowest amplitude that can lift "
             "the package at all)"},
    {SW_CLI_DOUBLE, 0, "max-amplitude", "X", BO(bo.search.x_max), .rule = SW_NUM_POSITIVE,
     .lo = 1e-3, .hi = 1e4, .what = "a positive amplitude in g tan alpha",
     .help = "end of the scan (default 20); a curve with no overturn up to it has an empty "
             "field at that point; 1e4 g tan alpha is beyond any accelerometer"},
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
    {SW_CLI_STRING, 'o', "out", "FILE.csv", BO(out),
     .help = "the curves (default, or '-': standard output): omega_ratio,<curve 1>,<curve 2>,... in "
             "units of g tan alpha"},
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
             "                          --omega-ratio FROM:TO:STEP [options]",
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
        "reported, and with --islands the safe islands above it.\n",
};

/* ---- curves -------------------------------------------------------------------- */

typedef struct {
    sw_curve_t c;
    char label[256];
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

/* ---- progress ------------------------------------------------------------------ */

static void on_progress(void *user, size_t done, size_t total)
{
    (void)user;
    fprintf(stderr, "\rswaywatch: boundary %3.0f%% (%zu/%zu points)", 100.0 * done / total, done,
            total);
    if (done == total) fputc('\n', stderr);
    fflush(stderr);
}

/* ---- output -------------------------------------------------------------------- */

static void csv_num(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, "%.6g", v);
}

static long write_curves(FILE *f, const curve_t *cv, size_t nc, const double *ratios, size_t nr,
                         const sw_boundary_point_t *pts)
{
    fputs("omega_ratio", f);
    for (size_t c = 0; c < nc; c++) {
        fputc(',', f);
        sw_cli_csv_text(f, cv[c].label);
    }
    fputc('\n', f);
    for (size_t i = 0; i < nr; i++) {
        fprintf(f, "%.6g", ratios[i]);
        for (size_t c = 0; c < nc; c++) {
            const sw_boundary_point_t *P = &pts[c * nr + i];
            fputc(',', f);
            if (P->th.found) csv_num(f, P->th.x);
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

static long write_detail(FILE *f, const curve_t *cv, size_t nc, const double *ratios, size_t nr,
                         const sw_boundary_point_t *pts)
{
    fputs("curve,omega_ratio,found,boundary,safe_below,lift,impacts,uplift_side,overturn_side,"
          "uplift_time,tip_time,overturn_time,end,trials\n",
          f);
    for (size_t c = 0; c < nc; c++)
        for (size_t i = 0; i < nr; i++) {
            const sw_boundary_point_t *P = &pts[c * nr + i];
            const sw_run_result_t *r = &P->th.at_x;
            sw_cli_csv_text(f, cv[c].label);
            fprintf(f, ",%.6g,%d,", ratios[i], P->th.found);
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
            fprintf(f, ",%ld\n", P->th.trials);
        }
    return (long)(nc * nr);
}

static long write_islands(FILE *f, const curve_t *cv, size_t nc, const double *ratios, size_t nr,
                          const sw_boundary_point_t *pts)
{
    fputs("curve,omega_ratio,from,to,open\n", f);
    long rows = 0;
    for (size_t c = 0; c < nc; c++)
        for (size_t i = 0; i < nr; i++) {
            const sw_threshold_t *T = &pts[c * nr + i].th;
            for (int k = 0; k < T->n_islands; k++, rows++) {
                sw_cli_csv_text(f, cv[c].label);
                fprintf(f, ",%.6g,%.6g,%.6g,%d\n", ratios[i], T->islands[k].lo, T->islands[k].hi,
                        T->islands[k].open);
            }
        }
    return rows;
}

/* Write path with fn; *rows gets the data rows written. */
static int write_file(const char *path, const curve_t *cv, size_t nc, const double *ratios,
                      size_t nr, const sw_boundary_point_t *pts,
                      long (*fn)(FILE *, const curve_t *, size_t, const double *, size_t,
                                 const sw_boundary_point_t *),
                      long *rows)
{
    FILE *f = sw_cli_out_open(path);
    if (!f) return SW_EXIT_IO;
    *rows = fn(f, cv, nc, ratios, nr, pts);
    return sw_cli_out_close(f, path);
}

static int plot(const char *path, const char *title, sw_pulse_shape shape, const curve_t *cv,
                size_t nc, const double *ratios, size_t nr, const sw_boundary_point_t *pts,
                int islands)
{
    sw_plot_t *p = sw_cli_plot_open(path, 900, 600);
    if (!p) return SW_EXIT_IO;
    FILE *g = sw_cli_plot_file(p);
    char deftitle[128];
    snprintf(deftitle, sizeof deftitle, "Overturning boundary, %s pulse",
             sw_pulse_shape_name(shape));
    fputs("set title ", g);
    sw_cli_plot_text(g, title ? title : deftitle);
    fputs("\nset xlabel 'ω_e / p'\nset ylabel 'a_e / (g tan α)'\n"
          "set grid\nset key top left box opaque\nset yrange [0:*]\n"
          "set datafile missing 'NaN'\n",
          g);
    for (size_t c = 0; c < nc; c++) {
        fprintf(g, "$c%zu << EOD\n", c);
        for (size_t i = 0; i < nr; i++) {
            const sw_boundary_point_t *P = &pts[c * nr + i];
            fprintf(g, "%.9g %.9g\n", ratios[i], P->th.found ? P->th.x : NAN);
        }
        fputs("EOD\n", g);
        if (islands) {
            fprintf(g, "$i%zu << EOD\n", c);
            int any = 0;
            for (size_t i = 0; i < nr; i++) {
                const sw_threshold_t *T = &pts[c * nr + i].th;
                for (int k = 0; k < T->n_islands; k++, any = 1)
                    fprintf(g, "%.9g %.9g %.9g\n", ratios[i], T->islands[k].lo,
                            T->islands[k].hi);
            }
            if (!any) fputs("NaN NaN NaN\n", g);
            fputs("EOD\n", g);
        }
    }
    fputs("plot ", g);
    for (size_t c = 0; c < nc; c++) {
        fprintf(g, "%s$c%zu using 1:2 with linespoints lw 2 pt 7 ps 0.6 lc %zu title ",
                c ? ", \\\n     " : "", c, c + 1);
        sw_cli_plot_text(g, cv[c].label);
        if (islands)
            fprintf(g, ", $i%zu using 1:2:(0):($3-$2) with vectors nohead lw 3 lc %zu "
                       "dt 3 title %s",
                    c, c + 1, c == 0 ? "'safe islands above (dotted)'" : "''");
    }
    fputc('\n', g);
    return sw_cli_plot_close(p);
}

/* ---- the command --------------------------------------------------------------- */

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
    sw_boundary_point_t *pts;
} boundary_t;

/* What the options leave to check together; the search's defaults. */
static int check_options(boundary_t *B, int argc, char **argv, int first)
{
    sw_boundary_opts_t *bo = &B->b.bo;
    if (sw_cli_no_operand("boundary", argc, argv, first) != SW_EXIT_OK) return SW_EXIT_USAGE;
    if (!B->b.have_shape || !B->b.nr) {
        sw_cli_error("boundary: missing %s; see 'swaywatch boundary --help'",
                     !B->b.have_shape ? "--pulse half-sine|full-sine"
                                      : "--omega-ratio FROM:TO:STEP");
        return SW_EXIT_USAGE;
    }
    if (bo->search.x_min > 0.0 && bo->search.x_max > 0.0 && bo->search.x_min >= bo->search.x_max) {
        sw_cli_error("--min-amplitude %g is not below --max-amplitude %g", bo->search.x_min,
                     bo->search.x_max);
        return SW_EXIT_USAGE;
    }
    if (!(bo->search.x_max > 0.0)) bo->search.x_max = 20.0;
    if (bo->search.x_min >= bo->search.x_max) {
        sw_cli_error("--min-amplitude %g is not below the default --max-amplitude %g",
                     bo->search.x_min, bo->search.x_max);
        return SW_EXIT_USAGE;
    }
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

/* ---- the points over the ranks of an MPI job -------------------------------------- */

typedef struct {
    boundary_t *B;
    const sw_curve_t *curves;
    char (*msgs)[256];
} ranks_t;

/* One point, on any thread of any rank: the point, then its message. */
static void point_run(void *user, size_t i, FILE *out)
{
    const ranks_t *R = user;
    const size_t nr = R->B->b.nr;
    sw_boundary_point_t pt;
    memset(&pt, 0, sizeof pt);
    char msg[256] = "";
    sw_boundary_point(&R->curves[i / nr], R->B->b.ratios[i % nr], &R->B->b.bo, &pt, msg,
                      sizeof msg);
    fwrite(&pt, sizeof pt, 1, out);
    fputs(msg, out);
}

static int point_take(void *user, size_t i, const char *data, size_t len, const char *msgs,
                      size_t mlen)
{
    ranks_t *R = user;
    if (mlen) fwrite(msgs, 1, mlen, stderr);
    if (len < sizeof *R->B->pts) {
        sw_cli_error("boundary: point %zu came back short", i + 1);
        return -1;
    }
    memcpy(&R->B->pts[i], data, sizeof *R->B->pts);
    size_t m = len - sizeof *R->B->pts;
    if (m >= sizeof R->msgs[i]) m = sizeof R->msgs[i] - 1;
    memcpy(R->msgs[i], data + sizeof *R->B->pts, m);
    R->msgs[i][m] = '\0';
    return 0;
}

/* What sw_boundary_sweep() does, with the points spread over the ranks:
 * the same points, the same first failure in (curve, ratio) order. */
static int sweep_ranks(boundary_t *B, const sw_curve_t *curves, char *msg, size_t msglen,
                       int *exit_code)
{
    const size_t np = B->nc * B->b.nr;
    ranks_t R = {B, curves, calloc(np, sizeof *R.msgs)};
    if (!R.msgs) {
        snprintf(msg, msglen, "out of memory");
        *exit_code = SW_EXIT_IO;
        return SW_ENOMEM;
    }
    const sw_cli_farm_t farm = {
        .world = &B->world,
        .n = np,
        .threads = B->b.bo.threads,
        .run = point_run,
        .take = point_take,
        .user = &R,
        .what = B->b.progress ? "points" : NULL,
    };
    *exit_code = sw_cli_farm_run(&farm);
    int rc = *exit_code == SW_EXIT_OK ? SW_OK : SW_ENOMEM;
    if (rc != SW_OK) snprintf(msg, msglen, "the points could not be gathered");
    else *exit_code = SW_EXIT_USAGE; /* if a point failed */
    for (size_t i = 0; rc == SW_OK && B->world.rank == 0 && i < np; i++)
        if (B->pts[i].status < 0) {
            rc = B->pts[i].status;
            snprintf(msg, msglen, "curve %zu, omega_e/p = %g: %s", i / B->b.nr + 1,
                     B->pts[i].omega_ratio, R.msgs[i][0] ? R.msgs[i] : sw_strerror(rc));
        }
    free(R.msgs);
    return rc;
}

static int sweep(boundary_t *B)
{
    B->pts = calloc(B->nc * B->b.nr, sizeof *B->pts);
    sw_curve_t *curves = calloc(B->nc, sizeof *curves);
    if (!B->pts || !curves) {
        free(curves);
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    for (size_t c = 0; c < B->nc; c++) curves[c] = B->cv[c].c;
    char msg[512] = "";
    int sr, code = SW_EXIT_USAGE;
    /* The sweep cannot stop between points and writes nothing: a signal
     * ends the process at once. */
    sw_cli_interrupt_now("boundary: interrupted during the sweep; nothing written");
    if (B->world.size > 1) {
        sr = sweep_ranks(B, curves, msg, sizeof msg, &code);
    } else {
        if (B->b.progress) B->b.bo.progress = on_progress;
        sr = sw_boundary_sweep(curves, B->nc, B->b.ratios, B->b.nr, &B->b.bo, B->pts, msg,
                               sizeof msg);
    }
    sw_cli_interrupt_now(NULL);
    free(curves);
    if (sr == SW_OK) return SW_EXIT_OK;
    if (B->world.rank != 0) return code; /* rank 0 says why */
    sw_cli_error("boundary: %s", msg[0] ? msg : sw_strerror(sr));
    return code;
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
    if (missing)
        sw_cli_error("boundary: %ld of %zu points did not overturn up to --max-amplitude %g "
                     "(empty fields)",
                     missing, np, B->b.bo.search.x_max);
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
    const curve_t *cv = B->cv;
    const size_t nc = B->nc, nr = B->b.nr;
    const double *ratios = B->b.ratios;
    const sw_boundary_point_t *pts = B->pts;
    const int say = !B->b.quiet;
    const char *out = B->b.out ? B->b.out : "-";
    long rows = 0;
    int rc = write_file(out, cv, nc, ratios, nr, pts, write_curves, &rows);
    if (rc == SW_EXIT_OK && say)
        sw_cli_error("boundary: wrote %s: %zu curve%s at %ld point%s", sw_cli_out_name(out), nc,
                     nc == 1 ? "" : "s", rows, rows == 1 ? "" : "s");
    if (rc == SW_EXIT_OK && B->b.detail) {
        rc = write_file(B->b.detail, cv, nc, ratios, nr, pts, write_detail, &rows);
        if (rc == SW_EXIT_OK && say)
            sw_cli_error("boundary: wrote %s: %ld row%s, one per curve and point",
                         sw_cli_out_name(B->b.detail), rows, rows == 1 ? "" : "s");
    }
    if (rc == SW_EXIT_OK && B->b.islands) {
        rc = write_file(B->b.islands, cv, nc, ratios, nr, pts, write_islands, &rows);
        if (rc == SW_EXIT_OK && say)
            sw_cli_error("boundary: wrote %s: %ld safe island%s", sw_cli_out_name(B->b.islands),
                         rows, rows == 1 ? "" : "s");
    }
    if (rc == SW_EXIT_OK && B->b.plot) {
        rc = plot(B->b.plot, B->b.title, B->b.bo.shape, cv, nc, ratios, nr, pts,
                  B->b.islands != NULL);
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
            (rc = sw_cli_load_scenes(&B.o, &B.scenes, &B.nsc)) == SW_EXIT_OK)
            rc = build_curves(B.scenes, B.nsc, B.b.vary, B.b.nvary, B.b.bearing, B.b.nbear,
                              B.bear_text, &B.cv, &B.nc);
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
    free(B.b.bearing);
    free(B.bear_copy);
    free(B.bear_text);
    sw_cli_parse_free(g, ng);
    return sw_cli_world_end(&B.world, rc);
}
