/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cmd_monitor.c - "swaywatch monitor": the live monitor on the vehicle's
 * LCM bus.  Subscribes to acceleration samples, advances every package's
 * model as they arrive, publishes states and alarms (the work is done by
 * the monitor core, src/lcm/monitor.c).
 *
 * One thread: poll() on LCM's file descriptor and on a self-pipe written by
 * the signal handler, with a timeout that wakes the loop for the sensor-gap
 * timer, the status line and the service manager's watchdog.  The
 * self-pipe (not a bare flag) because the signal may be delivered to LCM's
 * receive thread while this one sleeps in poll().  Nothing in the loop
 * writes files; publishing over udpm does not block.
 *
 * People are told on stderr: every alarm as one line (journal.h: with its
 * syslog priority when stderr is the journal, so that 'journalctl -p
 * warning' shows it), the status lines and the summary.  systemd is told
 * (notify.h) READY=1 once the monitor is subscribed, WATCHDOG=1 from the
 * loop at half the watchdog timeout (a loop that stalls is killed and
 * restarted), STATUS= the status line, STOPPING=1 at the end. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <lcm/lcm.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "clobber.h"
#include "cost.h"
#include "input.h"
#include "journal.h"
#include "lcmlog.h"
#include "lcmopts.h"
#include "monitor.h"
#include "notify.h"
#include "opts.h"
#include "output.h"

/* LCM's per-subscription queue drops what does not fit (default 30) and
 * counts nothing.  Unlimited (0), nothing is lost there; the backlog is
 * bounded by time instead: a message that waited longer than --max-backlog
 * is refused unread and counted (overload).  What the kernel drops before
 * LCM sees it is read from /proc/net/udp (socket_drops). */
#define ACCEL_QUEUE 0
/* Messages handled per wake-up before the timers get a look. */
#define BATCH 256
/* s between STATUS= updates for the service manager without --status. */
#define NOTIFY_STATUS_EVERY_S 10

/* monitor's own options, and the monitor core's. */
typedef struct {
    sw_mon_opts_t mo;
    sw_cli_gate_t gate;        /* the input gate's options, as every source has them */
    const char *url;           /* --lcm-url; NULL: LCM's default */
    const char *accel_channel; /* subscribed to */
    double status_every;       /* s, --status; 0: no status line */
    double max_backlog;        /* s, --max-backlog */
} monitor_opts_t;

static int check_accel_channel(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)dest;
    /* LCM's limit on channel names */
    if (!arg[0] || strlen(arg) > 63) {
        sw_cli_error("--%s: expected a channel regex of 1 to 63 characters, got '%s'", o->long_name,
                     arg);
        return SW_EXIT_USAGE;
    }
    return SW_EXIT_OK;
}

#define MO(f) SW_CLI_AT(monitor_opts_t, f)

/* --reserve-rate 0 turns the reserve off (monitor.h: reserve_rate < 0). */
static int check_reserve_rate(const sw_cli_option_t *o, const char *arg, void *dest)
{
    (void)o;
    (void)arg;
    double *v = dest;
    if (*v == 0.0)
        *v = -1.0;
    return SW_EXIT_OK;
}

static const sw_cli_option_t monitor_lcm_options[] = {
    {SW_CLI_SECTION, .help = "LCM:"},
    {SW_CLI_STRING, 'l', "lcm-url", "URL", MO(url),
     .help = "LCM URL (default: $LCM_DEFAULT_URL, else LCM's default, "
             "udpm://239.255.76.67:7667?ttl=0); a file://LOG is checked first and refused if "
             "damaged (LCM's reader trusts its length fields)"},
    {SW_CLI_STRING, 0, "accel-channel", "REGEX", MO(accel_channel), .fn = check_accel_channel,
     .help = "accel channel: a name or an anchored regex, as LCM subscribes "
             "(default " SW_MON_ACCEL_CHANNEL ")"},
    {SW_CLI_END},
};

