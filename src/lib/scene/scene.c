/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scene.c - what stands on the truck: the keys a scene knows, filling a
 * scene key by key, "--set section.key=value" overrides, and whether two
 * scenes are the same.  Parsing a scene file is in scene_parse.c,
 * validation and the derived quantities of physics.md in
 * scene_validate.c.
 *
 * No I/O and no global mutable state: the caller hands in the text and a
 * callback for diagnostics. */
#include "swaywatch/scene.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_int.h"
#include "swaywatch/model.h"
#include "swaywatch/status.h"

/* ---- the keys a scene file knows ---------------------------------------- */

const char *const sw_scene_section_names[SEC_COUNT] = {"package", "frame", "cushion", "alarm"};
static const char *const section_keys[SEC_COUNT] = {
    "name, height, width, mass, g, depth",
    "mass, stiffness or omega, damping or zeta, lateral_stiffness or lateral_omega, "
    "lateral_damping or lateral_zeta",
    "stiffness or omega, damping or zeta, cubic, lateral_stiffness or lateral_omega, "
    "lateral_damping or lateral_zeta, lateral_cubic",
    "warn_margin, critical_margin, design_pulse, warn_reserve_g, critical_reserve_g",
};

const key_info sw_scene_keys[K_COUNT] = {
    [K_NAME] = {SEC_PACKAGE, "name", -1, ""},
    [K_HEIGHT] = {SEC_PACKAGE, "height", -1, "m"},
    [K_WIDTH] = {SEC_PACKAGE, "width", -1, "m"},
    [K_MASS] = {SEC_PACKAGE, "mass", -1, "kg"},
    [K_G] = {SEC_PACKAGE, "g", -1, "m/s^2"},
    [K_DEPTH] = {SEC_PACKAGE, "depth", -1, "m"},
    [K_FRAME_MASS] = {SEC_FRAME, "mass", -1, "kg"},
    [K_FRAME_STIFFNESS] = {SEC_FRAME, "stiffness", K_FRAME_OMEGA, "N/m"},
    [K_FRAME_OMEGA] = {SEC_FRAME, "omega", K_FRAME_STIFFNESS, "rad/s"},
    [K_FRAME_DAMPING] = {SEC_FRAME, "damping", K_FRAME_ZETA, "N*s/m"},
    [K_FRAME_ZETA] = {SEC_FRAME, "zeta", K_FRAME_DAMPING, ""},
    [K_FRAME_LAT_STIFFNESS] = {SEC_FRAME, "lateral_stiffness", K_FRAME_LAT_OMEGA, "N/m"},
    [K_FRAME_LAT_OMEGA] = {SEC_FRAME, "lateral_omega", K_FRAME_LAT_STIFFNESS, "rad/s"},
    [K_FRAME_LAT_DAMPING] = {SEC_FRAME, "lateral_damping", K_FRAME_LAT_ZETA, "N*s/m"},
    [K_FRAME_LAT_ZETA] = {SEC_FRAME, "lateral_zeta", K_FRAME_LAT_DAMPING, ""},
    [K_CUSHION_STIFFNESS] = {SEC_CUSHION, "stiffness", K_CUSHION_OMEGA, "N/m"},
    [K_CUSHION_OMEGA] = {SEC_CUSHION, "omega", K_CUSHION_STIFFNESS, "rad/s"},
    [K_CUSHION_DAMPING] = {SEC_CUSHION, "damping", K_CUSHION_ZETA, "N*s/m"},
    [K_CUSHION_ZETA] = {SEC_CUSHION, "zeta", K_CUSHION_DAMPING, ""},
    [K_CUSHION_CUBIC] = {SEC_CUSHION, "cubic", -1, "N/m^3"},
    [K_CUSHION_LAT_STIFFNESS] = {SEC_CUSHION, "lateral_stiffness", K_CUSHION_LAT_OMEGA, "N/m"},
    [K_CUSHION_LAT_OMEGA] = {SEC_CUSHION, "lateral_omega", K_CUSHION_LAT_STIFFNESS, "rad/s"},
    [K_CUSHION_LAT_DAMPING] = {SEC_CUSHION, "lateral_damping", K_CUSHION_LAT_ZETA, "N*s/m"},
    [K_CUSHION_LAT_ZETA] = {SEC_CUSHION, "lateral_zeta", K_CUSHION_LAT_DAMPING, ""},
    [K_CUSHION_LAT_CUBIC] = {SEC_CUSHION, "lateral_cubic", -1, "N/m^3"},
    [K_WARN] = {SEC_ALARM, "warn_margin", -1, ""},
    [K_CRITICAL] = {SEC_ALARM, "critical_margin", -1, ""},
    [K_DESIGN_PULSE] = {SEC_ALARM, "design_pulse", -1, "s"},
    [K_WARN_RESERVE] = {SEC_ALARM, "warn_reserve_g", -1, "g"},
    [K_CRITICAL_RESERVE] = {SEC_ALARM, "critical_reserve_g", -1, "g"},
};

