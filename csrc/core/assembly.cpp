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

// Joint k's input, from its record; its bodies' frames from `frames` (every body's), else formed
// into fi and fj.
[[gnu::always_inline]] inline JointInput joint_input(const JointDef &j, const JointRecord &r,
                                                     const double *q, const double *q_dot,
                                                     const DriverValue *drv,
                                                     const BodyFrame *frames, BodyFrame &fi,
                                                     BodyFrame &fj) {
    const double *qi = q + r.coord_i, *qj = r.coord_j >= 0 ? q + r.coord_j : nullptr;
    const double *vi = q_dot ? q_dot + r.coord_i : nullptr;
    const double *vj = (q_dot && r.coord_j >= 0) ? q_dot + r.coord_j : nullptr;
    const BodyFrame *pi = nullptr, *pj = nullptr;
    if (r.frames) {
        if (frames) {
            pi = frames + j.body_i, pj = frames + j.body_j;
        } else {
            make_frame(qi, vi, fi);
            make_frame(qj, vj, fj);
            pi = &fi, pj = &fj;
        }
    }
    return JointInput{j, qi, qj, vi, vj, r.driver >= 0 ? drv + r.driver : nullptr, pi, pj};
}

[[gnu::always_inline]] inline void evaluate_with_frames(const JointDef &j, const JointRecord &r,
                                                        const double *q, const double *q_dot,
                                                        const DriverValue *drv,
                                                        const JointOutput &out,
                                                        const BodyFrame *frames) {
    BodyFrame fi, fj;
    r.evaluate(joint_input(j, r, q, q_dot, drv, frames, fi, fj), out);
}

// Calls output(record) for the outputs of each joint and evaluates every joint.
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
    const JointRecord *const records = m.joint_records.data();
    for (size_t k = 0; k < joints; ++k) {
        const JointRecord &r = records[k];
        switch (path[k]) {
            case AssemblyPath::Own:
                evaluate_with_frames(defs[k], r, q, q_dot, drv, output(r), frames);
                break;
            case AssemblyPath::Normalization: {
                const int p = r.coord_i + MBS_BODY_P(0);  // its Euler parameters, after r
                normalization_rows(q + p, q_dot ? q_dot + p : nullptr, output(r));
                break;
            }
            case AssemblyPath::WithDistance: {
                BodyFrame fi, fj, di, dj;
                const int driver = distance_with[k];
                const JointRecord &rd = records[driver];
                evaluate_cylindrical_with_distance(
                    joint_input(defs[k], r, q, q_dot, drv, frames, fi, fj), output(r),
                    joint_input(defs[driver], rd, q, q_dot, drv, frames, di, dj), output(rd));
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
    evaluate_with_frames(m.joints[k], m.joint_records[k], q, q_dot, drv, out, nullptr);
}

void assemble_residual(const Mechanism &m, const double *q, const DriverValue *drv, double *phi) {
    assemble(m, q, nullptr, drv, [&](const JointRecord &r) {
        return JointOutput{phi + r.first_row, nullptr, nullptr, nullptr, nullptr};
    });
}

namespace {
JointOutput jacobian_blocks(const JointRecord &r, double *values, double *phi) {
    double *block = values + r.first_value;
    double *block_j = r.block_j >= 0 ? block + r.block_j : nullptr;
    return JointOutput{phi ? phi + r.first_row : nullptr, block, block_j, nullptr, nullptr};
}
}  // namespace

void assemble_jacobian(const Mechanism &m, const double *q, const DriverValue *drv,
                       double *values) {
    assemble(m, q, nullptr, drv,
             [&](const JointRecord &r) { return jacobian_blocks(r, values, nullptr); });
}

void assemble_residual_and_jacobian(const Mechanism &m, const double *q, const DriverValue *drv,
                                    double *phi, double *values) {
    assemble(m, q, nullptr, drv,
             [&](const JointRecord &r) { return jacobian_blocks(r, values, phi); });
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
    assemble(m, q, q_dot, drv, [&](const JointRecord &r) {
        return JointOutput{nullptr, nullptr, nullptr, nullptr, gamma + r.first_row};
    });
}

}  // namespace mbs
