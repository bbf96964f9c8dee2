/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cmd_simulate.c - "swaywatch simulate": drive every package with a
 * half-sine or full-sine pulse of the bed (physics.md) and report the same
 * summary, state series and events as replay.
 *
 * The pulse is handed to the engine as a function of time, so the input is
 * exact (no sampling).  The engine reports state only per pushed sample, so
 * the state series is produced here by advancing in --sample-interval
 * increments and reading the state after each; --wide and --plot take
 * the same rows as --out. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clobber.h"
#include "figure.h"
#include "interrupt.h"
#include "opts.h"
#include "output.h"

#define FREE_PERIODS 20 /* rocking periods 2 pi / p after the pulse */
#define MAX_ROWS 1e8    /* --duration / --sample-interval */

/* simulate's own options. */
typedef struct {
    sw_pulse_t pulse;
    int have_shape, have_amp;
    const sw_cli_option_t *amp_opt; /* --amplitude or --amplitude-g, the last given */
    double pulse_duration;          /* s, --pulse-duration; 0: not given (--omega) */
    double duration, interval;
    int fail_on_overturn;
} sim_opts_t;

static int parse_shape(const sw_cli_option_t *o, const char *arg, void *dest)
{
    sim_opts_t *s = dest;
    s->have_shape = 1;
    if (sw_pulse_shape_parse(arg, &s->pulse.shape) == SW_OK)
        return SW_EXIT_OK;
    sw_cli_error("--%s: expected half-sine or full-sine, got '%s'", o->long_name, arg);
    return SW_EXIT_USAGE;
}

/* --amplitude with its unit (10g, 98.1m/s2; a bare number is m/s^2, as
 * it always was), --amplitude-g a bare number in g (the row's def is the
 * unit). */
static int parse_amplitude(const sw_cli_option_t *o, const char *arg, void *dest)
{
    sim_opts_t *s = dest;
    double a;
    int r =
        o->def == 1.0 ? sw_cli_opt_quantity(o, arg, 0, 1, &a, NULL) : sw_cli_opt_double(o, arg, &a);
    if (r != SW_EXIT_OK)
        return r;
    s->pulse.amplitude = o->def == 1.0 ? a : a * o->def;
    s->have_amp = 1;
    s->amp_opt = o;
    return r;
}

/* --pulse-duration: a time with its unit, always (11ms, 0.011s): a bare
 * number could be either, and reading ms as s makes a pulse 1000 times
 * too long. */
static int parse_pulse_duration(const sw_cli_option_t *o, const char *arg, void *dest)
{
    sim_opts_t *s = dest;
    return sw_cli_opt_quantity(o, arg, 1, 0, &s->pulse_duration, NULL);
}

#define SIM(f) SW_CLI_AT(sim_opts_t, f)

