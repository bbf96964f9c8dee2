/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sample_path.c - the path of one sample through the library, for
 * scripts/arch/sample-path.sh: built with the library's sources compiled
 * with -finstrument-functions, it pushes the samples of a CSV log (t, a_g
 * in SI, one per line, no header) into an engine of one scene and records
 * every function entered and left while sample number N is pushed.  It
 * prints one line per record, "> ADDR" or "< ADDR"; the script turns the
 * addresses into files. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swaywatch/swaywatch.h"

#define NI __attribute__((no_instrument_function))
#define MAX_REC (1 << 20)

typedef struct {
    char dir; /* '>' entered, '<' left */
    void *fn;
} rec_t;
static rec_t rec[MAX_REC];
static long nrec;
static int tracing;

NI void __cyg_profile_func_enter(void *fn, void *site);
NI void __cyg_profile_func_exit(void *fn, void *site);

NI void __cyg_profile_func_enter(void *fn, void *site)
{
    (void)site;
    if (tracing && nrec < MAX_REC)
        rec[nrec++] = (rec_t){'>', fn};
}

NI void __cyg_profile_func_exit(void *fn, void *site)
{
    (void)site;
    if (tracing && nrec < MAX_REC)
        rec[nrec++] = (rec_t){'<', fn};
}

NI static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = malloc(1 << 20);
    size_t n = buf ? fread(buf, 1, (1 << 20) - 1, f) : 0;
    fclose(f);
    if (buf)
        buf[n] = '\0';
    return buf;
}

NI int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: sample_path SCENE.ini LOG.csv N SCHEME|default\n");
        return 2;
    }
    char *text = slurp(argv[1]);
    sw_scene_t sc;
    sw_scene_init(&sc);
    if (!text || sw_scene_parse(&sc, text, argv[1], NULL, NULL) != SW_OK ||
        sw_scene_validate(&sc, NULL, argv[1], NULL, NULL) != SW_OK) {
        fprintf(stderr, "sample_path: %s: not a valid scene\n", argv[1]);
        return 2;
    }
    sw_engine_opts_t eo;
    memset(&eo, 0, sizeof eo);
    eo.scheme = strcmp(argv[4], "default") ? argv[4] : NULL;
    int err = 0;
    char msg[256];
    sw_engine_t *e = sw_engine_create(&sc, 1, &eo, &err, msg, sizeof msg);
    if (!e) {
        fprintf(stderr, "sample_path: %s\n", msg);
        return 2;
    }
    FILE *log = fopen(argv[2], "r");
    const long want = atol(argv[3]);
    double t, a;
    long k = 0;
    char line[256];
    while (log && fgets(line, sizeof line, log))
        if (sscanf(line, "%lf,%lf", &t, &a) == 2) {
            tracing = k == want;
            sw_engine_push(e, t, a, 0.0);
            tracing = 0;
            if (k++ == want)
                break;
        }
    if (log)
        fclose(log);
    sw_engine_destroy(e);
    free(text);
    for (long i = 0; i < nrec; i++) printf("%c %p\n", rec[i].dir, rec[i].fn);
    return k > want ? 0 : 1;
}
