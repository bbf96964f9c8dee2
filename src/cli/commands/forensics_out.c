/* SPDX-License-Identifier: GPL-3.0-or-later */
/* forensics_out.c - the answer of "swaywatch forensics" in words and as
 * JSON (forensics.h): for every package first what happened, its safety
 * factor as a bracket with a sentence that says what it means, and what
 * would have saved it; then the what-if table; then how it was found. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "forensics.h"

/* Impacts of one package kept for the report's table: the first few; the
 * rest are counted (a package can chatter hundreds of times). */
#define IMPACTS_KEPT 20

int sw_cli_forensics_begin(sw_cli_forensics_t *F)
{
    if (!F->fo.report)
        return SW_EXIT_OK;
    F->ev = calloc(SW_CLI_FORENSICS_EVENTS, sizeof *F->ev);
    F->impacts_seen = calloc(F->n ? F->n : 1, sizeof *F->impacts_seen);
    if (F->ev && F->impacts_seen)
        return SW_EXIT_OK;
    sw_cli_error("out of memory");
    return SW_EXIT_IO;
}

void sw_cli_forensics_event(sw_cli_forensics_t *F, const sw_event_t *ev)
{
    if (!F->ev || ev->pkg >= F->n)
        return;
    if (ev->kind == SW_EV_IMPACT && ++F->impacts_seen[ev->pkg] > IMPACTS_KEPT) {
        F->ev_dropped++;
        return;
    }
    if (F->nev == SW_CLI_FORENSICS_EVENTS) {
        F->ev_dropped++;
        return;
    }
    F->ev[F->nev++] = *ev;
}

void sw_cli_forensics_end(sw_cli_forensics_t *F)
{
    (void)F;
}

/* The thread reads only its descriptor and writes only the digest: the
 * replay's reader is the main thread's alone. */
static void *digest_main(void *arg)
{
    sw_cli_forensics_t *F = arg;
    sw_cli_digest_fd(F->digest_fd, &F->log_digest);
    return NULL;
}

void sw_cli_forensics_digest_start(sw_cli_forensics_t *F)
{
    if (!F->R.lf.in || F->digest_running)
        return;
    F->digest_fd = fileno(F->R.lf.in);
    F->digest_running = pthread_create(&F->digest_thread, NULL, digest_main, F) == 0;
}

/* The digest made beside the replay, if one was started: 1 once joined. */
static int digest_join(sw_cli_forensics_t *F)
{
    if (!F->digest_running)
        return 0;
    pthread_join(F->digest_thread, NULL);
    F->digest_running = 0;
    return 1;
}

void sw_cli_forensics_free(sw_cli_forensics_t *F)
{
    digest_join(F); /* before the log's descriptor is closed */
    free(F->ev);
    free(F->impacts_seen);
    free(F->scene_digest);
    free(F->command_line);
    F->ev = NULL;
    F->impacts_seen = NULL;
    F->scene_digest = NULL;
    F->command_line = NULL;
    F->fingerprinted = 0;
}

int sw_cli_forensics_fingerprint(sw_cli_forensics_t *F)
{
    const sw_cli_list_t *sc = &F->o.scenes;
    if (!digest_join(F)) { /* not made beside the replay */
        if (F->R.lf.in)
            sw_cli_digest_fd(fileno(F->R.lf.in), &F->log_digest);
        else
            snprintf(F->log_digest.why, sizeof F->log_digest.why, "not open");
    }
    F->scene_digest = calloc(sc->n ? sc->n : 1, sizeof *F->scene_digest);
    F->command_line = sw_cli_shell_line("swaywatch", F->argc, F->argv);
    if (!F->scene_digest || !F->command_line) {
        sw_cli_error("out of memory");
        return SW_EXIT_IO;
    }
    for (size_t i = 0; i < sc->n; i++) sw_cli_digest_path(sc->v[i], &F->scene_digest[i]);
    F->fingerprinted = 1;
    return SW_EXIT_OK;
}

