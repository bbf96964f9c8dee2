/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_pool.c - the library's pool of worker threads (pool.c): every task
 * runs exactly once, a round's tasks only after the round before it has
 * ended, whatever the number of threads; the calling thread alone takes
 * them in order; a job it cannot hold runs nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "pool_int.h"

#define ROUNDS 7
#define PER_ROUND 5

/* Rounds of PER_ROUND tasks; the last task done of round r makes round
 * r + 1 available, as the safety factors' searches do. */
typedef struct {
    int round, handed, pending;
    int runs[ROUNDS][PER_ROUND];
    int order[ROUNDS * PER_ROUND], norder; /* task ids in the order taken */
    int early; /* a task ran while its round was not yet the current one */
} rounds_t;

typedef struct {
    int round, slot;

} rtask_t;

static int r_take(void *user, void *task)
{
    rounds_t *R = user;
    if (R->round >= ROUNDS || R->handed == PER_ROUND)
        return 0;
    rtask_t t = {R->round, R->handed++};
    R->pending++;
    R->order[R->norder++] = t.round * PER_ROUND + t.slot;
    memcpy(task, &t, sizeof t);
    return 1;
}

static int r_ended(void *user)
{
    const rounds_t *R = user;
    return R->round >= ROUNDS;
}

static void r_run(void *user, void *task)
{
    rounds_t *R = user;
    const rtask_t *t = task;
    __atomic_fetch_add(&R->runs[t->round][t->slot], 1, __ATOMIC_RELAXED);
}

static void r_done(void *user, void *task)
{
    rounds_t *R = user;
    const rtask_t *t = task;
    if (t->round != R->round)
        R->early = 1;
    if (--R->pending == 0 && R->handed == PER_ROUND) {
        R->round++;
        R->handed = 0;
    }
}

static void run_rounds(int threads, rounds_t *R)
{
    memset(R, 0, sizeof *R);
    const sw_pool_job_t J = {sizeof(rtask_t), r_take, r_ended, r_run, r_done, R};
    sw_pool_run(&J, threads);
}

static void test_rounds(void **state)
{
    (void)state;
    const int threads[] = {0, 1, 2, 3, 8, 1000};
    for (size_t k = 0; k < sizeof threads / sizeof threads[0]; k++) {
        rounds_t R;
        run_rounds(threads[k], &R);
        assert_int_equal(R.round, ROUNDS);
        assert_int_equal(R.norder, ROUNDS * PER_ROUND);
        assert_int_equal(R.early, 0);
        for (int r = 0; r < ROUNDS; r++)
            for (int j = 0; j < PER_ROUND; j++) assert_int_equal(R.runs[r][j], 1);
    }
}

static void test_one_thread_in_order(void **state)
{
    (void)state;
    rounds_t R;
    run_rounds(1, &R);
    for (int i = 0; i < ROUNDS * PER_ROUND; i++) assert_int_equal(R.order[i], i);
}

static void test_bad_job_runs_nothing(void **state)
{
    (void)state;
    rounds_t R;
    memset(&R, 0, sizeof R);
    sw_pool_job_t J = {SW_POOL_TASK_MAX + 1, r_take, r_ended, r_run, r_done, &R};
    sw_pool_run(&J, 2);
    assert_int_equal(R.norder, 0);
    J.task_size = 0;
    sw_pool_run(&J, 2);
    assert_int_equal(R.norder, 0);
    sw_pool_run(NULL, 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rounds),
        cmocka_unit_test(test_one_thread_in_order),
        cmocka_unit_test(test_bad_job_runs_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
