/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lcmopts.c - the options of the LCM commands (lcmopts.h): the channels
 * and rate of what is published, and the checks on the samples taken; and
 * the refusal counts both commands print. */
#include "lcmopts.h"

#include <string.h>

#include "text.h"

void sw_cli_mon_opts_init(sw_mon_opts_t *mo)
{
    memset(mo, 0, sizeof *mo);
    mo->vertical = -1;
    mo->hysteresis = -1.0;
    mo->lat_axis = 1; /* y, left: accel_t's */
}

void sw_cli_print_rejected(FILE *f, const sw_mon_counts_t *k)
{
    const long total = sw_mon_rejected(k);
    fprintf(f, "rejected %ld", total);
    if (!total)
        return;
    const char *sep = " (";
    for (int r = 0; r < SW_MON_NREJ; r++)
        if (k->rejected[r]) {
            fprintf(f, "%s%s %ld", sep, sw_mon_reject_name((sw_mon_reject)r), k->rejected[r]);
            sep = ", ";
        }
    fputc(')', f);
}

static void print_place(FILE *f, const sw_auth_place_t *p)
{
    char chan[sizeof p->channel];
    sw_cli_term_text(chan, sizeof chan, p->channel, sizeof p->channel); /* off the bus */
    fprintf(f, "message %ld on %s, %s", p->where, chan, sw_auth_result_name(p->why));
    if (p->key_id)
        fprintf(f, " (key %d)", p->key_id);
}

void sw_cli_print_auth(FILE *f, const sw_auth_facts_t *a)
{
    const long refused = a->checked - a->refused[SW_AUTH_OK];
    fprintf(f, "authentication: %ld checked, %ld authentic, %ld refused", a->checked,
            a->refused[SW_AUTH_OK], refused);
    if (!refused)
        return;
    fputs(" (the first: ", f);
    print_place(f, &a->first);
    if (refused > 1) {
        fputs("; the last: ", f);
        print_place(f, &a->last);
    }
    fputc(')', f);
}

/* --axis x|y|z; --vertical also none (the row's value is 1). */
static int parse_axis(const sw_cli_option_t *o, const char *arg, void *dest)
{
    int *out = dest;
    if (o->value && !strcmp(arg, "none")) {
        *out = -1;
        return SW_EXIT_OK;
    }
    *out = sw_mon_axis_parse(arg);
    if (*out >= 0)
        return SW_EXIT_OK;
    sw_cli_error("--%s: expected x, y or z%s, got '%s'", o->long_name, o->value ? " or none" : "",
                 arg);
    return SW_EXIT_USAGE;
}

static int check_channel(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    /* LCM's limit on channel names. */
    if (!arg[0] || strlen(arg) > 63) {
        sw_cli_error("--%s: expected a channel name of 1 to 63 characters, got '%s'", o->long_name,
                     arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

#define MON(f) SW_CLI_AT(sw_mon_opts_t, f)

const sw_cli_option_t sw_cli_lcm_publish_options[] = {
    {SW_CLI_STRING, 0, "state-channel", "CHAN", MON(state_channel), .fn = check_channel,
     .help = "states (default " SW_MON_STATE_CHANNEL ")"},
    {SW_CLI_STRING, 0, "alarm-channel", "CHAN", MON(alarm_channel), .fn = check_channel,
     .help = "alarms (default " SW_MON_ALARM_CHANNEL ")"},
    {SW_CLI_DOUBLE, 0, "state-rate", "HZ", MON(state_rate), .rule = SW_NUM_NONNEGATIVE, .lo = 1e-3,
     .hi = 1e6, .what = "a rate in Hz >= 0 (0: every sample)",
     .help = "states per package per second of sample time (default 0: one per sample); from "
             "one per 1000 s to one per microsecond of utime"},
    {.kind = SW_CLI_END},
};

const sw_cli_option_t sw_cli_lcm_input_options[] = {
    {SW_CLI_CALL, 0, "axis", "x|y|z", MON(axis), .fn = parse_axis,
     .help = "message axis along the truck's travel (default x)"},
    {SW_CLI_CALL, 0, "lat-axis", "x|y|z|none", MON(lat_axis), .fn = parse_axis, .value = 1,
     .help = "message axis across the truck, to the left: it drives the lateral plane of the "
             "scenes that give package.depth (default y; none: one plane, along the truck)"},
    {SW_CLI_CALL, 0, "vertical", "x|y|z|none", MON(vertical), .fn = parse_axis, .value = 1,
     .help = "message axis used as vertical acceleration, up (say whether it includes gravity: "
             "--vert-includes-gravity or --vert-excludes-gravity; default none: gravity only)"},
    {SW_CLI_DOUBLE, 0, "max-skew", "SECONDS", MON(max_skew), .rule = SW_NUM_NONNEGATIVE, .lo = 1e-3,
     .hi = 1e9, .what = "a number of seconds >= 0 (0: not checked)",
     .help = "refuse samples whose utime is further than this from the time they arrived (live: "
             "the wall clock; a log: when lcm-logger received them; default: not checked)"},
    {.kind = SW_CLI_END},
};

int sw_cli_mon_lateral(sw_mon_opts_t *mo, const sw_scene_t *scenes, size_t n)
{
    int depth = 0;
    for (size_t k = 0; k < n; k++) depth |= sw_scene_has_depth(&scenes[k]);
    mo->lateral = depth && mo->lat_axis >= 0;
    if (!mo->lateral)
        return SW_EXIT_OK;
    static const char axes[] = "xyz";
    if (mo->lat_axis == mo->axis || mo->lat_axis == mo->vertical) {
        sw_cli_error(
            "--lat-axis %c is also the %s axis (--%s %c), and a scene gives package.depth: "
            "say which message axis is across the truck (--lat-axis x|y|z), or --lat-axis "
            "none for one plane along the truck",
            axes[mo->lat_axis], mo->lat_axis == mo->axis ? "longitudinal" : "vertical",
            mo->lat_axis == mo->axis ? "axis" : "vertical", axes[mo->lat_axis]);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

int sw_cli_mon_gate(sw_mon_opts_t *mo, const sw_cli_gate_t *g)
{
    if (mo->vertical >= 0 && g->vert_gravity < 0) {
        sw_cli_error(
            "--vertical: say whether that axis includes gravity (an accelerometer reads "
            "+1 g at rest): --vert-includes-gravity or --vert-excludes-gravity");
        return SW_EXIT_USAGE;
    }
    sw_gate_opts_t o;
    sw_cli_gate_opts(g, &o);
    mo->gap = o.gap;
    mo->gap_policy = o.gap_policy;
    mo->max_bridge = o.max_bridge;
    mo->max_accel = o.max_accel;
    mo->max_jump = o.jump;
    mo->confirm = o.confirm;
    mo->vert_gravity = o.vert_gravity;
    return SW_EXIT_OK;
}
