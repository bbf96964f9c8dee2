/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_gnuplot.c - libFuzzer target for the strings that reach gnuplot: a
 * figure's file name, its title and the packages' names, through the
 * quoting of src/cli/output/plot.c and the script src/cli/output/figure.c builds
 * (replay, simulate and forensics draw with it).
 *
 * Input: 1 byte of options (.svg or .png, 1 to 3 packages, events, gaps),
 * then the file name (a '/' in it becomes '_'), the title and the package
 * names, separated by NUL bytes.
 *
 * Checks, for every input, in-process:
 *   - each string quoted by sw_cli_plot_string() and sw_cli_plot_text() is
 *     one gnuplot double-quoted literal with nothing raw in it that gnuplot
 *     reads otherwise (no control byte, no byte above 0x7e, no backquote,
 *     which gnuplot substitutes even inside double quotes; every backslash
 *     one of gnuplot's escapes), and it decodes, by gnuplot's escape rules,
 *     to the string itself (file names: every byte kept) or to the text
 *     shown (titles: control bytes as '?', enhanced-text markup escaped);
 *   - the figure's script, with every string literal replaced by a token,
 *     is the script of the same figure drawn with plain names: no byte of a
 *     name changes what gnuplot reads as commands.
 * Checks, for one input in GNUPLOT_EVERY (and every input of the
 * regression replay), by gnuplot itself: the script runs with the dumb
 * terminal in a sandbox folder, gnuplot reports no error, the figure is
 * written under its exact name, gnuplot prints each quoted string back as
 * the decoding above says, and the folder holds nothing else (a name that
 * ran `touch`, system() or a shell command would leave a file).  gnuplot
 * costs about 20 ms a run, hence the sample; the target runs at the rate of
 * the others on the rest.  The script does not go through popen(): the
 * target's link wraps popen() and pclose() (-Wl,--wrap) to keep it. */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdarg.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../testutil.h"
#include "figure.h"
#include "fuzz.h"
#include "plot.h"

#ifndef GNUPLOT_EVERY
#define GNUPLOT_EVERY 64 /* inputs per gnuplot run when fuzzing */
#endif
#define MAX_PKG 3
#define MAX_STEM 120  /* bytes of the file name (a name is at most 255) */
#define MAX_TITLE 300 /* bytes of the title */

FILE *__real_popen(const char *command, const char *type);
int __real_pclose(FILE *stream);
FILE *__wrap_popen(const char *command, const char *type);
int __wrap_pclose(FILE *stream);

/* The messages the command would print (plot.c, figure.c). */
static long errors;
void sw_cli_error(const char *fmt, ...)
{
    (void)fmt;
    errors++;
}

/* ---- the script, kept instead of piped to gnuplot ------------------------------- */

static struct {
    FILE *f;         /* the script being written (open_memstream) */
    char *text;      /* ... and once closed */
    size_t len;      /* bytes */
    int run;         /* run gnuplot on it */
    int rc;          /* what sw_cli_figure_draw() returned */
    const char *out; /* the figure's file name */
    char extra[8192];
    size_t nextra; /* script lines appended to the run (the prints) */
} cap;

static char sandbox[256]; /* cwd of gnuplot: the figure and print.out only */
static char errpath[300]; /* gnuplot's standard error, beside it */

FILE *__wrap_popen(const char *command, const char *type)
{
    if (strncmp(command, "exec gnuplot", 12) != 0)
        return __real_popen(command, type);
    free(cap.text);
    cap.text = NULL;
    cap.len = 0;
    cap.f = open_memstream(&cap.text, &cap.len);
    return cap.f;
}

static int run_gnuplot(void);

int __wrap_pclose(FILE *stream)
{
    if (stream != cap.f)
        return __real_pclose(stream);
    FZ_CHECK(fclose(stream) == 0);
    cap.f = NULL;
    if (cap.run)
        return run_gnuplot();
    /* not run: a figure as gnuplot would leave it, for sw_cli_plot_close() */
    const int fd = open(cap.out, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    FZ_CHECK(fd >= 0);
    FZ_CHECK(write(fd, "x", 1) == 1);
    close(fd);
    return 0;
}

/* The script as gnuplot gets it: the dumb terminal (text, and cheap)
 * chosen before the output is set, and the prints appended. */
static int run_gnuplot(void)
{
    char script[sizeof errpath + 4];
    snprintf(script, sizeof script, "%s.gp", errpath);
    FILE *s = fopen(script, "w");
    FZ_CHECK(s != NULL);
    const char *at = strstr(cap.text, "\nset output ");
    FZ_CHECK(at != NULL);
    fwrite(cap.text, 1, (size_t)(at + 1 - cap.text), s);
    fputs("set terminal dumb enhanced\n", s);
    fwrite(at + 1, 1, cap.len - (size_t)(at + 1 - cap.text), s);
    fputs("set print \"print.out\"\n", s);
    fwrite(cap.extra, 1, cap.nextra, s);
    FZ_CHECK(fclose(s) == 0);

    /* spawned, not forked: a fork copies the page tables of the
     * sanitizers' shadow memory, which cost more than gnuplot's run */
    posix_spawn_file_actions_t fa;
    FZ_CHECK(posix_spawn_file_actions_init(&fa) == 0);
    FZ_CHECK(posix_spawn_file_actions_addopen(&fa, 0, script, O_RDONLY, 0) == 0);
    FZ_CHECK(posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0) == 0);
    FZ_CHECK(
        posix_spawn_file_actions_addopen(&fa, 2, errpath, O_WRONLY | O_CREAT | O_TRUNC, 0644) == 0);
    FZ_CHECK(posix_spawn_file_actions_addchdir_np(&fa, sandbox) == 0);
    char *const argv[] = {"gnuplot", NULL};
    pid_t pid;
    FZ_CHECK(posix_spawnp(&pid, "gnuplot", &fa, NULL, argv, environ) == 0);
    posix_spawn_file_actions_destroy(&fa);
    int st;
    pid_t w;
    while ((w = waitpid(pid, &st, 0)) < 0 && errno == EINTR) {
        /* libFuzzer's timer */
    }
    FZ_CHECK(w == pid);
    unlink(script);
    return st;
}

/* ---- gnuplot's double-quoted strings --------------------------------------------- */

/* What gnuplot reads from the literal q[0..n) (quotes included) by its
 * escape rules (gnuplot 5.4, parse_esc(): \\ \" \n \r \t and octal codes,
 * four digits when the first is 0, else three), into out; checks that
 * nothing in it is read otherwise than as text.  Returns the length. */
static size_t decode_literal(const char *q, size_t n, char *out)
{
    FZ_CHECK(n >= 2 && q[0] == '"' && q[n - 1] == '"');
    size_t k = 0;
    for (size_t i = 1; i < n - 1; i++) {
        const unsigned char c = (unsigned char)q[i];
        FZ_CHECK(c >= 0x20 && c < 0x7f && c != '`' && c != '"');
        if (c != '\\') {
            out[k++] = (char)c;
            continue;
        }
        FZ_CHECK(i + 1 < n - 1);
        const char e = q[++i];
        if (e == '\\' || e == '"') {
            out[k++] = e;
            continue;
        }
        FZ_CHECK(e >= '0' && e <= '7'); /* the only other escape the quoting writes */
        const int max = e == '0' ? 4 : 3;
        int v = 0, d = 0;
        for (; d < max && i < n - 1 && q[i] >= '0' && q[i] <= '7'; d++, i++)
            v = 8 * v + (q[i] - '0');
        i--;
        FZ_CHECK(v > 0 && v < 256); /* a NUL would end the string */
        out[k++] = (char)v;
    }
    return k;
}

typedef void (*quote_fn)(FILE *, const char *);

/* What a run prints back: the quoted strings, as they were appended. */
static char expect[8192];
static size_t nexpect;

/* s quoted by fn: one literal, decoding to want[0..wn); for a run, a print
 * of it appended, and want to what it prints. */
static void check_quoted(quote_fn fn, const char *s, const char *want, size_t wn)
{
    char *q = NULL;
    size_t n = 0;
    FILE *m = open_memstream(&q, &n);
    FZ_CHECK(m != NULL);
    fn(m, s);
    FZ_CHECK(fclose(m) == 0);
    char *got = malloc(n + 1);
    FZ_CHECK(got != NULL);
    const size_t k = decode_literal(q, n, got);
    FZ_CHECK(k == wn && memcmp(got, want, wn) == 0);
    if (cap.nextra + n + 8 < sizeof cap.extra && nexpect + wn + 1 < sizeof expect) {
        memcpy(cap.extra + cap.nextra, "print ", 6);
        memcpy(cap.extra + cap.nextra + 6, q, n);
        cap.extra[cap.nextra + 6 + n] = '\n';
        cap.nextra += n + 7;
        memcpy(expect + nexpect, want, wn);
        expect[nexpect + wn] = '\n';
        nexpect += wn + 1;
    }
    free(got);
    free(q);
}

/* What sw_cli_plot_text() is to show: control bytes as '?', the markup of
 * enhanced text (_ ^ { } @ & ~ and the backslash) escaped by a backslash. */
static size_t shown(const char *s, char *out)
{
    size_t k = 0;
    for (; *s; s++) {
        const unsigned char c = (unsigned char)*s;
        if (c < 0x20 || c == 0x7f) {
            out[k++] = '?';
            continue;
        }
        if (strchr("_^{}@&~\\", c))
            out[k++] = '\\';
        out[k++] = (char)c;
    }
    return k;
}

static void check_string(const char *s)
{
    const size_t n = strlen(s);
    check_quoted(sw_cli_plot_string, s, s, n);
    char t[2 * MAX_TITLE + 2];
    const size_t k = shown(s, t);
    check_quoted(sw_cli_plot_text, s, t, k);
}

/* ---- the script's commands --------------------------------------------------------- */

/* s with every string literal replaced by "S": what gnuplot reads as
 * commands, whatever the strings hold.  A literal left open at the end of
 * its line is an error: the rest of the line would be read as commands. */
static char *skeleton(const char *s, size_t n)
{
    char *k = malloc(n + 1);
    FZ_CHECK(k != NULL);
    size_t j = 0;
    for (size_t i = 0; i < n; i++) {
        const char c = s[i];
        if (c == '"') {
            for (i++; i < n && s[i] != '"'; i++) {
                FZ_CHECK(s[i] != '\n');
                if (s[i] == '\\')
                    i++;
            }
            FZ_CHECK(i < n);
            k[j++] = 'S';
        } else if (c == '\'') {
            for (i++; i < n && !(s[i] == '\'' && (i + 1 >= n || s[i + 1] != '\'')); i++) {
                FZ_CHECK(s[i] != '\n');
                if (s[i] == '\'')
                    i++; /* '' is a quote inside */
            }
            FZ_CHECK(i < n);
            k[j++] = 'S';
        } else {
            FZ_CHECK(c != '`');
            k[j++] = c;
        }
    }
    k[j] = '\0';
    return k;
}

/* The engine a figure of n packages reads its packages' geometry from
 * (sw_engine_derived(): the angle alpha), made once per process for each
 * n and never pushed: nothing in it changes from one input to the next,
 * so no input can leave anything behind for another.  The figure takes
 * the names from the scenes it is given, not from the engine (the engine
 * copies names, it reads none).  Made per input, it cost a fifth of the
 * target's time (the stability bound of its step, sw_step_init). */
static const sw_engine_t *engine(size_t n)
{
    static sw_engine_t *made[MAX_PKG + 1];
    if (!made[n]) {
        sw_scene_t sc[MAX_PKG];
        for (size_t k = 0; k < n; k++) {
            sc[k] = tu_bare(2.0, 0.728);
            snprintf(sc[k].name, sizeof sc[k].name, "P%zu", k);
        }
        sw_engine_opts_t eo;
        memset(&eo, 0, sizeof eo);
        int err;
        made[n] = sw_engine_create(sc, n, &eo, &err, NULL, 0);
        FZ_CHECK(made[n] != NULL);
    }
    return made[n];
}

/* The figure of n packages named names[], drawn into path under title
 * (states and events from the options only); its script in cap. */
static void draw(uint8_t o, size_t n, char names[][SW_NAME_MAX], const char *path,
                 const char *title)
{
    sw_scene_t sc[MAX_PKG];
    for (size_t k = 0; k < n; k++) {
        sc[k] = tu_bare(2.0, 0.728);
        memcpy(sc[k].name, names[k], SW_NAME_MAX);
    }
    sw_cli_figure_t *f = sw_cli_figure_create(engine(n), sc, n);
    FZ_CHECK(f != NULL);
    for (size_t k = 0; k < n; k++)
        for (int i = 0; i < 4; i++) {
            sw_output_t out;
            memset(&out, 0, sizeof out);
            out.pkg = k;
            out.t = 0.01 * i;
            out.state.theta = 0.01 * i * (double)(k + 1);
            out.state.phase = i ? SW_PHASE_ROCKING : SW_PHASE_STUCK;
            out.margin = 1.0 - 0.2 * i;
            out.a_g = -3.0 * i;
            sw_cli_figure_state(f, &out);
        }
    if (o & 0x10) {
        static const sw_event_kind kinds[] = {SW_EV_UPLIFT, SW_EV_IMPACT, SW_EV_TIP,
                                              SW_EV_OVERTURN};
        for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
            const sw_event_t ev = {.pkg = i % n, .kind = kinds[i], .t = 0.005 + 0.008 * i};
            sw_cli_figure_event(f, &ev);
        }
    }
    if (o & 0x20) {
        sw_cli_figure_gap(f, 0.012, 0.018);
        sw_cli_figure_mark(f, 0.02);
    }
    cap.out = path;
    const long before = errors;
    cap.rc = sw_cli_figure_draw(f, path, title);
    FZ_CHECK(cap.text != NULL);
    if (!cap.run)
        FZ_CHECK(cap.rc == SW_EXIT_OK && errors == before);
    sw_cli_figure_destroy(f);
}

