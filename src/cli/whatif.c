/* SPDX-License-Identifier: GPL-3.0-or-later */
/* whatif.c - the what-if cases of forensics (whatif.h): each scene as
 * given, on the bed, on the catalogue's typical supports (or the user's
 * frame and cushion) and in other sizes, every case's safety factor for
 * the same log, and the table and JSON that report them. */
#include "whatif.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "output.h"

#define FRAME_MASS_RATIO 0.25 /* m_b = m/4: gamma = 0.8, the paper's Table I */
#define TWO_PI 6.283185307179586

/* The catalogue (docs/forensics.md says where the numbers come from):
 * natural frequencies with the package on the support, as their makers
 * state them for a support loaded as intended. */
const sw_cli_support_t sw_cli_supports[] = {
    {"frame, soft bearings", 0, 1.0, 0.10,
     "a transport skid on air springs or soft wire-rope isolators"},
    {"frame, stiff bearings", 0, 5.0, 0.10,
     "a frame or pallet on rubber (elastomer) mounts or stiff wire-rope isolators"},
    {"cushion, soft", 1, 8.0, 0.10, "polyurethane or soft polyethylene foam pads, 50-100 mm"},
    {"cushion, firm", 1, 25.0, 0.10, "dense polyethylene foam, rubber or cork-rubber pads"},
};
const size_t sw_cli_nsupports = sizeof sw_cli_supports / sizeof sw_cli_supports[0];

int sw_cli_opt_frequency(const sw_cli_option_t *o, const char *arg, void *dest)
{
    char *end = NULL;
    const double v = strtod(arg, &end);
    if (end == arg || !isfinite(v) || v <= 0.0) {
        sw_cli_error("--%s: expected a frequency > 0 (e.g. 2Hz, or 12.6 for rad/s), got '%s'",
                     o->long_name, arg);
        return SW_EXIT_USAGE;
    }
    while (*end == ' ') end++;
    double scale = 1.0;
    if (!strcasecmp(end, "hz"))
        scale = TWO_PI;
    else if (*end && strcasecmp(end, "rad/s")) {
        sw_cli_error(
            "--%s: unknown unit '%s' in '%s': expected Hz or rad/s (a bare number is "
            "rad/s)",
            o->long_name, end, arg);
        return SW_EXIT_USAGE;
    }
    if (v * scale > 1e4) {
        sw_cli_error("--%s: out of range: expected up to 1e4 rad/s (1592 Hz), got '%s'",
                     o->long_name, arg);
        return SW_EXIT_USAGE;
    }
    *(double *)dest = v * scale;
    return SW_EXIT_OK;
}

int sw_cli_parse_size(const char *arg, double *h, double *w)
{
    char tail;
    return sscanf(arg, "%lfx%lf%c", h, w, &tail) == 2 && isfinite(*h) && isfinite(*w) && *h > 0.0 &&
                   *w > 0.0
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
    if (n->buf[0] == '\0')
        snprintf(n->buf, n->len, "%s: %s", origin ? origin : "scene", msg);
}

static int case_set(sw_cli_case_t *C, const char *sec, const char *key, const char *val,
                    const char *origin)
{
    note_t n = {C->note, sizeof C->note};
    if (sw_scene_set(&C->scene, sec, key, val, 1, origin, 0, note_diag, &n) != SW_OK) {
        C->available = 0;
        if (!C->note[0])
            snprintf(C->note, sizeof C->note, "%s: rejected", origin);
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
        if (!C->note[0])
            snprintf(C->note, sizeof C->note, "invalid scene");
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
                      ", frame m_b %g kg, %.3g Hz (w_b %.4g rad/s), zeta_b %.3g",
                      C->scene.frame_mass, d.omega_b / TWO_PI, d.omega_b, d.zeta_b);
    if (C->scene.has_cushion && k < (int)sizeof C->desc)
        snprintf(C->desc + k, sizeof C->desc - (size_t)k,
                 ", cushion %.3g Hz (w_c %.4g rad/s), zeta_c %.3g", d.omega_c / TWO_PI, d.omega_c,
                 d.zeta_c);
}

/* A number as a scene value. */
static const char *num(char *buf, size_t len, double v)
{
    snprintf(buf, len, "%.17g", v);
    return buf;
}

/* The package on a frame (no cushion): the scene's frame with the
 * options' values, or one made of them; omega rad/s, zeta as text. */
