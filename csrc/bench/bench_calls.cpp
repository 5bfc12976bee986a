// One row of issue 22's cost table per run, through the public API only, along the combined cue
// (scenes/combined.json's formula): `bench-calls ROW CALLS` makes CALLS calls of the row's API
// function and prints the median nanoseconds per call. The calls are the only uses of that
// function in the run, so a profiler toggled on it (scripts/bench/instructions.sh: callgrind
// --toggle-collect) counts exactly CALLS calls. Rows:
//   inverse-kinematic, inverse-massless, inverse-full   stewart_solve at each fidelity
//   forward-tracking                                    stewart_forward_solve at 1 kHz, with rates
//   plant-massless, plant-full                          stewart_plant_step, 1 ms, Hermite forces
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "bench/combined_cue.hpp"
#include "stewart/stewart.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_plant.h"

namespace {

constexpr double kStep = 1e-3;  // 1 kHz

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

double ns_since(Clock::time_point start) {
    return std::chrono::duration<double, std::nano>(Clock::now() - start).count();
}

// Inverse outputs (lengths, their rates and accelerations, forces) along the cue, at `fidelity`;
// forces and their central-difference rates for the plant's Hermite drive.
bool inverse_along_cue(const stewart_model *m, int fidelity, int calls,
                       std::vector<stewart_output> &out, std::vector<double> *force_rate) {
    stewart_data *d = stewart_data_create(m);
    stewart_options o;
    stewart_options_default(&o);
    o.fidelity = static_cast<stewart_fidelity>(fidelity);
    out.resize(calls + 1);
    bool ok = d != nullptr;
    for (int i = 0; i <= calls && ok; ++i) {
        const stewart_pose p = combined_cue(i * kStep);
        ok = stewart_solve(m, d, &o, &p, &out[i]) == STEWART_OK;
    }
    if (force_rate && ok) {
        force_rate->assign(6 * (calls + 1), 0.0);
        for (int i = 0; i <= calls; ++i)
            for (int k = 0; k < 6; ++k) {
                const double before = out[std::max(i - 1, 0)].force[k];
                const double after = out[std::min(i + 1, calls)].force[k];
                (*force_rate)[6 * i + k] = (after - before) / (2 * kStep);
            }
    }
    stewart_data_free(d);
    return ok;
}

double run_inverse(const stewart_model *m, int fidelity, int calls) {
    stewart_data *d = stewart_data_create(m);
    stewart_options o;
    stewart_options_default(&o);
    o.fidelity = static_cast<stewart_fidelity>(fidelity);
    std::vector<stewart_pose> poses(calls);
    for (int i = 0; i < calls; ++i) poses[i] = combined_cue(i * kStep);
    std::vector<double> ns(calls);
    stewart_output out;
    for (int i = 0; i < calls; ++i) {
        const Clock::time_point start = Clock::now();
        const stewart_status s = stewart_solve(m, d, &o, &poses[i], &out);
        ns[i] = ns_since(start);
        if (s != STEWART_OK) return -1;
    }
    stewart_data_free(d);
    return median(ns);
}

double run_forward(const stewart_model *m, int calls) {
    std::vector<stewart_output> legs;
    stewart_data *d = stewart_data_create(m);
    stewart_data *inverse = stewart_data_create(m);
    stewart_options io;
    stewart_options_default(&io);
    io.fidelity = STEWART_KINEMATIC;
    legs.resize(calls);
    for (int i = 0; i < calls; ++i) {
        const stewart_pose p = combined_cue(i * kStep);
        if (stewart_solve(m, inverse, &io, &p, &legs[i]) != STEWART_OK) return -1;
    }
    stewart_forward_options o;
    stewart_forward_options_default(&o);
    std::vector<double> ns(calls);
    stewart_forward_result r;
    for (int i = 0; i < calls; ++i) {
        const Clock::time_point start = Clock::now();
        const stewart_status s =
            stewart_forward_solve(m, d, &o, i * kStep, legs[i].length, legs[i].length_rate,
                                  legs[i].length_accel, nullptr, &r);
        ns[i] = ns_since(start);
        if (s != STEWART_OK) return -1;
    }
    stewart_data_free(inverse);
    stewart_data_free(d);
    return median(ns);
}

double run_plant(const stewart_model *m, int fidelity, int calls) {
    std::vector<stewart_output> drive;
    std::vector<double> rate;
    if (!inverse_along_cue(m, fidelity, calls, drive, &rate)) return -1;
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = fidelity;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_plant *plant = stewart_plant_create(m, &o, msg, sizeof msg);
    if (!plant) return -1;
    const stewart_pose start = combined_cue(0);
    stewart_plant_set_state(plant, 0, start.q, start.q_dot);
    std::vector<double> ns(calls);
    for (int i = 0; i < calls; ++i) {
        const Clock::time_point t0 = Clock::now();
        const stewart_status s = stewart_plant_step(plant, kStep, drive[i].force,
                                                    drive[i + 1].force, &rate[6 * i],
                                                    &rate[6 * i + 6]);
        ns[i] = ns_since(t0);
        if (s != STEWART_OK) return -1;
    }
    stewart_plant_free(plant);
    return median(ns);
}

}  // namespace

int main(int argc, char **argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: bench-calls ROW CALLS (rows: see the source)\n");
        return 2;
    }
    const char *row = argv[1];
    const int calls = std::atoi(argv[2]);
    if (calls < 1) {
        std::fprintf(stderr, "bench-calls: CALLS = %s is not a positive count\n", argv[2]);
        return 2;
    }
    stewart_params params;
    stewart_params_default(&params);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *m = stewart_model_create(&params, msg, sizeof msg);
    if (!m) {
        std::fprintf(stderr, "bench-calls: %s\n", msg);
        return 1;
    }
    double ns = -2;
    if (!std::strcmp(row, "inverse-kinematic")) ns = run_inverse(m, STEWART_KINEMATIC, calls);
    if (!std::strcmp(row, "inverse-massless")) ns = run_inverse(m, STEWART_MASSLESS, calls);
    if (!std::strcmp(row, "inverse-full")) ns = run_inverse(m, STEWART_FULL, calls);
    if (!std::strcmp(row, "forward-tracking")) ns = run_forward(m, calls);
    if (!std::strcmp(row, "plant-massless")) ns = run_plant(m, STEWART_MASSLESS, calls);
    if (!std::strcmp(row, "plant-full")) ns = run_plant(m, STEWART_FULL, calls);
    stewart_model_free(m);
    if (ns == -2) {
        std::fprintf(stderr, "bench-calls: unknown row %s\n", row);
        return 2;
    }
    if (ns < 0) {
        std::fprintf(stderr, "bench-calls: a call of row %s failed\n", row);
        return 1;
    }
    std::printf("%s: %d calls, median %.1f ns per call\n", row, calls, ns);
    return 0;
}
