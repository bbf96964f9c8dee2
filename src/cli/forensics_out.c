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

void sw_cli_forensics_free(sw_cli_forensics_t *F)
{
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
    if (F->R.lf.in)
        sw_cli_digest_fd(fileno(F->R.lf.in), &F->log_digest);
    else
        snprintf(F->log_digest.why, sizeof F->log_digest.why, "not open");
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

int sw_cli_forensics_summary(const sw_cli_forensics_t *F, size_t k, sw_summary_t *s)
{
    return F->R.e && sw_engine_summary(F->R.e, k, s) == SW_OK;
}

const sw_cli_case_t *sw_cli_forensics_scene_case(const sw_cli_forensics_t *F, size_t k)
{
    for (size_t i = 0; i < F->ncases; i++)
        if (F->cases[i].pkg == k && F->cases[i].is_scene)
            return &F->cases[i];
    return NULL;
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
    const sw_cli_case_t *C = sw_cli_forensics_scene_case(F, k);
    if (!C || !sw_cli_forensics_summary(F, k, &s))
        return;
    fprintf(f, "%s (%s): ", F->scenes[k].name, C->desc);
    const char *verdict = sw_cli_verdict(&s, &F->R.run);
    char utc[64];
    if (s.overturned) {
        fprintf(f, "OVERTURNED at %.3f s", s.overturn_time);
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
        fprintf(f, "%s; peak %.3f alpha, minimum margin %.3f\n",
                strcmp(verdict, "upright") ? "NO VERDICT (the model faulted)" : "stayed upright",
                s.max_theta_ratio, s.min_margin);
    }
    if (F->R.risk)
        sw_cli_print_reserve(f, sw_risk_pkg(F->R.risk, k));
    char b[64], sentence[640];
    sw_cli_safety_bracket(b, sizeof b, &C->sf);
    sw_cli_safety_sentence(sentence, sizeof sentence, &C->sf);
    fprintf(f, "  safety factor %s\n", b);
    wrapped(f, sentence);
    if (F->fo.w.no_what_if)
        return;
    if (s.overturned) {
        char save[512];
        sw_cli_whatif_savers(save, sizeof save, F->cases, F->ncases, k);
        fprintf(f, "  would have stayed upright: %s\n", save[0] ? save : "none of the cases below");
    }
    fprintf(f, "  what if (the same log):\n");
    sw_cli_whatif_print_table(f, F->cases, F->ncases, k);
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
    long runs = 0;
    for (size_t i = 0; i < F->ncases; i++)
        runs += F->cases[i].available ? F->cases[i].sf.trials : 0;
    const sw_search_opts_t *so = &F->fo.so;
    fprintf(
        f,
        "\nsafety factors: the recorded longitudinal acceleration, as the input gate handed it\n"
        "to the engine (%zu samples), scaled by a factor and run again from the state the\n"
        "package has where that factor can first lift it; scanned upward in steps of %g\n"
        "(wider while the package stays far from tipping), then the change from upright to\n"
        "overturned cut down to a relative width of %g; %ld runs for %zu cases.\n",
        F->L.n, so->step > 0 ? so->step : 0.02, so->tol > 0 ? so->tol : 1e-3, runs, F->ncases);
    for (size_t k = 0; k < F->n; k++) {
        const sw_cli_case_t *C = sw_cli_forensics_scene_case(F, k);
        if (C && !isinf(C->sf.lift_scale))
            fprintf(f, "%s: starts to rock at %.4g times the recorded acceleration\n",
                    F->scenes[k].name, C->sf.lift_scale);
    }
    if (!F->fo.w.no_what_if) {
        fprintf(f,
                "catalogue supports (docs/forensics.md; frequencies with the package on "
                "them):\n");
        for (size_t i = 0; i < sw_cli_nsupports; i++)
            fprintf(f, "  %-22s %5.3g Hz, zeta %.2g: %s\n", sw_cli_supports[i].name,
                    sw_cli_supports[i].hz, sw_cli_supports[i].zeta, sw_cli_supports[i].stands_for);
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

void sw_cli_forensics_json_package(FILE *f, const sw_cli_forensics_t *F, size_t k)
{
    sw_summary_t s;
    const sw_cli_case_t *C = sw_cli_forensics_scene_case(F, k);
    fprintf(f, "\"name\": ");
    sw_cli_json_string(f, F->scenes[k].name);
    if (!C || !sw_cli_forensics_summary(F, k, &s)) {
        fprintf(f, ", \"verdict\": null");
        return;
    }
    fprintf(f, ", \"model\": ");
    sw_cli_json_string(f, sw_model_name(s.model));
    fprintf(f, ", \"verdict\": ");
    sw_cli_json_string(f, sw_cli_verdict(&s, &F->R.run));
    fprintf(f, ", \"seen\": ");
    sw_cli_json_string(f, sw_cli_verdict_seen(&s));
    fprintf(f, ", ");
    sw_cli_json_incomplete(f, &s, &F->R.run);
    fprintf(f, ", \"overturned\": %s, \"overturn_time\": ", s.overturned ? "true" : "false");
    sw_cli_json_num(f, s.overturn_time);
    fprintf(f, ", \"max_theta_ratio\": ");
    sw_cli_json_num(f, s.max_theta_ratio);
    fprintf(f, ", \"min_margin\": ");
    sw_cli_json_num(f, s.min_margin);
    const sw_risk_pkg_t *rp = F->R.risk ? sw_risk_pkg(F->R.risk, k) : NULL;
    const int rv = rp && rp->evaluations > 0;
    fprintf(f, ", \"min_reserve_g\": ");
    sw_cli_json_num(f, rv ? rp->min_reserve_g : NAN);
    fprintf(f, ", \"min_reserve_time\": ");
    sw_cli_json_num(f, rv ? rp->min_reserve_time : NAN);
    fprintf(f, ", \"rest_reserve_g\": ");
    sw_cli_json_num(f, rv ? rp->rest_reserve_g : NAN);
    /* the decisive moments on the log's clock (null: no dates, or none) */
    const struct {
        const char *key;
        double t;
    } when[] = {{"uplift", s.uplift_time},
                {"tip", s.tip_time},
                {"overturn", s.overturn_time},
                {"min_reserve", rv ? rp->min_reserve_time : NAN}};
    fprintf(f, ",\n  \"utc\": {");
    for (size_t i = 0; i < sizeof when / sizeof when[0]; i++) {
        char utc[64];
        fprintf(f, "%s\"%s\": ", i ? ", " : "", when[i].key);
        if (sw_cli_forensics_utc(F, when[i].t, utc, sizeof utc))
            sw_cli_json_string(f, utc);
        else
            fputs("null", f);
    }
    fputc('}', f);
    fprintf(f, ",\n  \"safety_factor\": ");
    sw_cli_whatif_json_safety(f, C);
    fprintf(f, ",\n  \"saved_by\": [");
    int first = 1;
    for (size_t i = 0; i < F->ncases && s.overturned; i++) {
        const sw_cli_case_t *W = &F->cases[i];
        if (W->pkg != k || W->is_scene || !W->available || W->sf.overturned)
            continue;
        fprintf(f, "%s", first ? "" : ", ");
        sw_cli_json_string(f, W->name);
        first = 0;
    }
    fprintf(f, "],\n  \"what_if\": [");
    first = 1;
    for (size_t i = 0; i < F->ncases; i++) {
        if (F->cases[i].pkg != k)
            continue;
        fprintf(f, "%s\n   ", first ? "" : ",");
        sw_cli_whatif_json_case(f, &F->cases[i]);
        first = 0;
    }
    fprintf(f, "]");
}

/* A file's digest as JSON members (no braces). */
static void json_digest(FILE *f, const sw_cli_digest_t *d)
{
    fputs("\"sha256\": ", f);
    if (d->ok) {
        sw_cli_json_string(f, d->sha256);
        fprintf(f, ", \"size\": %lld, \"no_digest\": null", d->size);
    } else {
        fputs("null, \"size\": null, \"no_digest\": ", f);
        sw_cli_json_string(f, d->why);
    }
}

/* What the reading did not use: the refusals by reason, the gaps. */
static void json_unused(FILE *f, const sw_cli_unused_t *u, double t_origin)
{
    fprintf(f, "{\"rejected\": %ld, \"by_reason\": [", u->rejected);
    for (size_t i = 0; i < u->nreason; i++) {
        const sw_cli_unused_reason_t *r = &u->reason[i];
        fprintf(f, "%s{\"reason\": ", i ? ", " : "");
        sw_cli_json_string(f, r->reason);
        fprintf(f, ", \"count\": %ld, \"first_lines\": ", r->count);
        if (u->places) {
            fputc('[', f);
            for (int k = 0; k < r->nwhere; k++) fprintf(f, "%s%ld", k ? ", " : "", r->where[k]);
            fputs("], \"first_message\": ", f);
            sw_cli_json_string(f, r->first);
        } else {
            fputs("null, \"first_message\": null", f);
        }
        fputc('}', f);
    }
    fprintf(f, "], \"other_reasons\": %ld,\n   \"stream_events\": %ld, \"listed\": ", u->other,
            u->events);
    if (!u->listed) {
        fputs("null}", f);
        return;
    }
    fputc('[', f);
    for (size_t i = 0; i < u->ngap; i++) {
        const sw_cli_unused_gap_t *g = &u->gap[i];
        fprintf(f, "%s{\"kind\": ", i ? ",\n    " : "\n    ");
        sw_cli_json_string(f, sw_gate_event_name(g->kind));
        fprintf(f, ", \"time\": ");
        sw_cli_json_num(f, g->t - t_origin);
        fprintf(f, ", \"span\": ");
        sw_cli_json_num(f, g->span);
        fprintf(f, ", \"line\": %ld, \"incomplete\": %s, \"restarted\": %s, \"bridged\": %s}",
                g->where, g->incomplete ? "true" : "false", g->restarted ? "true" : "false",
                g->bridged ? "true" : "false");
    }
    fputs("]}", f);
}

void sw_cli_forensics_json(FILE *f, const sw_cli_forensics_t *F)
{
    const sw_cli_run_t *run = &F->R.run;
    fprintf(f, "{\n\"swaywatch\": ");
    sw_cli_json_string(f, SW_VERSION);
    char v[160];
    sw_cli_version_text(v, sizeof v);
    fprintf(f, ",\n\"build\": {\"version\": ");
    sw_cli_json_string(f, SW_VERSION);
    fprintf(f, ", \"commit\": ");
    if (sw_cli_commit()[0])
        sw_cli_json_string(f, sw_cli_commit());
    else
        fputs("null", f);
    fprintf(f, ", \"modified\": %s, \"text\": ", sw_cli_commit_modified() ? "true" : "false");
    sw_cli_json_string(f, v);
    fprintf(f, "},\n\"command\": [\"swaywatch\"");
    for (int i = 0; i < F->argc; i++) {
        fprintf(f, ", ");
        sw_cli_json_string(f, F->argv[i]);
    }
    fprintf(f, "],\n\"command_line\": ");
    if (F->command_line)
        sw_cli_json_string(f, F->command_line);
    else
        fputs("null", f);
    fprintf(f, ",\n\"log\": {\"name\": ");
    sw_cli_json_string(f, F->log);
    fprintf(f, ", \"source\": ");
    sw_cli_json_string(f, F->R.src ? F->R.src->name : "");
    fprintf(f, ", ");
    json_digest(f, &F->log_digest);
    fprintf(f, ",\n  \"start_utc\": ");
    char iso[64];
    if (run->absolute) {
        sw_cli_iso_seconds(iso, sizeof iso, run->abs_start);
        sw_cli_json_string(f, iso);
        fprintf(f, ", \"end_utc\": ");
        sw_cli_iso_seconds(iso, sizeof iso, run->abs_end);
        sw_cli_json_string(f, iso);
        fprintf(f, ", \"dates_from\": ");
        sw_cli_json_string(f, run->abs_from);
    } else {
        fputs("null, \"end_utc\": null, \"dates_from\": null", f);
    }
    fprintf(f,
            ",\n  \"samples_read\": %ld, \"samples_rejected\": %ld, \"samples_used\": %zu, "
            "\"facts\": ",
            run->samples_read, run->samples_rejected, F->L.n);
    if (run->have_facts)
        sw_cli_json_facts(f, run, " ");
    else
        fputs("null", f);
    fprintf(f, ",\n  \"unused\": ");
    json_unused(f, &run->unused, run->have_facts ? run->facts.t_origin : 0.0);
    fprintf(f, "},\n\"scenes\": [");
    for (size_t i = 0; i < F->o.scenes.n; i++) {
        fprintf(f, "%s{\"path\": ", i ? ", " : "");
        sw_cli_json_string(f, F->o.scenes.v[i]);
        fprintf(f, ", ");
        if (F->scene_digest)
            json_digest(f, &F->scene_digest[i]);
        else
            fputs("\"sha256\": null, \"size\": null, \"no_digest\": null", f);
        fputc('}', f);
    }
    fprintf(f, "],\n\"replay\": ");
    sw_cli_print_json(f, F->R.e, run);
    fprintf(f, ",\n\"packages\": [");
    for (size_t k = 0; k < F->n; k++) {
        fprintf(f, "%s\n {", k ? "," : "");
        sw_cli_forensics_json_package(f, F, k);
        fputc('}', f);
    }
    fprintf(f, "\n]\n}\n");
}
