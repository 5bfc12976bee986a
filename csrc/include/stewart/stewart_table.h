/*
 * The parameter and option tables: one entry per field of stewart_params and of the options
 * structs (stewart_inverse_options, stewart_forward_options, stewart_plant_options),
 * with its stable id, name, element count, unit, valid range, default and description. The
 * library's defaults, checks and setters are expanded from these lists, and the upper layers
 * (FMU variables and model descriptions, the CLI's --param, fuzz seeds, Python) iterate them
 * through the functions below instead of writing a parameter down again.
 *
 * X-macros (in the spirit of MuJoCo's mjxmacro.h): STEWART_PARAM_TABLE(X) calls
 *   X(id, name, count, unit, display_unit, min, min_closed, max, max_closed, defaults, description)
 * once per stewart_params field, in declaration order:
 *   id           stable integer id of element 0 (= the FMU value reference); element e is id + e
 *   name         the field's name (a C identifier; element e is named "name[e+1]" if count > 1)
 *   count        number of doubles: 1, 3 (x, y, z), 6 (legs 1..6), 18 (x, y, z of legs
 *                1..6) or STEWART_POSE_ELEMENTS (6: a pose x, y, z [m], roll, pitch, yaw
 *                [rad], with unit STEWART_POSE_UNIT and display unit "deg" of its angles;
 *                stewart_param_element_unit names each one's)
 *   unit         SI unit string ("m", "rad", "kg", "kg.m2", "m/s2"); display_unit "deg" or ""
 *   min, max     valid range of each element; min_closed/max_closed 1 if the end is included.
 *                Ends at -DBL_MAX/DBL_MAX (closed) mean "finite": no value may be NaN or Inf.
 *   defaults     a parenthesised list of count doubles (the thesis platform, SI)
 *   description  one sentence; an element's adds " of leg k" (count 6) or " x"/" y"/" z" (count 3)
 *                or " x" .. " yaw" (a pose)
 * Range checks across fields (inertia triangle inequalities, stroke_min < stroke_max) are code,
 * in stewart_params_check.
 *
 * STEWART_OPTION_TABLE(X) (the inverse solver's), STEWART_FORWARD_OPTION_TABLE(X) and
 * STEWART_PLANT_OPTION_TABLE(X) call
 *   X(id, name, type, unit, min, min_closed, max, max_closed, default, description)
 * once per field of stewart_inverse_options, stewart_forward_options and stewart_plant_options,
 * in declaration order; type is int, long or double. An option is one line here and its field
 * in the struct (a static_assert checks they match); setters and lookup by name come from the
 * table, and so do the defaults and the range checks of all three (table/options.cpp).
 */
#ifndef STEWART_STEWART_TABLE_H
#define STEWART_STEWART_TABLE_H

#include <float.h>
#include <stddef.h>

#include "mbs/mbs.h"
#include "stewart/stewart.h"
#include "stewart/stewart_cueing.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_limits.h"
#include "stewart/stewart_linearize.h"
#include "stewart/stewart_plant.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The values and tables below are laid out by hand, one entry a line (not formatted). */
/* clang-format off */
/* The thesis platform's values, from its formulas (thesis 4.2.8): an aluminium (2700 kg/m^3)
 * disc of radius 0.5 m and 0.05 m thickness, and leg bodies that are aluminium rods of
 * diameter 0.015 m and length 0.3 m, each with its centre 0.15 m from its Cardan centre. */
#define STEWART_PI 3.14159265358979323846
#define STEWART_DEG(d) ((d) * (STEWART_PI / 180.0))
#define STEWART_THESIS_PLATE_MASS (2700.0 * STEWART_PI * 0.5 * 0.5 * 0.05)
#define STEWART_THESIS_ROD_MASS (2700.0 * STEWART_PI * 0.0075 * 0.0075 * 0.3)
/* A solid rod of mass m, radius 0.0075 m, length 0.3 m, axis z: principal moments about its
 * centre. */
#define STEWART_THESIS_ROD_INERTIA                                                         \
    (STEWART_THESIS_ROD_MASS * (3.0 * 0.0075 * 0.0075 + 0.3 * 0.3) / 12.0,                 \
     STEWART_THESIS_ROD_MASS * (3.0 * 0.0075 * 0.0075 + 0.3 * 0.3) / 12.0,                 \
     STEWART_THESIS_ROD_MASS * 0.0075 * 0.0075 / 2.0)

