/* SPDX-License-Identifier: GPL-3.0-or-later */
/* keyset.h - which strings of a list are equal, in n log n: a batch's
 * manifest lines grouped by their options, so that each distinct set of
 * options is parsed once however many lines and sets there are (a linear
 * search per line was quadratic: a million lines with 50,000 sets did not
 * start in two minutes). */
#ifndef SWAYWATCH_CLI_KEYSET_H
#define SWAYWATCH_CLI_KEYSET_H

#include <stddef.h>

/* For each i < n, first[i] = the smallest j with keys[j] equal to keys[i]
 * (strcmp; NULL keys are equal to each other and to nothing else).  One
 * sort of the indices, by key then index: O(n log n) comparisons, counted
 * in *compares when it is not NULL.  Returns 0, or -1 when memory ran
 * out. */
int sw_cli_keyset_first(const char *const *keys, size_t n, size_t *first, long *compares);

#endif
