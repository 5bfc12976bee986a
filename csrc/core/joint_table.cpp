// The joint table: one entry per JointType, in enum order.
#include "core/joint.hpp"

namespace mbs {

extern const JointTypeInfo kFixedBody, kNormalization, kSpherical, kCardan, kCylindrical, kRevolute,
    kPrismatic, kWeld, kCoordinateDriver, kPoseDriver, kDistanceDriver, kAngleDriver;

const JointTypeInfo &joint_type(JointType t) {
    static const JointTypeInfo *const table[] = {&kFixedBody,  &kNormalization,  &kSpherical,
                                                 &kCardan,     &kCylindrical,    &kRevolute,
                                                 &kPrismatic,  &kWeld,           &kCoordinateDriver,
                                                 &kPoseDriver, &kDistanceDriver, &kAngleDriver};
    static_assert(sizeof table / sizeof table[0] == static_cast<int>(JointType::Count),
                  "one table entry per joint type");
    return *table[static_cast<int>(t)];
}

}  // namespace mbs
