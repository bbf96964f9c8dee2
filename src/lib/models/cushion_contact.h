/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cushion_contact.h - what a Winkler cushion does to the package at one
 * state (cushion_contact.c), for the cushion model (model_cushion.c).
 * Internal. */
#ifndef SWAYWATCH_CUSHION_CONTACT_H
#define SWAYWATCH_CUSHION_CONTACT_H

#include "swaywatch/scene.h"

/* What the cushion does to the package at one state, per unit mass. */
typedef struct {
    double F;  /* m/s^2: F_B / m, upward */
    double Ms; /* m^2/s^2: (integral of f sigma) / m; M_B = cos(theta) Ms */
    double S;  /* 1/s^2: tangent stiffness dF/dz over the pushing part */
    double U;  /* J/kg: strain energy over the compressed part */
    /* moments of the tangent stiffness density (k' + 3 beta' z^2)/m and
     * of the length over the pushing part: sigma^1, sigma^2 (S and L0 are
     * the zeroth) -- the contact's stiffness and damping matrices */
    double S1, S2, L0, L1, L2;
} contact_t;

/* What a caller of contact() needs: the push (F, Ms), the stiffness and
 * damping moments (S, S1, S2, L0, L1, L2), the strain energy (U).  The
 * right-hand side needs the moments only while its rate is tracked, and
 * the strain energy never; each sum is the same, bit for bit, whatever
 * else is computed. */
enum { CT_PUSH = 1, CT_MOMENTS = 2, CT_STRAIN = 4 };

/* Forces, tangent stiffness and strain energy of the cushion of a scene's
 * derived quantities d at (theta, z) moving at (theta', z'), given
 * s = sin(theta) and co = cos(theta), as much of it as what asks for
 * (CT_*).  The cushion's constants per unit mass are its own: the model
 * hands over the scene, not them. */
void sw_cushion_contact(const sw_derived_t *d, double s, double co, double z, double dth, double dz,
                        int what, contact_t *o);

#endif
