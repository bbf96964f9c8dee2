/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gate.c - the input gate (gate.h): every source's samples pass here on
 * their way to the engine.  The API: a gate made once (its look-ahead
 * allocated here, nothing later), each sample checked for its values and
 * handed to the look-ahead (no receive time: a log) or to the chains
 * (receive times: live, lcm-logger files), the facts, and the
 * plausibility check of a whole log.  gate_int.h maps the other files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gate_int.h"

static const char *const reject_names[SW_GATE_NREJ] = {
    "nonfinite", "implausible", "time", "skew", "duplicate", "late", "jump", "engine", "contested"};

const char *sw_gate_reject_name(sw_gate_reject r)
{
    return (unsigned)r < SW_GATE_NREJ ? reject_names[r] : "unknown";
}

const char *sw_gate_event_name(sw_gate_event_kind k)
{
    switch (k) {
        case SW_GATE_EV_GAP: return "gap";
        case SW_GATE_EV_CLOCK_STEP: return "clock step";
        case SW_GATE_EV_RESTART: return "restart";
        case SW_GATE_EV_SEQ_RESTART: return "seq restart";
        case SW_GATE_EV_RECONSTRUCT: return "reconstructed";
        case SW_GATE_EV_CONTESTED: return "contested";
        case SW_GATE_EV_UNCONTESTED: return "uncontested";
    }
    return "unknown";
}

long sw_gate_rejected(const sw_gate_facts_t *f)
{
    long n = 0;
    for (int r = 0; r < SW_GATE_NREJ; r++) n += f->rejected[r];
    return n;
}

static void clear(sw_gate_t *g)
{
    sw_engine_t *e = g->e;
    sw_gate_opts_t o = g->o;
    sw_sample_t *ahead = g->ahead;
    const int window = g->window;
    memset(g, 0, sizeof *g);
    g->e = e;
    g->o = o;
    g->ahead = ahead;
    g->window = window;
    g->tm.spacing = NAN;
    g->rx_prev = g->burst_from = g->burst_until = g->burst_env = NAN;
    g->seq.outlier_at = -1;
    g->rv.switched = -1;
    g->f.t_first = g->f.t_last = g->f.first_incomplete = NAN;
    g->f.dt_min = g->f.dt_median = g->f.dt_max = g->f.rate = NAN;
    g->f.spacing = NAN;
    g->f.gap_threshold = INFINITY;
    g->f.min_a = g->f.max_a = NAN;
    g->f.lateral = g->o.lateral != 0;
    g->f.lat.min = g->f.lat.max = NAN;
}

sw_gate_t *sw_gate_create(sw_engine_t *e, const sw_gate_opts_t *o, char *msg, size_t msglen)
{
    static const sw_gate_opts_t defaults;
    if (msg && msglen)
        msg[0] = '\0';
    if (!o)
        o = &defaults;
    const char *bad = NULL;
    if (!e)
        bad = "no engine";
    else if (!(o->gap >= 0.0) || !isfinite(o->gap))
        bad = "gap must be >= 0";
    else if (!(o->max_bridge >= 0.0) || !isfinite(o->max_bridge))
        bad = "max_bridge must be >= 0";
    else if (!(o->max_accel >= 0.0) || !isfinite(o->max_accel))
        bad = "max_accel must be >= 0";
    else if (isnan(o->jump) || isinf(o->jump))
        bad = "jump must be finite";
    else if (!(o->max_skew >= 0.0) || !isfinite(o->max_skew))
        bad = "max_skew must be >= 0";
    else if (o->confirm < 0 || o->confirm > SW_GATE_CONFIRM_MAX)
        bad = "confirm must be 0..8";
    else if (o->gap_policy != SW_GAP_BRIDGE && o->gap_policy != SW_GAP_RESTART)
        bad = "unknown gap policy";
    else if (o->lookahead != 0 && (o->lookahead < 2 || o->lookahead > SW_GATE_LOOKAHEAD))
        bad = "lookahead must be 2..64";
    if (bad) {
        if (msg && msglen)
            snprintf(msg, msglen, "%s", bad);
        return NULL;
    }
    sw_gate_t *g = calloc(1, sizeof *g);
    const int window = o->lookahead ? o->lookahead : SW_GATE_LOOKAHEAD;
    sw_sample_t *ahead = calloc((size_t)window, sizeof *ahead);
    if (!g || !ahead) {
        free(g);
        free(ahead);
        if (msg && msglen)
            snprintf(msg, msglen, "out of memory");
        return NULL;
    }
    g->e = e;
    g->o = *o;
    if (g->o.max_bridge == 0.0)
        g->o.max_bridge = 10.0;
    if (g->o.max_accel == 0.0)
        g->o.max_accel = 50.0 * SW_G0;
    if (g->o.confirm == 0)
        g->o.confirm = 3;
    g->ahead = ahead;
    g->window = window;
    clear(g);
    return g;
}

