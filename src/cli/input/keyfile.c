/* SPDX-License-Identifier: GPL-3.0-or-later */
/* keyfile.c - key files read with their permissions checked (keyfile.h). */
#include "keyfile.h"

#include <errno.h>
#include <fcntl.h>
#include <sodium.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

const char *sw_cli_key_mode_refused(mode_t mode)
{
    if (mode & S_IROTH)
        return "readable by every user";
    if (mode & (S_IWOTH | S_IXOTH))
        return "open to every user";
    if (mode & S_IWGRP)
        return "writable by its group";
    return NULL;
}

sw_keyring_t *sw_cli_key_load(const char *opt, const char *path, int *rc)
{
    *rc = SW_EXIT_IO;
    /* O_NONBLOCK: a FIFO in its place is refused below, not waited on */
    const int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
    if (fd < 0) {
        sw_cli_error("%s %s: cannot open: %s", opt, path, strerror(errno));
        return NULL;
    }
    struct stat st;
    if (fstat(fd, &st) != 0) {
        sw_cli_error("%s %s: %s", opt, path, strerror(errno));
        close(fd);
        return NULL;
    }
    *rc = SW_EXIT_USAGE;
    const char *why = sw_cli_key_mode_refused(st.st_mode);
    if (!S_ISREG(st.st_mode))
        sw_cli_error("%s %s: not a regular file; a key file is a file of key lines", opt, path);
    else if (why)
        sw_cli_error(
            "%s %s: permissions %04o are too open (%s): a key others can read is no "
            "secret, and one others can write is not the sender's; 'chmod 600 %s' (or 640 "
            "with a group of the monitor's user alone)",
            opt, path, (unsigned)(st.st_mode & 07777), why, path);
    else if (st.st_size > SW_AUTH_FILE_MAX)
        sw_cli_error("%s %s: %lld bytes: longer than a key file (at most %d)", opt, path,
                     (long long)st.st_size, SW_AUTH_FILE_MAX);
    if (!S_ISREG(st.st_mode) || why || st.st_size > SW_AUTH_FILE_MAX) {
        close(fd);
        return NULL;
    }
    char *text = malloc(SW_AUTH_FILE_MAX + 1);
    if (!text) {
        sw_cli_error("out of memory");
        close(fd);
        *rc = SW_EXIT_IO;
        return NULL;
    }
    size_t len = 0;
    for (;;) {
        const ssize_t r = read(fd, text + len, SW_AUTH_FILE_MAX + 1 - len);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0) {
            sw_cli_error("%s %s: cannot read: %s", opt, path, strerror(errno));
            sodium_memzero(text, len);
            free(text);
            close(fd);
            *rc = SW_EXIT_IO;
            return NULL;
        }
        if (r == 0 || (len += (size_t)r) > SW_AUTH_FILE_MAX)
            break;
    }
    close(fd);
    char msg[320];
    sw_keyring_t *k = NULL;
    if (len > SW_AUTH_FILE_MAX)
        sw_cli_error("%s %s: longer than a key file (at most %d bytes)", opt, path,
                     SW_AUTH_FILE_MAX);
    else if (!(k = sw_keyring_parse(text, len, path, msg, sizeof msg)))
        sw_cli_error("%s %s", opt, msg);
    sodium_memzero(text, len < SW_AUTH_FILE_MAX + 1 ? len : SW_AUTH_FILE_MAX + 1);
    free(text);
    if (k)
        *rc = SW_EXIT_OK;
    return k;
}
