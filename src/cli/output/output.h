/* SPDX-License-Identifier: GPL-3.0-or-later */
/* output.h - what the commands write: state and event CSVs, summaries. */
#ifndef SWAYWATCH_CLI_OUTPUT_H
#define SWAYWATCH_CLI_OUTPUT_H

#include <stdio.h>

#include "cli.h"
#include "record.h"
#include "text.h"
#include "unused.h"

/* Derived quantities of every package (--verbose), on f. */
void sw_cli_print_derived(FILE *f, const sw_engine_t *e, const sw_scene_t *scenes, size_t n);

/* Refuse (message, SW_EXIT_USAGE) an --out or --events (paths, may be
 * NULL) that names the input being read (in, may be NULL) or each other:
 * opening them truncates.  "-" is standard output: for one of them, and
 * only if no summary goes there (neither json nor, without quiet, the
 * human summary). */
int sw_cli_check_outputs(const char *out_path, const char *events_path, FILE *in, int json,
                         int quiet);

/* An output file: path, or "-" for standard output.  Open reports its
 * failure; close flushes, closes (standard output stays open) and reports
 * a write error: SW_EXIT_OK or SW_EXIT_IO.  The name is what messages call
 * it. */
FILE *sw_cli_out_open(const char *path);
int sw_cli_out_close(FILE *f, const char *path);
const char *sw_cli_out_name(const char *path);

/* --out: the state time series, one row per package and output instant:
 * t,package,phase,theta,theta_dot,u,u_dot,z,z_dot,margin,margin_bound,
 * uplift_ratio,a_g,reserve_g.  Numbers as %.9g; a non-finite value is
 * written as an empty field and counted.  reserve_g: the package's latest
 * reserve (risk, when set: the caller feeds it before each write; empty
 * before its first evaluation or without one).  When a package of the
 * engine rocks in a lateral plane too, three columns follow:
 * theta_lat,margin_lat,reserve_g_lat, its lateral plane's at the same
 * instant (the engine reports it first), empty for a package without. */
typedef struct {
    FILE *f;
    const char *path;
    const sw_scene_t *scenes; /* for package names */
    size_t n;
    long every;
    long *seen;            /* per package: rows offered, for --every */
    long rows;             /* rows written */
    long nonfinite;        /* fields left empty because the value was not finite */
    const sw_risk_t *risk; /* the reserve column's source; NULL: empty */
    /* the lateral planes (none: the columns are those above, and nothing
     * below is used) */
    int lat;                   /* some package has one: the _lat columns */
    sw_output_t *lat_out;      /* per package, its lateral plane's latest output */
    unsigned char *lat_have;   /* ... received */
    const sw_stream_t *stream; /* their reserve (sw_stream_risk_plane); NULL: empty */
} sw_cli_states_t;

/* Open (path NULL: a disabled writer whose write does nothing); e (may be
 * NULL) says which packages rock in a lateral plane. */
int sw_cli_states_open(sw_cli_states_t *w, const char *path, long every, const sw_engine_t *e,
                       const sw_scene_t *scenes, size_t n);
void sw_cli_states_write(sw_cli_states_t *w, const sw_output_t *out);
/* Flush and close; returns SW_EXIT_OK or SW_EXIT_IO (reported). */
int sw_cli_states_close(sw_cli_states_t *w);

/* --wide: the state series one row per output instant, a column group per
 * package, for a plain plot or a spreadsheet: t,a_g, then for each package
 * P: P.phase,P.theta,P.theta_dot,P.ratio,P.margin,P.margin_bound,
 * P.uplift_ratio,P.reserve_g (ratio = theta/alpha; reserve_g as --out's).  The engine reports every
 * package at each instant, in order: a row is written when the last package's state arrives, or
 * when the time moves on before it (the missing fields left empty and counted).  Packages of the
 * same name are told apart as NAME#2, NAME#3, ... --every keeps every Nth row.  A package that
 * rocks in a lateral plane too has three more: P.theta_lat,P.margin_lat,P.reserve_g_lat. */
