/* SPDX-License-Identifier: GPL-3.0-or-later */
/* interrupt.c - SIGINT and SIGTERM in the commands that run to an end
 * (interrupt.h). */
#include "interrupt.h"

#include <errno.h>
#include <string.h>
#include <unistd.h>

volatile sig_atomic_t sw_cli_signal;

/* Immediate mode's message; read by the handler. */
static const char *volatile immediate;
/* sw_cli_interrupt_deferred(): never immediate. */
static volatile sig_atomic_t deferred;

static void say(const char *s)
{
    ssize_t r = write(STDERR_FILENO, s, strlen(s));
    (void)r; /* nothing more to do about stderr from here */
}

static void on_signal(int sig)
{
    if (sw_cli_signal) { /* a second signal: the default action, at once */
        signal(sig, SIG_DFL);
        raise(sig);
        return;
    }
    sw_cli_signal = sig;
    const char *msg = immediate;
    if (msg) {
        say("swaywatch: ");
        say(msg);
        say(sig == SIGINT ? " (SIGINT)\n" : " (SIGTERM)\n");
        _exit(128 + sig);
    }
}

int sw_cli_interrupt_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sa.sa_flags = SA_RESTART; /* reads and writes go on; a sleep ends early */
    sigemptyset(&sa.sa_mask);
    if (sigaction(SIGINT, &sa, NULL) == 0 && sigaction(SIGTERM, &sa, NULL) == 0)
        return SW_EXIT_OK;
    sw_cli_error("cannot install signal handlers: %s", strerror(errno));
    return SW_EXIT_IO;
}

void sw_cli_interrupt_deferred(void)
{
    deferred = 1;
    immediate = NULL;
}

void sw_cli_interrupt_now(const char *msg)
{
    if (deferred)
        return;
    immediate = msg;
    /* a signal that came while the flag alone was looked at */
    if (msg && sw_cli_signal) {
        sw_cli_error("%s (%s)", msg, sw_cli_signal_name(sw_cli_signal));
        _exit(128 + sw_cli_signal);
    }
}

int sw_cli_interrupt_code(void)
{
    return sw_cli_signal ? 128 + sw_cli_signal : SW_EXIT_OK;
}

const char *sw_cli_signal_name(int sig)
{
    return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}
