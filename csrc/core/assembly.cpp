#include "core/assembly.hpp"

#include <algorithm>

namespace mbs {

namespace {

void make_frame(const double *q, const double *v, BodyFrame &f) {
    f.A = rotation(q + 3);
    if (v) {
        f.rate = 2.0 * bilinear_matrix(q + 3, v + 3);
        f.quad = 2.0 * rotation(v + 3);
    }
}

}  // namespace

void evaluate_joint(const Mechanism &m, int k, const double *q, const double *q_dot,
                    const DriverValue *drv, const JointOutput &out) {
    const JointDef &j = m.joints[k];
    const JointTypeInfo &info = joint_type(j.type);
    const double *qi = q + 7 * j.body_i, *qj = j.body_j >= 0 ? q + 7 * j.body_j : nullptr;
    const double *vi = q_dot ? q_dot + 7 * j.body_i : nullptr;
    const double *vj = (q_dot && j.body_j >= 0) ? q_dot + 7 * j.body_j : nullptr;
    BodyFrame fi, fj;
    if (info.bodies == 2) {
        make_frame(qi, vi, fi);
        make_frame(qj, vj, fj);
    }
    const JointInput in{j, qi, qj, vi, vj, j.driver >= 0 ? drv + j.driver : nullptr,
                        info.bodies == 2 ? &fi : nullptr, info.bodies == 2 ? &fj : nullptr};
    info.evaluate(in, out);
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
