#include "plant/plant_reactions.hpp"

namespace stewart {
namespace plant {

namespace {

Mat3 skew(const Vec3 &v) {
    Mat3 S;
    S << 0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0;
    return S;
}

void store(const Vec3 &v, double out[3]) {
    for (int i = 0; i < 3; ++i) out[i] = v[i];
}

Mat3 world_inertia(const Mat3 &A, const Vec3 &principal) {
    return A * principal.asDiagonal() * A.transpose();
}

}  // namespace

bool leg_reactions(const DynamicsModel &d, int k, const LegConfiguration &leg,
                   const Motion bodies[13], double force, stewart_plant_reactions &out) {
    const Vec3 &n = leg.n;
    if (!d.with_legs) {  // two-force members: the axial force only
        store(force * n, out.base_cardan_force[k]);
        store(-force * n, out.platform_cardan_force[k]);
        for (double *v : {out.base_cardan_torque[k], out.platform_cardan_torque[k],
                          out.cylindrical_force[k], out.cylindrical_torque[k]})
            v[0] = v[1] = v[2] = 0;
        return true;
    }
    const Motion &cyl = bodies[1 + k], &pis = bodies[7 + k];
    const Vec3 a = d.legs.base_points.col(k);
    const Vec3 P = bodies[0].position - bodies[0].rotation * d.platform_com + leg.arm;
    const Vec3 t1 = leg.cylinder_x, t2 = n.cross(t1);  // span the plane across the leg
    const Vec3 e_base = d.legs.base_arm.col(k).cross(leg.cylinder_x);  // held rotation axes
    const Vec3 e_plate = leg.piston_arm.cross(leg.piston_x);
    // Unknowns: base Cardan force (3) and torque along e_base (1), platform Cardan force (3) and
    // torque along e_plate (1), cylindrical force (2) and torque (2) across the leg, about P.
    Eigen::Matrix<double, 12, 12> A = Eigen::Matrix<double, 12, 12>::Zero();
    Eigen::Matrix<double, 12, 1> b;
    Eigen::Matrix<double, 3, 2> across;
    across << t1, t2;
    // Cylinder: f_B - f_C = m (a - g) + F n; moments about its centre of mass.
    A.block<3, 3>(0, 0).setIdentity();
    A.block<3, 2>(0, 8) = -across;
    A.block<3, 3>(3, 0) = skew(a - cyl.position);
    A.block<3, 1>(3, 3) = e_base;
    A.block<3, 2>(3, 8) = -skew(P - cyl.position) * across;
    A.block<3, 2>(3, 10) = -across;
    // Piston: f_P + f_C = m (a - g) - F n; moments about its centre of mass.
    A.block<3, 3>(6, 4).setIdentity();
    A.block<3, 2>(6, 8) = across;
    A.block<3, 3>(9, 4) = skew(P - pis.position);
    A.block<3, 1>(9, 7) = e_plate;
    A.block<3, 2>(9, 8) = skew(P - pis.position) * across;
    A.block<3, 2>(9, 10) = across;
    const Mat3 I_cyl = world_inertia(cyl.rotation, d.cylinder_inertia);
    const Mat3 I_pis = world_inertia(pis.rotation, d.piston_inertia);
    b.segment<3>(0) = d.cylinder_mass * (cyl.acceleration - d.gravity) + force * n;
    b.segment<3>(3) = I_cyl * cyl.alpha + cyl.omega.cross(I_cyl * cyl.omega);
    b.segment<3>(6) = d.piston_mass * (pis.acceleration - d.gravity) - force * n;
    b.segment<3>(9) = I_pis * pis.alpha + pis.omega.cross(I_pis * pis.omega);
    const Eigen::PartialPivLU<Eigen::Matrix<double, 12, 12>> lu(A);
    if (!(std::abs(lu.determinant()) > 1e-300)) return false;
    const Eigen::Matrix<double, 12, 1> z = lu.solve(b);
    store(z.segment<3>(0), out.base_cardan_force[k]);
    store(z[3] * e_base, out.base_cardan_torque[k]);
    store(z.segment<3>(4), out.platform_cardan_force[k]);
    store(z[7] * e_plate, out.platform_cardan_torque[k]);
    store(across * z.segment<2>(8), out.cylindrical_force[k]);
    store(across * z.segment<2>(10), out.cylindrical_torque[k]);
    return true;
}

}  // namespace plant
}  // namespace stewart