/* A pose parameter (tool_frame, user_frame): its count, written in the table as this name so
 * that the FMU's element expansion (fmu/runtime/elements.h) tells it from six legs, and its unit
 * string (x, y, z in m; roll, pitch, yaw in rad). */
#define STEWART_POSE_ELEMENTS 6
#define STEWART_POSE_UNIT "m, rad"

/* The thesis platform's joints as coordinates (x1, y1, z1, ..., z6): r (cos angle, sin angle, 0)
 * of the default radii and angles, each the double that expression gives, so that geometry 1
 * with these joints places every joint exactly where geometry 0 does. */
#define STEWART_THESIS_BASE_JOINTS                                                         \
    (0.5, 0.0, 0.0,  \
     0.43301270189221935, 0.24999999999999997, 0.0,  \
     -0.24999999999999989, 0.43301270189221935, 0.0,  \
     -0.43301270189221935, 0.24999999999999997, 0.0,  \
     -0.25000000000000022, -0.43301270189221919, 0.0,  \
     -9.1848509936051484e-17, -0.5, 0.0)
#define STEWART_THESIS_PLATFORM_JOINTS                                                     \
    (0.43301270189221919, -0.25000000000000022, 0.0,  \
     0.25000000000000006, 0.4330127018922193, 0.0,  \
     3.061616997868383e-17, 0.5, 0.0,  \
     -0.5, 6.123233995736766e-17, 0.0,  \
     -0.4330127018922193, -0.25000000000000006, 0.0,  \
     0.25000000000000006, -0.4330127018922193, 0.0)
#define STEWART_ZERO_18 (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)

