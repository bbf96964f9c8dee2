/* SPDX-License-Identifier: GPL-3.0-or-later */
/* forensics.h - what "swaywatch forensics" holds while it runs, shared by
 * the command (cmd_forensics.c), its answer in words and in JSON
 * (forensics_out.c) and its HTML report (report.c). */
#ifndef SWAYWATCH_CLI_FORENSICS_H
#define SWAYWATCH_CLI_FORENSICS_H

#include <pthread.h>
#include <stdio.h>

#include "figure.h"
#include "fingerprint.h"
#include "input.h"
#include "opts.h"
#include "output.h"
#include "source.h"
#include "whatif.h"

/* forensics' own options. */
typedef struct {
    double settle; /* s of zero input after the end of the log, as replay */
    int fail_on_overturn;
    long threads;
    long max_samples; /* the log held in memory, at most */
    sw_search_opts_t so;
    sw_cli_whatif_t w;
    const char *plot;   /* --plot FILE.png|.svg */
    const char *report; /* --report FILE.html */
} sw_cli_forensics_opts_t;

/* The events kept for the report's table, at most. */
#define SW_CLI_FORENSICS_EVENTS 400

typedef struct {
    sw_cli_opts_t o;
    sw_cli_read_opts_t in;
    sw_cli_forensics_opts_t fo;
    sw_cli_given_t given;
    int argc;
    char **argv;       /* the command as given (argv[0] is "forensics") */
    const char *log;   /* LOG as given */
    int scenes_shared; /* a batch's: scenes read, and their cost warned about, once */
    sw_cli_reader_t R; /* the log's reading and the engine of every package */
    sw_scene_t *scenes;
    size_t n;
    sw_engine_opts_t eo; /* the integration options of the replay and of every search */
    sw_cli_states_t states;
    sw_cli_events_t events;
    sw_cli_figure_t *fig;       /* --plot or --report */
    sw_forensics_t *fx;         /* the library's: the log the gate handed the engine, the
                                   cases and their searches */
    volatile sig_atomic_t halt; /* the log could not be held whole: the reading may stop */
    sw_whatif_case_t *cases;    /* every package's cases, package by package (fx's, once
                                  searched) */
    size_t ncases;
    /* events kept for the report (impacts beyond the first few of a package
     * are counted only) */
    sw_event_t *ev;
    size_t nev;
    long *impacts_seen; /* per package */
    long ev_dropped;
    /* the search's progress line and its time */
    double started, progress_at, search_s;
    int progress_shown;
    /* what ties the answer to its inputs (sw_cli_forensics_fingerprint) */
    int fingerprinted;
    pthread_t digest_thread; /* the log's digest, made beside the replay */
    int digest_fd;           /* the log's descriptor it reads */
    int digest_running;      /* started and not yet joined */
    sw_cli_digest_t log_digest;
    sw_cli_digest_t *scene_digest; /* one per --scene file, in order */
    char *command_line;            /* the command, quoted for a POSIX shell */
} sw_cli_forensics_t;

/* The events kept for the report: begin before the replay (SW_EXIT_OK or
 * SW_EXIT_IO, reported), one call per engine event, end after it. */
int sw_cli_forensics_begin(sw_cli_forensics_t *F);
void sw_cli_forensics_event(sw_cli_forensics_t *F, const sw_event_t *ev);
void sw_cli_forensics_end(sw_cli_forensics_t *F);
void sw_cli_forensics_free(sw_cli_forensics_t *F); /* what begin allocated */

/* Before the replay: the log's SHA-256 and size begin on a thread of
 * their own (the replay reads on one core; the digest reads the same
 * descriptor with pread(), which leaves its offset alone).  No thread, no
 * harm: the fingerprint then makes them itself. */
void sw_cli_forensics_digest_start(sw_cli_forensics_t *F);

/* After the replay: the SHA-256 and size of the log (the file being read,
 * through its open descriptor) and of each scene file, and the command
 * line quoted for a shell.  SW_EXIT_OK, or SW_EXIT_IO when memory ran out
 * (reported); a file that cannot be hashed is no failure: its digest says
 * why. */
int sw_cli_forensics_fingerprint(sw_cli_forensics_t *F);

/* The UTC of engine time t (s) of the replay in buf ("" when the log has
 * no dates, or t is after a clock step or restart): 1 or 0. */
int sw_cli_forensics_utc(const sw_cli_forensics_t *F, double t, char *buf, size_t len);

/* The answer first, then (without -q) the method: the replay summary and
 * how the safety factors were found. */
void sw_cli_forensics_text(FILE *f, const sw_cli_forensics_t *F);
/* The same as one JSON object (docs/forensics.md): SW_EXIT_OK, or
 * SW_EXIT_IO when memory ran out (reported). */
int sw_cli_forensics_json(FILE *f, const sw_cli_forensics_t *F);
/* The same as one self-contained HTML page: SW_EXIT_OK or SW_EXIT_IO
 * (reported). */
