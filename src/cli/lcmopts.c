/* lcmopts.c - the options of the LCM commands (lcmopts.h): the channels
 * and rate of what is published, and the checks on the samples taken; and
 * the refusal counts both commands print. */
#include "lcmopts.h"

#include <string.h>

void sw_cli_mon_opts_init(sw_mon_opts_t *mo)
{
    memset(mo, 0, sizeof *mo);
    mo->vertical = -1;
    mo->hysteresis = -1.0;
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

/* "--max-accel 30g" or "--max-accel 294.2" (m/s^2). */
static int parse_accel_limit(const sw_cli_option_t *o, const char *arg, void *dest)
{
    double *out = dest;
    const char *given = arg;
    char buf[64];
    size_t len = strlen(arg);
    double scale = 1.0;
    if (len > 0 && len < sizeof buf && arg[len - 1] == 'g') {
        memcpy(buf, arg, len - 1);
        buf[len - 1] = '\0';
        arg = buf;
        scale = SW_G0;
    }
    /* the bounds (m/s^2) apply once the value is in m/s^2 */
    sw_cli_option_t unbounded = *o;
    unbounded.lo = unbounded.hi = 0.0;
    if (sw_cli_opt_double(&unbounded, arg, out) != SW_EXIT_OK)
        return SW_EXIT_USAGE;
    *out *= scale;
    return sw_cli_opt_range(o, given, *out);
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
        sw_cli_error("--%s: expected a channel name of 1 to 63 characters, got '%s'",
                     o->long_name, arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

/* --max-jump 0 takes any jump at once (monitor.h: max_jump < 0). */
static int check_max_jump(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)o;
    (void)arg;
    double *v = dest;
    if (*v == 0.0) *v = -1.0;
    return SW_EXIT_OK;
}

#define MON(f) SW_CLI_AT(sw_mon_opts_t, f)

const sw_cli_option_t sw_cli_lcm_publish_options[] = {
    {SW_CLI_STRING, 0, "state-channel", "CHAN", MON(state_channel), .fn = check_channel,
     .help = "states (default " SW_MON_STATE_CHANNEL ")"},
    {SW_CLI_STRING, 0, "alarm-channel", "CHAN", MON(alarm_channel), .fn = check_channel,
     .help = "alarms (default " SW_MON_ALARM_CHANNEL ")"},
    {SW_CLI_DOUBLE, 0, "state-rate", "HZ", MON(state_rate), .rule = SW_NUM_NONNEGATIVE,
     .lo = 1e-3, .hi = 1e6, .what = "a rate in Hz >= 0 (0: every sample)",
     .help = "states per package per second of sample time (default 0: one per sample); from "
             "one per 1000 s to one per microsecond of utime"},
    {SW_CLI_END},
};

const sw_cli_option_t sw_cli_lcm_input_options[] = {
    {SW_CLI_CALL, 0, "axis", "x|y|z", MON(axis), .fn = parse_axis,
     .help = "message axis along the truck's travel (default x)"},
    {SW_CLI_CALL, 0, "vertical", "x|y|z|none", MON(vertical), .fn = parse_axis, .value = 1,
     .help = "message axis used as vertical acceleration (up, gravity removed; default none: "
             "gravity only)"},
    {SW_CLI_CALL, 0, "max-accel", "A", MON(max_accel), .fn = parse_accel_limit,
     .rule = SW_NUM_POSITIVE, .lo = 0.1, .hi = SW_MAX_ACCEL,
     .what = "a positive acceleration in m/s^2, or in g with a g suffix",
     .help = "refuse samples with any axis beyond A, in m/s^2 or with a g suffix, e.g. 30g "
             "(default 50g); at most the engine's own limit on samples, in m/s^2"},
    {SW_CLI_DOUBLE, 0, "max-skew", "SECONDS", MON(max_skew), .rule = SW_NUM_NONNEGATIVE,
     .lo = 1e-3, .hi = 1e9, .what = "a number of seconds >= 0 (0: not checked)",
     .help = "refuse samples whose utime is further than this from the time they arrived (live: "
             "the wall clock; a log: when lcm-logger received them; default: not checked)"},
    {SW_CLI_DOUBLE, 0, "max-jump", "SECONDS", MON(max_jump), .rule = SW_NUM_NONNEGATIVE,
     .def = SW_MON_MAX_JUMP, .fn = check_max_jump, .lo = 1e-6, .hi = 1e8,
     .what = "a number of seconds >= 0 (0: take any jump)",
     .help = "hold a sample whose utime is further than this after the last one until the next "
             "sample confirms it (default %g; 0: take any jump at once); beyond years one sample "
             "could move the clock by years"},
    {SW_CLI_DOUBLE, 0, "gap", "SECONDS", MON(gap), .rule = SW_NUM_POSITIVE, .def = SW_MON_GAP,
     .lo = 1e-4, .hi = 86400, .what = "a positive number of seconds",
     .help = "sensor gap threshold: samples further apart raise SENSOR_GAP (default %g); at "
             "most a day"},
    {SW_CLI_END},
};
