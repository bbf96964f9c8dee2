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
 * characters are shown as '?'). */
#include <curses.h>
#include <errno.h>
#include <lcm/lcm.h>
#include <limits.h>
#include <locale.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "journal.h"
#include "monitor.h"
#include "opts.h"
#include "swaywatch_alarm_t.h"
#include "swaywatch_state_t.h"

#define REDRAW_HZ 4
#define MAX_PKG 64        /* packages shown; more are counted */
#define MAX_REASONS 16    /* refusal reasons told apart */
#define STATE_QUEUE 20000 /* LCM queue of the state subscription: 2 s of 10 packages at 1 kHz */
#define STALE 2.0         /* s without a state: said so */
#define PLAIN_WIDTH 100   /* columns of a plain snapshot */
#define MAX_COLS 512
#define MAX_ROWS 256

/* state_t has a reserve column when the build's state_t.lcm has reserve_g
 * (CMake defines SW_STATE_HAS_RESERVE). */
#ifdef SW_STATE_HAS_RESERVE
#define RESERVE_OF(s) ((s)->reserve_g)
#define HAVE_RESERVE 1
#else
#define RESERVE_OF(s) ((void)(s), NAN)
#define HAVE_RESERVE 0
#endif

/* ---- options ------------------------------------------------------------------ */

typedef struct {
    const char *url;
    const char *state_channel, *alarm_channel;
    int once;
    double wait;  /* s, --once listens this long */
    double every; /* s between plain snapshots */
    long alarms;  /* last alarms shown */
} watch_opts_t;

static int check_channel(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    if (!arg[0] || strlen(arg) > 63) { /* LCM's limit on channel names */
        sw_cli_error("--%s: expected a channel regex of 1 to 63 characters, got '%s'",
                     o->long_name, arg);
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
     .help = "states: a name or an anchored regex, as LCM subscribes (default "
             SW_MON_STATE_CHANNEL ")"},
    {SW_CLI_STRING, 0, "alarm-channel", "REGEX", WO(alarm_channel), .fn = check_channel,
     .help = "alarms (default " SW_MON_ALARM_CHANNEL ")"},
    {SW_CLI_END},
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
    {SW_CLI_END},
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
     .help = "\nOn a terminal the view is redrawn " SW_CLI_STR(REDRAW_HZ) " times a second, at its "
             "size; q quits.\n"
             "Per package: model, phase, |theta|/alpha as a bar (| marks the peak so far) and\n"
             "as a number, theta, margin (1 at rest, 0 at the edge of overturning), states\n"
             "per second; a package with no state for " SW_CLI_STR(STALE) " s says so.\n"
             "Input: states per second and their lag behind this computer's clock (the\n"
             "sensor's clock against it), samples the monitor refused (by reason, from its\n"
             "INPUT_REJECTED alarms), sensor gaps, states and alarms lost on the way here\n"
             "(their seq).  Then the last alarms, newest first.  Not on a terminal, or with\n"
             "--once, the same view is printed as plain text."},
    {SW_CLI_END},
};

static const sw_cli_command_t watch_cmd = {
    .name = "watch",
    .usage = "watch [-l URL] [--scene S.ini ...] [--once] [options]",
    .about = "Live view of the monitor's states and alarms on the LCM bus (swaywatch.state_t\n"
             "on SWAY_STATE, swaywatch.alarm_t on SWAY_ALARM), in the terminal: every\n"
             "package's tilt against its tipping angle, margin and phase, the input's\n"
             "health and the last alarms.  Runs until q, SIGINT or SIGTERM.\n",
    .exit_text = "Exit codes: 0 ok (q, SIGINT, SIGTERM, or --once done), 2 bad usage or bad\n"
                 "scene, 3 LCM could not be set up (URL, network) or a scene file could not be\n"
                 "read.\n",
};

/* ---- what has been seen --------------------------------------------------------- */

