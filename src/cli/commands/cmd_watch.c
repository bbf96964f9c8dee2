/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cmd_watch.c - "swaywatch watch": a live view of the monitor's messages
 * in a terminal (ncurses), for a person at the vehicle: every package's
 * tilt as a share of its tipping angle (a bar), its margin, phase and
 * state rate, the health of the input and the last alarms.  lcm-spy does
 * the like for any LCM type but does not start on Debian 12 (Java 17).
 *
 * It subscribes to the state and alarm channels (raw, decoding itself:
 * LCM's generated subscription prints on stderr, under the screen, for a
 * message it cannot decode, and counts nothing) and keeps, per package,
 * the last state.  Input health comes from what the messages carry: the
 * state rate and the lag of the states behind the wall clock (sensor
 * clock against this computer's), states and alarms lost on the way (their
 * seq), the monitor's refusals (INPUT_REJECTED alarms: "... rejected:
 * REASON (N so far)") and its sensor gaps (SENSOR_GAP).
 *
 * alpha, the tipping angle, is not in state_t: it comes from the package's
 * scene file (--scene, matched by name) or, for a package on the bed (the
 * bare model, whose uplift_ratio is |a_g| / (g tan alpha)), from its states
 * (with standard gravity).  A frame or cushion package without its scene
 * shows theta without the bar.
 *
 * One thread: poll() on LCM's file descriptor and standard input, woken at
 * least REDRAW_HZ times a second to draw.  On a terminal the screen is
 * redrawn REDRAW_HZ times a second, 'q' quits, a resize redraws at the new
 * size; otherwise (or with --once) plain text snapshots go to standard
 * output.  Everything shown is ASCII but for names and texts (UTF-8; control
 * characters are shown as '?').
 *
 * This file holds the options, the loop and the command; what has been
 * seen and its view have files of their own (watch.h). */
#include <curses.h>
#include <errno.h>
#include <lcm/lcm.h>
#include <locale.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lcmlog.h"
#include "monitor.h"
#include "opts.h"
#include "watch.h"

/* ---- options ------------------------------------------------------------------ */

