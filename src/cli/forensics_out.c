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
    F->ev = NULL;
    F->impacts_seen = NULL;
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
    if (s.overturned) {
        fprintf(f, "OVERTURNED at %.3f s\n", s.overturn_time);
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

void sw_cli_forensics_json(FILE *f, const sw_cli_forensics_t *F)
{
    fprintf(f, "{\n\"swaywatch\": ");
    sw_cli_json_string(f, SW_VERSION);
    fprintf(f, ",\n\"command\": [\"swaywatch\"");
    for (int i = 0; i < F->argc; i++) {
        fprintf(f, ", ");
        sw_cli_json_string(f, F->argv[i]);
    }
    fprintf(f, "],\n\"log\": {\"name\": ");
    sw_cli_json_string(f, F->log);
    fprintf(f, ", \"source\": ");
    sw_cli_json_string(f, F->R.src ? F->R.src->name : "");
    fprintf(f,
            ", \"samples_read\": %ld, \"samples_rejected\": %ld, \"samples_used\": %zu, "
            "\"facts\": ",
            F->R.run.samples_read, F->R.run.samples_rejected, F->L.n);
    if (F->R.run.have_facts)
        sw_cli_json_facts(f, &F->R.run, " ");
    else
        fputs("null", f);
    fprintf(f, "},\n\"replay\": ");
    sw_cli_print_json(f, F->R.e, &F->R.run);
    fprintf(f, ",\n\"packages\": [");
    for (size_t k = 0; k < F->n; k++) {
        fprintf(f, "%s\n {", k ? "," : "");
        sw_cli_forensics_json_package(f, F, k);
        fputc('}', f);
    }
    fprintf(f, "\n]\n}\n");
}
