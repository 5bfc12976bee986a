// White-box test of the inverse batch's vector kernels (kinematics/closed_form_quad.*): at the
// kinematic and massless levels, every kernel this CPU runs (portable, AVX2) against the scalar
// stewart_inverse_solve row by row, over thousands of random poses with rates and accelerations,
// near-singular and singular ones, rows outside the stroke, a leg on its base point and bad input
// (NaN, infinity, huge values, pitch at +-90 deg, angles beyond the kernel's range): the same
// status, message, warnings and stroke_legs per row, the numbers within the bounds below (those of
// docs/speed-accuracy.md). Three platforms: the thesis', a general geometry with a payload off
// centre and length offsets, and one with tool and user frames (which the batch leaves to the
// scalar path: bit for bit).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "batch_paths.hpp"
#include "model.hpp"
#include "unity.h"

namespace {

// Each output group of a row against the scalar row: |vector - scalar| <= bound * scale, scale the
// group's largest |scalar| value; for the forces and the base wrench the bound is times the
// condition number (the solve loses that much of its last bits either way).
constexpr double kKinematicBound = 2e-14;
constexpr double kForceBound = 2e-15;  // times the condition number

double uniform(uint64_t &state, double a, double b) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return a + (b - a) * static_cast<double>(state >> 11) / 9007199254740992.0;
}

struct Rows {
    std::vector<double> q, q_dot, q_ddot;
    size_t n = 0;
    double *row(std::vector<double> &v, size_t j) { return &v[6 * j]; }
    void add(const double q_j[6], const double q_dot_j[6], const double q_ddot_j[6]) {
        q.insert(q.end(), q_j, q_j + 6);
        q_dot.insert(q_dot.end(), q_dot_j, q_dot_j + 6);
        q_ddot.insert(q_ddot.end(), q_ddot_j, q_ddot_j + 6);
        ++n;
    }
};

// Random poses around home of the model's platform (some far enough to be singular or outside
// the stroke), then the special rows.
Rows test_rows(const stewart_model *m, uint64_t seed) {
    Rows rows;
    const double home = m->params.home_height;
    const double half[6] = {0.25, 0.25, 0.2, 0.6, 0.6, 1.2};
    for (int j = 0; j < 4000; ++j) {
        double q[6], q_dot[6], q_ddot[6];
        const double reach = j % 4 == 0 ? 1.0 : 0.3;  // a quarter of the rows far out
        for (int i = 0; i < 6; ++i) {
            q[i] = uniform(seed, -half[i], half[i]) * reach;
            q_dot[i] = uniform(seed, -1, 1);
            q_ddot[i] = uniform(seed, -10, 10);
        }
        q[2] += home;
        rows.add(q, q_dot, q_ddot);
    }
    const double zero[6] = {0, 0, 0, 0, 0, 0};
    const double q[6] = {0.01, -0.02, home, 0.05, 0.02, -0.03};
    // Toward a singular roll (bisection on the sign of det J between -1.1 and -0.8 rad, where the
    // thesis platform and the one moved about from it are singular): conditions from tens to
    // beyond singular_condition, around both thresholds.
    auto det_at = [&](double roll) {
        double pose[6];
        std::memcpy(pose, q, sizeof pose);
        pose[3] = roll;
        const double zero6[6] = {0, 0, 0, 0, 0, 0};
        stewart::LegKinematics legs;
        TEST_ASSERT_EQUAL_INT(STEWART_OK,
                              stewart::leg_kinematics(m->geometry,
                                                      stewart::motion_of_pose<double>(pose, zero6,
                                                                                      zero6),
                                                      legs, nullptr, 0));
        stewart::LegJacobian jacobian;
        stewart::leg_jacobian(m->geometry, legs, jacobian);
        return jacobian.transposed.determinant();
    };
    double regular = -1.1, singular = -0.8;
    TEST_ASSERT_TRUE_MESSAGE(det_at(regular) * det_at(singular) < 0, "a singular roll");
    for (int i = 0; i < 60; ++i) {
        const double middle = 0.5 * (regular + singular);
        (det_at(middle) * det_at(regular) > 0 ? regular : singular) = middle;
    }
    for (int e = 1; e <= 14; ++e)
        for (int i = 1; i <= 9; ++i)
            for (int side : {-1, 1}) {
                double near[6], q_dot[6], q_ddot[6];
                std::memcpy(near, q, sizeof near);
                near[3] = regular + side * i * std::pow(10.0, -e);
                for (int c = 0; c < 6; ++c) {
                    q_dot[c] = uniform(seed, -1, 1);
                    q_ddot[c] = uniform(seed, -10, 10);
                }
                rows.add(near, q_dot, q_ddot);
            }
    double bad[6];
    // bad input, each alone in its row
    for (int i = 0; i < 6; ++i) {
        std::memcpy(bad, q, sizeof bad), bad[i] = NAN, rows.add(bad, zero, zero);
        std::memcpy(bad, zero, sizeof bad), bad[i] = INFINITY, rows.add(q, bad, zero);
        std::memcpy(bad, zero, sizeof bad), bad[i] = -1e300, rows.add(q, zero, bad);
        std::memcpy(bad, q, sizeof bad), bad[i] = 1e60, rows.add(bad, zero, zero);
    }
    std::memcpy(bad, q, sizeof bad), bad[4] = M_PI / 2, rows.add(bad, q, q);   // pitch +90 deg
    std::memcpy(bad, q, sizeof bad), bad[4] = -M_PI / 2, rows.add(bad, q, q);  // pitch -90 deg
    std::memcpy(bad, q, sizeof bad), bad[5] = 2e4, rows.add(bad, zero, zero);  // beyond the kernel
    std::memcpy(bad, q, sizeof bad), bad[3] = 9999.5, rows.add(bad, q, q);     // within it
    // leg 1's platform point on its base point: unreachable
    const Eigen::Vector3d on_base =
        m->geometry.base_points.col(0) - m->geometry.platform_points.col(0);
    const double on[6] = {on_base.x(), on_base.y(), on_base.z(), 0, 0, 0};
    rows.add(on, zero, zero);
    // far outside the stroke (every leg), and exactly at home
    std::memcpy(bad, q, sizeof bad), bad[2] = 3 * home, rows.add(bad, zero, zero);
    const double at_home[6] = {0, 0, home, 0, 0, 0};
    rows.add(at_home, zero, zero);
    return rows;
}

