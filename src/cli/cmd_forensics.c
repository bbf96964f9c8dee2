/* cmd_forensics.c - "swaywatch forensics": after an incident, what a
 * recorded log did to a package, how much margin was left, and what would
 * have saved it.
 *
 * The report is what replay prints, plus
 *   - the safety factor: the smallest factor by which the recorded
 *     longitudinal acceleration would have to be scaled to overturn the
 *     package (sweep.h: scan the scale upward, then bisect; overturning is
 *     not monotonic, so a survived log is also searched below 1 for a
 *     weaker shock of the same shape that would have overturned it);
 *   - a what-if table: the same log with the package on the bed, on a
 *     frame, on a cushion, and in other sizes, each with its outcome and
 *     safety factor;
 *   - optionally a figure of a_g(t), theta(t)/alpha and margin(t) with the
 *     events, and the whole report as JSON.
 *
 * Unlike replay, forensics holds the whole log in memory (input.c): the
 * safety-factor search replays it tens of times per case, and re-reading
 * and re-parsing the file for each trial would cost more than the physics.
 * The figure also keeps the state series in memory. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "input.h"
#include "opts.h"
#include "output.h"
#include "plot.h"

#define DEFAULT_SETTLE 30.0   /* s of zero input after the end of the log, as replay */
#define DEFAULT_THREADS 2
#define DEFAULT_FRAME_ZETA "0.1"   /* the paper's Table I */
#define DEFAULT_CUSHION_ZETA "0.1"
#define FRAME_MASS_RATIO 0.25 /* m_b = m/4: gamma = 0.8, the paper's Table I */
#define MAX_EVENTS 100000     /* events kept for the figure */
#define PLOT_BUCKETS 3000     /* the figure keeps each series' extremes per bucket */

enum {
    OPT_SETTLE = SW_OPT_FIRST_OWN,
    OPT_FAIL_ON_OVERTURN,
    OPT_FRAME_MASS,
    OPT_FRAME_OMEGA,
    OPT_FRAME_ZETA,
    OPT_CUSHION_OMEGA,
    OPT_CUSHION_ZETA,
    OPT_SIZE,
    OPT_PLOT,
    OPT_THREADS,
    OPT_STEP,
    OPT_TOL,
    OPT_MAX_FACTOR,
    OPT_NO_WHAT_IF
};