#define STEWART_PARAM_TABLE(X)                                                                   \
    X(210, base_radius, 1, "m", "", 0.0, 0, DBL_MAX, 1, (0.5),                                   \
      "Radius of the circle of base Cardan centres")                                             \
    X(211, platform_radius, 1, "m", "", 0.0, 0, DBL_MAX, 1, (0.5),                               \
      "Radius of the circle of platform Cardan centres")                                         \
    X(212, base_angle, 6, "rad", "deg", -DBL_MAX, 1, DBL_MAX, 1,                                 \
      (STEWART_DEG(0.0), STEWART_DEG(30.0), STEWART_DEG(120.0), STEWART_DEG(150.0),              \
       STEWART_DEG(240.0), STEWART_DEG(270.0)),                                                  \
      "Angle of the base Cardan centre")                                                         \
    X(218, platform_angle, 6, "rad", "deg", -DBL_MAX, 1, DBL_MAX, 1,                             \
      (STEWART_DEG(330.0), STEWART_DEG(60.0), STEWART_DEG(90.0), STEWART_DEG(180.0),             \
       STEWART_DEG(210.0), STEWART_DEG(300.0)),                                                  \
      "Angle (platform frame) of the platform Cardan centre")                                   \
    X(224, home_height, 1, "m", "", -DBL_MAX, 1, DBL_MAX, 1, (0.5), "z of the home pose")        \
    X(500, geometry, 1, "", "", 0.0, 1, 1.0, 1, (0.0),                                           \
      "Which joints: 0 the circles (base_radius, platform_radius, base_angle, platform_angle), "  \
      "1 base_joint and platform_joint as given")                                                \
    X(501, base_joint, 18, "m", "", -DBL_MAX, 1, DBL_MAX, 1, STEWART_THESIS_BASE_JOINTS,          \
      "Base Cardan centre (geometry 1), base frame")                                             \
    X(519, platform_joint, 18, "m", "", -DBL_MAX, 1, DBL_MAX, 1, STEWART_THESIS_PLATFORM_JOINTS,  \
      "Platform Cardan centre (geometry 1), platform frame")                                     \
    X(537, base_cardan_axis, 18, "1", "", -1.0, 1, 1.0, 1, STEWART_ZERO_18,                      \
      "Fixed arm of the base Cardan, base frame: a unit vector, or zero for the tangent to the "  \
      "joint's azimuth")                                                                         \
    X(555, platform_cardan_axis, 18, "1", "", -1.0, 1, 1.0, 1, STEWART_ZERO_18,                  \
      "Fixed arm of the platform Cardan, platform frame: a unit vector, or zero for the tangent " \
      "to the joint's azimuth")                                                                  \
    X(225, gravity, 3, "m/s2", "", -DBL_MAX, 1, DBL_MAX, 1, (0.0, 0.0, -9.81), "Gravity, world") \
    X(230, platform_mass, 1, "kg", "", 0.0, 0, DBL_MAX, 1, (STEWART_THESIS_PLATE_MASS),          \
      "Mass of the moving platform")                                                             \
    X(231, platform_com, 3, "m", "", -DBL_MAX, 1, DBL_MAX, 1, (0.0, 0.0, 0.0),                   \
      "Platform centre of mass, platform frame")                                                 \
    X(234, platform_inertia, 3, "kg.m2", "", 0.0, 0, DBL_MAX, 1,                                 \
      (STEWART_THESIS_PLATE_MASS * 0.5 * 0.5 / 4.0, STEWART_THESIS_PLATE_MASS * 0.5 * 0.5 / 4.0, \
       STEWART_THESIS_PLATE_MASS * 0.5 * 0.5 / 2.0),                                             \
      "Platform principal moment about its centre of mass, platform axis")                       \
    X(240, payload_mass, 1, "kg", "", 0.0, 1, DBL_MAX, 1, (0.0),                                 \
      "Payload mass carried by the platform (0 for none)")                                       \
    X(241, payload_com, 3, "m", "", -DBL_MAX, 1, DBL_MAX, 1, (0.0, 0.0, 0.0),                    \
      "Payload centre of mass, platform frame")                                                  \
    X(244, payload_inertia, 3, "kg.m2", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0),                 \
      "Payload principal moment about its centre of mass, platform axis")                        \
    X(250, cylinder_mass, 1, "kg", "", 0.0, 1, DBL_MAX, 1, (STEWART_THESIS_ROD_MASS),            \
      "Mass of each cylinder (lower leg body, on the base Cardan)")                              \
    X(251, cylinder_inertia, 3, "kg.m2", "", 0.0, 1, DBL_MAX, 1, STEWART_THESIS_ROD_INERTIA,     \
      "Cylinder principal moment about its centre of mass (x along the Cardan cross arm, z "     \
      "along the leg), axis")                                                                    \
    X(254, cylinder_com, 1, "m", "", -DBL_MAX, 1, DBL_MAX, 1, (0.3 / 2.0),                       \
      "Cylinder centre of mass from the base Cardan centre along the leg")                       \
    X(255, piston_mass, 1, "kg", "", 0.0, 1, DBL_MAX, 1, (STEWART_THESIS_ROD_MASS),              \
      "Mass of each piston (upper leg body, on the platform Cardan)")                            \
    X(256, piston_inertia, 3, "kg.m2", "", 0.0, 1, DBL_MAX, 1, STEWART_THESIS_ROD_INERTIA,       \
      "Piston principal moment about its centre of mass (x along the Cardan cross arm, z "       \
      "along the leg), axis")                                                                    \
    X(259, piston_com, 1, "m", "", -DBL_MAX, 1, DBL_MAX, 1, (0.3 / 2.0),                         \
      "Piston centre of mass from the platform Cardan centre toward the base")                   \
    X(573, stroke_min, 6, "m", "", 0.0, 0, DBL_MAX, 1, (0.40, 0.40, 0.40, 0.40, 0.40, 0.40),     \
      "Shortest allowed actuator length (a warning below)")                                      \
    X(579, stroke_max, 6, "m", "", 0.0, 0, DBL_MAX, 1, (0.70, 0.70, 0.70, 0.70, 0.70, 0.70),     \
      "Longest allowed actuator length (a warning above)")                                       \
    X(600, tool_frame, STEWART_POSE_ELEMENTS, STEWART_POSE_UNIT, "deg", -1e3, 1, 1e3, 1,         \
      (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),                                                            \
      "Pose of the tool frame (the pose given and returned) in the platform frame:")             \
    X(606, user_frame, STEWART_POSE_ELEMENTS, STEWART_POSE_UNIT, "deg", -1e3, 1, 1e3, 1,         \
      (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),                                                            \
      "Pose of the user frame (poses are given and returned in it) in the base frame:")          \
    X(590, rotation_order, 1, "", "", 0.0, 1, 1.0, 1, (0.0),                                    \
      "Angles of every pose given and returned (frames too): 0 R = Rz(yaw) Ry(pitch) Rx(roll), "  \
      "1 R = Rx(roll) Ry(pitch) Rz(yaw) (PI's U-V-W)")                                            \
    X(591, frame_convention, 1, "", "", 0.0, 1, 1.0, 1, (0.0),                                  \
      "Base and platform frames of the joints and poses: 0 z up, 1 z down (x forward, y right, "  \
      "as flight simulators state them)")                                                         \
    X(612, length_offset, 6, "m", "", -1e3, 1, 1e3, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),           \
      "Length sensor offset: Cardan-to-Cardan length minus the reading given and returned")      \
    X(440, base_joint_limit, 1, "rad", "deg", 0.0, 0, STEWART_PI, 1, (STEWART_DEG(90.0)),       \
      "Largest angle between a leg and its base joint's neutral axis (docs/limits.md)")         \
    X(441, platform_joint_limit, 1, "rad", "deg", 0.0, 0, STEWART_PI, 1, (STEWART_DEG(90.0)),   \
      "Largest angle between a leg and its platform joint's neutral axis (docs/limits.md)")     \
    X(442, base_joint_neutral, 18, "1", "", -DBL_MAX, 1, DBL_MAX, 1,                            \
      (0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0),                                   \
      "Neutral axis of the base joint, base frame, base toward platform (zero: the leg at "     \
      "home)")                                                                                   \
    X(460, platform_joint_neutral, 18, "1", "", -DBL_MAX, 1, DBL_MAX, 1,                        \
      (0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0),                                   \
      "Neutral axis of the platform joint, platform frame, base toward platform (zero: the "    \
      "leg at home)")                                                                            \
    X(478, leg_diameter, 1, "m", "", 0.0, 1, DBL_MAX, 1, (0.015),                               \
      "Diameter of a leg along its whole length when leg_body_length and leg_rod_length are 0: "  \
      "two legs' axes closer than it interfere (0: no check)")                                   \
    X(620, leg_body_diameter, 1, "m", "", 0.0, 1, DBL_MAX, 1, (0.0),                            \
      "Diameter of the actuator body, a cylinder from the base joint toward the platform")       \
    X(621, leg_body_length, 1, "m", "", 0.0, 1, DBL_MAX, 1, (0.0),                              \
      "Length of the actuator body from the base joint (0 with leg_rod_length 0: the leg is "    \
      "leg_diameter thick from joint to joint)")                                                 \
    X(622, leg_rod_diameter, 1, "m", "", 0.0, 1, DBL_MAX, 1, (0.0),                             \
      "Diameter of the actuator rod, a cylinder from the platform joint toward the base")        \
    X(623, leg_rod_length, 1, "m", "", 0.0, 1, DBL_MAX, 1, (0.0),                               \
      "Length of the actuator rod from the platform joint")                                      \
    X(626, axis_min, STEWART_POSE_ELEMENTS, STEWART_POSE_UNIT, "deg", -DBL_MAX, 1, DBL_MAX, 1,  \
      (-DBL_MAX, -DBL_MAX, -DBL_MAX, -DBL_MAX, -DBL_MAX, -DBL_MAX),                              \
      "Software position limit, smallest tool pose in the user frame (-1.8e308: none):")        \
    X(632, axis_max, STEWART_POSE_ELEMENTS, STEWART_POSE_UNIT, "deg", -DBL_MAX, 1, DBL_MAX, 1,  \
      (DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX),                                    \
      "Software position limit, largest tool pose in the user frame (1.8e308: none):")          \
    X(640, screw_lead, 6, "m", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),          \
      "Leg travel per turn of the leg's screw (0: no drive; the leg is driven by its force)")   \
    X(646, gear_ratio, 6, "1", "", 0.0, 0, DBL_MAX, 1, (1.0, 1.0, 1.0, 1.0, 1.0, 1.0),          \
      "Motor turns per screw turn (gearbox or belt)")                                           \
    X(652, rotor_inertia, 6, "kg.m2", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),   \
      "Motor rotor's inertia about its axis, with the parts that turn at motor speed")          \
    X(658, screw_inertia, 6, "kg.m2", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),   \
      "Screw's inertia about its axis, with the parts that turn at screw speed")                \
    X(664, screw_efficiency, 6, "1", "", 0.0, 0, 1.0, 1, (1.0, 1.0, 1.0, 1.0, 1.0, 1.0),        \
      "Screw and gear efficiency when the motor drives the load")                               \
    X(670, screw_back_efficiency, 6, "1", "", 0.0, 1, 1.0, 1, (1.0, 1.0, 1.0, 1.0, 1.0, 1.0),   \
      "Screw and gear efficiency when the load drives the motor (0: self-locking)")             \
    X(676, torque_constant, 6, "N.m/A", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), \
      "Motor torque per ampere, equal to the back-EMF constant in V.s/rad")                     \
    X(682, winding_resistance, 6, "Ohm", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),\
      "Motor winding resistance, terminal to terminal as the current sees it")                  \
    X(688, winding_inductance, 6, "H", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),  \
      "Motor winding inductance (0: the current follows the voltage at once)")                  \
    X(694, coulomb_friction, 6, "N", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),    \
      "Leg friction force while sliding, on the leg's axis")                                    \
    X(700, viscous_friction, 6, "N.s/m", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),\
      "Leg friction force per leg speed")                                                       \
    X(706, stribeck_friction, 6, "N", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),   \
      "Leg breakaway friction force at rest (at most coulomb_friction: no Stribeck peak)")      \
    X(712, stribeck_speed, 6, "m/s", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),    \
      "Leg speed over which friction falls from stribeck_friction toward coulomb_friction")     \
    X(718, end_stop_stiffness, 6, "N/m", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),\
      "Stiffness of the leg's end stops beyond stroke_min and stroke_max (0: none)")            \
    X(724, end_stop_damping, 6, "N.s/m", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),\
      "Damping of the leg's end stops while compressed")                                        \
    X(730, leg_stiffness, 6, "N/m", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),     \
      "Axial stiffness of the leg between screw and joints (0: rigid)")                         \
    X(736, leg_damping, 6, "N.s/m", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),     \
      "Axial damping of the leg's compliance")                                                  \
    X(742, current_max, 6, "A", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),         \
      "Largest motor current of the drive (0: no limit)")                                       \
    X(748, voltage_max, 6, "V", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),         \
      "Largest motor terminal voltage of the drive (0: no limit)")                              \
    X(754, motor_speed_max, 6, "rad/s", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), \
      "Largest motor speed (0: no limit)")                                                      \
    X(760, leg_speed_max, 6, "m/s", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),     \
      "Largest leg speed (0: no limit)")                                                        \
    X(766, leg_accel_max, 6, "m/s2", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),    \
      "Largest leg acceleration (0: no limit)")                                                 \
    X(772, leg_jerk_max, 6, "m/s3", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),     \
      "Largest leg jerk (0: no limit)")                                                         \
    X(778, leg_force_max, 6, "N", "", 0.0, 1, DBL_MAX, 1, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),       \
      "Largest leg force, pushing or pulling (0: no limit)")

