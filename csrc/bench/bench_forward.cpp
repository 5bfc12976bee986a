// Forward kinematics speed: microseconds per solve and Newton iterations (median, p99, max) for
// (a) tracking the combined cue at 1 kHz and (b) cold starts from home over random poses of the
// stroke workspace, for the library's solver (KINSOL, analytic Jacobian, predictor) and for a
// plain hand-written Newton with a finite-difference Jacobian warm-started from the last pose
// (what most open-source forward kinematics does). Also counts wrong answers (pose off the
// closed-form truth by more than 1e-9). Prints one table and writes it to argv[1] if given
// (argv[2]: tracking solves, 1e6 by default).
// `bench-forward --map MAP.csv` instead writes the cold-start convergence map over three slices
// of the workspace through home (studies/forward_convergence.py plots it).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench/bench_support.hpp"
#include "stewart/stewart_forward.h"

namespace {

using bench::Clock;
using bench::percentile;

struct Sample {
    double truth[6];
    double length[6], rate[6], accel[6];
};

struct Stats {
    std::vector<double> us;
    std::vector<int> iterations;
    long wrong = 0, failed = 0;
};

// ---- the baseline: a plain Newton with a forward-difference Jacobian, written out ----------
struct Geometry {
    double base[6][3], plate[6][3];
};

void baseline_lengths(const Geometry &g, const double q[6], double L[6]) {
    const double cr = std::cos(q[3]), sr = std::sin(q[3]), cp = std::cos(q[4]), sp = std::sin(q[4]),
                 cy = std::cos(q[5]), sy = std::sin(q[5]);
    const double R[3][3] = {{cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr},
                            {sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr},
                            {-sp, cp * sr, cp * cr}};
    for (int k = 0; k < 6; ++k) {
        double d2 = 0;
        for (int i = 0; i < 3; ++i) {
            const double d = q[i] + R[i][0] * g.plate[k][0] + R[i][1] * g.plate[k][1] +
                             R[i][2] * g.plate[k][2] - g.base[k][i];
            d2 += d * d;
        }
        L[k] = std::sqrt(d2);
    }
}

// Gaussian elimination with partial pivoting: A x = b, in place; false if singular.
bool gauss_solve(double A[6][6], double b[6]) {
    for (int c = 0; c < 6; ++c) {
        int p = c;
        for (int r = c + 1; r < 6; ++r)
            if (std::fabs(A[r][c]) > std::fabs(A[p][c])) p = r;
        if (!(std::fabs(A[p][c]) > 1e-14)) return false;
        std::swap(A[p], A[c]);
        std::swap(b[p], b[c]);
        for (int r = c + 1; r < 6; ++r) {
            const double f = A[r][c] / A[c][c];
            for (int j = c; j < 6; ++j) A[r][j] -= f * A[c][j];
            b[r] -= f * b[c];
        }
    }
    for (int c = 5; c >= 0; --c) {
        for (int j = c + 1; j < 6; ++j) b[c] -= A[c][j] * b[j];
        b[c] /= A[c][c];
    }
    return true;
}

// Newton from q to |L(q) - target|_max <= tol; returns iterations, or -1.
int baseline_newton(const Geometry &g, const double target[6], double q[6], double tol) {
    double L[6], F[6];
    for (int it = 0; it <= 50; ++it) {
        baseline_lengths(g, q, L);
        double worst = 0;
        for (int k = 0; k < 6; ++k)
            F[k] = L[k] - target[k], worst = std::max(worst, std::fabs(F[k]));
        if (worst <= tol) return it;
        double J[6][6];
        for (int j = 0; j < 6; ++j) {
            const double h = 1e-7 * std::max(1.0, std::fabs(q[j]));
            double qh[6], Lh[6];
            std::copy(q, q + 6, qh);
            qh[j] += h;
            baseline_lengths(g, qh, Lh);
            for (int k = 0; k < 6; ++k) J[k][j] = (Lh[k] - L[k]) / h;
        }
        if (!gauss_solve(J, F)) return -1;
        for (int j = 0; j < 6; ++j) q[j] -= F[j];
    }
    return -1;
}

// The library's solvers of one model: inverse kinematics (kinematic and massless levels, for the
// samples' lengths) and forward kinematics.
struct Solvers {
    stewart_inverse *kinematic = nullptr, *massless = nullptr;
    stewart_forward *forward = nullptr;
};

// One forward solve from arrays (rates, accels and guess may be null).
stewart_status forward_solve(stewart_forward *f, double t, const double *L, const double *rates,
                             const double *accels, const double *guess, stewart_forward_output *r) {
    stewart_forward_input in{};
    in.time = t;
    std::copy(L, L + 6, in.lengths.length);
    if (rates) std::copy(rates, rates + 6, in.lengths.length_rate);
    if (accels) std::copy(accels, accels + 6, in.lengths.length_accel);
    in.derivatives = accels ? 2 : rates ? 1 : 0;
    in.use_guess = guess != nullptr;
    if (guess) std::copy(guess, guess + 6, in.guess);
    return stewart_forward_solve(f, &in, r);
}

// ---- the samples ---------------------------------------------------------------------------
// Samples first .. first + count - 1 of the combined cue at 1 kHz (continuous over chunks).
std::vector<Sample> combined_cue(const stewart_model *m, Solvers *d, long first, int count) {
    const double amp[6] = {0.05, 0.04, 0.03, 0.10, 0.08, 0.15},
                 w[6] = {3.0, 2.0, 4.0, 2.5, 3.5, 1.5}, ph[6] = {0.1, 0.7, 0.3, 1.1, 0.4, 0.9};
    std::vector<Sample> out;
    for (long i = first; i < first + count; ++i) {
        const double t = 1e-3 * static_cast<double>(i);
        stewart_pose p{};
        for (int j = 0; j < 6; ++j) {
            p.q[j] = (j == 2 ? 0.5 : 0.0) + amp[j] * std::sin(w[j] * t + ph[j]);
            p.q_dot[j] = amp[j] * w[j] * std::cos(w[j] * t + ph[j]);
            p.q_ddot[j] = -amp[j] * w[j] * w[j] * std::sin(w[j] * t + ph[j]);
        }
        stewart_inverse_output legs;
        const stewart_inverse_input in = {p};
        stewart_inverse_solve(d->kinematic, &in, &legs);
        Sample s;
        std::copy(p.q, p.q + 6, s.truth);
        std::copy(legs.lengths.length, legs.lengths.length + 6, s.length);
        std::copy(legs.lengths.length_rate, legs.lengths.length_rate + 6, s.rate);
        std::copy(legs.lengths.length_accel, legs.lengths.length_accel + 6, s.accel);
        out.push_back(s);
    }
    return out;
}

// Random poses with every length inside the stroke and condition below 1e3.
std::vector<Sample> workspace(const stewart_model *m, Solvers *d, int n) {
    const stewart_params *p = stewart_model_params(m);
    unsigned long long state = 2024;
    auto uniform = [&](double lo, double hi) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return lo + (hi - lo) * static_cast<double>(state >> 11) / 9007199254740992.0;
    };
    std::vector<Sample> out;
    const double box[6] = {0.15, 0.15, 0.15, 0.35, 0.35, 0.45};
    while (static_cast<int>(out.size()) < n) {
        stewart_pose pose{};
        for (int i = 0; i < 6; ++i) pose.q[i] = uniform(-box[i], box[i]) + (i == 2 ? 0.5 : 0);
        stewart_inverse_output legs;
        const stewart_inverse_input in = {pose};
        if (stewart_inverse_solve(d->massless, &in, &legs) != STEWART_OK || legs.condition > 1e3)
            continue;
        bool inside = true;
        for (int k = 0; k < 6; ++k)
            inside = inside && legs.lengths.length[k] >= p->stroke_min[k] &&
                     legs.lengths.length[k] <= p->stroke_max[k];
        if (!inside) continue;
        Sample s{};
        std::copy(pose.q, pose.q + 6, s.truth);
        std::copy(legs.lengths.length, legs.lengths.length + 6, s.length);
        out.push_back(s);
    }
    return out;
}

