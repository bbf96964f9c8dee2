/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sources.c - the sources of samples this build reads (sources.h), as
 * LCM's table of providers: a row per source built, the first whose
 * sniff matches a log's first bytes reads it, CSV (the last) anything.
 * An lcm-logger file is recognised in every build (eventlog.h needs no
 * LCM), to be refused with the reason where no row reads it. */
#include "sources.h"

#include "eventlog.h"

static const sw_cli_source_t *const sources[] = {
#ifdef SW_HAVE_LCM
    &sw_cli_source_lcmlog,
#endif
    &sw_cli_source_csv,
};

/* Kinds of log a build may lack: what they are, and what reads them. */
static const struct {
    int (*sniff)(const void *buf, size_t len);
    const char *needs;
} known[] = {
    {sw_lcmlog_sniff, "lcm-logger files need the LCM build"},
};

_Static_assert(sizeof sources / sizeof sources[0] <= SW_CLI_SOURCES_MAX, "SW_CLI_SOURCES_MAX");

const sw_cli_source_t *sw_cli_source_at(size_t i)
{
    return i < sizeof sources / sizeof sources[0] ? sources[i] : NULL;
}

const sw_cli_source_t *sw_cli_source_of(const void *buf, size_t len, const char **needs)
{
    const size_t n = sizeof sources / sizeof sources[0];
    for (size_t i = 0; i + 1 < n; i++)
        if (sources[i]->sniff(buf, len))
            return sources[i];
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (known[i].sniff(buf, len)) {
            *needs = known[i].needs;
            return NULL;
        }
    return sources[n - 1];
}
