/* SPDX-License-Identifier: GPL-3.0-or-later */
/* whatif.c - the what-if cases (whatif.h): the catalogue of typical
 * supports, each scene's cases built from it, and their safety factors
 * and smallest reserves by the analyses of sweep.h and reserve.h. */
#include "swaywatch/whatif.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/pool.h"
#include "swaywatch/status.h"

#define TWO_PI 6.283185307179586

/* The catalogue (docs/forensics.md says where the numbers come from):
 * natural frequencies with the package on the support, as their makers
 * state them for a support loaded as intended. */
static const sw_support_t supports[] = {
    {"frame, soft bearings", 0, 1.0, SW_WHATIF_ZETA,
     "a transport skid on air springs or soft wire-rope isolators"},
    {"frame, stiff bearings", 0, 5.0, SW_WHATIF_ZETA,
     "a frame or pallet on rubber (elastomer) mounts or stiff wire-rope isolators"},
    {"cushion, soft", 1, 8.0, SW_WHATIF_ZETA,
     "polyurethane or soft polyethylene foam pads, 50-100 mm"},
    {"cushion, firm", 1, 25.0, SW_WHATIF_ZETA,
     "dense polyethylene foam, rubber or cork-rubber pads"},
};
#define NSUPPORTS (sizeof supports / sizeof supports[0])

const sw_support_t *sw_whatif_supports(size_t *n)
{
    *n = NSUPPORTS;
    return supports;
}

size_t sw_whatif_max(size_t n, const sw_whatif_opts_t *o)
{
    /* as given, bed, the catalogue, the caller's frame and cushion, sizes */
    return n * (4 + NSUPPORTS + o->nsizes);
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

static void set(sw_whatif_case_t *C, const char *sec, const char *key, const char *val,
                const char *origin)
{
    note_t n = {C->note, sizeof C->note};
    if (C->available &&
        sw_scene_set(&C->scene, sec, key, val, 1, origin, 0, note_diag, &n) != SW_OK) {
        C->available = 0;
        if (!C->note[0])
            snprintf(C->note, sizeof C->note, "%s: rejected", origin);
    }
}

/* The case's scene validated: its model and derived quantities. */
static void check(sw_whatif_case_t *C)
{
    note_t n = {C->note, sizeof C->note};
    if (!C->available)
        return;
    if (sw_scene_validate(&C->scene, &C->derived, C->name, note_diag, &n) != SW_OK) {
        C->available = 0;
        if (!C->note[0])
            snprintf(C->note, sizeof C->note, "invalid scene");
        return;
    }
    C->built = 1;
    C->model = C->derived.model;
}

/* A number as a scene value. */
static const char *num(char *buf, size_t len, double v)
{
    snprintf(buf, len, "%.17g", v);
    return buf;
}

/* The package on a frame (no cushion): the scene's frame with the
 * options' values, or one made of them; omega rad/s, zeta as text. */
static void frame_case(sw_whatif_case_t *C, const sw_scene_t *sc, const sw_whatif_opts_t *o,
                       double omega, const char *zeta)
{
    char mass[32], om[32], z[32];
    C->scene = *sc;
    C->scene.has_cushion = 0;
    C->available = 1;
    const char *fm = o->frame_mass ? o->frame_mass
                     : sc->has_frame
                         ? NULL
                         : num(mass, sizeof mass, SW_WHATIF_FRAME_MASS_RATIO * sc->mass);
    const char *fz = zeta ? zeta : sc->has_frame ? NULL : num(z, sizeof z, SW_WHATIF_ZETA);
    if (omega > 0.0) { /* the case's bearings across the truck too */
        C->scene.frame_lat_stiffness = C->scene.frame_lat_omega = NAN;
        C->scene.frame_lat_k_given = SW_GIVEN_NONE;
    }
    if (zeta) {
        C->scene.frame_lat_damping = C->scene.frame_lat_zeta = NAN;
        C->scene.frame_lat_c_given = SW_GIVEN_NONE;
    }
    if (fm)
        set(C, "frame", "mass", fm, "frame_mass");
    if (omega > 0.0)
        set(C, "frame", "omega", num(om, sizeof om, omega), "frame_omega");
    if (fz)
        set(C, "frame", "zeta", fz, "frame_zeta");
    check(C);
}

/* The package on a cushion: on the bed (a catalogue cushion), or on the
 * scene's support (the caller's). */
static void cushion_case(sw_whatif_case_t *C, const sw_scene_t *sc, int on_bed, double omega,
                         const char *zeta)
{
    char om[32], z[32];
    C->scene = *sc;
    if (on_bed)
        C->scene.has_frame = 0;
    C->available = 1;
    const char *cz = zeta ? zeta : sc->has_cushion ? NULL : num(z, sizeof z, SW_WHATIF_ZETA);
    if (omega > 0.0) { /* the case's cushion across the truck too */
        C->scene.cushion_lat_stiffness = C->scene.cushion_lat_omega = NAN;
        C->scene.cushion_lat_k_given = SW_GIVEN_NONE;
    }
    if (zeta) {
        C->scene.cushion_lat_damping = C->scene.cushion_lat_zeta = NAN;
        C->scene.cushion_lat_c_given = SW_GIVEN_NONE;
    }
    if (omega > 0.0)
        set(C, "cushion", "omega", num(om, sizeof om, omega), "cushion_omega");
    if (cz)
        set(C, "cushion", "zeta", cz, "cushion_zeta");
    check(C);
}

/* The cases of one scene into cs. */
static size_t scene_cases(sw_whatif_case_t *cs, const sw_scene_t *sc, size_t pkg,
                          const sw_whatif_opts_t *o)
{
    size_t m = 0;
    sw_whatif_case_t *C = &cs[m++];
    snprintf(C->name, sizeof C->name, "as given");
    C->scene = *sc;
    C->is_scene = C->available = 1;
    check(C);
    if (o->scenes_only)
        goto done;

    if (sc->has_frame || sc->has_cushion) { /* the package alone on the bed */
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "bed");
        C->scene = *sc;
        C->scene.has_frame = C->scene.has_cushion = 0;
        C->available = 1;
        check(C);
    }
    /* The caller's supports replace the catalogue's of their kind. */
    const int own_frame = o->frame_omega > 0.0 || o->frame_mass || o->frame_zeta;
    const int own_cushion = o->cushion_omega > 0.0 || o->cushion_zeta;
    for (size_t k = 0; k < NSUPPORTS; k++) {
        const sw_support_t *S = &supports[k];
        if (S->cushion ? own_cushion : own_frame)
            continue;
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "%s", S->name);
        C->stands_for = S->stands_for;
        char z[32];
        num(z, sizeof z, S->zeta);
        if (S->cushion)
            cushion_case(C, sc, 1, TWO_PI * S->hz, z);
        else
            frame_case(C, sc, o, TWO_PI * S->hz, z);
    }
    if (own_frame) {
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "frame");
        if (!sc->has_frame && !(o->frame_omega > 0.0))
            snprintf(C->note, sizeof C->note, "no bearing frequency given (frame_omega)");
        else
            frame_case(C, sc, o, o->frame_omega, o->frame_zeta);
    }
    if (own_cushion) {
        C = &cs[m++];
        snprintf(C->name, sizeof C->name, "cushion");
        if (!sc->has_cushion && !(o->cushion_omega > 0.0))
            snprintf(C->note, sizeof C->note, "no cushion frequency given (cushion_omega)");
        else
            cushion_case(C, sc, 0, o->cushion_omega, o->cushion_zeta);
    }
    for (size_t i = 0; i < o->nsizes; i++) {
        C = &cs[m++];
        const double h = o->sizes[2 * i], w = o->sizes[2 * i + 1];
        const double d = o->depths ? o->depths[i] : 0.0; /* m; 0: the scene's */
        if (d > 0.0)
            snprintf(C->name, sizeof C->name, "size %.6gx%.6gx%.6g m", h, w, d);
        else
            snprintf(C->name, sizeof C->name, "size %.6gx%.6g m", h, w);
        C->scene = *sc;
        C->scene.height = h;
        C->scene.width = w;
        if (d > 0.0)
            C->scene.depth = d;
        C->available = 1;
        check(C);
    }
