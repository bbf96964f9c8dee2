/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cmd_keygen.c - "swaywatch keygen": a key for authenticated sensors
 * (docs/security.md), as `chronyc keygen` writes NTP's: one line "ID
 * HMAC-SHA256 HEX:KEY", 32 bytes from the system's random generator
 * (libsodium's randombytes_buf).  On standard output, as `wg genkey`
 * does (with its warning when that is a file others can read), or added
 * to a key file with -o, which is made with mode 600 and takes the next
 * free id: a change of key is `keygen -o FILE` on both sides. */
#include <errno.h>
#include <fcntl.h>
#include <sodium.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "keyfile.h"
#include "opts.h"

typedef struct {
    const char *out; /* -o: the key file the key is added to */
    long id;         /* --id; 0: the next free one */
} keygen_opts_t;

#define KG(f) SW_CLI_AT(keygen_opts_t, f)

static const sw_cli_option_t keygen_options[] = {
    {SW_CLI_STRING, 'o', "output", "FILE", KG(out),
     .help = "add the key to the key file FILE, with the next free id: a new file is made with "
             "mode 600; an existing one must be a key file others cannot read"},
    {SW_CLI_LONG, 0, "id", "N", KG(id), .min = 1, .max = SW_AUTH_ID_MAX,
     .what = "a key id from 1 to 255",
     .help = "the key's id, 1 to 255, the accel_t.key_id of what it signs (default 1; with -o, "
             "one above the highest in FILE)"},
    {SW_CLI_HELP, 'h', "help", .help = "this help"},
    {.kind = SW_CLI_END},
};

static const sw_cli_command_t keygen_cmd = {
    .name = "keygen",
    .usage = "keygen [--id N] [-o FILE]",
    .about =
        "Makes a key for authenticated sensors: one line 'ID HMAC-SHA256 HEX:KEY' (KEY 32\n"
        "random bytes from the system's generator, as 64 hexadecimal digits), on standard\n"
        "output or added to FILE.  A sender signs every accel_t with the last key of its\n"
        "--key file; a monitor with --key refuses every sample not signed by one of the keys\n"
        "of its file (docs/security.md).  A key file that every user can read, or that its\n"
        "group can write, is refused: keep it at mode 600 (or 640 with a group of the\n"
        "monitor's user alone).\n"
        "\n"
        "Changing a key: 'swaywatch keygen -o FILE' adds a key with a new id; give the monitor\n"
        "the file first (it accepts both keys: restart it, or SIGHUP), then the sender (it\n"
        "signs with the new, last key), then delete the old line from both.\n",
    .exit_text =
        "Exit codes: 0 ok, 2 bad usage or FILE not a key file, 3 FILE could not be "
        "read or written.\n",
};

/* An id for a new key in keys: one above the highest, or the lowest free
 * one after 255; 0 if all are taken. */
static int next_id(const sw_keyring_t *keys)
{
    int top = 0;
    for (int i = 0; i < sw_keyring_size(keys); i++)
        if (sw_keyring_id(keys, i) > top)
            top = sw_keyring_id(keys, i);
    if (top < SW_AUTH_ID_MAX)
        return top + 1;
    for (int id = 1; id <= SW_AUTH_ID_MAX; id++)
        if (!sw_keyring_has(keys, id))
            return id;
    return 0;
}

/* "ID HMAC-SHA256 HEX:KEY\n" for a new random key into line. */
static void key_line(int id, char *line, size_t len)
{
    unsigned char key[SW_AUTH_KEY_LEN];
    char hex[2 * SW_AUTH_KEY_LEN + 1];
    randombytes_buf(key, sizeof key);
    sodium_bin2hex(hex, sizeof hex, key, sizeof key);
    snprintf(line, len, "%d " SW_AUTH_TYPE " HEX:%s\n", id, hex);
    sodium_memzero(key, sizeof key);
    sodium_memzero(hex, sizeof hex);
}

/* Write all of line to fd: SW_EXIT_OK, or SW_EXIT_IO (reported). */
static int write_all(int fd, const char *line, const char *name)
{
    size_t left = strlen(line);
    while (left > 0) {
        const ssize_t w = write(fd, line, left);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            sw_cli_error("keygen: %s: cannot write: %s", name, strerror(errno));
            return SW_EXIT_IO;
        }
        line += w;
        left -= (size_t)w;
    }
    return SW_EXIT_OK;
}