typedef struct {
    char name[SW_NAME_MAX];
    swaywatch_state_t last;
    double rx;      /* monotonic s at the arrival of the last state */
    double alpha;   /* rad; NaN: not known */
    int alpha_from; /* 0 unknown, 1 the scene, 2 inferred from the states */
    double peak;    /* largest |theta| / alpha so far */
    long win;       /* states in the current window */
    double rate;    /* states/s over the last window */
} pkg_view_t;

typedef struct {
    int64_t wall_us; /* when it arrived */
    swaywatch_alarm_t a;
} alarm_view_t;

typedef struct {
    char name[24];
    long so_far; /* the monitor's count, from its latest alarm of this reason */
} reason_t;

typedef struct {
    const watch_opts_t *o;
    const sw_scene_t *scenes; /* --scene, for alpha */
    const double *scene_alpha;
    size_t nscenes;

    pkg_view_t pkg[MAX_PKG];
    size_t npkg;
    long pkg_overflow; /* states of packages beyond MAX_PKG */

    alarm_view_t *ring; /* the last o->alarms alarms */
    size_t ring_n, ring_next;

    long states, alarms, undecodable;
    int64_t state_seq, alarm_seq; /* last seen */
    int have_state_seq, have_alarm_seq;
    long lost_states, lost_alarms, seq_restarts;
    reason_t reason[MAX_REASONS];
    size_t nreasons;
    long gaps;
    int gap_open; /* the monitor said no sample arrives, and nothing has come since */

    double start, last_rx; /* monotonic s: start, last state */
    double win_start;      /* the rate and lag window */
    long win_states;
    double win_lag_sum;
    double rate, lag; /* the last window's: states/s, mean lag (s); NaN: none yet */
} watch_t;

static double mono_now(void)
{
    return sw_mon_clock();
}

static int64_t wall_now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* An int8_t[cap] text of a message as a C string: NUL-terminated, control
 * characters as '?'. */
static void msg_text(char *dst, const int8_t *src, size_t cap)
{
    size_t i = 0;
    for (; i + 1 < cap && src[i]; i++) {
        unsigned char c = (unsigned char)src[i];
        dst[i] = c < 0x20 || c == 0x7f ? '?' : (char)c;
    }
    dst[i] = '\0';
}

/* Messages lost between last and seq (the publisher's counter); a seq at or
 * before last is a publisher that started again. */
static void count_seq(int64_t seq, int64_t *last, int *have, long *lost, long *restarts)
{
    if (*have) {
        if (seq <= *last) {
            (*restarts)++;
        } else {
            unsigned long long d = (unsigned long long)seq - (unsigned long long)*last - 1;
            *lost += d > (unsigned long long)(LONG_MAX / 2) ? LONG_MAX / 2 : (long)d;
            if (*lost > LONG_MAX / 2)
                *lost = LONG_MAX / 2;
        }
    }
    *last = seq;
    *have = 1;
}

static pkg_view_t *find_pkg(watch_t *w, const char *name)
{
    for (size_t i = 0; i < w->npkg; i++)
        if (!strcmp(w->pkg[i].name, name))
            return &w->pkg[i];
    if (w->npkg == MAX_PKG)
        return NULL;
    pkg_view_t *p = &w->pkg[w->npkg++];
    memset(p, 0, sizeof *p);
    snprintf(p->name, sizeof p->name, "%s", name);
    p->alpha = NAN;
    p->rate = NAN;
    for (size_t k = 0; k < w->nscenes; k++)
        if (!strcmp(w->scenes[k].name, name)) {
            p->alpha = w->scene_alpha[k];
            p->alpha_from = 1;
        }
    return p;
}

/* alpha of a bare package from one of its states: uplift_ratio =
 * |a_g| / (g tan alpha).  Only from a state that says enough. */
static void infer_alpha(pkg_view_t *p, const swaywatch_state_t *s)
{
    if (p->alpha_from == 1 || s->model != SWAYWATCH_STATE_T_MODEL_BARE)
        return;
    if (!(s->uplift_ratio > 1e-3) || !(fabs(s->a_g) > 1e-2) || !isfinite(s->a_g))
        return;
    double a = atan(fabs(s->a_g) / (SW_G0 * s->uplift_ratio));
    if (isfinite(a) && a > 0.0 && a < M_PI_2) {
        p->alpha = a;
        p->alpha_from = 2;
    }
}

