/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lcmurl.c - an LCM URL read the way liblcm reads it (lcmurl.h). */
#include "lcmurl.h"

#include <stdlib.h>
#include <string.h>

const char *sw_cli_lcm_url_effective(const char *url)
{
    if (!url || !url[0])
        url = getenv("LCM_DEFAULT_URL");
    return url && url[0] ? url : NULL;
}

/* The part after the provider's "://", or NULL if there is none (liblcm
 * then refuses the URL). */
static const char *after_provider(const char *url)
{
    const char *sep = url ? strstr(url, "://") : NULL;
    return sep ? sep + 3 : NULL;
}

int sw_cli_lcm_url_option(const char *url, const char *key, char *val, size_t len)
{
    const char *rest = after_provider(url);
    if (!rest)
        return 0;
    const size_t klen = strlen(key);
    const char *q = strchr(rest, '?');
    int found = 0;
    /* Every part after a '?' holds options, '&' between them; '?' and '&'
     * both end an option. */
    for (const char *o = q ? q + 1 : NULL; o && *o;) {
        const size_t olen = strcspn(o, "?&");
        const char *eq = memchr(o, '=', olen);
        const size_t kl = eq ? (size_t)(eq - o) : olen;
        if (kl > 0 && kl == klen && !memcmp(o, key, klen)) {
            const char *v = eq ? eq + 1 : o + olen;
            const size_t vl = (size_t)(o + olen - v);
            found = vl < len;
            if (found) {
                memcpy(val, v, vl);
                val[vl] = '\0';
            }
        }
        o += olen;
        if (*o)
            o++;
    }
    return found;
}

sw_cli_url_file sw_cli_lcm_url_file(const char *url, char *path, size_t len)
{
    const char *rest = after_provider(url);
    if (!rest || (size_t)(rest - url) != 7 || strncmp(url, "file", 4) != 0)
        return SW_CLI_URL_NO_FILE;
    const size_t n = strcspn(rest, "?");
    if (path) {
        if (n >= len)
            return SW_CLI_URL_NO_FILE;
        memcpy(path, rest, n);
        path[n] = '\0';
    }
    char mode[4];
    if (sw_cli_lcm_url_option(url, "mode", mode, sizeof mode) &&
        (!strcmp(mode, "w") || !strcmp(mode, "a")))
        return SW_CLI_URL_WRITES;
    return SW_CLI_URL_READS;
}