int sw_cli_forensics_utc(const sw_cli_forensics_t *F, double t, char *buf, size_t len)
{
    return sw_cli_run_utc(&F->R.run, t, buf, len);
}

sw_plane sw_cli_forensics_plane(const sw_cli_forensics_t *F, size_t k, int *planes)
{
    sw_planes_t p;
    const int ok = F->R.e && sw_engine_planes_summary(F->R.e, k, &p) == SW_OK;
    if (planes)
        *planes = ok ? p.planes : 1;
    return ok ? p.worse : SW_PLANE_LONG;
}

int sw_cli_forensics_summary(const sw_cli_forensics_t *F, size_t k, sw_summary_t *s)
{
    return F->R.e &&
           sw_engine_summary_plane(F->R.e, k, sw_cli_forensics_plane(F, k, NULL), s) == SW_OK;
}

const sw_risk_pkg_t *sw_cli_forensics_reserve(const sw_cli_forensics_t *F, size_t k, sw_plane p)
{
    return sw_stream_risk_plane(F->R.st, k, p); /* NULL without a stream */
}

int sw_cli_forensics_factor(const sw_cli_forensics_t *F, size_t k, sw_forensics_factor_t *fx)
{
    if (F->cases && sw_forensics_factor(F->fx, k, fx) == SW_OK)
        return 1;
    memset(fx, 0, sizeof *fx); /* no factor: no plane of it either */
    return 0;
}

int sw_cli_forensics_savers(const sw_cli_forensics_t *F, size_t k, char *buf, size_t len)
{
    /* every case is judged across the truck too when the replay was: a
     * package that overturned across the truck without its cases judged
     * there has no savers known */
    sw_summary_t lat;
    if (F->R.e && sw_engine_summary_plane(F->R.e, k, SW_PLANE_LAT, &lat) == SW_OK &&
        lat.overturned && !(F->fx && sw_forensics_lateral_case(F->fx, k))) {
        snprintf(buf, len,
                 "not known: the what-if cases change the plane along the truck only, and it "
                 "overturned across the truck");
        return 0;
    }
    sw_cli_whatif_savers(buf, len, F->fx, F->cases, F->ncases, k);
    return 1;
}

const char *sw_cli_forensics_where(int planes, sw_plane p)
{
    if (planes < 2)
        return "";
    return p == SW_PLANE_LAT ? " across the truck" : " along the truck";
}

void sw_cli_forensics_planes(char *buf, size_t len, const sw_forensics_factor_t *fx,
                             const sw_safety_t *along)
{
    char lb[64], tb[64];
    sw_cli_safety_bracket(lb, sizeof lb, along);
    sw_cli_safety_bracket(tb, sizeof tb, &fx->lateral->sf);
    snprintf(buf, len, "gives out first%s (along the truck %s, across %s)",
             sw_cli_forensics_where(2, fx->first), lb, tb);
}

const sw_whatif_case_t *sw_cli_forensics_scene_case(const sw_cli_forensics_t *F, size_t k)
{
    return F->cases ? sw_forensics_scene_case(F->fx, k) : NULL;
}

/* ---- in words ---------------------------------------------------------------------- */

/* text on f, wrapped at 92 columns, each line indented by two spaces. */
static void wrapped(FILE *f, const char *text)
{
    const char *p = text;
    while (*p) {
        size_t n = strlen(p);
        if (n > 90) {
            n = 90;
            while (n > 0 && p[n] != ' ') n--;
            if (n == 0)
                n = strcspn(p, " ");
        }
        fprintf(f, "  %.*s\n", (int)n, p);
        p += n;
        while (*p == ' ') p++;
    }
}