bool wrong(const double *q, const double *truth) {
    for (int i = 0; i < 6; ++i)
        if (!(std::fabs(q[i] - truth[i]) <= 1e-9)) return true;
    return false;
}

double micros(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::micro>(b - a).count();
}

// ---- the runs ------------------------------------------------------------------------------
constexpr int kChunk = 12000;  // samples generated (untimed) at a time

// Tracking the cue; with_rates: the lengths' rates and accelerations given (Taylor predictor,
// pose rates and accelerations out), else the lengths only (chord predictor, pose only).
Stats ours_tracking(const stewart_model *m, Solvers *d, long solves, bool with_rates) {
    Stats st;
    stewart_forward_output r;
    stewart_forward_reset(d->forward);
    for (long first = 0; first <= solves; first += kChunk) {
        const std::vector<Sample> cue = combined_cue(m, d, first, kChunk);
        for (int i = 0; i < kChunk; ++i) {
            const Sample &s = cue[i];
            const double t = 1e-3 * static_cast<double>(first + i);
            const auto a = Clock::now();
            const stewart_status status =
                forward_solve(d->forward, t, s.length, with_rates ? s.rate : nullptr,
                              with_rates ? s.accel : nullptr, nullptr, &r);
            const auto b = Clock::now();
            if (first + i == 0) continue;  // the very first solve is a cold start
            if (static_cast<long>(st.us.size()) == solves) break;
            st.us.push_back(micros(a, b));
            st.iterations.push_back(r.iterations);
            if (status != STEWART_OK) ++st.failed;
            else if (wrong(r.pose.q, s.truth)) ++st.wrong;
        }
    }
    return st;
}

