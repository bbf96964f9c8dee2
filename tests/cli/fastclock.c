/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fastclock.c - LD_PRELOAD shim for tests/cli/cost.sh: the process's and
 * threads' CPU clocks run a million times fast, as on a machine so loaded
 * that every measurement of CPU time comes out huge.  A decision that
 * timed the engine would change under it; one made from the scene does
 * not. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <time.h>

int clock_gettime(clockid_t id, struct timespec *ts)
{
    static int (*real)(clockid_t, struct timespec *);
    if (!real)
        real = (int (*)(clockid_t, struct timespec *))dlsym(RTLD_NEXT, "clock_gettime");
    const int r = real(id, ts);
    if (r == 0 && (id == CLOCK_PROCESS_CPUTIME_ID || id == CLOCK_THREAD_CPUTIME_ID)) {
        const long double t = ((long double)ts->tv_sec + 1e-9L * ts->tv_nsec) * 1e6L;
        ts->tv_sec = (time_t)t;
        ts->tv_nsec = (long)((t - (long double)ts->tv_sec) * 1e9L);
    }
    return r;
}
