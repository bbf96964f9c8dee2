/* cmd_replay.c - "swaywatch replay": run a recorded acceleration log (CSV
 * file, standard input, or an lcm-logger file) through the model of every
 * package and report whether, when and how close each came to overturning.
 *
 * The log is streamed in fixed chunks through the CSV reader into the
 * engine, so memory does not grow with the length of the log. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eventlog.h"
#include "input.h"
#include "opts.h"
#include "output.h"

#define DEFAULT_SETTLE 30.0     /* s of zero input after the end of the log */

enum { OPT_SETTLE = SW_OPT_FIRST_OWN, OPT_FAIL_ON_OVERTURN };

static const struct option long_opts[] = {
    SW_CLI_COMMON_LONGOPTS,
    SW_CLI_CSV_LONGOPTS,
    {"settle", required_argument, NULL, OPT_SETTLE},
    {"fail-on-overturn", no_argument, NULL, OPT_FAIL_ON_OVERTURN},
    SW_CLI_LCMLOG_LONGOPTS,
    {NULL, 0, NULL, 0},
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: swaywatch replay LOG --scene S.ini [--scene T.ini ...] [options]\n"
            "\n"
            "Replays a recorded acceleration log of the truck bed through the rocking model of\n"
            "each package and reports whether, when and how close it came to overturning.\n"
            "LOG is a CSV file, '-' for standard input, or an lcm-logger file (recognised by\n"
            "its first bytes; needs a build with LCM).\n"
            "\n");
    sw_cli_print_csv_help(f);
    fprintf(f,
            "\n"
            "Run:\n"
            "      --settle SECONDS     after the log ends, go on with zero acceleration for up to\n"
            "                           this long, or until every package is at rest or has\n"
            "                           overturned (default %g; 0: stop at the end of the log)\n"
            "      --fail-on-overturn   exit 1 if any package overturned\n"
            "\n",
            DEFAULT_SETTLE);
#ifdef SW_HAVE_LCM
    sw_cli_print_lcmlog_help(f);
    fputc('\n', f);
#endif
    sw_cli_print_common_help(f);
    fprintf(f, "\nWith --quiet, rejected rows are only counted (one line on stderr).\n");
    sw_cli_print_exit_help(f, 1, 1);
}

typedef struct {
    sw_engine_t *e;
    sw_cli_states_t *states;
    sw_cli_events_t *events;
    sw_cli_rejects_t rej;
    long refused_line; /* a row the engine refused, awaiting its report */
    int refused_rc;
    long engine_refused; /* rows the CSV layer accepted and the engine did not */
} replay_ctx_t;

static int on_row(void *user, long line, double t, double a_g, double a_z)
{
    replay_ctx_t *c = user;
    if (c->rej.stop) return 1; /* --strict: nothing after the first bad row counts */
    int rc = sw_engine_push(c->e, t, a_g, a_z);
    if (rc >= 0) return 0;
    /* The CSV layer already checks order and finiteness, so this should not
     * happen; if it does the row is counted as rejected all the same. */
    c->engine_refused++;
    c->refused_line = line;
    c->refused_rc = rc;
    return 1;
}

static void on_reject(void *user, long line, const char *reason)
{
    replay_ctx_t *c = user;
    if (c->refused_line && line == c->refused_line) {
        char buf[160];
        snprintf(buf, sizeof buf, "sample refused by the engine: %s", sw_strerror(c->refused_rc));
        c->refused_line = 0;
        sw_cli_rejects_add(&c->rej, line, buf);
        return;
    }
    sw_cli_rejects_add(&c->rej, line, reason);
}

/* An engine refusal the CSV layer did not pass back through on_reject. */
static void flush_refusal(void *user)
{
    replay_ctx_t *c = user;
    if (!c->refused_line) return;
    long line = c->refused_line;
    on_reject(c, line, "");
}

static void on_state(void *user, const sw_output_t *out)
{
    replay_ctx_t *c = user;
    sw_cli_states_write(c->states, out);
}