static void on_state(const lcm_recv_buf_t *rb, const char *channel, void *user)
{
    (void)channel;
    watch_t *w = user;
    swaywatch_state_t s;
    if (rb->data_size > INT32_MAX ||
        swaywatch_state_t_decode(rb->data, 0, (int)rb->data_size, &s) != (int)rb->data_size) {
        w->undecodable++;
        return;
    }
    const double now = mono_now();
    w->states++;
    count_seq(s.seq, &w->state_seq, &w->have_state_seq, &w->lost_states, &w->seq_restarts);
    char name[SW_NAME_MAX];
    msg_text(name, s.name, sizeof s.name);
    pkg_view_t *p = find_pkg(w, name);
    if (!p) {
        w->pkg_overflow++;
        return;
    }
    p->last = s;
    p->rx = now;
    p->win++;
    infer_alpha(p, &s);
    if (p->alpha_from && isfinite(s.theta)) {
        double r = fabs(s.theta) / p->alpha;
        if (r > p->peak)
            p->peak = r;
    }
    w->last_rx = now;
    w->gap_open = 0;
    w->win_states++;
    /* in double: a hostile utime (INT64_MIN) must not overflow */
    w->win_lag_sum += ((double)wall_now_us() - (double)s.utime) / 1e6;
}

/* "... rejected: REASON (N so far)": the monitor's count of that reason. */
static void count_rejected(watch_t *w, const char *text)
{
    const char *p = strstr(text, "rejected: ");
    char reason[24];
    long n;
    if (!p || sscanf(p + 10, "%23[a-z_] (%ld so far)", reason, &n) != 2)
        snprintf(reason, sizeof reason, "other"), n = -1;
    size_t i = 0;
    while (i < w->nreasons && strcmp(w->reason[i].name, reason)) i++;
    if (i == w->nreasons) {
        if (w->nreasons == MAX_REASONS)
            i = MAX_REASONS - 1; /* the rest are told together */
        else
            snprintf(w->reason[w->nreasons++].name, sizeof w->reason[0].name, "%s", reason);
    }
    /* The count the alarm states, or one more for an alarm that states none. */
    w->reason[i].so_far = n >= 0 ? (n > w->reason[i].so_far ? n : w->reason[i].so_far)
                                 : w->reason[i].so_far + 1;
}

static void on_alarm(const lcm_recv_buf_t *rb, const char *channel, void *user)
{
    (void)channel;
    watch_t *w = user;
    swaywatch_alarm_t a;
    if (rb->data_size > INT32_MAX ||
        swaywatch_alarm_t_decode(rb->data, 0, (int)rb->data_size, &a) != (int)rb->data_size) {
        w->undecodable++;
        return;
    }
    w->alarms++;
    long restarts = 0;
    count_seq(a.seq, &w->alarm_seq, &w->have_alarm_seq, &w->lost_alarms, &restarts);
    w->ring[w->ring_next] = (alarm_view_t){.wall_us = wall_now_us(), .a = a};
    w->ring_next = (w->ring_next + 1) % (size_t)w->o->alarms;
    if (w->ring_n < (size_t)w->o->alarms)
        w->ring_n++;
    char text[sizeof a.text];
    msg_text(text, a.text, sizeof a.text);
    if (a.kind == SWAYWATCH_ALARM_T_KIND_INPUT_REJECTED)
        count_rejected(w, text);
    if (a.kind == SWAYWATCH_ALARM_T_KIND_SENSOR_GAP) {
        if (a.level >= SWAYWATCH_ALARM_T_LEVEL_WARN) {
            w->gaps++;
            w->gap_open = !strncmp(text, "no accel sample", 15);
        } else {
            w->gap_open = 0;
        }
    }
}

