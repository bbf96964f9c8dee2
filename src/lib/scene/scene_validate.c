/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scene_validate.c - checking a scene: every value finite, in its range
 * and consistent with the others, with messages that name the key, the
 * line and what was expected; then the derived quantities of physics.md
 * (sizes, frequencies, the frame's and the cushion's springs, the fastest
 * mode an explicit stepper must resolve). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene_int.h"
#include "swaywatch/model.h"
#include "swaywatch/scene.h"
#include "swaywatch/status.h"

/* Limits beyond which a value is a typo rather than a package.  Every
 * physical key has both: a value far below the lower one (a mass of
 * 1e-320 kg, a subnormal number) makes the derived quantities overflow or
 * lose every digit, and the model faults at every sample. */
#define SIZE_MIN 1e-3      /* m */
#define SIZE_MAX_ 100.0    /* m (SIZE_MAX is taken by stdint.h) */
#define MASS_MIN 1e-3      /* kg, of the package and of the frame */
#define MASS_MAX 1e6       /* kg */
#define FRAME_MASS_MAX 1e7 /* kg */
#define G_MIN 1.0          /* m/s^2 */
#define G_MAX 100.0        /* m/s^2 */
#define OMEGA_MIN 1e-2     /* rad/s: a spring with a period over ten minutes */
#define OMEGA_MAX 1e6      /* rad/s */
#define ZETA_MIN 1e-6      /* 1: a damping ratio other than 0 (undamped) */
#define ZETA_MAX 100.0     /* 1 */
#define CUBIC_MIN 1e-3     /* N/m^3: a cubic stiffness other than 0 */
#define PULSE_MIN 1e-3     /* s: a shorter design pulse is a typo for ms */
#define PULSE_MAX 60.0     /* s: longer is a steady acceleration, not a pulse */
#define RESERVE_G_MAX 10.0 /* g: no truck brakes or speeds up harder */
#define MARGIN_MIN 1e-3    /* 1: an alarm level so close to the edge is the edge */
#define RESERVE_G_MIN 1e-3 /* g: a reserve alarm level below any measurable one */

/* Fastest rate (1/s) of a spring-damper mode of frequency w (rad/s) and
 * damping ratio z: w while underdamped; an overdamped mode also has a fast
 * decay, w (z + sqrt(z^2 - 1)), which bounds an explicit stepper's step
 * just as a stiff spring does. */
static double mode_rate(double w, double z)
{
    return z > 1 ? w * (z + sqrt(z * z - 1)) : w;
}
/* ---- validation ---------------------------------------------------------- */

typedef struct {
    const char *origin;
    sw_diag_fn diag;
    void *user;
    int errors;
} vctx;

#define VREPORT(v, line, ...) \
    ((v)->errors++, sw_scene_report((v)->diag, (v)->user, (v)->origin, (line), __VA_ARGS__))

/* "2 m", or "0.1" for a dimensionless value. */
static const char *qty(char *buf, size_t size, double x, const char *unit)
{
    snprintf(buf, size, "%g%s%s", x, *unit ? " " : "", unit);
    return buf;
}

/* Check one given value: finite, > 0 (>= 0 when zero_ok), within [lo, hi]
 * (lo = 0: no lower limit beyond the sign; with zero_ok, 0 itself is
 * allowed below lo).  what says what the key is.  Returns 1 if good. */