static const sw_cli_option_t sim_options[] = {
    {SW_CLI_SECTION, .help = "Pulse:"},
    {SW_CLI_CALL, 0, "pulse", "SHAPE", .fn = parse_shape,
     .help = "half-sine or full-sine (required)"},
    {SW_CLI_CALL, 0, "amplitude", "A", .fn = parse_amplitude, .def = 1.0, .rule = SW_NUM_NONZERO,
     .what = "a non-zero acceleration, e.g. -10g or -98.1m/s2",
     .help = "peak acceleration, sign included, with its unit: g or m/s2, e.g. -10g, -98.1m/s2 "
             "(a bare number is m/s^2; required, or --amplitude-g); |A| at most 1e5 m/s^2 "
             "(about 10,200 g), the most the engine takes from an accelerometer"},
    {SW_CLI_CALL, 0, "amplitude-g", "A", .fn = parse_amplitude, .def = SW_G0,
     .rule = SW_NUM_NONZERO, .what = "a non-zero acceleration in g",
     .help = "the same as a bare number in g (1 g = %g m/s^2)"},
    {SW_CLI_CALL, 0, "pulse-duration", "D", .fn = parse_pulse_duration, .rule = SW_NUM_POSITIVE,
     .what = "a positive time with its unit, e.g. 11ms or 0.011s",
     .help = "how long the pulse lasts, with its unit: ms, s or us, e.g. 11ms (a half-sine of 11 "
             "ms has W = pi/0.011 s; a full-sine W = 2 pi/D); instead of --omega, with W within "
             "--omega's range"},
    {SW_CLI_DOUBLE, 0, "omega", "W", SIM(pulse.omega), .rule = SW_NUM_POSITIVE, .lo = 1e-2,
     .hi = 1e5, .what = "a positive angular frequency in rad/s",
     .help = "rad/s, angular frequency of the sine (required, or --pulse-duration); below 0.01 "
             "the pulse lasts over 5 minutes, above 1e5 it is far shorter than a step"},
    {SW_CLI_DOUBLE, 0, "duration", "T", SIM(duration), .rule = SW_NUM_POSITIVE, .lo = 1e-6,
     .hi = 1e5, .what = "a positive number of seconds",
     .help = "s simulated from t = 0 (default: the pulse plus " SW_CLI_STR(
         FREE_PERIODS) " free "
                       "rocking periods 2 pi/p of the slowest package); the run stops early once "
                       "the pulse "
                       "is over and every package is at rest or has overturned; at most a day"},
    {SW_CLI_DOUBLE, 0, "sample-interval", "S", SIM(interval), .rule = SW_NUM_POSITIVE, .def = 0.001,
     .lo = 1e-6, .hi = 10, .what = "a positive number of seconds",
     .help = "s between rows of --out (default %g); at most " SW_CLI_STR(MAX_ROWS) " rows in "
                                                                                   "all"},
    {SW_CLI_FLAG, 0, "fail-on-overturn", SIM(fail_on_overturn), .value = 1,
     .help = "exit 1 if any package overturned"},
    {.kind = SW_CLI_END},
};

static const sw_cli_option_t sim_output_notes[] = {
    {SW_CLI_SECTION, .help = "Output:"},
    {SW_CLI_TEXT, .help = "\nsamples_read and samples_rejected are 0 in the JSON summary: there is "
                          "no log."},
    {.kind = SW_CLI_END},
};

static const sw_cli_command_t simulate_cmd = {
    .name = "simulate",
    .usage =
        "simulate --scene S.ini --pulse half-sine|full-sine\n"
        "                          --amplitude A --omega W|--pulse-duration D\n"
        "                          [--duration T] [options]",
    .about =
        "Drives every package with one acceleration pulse of the truck bed:\n"
        "  half-sine: a(t) = A sin(W t) for 0 <= t <= D = pi/W, then 0;\n"
        "  full-sine: a(t) = A sin(W t) for 0 <= t <= D = 2 pi/W, then 0.\n"
        "The pulse is evaluated exactly (not sampled).  x points forward: a negative A\n"
        "brakes and tips the top forward.  As a shock standard states it: a half-sine\n"
        "of 10 g lasting 11 ms is --pulse half-sine --amplitude -10g --pulse-duration\n"
        "11ms (braking).\n",
    .exits = SW_CLI_EXIT_OVERTURN,
};

/* Where the states and events go. */
typedef struct {
    sw_cli_events_t *events;
    sw_cli_states_t *states;
    sw_cli_wide_t *wide;
    sw_cli_figure_t *fig;
    sw_risk_t *risk;
} sim_ctx_t;

static void on_event(void *user, const sw_event_t *ev)
{
    sim_ctx_t *c = user;
    if (sw_cli_events_feed(c->events, c->risk, ev) & SW_SETTLE_REPORT)
        sw_cli_figure_event(c->fig, ev);
}

/* One state row per package at the engine's current time. */
static void write_states(sw_engine_t *e, sim_ctx_t *c)
{
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_output_t out;
        if (sw_engine_get_output(e, i, &out) != SW_OK)
            continue;
        sw_risk_output(c->risk, &out); /* first: the rows carry its reserve */
        sw_cli_states_write(c->states, &out);
        sw_cli_wide_write(c->wide, &out);
        sw_cli_figure_state(c->fig, &out);
    }
}

/* Nothing left to happen: every package overturned, or standing with no
 * way to lift again once the input has stopped (sw_model_settled); in
 * the default's run beside it too (sw_engine_checker), whose verdict is
 * still to come. */