/* Close the rate and lag window once a second. */
static void window(watch_t *w, double now)
{
    double span = now - w->win_start;
    if (span < 1.0)
        return;
    w->rate = (double)w->win_states / span;
    w->lag = w->win_states ? w->win_lag_sum / (double)w->win_states : NAN;
    for (size_t i = 0; i < w->npkg; i++) {
        w->pkg[i].rate = (double)w->pkg[i].win / span;
        w->pkg[i].win = 0;
    }
    w->win_states = 0;
    w->win_lag_sum = 0.0;
    w->win_start = now;
}

/* ---- the view as lines of text ------------------------------------------------ */

enum { ATTR_NONE = 0, ATTR_TITLE, ATTR_HEAD, ATTR_WARN, ATTR_CRIT };

typedef struct {
    int width, rows; /* the room there is: longer lines are cut */
    int layout;      /* the width the package table is laid out for */
    int n;
    char line[MAX_ROWS][MAX_COLS + 1];
    int attr[MAX_ROWS];
} view_t;

static void add(view_t *v, int attr, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

static void add(view_t *v, int attr, const char *fmt, ...)
{
    if (v->n >= v->rows || v->n >= MAX_ROWS)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->line[v->n], (size_t)v->width + 1, fmt, ap);
    va_end(ap);
    v->attr[v->n++] = attr;
}

/* A duration for people: ms, s, h or days. */
static void human_secs(char *buf, size_t len, double s)
{
    double a = fabs(s);
    if (!isfinite(s))
        snprintf(buf, len, "-");
    else if (a < 1.0)
        snprintf(buf, len, "%.1f ms", s * 1e3);
    else if (a < 120.0)
        snprintf(buf, len, "%.2f s", s);
    else if (a < 48 * 3600.0)
        snprintf(buf, len, "%.1f h", s / 3600.0);
    else
        snprintf(buf, len, "%.0f days", s / 86400.0);
}

static void view_input(view_t *v, const watch_t *w, double now)
{
    char lag[32], rej[256] = "", buf[MAX_COLS + 1];
    human_secs(lag, sizeof lag, w->lag);
    long total = 0;
    size_t used = 0;
    for (size_t i = 0; i < w->nreasons; i++) {
        total += w->reason[i].so_far;
        used += (size_t)snprintf(rej + used, sizeof rej - used, "%s%s %ld", i ? ", " : " (",
                                 w->reason[i].name, w->reason[i].so_far);
        if (used >= sizeof rej)
            break;
    }
    if (w->nreasons && used < sizeof rej - 1)
        snprintf(rej + used, sizeof rej - used, ")");
    snprintf(buf, sizeof buf, "input: %.1f states/s, lag %s, rejected %ld%s, gaps %ld, lost %ld "
             "states %ld alarms",
             isfinite(w->rate) ? w->rate : 0.0, lag, total, rej, w->gaps, w->lost_states,
             w->lost_alarms);
    int warn = total > 0 || w->gaps > 0 || w->lost_states > 0 || w->lost_alarms > 0;
    add(v, warn ? ATTR_WARN : ATTR_NONE, "%s", buf);
    char extra[MAX_COLS + 1] = "";
    used = 0;
    if (!w->states)
        used += (size_t)snprintf(extra, sizeof extra, "no state received yet");
    else if (now - w->last_rx > STALE) {
        char age[32];
        human_secs(age, sizeof age, now - w->last_rx);
        used += (size_t)snprintf(extra, sizeof extra, "NO STATE for %s%s", age,
                                 w->gap_open ? " (the monitor reports a sensor gap)" : "");
    } else if (w->gap_open)
        used += (size_t)snprintf(extra, sizeof extra, "SENSOR GAP: the monitor has no samples");
    if (w->seq_restarts && used < sizeof extra)
        used += (size_t)snprintf(extra + used, sizeof extra - used, "%smonitor restarted %ld x",
                                 used ? "; " : "", w->seq_restarts);
    if ((w->undecodable || w->pkg_overflow) && used < sizeof extra)
        snprintf(extra + used, sizeof extra - used, "%s%ld undecodable messages, %ld states of "
                 "packages beyond %d", used ? "; " : "", w->undecodable, w->pkg_overflow, MAX_PKG);
    if (extra[0])
        add(v, ATTR_CRIT, "       %s", extra);
}

