/* SPDX-License-Identifier: GPL-3.0-or-later */
/* flight.c - a rigid package in free flight (physics.md, "Free flight"):
 * the bare block and the package on a frame, when the bed falls away
 * faster than gravity (g_eff = g + a_z <= 0).
 *
 * The package leaves its support with the momentum it has.  In the air
 * no force but gravity acts on it: it turns at a constant rate about its
 * centre of mass, and the centre of mass moves, relative to the bed, as a
 * projectile under -a_g horizontally (no force from the bed) and -g_eff
 * vertically; a frame left behind rings on its bearings alone (mass m_b).
 * For an input linear in time all three are exact (polynomials, and the
 * damped oscillator's exact step, sw_nj_step), so a flight is advanced in
 * closed form, as a package standing on its support is (stuck.c), never
 * by the scheme's steps.
 *
 * It lands when its lowest corner, R cos(alpha - |theta|) below the centre
 * of mass, reaches the support again.  The landing keeps the package's
 * angular momentum about that corner (the support's impulse passes
 * through it) and the horizontal momentum of package and frame (the
 * bearings' forces are finite), with no bounce and no slide, the
 * assumptions of physics.md's impact maps, which are its special case: a
 * corner landing with the velocities of rocking about the other corner
 * gives eta on the bed and r_frame on a frame.  A level landing with
 * neither corner's rotation starting to lift the other is a rest. */
#include <math.h>
#include <string.h>

#include "flight.h"
#include "input.h"
#include "numeric.h"
#include "pkg.h"
#include "step.h"
#include "stuck.h"
#include "swaywatch/status.h"

/* The frame's bearings with the package away: w (rad/s) and zeta of the
 * frame alone, k_b / m_b and c_b / m_b. */
static void frame_alone(const sw_pkg_t *P, double *w, double *zeta)
{
    const double mb = P->scene.frame_mass; /* kg */
    *w = sqrt(P->m.d.k_b / mb);
    *zeta = P->m.d.c_b / (2.0 * *w * mb);
}

/* The vector from the corner on side s to the centre of mass, tilted by
 * theta (x forward, y up; m): (-s R sin(alpha - s theta), R cos(alpha - s
 * theta)). */
static void corner_to_cm(const sw_pkg_t *P, int s, double theta, double *rx, double *ry)
{
    const double A = P->m.d.alpha - s * theta;
    *rx = -s * P->m.d.R * sin(A);
    *ry = P->m.d.R * cos(A);
}

void sw_flight_note(sw_pkg_ctx_t *C, sw_pkg_t *P, double dur)
{
    if (P->fl_long || !(dur > SW_FLIGHT_LONG))
        return;
    P->fl_long = 1;
    if (isnan(P->sum.flight_long_time))
        P->sum.flight_long_time = P->fl_t0;
    sw_pkg_emit_at(C, P, SW_EV_FLIGHT, P->fl_t0 + SW_FLIGHT_LONG, NULL, C->origin + P->fl_t0, NULL);
}

void sw_flight_take_off(sw_pkg_ctx_t *C, sw_pkg_t *P, double t)
{
    const double th = P->y[P->m.ith], w = P->y[P->m.idth]; /* rad, rad/s */
    const double du = P->m.iu >= 0 ? P->y[P->m.idu] : 0.0; /* m/s, the support's */
    const int standing = P->m.phase == SW_PHASE_STUCK;
    P->fl_vx = du;
    P->fl_vy = 0.0;
    P->fl_yc = P->m.d.h;
    if (!standing) {
        /* rocking about the corner on side s: v_C = (th' r_y, -th' r_x)
         * relative to the support */
        double rx, ry;
        corner_to_cm(P, P->m.side, th, &rx, &ry);
        P->fl_vx += w * ry;
        P->fl_vy = -w * rx;
        P->fl_yc = ry;
    }
    P->m.flying = 1;
    P->fl_long = 0;
    P->fl_t0 = t;
    P->fl_up = 0;
    P->sum.flights++;
    if (standing) {
        /* the level base leaves at once: an uplift with no direction */
        P->m.phase = SW_PHASE_ROCKING;
        P->m.t_lift = t;
        P->sum.uplifts++;
        if (isnan(P->sum.uplift_time))
            P->sum.uplift_time = t;
        sw_pkg_emit_at(C, P, SW_EV_UPLIFT, t, NULL, 0.0, NULL);
    }
}

