/* The bordered-block solver against the dense LU on a hexapod's Jacobian: at assembled and at
 * random configurations, and with a planned pivot forced to zero so the refactorisation must
 * fall back to partial pivoting. Solves and transposed solves must agree. Also the assembly's
 * shared evaluation of a cylindrical joint with its distance driver against the two joints
 * evaluated alone. The lane kernels (the legs side by side, one per vector lane) against one leg
 * at a time, bit for bit. The core alone: no platform header. */
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "core/assembly.hpp"
#include "core/lane_lu.hpp"
#include "core/lane_sets.hpp"
#include "core/linear_solver.hpp"
#include "core/mbs_handles.hpp"
#include "unity.h"

/* A hexapod built here on the core alone (the Stewart platform's topology, not its library):
 * fixed base, per leg a cylinder on a base Cardan and a piston on a platform Cardan joined by a
 * cylindrical joint with a length driver, and the platform as the hub. */
static mbs_model *model;

static void add_body(const char *name, const Eigen::Vector3d &r, const Eigen::Matrix3d &A) {
    const Eigen::Quaterniond p(A);
    const double q[7] = {r[0], r[1], r[2], p.w(), p.x(), p.y(), p.z()};
    const double inertia[3] = {0.02, 0.02, 0.001};
    TEST_ASSERT_TRUE(mbs_add_body(model, name, 1.0, inertia, q) >= 0);
}

