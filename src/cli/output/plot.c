/* SPDX-License-Identifier: GPL-3.0-or-later */
/* plot.c - figures drawn by gnuplot, run as a subprocess: the script and
 * its data (inline datablocks) go down a pipe and gnuplot writes the file.
 * gnuplot's own messages are caught in a temporary file and passed on with
 * the "swaywatch: " prefix when it fails. */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "plot.h"

struct sw_plot {
    FILE *gp;
    const char *path;
    char errfile[64];
    struct sigaction old_pipe; /* SIGPIPE is ignored while gnuplot runs */
};

static const char *ext_of(const char *path)
{
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    return dot && (!slash || dot > slash) ? dot + 1 : "";
}

int sw_cli_plot_check(const sw_cli_option_t *o, const char *path, void *dest)
{
    (void)dest;
    const char *ext = ext_of(path);
    if (!strcmp(ext, "png") || !strcmp(ext, "svg"))
        return SW_EXIT_OK;
    sw_cli_error("--%s: '%s': the file name must end in .png or .svg", o->long_name, path);
    return SW_EXIT_USAGE;
}

/* One byte inside a gnuplot double-quoted string.  Every byte that is not
 * printable ASCII goes as an octal escape, so that no byte of a string
 * from a file name, a scene or the command line can end the string or the
 * command (a newline ends a gnuplot command, and a single-quoted string
 * has no escapes at all): gnuplot turns the escape back into the same
 * byte, so a file name keeps every byte it has.  A backquote too: gnuplot
 * substitutes `...` with a shell command's output before it parses a
 * line, inside double-quoted strings as well.  gnuplot reads up to four
 * digits after "\0" and three after "\1" to "\3": a control byte goes
 * with four ("\0001"), or a digit after it would be read into it ("\0015"
 * is a carriage return, not byte 1 and a '5'). */
static void put_byte(FILE *f, unsigned char c)
{
    if (c == '"' || c == '\\')
        fprintf(f, "\\%c", c);
    else if (c < 0x20 || c > 0x7e || c == '`')
        fprintf(f, c < 0100 ? "\\%04o" : "\\%03o", c);
    else
        fputc(c, f);
}

void sw_cli_plot_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) put_byte(f, (unsigned char)*s);
    fputc('"', f);
}

void sw_cli_plot_text(FILE *f, const char *s)
{
    /* the terminals are set up "enhanced": _ ^ { } @ & ~ are markup unless
     * escaped by a backslash, itself escaped in a double-quoted string; a
     * control byte would only draw as a box or break a line: shown as '?' */
    fputc('"', f);
    for (; *s; s++) {
        const unsigned char c = (unsigned char)*s;
        if (c < 0x20 || c == 0x7f) {
            fputc('?', f);
            continue;
        }
        if (strchr("_^{}@&~\\", c))
            fputs("\\\\", f);
        put_byte(f, c);
    }
    fputc('"', f);
}

sw_plot_t *sw_cli_plot_open(const char *path, int width, int height)
{
    sw_plot_t *p = calloc(1, sizeof *p);
    if (!p) {
        sw_cli_error("out of memory");
        return NULL;
    }
    p->path = path;
    const char *tmp = getenv("TMPDIR");
    snprintf(p->errfile, sizeof p->errfile, "%s/swaywatch-gnuplot-XXXXXX",
             tmp && *tmp && strlen(tmp) < 32 && !strpbrk(tmp, "'\"\\$` ") ? tmp : "/tmp");
    int fd = mkstemp(p->errfile);
    if (fd < 0) {
        sw_cli_error("%s: cannot create a temporary file for gnuplot: %s", path, strerror(errno));
        free(p);
        return NULL;
    }
    close(fd);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "exec gnuplot 2>'%s' >&2", p->errfile);
    struct sigaction ign;
    memset(&ign, 0, sizeof ign);
    ign.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &ign, &p->old_pipe);
    fflush(NULL);
    p->gp = popen(cmd, "w");
    if (!p->gp) {
        sw_cli_error("%s: cannot run gnuplot: %s", path, strerror(errno));
        sigaction(SIGPIPE, &p->old_pipe, NULL);
        unlink(p->errfile);
        free(p);
        return NULL;
    }
    FILE *g = p->gp;
    const char *ext = ext_of(path);
    if (!strcmp(ext, "svg")) {
        fprintf(g, "set terminal svg size %d,%d dynamic enhanced font 'sans,12'\n", width, height);
    } else {
        /* pngcairo draws antialiased lines and UTF-8 text; the plain libgd
         * terminal is the fallback where cairo is missing */
        fprintf(g,
                "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
                "  set terminal pngcairo size %d,%d enhanced font 'sans,11'\n"
                "} else {\n"
                "  set terminal png size %d,%d\n"
                "}\n",
                width, height, width, height);
    }
    fputs("set output ", g);
    sw_cli_plot_string(g, path);
    fputs("\nset encoding utf8\n", g);
    return p;
}

FILE *sw_cli_plot_file(sw_plot_t *p)
{
    return p->gp;
}

int sw_cli_plot_close(sw_plot_t *p)
{
    if (!p)
        return SW_EXIT_OK;
    int rc = SW_EXIT_OK;
    fputs("unset output\n", p->gp);
    int st = pclose(p->gp);
    sigaction(SIGPIPE, &p->old_pipe, NULL);
    struct stat sb;
    if (st == -1 || !WIFEXITED(st) || WEXITSTATUS(st) != 0 || stat(p->path, &sb) != 0 ||
        sb.st_size == 0) {
        if (st != -1 && WIFEXITED(st) && WEXITSTATUS(st) == 127)
            sw_cli_error("%s: gnuplot was not found; install gnuplot (gnuplot-nox)", p->path);
        else
            sw_cli_error("%s: gnuplot failed to draw the figure", p->path);
        FILE *e = fopen(p->errfile, "r");
        char line[512];
        for (int n = 0; e && n < 20 && fgets(line, sizeof line, e); n++) {
            line[strcspn(line, "\n")] = '\0';
            if (line[0])
                sw_cli_error("gnuplot: %s", line);
        }
        if (e)
            fclose(e);
        rc = SW_EXIT_IO;
    }
    unlink(p->errfile);
    free(p);
    return rc;
}
