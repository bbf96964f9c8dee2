/* SPDX-License-Identifier: GPL-3.0-or-later */
/* whatif.c - forensics' what-if cases on the command line (whatif.h):
 * their options into the library's (swaywatch/whatif.h), and the table,
 * the words and the JSON that report them. */
#include "whatif.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "output.h"
#include "swaywatch/status.h"

#define TWO_PI 6.283185307179586

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

int sw_cli_parse_size(const char *arg, double *h, double *w, double *d)
{
    /* split at each 'x' before reading the numbers: strtod alone would
     * read "0x1" as hexadecimal */
    double v[3] = {0.0, 0.0, 0.0};
    size_t n = 0;
    const char *p = arg;
    for (;;) {
        const size_t len = strcspn(p, "x");
        char part[64];
        char *end = NULL;
        if (n == 3 || len == 0 || len >= sizeof part)
            return -1;
        memcpy(part, p, len);
        part[len] = '\0';
        v[n] = strtod(part, &end);
        if (*end || !isfinite(v[n]) || !(v[n] > 0.0))
            return -1;
        n++;
        if (!p[len])
            break;
        p += len + 1;
    }
    if (n < 2)
        return -1;
    *h = v[0];
    *w = v[1];
    *d = v[2]; /* 0: not given */
    return 0;
}

/* ---- the cases -------------------------------------------------------------------- */

/* A case's note names the member of sw_whatif_opts_t that would make it;
 * the user gives an option. */
static void name_option(char *note, size_t len)
{
    static const char *const option[][2] = {
        {"frame_mass", "--frame-mass"},     {"frame_omega", "--frame-omega"},
        {"frame_zeta", "--frame-zeta"},     {"cushion_omega", "--cushion-omega"},
        {"cushion_zeta", "--cushion-zeta"},
    };
    for (size_t i = 0; i < sizeof option / sizeof option[0]; i++) {
        char *at = strstr(note, option[i][0]);
        if (!at)
            continue;
        char tail[256];
        snprintf(tail, sizeof tail, "%s", at + strlen(option[i][0]));
        snprintf(at, len - (size_t)(at - note), "%s%s", option[i][1], tail);
        return;
    }
}

double *sw_cli_whatif_opts(const sw_cli_whatif_t *w, sw_whatif_opts_t *o)
{
    /* height, width of each size, then their depths (0: the scene's) */
    double *sizes = calloc(3 * w->sizes.n + 1, sizeof *sizes);
    for (size_t i = 0; sizes && i < w->sizes.n; i++) /* checked while parsing options */
        sw_cli_parse_size(w->sizes.v[i], &sizes[2 * i], &sizes[2 * i + 1],
                          &sizes[2 * w->sizes.n + i]);
    *o = (sw_whatif_opts_t){.frame_mass = w->frame_mass,
                            .frame_omega = w->frame_omega,
                            .frame_zeta = w->frame_zeta,
                            .cushion_omega = w->cushion_omega,
                            .cushion_zeta = w->cushion_zeta,
                            .sizes = sizes,
                            .nsizes = w->sizes.n,
                            .depths = sizes ? sizes + 2 * w->sizes.n : NULL,
                            .scenes_only = w->no_what_if};
    return sizes;
}

void sw_cli_whatif_name_options(sw_whatif_case_t *cs, size_t n)
{
    for (size_t i = 0; i < n; i++) name_option(cs[i].note, sizeof cs[i].note);
}

const char *sw_cli_whatif_desc(char *buf, size_t len, const sw_whatif_case_t *C)
{
    const sw_derived_t *d = &C->derived;
    buf[0] = '\0';
    if (!C->built)
        return buf;
    /* with a depth, HxWxD as --size writes it: the depth is what a size
     * across the truck varies, or the scene's that a size kept */
    int k = sw_scene_has_depth(&C->scene) ? snprintf(buf, len, "%gx%gx%g m, %g kg", C->scene.height,
                                                     C->scene.width, C->scene.depth, C->scene.mass)
                                          : snprintf(buf, len, "%gx%g m, %g kg", C->scene.height,
                                                     C->scene.width, C->scene.mass);
    if (C->model == SW_MODEL_BARE) {
        snprintf(buf + k, len - (size_t)k, ", on the bed");
        return buf;
    }
    if (C->scene.has_frame)
        k += snprintf(buf + k, len - (size_t)k,
                      ", frame m_b %g kg, %.3g Hz (w_b %.4g rad/s), zeta_b %.3g",
                      C->scene.frame_mass, d->omega_b / TWO_PI, d->omega_b, d->zeta_b);
    if (C->scene.has_cushion && k < (int)len)
        snprintf(buf + k, len - (size_t)k, ", cushion %.3g Hz (w_c %.4g rad/s), zeta_c %.3g",
                 d->omega_c / TWO_PI, d->omega_c, d->zeta_c);
    return buf;
}