int sw_scene_find_section(const char *name)
{
    for (int s = 0; s < SEC_COUNT; s++)
        if (!strcmp(name, sw_scene_section_names[s]))
            return s;
    return -1;
}

int sw_scene_find_key(int section, const char *name)
{
    for (int k = 0; k < K_COUNT; k++)
        if (sw_scene_keys[k].section == section && !strcmp(name, sw_scene_keys[k].name))
            return k;
    return -1;
}

/* Where the value of key k lives (NULL for the name). */
static double *key_value(sw_scene_t *sc, int k)
{
    switch (k) {
        case K_HEIGHT: return &sc->height;
        case K_WIDTH: return &sc->width;
        case K_MASS: return &sc->mass;
        case K_G: return &sc->g;
        case K_DEPTH: return &sc->depth;
        case K_FRAME_MASS: return &sc->frame_mass;
        case K_FRAME_STIFFNESS: return &sc->frame_stiffness;
        case K_FRAME_OMEGA: return &sc->frame_omega;
        case K_FRAME_DAMPING: return &sc->frame_damping;
        case K_FRAME_ZETA: return &sc->frame_zeta;
        case K_FRAME_LAT_STIFFNESS: return &sc->frame_lat_stiffness;
        case K_FRAME_LAT_OMEGA: return &sc->frame_lat_omega;
        case K_FRAME_LAT_DAMPING: return &sc->frame_lat_damping;
        case K_FRAME_LAT_ZETA: return &sc->frame_lat_zeta;
        case K_CUSHION_STIFFNESS: return &sc->cushion_stiffness;
        case K_CUSHION_OMEGA: return &sc->cushion_omega;
        case K_CUSHION_DAMPING: return &sc->cushion_damping;
        case K_CUSHION_ZETA: return &sc->cushion_zeta;
        case K_CUSHION_CUBIC: return &sc->cushion_cubic;
        case K_CUSHION_LAT_STIFFNESS: return &sc->cushion_lat_stiffness;
        case K_CUSHION_LAT_OMEGA: return &sc->cushion_lat_omega;
        case K_CUSHION_LAT_DAMPING: return &sc->cushion_lat_damping;
        case K_CUSHION_LAT_ZETA: return &sc->cushion_lat_zeta;
        case K_CUSHION_LAT_CUBIC: return &sc->cushion_lat_cubic;
        case K_WARN: return &sc->warn_margin;
        case K_CRITICAL: return &sc->critical_margin;
        case K_WARN_RESERVE: return &sc->warn_reserve_g;
        case K_CRITICAL_RESERVE: return &sc->critical_reserve_g;
        default: return NULL;
    }
}

/* The "given" flag of the pair key k belongs to (NULL if none). */
static sw_given *key_given(sw_scene_t *sc, int k)
{
    switch (k) {
        case K_FRAME_STIFFNESS:
        case K_FRAME_OMEGA: return &sc->frame_k_given;
        case K_FRAME_DAMPING:
        case K_FRAME_ZETA: return &sc->frame_c_given;
        case K_CUSHION_STIFFNESS:
        case K_CUSHION_OMEGA: return &sc->cushion_k_given;
        case K_CUSHION_DAMPING:
        case K_CUSHION_ZETA: return &sc->cushion_c_given;
        case K_FRAME_LAT_STIFFNESS:
        case K_FRAME_LAT_OMEGA: return &sc->frame_lat_k_given;
        case K_FRAME_LAT_DAMPING:
        case K_FRAME_LAT_ZETA: return &sc->frame_lat_c_given;
        case K_CUSHION_LAT_STIFFNESS:
        case K_CUSHION_LAT_OMEGA: return &sc->cushion_lat_k_given;
        case K_CUSHION_LAT_DAMPING:
        case K_CUSHION_LAT_ZETA: return &sc->cushion_lat_c_given;
        default: return NULL;
    }
}

