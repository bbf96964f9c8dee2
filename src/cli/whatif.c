/* whatif.c - the what-if cases of forensics (whatif.h): the scene as
 * given, on the bed, on a frame, on a cushion and in other sizes, each
 * case's safety factor for the same log, and the table and JSON that
 * report them. */
#include "whatif.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "output.h"

#define FRAME_MASS_RATIO 0.25 /* m_b = m/4: gamma = 0.8, the paper's Table I */

int sw_cli_parse_size(const char *arg, double *h, double *w)
{
    char tail;
    return sscanf(arg, "%lfx%lf%c", h, w, &tail) == 2 && isfinite(*h) && isfinite(*w) &&
                   *h > 0.0 && *w > 0.0
               ? 0
               : -1;
}

/* ---- building the cases ------------------------------------------------------- */

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

static int case_set(sw_cli_case_t *C, const char *sec, const char *key, const char *val,
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

static void describe(sw_cli_case_t *C)
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

/* The cases of the table; the first is the scene as given. */
/* The package on a frame, no cushion: the scene's frame with the options'
 * values, or one made of them. */
static void frame_case(sw_cli_case_t *C, const sw_scene_t *sc, const sw_cli_whatif_t *w)
{
    snprintf(C->name, sizeof C->name, "frame");
    C->scene = *sc;
    C->scene.has_cushion = 0;
    C->available = 1;
    if (!sc->has_frame && !w->frame_omega) {
        C->available = 0;
        snprintf(C->note, sizeof C->note,
                 "no frame given (--frame-omega, --frame-mass, --frame-zeta)");
        return;
    }
    char mass[32];
    snprintf(mass, sizeof mass, "%.17g", FRAME_MASS_RATIO * sc->mass);
    const char *fm = w->frame_mass ? w->frame_mass : sc->has_frame ? NULL : mass;
    const char *fz = w->frame_zeta ? w->frame_zeta
                     : sc->has_frame ? NULL
                                     : SW_CLI_FRAME_ZETA;
    if (fm) case_set(C, "frame", "mass", fm, "--frame-mass");
    if (C->available && w->frame_omega)
        case_set(C, "frame", "omega", w->frame_omega, "--frame-omega");
    if (C->available && fz) case_set(C, "frame", "zeta", fz, "--frame-zeta");
    if (C->available) describe(C);
}

/* The package on a cushion, on the scene's support. */
static void cushion_case(sw_cli_case_t *C, const sw_scene_t *sc, const sw_cli_whatif_t *w)
{
    snprintf(C->name, sizeof C->name, "cushion");
    C->scene = *sc;
    C->available = 1;
    if (!sc->has_cushion && !w->cushion_omega) {
        C->available = 0;
        snprintf(C->note, sizeof C->note, "no cushion given (--cushion-omega, --cushion-zeta)");
        return;
    }
    const char *cz = w->cushion_zeta ? w->cushion_zeta
                     : sc->has_cushion ? NULL
                                       : SW_CLI_CUSHION_ZETA;
    if (w->cushion_omega) case_set(C, "cushion", "omega", w->cushion_omega, "--cushion-omega");
    if (C->available && cz) case_set(C, "cushion", "zeta", cz, "--cushion-zeta");
    if (C->available) describe(C);
}

sw_cli_case_t *sw_cli_whatif_build(const sw_scene_t *sc, const sw_cli_whatif_t *w, size_t *n)
{
    const size_t cap = 4 + w->sizes.n;
    sw_cli_case_t *cs = calloc(cap, sizeof *cs);
    if (!cs) return NULL;
    size_t m = 0;
    sw_cli_case_t *C = &cs[m++];
    snprintf(C->name, sizeof C->name, "as given");
    C->scene = *sc;
    C->is_scene = C->available = 1;
    describe(C);
    if (w->no_what_if) {
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
        frame_case(&cs[m++], sc, w);
    }

    if (!sc->has_cushion || cushion_opts) { /* on a cushion, on the scene's support */
        cushion_case(&cs[m++], sc, w);
    }

    for (size_t i = 0; i < w->sizes.n; i++) {
        C = &cs[m++];
        double h = 0.0, wd = 0.0;
        sw_cli_parse_size(w->sizes.v[i], &h, &wd); /* checked while parsing options */
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
    sw_cli_case_t *cases;
    const sw_log_t *log;
    const sw_run_opts_t *ro;
    const sw_search_opts_t *so;
} cases_job_t;

static void case_job(void *user, size_t i)
{
    cases_job_t *J = user;
    sw_cli_case_t *C = &J->cases[i];
    if (!C->available) return;
    char msg[256] = "";
    C->status = sw_safety_factor(&C->scene, J->log, J->ro, J->so, &C->sf, msg, sizeof msg);
    if (C->status == SW_OK) return;
    C->available = 0;
    snprintf(C->note, sizeof C->note, "%s", msg[0] ? msg : sw_strerror(C->status));
}

void sw_cli_whatif_run(sw_cli_case_t *cases, size_t n, const sw_log_t *log,
                       const sw_run_opts_t *ro, const sw_search_opts_t *so, int threads)
{
    cases_job_t J = {cases, log, ro, so};
    sw_parallel_for(n, threads, case_job, &J);
}

/* ---- report ---------------------------------------------------------------------- */

void sw_cli_whatif_print_safety(FILE *f, const sw_cli_case_t *C)
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

void sw_cli_whatif_print_table(FILE *f, const sw_cli_case_t *cs, size_t n)
{
    fprintf(f, "\nwhat if (the same log):\n");
    fprintf(f, "  %-20s %-11s %7s %7s %7s %8s  %s\n", "case", "outcome", "peak/a", "margin",
            "impacts", "factor", "package and support");
    for (size_t i = 0; i < n; i++) {
        const sw_cli_case_t *C = &cs[i];
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

void sw_cli_whatif_json_safety(FILE *f, const sw_cli_case_t *C)
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
    sw_cli_json_num(f, s->found ? s->factor : NAN);
    fprintf(f, ", \"factor_safe\": ");
    sw_cli_json_num(f, s->found ? s->factor_safe : NAN);
    fprintf(f, ", \"weaker_overturning_factor\": ");
    sw_cli_json_num(f, !s->overturned && s->below.found ? s->below.x : NAN);
    fprintf(f, ", \"lift_scale\": ");
    sw_cli_json_num(f, s->lift_scale);
    fprintf(f, ", \"max_scale\": ");
    sw_cli_json_num(f, s->max_scale);
    fprintf(f, ", \"trials\": %ld}", s->trials);
}

void sw_cli_whatif_json_case(FILE *f, const sw_cli_case_t *C)
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
    sw_cli_json_num(f, r->overturn_time);
    fprintf(f, ", \"tip_time\": ");
    sw_cli_json_num(f, r->tip_time);
    fprintf(f, ", \"max_theta_ratio\": ");
    sw_cli_json_num(f, r->max_theta_ratio);
    fprintf(f, ", \"min_margin\": ");
    sw_cli_json_num(f, r->min_margin);
    fprintf(f, ", \"impacts\": %ld, \"safety_factor\": ", r->impacts);
    sw_cli_whatif_json_safety(f, C);
    fputc('}', f);
}
