/* SPDX-License-Identifier: GPL-3.0-or-later */
/* farm_mpi.c - the ranks of an MPI job (farm.h): starting MPI when an MPI
 * launcher started this process, agreeing on exit codes, and the messages
 * of a farm: rank 0 hands out jobs costliest first to the ranks that ask
 * (each asks for as many as it has free threads, plus one in reserve so
 * that it never waits idle for the answer) and gathers their results.
 *
 * Messages (MPI_COMM_WORLD):
 *   ASK     rank r -> 0: int, how many jobs r can take
 *   WORK    0 -> r: uint64 job numbers, none when there are no more
 *   RESULT  r -> 0: uint64 job, uint64 bytes of data, uint64 bytes of
 *           messages, then the data and the messages
 * Only the main thread of each rank calls MPI (MPI_THREAD_FUNNELED); it
 * probes without blocking and sleeps between probes, so a rank waiting
 * for work does not spin on a core its worker threads need.  Results are
 * bytes: the ranks must share one architecture, as the nodes of a cluster
 * do.  Errors of MPI calls are returned (MPI_ERRORS_RETURN) and end the
 * job with MPI_Abort, saying which call failed on which rank. */
#include <mpi.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "farm.h"
#include "farm_int.h"

enum { TAG_ASK = 1, TAG_WORK = 2, TAG_RESULT = 3 };

#define HEADER (3 * sizeof(uint64_t)) /* of a RESULT */

static int world_rank(void)
{
    int r = -1;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

static _Noreturn void sw_farm_mpi_abort(const char *why, int code)
{
    fprintf(stderr, "swaywatch: rank %d: %s; stopping every rank\n", world_rank(), why);
    fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, code);
    exit(code); /* MPI_Abort does not return; should it, do not go on */
}

/* An MPI call that failed ends the job. */
static void check(int err, const char *call)
{
    if (err == MPI_SUCCESS)
        return;
    char text[MPI_MAX_ERROR_STRING];
    int len = 0;
    if (MPI_Error_string(err, text, &len) != MPI_SUCCESS)
        snprintf(text, sizeof text, "error %d", err);
    char why[MPI_MAX_ERROR_STRING + 64];
    snprintf(why, sizeof why, "%s failed: %s", call, text);
    sw_farm_mpi_abort(why, SW_EXIT_IO);
}

static void *alloc_or_abort(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p)
        sw_farm_mpi_abort("out of memory", SW_EXIT_IO);
    return p;
}

/* ---- the world ----------------------------------------------------------------- */

/* Started by an MPI launcher: Open MPI's mpirun, a PMIx or PMI launcher
 * (srun --mpi=pmix or pmi2, MPICH's hydra). */
static int launched(void)
{
    static const char *const vars[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"};
    for (size_t i = 0; i < sizeof vars / sizeof vars[0]; i++)
        if (getenv(vars[i]))
            return 1;
    return 0;
}

/* The farm's messages, handed to the farm by the world (farm_int.h). */
static int sw_farm_mpi_serve(sw_farm_t *st, int *open);
static void sw_farm_mpi_worker(sw_farm_t *st);
static const struct sw_farm_ranks mpi_ranks = {
    .serve = sw_farm_mpi_serve, .worker = sw_farm_mpi_worker, .abort = sw_farm_mpi_abort};

int sw_cli_world_start(sw_cli_world_t *w)
{
    *w = (sw_cli_world_t){.rank = 0, .size = 1, .mpi = 0, .local = 1};
    const char *tasks = getenv("SLURM_STEP_NUM_TASKS");
    if (!launched()) {
        if (tasks && atol(tasks) > 1) {
            sw_cli_error(
                "srun started %s tasks without MPI (no PMI): each would do the whole "
                "work; give srun --mpi=pmix (or pmi2), or run one task",
                tasks);
            return SW_EXIT_USAGE;
        }
        return SW_EXIT_OK;
    }
    int provided = 0;
    if (MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
        sw_cli_error("MPI cannot be started");
        return SW_EXIT_IO;
    }
    w->mpi = 1;
    w->ranks = &mpi_ranks;
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    check(MPI_Comm_rank(MPI_COMM_WORLD, &w->rank), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &w->size), "MPI_Comm_size");
    if (provided < MPI_THREAD_FUNNELED)
        sw_farm_mpi_abort(
            "the MPI library gives no thread support (MPI_THREAD_FUNNELED), "
            "which the worker threads need",
            SW_EXIT_IO);
    MPI_Comm node;
    check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node),
          "MPI_Comm_split_type");
    check(MPI_Comm_size(node, &w->local), "MPI_Comm_size");
    MPI_Comm_free(&node);
    /* Rank 0 writes the outputs; the others' --help, summaries and the
     * like would only repeat it. */
    if (w->rank != 0 && !freopen("/dev/null", "w", stdout))
        sw_farm_mpi_abort("cannot send standard output to /dev/null", SW_EXIT_IO);
    return SW_EXIT_OK;
}