int sw_cli_forensics_report(const sw_cli_forensics_t *F, const char *path);

/* The report's close-ups (report_zoom.c): a window of SW_CLI_ZOOM_HALF s
 * either side of each decisive moment (a package's overturn, else its
 * smallest reserve, else its first uplift); moments closer than that
 * share a window.  At most SW_CLI_ZOOMS windows, in time order, into z;
 * how many. */
#define SW_CLI_ZOOMS 4
#define SW_CLI_ZOOM_HALF 3.0 /* s */
#define SW_CLI_ZOOM_MARKS 4
typedef struct {
    double t, t0, t1; /* s: the (first) moment, the window */
    double marks[SW_CLI_ZOOM_MARKS];
    int nmarks;
    char what[400]; /* "the overturn of crate-A at 3.764 s; ..." */
} sw_cli_zoom_t;
size_t sw_cli_report_moments(const sw_cli_forensics_t *F, sw_cli_zoom_t *z, size_t max);
/* A figure of each window (no margin panel; the reserve with its own
 * evaluations from the window's start), from the held log run again
 * through a fresh engine up to the last window's end: fig[i] and risk[i]
 * (the figure's reserve: destroy it after the figure).  SW_EXIT_OK, or
 * SW_EXIT_IO (reported; nothing made). */
int sw_cli_report_zooms(const sw_cli_forensics_t *F, const sw_cli_zoom_t *z, size_t nz,
                        sw_cli_figure_t **fig, sw_risk_t **risk);

/* Shared by the text, JSON and HTML: package k's summary of the replay
 * (0 if there is none): that of its worse plane, the one that decides its
 * verdict (sw_cli_forensics_plane); and its case as given. */
int sw_cli_forensics_summary(const sw_cli_forensics_t *F, size_t k, sw_summary_t *s);
/* The plane of package k's verdict (SW_PLANE_LONG with one plane), and
 * how many planes it rocked in (1 or 2). */
sw_plane sw_cli_forensics_plane(const sw_cli_forensics_t *F, size_t k, int *planes);
/* The reserve of package k's plane p (NULL: none). */
const sw_risk_pkg_t *sw_cli_forensics_reserve(const sw_cli_forensics_t *F, size_t k, sw_plane p);
/* Package k's safety factor with both horizontal axes scaled together
 * (sw_forensics_factor; one plane: the case as given's): 1, or 0 when
 * there is none (fx zeroed). */
int sw_cli_forensics_factor(const sw_cli_forensics_t *F, size_t k, sw_forensics_factor_t *fx);
/* " across the truck" or " along the truck" for plane p of a package
 * that rocks in two planes, "" for one that rocks in one. */
const char *sw_cli_forensics_where(int planes, sw_plane p);
/* "gives out first across the truck (along the truck [..], across [..])":
 * both planes' safety factors, along the one given, across fx's. */
void sw_cli_forensics_planes(char *buf, size_t len, const sw_forensics_factor_t *fx,
                             const sw_safety_t *along);
/* The what-if cases of package k that stayed upright where it did not
 * (sw_cli_whatif_savers) into buf: 1; or 0 with the reason in buf when
 * that cannot be said: the cases vary the plane along the truck only, so
 * for a package that overturned across the truck none is known to save
 * it. */
int sw_cli_forensics_savers(const sw_cli_forensics_t *F, size_t k, char *buf, size_t len);
const sw_whatif_case_t *sw_cli_forensics_scene_case(const sw_cli_forensics_t *F, size_t k);

/* forensics of many logs, for its batch job (forensics_job.c): the options
 * at their defaults (NULL: out of memory, reported), freed with
 * sw_cli_forensics_destroy() (NULL ok); the groups a batch takes (the
 * log's reading, scenes, integration, the searches and the what-if, not
 * the outputs), at most 16; after parsing them, the scenes read once. */
sw_cli_forensics_t *sw_cli_forensics_new(void);
void sw_cli_forensics_destroy(sw_cli_forensics_t *F);
size_t sw_cli_forensics_groups(sw_cli_forensics_t *F, sw_cli_group_t *g);
int sw_cli_forensics_ready(sw_cli_forensics_t *F, const sw_cli_group_t *g, size_t ng);

/* The forensics of log with the options of opts (ready; only read, so any
 * number of threads may share it), as "swaywatch forensics -q" would do
 * it: on success report(user, F) is called with the run's state and the
 * exit code returned (0, or 1 with --fail-on-overturn); otherwise the exit
 * code forensics would give (reported), and report is not called. */
typedef void (*sw_cli_forensics_report_fn)(void *user, const sw_cli_forensics_t *F);
int sw_cli_forensics_log(const sw_cli_forensics_t *opts, const char *log,
                         sw_cli_forensics_report_fn report, void *user);

/* Package k's members of the JSON's "packages", into o. */
void sw_cli_forensics_json_package(json_t *o, const sw_cli_forensics_t *F, size_t k);

#endif
