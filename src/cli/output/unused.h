/* SPDX-License-Identifier: GPL-3.0-or-later */
/* unused.h - what the reading of a log did not use, kept for the summaries
 * and the report (standard error says it line by line as it happens, and
 * an investigator's report must say it too): the refused rows or messages
 * counted by reason with the first places of each, and the gaps, restarts
 * and clock steps of the stream with their times.  Fixed size: a log of
 * any length fills it at no cost beyond its first entries, and every
 * refusal is still counted. */
#ifndef SWAYWATCH_CLI_UNUSED_H
#define SWAYWATCH_CLI_UNUSED_H

#include "swaywatch/swaywatch.h"

#define SW_CLI_UNUSED_REASONS 12 /* reasons kept by name; the rest counted together */
#define SW_CLI_UNUSED_WHERE 5    /* places kept per reason */
#define SW_CLI_UNUSED_GAPS 20    /* stream events kept */

typedef struct {
    char reason[48]; /* what was wrong, in a few words ("not a number", "duplicate time") */
    long count;
    long where[SW_CLI_UNUSED_WHERE]; /* the first places: lines of a CSV log */
    int nwhere;
    char first[200]; /* the first one's message as it was printed */
} sw_cli_unused_reason_t;

typedef struct {
    sw_gate_event_kind kind; /* gap, clock step or restart */
    double t;                /* s, the source's time of the last sample before it */
    double t_engine;         /* s, the engine's time of the first sample after it */
    double span;             /* s, as the gate's event says (gate.h) */
    long where;              /* the source's place of the first sample after it */
    int incomplete, restarted, bridged;
} sw_cli_unused_gap_t;

typedef struct {
    int places;     /* the reasons have places (lines); 0: counts alone (lcm-logger files) */
    long rejected;  /* every refusal counted here */
    size_t nreason; /* reasons kept */
    long other;     /* refusals of reasons beyond the table */
    sw_cli_unused_reason_t reason[SW_CLI_UNUSED_REASONS];
    int listed;  /* the stream events below were kept (a CSV log's) */
    long events; /* gaps, clock steps and restarts, all of them */
    size_t ngap; /* the first ones kept */
    sw_cli_unused_gap_t gap[SW_CLI_UNUSED_GAPS];
    int have_incomplete; /* the first event that left the verdict incomplete */
    sw_cli_unused_gap_t first_incomplete;
    double first_shift; /* s, engine time of the first clock step or restart (times after it
                           are no longer the source's plus a constant); INFINITY: none */
} sw_cli_unused_t;

void sw_cli_unused_init(sw_cli_unused_t *u, int places);

/* A refused row at place where (a line), with its message: counted under
 * reason (NULL: read from the message, for the CSV reader's). */
void sw_cli_unused_reject(sw_cli_unused_t *u, long where, const char *reason, const char *text);
/* n refusals of one reason, without places (an lcm-logger file's counts). */
void sw_cli_unused_count(sw_cli_unused_t *u, const char *reason, long n);
/* A stream event of the gate (a sequence restart is not one: it loses no
 * time). */
void sw_cli_unused_event(sw_cli_unused_t *u, const sw_gate_event_t *ev);

/* The few words for a CSV reader's refusal message: "not a number",
 * "empty field", "missing field", ...; "unreadable row" for one not
 * known. */
const char *sw_cli_unused_csv_reason(const char *text);
/* The same for the input gate's reasons ("duplicate time", "spike"). */
const char *sw_cli_unused_gate_reason(sw_gate_reject r);

#endif