/* |theta|/alpha as [####....|...] in width w (>= 3): '#' up to the ratio,
 * '|' at the peak, '>' at the end beyond 1. */
static void bar(char *buf, int width, double ratio, double peak)
{
    const int in = width - 2;
    int fill = isfinite(ratio) ? (int)lround(fmin(ratio, 1.0) * in) : 0;
    int at = isfinite(peak) && peak > 0.0 ? (int)lround(fmin(peak, 1.0) * in) - 1 : -1;
    buf[0] = '[';
    for (int i = 0; i < in; i++) buf[1 + i] = i < fill ? '#' : i == at ? '|' : '.';
    if (ratio > 1.0)
        buf[in] = '>';
    buf[in + 1] = ']';
    buf[in + 2] = '\0';
}

static const char *model_name(int m)
{
    static const char *const n[] = {"bare", "frame", "cushion"};
    return m >= 0 && m < 3 ? n[m] : "?";
}

static const char *phase_name(int p)
{
    static const char *const n[] = {"stuck", "rocking", "OVERTURNED"};
    return p >= 0 && p < 3 ? n[p] : "?";
}

/* The package table's columns, dropped right to left of importance when
 * the terminal is narrow: the bar keeps at least MIN_BAR columns. */
#define MIN_BAR 12
#define MAX_BAR 52
typedef struct {
    int bar;                /* columns of the bar, brackets included */
    int model, theta, rate; /* shown */
} layout_t;

static layout_t layout(int width)
{
    layout_t l = {.model = 1, .theta = 1, .rate = 1};
    /* name 16, phase 10, ratio 5, margin 7 (+ reserve 7), a blank after each */
    const int fixed = 17 + 11 + 6 + 8 + (HAVE_RESERVE ? 8 : 0);
    l.bar = width - fixed - 8 - 10 - 10;
    if (l.bar < MIN_BAR) {
        l.model = 0;
        l.bar += 8;
    }
    if (l.bar < MIN_BAR) {
        l.rate = 0;
        l.bar += 10;
    }
    if (l.bar < MIN_BAR) {
        l.theta = 0;
        l.bar += 10;
    }
    l.bar = l.bar > MAX_BAR ? MAX_BAR : l.bar < 3 ? 3 : l.bar;
    return l;
}

/* One row of the table: the cells of a package (or the titles). */
static void table_row(view_t *v, int attr, const layout_t *l, const char *name, const char *model,
                      const char *phase, const char *bar_, const char *ratio, const char *theta,
                      const char *margin, const char *reserve, const char *rate)
{
    char row[MAX_COLS + 1];
    int k = snprintf(row, sizeof row, "%-16.16s ", name);
    if (l->model)
        k += snprintf(row + k, sizeof row - (size_t)k, "%-7.7s ", model);
    k += snprintf(row + k, sizeof row - (size_t)k, "%-10.10s %-*s %5s", phase, l->bar, bar_,
                  ratio);
    if (l->theta)
        k += snprintf(row + k, sizeof row - (size_t)k, " %9s", theta);
    k += snprintf(row + k, sizeof row - (size_t)k, " %7s", margin);
    if (HAVE_RESERVE)
        k += snprintf(row + k, sizeof row - (size_t)k, " %7s", reserve);
    if (l->rate)
        snprintf(row + k, sizeof row - (size_t)k, " %9s", rate);
    add(v, attr, "%s", row);
}