Stats ours_cold(const stewart_model *m, Solvers *d, const std::vector<Sample> &poses) {
    Stats st;
    stewart_forward_output r;
    for (const Sample &s : poses) {
        stewart_forward_reset(d->forward);
        const auto a = Clock::now();
        const stewart_status status =
            forward_solve(d->forward, 0, s.length, nullptr, nullptr, nullptr, &r);
        const auto b = Clock::now();
        st.us.push_back(micros(a, b));
        st.iterations.push_back(r.iterations);
        if (status != STEWART_OK) ++st.failed;
        else if (wrong(r.pose.q, s.truth)) ++st.wrong;
    }
    return st;
}

// The baseline over samples: tracking (warm start from its last pose) or cold (from home).
void baseline_run(const Geometry &g, const std::vector<Sample> &samples, bool tracking,
                  double home_z, double q[6], bool &first, Stats &st) {
    for (const Sample &s : samples) {
        if (!tracking || first) std::fill(q, q + 6, 0.0), q[2] = home_z;
        const auto a = Clock::now();
        const int it = baseline_newton(g, s.length, q, 1e-12);
        const auto b = Clock::now();
        if (tracking && first) {
            first = false;
            continue;
        }
        st.us.push_back(micros(a, b));
        st.iterations.push_back(it);
        if (it < 0) ++st.failed, std::fill(q, q + 6, 0.0), q[2] = home_z;
        else if (wrong(q, s.truth)) ++st.wrong;
    }
}

std::string line(const char *name, const Stats &s) {
    std::vector<double> it(s.iterations.begin(), s.iterations.end());
    char text[256];
    std::snprintf(text, sizeof text,
                  "  %-34s %8.3f %8.3f %8.3f   %4.0f %4.0f %4.0f   %8ld %6ld %6ld\n", name,
                  percentile(s.us, 0.5), percentile(s.us, 0.99),
                  *std::max_element(s.us.begin(), s.us.end()), percentile(it, 0.5),
                  percentile(it, 0.99), *std::max_element(it.begin(), it.end()),
                  static_cast<long>(s.us.size()), s.wrong, s.failed);
    return text;
}

