/* cmd_simulate.c - "swaywatch simulate": drive every package with a
 * half-sine or full-sine pulse of the bed (physics.md) and report the same
 * summary, state series and events as replay.
 *
 * The pulse is handed to the engine as a function of time, so the input is
 * exact (no sampling).  The engine reports state only per pushed sample, so
 * the state series is produced here by advancing in --sample-interval
 * increments and reading the state after each. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "opts.h"
#include "output.h"

#define STANDARD_GRAVITY 9.80665   /* m/s^2, for --amplitude-g */
#define DEFAULT_INTERVAL 1e-3      /* s, --sample-interval */
#define FREE_PERIODS 20.0          /* rocking periods 2 pi / p after the pulse */

enum {
    OPT_PULSE = SW_OPT_FIRST_OWN,
    OPT_AMPLITUDE,
    OPT_AMPLITUDE_G,
    OPT_OMEGA,
    OPT_DURATION,
    OPT_INTERVAL,
    OPT_FAIL_ON_OVERTURN
};

static const struct option long_opts[] = {
    SW_CLI_COMMON_LONGOPTS,
    {"pulse", required_argument, NULL, OPT_PULSE},
    {"amplitude", required_argument, NULL, OPT_AMPLITUDE},
    {"amplitude-g", required_argument, NULL, OPT_AMPLITUDE_G},
    {"omega", required_argument, NULL, OPT_OMEGA},
    {"duration", required_argument, NULL, OPT_DURATION},
    {"sample-interval", required_argument, NULL, OPT_INTERVAL},
    {"fail-on-overturn", no_argument, NULL, OPT_FAIL_ON_OVERTURN},
    {NULL, 0, NULL, 0},
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: swaywatch simulate --scene S.ini --pulse half-sine|full-sine\n"
            "                          --amplitude A --omega W [--duration T] [options]\n"
            "\n"
            "Drives every package with one acceleration pulse of the truck bed:\n"
            "  half-sine: a(t) = A sin(W t) for 0 <= t <= pi/W, then 0;\n"
            "  full-sine: a(t) = A sin(W t) for 0 <= t <= 2 pi/W, then 0.\n"
            "The pulse is evaluated exactly (not sampled).  x points forward: a negative A\n"
            "brakes and tips the top forward.\n"
            "\n"
            "Pulse:\n"
            "      --pulse SHAPE        half-sine or full-sine (required)\n"
            "      --amplitude A        m/s^2, sign included (required, or --amplitude-g)\n"
            "      --amplitude-g A      the same in g (1 g = 9.80665 m/s^2)\n"
            "      --omega W            rad/s, angular frequency of the sine (required)\n"
            "      --duration T         s simulated from t = 0 (default: the pulse plus %g free\n"
            "                           rocking periods 2 pi/p of the slowest package); the run\n"
            "                           stops early once the pulse is over and every package is\n"
            "                           at rest or has overturned\n"
            "      --sample-interval S  s between rows of --out (default %g)\n"
            "      --fail-on-overturn   exit 1 if any package overturned\n"
            "\n",
            FREE_PERIODS, DEFAULT_INTERVAL);
    sw_cli_print_common_help(f);
    fprintf(f, "\nsamples_read and samples_rejected are 0 in the JSON summary: there is no log.\n");
    sw_cli_print_exit_help(f, 1, 0);
}

typedef struct {
    sw_cli_events_t *events;
} sim_ctx_t;

static void on_event(void *user, const sw_event_t *ev)
{
    sim_ctx_t *c = user;
    sw_cli_events_write(c->events, ev);
}

/* One state row per package at the engine's current time. */
static void write_states(sw_engine_t *e, sw_cli_states_t *w)
{
    if (!w->f) return;
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_output_t out;
        if (sw_engine_get_output(e, i, &out) == SW_OK) sw_cli_states_write(w, &out);
    }
}

