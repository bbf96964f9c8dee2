/* lcmopts.c - options shared by the LCM commands (lcmopts.h). */
#include "lcmopts.h"

#include <string.h>

#include "opts.h"

/* "--max-accel 30g" or "--max-accel 294.2" (m/s^2). */
static int parse_accel_limit(const char *arg, double *out)
{
    char buf[64];
    size_t len = strlen(arg);
    double scale = 1.0;
    if (len > 0 && len < sizeof buf && arg[len - 1] == 'g') {
        memcpy(buf, arg, len - 1);
        buf[len - 1] = '\0';
        arg = buf;
        scale = SW_G0;
    }
    if (sw_cli_parse_double("--max-accel", arg, SW_NUM_POSITIVE,
                            "a positive acceleration in m/s^2, or in g with a g suffix",
                            out) != SW_EXIT_OK)
        return SW_EXIT_USAGE;
    *out *= scale;
    return SW_EXIT_OK;
}

static int parse_axis(const char *opt, const char *arg, int allow_none, int *out)
{
    if (allow_none && !strcmp(arg, "none")) {
        *out = -1;
        return SW_EXIT_OK;
    }
    *out = sw_mon_axis_parse(arg);
    if (*out >= 0)
        return SW_EXIT_OK;
    sw_cli_error("%s: expected x, y or z%s, got '%s'", opt, allow_none ? " or none" : "", arg);
    return SW_EXIT_USAGE;
}

static int parse_channel(const char *opt, const char *arg, const char **out)
{
    /* LCM's limit on channel names. */
    if (!arg[0] || strlen(arg) > 63) {
        sw_cli_error("%s: expected a channel name of 1 to 63 characters, got '%s'", opt, arg);
        return SW_EXIT_USAGE;
    }
    *out = arg;
    return SW_EXIT_OK;
}

int sw_cli_mon_option(void *opts, int c, const char *arg)
{
    sw_mon_opts_t *mo = opts;
    switch (c) {
        case SW_OPT_LCM_STATE_CHANNEL:
            return parse_channel("--state-channel", arg, &mo->state_channel);
        case SW_OPT_LCM_ALARM_CHANNEL:
            return parse_channel("--alarm-channel", arg, &mo->alarm_channel);
        case SW_OPT_LCM_STATE_RATE:
            return sw_cli_parse_double("--state-rate", arg, SW_NUM_NONNEGATIVE,
                                       "a rate in Hz >= 0 (0: every sample)", &mo->state_rate);
        case SW_OPT_LCM_AXIS: return parse_axis("--axis", arg, 0, &mo->axis);
        case SW_OPT_LCM_VERTICAL: return parse_axis("--vertical", arg, 1, &mo->vertical);
        case SW_OPT_LCM_GAP:
            return sw_cli_parse_double("--gap", arg, SW_NUM_POSITIVE,
                                       "a positive number of seconds", &mo->gap);
        case SW_OPT_LCM_MAX_ACCEL: return parse_accel_limit(arg, &mo->max_accel);
        case SW_OPT_LCM_MAX_SKEW:
            return sw_cli_parse_double("--max-skew", arg, SW_NUM_NONNEGATIVE,
                                       "a number of seconds >= 0 (0: not checked)", &mo->max_skew);
        case SW_OPT_LCM_MAX_JUMP: {
            int r = sw_cli_parse_double("--max-jump", arg, SW_NUM_NONNEGATIVE,
                                        "a number of seconds >= 0 (0: take any jump)",
                                        &mo->max_jump);
            if (r == SW_EXIT_OK && mo->max_jump == 0.0) mo->max_jump = -1.0; /* monitor.h: any */
            else if (r == SW_EXIT_OK && !(mo->max_jump < 1e9)) {
                sw_cli_error("--max-jump: expected at most 1e9 s, got '%s'", arg);
                r = SW_EXIT_USAGE;
            }
            return r;
        }
        default: return -1;
    }
}
