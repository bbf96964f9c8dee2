/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scene_int.h - what the scene's files share (scene.h is the API): the
 * keys a scene file knows, their sections and units (scene.c), looked up
 * by the file parser (scene_parse.c) and named in the messages of
 * validation (scene_validate.c), and the diagnostics callback's wrapper. */
#ifndef SWAYWATCH_SCENE_INT_H
#define SWAYWATCH_SCENE_INT_H

#include "swaywatch/scene.h"

#if defined(__GNUC__)
#define SW_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define SW_PRINTF(f, a)
#endif

/* ---- the keys a scene file knows ---------------------------------------- */

enum { SEC_PACKAGE, SEC_FRAME, SEC_CUSHION, SEC_ALARM, SEC_COUNT };
/* Pseudo-sections while parsing: before the first header, and after a bad
 * header (its keys are skipped; the header was reported already). */
enum { SEC_NONE = -1, SEC_SKIP = -2 };

enum key_id {
    K_NAME,
    K_HEIGHT,
    K_WIDTH,
    K_MASS,
    K_G,
    K_DEPTH,
    K_FRAME_MASS,
    K_FRAME_STIFFNESS,
    K_FRAME_OMEGA,
    K_FRAME_DAMPING,
    K_FRAME_ZETA,
    K_FRAME_LAT_STIFFNESS,
    K_FRAME_LAT_OMEGA,
    K_FRAME_LAT_DAMPING,
    K_FRAME_LAT_ZETA,
    K_CUSHION_STIFFNESS,
    K_CUSHION_OMEGA,
    K_CUSHION_DAMPING,
    K_CUSHION_ZETA,
    K_CUSHION_CUBIC,
    K_CUSHION_LAT_STIFFNESS,
    K_CUSHION_LAT_OMEGA,
    K_CUSHION_LAT_DAMPING,
    K_CUSHION_LAT_ZETA,
    K_CUSHION_LAT_CUBIC,
    K_WARN,
    K_CRITICAL,
    K_DESIGN_PULSE,
    K_WARN_RESERVE,
    K_CRITICAL_RESERVE,
    K_COUNT
};

typedef struct {
    int section;
    const char *name;
    int partner;      /* the other form of a pair, or -1 */
    const char *unit; /* "" for dimensionless */
} key_info;

extern const char *const sw_scene_section_names[SEC_COUNT];
extern const key_info sw_scene_keys[K_COUNT];

/* The section named name (SEC_*), or -1. */
int sw_scene_find_section(const char *name);
/* The key name of section (K_*), or -1. */
int sw_scene_find_key(int section, const char *name);

/* A printf-style message to diag (NULL: none), with its origin and line. */
void sw_scene_report(sw_diag_fn diag, void *user, const char *origin, int line, const char *fmt,
                     ...) SW_PRINTF(5, 6);

#endif