/* Nothing left to happen: every package at rest or overturned. */
/* Every package overturned, or standing with no way to lift again once the
 * input has stopped.  A stuck package on a frame is settled only when the
 * bearing's remaining energy E = u'^2/2 + w^2 u^2/2 (per unit mass, which
 * damping only lowers) cannot drive the support's acceleration
 * |A| = |2 z w u' + w^2 u| <= (2 z w + w) sqrt(2 E) up to the uplift
 * threshold g tan(alpha). */
static int all_settled(const sw_engine_t *e)
{
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_output_t out;
        if (sw_engine_get_output(e, i, &out) != SW_OK) return 0;
        if (out.state.phase == SW_PHASE_OVERTURNED) continue;
        if (out.state.phase == SW_PHASE_ROCKING) return 0;
        const sw_derived_t *d = sw_engine_derived(e, i);
        if (d->model == SW_MODEL_FRAME) {
            const double w = d->omega_b, u = out.state.u, v = out.state.u_dot;
            const double E = 0.5 * v * v + 0.5 * w * w * u * u; /* J/kg */
            const double g = d->p * d->p * 4.0 * d->R / 3.0;    /* m/s^2 */
            if ((2.0 * d->zeta_b * w + w) * sqrt(2.0 * E) >= g * tan(d->alpha)) return 0;
        }
    }
    return 1;
}

