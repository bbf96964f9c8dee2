/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pool.c - the library's one pool of worker threads (pool_int.h) and
 * sw_parallel_for() (pool.h) on it.  Threads are started and joined within
 * each call: the library keeps no pool, and no state, between calls. */
#include <pthread.h>
#include <stddef.h>
#include <string.h>

#include "pool_int.h"
#include "swaywatch/pool.h"

typedef struct {
    const sw_pool_job_t *job;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    int locked; /* mu and cv exist: else the calling thread works alone */
} pool_t;

/* One worker: take, run, hand back, until the job has ended. */
static void *worker(void *arg)
{
    pool_t *P = arg;
    const sw_pool_job_t *J = P->job;
    union {
        max_align_t align;
        unsigned char bytes[SW_POOL_TASK_MAX];
    } task;
    if (!P->locked) {
        while (J->take(J->user, &task)) {
            J->run(J->user, &task);
            if (J->done)
                J->done(J->user, &task);
        }
        return NULL;
    }
    pthread_mutex_lock(&P->mu);
    for (;;) {
        if (J->take(J->user, &task)) {
            pthread_mutex_unlock(&P->mu);
            J->run(J->user, &task);
            pthread_mutex_lock(&P->mu);
            if (J->done)
                J->done(J->user, &task);
            pthread_cond_broadcast(&P->cv); /* a round may have ended, or the job */
            continue;
        }
        if (J->ended(J->user))
            break;
        pthread_cond_wait(&P->cv, &P->mu);
    }
    pthread_mutex_unlock(&P->mu);
    return NULL;
}

void sw_pool_run(const sw_pool_job_t *job, int threads)
{
    if (!job || !job->take || !job->ended || !job->run || job->task_size == 0 ||
        job->task_size > SW_POOL_TASK_MAX)
        return;
    pool_t P = {.job = job};
    const size_t want = threads > SW_POOL_MAX_THREADS ? SW_POOL_MAX_THREADS
                        : threads > 1                 ? (size_t)threads
                                                      : 1;
    if (want > 1 && pthread_mutex_init(&P.mu, NULL) == 0) {
        if (pthread_cond_init(&P.cv, NULL) == 0)
            P.locked = 1;
        else
            pthread_mutex_destroy(&P.mu);
    }
    pthread_t tid[SW_POOL_MAX_THREADS];
    size_t started = 0;
    if (P.locked)
        for (; started + 1 < want; started++)
            if (pthread_create(&tid[started], NULL, worker, &P) != 0)
                break;
    worker(&P);
    for (size_t i = 0; i < started; i++) pthread_join(tid[i], NULL);
    if (P.locked) {
        pthread_cond_destroy(&P.cv);
        pthread_mutex_destroy(&P.mu);
    }
}

/* ---- sw_parallel_for: the indices 0 .. n-1, each a task ------------------------ */

typedef struct {
    size_t next, n;
    void (*job)(void *user, size_t i);
    void *user;
} for_t;

static int for_take(void *user, void *task)
{
    for_t *F = user;
    if (F->next >= F->n)
        return 0;
    const size_t i = F->next++;
    memcpy(task, &i, sizeof i);
    return 1;
}

static int for_ended(void *user)
{
    (void)user;
    return 1; /* every index is handed out at once: none comes later */
}

static void for_run(void *user, void *task)
{
    const for_t *F = user;
    size_t i;
    memcpy(&i, task, sizeof i);
    F->job(F->user, i);
}

void sw_parallel_for(size_t n, int threads, void (*job)(void *user, size_t i), void *user)
{
    if (!job || n == 0)
        return;
    for_t F = {0, n, job, user};
    const sw_pool_job_t J = {sizeof(size_t), for_take, for_ended, for_run, NULL, &F};
    sw_pool_run(&J, n < (size_t)(threads > 0 ? threads : 1) ? (int)n : threads);
}
