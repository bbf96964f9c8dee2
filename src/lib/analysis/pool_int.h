/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pool_int.h - the library's one pool of worker threads (pool.c), for
 * every analysis that runs independent trials at once: sw_parallel_for()
 * (boundary points, the what-ifs' reserves) and the safety factors'
 * searches, whose rounds are tasks that the end of a round makes
 * available.  Internal: not part of the public API.
 *
 * The pool asks its job for tasks and hands them back under one lock;
 * only run() works outside it.  A task is a small value of the job's own
 * type (task_size bytes, at most SW_POOL_TASK_MAX), copied into the
 * worker that runs it: the job keeps no per-thread state, so a result
 * cannot depend on the thread that computed it. */
#ifndef SWAYWATCH_POOL_INT_H
#define SWAYWATCH_POOL_INT_H

#include <stddef.h>

#define SW_POOL_MAX_THREADS 256
#define SW_POOL_TASK_MAX 512 /* bytes of one task */

typedef struct {
    size_t task_size; /* bytes of a task, 1 .. SW_POOL_TASK_MAX */
    /* Under the lock: put the next task into *task and return 1, or
     * return 0 if none is available now. */
    int (*take)(void *user, void *task);
    /* Under the lock, when take() gave none: 1 if no task will come any
     * more (the worker ends), 0 if one may (a task still running will
     * make it available: the worker waits). */
    int (*ended)(void *user);
    /* Without the lock: the work of one task, results into the task. */
    void (*run)(void *user, void *task);
    /* Under the lock, may be NULL: the task ran; new tasks may be
     * available now (the next round). */
    void (*done)(void *user, void *task);
    void *user;
} sw_pool_job_t;

/* Run the job's tasks on up to threads threads, the calling thread one
 * of them (0 or 1: the calling thread alone, taking the tasks in order).
 * If a thread cannot be started the others do its share, and if the lock
 * cannot be made the calling thread does all.  Returns when ended() says
 * so and every task taken is done. */
void sw_pool_run(const sw_pool_job_t *job, int threads);

#endif
