/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_scene.c - libFuzzer target for scene files and the engine behind
 * them: sw_scene_parse(), sw_scene_set_arg() overrides, sw_scene_validate(),
 * then sw_engine_create() and a few pushed samples.
 *
 * Input: the scene text, a NUL, "--set" assignments one per line, a NUL,
 * then engine options (2 bytes) and samples (4 bytes each).  Without a NUL
 * the whole input is the scene text and a default pulse is pushed.
 *
 * Checks: only documented status codes; a scene that validates derives
 * finite quantities and makes an engine (or a reasoned refusal); every
 * state, event and summary number the engine hands out is finite, however
 * odd the samples (NaN, 1e300, time going back, free fall).
 *
 * The work per input is bounded (fuzz.h): pushing stops at FZ_STEP_BUDGET
 * engine steps, no sample interval is longer than MAX_STEPS_PER_SAMPLE of
 * the package's own step (a stiff scene steps in microseconds: a 32 ms
 * interval would be tens of thousands of steps), and the settle at the end
 * is as short. */
#include "fuzz.h"

#define MAX_SAMPLES 48
#define MAX_STEPS_PER_SAMPLE 64
#define G 9.81

typedef struct {
    long diags;
    long states, events, faults;
} ctx_t;

static void on_diag(void *user, const char *origin, int line, const char *msg)
{
    ctx_t *c = user;
    FZ_CHECK(origin != NULL && msg != NULL && msg[0] != '\0');
    FZ_CHECK(line >= 0);
    c->diags++;
}

static void on_state(void *user, const sw_output_t *o)
{
    ctx_t *c = user;
    fz_check_output(o);
    c->states++;
}

static void on_event(void *user, const sw_event_t *ev)
{
    ctx_t *c = user;
    fz_check_event(ev);
    c->events++;
    c->faults += ev->kind == SW_EV_FAULT;
}

static int known_code(int rc)
{
    return rc == SW_OK || rc == SW_EINVAL || rc == SW_ENOTFOUND || rc == SW_EPARSE ||
           rc == SW_ENOMEM;
}

static void check_derived(const sw_derived_t *d)
{
    const double v[] = {d->h,   d->b,     d->R,   d->alpha,   d->p,       d->I_C,      d->I_O,
                        d->eta, d->gamma, d->k_b, d->c_b,     d->omega_b, d->zeta_b,   d->r_frame,
                        d->K,   d->C,     d->B3,  d->omega_c, d->zeta_c,  d->omega_max};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) FZ_CHECK(isfinite(v[i]));
    FZ_CHECK(d->alpha > 0.0 && d->alpha < M_PI_2);
    FZ_CHECK(d->R > 0.0 && d->p > 0.0 && d->omega_max >= 0.0);
}

/* Special values a sample may carry. */
static const double specials[] = {NAN, INFINITY,  -INFINITY, 1e300,  -1e300,  1e6,      -1e6,
                                  -G,  -G - 1e-9, -2 * G,    1e-300, DBL_MAX, -DBL_MAX, 0.0};
#define NSPECIAL (sizeof specials / sizeof specials[0])