static void frame_case(sw_cli_case_t *C, const sw_scene_t *sc, const sw_cli_whatif_t *w,
                       double omega, const char *zeta)
{
    char mass[32], om[32];
    C->scene = *sc;
    C->scene.has_cushion = 0;
    C->available = 1;
    const char *fm = w->frame_mass   ? w->frame_mass
                     : sc->has_frame ? NULL
                                     : num(mass, sizeof mass, FRAME_MASS_RATIO * sc->mass);
    const char *fz = zeta ? zeta : sc->has_frame ? NULL : SW_CLI_FRAME_ZETA;
    if (fm)
        case_set(C, "frame", "mass", fm, "--frame-mass");
    if (C->available && omega > 0.0)
        case_set(C, "frame", "omega", num(om, sizeof om, omega), "--frame-omega");
    if (C->available && fz)
        case_set(C, "frame", "zeta", fz, "--frame-zeta");
    if (C->available)
        describe(C);
}

/* The package on a cushion: on the bed (a catalogue cushion), or on the
 * scene's support (the user's). */
static void cushion_case(sw_cli_case_t *C, const sw_scene_t *sc, int on_bed, double omega,
                         const char *zeta)
{
    char om[32];
    C->scene = *sc;
    if (on_bed)
        C->scene.has_frame = 0;
    C->available = 1;
    const char *cz = zeta ? zeta : sc->has_cushion ? NULL : SW_CLI_CUSHION_ZETA;
    if (omega > 0.0)
        case_set(C, "cushion", "omega", num(om, sizeof om, omega), "--cushion-omega");
    if (C->available && cz)
        case_set(C, "cushion", "zeta", cz, "--cushion-zeta");
    if (C->available)
        describe(C);
}

/* The cases of one scene into cs (room for 4 + nsupports + sizes). */
static size_t scene_cases(sw_cli_case_t *cs, const sw_scene_t *sc, size_t pkg,
                          const sw_cli_whatif_t *w)
{
    size_t m = 0;
    sw_cli_case_t *C = &cs[m++];
    snprintf(C->name, sizeof C->name, "as given");
    C->scene = *sc;
    C->is_scene = C->available = 1;
    describe(C);
    if (w->no_what_if)
        goto done;

    if (sc->has_frame || sc->has_cushion) { /* the package alone on the bed */
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "bed");
        C->scene = *sc;
        C->scene.has_frame = C->scene.has_cushion = 0;
        C->available = 1;
        describe(C);
    }
    /* The user's supports replace the catalogue's of their kind. */
    const int user_frame = w->frame_omega > 0.0 || w->frame_mass || w->frame_zeta;
    const int user_cushion = w->cushion_omega > 0.0 || w->cushion_zeta;
    for (size_t k = 0; k < sw_cli_nsupports; k++) {
        const sw_cli_support_t *S = &sw_cli_supports[k];
        if (S->cushion ? user_cushion : user_frame)
            continue;
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "%s", S->name);
        C->stands_for = S->stands_for;
        char z[32];
        num(z, sizeof z, S->zeta);
        if (S->cushion)
            cushion_case(C, sc, 1, TWO_PI * S->hz, z);
        else
            frame_case(C, sc, w, TWO_PI * S->hz, z);
    }
    if (user_frame) {
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "frame");
        if (!sc->has_frame && !(w->frame_omega > 0.0)) {
            snprintf(C->note, sizeof C->note, "no bearing frequency given (--frame-omega)");
        } else {
            frame_case(C, sc, w, w->frame_omega, w->frame_zeta);
        }
    }
    if (user_cushion) {
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "cushion");
        if (!sc->has_cushion && !(w->cushion_omega > 0.0))
            snprintf(C->note, sizeof C->note, "no cushion frequency given (--cushion-omega)");
        else
            cushion_case(C, sc, 0, w->cushion_omega, w->cushion_zeta);
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
done:
    for (size_t i = 0; i < m; i++) cs[i].pkg = pkg;
    return m;
}

sw_cli_case_t *sw_cli_whatif_build(const sw_scene_t *scenes, size_t nsc, const sw_cli_whatif_t *w,
                                   size_t *n)
{
    const size_t per = 4 + sw_cli_nsupports + w->sizes.n;
    sw_cli_case_t *cs = calloc(nsc * per, sizeof *cs);
    if (!cs)
        return NULL;
    size_t m = 0;
    for (size_t i = 0; i < nsc; i++) m += scene_cases(cs + m, &scenes[i], i, w);
    *n = m;
    return cs;
}