static sw_given key_form(int k)
{
    switch (k) {
        case K_FRAME_OMEGA:
        case K_FRAME_ZETA:
        case K_CUSHION_OMEGA:
        case K_CUSHION_ZETA:
        case K_FRAME_LAT_OMEGA:
        case K_FRAME_LAT_ZETA:
        case K_CUSHION_LAT_OMEGA:
        case K_CUSHION_LAT_ZETA: return SW_GIVEN_RATIO;
        default: return SW_GIVEN_DIMENSIONAL;
    }
}

/* ---- diagnostics --------------------------------------------------------- */

void sw_scene_report(sw_diag_fn diag, void *user, const char *origin, int line, const char *fmt,
                     ...)
{
    if (!diag)
        return;
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    diag(user, origin ? origin : "", line, msg);
}

/* ---- setting one key ----------------------------------------------------- */

/* Read a finite decimal number; white space around it is allowed.  Returns
 * NULL on success, else why the text is not one. */
static const char *parse_number(const char *s, double *out)
{
    while (isspace((unsigned char)*s)) s++;
    if (*s == '\0')
        return "empty value";
    /* strtod() also reads hexadecimal floats ("0x1p3"); a scene file is
     * written by people in decimal, so an 'x' anywhere is a typo. */
    if (strpbrk(s, "xX"))
        return "not a decimal number";
    errno = 0;
    char *end;
    double v = strtod(s, &end);
    if (end == s)
        return "not a number";
    while (isspace((unsigned char)*end)) end++;
    if (*end != '\0')
        return "unexpected text after the number";
    /* "nan", "inf" and overflow ("1e400" gives HUGE_VAL, ERANGE) all end
     * here; an underflow to 0 or a subnormal is harmless and is let through
     * to the range checks. */
    if (!isfinite(v))
        return "not a finite number";
    *out = v;
    return NULL;
}

static int set_name(sw_scene_t *sc, const char *value, const char *origin, int line,
                    sw_diag_fn diag, void *user)
{
    const char *s = value;
    while (isspace((unsigned char)*s)) s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1])) n--;
    if (n == 0) {
        sw_scene_report(diag, user, origin, line,
                        "package.name is empty: expected a name for messages");
        return SW_EINVAL;
    }
    if (n > SW_NAME_MAX - 1) {
        sw_scene_report(diag, user, origin, line,
                        "package.name is %zu characters long: expected at most %d characters", n,
                        SW_NAME_MAX - 1);
        return SW_EINVAL;
    }
    for (size_t i = 0; i < n; i++) {
        /* Bytes >= 0x80 are let through so that UTF-8 names work; control
         * characters would garble messages and reports. */
        unsigned char ch = (unsigned char)s[i];
        if (ch < 0x20 || ch == 0x7f) {
            sw_scene_report(diag, user, origin, line,
                            "package.name contains a control character: expected printable text");
            return SW_EINVAL;
        }
    }
    memcpy(sc->name, s, n);
    sc->name[n] = '\0';
    return SW_OK;
}

/* alarm.design_pulse: 1 to SW_DESIGN_PULSES_MAX finite numbers separated
 * by commas; the list replaces the one before (ranges are checked by
 * validation, as for every number). */
