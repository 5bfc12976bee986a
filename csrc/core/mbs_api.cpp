// The C API of the multibody core (include/mbs/mbs.h) over mbs::Mechanism and mbs::State.
#include "mbs/mbs.h"

#include <cmath>
#include <new>

#include "core/assembly.hpp"
#include "core/mbs_handles.hpp"
#include "core/dynamics.hpp"
#include "core/step.hpp"
#include "core/message.hpp"

using mbs::set_message;


namespace {

mbs::Vec3 vec(const double *v) { return v ? mbs::Vec3(v[0], v[1], v[2]) : mbs::Vec3::Zero(); }

mbs::SolverOptions solver_options(const mbs_options &o, mbs_linear_solver kind) {
    mbs::SolverOptions s;
    s.tolerance = o.tolerance;
    s.max_iterations = o.max_iterations;
    s.modified_newton = o.modified_newton != 0;
    s.linear = kind == MBS_LINEAR_DENSE   ? mbs::LinearSolverKind::Dense
               : kind == MBS_LINEAR_BLOCK ? mbs::LinearSolverKind::Block
                                          : mbs::LinearSolverKind::Automatic;
    s.kinsol_dense = kind == MBS_LINEAR_KINSOL_DENSE;
    return s;
}

}  // namespace

extern "C" {

void mbs_options_default(mbs_options *o) {
    if (!o) return;
    o->tolerance = MBS_DEFAULT_TOLERANCE;
    o->max_iterations = MBS_DEFAULT_MAX_ITERATIONS;
    o->modified_newton = 0;
    o->use_predictor = 1;
}

mbs_model *mbs_model_create(void) { return new (std::nothrow) mbs_model; }
void mbs_model_free(mbs_model *m) { delete m; }
const char *mbs_model_message(const mbs_model *m) { return m ? m->message : "model is NULL"; }

mbs_status mbs_set_gravity(mbs_model *m, const double g[3]) {
    if (!m || !g) return MBS_ERR_ARGUMENT;
    if (!vec(g).allFinite())
        return set_message(m->message, sizeof m->message, MBS_ERR_ARGUMENT,
                           "gravity = (%g, %g, %g) must be finite", g[0], g[1], g[2]);
    m->mechanism.gravity = vec(g);
    return MBS_OK;
}

int mbs_add_body(mbs_model *m, const char *name, double mass, const double inertia[3],
                 const double q[7]) {
    if (!m || !inertia || !q) return MBS_ERR_ARGUMENT;
    return m->builder().body(name, mass, vec(inertia), q);
}

mbs_status mbs_fix_body(mbs_model *m, int body) {
    if (!m) return MBS_ERR_ARGUMENT;
    const int k = m->builder().fix(body);
    return k < 0 ? static_cast<mbs_status>(k) : MBS_OK;
}

int mbs_add_spherical(mbs_model *m, int bi, const double ui[3], int bj, const double uj[3]) {
    if (!m || !ui || !uj) return MBS_ERR_ARGUMENT;
    return m->builder().spherical(bi, vec(ui), bj, vec(uj));
}

int mbs_add_cardan(mbs_model *m, int bi, const double ui[3], const double si[3], int bj,
                   const double uj[3], const double sj[3]) {
    if (!m || !ui || !si || !uj || !sj) return MBS_ERR_ARGUMENT;
    return m->builder().cardan(bi, vec(ui), vec(si), bj, vec(uj), vec(sj));
}

int mbs_add_cylindrical(mbs_model *m, int bi, const double ui[3], const double vi[3], int bj,
                        const double uj[3], const double vj[3]) {
    if (!m || !ui || !vi || !uj || !vj) return MBS_ERR_ARGUMENT;
    return m->builder().cylindrical(bi, vec(ui), vec(vi), bj, vec(uj), vec(vj));
}

int mbs_add_revolute(mbs_model *m, int bi, const double ui[3], const double vi[3], int bj,
                     const double uj[3], const double vj[3]) {
    if (!m || !ui || !vi || !uj || !vj) return MBS_ERR_ARGUMENT;
    return m->builder().revolute(bi, vec(ui), vec(vi), bj, vec(uj), vec(vj));
}

int mbs_add_prismatic(mbs_model *m, int bi, const double ui[3], const double vi[3], int bj,
                      const double uj[3], const double vj[3]) {
    if (!m || !ui || !vi || !uj || !vj) return MBS_ERR_ARGUMENT;
    return m->builder().prismatic(bi, vec(ui), vec(vi), bj, vec(uj), vec(vj));
}

int mbs_add_weld(mbs_model *m, int bi, const double ui[3], int bj, const double uj[3]) {
    if (!m || !ui || !uj) return MBS_ERR_ARGUMENT;
    return m->builder().weld(bi, vec(ui), bj, vec(uj));
}

int mbs_add_coordinate_driver(mbs_model *m, int body, int coordinate, int *driver) {
    if (!m) return MBS_ERR_ARGUMENT;
    return m->builder().coordinate_driver(body, coordinate, driver);
}

int mbs_add_pose_driver(mbs_model *m, int body, int *driver) {
    if (!m) return MBS_ERR_ARGUMENT;
    return m->builder().pose_driver(body, driver);
}

int mbs_add_distance_driver(mbs_model *m, int joint, int *driver) {
    if (!m) return MBS_ERR_ARGUMENT;
    return m->builder().distance_driver(joint, driver);
}

int mbs_add_angle_driver(mbs_model *m, int joint, int *driver) {
    if (!m) return MBS_ERR_ARGUMENT;
    return m->builder().angle_driver(joint, driver);
}

mbs_status mbs_model_finalize(mbs_model *m, char *message, size_t size) {
    if (!m) return set_message(message, size, MBS_ERR_ARGUMENT, "model is NULL");
    if (!mbs::finalize(m->mechanism, m->message, sizeof m->message)) {
        set_message(message, size, MBS_ERR_PARAMETER, "%s", m->message);
        return MBS_ERR_PARAMETER;
    }
    return mbs::clear_message(message, size, MBS_OK);
}

int mbs_coordinate_count(const mbs_model *m) { return m ? m->mechanism.coordinates : 0; }
int mbs_equation_count(const mbs_model *m) { return m ? m->mechanism.equations : 0; }
int mbs_joint_first_row(const mbs_model *m, int joint) {
    if (!m || !m->mechanism.finalized || joint < 0 ||
        joint >= static_cast<int>(m->mechanism.joints.size()))
        return MBS_ERR_ARGUMENT;
    return m->mechanism.first_row[joint];
}

mbs_data *mbs_data_create(const mbs_model *m, mbs_linear_solver kind) {
    if (!m || !m->mechanism.finalized) return nullptr;
    mbs_options o;
    mbs_options_default(&o);
    mbs_data *d = new (std::nothrow) mbs_data(m, solver_options(o, kind));
    if (d && !d->state.ok()) {
        delete d;
        return nullptr;
    }
    return d;
}

void mbs_data_free(mbs_data *d) { delete d; }

mbs_status mbs_data_copy(mbs_data *dst, const mbs_data *src) {
    if (!dst || !src || dst->model != src->model) return MBS_ERR_ARGUMENT;
    mbs::copy_state(dst->state, src->state);
    return MBS_OK;
}

const char *mbs_data_message(const mbs_data *d) { return d ? d->state.message : "data is NULL"; }

mbs_status mbs_set_driver(mbs_data *d, int driver, double value, double rate, double accel) {
    if (!d) return MBS_ERR_ARGUMENT;
    mbs::State &s = d->state;
    if (driver < 0 || driver >= static_cast<int>(s.drive.size()))
        return set_message(s.message, sizeof s.message, MBS_ERR_ARGUMENT,
                           "driver = %d is not a driver slot (the model has %zu)", driver,
                           s.drive.size());
    if (!std::isfinite(value) || !std::isfinite(rate) || !std::isfinite(accel))
        return set_message(s.message, sizeof s.message, MBS_ERR_ARGUMENT,
                           "driver %d value, rate, accel = %g, %g, %g must be finite", driver,
                           value, rate, accel);
    s.drive[driver] = mbs::DriverValue{value, rate, accel};
    return MBS_OK;
}

mbs_status mbs_step(mbs_data *d, double t, const mbs_options *o) {
    if (!d || !o) return MBS_ERR_ARGUMENT;
    mbs::State &s = d->state;
    if (!std::isfinite(t))
        return set_message(s.message, sizeof s.message, MBS_ERR_ARGUMENT, "t = %g must be finite",
                           t);
    if (!(o->tolerance > 0) || o->max_iterations < 1)
        return set_message(s.message, sizeof s.message, MBS_ERR_PARAMETER,
                           "tolerance = %g must be > 0 and max_iterations = %d >= 1", o->tolerance,
                           o->max_iterations);
    const mbs::SolverOptions so = solver_options(*o, MBS_LINEAR_AUTOMATIC);
    return mbs::solve_step(s, t, so, o->use_predictor != 0);
}

const double *mbs_q(const mbs_data *d) { return d ? d->state.q.data() : nullptr; }
const double *mbs_q_dot(const mbs_data *d) { return d ? d->state.q_dot.data() : nullptr; }
const double *mbs_q_ddot(const mbs_data *d) { return d ? d->state.q_ddot.data() : nullptr; }
const double *mbs_lambda(const mbs_data *d) { return d ? d->state.lambda.data() : nullptr; }
int mbs_iterations(const mbs_data *d) { return d ? d->state.stats.iterations : 0; }
double mbs_residual(const mbs_data *d) { return d ? d->state.stats.residual : 0; }
long mbs_linear_fallbacks(const mbs_data *d) {
    return d && d->state.linear ? d->state.linear->fallbacks() : 0;
}

mbs_status mbs_joint_reaction(const mbs_data *d, int joint, int side, double force[3],
                              double torque[3]) {
    if (!d || !force || !torque) return MBS_ERR_ARGUMENT;
    const mbs::Mechanism &m = d->model->mechanism;
    if (joint < 0 || joint >= static_cast<int>(m.joints.size()) || side < 0 || side > 1 ||
        (side == 1 && m.joints[joint].body_j < 0))
        return MBS_ERR_ARGUMENT;
    mbs::Vec3 f, n;
    mbs::joint_reaction(m, d->state, joint, side, f, n);
    for (int c = 0; c < 3; ++c) force[c] = f[c], torque[c] = n[c];
    return MBS_OK;
}

mbs_status mbs_evaluate(const mbs_data *d, const double *q, const double *q_dot, double *phi,
                        double *jacobian, double *phi_t, double *gamma) {
    if (!d || !q || (gamma && !q_dot)) return MBS_ERR_ARGUMENT;
    const mbs::Mechanism &m = d->model->mechanism;
    const mbs::DriverValue *drv = d->state.drive.data();
    if (phi) mbs::assemble_residual(m, q, drv, phi);
    if (phi_t) mbs::assemble_phi_t(m, q, drv, phi_t);
    if (gamma) mbs::assemble_gamma(m, q, q_dot, drv, gamma);
    if (jacobian) {
        std::vector<double> values(m.values());
        mbs::assemble_jacobian(m, q, drv, values.data());
        std::fill(jacobian, jacobian + m.equations * m.coordinates, 0.0);
        for (int t = 0; t < m.values(); ++t)
            jacobian[m.pattern_row[t] * m.coordinates + m.pattern_col[t]] = values[t];
    }
    return MBS_OK;
}

double mbs_energy(const mbs_data *d, const double *q, const double *q_dot) {
    if (!d || !q || !q_dot) return 0;
    return mbs::mechanical_energy(d->model->mechanism, q, q_dot);
}

}  // extern "C"