#define STEWART_OPTION_TABLE(X)                                                                  \
    X(200, fidelity, int, "", 0, 1, 2, 1, STEWART_MASSLESS,                                      \
      "0 kinematic, 1 massless legs, 2 full 14-body model")                                      \
    X(202, tolerance, double, "1", 2.5e-16, 1, DBL_MAX, 1, MBS_DEFAULT_TOLERANCE,               \
      "Newton residual tolerance (fidelity 2), max-norm, relative to the platform's size "        \
      "max(1 m, the joints' radii, home_height, |pose position|)")                               \
    X(203, max_iterations, int, "", 1, 1, 1000, 1, MBS_DEFAULT_MAX_ITERATIONS,                   \
      "Newton iteration cap (fidelity 2); at most 1000, which bounds a failing solve's time")  \
    X(204, modified_newton, int, "", 0, 1, 1, 1, 0,                                              \
      "0 exact Newton, 1 Jacobian kept over a step (fidelity 2)")                                \
    X(205, warn_condition, double, "1", 1.0, 1, DBL_MAX, 1, 1e3,                                 \
      "Condition number above which the near-singular warning is set")                           \
    X(206, singular_condition, double, "1", 1.0, 1, DBL_MAX, 1, 1e10,                            \
      "Condition number above which the pose is not solved (singular)")

