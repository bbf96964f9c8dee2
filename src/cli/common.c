/* common.c - what the swaywatch subcommands share: the scene, engine and
 * output options, loading and checking scene files, the state and event CSV
 * writers, and the human and JSON summaries.
 *
 * Everything here prints its own messages ("swaywatch: ..." on stderr) and
 * returns an exit code, so a command is a short sequence of calls with one
 * cleanup path. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"

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

/* One aligned line of --verbose: name, value with unit, what it is. */
static void derived_line(FILE *f, const char *name, double v, const char *unit, const char *what)
{
    char val[48];
    snprintf(val, sizeof val, "%.6g %s", v, unit);
    fprintf(f, "  %-8s %-18s %s\n", name, val, what);
}

void sw_cli_print_derived(FILE *f, const sw_engine_t *e, const sw_scene_t *scenes, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        const sw_derived_t *d = sw_engine_derived(e, i);
        const sw_scene_t *sc = &scenes[i];
        if (!d) continue;
        fprintf(f, "swaywatch: %s: %s model\n", sc->name, sw_model_name(d->model));
        derived_line(f, "R", d->R, "m", "half-diagonal sqrt(h^2 + b^2)");
        derived_line(f, "alpha", d->alpha * 180.0 / M_PI, "deg", "atan(b/h), slenderness");
        derived_line(f, "g tan a", sc->g * tan(d->alpha), "m/s^2", "uplift threshold (rigid support)");
        derived_line(f, "p", d->p, "rad/s", "rocking frequency sqrt(3 g / 4 R)");
        derived_line(f, "eta", d->eta, "", "impact ratio on a rigid support");
        if (sc->has_frame) {
            derived_line(f, "gamma", d->gamma, "", "m / (m + m_b)");
            derived_line(f, "omega_b", d->omega_b, "rad/s", "bearing frequency");
            derived_line(f, "zeta_b", d->zeta_b, "", "bearing damping ratio");
            derived_line(f, "r_frame", d->r_frame, "", "impact ratio on the frame");
        }
        if (sc->has_cushion) {
            derived_line(f, "omega_c", d->omega_c, "rad/s", "cushion frequency sqrt(K/m)");
            derived_line(f, "zeta_c", d->zeta_c, "", "cushion damping ratio");
            if (d->K > 0.0) {
                double wz, wr;
                sw_cushion_frequencies(d, sc->g, &wz, &wr);
                derived_line(f, "z_static", sw_cushion_static_deflection(d, sc->g), "m",
                             "static cushion deflection, root of K z + B3 z^3 = m g");
                derived_line(f, "omega_z", wz, "rad/s", "vertical natural frequency (undamped)");
                derived_line(f, "omega_r", wr, "rad/s", "rocking natural frequency on the cushion");
            }
        }
        char what[64];
        snprintf(what, sizeof what, "internal step of scheme %s", sw_engine_scheme(e));
        derived_line(f, "dt", sw_engine_dt(e, i), "s", what);
    }
}

/* ---- output files ---------------------------------------------------------- */

/* Non-zero if path exists and is the file st describes. */
static int is_file(const char *path, const struct stat *st)
{
    struct stat ps;
    return path && stat(path, &ps) == 0 && ps.st_dev == st->st_dev && ps.st_ino == st->st_ino;
}