int sw_cli_whatif_run(sw_cli_case_t *cases, size_t n, const sw_log_t *log, const sw_run_opts_t *ro,
                      const sw_search_opts_t *so, int threads,
                      void (*progress)(void *user, const sw_safety_progress_t *p), void *user)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++) m += cases[i].available != 0;
    if (m == 0)
        return SW_OK;
    sw_safety_case_t *sc = calloc(m, sizeof *sc);
    size_t *of = calloc(m, sizeof *of);
    if (!sc || !of) {
        free(sc);
        free(of);
        return SW_ENOMEM;
    }
    m = 0;
    for (size_t i = 0; i < n; i++)
        if (cases[i].available) {
            of[m] = i;
            sc[m++].scene = cases[i].scene;
        }
    sw_safety_opts_t o = {.run = *ro, .threads = threads, .progress = progress, .user = user};
    if (so)
        o.search = *so;
    const int rc = sw_safety_factors(sc, m, log, &o);
    int any = 0; /* a case of its own failed: rc is its status */
    for (size_t k = 0; k < m; k++) any |= sc[k].status != SW_OK;
    for (size_t k = 0; k < m; k++) {
        sw_cli_case_t *C = &cases[of[k]];
        C->status = any ? sc[k].status : rc;
        C->sf = sc[k].sf;
        if (C->status == SW_OK)
            continue;
        C->available = 0;
        snprintf(C->note, sizeof C->note, "%s", sc[k].msg[0] ? sc[k].msg : sw_strerror(C->status));
    }
    free(sc);
    free(of);
    return rc == SW_ENOMEM ? SW_ENOMEM : SW_OK;
}

typedef struct {
    sw_cli_case_t *cases;
    size_t *of;
    const sw_log_t *log;
    sw_reserve_log_opts_t o;
} reserve_job_t;

static void reserve_job(void *user, size_t k)
{
    const reserve_job_t *J = user;
    sw_cli_case_t *C = &J->cases[J->of[k]];
    const int rc = sw_reserve_log_min(&C->scene, J->log, &J->o, &C->rl, C->reserve_note,
                                      sizeof C->reserve_note);
    C->reserve_status = rc;
    C->has_reserve = rc == SW_OK;
    if (rc != SW_OK && !C->reserve_note[0])
        snprintf(C->reserve_note, sizeof C->reserve_note, "%s", sw_strerror(rc));
}

int sw_cli_whatif_reserve(sw_cli_case_t *cases, size_t n, const sw_log_t *log,
                          const sw_run_opts_t *ro, double rate, long max_evals, int threads)
{
    size_t *of = calloc(n ? n : 1, sizeof *of), m = 0;
    if (!of)
        return SW_ENOMEM;
    for (size_t i = 0; i < n; i++)
        if (cases[i].available && !cases[i].is_scene)
            of[m++] = i;
    reserve_job_t J = {.cases = cases, .of = of, .log = log};
    J.o.rate = rate;
    J.o.max_evals = max_evals;
    J.o.run = *ro;
    sw_parallel_for(m, threads, reserve_job, &J);
    int rc = SW_OK;
    for (size_t k = 0; k < m; k++)
        if (cases[of[k]].reserve_status == SW_ENOMEM)
            rc = SW_ENOMEM;
    free(of);
    return rc;
}

void sw_cli_whatif_reserve_text(char *buf, size_t len, const sw_cli_case_t *C)
{
    const sw_reserve_log_t *r = &C->rl;
    if (!C->has_reserve)
        snprintf(buf, len, "%s%s", C->reserve_note[0] ? "n/a: " : "-", C->reserve_note);
    else if (isnan(r->min_g))
        snprintf(buf, len, "-");
    else if (r->exact)
        snprintf(buf, len, "%.3f g", r->min_g);
    else
        snprintf(buf, len, "<= %.3f g (>= %.3f)", r->min_g, r->lower_g);
}

/* ---- report ---------------------------------------------------------------------- */

/* x with the fewest significant digits (at least 4) that tell it from y. */
static void digits_apart(char *buf, size_t len, double x, double y, int *prec)
{
    int p = 4;
    char a[40], b[40];
    for (; p < 17; p++) {
        snprintf(a, sizeof a, "%#.*g", p, x);
        snprintf(b, sizeof b, "%#.*g", p, y);
        if (strcmp(a, b) != 0)
            break;
    }
    snprintf(buf, len, "%#.*g", p, x);
    if (prec)
        *prec = p;
}