/* Forward kinematics' options (ids 400..: no FMU has them). */
#define STEWART_FORWARD_OPTION_TABLE(X)                                                          \
    X(400, tolerance, double, "m", 2.5e-16, 1, DBL_MAX, 1, MBS_DEFAULT_TOLERANCE,                \
      "max-norm of L(q) - L_measured at which Newton stops")                                     \
    X(401, max_iterations, int, "", 1, 1, 1000, 1, MBS_DEFAULT_MAX_ITERATIONS,                   \
      "Newton iteration cap per start")                                                          \
    X(402, warn_condition, double, "1", 1.0, 1, DBL_MAX, 1, 1e3,                                 \
      "Condition number above which the near-singular warning is set")                           \
    X(403, singular_condition, double, "1", 1.0, 1, DBL_MAX, 1, 1e10,                            \
      "Condition number above which the lengths are not solved (singular)")

/* The plant's (forward dynamics') options: ids 200.. are the StewartPlant FMU's value references,
 * and the descriptions its parameters'. Type long is an integer option too (the FMU's Integer,
 * hence at most 2^31 - 1). stewart_plant_options_check checks these ranges, and that
 * fixed_steps > 0 needs an explicit method. */
#define STEWART_PLANT_OPTION_TABLE(X)                                                            \
    X(200, fidelity, int, "", 1, 1, 2, 1, STEWART_FULL,                                          \
      "1 massless legs (one rigid body), 2 full 14-body model")                                  \
    X(201, method, int, "", 0, 1, 3, 1, STEWART_PLANT_ERK,                                       \
      "Integrator: 0 CVODE Adams, 1 CVODE BDF (dense Jacobian), 2 ARKODE explicit Runge-Kutta "  \
      "4(3), 3 ARKODE explicit Runge-Kutta 5(4)")                                                \
    X(202, relative_tolerance, double, "1", 1e-15, 1, 1.0, 0, 1e-10,                             \
      "Integrator relative tolerance")                                                           \
    X(203, absolute_tolerance, double, "1", 1e-20, 1, DBL_MAX, 1, 1e-12,                         \
      "Integrator absolute tolerance on every state [m, -, m/s, rad/s]")                         \
    X(204, max_internal_steps, long, "", 1, 1, 2147483647, 1, 10000,                             \
      "Integrator steps allowed within one communication step")                                  \
    X(205, fixed_steps, int, "", 0, 1, 1000, 1, 0,                                               \
      "0: adaptive steps (the tolerances); N: N equal explicit Runge-Kutta steps per "           \
      "communication step without error control, the same work every step (methods 2 and 3)")  \
    X(206, input, int, "", 0, 1, 2, 1, STEWART_PLANT_INPUT_FORCE,                                \
      "What drives each leg: 0 force [N] (the drives' parameters unused), 1 motor current [A], " \
      "2 motor voltage [V] (1 and 2 need a drive on every leg)")                                 \
    X(207, smoothing_speed, double, "m/s", 1e-9, 1, 1e3, 1, 1e-4,                               \
      "Leg speed below which the drives' friction and screw losses fade out smoothly (current " \
      "and voltage input)")