int sw_cli_check_outputs(const sw_cli_opts_t *o, FILE *in)
{
    struct stat st;
    /* Opening an output truncates it: it must be neither the log being
     * read nor the other output. */
    if (in && in != stdin && fstat(fileno(in), &st) == 0) {
        if (is_file(o->out_path, &st)) {
            sw_cli_error("--out %s: that is the log being read", o->out_path);
            return SW_EXIT_USAGE;
        }
        if (is_file(o->events_path, &st)) {
            sw_cli_error("--events %s: that is the log being read", o->events_path);
            return SW_EXIT_USAGE;
        }
    }
    if (o->out_path && o->events_path &&
        (!strcmp(o->out_path, o->events_path) ||
         (stat(o->out_path, &st) == 0 && is_file(o->events_path, &st)))) {
        sw_cli_error("--out and --events name the same file '%s'", o->out_path);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* ---- CSV writers ------------------------------------------------------------ */

void sw_cli_csv_text(FILE *f, const char *s)
{
    if (!strpbrk(s, ",;\t\"\r\n")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"') fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

/* A number field preceded by a comma; non-finite values stay empty. */
static void csv_num(FILE *f, double v, long *nonfinite)
{
    if (isfinite(v))
        fprintf(f, ",%.9g", v);
    else {
        fputc(',', f);
        (*nonfinite)++;
    }
}

static const char *pkg_name(const sw_scene_t *scenes, size_t n, size_t pkg)
{
    return pkg < n ? scenes[pkg].name : "?";
}

static FILE *open_out(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) sw_cli_error("%s: cannot create: %s", path, strerror(errno));
    return f;
}

/* Flush, close and report a write error on path; SW_EXIT_OK or SW_EXIT_IO. */
static int close_out(FILE *f, const char *path)
{
    if (!f) return SW_EXIT_OK;
    int bad = ferror(f);
    int saved = errno;
    if (fclose(f) != 0) {
        bad = 1;
        saved = errno;
    }
    if (bad) {
        sw_cli_error("%s: write failed: %s", path, strerror(saved));
        return SW_EXIT_IO;
    }
    return SW_EXIT_OK;
}

int sw_cli_states_open(sw_cli_states_t *w, const char *path, long every, const sw_scene_t *scenes,
                       size_t n)
{
    memset(w, 0, sizeof *w);
    w->path = path;
    w->scenes = scenes;
    w->n = n;
    w->every = every > 0 ? every : 1;
    if (!path) return SW_EXIT_OK;
    w->seen = calloc(n ? n : 1, sizeof *w->seen);
    if (!w->seen) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    w->f = open_out(path);
    if (!w->f) {
        free(w->seen);
        w->seen = NULL;
        return SW_EXIT_IO;
    }
    fputs("t,package,phase,theta,theta_dot,u,u_dot,z,z_dot,margin,margin_bound,uplift_ratio,a_g\n",
          w->f);
    return SW_EXIT_OK;
}

void sw_cli_states_write(sw_cli_states_t *w, const sw_output_t *o)
{
    if (!w->f) return;
    if (o->pkg < w->n && w->seen[o->pkg]++ % w->every != 0) return;
    const sw_state_t *s = &o->state;
    long *nf = &w->nonfinite;
    if (isfinite(o->t))
        fprintf(w->f, "%.9g,", o->t);
    else {
        fputc(',', w->f);
        (*nf)++;
    }
    sw_cli_csv_text(w->f, pkg_name(w->scenes, w->n, o->pkg));
    fprintf(w->f, ",%s", sw_phase_name(s->phase));
    csv_num(w->f, s->theta, nf);
    csv_num(w->f, s->theta_dot, nf);
    csv_num(w->f, s->u, nf);
    csv_num(w->f, s->u_dot, nf);
    csv_num(w->f, s->z, nf);
    csv_num(w->f, s->z_dot, nf);
    csv_num(w->f, o->margin, nf);
    csv_num(w->f, o->margin_bound, nf);
    csv_num(w->f, o->uplift_ratio, nf);
    csv_num(w->f, o->a_g, nf);
    fputc('\n', w->f);
    w->rows++;
}

int sw_cli_states_close(sw_cli_states_t *w)
{
    int rc = close_out(w->f, w->path);
    if (w->f && w->nonfinite)
        sw_cli_error("%s: %ld non-finite values written as empty fields", w->path, w->nonfinite);
    free(w->seen);
    w->seen = NULL;
    w->f = NULL;
    return rc;
}

int sw_cli_events_open(sw_cli_events_t *w, const char *path, const sw_scene_t *scenes, size_t n)
{
    memset(w, 0, sizeof *w);
    w->path = path;
    w->scenes = scenes;
    w->n = n;
    if (!path) return SW_EXIT_OK;
    w->f = open_out(path);
    if (!w->f) return SW_EXIT_IO;
    fputs("t,package,event,theta,theta_dot,margin,info\n", w->f);
    return SW_EXIT_OK;
}

void sw_cli_events_write(sw_cli_events_t *w, const sw_event_t *ev)
{
    if (!w->f) return;
    long *nf = &w->nonfinite;
    if (isfinite(ev->t))
        fprintf(w->f, "%.9g,", ev->t);
    else {
        fputc(',', w->f);
        (*nf)++;
    }
    sw_cli_csv_text(w->f, pkg_name(w->scenes, w->n, ev->pkg));
    fprintf(w->f, ",%s", sw_event_name(ev->kind));
    csv_num(w->f, ev->theta, nf);
    csv_num(w->f, ev->theta_dot, nf);
    csv_num(w->f, ev->margin, nf);
    csv_num(w->f, ev->info, nf);
    fputc('\n', w->f);
    w->rows++;
}

int sw_cli_events_close(sw_cli_events_t *w)
{
    int rc = close_out(w->f, w->path);
    if (w->f && w->nonfinite)
        sw_cli_error("%s: %ld non-finite values written as empty fields", w->path, w->nonfinite);
    w->f = NULL;
    return rc;
}

/* ---- summaries --------------------------------------------------------------- */

int sw_cli_any_overturned(const sw_engine_t *e)
{
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) == SW_OK && s.overturned) return 1;
    }
    return 0;
}

