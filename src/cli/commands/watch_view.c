/* SPDX-License-Identifier: GPL-3.0-or-later */
/* watch_view.c - the view of "swaywatch watch" as lines of text: the
 * input's health, a table of the packages (its columns dropped on a
 * narrow terminal), the last alarms; drawn on the curses screen or
 * printed as a plain snapshot.  Everything shown is ASCII but for names
 * and texts (UTF-8; control characters as '?'). */
#include <curses.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "journal.h"
#include "opts.h"
#include "text.h"
#include "watch.h"

/* ---- the view as lines of text ------------------------------------------------ */

enum { ATTR_NONE = 0, ATTR_TITLE, ATTR_HEAD, ATTR_WARN, ATTR_CRIT };

typedef struct {
    int width, rows; /* the room there is: longer lines are cut */
    int layout;      /* the width the package table is laid out for */
    int n;
    char line[MAX_ROWS][MAX_COLS + 1];
    int attr[MAX_ROWS];
} view_t;

static void add(view_t *v, int attr, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

static void add(view_t *v, int attr, const char *fmt, ...)
{
    if (v->n >= v->rows || v->n >= MAX_ROWS)
        return;
    char full[2 * MAX_COLS + 1];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(full, sizeof full, fmt, ap);
    va_end(ap);
    /* cut to the room there is, never inside a character */
    const size_t k = sw_cli_utf8_fit(full, (size_t)v->width);
    memcpy(v->line[v->n], full, k);
    v->line[v->n][k] = '\0';
    v->attr[v->n++] = attr;
}

/* A duration for people: ms, s, h or days. */
static void human_secs(char *buf, size_t len, double s)
{
    double a = fabs(s);
    if (!isfinite(s))
        snprintf(buf, len, "-");
    else if (a < 1.0)
        snprintf(buf, len, "%.1f ms", s * 1e3);
    else if (a < 120.0)
        snprintf(buf, len, "%.2f s", s);
    else if (a < 48 * 3600.0)
        snprintf(buf, len, "%.1f h", s / 3600.0);
    else
        snprintf(buf, len, "%.0f days", s / 86400.0);
}

static void view_input(view_t *v, const watch_t *w, double now)
{
    char lag[32], rej[256] = "", buf[MAX_COLS + 1];
    human_secs(lag, sizeof lag, w->lag);
    long total = 0;
    size_t used = 0;
    for (size_t i = 0; i < w->nreasons; i++) {
        total += w->reason[i].so_far;
        used += (size_t)snprintf(rej + used, sizeof rej - used, "%s%s %ld", i ? ", " : " (",
                                 w->reason[i].name, w->reason[i].so_far);
        if (used >= sizeof rej)
            break;
    }
    if (w->nreasons && used < sizeof rej - 1)
        snprintf(rej + used, sizeof rej - used, ")");
    snprintf(buf, sizeof buf,
             "input: %.1f states/s, lag %s, rejected %ld%s, gaps %ld, lost %ld "
             "states %ld alarms",
             isfinite(w->rate) ? w->rate : 0.0, lag, total, rej, w->gaps, w->lost_states,
             w->lost_alarms);
    int warn = total > 0 || w->gaps > 0 || w->lost_states > 0 || w->lost_alarms > 0;
    add(v, warn ? ATTR_WARN : ATTR_NONE, "%s", buf);
    char extra[MAX_COLS + 1] = "";
    used = 0;
    if (!w->states)
        used += (size_t)snprintf(extra, sizeof extra, "no state received yet");
    else if (now - w->last_rx > STALE) {
        char age[32];
        human_secs(age, sizeof age, now - w->last_rx);
        used += (size_t)snprintf(extra, sizeof extra, "NO STATE for %s%s", age,
                                 w->gap_open ? " (the monitor reports a sensor gap)" : "");
    } else if (w->gap_open)
        used += (size_t)snprintf(extra, sizeof extra, "SENSOR GAP: the monitor has no samples");
    if (w->contest_open && used < sizeof extra)
        used += (size_t)snprintf(extra + used, sizeof extra - used,
                                 "%sINPUT CONTESTED: two timelines on the accel channel",
                                 used ? "; " : "");
    else if (w->contests && used < sizeof extra)
        used += (size_t)snprintf(extra + used, sizeof extra - used, "%scontested %ld x",
                                 used ? "; " : "", w->contests);
    if (w->seq_restarts && used < sizeof extra)
        used += (size_t)snprintf(extra + used, sizeof extra - used, "%smonitor restarted %ld x",
                                 used ? "; " : "", w->seq_restarts);
    if ((w->undecodable || w->pkg_overflow) && used < sizeof extra)
        snprintf(extra + used, sizeof extra - used,
                 "%s%ld undecodable messages, %ld states of "
                 "packages beyond %d",
                 used ? "; " : "", w->undecodable, w->pkg_overflow, MAX_PKG);
    if (extra[0])
        add(v, ATTR_CRIT, "       %s", extra);
}

/* |theta|/alpha as [####....|...] in width w (>= 3): '#' up to the ratio,
 * '|' at the peak, '>' at the end beyond 1. */
static void bar(char *buf, int width, double ratio, double peak)
{
    const int in = width - 2;
    int fill = isfinite(ratio) ? (int)lround(fmin(ratio, 1.0) * in) : 0;
    int at = isfinite(peak) && peak > 0.0 ? (int)lround(fmin(peak, 1.0) * in) - 1 : -1;
    buf[0] = '[';
    for (int i = 0; i < in; i++) buf[1 + i] = i < fill ? '#' : i == at ? '|' : '.';
    if (ratio > 1.0)
        buf[in] = '>';
    buf[in + 1] = ']';
    buf[in + 2] = '\0';
}

static const char *model_name(int m)
{
    static const char *const n[] = {"bare", "frame", "cushion"};
    return m >= 0 && m < 3 ? n[m] : "?";
}

static const char *phase_name(int p)
{
    static const char *const n[] = {"stuck", "rocking", "OVERTURNED"};
    return p >= 0 && p < 3 ? n[p] : "?";
}

/* The package table's columns, dropped right to left of importance when
 * the terminal is narrow: the bar keeps at least MIN_BAR columns. */
#define MIN_BAR 12
#define MAX_BAR 52
typedef struct {
    int bar;                /* columns of the bar, brackets included */
    int model, theta, rate; /* shown */
} layout_t;

static layout_t layout(int width)
{
    layout_t l = {.model = 1, .theta = 1, .rate = 1};
    /* name 16, phase 10, ratio 5, margin 7 (+ reserve 7), a blank after each */
    const int fixed = 17 + 11 + 6 + 8 + (HAVE_RESERVE ? 8 : 0);
    l.bar = width - fixed - 8 - 10 - 10;
    if (l.bar < MIN_BAR) {
        l.model = 0;
        l.bar += 8;
    }
    if (l.bar < MIN_BAR) {
        l.rate = 0;
        l.bar += 10;
    }
    if (l.bar < MIN_BAR) {
        l.theta = 0;
        l.bar += 10;
    }
    l.bar = l.bar > MAX_BAR ? MAX_BAR : l.bar < 3 ? 3 : l.bar;
    return l;
}

/* One row of the table: the cells of a package (or the titles). */
static void table_row(view_t *v, int attr, const layout_t *l, const char *name, const char *model,
                      const char *phase, const char *bar_, const char *ratio, const char *theta,
                      const char *margin, const char *reserve, const char *rate)
{
    char row[MAX_COLS + 1];
    int k = snprintf(row, sizeof row, "%-16.*s ", (int)sw_cli_utf8_fit(name, 16), name);
    if (l->model)
        k += snprintf(row + k, sizeof row - (size_t)k, "%-7.7s ", model);
    k += snprintf(row + k, sizeof row - (size_t)k, "%-10.10s %-*s %5s", phase, l->bar, bar_, ratio);
    if (l->theta)
        k += snprintf(row + k, sizeof row - (size_t)k, " %9s", theta);
    k += snprintf(row + k, sizeof row - (size_t)k, " %7s", margin);
    if (HAVE_RESERVE)
        k += snprintf(row + k, sizeof row - (size_t)k, " %7s", reserve);
    if (l->rate)
        snprintf(row + k, sizeof row - (size_t)k, " %9s", rate);
    add(v, attr, "%s", row);
}

/* name: what the row's first column says (a lateral row under its
 * package's: "  sideways"). */
static void view_package(view_t *v, const layout_t *l, const pkg_view_t *p, const char *name,
                         double now)
{
    const swaywatch_state_t *s = &p->last;
    char b[MAX_BAR + 1], ratio[16] = "", theta[16], margin[16], reserve[16], rate[32];
    double r = p->alpha_from ? fabs(s->theta) / p->alpha : NAN;
    if (p->alpha_from) {
        bar(b, l->bar, r, p->peak);
        snprintf(ratio, sizeof ratio, "%5.2f", r);
    } else {
        snprintf(b, sizeof b, "%.*s", l->bar, "(alpha unknown: --scene)");
    }
    snprintf(theta, sizeof theta, "%+6.1fdeg", s->theta * 180.0 / M_PI);
    snprintf(margin, sizeof margin, "%7.3f", s->margin);
    if (RESERVE_OF(s) >= 0.0) /* -1: none yet, or the monitor's reserve is off */
        snprintf(reserve, sizeof reserve, "%7.3f", RESERVE_OF(s));
    else
        snprintf(reserve, sizeof reserve, "%7s", "-");
    if (now - p->rx > STALE)
        snprintf(rate, sizeof rate, "stale %3.0fs", fmin(now - p->rx, 999.0));
    else
        snprintf(rate, sizeof rate, "%9.1f", isfinite(p->rate) ? p->rate : 0.0);
    int attr = s->phase == SWAYWATCH_STATE_T_PHASE_OVERTURNED || r >= 1.0 ? ATTR_CRIT
               : s->phase == SWAYWATCH_STATE_T_PHASE_ROCKING              ? ATTR_WARN
                                                                          : ATTR_NONE;
    table_row(v, attr, l, name, model_name(s->model), phase_name(s->phase), b, ratio, theta, margin,
              reserve, rate);
}

static void view_packages(view_t *v, const watch_t *w, double now)
{
    const layout_t l = layout(v->layout);
    table_row(v, ATTR_HEAD, &l, "PACKAGE", "MODEL", "PHASE", "|THETA|/ALPHA", "", "THETA", "MARGIN",
              "RESERVE", "STATES/S");
    /* each package's plane along the truck, its lateral plane under it;
     * a lateral plane seen without the other on its own row */
    for (size_t i = 0; i < w->npkg; i++) {
        const pkg_view_t *p = &w->pkg[i];
        if (p->plane != SWAYWATCH_STATE_T_PLANE_LONGITUDINAL)
            continue;
        view_package(v, &l, p, p->name, now);
        for (size_t j = 0; j < w->npkg; j++)
            if (w->pkg[j].plane != SWAYWATCH_STATE_T_PLANE_LONGITUDINAL &&
                !strcmp(w->pkg[j].name, p->name))
                view_package(v, &l, &w->pkg[j], "  sideways", now);
    }
    for (size_t i = 0; i < w->npkg; i++) {
        const pkg_view_t *p = &w->pkg[i];
        int alone = p->plane != SWAYWATCH_STATE_T_PLANE_LONGITUDINAL;
        for (size_t j = 0; j < w->npkg && alone; j++)
            alone = !(w->pkg[j].plane == SWAYWATCH_STATE_T_PLANE_LONGITUDINAL &&
                      !strcmp(w->pkg[j].name, p->name));
        if (alone) {
            char name[SW_NAME_MAX + 16];
            snprintf(name, sizeof name, "%s sideways", p->name);
            view_package(v, &l, p, name, now);
        }
    }
    if (!w->npkg)
        add(v, ATTR_NONE, "(no package yet)");
}

static void view_alarms(view_t *v, const watch_t *w)
{
    add(v, ATTR_HEAD, "LAST ALARMS (newest first; %ld received)", w->alarms);
    for (size_t k = 0; k < w->ring_n; k++) {
        size_t i = (w->ring_next + (size_t)w->o->alarms - 1 - k) % (size_t)w->o->alarms;
        const alarm_view_t *e = &w->ring[i];
        char when[40], name[SW_NAME_MAX], text[sizeof e->a.text], nums[64] = "";
        sw_cli_iso_time(when, sizeof when, e->wall_us);
        sw_watch_msg_text(name, e->a.name, sizeof e->a.name);
        sw_watch_msg_text(text, e->a.text, sizeof e->a.text);
        /* the text first: on a narrow terminal the numbers are cut, not it */
        if (name[0] && RESERVE_OF(&e->a) >= 0.0)
            snprintf(nums, sizeof nums, "  (theta %+.4f, margin %.3f, reserve %.3f g)", e->a.theta,
                     e->a.margin, RESERVE_OF(&e->a));
        else if (name[0])
            snprintf(nums, sizeof nums, "  (theta %+.4f, margin %.3f)", e->a.theta, e->a.margin);
        const int lv = e->a.level;
        add(v,
            lv >= SWAYWATCH_ALARM_T_LEVEL_CRITICAL ? ATTR_CRIT
            : lv == SWAYWATCH_ALARM_T_LEVEL_WARN   ? ATTR_WARN
                                                   : ATTR_NONE,
            "%s %-8s %-16.*s %-14s %s%s", when + 11, sw_alarm_level_name((sw_alarm_level)lv),
            (int)sw_cli_utf8_fit(name[0] ? name : "-", 16), name[0] ? name : "-",
            sw_alarm_kind_name((sw_alarm_kind)e->a.kind), text, nums);
    }
    if (!w->ring_n)
        add(v, ATTR_NONE, "(none)");
}

/* The whole view in v's width and rows. */
static void view_make(view_t *v, const watch_t *w, int tty)
{
    const double now = sw_watch_mono_now();
    char when[40];
    sw_cli_iso_time(when, sizeof when, sw_watch_wall_now_us());
    v->n = 0;
    add(v, ATTR_TITLE, "swaywatch watch  %.19sZ  %s  %s %s%s", when,
        w->o->url && w->o->url[0] ? w->o->url : "(LCM default)", w->o->state_channel,
        w->o->alarm_channel, tty ? "   q: quit" : "");
    view_input(v, w, now);
    add(v, ATTR_NONE, "%s", "");
    view_packages(v, w, now);
    add(v, ATTR_NONE, "%s", "");
    view_alarms(v, w);
}

/* ---- terminals and snapshots ------------------------------------------------------ */

void sw_watch_plain_snapshot(const watch_t *w)
{
    static view_t v;
    v.width = MAX_COLS; /* nothing cut: the texts in full */
    v.layout = PLAIN_WIDTH;
    v.rows = MAX_ROWS;
    view_make(&v, w, 0);
    for (int i = 0; i < v.n; i++) printf("%s\n", v.line[i]);
    printf("\n");
    fflush(stdout);
}

void sw_watch_screen_draw(const watch_t *w)
{
    static view_t v;
    int rows, cols;
    getmaxyx(stdscr, rows, cols);
    v.width = v.layout = cols < 1 ? 1 : cols > MAX_COLS ? MAX_COLS : cols;
    v.rows = rows < 1 ? 1 : rows;
    view_make(&v, w, 1);
    erase();
    for (int i = 0; i < v.n; i++) {
        attr_t a = v.attr[i] == ATTR_TITLE  ? A_REVERSE
                   : v.attr[i] == ATTR_HEAD ? A_UNDERLINE
                   : v.attr[i] == ATTR_CRIT ? A_BOLD | A_STANDOUT
                   : v.attr[i] == ATTR_WARN ? A_BOLD
                                            : A_NORMAL;
        attrset(a);
        mvaddnstr(i, 0, v.line[i], v.width);
    }
    attrset(A_NORMAL);
    refresh();
}