static void answer(FILE *f, const sw_cli_forensics_t *F, size_t k)
{
    sw_summary_t s;
    const sw_whatif_case_t *C = sw_cli_forensics_scene_case(F, k);
    if (!C || !sw_cli_forensics_summary(F, k, &s))
        return;
    char desc[224];
    fprintf(f, "%s (%s): ", F->scenes[k].name, sw_cli_whatif_desc(desc, sizeof desc, C));
    const char *verdict = sw_cli_verdict(&s, &F->R.run);
    int planes;
    const sw_plane plane = sw_cli_forensics_plane(F, k, &planes);
    const char *where = sw_cli_forensics_where(planes, plane);
    char utc[64];
    if (s.overturned) {
        fprintf(f, "OVERTURNED%s at %.3f s", where, s.overturn_time);
        if (sw_cli_forensics_utc(F, s.overturn_time, utc, sizeof utc))
            fprintf(f, " (%s)", utc);
        fputc('\n', f);
    } else if (!strcmp(verdict, "incomplete")) {
        char why[256];
        sw_cli_incomplete_why(&F->R.run, why, sizeof why);
        fprintf(f,
                "INCOMPLETE: %s as far as the samples go; peak %.3f alpha, minimum margin %.3f\n",
                s.faults ? "no verdict (the model faulted)" : "upright", s.max_theta_ratio,
                s.min_margin);
        fprintf(f, "  but %s: an overturn may be hidden there\n", why);
    } else {
        fprintf(f, "%s; peak %.3f alpha%s, minimum margin %.3f\n",
                strcmp(verdict, "upright") ? "NO VERDICT (the model faulted)" : "stayed upright",
                s.max_theta_ratio, where, s.min_margin);
    }
    if (F->R.risk)
        sw_cli_print_reserve(f, sw_cli_forensics_reserve(F, k, plane));
    char b[64], sentence[640];
    sw_forensics_factor_t fx;
    const sw_safety_t *sf = sw_cli_forensics_factor(F, k, &fx) ? &fx.sf : &C->sf;
    sw_cli_safety_bracket(b, sizeof b, sf);
    sw_cli_safety_sentence(sentence, sizeof sentence, sf);
    fprintf(f, "  safety factor %s\n", b);
    if (fx.planes == 2) {
        char both[256];
        sw_cli_forensics_planes(both, sizeof both, &fx, &C->sf);
        fprintf(f, "  both horizontal axes scaled together: %s\n", both);
    }
    wrapped(f, sentence);
    if (F->fo.w.no_what_if)
        return;
    if (s.overturned) {
        char save[512];
        sw_cli_forensics_savers(F, k, save, sizeof save);
        fprintf(f, "  would have stayed upright: %s\n", save[0] ? save : "none of the cases below");
    }
    fprintf(f, "  what if (the same log%s):\n", planes == 2 ? ", both planes" : "");
    sw_cli_whatif_print_table(f, F->fx, F->cases, F->ncases, k);
}

/* What ties the answer to its inputs and to the program. */
static void fingerprint_text(FILE *f, const sw_cli_forensics_t *F)
{
    if (!F->fingerprinted)
        return;
    char v[160];
    sw_cli_version_text(v, sizeof v);
    fprintf(f, "\nfingerprint\n  log     %s: ", strcmp(F->log, "-") ? F->log : "(stdin)");
    if (F->log_digest.ok)
        fprintf(f, "%lld bytes, SHA-256 %s\n", F->log_digest.size, F->log_digest.sha256);
    else
        fprintf(f, "no digest: %s\n", F->log_digest.why);
    for (size_t i = 0; i < F->o.scenes.n; i++) {
        const sw_cli_digest_t *d = &F->scene_digest[i];
        fprintf(f, "  scene   %s: ", F->o.scenes.v[i]);
        if (d->ok)
            fprintf(f, "%lld bytes, SHA-256 %s\n", d->size, d->sha256);
        else
            fprintf(f, "no digest: %s\n", d->why);
    }
    fprintf(f, "  program swaywatch %s\n  command %s\n", v, F->command_line);
}