double sw_landing_map(const sw_derived_t *d, int s, double theta, double w, double vx, double vy,
                      double du, double *du_after)
{
    const double A = d->alpha - s * theta, R2 = d->R * d->R;
    const double rx = -s * d->R * sin(A), ry = d->R * cos(A);
    const double g = d->gamma;
    /* (4R^2/3 - gamma ry^2) th'+ = R^2/3 th'- - rx vy + (1 - gamma) ry (vx - du) */
    const double wp =
        (R2 / 3.0 * w - rx * vy + (1.0 - g) * ry * (vx - du)) / (4.0 * R2 / 3.0 - g * ry * ry);
    if (du_after)
        *du_after = g * vx + (1.0 - g) * du - g * ry * wp;
    return wp;
}

/* The lowest corner's height over the support (m) at tilt th with the
 * centre of mass at height yc. */
static double clearance(const sw_pkg_t *P, double yc, double th)
{
    return yc - P->m.d.R * cos(P->m.d.alpha - fabs(th));
}

/* The flight's state tau (s) after (t0, state): the centre of mass's
 * height, velocities and the tilt, under a_g = a0 + as tau and g_eff =
 * g0 + gs tau. */
typedef struct {
    double t0, th0, w, yc0, vx0, vy0; /* s, rad, rad/s, m, m/s, m/s */
    double a0, as, g0, gs;            /* m/s^2, m/s^3 */
} arc_t;

static void arc_at(const arc_t *a, double tau, double *yc, double *vx, double *vy, double *th)
{
    const double t2 = tau * tau, t3 = t2 * tau;
    *yc = a->yc0 + a->vy0 * tau - (0.5 * a->g0 * t2 + a->gs * t3 / 6.0);
    *vx = a->vx0 - (a->a0 * tau + 0.5 * a->as * t2);
    *vy = a->vy0 - (a->g0 * tau + 0.5 * a->gs * t2);
    *th = a->th0 + a->w * tau;
}

static double arc_clearance(const sw_pkg_t *P, const arc_t *a, double tau)
{
    double yc, vx, vy, th;
    arc_at(a, tau, &yc, &vx, &vy, &th);
    return clearance(P, yc, th);
}

/* Move the package along the arc to tau (the frame on its own). */
static void arc_move(sw_pkg_t *P, const arc_t *a, double tau)
{
    double th;
    arc_at(a, tau, &P->fl_yc, &P->fl_vx, &P->fl_vy, &th);
    P->y[P->m.ith] = th;
    if (P->m.iu >= 0 && tau > 0.0) {
        double w, z, u1[2];
        const double u0[2] = {P->y[P->m.iu], P->y[P->m.idu]};
        frame_alone(P, &w, &z);
        sw_nj_step(w, z, tau, a->a0, a->as, u0, u1);
        P->y[P->m.iu] = u1[0];
        P->y[P->m.idu] = u1[1];
    }
    P->t = a->t0 + tau;
}

/* Landed at P->t: the map, then rocking on the corner, or standing. */
static void land(sw_pkg_ctx_t *C, sw_pkg_t *P)
{
    const double t = P->t, th = P->y[P->m.ith], w = P->y[P->m.idth];
    const double du = P->m.iu >= 0 ? P->y[P->m.idu] : 0.0;
    const double dur = t - P->fl_t0; /* s */
    sw_flight_note(C, P, dur);
    P->m.flying = 0;
    P->sum.flight_max = sw_max2(P->sum.flight_max, dur);
    sw_step_reset(&P->st);
    int s = th > 0.0 ? 1 : th < 0.0 ? -1 : 0;
    double wp = 0.0, du_after = du;
    if (s) {
        wp = sw_landing_map(&P->m.d, s, th, w, P->fl_vx, P->fl_vy, du, &du_after);
    } else {
        /* level: it rocks on the corner whose rotation lifts the other,
         * or it stands */
        double up[2], uu[2];
        for (int k = 0; k < 2; k++) {
            const int sk = k ? -1 : 1;
            up[k] = sw_landing_map(&P->m.d, sk, 0.0, w, P->fl_vx, P->fl_vy, du, &uu[k]);
            up[k] *= sk; /* > 0: lifts the other corner */
        }
        const int k = up[0] >= up[1] ? 0 : 1;
        if (up[k] > 0.0) {
            s = k ? -1 : 1;
            wp = s * up[k];
            du_after = uu[k];
        } else {
            /* both corners down: the package moves with its support, the
             * horizontal momentum shared with the frame */
            const double g = P->m.d.gamma;
            if (P->m.iu >= 0)
                P->y[P->m.idu] = g * P->fl_vx + (1.0 - g) * du;
            P->y[P->m.ith] = P->y[P->m.idth] = 0.0;
            P->m.phase = SW_PHASE_STUCK;
            P->sum.rests++;
            sw_pkg_emit_at(C, P, SW_EV_REST, t, NULL, 0.0, NULL);
            return;
        }
    }
    P->m.phase = SW_PHASE_ROCKING;
    P->m.side = s;
    P->y[P->m.idth] = wp;
    if (P->m.iu >= 0)
        P->y[P->m.idu] = du_after;
    P->beyond_alpha = fabs(th) >= P->m.d.alpha;
    P->sum.impacts++;
    sw_pkg_emit_at(C, P, SW_EV_IMPACT, t, NULL, w, NULL);
}

