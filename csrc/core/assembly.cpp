#include "core/assembly.hpp"

#include <algorithm>

namespace mbs {

void evaluate_joint(const Mechanism &m, int k, const double *q, const double *q_dot,
                    const DriverValue *drv, const JointOutput &out) {
    const JointDef &j = m.joints[k];
    const JointInput in{j,
                        q + 7 * j.body_i,
                        j.body_j >= 0 ? q + 7 * j.body_j : nullptr,
                        q_dot ? q_dot + 7 * j.body_i : nullptr,
                        (q_dot && j.body_j >= 0) ? q_dot + 7 * j.body_j : nullptr,
                        j.driver >= 0 ? drv + j.driver : nullptr};
    joint_type(j.type).evaluate(in, out);
}

void assemble_residual(const Mechanism &m, const double *q, const DriverValue *drv, double *phi) {
    for (size_t k = 0; k < m.joints.size(); ++k)
        evaluate_joint(m, static_cast<int>(k), q, nullptr, drv,
                       JointOutput{phi + m.first_row[k], nullptr, nullptr, nullptr, nullptr});
}

void assemble_jacobian(const Mechanism &m, const double *q, const DriverValue *drv,
                       double *values) {
    for (size_t k = 0; k < m.joints.size(); ++k) {
        double *block = values + m.first_value[k];
        const int n = joint_type(m.joints[k].type).equations;
        double *block_j = m.joints[k].body_j >= 0 ? block + 7 * n : nullptr;
        evaluate_joint(m, static_cast<int>(k), q, nullptr, drv,
                       JointOutput{nullptr, block, block_j, nullptr, nullptr});
    }
}

void assemble_residual_and_jacobian(const Mechanism &m, const double *q, const DriverValue *drv,
                                    double *phi, double *values) {
    for (size_t k = 0; k < m.joints.size(); ++k) {
        double *block = values + m.first_value[k];
        const int n = joint_type(m.joints[k].type).equations;
        double *block_j = m.joints[k].body_j >= 0 ? block + 7 * n : nullptr;
        evaluate_joint(m, static_cast<int>(k), q, nullptr, drv,
                       JointOutput{phi + m.first_row[k], block, block_j, nullptr, nullptr});
    }
}

void assemble_phi_t(const Mechanism &m, const double *q, const DriverValue *drv, double *phi_t) {
    for (size_t k = 0; k < m.joints.size(); ++k) {
        const JointTypeInfo &info = joint_type(m.joints[k].type);
        if (info.drivers == 0) {  // only drivers depend on time
            std::fill(phi_t + m.first_row[k], phi_t + m.first_row[k] + info.equations, 0.0);
            continue;
        }
        evaluate_joint(m, static_cast<int>(k), q, nullptr, drv,
                       JointOutput{nullptr, nullptr, nullptr, phi_t + m.first_row[k], nullptr});
    }
}

void assemble_gamma(const Mechanism &m, const double *q, const double *q_dot,
                    const DriverValue *drv, double *gamma) {
    for (size_t k = 0; k < m.joints.size(); ++k)
        evaluate_joint(m, static_cast<int>(k), q, q_dot, drv,
                       JointOutput{nullptr, nullptr, nullptr, nullptr, gamma + m.first_row[k]});
}

}  // namespace mbs
