/* SPDX-License-Identifier: GPL-3.0-or-later */
/* farm.c - many independent jobs over the threads of one process (farm.h);
 * with MPI (farm_mpi.c) the same, on every rank, with rank 0 handing out
 * the jobs and gathering the results.
 *
 * Threads: a helper thread runs the library's sw_parallel_for() over the
 * worker threads; each call of its job takes the next job (on rank 0 from
 * the costliest-first order, elsewhere from what rank 0 sent) or returns
 * at once when there is none.  The calling (main) thread hands the results
 * to the command in the jobs' order, and under MPI it alone talks to the
 * other ranks (MPI_THREAD_FUNNELED).  It sleeps on a condition variable
 * between events, never spins. */
#define _GNU_SOURCE /* sched_getaffinity, CPU_COUNT */
#include "farm.h"

#include <errno.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "farm_int.h"
#include "swaywatch/pool.h"

/* ---- without MPI, the world is one process ------------------------------------ */

#ifndef SW_HAVE_MPI
int sw_cli_world_start(sw_cli_world_t *w)
{
    *w = (sw_cli_world_t){.rank = 0, .size = 1, .mpi = 0, .local = 1};
    /* srun, Open MPI's mpirun, MPICH's: each task would do the whole work
     * and write the same outputs */
    static const char *const launchers[][2] = {{"SLURM_STEP_NUM_TASKS", "srun"},
                                               {"OMPI_COMM_WORLD_SIZE", "mpirun"},
                                               {"PMI_SIZE", "mpiexec"}};
    for (size_t i = 0; i < sizeof launchers / sizeof launchers[0]; i++) {
        const char *tasks = getenv(launchers[i][0]);
        if (tasks && atol(tasks) > 1) {
            sw_cli_error(
                "%s started %s tasks, and this program has no MPI to share the work among "
                "them: run one task, or run swaywatch-mpi (the swaywatch-mpi package, a "
                "build with MPI)",
                launchers[i][1], tasks);
            return SW_EXIT_USAGE;
        }
    }
    return SW_EXIT_OK;
}

int sw_cli_world_agree(const sw_cli_world_t *w, int rc, const char *msgs, size_t len)
{
    (void)w;
    (void)msgs;
    (void)len;
    return rc;
}

int sw_cli_world_share(const sw_cli_world_t *w, int rc, char **text, size_t *len)
{
    (void)w;
    (void)text;
    (void)len;
    return rc;
}

int sw_cli_world_end(sw_cli_world_t *w, int rc)
{
    (void)w;
    return rc;
}

void sw_cli_world_exit(const sw_cli_world_t *w, int code)
{
    (void)w;
    fflush(stderr);
    _exit(code);
}
#endif

int sw_cli_threads(const sw_cli_world_t *w, long n)
{
    if (n > 0)
        return (int)n;
    long online = sysconf(_SC_NPROCESSORS_ONLN);
    if (online < 1)
        online = 1;
    long cpus = online;
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0)
        cpus = CPU_COUNT(&set);
    /* Ranks that were not bound each see every CPU of the machine: share
     * them rather than start ranks x CPUs threads. */
    if (w->local > 1 && cpus >= online)
        cpus /= w->local;
    return cpus > 0 ? (int)cpus : 1;
}

/* ---- one job -------------------------------------------------------------------- */

int sw_farm_run_one(sw_farm_t *st, size_t i, sw_farm_result_t *r)
{
    memset(r, 0, sizeof *r);
    FILE *out = open_memstream(&r->data, &r->len);
    FILE *msgs = open_memstream(&r->msgs, &r->mlen);
    if (!out || !msgs)
        goto oom;
    FILE *before = sw_cli_msg_to(msgs);
    st->f->run(st->f->user, i, out);
    sw_cli_msg_to(before == stderr ? NULL : before);
    int bad = fclose(out) != 0;
    out = NULL;
    bad |= fclose(msgs) != 0;
    msgs = NULL;
    if (bad)
        goto oom;
    r->ready = 1;
    return 0;
oom:
    if (out)
        fclose(out);
    if (msgs)
        fclose(msgs);
    free(r->data);
    free(r->msgs);
    memset(r, 0, sizeof *r);
    return -1;
}

/* The farm's stop flag (a signal) is set. */
static int stopped(const sw_farm_t *st)
{
    return st->f->stop && *st->f->stop;
}

int sw_farm_next(sw_farm_t *st, size_t *i)
{
    if (st->stop || stopped(st) || st->next >= st->f->n)
        return 0;
    *i = st->order[st->next++];
    return 1;
}

void sw_farm_store(sw_farm_t *st, size_t i, sw_farm_result_t *r, int from)
{
    if (st->f->by_rank)
        st->f->by_rank[from]++;
    st->res[i] = *r;
    st->res[i].ready = 1;
    st->arrived++;
    pthread_cond_broadcast(&st->cv);
}

static void fail_oom(sw_farm_t *st)
{
    st->stop = st->oom = 1;
    pthread_cond_broadcast(&st->cv);
}