/* The figure with plain names: its skeleton, per options (what it draws). */
static const char *plain_skeleton(uint8_t o, size_t n, int png)
{
    static char *cache[256];
    if (!cache[o]) {
        char names[MAX_PKG][SW_NAME_MAX];
        for (size_t k = 0; k < n; k++) snprintf(names[k], SW_NAME_MAX, "P%zu", k);
        char path[300];
        snprintf(path, sizeof path, "%s/plain.%s", sandbox, png ? "png" : "svg");
        const int run = cap.run;
        cap.run = 0;
        draw(o, n, names, path, "T");
        cap.run = run;
        unlink(path);
        cache[o] = skeleton(cap.text, cap.len);
    }
    return cache[o];
}

/* The sandbox must hold the figure and print.out, nothing else. */
static void check_sandbox(const char *figure)
{
    DIR *d = opendir(sandbox);
    FZ_CHECK(d != NULL);
    for (struct dirent *e; (e = readdir(d));) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        if (strcmp(e->d_name, figure) && strcmp(e->d_name, "print.out")) {
            fprintf(stderr, "gnuplot left '%s' in %s\n", e->d_name, sandbox);
            FZ_CHECK(!"a string ran a command or changed the figure's name");
        }
    }
    closedir(d);
}

static int have_gnuplot(void)
{
    static int have = -1;
    if (have < 0) {
        have = system("gnuplot -e 'exit' >/dev/null 2>&1") == 0;
        if (!have)
            fprintf(stderr, "fuzz_gnuplot: no gnuplot: the scripts are not run\n");
    }
    return have;
}