static int all_settled(const sw_engine_t *e, const sw_scene_t *scenes)
{
    if (sw_engine_checker(e) && !all_settled(sw_engine_checker(e), scenes))
        return 0;
    for (size_t i = 0; i < sw_engine_count(e); i++) {
        sw_output_t out;
        if (sw_engine_get_output(e, i, &out) != SW_OK)
            return 0;
        if (!sw_model_settled(sw_engine_derived(e, i), scenes[i].g, &out.state))
            return 0;
    }
    return 1;
}

/* The pulse is whole, and within what an accelerometer reads; omega from
 * --pulse-duration (pulse.h: a half-sine lasts pi/omega, a full-sine
 * 2 pi/omega). */
static int check_pulse(sim_opts_t *so)
{
    if (so->pulse.omega > 0.0 && so->pulse_duration > 0.0) {
        sw_cli_error("simulate: --omega and --pulse-duration say the same thing: give one");
        return SW_EXIT_USAGE;
    }
    if (so->have_shape && so->pulse_duration > 0.0)
        so->pulse.omega =
            (so->pulse.shape == SW_PULSE_FULL_SINE ? 2.0 * M_PI : M_PI) / so->pulse_duration;
    if (!so->have_shape || !so->have_amp || !(so->pulse.omega > 0.0)) {
        sw_cli_error("simulate: missing %s; see 'swaywatch simulate --help'",
                     !so->have_shape ? "--pulse half-sine|full-sine"
                     : !so->have_amp ? "--amplitude A (e.g. -10g or -98.1m/s2)"
                                     : "--omega W (rad/s) or --pulse-duration D (e.g. 11ms)");
        return SW_EXIT_USAGE;
    }
    /* A duration is an omega: the same bounds as --omega's. */
    const sw_cli_option_t *w = sim_options;
    while (w->kind != SW_CLI_END && !(w->long_name && !strcmp(w->long_name, "omega"))) w++;
    if (so->pulse_duration > 0.0 && w->kind != SW_CLI_END &&
        !(so->pulse.omega >= w->lo && so->pulse.omega <= w->hi)) {
        const double k = so->pulse.shape == SW_PULSE_FULL_SINE ? 2.0 * M_PI : M_PI;
        sw_cli_error(
            "--pulse-duration: out of range: a %s of omega %g to %g rad/s lasts %g to "
            "%g s, got %g s",
            sw_pulse_shape_name(so->pulse.shape), w->lo, w->hi, k / w->hi, k / w->lo,
            so->pulse_duration);
        return SW_EXIT_USAGE;
    }
    /* The limit sw_engine_push() puts on samples; the pulse reaches the
     * engine as a function, unchecked, and beyond it the outputs overflow. */
    if (!(fabs(so->pulse.amplitude) <= SW_MAX_ACCEL)) {
        sw_cli_error(
            "--%s: the pulse amplitude is beyond any accelerometer: expected at most %g "
            "m/s^2 (about %.0f g)",
            so->amp_opt->long_name, SW_MAX_ACCEL, SW_MAX_ACCEL / SW_G0);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* Drive the engine with the pulse, a state row every --sample-interval,
 * until --duration or until nothing can happen any more; *t_end gets the
 * time reached.  SW_EXIT_OK, or SW_EXIT_USAGE (reported) if the engine
 * stopped. */
static int run_pulse(sw_engine_t *e, const sw_scene_t *scenes, sim_opts_t *so, sim_ctx_t *states,
                     double *t_end)
{
    const double t_pulse = sw_pulse_duration(&so->pulse);
    double duration = so->duration;
    if (duration <= 0.0) {
        double p_min = INFINITY;
        for (size_t i = 0; i < sw_engine_count(e); i++) {
            const sw_derived_t *d = sw_engine_derived(e, i);
            if (d && d->p > 0.0 && d->p < p_min)
                p_min = d->p;
        }
        duration = t_pulse + (isfinite(p_min) ? FREE_PERIODS * 2.0 * M_PI / p_min : 0.0);
    }
    if (duration / so->interval > MAX_ROWS) {
        sw_cli_error(
            "simulate: %g s in steps of --sample-interval %g s is more than %g steps; "
            "give a larger --sample-interval or a shorter --duration",
            duration, so->interval, MAX_ROWS);
        return SW_EXIT_USAGE;
    }
    /* Whole steps of the interval from t = 0, computed from the index so
     * rounding does not accumulate over a long run.  The pulse's end is a
     * kink of the input: sw_pulse_advance stops the engine there exactly
     * (no row), as sw_pulse_run does, so that no step straddles it (one
     * across it lost the scheme's order: 1e-7 rad where --accuracy asked
     * for 1e-10). */
    double t = 0.0;
    write_states(e, states);
    for (long k = 1; t < duration && !sw_cli_signal; k++) {
        double t1 = fmin((double)k * so->interval, duration);
        const int ar = sw_pulse_advance(e, t1, &so->pulse);
        if (ar < 0) {
            sw_cli_error("simulate: engine stopped at t = %g s: %s", t, sw_strerror(ar));
            return SW_EXIT_USAGE;
        }
        t = t1;
        write_states(e, states);
        if (t >= t_pulse && all_settled(e, scenes))
            break;
    }
    sw_engine_finish(e, 0.0);
    *t_end = t;
    return SW_EXIT_OK;
}

/* The output files: none an input or another output, at most one on
 * standard output. */
static int check_files(const sw_cli_opts_t *o)
{
    const sw_cli_file_t outputs[] = {{"--out", o->out_path},
                                     {"--events", o->events_path},
                                     {"--wide", o->wide_path},
                                     {"--plot", o->plot_path}};
    int rc = sw_cli_check_run_files(NULL, &o->scenes, outputs, 4);
    if (rc != SW_EXIT_OK)
        return rc;
    rc = sw_cli_check_outputs(o->out_path, o->events_path, NULL, o->json, o->quiet);
    if (rc != SW_EXIT_OK)
        return rc;
    const char *const names[] = {"--out", "--events", "--wide"};
    const char *const paths[] = {o->out_path, o->events_path, o->wide_path};
    return sw_cli_check_stdout(names, paths, 3, o->json, o->quiet);
}

/* The writers, the figure and the reserve, for the n packages of e. */
static int open_outputs(const sw_cli_opts_t *o, const sw_engine_t *e, const sw_scene_t *scenes,
                        size_t n, sim_ctx_t *ctx)
{
    int rc = sw_cli_states_open(ctx->states, o->out_path, o->every, NULL, scenes, n);
    if (rc != SW_EXIT_OK)
        return rc;
    if ((rc = sw_cli_events_open(ctx->events, o->events_path, NULL, scenes, n)) != SW_EXIT_OK)
        return rc;
    rc = sw_cli_wide_open(ctx->wide, o->wide_path, o->every, e, scenes, n);
    if (rc != SW_EXIT_OK)
        return rc;
    if (o->plot_path && !(ctx->fig = sw_cli_figure_create(e, scenes, n)))
        return SW_EXIT_IO;
    if (!(ctx->risk = sw_cli_risk_create(o, scenes, n)))
        return SW_EXIT_USAGE;
    ctx->states->risk = ctx->wide->risk = ctx->risk; /* after open, which clears them */
    ctx->events->all_impacts = o->all_impacts;
    return SW_EXIT_OK;
}

/* The end of the run: the files closed, the summary, the figure. */
static int conclude(const sw_cli_opts_t *o, const sw_engine_t *e, size_t n, sim_ctx_t *ctx,
                    const sw_cli_run_t *run)
{
    sw_cli_events_finish(ctx->events, ctx->risk, n);
    int rc = sw_cli_states_close(ctx->states);
    int rc2 = sw_cli_events_close(ctx->events);
    if (rc == SW_EXIT_OK)
        rc = rc2;
    rc2 = sw_cli_wide_close(ctx->wide);
    if (rc == SW_EXIT_OK)
        rc = rc2;
    if (o->json && sw_cli_print_json(stdout, e, run) != SW_EXIT_OK)
        rc = SW_EXIT_IO;
    else if (!o->json && !o->quiet)
        sw_cli_print_summary(stdout, e, run);
    if (rc == SW_EXIT_OK && ctx->fig) {
        const sw_pulse_t *pulse = run->pulse;
        char title[256];
        snprintf(title, sizeof title, "swaywatch simulate: %s pulse, %.4g g, %.4g ms%s",
                 sw_pulse_shape_name(pulse->shape), pulse->amplitude / SW_G0,
                 sw_pulse_duration(pulse) * 1e3, run->interrupted ? " (interrupted)" : "");
        rc = sw_cli_figure_draw(ctx->fig, o->plot_path, title);
    }
    return rc;
}

int cmd_simulate(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    sw_cli_opts_t o = {0};
    sim_opts_t so = {0};
    sw_scene_t *scenes = NULL;
    size_t n = 0;
    sw_engine_t *e = NULL;
    sw_cli_states_t states = {0};
    sw_cli_events_t events = {0};
    sw_cli_wide_t wide = {0};
    sim_ctx_t ctx = {&events, &states, &wide, NULL, NULL};
    sw_cli_group_t groups[] = {
        SW_CLI_GROUP(sim_options, &so),
        SW_CLI_GROUP(sw_cli_scene_options, &o),
        SW_CLI_GROUP(sw_cli_integration_options, &o),
        SW_CLI_GROUP(sw_cli_accuracy_options, &o),
        SW_CLI_GROUP(sw_cli_reserve_options, &o),
        SW_CLI_GROUP(sw_cli_output_options, &o),
        SW_CLI_GROUP(sw_cli_picture_options, &o),
        SW_CLI_GROUP(sim_output_notes, NULL),
        SW_CLI_GROUP_IN(sw_cli_common_options, &o, "Output:"),
    };
    const size_t ng = sizeof groups / sizeof groups[0];
    sw_pulse_t *pulse = &so.pulse;

    int first;
    if ((rc = sw_cli_parse(&simulate_cmd, groups, ng, argc, argv, &first)) != SW_CLI_CONTINUE)
        goto out;
    rc = SW_EXIT_USAGE;
    if (sw_cli_no_operand("simulate", argc, argv, first) != SW_EXIT_OK)
        goto out;
    if ((rc = sw_cli_interrupt_install()) != SW_EXIT_OK)
        goto out;
    rc = SW_EXIT_USAGE;
    if (check_pulse(&so) != SW_EXIT_OK)
        goto out;

    if ((rc = check_files(&o)) != SW_EXIT_OK)
        goto out;
    rc = sw_cli_load_scenes(&o, &scenes, &n);
    if (rc != SW_EXIT_OK)
        goto out;

    sw_engine_opts_t eo;
    sw_cli_engine_opts(&o, &eo);
    eo.check_default = 1; /* a chosen scheme or dt: its verdict checked (summary.c) */
    if ((rc = sw_cli_resolve_accuracy(&o, scenes, n, &eo)) != SW_EXIT_OK)
        goto out;
    eo.on_event = on_event;
    eo.user = &ctx;
    rc = SW_EXIT_USAGE;
    e = sw_cli_engine_create(scenes, n, &eo);
    if (!e)
        goto out;
    if (o.verbose)
        sw_cli_print_derived(stderr, e, scenes, n);

    if ((rc = open_outputs(&o, e, scenes, n, &ctx)) != SW_EXIT_OK)
        goto out;
    double t = 0.0;
    if ((rc = run_pulse(e, scenes, &so, &ctx, &t)) != SW_EXIT_OK)
        goto out;

    const sw_cli_run_t run = {
        .pulse = pulse, .duration = t, .interrupted = sw_cli_signal, .risk = ctx.risk};
    rc = conclude(&o, e, n, &ctx, &run);
    if (rc == SW_EXIT_OK)
        rc = sw_cli_verdict_exit(e, NULL, so.fail_on_overturn);
    if (run.interrupted) {
        sw_cli_error(
            "simulate: interrupted by %s at t = %g s; the output files end with the "
            "last whole row",
            sw_cli_signal_name(run.interrupted), t);
        if (rc != SW_EXIT_IO)
            rc = sw_cli_interrupt_code();
    }
out:
    sw_cli_states_close(&states);
    sw_cli_events_close(&events);
    sw_cli_wide_close(&wide);
    sw_cli_figure_destroy(ctx.fig);
    sw_risk_destroy(ctx.risk);
    sw_engine_destroy(e);
    free(scenes);
    sw_cli_parse_free(groups, ng);
    return rc;
}
