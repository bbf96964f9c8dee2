/* SPDX-License-Identifier: GPL-3.0-or-later */
/* figure.h - the state figure of replay, simulate and forensics: the bed
 * acceleration with the uplift thresholds +-g tan(alpha), theta/alpha of
 * every package, its margin to overturn, and the events, drawn by gnuplot
 * (plot.h); with a lateral plane (a depth and a lateral column), the
 * lateral acceleration and each plane's tilt, the events of each named.
 *
 * The series are kept as the engine reports them, in a fixed number of
 * buckets per package: each bucket keeps the minimum and the maximum of
 * every quantity with their times, and when the buckets are full,
 * neighbours merge and each bucket covers twice as many samples.  A log of
 * any length is drawn from fixed memory, every sample of a short one is
 * drawn, and no peak is lost to the thinning. */
#ifndef SWAYWATCH_CLI_FIGURE_H
#define SWAYWATCH_CLI_FIGURE_H

#include "cli.h"

typedef struct sw_cli_figure sw_cli_figure_t;

/* A figure of the n packages of engine e (their alpha, g tan alpha and
 * names are read now).  NULL after "out of memory" (reported). */
sw_cli_figure_t *sw_cli_figure_create(const sw_engine_t *e, const sw_scene_t *scenes, size_t n);
void sw_cli_figure_destroy(sw_cli_figure_t *f); /* NULL accepted */

/* Draw the reserve of risk (reserve_g of each package as the state
 * comes, so risk is fed first) in a fourth panel; NULL: none. */
void sw_cli_figure_risk(sw_cli_figure_t *f, const sw_risk_t *risk);

/* The lateral planes' reserve (sw_stream_risk_plane of st, fed by the
 * stream before their states come), drawn beside the longitudinal ones'
 * when a risk is set; without it the reserve panel is along the truck
 * only, and its caption says so. */
void sw_cli_figure_stream(sw_cli_figure_t *f, const sw_stream_t *st);

/* Keep a state and an event (either plane: a package with a lateral
 * plane has its lateral tilt drawn in a panel of its own, its margin and
 * reserve dashed beside the others, the lateral acceleration under the
 * longitudinal one; f may be NULL: nothing kept). */
void sw_cli_figure_state(sw_cli_figure_t *f, const sw_output_t *out);
void sw_cli_figure_event(sw_cli_figure_t *f, const sw_event_t *ev);

/* A zoom: only the states and events between t0 and t1 (s) are kept (call
 * before feeding it). */
void sw_cli_figure_window(sw_cli_figure_t *f, double t0, double t1);
/* Leave the margin panel out. */
void sw_cli_figure_no_margin(sw_cli_figure_t *f);
/* A span without samples (s, engine time), shaded in every panel. */
void sw_cli_figure_gap(sw_cli_figure_t *f, double t0, double t1);
/* A decisive moment (s): a solid line through every panel. */
void sw_cli_figure_mark(sw_cli_figure_t *f, double t);

/* The caption of the figure as it is drawn, in plain UTF-8 words: what
 * each panel shows, top to bottom, what the lines and bands mean.  The
 * length written (0: nothing, or buf too small). */
size_t sw_cli_figure_caption(const sw_cli_figure_t *f, char *buf, size_t len);

/* Draw the figure into path (.png or .svg) under title: SW_EXIT_OK, or
 * SW_EXIT_IO (reported; gnuplot's own messages passed on). */
int sw_cli_figure_draw(const sw_cli_figure_t *f, const char *path, const char *title);

#endif
