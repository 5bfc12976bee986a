#include "core/assembly.hpp"

#include <algorithm>

#include "core/euler_pairs.hpp"
#include "core/joints/primitives.hpp"

namespace mbs {

namespace {

void make_frame(const double *q, const double *v, BodyFrame &f) {
    f.A = rotation(q + 3);
    if (v) {
        f.rate = 2.0 * bilinear_matrix(q + 3, v + 3);
        f.quad = 2.0 * rotation(v + 3);
    }
}

// Frames of every body, formed once per pass (on the stack: no allocation in a step); larger
// mechanisms form them per joint instead.
constexpr size_t kFrameCache = 64;

// Joint k's input; its bodies' frames from `frames` (every body's), else formed into fi and fj.
[[gnu::always_inline]] inline JointInput joint_input(const Mechanism &m, int k, const double *q,
                                                     const double *q_dot, const DriverValue *drv,
                                                     const BodyFrame *frames, BodyFrame &fi,
                                                     BodyFrame &fj) {
    const JointDef &j = m.joints[k];
    const double *qi = body_r(q, j.body_i), *qj = j.body_j >= 0 ? body_r(q, j.body_j) : nullptr;
    const double *vi = q_dot ? body_r(q_dot, j.body_i) : nullptr;
    const double *vj = (q_dot && j.body_j >= 0) ? body_r(q_dot, j.body_j) : nullptr;
    const BodyFrame *pi = nullptr, *pj = nullptr;
    if (m.joint_info[k]->bodies == 2) {
        if (frames) {
            pi = frames + j.body_i, pj = frames + j.body_j;
        } else {
            make_frame(qi, vi, fi);
            make_frame(qj, vj, fj);
            pi = &fi, pj = &fj;
        }
    }
    return JointInput{j, qi, qj, vi, vj, j.driver >= 0 ? drv + j.driver : nullptr, pi, pj};
}

[[gnu::always_inline]] inline void evaluate_with_frames(const Mechanism &m, int k,
                                                       const double *q, const double *q_dot,
                                                       const DriverValue *drv,
                                                       const JointOutput &out,
                                                       const BodyFrame *frames) {
    BodyFrame fi, fj;
    m.joint_info[k]->evaluate(joint_input(m, k, q, q_dot, drv, frames, fi, fj), out);
}

// Calls output(k) for the outputs of joint k and evaluates every joint.
template <class Outputs>
void assemble(const Mechanism &m, const double *q, const double *q_dot, const DriverValue *drv,
              Outputs output) {
    BodyFrame cache[kFrameCache];
    const bool cached = m.bodies.size() <= kFrameCache;
    size_t b = 0;
    if (cached && !q_dot)  // rotations only: two bodies at a time, in the lanes of a vector
        for (; b + 2 <= m.bodies.size(); b += 2)
            rotation_two(body_p(q, b), body_p(q, b + 1), cache[b].A, cache[b + 1].A);
    if (cached)
        for (; b < m.bodies.size(); ++b)
            make_frame(body_r(q, b), q_dot ? body_r(q_dot, b) : nullptr, cache[b]);
    const BodyFrame *frames = cached ? cache : nullptr;
    // Read once: the joints' calls could write anywhere for all the compiler knows, and it
    // reloaded the count and these arrays per joint.
    const size_t joints = m.joints.size();
    const AssemblyPath *const path = m.assembly_path.data();
    const int *const distance_with = m.distance_with.data();
    const JointDef *const defs = m.joints.data();
    for (size_t k = 0; k < joints; ++k) {
        switch (path[k]) {
        case AssemblyPath::Own:
            evaluate_with_frames(m, static_cast<int>(k), q, q_dot, drv, output(k), frames);
            break;
        case AssemblyPath::Normalization: {
            const int b = defs[k].body_i;
            normalization_rows(body_p(q, b), q_dot ? body_p(q_dot, b) : nullptr, output(k));
            break;
        }
        case AssemblyPath::WithDistance: {
            BodyFrame fi, fj, di, dj;
            const int driver = distance_with[k];
            evaluate_cylindrical_with_distance(
                joint_input(m, static_cast<int>(k), q, q_dot, drv, frames, fi, fj), output(k),
                joint_input(m, driver, q, q_dot, drv, frames, di, dj), output(driver));
            break;
        }
        case AssemblyPath::InJointCall:  // its cylindrical joint's call writes it
            break;
        }
    }
}

}  // namespace

void evaluate_joint(const Mechanism &m, int k, const double *q, const double *q_dot,
                    const DriverValue *drv, const JointOutput &out) {
    evaluate_with_frames(m, k, q, q_dot, drv, out, nullptr);
}

void assemble_residual(const Mechanism &m, const double *q, const DriverValue *drv, double *phi) {
    assemble(m, q, nullptr, drv, [&](size_t k) {
        return JointOutput{phi + m.first_row[k], nullptr, nullptr, nullptr, nullptr};
    });
}

namespace {
JointOutput jacobian_blocks(const Mechanism &m, size_t k, double *values, double *phi) {
    double *block = values + m.first_value[k];
    const int n = m.joint_info[k]->equations;
    double *block_j = m.joints[k].body_j >= 0 ? block + MBS_BODY_COORDINATES * n : nullptr;
    return JointOutput{phi ? phi + m.first_row[k] : nullptr, block, block_j, nullptr, nullptr};
}
}  // namespace

void assemble_jacobian(const Mechanism &m, const double *q, const DriverValue *drv,
                       double *values) {
    assemble(m, q, nullptr, drv,
             [&](size_t k) { return jacobian_blocks(m, k, values, nullptr); });
}

void assemble_residual_and_jacobian(const Mechanism &m, const double *q, const DriverValue *drv,
                                    double *phi, double *values) {
    assemble(m, q, nullptr, drv, [&](size_t k) { return jacobian_blocks(m, k, values, phi); });
}

void assemble_phi_t(const Mechanism &m, const double *q, const DriverValue *drv, double *phi_t) {
    for (size_t k = 0; k < m.joints.size(); ++k) {
        const JointTypeInfo &info = *m.joint_info[k];
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
    assemble(m, q, q_dot, drv, [&](size_t k) {
        return JointOutput{nullptr, nullptr, nullptr, nullptr, gamma + m.first_row[k]};
    });
}

}  // namespace mbs