static int check_value(vctx *v, int line, const char *key, double x, const char *unit,
                       const char *what, int zero_ok, double lo, double hi)
{
    char a[64], b[64];
    if (isnan(x)) {
        VREPORT(v, line, "%s missing: expected %s%s%s", key, what, *unit ? " in " : "", unit);
        return 0;
    }
    if (!isfinite(x)) {
        VREPORT(v, line, "%s is not finite: expected %s%s%s", key, what, *unit ? " in " : "", unit);
        return 0;
    }
    if (x < 0 || (x == 0 && !zero_ok)) {
        VREPORT(v, line, "%s = %s: expected %s value (%s)", key, qty(a, sizeof a, x, unit),
                zero_ok ? "a non-negative" : "a positive", what);
        return 0;
    }
    if (lo > 0 && x < lo && !(zero_ok && x == 0)) {
        VREPORT(v, line, "%s = %s is too small: expected %sat least %s (%s)", key,
                qty(a, sizeof a, x, unit), zero_ok ? "0 or " : "", qty(b, sizeof b, lo, unit),
                what);
        return 0;
    }
    if (x > hi) {
        VREPORT(v, line, "%s = %s is absurd: expected at most %s (%s)", key,
                qty(a, sizeof a, x, unit), qty(b, sizeof b, hi, unit), what);
        return 0;
    }
    return 1;
}

/* A (stiffness|omega) or (damping|zeta) pair, given in the form `given`.
 * Returns 1 if good (or absent and optional). */
static int check_pair(vctx *v, int line, const char *sec, sw_given given, double dim, double ratio,
                      int dim_key, int ratio_key, int required, int zero_ok, double ratio_min,
                      double ratio_max, const char *dim_what, const char *ratio_what)
{
    char key[48];
    if (given == SW_GIVEN_NONE) {
        if (!required)
            return 1;
        const char *ru = sw_scene_keys[ratio_key].unit;
        VREPORT(v, line, "%s.%s (or %s.%s) missing: expected %s in %s, or %s%s%s", sec,
                sw_scene_keys[dim_key].name, sec, sw_scene_keys[ratio_key].name, dim_what,
                sw_scene_keys[dim_key].unit, ratio_what, *ru ? " in " : "", ru);
        return 0;
    }
    int k = given == SW_GIVEN_RATIO ? ratio_key : dim_key;
    snprintf(key, sizeof key, "%s.%s", sec, sw_scene_keys[k].name);
    return given == SW_GIVEN_RATIO ? check_value(v, line, key, ratio, sw_scene_keys[k].unit,
                                                 ratio_what, zero_ok, ratio_min, ratio_max)
                                   : check_value(v, line, key, dim, sw_scene_keys[k].unit, dim_what,
                                                 zero_ok, 0, INFINITY);
}

/* A spring-damper given either dimensionally (stiffness N/m, damping
 * N*s/m) or as a frequency and damping ratio, on a moving mass mt (kg):
 * both forms out, and a report when the pair is absurd.  sec is the
 * section ("frame", "cushion"), sym the subscript ("b", "c"), what names
 * what decays ("the bearings").  Neither damping given: none. */
typedef struct {
    double k, omega, c, zeta; /* N/m, rad/s, N*s/m, 1 */
} spring_t;