static int check_channel(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    if (!arg[0] || strlen(arg) > 63) { /* LCM's limit on channel names */
        sw_cli_error("--%s: expected a channel regex of 1 to 63 characters, got '%s'", o->long_name,
                     arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

#define WO(f) SW_CLI_AT(watch_opts_t, f)

static const sw_cli_option_t watch_lcm_options[] = {
    {SW_CLI_SECTION, .help = "LCM:"},
    {SW_CLI_STRING, 'l', "lcm-url", "URL", WO(url),
     .help = "LCM URL (default: $LCM_DEFAULT_URL, else LCM's default, "
             "udpm://239.255.76.67:7667?ttl=0)"},
    {SW_CLI_STRING, 0, "state-channel", "REGEX", WO(state_channel), .fn = check_channel,
     .help = "states: a name or an anchored regex, as LCM subscribes (default " SW_MON_STATE_CHANNEL
             ")"},
    {SW_CLI_STRING, 0, "alarm-channel", "REGEX", WO(alarm_channel), .fn = check_channel,
     .help = "alarms (default " SW_MON_ALARM_CHANNEL ")"},
    {.kind = SW_CLI_END},
};

static const sw_cli_option_t watch_scene_options[] = {
    {SW_CLI_SECTION, .help = "Scene:"},
    {SW_CLI_LIST, 's', "scene", "FILE", SW_CLI_AT(sw_cli_opts_t, scenes),
     .help = "a scene the monitor watches (repeatable, optional): its package's tipping "
             "angle alpha, for the bar"},
    {SW_CLI_TEXT,
     .help = "\nWithout its scene, a package on the bed (bare model) gets alpha from its\n"
             "states (their uplift_ratio, with standard gravity); a package on a frame or\n"
             "cushion shows theta in degrees and no bar."},
    {.kind = SW_CLI_END},
};

static const sw_cli_option_t watch_output_options[] = {
    {SW_CLI_SECTION, .help = "Output:"},
    {SW_CLI_FLAG, 0, "once", WO(once), .value = 1,
     .help = "listen for --wait seconds, print one plain snapshot on stdout, exit"},
    {SW_CLI_DOUBLE, 0, "wait", "SECONDS", WO(wait), .rule = SW_NUM_POSITIVE, .def = 2.0,
     .what = "a positive number of seconds", .help = "how long --once listens (default %g)"},
    {SW_CLI_DOUBLE, 0, "every", "SECONDS", WO(every), .rule = SW_NUM_POSITIVE, .def = 10.0,
     .what = "a positive number of seconds",
     .help = "when stdout is not a terminal: a plain snapshot every SECONDS (default %g)"},
    {SW_CLI_LONG, 0, "alarms", "N", WO(alarms), .min = 1, .max = 100, .def = 8,
     .what = "a number of alarms from 1 to 100",
     .help = "the last N alarms are shown (default %g)"},
    {SW_CLI_HELP, 'h', "help", .help = "this help"},
    {SW_CLI_TEXT,
     .help = "\nOn a terminal the view is redrawn " SW_CLI_STR(
         REDRAW_HZ) " times a second, at its "
                    "size; q quits.\n"
                    "Per package: model, phase, |theta|/alpha as a bar (| marks the peak so far) "
                    "and\n"
                    "as a number, theta, margin (1 at rest, 0 at the edge of overturning), states\n"
                    "per second; a package with no state for " SW_CLI_STR(
                        STALE) " s says so.\n"
                               "Input: states per second and their lag behind this computer's "
                               "clock (the\n"
                               "sensor's clock against it), samples the monitor refused (by "
                               "reason, from its\n"
                               "INPUT_REJECTED alarms), sensor gaps, states and alarms lost on the "
                               "way here\n"
                               "(their seq).  Then the last alarms, newest first.  Not on a "
                               "terminal, or with\n"
                               "--once, the same view is printed as plain text."},
    {.kind = SW_CLI_END},
};

static const sw_cli_command_t watch_cmd = {
    .name = "watch",
    .usage = "watch [-l URL] [--scene S.ini ...] [--once] [options]",
    .about =
        "Live view of the monitor's states and alarms on the LCM bus (swaywatch.state_t\n"
        "on SWAY_STATE, swaywatch.alarm_t on SWAY_ALARM), in the terminal: every\n"
        "package's tilt against its tipping angle, margin and phase, the input's\n"
        "health and the last alarms.  Runs until q, SIGINT or SIGTERM.\n",
    .exit_text =
        "Exit codes: 0 ok (q, SIGINT, SIGTERM, or --once done), 2 bad usage or bad\n"
        "scene, 3 LCM could not be set up (URL, network) or a scene file could not be\n"
        "read.\n",
};

/* ---- the loop ------------------------------------------------------------------- */

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig)
{
    stop_signal = sig;
}

/* Handle what LCM has queued, without waiting. */
static int drain(lcm_t *lcm)
{
    for (int i = 0; i < 4 * STATE_QUEUE; i++) {
        int r = lcm_handle_timeout(lcm, 0);
        if (r < 0)
            return -1;
        if (r == 0)
            break;
    }
    return 0;
}

/* Until q, a signal, or (once) the wait: wake for LCM, keys and the next
 * draw.  curses: the screen, else plain snapshots every `every` s. */
static int run(lcm_t *lcm, watch_t *w, int curses)
{
    const double period = curses ? 1.0 / REDRAW_HZ : w->o->once ? w->o->wait : w->o->every;
    const double end = w->o->once ? w->start + w->o->wait : INFINITY;
    double next = sw_watch_mono_now() + (curses ? 0.0 : period);
    const int fd = lcm_get_fileno(lcm);
    const int keys = curses && isatty(STDIN_FILENO); /* else poll() would see EOF at once */
    while (!stop_signal) {
        double now = sw_watch_mono_now();
        double due = fmin(fmin(next, end), w->win_start + 1.0);
        int timeout = due <= now ? 0 : (int)ceil((due - now) * 1e3);
        struct pollfd p[2] = {{.fd = fd, .events = POLLIN}, {.fd = STDIN_FILENO, .events = POLLIN}};
        int r = poll(p, keys ? 2 : 1, timeout);
        if (r < 0 && errno != EINTR) {
            sw_cli_error("watch: poll: %s", strerror(errno));
            return SW_EXIT_IO;
        }
        if (r > 0 && (p[0].revents & POLLIN) && drain(lcm) != 0) {
            sw_cli_error("watch: lcm_handle failed");
            return SW_EXIT_IO;
        }
        now = sw_watch_mono_now();
        sw_watch_window(w, now);
        int redraw = now >= next;
        for (int ch; curses && (ch = getch()) != ERR;) {
            if (ch == 'q' || ch == 'Q')
                return SW_EXIT_OK;
            if (ch == KEY_RESIZE || ch == 12 /* ^L */)
                redraw = 1;
        }
        if (w->o->once && now >= end)
            break;
        if (redraw) {
            if (curses)
                sw_watch_screen_draw(w);
            else
                sw_watch_plain_snapshot(w);
            next = now + period;
        }
    }
    if (!curses && w->o->once)
        sw_watch_plain_snapshot(w);
    return SW_EXIT_OK;
}

/* The terminal for curses, or NULL (not a terminal, or one curses cannot
 * drive: then plain snapshots). */
static SCREEN *screen_open(void)
{
    if (!isatty(STDOUT_FILENO))
        return NULL;
    setlocale(LC_CTYPE, ""); /* UTF-8 names; numbers stay in the C locale */
    SCREEN *s = newterm(NULL, stdout, stdin);
    if (!s) {
        sw_cli_error("watch: the terminal '%s' cannot be driven; plain text instead",
                     getenv("TERM") ? getenv("TERM") : "");
        return NULL;
    }
    set_term(s);
    cbreak();
    noecho();
    nodelay(stdscr, TRUE);
    keypad(stdscr, TRUE);
    curs_set(0);
    return s;
}

/* ---- the command ------------------------------------------------------------------ */

/* alpha of every --scene (validated as the monitor does): along the truck
 * at k, across it at n + k (NaN without a depth). */
static int scene_alphas(const sw_cli_opts_t *so, sw_scene_t **scenes, size_t *n, double **alpha)
{
    *scenes = NULL;
    *n = 0;
    *alpha = NULL;
    if (so->scenes.n == 0)
        return SW_EXIT_OK;
    int rc = sw_cli_load_scenes(so, scenes, n);
    if (rc != SW_EXIT_OK)
        return rc;
    if (!(*alpha = calloc(2 * *n, sizeof **alpha))) {
        sw_cli_error("watch: out of memory");
        return SW_EXIT_IO;
    }
    for (size_t k = 0; k < *n; k++) {
        sw_derived_t d;
        sw_scene_validate(&(*scenes)[k], &d, NULL, NULL, NULL);
        (*alpha)[k] = d.alpha;
        sw_scene_t lat;
        (*alpha)[*n + k] = NAN;
        if (sw_scene_has_depth(&(*scenes)[k]) && sw_scene_lateral(&(*scenes)[k], &lat) == SW_OK &&
            sw_scene_validate(&lat, &d, NULL, NULL, NULL) == SW_OK)
            (*alpha)[*n + k] = d.alpha;
    }
    return SW_EXIT_OK;
}

int cmd_watch(int argc, char **argv)
{
    watch_opts_t o = {.state_channel = SW_MON_STATE_CHANNEL, .alarm_channel = SW_MON_ALARM_CHANNEL};
    sw_cli_opts_t so = {0};
    sw_cli_group_t g[] = {
        SW_CLI_GROUP(watch_lcm_options, &o),
        SW_CLI_GROUP(watch_scene_options, &so),
        SW_CLI_GROUP(watch_output_options, &o),
    };
    const size_t ng = sizeof g / sizeof g[0];
    sw_scene_t *scenes = NULL;
    double *alpha = NULL;
    size_t n = 0;
    lcm_t *lcm = NULL;
    lcm_subscription_t *s1 = NULL, *s2 = NULL;
    SCREEN *screen = NULL;
    watch_t *w = calloc(1, sizeof *w);
    int first, rc = sw_cli_parse(&watch_cmd, g, ng, argc, argv, &first);
    if (rc != SW_CLI_CONTINUE)
        goto out;
    if ((rc = sw_cli_no_operand("watch", argc, argv, first)) != SW_EXIT_OK ||
        (rc = scene_alphas(&so, &scenes, &n, &alpha)) != SW_EXIT_OK)
        goto out;
    rc = SW_EXIT_IO;
    if (!w || !(w->ring = calloc((size_t)o.alarms, sizeof *w->ring))) {
        sw_cli_error("watch: out of memory");
        goto out;
    }
    w->o = &o;
    w->scenes = scenes;
    w->scene_alpha = alpha;
    w->scene_alpha_lat = alpha ? alpha + n : NULL;
    w->nscenes = n;
    w->start = w->win_start = sw_watch_mono_now();
    w->rate = w->lag = NAN;
    /* A file:// URL: LCM's reader trusts the log, ours checks it first. */
    if ((rc = sw_cli_check_lcm_url("watch", o.url)) != SW_EXIT_OK)
        goto out;
    rc = SW_EXIT_IO;
    if (!(lcm = lcm_create(o.url))) {
        sw_cli_error("watch: cannot set up LCM with %s (udpm needs a route for 224.0.0.0/4)",
                     o.url && o.url[0] ? o.url : "the default URL");
        goto out;
    }
    if ((rc = sw_watch_subscribe(lcm, w, &s1, &s2)) != SW_EXIT_OK)
        goto out;
    struct sigaction sa = {.sa_handler = on_signal};
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    if (!o.once)
        screen = screen_open();
    rc = run(lcm, w, screen != NULL);
out:
    if (screen) {
        endwin();
        delscreen(screen);
    }
    if (s1)
        lcm_unsubscribe(lcm, s1);
    if (s2)
        lcm_unsubscribe(lcm, s2);
    if (lcm)
        lcm_destroy(lcm);
    if (w)
        free(w->ring);
    free(w);
    free(alpha);
    free(scenes);
    sw_cli_parse_free(g, ng);
    return rc;
}
