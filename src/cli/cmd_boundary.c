/* cmd_boundary.c - "swaywatch boundary": overturning boundary curves, the
 * lowest pulse amplitude a_e/(g tan alpha) that overturns the package as a
 * function of omega_e/p, for one or more curves (scenes, --vary values of
 * a scene key, --bearing-ratio values), as CSV and optionally a figure.
 *
 * The points are independent runs of the library's boundary search
 * (sweep.h) spread over --threads worker threads; the output does not
 * depend on the number of threads. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "opts.h"
#include "output.h"
#include "plot.h"

#define MAX_POINTS 100000 /* omega_e/p values; a typo such as 1:12:0.0001 is refused */
#define MAX_CURVES 1000
#define DEFAULT_THREADS 2

enum {
    OPT_PULSE = SW_OPT_FIRST_OWN,
    OPT_RATIO,
    OPT_VARY,
    OPT_BEARING,
    OPT_THREADS,
    OPT_PLOT,
    OPT_PROGRESS,
    OPT_NO_PROGRESS,
    OPT_STEP,
    OPT_TOL,
    OPT_MIN,
    OPT_MAX,
    OPT_FREE,
    OPT_ISLANDS,
    OPT_DETAIL,
    OPT_TITLE
};

static const struct option long_opts[] = {
    {"scene", required_argument, NULL, SW_OPT_SCENE},
    {"set", required_argument, NULL, SW_OPT_SET},
    {"scheme", required_argument, NULL, SW_OPT_SCHEME},
    {"dt", required_argument, NULL, SW_OPT_DT},
    {"rtol", required_argument, NULL, SW_OPT_RTOL},
    {"atol", required_argument, NULL, SW_OPT_ATOL},
    {"out", required_argument, NULL, SW_OPT_OUT},
    {"quiet", no_argument, NULL, SW_OPT_QUIET},
    {"verbose", no_argument, NULL, SW_OPT_VERBOSE},
    {"help", no_argument, NULL, SW_OPT_HELP},
    {"pulse", required_argument, NULL, OPT_PULSE},
    {"omega-ratio", required_argument, NULL, OPT_RATIO},
    {"vary", required_argument, NULL, OPT_VARY},
    {"bearing-ratio", required_argument, NULL, OPT_BEARING},
    {"threads", required_argument, NULL, OPT_THREADS},
    {"plot", required_argument, NULL, OPT_PLOT},
    {"progress", no_argument, NULL, OPT_PROGRESS},
    {"no-progress", no_argument, NULL, OPT_NO_PROGRESS},
    {"step", required_argument, NULL, OPT_STEP},
    {"tol", required_argument, NULL, OPT_TOL},
    {"min-amplitude", required_argument, NULL, OPT_MIN},
    {"max-amplitude", required_argument, NULL, OPT_MAX},
    {"free-periods", required_argument, NULL, OPT_FREE},
    {"islands", required_argument, NULL, OPT_ISLANDS},
    {"detail", required_argument, NULL, OPT_DETAIL},
    {"title", required_argument, NULL, OPT_TITLE},
    {NULL, 0, NULL, 0},
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: swaywatch boundary --scene S.ini --pulse half-sine|full-sine\n"
            "                          --omega-ratio FROM:TO:STEP [options]\n"
            "\n"
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
            "\n"
            "Curves (one CSV column each): every --scene, times every --vary value, times\n"
            "every --bearing-ratio value for scenes with a frame.\n"
            "  -s, --scene FILE          scene file (INI); repeatable\n"
            "      --set SEC.KEY=VALUE   override a key in every scene\n"
            "      --pulse SHAPE         half-sine or full-sine (required)\n"
            "      --omega-ratio R       omega_e/p values: FROM:TO:STEP (inclusive) or a list\n"
            "                            R1,R2,... (required)\n"
            "      --vary SEC.KEY=V1,V2  one curve per value of a scene key, e.g.\n"
            "                            --vary frame.zeta=0.05,0.1,0.2; repeatable (all\n"
            "                            combinations); a frame or cushion key leaves scenes\n"
            "                            without that section as they are\n"
            "      --bearing-ratio B1,B2 omega_b = B * omega_e at every point (the paper's\n"
            "                            omega_b/omega_e); values may be fractions such as 1/3;\n"
            "                            scenes without a [frame] are drawn once, as they are\n"
            "\n"
            "Search:\n"
            "      --step X              relative scan step (default 0.02)\n"
            "      --tol X               relative width of the final bracket (default 0.001)\n"
            "      --min-amplitude X     start of the scan, in g tan alpha (default: the lowest\n"
            "                            amplitude that can lift the package at all)\n"
            "      --max-amplitude X     end of the scan (default 20); a curve with no overturn\n"
            "                            up to it has an empty field at that point\n"
            "      --free-periods N      free motion after the pulse, in rocking periods 2 pi/p\n"
            "                            (default 20)\n"
            "      --threads N           worker threads (default %d); results do not depend on it\n"
            "      --scheme NAME         time stepper:",
            DEFAULT_THREADS);
    for (size_t i = 0; sw_scheme_at(i); i++)
        fprintf(f, "%s %s", i ? "," : "", sw_scheme_name(sw_scheme_at(i)));
    fprintf(f,
            " (default %s)\n"
            "      --dt SECONDS          internal step (default: the scheme's, at most 1/400 of the\n"
            "                            pulse period and of the rocking period)\n"
            "      --rtol X, --atol X    tolerances of the adaptive schemes\n"
            "\n"
            "Output:\n"
            "  -o, --out FILE.csv        the curves (default: standard output):\n"
            "                            omega_ratio,<curve 1>,<curve 2>,... in units of g tan alpha\n"
            "      --detail FILE.csv     one row per curve and point: the bracket, impacts before\n"
            "                            the overturn at the boundary (0: overturned directly;\n"
            "                            >= 1: after an impact), the directions of the first\n"
            "                            uplift and of the overturn (+1 the top forward, -1 back;\n"
            "                            opposite: it overturned after a reverse sway), times,\n"
            "                            trials\n"
            "      --islands FILE.csv    scan on up to --max-amplitude and list the safe islands\n"
            "                            above the boundary: curve,omega_ratio,from,to,open\n"
            "      --plot FILE.png|.svg  draw the curves (and islands) with gnuplot\n"
            "      --title TEXT          title of the figure\n"
            "      --progress            percentage on stderr (default: only when stderr is a\n"
            "                            terminal); --no-progress: never\n"
            "  -q, --quiet               no summary on stderr\n"
            "  -v, --verbose             the derived quantities of each curve's scene, on stderr\n"
            "  -h, --help                this help\n",
            SW_DEFAULT_SCHEME);
    sw_cli_print_exit_help(f, 0, 0);
}