static double alpha_of(const sw_engine_t *e, size_t i)
{
    const sw_derived_t *d = sw_engine_derived(e, i);
    return d ? d->alpha : NAN;
}

/* "at 7.5123 s" or a fallback phrase when the time is absent. */
static void print_time(FILE *f, double t, const char *none)
{
    if (isfinite(t))
        fprintf(f, "%.4f s", t);
    else
        fputs(none, f);
}

void sw_cli_print_summary(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run)
{
    if (run->log) {
        fprintf(f, "log %s: %ld samples read, %ld accepted, %ld rejected", strcmp(run->log, "-") ? run->log : "(stdin)",
                run->samples_read, run->samples_read - run->samples_rejected,
                run->samples_rejected);
        if (run->settle > 0.0) fprintf(f, "; settle up to %g s after the end", run->settle);
        fputc('\n', f);
    }
    if (run->pulse) {
        const sw_pulse_t *p = run->pulse;
        fprintf(f, "pulse %s: amplitude %g m/s^2 (%.4g g), omega %g rad/s, %.6g s long; %.6g s "
                   "simulated\n",
                sw_pulse_shape_name(p->shape), p->amplitude, p->amplitude / 9.80665, p->omega,
                sw_pulse_duration(p), run->duration);
    }
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) != SW_OK) continue;
        double alpha = alpha_of(e, i);
        double dt = sw_engine_dt(e, i);
        fprintf(f, "\npackage %s: %s model, scheme %s, dt %.6g ms\n", s.name,
                sw_model_name(s.model), sw_engine_scheme(e), dt * 1e3);
        if (run->log)
            fprintf(f, "  samples         %ld read, %ld accepted, %ld rejected\n", run->samples_read,
                    run->samples_read - run->samples_rejected, run->samples_rejected);
        fputs("  first uplift    ", f);
        print_time(f, s.uplift_time, "none (never left the upright position)");
        if (s.uplifts > 1) fprintf(f, " (%ld uplifts in all)", s.uplifts);
        fprintf(f, "\n  impacts         %ld\n", s.impacts);
        fprintf(f, "  peak |theta|    %.3f deg = %.3f alpha (alpha = %.2f deg)\n",
                s.max_abs_theta * 180.0 / M_PI, s.max_theta_ratio, alpha * 180.0 / M_PI);
        fputs("  tipped (alpha)  ", f);
        print_time(f, s.tip_time, "no (|theta| stayed below alpha)");
        fprintf(f, "\n  minimum margin  %.4f (1 at rest, 0 at the edge of overturning)\n",
                s.min_margin);
        fputs("  outcome         ", f);
        if (s.overturned) {
            fputs("OVERTURNED at ", f);
            print_time(f, s.overturn_time, "an unknown time");
        } else {
            fputs("stayed upright", f);
        }
        if (s.faults) fprintf(f, " (%ld model faults: see --events)", s.faults);
        fputc('\n', f);
    }
}

