/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fingerprint.h - what ties a report to its inputs and to the program that
 * made it: the SHA-256 and size of a file (libsodium's
 * crypto_hash_sha256), the command line quoted so that a POSIX shell reads
 * it back into the same words, and the version with the commit it was
 * built from (scripts/commit.cmake). */
#ifndef SWAYWATCH_CLI_FINGERPRINT_H
#define SWAYWATCH_CLI_FINGERPRINT_H

#include <stdio.h>

/* A file's digest, or why there is none. */
typedef struct {
    int ok;          /* sha256 and size are set */
    char sha256[65]; /* lowercase hex */
    long long size;  /* bytes hashed */
    char why[160];   /* when not ok: why ("standard input is a pipe: ...") */
} sw_cli_digest_t;

/* The digest of what the open descriptor fd holds, read from its start
 * with pread(): the exact file being read (no second lookup by name), and
 * its file offset is left where it was.  A pipe cannot be read again: not
 * ok, and why says so.  Returns d->ok. */
int sw_cli_digest_fd(int fd, sw_cli_digest_t *d);

/* The digest of the file at path.  Returns d->ok. */
int sw_cli_digest_path(const char *path, sw_cli_digest_t *d);

/* One word quoted for a POSIX shell: as it is when it holds only
 * characters no shell treats specially, else in single quotes (a single
 * quote as '\''); the empty word as ''. */
void sw_cli_shell_word(FILE *f, const char *w);
/* "prog argv[0] argv[1] ...", each word quoted, into a malloc'd string
 * (NULL: out of memory). */
char *sw_cli_shell_line(const char *prog, int argc, char *const *argv);

/* The commit the program was built from (40 hex digits), or "" when the
 * build did not know it; whether the checkout had changes to tracked
 * files. */
const char *sw_cli_commit(void);
int sw_cli_commit_modified(void);
/* "0.1.0 (commit 0123abcd..., with local changes)", "0.1.0 (commit
 * unknown)". */
void sw_cli_version_text(char *buf, size_t len);

#endif