static spring_t spring_of(vctx *v, int line, const char *sec, const char *sym, const char *what,
                          double mt, int k_given, double stiffness, double omega, int c_given,
                          double damping, double zeta)
{
    char a[64];
    spring_t r = {0, 0, 0, 0};
    int bad_zeta = 0;
    if (k_given == SW_GIVEN_RATIO) {
        r.omega = omega;
        r.k = omega * omega * mt;
    } else {
        r.k = stiffness;
        r.omega = sqrt(r.k / mt);
        if (r.omega > OMEGA_MAX)
            VREPORT(v, line,
                    "%s.stiffness = %s gives omega_%s = %g rad/s, which is absurd: expected at "
                    "most %g rad/s",
                    sec, qty(a, sizeof a, r.k, "N/m"), sym, r.omega, OMEGA_MAX);
        else if (r.omega < OMEGA_MIN)
            VREPORT(v, line,
                    "%s.stiffness = %s gives omega_%s = %g rad/s, which is too small: expected "
                    "at least %g rad/s",
                    sec, qty(a, sizeof a, r.k, "N/m"), sym, r.omega, OMEGA_MIN);
    }
    if (c_given == SW_GIVEN_RATIO) {
        r.zeta = zeta;
        r.c = 2 * zeta * r.omega * mt;
    } else if (c_given == SW_GIVEN_DIMENSIONAL) {
        r.c = damping;
        r.zeta = r.c / (2 * r.omega * mt);
        if (r.c != 0 && !(r.zeta >= ZETA_MIN && r.zeta <= ZETA_MAX) && (bad_zeta = 1))
            VREPORT(v, line,
                    "%s.damping = %s gives zeta_%s = %g, which is %s: expected 0 or a damping "
                    "ratio from %g to %g",
                    sec, qty(a, sizeof a, r.c, "N*s/m"), sym, r.zeta,
                    r.zeta < ZETA_MIN ? "too small" : "absurd", ZETA_MIN, ZETA_MAX);
    }
    if (!bad_zeta && r.omega <= OMEGA_MAX && mode_rate(r.omega, r.zeta) > OMEGA_MAX)
        VREPORT(v, line,
                "%s.%s: zeta_%s = %g with omega_%s = %g rad/s makes %s decay at %g 1/s, which "
                "is absurd: expected at most %g 1/s",
                sec, c_given == SW_GIVEN_RATIO ? "zeta" : "damping", sym, r.zeta, sym, r.omega,
                what, mode_rate(r.omega, r.zeta), OMEGA_MAX);
    return r;
}

/* [package]: its size, mass and gravity.  Returns 1 if good. */
static int check_package(vctx *v, const sw_scene_t *sc)
{
    char a[64];
    int lp = sc->line_package;
    int pkg_ok = check_value(v, lp, "package.height", sc->height, "m", "the package height 2h", 0,
                             SIZE_MIN, SIZE_MAX_);
    pkg_ok &= check_value(v, lp, "package.width", sc->width, "m",
                          "the package width 2b along the axis of travel", 0, SIZE_MIN, SIZE_MAX_);
    pkg_ok &= check_value(v, lp, "package.mass", sc->mass, "kg", "the package mass m", 0, MASS_MIN,
                          MASS_MAX);
    if (!isfinite(sc->g) || sc->g < G_MIN || sc->g > G_MAX) {
        VREPORT(v, lp, "package.g = %s: expected gravity between %g and %g m/s^2",
                qty(a, sizeof a, sc->g, "m/s^2"), G_MIN, G_MAX);
        pkg_ok = 0;
    }
    return pkg_ok;
}

/* The frame, once checked: all zero without a [frame] or when a value is
 * bad (reported). */
typedef struct {
    double m_b;   /* kg */
    double gamma; /* m/(m + m_b) */
    spring_t br;  /* the bearings: k_b, omega_b, c_b, zeta_b */
} frame_t;

/* [frame]: its mass and bearings, on a good package (pkg_ok). */
static frame_t check_frame(vctx *v, const sw_scene_t *sc, int pkg_ok)
{
    frame_t f = {0, 0, {0, 0, 0, 0}};
    if (!sc->has_frame)
        return f;
    const double m = sc->mass; /* kg */
    int lf = sc->line_frame;
    int mb_ok = check_value(v, lf, "frame.mass", sc->frame_mass, "kg", "the frame mass m_b", 0,
                            MASS_MIN, FRAME_MASS_MAX);
    int k_ok = check_pair(v, lf, "frame", sc->frame_k_given, sc->frame_stiffness, sc->frame_omega,
                          K_FRAME_STIFFNESS, K_FRAME_OMEGA, 1, 0, OMEGA_MIN, OMEGA_MAX,
                          "the bearing stiffness k_b",
                          "the bearing frequency omega_b = sqrt(k_b/(m+m_b))");
    int c_ok = check_pair(v, lf, "frame", sc->frame_c_given, sc->frame_damping, sc->frame_zeta,
                          K_FRAME_DAMPING, K_FRAME_ZETA, 1, 1, ZETA_MIN, ZETA_MAX,
                          "the bearing damping c_b", "the bearing damping ratio zeta_b");
    if (pkg_ok && mb_ok && k_ok && c_ok) {
        f.m_b = sc->frame_mass;
        const double mt = m + f.m_b; /* kg, package and frame move together */
        f.gamma = m / mt;
        f.br = spring_of(v, lf, "frame", "b", "the bearings", mt, sc->frame_k_given,
                         sc->frame_stiffness, sc->frame_omega, sc->frame_c_given, sc->frame_damping,
                         sc->frame_zeta);
    }
    return f;
}