void sw_gate_destroy(sw_gate_t *g)
{
    if (!g)
        return;
    free(g->ahead);
    free(g);
}

void sw_gate_reset(sw_gate_t *g)
{
    if (g)
        clear(g);
}

double sw_gate_gap_threshold(const sw_gate_t *g)
{
    /* cheap (a monitor asks after every message): the long-run pace and the
     * median of the last eight, not the sorted ring of the last 64 */
    return !g                                          ? INFINITY
           : isnan(g->last.rx) || g->tm.seen >= WARM_N ? gate_threshold_of(g, gate_spacing(g))
                                                       : INFINITY;
}

int sw_gate_contested(const sw_gate_t *g)
{
    return g ? g->rv.contested : 0;
}

int sw_gate_push(sw_gate_t *g, const sw_sample_t *s)
{
    if (!g || !s)
        return SW_EINVAL;
    g->f.received++;
    char text[160];
    if (!isfinite(s->t) || !isfinite(s->a_g) || !isfinite(s->a_z) ||
        (g->o.lateral && !isfinite(s->a_y)))
        return gate_refuse(g, s, SW_GATE_REJ_NONFINITE, "a value is not finite");
    double amax = s->a_max; /* m/s^2 */
    if (isnan(amax))
        amax = fmax(fmax(fabs(s->a_g), fabs(s->a_z)), g->o.lateral ? fabs(s->a_y) : 0.0);
    if (!(amax <= g->o.max_accel)) {
        snprintf(text, sizeof text, "|a| = %.6g m/s^2 (%.4g g) beyond the limit %.6g m/s^2", amax,
                 amax / SW_G0, g->o.max_accel);
        return gate_refuse(g, s, SW_GATE_REJ_IMPLAUSIBLE, text);
    }
    if (!(fabs(s->t) < TIME_MAX)) {
        snprintf(text, sizeof text,
                 "time %.15g s: its steps are coarser than 2e-6 s (a time unit mistake?)", s->t);
        return gate_refuse(g, s, SW_GATE_REJ_TIME, text);
    }
    if (g->o.max_skew > 0.0 && !isnan(s->wall) && !(fabs(s->t - s->wall) <= g->o.max_skew)) {
        snprintf(text, sizeof text, "time %.15g s is %.6g s from the wall clock", s->t,
                 s->t - s->wall);
        return gate_refuse(g, s, SW_GATE_REJ_SKEW, text);
    }
    if (isnan(s->rx))
        return gate_ahead_push(g, s);
    gate_ahead_drain(g); /* a source that gains receive times: what waits is decided */
    return gate_live_push(g, s);
}

int sw_gate_flush(sw_gate_t *g)
{
    if (!g)
        return SW_EINVAL;
    g->flushing = 1;
    gate_ahead_drain(g);
    gate_judge_deferred(g);
    if (!g->have_last && g->nchain) {
        /* a stream too short to confirm anything: its longest stretch,
         * which nothing contradicts, is the timeline */
        int best = 0;
        for (int k = 1; k < g->nchain; k++)
            if (g->chain[k].n > g->chain[best].n)
                best = k;
        gate_confirm(g, best);
    }
    gate_drop_chains(g);
    g->flushing = 0;
    return SW_OK;
}

void sw_gate_facts(const sw_gate_t *g, sw_gate_facts_t *f)
{
    *f = g->f;
    f->held = g->nahead;
    for (int k = 0; k < g->nchain; k++) f->held += g->chain[k].n;
    f->mean_z = f->accepted ? g->sum_z / (double)f->accepted : 0.0;
    f->mean_abs_a = f->accepted ? g->sum_abs_a / (double)f->accepted : 0.0;
    f->lat.mean_abs = f->accepted && f->lateral ? g->sum_abs_y / (double)f->accepted : 0.0;
    const long n = g->hist_n;
    long half = 0;
    for (int b = g->hist_lo; b <= g->hist_hi && n; b++) {
        half += g->hist[b];
        if (2 * half >= n) {
            f->dt_median = g->hist_sum[b] / (double)g->hist[b]; /* the bin's mean */
            break;
        }
    }
    /* spread stamps alternate (half a unit, a unit): their median says
     * nothing of the logger's pace, their mean does */
    if (f->reconstructed > 0 && f->accepted > 1 && f->duration > 0.0)
        f->dt_median = f->duration / (double)(f->accepted - 1);
    f->rate = f->dt_median > 0.0 ? 1.0 / f->dt_median : NAN;
    /* cheap: a monitor reads the facts after every message */
    f->spacing = gate_spacing(g);
    f->gap_threshold = sw_gate_gap_threshold(g);
}

long sw_gate_accepted(const sw_gate_t *g)
{
    return g ? g->f.accepted : 0;
}

double sw_gate_source_time(const sw_gate_t *g, double t_engine)
{
    return t_engine - g->offset;
}

/* One horizontal axis of a log (lateral: 0 the longitudinal, 1 the
 * lateral): no larger than a truck bed sees, and, over a long log, not
 * beyond 0.5 g most of the time nor never varying.  1 with why filled
 * when it is implausible. */