/* ---- option values ----------------------------------------------------------- */

/* "1/3" or a decimal number. */
static int parse_fraction(const char *s, double *out)
{
    char *end = NULL;
    double a = strtod(s, &end);
    if (end == s) return -1;
    if (*end == '/') {
        const char *q = end + 1;
        double b = strtod(q, &end);
        if (end == q || b == 0.0) return -1;
        a /= b;
    }
    if (*end != '\0' || !isfinite(a)) return -1;
    *out = a;
    return 0;
}

/* A comma-separated list of numbers (fractions allowed) into a new array. */
static int parse_list(const char *opt, const char *arg, int positive, double **vals, size_t *n)
{
    size_t cap = 1;
    for (const char *p = arg; *p; p++) cap += *p == ',';
    double *v = calloc(cap, sizeof *v);
    char *copy = strdup(arg);
    if (!v || !copy) {
        free(v);
        free(copy);
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    size_t k = 0;
    for (char *tok = copy, *next; tok; tok = next) {
        next = strchr(tok, ',');
        if (next) *next++ = '\0'; /* an empty item ("1,,2") is an error, not skipped */
        double x;
        if (parse_fraction(tok, &x) != 0 || (positive && !(x > 0.0))) {
            sw_cli_error("%s: expected %snumbers separated by commas, got '%s'", opt,
                         positive ? "positive " : "", tok);
            free(v);
            free(copy);
            return SW_EXIT_USAGE;
        }
        v[k++] = x;
    }
    free(copy);
    if (k == 0) {
        sw_cli_error("%s: expected at least one value, got '%s'", opt, arg);
        free(v);
        return SW_EXIT_USAGE;
    }
    *vals = v;
    *n = k;
    return SW_EXIT_OK;
}

/* FROM:TO:STEP (inclusive, values FROM + i STEP computed from i), or a list. */
static int parse_ratios(const char *arg, double **vals, size_t *n)
{
    if (!strchr(arg, ':')) return parse_list("--omega-ratio", arg, 1, vals, n);
    double a, b, s;
    char tail;
    if (sscanf(arg, "%lf:%lf:%lf%c", &a, &b, &s, &tail) != 3 || !isfinite(a) || !isfinite(b) ||
        !isfinite(s) || !(a > 0.0) || !(b >= a) || !(s > 0.0)) {
        sw_cli_error("--omega-ratio: expected FROM:TO:STEP with 0 < FROM <= TO and STEP > 0, "
                     "got '%s'",
                     arg);
        return SW_EXIT_USAGE;
    }
    const double count = floor((b - a) / s * (1.0 + 1e-12) + 1e-9) + 1.0;
    if (count > MAX_POINTS) {
        sw_cli_error("--omega-ratio: '%s' gives %.0f points, more than %d", arg, count,
                     MAX_POINTS);
        return SW_EXIT_USAGE;
    }
    double *v = calloc((size_t)count, sizeof *v);
    if (!v) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    for (size_t i = 0; i < (size_t)count; i++) v[i] = a + (double)i * s;
    *vals = v;
    *n = (size_t)count;
    return SW_EXIT_OK;
}

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

static void write_curves(FILE *f, const curve_t *cv, size_t nc, const double *ratios, size_t nr,
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

static void write_detail(FILE *f, const curve_t *cv, size_t nc, const double *ratios, size_t nr,
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
}

static void write_islands(FILE *f, const curve_t *cv, size_t nc, const double *ratios, size_t nr,
                          const sw_boundary_point_t *pts)
{
    fputs("curve,omega_ratio,from,to,open\n", f);
    for (size_t c = 0; c < nc; c++)
        for (size_t i = 0; i < nr; i++) {
            const sw_threshold_t *T = &pts[c * nr + i].th;
            for (int k = 0; k < T->n_islands; k++) {
                sw_cli_csv_text(f, cv[c].label);
                fprintf(f, ",%.6g,%.6g,%.6g,%d\n", ratios[i], T->islands[k].lo, T->islands[k].hi,
                        T->islands[k].open);
            }
        }
}

static int write_file(const char *path, const curve_t *cv, size_t nc, const double *ratios,
                      size_t nr, const sw_boundary_point_t *pts,
                      void (*fn)(FILE *, const curve_t *, size_t, const double *, size_t,
                                 const sw_boundary_point_t *))
{
    FILE *f = fopen(path, "w");
    if (!f) {
        sw_cli_error("%s: cannot create: %s", path, strerror(errno));
        return SW_EXIT_IO;
    }
    fn(f, cv, nc, ratios, nr, pts);
    int bad = ferror(f);
    if (fclose(f) != 0) bad = 1;
    if (bad) {
        sw_cli_error("%s: write failed", path);
        return SW_EXIT_IO;
    }
    return SW_EXIT_OK;
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

int cmd_boundary(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    sw_cli_opts_t o;
    sw_boundary_opts_t bo;
    memset(&bo, 0, sizeof bo);
    bo.threads = DEFAULT_THREADS;
    int have_shape = 0, progress = isatty(fileno(stderr)) ? 1 : 0;
    long threads = DEFAULT_THREADS;
    double *ratios = NULL, *bearing = NULL;
    size_t nr = 0, nbear = 0, nvary = 0, nsc = 0, nc = 0;
    const char *plot_path = NULL, *islands_path = NULL, *detail_path = NULL, *title = NULL;
    const char *bear_arg = NULL;
    char *bear_copy = NULL;
    const char **bear_text = NULL;
    vary_t *vary = NULL;
    sw_scene_t *scenes = NULL;
    curve_t *cv = NULL;
    sw_boundary_point_t *pts = NULL;

    if (sw_cli_opts_init(&o, argc) != SW_EXIT_OK) return SW_EXIT_IO;
    vary = calloc((size_t)argc + 1, sizeof *vary);
    if (!vary) {
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
        goto out;
    }
    int opt;
    while ((opt = sw_cli_getopt(&o, argc, argv, ":hs:o:qv", long_opts, NULL, NULL, 0, usage)) > 0) {
        int r = SW_EXIT_OK;
        switch (opt) {
        case OPT_PULSE:
            if (sw_pulse_shape_parse(optarg, &bo.shape) != SW_OK) {
                sw_cli_error("--pulse: expected half-sine or full-sine, got '%s'", optarg);
                r = SW_EXIT_USAGE;
            }
            have_shape = 1;
            break;
        case OPT_RATIO:
            free(ratios);
            ratios = NULL;
            r = parse_ratios(optarg, &ratios, &nr);
            break;
        case OPT_VARY: r = parse_vary(optarg, &vary[nvary++]); break;
        case OPT_BEARING:
            free(bearing);
            bearing = NULL;
            bear_arg = optarg;
            r = parse_list("--bearing-ratio", optarg, 1, &bearing, &nbear);
            break;
        case OPT_THREADS:
            r = sw_cli_parse_long("--threads", optarg, 1, "a whole number of threads >= 1",
                                  &threads);
            if (r == SW_EXIT_OK && threads > 256) threads = 256;
            bo.threads = (int)threads;
            break;
        case OPT_PLOT:
            plot_path = optarg;
            r = sw_cli_plot_check("--plot", optarg);
            break;
        case OPT_PROGRESS: progress = 1; break;
        case OPT_NO_PROGRESS: progress = 0; break;
        case OPT_STEP:
            r = sw_cli_parse_double("--step", optarg, SW_NUM_POSITIVE, "a positive relative step",
                                    &bo.search.step);
            break;
        case OPT_TOL:
            r = sw_cli_parse_double("--tol", optarg, SW_NUM_POSITIVE,
                                    "a positive relative tolerance", &bo.search.tol);
            break;
        case OPT_MIN:
            r = sw_cli_parse_double("--min-amplitude", optarg, SW_NUM_POSITIVE,
                                    "a positive amplitude in g tan alpha", &bo.search.x_min);
            break;
        case OPT_MAX:
            r = sw_cli_parse_double("--max-amplitude", optarg, SW_NUM_POSITIVE,
                                    "a positive amplitude in g tan alpha", &bo.search.x_max);
            break;
        case OPT_FREE:
            r = sw_cli_parse_double("--free-periods", optarg, SW_NUM_POSITIVE,
                                    "a positive number of rocking periods", &bo.run.free_periods);
            break;
        case OPT_ISLANDS: islands_path = optarg; break;
        case OPT_DETAIL: detail_path = optarg; break;
        case OPT_TITLE: title = optarg; break;
        default: sw_cli_error("boundary: unhandled option"); r = SW_EXIT_USAGE;
        }
        if (r != SW_EXIT_OK) {
            rc = r;
            goto out;
        }
    }
    if (opt != SW_CLI_OPT_END) {
        if (opt == SW_CLI_OPT_HELP) rc = SW_EXIT_OK;
        goto out;
    }
    if (optind < argc) {
        sw_cli_error("boundary: unexpected argument '%s'; see 'swaywatch boundary --help'",
                     argv[optind]);
        goto out;
    }
    if (!have_shape || !nr) {
        sw_cli_error("boundary: missing %s; see 'swaywatch boundary --help'",
                     !have_shape ? "--pulse half-sine|full-sine"
                                 : "--omega-ratio FROM:TO:STEP");
        goto out;
    }
    if (bo.search.x_min > 0.0 && bo.search.x_max > 0.0 && bo.search.x_min >= bo.search.x_max) {
        sw_cli_error("--min-amplitude %g is not below --max-amplitude %g", bo.search.x_min,
                     bo.search.x_max);
        goto out;
    }
    if (!(bo.search.x_max > 0.0)) bo.search.x_max = 20.0;
    if (bo.search.x_min >= bo.search.x_max) {
        sw_cli_error("--min-amplitude %g is not below the default --max-amplitude %g",
                     bo.search.x_min, bo.search.x_max);
        goto out;
    }
    bo.search.islands = islands_path != NULL;
    sw_cli_engine_opts(&o, &bo.run.engine);

    /* labels of the bearing ratios as the user wrote them ("1/3") */
    if (nbear) {
        bear_copy = strdup(bear_arg);
        bear_text = calloc(nbear, sizeof *bear_text);
        if (!bear_copy || !bear_text) {
            sw_cli_error("out of memory");
            rc = SW_EXIT_IO;
            goto out;
        }
        size_t k = 0;
        char *save = NULL;
        for (char *t = strtok_r(bear_copy, ",", &save); t && k < nbear;
             t = strtok_r(NULL, ",", &save))
            bear_text[k++] = t;
    }

    rc = sw_cli_load_scenes(&o, &scenes, &nsc);
    if (rc != SW_EXIT_OK) goto out;
    rc = build_curves(scenes, nsc, vary, nvary, bearing, nbear, bear_text, &cv, &nc);
    if (rc != SW_EXIT_OK) goto out;
    if (o.verbose)
        for (size_t c = 0; c < nc; c++) {
            sw_derived_t d;
            sw_scene_t s; /* omega_b is set per point */
            sw_curve_scene(&cv[c].c, 0.0, &s);
            if (sw_scene_validate(&s, &d, NULL, NULL, NULL) != SW_OK) continue;
            fprintf(stderr,
                    "swaywatch: curve %zu '%s': %s model, alpha %.4g deg, p %.6g rad/s, "
                    "g tan alpha %.6g m/s^2",
                    c + 1, cv[c].label, sw_model_name(d.model), d.alpha * 180.0 / M_PI, d.p,
                    s.g * tan(d.alpha));
            if (d.model == SW_MODEL_FRAME)
                fprintf(stderr, ", gamma %.4g, zeta_b %.4g, omega_b %s", d.gamma, d.zeta_b,
                        cv[c].c.bearing_ratio > 0.0 ? "per point" : "");
            if (d.model == SW_MODEL_FRAME && !(cv[c].c.bearing_ratio > 0.0))
                fprintf(stderr, "%.6g rad/s", d.omega_b);
            fputc('\n', stderr);
        }

    pts = calloc(nc * nr, sizeof *pts);
    sw_curve_t *curves = calloc(nc, sizeof *curves);
    if (!pts || !curves) {
        free(curves);
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
        goto out;
    }
    for (size_t c = 0; c < nc; c++) curves[c] = cv[c].c;
    if (progress) bo.progress = on_progress;
    char msg[512] = "";
    int sr = sw_boundary_sweep(curves, nc, ratios, nr, &bo, pts, msg, sizeof msg);
    free(curves);
    if (sr != SW_OK) {
        sw_cli_error("boundary: %s", msg[0] ? msg : sw_strerror(sr));
        rc = SW_EXIT_USAGE;
        goto out;
    }

    long at_min = 0, missing = 0, truncated = 0;
    for (size_t i = 0; i < nc * nr; i++) {
        at_min += pts[i].th.found && pts[i].th.at_min;
        missing += !pts[i].th.found;
        truncated += pts[i].th.islands_truncated;
    }
    rc = SW_EXIT_OK;
    if (o.out_path)
        rc = write_file(o.out_path, cv, nc, ratios, nr, pts, write_curves);
    else
        write_curves(stdout, cv, nc, ratios, nr, pts);
    if (rc == SW_EXIT_OK && detail_path)
        rc = write_file(detail_path, cv, nc, ratios, nr, pts, write_detail);
    if (rc == SW_EXIT_OK && islands_path)
        rc = write_file(islands_path, cv, nc, ratios, nr, pts, write_islands);
    if (rc == SW_EXIT_OK && plot_path)
        rc = plot(plot_path, title, bo.shape, cv, nc, ratios, nr, pts, islands_path != NULL);
    if (!o.quiet) {
        if (missing)
            sw_cli_error("boundary: %ld of %zu points did not overturn up to --max-amplitude %g "
                         "(empty fields)",
                         missing, nc * nr, bo.search.x_max);
        if (at_min)
            sw_cli_error("boundary: %ld points overturned at --min-amplitude already: their "
                         "value is an upper bound",
                         at_min);
        if (truncated)
            sw_cli_error("boundary: %ld points have more than %d safe islands; the rest are "
                         "not listed",
                         truncated, SW_MAX_ISLANDS);
    }
out:
    free(pts);
    free(cv);
    free(scenes);
    for (size_t k = 0; vary && k < nvary; k++) vary_free(&vary[k]);
    free(vary);
    free(ratios);
    free(bearing);
    free(bear_copy);
    free(bear_text);
    sw_cli_opts_fini(&o);
    return rc;
}