static const struct option long_opts[] = {
    SW_CLI_COMMON_LONGOPTS,
    SW_CLI_CSV_LONGOPTS,
    {"settle", required_argument, NULL, OPT_SETTLE},
    {"fail-on-overturn", no_argument, NULL, OPT_FAIL_ON_OVERTURN},
    {"frame-mass", required_argument, NULL, OPT_FRAME_MASS},
    {"frame-omega", required_argument, NULL, OPT_FRAME_OMEGA},
    {"frame-zeta", required_argument, NULL, OPT_FRAME_ZETA},
    {"cushion-omega", required_argument, NULL, OPT_CUSHION_OMEGA},
    {"cushion-zeta", required_argument, NULL, OPT_CUSHION_ZETA},
    {"size", required_argument, NULL, OPT_SIZE},
    {"plot", required_argument, NULL, OPT_PLOT},
    {"threads", required_argument, NULL, OPT_THREADS},
    {"step", required_argument, NULL, OPT_STEP},
    {"tol", required_argument, NULL, OPT_TOL},
    {"max-factor", required_argument, NULL, OPT_MAX_FACTOR},
    {"no-what-if", no_argument, NULL, OPT_NO_WHAT_IF},
    {NULL, 0, NULL, 0},
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: swaywatch forensics LOG --scene S.ini [options]\n"
            "\n"
            "After an incident: replays the CSV log LOG ('-' for standard input) through the\n"
            "package of S.ini and prints what replay prints, then\n"
            "  - the safety factor: the smallest factor by which the recorded longitudinal\n"
            "    acceleration would have to be scaled to overturn the package (at most 1 if it\n"
            "    overturned; for a log it survived, also any weaker scale of the same shock\n"
            "    that would have overturned it: overturning is not monotonic in the amplitude);\n"
            "  - a what-if table: the same log with the package on the bed, on a frame, on a\n"
            "    cushion and in other sizes, each with its outcome and safety factor.\n"
            "The log is held in memory (about 16 bytes a sample): the search replays it tens\n"
            "of times for every case.\n"
            "\n");
    sw_cli_print_csv_help(f);
    fprintf(f,
            "\n"
            "Run:\n"
            "      --settle SECONDS     after the log, zero acceleration for up to this long or\n"
            "                           until the outcome is certain (default %g; 0: none)\n"
            "      --fail-on-overturn   exit 1 if the package as given overturned\n"
            "\n"
            "Safety factor (scale of the whole longitudinal acceleration):\n"
            "      --step X             relative scan step (default 0.02)\n"
            "      --tol X              relative width of the final bracket (default 0.001)\n"
            "      --max-factor X       largest scale tried (default: 20 times the scale at\n"
            "                           which the log's peak lifts a package on the bed)\n"
            "      --threads N          what-if cases computed in parallel (default %d)\n"
            "\n"
            "What if (each case replaces part of the scene; scene values are the defaults):\n"
            "      --frame-mass KG      frame mass m_b (default: the scene's, else m/4)\n"
            "      --frame-omega W      bearing frequency omega_b, rad/s (needed if the scene\n"
            "                           has no [frame])\n"
            "      --frame-zeta Z       bearing damping ratio (default: the scene's, else %s)\n"
            "      --cushion-omega W    cushion frequency omega_c, rad/s (needed if the scene\n"
            "                           has no [cushion]); on the frame if the scene has one\n"
            "      --cushion-zeta Z     cushion damping ratio (default: the scene's, else %s)\n"
            "      --size HxW           the package with height H and width W (m), on the\n"
            "                           scene's support; repeatable\n"
            "      --no-what-if         only the replay and the safety factor\n"
            "\n"
            "Output:\n"
            "      --plot FILE.png|.svg a_g(t), theta(t)/alpha and margin(t) with the events\n",
            DEFAULT_SETTLE, DEFAULT_THREADS, DEFAULT_FRAME_ZETA, DEFAULT_CUSHION_ZETA);
    sw_cli_print_common_help(f);
    fprintf(f, "\nWith --json the whole report is one JSON object on stdout: 'replay' (replay's\n"
               "JSON summary), 'safety_factor' and 'what_if'.\n");
    sw_cli_print_exit_help(f, 1, 1);
}

/* ---- the replay, with what the figure needs ----------------------------------- */

typedef struct {
    double t, a_g, ratio, margin;
} sample_t;

typedef struct {
    sw_cli_states_t *states;
    sw_cli_events_t *events;
    double alpha; /* rad */
    int keep;     /* keep the series for the figure */
    sample_t *s;
    size_t n, cap;
    sw_event_t *ev;
    size_t nev;
    int oom;
} replay_t;

static void on_state(void *user, const sw_output_t *out)
{
    replay_t *R = user;
    sw_cli_states_write(R->states, out);
    if (!R->keep || R->oom) return;
    if (R->n == R->cap) {
        size_t cap = R->cap ? 2 * R->cap : 8192;
        sample_t *s = realloc(R->s, cap * sizeof *s);
        if (!s) {
            R->oom = 1;
            return;
        }
        R->s = s;
        R->cap = cap;
    }
    R->s[R->n++] = (sample_t){out->t, out->a_g, out->state.theta / R->alpha, out->margin};
}

static void on_event(void *user, const sw_event_t *ev)
{
    replay_t *R = user;
    sw_cli_events_write(R->events, ev);
    if (R->keep && R->ev && R->nev < MAX_EVENTS) R->ev[R->nev++] = *ev;
}

/* ---- what-if cases -------------------------------------------------------------- */

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
} case_t;

typedef struct {
    const char *frame_mass, *frame_omega, *frame_zeta;
    const char *cushion_omega, *cushion_zeta;
    const char **sizes;
    size_t nsizes;
} whatif_opts_t;

typedef struct {
    char *buf;
    size_t len;
} note_t;

static void note_diag(void *user, const char *origin, int line, const char *msg)
{
    note_t *n = user;
    (void)line;
    if (n->buf[0] == '\0') snprintf(n->buf, n->len, "%s: %s", origin ? origin : "scene", msg);
}

static int case_set(case_t *C, const char *sec, const char *key, const char *val,
                    const char *origin)
{
    note_t n = {C->note, sizeof C->note};
    if (sw_scene_set(&C->scene, sec, key, val, 1, origin, 0, note_diag, &n) != SW_OK) {
        C->available = 0;
        if (!C->note[0]) snprintf(C->note, sizeof C->note, "%s: rejected", origin);
        return -1;
    }
    return 0;
}