void sw_cli_whatif_reserve_text(char *buf, size_t len, const sw_whatif_case_t *C)
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

void sw_cli_whatif_savers(char *buf, size_t len, const sw_forensics_t *fx,
                          const sw_whatif_case_t *cs, size_t n, size_t pkg)
{
    size_t k = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < n && k < len; i++) {
        sw_forensics_verdict_t v;
        if (cs[i].pkg != pkg || sw_forensics_case_verdict(fx, i, &v) != SW_OK || !v.saves)
            continue;
        int w = snprintf(buf + k, len - k, "%s%s", k ? "; " : "", cs[i].name);
        if (w < 0)
            break;
        k += (size_t)w;
    }
    if (k >= len && len > 4)
        snprintf(buf + len - 4, 4, "...");
}

void sw_cli_whatif_print_table(FILE *f, const sw_forensics_t *fx, const sw_whatif_case_t *cs,
                               size_t n, size_t pkg)
{
    int two = 0; /* a case of the package in both planes: a column names the plane */
    for (size_t i = 0; i < n; i++) {
        sw_forensics_verdict_t v;
        two |= cs[i].pkg == pkg && sw_forensics_case_verdict(fx, i, &v) == SW_OK && v.planes == 2;
    }
    fprintf(f, "  %-22s %-10s %s%7s %8s %8s  %-12s %-20s %s\n", "case", "outcome",
            two ? "plane   " : "", "peak/a", "peak", "margin", "min reserve", "safety factor",
            "package and support");
    int bracket = 0;
    int luck = 0;
    for (size_t i = 0; i < n; i++) {
        const sw_whatif_case_t *C = &cs[i];
        if (C->pkg != pkg)
            continue;
        fprintf(f, "  %-22s ", C->name);
        sw_forensics_verdict_t v;
        sw_forensics_case_verdict(fx, i, &v);
        if (!v.judged) {
            fprintf(f, "n/a: %s%s\n", v.unjudged == SW_PLANE_LAT ? "across the truck: " : "",
                    v.note);
            continue;
        }
        const sw_safety_t *sf = &v.factor.sf;
        const sw_whatif_case_t *W = v.run, *T = v.factor.lateral;
        const sw_run_result_t *r = &W->sf.at_one;
        char fac[64];
        sw_cli_safety_bracket(fac, sizeof fac, sf);
        if (!sf->overturned && sf->below.found) {
            strncat(fac, " *", sizeof fac - strlen(fac) - 1);
            luck = 1;
        }
        char rsv[192], desc[224];
        sw_cli_whatif_reserve_text(rsv, sizeof rsv, v.reserve);
        bracket |= C->has_reserve && !C->rl.exact;
        bracket |= T && T->has_reserve && !T->rl.exact;
        fprintf(f, "%-10s ", r->overturned ? "OVERTURNED" : "upright");
        if (two)
            fprintf(f, "%-7s ", W == C ? "along" : "across");
        fprintf(f, "%7.3f %6.1f deg %8.3f  %-12s %-20s %s\n", r->max_theta_ratio,
                fmin(r->max_theta_ratio * atan2(W->scene.width, W->scene.height), M_PI / 2) *
                    180.0 / M_PI,
                r->min_margin, rsv, fac, sw_cli_whatif_desc(desc, sizeof desc, C));
    }
    fprintf(f,
            "  peak/a: largest |theta|/alpha; margin: smallest margin to overturn (1 at rest, "
            "0 at the edge);\n"
            "  min reserve: the smallest reserve along the recording (the design pulse, in g, "
            "that would\n  have overturned it at that moment; docs/reserve.md)%s;\n"
            "  safety factor: scales of the recording that leave it upright / overturn it%s%s\n",
            bracket ? ", '<= x (>= y)': between y and x, the search stopped at its budget" : "",
            two ? "\n  plane: the worse plane, along or across the truck (with a depth, each case "
                  "in both;\n  its reserve the smaller, its safety factor both axes scaled "
                  "together)"
                : "",
            luck ? "\n  *: survived, but a weaker shock of the same shape overturns it" : "");
}

