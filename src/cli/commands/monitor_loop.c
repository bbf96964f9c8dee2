/* SPDX-License-Identifier: GPL-3.0-or-later */
/* monitor_loop.c - the loop of "swaywatch monitor" (monitor_cli.h): the
 * signals that stop it or reload the scenes, the samples handed to the
 * monitor core, the alarm lines, the status line and the service
 * manager's timers.
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
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "journal.h"
#include "lcmopts.h"
#include "monitor_cli.h"
#include "notify.h"
#include "output.h"
#include "text.h"

/* Messages handled per wake-up before the timers get a look. */
#define BATCH 256

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

int sw_cli_mon_signals_install(void)
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

void sw_cli_mon_signals_remove(void)
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

/* ---- the loop ------------------------------------------------------------------ */

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

void sw_cli_mon_on_accel(const lcm_recv_buf_t *rb, const char *channel, void *user)
{
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
    sw_mon_feed_on(c->mon, channel, rb->data, rb->data_size, rb->recv_utime, arrived, NULL);
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
void sw_cli_mon_print_alarm(void *user, const sw_alarm_t *a)
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
        if (k.contests > 0)
            fprintf(f, ", contested %ld (%ld samples on a second timeline)", k.contests,
                    k.contested);
        const sw_auth_facts_t *au = sw_mon_auth_facts(c->mon);
        if (au && au->checked > au->refused[SW_AUTH_OK]) {
            char chan[sizeof au->last.channel];
            sw_cli_term_text(chan, sizeof chan, au->last.channel, sizeof au->last.channel);
            fprintf(f, ", unauthentic %ld in %ld bursts (the last: message %ld on %s, %s)",
                    au->checked - au->refused[SW_AUTH_OK], k.auth_contests, au->last.where, chan,
                    sw_auth_result_name(au->last.why));
        }
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
            "them by the rate limit); %ld publish errors; contested %ld (%ld samples on a "
            "second timeline, evaluated apart)",
            k.lost, k.seq_restarts, k.gaps, k.restarts, k.clock_steps, k.states, k.states_withheld,
            k.alarms, k.alarms_folded, k.publish_errors, k.contests, k.contested);
    const long drops = socket_drops();
    if (drops >= 0)
        fprintf(stderr, "; %ld datagrams dropped by the kernel before LCM read them", drops);
    fputc('\n', stderr);
    const sw_auth_facts_t *au = sw_mon_auth_facts(mon);
    if (au) {
        fputs("swaywatch: monitor: ", stderr);
        sw_cli_print_auth(stderr, au);
        fprintf(stderr, "; %ld times unauthentic samples began to arrive (INPUT_CONTESTED)\n",
                k.auth_contests);
    } else if (k.macs_unchecked > 0) {
        fprintf(stderr,
                "swaywatch: monitor: %ld samples carried a MAC that was not checked: give the "
                "monitor the senders' key file (--key FILE) to refuse forged and replayed "
                "samples\n",
                k.macs_unchecked);
    }
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

int sw_cli_mon_run(lcm_t *lcm, mon_ctx_t *c, double status_every)
{
    int fd = lcm_get_fileno(lcm);
    loop_timers_t tm;
    timers_init(&tm, status_every);
    while (!stop_signal) {
        double now = sw_mon_clock();
        double deadline = fmin(sw_mon_deadline(c->mon), fmin(tm.next_status, tm.next_ping));
        deadline = fmin(deadline, sw_cli_mon_reload_due(c));
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
            sw_cli_mon_reload_ask(c, sw_mon_clock());
        }
        now = sw_mon_clock();
        /* the files are read once they stay unchanged: the loop goes on */
        if (sw_cli_mon_reload_poll(c, now))
            sw_cli_notify("READY=1");
        if (now >= sw_mon_deadline(c->mon))
            sw_mon_tick(c->mon, now);
        timers_run(&tm, c, now);
    }
    sw_cli_notify("STOPPING=1");
    sw_mon_flush(c->mon);
    print_final(c->mon, sw_mon_clock() - tm.start);
    return SW_EXIT_OK;
}
