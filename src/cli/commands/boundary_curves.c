/* SPDX-License-Identifier: GPL-3.0-or-later */
/* boundary_curves.c - the curves of "swaywatch boundary": the library's
 * family of curves (every scene times the --vary values that apply to it
 * times the bearing ratios, boundary.h) from the options, each curve's
 * scan range (amplitudes given in g or m/s^2 are its own) checked against
 * the options' bounds and, with --verbose, what it is. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boundary.h"

/* Every scene x every combination of the --vary values that apply to it x
 * every bearing ratio (scenes without a frame: as they are): the
 * library's family of curves (boundary.h), its refusals in the options'
 * words. */
int sw_bnd_build_curves(const sw_scene_t *scenes, size_t nsc, const vary_t *vary, size_t nvary,
                        const double *bearing, size_t nbear, const char *bear_text[], curve_t **out,
                        size_t *nout)
{
    sw_vary_t *sv = calloc(nvary + 1, sizeof *sv);
    if (!sv) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    for (size_t k = 0; k < nvary; k++)
        sv[k] = (sw_vary_t){vary[k].key, (const char *const *)vary[k].values, vary[k].n};
    size_t framed = 0;
    const size_t total = sw_family_count(scenes, nsc, sv, nvary, nbear, &framed);
    int rc = SW_EXIT_USAGE;
    sw_family_curve_t *fc = NULL;
    curve_t *cv = NULL;
    if (nbear && !framed) {
        sw_cli_error("--bearing-ratio: no scene has a [frame]");
        goto out;
    }
    if (total > SW_FAMILY_MAX) {
        sw_cli_error("boundary: more than %d curves", SW_FAMILY_MAX);
        goto out;
    }
    fc = calloc(total + 1, sizeof *fc);
    cv = calloc(total + 1, sizeof *cv);
    if (!fc || !cv) {
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
        goto out;
    }
    sw_cli_diag_t diag = {0};
    sw_family_fail_t fail;
    if (sw_family_build(scenes, nsc, sv, nvary, bearing, bear_text, nbear, fc, sw_cli_print_diag,
                        &diag, &fail) != SW_OK) {
        /* the library said why, unless the scene's parser had no words */
        if (diag.errors == 0 && fail.vary == SIZE_MAX)
            sw_cli_error("%s: invalid scene", fc[fail.curve].label);
        else if (diag.errors == 0)
            sw_cli_error("--vary %s=%s: rejected", sv[fail.vary].key,
                         sv[fail.vary].values[fail.value]);
        goto out;
    }
    for (size_t c = 0; c < total; c++) {
        cv[c].c = fc[c].c;
        memcpy(cv[c].label, fc[c].label, sizeof cv[c].label);
        cv[c].p = fc[c].p;
        cv[c].gtan = fc[c].gtan;
    }
    *out = cv;
    *nout = total;
    cv = NULL;
    rc = SW_EXIT_OK;
out:
    free(cv);
    free(fc);
    free(sv);
    return rc;
}

/* pulse.h: a half-sine of omega_e lasts pi/omega_e, a full-sine 2 pi/omega_e. */
double sw_bnd_shape_angle(const boundary_t *B)
{
    return B->b.bo.shape == SW_PULSE_FULL_SINE ? 2.0 * M_PI : M_PI;
}

/* omega_e/p of curve c at point i. */
double sw_bnd_ratio_at(const boundary_t *B, size_t c, size_t i)
{
    if (B->b.durations)
        return sw_bnd_shape_angle(B) / (B->b.durations[i] * B->cv[c].p);
    return B->b.ratios[i];
}

/* Non-zero (reported) if v, what arg (given in physical units) is for
 * curve C, is outside the bounds of boundary's option named opt. */
static int in_range(const boundary_t *B, const char *opt, const char *arg, const curve_t *C,
                    double v)
{
    const sw_cli_option_t *o = sw_cli_option_named(B->options, opt);
    if (!o || !(o->hi > o->lo) || (v >= o->lo && v <= o->hi))
        return 0;
    sw_cli_error("curve '%s': %s is %g %s, out of range: expected %g to %g", C->label,
                 arg ? arg : "", v, strcmp(opt, "omega-ratio") ? "g tan alpha" : "omega_e/p", o->lo,
                 o->hi);
    return 1;
}

/* Each curve's scan range (amplitudes given in g or m/s^2 are a
 * different g tan alpha for each package). */
int sw_bnd_curve_units(boundary_t *B)
{
    const sw_boundary_opts_t *bo = &B->b.bo;
    for (size_t c = 0; c < B->nc; c++) {
        curve_t *C = &B->cv[c];
        C->x_min = B->b.min_si > 0.0 ? B->b.min_si / C->gtan : bo->search.x_min;
        C->x_max = B->b.max_si > 0.0 ? B->b.max_si / C->gtan : bo->search.x_max;
        /* what the options' bounds say in g tan alpha and omega_e/p, for
         * the values given in g, m/s^2 or ms */
        if ((B->b.min_si > 0.0 && in_range(B, "min-amplitude", B->b.min_arg, C, C->x_min)) ||
            (B->b.max_si > 0.0 && in_range(B, "max-amplitude", B->b.max_arg, C, C->x_max)))
            return SW_EXIT_USAGE;
        for (size_t i = 0; B->b.durations && i < B->b.nr; i++) {
            char dur[64];
            snprintf(dur, sizeof dur, "%gms", B->b.durations[i] * 1e3);
            if (in_range(B, "omega-ratio", dur, C, sw_bnd_ratio_at(B, c, i)))
                return SW_EXIT_USAGE;
        }
        if (C->x_min > 0.0 && C->x_min >= C->x_max) {
            sw_cli_error(
                "curve '%s': --min-amplitude %s (%g g tan alpha) is not below "
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
void sw_bnd_print_curves(const boundary_t *B)
{
    for (size_t c = 0; c < B->nc; c++) {
        const curve_t *C = &B->cv[c];
        sw_derived_t d;
        sw_scene_t s; /* omega_b is set per point */
        sw_curve_scene(&C->c, 0.0, &s);
        if (sw_scene_validate(&s, &d, NULL, NULL, NULL) != SW_OK)
            continue;
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