json_t *sw_cli_json_safety(json_t *o, const char *key, const sw_whatif_case_t *C,
                           const sw_safety_t *s)
{
    json_t *j = sw_cli_rec_obj(o, key);
    sw_cli_rec_bool(j, "available", C->available);
    if (!C->available) {
        sw_cli_rec_text(j, "note", C->note);
        return j;
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
    return j;
}

json_t *sw_cli_json_factor(json_t *o, const sw_whatif_case_t *C, const sw_forensics_factor_t *x)
{
    json_t *j = sw_cli_json_safety(o, "safety_factor", C, &x->sf);
    if (x->planes < 2)
        return j;
    /* both axes scaled together: the plane that gives out first, and each
     * plane's own search */
    sw_cli_rec_text(j, "plane", sw_plane_name(x->first));
    json_t *by = sw_cli_rec_obj(j, "planes");
    sw_cli_json_safety(by, "longitudinal", C, &C->sf);
    sw_cli_json_safety(by, "lateral", x->lateral, &x->lateral->sf);
    return j;
}

/* "min_reserve_g", its time, whether exact, its proven lower end, and
 * the states evaluated; nulls without a reserve (and why). */
static void whatif_json_reserve(json_t *o, const sw_whatif_case_t *C)
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

/* A run at scale 1 (a case's, or its worse plane's) and the reserve of
 * case C as members of o. */
static void json_run(json_t *o, const sw_whatif_case_t *C, const sw_run_result_t *r)
{
    sw_cli_rec_bool(o, "overturned", r->overturned);
    sw_cli_rec_num(o, "overturn_time", r->overturn_time);
    sw_cli_rec_num(o, "tip_time", r->tip_time);
    sw_cli_rec_num(o, "uplift_time", r->uplift_time);
    sw_cli_rec_num(o, "max_theta_ratio", r->max_theta_ratio);
    sw_cli_rec_num(o, "min_margin", r->min_margin);
    sw_cli_rec_int(o, "impacts", r->impacts);
    whatif_json_reserve(o, C);
}

void sw_cli_whatif_json_case(json_t *o, const sw_forensics_t *fx, const sw_whatif_case_t *cs,
                             size_t i)
{
    const sw_whatif_case_t *C = &cs[i];
    sw_cli_rec_text(o, "case", C->name);
    sw_cli_rec_bool(o, "as_given", C->is_scene);
    sw_cli_rec_bool(o, "available", C->available);
    if (C->stands_for)
        sw_cli_rec_text(o, "stands_for", C->stands_for);
    if (C->built) {
        char desc[224];
        sw_cli_rec_text(o, "model", sw_model_name(C->model));
        sw_cli_rec_text(o, "support", sw_cli_whatif_desc(desc, sizeof desc, C));
    }
    if (!C->available) {
        sw_cli_rec_text(o, "note", C->note);
        return;
    }
    sw_forensics_verdict_t v;
    sw_forensics_case_verdict(fx, i, &v);
    const sw_whatif_case_t *T = v.factor.lateral;
    if (v.factor.planes == 2) /* the worse plane's verdict, named */
        sw_cli_rec_text(o, "plane", sw_plane_name(v.factor.worse));
    /* the smaller reserve; the factor with both axes scaled */
    json_run(o, v.judged ? v.reserve : C, v.judged ? &v.run->sf.at_one : &C->sf.at_one);
    sw_cli_json_factor(o, C, &v.factor);
    if (T) {
        json_run(sw_cli_rec_obj(o, "lateral"), T, &T->sf.at_one);
    } else if (v.unjudged == SW_PLANE_LAT) { /* a depth, but no verdict across: not upright */
        json_t *l = sw_cli_rec_obj(o, "lateral");
        sw_cli_rec_bool(l, "available", 0);
        sw_cli_rec_text(l, "note", v.note);
    }
}