static void describe(case_t *C)
{
    sw_derived_t d;
    note_t n = {C->note, sizeof C->note};
    if (sw_scene_validate(&C->scene, &d, C->name, note_diag, &n) != SW_OK) {
        C->available = 0;
        if (!C->note[0]) snprintf(C->note, sizeof C->note, "invalid scene");
        return;
    }
    C->model = d.model;
    int k = snprintf(C->desc, sizeof C->desc, "%gx%g m, %g kg", C->scene.height, C->scene.width,
                     C->scene.mass);
    if (d.model == SW_MODEL_BARE) {
        snprintf(C->desc + k, sizeof C->desc - (size_t)k, ", on the bed");
        return;
    }
    if (C->scene.has_frame)
        k += snprintf(C->desc + k, sizeof C->desc - (size_t)k,
                      ", frame m_b %g kg, w_b %.4g rad/s, zeta_b %.3g", C->scene.frame_mass,
                      d.omega_b, d.zeta_b);
    if (C->scene.has_cushion && k < (int)sizeof C->desc)
        snprintf(C->desc + k, sizeof C->desc - (size_t)k, ", cushion w_c %.4g rad/s, zeta_c %.3g",
                 d.omega_c, d.zeta_c);
}

static int parse_size(const char *arg, double *h, double *w)
{
    char tail;
    return sscanf(arg, "%lfx%lf%c", h, w, &tail) == 2 && isfinite(*h) && isfinite(*w) &&
                   *h > 0.0 && *w > 0.0
               ? 0
               : -1;
}

/* The cases of the table; the first is the scene as given. */
static case_t *build_cases(const sw_scene_t *sc, const whatif_opts_t *w, int what_if, size_t *n)
{
    const size_t cap = 4 + w->nsizes;
    case_t *cs = calloc(cap, sizeof *cs);
    if (!cs) return NULL;
    size_t m = 0;
    case_t *C = &cs[m++];
    snprintf(C->name, sizeof C->name, "as given");
    C->scene = *sc;
    C->is_scene = C->available = 1;
    describe(C);
    if (!what_if) {
        *n = m;
        return cs;
    }

    const int frame_opts = w->frame_mass || w->frame_omega || w->frame_zeta;
    const int cushion_opts = w->cushion_omega || w->cushion_zeta;

    if (sc->has_frame || sc->has_cushion) { /* the package alone on the bed */
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "bed");
        C->scene = *sc;
        C->scene.has_frame = C->scene.has_cushion = 0;
        C->available = 1;
        describe(C);
    }

    if (!sc->has_frame || frame_opts || sc->has_cushion) { /* on a frame, no cushion */
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "frame");
        C->scene = *sc;
        C->scene.has_cushion = 0;
        C->available = 1;
        if (!sc->has_frame && !w->frame_omega) {
            C->available = 0;
            snprintf(C->note, sizeof C->note,
                     "no frame given (--frame-omega, --frame-mass, --frame-zeta)");
        } else {
            char mass[32];
            snprintf(mass, sizeof mass, "%.17g", FRAME_MASS_RATIO * sc->mass);
            const char *fm = w->frame_mass ? w->frame_mass : sc->has_frame ? NULL : mass;
            const char *fz = w->frame_zeta ? w->frame_zeta
                             : sc->has_frame ? NULL
                                             : DEFAULT_FRAME_ZETA;
            if (fm) case_set(C, "frame", "mass", fm, "--frame-mass");
            if (C->available && w->frame_omega)
                case_set(C, "frame", "omega", w->frame_omega, "--frame-omega");
            if (C->available && fz) case_set(C, "frame", "zeta", fz, "--frame-zeta");
            if (C->available) describe(C);
        }
    }

    if (!sc->has_cushion || cushion_opts) { /* on a cushion, on the scene's support */
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "cushion");
        C->scene = *sc;
        C->available = 1;
        if (!sc->has_cushion && !w->cushion_omega) {
            C->available = 0;
            snprintf(C->note, sizeof C->note, "no cushion given (--cushion-omega, --cushion-zeta)");
        } else {
            const char *cz = w->cushion_zeta ? w->cushion_zeta
                             : sc->has_cushion ? NULL
                                               : DEFAULT_CUSHION_ZETA;
            if (w->cushion_omega) case_set(C, "cushion", "omega", w->cushion_omega,
                                           "--cushion-omega");
            if (C->available && cz) case_set(C, "cushion", "zeta", cz, "--cushion-zeta");
            if (C->available) describe(C);
        }
    }

    for (size_t i = 0; i < w->nsizes; i++) {
        C = &cs[m++];
        double h = 0.0, wd = 0.0;
        parse_size(w->sizes[i], &h, &wd); /* checked while parsing options */
        snprintf(C->name, sizeof C->name, "size %.6gx%.6g m", h, wd);
        C->scene = *sc;
        C->scene.height = h;
        C->scene.width = wd;
        C->available = 1;
        describe(C);
    }
    *n = m;
    return cs;
}

