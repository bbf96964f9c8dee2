/* SPDX-License-Identifier: GPL-3.0-or-later */
/* boundary_sweep.c - the sweep of "swaywatch boundary": the curves in
 * groups that share the points and the scan, each group one run of the
 * library's boundary sweep (sweep.h) on the worker threads, or under
 * mpirun or srun its points spread over the ranks too (farm.h); the
 * points, and the first failure, do not depend on how they were spread. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boundary.h"
#include "interrupt.h"

/* ---- progress ------------------------------------------------------------------ */

/* The curves are swept in groups: the points before this group, and all. */
typedef struct {
    size_t offset, total;
} progress_t;

static void on_progress(void *user, size_t done, size_t total)
{
    const progress_t *P = user;
    (void)total;
    done += P->offset;
    fprintf(stderr, "\rswaywatch: boundary %3.0f%% (%zu/%zu points)", 100.0 * done / P->total, done,
            P->total);
    if (done == P->total)
        fputc('\n', stderr);
    fflush(stderr);
}

/* Curves a and b take the same points and the same scan: one sweep. */
static int same_sweep(const boundary_t *B, size_t a, size_t b)
{
    const curve_t *A = &B->cv[a], *C = &B->cv[b];
    return A->x_min == C->x_min && A->x_max == C->x_max && (!B->b.durations || A->p == C->p);
}

/* ---- the points over the ranks of an MPI job -------------------------------------- */

/* One group's sweep: its curves at its ratios, into gp (curve-major). */
typedef struct {
    const sw_cli_world_t *world;
    const sw_curve_t *curves;
    size_t k;
    const double *ratios;
    size_t nr;
    const sw_boundary_opts_t *bo;
    sw_boundary_point_t *gp;
    char (*msgs)[256];
    int progress;
} group_t;

/* One point, on any thread of any rank: the point, then its message. */
static void point_run(void *user, size_t i, FILE *out)
{
    const group_t *G = user;
    sw_boundary_point_t pt;
    memset(&pt, 0, sizeof pt);
    char msg[256] = "";
    sw_boundary_point(&G->curves[i / G->nr], G->ratios[i % G->nr], G->bo, &pt, msg, sizeof msg);
    fwrite(&pt, sizeof pt, 1, out);
    fputs(msg, out);
}

static int point_take(void *user, size_t i, const char *data, size_t len, const char *msgs,
                      size_t mlen)
{
    group_t *G = user;
    if (mlen)
        fwrite(msgs, 1, mlen, stderr);
    if (len < sizeof *G->gp) {
        sw_cli_error("boundary: point %zu came back short", i + 1);
        return -1;
    }
    memcpy(&G->gp[i], data, sizeof *G->gp);
    size_t m = len - sizeof *G->gp;
    if (m >= sizeof G->msgs[i])
        m = sizeof G->msgs[i] - 1;
    memcpy(G->msgs[i], data + sizeof *G->gp, m);
    G->msgs[i][m] = '\0';
    return 0;
}

/* What sw_boundary_sweep() does, with the points spread over the ranks:
 * the same points, the same first failure in (curve, ratio) order.
 * *exit_code: the exit code if it failed. */
static int sweep_ranks(group_t *G, char *msg, size_t msglen, int *exit_code)
{
    const size_t np = G->k * G->nr;
    G->msgs = calloc(np, sizeof *G->msgs);
    if (!G->msgs) {
        snprintf(msg, msglen, "out of memory");
        *exit_code = SW_EXIT_IO;
        return SW_ENOMEM;
    }
    const sw_cli_farm_t farm = {
        .world = G->world,
        .n = np,
        .threads = G->bo->threads,
        .run = point_run,
        .take = point_take,
        .user = G,
        .what = G->progress ? "points" : NULL,
    };
    *exit_code = sw_cli_farm_run(&farm);
    int rc = *exit_code == SW_EXIT_OK ? SW_OK : SW_ENOMEM;
    if (rc != SW_OK)
        snprintf(msg, msglen, "the points could not be gathered");
    else
        *exit_code = SW_EXIT_USAGE; /* if a point failed */
    for (size_t i = 0; rc == SW_OK && G->world->rank == 0 && i < np; i++)
        if (G->gp[i].status < 0) {
            rc = G->gp[i].status;
            snprintf(msg, msglen, "curve %zu, omega_e/p = %g: %s", i / G->nr + 1,
                     G->gp[i].omega_ratio, G->msgs[i][0] ? G->msgs[i] : sw_strerror(rc));
        }
    free(G->msgs);
    G->msgs = NULL;
    return rc;
}