/* The cushion, once checked: all zero without a [cushion] or when a value
 * is bad (reported). */
typedef struct {
    spring_t s; /* K, omega_c, C, zeta_c */
    double B3;  /* N/m^3 */
} cushion_t;

/* [cushion]: its springs, on a good package (pkg_ok), stiff enough to
 * hold the package upright. */
static cushion_t check_cushion(vctx *v, const sw_scene_t *sc, int pkg_ok)
{
    char a[64], b[64];
    cushion_t cu = {{0, 0, 0, 0}, 0};
    if (!sc->has_cushion)
        return cu;
    const double m = sc->mass;       /* kg */
    const double h = sc->height / 2; /* m */
    const double bb = sc->width / 2; /* m, b */
    const double g = sc->g;          /* m/s^2 */
    int lc = sc->line_cushion;
    int k_ok =
        check_pair(v, lc, "cushion", sc->cushion_k_given, sc->cushion_stiffness, sc->cushion_omega,
                   K_CUSHION_STIFFNESS, K_CUSHION_OMEGA, 1, 0, OMEGA_MIN, OMEGA_MAX,
                   "the total cushion stiffness K", "the cushion frequency omega_c = sqrt(K/m)");
    int c_ok =
        check_pair(v, lc, "cushion", sc->cushion_c_given, sc->cushion_damping, sc->cushion_zeta,
                   K_CUSHION_DAMPING, K_CUSHION_ZETA, 0, 1, ZETA_MIN, ZETA_MAX,
                   "the total cushion damping C", "the cushion damping ratio zeta_c");
    int b_ok = check_value(v, lc, "cushion.cubic", sc->cushion_cubic, "N/m^3",
                           "the total cubic cushion stiffness B3", 1, CUBIC_MIN, INFINITY);
    if (!(pkg_ok && k_ok && c_ok && b_ok))
        return cu;
    const char *kkey =
        sc->cushion_k_given == SW_GIVEN_RATIO ? "cushion.omega" : "cushion.stiffness";
    cu.s = spring_of(v, lc, "cushion", "c", "the cushion", m, sc->cushion_k_given,
                     sc->cushion_stiffness, sc->cushion_omega, sc->cushion_c_given,
                     sc->cushion_damping, sc->cushion_zeta);
    cu.B3 = sc->cushion_cubic;
    /* The cubic term bounded as a spring's frequency is: the cushion's
     * tangent stiffness where the weight alone presses it, K + 3 B3 z^2 at
     * z = m g / K, gives at most OMEGA_MAX. */
    const double zw = m * g / cu.s.k; /* m */
    const double w_t = sqrt((cu.s.k + 3 * cu.B3 * zw * zw) / m);
    if (cu.s.omega <= OMEGA_MAX && w_t > OMEGA_MAX)
        VREPORT(
            v, lc,
            "cushion.cubic = %s makes the cushion's frequency %g rad/s where the weight "
            "presses it (z = m g / K = %g m), which is absurd: expected at most %g rad/s "
            "(B3 at most %s)",
            qty(a, sizeof a, cu.B3, "N/m^3"), w_t, zw, OMEGA_MAX,
            qty(b, sizeof b,
                (m * OMEGA_MAX * OMEGA_MAX - cu.s.k) * cu.s.k * cu.s.k / (3 * (m * g) * (m * g)),
                "N/m^3"));
    /* physics.md, static stability: tilting by a small angle the
     * cushion's restoring moment K b^2/3 per radian must beat the
     * overturning moment m g h of gravity. */
    const double K = cu.s.k;
    const double restoring = K * bb * bb / 3; /* N*m per rad */
    const double toppling = m * g * h;        /* N*m per rad */
    if (restoring <= toppling) {
        const double K_min = 3 * toppling / (bb * bb); /* N/m */
        VREPORT(v, lc,
                "%s: cushion too soft to hold the package upright: K*b^2/3 = %.4g N*m "
                "<= m*g*h = %.4g N*m; expected K above %s (omega_c above %s)",
                kkey, restoring, toppling, qty(a, sizeof a, K_min, "N/m"),
                qty(b, sizeof b, sqrt(K_min / m), "rad/s"));
    }
    return cu;
}

