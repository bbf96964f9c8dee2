/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scene.h - what stands on the truck: a package, optionally on a support
 * frame with viscoelastic bearings, optionally on a Winkler cushion.
 *
 * A scene is plain data.  It is filled key by key (from an INI file, from
 * "--set section.key=value" overrides, or from code), then validated, which
 * also derives the dimensionless groups of physics.md.  The scene decides
 * the model: no frame and no cushion -> "bare" (1 DOF), a frame -> "frame"
 * (2 DOF), a cushion -> "cushion" (3 DOF, 2 DOF without a frame).
 *
 * The library does no I/O: sw_scene_parse() takes the text of a file and a
 * name to quote in messages; the caller reads the file. */
#ifndef SWAYWATCH_SCENE_H
#define SWAYWATCH_SCENE_H

#include <stddef.h>

#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SW_NAME_MAX 64
#define SW_DESIGN_PULSES_MAX 8             /* design pulse durations a scene may list */
#define SW_DESIGN_PULSE_DEFAULT 1.0        /* s, docs/reserve.md says why */
#define SW_WARN_RESERVE_G_DEFAULT 0.20     /* g, docs/alarms.md says why */
#define SW_CRITICAL_RESERVE_G_DEFAULT 0.10 /* g */

typedef enum { SW_MODEL_BARE = 0, SW_MODEL_FRAME = 1, SW_MODEL_CUSHION = 2 } sw_model_kind;

/* How one of the (stiffness|omega) or (damping|zeta) pairs was given. */
typedef enum { SW_GIVEN_NONE = 0, SW_GIVEN_DIMENSIONAL = 1, SW_GIVEN_RATIO = 2 } sw_given;

/* A number that was not given is NAN (sw_scene_init); a given one is always
 * finite.  Of each (stiffness|omega) and (damping|zeta) pair only the form
 * recorded in *_given holds a value, the other form is NAN. */
typedef struct {
    /* [package] */
    char name[SW_NAME_MAX]; /* used in messages and reports */
    double height;          /* m, 2h */
    double width;           /* m, 2b, along the axis of travel */
    double mass;            /* kg, m */
    double g;               /* m/s^2, gravity (default 9.81) */
    double depth;           /* m, 2d, across the truck (the lateral plane rocks over it);
                               NAN: not given, one plane (along the truck) */

    /* [frame] (optional) */
    int has_frame;
    double frame_mass;      /* kg, m_b */
    double frame_stiffness; /* N/m, k_b   (if given as such) */
    double frame_omega;     /* rad/s, w_b (if given as such) */
    double frame_damping;   /* N s/m, c_b (if given as such) */
    double frame_zeta;      /* 1, zeta_b  (if given as such) */
    sw_given frame_k_given, frame_c_given;
    /* the bearings across the truck (lateral_*): NAN and SW_GIVEN_NONE where
     * not given, and then the ones along it apply (sw_scene_lateral) */
    double frame_lat_stiffness, frame_lat_omega; /* N/m, rad/s */
    double frame_lat_damping, frame_lat_zeta;    /* N s/m, 1 */
    sw_given frame_lat_k_given, frame_lat_c_given;

    /* [cushion] (optional) */
    int has_cushion;
    double cushion_stiffness; /* N/m, total K */
    double cushion_omega;     /* rad/s, w_c = sqrt(K/m) */
    double cushion_damping;   /* N s/m, total C */
    double cushion_zeta;      /* 1, zeta_c = C/(2 m w_c) */
    double cushion_cubic;     /* N/m^3, total B3 */
    sw_given cushion_k_given, cushion_c_given;
    /* the cushion across the truck (lateral_*), as the frame's */
    double cushion_lat_stiffness, cushion_lat_omega; /* N/m, rad/s */
    double cushion_lat_damping, cushion_lat_zeta;    /* N s/m, 1 */
    double cushion_lat_cubic;                        /* N/m^3; NAN: cushion_cubic */
    sw_given cushion_lat_k_given, cushion_lat_c_given;

    /* [alarm] */
    double warn_margin;     /* 1, default 0.5 */
    double critical_margin; /* 1, default 0.2 */
    /* design_pulse = T[, T2 ...]: half-sine pulses of these durations (s)
     * define the reserve (reserve.h); default one of SW_DESIGN_PULSE_DEFAULT */
    double design_pulse[SW_DESIGN_PULSES_MAX];
    int n_design_pulse;
    double warn_reserve_g;     /* g (SW_G0), default SW_WARN_RESERVE_G_DEFAULT */
    double critical_reserve_g; /* g, default SW_CRITICAL_RESERVE_G_DEFAULT */

    /* where each section started, for messages (0 = not from a file) */
    int line_package, line_frame, line_cushion, line_alarm;
} sw_scene_t;

