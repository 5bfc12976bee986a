// Nanoseconds per pose for the kinematic and massless-leg levels: the median over repeated
// batches of the thesis yaw manoeuvre, printed and (with an argument) appended to a file.
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench/bench_support.hpp"

namespace {

std::vector<stewart_pose> yaw_manoeuvre(int n) {
    std::vector<stewart_pose> poses(n);
    const double w = 5.0, a = M_PI / 18.0;
    for (int i = 0; i < n; ++i) {
        const double t = 12.0 * i / (n - 1);
        stewart_pose &p = poses[i];
        p = stewart_pose{};
        p.q[2] = 0.5;
        p.q[5] = a * std::sin(w * t);
        p.q_dot[5] = a * w * std::cos(w * t);
        p.q_ddot[5] = -a * w * w * std::sin(w * t);
    }
    return poses;
}

double median_ns_per_pose(const stewart_model *m, stewart_fidelity f,
                          const std::vector<stewart_pose> &poses, double *checksum) {
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = f;
    stewart_inverse *d = stewart_inverse_create(m, &o, nullptr, 0);
    if (!d) return 0;
    stewart_inverse_output out;
    stewart_inverse_input in{};
    std::vector<double> batches;
    for (int b = 0; b < 201; ++b) {
        const auto start = bench::Clock::now();
        for (const stewart_pose &p : poses) {
            in.pose = p;
            stewart_inverse_solve(d, &in, &out);
            *checksum += out.lengths.length[0] + out.force[0];
        }
        batches.push_back(bench::ns_since(start) / poses.size());
    }
    stewart_inverse_free(d);
    return bench::median(batches);
}

}  // namespace

int main(int argc, char **argv) {
    stewart_model *m = bench::make_model("bench-closed-form");
    if (!m) return 1;
    const std::vector<stewart_pose> poses = yaw_manoeuvre(1201);
    double checksum = 0;
    const double kin = median_ns_per_pose(m, STEWART_KINEMATIC, poses, &checksum);
    const double mass = median_ns_per_pose(m, STEWART_MASSLESS, poses, &checksum);
    char report[256];
    std::snprintf(
        report, sizeof report,
        "closed-form levels, median of 201 batches of 1201 poses (yaw manoeuvre):\n"
        "  kinematic: %.1f ns/pose\n  massless:  %.1f ns/pose\n  ratio massless/kinematic: %.2f\n",
        kin, mass, mass / kin);
    std::fputs(report, stdout);
    std::fprintf(stderr, "(checksum %g)\n", checksum);
    if (argc > 1) {
        FILE *f = std::fopen(argv[1], "w");
        if (f) {
            std::fputs(report, f);
            std::fclose(f);
        }
    }
    stewart_model_free(m);
    return 0;
}