struct Result {
    std::vector<stewart_inverse_output> rows;
    std::vector<int> status;
    std::vector<size_t> message_rows;
    std::vector<char> text;
    size_t messages = 0, first_failed = 0;
    stewart_status returned = STEWART_OK;
    char message[STEWART_MESSAGE_SIZE] = "";
};

// The whole batch on path, every column asked for.
Result run(const stewart_model *m, const stewart_inverse_options &o, Rows &rows,
           stewart::VectorPath path) {
    const size_t n = rows.n;
    Result r;
    r.rows.resize(n), r.status.resize(n), r.message_rows.resize(n);
    r.text.resize(n * STEWART_MESSAGE_SIZE);
    std::vector<double> length(6 * n), rate(6 * n), accel(6 * n), force(6 * n), condition(n),
        residual(n), base_force(3 * n), base_torque(3 * n);
    std::vector<int> iterations(n), warnings(n), stroke_legs(n);
    stewart_inverse_batch_outputs out{};
    out.length = length.data(), out.length_rate = rate.data(), out.length_accel = accel.data();
    out.force = force.data(), out.condition = condition.data(), out.residual = residual.data();
    out.base_force = base_force.data(), out.base_torque = base_torque.data();
    out.iterations = iterations.data(), out.warnings = warnings.data();
    out.stroke_legs = stroke_legs.data(), out.status = r.status.data();
    stewart_batch_messages messages = {n, 0, r.message_rows.data(), r.text.data()};
    stewart_inverse *d = stewart_inverse_create(m, &o, nullptr, 0);
    TEST_ASSERT_NOT_NULL(d);
    r.returned = stewart::inverse_batch(d, n, rows.q.data(), rows.q_dot.data(), rows.q_ddot.data(),
                                        &out, &messages, &r.first_failed, path);
    r.messages = messages.count;
    std::snprintf(r.message, sizeof r.message, "%s", stewart_inverse_message(d));
    stewart_inverse_free(d);
    for (size_t j = 0; j < n; ++j) {
        stewart_inverse_output &x = r.rows[j];
        std::memcpy(x.lengths.length, &length[6 * j], sizeof x.lengths.length);
        std::memcpy(x.lengths.length_rate, &rate[6 * j], sizeof x.lengths.length_rate);
        std::memcpy(x.lengths.length_accel, &accel[6 * j], sizeof x.lengths.length_accel);
        std::memcpy(x.force, &force[6 * j], sizeof x.force);
        std::memcpy(x.base_force, &base_force[3 * j], sizeof x.base_force);
        std::memcpy(x.base_torque, &base_torque[3 * j], sizeof x.base_torque);
        x.condition = condition[j], x.residual = residual[j], x.iterations = iterations[j];
        x.warnings = warnings[j], x.stroke_legs = stroke_legs[j];
    }
    return r;
}

