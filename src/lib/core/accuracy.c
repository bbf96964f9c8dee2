/* SPDX-License-Identifier: GPL-3.0-or-later */
/* accuracy.c - from a tolerance on the sway angle to a scheme and a step,
 * by a table of measured errors (docs/accuracy-speed.md, "Accuracy
 * option": scripts/run-bench.sh prints the rows a run measures, and
 * scripts/accuracy-rows.sh writes the rows below into the document).
 *
 * Each row is the cheapest setting (ns per input sample while rocking; the
 * default when it is within 25 % of that) whose worst error in max|theta|
 * over the benchmark's pulses (half-sine braking at 0.9 of the overturning
 * boundary, omega_e/p = 1.5 .. 12, 1 kHz samples) against rk8pd at rtol
 * 1e-12 was at most half the row's tolerance.  No step was longer than
 * the 1 ms of the samples, so an engine whose setting comes from here
 * keeps its steps within SW_ACCURACY_HMAX whatever its input (engine.c).
 * The pulses were run on the reference crate (2 m x 0.728 m, p = 2.63 rad/s;
 * frame: gamma = 0.8, omega_b = 5.59 rad/s, zeta_b = 0.1).  A fixed-step
 * error grows as (p dt)^order: for a package with a larger p, or stiffer
 * bearings, pick a tighter tolerance or check with the benchmark. */
#include <math.h>
#include <stddef.h>

#include "swaywatch/scheme.h"
#include "swaywatch/status.h"

typedef struct {
    sw_model_kind model;
    double tol; /* rad: the row serves tolerances >= tol */
    const char *scheme;
    double dt; /* s; 0 = the scheme's default (adaptive: rtol 1e-10) */
} acc_row_t;

/* Rows of one model in decreasing tol (cheapest first), as printed by
 * sw_bench run (docs/accuracy-speed.md, measured 2026-11-22 on an idle
 * machine).  The errors behind them, worst over the pulses, bare / frame:
 * rk4 at 1 ms 1.9e-11 / 5.6e-12 rad; rk4 at 0.5 ms 1.2e-12 / 3.6e-13;
 * rkf45 1.9e-14 / 1.2e-14; rkck 3.1e-15 / 1.3e-15.  Below 1e-14 rad the
 * reference itself is not that good.  (Heun at 1 ms, 4.5e-5 rad on the
 * bare block, was within 25 % of RK4's cost in this run, so the default
 * serves the loose tolerances.) */
static const acc_row_t rows[] = {
    {SW_MODEL_BARE, 1e-10, "rk4", 1e-3},   {SW_MODEL_BARE, 1e-11, "rk4", 5e-4},
    {SW_MODEL_BARE, 1e-13, "rkf45", 0.0},  {SW_MODEL_BARE, 1e-14, "rkck", 0.0},
    {SW_MODEL_FRAME, 1e-10, "rk4", 1e-3},  {SW_MODEL_FRAME, 1e-12, "rk4", 5e-4},
    {SW_MODEL_FRAME, 1e-13, "rkf45", 0.0}, {SW_MODEL_FRAME, 1e-14, "rkck", 0.0},
};

int sw_scheme_for_accuracy(sw_model_kind model, double theta_tol, const char **scheme, double *dt)
{
    if (!scheme || !dt || !(theta_tol > 0.0) || isnan(theta_tol))
        return SW_EINVAL;
    int known = 0;
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        if (rows[i].model != model)
            continue;
        known = 1;
        if (theta_tol >= rows[i].tol) {
            *scheme = rows[i].scheme;
            *dt = rows[i].dt;
            return SW_OK;
        }
    }
    return known ? SW_ENOTFOUND : SW_EINVAL;
}

int sw_scheme_for_accuracy_n(const sw_scene_t *scenes, size_t n, double theta_tol,
                             const char **scheme, double *dt, size_t *bad)
{
    if (!scenes || n == 0 || !scheme || !dt)
        return SW_EINVAL;
    /* The table's rows are ordered from cheap to accurate; for several
     * packages keep the most accurate (adaptive first, then the higher
     * order, then the smaller step). */
    int best = -1;
    *scheme = NULL;
    *dt = 0.0;
    for (size_t i = 0; i < n; i++) {
        sw_derived_t d;
        const char *si = NULL;
        double dti = 0.0;
        int r = sw_scene_validate(&scenes[i], &d, NULL, NULL, NULL);
        if (r == SW_OK)
            r = sw_scheme_for_accuracy(d.model, theta_tol, &si, &dti);
        if (r != SW_OK) {
            if (bad)
                *bad = i;
            return r;
        }
        const sw_scheme_t *T = sw_scheme_lookup(si);
        const int rank = T ? 2 * sw_scheme_adaptive(T) * 100 + sw_scheme_order(T) : 0;
        if (rank > best || (rank == best && dti > 0.0 && (*dt == 0.0 || dti < *dt))) {
            best = rank;
            *scheme = si;
            *dt = dti;
        }
    }
    return SW_OK;
}
