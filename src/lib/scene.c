/* scene.c - what stands on the truck: filling a scene key by key, parsing a
 * scene file (INI, through inih), "--set section.key=value" overrides,
 * validation with messages that name the key, the line and what was
 * expected, and the derived quantities of physics.md.
 *
 * No I/O and no global mutable state: the caller hands in the text of the
 * file and a callback for diagnostics. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The packaged libinih is built with INI_HANDLER_LINENO = 0, so the handler
 * cannot be told the line number (defining the macro here would only make
 * our handler's type disagree with how the library calls it).  Line numbers
 * come from our own reader instead, see scene_reader(). */
#include <ini.h>

#include "swaywatch/model.h"
#include "swaywatch/scene.h"
#include "swaywatch/status.h"

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

static const char *const section_names[SEC_COUNT] = {"package", "frame", "cushion", "alarm"};
static const char *const section_keys[SEC_COUNT] = {
    "name, height, width, mass, g",
    "mass, stiffness or omega, damping or zeta",
    "stiffness or omega, damping or zeta, cubic",
    "warn_margin, critical_margin, design_pulse, warn_reserve_g, critical_reserve_g",
};

enum key_id {
    K_NAME,
    K_HEIGHT,
    K_WIDTH,
    K_MASS,
    K_G,
    K_FRAME_MASS,
    K_FRAME_STIFFNESS,
    K_FRAME_OMEGA,
    K_FRAME_DAMPING,
    K_FRAME_ZETA,
    K_CUSHION_STIFFNESS,
    K_CUSHION_OMEGA,
    K_CUSHION_DAMPING,
    K_CUSHION_ZETA,
    K_CUSHION_CUBIC,
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

static const key_info keys[K_COUNT] = {
    [K_NAME] = {SEC_PACKAGE, "name", -1, ""},
    [K_HEIGHT] = {SEC_PACKAGE, "height", -1, "m"},
    [K_WIDTH] = {SEC_PACKAGE, "width", -1, "m"},
    [K_MASS] = {SEC_PACKAGE, "mass", -1, "kg"},
    [K_G] = {SEC_PACKAGE, "g", -1, "m/s^2"},
    [K_FRAME_MASS] = {SEC_FRAME, "mass", -1, "kg"},
    [K_FRAME_STIFFNESS] = {SEC_FRAME, "stiffness", K_FRAME_OMEGA, "N/m"},
    [K_FRAME_OMEGA] = {SEC_FRAME, "omega", K_FRAME_STIFFNESS, "rad/s"},
    [K_FRAME_DAMPING] = {SEC_FRAME, "damping", K_FRAME_ZETA, "N*s/m"},
    [K_FRAME_ZETA] = {SEC_FRAME, "zeta", K_FRAME_DAMPING, ""},
    [K_CUSHION_STIFFNESS] = {SEC_CUSHION, "stiffness", K_CUSHION_OMEGA, "N/m"},
    [K_CUSHION_OMEGA] = {SEC_CUSHION, "omega", K_CUSHION_STIFFNESS, "rad/s"},
    [K_CUSHION_DAMPING] = {SEC_CUSHION, "damping", K_CUSHION_ZETA, "N*s/m"},
    [K_CUSHION_ZETA] = {SEC_CUSHION, "zeta", K_CUSHION_DAMPING, ""},
    [K_CUSHION_CUBIC] = {SEC_CUSHION, "cubic", -1, "N/m^3"},
    [K_WARN] = {SEC_ALARM, "warn_margin", -1, ""},
    [K_CRITICAL] = {SEC_ALARM, "critical_margin", -1, ""},
    [K_DESIGN_PULSE] = {SEC_ALARM, "design_pulse", -1, "s"},
    [K_WARN_RESERVE] = {SEC_ALARM, "warn_reserve_g", -1, "g"},
    [K_CRITICAL_RESERVE] = {SEC_ALARM, "critical_reserve_g", -1, "g"},
};

/* Limits beyond which a value is a typo rather than a package. */
#define SIZE_MIN 1e-3      /* m */
#define SIZE_MAX_ 100.0    /* m (SIZE_MAX is taken by stdint.h) */
#define MASS_MAX 1e6       /* kg */
#define FRAME_MASS_MAX 1e7 /* kg */
#define G_MIN 1.0          /* m/s^2 */
#define G_MAX 100.0        /* m/s^2 */
#define OMEGA_MAX 1e6      /* rad/s */
#define PULSE_MIN 1e-3     /* s: a shorter design pulse is a typo for ms */
#define PULSE_MAX 60.0     /* s: longer is a steady acceleration, not a pulse */
#define RESERVE_G_MAX 10.0 /* g: no truck brakes or speeds up harder */

/* Fastest rate (1/s) of a spring-damper mode of frequency w (rad/s) and
 * damping ratio z: w while underdamped; an overdamped mode also has a fast
 * decay, w (z + sqrt(z^2 - 1)), which bounds an explicit stepper's step
 * just as a stiff spring does. */
static double mode_rate(double w, double z)
{
    return z > 1 ? w * (z + sqrt(z * z - 1)) : w;
}

static int find_section(const char *name)
{
    for (int s = 0; s < SEC_COUNT; s++)
        if (!strcmp(name, section_names[s]))
            return s;
    return -1;
}

static int find_key(int section, const char *name)
{
    for (int k = 0; k < K_COUNT; k++)
        if (keys[k].section == section && !strcmp(name, keys[k].name))
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
        case K_FRAME_MASS: return &sc->frame_mass;
        case K_FRAME_STIFFNESS: return &sc->frame_stiffness;
        case K_FRAME_OMEGA: return &sc->frame_omega;
        case K_FRAME_DAMPING: return &sc->frame_damping;
        case K_FRAME_ZETA: return &sc->frame_zeta;
        case K_CUSHION_STIFFNESS: return &sc->cushion_stiffness;
        case K_CUSHION_OMEGA: return &sc->cushion_omega;
        case K_CUSHION_DAMPING: return &sc->cushion_damping;
        case K_CUSHION_ZETA: return &sc->cushion_zeta;
        case K_CUSHION_CUBIC: return &sc->cushion_cubic;
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
        default: return NULL;
    }
}

