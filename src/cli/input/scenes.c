/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scenes.c - the options every command shares (opts.h: scene,
 * integration, output) and what they build: the scenes (read, --set
 * applied, validated) and the engine.
 *
 * Everything here prints its own messages ("swaywatch: ..." on stderr) and
 * returns an exit code. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cost.h"
#include "opts.h"
#include "plot.h"

/* Scene files are small; anything this big is not a scene. */
#define SCENE_MAX_BYTES (1L << 20)

/* ---- scene, integration and output options ---------------------------------- */

static int check_set(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    if (!strchr(arg, '=') || !strchr(arg, '.') || strchr(arg, '.') > strchr(arg, '=')) {
        sw_cli_error("--%s: expected SECTION.KEY=VALUE, got '%s'", o->long_name, arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

static int check_scheme(const sw_cli_option_t *o, const char *name, void *dest)
{
    (void)dest;
    if (sw_scheme_lookup(name))
        return SW_EXIT_OK;
    FILE *m = sw_cli_msg();
    fprintf(m, "swaywatch: --%s: unknown scheme '%s'; valid:", o->long_name, name);
    for (size_t i = 0; sw_scheme_at(i); i++)
        fprintf(m, "%s %s", i ? "," : "", sw_scheme_name(sw_scheme_at(i)));
    fputc('\n', m);
    return SW_EXIT_USAGE;
}

static void scheme_help(char *buf, size_t len)
{
    int k = snprintf(buf, len, "time stepper:");
    for (size_t i = 0; sw_scheme_at(i) && k > 0 && (size_t)k < len; i++)
        k += snprintf(buf + k, len - (size_t)k, "%s %s", i ? "," : "",
                      sw_scheme_name(sw_scheme_at(i)));
    if (k > 0 && (size_t)k < len)
        snprintf(buf + k, len - (size_t)k, " (default %s)", SW_DEFAULT_SCHEME);
}

#define OPTS(f) SW_CLI_AT(sw_cli_opts_t, f)

const sw_cli_option_t sw_cli_scene_options[] = {
    {SW_CLI_SECTION, .help = "Scene (one package per file; several files, several packages):"},
    {SW_CLI_LIST, 's', "scene", "FILE", OPTS(scenes),
     .help = "scene file (INI); at least one, repeatable"},
    {SW_CLI_LIST, 0, "set", "SEC.KEY=VALUE", OPTS(sets), .fn = check_set,
     .help = "override a key in every scene, e.g. --set frame.zeta=0.2"},
    {.kind = SW_CLI_END},
};

const sw_cli_option_t sw_cli_integration_options[] = {
    {SW_CLI_SECTION, .help = "Integration:"},
    {SW_CLI_STRING, 0, "scheme", "NAME", OPTS(scheme), .fn = check_scheme, .help_fn = scheme_help},
    {SW_CLI_DOUBLE, 0, "dt", "SECONDS", OPTS(dt), .rule = SW_NUM_POSITIVE, .lo = 1e-7, .hi = 1,
     .what = "a positive number of seconds",
     .help = "internal step; refused outside the scheme's stability region for the scene's "
             "modes, with a stable dt named (default: the scheme's own, shortened as needed); "
             "replay, simulate and forensics run the default scheme and step beside a chosen "
             "--scheme or --dt and warn of a verdict they contradict; at least 1e-7 s, 10,000 "
             "steps per 1 ms sample, which already runs slower than real time"},
    {SW_CLI_DOUBLE, 0, "rtol", "X", OPTS(rtol), .rule = SW_NUM_POSITIVE, .lo = 1e-14, .hi = 1e-2,
     .what = "a positive tolerance",
     .help = "relative tolerance of the adaptive schemes (default 1e-10); below 1e-14 double "
             "precision cannot meet it and steps fail"},
    {SW_CLI_DOUBLE, 0, "atol", "X", OPTS(atol), .rule = SW_NUM_POSITIVE, .lo = 1e-16, .hi = 1e-2,
     .what = "a positive tolerance",
     .help = "absolute tolerance of the adaptive schemes (default 1e-12); below 1e-16 rad it is "
             "under the rounding of angles near 1 rad and steps fail"},
    {.kind = SW_CLI_END},
};

const sw_cli_option_t sw_cli_accuracy_options[] = {
    {SW_CLI_SECTION, .help = "Integration:"},
    {SW_CLI_DOUBLE, 0, "accuracy", "RAD", OPTS(accuracy), .rule = SW_NUM_POSITIVE,
     .what = "a positive angle in radians",
     .help = "pick the cheapest scheme and step measured to keep the error of theta within RAD "
             "(docs/accuracy-speed.md); bounded by that table: tighter than about 1e-14 rad is "
             "refused"},
    {.kind = SW_CLI_END},
};

const sw_cli_option_t sw_cli_output_options[] = {
    {SW_CLI_SECTION, .help = "Output:"},
    {SW_CLI_STRING, 'o', "out", "FILE.csv", OPTS(out_path),
     .help = "state time series ('-': standard output): "
             "t,package,phase,theta,theta_dot,u,u_dot,z,z_dot,margin,"
             "margin_bound,uplift_ratio,a_g,reserve_g (SI units, rad; the reserve in g, the "
             "latest evaluation, made at --reserve-rate)"},
    {SW_CLI_LONG, 0, "every", "N", OPTS(every), .min = 1, .def = 1,
     .what = "a whole number of rows >= 1",
     .help = "every Nth state row of each package (default %g)"},
    {SW_CLI_STRING, 'e', "events", "FILE.csv", OPTS(events_path),
     .help = "events ('-': standard output): t,package,event,theta,theta_dot,margin,info; info: "
             "uplift the direction (+1 top forward), impact theta_dot before it (rad/s), "
             "settling the micro-impacts in the cascade (theta_dot: the fastest), rest 0, tip "
             "+-alpha (rad, its sign the side), overturn theta_dot then (rad/s), fault the "
             "status code, flight when the flight began (s)"},
    {SW_CLI_FLAG, 0, "json", OPTS(json), .value = 1,
     .help = "JSON summary on stdout instead of the human summary"},
    {SW_CLI_FLAG, 'q', "quiet", OPTS(quiet), .value = 1, .help = "no human summary"},
    {.kind = SW_CLI_END},
};

const sw_cli_option_t sw_cli_reserve_options[] = {
    {SW_CLI_SECTION, .help = "Reserve and impacts:"},
    {SW_CLI_DOUBLE, 0, "reserve-rate", "HZ", OPTS(reserve_rate), .rule = SW_NUM_NONNEGATIVE,
     .def = SW_RISK_RATE, .lo = 0.01, .hi = 1000, .what = "a rate in Hz >= 0 (0: none)",
     .help = "evaluations per second of the log's time of each package's reserve: the smallest "
             "design braking pulse in g that would overturn it from its state then (the scene's "
             "[alarm] design_pulse; docs/reserve.md); shown in --out and --wide (reserve_g) and as "
             "the minimum in the summary (default %g; 0: none).  A replay (and forensics) with "
             "neither --out nor --wide nor a figure seeks only the minimum over the states at "
             "this rate, most threatened first: the same value, far fewer evaluations where it "
             "stands out"},
    {SW_CLI_FLAG, 0, "all-impacts", OPTS(all_impacts), .value = 1,
     .help = "write every impact in --events; without it the micro-impacts of settling (slower "
             "than a tenth of the tipping speed) are one 'settling' row per cascade"},
    {.kind = SW_CLI_END},
};

const sw_cli_option_t sw_cli_picture_options[] = {
    {SW_CLI_SECTION, .help = "Output:"},
    {SW_CLI_STRING, 0, "wide", "FILE.csv", OPTS(wide_path),
     .help = "the state series one row per instant ('-': standard output), for a plain plot or "
             "a spreadsheet: t,a_g, then for each package P: P.phase,P.theta,P.theta_dot,"
             "P.ratio (theta/alpha),P.margin,P.margin_bound,P.uplift_ratio,P.reserve_g (the "
             "latest evaluation, made at --reserve-rate); --every keeps every Nth row"},
    {SW_CLI_STRING, 0, "plot", "FILE.png|.svg", OPTS(plot_path), .fn = sw_cli_plot_check,
     .help = "a figure drawn by gnuplot: the bed acceleration with the uplift thresholds "
             "+-g tan alpha, theta/alpha and the margin of every package, the events marked"},
    {.kind = SW_CLI_END},
};

const sw_cli_option_t sw_cli_common_options[] = {
    {SW_CLI_FLAG, 'v', "verbose", OPTS(verbose), .value = 1,
     .help = "derived quantities of each scene, on stderr"},
    {SW_CLI_HELP, 'h', "help", .help = "this help"},
    {.kind = SW_CLI_END},
};

/* ---- scenes --------------------------------------------------------------- */

void sw_cli_print_diag(void *user, const char *origin, int line, const char *msg)
{
    sw_cli_diag_t *d = user;
    d->errors++;
    if (line > 0)
        sw_cli_error("%s:%d: %s", origin ? origin : "scene", line, msg);
    else
        sw_cli_error("%s: %s", origin ? origin : "scene", msg);
}

/* What a path that is not a regular file is, in words. */
static const char *file_kind(mode_t mode)
{
    return S_ISDIR(mode)    ? "a directory"
           : S_ISFIFO(mode) ? "a FIFO"
           : S_ISCHR(mode)  ? "a character device"
           : S_ISBLK(mode)  ? "a block device"
           : S_ISSOCK(mode) ? "a socket"
                            : "not a regular file";
}

/* Open a scene file for reading: a regular file, or refused.  Opened with
 * O_NONBLOCK so that a FIFO (or a device) in its place cannot block the
 * caller, a monitor reloading on SIGHUP, until someone writes to it; the
 * type is checked on the opened file, not on the name (no race). */
static FILE *open_regular(const char *path, int *rc)
{
    *rc = SW_EXIT_IO;
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        sw_cli_error("%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    struct stat st;
    if (fstat(fd, &st) != 0) {
        sw_cli_error("%s: cannot read: %s", path, strerror(errno));
        close(fd);
        return NULL;
    }
    if (!S_ISREG(st.st_mode)) {
        sw_cli_error("%s: %s: a scene must be a regular file", path, file_kind(st.st_mode));
        *rc = SW_EXIT_USAGE;
        close(fd);
        return NULL;
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        sw_cli_error("%s: cannot read: %s", path, strerror(errno));
        close(fd);
    }
    return f;
}

/* Whole file into a NUL-terminated buffer; prints its own errors. */
static int read_text(const char *path, char **text)
{
    int rc = SW_EXIT_IO;
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_regular(path, &rc);
    if (!f)
        goto out;
    rc = SW_EXIT_IO;
    buf = malloc((size_t)SCENE_MAX_BYTES + 1);
    if (!buf) {
        sw_cli_error("%s: out of memory", path);
        goto out;
    }
    len = fread(buf, 1, (size_t)SCENE_MAX_BYTES + 1, f);
    if (ferror(f)) {
        sw_cli_error("%s: cannot read: %s", path, strerror(errno));
        goto out;
    }
    if (len > (size_t)SCENE_MAX_BYTES) {
        sw_cli_error("%s: larger than %ld bytes: not a scene file", path, SCENE_MAX_BYTES);
        rc = SW_EXIT_USAGE;
        goto out;
    }
    buf[len] = '\0';
    if (strlen(buf) != len) {
        sw_cli_error("%s: contains a NUL byte: not a scene file", path);
        rc = SW_EXIT_USAGE;
        goto out;
    }
    *text = buf;
    buf = NULL;
    rc = SW_EXIT_OK;
out:
    free(buf);
    if (f)
        fclose(f);
    return rc;
}

int sw_cli_load_scenes(const sw_cli_opts_t *o, sw_scene_t **scenes, size_t *n)
{
    int rc = SW_EXIT_USAGE;
    sw_scene_t *sc = NULL;
    char *text = NULL;
    sw_cli_diag_t diag = {0};

    if (o->scenes.n == 0) {
        sw_cli_error("no scene: give at least one --scene FILE");
        goto out;
    }
    sc = calloc(o->scenes.n, sizeof *sc);
    if (!sc) {
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
        goto out;
    }
    for (size_t i = 0; i < o->scenes.n; i++) {
        const char *path = o->scenes.v[i];
        int r = read_text(path, &text);
        if (r != SW_EXIT_OK) {
            rc = r;
            goto out;
        }
        sw_scene_init(&sc[i]);
        long before = diag.errors;
        int pr = sw_scene_parse(&sc[i], text, path, sw_cli_print_diag, &diag);
        free(text);
        text = NULL;
        if (pr != SW_OK) {
            if (diag.errors == before)
                sw_cli_error("%s: %s", path, sw_strerror(pr));
            diag.errors++;
            continue; /* report every file's problems before giving up */
        }
        for (size_t k = 0; k < o->sets.n; k++) {
            before = diag.errors;
            if (sw_scene_set_arg(&sc[i], o->sets.v[k], sw_cli_print_diag, &diag) != SW_OK) {
                if (diag.errors == before)
                    sw_cli_error("--set %s: rejected", o->sets.v[k]);
                /* The same override would fail the same way on every scene. */
                goto out;
            }
        }
        if (sc[i].name[0] == '\0') {
            /* no package.name: messages and reports name the file instead */
            const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
            const char *dot = strrchr(base, '.');
            const int len = dot && dot > base ? (int)(dot - base) : (int)strlen(base);
            snprintf(sc[i].name, sizeof sc[i].name, "%.*s", len, base);
        }
        before = diag.errors;
        if (sw_scene_validate(&sc[i], NULL, path, sw_cli_print_diag, &diag) != SW_OK) {
            if (diag.errors == before)
                sw_cli_error("%s: invalid scene", path);
            diag.errors++;
        }
    }
    if (diag.errors)
        goto out;
    *scenes = sc;
    *n = o->scenes.n;
    sc = NULL;
    rc = SW_EXIT_OK;
out:
    free(text);
    free(sc);
    return rc;
}

/* ---- engine --------------------------------------------------------------- */

void sw_cli_engine_opts(const sw_cli_opts_t *o, sw_engine_opts_t *eo)
{
    memset(eo, 0, sizeof *eo);
    eo->scheme = o->scheme;
    eo->dt = o->dt;
    /* A step the user chose is taken as given: better refused than quietly
     * replaced by a smaller one. */
    eo->dt_forced = o->dt > 0.0;
    eo->rtol = o->rtol;
    eo->atol = o->atol;
}

int sw_cli_resolve_accuracy(const sw_cli_opts_t *o, const sw_scene_t *scenes, size_t n,
                            sw_engine_opts_t *eo)
{
    if (!(o->accuracy > 0.0))
        return SW_EXIT_OK;
    if (o->scheme || o->dt > 0.0) {
        sw_cli_error(
            "--accuracy chooses the scheme and the step: give it without --scheme and "
            "--dt");
        return SW_EXIT_USAGE;
    }
    /* The engine applies the policy (so do the sweeps' engines, each for
     * its own scene); asked here first to word a refusal as options. */
    const char *scheme = NULL;
    double dt = 0.0;
    const int r = sw_scheme_for_accuracy_n(scenes, n, o->accuracy, &scheme, &dt, NULL);
    if (r != SW_OK) {
        sw_cli_error("--accuracy %g rad: %s", o->accuracy,
                     r == SW_ENOTFOUND ? "tighter than any measured setting reaches "
                                         "(about 1e-14 rad); use --scheme rk8pd --rtol"
                                       : "no measured table for this model; choose --scheme "
                                         "and --dt or --rtol");
        return SW_EXIT_USAGE;
    }
    eo->scheme = NULL;
    eo->dt = 0.0;
    eo->dt_forced = 0;
    eo->accuracy = o->accuracy;
    return SW_EXIT_OK;
}

sw_risk_t *sw_cli_risk_create(const sw_cli_opts_t *o, const sw_scene_t *scenes, size_t n)
{
    const sw_risk_opts_t ro = {.reserve_rate = o->reserve_rate > 0.0 ? o->reserve_rate : -1.0};
    int err = SW_OK;
    char msg[512] = "";
    sw_risk_t *r = sw_risk_create(scenes, n, &ro, &err, msg, sizeof msg);
    if (!r)
        sw_cli_error("cannot start the reserve: %s", msg[0] ? msg : sw_strerror(err));
    else {
        sw_cli_warn_no_reserve(r, 0, n, scenes);
        sw_cli_warn_reserve_cost(r, 0, n, scenes, o->reserve_rate);
    }
    return r;
}

void sw_cli_risk_resolve(sw_risk_t *r, const sw_scene_t *scenes, size_t n)
{
    for (size_t k = 0; r && k < n; k++) {
        const int rc = sw_risk_resolve(r, k);
        if (rc < 0)
            sw_cli_error("%s: the smallest reserve could not be found: %s", scenes[k].name,
                         sw_strerror(rc));
    }
}

sw_engine_t *sw_cli_engine_create(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo)
{
    int err = 0;
    char msg[512] = "";
    sw_engine_t *e = sw_engine_create(scenes, n, eo, &err, msg, sizeof msg);
    if (!e)
        sw_cli_error("cannot start the engine: %s", msg[0] ? msg : sw_strerror(err));
    else
        sw_cli_warn_scene_cost(scenes, n, eo);
    return e;
}