/* [alarm]: both margins are fractions of the way from overturn (0) to
 * rest (1); the critical alarm must fire closer to overturn. */
static void check_margins(vctx *v, const sw_scene_t *sc)
{
    int la = sc->line_alarm;
    int warn_ok =
        isfinite(sc->warn_margin) && sc->warn_margin >= MARGIN_MIN && sc->warn_margin <= 1;
    if (!warn_ok)
        VREPORT(v, la, "alarm.warn_margin = %g: expected a value from %g to 1", sc->warn_margin,
                MARGIN_MIN);
    if (!isfinite(sc->critical_margin) || sc->critical_margin < MARGIN_MIN ||
        sc->critical_margin > 1) {
        VREPORT(v, la,
                "alarm.critical_margin = %g: expected a value from %g to 1, below "
                "alarm.warn_margin",
                sc->critical_margin, MARGIN_MIN);
    } else if (warn_ok && sc->critical_margin >= sc->warn_margin) {
        VREPORT(v, la,
                "alarm.critical_margin = %g is not below alarm.warn_margin = %g: expected "
                "0 < critical_margin < warn_margin <= 1",
                sc->critical_margin, sc->warn_margin);
    }
}

/* [alarm], the reserve (reserve.h): pulse durations and levels in g;
 * the critical level must be the lower reserve. */
static void check_reserve(vctx *v, const sw_scene_t *sc)
{
    int la = sc->line_alarm;
    if (sc->n_design_pulse < 1 || sc->n_design_pulse > SW_DESIGN_PULSES_MAX) {
        VREPORT(v, la, "alarm.design_pulse has %d durations: expected 1 to %d", sc->n_design_pulse,
                SW_DESIGN_PULSES_MAX);
    } else {
        for (int i = 0; i < sc->n_design_pulse; i++) {
            const double T = sc->design_pulse[i]; /* s */
            if (!isfinite(T) || T < PULSE_MIN || T > PULSE_MAX)
                VREPORT(v, la,
                        "alarm.design_pulse item %d = %g s: expected a half-sine duration "
                        "between %g and %g s",
                        i + 1, T, PULSE_MIN, PULSE_MAX);
        }
    }
    int wr_ok = isfinite(sc->warn_reserve_g) && sc->warn_reserve_g >= RESERVE_G_MIN &&
                sc->warn_reserve_g <= RESERVE_G_MAX;
    if (!wr_ok)
        VREPORT(v, la, "alarm.warn_reserve_g = %g: expected a value from %g to %g g",
                sc->warn_reserve_g, RESERVE_G_MIN, RESERVE_G_MAX);
    if (!isfinite(sc->critical_reserve_g) || sc->critical_reserve_g < RESERVE_G_MIN ||
        sc->critical_reserve_g > RESERVE_G_MAX) {
        VREPORT(v, la,
                "alarm.critical_reserve_g = %g: expected a value from %g to %g g, below "
                "alarm.warn_reserve_g",
                sc->critical_reserve_g, RESERVE_G_MIN, RESERVE_G_MAX);
    } else if (wr_ok && sc->critical_reserve_g >= sc->warn_reserve_g) {
        VREPORT(v, la,
                "alarm.critical_reserve_g = %g is not below alarm.warn_reserve_g = %g: "
                "expected 0 < critical_reserve_g < warn_reserve_g",
                sc->critical_reserve_g, sc->warn_reserve_g);
    }
}