int sw_cli_world_agree(const sw_cli_world_t *w, int rc, const char *msgs, size_t len)
{
    if (!w->mpi)
        return rc;
    int worst = rc, r0 = rc;
    check(MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
    check(MPI_Bcast(&r0, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
    if (w->rank != 0 && rc != SW_EXIT_OK && r0 == SW_EXIT_OK) {
        /* what rank 0 could do and this rank could not (a file missing on
         * this node): its own words */
        fprintf(stderr, "swaywatch: rank %d of %d failed where rank 0 did not:\n", w->rank,
                w->size);
        if (msgs)
            fwrite(msgs, 1, len, stderr);
        fflush(stderr);
    }
    return worst;
}

int sw_cli_world_share(const sw_cli_world_t *w, int rc, char **text, size_t *len)
{
    if (!w->mpi)
        return rc;
    check(MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
    if (rc != SW_EXIT_OK)
        return rc;
    uint64_t n = *len;
    check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
    if (w->rank != 0) {
        *len = (size_t)n;
        *text = alloc_or_abort(*len + 1);
        (*text)[*len] = '\0';
    }
    for (size_t at = 0; at < *len;) { /* counts are ints */
        const size_t part = *len - at < (size_t)INT32_MAX ? *len - at : (size_t)INT32_MAX;
        check(MPI_Bcast(*text + at, (int)part, MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
        at += part;
    }
    return rc;
}

int sw_cli_world_end(sw_cli_world_t *w, int rc)
{
    if (!w->mpi)
        return rc;
    fflush(stdout);
    check(MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
    MPI_Finalize();
    w->mpi = 0;
    return rc;
}

void sw_cli_world_exit(const sw_cli_world_t *w, int code)
{
    fflush(stdout);
    fflush(stderr);
    if (w->mpi && w->size > 1)
        MPI_Abort(MPI_COMM_WORLD, code); /* the other ranks too */
    _exit(code);
}

/* ---- rank 0 ----------------------------------------------------------------------- */

static void answer_ask(sw_farm_t *st, int from, int *open)
{
    int want = 0;
    check(MPI_Recv(&want, 1, MPI_INT, from, TAG_ASK, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
          "MPI_Recv");
    if (want < 1)
        want = 1;
    uint64_t *jobs = alloc_or_abort((size_t)want * sizeof *jobs);
    int k = 0;
    size_t i;
    pthread_mutex_lock(&st->mu);
    while (k < want && sw_farm_next(st, &i)) jobs[k++] = (uint64_t)i;
    pthread_mutex_unlock(&st->mu);
    check(MPI_Send(jobs, k, MPI_UINT64_T, from, TAG_WORK, MPI_COMM_WORLD), "MPI_Send");
    free(jobs);
    if (k == 0)
        (*open)--; /* that rank stops asking */
}

static void take_result(sw_farm_t *st, const MPI_Status *s)
{
    int count = 0;
    check(MPI_Get_count(s, MPI_BYTE, &count), "MPI_Get_count");
    char *buf = alloc_or_abort((size_t)count);
    check(MPI_Recv(buf, count, MPI_BYTE, s->MPI_SOURCE, TAG_RESULT, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE),
          "MPI_Recv");
    uint64_t h[3];
    if ((size_t)count < HEADER)
        sw_farm_mpi_abort("a result message is too short", SW_EXIT_IO);
    memcpy(h, buf, HEADER);
    if (h[0] >= st->f->n || h[1] + h[2] != (size_t)count - HEADER)
        sw_farm_mpi_abort("a result message does not add up", SW_EXIT_IO);
    sw_farm_result_t r = {0};
    r.len = (size_t)h[1];
    r.mlen = (size_t)h[2];
    r.data = alloc_or_abort(r.len);
    r.msgs = alloc_or_abort(r.mlen);
    memcpy(r.data, buf + HEADER, r.len);
    memcpy(r.msgs, buf + HEADER + r.len, r.mlen);
    free(buf);
    pthread_mutex_lock(&st->mu);
    if (st->res[h[0]].ready) {
        pthread_mutex_unlock(&st->mu);
        sw_farm_mpi_abort("a job's result came twice", SW_EXIT_IO);
    }
    sw_farm_store(st, (size_t)h[0], &r, s->MPI_SOURCE);
    pthread_mutex_unlock(&st->mu);
}

static int sw_farm_mpi_serve(sw_farm_t *st, int *open)
{
    int any = 0;
    for (;;) {
        int flag = 0;
        MPI_Status s;
        check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &s), "MPI_Iprobe");
        if (!flag)
            return any;
        any = 1;
        if (s.MPI_TAG == TAG_ASK)
            answer_ask(st, s.MPI_SOURCE, open);
        else if (s.MPI_TAG == TAG_RESULT)
            take_result(st, &s);
        else
            sw_farm_mpi_abort("a message of an unknown kind came", SW_EXIT_IO);
    }
}

/* ---- the other ranks ----------------------------------------------------------------- */

static void send_result(size_t i, const sw_farm_result_t *r)
{
    const size_t len = HEADER + r->len + r->mlen;
    if (len > (size_t)INT32_MAX)
        sw_farm_mpi_abort("a job's result is over 2 GiB", SW_EXIT_IO);
    char *buf = alloc_or_abort(len);
    const uint64_t h[3] = {i, r->len, r->mlen};
    memcpy(buf, h, HEADER);
    if (r->len)
        memcpy(buf + HEADER, r->data, r->len);
    if (r->mlen)
        memcpy(buf + HEADER + r->len, r->msgs, r->mlen);
    check(MPI_Send(buf, (int)len, MPI_BYTE, 0, TAG_RESULT, MPI_COMM_WORLD), "MPI_Send");
    free(buf);
}

static void nap(sw_farm_t *st)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    ts.tv_nsec += 1000000L; /* 1 ms: the latency of an answer, nothing next to a job */
    if (ts.tv_nsec >= 1000000000L) {
        ts.tv_sec++;
        ts.tv_nsec -= 1000000000L;
    }
    pthread_cond_timedwait(&st->cv, &st->mu, &ts);
}

static void sw_farm_mpi_worker(sw_farm_t *st)
{
    uint64_t *got = alloc_or_abort(st->qcap * sizeof *got);
    MPI_Request req = MPI_REQUEST_NULL;
    int asking = 0;
    pthread_mutex_lock(&st->mu);
    for (;;) {
        if (st->oom) {
            pthread_mutex_unlock(&st->mu);
            sw_farm_mpi_abort("out of memory", SW_EXIT_IO);
        }
        int moved = 0;
        while (st->done) { /* results first: rank 0 writes them as they come */
            sw_farm_done_t *d = st->done;
            st->done = d->next;
            if (!st->done)
                st->done_tail = NULL;
            pthread_mutex_unlock(&st->mu);
            send_result(d->i, &d->r);
            free(d->r.data);
            free(d->r.msgs);
            free(d);
            pthread_mutex_lock(&st->mu);
            moved = 1;
        }
        const size_t busy = st->qlen + (size_t)st->running;
        if (!asking && !st->exhausted && busy < st->qcap) {
            const int want = (int)(st->qcap - busy);
            pthread_mutex_unlock(&st->mu);
            check(MPI_Send(&want, 1, MPI_INT, 0, TAG_ASK, MPI_COMM_WORLD), "MPI_Send");
            check(MPI_Irecv(got, want, MPI_UINT64_T, 0, TAG_WORK, MPI_COMM_WORLD, &req),
                  "MPI_Irecv");
            pthread_mutex_lock(&st->mu);
            asking = moved = 1;
        }
        if (asking) {
            int flag = 0;
            MPI_Status s;
            pthread_mutex_unlock(&st->mu);
            check(MPI_Test(&req, &flag, &s), "MPI_Test");
            int count = 0;
            if (flag)
                check(MPI_Get_count(&s, MPI_UINT64_T, &count), "MPI_Get_count");
            pthread_mutex_lock(&st->mu);
            if (flag) {
                asking = 0;
                moved = 1;
                for (int k = 0; k < count; k++) {
                    st->queue[(st->qhead + st->qlen) % st->qcap] = (size_t)got[k];
                    st->qlen++;
                }
                if (count == 0)
                    st->exhausted = 1;
                pthread_cond_broadcast(&st->cv);
            }
        }
        if (st->exhausted && !st->qlen && !st->running && !st->done)
            break;
        if (!moved)
            nap(st);
    }
    pthread_mutex_unlock(&st->mu);
    free(got);
}
