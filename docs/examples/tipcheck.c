/* SPDX-License-Identifier: GPL-3.0-or-later */
/* tipcheck.c - the smallest program on the swaywatch library: a scene made
 * in code (a crate standing free on the bed), a braking pulse pushed sample
 * by sample as a logger would deliver it, and the summary checked.
 *
 * Build against an installed library:
 *     cc -o tipcheck tipcheck.c $(pkg-config --cflags --libs swaywatch)
 * Run: prints the summary of a gentle and of a hard stop; exits 0 when the
 * crate rocks but stands after the gentle one and overturns in the hard one,
 * 1 otherwise. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <swaywatch/swaywatch.h>

static void on_diag(void *user, const char *origin, int line, const char *msg)
{
    (void)user;
    fprintf(stderr, "tipcheck: %s:%d: %s\n", origin, line, msg);
}

/* A 2.0 m x 0.728 m, 1000 kg crate: it starts to rock above
 * g tan(alpha) = 3.57 m/s^2. */
static int make_scene(sw_scene_t *sc)
{
    static const char *const keys[][3] = {{"package", "name", "crate-A"},
                                          {"package", "height", "2.0"},
                                          {"package", "width", "0.728"},
                                          {"package", "mass", "1000"}};
    sw_scene_init(sc);
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        if (sw_scene_set(sc, keys[i][0], keys[i][1], keys[i][2], 0, "tipcheck.c", 0, on_diag,
                         NULL) != SW_OK)
            return -1;
    return sw_scene_validate(sc, NULL, "tipcheck.c", on_diag, NULL) == SW_OK ? 0 : -1;
}

/* Braking as a half-sine of amplitude a (m/s^2, < 0) and angular frequency
 * 10 rad/s, sampled at 1 kHz, then 3 s of still bed; returns the summary. */
static int run(const sw_scene_t *sc, double a, sw_summary_t *sum)
{
    int err = 0;
    char msg[256];
    sw_engine_opts_t o = {0}; /* default scheme (rk4) and step (1 ms) */
    sw_engine_t *e = sw_engine_create(sc, 1, &o, &err, msg, sizeof msg);
    if (!e) {
        fprintf(stderr, "tipcheck: %s: %s\n", sw_strerror(err), msg);
        return -1;
    }
    const double w = 10.0, T = 3.14159265358979323846 / w; /* s, half a period */
    int rc = SW_OK;
    for (int i = 0; i <= 3000 + (int)(T * 1000) && rc >= 0; i++) {
        const double t = i * 1e-3;
        rc = sw_engine_push(e, t, t < T ? a * sin(w * t) : 0.0, 0.0);
    }
    if (rc >= 0)
        rc = sw_engine_finish(e, 30.0);
    if (rc >= 0)
        rc = sw_engine_summary(e, 0, sum);
    sw_engine_destroy(e);
    if (rc < 0)
        fprintf(stderr, "tipcheck: %s\n", sw_strerror(rc));
    return rc < 0 ? -1 : 0;
}

static void print(const char *what, const sw_summary_t *s)
{
    printf("%-11s %s (%s): uplift at %.3f s, %ld impacts, max |theta| %.2f alpha, %s\n", what,
           s->name, sw_model_name(s->model), s->uplift_time, s->impacts, s->max_theta_ratio,
           s->overturned ? "OVERTURNED" : "stands");
}

int main(void)
{
    gsl_set_error_handler_off(); /* the library reports, it never aborts */
    sw_scene_t sc;
    sw_summary_t gentle, hard;
    if (make_scene(&sc) != 0 || run(&sc, -5.0, &gentle) != 0 || run(&sc, -12.0, &hard) != 0)
        return 1;
    printf("swaywatch %s\n", sw_version());
    print("gentle stop", &gentle);
    print("hard stop", &hard);
    const int ok = isfinite(gentle.uplift_time) && !gentle.overturned && hard.overturned;
    printf("%s\n", ok ? "as expected" : "NOT as expected");
    return ok ? 0 : 1;
}