static void on_event(void *user, const sw_event_t *ev)
{
    replay_ctx_t *c = user;
    sw_cli_events_write(c->events, ev);
}

int cmd_replay(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    sw_cli_opts_t o;
    sw_cli_csv_opts_t copts;
    sw_cli_csv_opts_init(&copts);
    double settle = DEFAULT_SETTLE;
    int fail_on_overturn = 0;
    const char *log = NULL;
    int lcm_only = 0; /* an option only lcm-logger files take */
    char **orig = NULL;
    sw_cli_logfile_t lf = {0};
    sw_scene_t *scenes = NULL;
    size_t n = 0;
    sw_engine_t *e = NULL;
    sw_csv_t *csv = NULL;
    sw_cli_states_t states = {0};
    sw_cli_events_t events = {0};
    replay_ctx_t ctx = {0};

    if (sw_cli_opts_init(&o, argc) != SW_EXIT_OK) return SW_EXIT_IO;
    /* getopt_long permutes argv; an lcm-logger file is handed the
     * arguments as typed. */
    orig = malloc(((size_t)argc + 1) * sizeof *orig);
    if (!orig) {
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
        goto out;
    }
    memcpy(orig, argv, ((size_t)argc + 1) * sizeof *orig);

    const sw_cli_group_t groups[] = {{sw_cli_csv_option, &copts}};
    int c;
    while ((c = sw_cli_getopt(&o, argc, argv, SW_CLI_COMMON_SHORTOPTS, long_opts, NULL, groups, 1,
                              usage)) > 0) {
        int r = SW_EXIT_OK;
        switch (c) {
        case OPT_SETTLE:
            r = sw_cli_parse_double("--settle", optarg, SW_NUM_NONNEGATIVE,
                                    "a number of seconds >= 0", &settle);
            break;
        case OPT_FAIL_ON_OVERTURN: fail_on_overturn = 1; break;
        default:
            if (c >= SW_OPT_LCM_CHANNEL && c < SW_OPT_LCM_END) { /* read by lcmlog.c */
                lcm_only = c;
                break;
            }
            sw_cli_error("replay: unhandled option");
            r = SW_EXIT_USAGE;
        }
        if (r != SW_EXIT_OK) goto out;
    }
    if (c != SW_CLI_OPT_END) {
        if (c == SW_CLI_OPT_HELP) rc = SW_EXIT_OK;
        goto out;
    }
    if (!(log = sw_cli_log_operand("replay", argc, argv))) goto out;

    /* Open the log first: a missing file is an I/O error (3) whatever else
     * is wrong, and the first bytes decide CSV or lcm-logger. */
    if (sw_cli_logfile_open(&lf, log) != SW_EXIT_OK) {
        rc = SW_EXIT_IO;
        goto out;
    }
    ctx.rej = (sw_cli_rejects_t){.name = lf.name, .quiet = o.quiet, .strict = copts.strict};
    if (sw_lcmlog_sniff(lf.buf, lf.len)) {
        if (lf.in == stdin) {
            sw_cli_error("%s: an lcm-logger file cannot be read from standard input; give its "
                         "file name",
                         lf.name);
            goto out;
        }
        sw_cli_logfile_close(&lf);
#ifdef SW_HAVE_LCM
        rc = sw_cli_replay_lcmlog(log, argc, orig);
#else
        sw_cli_error("%s: lcm-logger files need the LCM build", log);
        rc = SW_EXIT_USAGE;
#endif
        goto out;
    }

    if (lcm_only) {
        const char *name = "?";
        for (const struct option *op = long_opts; op->name; op++)
            if (op->val == lcm_only) name = op->name;
        sw_cli_error("%s: option '--%s' is for lcm-logger files, and this is a CSV log", lf.name,
                     name);
        rc = SW_EXIT_USAGE;
        goto out;
    }
    rc = sw_cli_check_outputs(o.out_path, o.events_path, lf.in);
    if (rc != SW_EXIT_OK) goto out;
    rc = sw_cli_load_scenes(&o, &scenes, &n);
    if (rc != SW_EXIT_OK) goto out;

    sw_engine_opts_t eo;
    sw_cli_engine_opts(&o, &eo);
    if ((rc = sw_cli_resolve_accuracy(&o, scenes, n, &eo)) != SW_EXIT_OK) goto out;
    eo.on_event = on_event;
    eo.on_state = o.out_path ? on_state : NULL;
    eo.user = &ctx;
    rc = SW_EXIT_USAGE;
    e = sw_cli_engine_create(scenes, n, &eo);
    if (!e) goto out;
    ctx.e = e;
    if (o.verbose) sw_cli_print_derived(stderr, e, scenes, n);

    rc = sw_cli_states_open(&states, o.out_path, o.every, scenes, n);
    if (rc != SW_EXIT_OK) goto out;
    rc = sw_cli_events_open(&events, o.events_path, scenes, n);
    if (rc != SW_EXIT_OK) goto out;
    ctx.states = &states;
    ctx.events = &events;

    int err = 0;
    char msg[256] = "";
    csv = sw_csv_create(&copts.csv, on_row, on_reject, &ctx, &err, msg, sizeof msg);
    if (!csv) {
        sw_cli_error("%s: %s", lf.name, msg[0] ? msg : sw_strerror(err));
        rc = SW_EXIT_USAGE;
        goto out;
    }

    int fr;
    rc = sw_cli_logfile_pump(&lf, csv, &ctx.rej.stop, flush_refusal, &ctx, &fr);
    if (rc != SW_EXIT_OK) goto out;
    rc = SW_EXIT_USAGE;
    if (fr < 0) {
        /* The reader reports why through on_reject where it can (e.g. the
         * header line lacking a named column); this names the failure. */
        sw_cli_error("%s: %s", lf.name,
                     fr == SW_ENOTFOUND ? "a column given by name is not in the header"
                                        : sw_strerror(fr));
        rc = fr == SW_ENOMEM ? SW_EXIT_IO : SW_EXIT_USAGE;
        goto out;
    }
    if (ctx.rej.stop) {
        sw_cli_error("%s: stopped at the first rejected row (--strict)", lf.name);
        rc = SW_EXIT_USAGE;
        goto out;
    }

    sw_csv_counts_t counts;
    sw_csv_counts(csv, &counts);
    long rejected = counts.rejected;
    /* Rows the engine refused are normally counted by the reader too (the
     * consumer's non-zero return); make sure they are never lost. */
    if (rejected < ctx.rej.reported) rejected = ctx.rej.reported;
    sw_cli_rejects_summary(&ctx.rej);
    if (counts.rows - rejected <= 0) {
        sw_cli_error("%s: no usable samples (%ld data rows, %ld rejected)", lf.name, counts.rows,
                     rejected);
        rc = SW_EXIT_USAGE;
        goto out;
    }

    sw_engine_finish(e, settle);

    rc = sw_cli_states_close(&states);
    int rc2 = sw_cli_events_close(&events);
    if (rc == SW_EXIT_OK) rc = rc2;

    sw_cli_run_t run = {
        .log = log,
        .samples_read = counts.rows,
        .samples_rejected = rejected,
        .settle = settle,
    };
    if (o.json)
        sw_cli_print_json(stdout, e, &run);
    else if (!o.quiet)
        sw_cli_print_summary(stdout, e, &run);
    if (rc == SW_EXIT_OK && fail_on_overturn && sw_cli_any_overturned(e)) rc = SW_EXIT_OVERTURNED;
out:
    sw_csv_destroy(csv);
    sw_cli_states_close(&states);
    sw_cli_events_close(&events);
    sw_engine_destroy(e);
    free(scenes);
    sw_cli_logfile_close(&lf);
    free(orig);
    sw_cli_opts_fini(&o);
    return rc;
}
