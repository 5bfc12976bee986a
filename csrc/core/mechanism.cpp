#include "core/mechanism.hpp"

#include <algorithm>

#include "core/linear_solver.hpp"
#include "core/message.hpp"

namespace mbs {

void place_at_reference(const Mechanism &m, double *q) {
    for (size_t b = 0; b < m.bodies.size(); ++b)
        std::copy(m.bodies[b].q_reference, m.bodies[b].q_reference + MBS_BODY_COORDINATES,
                  body_r(q, b));
}

namespace {

// Pairs each distance driver with a cylindrical joint on the same bodies and points, so that
// assembly evaluates the two in one call (evaluate_cylindrical_with_distance); normalisations are
// written inline.
void make_joint_records(Mechanism &m) {
    m.joint_records.clear();
    for (size_t k = 0; k < m.joints.size(); ++k) {
        const JointDef &j = m.joints[k];
        const JointTypeInfo &info = *m.joint_info[k];
        const bool has_j = j.body_j >= 0;
        m.joint_records.push_back(JointRecord{
            info.evaluate, MBS_BODY_R(j.body_i), has_j ? MBS_BODY_R(j.body_j) : -1, j.driver,
            m.first_row[k], m.first_value[k], has_j ? MBS_BODY_COORDINATES * info.equations : -1,
            info.bodies == 2});
    }
}

void choose_assembly_paths(Mechanism &m) {
    const size_t n = m.joints.size();
    m.distance_with.assign(n, -1);
    m.assembly_path.assign(n, AssemblyPath::Own);
    for (size_t k = 0; k < n; ++k) {
        const JointDef &d = m.joints[k];
        if (d.type == JointType::Normalization) m.assembly_path[k] = AssemblyPath::Normalization;
        if (d.type != JointType::DistanceDriver) continue;
        for (size_t c = 0; c < n; ++c) {
            const JointDef &j = m.joints[c];
            if (j.type == JointType::Cylindrical && m.distance_with[c] < 0 &&
                j.body_i == d.body_i && j.body_j == d.body_j && j.point_i == d.point_i &&
                j.point_j == d.point_j) {
                m.distance_with[c] = static_cast<int>(k);
                m.assembly_path[c] = AssemblyPath::WithDistance;
                m.assembly_path[k] = AssemblyPath::InJointCall;
                break;
            }
        }
    }
}

}  // namespace

bool finalize(Mechanism &m, char *msg, size_t size) {
    if (m.finalized) return true;
    for (size_t b = 0; b < m.bodies.size(); ++b)
        if (!m.bodies[b].fixed && !m.bodies[b].pose_driven) {
            JointDef n;
            n.type = JointType::Normalization;
            n.body_i = static_cast<int>(b);
            m.joints.push_back(n);
        }
    m.coordinates = MBS_BODY_R(static_cast<int>(m.bodies.size()));
    m.equations = 0;
    m.drivers = 0;
    m.first_row.clear();
    m.joint_info.clear();
    m.first_value.clear();
    m.pattern_row.clear();
    m.pattern_col.clear();
    m.driver_joint.clear();
    for (size_t k = 0; k < m.joints.size(); ++k) {
        const JointDef &j = m.joints[k];
        const JointTypeInfo &info = joint_type(j.type);
        m.first_row.push_back(m.equations);
        m.joint_info.push_back(&info);
        m.first_value.push_back(static_cast<int>(m.pattern_row.size()));
        const int bodies[2] = {j.body_i, j.body_j};
        for (int side = 0; side < info.bodies; ++side)
            for (int r = 0; r < info.equations; ++r)
                for (int c = 0; c < MBS_BODY_COORDINATES; ++c) {
                    m.pattern_row.push_back(m.equations + r);
                    m.pattern_col.push_back(body_column(bodies[side], c));
                }
        m.equations += info.equations;
        for (int d = 0; d < info.drivers; ++d) m.driver_joint.push_back(static_cast<int>(k));
        m.drivers += info.drivers;
    }
    if (m.equations != m.coordinates) {
        mbs::set_message(msg, size, MBS_ERR_PARAMETER,
                         "the mechanism has %d constraint equations for %d coordinates: it "
                         "must have exactly as many (add or remove drivers)",
                         m.equations, m.coordinates);
        return false;
    }
    choose_assembly_paths(m);
    make_joint_records(m);
    m.block_plan = plan_blocks(m);
    m.finalized = true;
    return true;
}

}  // namespace mbs