void sw_cli_json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        switch (*p) {
        case '"': fputs("\\\"", f); break;
        case '\\': fputs("\\\\", f); break;
        case '\n': fputs("\\n", f); break;
        case '\r': fputs("\\r", f); break;
        case '\t': fputs("\\t", f); break;
        default:
            /* Other control characters escaped; bytes >= 0x80 pass as UTF-8. */
            if (*p < 0x20)
                fprintf(f, "\\u%04x", *p);
            else
                fputc(*p, f);
        }
    }
    fputc('"', f);
}

/* A JSON number, or null: JSON has no NaN or infinity. */
static void json_num(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.9g", v);
    else
        fputs("null", f);
}

void sw_cli_print_json(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run)
{
    fprintf(f, "{\n  \"swaywatch\": ");
    sw_cli_json_string(f, sw_version());
    fprintf(f, ",\n  \"log\": ");
    if (run->log)
        sw_cli_json_string(f, run->log);
    else
        fputs("null", f);
    if (run->pulse) {
        fprintf(f, ",\n  \"pulse\": {\"shape\": ");
        sw_cli_json_string(f, sw_pulse_shape_name(run->pulse->shape));
        fprintf(f, ", \"amplitude\": ");
        json_num(f, run->pulse->amplitude);
        fprintf(f, ", \"omega\": ");
        json_num(f, run->pulse->omega);
        fprintf(f, ", \"duration\": ");
        json_num(f, sw_pulse_duration(run->pulse));
        fprintf(f, "},\n  \"simulated\": ");
        json_num(f, run->duration);
    }
    if (run->log) {
        fprintf(f, ",\n  \"settle\": ");
        json_num(f, run->settle);
    }
    fprintf(f, ",\n  \"samples_read\": %ld,\n  \"samples_rejected\": %ld,\n  \"packages\": [",
            run->samples_read, run->samples_rejected);
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_summary_t s;
        if (sw_engine_summary(e, i, &s) != SW_OK) continue;
        fprintf(f, "%s\n    {\"name\": ", i ? "," : "");
        sw_cli_json_string(f, s.name);
        fprintf(f, ", \"model\": ");
        sw_cli_json_string(f, sw_model_name(s.model));
        fprintf(f, ", \"overturned\": %s", s.overturned ? "true" : "false");
        fprintf(f, ",\n     \"overturn_time\": ");
        json_num(f, s.overturn_time);
        fprintf(f, ", \"tip_time\": ");
        json_num(f, s.tip_time);
        fprintf(f, ", \"uplift_time\": ");
        json_num(f, s.uplift_time);
        fprintf(f, ",\n     \"max_abs_theta\": ");
        json_num(f, s.max_abs_theta);
        fprintf(f, ", \"max_theta_ratio\": ");
        json_num(f, s.max_theta_ratio);
        fprintf(f, ", \"alpha\": ");
        json_num(f, alpha_of(e, i));
        fprintf(f, ",\n     \"min_margin\": ");
        json_num(f, s.min_margin);
        fprintf(f, ", \"min_margin_bound\": ");
        json_num(f, s.min_margin_bound);
        fprintf(f, ", \"max_uplift_ratio\": ");
        json_num(f, s.max_uplift_ratio);
        fprintf(f, ",\n     \"impacts\": %ld, \"uplifts\": %ld, \"rests\": %ld, \"faults\": %ld",
                s.impacts, s.uplifts, s.rests, s.faults);
        fprintf(f, ",\n     \"samples_read\": %ld, \"samples_rejected\": %ld", run->samples_read,
                run->samples_rejected);
        fprintf(f, ",\n     \"scheme\": ");
        sw_cli_json_string(f, sw_engine_scheme(e));
        fprintf(f, ", \"dt\": ");
        json_num(f, sw_engine_dt(e, i));
        fprintf(f, ", \"steps\": %ld}", s.steps);
    }
    fprintf(f, "\n  ]\n}\n");
}
