/* SPDX-License-Identifier: GPL-3.0-or-later */
/* clobber.h - no output overwrites an input or another output.
 *
 * Opening an output truncates it.  Before a command opens anything for
 * writing, every output it will write is compared with every input it
 * reads and with every other output: two paths are the same file when
 * stat() (which follows symbolic links) gives the same device and inode,
 * so hard links and symbolic links are caught as well as the same name;
 * an output that does not exist yet is compared by its resolved path
 * (directory through realpath(), a dangling symbolic link followed to
 * where it would create the file). */
#ifndef SWAYWATCH_CLI_CLOBBER_H
#define SWAYWATCH_CLI_CLOBBER_H

#include <stddef.h>

#include "cli.h"
#include "opts.h"

/* A file a command reads or writes.  path NULL: none given; "-": standard
 * input (an input: checked through its descriptor, a file redirected to
 * it counts) or standard output (an output: not checked). */
typedef struct {
    const char *what; /* as named in messages: "--out", "LOG", "--scene" */
    const char *path;
} sw_cli_file_t;

/* SW_EXIT_OK, or SW_EXIT_USAGE after "swaywatch: --out PATH: that is the
 * log being read (LOG PATH)" / "... that is the scene file (--scene PATH)"
 * / "--out A and --events B name the same file". */
int sw_cli_check_files(const sw_cli_file_t *in, size_t nin, const sw_cli_file_t *out, size_t nout);

/* The same with the inputs of most commands: log (NULL: none; "-":
 * standard input) and every --scene of scenes. */
int sw_cli_check_run_files(const char *log, const sw_cli_list_t *scenes, const sw_cli_file_t *out,
                           size_t nout);

/* The file an LCM URL makes LCM write (file://PATH?mode=w or mode=a, its
 * options read as liblcm reads them: lcmurl.h), in buf; NULL if url
 * writes no file (or buf is too small).  url NULL or "": $LCM_DEFAULT_URL,
 * as LCM does. */
const char *sw_cli_lcm_url_output(const char *url, char *buf, size_t len);

#endif