void setUp(void) {
    const double pi = 3.14159265358979323846, beta[6] = {0, 30, 120, 150, 240, 270},
                 tau[6] = {330, 60, 90, 180, 210, 300}, radius = 0.5, height = 0.5, com = 0.15;
    model = mbs_model_create();
    Eigen::Vector3d a[6], b[6], arm_a[6], arm_b[6], n[6];
    for (int k = 0; k < 6; ++k) {
        const double ba = beta[k] * pi / 180, ta = tau[k] * pi / 180;
        a[k] = radius * Eigen::Vector3d(std::cos(ba), std::sin(ba), 0);
        b[k] = radius * Eigen::Vector3d(std::cos(ta), std::sin(ta), 0);
        arm_a[k] = Eigen::Vector3d(-std::sin(ba), std::cos(ba), 0);
        arm_b[k] = Eigen::Vector3d(-std::sin(ta), std::cos(ta), 0);
        n[k] = (b[k] + Eigen::Vector3d(0, 0, height) - a[k]).normalized();
    }
    add_body("base", Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k < 6; ++k) {
            Eigen::Matrix3d A; /* z along the leg, x along the Cardan arm's perpendicular */
            A.col(2) = n[k];
            A.col(0) = (side ? arm_b[k] : arm_a[k]).cross(n[k]).normalized();
            A.col(1) = n[k].cross(A.col(0));
            const Eigen::Vector3d end =
                side ? Eigen::Vector3d(b[k] + Eigen::Vector3d(0, 0, height) - com * n[k])
                     : Eigen::Vector3d(a[k] + com * n[k]);
            add_body(side ? "piston" : "cylinder", end, A);
        }
    add_body("platform", Eigen::Vector3d(0, 0, height), Eigen::Matrix3d::Identity());
    TEST_ASSERT_EQUAL(MBS_OK, mbs_fix_body(model, 0));
    const double ex[3] = {1, 0, 0}, ez[3] = {0, 0, 1}, low[3] = {0, 0, -com}, high[3] = {0, 0, com};
    for (int k = 0; k < 6; ++k) {
        TEST_ASSERT_TRUE(mbs_add_cardan(model, 0, a[k].data(), arm_a[k].data(), 1 + k, low, ex) >=
                         0);
        TEST_ASSERT_TRUE(mbs_add_cardan(model, 13, b[k].data(), arm_b[k].data(), 7 + k, high, ex) >=
                         0);
        const int cylindrical = mbs_add_cylindrical(model, 1 + k, low, ez, 7 + k, high, ez);
        TEST_ASSERT_TRUE(mbs_add_distance_driver(model, cylindrical, NULL) >= 0);
    }
    char msg[MBS_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_MESSAGE(MBS_OK, mbs_model_finalize(model, msg, sizeof msg), msg);
}

void tearDown(void) { mbs_model_free(model); }

static void compare_with(const mbs::Mechanism &m, const std::vector<double> &values,
                         mbs::LinearSolver *dense, mbs::LinearSolver *block) {
    TEST_ASSERT_TRUE(dense->factor(values.data()));
    TEST_ASSERT_TRUE(block->factor(values.data()));
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(-1, 1);
    for (int transposed = 0; transposed <= 1; ++transposed) {
        std::vector<double> x1(m.equations), x2;
        for (double &v : x1) v = uniform(random);
        x2 = x1;
        if (transposed) {
            dense->solve_transposed(x1.data());
            block->solve_transposed(x2.data());
        } else {
            dense->solve(x1.data());
            block->solve(x2.data());
        }
        double scale = 0;
        for (double v : x1) scale = std::fmax(scale, std::fabs(v));
        for (int i = 0; i < m.equations; ++i)
            TEST_ASSERT_DOUBLE_WITHIN(1e-9 * (1 + scale), x1[i], x2[i]);
    }
}

/* Returns how many group factorisations fell back to partial pivoting. */
static long compare(const mbs::Mechanism &m, const std::vector<double> &values) {
    auto dense = mbs::make_linear_solver(m, mbs::LinearSolverKind::Dense);
    auto block = mbs::make_linear_solver(m, mbs::LinearSolverKind::Block);
    TEST_ASSERT_NOT_NULL(block.get());
    compare_with(m, values, dense.get(), block.get());
    TEST_ASSERT_EQUAL(0, (int)dense->fallbacks());
    return block->fallbacks();
}

static std::vector<double> jacobian_at(const mbs::Mechanism &m, const std::vector<double> &q) {
    std::vector<double> values(m.values());
    std::vector<mbs::DriverValue> drive(m.drivers);
    mbs::assemble_jacobian(m, q.data(), drive.data(), values.data());
    return values;
}

static std::vector<double> reference(const mbs::Mechanism &m) {
    std::vector<double> q(m.coordinates);
    mbs::place_at_reference(m, q.data());
    return q;
}

static void test_structure_detected(void) {
    const mbs::Mechanism &m = model->mechanism;
    TEST_ASSERT_NOT_NULL(m.block_plan.get());
    const mbs::BlockPlan &plan = *m.block_plan;
    TEST_ASSERT_EQUAL(7, plan.border);             /* the platform */
    TEST_ASSERT_EQUAL(6, (int)plan.groups.size()); /* the legs */
    for (const mbs::BlockGroup &g : plan.groups) {
        TEST_ASSERT_EQUAL(15, (int)g.rows.size());
        TEST_ASSERT_EQUAL(14, (int)g.cols.size());
        TEST_ASSERT_TRUE(g.has_program);
    }
}

static void test_agrees_at_reference_and_random_configurations(void) {
    const mbs::Mechanism &m = model->mechanism;
    std::vector<double> q = reference(m);
    TEST_ASSERT_EQUAL(0, (int)compare(m, jacobian_at(m, q))); /* the planned order holds */
    std::mt19937 random(11);
    std::uniform_real_distribution<double> uniform(-1, 1);
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<double> p = q;
        for (double &v : p) v += 0.05 * uniform(random);
        compare(m, jacobian_at(m, p)); /* off the constraints: a fallback may be due */
    }
}

/* A planned pivot made tiny next to the rest of its column: the refactorisation must refuse it
 * and pivot afresh (the matrix itself stays regular). */