static char topdir[200]; /* the sandbox's parent, removed at exit */

static void cleanup(void)
{
    unlink(errpath);
    rmdir(sandbox);
    rmdir(topdir);
}

/* The folders are in memory (/dev/shm) unless TMPDIR says where: every
 * input creates and removes the figure and plot.c's file for gnuplot's
 * messages, which on a disk's filesystem cost a third of the target's
 * time (inodes created and journalled).  plot.c's temporary file goes
 * beside the sandbox (TMPDIR set to its parent). */
static void setup(void)
{
    if (sandbox[0])
        return;
    const char *tmp = getenv("TMPDIR");
    const int given = tmp && *tmp;
    if (!given)
        tmp = access("/dev/shm", W_OK | X_OK) == 0 ? "/dev/shm" : "/tmp";
    snprintf(topdir, sizeof topdir, "%s/fuzz_gnuplot.XXXXXX", tmp);
    FZ_CHECK(mkdtemp(topdir) != NULL);
    snprintf(sandbox, sizeof sandbox, "%s/run", topdir);
    snprintf(errpath, sizeof errpath, "%s/stderr", topdir);
    FZ_CHECK(mkdir(sandbox, 0700) == 0);
    if (!given)
        FZ_CHECK(setenv("TMPDIR", topdir, 1) == 0);
    atexit(cleanup);
}