/* The lateral plane's scene validated on its own reports its problems
 * with this said first: its width is the depth, its springs the
 * lateral_* ones where given. */
typedef struct {
    vctx *v;
} lat_diag_t;

static void lat_diag(void *user, const char *origin, int line, const char *msg)
{
    vctx *v = ((lat_diag_t *)user)->v;
    VREPORT(v, line,
            "across the truck (package.depth as the width, the lateral_ keys where given): %s",
            msg);
    (void)origin;
}

/* package.depth and the lateral_* keys (physics.md, "The lateral plane"):
 * without a depth none may be given (nothing rocks across the truck to
 * use them); with one, each in its range, and then the lateral plane's
 * scene valid as a scene of its own. */
static void check_lateral(vctx *v, const sw_scene_t *sc, int pkg_ok)
{
    const int lat_frame = sc->frame_lat_k_given || sc->frame_lat_c_given;
    const int lat_cushion =
        sc->cushion_lat_k_given || sc->cushion_lat_c_given || !isnan(sc->cushion_lat_cubic);
    if (isnan(sc->depth)) {
        if (lat_frame || lat_cushion)
            VREPORT(v, lat_frame ? sc->line_frame : sc->line_cushion,
                    "%s.lateral_ keys given without package.depth: expected package.depth in m "
                    "(the size across the truck, over which the lateral plane rocks), or no "
                    "lateral_ keys",
                    lat_frame ? "frame" : "cushion");
        return;
    }
    int ok = check_value(v, sc->line_package, "package.depth", sc->depth, "m",
                         "the package depth 2d across the truck", 0, SIZE_MIN, SIZE_MAX_);
    const int lf = sc->line_frame, lc = sc->line_cushion;
    ok &= check_pair(v, lf, "frame", sc->frame_lat_k_given, sc->frame_lat_stiffness,
                     sc->frame_lat_omega, K_FRAME_LAT_STIFFNESS, K_FRAME_LAT_OMEGA, 0, 0, OMEGA_MIN,
                     OMEGA_MAX, "the bearing stiffness across the truck",
                     "the bearing frequency across the truck");
    ok &= check_pair(v, lf, "frame", sc->frame_lat_c_given, sc->frame_lat_damping,
                     sc->frame_lat_zeta, K_FRAME_LAT_DAMPING, K_FRAME_LAT_ZETA, 0, 1, ZETA_MIN,
                     ZETA_MAX, "the bearing damping across the truck",
                     "the bearing damping ratio across the truck");
    ok &= check_pair(v, lc, "cushion", sc->cushion_lat_k_given, sc->cushion_lat_stiffness,
                     sc->cushion_lat_omega, K_CUSHION_LAT_STIFFNESS, K_CUSHION_LAT_OMEGA, 0, 0,
                     OMEGA_MIN, OMEGA_MAX, "the total cushion stiffness across the truck",
                     "the cushion frequency across the truck");
    ok &= check_pair(v, lc, "cushion", sc->cushion_lat_c_given, sc->cushion_lat_damping,
                     sc->cushion_lat_zeta, K_CUSHION_LAT_DAMPING, K_CUSHION_LAT_ZETA, 0, 1,
                     ZETA_MIN, ZETA_MAX, "the total cushion damping across the truck",
                     "the cushion damping ratio across the truck");
    if (!isnan(sc->cushion_lat_cubic))
        ok &= check_value(v, lc, "cushion.lateral_cubic", sc->cushion_lat_cubic, "N/m^3",
                          "the total cubic cushion stiffness across the truck", 1, CUBIC_MIN,
                          INFINITY);
    if (!ok || !pkg_ok || v->errors)
        return; /* its problems said once, along the truck */
    /* the rest, as any scene's (the springs against the masses, a cushion
     * stiff enough to hold the package upright over its depth) */
    sw_scene_t lat;
    sw_scene_lateral(sc, &lat);
    lat_diag_t ld = {v};
    vctx lv = {v->origin, lat_diag, &ld, 0};
    (void)check_frame(&lv, &lat, 1);
    (void)check_cushion(&lv, &lat, 1);
}

