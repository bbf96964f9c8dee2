/* SPDX-License-Identifier: GPL-3.0-or-later */
/* family.c - a family of boundary curves (boundary.h): every scene times
 * the values of scene keys that apply to it times the bearing ratios,
 * each curve's scene checked, and its units (p, g tan alpha).  The curves
 * themselves are computed by boundary.c. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "swaywatch/boundary.h"
#include "swaywatch/status.h"

int sw_vary_applies(const sw_vary_t *v, const sw_scene_t *s)
{
    if (!strncmp(v->key, "frame.", 6))
        return s->has_frame;
    if (!strncmp(v->key, "cushion.", 8))
        return s->has_cushion;
    return 1;
}

/* The combinations of the values of the keys that apply to scene s. */
static size_t combos_of(const sw_vary_t *vary, size_t nvary, const sw_scene_t *s)
{
    size_t combos = 1;
    for (size_t k = 0; k < nvary; k++)
        if (sw_vary_applies(&vary[k], s))
            combos *= vary[k].n;
    return combos;
}

size_t sw_family_count(const sw_scene_t *scenes, size_t nsc, const sw_vary_t *vary, size_t nvary,
                       size_t nbear, size_t *framed)
{
    size_t total = 0, nf = 0;
    for (size_t s = 0; s < nsc; s++) {
        total += combos_of(vary, nvary, &scenes[s]) * (scenes[s].has_frame && nbear ? nbear : 1);
        nf += scenes[s].has_frame != 0;
        if (total > SW_FAMILY_MAX)
            break;
    }
    if (framed)
        *framed = nf;
    return total;
}

static void append(char *buf, size_t len, const char *fmt, const char *a, const char *b)
{
    size_t used = strlen(buf);
    if (used < len)
        snprintf(buf + used, len - used, fmt, a, b);
}

static int failed(sw_family_fail_t *fail, size_t curve, size_t vary, size_t value, int rc)
{
    if (fail) {
        fail->curve = curve;
        fail->vary = vary;
        fail->value = value;
    }
    return rc;
}

int sw_family_build(const sw_scene_t *scenes, size_t nsc, const sw_vary_t *vary, size_t nvary,
                    const double *bearing, const char *const *bearing_text, size_t nbear,
                    sw_family_curve_t *out, sw_diag_fn diag, void *user, sw_family_fail_t *fail)
{
    size_t m = 0;
    for (size_t s = 0; s < nsc; s++) {
        const size_t combos = combos_of(vary, nvary, &scenes[s]);
        const size_t nb = scenes[s].has_frame && nbear ? nbear : 1;
        for (size_t c = 0; c < combos; c++)
            for (size_t b = 0; b < nb; b++, m++) {
                sw_family_curve_t *C = &out[m];
                memset(C, 0, sizeof *C);
                C->c.scene = scenes[s]; /* a copy: a key's value edits only this curve */
                snprintf(C->label, sizeof C->label, "%s", scenes[s].name);
                size_t idx = c;
                for (size_t k = 0; k < nvary; k++) {
                    if (!sw_vary_applies(&vary[k], &scenes[s]))
                        continue;
                    const size_t j = idx % vary[k].n;
                    const char *val = vary[k].values[j];
                    idx /= vary[k].n;
                    char assign[512];
                    snprintf(assign, sizeof assign, "%s=%s", vary[k].key, val);
                    const int rc = sw_scene_set_arg(&C->c.scene, assign, diag, user);
                    if (rc != SW_OK)
                        return failed(fail, m, k, j, rc);
                    append(C->label, sizeof C->label, " %s=%s", vary[k].key, val);
                }
                if (scenes[s].has_frame && nbear) {
                    C->c.bearing_ratio = bearing[b];
                    append(C->label, sizeof C->label, " wb/we=%s%s", bearing_text[b], "");
                }
                sw_scene_t check; /* omega_b is set at each point */
                sw_derived_t d;
                sw_curve_scene(&C->c, 0.0, &check);
                if (sw_scene_validate(&check, &d, C->label, diag, user) != SW_OK)
                    return failed(fail, m, SIZE_MAX, 0, SW_EINVAL);
                C->p = d.p;
                C->gtan = check.g * tan(d.alpha);
            }
    }
    return SW_OK;
}