typedef struct {
    case_t *cases;
    const sw_log_t *log;
    const sw_run_opts_t *ro;
    const sw_search_opts_t *so;
} cases_job_t;

static void case_job(void *user, size_t i)
{
    cases_job_t *J = user;
    case_t *C = &J->cases[i];
    if (!C->available) return;
    char msg[256] = "";
    C->status = sw_safety_factor(&C->scene, J->log, J->ro, J->so, &C->sf, msg, sizeof msg);
    if (C->status == SW_OK) return;
    C->available = 0;
    snprintf(C->note, sizeof C->note, "%s", msg[0] ? msg : sw_strerror(C->status));
}

/* ---- report ---------------------------------------------------------------------- */

static void print_safety(FILE *f, const case_t *C)
{
    const sw_safety_t *s = &C->sf;
    fprintf(f, "\nsafety factor   ");
    if (isinf(s->lift_scale)) {
        fprintf(f, "none: the log has no longitudinal acceleration\n");
        return;
    }
    if (!s->found) {
        fprintf(f, "> %.4g: no scale of the recorded acceleration up to %.4g overturns it\n",
                s->max_scale, s->max_scale);
    } else if (s->overturned) {
        fprintf(f, "%.4g: it OVERTURNED; %.4g times the recorded acceleration already\n"
                   "                overturns it (%.4g times does not)\n",
                s->factor, s->factor, s->factor_safe);
    } else {
        fprintf(f, "%.4g: the recorded acceleration would have had to be %.4g times\n"
                   "                larger to overturn it (%.4g times did not)\n",
                s->factor, s->factor, s->factor_safe);
    }
    if (!s->overturned && s->below.found)
        fprintf(f, "                but a weaker shock of the same shape, %.4g times the recorded "
                   "one,\n"
                   "                would have overturned it: it survived by luck of timing\n",
                s->below.x);
    fprintf(f, "                (it starts to rock at %.4g times the recorded acceleration; %ld "
               "runs)\n",
            s->lift_scale, s->trials);
}

/* The factor column: "1.234", "1.234*" (a weaker shock overturns), "> 20"
 * (nothing up to the largest scale tried), "none" (no acceleration). */
static void factor_text(char *buf, size_t len, const sw_safety_t *s)
{
    if (isinf(s->lift_scale))
        snprintf(buf, len, "none");
    else if (!s->found)
        snprintf(buf, len, "> %.3g", s->max_scale);
    else
        snprintf(buf, len, "%.4g%s", s->factor, !s->overturned && s->below.found ? "*" : "");
}

static void print_table(FILE *f, const case_t *cs, size_t n)
{
    fprintf(f, "\nwhat if (the same log):\n");
    fprintf(f, "  %-20s %-11s %7s %7s %7s %8s  %s\n", "case", "outcome", "peak/a", "margin",
            "impacts", "factor", "package and support");
    for (size_t i = 0; i < n; i++) {
        const case_t *C = &cs[i];
        fprintf(f, "  %-20s ", C->name);
        if (!C->available) {
            fprintf(f, "n/a: %s\n", C->note);
            continue;
        }
        const sw_run_result_t *r = &C->sf.at_one;
        char fac[32];
        factor_text(fac, sizeof fac, &C->sf);
        fprintf(f, "%-11s %7.3f %7.3f %7ld %8s  %s\n", r->overturned ? "OVERTURNED" : "upright",
                r->max_theta_ratio, r->min_margin, r->impacts, fac, C->desc);
    }
    int luck = 0;
    for (size_t i = 0; i < n; i++)
        luck |= cs[i].available && !cs[i].sf.overturned && cs[i].sf.below.found;
    fprintf(f, "  peak/a: largest |theta|/alpha; margin: smallest margin to overturn; factor:\n"
               "  safety factor of the case%s\n",
            luck ? "; *: survived, but a weaker shock of the same shape overturns it" : "");
}

