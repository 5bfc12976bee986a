// A mechanism as data: bodies and constraints, finalised once into an immutable layout
// (equation rows, Jacobian pattern, linear-solver plan). Nothing here changes during a run.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/joint.hpp"
#include "mbs/mbs.h"

namespace mbs {

// Reference point at the centre of mass, axes on the principal axes of inertia.
struct Body {
    std::string name;
    double mass = 0;
    Vec3 inertia = Vec3::Zero();                    // principal moments about the centre of mass
    double q_reference[7] = {0, 0, 0, 1, 0, 0, 0};  // assembly configuration
    bool fixed = false;
    bool pose_driven = false;  // a pose driver replaces its normalisation
};

struct BlockPlan;  // linear_solver.hpp

// How assembly evaluates a joint: by its type's function; inline (a normalisation, a few
// products not worth a call); together with its distance driver (a cylindrical joint); or not at
// all (a distance driver written by its cylindrical joint's call).
enum class AssemblyPath : char { Own, Normalization, WithDistance, InJointCall };

// Per joint, made by finalize: what the assembly loop reads for it, side by side (it read five
// per-joint arrays, the joint's definition and its type's table entry).
struct JointRecord {
    JointEvaluate evaluate;  // its type's function
    int coord_i, coord_j;    // its bodies' first coordinates; coord_j -1 without a body j
    int driver;              // its first driver slot, -1 if none
    int first_row, first_value;
    int block_j;  // body j's Jacobian block after first_value (7 x equations), or -1
    bool frames;  // a two-body type: it is given its bodies' frames
};

struct Mechanism {
    std::vector<Body> bodies;
    std::vector<JointDef> joints;
    Vec3 gravity = Vec3::Zero();

    // Filled by finalize().
    bool finalized = false;
    int coordinates = 0, equations = 0, drivers = 0;
    std::vector<int> first_row;                     // per joint
    std::vector<const JointTypeInfo *> joint_info;  // per joint: joint_type(its type)
    std::vector<int> first_value;  // per joint: offset of its Jacobian blocks in the values
    std::vector<int> pattern_row, pattern_col;  // per Jacobian value
    std::vector<int> driver_joint;              // per driver slot: the joint that reads it
    // Per joint: how assembly evaluates it, and for a cylindrical joint with a distance driver,
    // that driver (else -1).
    std::vector<AssemblyPath> assembly_path;
    std::vector<int> distance_with;
    std::vector<JointRecord> joint_records;
    std::shared_ptr<const BlockPlan> block_plan;  // null if the structure is not bordered blocks

    int values() const { return static_cast<int>(pattern_row.size()); }
};

// Body b's position r and Euler parameters p inside a coordinate vector (q, q_dot, q_ddot).
template <class T>
inline T *body_r(T *q, size_t b) {
    return q + MBS_BODY_R(b);
}
template <class T>
inline T *body_p(T *q, size_t b) {
    return q + MBS_BODY_P(b);
}
// Coordinate c (0..6: r then p) of body b: its column in the Jacobian.
inline int body_column(int b, int c) { return MBS_BODY_R(b) + c; }

// Every body at its reference configuration in q (coordinates long): the one reset of positions.
void place_at_reference(const Mechanism &m, double *q);

// Adds the normalisations, lays out rows and the Jacobian pattern, plans the linear solver.
// False (message says why) if the equations do not match the coordinates.
bool finalize(Mechanism &m, char *msg, size_t size);

}  // namespace mbs