static int set_pulses(sw_scene_t *sc, const char *value, const char *origin, int line,
                      sw_diag_fn diag, void *user)
{
    double v[SW_DESIGN_PULSES_MAX];
    int n = 0;
    const char *p = value;
    for (;;) {
        const size_t len = strcspn(p, ",");
        char item[64];
        if (n == SW_DESIGN_PULSES_MAX) {
            sw_scene_report(
                diag, user, origin, line,
                "alarm.design_pulse = \"%.40s\": more than %d durations, expected at most %d",
                value, SW_DESIGN_PULSES_MAX, SW_DESIGN_PULSES_MAX);
            return SW_EINVAL;
        }
        if (len >= sizeof item) {
            sw_scene_report(
                diag, user, origin, line,
                "alarm.design_pulse = \"%.40s\": item %d is too long, expected a duration "
                "in s",
                value, n + 1);
            return SW_EINVAL;
        }
        memcpy(item, p, len);
        item[len] = '\0';
        const char *why = parse_number(item, &v[n]);
        if (why) {
            sw_scene_report(diag, user, origin, line,
                            "alarm.design_pulse = \"%.40s\": item %d: %s, expected durations in s "
                            "separated by commas",
                            value, n + 1, why);
            return SW_EINVAL;
        }
        n++;
        if (p[len] != ',')
            break;
        p += len + 1;
    }
    memcpy(sc->design_pulse, v, sizeof(double) * (size_t)n);
    for (int i = n; i < SW_DESIGN_PULSES_MAX; i++) sc->design_pulse[i] = 0.0;
    sc->n_design_pulse = n;
    return SW_OK;
}

void sw_scene_init(sw_scene_t *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->height = sc->width = sc->mass = NAN;
    sc->g = 9.81;
    sc->frame_mass = sc->frame_stiffness = sc->frame_omega = NAN;
    sc->frame_damping = sc->frame_zeta = NAN;
    sc->cushion_stiffness = sc->cushion_omega = NAN;
    sc->cushion_damping = sc->cushion_zeta = NAN;
    sc->cushion_cubic = 0.0;
    sc->depth = NAN;
    sc->frame_lat_stiffness = sc->frame_lat_omega = NAN;
    sc->frame_lat_damping = sc->frame_lat_zeta = NAN;
    sc->cushion_lat_stiffness = sc->cushion_lat_omega = NAN;
    sc->cushion_lat_damping = sc->cushion_lat_zeta = sc->cushion_lat_cubic = NAN;
    sc->frame_lat_k_given = sc->frame_lat_c_given = SW_GIVEN_NONE;
    sc->cushion_lat_k_given = sc->cushion_lat_c_given = SW_GIVEN_NONE;
    sc->frame_k_given = sc->frame_c_given = SW_GIVEN_NONE;
    sc->cushion_k_given = sc->cushion_c_given = SW_GIVEN_NONE;
    sc->warn_margin = 0.5;
    sc->critical_margin = 0.2;
    sc->design_pulse[0] = SW_DESIGN_PULSE_DEFAULT;
    sc->n_design_pulse = 1;
    sc->warn_reserve_g = SW_WARN_RESERVE_G_DEFAULT;
    sc->critical_reserve_g = SW_CRITICAL_RESERVE_G_DEFAULT;
}

int sw_scene_set(sw_scene_t *sc, const char *section, const char *key, const char *value,
                 int override, const char *origin, int line, sw_diag_fn diag, void *user)
{
    if (!sc || !section || !key || !value) {
        sw_scene_report(diag, user, origin, line, "internal: sw_scene_set called without a %s",
                        !sc        ? "scene"
                        : !section ? "section"
                        : !key     ? "key"
                                   : "value");
        return SW_EINVAL;
    }
    int s = sw_scene_find_section(section);
    if (s < 0) {
        sw_scene_report(diag, user, origin, line,
                        "unknown section [%.40s]: expected package, frame, cushion or alarm",
                        section);
        return SW_ENOTFOUND;
    }
    int k = sw_scene_find_key(s, key);
    if (k < 0) {
        sw_scene_report(diag, user, origin, line, "unknown key %s.%.40s: expected one of %s",
                        section, key, section_keys[s]);
        return SW_ENOTFOUND;
    }

    int rc;
    if (k == K_NAME) {
        rc = set_name(sc, value, origin, line, diag, user);
    } else if (k == K_DESIGN_PULSE) {
        rc = set_pulses(sc, value, origin, line, diag, user);
    } else {
        double v;
        const char *why = parse_number(value, &v);
        if (why) {
            sw_scene_report(diag, user, origin, line,
                            "%s.%s = \"%.40s\": %s, expected a finite number%s%s", section, key,
                            value, why, *sw_scene_keys[k].unit ? " in " : "",
                            sw_scene_keys[k].unit);
            return SW_EINVAL;
        }
        sw_given *given = key_given(sc, k);
        if (given && *given != SW_GIVEN_NONE && *given != key_form(k)) {
            int other = sw_scene_keys[k].partner;
            if (!override) {
                sw_scene_report(diag, user, origin, line,
                                "%s.%s and %s.%s both given: expected one of the two, not both",
                                section, key, section, sw_scene_keys[other].name);
                return SW_EINVAL;
            }
            /* An override replaces the pair, whichever form it was in. */
            *key_value(sc, other) = NAN;
        }
        *key_value(sc, k) = v;
        if (given)
            *given = key_form(k);
        rc = SW_OK;
    }
    if (rc == SW_OK) {
        if (s == SEC_FRAME)
            sc->has_frame = 1;
        if (s == SEC_CUSHION)
            sc->has_cushion = 1;
    }
    return rc;
}

