/* model.h - pure functions of the rocking models (physics.md): margins to
 * overturn, energies, impact ratios.  No allocation, no I/O, no state. */
#ifndef SWAYWATCH_MODEL_H
#define SWAYWATCH_MODEL_H

#include "engine.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Margin to overturn of a rigidly rocking package (bare, or frame with the
 * package's energy relative to the frame): 1 at rest, 0 at the edge, < 0
 * beyond.  r is the impact ratio (eta for bare, r_frame for the frame). */
double sw_margin_rocking(const sw_derived_t *d, double r, double theta, double theta_dot);

/* margin_bound of physics.md for the frame: 1 - E_tot / (m g R (1 - cos a)),
 * a guarantee once the excitation stops.  g_eff in m/s^2. */
double sw_margin_bound_frame(const sw_derived_t *d, double g_eff, const sw_state_t *s);

/* Total mechanical energy per unit package mass (J/kg) of the frame model
 * while rocking or stuck: kinetic + gravity + bearing strain, gravity
 * measured from the upright package. */
double sw_energy_frame(const sw_derived_t *d, double g_eff, const sw_state_t *s);

/* Energy of the bare block per unit mass (J/kg), from upright. */
double sw_energy_bare(const sw_derived_t *d, double g_eff, const sw_state_t *s);

#ifdef __cplusplus
}
#endif
#endif
