// The core's linear algebra against well-kept libraries, on the full inverse step's own systems:
// the constraint Jacobian Phi_q of the 14-body platform (98 x 98) at poses along the combined cue,
// factorised and solved once transposed for the multipliers (Phi_q^T lambda = Q - M q_ddot),
// which is what a full step asks of it. Variants (each an extern "C" function, so that
// studies/bench/linear_solvers.sh can count its instructions with callgrind --toggle-collect):
//   linear_block        ours: the bordered-block LU (refactorisation on a fixed pivot order),
//                       the legs side by side in the lane kernels the CPU's best choice
//   linear_block_groups ours: the same one leg block at a time (no lanes)
//   linear_block_2/4/8  ours: the same on the 2-, 4- or 8-lane kernels (lane_lu.hpp: 8 in two
//                       AVX2 registers), where this CPU runs them
//   linear_dense        ours: dense LU with partial pivoting
//   linear_klu          SUNDIALS' KLU linear solver (SuiteSparse; refactorisation after the first)
//   linear_eigen_sparse Eigen's SparseLU (pattern analysed once, factorised every step)
//   linear_eigen_dense  Eigen's PartialPivLU on the dense matrix
// Prints the median nanoseconds per factorisation + solve and the largest residual
// |Phi_q^T lambda - g| relative to |g| of each; `bench-linear VARIANT N` runs only that variant
// N times (for the profiler).
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <nvector/nvector_serial.h>

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "bench/bench_support.hpp"
#include "bench/combined_cue.hpp"
#include "core/assembly.hpp"
#include "core/dynamics.hpp"
#include "core/lane_lu.hpp"
#include "core/linear_solver.hpp"
#include "core/step.hpp"
#include "core/sundials_holder.hpp"
#include "bench/full_platform.hpp"

namespace {

// One system: Jacobian values (the mechanism's pattern) and the right-hand side g.
struct Sample {
    std::vector<double> values, g;
};

// Every variant: set up once on the mechanism, then factor + transposed solve per sample.
struct Variants {
    const mbs::Mechanism &m;
    const int n;
    std::vector<int> entries;  // structural Jacobian values (the others are zero everywhere)
    std::unique_ptr<mbs::LinearSolver> block, dense, groups, lanes[4];  // lanes[k]: 2^k lanes
    // KLU on A = Phi_q^T in compressed columns (column j of A = row j of Phi_q).
    mbs::sundials::Context context;
    mbs::sundials::Matrix klu_matrix;
    mbs::sundials::LinearSolver klu;
    mbs::sundials::Vector klu_x, klu_b;
    std::vector<int> klu_slot;  // per structural entry: its place in the KLU matrix data
    // Eigen: the same A.
    Eigen::SparseMatrix<double> eigen_a;
    std::vector<int> eigen_slot;
    Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> eigen_sparse;
    Eigen::MatrixXd eigen_dense_a;
    Eigen::PartialPivLU<Eigen::MatrixXd> eigen_dense;