/* A worker thread's job on rank 0: the next job in order, if any. */
static void job_rank0(void *user, size_t unused)
{
    (void)unused;
    sw_farm_t *st = user;
    size_t i;
    pthread_mutex_lock(&st->mu);
    const int have = sw_farm_next(st, &i);
    pthread_mutex_unlock(&st->mu);
    if (!have)
        return;
    sw_farm_result_t r;
    const int bad = sw_farm_run_one(st, i, &r);
    pthread_mutex_lock(&st->mu);
    if (bad)
        fail_oom(st);
    else
        sw_farm_store(st, i, &r, 0);
    pthread_mutex_unlock(&st->mu);
}

/* A worker thread's job on another rank: the next job rank 0 sent, once
 * it came, or none when rank 0 has no more. */
static void job_remote(void *user, size_t unused)
{
    (void)unused;
    sw_farm_t *st = user;
    pthread_mutex_lock(&st->mu);
    while (!st->qlen && !st->exhausted && !st->stop) pthread_cond_wait(&st->cv, &st->mu);
    if (!st->qlen || st->stop) {
        pthread_mutex_unlock(&st->mu);
        return;
    }
    const size_t i = st->queue[st->qhead];
    st->qhead = (st->qhead + 1) % st->qcap;
    st->qlen--;
    st->running++;
    pthread_cond_broadcast(&st->cv); /* room for more: the main thread may ask */
    pthread_mutex_unlock(&st->mu);
    sw_farm_done_t *d = calloc(1, sizeof *d);
    const int bad = !d || sw_farm_run_one(st, i, &d->r);
    pthread_mutex_lock(&st->mu);
    st->running--;
    if (bad) {
        free(d);
        fail_oom(st);
    } else {
        d->i = i;
        if (st->done_tail)
            st->done_tail->next = d;
        else
            st->done = d;
        st->done_tail = d;
        pthread_cond_broadcast(&st->cv);
    }
    pthread_mutex_unlock(&st->mu);
}

/* ---- the worker threads ------------------------------------------------------------ */

typedef struct {
    sw_farm_t *st;
    void (*job)(void *, size_t);
    int done;
} pool_arg_t;

static void *pool(void *arg)
{
    pool_arg_t *a = arg;
    /* n calls at most: every job once, on this rank or another */
    sw_parallel_for(a->st->f->n, a->st->f->threads, a->job, a->st);
    pthread_mutex_lock(&a->st->mu);
    a->done = 1;
    pthread_cond_broadcast(&a->st->cv);
    pthread_mutex_unlock(&a->st->mu);
    return NULL;
}

/* ---- progress ------------------------------------------------------------------------ */

static void progress_line(const sw_farm_t *st, size_t done)
{
    fprintf(stderr, "\rswaywatch: %3.0f%% (%zu/%zu %s)", 100.0 * (double)done / (double)st->f->n,
            done, st->f->n, st->f->what);
    fflush(stderr);
}

static void progress_clear(void)
{
    fprintf(stderr, "\r%*s\r", 60, "");
}

/* ---- rank 0 ------------------------------------------------------------------------------ */

/* Costliest first; ties in order. */
static int by_cost(const void *a, const void *b, void *user)
{
    const double *cost = user;
    const size_t i = *(const size_t *)a, j = *(const size_t *)b;
    if (cost[i] != cost[j])
        return cost[i] < cost[j] ? 1 : -1;
    return i < j ? -1 : i > j;
}

static void make_order(sw_farm_t *st)
{
    for (size_t i = 0; i < st->f->n; i++) st->order[i] = i;
    if (st->f->cost)
        qsort_r(st->order, st->f->n, sizeof *st->order, by_cost, (void *)st->f->cost);
}

static void wait_a_little(sw_farm_t *st, long ns)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    ts.tv_nsec += ns;
    if (ts.tv_nsec >= 1000000000L) {
        ts.tv_sec++;
        ts.tv_nsec -= 1000000000L;
    }
    pthread_cond_timedwait(&st->cv, &st->mu, &ts);
}

/* Hand the results over in order as they come; under MPI serve the other
 * ranks meanwhile. */