void sw_cli_safety_bracket(char *buf, size_t len, const sw_safety_t *s)
{
    if (isinf(s->lift_scale)) {
        snprintf(buf, len, "none");
    } else if (!s->found) {
        snprintf(buf, len, "> %.4g", s->max_scale);
    } else if (!(s->factor_safe > 0.0)) {
        snprintf(buf, len, "<= %.4g", s->factor);
    } else {
        char lo[40], hi[40];
        int p;
        digits_apart(lo, sizeof lo, s->factor_safe, s->factor, &p);
        snprintf(hi, sizeof hi, "%#.*g", p, s->factor);
        snprintf(buf, len, "[%s, %s]", lo, hi);
    }
}

void sw_cli_safety_sentence(char *buf, size_t len, const sw_safety_t *s)
{
    char lo[40] = "", hi[40] = "";
    int p = 4;
    if (s->found && s->factor_safe > 0.0) {
        digits_apart(lo, sizeof lo, s->factor_safe, s->factor, &p);
        snprintf(hi, sizeof hi, "%#.*g", p, s->factor);
    }
    int k = 0;
    if (isinf(s->lift_scale)) {
        k = snprintf(buf, len,
                     "The log has no longitudinal acceleration: no scale of it moves "
                     "the package.");
    } else if (!s->found) {
        k = snprintf(buf, len,
                     "%s: no scale of the recorded acceleration up to %.4g times overturns it.",
                     s->overturned ? "It overturned" : "It stayed upright", s->max_scale);
    } else if (s->overturned && !(s->factor_safe > 0.0)) {
        k = snprintf(buf, len,
                     "It overturned, and so does every scale of the recording tried, down to "
                     "%.4g times.",
                     s->factor);
    } else if (s->overturned) {
        k = snprintf(buf, len,
                     "It overturned: the same recording at %s times its strength would have left "
                     "it upright, at %s times it already overturns it, so the shock was about "
                     "%.3g times what the package could take.",
                     lo, hi, 1.0 / s->factor);
    } else {
        k = snprintf(buf, len,
                     "It stayed upright: the same recording %s times as strong would still have "
                     "left it upright, %s times as strong overturns it.",
                     lo, hi);
    }
    if (k > 0 && (size_t)k < len && !s->overturned && s->below.found)
        snprintf(buf + k, len - (size_t)k,
                 " But a weaker shock of the same shape, %.4g times the recorded one, overturns "
                 "it: it survived by luck of timing.",
                 s->below.x);
}

void sw_cli_whatif_savers(char *buf, size_t len, const sw_cli_case_t *cs, size_t n, size_t pkg)
{
    size_t k = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < n && k < len; i++) {
        const sw_cli_case_t *C = &cs[i];
        if (C->pkg != pkg || C->is_scene || !C->available || C->sf.overturned)
            continue;
        int w = snprintf(buf + k, len - k, "%s%s", k ? "; " : "", C->name);
        if (w < 0)
            break;
        k += (size_t)w;
    }
    if (k >= len && len > 4)
        snprintf(buf + len - 4, 4, "...");
}

void sw_cli_whatif_print_table(FILE *f, const sw_cli_case_t *cs, size_t n, size_t pkg)
{
    fprintf(f, "  %-22s %-10s %7s %8s %8s  %-12s %-20s %s\n", "case", "outcome", "peak/a", "peak",
            "margin", "min reserve", "safety factor", "package and support");
    int bracket = 0;
    int luck = 0;
    for (size_t i = 0; i < n; i++) {
        const sw_cli_case_t *C = &cs[i];
        if (C->pkg != pkg)
            continue;
        fprintf(f, "  %-22s ", C->name);
        if (!C->available) {
            fprintf(f, "n/a: %s\n", C->note);
            continue;
        }
        const sw_run_result_t *r = &C->sf.at_one;
        char fac[64];
        sw_cli_safety_bracket(fac, sizeof fac, &C->sf);
        if (!C->sf.overturned && C->sf.below.found) {
            strncat(fac, " *", sizeof fac - strlen(fac) - 1);
            luck = 1;
        }
        char rsv[192];
        sw_cli_whatif_reserve_text(rsv, sizeof rsv, C);
        bracket |= C->has_reserve && !C->rl.exact;
        fprintf(f, "%-10s %7.3f %6.1f deg %8.3f  %-12s %-20s %s\n",
                r->overturned ? "OVERTURNED" : "upright", r->max_theta_ratio,
                fmin(r->max_theta_ratio * atan2(C->scene.width, C->scene.height), M_PI / 2) *
                    180.0 / M_PI,
                r->min_margin, rsv, fac, C->desc);
    }
    fprintf(f,
            "  peak/a: largest |theta|/alpha; margin: smallest margin to overturn (1 at rest, "
            "0 at the edge);\n"
            "  min reserve: the smallest reserve along the recording (the design pulse, in g, "
            "that would\n  have overturned it at that moment; docs/reserve.md)%s;\n"
            "  safety factor: scales of the recording that leave it upright / overturn it%s\n",
            bracket ? ", '<= x (>= y)': between y and x, the search stopped at its budget" : "",
            luck ? "\n  *: survived, but a weaker shock of the same shape overturns it" : "");
}