static void test_fallback_when_a_planned_pivot_is_tiny(void) {
    const mbs::Mechanism &m = model->mechanism;
    const mbs::BlockPlan &plan = *m.block_plan;
    std::vector<double> values = jacobian_at(m, reference(m));
    int changed = 0;
    for (const mbs::BlockGroup &g : plan.groups) {
        const int width = (int)g.cols.size() + plan.border;
        for (int k = 0; k < (int)g.cols.size() && !changed; ++k) {
            if (g.program.below_start[k + 1] == g.program.below_start[k]) continue;
            for (size_t v = 0; v < g.value_dest.size(); ++v)
                if (g.value_dest[v] == g.offset + k * width + k &&
                    values[g.value_index[v]] != 0.0) {
                    values[g.value_index[v]] *= 1e-5;
                    ++changed;
                    break;
                }
        }
        if (changed) break;
    }
    TEST_ASSERT_TRUE(changed > 0);
    TEST_ASSERT_EQUAL(1, (int)compare(m, values)); /* that block alone, and counted */
}

/* One solver refactorised again and again (nothing of an earlier factorisation may leak into a
 * later one), a fallback in between included. */
static void test_repeated_factorisations(void) {
    const mbs::Mechanism &m = model->mechanism;
    auto dense = mbs::make_linear_solver(m, mbs::LinearSolverKind::Dense);
    auto block = mbs::make_linear_solver(m, mbs::LinearSolverKind::Block);
    const std::vector<double> q = reference(m);
    std::mt19937 random(5);
    std::uniform_real_distribution<double> uniform(-1, 1);
    for (int trial = 0; trial < 30; ++trial) {
        std::vector<double> p = q;
        for (double &v : p) v += 0.03 * uniform(random);
        std::vector<double> values = jacobian_at(m, p);
        if (trial == 10) values[m.block_plan->groups[2].value_index[0]] *= 1e-6;
        compare_with(m, values, dense.get(), block.get());
        /* Only trial 10's damaged block pivots afresh; the next trials take the plan again. */
        TEST_ASSERT_EQUAL(trial < 10 ? 0 : 1, (int)block->fallbacks());
    }
}

/* Assembly evaluates each cylindrical joint and its distance driver in one call that forms their
 * common products once (evaluate_cylindrical_with_distance); evaluate_joint runs each joint's own
 * type function alone. The assembled residual and Jacobian must be those, bit for bit, at the
 * reference and at random configurations and driver values. */
static void test_paired_joints_write_the_separate_rows(void) {
    const mbs::Mechanism &m = model->mechanism;
    int paired = 0;
    for (int driver : m.distance_with) paired += driver >= 0;
    TEST_ASSERT_EQUAL(6, paired); /* every leg's pair goes through the shared call */
    std::mt19937 random(13);
    std::uniform_real_distribution<double> uniform(-1, 1);
    std::vector<mbs::DriverValue> drive(m.drivers);
    for (int trial = 0; trial < 10; ++trial) {
        std::vector<double> q = reference(m);
        if (trial > 0)
            for (double &v : q) v += 0.05 * uniform(random);
        for (mbs::DriverValue &d : drive) d.value = uniform(random);
        std::vector<double> phi(m.equations), values(m.values()), phi_only(m.equations);
        mbs::assemble_residual_and_jacobian(m, q.data(), drive.data(), phi.data(), values.data());
        mbs::assemble_residual(m, q.data(), drive.data(), phi_only.data());
        std::vector<double> phi_alone(m.equations), values_alone(m.values());
        for (size_t k = 0; k < m.joints.size(); ++k) {
            double *block = values_alone.data() + m.first_value[k];
            double *block_j = m.joints[k].body_j >= 0
                                  ? block + MBS_BODY_COORDINATES * m.joint_info[k]->equations
                                  : nullptr;
            mbs::evaluate_joint(m, (int)k, q.data(), nullptr, drive.data(),
                                mbs::JointOutput{phi_alone.data() + m.first_row[k], block, block_j,
                                                 nullptr, nullptr});
        }
        TEST_ASSERT_EQUAL_MEMORY(phi_alone.data(), phi.data(), phi.size() * sizeof(double));
        TEST_ASSERT_EQUAL_MEMORY(phi_alone.data(), phi_only.data(), phi.size() * sizeof(double));
        TEST_ASSERT_EQUAL_MEMORY(values_alone.data(), values.data(),
                                 values.size() * sizeof(double));
    }
}