int cmd_simulate(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    sw_cli_opts_t o;
    sw_pulse_t pulse = {0};
    int have_shape = 0, have_amp = 0, have_omega = 0, fail_on_overturn = 0;
    const char *amp_opt = "--amplitude";
    double duration = 0.0, interval = DEFAULT_INTERVAL, amp_g = 0.0;
    sw_scene_t *scenes = NULL;
    size_t n = 0;
    sw_engine_t *e = NULL;
    sw_cli_states_t states = {0};
    sw_cli_events_t events = {0};
    sim_ctx_t ctx = {&events};

    if (sw_cli_opts_init(&o, argc) != SW_EXIT_OK) return SW_EXIT_IO;
    int c;
    while ((c = sw_cli_getopt(&o, argc, argv,
                              SW_CLI_COMMON_SHORTOPTS, long_opts, NULL, NULL, 0, usage)) > 0) {
        int r = SW_EXIT_OK;
        switch (c) {
        case OPT_PULSE:
            r = sw_pulse_shape_parse(optarg, &pulse.shape) == SW_OK ? SW_EXIT_OK : SW_EXIT_USAGE;
            if (r != SW_EXIT_OK)
                sw_cli_error("--pulse: expected half-sine or full-sine, got '%s'", optarg);
            have_shape = 1;
            break;
        case OPT_AMPLITUDE:
            r = sw_cli_parse_double("--amplitude", optarg, SW_NUM_NONZERO,
                                    "a non-zero acceleration in m/s^2", &pulse.amplitude);
            have_amp = 1;
            amp_opt = "--amplitude";
            break;
        case OPT_AMPLITUDE_G:
            r = sw_cli_parse_double("--amplitude-g", optarg, SW_NUM_NONZERO,
                                    "a non-zero acceleration in g", &amp_g);
            pulse.amplitude = amp_g * STANDARD_GRAVITY;
            have_amp = 1;
            amp_opt = "--amplitude-g";
            break;
        case OPT_OMEGA:
            r = sw_cli_parse_double("--omega", optarg, SW_NUM_POSITIVE,
                                    "a positive angular frequency in rad/s", &pulse.omega);
            have_omega = 1;
            break;
        case OPT_DURATION:
            r = sw_cli_parse_double("--duration", optarg, SW_NUM_POSITIVE,
                                    "a positive number of seconds", &duration);
            break;
        case OPT_INTERVAL:
            r = sw_cli_parse_double("--sample-interval", optarg, SW_NUM_POSITIVE,
                                    "a positive number of seconds", &interval);
            break;
        case OPT_FAIL_ON_OVERTURN: fail_on_overturn = 1; break;
        default: sw_cli_error("simulate: unhandled option"); r = SW_EXIT_USAGE;
        }
        if (r != SW_EXIT_OK) goto out;
    }
    if (c != SW_CLI_OPT_END) {
        if (c == SW_CLI_OPT_HELP) rc = SW_EXIT_OK;
        goto out;
    }
    if (optind < argc) {
        sw_cli_error("simulate: unexpected argument '%s'; see 'swaywatch simulate --help'",
                     argv[optind]);
        goto out;
    }
    if (!have_shape || !have_amp || !have_omega) {
        sw_cli_error("simulate: missing %s; see 'swaywatch simulate --help'",
                     !have_shape ? "--pulse half-sine|full-sine"
                     : !have_amp ? "--amplitude A (m/s^2) or --amplitude-g A"
                                 : "--omega W (rad/s)");
        goto out;
    }
    /* The limit sw_engine_push() puts on samples; the pulse reaches the
     * engine as a function, unchecked, and beyond it the outputs overflow. */
    if (!(fabs(pulse.amplitude) <= SW_MAX_ACCEL)) {
        sw_cli_error("%s: the pulse amplitude is beyond any accelerometer: expected at most %g "
                     "m/s^2 (about %.0f g)",
                     amp_opt, SW_MAX_ACCEL, SW_MAX_ACCEL / STANDARD_GRAVITY);
        goto out;
    }

    rc = sw_cli_check_outputs(o.out_path, o.events_path, NULL);
    if (rc != SW_EXIT_OK) goto out;
    rc = sw_cli_load_scenes(&o, &scenes, &n);
    if (rc != SW_EXIT_OK) goto out;

    sw_engine_opts_t eo;
    sw_cli_engine_opts(&o, &eo);
    if ((rc = sw_cli_resolve_accuracy(&o, scenes, n, &eo)) != SW_EXIT_OK) goto out;
    eo.on_event = on_event;
    eo.user = &ctx;
    rc = SW_EXIT_USAGE;
    e = sw_cli_engine_create(scenes, n, &eo);
    if (!e) goto out;
    if (o.verbose) sw_cli_print_derived(stderr, e, scenes, n);

    double t_pulse = sw_pulse_duration(&pulse);
    if (duration <= 0.0) {
        double p_min = INFINITY;
        for (size_t i = 0; i < n; i++) {
            const sw_derived_t *d = sw_engine_derived(e, i);
            if (d && d->p > 0.0 && d->p < p_min) p_min = d->p;
        }
        duration = t_pulse + (isfinite(p_min) ? FREE_PERIODS * 2.0 * M_PI / p_min : 0.0);
    }

    rc = sw_cli_states_open(&states, o.out_path, o.every, scenes, n);
    if (rc != SW_EXIT_OK) goto out;
    rc = sw_cli_events_open(&events, o.events_path, scenes, n);
    if (rc != SW_EXIT_OK) goto out;

    /* Whole steps of the interval from t = 0, computed from the index so
     * rounding does not accumulate over a long run. */
    double t = 0.0;
    write_states(e, &states);
    for (long k = 1; t < duration; k++) {
        double t1 = fmin((double)k * interval, duration);
        int ar = sw_engine_advance_fn(e, t1, sw_pulse_eval, &pulse);
        if (ar < 0) {
            sw_cli_error("simulate: engine stopped at t = %g s: %s", t, sw_strerror(ar));
            rc = SW_EXIT_USAGE;
            goto out;
        }
        t = t1;
        write_states(e, &states);
        if (t >= t_pulse && all_settled(e)) break;
    }
    sw_engine_finish(e, 0.0);

    rc = sw_cli_states_close(&states);
    int rc2 = sw_cli_events_close(&events);
    if (rc == SW_EXIT_OK) rc = rc2;

    sw_cli_run_t run = {.pulse = &pulse, .duration = t};
    if (o.json)
        sw_cli_print_json(stdout, e, &run);
    else if (!o.quiet)
        sw_cli_print_summary(stdout, e, &run);
    if (rc == SW_EXIT_OK && fail_on_overturn && sw_cli_any_overturned(e)) rc = SW_EXIT_OVERTURNED;
out:
    sw_cli_states_close(&states);
    sw_cli_events_close(&events);
    sw_engine_destroy(e);
    free(scenes);
    sw_cli_opts_fini(&o);
    return rc;
}