/* Every curve at every point, in groups of curves that share the points
 * and the scan (one group, all the curves, in dimensionless units). */
int sw_bnd_sweep(boundary_t *B)
{
    const size_t nc = B->nc, nr = B->b.nr;
    int rc = SW_EXIT_IO;
    B->pts = calloc(nc * nr, sizeof *B->pts);
    sw_curve_t *curves = calloc(nc, sizeof *curves);
    size_t *member = calloc(nc, sizeof *member);
    unsigned char *done = calloc(nc, 1);
    double *ratios = calloc(nr, sizeof *ratios);
    sw_boundary_point_t *gp = calloc(nc * nr, sizeof *gp);
    if (!B->pts || !curves || !member || !done || !ratios || !gp) {
        sw_cli_error("out of memory");
        goto out;
    }
    progress_t P = {0, nc * nr};
    /* The sweep cannot stop between points and writes nothing: a signal
     * ends the process at once. */
    sw_cli_interrupt_now("boundary: interrupted during the sweep; nothing written");
    for (size_t c0 = 0; c0 < nc; c0++) {
        if (done[c0])
            continue;
        size_t k = 0;
        for (size_t c = c0; c < nc; c++)
            if (!done[c] && same_sweep(B, c0, c)) {
                done[c] = 1;
                member[k] = c;
                curves[k++] = B->cv[c].c;
            }
        for (size_t i = 0; i < nr; i++) ratios[i] = sw_bnd_ratio_at(B, c0, i);
        sw_boundary_opts_t bo = B->b.bo;
        bo.search.x_min = B->cv[c0].x_min;
        bo.search.x_max = B->cv[c0].x_max;
        bo.progress = B->b.progress && B->world.size == 1 ? on_progress : NULL;
        bo.user = &P;
        char msg[512] = "";
        int sr, code = SW_EXIT_USAGE;
        if (B->world.size > 1) {
            group_t G = {&B->world, curves, k, ratios, nr, &bo, gp, NULL, B->b.progress};
            sr = sweep_ranks(&G, msg, sizeof msg, &code);
        } else {
            sr = sw_boundary_sweep(curves, k, ratios, nr, &bo, gp, msg, sizeof msg);
        }
        for (size_t j = 0; j < k; j++)
            memcpy(&B->pts[member[j] * nr], &gp[j * nr], nr * sizeof *gp);
        P.offset += k * nr;
        if (sr != SW_OK && B->world.rank != 0) { /* rank 0 says why */
            rc = code;
            goto out;
        }
        if (sr != SW_OK) {
            /* the library numbers the curves of the group: name the curve instead */
            size_t bad = 0;
            while (bad + 1 < k * nr && gp[bad].status >= 0) bad++;
            const char *why = msg;
            if (!strncmp(why, "curve ", 6) && strstr(why, ", "))
                why = strstr(why, ", ") + 2;
            sw_cli_error("boundary: curve '%s', %s", B->cv[member[bad / nr]].label,
                         why[0] ? why : sw_strerror(sr));
            rc = code;
            goto out;
        }
    }
    rc = SW_EXIT_OK;
out:
    sw_cli_interrupt_now(NULL);
    free(curves);
    free(member);
    free(done);
    free(ratios);
    free(gp);
    return rc;
}