static void json_num(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.9g", v);
    else
        fputs("null", f);
}

static void json_safety(FILE *f, const case_t *C)
{
    const sw_safety_t *s = &C->sf;
    fprintf(f, "{\"available\": %s", C->available ? "true" : "false");
    if (!C->available) {
        fprintf(f, ", \"note\": ");
        sw_cli_json_string(f, C->note);
        fputc('}', f);
        return;
    }
    fprintf(f, ", \"overturned\": %s, \"found\": %s, \"factor\": ", s->overturned ? "true" : "false",
            s->found ? "true" : "false");
    json_num(f, s->found ? s->factor : NAN);
    fprintf(f, ", \"factor_safe\": ");
    json_num(f, s->found ? s->factor_safe : NAN);
    fprintf(f, ", \"weaker_overturning_factor\": ");
    json_num(f, !s->overturned && s->below.found ? s->below.x : NAN);
    fprintf(f, ", \"lift_scale\": ");
    json_num(f, s->lift_scale);
    fprintf(f, ", \"max_scale\": ");
    json_num(f, s->max_scale);
    fprintf(f, ", \"trials\": %ld}", s->trials);
}

static void json_case(FILE *f, const case_t *C)
{
    fprintf(f, "{\"case\": ");
    sw_cli_json_string(f, C->name);
    fprintf(f, ", \"as_given\": %s, \"available\": %s", C->is_scene ? "true" : "false",
            C->available ? "true" : "false");
    if (C->desc[0]) {
        fprintf(f, ", \"model\": ");
        sw_cli_json_string(f, sw_model_name(C->model));
        fprintf(f, ", \"support\": ");
        sw_cli_json_string(f, C->desc);
    }
    if (!C->available) {
        fprintf(f, ", \"note\": ");
        sw_cli_json_string(f, C->note);
        fputc('}', f);
        return;
    }
    const sw_run_result_t *r = &C->sf.at_one;
    fprintf(f, ", \"overturned\": %s, \"overturn_time\": ", r->overturned ? "true" : "false");
    json_num(f, r->overturn_time);
    fprintf(f, ", \"tip_time\": ");
    json_num(f, r->tip_time);
    fprintf(f, ", \"max_theta_ratio\": ");
    json_num(f, r->max_theta_ratio);
    fprintf(f, ", \"min_margin\": ");
    json_num(f, r->min_margin);
    fprintf(f, ", \"impacts\": %ld, \"safety_factor\": ", r->impacts);
    json_safety(f, C);
    fputc('}', f);
}

/* ---- figure ------------------------------------------------------------------------ */

/* One series in at most PLOT_BUCKETS buckets, each kept as its minimum and
 * maximum in time order, so that peaks survive the thinning. */
static void series_block(FILE *g, const char *name, const replay_t *R, int which)
{
    fprintf(g, "$%s << EOD\n", name);
    const size_t per = R->n / PLOT_BUCKETS + 1;
    for (size_t b = 0; b < R->n; b += per) {
        size_t imin = b, imax = b;
        const size_t e = b + per < R->n ? b + per : R->n;
        for (size_t i = b; i < e; i++) {
            const double v = which == 0 ? R->s[i].a_g : which == 1 ? R->s[i].ratio : R->s[i].margin;
            const double vmin = which == 0   ? R->s[imin].a_g
                                : which == 1 ? R->s[imin].ratio
                                             : R->s[imin].margin;
            const double vmax = which == 0   ? R->s[imax].a_g
                                : which == 1 ? R->s[imax].ratio
                                             : R->s[imax].margin;
            if (v < vmin) imin = i;
            if (v > vmax) imax = i;
        }
        const size_t first = imin < imax ? imin : imax, second = imin < imax ? imax : imin;
        for (int k = 0; k < (first == second ? 1 : 2); k++) {
            const size_t i = k ? second : first;
            const double v = which == 0 ? R->s[i].a_g : which == 1 ? R->s[i].ratio : R->s[i].margin;
            if (isfinite(v)) fprintf(g, "%.9g %.9g\n", R->s[i].t, v);
        }
    }
    fputs("EOD\n", g);
}