// One cold start from home per grid point of three slices through home (x-y, roll-pitch,
// yaw-z): the outcome against the pose the lengths came from.
int write_map(const stewart_model *m, Solvers *d, const char *path) {
    FILE *out = std::fopen(path, "w");
    if (!out) return 1;
    std::fprintf(out,
                 "slice,u,v,inside_stroke,condition,truth_branch,status,iterations,branch,error\n");
    const stewart_params *p = stewart_model_params(m);
    struct Slice {
        const char *name;
        int u, v;
        double u0, u1, v0, v1;
    };
    const Slice slices[3] = {{"x-y", 0, 1, -0.4, 0.4, -0.4, 0.4},
                             {"roll-pitch", 3, 4, -0.8, 0.8, -0.8, 0.8},
                             {"yaw-z", 5, 2, -1.8, 1.8, 0.1, 0.9}};
    const int n = 81;
    for (const Slice &sl : slices)
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                stewart_pose pose{};
                pose.q[2] = p->home_height;
                pose.q[sl.u] = sl.u0 + (sl.u1 - sl.u0) * i / (n - 1);
                pose.q[sl.v] = sl.v0 + (sl.v1 - sl.v0) * j / (n - 1);
                stewart_inverse_output legs;
                const stewart_inverse_input in = {pose};
                const stewart_status inv = stewart_inverse_solve(d->massless, &in, &legs);
                bool inside = inv == STEWART_OK;
                for (int k = 0; k < 6 && inside; ++k)
                    inside = legs.lengths.length[k] >= p->stroke_min[k] &&
                             legs.lengths.length[k] <= p->stroke_max[k];
                stewart_forward_output r{};
                stewart_status s = STEWART_ERR_SINGULAR;
                if (inv == STEWART_OK) {
                    stewart_forward_reset(d->forward);
                    s = forward_solve(d->forward, 0, legs.lengths.length, nullptr, nullptr, nullptr,
                                      &r);
                }
                // The branch of the pose the lengths came from: solved from itself.
                stewart_forward_output self{};
                int truth_branch = -1;
                if (inv == STEWART_OK) {
                    const stewart_status t = forward_solve(d->forward, 0, legs.lengths.length,
                                                           nullptr, nullptr, pose.q, &self);
                    if (t == STEWART_OK || t == STEWART_ERR_OTHER_BRANCH)
                        truth_branch = self.branch;
                }
                double error = 0;
                for (int c = 0; c < 6; ++c)
                    error = std::max(error, std::fabs(r.pose.q[c] - pose.q[c]));
                std::fprintf(out, "%s,%.6g,%.6g,%d,%.6g,%d,%d,%d,%d,%.3g\n", sl.name, pose.q[sl.u],
                             pose.q[sl.v], inside ? 1 : 0, inv == STEWART_OK ? legs.condition : 0,
                             truth_branch, static_cast<int>(s), r.iterations, r.branch,
                             s == STEWART_OK || s == STEWART_ERR_OTHER_BRANCH ? error : -1.0);
            }
    return std::fclose(out) == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char **argv) {
    if (argc > 1 && argv[1][0] == '-' && std::strcmp(argv[1], "--map") != 0) {
        std::fprintf(stderr, "usage: bench-forward [OUT.txt [TRACKING_SOLVES]] | --map OUT.csv\n");
        return 2;  // an option is not a file to write the table to
    }
    stewart_params params;
    stewart_params_default(&params);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *m = stewart_model_create(&params, msg, sizeof msg);
    stewart_inverse_options kinematic, massless;
    stewart_inverse_options_default(&kinematic);
    stewart_inverse_options_default(&massless);
    kinematic.fidelity = STEWART_KINEMATIC;
    stewart_forward_options forward;
    stewart_forward_options_default(&forward);
    Solvers solvers;
    if (m) {
        solvers.kinematic = stewart_inverse_create(m, &kinematic, msg, sizeof msg);
        solvers.massless = stewart_inverse_create(m, &massless, msg, sizeof msg);
        solvers.forward = stewart_forward_create(m, &forward, msg, sizeof msg);
    }
    Solvers *d = &solvers;
    auto free_all = [&]() {
        stewart_forward_free(solvers.forward);
        stewart_inverse_free(solvers.massless);
        stewart_inverse_free(solvers.kinematic);
        stewart_model_free(m);
    };
    if (!solvers.kinematic || !solvers.massless || !solvers.forward) {
        std::fprintf(stderr, "bench-forward: %s\n", msg);
        free_all();
        return 1;
    }
    if (argc > 2 && !std::strcmp(argv[1], "--map")) {
        const int status = write_map(m, d, argv[2]);
        free_all();
        return status;
    }
    Geometry g;
    for (int k = 0; k < 6; ++k) {
        g.base[k][0] = params.base_radius * std::cos(params.base_angle[k]);
        g.base[k][1] = params.base_radius * std::sin(params.base_angle[k]);
        g.base[k][2] = 0;
        g.plate[k][0] = params.platform_radius * std::cos(params.platform_angle[k]);
        g.plate[k][1] = params.platform_radius * std::sin(params.platform_angle[k]);
        g.plate[k][2] = 0;
    }
    const long tracking_solves = argc > 2 ? std::atol(argv[2]) : 1000000;
    const std::vector<Sample> poses = workspace(m, d, 20000);

    const Stats ot = ours_tracking(m, d, tracking_solves, true);
    const Stats op = ours_tracking(m, d, 120000, false);
    const Stats oc = ours_cold(m, d, poses);
    Stats bt, bc;
    double q[6];
    bool first = true;
    for (long start = 0; start < 10 * kChunk; start += kChunk)
        baseline_run(g, combined_cue(m, d, start, kChunk), true, params.home_height, q, first, bt);
    baseline_run(g, poses, false, params.home_height, q, first, bc);

    std::string report =
        "forward kinematics, thesis platform, tolerance 1e-12 m (max-norm of the length "
        "residual)\n"
        "  (a) tracking the combined cue at 1 kHz; (b) cold starts from home over random poses "
        "of the stroke workspace\n"
        "  time per solve [us] includes the clock read (~0.02 us); wrong = pose off the truth by "
        "> 1e-9\n"
        "                                     us: median     p99      max   iterations: med p99 "
        "max     solves  wrong failed\n";
    report += line("(a) library (KINSOL, analytic J)", ot);
    report += line("(a) library, lengths only", op);
    report += line("(a) baseline (plain Newton, FD J)", bt);
    report += line("(b) library (KINSOL, analytic J)", oc);
    report += line("(b) baseline (plain Newton, FD J)", bc);
    char ratio[200];
    std::snprintf(ratio, sizeof ratio,
                  "  median time ratio baseline/library: tracking %.2f, cold start %.2f\n",
                  percentile(bt.us, 0.5) / percentile(ot.us, 0.5),
                  percentile(bc.us, 0.5) / percentile(oc.us, 0.5));
    report += ratio;
    std::fputs(report.c_str(), stdout);
    if (argc > 1) {
        FILE *f = std::fopen(argv[1], "w");
        if (f) std::fputs(report.c_str(), f), std::fclose(f);
    }
    free_all();
    return 0;
}