static void method(FILE *f, const sw_cli_forensics_t *F)
{
    fprintf(f, "\nHow this was found\n\n");
    sw_cli_print_summary(f, F->R.e, &F->R.run);
    const long runs = sw_forensics_trials(F->fx);
    const sw_search_opts_t *so = &F->fo.so;
    fprintf(
        f,
        "\nsafety factors: the recorded longitudinal acceleration, as the input gate handed it\n"
        "to the engine (%zu samples), scaled by a factor and run again from the state the\n"
        "package has where that factor can first lift it; scanned upward in steps of %g\n"
        "(wider while the package stays far from tipping), then the change from upright to\n"
        "overturned cut down to a relative width of %g; %ld runs for %zu cases.\n",
        sw_forensics_log(F->fx)->n, so->step > 0 ? so->step : 0.02, so->tol > 0 ? so->tol : 1e-3,
        runs, F->ncases);
    if (sw_forensics_log_lat(F->fx))
        fprintf(f,
                "with a lateral acceleration, every case of a package with a depth is searched\n"
                "across the truck too (the lateral acceleration scaled by the same factor, the\n"
                "plane over the case's depth, on its support): the factor is the smaller\n"
                "plane's, both axes scaled together.\n");
    for (size_t k = 0; k < F->n; k++) {
        const sw_whatif_case_t *C = sw_cli_forensics_scene_case(F, k);
        if (C && !isinf(C->sf.lift_scale))
            fprintf(f, "%s: starts to rock at %.4g times the recorded acceleration\n",
                    F->scenes[k].name, C->sf.lift_scale);
    }
    if (!F->fo.w.no_what_if) {
        fprintf(f,
                "catalogue supports (docs/forensics.md; frequencies with the package on "
                "them):\n");
        size_t ns;
        const sw_support_t *S = sw_whatif_supports(&ns);
        for (size_t i = 0; i < ns; i++)
            fprintf(f, "  %-22s %5.3g Hz, zeta %.2g: %s\n", S[i].name, S[i].hz, S[i].zeta,
                    S[i].stands_for);
    }
    fingerprint_text(f, F);
}

void sw_cli_forensics_text(FILE *f, const sw_cli_forensics_t *F)
{
    for (size_t k = 0; k < F->n; k++) {
        if (k)
            fputc('\n', f);
        answer(f, F, k);
    }
    if (!F->o.quiet)
        method(f, F);
}

/* ---- JSON -------------------------------------------------------------------------- */