static int draw(const char *path, const char *log, const sw_scene_t *sc, const replay_t *R,
                double g_tan_alpha)
{
    sw_plot_t *p = sw_cli_plot_open(path, 1000, 900);
    if (!p) return SW_EXIT_IO;
    FILE *g = sw_cli_plot_file(p);
    series_block(g, "ag", R, 0);
    series_block(g, "th", R, 1);
    series_block(g, "mg", R, 2);
    /* impacts and rests as points; uplift, tip and overturn as lines */
    fputs("$imp << EOD\n", g);
    int nimp = 0;
    for (size_t i = 0; i < R->nev; i++)
        if (R->ev[i].kind == SW_EV_IMPACT || R->ev[i].kind == SW_EV_REST) {
            fprintf(g, "%.9g 0\n", R->ev[i].t);
            nimp++;
        }
    if (!nimp) fputs("NaN NaN\n", g);
    fputs("EOD\n", g);
    int arrows = 0;
    for (size_t i = 0; i < R->nev && arrows < 200; i++) {
        const sw_event_t *ev = &R->ev[i];
        const char *col = ev->kind == SW_EV_UPLIFT     ? "#2a9d8f"
                          : ev->kind == SW_EV_TIP      ? "#e9c46a"
                          : ev->kind == SW_EV_OVERTURN ? "#d62828"
                          : ev->kind == SW_EV_FAULT    ? "#000000"
                                                       : NULL;
        if (!col) continue;
        /* uplifts can be many: draw the first 50 */
        if (ev->kind == SW_EV_UPLIFT && arrows >= 50) continue;
        fprintf(g,
                "set arrow %d from first %.9g, graph 0 to first %.9g, graph 1 nohead lc rgb '%s' "
                "lw 1.5 dt 2\n",
                ++arrows, ev->t, ev->t, col);
    }
    fputs("set multiplot layout 3,1 title ", g);
    char title[512];
    snprintf(title, sizeof title, "%s: %s", log, sc->name);
    sw_cli_plot_text(g, title);
    fputs("\nset grid\nset key top right opaque box\nset lmargin 12\n"
          "set xlabel ''\nset format x ''\n",
          g);
    fprintf(g, "set ylabel 'a_g (m/s^2)'\n"
               "plot $ag using 1:2 with lines lc rgb '#264653' title 'bed acceleration', "
               "%.9g with lines lc rgb '#999999' dt 3 title '± g tan α', %.9g with lines "
               "lc rgb '#999999' dt 3 notitle\n",
            g_tan_alpha, -g_tan_alpha);
    fputs("set ylabel 'θ / α'\n"
          "plot $th using 1:2 with lines lc rgb '#1d3557' lw 1.5 title 'θ/α', "
          "1 with lines lc rgb '#d62828' dt 3 title 'tipping ±1', -1 with lines lc rgb '#d62828' "
          "dt 3 notitle, $imp using 1:2 with points pt 7 ps 0.5 lc rgb '#e76f51' "
          "title 'impacts / rest', NaN with lines lc rgb '#2a9d8f' lw 1.5 dt 2 title 'uplift', "
          "NaN with lines lc rgb '#e9c46a' lw 1.5 dt 2 title 'tip (|θ| = α)', "
          "NaN with lines lc rgb '#d62828' lw 1.5 dt 2 title 'overturn'\n",
          g);
    fputs("set format x '%g'\nset xlabel 't (s)'\nset ylabel 'margin'\n"
          "set yrange [*:1.05]\n"
          "plot $mg using 1:2 with lines lc rgb '#2a9d8f' lw 1.5 title 'margin to overturn', "
          "0 with lines lc rgb '#d62828' dt 3 notitle\n"
          "unset multiplot\n",
          g);
    return sw_cli_plot_close(p);
}

/* ---- the command --------------------------------------------------------------------- */