static void run_engine(const sw_scene_t *sc, fz_bytes_t *b, int have_samples)
{
    static const char *const schemes[] = {NULL,   "rk4",   "heun",   "euler", "rkf45",
                                          "rkck", "rk8pd", "rk4imp", "bsimp", "msbdf"};
    ctx_t c = {0};
    sw_engine_opts_t o;
    memset(&o, 0, sizeof o);
    const uint8_t s0 = fz_byte(b), s1 = fz_byte(b);
    o.scheme = schemes[s0 % (sizeof schemes / sizeof schemes[0])];
    /* Euler's default step is tiny; keep the run short with the others'. */
    if (o.scheme && !strcmp(o.scheme, "euler"))
        o.dt = 1e-4;
    if (s0 & 0x80) {
        o.dt = 1e-4 * (1 + (s1 & 0x3f));
        o.dt_forced = (s1 >> 6) & 1;
    }
    o.on_state = on_state;
    o.on_event = on_event;
    o.user = &c;
    int err = 0;
    char msg[512];
    sw_engine_t *e = sw_engine_create(sc, 1, &o, &err, msg, sizeof msg);
    if (!e) {
        FZ_CHECK(err == SW_EUNSTABLE || err == SW_EINVAL);
        FZ_CHECK(msg[0] != '\0');
        return;
    }
    double t = 0.0;
    const double h = sw_engine_dt(e, 0); /* s, the package's step */
    FZ_CHECK(h > 0.0 && isfinite(h));
    const double longest = MAX_STEPS_PER_SAMPLE * h; /* s, of a sample interval */
    if (!have_samples) {
        /* A braking half-sine that lifts most packages. */
        for (int i = 0; i <= 200 && fz_steps(e) < FZ_STEP_BUDGET; i++) {
            const double ti = i * 1e-3;
            sw_engine_push(e, ti, -1.2 * G * sin(M_PI * ti / 0.2), 0.0);
        }
    }
    for (int i = 0; i < MAX_SAMPLES && b->n > 0 && fz_steps(e) < FZ_STEP_BUDGET; i++) {
        const uint8_t k = fz_byte(b), x = fz_byte(b), y = fz_byte(b), z = fz_byte(b);
        double dt = fmin((1 + (k & 0x3f)) * 5e-4, longest); /* up to 32 ms */
        double ag = (int8_t)x * 0.25, az = (int8_t)y * 0.1;
        switch (k >> 6) {
            case 1: ag = specials[z % NSPECIAL]; break;
            case 2: az = specials[z % NSPECIAL]; break;
            case 3:
                if (z & 1)
                    dt = (z & 2) ? 0.0 : -dt; /* same time, or back */
                else if (z & 2)
                    dt = 1e-300; /* almost the same time */
                else
                    dt = NAN;
                break;
            default: break;
        }
        const double tn = t + dt;
        const int rc = sw_engine_push(e, tn, ag, az);
        FZ_CHECK(rc == SW_OK || rc == SW_EVENT || rc == SW_EORDER || rc == SW_ENONFINITE ||
                 rc == SW_ETOOBIG);
        const int nonfinite = !(isfinite(tn) && isfinite(ag) && isfinite(az));
        FZ_CHECK((rc == SW_ENONFINITE) == nonfinite);
        FZ_CHECK((rc == SW_ETOOBIG) ==
                 (!nonfinite && (fabs(ag) > SW_MAX_ACCEL || fabs(az) > SW_MAX_ACCEL)));
        if (rc >= 0)
            t = tn;
    }
    FZ_CHECK(sw_engine_finish(e, fmin(0.05, longest)) >= 0);
    sw_summary_t s;
    FZ_CHECK(sw_engine_summary(e, 0, &s) == SW_OK);
    fz_check_summary(&s);
    FZ_CHECK(s.faults == c.faults);
    sw_output_t out;
    FZ_CHECK(sw_engine_get_output(e, 0, &out) == SW_OK);
    fz_check_output(&out);
    sw_engine_destroy(e);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* Scene files are small; the CLI refuses anything above 1 MiB. */
    if (size > 64 * 1024)
        return 0;
    const uint8_t *nul1 = memchr(data, 0, size);
    size_t text_len = nul1 ? (size_t)(nul1 - data) : size;
    char *text = malloc(text_len + 1);
    if (!text)
        return 0;
    memcpy(text, data, text_len);
    text[text_len] = '\0';

    ctx_t c = {0};
    sw_scene_t sc;
    sw_scene_init(&sc);
    int rc = sw_scene_parse(&sc, text, "fuzz.ini", on_diag, &c);
    FZ_CHECK(known_code(rc));
    FZ_CHECK((rc == SW_OK) == (c.diags == 0));
    free(text);

    fz_bytes_t rest = {NULL, 0};
    if (nul1) {
        const uint8_t *sets = nul1 + 1;
        size_t left = size - text_len - 1;
        const uint8_t *nul2 = memchr(sets, 0, left);
        size_t sets_len = nul2 ? (size_t)(nul2 - sets) : left;
        char *s = malloc(sets_len + 1);
        if (!s)
            return 0;
        memcpy(s, sets, sets_len);
        s[sets_len] = '\0';
        for (char *line = s, *next; line; line = next) {
            next = strchr(line, '\n');
            if (next)
                *next++ = '\0';
            long before = c.diags;
            int r = sw_scene_set_arg(&sc, line, on_diag, &c);
            FZ_CHECK(known_code(r));
            FZ_CHECK((r == SW_OK) == (c.diags == before));
        }
        free(s);
        if (nul2)
            rest = (fz_bytes_t){nul2 + 1, left - sets_len - 1};
    }

    sw_derived_t d;
    long before = c.diags;
    int v = sw_scene_validate(&sc, &d, "fuzz.ini", on_diag, &c);
    FZ_CHECK(v == SW_OK || v == SW_EINVAL);
    FZ_CHECK((v == SW_OK) == (c.diags == before));
    if (v != SW_OK || rc != SW_OK)
        return 0;
    check_derived(&d);
    FZ_CHECK(memchr(sc.name, '\0', sizeof sc.name) != NULL);
    run_engine(&sc, &rest, nul1 != NULL);
    return 0;
}