/* The linearisation's options (stewart_linearize_options; ids 420..: no FMU has them, the units'
 * derivatives take the unit's own fidelity) and the limits' (stewart_limits_options; ids 430..:
 * the StewartPlatform unit gives its limits its inverse warn_condition, 205), in the form above;
 * table/options.cpp gives them the same calls and checks as the three tables above. */
#define STEWART_LINEARIZE_OPTION_TABLE(X)                                                        \
    X(420, fidelity, int, "", 1, 1, 2, 1, STEWART_FULL,                                          \
      "The plant's fidelity: 1 massless legs (one rigid body), 2 full 14-body model")
#define STEWART_LIMITS_OPTION_TABLE(X)                                                           \
    X(430, warn_condition, double, "1", 1.0, 1, DBL_MAX, 1, 1e3,                                 \
      "Condition number above which a pose fails the condition limit (the inverse option of "    \
      "that name)")

/* The cueing unit's options (stewart_cueing_options; ids 800..: the StewartCueing FMU's value
 * references). The defaults: the classical washout at a moderate tuning (docs/cueing.md), the
 * tilt rate at 3 deg/s, the threshold of tilt perception used in tilt coordination (Groen & Bles
 * 2004, J. Vestib. Res. 14(5): 375-385). */
#define STEWART_CUEING_OPTION_TABLE(X)                                                           \
    X(800, algorithm, int, "", 0, 1, STEWART_CUEING_ALGORITHMS - 1, 1, STEWART_CUEING_CLASSICAL,  \
      "0 classical washout with tilt coordination")                                              \
    X(801, surge_scale, double, "1", 0.0, 1, 10.0, 1, 0.5, "Scale of the specific force x")      \
    X(802, sway_scale, double, "1", 0.0, 1, 10.0, 1, 0.5, "Scale of the specific force y")       \
    X(803, heave_scale, double, "1", 0.0, 1, 10.0, 1, 0.5, "Scale of the specific force z")      \
    X(804, roll_scale, double, "1", 0.0, 1, 10.0, 1, 0.5, "Scale of the roll rate")              \
    X(805, pitch_scale, double, "1", 0.0, 1, 10.0, 1, 0.5, "Scale of the pitch rate")            \
    X(806, yaw_scale, double, "1", 0.0, 1, 10.0, 1, 0.5, "Scale of the yaw rate")                \
    X(807, translation_order, int, "", 2, 1, 3, 1, 3,                                            \
      "Order of the translation's high-pass: 2, or 3 (returns to home after a sustained "        \
      "acceleration)")                                                                           \
    X(808, translation_frequency, double, "rad/s", 0.0, 0, 1e4, 1, 2.5,                          \
      "Break frequency of the translation's second-order high-pass")                             \
    X(809, translation_damping, double, "1", 0.0, 0, 10.0, 1, 1.0,                               \
      "Damping ratio of the translation's second-order high-pass")                               \
    X(810, translation_washout_frequency, double, "rad/s", 0.0, 0, 1e4, 1, 0.5,                  \
      "Break frequency of the translation's first-order high-pass (order 3)")                    \
    X(811, tilt_frequency, double, "rad/s", 0.0, 0, 1e4, 1, 2.0,                                 \
      "Break frequency of the tilt coordination's second-order low-pass")                        \
    X(812, tilt_damping, double, "1", 0.0, 0, 10.0, 1, 1.0,                                      \
      "Damping ratio of the tilt coordination's low-pass")                                       \
    X(813, tilt_max, double, "rad", 0.0, 1, STEWART_DEG(60.0), 1, STEWART_DEG(15.0),             \
      "Largest tilt angle of the tilt coordination")                                             \
    X(814, tilt_rate_max, double, "rad/s", 0.0, 1, STEWART_PI, 1, STEWART_DEG(3.0),              \
      "Largest tilt rate (below the tilt perception threshold, about 3 deg/s)")                  \
    X(815, rotation_filter_order, int, "", 1, 1, 2, 1, 2,                                        \
      "Order of the rotation's high-pass: 1, or 2 (returns to home after a sustained rate)")     \
    X(816, rotation_frequency, double, "rad/s", 0.0, 0, 1e4, 1, 1.0,                             \
      "Break frequency of the rotation's high-pass")                                             \
    X(817, rotation_damping, double, "1", 0.0, 0, 10.0, 1, 1.0,                                  \
      "Damping ratio of the rotation's high-pass (order 2)")                                     \
    X(818, head_x, double, "m", -1e3, 1, 1e3, 1, 0.0, "Head position x in the platform frame")   \
    X(819, head_y, double, "m", -1e3, 1, 1e3, 1, 0.0, "Head position y in the platform frame")   \
    X(820, head_z, double, "m", -1e3, 1, 1e3, 1, 0.0, "Head position z in the platform frame")   \
    X(821, limiter_rate, double, "1/s", 0.0, 0, 1e6, 1, 5.0,                                     \
      "Largest rate at which the limiter's scale of the excursion changes smoothly")             \
    X(822, limiter_lookahead, double, "s", 0.0, 1, 10.0, 1, 0.5,                                 \
      "How far ahead the limiter extrapolates the excursion to scale it down in time")           \
    X(823, limiter_accel, double, "1/s2", 0.0, 0, 1e9, 1, 50.0,                                  \
      "Largest acceleration of the limiter's scale while it moves smoothly")                     \
    X(824, warn_condition, double, "1", 1.0, 1, DBL_MAX, 1, 1e3,                                 \
      "Condition number above which a pose fails the condition limit (the limits' option)")