int cmd_forensics(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    sw_cli_opts_t o;
    sw_cli_csv_opts_t copts;
    sw_cli_csv_opts_init(&copts);
    whatif_opts_t w;
    memset(&w, 0, sizeof w);
    double settle = DEFAULT_SETTLE;
    long threads = DEFAULT_THREADS;
    int fail_on_overturn = 0, what_if = 1;
    const char *plot_path = NULL, *log_path = NULL;
    sw_search_opts_t so;
    memset(&so, 0, sizeof so);
    sw_cli_log_t L;
    memset(&L, 0, sizeof L);
    sw_scene_t *scenes = NULL;
    size_t nsc = 0, ncases = 0;
    sw_engine_t *e = NULL;
    sw_cli_states_t states = {0};
    sw_cli_events_t events = {0};
    replay_t R;
    memset(&R, 0, sizeof R);
    case_t *cases = NULL;

    if (sw_cli_opts_init(&o, argc) != SW_EXIT_OK) return SW_EXIT_IO;
    w.sizes = calloc((size_t)argc + 1, sizeof *w.sizes);
    if (!w.sizes) {
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
        goto out;
    }
    const sw_cli_group_t groups[] = {{sw_cli_csv_option, &copts}};
    int c;
    while ((c = sw_cli_getopt(&o, argc, argv,
                              SW_CLI_COMMON_SHORTOPTS, long_opts, NULL, groups, 1, usage)) > 0) {
        int r = SW_EXIT_OK;
        switch (c) {
        case OPT_SETTLE:
            r = sw_cli_parse_double("--settle", optarg, SW_NUM_NONNEGATIVE,
                                    "a number of seconds >= 0", &settle);
            break;
        case OPT_FAIL_ON_OVERTURN: fail_on_overturn = 1; break;
        case OPT_FRAME_MASS: w.frame_mass = optarg; break;
        case OPT_FRAME_OMEGA: w.frame_omega = optarg; break;
        case OPT_FRAME_ZETA: w.frame_zeta = optarg; break;
        case OPT_CUSHION_OMEGA: w.cushion_omega = optarg; break;
        case OPT_CUSHION_ZETA: w.cushion_zeta = optarg; break;
        case OPT_SIZE: {
            double h, wd;
            if (parse_size(optarg, &h, &wd) != 0) {
                sw_cli_error("--size: expected HEIGHTxWIDTH in m, e.g. 2.4x0.8, got '%s'", optarg);
                r = SW_EXIT_USAGE;
            }
            w.sizes[w.nsizes++] = optarg;
            break;
        }
        case OPT_PLOT:
            plot_path = optarg;
            r = sw_cli_plot_check("--plot", optarg);
            break;
        case OPT_THREADS:
            r = sw_cli_parse_long("--threads", optarg, 1, "a whole number of threads >= 1",
                                  &threads);
            if (threads > 256) threads = 256;
            break;
        case OPT_STEP:
            r = sw_cli_parse_double("--step", optarg, SW_NUM_POSITIVE, "a positive relative step",
                                    &so.step);
            break;
        case OPT_TOL:
            r = sw_cli_parse_double("--tol", optarg, SW_NUM_POSITIVE,
                                    "a positive relative tolerance", &so.tol);
            break;
        case OPT_MAX_FACTOR:
            r = sw_cli_parse_double("--max-factor", optarg, SW_NUM_POSITIVE,
                                    "a positive scale factor", &so.x_max);
            break;
        case OPT_NO_WHAT_IF: what_if = 0; break;
        default: sw_cli_error("forensics: unhandled option"); r = SW_EXIT_USAGE;
        }
        if (r != SW_EXIT_OK) {
            rc = r;
            goto out;
        }
    }
    if (c != SW_CLI_OPT_END) {
        if (c == SW_CLI_OPT_HELP) rc = SW_EXIT_OK;
        goto out;
    }
    if (!(log_path = sw_cli_log_operand("forensics", argc, argv))) goto out;
    if (o.n_scene_files > 1) {
        sw_cli_error("forensics: one --scene (one package) at a time");
        goto out;
    }
    if (so.x_max > 0.0 && so.x_max <= 1.0) {
        sw_cli_error("--max-factor: expected a factor above 1, got %g", so.x_max);
        goto out;
    }

    rc = sw_cli_log_read(log_path, &copts, o.quiet, &L);
    if (rc != SW_EXIT_OK) goto out;
    rc = sw_cli_load_scenes(&o, &scenes, &nsc);
    if (rc != SW_EXIT_OK) goto out;

    /* 1. the replay, exactly as replay runs it */
    sw_engine_opts_t eo;
    sw_cli_engine_opts(&o, &eo);
    if ((rc = sw_cli_resolve_accuracy(&o, scenes, nsc, &eo)) != SW_EXIT_OK) goto out;
    R.keep = plot_path != NULL;
    if (R.keep) {
        R.ev = calloc(MAX_EVENTS, sizeof *R.ev);
        if (!R.ev) {
            sw_cli_error("out of memory");
            rc = SW_EXIT_IO;
            goto out;
        }
    }
    eo.on_event = on_event;
    eo.on_state = o.out_path || R.keep ? on_state : NULL;
    eo.user = &R;
    rc = SW_EXIT_USAGE;
    e = sw_cli_engine_create(scenes, 1, &eo);
    if (!e) goto out;
    R.alpha = sw_engine_derived(e, 0)->alpha;
    if (o.verbose) sw_cli_print_derived(stderr, e, scenes, 1);
    rc = sw_cli_states_open(&states, o.out_path, o.every, scenes, 1);
    if (rc != SW_EXIT_OK) goto out;
    rc = sw_cli_events_open(&events, o.events_path, scenes, 1);
    if (rc != SW_EXIT_OK) goto out;
    R.states = &states;
    R.events = &events;
    long refused = 0;
    for (size_t i = 0; i < L.n; i++)
        if (sw_engine_push(e, L.t[i], L.a_g[i], L.has_z ? L.a_z[i] : 0.0) < 0) refused++;
    sw_engine_finish(e, settle);
    rc = sw_cli_states_close(&states);
    int rc2 = sw_cli_events_close(&events);
    if (rc == SW_EXIT_OK) rc = rc2;
    if (rc != SW_EXIT_OK) goto out;
    if (R.oom) sw_cli_error("out of memory keeping the state series: the figure is partial");

    /* 2. the safety factor and the what-if cases */
    cases = build_cases(&scenes[0], &w, what_if, &ncases);
    if (!cases) {
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
        goto out;
    }
    sw_run_opts_t ro;
    memset(&ro, 0, sizeof ro);
    ro.engine = eo; /* the replay's integration options, --accuracy included */
    ro.settle = settle > 0.0 ? settle : -1.0; /* negative: no free motion at all */
    sw_log_t lg = {L.t, L.a_g, L.has_z ? L.a_z : NULL, L.n};
    cases_job_t J = {cases, &lg, &ro, &so};
    sw_parallel_for(ncases, (int)threads, case_job, &J);
    if (!cases[0].available) {
        sw_cli_error("forensics: safety factor: %s", cases[0].note);
        rc = SW_EXIT_USAGE;
        goto out;
    }
    sw_summary_t sum;
    sw_engine_summary(e, 0, &sum);
    if (sum.overturned != cases[0].sf.overturned)
        sw_cli_error("forensics: the replay and the safety-factor run disagree on the outcome "
                     "(overturned %s / %s): the shock is at the edge of the model's resolution",
                     sum.overturned ? "yes" : "no", cases[0].sf.overturned ? "yes" : "no");
    sw_cli_run_t run = {
        .log = log_path,
        .samples_read = L.rows,
        .samples_rejected = L.rejected + refused,
        .settle = settle,
    };
    if (o.json) {
        fprintf(stdout, "{\n\"replay\": ");
        sw_cli_print_json(stdout, e, &run);
        fprintf(stdout, ",\n\"safety_factor\": ");
        json_safety(stdout, &cases[0]);
        fprintf(stdout, ",\n\"what_if\": [");
        for (size_t i = 0; i < ncases; i++) {
            fprintf(stdout, "%s\n  ", i ? "," : "");
            json_case(stdout, &cases[i]);
        }
        fprintf(stdout, "\n]\n}\n");
    } else if (!o.quiet) {
        sw_cli_print_summary(stdout, e, &run);
        print_safety(stdout, &cases[0]);
        if (what_if) print_table(stdout, cases, ncases);
    }
    if (plot_path) {
        const sw_derived_t *d = sw_engine_derived(e, 0);
        rc = draw(plot_path, log_path, &scenes[0], &R, scenes[0].g * tan(d->alpha));
        if (rc != SW_EXIT_OK) goto out;
    }
    rc = SW_EXIT_OK;
    if (fail_on_overturn && sum.overturned) rc = SW_EXIT_OVERTURNED;
out:
    sw_cli_states_close(&states);
    sw_cli_events_close(&events);
    sw_engine_destroy(e);
    free(cases);
    free(R.s);
    free(R.ev);
    free(scenes);
    sw_cli_log_free(&L);
    free(w.sizes);
    sw_cli_opts_fini(&o);
    return rc;
}