done:
    for (size_t i = 0; i < m; i++) cs[i].pkg = pkg;
    return m;
}

size_t sw_whatif_cases(const sw_scene_t *scenes, size_t n, const sw_whatif_opts_t *o,
                       sw_whatif_case_t *cs)
{
    memset(cs, 0, sw_whatif_max(n, o) * sizeof *cs);
    size_t m = 0;
    for (size_t i = 0; i < n; i++) m += scene_cases(cs + m, &scenes[i], i, o);
    return m;
}

/* ---- the analyses ---------------------------------------------------------------- */

int sw_whatif_safety(sw_whatif_case_t *cs, size_t n, const sw_log_t *log, const sw_safety_opts_t *o)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++) m += cs[i].available != 0;
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
        if (cs[i].available) {
            of[m] = i;
            sc[m++].scene = cs[i].scene;
        }
    const int rc = sw_safety_factors(sc, m, log, o);
    int any = 0; /* a case of its own failed: rc is its status */
    for (size_t k = 0; k < m; k++) any |= sc[k].status != SW_OK;
    for (size_t k = 0; k < m; k++) {
        sw_whatif_case_t *C = &cs[of[k]];
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
    sw_whatif_case_t *cs;
    const size_t *of;
    const sw_log_t *log;
    const sw_reserve_log_opts_t *o;
} reserve_job_t;

void sw_whatif_reserve_case(sw_whatif_case_t *C, const sw_log_t *log,
                            const sw_reserve_log_opts_t *o)
{
    const int rc =
        sw_reserve_log_min(&C->scene, log, o, &C->rl, C->reserve_note, sizeof C->reserve_note);
    C->reserve_status = rc;
    C->has_reserve = rc == SW_OK;
    if (rc != SW_OK && !C->reserve_note[0])
        snprintf(C->reserve_note, sizeof C->reserve_note, "%s", sw_strerror(rc));
}

static void reserve_job(void *user, size_t k)
{
    const reserve_job_t *J = user;
    sw_whatif_reserve_case(&J->cs[J->of[k]], J->log, J->o);
}

int sw_whatif_reserve(sw_whatif_case_t *cs, size_t n, const sw_log_t *log,
                      const sw_reserve_log_opts_t *o, int threads)
{
    size_t *of = calloc(n ? n : 1, sizeof *of), m = 0;
    if (!of)
        return SW_ENOMEM;
    for (size_t i = 0; i < n; i++)
        if (cs[i].available && !cs[i].is_scene)
            of[m++] = i;
    const reserve_job_t J = {.cs = cs, .of = of, .log = log, .o = o};
    sw_parallel_for(m, threads, reserve_job, (void *)&J);
    int rc = SW_OK;
    for (size_t k = 0; k < m; k++)
        if (cs[of[k]].reserve_status == SW_ENOMEM)
            rc = SW_ENOMEM;
    free(of);
    return rc;
}