int sw_scene_set_arg(sw_scene_t *sc, const char *assignment, sw_diag_fn diag, void *user)
{
    static const char origin[] = "--set";
    if (!sc || !assignment) {
        sw_scene_report(diag, user, origin, 0, "internal: sw_scene_set_arg called without %s",
                        !sc ? "a scene" : "an assignment");
        return SW_EINVAL;
    }
    const char *eq = strchr(assignment, '=');
    const char *dot = eq ? memchr(assignment, '.', (size_t)(eq - assignment)) : NULL;
    /* Section and key names are short; anything longer is malformed. */
    char section[32], key[32];
    const char *p[2][2] = {{assignment, dot}, {dot ? dot + 1 : NULL, eq}};
    char *dst[2] = {section, key};
    int ok = dot != NULL;
    for (int i = 0; ok && i < 2; i++) {
        const char *a = p[i][0], *b = p[i][1];
        while (a < b && isspace((unsigned char)*a)) a++;
        while (b > a && isspace((unsigned char)b[-1])) b--;
        size_t n = (size_t)(b - a);
        if (n == 0 || n >= sizeof section) {
            ok = 0;
            break;
        }
        memcpy(dst[i], a, n);
        dst[i][n] = '\0';
    }
    if (!ok) {
        sw_scene_report(diag, user, origin, 0,
                        "\"%.60s\": expected section.key=value, e.g. frame.zeta=0.1", assignment);
        return SW_EINVAL;
    }
    return sw_scene_set(sc, section, key, eq + 1, 1, origin, 0, diag, user);
}

static int same_number(double a, double b)
{
    return a == b || (isnan(a) && isnan(b));
}

/* The design pulse lists: the same durations in the same order (entries
 * past the count do not count). */
static int same_pulses(const sw_scene_t *a, const sw_scene_t *b)
{
    if (a->n_design_pulse != b->n_design_pulse)
        return 0;
    for (int i = 0; i < a->n_design_pulse && i < SW_DESIGN_PULSES_MAX; i++)
        if (!same_number(a->design_pulse[i], b->design_pulse[i]))
            return 0;
    return 1;
}

/* The depth and the lateral_* values. */
static int same_lateral(const sw_scene_t *a, const sw_scene_t *b)
{
    return same_number(a->depth, b->depth) &&
           same_number(a->frame_lat_stiffness, b->frame_lat_stiffness) &&
           same_number(a->frame_lat_omega, b->frame_lat_omega) &&
           same_number(a->frame_lat_damping, b->frame_lat_damping) &&
           same_number(a->frame_lat_zeta, b->frame_lat_zeta) &&
           a->frame_lat_k_given == b->frame_lat_k_given &&
           a->frame_lat_c_given == b->frame_lat_c_given &&
           same_number(a->cushion_lat_stiffness, b->cushion_lat_stiffness) &&
           same_number(a->cushion_lat_omega, b->cushion_lat_omega) &&
           same_number(a->cushion_lat_damping, b->cushion_lat_damping) &&
           same_number(a->cushion_lat_zeta, b->cushion_lat_zeta) &&
           same_number(a->cushion_lat_cubic, b->cushion_lat_cubic) &&
           a->cushion_lat_k_given == b->cushion_lat_k_given &&
           a->cushion_lat_c_given == b->cushion_lat_c_given;
}