/* clang-format on */

/* One parameter of the table, for iteration. */
typedef struct stewart_param_info {
    int id;                     /* stable id of element 0; element e has id + e */
    const char *name;           /* field name, e.g. "base_angle" */
    int count;                  /* elements: 1, 3 (x, y, z), 6 (legs 1..6, or a pose), 18 */
    const char *unit;           /* SI unit (a pose's: STEWART_POSE_UNIT) */
    const char *display_unit;   /* "deg" for angles (and a pose's angles), else "" */
    const char *description;    /* of the whole parameter (see stewart_param_element_text) */
    double min, max;            /* valid range of each element */
    int min_closed, max_closed; /* 1: the end is part of the range */
    const double *defaults;     /* count values: the thesis platform */
} stewart_param_info;

/* Number of parameters (fields of stewart_params). */
int stewart_param_count(void);
/* Parameter i (0 <= i < stewart_param_count(), declaration order), or NULL. */
const stewart_param_info *stewart_param(int i);
/* Address of element e of parameter i in params, or NULL if i, e or params are out of range.
 * Cast a const stewart_params * to read only. */
double *stewart_param_element(stewart_params *params, int i, int e);
/* The parameter holding the element named `name` ("payload_mass", "base_angle[2]": arrays
 * counted from 1), with that element in *element; -1 if no element has that name. */