static int gather(sw_farm_t *st, pool_arg_t *pa)
{
    const sw_cli_farm_t *f = st->f;
    int open = f->world->size - 1; /* ranks not yet told there is no more */
    size_t emitted = 0, shown = (size_t)-1;
    int rc = SW_EXIT_OK;
    pthread_mutex_lock(&st->mu);
    while (!st->oom && (emitted < f->n || open > 0)) {
        int moved = 0;
        while (emitted < f->n && st->res[emitted].ready && rc == SW_EXIT_OK) {
            sw_farm_result_t r = st->res[emitted];
            memset(&st->res[emitted], 0, sizeof r);
            pthread_mutex_unlock(&st->mu);
            if (f->what && r.mlen && shown != (size_t)-1)
                progress_clear();
            if (f->take(f->user, emitted, r.data, r.len, r.msgs, r.mlen) != 0)
                rc = SW_EXIT_IO;
            free(r.data);
            free(r.msgs);
            pthread_mutex_lock(&st->mu);
            emitted++;
            moved = 1;
        }
        if (rc != SW_EXIT_OK) {
            st->stop = 1;
            pthread_cond_broadcast(&st->cv);
            break;
        }
        if (stopped(st)) {
            /* a signal: no new job; what is in is handed over, in order
             * with gaps, and the jobs still running are not waited for */
            st->stop = st->interrupted = 1;
            pthread_cond_broadcast(&st->cv);
            for (; emitted < f->n && rc == SW_EXIT_OK; emitted++) {
                if (!st->res[emitted].ready)
                    continue;
                sw_farm_result_t r = st->res[emitted];
                memset(&st->res[emitted], 0, sizeof r);
                pthread_mutex_unlock(&st->mu);
                if (f->take(f->user, emitted, r.data, r.len, r.msgs, r.mlen) != 0)
                    rc = SW_EXIT_IO;
                free(r.data);
                free(r.msgs);
                pthread_mutex_lock(&st->mu);
            }
            break;
        }
        if (f->what && (moved || st->arrived != shown)) {
            shown = st->arrived;
            progress_line(st, shown);
        }
        if (f->world->ranks && f->world->size > 1) {
            pthread_mutex_unlock(&st->mu);
            moved |= f->world->ranks->serve(st, &open);
            pthread_mutex_lock(&st->mu);
        }
        if (moved)
            continue;
        if (pa->done && emitted < f->n && !st->res[emitted].ready && f->world->size == 1) {
            st->oom = 1; /* every job ran, and one result is missing: cannot be */
            break;
        }
        /* without other ranks nothing comes but a signal; with them, poll
         * MPI every millisecond at most */
        wait_a_little(st, f->world->size > 1 ? 1000000L : 100000000L);
    }
    pthread_mutex_unlock(&st->mu);
    if (f->what && shown != (size_t)-1)
        fputc('\n', stderr);
    return rc == SW_EXIT_OK && st->interrupted ? SW_CLI_FARM_INTERRUPTED : rc;
}

/* ---- the farm ---------------------------------------------------------------------------- */

int sw_cli_farm_run(const sw_cli_farm_t *f)
{
    /* On the heap: after a signal the farm returns while jobs still run
     * and use it (the caller then ends the process). */
    sw_farm_t *st = calloc(1, sizeof *st);
    pool_arg_t *pa = calloc(1, sizeof *pa);
    if (!st || !pa) {
        free(st);
        free(pa);
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    st->f = f;
    pthread_mutex_init(&st->mu, NULL);
    pthread_cond_init(&st->cv, NULL);
    const int root = f->world->rank == 0;
    int rc = SW_EXIT_OK;
    if (root) {
        st->order = calloc(f->n ? f->n : 1, sizeof *st->order);
        st->res = calloc(f->n ? f->n : 1, sizeof *st->res);
        if (!st->order || !st->res)
            st->oom = 1;
    } else {
        st->qcap = (size_t)f->threads + 1;
        st->queue = calloc(st->qcap, sizeof *st->queue);
        if (!st->queue)
            st->oom = 1;
    }
    if (st->oom) {
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
        goto out;
    }
    if (root)
        make_order(st);
    if (root && f->by_rank)
        memset(f->by_rank, 0, (size_t)f->world->size * sizeof *f->by_rank);

    *pa = (pool_arg_t){.st = st, .job = job_rank0};
    if (!root)
        pa->job = job_remote;
    pthread_t helper;
    const int threaded = pthread_create(&helper, NULL, pool, pa) == 0;
    if (!threaded) {
        if (f->world->size > 1) {
            sw_cli_error("cannot start a thread: %s", strerror(errno));
            rc = SW_EXIT_IO;
            goto out;
        }
        pool(pa); /* one process: run everything here, then hand it over */
    }
    if (root)
        rc = gather(st, pa);
    else
        f->world->ranks->worker(st);
    if (rc == SW_CLI_FARM_INTERRUPTED)
        return rc; /* st and pa stay: jobs may be running */
    /* The other ranks wait for work or answers that will not come. */
    if (f->world->ranks && f->world->size > 1 && (rc != SW_EXIT_OK || st->oom))
        f->world->ranks->abort(st->oom ? "out of memory" : "the results cannot be written",
                               SW_EXIT_IO);
    if (threaded) {
        pthread_mutex_lock(&st->mu);
        st->stop = 1; /* jobs not started stay so */
        pthread_cond_broadcast(&st->cv);
        pthread_mutex_unlock(&st->mu);
        pthread_join(helper, NULL);
    }
    if (st->oom) {
        sw_cli_error("out of memory");
        rc = SW_EXIT_IO;
    }
out:
    if (st->res)
        for (size_t i = 0; i < f->n; i++) {
            free(st->res[i].data);
            free(st->res[i].msgs);
        }
    free(st->res);
    free(st->order);
    free(st->queue);
    while (st->done) {
        sw_farm_done_t *d = st->done;
        st->done = d->next;
        free(d->r.data);
        free(d->r.msgs);
        free(d);
    }
    pthread_cond_destroy(&st->cv);
    pthread_mutex_destroy(&st->mu);
    free(st);
    free(pa);
    return rc;
}
