/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fingerprint.c - file digests, shell quoting and the build's commit
 * (fingerprint.h): what lets anyone show that a report belongs to a log,
 * to its scenes and to a version of the program. */
#include "fingerprint.h"

#include <errno.h>
#include <fcntl.h>
#include <sodium.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "interrupt.h"
#include "sw_commit.h"

#define CHUNK (1 << 16) /* bytes read at a time */

static void hex(char out[65], const unsigned char h[crypto_hash_sha256_BYTES])
{
    static const char digits[] = "0123456789abcdef";
    for (size_t i = 0; i < crypto_hash_sha256_BYTES; i++) {
        out[2 * i] = digits[h[i] >> 4];
        out[2 * i + 1] = digits[h[i] & 15];
    }
    out[64] = '\0';
}

int sw_cli_digest_fd(int fd, sw_cli_digest_t *d)
{
    memset(d, 0, sizeof *d);
    if (sodium_init() < 0) {
        snprintf(d->why, sizeof d->why, "libsodium could not be initialised");
        return 0;
    }
    unsigned char *buf = malloc(CHUNK);
    if (!buf) {
        snprintf(d->why, sizeof d->why, "out of memory");
        return 0;
    }
    crypto_hash_sha256_state st;
    crypto_hash_sha256_init(&st);
    long long off = 0;
    for (;;) {
        const ssize_t n = pread(fd, buf, CHUNK, (off_t)off);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            if (errno == ESPIPE)
                snprintf(d->why, sizeof d->why,
                         "read from a pipe, which cannot be read again: give the file's name "
                         "for its digest");
            else
                snprintf(d->why, sizeof d->why, "cannot be read again: %s", strerror(errno));
            free(buf);
            return 0;
        }
        if (n == 0)
            break;
        if (sw_cli_signal) { /* stopping: a digest is no reason to wait */
            snprintf(d->why, sizeof d->why, "interrupted by %s", sw_cli_signal_name(sw_cli_signal));
            free(buf);
            return 0;
        }
        crypto_hash_sha256_update(&st, buf, (unsigned long long)n);
        off += n;
    }
    free(buf);
    unsigned char h[crypto_hash_sha256_BYTES];
    crypto_hash_sha256_final(&st, h);
    hex(d->sha256, h);
    d->size = off;
    d->ok = 1;
    return 1;
}

int sw_cli_digest_path(const char *path, sw_cli_digest_t *d)
{
    const int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        memset(d, 0, sizeof *d);
        snprintf(d->why, sizeof d->why, "cannot be opened again: %s", strerror(errno));
        return 0;
    }
    sw_cli_digest_fd(fd, d);
    close(fd);
    return d->ok;
}

/* ---- the command line ----------------------------------------------------------- */

/* Characters no POSIX shell gives a meaning to in a word (nor at its
 * start: '=' only matters before the command name, '~' is not here). */
static int plain(const char *w)
{
    if (!*w)
        return 0;
    for (const unsigned char *p = (const unsigned char *)w; *p; p++)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') ||
              strchr("_@%+=:,./-", *p)))
            return 0;
    return 1;
}

void sw_cli_shell_word(FILE *f, const char *w)
{
    if (plain(w)) {
        fputs(w, f);
        return;
    }
    fputc('\'', f);
    for (const char *p = w; *p; p++)
        if (*p == '\'')
            fputs("'\\''", f);
        else
            fputc(*p, f);
    fputc('\'', f);
}

char *sw_cli_shell_line(const char *prog, int argc, char *const *argv)
{
    char *s = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&s, &len);
    if (!f)
        return NULL;
    sw_cli_shell_word(f, prog);
    for (int i = 0; i < argc; i++) {
        fputc(' ', f);
        sw_cli_shell_word(f, argv[i]);
    }
    if (fclose(f) != 0) {
        free(s);
        return NULL;
    }
    return s;
}

/* ---- the build -------------------------------------------------------------------- */

const char *sw_cli_commit(void)
{
    return SW_CLI_COMMIT;
}

int sw_cli_commit_modified(void)
{
    return SW_CLI_COMMIT_MODIFIED;
}

void sw_cli_version_text(char *buf, size_t len)
{
    if (!SW_CLI_COMMIT[0])
        snprintf(buf, len, "%s (commit unknown)", sw_version());
    else
        snprintf(buf, len, "%s (commit %s%s)", sw_version(), SW_CLI_COMMIT,
                 SW_CLI_COMMIT_MODIFIED ? ", with local changes" : "");
}
