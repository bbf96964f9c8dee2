/* opts.c - the options every command shares (scene, integration, output),
 * the number parsers, and loading and checking the scene files.
 *
 * Everything here prints its own messages ("swaywatch: ..." on stderr) and
 * returns an exit code, so a command is a short sequence of calls with one
 * cleanup path. */
#include "opts.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Scene files are small; anything this big is not a scene. */
#define SCENE_MAX_BYTES (1L << 20)

/* ---- options ------------------------------------------------------------ */

void sw_cli_print_scene_help(FILE *f)
{
    fprintf(f,
            "Scene (one package per file; several files, several packages):\n"
            "  -s, --scene FILE         scene file (INI); at least one, repeatable\n"
            "      --set SEC.KEY=VALUE  override a key in every scene, e.g. --set frame.zeta=0.2\n"
            "\n"
            "Integration:\n"
            "      --scheme NAME        time stepper:");
    for (size_t i = 0; sw_scheme_at(i); i++)
        fprintf(f, "%s %s", i ? "," : "", sw_scheme_name(sw_scheme_at(i)));
    fprintf(f, " (default %s)\n", SW_DEFAULT_SCHEME);
    fprintf(f,
            "      --dt SECONDS         internal step; refused if above the scheme's stability\n"
            "                           bound (default: the scheme's own, sub-stepped as needed)\n"
            "      --rtol X, --atol X   tolerances of the adaptive schemes (default 1e-10, 1e-12)\n"
            "      --accuracy RAD       pick the cheapest scheme and step measured to keep the\n"
            "                           error of theta within RAD (docs/accuracy-speed.md)\n");
}

void sw_cli_print_common_help(FILE *f)
{
    sw_cli_print_scene_help(f);
    fprintf(f,
            "\n"
            "Output:\n"
            "  -o, --out FILE.csv       state time series: t,package,phase,theta,theta_dot,u,u_dot,\n"
            "                           z,z_dot,margin,margin_bound,uplift_ratio,a_g (SI units, rad)\n"
            "      --every N            keep every Nth state row of each package (default 1)\n"
            "  -e, --events FILE.csv    events: t,package,event,theta,theta_dot,margin,info\n"
            "      --json               JSON summary on stdout instead of the human summary\n"
            "  -q, --quiet              no human summary\n"
            "  -v, --verbose            derived quantities of each scene, on stderr\n"
            "  -h, --help               this help\n");
}

void sw_cli_print_exit_help(FILE *f, int overturn, int strict)
{
    fprintf(f, "\nExit codes: 0 ok");
    if (overturn) fprintf(f, ", 1 a package overturned and --fail-on-overturn was given");
    fprintf(f, ",\n2 bad usage or bad input (options, scene files%s),\n"
               "3 a file could not be read or written.\n",
            strict ? ", rows under --strict" : "");
}

int sw_cli_opts_init(sw_cli_opts_t *o, int argc)
{
    memset(o, 0, sizeof *o);
    o->every = 1;
    /* No option can repeat more often than there are arguments. */
    size_t cap = argc > 0 ? (size_t)argc : 1;
    o->scene_files = calloc(cap, sizeof *o->scene_files);
    o->sets = calloc(cap, sizeof *o->sets);
    if (!o->scene_files || !o->sets) {
        sw_cli_error("out of memory");
        sw_cli_opts_fini(o);
        return SW_EXIT_IO;
    }
    return SW_EXIT_OK;
}

void sw_cli_opts_fini(sw_cli_opts_t *o)
{
    free(o->scene_files);
    free(o->sets);
    o->scene_files = NULL;
    o->sets = NULL;
}

int sw_cli_parse_double(const char *opt, const char *arg, int rule, const char *what, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = arg ? strtod(arg, &end) : NAN;
    int ok = arg && end != arg && *end == '\0' && errno != ERANGE && isfinite(v);
    if (ok && rule == SW_NUM_POSITIVE) ok = v > 0.0;
    if (ok && rule == SW_NUM_NONNEGATIVE) ok = v >= 0.0;
    if (ok && rule == SW_NUM_NONZERO) ok = v != 0.0;
    if (!ok) {
        sw_cli_error("%s: expected %s, got '%s'", opt, what, arg ? arg : "");
        return SW_EXIT_USAGE;
    }
    *out = v;
    return SW_EXIT_OK;
}

