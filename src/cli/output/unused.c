/* SPDX-License-Identifier: GPL-3.0-or-later */
/* unused.c - what the reading of a log did not use (unused.h): refusals by
 * reason with their first places, the stream's gaps, steps and restarts. */
#include "unused.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void sw_cli_unused_init(sw_cli_unused_t *u, int places)
{
    memset(u, 0, sizeof *u);
    u->places = places;
    u->first_shift = INFINITY;
}

/* The reason's row, made if there is room; NULL: counted in other. */
static sw_cli_unused_reason_t *row(sw_cli_unused_t *u, const char *reason)
{
    for (size_t i = 0; i < u->nreason; i++)
        if (!strcmp(u->reason[i].reason, reason))
            return &u->reason[i];
    if (u->nreason == SW_CLI_UNUSED_REASONS)
        return NULL;
    sw_cli_unused_reason_t *r = &u->reason[u->nreason++];
    snprintf(r->reason, sizeof r->reason, "%s", reason);
    return r;
}

void sw_cli_unused_reject(sw_cli_unused_t *u, long where, const char *reason, const char *text)
{
    u->rejected++;
    sw_cli_unused_reason_t *r = row(u, reason ? reason : sw_cli_unused_csv_reason(text));
    if (!r) {
        u->other++;
        return;
    }
    if (r->count++ == 0)
        snprintf(r->first, sizeof r->first, "%s", text ? text : "");
    if (r->nwhere < SW_CLI_UNUSED_WHERE)
        r->where[r->nwhere++] = where;
}

void sw_cli_unused_count(sw_cli_unused_t *u, const char *reason, long n)
{
    if (n <= 0)
        return;
    u->rejected += n;
    sw_cli_unused_reason_t *r = row(u, reason);
    if (r)
        r->count += n;
    else
        u->other += n;
}

void sw_cli_unused_event(sw_cli_unused_t *u, const sw_gate_event_t *ev)
{
    if (ev->kind == SW_GATE_EV_SEQ_RESTART)
        return;
    const sw_cli_unused_gap_t g = {.kind = ev->kind,
                                   .t = ev->t,
                                   .t_engine = ev->t_engine,
                                   .span = ev->span,
                                   .where = ev->where,
                                   .incomplete = ev->incomplete,
                                   .restarted = ev->restarted,
                                   .bridged = ev->bridged};
    u->events++;
    if (u->ngap < SW_CLI_UNUSED_GAPS)
        u->gap[u->ngap++] = g;
    if (g.incomplete && !u->have_incomplete) {
        u->have_incomplete = 1;
        u->first_incomplete = g;
    }
    /* a gap keeps the source's clock; a step or a restart re-times what follows */
    if (ev->kind != SW_GATE_EV_GAP && ev->t_engine < u->first_shift)
        u->first_shift = ev->t_engine;
}

const char *sw_cli_unused_csv_reason(const char *text)
{
    /* the CSV reader's messages (csv.c, csv_split.c), by what they say */
    static const struct {
        const char *says, *reason;
    } known[] = {
        {"is not a number", "not a number"},
        {"is empty", "empty field"},
        {"missing field", "missing field"},
        {"out of range", "number out of range"},
        {"quot", "malformed quoting"},
        {"line longer", "line too long"},
        {"not after previous", "time not increasing"},
        {"refused by consumer", "refused"},
    };
    for (size_t i = 0; text && i < sizeof known / sizeof known[0]; i++)
        if (strstr(text, known[i].says))
            return known[i].reason;
    return "unreadable row";
}

const char *sw_cli_unused_gate_reason(sw_gate_reject r)
{
    switch (r) {
        case SW_GATE_REJ_NONFINITE: return "value not finite";
        case SW_GATE_REJ_IMPLAUSIBLE: return "spike beyond --max-accel";
        case SW_GATE_REJ_TIME: return "time too large";
        case SW_GATE_REJ_SKEW: return "far from the wall clock";
        case SW_GATE_REJ_DUPLICATE: return "duplicate time";
        case SW_GATE_REJ_LATE: return "time before the timeline";
        case SW_GATE_REJ_JUMP: return "time leaps from the timeline";
        case SW_GATE_REJ_ENGINE: return "refused by the engine";
        default: return sw_gate_reject_name(r);
    }
}