static const sw_cli_option_t monitor_input_options[] = {
    {SW_CLI_SECTION, .help = "Input:"},
    {SW_CLI_FLAG, 0, "flip", MO(mo.flip), .value = 1,
     .help = "negate the longitudinal axis (sensor mounted backwards)"},
    {SW_CLI_CALL, 0, "accel-unit", "m/s2|g", MO(mo.accel_scale), .fn = sw_cli_accel_unit,
     .help = "unit of the message's values (default m/s2)"},
    {SW_CLI_DOUBLE, 0, "reserve-rate", "HZ", MO(mo.reserve_rate), .rule = SW_NUM_NONNEGATIVE,
     .def = SW_RISK_RATE, .lo = 0.01, .hi = 1000, .fn = check_reserve_rate,
     .what = "a rate in Hz >= 0 (0: none)",
     .help = "reserve evaluations per second of sample time for each package: the smallest "
             "design braking pulse in g that would overturn it now, in state_t.reserve_g and "
             "behind the RESERVE_WARN and RESERVE_CRITICAL alarms (default %g; 0: none; "
             "docs/reserve.md gives the cost per model)"},
    {SW_CLI_DOUBLE, 0, "max-backlog", "SECONDS", MO(max_backlog), .rule = SW_NUM_POSITIVE, .def = 1,
     .lo = 1e-3, .hi = 3600, .what = "a positive number of seconds",
     .help = "a message that waited longer than this in the receive queue (the monitor fell "
             "behind: a flood, a stalled machine) is refused unread as overload and counted, so "
             "the monitor catches up instead of working on stale samples (default %g; "
             "udpm and tcpq only)"},
    {SW_CLI_DOUBLE, 0, "status", "SECONDS", MO(status_every), .rule = SW_NUM_NONNEGATIVE, .lo = 0.1,
     .hi = 86400, .what = "a number of seconds >= 0 (0: no status)",
     .help = "one status line on stderr every SECONDS: sample rate, lag behind the sensor clock, "
             "CPU share, counts (default 0: none; under systemd it is also the service's "
             "status, updated every " SW_CLI_STR(NOTIFY_STATUS_EVERY_S) " s without --status)"},
    {SW_CLI_TEXT,
     .help = "\nA sensor with a synchronised clock can use --max-skew (e.g. 10); leave it off\n"
             "when lcm-logplayer replays an old log.\n"
             "\n"
             "Sensor gaps: when no sample has arrived for --gap seconds (0.1 s if --gap is not\n"
             "given), a SENSOR_GAP alarm (warn) is published and the model waits: it is not\n"
             "advanced and publishes no state.  When samples resume, the gap follows\n"
             "--gap-policy (bridged linearly up to --max-bridge, else the packages restart\n"
             "from rest) and a SENSOR_GAP alarm says so; critical when the gap overlaps\n"
             "rocking or an acceleration past an uplift threshold (the verdict is incomplete).\n"
             "\n"
             "Time: samples are integrated by their own utime, the time that really passed\n"
             "taken from their arrival.  A sample whose utime leaps ahead of that (beyond\n"
             "--max-jump) or goes back waits until --confirm samples in a row follow it: then\n"
             "the sensor's clock stepped (re-timed, the motion goes on), it restarted (utime\n"
             "went back), or it was silent (a gap), each a SENSOR_GAP alarm and a counter;\n"
             "else the stream refutes it and it alone is refused.  One forged or corrupt utime\n"
             "cannot make the later samples late, nor blind the monitor.\n"
             "\n"
             "Bad input: messages that are not accel_t (wrong type, truncated, trailing bytes),\n"
             "samples with a non-finite value or beyond --max-accel or --max-skew, duplicates\n"
             "(same utime as the last accepted sample) and late samples (utime before it) are\n"
             "refused and counted by reason: the model never integrates backwards.  The first\n"
             "refusal of each reason raises INPUT_REJECTED at once, later ones at most once a\n"
             "second with their count.  Samples lost on the way are counted from the sender's\n"
             "seq.  A state whose numbers are not all finite is never published: a MODEL_FAULT\n"
             "alarm is, instead."},
    {SW_CLI_END},
};