/* The derived quantities of a valid scene: physics.md, "Package, vehicle,
 * conventions" and the scene sections. */
static void derive(const sw_scene_t *sc, const frame_t *f, const cushion_t *cu, sw_derived_t *d)
{
    const double m = sc->mass;       /* kg */
    const double h = sc->height / 2; /* m */
    const double bb = sc->width / 2; /* m, b */
    const double g = sc->g;          /* m/s^2 */
    const double gamma = f->gamma;
    d->model = sc->has_cushion ? SW_MODEL_CUSHION : sc->has_frame ? SW_MODEL_FRAME : SW_MODEL_BARE;
    d->h = h;
    d->b = bb;
    d->R = hypot(h, bb);
    d->alpha = atan2(bb, h);
    d->p = sqrt(3 * g / (4 * d->R));
    d->I_C = m * d->R * d->R / 3;
    d->I_O = 4.0 / 3.0 * m * d->R * d->R;
    const double s = sin(d->alpha), co = cos(d->alpha);
    d->eta = 1 - 1.5 * s * s;
    d->gamma = gamma;
    d->k_b = f->br.k;
    d->c_b = f->br.c;
    d->omega_b = f->br.omega;
    d->zeta_b = f->br.zeta;
    /* With gamma = 0 this is eta: a package on the bed. */
    d->r_frame = 1 - 6 * s * s / (4 - 3 * gamma * co * co);
    d->K = cu->s.k;
    d->C = cu->s.c;
    d->B3 = cu->B3;
    d->omega_c = cu->s.omega;
    d->zeta_c = cu->s.zeta;

    /* The fastest natural frequency bounds an explicit stepper's step.  The
     * coupled frame frequency lies below omega_b / sqrt(1 - 3 gamma/4): the
     * package's inertia seen by the frame is at most reduced by the factor
     * D = 1 - (3/4) gamma cos^2 of physics.md.  Overdamped modes count with
     * their fast decay rate (mode_rate). */
    double w = 0; /* rad/s */
    if (sc->has_frame)
        w = mode_rate(f->br.omega, f->br.zeta) / sqrt(1 - 0.75 * gamma);
    /* The cushion's vertical and rocking modes, damping included (an
     * overdamped mode's fast real root exceeds omega_c: 3.7 omega_c at
     * zeta_c = 2), the rocking mode coupled to the frame if there is one. */
    if (sc->has_cushion)
        w = fmax(w, sw_cushion_omega_max(d, g));
    d->omega_max = w;
}

int sw_scene_validate(const sw_scene_t *sc, sw_derived_t *d, const char *origin, sw_diag_fn diag,
                      void *user)
{
    if (d)
        memset(d, 0, sizeof *d);
    vctx v = {origin ? origin : "", diag, user, 0};
    if (!sc) {
        VREPORT(&v, 0, "internal: sw_scene_validate called without a scene");
        return SW_EINVAL;
    }
    /* The sections in this order: the messages come in it. */
    const int pkg_ok = check_package(&v, sc);
    const frame_t f = check_frame(&v, sc, pkg_ok);
    const cushion_t cu = check_cushion(&v, sc, pkg_ok);
    check_margins(&v, sc);
    check_reserve(&v, sc);
    check_lateral(&v, sc, pkg_ok);
    if (v.errors)
        return SW_EINVAL;
    if (!d)
        return SW_OK;
    derive(sc, &f, &cu, d);
    return SW_OK;
}