int sw_cli_parse_long(const char *opt, const char *arg, long min, const char *what, long *out)
{
    char *end = NULL;
    errno = 0;
    long v = arg ? strtol(arg, &end, 10) : 0;
    if (!arg || end == arg || *end != '\0' || errno == ERANGE || v < min) {
        sw_cli_error("%s: expected %s, got '%s'", opt, what, arg ? arg : "");
        return SW_EXIT_USAGE;
    }
    *out = v;
    return SW_EXIT_OK;
}

static int check_scheme(const char *name)
{
    if (sw_scheme_lookup(name)) return SW_EXIT_OK;
    fprintf(stderr, "swaywatch: --scheme: unknown scheme '%s'; valid:", name);
    for (size_t i = 0; sw_scheme_at(i); i++)
        fprintf(stderr, "%s %s", i ? "," : "", sw_scheme_name(sw_scheme_at(i)));
    fputc('\n', stderr);
    return SW_EXIT_USAGE;
}

int sw_cli_common_option(sw_cli_opts_t *o, int c, const char *arg, char **argv)
{
    switch (c) {
    case 's':
    case SW_OPT_SCENE: o->scene_files[o->n_scene_files++] = arg; return SW_EXIT_OK;
    case SW_OPT_SET:
        if (!strchr(arg, '=') || !strchr(arg, '.') || strchr(arg, '.') > strchr(arg, '=')) {
            sw_cli_error("--set: expected SECTION.KEY=VALUE, got '%s'", arg);
            return SW_EXIT_USAGE;
        }
        o->sets[o->n_sets++] = arg;
        return SW_EXIT_OK;
    case SW_OPT_SCHEME: o->scheme = arg; return check_scheme(arg);
    case SW_OPT_DT:
        return sw_cli_parse_double("--dt", arg, SW_NUM_POSITIVE, "a positive number of seconds",
                                   &o->dt);
    case SW_OPT_RTOL:
        return sw_cli_parse_double("--rtol", arg, SW_NUM_POSITIVE, "a positive tolerance",
                                   &o->rtol);
    case SW_OPT_ATOL:
        return sw_cli_parse_double("--atol", arg, SW_NUM_POSITIVE, "a positive tolerance",
                                   &o->atol);
    case SW_OPT_ACCURACY:
        return sw_cli_parse_double("--accuracy", arg, SW_NUM_POSITIVE,
                                   "a positive angle in radians", &o->accuracy);
    case 'o':
    case SW_OPT_OUT: o->out_path = arg; return SW_EXIT_OK;
    case SW_OPT_EVERY:
        return sw_cli_parse_long("--every", arg, 1, "a whole number of rows >= 1", &o->every);
    case 'e':
    case SW_OPT_EVENTS: o->events_path = arg; return SW_EXIT_OK;
    case SW_OPT_JSON: o->json = 1; return SW_EXIT_OK;
    case 'q':
    case SW_OPT_QUIET: o->quiet = 1; return SW_EXIT_OK;
    case 'v':
    case SW_OPT_VERBOSE: o->verbose = 1; return SW_EXIT_OK;
    case 'h':
    case SW_OPT_HELP: o->help = 1; return SW_EXIT_OK;
    case ':':
        /* getopt leaves the option it was parsing in argv[optind - 1]. */
        sw_cli_error("%s: option '%s' needs a value", argv[0], argv[optind - 1]);
        return SW_EXIT_USAGE;
    case '?':
        if (optopt > 0 && optopt < 256)
            sw_cli_error("%s: unknown option '-%c'; see 'swaywatch %s --help'", argv[0], optopt,
                         argv[0]);
        else if (optopt >= 256) { /* a known long option given a value it does not take */
            const char *opt = argv[optind - 1];
            const char *eq = strchr(opt, '=');
            sw_cli_error("%s: option '%.*s' takes no value", argv[0],
                         (int)(eq ? eq - opt : (long)strlen(opt)), opt);
        }
        else
            sw_cli_error("%s: unknown option '%s'; see 'swaywatch %s --help'", argv[0],
                         argv[optind - 1], argv[0]);
        return SW_EXIT_USAGE;
    default: return -1;
    }
}

