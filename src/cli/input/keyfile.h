/* SPDX-License-Identifier: GPL-3.0-or-later */
/* keyfile.h - key files of authenticated sensors (src/lcm/auth.h) as the
 * commands read them: --key FILE for monitor and for lcm-logger files, and
 * swaywatch keygen.  A key file someone else can read is no secret, so
 * one readable or writable by every user, or writable by its group, is
 * refused before it is read, as ssh refuses a private key others can read
 * (group read is allowed: 0640 root:swaywatch is how a service's key is
 * kept).  LCM builds only. */
#ifndef SWAYWATCH_CLI_KEYFILE_H
#define SWAYWATCH_CLI_KEYFILE_H

#include <sys/types.h>

#include "auth.h"

/* Permission bits that make a key file refused. */
#define SW_CLI_KEY_MODE_REFUSED 0027

/* Why a mode is refused ("readable by every user", ...), or NULL if it
 * is not. */
const char *sw_cli_key_mode_refused(mode_t mode);

/* The keys of the key file at path, for option opt ("--key"): NULL after
 * the reason was printed, with *rc SW_EXIT_USAGE (permissions, not a
 * regular file, not a key file: with what fixes it) or SW_EXIT_IO (cannot
 * be read).  The file's bytes are wiped from memory once parsed. */
sw_keyring_t *sw_cli_key_load(const char *opt, const char *path, int *rc);

#endif
