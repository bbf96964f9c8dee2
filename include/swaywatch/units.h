/* SPDX-License-Identifier: GPL-3.0-or-later */
/* units.h - the units the library converts at its edges.
 *
 * Inside, everything is SI (m, s, kg, rad, m/s^2).  An acceleration in g
 * (a logger's column, a reserve, a pulse given in g) is one of standard
 * gravity, SW_G0, whatever the scene's g: sw_scene_t.g is the gravity of
 * the physics (default 9.81 m/s^2), SW_G0 the unit loggers and standards
 * use (ISO 80000-3, CIPM 1901). */
#ifndef SWAYWATCH_UNITS_H
#define SWAYWATCH_UNITS_H

#define SW_G0 9.80665 /* m/s^2 per g: standard gravity */

#endif