void sw_cli_forensics_json_package(json_t *o, const sw_cli_forensics_t *F, size_t k)
{
    sw_summary_t s;
    const sw_whatif_case_t *C = sw_cli_forensics_scene_case(F, k);
    sw_cli_rec_text(o, "name", F->scenes[k].name);
    if (!C || !sw_cli_forensics_summary(F, k, &s)) {
        sw_cli_rec_null(o, "verdict");
        return;
    }
    int planes;
    const sw_plane plane = sw_cli_forensics_plane(F, k, &planes);
    sw_cli_rec_text(o, "model", sw_model_name(s.model));
    sw_planes_t P;
    if (planes == 2 && sw_engine_planes_summary(F->R.e, k, &P) == SW_OK) {
        /* the verdict's plane, whose are the fields that follow; both
         * planes lifted at once marked as replay marks them */
        sw_cli_rec_text(o, "plane", sw_plane_name(plane));
        sw_cli_rec_bool(o, "both_planes_rocking", P.both_rocking);
        sw_cli_rec_num(o, "both_planes_from", P.both_from);
        sw_cli_rec_num(o, "both_planes_to", P.both_to);
        sw_cli_rec_num(o, "both_planes_time", P.both_rocking ? P.both_time : NAN);
    }
    sw_cli_rec_text(o, "verdict", sw_cli_verdict(&s, &F->R.run));
    sw_cli_rec_text(o, "seen", sw_cli_verdict_seen(&s));
    sw_cli_json_incomplete(o, &s, &F->R.run);
    sw_cli_rec_bool(o, "overturned", s.overturned);
    sw_cli_rec_num(o, "overturn_time", s.overturn_time);
    sw_cli_rec_num(o, "max_theta_ratio", s.max_theta_ratio);
    sw_cli_rec_num(o, "min_margin", s.min_margin);
    const sw_risk_pkg_t *rp = sw_cli_forensics_reserve(F, k, plane);
    const int rv = rp && rp->evaluations > 0;
    sw_cli_rec_num(o, "min_reserve_g", rv ? rp->min_reserve_g : NAN);
    sw_cli_rec_num(o, "min_reserve_time", rv ? rp->min_reserve_time : NAN);
    sw_cli_rec_num(o, "rest_reserve_g", rv ? rp->rest_reserve_g : NAN);
    /* the decisive moments on the log's clock (null: no dates, or none) */
    const struct {
        const char *key;
        double t;
    } when[] = {{"uplift", s.uplift_time},
                {"tip", s.tip_time},
                {"overturn", s.overturn_time},
                {"min_reserve", rv ? rp->min_reserve_time : NAN}};
    json_t *u = sw_cli_rec_obj(o, "utc");
    for (size_t i = 0; i < sizeof when / sizeof when[0]; i++) {
        char utc[64];
        const int have = sw_cli_forensics_utc(F, when[i].t, utc, sizeof utc);
        sw_cli_rec_text(u, when[i].key, have ? utc : NULL);
    }
    sw_forensics_factor_t fx = {.planes = 1, .sf = C->sf}; /* the scene case's, if none */
    sw_cli_forensics_factor(F, k, &fx);
    sw_cli_json_factor(o, C, &fx); /* with two planes, both axes scaled together */
    char why[256];
    if (s.overturned && !sw_cli_forensics_savers(F, k, why, sizeof why)) {
        sw_cli_rec_null(o, "saved_by"); /* not known: why */
        sw_cli_rec_text(o, "saved_by_note", why);
    }
    json_t *saved = json_object_get(o, "saved_by") ? NULL : sw_cli_rec_arr(o, "saved_by");
    for (size_t i = 0; saved && i < F->ncases && s.overturned; i++) {
        sw_forensics_verdict_t v;
        if (F->cases[i].pkg == k && sw_forensics_case_verdict(F->fx, i, &v) == SW_OK && v.saves)
            sw_cli_rec_text(saved, NULL, F->cases[i].name);
    }
    json_t *cases = sw_cli_rec_arr(o, "what_if");
    for (size_t i = 0; i < F->ncases; i++)
        if (F->cases[i].pkg == k)
            sw_cli_whatif_json_case(sw_cli_rec_obj(cases, NULL), F->fx, F->cases, i);
}

/* A file's digest as members of o. */
static void json_digest(json_t *o, const sw_cli_digest_t *d)
{
    sw_cli_rec_text(o, "sha256", d && d->ok ? d->sha256 : NULL);
    sw_cli_rec_put(o, "size", d && d->ok ? json_integer(d->size) : json_null());
    sw_cli_rec_text(o, "no_digest", d && !d->ok ? d->why : NULL);
}

/* What the reading did not use: the refusals by reason, the gaps. */
static void json_unused(json_t *o, const sw_cli_unused_t *u, double t_origin)
{
    json_t *j = sw_cli_rec_obj(o, "unused");
    sw_cli_rec_int(j, "rejected", u->rejected);
    json_t *by = sw_cli_rec_arr(j, "by_reason");
    for (size_t i = 0; i < u->nreason; i++) {
        const sw_cli_unused_reason_t *r = &u->reason[i];
        json_t *w = sw_cli_rec_obj(by, NULL);
        sw_cli_rec_text(w, "reason", r->reason);
        sw_cli_rec_int(w, "count", r->count);
        if (u->places) {
            json_t *lines = sw_cli_rec_arr(w, "first_lines");
            for (int k = 0; k < r->nwhere; k++) sw_cli_rec_int(lines, NULL, r->where[k]);
        } else {
            sw_cli_rec_null(w, "first_lines");
        }
        sw_cli_rec_text(w, "first_message", u->places ? r->first : NULL);
    }
    sw_cli_rec_int(j, "other_reasons", u->other);
    sw_cli_rec_int(j, "stream_events", u->events);
    if (!u->listed) {
        sw_cli_rec_null(j, "listed");
        return;
    }
    json_t *listed = sw_cli_rec_arr(j, "listed");
    for (size_t i = 0; i < u->ngap; i++) {
        const sw_cli_unused_gap_t *g = &u->gap[i];
        json_t *w = sw_cli_rec_obj(listed, NULL);
        sw_cli_rec_text(w, "kind", sw_gate_event_name(g->kind));
        sw_cli_rec_num(w, "time", g->t - t_origin);
        sw_cli_rec_num(w, "span", g->span);
        sw_cli_rec_int(w, "line", g->where);
        sw_cli_rec_bool(w, "incomplete", g->incomplete);
        sw_cli_rec_bool(w, "restarted", g->restarted);
        sw_cli_rec_bool(w, "bridged", g->bridged);
    }
}