/* What the monitor publishes: the states and alarms (sw_cli_lcm_publish_options). */
static const sw_cli_option_t monitor_output_notes[] = {
    {SW_CLI_SECTION, .help = "Output:"},
    {SW_CLI_TEXT,
     .help = "\nThe monitor writes no files: record its output with lcm-logger.\n"
             "\n"
             "Every alarm it raises also goes to stderr, as one line:\n"
             "  swaywatch: alarm TIME level=LEVEL package=NAME kind=KIND theta=RAD\n"
             "  margin=M text=\"...\"\n"
             "TIME is the wall clock, ISO 8601 UTC with ms; input alarms have package=-\n"
             "theta=- margin=-.  When stderr is the journal (systemd's JOURNAL_STREAM), the\n"
             "line starts with the syslog priority of its level, <2> critical, <4> warn,\n"
             "<6> info, and errors with <3>: 'journalctl -p warning -u swaywatch-monitor'\n"
             "lists the warn and critical alarms and the errors.\n"
             "\n"
             "Under systemd (Type=notify) the monitor sends READY=1 once it is subscribed,\n"
             "WATCHDOG=1 from its main loop at half of WatchdogSec= (a stalled loop is\n"
             "killed and restarted), its status line as STATUS= and STOPPING=1 at the end."},
    {SW_CLI_END},
};

static const sw_cli_command_t monitor_cmd = {
    .name = "monitor",
    .usage = "monitor --scene S.ini [--scene T.ini ...] [options]",
    .about =
        "Live monitor: subscribes to acceleration samples (swaywatch.accel_t) over LCM,\n"
        "advances the model of every package as they arrive, and publishes each package's\n"
        "state (swaywatch.state_t) and alarms (swaywatch.alarm_t).  Runs until SIGINT or\n"
        "SIGTERM, then prints a summary on stderr.  Samples are integrated by their own\n"
        "utime, never by arrival time.\n"
        "\n"
        "SIGHUP (systemctl reload) re-reads the scene files: a package whose scene values\n"
        "changed is rebuilt and starts from rest; the others keep their state, alarms and\n"
        "message sequence.  If a file is unreadable or invalid, nothing changes.\n",
    .exit_text =
        "Exit codes: 0 stopped by SIGINT or SIGTERM, 2 bad usage or bad scene,\n"
        "3 LCM could not be set up (URL, network) or a scene file could not be read.\n",
};

/* ---- signals --------------------------------------------------------------- */

static volatile sig_atomic_t stop_signal;
static volatile sig_atomic_t reload_signal; /* SIGHUP: re-read the scene files */
static int wake_pipe[2] = {-1, -1};

static void on_signal(int sig)
{
    int saved = errno;
    if (sig == SIGHUP)
        reload_signal = 1;
    else
        stop_signal = sig;
    if (wake_pipe[1] >= 0) {
        ssize_t r = write(wake_pipe[1], "", 1);
        (void)r; /* a full pipe already wakes the loop */
    }
    errno = saved;
}