static void view_package(view_t *v, const layout_t *l, const pkg_view_t *p, double now)
{
    const swaywatch_state_t *s = &p->last;
    char b[MAX_BAR + 1], ratio[16] = "", theta[16], margin[16], reserve[16], rate[32];
    double r = p->alpha_from ? fabs(s->theta) / p->alpha : NAN;
    if (p->alpha_from) {
        bar(b, l->bar, r, p->peak);
        snprintf(ratio, sizeof ratio, "%5.2f", r);
    } else {
        snprintf(b, sizeof b, "%.*s", l->bar, "(alpha unknown: --scene)");
    }
    snprintf(theta, sizeof theta, "%+6.1fdeg", s->theta * 180.0 / M_PI);
    snprintf(margin, sizeof margin, "%7.3f", s->margin);
    if (RESERVE_OF(s) >= 0.0) /* -1: none yet, or the monitor's reserve is off */
        snprintf(reserve, sizeof reserve, "%7.3f", RESERVE_OF(s));
    else
        snprintf(reserve, sizeof reserve, "%7s", "-");
    if (now - p->rx > STALE)
        snprintf(rate, sizeof rate, "stale %3.0fs", fmin(now - p->rx, 999.0));
    else
        snprintf(rate, sizeof rate, "%9.1f", isfinite(p->rate) ? p->rate : 0.0);
    int attr = s->phase == SWAYWATCH_STATE_T_PHASE_OVERTURNED || r >= 1.0 ? ATTR_CRIT
               : s->phase == SWAYWATCH_STATE_T_PHASE_ROCKING            ? ATTR_WARN
                                                                        : ATTR_NONE;
    table_row(v, attr, l, p->name, model_name(s->model), phase_name(s->phase), b, ratio, theta,
              margin, reserve, rate);
}

static void view_packages(view_t *v, const watch_t *w, double now)
{
    const layout_t l = layout(v->layout);
    table_row(v, ATTR_HEAD, &l, "PACKAGE", "MODEL", "PHASE", "|THETA|/ALPHA", "", "THETA",
              "MARGIN", "RESERVE", "STATES/S");
    for (size_t i = 0; i < w->npkg; i++) view_package(v, &l, &w->pkg[i], now);
    if (!w->npkg)
        add(v, ATTR_NONE, "(no package yet)");
}

static void view_alarms(view_t *v, const watch_t *w)
{
    add(v, ATTR_HEAD, "LAST ALARMS (newest first; %ld received)", w->alarms);
    for (size_t k = 0; k < w->ring_n; k++) {
        size_t i = (w->ring_next + (size_t)w->o->alarms - 1 - k) % (size_t)w->o->alarms;
        const alarm_view_t *e = &w->ring[i];
        char when[40], name[SW_NAME_MAX], text[sizeof e->a.text], nums[64] = "";
        sw_cli_iso_time(when, sizeof when, e->wall_us);
        msg_text(name, e->a.name, sizeof e->a.name);
        msg_text(text, e->a.text, sizeof e->a.text);
        /* the text first: on a narrow terminal the numbers are cut, not it */
        if (name[0] && RESERVE_OF(&e->a) >= 0.0)
            snprintf(nums, sizeof nums, "  (theta %+.4f, margin %.3f, reserve %.3f g)",
                     e->a.theta, e->a.margin, RESERVE_OF(&e->a));
        else if (name[0])
            snprintf(nums, sizeof nums, "  (theta %+.4f, margin %.3f)", e->a.theta, e->a.margin);
        const int lv = e->a.level;
        add(v, lv >= SWAYWATCH_ALARM_T_LEVEL_CRITICAL ? ATTR_CRIT
               : lv == SWAYWATCH_ALARM_T_LEVEL_WARN   ? ATTR_WARN
                                                      : ATTR_NONE,
            "%s %-8s %-16.16s %-14s %s%s", when + 11, sw_alarm_level_name((sw_alarm_level)lv),
            name[0] ? name : "-", sw_alarm_kind_name((sw_alarm_kind)e->a.kind), text, nums);
    }
    if (!w->ring_n)
        add(v, ATTR_NONE, "(none)");
}

/* The whole view in v's width and rows. */
static void view_make(view_t *v, const watch_t *w, int tty)
{
    const double now = mono_now();
    char when[40];
    sw_cli_iso_time(when, sizeof when, wall_now_us());
    v->n = 0;
    add(v, ATTR_TITLE, "swaywatch watch  %.19sZ  %s  %s %s%s", when,
        w->o->url && w->o->url[0] ? w->o->url : "(LCM default)", w->o->state_channel,
        w->o->alarm_channel, tty ? "   q: quit" : "");
    view_input(v, w, now);
    add(v, ATTR_NONE, "%s", "");
    view_packages(v, w, now);
    add(v, ATTR_NONE, "%s", "");
    view_alarms(v, w);
}