int sw_cli_forensics_json(FILE *f, const sw_cli_forensics_t *F)
{
    const sw_cli_run_t *run = &F->R.run;
    json_t *o = sw_cli_rec_new();
    sw_cli_rec_text(o, "swaywatch", SW_VERSION);
    char v[160];
    sw_cli_version_text(v, sizeof v);
    json_t *b = sw_cli_rec_obj(o, "build");
    sw_cli_rec_text(b, "version", SW_VERSION);
    sw_cli_rec_text(b, "commit", sw_cli_commit()[0] ? sw_cli_commit() : NULL);
    sw_cli_rec_bool(b, "modified", sw_cli_commit_modified());
    sw_cli_rec_text(b, "text", v);
    json_t *cmd = sw_cli_rec_arr(o, "command");
    sw_cli_rec_text(cmd, NULL, "swaywatch");
    for (int i = 0; i < F->argc; i++) sw_cli_rec_text(cmd, NULL, F->argv[i]);
    sw_cli_rec_text(o, "command_line", F->command_line);
    json_t *log = sw_cli_rec_obj(o, "log");
    sw_cli_rec_text(log, "name", F->log);
    sw_cli_rec_text(log, "source", F->R.src ? F->R.src->name : "");
    json_digest(log, &F->log_digest);
    char iso[64];
    sw_cli_iso_seconds(iso, sizeof iso, run->abs_start);
    sw_cli_rec_text(log, "start_utc", run->absolute ? iso : NULL);
    sw_cli_iso_seconds(iso, sizeof iso, run->abs_end);
    sw_cli_rec_text(log, "end_utc", run->absolute ? iso : NULL);
    sw_cli_rec_text(log, "dates_from", run->absolute ? run->abs_from : NULL);
    sw_cli_rec_int(log, "samples_read", run->samples_read);
    sw_cli_rec_int(log, "samples_rejected", run->samples_rejected);
    sw_cli_rec_int(log, "samples_used", (long long)sw_forensics_log(F->fx)->n);
    if (run->have_facts) /* the summary's "input" */
        sw_cli_json_facts(log, "facts", run);
    else
        sw_cli_rec_null(log, "facts");
    json_unused(log, &run->unused, run->have_facts ? run->facts.t_origin : 0.0);
    json_t *sc = sw_cli_rec_arr(o, "scenes");
    for (size_t i = 0; i < F->o.scenes.n; i++) {
        json_t *w = sw_cli_rec_obj(sc, NULL);
        sw_cli_rec_text(w, "path", F->o.scenes.v[i]);
        json_digest(w, F->scene_digest ? &F->scene_digest[i] : NULL);
    }
    sw_cli_json_summary(sw_cli_rec_obj(o, "replay"), F->R.e, run);
    json_t *pk = sw_cli_rec_arr(o, "packages");
    for (size_t k = 0; k < F->n; k++) sw_cli_forensics_json_package(sw_cli_rec_obj(pk, NULL), F, k);
    if (sw_cli_rec_write(f, o, SW_CLI_REC_DOC) == 0)
        return SW_EXIT_OK;
    sw_cli_error("the JSON report: out of memory");
    return SW_EXIT_IO;
}
