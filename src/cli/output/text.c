/* SPDX-License-Identifier: GPL-3.0-or-later */
/* text.c - UTF-8 read as Unicode defines it, and terminal lines that stay
 * valid whatever bytes a name holds (text.h). */
#include "text.h"

#include <string.h>

int sw_cli_utf8_next(const unsigned char *s, size_t n, size_t *len, uint32_t *cp)
{
    const unsigned c = s[0];
    *len = 1;
    if (c < 0x80) {
        *cp = c;
        return 1;
    }
    /* Table 3-7: the lead byte gives the length and the range of the
     * second byte; every later byte is 80..BF. */
    size_t need;
    unsigned lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF)
        need = 1;
    else if (c >= 0xE0 && c <= 0xEF)
        need = 2, lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    else if (c >= 0xF0 && c <= 0xF4)
        need = 3, lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    else
        return 0; /* 80..C1, F5..FF never begin a character */
    uint32_t v = c & (0x3Fu >> need);
    for (size_t i = 1; i <= need; i++) {
        const unsigned b = i < n ? s[i] : 0;
        if (b < (i == 1 ? lo : 0x80) || b > (i == 1 ? hi : 0xBF)) {
            *len = i; /* the maximal subpart: what was well-formed so far */
            return 0;
        }
        v = (v << 6) | (b & 0x3F);
    }
    *len = need + 1;
    *cp = v;
    return 1;
}

size_t sw_cli_term_text(char *dst, size_t cap, const char *src, size_t n)
{
    const unsigned char *p = (const unsigned char *)src;
    const void *nul = memchr(src, '\0', n);
    if (nul)
        n = (size_t)((const char *)nul - src);
    size_t k = 0, bad = 0;
    while (n > 0) {
        size_t len;
        uint32_t cp;
        const int ok = sw_cli_utf8_next(p, n, &len, &cp);
        if (!ok || cp < 0x20 || (cp >= 0x7F && cp <= 0x9F)) {
            if (k + 1 >= cap)
                break;
            dst[k++] = '?';
            bad++;
        } else {
            if (k + len >= cap)
                break;
            memcpy(dst + k, p, len);
            k += len;
        }
        p += len;
        n -= len;
    }
    dst[k] = '\0';
    return bad;
}

size_t sw_cli_utf8_fit(const char *s, size_t max)
{
    const unsigned char *p = (const unsigned char *)s;
    size_t n = strlen(s), k = 0;
    while (k < n) {
        size_t len;
        uint32_t cp;
        sw_cli_utf8_next(p + k, n - k, &len, &cp);
        if (k + len > max)
            break;
        k += len;
    }
    return k;
}