/* The next NUL-terminated piece of the input, at most max bytes of it. */
static void piece(fz_bytes_t *b, char *dst, size_t max)
{
    const uint8_t *z = memchr(b->p, 0, b->n);
    const size_t len = z ? (size_t)(z - b->p) : b->n;
    const size_t k = len < max ? len : max;
    memcpy(dst, b->p, k);
    dst[k] = '\0';
    b->p += len + (z != NULL);
    b->n -= len + (z != NULL);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    setup();
    fz_bytes_t b = {data, size};
    const uint8_t o = fz_byte(&b);
    const int png = o & 1;
    const size_t n = 1 + (size_t)((o >> 1) & 3) % MAX_PKG;
    char stem[MAX_STEM + 1], title[MAX_TITLE + 1], names[MAX_PKG][SW_NAME_MAX];
    piece(&b, stem, MAX_STEM);
    piece(&b, title, MAX_TITLE);
    for (size_t k = 0; k < n; k++) piece(&b, names[k], SW_NAME_MAX - 1);
    for (char *p = stem; *p; p++)
        if (*p == '/')
            *p = '_';
    if (!stem[0] || !strcmp(stem, ".") || !strcmp(stem, ".."))
        snprintf(stem, sizeof stem, "f");

    /* one run of gnuplot in GNUPLOT_EVERY inputs, chosen by their bytes */
    uint64_t h = 0xcbf29ce484222325ULL;
    for (size_t i = 0; i < size; i++) h = (h ^ data[i]) * 0x100000001b3ULL;
#ifdef FZ_REPLAY
    cap.run = have_gnuplot();
#else
    cap.run = h % GNUPLOT_EVERY == 0 && have_gnuplot();
#endif
    const char *plain = plain_skeleton(o, n, png);

    cap.nextra = nexpect = 0;
    check_string(stem);
    check_string(title);
    for (size_t k = 0; k < n; k++) check_string(names[k]);

    char figure[MAX_STEM + 8], path[sizeof sandbox + sizeof figure + 1];
    snprintf(figure, sizeof figure, "%s.%s", stem, png ? "png" : "svg");
    snprintf(path, sizeof path, "%s/%s", sandbox, figure);
    draw(o, n, names, path, title);
    char *k = skeleton(cap.text, cap.len);
    FZ_CHECK(strcmp(k, plain) == 0);
    free(k);

    if (cap.run) {
        check_sandbox(figure); /* first: the worst finding */
        /* gnuplot's messages: warnings at most */
        FILE *e = fopen(errpath, "r");
        FZ_CHECK(e != NULL && fseek(e, 0, SEEK_END) == 0);
        const long size_e = ftell(e);
        FZ_CHECK(size_e >= 0 && fseek(e, 0, SEEK_SET) == 0);
        char *msgs = malloc((size_t)size_e + 1);
        FZ_CHECK(msgs != NULL);
        msgs[fread(msgs, 1, (size_t)size_e, e)] = '\0';
        fclose(e);
        for (char *l = msgs, *nl; l && *l; l = nl) {
            if ((nl = strchr(l, '\n')))
                *nl++ = '\0';
            if (l[strspn(l, " ^")] && !strstr(l, "warning:")) {
                fprintf(stderr, "gnuplot said: %s\n", l);
                FZ_CHECK(!"gnuplot reported an error");
            }
        }
        free(msgs);
        FZ_CHECK(cap.rc == SW_EXIT_OK); /* gnuplot's status 0, the figure written */
        struct stat st;
        FZ_CHECK(stat(path, &st) == 0 && st.st_size > 0); /* under its exact name */
        char pout[sizeof sandbox + 16];
        snprintf(pout, sizeof pout, "%s/print.out", sandbox);
        FILE *p = fopen(pout, "rb");
        FZ_CHECK(p != NULL);
        static char got[sizeof expect + 1];
        const size_t g = fread(got, 1, sizeof got, p);
        fclose(p);
        FZ_CHECK(g == nexpect && memcmp(got, expect, g) == 0);
        unlink(pout);
    }
    unlink(path);
    return 0;
}
