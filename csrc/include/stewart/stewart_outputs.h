/*
 * The output tables: one entry per column of a direction's output, in the order of its batch
 * output struct. Adding an output is its field in the output struct (stewart.h,
 * stewart_forward.h) and one line here: the batch output struct, the batch's row writer and the
 * check that the table covers the struct are expanded from these lists.
 *
 * STEWART_INVERSE_OUTPUT_TABLE(X), STEWART_FORWARD_OUTPUT_TABLE(X), STEWART_PLANT_OUTPUT_TABLE(X)
 * and STEWART_PLANT_STEP_TABLE(X) call
 *   X(name, member, count, type, unit, description)
 * once per column:
 *   name         the column's name (the batch output field, the Python result's array)
 *   member       its place in the output struct (stewart_inverse_output, stewart_forward_output,
 *                stewart_plant_output; the plant's step table: stewart_plant_statistics)
 *   count        values per row: 1, 3 (x, y, z), 6 (legs 1..6 or x, y, z, roll, pitch, yaw)
 *   type         double, int or long
 *   unit         SI unit ("1" dimensionless, "" for integers and bit sets)
 *   description  one sentence
 */
#ifndef STEWART_STEWART_OUTPUTS_H
#define STEWART_STEWART_OUTPUTS_H

/* The tables are laid out by hand, one entry a line (not formatted). */
/* clang-format off */
#define STEWART_INVERSE_OUTPUT_TABLE(X)                                                          \
    X(length, lengths.length, 6, double, "m", "Actuator length L_k")                             \
    X(length_rate, lengths.length_rate, 6, double, "m/s", "dL_k/dt")                             \
    X(length_accel, lengths.length_accel, 6, double, "m/s2", "d2L_k/dt2")                        \
    X(force, force, 6, double, "N", "Actuator force F_k, > 0 pushes the platform away")          \
    X(condition, condition, 1, double, "1", "Leg Jacobian condition number")                     \
    X(residual, residual, 1, double, "m", "Constraint residual after the solve (full level)")     \
    X(base_force, base_force, 3, double, "N", "Force the legs put on the base, world frame")     \
    X(base_torque, base_torque, 3, double, "N.m", "Its torque about the world origin")           \
    X(iterations, iterations, 1, int, "", "Newton iterations of the position problem")           \
    X(warnings, warnings, 1, int, "", "STEWART_WARN_* bits")                                     \
    X(stroke_legs, stroke_legs, 1, int, "", "Bit k set: leg k+1 is outside the stroke")       \
    STEWART_INVERSE_DRIVE_OUTPUT_TABLE(X)

/* The inverse's drive columns (docs/drives.md), the last of its table: 0 on a leg without a
 * drive. */
#define STEWART_INVERSE_DRIVE_OUTPUT_TABLE(X)                                                    \
    X(motor_angle, motor_angle, 6, double, "rad", "Motor angle 2 pi N L_k / lead")               \
    X(motor_speed, motor_speed, 6, double, "rad/s", "Motor speed")                               \
    X(motor_accel, motor_accel, 6, double, "rad/s2", "Motor acceleration")                       \
    X(motor_torque, motor_torque, 6, double, "N.m",                                              \
      "Motor torque: drive inertia, leg force and friction through the screw")                   \
    X(current, current, 6, double, "A", "Motor current, motor_torque / torque_constant")         \
    X(current_rate, current_rate, 6, double, "A/s",                                              \
      "dI/dt: 0 from one pose, differences along a trajectory")                                  \
    X(voltage, voltage, 6, double, "V", "Motor voltage R I + L dI/dt + k_t motor_speed")         \
    X(electrical_power, electrical_power, 6, double, "W", "voltage x current, < 0 regenerating") \
    X(motor_power, motor_power, 6, double, "W", "motor_torque x motor_speed")                    \
    X(current_max_legs, current_max_legs, 1, int, "", "Bit k set: leg k+1 is over current_max")  \
    X(voltage_max_legs, voltage_max_legs, 1, int, "", "Bit k set: leg k+1 is over voltage_max")  \
    X(motor_speed_max_legs, motor_speed_max_legs, 1, int, "",                                    \
      "Bit k set: leg k+1 is over motor_speed_max")

