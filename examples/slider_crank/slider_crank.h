/*
 * The thesis' slider-crank (4.1) as data on the multibody core, in 3-D with a joint set free of
 * redundant constraints: ground (fixed), crank on a revolute about z at the origin, rod on a
 * spherical joint at the crank pin and a Cardan at the slider, slider on a prismatic joint along
 * x. Motion in the xy-plane, gravity along -y. Bars are slender rods with the centre of mass at
 * mid-length; the crank is driven by an angle driver whose multiplier is the driving torque.
 */
#ifndef SLIDER_CRANK_H
#define SLIDER_CRANK_H

#include "mbs/mbs.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct slider_crank_params {
    double crank_length, rod_length;          /* [m]: thesis 1, 2 */
    double crank_mass, rod_mass, slider_mass; /* [kg]: thesis 1, 2, 3 */
    double gravity;                           /* along -y [m/s^2]: 9.81 */
} slider_crank_params;

typedef struct slider_crank_layout {
    int ground, crank, rod, slider; /* body indices */
    int crank_driver;               /* driver slot of the crank angle (from the x axis) */
    int crank_driver_joint;         /* its joint: multiplier row mbs_joint_first_row(...) */
    int crank_bearing, rod_slider_cardan, slider_guide; /* joints: revolute (ground, crank),
                                      Cardan (rod, slider), prismatic (ground, slider) */
} slider_crank_layout;

void slider_crank_params_default(slider_crank_params *params);
/* Built and finalised, at crank angle 0 (everything along +x); NULL with a message on error. */
mbs_model *slider_crank_create(const slider_crank_params *params, slider_crank_layout *layout,
                               char *message, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* SLIDER_CRANK_H */