// Largest |a - b| over count values, and largest |b|.
void group_error(const double *a, const double *b, int count, double &error, double &scale) {
    error = scale = 0;
    for (int i = 0; i < count; ++i) {
        error = std::max(error, std::fabs(a[i] - b[i]));
        scale = std::max(scale, std::fabs(b[i]));
    }
}

// The vector batch against the scalar one on m at the level; bit for bit if exact. Returns the
// largest relative errors seen (kinematic groups, force groups over the condition).
void compare(const stewart_model *m, int fidelity, stewart::VectorPath path, bool exact,
             double &kinematic_error, double &force_error, double singular_condition = 0) {
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = fidelity;
    if (singular_condition > 0) o.singular_condition = singular_condition;
    Rows rows = test_rows(m, 0x5eed + fidelity);
    const Result scalar = run(m, o, rows, stewart::VectorPath::scalar);
    const Result vector = run(m, o, rows, path);
    TEST_ASSERT_EQUAL_INT(scalar.returned, vector.returned);
    TEST_ASSERT_EQUAL_size_t(scalar.first_failed, vector.first_failed);
    TEST_ASSERT_EQUAL_STRING(scalar.message, vector.message);
    TEST_ASSERT_EQUAL_size_t(scalar.messages, vector.messages);
    for (size_t i = 0; i < scalar.messages; ++i) {
        TEST_ASSERT_EQUAL_size_t(scalar.message_rows[i], vector.message_rows[i]);
        TEST_ASSERT_EQUAL_STRING(&scalar.text[i * STEWART_MESSAGE_SIZE],
                                 &vector.text[i * STEWART_MESSAGE_SIZE]);
    }
    size_t failed = 0, warned = 0, stroked = 0;
    for (size_t j = 0; j < rows.n; ++j) {
        char where[80];
        std::snprintf(where, sizeof where, "row %zu", j);
        TEST_ASSERT_EQUAL_INT_MESSAGE(scalar.status[j], vector.status[j], where);
        const stewart_inverse_output &s = scalar.rows[j], &v = vector.rows[j];
        failed += scalar.status[j] != STEWART_OK;
        warned += (s.warnings & STEWART_WARN_NEAR_SINGULAR) != 0;
        stroked += s.stroke_legs != 0;
        if (exact) {
            TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&s, &v, sizeof s, where);
            continue;
        }
        TEST_ASSERT_EQUAL_INT_MESSAGE(s.warnings, v.warnings, where);
        TEST_ASSERT_EQUAL_INT_MESSAGE(s.stroke_legs, v.stroke_legs, where);
        TEST_ASSERT_EQUAL_INT_MESSAGE(s.iterations, v.iterations, where);
        TEST_ASSERT_EQUAL_DOUBLE_MESSAGE(s.residual, v.residual, where);
        double error, scale;
        const double *groups[3][2] = {{v.lengths.length, s.lengths.length},
                                      {v.lengths.length_rate, s.lengths.length_rate},
                                      {v.lengths.length_accel, s.lengths.length_accel}};
        for (auto &g : groups) {
            group_error(g[0], g[1], 6, error, scale);
            const double relative = error / std::max(scale, 1e-300);
            kinematic_error = std::max(kinematic_error, relative);
            TEST_ASSERT_TRUE_MESSAGE(error <= kKinematicBound * scale, where);
        }
        const double cond = std::max(s.condition, 1.0);
        group_error(&v.condition, &s.condition, 1, error, scale);
        TEST_ASSERT_TRUE_MESSAGE(error <= kForceBound * cond * scale, where);
        const double *wrench[3][3] = {{v.force, s.force, nullptr},
                                      {v.base_force, s.base_force, nullptr},
                                      {v.base_torque, s.base_torque, nullptr}};
        for (int g = 0; g < 3; ++g) {
            group_error(wrench[g][0], wrench[g][1], g == 0 ? 6 : 3, error, scale);
            // the base wrench is a sum of the forces: its scale is theirs
            double force_scale, unused;
            group_error(s.force, s.force, 6, unused, force_scale);
            const double reference = std::max(scale, force_scale);
            if (reference == 0) continue;
            force_error = std::max(force_error, error / (reference * cond));
            TEST_ASSERT_TRUE_MESSAGE(error <= kForceBound * cond * reference, where);
        }
    }
    // The rows cover what they should: failures, outside the stroke, and (massless) warnings.
    std::printf("%zu rows: %zu failed, %zu outside the stroke, %zu near-singular\n", rows.n, failed,
                stroked, warned);
    TEST_ASSERT_TRUE(failed >= 12);
    TEST_ASSERT_TRUE(stroked > 100);
    if (fidelity == STEWART_MASSLESS && !exact && singular_condition == 0)
        TEST_ASSERT_TRUE(warned > 50 && failed > 50);
}