static int install_signals(void)
{
    if (pipe(wake_pipe) != 0)
        return -1;
    for (int i = 0; i < 2; i++) {
        int fl = fcntl(wake_pipe[i], F_GETFL);
        if (fl < 0 || fcntl(wake_pipe[i], F_SETFL, fl | O_NONBLOCK) != 0)
            return -1;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    if (sigaction(SIGINT, &sa, NULL) != 0 || sigaction(SIGTERM, &sa, NULL) != 0 ||
        sigaction(SIGHUP, &sa, NULL) != 0)
        return -1;
    return 0;
}

static void remove_signals(void)
{
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    signal(SIGHUP, SIG_DFL);
    for (int i = 0; i < 2; i++)
        if (wake_pipe[i] >= 0) {
            close(wake_pipe[i]);
            wake_pipe[i] = -1;
        }
}

/* ---- clocks ------------------------------------------------------------------ */

static int64_t wall_now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* ---- reload (SIGHUP) ---------------------------------------------------------
 * The monitor re-reads its scene files on SIGHUP (systemctl reload),
 * without losing the state of the packages whose scene did not change.
 *
 * Every --scene file is read again, with the --set overrides, exactly as at
 * start.  A package whose scene values are the same as before (comments,
 * layout and the order of keys do not count) is left alone: its state, its
 * alarm state and its place in the message streams go on.  A package whose
 * scene changed is rebuilt and starts from rest at the current sample time
 * (sw_mon_replace).  All or nothing: if a file cannot be read or is not a
 * valid scene, or a changed scene cannot be built, nothing is changed and
 * the monitor goes on with the scenes it had.  The file list itself is the
 * one given at start. */

/* Re-read the scene files of o (with its --set overrides) and rebuild the
 * packages of mon whose scene changed; scenes[0..n) are the monitor's
 * current scenes, updated in place.  Says what it did on stderr.  Returns
 * SW_EXIT_OK, or SW_EXIT_USAGE / SW_EXIT_IO with nothing changed. */
static int reload_scenes(sw_mon_t *mon, const sw_cli_opts_t *o, sw_scene_t *scenes, size_t n)
{
    sw_scene_t *fresh = NULL, *changed = NULL;
    size_t nf = 0, nchanged = 0;
    sw_engine_t *trial = NULL;
    char msg[512] = "";

    int rc = sw_cli_load_scenes(o, &fresh, &nf);
    if (rc != SW_EXIT_OK)
        goto keep;
    if (nf != n) { /* the same files as at start: cannot happen */
        sw_cli_error("monitor: reload: %zu scenes instead of %zu", nf, n);
        rc = SW_EXIT_USAGE;
        goto keep;
    }
    changed = calloc(n, sizeof *changed);
    if (!changed) {
        sw_cli_error("monitor: reload: out of memory");
        rc = SW_EXIT_IO;
        goto keep;
    }
    for (size_t k = 0; k < n; k++)
        if (!sw_scene_equal(&scenes[k], &fresh[k]))
            changed[nchanged++] = fresh[k];
    if (nchanged == 0) {
        fprintf(stderr, "swaywatch: monitor: reload: no scene changed; %zu packages kept\n", n);
        goto done;
    }
    /* Build the changed packages once on the side with the monitor's
     * options: what passes here cannot fail in sw_mon_replace() but for
     * memory, so a reload does not stop half-way. */
    sw_engine_opts_t eo;
    sw_cli_engine_opts(o, &eo);
    int err = 0;
    trial = sw_engine_create(changed, nchanged, &eo, &err, msg, sizeof msg);
    if (!trial) {
        sw_cli_error("monitor: reload: %s", msg[0] ? msg : sw_strerror(err));
        rc = SW_EXIT_USAGE;
        goto keep;
    }
    for (size_t k = 0; k < n; k++) {
        if (sw_scene_equal(&scenes[k], &fresh[k]))
            continue;
        if (sw_mon_replace(mon, k, &fresh[k], msg, sizeof msg) != SW_OK) {
            sw_cli_error("monitor: reload: %s: %s", fresh[k].name, msg);
            rc = SW_EXIT_IO;
            continue; /* only memory: the package keeps its old scene */
        }
        fprintf(stderr, "swaywatch: monitor: reload: %s rebuilt from %s (scene changed)\n",
                fresh[k].name, o->scenes.v[k]);
        scenes[k] = fresh[k];
        sw_cli_warn_no_reserve(sw_mon_risk(mon), k, k + 1, scenes);
    }
    fprintf(stderr, "swaywatch: monitor: reload: %zu of %zu packages rebuilt, the others kept\n",
            nchanged, n);
    sw_cli_warn_scene_cost(changed, nchanged, &eo);
    goto done;

keep:
    sw_cli_error("monitor: reload: scene files not applied; going on with the scenes of before");
done:
    sw_engine_destroy(trial);
    free(changed);
    free(fresh);
    return rc;
}

/* ---- the loop ------------------------------------------------------------------ */

typedef struct {
    sw_mon_t *mon;
    const sw_cli_opts_t *opts; /* for a reload: the scene files and --set */
    sw_scene_t *scenes;
    size_t n;
    /* since the last status line */
    long accepted;
    double lag_sum, lag_max; /* s, wall clock at handling minus sample utime */
    double busy;             /* s spent handling samples */
    double max_backlog;      /* s; 0: no shedding (a log, memq: the receive time is not now) */
} mon_ctx_t;

/* Datagrams the kernel dropped on this process's UDP sockets (the column
 * "drops" of /proc/net/udp and udp6 for the inodes of our sockets): what
 * arrived at the host but never reached LCM.  -1 if it cannot be read. */
static long socket_drops(void)
{
    unsigned long inode[64];
    int n = 0;
    DIR *d = opendir("/proc/self/fd");
    if (!d)
        return -1;
    for (struct dirent *e; (e = readdir(d)) && n < 64;) {
        char path[300], link[64];
        snprintf(path, sizeof path, "/proc/self/fd/%s", e->d_name);
        const ssize_t len = readlink(path, link, sizeof link - 1);
        if (len <= 0)
            continue;
        link[len] = '\0';
        if (sscanf(link, "socket:[%lu]", &inode[n]) == 1)
            n++;
    }
    closedir(d);
    long drops = 0;
    int seen = 0;
    static const char *const tables[] = {"/proc/net/udp", "/proc/net/udp6"};
    for (int t = 0; t < 2; t++) {
        FILE *f = fopen(tables[t], "r");
        if (!f)
            continue;
        seen = 1;
        char line[512];
        while (fgets(line, sizeof line, f)) {
            unsigned long ino;
            long dr;
            /* sl local rem st tx:rx tr:when retrnsmt uid timeout inode ref pointer drops */
            if (sscanf(line, "%*s %*s %*s %*s %*s %*s %*s %*s %*s %lu %*s %*s %ld", &ino, &dr) != 2)
                continue;
            for (int i = 0; i < n; i++)
                if (inode[i] == ino)
                    drops += dr;
        }
        fclose(f);
    }
    return seen ? drops : -1;
}

static void on_accel(const lcm_recv_buf_t *rb, const char *channel, void *user)
{
    (void)channel;
    mon_ctx_t *c = user;
    double t0 = sw_mon_clock();
    double arrived = t0;
    if (c->max_backlog > 0.0) {
        /* how long it waited: LCM stamps it on arrival, on the wall clock */
        const double waited = ((double)wall_now_us() - (double)rb->recv_utime) / 1e6;
        if (waited > c->max_backlog) {
            sw_mon_refuse(c->mon, SW_MON_REJ_OVERLOAD, t0);
            c->busy += sw_mon_clock() - t0;
            return;
        }
        if (waited > 0.0)
            arrived = t0 - waited; /* the gate wants the arrival time, not ours */
    }
    sw_mon_counts_t k0, k1;
    sw_mon_counts(c->mon, &k0);
    sw_mon_feed(c->mon, rb->data, rb->data_size, rb->recv_utime, arrived, NULL);
    sw_mon_counts(c->mon, &k1);
    if (k1.accepted > k0.accepted) { /* none while a sample is held; two when it is confirmed */
        /* in double: utime may be anything an int64 holds (a forged one
         * minus the wall clock overflows int64) */
        double lag = ((double)wall_now_us() - (double)sw_mon_last_utime(c->mon)) / 1e6;
        c->accepted += k1.accepted - k0.accepted;
        c->lag_sum += lag;
        if (c->accepted == 1 || lag > c->lag_max)
            c->lag_max = lag;
    }
    c->busy += sw_mon_clock() - t0;
}

/* Every alarm on stderr, one line each (journal.h). */
static void print_alarm(void *user, const sw_alarm_t *a)
{
    const mon_ctx_t *c = user;
    const sw_risk_pkg_t *rp = sw_risk_pkg(sw_mon_risk(c->mon), a->pkg);
    sw_cli_alarm_line_t line = {
        .wall_us = wall_now_us(),
        .level = a->level,
        .kind = a->kind,
        .package = a->pkg < c->n ? c->scenes[a->pkg].name : NULL,
        .theta = a->theta,
        .margin = a->margin,
        .reserve_g = rp ? rp->reserve_g : NAN, /* the latest reserve, as alarm_t carries */
        .text = a->text,
    };
    sw_cli_alarm_print(&line);
}

/* The status line since the last one (interval s; elapsed s since the
 * start), without "swaywatch: " and newline, into buf; starts a new
 * interval. */
static void status_text(mon_ctx_t *c, double elapsed, double interval, char *buf, size_t len)
{
    sw_mon_counts_t k;
    sw_mon_counts(c->mon, &k);
    FILE *f = fmemopen(buf, len, "w");
    if (!f) {
        snprintf(buf, len, "monitor %.0f s", elapsed);
    } else {
        fprintf(f, "monitor %.0f s: %.1f samples/s", elapsed, (double)c->accepted / interval);
        if (c->accepted)
            fprintf(f, ", lag %.2f ms (max %.2f)", 1e3 * c->lag_sum / (double)c->accepted,
                    1e3 * c->lag_max);
        fprintf(f, ", busy %.1f%%; accepted %ld, ", 100.0 * c->busy / interval, k.accepted);
        sw_cli_print_rejected(f, &k);
        fprintf(f, ", held %ld of %ld received, lost %ld, gaps %ld, states %ld, alarms %ld", k.held,
                k.received, k.lost, k.gaps, k.states, k.alarms);
        const long drops = socket_drops();
        if (drops >= 0)
            fprintf(f, ", kernel drops %ld", drops);
        fclose(f); /* NUL-terminates, truncated to fit */
    }
    c->accepted = 0;
    c->lag_sum = c->lag_max = c->busy = 0.0;
}

static void print_final(sw_mon_t *mon, double elapsed)
{
    sw_mon_counts_t k;
    sw_mon_counts(mon, &k);
    fprintf(stderr, "swaywatch: monitor stopped (%s) after %.1f s: received %ld = accepted %ld + ",
            stop_signal == SIGTERM ? "SIGTERM" : "SIGINT", elapsed, k.received, k.accepted);
    sw_cli_print_rejected(stderr, &k);
    fprintf(stderr,
            "; lost %ld (by seq), seq restarts %ld, gaps %ld, sensor restarts %ld, clock "
            "steps %ld; published %ld states (%ld withheld), %ld alarms (%ld more folded into "
            "them by the rate limit); %ld publish errors",
            k.lost, k.seq_restarts, k.gaps, k.restarts, k.clock_steps, k.states, k.states_withheld,
            k.alarms, k.alarms_folded, k.publish_errors);
    const long drops = socket_drops();
    if (drops >= 0)
        fprintf(stderr, "; %ld datagrams dropped by the kernel before LCM read them", drops);
    fputc('\n', stderr);
    sw_cli_run_t run;
    memset(&run, 0, sizeof run);
    run.samples_read = k.received;
    run.samples_rejected = k.received - k.accepted;
    sw_cli_print_summary(stderr, sw_mon_engine(mon), &run);
}

/* The timers of the loop besides the monitor core's. */
typedef struct {
    double start;
    double status_every, last_status, next_status; /* the status line (and STATUS=) */
    int status_line;                               /* on stderr too (--status) */
    double ping_every, next_ping;                  /* WATCHDOG=1 */
} loop_timers_t;

static void timers_init(loop_timers_t *t, double status_every)
{
    t->start = t->last_status = sw_mon_clock();
    t->status_line = status_every > 0.0;
    /* Without --status, systemd still gets the status now and then. */
    t->status_every = t->status_line ? status_every : (double)NOTIFY_STATUS_EVERY_S;
    t->next_status = t->start + t->status_every;
    t->ping_every = sw_cli_watchdog_interval();
    t->next_ping = t->ping_every > 0.0 ? t->start : INFINITY;
}

/* Status line, STATUS= and WATCHDOG=1 when due at now. */
static void timers_run(loop_timers_t *t, mon_ctx_t *c, double now)
{
    if (now >= t->next_status) {
        char text[400];
        status_text(c, now - t->start, now - t->last_status, text, sizeof text);
        if (t->status_line)
            fprintf(stderr, "swaywatch: %s\n", text);
        sw_cli_notify_status(text);
        t->last_status = now;
        t->next_status += t->status_every;
        if (t->next_status <= now)
            t->next_status = now + t->status_every;
    }
    if (now >= t->next_ping) {
        /* The loop turns: it got here. */
        sw_cli_notify("WATCHDOG=1");
        t->next_ping = now + t->ping_every;
    }
}

static int run_loop(lcm_t *lcm, mon_ctx_t *c, double status_every)
{
    int fd = lcm_get_fileno(lcm);
    loop_timers_t tm;
    timers_init(&tm, status_every);
    while (!stop_signal) {
        double now = sw_mon_clock();
        double deadline = fmin(sw_mon_deadline(c->mon), fmin(tm.next_status, tm.next_ping));
        int timeout = -1;
        if (isfinite(deadline))
            timeout = deadline <= now ? 0 : (int)ceil((deadline - now) * 1e3);
        struct pollfd p[2] = {{.fd = fd, .events = POLLIN}, {.fd = wake_pipe[0], .events = POLLIN}};
        int r = poll(p, 2, timeout);
        if (r < 0 && errno != EINTR) {
            sw_cli_error("monitor: poll: %s", strerror(errno));
            return SW_EXIT_IO;
        }
        if (r > 0 && (p[0].revents & POLLIN)) {
            /* Drain what is queued, a batch at a time, without blocking. */
            if (lcm_handle(lcm) != 0) {
                sw_cli_error("monitor: lcm_handle failed");
                return SW_EXIT_IO;
            }
            for (int i = 1; i < BATCH && lcm_handle_timeout(lcm, 0) > 0; i++) {
            }
        }
        if (reload_signal) {
            /* Empty the wake-up pipe first: a SIGHUP after this point
             * writes to it again and is not lost. */
            char junk[64];
            while (read(wake_pipe[0], junk, sizeof junk) > 0) {
            }
            reload_signal = 0;
            sw_cli_notify("RELOADING=1");
            reload_scenes(c->mon, c->opts, c->scenes, c->n);
            sw_cli_notify("READY=1");
        }
        now = sw_mon_clock();
        if (now >= sw_mon_deadline(c->mon))
            sw_mon_tick(c->mon, now);
        timers_run(&tm, c, now);
    }
    sw_cli_notify("STOPPING=1");
    sw_mon_flush(c->mon);
    print_final(c->mon, sw_mon_clock() - tm.start);
    return SW_EXIT_OK;
}

/* ---- the command --------------------------------------------------------------- */

/* Non-zero if LCM at url receives from the network (udpm, tcpq): its
 * receive times are when a message arrived, and a backlog can build up.
 * A file:// log's are the recording's; memq's are the publishing's. */
static int network_url(const char *url)
{
    const char *u = url ? url : getenv("LCM_DEFAULT_URL");
    return !u || !u[0] || !strncmp(u, "udpm://", 7) || !strncmp(u, "tcpq://", 7);
}

/* LCM at url, or why not. */
static lcm_t *open_lcm(const char *url)
{
    lcm_t *lcm = lcm_create(url);
    if (lcm)
        return lcm;
    /* The usual cause with udpm: no route for multicast (a host or network
     * namespace with only loopback). */
    int udpm = !url || !url[0] || !strncmp(url, "udpm://", 7);
    sw_cli_error("monitor: cannot set up LCM with %s%s", url && url[0] ? url : "the default URL",
                 udpm ? " (udpm needs a route for 224.0.0.0/4, e.g. 'ip route add "
                        "224.0.0.0/4 dev lo')"
                      : "");
    return NULL;
}

/* The monitor core on c's scenes, publishing on lcm. */
static int start(mon_ctx_t *c, const sw_mon_opts_t *mo, lcm_t *lcm)
{
    sw_engine_opts_t eo;
    sw_cli_engine_opts(c->opts, &eo);
    int rc = sw_cli_resolve_accuracy(c->opts, c->scenes, c->n, &eo);
    if (rc != SW_EXIT_OK)
        return rc;
    char msg[512] = "";
    sw_mon_opts_t o = *mo;
    o.on_alarm = print_alarm;
    o.user = c;
    c->mon = sw_mon_create(c->scenes, c->n, &eo, &o, lcm, msg, sizeof msg);
    if (!c->mon) {
        sw_cli_error("monitor: %s", msg[0] ? msg : "cannot start");
        return SW_EXIT_USAGE;
    }
    if (c->opts->verbose)
        sw_cli_print_derived(stderr, sw_mon_engine(c->mon), c->scenes, c->n);
    sw_cli_warn_scene_cost(c->scenes, c->n, &eo);
    sw_cli_warn_no_reserve(sw_mon_risk(c->mon), 0, c->n, c->scenes);
    return SW_EXIT_OK;
}

/* What the options name: no replay outputs, the gate's settings, the
 * scenes loaded, an LCM log URL checked; the files apart from each other. */
static int check_args(const sw_cli_opts_t *o, monitor_opts_t *m, sw_scene_t **scenes, size_t *n)
{
    int rc;
    if (o->out_path || o->events_path || o->json || o->every != 1) {
        sw_cli_error(
            "monitor: --out, --events, --every and --json are for replay and "
            "simulate; record the monitor's output with lcm-logger");
        return SW_EXIT_USAGE;
    }
    if ((rc = sw_cli_mon_gate(&m->mo, &m->gate)) != SW_EXIT_OK)
        return rc;
    char url_path[4096];
    const sw_cli_file_t url_out = {"--lcm-url",
                                   sw_cli_lcm_url_output(m->url, url_path, sizeof url_path)};
    if ((rc = sw_cli_check_run_files(NULL, &o->scenes, &url_out, 1)) != SW_EXIT_OK ||
        (rc = sw_cli_load_scenes(o, scenes, n)) != SW_EXIT_OK)
        return rc;
    /* A file:// URL: LCM's reader trusts the log, ours checks it first. */
    return sw_cli_check_lcm_url("monitor", m->url);
}

int cmd_monitor(int argc, char **argv)
{
    int rc = SW_EXIT_USAGE;
    sw_cli_opts_t o = {0};
    monitor_opts_t m = {.accel_channel = SW_MON_ACCEL_CHANNEL};
    sw_scene_t *scenes = NULL;
    size_t n = 0;
    lcm_t *lcm = NULL;
    lcm_subscription_t *sub = NULL;
    mon_ctx_t ctx;
    memset(&ctx, 0, sizeof ctx);
    sw_cli_mon_opts_init(&m.mo);
    sw_cli_gate_init(&m.gate);
    sw_cli_group_t g[] = {
        SW_CLI_GROUP(monitor_lcm_options, &m),
        SW_CLI_GROUP_IN(sw_cli_lcm_input_options, &m.mo, "Input:"),
        SW_CLI_GROUP(monitor_input_options, &m),
        SW_CLI_GROUP(sw_cli_gate_options, &m.gate),
        SW_CLI_GROUP(sw_cli_scene_options, &o),
        SW_CLI_GROUP(sw_cli_integration_options, &o),
        SW_CLI_GROUP(sw_cli_accuracy_options, &o),
        SW_CLI_GROUP_IN(sw_cli_lcm_publish_options, &m.mo, "Output:"),
        SW_CLI_GROUP(monitor_output_notes, NULL),
        SW_CLI_GROUP_IN(sw_cli_common_options, &o, "Output:"),
        /* taken, to be refused below with the reason */
        {.rows = sw_cli_output_options, .base = &o, .flags = SW_CLI_HIDDEN},
    };
    const size_t ng = sizeof g / sizeof g[0];

    int first;
    if ((rc = sw_cli_parse(&monitor_cmd, g, ng, argc, argv, &first)) != SW_CLI_CONTINUE)
        goto out;
    rc = SW_EXIT_USAGE;
    if (sw_cli_no_operand("monitor", argc, argv, first) != SW_EXIT_OK)
        goto out;
    if ((rc = check_args(&o, &m, &scenes, &n)) != SW_EXIT_OK)
        goto out;
    rc = SW_EXIT_IO;
    if (install_signals() != 0) {
        sw_cli_error("monitor: cannot install signal handlers: %s", strerror(errno));
        goto out;
    }
    if (!(lcm = open_lcm(m.url)))
        goto out;

    ctx.opts = &o;
    ctx.scenes = scenes;
    ctx.n = n;
    ctx.max_backlog = network_url(m.url) ? m.max_backlog : 0.0;
    if ((rc = start(&ctx, &m.mo, lcm)) != SW_EXIT_OK)
        goto out;

    /* Raw subscription: the generated one drops bad messages with a line
     * on stderr and no count. */
    sub = lcm_subscribe(lcm, m.accel_channel, on_accel, &ctx);
    if (!sub) {
        sw_cli_error("monitor: cannot subscribe to %s", m.accel_channel);
        rc = SW_EXIT_IO;
        goto out;
    }
    lcm_subscription_set_queue_capacity(sub, ACCEL_QUEUE);
    char ready[128];
    snprintf(ready, sizeof ready, "READY=1\nSTATUS=waiting for samples on %s", m.accel_channel);
    sw_cli_notify(ready);
    rc = run_loop(lcm, &ctx, m.status_every);

out:
    if (sub)
        lcm_unsubscribe(lcm, sub);
    sw_mon_destroy(ctx.mon);
    if (lcm)
        lcm_destroy(lcm);
    remove_signals();
    free(scenes);
    sw_cli_parse_free(g, ng);
    return rc;
}