int sw_cli_getopt(sw_cli_opts_t *o, int argc, char **argv, const char *shortopts,
                  const struct option *longopts, int *longindex, const sw_cli_group_t *groups,
                  size_t n, void (*usage)(FILE *))
{
    opterr = 0; /* sw_cli_common_option words the errors */
    for (int c; (c = getopt_long(argc, argv, shortopts, longopts, longindex)) != -1;) {
        int r = sw_cli_common_option(o, c, optarg, argv);
        for (size_t i = 0; r == -1 && i < n; i++) r = groups[i].fn(groups[i].ctx, c, optarg);
        if (r == -1) return c;
        if (r != SW_EXIT_OK) return SW_CLI_OPT_BAD;
        if (o->help) {
            if (usage) usage(stdout);
            return SW_CLI_OPT_HELP;
        }
    }
    return SW_CLI_OPT_END;
}

const char *sw_cli_log_operand(const char *cmd, int argc, char **argv)
{
    if (optind >= argc) {
        sw_cli_error("%s: missing LOG (a CSV file, or - for standard input); see 'swaywatch %s "
                     "--help'",
                     cmd, cmd);
        return NULL;
    }
    if (optind + 1 < argc) {
        sw_cli_error("%s: one LOG at a time; unexpected '%s'", cmd, argv[optind + 1]);
        return NULL;
    }
    return argv[optind];
}

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

/* Whole file into a NUL-terminated buffer; prints its own errors. */
static int read_text(const char *path, char **text)
{
    int rc = SW_EXIT_IO;
    char *buf = NULL;
    size_t len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        sw_cli_error("%s: cannot open: %s", path, strerror(errno));
        goto out;
    }
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
    if (f) fclose(f);
    return rc;
}

int sw_cli_load_scenes(const sw_cli_opts_t *o, sw_scene_t **scenes, size_t *n)
{
    int rc = SW_EXIT_USAGE;
    sw_scene_t *sc = NULL;
    char *text = NULL;
    sw_cli_diag_t diag = {0};

    if (o->n_scene_files == 0) {
        sw_cli_error("no scene: give at least one --scene FILE");
        goto out;
    }
    sc = calloc(o->n_scene_files, sizeof *sc);
    if (!sc) {
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
        goto out;
    }
    for (size_t i = 0; i < o->n_scene_files; i++) {
        const char *path = o->scene_files[i];
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
            if (diag.errors == before) sw_cli_error("%s: %s", path, sw_strerror(pr));
            diag.errors++;
            continue; /* report every file's problems before giving up */
        }
        for (size_t k = 0; k < o->n_sets; k++) {
            before = diag.errors;
            if (sw_scene_set_arg(&sc[i], o->sets[k], sw_cli_print_diag, &diag) != SW_OK) {
                if (diag.errors == before) sw_cli_error("--set %s: rejected", o->sets[k]);
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
            if (diag.errors == before) sw_cli_error("%s: invalid scene", path);
            diag.errors++;
        }
    }
    if (diag.errors) goto out;
    *scenes = sc;
    *n = o->n_scene_files;
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
    if (!(o->accuracy > 0.0)) return SW_EXIT_OK;
    if (o->scheme || o->dt > 0.0) {
        sw_cli_error("--accuracy chooses the scheme and the step: give it without --scheme and "
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

sw_engine_t *sw_cli_engine_create(const sw_scene_t *scenes, size_t n, const sw_engine_opts_t *eo)
{
    int err = 0;
    char msg[512] = "";
    sw_engine_t *e = sw_engine_create(scenes, n, eo, &err, msg, sizeof msg);
    if (!e) sw_cli_error("cannot start the engine: %s", msg[0] ? msg : sw_strerror(err));
    return e;
}