/* The six legs share one elimination program (one pivot order suits every leg's samples, their
 * rows listed alike whatever order the joints came in), so a set of lanes takes them all where
 * the vector has room. */
static void test_legs_share_one_program(void) {
    const mbs::BlockPlan &plan = *model->mechanism.block_plan;
    for (const mbs::BlockGroup &g : plan.groups) {
        TEST_ASSERT_TRUE(g.program.below == plan.groups[0].program.below);
        TEST_ASSERT_TRUE(g.program.span_end == plan.groups[0].program.span_end);
    }
    const mbs::LaneLayout eight = mbs::plan_lane_sets(plan, 8), four = mbs::plan_lane_sets(plan, 4),
                          two = mbs::plan_lane_sets(plan, 2);
    TEST_ASSERT_EQUAL(1, (int)eight.sets.size());
    TEST_ASSERT_EQUAL(6, (int)eight.sets[0].groups.size());
    TEST_ASSERT_EQUAL(2, (int)four.sets.size()); /* 4 + 2 (two pad lanes) */
    TEST_ASSERT_EQUAL(3, (int)two.sets.size());
    TEST_ASSERT_EQUAL(0, (int)mbs::plan_lane_sets(plan, 1).sets.size());
}

/* Each lane does the scalar path's operations in its order: solves and transposed solves of the
 * lane solvers (every kernel this CPU runs) equal one group at a time bit for bit, at the
 * reference, at random configurations, and with one leg's planned pivot refused (that leg alone
 * falls back to partial pivoting, its lane's results unused). */
static void test_lanes_equal_one_group_at_a_time(void) {
    const mbs::Mechanism &m = model->mechanism;
    const mbs::LaneKernels *kernels[mbs::kMaxLaneKernels];
    const int count = mbs::runnable_lane_kernels(kernels);
    TEST_ASSERT_TRUE(count >= 1);
    auto scalar = mbs::make_block_solver(m, nullptr);
    std::mt19937 random(17);
    std::uniform_real_distribution<double> uniform(-1, 1);
    const std::vector<double> q = reference(m);
    for (int trial = 0; trial < 12; ++trial) {
        std::vector<double> p = q;
        if (trial > 0)
            for (double &v : p) v += 0.03 * uniform(random);
        std::vector<double> values = jacobian_at(m, p);
        if (trial == 5) values[m.block_plan->groups[3].value_index[0]] *= 1e-6;
        TEST_ASSERT_TRUE(scalar->factor(values.data()));
        std::vector<double> rhs(m.equations);
        for (double &v : rhs) v = uniform(random);
        std::vector<double> x0 = rhs, y0 = rhs;
        scalar->solve(x0.data());
        scalar->solve_transposed(y0.data());
        for (int k = 0; k < count; ++k) {
            auto lanes = mbs::make_block_solver(m, kernels[k]);
            TEST_ASSERT_TRUE(lanes->factor(values.data()));
            TEST_ASSERT_EQUAL_MESSAGE(trial == 5 ? 1 : 0, (int)lanes->fallbacks(),
                                      kernels[k]->name);
            std::vector<double> x = rhs, y = rhs;
            lanes->solve(x.data());
            lanes->solve_transposed(y.data());
            TEST_ASSERT_EQUAL_MEMORY_MESSAGE(x0.data(), x.data(), x.size() * sizeof(double),
                                             kernels[k]->name);
            TEST_ASSERT_EQUAL_MEMORY_MESSAGE(y0.data(), y.data(), y.size() * sizeof(double),
                                             kernels[k]->name);
        }
    }
    TEST_ASSERT_EQUAL(1, (int)scalar->fallbacks());
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_structure_detected);
    RUN_TEST(test_agrees_at_reference_and_random_configurations);
    RUN_TEST(test_fallback_when_a_planned_pivot_is_tiny);
    RUN_TEST(test_repeated_factorisations);
    RUN_TEST(test_paired_joints_write_the_separate_rows);
    RUN_TEST(test_legs_share_one_program);
    RUN_TEST(test_lanes_equal_one_group_at_a_time);
    return UNITY_END();
}
