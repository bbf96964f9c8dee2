/* SPDX-License-Identifier: GPL-3.0-or-later */
/* whatif.h - forensics' what-if cases (swaywatch/whatif.h) on the command
 * line: their options, and the table, the words and the JSON that report
 * them. */
#ifndef SWAYWATCH_CLI_WHATIF_H
#define SWAYWATCH_CLI_WHATIF_H

#include <stdio.h>

#include "opts.h"
#include "record.h"

/* The what-if options.  Frequencies in rad/s (0: not given); the other
 * scene values as text, set as scene keys. */
typedef struct {
    const char *frame_mass, *frame_zeta, *cushion_zeta;
    double frame_omega, cushion_omega;
    sw_cli_list_t sizes; /* --size HxW or HxWxD */
    int no_what_if;      /* only the scenes as given */
    long reserve_evals;  /* --reserve-evals: per case, at most (0: no limit) */
} sw_cli_whatif_t;

/* An option's check for a frequency (dest: a double, rad/s): "2Hz",
 * "2 Hz", "12.6rad/s", or a bare number in rad/s. */
int sw_cli_opt_frequency(const sw_cli_option_t *o, const char *arg, void *dest);

/* "HEIGHTxWIDTH" or "HEIGHTxWIDTHxDEPTH" (m, each > 0) into *h, *w, *d
 * (0 when the depth is not given): 0, or -1 if it is not one. */
int sw_cli_parse_size(const char *arg, double *h, double *w, double *d);

/* The options w as the library's (swaywatch/whatif.h) into *o; returns
 * the sizes o points to (free() them after the cases are made), NULL when
 * out of memory. */
double *sw_cli_whatif_opts(const sw_cli_whatif_t *w, sw_whatif_opts_t *o);
/* The cases' notes name the command's options rather than the library's
 * members ("--frame-omega", not "frame_omega"). */
void sw_cli_whatif_name_options(sw_whatif_case_t *cs, size_t n);

/* The package and its support, in numbers ("2x0.728 m, 1000 kg, frame
 * m_b 250 kg, 1 Hz (w_b 6.283 rad/s), zeta_b 0.1"), into buf; "" for a
 * case that was not built.  Returns buf. */
const char *sw_cli_whatif_desc(char *buf, size_t len, const sw_whatif_case_t *C);

/* The case's smallest reserve as text: "0.236 g", "<= 0.236 g (>= 0.150)",
 * "n/a: ..." or "-" (not computed). */
void sw_cli_whatif_reserve_text(char *buf, size_t len, const sw_whatif_case_t *C);

/* The bracket of a found factor, with as many digits as its two ends need
 * to differ: "[0.459, 0.4593]". */
void sw_cli_safety_bracket(char *buf, size_t len, const sw_safety_t *s);
/* What the safety factor means for this package, in one sentence. */
void sw_cli_safety_sentence(char *buf, size_t len, const sw_safety_t *s);

/* The cases cs are fx's (sw_forensics_cases), each said as the library
 * judges it (sw_forensics_case_verdict): with a lateral acceleration
 * held, a case of a package with a depth is judged in both planes, its
 * outcome, peak and margin the worse plane's, named; its reserve the
 * smaller; its safety factor the package's with both axes scaled. */

/* The what-if table of package pkg's cases (a row each), on f. */
void sw_cli_whatif_print_table(FILE *f, const sw_forensics_t *fx, const sw_whatif_case_t *cs,
                               size_t n, size_t pkg);
/* The cases of package pkg that stayed upright (in every plane judged)
 * where the scene did not, in words ("frame, soft bearings; cushion,
 * firm"), or "" if none. */
void sw_cli_whatif_savers(char *buf, size_t len, const sw_forensics_t *fx,
                          const sw_whatif_case_t *cs, size_t n, size_t pkg);
/* As JSON (record.h): a safety factor s of case C (its availability and
 * note) as the member key of o; the member made. */
json_t *sw_cli_json_safety(json_t *o, const char *key, const sw_whatif_case_t *C,
                           const sw_safety_t *s);
/* Case C's safety factor x (one plane, or both with each plane's own) as
 * the member "safety_factor" of o; the member made. */
json_t *sw_cli_json_factor(json_t *o, const sw_whatif_case_t *C, const sw_forensics_factor_t *x);
/* The case's members into o. */
void sw_cli_whatif_json_case(json_t *o, const sw_forensics_t *fx, const sw_whatif_case_t *cs,
                             size_t i);

#endif
