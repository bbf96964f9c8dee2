/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sweep.h - the analyses made of many runs of the engine, in one include,
 * as before they had headers of their own: one run (run.h), the
 * threshold search (search.h), the boundary curves (boundary.h), the
 * safety factor of a log (safety.h) and parallel jobs (pool.h).  New code
 * includes the header it needs. */
#ifndef SWAYWATCH_SWEEP_H
#define SWAYWATCH_SWEEP_H

#include "boundary.h"
#include "pool.h"
#include "run.h"
#include "safety.h"
#include "search.h"

#endif
