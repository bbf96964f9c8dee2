/* SPDX-License-Identifier: GPL-3.0-or-later */
/* flight.h - a rigid package in free flight while the bed falls away
 * faster than gravity (flight.c), in closed form, and its landing.  The
 * codes of sw_flight_advance are stuck.h's.  Internal. */
#ifndef SWAYWATCH_FLIGHT_H
#define SWAYWATCH_FLIGHT_H

#include "pkg.h"
#include "stuck.h"

/* P leaves its support at t (g_eff reached 0), with its momentum. */
void sw_flight_take_off(sw_pkg_ctx_t *C, sw_pkg_t *P, double t);
/* A flight of P (flying since P->fl_t0, or landed after dur s) that has
 * lasted SW_FLIGHT_LONG: said once, as SW_EV_FLIGHT at fl_t0 +
 * SW_FLIGHT_LONG, and kept in the summary.  dur: s in the air so far. */
void sw_flight_note(sw_pkg_ctx_t *C, sw_pkg_t *P, double dur);
/* Advance a flying P toward t1 in closed form: SW_STUCK_STILL (in the
 * air at t1), SW_STUCK_MOVED (landed, or on its side, at P->t). */
int sw_flight_advance(sw_pkg_ctx_t *C, sw_pkg_t *P, double t1);

#endif
