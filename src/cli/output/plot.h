/* SPDX-License-Identifier: GPL-3.0-or-later */
/* plot.h - figures drawn by gnuplot, run as a subprocess (plot.c). */
#ifndef SWAYWATCH_CLI_PLOT_H
#define SWAYWATCH_CLI_PLOT_H

#include <stdio.h>

#include "cli.h"
#include "opts.h"

/* sw_cli_plot_open() starts gnuplot with the terminal chosen by the file's
 * extension (.png: pngcairo, or png without cairo; .svg) and its output set;
 * the caller writes the rest of the script (data as inline datablocks) to
 * sw_cli_plot_file() and sw_cli_plot_close() waits for gnuplot and reports
 * its failure with gnuplot's own messages. */
typedef struct sw_plot sw_plot_t;

/* fn of a figure option's row: SW_EXIT_OK if path ends in .png or .svg,
 * else SW_EXIT_USAGE (reported, naming the option). */
int sw_cli_plot_check(const sw_cli_option_t *o, const char *path, void *dest);
sw_plot_t *sw_cli_plot_open(const char *path, int width, int height);
FILE *sw_cli_plot_file(sw_plot_t *p);
int sw_cli_plot_close(sw_plot_t *p); /* SW_EXIT_OK or SW_EXIT_IO */
/* s as a gnuplot string literal (double quotes, every byte that is not
 * printable ASCII escaped), as it is (file names). */
void sw_cli_plot_string(FILE *f, const char *s);
/* s as a gnuplot string literal to be shown as text: the enhanced-text
 * markup characters (_ ^ { } @ & ~) escaped. */
void sw_cli_plot_text(FILE *f, const char *s);

#endif
