// Microseconds per full step (position + velocity + acceleration + multipliers) of the 14-body
// platform along the thesis yaw manoeuvre, for our solver (KINSOL with the bordered-block LU) and
// for a dense baseline (KINSOL's SUNDenseMatrix + SUNLinSol_Dense for Newton, dense LU for the
// rest). Two initial-guess strategies: the closed-form placement (the product's path) and the
// generic predictor q + h q_dot + h^2/2 q_ddot. Prints the medians and writes them to argv[1].
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench/bench_support.hpp"
#include "bench/full_platform.hpp"
#include "core/step.hpp"
#include "util/message.hpp"

namespace {

struct Sample {
    double t;
    stewart_pose pose;
};

std::vector<Sample> yaw_manoeuvre(int n, double duration) {
    std::vector<Sample> s(n);
    const double w = 5.0, a = M_PI / 18.0;
    for (int i = 0; i < n; ++i) {
        const double t = duration * i / (n - 1);
        stewart_pose &p = s[i].pose;
        p = stewart_pose{};
        p.q[2] = 0.5;
        p.q[5] = a * std::sin(w * t);
        p.q_dot[5] = a * w * std::cos(w * t);
        p.q_ddot[5] = -a * w * w * std::sin(w * t);
        s[i].t = t;
    }
    return s;
}

struct Result {
    double median_us = 0, mean_iterations = 0;
    int max_iterations = 0;
    double checksum = 0;
    bool ok = true;
};

Result run(const FullPlatform &model, const mbs::SolverOptions &kind, bool closed_form,
           const std::vector<Sample> &samples, int passes) {
    mbs::State state(model.full->mechanism, kind);
    Result r;
    if (!state.ok()) {
        std::fprintf(stderr, "solver creation failed: %s\n", state.message);
        r.ok = false;
        return r;
    }
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = STEWART_FULL;
    std::vector<double> times;
    times.reserve(samples.size() * passes);
    long iterations = 0, steps = 0;
    char msg[STEWART_MESSAGE_SIZE];
    for (int pass = 0; pass < passes; ++pass) {
        mbs::reset_history(state);
        for (const Sample &smp : samples) {
            const auto start = bench::Clock::now();
            const stewart::Motion motion = stewart::motion_of_pose(smp.pose);
            stewart::LegKinematics legs;
            stewart::leg_kinematics(model.geometry, motion, legs, msg, sizeof msg);
            stewart_status s;
            stewart_inverse_output out{};
            if (closed_form || !state.has_history) {
                s = stewart::full_solve(model.full_layout, state, o, motion, legs, out, msg,
                                        sizeof msg);
            } else {
                stewart::full_set_drivers(model.full_layout, motion, legs, state);
                s = stewart::from_mbs(mbs::solve_step(state, smp.t, kind, true));
                out.force[0] = -state.lambda[model.full->mechanism
                                                 .first_row[model.full_layout.driver_joint[0]]];
                out.iterations = state.stats.iterations;
            }
            const double us = 1e-3 * bench::ns_since(start);
            if (s != STEWART_OK) {
                std::fprintf(stderr, "step at t = %g failed: %s\n", smp.t, msg);
                r.ok = false;
                return r;
            }
            times.push_back(us);
            iterations += out.iterations;
            r.max_iterations = std::max(r.max_iterations, out.iterations);
            ++steps;
            r.checksum += out.force[0];
        }
    }
    r.median_us = bench::median(std::move(times));
    r.mean_iterations = static_cast<double>(iterations) / steps;
    return r;
}

}  // namespace

int main(int argc, char **argv) {
    stewart_params params;
    stewart_params_default(&params);
    const FullPlatform model(params);
    if (!model.full) return 1;
    // The thesis sampling (0.1 s) for the closed-form guess; a finer 1 ms step for the predictor.
    const std::vector<Sample> coarse = yaw_manoeuvre(121, 12.0);
    const std::vector<Sample> fine = yaw_manoeuvre(12001, 12.0);
    mbs::SolverOptions ours, dense;
    dense.linear = mbs::LinearSolverKind::Dense;
    dense.kinsol_dense = true;

    const Result a = run(model, ours, true, coarse, 200);
    // BENCH_OURS_ONLY=1: only our solver, longer (for a profiler).
    if (std::getenv("BENCH_OURS_ONLY")) {
        run(model, ours, true, coarse, 2000);
        return 0;
    }
    const Result b = run(model, dense, true, coarse, 5);
    const Result c = run(model, ours, false, fine, 3);
    const Result d = run(model, dense, false, fine, 1);
    if (!a.ok || !b.ok || !c.ok || !d.ok) return 1;

    char report[2048];
    std::snprintf(
        report, sizeof report,
        "full level (14 bodies, 98 coordinates), yaw manoeuvre, median us per full step\n"
        "(position + velocity + acceleration + multipliers), -O2:\n"
        "  closed-form initial guess, 121 poses (0.1 s):\n"
        "    block LU (ours):        %8.2f us   Newton iterations/step mean %.3f max %d\n"
        "    dense baseline:         %8.2f us   Newton iterations/step mean %.3f max %d\n"
        "    ratio dense/ours:       %8.1f\n"
        "  predictor q + h q_dot + h^2/2 q_ddot, 12001 poses (1 ms):\n"
        "    block LU (ours):        %8.2f us   Newton iterations/step mean %.3f max %d\n"
        "    dense baseline:         %8.2f us   Newton iterations/step mean %.3f max %d\n"
        "    ratio dense/ours:       %8.1f\n"
        "(dense baseline: KINSOL with SUNDenseMatrix + SUNLinSol_Dense for the Newton iterations,\n"
        " dense LU of Phi_q for velocity, acceleration and multipliers; ours: KINSOL with the\n"
        " bordered-block LU behind a custom SUNLinearSolver for all of them)\n",
        a.median_us, a.mean_iterations, a.max_iterations, b.median_us, b.mean_iterations,
        b.max_iterations, b.median_us / a.median_us, c.median_us, c.mean_iterations,
        c.max_iterations, d.median_us, d.mean_iterations, d.max_iterations,
        d.median_us / c.median_us);
    std::fputs(report, stdout);
    std::fprintf(stderr, "(checksum %.6g)\n", a.checksum + b.checksum + c.checksum + d.checksum);
    if (argc > 1) {
        FILE *f = std::fopen(argv[1], "w");
        if (!f) {
            std::fprintf(stderr, "cannot write %s\n", argv[1]);
            return 1;
        }
        std::fputs(report, f);
        std::fclose(f);
    }
    return 0;
}