#define GRID_MIN 8    /* clearance samples in a piece of flight, at least */
#define GRID_DT 1e-4  /* s, and at least one per this much of it */
#define GRID_MAX 4096 /* and at most */

int sw_flight_advance(sw_pkg_ctx_t *C, sw_pkg_t *P, double t1)
{
    const sw_input_t *in = P->m.in;
    const double t0 = P->t, H = t1 - t0; /* s */
    if (!(H > 0.0))
        return SW_STUCK_STILL;
    /* the input over the piece: exact for samples (linear), the chord of
     * a function input */
    const double a0 = sw_input_ag(in, t0), a1 = sw_input_ag(in, t1);
    const double g0 = sw_input_geff(P->m.in, P->m.g, t0), g1 = sw_input_geff(P->m.in, P->m.g, t1);
    const arc_t a = {.t0 = t0,
                     .th0 = P->y[P->m.ith],
                     .w = P->y[P->m.idth],
                     .yc0 = P->fl_yc,
                     .vx0 = P->fl_vx,
                     .vy0 = P->fl_vy,
                     .a0 = a0,
                     .as = (a1 - a0) / H,
                     .g0 = g0,
                     .gs = (g1 - g0) / H};
    /* on its side before it lands: overturned there */
    double t_over = INFINITY; /* s */
    if (a.w != 0.0) {
        const double edge = a.w > 0.0 ? M_PI_2 : -M_PI_2;
        const double tau = (edge - a.th0) / a.w;
        if (tau >= 0.0 && tau <= H)
            t_over = tau;
    }
    const double eps = 1e-12 * P->m.d.R; /* m: the clearance's rounding */
    const double tend = sw_min2(H, t_over);
    /* clamped before the conversion: a flight between samples days apart
     * is more grid points than an int holds */
    const double q = ceil(tend / GRID_DT);
    const int n = !(q > GRID_MIN) ? GRID_MIN : q > GRID_MAX ? GRID_MAX : (int)q;
    double lo = 0.0, land_at = -1.0;
    for (int k = 1; k <= n && land_at < 0.0; k++) {
        const double tau = tend * k / n, c = arc_clearance(P, &a, tau);
        if (!P->fl_up) {
            if (c > eps)
                P->fl_up = 1; /* it has left its support */
            else if (c < -eps)
                land_at = tau; /* it never rose: back down at once */
            lo = tau;
            continue;
        }
        if (c > 0.0) {
            lo = tau;
            continue;
        }
        /* the first crossing down: bisected */
        double hi = tau;
        for (int i = 0; i < 80 && hi - lo > 1e-15 * sw_max2(1.0, fabs(t0)); i++) {
            const double mid = 0.5 * (lo + hi);
            if (arc_clearance(P, &a, mid) > 0.0)
                lo = mid;
            else
                hi = mid;
        }
        land_at = hi;
    }
    /* theta is linear in the air: its largest |theta| at an end; tipped
     * past alpha on the way (the centre of mass beyond the corner) */
    const double tau_end = land_at >= 0.0 ? land_at : tend;
    sw_pkg_track_theta(P, a.th0 + a.w * tau_end);
    if (!P->beyond_alpha && a.w != 0.0) {
        const double edge = a.w > 0.0 ? P->m.d.alpha : -P->m.d.alpha;
        const double tau = (edge - a.th0) / a.w;
        if (tau >= 0.0 && tau <= tau_end) {
            double y_at[SW_NMAX];
            memcpy(y_at, P->y, sizeof y_at);
            y_at[P->m.ith] = edge;
            sw_pkg_tip(C, P, t0 + tau, NULL, y_at);
        }
    }
    if (land_at >= 0.0) {
        arc_move(P, &a, land_at);
        land(C, P);
        return SW_STUCK_MOVED;
    }
    if (t_over <= H) {
        arc_move(P, &a, t_over);
        sw_flight_note(C, P, P->t - P->fl_t0);
        P->m.flying = 0;
        P->sum.flight_max = sw_max2(P->sum.flight_max, P->t - P->fl_t0);
        P->m.side = a.w > 0.0 ? 1 : -1;
        sw_pkg_on_cut(C, P, SW_EVF_OVERTURN, P->t);
        sw_step_reset(&P->st);
        return SW_STUCK_MOVED;
    }
    arc_move(P, &a, H);
    P->t = t1;
    return SW_STUCK_STILL;
}