stewart_model *thesis_model() {
    stewart_params p;
    stewart_params_default(&p);
    return stewart_model_create(&p, nullptr, 0);
}

// A general geometry (the thesis' joints moved about), a payload off centre and length offsets.
stewart_model *general_model() {
    stewart_params p;
    stewart_params_default(&p);
    stewart_model *thesis = stewart_model_create(&p, nullptr, 0);
    p.geometry = 1;
    uint64_t seed = 77;
    for (int k = 0; k < STEWART_LEGS; ++k)
        for (int i = 0; i < 3; ++i) {
            p.base_joint[3 * k + i] =
                thesis->geometry.base_points(i, k) + uniform(seed, -0.03, 0.03);
            p.platform_joint[3 * k + i] =
                thesis->geometry.platform_points(i, k) + uniform(seed, -0.03, 0.03);
        }
    stewart_model_free(thesis);
    p.payload_mass = 120;
    p.payload_com[0] = 0.1, p.payload_com[1] = -0.05, p.payload_com[2] = 0.2;
    p.payload_inertia[0] = 3, p.payload_inertia[1] = 4, p.payload_inertia[2] = 5;
    for (int k = 0; k < STEWART_LEGS; ++k) p.length_offset[k] = 0.01 * (k + 1);
    char message[STEWART_MESSAGE_SIZE];
    stewart_model *m = stewart_model_create(&p, message, sizeof message);
    TEST_ASSERT_NOT_NULL_MESSAGE(m, message);
    return m;
}

stewart_model *framed_model() {
    stewart_params p;
    stewart_params_default(&p);
    p.tool_frame[2] = 0.1, p.tool_frame[5] = 0.3;
    p.user_frame[0] = 0.02, p.user_frame[3] = 0.01;
    return stewart_model_create(&p, nullptr, 0);
}

std::vector<stewart::VectorPath> kernels() {
    std::vector<stewart::VectorPath> paths = {stewart::VectorPath::portable};
    for (stewart::VectorPath path : {stewart::VectorPath::avx2, stewart::VectorPath::avx512vl})
        if (stewart::vector_path_available(path)) paths.push_back(path);
    return paths;
}

const char *kernel_name(stewart::VectorPath path) {
    return path == stewart::VectorPath::avx512vl ? "avx512vl"
           : path == stewart::VectorPath::avx2   ? "avx2"
                                                 : "portable";
}

void on_every_kernel(stewart_model *m, bool exact) {
    TEST_ASSERT_NOT_NULL(m);
    for (int fidelity : {STEWART_KINEMATIC, STEWART_MASSLESS})
        for (stewart::VectorPath path : kernels()) {
            double kinematic_error = 0, force_error = 0;
            compare(m, fidelity, path, exact, kinematic_error, force_error);
            std::printf("%s kernel, %s: largest relative difference %.2g (lengths, rates, "
                        "accelerations), %.2g x condition (forces, base wrench)\n",
                        kernel_name(path), fidelity ? "massless" : "kinematic", kinematic_error,
                        force_error);
        }
    stewart_model_free(m);
}

}  // namespace

void setUp(void) {}
void tearDown(void) {}

static void test_thesis_platform(void) { on_every_kernel(thesis_model(), false); }
static void test_general_geometry_payload_and_offsets(void) {
    on_every_kernel(general_model(), false);
}
static void test_tool_and_user_frames_stay_scalar(void) { on_every_kernel(framed_model(), true); }