/* Quantities derived by sw_scene_validate(); all SI. */
typedef struct {
    sw_model_kind model;
    double h, b;      /* m, half height and half width */
    double R;         /* m, sqrt(h^2 + b^2) */
    double alpha;     /* rad, atan(b/h) */
    double p;         /* rad/s, sqrt(3 g / (4 R)) */
    double I_C, I_O;  /* kg m^2, about the centre of mass and a base corner */
    double eta;       /* 1, bare impact ratio 1 - 1.5 sin^2(alpha) */
    double gamma;     /* 1, m/(m+m_b) (0 without a frame) */
    double k_b, c_b;  /* N/m, N s/m */
    double omega_b;   /* rad/s, sqrt(k_b/(m+m_b)) */
    double zeta_b;    /* 1 */
    double r_frame;   /* 1, frame impact ratio 1 - 6 sin^2(a)/(4 - 3 g cos^2(a)) */
    double K, C, B3;  /* N/m, N s/m, N/m^3 cushion totals */
    double omega_c;   /* rad/s, sqrt(K/m) */
    double zeta_c;    /* 1, C/(2 m omega_c) */
    double omega_max; /* rad/s, the scene's fastest natural frequency */
} sw_derived_t;

/* Receives one diagnostic: origin (file name or "--set"), 1-based line (0 if
 * none), and a message naming the key and what was expected. */
typedef void (*sw_diag_fn)(void *user, const char *origin, int line, const char *msg);

/* Fill sc with defaults: no sizes (they are required; NAN), g = 9.81, alarm
 * thresholds 0.5 and 0.2, one design pulse of SW_DESIGN_PULSE_DEFAULT s,
 * reserve alarms at SW_WARN_RESERVE_G_DEFAULT and
 * SW_CRITICAL_RESERVE_G_DEFAULT g, no frame, no cushion (cubic term 0). */
SW_API void sw_scene_init(sw_scene_t *sc);

/* Set one key, e.g. section "frame", key "zeta", value "0.1".  The one
 * list, alarm.design_pulse, takes 1 to SW_DESIGN_PULSES_MAX numbers
 * separated by commas, and replaces the whole list.  When override
 * is non-zero (the --set path) giving one form of a pair replaces the other
 * form; otherwise giving both forms of a pair is an error.  Setting any frame
 * (cushion) key sets has_frame (has_cushion).  Numbers are decimal, finite,
 * with nothing but white space after them (no "nan", "inf", hex floats).
 * Ranges are checked later, by sw_scene_validate(), so that an override can
 * still correct a value.  Errors go to diag (may be NULL).  Returns SW_OK,
 * SW_ENOTFOUND (unknown section or key) or SW_EINVAL (value not a finite
 * number, bad name, or both forms of a pair). */
SW_API int sw_scene_set(sw_scene_t *sc, const char *section, const char *key, const char *value,
                        int override, const char *origin, int line, sw_diag_fn diag, void *user);

/* Apply "section.key=value" as an override (origin "--set", line 0).
 * Returns SW_EINVAL for an assignment of another shape, else as
 * sw_scene_set(). */
SW_API int sw_scene_set_arg(sw_scene_t *sc, const char *assignment, sw_diag_fn diag, void *user);

/* Parse INI text (a whole scene file) into sc, which should come from
 * sw_scene_init().  Lines whose first non-blank character is '#' or ';' are
 * comments, and so is the rest of a line from a '#' or ';' that follows white
 * space.  Unknown sections and keys, duplicate sections and keys, both forms
 * of a pair and malformed lines are errors.  A section header alone sets
 * has_frame / has_cushion (so "[frame]" without keys is reported as missing
 * keys by validation).  Every bad line is reported, with its line number;
 * returns SW_OK or the first error code.  Does not validate: call
 * sw_scene_validate() afterwards (after any overrides). */
SW_API int sw_scene_parse(sw_scene_t *sc, const char *text, const char *origin, sw_diag_fn diag,
                          void *user);

/* Check required keys and ranges, derive d (may be NULL).  Every problem is
 * reported, with the line of the section it belongs to (0 if none); returns
 * SW_OK or SW_EINVAL.  d is filled only on SW_OK (zeroed otherwise). */
SW_API int sw_scene_validate(const sw_scene_t *sc, sw_derived_t *d, const char *origin,
                             sw_diag_fn diag, void *user);

/* The scene of the lateral plane (physics.md, "The lateral plane"): the
 * same package rocking over its depth, with width = depth and the frame's
 * and the cushion's lateral_* values where given (their values along the
 * truck where not); it has no depth of its own.  Returns SW_OK, or
 * SW_ENOTFOUND (lat untouched) when sc gives no depth. */
SW_API int sw_scene_lateral(const sw_scene_t *sc, sw_scene_t *lat);

/* Non-zero if the scene gives a depth: it rocks in a lateral plane too
 * when the input has a lateral acceleration. */
SW_API int sw_scene_has_depth(const sw_scene_t *sc);

/* "bare", "frame" or "cushion" ("unknown" for any other value). */
SW_API const char *sw_model_name(sw_model_kind k);

/* Non-zero if a and b hold the same values (numbers not given compare
 * equal); the line numbers of the sections, where they were in a file, do
 * not count.  A reload uses it to tell a changed scene from an unchanged
 * one. */
SW_API int sw_scene_equal(const sw_scene_t *a, const sw_scene_t *b);

#ifdef __cplusplus
}
#endif
#endif
