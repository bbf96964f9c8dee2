/* SPDX-License-Identifier: GPL-3.0-or-later */
/* farm.h - many independent jobs (the logs of a batch, the points of a
 * boundary sweep) spread over threads, and over the ranks of an MPI job
 * when swaywatch was started by mpirun or srun (a build with MPI).
 *
 * Jobs start from the costliest (logs differ in length by orders of
 * magnitude: the long ones must not be the last to start), and each
 * thread, each rank, takes the next when it is free: rank 0 hands them
 * out as the others ask (dynamic load balancing) and computes too.  Every
 * result comes back to rank 0, which hands them to the command in the
 * jobs' order, so what is written does not depend on the number of
 * threads or ranks.
 *
 * The ranks of an MPI job all run the command: each parses the options and
 * reads the scenes; only rank 0 writes outputs (the others' standard
 * output goes to /dev/null) and the others' messages are printed only when
 * they alone failed.  Every rank ends with the same exit code. */
#ifndef SWAYWATCH_CLI_FARM_H
#define SWAYWATCH_CLI_FARM_H

#include <signal.h>
#include <stddef.h>
#include <stdio.h>

/* The processes this run is made of. */
typedef struct {
    int rank, size; /* 0 of 1 without MPI */
    int mpi;        /* MPI was started (and must be finalised) */
    int local;      /* ranks on this machine */
    /* the farm's messages between ranks (farm_int.h), given by the world
     * MPI started; NULL in one process */
    const struct sw_farm_ranks *ranks;
} sw_cli_world_t;

/* Start MPI if this process was started by an MPI launcher (mpirun,
 * mpiexec, srun: told by their environment) in a build with MPI; a plain
 * run is rank 0 of 1 and never touches MPI.  Returns SW_EXIT_OK, or
 * SW_EXIT_IO (reported) if MPI cannot be started. */
int sw_cli_world_start(sw_cli_world_t *w);

/* Collective: the worst (highest) of the ranks' exit codes, on every
 * rank.  A rank other than 0 that failed where rank 0 did not prints its
 * messages (msgs, len bytes: what it kept instead of printing them). */
int sw_cli_world_agree(const sw_cli_world_t *w, int rc, const char *msgs, size_t len);

/* Collective: rank 0's rc and, if it is SW_EXIT_OK, its text (*len
 * bytes, a NUL after them) on every rank: what rank 0 alone can read (a
 * manifest on standard input, which mpirun gives rank 0 only).  On the
 * other ranks *text is allocated (free()).  Returns rank 0's rc. */
int sw_cli_world_share(const sw_cli_world_t *w, int rc, char **text, size_t *len);

/* The end: rank 0's exit code on every rank (its outputs decide it), MPI
 * finalised.  Returns that code. */
int sw_cli_world_end(sw_cli_world_t *w, int rc);

/* Worker threads per rank for --threads n: n, or for n <= 0 the CPUs this
 * process may run on (its affinity, as mpirun, srun or taskset bound it),
 * shared by the ranks on this machine when they are not bound. */
int sw_cli_threads(const sw_cli_world_t *w, long n);

typedef struct {
    const sw_cli_world_t *world;
    size_t n;           /* jobs 0 .. n-1 */
    const double *cost; /* a guess of each job's duration (a log's bytes); the costliest
                           start first, ties in order.  NULL: in order */
    int threads;        /* per rank, >= 1 */
    /* Job i: its result written to out (a memory stream).  Any thread of
     * any rank; the thread's messages go to msgs (sw_cli_msg()) and are
     * part of the result too.  A failure is a result, not a reason to
     * stop. */
    void (*run)(void *user, size_t i, FILE *out);
    /* Rank 0: result i (the bytes run wrote) and its messages, in the
     * order i = 0, 1, 2, ..., one at a time.  Returns 0, or non-zero if
     * the results can no longer be written (reported): the farm stops. */
    int (*take)(void *user, size_t i, const char *data, size_t len, const char *msgs, size_t mlen);
    void *user;
    const char *what; /* "logs", "points": the progress line's unit; NULL: no progress */
    long *by_rank;    /* rank 0, if not NULL: set to the jobs each rank ran (size entries) */
    /* If not NULL, a flag a signal handler sets (interrupt.h): once it is
     * non-zero no job starts any more, and rank 0 takes, in order, the
     * results that are in and returns SW_CLI_FARM_INTERRUPTED within a
     * tenth of a second, without waiting for the jobs still running. */
    const volatile sig_atomic_t *stop;
} sw_cli_farm_t;

/* sw_cli_farm_run() was stopped by f->stop: jobs may still be running on
 * other threads and ranks, using the farm's and the caller's data, so the
 * caller must end the process (sw_cli_world_exit) once it has closed its
 * outputs, and must not free anything the jobs use. */
#define SW_CLI_FARM_INTERRUPTED (-1)

/* Run every job once and take every result on rank 0 (collective: every
 * rank calls it).  Returns SW_EXIT_OK, SW_CLI_FARM_INTERRUPTED, or
 * SW_EXIT_IO when take failed (under MPI the job is then aborted, with
 * the reason) or memory ran out (reported). */
int sw_cli_farm_run(const sw_cli_farm_t *f);

/* End the process at once with code (every rank, under MPI: MPI_Abort),
 * without waiting for threads still running: after an interrupted farm,
 * once the outputs are closed. */
void sw_cli_world_exit(const sw_cli_world_t *w, int code) __attribute__((noreturn));

#endif