static sw_given key_form(int k)
{
    return (k == K_FRAME_OMEGA || k == K_FRAME_ZETA || k == K_CUSHION_OMEGA || k == K_CUSHION_ZETA)
               ? SW_GIVEN_RATIO
               : SW_GIVEN_DIMENSIONAL;
}

/* ---- diagnostics --------------------------------------------------------- */

static void report(sw_diag_fn diag, void *user, const char *origin, int line, const char *fmt, ...)
    SW_PRINTF(5, 6);

static void report(sw_diag_fn diag, void *user, const char *origin, int line, const char *fmt, ...)
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
        report(diag, user, origin, line, "package.name is empty: expected a name for messages");
        return SW_EINVAL;
    }
    if (n > SW_NAME_MAX - 1) {
        report(diag, user, origin, line,
               "package.name is %zu characters long: expected at most %d characters", n,
               SW_NAME_MAX - 1);
        return SW_EINVAL;
    }
    for (size_t i = 0; i < n; i++) {
        /* Bytes >= 0x80 are let through so that UTF-8 names work; control
         * characters would garble messages and reports. */
        unsigned char ch = (unsigned char)s[i];
        if (ch < 0x20 || ch == 0x7f) {
            report(diag, user, origin, line,
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
            report(diag, user, origin, line,
                   "alarm.design_pulse = \"%.40s\": more than %d durations, expected at most %d",
                   value, SW_DESIGN_PULSES_MAX, SW_DESIGN_PULSES_MAX);
            return SW_EINVAL;
        }
        if (len >= sizeof item) {
            report(diag, user, origin, line,
                   "alarm.design_pulse = \"%.40s\": item %d is too long, expected a duration "
                   "in s",
                   value, n + 1);
            return SW_EINVAL;
        }
        memcpy(item, p, len);
        item[len] = '\0';
        const char *why = parse_number(item, &v[n]);
        if (why) {
            report(diag, user, origin, line,
                   "alarm.design_pulse = \"%.40s\": item %d: %s, expected durations in s "
                   "separated by commas",
                   value, n + 1, why);
            return SW_EINVAL;
        }
        n++;
        if (p[len] != ',') break;
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
        report(diag, user, origin, line, "internal: sw_scene_set called without a %s",
               !sc        ? "scene"
               : !section ? "section"
               : !key     ? "key"
                          : "value");
        return SW_EINVAL;
    }
    int s = find_section(section);
    if (s < 0) {
        report(diag, user, origin, line,
               "unknown section [%.40s]: expected package, frame, cushion or alarm", section);
        return SW_ENOTFOUND;
    }
    int k = find_key(s, key);
    if (k < 0) {
        report(diag, user, origin, line, "unknown key %s.%.40s: expected one of %s", section, key,
               section_keys[s]);
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
            report(diag, user, origin, line, "%s.%s = \"%.40s\": %s, expected a finite number%s%s",
                   section, key, value, why, *keys[k].unit ? " in " : "", keys[k].unit);
            return SW_EINVAL;
        }
        sw_given *given = key_given(sc, k);
        if (given && *given != SW_GIVEN_NONE && *given != key_form(k)) {
            int other = keys[k].partner;
            if (!override) {
                report(diag, user, origin, line,
                       "%s.%s and %s.%s both given: expected one of the two, not both", section,
                       key, section, keys[other].name);
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
        report(diag, user, origin, 0, "internal: sw_scene_set_arg called without %s",
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
        report(diag, user, origin, 0, "\"%.60s\": expected section.key=value, e.g. frame.zeta=0.1",
               assignment);
        return SW_EINVAL;
    }
    return sw_scene_set(sc, section, key, eq + 1, 1, origin, 0, diag, user);
}

/* ---- parsing a file ------------------------------------------------------ */

typedef struct {
    sw_scene_t *sc;
    const char *origin;
    sw_diag_fn diag;
    void *user;
    const char *pos; /* next unread character of the text */
    int lineno;      /* 1-based number of the line last handed to inih */
    int section;     /* SEC_*, SEC_NONE or SEC_SKIP */
    int section_line[SEC_COUNT];
    int key_line[K_COUNT];
    int rc; /* first error, SW_OK if none */
} parse_ctx;

static void fail(parse_ctx *c, int code)
{
    if (c->rc == SW_OK)
        c->rc = code;
}

/* A section header, already stripped to "[...]".  Returns the text to hand
 * to inih. */
static const char *section_header(parse_ctx *c, const char *a, size_t n)
{
    const char *in = a + 1, *end = a + n - 1; /* between the brackets */
    while (in < end && isspace((unsigned char)*in)) in++;
    while (end > in && isspace((unsigned char)end[-1])) end--;
    char name[32];
    size_t len = (size_t)(end - in);
    if (len >= sizeof name)
        len = sizeof name - 1; /* unknown anyway */
    memcpy(name, in, len);
    name[len] = '\0';

    int s = find_section(name);
    c->section = SEC_SKIP;
    if (s < 0) {
        report(c->diag, c->user, c->origin, c->lineno,
               "unknown section [%s]: expected [package], [frame], [cushion] or [alarm]", name);
        fail(c, SW_ENOTFOUND);
        return "";
    }
    if (c->section_line[s]) {
        report(c->diag, c->user, c->origin, c->lineno,
               "section [%s] given twice (first at line %d): expected each section once, "
               "one package per file",
               name, c->section_line[s]);
        fail(c, SW_EINVAL);
        return "";
    }
    c->section = s;
    c->section_line[s] = c->lineno;
    switch (s) {
        case SEC_PACKAGE: c->sc->line_package = c->lineno; break;
        case SEC_FRAME:
            c->sc->line_frame = c->lineno;
            c->sc->has_frame = 1;
            break;
        case SEC_CUSHION:
            c->sc->line_cushion = c->lineno;
            c->sc->has_cushion = 1;
            break;
        default: c->sc->line_alarm = c->lineno; break;
    }
    return section_names[s];
}

/* inih's line reader, fed from the text.  It does three things inih cannot
 * do for us as packaged:
 *  - it counts lines, so the handler knows which line it is called for
 *    (inih calls the handler for a line before it reads the next one);
 *  - it strips comments: the packaged inih strips inline comments only
 *    after ';' (INI_INLINE_COMMENT_PREFIXES is ";"), while scene files use
 *    "height = 2.0   # m".  Changing ini_inline_comment_prefixes would
 *    change a global of a shared library for every user of it, so a '#' or
 *    ';' at the start of a line or after white space starts a comment here;
 *  - it rejects what inih would accept silently or report only as "the
 *    first bad line": lines without '=', broken section headers, lines too
 *    long for inih's buffer (it would truncate them), and leading white
 *    space, which inih would take as the continuation of the previous
 *    value (INI_ALLOW_MULTILINE) - here it is just indentation.
 * Bad lines are reported and handed to inih as empty lines. */
static char *scene_reader(char *str, int num, void *stream)
{
    parse_ctx *c = stream;
    if (*c->pos == '\0')
        return NULL;
    const char *a = c->pos;
    size_t n = strcspn(a, "\n");
    c->pos = a + n + (a[n] == '\n');
    c->lineno++;

    /* A UTF-8 byte order mark, as some editors write. */
    if (c->lineno == 1 && n >= 3 && !memcmp(a, "\xEF\xBB\xBF", 3)) {
        a += 3;
        n -= 3;
    }
    while (n > 0 && isspace((unsigned char)*a)) a++, n--;
    for (size_t i = 0; i < n; i++) {
        if ((a[i] == '#' || a[i] == ';') && (i == 0 || isspace((unsigned char)a[i - 1]))) {
            n = i;
            break;
        }
    }
    while (n > 0 && isspace((unsigned char)a[n - 1])) n--;

    str[0] = '\0';
    if (n == 0)
        return str;

    if (a[0] == '[') {
        if (a[n - 1] != ']') {
            report(c->diag, c->user, c->origin, c->lineno,
                   memchr(a, ']', n) ? "unexpected text after the section header: expected "
                                       "[section] alone on its line"
                                     : "section header without its closing ']'");
            fail(c, SW_EPARSE);
            c->section = SEC_SKIP;
            return str;
        }
        const char *name = section_header(c, a, n);
        if (*name)
            snprintf(str, (size_t)num, "[%s]\n", name);
        return str;
    }

    size_t sep = strcspn(a, "=:");
    if (sep >= n) {
        /* Quote this line only: a runs on into the rest of the text. */
        report(c->diag, c->user, c->origin, c->lineno,
               "\"%.*s\": expected key = value, a [section] header or a comment",
               (int)(n < 40 ? n : 40), a);
        fail(c, SW_EPARSE);
        return str;
    }
    size_t keylen = sep;
    while (keylen > 0 && isspace((unsigned char)a[keylen - 1])) keylen--;
    if (keylen == 0) {
        report(c->diag, c->user, c->origin, c->lineno, "missing key before '%c'", a[sep]);
        fail(c, SW_EPARSE);
        return str;
    }
    /* inih needs room for the text, a newline and the terminator. */
    if (num < 2 || n > (size_t)num - 2) {
        report(c->diag, c->user, c->origin, c->lineno,
               "line too long: expected at most %d characters before any comment", num - 2);
        fail(c, SW_EPARSE);
        return str;
    }
    memcpy(str, a, n);
    str[n] = '\n';
    str[n + 1] = '\0';
    return str;
}

static int scene_handler(void *user, const char *section, const char *name, const char *value)
{
    parse_ctx *c = user;
    (void)section; /* c->section is the same, already checked */
    int line = c->lineno;
    if (c->section == SEC_SKIP)
        return 1; /* its header was reported */
    if (c->section == SEC_NONE) {
        report(c->diag, c->user, c->origin, line,
               "key \"%.40s\" outside any section: expected a [package], [frame], [cushion] "
               "or [alarm] header before it",
               name);
        fail(c, SW_EPARSE);
        return 1;
    }
    const char *sec = section_names[c->section];
    int k = find_key(c->section, name);
    if (k >= 0 && c->key_line[k]) {
        report(c->diag, c->user, c->origin, line,
               "%s.%s given twice (first at line %d): expected each key once", sec, name,
               c->key_line[k]);
        fail(c, SW_EINVAL);
        return 1;
    }
    if (k >= 0 && keys[k].partner >= 0 && c->key_line[keys[k].partner]) {
        int other = keys[k].partner;
        report(c->diag, c->user, c->origin, line,
               "%s.%s (line %d) and %s.%s (line %d) both given: expected one of the two, not "
               "both",
               sec, keys[other].name, c->key_line[other], sec, name, line);
        c->key_line[k] = line;
        fail(c, SW_EINVAL);
        return 1;
    }
    if (k >= 0)
        c->key_line[k] = line;
    /* Unknown keys are reported by sw_scene_set, as for --set. */
    int rc = sw_scene_set(c->sc, sec, name, value, 0, c->origin, line, c->diag, c->user);
    if (rc != SW_OK)
        fail(c, rc);
    return 1;
}

int sw_scene_parse(sw_scene_t *sc, const char *text, const char *origin, sw_diag_fn diag,
                   void *user)
{
    if (!sc || !text) {
        report(diag, user, origin, 0, "internal: sw_scene_parse called without %s",
               !sc ? "a scene" : "text");
        return SW_EINVAL;
    }
    parse_ctx c;
    memset(&c, 0, sizeof c);
    c.sc = sc;
    c.origin = origin ? origin : "";
    c.diag = diag;
    c.user = user;
    c.pos = text;
    c.section = SEC_NONE;
    c.rc = SW_OK;

    int r = ini_parse_stream(scene_reader, &c, scene_handler, &c);
    if (r == -2) {
        report(diag, user, c.origin, 0, "out of memory while parsing");
        return SW_ENOMEM;
    }
    /* The reader hands inih only well-formed lines and the handler never
     * fails, so inih should have nothing to add; if it does, say where. */
    if (r > 0 && c.rc == SW_OK) {
        report(diag, user, c.origin, r, "malformed line");
        c.rc = SW_EPARSE;
    }
    return c.rc;
}

/* ---- validation ---------------------------------------------------------- */

typedef struct {
    const char *origin;
    sw_diag_fn diag;
    void *user;
    int errors;
} vctx;

#define VREPORT(v, line, ...) \
    ((v)->errors++, report((v)->diag, (v)->user, (v)->origin, (line), __VA_ARGS__))

/* "2 m", or "0.1" for a dimensionless value. */
static const char *qty(char *buf, size_t size, double x, const char *unit)
{
    snprintf(buf, size, "%g%s%s", x, *unit ? " " : "", unit);
    return buf;
}

/* Check one given value: finite, > 0 (>= 0 when zero_ok), within [lo, hi]
 * (lo = 0: no lower limit beyond the sign).  what says what the key is.
 * Returns 1 if good. */
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
    if (lo > 0 && x < lo) {
        VREPORT(v, line, "%s = %s is too small: expected at least %s (%s)", key,
                qty(a, sizeof a, x, unit), qty(b, sizeof b, lo, unit), what);
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
                      int dim_key, int ratio_key, int required, int zero_ok, double ratio_max,
                      const char *dim_what, const char *ratio_what)
{
    char key[48];
    if (given == SW_GIVEN_NONE) {
        if (!required)
            return 1;
        const char *ru = keys[ratio_key].unit;
        VREPORT(v, line, "%s.%s (or %s.%s) missing: expected %s in %s, or %s%s%s", sec,
                keys[dim_key].name, sec, keys[ratio_key].name, dim_what, keys[dim_key].unit,
                ratio_what, *ru ? " in " : "", ru);
        return 0;
    }
    int k = given == SW_GIVEN_RATIO ? ratio_key : dim_key;
    snprintf(key, sizeof key, "%s.%s", sec, keys[k].name);
    return given == SW_GIVEN_RATIO
               ? check_value(v, line, key, ratio, keys[k].unit, ratio_what, zero_ok, 0, ratio_max)
               : check_value(v, line, key, dim, keys[k].unit, dim_what, zero_ok, 0, INFINITY);
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
    }
    if (c_given == SW_GIVEN_RATIO) {
        r.zeta = zeta;
        r.c = 2 * zeta * r.omega * mt;
    } else if (c_given == SW_GIVEN_DIMENSIONAL) {
        r.c = damping;
        r.zeta = r.c / (2 * r.omega * mt);
    }
    if (r.omega <= OMEGA_MAX && mode_rate(r.omega, r.zeta) > OMEGA_MAX)
        VREPORT(v, line,
                "%s.%s: zeta_%s = %g with omega_%s = %g rad/s makes %s decay at %g 1/s, which "
                "is absurd: expected at most %g 1/s",
                sec, c_given == SW_GIVEN_RATIO ? "zeta" : "damping", sym, r.zeta, sym, r.omega,
                what, mode_rate(r.omega, r.zeta), OMEGA_MAX);
    return r;
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
    char a[64], b[64];

    /* [package] */
    int lp = sc->line_package;
    int pkg_ok = check_value(&v, lp, "package.height", sc->height, "m", "the package height 2h", 0,
                             SIZE_MIN, SIZE_MAX_);
    pkg_ok &= check_value(&v, lp, "package.width", sc->width, "m",
                          "the package width 2b along the axis of travel", 0, SIZE_MIN, SIZE_MAX_);
    pkg_ok &=
        check_value(&v, lp, "package.mass", sc->mass, "kg", "the package mass m", 0, 0, MASS_MAX);
    if (!isfinite(sc->g) || sc->g < G_MIN || sc->g > G_MAX) {
        VREPORT(&v, lp, "package.g = %s: expected gravity between %g and %g m/s^2",
                qty(a, sizeof a, sc->g, "m/s^2"), G_MIN, G_MAX);
        pkg_ok = 0;
    }

    const double m = sc->mass;       /* kg */
    const double h = sc->height / 2; /* m */
    const double bb = sc->width / 2; /* m, b */
    const double g = sc->g;          /* m/s^2 */

    /* [frame] */
    double m_b = 0, k_b = 0, c_b = 0, omega_b = 0, zeta_b = 0, gamma = 0;
    if (sc->has_frame) {
        int lf = sc->line_frame;
        int mb_ok = check_value(&v, lf, "frame.mass", sc->frame_mass, "kg", "the frame mass m_b", 0,
                                0, FRAME_MASS_MAX);
        int k_ok = check_pair(&v, lf, "frame", sc->frame_k_given, sc->frame_stiffness,
                              sc->frame_omega, K_FRAME_STIFFNESS, K_FRAME_OMEGA, 1, 0, OMEGA_MAX,
                              "the bearing stiffness k_b",
                              "the bearing frequency omega_b = sqrt(k_b/(m+m_b))");
        int c_ok = check_pair(&v, lf, "frame", sc->frame_c_given, sc->frame_damping, sc->frame_zeta,
                              K_FRAME_DAMPING, K_FRAME_ZETA, 1, 1, INFINITY,
                              "the bearing damping c_b", "the bearing damping ratio zeta_b");
        if (pkg_ok && mb_ok && k_ok && c_ok) {
            m_b = sc->frame_mass;
            const double mt = m + m_b; /* kg, package and frame move together */
            gamma = m / mt;
            const spring_t br = spring_of(&v, lf, "frame", "b", "the bearings", mt,
                                          sc->frame_k_given, sc->frame_stiffness, sc->frame_omega,
                                          sc->frame_c_given, sc->frame_damping, sc->frame_zeta);
            k_b = br.k;
            omega_b = br.omega;
            c_b = br.c;
            zeta_b = br.zeta;
        }
    }

    /* [cushion] */
    double K = 0, C = 0, B3 = 0, omega_c = 0, zeta_c = 0;
    if (sc->has_cushion) {
        int lc = sc->line_cushion;
        int k_ok = check_pair(&v, lc, "cushion", sc->cushion_k_given, sc->cushion_stiffness,
                              sc->cushion_omega, K_CUSHION_STIFFNESS, K_CUSHION_OMEGA, 1, 0,
                              OMEGA_MAX, "the total cushion stiffness K",
                              "the cushion frequency omega_c = sqrt(K/m)");
        int c_ok = check_pair(&v, lc, "cushion", sc->cushion_c_given, sc->cushion_damping,
                              sc->cushion_zeta, K_CUSHION_DAMPING, K_CUSHION_ZETA, 0, 1, INFINITY,
                              "the total cushion damping C", "the cushion damping ratio zeta_c");
        int b_ok = check_value(&v, lc, "cushion.cubic", sc->cushion_cubic, "N/m^3",
                               "the total cubic cushion stiffness B3", 1, 0, INFINITY);
        if (pkg_ok && k_ok && c_ok && b_ok) {
            const char *kkey =
                sc->cushion_k_given == SW_GIVEN_RATIO ? "cushion.omega" : "cushion.stiffness";
            const spring_t cu = spring_of(&v, lc, "cushion", "c", "the cushion", m,
                                          sc->cushion_k_given, sc->cushion_stiffness,
                                          sc->cushion_omega, sc->cushion_c_given,
                                          sc->cushion_damping, sc->cushion_zeta);
            K = cu.k;
            omega_c = cu.omega;
            C = cu.c;
            zeta_c = cu.zeta;
            B3 = sc->cushion_cubic;
            /* physics.md, static stability: tilting by a small angle the
             * cushion's restoring moment K b^2/3 per radian must beat the
             * overturning moment m g h of gravity. */
            const double restoring = K * bb * bb / 3; /* N*m per rad */
            const double toppling = m * g * h;        /* N*m per rad */
            if (restoring <= toppling) {
                const double K_min = 3 * toppling / (bb * bb); /* N/m */
                VREPORT(&v, lc,
                        "%s: cushion too soft to hold the package upright: K*b^2/3 = %.4g N*m "
                        "<= m*g*h = %.4g N*m; expected K above %s (omega_c above %s)",
                        kkey, restoring, toppling, qty(a, sizeof a, K_min, "N/m"),
                        qty(b, sizeof b, sqrt(K_min / m), "rad/s"));
            }
        }
    }

    /* [alarm]: both margins are fractions of the way from overturn (0) to
     * rest (1); the critical alarm must fire closer to overturn. */
    int la = sc->line_alarm;
    int warn_ok = isfinite(sc->warn_margin) && sc->warn_margin > 0 && sc->warn_margin <= 1;
    if (!warn_ok)
        VREPORT(&v, la, "alarm.warn_margin = %g: expected a value in (0, 1]", sc->warn_margin);
    if (!isfinite(sc->critical_margin) || sc->critical_margin <= 0 || sc->critical_margin > 1) {
        VREPORT(&v, la,
                "alarm.critical_margin = %g: expected a value in (0, 1) below "
                "alarm.warn_margin",
                sc->critical_margin);
    } else if (warn_ok && sc->critical_margin >= sc->warn_margin) {
        VREPORT(&v, la,
                "alarm.critical_margin = %g is not below alarm.warn_margin = %g: expected "
                "0 < critical_margin < warn_margin <= 1",
                sc->critical_margin, sc->warn_margin);
    }

    /* [alarm], the reserve (reserve.h): pulse durations and levels in g;
     * the critical level must be the lower reserve. */
    if (sc->n_design_pulse < 1 || sc->n_design_pulse > SW_DESIGN_PULSES_MAX) {
        VREPORT(&v, la, "alarm.design_pulse has %d durations: expected 1 to %d",
                sc->n_design_pulse, SW_DESIGN_PULSES_MAX);
    } else {
        for (int i = 0; i < sc->n_design_pulse; i++) {
            const double T = sc->design_pulse[i]; /* s */
            if (!isfinite(T) || T < PULSE_MIN || T > PULSE_MAX)
                VREPORT(&v, la,
                        "alarm.design_pulse item %d = %g s: expected a half-sine duration "
                        "between %g and %g s",
                        i + 1, T, PULSE_MIN, PULSE_MAX);
        }
    }
    int wr_ok = isfinite(sc->warn_reserve_g) && sc->warn_reserve_g > 0 &&
                sc->warn_reserve_g <= RESERVE_G_MAX;
    if (!wr_ok)
        VREPORT(&v, la, "alarm.warn_reserve_g = %g: expected a value in (0, %g] g",
                sc->warn_reserve_g, RESERVE_G_MAX);
    if (!isfinite(sc->critical_reserve_g) || sc->critical_reserve_g <= 0 ||
        sc->critical_reserve_g > RESERVE_G_MAX) {
        VREPORT(&v, la,
                "alarm.critical_reserve_g = %g: expected a value in (0, %g] g below "
                "alarm.warn_reserve_g",
                sc->critical_reserve_g, RESERVE_G_MAX);
    } else if (wr_ok && sc->critical_reserve_g >= sc->warn_reserve_g) {
        VREPORT(&v, la,
                "alarm.critical_reserve_g = %g is not below alarm.warn_reserve_g = %g: "
                "expected 0 < critical_reserve_g < warn_reserve_g",
                sc->critical_reserve_g, sc->warn_reserve_g);
    }

    if (v.errors)
        return SW_EINVAL;
    if (!d)
        return SW_OK;

    /* physics.md, "Package, vehicle, conventions" and the scene sections. */
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
    d->k_b = k_b;
    d->c_b = c_b;
    d->omega_b = omega_b;
    d->zeta_b = zeta_b;
    /* With gamma = 0 this is eta: a package on the bed. */
    d->r_frame = 1 - 6 * s * s / (4 - 3 * gamma * co * co);
    d->K = K;
    d->C = C;
    d->B3 = B3;
    d->omega_c = omega_c;
    d->zeta_c = zeta_c;

    /* The fastest natural frequency bounds an explicit stepper's step.  The
     * coupled frame frequency lies below omega_b / sqrt(1 - 3 gamma/4): the
     * package's inertia seen by the frame is at most reduced by the factor
     * D = 1 - (3/4) gamma cos^2 of physics.md.  Overdamped modes count with
     * their fast decay rate (mode_rate). */
    double w = 0; /* rad/s */
    if (sc->has_frame)
        w = mode_rate(omega_b, zeta_b) / sqrt(1 - 0.75 * gamma);
    /* The cushion's vertical and rocking modes, damping included (an
     * overdamped mode's fast real root exceeds omega_c: 3.7 omega_c at
     * zeta_c = 2), the rocking mode coupled to the frame if there is one. */
    if (sc->has_cushion)
        w = fmax(w, sw_cushion_omega_max(d, g));
    d->omega_max = w;
    return SW_OK;
}

static int same_number(double a, double b)
{
    return a == b || (isnan(a) && isnan(b));
}

/* The design pulse lists: the same durations in the same order (entries
 * past the count do not count). */
static int same_pulses(const sw_scene_t *a, const sw_scene_t *b)
{
    if (a->n_design_pulse != b->n_design_pulse) return 0;
    for (int i = 0; i < a->n_design_pulse && i < SW_DESIGN_PULSES_MAX; i++)
        if (!same_number(a->design_pulse[i], b->design_pulse[i])) return 0;
    return 1;
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
           same_number(a->critical_reserve_g, b->critical_reserve_g);
}

const char *sw_model_name(sw_model_kind k)
{
    switch (k) {
        case SW_MODEL_BARE: return "bare";
        case SW_MODEL_FRAME: return "frame";
        case SW_MODEL_CUSHION: return "cushion";
        default: return "unknown";
    }
}
