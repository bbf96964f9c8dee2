/* SPDX-License-Identifier: GPL-3.0-or-later */
/* text.h - text the command writes from names: UTF-8 checked (for the
 * JSON strings of record.h) and lines shown on a terminal by watch.  A
 * name comes from anywhere (a file name, a scene, a message off the bus)
 * and may hold any byte; what is written stays valid whatever it holds,
 * and every writer of such text goes through here.
 *
 * UTF-8 is checked as Unicode defines it (The Unicode Standard, table 3-7
 * "Well-Formed UTF-8 Byte Sequences": no overlong forms, no surrogates,
 * nothing above U+10FFFF).  An ill-formed sequence counts as one error per
 * maximal subpart (section 3.9, "U+FFFD Substitution of Maximal
 * Subparts"), as Python's and the WHATWG decoders count them. */
#ifndef SWAYWATCH_CLI_TEXT_H
#define SWAYWATCH_CLI_TEXT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* The character at s (n > 0 bytes there): 1 and its length in *len, with
 * its code point in *cp; or 0 when s starts an ill-formed sequence, its
 * maximal subpart *len bytes long (at least 1). */
int sw_cli_utf8_next(const unsigned char *s, size_t n, size_t *len, uint32_t *cp);

/* n bytes of src (up to its first NUL) as a line for a terminal, into dst
 * (cap > 0 bytes, NUL-terminated, cut at a character): well-formed UTF-8
 * as it is, but each control character (C0, DEL, C1: U+0080 to U+009F,
 * which a terminal reads as CSI, OSC and the like) and each ill-formed
 * subpart as '?'.  Returns the '?' put in. */
size_t sw_cli_term_text(char *dst, size_t cap, const char *src, size_t n);

/* The longest prefix of s (a C string) of at most max bytes that does not
 * end inside a character: where to cut s to fit max bytes. */
size_t sw_cli_utf8_fit(const char *s, size_t max);

#endif