typedef struct {
    FILE *f;
    const char *path;
    size_t n;
    long every, seen;
    double *alpha;       /* rad, per package */
    sw_output_t *row;    /* the row being gathered, per package */
    unsigned char *have; /* which packages it has */
    int open;            /* a row is being gathered */
    long rows, nonfinite, incomplete;
    const sw_risk_t *risk;     /* the reserve columns' source; NULL: empty */
    unsigned char *planes;     /* per package: 2 with a lateral plane (its columns), else 1 */
    sw_output_t *lat_row;      /* per package, its lateral plane's latest output */
    const sw_stream_t *stream; /* the lateral reserve's source; NULL: empty */
} sw_cli_wide_t;

/* Open (path NULL: a disabled writer) for the n packages of engine e. */
int sw_cli_wide_open(sw_cli_wide_t *w, const char *path, long every, const sw_engine_t *e,
                     const sw_scene_t *scenes, size_t n);
void sw_cli_wide_write(sw_cli_wide_t *w, const sw_output_t *out);
/* The last row, flush, close: SW_EXIT_OK or SW_EXIT_IO (reported). */
int sw_cli_wide_close(sw_cli_wide_t *w);

/* Refuse (SW_EXIT_USAGE, reported) outputs of one run on standard output
 * ("-") that clash: names[i] is the option ("--wide"), paths[i] its file
 * (NULL: not given).  Two of them there, or one beside a summary (json, or
 * without quiet the human one).  Clashes between files: clobber.h. */
int sw_cli_check_stdout(const char *const names[], const char *const paths[], size_t n, int json,
                        int quiet);

/* --events: t,package,event,theta,theta_dot,margin,info, one row per
 * event, except the micro-impacts of settling (risk.h): one "settling" row
 * per span instead, at its first micro-impact, with theta_dot the fastest
 * of them (rad/s) and info how many (all_impacts: every impact instead).
 * When a package of the engine rocks in a lateral plane too, a last
 * column, plane, says longitudinal or lateral; the lateral plane's
 * impacts are each written (no settling spans). */
typedef struct {
    FILE *f;
    const char *path;
    const sw_scene_t *scenes;
    size_t n;
    long rows, nonfinite;
    int all_impacts; /* --all-impacts */
    int lat;         /* the plane column */
} sw_cli_events_t;

int sw_cli_events_open(sw_cli_events_t *w, const char *path, const sw_engine_t *e,
                       const sw_scene_t *scenes, size_t n);
void sw_cli_events_write(sw_cli_events_t *w, const sw_event_t *ev);
/* A settling span of package pkg, as one row. */
void sw_cli_events_span(sw_cli_events_t *w, size_t pkg, const sw_settle_span_t *span);
/* An engine event through risk (may be NULL: every event as it is) into
 * the file: a micro-impact folded into its span, a closed span written
 * before the event.  Returns sw_risk_event()'s flags: SW_SETTLE_REPORT
 * when the event is to be reported (figures, summaries). */
int sw_cli_events_feed(sw_cli_events_t *w, sw_risk_t *risk, const sw_event_t *ev);
/* End of the stream: the spans still open, for the n packages. */
void sw_cli_events_finish(sw_cli_events_t *w, sw_risk_t *risk, size_t n);
int sw_cli_events_close(sw_cli_events_t *w);

/* What fed the engine, for the summaries. */
typedef struct {
    const char *log;         /* LOG as given ("-" for stdin), or NULL */
    const sw_pulse_t *pulse; /* simulate: the pulse, or NULL */
    double duration;         /* s, simulate: time simulated */
    long samples_read;       /* data rows seen */
    long samples_rejected;   /* data rows refused (CSV layer or engine) */
    double settle;           /* s, replay: --settle */
    /* a log's facts (the input gate's), and its verdict's check */
    int have_facts;
    sw_gate_facts_t facts;
    int forced;                /* the plausibility check refused; --force gave the verdict */
    char check[320];           /* its reason, or a warning (a low rate); "" none */
    int interrupted;           /* the signal that stopped the run early (SIGINT, SIGTERM), or 0:
                                  the summaries say so, and up to which time they cover */
    const sw_risk_t *risk;     /* reserves and impacts that matter (NULL: none) */
    const sw_stream_t *stream; /* the lateral planes' reserves (sw_stream_risk_plane); NULL */
    sw_cli_unused_t unused;    /* a log's: what its reading did not use (rows, gaps) */
    /* a log whose times are dates (a date-time column, epoch times, an
     * lcm-logger file): a source time plus abs_base is UTC (s since 1970);
     * abs_start and abs_end are its first and last samples'; abs_from says
     * where the dates come from */
    int absolute;
    double abs_base, abs_start, abs_end; /* s */
    const char *abs_from;
} sw_cli_run_t;

