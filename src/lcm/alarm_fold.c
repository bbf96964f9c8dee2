/* SPDX-License-Identifier: GPL-3.0-or-later */
/* alarm_fold.c - the monitor's alarm rate limit (alarm_fold.h): one slot
 * per package, plane and alarm kind, a window, a burst, and a summary of what
 * the window held back.  Allocates only in sw_fold_create(). */
#include "alarm_fold.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FOLD_KINDS 32 /* alarm kinds the limit tells apart (sw_alarm_kind < 32) */

/* The limit of one package and kind. */
typedef struct {
    double win;           /* mono s, start of the window; -INFINITY: none yet */
    int sent;             /* alarms sent in the window */
    sw_alarm_level top;   /* highest level sent in the window */
    long folded;          /* held back since */
    sw_alarm_level level; /* the highest level among them */
    sw_alarm_t latest;    /* the latest of them, sent in the summary */
    int64_t latest_us;
} slot_t;

struct sw_fold {
    size_t n;
    slot_t *slot;    /* (2 n + 1) * FOLD_KINDS: package k's plane p at row 2 k + p,
                        input alarms at row 2 n */
    double next;     /* mono s of the earliest pending summary; INFINITY: none */
    double interval; /* s; 0: no limit */
    long folded;     /* held back and sent in summaries */
    sw_fold_emit_fn emit;
    void *user;
};

sw_fold_t *sw_fold_create(size_t n, double interval, sw_fold_emit_fn emit, void *user)
{
    sw_fold_t *f = calloc(1, sizeof *f);
    if (!f || n > SIZE_MAX / (2 * FOLD_KINDS * sizeof *f->slot) - 1 ||
        !(f->slot = calloc((2 * n + 1) * FOLD_KINDS, sizeof *f->slot))) {
        free(f);
        return NULL;
    }
    f->n = n;
    f->interval = interval;
    f->next = INFINITY;
    f->emit = emit;
    f->user = user;
    for (size_t i = 0; i < (2 * n + 1) * FOLD_KINDS; i++) f->slot[i].win = -INFINITY;
    return f;
}

void sw_fold_destroy(sw_fold_t *f)
{
    if (!f)
        return;
    free(f->slot);
    free(f);
}

/* The slot of an alarm; NULL for INPUT_REJECTED, which is folded per
 * reason before it gets here, and without a limit. */
static slot_t *slot_of(sw_fold_t *f, const sw_alarm_t *a)
{
    if (a->kind == SW_ALARM_INPUT_REJECTED || f->interval <= 0.0)
        return NULL;
    /* each plane of a package apart: a storm across the truck never holds
     * back an alarm along it, nor the other way round */
    const size_t row = a->pkg < f->n ? 2 * a->pkg + (a->plane == SW_PLANE_LAT) : 2 * f->n;
    const unsigned k = (unsigned)a->kind < FOLD_KINDS ? (unsigned)a->kind : FOLD_KINDS - 1;
    return &f->slot[row * FOLD_KINDS + k];
}

/* Send what s held back: the one alarm as it was, or a summary with the
 * count, the highest level and the latest one's text. */
static void summary(sw_fold_t *f, slot_t *s, double span)
{
    sw_alarm_t a = s->latest;
    a.level = s->level;
    if (s->folded > 1) {
        char head[64];
        snprintf(head, sizeof head, "%ld more in %.3g s, the last: ", s->folded, span);
        const size_t hl = strlen(head); /* < 64 < SW_ALARM_TEXT_MAX */
        size_t tl = strlen(s->latest.text);
        if (tl > sizeof a.text - 1 - hl)
            tl = sizeof a.text - 1 - hl; /* the latest text, cut to fit */
        memcpy(a.text, head, hl);
        memcpy(a.text + hl, s->latest.text, tl);
        a.text[hl + tl] = '\0';
    }
    f->folded += s->folded - 1;
    s->folded = 0;
    f->emit(f->user, &a, s->latest_us);
}

/* Send a now, as alarm number s->sent + 1 of the window. */
static void pass(sw_fold_t *f, slot_t *s, const sw_alarm_t *a, int64_t utime)
{
    s->sent++;
    if (a->level > s->top)
        s->top = a->level;
    f->emit(f->user, a, utime);
}

void sw_fold_send(sw_fold_t *f, const sw_alarm_t *a, int64_t utime, double mono)
{
    slot_t *s = slot_of(f, a);
    if (!s) {
        f->emit(f->user, a, utime);
        return;
    }
    if (!(mono - s->win < f->interval)) { /* a new window (not finite: a flush) */
        if (s->folded > 0)
            summary(f, s, f->interval);
        s->win = isfinite(mono) ? mono : -INFINITY; /* after a flush, a fresh start */
        s->sent = 0;
        s->top = a->level;
        pass(f, s, a, utime);
        return;
    }
    if (s->sent < SW_FOLD_BURST || a->level > s->top) {
        pass(f, s, a, utime);
        return;
    }
    if (s->folded == 0 || a->level > s->level)
        s->level = a->level;
    s->folded++;
    s->latest = *a;
    s->latest_us = utime;
    if (s->win + f->interval < f->next)
        f->next = s->win + f->interval;
}

void sw_fold_tick(sw_fold_t *f, double mono)
{
    if (!(mono >= f->next))
        return;
    f->next = INFINITY;
    for (size_t i = 0; i < (2 * f->n + 1) * FOLD_KINDS; i++) {
        slot_t *s = &f->slot[i];
        if (s->folded == 0)
            continue;
        if (!(mono - s->win < f->interval))
            summary(f, s, f->interval);
        else if (s->win + f->interval < f->next)
            f->next = s->win + f->interval;
    }
}

double sw_fold_deadline(const sw_fold_t *f)
{
    return f->next;
}

long sw_fold_folded(const sw_fold_t *f)
{
    return f->folded;
}
