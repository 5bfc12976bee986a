// stewart._core's linearisation (linearize.py): the plant's A, B, C, D and the inverse side's
// Jacobian at one point, into arrays Python makes.
#include "_core.hpp"

namespace stewart_core {

namespace {

// A linearisation of model at fidelity from the model's pool, or ValueError with the library's
// message. Used with the GIL held throughout.
struct Linearization {
    Linearization(const Model &model, int fidelity) : lease(model.linearize_pool(), fidelity) {
        if (lease.solver) return;
        stewart_linearize_options o;
        stewart_linearize_options_default(&o);
        o.fidelity = fidelity;
        char message[STEWART_MESSAGE_SIZE];
        lease.solver = stewart_linearize_create(model.get(), &o, message, sizeof message);
        if (!lease.solver) fail(message);
    }
    Lease<stewart_linearize, int> lease;
};

// A result array of a linearisation, of a fixed shape, which the caller makes.
template <size_t... Shape>
using Fixed = nb::ndarray<double, nb::shape<Shape...>, nb::c_contig, nb::device::cpu>;

// Copies the n values at first into a (of n values).
template <typename Array>
void put(const double *first, Array &a) {
    std::copy_n(first, a.size(), a.data());
}

// Platform.linearize's call, into the caller's arrays: (status, message, warnings).
std::tuple<int, std::string, int> linearize_plant(
    const Model &model, int fidelity, const std::vector<double> &q,
    const std::vector<double> &q_dot, const std::vector<double> &force, Fixed<12> state_rate,
    Fixed<24> output, Fixed<12, 12> A, Fixed<12, 6> B, Fixed<24, 12> C, Fixed<24, 6> D) {
    if (q.size() != 6 || q_dot.size() != 6 || force.size() != 6)
        fail("linearize: pose, pose_rate and forces need 6 values each");
    Linearization l(model, fidelity);
    stewart_linearize_input in{};
    std::copy(q.begin(), q.end(), in.pose.q);
    std::copy(q_dot.begin(), q_dot.end(), in.pose.q_dot);
    std::copy(force.begin(), force.end(), in.force);
    stewart_linearize_output out{};
    const stewart_status s = stewart_linearize_plant(l.lease.solver, &in, &out);
    put(out.state_rate, state_rate);
    put(out.output, output);
    put(&out.A[0][0], A);
    put(&out.B[0][0], B);
    put(&out.C[0][0], C);
    put(&out.D[0][0], D);
    return {static_cast<int>(s), stewart_linearize_message(l.lease.solver), out.warnings};
}

// Platform.linearize_inverse's call, into the caller's arrays (L, L_dot, L_ddot, force,
// base_force, base_torque, jacobian): (status, message, warnings).
std::tuple<int, std::string, int> linearize_inverse(
    const Model &model, int fidelity, const std::vector<double> &q,
    const std::vector<double> &q_dot, const std::vector<double> &q_ddot, Fixed<6> length,
    Fixed<6> length_rate, Fixed<6> length_accel, Fixed<6> force, Fixed<3> base_force,
    Fixed<3> base_torque, Fixed<30, 18> jacobian) {
    if (q.size() != 6 || q_dot.size() != 6 || q_ddot.size() != 6)
        fail("linearize_inverse: pose, pose_rate and pose_accel need 6 values each");
    Linearization l(model, fidelity);
    stewart_pose pose{};
    std::copy(q.begin(), q.end(), pose.q);
    std::copy(q_dot.begin(), q_dot.end(), pose.q_dot);
    std::copy(q_ddot.begin(), q_ddot.end(), pose.q_ddot);
    stewart_linearize_inverse_output out{};
    const stewart_status s = stewart_linearize_inverse(l.lease.solver, &pose, &out);
    put(out.lengths.length, length);
    put(out.lengths.length_rate, length_rate);
    put(out.lengths.length_accel, length_accel);
    put(out.force, force);
    put(out.base_force, base_force);
    put(out.base_torque, base_torque);
    put(&out.jacobian[0][0], jacobian);
    return {static_cast<int>(s), stewart_linearize_message(l.lease.solver), out.warnings};
}

// Platform.linearize's call with current or voltage input, into the caller's arrays:
// (status, message, warnings, states, not_smooth_legs).
std::tuple<int, std::string, int, int, int> linearize_driven(
    const Model &model, int fidelity, int input, std::optional<double> smoothing_speed,
    const std::vector<double> &q, const std::vector<double> &q_dot,
    const std::vector<double> &inputs, const std::vector<double> &current, Fixed<18> state_rate,
    Fixed<24> output, Fixed<18, 18> A, Fixed<18, 6> B, Fixed<24, 18> C, Fixed<24, 6> D,
    Fixed<6> leg_force) {
    if (q.size() != 6 || q_dot.size() != 6 || inputs.size() != 6 || current.size() != 6)
        fail("linearize: pose, pose_rate, inputs and currents need 6 values each");
    Linearization l(model, fidelity);
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = fidelity;
    o.input = input;
    if (smoothing_speed) o.smoothing_speed = *smoothing_speed;  // else the plant's default
    stewart_linearize_driven_input in{};
    std::copy(q.begin(), q.end(), in.pose.q);
    std::copy(q_dot.begin(), q_dot.end(), in.pose.q_dot);
    std::copy(inputs.begin(), inputs.end(), in.input);
    std::copy(current.begin(), current.end(), in.current);
    stewart_linearize_driven_output out{};
    const stewart_status s = stewart_linearize_driven(l.lease.solver, &o, &in, &out);
    put(out.state_rate, state_rate);
    put(out.output, output);
    put(&out.A[0][0], A);
    put(&out.B[0][0], B);
    put(&out.C[0][0], C);
    put(&out.D[0][0], D);
    put(out.leg_force, leg_force);
    return {static_cast<int>(s), stewart_linearize_message(l.lease.solver), out.warnings,
            out.states, out.not_smooth_legs};
}

}  // namespace

void bind_linearize(nb::module_ &m) {
    m.def("linearize_plant", &linearize_plant, nb::arg("model"), nb::arg("fidelity"), nb::arg("q"),
          nb::arg("q_dot"), nb::arg("force"), nb::arg("state_rate"), nb::arg("output"),
          nb::arg("A"), nb::arg("B"), nb::arg("C"), nb::arg("D"));
    m.def("linearize_driven", &linearize_driven, nb::arg("model"), nb::arg("fidelity"),
          nb::arg("input"), nb::arg("smoothing_speed"), nb::arg("q"), nb::arg("q_dot"),
          nb::arg("inputs"), nb::arg("current"), nb::arg("state_rate"), nb::arg("output"),
          nb::arg("A"), nb::arg("B"), nb::arg("C"), nb::arg("D"), nb::arg("leg_force"));
    m.def("linearize_inverse", &linearize_inverse, nb::arg("model"), nb::arg("fidelity"),
          nb::arg("q"), nb::arg("q_dot"), nb::arg("q_ddot"), nb::arg("length"),
          nb::arg("length_rate"), nb::arg("length_accel"), nb::arg("force"), nb::arg("base_force"),
          nb::arg("base_torque"), nb::arg("jacobian"));
}

}  // namespace stewart_core