/* The key added to the key file path (made if it does not exist). */
static int add_to_file(const char *path, long id, char *line, size_t len)
{
    int rc;
    sw_keyring_t *keys = NULL;
    int fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0 && errno == EEXIST) {
        /* an existing file: read as the monitor reads it (permissions, key
         * lines), so that what is added to it can be used */
        if (!(keys = sw_cli_key_load("keygen: -o", path, &rc)))
            return rc;
        if (id == 0 && !(id = next_id(keys))) {
            sw_cli_error("keygen: %s: every key id from 1 to %d is taken; delete old keys first",
                         path, SW_AUTH_ID_MAX);
            sw_keyring_destroy(keys);
            return SW_EXIT_USAGE;
        }
        if (sw_keyring_has(keys, (int)id)) {
            sw_cli_error(
                "keygen: %s: key id %ld is in it already; leave out --id to take the "
                "next free one",
                path, id);
            sw_keyring_destroy(keys);
            return SW_EXIT_USAGE;
        }
        sw_keyring_destroy(keys);
        fd = open(path, O_WRONLY | O_APPEND | O_CLOEXEC | O_NOCTTY);
    }
    if (fd < 0) {
        sw_cli_error("keygen: %s: cannot open: %s", path, strerror(errno));
        return SW_EXIT_IO;
    }
    if (id == 0)
        id = 1;
    key_line((int)id, line, len);
    rc = write_all(fd, line, path);
    if (close(fd) != 0 && rc == SW_EXIT_OK) {
        sw_cli_error("keygen: %s: cannot write: %s", path, strerror(errno));
        rc = SW_EXIT_IO;
    }
    if (rc == SW_EXIT_OK)
        fprintf(stderr, "swaywatch: keygen: key %ld added to %s\n", id, path);
    return rc;
}

int cmd_keygen(int argc, char **argv)
{
    keygen_opts_t k = {0};
    sw_cli_group_t g[] = {SW_CLI_GROUP_IN(keygen_options, &k, "Output:")};
    int first;
    int rc = sw_cli_parse(&keygen_cmd, g, 1, argc, argv, &first);
    if (rc != SW_CLI_CONTINUE)
        goto out;
    if ((rc = sw_cli_no_operand("keygen", argc, argv, first)) != SW_EXIT_OK)
        goto out;
    if (sodium_init() < 0) {
        sw_cli_error("keygen: libsodium could not be initialised");
        rc = SW_EXIT_IO;
        goto out;
    }
    char line[32 + 2 * SW_AUTH_KEY_LEN];
    if (k.out) {
        rc = add_to_file(k.out, k.id, line, sizeof line);
    } else {
        /* as wg genkey: a file others can read is no place for a key */
        struct stat st;
        if (fstat(STDOUT_FILENO, &st) == 0 && S_ISREG(st.st_mode) &&
            sw_cli_key_mode_refused(st.st_mode))
            sw_cli_error(
                "keygen: warning: standard output is a file others can read (mode %04o); "
                "a monitor refuses such a key file: chmod 600 it, or use -o FILE",
                (unsigned)(st.st_mode & 07777));
        key_line(k.id ? (int)k.id : 1, line, sizeof line);
        rc = write_all(STDOUT_FILENO, line, "standard output");
    }
    sodium_memzero(line, sizeof line);
out:
    sw_cli_parse_free(g, 1);
    return rc;
}