static int check_axis(const sw_gate_facts_t *f, const sw_gate_axis_t *x, int lateral,
                      double max_peak, double min_still, char *why, size_t whylen)
{
    const char *const name = lateral ? "lateral" : "longitudinal";
    /* the options that choose a channel are the source's: the caller names them */
    const char *const col = lateral ? "the column or axis of the lateral acceleration"
                                    : "the column or axis of the longitudinal acceleration";
    if (x->peak > max_peak) {
        snprintf(why, whylen,
                 "the largest %sacceleration is %.4g m/s^2 (%.3g g), beyond what a truck bed "
                 "sees (%.3g g): an acceleration in g read as m/s^2 the other way round, or "
                 "a wrong column?",
                 lateral ? "lateral " : "", x->peak, x->peak / SW_G0, max_peak / SW_G0);
        return 1;
    }
    /* A truck brakes at 0.5 g for seconds, never for a minute, nor takes a
     * curve that long: a channel beyond it most of a long log, or one that
     * never moves, is no horizontal acceleration (gravity on a vertical
     * axis, a GPS, speed or angle column). */
    if (!(f->duration >= min_still && f->accepted >= 100))
        return 0;
    const int high = 2 * x->above_half_g > f->accepted;
    const int still = x->min == x->max;
    if (high)
        snprintf(why, whylen,
                 "the %s channel looks like gravity or not an acceleration: "
                 "%.0f %% of %.3g min beyond 0.5 g (mean |a| %.3g g), which no truck "
                 "%s for that long; choose %s",
                 name, 100.0 * (double)x->above_half_g / (double)f->accepted, f->duration / 60.0,
                 x->mean_abs / SW_G0, lateral ? "takes a curve" : "brakes or speeds up", col);
    else if (still)
        snprintf(why, whylen,
                 "the %s channel looks like gravity or not an acceleration: "
                 "it reads %.6g m/s^2 for all %.3g min and never varies; choose %s",
                 name, x->min, f->duration / 60.0, col);
    return high || still;
}

int sw_gate_check(const sw_gate_facts_t *f, const sw_gate_limits_t *lim, char *why, size_t whylen)
{
    static const sw_gate_limits_t defaults;
    if (!lim)
        lim = &defaults;
    const double max_rej = lim->max_rejected > 0.0 ? lim->max_rejected : 0.01;
    const double min_rate = lim->min_rate > 0.0 ? lim->min_rate : 2.0;
    const double warn_rate = lim->warn_rate > 0.0 ? lim->warn_rate : 20.0;
    const double max_dur = lim->max_duration > 0.0 ? lim->max_duration : 366.0 * 86400.0;
    const double max_peak = lim->max_peak > 0.0 ? lim->max_peak : 25.0 * SW_G0;
    const double min_still = lim->min_still > 0.0 ? lim->min_still : 60.0;
    const long rej = sw_gate_rejected(f) + f->upstream_rejected;
    const long seen = f->received + f->upstream_rejected;
    if (why && whylen)
        why[0] = '\0';
    if (seen > 0 && (double)rej > max_rej * (double)seen) {
        snprintf(why, whylen,
                 "%ld of %ld samples (%.1f %%) were refused, more than %.3g %%: a wrong "
                 "column, unit or delimiter is the usual cause",
                 rej, seen, 100.0 * (double)rej / (double)seen, 100.0 * max_rej);
        return SW_GATE_REFUSE;
    }
    if (f->accepted < 2) {
        snprintf(why, whylen, "%ld usable samples: nothing to judge", f->accepted);
        return SW_GATE_REFUSE;
    }
    if (f->rate < min_rate) {
        snprintf(why, whylen,
                 "the samples are %.4g s apart (%.3g Hz): no vehicle log is that slow; a "
                 "time column in ms or us read as seconds?",
                 f->dt_median, f->rate);
        return SW_GATE_REFUSE;
    }
    if (f->duration > max_dur) {
        snprintf(why, whylen, "the log spans %.3g days: a time unit mistake?",
                 f->duration / 86400.0);
        return SW_GATE_REFUSE;
    }
    const sw_gate_axis_t lon = {.peak = f->peak_a,
                                .above_half_g = f->above_half_g,
                                .mean_abs = f->mean_abs_a,
                                .min = f->min_a,
                                .max = f->max_a};
    if (check_axis(f, &lon, 0, max_peak, min_still, why, whylen) ||
        (f->lateral && check_axis(f, &f->lat, 1, max_peak, min_still, why, whylen)))
        return SW_GATE_REFUSE;
    if (f->rate < warn_rate) {
        snprintf(why, whylen,
                 "%.3g Hz: shocks shorter than a few sample intervals (about %.2g s) are not "
                 "resolved",
                 f->rate, 3.0 / f->rate);
        return SW_GATE_WARN;
    }
    return SW_OK;
}