// With singular_condition at its largest only the pivot rule calls a pose singular: the rows
// walking into the singular roll must get the scalar path's statuses and messages there too.
static void test_pivot_rule_when_the_condition_never_refuses(void) {
    stewart_model *m = thesis_model();
    TEST_ASSERT_NOT_NULL(m);
    for (stewart::VectorPath path : kernels()) {
        double kinematic_error = 0, force_error = 0;
        compare(m, STEWART_MASSLESS, path, false, kinematic_error, force_error, 1e300);
    }
    stewart_model_free(m);
}

// The kernel itself solves nearly every ordinary row (the comparisons above would hold trivially
// if it left every row to the scalar path).
static void test_kernel_takes_ordinary_rows(void) {
    stewart_model *m = thesis_model();
    Rows rows = test_rows(m, 99);
    for (int fidelity : {STEWART_KINEMATIC, STEWART_MASSLESS})
        for (stewart::VectorPath path : kernels()) {
            stewart_inverse_options o;
            stewart_inverse_options_default(&o);
            o.fidelity = fidelity;
            const stewart::QuadModel quad =
                stewart::quad_model(m->geometry, m->platform, m->gravity, m->params, o);
            size_t taken = 0, ordinary = 0;
            std::vector<double> length(6 * rows.n);
            stewart_inverse_batch_outputs out{};
            out.length = length.data();
            for (size_t j = 0; j + 4 <= 4000; j += 4) {
                const stewart::QuadRows quad_rows = {&rows.q[6 * j], &rows.q_dot[6 * j],
                                                     &rows.q_ddot[6 * j]};
                const unsigned left = stewart::closed_form_quad(path, quad, quad_rows, out, j);
                for (int l = 1; l < 4; ++l)  // rows 4i+1..: near home
                    taken += !(left >> l & 1), ++ordinary;
            }
            TEST_ASSERT_TRUE(taken >= ordinary * 9 / 10);
        }
    stewart_model_free(m);
}

// The massless kernel factors J^T without row exchanges in the model's row order, a lane that
// breaks threshold pivoting's rule with partial pivoting instead: whatever the order (the one from
// home, the natural one, reversed, rotated), its forces and condition agree with the scalar
// path's within the bounds, and it takes the ordinary rows (an order that breaks the rule takes
// the pivoting branch).
static void test_any_row_order_gives_the_same_forces(void) {
    stewart_model *m = thesis_model();
    Rows rows = test_rows(m, 7);
    const size_t n = 4000;
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = STEWART_MASSLESS;
    stewart_inverse *d = stewart_inverse_create(m, &o, nullptr, 0);
    TEST_ASSERT_NOT_NULL(d);
    std::vector<stewart_inverse_output> scalar(n);
    std::vector<int> status(n);
    for (size_t j = 0; j < n; ++j) {
        stewart_inverse_input in{};
        std::memcpy(in.pose.q, &rows.q[6 * j], sizeof in.pose.q);
        std::memcpy(in.pose.q_dot, &rows.q_dot[6 * j], sizeof in.pose.q_dot);
        std::memcpy(in.pose.q_ddot, &rows.q_ddot[6 * j], sizeof in.pose.q_ddot);
        status[j] = stewart_inverse_solve(d, &in, &scalar[j]);
    }
    stewart_inverse_free(d);
    const stewart::QuadModel home =
        stewart::quad_model(m->geometry, m->platform, m->gravity, m->params, o);
    const int orders[5][6] = {{0, 1, 2, 3, 4, 5},
                              {5, 4, 3, 2, 1, 0},
                              {1, 2, 3, 4, 5, 0},
                              {3, 4, 5, 0, 1, 2},
                              {2, 0, 1, 5, 3, 4}};
    std::vector<double> force(6 * n), condition(n);
    stewart_inverse_batch_outputs out{};
    out.force = force.data(), out.condition = condition.data();
    for (stewart::VectorPath path : kernels())
        for (int which = -1; which < 5; ++which) {
            stewart::QuadModel quad = home;
            if (which >= 0) std::memcpy(quad.row_slot, orders[which], sizeof quad.row_slot);
            size_t taken = 0, ordinary = 0;
            for (size_t j = 0; j + 4 <= n; j += 4) {
                const stewart::QuadRows quad_rows = {&rows.q[6 * j], &rows.q_dot[6 * j],
                                                     &rows.q_ddot[6 * j]};
                const unsigned left = stewart::closed_form_quad(path, quad, quad_rows, out, j);
                for (int l = 0; l < 4; ++l) {
                    const size_t row = j + l;
                    if (l > 0) taken += !(left >> l & 1), ++ordinary;  // rows 4i+1..: near home
                    if (left >> l & 1) continue;
                    TEST_ASSERT_EQUAL_INT(STEWART_OK, status[row]);
                    const stewart_inverse_output &s = scalar[row];
                    const double cond = std::max(s.condition, 1.0);
                    double error, scale;
                    group_error(&condition[row], &s.condition, 1, error, scale);
                    TEST_ASSERT_TRUE(error <= kForceBound * cond * scale);
                    group_error(&force[6 * row], s.force, 6, error, scale);
                    TEST_ASSERT_TRUE(error <= kForceBound * cond * scale);
                }
            }
            TEST_ASSERT_TRUE(taken >= ordinary * 9 / 10);
        }
    stewart_model_free(m);
}