/* ---- terminals and snapshots ------------------------------------------------------ */

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig)
{
    stop_signal = sig;
}

static void plain_snapshot(const watch_t *w)
{
    static view_t v;
    v.width = MAX_COLS; /* nothing cut: the texts in full */
    v.layout = PLAIN_WIDTH;
    v.rows = MAX_ROWS;
    view_make(&v, w, 0);
    for (int i = 0; i < v.n; i++) printf("%s\n", v.line[i]);
    printf("\n");
    fflush(stdout);
}

static void screen_draw(const watch_t *w)
{
    static view_t v;
    int rows, cols;
    getmaxyx(stdscr, rows, cols);
    v.width = v.layout = cols < 1 ? 1 : cols > MAX_COLS ? MAX_COLS : cols;
    v.rows = rows < 1 ? 1 : rows;
    view_make(&v, w, 1);
    erase();
    for (int i = 0; i < v.n; i++) {
        attr_t a = v.attr[i] == ATTR_TITLE  ? A_REVERSE
                   : v.attr[i] == ATTR_HEAD ? A_UNDERLINE
                   : v.attr[i] == ATTR_CRIT ? A_BOLD | A_STANDOUT
                   : v.attr[i] == ATTR_WARN ? A_BOLD
                                            : A_NORMAL;
        attrset(a);
        mvaddnstr(i, 0, v.line[i], v.width);
    }
    attrset(A_NORMAL);
    refresh();
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
    double next = mono_now() + (curses ? 0.0 : period);
    const int fd = lcm_get_fileno(lcm);
    const int keys = curses && isatty(STDIN_FILENO); /* else poll() would see EOF at once */
    while (!stop_signal) {
        double now = mono_now();
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
        now = mono_now();
        window(w, now);
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
                screen_draw(w);
            else
                plain_snapshot(w);
            next = now + period;
        }
    }
    if (!curses && w->o->once)
        plain_snapshot(w);
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

/* alpha of every --scene (validated as the monitor does). */
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
    if (!(*alpha = calloc(*n, sizeof **alpha))) {
        sw_cli_error("watch: out of memory");
        return SW_EXIT_IO;
    }
    for (size_t k = 0; k < *n; k++) {
        sw_derived_t d;
        sw_scene_validate(&(*scenes)[k], &d, NULL, NULL, NULL);
        (*alpha)[k] = d.alpha;
    }
    return SW_EXIT_OK;
}

static int subscribe(lcm_t *lcm, watch_t *w, lcm_subscription_t **s1, lcm_subscription_t **s2)
{
    *s1 = lcm_subscribe(lcm, w->o->state_channel, on_state, w);
    *s2 = lcm_subscribe(lcm, w->o->alarm_channel, on_alarm, w);
    if (!*s1 || !*s2) {
        sw_cli_error("watch: cannot subscribe to %s and %s", w->o->state_channel,
                     w->o->alarm_channel);
        return SW_EXIT_IO;
    }
    lcm_subscription_set_queue_capacity(*s1, STATE_QUEUE);
    lcm_subscription_set_queue_capacity(*s2, 1000);
    return SW_EXIT_OK;
}

int cmd_watch(int argc, char **argv)
{
    watch_opts_t o = {.state_channel = SW_MON_STATE_CHANNEL,
                      .alarm_channel = SW_MON_ALARM_CHANNEL};
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
    w->nscenes = n;
    w->start = w->win_start = mono_now();
    w->rate = w->lag = NAN;
    if (!(lcm = lcm_create(o.url))) {
        sw_cli_error("watch: cannot set up LCM with %s (udpm needs a route for 224.0.0.0/4)",
                     o.url && o.url[0] ? o.url : "the default URL");
        goto out;
    }
    if ((rc = subscribe(lcm, w, &s1, &s2)) != SW_EXIT_OK)
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
