/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lcmurl.h - an LCM URL read the way liblcm reads it, for the checks
 * made before LCM gets it: a file:// URL that makes LCM read a log (the
 * log is checked first, lcmlog.h) or write one (an output, clobber.h).
 *
 * liblcm 1.3.1 (lcm_parse_url() in lcm/lcm.c, new_argument() in
 * lcm/lcm_file.c) takes the provider before the first "://", the network
 * (for file://, the path) up to the first '?', and options from every
 * later '?'-separated part, each split on '&' into KEY=VALUE (a KEY alone
 * has the value ""; an empty KEY is ignored); a later KEY replaces an
 * earlier one.  The file provider's mode is read for "r", written for "w",
 * appended for "a", and read for any other value (with a warning).  So
 * "file://LOG?mode=w&mode=r" and "file://LOG?speed=0?mode=r" read LOG:
 * the checks must see the same. */
#ifndef SWAYWATCH_CLI_LCMURL_H
#define SWAYWATCH_CLI_LCMURL_H

#include <stddef.h>

/* What LCM does with the file of a file:// URL. */
typedef enum {
    SW_CLI_URL_NO_FILE = 0, /* another provider (udpm, memq, ...), or no valid URL */
    SW_CLI_URL_READS,       /* LCM reads the log at the path */
    SW_CLI_URL_WRITES       /* LCM writes (mode w) or appends to (mode a) the path */
} sw_cli_url_file;

/* The URL lcm_create(url) uses: url, or $LCM_DEFAULT_URL when url is
 * NULL or "" (NULL if that is unset or "" too: LCM's built-in udpm). */
const char *sw_cli_lcm_url_effective(const char *url);

/* The file of LCM URL url (not resolved: see sw_cli_lcm_url_effective)
 * and what LCM does with it.  The path (the network part, maybe empty) is
 * copied into path (len bytes) when path is not NULL; SW_CLI_URL_NO_FILE
 * also when it does not fit. */
sw_cli_url_file sw_cli_lcm_url_file(const char *url, char *path, size_t len);

/* The value of the option key in url as liblcm sees it (the last one
 * given) copied into val (len bytes): 1, or 0 if url has no such option
 * (or the value does not fit). */
int sw_cli_lcm_url_option(const char *url, const char *key, char *val, size_t len);

#endif