/* Every field but the line numbers; a new field of sw_scene_t must be
 * added here. */
int sw_scene_equal(const sw_scene_t *a, const sw_scene_t *b)
{
    return !strcmp(a->name, b->name) && same_number(a->height, b->height) &&
           same_number(a->width, b->width) && same_number(a->mass, b->mass) &&
           same_number(a->g, b->g) && a->has_frame == b->has_frame &&
           same_number(a->frame_mass, b->frame_mass) &&
           same_number(a->frame_stiffness, b->frame_stiffness) &&
           same_number(a->frame_omega, b->frame_omega) &&
           same_number(a->frame_damping, b->frame_damping) &&
           same_number(a->frame_zeta, b->frame_zeta) && a->frame_k_given == b->frame_k_given &&
           a->frame_c_given == b->frame_c_given && a->has_cushion == b->has_cushion &&
           same_number(a->cushion_stiffness, b->cushion_stiffness) &&
           same_number(a->cushion_omega, b->cushion_omega) &&
           same_number(a->cushion_damping, b->cushion_damping) &&
           same_number(a->cushion_zeta, b->cushion_zeta) &&
           same_number(a->cushion_cubic, b->cushion_cubic) &&
           a->cushion_k_given == b->cushion_k_given && a->cushion_c_given == b->cushion_c_given &&
           same_number(a->warn_margin, b->warn_margin) &&
           same_number(a->critical_margin, b->critical_margin) && same_pulses(a, b) &&
           same_number(a->warn_reserve_g, b->warn_reserve_g) &&
           same_number(a->critical_reserve_g, b->critical_reserve_g) && same_lateral(a, b);
}

int sw_scene_has_depth(const sw_scene_t *sc)
{
    return sc && !isnan(sc->depth);
}

/* One (stiffness|omega) or (damping|zeta) pair across the truck: its own
 * where given, else the one along the truck. */
static void lateral_pair(sw_given lat_given, double lat_dim, double lat_ratio, sw_given *given,
                         double *dim, double *ratio)
{
    if (lat_given == SW_GIVEN_NONE)
        return;
    *given = lat_given;
    *dim = lat_dim;
    *ratio = lat_ratio;
}

int sw_scene_lateral(const sw_scene_t *sc, sw_scene_t *lat)
{
    if (!sw_scene_has_depth(sc) || !lat)
        return SW_ENOTFOUND;
    sw_scene_t l = *sc;
    l.width = sc->depth;
    l.depth = NAN;
    lateral_pair(sc->frame_lat_k_given, sc->frame_lat_stiffness, sc->frame_lat_omega,
                 &l.frame_k_given, &l.frame_stiffness, &l.frame_omega);
    lateral_pair(sc->frame_lat_c_given, sc->frame_lat_damping, sc->frame_lat_zeta, &l.frame_c_given,
                 &l.frame_damping, &l.frame_zeta);
    lateral_pair(sc->cushion_lat_k_given, sc->cushion_lat_stiffness, sc->cushion_lat_omega,
                 &l.cushion_k_given, &l.cushion_stiffness, &l.cushion_omega);
    lateral_pair(sc->cushion_lat_c_given, sc->cushion_lat_damping, sc->cushion_lat_zeta,
                 &l.cushion_c_given, &l.cushion_damping, &l.cushion_zeta);
    if (!isnan(sc->cushion_lat_cubic))
        l.cushion_cubic = sc->cushion_lat_cubic;
    l.frame_lat_stiffness = l.frame_lat_omega = l.frame_lat_damping = l.frame_lat_zeta = NAN;
    l.cushion_lat_stiffness = l.cushion_lat_omega = NAN;
    l.cushion_lat_damping = l.cushion_lat_zeta = l.cushion_lat_cubic = NAN;
    l.frame_lat_k_given = l.frame_lat_c_given = SW_GIVEN_NONE;
    l.cushion_lat_k_given = l.cushion_lat_c_given = SW_GIVEN_NONE;
    *lat = l;
    return SW_OK;
}