/* Epoch times outside these are no date of a recording (an uptime in s,
 * a clock never set): no UTC is given for them. */
#define SW_CLI_EPOCH_MIN 631152000.0  /* s since 1970: 1990-01-01 */
#define SW_CLI_EPOCH_MAX 4102444800.0 /* 2100-01-01 */
int sw_cli_epoch_plausible(double t);

/* The UTC of engine time t (s) of run, ISO-8601 with ms, into buf: 1, or
 * 0 (buf "") when the log has no dates or t is after a clock step or a
 * restart that re-timed the log (what followed is not the source's time
 * plus a constant). */
int sw_cli_run_utc(const sw_cli_run_t *run, double t, char *buf, size_t len);

/* A package's smallest reserve, in g, and what it means: one line (two
 * with faults) as the human summary has it; nothing without a reserve. */
void sw_cli_print_reserve(FILE *f, const sw_risk_pkg_t *p);

/* The one-screen human summary (DESIGN.md contract). */
void sw_cli_print_summary(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run);
/* The JSON summary (DESIGN.md contract, docs/design.md): its members into
 * o (record.h), or written on f: SW_EXIT_OK, or SW_EXIT_IO when memory ran
 * out (reported). */
void sw_cli_json_summary(json_t *o, const sw_engine_t *e, const sw_cli_run_t *run);
int sw_cli_print_json(FILE *f, const sw_engine_t *e, const sw_cli_run_t *run);

/* The parts of the JSON summary, for the records of a batch and
 * forensics: the log's facts (the summary's "input") as member key of o;
 * the members of package i's object into o (-1 and nothing set if i has
 * no summary). */
void sw_cli_json_facts(json_t *o, const char *key, const sw_cli_run_t *run);
int sw_cli_json_package(json_t *o, const sw_engine_t *e, size_t i, const sw_cli_run_t *run);

/* An absolute time (s since 1970) as ISO-8601 UTC with milliseconds. */
void sw_cli_iso_seconds(char *buf, size_t len, double t);

/* Non-zero if any package overturned. */
int sw_cli_any_overturned(const sw_engine_t *e);

/* What the run saw of a package: "overturned", "upright", or "unreliable"
 * when it did not overturn but its model faulted (reset to rest mid-run:
 * "stayed upright" would not be a verdict). */
const char *sw_cli_verdict_seen(const sw_summary_t *s);

/* How many things the input did not show may have changed the run's
 * verdicts: the gate's gaps and restarts over motion (gate.h's
 * incomplete); 0 with none, or without a run (a simulation).  The one
 * place that decides it: other doubts (a contested stream) belong here. */
long sw_cli_run_incomplete(const sw_cli_run_t *run);
/* The first of them in words ("a gap of 2 s at 6.499 s overlapped rocking
 * or an acceleration near the uplift threshold"); "" with none. */
void sw_cli_incomplete_why(const sw_cli_run_t *run, char *buf, size_t len);

/* A package's verdict (JSON "verdict"; the summaries say it in words):
 * "overturned" whatever the gaps (an overturn seen is one); "incomplete"
 * when the run is (sw_cli_run_incomplete: what it saw is
 * sw_cli_verdict_seen); else what it saw.  run may be NULL. */
const char *sw_cli_verdict(const sw_summary_t *s, const sw_cli_run_t *run);

/* Member "incomplete_because" of o: null, or {count, first_time,
 * first_kind, first_span, text} of an incomplete verdict. */
void sw_cli_json_incomplete(json_t *o, const sw_summary_t *s, const sw_cli_run_t *run);

/* The exit code of a run that went well, from its verdicts: SW_EXIT_OK
 * without fail_on_overturn; with it SW_EXIT_OVERTURNED if a package
 * overturned or the verdict is incomplete (fail safe: it may hide an
 * overturn; reported), else SW_EXIT_USAGE (reported, naming the package)
 * if one has no verdict because its model faulted, else SW_EXIT_OK.  run
 * may be NULL (a simulation). */
int sw_cli_verdict_exit(const sw_engine_t *e, const sw_cli_run_t *run, int fail_on_overturn);

#endif