    explicit Variants(const mbs::Mechanism &mech) : m(mech), n(mech.equations) {
        const std::vector<char> &structural = m.block_plan->structural;
        for (int t = 0; t < m.values(); ++t)
            if (structural[t]) entries.push_back(t);
        block = mbs::make_linear_solver(m, mbs::LinearSolverKind::Block);
        dense = mbs::make_linear_solver(m, mbs::LinearSolverKind::Dense);
        groups = mbs::make_block_solver(m, nullptr);
        const mbs::LaneKernels *kernels[mbs::kMaxLaneKernels];
        const int count = mbs::runnable_lane_kernels(kernels);
        for (int k = 0; k < count; ++k)
            for (int w = 1; w < 4; ++w)
                if (kernels[k]->lanes == 1 << w) lanes[w] = mbs::make_block_solver(m, kernels[k]);
        // A(col(t), row(t)) = Phi_q(row(t), col(t)): sort the entries by A's column, then row.
        std::vector<int> order(entries.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
        auto a_col = [&](int i) { return m.pattern_row[entries[i]]; };
        auto a_row = [&](int i) { return m.pattern_col[entries[i]]; };
        std::sort(order.begin(), order.end(), [&](int x, int y) {
            return a_col(x) != a_col(y) ? a_col(x) < a_col(y) : a_row(x) < a_row(y);
        });
        context = mbs::sundials::make_context();
        klu_matrix.reset(SUNSparseMatrix(n, n, static_cast<sunindextype>(entries.size()), CSC_MAT,
                                         context.get()));
        sunindextype *colptr = SUNSparseMatrix_IndexPointers(klu_matrix.get());
        sunindextype *rowind = SUNSparseMatrix_IndexValues(klu_matrix.get());
        klu_slot.assign(entries.size(), 0);
        std::vector<Eigen::Triplet<double>> triplets;
        for (int c = 0; c <= n; ++c) colptr[c] = 0;
        for (size_t k = 0; k < order.size(); ++k) {
            const int i = order[k];
            rowind[k] = a_row(i);
            ++colptr[a_col(i) + 1];
            klu_slot[i] = static_cast<int>(k);
            triplets.emplace_back(a_row(i), a_col(i), 1.0);
        }
        for (int c = 0; c < n; ++c) colptr[c + 1] += colptr[c];
        klu_x.reset(N_VNew_Serial(n, context.get()));
        klu_b.reset(N_VNew_Serial(n, context.get()));
        klu.reset(SUNLinSol_KLU(klu_x.get(), klu_matrix.get(), context.get()));
        eigen_a.resize(n, n);
        eigen_a.setFromTriplets(triplets.begin(), triplets.end());
        eigen_a.makeCompressed();
        // Where each entry's value lives in Eigen's compressed storage.
        eigen_slot.assign(entries.size(), 0);
        for (size_t i = 0; i < entries.size(); ++i) {
            const int r = a_row(static_cast<int>(i)), c = a_col(static_cast<int>(i));
            for (int p = eigen_a.outerIndexPtr()[c]; p < eigen_a.outerIndexPtr()[c + 1]; ++p)
                if (eigen_a.innerIndexPtr()[p] == r) eigen_slot[i] = p;
        }
        eigen_sparse.analyzePattern(eigen_a);
        eigen_dense_a.setZero(n, n);
    }
};

Variants *variants = nullptr;  // the bench's one instance, for the extern "C" entry points

}  // namespace

extern "C" {

__attribute__((noinline)) int linear_block(const Sample *s, double *lambda) {
    Variants &v = *variants;
    if (!v.block->factor(s->values.data())) return 0;
    std::copy(s->g.begin(), s->g.end(), lambda);
    v.block->solve_transposed(lambda);
    return 1;
}

// The block LU through a given solver (null: the kernel does not run on this CPU).
int block_with(mbs::LinearSolver *solver, const Sample *s, double *lambda) {
    if (!solver || !solver->factor(s->values.data())) return 0;
    std::copy(s->g.begin(), s->g.end(), lambda);
    solver->solve_transposed(lambda);
    return 1;
}

__attribute__((noinline)) int linear_block_groups(const Sample *s, double *lambda) {
    return block_with(variants->groups.get(), s, lambda);
}
__attribute__((noinline)) int linear_block_2(const Sample *s, double *lambda) {
    return block_with(variants->lanes[1].get(), s, lambda);
}
__attribute__((noinline)) int linear_block_4(const Sample *s, double *lambda) {
    return block_with(variants->lanes[2].get(), s, lambda);
}
__attribute__((noinline)) int linear_block_8(const Sample *s, double *lambda) {
    return block_with(variants->lanes[3].get(), s, lambda);
}

__attribute__((noinline)) int linear_dense(const Sample *s, double *lambda) {
    Variants &v = *variants;
    if (!v.dense->factor(s->values.data())) return 0;
    std::copy(s->g.begin(), s->g.end(), lambda);
    v.dense->solve_transposed(lambda);
    return 1;
}

__attribute__((noinline)) int linear_klu(const Sample *s, double *lambda) {
    Variants &v = *variants;
    double *data = SUNSparseMatrix_Data(v.klu_matrix.get());
    for (size_t i = 0; i < v.entries.size(); ++i) data[v.klu_slot[i]] = s->values[v.entries[i]];
    if (SUNLinSolSetup(v.klu.get(), v.klu_matrix.get()) != 0) return 0;
    std::copy(s->g.begin(), s->g.end(), N_VGetArrayPointer(v.klu_b.get()));
    if (SUNLinSolSolve(v.klu.get(), v.klu_matrix.get(), v.klu_x.get(), v.klu_b.get(), 0.0) != 0)
        return 0;
    std::copy(N_VGetArrayPointer(v.klu_x.get()), N_VGetArrayPointer(v.klu_x.get()) + v.n, lambda);
    return 1;
}

__attribute__((noinline)) int linear_eigen_sparse(const Sample *s, double *lambda) {
    Variants &v = *variants;
    double *data = v.eigen_a.valuePtr();
    for (size_t i = 0; i < v.entries.size(); ++i) data[v.eigen_slot[i]] = s->values[v.entries[i]];
    v.eigen_sparse.factorize(v.eigen_a);
    if (v.eigen_sparse.info() != Eigen::Success) return 0;
    Eigen::Map<Eigen::VectorXd>(lambda, v.n) =
        v.eigen_sparse.solve(Eigen::Map<const Eigen::VectorXd>(s->g.data(), v.n));
    return 1;
}

__attribute__((noinline)) int linear_eigen_dense(const Sample *s, double *lambda) {
    Variants &v = *variants;
    for (int t : v.entries) v.eigen_dense_a(v.m.pattern_col[t], v.m.pattern_row[t]) = s->values[t];
    v.eigen_dense.compute(v.eigen_dense_a);
    Eigen::Map<Eigen::VectorXd>(lambda, v.n) =
        v.eigen_dense.solve(Eigen::Map<const Eigen::VectorXd>(s->g.data(), v.n));
    return 1;
}

}  // extern "C"

namespace {

using Variant = int (*)(const Sample *, double *);
struct Named {
    const char *name;
    Variant run;
};
const Named kVariants[] = {{"linear_block", linear_block},
                           {"linear_block_groups", linear_block_groups},
                           {"linear_block_2", linear_block_2},
                           {"linear_block_4", linear_block_4},
                           {"linear_block_8", linear_block_8},
                           {"linear_dense", linear_dense},
                           {"linear_klu", linear_klu},
                           {"linear_eigen_sparse", linear_eigen_sparse},
                           {"linear_eigen_dense", linear_eigen_dense}};

// |Phi_q^T lambda - g|_max / |g|_max.
double residual(const mbs::Mechanism &m, const Sample &s, const double *lambda) {
    std::vector<double> r(s.g);
    double scale = 0;
    for (double x : s.g) scale = std::max(scale, std::fabs(x));
    for (int t = 0; t < m.values(); ++t)
        r[m.pattern_col[t]] -= s.values[t] * lambda[m.pattern_row[t]];
    double worst = 0;
    for (double x : r) worst = std::max(worst, std::fabs(x));
    return worst / scale;
}

}  // namespace

int main(int argc, char **argv) {
    stewart_params params;
    stewart_params_default(&params);
    char msg[STEWART_MESSAGE_SIZE];
    const FullPlatform platform(params);
    if (!platform.full) return 1;
    const FullPlatform *model = &platform;
    const mbs::Mechanism &m = model->full->mechanism;
    // The systems of 200 full steps along the cue (1 kHz).
    std::vector<Sample> samples(200);
    {
        mbs::State state(m);
        stewart_inverse_options o;
        stewart_inverse_options_default(&o);
        o.fidelity = STEWART_FULL;
        for (size_t i = 0; i < samples.size(); ++i) {
            const stewart::Motion motion = stewart::motion_of_pose(combined_cue(1e-3 * i));
            stewart::LegKinematics legs;
            stewart::leg_kinematics(model->geometry, motion, legs, msg, sizeof msg);
            stewart_inverse_output out{};
            if (stewart::full_solve(model->full_layout, state, o, motion, legs, out, msg,
                                    sizeof msg) != STEWART_OK) {
                std::fprintf(stderr, "bench-linear: %s\n", msg);
                return 1;
            }
            Sample &s = samples[i];
            s.values.resize(m.values());
            mbs::assemble_jacobian(m, state.q.data(), state.drive.data(), s.values.data());
            s.g.resize(m.coordinates);
            mbs::applied_minus_inertial(m, state.q.data(), state.q_dot.data(), state.q_ddot.data(),
                                        s.g.data());
        }
    }
    Variants v(m);
    variants = &v;
    std::vector<double> lambda(m.equations);
    if (argc > 2) {  // one variant, N times (for callgrind)
        const int count = std::atoi(argv[2]);
        for (const Named &named : kVariants)
            if (!std::strcmp(named.name, argv[1])) {
                for (int i = 0; i < count; ++i)
                    if (!named.run(&samples[i % samples.size()], lambda.data())) return 1;
                return 0;
            }
        std::fprintf(stderr, "bench-linear: unknown variant %s\n", argv[1]);
        return 2;
    }
    std::printf("Phi_q of the full step (%d x %d, %zu structural nonzeros), factorisation + one "
                "transposed solve,\n%zu systems along the combined cue, median of 25 passes:\n",
                m.equations, m.coordinates, v.entries.size(), samples.size());
    for (const Named &named : kVariants)  // one pass each first: none is timed cold
        for (const Sample &s : samples) named.run(&s, lambda.data());
    for (const Named &named : kVariants) {
        if (!named.run(&samples[0], lambda.data())) {
            std::printf("  %-20s not run on this CPU\n", named.name);
            continue;
        }
        std::vector<double> ns;
        double worst = 0;
        for (int pass = 0; pass < 25; ++pass)
            for (const Sample &s : samples) {
                const auto start = bench::Clock::now();
                const int ok = named.run(&s, lambda.data());
                ns.push_back(bench::ns_since(start));
                worst = std::max(worst, ok ? residual(m, s, lambda.data()) : INFINITY);
            }
        std::printf("  %-20s %9.0f ns   largest relative residual %.2g\n", named.name,
                    bench::median(ns), worst);
    }
    return 0;
}