#define STEWART_FORWARD_OUTPUT_TABLE(X)                                                          \
    X(pose, pose.q, 6, double, "m, rad", "Pose (x, y, z, roll, pitch, yaw)")                     \
    X(pose_rate, pose.q_dot, 6, double, "m/s, rad/s", "d/dt of the pose (0 unless rates given)") \
    X(pose_accel, pose.q_ddot, 6, double, "m/s2, rad/s2",                                        \
      "d2/dt2 of the pose (0 unless accelerations given)")                                       \
    X(residual, residual, 1, double, "m", "max |L_k(q) - L_k measured| at the last iterate")     \
    X(condition, condition, 1, double, "1", "Leg Jacobian condition number")                     \
    X(jump, jump, 1, double, "m", "Largest platform-point move from the last pose")              \
    X(iterations, iterations, 1, int, "", "Newton iterations over every start tried")            \
    X(warnings, warnings, 1, int, "", "STEWART_WARN_* bits")                                     \
    X(branch, branch, 1, int, "", "STEWART_BRANCH_* bits (why a pose is on another mode)")       \
    X(start, start, 1, int, "", "STEWART_START_* the pose was reached from")                     \
    X(stroke_legs, stroke_legs, 1, int, "", "Bit k set: measured length k+1 is outside the stroke")

/* The plant's columns: those of stewart_plant_output a plant batch row holds (its time is the
 * row's, and the plant gives no accelerations), then the statistics of the step into the row. */
#define STEWART_PLANT_OUTPUT_TABLE(X)                                                            \
    X(pose, pose.q, 6, double, "m, rad", "Pose (x, y, z, roll, pitch, yaw)")                     \
    X(pose_rate, pose.q_dot, 6, double, "m/s, rad/s", "d/dt of the pose")                        \
    X(length, lengths.length, 6, double, "m", "Actuator length L_k")                             \
    X(length_rate, lengths.length_rate, 6, double, "m/s", "dL_k/dt")                             \
    X(base_force, base_force, 3, double, "N", "Force the moving bodies put on the base, world frame") \
    X(base_torque, base_torque, 3, double, "N.m", "Its torque about the world origin")           \
    X(warnings, warnings, 1, int, "", "STEWART_WARN_* bits")                                     \
    X(stroke_legs, stroke_legs, 1, int, "", "Bit k set: leg k+1 is outside the stroke")         \
    X(force, force, 6, double, "N", "Actuator force F_k on the mechanism, > 0 extends")           \
    X(current, current, 6, double, "A", "Motor current (0 with force input)")                    \
    X(voltage, voltage, 6, double, "V", "Motor voltage: the input, or R i + k_t omega (current)") \
    X(motor_speed, motor_speed, 6, double, "rad/s", "Motor speed 2 pi N L_dot / lead")           \
    X(motor_torque, motor_torque, 6, double, "N.m", "Motor torque k_t i")                        \
    X(electrical_power, electrical_power, 6, double, "W", "Voltage times current, < 0 regenerates") \
    X(current_max_legs, current_max_legs, 1, int, "", "Bit k set: leg k+1 above current_max") \
    X(voltage_max_legs, voltage_max_legs, 1, int, "", "Bit k set: leg k+1 above voltage_max") \
    X(motor_speed_max_legs, motor_speed_max_legs, 1, int, "", "Bit k set: leg k+1 above motor_speed_max")

#define STEWART_PLANT_STEP_TABLE(X)                                                              \
    X(steps, steps, 1, long, "", "Internal integrator steps of the step into the row")           \
    X(rhs_evaluations, rhs_evaluations, 1, long, "", "Right-hand side evaluations of that step") \
    X(nonlinear_iterations, nonlinear_iterations, 1, long, "", "Nonlinear iterations of that step") \
    X(error_test_failures, error_test_failures, 1, long, "", "Error test failures of that step")
/* clang-format on */

#endif /* STEWART_STEWART_OUTPUTS_H */
