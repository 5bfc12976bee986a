// Building a mechanism: bodies and joints with their input checked. Every function returns the
// new index (>= 0) or a negative mbs_status with a message naming the offending value.
#pragma once

#include "core/mechanism.hpp"

namespace mbs {

struct Builder {
    Mechanism &m;
    char *msg;
    size_t size;

    int body(const char *name, double mass, const Vec3 &inertia, const double q_reference[7]);
    int fix(int body);
    int spherical(int bi, const Vec3 &ui, int bj, const Vec3 &uj);
    int cardan(int bi, const Vec3 &ui, const Vec3 &si, int bj, const Vec3 &uj, const Vec3 &sj);
    int cylindrical(int bi, const Vec3 &ui, const Vec3 &vi, int bj, const Vec3 &uj, const Vec3 &vj);
    int revolute(int bi, const Vec3 &ui, const Vec3 &vi, int bj, const Vec3 &uj, const Vec3 &vj);
    int prismatic(int bi, const Vec3 &ui, const Vec3 &vi, int bj, const Vec3 &uj, const Vec3 &vj);
    int weld(int bi, const Vec3 &ui, int bj, const Vec3 &uj);
    // Drivers also report their first driver slot.
    int coordinate_driver(int body, int coordinate, int *slot);
    int pose_driver(int body, int *slot);
    int distance_driver(int joint, int *slot);
    int angle_driver(int joint, int *slot);

private:
    int check_open();
    int check_body(int b, const char *what);
    int check_pair(int bi, int bj);
    int check_free(int b);  // neither fixed nor pose-driven yet
    int check_direction(const Vec3 &v, const char *what, Vec3 &unit);
    int add(JointDef j);
    int add_driver(JointDef j, int *slot);
    // Body j's frame image of body i's vector v at the reference configuration.
    Vec3 reference_image(int bi, int bj, const Vec3 &v) const;
};

}  // namespace mbs