int stewart_param_find(const char *name, int *element);
/* The parameter whose elements include the stable id `id`, with the element in *element; -1. */
int stewart_param_find_id(int id, int *element);
/* Element e's name ("base_angle[2]") or description ("... of leg 2") into text; the length it
 * needs (as snprintf), or -1 if i or e are out of range. */
int stewart_param_element_name(int i, int e, char *text, size_t size);
int stewart_param_element_description(int i, int e, char *text, size_t size);
/* Element e's SI unit and display unit ("deg" or ""): the parameter's, or for a pose "m" and ""
 * (x, y, z), "rad" and "deg" (roll, pitch, yaw); NULL if i or e are out of range. */
const char *stewart_param_element_unit(int i, int e);
const char *stewart_param_element_display_unit(int i, int e);
/* 1 if parameter i is per leg and a single value given by its bare name ("stroke_min") fills all
 * six legs (stewart_params_set, --param, Python keywords, platform files); else 0. */
int stewart_param_fills_from_scalar(int i);
/* STEWART_OK if value is in element e of parameter i's range, else STEWART_ERR_PARAMETER and a
 * message naming the element and the value with all its digits (cross-field checks are
 * stewart_params_check's). */
stewart_status stewart_param_check_value(int i, int e, double value, char *message, size_t size);

/* One option of the table. */
typedef struct stewart_option_info {
    int id;           /* stable id (= FMU value reference) */
    const char *name; /* field name in its options struct */
    int is_integer;   /* 1: an int or long field, 0: a double */
    const char *unit; /* "1" for dimensionless reals, "" for integers */
    const char *description;
    double min, max; /* valid range */
    int min_closed, max_closed;
    double default_value; /* the default (stewart_*_options_default's) */
} stewart_option_info;

/* The options of the inverse solver (STEWART_OPTION_TABLE), of forward kinematics
 * (STEWART_FORWARD_OPTION_TABLE) and of the plant (STEWART_PLANT_OPTION_TABLE), the same calls
 * for each: how many; option i (declaration order) or NULL; option i's value in options (ints
 * converted exactly; 0 if out of range); set option i (STEWART_ERR_PARAMETER, options
 * unchanged, if the value is outside its range or, for an integer option, not a whole number);
 * the option named `name`, or -1. */
int stewart_inverse_option_count(void);
const stewart_option_info *stewart_inverse_option(int i);
double stewart_inverse_option_get(const stewart_inverse_options *options, int i);
stewart_status stewart_inverse_option_set(stewart_inverse_options *options, int i, double value,
                                          char *message, size_t size);
int stewart_inverse_option_find(const char *name);

int stewart_forward_option_count(void);
const stewart_option_info *stewart_forward_option(int i);
double stewart_forward_option_get(const stewart_forward_options *options, int i);
stewart_status stewart_forward_option_set(stewart_forward_options *options, int i, double value,
                                          char *message, size_t size);
int stewart_forward_option_find(const char *name);

int stewart_plant_option_count(void);
const stewart_option_info *stewart_plant_option(int i);
double stewart_plant_option_get(const stewart_plant_options *options, int i);
stewart_status stewart_plant_option_set(stewart_plant_options *options, int i, double value,
                                        char *message, size_t size);
int stewart_plant_option_find(const char *name);

/* The same for the linearisation's (STEWART_LINEARIZE_OPTION_TABLE), the limits' options
 * (STEWART_LIMITS_OPTION_TABLE) and the cueing unit's (STEWART_CUEING_OPTION_TABLE). */
int stewart_linearize_option_count(void);
const stewart_option_info *stewart_linearize_option(int i);
double stewart_linearize_option_get(const stewart_linearize_options *options, int i);
stewart_status stewart_linearize_option_set(stewart_linearize_options *options, int i, double value,
                                            char *message, size_t size);
int stewart_linearize_option_find(const char *name);

int stewart_limits_option_count(void);
const stewart_option_info *stewart_limits_option(int i);
double stewart_limits_option_get(const stewart_limits_options *options, int i);
stewart_status stewart_limits_option_set(stewart_limits_options *options, int i, double value,
                                         char *message, size_t size);
int stewart_limits_option_find(const char *name);

int stewart_cueing_option_count(void);
const stewart_option_info *stewart_cueing_option(int i);
double stewart_cueing_option_get(const stewart_cueing_options *options, int i);
stewart_status stewart_cueing_option_set(stewart_cueing_options *options, int i, double value,
                                         char *message, size_t size);
int stewart_cueing_option_find(const char *name);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_TABLE_H */
