/* SPDX-License-Identifier: GPL-3.0-or-later */
/* keyset.c - which strings of a list are equal (keyset.h). */
#define _GNU_SOURCE /* qsort_r */
#include "keyset.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *const *keys;
    long compares;
} order_t;

/* By key (NULL first), then by index: equal keys end up together, the
 * first occurrence at the head of each run. */
static int by_key(const void *a, const void *b, void *user)
{
    order_t *o = user;
    const size_t i = *(const size_t *)a, j = *(const size_t *)b;
    const char *ki = o->keys[i], *kj = o->keys[j];
    o->compares++;
    int c = ki && kj ? strcmp(ki, kj) : (ki != NULL) - (kj != NULL);
    if (c == 0)
        c = i < j ? -1 : i > j;
    return c;
}

int sw_cli_keyset_first(const char *const *keys, size_t n, size_t *first, long *compares)
{
    size_t *idx = malloc((n ? n : 1) * sizeof *idx);
    if (!idx)
        return -1;
    for (size_t i = 0; i < n; i++) idx[i] = i;
    order_t o = {keys, 0};
    qsort_r(idx, n, sizeof *idx, by_key, &o);
    for (size_t k = 0; k < n; k++) {
        const char *a = keys[idx[k]], *b = k ? keys[idx[k - 1]] : NULL;
        const int same = k > 0 && (a && b ? !strcmp(a, b) : a == b);
        first[idx[k]] = same ? first[idx[k - 1]] : idx[k];
    }
    free(idx);
    if (compares)
        *compares = o.compares;
    return 0;
}