void sw_cli_whatif_json_safety(json_t *o, const sw_cli_case_t *C)
{
    const sw_safety_t *s = &C->sf;
    json_t *j = sw_cli_rec_obj(o, "safety_factor");
    sw_cli_rec_bool(j, "available", C->available);
    if (!C->available) {
        sw_cli_rec_text(j, "note", C->note);
        return;
    }
    char text[640];
    const int both = s->found && s->factor_safe > 0.0;
    sw_cli_rec_bool(j, "overturned", s->overturned);
    sw_cli_rec_bool(j, "found", s->found);
    if (both) {
        json_t *b = sw_cli_rec_arr(j, "bracket");
        sw_cli_rec_num(b, NULL, s->factor_safe);
        sw_cli_rec_num(b, NULL, s->factor);
    } else {
        sw_cli_rec_null(j, "bracket");
    }
    sw_cli_rec_num(j, "factor", s->found ? s->factor : NAN);
    sw_cli_rec_num(j, "factor_safe", both ? s->factor_safe : NAN);
    sw_cli_safety_bracket(text, sizeof text, s);
    sw_cli_rec_text(j, "text", text);
    sw_cli_safety_sentence(text, sizeof text, s);
    sw_cli_rec_text(j, "meaning", text);
    sw_cli_rec_num(j, "weaker_overturning_factor",
                   !s->overturned && s->below.found ? s->below.x : NAN);
    sw_cli_rec_num(j, "lift_scale", s->lift_scale);
    sw_cli_rec_num(j, "max_scale", s->max_scale);
    sw_cli_rec_int(j, "trials", s->trials);
}

/* "min_reserve_g", its time, whether exact, its proven lower end, and
 * the states evaluated; nulls without a reserve (and why). */
static void whatif_json_reserve(json_t *o, const sw_cli_case_t *C)
{
    const sw_reserve_log_t *r = &C->rl;
    const int has = C->has_reserve && !isnan(r->min_g);
    sw_cli_rec_num(o, "min_reserve_g", has ? r->min_g : NAN);
    sw_cli_rec_num(o, "min_reserve_time", has ? r->min_time : NAN);
    sw_cli_rec_put(o, "min_reserve_exact", has ? json_boolean(r->exact) : json_null());
    sw_cli_rec_num(o, "min_reserve_lower_g", has ? r->lower_g : NAN);
    sw_cli_rec_int(o, "reserve_states", has ? (long long)r->states : 0);
    sw_cli_rec_int(o, "reserve_evaluations", has ? r->evaluated : 0L);
    if (!C->has_reserve && C->reserve_note[0])
        sw_cli_rec_text(o, "no_reserve", C->reserve_note);
}

void sw_cli_whatif_json_case(json_t *o, const sw_cli_case_t *C)
{
    sw_cli_rec_text(o, "case", C->name);
    sw_cli_rec_bool(o, "as_given", C->is_scene);
    sw_cli_rec_bool(o, "available", C->available);
    if (C->stands_for)
        sw_cli_rec_text(o, "stands_for", C->stands_for);
    if (C->desc[0]) {
        sw_cli_rec_text(o, "model", sw_model_name(C->model));
        sw_cli_rec_text(o, "support", C->desc);
    }
    if (!C->available) {
        sw_cli_rec_text(o, "note", C->note);
        return;
    }
    const sw_run_result_t *r = &C->sf.at_one;
    sw_cli_rec_bool(o, "overturned", r->overturned);
    sw_cli_rec_num(o, "overturn_time", r->overturn_time);
    sw_cli_rec_num(o, "tip_time", r->tip_time);
    sw_cli_rec_num(o, "uplift_time", r->uplift_time);
    sw_cli_rec_num(o, "max_theta_ratio", r->max_theta_ratio);
    sw_cli_rec_num(o, "min_margin", r->min_margin);
    sw_cli_rec_int(o, "impacts", r->impacts);
    whatif_json_reserve(o, C);
    sw_cli_whatif_json_safety(o, C);
}