// Lanes never mix and the kernel's choices are per lane: a row's numbers are the same bits
// wherever in a batch (in which block of four, in which lane) it sits.
static void test_a_rows_numbers_do_not_depend_on_its_block(void) {
    stewart_model *m = thesis_model();
    Rows rows = test_rows(m, 11);
    for (int fidelity : {STEWART_KINEMATIC, STEWART_MASSLESS})
        for (stewart::VectorPath path : kernels()) {
            stewart_inverse_options o;
            stewart_inverse_options_default(&o);
            o.fidelity = fidelity;
            const Result whole = run(m, o, rows, path);
            for (size_t shift = 1; shift < 4; ++shift) {
                Rows shifted;
                for (size_t j = shift; j < rows.n; ++j)
                    shifted.add(&rows.q[6 * j], &rows.q_dot[6 * j], &rows.q_ddot[6 * j]);
                const Result part = run(m, o, shifted, path);
                for (size_t j = 0; j < shifted.n; ++j) {
                    char where[80];
                    std::snprintf(where, sizeof where, "row %zu shifted by %zu", j + shift, shift);
                    TEST_ASSERT_EQUAL_INT_MESSAGE(whole.status[j + shift], part.status[j], where);
                    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&whole.rows[j + shift], &part.rows[j],
                                                     sizeof part.rows[j], where);
                }
            }
        }
    stewart_model_free(m);
}

// The AVX-512VL kernel is the AVX2 kernel's source with more registers: the same operations, so
// every output and status the same bits (on the thesis platform and the general geometry).
static void test_avx512vl_kernel_gives_the_avx2_bits(void) {
    if (!stewart::vector_path_available(stewart::VectorPath::avx512vl))
        TEST_IGNORE_MESSAGE("no AVX-512VL kernel on this CPU or build");
    for (stewart_model *m : {thesis_model(), general_model()}) {
        TEST_ASSERT_NOT_NULL(m);
        Rows rows = test_rows(m, 13);
        for (int fidelity : {STEWART_KINEMATIC, STEWART_MASSLESS}) {
            stewart_inverse_options o;
            stewart_inverse_options_default(&o);
            o.fidelity = fidelity;
            const Result avx2 = run(m, o, rows, stewart::VectorPath::avx2);
            const Result avx512vl = run(m, o, rows, stewart::VectorPath::avx512vl);
            TEST_ASSERT_EQUAL_size_t(avx2.messages, avx512vl.messages);
            for (size_t j = 0; j < rows.n; ++j) {
                char where[40];
                std::snprintf(where, sizeof where, "row %zu", j);
                TEST_ASSERT_EQUAL_INT_MESSAGE(avx2.status[j], avx512vl.status[j], where);
                TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&avx2.rows[j], &avx512vl.rows[j],
                                                 sizeof avx2.rows[j], where);
            }
        }
        stewart_model_free(m);
    }
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_thesis_platform);
    RUN_TEST(test_general_geometry_payload_and_offsets);
    RUN_TEST(test_tool_and_user_frames_stay_scalar);
    RUN_TEST(test_pivot_rule_when_the_condition_never_refuses);
    RUN_TEST(test_kernel_takes_ordinary_rows);
    RUN_TEST(test_any_row_order_gives_the_same_forces);
    RUN_TEST(test_a_rows_numbers_do_not_depend_on_its_block);
    RUN_TEST(test_avx512vl_kernel_gives_the_avx2_bits);
    return UNITY_END();
}
