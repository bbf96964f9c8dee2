/* SPDX-License-Identifier: GPL-3.0-or-later */
/* farm_int.h - the state of a farm (farm.h), shared by the threads of one
 * process (farm.c) and the messages between ranks (farm_mpi.c). */
#ifndef SWAYWATCH_CLI_FARM_INT_H
#define SWAYWATCH_CLI_FARM_INT_H

#include <pthread.h>

#include "farm.h"

/* A job's result: the bytes it wrote, and its messages. */
typedef struct {
    char *data, *msgs;
    size_t len, mlen;
    int ready;
} sw_farm_result_t;

/* One finished job on a rank other than 0, waiting to be sent. */
typedef struct sw_farm_done {
    size_t i;
    sw_farm_result_t r;
    struct sw_farm_done *next;
} sw_farm_done_t;

typedef struct {
    const sw_cli_farm_t *f;
    pthread_mutex_t mu;
    pthread_cond_t cv; /* a job finished, work arrived, or the farm stops */
    int stop;          /* no new job: take failed, memory ran out, a signal */
    int interrupted;   /* rank 0: the farm's stop flag ended it */
    int oom;
    /* rank 0 */
    size_t *order;         /* the jobs, costliest first */
    size_t next;           /* the next in order to hand out */
    sw_farm_result_t *res; /* by job */
    size_t arrived;        /* results in */
    /* other ranks: the jobs rank 0 gave, not started, and the finished */
    size_t *queue;
    size_t qhead, qlen, qcap;
    int exhausted; /* rank 0 has no more */
    int running;   /* jobs started, not yet in done */
    sw_farm_done_t *done, *done_tail;
} sw_farm_t;

/* Run job i into r (the thread's messages collected); -1 if out of memory. */
int sw_farm_run_one(sw_farm_t *st, size_t i, sw_farm_result_t *r);
/* Rank 0, mu held: the next job to start (1), or none left (0). */
int sw_farm_next(sw_farm_t *st, size_t *i);
/* Rank 0, mu held: job i's result is in, from rank from (r's buffers are
 * taken). */
void sw_farm_store(sw_farm_t *st, size_t i, sw_farm_result_t *r, int from);

/* The messages between ranks (farm_mpi.c, in a build with MPI), which the
 * world gives the farm (sw_cli_world_t.ranks) once MPI has started: the
 * farm's threads (farm.c) reach them through it, as a lower layer reaches
 * what it is handed, while the messages call the farm's queue above. */
struct sw_farm_ranks {
    /* Rank 0: answer what the other ranks sent (requests for work,
     * results); mu not held.  Returns non-zero if anything came.  *open
     * is the number of ranks not yet told there is no more work. */
    int (*serve)(sw_farm_t *st, int *open);
    /* Any other rank: ask rank 0 for work, run it on the threads, send
     * the results back, until rank 0 has no more and all is sent.  The
     * worker threads run already. */
    void (*worker)(sw_farm_t *st);
    /* A failure every rank must stop for: why on stderr, then MPI_Abort;
     * does not return. */
    void (*abort)(const char *why, int code);
};

#endif
