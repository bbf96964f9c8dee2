/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pool.h - independent jobs on worker threads, for callers that run many
 * analyses at once.  The library keeps no pool between calls: threads are
 * started and joined within each call. */
#ifndef SWAYWATCH_POOL_H
#define SWAYWATCH_POOL_H

#include <stddef.h>

#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Call job(user, i) for i = 0 .. n-1 on up to threads threads (0 or 1:
 * in the calling thread, in order), each thread taking the next index when
 * it is free.  Jobs must be independent: each writes only its own results.
 * If a thread cannot be started its share runs on the others (or in the
 * calling thread); every job runs exactly once. */
SW_API void sw_parallel_for(size_t n, int threads, void (*job)(void *user, size_t i), void *user);

#ifdef __cplusplus
}
#endif
#endif
